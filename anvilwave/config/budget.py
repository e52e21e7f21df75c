"""Refuse a run too big for the machine before any work starts.

A case's cost is estimated from its file alone (no modes, no engine): the pile's segment
updates (every segment at its own Courant step, the least the pile unit does), the master
steps where a time step is given, and the memory of the recorded time series of every blow.
A case above a limit stops with one clear message naming the key to change, its estimated size
and the limit (exit status 2 on the command line), in milliseconds.
"""

from __future__ import annotations

from anvilwave.inputs import InputError

MAX_MEMORY = 8 * 2**30
"""Recorded results one run may hold [bytes] (a third of this 24 GiB machine)."""
MAX_WALL_TIME = 24 * 3600.0
"""Estimated wall time one run may take [s]."""
SECONDS_PER_SEGMENT_UPDATE = 2e-9
"""Wall time of one pile segment update [s] (measured order, benchmarks/bench_engine.py)."""
SECONDS_PER_MASTER_STEP = 5e-7
"""Wall time of one master step outside the pile (ram, anvil, contacts, recording) [s]."""
RECORDED_COLUMNS = 24
"""Time series recorded per sample (result columns and energy columns)."""


def run_estimate(config) -> dict[str, float]:
    """Estimated size of a system's run.

    Parameters
    ----------
    config : SystemConfig
        The system.

    Returns
    -------
    dict
        ``segments``, ``pile_step [s]``, ``steps`` (master steps of all blows, a lower bound
        when the step is automatic), ``segment_updates``, ``memory [B]`` of the recorded series,
        ``wall_time [s]``.
    """
    pile = config.pile_soil.pile
    length = sum(s.length for s in pile.sections)
    segments = sum(max(1, -(-s.length // pile.segment_length)) for s in pile.sections)
    c = max(s.wave_speed for s in pile.sections)
    pile_step = min(pile.segment_length, length) / c
    per_blow_pile_steps = config.duration / pile_step
    master_step = config.time_step if config.time_step is not None else pile_step
    steps = config.blows * config.duration / master_step
    sample = config.output_interval if config.output_interval is not None else master_step
    rows = config.blows * (config.duration / max(sample, master_step) + 1)
    updates = config.blows * per_blow_pile_steps * segments
    return {
        "segments": float(segments),
        "pile_step [s]": pile_step,
        "steps": steps,
        "segment_updates": updates,
        "memory [B]": rows * RECORDED_COLUMNS * 8.0,
        "wall_time [s]": updates * SECONDS_PER_SEGMENT_UPDATE + steps * SECONDS_PER_MASTER_STEP,
    }


def check_run_budget(config) -> dict[str, float]:
    """Check a system's run against :data:`MAX_MEMORY` and :data:`MAX_WALL_TIME`.

    Parameters
    ----------
    config : SystemConfig
        The system.

    Returns
    -------
    dict
        The estimate (:func:`run_estimate`).

    Raises
    ------
    InputError
        Naming the key to change, if the run exceeds a limit.
    """
    est = run_estimate(config)
    too_big = est["memory [B]"] > MAX_MEMORY or est["wall_time [s]"] > MAX_WALL_TIME
    if not too_big:
        return est
    if config.blows > 1:
        key = "simulation.blows"
    elif config.time_step is not None and config.time_step < est["pile_step [s]"] / 100:
        key = "simulation.time_step"
    elif config.output_interval is None and est["memory [B]"] > MAX_MEMORY:
        key = "simulation.output_interval"
    else:
        key = "simulation.duration"
    raise InputError(
        config.source, key,
        f"the run is too big for this machine: about {est['steps']:.3g} steps, "
        f"{est['segment_updates']:.3g} pile segment updates ({est['segments']:.0f} segments), "
        f"{est['memory [B]'] / 2**30:.3g} GiB of results and {_duration(est['wall_time [s]'])} "
        f"(limits {MAX_MEMORY / 2**30:.0f} GiB, {_duration(MAX_WALL_TIME)})")


MAX_MATCH_TIME = 3600.0
"""Estimated wall time one signal match may take [s]."""
SECONDS_PER_MATCH_UPDATE = 2e-8
"""Wall time of one segment update of the matching model (soil included) [s]."""
MATCH_ITERATIONS = 30
"""Trust-region iterations the estimate assumes (each a Jacobian by forward differences)."""


def match_estimate(zones: int, segments: int, samples: int, max_evaluations: int,
                   extra_parameters: int = 4) -> dict[str, float]:
    """Estimated size of a signal match.

    Parameters
    ----------
    zones : int
        Shaft resistance zones of the match [-].
    segments : int
        Segments of the matching model's pile [-].
    samples : int
        Samples of the record, the steps of one forward run [-].
    max_evaluations : int
        Largest number of iteration steps [-].
    extra_parameters : int, default 4
        Quakes and dampings fitted besides the zones and the toe [-].

    Returns
    -------
    dict
        ``parameters`` (the zones, the toe and ``extra_parameters`` quakes and dampings),
        ``evaluations`` (forward runs: the iterations' Jacobians by forward differences and their
        steps, at most ``max_evaluations`` steps), ``run [s]`` (one forward run: ``segments`` x
        ``samples`` updates) and ``wall_time [s]``.
    """
    parameters = zones + 1 + extra_parameters
    iterations = min(MATCH_ITERATIONS, max_evaluations)
    evaluations = iterations * (parameters + 1)
    run = segments * samples * SECONDS_PER_MATCH_UPDATE
    return {"parameters": float(parameters), "evaluations": float(evaluations),
            "run [s]": run, "wall_time [s]": evaluations * run}


def check_match_budget(zones: int, segments: int, samples: int, max_evaluations: int,
                       extra_parameters: int = 4) -> dict[str, float]:
    """Refuse ``--zones`` before any work.

    Refused: fewer than one zone, more zones than the matching model's segments (``segments``),
    or an estimated wall time (:func:`match_estimate`) above :data:`MAX_MATCH_TIME`.

    Parameters
    ----------
    zones : int
        Shaft resistance zones of the match [-].
    segments : int
        Segments of the matching model's pile [-].
    samples : int
        Samples of the record, the steps of one forward run [-].
    max_evaluations : int
        Largest number of iteration steps [-].
    extra_parameters : int, default 4
        Quakes and dampings fitted besides the zones and the toe [-].

    Returns
    -------
    dict
        The estimate (:func:`match_estimate`).

    Raises
    ------
    InputError
        If ``--zones`` is refused.
    """
    if zones < 1:
        raise InputError("--zones", "", f"must be at least 1, got {zones}")
    if zones > segments:
        raise InputError("--zones", "", f"{zones} zones on a pile of {segments} segments "
                                        "below the gauges: at most one zone per segment")
    est = match_estimate(zones, segments, samples, max_evaluations, extra_parameters)
    if est["wall_time [s]"] > MAX_MATCH_TIME:
        raise InputError("--zones", "", f"{zones} zones need about {est['evaluations']:.3g} "
                                        f"forward runs of {est['run [s]']:.3g} s, "
                                        f"{_duration(est['wall_time [s]'])} (limit "
                                        f"{_duration(MAX_MATCH_TIME)}): use fewer zones")
    return est


def _duration(seconds: float) -> str:
    if seconds < 3600:
        return f"{seconds:.3g} s"
    if seconds < 86400 * 2:
        return f"{seconds / 3600:.3g} hours"
    return f"{seconds / 86400:.3g} days"
