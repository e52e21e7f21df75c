"""The classic driving system of Smith-type wave-equation programs: cushions and helmet.

    ram toe --[ram bottom spring + hammer cushion || hammer damping]-- helmet / anvil mass
                                                                         |        |
           assembly mass 0 --[k_0]-- ... -- mass n-1 --[assembly contact]-        |
                                                                   [pile cushion or contact]
                                                                              pile head

Both cushions are compression-only springs with Smith's restitution law and optional round-out
(:mod:`anvilwave.hammer.cushion`); the helmet (anvil plus inserts) is one rigid mass; the hammer
assembly (housing, sleeve) is a chain of n masses (top first) joined by linear springs, whose
lowest mass rests on the helmet through a compression-only contact with its own restitution and
round-out, so it adds its weight and can lift off (n = 1 is the single assembly mass of the
classic model).
Without a pile cushion the helmet bears on the pile through a steel contact of given stiffness
(GRLWEAP: E A / dx of the first pile segment), with a restitution and round-out of its own
(default 1 and 0: elastic and linear). This is the driving-system model of Smith (1960),
Hirsch et al. (1970) and GRLWEAP (Pile Dynamics 2010).

GRLWEAP's hammer model adds two rules, both optional here (without them the model is the
classic one, number for number):

* Ram bottom spring in series with the hammer cushion. A ram given by segment masses and the
  springs between them (no lengths, :meth:`anvilwave.hammer.ram.RamRod.from_segments`) has no toe
  half segment; GRLWEAP's hammer file gives the spring below its last segment, and that spring acts
  in series with the hammer cushion. The two form one spring of stiffness
  1 / (1 / k_ram_bottom + 1 / k_cushion) (:func:`series_stiffness`) to which the cushion's
  restitution and round-out apply (they describe the combination, as in GRLWEAP); the cushion
  law acts between the ram's toe mass and the helmet.
* Hammer damping: a dashpot c [N s/m] in parallel with that (combined) hammer cushion, given
  or by GRLWEAP's rule (:func:`grlweap_2010_hammer_damping`). It acts only while the cushion
  carries load (its spring force is above 0; a separated or unloaded cushion transmits
  nothing), and the cushion's total force never becomes tension: F = max(0, F_spring +
  c (v_ram - v_helmet)). Its end-of-step force is taken implicitly in the helmet's velocity
  (the velocity-Verlet half kick solved for it), the same force it gives the ram.

As an anvilwave component it has the interface of the Anvil unit of DESIGN.md: inputs are the
ram toe (u_ram, v_ram) and the pile head (u_pile, v_pile), outputs the forces on them, F_ram
(compression, pushes the ram up) and F_pile (compression, pushes the pile down), and u_top =
u_bottom = the helmet displacement. Its own state is the helmet and assembly motion, the
largest compression of each Smith-law spring and the work done by the hammer damping.

Displacements are measured from the configuration at t = 0 (first ram contact). A spring's
compression is c = c_0 + (u_upper - u_lower), where c_0 is the static compression at t = 0:
0 for the hammer cushion (the ram just touches), the compressions under the weight of helmet
and assembly for the pile cushion, the assembly contact and the springs inside the assembly
(the system starts in static equilibrium on the pile head, so the pile head carries
(m_helmet + sum m_assembly) g at t = 0).

Arrays (float64) used by the kernels: ``params`` with the P_* layout, ``state`` with the S_*
layout below; build them with :meth:`DrivingSystem.parameters` and
:meth:`DrivingSystem.initial_state`. With n assembly masses (n >= 1) ``params`` holds after
its N_PARAMS header the masses (n, top first), the springs between them (n - 1) and their
static compressions (n - 1): length N_PARAMS + 3 n - 2; ``state`` holds after its N_STATE
header u, v of the masses above the lowest one (the lowest is at S_ASSEMBLY_U, S_ASSEMBLY_V):
length N_STATE + 2 (n - 1).

References
----------
Smith, E.A.L. (1960). Pile-driving analysis by the wave equation. J. Soil Mech. Found. Div.,
    ASCE, 86(SM4), 35-61.
Hirsch, T.J., Lowery, L.L., Coyle, H.M. & Samson, C.H. (1970). Pile-driving analysis by
    one-dimensional wave theory: state of the art. Highway Research Record 333, 33-54.
Pile Dynamics, Inc. (2010). GRLWEAP background report (wave equation analysis of pile
    driving). Cleveland, Ohio.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from anvilwave.hammer.cushion import (
    cushion_force,
    hysteresis_loss,
    loading_compression,
    recoverable_energy,
)
from anvilwave.hammer.impact import GRAVITY
from anvilwave.hammer.ram import stable_time_step
from anvilwave.inputs import Table

# parameter array layout (header)
P_HC_STIFFNESS = 0  # hammer cushion loading stiffness [N/m], in series with the ram bottom spring
P_HC_RESTITUTION = 1  # hammer cushion coefficient of restitution [-]
P_HC_ROUND_OUT = 2  # hammer cushion round-out compression [m]
P_HC_PRECOMPRESSION = 3  # hammer cushion compression at t = 0 [m]
P_PC_STIFFNESS = 4  # pile cushion (or helmet-pile contact) stiffness [N/m]
P_PC_RESTITUTION = 5  # pile cushion restitution [-]
P_PC_ROUND_OUT = 6  # pile cushion round-out [m]
P_PC_PRECOMPRESSION = 7  # pile cushion compression at t = 0 [m]
P_HELMET_MASS = 8  # helmet / anvil mass [kg]
P_ASSEMBLY_MASS = 9  # lowest assembly mass, resting on the helmet [kg] (0: no assembly)
P_ASSEMBLY_STIFFNESS = 10  # assembly-helmet contact stiffness [N/m]
P_ASSEMBLY_PRECOMPRESSION = 11  # assembly contact compression at t = 0 [m]
P_GRAVITY = 12  # gravitational acceleration [m/s^2]
P_HAMMER_DAMPING = 13  # dashpot parallel to the hammer cushion [N s/m]
P_ASSEMBLY_RESTITUTION = 14  # assembly contact restitution [-]
P_ASSEMBLY_ROUND_OUT = 15  # assembly contact round-out [m]
P_N_ASSEMBLY = 16  # number of assembly masses n (0: none)
P_RAM_BOTTOM_STIFFNESS = 17  # ram bottom spring [N/m] (inf: none), already in P_HC_STIFFNESS
N_PARAMS = 18
P_ASSEMBLY_CHAIN = N_PARAMS  # masses (n), springs (n - 1), their static compressions (n - 1)

# state array layout (header)
S_HELMET_U = 0  # helmet displacement [m]
S_HELMET_V = 1  # helmet velocity [m/s]
S_ASSEMBLY_U = 2  # displacement of the lowest assembly mass [m]
S_ASSEMBLY_V = 3  # velocity of the lowest assembly mass [m/s]
S_HC_MAX = 4  # largest hammer cushion compression so far [m]
S_PC_MAX = 5  # largest pile cushion compression so far [m]
S_AS_MAX = 6  # largest assembly contact compression so far [m]
S_DAMPING_WORK = 7  # work dissipated by the hammer damping since t = 0 [J]
N_STATE = 8
S_ASSEMBLY_CHAIN = N_STATE  # u, v of the assembly masses above the lowest one, top first


def series_stiffness(*stiffnesses: float) -> float:
    """Stiffness [N/m] of springs in series, 1 / sum(1 / k_i) (an infinite k_i drops out).

    The ram bottom spring and the hammer cushion of GRLWEAP's hammer model (Pile Dynamics
    2010) form one spring this way.

    Parameters
    ----------
    *stiffnesses : float
        Spring stiffnesses k_i [N/m], each greater than 0 (math.inf for a rigid link).

    Returns
    -------
    float
        The series stiffness [N/m] (inf when every k_i is infinite or none is given).

    Raises
    ------
    ValueError
        If a stiffness is not greater than 0 (or is nan).
    """
    flexibility = 0.0
    for k in stiffnesses:
        if not k > 0.0:
            raise ValueError(f"spring stiffnesses must be greater than 0 N/m, got {k!r}")
        flexibility += 1.0 / k
    return math.inf if flexibility == 0.0 else 1.0 / flexibility


GRLWEAP_HAMMER_DAMPING_RATIO = 0.02
"""GRLWEAP's default hammer damping (option H-D = 2, read as 2 % of critical) [-]."""


def grlweap_2010_hammer_damping(ram_bottom_mass: float, stiffness: float,
                                damping_ratio: float = GRLWEAP_HAMMER_DAMPING_RATIO) -> float:
    """Hammer damping [N s/m] in parallel with the hammer cushion, GRLWEAP 2010's default.

    c = 2 zeta sqrt(m k): the fraction zeta of the critical damping of the ram's lowest segment
    (mass m) on the hammer cushion combined with the ram bottom spring (stiffness k). With
    GRLWEAP's default hammer damping option (H-D = 2, zeta = 0.02) this is
    c = 2/50 sqrt(m k). The rule is inferred, not documented: it reproduces the 765.6 kN s/m
    that GRLWEAP 2010 prints for the IHC S-4000 (m = 109.516 kN / 9.81, k = 32,811.0 kN/mm) in
    the public CODRIVE benchmark input; reading the option value as a percentage of critical
    damping is an interpretation that only the default (2) has confirmed.

    Parameters
    ----------
    ram_bottom_mass : float
        Mass of the ram's lowest segment m [kg].
    stiffness : float
        Hammer cushion stiffness combined with the ram bottom spring k [N/m].
    damping_ratio : float, default GRLWEAP_HAMMER_DAMPING_RATIO
        Fraction of critical damping zeta [-] (GRLWEAP default 0.02).

    Returns
    -------
    float
        The hammer damping c [N s/m].

    Raises
    ------
    ValueError
        If ``ram_bottom_mass`` or ``stiffness`` is not greater than 0, or ``damping_ratio`` is
        negative.

    References
    ----------
    Pile Dynamics, Inc. (2010). GRLWEAP background report (hammer damping option).
    """
    if not (ram_bottom_mass > 0.0 and stiffness > 0.0 and damping_ratio >= 0.0):
        raise ValueError("ram_bottom_mass and stiffness must be > 0, damping_ratio >= 0")
    return 2.0 * damping_ratio * math.sqrt(ram_bottom_mass * stiffness)


@dataclass(frozen=True)
class Cushion:
    """A compression-only cushion (or contact) with restitution and round-out.

    Parameters
    ----------
    stiffness : float
        Loading stiffness k [N/m] (E A / t of the cushion material).
    restitution : float, default 1.0
        Coefficient of restitution e [-], 0 < e <= 1.
    round_out : float, default 0.0
        Round-out compression r [m] (0: linear from first contact).

    Raises
    ------
    ValueError
        If the stiffness is not finite and positive, the restitution is outside (0, 1] or the
        round-out is negative or not finite.
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
        """Read a cushion from a TOML table (errors name the key and the rule).

        Parameters
        ----------
        table : anvilwave.inputs.Table
            The cushion table: ``stiffness`` [N/m], or ``area`` [m^2] + ``elastic_modulus`` [Pa] +
            ``thickness`` [m] (k = E A / t); ``restitution`` [-] (required); ``round_out`` [m]
            (default 0).

        Returns
        -------
        Cushion
            The cushion.

        Raises
        ------
        anvilwave.inputs.InputError
            If a key is missing, invalid or unknown, or ``stiffness`` is given together with the
            material keys.
        """
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


def _positive(value: float) -> bool:
    return value > 0.0 and math.isfinite(value)


@dataclass(frozen=True)
class DrivingSystem:
    """Hammer cushion, helmet (+ resting assembly) and pile cushion between ram and pile.

    Parameters
    ----------
    hammer_cushion : Cushion
        Between ram toe and helmet (its own stiffness; see ``ram_bottom_stiffness``).
    helmet_mass : float
        Helmet / anvil mass including striker plate and inserts [kg].
    pile_cushion : Cushion
        Between helmet and pile head; without a pile cushion the steel helmet-pile contact
        (GRLWEAP: E A / dx of the first pile segment, round-out 3 mm, restitution 1), see
        ``has_pile_cushion``.
    assembly_mass : float, default 0.0
        One hammer assembly mass resting on the helmet [kg] (0: none); or use
        ``assembly_masses`` for a chain.
    assembly_stiffness : float, default 0.0
        Stiffness of the compression-only contact of ``assembly_mass`` on the helmet [N/m].
    has_pile_cushion : bool, default True
        False when ``pile_cushion`` stands for the bare steel contact.
    ram_bottom_stiffness : float, default inf
        Spring below the ram's lowest segment [N/m], in series with the hammer cushion
        (math.inf: none, the cushion acts on the ram's toe mass directly).
    hammer_damping : float, default 0.0
        Dashpot parallel to the (combined) hammer cushion [N s/m], acting only while the
        cushion carries load.
    assembly_masses : tuple of float, default ()
        Hammer assembly as a chain of masses [kg], top first (instead of ``assembly_mass``).
    assembly_stiffnesses : tuple of float, default ()
        The spring below each of ``assembly_masses`` [N/m]: springs 0 ... n-2 join the masses
        (linear, tension and compression), the last is the compression-only contact of the
        lowest mass on the helmet.
    assembly_restitution : float, default 1.0
        Coefficient of restitution of the assembly contact [-] (1: elastic).
    assembly_round_out : float, default 0.0
        Round-out of the assembly contact [m] (0: linear).

    Raises
    ------
    ValueError
        If a mass, stiffness, restitution, round-out or damping is out of range, both
        ``assembly_mass`` and ``assembly_masses`` are given, or ``assembly_stiffnesses`` does
        not have one entry per assembly mass.
    """

    hammer_cushion: Cushion
    helmet_mass: float
    pile_cushion: Cushion
    assembly_mass: float = 0.0
    assembly_stiffness: float = 0.0
    has_pile_cushion: bool = True
    ram_bottom_stiffness: float = math.inf
    hammer_damping: float = 0.0
    assembly_masses: tuple[float, ...] = ()
    assembly_stiffnesses: tuple[float, ...] = ()
    assembly_restitution: float = 1.0
    assembly_round_out: float = 0.0

    def __post_init__(self):
        if not _positive(self.helmet_mass):
            raise ValueError("helmet_mass must be finite and greater than 0 kg")
        if not (self.assembly_mass >= 0.0 and math.isfinite(self.assembly_mass)):
            raise ValueError("assembly_mass must be at least 0 kg")
        if self.assembly_mass > 0.0 and not _positive(self.assembly_stiffness):
            raise ValueError("assembly_stiffness must be greater than 0 N/m with an assembly")
        masses = tuple(float(m) for m in self.assembly_masses)
        springs = tuple(float(k) for k in self.assembly_stiffnesses)
        object.__setattr__(self, "assembly_masses", masses)
        object.__setattr__(self, "assembly_stiffnesses", springs)
        if masses and self.assembly_mass > 0.0:
            raise ValueError("give assembly_mass or assembly_masses, not both")
        if len(springs) != len(masses):
            raise ValueError("assembly_stiffnesses must have one entry per assembly mass")
        if not all(_positive(m) for m in masses):
            raise ValueError("assembly_masses must be finite and greater than 0 kg")
        if not all(_positive(k) for k in springs):
            raise ValueError("assembly_stiffnesses must be finite and greater than 0 N/m")
        if not 0.0 < self.assembly_restitution <= 1.0:
            raise ValueError("assembly_restitution must be in (0, 1]")
        if not (self.assembly_round_out >= 0.0 and math.isfinite(self.assembly_round_out)):
            raise ValueError("assembly_round_out must be at least 0 m")
        if not self.ram_bottom_stiffness > 0.0:
            raise ValueError("ram_bottom_stiffness must be greater than 0 N/m (inf: none)")
        if not (self.hammer_damping >= 0.0 and math.isfinite(self.hammer_damping)):
            raise ValueError("hammer_damping must be finite and at least 0 N s/m")

    @classmethod
    def from_table(cls, table: Table) -> DrivingSystem:
        """Read a driving system from a TOML table (``[anvil.classic]`` of a system file).

        Parameters
        ----------
        table : anvilwave.inputs.Table
            The table, with the keys

            * ``helmet_mass`` [kg]: helmet / anvil mass (required);
            * ``hammer_cushion``: a table, see :meth:`Cushion.from_table` (required);
            * ``ram_bottom_stiffness`` [N/m]: optional spring below the ram's lowest segment, in
              series with the hammer cushion (GRLWEAP's hammer file gives it for a ram of segment
              masses and springs; the cushion's restitution and round-out apply to the
              combination); default none;
            * ``hammer_damping`` [N s/m]: optional dashpot parallel to the (combined) hammer
              cushion, acting while it carries load (default 0); or ``hammer_damping_ratio`` [-],
              GRLWEAP's rule instead, c = 2 zeta sqrt(m k) (:func:`grlweap_2010_hammer_damping`;
              GRLWEAP's default 0.02), with ``ram_bottom_mass`` [kg], the mass of the ram's lowest
              segment (only with hammer_damping_ratio, required there);
            * ``assembly_mass`` [kg]: one assembly mass (0) with ``assembly_stiffness`` [N/m], its
              contact on the helmet; or ``assembly_masses`` [kg], a chain of assembly masses, top
              first, with ``assembly_stiffnesses`` [N/m], the spring below each (the last one is
              the compression-only contact on the helmet), as many as assembly_masses;
            * ``assembly_restitution`` [-]: restitution of the assembly contact (1) and
              ``assembly_round_out`` [m]: its round-out (0); only with an assembly;
            * ``pile_cushion``: a table, see :meth:`Cushion.from_table`; or without it
              ``pile_contact_stiffness`` [N/m], the helmet-pile steel contact (GRLWEAP: E A / dx of
              the first pile segment), with ``pile_contact_restitution`` [-] (1) and
              ``pile_contact_round_out`` [m] (0).

        Returns
        -------
        DrivingSystem
            The driving system.

        Raises
        ------
        anvilwave.inputs.InputError
            If a key is missing, invalid or unknown, or keys that exclude each other are given
            together (a pile cushion and the pile contact keys, hammer_damping and
            hammer_damping_ratio, one assembly mass and a chain).
        """
        helmet_mass = table.number("helmet_mass", gt=0, unit="kg")
        (assembly_mass, assembly_stiffness, masses,
         springs, restitution, round_out) = _assembly_from_table(table)
        hammer_cushion = Cushion.from_table(table.table("hammer_cushion"))
        ram_bottom = _given(table, "ram_bottom_stiffness", math.inf, gt=0, unit="N/m")
        damping = _hammer_damping_from_table(table, hammer_cushion, ram_bottom)
        contact_keys = ("pile_contact_stiffness", "pile_contact_restitution",
                        "pile_contact_round_out")
        if table.has("pile_cushion"):
            for key in contact_keys:
                if table.has(key):
                    raise table.error(key, "cannot be given together with a pile_cushion")
            pile_cushion = Cushion.from_table(table.table("pile_cushion"))
            has_pile_cushion = True
        else:
            stiffness = table.number("pile_contact_stiffness", gt=0, unit="N/m")
            pile_cushion = Cushion(stiffness,
                                   _given(table, "pile_contact_restitution", 1.0, gt=0, le=1),
                                   _given(table, "pile_contact_round_out", 0.0, ge=0, unit="m"))
            has_pile_cushion = False
        table.finish()
        return cls(hammer_cushion, helmet_mass, pile_cushion, assembly_mass,
                   assembly_stiffness, has_pile_cushion, ram_bottom, damping, masses, springs,
                   restitution, round_out)

    # ------------------------------------------------------------------ derived values
    @property
    def assembly_chain(self) -> tuple[np.ndarray, np.ndarray]:
        """(masses [kg], springs below them [N/m]) of the assembly, top first; empty if none.

        The last spring is the compression-only contact on the helmet.
        """
        if self.assembly_masses:
            return np.array(self.assembly_masses), np.array(self.assembly_stiffnesses)
        if self.assembly_mass > 0.0:
            return np.array([self.assembly_mass]), np.array([self.assembly_stiffness])
        return np.zeros(0), np.zeros(0)

    @property
    def total_assembly_mass(self) -> float:
        """Mass of the whole assembly [kg]."""
        return float(self.assembly_chain[0].sum())

    @property
    def effective_hammer_cushion(self) -> Cushion:
        """The hammer cushion in series with the ram bottom spring.

        Its restitution and round-out apply to the combination; the cushion itself without a ram
        bottom spring.
        """
        hc = self.hammer_cushion
        if math.isinf(self.ram_bottom_stiffness):
            return hc
        return Cushion(series_stiffness(self.ram_bottom_stiffness, hc.stiffness),
                       hc.restitution, hc.round_out)

    def static_pile_force(self, gravity: float = GRAVITY) -> float:
        """Force on the pile head at rest, (m_helmet + sum m_assembly) g [N].

        Parameters
        ----------
        gravity : float, default GRAVITY
            Gravitational acceleration [m/s^2].

        Returns
        -------
        float
            The static force [N].
        """
        return (self.helmet_mass + self.total_assembly_mass) * gravity

    def parameters(self, gravity: float = GRAVITY) -> np.ndarray:
        """The float64 parameter array (P_* layout) for the kernels.

        Parameters
        ----------
        gravity : float, default GRAVITY
            Gravitational acceleration [m/s^2] (it also sets the static compressions).

        Returns
        -------
        numpy.ndarray
            (N_PARAMS + 3 n - 2,) parameters, n the number of assembly masses (N_PARAMS without an
            assembly) [SI units of each entry].
        """
        masses, springs = self.assembly_chain
        n = masses.size
        p = np.zeros(N_PARAMS + (3 * n - 2 if n else 0))
        hc, pc = self.effective_hammer_cushion, self.pile_cushion
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
        p[P_GRAVITY] = gravity
        p[P_HAMMER_DAMPING] = self.hammer_damping
        p[P_RAM_BOTTOM_STIFFNESS] = self.ram_bottom_stiffness
        p[P_ASSEMBLY_RESTITUTION] = 1.0
        p[P_N_ASSEMBLY] = n
        if n:
            p[P_ASSEMBLY_MASS] = masses[-1]
            p[P_ASSEMBLY_STIFFNESS] = springs[-1]
            p[P_ASSEMBLY_RESTITUTION] = self.assembly_restitution
            p[P_ASSEMBLY_ROUND_OUT] = self.assembly_round_out
            p[P_ASSEMBLY_PRECOMPRESSION] = loading_compression(
                masses.sum() * gravity, springs[-1], self.assembly_round_out)
            chain = P_ASSEMBLY_CHAIN
            p[chain:chain + n] = masses
            p[chain + n:chain + 2 * n - 1] = springs[:-1]
            # spring j carries the weight of the masses above it
            p[chain + 2 * n - 1:chain + 3 * n - 2] = (np.cumsum(masses)[:-1] * gravity
                                                      / springs[:-1])
        return p

    @staticmethod
    def initial_state(params: np.ndarray) -> np.ndarray:
        """The float64 state array (S_* layout) at t = 0: at rest, springs at static compression.

        Parameters
        ----------
        params : numpy.ndarray
            The parameter array (:meth:`parameters`) [SI units of each entry].

        Returns
        -------
        numpy.ndarray
            (N_STATE + 2 (n - 1),) state [SI units of each entry] (N_STATE without an assembly).
        """
        n = int(params[P_N_ASSEMBLY])
        state = np.zeros(N_STATE + (2 * (n - 1) if n else 0))
        state[S_HC_MAX] = params[P_HC_PRECOMPRESSION]
        state[S_PC_MAX] = params[P_PC_PRECOMPRESSION]
        state[S_AS_MAX] = params[P_ASSEMBLY_PRECOMPRESSION]
        return state


def _given(table: Table, key: str, default: float, **rules) -> float:
    """An optional number, read (and so recorded as used) only when the table has it."""
    return table.number(key, **rules) if table.has(key) else default


def _assembly_from_table(table: Table):
    """(assembly_mass, assembly_stiffness, masses, springs, restitution, round_out)."""
    single = table.has("assembly_mass") or table.has("assembly_stiffness")
    chain = table.has("assembly_masses") or table.has("assembly_stiffnesses")
    if single and chain:
        key = "assembly_masses" if table.has("assembly_masses") else "assembly_stiffnesses"
        raise table.error(key, "cannot be given together with assembly_mass / "
                               "assembly_stiffness (one mass, or a chain of masses)")
    assembly_mass, assembly_stiffness, masses, springs = 0.0, 0.0, (), ()
    if chain:
        masses_array = table.array("assembly_masses")
        springs_array = table.array("assembly_stiffnesses")
        if np.any(masses_array <= 0):
            raise table.error("assembly_masses", "must all be greater than 0 kg")
        if np.any(springs_array <= 0):
            raise table.error("assembly_stiffnesses", "must all be greater than 0 N/m")
        if springs_array.size != masses_array.size:
            raise table.error("assembly_stiffnesses",
                              f"must have one entry per assembly mass ({masses_array.size}: "
                              f"the spring below each, the last on the helmet), got "
                              f"{springs_array.size}")
        masses, springs = tuple(masses_array.tolist()), tuple(springs_array.tolist())
    else:
        assembly_mass = table.number("assembly_mass", 0.0, ge=0, unit="kg")
        if assembly_mass > 0.0:
            assembly_stiffness = table.number("assembly_stiffness", gt=0, unit="N/m")
        elif table.has("assembly_stiffness"):
            raise table.error("assembly_stiffness", "needs an assembly_mass above 0 kg")
    if not (masses or assembly_mass > 0.0):
        for key in ("assembly_restitution", "assembly_round_out"):
            if table.has(key):
                raise table.error(key, "needs an assembly (assembly_mass or assembly_masses)")
    restitution = _given(table, "assembly_restitution", 1.0, gt=0, le=1)
    round_out = _given(table, "assembly_round_out", 0.0, ge=0, unit="m")
    return assembly_mass, assembly_stiffness, masses, springs, restitution, round_out


def _hammer_damping_from_table(table: Table, hammer_cushion: Cushion,
                               ram_bottom_stiffness: float) -> float:
    if table.has("hammer_damping") and table.has("hammer_damping_ratio"):
        raise table.error("hammer_damping_ratio", "cannot be given together with "
                                                  "hammer_damping (a value or GRLWEAP's rule)")
    if table.has("hammer_damping_ratio"):
        ratio = table.number("hammer_damping_ratio", ge=0, lt=1)
        if not table.has("ram_bottom_mass"):
            raise table.error("ram_bottom_mass", "is required with hammer_damping_ratio (the "
                                                 "mass of the ram's lowest segment [kg])")
        mass = table.number("ram_bottom_mass", gt=0, unit="kg")
        stiffness = series_stiffness(ram_bottom_stiffness, hammer_cushion.stiffness)
        return grlweap_2010_hammer_damping(mass, stiffness, ratio)
    if table.has("ram_bottom_mass"):
        raise table.error("ram_bottom_mass", "applies to hammer_damping_ratio only")
    return _given(table, "hammer_damping", 0.0, ge=0, unit="N s/m")


# --------------------------------------------------------------------------- kernels
@njit(cache=True)
def _assembly_contact(c, c_max, params):
    """Force [N] of the compression-only assembly contact at compression c [m]."""
    k = params[P_ASSEMBLY_STIFFNESS]
    e = params[P_ASSEMBLY_RESTITUTION]
    r = params[P_ASSEMBLY_ROUND_OUT]
    if e == 1.0 and r == 0.0:
        return k * c if c > 0.0 else 0.0
    return cushion_force(c, c_max, k, e, r)


@njit(cache=True)
def _forces(params, u_helmet, u_assembly, u_ram, u_pile, hc_max, pc_max, as_max):
    """Spring forces at one instant: (F_hc, F_pc, F_as, c_hc, c_pc, c_as).

    F_hc: hammer cushion (combined with the ram bottom spring) without the damping; F_pc: pile
    cushion; F_as: assembly contact on the helmet (0 without an assembly).
    """
    c_hc = params[P_HC_PRECOMPRESSION] + u_ram - u_helmet
    f_hc = cushion_force(c_hc, hc_max, params[P_HC_STIFFNESS], params[P_HC_RESTITUTION],
                         params[P_HC_ROUND_OUT])
    c_pc = params[P_PC_PRECOMPRESSION] + u_helmet - u_pile
    f_pc = cushion_force(c_pc, pc_max, params[P_PC_STIFFNESS], params[P_PC_RESTITUTION],
                         params[P_PC_ROUND_OUT])
    f_as = 0.0
    c_as = 0.0
    if params[P_ASSEMBLY_MASS] > 0.0:
        c_as = params[P_ASSEMBLY_PRECOMPRESSION] + u_assembly - u_helmet
        f_as = _assembly_contact(c_as, as_max, params)
    return f_hc, f_pc, f_as, c_hc, c_pc, c_as


@njit(cache=True)
def _damped(f_spring, damping, v_relative):
    """Hammer cushion force [N] with the parallel dashpot: acts only while the spring carries
    load, and the total stays compressive."""
    if damping == 0.0 or f_spring <= 0.0:
        return f_spring
    total = f_spring + damping * v_relative
    return total if total > 0.0 else 0.0


@njit(cache=True)
def _u_index(n, i):
    """State index of the displacement of assembly mass i of n (top first)."""
    return S_ASSEMBLY_U if i == n - 1 else S_ASSEMBLY_CHAIN + 2 * i


@njit(cache=True)
def _chain_force(params, state, n, j):
    """Force [N] of assembly spring j (between masses j and j + 1), compression positive."""
    chain = P_ASSEMBLY_CHAIN
    return params[chain + n + j] * (params[chain + 2 * n - 1 + j]
                                    + state[_u_index(n, j)] - state[_u_index(n, j + 1)])


@njit(cache=True)
def _kick_assembly(params, state, n, f_contact, g, half_dt):
    """v += half_dt * a for every assembly mass (in place); f_contact: contact force [N]."""
    chain = P_ASSEMBLY_CHAIN
    from_above = 0.0
    for i in range(n):
        below = _chain_force(params, state, n, i) if i < n - 1 else f_contact
        state[_u_index(n, i) + 1] += half_dt * (g + (from_above - below) / params[chain + i])
        from_above = below


@njit(cache=True)
def _drift_assembly(state, n, dt):
    for i in range(n):
        state[_u_index(n, i)] += dt * state[_u_index(n, i) + 1]


@njit(cache=True)
def driving_system_forces(params, state, u_ram, v_ram, u_pile, v_pile):
    """Outputs at the current instant (feedthrough); the state is not changed.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].
    state : numpy.ndarray
        The state array (S_* layout) [SI units of each entry].
    u_ram : float
        Ram toe displacement [m], positive down.
    v_ram : float
        Ram toe velocity [m/s], positive down.
    u_pile : float
        Pile head displacement [m], positive down.
    v_pile : float
        Pile head velocity [m/s]; part of the interface but not used.

    Returns
    -------
    F_ram : float
        Hammer cushion force on the ram toe [N], compression positive (pushes the ram up),
        including the hammer damping c (v_ram - v_helmet) while the cushion carries load.
    F_pile : float
        Pile cushion force on the pile head [N], compression positive (pushes it down).
    u_top : float
        Helmet displacement [m].
    u_bottom : float
        Helmet displacement [m] (a rigid helmet: the same as ``u_top``).
    """
    f_hc, f_pc, f_as, c_hc, c_pc, c_as = _forces(params, state[S_HELMET_U],
                                                 state[S_ASSEMBLY_U], u_ram, u_pile,
                                                 state[S_HC_MAX], state[S_PC_MAX],
                                                 state[S_AS_MAX])
    f_ram = _damped(f_hc, params[P_HAMMER_DAMPING], v_ram - state[S_HELMET_V])
    return f_ram, f_pc, state[S_HELMET_U], state[S_HELMET_U]


@njit(cache=True)
def driving_system_step(params, state, u_ram, v_ram, u_pile, v_pile, h, n_sub):
    """Advance helmet, assembly and spring memory over a step h [s] (in place on state).

    The ram toe and pile head move with the given velocities during the step,
    u_ram(t_n + s) = u_ram + v_ram s (and likewise the pile), and the helmet and the assembly
    masses are integrated with n_sub velocity-Verlet sub-steps (h / n_sub below
    :func:`driving_system_stable_time_step`). The largest compressions of the Smith-law
    springs are updated after every sub-step. With hammer damping, the helmet's second half
    kick is solved for its own end velocity (the dashpot force depends on it), and the
    dashpot's work over a sub-step, dt (F_d0 + F_d1) / 2 (v_rel0 + v_rel1) / 2, is added to
    the state: it is exactly the energy the velocity-Verlet step takes out through it.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].
    state : numpy.ndarray
        The state array (S_* layout) [SI units of each entry]; updated in place.
    u_ram : float
        Ram toe displacement at the start of the step [m].
    v_ram : float
        Ram toe velocity over the step [m/s].
    u_pile : float
        Pile head displacement at the start of the step [m].
    v_pile : float
        Pile head velocity over the step [m/s].
    h : float
        The step [s].
    n_sub : int
        Number of sub-steps [-].
    """
    dt = h / n_sub
    m_h = params[P_HELMET_MASS]
    g = params[P_GRAVITY]
    c_d = params[P_HAMMER_DAMPING]
    n_a = int(params[P_N_ASSEMBLY])
    u_h = state[S_HELMET_U]
    v_h = state[S_HELMET_V]
    hc_max = state[S_HC_MAX]
    pc_max = state[S_PC_MAX]
    as_max = state[S_AS_MAX]
    damping_work = state[S_DAMPING_WORK]
    f_hc, f_pc, f_as, c_hc, c_pc, c_as = _forces(params, u_h, state[S_ASSEMBLY_U], u_ram,
                                                 u_pile, hc_max, pc_max, as_max)
    hc_max = max(hc_max, c_hc)
    pc_max = max(pc_max, c_pc)
    as_max = max(as_max, c_as)
    f_hc_total = _damped(f_hc, c_d, v_ram - v_h)
    for s in range(n_sub):
        a_h = g + (f_hc_total - f_pc + f_as) / m_h
        v_h0 = v_h
        f_d0 = f_hc_total - f_hc
        v_h += 0.5 * dt * a_h
        u_h += dt * v_h
        if n_a > 0:
            _kick_assembly(params, state, n_a, f_as, g, 0.5 * dt)
            _drift_assembly(state, n_a, dt)
        t = (s + 1) * dt
        f_hc, f_pc, f_as, c_hc, c_pc, c_as = _forces(params, u_h, state[S_ASSEMBLY_U],
                                                     u_ram + v_ram * t, u_pile + v_pile * t,
                                                     hc_max, pc_max, as_max)
        hc_max = max(hc_max, c_hc)
        pc_max = max(pc_max, c_pc)
        as_max = max(as_max, c_as)
        if c_d == 0.0:
            f_hc_total = f_hc
            v_h += 0.5 * dt * (g + (f_hc - f_pc + f_as) / m_h)
        else:
            # v_1 = A + beta F(v_1) with F = max(0, f_hc + c (v_ram - v_1)) while loaded
            beta = 0.5 * dt / m_h
            a_free = v_h + 0.5 * dt * (g + (f_as - f_pc) / m_h)
            f_hc_total = 0.0
            if f_hc > 0.0:
                v_1 = (a_free + beta * (f_hc + c_d * v_ram)) / (1.0 + beta * c_d)
                f_hc_total = f_hc + c_d * (v_ram - v_1)
                if f_hc_total < 0.0:
                    f_hc_total = 0.0
            v_h = a_free + beta * f_hc_total
            f_d1 = f_hc_total - f_hc
            damping_work += 0.25 * dt * (f_d0 + f_d1) * (2.0 * v_ram - v_h0 - v_h)
        if n_a > 0:
            _kick_assembly(params, state, n_a, f_as, g, 0.5 * dt)
    state[S_HELMET_U] = u_h
    state[S_HELMET_V] = v_h
    state[S_HC_MAX] = hc_max
    state[S_PC_MAX] = pc_max
    state[S_AS_MAX] = as_max
    state[S_DAMPING_WORK] = damping_work


@njit(cache=True)
def driving_system_stable_time_step(params):
    """Stable sub-step [s] for the helmet and assembly with ram and pile held: 2 / omega_max.

    omega_max^2 is bounded (Gershgorin discs of M^-1/2 K M^-1/2) with the stiffest branch of
    each Smith-law spring, the unloading line k / e^2: helmet row (k_hc / e_hc^2 + k_pc / e_pc^2
    + k_c / e_c^2) / m_h + k_c / e_c^2 / sqrt(m_h m_n-1), assembly rows (k_i-1 + k_i) / m_i
    + k_i-1 / sqrt(m_i-1 m_i) + k_i / sqrt(m_i m_i+1), where k_c = k_n-1 is the contact on the
    helmet (mass "n" is the helmet). The hammer damping does not enter: its rate c / m_h is
    three orders of magnitude below omega_max (1e-3 of it for the GRLWEAP IHC S-4000 system)
    and its end-of-step force is taken implicitly.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].

    Returns
    -------
    float
        The stable sub-step [s].
    """
    m_h = params[P_HELMET_MASS]
    k_hc = params[P_HC_STIFFNESS] / params[P_HC_RESTITUTION] ** 2
    k_pc = params[P_PC_STIFFNESS] / params[P_PC_RESTITUTION] ** 2
    omega2 = (k_hc + k_pc) / m_h
    n = int(params[P_N_ASSEMBLY])
    if n > 0:
        chain = P_ASSEMBLY_CHAIN
        k_c = params[P_ASSEMBLY_STIFFNESS] / params[P_ASSEMBLY_RESTITUTION] ** 2
        coupling = k_c / math.sqrt(m_h * params[chain + n - 1])
        omega2 = (k_hc + k_pc + k_c) / m_h + coupling
        for i in range(n):
            m_i = params[chain + i]
            k_sum = 0.0
            off = 0.0
            if i > 0:
                k_up = params[chain + n + i - 1]
                k_sum += k_up
                off += k_up / math.sqrt(params[chain + i - 1] * m_i)
            if i < n - 1:
                k_down = params[chain + n + i]
                k_sum += k_down
                off += k_down / math.sqrt(m_i * params[chain + i + 1])
            else:
                k_sum += k_c
                off += coupling
            omega2 = max(omega2, k_sum / m_i + off)
    return 2.0 / math.sqrt(omega2)


@njit(cache=True)
def driving_system_energy(params, state, u_ram, u_pile):
    """Kinetic, strain and damping, and gravity potential energy of the driving system [J].

    kinetic: helmet and assembly masses; strain and damping: what the Smith-law springs give
    back if unloaded (e^2 F^2 / (2 k) each: hammer cushion, pile cushion, assembly contact),
    the strain energy k c^2 / 2 of the springs inside the assembly, plus the work the hammer
    damping has dissipated since t = 0 (state S_DAMPING_WORK); gravity potential:
    -g (m_h u_h + sum m_i u_i), relative to t = 0. The energy dissipated by the restitution
    law of the springs is not included: :func:`driving_system_losses` gives it, and
    kinetic + strain and damping + potential + losses changes by the work done on the system.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].
    state : numpy.ndarray
        The state array (S_* layout) [SI units of each entry].
    u_ram : float
        Ram toe displacement [m].
    u_pile : float
        Pile head displacement [m].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    strain : float
        Recoverable strain energy plus the hammer damping's work [J].
    potential : float
        Gravity potential relative to t = 0 [J].
    """
    m_h = params[P_HELMET_MASS]
    u_h = state[S_HELMET_U]
    kinetic = 0.5 * m_h * state[S_HELMET_V] ** 2
    potential_sum = m_h * u_h
    f_hc, f_pc, f_as, c_hc, c_pc, c_as = _forces(params, u_h, state[S_ASSEMBLY_U], u_ram,
                                                 u_pile, state[S_HC_MAX], state[S_PC_MAX],
                                                 state[S_AS_MAX])
    strain = (recoverable_energy(f_hc, params[P_HC_STIFFNESS], params[P_HC_RESTITUTION])
              + recoverable_energy(f_pc, params[P_PC_STIFFNESS], params[P_PC_RESTITUTION]))
    n = int(params[P_N_ASSEMBLY])
    if n > 0:
        chain = P_ASSEMBLY_CHAIN
        strain += recoverable_energy(f_as, params[P_ASSEMBLY_STIFFNESS],
                                     params[P_ASSEMBLY_RESTITUTION])
        for i in range(n):
            index = _u_index(n, i)
            kinetic += 0.5 * params[chain + i] * state[index + 1] ** 2
            potential_sum += params[chain + i] * state[index]
            if i < n - 1:
                force = _chain_force(params, state, n, i)
                strain += 0.5 * force * force / params[chain + n + i]
    strain += state[S_DAMPING_WORK]
    potential = -params[P_GRAVITY] * potential_sum
    return kinetic, strain, potential


@njit(cache=True)
def driving_system_losses(params, state):
    """Energy [J] dissipated since t = 0 by the restitution law (and round-out) of the springs.

    The Smith-law springs: hammer cushion, pile cushion or contact, assembly contact. Each loses
    :func:`anvilwave.hammer.cushion.hysteresis_loss` of its largest compression so far,
    minus that of its static compression at t = 0 (the state a blow starts from). Without
    round-out, (1 - e^2) k (c_max^2 - c_0^2) / 2; an elastic linear spring (e = 1, no
    round-out) loses nothing. The hammer damping's work is part of
    :func:`driving_system_energy` instead.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].
    state : numpy.ndarray
        The state array (S_* layout) [SI units of each entry].

    Returns
    -------
    float
        The dissipated energy [J].
    """
    loss = (hysteresis_loss(state[S_HC_MAX], params[P_HC_STIFFNESS], params[P_HC_RESTITUTION],
                            params[P_HC_ROUND_OUT])
            - hysteresis_loss(params[P_HC_PRECOMPRESSION], params[P_HC_STIFFNESS],
                              params[P_HC_RESTITUTION], params[P_HC_ROUND_OUT]))
    loss += (hysteresis_loss(state[S_PC_MAX], params[P_PC_STIFFNESS],
                             params[P_PC_RESTITUTION], params[P_PC_ROUND_OUT])
             - hysteresis_loss(params[P_PC_PRECOMPRESSION], params[P_PC_STIFFNESS],
                               params[P_PC_RESTITUTION], params[P_PC_ROUND_OUT]))
    if params[P_N_ASSEMBLY] > 0:
        k = params[P_ASSEMBLY_STIFFNESS]
        e = params[P_ASSEMBLY_RESTITUTION]
        r = params[P_ASSEMBLY_ROUND_OUT]
        loss += (hysteresis_loss(state[S_AS_MAX], k, e, r)
                 - hysteresis_loss(params[P_ASSEMBLY_PRECOMPRESSION], k, e, r))
    return loss


def interface_time_step(params: np.ndarray, ram_toe_mass: float, pile_head_mass: float) -> float:
    """Estimate of the largest stable communication step [s] of the explicit coupling.

    The master holds the contact forces over a step, which for the ram toe and the pile head
    acts like an explicit step of the chain ram toe -- hammer cushion -- helmet -- pile cushion
    -- pile head (stiffest cushion branches k / e^2; the hammer cushion combined with the ram
    bottom spring). Returns 2 / omega_max of that chain (Gershgorin bound, as
    :func:`anvilwave.hammer.ram.stable_time_step`), never above the driving system's own stable
    sub-step, nor above 2 m_toe / c, the limit of the hammer damping c held on the ram toe mass
    (explicit). A guide, not a proof: use a safety factor.

    Parameters
    ----------
    params : numpy.ndarray
        The parameter array (P_* layout) [SI units of each entry].
    ram_toe_mass : float
        Mass of the ram's toe node [kg].
    pile_head_mass : float
        Mass of the pile's head node [kg].

    Returns
    -------
    float
        The step estimate [s].
    """
    mass = np.array([ram_toe_mass, params[P_HELMET_MASS], pile_head_mass], dtype=np.float64)
    stiffness = np.array([params[P_HC_STIFFNESS] / params[P_HC_RESTITUTION] ** 2,
                          params[P_PC_STIFFNESS] / params[P_PC_RESTITUTION] ** 2])
    step = min(float(stable_time_step(mass, stiffness)),
               float(driving_system_stable_time_step(params)))
    damping = params[P_HAMMER_DAMPING]
    if damping > 0.0:
        step = min(step, 2.0 * ram_toe_mass / damping)
    return step
