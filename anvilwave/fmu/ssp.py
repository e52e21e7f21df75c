"""The SSP 1.0 system description (``system.ssp``) of three FMUs.

:func:`write_ssp` writes an SSP 1.0 archive (``SystemStructure.ssd`` plus the FMUs under
``resources/``): the units, their connections (DESIGN.md interface, :data:`CONNECTIONS`) and
parameter values (``ssv:ParameterSet`` per component). ``DefaultExperiment`` carries the
Open Simulation Platform annotation (``osp:FixedStepAlgorithm``) with the base step in whole
nanoseconds (libcosim's time unit). Which step a system needs, and why it is finer than the
fmpy master's (a Jacobi master lags the contact forces by one step), is decided by the system
layer (:mod:`anvilwave.engine.fmus`). This module knows FMUs and parameters, not system files.
"""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from typing import Any

from anvilwave.fmu.fmi_build import UNIT_DEFINITIONS
from anvilwave.inputs import InputError

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
