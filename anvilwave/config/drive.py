"""The ``[driveability]`` and ``[srd]`` tables of a system file, and the pile and soil they
give at a tip depth.

:class:`DriveSettings` holds the depths, blow schedules, set rule and refusal criterion;
:class:`SrdSource` says where the SRD of each tip depth comes from. :func:`pile_soil_at`
embeds the system's pile to a tip depth with that tip's SRD, which every analysis that drives
the pile (drive, install, batch) starts from.

Tables per tip depth (``[srd] method = "tip-table"``): ``tip_table_rule`` chooses the table of
a tip depth, "interpolate" (default; a blend of the two tables around it) or "grlweap" (the
nearest table at or below the tip, the toe value above a step at the tip: a GRLWEAP run with
the table of tip depth t analyses the penetrations from the previous table depth down to t
with that table; :func:`anvilwave.pile.soil.profile.tip_table_resistance`); on a table depth
both take that table. ``layer_parameters = "file"`` takes the quakes and dampings per row of
each tip's table of a GRLWEAP model (:func:`grlweap_rows_to_layers`) instead of the [soil]
table's. ``[driveability] weight_on_soil`` and ``window`` are explained in
:mod:`anvilwave.analyses.drive`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from anvilwave.hammer.impact import impact_velocity_from_energy
from anvilwave.inputs import InputError, Table, note_input
from anvilwave.pile.soil.cpt import read_cpt_csv
from anvilwave.pile.soil.models import SoilLayers, smith_damping_by_soil_type, soil_capacities
from anvilwave.pile.soil.profile import (
    TIP_TABLE_RULES,
    AlmHamre2001,
    SoilLayer,
    SoilProfile,
    Stevens1982,
    TipDepthTables,
    srd_distribution,
    tip_table_index,
)

SET_RULES = ("permanent", "grlweap")

ENTHRU_LOCATIONS = ("gauge", "head")

BOUNDS = ("lower", "best", "upper")

SRD_METHODS = ("table", "tip-table", "alm-hamre-2001", "stevens-1982")

WEIGHT_RULES = ("all", "grlweap")
"""What weighs on the soil for the self-weight penetration and pile-run check (module
docstring of :mod:`anvilwave.analyses.drive`)."""

WINDOWS = ("fixed", "toe-rebound")
"""Blow windows (module docstring of :mod:`anvilwave.analyses.drive`)."""

DEFAULT_REFUSAL = 250.0
"""Refusal blow count [blows / 0.25 m] (common offshore practice)."""

DEFAULT_BLOW_RATE = 30.0
"""Blow rate of a hydraulic hammer [blows/min]."""

@dataclass(frozen=True)
class DriveSettings:
    """The ``[driveability]`` table of a system file.

    Parameters
    ----------
    depths : numpy.ndarray
        Tip depths below the mudline to analyse [m], increasing.
    blows_per_depth : int, default 1
        Blows per depth; > 1 is the residual-stress analysis [-].
    refusal : float, default DEFAULT_REFUSAL
        Refusal blow count [blows / 0.25 m].
    blow_rate : float, default DEFAULT_BLOW_RATE
        Hammer blow rate [blows/min].
    set_rule : {"permanent", "grlweap"}
        The set rule (module docstring of :mod:`anvilwave.analyses.drive`).
    enthru_location : {"gauge", "head"}
        Where ENTHRU is taken.
    energy_schedule : numpy.ndarray or None, default None
        (n, 2) rows [tip depth [m], blow energy [J]], linear between rows and constant
        beyond; None = the hammer's energy of the system file.
    bound : {"lower", "best", "upper"}
        The SRD bound.
    multipliers : dict, optional
        SRD factor of each bound [-] (default lower 0.8, best 1.0, upper 1.25).
    time_series_depths : tuple, default ()
        Depths whose blow time series are written [m].
    duration : float or None, default None
        Blow window [s] (default: the system's duration).
    stroke_schedule : numpy.ndarray or None, default None
        (n, 2) rows [tip depth [m], stroke [m]] instead of energies (the energy is
        m g stroke).
    efficiency_schedule : numpy.ndarray or None, default None
        (n, 2) rows [tip depth [m], efficiency [-]]; None = the hammer's.
    weight_on_soil : {"all", "grlweap"}
        The weight resting on the soil before driving (:mod:`anvilwave.analyses.drive`).
    window : str, default "fixed"
        The blow window, one of :data:`WINDOWS` (:mod:`anvilwave.analyses.drive`).
    """

    depths: np.ndarray
    blows_per_depth: int = 1
    refusal: float = DEFAULT_REFUSAL
    blow_rate: float = DEFAULT_BLOW_RATE
    set_rule: str = "permanent"
    enthru_location: str = "gauge"
    energy_schedule: np.ndarray | None = None
    bound: str = "best"
    multipliers: dict = field(default_factory=lambda: {"lower": 0.8, "best": 1.0,
                                                       "upper": 1.25})
    time_series_depths: tuple = ()
    duration: float | None = None
    stroke_schedule: np.ndarray | None = None
    efficiency_schedule: np.ndarray | None = None
    weight_on_soil: str = "all"
    window: str = "fixed"

    @property
    def multiplier(self) -> float:
        """SRD factor of the bound analysed [-]."""
        return float(self.multipliers[self.bound])

@dataclass(frozen=True)
class SrdSource:
    """Where the SRD of each tip depth comes from (the ``[srd]`` table).

    Parameters
    ----------
    method : str
        One of :data:`SRD_METHODS`: "table" (the ``[soil] srd`` rows against depth, no
        friction fatigue), "tip-table" (a table per tip depth, as GRLWEAP takes them),
        "alm-hamre-2001" (CPT and layers), "stevens-1982" (layers).
    profile : SoilProfile, optional
        The soil profile (layers and CPT) of the CPT/layer methods.
    method_object : object, optional
        The method with its options (:mod:`anvilwave.pile.soil.profile`).
    pile_mode : {"coring", "plugged"}
        The pile mode.
    faces : str or None, default None
        Friction faces override (None: the mode's).
    tip_layers : tuple or None, default None
        Quakes and dampings per layer of each tip table, a tuple of
        :class:`~anvilwave.pile.soil.models.SoilLayers` (one per table, from a GRLWEAP file's
        columns with ``layer_parameters = "file"``), or None (the [soil] table's).
    layers : SoilLayers or None, default None
        Quakes and dampings per layer for every tip (``layer_parameters = "soil-type"`` of the
        CPT and layer methods: by each layer's soil type), or None.
    """

    method: str
    profile: object = None
    method_object: object = None
    pile_mode: str = "coring"
    faces: str | None = None
    tip_layers: tuple | None = None
    layers: SoilLayers | None = None

def load_drive_settings(table: Table | None, source: str) -> DriveSettings:
    """Read and validate the ``[driveability]`` table.

    Parameters
    ----------
    table : Table or None
        The table (None when the file has none).
    source : str
        The system file, for messages.

    Returns
    -------
    DriveSettings
        The settings.

    Raises
    ------
    InputError
        If the table is missing or a key breaks its rule.
    """
    if table is None:
        raise InputError(source, "driveability", "the drive analysis needs a [driveability] "
                                                 "table (depths, refusal, energy schedule ...)")
    if table.has("depths") and any(table.has(k) for k in ("start", "stop", "step")):
        raise table.error("depths", "give either depths = [...] or start, stop and step")
    if table.has("depths"):
        depths = table.array("depths", min_rows=1)
    else:
        start = table.number("start", ge=0.0, unit="m")
        stop = table.number("stop", gt=start, unit="m")
        step = table.number("step", gt=0.0, unit="m")
        if (stop - start) / step > 10_000:
            raise table.error("step", f"gives {(stop - start) / step:.3g} depths (at most "
                                      "10000)")
        depths = start + step * np.arange(int(math.floor((stop - start) / step + 1e-9)) + 1)
    if np.any(depths <= 0.0) or np.any(np.diff(depths) <= 0.0):
        raise table.error("depths" if table.has("depths") else "start",
                          "tip depths must be positive and strictly increasing")
    blows = table.integer("blows_per_depth", 1, ge=1)
    if blows > 50:
        raise table.error("blows_per_depth", f"must be at most 50, got {blows}")
    refusal = table.number("refusal", DEFAULT_REFUSAL, gt=0.0, unit="blows/0.25m")
    rate = table.number("blow_rate", DEFAULT_BLOW_RATE, gt=0.0, le=300.0, unit="blows/min")
    set_rule = table.string("set_rule", "permanent", choices=SET_RULES)
    enthru = table.string("enthru_location", "gauge", choices=ENTHRU_LOCATIONS)
    schedule = table.array("energy", None, columns=2)
    if schedule is not None:
        if np.any(np.diff(schedule[:, 0]) <= 0.0) or np.any(schedule[:, 0] < 0.0):
            raise table.error("energy", "rows [tip depth [m], energy [J]] need strictly "
                                        "increasing, non-negative depths")
        if np.any(schedule[:, 1] <= 0.0):
            raise table.error("energy", "energies must be positive [J]")
    stroke = _schedule(table, "stroke", "stroke [m]", upper=10.0)
    efficiency = _schedule(table, "efficiency", "efficiency [-]", upper=1.0)
    if stroke is not None and schedule is not None:
        raise table.error("stroke", "give an energy or a stroke schedule, not both")
    bound = table.string("bound", "best", choices=BOUNDS)
    multipliers = {"lower": table.number("lower_multiplier", 0.8, gt=0.0, le=1.0),
                   "best": 1.0,
                   "upper": table.number("upper_multiplier", 1.25, ge=1.0, le=5.0)}
    series = table.array("time_series_depths", None, min_rows=0)  # [] writes none
    duration = table.number("duration", None, gt=0.0, le=1.0, unit="s")
    weight_rule = table.string("weight_on_soil", "all", choices=WEIGHT_RULES)
    window = table.string("window", "fixed", choices=WINDOWS)
    if window == "toe-rebound" and (blows > 1 or set_rule != "grlweap"):
        raise table.error("window", "'toe-rebound' stops the blow before the pile rests: it "
                                    "needs set_rule = 'grlweap' and blows_per_depth = 1")
    table.finish()
    return DriveSettings(depths=depths, blows_per_depth=blows, refusal=refusal,
                         blow_rate=rate, set_rule=set_rule, enthru_location=enthru,
                         energy_schedule=schedule, bound=bound, multipliers=multipliers,
                         time_series_depths=tuple(series) if series is not None else (),
                         duration=duration, stroke_schedule=stroke,
                         efficiency_schedule=efficiency, weight_on_soil=weight_rule,
                         window=window)

def _schedule(table: Table, key: str, what: str, upper: float):
    """A per-depth schedule: rows [tip depth [m], value], depths strictly increasing."""
    rows = table.array(key, None, columns=2)
    if rows is None:
        return None
    if np.any(np.diff(rows[:, 0]) <= 0.0) or np.any(rows[:, 0] < 0.0):
        raise table.error(key, f"rows [tip depth [m], {what}] need strictly increasing, "
                               "non-negative depths")
    if np.any(rows[:, 1] <= 0.0) or np.any(rows[:, 1] > upper):
        raise table.error(key, f"values must be in (0, {upper:g}]")
    return rows

def impact_at(settings: DriveSettings, depth: float, cfg) -> tuple[float, float]:
    """Blow energy and impact velocity of the schedules at a tip depth.

    Energy or stroke, and efficiency, each linear between rows and constant beyond; the system's
    blow energy and the hammer's efficiency where no schedule is given.

    Parameters
    ----------
    settings : DriveSettings
        The driveability settings.
    depth : float
        Tip depth below the mudline [m].
    cfg : SystemConfig
        The system (its hammer).

    Returns
    -------
    energy : float
        Blow energy [J].
    velocity : float
        Impact velocity [m/s].
    """

    mass = float(np.sum(cfg.hammer.ram.mass))
    eff = cfg.hammer.efficiency
    if settings.efficiency_schedule is not None:
        e = settings.efficiency_schedule
        eff = float(np.interp(depth, e[:, 0], e[:, 1]))
    if settings.stroke_schedule is not None:
        s = settings.stroke_schedule
        energy = mass * cfg.gravity * float(np.interp(depth, s[:, 0], s[:, 1]))
    else:
        energy = energy_at(settings, depth, cfg.blow_energy)
    if not eff == eff:  # a hammer given by its impact velocity: no efficiency
        eff = 1.0
    return energy, impact_velocity_from_energy(energy, mass, eff)

def energy_at(settings: DriveSettings, depth: float, default: float) -> float:
    """Blow energy of the schedule at a tip depth [J].

    Linear between rows, constant beyond.

    Parameters
    ----------
    settings : DriveSettings
        The driveability settings.
    depth : float
        Tip depth below the mudline [m].
    default : float
        Energy without a schedule [J].

    Returns
    -------
    float
        Blow energy [J].
    """
    s = settings.energy_schedule
    if s is None:
        return float(default)
    return float(np.interp(depth, s[:, 0], s[:, 1]))

def segment_capacities(pile_soil, srd: SrdSource, tip_depth: float, multiplier: float):
    """Shaft resistance per segment and toe resistance for the tip at ``tip_depth``.

    The pile head lies ``L - tip_depth`` above the mudline.

    Parameters
    ----------
    pile_soil : PileSoil
        The system's pile and soil model.
    srd : SrdSource
        The SRD source.
    tip_depth : float
        Tip depth below the mudline [m].
    multiplier : float
        SRD factor of the bound [-].

    Returns
    -------
    shaft : numpy.ndarray
        Shaft resistance per segment [N].
    toe : float
        Toe resistance [N].
    """

    pile = pile_soil.pile
    seg = pile.discretise()
    if srd.method == "table":
        soil = replace(pile_soil.soil, penetration=float(tip_depth), capacities=None)
        shaft, toe = soil_capacities(soil, pile, seg)
        return multiplier * shaft, multiplier * toe
    mudline = pile.length - tip_depth
    dist = srd_distribution(srd.profile, srd.method_object, float(tip_depth),
                            seg.top - mudline, seg.length, seg.outer_diameter,
                            seg.wall_thickness, pile_mode=srd.pile_mode, faces=srd.faces,
                            bound_multiplier=multiplier)
    return np.asarray(dist.shaft, dtype=float), float(dist.toe)

def pile_soil_at(pile_soil, srd: SrdSource, tip_depth: float, multiplier: float):
    """The system's PileSoil embedded to ``tip_depth`` with the SRD of that tip.

    Parameters
    ----------
    pile_soil : PileSoil
        The system's pile and soil model.
    srd : SrdSource
        The SRD source.
    tip_depth : float
        Tip depth below the mudline [m].
    multiplier : float
        SRD factor of the bound [-].

    Returns
    -------
    pile_soil : PileSoil
        The embedded pile and soil.
    shaft : float
        Total shaft resistance [N].
    toe : float
        Toe resistance [N].
    """
    shaft, toe = segment_capacities(pile_soil, srd, tip_depth, multiplier)
    soil = replace(pile_soil.soil, penetration=float(tip_depth), capacities=(shaft, toe))
    if srd.layers is not None:
        soil = replace(soil, layers=srd.layers)
    if srd.tip_layers is not None:
        tables = srd.method_object
        j = tip_table_index(tables.tip_depths, float(tip_depth), tables.rule)
        soil = replace(soil, layers=srd.tip_layers[j])
    return replace(pile_soil, soil=soil), float(shaft.sum()), float(toe)

def load_srd_source(table: Table | None, source: str, pile_soil) -> SrdSource:
    """Read the ``[srd]`` table (default: the ``[soil] srd`` rows, method "table").

    Parameters
    ----------
    table : Table or None
        The table (None when the file has none).
    source : str
        The system file, for messages.
    pile_soil : PileSoil
        The system's pile and soil model.

    Returns
    -------
    SrdSource
        The SRD source.

    Raises
    ------
    InputError
        If no SRD is given or a key of the table breaks its rule.
    """

    if table is None:
        if pile_soil.soil is None or pile_soil.soil.srd is None:
            raise InputError(source, "srd", "the drive analysis needs an SRD: a [srd] table "
                                            "or [soil] srd rows")
        return SrdSource("table")
    method = table.string("method", choices=SRD_METHODS)
    pile_mode = table.string("pile_mode", "coring", choices=("coring", "plugged"))
    faces = table.string("faces", None, choices=("outside", "outside+inside"))
    if method == "table":
        table.finish()
        if pile_soil.soil is None or pile_soil.soil.srd is None:
            raise table.error("method", "'table' uses the [soil] srd rows, which are missing")
        return SrdSource("table", pile_mode=pile_mode, faces=faces)
    if method == "tip-table":
        obj, layers = _tip_tables(table, pile_soil)
        table.finish()
        return SrdSource("tip-table", None, obj, pile_mode, faces, layers)
    layers = []
    for lt in table.tables("layers"):
        kind = lt.string("soil", choices=("sand", "clay"))
        try:
            layers.append(SoilLayer(
                top=lt.number("top", ge=0.0, unit="m"),
                bottom=lt.number("bottom", unit="m"),
                soil_type=kind,
                submerged_unit_weight=lt.number("submerged_unit_weight", gt=0.0,
                                                unit="N/m^3"),
                interface_friction_angle=lt.number("interface_friction_angle", None, gt=0.0,
                                                   lt=45.0, unit="deg"),
                friction_angle=lt.number("friction_angle", None, gt=0.0, lt=50.0, unit="deg"),
                undrained_shear_strength=lt.number("undrained_shear_strength", None, ge=0.0,
                                                   unit="Pa"),
                undrained_shear_strength_gradient=lt.number(
                    "undrained_shear_strength_gradient", 0.0, ge=0.0, unit="Pa/m"),
                plasticity_index=lt.number("plasticity_index", None, ge=0.0, le=2.0),
            ))
        except ValueError as exc:
            raise lt.error("soil", str(exc)) from None
        lt.finish()
    cpt = None
    if table.has("cpt"):

        path = table.path("cpt")
        cpt = read_cpt_csv(path, qc_unit=table.string("cpt_qc_unit", None),
                           fs_unit=table.string("cpt_fs_unit", None),
                           u2_unit=table.string("cpt_u2_unit", None),
                           depth_reference=table.string("cpt_depth_reference", "mudline",
                                                        choices=("mudline", "sea-level")),
                           water_depth=table.number("water_depth", None, ge=0.0, unit="m"))
    try:
        profile = SoilProfile(layers, cpt=cpt,
                              net_area_ratio=table.number("net_area_ratio", 0.8, gt=0.0,
                                                          le=1.0))
    except ValueError as exc:
        raise table.error("layers", str(exc)) from None
    if method == "alm-hamre-2001":
        if cpt is None:
            raise table.error("cpt", "the Alm & Hamre (2001) method needs a CPT file")
        obj = AlmHamre2001(
            sand_toe_factor=table.number("sand_toe_factor", 0.15, gt=0.0, le=1.0),
            clay_residual_floor=table.string("clay_residual_floor", "zero",
                                             choices=("zero", "0.002qt", "clamp")))
    else:
        obj = Stevens1982(bound=table.string("stevens_bound", "lower",
                                             choices=("lower", "upper")))
    by_type = table.string("layer_parameters", "soil", choices=("soil", "soil-type"))
    table.finish()
    layers = soil_type_layers(profile, pile_soil.soil) if by_type == "soil-type" else None
    return SrdSource(method, profile, obj, pile_mode, faces, layers=layers)


def soil_type_layers(profile, soil) -> SoilLayers:
    """Quakes and dampings per layer of a soil profile by its layers' soil types.

    The Smith shaft and toe dampings of
    :func:`anvilwave.pile.soil.models.smith_damping_by_soil_type`, the quakes of the [soil]
    table (``soil``); the last layer extended 1 km down.

    Parameters
    ----------
    profile : SoilProfile
        The soil profile.
    soil : SoilSpec
        The [soil] table's model (its quakes).

    Returns
    -------
    SoilLayers
        One layer per layer of the profile.
    """
    rows = []
    for k, layer in enumerate(profile.layers):
        shaft, toe = smith_damping_by_soil_type(layer.soil_type)
        bottom = layer.bottom if k + 1 < len(profile.layers) else layer.bottom + 1e3
        rows.append([layer.top, bottom, soil.quake_shaft, soil.quake_toe, shaft, toe])
    return SoilLayers(np.array(rows))

def _tip_tables(table: Table, pile_soil):
    """Per-tip-depth tables: inline ``[[srd.tables]]`` (tip_depth, rows [depth [m], unit shaft
    [Pa], unit toe [Pa]]) or ``file`` = a GRLWEAP-style model.json (``format``); ``tip_table_rule``
    says how a tip depth picks its table (:func:`anvilwave.pile.soil.profile.
    tip_table_resistance`)."""
    rule = table.string("tip_table_rule", "interpolate", choices=TIP_TABLE_RULES)
    layers = None
    if table.has("file"):
        path = table.path("file")
        fmt = table.string("format", "grlweap-model-json", choices=("grlweap-model-json",))
        if not path.exists():
            raise table.error("file", f"{path} not found (the GRLWEAP benchmark input lies in "
                                      "../shared/reference/grlweap-s4000/ beside the "
                                      "repository; it is never copied into it)")
        tips, tables = read_grlweap_tip_tables(path, pile_soil, table.source, fmt)
        if table.string("layer_parameters", "soil", choices=("soil", "file")) == "file":
            layers = read_grlweap_tip_layers(path)
    else:
        tips, tables = [], []
        for t in table.tables("tables"):
            tips.append(t.number("tip_depth", ge=0.0, unit="m"))
            tables.append(t.array("rows", columns=3))
            t.finish()
    try:
        return TipDepthTables(np.array(tips), tuple(tables), rule=rule), layers
    except ValueError as exc:
        raise table.error("tables", str(exc)) from None


GRLWEAP_LAYER_COLUMNS = ("shaft_quake [mm]", "toe_quake [mm]", "shaft_damping [s/m]",
                         "toe_damping [s/m]")
"""The quake and damping columns of a GRLWEAP table row, in :class:`SoilLayers` order."""


def grlweap_rows_to_layers(rows: np.ndarray) -> SoilLayers:
    """Quakes and dampings per layer from the rows of a GRLWEAP resistance table.

    Parameters
    ----------
    rows : ndarray
        (n, 5) rows [soil depth [m], shaft quake [mm], toe quake [mm], shaft damping [s/m], toe
        damping [s/m]], depths non-decreasing (a repeated depth is a step).

    Returns
    -------
    SoilLayers
        One layer from each row to the next deeper row, with the values of the row at its top
        (below a step, the step's second row); the last row's values from its depth down.
    """
    rows = np.asarray(rows, dtype=float)
    out = []
    for k in range(rows.shape[0]):
        top = rows[k, 0]
        bottom = rows[k + 1, 0] if k + 1 < rows.shape[0] else max(top, 0.0) + 1e3
        if bottom > top:
            out.append([top, bottom, 1e-3 * rows[k, 1], 1e-3 * rows[k, 2], rows[k, 3],
                        rows[k, 4]])
    return SoilLayers(np.array(out))


def read_grlweap_tip_layers(path: Path) -> tuple:
    """The quakes and dampings of every tip table of a GRLWEAP input decoded to JSON.

    Sorted by tip depth (:func:`grlweap_rows_to_layers`).

    Parameters
    ----------
    path : pathlib.Path
        The JSON file.

    Returns
    -------
    tuple of SoilLayers
        One per tip table.

    Raises
    ------
    InputError
        If a table's rows cannot be read.
    """
    runs = json.loads(Path(path).read_text())["soil_model"]["srd_tables_by_run"]
    note_input(path)
    items = []
    for key, run in runs.items():
        try:
            cols = run["columns"]
            rows = np.array(run["rows"], dtype=float)
            idx = [cols.index("soil_depth [m]")] + [cols.index(c) for c in GRLWEAP_LAYER_COLUMNS]
            items.append((float(run["tip_depth_the_table_was_built_for [m]"]),
                          grlweap_rows_to_layers(rows[:, idx])))
        except (KeyError, ValueError, TypeError) as exc:
            raise InputError(path, f"soil_model.srd_tables_by_run.{key}",
                             f"has no valid quake and damping columns ({exc})") from None
    items.sort(key=lambda x: x[0])
    return tuple(x[1] for x in items)

def read_grlweap_tip_tables(path: Path, pile_soil, source: str, fmt: str):
    """The SRD tables by tip depth of a GRLWEAP input decoded to JSON.

    ``soil_model.srd_tables_by_run``: rows soil depth [m], unit shaft [kPa], toe resistance [kN].
    The toe force is turned into a unit resistance on the pile's toe annulus, so the
    distribution gives it back on the same area.

    Parameters
    ----------
    path : pathlib.Path
        The JSON file.
    pile_soil : PileSoil
        The system's pile and soil model.
    source : str
        The system file, for messages.
    fmt : str
        Format of the file (``"grlweap-model-json"``).

    Returns
    -------
    tip_depths : list of float
        The tip depths of the tables [m], increasing.
    tables : list of numpy.ndarray
        Rows [depth [m], unit shaft friction [Pa], unit toe resistance [Pa]].

    Raises
    ------
    InputError
        If the file cannot be read or a run breaks a rule.
    """
    try:
        data = json.loads(Path(path).read_text())
        note_input(path)
        runs = data["soil_model"]["srd_tables_by_run"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError(path, "soil_model.srd_tables_by_run", f"cannot be read ({exc})") \
            from None
    where = "soil_model.srd_tables_by_run"
    if not isinstance(runs, dict) or not runs:
        raise InputError(path, where, "must be a non-empty object of runs {\"1\": {...}, ...}, "
                                      f"got {type(runs).__name__}")
    seg = pile_soil.pile.discretise()
    d, t = float(seg.outer_diameter[-1]), float(seg.wall_thickness[-1])
    area = math.pi * (d - t) * t
    items = []
    for key, run in runs.items():
        at = f"{where}.{key}"
        try:
            if not isinstance(run, dict):
                raise TypeError(f"the run is a {type(run).__name__}, not an object")
            tip = float(run["tip_depth_the_table_was_built_for [m]"])
            cols = list(run["columns"])
            rows = np.array(run["rows"], dtype=float)
            iz, ish, ito = (cols.index(c) for c in ("soil_depth [m]",
                                                     "unit_shaft_resistance [kPa]",
                                                     "toe_resistance [kN]"))
        except (KeyError, ValueError, TypeError) as exc:
            raise InputError(path, at, f"is not a GRLWEAP table ({exc})") from None
        if rows.ndim != 2 or rows.shape[0] < 1 or rows.shape[1] != len(cols):
            raise InputError(path, f"{at}.rows", f"must be at least one row of {len(cols)} "
                                                 f"numbers (the columns), got shape "
                                                 f"{rows.shape}")
        if not math.isfinite(tip) or tip < 0.0:
            raise InputError(path, f"{at}.tip_depth_the_table_was_built_for [m]",
                             f"must be a finite depth >= 0 m, got {tip!r}")
        for i, row in enumerate(rows):
            if not np.all(np.isfinite(row)):
                raise InputError(path, f"{at}.rows", f"row {i + 1}: {row.tolist()} is not "
                                                     "finite")
            if row[ish] < 0.0 or row[ito] < 0.0 or row[iz] < 0.0:
                raise InputError(path, f"{at}.rows", f"row {i + 1}: {row.tolist()} has a "
                                                     "negative depth or resistance")
        if np.any(np.diff(rows[:, iz]) < 0.0):
            # a depth given twice is a step of the resistance (GRLWEAP's layer boundaries)
            bad = int(np.flatnonzero(np.diff(rows[:, iz]) < 0.0)[0]) + 2
            raise InputError(path, f"{at}.rows", f"row {bad}: soil depths must not decrease "
                                                 f"({rows[bad - 2, iz]:g} m, then "
                                                 f"{rows[bad - 1, iz]:g} m)")
        if any(abs(tip - other) < 1e-9 for other, _ in items):
            raise InputError(path, f"{at}.tip_depth_the_table_was_built_for [m]",
                             f"{tip:g} m is the tip depth of another run (duplicate)")
        table = np.column_stack([rows[:, iz], 1e3 * rows[:, ish], 1e3 * rows[:, ito] / area])
        items.append((tip, table))
    items.sort(key=lambda x: x[0])
    return [x[0] for x in items], [x[1] for x in items]
