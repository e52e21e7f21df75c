"""Numbers the docs and the example files quote, computed: the ram contact dashpot of Table 1
and the lowest valid one-third-octave band of a 25 ms blow (what the demo prints)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from anvilwave.pile.post.spectra import third_octave_band_energies

from .conftest import EXAMPLES

ROOT = Path(__file__).resolve().parents[1]


def test_table1_ram_dashpot_is_quoted_as_computed():
    """ram_contact_damping = "ram-impedance": A sqrt(E rho) of the 1.8 m steel ram toe,
    1.033e8 N s/m, quoted as 1.03e8 in table1.toml, table1_interfaces.toml and theory.md."""
    area = np.pi * 0.9**2
    impedance = area * np.sqrt(210e9 * 7850.0)
    assert f"{impedance:.2e}" == "1.03e+08"
    for path in (EXAMPLES / "table1.toml", EXAMPLES / "table1_interfaces.toml",
                 ROOT / "docs" / "theory.md"):
        quoted = set(re.findall(r"(\d\.\d\de8) N s/m", path.read_text()))
        assert quoted == {"1.03e8"}, (path.name, quoted)


def test_lowest_valid_band_of_a_25_ms_blow_is_50_hz():
    """The valid band starts at 1/T = 40 Hz; the lowest band wholly inside it is centred at
    50 Hz, the first band the demo and the docs name (never "from 40 Hz")."""
    step = 2e-5
    t = np.arange(0.0, 0.025, step)
    bands = third_octave_band_energies(np.sin(2e3 * t), step)
    assert bands.valid_range[0] == 40.0
    assert round(float(bands.centre_frequency[bands.valid][0])) == 50
    for path in (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))):
        assert "band from 40 Hz" not in re.sub(r"\s+", " ", path.read_text()), path.name


# --- Numbers in prose --------------------------------------------------------------------------
# Every number with a unit (or %, dB, a ratio, a count of modes, blows, ...) in the prose of
# README.md and docs/*.md (sentences, lists, headings, admonitions; not code blocks, whose
# checked outputs tests/test_readme_outputs.py reruns, nor tables, which tests/test_doc_tables.py
# covers) is a MyST substitution from docs/data/*.json (``{{ NAME }}``, rendered by
# docs/_ext/data_tables.py and checked with its file by tests/test_doc_tables.py and
# tests/test_compare.py), an input or definition (:data:`INPUTS`, :data:`DEFINITIONS`), a number
# a named test checks (:data:`CHECKED`) or in a section another change regenerates
# (:data:`PENDING`). Anything else was typed by hand: this test fails on it.

UNITS = sorted([
    "%", "dB", "Hz", "kHz", "MHz", "N", "kN", "MN", "GN", "N s/m", "N/m", "Pa", "kPa", "MPa",
    "GPa", "J", "kJ", "MJ", "W", "kW", "MW", "s", "ms", "µs", "us", "ns", "min", "minutes",
    "minute", "h", "hours", "hour", "day", "days", "m", "mm", "cm", "km", "m/s", "kg", "t",
    "kg/m³", "GiB", "MiB", "DOF", "mode", "modes", "blow", "blows", "blows/m", "/m", "1/m", "x",
    "×", "times", "core", "cores", "core-hours", "files", "FEAs", "depths", "bands", "steps",
    "cases", "piles", "points", "records", "seeds", "segments", "workers", "foundations",
    "per cent", "elements", "rounds",
], key=len, reverse=True)
"""Units and counted things that make a number a quantity (a bare number, a figure or table
label, a year, a name like S-4000 is not one)."""

_NUMBER = r"[+\-−±~≈]?\d+(?:,\d{3})*(?:\.\d+)?(?:e[+\-−]?\d+)?"
_QUANTITY = re.compile(
    r"(?<![\w.\-−/^])" + _NUMBER + r"(?:\s?(?:-|–|to)\s?" + _NUMBER + r")?\s?(?:"
    + "|".join(re.escape(u) for u in UNITS) + r")(?![\w/³²])")
_PROSE_FENCES = ("{note}", "{warning}", "{admonition}", "{tip}", "{important}", "{seealso}",
                 "{attention}", "{caution}", "{danger}", "{hint}")


def prose_lines(text: str):
    """(line number, heading, text) of every prose line of a markdown page: outside fenced
    blocks (an admonition's block is prose), tables and HTML comments; inline code, MyST
    substitutions and link targets removed. ``heading`` is the last heading above it."""
    fence, heading = None, ""
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if stripped.startswith("```"):
            if fence is None:
                fence = stripped[3:].strip() or "code"
                if fence.split()[0] in _PROSE_FENCES:
                    fence = "prose"
            else:
                fence = None
            continue
        if fence not in (None, "prose") or stripped.startswith(("|", "<!--")):
            continue
        if stripped.startswith("#"):
            heading = stripped.lstrip("#").strip()
        line = re.sub(r"`[^`]*`", " ", line)
        line = re.sub(r"\{\{[^}]*\}\}", " ", line)
        line = re.sub(r"\]\([^)]*\)", "]", line)
        yield number, heading, line


def prose_numbers(text: str) -> list[tuple[int, str, str]]:
    """(line, heading, quantity) of every number with a unit in the prose of a page, the
    quantity with its whitespace collapsed (``4.8 %``, ``1.6-4 kHz``)."""
    return [(number, heading, re.sub(r"\s+", " ", m.group(0)))
            for number, heading, line in prose_lines(text)
            for m in _QUANTITY.finditer(line)]


def test_the_prose_scan_finds_typed_numbers():
    page = ("# A page\n\nThe peak is 455.8 MN, {{ demo_lumped_ram_peak }} high, in `25 ms`;\n"
            "- the band to 1.6-4 kHz is +3.3 dB off (Fig. 2, Table 1, 2018, IHC S-4000);\n"
            "\n| a | 5 % |\n|---|---|\n\n```\n$ anvilwave x\n10.3 s\n```\n\n"
            "```{note}\nIt took 80 s and 7 modes ([here](x_5_m.md)).\n```\n"
            "## Speed\n\n5x real time, 1.03e8 N s/m, −2.0 % and 87,990 blows.\n")
    assert [(n, q) for n, _, q in prose_numbers(page)] == [
        (3, "455.8 MN"), (4, "1.6-4 kHz"), (4, "+3.3 dB"), (15, "80 s"), (15, "7 modes"),
        (19, "5x"), (19, "1.03e8 N s/m"), (19, "−2.0 %"), (19, "87,990 blows")]
    assert {h for _, h, _ in prose_numbers(page)} == {"A page", "Speed"}
