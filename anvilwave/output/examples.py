"""The shipped example files (:mod:`anvilwave.examples`, package data) and their copy out of
the package (``anvilwave examples DIR``)."""


from __future__ import annotations

import shutil
from pathlib import Path

EXAMPLES_DIR = Path(__file__).resolve().parents[1] / "examples"
"""Folder of the shipped example files."""

_SKIP = shutil.ignore_patterns("__init__.py", "__pycache__", "*.pyc")

def copy_examples(dest: str | Path) -> list[Path]:
    """Copy the example files into a folder.

    Parameters
    ----------
    dest : str or Path
        The folder (created; existing files are kept, never overwritten).

    Returns
    -------
    list of Path
        The copied files.

    Raises
    ------
    FileExistsError
        When a file to copy is already there.
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
