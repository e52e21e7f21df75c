"""Soil models along the shaft and at the toe, selectable by name.

A soil table is TOML::

    [soil]
    model = "smith-viscous"      # "smith", "smith-viscous" or "lysmer-toe"
    penetration = 30.0           # [m] embedded length (the pile sticks up L - penetration)
    quake_shaft = 0.0025         # [m]
    quake_toe = 0.0025           # [m]   not for "lysmer-toe"
    damping_shaft = 0.65         # [s/m] Smith damping factor J
    damping_toe = 0.5            # [s/m] not for "lysmer-toe"
    friction_perimeter = "outside+inside"   # or "outside"
    toe_area = "annulus"         # or "plugged"
    srd = [[0.0, 0.0, 0.0], [30.0, 80e3, 8e6]]  # depth [m], unit shaft [Pa], unit toe [Pa]

Models (every soil spring is the elastic-perfectly-plastic Smith spring of
:func:`anvilwave.pile.kernels.soil_resistance`; they differ only in the parameter arrays, so one
kernel
serves all and the in-process engine needs no branch):

``"smith"``         Smith (1960): quake q, R_d = J |R_s| v (damping proportional to the
                    mobilised static resistance).
``"smith-viscous"`` GRLWEAP's Smith-viscous damping: R_d = J R_u v, a linear dashpot
                    c = J R_u (the default: damping does not depend on the history of R_s).
``"lysmer-toe"``    Smith-viscous shaft; the toe is Lysmer's analog (Lysmer & Richart 1966) of
                    a rigid disc of radius r0 on an elastic half-space: spring
                    k = 4 G r0 / (1 - nu) with a plastic limit at the toe capacity (so its quake
                    is R_u / k) and a radiation dashpot c = 3.4 r0^2 sqrt(G rho) / (1 - nu)
                    = (3.4 / pi) / (1 - nu) rho c_s A, with c_s = sqrt(G / rho) and r0 the
                    radius of the toe area A. Keys: toe_shear_modulus [Pa], toe_density
                    [kg/m^3], toe_poisson_ratio [-] (default 0.3) instead of quake_toe and
                    damping_toe. Deeks & Randolph (1995) use this toe in wave-equation analysis.

Quakes and dampings per layer: ``layers = [[top [m], bottom [m], quake_shaft [m], quake_toe
[m], damping_shaft [s/m], damping_toe [s/m]], ...]`` (depths below the mudline, layers not
overlapping; :class:`SoilLayers`) give each shaft segment the shaft values of the layer holding
the middle of its embedded part, and the toe the toe values of the layer holding the tip (the
upper layer when the tip lies on a boundary); depths outside every layer keep the table's
scalar values. :func:`smith_damping_by_soil_type` gives the customary Smith values by soil type.

Shaft springs resist both ways with the same capacity (friction reverses); the toe takes no
tension (it lifts off and re-contacts at its permanent set). Defaults: quake 2.5 mm shaft and
toe (GRLWEAP's recommendation for the shaft and for the toe of non-displacement piles such as
coring open-ended tubes; D/120 of the toe diameter is the offshore choice for plugged/
displacement toes - set ``quake_toe`` explicitly), Smith damping 0.65 s/m shaft (clay;
0.16 s/m for sand) and 0.5 s/m toe.

References
----------
Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech. Found.
Div. 86(4), 35-61.
Lysmer, J., Richart, F.E. (1966). Dynamic response of footings to vertical loading. ASCE J.
Soil Mech. Found. Div. 92(SM1), 65-91.
Deeks, A.J., Randolph, M.F. (1995). A simple model for inelastic footing response to transient
loading. Int. J. Numer. Anal. Methods Geomech. 19(5), 307-329.
Rausche, F., Goble, G.G., Likins, G.E. GRLWEAP background report (Pile Dynamics Inc.).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from anvilwave.inputs import Table
from anvilwave.pile.kernels import (
    SOIL_CAPACITY,
    SOIL_DASHPOT,
    SOIL_ROWS,
    SOIL_SMITH,
    SOIL_STIFFNESS,
    SOIL_TENSION,
)
from anvilwave.pile.pile import PileSpec, Segments, discretise
from anvilwave.pile.soil.srd import (
    PERIMETERS,
    TOE_AREAS,
    SoilResistanceTable,
    shaft_capacities,
    toe_area,
    toe_capacity,
)

MODELS = ("smith", "smith-viscous", "lysmer-toe")
"""Soil model names."""
DEFAULT_MODEL = "smith-viscous"
DEFAULT_QUAKE = 0.0025
"""Default shaft and toe quake [m]."""
DEFAULT_DAMPING_SHAFT = 0.65
"""Default Smith damping factor on the shaft [s/m]."""
DEFAULT_DAMPING_TOE = 0.5
"""Default Smith damping factor at the toe [s/m]."""
DEFAULT_TOE_POISSON_RATIO = 0.3


@dataclass(frozen=True, eq=False)
class SoilSpec:
    """Soil along an embedded pile.

    Parameters
    ----------
    model : str
        One of :data:`MODELS`.
    penetration : float
        Embedded length below the mudline [m].
    srd : SoilResistanceTable or None
        Unit resistances against depth below the mudline.
    quake_shaft : float, default DEFAULT_QUAKE
        Shaft quake [m].
    quake_toe : float, default DEFAULT_QUAKE
        Toe quake [m] (unused by "lysmer-toe").
    damping_shaft : float, default DEFAULT_DAMPING_SHAFT
        Shaft Smith damping factor J [s/m].
    damping_toe : float, default DEFAULT_DAMPING_TOE
        Toe Smith damping factor J [s/m] (unused by "lysmer-toe").
    friction_perimeter : {"outside+inside", "outside"}
        See :func:`anvilwave.pile.soil.srd.shaft_perimeter`.
    toe_area : {"annulus", "plugged"}
        See :func:`anvilwave.pile.soil.srd.toe_area`.
    toe_shear_modulus : float, default 0.0
        Soil shear modulus below the toe G [Pa] ("lysmer-toe").
    toe_density : float, default 0.0
        Soil density below the toe [kg/m^3] ("lysmer-toe").
    toe_poisson_ratio : float, default DEFAULT_TOE_POISSON_RATIO
        Soil Poisson's ratio below the toe [-] ("lysmer-toe").
    capacities : tuple or None, default None
        (shaft per segment (N,) [N], toe [N]) given directly (an SRD distribution computed
        elsewhere, e.g. per tip depth with friction fatigue); when set, ``srd``,
        ``friction_perimeter`` and ``toe_area`` do not enter the capacities.
    layers : SoilLayers or None, default None
        Quakes and dampings per layer (module docstring).
    """

    model: str
    penetration: float
    srd: SoilResistanceTable | None
    quake_shaft: float = DEFAULT_QUAKE
    quake_toe: float = DEFAULT_QUAKE
    damping_shaft: float = DEFAULT_DAMPING_SHAFT
    damping_toe: float = DEFAULT_DAMPING_TOE
    friction_perimeter: str = PERIMETERS[0]
    toe_area: str = TOE_AREAS[0]
    toe_shear_modulus: float = 0.0
    toe_density: float = 0.0
    toe_poisson_ratio: float = DEFAULT_TOE_POISSON_RATIO
    capacities: tuple | None = None
    layers: SoilLayers | None = None


SOIL_TYPE_SMITH_DAMPING = {"sand": (0.16, 0.5), "clay": (0.65, 0.5)}
"""Smith damping factors (shaft, toe) [s/m] by soil type: 0.05 s/ft in non-cohesive ("sand")
and 0.2 s/ft in cohesive ("clay") soils on the shaft, 0.15 s/ft at the toe, rounded (the
wave-equation recommendations of Hannigan et al. 2016, FHWA-NHI-16-009, also GRLWEAP's)."""


def smith_damping_by_soil_type(soil_type: str) -> tuple[float, float]:
    """Smith damping factors (shaft, toe) [s/m] customary for a soil type.

    Parameters
    ----------
    soil_type : str
        "sand" or "clay".

    Returns
    -------
    tuple of float
        (shaft J [s/m], toe J [s/m]) of :data:`SOIL_TYPE_SMITH_DAMPING`.

    References
    ----------
    Hannigan, P.J., Rausche, F., Likins, G.E., Robinson, B.R., Becker, M.L. (2016). Design and
    construction of driven pile foundations, Vol. II. FHWA-NHI-16-009, Federal Highway
    Administration, Washington DC.
    """
    try:
        return SOIL_TYPE_SMITH_DAMPING[soil_type]
    except KeyError:
        raise ValueError(f"unknown soil type {soil_type!r}; choose one of "
                         f"{tuple(SOIL_TYPE_SMITH_DAMPING)}") from None


LAYER_COLUMNS = ("top [m]", "bottom [m]", "quake_shaft [m]", "quake_toe [m]",
                 "damping_shaft [s/m]", "damping_toe [s/m]")
"""Columns of the per-layer soil parameters (:class:`SoilLayers`)."""


@dataclass(frozen=True, eq=False)
class SoilLayers:
    """Quakes and Smith dampings per soil layer (module docstring).

    Parameters
    ----------
    rows : numpy.ndarray
        (n, 6) rows of :data:`LAYER_COLUMNS`, depths below the mudline, top < bottom, sorted
        and not overlapping; quakes > 0, dampings >= 0.
    """

    rows: np.ndarray

    def __post_init__(self):
        rows = np.atleast_2d(np.asarray(self.rows, dtype=float))
        object.__setattr__(self, "rows", rows)
        problem = self.problem()
        if problem is not None:
            raise ValueError(problem)

    def problem(self) -> str | None:
        """Why the rows are not valid, or None.

        Returns
        -------
        str or None
            The problem, None when the rows are valid.
        """
        r = self.rows
        if r.ndim != 2 or r.shape[1] != 6 or r.shape[0] < 1:
            return "needs rows [top, bottom, quake_shaft, quake_toe, damping_shaft, damping_toe]"
        if not np.all(np.isfinite(r)):
            return "must contain finite numbers only"
        if np.any(r[:, 0] < 0.0) or np.any(r[:, 1] <= r[:, 0]):
            return "layers need 0 <= top < bottom [m]"
        if np.any(r[1:, 0] < r[:-1, 1] - 1e-9):
            return "layers must be sorted by depth and must not overlap"
        if np.any(r[:, 2:4] <= 0.0):
            return "quakes must be positive [m]"
        if np.any(r[:, 4:6] < 0.0):
            return "dampings must not be negative [s/m]"
        return None

    def values(self, depth, column: int, default: float, upper: bool = False) -> np.ndarray:
        """Column ``column`` of the layer holding each ``depth``; ``default`` outside every layer.

        Parameters
        ----------
        depth : float or array_like
            Depths below the mudline [m].
        column : int
            Index into :data:`LAYER_COLUMNS`.
        default : float
            Value outside every layer [unit of the column].
        upper : bool, default False
            A depth on a boundary belongs to the layer above it.

        Returns
        -------
        numpy.ndarray
            The values at the depths [unit of the column].
        """
        z = np.atleast_1d(np.asarray(depth, dtype=float))
        out = np.full(z.shape, float(default))
        for top, bottom, *vals in self.rows:
            inside = (z > top) & (z <= bottom) if upper else (z >= top) & (z < bottom)
            out[inside] = vals[column - 2]
        return out


def layer_values(soil: SoilSpec, segments: Segments, pile_length: float):
    """Quakes and dampings of the soil's segments and toe.

    Per layer where ``soil.layers`` gives them, else the soil's scalars.

    Parameters
    ----------
    soil : SoilSpec
        The soil.
    segments : Segments
        The pile's segments.
    pile_length : float
        Pile length [m] (the mudline lies ``pile_length - penetration`` below the head).

    Returns
    -------
    quake_shaft : numpy.ndarray
        (N,) shaft quake [m].
    damping_shaft : numpy.ndarray
        (N,) shaft damping [s/m].
    quake_toe : float
        Toe quake [m].
    damping_toe : float
        Toe damping [s/m].
    """
    n = segments.count
    qs = np.full(n, float(soil.quake_shaft))
    js = np.full(n, float(soil.damping_shaft))
    qt, jt = float(soil.quake_toe), float(soil.damping_toe)
    if soil.layers is None:
        return qs, js, qt, jt
    mudline = pile_length - soil.penetration
    low = np.clip(segments.top - mudline, 0.0, soil.penetration)
    high = np.clip(segments.bottom - mudline, 0.0, soil.penetration)
    middle = 0.5 * (low + high)
    layers = soil.layers
    qs = layers.values(middle, 2, soil.quake_shaft)
    js = layers.values(middle, 4, soil.damping_shaft)
    qt = float(layers.values(soil.penetration, 3, soil.quake_toe, upper=True)[0])
    jt = float(layers.values(soil.penetration, 5, soil.damping_toe, upper=True)[0])
    return qs, js, qt, jt


def toe_quake(soil: SoilSpec, pile: PileSpec) -> float:
    """The toe quake of the soil at its penetration (per layer where given).

    Parameters
    ----------
    soil : SoilSpec
        The soil.
    pile : PileSpec
        The pile.

    Returns
    -------
    float
        Toe quake [m].
    """
    if soil.layers is None:
        return float(soil.quake_toe)
    return layer_values(soil, discretise(pile), pile.length)[2]


def lysmer_stiffness(shear_modulus: float, radius: float, poisson_ratio: float) -> float:
    """Static stiffness of a rigid disc on an elastic half-space, 4 G r0 / (1 - nu) [N/m].

    Lysmer & Richart (1966).

    Parameters
    ----------
    shear_modulus : float
        G [Pa].
    radius : float
        r0 [m].
    poisson_ratio : float
        nu [-].

    Returns
    -------
    float
        Stiffness [N/m].
    """
    return 4.0 * shear_modulus * radius / (1.0 - poisson_ratio)


def lysmer_dashpot(shear_modulus: float, density: float, radius: float,
                   poisson_ratio: float) -> float:
    """Radiation dashpot of Lysmer's analog, 3.4 r0^2 sqrt(G rho) / (1 - nu) [N s/m].

    Parameters
    ----------
    shear_modulus : float
        G [Pa].
    density : float
        rho [kg/m^3].
    radius : float
        r0 [m].
    poisson_ratio : float
        nu [-].

    Returns
    -------
    float
        Dashpot [N s/m].
    """
    return 3.4 * radius * radius * math.sqrt(shear_modulus * density) / (1.0 - poisson_ratio)


def smith_springs(capacity, quake, damping, viscous: bool) -> tuple:
    """Stiffness, Smith J and dashpot arrays of Smith springs.

    Parameters
    ----------
    capacity : array_like
        R_u [N].
    quake : array_like
        q [m].
    damping : array_like
        J [s/m].
    viscous : bool
        Smith-viscous (c = J R_u) instead of Smith (J applied to |R_s| in the kernel).

    Returns
    -------
    stiffness : numpy.ndarray
        R_u / q [N/m].
    smith_j : numpy.ndarray
        Smith J [s/m] (0 when viscous).
    dashpot : numpy.ndarray
        Dashpot [N s/m] (0 unless viscous).
    """
    capacity = np.asarray(capacity, dtype=float)
    stiffness = capacity / quake
    if viscous:
        return stiffness, np.zeros_like(capacity), damping * capacity
    return (stiffness, np.broadcast_to(np.asarray(damping, dtype=float), capacity.shape).copy(),
            np.zeros_like(capacity))


def soil_capacities(soil: SoilSpec, pile: PileSpec, segments: Segments | None = None):
    """Static shaft resistance per segment and toe resistance.

    Parameters
    ----------
    soil : SoilSpec
        The soil.
    pile : PileSpec
        The pile.
    segments : Segments or None, default None
        The pile's segments (default: ``discretise(pile)``).

    Returns
    -------
    shaft : numpy.ndarray
        (N,) shaft resistance per segment [N].
    toe : float
        Toe resistance [N].

    Raises
    ------
    ValueError
        If ``soil.capacities`` has not one shaft value per segment.
    """
    seg = segments if segments is not None else discretise(pile)
    if soil.capacities is not None:
        shaft, toe = soil.capacities
        shaft = np.asarray(shaft, dtype=float)
        if shaft.shape != (seg.count,):
            raise ValueError(f"capacities: {shaft.shape[0]} shaft values for "
                             f"{seg.count} segments")
        return shaft.copy(), float(toe)
    mudline = pile.length - soil.penetration
    shaft = shaft_capacities(soil.srd, seg.top, seg.bottom, mudline, seg.outer_diameter,
                             seg.wall_thickness, soil.friction_perimeter)
    toe = toe_capacity(soil.srd, soil.penetration, seg.outer_diameter[-1],
                       seg.wall_thickness[-1], soil.toe_area)
    return shaft, toe


def soil_parameters(soil: SoilSpec | None, pile: PileSpec,
                    segments: Segments | None = None) -> np.ndarray:
    """The soil parameter array of the kernels, shape (SOIL_ROWS, N+1), float64 (toe last).

    Parameters
    ----------
    soil : SoilSpec or None
        The soil; None gives a pile without soil (all zeros: a free toe).
    pile : PileSpec
        The pile.
    segments : Segments or None, default None
        The pile's segments (default: ``discretise(pile)``).

    Returns
    -------
    numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters.
    """
    seg = segments if segments is not None else discretise(pile)
    params = np.zeros((SOIL_ROWS, seg.count + 1))
    if soil is None:
        return params
    shaft, toe = soil_capacities(soil, pile, seg)
    viscous = soil.model != "smith"
    qs, js, qt, jt = layer_values(soil, seg, pile.length)
    k, smith, dashpot = smith_springs(shaft, qs, js, viscous)
    params[SOIL_CAPACITY, :-1] = shaft
    params[SOIL_TENSION, :-1] = shaft
    params[SOIL_STIFFNESS, :-1] = k
    params[SOIL_SMITH, :-1] = smith
    params[SOIL_DASHPOT, :-1] = dashpot
    params[SOIL_CAPACITY, -1] = toe
    params[SOIL_TENSION, -1] = 0.0
    if soil.model == "lysmer-toe":
        area = toe_area(seg.outer_diameter[-1], seg.wall_thickness[-1], soil.toe_area)
        radius = math.sqrt(area / math.pi)
        params[SOIL_STIFFNESS, -1] = lysmer_stiffness(soil.toe_shear_modulus, radius,
                                                      soil.toe_poisson_ratio)
        params[SOIL_DASHPOT, -1] = lysmer_dashpot(soil.toe_shear_modulus, soil.toe_density,
                                                  radius, soil.toe_poisson_ratio)
    else:
        k, smith, dashpot = smith_springs(np.array([toe]), qt, jt, viscous)
        params[SOIL_STIFFNESS, -1] = k[0]
        params[SOIL_SMITH, -1] = smith[0]
        params[SOIL_DASHPOT, -1] = dashpot[0]
    return params


# ---------------------------------------------------------------------------- input
def _layers(table: Table) -> SoilLayers | None:
    """The ``layers`` rows of a soil table (:class:`SoilLayers`), or None."""
    rows = table.array("layers", None, columns=6)
    if rows is None:
        return None
    try:
        return SoilLayers(rows)
    except ValueError as exc:
        raise table.error("layers", str(exc)) from None


def soil_from_table(table: Table, pile_length: float, srd_optional: bool = False,
                    default_penetration: float | None = None) -> SoilSpec:
    """Read and validate the ``[soil]`` table (module docstring).

    Parameters
    ----------
    table : Table
        The ``[soil]`` table.
    pile_length : float
        Length of the pile the soil is for [m] (bounds the penetration).
    srd_optional : bool, default False
        The SRD comes from elsewhere (a drive analysis's ``[srd]`` table): ``srd`` may be
        omitted, and ``penetration`` then defaults to ``default_penetration``.
    default_penetration : float or None, default None
        Penetration when ``srd_optional`` and none is given [m].

    Returns
    -------
    SoilSpec
        The soil.

    Raises
    ------
    InputError
        If a key breaks its rule.
    """
    model = table.string("model", DEFAULT_MODEL, choices=MODELS)
    if srd_optional and default_penetration is not None:
        penetration = table.number("penetration", min(default_penetration, pile_length),
                                   ge=0.0, le=pile_length, unit="m")
    else:
        penetration = table.number("penetration", ge=0.0, le=pile_length, unit="m")
    srd = None
    if table.has("srd") or not srd_optional:
        rows = table.array("srd", columns=3)
        srd = SoilResistanceTable.from_rows(rows)
        problem = srd.check()
        if problem is None and srd.depth[-1] < penetration:
            problem = (f"must reach the penetration depth {penetration:g} m "
                       f"(last row at {srd.depth[-1]:g} m)")
        if problem is not None:
            raise table.error("srd", problem)
    common = dict(
        model=model, penetration=penetration, srd=srd,
        quake_shaft=table.number("quake_shaft", DEFAULT_QUAKE, gt=0.0, unit="m"),
        damping_shaft=table.number("damping_shaft", DEFAULT_DAMPING_SHAFT, ge=0.0, unit="s/m"),
        friction_perimeter=table.string("friction_perimeter", PERIMETERS[0], choices=PERIMETERS),
        toe_area=table.string("toe_area", TOE_AREAS[0], choices=TOE_AREAS),
        layers=_layers(table),
    )
    if model == "lysmer-toe":
        spec = SoilSpec(
            **common,
            toe_shear_modulus=table.number("toe_shear_modulus", gt=0.0, unit="Pa"),
            toe_density=table.number("toe_density", gt=0.0, unit="kg/m^3"),
            toe_poisson_ratio=table.number("toe_poisson_ratio", DEFAULT_TOE_POISSON_RATIO,
                                           ge=0.0, lt=0.5),
        )
    else:
        spec = SoilSpec(
            **common,
            quake_toe=table.number("quake_toe", DEFAULT_QUAKE, gt=0.0, unit="m"),
            damping_toe=table.number("damping_toe", DEFAULT_DAMPING_TOE, ge=0.0, unit="s/m"),
        )
    table.finish()
    return spec
