"""The docs' data files (docs/data/*.json) and the scripts that write them (benchmarks/), for
the tests that check the files: tests/test_doc_tables.py and tests/test_compare.py."""

from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOC_DATA = ROOT / "docs" / "data"
BENCHMARKS = ROOT / "benchmarks"

SAME_RUN = {"rel": 1e-6, "abs": 1e-9}
"""Tolerance of a number recomputed the way its data file's script computed it (the same
inputs, code and engine), as in tests/test_example_numbers.py: the runs are deterministic, so
on one machine type they repeat to the last bit; 1e-6 relative leaves room for another BLAS's
summation order in the modal analysis (1e-10 in the eigenvectors) and is far below the last
digit the docs show (0.1 % points = 1e-3 of a fraction, 0.1 dB, 0.01 ms); the absolute 1e-9
covers errors that are zero or nearly so (a fraction; an arrival time error [s] lies on the
FEA's 10 us grid)."""


def doc_data(name: str) -> dict:
    """docs/data/NAME.json."""
    return json.loads((DOC_DATA / f"{name}.json").read_text(encoding="utf-8"))


def benchmark(name: str):
    """The module of benchmarks/NAME.py (its folder on the path: the scripts import
    benchmarks/doc_data.py as ``doc_data``, as when run as ``python benchmarks/NAME.py``)."""
    if str(BENCHMARKS) not in sys.path:
        sys.path.insert(0, str(BENCHMARKS))
    return importlib.import_module(name)


def assert_same_numbers(computed, stored, path: str = "", skip: tuple[str, ...] = ()) -> None:
    """Every number of ``stored`` (nested dicts and lists, as a data file holds them) equals
    ``computed``'s within :data:`SAME_RUN`; keys in ``skip`` are not compared (wall times and
    real-time factors: speed is measured in benchmarks/, never asserted). A null stored value
    stands for a non-finite one (the data files hold no NaN)."""
    if isinstance(stored, dict):
        for key, value in stored.items():
            if key in skip:
                continue
            assert key in computed, f"{path}/{key}: not computed"
            assert_same_numbers(computed[key], value, f"{path}/{key}", skip)
    elif isinstance(stored, list):
        assert len(computed) == len(stored), f"{path}: {len(computed)} != {len(stored)} items"
        for i, (a, b) in enumerate(zip(computed, stored, strict=True)):
            assert_same_numbers(a, b, f"{path}[{i}]", skip)
    elif isinstance(stored, bool) or isinstance(stored, str):
        assert computed == stored, f"{path}: {computed!r} != {stored!r}"
    elif stored is None:
        assert computed is None or computed != computed or abs(computed) == float("inf"), \
            f"{path}: {computed!r}, stored null"
    else:
        assert computed == pytest.approx(stored, **SAME_RUN), f"{path}: {computed} != {stored}"
