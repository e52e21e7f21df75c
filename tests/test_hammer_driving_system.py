"""The classic driving system (hammer cushion, helmet, assembly, pile cushion) as a component."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from anvilwave.hammer import (
    Cushion,
    DrivingSystem,
    RamRod,
    driving_system_energy,
    driving_system_forces,
    driving_system_stable_time_step,
    driving_system_step,
    interface_time_step,
    kinetic_energy,
    load_hammer,
    ram_step,
    required_substeps,
    strain_energy,
)
from anvilwave.hammer.driving_system import (
    P_PC_PRECOMPRESSION,
    S_ASSEMBLY_U,
    S_HC_MAX,
    S_HELMET_U,
    S_HELMET_V,
    S_PC_MAX,
)
from anvilwave.inputs import InputError, Table

G = 9.81
# the 8000 x 140 mm pile of the paper's Table 1 (steel): Z = rho c A
PILE_IMPEDANCE = 7850.0 * math.sqrt(210e9 / 7850.0) * 0.25 * math.pi * (8.0**2 - 7.72**2)


def test_static_equilibrium_on_the_pile_head():
    """Helmet and assembly at rest on the pile: F_pile = (m_h + m_a) g, nothing moves."""
    ds = DrivingSystem(Cushion(5e10, 0.8), 1.5e5, Cushion(3e10, 0.5, 2e-3), 2.5e5, 2e9)
    params = ds.parameters(G)
    state = ds.initial_state(params)
    weight = (1.5e5 + 2.5e5) * G
    # the pile cushion sits in the round-out: compression sqrt(2 r F / k)
    assert params[P_PC_PRECOMPRESSION] == pytest.approx(math.sqrt(2 * 2e-3 * weight / 3e10))
    h = 1e-4
    n_sub = required_substeps(h, driving_system_stable_time_step(params))
    for _ in range(200):
        f_ram, f_pile, u_top, u_bottom = driving_system_forces(params, state, -1.0, 0.0, 0.0,
                                                               0.0)
        assert f_ram == 0.0  # the ram is 1 m above: no contact
        # equilibrium up to round-off of the precompressions (1e-12 relative)
        assert f_pile == pytest.approx(weight, rel=1e-12)
        driving_system_step(params, state, -1.0, 0.0, 0.0, 0.0, h, n_sub)
    # a residual force of 1e-12 W (4 uN) acting for 0.02 s moves the helmet by ~5e-15 m
    assert abs(state[S_HELMET_U]) < 1e-12 and abs(state[S_ASSEMBLY_U]) < 1e-12
    _, _, u_top, u_bottom = driving_system_forces(params, state, -1.0, 0.0, 0.0, 0.0)
    assert u_top == u_bottom == state[S_HELMET_U]


def test_forces_are_feedthrough_and_leave_the_state_alone():
    ds = DrivingSystem(Cushion(2e10, 0.7), 2e4, Cushion(1e10, 1.0))
    params = ds.parameters(0.0)
    state = ds.initial_state(params)
    before = state.copy()
    f_ram, f_pile, _, _ = driving_system_forces(params, state, 1e-4, 3.0, -1e-4, 0.0)
    assert f_ram == pytest.approx(2e10 * 1e-4) and f_pile == pytest.approx(1e10 * 1e-4)
    np.testing.assert_array_equal(state, before)


@pytest.mark.parametrize("e", [1.0, 0.8, 0.5])
def test_ram_helmet_impact_obeys_newtons_restitution(e):
    """Rigid ram on a free helmet through a Smith cushion: the relative velocity reverses
    with the factor e (spring loads at k, unloads at k / e^2: e^2 of the energy returns)."""
    m_ram, m_helmet, v0, h = 1e4, 2e4, 5.0, 1e-6
    ds = DrivingSystem(Cushion(2e10, e), m_helmet, Cushion(1e10, 1.0))
    params = ds.parameters(0.0)
    state = ds.initial_state(params)
    ram = RamRod.rigid(m_ram)
    u, v = ram.initial_state(v0)
    far_pile = 10.0  # the pile head 10 m below: the helmet flies free
    n_sub = required_substeps(h, driving_system_stable_time_step(params))
    touched = False
    for _ in range(100_000):
        f_ram, _, _, _ = driving_system_forces(params, state, u[0], v[0], far_pile, 0.0)
        touched |= f_ram > 0.0
        if touched and f_ram == 0.0:
            break
        driving_system_step(params, state, u[0], v[0], far_pile, 0.0, h, n_sub)
        ram_step(ram.mass, ram.stiffness, u, v, f_ram, 0.0, h, 1)
    # the force held over a step for the ram but not for the helmet is a first-order coupling
    # error: 1.0 % at h = 10 us, 0.1 % at 1 us; tolerance 0.5 %
    assert (state[S_HELMET_V] - v[0]) / (e * v0) == pytest.approx(1.0, rel=5e-3)
    # momentum: same first-order error, 2e-6 at 1 us; tolerance 1e-4
    total = m_ram * v[0] + m_helmet * state[S_HELMET_V]
    assert total == pytest.approx(m_ram * v0, rel=1e-4)


def test_stable_time_step_is_sharp_for_the_helmet():
    """Helmet between a pressed-in ram and a fixed pile: bounded just below the stable step,
    growing just above it (both cushions compressed throughout, so the system is linear)."""
    ds = DrivingSystem(Cushion(4e10, 1.0), 1e5, Cushion(2e10, 1.0))
    params = ds.parameters(0.0)
    dt = driving_system_stable_time_step(params)
    assert dt == pytest.approx(2.0 / math.sqrt(6e10 / 1e5), rel=1e-14)
    u_ram = 0.1  # pressed in far enough that neither cushion opens during the test
    equilibrium = u_ram * 4e10 / 6e10
    offset = 1e-6
    amplitudes = []
    for factor, steps in ((0.99, 2000), (1.02, 20)):
        state = ds.initial_state(params)
        state[S_HELMET_U] = equilibrium + offset
        worst = 0.0
        for _ in range(steps):
            driving_system_step(params, state, u_ram, 0.0, 0.0, 0.0, factor * dt, 1)
            worst = max(worst, abs(state[S_HELMET_U] - equilibrium))
        amplitudes.append(worst)
    # stable: velocity Verlet keeps 1/2 v^2 + 1/2 w^2 x^2 (1 - (w dt)^2 / 4), so |x| never
    # exceeds its starting value (up to round-off of 1e-16 / 1e-6)
    assert amplitudes[0] <= offset * (1 + 1e-6)
    # unstable: |lambda| = 1.49 per step at w dt = 2.04, x 2900 in 20 steps
    assert amplitudes[1] > 100 * offset
    # the coupling estimate never exceeds the component's own stable step
    assert 0 < interface_time_step(params, 5e3, 1e4) <= dt


@njit
def _blow(ram_mass, ram_stiffness, u, v, params, state, impedance, static_force, h, n_ram,
          n_ds, steps):
    """A minimal in-process engine: ram rod + driving system + pile as a dashpot (one
    numba loop, kernels called as they would be by the engine). Returns the pile work."""
    u_pile = 0.0
    v_pile = 0.0
    work = 0.0
    for _ in range(steps):
        f_ram, f_pile, u_top, u_bottom = driving_system_forces(params, state, u[-1], v[-1],
                                                               u_pile, v_pile)
        v_new = (f_pile - static_force) / impedance
        driving_system_step(params, state, u[-1], v[-1], u_pile, v_new, h, n_ds)
        ram_step(ram_mass, ram_stiffness, u, v, f_ram, 0.0, h, n_ram)
        work += f_pile * v_new * h
        u_pile += v_new * h
        v_pile = v_new
    return u_pile, work


@pytest.mark.parametrize("e_hammer, e_pile", [(1.0, 1.0), (0.8, 0.5)])
def test_energy_balance_of_a_blow(e_hammer, e_pile):
    """5500 kJ illustrative ram, driving system, 8 m pile (dashpot): the ram's energy ends in
    ram, helmet, cushions, pile work and the cushion losses (1 - e^2) k c_max^2 / 2."""
    hammer = load_hammer("illustrative_5500kj")
    ram = hammer.ram
    ds = DrivingSystem(Cushion(5e10, e_hammer), 1.5e5, Cushion(3e10, e_pile))
    params = ds.parameters(0.0)
    state = ds.initial_state(params)
    u, v = ram.initial_state(hammer.impact_velocity)
    h = 2e-6
    n_ram = required_substeps(h, ram.stable_time_step())
    n_ds = required_substeps(h, driving_system_stable_time_step(params))
    energy0 = kinetic_energy(ram.mass, v)
    u_pile, work = _blow(ram.mass, ram.stiffness, u, v, params, state, PILE_IMPEDANCE, 0.0,
                         h, n_ram, n_ds, int(0.03 / h))
    remaining = (kinetic_energy(ram.mass, v) + strain_energy(ram.stiffness, u)
                 + sum(driving_system_energy(params, state, u[-1], u_pile)))
    # Smith's law dissipates (1 - e^2) k c_max^2 / 2 per cushion whatever the path (partial
    # unloading and reloading run along one line), c_max as recorded at the sub-steps
    lost = (0.5 * (1 - e_hammer**2) * 5e10 * state[S_HC_MAX] ** 2
            + 0.5 * (1 - e_pile**2) * 3e10 * state[S_PC_MAX] ** 2)
    assert work > 0.5 * energy0  # most of the energy went into the pile
    # first-order coupling error of the explicit master: 0.27 % at h = 20 us, 0.07 % at 5 us,
    # 0.013 % at 1 us (elastic case); tolerance 0.1 % at 2 us
    assert remaining + work + lost == pytest.approx(energy0, rel=1e-3)


def test_driving_system_table():
    data = {
        "helmet_mass": 1.2e5,
        "assembly_mass": 3e5,
        "assembly_stiffness": 1e9,
        "hammer_cushion": {"area": 1.5, "elastic_modulus": 3.5e9, "thickness": 0.1,
                           "restitution": 0.8, "round_out": 1e-3},
        "pile_contact_stiffness": 8e10,
    }
    ds = DrivingSystem.from_table(Table(data, "sys.toml", "driving_system"))
    assert ds.hammer_cushion.stiffness == pytest.approx(3.5e9 * 1.5 / 0.1)
    assert ds.pile_cushion == Cushion(8e10, 1.0, 0.0) and not ds.has_pile_cushion
    assert ds.static_pile_force(G) == pytest.approx(4.2e5 * G)


@pytest.mark.parametrize("change, key, rule", [
    ({"helmet_mass": 0.0}, "driving_system.helmet_mass", "greater than 0"),
    ({"assembly_mass": 1e5}, "driving_system.assembly_stiffness", "required"),
    ({"assembly_stiffness": 1e9}, "driving_system.assembly_stiffness", "needs an assembly"),
    ({"pile_cushion": {"stiffness": 1e10, "restitution": 0.5}},
     "driving_system.pile_contact_stiffness", "cannot be given together"),
    ({"pile_contact_stiffness": None}, "driving_system.pile_contact_stiffness", "required"),
    ({"hammer_cushion": {"stiffness": 1e10, "restitution": 1.5}},
     "driving_system.hammer_cushion.restitution", "at most 1"),
    ({"hammer_cushion": {"stiffness": 1e10, "area": 1.0, "restitution": 0.5}},
     "driving_system.hammer_cushion.area", "cannot be given together"),
    ({"hammer_cushion": {"restitution": 0.5}}, "driving_system.hammer_cushion.stiffness",
     "is required"),
    ({"hammer_cushion": {"stiffness": 1e10, "restitution": 0.5, "damping": 1.0}},
     "driving_system.hammer_cushion.damping", "unknown key"),
])
def test_driving_system_table_errors(change, key, rule):
    data = {"helmet_mass": 1e5, "hammer_cushion": {"stiffness": 1e10, "restitution": 0.8},
            "pile_contact_stiffness": 5e10}
    data.update(change)
    data = {name: value for name, value in data.items() if value is not None}
    with pytest.raises(InputError) as info:
        DrivingSystem.from_table(Table(data, "sys.toml", "driving_system"))
    assert info.value.key == key
    assert rule in info.value.rule
