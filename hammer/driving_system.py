"""The classic driving system of Smith-type wave-equation programs (the "lumped-mass anvil").

    ram toe --[hammer cushion]-- helmet / anvil mass --[pile cushion]-- pile head
                                      |
                        [assembly contact] -- hammer assembly mass (resting on the helmet)

Both cushions are compression-only springs with Smith's restitution law and optional round-out
(:mod:`hammer.cushion`); the helmet (anvil plus inserts) is one rigid mass; the hammer assembly
(housing, sleeve) rests on it through a compression-only elastic contact, so it adds its weight
and can lift off. Without a pile cushion the helmet bears on the pile through an elastic
steel contact of given stiffness (a cushion with e = 1). This is the driving-system model of
Smith (1960), Hirsch et al. (1970) and GRLWEAP (Pile Dynamics, GRLWEAP background report).

As an anvilwave component it has the interface of the Anvil unit of DESIGN.md: inputs are the
ram toe (u_ram, v_ram) and the pile head (u_pile, v_pile), outputs the forces on them, F_ram
(compression, pushes the ram up) and F_pile (compression, pushes the pile down), and u_top =
u_bottom = the helmet displacement. Its own state is the helmet and assembly motion and the
largest compression of each cushion.

Displacements are measured from the configuration at t = 0 (first ram contact). The cushion
compression is c = c_0 + (u_upper - u_lower), where c_0 is the static compression at t = 0: 0 for
the hammer cushion (the ram just touches), the compressions under the weight of helmet and
assembly for the pile cushion and the assembly contact (the system starts in static
equilibrium on the pile head, so the pile head carries (m_helmet + m_assembly) g at t = 0).

Arrays (float64) used by the kernels: ``params`` with the P_* layout, ``state`` with the S_*
layout below; build them with :meth:`DrivingSystem.parameters` and
:meth:`DrivingSystem.initial_state`.

References
----------
Smith, E.A.L. (1960). Pile-driving analysis by the wave equation. J. Soil Mech. Found. Div.,
    ASCE, 86(SM4), 35-61.
Hirsch, T.J., Lowery, L.L., Coyle, H.M. & Samson, C.H. (1970). Pile-driving analysis by
    one-dimensional wave theory: state of the art. Highway Research Record 333, 33-54.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from anvilwave_inputs import Table

from .cushion import cushion_force, loading_compression, recoverable_energy
from .impact import GRAVITY
from .ram import stable_time_step

# parameter array layout
P_HC_STIFFNESS = 0  # hammer cushion loading stiffness [N/m]
P_HC_RESTITUTION = 1  # hammer cushion coefficient of restitution [-]
P_HC_ROUND_OUT = 2  # hammer cushion round-out compression [m]
P_HC_PRECOMPRESSION = 3  # hammer cushion compression at t = 0 [m]
P_PC_STIFFNESS = 4  # pile cushion (or helmet-pile contact) stiffness [N/m]
P_PC_RESTITUTION = 5  # pile cushion restitution [-]
P_PC_ROUND_OUT = 6  # pile cushion round-out [m]
P_PC_PRECOMPRESSION = 7  # pile cushion compression at t = 0 [m]
P_HELMET_MASS = 8  # helmet / anvil mass [kg]
P_ASSEMBLY_MASS = 9  # hammer assembly mass resting on the helmet [kg] (0: none)
P_ASSEMBLY_STIFFNESS = 10  # assembly-helmet contact stiffness [N/m]
P_ASSEMBLY_PRECOMPRESSION = 11  # assembly contact compression at t = 0 [m]
P_GRAVITY = 12  # gravitational acceleration [m/s^2]
N_PARAMS = 13

# state array layout
S_HELMET_U = 0  # helmet displacement [m]
S_HELMET_V = 1  # helmet velocity [m/s]
S_ASSEMBLY_U = 2  # assembly displacement [m]
S_ASSEMBLY_V = 3  # assembly velocity [m/s]
S_HC_MAX = 4  # largest hammer cushion compression so far [m]
S_PC_MAX = 5  # largest pile cushion compression so far [m]
N_STATE = 6


@dataclass(frozen=True)
class Cushion:
    """A compression-only cushion (or contact) with restitution and round-out.

    Attributes
    ----------
    stiffness : float
        Loading stiffness k [N/m] (E A / t of the cushion material).
    restitution : float
        Coefficient of restitution e [-], 0 < e <= 1.
    round_out : float
        Round-out compression r [m] (0: linear from first contact).
    """

    stiffness: float
    restitution: float = 1.0
    round_out: float = 0.0

    def __post_init__(self):
        if not (self.stiffness > 0.0 and math.isfinite(self.stiffness)):
            raise ValueError("cushion stiffness must be finite and greater than 0 N/m")
        if not 0.0 < self.restitution <= 1.0:
            raise ValueError("cushion restitution must be in (0, 1]")
        if not (self.round_out >= 0.0 and math.isfinite(self.round_out)):
            raise ValueError("cushion round_out must be at least 0 m")

    @classmethod
    def from_table(cls, table: Table) -> Cushion:
        """Keys: ``stiffness`` [N/m], or ``area`` [m^2] + ``elastic_modulus`` [Pa] +
        ``thickness`` [m] (k = E A / t); ``restitution`` [-]; ``round_out`` [m] (0)."""
        material_keys = ("area", "elastic_modulus", "thickness")
        if table.has("stiffness"):
            for key in material_keys:
                if table.has(key):
                    raise table.error(key, "cannot be given together with stiffness")
            stiffness = table.number("stiffness", gt=0, unit="N/m")
        else:
            if not any(table.has(key) for key in material_keys):
                raise table.error("stiffness", "is required (or area, elastic_modulus and "
                                  "thickness of the cushion material)")
            area = table.number("area", gt=0, unit="m^2")
            modulus = table.number("elastic_modulus", gt=0, unit="Pa")
            thickness = table.number("thickness", gt=0, unit="m")
            stiffness = modulus * area / thickness
        restitution = table.number("restitution", gt=0, le=1)
        round_out = table.number("round_out", 0.0, ge=0, unit="m")
        table.finish()
        return cls(stiffness, restitution, round_out)


@dataclass(frozen=True)
class DrivingSystem:
    """Hammer cushion, helmet (+ resting assembly) and pile cushion between ram and pile.

    Attributes
    ----------
    hammer_cushion : Cushion
        Between ram toe and helmet.
    helmet_mass : float
        Helmet / anvil mass including striker plate and inserts [kg].
    pile_cushion : Cushion
        Between helmet and pile head; without a pile cushion the elastic helmet-pile contact
        (restitution 1, no round-out), see ``has_pile_cushion``.
    assembly_mass : float
        Hammer assembly mass resting on the helmet [kg] (0: none).
    assembly_stiffness : float
        Stiffness of the compression-only assembly-helmet contact [N/m].
    has_pile_cushion : bool
        False when ``pile_cushion`` stands for the bare steel contact.
    """

    hammer_cushion: Cushion
    helmet_mass: float
    pile_cushion: Cushion
    assembly_mass: float = 0.0
    assembly_stiffness: float = 0.0
    has_pile_cushion: bool = True

    def __post_init__(self):
        if not (self.helmet_mass > 0.0 and math.isfinite(self.helmet_mass)):
            raise ValueError("helmet_mass must be finite and greater than 0 kg")
        if not (self.assembly_mass >= 0.0 and math.isfinite(self.assembly_mass)):
            raise ValueError("assembly_mass must be at least 0 kg")
        if self.assembly_mass > 0.0 and not (self.assembly_stiffness > 0.0
                                             and math.isfinite(self.assembly_stiffness)):
            raise ValueError("assembly_stiffness must be greater than 0 N/m with an assembly")

    @classmethod
    def from_table(cls, table: Table) -> DrivingSystem:
        """Read a driving system from a TOML table.

        Keys: ``helmet_mass`` [kg]; ``assembly_mass`` [kg] (0) with ``assembly_stiffness``
        [N/m]; table ``hammer_cushion`` (see :meth:`Cushion.from_table`); table ``pile_cushion``
        or, without it, ``pile_contact_stiffness`` [N/m].
        """
        helmet_mass = table.number("helmet_mass", gt=0, unit="kg")
        assembly_mass = table.number("assembly_mass", 0.0, ge=0, unit="kg")
        if assembly_mass > 0.0:
            assembly_stiffness = table.number("assembly_stiffness", gt=0, unit="N/m")
        else:
            assembly_stiffness = 0.0
            if table.has("assembly_stiffness"):
                raise table.error("assembly_stiffness", "needs an assembly_mass above 0 kg")
        hammer_cushion = Cushion.from_table(table.table("hammer_cushion"))
        if table.has("pile_cushion"):
            if table.has("pile_contact_stiffness"):
                raise table.error("pile_contact_stiffness",
                                  "cannot be given together with a pile_cushion")
            pile_cushion = Cushion.from_table(table.table("pile_cushion"))
            has_pile_cushion = True
        else:
            stiffness = table.number("pile_contact_stiffness", gt=0, unit="N/m")
            pile_cushion = Cushion(stiffness, 1.0, 0.0)
            has_pile_cushion = False
        table.finish()
        return cls(hammer_cushion, helmet_mass, pile_cushion, assembly_mass,
                   assembly_stiffness, has_pile_cushion)

    def static_pile_force(self, gravity: float = GRAVITY) -> float:
        """Force on the pile head at rest, (m_helmet + m_assembly) g [N]; gravity [m/s^2]."""
        return (self.helmet_mass + self.assembly_mass) * gravity

    def parameters(self, gravity: float = GRAVITY) -> np.ndarray:
        """The float64 parameter array (P_* layout) for the kernels; gravity [m/s^2]."""
        p = np.zeros(N_PARAMS)
        hc, pc = self.hammer_cushion, self.pile_cushion
        p[P_HC_STIFFNESS] = hc.stiffness
        p[P_HC_RESTITUTION] = hc.restitution
        p[P_HC_ROUND_OUT] = hc.round_out
        p[P_HC_PRECOMPRESSION] = 0.0
        p[P_PC_STIFFNESS] = pc.stiffness
        p[P_PC_RESTITUTION] = pc.restitution
        p[P_PC_ROUND_OUT] = pc.round_out
        p[P_PC_PRECOMPRESSION] = loading_compression(self.static_pile_force(gravity),
                                                     pc.stiffness, pc.round_out)
        p[P_HELMET_MASS] = self.helmet_mass
        p[P_ASSEMBLY_MASS] = self.assembly_mass
        p[P_ASSEMBLY_STIFFNESS] = self.assembly_stiffness
        if self.assembly_mass > 0.0:
            p[P_ASSEMBLY_PRECOMPRESSION] = self.assembly_mass * gravity / self.assembly_stiffness
        p[P_GRAVITY] = gravity
        return p

    @staticmethod
    def initial_state(params: np.ndarray) -> np.ndarray:
        """The float64 state array (S_* layout) at t = 0: at rest, cushions at their
        static compression."""
        state = np.zeros(N_STATE)
        state[S_HC_MAX] = params[P_HC_PRECOMPRESSION]
        state[S_PC_MAX] = params[P_PC_PRECOMPRESSION]
        return state


# --------------------------------------------------------------------------- kernels
@njit(cache=True)
def _forces(params, u_helmet, u_assembly, u_ram, u_pile, hc_max, pc_max):
    """(F_hammer_cushion, F_pile_cushion, F_assembly, c_hc, c_pc) at one instant."""
    c_hc = params[P_HC_PRECOMPRESSION] + u_ram - u_helmet
    f_hc = cushion_force(c_hc, hc_max, params[P_HC_STIFFNESS], params[P_HC_RESTITUTION],
                         params[P_HC_ROUND_OUT])
    c_pc = params[P_PC_PRECOMPRESSION] + u_helmet - u_pile
    f_pc = cushion_force(c_pc, pc_max, params[P_PC_STIFFNESS], params[P_PC_RESTITUTION],
                         params[P_PC_ROUND_OUT])
    f_as = 0.0
    if params[P_ASSEMBLY_MASS] > 0.0:
        c_as = params[P_ASSEMBLY_PRECOMPRESSION] + u_assembly - u_helmet
        if c_as > 0.0:
            f_as = params[P_ASSEMBLY_STIFFNESS] * c_as
    return f_hc, f_pc, f_as, c_hc, c_pc


@njit(cache=True)
def driving_system_forces(params, state, u_ram, v_ram, u_pile, v_pile):
    """Outputs at the current instant (feedthrough): (F_ram, F_pile, u_top, u_bottom).

    F_ram : hammer cushion force on the ram toe [N], compression positive (pushes the ram up).
    F_pile : pile cushion force on the pile head [N], compression positive (pushes it down).
    u_top, u_bottom : helmet displacement [m] (a rigid helmet: both the same).
    The velocities are part of the interface but not used (no cushion dashpots).
    The state is not changed.
    """
    f_hc, f_pc, f_as, c_hc, c_pc = _forces(params, state[S_HELMET_U], state[S_ASSEMBLY_U],
                                           u_ram, u_pile, state[S_HC_MAX], state[S_PC_MAX])
    return f_hc, f_pc, state[S_HELMET_U], state[S_HELMET_U]


@njit(cache=True)
def driving_system_step(params, state, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    """Advance helmet, assembly and cushion memory over a step h [s] (in place on state).

    The ram toe and pile head move with the given velocities during the step,
    u_ram(t_n + s) = u_ram + v_ram s (and likewise the pile), and the helmet and assembly are
    integrated with n_sub velocity-Verlet sub-steps (h / n_sub below
    :func:`driving_system_stable_time_step`). The largest cushion compressions are updated
    after every sub-step.

    Parameters
    ----------
    params : (N_PARAMS,) parameter array. state : (N_STATE,) state array.
    u_ram, v_ram : ram toe displacement [m] and velocity [m/s] at the start of the step.
    u_pile, v_pile : pile head displacement [m] and velocity [m/s] at the start of the step.
    h : step [s]. n_sub : number of sub-steps.
    """
    dt = h / n_sub
    m_h = params[P_HELMET_MASS]
    m_a = params[P_ASSEMBLY_MASS]
    g = params[P_GRAVITY]
    u_h = state[S_HELMET_U]
    v_h = state[S_HELMET_V]
    u_a = state[S_ASSEMBLY_U]
    v_a = state[S_ASSEMBLY_V]
    hc_max = state[S_HC_MAX]
    pc_max = state[S_PC_MAX]
    f_hc, f_pc, f_as, c_hc, c_pc = _forces(params, u_h, u_a, u_ram, u_pile, hc_max, pc_max)
    hc_max = max(hc_max, c_hc)
    pc_max = max(pc_max, c_pc)
    for s in range(n_sub):
        a_h = g + (f_hc - f_pc + f_as) / m_h
        v_h += 0.5 * dt * a_h
        u_h += dt * v_h
        if m_a > 0.0:
            v_a += 0.5 * dt * (g - f_as / m_a)
            u_a += dt * v_a
        t = (s + 1) * dt
        f_hc, f_pc, f_as, c_hc, c_pc = _forces(params, u_h, u_a, u_ram + v_ram * t,
                                               u_pile + v_pile * t, hc_max, pc_max)
        hc_max = max(hc_max, c_hc)
        pc_max = max(pc_max, c_pc)
        v_h += 0.5 * dt * (g + (f_hc - f_pc + f_as) / m_h)
        if m_a > 0.0:
            v_a += 0.5 * dt * (g - f_as / m_a)
    state[S_HELMET_U] = u_h
    state[S_HELMET_V] = v_h
    state[S_ASSEMBLY_U] = u_a
    state[S_ASSEMBLY_V] = v_a
    state[S_HC_MAX] = hc_max
    state[S_PC_MAX] = pc_max


@njit(cache=True)
def driving_system_stable_time_step(params):
    """Stable sub-step [s] for the helmet and assembly with ram and pile held: 2 / omega_max.

    omega_max^2 is bounded (Gershgorin) with the stiffest branch of each cushion, the
    unloading line k / e^2: helmet row (k_hc / e_hc^2 + k_pc / e_pc^2 + k_a) / m_h
    + k_a / sqrt(m_h m_a), assembly row k_a / m_a + k_a / sqrt(m_h m_a).
    """
    m_h = params[P_HELMET_MASS]
    m_a = params[P_ASSEMBLY_MASS]
    k_hc = params[P_HC_STIFFNESS] / params[P_HC_RESTITUTION] ** 2
    k_pc = params[P_PC_STIFFNESS] / params[P_PC_RESTITUTION] ** 2
    omega2 = (k_hc + k_pc) / m_h
    if m_a > 0.0:
        k_a = params[P_ASSEMBLY_STIFFNESS]
        coupling = k_a / math.sqrt(m_h * m_a)
        omega2 = max((k_hc + k_pc + k_a) / m_h + coupling, k_a / m_a + coupling)
    return 2.0 / math.sqrt(omega2)


@njit(cache=True)
def driving_system_energy(params, state, u_ram, u_pile):
    """(kinetic, recoverable strain, gravity potential) energy of the driving system [J].

    kinetic: helmet and assembly; recoverable strain: what the cushions and the assembly
    contact give back if unloaded (e^2 F^2 / (2 k) per cushion, F^2 / (2 k_a)); gravity
    potential: -g (m_h u_h + m_a u_a), relative to t = 0. The energy dissipated by the cushions
    is the work done on the system minus the change of these terms.
    """
    m_h = params[P_HELMET_MASS]
    m_a = params[P_ASSEMBLY_MASS]
    u_h = state[S_HELMET_U]
    u_a = state[S_ASSEMBLY_U]
    kinetic = 0.5 * m_h * state[S_HELMET_V] ** 2 + 0.5 * m_a * state[S_ASSEMBLY_V] ** 2
    f_hc, f_pc, f_as, c_hc, c_pc = _forces(params, u_h, u_a, u_ram, u_pile,
                                           state[S_HC_MAX], state[S_PC_MAX])
    strain = (recoverable_energy(f_hc, params[P_HC_STIFFNESS], params[P_HC_RESTITUTION])
              + recoverable_energy(f_pc, params[P_PC_STIFFNESS], params[P_PC_RESTITUTION]))
    if m_a > 0.0:
        strain += recoverable_energy(f_as, params[P_ASSEMBLY_STIFFNESS], 1.0)
    potential = -params[P_GRAVITY] * (m_h * u_h + m_a * u_a)
    return kinetic, strain, potential


def interface_time_step(params: np.ndarray, ram_toe_mass: float, pile_head_mass: float) -> float:
    """Estimate of the largest stable communication step [s] of the explicit coupling.

    The master holds the contact forces over a step, which for the ram toe and the pile head
    acts like an explicit step of the chain ram toe -- hammer cushion -- helmet -- pile cushion
    -- pile head (stiffest cushion branches k / e^2). Returns 2 / omega_max of that chain
    (Gershgorin bound, as :func:`hammer.ram.stable_time_step`), never above the driving
    system's own stable sub-step. A guide, not a proof: use a safety factor.

    Parameters
    ----------
    params : parameter array. ram_toe_mass : mass of the ram's toe node [kg].
    pile_head_mass : mass of the pile's head node [kg].
    """
    mass = np.array([ram_toe_mass, params[P_HELMET_MASS], pile_head_mass], dtype=np.float64)
    stiffness = np.array([params[P_HC_STIFFNESS] / params[P_HC_RESTITUTION] ** 2,
                          params[P_PC_STIFFNESS] / params[P_PC_RESTITUTION] ** 2])
    return min(float(stable_time_step(mass, stiffness)),
               float(driving_system_stable_time_step(params)))
