"""anvilwave: impact pile driving with a Mode Displacement Method anvil.

The system layer and public API. Scripting users (who would otherwise batch a closed program's
executable) work with a handful of functions, all SI, with the names and units of the files
the command line writes:

- :func:`load_system` - read and validate a system file (TOML);
- :func:`simulate` - run its blows with the in-process engine (``engine="direct"``) or the
  FMUs through fmpy (``engine="fmi"``); each :class:`Blow` has ``columns`` (``impact.csv``)
  and ``summary`` (``summary.json``);
- :func:`compute_anvil_modes` - free-free modes and modal ROM data of an anvil file;
- :func:`build_fmus` - the four FMI 2.0 units and ``system.ssp`` of a system;
- :class:`InputError` - every bad input, one line naming the file, the key and the rule.

Layers (DESIGN.md, enforced by import-linter): the physics packages ``anvilwave.anvil_rom``,
``hammer``,
``pile`` <- ``anvilwave.fmu`` (FMI units, FMU build, SSP, fmpy master) <- ``anvilwave`` (system
files,
engine, analyses, reports, plots, command line).
"""

from anvilwave.api import Blow, build_fmus, compute_anvil_modes, load_system, simulate
from anvilwave.config.system import SystemConfig
from anvilwave.inputs import InputError

__all__ = ["Blow", "InputError", "SystemConfig", "build_fmus", "compute_anvil_modes",
           "load_system", "simulate"]
