"""The example input files that ship with anvilwave (system files, anvils, soil, PDA records).

They are package data, so an installed wheel runs its own demo: ``anvilwave examples DIR``
copies them out (``copy_examples``), ``anvilwave demo`` reads Table 1 from here. Every path
inside them is relative to the file that names it (a hammer file under ``hammers/``, the
anvils under ``anvils/``), so the copy runs where it lands. The scripts (``script_api.py``,
``make_synthetic_*.py``, ``fmpy_cosim.py``) are examples to run, not modules to import.
"""

from __future__ import annotations

import shutil
from pathlib import Path

EXAMPLES_DIR = Path(__file__).resolve().parent
"""Folder of the shipped example files."""

_SKIP = shutil.ignore_patterns("__init__.py", "__pycache__", "*.pyc")

def copy_examples(dest: str | Path) -> list[Path]:
    """Copy the example files into ``dest``.

    ``dest`` is created; existing files are kept, never overwritten.

    Parameters
    ----------
    dest : str or pathlib.Path
        The destination folder.

    Returns
    -------
    list of pathlib.Path
        The copied files.

    Raises
    ------
    FileExistsError
        If a file to copy is already there (nothing is copied then).
    """
    dest = Path(dest)
    sources = [p for p in sorted(EXAMPLES_DIR.rglob("*"))
               if p.is_file() and p.name != "__init__.py" and "__pycache__" not in p.parts
               and p.suffix != ".pyc"]
    clashes = [dest / p.relative_to(EXAMPLES_DIR) for p in sources
               if (dest / p.relative_to(EXAMPLES_DIR)).exists()]
    if clashes:
        raise FileExistsError(f"{clashes[0]} exists (and {len(clashes) - 1} more); "
                              "choose an empty folder")
    copied = []
    for p in sources:
        target = dest / p.relative_to(EXAMPLES_DIR)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(p, target)
        copied.append(target)
    return copied
