"""Campaigns: the driveability of many foundation positions for every combination of SRD
bound, hammer, anvil model and energy schedule, run on dask.distributed.

A wind farm has 50-150 positions, each with its own CPT and pile; every position is run for
lower / best / upper SRD, two or three hammers and (with anvilwave) two anvil models. A case is
one driveability (:func:`anvilwave.analyses.drive.run_driveability`, its depths run serially in
one process); the parallelism is across cases, on a LocalCluster of worker processes (one
thread each) or on an existing dask scheduler (a cluster started by dask-jobqueue on Slurm or
PBS, see the README).

The campaign file (TOML; every key checked, units in brackets; paths relative to the file)::

    [campaign]
    name = "small"                    # optional (plot titles); default the file's stem
    system = "xl_campaign_base.toml"  # the base system file: a complete system file whose
                                      # [simulation], [hammer], [anvil], [soil] and
                                      # [driveability] settings every case shares

    [axes]                            # optional; an axis left out takes the base file's value
    bounds = ["lower", "best", "upper"]
    anvil_models = ["rom", "lumped"]  # "rom", "lumped", "classic", "none"

    [[axes.hammers]]                  # optional: default the base file's hammer
    name = "IL5500"                   # label: case names, campaign.csv, plots
    database = "illustrative_5500kj"  # a hammer of anvilwave/hammer/data, or file =
    "my_hammer.toml"
    energy = [[0.0, 2.0e6], [25.0, 5.5e6]]   # [m, J] optional energy schedule of this hammer
    ram_model = "modal"               # optional ("rod", "modal"; default the base file's)
    ram_mesh_size = 0.1               # [m] optional (modal ram)
    [axes.hammers.anvil]              # optional: keys replacing the base file's [anvil] ones
    file = "anvils/xl8.toml"          # (this hammer's anvil; the model is the anvil_models axis)

    [[axes.energy_schedules]]         # optional axis (then no hammer gives its own energy)
    name = "soft-start"
    fraction = [[0.0, 0.3], [20.0, 1.0]]     # [m, -] of each hammer's rated energy, or
                                             # energy = [[m, J], ...]

    [[positions]]                     # one or more
    name = "A01"
    water_depth = 28.0                # [m] (the CPT's sea-level reference; campaign.csv)
    target_penetration = 36.0         # [m] the last tip depth analysed
    [positions.pile]                  # replaces the base file's [pile] keys given here
    [[positions.pile.sections]]
    length = 80.0
    outer_diameter = 8.0
    wall_thickness = 0.14
    [positions.soil]                  # optional: replaces [soil] keys (quakes, dampings ...)
    [positions.srd]                   # the position's [srd] (method, cpt, layers ...), or
    method = "alm-hamre-2001"         # srd_file = "soil/a01_srd.toml", a file holding an
    cpt = "soil/a01_cpt.csv"          # [srd] table (its paths relative to that file)
    [[positions.srd.layers]]
    ...

The cases are every combination position x bound x hammer x anvil model (x energy schedule),
named ``<position>_<bound>_<hammer>_<anvil model>[_<energy schedule>]``. Each case is a
complete system file, ``DIR/cases/<case>/system.toml`` (the base with the position's pile and
SRD, its target penetration as the last depth, and the case's bound, hammer, anvil model and
energy schedule): ``anvilwave drive DIR/cases/<case>/system.toml`` reruns it alone.

Checks. The campaign file itself (unknown keys, names, axes, hammers and energy schedules
against their rated energies) and the base system file are checked before any case runs, and a
problem stops everything with one message naming the file, the key and the rule. A position's
own data (pile, soil, [srd] and its CPT file), checked next, and anything a case meets while it
runs (a CPT that ends above the target penetration, a failed blow ...) make only the cases
concerned fail: each is recorded with its error and the others run. The driver loads one case
of every hammer x anvil model combination first: this checks the combination (a problem in a
hammer's anvil table stops the campaign) and fills the modal-data cache (anvil and ram modes,
:mod:`anvilwave.config.cache`) so that the workers read the modes instead of each computing them (on
a cluster, point ``ANVILWAVE_CACHE_DIR`` at a folder every node sees).

Results. Each case writes, as it finishes, into its own folder ``DIR/cases/<case>/``:
``driveability.csv`` and ``driveability.png`` (as ``anvilwave drive``), then ``summary.json``,
atomically and last: a case is finished when its folder holds the summary of its current input
(``case_input_sha256``, the hash of its system.toml). A case that fails writes ``error.json``
instead. ``DIR/campaign.csv`` is rebuilt from the case folders at the end (one row per case,
so no case is recorded twice): ``case``, the axes (``position``, ``bound``, ``hammer``,
``anvil_model`` and ``energy_schedule`` when that axis is given), ``status`` (ok / error, or
pending for a case an interrupted run did not reach), ``refusal_depth [m]``, ``total_blows
[-]``, ``max_blow_count [1/m]``, ``max_compression_stress [Pa]``, ``max_tension_stress [Pa]``
(negative: compression positive), ``driving_time [s]``, ``wall_time [s]`` (the case in its
worker: loading, engine, depths and writing) and ``error``. The campaign plots go to
``DIR/plots/`` (:mod:`anvilwave.output.campaign_plots`). Run inside
:func:`anvilwave.inputs.record_inputs` (as the command line runs it), the campaign file and
every file it reads are copied into ``DIR/inputs/`` with their SHA-256 hashes in
``DIR/inputs.json``; the folder's marker names ``batch`` (:mod:`anvilwave.output.writer`).

Reruns and failures. A rerun skips the finished cases and runs the others (those that failed
included, after their input was fixed); a case whose input changed (its system.toml hash) runs
again. A case that raises is recorded as failed and never stops the others. A worker that dies
mid-case (killed, out of memory) is replaced and its case retried by dask, up to
:data:`ALLOWED_FAILURES` deaths per case (``distributed.scheduler.allowed-failures``; on an
existing scheduler its own setting applies); the case is then recorded as failed.
"""

from __future__ import annotations

import copy
import csv
import hashlib
import io
import json
import math
import os
import re
import shutil
import signal
import socket
import tempfile
import threading
import time
import traceback
import uuid
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from anvilwave.analyses.drive import COLUMNS, DriveResult, run_driveability
from anvilwave.config.drive import load_srd_source
from anvilwave.config.system import load_system
from anvilwave.engine.direct import anvil_modal_data
from anvilwave.hammer.database import available_hammers, load_hammer
from anvilwave.inputs import InputError, Table, active_record, read_toml, toml_dumps
from anvilwave.output.campaign_plots import plot_campaign
from anvilwave.output.plots import plot_driveability
from anvilwave.output.progress import CtrlC, Step
from anvilwave.output.progress import bar as progress_bar
from anvilwave.output.tables import write_csv
from anvilwave.output.writer import (
    check_output,
    result_command,
    write_inputs,
    write_marker,
)
from anvilwave.pile.model import PileSoil

ALLOWED_FAILURES = 3
"""Worker deaths a case survives on the LocalCluster before it is recorded as failed."""
BOUNDS = ("lower", "best", "upper")
ANVIL_MODELS = ("rom", "lumped", "classic", "none")
RAM_MODELS = ("rod", "modal")
NAME_RULE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9.+-]{0,39}$")
"""Names of positions, hammers and energy schedules: letters, digits, '.', '+', '-' (they make
the case folders' names, joined by '_')."""
RESULT_COLUMNS = ("refusal_depth [m]", "total_blows [-]", "max_blow_count [1/m]",
                  "max_compression_stress [Pa]", "max_tension_stress [Pa]", "driving_time [s]",
                  "wall_time [s]")
"""Result columns of campaign.csv (from each case's summary.json)."""
STATUS_OK, STATUS_ERROR, STATUS_PENDING = "ok", "error", "pending"
KEY_PREFIX = "anvilwave-case-"
"""Dask keys of the case tasks: KEY_PREFIX + case name + '-' + a token of the run."""
PATH_KEYS = {"hammer": ("file",), "anvil": ("file",), "srd": ("cpt", "file")}
"""Keys of a system file that name files (made absolute in the cases' system.toml)."""

CAMPAIGN_KEYS: dict[str, tuple[str, object, str]] = {
    "campaign": ("-", "required", "the campaign's name and base system file"),
    "campaign.name": ("-", "file stem", "label of the campaign (plot titles)"),
    "campaign.system": ("-", "required", "base system file (complete; its settings are shared)"),
    "axes": ("-", None, "the axes swept (each optional: default the base file's value)"),
    "axes.bounds": ("-", "the base's bound", "SRD bounds: 'lower', 'best', 'upper'"),
    "axes.anvil_models": ("-", "the base's model", "'rom', 'lumped', 'classic', 'none'"),
    "axes.hammers": ("-", "the base's hammer", "[[axes.hammers]] entries"),
    "axes.hammers.name": ("-", "required", "label of the hammer"),
    "axes.hammers.database": ("-", None, "a hammer of anvilwave/hammer/data (or file)"),
    "axes.hammers.file": ("-", None, "a hammer file (TOML, the format of anvilwave/hammer/data)"),
    "axes.hammers.energy": ("[m, J]", None, "energy schedule of this hammer"),
    "axes.hammers.ram_model": ("-", "the base's", "'rod' or 'modal'"),
    "axes.hammers.ram_mesh_size": ("m", None, "modal ram FE size"),
    "axes.hammers.anvil": ("-", None, "keys replacing the base's [anvil] keys (not model)"),
    "axes.hammers.anvil.*": ("", None, "as the system file's [anvil] keys"),
    "axes.energy_schedules": ("-", None, "[[axes.energy_schedules]] entries"),
    "axes.energy_schedules.name": ("-", "required", "label of the schedule"),
    "axes.energy_schedules.energy": ("[m, J]", None, "rows tip depth, blow energy"),
    "axes.energy_schedules.fraction": ("[m, -]", None, "rows tip depth, fraction of the "
                                                       "hammer's rated energy"),
    "positions": ("-", "required", "[[positions]] entries"),
    "positions.name": ("-", "required", "label of the position"),
    "positions.water_depth": ("m", "required", "water depth (CPT sea-level reference)"),
    "positions.target_penetration": ("m", "required", "last tip depth analysed"),
    "positions.pile": ("-", "required", "keys replacing the base's [pile] keys (sections)"),
    "positions.pile.*": ("", None, "as the system file's [pile] keys"),
    "positions.soil": ("-", None, "keys replacing the base's [soil] keys"),
    "positions.soil.*": ("", None, "as the system file's [soil] keys"),
    "positions.srd": ("-", None, "the position's [srd] table (or srd_file)"),
    "positions.srd.*": ("", None, "as the system file's [srd] keys (no water_depth)"),
    "positions.srd_file": ("-", None, "a TOML file holding the position's [srd] table"),
}
"""Every key of a campaign file: unit, default, meaning (``*``: the system file's keys)."""


# ----------------------------------------------------------------------------- the file
@dataclass(frozen=True)
class HammerEntry:
    """A value of the hammers axis.

    Parameters
    ----------
    name : str
        Label of the hammer.
    table : dict or None
        The cases' [hammer] table (None: the base file's).
    anvil : dict
        Keys replacing the base's [anvil] keys.
    energy : numpy.ndarray or None
        (n, 2) energy schedule, rows [tip depth [m], energy [J]], or None.
    rated_energy : float
        Rated energy of the hammer [J] (NaN if the hammer has none).
    key : str
        Its key in the campaign file.
    """

    name: str
    table: dict | None
    anvil: dict
    energy: np.ndarray | None
    rated_energy: float
    key: str


@dataclass(frozen=True)
class EnergySchedule:
    """A value of the energy-schedule axis.

    Parameters
    ----------
    name : str
        Label of the schedule.
    rows : numpy.ndarray
        (n, 2) rows [tip depth [m], energy [J]] (``energy``) or [tip depth [m], fraction of the
        rated energy [-]] (``fraction``).
    relative : bool
        True when the rows are fractions of the rated energy.
    """

    name: str
    rows: np.ndarray
    relative: bool

    def for_hammer(self, hammer: HammerEntry) -> np.ndarray:
        """The schedule for a hammer.

        Parameters
        ----------
        hammer : HammerEntry
            The hammer (its rated energy scales a relative schedule).

        Returns
        -------
        numpy.ndarray
            (n, 2) rows [tip depth [m], energy [J]].
        """
        if not self.relative:
            return self.rows
        return np.column_stack([self.rows[:, 0], self.rows[:, 1] * hammer.rated_energy])


@dataclass(frozen=True)
class Position:
    """A foundation position: its validated tables or the error that makes its cases fail.

    Parameters
    ----------
    name : str
        Label of the position.
    water_depth : float
        Water depth (the CPT's sea-level reference) [m].
    target_penetration : float
        Last tip depth analysed [m].
    pile : dict
        The validated [pile] table (paths absolute).
    soil : dict
        The validated [soil] table.
    srd : dict
        The validated [srd] table (paths absolute).
    error : str or None, default None
        The error that makes the position's cases fail (None: valid).
    """

    name: str
    water_depth: float
    target_penetration: float
    pile: dict
    soil: dict
    srd: dict
    error: str | None = None


@dataclass(frozen=True)
class Case:
    """One driveability of the campaign.

    Parameters
    ----------
    name : str
        Case name, ``<position>_<bound>_<hammer>_<anvil model>[_<energy schedule>]``.
    axes : dict
        {"position", "bound", "hammer", "anvil_model"[, "energy_schedule"]: value}.
    system_text : str
        Its system file (TOML).
    input_sha256 : str
        The hash of that text.
    hammer_index : int
        Index of its hammer in the campaign's hammers.
    error : str or None, default None
        Set when its position failed its checks (the case is recorded, not run).
    cost : float, default 0.0
        Estimated work (depths x blows x pile segments) [-], the order cases start in.
    """

    name: str
    axes: dict
    system_text: str
    input_sha256: str
    hammer_index: int
    error: str | None = None
    cost: float = 0.0


@dataclass(frozen=True)
class Campaign:
    """A validated campaign file and its cases (in file order).

    Parameters
    ----------
    source : str
        The campaign file, for messages.
    name : str
        Label of the campaign (plot titles).
    base_path : pathlib.Path
        The base system file.
    positions : tuple of Position
        The positions.
    hammers : tuple of HammerEntry
        The values of the hammers axis.
    bounds : tuple of str
        The SRD bounds.
    anvil_models : tuple of str
        The anvil models.
    energy_schedules : tuple of EnergySchedule
        The values of the energy-schedule axis (empty when the axis is not given).
    cases : tuple of Case, default ()
        The cases.
    """

    source: str
    name: str
    base_path: Path
    positions: tuple
    hammers: tuple
    bounds: tuple
    anvil_models: tuple
    energy_schedules: tuple
    cases: tuple = field(default=())

    @property
    def axes(self) -> tuple[str, ...]:
        """The axis columns of campaign.csv."""
        names = ("position", "bound", "hammer", "anvil_model")
        return names + (("energy_schedule",) if self.energy_schedules else ())


def load_campaign(path: str | Path) -> Campaign:
    """Read and check a campaign file (module docstring) and compose its cases.

    Parameters
    ----------
    path : str or pathlib.Path
        The campaign file (TOML).

    Returns
    -------
    Campaign
        The validated campaign and its cases.

    Raises
    ------
    InputError
        If the campaign file or its base system file breaks a rule (the message names the file,
        the key and the rule).
    """

    path = Path(path)
    root = Table.from_file(path)
    source = str(path)
    head = root.table("campaign")
    name = head.string("name", path.stem)
    base_path = head.path("system")
    head.finish()
    if not base_path.is_file():
        raise head.error("system", f"base system file {base_path} not found")
    base_cfg = load_system(base_path)  # the base must be a valid system file on its own
    if base_cfg.drive is None or base_cfg.srd is None:
        raise head.error("system", f"{base_path} needs a [driveability] and an [srd] table "
                                   "(the settings the cases share)")
    base = _absolute_paths(read_toml(base_path), base_path.parent)

    axes = root.table("axes", required=False)
    if axes is None:
        axes = Table({}, source, "axes")
    bounds = _names(axes, "bounds", [base_cfg.drive.bound], BOUNDS)
    anvil_models = _names(axes, "anvil_models", [base_cfg.anvil.model], ANVIL_MODELS)
    hammers = _hammers(axes, base, base_cfg, source)
    schedules = _schedules(axes, hammers)
    axes.finish()
    for j, h in enumerate(hammers):
        anvil = {**base["anvil"], **h.anvil}
        for m in anvil_models:
            if m in ("rom", "lumped") and "file" not in anvil:
                raise axes.error("anvil_models", f"the {m!r} anvil needs an anvil file "
                                                 f"([anvil] file of the base or of "
                                                 f"axes.hammers[{j}].anvil)")
            if m == "classic" and "classic" not in anvil:
                raise axes.error("anvil_models", "the 'classic' anvil needs an "
                                                 "[anvil.classic] table")
    _check_base_energy(base, hammers, schedules, source, base_path)

    positions = []
    seen: set[str] = set()
    for t in root.tables("positions"):
        positions.append(_position(t, base, seen))
    if not positions:
        raise root.error("positions", "a campaign needs at least one [[positions]] entry")
    root.finish()

    campaign = Campaign(source, name, base_path, tuple(positions), tuple(hammers),
                        tuple(bounds), tuple(anvil_models), tuple(schedules))
    cases = _compose_cases(campaign, base)
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        dup = next(n for n in names if names.count(n) > 1)
        raise InputError(source, "positions", f"two cases get the same name {dup!r}: rename "
                                              "a position, hammer or energy schedule")
    return Campaign(source, name, base_path, tuple(positions), tuple(hammers), tuple(bounds),
                    tuple(anvil_models), tuple(schedules), tuple(cases))


def _names(table: Table, key: str, default: list, choices) -> list[str]:
    """A non-empty list of distinct strings from ``choices``."""
    value = table._get(key, default)  # Table's raw access: it has no list-of-strings getter
    if (not isinstance(value, list) or not value
            or not all(isinstance(v, str) for v in value)):
        raise table.error(key, f"must be a non-empty list of strings from "
                               f"{', '.join(map(repr, choices))}, got {value!r}")
    for v in value:
        if v not in choices:
            raise table.error(key, f"entries must be one of {', '.join(map(repr, choices))}, "
                                   f"got {v!r}")
    if len(set(value)) != len(value):
        raise table.error(key, f"lists a value twice: {value!r}")
    return list(value)


def _label(table: Table, seen: set[str]) -> str:
    name = table.string("name")
    if not NAME_RULE.match(name):
        raise table.error("name", f"must be 1-40 letters, digits, '.', '+' or '-' (starting "
                                  f"with a letter or digit), got {name!r}")
    if name in seen:
        raise table.error("name", f"{name!r} is used twice")
    seen.add(name)
    return name


def _schedule_rows(table: Table, key: str, source_rule: str) -> np.ndarray | None:
    rows = table.array(key, None, columns=2)
    if rows is None:
        return None
    if np.any(rows[:, 0] < 0.0) or np.any(np.diff(rows[:, 0]) <= 0.0):
        raise table.error(key, "rows [tip depth [m], ...] need strictly increasing, "
                               "non-negative depths")
    if np.any(rows[:, 1] <= 0.0):
        raise table.error(key, f"{source_rule} must be positive")
    return rows


def _hammers(axes: Table, base: dict, base_cfg, source: str) -> list[HammerEntry]:

    if not axes.has("hammers"):
        table = base["hammer"]
        label = table.get("database") or Path(table.get("file", "hammer")).stem
        return [HammerEntry(str(label), None, {}, None, float(base_cfg.hammer.rated_energy),
                            "hammer")]
    entries, seen = [], set()
    base_ram_model = base["hammer"].get("ram_model", "rod")
    for j, t in enumerate(axes.tables("hammers")):
        name = _label(t, seen)
        if t.has("database") == t.has("file"):
            raise t.error("database", "give exactly one of database = \"name\" (one of "
                                      f"{', '.join(available_hammers())}) or file = \"path\"")
        if t.has("database"):
            ident = t.string("database", choices=available_hammers())
            hammer = load_hammer(ident, base_cfg.gravity)
            table = {"database": ident}
        else:
            file = t.path("file")
            if not file.is_file():
                raise t.error("file", f"hammer file {file} not found")
            hammer = load_hammer(file, base_cfg.gravity)
            table = {"file": str(file.resolve())}
        ram_model = t.string("ram_model", base_ram_model, choices=RAM_MODELS)
        table["ram_model"] = ram_model
        mesh = t.number("ram_mesh_size", base["hammer"].get("ram_mesh_size")
                        if ram_model == "modal" else None, gt=0.0, le=1.0, unit="m")
        if mesh is not None:
            if ram_model != "modal":
                raise t.error("ram_mesh_size", "applies to ram_model = \"modal\" only")
            table["ram_mesh_size"] = mesh
        rated = float(hammer.rated_energy)
        energy = _schedule_rows(t, "energy", "energies [J]")
        if energy is not None:
            _check_rated(t, "energy", energy, rated, hammer.name)
        anvil_table = t.table("anvil", required=False)
        anvil = {}
        if anvil_table is not None:
            anvil = _absolute_paths({"anvil": copy.deepcopy(anvil_table.data)},
                                    Path(source).parent)["anvil"]
            if "model" in anvil:  # its other keys are checked when the cases load
                raise anvil_table.error("model", "the anvil model is the anvil_models axis")
        t.finish()
        entries.append(HammerEntry(name, table, anvil, energy, rated, f"axes.hammers[{j}]"))
    if not entries:
        raise axes.error("hammers", "give at least one [[axes.hammers]] entry or leave the "
                                    "axis out (the base file's hammer)")
    return entries


def _check_rated(table: Table, key: str, rows: np.ndarray, rated: float, name: str) -> None:
    if rated == rated and np.max(rows[:, 1]) > rated * 1.0001:
        raise table.error(key, f"reaches {np.max(rows[:, 1]) / 1e3:g} kJ, above the rated "
                               f"energy of {name} ({rated / 1e3:g} kJ)")


def _schedules(axes: Table, hammers: list[HammerEntry]) -> list[EnergySchedule]:
    if not axes.has("energy_schedules"):
        return []
    for h in hammers:
        if h.energy is not None:
            raise InputError(axes.source, f"{h.key}.energy", "give the energy schedules either "
                                                             "per hammer or as the "
                                                             "energy_schedules axis, not both")
    out, seen = [], set()
    for t in axes.tables("energy_schedules"):
        name = _label(t, seen)
        if t.has("energy") == t.has("fraction"):
            raise t.error("energy", "give exactly one of energy = [[depth, J], ...] or "
                                    "fraction = [[depth, fraction of the rated energy], ...]")
        relative = t.has("fraction")
        rows = _schedule_rows(t, "fraction" if relative else "energy",
                              "fractions [-]" if relative else "energies [J]")
        if relative and np.any(rows[:, 1] > 1.0):
            raise t.error("fraction", "fractions of the rated energy must be at most 1")
        if relative:
            for h in hammers:
                if not h.rated_energy == h.rated_energy:
                    raise t.error("fraction", f"hammer {h.name} has no rated energy: give "
                                              "energy = [[depth, J], ...]")
        else:
            for h in hammers:
                _check_rated(t, "energy", rows, h.rated_energy, h.name)
        t.finish()
        out.append(EnergySchedule(name, rows, relative))
    if not out:
        raise axes.error("energy_schedules", "give at least one entry or leave the axis out")
    return out


def _check_base_energy(base: dict, hammers, schedules, source: str, base_path: Path) -> None:
    """The base file's [driveability] energy schedule serves the hammers that have none."""
    rows = base.get("driveability", {}).get("energy")
    if schedules or rows is None:
        return
    top = max(r[1] for r in rows)
    for h in hammers:
        if h.energy is None and h.rated_energy == h.rated_energy and \
                top > h.rated_energy * 1.0001:
            if h.table is None:  # the base file's own hammer
                raise InputError(base_path, "driveability.energy",
                                 f"reaches {top / 1e3:g} kJ, above the rated energy of the "
                                 f"hammer ({h.rated_energy / 1e3:g} kJ)")
            raise InputError(source, h.key, f"the base file's [driveability] energy schedule "
                                            f"reaches {top / 1e3:g} kJ, above the rated energy "
                                            f"of {h.name} ({h.rated_energy / 1e3:g} kJ): give "
                                            "this hammer its own energy = [[depth, J], ...]")


def _position(t: Table, base: dict, seen: set[str]) -> Position:
    """Read a [[positions]] entry: its keys stop the campaign when wrong; its pile, soil and
    SRD data (and CPT file) only make its own cases fail."""
    name = _label(t, seen)
    water = t.number("water_depth", ge=0.0, le=5000.0, unit="m")
    target = t.number("target_penetration", gt=0.0, unit="m")
    pile = copy.deepcopy(t.table("pile").data)
    soil_table = t.table("soil", required=False)
    soil = copy.deepcopy(soil_table.data) if soil_table is not None else {}
    if t.has("srd") == t.has("srd_file"):
        raise t.error("srd", "give exactly one of an [positions.srd] table or srd_file")
    srd_table = t.table("srd", required=False)
    srd_file = t.path("srd_file", None)
    t.finish()
    merged_pile = {**base["pile"], **pile}
    merged_soil = {k: v for k, v in base.get("soil", {}).items() if k not in ("penetration",
                                                                               "srd")}
    merged_soil.update(soil)
    try:
        if srd_file is not None:
            if not srd_file.is_file():
                raise InputError(t.source, t.key("srd_file"), f"{srd_file} not found")
            holder = Table.from_file(srd_file)
            srd_source, prefix = str(srd_file), "srd"
            srd = copy.deepcopy(holder.table("srd").data)
            holder.finish()
            srd = _absolute_paths({"srd": srd}, srd_file.parent)["srd"]
        else:
            srd_source, prefix = t.source, t.key("srd")
            srd = _absolute_paths({"srd": copy.deepcopy(srd_table.data)},
                                  Path(t.source).parent)["srd"]
        if "water_depth" in srd:
            raise InputError(srd_source, f"{prefix}.water_depth",
                             f"give the water depth once, as {t.key('water_depth')}")
        if "cpt" in srd:
            srd["water_depth"] = water
        _check_position(t, target, merged_pile, merged_soil, srd, srd_source, prefix, base)
    except (InputError, ValueError) as exc:
        return Position(name, water, target, merged_pile, merged_soil, {}, str(exc))
    return Position(name, water, target, merged_pile, merged_soil, srd)


def _check_position(t: Table, target: float, pile: dict, soil: dict, srd: dict,
                    srd_source: str, prefix: str, base: dict) -> None:
    """Pile, soil and SRD of a position through the system file's own readers (which also
    read its CPT file)."""

    pile_soil = PileSoil.from_tables(Table(pile, t.source, t.key("pile")),
                                     Table(soil, t.source, t.key("soil")),
                                     srd_optional=True, default_penetration=target)
    length = float(pile_soil.pile.length)
    if not target < length:
        raise t.error("target_penetration", f"must be less than the pile length {length:g} m")
    drive = base["driveability"]
    first = min(drive["depths"]) if "depths" in drive else drive["start"]
    if not target > first:
        raise t.error("target_penetration", f"must be deeper than the base file's first "
                                            f"depth {first:g} m")
    load_srd_source(Table(srd, srd_source, prefix), srd_source, pile_soil)


def _absolute_paths(data: dict, folder: Path) -> dict:
    """``data`` (a system file's tables) with the file names of :data:`PATH_KEYS` absolute."""
    out = copy.deepcopy(data)
    for table, keys in PATH_KEYS.items():
        t = out.get(table)
        if not isinstance(t, dict):
            continue
        for key in keys:
            if isinstance(t.get(key), str) and not Path(t[key]).is_absolute():
                t[key] = str((folder / t[key]).resolve())
    return out


def _compose_cases(campaign: Campaign, base: dict) -> list[Case]:
    cases = []
    for p in campaign.positions:
        for bound in campaign.bounds:
            for j, h in enumerate(campaign.hammers):
                for model in campaign.anvil_models:
                    for s in campaign.energy_schedules or (None,):
                        cases.append(_case(campaign, base, p, bound, j, h, model, s))
    return cases


def _case(campaign, base, p: Position, bound, j, h: HammerEntry, model, schedule) -> Case:
    axes = {"position": p.name, "bound": bound, "hammer": h.name, "anvil_model": model}
    if schedule is not None:
        axes["energy_schedule"] = schedule.name
    name = "_".join(axes.values())
    d = copy.deepcopy(base)
    d["pile"], d["soil"], d["srd"] = p.pile, p.soil, p.srd
    drive = d["driveability"]
    if "depths" in drive:
        drive["depths"] = [float(z) for z in drive["depths"] if z < p.target_penetration] + \
                          [p.target_penetration]
        n_depths = len(drive["depths"])
    else:
        drive["stop"] = p.target_penetration
        n_depths = max(1, int((p.target_penetration - drive["start"]) / drive["step"]) + 1)
    drive.pop("time_series_depths", None)  # blow time series are not part of a campaign
    drive["bound"] = bound
    if schedule is not None:
        drive["energy"] = schedule.for_hammer(h).tolist()
    elif h.energy is not None:
        drive["energy"] = h.energy.tolist()
    if h.table is not None:
        d["hammer"] = dict(h.table)
    d["anvil"] = {**d["anvil"], **h.anvil, "model": model}
    body = toml_dumps(d)  # its hash identifies the case's input (paths in it are absolute)
    header = (f"# Case {name} of the campaign\n# {Path(campaign.source).resolve()}:\n# its "
              f"base system file\n# {campaign.base_path.resolve()}\n# with the position's "
              "pile and SRD and the case's axes (anvilwave.analyses.batch).\n# A complete system "
              "file: anvilwave drive runs it alone.\n")
    segments = sum(s["length"] for s in p.pile["sections"]) / p.pile.get("segment_length",
                                                                          0.5) \
        if p.error is None else 1.0
    cost = n_depths * drive.get("blows_per_depth", 1) * segments
    return Case(name, axes, header + body, hashlib.sha256(body.encode()).hexdigest(), j,
                p.error, float(cost))


# ----------------------------------------------------------------------------- one case
def run_case(spec: dict) -> dict:
    """Run one case in this process and write its folder (the dask task; module docstring).

    Never raises for a failing case: the error is written to the case's ``error.json`` and
    returned in the row.

    Parameters
    ----------
    spec : dict
        ``name``, ``dir``, ``axes``, ``system_text``, ``input_sha256``, ``plots``.

    Returns
    -------
    dict
        Its campaign.csv row.
    """
    start = time.perf_counter()
    folder = Path(spec["dir"])
    done = _read_record(folder / "summary.json", spec["input_sha256"])
    if done is not None:  # finished already (a task recomputed after a lost result)
        return _row(spec["name"], spec["axes"], done)
    folder.mkdir(parents=True, exist_ok=True)
    for stale in ("summary.json", "error.json"):  # of another input: not this case's result
        if (folder / stale).exists():
            (folder / stale).unlink()
    system = folder / "system.toml"
    _write_atomic(system, spec["system_text"])
    try:

        cfg = load_system(system)
        result = run_driveability(cfg, cfg.srd, cfg.drive, None, workers=1)
        summary = dict(result.summary)
        summary["driveability_wall_time [s]"] = summary.pop("wall_time [s]")
        summary.update(_identity(spec))
        summary["system"] = system.name
        _write_case(folder, result, summary, cfg, spec, start)
        return _row(spec["name"], spec["axes"], summary)
    except Exception as exc:  # a failing case is recorded, never stops the campaign
        record = record_error(folder, spec, error_message(exc), traceback.format_exc(),
                              time.perf_counter() - start)
        return _row(spec["name"], spec["axes"], record)


def error_message(exc: BaseException) -> str:
    """One line for campaign.csv describing an exception.

    Parameters
    ----------
    exc : BaseException
        The exception.

    Returns
    -------
    str
        An input error as it reads (file: key: rule), anything else with its type.
    """
    text = str(exc) if isinstance(exc, InputError) else f"{type(exc).__name__}: {exc}"
    return " ".join(text.split())[:1000]


def record_error(folder: Path, spec: dict, message: str, trace: str = "",
                 wall_time: float = float("nan"), in_worker: bool = True) -> dict:
    """Write a case's ``error.json`` atomically (unless it finished meanwhile).

    Parameters
    ----------
    folder : pathlib.Path
        The case folder.
    spec : dict
        The case spec (:func:`run_case`).
    message : str
        The error message.
    trace : str, default ""
        The traceback.
    wall_time : float, default nan
        Wall time of the case [s].
    in_worker : bool, default True
        Recorded by the case's worker (with its host and memory), else by the driver (a case not
        run, or whose worker died).

    Returns
    -------
    dict
        The record.
    """
    record = {**_identity(spec), "status": STATUS_ERROR, "error": message,
              "wall_time [s]": wall_time,
              **(_worker_info() if in_worker else {"recorded_by": "driver"})}
    if trace:
        record["traceback"] = trace
    folder.mkdir(parents=True, exist_ok=True)
    if _read_record(folder / "summary.json", spec["input_sha256"]) is None:
        _write_atomic(folder / "error.json", json.dumps(_jsonable(record), indent=2) + "\n")
    return record


def _identity(spec: dict) -> dict:
    return {"case": spec["name"], **spec["axes"], "status": STATUS_OK,
            "case_input_sha256": spec["input_sha256"]}


def _worker_info() -> dict:
    import resource

    return {"worker_host": socket.gethostname(), "worker_pid": os.getpid(),
            # Linux reports the peak resident set size in KiB
            "worker_max_rss [B]": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}


def _write_case(folder: Path, result: DriveResult, summary: dict, cfg, spec: dict,
                start: float) -> None:
    """driveability.csv (and .png), then summary.json atomically and last (with the case's
    wall time since ``start`` [s] (perf_counter) and its worker's peak memory)."""

    staging = Path(tempfile.mkdtemp(prefix=".partial-", dir=folder))
    try:
        rows = result.rows
        columns = {n: np.array([r[n] for r in rows], dtype=float) for n in COLUMNS}
        write_csv(columns, staging / "driveability.csv")
        if spec.get("plots", True):

            plot_driveability(columns, summary, staging / "driveability.png",
                              title=f"case {spec['name']}: {cfg.anvil.model} anvil, "
                                    f"{cfg.drive.bound} SRD")
        for item in staging.iterdir():
            item.replace(folder / item.name)
        summary["wall_time [s]"] = time.perf_counter() - start
        summary.update(_worker_info())
        (staging / "summary.json").write_text(json.dumps(_jsonable(summary), indent=2) + "\n")
        (staging / "summary.json").replace(folder / "summary.json")
        if (folder / "error.json").exists():
            (folder / "error.json").unlink()
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def _write_atomic(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}-", suffix=".part", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def _read_record(path: Path, sha256: str) -> dict | None:
    """A case's summary.json / error.json if it is of the input ``sha256``, else None."""
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(record, dict) or record.get("case_input_sha256") != sha256:
        return None
    return record


def _row(name: str, axes: dict, record: dict | None) -> dict:
    """A campaign.csv row from a case's summary or error record (None: pending)."""
    row = {"case": name, **axes}
    if record is None:
        row["status"] = STATUS_PENDING
    else:
        row["status"] = record.get("status", STATUS_OK)
        for col in RESULT_COLUMNS:
            row[col] = record.get(col)
        row["error"] = record.get("error", "")
    return row


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.floating | np.integer):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


# ----------------------------------------------------------------------------- campaign
@dataclass
class BatchResult:
    """A campaign run (``anvilwave batch``).

    Parameters
    ----------
    cases : int
        Cases of the campaign [-].
    ran : int
        Cases run now [-].
    skipped : int
        Cases finished in the folder before (not run again) [-].
    ok : int
        Cases of status ok in ``campaign.csv`` [-].
    error : int
        Cases of status error in ``campaign.csv`` [-].
    pending : int
        Cases of status pending in ``campaign.csv`` [-].
    workers : int
        Dask workers used (0: nothing to run) [-].
    wall_time : float
        Wall time of the run [s].
    campaign_csv : str
        The campaign table (one row per case: its axes, status, summary and timings).
    rows : list of dict
        Its rows.
    """

    cases: int
    ran: int
    skipped: int
    ok: int
    error: int
    pending: int
    workers: int
    wall_time: float
    campaign_csv: str
    rows: list[dict]


def run_campaign(campaign_path: str | Path, out_dir: str | Path, *, workers: int | None = None,
                 scheduler=None, progress: bool = True, plots: bool = True,
                 force: bool = False) -> BatchResult:
    """Run every case of a campaign not finished yet in ``out_dir`` (module docstring).

    Parameters
    ----------
    campaign_path : str or pathlib.Path
        The campaign file (TOML).
    out_dir : str or pathlib.Path
        The campaign folder: ``cases/<case>/``, ``campaign.csv``, ``plots/``.
    workers : int or None, default None
        Worker processes of the LocalCluster [-] (default: the machine's cores; at most the cases
        to run). Ignored with ``scheduler``.
    scheduler : str, cluster or distributed.Client, optional
        An existing dask scheduler: its address (``"tcp://host:8786"``), a cluster object (e.g.
        dask-jobqueue's ``SLURMCluster``) or a ``distributed.Client``.
    progress : bool, default True
        A progress bar over the cases (stderr).
    plots : bool, default True
        Each case's driveability.png and the campaign plots.
    force : bool, default False
        A folder holding another command's result is removed first (refused without it).

    Returns
    -------
    BatchResult
        The counts, timings and rows of the run.

    Raises
    ------
    InputError
        If ``workers`` is not a whole number of at least 1, the campaign file breaks a rule, or
        no dask scheduler answers at ``scheduler``.
    """
    start = time.perf_counter()
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError("workers", "", f"must be a whole number of at least 1, got "
                                        f"{workers!r}")
    campaign = load_campaign(campaign_path)
    out = check_output(out_dir, "batch", force)
    if force and result_command(out) not in (None, "batch"):
        shutil.rmtree(out)  # another command's result: replaced, never mixed
    fresh = not out.exists()  # made by this run: removed again if it stops before any case
    try:
        return _run_campaign(campaign, out, workers, scheduler, progress, plots, start)
    except BaseException:
        if fresh and out.is_dir() and not any((out / "cases").glob("*/summary.json")):
            shutil.rmtree(out, ignore_errors=True)
        raise


def _run_campaign(campaign, out: Path, workers, scheduler, progress: bool, plots: bool,
                  start: float) -> BatchResult:
    """The body of :func:`run_campaign` once the campaign file is read."""
    cases_dir = out / "cases"
    cases_dir.mkdir(parents=True, exist_ok=True)
    write_marker(out, "batch")  # at once: no other command writes into a killed run's folder
    specs = {c.name: _spec(c, cases_dir, plots) for c in campaign.cases}
    finished = {c.name for c in campaign.cases
                if _read_record(cases_dir / c.name / "summary.json", c.input_sha256)}
    todo = [c for c in campaign.cases if c.name not in finished]
    for c in todo:
        if c.error is not None:  # its position failed its checks: recorded, not run
            record_error(cases_dir / c.name, specs[c.name], c.error, in_worker=False)
    runnable = [c for c in todo if c.error is None]
    if runnable:  # a hammer x anvil problem stops the campaign before its progress bar
        with Step("checking every hammer x anvil model and computing their modes...",
                  enabled=progress):
            _prepare(campaign, runnable, out)
    bar = None

    def open_bar():  # once the cluster runs: Ctrl-C is seen from the moment the bar shows
        if not progress:
            return None
        # no estimate before a case per worker has finished: the first cases of each worker
        # compile its kernels
        opened = progress_bar(len(campaign.cases), warm=workers or os.cpu_count() or 1,
                              initial=len(campaign.cases) - len(runnable),
                              desc=f"campaign {campaign.name}", unit="case")
        for c in todo:
            if c.error is not None:
                opened.write(f"{c.name}: {c.error}")
        return opened

    n_workers = 0
    try:
        if runnable:
            with Step("starting the dask workers...", enabled=progress) as starting, \
                    _dask_client(workers, scheduler, len(runnable)) as client:
                starting.__exit__(None, None, None)
                n_workers = len(client.scheduler_info().get("workers", {}))
                bar = open_bar()
                _run_on(client, runnable, specs, bar)
        else:
            bar = open_bar()
    finally:
        if bar is not None:
            bar.close()
        _remove_partials(cases_dir)
        rows = collect(campaign, out)
        _write_atomic(out / "campaign.csv", campaign_csv_text(campaign, rows))
    if plots:
        with Step(f"writing the campaign figures into {out / 'plots'}...", enabled=progress):
            plot_campaign(campaign, rows, out)
    record = active_record()
    if record is not None:
        write_inputs(out, record)
    counts = {s: sum(r["status"] == s for r in rows)
              for s in (STATUS_OK, STATUS_ERROR, STATUS_PENDING)}
    return BatchResult(cases=len(campaign.cases), ran=len(runnable), skipped=len(finished),
                       ok=counts[STATUS_OK], error=counts[STATUS_ERROR],
                       pending=counts[STATUS_PENDING], workers=n_workers,
                       wall_time=time.perf_counter() - start,
                       campaign_csv=str(out / "campaign.csv"), rows=rows)


def _spec(case: Case, cases_dir: Path, plots: bool) -> dict:
    return {"name": case.name, "dir": str((cases_dir / case.name).resolve()),
            "axes": dict(case.axes), "system_text": case.system_text,
            "input_sha256": case.input_sha256, "plots": bool(plots)}


def _prepare(campaign: Campaign, runnable: list[Case], out: Path) -> None:
    """Load one case of every hammer x anvil model combination on the driver: a problem of
    the combination (a hammer's anvil table) stops the campaign; the anvil and ram modes
    go into the modal-data cache for the workers. Other problems are left to the cases."""

    firsts: dict[tuple, Case] = {}
    for c in runnable:
        firsts.setdefault((c.hammer_index, c.axes["anvil_model"]), c)
    with tempfile.TemporaryDirectory(prefix=".prepare-", dir=out) as tmp:
        for (j, model), case in firsts.items():
            path = Path(tmp) / f"{case.name}.toml"
            path.write_text(case.system_text)
            try:
                cfg = load_system(path)
                if model == "rom":
                    anvil_modal_data(cfg)
            except InputError as exc:
                if exc.key.split(".")[0] in ("hammer", "anvil"):
                    h = campaign.hammers[j]
                    raise InputError(campaign.source, h.key,
                                     f"hammer {h.name} with the {model!r} anvil: "
                                     f"{exc.key}: {exc.rule}") from None
            except ValueError:
                pass  # the cases record it


@contextmanager
def _dask_client(workers: int | None, scheduler, n_cases: int):
    """A Client on the given scheduler, or on a LocalCluster of processes started here."""
    import logging

    import dask
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        if isinstance(scheduler, Client):
            yield scheduler
            return
        try:
            client = Client(scheduler, timeout=30)
        except (OSError, TimeoutError) as exc:
            raise InputError("--scheduler", "", f"no dask scheduler answers at {scheduler!r} "
                                              f"({exc})") from None
        try:
            yield client
        finally:
            client.close()
        return
    n = max(1, min(workers or os.cpu_count() or 1, n_cases))
    # the worker processes start with SIGINT ignored (inherited): a Ctrl-C reaches this
    # process only, which prints one line and closes the cluster, instead of a traceback
    # from every worker (one pressed while the cluster starts is not seen)
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main_thread else None
    try:
        with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES}):
            # workers' own logs only when critical: a worker losing the scheduler as the
            # cluster closes is not news, and case failures are recorded with the case
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=":0", silence_logs=logging.CRITICAL)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
    try:
        client = Client(cluster)
        try:
            yield client
        finally:
            client.close()
    finally:
        cluster.close()


def _run_on(client, runnable: list[Case], specs: dict, bar) -> None:
    """Submit the cases (the most work first) and record each as it completes."""
    from dask.distributed import as_completed

    token = uuid.uuid4().hex[:8]
    by_key = {}
    futures = []
    for case in runnable:
        key = f"{KEY_PREFIX}{case.name}-{token}"
        fut = client.submit(run_case, specs[case.name], key=key, pure=False,
                            priority=int(case.cost))
        by_key[key] = case
        futures.append(fut)
    with CtrlC() as ctrl_c:
        _record(futures, as_completed, by_key, specs, bar, ctrl_c, client)


def _record(futures, as_completed, by_key, specs, bar, ctrl_c, client) -> None:
    """Record each case of ``futures`` as it completes (:func:`_run_on`); a Ctrl-C that the
    client's event loop swallowed stops it at the next case."""
    ok = failed = 0
    try:
        for fut in as_completed(futures):
            ctrl_c.check()
            case = by_key[fut.key]
            spec = specs[case.name]
            if fut.status == "finished":
                row = fut.result()
            else:  # the task itself failed: its worker died too often, or it was lost
                try:
                    exc = fut.exception()
                except Exception as cancelled:  # noqa: BLE001 (a cancelled future raises)
                    exc = cancelled
                message = error_message(exc)
                if type(exc).__name__ == "KilledWorker":
                    message = ("the workers running this case died too often (dask's "
                               "distributed.scheduler.allowed-failures; out of memory? "
                               f"killed?): {message}")
                row = _row(case.name, case.axes, record_error(Path(spec["dir"]), spec,
                                                              message, in_worker=False))
            fut.release()
            if row["status"] == STATUS_OK:
                ok += 1
            else:
                failed += 1
                if bar is not None:
                    bar.write(f"{case.name}: {row['error']}")
            if bar is not None:
                bar.set_postfix(ok=ok, error=failed, refresh=False)
                bar.update(1)
        ctrl_c.check()
    except BaseException:
        client.cancel(futures)
        raise


def _remove_partials(cases_dir: Path) -> None:
    """Staging folders left by workers that died while writing (their cases ran again)."""
    for partial in cases_dir.glob("*/.partial-*"):
        shutil.rmtree(partial, ignore_errors=True)
    for part in cases_dir.glob("*/.*.part"):
        part.unlink(missing_ok=True)


def collect(campaign: Campaign, out_dir: str | Path) -> list[dict]:
    """The campaign.csv rows from the case folders, one per case, in the campaign's order.

    Parameters
    ----------
    campaign : Campaign
        The campaign.
    out_dir : str or pathlib.Path
        The campaign folder.

    Returns
    -------
    list of dict
        Per case the summary of its current input, else its error record, else pending.
    """
    cases_dir = Path(out_dir) / "cases"
    rows = []
    for c in campaign.cases:
        folder = cases_dir / c.name
        record = _read_record(folder / "summary.json", c.input_sha256)
        if record is None:
            record = _read_record(folder / "error.json", c.input_sha256)
        rows.append(_row(c.name, c.axes, record))
    return rows


def campaign_csv_columns(campaign: Campaign) -> list[str]:
    """The columns of campaign.csv: case, the axes, status, the result columns and error.

    Parameters
    ----------
    campaign : Campaign
        The campaign (its axes).

    Returns
    -------
    list of str
        The column names.
    """
    return ["case", *campaign.axes, "status", *RESULT_COLUMNS, "error"]


def campaign_csv_text(campaign: Campaign, rows: list[dict]) -> str:
    """campaign.csv (module docstring): empty cells for missing numbers.

    Parameters
    ----------
    campaign : Campaign
        The campaign (its columns).
    rows : list of dict
        The rows (:func:`collect`).

    Returns
    -------
    str
        The CSV text.
    """
    columns = campaign_csv_columns(campaign)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        cells = []
        for col in columns:
            value = row.get(col)
            if value is None or (isinstance(value, float) and not math.isfinite(value)):
                cells.append("")
            elif isinstance(value, float | int) and not isinstance(value, bool):
                cells.append(f"{float(value):.9g}")
            else:
                cells.append(str(value))
        writer.writerow(cells)
    return buffer.getvalue()


def read_campaign_csv(path: str | Path) -> list[dict]:
    """The rows of a campaign.csv (numbers as floats, empty cells as None).

    Parameters
    ----------
    path : str or pathlib.Path
        The campaign.csv file.

    Returns
    -------
    list of dict
        One dict per row, keyed by column.
    """
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    for row in rows:
        for col in RESULT_COLUMNS:
            if col in row:
                row[col] = float(row[col]) if row[col] else None
    return rows
