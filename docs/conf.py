"""Sphinx configuration: the markdown pages of docs/ (MyST) and the API reference (autodoc).

Built by CI with warnings as errors: ``sphinx-build -W -b html docs docs/_build/html``.
"""

from importlib.metadata import version as _version

project = "anvilwave"
release = _version("anvilwave")
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build"]
napoleon_numpy_docstring = True
napoleon_google_docstring = False
autodoc_member_order = "bysource"
myst_heading_anchors = 3
html_theme = "alabaster"
suppress_warnings = ["myst.xref_missing"]
