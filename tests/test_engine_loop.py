"""The engine's fused loop against a plain master loop over the units' own kernels, its blow
API for driveability (static state, other soils, summaries inside the loop) and its
one-per-engine stability analysis."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import anvilwave.engine.direct as engine_module
from anvilwave.analyses.impact import energy_balance
from anvilwave.anvil_rom.contact import contact_force
from anvilwave.anvil_rom.unit import AnvilUnit
from anvilwave.config.system import load_system
from anvilwave.engine.direct import COLUMNS, ENERGY_COLUMNS, ENERGY_STEPS, PileState, build_engine
from anvilwave.hammer.driving_system import driving_system_forces, driving_system_step
from anvilwave.hammer.modal_ram import ModalRamUnit, modal_ram_chain
from anvilwave.hammer.ram import leapfrog_energies, ram_step
from anvilwave.pile.kernels import (
    gauge_force,
    gauge_velocity,
    head_displacement,
    head_velocity,
    pile_energies,
    pile_step,
    update_energy,
    update_stress_extremes,
)
from anvilwave.pile.model import initial_state
from anvilwave.pile.pda.case_method import transferred_energy

from .conftest import EXAMPLES

DURATION = 0.012  # [s] 480 steps of Table 1: the impact, the lift-off and the re-impact


@pytest.fixture(scope="module")
def table1():
    return load_system(EXAMPLES / "table1.toml")


@pytest.fixture(scope="module")
def engines(table1):
    """One engine per anvil model (the ROM from the modal-data cache)."""
    rom = build_engine(table1)
    out = {"rom": rom}
    for model in ("lumped", "classic", "none"):
        out[model] = build_engine(table1.with_anvil_model(model), rom.modal)
    return out


def reference_blow(engine, duration):
    """The DESIGN.md master loop in Python over each unit's own kernels (those the FMUs call):
    ram_step, AnvilUnit.forces / step (or the driving system, or one contact spring),
    pile_step; the columns of COLUMNS at every step and the pile's stress extremes."""
    cfg = engine.config
    h = engine.time_step
    n_steps = int(round(duration / h))
    g = cfg.gravity
    kind = engine.anvil.kind
    arrays = engine.pile_arrays
    state = initial_state(arrays, head_force=engine.static_head_force, gravity=g)
    u, v, offset, energy = (np.array(a) for a in state)
    face0 = head_displacement(arrays.probes, u)
    unit = None
    u_top0 = 0.0
    if kind in ("rom", "lumped"):
        unit = AnvilUnit(engine.anvil.unit.anvil, engine.anvil.unit.contact, gravity=g)
        u_top0, _ = unit.rest_on_pile(0.0)
        unit.set_step(h)
    elif kind == "classic":
        ds_p, ds_s = engine.anvil.P, engine.anvil.S.copy()
    t0 = -0.5 * h
    mass, stiffness = engine.ram_mass, engine.ram_stiffness
    ram_u = np.full(mass.shape, u_top0 + t0 * cfg.impact_velocity)
    ram_v = np.full(mass.shape, cfg.impact_velocity)
    ram_nsub, pile_nsub = engine._ram_nsub, engine._pile_nsub
    modal_ram = None
    if engine.ram_modes is not None:  # the modal ram unit (table1.toml's ram_model = "modal")
        modal_ram = ModalRamUnit(engine.ram_modes, g)
        modal_ram.start(u_top0 + t0 * cfg.impact_velocity, cfg.impact_velocity, h)
    factor = cfg.pile_soil.stress_factors()
    extremes = np.zeros(2)
    rows = []
    for n in range(n_steps + 1):
        u_ram, v_ram = ram_u[-1], ram_v[-1]
        if modal_ram is not None:
            u_ram, v_ram = modal_ram.toe[0], modal_ram.toe[1]
        u_pile = head_displacement(arrays.probes, u) - face0
        v_pile = head_velocity(arrays.probes, v)
        if unit is not None:
            f_ram, f_pile = unit.forces(u_ram, v_ram, u_pile, v_pile)
            u_top, _, u_bottom, _ = unit.outputs(f_ram, f_pile)
        elif kind == "classic":
            f_ram, f_pile, u_top, u_bottom = driving_system_forces(ds_p, ds_s, u_ram, v_ram,
                                                                   u_pile, v_pile)
        else:
            k, c = engine.anvil.P
            f_ram = f_pile = contact_force(u_ram - u_pile, v_ram - v_pile, k, c)
            u_top = u_bottom = u_pile
        update_stress_extremes(factor, u, extremes)
        rows.append([t0 + n * h, f_ram, f_pile, v_pile,
                     gauge_force(arrays.pile, arrays.probes, u, v),
                     gauge_velocity(arrays.probes, v), v_ram, u_top, u_bottom, u_pile + face0,
                     u[-1]])
        if n == n_steps:
            break
        if modal_ram is not None:
            modal_ram.step(f_ram)
        else:
            ram_step(mass, stiffness, ram_u, ram_v, f_ram, g, h, ram_nsub)
        if unit is not None:
            unit.step(f_ram, f_pile, h)
        elif kind == "classic":
            driving_system_step(ds_p, ds_s, u_ram, v_ram, u_pile, v_pile, h, engine.anvil.n_sub)
        pile_step(arrays.pile, arrays.soil, u, v, offset, energy, f_pile, g, h, pile_nsub)
    columns = dict(zip(COLUMNS, np.array(rows).T, strict=True))
    return columns, extremes, (u, v, offset, energy)


@pytest.mark.parametrize("model", ["rom", "lumped", "classic", "none"])
def test_fused_loop_equals_the_units_own_kernels(engines, model):
    """The engine's loop (fused sweeps, inverse masses, per-mass work sums, specialised per
    anvil model) against the plain loop over the kernels the FMUs run: the same operations
    in the same order, so the time series agree to round-off (measured: identical). The
    summaries computed inside the loop agree with those of the recorded series."""
    engine = engines[model]
    blow = engine.blow(duration=DURATION)
    columns, extremes, final = reference_blow(engine, DURATION)
    for name in COLUMNS:
        scale = max(np.abs(columns[name]).max(), 1e-300)
        np.testing.assert_allclose(blow.columns[name], columns[name], rtol=0,
                                   atol=1e-12 * scale, err_msg=name)
    assert blow.max_compression_stress == pytest.approx(extremes[0], rel=1e-12)
    assert blow.max_tension_stress == pytest.approx(extremes[1], rel=1e-12)
    for got, want in zip((blow.final_state.u, blow.final_state.v,
                          blow.final_state.soil_offset), final[:3], strict=True):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
    # the energy state: pile_step sums every work at every step; the engine sums the soil's
    # per mass, takes gravity's from the states and the dashpots' from the pile's exact
    # balance: the same to round-off (of the impact energy)
    np.testing.assert_allclose(blow.final_state.energy, final[3], rtol=0,
                               atol=1e-11 * blow.input_energy)
    # summaries inside the loop = the same quantities of the recorded series
    c = blow.columns
    assert blow.max_pile_head_force == pytest.approx(c["anvil_pile_force [N]"].max(), rel=1e-14)
    assert blow.max_toe_displacement == pytest.approx(c["pile_toe_displacement [m]"].max(),
                                                      rel=1e-14)
    toe = c["pile_toe_displacement [m]"]
    assert blow.permanent_set == pytest.approx(toe[-1] - toe[0], rel=1e-12, abs=1e-15)
    # EMX: the trapezoidal running integral of F v at the gauge (case_method.transferred_energy
    # integrates the same samples; its time steps are differences of the recorded times)
    emx = float(np.max(transferred_energy(c["time [s]"], c["gauge_force [N]"],
                                          c["gauge_velocity [m/s]"])))
    assert blow.emx_gauge == pytest.approx(emx, rel=1e-9)


@pytest.mark.parametrize("model", ["rom", "lumped", "classic", "none"])
def test_table1_blow_is_the_units_own_kernels_to_the_bit(engines, model):
    """The Table 1 blow (table1.toml: the modal ram unit; every anvil model) over its first
    4 ms (the impact): the engine's loop, its state in named bundles and its step in one helper
    per unit, does the units' own arithmetic in their order, so its time series and final pile
    state are those of the plain master loop over the units' kernels bit for bit. Two
    exceptions, bounded by :func:`test_fused_loop_equals_the_units_own_kernels`: the energy
    works, summed in another order there, and the ROM anvil's recorded face displacements,
    to which AnvilUnit.outputs adds the static correction's two terms one at a time (the
    engine their difference; measured: within 2e-18 m)."""
    engine = engines[model]
    duration = 0.004
    blow = engine.blow(duration=duration)
    columns, _, final = reference_blow(engine, duration)
    faces = ("anvil_top_displacement [m]", "anvil_bottom_displacement [m]")
    for name in COLUMNS:
        if model == "rom" and name in faces:
            scale = np.abs(columns[name]).max()
            np.testing.assert_allclose(blow.columns[name], columns[name], rtol=0,
                                       atol=1e-12 * scale, err_msg=name)
        else:
            np.testing.assert_array_equal(blow.columns[name], columns[name], err_msg=name)
    for got, want in zip((blow.final_state.u, blow.final_state.v,
                          blow.final_state.soil_offset), final[:3], strict=True):
        np.testing.assert_array_equal(got, want)


def test_blow_summary_does_not_depend_on_recording(engines):
    """record=False keeps no series but the same summary, state and set; the energy
    bookkeeping does not change the motion."""
    engine = engines["rom"]
    full = engine.blow(duration=DURATION)
    bare = engine.blow(duration=DURATION, record=False)
    assert bare.columns == {} and bare.energies == {}
    for name in ("max_compression_stress", "max_tension_stress", "emx_gauge", "emx_head",
                 "max_pile_head_force", "max_toe_displacement", "permanent_set",
                 "toe_velocity_end"):
        assert getattr(bare, name) == getattr(full, name), name
    np.testing.assert_array_equal(bare.final_state.u, full.final_state.u)
    np.testing.assert_array_equal(bare.final_state.soil_offset, full.final_state.soil_offset)


def test_energy_series_every_energy_interval_and_exact_at_its_rows(engines):
    """The energies are recorded every ENERGY_STEPS steps (and at the last); each row is the
    bookkeeping of that instant, the same as a record of every step gives there."""
    engine = engines["lumped"]
    coarse = engine.blow(duration=DURATION)
    fine = engine.blow(duration=DURATION, energy_interval=engine.time_step)
    n_steps = coarse.n_steps
    t = coarse.energies["time [s]"]
    expected = list(range(0, n_steps + 1, ENERGY_STEPS))
    if expected[-1] != n_steps:
        expected.append(n_steps)
    np.testing.assert_allclose(t, fine.columns["time [s]"][expected], rtol=0, atol=1e-15)
    assert len(fine.energies["time [s]"]) == n_steps + 1
    for name in ENERGY_COLUMNS:
        np.testing.assert_array_equal(coarse.energies[name], fine.energies[name][expected],
                                      err_msg=name)
    a, b = energy_balance(coarse), energy_balance(fine)
    assert a["residual [J]"] == b["residual [J]"]


def test_energy_sums_in_any_order_change_only_the_last_bits(engines):
    """The energy bookkeeping's sums are compiled with reassociation (fastmath "reassoc"):
    against exactly rounded sums (math.fsum) of the same terms they agree to 1e-13."""
    engine = engines["rom"]
    blow = engine.blow(duration=DURATION)
    u, v = blow.final_state.u, blow.final_state.v
    pile = engine.pile_arrays.pile
    dt = engine.time_step / engine._pile_nsub
    m, k = pile[0], pile[1]
    e = u[:-1] - u[1:]
    kinetic = math.fsum(0.5 * m * v * v)
    strain = math.fsum(0.5 * k[:-1] * e * (e - dt * (v[:-1] - v[1:])))
    works = tuple(np.random.default_rng(1).normal(size=(2, u.size)))
    got = pile_energies(m, k, m * 9.81, u, v, dt, u, v, works)
    assert got[0] == pytest.approx(kinetic, rel=1e-13)
    assert got[1] == pytest.approx(strain, rel=1e-13)
    for total, w in zip(got[3:], works, strict=True):
        assert total == pytest.approx(math.fsum(w), rel=1e-12, abs=1e-13)
    energy = np.zeros(8)
    update_energy(pile, u, v, energy, dt)
    assert energy[0] == pytest.approx(got[0], rel=1e-13)
    mr, kr = engine.ram_mass, engine.ram_stiffness
    ru = np.linspace(0.0, 1e-3, mr.size)
    rv = np.linspace(5.0, 6.0, mr.size)
    ke, se, pe = leapfrog_energies(mr, kr, ru, rv, 9.81, 1e-5)
    er = ru[:-1] - ru[1:]
    assert ke == pytest.approx(math.fsum(0.5 * mr * rv * rv), rel=1e-13)
    assert se == pytest.approx(math.fsum(0.5 * kr * er * (er - 1e-5 * (rv[:-1] - rv[1:]))),
                               rel=1e-13)
    assert pe == pytest.approx(-math.fsum(mr * 9.81 * (ru - 0.5e-5 * rv)), rel=1e-13)


def test_static_state_is_the_start_of_a_blow_and_a_copy(engines, table1):
    engine = engines["rom"]
    state = engine.static_state()
    s = initial_state(engine.pile_arrays, head_force=engine.static_head_force,
                      gravity=table1.gravity)
    np.testing.assert_array_equal(state.u, s.u)
    np.testing.assert_array_equal(state.soil_offset, s.soil_offset)
    assert engine.static_head_force == pytest.approx(
        engine.anvil.unit.anvil.total_mass * table1.gravity)
    state.u[:] = 1.0  # the engine keeps its own
    assert engine.static_state().u[0] != 1.0
    # the aliases of the kernel argument names
    assert state.pu is state.u and state.poff is state.soil_offset


def test_blow_leaves_its_start_state_alone_and_run_chains_blows(engines):
    """blow(state) does not modify the state; run() is blow() after blow(), each from the
    final state of the one before (the soil keeps its set)."""
    engine = engines["lumped"]
    start = engine.static_state()
    kept = start.copy()
    first = engine.blow(start, duration=DURATION, record=False)
    for a, b in zip((start.u, start.v, start.soil_offset, start.energy),
                    (kept.u, kept.v, kept.soil_offset, kept.energy), strict=True):
        np.testing.assert_array_equal(a, b)
    second = engine.blow(first.final_state, duration=DURATION, record=False)
    run = engine.run(duration=DURATION, record=False, blows=2)
    assert run[0].permanent_set == first.permanent_set
    assert run[1].permanent_set == second.permanent_set
    np.testing.assert_array_equal(run[1].final_state.soil_offset,
                                  second.final_state.soil_offset)
    np.testing.assert_array_equal(run[1].initial_state.u, run[0].final_state.u)
    # the mapping of earlier versions' final_state
    assert "soil_offset_start" in first.final_state
    np.testing.assert_array_equal(first.final_state["soil_offset_start"], start.soil_offset)


def test_with_pile_soil_reuses_the_engine(engines, table1, monkeypatch):
    """Another soil on the same pile: no eigenvalue problem and no stability analysis, the
    same step; the blow equals that of an engine built for the new system."""
    engine = engines["lumped"]
    soil = table1.pile_soil.soil
    srd = dataclasses.replace(soil.srd, unit_shaft_friction=soil.srd.unit_shaft_friction * 2,
                              unit_toe_resistance=soil.srd.unit_toe_resistance * 2)
    stiffer = dataclasses.replace(table1.pile_soil, soil=dataclasses.replace(soil, srd=srd))
    cfg = dataclasses.replace(table1, pile_soil=stiffer).with_anvil_model("lumped")
    built = build_engine(cfg, engine.modal)

    def refuse(*args, **kwargs):
        raise AssertionError("with_pile_soil must not redo the stability analysis")

    monkeypatch.setattr(engine_module, "coupled_stable_time_step", refuse)
    other = engine.with_pile_soil(stiffer)
    assert other.time_step == engine.time_step and other.anvil is engine.anvil
    assert other.ram_unit is engine.ram_unit is not None  # table1.toml's modal ram
    a = other.blow(duration=0.04, record=False)  # the toe moves after 2 L / c = 31 ms
    b = built.blow(duration=0.04, record=False)
    assert a.permanent_set == b.permanent_set
    assert a.max_compression_stress == b.max_compression_stress
    assert 0.0 < a.permanent_set < engine.blow(duration=0.04, record=False).permanent_set
    longer = dataclasses.replace(table1.pile_soil.pile,
                                 segment_length=2 * table1.pile_soil.pile.segment_length)
    with pytest.raises(ValueError, match="same pile"):
        engine.with_pile_soil(dataclasses.replace(stiffer, pile=longer))


def test_emx_at_the_head_is_the_work_into_the_pile_top(engines):
    """emx_head is the largest work of the head force on the pile top in the blow; with the
    head outputs at the top mass it is the energy bookkeeping's pile_head_face_work, and the
    gauge (2 m down) sees a little less of it."""
    blow = engines["rom"].blow(duration=DURATION, energy_interval=engines["rom"].time_step)
    work = blow.energies["pile_head_face_work [J]"]
    assert blow.emx_head == pytest.approx((work - work[0]).max(), rel=1e-12)
    assert 0.8 * blow.emx_head < blow.emx_gauge < 1.01 * blow.emx_head


def test_coupled_stability_limit_is_the_largest_eigenvalue(table1, engines):
    """The bisection on the chains-and-block structure equals a dense eigenvalue solution of
    the same stiffness and mass (assembled here spring by spring) to round-off; the ram is
    table1.toml's modal ram realised as its chain (the modal unit's modes integrate exactly
    and take no part in the leapfrog limit)."""
    ram = modal_ram_chain(table1.hammer.ram, table1.hammer.ram.modes)
    engine = build_engine(dataclasses.replace(
        table1, hammer=dataclasses.replace(table1.hammer, ram=ram)), engines["rom"].modal)
    assert engine.ram_modes is None and engine.ram_mass.size > 50
    unit = engine.anvil.unit
    cfg = engine.config
    arrays = engine.pile_arrays
    k_ram, k_pile = unit.contact.ram_stiffness, unit.contact.pile_stiffness
    pr, pp = unit.anvil.participation_ram, unit.anvil.participation_pile
    m_r, k_r = engine.ram_mass, np.asarray(cfg.hammer.ram.stiffness)
    m_p, k_p = arrays.pile[0], arrays.pile[1][:-1]
    n_r, n_a, n_p = m_r.size, pr.size, m_p.size
    n = n_r + n_a + n_p
    K = np.zeros((n, n))

    def spring(d, k):
        K[:] += k * np.outer(d, d)

    for i, k in enumerate(k_r):
        d = np.zeros(n)
        d[i], d[i + 1] = 1.0, -1.0
        spring(d, k)
    d = np.zeros(n)
    d[n_r - 1] = 1.0
    d[n_r:n_r + n_a] = -pr
    spring(d, k_ram)
    d = np.zeros(n)
    d[n_r:n_r + n_a] = pp
    d[n_r + n_a] = -1.0
    spring(d, k_pile)
    for i, k in enumerate(k_p):
        d = np.zeros(n)
        d[n_r + n_a + i], d[n_r + n_a + i + 1] = 1.0, -1.0
        spring(d, k)
    soil = arrays.soil[2]
    K[range(n_r + n_a, n), range(n_r + n_a, n)] += soil[:n_p]
    K[n - 1, n - 1] += soil[n_p]
    s = 1.0 / np.sqrt(np.concatenate([m_r, np.ones(n_a), m_p]))
    dense = 2.0 / np.sqrt(np.linalg.eigvalsh(s[:, None] * K * s[None, :]).max())
    # both to round-off (the dense solver's own last bits): measured 1e-16
    assert engine.limits["anvil coupling"] == pytest.approx(dense, rel=1e-13)


def test_pile_state_mapping_and_values(engines):
    state = engines["none"].static_state()
    assert isinstance(state, PileState)
    assert "soil_offset_start" not in state
    assert state["pile_u"] is state.u
    assert state.toe_displacement == state.u[-1]
