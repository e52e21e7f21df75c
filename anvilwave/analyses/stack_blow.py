"""One blow of a system with the driving stack (:class:`anvilwave.anvil_rom.stack.StackUnit`),
stepped in-process in DESIGN.md's coupling order, step by step in Python: the reference the
engine's compiled blow loop is checked against (``tests/test_stack_system.py``), and the
comparison with the reference FEA stack (``benchmarks/study_anvil_ring.py``). It is the slow
path: ``anvilwave impact`` and ``drive`` run the stack in the engine's loop
(:func:`anvilwave.engine.direct.run_blow`).

The ram is the system's modal ram unit (:class:`anvilwave.hammer.modal_ram.ModalRamUnit`), the
pile/soil the pile unit's kernel (:class:`anvilwave.fmu.units.pile_soil.PileSoilState`), the
anvil any unit with ``forces``/``step``/``rest_on_pile``/``energy`` (the stack, or the anvil
unit itself). From t_n to t_n+1: read the ram toe and the pile head (states), the anvil unit's
two contact forces (feedthrough, at t_n), then every unit steps over h with its force held.
The ram starts half a step before the first contact, as the engine's blow. The stack itself is
built by :func:`anvilwave.engine.anvils.stack_unit` (named here too).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from anvilwave.config.system import SystemConfig
from anvilwave.engine.anvils import (
    PILE_RINGS,
    RAM_ANNULI,
    SEAT_RINGS,
    cached_stack_data,
    stack_faces,
    stack_unit,
    with_ram_annuli,
)
from anvilwave.fmu.units.pile_soil import PileSoilState, pile_outputs
from anvilwave.hammer.modal_ram import ModalRamUnit

__all__ = ["PILE_RINGS", "RAM_ANNULI", "SEAT_RINGS", "StackBlow", "cached_stack_data",
           "run_stack_blow", "stack_faces", "stack_unit", "unit_losses", "with_ram_annuli"]


@dataclasses.dataclass
class StackBlow:
    """Records of one blow (every step).

    Parameters
    ----------
    time : numpy.ndarray
        t_n [s], 0 half a step before the first contact.
    ram_force : numpy.ndarray
        Ram-anvil contact force [N].
    pile_force : numpy.ndarray
        Force into the pile head [N].
    energy_residual : numpy.ndarray
        Energy balance of the anvil unit, (E_n + D_n - E_0 - W_n) [J]: its energy, the
        friction and dashpot dissipation, the work the ram and the pile did on it.
    friction_energy : float
        Energy the seat friction dissipated [J].
    input_energy : float
        The ram's kinetic energy at impact [J].
    """

    time: np.ndarray
    ram_force: np.ndarray
    pile_force: np.ndarray
    energy_residual: np.ndarray
    friction_energy: float
    input_energy: float


def run_stack_blow(cfg: SystemConfig, unit, h: float | None = None,
                   duration: float | None = None) -> StackBlow:
    """One blow of ``cfg`` with ``unit`` as the anvil, at the fixed step ``h``.

    Parameters
    ----------
    cfg : SystemConfig
        The system (a modal ram).
    unit : StackUnit or AnvilUnit
        The anvil unit (``forces``, ``step``, ``set_step``, ``rest_on_pile``, ``energy``).
    h : float, optional
        Step [s]; default the system's ``time_step``.
    duration : float, optional
        Window [s]; default the system's.

    Returns
    -------
    StackBlow
        The records.
    """
    h = float(cfg.time_step if h is None else h)
    duration = float(cfg.duration if duration is None else duration)
    n = int(round(duration / h))
    unit.set_step(h)
    weight = unit.total_mass * cfg.gravity if hasattr(unit, "total_mass") \
        else unit.anvil.total_mass * cfg.gravity
    pile = PileSoilState(cfg.pile_soil, weight, cfg.gravity)
    u_top0, _ = unit.rest_on_pile(0.0)
    modes = getattr(unit, "ram_modes", None)  # the stack's ram face's, where it has one
    ram = ModalRamUnit(cfg.hammer.ram.modes if modes is None else modes, cfg.gravity)
    velocity = float(cfg.impact_velocity)
    ram.start(u_top0 - 0.5 * h * velocity, velocity, h)
    mass = float(ram.modes.total_mass)
    time = np.arange(n) * h
    f_ram = np.empty(n)
    f_pile = np.empty(n)
    residual = np.empty(n)
    arrays = pile.arrays
    work = 0.0
    e0 = None
    u_r, v_r = float(ram.toe[0]), float(ram.toe[1])
    out = pile_outputs(arrays.pile, arrays.probes, pile.u, pile.v, pile.face0)
    u_p, v_p = out[0], out[1]
    for i in range(n):
        fr, fp = unit.forces(u_r, v_r, u_p, v_p)
        f_ram[i], f_pile[i] = fr, fp
        energy = sum(unit.energy(u_r, v_r, u_p, v_p)) + unit_losses(unit)
        if e0 is None:
            e0 = energy
        residual[i] = energy - e0 - work
        unit.step(fr, fp, h)
        ram.step(fr)
        pile.step(fp, h)
        u_r1, v_r1 = float(ram.toe[0]), float(ram.toe[1])
        out = pile_outputs(arrays.pile, arrays.probes, pile.u, pile.v, pile.face0)
        # F_n against (u_n+1 - u_n-1) / 2: the central-difference scheme's work pairing
        work += 0.5 * h * (fr * (v_r1 + v_r) - fp * (out[1] + v_p))
        u_r, v_r, u_p, v_p = u_r1, v_r1, out[0], out[1]
    friction = float(getattr(unit, "friction_energy", 0.0))
    return StackBlow(time, f_ram, f_pile, residual, friction, 0.5 * mass * velocity**2)


def unit_losses(unit) -> float:
    """Friction and dashpot dissipation an anvil unit has booked so far [J].

    Parameters
    ----------
    unit : StackUnit or AnvilUnit
        The unit.

    Returns
    -------
    float
        Dissipated energy [J] (0 for a unit that books none).
    """
    return float(getattr(unit, "friction_energy", 0.0) + getattr(unit, "dashpot_work", 0.0))
