"""The PDA commands of the system layer (anvilwave/analyses/pda.py): the Case method on the
synthetic example record, the PDA summary of simulated blows, compare-pda (the paper's Fig. 4
and 5), and one clear error for each kind of bad record."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import anvilwave
from anvilwave.analyses.impact import pda_summary
from anvilwave.analyses.match import rest_force_at_gauges
from anvilwave.analyses.pda import STEEL_WAVE_SPEED, load_record, run_compare_pda, run_pda
from tests.conftest import EXAMPLES

RECORD = EXAMPLES / "pda_record_synthetic.csv"
RAW = EXAMPLES / "pda_raw_synthetic.csv"
AREA = math.pi * (8.0 - 0.14) * 0.14  # [m^2] steel at the gauges of anvilwave/examples/table1.toml
LENGTH = 78.0  # [m] below the gauges (80 m pile, gauges 2 m below the head)
NAMES = ("RTL [N]", "RSP [N]", "RMX [N]", "EMX [J]", "FMX [N]", "CSX [Pa]", "TSX [Pa]",
         "BTA [-]")


@pytest.fixture(scope="module")
def table1():
    return anvilwave.load_system(EXAMPLES / "table1.toml")


def test_default_wave_speed_is_the_project_steel():
    assert STEEL_WAVE_SPEED == pytest.approx(math.sqrt(210e9 / 7850.0))
    assert STEEL_WAVE_SPEED == pytest.approx(5172.2, abs=0.05)


def test_synthetic_record_is_documented_and_consistent():
    """The example record says it is synthetic, and the converted record is the conversion of
    the raw channels (bending and rocking cancel in the means; offsets and zero shifts are
    removed by the drift correction)."""
    record, notes, kind = load_record(RECORD)
    raw, raw_notes, raw_kind = load_record(RAW, area=AREA)
    assert kind == "gauge" and raw_kind == "raw"
    assert "SYNTHETIC" in notes[0] and "NOT A MEASUREMENT" in notes[0]
    assert "SYNTHETIC" in raw_notes[0]
    assert np.allclose(record.time, raw.time)
    # the converted file holds 9 significant digits
    assert np.max(np.abs(record.force - raw.force)) < 1e-8 * np.abs(raw.force).max()
    assert np.max(np.abs(record.velocity - raw.velocity)) < 1e-7 * np.abs(raw.velocity).max()
    assert 400e6 < record.force.max() < 500e6 and 2.5 < record.velocity.max() < 4.0


def test_run_pda_on_the_synthetic_record(tmp_path):
    out = tmp_path / "pda"
    summary = run_pda(RECORD, out, length=LENGTH, area=AREA, jc=0.4)
    saved = json.loads((out / "pda.json").read_text())
    for name in NAMES:
        assert math.isfinite(saved[name]) and saved[name] == summary[name]
    assert saved["inputs"]["wave_speed [m/s]"] == pytest.approx(STEEL_WAVE_SPEED)
    assert saved["record_notes"][0].startswith("SYNTHETIC")
    # physical ranges: the 5500 kJ hammer transfers 4.7 MJ (ENTHRU of the noise-free
    # simulation 4.71 MJ); FMX is the ROM's 456 MN plus noise; no tension above the yield
    assert 4.4e6 < summary["EMX [J]"] < 5.0e6
    assert summary["CSX [Pa]"] == pytest.approx(summary["FMX [N]"] / AREA)
    assert 0.0 <= summary["TSX [Pa]"] < 355e6 and 0.0 < summary["BTA [-]"] <= 1.0
    assert summary["RMX [N]"] >= summary["RSP [N]"]
    for name in ("pda.png", "pda.csv"):
        assert (out / name).stat().st_size > 0
    # the raw channels give the same analysis
    raw = run_pda(RAW, tmp_path / "raw", length=LENGTH, area=AREA, jc=0.4)
    for name in NAMES:
        assert raw[name] == pytest.approx(summary[name], rel=1e-6, abs=1e-3)


def test_pda_summary_of_simulated_table1_gauges(table1):
    """The Case method on anvilwave's own gauge signals: finite EMX, FMX, RMX once the blow
    reaches t1 + 2L/c (78 m: 30 ms); the 25 ms window of table1 is too short for RMX."""
    long = dataclasses.replace(table1, duration=0.06)
    blow = anvilwave.simulate(long)[0]
    pda = pda_summary(blow.columns, long)
    for name in ("EMX [J]", "FMX [N]", "RMX [N]", "case_damping [-]"):
        assert math.isfinite(pda[name]), name
    rest = blow["gauge_force [N]"][0]
    # the force at rest the match model puts on the gauges is the engine's: the anvil's FE
    # mass (the volume of revolution of its outline) and the pile above the gauges, by weight
    assert rest_force_at_gauges(long) == pytest.approx(rest, rel=1e-9)
    assert pda["FMX [N]"] == pytest.approx(blow["gauge_force [N]"].max() - rest)
    # EMX with the gauges zeroed: the transferred energy of the summary less the work of the
    # force at rest (3.7 MN) over the gauges' travel (about 15 mm): 56 kJ, 1.2 %
    travel = (blow["pile_head_displacement [m]"].max() - blow["pile_head_displacement [m]"][0])
    difference = blow.summary["transferred_energy_unzeroed [J]"] - pda["EMX [J]"]
    assert 0.0 < difference < 1.1 * rest * travel
    assert 0.0 < pda["RMX [N]"] < 2.0 * pda["FMX [N]"]
    short = pda_summary(anvilwave.simulate(table1)[0].columns, table1)
    assert short["RMX [N]"] is None and math.isfinite(short["EMX [J]"])


@pytest.mark.slow
def test_compare_pda_writes_fig4_and_fig5(tmp_path):
    out = tmp_path / "cmp"
    content = run_compare_pda(RECORD, EXAMPLES / "table1.toml", out, align="rom")
    for name in ("fig4_pile_top_force.png", "fig5_pile_top_velocity.png",
                 "compare_pda.json", "compare_pda.csv"):
        assert (out / name).stat().st_size > 0
    # aligned on the ROM: the record is shifted, the ROM's arrival error is 0 by construction
    assert content["arrival_aligned_on"] == "rom" and content["record_time_shift [s]"] != 0.0
    assert abs(content["rom"]["force_arrival_error [s]"]) < 1e-9
    # the record is the ROM's with 2 % noise: the ROM matches it to the noise, the lumped
    # anvil (no wave travel through the anvil) arrives about 3 ms early
    assert content["rom"]["force_normalised_rms_error [-]"] < 0.03
    assert content["lumped"]["force_normalised_rms_error [-]"] > 0.1
    assert content["rom_minus_lumped_arrival [s]"] > 0.002
    assert content["rom"]["removed_rest_force [N]"] > 0.0
    # the default keeps the record's time (its pre-trigger samples before the impact): no
    # shift, and the ROM arrives earlier than the record by its pre-trigger time
    kept = run_compare_pda(RECORD, EXAMPLES / "table1.toml", tmp_path / "kept")
    assert kept["alignment"] == "none" and kept["record_time_shift [s]"] == 0.0
    assert kept["rom"]["force_arrival_error [s]"] == pytest.approx(
        content["record_time_shift [s]"], abs=1e-9)


# ---------------------------------------------------------------------------------- bad records
GOOD = "time [s],force [N],velocity [m/s]\n" + "".join(
    f"{i * 1e-4:g},{1e6 * math.sin(0.05 * i):g},{0.1 * math.cos(0.03 * i):g}\n"
    for i in range(200))


def _with_cell(row: int, column: int, value: str) -> str:
    """GOOD with one cell replaced (row: data row index, from 0)."""
    lines = GOOD.splitlines()
    cells = lines[row + 1].split(",")
    cells[column] = value
    lines[row + 1] = ",".join(cells)
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(("name", "text", "message"), [
    ("nan", _with_cell(50, 1, "nan"), "line 52: 'nan' is not a finite number"),
    ("time", _with_cell(11, 0, "0.0009"), "must increase strictly"),
    ("lengths", GOOD.rstrip("\n").rsplit("\n", 1)[0] + "\n0.02,1.0,\n", "different lengths"),
    ("text", _with_cell(10, 1, "abc"), "line 12: 'abc' is not a number"),
    ("column", GOOD.replace("velocity [m/s]", "speed [m/s]"), "is missing"),
    ("clipped", "time [s],force [N],velocity [m/s]\n" + "".join(  # a pulse cut at 80 %
        f"{i * 1e-4:g},{min(1e6 * math.sin(0.05 * i) ** 8, 8e5):g},{0.1 * math.cos(0.03 * i):g}\n"
        for i in range(200)), "is clipped"),
])
def test_bad_records_give_one_clear_error(tmp_path, name, text, message):
    path = tmp_path / f"{name}.csv"
    path.write_text(text)
    with pytest.raises(anvilwave.InputError, match=message) as info:
        run_pda(path, tmp_path / "out", length=40.0, area=0.3, jc=0.4)
    assert str(path) in str(info.value) and "\n" not in str(info.value)
    assert not (tmp_path / "out").exists()  # nothing half-written


def test_comment_lines_keep_the_line_numbers(tmp_path):
    path = tmp_path / "commented.csv"
    path.write_text("# a note\n# another\n" + _with_cell(10, 1, "abc"))
    with pytest.raises(anvilwave.InputError, match="line 14:"):
        load_record(path)
    path.write_text("# a note\n" + GOOD)
    record, notes, kind = load_record(path)
    assert notes == ["a note"] and record.source == str(path) and record.time.size == 200


def test_raw_record_needs_the_area(tmp_path):
    with pytest.raises(anvilwave.InputError, match="needs the steel area"):
        load_record(RAW)


def test_bad_inputs_and_short_records(tmp_path):
    path = tmp_path / "good.csv"
    path.write_text(GOOD)
    with pytest.raises(anvilwave.InputError, match="length: must be a positive number"):
        run_pda(path, tmp_path / "o", length=-1.0, area=0.3, jc=0.4)
    with pytest.raises(anvilwave.InputError, match="jc"):
        run_pda(path, tmp_path / "o", length=40.0, area=0.3, jc=-0.1)
    with pytest.raises(anvilwave.InputError, match="before t1"):  # 20 ms < t1 + 2 x 400 m / c
        run_pda(path, tmp_path / "o", length=400.0, area=0.3, jc=0.4)
    with pytest.raises(anvilwave.InputError, match="file not found"):
        run_pda(tmp_path / "missing.csv", tmp_path / "o", length=40.0, area=0.3, jc=0.4)
