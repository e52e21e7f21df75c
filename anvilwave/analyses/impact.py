"""Impact: one system's blows (the ``impact`` command), its summary as ``summary.json`` holds it,
the anvil's modes (``modes``) and the system's FMUs (``build-fmus``).

:func:`simulate` runs the blows with the in-process engine or through the FMUs and returns
:class:`Blow` results; :func:`summarise` is the blow's summary: peaks, stresses, transferred
energy, permanent set, the PDA quantities of the simulated gauges (:func:`pda_summary`) and the
energy balance (:func:`energy_balance`).
"""

from __future__ import annotations

import json
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.anvil_rom.fem.geometry import AnvilSpec, load_anvil
from anvilwave.anvil_rom.fem.modalfile import load_modal_data
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes as _compute
from anvilwave.config.system import SystemConfig
from anvilwave.config.system import load_system as _load_system
from anvilwave.engine.direct import build_engine
from anvilwave.engine.fmi import run_fmi
from anvilwave.engine.fmus import build_system_fmus
from anvilwave.inputs import InputError
from anvilwave.output.plots import plot_impact_blows
from anvilwave.output.tables import write_csv
from anvilwave.pile.kernels import SOIL_CAPACITY, SOIL_DASHPOT, SOIL_SMITH
from anvilwave.pile.pda.case_method import case_method, pile_impedance, transferred_energy

ENGINES = ("direct", "fmi")
"""``"direct"``: the in-process engine; ``"fmi"``: the four FMUs through the fmpy master."""


@dataclass
class Blow:
    """One simulated blow.

    Parameters
    ----------
    columns : dict
        Time series ``{"name [unit]": array}`` (the columns of ``impact.csv``).
    summary : dict
        The blow's ``summary.json`` entries (peaks [N], stresses [Pa], transferred energy [J],
        permanent set [m], energy balance, wall time [s] ...).
    energies : dict, optional
        Energy bookkeeping time series [J] (in-process engine only; empty otherwise).
    """

    columns: dict[str, np.ndarray]
    summary: dict[str, Any]
    energies: dict[str, np.ndarray] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]


def simulate(system: SystemConfig | str | Path, *, engine: str = "direct",
             anvil: str | None = None, modal_data=None, progress: bool = False) -> list[Blow]:
    """Simulate the blows of a system (``[simulation] blows`` consecutive blows).

    Parameters
    ----------
    system : SystemConfig, str or pathlib.Path
        A :class:`SystemConfig` (from :func:`load_system`) or the path of a system file.
    engine : {"direct", "fmi"}
        ``"direct"`` (in-process numba engine) or ``"fmi"`` (FMUs through fmpy; the FMUs
        are built in a temporary folder).
    anvil : str, optional
        Override the anvil model: ``"rom"``, ``"lumped"``, ``"classic"`` or ``"none"``.
    modal_data : ModalData or path, optional
        Precomputed modal data of the anvil (``ModalData`` or a ``modes.npz`` path), to
        skip the eigenvalue problem.
    progress : bool, default False
        Show a progress bar over the blows.

    Returns
    -------
    list of Blow
        The blows, in order.

    Raises
    ------
    ValueError
        If ``engine`` is unknown.
    InputError
        If the FMI engine is asked for an anvil model other than ``"rom"`` or ``"lumped"``.
    """

    cfg = system if isinstance(system, SystemConfig) else _load_system(system)
    if anvil is not None:
        cfg = cfg.with_anvil_model(anvil)
    if engine not in ENGINES:
        raise ValueError(f"engine must be one of {ENGINES}, got {engine!r}")
    if engine == "fmi":
        if cfg.anvil.model not in ("rom", "lumped"):
            raise InputError(str(cfg.source), "anvil.model",
                             f"the FMI engine has the 'rom' and 'lumped' anvil units, not "
                             f"{cfg.anvil.model!r}: use --engine direct")
        with tempfile.TemporaryDirectory(prefix="anvilwave-fmus-") as tmp:
            results = run_fmi(cfg, tmp, anvil_model=modal_data, progress=None)
    else:
        modal = modal_data
        if modal is not None and not hasattr(modal, "frequencies"):
            modal = load_modal_data(Path(modal))
        results = build_engine(cfg, modal).run(progress=progress)
    area = gauge_steel_area(cfg)
    return [Blow(columns=r.columns, summary=summarise(r, cfg, engine, cfg.anvil.model, area),
                 energies=getattr(r, "energies", None) or {})
            for r in results]


def compute_anvil_modes(anvil: str | Path | Any, fmax: float | None = None):
    """Free-free modes and the modal ROM data of an anvil (or any axisymmetric body).

    Parameters
    ----------
    anvil : str, pathlib.Path or AnvilSpec
        An anvil file (TOML, see the README) or an ``AnvilSpec``.
    fmax : float or None, default None
        Frequency content [Hz] (default: the file's ``[modes] fmax``).

    Returns
    -------
    AnvilModes
        With ``.modes.frequencies`` [Hz] (rigid-body mode first), ``.modal_data`` (the ROM's
        data; save it with :func:`save_modal_data`), ``.model`` (the FE model:
        ``.total_mass()`` [kg], ``.n_dof``) and ``.wall_time`` [s].
    """

    spec = anvil if isinstance(anvil, AnvilSpec) else load_anvil(anvil)
    return _compute(spec, fmax=fmax)


def build_fmus(system: SystemConfig | str | Path, out_dir: str | Path, *,
               anvil: str | None = None, modal_data=None, native_anvil: bool = True,
               native_units: bool | None = None, fmi_version: int = 2) -> dict[str, Any]:
    """Write the co-simulation FMUs and ``system.ssp`` of a system into ``out_dir``.

    ``Ram.fmu``, ``Anvil.fmu``, ``AnvilLumped.fmu``, ``PileSoil.fmu`` and ``system.ssp``.

    Parameters
    ----------
    system : SystemConfig, str or Path
        The system (or its file).
    out_dir : str or Path
        The folder the FMUs and ``system.ssp`` are written to.
    anvil : str, optional
        The anvil model instead of the system's.
    modal_data : ModalData or path, optional
        The anvil's modal data (default: from the cache or computed).
    native_anvil : bool
        The anvils in C (default; the shipped binaries), else with pythonfmu.
    native_units : bool, optional
        The Ram and PileSoil units: the shipped native binaries (True), pythonfmu (False), or
        native where they support the system and pythonfmu otherwise (None, default).
    fmi_version : int
        2 or 3 (FMI 3.0 Ram and PileSoil; the anvils stay FMI 2.0).

    Returns
    -------
    dict
        ``{"Ram": path, "Anvil": path, "AnvilLumped": path, "PileSoil": path, "ssp": path,
        "anvil": name of the system's anvil FMU, "parameters": {...}, "time_step": master
        step [s], "ssp_step": the step of system.ssp [s], and the implementation of each
        unit}`` (:func:`anvilwave.engine.fmus.build_system_fmus`).
    """
    cfg = system if isinstance(system, SystemConfig) else _load_system(system)
    if anvil is not None:
        cfg = cfg.with_anvil_model(anvil)
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    return build_system_fmus(cfg, out_dir, modal_data, native_anvil=native_anvil,
                             native_units=native_units, fmi_version=fmi_version)


def write_blows(blows: list[Blow], out, system: str, title: str = "") -> None:
    """Write the blows into a ResultWriter ``out``.

    ``impact.csv`` (``impact_blow<k>.csv`` for several blows), ``summary.json`` (the first
    blow's summary, with every blow's under ``"blows"``) and ``impact.png``.

    Parameters
    ----------
    blows : list of Blow
        The blows (:func:`simulate`).
    out : ResultWriter
        The writer (:mod:`anvilwave.output.writer`).
    system : str
        The system file, recorded in the summary (its name).
    title : str, default ""
        Title of the plot.
    """
    for i, blow in enumerate(blows):
        name = "impact.csv" if len(blows) == 1 else f"impact_blow{i + 1}.csv"
        write_csv(blow.columns, out.part(name))
    summary = dict(blows[0].summary)
    summary["system"] = Path(system).name
    if len(blows) > 1:
        summary["blows"] = [b.summary for b in blows]
    out.part("summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot_impact_blows(blows, out.part("impact.png"), title=title)


def gauge_steel_area(config) -> float:
    """Steel area of the pile section at the gauge depth of a system configuration.

    Parameters
    ----------
    config : SystemConfig
        The system.

    Returns
    -------
    float
        Steel area at the gauges [m^2].
    """
    depth = 0.0
    for section in config.pile_soil.pile.sections:
        depth += section.length
        if config.pile_soil.pile.gauge_depth <= depth:
            return section.area
    return config.pile_soil.pile.sections[-1].area


def summarise(result, config, engine: str, anvil_model: str, pile_area_at_gauge: float
              ) -> dict:
    """The summary.json content of one blow.

    Parameters
    ----------
    result : BlowResult
        The simulated blow.
    config : SystemConfig
        The system simulated.
    engine : str
        The engine that ran it (``"direct"`` or ``"fmi"``).
    anvil_model : str
        The anvil model.
    pile_area_at_gauge : float
        Steel area at the gauges [m^2], for the stresses.

    Returns
    -------
    dict
        The summary entries, named ``name [unit]``. Two transferred energies:
        ``"EMX [J]"`` (:func:`pda_summary`: the gauges zeroed at rest, as a PDA reports it)
        and ``"transferred_energy_unzeroed [J]"`` (the total gauge force, the weight at rest
        included; larger by that weight's work over the gauges' travel).
    """
    c = result.columns
    t = c["time [s]"]
    summary = {
        "engine": engine,
        "anvil_model": anvil_model,
        "impact_velocity [m/s]": config.impact_velocity,
        "peak_ram_anvil_force [N]": float(c["ram_anvil_force [N]"].max()),
        "peak_anvil_pile_force [N]": float(c["anvil_pile_force [N]"].max()),
        "peak_gauge_force [N]": float(c["gauge_force [N]"].max()),
        "peak_gauge_stress [Pa]": float(c["gauge_force [N]"].max() / pile_area_at_gauge),
        "peak_pile_compression_stress [Pa]": getattr(result, "pile_max_compression_stress",
                                                     None),
        "peak_pile_tension_stress [Pa]": getattr(result, "pile_max_tension_stress", None),
        "transferred_energy_unzeroed [J]": float(np.max(transferred_energy(
            t, c["gauge_force [N]"], c["gauge_velocity [m/s]"]))),
        "simulated_time [s]": float(t[-1] - t[0]),
        "time_step [s]": result.time_step,
        "n_steps": result.n_steps,
        "wall_time [s]": result.wall_time,
        "realtime_factor [-]": float((t[-1] - t[0]) / max(result.wall_time, 1e-12)),
    }
    # the toe's displacement over the window: the blow's permanent set once the pile has come
    # to rest (a window of some tens of ms); the same in both engines
    toe = c["pile_toe_displacement [m]"]
    summary["permanent_set [m]"] = float(toe[-1] - toe[0])
    final = getattr(result, "final_state", {})
    if "soil_offset" in final:
        # the toe soil's plastic offset gained in the blow (the set as the soil sees it)
        summary["toe_soil_set [m]"] = float(final["soil_offset"][-1]
                                            - final["soil_offset_start"][-1])
    # the Case method on the simulated gauge signals, as a PDA reports a blow

    try:
        summary.update(pda_summary(c, config))
    except (ValueError, KeyError):  # a record too short or without a velocity peak
        pass
    if getattr(result, "energies", None):
        summary["energy_balance"] = energy_balance(result)
    else:
        summary["note"] = ("the energy balance is computed by the in-process engine only (the "
                           "FMU interface exposes forces, motions and stress extremes)")
    return summary


def energy_balance(result) -> dict[str, float]:
    """Where the ram's energy went at the end of the blow [J], and the closing residual.

    Every term is the change from the start of the blow; gravity's work on ram, anvil and pile
    enters as the change of their potential energy. residual = final - initial total; relative
    to the ram's impact energy.

    Parameters
    ----------
    result : BlowResult
        A blow of the in-process engine (with its energy time series).

    Returns
    -------
    dict
        ``{name [J]: value}`` and the residual.
    """
    E = result.energies

    def change(name):
        return float(E[name][-1] - E[name][0])

    terms = {
        "ram_impact_energy [J]": result.input_energy,
        "ram_kinetic_and_strain [J]": change("ram_kinetic [J]") + change("ram_strain [J]"),
        "anvil_kinetic [J]": change("anvil_kinetic [J]"),
        "anvil_strain_contact_and_gravity [J]": change("anvil_potential [J]"),
        "pile_kinetic [J]": change("pile_kinetic [J]"),
        "pile_strain [J]": change("pile_strain [J]"),
        "soil_static_work [J]": change("soil_static_work [J]"),
        "soil_damping_work [J]": change("soil_damping_work [J]"),
        "pile_damping_work [J]": change("pile_damping_work [J]"),
        "contact_damping_work [J]": (change("contact_damping_work [J]")
                                     if "contact_damping_work [J]" in E else 0.0),
        "gravity_work_ram_and_pile [J]": (-change("ram_gravity_potential [J]")
                                          + change("pile_gravity_work [J]")),
    }
    total = total_energy(E)
    terms["residual [J]"] = float(total[-1] - total[0])
    terms["residual_relative [-]"] = terms["residual [J]"] / result.input_energy
    terms["max_deviation_relative [-]"] = float(np.abs(total - total[0]).max()
                                                / result.input_energy)
    return terms


def total_energy(E: dict[str, np.ndarray]) -> np.ndarray:
    """Total mechanical energy plus the work dissipated or stored in the soil [J] over time.

    Parameters
    ----------
    E : dict
        Energy bookkeeping time series ``{name: array}`` [J].

    Returns
    -------
    numpy.ndarray
        The total energy at each sample [J].
    """
    return (E["ram_kinetic [J]"] + E["ram_strain [J]"] + E["ram_gravity_potential [J]"]
            + E["anvil_kinetic [J]"] + E["anvil_potential [J]"]
            + E["pile_kinetic [J]"] + E["pile_strain [J]"] - E["pile_gravity_work [J]"]
            + E["soil_static_work [J]"] + E["soil_damping_work [J]"]
            + E["pile_damping_work [J]"] + E.get("contact_damping_work [J]", 0.0))


def case_damping_of_soil(cfg) -> float:
    """Case damping Jc [-] equivalent to a system's soil damping.

    The sum of the soil dashpots (Smith-viscous J R_u, a radiation dashpot, or Smith J R_u at
    full mobilisation) over the pile impedance at the gauges, i.e. Jc Z v = the soil's damping
    force when every spring moves with the same velocity v (the Case method lumps all damping at
    the toe).

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    float
        Case damping Jc [-].
    """
    arrays = cfg.pile_soil.arrays()
    dashpots = float(np.sum(arrays.soil[SOIL_DASHPOT]
                            + arrays.soil[SOIL_SMITH] * arrays.soil[SOIL_CAPACITY]))
    section = gauge_section(cfg)
    return dashpots / float(pile_impedance(section.youngs_modulus, section.area,
                                           section.wave_speed))


def gauge_section(cfg):
    """The pile section holding the gauges (the last section when they lie below it).

    Parameters
    ----------
    cfg : SystemConfig
        The system (its pile and gauge depth).

    Returns
    -------
    Section
        The section at the gauge depth (:class:`anvilwave.pile.pile.Section`).
    """
    pile = cfg.pile_soil.pile
    depth = 0.0
    for section in pile.sections:
        depth += section.length
        if pile.gauge_depth < depth:
            return section
    return pile.sections[-1]


def pda_summary(columns: dict[str, np.ndarray], cfg, *, case_damping: float | None = None
                ) -> dict:
    """EMX, FMX and RMX of a simulated blow, as a PDA would report them.

    The gauges are zeroed at rest as a PDA's are: the force at the first sample (the hammer
    and pile weights at rest) is subtracted. L is the pile length below the gauges, Z and c
    those of the section at the gauges. RMX needs the record to reach t1 + 2L/c; it is None
    when the blow is shorter.

    Parameters
    ----------
    columns : dict
        The blow's time series (``time [s]``, ``gauge_force [N]``, ``gauge_velocity [m/s]``).
    cfg : SystemConfig
        The ``SystemConfig`` simulated (pile, gauge depth, soil).
    case_damping : float or None, default None
        Jc [-] (default :func:`case_damping_of_soil`).

    Returns
    -------
    dict
        ``{"EMX [J]", "FMX [N]", "RMX [N]", "case_damping [-]"}``.
    """
    t = np.asarray(columns["time [s]"], dtype=float)
    force = np.asarray(columns["gauge_force [N]"], dtype=float)
    force = force - force[0]
    velocity = np.asarray(columns["gauge_velocity [m/s]"], dtype=float)
    pile = cfg.pile_soil.pile
    section = gauge_section(cfg)
    jc = case_damping_of_soil(cfg) if case_damping is None else float(case_damping)
    out = {"EMX [J]": float(np.max(transferred_energy(t, force, velocity))),
           "FMX [N]": float(np.max(force)), "RMX [N]": None, "case_damping [-]": jc}
    length = pile.length - pile.gauge_depth
    try:
        result = case_method(t, force, velocity, area=section.area,
                             elastic_modulus=section.youngs_modulus,
                             wave_speed=section.wave_speed, length_below_gauges=length,
                             case_damping=jc)
    except ValueError:  # shorter than t1 + 2L/c (or no velocity peak): no RMX
        return out
    out["RMX [N]"] = result.rmx
    return out
