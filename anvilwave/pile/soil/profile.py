"""Soil profiles, CPT data and the SRD distribution along a pile for a given tip depth.

Model -> method -> distribution, as separate stages:

* :class:`SoilLayer`, :class:`SoilProfile` - layers below the mudline (type, submerged unit
  weight, friction angles, undrained strength, plasticity) and optionally a :class:`Cpt`
  (depth, qc, fs, u2). The profile gives sigma'v0(z) (exact integral of the layer weights), the
  corrected cone resistance qt(z) and the layer properties at any depth.
* SRD methods, small objects that only assemble the pure functions of
  :mod:`anvilwave.pile.soil.srd_methods`: :class:`AlmHamre2001` (needs the CPT; soil type and delta
  from the
  layers), :class:`Stevens1982` (needs the layers; Semple & Gemeinhardt 1981 in clay) and
  :class:`TipDepthTables` (user tables per tip depth, GRLWEAP style; no profile needed).
* :func:`srd_distribution` - ultimate shaft resistance per pile segment and toe resistance for
  one tip depth. Friction fatigue makes the friction at a depth depend on how far the tip has
  passed it, so call it again for every tip depth.

Conventions: depth z is measured DOWN from the mudline [m]; the tip depth p is the penetration;
stresses in Pa, unit weights in N/m^3, angles in degrees. The layers carry the SUBMERGED unit
weight (offshore: the soil is saturated and the water table is at the mudline), so no water
depth is needed for sigma'v0. The CPT is that of a cone zeroed at the mudline (usual offshore
practice: qc and u2 exclude the ambient water pressure at the seabed, and qt is formed from
them as they are).

Integration along the shaft: the embedded part of every segment, [max(top, 0),
min(bottom, p)], is cut at every depth where the inputs change (layer boundaries, CPT readings,
table rows) and into pieces no longer than ``resolution`` (0.1 m by default); each piece is
integrated with Gauss-Legendre points (3 by default). A segment spanning a layer boundary thus
takes the right share of each layer, and no single mid-point sample stands for a segment.
Next to the mudline the pieces are graded geometrically (sigma'v0 -> 0 makes the Alm & Hamre
integrands singular there).

Faces and factors (they differ by 2x between codes, so they are explicit):
``pile_mode="coring"`` (default) puts the toe resistance on the steel annulus and friction on
the outside and the inside; ``"plugged"`` puts it on the full cross-section and friction on the
outside only; ``faces`` overrides the faces. Each method object carries its own face factors:
Alm & Hamre 0.5 outside + 0.5 inside in sand (calibrated as outside friction, split in half
over the two faces) and 1.0 + 1.0 in clay; Stevens et al. and the user tables 1.0 + 1.0.
With ``faces="outside"`` the same factors give the other variants in use (0.5 outside only in
sand, 1.0 outside only in clay): the shaft resistance differs by 2x between them.
``bound_multiplier`` scales shaft and toe (lower / best / upper bound, e.g. 1.25 for the
common Alm & Hamre upper bound).

References
----------
Alm, T., Hamre, L. (2001). Soil model for pile driveability predictions based on CPT
interpretations. Proc. 15th ICSMGE, Istanbul, 1297-1302.
Stevens, R.S., Wiltsie, E.A., Turton, T.H. (1982). Evaluating pile drivability for hard clay,
very dense sand and rock. OTC 4205.
Semple, R.M., Gemeinhardt, J.P. (1981). Stress history approach to analysis of soil resistance
to pile driving. OTC 3969.
Campanella, R.G., Gillespie, D., Robertson, P.K. (1982). Pore pressures during cone
penetration testing. Proc. 2nd European Symposium on Penetration Testing, Amsterdam, 507-512.
Lunne, T., Robertson, P.K., Powell, J.J.M. (1997). Cone penetration testing in geotechnical
practice. Blackie / Spon.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from anvilwave.pile.soil import srd_methods as sm

SOIL_TYPES = ("sand", "clay")
"""Soil types of a layer."""
PILE_MODES = ("coring", "plugged")
"""Pile modes: coring (annulus toe, outside + inside friction) or plugged (full toe, outside)."""
FACES = ("outside", "outside+inside")
"""Friction faces."""
METHODS = ("alm-hamre-2001", "stevens-1982")
"""Names of the SRD methods built from a soil profile."""
DEFAULT_NET_AREA_RATIO = 0.8
"""Default net area ratio a of the cone [-]."""
DEFAULT_RESOLUTION = 0.1
"""Default longest integration piece along the shaft [m]."""
DEFAULT_GAUSS_POINTS = 3
"""Default number of Gauss-Legendre points per integration piece."""
_DEPTH_TOLERANCE = 1e-9  # [m] round-off allowed when comparing depths


def campanella_1982_total_cone_resistance(qc, u2, net_area_ratio=DEFAULT_NET_AREA_RATIO):
    """Corrected (total) cone resistance qt = qc + (1 - a) u2 [Pa].

    Parameters
    ----------
    qc : float or array_like
        Measured cone resistance [Pa].
    u2 : float or array_like
        Pore pressure measured behind the cone (u2 position) [Pa].
    net_area_ratio : float, default DEFAULT_NET_AREA_RATIO
        Net area ratio a of the cone [-] (0.8 typical; 1 gives qt = qc).

    Returns
    -------
    numpy.ndarray
        Corrected cone resistance qt [Pa].

    References
    ----------
    Campanella, R.G., Gillespie, D., Robertson, P.K. (1982). Pore pressures during cone
    penetration testing. Proc. 2nd European Symposium on Penetration Testing, Amsterdam, 507-512.
    Lunne, T., Robertson, P.K., Powell, J.J.M. (1997). Cone penetration testing in geotechnical
    practice. Blackie / Spon, eq. 2.2.
    """
    return np.asarray(qc, dtype=float) + (1.0 - net_area_ratio) * np.asarray(u2, dtype=float)


# ---------------------------------------------------------------------------- model
@dataclass(frozen=True, eq=False)
class Cpt:
    """A cone penetration test, depths below the mudline.

    Parameters
    ----------
    depth : numpy.ndarray
        (n,) depth below the mudline [m], strictly increasing, >= 0.
    qc : numpy.ndarray
        (n,) cone resistance [Pa], >= 0.
    fs : numpy.ndarray
        (n,) sleeve friction [Pa], >= 0.
    u2 : numpy.ndarray
        (n,) pore pressure at the u2 position [Pa] (zeros when not measured).
    source : str, default ""
        Where the data came from (file name), for messages.

    Raises
    ------
    ValueError
        If the arrays are not 1-D of one shape with at least two readings, not finite, the
        depths do not increase strictly or are negative, or qc or fs is negative.
    """

    depth: np.ndarray
    qc: np.ndarray
    fs: np.ndarray
    u2: np.ndarray
    source: str = ""

    def __post_init__(self):
        arrays = {name: np.asarray(getattr(self, name), dtype=float)
                  for name in ("depth", "qc", "fs", "u2")}
        for name, value in arrays.items():
            object.__setattr__(self, name, value)
        n = arrays["depth"].shape
        if len(n) != 1 or n[0] < 2:
            raise ValueError("CPT depth must be a 1-D array with at least two readings")
        for name, value in arrays.items():
            if value.shape != n:
                raise ValueError(f"CPT {name} must have the shape of depth {n}, got "
                                 f"{value.shape}")
            if not np.all(np.isfinite(value)):
                raise ValueError(f"CPT {name} must be finite")
        if np.any(np.diff(arrays["depth"]) <= 0.0):
            raise ValueError("CPT depths must increase strictly")
        if arrays["depth"][0] < 0.0:
            raise ValueError("CPT depths are below the mudline and must not be negative")
        for name in ("qc", "fs"):
            if np.any(arrays[name] < 0.0):
                raise ValueError(f"CPT {name} must not be negative")

    def qt(self, net_area_ratio: float = DEFAULT_NET_AREA_RATIO) -> np.ndarray:
        """Corrected cone resistance at the readings [Pa], floored at 0.

        The floor is there because a negative u2 with a tiny qc can otherwise give qt < 0.

        Parameters
        ----------
        net_area_ratio : float, default DEFAULT_NET_AREA_RATIO
            Net area ratio a of the cone [-].

        Returns
        -------
        numpy.ndarray
            (n,) corrected cone resistance qt at the readings [Pa].
        """
        return np.maximum(campanella_1982_total_cone_resistance(self.qc, self.u2,
                                                                net_area_ratio), 0.0)


@dataclass(frozen=True)
class SoilLayer:
    """One soil layer.

    Parameters
    ----------
    top : float
        Depth of the layer's top below the mudline [m].
    bottom : float
        Depth of the layer's bottom below the mudline [m].
    soil_type : {"sand", "clay"}
        Soil type.
    submerged_unit_weight : float
        gamma' [N/m^3] (> 0), e.g. 10e3 for a dense sand.
    interface_friction_angle : float or None, default None
        Soil-pile friction angle delta [deg] (sand; Alm & Hamre use the constant-volume interface
        angle). When None, phi' - 5 deg (Stevens et al. 1982).
    friction_angle : float or None, default None
        Effective friction angle phi' [deg] (sand), used when delta is None.
    undrained_shear_strength : float or None, default None
        su at the top of the layer [Pa] (clay, Stevens et al.).
    undrained_shear_strength_gradient : float, default 0.0
        d su / dz [Pa/m] (su linear with depth in the layer).
    plasticity_index : float or None, default None
        PI as a fraction [-] (0.30 for 30 %; clay, Semple & Gemeinhardt).

    Raises
    ------
    ValueError
        If the soil type is unknown, the depths break 0 <= top < bottom, the unit weight is not
        positive, an angle lies outside (0, 90) deg, su is negative or PI lies outside [0, 2].
    """

    top: float
    bottom: float
    soil_type: str
    submerged_unit_weight: float
    interface_friction_angle: float | None = None
    friction_angle: float | None = None
    undrained_shear_strength: float | None = None
    undrained_shear_strength_gradient: float = 0.0
    plasticity_index: float | None = None

    def __post_init__(self):
        if self.soil_type not in SOIL_TYPES:
            raise ValueError(f"soil_type must be one of {SOIL_TYPES}, got {self.soil_type!r}")
        if not (0.0 <= self.top < self.bottom):
            raise ValueError(f"layer depths need 0 <= top < bottom, got top {self.top:g} m, "
                             f"bottom {self.bottom:g} m")
        if not self.submerged_unit_weight > 0.0:
            raise ValueError("submerged_unit_weight must be greater than 0 N/m^3, got "
                             f"{self.submerged_unit_weight:g}")
        for name in ("interface_friction_angle", "friction_angle"):
            value = getattr(self, name)
            if value is not None and not 0.0 < value < 90.0:
                raise ValueError(f"{name} must lie between 0 and 90 deg, got {value:g}")
        if self.undrained_shear_strength is not None and self.undrained_shear_strength < 0.0:
            raise ValueError("undrained_shear_strength must not be negative")
        if self.plasticity_index is not None and not 0.0 <= self.plasticity_index <= 2.0:
            raise ValueError("plasticity_index is a fraction [-] (0.3 for 30 %) between 0 and "
                             f"2, got {self.plasticity_index:g}")

    @property
    def delta(self) -> float:
        """Soil-pile friction angle [deg]: delta if given, else phi' - 5, else NaN."""
        if self.interface_friction_angle is not None:
            return float(self.interface_friction_angle)
        if self.friction_angle is not None:
            return float(sm.stevens_1982_interface_friction_angle(self.friction_angle))
        return float("nan")


@dataclass(frozen=True, eq=False)
class SoilProfile:
    """Soil layers from the mudline down, with an optional CPT.

    Parameters
    ----------
    layers : tuple of SoilLayer
        Contiguous layers, the first at the mudline (top 0), each starting where the previous one
        ends.
    cpt : Cpt or None, default None
        The CPT (needed by :class:`AlmHamre2001`).
    net_area_ratio : float, default DEFAULT_NET_AREA_RATIO
        Net area ratio a of the cone [-], for qt = qc + (1 - a) u2.

    Raises
    ------
    ValueError
        If there is no layer, the first does not start at the mudline, the layers are not
        contiguous or the net area ratio lies outside (0, 1].
    """

    layers: tuple[SoilLayer, ...]
    cpt: Cpt | None = None
    net_area_ratio: float = DEFAULT_NET_AREA_RATIO

    def __post_init__(self):
        layers = tuple(self.layers)
        object.__setattr__(self, "layers", layers)
        if not layers:
            raise ValueError("a soil profile needs at least one layer")
        if layers[0].top != 0.0:
            raise ValueError(f"the first layer must start at the mudline (0 m), got "
                             f"{layers[0].top:g} m")
        for i in range(1, len(layers)):
            if abs(layers[i].top - layers[i - 1].bottom) > _DEPTH_TOLERANCE:
                raise ValueError(f"layer {i} must start where layer {i - 1} ends "
                                 f"({layers[i - 1].bottom:g} m), got {layers[i].top:g} m")
        if not 0.0 < self.net_area_ratio <= 1.0:
            raise ValueError(f"net_area_ratio must lie in (0, 1], got {self.net_area_ratio:g}")

    # ------------------------------------------------------------ layer arrays
    @cached_property
    def tops(self) -> np.ndarray:
        """Layer tops [m]."""
        return np.array([layer.top for layer in self.layers])

    @cached_property
    def bottoms(self) -> np.ndarray:
        """Layer bottoms [m]."""
        return np.array([layer.bottom for layer in self.layers])

    @property
    def bottom(self) -> float:
        """Depth of the bottom of the profile [m]."""
        return float(self.bottoms[-1])

    @cached_property
    def _unit_weight(self) -> np.ndarray:
        return np.array([layer.submerged_unit_weight for layer in self.layers])

    @cached_property
    def _stress_at_tops(self) -> np.ndarray:
        weights = self._unit_weight * (self.bottoms - self.tops)
        return np.concatenate(([0.0], np.cumsum(weights)[:-1]))

    @cached_property
    def is_sand(self) -> np.ndarray:
        """True for sand layers, per layer."""
        return np.array([layer.soil_type == "sand" for layer in self.layers])

    @cached_property
    def delta(self) -> np.ndarray:
        """Soil-pile friction angle per layer [deg] (NaN where not given)."""
        return np.array([layer.delta for layer in self.layers])

    @cached_property
    def _su(self) -> tuple[np.ndarray, np.ndarray]:
        su = [np.nan if layer.undrained_shear_strength is None
              else layer.undrained_shear_strength for layer in self.layers]
        gradient = [layer.undrained_shear_strength_gradient for layer in self.layers]
        return np.array(su), np.array(gradient)

    @cached_property
    def plasticity_index(self) -> np.ndarray:
        """Plasticity index per layer as a fraction [-] (NaN where not given)."""
        return np.array([np.nan if layer.plasticity_index is None else layer.plasticity_index
                         for layer in self.layers])

    @cached_property
    def _qt(self) -> np.ndarray:
        return self.cpt.qt(self.net_area_ratio)

    # ------------------------------------------------------------ at depth
    def _check_depth(self, z: np.ndarray) -> None:
        if np.any(z < -_DEPTH_TOLERANCE) or np.any(z > self.bottom + _DEPTH_TOLERANCE):
            raise ValueError(f"depths must lie within the soil profile, 0 to {self.bottom:g} m"
                             f" below the mudline; got {np.min(z):g} to {np.max(z):g} m")

    def layer_index(self, depth) -> np.ndarray:
        """Index of the layer at ``depth`` (the deeper layer on a boundary).

        Parameters
        ----------
        depth : float or array_like
            Depth below the mudline [m], within the profile.

        Returns
        -------
        numpy.ndarray
            Layer index at each depth.

        Raises
        ------
        ValueError
            If a depth lies outside the profile.
        """
        z = np.asarray(depth, dtype=float)
        self._check_depth(z)
        return np.minimum(np.searchsorted(self.bottoms, z, side="right"), len(self.layers) - 1)

    def vertical_effective_stress(self, depth) -> np.ndarray:
        """sigma'v0(z) = integral of gamma' from the mudline to ``depth`` [Pa] (exact).

        Parameters
        ----------
        depth : float or array_like
            Depth below the mudline [m].

        Returns
        -------
        numpy.ndarray
            Vertical effective stress sigma'v0 at each depth [Pa].
        """
        z = np.asarray(depth, dtype=float)
        i = self.layer_index(z)
        return self._stress_at_tops[i] + self._unit_weight[i] * (z - self.tops[i])

    def undrained_shear_strength(self, depth) -> np.ndarray:
        """su(z) = su_top + gradient (z - top) of the layer at ``depth`` [Pa] (NaN if unset).

        Parameters
        ----------
        depth : float or array_like
            Depth below the mudline [m].

        Returns
        -------
        numpy.ndarray
            Undrained shear strength at each depth [Pa], NaN where the layer has none.
        """
        z = np.asarray(depth, dtype=float)
        i = self.layer_index(z)
        su, gradient = self._su
        return su[i] + gradient[i] * (z - self.tops[i])

    def _require_cpt(self, z: np.ndarray) -> None:
        if self.cpt is None:
            raise ValueError("this method needs a CPT in the soil profile")
        deepest = float(np.max(z)) if z.size else 0.0
        if deepest > self.cpt.depth[-1] + _DEPTH_TOLERANCE:
            raise ValueError(f"the CPT{' ' + self.cpt.source if self.cpt.source else ''} ends "
                             f"at {self.cpt.depth[-1]:g} m, above the depth {deepest:g} m "
                             "where it is needed")

    @property
    def qt_readings(self) -> np.ndarray:
        """Corrected cone resistance qt at the CPT's readings [Pa] (at ``cpt.depth``; read-only).

        Raises
        ------
        ValueError
            If the profile has no CPT.
        """
        self._require_cpt(np.zeros(0))
        out = np.asarray(self._qt, dtype=float).view()
        out.flags.writeable = False
        return out

    def qt(self, depth) -> np.ndarray:
        """Corrected cone resistance at ``depth`` [Pa], linear between readings.

        Between the mudline and the first reading it is held at the first reading.

        Parameters
        ----------
        depth : float or array_like
            Depth below the mudline [m] (not below the last reading).

        Returns
        -------
        numpy.ndarray
            Corrected cone resistance qt at each depth [Pa].

        Raises
        ------
        ValueError
            If the profile has no CPT or a depth lies below its last reading.
        """
        z = np.asarray(depth, dtype=float)
        self._require_cpt(z)
        return np.interp(z, self.cpt.depth, self._qt)

    def sleeve_friction(self, depth) -> np.ndarray:
        """CPT sleeve friction at ``depth`` [Pa] (interpolated like :meth:`qt`).

        Parameters
        ----------
        depth : float or array_like
            Depth below the mudline [m].

        Returns
        -------
        numpy.ndarray
            Sleeve friction fs at each depth [Pa].

        Raises
        ------
        ValueError
            If the profile has no CPT or a depth lies below its last reading.
        """
        z = np.asarray(depth, dtype=float)
        self._require_cpt(z)
        return np.interp(z, self.cpt.depth, self.cpt.fs)

    def breakpoints(self, with_cpt: bool) -> np.ndarray:
        """Depths where the inputs change slope or jump [m].

        Parameters
        ----------
        with_cpt : bool
            Include the CPT readings besides the layer boundaries.

        Returns
        -------
        numpy.ndarray
            Sorted unique depths [m]: layer boundaries and (``with_cpt``) the CPT readings.
        """
        points = [self.tops, self.bottoms]
        if with_cpt and self.cpt is not None:
            points.append(self.cpt.depth)
        return np.unique(np.concatenate(points))


# ---------------------------------------------------------------------------- methods
@dataclass(frozen=True)
class AlmHamre2001:
    """Alm & Hamre (2001) CPT-based SRD with friction fatigue.

    Soil type and delta (sand) come from the layers; qt, fs from the CPT.

    Parameters
    ----------
    sand_outside_factor : float, default 0.5
        Factor on the sand unit friction on the outside face [-]. The sand friction was
        calibrated as outside friction, and practice splits it half outside, half inside
        (another variant in use: 0.5 outside only, i.e. ``faces="outside"``).
    sand_inside_factor : float, default 0.5
        Factor on the sand unit friction on the inside face [-].
    clay_outside_factor : float, default 1.0
        Factor on the clay unit friction on the outside face [-] (the variant in use besides:
        1.0 outside only).
    clay_inside_factor : float, default 1.0
        Factor on the clay unit friction on the inside face [-].
    sand_toe_factor : float, default ALM_HAMRE_2001_SAND_TOE_FACTOR
        0.15 (2001) or 0.10 (2018 revision, :data:`ALM_HAMRE_2018_SAND_TOE_FACTOR`) [-].
    clay_residual_floor : {"zero", "0.002qt", "clamp"}
        See :func:`anvilwave.pile.soil.srd_methods.alm_hamre_2001_clay_residual_friction`.
    atmospheric_pressure : float, default ATMOSPHERIC_PRESSURE
        pa [Pa] (100 kPa in the paper).
    toe_window : float, default 0.0
        Length over which the unit toe resistance is averaged, centred on the tip [m] (0: the
        value at the tip).
    fatigue_rate_factor : float, default 1.0
        Factor on the friction-fatigue shape factor k [-] (1: the paper's rate; see
        :func:`anvilwave.pile.soil.srd_methods.alm_hamre_2001_friction_fatigue_k`).
    toe_qt_half_window : float, default 0.0
        Half-length of the window about the tip over which qt is averaged BEFORE the sand toe
        formula is applied (with sigma'v0 at the tip), where the tip stands in sand [m]: the
        base rule of ICP-05 and UWA-05 (both sand methods), qc averaged from 1.5 D above to
        1.5 D below the tip
        (:func:`anvilwave.pile.soil.srd_methods.cone_resistance_averaged_about_tip`;
        ``1.5 * D``). A tip in clay keeps the clay toe at its own qt (0.6 qt is calibrated on
        the clay's qt: applied to a mean that takes in a sand layer below or above it would
        give a clay toe far above the sand's). 0: qt at the tip. Not together with
        ``toe_window`` (which averages the unit toe resistance itself).

    Raises
    ------
    ValueError
        If ``clay_residual_floor`` is unknown, ``toe_window`` or ``toe_qt_half_window`` is
        negative, both are positive, or ``fatigue_rate_factor`` is not positive and finite.

    References
    ----------
    Alm, T., Hamre, L. (2001). Soil model for pile driveability predictions based on CPT
    interpretations. Proc. 15th ICSMGE, Istanbul, 1297-1302.
    """

    sand_outside_factor: float = 0.5
    sand_inside_factor: float = 0.5
    clay_outside_factor: float = 1.0
    clay_inside_factor: float = 1.0
    sand_toe_factor: float = sm.ALM_HAMRE_2001_SAND_TOE_FACTOR
    clay_residual_floor: str = sm.CLAY_RESIDUAL_FLOORS[0]
    atmospheric_pressure: float = sm.ATMOSPHERIC_PRESSURE
    toe_window: float = 0.0
    fatigue_rate_factor: float = 1.0
    toe_qt_half_window: float = 0.0

    name = "alm-hamre-2001"

    def __post_init__(self):
        if self.clay_residual_floor not in sm.CLAY_RESIDUAL_FLOORS:
            raise ValueError(f"clay_residual_floor must be one of {sm.CLAY_RESIDUAL_FLOORS}, "
                             f"got {self.clay_residual_floor!r}")
        if self.toe_window < 0.0:
            raise ValueError("toe_window must not be negative")
        if not self.toe_qt_half_window >= 0.0:
            raise ValueError("toe_qt_half_window must not be negative")
        if self.toe_window > 0.0 and self.toe_qt_half_window > 0.0:
            raise ValueError("toe_window (the unit toe averaged) and toe_qt_half_window (qt "
                             "averaged) exclude each other: set one of them")
        if not (np.isfinite(self.fatigue_rate_factor) and self.fatigue_rate_factor > 0.0):
            raise ValueError("fatigue_rate_factor must be positive and finite, got "
                             f"{self.fatigue_rate_factor!r}")

    def check(self, profile: SoilProfile, deepest: float) -> None:
        """Check that ``profile`` has the data needed down to ``deepest``.

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        deepest : float
            Deepest tip depth to be analysed [m].

        Raises
        ------
        ValueError
            If the CPT is missing or too short, or a sand layer has neither delta nor phi'.
        """
        profile._require_cpt(np.array([deepest]))
        for i, layer in enumerate(profile.layers):
            if layer.top < deepest and layer.soil_type == "sand" and np.isnan(layer.delta):
                raise ValueError(f"sand layer {i} ({layer.top:g}-{layer.bottom:g} m) needs "
                                 "interface_friction_angle or friction_angle")

    def breakpoints(self, profile: SoilProfile) -> np.ndarray:
        """Depths where the inputs change: layer boundaries and CPT readings [m].

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.

        Returns
        -------
        numpy.ndarray
            Sorted unique depths [m].
        """
        return profile.breakpoints(with_cpt=True)

    def unit_friction(self, profile: SoilProfile, depth, tip_depth: float):
        """(outside, inside) unit shaft friction at ``depth`` for the tip at ``tip_depth``.

        Face factors applied; depth > 0.

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        depth : float or array_like
            Depths below the mudline [m].
        tip_depth : float
            Tip depth p [m].

        Returns
        -------
        outside : numpy.ndarray
            Unit shaft friction on the outside face [Pa].
        inside : numpy.ndarray
            Unit shaft friction on the inside face [Pa].
        """
        z = np.asarray(depth, dtype=float)
        i = profile.layer_index(z)
        sand = profile.is_sand[i]
        sigma_v = profile.vertical_effective_stress(z)
        qt = profile.qt(z)
        fs = profile.sleeve_friction(z)
        with np.errstate(invalid="ignore", divide="ignore"):
            fs_i_sand = sm.alm_hamre_2001_sand_initial_friction(qt, sigma_v, profile.delta[i],
                                                                self.atmospheric_pressure)
            fs_i_clay = sm.alm_hamre_2001_clay_initial_friction(fs)
            fs_i = np.where(sand, fs_i_sand, fs_i_clay)
            fs_res = np.where(sand, sm.alm_hamre_2001_sand_residual_friction(fs_i_sand),
                              sm.alm_hamre_2001_clay_residual_friction(
                                  qt, sigma_v, self.clay_residual_floor, fs_initial=fs_i_clay))
            k = sm.alm_hamre_2001_friction_fatigue_k(qt, sigma_v, self.fatigue_rate_factor)
        f = sm.alm_hamre_2001_degraded_friction(fs_i, fs_res, k, z, tip_depth)
        outside = np.where(sand, self.sand_outside_factor, self.clay_outside_factor)
        inside = np.where(sand, self.sand_inside_factor, self.clay_inside_factor)
        return f * outside, f * inside

    def point_toe(self, profile: SoilProfile, depth) -> np.ndarray:
        """Unit toe resistance with the tip at ``depth`` [Pa] (no averaging; depth > 0).

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        depth : float or array_like
            Tip depth below the mudline [m].

        Returns
        -------
        numpy.ndarray
            Unit toe resistance [Pa].
        """
        z = np.asarray(depth, dtype=float)
        i = profile.layer_index(z)
        qt = profile.qt(z)
        with np.errstate(invalid="ignore", divide="ignore"):
            sand = sm.alm_hamre_2001_sand_toe(qt, profile.vertical_effective_stress(z),
                                              self.sand_toe_factor)
        return np.where(profile.is_sand[i], sand, sm.alm_hamre_2001_clay_toe(qt))

    def unit_toe(self, profile: SoilProfile, tip_depth: float) -> float:
        """Unit toe resistance for the tip at ``tip_depth`` [Pa].

        Averaged over ``toe_window`` centred on the tip, clipped to the profile and the CPT;
        or, with ``toe_qt_half_window`` and the tip in sand, the sand toe formula applied to
        qt averaged over the tip +- that half-window (clipped to the mudline and the CPT; qt
        held at the first reading above it, as :meth:`SoilProfile.qt`).

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        tip_depth : float
            Tip depth p [m].

        Returns
        -------
        float
            Unit toe resistance [Pa].
        """
        if self.toe_qt_half_window > 0.0:
            return self._averaged_qt_toe(profile, tip_depth)
        if self.toe_window <= 0.0:
            return float(self.point_toe(profile, tip_depth))
        half = 0.5 * self.toe_window
        low = max(tip_depth - half, 0.0)
        high = min(tip_depth + half, profile.bottom, float(profile.cpt.depth[-1]))
        if high <= low:
            return float(self.point_toe(profile, tip_depth))
        return _average(lambda z: self.point_toe(profile, z), low, high,
                        self.breakpoints(profile))

    def _averaged_qt_toe(self, profile: SoilProfile, tip_depth: float) -> float:
        """Unit toe resistance [Pa] of a tip in sand from qt averaged over the tip +-
        ``toe_qt_half_window`` (ICP-05 / UWA-05), sigma'v0 that at the tip; a tip in clay:
        the clay toe at the tip's qt."""
        profile.qt(tip_depth)  # a CPT that reaches the tip (ValueError otherwise)
        z = np.asarray(tip_depth, dtype=float)
        if not profile.is_sand[int(np.asarray(profile.layer_index(z)).reshape(-1)[0])]:
            return float(self.point_toe(profile, tip_depth))
        depth, qt = np.asarray(profile.cpt.depth, float), profile.qt_readings
        if depth[0] > 0.0:  # held at the first reading up to the mudline (SoilProfile.qt)
            depth, qt = np.concatenate(([0.0], depth)), np.concatenate((qt[:1], qt))
        qt_avg = sm.cone_resistance_averaged_about_tip(depth, qt, min(tip_depth, depth[-1]),
                                                       self.toe_qt_half_window)
        with np.errstate(invalid="ignore", divide="ignore"):
            return float(sm.alm_hamre_2001_sand_toe(
                qt_avg, profile.vertical_effective_stress(z), self.sand_toe_factor))


@dataclass(frozen=True)
class Stevens1982:
    """Stevens, Wiltsie & Turton (1982) SRD from soil layers.

    Clay after Semple & Gemeinhardt (1981).

    Parameters
    ----------
    bound : {"lower", "upper"}
        "lower" (K = 0.5) or "upper" (K = 0.7) sand friction.
    earth_pressure_coefficient : float or None, default None
        K [-] overriding ``bound`` (None: from ``bound``).
    outside_factor : float, default 1.0
        Factor on the unit friction on the outside face [-].
    inside_factor : float, default 1.0
        Factor on the unit friction on the inside face [-].
    ocr_floor : float or None, default SEMPLE_GEMEINHARDT_1981_OCR_FLOOR
        Lower limit of the estimated OCR in clay [-] (None for none).

    Raises
    ------
    ValueError
        If ``bound`` is neither "lower" nor "upper".

    References
    ----------
    Stevens, R.S., Wiltsie, E.A., Turton, T.H. (1982). Evaluating pile drivability for hard clay,
    very dense sand and rock. OTC 4205.
    Semple, R.M., Gemeinhardt, J.P. (1981). Stress history approach to analysis of soil resistance
    to pile driving. OTC 3969.
    """

    bound: str = "lower"
    earth_pressure_coefficient: float | None = None
    outside_factor: float = 1.0
    inside_factor: float = 1.0
    ocr_floor: float | None = sm.SEMPLE_GEMEINHARDT_1981_OCR_FLOOR

    name = "stevens-1982"

    def __post_init__(self):
        if self.bound not in ("lower", "upper"):
            raise ValueError(f"bound must be 'lower' or 'upper', got {self.bound!r}")

    @property
    def k(self) -> float:
        """Lateral earth-pressure coefficient K of the sand friction [-]."""
        if self.earth_pressure_coefficient is not None:
            return float(self.earth_pressure_coefficient)
        return sm.STEVENS_1982_K_UPPER if self.bound == "upper" else sm.STEVENS_1982_K_LOWER

    def check(self, profile: SoilProfile, deepest: float) -> None:
        """Check that ``profile`` has the data needed down to ``deepest``.

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        deepest : float
            Deepest tip depth to be analysed [m].

        Raises
        ------
        ValueError
            If a sand layer has neither delta nor phi', or a clay layer lacks su or PI or has
        su <= 0.
        """
        for i, layer in enumerate(profile.layers):
            if layer.top > deepest:
                break
            where = f"{layer.soil_type} layer {i} ({layer.top:g}-{layer.bottom:g} m)"
            if layer.soil_type == "sand" and np.isnan(layer.delta):
                raise ValueError(f"{where} needs interface_friction_angle or friction_angle")
            if layer.soil_type == "clay":
                if layer.undrained_shear_strength is None or layer.plasticity_index is None:
                    raise ValueError(f"{where} needs undrained_shear_strength and "
                                     "plasticity_index")
                su_bottom = (layer.undrained_shear_strength
                             + layer.undrained_shear_strength_gradient
                             * (layer.bottom - layer.top))
                if layer.undrained_shear_strength <= 0.0 or su_bottom <= 0.0:
                    raise ValueError(f"{where} needs an undrained shear strength above 0 Pa")

    def breakpoints(self, profile: SoilProfile) -> np.ndarray:
        """Depths where the inputs change: layer boundaries [m].

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.

        Returns
        -------
        numpy.ndarray
            Sorted unique depths [m].
        """
        return profile.breakpoints(with_cpt=False)

    def unit_friction(self, profile: SoilProfile, depth, tip_depth: float):
        """(outside, inside) unit shaft friction at ``depth`` (face factors applied; depth > 0).

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        depth : float or array_like
            Depths below the mudline [m].
        tip_depth : float
            Tip depth p [m]; not used (no friction fatigue).

        Returns
        -------
        outside : numpy.ndarray
            Unit shaft friction on the outside face [Pa].
        inside : numpy.ndarray
            Unit shaft friction on the inside face [Pa].
        """
        z = np.asarray(depth, dtype=float)
        i = profile.layer_index(z)
        sigma_v = profile.vertical_effective_stress(z)
        with np.errstate(invalid="ignore", divide="ignore"):
            sand = sm.stevens_1982_sand_friction(sigma_v, profile.delta[i], self.k)
            clay = sm.semple_gemeinhardt_1981_clay_friction(
                profile.undrained_shear_strength(z), sigma_v, profile.plasticity_index[i],
                ocr_floor=self.ocr_floor)
        f = np.where(profile.is_sand[i], sand, clay)
        return f * self.outside_factor, f * self.inside_factor

    def unit_toe(self, profile: SoilProfile, tip_depth: float) -> float:
        """Unit toe resistance for the tip at ``tip_depth`` [Pa].

        Parameters
        ----------
        profile : SoilProfile
            The soil profile.
        tip_depth : float
            Tip depth p [m].

        Returns
        -------
        float
            Unit toe resistance [Pa].
        """
        i = profile.layer_index(tip_depth)
        if profile.is_sand[i]:
            sigma_v = profile.vertical_effective_stress(tip_depth)
            return float(sm.stevens_1982_sand_toe(sigma_v, profile.delta[i]))
        return float(sm.stevens_1982_clay_toe(profile.undrained_shear_strength(tip_depth)))


TIP_TABLE_RULES = ("interpolate", "grlweap")
"""How a tip depth picks its table among tables per tip depth (:func:`tip_table_resistance`)."""


def tip_table_resistance(tip_depths, tables, tip_depth: float, depth, rule: str = "interpolate"):
    """Unit resistances from user tables given per tip depth (GRLWEAP style).

    For tip depths t_1 < ... < t_m the user gives tables of rows [depth [m], unit shaft
    friction [Pa], unit toe resistance [Pa]] (each linear between its rows, held constant
    beyond its first and last rows; a repeated depth makes a step). On a table's tip depth
    (p = t_j) both rules take that table exactly. Between table depths:

    ``"interpolate"`` (default)
        For t_j <= p <= t_j+1 the linear blend (1 - w) table_j + w table_j+1,
        w = (p - t_j) / (t_j+1 - t_j), both tables evaluated at the same depth; above t_1 the
        first table as it is. A single table (m = 1) is therefore a plain per-depth table. The
        toe value at a step (a repeated depth) is the one below the step.
    ``"grlweap"``
        GRLWEAP's convention: a driveability run with the table of tip depth t_j analyses the
        penetrations from t_j-1 down to t_j with that one table (its resistance distribution
        does not change within the run), so a tip at t_j-1 < p <= t_j takes table j, the
        nearest table at or below the tip (the first table above t_1). The toe value at a step
        lying exactly at the tip is the one above the step (the first of the repeated rows),
        as GRLWEAP interpolates the toe column at the penetration.

    Parameters
    ----------
    tip_depths : array_like
        (m,) tip depths of the tables [m], strictly increasing.
    tables : sequence of array_like
        m arrays of shape (n_j, 3).
    tip_depth : float
        Tip depth p [m], 0 <= p <= t_m.
    depth : float or array_like
        Depths at which the unit shaft friction is wanted [m].
    rule : {"interpolate", "grlweap"}
        How the tip depth picks its table.

    Returns
    -------
    shaft : numpy.ndarray
        Unit shaft friction at ``depth`` [Pa].
    toe : float
        Unit toe resistance at the tip [Pa].

    Raises
    ------
    ValueError
        If the rule is unknown or the tip depth lies outside 0 to t_m.
    """
    if rule not in TIP_TABLE_RULES:
        raise ValueError(f"unknown tip-table rule {rule!r}; choose one of {TIP_TABLE_RULES}")
    tips = np.asarray(tip_depths, dtype=float)
    if tip_depth > tips[-1] + _DEPTH_TOLERANCE or tip_depth < 0.0:
        raise ValueError(f"tip depth {tip_depth:g} m outside the tables' range 0 to "
                         f"{tips[-1]:g} m")
    z = np.asarray(depth, dtype=float)

    def at(table, column, x):
        table = np.asarray(table, dtype=float)
        return np.interp(x, table[:, 0], table[:, column])

    if rule == "grlweap":
        j = tip_table_index(tips, tip_depth, rule)
        table = np.asarray(tables[j], dtype=float)
        return at(table, 1, z), _toe_above_step(table, tip_depth)
    j = int(np.clip(np.searchsorted(tips, tip_depth, side="right") - 1, 0, tips.size - 1))
    j_next = min(j + 1, tips.size - 1)
    width = tips[j_next] - tips[j]
    w = float(np.clip((tip_depth - tips[j]) / width, 0.0, 1.0)) if width > 0.0 else 0.0
    shaft = (1.0 - w) * at(tables[j], 1, z) + w * at(tables[j_next], 1, z)
    toe = (1.0 - w) * at(tables[j], 2, tip_depth) + w * at(tables[j_next], 2, tip_depth)
    return shaft, float(toe)


def tip_table_index(tip_depths, tip_depth: float, rule: str = "interpolate") -> int:
    """Index of the table a tip depth takes by ``rule`` (:func:`tip_table_resistance`).

    Parameters
    ----------
    tip_depths : array_like
        (m,) tip depths of the tables [m], strictly increasing.
    tip_depth : float
        Tip depth p [m].
    rule : {"interpolate", "grlweap"}
        "grlweap" the nearest table at or below the tip, "interpolate" the nearest at or above it
        (the first of the two it blends).

    Returns
    -------
    int
        Index of the table.
    """
    tips = np.asarray(tip_depths, dtype=float)
    if rule == "grlweap":
        j = np.searchsorted(tips, tip_depth - _DEPTH_TOLERANCE, side="left")
    else:
        j = np.searchsorted(tips, tip_depth + _DEPTH_TOLERANCE, side="right") - 1
    return int(np.clip(j, 0, tips.size - 1))


def _toe_above_step(table: np.ndarray, tip_depth: float) -> float:
    """The toe column at ``tip_depth`` [m], linear between rows; at a repeated depth the
    value of its first row (above the step)."""
    on = np.flatnonzero(np.abs(table[:, 0] - tip_depth) <= 1e-9)
    if on.size:
        return float(table[on[0], 2])
    return float(np.interp(tip_depth, table[:, 0], table[:, 2]))


@dataclass(frozen=True, eq=False)
class TipDepthTables:
    """User SRD tables per tip depth (:func:`tip_table_resistance`); no soil profile needed.

    Parameters
    ----------
    tip_depths : numpy.ndarray
        (m,) tip depths [m], strictly increasing, >= 0.
    tables : tuple of numpy.ndarray
        m arrays of rows [depth [m], unit shaft friction [Pa], unit toe resistance [Pa]], depths
        non-decreasing from >= 0, resistances >= 0.
    outside_factor : float, default 1.0
        Factor on the unit friction on the outside face [-].
    inside_factor : float, default 1.0
        Factor on the unit friction on the inside face [-].
    rule : {"interpolate", "grlweap"}
        How a tip depth picks its table (:func:`tip_table_resistance`).

    Raises
    ------
    ValueError
        If the tip depths are negative or not strictly increasing, the rule is unknown, the number
        of tables differs from the number of tip depths, or a table is malformed, not finite, has
        decreasing or negative depths or negative resistances.
    """

    tip_depths: np.ndarray
    tables: tuple
    outside_factor: float = 1.0
    inside_factor: float = 1.0
    rule: str = "interpolate"

    name = "tip-depth-tables"

    def __post_init__(self):
        tips = np.atleast_1d(np.asarray(self.tip_depths, dtype=float))
        tables = tuple(np.asarray(t, dtype=float) for t in self.tables)
        object.__setattr__(self, "tip_depths", tips)
        object.__setattr__(self, "tables", tables)
        if tips.ndim != 1 or tips.size < 1 or np.any(np.diff(tips) <= 0.0) or tips[0] < 0.0:
            raise ValueError("tip_depths must be non-negative and strictly increasing")
        if self.rule not in TIP_TABLE_RULES:
            raise ValueError(f"unknown tip-table rule {self.rule!r}; choose one of "
                             f"{TIP_TABLE_RULES}")
        if len(tables) != tips.size:
            raise ValueError(f"need one table per tip depth: {tips.size} tip depths, "
                             f"{len(tables)} tables")
        for j, table in enumerate(tables):
            if table.ndim != 2 or table.shape[1] != 3 or table.shape[0] < 1:
                raise ValueError(f"table {j} must have rows [depth, unit shaft, unit toe]")
            if not np.all(np.isfinite(table)):
                raise ValueError(f"table {j} must contain finite numbers only")
            if table[0, 0] < 0.0 or np.any(np.diff(table[:, 0]) < 0.0):
                raise ValueError(f"table {j}: depths must start at >= 0 m and not decrease")
            if np.any(table[:, 1:] < 0.0):
                raise ValueError(f"table {j}: unit resistances must not be negative")

    def check(self, profile, deepest: float) -> None:
        """Check that ``deepest`` does not lie beyond the last tip depth.

        Parameters
        ----------
        profile : SoilProfile or None
            Not used (the tables need no profile).
        deepest : float
            Deepest tip depth to be analysed [m].

        Raises
        ------
        ValueError
            If ``deepest`` lies beyond the last tip depth.
        """
        if deepest > self.tip_depths[-1] + _DEPTH_TOLERANCE:
            raise ValueError(f"tip depth {deepest:g} m beyond the last table "
                             f"({self.tip_depths[-1]:g} m)")

    def breakpoints(self, profile) -> np.ndarray:
        """Depths of the table rows [m].

        Parameters
        ----------
        profile : SoilProfile or None
            Not used.

        Returns
        -------
        numpy.ndarray
            Sorted unique depths of the rows of all tables [m].
        """
        return np.unique(np.concatenate([t[:, 0] for t in self.tables]))

    def unit_friction(self, profile, depth, tip_depth: float):
        """(outside, inside) unit shaft friction at ``depth`` for the tip at ``tip_depth``.

        Face factors applied.

        Parameters
        ----------
        profile : SoilProfile or None
            Not used.
        depth : float or array_like
            Depths below the mudline [m].
        tip_depth : float
            Tip depth p [m].

        Returns
        -------
        outside : numpy.ndarray
            Unit shaft friction on the outside face [Pa].
        inside : numpy.ndarray
            Unit shaft friction on the inside face [Pa].
        """
        shaft, _ = tip_table_resistance(self.tip_depths, self.tables, tip_depth, depth,
                                        self.rule)
        return shaft * self.outside_factor, shaft * self.inside_factor

    def unit_toe(self, profile, tip_depth: float) -> float:
        """Unit toe resistance for the tip at ``tip_depth`` [Pa].

        Parameters
        ----------
        profile : SoilProfile or None
            Not used.
        tip_depth : float
            Tip depth p [m].

        Returns
        -------
        float
            Unit toe resistance [Pa].
        """
        return tip_table_resistance(self.tip_depths, self.tables, tip_depth, [], self.rule)[1]


def _method(method):
    if isinstance(method, str):
        if method == "alm-hamre-2001":
            return AlmHamre2001()
        if method == "stevens-1982":
            return Stevens1982()
        raise ValueError(f"unknown SRD method {method!r}; choose one of {METHODS} or pass a "
                         "method object")
    return method


# ---------------------------------------------------------------------------- integration
def _pieces(low: float, high: float, nodes: np.ndarray, resolution: float) -> np.ndarray:
    """Sorted piece ends covering [low, high]: ``nodes`` inside plus a split of every piece
    longer than ``resolution`` [m]."""
    inside = nodes[(nodes > low) & (nodes < high)]
    ends = np.unique(np.concatenate(([low, high], inside)))
    widths = np.diff(ends)
    counts = np.maximum(np.ceil(widths / resolution - 1e-9).astype(int), 1)
    if np.all(counts == 1):
        return ends
    starts = np.repeat(ends[:-1], counts)
    steps = np.repeat(widths / counts, counts)
    offsets = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    return np.concatenate((starts + offsets * steps, [high]))


def _cumulative(func, ends: np.ndarray, gauss_points: int):
    """Cumulative Gauss-Legendre integrals of ``func`` (returning a tuple of arrays) at
    ``ends``."""
    x, w = np.polynomial.legendre.leggauss(gauss_points)
    mid = 0.5 * (ends[:-1] + ends[1:])
    half = 0.5 * np.diff(ends)
    points = mid[:, None] + half[:, None] * x[None, :]
    values = func(points.ravel())
    return [np.concatenate(([0.0], np.cumsum((v.reshape(points.shape) @ w) * half)))
            for v in values]


def _average(func, low: float, high: float, nodes: np.ndarray) -> float:
    ends = _pieces(low, high, nodes, DEFAULT_RESOLUTION)
    (total,) = _cumulative(lambda z: (func(z),), ends, DEFAULT_GAUSS_POINTS)
    return float(total[-1] / (high - low))


@dataclass(frozen=True, eq=False)
class SrdDistribution:
    """Ultimate static soil resistance for one tip depth.

    Parameters
    ----------
    tip_depth : float
        Tip depth below the mudline [m].
    shaft : numpy.ndarray
        (N,) shaft resistance of each segment's embedded part [N].
    toe : float
        Toe resistance [N].
    embedded_length : numpy.ndarray
        (N,) embedded length of each segment [m].
    """

    tip_depth: float
    shaft: np.ndarray
    toe: float
    embedded_length: np.ndarray = field(repr=False)

    @property
    def srd_shaft(self) -> float:
        """Total shaft resistance [N]."""
        return float(np.sum(self.shaft))

    @property
    def srd_toe(self) -> float:
        """Toe resistance [N]."""
        return float(self.toe)

    @property
    def srd(self) -> float:
        """Total soil resistance to driving, shaft + toe [N]."""
        return self.srd_shaft + self.srd_toe


def toe_bearing_area(outer_diameter: float, wall_thickness: float,
                     pile_mode: str = "coring") -> float:
    """Toe bearing area [m^2] of a coring or a plugged pile.

    The steel annulus pi/4 (D^2 - (D - 2t)^2) for a coring pile, the full section pi/4 D^2 for a
    plugged one.

    Parameters
    ----------
    outer_diameter : float
        D [m].
    wall_thickness : float
        t [m].
    pile_mode : {"coring", "plugged"}
        Pile mode.

    Returns
    -------
    float
        Toe bearing area [m^2].

    Raises
    ------
    ValueError
        If ``pile_mode`` is unknown.
    """
    if pile_mode == "plugged":
        return 0.25 * np.pi * outer_diameter ** 2
    if pile_mode == "coring":
        inner = max(outer_diameter - 2.0 * wall_thickness, 0.0)
        return 0.25 * np.pi * (outer_diameter ** 2 - inner ** 2)
    raise ValueError(f"unknown pile_mode {pile_mode!r}; choose one of {PILE_MODES}")


def srd_distribution(profile: SoilProfile | None, method, tip_depth: float,
                     segment_top_depths, segment_lengths, outer_diameter, wall_thickness, *,
                     pile_mode: str = "coring", faces: str | None = None,
                     bound_multiplier: float = 1.0, resolution: float = DEFAULT_RESOLUTION,
                     gauss_points: int = DEFAULT_GAUSS_POINTS) -> SrdDistribution:
    """Shaft resistance per segment and toe resistance for the tip at ``tip_depth``.

    Parameters
    ----------
    profile : SoilProfile or None
        The soil profile (None for :class:`TipDepthTables`).
    method : str or object
        "alm-hamre-2001", "stevens-1982" (default options) or a method object
        (:class:`AlmHamre2001`, :class:`Stevens1982`, :class:`TipDepthTables`).
    tip_depth : float
        Depth of the pile tip below the mudline, the penetration p [m].
    segment_top_depths : array_like
        (N,) depth of each segment's top below the MUDLINE [m], negative above it; from segments
        measured down from the pile head: top - (pile_length - p).
    segment_lengths : array_like
        (N,) segment lengths [m]. No segment may reach below the tip; only the part of each
        segment below the mudline carries friction.
    outer_diameter : float or array_like
        D per segment or a scalar [m]; the toe takes that of the last segment (the toe segment).
    wall_thickness : float or array_like
        t per segment or a scalar [m]; the toe takes that of the last segment.
    pile_mode : {"coring", "plugged"}
        "coring" (toe on the annulus; default faces outside + inside) or "plugged" (toe on the
        full section; default faces outside).
    faces : {"outside", "outside+inside"} or None, default None
        Friction faces, overriding the default of ``pile_mode``.
    bound_multiplier : float, default 1.0
        Factor on shaft and toe [-] (1 best estimate).
    resolution : float, default DEFAULT_RESOLUTION
        Longest integration piece [m].
    gauss_points : int, default DEFAULT_GAUSS_POINTS
        Gauss-Legendre points per piece.

    Returns
    -------
    SrdDistribution
        Shaft resistance per segment and toe resistance [N].

    Raises
    ------
    ValueError
        If the method, ``pile_mode`` or ``faces`` is unknown, an option is out of range, a
        segment length is negative, a segment reaches below the tip, or the profile lacks data.
    """
    method = _method(method)
    if pile_mode not in PILE_MODES:
        raise ValueError(f"unknown pile_mode {pile_mode!r}; choose one of {PILE_MODES}")
    faces = faces if faces is not None else ("outside+inside" if pile_mode == "coring"
                                             else "outside")
    if faces not in FACES:
        raise ValueError(f"unknown faces {faces!r}; choose one of {FACES}")
    if bound_multiplier < 0.0 or resolution <= 0.0 or gauss_points < 1:
        raise ValueError("bound_multiplier must be >= 0, resolution > 0, gauss_points >= 1")
    top = np.atleast_1d(np.asarray(segment_top_depths, dtype=float))
    length = np.broadcast_to(np.asarray(segment_lengths, dtype=float), top.shape)
    diameter = np.broadcast_to(np.asarray(outer_diameter, dtype=float), top.shape)
    wall = np.broadcast_to(np.asarray(wall_thickness, dtype=float), top.shape)
    if np.any(length < 0.0):
        raise ValueError("segment lengths must not be negative")
    if np.any(top + length > tip_depth + 1e-6):
        raise ValueError(f"segments reach below the tip depth {tip_depth:g} m (deepest "
                         f"bottom {np.max(top + length):g} m): give the tops below the mudline")
    low = np.clip(top, 0.0, max(tip_depth, 0.0))
    high = np.clip(top + length, 0.0, max(tip_depth, 0.0))
    embedded = high - low
    shaft = np.zeros(top.shape)
    toe = 0.0
    if tip_depth > 0.0:
        if profile is not None:
            profile._check_depth(np.array([tip_depth]))
        method.check(profile, tip_depth)
        # graded pieces at the mudline, where sigma'v0 -> 0 makes the integrands singular
        # (sigma'v0^0.13, sqrt(1 / sigma'v0)): ratio 2.4 from 1e-9 x the resolution
        graded = resolution * np.geomspace(1e-9, 1.0, 25)
        nodes = np.concatenate((low, high, method.breakpoints(profile), graded))
        ends = _pieces(0.0, tip_depth, nodes, resolution)
        cum_out, cum_in = _cumulative(
            lambda z: method.unit_friction(profile, z, tip_depth), ends, gauss_points)
        ia, ib = np.searchsorted(ends, low), np.searchsorted(ends, high)
        outside_area = np.pi * diameter
        inside_area = np.pi * np.maximum(diameter - 2.0 * wall, 0.0)
        shaft = outside_area * (cum_out[ib] - cum_out[ia])
        if faces == "outside+inside":
            shaft = shaft + inside_area * (cum_in[ib] - cum_in[ia])
        area = toe_bearing_area(float(diameter[-1]), float(wall[-1]), pile_mode)
        toe = method.unit_toe(profile, tip_depth) * area
    return SrdDistribution(float(tip_depth), bound_multiplier * shaft,
                           float(bound_multiplier * toe), embedded)


def srd_versus_depth(profile: SoilProfile | None, method, tip_depths, outer_diameter: float,
                     wall_thickness: float, **options) -> tuple[np.ndarray, np.ndarray]:
    """Total shaft and toe resistance of a uniform pile for each tip depth.

    Parameters
    ----------
    profile : SoilProfile or None
        As :func:`srd_distribution`.
    method : str or object
        As :func:`srd_distribution`.
    tip_depths : array_like
        (m,) tip depths below the mudline [m].
    outer_diameter : float
        D of the embedded pile [m].
    wall_thickness : float
        t of the embedded pile [m].
    **options
        Keyword options of :func:`srd_distribution`.

    Returns
    -------
    srd_shaft : numpy.ndarray
        (m,) total shaft resistance [N].
    srd_toe : numpy.ndarray
        (m,) toe resistance [N].
    """
    tips = np.atleast_1d(np.asarray(tip_depths, dtype=float))
    shaft, toe = np.zeros(tips.shape), np.zeros(tips.shape)
    for n, tip in enumerate(tips):
        result = srd_distribution(profile, method, float(tip), [0.0], [float(tip)],
                                  outer_diameter, wall_thickness, **options)
        shaft[n], toe[n] = result.srd_shaft, result.srd_toe
    return shaft, toe
