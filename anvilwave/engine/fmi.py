"""The FMI engine: a system file run as Ram, Anvil and PileSoil FMUs under the fmpy master.

:func:`run_fmi` is the ``--engine fmi`` counterpart of :meth:`anvilwave.engine.direct.Engine.run`
(``--engine direct``): it builds the system's FMUs
(:func:`anvilwave.engine.fmus.build_system_fmus`: the native anvil from its shipped binary, else
the pythonfmu anvil with a warning; Ram and PileSoil native where they support the system),
drives them with
:class:`anvilwave.fmu.fmi_master.BlowMaster` at the engine's time step (DESIGN.md step order,
consecutive blows as the engine: the pile keeps its permanent set and soil state, ram and
anvil restart) and returns per blow the engine's result columns
(:data:`anvilwave.engine.direct.COLUMNS`), so that both engines write identical outputs. The FMUs
run the engine's kernels with the engine's initialisation and sub-stepping, so the two
agree to round-off.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.config.system import SystemConfig
from anvilwave.engine.compilation import announce_compilation
from anvilwave.engine.direct import COLUMNS, build_engine
from anvilwave.engine.fmus import build_system_fmus
from anvilwave.fmu.fmi_master import BlowMaster, BlowRecord

ROLES = {"ram": "Ram", "pile": "PileSoil"}


@dataclass
class FmiBlowResult:
    """One blow of the FMI engine, in the shape of :class:`anvilwave.engine.direct.BlowResult`.

    Parameters
    ----------
    columns : dict
        ``{name: array}`` with the names of :data:`anvilwave.engine.direct.COLUMNS` (SI units).
    time_step : float
        Master step h [s].
    n_steps : int
        Steps of the blow [-].
    wall_time : float
        Wall time of the stepping loop alone [s].
    input_energy : float
        Kinetic energy of the ram at impact [J].
    messages : dict, optional
        ``{unit role: [message, ...]}``, the messages the FMUs logged.
    pile_max_compression_stress : float or None, default None
        The PileSoil unit's running compression stress extreme [Pa] at the end of the run
        (the pile unit lives through all blows: for one blow it is the blow's, as the engine
        reports it; with several, only the last blow carries it, over the whole run).
    pile_max_tension_stress : float or None, default None
        The PileSoil unit's running tension stress extreme [Pa], as
        ``pile_max_compression_stress``.
    """

    columns: dict[str, np.ndarray]
    time_step: float
    n_steps: int
    wall_time: float
    input_energy: float
    messages: dict[str, list[str]] = field(default_factory=dict)
    pile_max_compression_stress: float | None = None
    pile_max_tension_stress: float | None = None

    @property
    def microseconds_per_step(self) -> float:
        """Wall time of one 3-unit communication step [us]."""
        return 1e6 * self.wall_time / max(self.n_steps, 1)

    @property
    def real_time_factor(self) -> float:
        """Wall time of the stepping over the simulated time [-] (< 1: faster than real time)."""
        return self.wall_time / max(self.n_steps * self.time_step, 1e-300)


def engine_columns(record: BlowRecord) -> dict[str, np.ndarray]:
    """The columns of :data:`anvilwave.engine.direct.COLUMNS` from a blow of the FMU master.

    Anvil displacements are taken relative to the pile head's position at the start of the
    blow (where the anvil came to rest), as the engine reports them; a column the FMUs do not
    provide is NaN.

    Parameters
    ----------
    record : BlowRecord
        A blow recorded by the FMU master.

    Returns
    -------
    dict
        ``{name: numpy.ndarray}`` in SI units.
    """

    head = record.pile_head_start
    known = {
        "time [s]": record.time,
        "ram_anvil_force [N]": record["F_ram"],
        "anvil_pile_force [N]": record["F_pile"],
        "pile_head_velocity [m/s]": record["v_head"],
        "gauge_force [N]": record["F_gauge"],
        "gauge_velocity [m/s]": record["v_gauge"],
        "ram_toe_displacement [m]": record["u_toe"],
        "ram_toe_velocity [m/s]": record["v_toe"],
        "anvil_top_displacement [m]": record["u_top"] - head,
        "anvil_bottom_displacement [m]": record["u_bottom"] - head,
        "pile_head_displacement [m]": record["u_head_total"],
        "pile_toe_displacement [m]": record["u_pile_toe"],
    }
    nan = np.full(record.time.shape, np.nan)
    return {name: np.array(known.get(name, nan), dtype=float) for name in COLUMNS}


def run_fmi(cfg: SystemConfig, out_dir_for_fmus: str | Path, anvil_model=None, *,
            duration: float | None = None, record_interval: float | None = None,
            progress: bool | None = None, fmus: dict[str, Any] | None = None,
            parameters: dict[str, dict[str, Any]] | None = None,
            time_step: float | None = None,
            native_anvil: bool | None = None) -> list[FmiBlowResult]:
    """Simulate ``cfg.blows`` blows with the FMUs of the system; one result per blow.

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    out_dir_for_fmus : str or pathlib.Path
        Folder the FMUs and ``system.ssp`` are built into.
    anvil_model : ModalData or path, optional
        Precomputed modal data (``ModalData`` or ``.npz`` path) of the anvil.
    duration : float or None, default None
        Simulated time of a blow [s], as :meth:`anvilwave.engine.direct.Engine.run`
        (default: the file's).
    record_interval : float or None, default None
        Spacing of the recorded samples [s], as :meth:`anvilwave.engine.direct.Engine.run`
        (default: the file's).
    progress : bool or None, default None
        Progress bar (default: on for runs of 100000 steps or more).
    fmus : dict or None, default None
        The dict of an earlier :func:`anvilwave.engine.fmus.build_system_fmus` (skips the
        build).
    parameters : dict or None, default None
        ``{"ram" | "anvil" | "pile": {name: value}}`` FMU parameters to change.
    time_step : float or None, default None
        Master step h [s] (default: the engine's, ``build_engine(cfg).time_step``).
    native_anvil : bool or None, default None
        The anvil FMUs to build (``build_system_fmus``): None (default) native when the
        shipped binaries are current, else pythonfmu with a warning; True native; False
        pythonfmu.

    Returns
    -------
    list of FmiBlowResult
        One result per blow.
    """

    if fmus is None:
        fmus = build_system_fmus(cfg, out_dir_for_fmus, anvil_model, time_step=time_step,
                                 ssp=True, native_anvil=native_anvil)
        h = float(fmus["time_step"])
    elif time_step is None:  # the engine's step for this system (its anvil model may differ)

        h = float(build_engine(cfg, fmus["modal_data"]).time_step)
    else:
        h = float(time_step)
    duration = cfg.duration if duration is None else duration
    record_interval = cfg.output_interval if record_interval is None else record_interval
    n_steps = int(round(duration / h))
    record_every = 1 if record_interval is None else max(1, int(round(record_interval / h)))
    kind = {"rom": "Anvil", "lumped": "AnvilLumped"}.get(cfg.anvil.model, fmus["anvil"])
    if fmus["anvil"] == "AnvilStack":  # the system's stack (build_system_fmus)
        kind = "AnvilStack"

    announce_compilation()
    with BlowMaster(fmus["Ram"], fmus[kind], fmus["PileSoil"], parameters) as master:
        records = master.run_blows(cfg.blows, n_steps, h, record_every=record_every,
                                   progress=progress)
        messages = {role: list(log) for role, log in master.messages.items()}
        pile = master.units["pile"]
        names = ["max_compression_stress", "max_tension_stress"]
        extremes = (pile.slave.getReal(list(pile.references(names)))
                    if all(n in pile.variables for n in names) else [None, None])
    ram_mass = float(np.sum(cfg.hammer.ram.mass))
    v_impact = float((parameters or {}).get("ram", {}).get("v_impact", cfg.impact_velocity))
    results = [FmiBlowResult(columns=engine_columns(rec), time_step=h, n_steps=n_steps,
                             wall_time=rec.wall_time, input_energy=0.5 * ram_mass * v_impact**2,
                             messages=messages) for rec in records]
    results[-1].pile_max_compression_stress, results[-1].pile_max_tension_stress = extremes
    return results
