"""The in-process system engine: ram -> anvil unit -> pile/soil in one compiled loop per blow.

The step order is the master algorithm of DESIGN.md, the same as the FMI master's:

1. read the ram toe (u, v) and the pile head (u, v) at t_n (states, no feedthrough);
2. the anvil unit turns them into the two contact forces at t_n (feedthrough);
3. the forces are held over [t_n, t_n+1] while ram, anvil unit and pile/soil each advance.

Time is t_n = t0 + n h, never accumulated, with t0 = -h/2: the ram starts half a step before
the first contact (t = 0), see :meth:`Engine.blow`. The kernels are those of the physics
packages (the FMUs run the same ones): :func:`anvilwave.hammer.ram.ram_advance`,
:func:`anvilwave.anvil_rom.unit.modal_unit_advance` (or the classic driving system, or no anvil) and
:func:`anvilwave.pile.kernels.pile_advance`.

Speed (benchmarks/bench_engine.py): everything that does not change during a run is prepared
once per engine (inverse masses, weights, yield displacements, the anvil's step coefficients
and its state at rest, the pile's static state, the coupled stability limit), so a blow only
copies its start state and runs the loop. The loop is compiled per anvil model and per choice
of recording and energy bookkeeping (the unused branches are removed at compile time, nothing
is dispatched inside it) with the units' kernels inlined; every unit is one sweep over its
degrees of freedom per step, each unit's part of the step one inlined helper, and the loop runs
without numba's reference counting (:func:`_blow`). It records the time series every
``record_every`` steps and the energies at most every ENERGY_STEPS steps; between those rows
only the soil's works are summed (per mass), the gravity work follows from the states and the
pile dashpots' work from the pile's exact energy balance. With ``record=False`` it keeps only
the blow's summary (stress extremes, EMX, peak head force, toe displacement, set), computed
inside the loop, so thousands of blows take no memory. The time stepping is compiled without
fastmath; only the sums of the energy bookkeeping may be reassociated
(:data:`anvilwave.pile.kernels.ENERGY_SUMS`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np
from numba import njit

from anvilwave.anvil_rom.arrays import aligned_copy, aligned_zeros
from anvilwave.anvil_rom.contact import contact_force
from anvilwave.anvil_rom.fem.pipeline import solid_mass
from anvilwave.anvil_rom.rings import (
    RamFace,
    RingState,
    copy_ring_state,
    ring_contact,
    ring_elastic_forces,
    ring_faces,
    ring_interface,
    ring_unit_advance,
    ring_unit_energy_at,
)
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.stack import (
    FRICTION_SWEEPS,
    StackState,
    stack_energy,
    stack_forces,
    stack_interface,
    stack_step,
)
from anvilwave.anvil_rom.unit import (
    AnvilUnit,
    ContactParameters,
    modal_unit_advance,
    modal_unit_contact,
    modal_unit_dashpot_power,
    modal_unit_energy_at,
    modal_unit_interface,
)
from anvilwave.config.cache import cached_chain
from anvilwave.config.system import SystemConfig
from anvilwave.engine.anvils import (
    anvil_modal_data,
    contact_stiffnesses,
    stack_unit,
    tube_head,
)
from anvilwave.engine.compilation import announce_compilation
from anvilwave.hammer.driving_system import (
    driving_system_energy,
    driving_system_forces,
    driving_system_losses,
    driving_system_stable_time_step,
    driving_system_step,
    interface_time_step,
)
from anvilwave.hammer.modal_ram import (
    ModalRamUnit,
    modal_ram_advance,
    modal_ram_chain,
    modal_ram_energies,
)
from anvilwave.hammer.ram import leapfrog_energies, ram_advance
from anvilwave.hammer.ram import stable_time_step as ram_stable_time_step
from anvilwave.inputs import InputError
from anvilwave.pile.kernels import (
    HEAD_EXTRAPOLATION,
    PILE_STIFFNESS,
    SOIL_STIFFNESS,
    WORK_GRAVITY,
    WORK_HEAD,
    WORK_PILE_DAMPING,
    WORK_SOIL_DAMPING,
    WORK_SOIL_STATIC,
    fold_elongations,
    gauge_force,
    gauge_velocity,
    head_displacement,
    head_face_work,
    head_velocity,
    pile_advance,
    pile_energies,
    sweep_arrays,
    update_energy,
)
from anvilwave.pile.kernels import stable_time_step as pile_stable_time_step
from anvilwave.pile.model import initial_state, substeps

COLUMNS = (
    "time [s]",
    "ram_anvil_force [N]",
    "anvil_pile_force [N]",
    "pile_head_velocity [m/s]",
    "gauge_force [N]",
    "gauge_velocity [m/s]",
    "ram_toe_velocity [m/s]",
    "anvil_top_displacement [m]",
    "anvil_bottom_displacement [m]",
    "pile_head_displacement [m]",
    "pile_toe_displacement [m]",
)
ENERGY_COLUMNS = (
    "ram_kinetic [J]", "ram_strain [J]", "ram_gravity_potential [J]",
    "anvil_kinetic [J]", "anvil_potential [J]",
    "pile_kinetic [J]", "pile_strain [J]", "pile_gravity_work [J]",
    "soil_static_work [J]", "soil_damping_work [J]", "pile_damping_work [J]",
    "pile_head_work [J]", "pile_head_face_work [J]", "contact_damping_work [J]",
)
STEPS_PER_PERIOD_AT_FMAX = 8
"""The automatic step samples the ROM's highest frequency fmax at least this often: the contact
forces are exchanged once per step, so the anvil's modes up to fmax must be resolved by the
exchange (Table 1, fmax 5 kHz: peak forces change by < 1 % from h = 1 / (8 fmax) = 25 us down to
2.5 us, while h = 80 us, near the stability limit, misplaces a re-impact by 35 %)."""
ACCURACY_FRACTION = 0.4
"""The automatic step is at most this fraction of the stability limit 2 / omega_max, i.e. the
highest frequency of the coupled system is sampled about 8 times per period (pi / 0.4). The
impact starts with a jump in velocity that excites the top of the spectrum: the lumped-anvil
ram force of Table 1 is within 2 % of its h -> 0 value at 0.4 of the limit but 10 % low at
0.84. Chains of equal segments meeting at the Courant number 1 are exact; give that step
explicitly (simulation.time_step) for such validation cases."""

ENERGY_STEPS = 20
"""The energy series of a blow is recorded at most every this many master steps by default
(:meth:`Engine.blow`): a row of it (a pass over every unit's states) costs about what a step
costs, and the balance needs no finer sampling: each row is exact, and the works between the
rows are summed at every step (Table 1: a row every 0.5 ms, 51 rows)."""

NO_MODAL_RAM = (np.zeros((9, 0)), np.zeros(0), np.zeros(3))
"""The modal ram arrays (C, S, toe) of :class:`LoopRam` when the ram is a chain (a unit
without modes)."""

# the blow summary the loop fills (BlowResult fields of the same names)
(S_MAX_COMPRESSION, S_MAX_TENSION, S_EMX_GAUGE, S_EMX_HEAD, S_MAX_HEAD_FORCE, S_MAX_TOE,
 S_TOE_START, S_TOE_END, S_TOE_VELOCITY_END) = range(9)
SUMMARY_SIZE = 9


def coupled_stable_time_step(ram_mass, ram_stiffness, k_ram, k_pile, pile_arrays,
                             participation_ram=None, participation_pile=None) -> float:
    """Largest stable master step [s] of the whole coupled chain, 2 / omega_max.

    Every unit is a leapfrog (the modal anvil its exact central-difference counterpart) and
    the contact forces are exchanged at t_n, so the system is one central-difference scheme:
    stable for h < 2 / omega_max of the linearised system ram chain + contact springs + anvil +
    pile chain with its soil springs. The anvil's modes enter as free unit masses coupled
    through their participations: their own stiffness needs no limit (they are integrated
    exactly) and their step mobility c_j <= h^2 makes this bound conservative. Without
    participations the contact is one spring from the ram toe to the pile head (no anvil).

    omega_max^2 is the largest eigenvalue of M^-1/2 K M^-1/2, found by bisection with a
    definiteness test (:func:`_below_spectrum`) that follows the matrix's structure: two chains
    (three diagonals) joined through the anvil's dense block of modes. Each test costs about
    one elimination of that block, so an engine gets its limit in milliseconds, without a
    dense eigenvalue solver (nor its threads).

    Parameters
    ----------
    ram_mass : array_like
        The ram chain's masses, shape (N_r,) [kg].
    ram_stiffness : array_like
        The ram chain's springs, shape (N_r - 1,) [N/m].
    k_ram : float
        Ram contact spring [N/m] (without an anvil: the two contacts in series).
    k_pile : float
        Pile contact spring [N/m].
    pile_arrays : PileSoilArrays
        The pile's and soil's parameter arrays (``PileSoil.arrays()``).
    participation_ram : array_like, optional
        The anvil's participations at the ram face, shape (n,) [kg^-1/2]; None: no anvil.
    participation_pile : array_like, optional
        The anvil's participations at the pile ring, shape (n,) [kg^-1/2].

    Returns
    -------
    float
        2 / omega_max [s].
    """
    ram_mass = np.asarray(ram_mass, float)
    ram_stiffness = np.asarray(ram_stiffness, float)
    pile_mass = np.asarray(pile_arrays.pile[0], float)
    k_chain = np.asarray(pile_arrays.pile[PILE_STIFFNESS][:-1], float)
    soil_k = pile_arrays.soil[SOIL_STIFFNESS]
    n_r, n_p = len(ram_mass), len(pile_mass)
    n_a = 0 if participation_ram is None else len(participation_ram)
    # the stiffness matrix by blocks: ram chain, anvil modes, pile chain
    ram_diagonal = np.zeros(n_r)
    ram_diagonal[:-1] += ram_stiffness
    ram_diagonal[1:] += ram_stiffness
    ram_diagonal[-1] += k_ram
    pile_diagonal = np.zeros(n_p)
    pile_diagonal[:-1] += k_chain
    pile_diagonal[1:] += k_chain
    pile_diagonal += soil_k[:n_p]
    pile_diagonal[-1] += soil_k[n_p]
    if n_a:
        top = np.asarray(participation_ram, float)
        bottom = np.asarray(participation_pile, float)
        # ram contact k (u_toe - top . q)^2 / 2, pile contact k (bottom . q - u_head)^2 / 2
        block = k_ram * np.outer(top, top) + k_pile * np.outer(bottom, bottom)
        to_toe = -k_ram * top
        to_head = -k_pile * bottom
        toe_head = 0.0
        pile_diagonal[0] += k_pile
    else:
        block = np.zeros((0, 0))
        to_toe = to_head = np.zeros(0)
        toe_head = -k_ram
        pile_diagonal[0] += k_ram
    # scaled by M^-1/2 (the modes have unit mass)
    r = 1.0 / np.sqrt(ram_mass)
    p = 1.0 / np.sqrt(pile_mass)
    arrays = (ram_diagonal * r * r, -ram_stiffness * r[:-1] * r[1:],
              np.ascontiguousarray(block), to_toe * r[-1], to_head * p[0],
              toe_head * r[-1] * p[0],
              pile_diagonal * p * p, -k_chain * p[:-1] * p[1:])
    return float(2.0 / math.sqrt(_largest_eigenvalue(*arrays)))


def modal_ram_coupled_stable_time_step(participation_toe, k_ram, k_pile, pile_arrays,
                                       participation_ram, participation_pile) -> float:
    """:func:`coupled_stable_time_step` with a modal ram unit [s].

    The ram's modes, like the anvil's, enter as free unit masses coupled through their toe
    participations (each is integrated exactly; the bound is conservative). One dense symmetric
    eigenvalue problem of the ram's and the anvil's modes and the pile chain (a few hundred to
    a few thousand rows).

    Parameters
    ----------
    participation_toe : array_like
        The ram's modes at its toe, shape (n_r,) [kg^-1/2].
    k_ram : float
        Ram contact spring [N/m].
    k_pile : float
        Pile contact spring [N/m].
    pile_arrays : PileSoilArrays
        The pile's and soil's parameter arrays (``PileSoil.arrays()``).
    participation_ram : array_like
        The anvil's participations at the ram face, shape (n,) [kg^-1/2].
    participation_pile : array_like
        The anvil's participations at the pile ring, shape (n,) [kg^-1/2].

    Returns
    -------
    float
        2 / omega_max [s].
    """
    from scipy.linalg import eigvalsh

    pile_mass = np.asarray(pile_arrays.pile[0], float)
    k_chain = np.asarray(pile_arrays.pile[PILE_STIFFNESS][:-1], float)
    soil_k = pile_arrays.soil[SOIL_STIFFNESS]
    toe = np.asarray(participation_toe, float)
    top = np.asarray(participation_ram, float)
    bottom = np.asarray(participation_pile, float)
    n_r, n_a, n_p = toe.size, top.size, pile_mass.size
    # ram contact k (toe . q_r - top . q_a)^2 / 2, pile contact k (bottom . q_a - u_head)^2 / 2
    ram_side = np.concatenate((toe, -top, np.zeros(n_p)))
    pile_side = np.concatenate((np.zeros(n_r), bottom, np.zeros(n_p)))
    pile_side[n_r + n_a] = -1.0 / math.sqrt(pile_mass[0])
    a = k_ram * np.outer(ram_side, ram_side) + k_pile * np.outer(pile_side, pile_side)
    r = 1.0 / np.sqrt(pile_mass)
    diagonal = np.zeros(n_p)
    diagonal[:-1] += k_chain
    diagonal[1:] += k_chain
    diagonal += soil_k[:n_p]
    diagonal[-1] += soil_k[n_p]
    j = np.arange(n_r + n_a, n_r + n_a + n_p)
    a[j, j] += diagonal * r * r
    a[j[:-1], j[1:]] -= k_chain * r[:-1] * r[1:]
    a[j[1:], j[:-1]] -= k_chain * r[:-1] * r[1:]
    n = a.shape[0]
    largest = float(eigvalsh(a, subset_by_index=[n - 1, n - 1])[0])
    return 2.0 / math.sqrt(largest)


@njit(cache=True)
def _below_spectrum(sigma, ram_diagonal, ram_off, block, to_toe, to_head, toe_head,
                    pile_diagonal, pile_off, work):
    """True if sigma exceeds every eigenvalue, i.e. A - sigma I is negative definite: its
    symmetric elimination (ram chain, the toe's couplings into the block of modes and the head,
    the block, the head and the pile chain) meets only negative pivots. ``work`` is scratch of
    the block's shape plus one column."""
    d = _chain_pivot(ram_diagonal, ram_off, sigma, ram_diagonal[0] - sigma)
    if d >= 0.0:
        return False
    # eliminate the toe: the block of modes, its column to the head and the head's pivot
    n = block.shape[0]
    for i in range(n):
        for j in range(n):
            work[i, j] = block[i, j] - to_toe[i] * to_toe[j] / d
        work[i, i] -= sigma
        work[i, n] = to_head[i] - to_toe[i] * toe_head / d
    head = (pile_diagonal[0] - sigma) - toe_head * toe_head / d
    for k in range(n):
        pivot = work[k, k]
        if pivot >= 0.0:
            return False
        for i in range(k + 1, n):
            factor = work[i, k] / pivot
            for j in range(k + 1, n + 1):
                work[i, j] -= factor * work[k, j]
        head -= work[k, n] * work[k, n] / pivot
    return _chain_pivot(pile_diagonal, pile_off, sigma, head) < 0.0


@njit(cache=True, inline='always')
def _chain_pivot(diagonal, off, sigma, first):
    """The last pivot of the symmetric elimination of a chain (tridiagonal: ``diagonal``,
    ``off``) shifted by sigma, from its first pivot ``first``, or the first pivot >= 0 met
    (then A - sigma I is not negative definite)."""
    d = first
    if d >= 0.0:
        return d
    for i in range(1, diagonal.size):
        d = (diagonal[i] - sigma) - off[i - 1] ** 2 / d
        if d >= 0.0:
            return d
    return d


@njit(cache=True)
def _largest_eigenvalue(ram_diagonal, ram_off, block, to_toe, to_head, toe_head,
                        pile_diagonal, pile_off):
    """Largest eigenvalue of the coupled matrix (:func:`_below_spectrum`) by bisection between
    0 and a Gershgorin bound, to the last bits; returns the upper end of the final bracket."""
    upper = 0.0
    for i in range(ram_diagonal.size):
        row = ram_diagonal[i]
        if i > 0:
            row += abs(ram_off[i - 1])
        if i < ram_off.size:
            row += abs(ram_off[i])
        upper = max(upper, row)
    upper = max(upper, ram_diagonal[-1] + abs(ram_off[-1]) if ram_off.size else 0.0)
    toe_row = abs(toe_head)
    for i in range(block.shape[0]):
        row = abs(to_toe[i]) + abs(to_head[i])
        toe_row += abs(to_toe[i])
        for j in range(block.shape[0]):
            row += abs(block[i, j])
        upper = max(upper, row)
    upper = max(upper, ram_diagonal[-1] + toe_row + (abs(ram_off[-1]) if ram_off.size else 0.0))
    head_row = abs(toe_head)
    for i in range(to_head.size):
        head_row += abs(to_head[i])
    for i in range(pile_diagonal.size):
        row = pile_diagonal[i]
        if i > 0:
            row += abs(pile_off[i - 1])
        if i < pile_off.size:
            row += abs(pile_off[i])
        if i == 0:
            row += head_row
        upper = max(upper, row)
    upper *= 1.0 + 1e-12
    lower = 0.0
    work = np.empty((block.shape[0], block.shape[0] + 1))
    for _ in range(200):
        middle = 0.5 * (lower + upper)
        if middle <= lower or middle >= upper:
            break
        if _below_spectrum(middle, ram_diagonal, ram_off, block, to_toe, to_head, toe_head,
                           pile_diagonal, pile_off, work):
            upper = middle
        else:
            lower = middle
    return upper


# ----------------------------------------------------------------- the loop's state
class LoopRam(NamedTuple):
    """The ram as the loop steps it: its chain or the modal ram unit.

    The chain is :func:`anvilwave.hammer.ram.ram_advance`'s; when ``modal_coefficients`` has
    columns the modal ram unit runs instead (:func:`anvilwave.hammer.modal_ram.modal_ram_advance`;
    the chain's arrays are then unused). Both rams run in the one compiled loop, chosen at run
    time, so that a ram model does not change how the compiler lays out the rest of the step.

    Parameters
    ----------
    weight : numpy.ndarray
        The chain's weights m g, shape (N,) [N].
    inverse_mass : numpy.ndarray
        1 / m, shape (N,) [1/kg].
    stiffness : numpy.ndarray
        The chain's springs, shape (N - 1,) [N/m].
    mass : numpy.ndarray
        The chain's masses, shape (N,) [kg].
    u : numpy.ndarray
        Displacements, shape (N,) [m] (written).
    v : numpy.ndarray
        Half-step velocities, shape (N,) [m/s] (written).
    n_sub : int
        The chain's sub-steps per master step [-].
    modal_coefficients : numpy.ndarray
        C of a :class:`anvilwave.hammer.modal_ram.ModalRamUnit` (no columns: the chain runs).
    modal_state : numpy.ndarray
        Its S (written).
    modal_toe : numpy.ndarray
        Its toe (u, v, half), shape (3,) [m, m/s, -] (written).
    """

    weight: np.ndarray
    inverse_mass: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray
    u: np.ndarray
    v: np.ndarray
    n_sub: int
    modal_coefficients: np.ndarray
    modal_state: np.ndarray
    modal_toe: np.ndarray


class LoopModalAnvil(NamedTuple):
    """The modal (ROM or lumped) anvil unit's kernel arrays (:mod:`anvilwave.anvil_rom.unit`).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m,
        N s/m, m/N, m/N, m/N, m/s^2, s].
    coefficients : numpy.ndarray
        ``C``: the modes' step coefficients and participations, shape (n, 8).
    state : numpy.ndarray
        ``S``: q at t_n and t_n-1, shape (2 n,) [m kg^1/2] (written).
    interface : numpy.ndarray
        The state's modal u_top, v_top, u_bottom, v_bottom, shape (4,) [m, m/s] (written).
    """

    parameters: np.ndarray
    coefficients: np.ndarray
    state: np.ndarray
    interface: np.ndarray


class LoopClassic(NamedTuple):
    """The classic driving system's kernel arrays (:mod:`anvilwave.hammer.driving_system`).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: the driving system's parameters
        (:meth:`anvilwave.hammer.driving_system.DrivingSystem.parameters`).
    state : numpy.ndarray
        ``S``: its state (written).
    n_sub : int
        Its sub-steps per master step [-].
    """

    parameters: np.ndarray
    state: np.ndarray
    n_sub: int


class LoopAnvil(NamedTuple):
    """The anvil unit: one of ``modal`` (with ``rings`` or not), ``classic``, ``direct``, ``stack``.

    The others are None, and the compiler keeps only the code of the given one.

    Parameters
    ----------
    modal : LoopModalAnvil or None
        The modal (ROM or lumped) anvil unit.
    rings : RingState or None
        The modal unit's pile port in rings (:class:`anvilwave.anvil_rom.rings.RingState`).
    classic : LoopClassic or None
        The classic driving system.
    direct : numpy.ndarray or None
        No anvil: the contact [k, c] [N/m, N s/m] of ram toe and pile head.
    stack : StackState or None, default None
        The driving stack, anvil and anvil ring (:class:`anvilwave.anvil_rom.stack.StackState`,
        ``[[anvil.bodies]]``).
    """

    modal: LoopModalAnvil | None
    rings: RingState | None
    classic: LoopClassic | None
    direct: np.ndarray | None
    stack: StackState | None = None


class LoopPile(NamedTuple):
    """The pile and soil as :func:`anvilwave.pile.kernels.pile_advance` takes them.

    With the blow's start and the stress extremes folded at every step.

    Parameters
    ----------
    parameters : numpy.ndarray
        The pile's parameter array (``PileSoil.arrays().pile``).
    probes : numpy.ndarray
        Its probe array (gauges, head extrapolation).
    pile_sweep : tuple
        The pile's sweep arrays (:func:`anvilwave.pile.kernels.sweep_arrays`).
    soil_sweep : tuple
        The soil's sweep arrays (:func:`anvilwave.pile.kernels.sweep_arrays`).
    first_soil : int
        The first mass with soil (:func:`anvilwave.pile.kernels.sweep_arrays`) [-].
    u : numpy.ndarray
        Displacements, shape (N,) [m] (written).
    v : numpy.ndarray
        Velocities, shape (N,) [m/s] (written).
    soil_offset : numpy.ndarray
        Plastic offsets of the soil springs, shape (N + 1,) [m] (written).
    energy : numpy.ndarray
        Energies and works, shape (ENERGY_SIZE,) [J] (written).
    n_sub : int
        The pile's sub-steps per master step [-].
    start_u : numpy.ndarray
        u at the start of the blow, shape (N,) [m].
    start_v : numpy.ndarray
        v at the start of the blow, shape (N,) [m/s].
    start_energy : numpy.ndarray
        energy at the start of the blow, shape (ENERGY_SIZE,) [J].
    face0 : float
        The head face displacement the anvil unit's pile input is measured from [m].
    stress_factor : numpy.ndarray
        The springs' stress factors, shape (N - 1,) [N/m^3].
    largest : numpy.ndarray
        The largest shortening of each spring, shape (N - 1,) [m] (written,
        :func:`anvilwave.pile.kernels.fold_elongations`).
    smallest : numpy.ndarray
        The smallest shortening of each spring, shape (N - 1,) [m] (written).
    """

    parameters: np.ndarray
    probes: np.ndarray
    pile_sweep: tuple
    soil_sweep: tuple
    first_soil: int
    u: np.ndarray
    v: np.ndarray
    soil_offset: np.ndarray
    energy: np.ndarray
    n_sub: int
    start_u: np.ndarray
    start_v: np.ndarray
    start_energy: np.ndarray
    face0: float
    stress_factor: np.ndarray
    largest: np.ndarray
    smallest: np.ndarray


class LoopSettings(NamedTuple):
    """The blow's time grid and recording.

    Parameters
    ----------
    gravity : float
        Gravitational acceleration [m/s^2].
    t0 : float
        The time of step 0 [s].
    h : float
        The master step [s].
    n_steps : int
        Number of master steps of the blow [-].
    record_every : int
        Steps between the rows of ``out`` (and of the sections) [-].
    energy_every : int
        Steps between the rows of ``energies`` (the last step is always one) [-].
    """

    gravity: float
    t0: float
    h: float
    n_steps: int
    record_every: int
    energy_every: int


class LoopRecords(NamedTuple):
    """What the loop writes besides the states.

    The energy bookkeeping is None when not kept: its code is removed from the compiled loop
    (it runs in the pile's inner loop). The time series and the sections are always arrays,
    empty when not kept, so that one compiled loop serves a blow recorded or not (each None
    would be a variant of its own, compiled separately: about half a minute each on an empty
    numba cache).

    Parameters
    ----------
    out : numpy.ndarray
        The time series, shape (len(COLUMNS), rows) (written); no rows: not kept.
    energies : numpy.ndarray or None
        The energy series, shape (1 + len(ENERGY_COLUMNS), rows) (written).
    works : tuple or None
        The per-mass soil work sums of :func:`anvilwave.pile.kernels.pile_advance` [J] (None:
        no energy bookkeeping).
    sections : tuple
        (spring indices, buffer (n_sections, rows)): the elongation u_i - u_i+1 [m] of chosen
        pile springs at every record row, whether ``out`` is recorded or not; no indices: none
        kept.
    summary : numpy.ndarray
        The blow's summary (S_* entries), shape (SUMMARY_SIZE,) (written).
    """

    out: np.ndarray
    energies: np.ndarray | None
    works: tuple | None
    sections: tuple
    summary: np.ndarray


# ----------------------------------------------------------------- the loop
@njit(cache=True)
def run_blow(ram, anvil, pile, settings, records):
    """Advance one blow of ``settings.n_steps`` master steps, the states in place.

    The steps are ``settings.h`` [s] from ``settings.t0`` [s]. Records every ``record_every``
    steps into ``records.out`` unless it has no rows and every ``energy_every`` steps and at
    the last into ``records.energies`` unless it is None; ``records.summary`` receives the
    blow's summary.

    The optional parts (the anvil's variants and the energy bookkeeping) are handed on as
    arguments of their own (:func:`_blow`): the compiler removes the code of those that are
    None only when they are arguments, not fields.

    Parameters
    ----------
    ram : LoopRam
        The ram (states written).
    anvil : LoopAnvil
        The anvil unit (states written).
    pile : LoopPile
        The pile and soil (states written).
    settings : LoopSettings
        The time grid and recording.
    records : LoopRecords
        What the loop writes besides the states.

    Returns
    -------
    row : int
        Number of rows recorded into ``records.out`` (and the sections) [-].
    energy_row : int
        Number of rows recorded into ``records.energies`` [-].
    """
    return _blow(ram, anvil.modal, anvil.rings, anvil.classic, anvil.direct, anvil.stack, pile,
                 settings, records.out, records.energies, records.works, records.sections,
                 records.summary)


@njit(cache=True, _nrt=False)
def _blow(ram, modal, rings, classic, direct, stack, pile_bundle, settings, out, energies,
          works, sections, summary):
    """:func:`run_blow` with the optional parts as arguments: the master algorithm (module
    docstring), each unit's part of a step one helper inlined into the loop (numba's IR-level
    ``inline='always'``): the ram's (:func:`_ram_toe`, :func:`_ram_step`), the anvil unit's
    (:func:`_anvil_contact`, :func:`_anvil_step`), the pile's (:func:`_pile_head`,
    :func:`_pile_step`) and the records' (:func:`_summary_at`, :func:`_record_row`, the energy
    rows). The bundles' fields are read into locals once, before the loop.

    The loop is compiled without numba's reference counting (``_nrt=False``): it allocates
    nothing, and every array it touches is held by the caller for the whole blow. Counted, each
    array handed to an inlined helper is increfed and decrefed at every step (an atomic update
    and an opaque call that LLVM must keep values in memory across): about 90 such calls per
    step in the one-body loop, 140 with the helpers, which made the Table 1 blow 10-15 % slower
    (benchmarks/bench_revisions.py); without the counting the loop has none. The functions it
    calls that numba compiles with it (an empty cache) inherit the setting, so none of them
    may allocate either: their work arrays are the units' (e.g. the ring unit's scratch), made
    before the blow (tests/test_cold_compile.py checks that nothing the loop reaches
    allocates; a clean clone compiles it on an empty cache)."""
    weight, inverse_mass, ram_stiffness, ram_mass = (ram.weight, ram.inverse_mass,
                                                     ram.stiffness, ram.mass)
    ram_u, ram_v, ram_nsub = ram.u, ram.v, ram.n_sub
    ram_C, ram_S, ram_toe = ram.modal_coefficients, ram.modal_state, ram.modal_toe
    pile, probes, pile_sweep, soil_sweep, first_soil = (pile_bundle.parameters,
                                                        pile_bundle.probes,
                                                        pile_bundle.pile_sweep,
                                                        pile_bundle.soil_sweep,
                                                        pile_bundle.first_soil)
    pu, pv, poff, pen, pile_nsub = (pile_bundle.u, pile_bundle.v, pile_bundle.soil_offset,
                                    pile_bundle.energy, pile_bundle.n_sub)
    start_u, start_v, start_energy = (pile_bundle.start_u, pile_bundle.start_v,
                                      pile_bundle.start_energy)
    face0 = pile_bundle.face0
    factor, largest, smallest = (pile_bundle.stress_factor, pile_bundle.largest,
                                 pile_bundle.smallest)
    gravity, t0, h, n_steps, record_every, energy_every = settings
    toe = ram_u.shape[0] - 1
    ram_is_modal = ram_C.shape[1] > 0
    last = pu.shape[0] - 1
    extrapolation = probes[HEAD_EXTRAPOLATION]
    dt_ram = h / ram_nsub
    dt_pile = h / pile_nsub
    head_work0 = head_face_work(probes, start_energy)
    pile_mass = pile[0]
    stored0 = 0.0
    if works is not None:  # the pile's kinetic and strain energy at the start
        kinetic, strain, _, _, _ = pile_energies(pile_mass, pile_sweep[2], pile_sweep[0], pu,
                                                 pv, dt_pile, pu, pv, works)
        stored0 = kinetic + strain
    work_contact = 0.0  # dissipated by the contact dashpots since the blow started
    damped = False
    if modal is not None:
        damped = modal.parameters[1] != 0.0 or modal.parameters[3] != 0.0
    if direct is not None:
        damped = direct[1] != 0.0
    if stack is not None:
        for i in range(stack.ratios.shape[0]):
            if stack.ratios[i] != 0.0:
                damped = True
    power_before = 0.0
    work_gauge = 0.0
    emx_gauge = 0.0
    emx_head = 0.0
    max_head_force = 0.0
    max_toe = pu[last]
    row = 0
    countdown = 0
    energy_row = 0
    energy_countdown = 0
    for n in range(n_steps + 1):
        # 1. states of the neighbours at t_n
        u_ram, v_ram = _ram_toe(ram_is_modal, ram_toe, ram_u, ram_v, toe)
        u_pile, v_pile = _pile_head(probes, pu, pv, extrapolation, face0)
        # 2. contact forces at t_n (feedthrough of the anvil unit)
        f_ram, f_pile, fe_ram, fe_pile, u_top, u_bottom, dissipated = _anvil_contact(
            modal, rings, classic, direct, stack, damped, h, u_ram, v_ram, u_pile, v_pile)
        if damped:
            work_contact += dissipated
        # the blow's summary at t_n
        (f_gauge, v_gauge, power_before, work_gauge, emx_gauge, emx_head, max_head_force,
         max_toe) = _summary_at(pile, probes, pu, pv, pen, last, n, h, f_pile, head_work0,
                                power_before, work_gauge, emx_gauge, emx_head, max_head_force,
                                max_toe)
        if countdown == 0:
            countdown = record_every
            row += 1
            _record_sections(sections[0], sections[1], pu, row - 1)
            if out.shape[1] > 0:
                u_top, u_bottom = _anvil_faces(modal, rings, stack, f_ram, f_pile, u_top,
                                               u_bottom)
                _record_row(out, row - 1, t0 + n * h, f_ram, f_pile, v_pile, f_gauge, v_gauge,
                            v_ram, u_top, u_bottom, u_pile + face0, pu[last])
        if energies is not None:
            if energy_countdown == 0 or n == n_steps:
                energy_countdown = energy_every
                kin, pot = _anvil_energies(modal, rings, classic, direct, stack, damped, u_ram,
                                           v_ram, u_pile, v_pile, fe_ram, fe_pile)
                ke, se, pe = _ram_energies(ram_is_modal, ram_C, ram_S, ram_toe, ram_mass,
                                           ram_stiffness, ram_u, ram_v, gravity, h, dt_ram)
                kinetic, strain, grav, soil_static, soil_damping, damping = _pile_works(
                    pile_mass, pile_sweep, pu, pv, pen, dt_pile, start_u, start_v,
                    start_energy, works, stored0)
                _record_energies(energies, energy_row, t0 + n * h, ke, se, pe, kin, pot,
                                 kinetic, strain, grav, soil_static, soil_damping, damping,
                                 pen[WORK_HEAD], head_face_work(probes, pen), work_contact)
                energy_row += 1
            energy_countdown -= 1
        countdown -= 1
        if n == n_steps:
            break
        # 3. every unit over [t_n, t_n+1] with the forces held
        _ram_step(ram_is_modal, ram_C, ram_S, ram_toe, weight, inverse_mass, ram_stiffness,
                  ram_u, ram_v, f_ram, h, ram_nsub)
        _anvil_step(modal, rings, classic, stack, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile,
                    h)
        _pile_step(pile_sweep, soil_sweep, first_soil, pu, pv, poff, pen, largest, smallest,
                   f_pile, h, pile_nsub, works)
    # the end state: its stresses, energies and works
    _blow_summary(summary, pile, pile_mass, pile_sweep, pu, pv, pen, dt_pile, factor, largest,
                  smallest, start_u, start_v, start_energy, works, stored0, emx_gauge,
                  emx_head, max_head_force, max_toe)
    return row, energy_row


# the step's parts, each inlined into _blow: the same operations in the same order as one
# loop body (bit-identical blows), every argument an array or a scalar the loop holds
@njit(cache=True, inline='always')
def _ram_toe(ram_is_modal, modal_toe, u, v, toe):
    """The ram's toe at t_n: the modal ram unit's or the chain's last mass.

    Parameters
    ----------
    ram_is_modal : bool
        The modal ram unit runs (else the chain).
    modal_toe : numpy.ndarray
        The modal unit's toe (u, v, half), shape (3,) [m, m/s, -].
    u : numpy.ndarray
        The chain's displacements, shape (N,) [m].
    v : numpy.ndarray
        The chain's half-step velocities, shape (N,) [m/s].
    toe : int
        The chain's toe mass, N - 1 [-].

    Returns
    -------
    u_ram : float
        Toe displacement [m].
    v_ram : float
        Toe velocity [m/s].
    """
    if ram_is_modal:
        return modal_toe[0], modal_toe[1]
    return u[toe], v[toe]


@njit(cache=True, inline='always')
def _ram_step(ram_is_modal, modal_coefficients, modal_state, modal_toe, weight, inverse_mass,
              stiffness, u, v, f_ram, h, n_sub):
    """The ram over [t_n, t_n+1] with its toe force held, states in place.

    :func:`anvilwave.hammer.modal_ram.modal_ram_advance` (the modal unit) or
    :func:`anvilwave.hammer.ram.ram_advance` (the chain, sub-stepped).

    Parameters
    ----------
    ram_is_modal : bool
        The modal ram unit runs (else the chain).
    modal_coefficients : numpy.ndarray
        The modal unit's C.
    modal_state : numpy.ndarray
        Its S (written).
    modal_toe : numpy.ndarray
        Its toe (u, v, half), shape (3,) [m, m/s, -] (written).
    weight : numpy.ndarray
        The chain's weights m g, shape (N,) [N].
    inverse_mass : numpy.ndarray
        1 / m, shape (N,) [1/kg].
    stiffness : numpy.ndarray
        The chain's springs, shape (N - 1,) [N/m].
    u : numpy.ndarray
        Displacements, shape (N,) [m] (written).
    v : numpy.ndarray
        Half-step velocities, shape (N,) [m/s] (written).
    f_ram : float
        The ram contact force on the toe [N].
    h : float
        The master step [s].
    n_sub : int
        The chain's sub-steps [-].
    """
    if ram_is_modal:
        modal_ram_advance(modal_coefficients, modal_state, f_ram, h, modal_toe)
    else:
        ram_advance(weight, inverse_mass, stiffness, u, v, f_ram, h, n_sub)


@njit(cache=True, inline='always')
def _ram_energies(ram_is_modal, modal_coefficients, modal_state, modal_toe, mass, stiffness,
                  u, v, gravity, h, dt):
    """The ram's energies at t_n (the modal unit's or the chain's).

    Parameters
    ----------
    ram_is_modal : bool
        The modal ram unit runs (else the chain).
    modal_coefficients : numpy.ndarray
        The modal unit's C.
    modal_state : numpy.ndarray
        Its S.
    modal_toe : numpy.ndarray
        Its toe (u, v, half), shape (3,) [m, m/s, -].
    mass : numpy.ndarray
        The chain's masses, shape (N,) [kg].
    stiffness : numpy.ndarray
        The chain's springs, shape (N - 1,) [N/m].
    u : numpy.ndarray
        Displacements, shape (N,) [m].
    v : numpy.ndarray
        Half-step velocities, shape (N,) [m/s].
    gravity : float
        Gravitational acceleration [m/s^2].
    h : float
        The master step [s].
    dt : float
        The chain's sub-step [s].

    Returns
    -------
    kinetic : float
        [J].
    strain : float
        [J].
    gravity_potential : float
        [J].
    """
    if ram_is_modal:
        return modal_ram_energies(modal_coefficients, modal_state, modal_toe, gravity, h)
    return leapfrog_energies(mass, stiffness, u, v, gravity, dt)


@njit(cache=True, inline='always')
def _pile_head(probes, u, v, extrapolation, face0):
    """The pile head at t_n as the anvil unit reads it.

    Parameters
    ----------
    probes : numpy.ndarray
        The pile's probe array.
    u : numpy.ndarray
        The pile's displacements, shape (N,) [m].
    v : numpy.ndarray
        Its velocities, shape (N,) [m/s].
    extrapolation : float
        The head's extrapolation factor from the first two masses [-].
    face0 : float
        The head face displacement the anvil's pile input is measured from [m].

    Returns
    -------
    u_pile : float
        Head face displacement from ``face0`` [m].
    v_pile : float
        Head velocity [m/s].
    """
    return u[0] + extrapolation * (u[0] - u[1]) - face0, head_velocity(probes, v)


@njit(cache=True, inline='always')
def _pile_step(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, energy, largest,
               smallest, f_pile, h, n_sub, works):
    """The pile and its soil over [t_n, t_n+1] with the head force held, states in place.

    The springs' shortenings at t_n are folded into their extremes first
    (:func:`anvilwave.pile.kernels.fold_elongations`), then
    :func:`anvilwave.pile.kernels.pile_advance` sub-steps.

    Parameters
    ----------
    pile_sweep : tuple
        The pile's sweep arrays (:func:`anvilwave.pile.kernels.sweep_arrays`).
    soil_sweep : tuple
        The soil's sweep arrays.
    first_soil : int
        The first mass with soil [-].
    u : numpy.ndarray
        Displacements, shape (N,) [m] (written).
    v : numpy.ndarray
        Velocities, shape (N,) [m/s] (written).
    soil_offset : numpy.ndarray
        Plastic offsets, shape (N + 1,) [m] (written).
    energy : numpy.ndarray
        Energies and works, shape (ENERGY_SIZE,) [J] (written).
    largest : numpy.ndarray
        Largest shortening of each spring, shape (N - 1,) [m] (written).
    smallest : numpy.ndarray
        Smallest shortening of each spring, shape (N - 1,) [m] (written).
    f_pile : float
        The head force [N].
    h : float
        The master step [s].
    n_sub : int
        The pile's sub-steps [-].
    works : tuple or None
        The per-mass soil work sums [J] (None: not summed).
    """
    fold_elongations(u, largest, smallest)
    pile_advance(pile_sweep, soil_sweep, first_soil, u, v, soil_offset, energy, f_pile, h,
                 n_sub, works, None)


@njit(cache=True, inline='always')
def _pile_works(mass, pile_sweep, u, v, energy, dt, start_u, start_v, start_energy, works,
                stored0):
    """The pile's energies at t_n and its works since the blow's start, added to the start's.

    Parameters
    ----------
    mass : numpy.ndarray
        The pile's masses, shape (N,) [kg].
    pile_sweep : tuple
        The pile's sweep arrays (:func:`anvilwave.pile.kernels.sweep_arrays`).
    u : numpy.ndarray
        Displacements, shape (N,) [m].
    v : numpy.ndarray
        Velocities, shape (N,) [m/s].
    energy : numpy.ndarray
        Energies and works, shape (ENERGY_SIZE,) [J].
    dt : float
        The pile's sub-step [s].
    start_u : numpy.ndarray
        u at the start of the blow, shape (N,) [m].
    start_v : numpy.ndarray
        v at the start of the blow, shape (N,) [m/s].
    start_energy : numpy.ndarray
        Energies and works at the start, shape (ENERGY_SIZE,) [J].
    works : tuple
        The per-mass soil work sums [J].
    stored0 : float
        The pile's kinetic and strain energy at the start [J].

    Returns
    -------
    kinetic : float
        [J].
    strain : float
        [J].
    gravity_work : float
        [J].
    soil_static_work : float
        [J].
    soil_damping_work : float
        [J].
    pile_damping_work : float
        [J] (:func:`_pile_damping_work`).
    """
    kinetic, strain, grav, soil_static, soil_damping = pile_energies(
        mass, pile_sweep[2], pile_sweep[0], u, v, dt, start_u, start_v, works)
    damping = _pile_damping_work(energy[WORK_HEAD] - start_energy[WORK_HEAD], grav,
                                 soil_static, soil_damping, kinetic + strain - stored0)
    return (kinetic, strain, start_energy[WORK_GRAVITY] + grav,
            start_energy[WORK_SOIL_STATIC] + soil_static,
            start_energy[WORK_SOIL_DAMPING] + soil_damping,
            start_energy[WORK_PILE_DAMPING] + damping)


@njit(cache=True, inline='always')
def _anvil_contact(modal, rings, classic, direct, stack, damped, h, u_ram, v_ram, u_pile,
                   v_pile):
    """The anvil unit's feedthrough at t_n: the two contact forces from the neighbours' states.

    One of ``modal`` (with ``rings`` or not), ``classic``, ``direct`` and ``stack`` is given,
    the others None; the compiler keeps the code of the given one.

    Parameters
    ----------
    modal : LoopModalAnvil or None
        The modal anvil unit.
    rings : RingState or None
        Its pile port in rings.
    classic : LoopClassic or None
        The classic driving system.
    direct : numpy.ndarray or None
        No anvil: the contact [k, c] [N/m, N s/m].
    stack : StackState or None
        The driving stack (:func:`anvilwave.anvil_rom.stack.stack_forces`).
    damped : bool
        A contact has a dashpot.
    h : float
        The master step [s].
    u_ram : float
        Ram toe displacement [m].
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].

    Returns
    -------
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    fe_ram : float
        Its elastic part, without the dashpot [N].
    fe_pile : float
        [N].
    u_top : float
        The classic driving system's top [m] (else ``u_pile``; :func:`_anvil_faces`).
    u_bottom : float
        Its helmet [m] (else ``u_pile``).
    dissipated : float
        The dashpots' work over the step, h times their power [J] (0 undamped).
    """
    f_ram = 0.0
    f_pile = 0.0
    u_top = u_pile
    u_bottom = u_pile
    fe_ram = 0.0
    fe_pile = 0.0
    dissipated = 0.0
    if modal is not None and rings is None:
        f_ram, f_pile = modal_unit_contact(modal.parameters, modal.interface, u_ram, v_ram,
                                           u_pile, v_pile)
        fe_ram = f_ram
        fe_pile = f_pile
        if damped:
            fe_ram, fe_pile, power = modal_unit_dashpot_power(
                modal.parameters, modal.interface, u_ram, v_ram, u_pile, v_pile, f_ram, f_pile)
            dissipated = h * power
    if modal is not None and rings is not None:
        f_ram, f_pile = ring_contact(rings, u_ram, v_ram, u_pile, v_pile)
        fe_ram = f_ram
        fe_pile = f_pile
        if damped:
            fe_ram, fe_pile, power = ring_elastic_forces(rings, u_ram, v_ram, u_pile, v_pile)
            dissipated = h * power
    if classic is not None:
        f_ram, f_pile, u_top, u_bottom = driving_system_forces(
            classic.parameters, classic.state, u_ram, v_ram, u_pile, v_pile)
    if direct is not None:
        f_ram = contact_force(u_ram - u_pile, v_ram - v_pile, direct[0], direct[1])
        f_pile = f_ram
        fe_ram = f_ram
        if damped:
            fe_ram = contact_force(u_ram - u_pile, 0.0, direct[0], 0.0)
            dissipated = h * (f_ram - fe_ram) * (v_ram - v_pile)
    if stack is not None:  # its own elastic forces in stack_energy; the dashpots' power kept
        f_ram, f_pile = stack_forces(stack, u_ram, v_ram, u_pile, v_pile)
        fe_ram = f_ram
        fe_pile = f_pile
        dissipated = h * stack.energies[3]
    return f_ram, f_pile, fe_ram, fe_pile, u_top, u_bottom, dissipated


@njit(cache=True, inline='always')
def _anvil_faces(modal, rings, stack, f_ram, f_pile, u_top, u_bottom):
    """The anvil's top and bottom faces at t_n for the records.

    Parameters
    ----------
    modal : LoopModalAnvil or None
        The modal anvil unit (its faces with the static correction).
    rings : RingState or None
        Its pile port in rings (:func:`anvilwave.anvil_rom.rings.ring_faces`).
    stack : StackState or None
        The driving stack (:func:`anvilwave.anvil_rom.stack.stack_interface`).
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    u_top : float
        The faces of the other units (:func:`_anvil_contact`) [m].
    u_bottom : float
        [m].

    Returns
    -------
    u_top : float
        Top face displacement [m].
    u_bottom : float
        Bottom face displacement [m].
    """
    if modal is not None and rings is None:
        P = modal.parameters
        u_top = modal.interface[0] + P[4] * f_ram - P[5] * f_pile
        u_bottom = modal.interface[2] + P[5] * f_ram - P[6] * f_pile
    if modal is not None and rings is not None:
        u_top, u_bottom = ring_faces(rings)
    if stack is not None:
        u_top, _, u_bottom, _ = stack_interface(stack)
    return u_top, u_bottom


@njit(cache=True, inline='always')
def _anvil_step(modal, rings, classic, stack, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h):
    """The anvil unit over [t_n, t_n+1] with the contact forces held, states in place.

    Parameters
    ----------
    modal : LoopModalAnvil or None
        The modal anvil unit.
    rings : RingState or None
        Its pile port in rings.
    classic : LoopClassic or None
        The classic driving system (it steps on the neighbours' states).
    stack : StackState or None
        The driving stack (:func:`anvilwave.anvil_rom.stack.stack_step`, the forces of its
        :func:`anvilwave.anvil_rom.stack.stack_forces` at t_n held).
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    u_ram : float
        Ram toe displacement [m].
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    h : float
        The master step [s].
    """
    if modal is not None and rings is None:
        modal_unit_advance(modal.parameters, modal.coefficients, modal.state, f_ram, f_pile,
                           modal.interface)
    if modal is not None and rings is not None:
        ring_unit_advance(modal.parameters, modal.coefficients, modal.state, f_ram, rings,
                          modal.interface)
    if classic is not None:
        driving_system_step(classic.parameters, classic.state, u_ram, v_ram, u_pile, v_pile, h,
                            classic.n_sub)
    if stack is not None:
        stack_step(stack, FRICTION_SWEEPS)


@njit(cache=True, inline='always')
def _anvil_energies(modal, rings, classic, direct, stack, damped, u_ram, v_ram, u_pile, v_pile,
                    fe_ram, fe_pile):
    """The anvil unit's energies at t_n, the contacts' stored energy in its potential.

    Parameters
    ----------
    modal : LoopModalAnvil or None
        The modal anvil unit.
    rings : RingState or None
        Its pile port in rings (the tube head's share in the potential).
    classic : LoopClassic or None
        The classic driving system (its cushions' restitution losses in the potential: energy
        the system no longer holds).
    direct : numpy.ndarray or None
        No anvil: the contact [k, c] [N/m, N s/m].
    stack : StackState or None
        The driving stack (:func:`anvilwave.anvil_rom.stack.stack_energy`; the energy its seat
        friction dissipated in the potential, energy the stack no longer holds, as the classic
        cushions' losses).
    damped : bool
        A contact has a dashpot.
    u_ram : float
        Ram toe displacement [m].
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    fe_ram : float
        The ram contact's elastic force [N].
    fe_pile : float
        The pile contact's elastic force [N].

    Returns
    -------
    kinetic : float
        [J].
    potential : float
        [J].
    """
    kin = 0.0
    pot = 0.0
    if modal is not None and rings is None:
        kin, pot = modal_unit_energy_at(modal.parameters, modal.coefficients, modal.state,
                                        modal.interface, u_ram, v_ram, u_pile, v_pile, fe_ram,
                                        fe_pile)
    if modal is not None and rings is not None:
        if not damped:  # the elastic forces are the forces (element by element: the loop
            for i in range(rings.forces.size):  # runs without reference counting)
                rings.elastic_forces[i] = rings.forces[i]
        kin, pot = ring_unit_energy_at(modal.parameters, modal.coefficients, modal.state, rings,
                                       u_ram, v_ram, u_pile, v_pile)
        pot += rings.head_count[1]  # handed to the tube head (0 on the 1D head)
    if classic is not None:
        kin, recoverable, potential = driving_system_energy(
            classic.parameters, classic.state, u_ram, u_pile)
        pot = recoverable + potential + driving_system_losses(classic.parameters,
                                                              classic.state)
    if direct is not None:
        pot = 0.5 * fe_ram * fe_ram / direct[0]
    if stack is not None:
        kin, pot = stack_energy(stack, u_ram, v_ram, u_pile, v_pile)
        pot += stack.energies[0]
    return kin, pot


@njit(cache=True, inline='always')
def _summary_at(pile, probes, u, v, energy, last, n, h, f_pile, head_work0, power_before,
                work_gauge, emx_gauge, emx_head, max_head_force, max_toe):
    """The gauge's signals at t_n and the blow's running summary carried to t_n.

    Parameters
    ----------
    pile : numpy.ndarray
        The pile's parameter array.
    probes : numpy.ndarray
        Its probe array.
    u : numpy.ndarray
        Displacements, shape (N,) [m].
    v : numpy.ndarray
        Velocities, shape (N,) [m/s].
    energy : numpy.ndarray
        Energies and works, shape (ENERGY_SIZE,) [J].
    last : int
        The toe mass, N - 1 [-].
    n : int
        The step [-] (0: no work yet).
    h : float
        The master step [s].
    f_pile : float
        Pile contact force at t_n [N].
    head_work0 : float
        The head face's work at the blow's start [J].
    power_before : float
        Gauge force x velocity at t_n-1 [W].
    work_gauge : float
        Its trapezoidal integral to t_n-1 [J].
    emx_gauge : float
        Its largest value to t_n-1 [J].
    emx_head : float
        The head face's largest work since the start to t_n-1 [J].
    max_head_force : float
        Largest pile contact force to t_n-1 [N].
    max_toe : float
        Largest toe displacement to t_n-1 [m].

    Returns
    -------
    f_gauge : float
        Gauge force at t_n [N].
    v_gauge : float
        Gauge velocity at t_n [m/s].
    power : float
        Their product [W].
    work_gauge : float
        The gauge's work to t_n [J].
    emx_gauge : float
        [J], to t_n.
    emx_head : float
        [J], to t_n.
    max_head_force : float
        [N], to t_n.
    max_toe : float
        [m], to t_n.
    """
    f_gauge = gauge_force(pile, probes, u, v)
    v_gauge = gauge_velocity(probes, v)
    power = f_gauge * v_gauge
    if n > 0:
        work_gauge += 0.5 * (power_before + power) * h
    emx_gauge = max(emx_gauge, work_gauge)
    emx_head = max(emx_head, head_face_work(probes, energy) - head_work0)
    max_head_force = max(max_head_force, f_pile)
    max_toe = max(max_toe, u[last])
    return f_gauge, v_gauge, power, work_gauge, emx_gauge, emx_head, max_head_force, max_toe


@njit(cache=True, inline='always')
def _record_sections(idx, buf, u, row):
    """The elongations u_i - u_i+1 [m] of the chosen pile springs into a record row.

    Parameters
    ----------
    idx : numpy.ndarray
        Spring indices, shape (n_sections,) [-].
    buf : numpy.ndarray
        The buffer, shape (n_sections, rows) [m] (written).
    u : numpy.ndarray
        The pile's displacements, shape (N,) [m].
    row : int
        The row [-].
    """
    for j in range(idx.size):
        buf[j, row] = u[idx[j]] - u[idx[j] + 1]


@njit(cache=True, inline='always')
def _record_row(out, row, t, f_ram, f_pile, v_pile, f_gauge, v_gauge, v_ram, u_top, u_bottom,
                u_head, u_toe):
    """One row of the time series (COLUMNS, in order).

    Parameters
    ----------
    out : numpy.ndarray
        The time series, shape (len(COLUMNS), rows) (written).
    row : int
        The row [-].
    t : float
        Time [s].
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    v_pile : float
        Pile head velocity [m/s].
    f_gauge : float
        Gauge force [N].
    v_gauge : float
        Gauge velocity [m/s].
    v_ram : float
        Ram toe velocity [m/s].
    u_top : float
        Anvil top face displacement [m].
    u_bottom : float
        Anvil bottom face displacement [m].
    u_head : float
        Pile head displacement [m].
    u_toe : float
        Pile toe displacement [m].
    """
    out[0, row] = t
    out[1, row] = f_ram
    out[2, row] = f_pile
    out[3, row] = v_pile
    out[4, row] = f_gauge
    out[5, row] = v_gauge
    out[6, row] = v_ram
    out[7, row] = u_top
    out[8, row] = u_bottom
    out[9, row] = u_head
    out[10, row] = u_toe


@njit(cache=True, inline='always')
def _record_energies(energies, row, t, ram_kinetic, ram_strain, ram_gravity, anvil_kinetic,
                     anvil_potential, pile_kinetic, pile_strain, gravity_work, soil_static,
                     soil_damping, pile_damping, head_work, head_face, contact_damping):
    """One row of the energy series ("time [s]" and ENERGY_COLUMNS, in order).

    Parameters
    ----------
    energies : numpy.ndarray
        The energy series, shape (1 + len(ENERGY_COLUMNS), rows) (written).
    row : int
        The row [-].
    t : float
        Time [s].
    ram_kinetic : float
        [J].
    ram_strain : float
        [J].
    ram_gravity : float
        The ram's gravity potential [J].
    anvil_kinetic : float
        [J].
    anvil_potential : float
        [J].
    pile_kinetic : float
        [J].
    pile_strain : float
        [J].
    gravity_work : float
        The pile's gravity work [J].
    soil_static : float
        The soil's static work [J].
    soil_damping : float
        The soil's damping work [J].
    pile_damping : float
        The pile dashpots' work [J].
    head_work : float
        The head force's work [J].
    head_face : float
        The head face's work [J].
    contact_damping : float
        The contact dashpots' work [J].
    """
    energies[0, row] = t
    energies[1, row] = ram_kinetic
    energies[2, row] = ram_strain
    energies[3, row] = ram_gravity
    energies[4, row] = anvil_kinetic
    energies[5, row] = anvil_potential
    energies[6, row] = pile_kinetic
    energies[7, row] = pile_strain
    energies[8, row] = gravity_work
    energies[9, row] = soil_static
    energies[10, row] = soil_damping
    energies[11, row] = pile_damping
    energies[12, row] = head_work
    energies[13, row] = head_face
    energies[14, row] = contact_damping


@njit(cache=True, inline='always')
def _blow_summary(summary, pile, mass, pile_sweep, u, v, energy, dt, factor, largest, smallest,
                  start_u, start_v, start_energy, works, stored0, emx_gauge, emx_head,
                  max_head_force, max_toe):
    """The blow's end: the last shortenings folded, the stress extremes, the pile's energy and
    (with the bookkeeping) its works since the start, and the summary.

    Parameters
    ----------
    summary : numpy.ndarray
        The blow's summary (S_* entries), shape (SUMMARY_SIZE,) (written).
    pile : numpy.ndarray
        The pile's parameter array.
    mass : numpy.ndarray
        The pile's masses, shape (N,) [kg].
    pile_sweep : tuple
        The pile's sweep arrays.
    u : numpy.ndarray
        Displacements, shape (N,) [m].
    v : numpy.ndarray
        Velocities, shape (N,) [m/s].
    energy : numpy.ndarray
        Energies and works, shape (ENERGY_SIZE,) [J] (written).
    dt : float
        The pile's sub-step [s].
    factor : numpy.ndarray
        The springs' stress factors, shape (N - 1,) [N/m^3].
    largest : numpy.ndarray
        Largest shortening of each spring, shape (N - 1,) [m] (written).
    smallest : numpy.ndarray
        Smallest shortening of each spring, shape (N - 1,) [m] (written).
    start_u : numpy.ndarray
        u at the start, shape (N,) [m].
    start_v : numpy.ndarray
        v at the start, shape (N,) [m/s].
    start_energy : numpy.ndarray
        Energies and works at the start, shape (ENERGY_SIZE,) [J].
    works : tuple or None
        The per-mass soil work sums [J] (None: no bookkeeping).
    stored0 : float
        The pile's kinetic and strain energy at the start [J].
    emx_gauge : float
        [J].
    emx_head : float
        [J].
    max_head_force : float
        [N].
    max_toe : float
        [m].
    """
    last = u.shape[0] - 1
    fold_elongations(u, largest, smallest)
    compression = 0.0
    tension = 0.0
    for i in range(last):
        compression = max(compression, factor[i] * largest[i])
        tension = min(tension, factor[i] * smallest[i])
    update_energy(pile, u, v, energy, dt)
    if works is not None:
        _, _, grav, soil_static, soil_damping, damping = _pile_works(
            mass, pile_sweep, u, v, energy, dt, start_u, start_v, start_energy, works, stored0)
        energy[WORK_GRAVITY] = grav
        energy[WORK_SOIL_STATIC] = soil_static
        energy[WORK_SOIL_DAMPING] = soil_damping
        energy[WORK_PILE_DAMPING] = damping
    summary[S_MAX_COMPRESSION] = compression
    summary[S_MAX_TENSION] = tension
    summary[S_EMX_GAUGE] = emx_gauge
    summary[S_EMX_HEAD] = emx_head
    summary[S_MAX_HEAD_FORCE] = max_head_force
    summary[S_MAX_TOE] = max_toe
    summary[S_TOE_START] = start_u[last]
    summary[S_TOE_END] = u[last]
    summary[S_TOE_VELOCITY_END] = v[last]


@njit(cache=True)
def _pile_damping_work(head, gravity, soil_static, soil_damping, stored):
    """Work of the pile's material dashpots in the blow [J]: the remainder of the pile's exact
    discrete energy balance (pile.kernels module docstring), head + gravity work - soil works
    - change of kinetic and strain energy, all since the start of the blow. Booked this way
    the loop sums no work over the free length of the pile; tests/test_pile.py checks the
    balance with every work summed (pile_step)."""
    return head + gravity - soil_static - soil_damping - stored


# ----------------------------------------------------------------- results and state
@dataclass
class PileState:
    """The state of the pile and its soil between blows (the engine keeps its own copies).

    Parameters
    ----------
    u : numpy.ndarray
        Displacements, shape (N,) [m] (positive down).
    v : numpy.ndarray
        Velocities, shape (N,) [m/s] (positive down, leapfrog half-step values).
    soil_offset : numpy.ndarray
        Plastic offsets of the soil springs, shape (N + 1,) [m] (toe last).
    energy : numpy.ndarray
        Energies and works of :mod:`anvilwave.pile.kernels`, shape (ENERGY_SIZE,) [J].
    start_soil_offset : numpy.ndarray or None, default None
        Of a blow's final state: the soil offsets at the start of that blow, shape (N + 1,)
        [m].
    """

    u: np.ndarray
    v: np.ndarray
    soil_offset: np.ndarray
    energy: np.ndarray
    start_soil_offset: np.ndarray | None = field(default=None, repr=False, compare=False)

    def copy(self) -> PileState:
        """A copy of the state's arrays (without ``start_soil_offset``).

        Returns
        -------
        PileState
            The copy.
        """
        return PileState(self.u.copy(), self.v.copy(), self.soil_offset.copy(),
                         self.energy.copy())

    @property
    def toe_displacement(self) -> float:
        """Displacement of the toe mass [m]."""
        return float(self.u[-1])

    # the names of the kernel arguments
    pu = property(lambda self: self.u, doc="Alias of ``u``.")
    pv = property(lambda self: self.v, doc="Alias of ``v``.")
    poff = property(lambda self: self.soil_offset, doc="Alias of ``soil_offset``.")
    pen = property(lambda self: self.energy, doc="Alias of ``energy``.")

    _KEYS = {"pile_u": "u", "pile_v": "v", "soil_offset": "soil_offset",
             "soil_offset_start": "start_soil_offset", "energy": "energy"}

    def __getitem__(self, key: str) -> np.ndarray:
        """Mapping access with the keys of earlier versions' ``final_state`` dict."""
        value = getattr(self, self._KEYS[key])
        if value is None:
            raise KeyError(key)
        return value

    def __contains__(self, key: str) -> bool:
        return key in self._KEYS and getattr(self, self._KEYS[key]) is not None


@dataclass
class BlowResult:
    """Time series and summary of one simulated blow (columns: COLUMNS, ENERGY_COLUMNS).

    The summary is computed inside the loop at every step, recorded or not.

    Parameters
    ----------
    columns : dict of str to numpy.ndarray
        Recorded time series, keys COLUMNS (empty with ``record=False``).
    energies : dict of str to numpy.ndarray
        Recorded energy series, keys "time [s]" and ENERGY_COLUMNS (empty with
        ``record=False`` or ``energy=False``).
    time_step : float
        The master step [s].
    n_steps : int
        Number of master steps [-].
    wall_time : float
        Wall-clock time of the loop [s].
    input_energy : float
        Kinetic energy of the ram at impact [J].
    max_compression_stress : float
        Largest compressive stress over all springs and steps [Pa].
    max_tension_stress : float
        Largest tensile stress over all springs and steps [Pa] (negative).
    emx_gauge : float
        Largest running integral of gauge force x gauge velocity, trapezoidal at the master
        steps [J].
    emx_head : float
        Largest work done by the head force on the pile-top face since the blow started [J]
        (ENTHRU at the head, GRLWEAP's location).
    max_pile_head_force : float
        Largest anvil-pile contact force [N].
    max_toe_displacement : float
        Largest toe displacement [m].
    permanent_set : float
        Toe displacement at the end minus at the start [m].
    toe_velocity_end : float
        Toe velocity at the end [m/s].
    impact_velocity : float
        Ram velocity at impact [m/s].
    initial_state : PileState
        The pile's state at the start.
    final_state : PileState
        The pile's state at the end, the one the next blow starts from.
    section_strain : numpy.ndarray or None, default None
        Elongation u_i - u_i+1 [m] of the springs asked for with ``sections`` at every record
        row, shape (rows, n_sections) (times the stress factor: the stress, positive in
        compression), or None.
    """

    columns: dict[str, np.ndarray]
    energies: dict[str, np.ndarray]
    time_step: float
    n_steps: int
    wall_time: float
    input_energy: float
    max_compression_stress: float
    max_tension_stress: float
    emx_gauge: float
    emx_head: float
    max_pile_head_force: float
    max_toe_displacement: float
    permanent_set: float
    toe_velocity_end: float
    impact_velocity: float
    initial_state: PileState
    final_state: PileState
    section_strain: np.ndarray | None = None

    @property
    def pile_max_compression_stress(self) -> float:
        """Alias of ``max_compression_stress`` [Pa]."""
        return self.max_compression_stress

    @property
    def pile_max_tension_stress(self) -> float:
        """Alias of ``max_tension_stress`` [Pa]."""
        return self.max_tension_stress


@dataclass
class AnvilKernels:
    """An anvil unit as kernel arrays: the state at rest S (copied for every blow).

    Parameters
    ----------
    kind : str
        "rom", "lumped", "classic", "none" or "stack" (the anvil and the anvil ring: the
        :class:`anvilwave.anvil_rom.stack.StackUnit` is ``unit``, its state at rest its
        ``state``; P, C and S unused).
    P : numpy.ndarray
        The unit's parameter array (without an anvil: the contact [k, c] [N/m, N s/m]).
    C : numpy.ndarray
        The unit's coefficient array (unused for classic and none).
    S : numpy.ndarray
        The unit's state at rest.
    u_top0 : float
        Top face at rest [m].
    stable_step : float
        The coupled stability limit of this unit [s].
    n_sub : int, default 1
        Its sub-steps per master step (classic) [-].
    unit : object, default None
        The :class:`anvilwave.anvil_rom.unit.AnvilUnit` or
        :class:`anvilwave.hammer.driving_system.DrivingSystem` or
        :class:`anvilwave.anvil_rom.stack.StackUnit` (None without an anvil).
    """

    kind: str
    P: np.ndarray
    C: np.ndarray
    S: np.ndarray
    u_top0: float
    stable_step: float
    n_sub: int = 1
    unit: object = None


_WARM: set = set()
"""Loop variants already compiled or loaded in this process."""


@dataclass
class Engine:
    """The in-process engine for one system configuration and anvil model.

    Build it with :func:`build_engine`. :meth:`blow` simulates one blow from a given pile
    state, :meth:`run` consecutive blows; :meth:`static_state` is the state a blow starts from
    by default and :meth:`with_pile_soil` the same engine on another soil or penetration.

    Parameters
    ----------
    config : SystemConfig
        The system configuration.
    anvil : AnvilKernels
        The anvil unit, prepared for ``time_step``.
    ram_mass : numpy.ndarray
        The ram chain's masses, shape (N_r,) [kg] (a modal ram unit: its total mass).
    ram_stiffness : numpy.ndarray
        The ram chain's springs, shape (N_r - 1,) [N/m].
    pile_arrays : PileSoilArrays
        The pile's and soil's parameter arrays (``PileSoil.arrays()``).
    time_step : float
        The master step [s].
    limits : dict of str to float
        The stability limits of the units and of their coupling [s] (and the ROM's fmax
        sampling).
    modal : ModalData, optional
        The anvil's modal data (ROM anvil), or None.
    ram_modes : RamToeModes, optional
        :class:`anvilwave.hammer.modal_ram.RamToeModes` of a modal ram unit (None: the ram
        chain).
    ram_unit : ModalRamUnit, optional
        The :class:`anvilwave.hammer.modal_ram.ModalRamUnit` of ``ram_modes``, its step
        coefficients set (built here when None; engines for other soils share it: every blow
        restarts its state).
    """

    config: SystemConfig
    anvil: AnvilKernels
    ram_mass: np.ndarray
    ram_stiffness: np.ndarray
    pile_arrays: object
    time_step: float
    limits: dict[str, float]
    modal: object = None
    ram_modes: object = None
    ram_unit: object = None

    def __post_init__(self):
        g = self.config.gravity
        self._ram = tuple(aligned_copy(a) for a in (self.ram_mass * g, 1.0 / self.ram_mass,
                                                    self.ram_stiffness, self.ram_mass))
        self._ram_nsub = substeps(self.time_step,
                                  ram_stable_time_step(self.ram_mass, self.ram_stiffness))
        if self.ram_modes is not None and self.ram_unit is None:
            self.ram_unit = ModalRamUnit(self.ram_modes, g)
            self.ram_unit.start(0.0, 0.0, self.time_step)  # the step's coefficients
        self._prepare_pile()

    def _prepare_pile(self) -> None:
        a = self.pile_arrays
        self._sweep = sweep_arrays(a.pile, a.soil, self.config.gravity)
        self._pile_nsub = substeps(self.time_step, pile_stable_time_step(a.pile, a.soil))
        factor = self.config.pile_soil.stress_factors()
        springs = factor.size
        self._stresses = (aligned_copy(factor), aligned_zeros(springs), aligned_zeros(springs))
        n = a.pile.shape[1]
        self._works = (aligned_zeros(n), aligned_zeros(n))
        self._static = None

    # ------------------------------------------------------------------ state
    @property
    def static_head_force(self) -> float:
        """Weight resting on the pile head before a blow [N] (anvil, helmet, assembly)."""
        return _static_pile_force(self.anvil, self.config.gravity)

    def static_state(self) -> PileState:
        """The pile and soil at rest under the anvil's (or helmet's) weight and their own.

        :func:`anvilwave.pile.model.initial_state`: the state a blow starts from by default.

        Returns
        -------
        PileState
            A copy of the static state.
        """
        if self._static is None:
            s = initial_state(self.pile_arrays, head_force=self.static_head_force,
                              gravity=self.config.gravity)
            self._static = PileState(*(np.array(a, dtype=float) for a in s))
        return self._static.copy()

    def with_pile_soil(self, pile_soil) -> Engine:
        """This engine for another pile-soil model with the same pile discretisation.

        Another soil, SRD or penetration: the anvil unit, the ram (a modal ram's unit too) and
        the time step are shared; only the pile's arrays, its sub-steps and its static state
        are new.

        The coupled stability limit is not recomputed: the soil springs are orders of magnitude
        softer than the contact and pile springs that set it, and the pile sub-steps within its
        own limit (soil included).

        Parameters
        ----------
        pile_soil : PileSoil
            The :class:`anvilwave.pile.model.PileSoil` with the same pile.

        Returns
        -------
        Engine
            The engine on ``pile_soil``.

        Raises
        ------
        ValueError
            If the pile's segments (sections, segment length, material damping) differ.
        """
        arrays = pile_soil.arrays()
        mine = self.pile_arrays.pile
        if arrays.pile.shape != mine.shape or not np.array_equal(arrays.pile, mine):
            raise ValueError("with_pile_soil needs the same pile (sections, segment length, "
                             "material damping): only the soil may change")
        limits = dict(self.limits)
        limits["pile"] = float(pile_stable_time_step(arrays.pile, arrays.soil))
        return Engine(replace(self.config, pile_soil=pile_soil), self.anvil, self.ram_mass,
                      self.ram_stiffness, arrays, self.time_step, limits, self.modal,
                      self.ram_modes, self.ram_unit)

    # ------------------------------------------------------------------ blows
    def blow(self, state: PileState | None = None, impact_velocity: float | None = None,
             duration: float | None = None, record_interval: float | None = None,
             record: bool = True, energy: bool | None = None,
             energy_interval: float | None = None, sections=None) -> BlowResult:
        """Simulate one blow from ``state`` (default :meth:`static_state`; not modified).

        The ram starts on the anvil at rest on the pile head. The result's ``final_state`` is
        the state the next blow starts from.

        Parameters
        ----------
        state : PileState, optional
            The pile's state to start from (not modified); default :meth:`static_state`.
        impact_velocity : float, optional
            Ram velocity at impact [m/s]; default: the system's.
        duration : float, optional
            Duration of the blow [s]; default: the system's.
        record_interval : float, optional
            Spacing of the records [s]; default: the system's output interval, else every
            step.
        record : bool, default True
            Keep the time series (False: the summary only, no memory per step).
        energy : bool, optional
            Keep the energy bookkeeping (the ENERGY_COLUMNS series and the works of the final
            state); default: as ``record``.
        energy_interval : float, optional
            Spacing of the energy series [s]; default: every record, but at least ENERGY_STEPS
            master steps apart. The last step is always in it, and each of its rows is exact
            (the works are summed at every step).
        sections : array_like of int, optional
            Indices of pile springs whose elongation is recorded at every record row
            (``BlowResult.section_strain``).

        Returns
        -------
        BlowResult
            The blow's time series and summary.

        Raises
        ------
        ValueError
            If ``duration`` or ``impact_velocity`` is not positive, the blow is longer than the
            tube head's kernel, or a section index is out of range.
        """
        cfg = self.config
        h = self.time_step
        duration = cfg.duration if duration is None else float(duration)
        velocity = cfg.impact_velocity if impact_velocity is None else float(impact_velocity)
        if not (math.isfinite(duration) and duration > 0.0):
            raise ValueError(f"duration must be positive [s], got {duration!r}")
        if not (math.isfinite(velocity) and velocity > 0.0):
            raise ValueError(f"impact_velocity must be positive [m/s], got {velocity!r}")
        interval = cfg.output_interval if record_interval is None else record_interval
        n_steps = int(round(duration / h))
        rings = getattr(self.anvil.unit, "rings", None)
        head = None if rings is None else rings.head_kernel  # the tube head's correction
        if self.anvil.kind == "stack" and self.anvil.unit.state is not None:
            head = self.anvil.unit.state.head_kernel
        if head is not None and head.shape[0] > 1 and n_steps >= head.shape[0]:
            raise ValueError(f"duration {duration:g} s is longer than the tube head's kernel "
                             f"({(head.shape[0] - 1) * h:g} s, [anvil] pile_head = 'tube'): "
                             "set [simulation] duration to the longest blow")
        record_every = 1 if interval is None else max(1, int(round(interval / h)))
        if energy_interval is None:
            energy_every = record_every * -(-ENERGY_STEPS // record_every)
        else:
            energy_every = max(1, int(round(float(energy_interval) / h)))
        energy = record if energy is None else bool(energy)
        start = self.static_state() if state is None else state.copy()
        pu, pv, poff, pen = (aligned_copy(start.u), aligned_copy(start.v),
                             aligned_copy(start.soil_offset), start.energy.copy())
        probes = self.pile_arrays.probes
        face0 = float(head_displacement(probes, pu))
        anvil = self.anvil
        # the ram starts half a step before the first contact (t0 = -h/2): with the leapfrog's
        # staggered velocities the first two displacement levels are then the exact ones, and
        # a chain meeting a chain at the Courant number 1 is exact
        t0 = -0.5 * h
        ram_u = aligned_zeros(self.ram_mass.shape)
        ram_u[:] = anvil.u_top0 + t0 * velocity
        ram_v = aligned_zeros(self.ram_mass.shape)
        ram_v[:] = velocity
        modal_ram = NO_MODAL_RAM
        if self.ram_unit is not None:
            unit = self.ram_unit
            unit.start(anvil.u_top0 + t0 * velocity, velocity, h)
            modal_ram = (unit.C, unit.S, unit.toe)
        ram = LoopRam(*self._ram, ram_u, ram_v, self._ram_nsub, *modal_ram)
        modal = classic = direct = rings = stack = None
        if anvil.kind in ("rom", "lumped"):
            S = anvil.S.copy()
            interface = np.empty(4)
            modal_unit_interface(anvil.P, anvil.C, S, interface)
            modal = LoopModalAnvil(anvil.P, anvil.C, S, interface)
            if anvil.unit.rings is not None:  # the state's parts copied, the rest shared
                rings = copy_ring_state(anvil.unit.rings)
                # the tube head's history and the ram face's modes start with the blow
                anvil.unit.restart_head(rings)
                ring_interface(anvil.C, S, rings, h)
        elif anvil.kind == "classic":
            classic = LoopClassic(anvil.P, anvil.S.copy(), anvil.n_sub)
        elif anvil.kind == "stack":
            stack = _copied_stack(anvil.unit.state)
        else:
            direct = anvil.P
        n_rows = n_steps // record_every + 1
        # filled (NaN) here: the memory is touched before the loop, not inside its timing
        out = np.full((len(COLUMNS), n_rows if record else 0), np.nan)
        energies = (np.full((1 + len(ENERGY_COLUMNS), n_steps // energy_every + 2), np.nan)
                    if record and energy else None)
        works = None
        if energy:
            works = self._works
            for w in works:
                w.fill(0.0)
        factor, largest, smallest = self._stresses
        largest.fill(0.0)
        smallest.fill(0.0)
        summary = np.zeros(SUMMARY_SIZE)
        idx = np.zeros(0, dtype=np.int64)
        if sections is not None:
            idx = np.ascontiguousarray(sections, dtype=np.int64)
            if idx.size and (idx.min() < 0 or idx.max() >= probes_springs(self.pile_arrays)):
                raise ValueError("sections: spring indices out of range")
        section_args = (idx, np.full((idx.size, n_rows), np.nan))
        pile_sweep, soil_sweep, first_soil = self._sweep
        loop = (ram, LoopAnvil(modal, rings, classic, direct, stack),
                LoopPile(self.pile_arrays.pile, probes, pile_sweep, soil_sweep, first_soil, pu,
                         pv, poff, pen, self._pile_nsub, start.u, start.v, start.energy, face0,
                         factor, largest, smallest),
                LoopSettings(cfg.gravity, t0, h, n_steps, record_every, energy_every),
                LoopRecords(out, energies, works, section_args, summary))
        _warm_up(loop, anvil.kind, energy)
        begin = time.perf_counter()
        rows, energy_rows = run_blow(*loop)
        wall = time.perf_counter() - begin
        columns = {} if not record else {name: out[i, :rows] for i, name in enumerate(COLUMNS)}
        series = {}
        if energies is not None:
            series = {name: energies[i, :energy_rows]
                      for i, name in enumerate(("time [s]",) + ENERGY_COLUMNS)}
        final = PileState(pu, pv, poff, pen, start_soil_offset=start.soil_offset)
        return BlowResult(
            columns=columns, energies=series, time_step=h, n_steps=n_steps, wall_time=wall,
            input_energy=0.5 * float(self.ram_mass.sum()) * velocity**2,
            max_compression_stress=float(summary[S_MAX_COMPRESSION]),
            max_tension_stress=float(summary[S_MAX_TENSION]),
            emx_gauge=float(summary[S_EMX_GAUGE]), emx_head=float(summary[S_EMX_HEAD]),
            max_pile_head_force=float(summary[S_MAX_HEAD_FORCE]),
            max_toe_displacement=float(summary[S_MAX_TOE]),
            permanent_set=float(summary[S_TOE_END] - summary[S_TOE_START]),
            toe_velocity_end=float(summary[S_TOE_VELOCITY_END]), impact_velocity=velocity,
            initial_state=start, final_state=final,
            section_strain=(section_args[1][:, :rows].T.copy() if sections is not None
                            else None))

    def run(self, duration: float | None = None, record_interval: float | None = None,
            progress: bool = False, record: bool = True, energy: bool | None = None,
            blows: int | None = None, energy_interval: float | None = None
            ) -> list[BlowResult]:
        """Simulate consecutive blows (:meth:`blow`) from the static state.

        Each blow restarts the ram at its impact velocity on the anvil at rest; the pile keeps
        its permanent set and soil state from the previous blow.

        Parameters
        ----------
        duration : float, optional
            Duration of each blow [s]; default: the system's.
        record_interval : float, optional
            Spacing of the records [s] (:meth:`blow`).
        progress : bool, default False
            Show a progress bar (tqdm) for more than one blow.
        record : bool, default True
            Keep the time series (:meth:`blow`).
        energy : bool, optional
            Keep the energy bookkeeping (:meth:`blow`); default: as ``record``.
        blows : int, optional
            Number of blows [-]; default ``config.blows``.
        energy_interval : float, optional
            Spacing of the energy series [s] (:meth:`blow`).

        Returns
        -------
        list of BlowResult
            One result per blow, in order.

        Raises
        ------
        ValueError
            As :meth:`blow`.
        """
        count = self.config.blows if blows is None else int(blows)
        sequence = range(count)
        if progress and count > 1:
            from tqdm import tqdm

            sequence = tqdm(sequence, desc="blows", unit="blow")
        results = []
        state = None
        for _ in sequence:
            result = self.blow(state, duration=duration, record_interval=record_interval,
                               record=record, energy=energy, energy_interval=energy_interval)
            state = result.final_state
            results.append(result)
        return results


WARM_UP_STEPS = 200
"""Steps of the trial run that compiles or loads a loop variant (on copies of the states)."""


def probes_springs(arrays) -> int:
    """Number of pile springs (segments - 1).

    Parameters
    ----------
    arrays : PileSoilArrays
        The pile's and soil's parameter arrays (``PileSoil.arrays()``).

    Returns
    -------
    int
        N - 1 [-].
    """
    return int(arrays.pile.shape[1] - 1)


def _copied(a):
    """A copy of ``a``, an array or None."""
    return None if a is None else a.copy()


def _warm_up(loop: tuple, kind: str, energy: bool) -> None:
    """Compile (or load from numba's cache) this variant of the loop, once per process, and
    run it for a few steps on copies of the states, so that the blow's timing excludes the
    compilation and the first touch of the code and of the parameter arrays.

    ``loop`` is :func:`run_blow`'s (ram, anvil, pile, settings, records); the trial copies,
    field by field, what the loop writes and shares the rest."""
    ram, anvil, pile, settings, records = loop
    key = ("modal" if kind in ("rom", "lumped") else kind, energy, anvil.rings is not None)
    if key in _WARM:
        return

    announce_compilation((run_blow, _blow))
    modal, classic = anvil.modal, anvil.classic
    trial_anvil = anvil._replace(
        modal=None if modal is None else modal._replace(state=modal.state.copy(),
                                                        interface=modal.interface.copy()),
        rings=None if anvil.rings is None else copy_ring_state(anvil.rings),
        classic=None if classic is None else classic._replace(state=classic.state.copy()),
        stack=None if anvil.stack is None else _copied_stack(anvil.stack))
    trial_ram = ram._replace(u=ram.u.copy(), v=ram.v.copy(), modal_state=ram.modal_state.copy(),
                             modal_toe=ram.modal_toe.copy())
    trial_pile = pile._replace(u=pile.u.copy(), v=pile.v.copy(),
                               soil_offset=pile.soil_offset.copy(), energy=pile.energy.copy(),
                               largest=pile.largest.copy(), smallest=pile.smallest.copy())
    trial_records = records._replace(
        out=records.out.copy(), energies=_copied(records.energies),
        works=None if records.works is None else tuple(w.copy() for w in records.works),
        sections=(records.sections[0], records.sections[1].copy()),
        summary=records.summary.copy())
    trial_settings = settings._replace(n_steps=min(settings.n_steps, WARM_UP_STEPS))
    run_blow(trial_ram, trial_anvil, trial_pile, trial_settings, trial_records)
    _WARM.add(key)


def _copied_stack(state: StackState) -> StackState:
    """A stack's arrays, each copied (the loop writes its states and scratch)."""
    return StackState(*(np.array(a, dtype=float, copy=True) for a in state))


def _static_pile_force(anvil: AnvilKernels, gravity: float) -> float:
    if anvil.kind == "none":
        return 0.0
    if anvil.kind == "classic":
        return anvil.unit.static_pile_force(gravity)
    if anvil.kind == "stack":
        return anvil.unit.total_mass * gravity
    return anvil.unit.anvil.total_mass * gravity


def _anvil_kernels(cfg: SystemConfig, ram_mass, pile_arrays, modal, mass,
                   ram_modes=None) -> AnvilKernels:
    """The anvil unit at rest and its coupled stability limit (the step is set later)."""
    settings = cfg.anvil
    if ram_modes is not None and settings.model not in ("rom", "lumped"):
        raise InputError(cfg.source, "hammer.ram_model", "the modal ram unit runs with the "
                                                         "ROM or lumped anvil")
    if settings.model == "none":
        # ram toe and pile head: the two contact springs in series (ram_contact_damping acts)
        contact = _contact(cfg)
        k = 1.0 / (1.0 / contact.ram_stiffness + 1.0 / contact.pile_stiffness)
        P = np.array([k, contact.ram_damping])
        limit = coupled_stable_time_step(ram_mass, cfg.hammer.ram.stiffness, k, k, pile_arrays)
        return AnvilKernels("none", P, np.zeros((1, 1)), np.zeros(1), 0.0, float(limit), 1,
                            None)
    if settings.model == "classic":
        ds = settings.classic
        P = ds.parameters(cfg.gravity)
        S = ds.initial_state(P)
        limit = min(driving_system_stable_time_step(P),
                    interface_time_step(P, ram_mass[-1], pile_arrays.pile[0, 0]))
        return AnvilKernels("classic", P, np.zeros((1, 1)), S, 0.0, float(limit), 1, ds)
    if settings.model == "rom":
        try:
            rom = ModalAnvil.from_modal_data(modal, fmax=settings.fmax,
                                             damping_ratio=settings.damping_ratio,
                                             static_correction=settings.static_correction,
                                             source=cfg.source)
        except InputError as exc:
            raise InputError(cfg.source, f"anvil.{exc.key}", exc.rule) from None
    else:
        rom = ModalAnvil.rigid(mass)
    face = _ram_face(cfg, rom, ram_modes) if rom.n_annuli > 1 else None
    unit = AnvilUnit(rom, _contact(cfg), gravity=cfg.gravity, ram_face=face)
    u_top0, _ = unit.rest_on_pile(0.0)
    if ram_modes is not None:
        limit = modal_ram_coupled_stable_time_step(
            ram_modes.participation, unit.contact.ram_stiffness, unit.contact.pile_stiffness,
            pile_arrays, rom.participation_ram, rom.participation_pile)
    else:
        limit = coupled_stable_time_step(ram_mass, cfg.hammer.ram.stiffness,
                                         unit.contact.ram_stiffness,
                                         unit.contact.pile_stiffness, pile_arrays,
                                         rom.participation_ram, rom.participation_pile)
    return AnvilKernels(settings.model, unit.P, unit.C, unit.S, u_top0, float(limit), 1, unit)


def _ram_face(cfg: SystemConfig, rom: ModalAnvil, ram_modes) -> RamFace:
    """The modal ram's toe in annuli for the anvil's ram port in annuli (``[anvil]
    ram_port_annuli``): the same annuli, the ram's toe the anvil's ram face (to 1 mm)."""
    J = rom.n_annuli
    if ram_modes is None or ram_modes.n_annuli != J:
        raise InputError(cfg.source, "anvil.ram_port_annuli",
                         f"the anvil's ram port in {J} annuli needs the modal ram unit with its "
                         "toe in as many annuli ([hammer] ram_model = 'modal', the ROM or "
                         "lumped anvil)")
    toe = 0.5 * cfg.hammer.ram.toe_diameter
    face = cfg.anvil.spec.interfaces.ram_contact_radius
    if not abs(toe - face) <= 1e-3:
        raise InputError(cfg.source, "anvil.ram_port_annuli",
                         f"the annuli are the ram toe's (radius {toe:g} m) and the anvil's ram "
                         f"face's (radius {face:g} m): they must be the same face (to 1 mm)")
    return RamFace.of(ram_modes.omega, ram_modes.annulus_participation, ram_modes.participation,
                      ram_modes.annulus_residual, ram_modes.annulus_areas)


def _set_step(anvil: AnvilKernels, h: float) -> AnvilKernels:
    """The anvil unit prepared for the master step h [s]."""
    if anvil.kind == "classic":
        n_sub = max(1, int(np.ceil(h / driving_system_stable_time_step(anvil.P))))
        return replace(anvil, n_sub=n_sub)
    if anvil.kind in ("rom", "lumped"):
        anvil.unit.set_step(h)
        return replace(anvil, P=anvil.unit.P.copy(), C=anvil.unit.C.copy(),
                       S=anvil.unit.S.copy())
    if anvil.kind == "stack":  # its state copied at every blow
        anvil.unit.set_step(h)
    return anvil


def _stack_kernels(cfg: SystemConfig, anvil: AnvilKernels) -> AnvilKernels:
    """The system's driving stack (``[[anvil.bodies]]``) at rest on the pile, in place of the
    anvil alone ``anvil``, whose coupled stability limit it keeps: the ram and pile contacts are
    the same springs on the anvil's and the ring's modes up to the same fmax (the seat's
    complementarity problem takes the modes at t_n; Table 1's ring stack balances its energy to
    0.4 % at 20 us, ``tests/test_stack.py``)."""
    st = cfg.anvil.stack
    try:
        unit = stack_unit(cfg, st.ring, seat_friction=st.seat_friction,
                          seat_rings=st.seat_rings, pile_rings=st.pile_rings,
                          ram_annuli=st.ram_annuli, sleeve_clearance=st.sleeve_clearance,
                          sleeve_friction=st.sleeve_friction, sleeve_bands=st.sleeve_bands)
    except InputError as exc:  # the unit's own checks named as the system file's keys; a
        if exc.source not in ("stack", cfg.source):  # body file's error names its file
            raise
        key = exc.key if exc.key.startswith("anvil.") else f"anvil.bodies.{exc.key}"
        raise InputError(cfg.source, key, exc.rule) from None
    u_top0, _ = unit.rest_on_pile(0.0)
    return AnvilKernels("stack", np.zeros(0), np.zeros((0, 0)), np.zeros(0), float(u_top0),
                        anvil.stable_step, 1, unit)


def _contact(cfg: SystemConfig) -> ContactParameters:
    s = cfg.anvil
    k_ram, k_pile = contact_stiffnesses(cfg)
    return ContactParameters(k_ram, k_pile, s.ram_contact_damping, s.pile_contact_damping)


def _modal_ram_as_chain(cfg: SystemConfig):
    """The system's modal-unit ram as its equivalent chain (cached)."""

    try:
        return modal_ram_chain(cfg.hammer.ram, cfg.hammer.ram.modes, cached_chain)
    except InputError as exc:
        raise InputError(cfg.source, "anvil.model", f"the {cfg.anvil.model} anvil steps the "
                                                    f"modal ram as its chain: {exc.rule}"
                         ) from None


def build_engine(cfg: SystemConfig, modal=None, ram_modes=None) -> Engine:
    """Assemble the components of a system.

    Parameters
    ----------
    cfg : SystemConfig
        The system configuration.
    modal : ModalData, optional
        Precomputed modal data of the anvil; default: the ROM anvil's from the modal-data
        cache (computed on a miss), the lumped anvil's mass from its geometry without modes
        (:func:`anvilwave.anvil_rom.fem.pipeline.solid_mass`).
    ram_modes : RamToeModes, optional
        :class:`anvilwave.hammer.modal_ram.RamToeModes`: the ram runs as the modal unit
        (:class:`anvilwave.hammer.modal_ram.ModalRamUnit`, exact per mode, its residual
        flexibility the ram's side of the contact) instead of the system's ram chain; None:
        the system's ram (a modal ram given as toe modes, ``ram_model = "modal"``, runs as the
        unit with the ROM and lumped anvils and as its equivalent chain with the classic
        driving system, whose kernel steps a ram chain).

    Returns
    -------
    Engine
        The engine, its time step chosen (or checked against the stability limits).

    Raises
    ------
    InputError
        If the configuration's anvil, ram and pile head do not fit together, or
        ``simulation.time_step`` is above the stable limit of the anvil contact coupling.
    """
    if ram_modes is None and cfg.hammer.ram.is_modal_unit:
        if cfg.anvil.model in ("rom", "lumped"):
            ram_modes = cfg.hammer.ram.modes
        else:
            cfg = replace(cfg, hammer=replace(cfg.hammer, ram=_modal_ram_as_chain(cfg)))
    if ram_modes is not None:
        ram = replace(cfg.hammer.ram, toe_stiffness=ram_modes.toe_stiffness)
        cfg = replace(cfg, hammer=replace(cfg.hammer, ram=ram))
    ram = cfg.hammer.ram
    ram_mass = np.ascontiguousarray(ram.mass, dtype=float)
    ram_stiffness = np.ascontiguousarray(ram.stiffness, dtype=float)
    if ram_modes is not None:  # a one-mass stand-in: the input energy; the kernel skips it
        ram_mass = np.array([ram_modes.total_mass])
        ram_stiffness = np.zeros(0)
    arrays = cfg.pile_soil.arrays()
    if cfg.anvil.model == "rom" and modal is None:
        modal = anvil_modal_data(cfg)
    mass = None
    if cfg.anvil.model == "lumped":
        if cfg.anvil.mass is not None:
            mass = cfg.anvil.mass
        elif modal is not None:
            mass = modal.total_mass
        else:

            mass = solid_mass(cfg.anvil.spec)
    anvil = _anvil_kernels(cfg, ram_mass, arrays, modal, mass, ram_modes)
    limits = {
        "ram": float(ram_stable_time_step(ram_mass, ram_stiffness)),
        "pile": float(pile_stable_time_step(arrays.pile, arrays.soil)),
        "anvil coupling": float(anvil.stable_step),
    }
    if cfg.anvil.model == "rom":
        fmax = anvil.unit.anvil.fmax
        limits["anvil fmax sampling"] = 1.0 / (STEPS_PER_PERIOD_AT_FMAX * fmax)
    if cfg.anvil.model == "rom" and cfg.anvil.stack is not None:
        anvil = _stack_kernels(cfg, anvil)
    stable = min(limits["ram"], limits["pile"], limits["anvil coupling"])
    if cfg.time_step is None:
        h = min(ACCURACY_FRACTION * stable, limits.get("anvil fmax sampling", np.inf))
        # a whole number of steps per output interval keeps the records on the grid (an
        # interval shorter than the step records every step)
        if cfg.output_interval is not None and cfg.output_interval > h:
            h = cfg.output_interval / int(np.ceil(cfg.output_interval / h))
    else:
        h = cfg.time_step
        # ram and pile sub-step on their own; the contact coupling cannot
        if h > limits["anvil coupling"]:
            raise InputError(cfg.source, "simulation.time_step",
                             f"{h:g} s is above the stable limit of the anvil contact coupling "
                             f"({limits['anvil coupling']:.3g} s): use a smaller step or omit "
                             "time_step for the automatic choice")
    if cfg.anvil.model == "rom" and cfg.anvil.pile_head == "tube":
        anvil = _tube_head(cfg, anvil, arrays, float(h))
    anvil = _set_step(anvil, float(h))
    return Engine(cfg, anvil, ram_mass, ram_stiffness, arrays, float(h), limits, modal,
                  ram_modes)


def _tube_head(cfg: SystemConfig, anvil: AnvilKernels, arrays, h: float) -> AnvilKernels:
    """The anvil's rings, or the stack's pile rings, put on a tube head (``[anvil] pile_head =
    "tube"``, :func:`anvilwave.engine.anvils.tube_head` at the step ``h`` [s]); the unit rests
    on it afresh."""
    unit = anvil.unit
    if anvil.kind == "stack":
        areas = unit.ring.areas[2 * unit.seat_rings:2 * unit.seat_rings + unit.pile_rings]
        unit.set_step(h)
        u_top0, _ = unit.set_head(tube_head(cfg, arrays, areas, h))
        return replace(anvil, u_top0=float(u_top0))
    u_top0, _ = unit.set_head(tube_head(cfg, arrays, unit.anvil.ring_areas, h))
    return replace(anvil, S=unit.S.copy(), u_top0=u_top0)
