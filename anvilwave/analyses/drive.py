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

Self-weight penetration and pile runs: a weight rests on the soil (``weight_on_soil``):
``"all"`` (default) the pile, the ram, the helmet (or anvil) and the hammer assembly;
``"grlweap"`` the pile, the helmet (or anvil) and the assembly, without the ram: GRLWEAP's
"Total Wt", the weight it compares with the total resistance Rut ("Hammer+Pile Weight > Rult:
Pile Runs", blow count 0; the benchmark's listing: 9158.8 kN = pile 3172.3 + helmet 2575.1 +
assembly 3411.4 kN). The pile penetrates under its own weight to the first depth where the SRD
(its static resistance at that tip depth) exceeds the weight; deeper, a depth where the SRD
falls below the weight again (a soft layer) is a pile run. Where the pile does not run, the
blow starts either way from the static equilibrium of the pile under its own weight and the
helmet's (or anvil's) and assembly's on its head; the ram falls freely and its weight acts on
it during the blow, as in GRLWEAP (its static analysis before the blow loads the soil with the
pile's and the hammer assembly's weight; the ram is in flight).

Restrike (``anvilwave drive --restrike HOURS``): at every depth a second blow estimates the
restrike after a pause of that duration: the shaft resistance of the embedded segments times
the set-up factor of Skov & Denver (1988) for each segment's soil type (the SRD's layers, or
``[installation] setup_soil``; :mod:`anvilwave.pile.soil.setup`), nothing remoulded yet, from
the static equilibrium on that soil; columns ``restrike_blow_count [1/m]`` and
``restrike_setup_factor [-]`` (the largest over the segments).

Blow window (``window``): ``"fixed"`` (default) simulates the whole ``duration``;
``"toe-rebound"`` ends the blow when the toe, having moved down, first moves up (the first
maximum of the toe displacement), at most ``duration``: the end of the analysis of Smith's
method, whose set (the maximum toe displacement minus the toe quake, ``set_rule =
"grlweap"``) assumes the pile rebounds from that instant (Smith 1960, J. Soil Mech. Found.
Div. 86(4), 35-61). Stresses and energies are then the extremes up to that instant: a tension
reflected after the toe's rebound (a high toe resistance) is not seen. The blow is simulated
twice (once recorded to find the instant). GRLWEAP's own default analysis time is not stated
in its input echo; this option follows the rule its set implies and is not fitted to its
results.
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

from anvilwave.analyses.impact import energy_balance, pda_summary
from anvilwave.config.drive import (
    DriveSettings,
    SrdSource,
    impact_at,
    load_srd_source,
    pile_soil_at,
)
from anvilwave.config.install import InstallSettings, segment_soil_types, setup_pile_soil
from anvilwave.config.system import depth_limit
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.impact import equivalent_stroke
from anvilwave.inputs import InputError
from anvilwave.output.plots import plot_driveability
from anvilwave.output.progress import CtrlC, Step
from anvilwave.output.progress import bar as progress_bar
from anvilwave.output.tables import write_csv
from anvilwave.pile.soil.models import toe_quake

MIN_SET = 1e-7
"""Sets below this [m] count as zero (blow count infinite: refusal)."""

COLUMNS = ("depth [m]", "srd [N]", "srd_shaft [N]", "srd_toe [N]", "blow_count [1/m]",
           "blows_per_0.25m [-]", "set [m]", "energy_setting [J]", "enthru [J]",
           "max_compression_stress [Pa]", "max_tension_stress [Pa]",
           "max_pile_head_force [N]", "emx_gauge [J]", "emx_head [J]",
           "permanent_set [m]", "grlweap_set [m]", "impact_velocity [m/s]",
           "energy_residual_relative [-]", "toe_velocity_end [m/s]", "FMX [N]", "RMX [N]",
           "case_damping [-]", "restrike_blow_count [1/m]", "restrike_setup_factor [-]",
           "stroke [m]")
"""Columns of ``driveability.csv`` (the DESIGN.md contract first, then extra columns)."""


# ----------------------------------------------------------------------------- settings


# ----------------------------------------------------------------------------- SRD


# ----------------------------------------------------------------------------- results
@dataclass
class DriveResult:
    """A driveability analysis of one anvil model (``anvilwave drive``).

    Parameters
    ----------
    model : str
        The anvil model analysed (``"rom"``, ``"lumped"``, ``"classic"`` or ``"none"``).
    source : str
        The system file.
    rows : list of dict
        One row per tip depth, keyed by :data:`COLUMNS` (the columns of ``driveability.csv``;
        names carry their SI unit in brackets, e.g. ``"blow_count [1/m]"``).
    summary : dict
        The entries of ``summary.json``: ``"refusal_depth [m]"`` (None: no refusal),
        ``"total_blows [-]"``, ``"driving_time [s]"``, ``"self_weight_penetration [m]"``,
        ``"pile_run_depths [m]"``, ``"max_compression_stress [Pa]"``,
        ``"max_tension_stress [Pa]"`` (negative), the settings used and ``"wall_time [s]"``.
    time_series : dict, optional
        ``{tip depth [m]: columns of the blow (as impact.csv), or None where the pile runs
        under its own weight}`` for the ``time_series_depths`` of the settings.
    """

    model: str
    source: str
    rows: list[dict]
    summary: dict
    time_series: dict = field(default_factory=dict)

    def columns(self) -> dict[str, np.ndarray]:
        """The rows as columns (the columns of driveability.csv).

        Returns
        -------
        dict
            ``{name [unit]: numpy.ndarray}``, one entry per column of :data:`COLUMNS`.
        """
        return {name: np.array([r.get(name, math.nan) for r in self.rows], dtype=float)
                for name in COLUMNS}

    def write(self, out, title: str = "", prefix: str = "") -> None:
        """Write the results into a ResultWriter.

        Writes ``driveability.csv``, ``summary.json``, ``driveability.png`` and a
        ``blow_<depth>m.csv`` per time series.

        Parameters
        ----------
        out : ResultWriter
            The writer (:mod:`anvilwave.output.writer`).
        title : str, default ""
            Title of the plot.
        prefix : str, default ""
            Folder inside ``out`` the files go under.
        """
        columns = self.columns()
        write_csv(columns, out.part(prefix + "driveability.csv"))
        summary = dict(self.summary)
        summary["system"] = Path(self.source).name
        out.part(prefix + "summary.json").write_text(json.dumps(jsonable(summary), indent=2)
                                                     + "\n")
        plot_driveability(columns, summary, out.part(prefix + "driveability.png"), title=title)
        for depth, blow in self.time_series.items():
            if blow is not None:
                write_csv(blow, out.part(f"{prefix}blow_{float(depth):g}m.csv"))


# ----------------------------------------------------------------------------- analysis
@dataclass
class DepthResult:
    """One analysed depth (the columns of :data:`COLUMNS`) and its last blow.

    Parameters
    ----------
    row : dict
        The row of the depth, keyed by :data:`COLUMNS`.
    blow : BlowResult or None, default None
        Its last blow (None where the pile runs under its own weight).
    """

    row: dict
    blow: object = None


TOE_MOVING = 1e-6
"""Toe displacement [m] from which the toe counts as moving down (window "toe-rebound")."""


def toe_rebound_time(blow) -> float:
    """The instant the toe first moves up after moving down [s].

    Its first maximum of displacement, the end of a "toe-rebound" window: the first recorded
    sample after the toe has moved :data:`TOE_MOVING` down whose successor is not lower; the
    blow's end if the toe never turns.

    Parameters
    ----------
    blow : BlowResult
        A recorded blow (columns ``time [s]`` and ``pile_toe_displacement [m]``).

    Returns
    -------
    float
        The blow window ending at the toe's first rebound [s] (at least one time step).
    """
    t = np.asarray(blow.columns["time [s]"], dtype=float)
    u = np.asarray(blow.columns["pile_toe_displacement [m]"], dtype=float)
    u = u - u[0]
    moving = np.flatnonzero(u > TOE_MOVING)
    if moving.size == 0:
        return float(t[-1])
    k0 = int(moving[0])
    turns = np.flatnonzero(np.diff(u[k0:]) <= 0.0)
    if turns.size == 0:
        return float(t[-1])
    return max(float(t[k0 + int(turns[0])]), float(blow.time_step))


def set_of_blow(blow, rule: str, toe_quake: float) -> float:
    """The blow's set [m] by the rule (module docstring).

    Parameters
    ----------
    blow : BlowResult
        A simulated blow.
    rule : {"permanent", "grlweap"}
        ``"permanent"``: the permanent set; ``"grlweap"``: the maximum toe displacement minus the
        toe quake.
    toe_quake : float
        Toe quake [m] (rule ``"grlweap"``).

    Returns
    -------
    float
        The set, not negative [m].
    """
    if rule == "grlweap":
        return max(float(blow.max_toe_displacement) - toe_quake, 0.0)
    return max(float(blow.permanent_set), 0.0)


def blow_count(set_m: float) -> float:
    """Blows per metre from the set (infinite below :data:`MIN_SET`).

    Parameters
    ----------
    set_m : float
        The set of a blow [m].

    Returns
    -------
    float
        Blow count [1/m].
    """
    return 1.0 / set_m if set_m > MIN_SET else math.inf


def analyse_depth(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float,
                  record: bool = False, restrike: tuple | None = None) -> DepthResult:
    """Simulate the blows of one tip depth and summarise them (one CSV row).

    Parameters
    ----------
    engine : Engine
        A built :class:`~anvilwave.engine.direct.Engine` for ``cfg``.
    cfg : SystemConfig
        The system (its hammer, anvil, pile and soil model).
    srd : SrdSource
        The SRD of the tip depths (:func:`~anvilwave.config.drive.load_srd_source`).
    settings : DriveSettings
        The driveability settings (``[driveability]``).
    depth : float
        Tip depth below the mudline [m].
    record : bool, default False
        Record the time series of the blows.
    restrike : tuple or None, default None
        (InstallSettings, pause [s]): adds the restrike blow count (module docstring).

    Returns
    -------
    DepthResult
        The row of the depth and its last blow.
    """
    ps, shaft, toe = pile_soil_at(cfg.pile_soil, srd, depth, settings.multiplier)
    energy, velocity = impact_at(settings, depth, cfg)
    weight = driving_weight(cfg, engine.static_head_force, settings.weight_on_soil)
    if shaft + toe <= weight:  # the pile runs (or stands) under its own weight: no blows
        return DepthResult(_run_row(depth, shaft, toe, energy, velocity, _stroke(cfg, energy)))
    eng = engine.with_pile_soil(ps)
    try:
        state = eng.static_state()
    except ValueError:  # no static equilibrium: the SRD does not carry the weight
        return DepthResult(_run_row(depth, shaft, toe, energy, velocity, _stroke(cfg, energy)))
    blow = None
    for k in range(settings.blows_per_depth):
        last = k == settings.blows_per_depth - 1
        # the last blow records its gauge signals (for the Case method; 2-7 % of its cost)
        blow = _window_blow(eng, state, velocity, settings, record or last, record)
        state = blow.final_state
    quake_toe = toe_quake(ps.soil, ps.pile)
    permanent = set_of_blow(blow, "permanent", quake_toe)
    grl = set_of_blow(blow, "grlweap", quake_toe)
    set_m = set_of_blow(blow, settings.set_rule, quake_toe)
    count = blow_count(set_m)
    enthru = blow.emx_gauge if settings.enthru_location == "gauge" else blow.emx_head
    residual = float("nan")
    if record and getattr(blow, "energies", None):

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
        "restrike_blow_count [1/m]": float("nan"), "restrike_setup_factor [-]": float("nan"),
        "stroke [m]": _stroke(cfg, energy),
    }
    row.update(_case_method(blow, replace(cfg, pile_soil=ps)))
    if restrike is not None:
        row.update(_restrike(engine, srd, settings, ps, depth, velocity, restrike))
    return DepthResult(row, blow if record else None)


def _window_blow(eng, state, velocity, settings: DriveSettings, record: bool, energy: bool):
    """One blow in the settings' window: the whole duration, or up to the toe's first
    rebound (found by a first, recorded blow)."""
    duration = settings.duration
    if settings.window == "toe-rebound":
        duration = toe_rebound_time(eng.blow(state=state, impact_velocity=velocity,
                                             duration=duration, record=True, energy=False))
    return eng.blow(state=state, impact_velocity=velocity, duration=duration, record=record,
                    energy=energy)


def _restrike(engine, srd, settings, ps, depth, velocity, restrike) -> dict:
    """The restrike blow count [1/m] and largest shaft set-up factor [-] after the pause of
    ``restrike`` = (InstallSettings, pause [s]) at the tip depth ``depth`` [m]."""
    install, duration = restrike
    set_up, _, factor = setup_pile_soil(ps, srd, depth, install, duration, depth, 0.0)
    eng = engine.with_pile_soil(set_up)
    blow = _window_blow(eng, eng.static_state(), velocity, settings, False, False)
    set_m = set_of_blow(blow, settings.set_rule, toe_quake(set_up.soil, set_up.pile))
    return {"restrike_blow_count [1/m]": blow_count(set_m),
            "restrike_setup_factor [-]": factor}


def _case_method(blow, cfg) -> dict:
    """FMX, RMX (and the Jc used) of the blow's gauge signals by the Case method."""

    try:
        p = pda_summary(blow.columns, cfg)
    except (ValueError, KeyError):
        return {}
    return {"FMX [N]": p["FMX [N]"], "RMX [N]": float("nan") if p["RMX [N]"] is None
            else float(p["RMX [N]"]), "case_damping [-]": p["case_damping [-]"]}


def _run_row(depth, shaft, toe, energy, velocity, stroke) -> dict:
    """The row of a depth where the SRD does not carry the driving weight: no blow needed
    (blow count 0, as GRLWEAP lists a pile run; the stresses and energies of a blow are not
    computed). The plots leave these depths out of the blow-count curve."""
    row = {name: float("nan") for name in COLUMNS}
    row.update({"depth [m]": float(depth), "srd [N]": shaft + toe, "srd_shaft [N]": shaft,
                "srd_toe [N]": toe, "blow_count [1/m]": 0.0, "blows_per_0.25m [-]": 0.0,
                "energy_setting [J]": energy, "impact_velocity [m/s]": float(velocity),
                "stroke [m]": stroke})
    return row


def _stroke(cfg, energy: float) -> float:
    """The equivalent stroke [m] of a blow energy ``energy`` [J]: E / (m g) of the ram (NaN
    without gravity)."""
    mass = float(np.sum(cfg.hammer.ram.mass))
    if not mass * cfg.gravity > 0.0:
        return float("nan")
    return equivalent_stroke(energy, mass, cfg.gravity)


# worker state for the process pool (inherited by fork: the engine is built once)
_WORK: dict = {}


def _work(depths: list[float]) -> list[dict]:
    w = _WORK
    return [analyse_depth(w["engine"], w["cfg"], w["srd"], w["settings"], depth,
                          restrike=w["restrike"]).row for depth in depths]


def run_driveability(cfg, srd: SrdSource, settings: DriveSettings, engine=None, *,
                     workers: int | None = None, progress: bool = False,
                     restrike: tuple | None = None) -> DriveResult:
    """Analyse every depth of ``settings`` (no time series).

    Parameters
    ----------
    cfg : SystemConfig
        The system (its hammer, anvil, pile and soil model).
    srd : SrdSource
        The SRD of the tip depths (:func:`~anvilwave.config.drive.load_srd_source`).
    settings : DriveSettings
        The driveability settings (``[driveability]``).
    engine : Engine, optional
        A built :class:`~anvilwave.engine.direct.Engine` for ``cfg`` (default: built here).
    workers : int or None, default None
        Processes over the depths (default: the machine's cores; 1 runs in-process).
    progress : bool, default False
        A progress bar over the depths.
    restrike : tuple or None, default None
        (InstallSettings, pause [s]) for the restrike columns (module docstring).

    Returns
    -------
    DriveResult
        The rows and the summary.
    """

    start = time.perf_counter()
    if engine is None:
        engine = build_engine(cfg)
    depths = [float(d) for d in settings.depths if d <= cfg.pile_soil.pile.length]
    workers = workers or os.cpu_count() or 1
    workers = max(1, min(workers, len(depths)))
    rows: list[dict] = []
    bar = None
    if depths:
        # the first depth in-process, before the bar (and the workers, which then inherit
        # its compiled kernels): on a first run it compiles this anvil model's kernels
        with Step(f"{cfg.anvil.model} anvil: first depth {depths[0]:g} m (compiling its "
                  "kernels on a first run, about 30 s)...", enabled=progress):
            rows.append(analyse_depth(engine, cfg, srd, settings, depths[0],
                                      restrike=restrike).row)
        rest = depths[1:]
        bar = progress_bar(len(depths), enabled=progress, warm=0, initial=1,
                           desc=f"{cfg.anvil.model} anvil: depths", unit="depth")
        workers = max(1, min(workers, len(rest)))
    else:
        rest = []
    try:
        if workers == 1:
            for d in rest:
                rows.append(analyse_depth(engine, cfg, srd, settings, d,
                                          restrike=restrike).row)
                if bar is not None:
                    bar.update(1)
        elif rest:
            import multiprocessing as mp
            from concurrent.futures import ProcessPoolExecutor

            _WORK.update(engine=engine, cfg=cfg, srd=srd, settings=settings,
                         restrike=restrike)
            try:
                size = max(1, len(rest) // (4 * workers))
                chunks = [rest[i:i + size] for i in range(0, len(rest), size)]
                with CtrlC() as ctrl_c, ProcessPoolExecutor(
                        workers, mp_context=mp.get_context("fork"), initializer=die_with_parent,
                        initargs=(os.getpid(),)) as pool:
                    # futures of their own, not pool.map: on a Ctrl-C, map cancels the
                    # pending ones while the pool's thread fails them for its dead workers,
                    # and concurrent.futures then raises InvalidStateError from that thread
                    futures = [pool.submit(_work, chunk) for chunk in chunks]
                    try:
                        for future, chunk in zip(futures, chunks, strict=True):
                            rows.extend(future.result())
                            if bar is not None:
                                bar.update(len(chunk))
                    except KeyboardInterrupt:
                        # the workers end on the Ctrl-C too (die_with_parent); killed here in
                        # case it reached this process only, so the pending depths fail with
                        # the broken pool and the pool closes at once
                        for process in list(getattr(pool, "_processes", {}).values()):
                            process.kill()
                        raise
                    except BaseException:  # an error: the depths not started never start
                        pool.shutdown(wait=False, cancel_futures=True)
                        # the workers the Ctrl-C ended may break the pool before this
                        # process sees the interrupt: then it is the interrupt, not an error
                        ctrl_c.check()
                        raise
            finally:
                _WORK.clear()
    finally:
        if bar is not None:
            bar.close()
    summary = summarise(rows, cfg, settings, engine.static_head_force)
    summary["wall_time [s]"] = time.perf_counter() - start
    summary["depths_analysed [-]"] = len(rows)
    summary["workers [-]"] = workers
    if restrike is not None:
        summary["restrike_pause [h]"] = restrike[1] / 3600.0
    return DriveResult(model=cfg.anvil.model, source=str(cfg.source), rows=rows,
                       summary=summary)


def die_with_parent(parent: int) -> None:
    """Worker initializer: the worker is killed when its parent dies, even by SIGKILL.

    On Linux by ``prctl(PR_SET_PDEATHSIG, SIGKILL)``; elsewhere a daemon thread polls the
    parent's pid, so no orphan keeps running. A Ctrl-C (SIGINT to the process group) ends a
    worker quietly, so the parent prints one line, not a traceback per worker.

    Parameters
    ----------
    parent : int
        Process id of the parent.
    """
    import signal
    import threading

    signal.signal(signal.SIGINT, lambda *_: os._exit(130))  # quietly, no traceback
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        if libc.prctl(1, signal.SIGKILL, 0, 0, 0) == 0:  # PR_SET_PDEATHSIG = 1
            if os.getppid() != parent:  # the parent died before the call
                os._exit(1)
            return
    except (OSError, AttributeError):
        pass

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, daemon=True).start()


def driving_weight(cfg, head_load: float, rule: str = "all") -> float:
    """Weight resting on the soil before driving [N].

    The pile's, plus ``head_load``, the anvil's (or the helmet's and hammer assembly's) weight on
    the pile head, plus the ram's with ``rule = "all"`` (not with ``"grlweap"``: module
    docstring).

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    head_load : float
        Static load on the pile head [N].
    rule : {"all", "grlweap"}
        Whether the ram's weight is included.

    Returns
    -------
    float
        The weight on the soil [N].
    """
    seg = cfg.pile_soil.pile.discretise()
    pile = float(np.sum(seg.area * seg.length * seg.density))
    ram = float(np.sum(cfg.hammer.ram.mass)) if rule == "all" else 0.0
    return (pile + ram) * cfg.gravity + float(head_load)


def summarise(rows: list[dict], cfg, settings: DriveSettings, head_load: float) -> dict:
    """Refusal depth, total blows, driving time, self-weight penetration and pile runs.

    Parameters
    ----------
    rows : list of dict
        The rows of the depths (:data:`COLUMNS`).
    cfg : SystemConfig
        The system (its hammer, anvil, pile and soil model).
    settings : DriveSettings
        The driveability settings (``[driveability]``).
    head_load : float
        Static load on the pile head [N].

    Returns
    -------
    dict
        The entries of ``summary.json`` (:class:`DriveResult`).
    """
    depth = np.array([r["depth [m]"] for r in rows])
    count = np.array([r["blow_count [1/m]"] for r in rows])
    srd = np.array([r["srd [N]"] for r in rows])
    refused = np.flatnonzero(0.25 * count > settings.refusal)
    refusal_depth = float(depth[refused[0]]) if refused.size else None
    weight = driving_weight(cfg, head_load, settings.weight_on_soil)
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
    blows = int(round(total))  # a count of blows (the integral is not more precise than 1)
    pile = cfg.pile_soil.pile
    return {
        "refusal_depth [m]": refusal_depth,
        "total_blows [-]": blows,
        "driving_time [s]": blows / settings.blow_rate * 60.0,
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
        "yield_strength [Pa]": float(pile.yield_strength),
        "allowable_driving_stress [Pa]": float(pile.allowable_driving_stress),
        "blow_rate [blows/min]": settings.blow_rate,
        "blows_per_depth [-]": settings.blows_per_depth,
        "weight_on_soil": settings.weight_on_soil,
        "window": settings.window,
        "anvil_model": cfg.anvil.model,
    }


def jsonable(x):
    """``x`` with numpy scalars as Python numbers and non-finite floats as None (JSON).

    Parameters
    ----------
    x : object
        A value, dict, list or tuple (converted recursively).

    Returns
    -------
    object
        The converted value.
    """
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [jsonable(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, np.floating | np.integer):
        return jsonable(x.item())
    return x


def bearing_graph(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float,
                  multipliers=(0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0)) -> list[dict]:
    """Blow count against the ultimate resistance Rut at one tip depth (for back-analysis).

    The SRD distribution of ``depth`` scaled by each multiplier.

    Parameters
    ----------
    engine : Engine
        A built :class:`~anvilwave.engine.direct.Engine` for ``cfg``.
    cfg : SystemConfig
        The system (its hammer, anvil, pile and soil model).
    srd : SrdSource
        The SRD of the tip depths (:func:`~anvilwave.config.drive.load_srd_source`).
    settings : DriveSettings
        The driveability settings (``[driveability]``).
    depth : float
        Tip depth below the mudline [m].
    multipliers : sequence of float, default (0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0)
        Factors on the SRD [-].

    Returns
    -------
    list of dict
        One row per multiplier, as :func:`analyse_depth`'s.
    """
    rows = []
    for m in multipliers:
        s = replace(settings, multipliers={**settings.multipliers, settings.bound: float(m)})
        rows.append(analyse_depth(engine, cfg, srd, s, depth).row)
    return rows


def time_series(engine, cfg, srd: SrdSource, settings: DriveSettings, depth: float):
    """The last blow at a tip depth with its time series (``.columns`` as impact.csv).

    Parameters
    ----------
    engine : Engine
        A built :class:`~anvilwave.engine.direct.Engine` for ``cfg``.
    cfg : SystemConfig
        The system (its hammer, anvil, pile and soil model).
    srd : SrdSource
        The SRD of the tip depths (:func:`~anvilwave.config.drive.load_srd_source`).
    settings : DriveSettings
        The driveability settings (``[driveability]``).
    depth : float
        Tip depth below the mudline [m].

    Returns
    -------
    BlowResult or None
        The recorded blow; None where the pile runs under its own weight (no blow).
    """
    return analyse_depth(engine, cfg, srd, settings, depth, record=True).blow


# ----------------------------------------------------------------------------- entry points
def drive(cfg, *, anvil: str | None = None, bound: str | None = None,
          workers: int | None = None, progress: bool = False,
          restrike: float | None = None) -> DriveResult:
    """The driveability of a system: blow count, stresses and ENTHRU against the tip depth.

    Parameters
    ----------
    cfg : SystemConfig
        A system with a ``[driveability]`` table (its ``[srd]``, or the ``[soil] srd`` rows).
    anvil : str, optional
        Analyse with this anvil model instead of the system's (``"rom"``, ``"lumped"``,
        ``"classic"``, ``"none"``).
    bound : str, optional
        SRD bound ``"lower"``, ``"best"`` or ``"upper"`` instead of the table's.
    workers : int, optional
        Processes over the depths (default: the machine's cores; 1 runs in-process).
    progress : bool
        A progress bar over the depths.
    restrike : float, optional
        A pause [h]: add the restrike blow count after it at every depth (module docstring;
        the set-up settings of ``[installation]``).

    Returns
    -------
    DriveResult
        The rows, the summary and the blows of the ``time_series_depths``.
    """
    settings = _settings(cfg, bound)
    run_cfg = cfg.with_anvil_model(anvil) if anvil is not None else cfg
    srd = _srd(cfg)
    model = run_cfg.anvil.model
    with Step(f"{model} anvil: building the engine (the modes of the anvil and the ram)...",
              enabled=progress):
        engine = build_engine(run_cfg)
    result = run_driveability(run_cfg, srd, settings, engine, workers=workers,
                              progress=progress, restrike=_restrike_settings(cfg, srd,
                                                                             restrike))
    for depth in settings.time_series_depths:
        with Step(f"{model} anvil: recording the blow at {float(depth):g} m (compiling the "
                  "recording kernel on a first run, about 15 s)...", enabled=progress):
            blow = time_series(engine, run_cfg, srd, settings, float(depth))
        result.time_series[float(depth)] = None if blow is None else blow.columns
    return result


def available_anvil_models(cfg) -> list[str]:
    """The anvil models a system can be driven with.

    Its own, the ROM and the lumped anvil where it has an anvil file, the classic driving system
    where it has one.

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    list of str
        The anvil model names.
    """
    return [m for m in ("rom", "lumped", "classic")
            if m == cfg.anvil.model or (m in ("rom", "lumped") and cfg.anvil.spec)
            or (m == "classic" and cfg.anvil.classic is not None)]


def compare_anvils(cfg, *, bound: str | None = None, workers: int | None = None,
                   progress: bool = False) -> dict[str, DriveResult]:
    """:func:`drive` with every anvil model of :func:`available_anvil_models`.

    Parameters
    ----------
    cfg : SystemConfig
        A system with a ``[driveability]`` table.
    bound : str, optional
        SRD bound ``"lower"``, ``"best"`` or ``"upper"`` instead of the table's.
    workers : int, optional
        Processes over the depths (default: the machine's cores; 1 runs in-process).
    progress : bool, default False
        A progress bar over the depths.

    Returns
    -------
    dict
        ``{model: DriveResult}`` in the order rom, lumped, classic.
    """
    models = available_anvil_models(cfg)
    return {m: drive(cfg, anvil=m, bound=bound, workers=workers, progress=progress)
            for m in models}


def write_anvil_comparison(results: dict[str, DriveResult], out, title: str = "") -> None:
    """Write every model's results and their comparison.

    The first model's results at the top, the others in ``<model>/``, the driveability curves of
    all models in one figure and ``anvil_comparison.json``.

    Parameters
    ----------
    results : dict
        ``{model: DriveResult}`` (:func:`compare_anvils`).
    out : ResultWriter
        The writer (:mod:`anvilwave.output.writer`).
    title : str, default ""
        Title of the plots.
    """
    for k, (model, result) in enumerate(results.items()):
        result.write(out, title=f"{title}: {model} anvil, {result.summary['bound']} SRD",
                     prefix="" if k == 0 else f"{model}/")
    if len(results) > 1:
        cols = {m: r.columns() for m, r in results.items()}
        first = next(iter(results))
        plot_driveability(cols[first], results[first].summary,
                          out.part("driveability_anvils.png"), title=f"{title}: anvil models",
                          others={m: c for m, c in cols.items() if m != first})
        comparison = {m: r.summary for m, r in results.items()}
        out.part("anvil_comparison.json").write_text(json.dumps(jsonable(comparison),
                                                                indent=2) + "\n")


def drive_bearing_graph(cfg, depth: float, *, anvil: str | None = None,
                        bound: str | None = None) -> DriveResult:
    """Blow count against the ultimate resistance at one tip depth (:func:`bearing_graph`).

    Parameters
    ----------
    cfg : SystemConfig
        A system with a ``[driveability]`` table.
    depth : float
        Tip depth below the mudline [m].
    anvil : str, optional
        Analyse with this anvil model instead of the system's.
    bound : str, optional
        SRD bound ``"lower"``, ``"best"`` or ``"upper"`` instead of the table's.

    Returns
    -------
    DriveResult
        A result whose rows are the multipliers'.

    Raises
    ------
    InputError
        If ``depth`` is not above 0 m and within the SRD.
    """
    settings = _settings(cfg, bound)
    limit, what = depth_limit(cfg.pile_soil, _srd(cfg))
    if not (0.0 < depth <= limit + 1e-9):
        raise InputError("--bearing-graph", "", f"tip depth {depth:g} m must be above 0 m and "
                                                f"within {what}, {limit:g} m")
    run_cfg = cfg.with_anvil_model(anvil) if anvil is not None else cfg
    rows = bearing_graph(build_engine(run_cfg), run_cfg, _srd(cfg), settings, depth)
    return DriveResult(model=run_cfg.anvil.model, source=str(cfg.source), rows=rows,
                       summary={"bearing_graph_depth [m]": float(depth)})


def _settings(cfg, bound: str | None) -> DriveSettings:
    if cfg.drive is None:
        raise InputError(str(cfg.source), "driveability", "the drive analysis needs a "
                                                          "[driveability] table")
    return cfg.drive if bound is None else replace(cfg.drive, bound=bound)


def _restrike_settings(cfg, srd, hours: float | None):
    """(InstallSettings, pause [s]) of a restrike of ``hours`` [h], or None."""
    if hours is None:
        return None
    if not (math.isfinite(hours) and 0.0 < hours <= 8760.0):
        raise InputError(str(cfg.source), "restrike", f"the pause must be in (0, 8760] h, got "
                                                      f"{hours!r}")
    install = cfg.install if cfg.install is not None else InstallSettings()
    if install.setup_soil is None and install.setup_a is None \
            and segment_soil_types(srd, np.array([0.0])) is None:
        raise InputError(str(cfg.source), "installation.setup_soil",
                         "the restrike's set-up needs the soil type ('sand' or 'clay') where "
                         "the SRD has no soil layers")
    return install, 3600.0 * float(hours)


def _srd(cfg) -> SrdSource:
    return cfg.srd if cfg.srd is not None else load_srd_source(None, cfg.source, cfg.pile_soil)
