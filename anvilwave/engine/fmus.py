"""The FMUs of a system file: the four units with the system's parameter values and
``system.ssp`` (the system layer's side of :mod:`anvilwave.fmu.ssp`, which knows no system files).

Anvil units. ``Anvil.fmu`` and ``AnvilLumped.fmu`` are native by default
(:func:`anvilwave.fmu.native_build.build_native_anvil_fmu`: C, no Python at run time, the
generic binaries shipped with anvilwave for Linux x86-64 and Windows x64, so that building
needs no C compiler, and the C sources inside, so that tools elsewhere can compile them);
``native_anvil=False`` (command line ``build-fmus --python-anvil``) builds the pythonfmu anvils
of :mod:`anvilwave.fmu.units.anvil` under the same names instead (same variables and value
references, same numbers to round-off). Without current shipped binaries ``native_anvil=True``
stops with an :class:`~anvilwave.inputs.InputError` naming the reason, and
``native_anvil=None`` falls back to the pythonfmu anvils with a warning. Ram and PileSoil are
pythonfmu units (they carry their anvilwave code and need a Python with numpy, scipy and numba;
their status shim runs them in C hosts: :mod:`anvilwave.fmu.fmi_build`) unless native.

Ram and PileSoil units. By default (``native_units=None``) ``Ram.fmu`` and ``PileSoil.fmu`` are
the native units of :mod:`anvilwave.fmu.native_units` (generic C binaries shipped with
anvilwave for Linux x86-64 and Windows x64, the model as a resource: no compiler needed to
build them, no Python to run them) when they support the system (a rod, rigid or modal ram;
any pile and soil) and their shipped binaries are built from the current sources.
Otherwise the pythonfmu unit is built, with a warning naming the reason; ``native_units=True``
makes that an :class:`~anvilwave.inputs.InputError`, ``False`` builds the pythonfmu units.
The native PileSoil fixes the pile and soil settings at the build (the pythonfmu unit also
takes them as parameters).

``system.ssp`` is for Jacobi-type masters (OSP libcosim, OMSimulator, fmpy's SSP runner: every
unit steps, then the outputs are exchanged, so the anvil's forces reach ram and pile one step
late). Its anvil has ``input_extrapolation`` on (:mod:`anvilwave.fmu.coupling`: the inputs
extrapolated to the unit's time, the ram toe's response to the force it holds included with
``ram_toe_mass``, :attr:`anvilwave.hammer.ram.RamRod.toe_mass`, the missed contact impulse
given back), and its fixed step is
the engine's step h over :data:`SSP_STEP_DIVISOR`, from -2.5 step (the engine's time axis: the
first contact at 0). Every parameter value of the SSP is also the FMUs' default (they are built
with them, ``input_extrapolation`` included: in the DESIGN.md order of the fmpy master it
changes no bit), so a tool that ignores the SSP's bindings runs the same system, and every
FMU's DefaultExperiment (native or pythonfmu) is the SSP's. The ram (native or pythonfmu)
places the first contact in the middle of the third step whatever the start time
(:mod:`anvilwave.fmu.units.ram`, ``anvilwave/fmu/native/ram_model.c``). Measured on Table 1
(modal ram) with libcosim at h/4: peak forces within 0.03 % (ROM anvil) and 0.07 % (lumped
anvil) of the fmpy master (DESIGN.md order) on the same step (docs/data/fmi_tools.json).
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path
from typing import Any

from anvilwave.anvil_rom.fem.modalfile import ModalData, load_modal_data, save_modal_data
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.stack import save_stack_data
from anvilwave.anvil_rom.unit import AnvilUnit, ContactParameters
from anvilwave.config.system import SystemConfig
from anvilwave.engine.direct import anvil_modal_data, build_engine, contact_stiffnesses
from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS
from anvilwave.fmu.fmi_build import (
    build_anvil_fmu,
    build_anvil_stack_fmu,
    build_pile_soil_fmu,
    build_ram_fmu,
)
from anvilwave.fmu.native_build import NativeBuildError, build_native_anvil_fmu
from anvilwave.fmu.native_units import (
    build_native_pile_soil_fmu,
    build_native_ram_fmu,
    native_ram_support,
    unit_binaries,
)
from anvilwave.fmu.ssp import ANVIL_FMU, write_ssp
from anvilwave.inputs import InputError


def load_anvil_modal_data(cfg: SystemConfig, anvil_model=None):
    """The modal data of the system's anvil.

    ``anvil_model`` (a ModalData or a modal-data ``.npz`` path) or that of the anvil file, from
    the modal-data cache as the engine takes it (:func:`anvilwave.config.cache.cached_modal_data`).

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    anvil_model : ModalData or path, optional
        Precomputed modal data (None: from the anvil file).

    Returns
    -------
    ModalData
        The anvil's modal data.

    Raises
    ------
    InputError
        If the system has no anvil geometry.
    """

    if isinstance(anvil_model, ModalData):
        return anvil_model
    if anvil_model is not None:
        return load_modal_data(Path(anvil_model))
    if cfg.anvil.spec is None:
        raise InputError(cfg.source, "anvil.file", "the FMUs need the anvil geometry (the "
                                                   "Anvil and AnvilLumped units are built "
                                                   "from its modes)")

    return anvil_modal_data(cfg)


def system_parameters(cfg: SystemConfig, modal) -> dict[str, dict[str, Any]]:
    """The FMU parameter values of a system (per FMU type), as the engine sets its units.

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    modal : ModalData
        The anvil's modal data.

    Returns
    -------
    dict
        ``{fmu type: {name: value}}``; also, under ``"_rest"``, the anvil top face at rest [m]
        per anvil FMU.
    """

    s = cfg.anvil
    k_ram, k_pile = contact_stiffnesses(cfg)
    contacts = {"ram_contact_stiffness": k_ram, "pile_contact_stiffness": k_pile,
                "ram_contact_damping": float(s.ram_contact_damping),
                "pile_contact_damping": float(s.pile_contact_damping),
                "gravity": float(cfg.gravity), "input_extrapolation": True,
                "ram_toe_mass": cfg.hammer.ram.toe_mass}
    rom = {**contacts, "fmax": float(s.fmax if s.fmax is not None else modal.fmax),
           "damping_ratio": float(s.damping_ratio if s.damping_ratio is not None
                                  else modal.damping_ratio),
           "static_correction": bool(s.static_correction)}
    lumped_mass = float(s.mass if s.mass is not None else modal.total_mass)
    lumped = {**contacts, "mass": lumped_mass}
    contact = ContactParameters(k_ram, k_pile, s.ram_contact_damping, s.pile_contact_damping)
    rest = {}
    for kind, anvil in (("Anvil", ModalAnvil.from_modal_data(
            modal, fmax=s.fmax, damping_ratio=s.damping_ratio,
            static_correction=s.static_correction, source=f"{cfg.source}: anvil")),
            ("AnvilLumped", ModalAnvil.rigid(lumped_mass))):
        rest[kind] = (float(AnvilUnit(anvil, contact, gravity=cfg.gravity).rest_on_pile(0.0)[0]),
                      float(anvil.total_mass * cfg.gravity))
    kind = ANVIL_FMU.get(s.model, "Anvil")
    ram = {"v_impact": float(cfg.impact_velocity), "gravity": float(cfg.gravity),
           "contact_displacement": rest[kind][0]}
    pile = {"static_head_load": rest[kind][1], "gravity": float(cfg.gravity)}
    return {"Ram": ram, "Anvil": rom, "AnvilLumped": lumped, "PileSoil": pile, "_rest": rest}


SSP_STEP_DIVISOR = 4
"""The SSP's fixed step is the engine's step over this (module docstring)."""
SSP_ANVIL_PARAMETERS = {"input_extrapolation": True}
"""Anvil parameters ``system.ssp`` needs (module docstring); the anvil FMUs are built with them
(:func:`system_parameters`), so that tools ignoring the SSP's bindings run them too."""


def build_system_fmus(cfg: SystemConfig, out_dir: str | Path, anvil_model=None, *,
                      time_step: float | None = None, ssp: bool = True,
                      native_anvil: bool | None = True,
                      native_units: bool | None = None,
                      fmi_version: int = 2) -> dict[str, Any]:
    """Write the FMUs and ``system.ssp`` of a system into ``out_dir`` (module docstring).

    ``Ram.fmu``, ``Anvil.fmu``, ``AnvilLumped.fmu``, ``PileSoil.fmu`` and ``system.ssp``.

    Parameters
    ----------
    cfg : SystemConfig
        The system; its anvil model must be "rom" or "lumped".
    out_dir : str or pathlib.Path
        The folder written to.
    anvil_model : ModalData or path, optional
        Precomputed modal data of the anvil (``ModalData`` or a ``.npz`` path); default:
        computed from the system's anvil file (as :func:`anvilwave.engine.direct.build_engine`).
    time_step : float or None, default None
        Master step h [s] (default: the engine's); the SSP's default experiment starts at
        -2.5 step (:data:`anvilwave.fmu.coupling.FIRST_CONTACT_STEPS` steps before the first
        contact) with the fixed step h / :data:`SSP_STEP_DIVISOR`.
    ssp : bool, default True
        Write ``system.ssp``.
    native_anvil : bool or None, default True
        True: native anvils (InputError without current shipped binaries); False: the
        pythonfmu anvils; None: native when the binaries are current, else pythonfmu with a
        warning.
    native_units : bool or None, default None
        Ram and PileSoil (module docstring): None native where supported, else pythonfmu
        with a warning; True native (InputError when not supported); False pythonfmu.
    fmi_version : int, default 2
        3 builds every unit as a native FMI 3.0 co-simulation unit (the same binaries and
        numbers); InputError when one of them cannot be native (the pythonfmu units are FMI
        2.0 only).

    Returns
    -------
    dict
        ``{"Ram": path, "Anvil": path, "AnvilLumped": path, "PileSoil": path, "ssp": path,
        "anvil": "Anvil" or "AnvilLumped" (the system's anvil FMU), "anvil_implementation",
        "ram_implementation", "pile_soil_implementation": "native" or "pythonfmu",
        "parameters": {fmu type: {name: value}}, "time_step": h [s], "ssp_step": [s],
        "modal_data": ModalData, "anvil_rest": {anvil FMU type: (top face at rest [m],
        weight [N])}}``.

    Raises
    ------
    InputError
        If the anvil model is not "rom" or "lumped", the system needs the in-process engine
        (a tube pile head, a ram face in annuli), ``fmi_version`` is not 2 or 3 (or 3 with a
        pythonfmu unit), or the native units asked for cannot be built.
    """

    if cfg.anvil.model not in ANVIL_FMU:
        raise InputError(cfg.source, "anvil.model",
                         f"the FMI units model the anvil as 'rom' or 'lumped', not "
                         f"{cfg.anvil.model!r}")
    if cfg.anvil.model == "rom" and cfg.anvil.pile_head != "rod":
        raise InputError(cfg.source, "anvil.pile_head",
                         f"{cfg.anvil.pile_head!r} runs in the in-process engine only (the anvil "
                         "FMUs put the rings on the 1D head): use the direct engine "
                         "(--engine direct, compare --rom-engine direct)")
    stack = cfg.anvil.stack if cfg.anvil.model == "rom" else None
    if stack is not None and stack.ram_annuli > 1:
        raise InputError(cfg.source, "anvil.ram_port_annuli",
                         f"the stack's ram face in {stack.ram_annuli} annuli runs in the "
                         "in-process engine only (Ram.fmu and AnvilStack.fmu have one toe "
                         "port): set ram_port_annuli = 1 for the FMUs")
    if cfg.anvil.model == "rom" and cfg.anvil.spec.interfaces.ram_annuli > 1:
        raise InputError(cfg.source, "anvil.ram_port_annuli",
                         "the ram face in annuli runs in the in-process engine only (Ram.fmu "
                         "and the anvil FMUs have one toe port): use the direct engine "
                         "(--engine direct, compare --rom-engine direct)")
    if fmi_version == 3:
        if native_anvil is False:
            raise InputError(cfg.source, "fmi_version", "FMI 3.0 anvils are the native anvils: "
                                                        "not with the pythonfmu anvils")
        native_anvil = True
    native = _native_anvil_wanted(native_anvil)  # before the modes: missing binaries first
    modal = load_anvil_modal_data(cfg, anvil_model)
    parameters = system_parameters(cfg, modal)
    rest = parameters.pop("_rest")
    unit = None
    if stack is not None:  # AnvilStack.fmu: the engine's stack at rest, its weight on the pile
        engine = build_engine(cfg, modal)
        time_step = engine.time_step if time_step is None else time_step
        unit = engine.anvil.unit
        c = unit.contact
        parameters["AnvilStack"] = {
            **parameters["Anvil"], "ram_contact_stiffness": c.ram_stiffness,
            "pile_contact_stiffness": c.pile_stiffness, "ram_contact_damping": c.ram_damping,
            "pile_contact_damping": c.pile_damping, "seat_friction": stack.seat_friction,
            "sleeve_friction": stack.sleeve_friction}
        for key in ("fmax", "damping_ratio", "static_correction"):  # the stack file's
            parameters["AnvilStack"].pop(key)
        rest["AnvilStack"] = (float(engine.anvil.u_top0), float(unit.total_mass * cfg.gravity))
        parameters["Ram"]["contact_displacement"] = rest["AnvilStack"][0]
        parameters["PileSoil"]["static_head_load"] = rest["AnvilStack"][1]
    if time_step is None:

        time_step = build_engine(cfg, modal).time_step
    out_dir = Path(out_dir)
    step = float(time_step) / SSP_STEP_DIVISOR
    result: dict[str, Any] = {"anvil": ANVIL_FMU[cfg.anvil.model] if unit is None
                              else "AnvilStack", "parameters": parameters,
                              "time_step": float(time_step), "ssp_step": step,
                              "modal_data": modal, "anvil_rest": rest,
                              "anvil_implementation": "native" if native else "pythonfmu"}
    if fmi_version not in (2, 3):
        raise InputError(cfg.source, "fmi_version", f"must be 2 or 3, got {fmi_version!r}")
    if fmi_version == 3:
        if native_units is False:
            raise InputError(cfg.source, "fmi_version", "FMI 3.0 units are the native Ram and "
                                                        "PileSoil: not with the pythonfmu units")
        native_units = True
    native_ram = _native_unit_wanted("Ram", native_units, native_ram_support(cfg.hammer.ram))
    native_pile = _native_unit_wanted("PileSoil", native_units, (True, ""))
    result["fmi_version"] = {"Ram": fmi_version, "PileSoil": fmi_version,
                             "Anvil": fmi_version, "AnvilLumped": fmi_version}
    result["ram_implementation"] = "native" if native_ram else "pythonfmu"
    result["pile_soil_implementation"] = "native" if native_pile else "pythonfmu"
    start = -FIRST_CONTACT_STEPS * step  # the first contact at 0 (module docstring)
    experiment = (start, float(cfg.duration), step)  # the SSP's
    with tempfile.TemporaryDirectory(prefix="anvilwave_system_") as tmp:
        stem = cfg.anvil.spec.name if cfg.anvil.spec is not None else "anvil"
        if native_ram:
            result["Ram"] = build_native_ram_fmu(cfg.hammer, out_dir / "Ram.fmu",
                                                 fmi_version=fmi_version,
                                                 default_experiment=experiment,
                                                 **parameters["Ram"])
        else:
            result["Ram"] = build_ram_fmu(out_dir, cfg.hammer, default_experiment=experiment,
                                          **parameters["Ram"])
        if native:

            result["Anvil"] = build_native_anvil_fmu(modal, out_dir / "Anvil.fmu",
                                                     fmi_version=fmi_version,
                                                     default_experiment=experiment,
                                                     **parameters["Anvil"])
            result["AnvilLumped"] = build_native_anvil_fmu(modal, out_dir / "AnvilLumped.fmu",
                                                           lumped=True,
                                                           fmi_version=fmi_version,
                                                           default_experiment=experiment,
                                                           **parameters["AnvilLumped"])
        else:
            modal_file = save_modal_data(modal, Path(tmp) / f"{stem}_modes.npz")
            result["Anvil"] = build_anvil_fmu(modal_file, out_dir, default_experiment=experiment,
                                              **parameters["Anvil"])
            result["AnvilLumped"] = build_anvil_fmu(modal_file, out_dir, lumped=True,
                                                    default_experiment=experiment,
                                                    **parameters["AnvilLumped"])
        if unit is not None:
            stack_file = Path(tmp) / f"{stem}_stack.npz"
            save_stack_data(stack_file, unit)
            result["AnvilStack"] = build_anvil_stack_fmu(stack_file, out_dir,
                                                         default_experiment=experiment,
                                                         **parameters["AnvilStack"])
        if native_pile:
            result["PileSoil"] = build_native_pile_soil_fmu(cfg.pile_soil,
                                                            out_dir / "PileSoil.fmu",
                                                            fmi_version=fmi_version,
                                                            default_experiment=experiment,
                                                            **parameters["PileSoil"])
        else:
            result["PileSoil"] = build_pile_soil_fmu(out_dir, cfg.pile_soil,
                                                     default_experiment=experiment,
                                                     **parameters["PileSoil"])
    if ssp:
        kind = result["anvil"]
        result["ssp"] = write_ssp(
            out_dir / "system.ssp",
            {"Ram": result["Ram"], "Anvil": result[kind], "PileSoil": result["PileSoil"]},
            {"Ram": parameters["Ram"], "Anvil": parameters[kind],
             "PileSoil": parameters["PileSoil"]},
            name=f"anvilwave {Path(cfg.source).stem}", start_time=start,
            stop_time=cfg.duration, step_size=step)
    return result


def _native_anvil_wanted(native_anvil: bool | None) -> bool:
    """Whether to build the native anvils (module docstring); InputError when they are asked
    for and their shipped binaries are missing or not current."""
    if native_anvil is False:
        return False
    try:
        unit_binaries("Anvil")
    except NativeBuildError as exc:
        if native_anvil is None:
            warnings.warn(f"the native anvil FMUs cannot be built ({exc}): using the pythonfmu "
                          "anvils (the same numbers)", stacklevel=3)
            return False
        raise InputError("native Anvil FMU", "binaries",
                         f"{exc}; or build the pythonfmu anvils instead (anvilwave build-fmus "
                         "--python-anvil, build_system_fmus(native_anvil=False))") from None
    return True


def _native_unit_wanted(kind: str, native_units: bool | None,
                        support: tuple[bool, str]) -> bool:
    """Whether to build the native Ram or PileSoil (module docstring); InputError when it is
    asked for and does not support the system or has no current binaries."""
    if native_units is False:
        return False
    supported, reason = support
    if supported:
        try:
            unit_binaries(kind)
        except NativeBuildError as exc:
            supported, reason = False, str(exc)
    if supported:
        return True
    if native_units is None:
        warnings.warn(f"the native {kind} FMU is not used ({reason}): building the pythonfmu "
                      f"{kind} unit (it runs in a Python with numpy, scipy and numba)",
                      stacklevel=3)
        return False
    raise InputError(f"native {kind} FMU", "native_units",
                     f"{reason}; or build the pythonfmu unit (native_units=False)")
