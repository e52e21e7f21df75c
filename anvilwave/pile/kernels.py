"""Numba kernels of the pile/soil component: one time step, stability limit, outputs, energy.

All kernels are ``@njit(cache=True)``, work in place on float64 arrays and can be called from
Python (FMU wrappers) or from inside another jitted time loop (the in-process engine).

Conventions: SI units; z points DOWN; u, v positive downward; axial (spring) force positive in
COMPRESSION; a soil resistance is positive when it pushes the pile UP (resists downward motion).

Array layout
------------
``pile``   (PILE_ROWS, N): PILE_MASS [kg] per segment, PILE_STIFFNESS [N/m] and PILE_DASHPOT
           [N s/m] of the spring between mass i and i+1 (zero in column N-1).
``soil``   (SOIL_ROWS, N+1): column i < N is the shaft soil on mass i, column N the toe soil on
           mass N-1. Rows: SOIL_CAPACITY R_u [N] (downward motion), SOIL_TENSION [N] (upward
           motion; 0 = the soil cannot pull, a gap opens instead: the toe), SOIL_STIFFNESS
           k = R_u / quake [N/m], SOIL_SMITH Smith damping J [s/m] (force J |R_s| v),
           SOIL_DASHPOT viscous dashpot [N s/m] (Smith-viscous J R_u, or a radiation dashpot).
``probes`` (PROBE_SIZE,): where the outputs are read: GAUGE_SPRING index and
           GAUGE_SPRING_WEIGHT, GAUGE_MASS index and GAUGE_MASS_WEIGHT (indices stored as
           floats), HEAD_EXTRAPOLATION (see :func:`head_displacement`).
state      ``u`` (N,) [m], ``v`` (N,) [m/s], ``soil_offset`` (N+1,) plastic offset of each
           soil spring [m] (the permanent set of the soil), ``energy`` (ENERGY_SIZE,) [J].

Time integration: semi-implicit (symplectic) Euler, v += dt a(u, v); u += dt v, i.e. leapfrog
with v held at half steps, as in Smith (1960). All forces (springs, dashpots, soil, gravity,
head force) are evaluated from the state at the start of the sub-step, so velocity-dependent
forces use v at t - dt/2.

Energy (exact discrete balance): with the work increments evaluated with the centred
displacement increment du = dt (v_old + v_new) / 2 and the "leapfrog" energies
KE = sum m v^2 / 2 (v at t - dt/2) and U = sum k e(t) e(t - dt) / 2 (e = spring shortening),
KE + U - (KE + U)_0 = W_head + W_gravity - W_soil_static - W_soil_damping - W_pile_damping
holds to round-off for a constant sub-step (the discrete energy identity of the central-
difference scheme; cf. the energy balance check of explicit codes in Belytschko, Liu & Moran
2000, Nonlinear Finite Elements for Continua and Structures, ch. 6).
U differs from sum k e^2 / 2 by O(dt), and so does KE from the energy at a full step.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from anvilwave.anvil_rom.arrays import aligned_copy, aligned_zeros

PILE_MASS, PILE_STIFFNESS, PILE_DASHPOT = 0, 1, 2
PILE_ROWS = 3

SOIL_CAPACITY, SOIL_TENSION, SOIL_STIFFNESS, SOIL_SMITH, SOIL_DASHPOT = 0, 1, 2, 3, 4
SOIL_ROWS = 5

GAUGE_SPRING, GAUGE_SPRING_WEIGHT, GAUGE_MASS, GAUGE_MASS_WEIGHT, HEAD_EXTRAPOLATION = range(5)
PROBE_SIZE = 5

(
    ENERGY_KINETIC,
    ENERGY_STRAIN,
    WORK_HEAD,
    WORK_GRAVITY,
    WORK_SOIL_STATIC,
    WORK_SOIL_DAMPING,
    WORK_PILE_DAMPING,
    WORK_HEAD_SHORTENING,
) = range(8)
ENERGY_SIZE = 8
"""Entries of the ``energy`` state [J]: kinetic, strain (leapfrog form), work done by the head
force on the top mass, by gravity, work done ON the soil by its static and its damping
resistance, energy dissipated in the pile material dashpots, and the integral of the head force
over the shortening of the first spring (for :func:`head_face_work`)."""


@njit(cache=True)
def soil_resistance(u, v, offset, capacity, tension, stiffness, smith, dashpot):
    """Smith (1960) soil spring: elastic-perfectly-plastic static part plus damping.

    Static: R_s = k (u - s), limited to [-tension, capacity]; at a limit s moves along (plastic
    flow) so unloading follows the elastic slope k and leaves the permanent set s. With
    tension = 0 and u < s the soil has lost contact: no force, s unchanged (reloading starts
    at u = s). Damping: R_d = (J |R_s| + c) v (Smith damping with |R_s| so that it always
    dissipates; Smith-viscous is c = J R_u). Where the soil cannot pull (tension = 0) the total
    R_s + R_d is kept >= 0. A spring with stiffness <= 0 carries nothing.

    Parameters
    ----------
    u : float
        Pile displacement at the spring [m], positive down.
    v : float
        Pile velocity at the spring [m/s], positive down.
    offset : float
        Plastic offset s of the spring [m] (the permanent set so far).
    capacity : float
        Ultimate resistance R_u for downward motion [N].
    tension : float
        Capacity for upward motion [N] (0: no tension, a gap opens).
    stiffness : float
        Spring stiffness R_u / quake [N/m].
    smith : float
        Smith damping J [s/m].
    dashpot : float
        Viscous dashpot c [N s/m].

    Returns
    -------
    static : float
        Static resistance R_s [N], positive when it pushes the pile up.
    damping : float
        Damping resistance R_d [N], positive when it pushes the pile up.
    offset : float
        The new plastic offset [m].

    References
    ----------
    Smith, E.A.L. (1960). Pile-driving analysis by the wave equation. Journal of the Soil Mechanics
        and Foundations Division, ASCE, 86(SM4), 35-61.
    """
    if stiffness <= 0.0:
        return 0.0, 0.0, offset
    return _soil_spring(u, v, offset, capacity, tension, stiffness, smith, dashpot,
                        capacity / stiffness, tension / stiffness)


@njit(cache=True, inline='always')
def _soil_spring(u, v, offset, capacity, tension, stiffness, smith, dashpot, yield_down,
                 yield_up):
    """:func:`soil_resistance` of a spring with stiffness > 0, its yield displacements
    capacity / stiffness and tension / stiffness [m] given (no division)."""
    r = stiffness * (u - offset)
    if r > capacity:
        r = capacity
        offset = u - yield_down
    elif r < -tension:
        if tension > 0.0:
            r = -tension
            offset = u + yield_up
        else:
            return 0.0, 0.0, offset
    rd = (smith * abs(r) + dashpot) * v
    if tension <= 0.0 and r + rd < 0.0:
        rd = -r
    return r, rd, offset


# ------------------------------------------------------------------ the time step
# The step works on 1D arrays prepared once (:func:`sweep_arrays`): no division per segment
# (inverse masses, yield displacements), the segments above the first soil spring in a loop
# without soil and without running totals (the soil's works are summed per mass), so that the
# compiler can vectorise the free length of the pile.
SWEEP_PILE = ("weight", "inverse_mass", "stiffness", "dashpot")
"""The ``pile_sweep`` tuple of :func:`sweep_arrays`, (N,) arrays: m g [N], 1 / m [1/kg], the
spring and the dashpot below each mass [N/m], [N s/m] (0 below the toe mass)."""
SWEEP_WORKS = ("soil_static", "soil_damping")
"""The ``soil_works`` tuple of :func:`pile_advance`, (N,) arrays [J]: work done on the soil by
its static and its damping resistance at each mass (the toe spring's on the last mass)."""
SWEEP_SOIL = ("capacity", "tension", "stiffness", "smith", "dashpot", "yield_down", "yield_up")
"""The ``soil_sweep`` tuple of :func:`sweep_arrays`, (N + 1,) arrays: the soil rows and the
yield displacements capacity / k and tension / k [m] (0 where k = 0)."""


def sweep_arrays(pile: np.ndarray, soil: np.ndarray, gravity: float):
    """The arrays of :func:`pile_advance` for a pile and soil, prepared once.

    Each array is contiguous and aligned (:mod:`anvilwave.anvil_rom.arrays`).

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters (module docstring) [kg], [N/m], [N s/m].
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters (module docstring) [N], [N/m], [s/m], [N s/m].
    gravity : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    pile_sweep : tuple of numpy.ndarray
        The (N,) arrays named by SWEEP_PILE: m g [N], 1 / m [1/kg], the spring [N/m] and the
        dashpot [N s/m] below each mass.
    soil_sweep : tuple of numpy.ndarray
        The (N + 1,) arrays named by SWEEP_SOIL: the soil rows and the yield displacements
        capacity / k and tension / k [m] (0 where k = 0).
    first_soil : int
        Index of the first mass with a shaft soil spring [-] (N - 1 when none above the toe
        mass).
    """
    mass = pile[PILE_MASS]
    pile_sweep = (aligned_copy(mass * gravity), aligned_copy(1.0 / mass),
                  aligned_copy(pile[PILE_STIFFNESS]), aligned_copy(pile[PILE_DASHPOT]))
    k = soil[SOIL_STIFFNESS]
    stiff = k > 0.0
    yield_down = aligned_zeros(k.shape)
    yield_up = aligned_zeros(k.shape)
    yield_down[stiff] = soil[SOIL_CAPACITY, stiff] / k[stiff]
    yield_up[stiff] = soil[SOIL_TENSION, stiff] / k[stiff]
    soil_sweep = tuple(aligned_copy(soil[row]) for row in range(SOIL_ROWS))
    soil_sweep += (yield_down, yield_up)
    n = mass.size
    shaft = np.flatnonzero(stiff[:n - 1])
    first_soil = int(shaft[0]) if shaft.size else n - 1
    return pile_sweep, soil_sweep, first_soil


@njit(cache=True, inline='always')
def pile_advance(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, energy, head_force, h,
                 n_sub, soil_works=None, damping_work=None):
    """Advance the pile and soil over a communication step h [s] in n_sub sub-steps.

    The physics of :func:`pile_step` on the arrays of :func:`sweep_arrays`. Works in place on
    u, v, soil_offset; adds the head works (WORK_HEAD, WORK_HEAD_SHORTENING) to ``energy``.
    The gravity work is not summed (:func:`gravity_work` has it from the states) and
    ENERGY_KINETIC / ENERGY_STRAIN are not updated (:func:`update_energy`). The dashpots' work is
    also the remainder of the exact energy balance (module docstring): the in-process engine books
    it that way, without a sum over the free length of the pile.

    Parameters
    ----------
    pile_sweep : tuple of numpy.ndarray
        The pile arrays of :func:`sweep_arrays` (SWEEP_PILE) [N], [1/kg], [N/m], [N s/m].
    soil_sweep : tuple of numpy.ndarray
        The soil arrays of :func:`sweep_arrays` (SWEEP_SOIL) [N], [N/m], [s/m], [N s/m], [m].
    first_soil : int
        Index of the first mass with a shaft soil spring [-] (:func:`sweep_arrays`).
    u : numpy.ndarray
        (N,) displacements [m], positive down; updated in place.
    v : numpy.ndarray
        (N,) velocities [m/s], positive down; updated in place.
    soil_offset : numpy.ndarray
        (N + 1,) plastic offsets of the soil springs [m]; updated in place.
    energy : numpy.ndarray
        (ENERGY_SIZE,) energy state [J]; the head works are added to it.
    head_force : float
        Force on the pile head, held over the step [N], compression positive.
    h : float
        Communication step [s].
    n_sub : int
        Number of equal sub-steps [-] (h / n_sub within :func:`stable_time_step`).
    soil_works : tuple of numpy.ndarray or None, optional
        None, or the (N,) per-mass sums of the soil's static and damping work (SWEEP_WORKS)
        to add to [J].
    damping_work : numpy.ndarray or None, optional
        None, or the (N,) per-mass sums of the pile dashpots' work to add to [J].
    """
    dt = h / n_sub
    for _ in range(n_sub):
        v0 = v[0]
        v1 = v[1]
        _pile_sweep(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, head_force, dt,
                    soil_works, damping_work)
        du_top = 0.5 * dt * (v0 + v[0])
        du_next = 0.5 * dt * (v1 + v[1])
        energy[WORK_HEAD] += head_force * du_top
        energy[WORK_HEAD_SHORTENING] += head_force * (du_top - du_next)


@njit(cache=True, inline='always')
def _pile_sweep(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, head_force, dt,
                soil_works, damping_work):
    """One leapfrog sub-step of dt [s] (module docstring), top to toe, in place."""
    weight, inverse_mass, k, c = pile_sweep
    capacity, tension, soil_k, smith, dashpot, yield_down, yield_up = soil_sweep
    n = u.size
    last = n - 1
    free_end = min(first_soil, last)
    spring_above = head_force  # compression force acting on the top of mass i
    dash_above = 0.0
    # the free length: no soil, nothing carried from segment to segment but the spring force
    for i in range(free_end):
        e = u[i] - u[i + 1]
        spring_below = k[i] * e
        dash_below = c[i] * (v[i] - v[i + 1])
        force = weight[i] + spring_above + dash_above - spring_below - dash_below
        v_new = v[i] + dt * force * inverse_mass[i]
        if damping_work is not None:
            du = 0.5 * dt * (v[i] + v_new)
            damping_work[i] += (dash_below - dash_above) * du
        v[i] = v_new
        u[i] += dt * v_new
        spring_above = spring_below
        dash_above = dash_below
    # the embedded length (unsigned indices: no negative-index handling in the loop)
    one = np.uint64(1)
    for i in range(np.uint64(free_end), np.uint64(last)):
        e = u[i] - u[i + one]
        spring_below = k[i] * e
        dash_below = c[i] * (v[i] - v[i + one])
        rs = 0.0
        rd = 0.0
        if soil_k[i] > 0.0:
            rs, rd, soil_offset[i] = _soil_spring(u[i], v[i], soil_offset[i], capacity[i],
                                                  tension[i], soil_k[i], smith[i], dashpot[i],
                                                  yield_down[i], yield_up[i])
        force = weight[i] + spring_above + dash_above - spring_below - dash_below - rs - rd
        v_new = v[i] + dt * force * inverse_mass[i]
        if soil_works is not None:
            du = 0.5 * dt * (v[i] + v_new)
            soil_works[0][i] += rs * du
            soil_works[1][i] += rd * du
        if damping_work is not None:
            du = 0.5 * dt * (v[i] + v_new)
            damping_work[i] += (dash_below - dash_above) * du
        v[i] = v_new
        u[i] += dt * v_new
        spring_above = spring_below
        dash_above = dash_below
    # the toe mass: its shaft spring and the toe spring
    rs = 0.0
    rd = 0.0
    if soil_k[last] > 0.0:
        rs, rd, soil_offset[last] = _soil_spring(
            u[last], v[last], soil_offset[last], capacity[last], tension[last], soil_k[last],
            smith[last], dashpot[last], yield_down[last], yield_up[last])
    if soil_k[n] > 0.0:
        ts, td, soil_offset[n] = _soil_spring(
            u[last], v[last], soil_offset[n], capacity[n], tension[n], soil_k[n], smith[n],
            dashpot[n], yield_down[n], yield_up[n])
        rs += ts
        rd += td
    force = weight[last] + spring_above + dash_above - 0.0 - 0.0 - rs - rd
    v_new = v[last] + dt * force * inverse_mass[last]
    if soil_works is not None:
        du = 0.5 * dt * (v[last] + v_new)
        soil_works[0][last] += rs * du
        soil_works[1][last] += rd * du
    if damping_work is not None:
        du = 0.5 * dt * (v[last] + v_new)
        damping_work[last] += (0.0 - dash_above) * du
    v[last] = v_new
    u[last] += dt * v_new


@njit(cache=True)
def gravity_work(weight, u, v, u_start, v_start, dt):
    """Work done by gravity on the pile since the state (u_start, v_start) [J].

    With sub-steps of a constant dt the leapfrog's centred increments du = dt (v_old +
    v_new) / 2 sum to u - u_start + dt (v_start - v) / 2 for every mass, so the work
    sum m g du needs no running total.

    Parameters
    ----------
    weight : numpy.ndarray
        (N,) weight m g of each mass [N].
    u : numpy.ndarray
        (N,) displacements now [m].
    v : numpy.ndarray
        (N,) velocities now [m/s] (of the last sub-step).
    u_start : numpy.ndarray
        (N,) displacements at the start [m].
    v_start : numpy.ndarray
        (N,) velocities at the start [m/s].
    dt : float
        The constant sub-step [s].

    Returns
    -------
    float
        The gravity work [J].
    """
    work = 0.0
    for i in range(u.size):
        work += weight[i] * ((u[i] - u_start[i]) + 0.5 * dt * (v_start[i] - v[i]))
    return work


ENERGY_SUMS = {"reassoc"}
"""The fastmath flags of the energy bookkeeping's sums (:func:`pile_energies`,
:func:`anvilwave.hammer.ram.leapfrog_energies`,
:func:`anvilwave.anvil_rom.unit.modal_unit_energy_at`): only
reassociation, so that the compiler may add the terms in any order (and vectorise the sums);
that changes their last bits and nothing else (tests/test_engine_loop.py checks them against
exactly rounded sums). The time stepping itself is compiled without fastmath."""


@njit(cache=True, fastmath=ENERGY_SUMS)
def pile_energies(mass, stiffness, weight, u, v, dt, u_start, v_start, soil_works):
    """The pile's energies at a record point in one pass [J].

    Kinetic and strain energy as :func:`update_energy`, the gravity work as
    :func:`gravity_work`, the soil works the totals of the per-mass sums of :func:`pile_advance`.

    Parameters
    ----------
    mass : numpy.ndarray
        (N,) segment masses [kg].
    stiffness : numpy.ndarray
        (N,) spring below each mass [N/m] (0 below the toe mass).
    weight : numpy.ndarray
        (N,) weight m g of each mass [N].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities of the last sub-step [m/s].
    dt : float
        The sub-step [s].
    u_start : numpy.ndarray
        (N,) displacements at the start of the gravity work [m].
    v_start : numpy.ndarray
        (N,) velocities at the start of the gravity work [m/s].
    soil_works : tuple of numpy.ndarray
        The (N,) per-mass soil work sums (SWEEP_WORKS order) [J].

    Returns
    -------
    kinetic : float
        Kinetic energy sum m v^2 / 2 [J].
    strain : float
        Strain energy in the leapfrog form sum k e e' / 2 [J].
    gravity : float
        Gravity work since (u_start, v_start) [J].
    soil_static : float
        Work done on the soil by its static resistance [J].
    soil_damping : float
        Work done on the soil by its damping resistance [J].
    """
    n = u.size
    kinetic = 0.0
    strain = 0.0
    gravity = 0.0
    soil_static = 0.0
    soil_damping = 0.0
    static_work, damping_work = soil_works
    for i in range(n - 1):
        kinetic += 0.5 * mass[i] * v[i] * v[i]
        e = u[i] - u[i + 1]
        strain += 0.5 * stiffness[i] * e * (e - dt * (v[i] - v[i + 1]))
        gravity += weight[i] * ((u[i] - u_start[i]) + 0.5 * dt * (v_start[i] - v[i]))
        soil_static += static_work[i]
        soil_damping += damping_work[i]
    i = n - 1
    kinetic += 0.5 * mass[i] * v[i] * v[i]
    gravity += weight[i] * ((u[i] - u_start[i]) + 0.5 * dt * (v_start[i] - v[i]))
    soil_static += static_work[i]
    soil_damping += damping_work[i]
    return kinetic, strain, gravity, soil_static, soil_damping


@njit(cache=True)
def sum_works(works):
    """Totals of per-mass work sums [J] (the three arrays of :func:`pile_step`).

    Parameters
    ----------
    works : tuple of numpy.ndarray
        Three (N,) arrays of per-mass work sums [J]: pile damping, soil static, soil damping.

    Returns
    -------
    damping : float
        Total work of the pile dashpots [J].
    soil_static : float
        Total work done on the soil by its static resistance [J].
    soil_damping : float
        Total work done on the soil by its damping resistance [J].
    """
    a = 0.0
    b = 0.0
    c = 0.0
    for i in range(works[0].size):
        a += works[0][i]
        b += works[1][i]
        c += works[2][i]
    return a, b, c


@njit(cache=True)
def pile_step(pile, soil, u, v, soil_offset, energy, head_force, gravity, h, n_sub):
    """Advance the pile and soil over a communication step.

    A convenience form of :func:`pile_advance` that prepares its arrays on every call and keeps
    every entry of ``energy`` up to date. u, v, soil_offset and energy are updated in place (see
    the module docstring).

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters [N], [N/m], [s/m], [N s/m].
    u : numpy.ndarray
        (N,) displacements [m], positive down.
    v : numpy.ndarray
        (N,) velocities [m/s], positive down.
    soil_offset : numpy.ndarray
        (N + 1,) plastic offsets of the soil springs [m].
    energy : numpy.ndarray
        (ENERGY_SIZE,) energy state [J].
    head_force : float
        Force on the pile head, held over the step [N], compression positive (pushes the head
        down).
    gravity : float
        Gravitational acceleration applied to the pile masses [m/s^2] (0 switches it off).
    h : float
        Communication step [s].
    n_sub : int
        Number of equal sub-steps [-]; h / n_sub must not exceed :func:`stable_time_step`
        (:func:`anvilwave.pile.model.substeps` chooses it).
    """
    n = u.size
    mass = pile[PILE_MASS]
    pile_sweep = (mass * gravity, 1.0 / mass, pile[PILE_STIFFNESS], pile[PILE_DASHPOT])
    k = soil[SOIL_STIFFNESS]
    yield_down = np.zeros(n + 1)
    yield_up = np.zeros(n + 1)
    first_soil = n - 1
    for i in range(n + 1):
        if k[i] > 0.0:
            yield_down[i] = soil[SOIL_CAPACITY, i] / k[i]
            yield_up[i] = soil[SOIL_TENSION, i] / k[i]
            if i < first_soil:
                first_soil = i
    soil_sweep = (soil[SOIL_CAPACITY], soil[SOIL_TENSION], k, soil[SOIL_SMITH],
                  soil[SOIL_DASHPOT], yield_down, yield_up)
    works = (np.zeros(n), np.zeros(n), np.zeros(n))
    u_start = u.copy()
    v_start = v.copy()
    pile_advance(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, energy, head_force, h,
                 n_sub, (works[1], works[2]), works[0])
    dt = h / n_sub
    damping, soil_static, soil_damping = sum_works(works)
    energy[WORK_GRAVITY] += gravity_work(pile_sweep[0], u, v, u_start, v_start, dt)
    energy[WORK_SOIL_STATIC] += soil_static
    energy[WORK_SOIL_DAMPING] += soil_damping
    energy[WORK_PILE_DAMPING] += damping
    update_energy(pile, u, v, energy, dt)


@njit(cache=True)
def update_energy(pile, u, v, energy, dt):
    """Set energy[ENERGY_KINETIC] = sum m v^2 / 2 and energy[ENERGY_STRAIN] = sum k e e' / 2 [J].

    e = u_i - u_{i+1} now and e' the same a sub-step dt earlier (u - dt v), the form that
    makes the discrete energy balance exact (module docstring). With v = 0 it is sum k e^2 / 2.

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities of the last sub-step [m/s].
    energy : numpy.ndarray
        (ENERGY_SIZE,) energy state [J]; its kinetic and strain entries are set in place.
    dt : float
        The sub-step [s].
    """
    n = u.size
    mass = pile[PILE_MASS]
    k = pile[PILE_STIFFNESS]
    kinetic = 0.0
    strain = 0.0
    for i in range(n):
        kinetic += 0.5 * mass[i] * v[i] * v[i]
        if i < n - 1:
            e = u[i] - u[i + 1]
            strain += 0.5 * k[i] * e * (e - dt * (v[i] - v[i + 1]))
    energy[ENERGY_KINETIC] = kinetic
    energy[ENERGY_STRAIN] = strain


@njit(cache=True)
def energy_residual(energy, energy_initial):
    """Discrete energy balance residual [J] (0 up to round-off; module docstring).

    (KE + U) - (KE + U)_0 - (W_head + W_gravity - W_soil_static - W_soil_damping - W_pile_damping),
    the works counted from the initial state ``energy_initial``.

    Parameters
    ----------
    energy : numpy.ndarray
        (ENERGY_SIZE,) energy state now [J].
    energy_initial : numpy.ndarray
        (ENERGY_SIZE,) energy state at the start [J].

    Returns
    -------
    float
        The residual [J].
    """
    stored = energy[ENERGY_KINETIC] + energy[ENERGY_STRAIN]
    stored0 = energy_initial[ENERGY_KINETIC] + energy_initial[ENERGY_STRAIN]
    supplied = (energy[WORK_HEAD] - energy_initial[WORK_HEAD]
                + energy[WORK_GRAVITY] - energy_initial[WORK_GRAVITY]
                - (energy[WORK_SOIL_STATIC] - energy_initial[WORK_SOIL_STATIC])
                - (energy[WORK_SOIL_DAMPING] - energy_initial[WORK_SOIL_DAMPING])
                - (energy[WORK_PILE_DAMPING] - energy_initial[WORK_PILE_DAMPING]))
    return stored - stored0 - supplied


@njit(cache=True, inline='always')
def head_face_work(probes, energy):
    """Work done by the head force on the pile-top face [J] (:func:`head_displacement`).

    A contact that uses the face displacement exchanges this work with the pile; it differs
    from energy[WORK_HEAD] (force x top-mass displacement, the one in the pile's exact balance)
    by e x energy[WORK_HEAD_SHORTENING]. That difference is the price of the face
    extrapolation: it acts like a small interface dashpot (the strain of the first spring lags
    the head force by about dx / 2c); for a 10 t ram on a spring (closed-form case 2) it takes
    3.1 %, 0.86 % and 0.22 % of the transferred energy at dx = 1, 0.5 and 0.25 m (~dx^2).

    Parameters
    ----------
    probes : numpy.ndarray
        (PROBE_SIZE,) output probes; HEAD_EXTRAPOLATION is the factor e [-].
    energy : numpy.ndarray
        (ENERGY_SIZE,) energy state [J].

    Returns
    -------
    float
        The work on the head face [J].
    """
    return energy[WORK_HEAD] + probes[HEAD_EXTRAPOLATION] * energy[WORK_HEAD_SHORTENING]


@njit(cache=True)
def stable_time_step(pile, soil):
    """Largest stable sub-step of :func:`pile_step` [s] (a safe estimate).

    Per mass i, omega_i^2 bounds the largest eigenvalue of M^-1 K (Gershgorin on
    M^-1/2 K M^-1/2, soil springs included) and beta_i = C / 2M likewise for the dashpots
    (pile material, soil viscous, Smith J R_u). The leapfrog with lagged damping is stable for
    omega dt <= 2 (sqrt(1 + zeta^2) - zeta), i.e. dt <= 2 / (sqrt(omega^2 + beta^2) + beta);
    the minimum over the masses is returned. For an undamped uniform pile without soil this is
    exactly the Courant limit dx / c.

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters [N], [N/m], [s/m], [N s/m].

    Returns
    -------
    float
        The stable sub-step [s] (inf when nothing restrains the masses).
    """
    mass = pile[PILE_MASS]
    k = pile[PILE_STIFFNESS]
    c = pile[PILE_DASHPOT]
    n = mass.size
    dt_min = np.inf
    for i in range(n):
        k_diag = soil[SOIL_STIFFNESS, i]
        c_diag = soil[SOIL_DASHPOT, i] + soil[SOIL_SMITH, i] * soil[SOIL_CAPACITY, i]
        if i == n - 1:
            k_diag += soil[SOIL_STIFFNESS, n]
            c_diag += soil[SOIL_DASHPOT, n] + soil[SOIL_SMITH, n] * soil[SOIL_CAPACITY, n]
        omega2 = 0.0
        beta = 0.0
        for j in (i - 1, i):
            if 0 <= j < n - 1:
                coupling = 1.0 / math.sqrt(mass[j] * mass[j + 1])
                omega2 += k[j] / mass[i] + k[j] * coupling
                beta += 0.5 * (c[j] / mass[i] + c[j] * coupling)
        omega2 += k_diag / mass[i]
        beta += 0.5 * c_diag / mass[i]
        dt = 2.0 / (math.sqrt(omega2 + beta * beta) + beta) if omega2 + beta > 0.0 else np.inf
        dt_min = min(dt_min, dt)
    return dt_min


# ---------------------------------------------------------------------------- outputs
@njit(cache=True)
def head_displacement(probes, u):
    """Displacement of the pile-top face [m], positive down.

    The top mass sits dx_0 / 2 below the head face; the face moves by the top mass plus the
    shortening of that half-segment, taken from the strain of the first spring:
    u_head = u_0 + e (u_0 - u_1), e = k_0 dx_0 / (2 E_0 A_0) (1/2 for a uniform top).
    Contacts that use this face displacement converge at second order in dx; using u_0 (the
    top mass) makes the contact a half-segment too deep, a first-order error (the pile head
    then looks stiffer by dx / (2 E A)). A state function: no feedthrough of the head force.

    Parameters
    ----------
    probes : numpy.ndarray
        (PROBE_SIZE,) output probes; HEAD_EXTRAPOLATION is the factor e [-].
    u : numpy.ndarray
        (N,) displacements [m].

    Returns
    -------
    float
        The head-face displacement [m].
    """
    return u[0] + probes[HEAD_EXTRAPOLATION] * (u[0] - u[1])


@njit(cache=True, inline='always')
def head_velocity(probes, v):
    """Velocity of the pile-top face [m/s], positive down (as :func:`head_displacement`).

    Parameters
    ----------
    probes : numpy.ndarray
        (PROBE_SIZE,) output probes; HEAD_EXTRAPOLATION is the factor e [-].
    v : numpy.ndarray
        (N,) velocities [m/s].

    Returns
    -------
    float
        The head-face velocity [m/s].
    """
    return v[0] + probes[HEAD_EXTRAPOLATION] * (v[0] - v[1])


@njit(cache=True, inline='always')
def spring_force(pile, u, v, j):
    """Axial force in spring j (between masses j and j+1) incl. material damping [N], compr. +.

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities [m/s].
    j : int
        Spring index [-], 0 <= j < N - 1.

    Returns
    -------
    float
        The spring force [N], compression positive.
    """
    return (pile[PILE_STIFFNESS, j] * (u[j] - u[j + 1])
            + pile[PILE_DASHPOT, j] * (v[j] - v[j + 1]))


@njit(cache=True)
def top_force(pile, u, v):
    """Axial force in the first spring, dx_0 / 2 + dx_1 / 2 below the head [N], compr. +.

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities [m/s].

    Returns
    -------
    float
        The force [N], compression positive.
    """
    return spring_force(pile, u, v, 0)


@njit(cache=True, inline='always')
def gauge_force(pile, probes, u, v):
    """Axial force at the gauge depth [N], compression positive.

    Linear interpolation between the springs around the gauge (weights in ``probes``); the
    velocity used by the damping part is v at t - dt/2 (leapfrog).

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters [kg], [N/m], [N s/m].
    probes : numpy.ndarray
        (PROBE_SIZE,) output probes: GAUGE_SPRING index and GAUGE_SPRING_WEIGHT [-].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities [m/s].

    Returns
    -------
    float
        The gauge force [N], compression positive.
    """
    j = int(probes[GAUGE_SPRING])
    w = probes[GAUGE_SPRING_WEIGHT]
    force = spring_force(pile, u, v, j)
    if w > 0.0:
        force = (1.0 - w) * force + w * spring_force(pile, u, v, j + 1)
    return force


@njit(cache=True, inline='always')
def gauge_velocity(probes, v):
    """Pile velocity at the gauge depth [m/s], linear between the mass centres around it.

    Parameters
    ----------
    probes : numpy.ndarray
        (PROBE_SIZE,) output probes: GAUGE_MASS index and GAUGE_MASS_WEIGHT [-].
    v : numpy.ndarray
        (N,) velocities [m/s].

    Returns
    -------
    float
        The gauge velocity [m/s], positive down.
    """
    i = int(probes[GAUGE_MASS])
    w = probes[GAUGE_MASS_WEIGHT]
    if w > 0.0:
        return (1.0 - w) * v[i] + w * v[i + 1]
    return v[i]


@njit(cache=True)
def toe_displacement(u):
    """Toe (last mass) displacement [m], positive down.

    Parameters
    ----------
    u : numpy.ndarray
        (N,) displacements [m].

    Returns
    -------
    float
        The toe displacement [m].
    """
    return u[u.size - 1]


@njit(cache=True)
def toe_velocity(v):
    """Toe (last mass) velocity [m/s], positive down.

    Parameters
    ----------
    v : numpy.ndarray
        (N,) velocities [m/s].

    Returns
    -------
    float
        The toe velocity [m/s].
    """
    return v[v.size - 1]


@njit(cache=True)
def toe_resistance(soil, u, v, soil_offset):
    """Toe soil resistance at the present state [N], static and total.

    Parameters
    ----------
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters [N], [N/m], [s/m], [N s/m]; column N is the toe.
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities [m/s].
    soil_offset : numpy.ndarray
        (N + 1,) plastic offsets of the soil springs [m] (not changed).

    Returns
    -------
    static : float
        Static toe resistance R_s [N].
    total : float
        Total toe resistance R_s + R_d [N].
    """
    n = u.size
    rs, rd, _ = soil_resistance(
        u[n - 1], v[n - 1], soil_offset[n], soil[SOIL_CAPACITY, n], soil[SOIL_TENSION, n],
        soil[SOIL_STIFFNESS, n], soil[SOIL_SMITH, n], soil[SOIL_DASHPOT, n])
    return rs, rs + rd


@njit(cache=True)
def soil_forces(soil, u, v, soil_offset, static_out, total_out):
    """Resistance of every soil spring at the present state [N] into (N+1,) arrays (toe last).

    Parameters
    ----------
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters [N], [N/m], [s/m], [N s/m].
    u : numpy.ndarray
        (N,) displacements [m].
    v : numpy.ndarray
        (N,) velocities [m/s].
    soil_offset : numpy.ndarray
        (N + 1,) plastic offsets of the soil springs [m] (not changed).
    static_out : numpy.ndarray
        (N + 1,) array that receives the static resistances R_s [N].
    total_out : numpy.ndarray
        (N + 1,) array that receives the total resistances R_s + R_d [N].
    """
    n = u.size
    for i in range(n + 1):
        m = min(i, n - 1)
        rs, rd, _ = soil_resistance(
            u[m], v[m], soil_offset[i], soil[SOIL_CAPACITY, i], soil[SOIL_TENSION, i],
            soil[SOIL_STIFFNESS, i], soil[SOIL_SMITH, i], soil[SOIL_DASHPOT, i])
        static_out[i] = rs
        total_out[i] = rs + rd


@njit(cache=True, inline='always')
def fold_elongations(u, largest, smallest):
    """Fold the shortening u_i - u_i+1 of every spring into per-spring extremes [m], in place.

    With the positive stress factors of :func:`update_stress_extremes` the extreme
    stresses are then stress_factor * largest and * smallest, exactly (rounding is
    monotonic). One short pass the compiler vectorises.

    Parameters
    ----------
    u : numpy.ndarray
        (N,) displacements [m].
    largest : numpy.ndarray
        (N - 1,) largest shortening of each spring so far [m]; updated in place.
    smallest : numpy.ndarray
        (N - 1,) smallest shortening (largest elongation, negative) so far [m]; updated in place.
    """
    for i in range(largest.size):
        e = u[i] - u[i + 1]
        if e > largest[i]:
            largest[i] = e
        if e < smallest[i]:
            smallest[i] = e


@njit(cache=True)
def update_stress_extremes(stress_factor, u, extremes):
    """Fold the axial stresses of the pile's springs into running extremes (in place).

    Stress = k (u_i - u_i+1) / A, compression positive.

    Parameters
    ----------
    stress_factor : numpy.ndarray
        (N - 1,) spring stiffness / steel area of each spring [N/m^3].
    u : numpy.ndarray
        (N,) displacements [m].
    extremes : numpy.ndarray
        [largest compression, largest tension (negative)] stress so far [Pa]; updated in place.
    """
    for i in range(u.size - 1):
        stress = stress_factor[i] * (u[i] - u[i + 1])
        if stress > extremes[0]:
            extremes[0] = stress
        if stress < extremes[1]:
            extremes[1] = stress
