"""The paper's comparison on the Table 1 case, end to end through `anvilwave demo`."""

from __future__ import annotations

import json

import numpy as np
import pytest

from anvilwave.cli import main
from anvilwave.compare import arrival_time, lift_off_intervals, lowpass


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    assert main(["demo", "--out", str(out)]) == 0
    return out, json.loads((out / "comparison.json").read_text())


def test_demo_writes_everything(demo):
    out, _ = demo
    for name in ("summary.json", "comparison.json", "fig2_ram_force.png", "fig3_pile_force.png",
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
