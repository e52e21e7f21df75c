"""The in-process engine against closed-form impacts, wave reflection, energy and soil."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from anvilwave.analyses.impact import energy_balance, total_energy
from anvilwave.cli import main
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.ram import RamRod
from anvilwave.inputs import InputError
from anvilwave.output.tables import read_csv
from anvilwave.pile.model import PileSoil

from .conftest import EXAMPLES

# ../shared/reference/closed-form-impacts.md: steel pile D = 2 m, wall 50 mm
E, RHO = 210e9, 7850.0
C0 = math.sqrt(E / RHO)
AREA = math.pi / 4 * (2.0**2 - 1.9**2)
Z = E * AREA / C0  # 12.43652 MN s/m


def write_system(tmp_path, ram: str, velocity: float, dx: float, *, duration=3e-3,
                 pile_length=40.0, extra_anvil="", time_step=None, soil="", gravity=0.0,
                 pile_area_factor=1.0):
    wall = 0.05 if pile_area_factor == 1.0 else None
    if wall is None:  # same outer diameter, wall chosen for the area ratio
        inner = math.sqrt(2.0**2 - 4 * AREA * pile_area_factor / math.pi)
        wall = (2.0 - inner) / 2
    (tmp_path / "hammer.toml").write_text(
        f'name = "test ram"\nimpact_velocity = {velocity}\n[ram]\n{ram}\n'
        '[source]\ndocument = "closed-form validation case"\nyear = 2026\n')
    step = "" if time_step is None else f"time_step = {time_step!r}\n"
    (tmp_path / "system.toml").write_text(f"""
[simulation]
duration = {duration!r}
gravity = {gravity!r}
{step}
[hammer]
file = "hammer.toml"
[anvil]
model = "none"
{extra_anvil}
[pile]
segment_length = {dx!r}
material_damping = 0.0
gauge_depth = 1.0
[[pile.sections]]
length = {pile_length!r}
outer_diameter = 2.0
wall_thickness = {wall!r}
{soil}
""")
    return load_system(tmp_path / "system.toml")


def rod_ram(length, dx, area=AREA):
    inner = math.sqrt(2.0**2 - 4 * area / math.pi)
    return f'kind = "rod"\nprofile = [[{length!r}, 2.0, {inner!r}]]\nsegment_length = {dx!r}'


def run(cfg):
    return build_engine(cfg).run()[0]


def off_jumps(t, jumps, h):
    """Samples farther than one step from the jumps of a discontinuous reference."""
    mask = np.ones_like(t, dtype=bool)
    for tj in jumps:
        mask &= np.abs(t - tj) > h
    return mask


def test_case3_two_equal_rods_is_exact_at_courant_one(tmp_path):
    """Striker of the pile's section, L1 = 2 m, 5 m/s: a rectangular pulse Z v0 / 2 lasting
    2 L1 / c. Chains of equal segments at the Courant number 1 propagate without dispersion,
    and with the Smith half-segment contact the two rods form one uniform chain: the discrete
    solution is exact at every sample (the half-step start puts the impact between samples)."""
    dx = 0.25
    cfg = write_system(tmp_path, rod_ram(2.0, dx), 5.0, dx, time_step=dx / C0)
    r = run(cfg)
    t, F = r.columns["time [s]"], r.columns["anvil_pile_force [N]"]
    duration = 2 * 2.0 / C0
    exact = np.where((t > 0) & (t < duration), Z * 5.0 / 2, 0.0)
    assert F.max() == pytest.approx(31.0913e6, rel=1e-2)  # reference: 31.0913 MN
    keep = off_jumps(t, [0.0, duration], r.time_step)
    # the samples next to the two jumps are excluded: a sampled step cannot place its jump
    # better than a step; elsewhere the chain is exact (measured 1e-12)
    rms = np.sqrt(np.mean((F[keep] - exact[keep]) ** 2)) / (Z * 2.5)
    assert rms < 0.02
    on = t[F > 0.5 * Z * 2.5]
    assert abs((on[-1] - on[0]) - duration) <= r.time_step
    # the striker ends at rest and all 60.112 kJ enter the pile (1 % for the sampling of the
    # transferred energy at the gauge is not used: the ram's own energy is exact here)
    ram_left = r.energies["ram_kinetic [J]"][-1] + r.energies["ram_strain [J]"][-1]
    assert ram_left < 1e-3 * r.input_energy
    assert r.input_energy == pytest.approx(60.112e3, rel=1e-4)


def case2_force(t, k=2e10, m=1e4, v0=5.0):
    w0 = math.sqrt(k / m)
    zeta = math.sqrt(k * m) / (2 * Z)
    wd = w0 * math.sqrt(1 - zeta**2)
    F = k * v0 / wd * np.exp(-zeta * w0 * t) * np.sin(wd * t)
    return np.where((t > 0) & (t < math.pi / wd), F, 0.0)


def test_case2_ram_on_spring_on_semi_infinite_pile(tmp_path):
    """Rigid 10 t ram at 5 m/s on a 2e10 N/m spring on a semi-infinite pile: closed form.

    The pile's head is its top segment mass, half a segment below the face (Smith): that is a
    first-order error for a smooth head load, measured at dx = 0.25 / 0.125 / 0.0625 m as peak
    +1.0 / +0.5 / +0.24 %, F(2 ms) -5.7 / -2.8 / -1.4 %, rebound -6 / -3 / -1.6 %. The test runs
    at 0.0625 m, where the issue's 1 % (peak) and 2 % (history) hold.
    """
    dx = 0.0625
    k_half = 2 * E * AREA / dx
    k_spring = 2e10
    # the contact is the spring in series with the pile's top half segment: choose the ram
    # side so that the series is the reference spring
    k_ram = 1 / (1 / k_spring - 1 / k_half)
    cfg = write_system(tmp_path, 'kind = "rigid"\nmass = 1.0e4', 5.0, dx,
                       extra_anvil=f"ram_contact_stiffness = {k_ram!r}")
    r = run(cfg)
    t, F = r.columns["time [s]"], r.columns["anvil_pile_force [N]"]
    exact = case2_force(t)
    # peak 36.2673 MN at 0.8304 ms: 1 % on the peak, 2 % RMS on the history
    assert F.max() == pytest.approx(36.2673e6, rel=1e-2)
    assert t[F.argmax()] == pytest.approx(0.8304e-3, rel=1e-2)
    rms = np.sqrt(np.mean((F - exact) ** 2)) / 36.2673e6
    assert rms < 0.02
    assert np.interp(0.5e-3, t, F) == pytest.approx(31.5931e6, rel=2e-2)
    assert np.interp(2e-3, t, F) == pytest.approx(12.5245e6, rel=2e-2)
    end = t[F > 0][-1]
    assert end == pytest.approx(2.7004e-3, rel=1e-2)
    # rebound velocity -0.5701 m/s (2 %, see above); energy into the pile 123.375 kJ (1 %)
    assert r.columns["ram_toe_velocity [m/s]"][-1] == pytest.approx(-0.5701, rel=2e-2)
    ram_left = r.energies["ram_kinetic [J]"][-1]
    assert r.input_energy - ram_left == pytest.approx(123.375e3, rel=1e-2)


def test_case1_rigid_ram_on_semi_infinite_pile(tmp_path):
    """Rigid 10 t ram at 5 m/s directly on the pile: F = Z v0 exp(-Z t / m).

    The rigid ram bears through one segment spring E A / dx (its side 2 E A / dx in series with
    the pile's top half segment), i.e. it enters the pile's chain as one heavy element, and the
    chain runs at the Courant number 1, where it carries the head wave without dispersion.
    Measured at dx = 0.05 m: peak -0.6 %, F(1 ms) +0.5 %, 0.3 % RMS (first order in dx: -2.4 %,
    -1.2 %, -0.6 % at 0.2, 0.1, 0.05 m), so 1 % on the peak and 2 % on the history hold. (A far
    stiffer contact makes the light top mass rattle against the ram: +41 % spikes.)
    """
    dx = 0.05
    cfg = write_system(tmp_path, 'kind = "rigid"\nmass = 1.0e4', 5.0, dx,
                       extra_anvil=f"ram_contact_stiffness = {2 * E * AREA / dx!r}",
                       time_step=dx / C0)
    r = run(cfg)
    t, F = r.columns["time [s]"], r.columns["anvil_pile_force [N]"]
    exact = np.where(t > 0, Z * 5.0 * np.exp(-Z * np.maximum(t, 0) / 1e4), 0.0)
    assert F.max() == pytest.approx(62.1826e6, rel=1e-2)
    keep = off_jumps(t, [0.0], r.time_step)  # the sample next to the jump at t = 0
    rms = np.sqrt(np.mean((F[keep] - exact[keep]) ** 2)) / 62.1826e6
    assert rms < 0.02
    assert np.interp(1e-3, t, F) == pytest.approx(17.9291e6, rel=1e-2)
    # all 125 kJ enter the pile: the ram stops (its kinetic energy is gone to 1 %)
    assert r.energies["ram_kinetic [J]"][-1] < 1e-2 * r.input_energy


@pytest.mark.parametrize(("ratio", "first", "second"), [(0.5, 20.7275e6, 0.0),
                                                         (2.0, 41.4551e6, 13.8184e6)])
def test_case4_unequal_impedances(tmp_path, ratio, first, second):
    """Striker of impedance Z1 = ratio Z2 (same material, area ratio) on the pile: the force
    starts at Z1 Z2 v0 / (Z1 + Z2) and steps by r = (Z1 - Z2)/(Z1 + Z2) every 2 L1 / c."""
    dx = 0.125
    cfg = write_system(tmp_path, rod_ram(2.0, dx, AREA * ratio), 5.0, dx, time_step=dx / C0,
                       duration=2.5e-3)
    r = run(cfg)
    t, F = r.columns["time [s]"], r.columns["anvil_pile_force [N]"]
    period = 2 * 2.0 / C0
    # plateau means over the middle of each interval (the interface between chains of unequal
    # impedance rings for a few samples after each jump): 1 %
    first_plateau = F[(t > 0.2 * period) & (t < 0.8 * period)].mean()
    second_plateau = F[(t > 1.2 * period) & (t < 1.8 * period)].mean()
    assert first_plateau == pytest.approx(first, rel=1e-2)
    assert second_plateau == pytest.approx(second, abs=1e-2 * first)


def test_free_toe_returns_tension_at_2L_over_c(tmp_path):
    """A 20 m free pile struck by a 2 m rod: the compression pulse reflects at the free toe as
    tension and reaches the gauge (1 m below the head) at (2 L - z_g) / c."""
    dx, L = 0.25, 20.0
    cfg = write_system(tmp_path, rod_ram(2.0, dx), 5.0, dx, time_step=dx / C0,
                       pile_length=L, duration=9e-3)
    r = run(cfg)
    t, Fg = r.columns["time [s]"], r.columns["gauge_force [N]"]
    first_tension = t[np.argmax(Fg < -0.5 * Z * 2.5)]
    expected = (2 * L - 1.0) / C0
    assert abs(first_tension - expected) <= 1.5 * r.time_step


@pytest.fixture(scope="module")
def table1():
    return load_system(EXAMPLES / "table1.toml")


@pytest.fixture(scope="module")
def xl8_modal(table1):
    """The xl8 modes, from the session's modal-data cache (the engine's own, computed once per
    session for every worker and module that runs Table 1)."""
    from anvilwave.config.cache import cached_modal_data

    return cached_modal_data(table1.anvil.spec, table1.anvil.fmax)


@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_energy_balance_of_a_table1_blow(table1, xl8_modal, model):
    """Ram energy = kinetic + strain + soil work + damping + contact (+ gravity), 0.5 %, at the
    engine's automatic step (the step its accuracy rule is made for).

    table1.toml fixes h = 25 us, 0.57 of the coupling limit of its modal ram's stiff toe
    contact: there the final residual is 2e-4 (lumped) and 1.4e-3 (ROM), but the lumped
    anvil's transient deviation while the contact closes reaches 0.51 % (O(h^2), see below)."""
    cfg = dataclasses.replace(table1, time_step=None).with_anvil_model(model)
    r = build_engine(cfg, modal=xl8_modal).run()[0]
    balance = energy_balance(r)
    # measured: residual 8.5e-4 (ROM) and 1.2e-3 (lumped) of the impact energy, largest
    # deviation 1.0e-3 and 2.9e-3; 0.5 % is the bound
    assert abs(balance["residual_relative [-]"]) < 5e-3
    assert balance["max_deviation_relative [-]"] < 5e-3
    assert balance["soil_static_work [J]"] > 0 and balance["soil_damping_work [J]"] > 0


@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_total_energy_conserved_without_damping_over_100ms(table1, xl8_modal, model):
    """All damping off (soil J, pile material damping, modal damping): the total energy (with
    the soil's static work) stays within 0.1 % of the impact energy over 100 ms.

    The explicit coupling conserves a discrete (shadow) energy of the leapfrog family exactly
    for linear parts; what remains is the penalty contact closing within a step, an error of
    about k (v h / 2)^2 / 2 per closing, O(h^2): 0.28 % of the impact energy for the lumped
    anvil at the automatic step with the rod ram (38 us), 0.02 % at the 10 us used here."""
    ps = table1.pile_soil
    soil = dataclasses.replace(ps.soil, damping_shaft=0.0, damping_toe=0.0)
    pile = dataclasses.replace(ps.pile, material_damping=0.0)
    anvil = dataclasses.replace(table1.anvil, damping_ratio=0.0, ram_contact_damping=0.0)
    cfg = dataclasses.replace(table1, duration=0.1, pile_soil=PileSoil(pile, soil),
                              anvil=anvil, time_step=1e-5).with_anvil_model(model)
    r = build_engine(cfg, modal=xl8_modal).run()[0]
    total = total_energy(r.energies)
    assert np.abs(total - total[0]).max() < 1e-3 * r.input_energy
    assert r.energies["soil_damping_work [J]"][-1] == 0.0


@pytest.mark.parametrize("model, step", [("rom", None), ("none", 5e-6)])
def test_contact_dashpot_work_closes_the_energy_balance(table1, xl8_modal, model, step):
    """table1.toml's ram-impedance dashpot dissipates part of the blow: booked as
    contact_damping_work (the contact force's part beyond its elastic part, times the
    contact's closing rate), the balance closes within 0.5 % of the impact energy, and without
    the booking it would not. Measured: ROM at table1.toml's 20 us, -7.5e-4 with 1.6 %
    dissipated. The direct ram-pile contact (no anvil) closes on the dashpot's full force c v
    within one step, an O(h) error of the booking: 5.8e-3 at 20 us, 2.2e-3 at 10 us, 1.0e-3 at
    the 5 us used here (1.1 % dissipated)."""
    cfg = table1.with_anvil_model(model)
    if step is not None:
        cfg = dataclasses.replace(cfg, time_step=step)
    assert cfg.anvil.ram_contact_damping == pytest.approx(
        table1.hammer.ram.toe_impedance, rel=1e-12)
    r = build_engine(cfg, modal=xl8_modal).run()[0]
    balance = energy_balance(r)
    dissipated = balance["contact_damping_work [J]"] / r.input_energy
    assert 0.005 < dissipated < 0.1
    assert abs(balance["residual_relative [-]"]) < 5e-3
    assert abs(balance["residual_relative [-]"] - dissipated) > 5e-3


def test_classic_driving_system_runs_with_the_same_interface(table1):
    """The classic cushion-helmet unit of the Smith-type programs in the same engine: with a
    rigid helmet of the anvil's FE mass and elastic contacts it is the lumped anvil by another
    road, so the peak pile force agrees with the lumped ROM-less anvil within 3 % (the contact
    stiffnesses are the same half segments, rounded to three digits in the example)."""
    classic = build_engine(table1.with_anvil_model("classic")).run()[0]
    lumped = build_engine(table1.with_anvil_model("lumped")).run()[0]
    a = classic.columns["anvil_pile_force [N]"].max()
    b = lumped.columns["anvil_pile_force [N]"].max()
    assert a == pytest.approx(b, rel=3e-2)
    assert abs(energy_balance(classic)["residual_relative [-]"]) < 5e-3


def test_permanent_set_positive_and_falls_with_resistance(table1, xl8_modal):
    sets = []
    for factor in (0.5, 1.0, 2.0):
        soil = table1.pile_soil.soil
        srd = dataclasses.replace(soil.srd,
                                  unit_shaft_friction=soil.srd.unit_shaft_friction * factor,
                                  unit_toe_resistance=soil.srd.unit_toe_resistance * factor)
        cfg = dataclasses.replace(table1, duration=0.06, pile_soil=PileSoil(
            table1.pile_soil.pile, dataclasses.replace(soil, srd=srd))).with_anvil_model("lumped")
        r = build_engine(cfg, modal=xl8_modal).run()[0]
        sets.append(r.final_state["soil_offset"][-1] - r.final_state["soil_offset_start"][-1])
    assert all(s > 0 for s in sets)
    assert sets[0] > sets[1] > sets[2], sets


def test_segment_length_convergence_of_peak_head_force(table1, xl8_modal):
    """Peak anvil-pile force of the Table 1 blow (lumped anvil, Smith's rod ram, springs only)
    as the pile and ram segments are refined: the changes shrink (the lumped chains
    converge)."""
    peaks = []
    for dx in (1.0, 0.5, 0.25):
        pile = dataclasses.replace(table1.pile_soil.pile, segment_length=dx)
        hammer = load_hammer("illustrative_5500kj")  # table1.toml's, as a rod
        ram = RamRod.uniform(hammer.ram.length, hammer.ram.toe_diameter, segment_length=dx)
        cfg = dataclasses.replace(table1, pile_soil=PileSoil(pile, table1.pile_soil.soil),
                                  hammer=dataclasses.replace(hammer, ram=ram),
                                  anvil=dataclasses.replace(table1.anvil,
                                                            ram_contact_damping=0.0))
        r = build_engine(cfg.with_anvil_model("lumped"), modal=xl8_modal).run()[0]
        peaks.append(r.columns["anvil_pile_force [N]"].max())
    changes = np.abs(np.diff(peaks))
    assert changes[1] < changes[0], peaks
    assert changes[1] / peaks[-1] < 0.02, peaks


def test_time_step_above_the_limit_is_refused(tmp_path):
    cfg = write_system(tmp_path, rod_ram(2.0, 0.25), 5.0, 0.25, time_step=1e-3)
    with pytest.raises(InputError, match="simulation.time_step"):
        build_engine(cfg)


def test_cli_impact_writes_results(tmp_path):
    out = tmp_path / "out"
    assert main(["impact", str(EXAMPLES / "table1.toml"), "--anvil", "lumped", "--out",
                 str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    for key in ("peak_ram_anvil_force [N]", "peak_anvil_pile_force [N]",
                "peak_pile_compression_stress [Pa]", "transferred_energy_unzeroed [J]",
                "permanent_set [m]", "energy_balance", "simulated_time [s]", "wall_time [s]"):
        assert key in summary
    columns = read_csv(out / "impact.csv")
    for name in ("time [s]", "ram_anvil_force [N]", "anvil_pile_force [N]",
                 "pile_head_velocity [m/s]", "gauge_force [N]", "gauge_velocity [m/s]"):
        assert name in columns
    assert (out / "impact.png").stat().st_size > 10_000
    # 25 ms at the automatic step, all of it written
    assert columns["time [s]"][-1] == pytest.approx(0.025, abs=1e-4)
