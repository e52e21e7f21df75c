"""Driveability: blow count, stresses and transferred energy against the tip depth.

For every penetration (tip depth p) the pile is embedded to p, its SRD distribution is rebuilt
for that tip (friction fatigue makes the unit friction at a point depend on how far the tip has
passed it), the hammer runs at the energy of the schedule at p, and one or more blows are
simulated (with ``blows_per_depth > 1`` each blow starts from the state the previous one left:
the residual-stress analysis). The blow's set gives the blow count. Stresses follow the
axial-force convention (positive in compression): ``max_tension_stress`` is the most negative
stress, a negative number.

Two set rules (``set_rule``):

``"permanent"`` (default)
    The toe's displacement at the end of the blow window minus at its start, once the pile has
    come to rest: the set the pile really keeps. The window must be long enough for the pile to
    rest (checked: the toe velocity at the end is reported, and a warning column flags blows
    whose pile is still moving).
``"grlweap"``
    GRLWEAP's rule: the maximum toe displacement during the blow minus the toe quake (the
    elastic rebound of the toe spring). It ignores the shaft's rebound and any later motion;
    used to put results beside GRLWEAP's.

ENTHRU (transferred energy) is EMX at the gauge (``enthru_location = "gauge"``, as a PDA
measures it) or at the pile head (``"head"``, GRLWEAP's first segment). Refusal is a blow count
above ``refusal`` blows per 0.25 m (default 250). Total blows integrate the blow count over
depth from the self-weight penetration to the last depth driven (or the refusal depth);
driving time is total blows / blow rate.

Self-weight penetration and pile runs: the weight of pile, hammer and helmet (or anvil) rests
on the soil. The pile penetrates under its own weight to the first depth where the SRD (its
static resistance at that tip depth) exceeds the weight; deeper, a depth where the SRD falls
below the weight again (a soft layer) is a pile run.
"""

from __future__ import annotations

import json
import math
import os
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.integrate import trapezoid

from anvilwave.inputs import InputError, Table

SET_RULES = ("permanent", "grlweap")
ENTHRU_LOCATIONS = ("gauge", "head")
BOUNDS = ("lower", "best", "upper")
SRD_METHODS = ("table", "tip-table", "alm-hamre-2001", "stevens-1982")
DEFAULT_REFUSAL = 250.0
"""Refusal blow count [blows / 0.25 m] (common offshore practice)."""
DEFAULT_BLOW_RATE = 30.0
"""Blow rate of a hydraulic hammer [blows/min]."""
MIN_SET = 1e-7
"""Sets below this [m] count as zero (blow count infinite: refusal)."""

COLUMNS = ("depth [m]", "srd [N]", "srd_shaft [N]", "srd_toe [N]", "blow_count [1/m]",
           "blows_per_0.25m [-]", "set [m]", "energy_setting [J]", "enthru [J]",
           "max_compression_stress [Pa]", "max_tension_stress [Pa]",
           "max_pile_head_force [N]", "emx_gauge [J]", "emx_head [J]",
           "permanent_set [m]", "grlweap_set [m]", "impact_velocity [m/s]",
           "energy_residual_relative [-]", "toe_velocity_end [m/s]", "FMX [N]", "RMX [N]",
           "case_damping [-]")
"""Columns of ``driveability.csv`` (the DESIGN.md contract first, then extra columns)."""


# ----------------------------------------------------------------------------- settings
@dataclass(frozen=True)
class DriveSettings:
    """The ``[driveability]`` table of a system file.

    depths : tip depths below the mudline to analyse [m], increasing.
    blows_per_depth : blows per depth; > 1 is the residual-stress analysis [-].
    refusal : refusal blow count [blows / 0.25 m].
    blow_rate : hammer blow rate [blows/min].
    set_rule : "permanent" or "grlweap" (module docstring).
    enthru_location : "gauge" or "head".
    energy_schedule : (n, 2) rows [tip depth [m], blow energy [J]], linear between rows and
        constant beyond; None = the hammer's energy of the system file.
    stroke_schedule : (n, 2) rows [tip depth [m], stroke [m]] instead of energies (the
        energy is m g stroke).
    efficiency_schedule : (n, 2) rows [tip depth [m], efficiency [-]]; None = the hammer's.
    bound : "lower", "best" or "upper"; multipliers : SRD factor of each bound [-].
    time_series_depths : depths whose blow time series are written [m].
    duration : blow window [s] (default: the system's duration).
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

    @property
    def multiplier(self) -> float:
        return float(self.multipliers[self.bound])


@dataclass(frozen=True)
class SrdSource:
    """Where the SRD of each tip depth comes from (the ``[srd]`` table).

    method : one of :data:`SRD_METHODS`: "table" (the ``[soil] srd`` rows against depth,
        no friction fatigue), "tip-table" (a table per tip depth, as GRLWEAP takes them),
        "alm-hamre-2001" (CPT and layers), "stevens-1982" (layers).
    profile : the soil profile (layers and CPT) of the CPT/layer methods.
    method_object : the method with its options (:mod:`anvilwave.pile.soil.profile`).
    pile_mode : "coring" or "plugged"; faces : friction faces override (None: the mode's).
    """

    method: str
    profile: object = None
    method_object: object = None
    pile_mode: str = "coring"
    faces: str | None = None


def load_drive_settings(table: Table | None, source: str) -> DriveSettings:
    """Read and validate the ``[driveability]`` table."""
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
    series = table.array("time_series_depths", None)
    duration = table.number("duration", None, gt=0.0, le=1.0, unit="s")
    table.finish()
    return DriveSettings(depths=depths, blows_per_depth=blows, refusal=refusal,
                         blow_rate=rate, set_rule=set_rule, enthru_location=enthru,
                         energy_schedule=schedule, bound=bound, multipliers=multipliers,
                         time_series_depths=tuple(series) if series is not None else (),
                         duration=duration, stroke_schedule=stroke,
                         efficiency_schedule=efficiency)


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
    """(blow energy [J], impact velocity [m/s]) of the schedules at a tip depth: energy or
    stroke, and efficiency, each linear between rows and constant beyond; the system's blow
    energy and the hammer's efficiency where no schedule is given."""
    from anvilwave.hammer.impact import impact_velocity_from_energy

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
    """Blow energy of the schedule at a tip depth [J] (linear between rows, constant
    beyond); ``default`` [J] without a schedule."""
    s = settings.energy_schedule
    if s is None:
        return float(default)
    return float(np.interp(depth, s[:, 0], s[:, 1]))


# ----------------------------------------------------------------------------- SRD
def segment_capacities(pile_soil, srd: SrdSource, tip_depth: float, multiplier: float):
    """Shaft resistance per segment [N], toe resistance [N] for the tip at ``tip_depth`` [m]
    below the mudline (the pile head ``L - tip_depth`` above it)."""
    from anvilwave.pile.soil.models import soil_capacities
    from anvilwave.pile.soil.profile import srd_distribution

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
    """The system's PileSoil embedded to ``tip_depth`` [m] with the SRD of that tip."""
    shaft, toe = segment_capacities(pile_soil, srd, tip_depth, multiplier)
    soil = replace(pile_soil.soil, penetration=float(tip_depth), capacities=(shaft, toe))
    return replace(pile_soil, soil=soil), float(shaft.sum()), float(toe)


# ----------------------------------------------------------------------------- analysis
@dataclass
class DepthResult:
    """One analysed depth (the columns of :data:`COLUMNS`) and its last blow."""

    row: dict
    blow: object = None


def set_of_blow(blow, rule: str, toe_quake: float) -> float:
    """The blow's set [m] by the rule (module docstring)."""
    if rule == "grlweap":
        return max(float(blow.max_toe_displacement) - toe_quake, 0.0)
    return max(float(blow.permanent_set), 0.0)


def blow_count(set_m: float) -> float:
    """Blows per metre from the set [m] (infinite below :data:`MIN_SET`)."""
    return 1.0 / set_m if set_m > MIN_SET else math.inf


def analyse_depth(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float,
                  record: bool = False) -> DepthResult:
    """Simulate the blows of one tip depth and summarise them (one CSV row)."""
    ps, shaft, toe = pile_soil_at(cfg.pile_soil, srd, depth, settings.multiplier)
    energy, velocity = impact_at(settings, depth, cfg)
    weight = driving_weight(cfg, engine.static_head_force)
    if shaft + toe <= weight:  # the pile runs (or stands) under its own weight: no blows
        return DepthResult(_run_row(depth, shaft, toe, energy, velocity))
    eng = engine.with_pile_soil(ps)
    try:
        state = eng.static_state()
    except ValueError:  # no static equilibrium: the SRD does not carry the weight
        return DepthResult(_run_row(depth, shaft, toe, energy, velocity))
    blow = None
    for k in range(settings.blows_per_depth):
        last = k == settings.blows_per_depth - 1
        # the last blow records its gauge signals (for the Case method; 2-7 % of its cost)
        blow = eng.blow(state=state, impact_velocity=velocity, duration=settings.duration,
                        record=record or last, energy=record)
        state = blow.final_state
    quake_toe = float(ps.soil.quake_toe)
    permanent = set_of_blow(blow, "permanent", quake_toe)
    grl = set_of_blow(blow, "grlweap", quake_toe)
    set_m = set_of_blow(blow, settings.set_rule, quake_toe)
    count = blow_count(set_m)
    enthru = blow.emx_gauge if settings.enthru_location == "gauge" else blow.emx_head
    residual = float("nan")
    if record and getattr(blow, "energies", None):
        from anvilwave.output.tables import energy_balance

        residual = energy_balance(blow)["residual_relative [-]"]
    row = {
        "depth [m]": float(depth), "srd [N]": shaft + toe, "srd_shaft [N]": shaft,
        "srd_toe [N]": toe, "blow_count [1/m]": count, "blows_per_0.25m [-]": 0.25 * count,
        "set [m]": set_m, "energy_setting [J]": energy, "enthru [J]": float(enthru),
        "max_compression_stress [Pa]": float(blow.max_compression_stress),
        "max_tension_stress [Pa]": float(blow.max_tension_stress),
        "max_pile_head_force [N]": float(blow.max_pile_head_force),
        "emx_gauge [J]": float(blow.emx_gauge), "emx_head [J]": float(blow.emx_head),
        "permanent_set [m]": permanent, "grlweap_set [m]": grl,
        "impact_velocity [m/s]": float(velocity),
        "energy_residual_relative [-]": residual,
        "toe_velocity_end [m/s]": float(getattr(blow, "toe_velocity_end", float("nan"))),
    }
    row.update(_case_method(blow, replace(cfg, pile_soil=ps)))
    return DepthResult(row, blow if record else None)


def _case_method(blow, cfg) -> dict:
    """FMX, RMX (and the Jc used) of the blow's gauge signals by the Case method."""
    from anvilwave.analyses.pda import pda_summary

    try:
        p = pda_summary(blow.columns, cfg)
    except (ValueError, KeyError):
        return {}
    return {"FMX [N]": p["FMX [N]"], "RMX [N]": float("nan") if p["RMX [N]"] is None
            else float(p["RMX [N]"]), "case_damping [-]": p["case_damping [-]"]}


def _run_row(depth, shaft, toe, energy, velocity) -> dict:
    """The row of a depth where the SRD does not carry the driving weight: no blow needed
    (blow count 0; the stresses and energies of a blow are not computed)."""
    row = {name: float("nan") for name in COLUMNS}
    row.update({"depth [m]": float(depth), "srd [N]": shaft + toe, "srd_shaft [N]": shaft,
                "srd_toe [N]": toe, "blow_count [1/m]": 0.0, "blows_per_0.25m [-]": 0.0,
                "energy_setting [J]": energy, "impact_velocity [m/s]": float(velocity)})
    return row


# worker state for the process pool (inherited by fork: the engine is built once)
_WORK: dict = {}


def _work(depth: float) -> dict:
    w = _WORK
    return analyse_depth(w["engine"], w["cfg"], w["srd"], w["settings"], depth).row


def run_driveability(cfg, srd: SrdSource, settings: DriveSettings, engine=None, *,
                     workers: int | None = None, progress: bool = False) -> dict:
    """Analyse every depth of ``settings``; returns ``{"rows": [...], "summary": {...}}``.

    cfg : the :class:`~anvilwave.config.system.SystemConfig` (its hammer, anvil, pile and soil
    model).
    engine : a built :class:`~anvilwave.engine.direct.Engine` for ``cfg`` (default: built here).
    workers : processes over the depths (default: the machine's cores; 1 runs in-process).
    """
    from anvilwave.engine.direct import build_engine

    start = time.perf_counter()
    if engine is None:
        engine = build_engine(cfg)
    depths = [float(d) for d in settings.depths if d <= cfg.pile_soil.pile.length]
    workers = workers or os.cpu_count() or 1
    workers = max(1, min(workers, len(depths)))
    rows: list[dict] = []
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(depths), desc="depths", unit="depth")
    try:
        if workers == 1:
            for d in depths:
                rows.append(analyse_depth(engine, cfg, srd, settings, d).row)
                if bar is not None:
                    bar.update(1)
        else:
            import multiprocessing as mp
            from concurrent.futures import ProcessPoolExecutor

            _WORK.update(engine=engine, cfg=cfg, srd=srd, settings=settings)
            try:
                with ProcessPoolExecutor(workers, mp_context=mp.get_context("fork")) as pool:
                    for row in pool.map(_work, depths, chunksize=max(1, len(depths)
                                                                     // (4 * workers))):
                        rows.append(row)
                        if bar is not None:
                            bar.update(1)
            finally:
                _WORK.clear()
    finally:
        if bar is not None:
            bar.close()
    summary = summarise(rows, cfg, settings, engine.static_head_force)
    summary["wall_time [s]"] = time.perf_counter() - start
    summary["depths_analysed [-]"] = len(rows)
    summary["workers [-]"] = workers
    return {"rows": rows, "summary": summary}


def driving_weight(cfg, head_load: float) -> float:
    """Weight resting on the soil before driving [N]: pile and ram, plus ``head_load`` [N],
    the anvil's (or the helmet's and hammer assembly's) weight on the pile head."""
    seg = cfg.pile_soil.pile.discretise()
    pile = float(np.sum(seg.area * seg.length * seg.density))
    return (pile + float(np.sum(cfg.hammer.ram.mass))) * cfg.gravity + float(head_load)


def summarise(rows: list[dict], cfg, settings: DriveSettings, head_load: float) -> dict:
    """Refusal depth, total blows, driving time, self-weight penetration and pile runs."""
    depth = np.array([r["depth [m]"] for r in rows])
    count = np.array([r["blow_count [1/m]"] for r in rows])
    srd = np.array([r["srd [N]"] for r in rows])
    refused = np.flatnonzero(0.25 * count > settings.refusal)
    refusal_depth = float(depth[refused[0]]) if refused.size else None
    weight = driving_weight(cfg, head_load)
    above = np.flatnonzero(srd >= weight)
    swp = float(depth[above[0]]) if above.size else (float(depth[-1]) if depth.size else 0.0)
    # a pile run: deeper than the self-weight penetration, the SRD falls below the weight
    runs = [float(d) for d, r in zip(depth, srd, strict=True) if d > swp and r < weight]
    # blows: the blow count integrated from the self-weight penetration to the last depth
    # driven (the refusal depth included, where driving stops)
    last = refused[0] if refused.size else len(depth) - 1
    z = depth[: last + 1]
    n = np.where(np.isfinite(count[: last + 1]), count[: last + 1], 0.0)
    n = np.where(z < swp, 0.0, n)
    n = np.where(np.isin(z, runs), 0.0, n)  # the pile runs through these depths
    total = float(trapezoid(n, z)) if z.size > 1 else 0.0
    if refused.size and refused[0] > 0:
        # the last interval at the refusal blow count would be infinite; count it to refusal
        total = float(trapezoid(np.where(np.isfinite(n), n, 4.0 * settings.refusal), z))
    return {
        "refusal_depth [m]": refusal_depth,
        "total_blows [-]": total,
        "driving_time [s]": total / settings.blow_rate * 60.0,
        "self_weight_penetration [m]": swp,
        "driving_weight [N]": weight,
        "pile_run_depths [m]": runs,
        "max_blow_count [1/m]": float(np.max(np.where(np.isfinite(count), count,
                                                        4.0 * settings.refusal))
                                      if count.size else 0.0),
        "max_compression_stress [Pa]": float(np.nanmax(
            [r["max_compression_stress [Pa]"] for r in rows] + [0.0])),
        # stresses are positive in compression: the largest tension is the most negative
        "max_tension_stress [Pa]": float(np.nanmin(
            [r["max_tension_stress [Pa]"] for r in rows] + [0.0])),
        "set_rule": settings.set_rule,
        "enthru_location": settings.enthru_location,
        "bound": settings.bound,
        "srd_multiplier [-]": settings.multiplier,
        "refusal_criterion [blows/0.25m]": settings.refusal,
        "blow_rate [blows/min]": settings.blow_rate,
        "blows_per_depth [-]": settings.blows_per_depth,
        "anvil_model": cfg.anvil.model,
    }


def write_results(result: dict, out, cfg, settings: DriveSettings, title: str = "") -> None:
    """``driveability.csv``, ``summary.json`` and ``driveability.png`` into a ResultWriter."""
    from anvilwave.output.plots import plot_driveability
    from anvilwave.output.tables import write_csv

    rows = result["rows"]
    columns = {name: np.array([r[name] for r in rows], dtype=float) for name in COLUMNS}
    write_csv(columns, out.part("driveability.csv"))
    summary = dict(result["summary"])
    summary["system"] = str(cfg.source)
    out.part("summary.json").write_text(json.dumps(_jsonable(summary), indent=2) + "\n")
    plot_driveability(columns, summary, out.part("driveability.png"), title=title)


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, np.floating | np.integer):
        return _jsonable(x.item())
    return x


def load_srd_source(table: Table | None, source: str, pile_soil) -> SrdSource:
    """Read the ``[srd]`` table (default: the ``[soil] srd`` rows, method "table")."""
    from anvilwave.pile.soil.profile import (
        AlmHamre2001,
        SoilLayer,
        SoilProfile,
        Stevens1982,
    )

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
        obj = _tip_tables(table, pile_soil)
        table.finish()
        return SrdSource("tip-table", None, obj, pile_mode, faces)
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
        from anvilwave.pile.soil.cpt import read_cpt_csv

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
    table.finish()
    return SrdSource(method, profile, obj, pile_mode, faces)


def _tip_tables(table: Table, pile_soil):
    """Per-tip-depth tables: inline ``[[srd.tables]]`` (tip_depth, rows [depth [m], unit shaft
    [Pa], unit toe [Pa]]) or ``file`` = a GRLWEAP-style model.json (``format``)."""
    from anvilwave.pile.soil.profile import TipDepthTables

    if table.has("file"):
        path = table.path("file")
        fmt = table.string("format", "grlweap-model-json", choices=("grlweap-model-json",))
        if not path.exists():
            raise table.error("file", f"{path} not found (the GRLWEAP benchmark input lies in "
                                      "../shared/reference/grlweap-s4000/ beside the "
                                      "repository; it is never copied into it)")
        tips, tables = read_grlweap_tip_tables(path, pile_soil, table.source, fmt)
    else:
        tips, tables = [], []
        for t in table.tables("tables"):
            tips.append(t.number("tip_depth", ge=0.0, unit="m"))
            tables.append(t.array("rows", columns=3))
            t.finish()
    try:
        return TipDepthTables(np.array(tips), tuple(tables))
    except ValueError as exc:
        raise table.error("tables", str(exc)) from None


def read_grlweap_tip_tables(path: Path, pile_soil, source: str, fmt: str):
    """The SRD tables by tip depth of a GRLWEAP input decoded to JSON (``soil_model.
    srd_tables_by_run``: rows soil depth [m], unit shaft [kPa], toe resistance [kN]).

    The toe force is turned into a unit resistance on the pile's toe annulus, so the
    distribution gives it back on the same area.
    """
    try:
        data = json.loads(Path(path).read_text())
        runs = data["soil_model"]["srd_tables_by_run"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError(path, "soil_model.srd_tables_by_run", f"cannot be read ({exc})") \
            from None
    seg = pile_soil.pile.discretise()
    d, t = float(seg.outer_diameter[-1]), float(seg.wall_thickness[-1])
    area = math.pi * (d - t) * t
    items = []
    for key, run in runs.items():
        try:
            tip = float(run["tip_depth_the_table_was_built_for [m]"])
            cols = run["columns"]
            rows = np.array(run["rows"], dtype=float)
            iz, ish, ito = (cols.index(c) for c in ("soil_depth [m]",
                                                     "unit_shaft_resistance [kPa]",
                                                     "toe_resistance [kN]"))
        except (KeyError, ValueError, TypeError) as exc:
            raise InputError(path, f"soil_model.srd_tables_by_run.{key}",
                             f"is not a GRLWEAP table ({exc})") from None
        table = np.column_stack([rows[:, iz], 1e3 * rows[:, ish], 1e3 * rows[:, ito] / area])
        items.append((tip, table))
    items.sort(key=lambda x: x[0])
    return [x[0] for x in items], [x[1] for x in items]


def bearing_graph(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float,
                  multipliers=(0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0)) -> list[dict]:
    """Blow count against the ultimate resistance Rut at one tip depth (for back-analysis):
    the SRD distribution of ``depth`` [m] scaled by each multiplier [-]; rows as
    :func:`analyse_depth`'s."""
    rows = []
    for m in multipliers:
        s = replace(settings, multipliers={**settings.multipliers, settings.bound: float(m)})
        rows.append(analyse_depth(engine, cfg, srd, s, depth).row)
    return rows


def time_series(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float):
    """The last blow at a tip depth with its time series (``.columns`` as impact.csv); None
    where the pile runs under its own weight (no blow)."""
    return analyse_depth(engine, cfg, srd, settings, depth, record=True).blow
