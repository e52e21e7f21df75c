"""Tests of pile/: Smith soil spring, lumped pile chain, static equilibrium, closed-form impacts,
convergence, energy bookkeeping and input validation.

Reference numbers are from /work/shared/reference/closed-form-impacts.md (example pile: steel,
D = 2 m, wall 50 mm, Z = 12.43652 MN s/m; ram 10 t at 5 m/s). Every tolerance is explained
where it is used.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import eigh_tridiagonal

from anvilwave.inputs import InputError, Table
from anvilwave.pile import (
    ENERGY_KINETIC,
    ENERGY_STRAIN,
    WORK_HEAD,
    WORK_PILE_DAMPING,
    WORK_SOIL_DAMPING,
    WORK_SOIL_STATIC,
    PileSoil,
    PileSoilState,
    PileSpec,
    Section,
    SoilResistanceTable,
    SoilSpec,
    energy_residual,
    gauge_force,
    head_displacement,
    head_face_work,
    head_velocity,
    initial_state,
    load_pile_soil,
    pile_step,
    soil_forces,
    soil_resistance,
    stable_time_step,
    substeps,
    toe_resistance,
)
from anvilwave.pile.kernels import (
    PILE_MASS,
    PILE_STIFFNESS,
    SOIL_CAPACITY,
    SOIL_DASHPOT,
    SOIL_STIFFNESS,
)
from anvilwave.pile.soil.models import lysmer_dashpot, lysmer_stiffness
from anvilwave.pile.soil.srd import shaft_capacities

E_STEEL, RHO_STEEL = 210e9, 7850.0
C_STEEL = math.sqrt(E_STEEL / RHO_STEEL)  # 5172.19 m/s
Z_REF = 12.43652e6  # [N s/m] impedance of the reference pile (closed-form-impacts.md)
RAM_MASS, V0 = 10e3, 5.0  # [kg], [m/s]


def uniform_pile(length=40.0, dx=0.5, damping=0.0, gauge_depth=1.0, soil=None) -> PileSoil:
    """The reference pile (D = 2 m, wall 50 mm) of a given length and segment length."""
    return PileSoil(PileSpec((Section(length, 2.0, 0.05),), dx, gauge_depth, damping), soil)


def copy_state(state: PileSoilState) -> PileSoilState:
    return PileSoilState(*(x.copy() for x in state))


def ram_spring_impact(dx, k_contact=2e10, head="face", duration=4e-3):
    """Case 2: rigid ram, massless compression-only spring, pile (long enough: no reflection).

    The co-simulation loop of DESIGN.md: read states at t_n, contact force at t_n, step both.
    The pile runs at Courant number 1 (h = dx / c, one sub-step). ``head="face"`` uses the
    pile-top face displacement, ``head="mass"`` the top mass displacement.
    """
    arrays = uniform_pile(dx=dx).arrays(extrapolate_head=True)
    state = initial_state(arrays)
    h = stable_time_step(arrays.pile, arrays.soil)
    u_ram, v_ram = 0.0, V0
    n = int(duration / h)
    force = np.empty(n)
    for i in range(n):
        u_head = head_displacement(arrays.probes, state.u) if head == "face" else state.u[0]
        f = k_contact * max(u_ram - u_head, 0.0)
        force[i] = f
        v_ram -= h * f / RAM_MASS
        u_ram += h * v_ram
        pile_step(arrays.pile, arrays.soil, *state, f, 0.0, h, 1)
    return np.arange(n) * h, force, v_ram, state, arrays


# ---------------------------------------------------------------------------- soil spring
def test_smith_spring_quasi_static_push_is_elastic_perfectly_plastic():
    """Loading, plastic flow, unloading with the same stiffness, permanent set (Smith 1960).

    The spring is piecewise linear, so the kernel must reproduce the curve to round-off
    (rtol 1e-12 on forces of order R_u).
    """
    capacity, quake = 2.0e6, 0.0025
    k = capacity / quake
    path = np.concatenate([np.linspace(0.0, 4 * quake, 81),        # load to 4 q
                           np.linspace(4 * quake, -2 * quake, 121),  # unload, reverse flow
                           np.linspace(-2 * quake, 0.0, 41)])        # reload
    offset = 0.0
    forces = []
    for u in path:
        r, rd, offset = soil_resistance(u, 0.0, offset, capacity, capacity, k, 0.0, 0.0)
        assert rd == 0.0
        forces.append(r)
    forces = np.array(forces)
    # expected: kinematic elastic-perfectly-plastic with yield +-R_u
    expected, s = [], 0.0
    for u in path:
        f = k * (u - s)
        if f > capacity:
            s, f = u - quake, capacity
        elif f < -capacity:
            s, f = u + quake, -capacity
        expected.append(f)
    np.testing.assert_allclose(forces, expected, rtol=0, atol=1e-12 * capacity)
    # the landmarks, explicitly
    i_q = 20  # u = q: yield reached exactly
    assert forces[i_q] == pytest.approx(capacity, rel=1e-12)
    assert np.all(forces[20:81] == pytest.approx(capacity, rel=1e-12))  # plastic flow
    unload = slice(81, 100)
    slopes = np.diff(forces[unload]) / np.diff(path[unload])
    np.testing.assert_allclose(slopes, k, rtol=1e-9)  # unloading stiffness = loading stiffness
    permanent_set = 4 * quake - quake  # zero force after unloading by one quake
    r0, _, _ = soil_resistance(permanent_set, 0.0, 3 * quake, capacity, capacity, k, 0.0, 0.0)
    assert abs(r0) < 1e-6


def test_toe_spring_lifts_off_and_recontacts_at_its_permanent_set():
    capacity, quake = 5.0e6, 0.0025
    k = capacity / quake
    r, _, offset = soil_resistance(3 * quake, 0.0, 0.0, capacity, 0.0, k, 0.0, 0.0)
    assert r == capacity and offset == pytest.approx(2 * quake)
    r, _, offset2 = soil_resistance(quake, 0.0, offset, capacity, 0.0, k, 0.0, 0.0)
    assert r == 0.0 and offset2 == offset  # gap: no tension, set unchanged
    r, _, _ = soil_resistance(2.5 * quake, 0.0, offset, capacity, 0.0, k, 0.0, 0.0)
    assert r == pytest.approx(0.5 * capacity, rel=1e-12)  # reloads from the set


def test_smith_and_smith_viscous_damping():
    capacity, quake, j = 1.0e6, 0.0025, 0.5
    k = capacity / quake
    u, v = 0.5 * quake, 2.0
    # Smith: J |R_s| v with R_s = R_u / 2
    _, rd, _ = soil_resistance(u, v, 0.0, capacity, capacity, k, j, 0.0)
    assert rd == pytest.approx(j * 0.5 * capacity * v, rel=1e-12)
    # upward motion on a shaft in tension still dissipates (sign follows v)
    _, rd, _ = soil_resistance(-u, -v, 0.0, capacity, capacity, k, j, 0.0)
    assert rd == pytest.approx(-j * 0.5 * capacity * v, rel=1e-12)
    # Smith-viscous: c = J R_u
    _, rd, _ = soil_resistance(u, v, 0.0, capacity, capacity, k, 0.0, j * capacity)
    assert rd == pytest.approx(j * capacity * v, rel=1e-12)
    # the toe never pulls: static + damping >= 0
    rs, rd, _ = soil_resistance(u, -10.0, 0.0, capacity, 0.0, k, 0.0, j * capacity)
    assert rs + rd == 0.0


# ---------------------------------------------------------------------------- pile chain
def test_lumped_chain_dispersion_relation_and_cutoff():
    """Free-free chain: omega_k = (2c/dx) sin(k pi / 2N), below the cut-off c / (pi dx).

    Eigenvalues of the tridiagonal M^-1/2 K M^-1/2 from the kernel arrays; rtol 1e-9 is
    round-off of a 100 x 100 symmetric eigenproblem.
    """
    dx, length = 1.0, 100.0
    arrays = uniform_pile(length=length, dx=dx).arrays(extrapolate_head=True)
    m, k = arrays.pile[PILE_MASS], arrays.pile[PILE_STIFFNESS, :-1]
    diag = (np.r_[0.0, k] + np.r_[k, 0.0]) / m
    off = -k / np.sqrt(m[:-1] * m[1:])
    omega = np.sqrt(np.clip(eigh_tridiagonal(diag, off, eigvals_only=True), 0.0, None))
    n = m.size
    expected = 2 * C_STEEL / dx * np.sin(np.arange(n) * np.pi / (2 * n))
    # atol: the rigid mode's eigenvalue is 0 up to ~1e-16 * 4k/m ~ 1e-8 rad^2/s^2, whose root
    # is ~1e-4 rad/s
    np.testing.assert_allclose(omega, expected, rtol=1e-9, atol=1e-3)
    cutoff = C_STEEL / (math.pi * dx)
    assert cutoff == pytest.approx(1646.4, abs=0.1)  # the reference value for dx = 1 m
    assert omega.max() / (2 * math.pi) < cutoff
    assert omega.max() / (2 * math.pi) > 0.999 * cutoff  # approached by the top mode


@pytest.mark.parametrize("courant", [1.0, 0.5])
def test_leapfrog_at_courant_one_is_dispersion_free(courant):
    """Mode k of the free-free chain, time-stepped by pile_step for 2L/c (= k periods).

    At Courant 1 the leapfrog's own error cancels the chain's dispersion exactly
    (sin(w dt / 2) = sin(kappa dx / 2)), so the mode returns with the continuous rod's period
    2L / (k c): error < 1e-9 of the amplitude (round-off over 80 steps). At Courant 0.5 the
    chain's dispersion remains (the mode runs at (2/dt) asin(0.5 sin(kappa dx / 2)) instead of
    c kappa): the error is of order one.
    """
    dx, length, mode = 1.0, 40.0, 25  # a short wave: 3.2 segments per wavelength
    arrays = uniform_pile(length=length, dx=dx).arrays(extrapolate_head=True)
    state = initial_state(arrays)
    n = arrays.pile.shape[1]
    shape = np.cos(mode * np.pi * (np.arange(n) + 0.5) / n)
    omega = mode * math.pi * C_STEEL / length
    steps = round(2 * n / courant)
    dt = 2 * length / C_STEEL / steps  # Courant number c dt / dx = courant
    state.u[:] = shape
    state.v[:] = shape * (1.0 - math.cos(omega * dt)) / dt  # v at t = -dt/2 of u = shape cos wt
    pile_step(arrays.pile, arrays.soil, *state, 0.0, 0.0, dt * steps, steps)
    error = np.max(np.abs(state.u - shape))
    if courant == 1.0:
        assert error < 1e-9
    else:
        assert error > 0.1


def test_free_toe_pile_returns_tension_at_2L_over_c():
    """Half-sine head force on a free pile: the gauge sees the pulse, then its tension reflection.

    Peaks are compared with the wave arrival times d/c and (2L - d)/c (+ half the pulse); the
    tolerance is one time step (the sampling of the output). Amplitudes within 1 %: the
    sampled half-sine peak of 1 ms held over dt = 0.097 ms steps is 0.995 F0.
    """
    length, gauge_depth, dx = 40.0, 2.0, 0.5
    pile = uniform_pile(length=length, dx=dx, gauge_depth=gauge_depth)
    arrays = pile.arrays(extrapolate_head=True)
    state = initial_state(arrays)
    dt = stable_time_step(arrays.pile, arrays.soil)
    assert dt == pytest.approx(dx / C_STEEL, rel=1e-12)  # Courant 1 is the stable limit
    pulse, f0 = 1e-3, 10e6
    n = int((2 * length / C_STEEL + 2 * pulse) / dt)
    t = (np.arange(n) + 1) * dt
    force = np.empty(n)
    for i in range(n):
        t_mid = (i + 0.5) * dt
        f = f0 * math.sin(math.pi * t_mid / pulse) if t_mid < pulse else 0.0
        pile_step(arrays.pile, arrays.soil, *state, f, 0.0, dt, 1)
        force[i] = gauge_force(arrays.pile, arrays.probes, state.u, state.v)
    i_c = np.argmax(np.where(t < length / C_STEEL, force, 0.0))  # the incident pulse
    i_t = np.argmin(force)
    assert t[i_c] == pytest.approx(0.5 * pulse + gauge_depth / C_STEEL, abs=dt)
    assert t[i_t] == pytest.approx(0.5 * pulse + (2 * length - gauge_depth) / C_STEEL, abs=dt)
    assert force[i_c] == pytest.approx(f0, rel=0.01)
    assert force[i_t] == pytest.approx(-f0, rel=0.01)


def test_closed_form_case2_ram_spring_pile():
    """Case 2 (k = 2e10 N/m) with 0.25 m segments at Courant 1.

    Tolerances: the halving study (test_segment_length_convergence) gives a peak error of
    0.04 MN at 0.25 m falling at ~2nd order; 0.3 % (0.11 MN) on forces and 1 % on the small
    rebound velocity leave margin for the sampling of the output at dt = 48 us; times within one
    step.
    """
    t, force, v_ram, state, arrays = ram_spring_impact(0.25)
    h = t[1]
    i = np.argmax(force)
    assert force[i] == pytest.approx(36.2673e6, rel=3e-3)
    assert t[i] == pytest.approx(0.8304e-3, abs=h)
    assert np.interp(0.5e-3, t, force) == pytest.approx(31.5931e6, rel=3e-3)
    assert np.interp(2e-3, t, force) == pytest.approx(12.5245e6, rel=3e-3)
    t_end = t[np.nonzero(force[i:] == 0.0)[0][0] + i]
    assert t_end == pytest.approx(2.7004e-3, abs=h)
    assert v_ram == pytest.approx(-0.5701, rel=1e-2)
    ram_loss = 0.5 * RAM_MASS * (V0**2 - v_ram**2)
    assert ram_loss == pytest.approx(123.375e3, rel=1e-3)
    # the contact acts on the head face: the work on the face equals the ram's loss (the
    # contact spring is relaxed after separation; 1e-4 covers the leapfrog's spring energy
    # term at the separation step)
    assert head_face_work(arrays.probes, state.energy) == pytest.approx(ram_loss, rel=1e-4)
    # the pile's own balance counts the work on the top mass, smaller by the interface loss of
    # the face extrapolation (head_face_work docstring): 0.2 % at dx = 0.25 m, < 0.5 % asserted
    assert 0.0 < ram_loss - state.energy[WORK_HEAD] < 5e-3 * ram_loss


def test_closed_form_case1_rigid_ram_tied_to_the_head():
    """Case 1: a rigid ram kinematically tied to the top mass (no spring).

    A rigid ram cannot meet a lumped top mass m0 = rho A dx without a perfectly plastic
    collision, which keeps m_r / (m_r + m0) of the 125 kJ; this is checked to 1e-6 (the
    bookkeeping is exact). After it, all of that energy enters the pile and F(1 ms) converges
    at first order in dx to the closed form 17.9291 MN: the Richardson extrapolation from
    dx = 0.5 and 0.25 m must match to 0.2 % (the remaining O(dx^2) term).
    """

    def run(dx):
        arrays = uniform_pile(dx=dx).arrays(extrapolate_head=True)
        state = initial_state(arrays)
        h = stable_time_step(arrays.pile, arrays.soil)
        v_ram, n = V0, int(6e-3 / h)
        force = np.empty(n)
        for i in range(n):
            # the head velocity after the step is affine in the force: probe with F = 0 and 1
            probe0, probe1 = copy_state(state), copy_state(state)
            pile_step(arrays.pile, arrays.soil, *probe0, 0.0, 0.0, h, 1)
            pile_step(arrays.pile, arrays.soil, *probe1, 1.0, 0.0, h, 1)
            slope = probe1.v[0] - probe0.v[0]
            f = (v_ram - probe0.v[0]) / (slope + h / RAM_MASS)  # v_ram_new = v_head_new
            force[i] = f
            v_ram -= h * f / RAM_MASS
            pile_step(arrays.pile, arrays.soil, *state, f, 0.0, h, 1)
        m0 = arrays.pile[PILE_MASS, 0]
        kept = 0.5 * RAM_MASS * V0**2 * RAM_MASS / (RAM_MASS + m0)
        # energy through the head: ram loss minus the head mass's share of the collision
        assert state.energy[WORK_HEAD] == pytest.approx(kept, rel=1e-6)
        t = (np.arange(n) + 0.5) * h  # the force is held over [t_n, t_n+1]
        return np.interp(1e-3, t, force)

    f_coarse, f_fine = run(0.5), run(0.25)
    assert abs(f_fine - 17.9291e6) < abs(f_coarse - 17.9291e6)
    assert 2 * f_fine - f_coarse == pytest.approx(17.9291e6, rel=2e-3)


def test_segment_length_convergence_of_peak_head_force():
    """Peak contact force of case 2 for dx = 1, 0.5, 0.25, 0.125 m.

    With the pile-top face displacement (extrapolated over the top half-segment) the error falls
    at about second order: the fitted log-log slope must exceed 1.5 (measured 1.90; the sampled
    peak makes single ratios irregular). Contact on the top mass instead is about first order
    (measured 1.16, asserted 0.8-1.5): the head looks stiffer by dx / (2 E A).
    """
    sizes = np.array([1.0, 0.5, 0.25, 0.125])
    exact = 36.2673e6
    err_face = [abs(ram_spring_impact(dx, duration=1.5e-3)[1].max() - exact) for dx in sizes]
    err_mass = [abs(ram_spring_impact(dx, head="mass", duration=1.5e-3)[1].max() - exact)
                for dx in sizes]
    slope_face = np.polyfit(np.log(sizes), np.log(err_face), 1)[0]
    slope_mass = np.polyfit(np.log(sizes), np.log(err_mass), 1)[0]
    assert slope_face > 1.5
    assert 0.8 < slope_mass < 1.5
    assert err_face[-1] < 1e-3 * exact


# ---------------------------------------------------------------------------- statics
def end_bearing_soil(toe_unit, penetration=10.0, quake=0.0025, model="smith-viscous"):
    rows = np.array([[0.0, 0.0, toe_unit], [penetration, 0.0, toe_unit]])
    return SoilSpec(model=model, penetration=penetration, srd=SoilResistanceTable.from_rows(rows),
                    quake_toe=quake)


def test_static_equilibrium_end_bearing_linear():
    """Head displacement = W x sum of flexibilities; the toe carries W; the blow starts at rest.

    Linear problem solved directly: rtol 1e-10 (a tridiagonal solve of 80 unknowns). At rest:
    |v| < 1e-9 m/s after 10 ms of pile_step under the same loads (round-off of forces of
    ~1e7 N on masses of ~1e3 kg over 100 steps of 1e-4 s gives ~1e-10 m/s).
    """
    weight = 3.0e6  # [N] hammer resting on the pile
    model = uniform_pile(soil=end_bearing_soil(toe_unit=200e6))
    arrays = model.arrays(extrapolate_head=True)
    state = initial_state(arrays, head_force=weight)
    k = arrays.pile[PILE_STIFFNESS, :-1]
    k_toe = arrays.soil[SOIL_STIFFNESS, -1]
    area = Section(40.0, 2.0, 0.05).area
    assert k_toe == pytest.approx(200e6 * area / 0.0025)
    top_mass = weight * (np.sum(1.0 / k) + 1.0 / k_toe)
    assert state.u[0] == pytest.approx(top_mass, rel=1e-10)
    # the head face adds the top half-segment, dx / (2 E A)
    face = top_mass + weight * 0.5 * 0.5 / (E_STEEL * area)
    assert head_displacement(arrays.probes, state.u) == pytest.approx(face, rel=1e-10)
    static, total = np.empty(81), np.empty(81)
    soil_forces(arrays.soil, state.u, state.v, state.soil_offset, static, total)
    assert static.sum() == pytest.approx(weight, rel=1e-10)
    assert toe_resistance(arrays.soil, state.u, state.v, state.soil_offset)[0] == pytest.approx(
        weight, rel=1e-10)
    h = stable_time_step(arrays.pile, arrays.soil)
    pile_step(arrays.pile, arrays.soil, *state, weight, 0.0, 100 * h, 100)
    assert np.max(np.abs(state.v)) < 1e-9


def test_static_equilibrium_with_gravity_and_partial_yield():
    """Self-weight + hammer weight on a shaft-and-toe pile loaded close to its capacity.

    Some springs yield (active set): those carry exactly their capacity with a plastic offset,
    the others stay below it. The soil reaction sums to W + pile weight (rtol 1e-10, a direct
    solve) and the state stays at rest under pile_step with the same loads and gravity.
    """
    weight, g = 5.0e6, 9.81
    rows = np.array([[0.0, 0.0, 5e6], [20.0, 40e3, 5e6]])
    soil = SoilSpec(model="smith", penetration=20.0, srd=SoilResistanceTable.from_rows(rows))
    arrays = uniform_pile(soil=soil, damping=0.02).arrays(extrapolate_head=True)
    capacity = arrays.soil[SOIL_CAPACITY]
    state = initial_state(arrays, head_force=weight, gravity=g)
    static, total = np.empty(81), np.empty(81)
    soil_forces(arrays.soil, state.u, state.v, state.soil_offset, static, total)
    pile_weight = arrays.pile[PILE_MASS].sum() * g
    assert static.sum() == pytest.approx(weight + pile_weight, rel=1e-10)
    plastic = state.soil_offset > 0.0
    elastic = (capacity > 0.0) & ~plastic
    assert plastic.any() and elastic.any()
    np.testing.assert_allclose(static[plastic], capacity[plastic], rtol=1e-12)
    assert np.all(static[elastic] < capacity[elastic])
    h = stable_time_step(arrays.pile, arrays.soil)
    pile_step(arrays.pile, arrays.soil, *state, weight, g, 100 * h, 100)
    assert np.max(np.abs(state.v)) < 1e-9


def test_static_load_above_capacity_is_refused():
    arrays = uniform_pile(soil=end_bearing_soil(toe_unit=1e6)).arrays(extrapolate_head=True)
    with pytest.raises(ValueError, match="capacity"):
        initial_state(arrays, head_force=1e7)


# ---------------------------------------------------------------------------- energy
@pytest.mark.parametrize("model", ["smith", "smith-viscous", "lysmer-toe"])
def test_energy_bookkeeping_closes(model):
    """KE + strain + soil work + damping work = head work + gravity work, every step.

    The kernel's energies are the exact discrete balance of the leapfrog (kernels docstring), so
    the residual is round-off: < 1e-12 of the head work (measured ~4e-15) after 600 sub-steps
    of sums over 120 masses (double precision, ~1e-16 per operation; 1e-12 leaves three
    decades for the accumulation). Non-uniform pile, gravity, hammer weight, plastic soil flow,
    two sub-steps per communication step.
    """
    rows = np.array([[0.0, 0.0, 2e6], [10.0, 30e3, 4e6], [30.0, 90e3, 8e6]])
    extra = dict(toe_shear_modulus=80e6, toe_density=2000.0) if model == "lysmer-toe" else {}
    soil = SoilSpec(model=model, penetration=30.0, srd=SoilResistanceTable.from_rows(rows),
                    **extra)
    sections = (Section(30.0, 2.0, 0.05), Section(20.0, 2.0, 0.04), Section(10.0, 1.8, 0.06))
    arrays = PileSoil(PileSpec(sections, 0.5, 1.0, 0.02), soil).arrays(extrapolate_head=True)
    weight, g = 1.0e6, 9.81
    state = initial_state(arrays, head_force=weight, gravity=g)
    e0 = state.energy.copy()
    h = 1e-4
    n_sub = substeps(h, stable_time_step(arrays.pile, arrays.soil))
    assert n_sub >= 2  # stiff soil springs/dashpots bring the limit below dx / c
    worst = 0.0
    for i in range(300):
        t = i * h
        f = weight + (40e6 * math.sin(math.pi * t / 4e-3) if t < 4e-3 else 0.0)
        pile_step(arrays.pile, arrays.soil, *state, f, g, h, n_sub)
        worst = max(worst, abs(energy_residual(state.energy, e0)))
    head_work = state.energy[WORK_HEAD]
    assert head_work > 1e5
    assert worst < 1e-12 * head_work
    assert state.energy[WORK_SOIL_STATIC] > 0.0 and state.energy[WORK_SOIL_DAMPING] > 0.0
    assert state.energy[WORK_PILE_DAMPING] > 0.0
    assert np.any(state.soil_offset > 0.0)  # the blow left a permanent set
    assert state.energy[ENERGY_KINETIC] >= 0.0 and state.energy[ENERGY_STRAIN] > 0.0


# ---------------------------------------------------------------------------- SRD, models
def test_srd_capacities_are_independent_of_segmentation():
    """Shaft capacity is the exact integral of the piecewise-linear unit friction x perimeter.

    Expected total with outside + inside friction: perimeter pi D + pi (D - 2t) times the area
    under the profile (a step at 12 m included); rtol 1e-12.
    """
    rows = np.array([[0.0, 0.0, 0.0], [12.0, 60e3, 5e6], [12.0, 20e3, 2e6], [30.0, 80e3, 8e6]])
    table = SoilResistanceTable.from_rows(rows)
    assert table.check() is None
    area_under = 0.5 * 12.0 * 60e3 + 0.5 * 18.0 * (20e3 + 80e3)
    perimeter = math.pi * 8.0 + math.pi * (8.0 - 0.28)
    for n in (7, 160, 333):
        edges = np.linspace(0.0, 80.0, n + 1)
        shaft = shaft_capacities(table, edges[:-1], edges[1:], 50.0, np.full(n, 8.0),
                                 np.full(n, 0.14))
        assert shaft.sum() == pytest.approx(perimeter * area_under, rel=1e-12)
        assert np.all(shaft[edges[1:] <= 50.0] == 0.0)  # nothing above the mudline
    assert table.toe_resistance(30.0) == 8e6
    assert table.toe_resistance(12.0) == 2e6  # deeper side of a step
    assert table.toe_resistance(21.0) == pytest.approx(5e6)


def test_lysmer_toe_parameters():
    """Spring 4 G r0 / (1 - nu) and dashpot 3.4 r0^2 sqrt(G rho) / (1 - nu) at the toe."""
    rows = np.array([[0.0, 0.0, 5e6], [10.0, 0.0, 5e6]])
    soil = SoilSpec(model="lysmer-toe", penetration=10.0, srd=SoilResistanceTable.from_rows(rows),
                    toe_shear_modulus=50e6, toe_density=1900.0, toe_poisson_ratio=0.3)
    arrays = uniform_pile(soil=soil).arrays(extrapolate_head=True)
    r0 = math.sqrt(Section(40.0, 2.0, 0.05).area / math.pi)
    assert arrays.soil[SOIL_STIFFNESS, -1] == pytest.approx(4 * 50e6 * r0 / 0.7)
    dashpot = 3.4 * r0**2 * math.sqrt(50e6 * 1900) / 0.7
    assert arrays.soil[SOIL_DASHPOT, -1] == pytest.approx(dashpot)
    assert lysmer_stiffness(50e6, r0, 0.3) == arrays.soil[SOIL_STIFFNESS, -1]
    assert lysmer_dashpot(50e6, 1900.0, r0, 0.3) == arrays.soil[SOIL_DASHPOT, -1]


# ---------------------------------------------------------------------------- input files
PILE_TOML = """
[pile]
segment_length = 0.5
gauge_depth = 1.0
material_damping = 0.01
[[pile.sections]]
length = 60.0
outer_diameter = 8.0
wall_thickness = 0.14
[[pile.sections]]
length = 20.0
outer_diameter = 8.0
wall_thickness = 0.09
youngs_modulus = 210e9
density = 7850.0

[soil]
model = "smith"
penetration = 30.0
quake_shaft = 0.0025
quake_toe = 0.0025
damping_shaft = 0.65
damping_toe = 0.5
srd = [[0.0, 0.0, 0.0], [30.0, 80e3, 8e6]]
"""


def write(tmp_path, text):
    path = tmp_path / "pile.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_load_pile_soil_file(tmp_path):
    model = load_pile_soil(write(tmp_path, PILE_TOML))
    assert model.pile.length == 80.0 and model.soil.model == "smith"
    arrays = model.arrays(extrapolate_head=True)
    assert arrays.pile.shape == (3, 160) and arrays.soil.shape == (5, 161)
    assert arrays.pile.dtype == np.float64 and arrays.pile.flags.c_contiguous
    steel = 7850.0 * (math.pi / 4) * (64.0 - 7.72**2) * 60.0
    steel += 7850.0 * (math.pi / 4) * (64.0 - 7.82**2) * 20.0
    assert arrays.pile[PILE_MASS].sum() == pytest.approx(steel, rel=1e-12)
    # shaft: f = 80 kPa z / 30 m; the upper 10 m of embedment in section 1 (inner 7.72 m), the
    # lower 20 m in section 2 (inner 7.82 m), outside + inside perimeter
    integral_1 = 80e3 / 30.0 * 0.5 * 10.0**2
    integral_2 = 80e3 / 30.0 * 0.5 * (30.0**2 - 10.0**2)
    shaft = (integral_1 * (math.pi * 8.0 + math.pi * 7.72)
             + integral_2 * (math.pi * 8.0 + math.pi * 7.82))
    assert arrays.soil[SOIL_CAPACITY, :-1].sum() == pytest.approx(shaft, rel=1e-12)
    toe = 8e6 * math.pi / 4 * (64.0 - 7.82**2)
    assert arrays.soil[SOIL_CAPACITY, -1] == pytest.approx(toe, rel=1e-12)


@pytest.mark.parametrize(
    ("old", "new", "key", "rule"),
    [
        ("wall_thickness = 0.14", "wall_thickness = 4.5", "pile.sections[0].wall_thickness",
         "at most half"),
        ("gauge_depth = 1.0", "gauge_depth = 90.0", "pile.gauge_depth", "less than 80"),
        ("material_damping = 0.01", "material_dampng = 0.01", "pile.material_dampng",
         "unknown key"),
        ('model = "smith"', 'model = "hyperbolic"', "soil.model", "must be one of"),
        ("penetration = 30.0", "penetration = 81.0", "soil.penetration", "at most 80"),
        ("[30.0, 80e3, 8e6]]", "[20.0, 80e3, 8e6]]", "soil.srd", "penetration depth"),
        ("[[0.0, 0.0, 0.0],", "[[1.0, 0.0, 0.0],", "soil.srd", "depth 0"),
        ("quake_toe = 0.0025", "quake_toe = -0.0025", "soil.quake_toe", "greater than 0"),
        ('model = "smith"', 'model = "lysmer-toe"', "soil.toe_shear_modulus", "required"),
    ],
)
def test_input_errors_name_key_and_rule(tmp_path, old, new, key, rule):
    assert old in PILE_TOML
    with pytest.raises(InputError) as info:
        load_pile_soil(write(tmp_path, PILE_TOML.replace(old, new, 1)))
    assert info.value.key == key
    assert rule in info.value.rule


def test_lysmer_toe_rejects_smith_toe_keys(tmp_path):
    text = PILE_TOML.replace('model = "smith"', 'model = "lysmer-toe"\ntoe_shear_modulus = 5e7'
                             '\ntoe_density = 2000.0')
    with pytest.raises(InputError) as info:
        load_pile_soil(write(tmp_path, text))
    assert info.value.key in ("soil.damping_toe", "soil.quake_toe")
    assert "unknown key" in info.value.rule


def test_pile_without_soil_from_table():
    table = Table({"sections": [{"length": 10.0, "outer_diameter": 1.0, "wall_thickness": 0.5}]},
                  "<memory>", "pile")
    model = PileSoil.from_tables(table, None)
    arrays = model.arrays(extrapolate_head=True)
    assert not arrays.soil.any()
    assert arrays.pile.shape[1] == 20  # 10 m at the default 0.5 m
    state = initial_state(arrays)
    pile_step(arrays.pile, arrays.soil, *state, 1e6, 0.0, 1e-4, 2)
    assert head_velocity(arrays.probes, state.v) > 0.0
