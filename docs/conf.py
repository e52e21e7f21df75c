"""Sphinx configuration: the markdown pages of docs/ (MyST) and the API reference (autodoc).

Built by CI with warnings as errors: ``sphinx-build -W -b html docs docs/_build/html``.
The measured numbers of the pages come from docs/data/*.json (docs/_ext/data_tables.py): the
``{data-table}`` directive renders their tables, ``myst_substitutions`` their inline numbers.
"""

import sys
from importlib.metadata import version as _version
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "_ext"))

import data_tables  # noqa: E402  (docs/_ext, on the path above)

project = "anvilwave"
release = _version("anvilwave")
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "data_tables"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build"]
napoleon_numpy_docstring = True
napoleon_google_docstring = False
autodoc_member_order = "bysource"
myst_heading_anchors = 3
myst_enable_extensions = ["substitution"]
myst_substitutions = data_tables.substitutions()
html_theme = "alabaster"
suppress_warnings = ["myst.xref_missing"]
