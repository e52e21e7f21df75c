"""Write a data file of the documentation: ``docs/data/NAME.json``.

The docs never type a measured number by hand: a study or benchmark script that computes a
table writes it here, and ``docs/_ext/data_tables.py`` renders it at build time (the
``{data-table}`` directive, the ``{{ name }}`` substitutions). A data file holds:

* ``command``: the command that wrote it (run it again to regenerate the file);
* ``anvilwave_version``: the version that computed it;
* ``inputs``: the repository files it read, each with its SHA-256 (``tests/test_doc_tables.py``
  fails when an input changed after the file was written: run the command again);
* ``tables``: NAME -> ``{"columns": [...], "formats": [...], "rows": [...]}``. A row is a list
  of cells or ``{"bold": true, "cells": [...]}``; a cell is a string (shown as is), a number
  (shown in its column's format, see ``FORMATS`` in docs/_ext/data_tables.py) or null (empty);
* ``substitutions``: NAME -> ``[number, format]``, the numbers the prose quotes
  (``{{ FILE_NAME }}`` in a page, FILE the data file's name);
* ``values``: the raw results behind the tables (what the tests compare).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import shlex
import sys
from importlib.metadata import version
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC_DATA = ROOT / "docs" / "data"


def file_hash(path: Path) -> str:
    """``sha256:HEX`` of a file's bytes."""
    return "sha256:" + hashlib.sha256(Path(path).read_bytes()).hexdigest()


def relative(path: Path) -> str:
    """A path as the data files name it: relative to the repository root (``../shared/...``
    for the shared reference data beside it)."""
    return Path(os.path.relpath(os.path.abspath(path), ROOT)).as_posix()


def system_inputs(system: Path) -> list[Path]:
    """A system file and the files it reads: every ``KEY = "NAME.toml"`` (or .csv, .json;
    relative to it) and the database hammer's file."""
    system = Path(system).resolve()
    text = system.read_text()
    out = [system]
    for name in re.findall(r'^\s*\w+\s*=\s*"([^"]+\.(?:toml|csv|json))"', text, flags=re.M):
        out.append(Path(os.path.abspath(system.parent / name)))
    for name in re.findall(r'^\s*database\s*=\s*"([^"]+)"', text, flags=re.M):
        out.append(ROOT / "anvilwave" / "hammer" / "data" / f"{name}.toml")
    for anvil in [p for p in out if p.parent.name == "anvils"]:
        out += [(anvil.parent / n).resolve() for n in
                re.findall(r'^\s*file\s*=\s*"([^"]+)"', anvil.read_text(), flags=re.M)]
    return out


def _finite(value):
    """NaN and infinities as null (JSON has none; a missing value renders empty)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def write_doc_data(name: str, *, about: str, inputs: list[Path], tables: dict,
                   substitutions: dict | None = None, values: dict | None = None,
                   command: str | None = None) -> Path:
    """Write ``docs/data/NAME.json`` (see the module docstring) and return its path."""
    if command is None:
        script = Path(sys.argv[0]).resolve()
        command = shlex.join(["python", relative(script), *sys.argv[1:]])
    data = {
        "about": about,
        "command": command,
        "anvilwave_version": version("anvilwave"),
        "inputs": {relative(p): file_hash(p) for p in sorted(set(map(Path, inputs)))},
        "tables": tables,
        "substitutions": substitutions or {},
        "values": values or {},
    }
    DOC_DATA.mkdir(parents=True, exist_ok=True)
    path = DOC_DATA / f"{name}.json"
    path.write_text(json.dumps(_finite(data), indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {relative(path)}")
    return path
