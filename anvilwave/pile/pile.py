"""The pile: sections of tube, discretised into Smith's lumped masses and springs.

A pile file (or the ``[pile]`` table of a system file) is TOML::

    [pile]
    segment_length = 0.5        # [m] target segment length (Ligthart & Orlando use 0.5 m)
    gauge_depth = 1.0           # [m] depth of the PDA gauges below the pile head
    material_damping = 0.01     # [-] pile damping, fraction of critical of one segment
    yield_strength = 355e6      # [Pa] steel yield strength fy (default: S355)
    [[pile.sections]]           # from the head down
    length = 80.0               # [m]
    outer_diameter = 8.0        # [m]
    wall_thickness = 0.14       # [m] (outer_diameter / 2 for a solid section)
    youngs_modulus = 210e9      # [Pa] default: steel
    density = 7850.0            # [kg/m^3] default: steel

Discretisation (Smith 1960; Hirsch, Lowery, Coyle & Samson 1970 "TTI"): each section is cut
into ``ceil(length / segment_length)`` equal segments (so no segment is longer than asked).
Segment i has its whole mass m_i = rho_i A_i dx_i lumped at its centre; the spring joining the
centres of segments i and i+1 is the series connection of the two half-segments,
1 / k_i = dx_i / (2 E_i A_i) + dx_{i+1} / (2 E_{i+1} A_{i+1}). For a uniform pile this is the
chain m = rho A dx, k = E A / dx whose free ends lie half a segment beyond the end masses, so the
chain represents the full length L = sum dx_i, and a wave needs exactly 2L/c to return to the
head. With the leapfrog scheme at Courant number c dt / dx = 1 the chain is dispersion free
(it then coincides with the Method of Characteristics on a uniform pile); below the cut-off
frequency f_c = c / (pi dx) the lumped chain disperses as omega = (2c/dx) |sin(kappa dx / 2)|.

Pile material damping: a dashpot in parallel with every spring, c_i = 2 zeta sqrt(k_i m_i*),
with zeta = ``material_damping`` and m_i* the mean of the two masses. For a uniform pile
c_i = 2 zeta E A / c = 2 zeta Z, independent of dx (GRLWEAP-style "pile damping in percent of
critical"); the damping ratio of a wave of angular frequency omega is zeta omega dx / c, i.e.
it acts mainly near the cut-off and is 2 zeta there. Default 1 %.
``material_damping_model = "uniform"`` takes GRLWEAP's rule instead: one dashpot value for every
spring, 2 zeta E A / c of the section at the pile's mid-length (GRLWEAP's "1 %" pile damping is
0.02 EA/c at mid-length, applied at every segment interface).

The gauge (PDA strain gauges and accelerometers) sits ``gauge_depth`` below the head. The gauge
force is interpolated linearly between the two springs (segment boundaries) around that depth
and the gauge velocity between the two mass centres around it; outside the first/last spring or
mass the nearest one is taken. With 0.5 m segments a gauge at 1.0 m lies exactly on a spring.

The head force acts on the top mass (Smith); the pile-head displacement and velocity handed to a
contact are those of the pile-top face, extrapolated over the top half-segment from the strain
of the first spring (:func:`anvilwave.pile.kernels.head_displacement`), which makes the head contact
second-order accurate in dx instead of first.

References
----------
Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech. Found.
Div. 86(4), 35-61.
Hirsch, T.J., Lowery, L.L., Coyle, H.M., Samson, C.H. (1970). Pile-driving analysis by
one-dimensional wave theory: state of the art. Highway Research Record 333, 33-54.
Rausche, F., Goble, G.G., Likins, G.E. GRLWEAP background report (wave equation analysis of
pile driving; Pile Dynamics Inc.).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from anvilwave.inputs import InputError, Table
from anvilwave.pile.kernels import (
    GAUGE_MASS,
    GAUGE_MASS_WEIGHT,
    GAUGE_SPRING,
    GAUGE_SPRING_WEIGHT,
    HEAD_EXTRAPOLATION,
    PILE_DASHPOT,
    PILE_MASS,
    PILE_ROWS,
    PILE_STIFFNESS,
    PROBE_SIZE,
)

STEEL_YOUNGS_MODULUS = 210e9
"""Default Young's modulus of the pile steel [Pa]."""
STEEL_DENSITY = 7850.0
"""Default density of the pile steel [kg/m^3]."""
DEFAULT_SEGMENT_LENGTH = 0.5
"""Default segment length [m], as in Ligthart & Orlando (after Hirsch et al. 1970)."""
DEFAULT_GAUGE_DEPTH = 1.0
"""Default gauge depth below the pile head [m]."""
DEFAULT_MATERIAL_DAMPING = 0.01
"""Default pile damping, fraction of critical of one segment [-]."""
DEFAULT_YIELD_STRENGTH = 355e6
"""Default yield strength fy of the pile steel [Pa]: structural steel S355 (EN 10025-2, 355 MPa
nominal up to 16 mm; the common grade of offshore monopiles and jacket piles, whose thicker
plates have a lower nominal fy: give ``[pile] yield_strength``)."""
ALLOWABLE_DRIVING_STRESS_RATIO = 0.9
"""Allowable driving stress over the yield strength [-]: the dynamic compression and tension
during driving should stay below 80 to 90 % of fy (API RP 2A-WSD, pile installation; DNV
practice for steel piles takes 0.9 fy); the driveability plot draws 0.9 fy."""


@dataclass(frozen=True)
class Section:
    """A uniform length of tube (or solid bar).

    Parameters
    ----------
    length : float
        Section length [m].
    outer_diameter : float
        Outer diameter [m].
    wall_thickness : float
        Wall thickness [m]; ``outer_diameter / 2`` for a solid section.
    youngs_modulus : float, default STEEL_YOUNGS_MODULUS
        Young's modulus [Pa].
    density : float, default STEEL_DENSITY
        Mass density [kg/m^3].
    """

    length: float
    outer_diameter: float
    wall_thickness: float
    youngs_modulus: float = STEEL_YOUNGS_MODULUS
    density: float = STEEL_DENSITY

    @property
    def area(self) -> float:
        """Steel cross-section area [m^2]."""
        return section_area(self.outer_diameter, self.wall_thickness)

    @property
    def wave_speed(self) -> float:
        """Bar wave speed c = sqrt(E / rho) [m/s]."""
        return math.sqrt(self.youngs_modulus / self.density)

    @property
    def impedance(self) -> float:
        """Impedance Z = E A / c [N s/m]."""
        return self.youngs_modulus * self.area / self.wave_speed


@dataclass(frozen=True)
class PileSpec:
    """A non-uniform pile from its sections (head first).

    Parameters
    ----------
    sections : tuple of Section
        The sections from the head down.
    segment_length : float, default DEFAULT_SEGMENT_LENGTH
        Target segment length [m] (an upper bound per section).
    gauge_depth : float, default DEFAULT_GAUGE_DEPTH
        Depth of the gauges below the pile head [m].
    material_damping : float, default DEFAULT_MATERIAL_DAMPING
        Pile damping, fraction of critical of one segment [-].
    material_damping_model : {"segment", "uniform"}
        ``"segment"`` (each spring's own 2 zeta sqrt(k m*)) or ``"uniform"``
        (GRLWEAP: 2 zeta EA/c at mid-length for every spring).
    yield_strength : float, default DEFAULT_YIELD_STRENGTH
        Yield strength fy of the pile steel [Pa]; the allowable driving stress is
        ``ALLOWABLE_DRIVING_STRESS_RATIO * yield_strength``.
    """

    sections: tuple[Section, ...]
    segment_length: float = DEFAULT_SEGMENT_LENGTH
    gauge_depth: float = DEFAULT_GAUGE_DEPTH
    material_damping: float = DEFAULT_MATERIAL_DAMPING
    material_damping_model: str = "segment"
    yield_strength: float = DEFAULT_YIELD_STRENGTH

    @property
    def allowable_driving_stress(self) -> float:
        """Allowable driving stress, compression or tension [Pa]: 0.9 fy."""
        return ALLOWABLE_DRIVING_STRESS_RATIO * self.yield_strength

    @property
    def length(self) -> float:
        """Total pile length [m]."""
        return float(sum(s.length for s in self.sections))

    def discretise(self) -> Segments:
        """The segments of this pile (see the module docstring).

        Returns
        -------
        Segments
            The per-segment properties, head first.
        """
        return discretise(self)


@dataclass(frozen=True, eq=False)
class Segments:
    """Per-segment properties of a discretised pile, head first (arrays of length N).

    Parameters
    ----------
    top : numpy.ndarray
        Upper segment ends, depth below the pile head [m].
    bottom : numpy.ndarray
        Lower segment ends, depth below the pile head [m].
    area : numpy.ndarray
        Steel area [m^2].
    youngs_modulus : numpy.ndarray
        Young's modulus [Pa].
    density : numpy.ndarray
        Mass density [kg/m^3].
    outer_diameter : numpy.ndarray
        Outer diameter [m].
    wall_thickness : numpy.ndarray
        Wall thickness [m].

    Attributes
    ----------
    count : int
        Number of segments N [-].
    length : numpy.ndarray
        Segment length [m].
    centre : numpy.ndarray
        Depth of the lumped masses below the head [m].
    wave_speed : numpy.ndarray
        Bar wave speed sqrt(E / rho) [m/s].
    """

    top: np.ndarray
    bottom: np.ndarray
    area: np.ndarray
    youngs_modulus: np.ndarray
    density: np.ndarray
    outer_diameter: np.ndarray
    wall_thickness: np.ndarray

    @property
    def count(self) -> int:
        """Number of segments N [-]."""
        return int(self.top.size)

    @property
    def length(self) -> np.ndarray:
        """Segment length, bottom - top [m]."""
        return self.bottom - self.top

    @property
    def centre(self) -> np.ndarray:
        """Depth of the lumped masses below the head [m]."""
        return 0.5 * (self.top + self.bottom)

    @property
    def wave_speed(self) -> np.ndarray:
        """Bar wave speed c = sqrt(E / rho) per segment [m/s]."""
        return np.sqrt(self.youngs_modulus / self.density)


def section_area(outer_diameter, wall_thickness):
    """Area of a tube, pi/4 (D^2 - (D - 2t)^2) [m^2].

    Parameters
    ----------
    outer_diameter : float or array_like
        Outer diameter D [m].
    wall_thickness : float or array_like
        Wall thickness t [m].

    Returns
    -------
    float or numpy.ndarray
        Steel cross-section area [m^2].
    """
    inner = np.maximum(np.asarray(outer_diameter) - 2.0 * np.asarray(wall_thickness), 0.0)
    return 0.25 * np.pi * (np.asarray(outer_diameter) ** 2 - inner**2)


def segment_masses(density, area, length) -> np.ndarray:
    """Lumped segment masses m_i = rho_i A_i dx_i [kg] (Smith 1960).

    Parameters
    ----------
    density : array_like
        Mass density rho_i [kg/m^3].
    area : array_like
        Steel area A_i [m^2].
    length : array_like
        Segment length dx_i [m].

    Returns
    -------
    numpy.ndarray
        Segment masses [kg].

    References
    ----------
    Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech.
    Found. Div. 86(4), 35-61.
    """
    return np.asarray(density) * np.asarray(area) * np.asarray(length)


def spring_stiffnesses(youngs_modulus, area, length) -> np.ndarray:
    """Stiffness of the springs joining consecutive segment centres [N/m], N - 1 values.

    1 / k_i = dx_i / (2 E_i A_i) + dx_{i+1} / (2 E_{i+1} A_{i+1}) (two half-segments in series).

    Parameters
    ----------
    youngs_modulus : array_like
        Young's modulus E_i per segment, shape (N,) [Pa].
    area : array_like
        Steel area A_i per segment, shape (N,) [m^2].
    length : array_like
        Segment length dx_i, shape (N,) [m].

    Returns
    -------
    numpy.ndarray
        Spring stiffnesses k_i, shape (N-1,) [N/m].
    """
    half_flex = 0.5 * np.asarray(length) / (np.asarray(youngs_modulus) * np.asarray(area))
    return 1.0 / (half_flex[:-1] + half_flex[1:])


def spring_dashpots(stiffness, mass, damping_ratio: float) -> np.ndarray:
    """Pile material dashpots c_i = 2 zeta sqrt(k_i (m_i + m_{i+1}) / 2) [N s/m].

    Parameters
    ----------
    stiffness : array_like
        Spring stiffness, shape (N-1,) [N/m].
    mass : array_like
        Segment masses, shape (N,) [kg].
    damping_ratio : float
        Fraction of critical zeta [-].

    Returns
    -------
    numpy.ndarray
        Dashpot constants c_i, shape (N-1,) [N s/m].
    """
    mean_mass = 0.5 * (np.asarray(mass)[:-1] + np.asarray(mass)[1:])
    return 2.0 * damping_ratio * np.sqrt(np.asarray(stiffness) * mean_mass)


def discretise(pile: PileSpec) -> Segments:
    """Cut every section into ceil(length / segment_length) equal segments.

    Parameters
    ----------
    pile : PileSpec
        The pile to discretise.

    Returns
    -------
    Segments
        The per-segment properties, head first.
    """
    rows = []
    top = 0.0
    for s in pile.sections:
        n = max(1, math.ceil(s.length / pile.segment_length - 1e-9))
        dx = s.length / n
        for i in range(n):
            rows.append((top + i * dx, top + (i + 1) * dx if i < n - 1 else top + s.length,
                         s.area, s.youngs_modulus, s.density, s.outer_diameter,
                         s.wall_thickness))
        top += s.length
    a = np.array(rows, dtype=float)
    return Segments(*(a[:, j].copy() for j in range(7)))


def pile_parameters(pile: PileSpec, segments: Segments | None = None) -> np.ndarray:
    """The pile parameter array of the kernels, shape (PILE_ROWS, N), float64.

    Row PILE_MASS: segment masses [kg]; row PILE_STIFFNESS: the spring below each mass [N/m]
    (0 below the toe mass); row PILE_DASHPOT: the material dashpot below each mass [N s/m].

    Parameters
    ----------
    pile : PileSpec
        The pile.
    segments : Segments, optional
        Its segments; discretised from `pile` when None.

    Returns
    -------
    numpy.ndarray
        The parameter array, shape (PILE_ROWS, N).

    Raises
    ------
    ValueError
        If the pile has fewer than 2 segments (reduce segment_length).
    """
    seg = segments if segments is not None else discretise(pile)
    if seg.count < 2:
        raise ValueError("the pile needs at least 2 segments (reduce segment_length)")
    mass = segment_masses(seg.density, seg.area, seg.length)
    k = spring_stiffnesses(seg.youngs_modulus, seg.area, seg.length)
    params = np.zeros((PILE_ROWS, seg.count))
    params[PILE_MASS] = mass
    params[PILE_STIFFNESS, :-1] = k
    if pile.material_damping_model == "uniform":
        params[PILE_DASHPOT, :-1] = grlweap_uniform_pile_damping(pile, seg)
    else:
        params[PILE_DASHPOT, :-1] = spring_dashpots(k, mass, pile.material_damping)
    return params


def grlweap_uniform_pile_damping(pile: PileSpec, segments: Segments) -> float:
    """GRLWEAP's pile damping: 2 zeta E A / c of the section at mid-length for every spring.

    zeta = ``material_damping``; GRLWEAP's "1 %" is zeta = 0.01.

    Parameters
    ----------
    pile : PileSpec
        The pile (its ``material_damping`` and length are used).
    segments : Segments
        Its segments.

    Returns
    -------
    float
        The dashpot constant of every spring [N s/m].

    References
    ----------
    Rausche, F., Likins, G.E., Liang, L., Hussein, M.H. GRLWEAP background report (Pile
    Dynamics Inc.).
    """
    mid = int(np.searchsorted(segments.bottom, 0.5 * pile.length))
    mid = min(mid, segments.count - 1)
    e, a, rho = (segments.youngs_modulus[mid], segments.area[mid], segments.density[mid])
    return 2.0 * pile.material_damping * a * math.sqrt(e * rho)


def _bracket(positions: np.ndarray, depth: float) -> tuple[int, float]:
    """Index j and weight w with depth ~ (1 - w) positions[j] + w positions[j+1], clamped."""
    if positions.size == 1 or depth <= positions[0]:
        return 0, 0.0
    if depth >= positions[-1]:
        return positions.size - 1, 0.0
    j = int(np.searchsorted(positions, depth, side="right")) - 1
    return j, float((depth - positions[j]) / (positions[j + 1] - positions[j]))


def head_extrapolation(segments: Segments) -> float:
    """Ratio e [-] with u_head = u_0 + e (u_0 - u_1).

    The flexibility of the top half-segment, dx_0 / (2 E_0 A_0), over that of the first spring
    (1/2 for a uniform top).

    Parameters
    ----------
    segments : Segments
        The pile segments (at least 2).

    Returns
    -------
    float
        The head extrapolation ratio e [-].
    """
    half = 0.5 * segments.length[:2] / (segments.youngs_modulus[:2] * segments.area[:2])
    return float(half[0] / (half[0] + half[1]))


def probe_parameters(pile: PileSpec, segments: Segments | None = None) -> np.ndarray:
    """The probe array of the output kernels, shape (PROBE_SIZE,), float64.

    [gauge spring index, its weight, gauge mass index, its weight, head extrapolation ratio];
    indices are stored as floats.

    Parameters
    ----------
    pile : PileSpec
        The pile (its ``gauge_depth`` is used).
    segments : Segments, optional
        Its segments; discretised from `pile` when None.

    Returns
    -------
    numpy.ndarray
        The probe array, shape (PROBE_SIZE,).
    """
    seg = segments if segments is not None else discretise(pile)
    springs = seg.bottom[:-1]
    j, w = _bracket(springs, pile.gauge_depth)
    i, wm = _bracket(seg.centre, pile.gauge_depth)
    probes = np.zeros(PROBE_SIZE)
    probes[GAUGE_SPRING], probes[GAUGE_SPRING_WEIGHT] = j, w
    probes[GAUGE_MASS], probes[GAUGE_MASS_WEIGHT] = i, wm
    probes[HEAD_EXTRAPOLATION] = head_extrapolation(seg)
    return probes


# ---------------------------------------------------------------------------- input
def section_from_table(table: Table) -> Section:
    """One ``[[pile.sections]]`` entry.

    Parameters
    ----------
    table : Table
        The section table.

    Returns
    -------
    Section
        The validated section.

    Raises
    ------
    InputError
        If an entry is missing or invalid (e.g. a wall thicker than half the diameter).
    """
    length = table.number("length", gt=0.0, unit="m")
    diameter = table.number("outer_diameter", gt=0.0, unit="m")
    wall = table.number("wall_thickness", gt=0.0, unit="m")
    if wall > 0.5 * diameter:
        raise table.error("wall_thickness",
                          f"must be at most half the outer diameter ({0.5 * diameter:g} m)")
    section = Section(
        length=length, outer_diameter=diameter, wall_thickness=wall,
        youngs_modulus=table.number("youngs_modulus", STEEL_YOUNGS_MODULUS, gt=0.0, unit="Pa"),
        density=table.number("density", STEEL_DENSITY, gt=0.0, unit="kg/m^3"),
    )
    table.finish()
    return section


MAX_SEGMENTS = 20_000
"""Most pile segments a case may have: 2 cm segments on a 400 m pile, far beyond what the
wave equation needs, and still small for this machine."""


def pile_from_table(table: Table) -> PileSpec:
    """Read and validate the ``[pile]`` table (see the module docstring).

    Parameters
    ----------
    table : Table
        The ``[pile]`` table.

    Returns
    -------
    PileSpec
        The validated pile.

    Raises
    ------
    InputError
        If an entry is missing or invalid, or the segmentation gives fewer than 2 or more than
        MAX_SEGMENTS segments.
    """
    segment_length = table.number("segment_length", DEFAULT_SEGMENT_LENGTH, gt=0.0, unit="m")
    damping = table.number("material_damping", DEFAULT_MATERIAL_DAMPING, ge=0.0, lt=1.0)
    damping_model = table.string("material_damping_model", "segment",
                                 choices=("segment", "uniform"))
    sections = tuple(section_from_table(t) for t in table.tables("sections"))
    if not sections:
        raise table.error("sections", "needs at least one [[pile.sections]] entry")
    length = sum(s.length for s in sections)
    gauge_depth = table.number("gauge_depth", DEFAULT_GAUGE_DEPTH, ge=0.0, lt=length, unit="m")
    n_segments = sum(math.ceil(s.length / segment_length - 1e-9) for s in sections)
    if n_segments > MAX_SEGMENTS:
        c = min(s.wave_speed for s in sections)
        steps = 0.025 / (segment_length / c)
        raise table.error(
            "segment_length",
            f"gives a pile too big for this machine: {n_segments:.3g} segments "
            f"({n_segments * 8 * 12 / 2**30:.3g} GiB of state), a stable step of "
            f"{segment_length / c:.2g} s ({steps:.3g} steps and {steps * n_segments:.3g} "
            f"segment updates per 25 ms blow; limit {MAX_SEGMENTS} segments); use at least "
            f"{length / MAX_SEGMENTS:.3g} m")
    yield_strength = table.number("yield_strength", DEFAULT_YIELD_STRENGTH, gt=0.0, unit="Pa")
    pile = PileSpec(sections, segment_length, gauge_depth, damping, damping_model,
                    yield_strength)
    if discretise(pile).count < 2:
        raise table.error("segment_length",
                          f"must give at least 2 segments over the {length:g} m pile")
    table.finish()
    return pile


def load_pile(path) -> PileSpec:
    """Read a file whose only table is ``[pile]``.

    Parameters
    ----------
    path : str or path-like
        The TOML file.

    Returns
    -------
    PileSpec
        The validated pile.
    """
    root = Table.from_file(path)
    pile = pile_from_table(root.table("pile"))
    root.finish()
    return pile


__all__ = [
    "InputError", "PileSpec", "Section", "Segments", "discretise", "head_extrapolation",
    "load_pile", "pile_from_table", "pile_parameters", "probe_parameters", "section_area",
    "segment_masses", "spring_dashpots", "spring_stiffnesses",
]
