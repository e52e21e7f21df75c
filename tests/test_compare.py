"""The paper's comparison on the Table 1 case, end to end through `anvilwave demo`."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import (
    ModelRun,
    arrival_time,
    band_levels,
    lift_off_intervals,
    lowpass,
    plot_spectra,
)
from anvilwave.cli import main
from anvilwave.config.cache import cached_modal_data
from anvilwave.output.tables import read_csv

from .conftest import DEMO_IN_WHEEL, EXAMPLES, FROM_CHECKOUT, assert_within_issue_bounds
from .doc_tables import assert_same_numbers, benchmark, doc_data

WALL = ("wall_time [s]", "realtime_factor [-]", "total_time [s]")
"""Speed, in the data files but never compared (measured in benchmarks/ only)."""


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    """The README's main job, ``anvilwave demo``, run once (in CI: from the installed wheel,
    outside the checkout, where .ci/run runs this file again)."""
    if DEMO_IN_WHEEL and FROM_CHECKOUT:
        pytest.skip("ANVILWAVE_CI_DEMO=wheel: .ci/run runs the demo and this file's checks of it "
                    "against the installed wheel, outside the checkout")
    given = os.environ.get("ANVILWAVE_DEMO_RESULT")
    if given:  # the folder of an `anvilwave demo --out DIR` run by the caller (.ci/run)
        out = Path(given)
        assert (out / "summary.json").is_file(), f"{out}: no demo result"
    else:
        out = tmp_path_factory.mktemp("demo")
        assert main(["demo", "--out", str(out)]) == 0
    return out, json.loads((out / "comparison.json").read_text())


def test_demo_writes_everything(demo):
    out, _ = demo
    for name in ("summary.json", "comparison.json", "fig2_ram_force.png", "fig3_pile_force.png",
                 "fig_spectra.png",
                 "fea.csv", "rom.csv", "lumped.csv", "modes/modes.npz", "fmus/Anvil.fmu",
                 "fmus/Ram.fmu", "fmus/PileSoil.fmu", "fmus/AnvilLumped.fmu", "fmus/system.ssp",
                 "interfaces/rom.csv", "interfaces/comparison.json",
                 "interfaces/fig_spectra.png"):
        assert (out / name).exists(), name
    summary = json.loads((out / "summary.json").read_text())
    assert summary["anvil_modes"] > 10
    assert summary["ram_model"] == "modal" and summary["ram_modes"] > 50
    # Table 1 with its interfaces resolved, against the same FEA (tests/test_ram_annuli.py
    # checks the same run with its own FEA): every band to 4 kHz within 1 dB (measured 0.71)
    resolved = summary["interfaces_rom_vs_fea"]
    assert resolved["max_abs_band_deviation_to_4_kHz [dB]"] <= 1.0
    assert abs(resolved["peak_anvil_pile_force_error [-]"]) <= 0.03


def test_table1_rom_against_fea(demo):
    """ROM vs FEA with every series low-passed at fmax = 5 kHz (the comparison band of
    table1.toml: its 0.25 m pile segments cut off at 6.5 kHz), with the bounds of the issue:
    arrival time within 0.1 ms, RMS errors within 10 %, peaks within 3 % (pile) and 5 % (ram),
    and the raw ROM peaks (what impact.csv holds) against the FEA's 5 kHz peaks within 5 %
    (pile) and 10 % (ram). Measured with table1.toml's modal ram unit and its ram-impedance
    contact dashpot: arrival +0.04 ms, RMS 4.8 % ram and 3.0 % pile, peaks +1.0 % pile and
    -1.0 % ram, raw peaks +1.2 % pile and +7.5 % ram. (Without the dashpot the raw ram peak
    is +57 %: the contact rings at 5-6 kHz; with the former 0.5 m segments and 25 us step the
    pile peak in the 5 kHz band was +5.8 %.)"""
    _, cmp = demo
    assert cmp["comparison_bandwidth [Hz]"] == pytest.approx(5000.0)
    rom = cmp["rom"]
    assert abs(rom["pile_force_arrival_error [s]"]) <= 1e-4
    assert rom["ram_anvil_force_normalised_rms_error [-]"] <= 0.10
    assert rom["anvil_pile_force_normalised_rms_error [-]"] <= 0.10
    assert abs(rom["peak_anvil_pile_force_error [-]"]) <= 0.03
    assert abs(rom["peak_ram_anvil_force_error [-]"]) <= 0.05
    assert abs(rom["peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]"]) <= 0.05
    assert abs(rom["peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"]) <= 0.10


def test_lumped_anvil_is_worse_and_misses_the_anvil_delay(demo):
    """The paper's point: the rigid lumped mass overestimates the ram force and cannot delay
    the pile force by the wave travel through the 8 m anvil."""
    _, cmp = demo
    rom, lumped = cmp["rom"], cmp["lumped"]
    for key in ("ram_anvil_force_normalised_rms_error [-]",
                "anvil_pile_force_normalised_rms_error [-]"):
        assert lumped[key] > 2 * rom[key]
    assert lumped["peak_ram_anvil_force_error [-]"] > 0.3
    assert lumped["pile_force_arrival_error [s]"] < -2e-3


def test_anvil_lifts_off_and_reimpacts_in_fea_and_rom(demo):
    """The FEA's anvil leaves the pile (the ram bends the plate, its rim rises) for about 2 ms
    before slamming back; the ROM has the same open interval. Measured: FEA 1.09-3.11 ms, ROM
    1.04-3.22 ms (the contact closes 0.11 ms later, though the force rises through 20 % of its
    peak at the FEA's time: the arrival test)."""
    _, cmp = demo

    def first_lift_off(intervals):  # the open interval around 2 ms
        return next(iv for iv in intervals if iv[0] < 2e-3 < iv[1])

    fea = first_lift_off(cmp["fea"]["anvil_lift_off_intervals [s]"])
    rom = first_lift_off(cmp["rom"]["anvil_lift_off_intervals [s]"])
    assert fea[1] - fea[0] > 1.5e-3
    assert abs(rom[0] - fea[0]) < 1e-4
    assert abs(rom[1] - fea[1]) < 2e-4
    assert not cmp["lumped"]["anvil_lift_off_intervals [s]"]


def test_comparison_helpers():
    t = np.linspace(0, 0.01, 1001)
    f = np.where(t > 0.004, 10.0, 1.0)
    assert arrival_time(t, f, preload=1.0) == pytest.approx(0.00401, abs=2e-5)
    assert lift_off_intervals(t, np.where((t > 0.002) & (t < 0.003), 0.0, 1.0)) == \
        [[pytest.approx(0.00201), pytest.approx(0.003)]]
    smooth = lowpass(t, np.sin(2 * np.pi * 100 * t), 1000.0)
    # a 4th-order Butterworth passes 100 Hz at 1 kHz with a gain of 1 - 1e-8 and no phase
    # (forward-backward); the ends carry the filter's start-up transient
    np.testing.assert_allclose(smooth[300:-300], np.sin(2 * np.pi * 100 * t)[300:-300],
                               atol=2e-3)


def test_table1_pile_head_force_band_levels(demo, tmp_path):
    """One-third-octave band levels of the pile-head force (the noise argument). The valid
    band runs from 1 / T (40 Hz, T = 25 ms) to the 5 kHz comparison band (also a tenth of the
    ROM's 50 kHz sampling). Measured, ROM - FEA: within 0.9 dB in every band from 50 Hz to
    1.26 kHz (largest -0.9 dB at 251 Hz), then +1.7, +3.9, +6.3, +7.5 and +8.4 dB in the 1.6,
    2, 2.5, 3.15 and 4 kHz bands: the issue's 1 dB target holds up to 1.26 kHz, not up to
    4 kHz (open). The lumped anvil is -1.8 dB at 100 Hz, -10 to -26 dB from 316 Hz to 4 kHz
    (it cannot carry the anvil's wave)."""
    _, cmp = demo
    spectra = cmp["pile_head_force_spectra"]
    low, high = spectra["valid_band [Hz]"]
    assert low == pytest.approx(40.0, rel=0.01)
    assert high == pytest.approx(cmp["comparison_bandwidth [Hz]"])
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool)
    rom = np.array(spectra["deviation_from_fea [dB]"]["rom"])
    lumped = np.array(spectra["deviation_from_fea [dB]"]["lumped"])
    up_to_1k = valid & (centre <= 1260.0)
    assert up_to_1k.sum() == 15
    assert np.all(np.abs(rom[up_to_1k]) <= 1.0)
    above_100 = valid & (centre >= 99.0)
    assert np.all(np.abs(rom[above_100]) < np.abs(lumped[above_100]))
    assert np.all(lumped[valid & (centre >= 316.0)] < -9.0)
    plot_spectra(spectra, tmp_path / "fig_spectra.png")
    assert (tmp_path / "fig_spectra.png").stat().st_size > 10_000


def test_band_levels_of_identical_runs_agree():
    t = np.arange(0.0, 0.025, 1e-5)
    force = 1e6 + 4e8 * np.exp(-t / 2e-3) * (1.0 - np.exp(-t / 1e-4))
    run = ModelRun("x", {"time [s]": t, "anvil_pile_force [N]": force}, 0.0, {})
    spectra = band_levels({"fea": run, "rom": run}, bandwidth=3300.0)
    assert spectra["valid_band [Hz]"] == [pytest.approx(40.0, rel=0.01), 3300.0]
    assert np.allclose(spectra["deviation_from_fea [dB]"]["rom"], 0.0)


def test_table1_pile_port_in_rings_against_fea(demo):
    """table1.toml with the pile port split into three rings across the wall (the mesh's three
    edges there; ``[anvil] pile_port_rings = 3``) against the demo's FEA: the rings close one
    after the other when the anvil comes back tilted, instead of the one port's slap.
    Measured: band levels +0.2, +1.0, +3.3, +3.1, +2.6 dB at 1.6-4 kHz (one port: +1.7 to
    +8.4 dB), within 1.0 dB from 50 Hz to 1.26 kHz; peaks in the 5 kHz band pile +2.1 %, ram
    -3.0 %, RMS 2.5 % / 6.1 %, raw pile +2.2 %, raw ram +7.5 %: the bounds of
    test_table1_rom_against_fea still hold. Bounds here: the one port's largest excess above
    1.26 kHz must drop by more than half (8.4 dB -> at most 3.5 dB), the bands up to 1.26 kHz
    within 1.1 dB (0.9 dB with one port; the 398 Hz band moves +0.1 dB). These levels hold
    for table1's 0.25 m segments: the rings' springs are shares of the pile's half segment, and
    with 0.0625 m segments the 2.5-4 kHz bands are +4.1 to +5.1 dB (README, "The ROM")."""
    import dataclasses

    from anvilwave.analyses.compare import metrics, without_soil
    from anvilwave.config.system import load_system
    from anvilwave.engine.direct import build_engine
    from anvilwave.output.tables import read_csv

    out, cmp = demo
    fea = ModelRun("fea", read_csv(out / "fea.csv"), 0.0, {})
    cfg = without_soil(load_system(EXAMPLES / "table1.toml"))
    spec = cfg.anvil.spec
    rings = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=3))))
    blow = build_engine(rings).blow()
    run = ModelRun("rom", blow.columns, blow.wall_time, {})
    spectra = band_levels({"rom": run, "fea": fea}, cmp["comparison_bandwidth [Hz]"])
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool)
    deviation = np.array(spectra["deviation_from_fea [dB]"]["rom"], dtype=float)
    assert np.all(np.abs(deviation[valid & (centre <= 1260.0)]) <= 1.1)
    assert np.all(np.abs(deviation[valid & (centre > 1260.0) & (centre < 4100.0)]) <= 3.5)
    m = metrics(run, fea, float(fea.columns["anvil_pile_force [N]"][0]), 5000.0)
    assert_within_issue_bounds(m)
    # the same run is docs/validation.md's `pile_port_rings = 3` row (benchmarks/doc_demo.py)
    stored = doc_data("demo")["values"]
    assert_same_numbers(m, stored["variants"]["pile_rings_3"], "pile_rings_3", skip=WALL)
    assert_same_numbers(benchmark("doc_demo").band_deviations(spectra, "rom"),
                        stored["spectra"]["pile_rings_3"], "pile_rings_3 bands")


def test_docs_demo_data_is_this_demo(demo):
    """docs/data/demo.json (benchmarks/doc_demo.py: docs/demo.md's table and figures, the band
    levels of docs/validation.md) holds this demo's figures: the ROM's and the lumped anvil's
    errors, the interfaces-resolved ROM's, the band levels of all three (tolerance:
    tests/doc_tables.py, SAME_RUN)."""
    out, cmp = demo
    stored = doc_data("demo")["values"]
    summary = json.loads((out / "summary.json").read_text())
    for model in ("rom", "lumped"):
        assert_same_numbers(cmp[model], stored[model], model, skip=WALL)
    assert_same_numbers(summary["interfaces_rom_vs_fea"], stored["interfaces"], "interfaces")
    assert_same_numbers(summary, stored["summary"], "summary")
    script = benchmark("doc_demo")
    resolved = json.loads((out / "interfaces" / "comparison.json").read_text())
    computed = {"rom": script.band_deviations(cmp["pile_head_force_spectra"], "rom"),
                "lumped": script.band_deviations(cmp["pile_head_force_spectra"], "lumped"),
                "interfaces": script.band_deviations(resolved["pile_head_force_spectra"], "rom")}
    assert_same_numbers(computed, {k: stored["spectra"][k] for k in computed}, "spectra")


@pytest.mark.parametrize("name", ["rod_ram", "modal_ram_no_dashpot", "rod_ram_no_dashpot",
                                  "pile_rings_3_tube"])
def test_docs_demo_variant_against_the_demo_fea(demo, name):
    """The Table 1 variants of docs/data/demo.json, rerun against the demo's FEA (one blow of
    the in-process engine each; the tube head's kernel is in the session's cache from the
    demo's step 4). pile_rings_3: test_table1_pile_port_in_rings_against_fea."""
    out, cmp = demo
    script = benchmark("doc_demo")
    fea = ModelRun("fea", read_csv(out / "fea.csv"), 0.0, {})
    m, run = script.run_variant(name, fea, cmp["comparison_bandwidth [Hz]"])
    stored = doc_data("demo")["values"]
    assert_same_numbers(m, stored["variants"][name], name, skip=WALL)
    if name in stored["spectra"]:
        spectra = band_levels({"rom": run, "fea": fea}, cmp["comparison_bandwidth [Hz]"])
        assert_same_numbers(script.band_deviations(spectra, "rom"), stored["spectra"][name],
                            f"{name} bands")


@pytest.mark.parametrize("correction", [True, False])
def test_docs_fmax_study_row_at_the_default_fmax(demo, correction):
    """docs/data/study_fmax.json (benchmarks/study_fmax.py), its rows at the default 5 kHz
    recomputed on the demo's FEA (the study's own: the same free pile and FEA settings) and the
    demo's modes (the study truncates its 10 kHz set: the same modes below 5 kHz, the mesh does
    not depend on fmax). The other fmax are not rerun: their ram modes (1 to 10 kHz, 502 modes
    at 10 kHz, minutes at a cache miss) are beyond the suite's budget, and they run the same
    code at another fmax."""
    out, _ = demo
    study = benchmark("study_fmax")
    cfg = study.study_config()
    fea = ModelRun("fea", read_csv(out / "fea.csv"), 0.0, {})
    row = study.study_row(cfg, fea, cached_modal_data(cfg.anvil.spec, 5000.0), 5000.0,
                          correction)
    stored = next(r for r in doc_data("study_fmax")["values"]["rom"]
                  if r["fmax [Hz]"] == 5000.0 and r["static_correction"] == correction)
    assert_same_numbers(row, stored, f"fmax 5000, correction {correction}",
                        skip=WALL)


def test_docs_anvil_size_study_xl8_on_the_demo_fea(demo):
    """docs/data/study_anvil_size.json (benchmarks/study_anvil_size.py), its xl8 case (Table 1
    with a Smith rod ram, contacts without dashpot, 0.5 m pile segments) recomputed against the
    demo's FEA: the study's own xl8 FEA has the same settings (the FE model does not depend on
    the 1D ram, the pile segments or the contact dashpot), so every figure of the row must be
    the stored one within the same-run tolerance. The other cases: tests/test_doc_tables.py."""
    out, _ = demo
    study = benchmark("study_anvil_size")
    case = study.SERIES["scaled"][2]
    assert case.name == "xl8"
    fea = ModelRun("fea", read_csv(out / "fea.csv"), 0.0, {})
    row = study.run_case(case, reference=fea, modes=cached_modal_data)
    # the FEA's size and wall time are its own run's, not the demo's
    assert_same_numbers(row, doc_data("study_anvil_size")["values"]["scaled"]["xl8"], "xl8",
                        skip=(*WALL, "fea_dof", "fea_wall_time [s]"))
