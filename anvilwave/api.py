"""The public scripting API (``import anvilwave``).

Everything the command line does is a function here, so that a study is a few lines of Python
instead of a batch file around an executable::

    import anvilwave

    system = anvilwave.load_system("examples/table1.toml")
    for fmax in (3000.0, 5000.0):
        blow = anvilwave.simulate(system.with_fmax(fmax))[0]
        print(fmax, blow.summary["peak_anvil_pile_force [N]"])

Results carry the names and units of the files the command line writes: ``Blow.columns`` are
the columns of ``impact.csv`` (``"time [s]"``, ``"anvil_pile_force [N]"`` ...) and
``Blow.summary`` the entries of ``summary.json``. All values are SI.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.config.system import SystemConfig
from anvilwave.config.system import load_system as _load_system

ENGINES = ("direct", "fmi")
"""``"direct"``: the in-process engine; ``"fmi"``: the four FMUs through the fmpy master."""


@dataclass
class Blow:
    """One simulated blow.

    columns : time series ``{"name [unit]": array}`` (the columns of ``impact.csv``).
    summary : the blow's ``summary.json`` entries (peaks [N], stresses [Pa], transferred
        energy [J], permanent set [m], energy balance, wall time [s] ...).
    energies : energy bookkeeping time series [J] (in-process engine only; empty otherwise).
    """

    columns: dict[str, np.ndarray]
    summary: dict[str, Any]
    energies: dict[str, np.ndarray] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]


def load_system(path: str | Path) -> SystemConfig:
    """Read and validate a system file (TOML; keys documented in :mod:`anvilwave.config.schema`).

    Raises :class:`anvilwave.InputError` (one line: file, key, rule) on bad input.
    """
    return _load_system(path)


def simulate(system: SystemConfig | str | Path, *, engine: str = "direct",
             anvil: str | None = None, modal_data=None, progress: bool = False) -> list[Blow]:
    """Simulate the blows of a system (``[simulation] blows`` consecutive blows).

    Parameters
    ----------
    system : a :class:`SystemConfig` (from :func:`load_system`) or the path of a system file.
    engine : ``"direct"`` (in-process numba engine) or ``"fmi"`` (FMUs through fmpy; the
        FMUs are built in a temporary folder).
    anvil : override the anvil model: ``"rom"``, ``"lumped"``, ``"classic"`` or ``"none"``.
    modal_data : precomputed modal data of the anvil (``ModalData`` or a ``modes.npz`` path),
        to skip the eigenvalue problem.
    progress : show a progress bar over the blows.
    """
    from anvilwave.output.tables import gauge_steel_area, summarise

    cfg = system if isinstance(system, SystemConfig) else _load_system(system)
    if anvil is not None:
        cfg = cfg.with_anvil_model(anvil)
    if engine not in ENGINES:
        raise ValueError(f"engine must be one of {ENGINES}, got {engine!r}")
    if engine == "fmi":
        from anvilwave.engine.fmi import run_fmi

        with tempfile.TemporaryDirectory(prefix="anvilwave-fmus-") as tmp:
            results = run_fmi(cfg, tmp, anvil_model=modal_data, progress=None)
    else:
        from anvilwave.engine.direct import build_engine

        modal = modal_data
        if modal is not None and not hasattr(modal, "frequencies"):
            from anvilwave.anvil_rom.fem.modalfile import load_modal_data

            modal = load_modal_data(Path(modal))
        results = build_engine(cfg, modal).run(progress=progress)
    area = gauge_steel_area(cfg)
    return [Blow(columns=r.columns, summary=summarise(r, cfg, engine, cfg.anvil.model, area),
                 energies=getattr(r, "energies", None) or {})
            for r in results]


def compute_anvil_modes(anvil: str | Path | Any, fmax: float | None = None):
    """Free-free modes and the modal ROM data of an anvil (or any axisymmetric body).

    anvil : an anvil file (TOML, see the README) or an ``AnvilSpec``.
    fmax : frequency content [Hz] (default: the file's ``[modes] fmax``).

    Returns an ``AnvilModes`` with ``.modes.frequencies`` [Hz] (rigid-body mode first),
    ``.modal_data`` (the ROM's data; save it with :func:`save_modal_data`), ``.model`` (the
    FE model: ``.total_mass()`` [kg], ``.n_dof``) and ``.wall_time`` [s].
    """
    from anvilwave.anvil_rom.fem.geometry import AnvilSpec, load_anvil
    from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes as _compute

    spec = anvil if isinstance(anvil, AnvilSpec) else load_anvil(anvil)
    return _compute(spec, fmax=fmax)


def build_fmus(system: SystemConfig | str | Path, out_dir: str | Path, *,
               anvil: str | None = None, modal_data=None,
               native_anvil: bool = True) -> dict[str, Any]:
    """Write ``Ram.fmu``, ``Anvil.fmu``, ``AnvilLumped.fmu``, ``PileSoil.fmu`` and
    ``system.ssp`` of a system into ``out_dir`` (FMI 2.0 co-simulation).

    native_anvil : the anvils in C (default; needs a C compiler), else with pythonfmu
        (:func:`anvilwave.engine.fmus.build_system_fmus`).

    Returns ``{"Ram": path, "Anvil": path, "AnvilLumped": path, "PileSoil": path,
    "ssp": path, "anvil": name of the system's anvil FMU, "parameters": {...},
    "time_step": master step [s], "ssp_step": the step of system.ssp [s]}``.
    """
    from anvilwave.engine.fmus import build_system_fmus

    cfg = system if isinstance(system, SystemConfig) else _load_system(system)
    if anvil is not None:
        cfg = cfg.with_anvil_model(anvil)
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    return build_system_fmus(cfg, out_dir, modal_data, native_anvil=native_anvil)
