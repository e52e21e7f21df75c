"""Signal matching: the soil of a system file fitted to a gauge record by least squares.

The measured velocity (or wave down) drives the pile below the gauges of the system file (cut at
the gauges, :func:`anvilwave.pile.pda.signal_matching.run_prescribed_head`); the computed wave up
is matched
to the measured one (:func:`anvilwave.pile.pda.signal_matching.match_residuals`, bounded
``scipy.optimize.least_squares``, trust-region reflective, forward-difference Jacobian). The
soil model is the system file's Smith model (``"smith"`` or ``"smith-viscous"``; a
``"lysmer-toe"`` toe is matched as a Smith-viscous toe started from the quake R_u / k and the
damping c / R_u of its Lysmer analog). The unknowns:

* the shaft resistance of ``shaft_zones`` zones of equal length between the mudline and the
  toe [N] (within a zone the resistance keeps the shape of the starting guess along the depth,
  uniform where the guess has none);
* the toe resistance [N];
* the shaft and toe quakes [m] (``fit_quakes``) and Smith dampings [s/m] (``fit_dampings``).

Start: the system file's soil (its SRD on the matching discretisation). Bounds: resistances
0 to 2 max F (no static resistance can exceed twice the largest force that reaches it),
quakes 0.25 mm to 25 mm, dampings 0 to 3 s/m. The variables are scaled to order one (a
resistance scale of max(Rut_start, max WD) / (zones + 1), quakes by 2.5 mm, dampings by 0.5 s/m)
and the Jacobian uses a relative step of 1e-3 (the model has kinks where a spring yields, so a
smaller step would differentiate noise).

Soil above the gauges (gauges below the mudline) is not seen by the match and is left out.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field

import numpy as np

from anvilwave.config.budget import check_match_budget
from anvilwave.engine.compilation import announce_compilation
from anvilwave.inputs import InputError
from anvilwave.pile.kernels import (
    SOIL_CAPACITY,
    SOIL_DASHPOT,
    SOIL_ROWS,
    SOIL_SMITH,
    SOIL_STIFFNESS,
    SOIL_TENSION,
)
from anvilwave.pile.pda.case_method import first_peak_index, pile_impedance, wave_down, wave_up
from anvilwave.pile.pda.records import GaugeRecord
from anvilwave.pile.pda.signal_matching import (
    DAVISSON_OFFSET,
    IMPOSED,
    davisson_capacity,
    face_displacement,
    face_stiffness,
    forward_time_step,
    impact_foot,
    match_intervals,
    match_quality,
    match_residuals,
    pile_below_gauges,
    run_prescribed_head,
    sections_above_gauges,
    static_load_test,
)
from anvilwave.pile.pile import discretise, pile_parameters
from anvilwave.pile.soil.models import (
    DEFAULT_DAMPING_TOE,
    DEFAULT_QUAKE,
    smith_springs,
    soil_capacities,
    soil_parameters,
)
from anvilwave.pile.static import static_equilibrium

QUAKE_BOUNDS = (2.5e-4, 2.5e-2)
"""Bounds of the fitted quakes [m]."""
DAMPING_BOUNDS = (0.0, 3.0)
"""Bounds of the fitted Smith dampings [s/m]."""
PRE_IMPACT = 5e-4
"""The match starts this long before the impact (or at the record start) [s]."""
DIFF_STEP = 1e-3
"""Relative step of the finite-difference Jacobian [-]."""


@dataclass(frozen=True)
class MatchSettings:
    """Options of :func:`match_record`.

    Parameters
    ----------
    shaft_zones : int, default 3
        Number of shaft resistance zones between the mudline and the toe [-].
    imposed : {"velocity", "wave_down"}
        ``"velocity"`` (compute the force) or ``"wave_down"`` (compute the wave up).
    segment_length : float, optional
        Segment length of the matching model [m] (default: the system file's).
    fit_quakes : bool, default True
        Fit the quakes (else keep the start).
    fit_dampings : bool, default True
        Fit the Smith dampings (else keep the start).
    preload : float, optional
        Force on the gauges at rest [N] (default: :func:`rest_force_at_gauges`).
    max_evaluations : int, default 2000
        Most forward runs of the least-squares search [-].
    """

    shaft_zones: int = 3
    imposed: str = "velocity"
    segment_length: float | None = None
    fit_quakes: bool = True
    fit_dampings: bool = True
    preload: float | None = None
    max_evaluations: int = 2000


@dataclass
class SoilParameters:
    """Soil of the matching model.

    Parameters
    ----------
    zone_resistance : numpy.ndarray
        Static shaft resistance of each zone [N].
    toe_resistance : float
        Static toe resistance [N].
    quake_shaft : float
        Shaft quake [m].
    quake_toe : float
        Toe quake [m].
    damping_shaft : float
        Shaft Smith damping J [s/m].
    damping_toe : float
        Toe Smith damping J [s/m].

    Attributes
    ----------
    rut_shaft : float
        Total static shaft resistance [N].
    rut : float
        Total static resistance, shaft and toe [N].
    """

    zone_resistance: np.ndarray
    toe_resistance: float
    quake_shaft: float
    quake_toe: float
    damping_shaft: float
    damping_toe: float

    @property
    def rut_shaft(self) -> float:
        """Total static shaft resistance, the sum over the zones [N]."""
        return float(np.sum(self.zone_resistance))

    @property
    def rut(self) -> float:
        """Total static resistance, shaft plus toe [N]."""
        return self.rut_shaft + float(self.toe_resistance)


@dataclass
class MatchResult:
    """The fitted soil, the match and the simulated static load test (SI).

    Parameters
    ----------
    soil : SoilParameters
        The fitted soil.
    start : SoilParameters
        The starting guess.
    match_quality : float
        MQ of the fit [-].
    match_quality_terms : dict of str to float
        MQ term per interval [-].
    start_match_quality : float
        MQ of the starting guess [-].
    zones : list of dict
        Depths [m] and resistances [N] of the shaft zones.
    columns : dict of str to numpy.ndarray
        Measured and computed signals, named ``name [unit]``.
    static_load_test : dict of str to numpy.ndarray
        ``settlement [m]`` and ``load [N]`` of the head.
    davisson_capacity : float
        Davisson's capacity of the load-settlement curve [N] (NaN if not reached).
    info : dict
        Settings and statistics of the match.
    """

    soil: SoilParameters
    start: SoilParameters
    match_quality: float
    match_quality_terms: dict[str, float]
    start_match_quality: float
    zones: list[dict]
    columns: dict[str, np.ndarray]
    static_load_test: dict[str, np.ndarray]
    davisson_capacity: float
    info: dict = field(default_factory=dict)

    def summary(self) -> dict:
        """match.json content, named ``name [unit]``.

        Returns
        -------
        dict
            The summary.
        """
        s = self.soil
        out = {
            "rut [N]": s.rut, "rut_shaft [N]": s.rut_shaft, "rut_toe [N]": s.toe_resistance,
            "match_quality [-]": self.match_quality,
            "quake_shaft [m]": s.quake_shaft, "quake_toe [m]": s.quake_toe,
            "damping_shaft [s/m]": s.damping_shaft, "damping_toe [s/m]": s.damping_toe,
            "shaft_zones": self.zones,
            "match_quality_terms [-]": self.match_quality_terms,
            "davisson_capacity [N]": (None if math.isnan(self.davisson_capacity)
                                      else self.davisson_capacity),
            "start": {"rut [N]": self.start.rut, "rut_shaft [N]": self.start.rut_shaft,
                      "rut_toe [N]": self.start.toe_resistance,
                      "quake_shaft [m]": self.start.quake_shaft,
                      "quake_toe [m]": self.start.quake_toe,
                      "damping_shaft [s/m]": self.start.damping_shaft,
                      "damping_toe [s/m]": self.start.damping_toe,
                      "match_quality [-]": self.start_match_quality},
        }
        out.update(self.info)
        return out


def rest_force_at_gauges(cfg) -> float:
    """Force on the gauges with the hammer at rest on the pile [N].

    What rests on the head (the anvil's weight; the classic system's helmet and assembly;
    nothing for ``"none"``) plus the weight of the pile above the gauges (gravity of the system
    file).

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    float
        The force at rest [N].
    """
    g = cfg.gravity
    pile = cfg.pile_soil.pile
    above = sum(s.density * s.area * s.length for s in sections_above_gauges(pile))
    return head_rest_force(cfg) + above * g


def head_rest_force(cfg) -> float:
    """Force on the pile head at rest [N] (:func:`rest_force_at_gauges`).

    The FE anvil's mass is the volume of revolution of its outline times its density (exact for
    the polygon).

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    float
        The force at rest on the head [N].

    Raises
    ------
    InputError
        If the anvil's mass is unknown (no ``anvil.mass`` and no outline).
    """
    g = cfg.gravity
    anvil = cfg.anvil
    if anvil.model == "none":
        return 0.0
    if anvil.model == "classic":
        return float(anvil.classic.static_pile_force(g))
    if anvil.mass is not None:
        return float(anvil.mass) * g
    spec = anvil.spec
    if spec is None or spec.outline is None:
        raise InputError(cfg.source, "anvil.file", "the anvil's mass is needed for the force "
                                                   "at rest: give anvil.mass or an outline")
    return revolution_volume(spec.outline) * spec.material.density * g


def revolution_volume(outline) -> float:
    """Volume of the solid of revolution of a closed (r, z) polygon about r = 0 [m^3].

    Pappus: 2 pi times the first moment of the polygon's area about the axis.

    Parameters
    ----------
    outline : array_like
        Polygon vertices, rows (r, z) [m].

    Returns
    -------
    float
        The volume [m^3].
    """
    r, z = np.asarray(outline, dtype=float).T
    r1, z1 = np.roll(r, -1), np.roll(z, -1)
    cross = r * z1 - r1 * z
    return float(abs(np.pi / 3.0 * np.sum((r + r1) * cross)))


def redistribute(values, old_top, old_bottom, new_top, new_bottom) -> np.ndarray:
    """Per-segment totals moved onto other segments by overlap length [same unit as ``values``].

    Each old total is spread uniformly over its segment.

    Parameters
    ----------
    values : array_like
        Totals per old segment.
    old_top : numpy.ndarray
        Upper ends of the old segments [m].
    old_bottom : numpy.ndarray
        Lower ends of the old segments [m].
    new_top : numpy.ndarray
        Upper ends of the new segments [m].
    new_bottom : numpy.ndarray
        Lower ends of the new segments [m].

    Returns
    -------
    numpy.ndarray
        Totals per new segment [same unit as ``values``].
    """
    values = np.asarray(values, dtype=float)
    out = np.zeros(len(new_top))
    for j, (a, b) in enumerate(zip(new_top, new_bottom, strict=True)):
        overlap = np.clip(np.minimum(old_bottom, b) - np.maximum(old_top, a), 0.0, None)
        out[j] = float(np.sum(values * overlap / (old_bottom - old_top)))
    return out


class ForwardModel:
    """The pile below the gauges of a system, driven by a record (module notes).

    Parameters
    ----------
    cfg : SystemConfig
        The system (its pile, soil and gravity).
    record : GaugeRecord
        The measured record.
    settings : MatchSettings
        The match options.

    Attributes
    ----------
    pile : PileSpec
        The pile below the gauges.
    start : SoilParameters
        The starting guess from the system's soil.
    impedance : float
        Impedance Z of the pile at the gauges [N s/m].
    round_trip : float
        2L/c below the gauges [s].
    preload : float
        Force on the gauges at rest [N].

    Raises
    ------
    InputError
        If the system has no soil, or the record is too short to match.
    ValueError
        If ``settings.imposed`` is unknown or ``settings.shaft_zones`` < 1.
    """

    def __init__(self, cfg, record: GaugeRecord, settings: MatchSettings):
        soil = cfg.pile_soil.soil
        if soil is None:
            raise InputError(cfg.source, "soil", "signal matching needs a [soil] table (the "
                                                 "soil model and the starting guess)")
        if settings.imposed not in IMPOSED:
            raise ValueError(f"imposed must be one of {tuple(IMPOSED)}, got "
                             f"{settings.imposed!r}")
        if settings.shaft_zones < 1:
            raise ValueError("shaft_zones must be at least 1")
        whole = cfg.pile_soil.pile
        self.pile = pile_below_gauges(whole, settings.segment_length)
        self.settings = settings
        seg = discretise(self.pile)
        self.segments = seg
        self.pile_arrays = np.ascontiguousarray(pile_parameters(self.pile, seg))
        self.head_stiffness = face_stiffness(self.pile)
        self.impedance = float(pile_impedance(seg.youngs_modulus[0], seg.area[0],
                                              seg.wave_speed[0]))
        self.length = self.pile.length
        travel = float(np.sum(seg.length / seg.wave_speed))
        self.round_trip = 2.0 * travel
        self.gravity = cfg.gravity
        self.preload = (rest_force_at_gauges(cfg) if settings.preload is None
                        else float(settings.preload))
        self.viscous = soil.model != "smith"
        self.model = soil.model
        self.mudline = whole.length - soil.penetration - whole.gauge_depth  # below the gauges
        check_match_budget(settings.shaft_zones, seg.count, len(record.time),
                           settings.max_evaluations,
                           2 * int(settings.fit_quakes) + 2 * int(settings.fit_dampings))
        self._zones(cfg, soil)
        self._record(record)

    # -- soil ---------------------------------------------------------------------------------
    def _zones(self, cfg, soil):
        whole = cfg.pile_soil.pile
        full = discretise(whole)
        shaft_full, toe = soil_capacities(soil, whole, full)
        g = whole.gauge_depth
        seg = self.segments
        guess = redistribute(shaft_full, full.top - g, full.bottom - g, seg.top, seg.bottom)
        n = self.settings.shaft_zones
        top = max(self.mudline, 0.0)
        edges = np.linspace(top, self.length, n + 1)
        embedded = np.clip(np.minimum(seg.bottom[:, None], edges[None, 1:])
                           - np.maximum(seg.top[:, None], edges[None, :-1]), 0.0, None)
        shape = np.zeros((n, seg.count))
        for k in range(n):
            part = guess * embedded[:, k] / np.maximum(seg.length, 1e-300)
            if part.sum() > 0.0:
                shape[k] = part / part.sum()
            else:
                shape[k] = embedded[:, k] / embedded[:, k].sum()
        self.zone_edges = edges
        self.zone_shape = shape
        zone_start = np.array([float(np.sum(guess * embedded[:, k]
                                            / np.maximum(seg.length, 1e-300)))
                               for k in range(n)])
        if soil.model == "lysmer-toe":  # its elastic toe as a Smith toe (module notes)
            arrays = soil_parameters(soil, whole, full)
            k_toe, c_toe = arrays[SOIL_STIFFNESS, -1], arrays[SOIL_DASHPOT, -1]
            quake_toe = toe / k_toe if toe > 0.0 and k_toe > 0.0 else DEFAULT_QUAKE
            damping_toe = c_toe / toe if toe > 0.0 else DEFAULT_DAMPING_TOE
        else:
            quake_toe, damping_toe = soil.quake_toe, soil.damping_toe
        self.start = SoilParameters(zone_start, float(toe), soil.quake_shaft, quake_toe,
                                    soil.damping_shaft, damping_toe)

    def soil_arrays(self, p: SoilParameters) -> np.ndarray:
        """The kernel soil array (SOIL_ROWS, N + 1) of soil parameters.

        Parameters
        ----------
        p : SoilParameters
            The soil.

        Returns
        -------
        numpy.ndarray
            The kernel soil array, shape (SOIL_ROWS, N + 1).
        """
        shaft = p.zone_resistance @ self.zone_shape
        n = shaft.size
        arr = np.zeros((SOIL_ROWS, n + 1))
        k, smith, dashpot = smith_springs(shaft, p.quake_shaft, p.damping_shaft, self.viscous)
        arr[SOIL_CAPACITY, :n] = shaft
        arr[SOIL_TENSION, :n] = shaft
        arr[SOIL_STIFFNESS, :n] = k
        arr[SOIL_SMITH, :n] = smith
        arr[SOIL_DASHPOT, :n] = dashpot
        k, smith, dashpot = smith_springs(np.array([p.toe_resistance]), p.quake_toe,
                                          p.damping_toe, self.viscous)
        arr[SOIL_CAPACITY, n] = p.toe_resistance
        arr[SOIL_STIFFNESS, n] = k[0]
        arr[SOIL_SMITH, n] = smith[0]
        arr[SOIL_DASHPOT, n] = dashpot[0]
        return arr

    # -- record -------------------------------------------------------------------------------
    def _record(self, record: GaugeRecord):
        z = self.impedance
        t, f, v = record.time, record.force, record.velocity
        wd = wave_down(f, v, z)
        i0 = impact_foot(wd)
        i1 = first_peak_index(wd)
        t0, t1 = float(t[i0]), float(t[i1])
        if t0 + self.round_trip > t[-1]:
            raise InputError(record.source, "time [s]",
                             f"the record ends at {t[-1]:g} s, before the impact "
                             f"({t0:g} s) + 2L/c ({self.round_trip:g} s): too short to match")
        start = int(np.searchsorted(t, t0 - PRE_IMPACT))
        end = int(np.searchsorted(t, t0 + 3.0 * self.round_trip, side="right"))
        window = slice(start, max(end, start + 3))
        self.time = np.ascontiguousarray(t[window])
        self.force = np.ascontiguousarray(f[window])
        self.velocity = np.ascontiguousarray(v[window])
        self.wave_down = wd[window]
        self.wave_up = wave_up(self.force, self.velocity, z)
        self.impact_time, self.peak_time = t0, t1
        self.intervals = match_intervals(self.time, t0, self.round_trip, t1 - t0)
        self.peak_wave_down = float(np.max(self.wave_down))
        self.max_force = float(np.max(self.force))

    # -- forward run --------------------------------------------------------------------------
    def run(self, p: SoilParameters, dt_max: float | None = None
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Run the forward model at the record samples of the match window.

        Parameters
        ----------
        p : SoilParameters
            The soil.
        dt_max : float, optional
            Largest sub-step [s] (default: :func:`forward_time_step` of this soil).

        Returns
        -------
        force : numpy.ndarray
            Force as the zeroed gauges read it [N].
        velocity : numpy.ndarray
            Velocity at the gauges [m/s].
        wave_up : numpy.ndarray
            Computed wave up [N].
        """
        soil = self.soil_arrays(p)
        try:
            u, offset = static_equilibrium(self.pile_arrays, soil, self.preload, self.gravity)
        except ValueError:  # the weights exceed this soil: start unloaded, the pile sinks
            u, offset = np.zeros(self.segments.count), np.zeros(self.segments.count + 1)
        vel = np.zeros_like(u)
        face0 = u[0] + self.preload / self.head_stiffness
        imposed = IMPOSED[self.settings.imposed]
        signal = (face_displacement(self.time, self.velocity, face0) if imposed == 0
                  else self.wave_down)
        if dt_max is None:
            dt_max = forward_time_step(self.pile_arrays, soil, self.head_stiffness)
        n = self.time.size
        force, velocity = np.zeros(n), np.zeros(n)
        run_prescribed_head(self.pile_arrays, soil, u, vel, offset, imposed, self.time,
                            np.ascontiguousarray(signal, dtype=float), face0,
                            self.head_stiffness, self.impedance, self.preload, self.gravity,
                            dt_max, force, velocity)
        force -= self.preload
        if imposed == 0:
            velocity = self.velocity.copy()
        return force, velocity, wave_up(force, velocity, self.impedance)

    def quality(self, computed_wave_up) -> tuple[float, dict[str, float]]:
        """Match quality of a computed wave up against the record's.

        Parameters
        ----------
        computed_wave_up : numpy.ndarray
            WU_c at the samples [N].

        Returns
        -------
        quality : float
            MQ [-].
        terms : dict of str to float
            The term of each interval [-].
        """
        return match_quality(computed_wave_up, self.wave_up, self.intervals, self.peak_wave_down)

    def residuals(self, computed_wave_up) -> np.ndarray:
        """Least-squares residuals of a computed wave up against the record's.

        Parameters
        ----------
        computed_wave_up : numpy.ndarray
            WU_c at the samples [N].

        Returns
        -------
        numpy.ndarray
            The residuals [-].
        """
        return match_residuals(computed_wave_up, self.wave_up, self.intervals, self.peak_wave_down)


# ---------------------------------------------------------------------------------- the fit
class _Packing:
    """Soil parameters <-> the scaled vector of the least-squares search."""

    def __init__(self, model: ForwardModel, settings: MatchSettings):
        self.start = model.start
        n = settings.shaft_zones
        self.n = n
        r_scale = max(model.start.rut, model.peak_wave_down) / (n + 1)
        names = [f"zone_{k + 1}" for k in range(n)] + ["toe"]
        scale = [r_scale] * (n + 1)
        upper = [2.0 * model.max_force] * (n + 1)
        lower = [0.0] * (n + 1)
        if settings.fit_quakes:
            names += ["quake_shaft", "quake_toe"]
            scale += [2.5e-3, 2.5e-3]
            lower += [QUAKE_BOUNDS[0]] * 2
            upper += [QUAKE_BOUNDS[1]] * 2
        if settings.fit_dampings:
            names += ["damping_shaft", "damping_toe"]
            scale += [0.5, 0.5]
            lower += [DAMPING_BOUNDS[0]] * 2
            upper += [DAMPING_BOUNDS[1]] * 2
        self.names = names
        self.scale = np.array(scale)
        self.lower = np.array(lower) / self.scale
        self.upper = np.array(upper) / self.scale

    def pack(self, p: SoilParameters) -> np.ndarray:
        values = {"toe": p.toe_resistance, "quake_shaft": p.quake_shaft,
                  "quake_toe": p.quake_toe, "damping_shaft": p.damping_shaft,
                  "damping_toe": p.damping_toe}
        values.update({f"zone_{k + 1}": p.zone_resistance[k] for k in range(self.n)})
        x = np.array([values[name] for name in self.names]) / self.scale
        return np.clip(x, self.lower, self.upper)

    def unpack(self, x) -> SoilParameters:
        values = dict(zip(self.names, np.asarray(x) * self.scale, strict=True))
        s = self.start
        return SoilParameters(
            np.array([values[f"zone_{k + 1}"] for k in range(self.n)]), float(values["toe"]),
            float(values.get("quake_shaft", s.quake_shaft)),
            float(values.get("quake_toe", s.quake_toe)),
            float(values.get("damping_shaft", s.damping_shaft)),
            float(values.get("damping_toe", s.damping_toe)))


def match_record(record: GaugeRecord, cfg, settings: MatchSettings | None = None
                 ) -> MatchResult:
    """Fit the soil of a system (``SystemConfig``) to a gauge record (module notes).

    Parameters
    ----------
    record : GaugeRecord
        The measured record.
    cfg : SystemConfig
        The system.
    settings : MatchSettings, optional
        The match options (default: ``MatchSettings()``).

    Returns
    -------
    MatchResult
        The fitted soil, the match and the simulated static load test.
    """
    from scipy.optimize import least_squares


    settings = settings or MatchSettings()
    started = _time.perf_counter()
    model = ForwardModel(cfg, record, settings)
    packing = _Packing(model, settings)
    x0 = packing.pack(model.start)
    start = packing.unpack(x0)
    # one sub-step size for the whole search (a fixed discretisation keeps the residuals
    # smooth in the parameters): the start's stable step, shortened if the bounds need it
    dt_start = forward_time_step(model.pile_arrays, model.soil_arrays(start),
                                 model.head_stiffness)
    announce_compilation([run_prescribed_head])
    _, _, wu_start = model.run(start, dt_start)
    start_quality, _ = model.quality(wu_start)
    evaluations = [0]

    def residuals(x):
        evaluations[0] += 1
        p = packing.unpack(x)
        dt = min(dt_start, forward_time_step(model.pile_arrays, model.soil_arrays(p),
                                             model.head_stiffness))
        return model.residuals(model.run(p, dt)[2])

    solution = least_squares(residuals, x0, bounds=(packing.lower, packing.upper),
                             method="trf", diff_step=DIFF_STEP, x_scale=1.0,
                             max_nfev=settings.max_evaluations, xtol=1e-8, ftol=1e-10)
    fitted = packing.unpack(solution.x)
    dt = min(dt_start, forward_time_step(model.pile_arrays, model.soil_arrays(fitted),
                                         model.head_stiffness))
    force, velocity, wu = model.run(fitted, dt)
    quality, terms = model.quality(wu)
    zones = []
    for k in range(settings.shaft_zones):
        top, bottom = model.zone_edges[k], model.zone_edges[k + 1]
        zones.append({"top_below_mudline [m]": float(top - model.mudline),
                      "bottom_below_mudline [m]": float(bottom - model.mudline),
                      "top_below_gauges [m]": float(top),
                      "bottom_below_gauges [m]": float(bottom),
                      "resistance [N]": float(fitted.zone_resistance[k]),
                      "start_resistance [N]": float(start.zone_resistance[k])})
    columns = {
        "time [s]": model.time,
        "measured_force [N]": model.force, "computed_force [N]": force,
        "measured_velocity [m/s]": model.velocity, "computed_velocity [m/s]": velocity,
        "measured_wave_down [N]": model.wave_down,
        "measured_wave_up [N]": model.wave_up, "computed_wave_up [N]": wu,
    }
    slt, davisson = _static_test(model, cfg, fitted)
    info = {
        "imposed": settings.imposed, "matched": "wave_up",
        "soil_model": model.model,
        "segment_length [m]": float(model.pile.segment_length),
        "length_below_gauges [m]": float(model.length),
        "impedance [N s/m]": model.impedance,
        "rest_force_at_gauges [N]": model.preload,
        "impact_time [s]": model.impact_time,
        "round_trip_time [s]": model.round_trip,
        "evaluations": int(evaluations[0]),
        "optimizer_status": int(solution.status),
        "optimizer_message": str(solution.message),
        "wall_time [s]": _time.perf_counter() - started,
    }
    return MatchResult(fitted, start, quality, terms, start_quality, zones, columns, slt,
                       davisson, info)


def _static_test(model: ForwardModel, cfg, soil: SoilParameters
                 ) -> tuple[dict[str, np.ndarray], float]:
    """Load-settlement curve of the head from the fitted soil, and Davisson's capacity."""
    arrays = model.soil_arrays(soil)
    whole = cfg.pile_soil.pile
    above = sections_above_gauges(whole)
    flex_above = sum(s.length / (s.youngs_modulus * s.area) for s in above)
    top = whole.sections[0]
    seg = model.segments
    flex_total = flex_above + float(np.sum(seg.length / (seg.youngs_modulus * seg.area)))
    quake = max(soil.quake_shaft, soil.quake_toe)
    toe_diameter = whole.sections[-1].outer_diameter
    limit = 1.2 * (soil.rut * flex_total + DAVISSON_OFFSET + toe_diameter / 120.0 + quake)
    face = np.linspace(0.0, limit, 201)
    loads = static_load_test(model.pile_arrays, arrays, model.head_stiffness, face)
    head = face + loads * flex_above
    davisson = davisson_capacity(head, loads, whole.length, top.area, top.youngs_modulus,
                                 toe_diameter)
    return {"settlement [m]": head, "load [N]": loads}, davisson


__all__ = ["ForwardModel", "MatchResult", "MatchSettings", "SoilParameters", "head_rest_force",
           "match_record", "redistribute", "rest_force_at_gauges", "revolution_volume"]
