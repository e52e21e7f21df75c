"""The paper's comparison on the Table 1 case, end to end through `anvilwave demo`."""

from __future__ import annotations

import json

import numpy as np
import pytest

from anvilwave.cli import main
from anvilwave.compare import (
    ModelRun,
    arrival_time,
    band_levels,
    lift_off_intervals,
    lowpass,
    plot_spectra,
)


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    assert main(["demo", "--out", str(out)]) == 0
    return out, json.loads((out / "comparison.json").read_text())


def test_demo_writes_everything(demo):
    out, _ = demo
    for name in ("summary.json", "comparison.json", "fig2_ram_force.png", "fig3_pile_force.png",
                 "fig_spectra.png",
                 "fea.csv", "rom.csv", "lumped.csv", "modes/modes.npz", "fmus/Anvil.fmu",
                 "fmus/Ram.fmu", "fmus/PileSoil.fmu", "fmus/AnvilLumped.fmu", "fmus/system.ssp"):
        assert (out / name).exists(), name
    summary = json.loads((out / "summary.json").read_text())
    assert summary["anvil_modes"] > 10
    assert summary["ram_model"] == "modal" and summary["ram_masses"] > 50


def test_table1_rom_against_fea(demo):
    """ROM vs FEA in the comparison band (3.3 kHz), with the bounds of the issue: arrival time
    within 0.1 ms, RMS errors within 10 %, peaks within 3 % (pile) and 5 % (ram). Measured with
    table1.toml's modal ram: arrival 0.0 ms, RMS 3.4 % ram and 2.8 % pile, peaks +2.2 % pile and
    -0.1 % ram. (With Smith's 1D rod ram, whose missing lateral inertia is the difference: peaks
    +4.7 % and +5.5 %, RMS 6.9 % and 3.6 %; test_modal_ram.py.)"""
    _, cmp = demo
    rom = cmp["rom"]
    assert abs(rom["pile_force_arrival_error [s]"]) <= 1e-4
    assert rom["ram_anvil_force_normalised_rms_error [-]"] <= 0.10
    assert rom["anvil_pile_force_normalised_rms_error [-]"] <= 0.10
    assert abs(rom["peak_anvil_pile_force_error [-]"]) <= 0.03
    assert abs(rom["peak_ram_anvil_force_error [-]"]) <= 0.05


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
    band runs from 1 / T (40 Hz, T = 25 ms) to the 3.3 kHz comparison band (a tenth of the
    ROM's 40 kHz sampling would allow 4 kHz). Measured, ROM - FEA: within 0.9 dB in every band
    from 50 Hz to 1 kHz (largest -0.87 dB at 251 Hz, +0.75 dB at 1 kHz), then +1.4, +2.7,
    +5.4 and +8.5 dB in the 1.26, 1.6, 2 and 2.5 kHz bands (+12.7 dB at 3.15 kHz): the 1 dB
    target holds up to 1 kHz, not up to 4 kHz. The lumped anvil is -1.8 dB at 100 Hz, -10 to
    -24 dB from 316 Hz to 2.5 kHz (it cannot carry the anvil's wave)."""
    _, cmp = demo
    spectra = cmp["pile_head_force_spectra"]
    low, high = spectra["valid_band [Hz]"]
    assert low == pytest.approx(40.0, rel=0.01)
    assert high == pytest.approx(cmp["comparison_bandwidth [Hz]"])
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool)
    rom = np.array(spectra["deviation_from_fea [dB]"]["rom"])
    lumped = np.array(spectra["deviation_from_fea [dB]"]["lumped"])
    up_to_1k = valid & (centre <= 1001.0)
    assert up_to_1k.sum() == 14
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
