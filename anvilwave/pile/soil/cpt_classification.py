"""Soil classification from a CPT: Robertson's soil behaviour type index Ic, sand or clay layers.

Pure, vectorised functions named after their sources (SI units: stresses in Pa, depths in m),
and :func:`soil_layers_from_cpt`, which turns a :class:`anvilwave.pile.soil.profile.Cpt` into the
sand
and clay :class:`anvilwave.pile.soil.profile.SoilLayer` list a CPT-based SRD method needs (Alm &
Hamre
2001 takes qt and fs from the CPT; the layers only say which formula applies, and carry the
submerged unit weight for sigma'v0 and the interface friction angle of the sand).

Normalisation (sigma_v0 total, sigma'v0 effective vertical stress, pa = 100 kPa)::

    Robertson (1990):  Q  = (qt - sigma_v0) / sigma'v0,      F = 100 fs / (qt - sigma_v0) [%]
    Robertson (2009):  Qtn = ((qt - sigma_v0) / pa) (pa / sigma'v0)^n,
                       n = 0.381 Ic + 0.05 sigma'v0 / pa - 0.15  (n <= 1; iterated with Ic)
    Robertson & Wride (1998):  Ic = sqrt((3.47 - log10 Q)^2 + (log10 F + 1.22)^2)

Ic < 2.6 is sand-like (coarse-grained, drained penetration), Ic >= 2.6 clay-like
(fine-grained, undrained): Robertson (2009), whose transition band is 2.5-2.7; the boundary is
a parameter. Q and F are clipped to the extent of Robertson's chart (Q 1-1000, F 0.1-10 %)
before the logarithms: next to the mudline qt - sigma_v0 may be ~0 and a zero sleeve friction
would give log10(0).

Offshore convention (as :mod:`anvilwave.pile.soil.profile`): the cone is zeroed at the seabed, so
qt and
u2 exclude the ambient water pressure there, and below the mudline sigma_v0 = sigma'v0 + u0
with the hydrostatic u0 = gamma_w z: the water depth plays no part.

References
----------
Robertson, P.K. (1990). Soil classification using the cone penetration test. Canadian
Geotechnical Journal 27(1), 151-158.
Robertson, P.K., Wride, C.E. (1998). Evaluating cyclic liquefaction potential using the cone
penetration test. Canadian Geotechnical Journal 35(3), 442-459 (eq. for Ic).
Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
Canadian Geotechnical Journal 46(11), 1337-1355.
"""

from __future__ import annotations

import numpy as np

from anvilwave.pile.soil.profile import DEFAULT_NET_AREA_RATIO, Cpt, SoilLayer

ATMOSPHERIC_PRESSURE = 100e3
"""Reference pressure pa of the normalisations [Pa]."""
ROBERTSON_2009_SAND_CLAY_BOUNDARY = 2.6
"""Ic separating sand-like (below) from clay-like (at and above) behaviour [-]."""
SEAWATER_UNIT_WEIGHT = 10.05e3
"""Unit weight of sea water [N/m^3] (for the hydrostatic u0 below the mudline)."""
CHART_Q_RANGE = (1.0, 1000.0)
"""Extent of Robertson's chart in normalised cone resistance [-]."""
CHART_F_RANGE = (0.1, 10.0)
"""Extent of Robertson's chart in normalised friction ratio [%]."""


def robertson_1990_normalised_cone_resistance(qt, sigma_v0, sigma_v0_effective):
    """Q = (qt - sigma_v0) / sigma'v0 [-] (Robertson 1990).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    sigma_v0 : float or array_like
        Total vertical stress [Pa].
    sigma_v0_effective : float or array_like
        Effective vertical stress [Pa] (> 0).

    Returns
    -------
    numpy.ndarray
        Normalised cone resistance Q [-].

    References
    ----------
    Robertson, P.K. (1990). Soil classification using the cone penetration test. Canadian
    Geotechnical Journal 27(1), 151-158. https://doi.org/10.1139/t90-014
    """
    qt, sv, se = (np.asarray(a, dtype=float) for a in (qt, sigma_v0, sigma_v0_effective))
    return (qt - sv) / se


def robertson_1990_normalised_friction_ratio(fs, qt, sigma_v0):
    """F = 100 fs / (qt - sigma_v0) [%] (Robertson 1990).

    Parameters
    ----------
    fs : float or array_like
        Sleeve friction [Pa].
    qt : float or array_like
        Corrected cone resistance [Pa].
    sigma_v0 : float or array_like
        Total vertical stress [Pa].

    Returns
    -------
    numpy.ndarray
        Normalised friction ratio F [%].

    References
    ----------
    Robertson, P.K. (1990). Soil classification using the cone penetration test. Canadian
    Geotechnical Journal 27(1), 151-158. https://doi.org/10.1139/t90-014
    """
    fs, qt, sv = (np.asarray(a, dtype=float) for a in (fs, qt, sigma_v0))
    with np.errstate(divide="ignore", invalid="ignore"):
        return 100.0 * fs / (qt - sv)


def robertson_wride_1998_soil_behaviour_type_index(q, f):
    """Ic = sqrt((3.47 - log10 Q)^2 + (log10 F + 1.22)^2) [-] (Robertson & Wride 1998).

    Both inputs are clipped to the chart's extent (:data:`CHART_Q_RANGE`,
    :data:`CHART_F_RANGE`).

    Parameters
    ----------
    q : float or array_like
        Normalised cone resistance Q or Qtn [-].
    f : float or array_like
        Normalised friction ratio F [%].

    Returns
    -------
    numpy.ndarray
        Soil behaviour type index Ic [-].

    References
    ----------
    Robertson, P.K., Wride, C.E. (1998). Evaluating cyclic liquefaction potential using the cone
    penetration test. Canadian Geotechnical Journal 35(3), 442-459.
    https://doi.org/10.1139/t98-017
    """
    q = np.clip(np.nan_to_num(np.asarray(q, dtype=float), nan=CHART_Q_RANGE[0],
                              posinf=CHART_Q_RANGE[1], neginf=CHART_Q_RANGE[0]), *CHART_Q_RANGE)
    f = np.clip(np.nan_to_num(np.asarray(f, dtype=float), nan=CHART_F_RANGE[1],
                              posinf=CHART_F_RANGE[1], neginf=CHART_F_RANGE[0]), *CHART_F_RANGE)
    return np.sqrt((3.47 - np.log10(q)) ** 2 + (np.log10(f) + 1.22) ** 2)


def robertson_1990_soil_behaviour_type_index(qt, fs, sigma_v0, sigma_v0_effective):
    """Ic from Robertson's (1990) Q and F (stress exponent n = 1) [-].

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    fs : float or array_like
        Sleeve friction [Pa].
    sigma_v0 : float or array_like
        Total vertical stress [Pa].
    sigma_v0_effective : float or array_like
        Effective vertical stress [Pa].

    Returns
    -------
    numpy.ndarray
        Soil behaviour type index Ic [-].

    References
    ----------
    Robertson, P.K. (1990). Soil classification using the cone penetration test. Canadian
    Geotechnical Journal 27(1), 151-158. https://doi.org/10.1139/t90-014
    """
    q = robertson_1990_normalised_cone_resistance(qt, sigma_v0, sigma_v0_effective)
    f = robertson_1990_normalised_friction_ratio(fs, qt, sigma_v0)
    return robertson_wride_1998_soil_behaviour_type_index(q, f)


def robertson_2009_stress_exponent(ic, sigma_v0_effective, atmospheric_pressure=
                                   ATMOSPHERIC_PRESSURE):
    """n = 0.381 Ic + 0.05 sigma'v0 / pa - 0.15, at most 1 [-] (Robertson 2009, eq. 7).

    Parameters
    ----------
    ic : float or array_like
        Soil behaviour type index [-].
    sigma_v0_effective : float or array_like
        Effective vertical stress [Pa].
    atmospheric_pressure : float, default ATMOSPHERIC_PRESSURE
        pa [Pa].

    Returns
    -------
    numpy.ndarray
        Stress exponent n [-].

    References
    ----------
    Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
    Canadian Geotechnical Journal 46(11), 1337-1355. https://doi.org/10.1139/T09-065
    """
    ic, se = np.asarray(ic, dtype=float), np.asarray(sigma_v0_effective, dtype=float)
    return np.minimum(0.381 * ic + 0.05 * se / atmospheric_pressure - 0.15, 1.0)


def robertson_2009_normalised_cone_resistance(qt, sigma_v0, sigma_v0_effective, n,
                                              atmospheric_pressure=ATMOSPHERIC_PRESSURE):
    """Qtn = ((qt - sigma_v0) / pa) (pa / sigma'v0)^n [-] (Robertson 2009).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    sigma_v0 : float or array_like
        Total vertical stress [Pa].
    sigma_v0_effective : float or array_like
        Effective vertical stress [Pa].
    n : float or array_like
        Stress exponent [-].
    atmospheric_pressure : float, default ATMOSPHERIC_PRESSURE
        pa [Pa].

    Returns
    -------
    numpy.ndarray
        Normalised cone resistance Qtn [-].

    References
    ----------
    Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
    Canadian Geotechnical Journal 46(11), 1337-1355. https://doi.org/10.1139/T09-065
    """
    qt, sv, se, n = (np.asarray(a, dtype=float) for a in (qt, sigma_v0, sigma_v0_effective, n))
    return (qt - sv) / atmospheric_pressure * (atmospheric_pressure / se) ** n


def robertson_2009_soil_behaviour_type_index(qt, fs, sigma_v0, sigma_v0_effective,
                                             atmospheric_pressure=ATMOSPHERIC_PRESSURE,
                                             tolerance=1e-6, max_iterations=100):
    """Ic with the stress exponent n iterated to consistency (Robertson 2009) [-].

    Starts from n = 1 (Robertson 1990) and repeats n <- n(Ic), Ic <- Ic(Qtn(n), F) until n
    changes by less than ``tolerance`` [-] everywhere (a contraction for the stresses of a
    pile's depth: dn/dIc = 0.381 and |dIc/dn| <= |log10(pa / sigma'v0)|, so the loop
    converges while sigma'v0 lies within about pa / 400 and 400 pa).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    fs : float or array_like
        Sleeve friction [Pa].
    sigma_v0 : float or array_like
        Total vertical stress [Pa].
    sigma_v0_effective : float or array_like
        Effective vertical stress [Pa].
    atmospheric_pressure : float, default ATMOSPHERIC_PRESSURE
        pa [Pa].
    tolerance : float, default 1e-6
        Convergence tolerance on n [-].
    max_iterations : int, default 100
        Most iterations [-].

    Returns
    -------
    ic : numpy.ndarray
        Soil behaviour type index Ic [-].
    n : numpy.ndarray
        Stress exponent n [-].

    References
    ----------
    Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
    Canadian Geotechnical Journal 46(11), 1337-1355. https://doi.org/10.1139/T09-065
    """
    qt, fs, sv, se = np.broadcast_arrays(*(np.asarray(a, dtype=float)
                                           for a in (qt, fs, sigma_v0, sigma_v0_effective)))
    f = robertson_1990_normalised_friction_ratio(fs, qt, sv)
    n = np.ones(qt.shape)
    ic = robertson_wride_1998_soil_behaviour_type_index(
        robertson_2009_normalised_cone_resistance(qt, sv, se, n, atmospheric_pressure), f)
    for _ in range(max_iterations):
        n_new = robertson_2009_stress_exponent(ic, se, atmospheric_pressure)
        ic = robertson_wride_1998_soil_behaviour_type_index(
            robertson_2009_normalised_cone_resistance(qt, sv, se, n_new, atmospheric_pressure),
            f)
        converged = np.all(np.abs(n_new - n) < tolerance)
        n = n_new
        if converged:
            break
    return ic, n


def robertson_2009_is_sand(ic, boundary=ROBERTSON_2009_SAND_CLAY_BOUNDARY):
    """True where the soil is sand-like, Ic < ``boundary`` [-] (Robertson 2009: 2.6).

    Parameters
    ----------
    ic : float or array_like
        Soil behaviour type index Ic [-].
    boundary : float, default ROBERTSON_2009_SAND_CLAY_BOUNDARY
        Ic boundary between sand and clay [-].

    Returns
    -------
    numpy.ndarray of bool
        True where sand-like.

    References
    ----------
    Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
    Canadian Geotechnical Journal 46(11), 1337-1355. https://doi.org/10.1139/T09-065
    """
    return np.asarray(ic, dtype=float) < boundary


# ---------------------------------------------------------------------------- layers
def _runs(is_sand: np.ndarray) -> list[tuple[int, int, bool]]:
    """(first, last + 1, sand) of every run of equal types."""
    edges = np.flatnonzero(np.diff(is_sand.astype(int))) + 1
    starts = np.concatenate(([0], edges))
    ends = np.concatenate((edges, [is_sand.size]))
    return [(int(a), int(b), bool(is_sand[a])) for a, b in zip(starts, ends, strict=True)]


def merge_thin_layers(is_sand, tops, bottoms, min_thickness: float) -> np.ndarray:
    """Types with every run thinner than ``min_thickness`` [m] absorbed by its neighbours.

    The thinnest run is flipped first (it joins its neighbours, which are of the other type),
    until every run is at least ``min_thickness`` thick or one run is left.

    Parameters
    ----------
    is_sand : array_like of bool
        Type of each interval, shape (n,).
    tops : array_like
        Interval tops, shape (n,) [m].
    bottoms : array_like
        Interval bottoms, shape (n,) [m].
    min_thickness : float
        Thinnest run kept [m] (<= 0: none merged).

    Returns
    -------
    numpy.ndarray of bool
        The merged types, shape (n,).
    """
    kind = np.asarray(is_sand, dtype=bool).copy()
    tops, bottoms = np.asarray(tops, dtype=float), np.asarray(bottoms, dtype=float)
    if min_thickness <= 0.0:
        return kind
    while True:
        runs = _runs(kind)
        if len(runs) < 2:
            return kind
        thickness = [bottoms[b - 1] - tops[a] for a, b, _ in runs]
        k = int(np.argmin(thickness))
        if thickness[k] >= min_thickness:
            return kind
        a, b, sand = runs[k]
        kind[a:b] = not sand


def soil_layers_from_cpt(cpt: Cpt, *, sand_unit_weight: float, clay_unit_weight: float,
                         sand_interface_friction_angle: float,
                         water_unit_weight: float = SEAWATER_UNIT_WEIGHT,
                         net_area_ratio: float = DEFAULT_NET_AREA_RATIO,
                         boundary: float = ROBERTSON_2009_SAND_CLAY_BOUNDARY,
                         min_layer_thickness: float = 0.0, bottom: float | None = None,
                         atmospheric_pressure: float = ATMOSPHERIC_PRESSURE,
                         max_iterations: int = 10):
    """Sand and clay layers from a CPT by Robertson's (2009) Ic.

    Every reading stands for the interval between the midpoints to its neighbours (the first
    from the mudline, the last down to ``bottom``); sigma'v0 comes from the assumed submerged
    unit weights of the classified intervals, so classification and stresses are iterated
    (at most ``max_iterations`` times) until the types no longer change. Consecutive intervals
    of one type form one layer; runs thinner than ``min_layer_thickness`` are merged into
    their neighbours first (:func:`merge_thin_layers`).

    Parameters
    ----------
    cpt : Cpt
        The CPT (depth below the mudline).
    sand_unit_weight : float
        Submerged unit weight gamma' of sand [N/m^3].
    clay_unit_weight : float
        Submerged unit weight gamma' of clay [N/m^3].
    sand_interface_friction_angle : float
        delta of the sand layers [deg].
    water_unit_weight : float, default SEAWATER_UNIT_WEIGHT
        gamma_w [N/m^3] (u0 = gamma_w z below the mudline).
    net_area_ratio : float, default DEFAULT_NET_AREA_RATIO
        Cone net area ratio a [-] (qt = qc + (1 - a) u2).
    boundary : float, default ROBERTSON_2009_SAND_CLAY_BOUNDARY
        Ic boundary between sand and clay [-].
    min_layer_thickness : float, default 0.0
        Thinnest layer kept [m] (0: none merged).
    bottom : float, optional
        Bottom of the last layer [m] (default: the last reading).
    atmospheric_pressure : float, default ATMOSPHERIC_PRESSURE
        pa [Pa].
    max_iterations : int, default 10
        Most classification iterations [-].

    Returns
    -------
    layers : tuple of SoilLayer
        The layers, from the mudline down.
    ic : numpy.ndarray
        Ic at the readings, shape (n,) [-].

    Raises
    ------
    ValueError
        If ``bottom`` does not lie below the midpoint of the last two readings.

    References
    ----------
    Robertson, P.K. (2009). Interpretation of cone penetration tests - a unified approach.
    Canadian Geotechnical Journal 46(11), 1337-1355. https://doi.org/10.1139/T09-065
    """
    z = cpt.depth
    bottom = float(z[-1]) if bottom is None else float(bottom)
    mids = 0.5 * (z[:-1] + z[1:])
    tops = np.concatenate(([0.0], mids))
    bottoms = np.concatenate((mids, [bottom]))
    if bottoms[-1] <= tops[-1]:
        raise ValueError(f"bottom {bottom:g} m must lie below the midpoint {tops[-1]:g} m of "
                         "the last two readings")
    qt = cpt.qt(net_area_ratio)
    weights = {True: float(sand_unit_weight), False: float(clay_unit_weight)}
    is_sand = np.ones(z.size, dtype=bool)
    ic = np.full(z.size, np.nan)
    for _ in range(max_iterations):
        gamma = np.where(is_sand, weights[True], weights[False])
        stress_tops = np.concatenate(([0.0], np.cumsum(gamma * (bottoms - tops))[:-1]))
        # effective stress at the reading, floored at 1 Pa at the mudline
        sigma_eff = np.maximum(stress_tops + gamma * (z - tops), 1.0)
        sigma_total = sigma_eff + water_unit_weight * z
        ic, _ = robertson_2009_soil_behaviour_type_index(qt, cpt.fs, sigma_total, sigma_eff,
                                                         atmospheric_pressure)
        new = merge_thin_layers(robertson_2009_is_sand(ic, boundary), tops, bottoms,
                                min_layer_thickness)
        if np.array_equal(new, is_sand):
            break
        is_sand = new
    layers = []
    for a, b, sand in _runs(is_sand):
        layers.append(SoilLayer(
            top=float(tops[a]), bottom=float(bottoms[b - 1]),
            soil_type="sand" if sand else "clay",
            submerged_unit_weight=weights[sand],
            interface_friction_angle=float(sand_interface_friction_angle) if sand else None))
    return tuple(layers), ic
