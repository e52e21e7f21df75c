"""anvilwave: impact pile driving with a Mode Displacement Method anvil.

The public API, all SI, with the names and units of the files the command line writes:

- :func:`load_system` - read and validate a system file (TOML);
- :func:`simulate` - its blows with the in-process engine (``engine="direct"``) or the FMUs
  through fmpy (``engine="fmi"``), each a :class:`Blow` (``impact``);
- :func:`drive`, :func:`compare_anvils` - driveability against the tip depth
  (:class:`DriveResult`);
- :func:`install` - blow-by-blow installation with fatigue (:class:`InstallResult`);
- :func:`pda`, :func:`match`, :func:`compare_pda` - gauge records: the Case method, signal
  matching, the paper's Fig. 4 and 5;
- :func:`batch` - a wind-farm campaign on dask (:class:`BatchResult`);
- :func:`compute_anvil_modes`, :func:`build_fmus` - the anvil's modes, the system's FMUs;
- :func:`report` - a result folder as one self-contained HTML file for a client;
- :class:`InputError` - every bad input, one line naming the file, the key and the rule.

Layers, bottom to top (enforced by import-linter): ``anvilwave.inputs`` <- ``anvil_rom``
<- ``hammer`` | ``pile`` <- ``fmu`` <- ``config`` <- ``engine`` <- ``fea`` <- ``output``
<- ``analyses`` <- ``api`` <- ``cli``.
"""

from anvilwave.api import (
    BatchResult,
    Blow,
    ComparePdaResult,
    DriveResult,
    InstallResult,
    MatchResult,
    PdaResult,
    SystemConfig,
    batch,
    build_fmus,
    compare_anvils,
    compare_pda,
    compute_anvil_modes,
    drive,
    install,
    load_system,
    match,
    pda,
    report,
    simulate,
)
from anvilwave.inputs import InputError
from anvilwave.output.writer import software_version as _software_version

__version__ = _software_version()
"""The version of the installed anvilwave."""

__all__ = ["BatchResult", "Blow", "ComparePdaResult", "DriveResult", "InputError",
           "InstallResult", "MatchResult", "PdaResult", "SystemConfig", "batch", "build_fmus",
           "compare_anvils", "compare_pda", "compute_anvil_modes", "drive", "install",
           "load_system", "match", "pda", "report", "simulate"]
