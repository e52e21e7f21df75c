"""The public scripting API (``import anvilwave``).

Everything the command line does is a function here, so that a study is a few lines of Python
instead of a batch file around an executable::

    import anvilwave

    system = anvilwave.load_system("anvilwave/examples/table1.toml")
    for fmax in (3000.0, 5000.0):
        blow = anvilwave.simulate(system.with_fmax(fmax))[0]
        print(fmax, blow.summary["peak_anvil_pile_force [N]"])

Every analysis returns a documented result dataclass whose names and units are those of the
files the command line writes (``write(...)`` writes them): :class:`Blow` (``impact``),
:class:`DriveResult` (``drive``), :class:`InstallResult` (``install``), :class:`PdaResult`
(``pda``), :class:`MatchResult` (``match``), :class:`ComparePdaResult` (``compare-pda``) and
:class:`BatchResult` (``batch``). All values are SI. :func:`report` turns a result folder into
one self-contained HTML file for a client.
"""

from __future__ import annotations

from pathlib import Path

from anvilwave.analyses import drive as _drive
from anvilwave.analyses import install as _install
from anvilwave.analyses.batch import BatchResult, run_campaign
from anvilwave.analyses.drive import DriveResult
from anvilwave.analyses.impact import Blow, build_fmus, compute_anvil_modes, simulate
from anvilwave.analyses.install import InstallResult
from anvilwave.analyses.pda import (
    ComparePdaResult,
    MatchResult,
    PdaResult,
    compare_pda,
    match,
    pda,
)
from anvilwave.config.system import SystemConfig
from anvilwave.config.system import load_system as _load_system
from anvilwave.output.report import write_report

__all__ = ["Blow", "BatchResult", "ComparePdaResult", "DriveResult", "InstallResult",
           "MatchResult", "PdaResult", "SystemConfig", "batch", "build_fmus", "compare_anvils",
           "compare_pda", "compute_anvil_modes", "drive", "install", "load_system", "match",
           "pda", "report", "simulate"]


def load_system(path: str | Path) -> SystemConfig:
    """Read and validate a system file.

    Parameters
    ----------
    path : str or Path
        The system file (TOML; every key is documented in :mod:`anvilwave.config.schema`).

    Returns
    -------
    SystemConfig
        The validated system.

    Raises
    ------
    anvilwave.InputError
        One line naming the file, the key and the rule.
    """
    return _load_system(path)


def _system(system: SystemConfig | str | Path) -> SystemConfig:
    return system if isinstance(system, SystemConfig) else _load_system(system)


def drive(system: SystemConfig | str | Path, *, anvil: str | None = None,
          bound: str | None = None, workers: int | None = None,
          progress: bool = False, restrike: float | None = None) -> DriveResult:
    """Driveability against the tip depth (``anvilwave drive``).

    Parameters
    ----------
    system : SystemConfig, str or Path
        A system (or its file) with a ``[driveability]`` table.
    anvil : str, optional
        The anvil model instead of the system's (``"rom"``, ``"lumped"``, ``"classic"``,
        ``"none"``).
    bound : str, optional
        The SRD bound (``"lower"``, ``"best"``, ``"upper"``) instead of the table's.
    workers : int, optional
        Processes over the depths (default: the machine's cores).
    progress : bool
        A progress bar.
    restrike : float, optional
        A pause [h]: the restrike blow count after it at every depth (set-up of Skov & Denver
        1988 by soil type; columns ``restrike_blow_count [1/m]``, ``restrike_setup_factor [-]``).

    Returns
    -------
    DriveResult
        ``rows`` (the columns of driveability.csv), ``summary`` (summary.json) and the
        ``time_series`` of the chosen depths.
    """
    return _drive.drive(_system(system), anvil=anvil, bound=bound, workers=workers,
                        progress=progress, restrike=restrike)


def compare_anvils(system: SystemConfig | str | Path, *, bound: str | None = None,
                   workers: int | None = None, progress: bool = False
                   ) -> dict[str, DriveResult]:
    """Driveability with every anvil model the system has (``drive --compare-anvils``).

    The Mode Displacement Method anvil, the rigid lumped anvil and the classic driving system.

    Parameters
    ----------
    system : SystemConfig, str or Path
        A system (or its file) with a ``[driveability]`` table.
    bound : str, optional
        The SRD bound, as for :func:`drive`.
    workers : int, optional
        Processes over the depths, as for :func:`drive`.
    progress : bool, default False
        A progress bar, as for :func:`drive`.

    Returns
    -------
    dict
        ``{model: DriveResult}``.
    """
    return _drive.compare_anvils(_system(system), bound=bound, workers=workers,
                                 progress=progress)


def install(system: SystemConfig | str | Path, *, anvil: str | None = None,
            progress: bool = False) -> InstallResult:
    """Blow-by-blow installation with residual stresses, fatigue and spectra (``install``).

    Parameters
    ----------
    system : SystemConfig, str or Path
        A system (or its file) with ``[driveability]`` (energy schedule, refusal) and
        optionally ``[installation]``.
    anvil : str, optional
        The anvil model instead of the system's.
    progress : bool
        A progress bar.

    Returns
    -------
    InstallResult
        ``blows`` (blows.csv), ``fatigue`` (fatigue.csv), ``spectra`` (spectra.csv) and
        ``summary`` (summary.json).
    """
    return _install.install(_system(system), anvil=anvil, progress=progress)


def batch(campaign: str | Path, out_dir: str | Path, *, workers: int | None = None,
          scheduler=None, progress: bool = False, force: bool = False) -> BatchResult:
    """A campaign: the driveability of many positions, hammers and anvils (``anvilwave batch``).

    Run on dask. Resumable: cases finished in ``out_dir`` are not run again.

    Parameters
    ----------
    campaign : str or Path
        The campaign file (TOML).
    out_dir : str or Path
        The campaign folder (``cases/<case>/``, ``campaign.csv``, ``plots/``).
    workers : int, optional
        Worker processes of a local dask cluster (default: the machine's cores).
    scheduler : optional
        A running dask scheduler (address, cluster object or client) instead.
    progress : bool
        A progress bar over the cases.
    force : bool, default False
        Replace a folder holding another command's result (refused without it).

    Returns
    -------
    BatchResult
        The counts of cases run, skipped and by status, the timings and the campaign.csv rows.
    """
    return run_campaign(campaign, out_dir, workers=workers, scheduler=scheduler,
                        progress=progress, force=force)


def report(result_dir: str | Path, out: str | Path | None = None) -> Path:
    """The client report of a result folder: one self-contained HTML file (``report``).

    It formats what the folder holds (summaries, tables in practitioner units, the inputs
    with their SHA-256 hashes, every figure embedded) and runs no analysis
    (:mod:`anvilwave.output.report`).

    Parameters
    ----------
    result_dir : str or Path
        A folder written by ``impact``, ``drive``, ``install``, ``batch``, ``compare``,
        ``match``, ``pda`` or ``compare-pda`` (or their API ``write``).
    out : str or Path, optional
        The HTML file (default: ``report.html`` in ``result_dir``).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    anvilwave.InputError
        If ``result_dir`` holds no anvilwave result, or ``out`` cannot be written.
    """
    return write_report(result_dir, out)
