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

# (FMU variable names read or written through the scratch row, in scratch order)
RAM_OUTPUTS = ("u_toe", "v_toe")
PILE_OUTPUTS = ("u_head", "v_head", "F_gauge", "v_gauge")
ANVIL_INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")
ANVIL_OUTPUTS = ("F_ram", "F_pile", "u_top", "u_bottom")

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
        """[s]"""
        return self["time"]

    @property
    def header(self) -> list[str]:
        """CSV header ``name [unit]``."""
        return [f"{n} [{u}]" for n, u in zip(self.names, self.units, strict=True)]

    @property
    def microseconds_per_step(self) -> float:
        """Wall time of the stepping loop per 3-unit step [us]."""
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

    Parameters
    ----------
    ram_fmu, anvil_fmu, pile_fmu : paths of the three ``.fmu`` files (DESIGN.md interfaces).
    parameters : ``{"ram": {...}, "anvil": {...}, "pile": {...}}`` parameter values set on each
        unit before initialization (SI units; see each FMU's modelDescription).
    debug_logging : forward the units' informational messages too (errors always are).

    Use as a context manager (or call :meth:`close`): the units stay loaded between runs; each
    :meth:`run` after the first resets them (``fmi2Reset``) and starts again.
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
        """Reset (after a run), set the parameters and initialize the three units."""
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
        """Initialize and run ``n_steps`` communication steps of ``step_size`` [s].

        progress : show a tqdm progress bar (default: when ``n_steps`` >= 100000).
        record_every : keep every k-th step (the first and the last row are always kept).
        Returns the time series (``n_steps // record_every + 1`` rows, plus the last step).
        """
        if not (isinstance(n_steps, int) and n_steps >= 0):
            raise ValueError(f"n_steps must be a non-negative integer, got {n_steps!r}")
        if not (np.isfinite(step_size) and step_size > 0.0):
            raise ValueError(f"step_size must be positive [s], got {step_size!r}")
        if not (isinstance(record_every, int) and record_every >= 1):
            raise ValueError(f"record_every must be a positive integer, got {record_every!r}")
        for log in self.messages.values():
            log.clear()
        h = float(step_size)
        t0 = float(start_time)
        self.initialize(t0, t0 + n_steps * h)
        rows = list(range(0, n_steps + 1, record_every))
        if rows[-1] != n_steps:
            rows.append(n_steps)
        data = np.empty((len(rows), len(COLUMNS)))
        start = time.perf_counter()
        self._loop(n_steps, h, t0, rows, data, progress)
        wall = time.perf_counter() - start
        data[:, 0] = t0 + np.asarray(rows, dtype=float) * h
        return ChainResult(data=data, wall_time=wall, n_steps=n_steps,
                           messages={r: list(m) for r, m in self.messages.items()})

    def _loop(self, n_steps, h, t0, rows, data, progress) -> None:
        from tqdm import tqdm

        ram, anvil, pile = (self.units[r].slave for r in UNITS)
        c_ram, c_anvil, c_pile = ram.component, anvil.component, pile.component
        get_ram, set_ram, step_ram = (getattr(ram.dll, f) for f in
                                      ("fmi2GetReal", "fmi2SetReal", "fmi2DoStep"))
        get_anvil, set_anvil, step_anvil = (getattr(anvil.dll, f) for f in
                                            ("fmi2GetReal", "fmi2SetReal", "fmi2DoStep"))
        get_pile, set_pile, step_pile = (getattr(pile.dll, f) for f in
                                         ("fmi2GetReal", "fmi2SetReal", "fmi2DoStep"))
        vr = self._vr
        vr_ram_out, vr_ram_in = vr["ram_out"], vr["ram_in"]
        vr_pile_out, vr_pile_in = vr["pile_out"], vr["pile_in"]
        vr_anvil_in, vr_anvil_out = vr["anvil_in"], vr["anvil_out"]
        # the scratch row: [u_toe, v_toe, u_head, v_head, F_gauge, v_gauge, F_ram, F_pile,
        # u_top, u_bottom]; each unit reads / writes its slice through a pointer into it
        scratch = (ctypes.c_double * (len(COLUMNS) - 1))()
        row = np.frombuffer(scratch, dtype=np.float64)
        base = ctypes.addressof(scratch)
        size = ctypes.sizeof(ctypes.c_double)

        def at(offset):
            return ctypes.cast(base + offset * size, ctypes.POINTER(ctypes.c_double))

        p_ram_out, p_pile_out, p_anvil_in = at(0), at(2), at(0)
        p_anvil_out, p_force_ram, p_force_pile = at(6), at(6), at(7)
        n_ram, n_pile, n_anvil = len(RAM_OUTPUTS), len(PILE_OUTPUTS), len(ANVIL_OUTPUTS)
        if progress is None:
            progress = n_steps >= 100_000
        chunk = max(1, (n_steps + 1) // 200)
        record = iter(rows)
        next_row = next(record)
        k = 0
        with tqdm(total=n_steps, unit="step", disable=not progress, mininterval=0.5) as bar:
            for first in range(0, n_steps + 1, chunk):
                last = min(first + chunk, n_steps + 1)
                for n in range(first, last):
                    # 1-2: states of ram and pile -> anvil -> contact forces at t_n
                    status = (get_ram(c_ram, vr_ram_out, n_ram, p_ram_out)
                              | get_pile(c_pile, vr_pile_out, n_pile, p_pile_out)
                              | set_anvil(c_anvil, vr_anvil_in, 4, p_anvil_in)
                              | get_anvil(c_anvil, vr_anvil_out, n_anvil, p_anvil_out))
                    if status > 1:  # statuses <= 1 (OK, warning) only ever set bit 0
                        self._diagnose(n, h, t0, "exchange")
                    if n == next_row:
                        data[k, 1:] = row
                        k += 1
                        next_row = next(record, -1)
                    if n == n_steps:
                        break
                    # 3-4: forces to ram and pile, then every unit steps over [t_n, t_n + h]
                    t = t0 + n * h
                    status = (set_ram(c_ram, vr_ram_in, 1, p_force_ram)
                              | set_pile(c_pile, vr_pile_in, 1, p_force_pile)
                              | step_ram(c_ram, t, h, 1)
                              | step_anvil(c_anvil, t, h, 1)
                              | step_pile(c_pile, t, h, 1))
                    if status > 1:
                        self._diagnose(n, h, t0, "step")
                bar.update(min(last, n_steps) - min(first, n_steps))

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
