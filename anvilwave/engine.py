"""The in-process system engine: ram -> anvil unit -> pile/soil in one jitted loop per blow.

The step order is the master algorithm of DESIGN.md, the same as the FMI master's:

1. read the ram toe (u, v) and the pile head (u, v) at t_n (states, no feedthrough);
2. the anvil unit turns them into the two contact forces at t_n (feedthrough);
3. the forces are held over [t_n, t_n+1] while ram, anvil unit and pile/soil each advance.

Time is t_n = t0 + n h, never accumulated, with t0 = -h/2: the ram starts half a step before
the first contact (t = 0), see :meth:`Engine.run`. The kernels are those of the physics
packages, called through small adapters that give every anvil unit (ROM, rigid mass, classic
cushion-helmet system, none) the same signature; one compiled loop serves all of them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from anvil_rom.contact import contact_force
from anvil_rom.pipeline import compute_anvil_modes
from anvil_rom.rom import ModalAnvil
from anvil_rom.unit import (
    AnvilUnit,
    ContactParameters,
    modal_unit_energy,
    modal_unit_forces,
    modal_unit_outputs,
    modal_unit_step,
)
from anvilwave_inputs import InputError
from hammer.driving_system import (
    driving_system_energy,
    driving_system_forces,
    driving_system_stable_time_step,
    driving_system_step,
    interface_time_step,
)
from hammer.ram import leapfrog_energies, ram_step
from hammer.ram import stable_time_step as ram_stable_time_step
from pile.kernels import (
    ENERGY_KINETIC,
    ENERGY_STRAIN,
    PILE_STIFFNESS,
    WORK_GRAVITY,
    WORK_HEAD,
    WORK_PILE_DAMPING,
    WORK_SOIL_DAMPING,
    WORK_SOIL_STATIC,
    gauge_force,
    gauge_velocity,
    head_displacement,
    head_face_work,
    head_velocity,
    pile_step,
    toe_displacement,
    update_stress_extremes,
)
from pile.kernels import stable_time_step as pile_stable_time_step
from pile.model import initial_state, substeps

from .system import SystemConfig

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
    "pile_head_work [J]", "pile_head_face_work [J]",
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
    """
    from pile.kernels import SOIL_STIFFNESS

    ram_mass = np.asarray(ram_mass, float)
    pile_mass = pile_arrays.pile[0]
    k_chain = pile_arrays.pile[PILE_STIFFNESS][:-1]
    n_r, n_p = len(ram_mass), len(pile_mass)
    n_a = 0 if participation_ram is None else len(participation_ram)
    n = n_r + n_a + n_p
    K = np.zeros((n, n))
    M = np.concatenate([ram_mass, np.ones(n_a), pile_mass])

    def spring(vec_a, vec_b, k):
        d = vec_a - vec_b
        K[:] += k * np.outer(d, d)

    def unit(i):
        e = np.zeros(n)
        e[i] = 1.0
        return e

    for i, k in enumerate(ram_stiffness):
        spring(unit(i), unit(i + 1), k)
    toe = unit(n_r - 1)
    head = unit(n_r + n_a)
    if n_a:
        top = np.zeros(n)
        bottom = np.zeros(n)
        top[n_r:n_r + n_a] = participation_ram
        bottom[n_r:n_r + n_a] = participation_pile
        spring(toe, top, k_ram)
        spring(bottom, head, k_pile)
    else:
        spring(toe, head, k_ram)
    for i, k in enumerate(k_chain):
        spring(unit(n_r + n_a + i), unit(n_r + n_a + i + 1), k)
    soil_k = pile_arrays.soil[SOIL_STIFFNESS]
    idx = np.arange(n_r + n_a, n)
    K[idx, idx] += soil_k[:n_p]
    K[n - 1, n - 1] += soil_k[n_p]
    scale = 1.0 / np.sqrt(M)
    omega2 = np.linalg.eigvalsh(scale[:, None] * K * scale[None, :]).max()
    return float(2.0 / np.sqrt(omega2))


# ----------------------------------------------------------------- anvil-unit adapters
# Every anvil unit: forces(P, C, S, u_ram, v_ram, u_pile, v_pile) -> (F_ram, F_pile, u_top,
# u_bottom); step(P, C, S, F_ram, F_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub);
# energy(P, C, S, u_ram, v_ram, u_pile, v_pile) -> (kinetic, potential).
@njit(cache=True)
def modal_forces(P, C, S, u_ram, v_ram, u_pile, v_pile):
    f_ram, f_pile = modal_unit_forces(P, C, S, u_ram, v_ram, u_pile, v_pile)
    ut, _, ub, _ = modal_unit_outputs(P, C, S, f_ram, f_pile)
    return f_ram, f_pile, ut, ub


@njit(cache=True)
def modal_step(P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    modal_unit_step(P, C, S, f_ram, f_pile)  # exact over h (C holds the h transition)


@njit(cache=True)
def modal_energy(P, C, S, u_ram, v_ram, u_pile, v_pile):
    return modal_unit_energy(P, C, S, u_ram, v_ram, u_pile, v_pile)


@njit(cache=True)
def direct_forces(P, C, S, u_ram, v_ram, u_pile, v_pile):
    """No anvil: the ram toe bears on the pile head through one contact spring (P = [k, c])."""
    f = contact_force(u_ram - u_pile, v_ram - v_pile, P[0], P[1])
    return f, f, u_pile, u_pile


@njit(cache=True)
def direct_step(P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    pass


@njit(cache=True)
def direct_energy(P, C, S, u_ram, v_ram, u_pile, v_pile):
    f = contact_force(u_ram - u_pile, v_ram - v_pile, P[0], P[1])
    return 0.0, 0.5 * f * f / P[0]


@njit(cache=True)
def classic_forces(P, C, S, u_ram, v_ram, u_pile, v_pile):
    return driving_system_forces(P, S, u_ram, v_ram, u_pile, v_pile)


@njit(cache=True)
def classic_step(P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    driving_system_step(P, S, u_ram, v_ram, u_pile, v_pile, h, n_sub)


@njit(cache=True)
def classic_energy(P, C, S, u_ram, v_ram, u_pile, v_pile):
    kinetic, strain, gravity = driving_system_energy(P, S, u_ram, u_pile)
    return kinetic, strain + gravity


# one compiled loop serves every anvil unit: numba's on-disk cache cannot hold a function
# specialised on function arguments across processes, so the unit is chosen by a code
UNIT_MODAL, UNIT_CLASSIC, UNIT_NONE = 0, 1, 2


@njit(cache=True)
def anvil_forces(kind, P, C, S, u_ram, v_ram, u_pile, v_pile):
    if kind == UNIT_MODAL:
        return modal_forces(P, C, S, u_ram, v_ram, u_pile, v_pile)
    if kind == UNIT_CLASSIC:
        return classic_forces(P, C, S, u_ram, v_ram, u_pile, v_pile)
    return direct_forces(P, C, S, u_ram, v_ram, u_pile, v_pile)


@njit(cache=True)
def anvil_step(kind, P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    if kind == UNIT_MODAL:
        modal_step(P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub)
    elif kind == UNIT_CLASSIC:
        classic_step(P, C, S, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, n_sub)


@njit(cache=True)
def anvil_energy(kind, P, C, S, u_ram, v_ram, u_pile, v_pile):
    if kind == UNIT_MODAL:
        return modal_energy(P, C, S, u_ram, v_ram, u_pile, v_pile)
    if kind == UNIT_CLASSIC:
        return classic_energy(P, C, S, u_ram, v_ram, u_pile, v_pile)
    return direct_energy(P, C, S, u_ram, v_ram, u_pile, v_pile)


# ----------------------------------------------------------------- the loop
@njit(cache=True)
def run_blow(kind,
             ram_mass, ram_stiffness, ram_u, ram_v, ram_nsub,
             aP, aC, aS, anvil_nsub,
             pile, soil, probes, stress_factor, pu, pv, poff, pen, pile_nsub,
             pile_face0, gravity, t0, h, n_steps, record_every, out, energies, extremes):
    """Advance one blow of ``n_steps`` master steps of ``h`` [s] from t0 [s] (states in place).

    Records every ``record_every`` steps into ``out`` (COLUMNS) and ``energies``
    (ENERGY_COLUMNS); ``extremes`` collects [max compression, max tension] of the pile's
    springs [N]. ``pile_face0`` is the head face displacement of the static state, the
    reference of the anvil unit's pile input.
    """
    row = 0
    for n in range(n_steps + 1):
        # 1. states of the neighbours at t_n
        u_ram = ram_u[ram_u.shape[0] - 1]
        v_ram = ram_v[ram_v.shape[0] - 1]
        u_pile = head_displacement(probes, pu) - pile_face0
        v_pile = head_velocity(probes, pv)
        # 2. contact forces at t_n (feedthrough of the anvil unit)
        f_ram, f_pile, u_top, u_bottom = anvil_forces(kind, aP, aC, aS, u_ram, v_ram, u_pile,
                                                      v_pile)
        update_stress_extremes(stress_factor, pu, extremes)
        if n % record_every == 0:
            out[row, 0] = t0 + n * h
            out[row, 1] = f_ram
            out[row, 2] = f_pile
            out[row, 3] = v_pile
            out[row, 4] = gauge_force(pile, probes, pu, pv)
            out[row, 5] = gauge_velocity(probes, pv)
            out[row, 6] = v_ram
            out[row, 7] = u_top
            out[row, 8] = u_bottom
            out[row, 9] = u_pile + pile_face0
            out[row, 10] = toe_displacement(pu)
            kin, pot = anvil_energy(kind, aP, aC, aS, u_ram, v_ram, u_pile, v_pile)
            ke, se, pe = leapfrog_energies(ram_mass, ram_stiffness, ram_u, ram_v, gravity,
                                           h / ram_nsub)
            energies[row, 0] = ke
            energies[row, 1] = se
            energies[row, 2] = pe
            energies[row, 3] = kin
            energies[row, 4] = pot
            energies[row, 5] = pen[ENERGY_KINETIC]
            energies[row, 6] = pen[ENERGY_STRAIN]
            energies[row, 7] = pen[WORK_GRAVITY]
            energies[row, 8] = pen[WORK_SOIL_STATIC]
            energies[row, 9] = pen[WORK_SOIL_DAMPING]
            energies[row, 10] = pen[WORK_PILE_DAMPING]
            energies[row, 11] = pen[WORK_HEAD]
            energies[row, 12] = head_face_work(probes, pen)
            row += 1
        if n == n_steps:
            break
        # 3. every unit over [t_n, t_n+1] with the forces held
        ram_step(ram_mass, ram_stiffness, ram_u, ram_v, f_ram, gravity, h, ram_nsub)
        anvil_step(kind, aP, aC, aS, f_ram, f_pile, u_ram, v_ram, u_pile, v_pile, h, anvil_nsub)
        pile_step(pile, soil, pu, pv, poff, pen, f_pile, gravity, h, pile_nsub)
    return row


# ----------------------------------------------------------------- set-up
@dataclass
class AnvilKernels:
    """An anvil unit as kernel functions and arrays (P, C, S) with the common signature."""

    kind: str
    code: int
    P: np.ndarray
    C: np.ndarray
    S: np.ndarray
    u_top0: float
    stable_step: float
    n_sub: int = 1
    unit: object = None


@dataclass
class BlowResult:
    """Time series and summary of one simulated blow (columns: COLUMNS, ENERGY_COLUMNS)."""

    columns: dict[str, np.ndarray]
    energies: dict[str, np.ndarray]
    time_step: float
    n_steps: int
    wall_time: float
    input_energy: float
    pile_max_compression_stress: float
    pile_max_tension_stress: float
    final_state: dict = field(default_factory=dict)


@dataclass
class Engine:
    """The in-process engine for one system configuration and anvil model.

    Build it with :func:`build_engine`; :meth:`run` simulates consecutive blows.
    """

    config: SystemConfig
    anvil: AnvilKernels
    ram_mass: np.ndarray
    ram_stiffness: np.ndarray
    pile_arrays: object
    time_step: float
    limits: dict[str, float]
    modal: object = None

    def run(self, duration: float | None = None, record_interval: float | None = None,
            progress: bool = False) -> list[BlowResult]:
        """Simulate ``config.blows`` consecutive blows of ``duration`` [s] each.

        Each blow restarts the ram at its impact velocity on the anvil at rest; the pile keeps
        its permanent set and soil state from the previous blow.
        """
        cfg = self.config
        duration = cfg.duration if duration is None else duration
        record_interval = cfg.output_interval if record_interval is None else record_interval
        h = self.time_step
        n_steps = int(round(duration / h))
        record_every = 1 if record_interval is None else max(1, int(round(record_interval / h)))
        arrays = self.pile_arrays
        static_force = _static_pile_force(self.anvil, cfg.gravity)
        state = initial_state(arrays, head_force=static_force, gravity=cfg.gravity)
        pu, pv, poff, pen = (np.array(a) for a in state)
        results = []
        blows = range(cfg.blows)
        if progress and cfg.blows > 1:
            from tqdm import tqdm

            blows = tqdm(blows, desc="blows", unit="blow")
        for _ in blows:
            anvil = self._fresh_anvil()
            offset_start = poff.copy()
            face0 = head_displacement(arrays.probes, pu)
            # the ram starts half a step before the first contact (t0 = -h/2): with the
            # leapfrog's staggered velocities the first two displacement levels are then the
            # exact ones, and a chain meeting a chain at the Courant number 1 is exact
            t0 = -0.5 * h
            ram_u = np.full(self.ram_mass.shape, anvil.u_top0 + t0 * cfg.impact_velocity)
            ram_v = np.full(self.ram_mass.shape, cfg.impact_velocity)
            input_energy = 0.5 * self.ram_mass.sum() * cfg.impact_velocity**2
            n_rows = n_steps // record_every + 1
            out = np.zeros((n_rows, len(COLUMNS)))
            energies = np.zeros((n_rows, len(ENERGY_COLUMNS)))
            extremes = np.zeros(2)
            pile_nsub = substeps(h, pile_stable_time_step(arrays.pile, arrays.soil))
            ram_nsub = substeps(h, ram_stable_time_step(self.ram_mass, self.ram_stiffness))
            args = (anvil.code, self.ram_mass, self.ram_stiffness,
                    ram_u, ram_v, ram_nsub, anvil.P, anvil.C, anvil.S, anvil.n_sub,
                    arrays.pile, arrays.soil, arrays.probes,
                    cfg.pile_soil.stress_factors(), pu, pv, poff,
                    pen, pile_nsub,
                    face0, cfg.gravity, t0, h)
            _warm_up(args, out.shape[1], energies.shape[1])
            start = time.perf_counter()
            rows = run_blow(*args, n_steps, record_every, out, energies, extremes)
            wall = time.perf_counter() - start
            results.append(BlowResult(
                columns={name: out[:rows, i].copy() for i, name in enumerate(COLUMNS)},
                energies={name: energies[:rows, i].copy() for i, name in enumerate(ENERGY_COLUMNS)},
                time_step=h, n_steps=n_steps, wall_time=wall, input_energy=input_energy,
                pile_max_compression_stress=float(extremes[0]),
                pile_max_tension_stress=float(extremes[1]),
                final_state={"pile_u": pu.copy(), "soil_offset": poff.copy(),
                             "soil_offset_start": offset_start},
            ))
        return results

    def _fresh_anvil(self) -> AnvilKernels:
        return _anvil_kernels(self.config, self.ram_mass, self.pile_arrays, self.time_step,
                              self.modal)


def _warm_up(args, n_columns, n_energy) -> None:
    """Compile (or load from cache) the loop on copies, so the timing excludes compilation."""
    from .kernels import announce_compilation

    announce_compilation()
    copies = tuple(a.copy() if isinstance(a, np.ndarray) else a for a in args)
    run_blow(*copies, 1, 1, np.zeros((2, n_columns)), np.zeros((2, n_energy)), np.zeros(2))


def _static_pile_force(anvil: AnvilKernels, gravity: float) -> float:
    if anvil.kind == "none":
        return 0.0
    if anvil.kind == "classic":
        return anvil.unit.static_pile_force(gravity)
    return anvil.unit.anvil.total_mass * gravity


def _anvil_kernels(cfg: SystemConfig, ram_mass, pile_arrays, h, modal) -> AnvilKernels:
    settings = cfg.anvil
    if settings.model == "none":
        # ram toe and pile head: the two contact springs in series (ram_contact_damping acts)
        contact = _contact(cfg)
        k = 1.0 / (1.0 / contact.ram_stiffness + 1.0 / contact.pile_stiffness)
        P = np.array([k, contact.ram_damping])
        limit = coupled_stable_time_step(ram_mass, cfg.hammer.ram.stiffness, k, k, pile_arrays)
        return AnvilKernels("none", UNIT_NONE, P,
                            np.zeros((1, 1)), np.zeros(1), 0.0, float(limit), 1, None)
    if settings.model == "classic":
        ds = settings.classic
        P = ds.parameters(cfg.gravity)
        S = ds.initial_state(P)
        limit = min(driving_system_stable_time_step(P),
                    interface_time_step(P, ram_mass[-1], pile_arrays.pile[0, 0]))
        n_sub = 1 if h is None else max(1, int(np.ceil(h / driving_system_stable_time_step(P))))
        return AnvilKernels("classic", UNIT_CLASSIC, P,
                            np.zeros((1, 1)), S, 0.0, limit, n_sub, ds)
    if settings.model == "rom":
        try:
            rom = ModalAnvil.from_modal_data(modal, fmax=settings.fmax,
                                             damping_ratio=settings.damping_ratio,
                                             static_correction=settings.static_correction,
                                             source=cfg.source)
        except InputError as exc:
            raise InputError(cfg.source, f"anvil.{exc.key}", exc.rule) from None
    else:
        rom = ModalAnvil.rigid(settings.mass if settings.mass is not None else modal.total_mass)
    unit = AnvilUnit(rom, _contact(cfg), gravity=cfg.gravity)
    u_top0, _ = unit.rest_on_pile(0.0)
    limit = coupled_stable_time_step(ram_mass, cfg.hammer.ram.stiffness,
                                     unit.contact.ram_stiffness, unit.contact.pile_stiffness,
                                     pile_arrays, rom.participation_ram, rom.participation_pile)
    if h is not None:
        unit.set_step(h)
    return AnvilKernels(settings.model, UNIT_MODAL, unit.P, unit.C,
                        unit.S, u_top0, limit, 1, unit)


def contact_stiffnesses(cfg: SystemConfig) -> tuple[float, float]:
    """Default (ram, pile) contact stiffnesses [N/m]: the half segments of the neighbours.

    The ram toe mass and the pile top mass sit half a segment from the faces they touch, so the
    contact springs are those half segments, 2 E A / dx (Smith 1960); a value in the system file
    replaces them (e.g. a cushion). A rigid ram has no half segment: its contact stiffness must
    be given.
    """
    s = cfg.anvil
    k_pile = s.pile_contact_stiffness or cfg.pile_soil.head_contact_stiffness()
    k_ram = s.ram_contact_stiffness
    if k_ram is None:
        k_ram = cfg.hammer.ram.toe_stiffness
        if not np.isfinite(k_ram):
            raise InputError(cfg.source, "anvil.ram_contact_stiffness",
                             "is required with a rigid ram or a ram given as explicit segments "
                             "(there is no toe half segment to take it from)")
    return float(k_ram), float(k_pile)


def _contact(cfg: SystemConfig) -> ContactParameters:
    s = cfg.anvil
    k_ram, k_pile = contact_stiffnesses(cfg)
    return ContactParameters(k_ram, k_pile, s.ram_contact_damping, s.pile_contact_damping)


def build_engine(cfg: SystemConfig, modal=None) -> Engine:
    """Assemble the components of a system (computing the anvil modes when needed).

    modal : precomputed ModalData of the anvil (else computed from the anvil file).
    """
    ram = cfg.hammer.ram
    ram_mass = np.ascontiguousarray(ram.mass, dtype=float)
    ram_stiffness = np.ascontiguousarray(ram.stiffness, dtype=float)
    arrays = cfg.pile_soil.arrays()
    if cfg.anvil.model in ("rom", "lumped") and modal is None:
        try:
            modal = compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax).modal_data
        except InputError as exc:
            if exc.key != "fmax" or cfg.anvil.fmax is None:
                raise
            raise InputError(cfg.source, "anvil.fmax", exc.rule) from None
    probe = _anvil_kernels(cfg, ram_mass, arrays, None, modal)
    limits = {
        "ram": float(ram_stable_time_step(ram_mass, ram_stiffness)),
        "pile": float(pile_stable_time_step(arrays.pile, arrays.soil)),
        "anvil coupling": float(probe.stable_step),
    }
    if cfg.anvil.model == "rom":
        fmax = probe.unit.anvil.fmax
        limits["anvil fmax sampling"] = 1.0 / (STEPS_PER_PERIOD_AT_FMAX * fmax)
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
    return Engine(cfg, probe, ram_mass, ram_stiffness, arrays, float(h), limits, modal)
