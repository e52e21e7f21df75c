"""Numbers the docs and the example files quote, computed: the ram contact dashpot of Table 1
and the lowest valid one-third-octave band of a 25 ms blow (what the demo prints)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from anvilwave.pile.post.spectra import third_octave_band_energies

from .conftest import EXAMPLES

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


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


INPUTS = {
    **dict.fromkeys(("5500 kJ", "8 m", "8000 mm", "8000 x", "8000 ×", "140 mm", "80 m", "1.8 m",
                     "275 t", "0.9 m", "4.15 m", "0.25 m", "25 ms", "20 µs", "13.8 m"),
                    "the paper's Table 1 case and table1.toml's inputs (hammer, anvil, ram, pile, "
                    "segments, blow window, step; docs/design.md lists them)"),
    **dict.fromkeys(("0.5 m", "3.3 kHz"),
                    "the paper's 0.5 m pile segments and their cut-off c / (pi dx), "
                    "test_segment_cut_offs_are_computed"),
    "6.6 kHz": "the cut-off of table1.toml's 0.25 m segments, test_segment_cut_offs_are_computed",
    "5.5 m": "the paper's statement: a lumped anvil is wrong above 5.5 m (a citation)",
    **dict.fromkeys(("50 Hz", "1 kHz", "1.26 kHz", "4 kHz", "5 kHz", "10 kHz", "1.6-4 kHz",
                     "1.6 to 4 kHz", "1 to 4 kHz", "1.6-5 kHz", "5-10 kHz", "1.6-2 kHz",
                     "3.15 kHz", "3.15-4 kHz", "316 Hz", "500 Hz", "1 dB"),
                    "band edges and fmax settings: the range a figure is quoted over, an input "
                    "(fmax's default 5 kHz, the study's top 10 kHz) or the issue's 1 dB bar, "
                    "not a result"),
    **dict.fromkeys(("250 blows", "0 blows", "1 blow"),
                    "the refusal default (250 blows per 0.25 m) and counts that define a term"),
    **dict.fromkeys(("2.48 m", "72 m", "3.5 m", "800 kJ", "40 t", "0.95 m", "2 m"),
                    "inputs of the GRLWEAP benchmark, the ISFOG piles and the IHC S-800 class "
                    "(their data files)"),
}
"""Quantities that are inputs or definitions on every page: quantity -> why."""

DEFINITIONS = {
    ("design.md", q): "the Table 1 specification (inputs)" for q in (
        "0.45 m", "0.55 m", "0.75 m", "1.2 m", "3.6 to 4.15 m", "3.93 m", "210 GPa",
        "7850 kg/m³", "0.5 m", "4 ms", "2x")
} | {
    ("drive.md", q): "inputs of the example drives and the codes' rules" for q in (
        "355 MPa", "320 MPa", "80-90 %", "1.05 times", "40 m", "2000 to 5500 kJ", "500-1200 kJ",
        "0.1 s", "0.5 m")
} | {
    ("demo.md", "4 ms"): "the paper's figure (a citation)",
    **{("batch.md", q): "the example campaigns' definitions (their files)"
       for q in ("12 cases", "40 m", "10 blows", "72 cases")},
    ("pda.md", "2 %"): "the synthetic record's noise (an input of its script)",
    **{("validation.md", q): "the illustrative ring of anvilwave/examples/anvils/xl8_ring.toml, "
       "the study's and the tests' settings (pile cut, clearances, steps, windows), the issue's "
       "bars and the rise's definition"
       for q in ("52.6 t", "3.6 to 4.15 m", "0.26 m", "10 mm", "0.5 mm", "10 m", "0.55 m",
                 "20 us", "0.5 %", "3 %", "5 %", "10 %", "1.5 dB", "12 kHz",
                 "90 %", "1 %", "7 %", "1 mm")},
    **{("fmi.md", q): "Table 1's steps: the engine's h, the SSP's h/4 and the start 2.5 of "
       "them before the contact (inputs and the SSP's definition); OMSimulator's own defaults"
       for q in ("5 µs", "5 us", "20 us", "-2.5 steps", "5e-6 s", "-12.5 us", "5000 ns", "1 s",
                 "0 - 1 s")},
    **{("install.md", q): "inputs and definitions of the installation run and the set-up "
                          "model (the example file, IEC 61260-1's reference, public records' "
                          "pile size and pause times)"
       for q in ("5 cm", "1 N", "10 m", "30 m", "10 to 30 m", "0.5 day", "1 day", "48 h", "1/m",
                 "1.83 m", "43-47 h", "99-122 h")},
    ("validation.md", "1 N"): "the dB reference, re 1 N^2 s (IEC 61260-1)",
    ("limitations.md", "1 mm"): "the anvil-ring study's sleeve clearance (an input, "
                                "benchmarks/study_anvil_ring.py DOCS_SLEEVE)",
    ("validation.md", "~4 ms"): "the paper's figure (a citation)",
    ("validation.md", "6.16 m/s"): "the studies' impact velocity (an input)",
    ("validation.md", "0.125 m"): "a segment length (an input)",
    ("validation.md", "3.0 m"): "the widetop anvil's top radius (an input)",
    ("validation.md", "0.1 m"): "the FEA's mesh size along the pile (an input)",
    **{("validation.md", q): "the anvil-ring study's reference meshes (inputs, "
                             "benchmarks/study_anvil_ring.py DOCS_REFERENCE_MESHES)"
       for q in ("0.05 m", "0.1 to 0.05 m")},
    ("validation.md", "5-95 %"): "a percentile range (a definition)",
    ("validation.md", "1.0 x"): "the ENTHRU ratios that select piles (0.65 or 1.0 x the energy)",
    ("impact.md", "8 times"): "the step rule: fmax sampled 8 times per period (an input)",
    ("impact.md", "20 steps"): "the energy bookkeeping interval (an input)",
    ("impact.md", "100 blows"): "the size of the benchmark's run (an input)",
    ("anvil-file.md", "4 ×"): "the size of a flexibility matrix (4 × 4)",
    ("modes.md", "8 %"): "the plot's scale rule (largest displacement at 8 % of the size)",
    ("report.md", "50 MiB"): "a size limit of the report (an input)",
}
"""Page-specific inputs and definitions: (page, quantity) -> why."""

CHECKED = {
    ("theory.md", "1.03e8 N s/m"): "test_table1_ram_dashpot_is_quoted_as_computed",
    ("validation.md", "40 Hz"): "test_lowest_valid_band_of_a_25_ms_blow_is_50_hz (1/T)",
    ("install.md", "2 %"): "tests/test_setup.py: the blow count back on the unpaused curve "
                           "within 2 %",
    ("install.md", "5 %"): "tests/test_setup.py: the blow count at the restart more than 5 % up",
}
"""Quantities a test of the suite checks where they stand: (page, quantity) -> the test."""

PENDING_SECTIONS: dict = {}
"""Sections whose prose numbers another change regenerates: (page, heading or None for the
whole page) -> why. A section runs to the next heading."""


def _allowed(page: str, heading: str, quantity: str) -> bool:
    return (quantity in INPUTS or (page, quantity) in DEFINITIONS
            or (page, quantity) in CHECKED or (page, None) in PENDING_SECTIONS
            or (page, heading) in PENDING_SECTIONS)


def typed_numbers() -> list[str]:
    """``page:line quantity`` of every prose quantity that no list above allows."""
    return [f"{p.name}:{n} {q}" for p in PAGES for n, h, q in prose_numbers(p.read_text("utf-8"))
            if not _allowed(p.name, h, q)]


def test_no_hand_typed_number_in_prose():
    found = typed_numbers()
    assert not found, ("numbers typed in prose: quote them from a docs/data file "
                       "({{ FILE_KEY }}), reword, or list an input with its reason: "
                       + "; ".join(found))


def test_allowed_numbers_still_stand():
    shown = {(p.name, h, q) for p in PAGES for _, h, q in prose_numbers(p.read_text("utf-8"))}
    quantities = {q for _, _, q in shown}
    stale = sorted(q for q in INPUTS if q not in quantities)
    stale += sorted(f"{p}: {q}" for p, q in (*DEFINITIONS, *CHECKED)
                    if (p, q) not in {(a, c) for a, _, c in shown})
    headings = {(p.name, None) for p in PAGES} | {(p.name, h) for p in PAGES
                                                  for _, h, _ in prose_lines(p.read_text())}
    stale += sorted(str(k) for k in PENDING_SECTIONS if k not in headings)
    assert not stale, f"no longer in the pages (drop them from the lists): {stale}"


def test_the_checker_fails_on_a_typed_number(tmp_path, monkeypatch):
    page = tmp_path / "validation.md"
    page.write_text("# Validation\n\nThe ROM is 4.8 % off in RMS, {{ demo_rom_rms_ram }} here, "
                    "on the 8 m anvil.\n\n## The ROM stack against the FEA stack\n\n3.1 % off.\n")
    monkeypatch.setattr(f"{__name__}.PAGES", [page])
    monkeypatch.setattr(f"{__name__}.PENDING_SECTIONS",
                        {("validation.md", "The ROM stack against the FEA stack"): "a test"})
    assert typed_numbers() == ["validation.md:3 4.8 %"]  # the pending section's is allowed


def test_segment_cut_offs_are_computed():
    """A Smith chain of segment length dx passes waves up to c / (pi dx) (its highest
    frequency, 2 c / dx / (2 pi)): 3.3 kHz for the paper's 0.5 m and 6.6 kHz for table1.toml's
    0.25 m in steel (E 210 GPa, rho 7850 kg/m^3, as the example files)."""
    c = np.sqrt(210e9 / 7850.0)
    assert [f"{c / (np.pi * dx) / 1e3:.1f} kHz" for dx in (0.5, 0.25)] == ["3.3 kHz", "6.6 kHz"]
    text = " ".join(re.sub(r"\s+", " ", p.read_text()) for p in (ROOT / "docs").glob("*.md"))
    assert "3.3 kHz for the paper's 0.5 m, 6.6 kHz for table1.toml's 0.25 m" in text

