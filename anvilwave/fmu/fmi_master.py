"""A fast fmpy master for the ram - anvil - pile chain of FMUs (FMI 2.0 co-simulation).

The three units are driven through fmpy's low-level FMI 2.0 functions (``fmpy.fmi2.FMU2Slave``
loads the binaries; the loop calls the library functions directly with value-reference and
value arrays allocated once), one ``fmi2GetReal`` and one ``fmi2SetReal`` per unit per step.
Step order, from t_n to t_n+1 (DESIGN.md, the same in every engine):

1. read the ram toe (``u_toe``, ``v_toe``) and the pile head (``u_head``, ``v_head``, with the
   gauge signals ``F_gauge``, ``v_gauge``): states, no feedthrough;
2. set them on the anvil (``u_ram``, ``v_ram``, ``u_pile``, ``v_pile``) and read its contact
   forces ``F_ram``, ``F_pile`` (feedthrough: the forces at t_n) with ``u_top``, ``u_bottom``;
3. set ``F_toe = F_ram`` on the ram and ``F_head = F_pile`` on the pile;
4. ``fmi2DoStep`` every unit over [t_n, t_n + h], t_n = t0 + n h (from the step count).

Row n of the result holds the exchanged values at t_n; a run of N steps has N + 1 rows.
Any unit that implements the interface of DESIGN.md can be used; each must accept the
communication step (the anvil ROM integrates exactly over any step).

Cost: the Python-side call overhead of pythonfmu units dominates (tens of microseconds per
3-unit step, measured by :meth:`ChainMaster.run`; ``ChainResult.microseconds_per_step``).

:class:`BlowMaster` (the master of :func:`anvilwave.engine.fmi.run_fmi`) runs consecutive blows the
way the in-process engine does (the pile/soil unit lives on, ram and anvil are reset for each
blow and start at rest on the pile head) with the same step order. Both masters run one step
loop, compiled with numba (:func:`_master_loop`, the DESIGN.md or the Jacobi exchange order):
the nine FMI calls per step go straight from machine code to the
FMU binaries, which leaves the FMUs' own cost (pythonfmu's C++ to Python crossing, ~1-1.5 us a
call, and the slaves' Python and kernels): about 13 us per step for Table 1 against ~21 us
with an interpreted loop on the reference 2-core machine.
"""

from __future__ import annotations

import ctypes
import shutil
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numba import njit

# (FMU variable names read or written through the scratch row, in scratch order)
RAM_OUTPUTS = ("u_toe", "v_toe")
PILE_OUTPUTS = ("u_head", "v_head", "F_gauge", "v_gauge")
ANVIL_INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")
ANVIL_OUTPUTS = ("F_ram", "F_pile", "u_top", "u_bottom")
PILE_EXTRA_OUTPUTS = ("u_head_total", "u_pile_toe")
"""Optional PileSoil outputs read with the interface ones when the unit has them."""
BLOW_ROW = RAM_OUTPUTS + PILE_OUTPUTS + PILE_EXTRA_OUTPUTS + ANVIL_OUTPUTS
"""The exchange row of :class:`BlowMaster`: every value read in one communication point."""
_F_RAM = BLOW_ROW.index("F_ram")
_F_PILE = BLOW_ROW.index("F_pile")
_PILE_AT = BLOW_ROW.index("u_head")
_OFFSETS = np.array([_PILE_AT, _F_RAM, _F_PILE], dtype=np.int64)
"""Offsets in the exchange row of the pile outputs and the two forces (for _master_loop)."""

COLUMNS: tuple[tuple[str, str], ...] = (
    ("time", "s"),
    ("ram_toe_displacement", "m"),
    ("ram_toe_velocity", "m/s"),
    ("pile_head_displacement", "m"),
    ("pile_head_velocity", "m/s"),
    ("gauge_force", "N"),
    ("gauge_velocity", "m/s"),
    ("ram_anvil_force", "N"),
    ("anvil_pile_force", "N"),
    ("anvil_top_displacement", "m"),
    ("anvil_bottom_displacement", "m"),
)
"""Result columns (name, unit); after ``time`` they follow the scratch row of the master."""

UNITS = ("ram", "anvil", "pile")


class CosimulationError(RuntimeError):
    """A unit returned fmi2Discard, fmi2Error or fmi2Fatal; the message holds its log."""


@dataclass
class ChainResult:
    """Time series of a chain run: ``data[:, j]`` is column ``names[j]`` (units in ``units``).

    ``result["ram_anvil_force"]`` gives one column [SI unit of the column].

    Parameters
    ----------
    data : numpy.ndarray
        The time series, shape (rows, columns) [SI unit of each column].
    names : tuple of str, default the names of ``COLUMNS``
        Column names.
    units : tuple of str, default the units of ``COLUMNS``
        Column units.
    wall_time : float, default 0.0
        Wall time of the stepping loop [s].
    n_steps : int, default 0
        Number of communication steps run [-].
    messages : dict of str to list of str, default {}
        Log messages of each unit (by role).
    """

    data: np.ndarray
    names: tuple[str, ...] = tuple(name for name, _ in COLUMNS)
    units: tuple[str, ...] = tuple(unit for _, unit in COLUMNS)
    wall_time: float = 0.0
    n_steps: int = 0
    messages: dict[str, list[str]] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[:, self.names.index(name)]

    @property
    def time(self) -> np.ndarray:
        """Time column [s].

        Returns
        -------
        numpy.ndarray
            The ``time`` column [s].
        """
        return self["time"]

    @property
    def header(self) -> list[str]:
        """CSV header ``name [unit]``.

        Returns
        -------
        list of str
            One ``name [unit]`` entry per column.
        """
        return [f"{n} [{u}]" for n, u in zip(self.names, self.units, strict=True)]

    @property
    def microseconds_per_step(self) -> float:
        """Wall time of the stepping loop per 3-unit step [us].

        Returns
        -------
        float
            Wall time per step [us].
        """
        return 1e6 * self.wall_time / max(self.n_steps, 1)


class _Unit:
    """One loaded FMU: fmpy slave, variable references, typed parameter setting."""

    def __init__(self, role: str, path: Path, callbacks):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave

        self.role = role
        self.path = path
        self.description = read_model_description(str(path))
        self.variables = {v.name: v for v in self.description.modelVariables}
        self.unzip_dir = extract(str(path))
        self.slave = FMU2Slave(guid=self.description.guid, unzipDirectory=self.unzip_dir,
                               modelIdentifier=self.description.coSimulation.modelIdentifier,
                               instanceName=role)
        saved_path = list(sys.path)
        try:
            self.slave.instantiate(callbacks=callbacks)
        finally:  # pythonfmu puts the FMU's resources folder first on sys.path for good
            sys.path[:] = saved_path
        self.needs_reset = False

    def references(self, names) -> ctypes.Array:
        missing = [n for n in names if n not in self.variables]
        if missing:
            raise CosimulationError(f"{self.role} FMU {self.path.name} lacks the variables "
                                    f"{missing} of the DESIGN.md interface")
        return (ctypes.c_uint * len(names))(*(self.variables[n].valueReference for n in names))

    def set_parameters(self, values: dict[str, Any]) -> None:
        for name, value in values.items():
            var = self.variables.get(name)
            if var is None or var.causality != "parameter":
                raise CosimulationError(f"{self.role} FMU {self.path.name}: {name!r} is not a "
                                        "parameter")
            setter = {"Real": self.slave.setReal, "Integer": self.slave.setInteger,
                      "Boolean": self.slave.setBoolean, "String": self.slave.setString}[var.type]
            setter([var.valueReference], [value])

    def close(self) -> None:
        try:
            self.slave.terminate()
        except Exception:  # noqa: BLE001 - a unit that failed may refuse to terminate
            pass
        self.slave.freeInstance()
        shutil.rmtree(self.unzip_dir, ignore_errors=True)


class ChainMaster:
    """Co-simulation of Ram, Anvil and PileSoil FMUs at a fixed communication step.

    Use as a context manager (or call :meth:`close`): the units stay loaded between runs; each
    :meth:`run` after the first resets them (``fmi2Reset``) and starts again.

    Parameters
    ----------
    ram_fmu : str or pathlib.Path
        Path of the Ram ``.fmu`` file (DESIGN.md interface).
    anvil_fmu : str or pathlib.Path
        Path of the Anvil ``.fmu`` file (DESIGN.md interface).
    pile_fmu : str or pathlib.Path
        Path of the PileSoil ``.fmu`` file (DESIGN.md interface).
    parameters : dict of str to dict, optional
        ``{"ram": {...}, "anvil": {...}, "pile": {...}}`` parameter values set on each unit
        before initialization (SI units; see each FMU's modelDescription).
    debug_logging : bool, default False
        Forward the units' informational messages too (errors always are).

    Raises
    ------
    CosimulationError
        If ``parameters`` names an unknown unit.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """

    def __init__(self, ram_fmu: str | Path, anvil_fmu: str | Path, pile_fmu: str | Path,
                 parameters: dict[str, dict[str, Any]] | None = None,
                 debug_logging: bool = False):
        from fmpy import calloc, free
        from fmpy.fmi2 import (
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
        )

        parameters = dict(parameters or {})
        unknown = set(parameters) - set(UNITS)
        if unknown:
            raise CosimulationError(f"parameters: unknown units {sorted(unknown)} (use {UNITS})")
        self.parameters = {role: dict(parameters.get(role, {})) for role in UNITS}
        if not hasattr(self, "exchange"):
            self.exchange = "design"
        self._pile_names = PILE_OUTPUTS
        self.messages: dict[str, list[str]] = {role: [] for role in UNITS}
        self.debug_logging = debug_logging
        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        try:  # fmpy's C proxy formats the printf-style message before it reaches _log
            from fmpy.logging import addLoggerProxy

            addLoggerProxy(ctypes.byref(self._callbacks))
        except Exception:  # noqa: BLE001 - without the proxy the raw message is logged
            pass
        self.units: dict[str, _Unit] = {}
        try:
            for role, path in zip(UNITS, (ram_fmu, anvil_fmu, pile_fmu), strict=True):
                self.units[role] = _Unit(role, Path(path), self._callbacks)
            ram, anvil, pile = (self.units[r] for r in UNITS)
            self._vr = {
                "ram_out": ram.references(RAM_OUTPUTS), "ram_in": ram.references(("F_toe",)),
                "pile_out": pile.references(PILE_OUTPUTS),
                "pile_in": pile.references(("F_head",)),
                "anvil_in": anvil.references(ANVIL_INPUTS),
                "anvil_out": anvil.references(ANVIL_OUTPUTS),
            }
        except BaseException:
            self.close()
            raise

    # ------------------------------------------------------------------ logging
    def _log(self, environment, instance_name, status, category, message) -> None:
        role = (instance_name or b"").decode(errors="replace")
        text = (message or b"").decode(errors="replace")
        if status >= 1 or self.debug_logging:
            self.messages.setdefault(role, []).append(text)

    def _raise(self, what: str, status: int) -> None:
        names = {2: "fmi2Discard", 3: "fmi2Error", 4: "fmi2Fatal"}
        log = "; ".join(f"{role}: {msg}" for role in UNITS for msg in self.messages[role])
        raise CosimulationError(f"{what} returned {names.get(status, status)}"
                                + (f" ({log})" if log else ""))

    # ------------------------------------------------------------------ run
    def initialize(self, start_time: float, stop_time: float | None) -> None:
        """Reset (after a run), set the parameters and initialize the three units.

        Parameters
        ----------
        start_time : float
            Start time of the experiment [s].
        stop_time : float or None
            Stop time of the experiment [s]; ``None``: not set.

        Raises
        ------
        CosimulationError
            If a unit returns fmi2Discard, fmi2Error or fmi2Fatal.
        """
        from fmpy.fmi1 import FMICallException

        for role in UNITS:
            unit = self.units[role]
            try:
                if unit.needs_reset:
                    unit.slave.reset()
                unit.needs_reset = True
                unit.set_parameters(self.parameters[role])
                unit.slave.setupExperiment(startTime=start_time, stopTime=stop_time)
                unit.slave.enterInitializationMode()
                unit.slave.exitInitializationMode()
            except FMICallException as exc:
                self._raise(f"{role} {exc.function}", exc.status)

    def run(self, n_steps: int, step_size: float, start_time: float = 0.0,
            progress: bool | None = None, record_every: int = 1) -> ChainResult:
        """Initialize and run ``n_steps`` communication steps of ``step_size``.

        Parameters
        ----------
        n_steps : int
            Number of communication steps [-], non-negative.
        step_size : float
            Communication step h [s], positive.
        start_time : float, default 0.0
            Start time [s].
        progress : bool or None, optional
            Show a tqdm progress bar (default: when ``n_steps`` >= 100000).
        record_every : int, default 1
            Keep every k-th step (the first and the last row are always kept).

        Returns
        -------
        ChainResult
            The time series (``n_steps // record_every + 1`` rows, plus the last step).

        Raises
        ------
        ValueError
            If ``n_steps``, ``step_size`` or ``record_every`` is out of range.
        CosimulationError
            If a unit returns fmi2Discard, fmi2Error or fmi2Fatal.
        """
        _check_run(n_steps, step_size, record_every)
        for log in self.messages.values():
            log.clear()
        h = float(step_size)
        t0 = float(start_time)
        self.initialize(t0, t0 + n_steps * h)
        from tqdm import tqdm

        if progress is None:
            progress = n_steps >= 100_000
        rows = list(range(0, n_steps + 1, record_every))
        if rows[-1] != n_steps:
            rows.append(n_steps)
        data = np.full((len(rows), len(BLOW_ROW)), np.nan)
        with tqdm(total=n_steps, unit="step", disable=not progress, mininterval=0.5) as bar:
            wall = self._loop(n_steps, h, 0, t0, record_every, data, bar, record_last=True)
        columns = [BLOW_ROW.index(name) for name in
                   RAM_OUTPUTS + PILE_OUTPUTS + ANVIL_OUTPUTS]
        table = np.empty((len(rows), len(COLUMNS)))
        table[:, 0] = t0 + np.asarray(rows, dtype=float) * h
        table[:, 1:] = data[:, columns]
        return ChainResult(data=table, wall_time=wall, n_steps=n_steps,
                           messages={r: list(m) for r, m in self.messages.items()})

    def _loop(self, n_steps, h, n_offset, t0, record_every, data, bar,
              record_last: bool = False) -> float:
        """Run THE step loop (:func:`_master_loop`, compiled) in the exchange order of
        ``self.exchange`` (DESIGN.md order, or Jacobi); returns its wall time [s].

        Rows n with n % record_every == 0 (and the last, with ``record_last``) of the exchange
        row (:data:`BLOW_ROW`, absent pile outputs NaN) go into ``data``; time is
        t0 + (n_offset + n) h from the step count. The loop calls the units' FMI functions
        directly from machine code: the same calls, arguments and order as through fmpy's
        ctypes functions, so the same numbers, without the interpreter's share of the cost.
        """
        functions = []
        for role in UNITS:
            dll = self.units[role].slave.dll
            functions += [_FMI_GET(ctypes.cast(dll.fmi2GetReal, ctypes.c_void_p).value),
                          _FMI_SET(ctypes.cast(dll.fmi2SetReal, ctypes.c_void_p).value),
                          _FMI_STEP(ctypes.cast(dll.fmi2DoStep, ctypes.c_void_p).value)]
        components = [self.units[role].slave.component for role in UNITS]
        vr = self._vr
        refs = [ctypes.addressof(vr[k]) for k in ("ram_out", "ram_in", "pile_out", "pile_in",
                                                   "anvil_in", "anvil_out")]
        counts = np.array([len(RAM_OUTPUTS), len(self._pile_names), len(ANVIL_OUTPUTS)],
                          dtype=np.int64)
        row = np.full(len(BLOW_ROW), np.nan)
        jacobi = self.exchange == "jacobi"
        chunk = max(1000, (n_steps + 1) // 50)
        arguments = (*functions, *components, *refs, counts, _OFFSETS, row, data)
        # compile (or load from numba's cache) outside the timed stepping: an empty range
        _master_loop(0, 0, n_steps, n_offset, h, t0, record_every, record_last, jacobi,
                     *arguments)
        start = time.perf_counter()
        for first in range(0, n_steps + 1, chunk):
            last = min(first + chunk, n_steps + 1)
            code = _master_loop(first, last, n_steps, n_offset, h, t0, record_every,
                                record_last, jacobi, *arguments)
            if code != 0:
                n = abs(code) - 1
                self._diagnose(n_offset + n, h, t0, "exchange" if code > 0 else "step")
            bar.update(min(last, n_steps) - min(first, n_steps))
        return time.perf_counter() - start

    def _diagnose(self, n: int, h: float, t0: float, phase: str) -> None:
        raise CosimulationError(
            f"the {phase} at t = {t0 + n * h:.9g} s (step {n}) failed: "
            + "; ".join(f"{role}: {msg}" for role in UNITS for msg in self.messages[role]))

    # ------------------------------------------------------------------ cleanup
    def close(self) -> None:
        """Terminate and free the units, delete their extracted files."""
        units, self.units = getattr(self, "units", {}), {}
        for unit in units.values():
            unit.close()

    def __enter__(self) -> ChainMaster:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


# ================================================================================ blows


@dataclass
class BlowRecord:
    """One blow of :meth:`BlowMaster.run`: ``data[:, j]`` is ``BLOW_ROW[j]`` [SI] at ``time``.

    Parameters
    ----------
    time : numpy.ndarray
        The blow's own time (t0 + n h, the first contact at 0) [s]; ``global_start`` is the
        start of the blow in the FMUs' continuous time.
    data : numpy.ndarray
        The exchange rows, shape (rows, ``len(BLOW_ROW)``) [SI].
    global_start : float
        Start of the blow in the FMUs' continuous time [s].
    pile_head_start : float
        ``u_head`` at the start of the blow (the anvil rested there) [m].
    contact_displacement : float
        The anvil top face at rest, where the ram's toe first touches [m].
    wall_time : float
        Wall time of the stepping loop alone [s].
    n_steps : int
        Steps of the blow [-].
    """

    time: np.ndarray
    data: np.ndarray
    global_start: float
    pile_head_start: float
    contact_displacement: float
    wall_time: float
    n_steps: int

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[:, BLOW_ROW.index(name)]

    @property
    def microseconds_per_step(self) -> float:
        """Wall time of the stepping loop per 3-unit step [us].

        Returns
        -------
        float
            Wall time per step [us].
        """
        return 1e6 * self.wall_time / max(self.n_steps, 1)


class BlowMaster(ChainMaster):
    """Consecutive blows of Ram, Anvil and PileSoil FMUs (the fmpy master of ``run_fmi``).

    Each blow mirrors the in-process engine (:class:`anvilwave.engine.direct.Engine`): the
    pile/soil unit
    lives on (permanent set, soil state, motion), the anvil is reset and rests on the pile head
    where the previous blow left it (its ``initial_pile_head_displacement`` parameter is the
    pile's ``u_head`` at the start of the blow), and the ram is reset and starts in free
    flight at its impact velocity so that its toe reaches the anvil's top face (``u_top``
    read from the anvil at rest, the ram's ``contact_displacement``) half a step after the
    start (``contact_time``; the ram's ``contact_mid_step`` would do the same, but the engine
    computes the start as start + h/2, and so does this master, to the bit). Time runs on
    continuously over the blows in the FMUs, T = t0 + (k N + n) h for step n of blow k (from
    the step count); each blow's own time is t0 + n h with the first contact at 0, as in the engine.

    The master sets ``initial_pile_head_displacement`` (anvil), ``contact_displacement``,
    ``contact_time`` and ``contact_mid_step`` (ram) itself unless given.

    Parameters
    ----------
    ram_fmu : str or pathlib.Path
        Path of the Ram ``.fmu`` file, as :class:`ChainMaster`.
    anvil_fmu : str or pathlib.Path
        Path of the Anvil ``.fmu`` file, as :class:`ChainMaster`.
    pile_fmu : str or pathlib.Path
        Path of the PileSoil ``.fmu`` file, as :class:`ChainMaster`.
    parameters : dict of str to dict, optional
        Parameter values of each unit, as :class:`ChainMaster`.
    debug_logging : bool, default False
        Forward the units' informational messages too, as :class:`ChainMaster`.
    exchange : {"design", "jacobi"}, default "design"
        ``"design"``, the DESIGN.md step order above; ``"jacobi"``, the exchange of the common
        fixed-step masters (libcosim's): every unit steps, then every output is read and passed
        on, so the anvil's forces, read right after its step, are those of its inputs of the
        step before (a one-step lag through its feedthrough). Only for comparing with such
        masters: the lag makes the stiff contacts lose accuracy (and energy balance) at the
        engine's step; the anvil's ``input_extrapolation`` parameter
        (:mod:`anvilwave.fmu.coupling`, set by ``system.ssp``) makes up for it.

    Raises
    ------
    ValueError
        If ``exchange`` is not one of ``EXCHANGES``.
    """

    EXCHANGES = ("design", "jacobi")

    def __init__(self, ram_fmu, anvil_fmu, pile_fmu, parameters=None, debug_logging=False,
                 exchange: str = "design"):
        if exchange not in self.EXCHANGES:
            raise ValueError(f"exchange must be one of {self.EXCHANGES}, got {exchange!r}")
        self.exchange = exchange
        super().__init__(ram_fmu, anvil_fmu, pile_fmu, parameters, debug_logging)
        try:
            pile = self.units["pile"]
            self._pile_names = PILE_OUTPUTS + tuple(n for n in PILE_EXTRA_OUTPUTS
                                                    if n in pile.variables)
            if len(self._pile_names) not in (len(PILE_OUTPUTS),
                                             len(PILE_OUTPUTS) + len(PILE_EXTRA_OUTPUTS)):
                self._pile_names = PILE_OUTPUTS
            self._vr["pile_out"] = pile.references(self._pile_names)
        except BaseException:
            self.close()
            raise

    # ------------------------------------------------------------------ set-up
    def _start_unit(self, role: str, values: dict, start: float, stop: float) -> None:
        from fmpy.fmi1 import FMICallException

        unit = self.units[role]
        try:
            if unit.needs_reset:
                unit.slave.reset()
            unit.needs_reset = True
            unit.set_parameters(values)
            unit.slave.setupExperiment(startTime=start, stopTime=stop)
            unit.slave.enterInitializationMode()
            unit.slave.exitInitializationMode()
        except FMICallException as exc:
            self._raise(f"{role} {exc.function}", exc.status)

    def _get(self, role: str, names) -> list[float]:
        from fmpy.fmi1 import FMICallException

        unit = self.units[role]
        try:
            return unit.slave.getReal([unit.variables[n].valueReference for n in names])
        except FMICallException as exc:
            self._raise(f"{role} {exc.function}", exc.status)

    def _set(self, role: str, values: dict[str, float]) -> None:
        from fmpy.fmi1 import FMICallException

        unit = self.units[role]
        try:
            unit.slave.setReal([unit.variables[n].valueReference for n in values],
                               list(values.values()))
        except FMICallException as exc:
            self._raise(f"{role} {exc.function}", exc.status)

    def _has_parameter(self, role: str, name: str) -> bool:
        var = self.units[role].variables.get(name)
        return var is not None and var.causality == "parameter"

    def _start_blow(self, first: bool, start: float, stop: float, h: float,
                    total_stop: float) -> tuple[float, float]:
        """Start (or reset) the units for a blow; returns (pile head u, anvil top at rest)."""
        if first:
            self._start_unit("pile", self.parameters["pile"], start, total_stop)
        head = self._get("pile", ("u_head",))[0]
        anvil = dict(self.parameters["anvil"])
        if self._has_parameter("anvil", "initial_pile_head_displacement"):
            anvil.setdefault("initial_pile_head_displacement", head)
        self._start_unit("anvil", anvil, start, stop)
        # the anvil at rest on the pile head, the ram well clear of it: its top face
        self._set("anvil", {"u_ram": head - 1.0, "v_ram": 0.0, "u_pile": head, "v_pile": 0.0})
        top = self._get("anvil", ("u_top",))[0]
        ram = dict(self.parameters["ram"])
        if self._has_parameter("ram", "contact_displacement"):
            ram.setdefault("contact_displacement", top)
        if self._has_parameter("ram", "contact_mid_step"):
            ram.setdefault("contact_mid_step", False)  # the engine's: the contact at start + h/2
        if self._has_parameter("ram", "contact_time"):
            ram.setdefault("contact_time", start + 0.5 * h)
        self._start_unit("ram", ram, start, stop)
        return head, top

    # ------------------------------------------------------------------ run
    def run_blows(self, blows: int, n_steps: int, step_size: float,
                  start_time: float | None = None, record_every: int = 1,
                  progress: bool | None = None) -> list[BlowRecord]:
        """Run ``blows`` consecutive blows of ``n_steps`` steps of ``step_size``.

        Parameters
        ----------
        blows : int
            Number of blows [-], positive.
        n_steps : int
            Communication steps per blow [-], non-negative.
        step_size : float
            Communication step h [s], positive.
        start_time : float or None, optional
            t0 of each blow's own time [s] (default -h/2, the engine's: the first contact half
            a step after the start).
        record_every : int, default 1
            Keep the rows n with n % record_every == 0 (the engine's records).
        progress : bool or None, optional
            tqdm bar over all steps (default: when blows x n_steps >= 100000).

        Returns
        -------
        list of BlowRecord
            One record per blow.

        Raises
        ------
        ValueError
            If ``blows``, ``n_steps``, ``step_size`` or ``record_every`` is out of range.
        CosimulationError
            If a unit returns fmi2Discard, fmi2Error or fmi2Fatal.
        """
        if not (isinstance(blows, int) and blows >= 1):
            raise ValueError(f"blows must be a positive integer, got {blows!r}")
        _check_run(n_steps, step_size, record_every)
        from tqdm import tqdm

        for log in self.messages.values():
            log.clear()
        h = float(step_size)
        t0 = -0.5 * h if start_time is None else float(start_time)
        rows = np.arange(0, n_steps + 1, record_every)
        local_time = t0 + rows * h
        if progress is None:
            progress = blows * n_steps >= 100_000
        for unit in self.units.values():  # a fresh start: the pile is reset too
            if unit.needs_reset:
                unit.slave.reset()
                unit.needs_reset = False
        records = []
        with tqdm(total=blows * n_steps, unit="step", disable=not progress,
                  mininterval=0.5) as bar:
            for k in range(blows):
                start = t0 + (k * n_steps) * h
                head, top = self._start_blow(k == 0, start, t0 + (k + 1) * n_steps * h, h,
                                             t0 + blows * n_steps * h)
                data = np.full((len(rows), len(BLOW_ROW)), np.nan)
                wall = self._blow_loop(n_steps, h, k * n_steps, t0, record_every, data, bar)
                records.append(BlowRecord(local_time.copy(), data, start, head, top, wall,
                                          n_steps))
        return records

    def _blow_loop(self, n_steps, h, n_offset, t0, record_every, data, bar) -> float:
        """The stepping loop of one blow (:meth:`ChainMaster._loop`); its wall time [s]."""
        return self._loop(n_steps, h, n_offset, t0, record_every, data, bar)

# The FMI 2.0 functions of the loop as C function types numba can call:
# fmi2GetReal / fmi2SetReal(component, const unsigned vr[], size_t nvr, double value[]) and
# fmi2DoStep(component, double t, double h, int noSetFMUStatePriorToCurrentPoint).
_FMI_GET = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t,
                            ctypes.c_void_p)
_FMI_SET = _FMI_GET
_FMI_STEP = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_double, ctypes.c_double,
                             ctypes.c_int)


@njit(cache=True)
def _master_loop(first, last, n_steps, n_offset, h, t0, record_every, record_last, jacobi,
                 get_ram, set_ram, step_ram, get_anvil, set_anvil, step_anvil,
                 get_pile, set_pile, step_pile, c_ram, c_anvil, c_pile,
                 vr_ram_out, vr_ram_in, vr_pile_out, vr_pile_in, vr_anvil_in, vr_anvil_out,
                 counts, offsets, row, data):
    """Steps n = first .. last - 1 of a run (THE master loop; see ChainMaster, BlowMaster).

    DESIGN.md order (``jacobi`` False): at t_n the states of ram and pile go to the anvil and
    its contact forces are read; the forces go to ram and pile; every unit steps. Jacobi
    order (``jacobi`` True): after the exchange at t_0, every unit steps, then every output
    is read (the anvil's with its inputs of t_n) and passed on. Row n (the exchanged values
    at t_n) is recorded when n % record_every == 0, and row n_steps with ``record_last``.

    ``row`` is the exchange row (BLOW_ROW), read and written in place through its address;
    the value-reference arguments are addresses of unsigned arrays; ``offsets`` the row
    offsets of the pile outputs and of F_ram, F_pile (:data:`_OFFSETS`). Returns 0, or n + 1 when
    the exchange at t_n failed, -(n + 1) when the doStep from t_n did.
    """
    size = 8  # bytes per double
    base = row.ctypes.data
    p_pile = base + offsets[0] * size
    p_forces = base + offsets[1] * size
    p_force_pile = base + offsets[2] * size
    n_ram, n_pile, n_anvil = counts[0], counts[1], counts[2]
    for n in range(first, last):
        if n == 0 or not jacobi:
            # 1-2: states of ram and pile -> anvil -> contact forces at t_n
            status = (get_ram(c_ram, vr_ram_out, n_ram, base)
                      | get_pile(c_pile, vr_pile_out, n_pile, p_pile)
                      | set_anvil(c_anvil, vr_anvil_in, 4, base)
                      | get_anvil(c_anvil, vr_anvil_out, n_anvil, p_forces))
            if status > 1:  # statuses <= 1 (OK, warning) only ever set bit 0
                return n + 1
        if n % record_every == 0:
            data[n // record_every, :] = row
        elif record_last and n == n_steps:
            data[n_steps // record_every + 1, :] = row
        if n == n_steps:
            break
        # 3-4: forces to ram and pile, then every unit steps over [t_n, t_n + h]
        t = t0 + (n_offset + n) * h
        status = (set_ram(c_ram, vr_ram_in, 1, p_forces)
                  | set_pile(c_pile, vr_pile_in, 1, p_force_pile)
                  | step_ram(c_ram, t, h, 1)
                  | step_anvil(c_anvil, t, h, 1)
                  | step_pile(c_pile, t, h, 1))
        if status > 1:
            return -(n + 1)
        if jacobi:
            # every output read after the step, the anvil's with its inputs of t_n
            status = (get_ram(c_ram, vr_ram_out, n_ram, base)
                      | get_pile(c_pile, vr_pile_out, n_pile, p_pile)
                      | get_anvil(c_anvil, vr_anvil_out, n_anvil, p_forces)
                      | set_anvil(c_anvil, vr_anvil_in, 4, base))
            if status > 1:
                return n + 2
    return 0


def _check_run(n_steps, step_size, record_every) -> None:
    """Refuse a non-integer or negative step count, a non-positive step [s], a bad stride."""
    if not (isinstance(n_steps, int) and n_steps >= 0):
        raise ValueError(f"n_steps must be a non-negative integer, got {n_steps!r}")
    if not (np.isfinite(step_size) and step_size > 0.0):
        raise ValueError(f"step_size must be positive [s], got {step_size!r}")
    if not (isinstance(record_every, int) and record_every >= 1):
        raise ValueError(f"record_every must be a positive integer, got {record_every!r}")
