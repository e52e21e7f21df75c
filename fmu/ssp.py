"""The FMUs of a system file and its SSP 1.0 system description (``system.ssp``).

:func:`build_system_fmus` (behind ``anvilwave build-fmus SYSTEM.toml --out DIR``) writes

- ``Ram.fmu``: the system's ram (its segments embedded as ``hammer.toml``), its impact
  velocity and gravity, the first contact at t = 0 on the anvil's top face at rest;
- ``Anvil.fmu``: the Mode Displacement Method anvil, the modal-data file of the system's anvil
  embedded, fmax, damping ratio, static correction and the contact springs of the system;
- ``AnvilLumped.fmu``: the rigid lumped-mass anvil (the FE mass) with the same contacts;
- ``PileSoil.fmu``: the system's ``[pile]`` and ``[soil]`` tables embedded, the anvil weight as
  the static head load;
- ``system.ssp``: an SSP 1.0 archive (``SystemStructure.ssd`` plus the three FMUs of the
  system's anvil model under ``resources/``): the units, their connections (DESIGN.md
  interface) and the parameter values of this system (``ssv:ParameterSet`` per component).
  ``DefaultExperiment`` spans one blow from t0 = -h/2 (h the engine's step; the first
  contact at t = 0) and carries the Open Simulation Platform annotation
  (``osp:FixedStepAlgorithm``) with the base step h / 64 in whole nanoseconds (libcosim's
  time unit). Why finer than h: a fixed-step Jacobi master (libcosim's) steps every unit and
  only then passes the outputs on, so the anvil's contact forces (a feedthrough) reach ram and
  pile computed from their displacements of one step before. That lag changes a contact force
  by up to k_c h v (contact spring k_c ~ 2-3e12 N/m for Table 1, closing speed v): at the
  engine's h the peak forces are off by tens of percent, at h / 64 by about 1% over the
  impact (first order in h). The DESIGN.md order of :class:`fmu.fmi_master.BlowMaster` has no
  such lag and runs at h. Every unit sub-steps internally, so any step is accepted.

Every value is the one the in-process engine uses (:func:`fmu.engine.build_engine`), so the FMU
chain driven by :func:`fmu.fmi_engine.run_fmi` reproduces the engine.
"""

from __future__ import annotations

import shutil
import tempfile
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from typing import Any

from anvil_rom.inputs import InputError

from .fmi_build import UNIT_DEFINITIONS, build_anvil_fmu, build_pile_soil_fmu, build_ram_fmu
from .system import SystemConfig

ANVIL_FMU = {"rom": "Anvil", "lumped": "AnvilLumped"}
"""FMU of each anvil model of a system file."""
CONNECTIONS = (
    ("Ram", "u_toe", "Anvil", "u_ram"),
    ("Ram", "v_toe", "Anvil", "v_ram"),
    ("PileSoil", "u_head", "Anvil", "u_pile"),
    ("PileSoil", "v_head", "Anvil", "v_pile"),
    ("Anvil", "F_ram", "Ram", "F_toe"),
    ("Anvil", "F_pile", "PileSoil", "F_head"),
)
"""(start component, output, end component, input) of the system (component names)."""

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}


def load_anvil_modal_data(cfg: SystemConfig, anvil_model=None):
    """The modal data of the system's anvil: ``anvil_model`` (a ModalData or a modal-data
    ``.npz`` path) or computed from the anvil file as the engine does."""
    from anvil_rom.modalfile import ModalData, load_modal_data

    if isinstance(anvil_model, ModalData):
        return anvil_model
    if anvil_model is not None:
        return load_modal_data(Path(anvil_model))
    if cfg.anvil.spec is None:
        raise InputError(cfg.source, "anvil.file", "the FMUs need the anvil geometry (the "
                                                   "Anvil and AnvilLumped units are built "
                                                   "from its modes)")
    from anvil_rom.pipeline import compute_anvil_modes

    return compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax).modal_data


def system_parameters(cfg: SystemConfig, modal) -> dict[str, dict[str, Any]]:
    """The FMU parameter values of a system (per FMU type), as the engine sets its units.

    Also returns, under ``"_rest"``, the anvil top face at rest [m] per anvil FMU.
    """
    from anvil_rom.rom import ModalAnvil
    from anvil_rom.unit import AnvilUnit, ContactParameters

    from .engine import contact_stiffnesses

    s = cfg.anvil
    k_ram, k_pile = contact_stiffnesses(cfg)
    contacts = {"ram_contact_stiffness": k_ram, "pile_contact_stiffness": k_pile,
                "ram_contact_damping": float(s.ram_contact_damping),
                "pile_contact_damping": float(s.pile_contact_damping),
                "gravity": float(cfg.gravity)}
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
           "contact_displacement": rest[kind][0], "contact_time": 0.0}
    pile = {"static_head_load": rest[kind][1], "gravity": float(cfg.gravity)}
    return {"Ram": ram, "Anvil": rom, "AnvilLumped": lumped, "PileSoil": pile, "_rest": rest}


SSP_STEP_DIVISOR = 64
"""The SSP's default fixed step is the engine's step over this (see the module docstring)."""


def build_system_fmus(cfg: SystemConfig, out_dir: str | Path, anvil_model=None, *,
                      time_step: float | None = None, ssp: bool = True) -> dict[str, Any]:
    """Write ``Ram.fmu``, ``Anvil.fmu``, ``AnvilLumped.fmu``, ``PileSoil.fmu`` and
    ``system.ssp`` for a system into ``out_dir`` (module docstring).

    anvil_model : precomputed modal data of the anvil (``ModalData`` or a ``.npz`` path);
        default: computed from the system's anvil file (as :func:`fmu.engine.build_engine`).
    time_step : master step h [s] (default: the engine's); the SSP's default experiment
        starts at -h/2 with the fixed step h / :data:`SSP_STEP_DIVISOR`.

    Returns ``{"Ram": path, "Anvil": path, "AnvilLumped": path, "PileSoil": path,
    "ssp": path, "anvil": "Anvil" or "AnvilLumped" (the system's anvil FMU),
    "parameters": {fmu type: {name: value}}, "time_step": h [s], "modal_data": ModalData,
    "anvil_rest": {anvil FMU type: (top face at rest [m], weight [N])}}``.
    The anvil model of the system must be "rom" or "lumped" (InputError otherwise).
    """
    from anvil_rom.modalfile import save_modal_data

    if cfg.anvil.model not in ANVIL_FMU:
        raise InputError(cfg.source, "anvil.model",
                         f"the FMI units model the anvil as 'rom' or 'lumped', not "
                         f"{cfg.anvil.model!r}")
    modal = load_anvil_modal_data(cfg, anvil_model)
    parameters = system_parameters(cfg, modal)
    rest = parameters.pop("_rest")
    if time_step is None:
        from .engine import build_engine

        time_step = build_engine(cfg, modal).time_step
    out_dir = Path(out_dir)
    result: dict[str, Any] = {"anvil": ANVIL_FMU[cfg.anvil.model], "parameters": parameters,
                              "time_step": float(time_step), "modal_data": modal,
                              "anvil_rest": rest}
    with tempfile.TemporaryDirectory(prefix="anvilwave_system_") as tmp:
        stem = cfg.anvil.spec.name if cfg.anvil.spec is not None else "anvil"
        modal_file = save_modal_data(modal, Path(tmp) / f"{stem}_modes.npz")
        result["Ram"] = build_ram_fmu(out_dir, cfg.hammer, **parameters["Ram"])
        result["Anvil"] = build_anvil_fmu(modal_file, out_dir, **parameters["Anvil"])
        result["AnvilLumped"] = build_anvil_fmu(modal_file, out_dir, lumped=True,
                                                **parameters["AnvilLumped"])
        result["PileSoil"] = build_pile_soil_fmu(out_dir, cfg.pile_soil,
                                                 **parameters["PileSoil"])
    if ssp:
        kind = result["anvil"]
        h = float(time_step)
        result["ssp"] = write_ssp(
            out_dir / "system.ssp",
            {"Ram": result["Ram"], "Anvil": result[kind], "PileSoil": result["PileSoil"]},
            {"Ram": parameters["Ram"], "Anvil": parameters[kind],
             "PileSoil": parameters["PileSoil"]},
            name=f"anvilwave {Path(cfg.source).stem}", start_time=-0.5 * h,
            stop_time=cfg.duration, step_size=h / SSP_STEP_DIVISOR)
    return result


# ---------------------------------------------------------------------------- SSP
def write_ssp(path: str | Path, fmus: dict[str, Path], parameters: dict[str, dict[str, Any]],
              name: str = "anvilwave", start_time: float = 0.0, stop_time: float | None = None,
              step_size: float | None = None) -> Path:
    """Write an SSP 1.0 archive of the Ram - Anvil - PileSoil system.

    fmus : component name ("Ram", "Anvil", "PileSoil") -> FMU file (copied into the archive's
        ``resources/``). parameters : component name -> parameter values of the
        component's ``ssv:ParameterSet``. start_time, stop_time [s]: the default experiment;
        step_size [s]: the OSP fixed-step annotation (rounded to whole nanoseconds).
    """
    from fmpy import read_model_description

    path = Path(path)
    for prefix, uri in NS.items():
        ET.register_namespace(prefix, uri)
    ssd, ssc, ssv, osp = (f"{{{NS[k]}}}" for k in ("ssd", "ssc", "ssv", "osp"))
    root = ET.Element(f"{ssd}SystemStructureDescription", {"version": "1.0", "name": name})
    system = ET.SubElement(root, f"{ssd}System", {
        "name": name, "description": "anvilwave impact pile driving: ram, anvil and pile/soil "
                                     "co-simulation units (DESIGN.md interface)"})
    elements = ET.SubElement(system, f"{ssd}Elements")
    used_units: set[str] = set()
    for component, fmu in fmus.items():
        md = read_model_description(str(fmu))
        variables = {v.name: v for v in md.modelVariables}
        element = ET.SubElement(elements, f"{ssd}Component", {
            "name": component, "type": "application/x-fmu-sharedlibrary",
            "source": f"resources/{Path(fmu).name}"})
        connectors = ET.SubElement(element, f"{ssd}Connectors")
        for var in md.modelVariables:
            if var.causality not in ("input", "output", "parameter"):
                continue
            connector = ET.SubElement(connectors, f"{ssd}Connector",
                                      {"name": var.name, "kind": var.causality})
            if var.description:
                connector.set("description", var.description)
            attrib = {}
            if var.type == "Real" and var.unit:
                attrib["unit"] = var.unit
                used_units.add(var.unit)
            ET.SubElement(connector, f"{ssc}{var.type}", attrib)
        values = parameters.get(component, {})
        if values:
            bindings = ET.SubElement(element, f"{ssd}ParameterBindings")
            binding = ET.SubElement(bindings, f"{ssd}ParameterBinding")
            holder = ET.SubElement(binding, f"{ssd}ParameterValues")
            pset = ET.SubElement(holder, f"{ssv}ParameterSet",
                                 {"version": "1.0", "name": f"{component} parameters"})
            plist = ET.SubElement(pset, f"{ssv}Parameters")
            for pname, value in values.items():
                var = variables.get(pname)
                if var is None or var.causality != "parameter":
                    raise InputError(str(fmu), pname, "is not a parameter of this FMU")
                parameter = ET.SubElement(plist, f"{ssv}Parameter", {"name": pname})
                ET.SubElement(parameter, f"{ssv}{var.type}", _ssv_value(var, value))
    connections = ET.SubElement(system, f"{ssd}Connections")
    for start, output, end, input_ in CONNECTIONS:
        if start in fmus and end in fmus:
            ET.SubElement(connections, f"{ssd}Connection", {
                "startElement": start, "startConnector": output,
                "endElement": end, "endConnector": input_})
    units = ET.SubElement(root, f"{ssd}Units")
    for unit in sorted(used_units):
        node = ET.SubElement(units, f"{ssc}Unit", {"name": unit})
        ET.SubElement(node, f"{ssc}BaseUnit", {k: str(e) for k, e in
                                               UNIT_DEFINITIONS.get(unit, {}).items()})
    attrib = {"startTime": repr(float(start_time))}
    if stop_time is not None:
        attrib["stopTime"] = repr(float(stop_time))
    experiment = ET.SubElement(root, f"{ssd}DefaultExperiment", attrib)
    if step_size is not None:
        step_ns = max(1, round(float(step_size) * 1e9))
        notes = ET.SubElement(experiment, f"{ssd}Annotations")
        note = ET.SubElement(notes, f"{ssc}Annotation", {"type": "com.opensimulationplatform"})
        algorithm = ET.SubElement(note, f"{osp}Algorithm")
        ET.SubElement(algorithm, f"{osp}FixedStepAlgorithm",
                      {"baseStepSize": repr(step_ns * 1e-9)})
    ET.indent(root, space="  ")
    xml = ET.tostring(root, encoding="UTF-8", xml_declaration=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    part = path.with_name(path.name + ".part")
    with zipfile.ZipFile(part, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("SystemStructure.ssd", xml)
        for fmu in fmus.values():
            zf.write(fmu, f"resources/{Path(fmu).name}")
    part.replace(path)
    return path


def _ssv_value(var, value) -> dict[str, str]:
    if var.type == "Real":
        return {"value": repr(float(value))}
    if var.type == "Boolean":
        return {"value": "true" if value else "false"}
    if var.type == "Integer":
        return {"value": str(int(value))}
    return {"value": str(value)}


def extract_ssp(path: str | Path, out_dir: str | Path) -> Path:
    """Unpack an SSP archive into ``out_dir`` (for tools that want a folder); returns it."""
    out_dir = Path(out_dir)
    if out_dir.exists():
        shutil.rmtree(out_dir)
    with zipfile.ZipFile(path) as zf:
        zf.extractall(out_dir)
    return out_dir
