"""SRD (soil resistance to driving) methods: unit shaft friction and unit toe resistance.

Pure, vectorised functions (any numpy-broadcastable arguments), each named after its source.
SI units throughout: stresses and resistances in Pa, depths in m, angles in degrees. Every
formula below is dimensionally homogeneous (cone resistance enters only as the ratio
qt / sigma'v0 or multiplied by a dimensionless factor, and the atmospheric pressure pa is a
parameter), so no conversion to kPa is needed anywhere; the tabulated limits of Stevens et al.
(1982), published in kPa and MPa, are stored here in Pa.

Sign and depth conventions: depth z is measured down from the mudline; the tip depth p is the
penetration; a point of the shaft has been passed by the tip over the distance h = p - z >= 0.
``sigma_v`` always means the in-situ vertical EFFECTIVE stress sigma'v0 [Pa].

Alm & Hamre (2001), CPT based, with friction fatigue (sand and clay)::

    fs(z; p) = fs,res + (fs,i - fs,res) exp(-k (p - z)),   k = sqrt(qt / sigma'v0) / 80 [1/m]
    sand:  fs,i = 0.0132 qt (sigma'v0 / pa)^0.13 tan(delta),   fs,res = 0.2 fs,i
           q_toe = 0.15 qt (qt / sigma'v0)^0.2   (0.10 in the 2018 revision)
    clay:  fs,i = fs (CPT sleeve friction),  fs,res = 0.004 qt (1 - 0.0025 qt / sigma'v0)
           q_toe = 0.6 qt

Stevens, Wiltsie & Turton (1982), sand, with the limits of their table (API RP 2A)::

    f = min(K sigma'v0 tan(delta), f_L(delta)),  q = min(Nq(delta) sigma'v0, q_L(delta))
    delta = phi' - 5 deg, K = 0.7 (upper bound) or 0.5 (lower bound)

Semple & Gemeinhardt (1981), clay (the clay part of the Stevens et al. 1982 SRD)::

    f = 0.5 OCR^0.3 alpha su,   alpha = API alpha(psi = su / sigma'v0)
    OCR = [(su / sigma'v0) / (0.11 + 0.0037 PI)]^(1 / 0.85)   (PI in percent)
    q = 9 su

References
----------
Alm, T., Hamre, L. (1998). Soil model for driveability predictions. OTC 8835, Houston.
Alm, T., Hamre, L. (2001). Soil model for pile driveability predictions based on CPT
interpretations. Proc. 15th ICSMGE, Istanbul, 1297-1302.
Stevens, R.S., Wiltsie, E.A., Turton, T.H. (1982). Evaluating pile drivability for hard clay,
very dense sand and rock. OTC 4205, Houston. doi:10.4043/4205-MS
Semple, R.M., Gemeinhardt, J.P. (1981). Stress history approach to analysis of soil resistance
to pile driving. OTC 3969, Houston. doi:10.4043/3969-MS
API RP 2A-WSD (1987 onwards). Recommended practice for planning, designing and constructing
fixed offshore platforms, section 6.4 (alpha method; Randolph & Murphy 1985).
"""

from __future__ import annotations

import numpy as np

ATMOSPHERIC_PRESSURE = 100e3
"""Reference atmospheric pressure pa of Alm & Hamre (2001) [Pa]."""

ALM_HAMRE_2001_SAND_TOE_FACTOR = 0.15
"""Sand toe factor of Alm & Hamre (2001) [-]."""
ALM_HAMRE_2018_SAND_TOE_FACTOR = 0.10
"""Sand toe factor of the 2018 revision of the Alm & Hamre method used in practice [-]."""
ALM_HAMRE_2001_SAND_RESIDUAL_RATIO = 0.2
"""fs,res / fs,i in sand (Alm & Hamre 2001) [-]."""
ALM_HAMRE_2001_SHAPE_DIVISOR = 80.0
"""Divisor of sqrt(qt / sigma'v0) in the friction-fatigue shape factor k [m]."""

CLAY_RESIDUAL_FLOORS = ("zero", "0.002qt", "clamp")
"""Floor rules for the Alm & Hamre clay residual friction (first = default)."""

STEVENS_1982_K_UPPER = 0.7
"""Lateral earth-pressure coefficient K of the upper-bound sand friction [-]."""
STEVENS_1982_K_LOWER = 0.5
"""Lateral earth-pressure coefficient K of the lower-bound sand friction [-]."""
STEVENS_1982_DELTA_OFFSET = 5.0
"""delta = phi' - 5 deg (Stevens et al. 1982) [deg]."""
STEVENS_1982_DELTA = np.array([15.0, 20.0, 25.0, 30.0, 35.0])
"""Tabulated soil-pile friction angles delta [deg]."""
STEVENS_1982_NQ = np.array([8.0, 12.0, 20.0, 40.0, 50.0])
"""Bearing capacity factors Nq at the tabulated delta [-]."""
STEVENS_1982_FRICTION_LIMIT = np.array([48e3, 67e3, 81e3, 96e3, 115e3])
"""Limiting unit shaft friction f_L at the tabulated delta [Pa] (48 ... 115 kPa)."""
STEVENS_1982_TOE_LIMIT = np.array([1.9e6, 2.9e6, 4.8e6, 9.6e6, 12e6])
"""Limiting unit toe resistance q_L at the tabulated delta [Pa] (1.9 ... 12 MPa)."""

API_ALPHA_MAX = 1.0
"""Upper limit of the API alpha factor [-] (API RP 2A: alpha <= 1.0)."""
SEMPLE_GEMEINHARDT_1981_OCR_FLOOR = 1.0
"""Default lower limit of the estimated OCR [-] (a clay is at least normally consolidated)."""
CLAY_TOE_BEARING_FACTOR = 9.0
"""Nc of the clay toe resistance q = 9 su [-]."""


# ---------------------------------------------------------------- Alm & Hamre (2001)
def alm_hamre_2001_sand_initial_friction(qt, sigma_v, delta, pa=ATMOSPHERIC_PRESSURE):
    """Initial (undegraded) unit shaft friction in sand, fs,i [Pa].

    fs,i = 0.0132 qt (sigma'v0 / pa)^0.13 tan(delta)   (Alm & Hamre 2001, eq. for sand).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa].
    delta : float or array_like
        Constant-volume interface friction angle [deg].
    pa : float, default ATMOSPHERIC_PRESSURE
        Reference atmospheric pressure [Pa]; 100 kPa in the paper (some implementations use
        101.325 kPa, which lowers fs,i by 0.17 %).

    Returns
    -------
    float or numpy.ndarray
        Initial unit shaft friction fs,i [Pa].
    """
    qt, sigma_v = np.asarray(qt, dtype=float), np.asarray(sigma_v, dtype=float)
    return 0.0132 * qt * (sigma_v / pa) ** 0.13 * np.tan(np.radians(delta))


def alm_hamre_2001_sand_residual_friction(fs_initial,
                                          ratio=ALM_HAMRE_2001_SAND_RESIDUAL_RATIO):
    """Residual (fully degraded) unit shaft friction in sand, fs,res = 0.2 fs,i [Pa].

    Parameters
    ----------
    fs_initial : float or array_like
        Initial unit shaft friction fs,i [Pa]
        (:func:`alm_hamre_2001_sand_initial_friction`).
    ratio : float, default ALM_HAMRE_2001_SAND_RESIDUAL_RATIO
        fs,res / fs,i [-], 0.2 in Alm & Hamre (2001).

    Returns
    -------
    float or numpy.ndarray
        Residual unit shaft friction fs,res [Pa].
    """
    return ratio * np.asarray(fs_initial, dtype=float)


def alm_hamre_2001_clay_initial_friction(fs):
    """Initial unit shaft friction in clay: the CPT sleeve friction, fs,i = fs [Pa].

    Parameters
    ----------
    fs : float or array_like
        CPT sleeve friction [Pa].

    Returns
    -------
    float or numpy.ndarray
        Initial unit shaft friction fs,i [Pa].
    """
    return np.array(fs, dtype=float)


def alm_hamre_2001_clay_residual_friction(qt, sigma_v, floor="zero", fs_initial=None):
    """Residual unit shaft friction in clay, never negative [Pa].

    fs,res = 0.004 qt (1 - 0.0025 qt / sigma'v0)   (Alm & Hamre 2001, after OTC 8835, 1998).

    The expression turns negative for qt / sigma'v0 > 400 (stiff, overconsolidated clay and
    near the mudline); implementations in use differ in how they floor it, so the rule is an
    explicit option:

    ``"zero"`` (default)
        max(fs,res, 0) - the formula as published wherever it is physical.
    ``"0.002qt"``
        max(fs,res, 0.002 qt) - the formula's value at qt / sigma'v0 = 200 as a floor (raises
        fs,res wherever qt / sigma'v0 > 200).
    ``"clamp"``
        fs,res clipped to [0, fs,i] (``fs_initial`` required), so friction fatigue never raises
        the friction above its initial value.

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa].
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa] (> 0).
    floor : {"zero", "0.002qt", "clamp"}
        One of :data:`CLAY_RESIDUAL_FLOORS`.
    fs_initial : float or array_like, optional
        Initial unit shaft friction fs,i [Pa] (only for ``"clamp"``).

    Returns
    -------
    float or numpy.ndarray
        Residual unit shaft friction fs,res [Pa].

    Raises
    ------
    ValueError
        If ``floor`` is unknown, or is ``"clamp"`` without ``fs_initial``.
    """
    qt, sigma_v = np.asarray(qt, dtype=float), np.asarray(sigma_v, dtype=float)
    fs_res = 0.004 * qt * (1.0 - 0.0025 * qt / sigma_v)
    if floor == "zero":
        return np.maximum(fs_res, 0.0)
    if floor == "0.002qt":
        return np.maximum(fs_res, 0.002 * qt)
    if floor == "clamp":
        if fs_initial is None:
            raise ValueError('clay residual floor "clamp" needs fs_initial')
        return np.clip(fs_res, 0.0, np.maximum(np.asarray(fs_initial, dtype=float), 0.0))
    raise ValueError(f"unknown clay residual floor {floor!r}; choose one of "
                     f"{CLAY_RESIDUAL_FLOORS}")


def alm_hamre_2001_friction_fatigue_k(qt, sigma_v, rate_factor=1.0):
    """Shape factor of the friction degradation, k = r sqrt(qt / sigma'v0) / 80 [1/m].

    Alm & Hamre (2001), the same for sand and clay; r = 1 is the paper's rate. A factor
    r != 1 scales the rate of the exponential decay with the distance from the tip (the
    friction at the distance h behind the tip with the factor r is that at r h with r = 1),
    leaving the initial and residual frictions unchanged.

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance [Pa] (>= 0).
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa] (> 0).
    rate_factor : float or array_like, default 1.0
        Factor r on the paper's rate [-] (> 0).

    Returns
    -------
    float or numpy.ndarray
        Shape factor k [1/m].

    Raises
    ------
    ValueError
        If ``rate_factor`` is not a positive finite number.
    """
    rate = np.asarray(rate_factor, dtype=float)
    if not np.all(np.isfinite(rate) & (rate > 0.0)):
        raise ValueError(f"rate_factor must be positive and finite, got {rate_factor!r}")
    qt, sigma_v = np.asarray(qt, dtype=float), np.asarray(sigma_v, dtype=float)
    return rate * np.sqrt(qt / sigma_v) / ALM_HAMRE_2001_SHAPE_DIVISOR


def alm_hamre_2001_degraded_friction(fs_i, fs_res, k, depth, tip_depth):
    """Unit shaft friction at ``depth`` once the tip has reached ``tip_depth`` [Pa].

    fs(z; p) = fs,res + (fs,i - fs,res) exp(-k (p - z))   (Alm & Hamre 2001).

    Parameters
    ----------
    fs_i : float or array_like
        Initial unit shaft friction at z [Pa].
    fs_res : float or array_like
        Residual unit shaft friction at z [Pa].
    k : float or array_like
        Shape factor at z [1/m] (:func:`alm_hamre_2001_friction_fatigue_k`).
    depth : float or array_like
        Depth z of the point below the mudline [m].
    tip_depth : float
        Depth p of the pile tip below the mudline [m]. Points below the tip (z > p) are not
        reached yet: the distance p - z is clipped at 0 there, giving fs,i.

    Returns
    -------
    float or numpy.ndarray
        Degraded unit shaft friction fs(z; p) [Pa].
    """
    fs_i, fs_res = np.asarray(fs_i, dtype=float), np.asarray(fs_res, dtype=float)
    passed = np.maximum(np.asarray(tip_depth, dtype=float) - np.asarray(depth, dtype=float),
                        0.0)
    return fs_res + (fs_i - fs_res) * np.exp(-np.asarray(k, dtype=float) * passed)


def alm_hamre_2001_sand_toe(qt, sigma_v, factor=ALM_HAMRE_2001_SAND_TOE_FACTOR):
    """Unit toe resistance in sand on the steel annulus [Pa].

    q_toe = factor qt (qt / sigma'v0)^0.2, factor 0.15 (Alm & Hamre 2001) or 0.10
    (:data:`ALM_HAMRE_2018_SAND_TOE_FACTOR`, the 2018 revision).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance at the tip [Pa].
    sigma_v : float or array_like
        Vertical effective stress at the tip sigma'v0 [Pa] (> 0).
    factor : float, default ALM_HAMRE_2001_SAND_TOE_FACTOR
        Toe factor [-].

    Returns
    -------
    float or numpy.ndarray
        Unit toe resistance q_toe [Pa].
    """
    qt, sigma_v = np.asarray(qt, dtype=float), np.asarray(sigma_v, dtype=float)
    return factor * qt * (qt / sigma_v) ** 0.2


def alm_hamre_2001_clay_toe(qt):
    """Unit toe resistance in clay, q_toe = 0.6 qt [Pa] (Alm & Hamre 2001).

    Parameters
    ----------
    qt : float or array_like
        Corrected cone resistance at the tip [Pa].

    Returns
    -------
    float or numpy.ndarray
        Unit toe resistance q_toe [Pa].
    """
    return 0.6 * np.asarray(qt, dtype=float)


ICP_05_TOE_HALF_WINDOW = 1.5
"""Half-length of the cone resistance averaging window about the pile tip, in pile
diameters D [-]: qc averaged from 1.5 D above to 1.5 D below the tip (ICP-05, UWA-05)."""


def cone_resistance_averaged_about_tip(depth, qc, tip_depth, half_window):
    """Mean cone resistance over a window centred on the pile tip [Pa] (ICP-05 / UWA-05).

    qc,avg = 1 / (z2 - z1) * integral of qc(z) dz from z1 to z2, z1 = max(p - h, z_0),
    z2 = min(p + h, z_n), with qc(z) linear between the readings (z_0 the first, z_n the last
    reading). The pile's base resistance in sand is governed by the cone resistance over a zone
    about the tip, not by the reading at the tip; ICP-05 and UWA-05 take qc,avg over 1.5 D above
    and below the tip (``half_window`` = :data:`ICP_05_TOE_HALF_WINDOW` x D). The window is
    clipped to the sounding: near the mudline (or the end of the CPT) the mean is over its part
    inside the readings.

    Parameters
    ----------
    depth : array_like
        (n,) increasing depths of the CPT readings below the mudline [m].
    qc : array_like
        (n,) cone resistance (qc, or qt) at those depths [Pa].
    tip_depth : float
        Tip depth p below the mudline [m].
    half_window : float
        Half-length h of the window [m] (>= 0; 0: qc at the tip).

    Returns
    -------
    float
        Mean cone resistance qc,avg over the window [Pa].

    Raises
    ------
    ValueError
        If ``depth`` and ``qc`` differ in length or are empty, ``depth`` is not increasing,
        ``half_window`` is negative or the tip lies outside the readings.

    References
    ----------
    Jardine, R.J., Chow, F.C., Overy, R.F., Standing, J.R. (2005). ICP design methods for driven
    piles in sands and clays. Thomas Telford, London. ISBN 0 7277 3272 2.
    Lehane, B.M., Schneider, J.A., Xu, X. (2005). The UWA-05 method for prediction of axial
    capacity of driven piles in sand. Frontiers in Offshore Geotechnics (ISFOG 2005), Perth,
    683-689.
    Schneider, J.A., Xu, X., Lehane, B.M. (2008). Database assessment of CPT-based design
    methods for axial capacity of driven piles in siliceous sands. J. Geotech. Geoenviron.
    Eng. 134(9), 1227-1244. doi:10.1061/(ASCE)1090-0241(2008)134:9(1227)
    """
    z, q = np.asarray(depth, dtype=float), np.asarray(qc, dtype=float)
    if z.ndim != 1 or z.shape != q.shape or z.size == 0:
        raise ValueError("depth and qc must be 1-D arrays of the same, non-zero length")
    if np.any(np.diff(z) <= 0.0):
        raise ValueError("the CPT depths must be increasing")
    if not half_window >= 0.0:
        raise ValueError(f"half_window must not be negative, got {half_window!r}")
    if not z[0] <= tip_depth <= z[-1]:
        raise ValueError(f"tip depth {tip_depth!r} m lies outside the CPT ({z[0]:g}-"
                         f"{z[-1]:g} m)")
    low, high = max(tip_depth - half_window, z[0]), min(tip_depth + half_window, z[-1])
    if high <= low:
        return float(np.interp(tip_depth, z, q))
    inside = (z > low) & (z < high)
    zz = np.concatenate(([low], z[inside], [high]))
    qq = np.interp(zz, z, q)
    return float(np.sum(0.5 * (qq[1:] + qq[:-1]) * np.diff(zz)) / (high - low))


# ---------------------------------------------------------------- Stevens et al. (1982)
def stevens_1982_interface_friction_angle(friction_angle):
    """Soil-pile friction angle delta = phi' - 5 deg [deg] (Stevens et al. 1982).

    Parameters
    ----------
    friction_angle : float or array_like
        Effective friction angle of the sand phi' [deg].

    Returns
    -------
    float or numpy.ndarray
        Soil-pile friction angle delta [deg].
    """
    return np.asarray(friction_angle, dtype=float) - STEVENS_1982_DELTA_OFFSET


def stevens_1982_limits(delta):
    """(Nq [-], f_L [Pa], q_L [Pa]) of the Stevens et al. (1982) table at ``delta``.

    Linear interpolation between the tabulated delta = 15, 20, 25, 30, 35 deg; outside that
    range the nearest row is used (clamped, no extrapolation).

    Parameters
    ----------
    delta : float or array_like
        Soil-pile friction angle [deg].

    Returns
    -------
    nq : float or numpy.ndarray
        Bearing capacity factor Nq [-].
    f_l : float or numpy.ndarray
        Limit unit shaft friction f_L [Pa].
    q_l : float or numpy.ndarray
        Limit unit toe resistance q_L [Pa].
    """
    delta = np.asarray(delta, dtype=float)
    return (np.interp(delta, STEVENS_1982_DELTA, STEVENS_1982_NQ),
            np.interp(delta, STEVENS_1982_DELTA, STEVENS_1982_FRICTION_LIMIT),
            np.interp(delta, STEVENS_1982_DELTA, STEVENS_1982_TOE_LIMIT))


def stevens_1982_sand_friction(sigma_v, delta, k=STEVENS_1982_K_LOWER):
    """Unit shaft friction in sand, f = min(K sigma'v0 tan(delta), f_L(delta)) [Pa].

    Stevens, Wiltsie & Turton (1982); limit f_L from :func:`stevens_1982_limits`.

    Parameters
    ----------
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa].
    delta : float or array_like
        Soil-pile friction angle [deg] (phi' - 5 deg).
    k : float, default STEVENS_1982_K_LOWER
        Lateral earth-pressure coefficient K [-]: 0.5 lower bound
        (:data:`STEVENS_1982_K_LOWER`), 0.7 upper bound (:data:`STEVENS_1982_K_UPPER`).

    Returns
    -------
    float or numpy.ndarray
        Unit shaft friction f [Pa].
    """
    sigma_v = np.asarray(sigma_v, dtype=float)
    _, f_limit, _ = stevens_1982_limits(delta)
    return np.minimum(k * sigma_v * np.tan(np.radians(delta)), f_limit)


def stevens_1982_sand_toe(sigma_v, delta):
    """Unit toe resistance in sand, q = min(Nq(delta) sigma'v0, q_L(delta)) [Pa].

    Stevens, Wiltsie & Turton (1982); Nq and q_L from :func:`stevens_1982_limits`.

    Parameters
    ----------
    sigma_v : float or array_like
        Vertical effective stress at the tip sigma'v0 [Pa].
    delta : float or array_like
        Soil-pile friction angle [deg].

    Returns
    -------
    float or numpy.ndarray
        Unit toe resistance q [Pa].
    """
    nq, _, q_limit = stevens_1982_limits(delta)
    return np.minimum(nq * np.asarray(sigma_v, dtype=float), q_limit)


def stevens_1982_clay_toe(su):
    """Unit toe resistance in clay, q = 9 su [Pa] (Stevens et al. 1982).

    Parameters
    ----------
    su : float or array_like
        Undrained shear strength at the tip [Pa].

    Returns
    -------
    float or numpy.ndarray
        Unit toe resistance q [Pa].
    """
    return CLAY_TOE_BEARING_FACTOR * np.asarray(su, dtype=float)


def api_rp2a_alpha(su, sigma_v, alpha_max=API_ALPHA_MAX):
    """Adhesion factor alpha of the API alpha method [-].

    alpha = 0.5 psi^-0.5 (psi <= 1), 0.5 psi^-0.25 (psi > 1), psi = su / sigma'v0,
    with alpha <= 1 (API RP 2A-WSD, after Randolph & Murphy 1985).

    Parameters
    ----------
    su : float or array_like
        Undrained shear strength [Pa] (> 0).
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa] (> 0).
    alpha_max : float, default API_ALPHA_MAX
        Upper limit of alpha [-] (1.0 in API RP 2A; ``np.inf`` for none).

    Returns
    -------
    float or numpy.ndarray
        Adhesion factor alpha [-].
    """
    psi = np.asarray(su, dtype=float) / np.asarray(sigma_v, dtype=float)
    alpha = np.where(psi <= 1.0, 0.5 * psi ** -0.5, 0.5 * psi ** -0.25)
    return np.minimum(alpha, alpha_max)


def semple_gemeinhardt_1981_ocr(su, sigma_v, plasticity_index,
                                floor=SEMPLE_GEMEINHARDT_1981_OCR_FLOOR):
    """Overconsolidation ratio estimated from the strength ratio [-].

    OCR = [(su / sigma'v0) / (0.11 + 0.0037 PI)]^(1 / 0.85), PI in percent (Skempton's
    normally consolidated strength ratio and su ~ OCR^0.85), as used by Semple & Gemeinhardt
    (1981).

    Parameters
    ----------
    su : float or array_like
        Undrained shear strength [Pa].
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa] (> 0).
    plasticity_index : float or array_like
        Plasticity index as a fraction [-] (0.30 for PI = 30 %); converted to percent inside
        the formula.
    floor : float or None, default SEMPLE_GEMEINHARDT_1981_OCR_FLOOR
        Lower limit of the OCR [-] (default 1: a strength ratio below the normally
        consolidated one is read as normally consolidated); None for no floor.

    Returns
    -------
    float or numpy.ndarray
        Estimated OCR [-].
    """
    ratio = np.asarray(su, dtype=float) / np.asarray(sigma_v, dtype=float)
    pi_percent = 100.0 * np.asarray(plasticity_index, dtype=float)
    ocr = (ratio / (0.11 + 0.0037 * pi_percent)) ** (1.0 / 0.85)
    return ocr if floor is None else np.maximum(ocr, floor)


def semple_gemeinhardt_1981_clay_friction(su, sigma_v, plasticity_index,
                                          ocr_floor=SEMPLE_GEMEINHARDT_1981_OCR_FLOOR,
                                          alpha_max=API_ALPHA_MAX):
    """Unit shaft friction in clay for driving, f = 0.5 OCR^0.3 alpha su [Pa].

    Semple & Gemeinhardt (1981): the API alpha friction times the driving factor
    Fp = 0.5 OCR^0.3; alpha from :func:`api_rp2a_alpha`, OCR from
    :func:`semple_gemeinhardt_1981_ocr`.

    Parameters
    ----------
    su : float or array_like
        Undrained shear strength [Pa] (> 0).
    sigma_v : float or array_like
        Vertical effective stress sigma'v0 [Pa] (> 0).
    plasticity_index : float or array_like
        Plasticity index as a fraction [-].
    ocr_floor : float or None, default SEMPLE_GEMEINHARDT_1981_OCR_FLOOR
        Lower limit of the estimated OCR [-] (None for none).
    alpha_max : float, default API_ALPHA_MAX
        Upper limit of alpha [-].

    Returns
    -------
    float or numpy.ndarray
        Unit shaft friction f [Pa].
    """
    su = np.asarray(su, dtype=float)
    ocr = semple_gemeinhardt_1981_ocr(su, sigma_v, plasticity_index, floor=ocr_floor)
    return 0.5 * ocr ** 0.3 * api_rp2a_alpha(su, sigma_v, alpha_max) * su
