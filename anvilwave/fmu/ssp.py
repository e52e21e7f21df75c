"""The SSP 1.0 system description (``system.ssp``) of three FMUs.

:func:`write_ssp` writes an SSP 1.0 archive (``SystemStructure.ssd`` plus the FMUs under
``resources/``): the units, their connections (DESIGN.md interface, :data:`CONNECTIONS`) and
parameter values (``ssv:ParameterSet`` per component). The file is written for the SSP tools
that the tests run (OMSimulator, OSP libcosim, fmpy's SSP runner; ``docs/fmi.md``) to take
as it is:

- the model and system names are identifiers (:func:`ssp_identifier`: OMSimulator refuses
  anything else);
- ``ssd:DefaultExperiment`` gives start and stop time; the fixed master step is written in the
  two annotations the fixed-step masters read: OMSimulator's (``org.openmodelica``,
  ``oms:FixedStepMaster`` of the system) and Open Simulation Platform's
  (``osp:FixedStepAlgorithm``, in whole nanoseconds, libcosim's time unit);
- String parameters (file names, the hammer's and the soil model's names) get no connector and
  no binding: OMSimulator cannot import String connectors. The FMUs default to the values the
  build gave them; :func:`write_ssp` refuses a String value that differs from the FMU's
  default (it could not be carried);
- the bindings of the other parameters are written, but a tool that ignores them (fmpy's SSP
  runner) must get the same system: the FMUs are built with these values as their defaults
  (:func:`anvilwave.engine.fmus.build_system_fmus`), and :func:`write_ssp` checks that every
  bound value equals the FMU's start value unless ``require_defaults=False``.

Which step a system needs, and why it is finer than the
fmpy master's (a Jacobi master lags the contact forces by one step), is decided by the system
layer (:mod:`anvilwave.engine.fmus`). This module knows FMUs and parameters, not system files.
"""

from __future__ import annotations

import re
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
    "oms": "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd",
}


def ssp_identifier(name: str) -> str:
    """``name`` as an identifier (letters, digits, ``_``; not starting with a digit).

    The form OMSimulator requires of model, system and component names: ``"anvilwave table1"``
    -> ``"anvilwave_table1"``.

    Parameters
    ----------
    name : str
        Any name.

    Returns
    -------
    str
        The identifier (``"system"`` for a name with no letter or digit).
    """
    ident = re.sub(r"\W", "_", str(name), flags=re.ASCII).strip("_") or "system"
    return f"_{ident}" if ident[0].isdigit() else ident


# ---------------------------------------------------------------------------- SSP
def write_ssp(path: str | Path, fmus: dict[str, Path], parameters: dict[str, dict[str, Any]],
              name: str = "anvilwave", start_time: float = 0.0, stop_time: float | None = None,
              step_size: float | None = None, require_defaults: bool = True) -> Path:
    """Write an SSP 1.0 archive of the Ram - Anvil - PileSoil system.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.ssp`` file to write.
    fmus : dict of str to pathlib.Path
        Component name ("Ram", "Anvil", "PileSoil") -> FMU file (copied into the archive's
        ``resources/``).
    parameters : dict of str to dict
        Component name -> parameter values of the component's ``ssv:ParameterSet`` [SI].
    name : str, default "anvilwave"
        Name of the model and its system (made an identifier, :func:`ssp_identifier`).
    start_time : float, default 0.0
        Start time of the default experiment [s].
    stop_time : float or None, optional
        Stop time of the default experiment [s].
    step_size : float or None, optional
        The fixed master step of the OMSimulator and OSP annotations [s] (rounded to whole
        nanoseconds in both).
    require_defaults : bool, default True
        Every bound value must be the FMU's own start value, so that a tool ignoring the
        bindings runs the same system (module docstring). String values must always be the
        FMU's.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    InputError
        If a parameter is not one of its FMU, or a value differs from the FMU's start value
        where it must not.

    References
    ----------
    Modelica Association. System Structure and Parameterization (SSP), version 1.0.
    https://ssp-standard.org
    """
    from fmpy import read_model_description

    path = Path(path)
    for prefix, uri in NS.items():
        ET.register_namespace(prefix, uri)
    ssd, ssc, ssv, osp, oms = (f"{{{NS[k]}}}" for k in ("ssd", "ssc", "ssv", "osp", "oms"))
    name = ssp_identifier(name)
    step_ns = None if step_size is None else max(1, round(float(step_size) * 1e9))
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
            if var.causality not in ("input", "output", "parameter") or var.type == "String":
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
        values = {}
        for pname, value in parameters.get(component, {}).items():
            var = variables.get(pname)
            if var is None or var.causality != "parameter":
                raise InputError(str(fmu), pname, "is not a parameter of this FMU")
            default = _start_value(var)
            if var.type == "String" or require_defaults:
                if _ssv_value(var, value) != _ssv_value(var, default):
                    why = ("String parameters cannot be carried by an SSP (OMSimulator imports "
                           "no String connector)" if var.type == "String" else
                           "tools that ignore the SSP's bindings (fmpy's SSP runner) would run "
                           "the FMU's default")
                    raise InputError(str(fmu), pname,
                                     f"the system's value {value!r} differs from the FMU's "
                                     f"default {default!r}: {why}; build the FMU with it")
            if var.type != "String":
                values[pname] = value
        if values:
            bindings = ET.SubElement(element, f"{ssd}ParameterBindings")
            binding = ET.SubElement(bindings, f"{ssd}ParameterBinding")
            holder = ET.SubElement(binding, f"{ssd}ParameterValues")
            pset = ET.SubElement(holder, f"{ssv}ParameterSet",
                                 {"version": "1.0", "name": f"{component} parameters"})
            plist = ET.SubElement(pset, f"{ssv}Parameters")
            for pname, value in values.items():
                var = variables[pname]
                parameter = ET.SubElement(plist, f"{ssv}Parameter", {"name": pname})
                ET.SubElement(parameter, f"{ssv}{var.type}", _ssv_value(var, value))
    connections = ET.SubElement(system, f"{ssd}Connections")
    for start, output, end, input_ in CONNECTIONS:
        if start in fmus and end in fmus:
            ET.SubElement(connections, f"{ssd}Connection", {
                "startElement": start, "startConnector": output,
                "endElement": end, "endConnector": input_})
    if step_ns is not None:  # OMSimulator's fixed-step master (it reads no other annotation)
        notes = ET.SubElement(system, f"{ssd}Annotations")
        note = ET.SubElement(notes, f"{ssc}Annotation", {"type": "org.openmodelica"})
        info = ET.SubElement(ET.SubElement(note, f"{oms}Annotations"),
                             f"{oms}SimulationInformation")
        ET.SubElement(info, f"{oms}FixedStepMaster", {"description": "oms-ma",
                                                       "stepSize": repr(step_ns * 1e-9)})
    units = ET.SubElement(root, f"{ssd}Units")
    for unit in sorted(used_units):
        node = ET.SubElement(units, f"{ssc}Unit", {"name": unit})
        ET.SubElement(node, f"{ssc}BaseUnit", {k: str(e) for k, e in
                                               UNIT_DEFINITIONS.get(unit, {}).items()})
    attrib = {"startTime": repr(float(start_time))}
    if stop_time is not None:
        attrib["stopTime"] = repr(float(stop_time))
    experiment = ET.SubElement(root, f"{ssd}DefaultExperiment", attrib)
    if step_ns is not None:
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


def _start_value(var):
    """The start value of a parameter as Python value (fmpy gives it as its XML text)."""
    start = var.start
    if var.type == "Real":
        return float(start)
    if var.type == "Boolean":
        return start in (True, "true", "1", 1)
    if var.type == "Integer":
        return int(start)
    return "" if start is None else str(start)


def _ssv_value(var, value) -> dict[str, str]:
    if var.type == "Real":
        return {"value": repr(float(value))}
    if var.type == "Boolean":
        return {"value": "true" if value else "false"}
    if var.type == "Integer":
        return {"value": str(int(value))}
    return {"value": str(value)}


def extract_ssp(path: str | Path, out_dir: str | Path) -> Path:
    """Unpack an SSP archive into ``out_dir`` (for tools that want a folder).

    An existing ``out_dir`` is replaced.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.ssp`` archive.
    out_dir : str or pathlib.Path
        Folder to unpack into.

    Returns
    -------
    pathlib.Path
        ``out_dir``.
    """
    out_dir = Path(out_dir)
    if out_dir.exists():
        shutil.rmtree(out_dir)
    with zipfile.ZipFile(path) as zf:
        zf.extractall(out_dir)
    return out_dir
