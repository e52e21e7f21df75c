"""The native units: generic C binaries, the model as a resource; the Ram and PileSoil FMUs.

Every native unit (Ram, PileSoil, and the anvils of :mod:`anvilwave.fmu.native_build`) is one
binary per unit kind and platform, compiled once from ``anvilwave/fmu/native/`` (the FMI 2.0
and 3.0 layers ``unit_fmu.c`` and ``unit_fmi3.c`` over the shared instance ``unit_core.c``,
``fmu_common.c``, and ``ram_model.c``, ``pile_soil_model.c`` or ``anvil_unit.c`` with
``anvil_model.c``) and shipped in ``anvilwave/fmu/native/binaries/<platform>/``. Every build
copies them into the FMU and writes what is particular to it into
``resources/anvilwave_unit.txt`` (the ``anvilwave-unit`` text format of
``anvilwave/fmu/native/fmu_common.h``: model identifier, GUID, parameter start values, the
kernel arrays as exact hexadecimal floats), so that building FMUs needs no C compiler and the
FMU runs on Linux x86-64 and Windows x64 without Python. The same binaries hold the FMI 3.0
co-simulation API: ``fmi_version=3`` packs them as an FMI 3.0 FMU.

The numerics are those of the Python kernels, operation for operation (``-ffp-contract=off``):
:func:`anvilwave.hammer.ram.ram_advance` and :func:`anvilwave.hammer.ram.stable_time_step` for
the rod ram, :func:`anvilwave.pile.kernels.pile_advance`, the output kernels and
:func:`anvilwave.pile.static.static_equilibrium` for the pile (tests/test_native_units.py
compares them). The variables are those of the pythonfmu units of the same kind
(:mod:`anvilwave.fmu.units.ram`, :mod:`anvilwave.fmu.units.pile_soil`) with the same value
references, less the parameters that name or rebuild the model (``hammer``,
``pile_soil_file`` and the pile and soil settings, which the kernel arrays fix at the build).
The modal ram (toe modes, :class:`anvilwave.hammer.modal_ram.ModalRamUnit`) runs natively too:
every mode exact over the step (its toe sum in the order of the C loop, where the numba kernel
may reassociate it: the two agree to rounding).

:func:`rebuild_binaries` compiles the shipped binaries from the sources (gcc for linux64,
x86_64-w64-mingw32-gcc for win64) and records the sources' SHA-256 beside them
(:data:`DIGEST_FILE`); the build refuses binaries whose recorded digest is not that of the
current sources (:func:`unit_binaries`). Run ``python -m anvilwave.fmu.native_units`` after
changing a C source.
"""

from __future__ import annotations

import ctypes
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import uuid
import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.hammer.database import load_hammer
from anvilwave.inputs import InputError
from anvilwave.pile.model import PileSoil, load_pile_soil

# ---------------------------------------------------------------------------- shared
NATIVE_DIR = Path(__file__).resolve().parent / "native"
"""The C sources and headers of the native anvil FMU."""

class NativeBuildError(RuntimeError):
    """The native FMU cannot be built here.

    No C compiler, an unsupported platform, the compiler failed, or the built FMU does not pass
    its check.
    """


UNITS: dict[str, dict[str, int]] = {
    "m": {"m": 1}, "m/s": {"m": 1, "s": -1}, "m/s2": {"m": 1, "s": -2},
    "N": {"kg": 1, "m": 1, "s": -2}, "N/m": {"kg": 1, "s": -2}, "N.s/m": {"kg": 1, "s": -1},
    "Hz": {"s": -1}, "kg": {"kg": 1}, "1": {},
}
"""SI base-unit exponents of the anvil's units (as in
:data:`anvilwave.fmu.fmi_build.UNIT_DEFINITIONS`)."""


DEFAULT_EXPERIMENT = (0.0, 0.02, 1e-5)
"""The ``DefaultExperiment`` (start, stop, step) [s] of a native FMU built without one (that of
the pythonfmu units' classes)."""


def default_experiment_values(default_experiment, source: str) -> tuple[float, float, float]:
    """(start, stop, step) of a ``default_experiment`` argument.

    Parameters
    ----------
    default_experiment : tuple of float or None
        (start, stop, step) [s]; None: :data:`DEFAULT_EXPERIMENT`.
    source : str
        Name of the source in error messages.

    Returns
    -------
    tuple of float
        (start, stop, step) [s].

    Raises
    ------
    InputError
        Unless start is finite, stop > start and step > 0.
    """
    if default_experiment is None:
        return DEFAULT_EXPERIMENT
    try:
        start, stop, step = (float(x) for x in default_experiment)
    except (TypeError, ValueError):
        start = stop = step = math.nan
    if not (math.isfinite(start) and math.isfinite(stop) and stop > start and
            math.isfinite(step) and step > 0.0):
        raise InputError(source, "default_experiment",
                         f"must be (start, stop > start, step > 0) [s], got "
                         f"{default_experiment!r}")
    return start, stop, step


def _zip(stage: Path, archive: Path) -> None:
    """The FMU archive of ``stage``: sorted entries with a fixed date (reproducible)."""
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted(p for p in stage.rglob("*") if p.is_file()):
            info = zipfile.ZipInfo(path.relative_to(stage).as_posix(), (1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = (0o755 if path.suffix == ".so" else 0o644) << 16
            zf.writestr(info, path.read_bytes())


def check_staged_fmu(archive: Path, stage: Path, model: str, guid: str, outputs: list[int],
                     *, run: bool = True, moment: str = "at the start") -> None:
    """fmpy's validation, then instantiate, initialize and step a staged FMU once.

    Skipped without fmpy (optional for building).

    Parameters
    ----------
    archive : pathlib.Path
        The ``.fmu``.
    stage : pathlib.Path
        The unpacked FMU (the folder the archive was made from).
    model : str
        Its model identifier.
    guid : str
        Its GUID.
    outputs : list of int
        Value references of the outputs that must be finite after initialization.
    run : bool
        Instantiate and step it (False: validation only, e.g. a binary for another
        platform).
    moment : str
        When the outputs are read, for the message (``"at rest"``, ``"at the start"``).

    Raises
    ------
    NativeBuildError
        If the FMU does not validate, instantiate or initialize, or its outputs are not
        finite.
    """
    try:
        from fmpy.fmi1 import FMICallException
        from fmpy.fmi2 import (
            FMU2Slave,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
        )
        from fmpy.logging import addLoggerProxy
        from fmpy.validation import validate_fmu
    except ImportError:  # fmpy is optional for building
        return
    from fmpy import calloc, free

    problems = validate_fmu(str(archive))
    if problems:
        raise NativeBuildError(f"{archive.name} does not validate: " + "; ".join(problems))
    if not run:
        return
    messages: list[str] = []
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(
        lambda env, name, status, category, message: messages.append(message.decode()))
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    addLoggerProxy(ctypes.byref(callbacks))
    fmu = FMU2Slave(guid=guid, unzipDirectory=str(stage), modelIdentifier=model,
                    instanceName="build_check")
    try:
        fmu.instantiate(callbacks=callbacks)
    except Exception as exc:  # noqa: BLE001 - reported with the FMU's own messages
        fmu.freeLibrary()
        raise NativeBuildError(f"{archive.name}: fmi2Instantiate failed ({exc}): "
                               + "; ".join(messages)) from None
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        values = fmu.getReal(outputs)
        fmu.doStep(0.0, 1e-5)
        fmu.terminate()
    except FMICallException as exc:
        raise NativeBuildError(f"{archive.name} does not initialize ({exc}): "
                               + "; ".join(messages)) from None
    finally:
        fmu.freeInstance()
    if not all(math.isfinite(x) for x in values):
        raise NativeBuildError(f"{archive.name}: outputs {moment} are not finite: {values}")


UNIT_KINDS = ("Ram", "PileSoil")
"""The unit kinds built here (the anvils: :mod:`anvilwave.fmu.native_build`)."""
BINARY_KINDS = ("Ram", "PileSoil", "Anvil")
"""The shipped binaries: one per kind and platform (``Anvil`` serves Anvil and AnvilLumped)."""
BINARY_OF = {"Ram": "Ram", "PileSoil": "PileSoil", "Anvil": "Anvil", "AnvilLumped": "Anvil"}
"""The binary of each model identifier."""
COMMON_SOURCES = ("unit_core.c", "unit_fmu.c", "unit_fmi3.c", "fmu_common.c")
"""The FMI layers and the instance shared by every native unit."""
MODEL_SOURCES = {"Ram": ("ram_model.c",), "PileSoil": ("pile_soil_model.c",),
                 "Anvil": ("anvil_unit.c", "anvil_model.c")}
UNIT_HEADERS = ("unit_core.h", "unit_model.h", "fmu_common.h", "fmi2Functions.h",
                "fmi2FunctionTypes.h", "fmi2TypesPlatform.h", "fmi3Functions.h",
                "fmi3FunctionTypes.h", "fmi3PlatformTypes.h")
MODEL_HEADERS = {"Ram": (), "PileSoil": (), "Anvil": ("anvil_model.h",)}
FMI3_PLATFORMS = {"linux64": "x86_64-linux", "win64": "x86_64-windows"}
"""The FMI 3.0 names of the binaries' folders (one binary holds the FMI 2.0 and 3.0 API)."""
RESOURCE = "anvilwave_unit.txt"
"""The unit's model in ``resources/`` (``anvilwave/fmu/native/fmu_common.h``)."""
RESOURCE_MAGIC = "anvilwave-unit 1"
BINARIES_DIR = NATIVE_DIR / "binaries"
"""The shipped binaries: ``<platform>/<kind>.so`` or ``.dll``."""
DIGEST_FILE = "SOURCES.sha256"
"""In :data:`BINARIES_DIR`: JSON ``{kind: SHA-256 of its sources}`` of the shipped binaries."""
WARNING_FLAGS = ("-Wall", "-Wextra", "-pedantic", "-Werror")
COMMON_FLAGS = ("-shared", "-O2", "-std=c99", "-ffp-contract=off", "-fno-fast-math", "-s")
PLATFORMS: dict[str, dict[str, Any]] = {
    "linux64": {"suffix": ".so", "compilers": ("gcc", "cc"),
                "flags": ("-fPIC", "-fvisibility=hidden"), "libs": ("-lm", "-Wl,-z,defs")},
    "win64": {"suffix": ".dll", "compilers": ("x86_64-w64-mingw32-gcc",),
              "flags": ("-static-libgcc", "-Wl,--disable-auto-image-base"),
              "libs": ("-lm",)},
}
"""The platforms of the shipped binaries: suffix, compilers (first found), extra flags."""
GENERATION_TOOL = "anvilwave fmu.native_units"
LICENSE = "MIT"
AUTHOR = "anvilwave contributors"


# ---------------------------------------------------------------------------- variables
@dataclass(frozen=True)
class UnitVariable:
    """A variable of a native unit: a Real, or a Boolean parameter.

    Parameters
    ----------
    name : str
        FMI variable name.
    vr : int
        Value reference (that of the pythonfmu unit).
    causality : {"parameter", "input", "output"}
        FMI causality.
    unit : str or None
        FMI unit; None for a Boolean parameter.
    description : str
        FMI variable description.
    type : {"Real", "Boolean"}, default "Real"
        FMI type (``"Boolean"`` for a Boolean parameter, ``unit`` None).
    """

    name: str
    vr: int
    causality: str  # "parameter", "input" or "output"
    unit: str | None
    description: str
    type: str = "Real"


VARIABLES: dict[str, tuple[UnitVariable, ...]] = {
    "Ram": (
        UnitVariable("v_impact", 1, "parameter", "m/s",
                     "Ram velocity at the first contact, positive down; 0 takes the hammer's "
                     "impact velocity at its rated energy [m/s]"),
        UnitVariable("mass", 2, "parameter", "kg",
                     "Ram mass; the segment masses are scaled to it; 0 keeps the hammer's "
                     "mass [kg]"),
        UnitVariable("gravity", 3, "parameter", "m/s2",
                     "Gravitational acceleration on the ram masses, 0 switches it off [m/s^2]"),
        UnitVariable("contact_displacement", 4, "parameter", "m",
                     "Toe displacement at the first contact (the anvil top face at rest), "
                     "positive down [m]"),
        UnitVariable("contact_time", 5, "parameter", "s",
                     "Time of the first contact when contact_mid_step is off; the ram starts at "
                     "the experiment's start time in free flight at v_impact towards it [s]"),
        UnitVariable("contact_mid_step", 6, "parameter", None,
                     "The first contact in the middle of the third communication step, "
                     "whatever the start time and step (as the engine starts; contact_time is "
                     "then unused) [-]", "Boolean"),
        UnitVariable("F_toe", 7, "input", "N",
                     "Ram-anvil contact force on the toe, compression positive (pushes the toe "
                     "up) [N]"),
        UnitVariable("u_toe", 8, "output", "m", "Ram toe displacement, positive down [m]"),
        UnitVariable("v_toe", 9, "output", "m/s",
                     "Ram toe velocity (leapfrog half-step value), positive down [m/s]"),
    ),
    "PileSoil": (
        UnitVariable("static_head_load", 1, "parameter", "N",
                     "Weight resting on the pile head at the start (anvil, helmet), in static "
                     "equilibrium [N]"),
        UnitVariable("gravity", 2, "parameter", "m/s2",
                     "Gravitational acceleration on the pile masses, 0 switches it off "
                     "[m/s^2]"),
        UnitVariable("F_head", 17, "input", "N",
                     "Anvil-pile contact force on the head, compression positive (pushes the "
                     "head down) [N]"),
        UnitVariable("u_head", 18, "output", "m",
                     "Pile head displacement relative to its static position at the start, "
                     "positive down [m]"),
        UnitVariable("v_head", 19, "output", "m/s", "Pile head velocity, positive down [m/s]"),
        UnitVariable("F_gauge", 20, "output", "N",
                     "Axial force at the gauge depth, compression positive [N]"),
        UnitVariable("v_gauge", 21, "output", "m/s",
                     "Pile velocity at the gauge depth, positive down [m/s]"),
        UnitVariable("u_head_total", 22, "output", "m",
                     "Pile head displacement from the undeformed pile (static settlement "
                     "included), positive down [m]"),
        UnitVariable("u_pile_toe", 23, "output", "m",
                     "Pile toe displacement from the undeformed pile, positive down [m]"),
        UnitVariable("max_compression_stress", 24, "output", "Pa",
                     "Largest axial compressive stress in the pile since the start [Pa]"),
        UnitVariable("max_tension_stress", 25, "output", "Pa",
                     "Largest axial tensile stress in the pile since the start (negative) "
                     "[Pa]"),
    ),
}
"""The variables of each native unit (the table of ``ram_model.c`` / ``pile_soil_model.c``)."""

DESCRIPTIONS = {
    "Ram": "anvilwave ram (native): lumped-mass rod (leapfrog, sub-stepped within its stable "
           "limit), struck face force in, toe state out (SI units, z down)",
    "PileSoil": "anvilwave pile and soil (native): Smith lumped pile with soil springs "
                "(leapfrog, sub-stepped within its stable limit), head force in, head and gauge "
                "signals out (SI units, z down, compression positive)",
}
_UNIT_EXPONENTS = {**UNITS, "s": {"s": 1}, "Pa": {"kg": 1, "m": -1, "s": -2}}


FMI3_COSIMULATION = {
    "needsExecutionTool": "false", "canBeInstantiatedOnlyOncePerProcess": "false",
    "canGetAndSetFMUState": "false", "canSerializeFMUState": "false",
    "providesDirectionalDerivatives": "false", "providesAdjointDerivatives": "false",
    "canHandleVariableCommunicationStepSize": "true", "providesIntermediateUpdate": "false",
    "canReturnEarlyAfterIntermediateUpdate": "false", "hasEventMode": "false"}
"""The ``CoSimulation`` capabilities of every native FMI 3.0 unit (besides its identifier)."""


def description_body(root: ET.Element, units: set[str],
                     experiment: tuple[float, float, float]) -> ET.Element:
    """The parts every native ``modelDescription.xml`` shares, after ``CoSimulation``.

    ``UnitDefinitions`` (SI base-unit exponents, sorted by name), ``LogCategories`` and
    ``DefaultExperiment``.

    Parameters
    ----------
    root : xml.etree.ElementTree.Element
        The ``fmiModelDescription`` element (FMI 2.0 or 3.0).
    units : set of str
        Names of the units the variables use.
    experiment : tuple of float
        (start, stop, step) of the ``DefaultExperiment`` [s].

    Returns
    -------
    xml.etree.ElementTree.Element
        The (empty) ``ModelVariables`` element, appended to ``root``.
    """
    definitions = ET.SubElement(root, "UnitDefinitions")
    for name in sorted(units):
        unit = ET.SubElement(definitions, "Unit", name=name)
        ET.SubElement(unit, "BaseUnit", {k: str(e) for k, e in _UNIT_EXPONENTS[name].items()})
    categories = ET.SubElement(root, "LogCategories")
    for name, text in (("logStatusError", "Errors (always reported)"),
                       ("logStatusWarning", "Warnings (always reported)"),
                       ("logCalls", "Every FMI call, with debug logging on")):
        ET.SubElement(categories, "Category", name=name, description=text)
    ET.SubElement(root, "DefaultExperiment", startTime=repr(experiment[0]),
                  stopTime=repr(experiment[1]), stepSize=repr(experiment[2]))
    return ET.SubElement(root, "ModelVariables")


# ---------------------------------------------------------------------------- binaries
def unit_sources(kind: str) -> tuple[str, ...]:
    """The C files of a binary kind: its ``.c`` sources, then its headers.

    Parameters
    ----------
    kind : {"Ram", "PileSoil", "Anvil"}
        Binary kind (:data:`BINARY_KINDS`).

    Returns
    -------
    tuple of str
        File names in ``anvilwave/fmu/native/``.
    """
    return (*COMMON_SOURCES, *MODEL_SOURCES[kind], *UNIT_HEADERS, *MODEL_HEADERS[kind])


def sources_digest(kind: str) -> str:
    """SHA-256 of the C sources and headers of a binary kind (names and bytes, sorted).

    Parameters
    ----------
    kind : {"Ram", "PileSoil", "Anvil"}
        Binary kind (:data:`BINARY_KINDS`).

    Returns
    -------
    str
        Hexadecimal digest.
    """
    digest = hashlib.sha256()
    for name in sorted(unit_sources(kind)):
        digest.update(name.encode())
        digest.update((NATIVE_DIR / name).read_bytes())
    return digest.hexdigest()


def platform_compiler(platform: str) -> str | None:
    """The compiler of a platform found on the PATH.

    Parameters
    ----------
    platform : str
        A platform of :data:`PLATFORMS`.

    Returns
    -------
    str or None
        The compiler command, None when there is none.
    """
    for name in PLATFORMS[platform]["compilers"]:
        if shutil.which(name):
            return name
    return None


def compile_unit(kind: str, platform: str, binary: Path, compiler: str | None = None) -> Path:
    """Compile the binary kind for a platform into ``binary`` (warnings are errors).

    Parameters
    ----------
    kind : {"Ram", "PileSoil", "Anvil"}
        Binary kind (:data:`BINARY_KINDS`).
    platform : str
        A platform of :data:`PLATFORMS`.
    binary : pathlib.Path
        The shared library to write.
    compiler : str or None, optional
        Compiler command (default: the platform's, found on the PATH).

    Returns
    -------
    pathlib.Path
        ``binary``, resolved.

    Raises
    ------
    NativeBuildError
        If no compiler is found or the compilation fails.
    """
    spec = PLATFORMS[platform]
    compiler = compiler or platform_compiler(platform)
    if compiler is None:
        raise NativeBuildError(f"no compiler for {platform} ({', '.join(spec['compilers'])}) "
                               "on the PATH")
    binary = Path(binary).resolve()
    binary.parent.mkdir(parents=True, exist_ok=True)
    sources = [*COMMON_SOURCES, *MODEL_SOURCES[kind]]
    # relative names from the sources folder: nothing of the build machine in the binary
    cmd = [compiler, *COMMON_FLAGS, *WARNING_FLAGS, *spec["flags"], "-I.", "-o", str(binary),
           *sources, *spec["libs"]]
    # SOURCE_DATE_EPOCH: no build time in the binary (the PE header's), reproducible builds
    env = {**os.environ, "SOURCE_DATE_EPOCH": "0"}
    run = subprocess.run(cmd, cwd=NATIVE_DIR, capture_output=True, text=True, timeout=300,
                         env=env)
    if run.returncode != 0 or not binary.is_file():
        raise NativeBuildError(f"compiling {kind} for {platform} failed ({' '.join(cmd)}):\n"
                               f"{run.stderr.strip()}")
    return binary


def rebuild_binaries(platforms: tuple[str, ...] | None = None,
                     out_dir: Path = BINARIES_DIR) -> dict[str, dict[str, Path]]:
    """Compile the shipped binaries of every binary kind and record the sources' digests.

    Parameters
    ----------
    platforms : tuple of str or None, optional
        Platforms to build for (default: every platform whose compiler is found).
    out_dir : pathlib.Path, default BINARIES_DIR
        Folder of the binaries.

    Returns
    -------
    dict of str to dict of str to pathlib.Path
        ``{platform: {kind: path}}``.

    Raises
    ------
    NativeBuildError
        When a platform asked for has no compiler, or a compilation fails.
    """
    out_dir = Path(out_dir)
    if platforms is None:
        platforms = tuple(p for p in PLATFORMS if platform_compiler(p) is not None)
    built: dict[str, dict[str, Path]] = {}
    for platform in platforms:
        suffix = PLATFORMS[platform]["suffix"]
        built[platform] = {kind: compile_unit(kind, platform,
                                              out_dir / platform / f"{kind}{suffix}")
                           for kind in BINARY_KINDS}
    record = {kind: sources_digest(kind) for kind in BINARY_KINDS}
    record["compilers"] = {platform: compiler_version(platform) for platform in platforms}
    (out_dir / DIGEST_FILE).write_text(json.dumps(record, indent=2, sort_keys=True) + "\n",
                                       encoding="ascii")
    return built


def compiler_version(platform: str) -> str | None:
    """The first line of ``--version`` of the platform's compiler.

    The shipped binaries are byte-reproducible with the same compiler version.

    Parameters
    ----------
    platform : str
        A platform of :data:`PLATFORMS`.

    Returns
    -------
    str or None
        The version line; None without a compiler.
    """
    compiler = platform_compiler(platform)
    if compiler is None:
        return None
    run = subprocess.run([compiler, "--version"], capture_output=True, text=True)
    return run.stdout.splitlines()[0].strip() if run.stdout else None


def unit_binaries(kind: str) -> dict[str, Path]:
    """The shipped binaries of a unit kind (model identifier).

    Parameters
    ----------
    kind : {"Ram", "PileSoil", "Anvil", "AnvilLumped"}
        Model identifier (its binary: :data:`BINARY_OF`).

    Returns
    -------
    dict of str to pathlib.Path
        ``{platform: path}``.

    Raises
    ------
    NativeBuildError
        When none is shipped or they were built from other sources than the current ones.
    """
    kind = BINARY_OF[kind]
    digests_path = BINARIES_DIR / DIGEST_FILE
    found = {p: BINARIES_DIR / p / f"{kind}{spec['suffix']}" for p, spec in PLATFORMS.items()}
    found = {p: path for p, path in found.items() if path.is_file()}
    if not found or not digests_path.is_file():
        raise NativeBuildError(f"no shipped binary of the native {kind} unit in {BINARIES_DIR} "
                               "(python -m anvilwave.fmu.native_units rebuilds them)")
    recorded = json.loads(digests_path.read_text(encoding="ascii")).get(kind)
    if recorded != sources_digest(kind):
        raise NativeBuildError(f"the shipped binaries of the native {kind} unit were built from "
                               "other sources than those in anvilwave/fmu/native (python -m "
                               "anvilwave.fmu.native_units rebuilds them)")
    return found


# ---------------------------------------------------------------------------- resources
def resource_text(kind: str, guid: str, starts: Mapping[str, float],
                  arrays: Mapping[str, np.ndarray]) -> str:
    """The ``anvilwave-unit`` resource (``fmu_common.h``): exact hexadecimal floats.

    Parameters
    ----------
    kind : {"Ram", "PileSoil"}
        Unit kind.
    guid : str
        GUID of the FMU (empty for the content digest).
    starts : mapping of str to float
        Parameter start values [SI] (Booleans as 0.0 or 1.0).
    arrays : mapping of str to numpy.ndarray
        Kernel arrays [SI].

    Returns
    -------
    str
        Content of the resource.
    """
    lines = [RESOURCE_MAGIC, f"kind {kind}", f"guid {guid}"]
    lines += [f"start {name} {float(value).hex()}" for name, value in starts.items()]
    for name, values in arrays.items():
        flat = np.asarray(values, dtype=np.float64).ravel()
        lines.append(f"array {name} {flat.size}")
        lines += [" ".join(float(x).hex() for x in flat[i:i + 8])
                  for i in range(0, flat.size, 8)]
    lines.append("end")
    return "\n".join(lines) + "\n"


def ram_arrays(hammer) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """The arrays and parameter defaults of a Ram unit for a hammer.

    Parameters
    ----------
    hammer : Hammer
        A :class:`anvilwave.hammer.database.Hammer` (the rod, rigid or modal ram of its
        ``ram``).

    Returns
    -------
    arrays : dict of str to numpy.ndarray
        Kernel arrays (masses [kg], springs [N/m], total mass [kg], impact velocity [m/s];
        a modal ram's toe modes too).
    defaults : dict of str to float
        Parameter defaults [SI].

    Raises
    ------
    InputError
        If the native Ram does not run this ram (:func:`native_ram_support`).
    """
    ram = hammer.ram
    supported, reason = native_ram_support(ram)
    if not supported:
        raise InputError("native Ram FMU", "hammer", reason)
    arrays = {"mass": ram.mass, "stiffness": ram.stiffness,
              "total_mass": np.array([ram.total_mass]),
              "impact_velocity": np.array([float(hammer.impact_velocity)])}
    if ram.is_modal_unit:  # the toe modes, the rigid-body mode first (ModalRamUnit's order)
        modes = ram.modes
        rigid = int(np.flatnonzero(modes.omega == 0.0)[0])
        order = np.r_[rigid, np.delete(np.arange(modes.n_modes), rigid)]
        arrays.update(modal_omega=modes.omega[order],
                      modal_participation=modes.participation[order],
                      modal_participation_gravity=np.array(
                          [float(modes.participation_gravity[rigid])]))
    defaults = {"v_impact": float(hammer.impact_velocity), "mass": ram.total_mass,
                "gravity": 9.81, "contact_displacement": 0.0, "contact_time": 0.0,
                "contact_mid_step": True}
    return arrays, defaults


def native_ram_support(ram) -> tuple[bool, str]:
    """Whether the native Ram runs this :class:`anvilwave.hammer.ram.RamRod`.

    Parameters
    ----------
    ram : RamRod
        The ram.

    Returns
    -------
    supported : bool
        True when the native Ram runs it.
    reason : str
        Why not; ``""`` when supported.
    """
    if ram.is_modal_unit and not np.any(ram.modes.omega == 0.0):
        return False, "a modal ram without its rigid-body mode (omega = 0)"
    return True, ""


def pile_soil_arrays(model) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """The arrays and parameter defaults of a PileSoil unit for a pile with its soil.

    Parameters
    ----------
    model : PileSoil
        A :class:`anvilwave.pile.model.PileSoil`.

    Returns
    -------
    arrays : dict of str to numpy.ndarray
        Its kernel arrays as the pythonfmu unit builds them (``PileSoil.arrays()``,
        ``stress_factors()``).
    defaults : dict of str to float
        Parameter defaults (``static_head_load`` [N], ``gravity`` [m/s^2]).
    """
    arrays = model.arrays()
    return ({"pile": arrays.pile, "soil": arrays.soil, "probes": arrays.probes,
             "stress_factor": model.stress_factors()},
            {"static_head_load": 0.0, "gravity": 9.81})


# ---------------------------------------------------------------------------- build
def build_native_ram_fmu(hammer, out_path: str | Path, *, validate: bool = True,
                         fmi_version: int = 2,
                         default_experiment: tuple[float, float, float] | None = None,
                         **parameters) -> Path:
    """``Ram.fmu`` (native) for a hammer.

    Parameters
    ----------
    hammer : Hammer or str
        A :class:`anvilwave.hammer.database.Hammer` (or a name of the hammer database).
    out_path : str or pathlib.Path
        The ``.fmu`` or a folder (:func:`build_unit_fmu`).
    validate : bool, default True
        Check the FMU with fmpy (:func:`build_unit_fmu`).
    fmi_version : {2, 3}, default 2
        FMI version of the FMU (:func:`build_unit_fmu`).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] as :func:`build_unit_fmu`'s.
    **parameters
        As the pythonfmu Ram's (``v_impact`` [m/s], ``mass`` [kg], ``gravity`` [m/s^2],
        ``contact_displacement`` [m], ``contact_time`` [s], ``contact_mid_step``, default on:
        the first contact in the middle of the third step, :mod:`anvilwave.fmu.units.ram`).

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu``.
    """
    if isinstance(hammer, str):

        hammer = load_hammer(hammer, float(parameters.get("gravity", 9.81)))
    arrays, defaults = ram_arrays(hammer)
    return build_unit_fmu("Ram", arrays, {**defaults, **parameters}, out_path,
                          validate=validate, explicit=set(parameters), fmi_version=fmi_version,
                          default_experiment=default_experiment)


def build_native_pile_soil_fmu(pile_soil, out_path: str | Path, *, validate: bool = True,
                               fmi_version: int = 2,
                               default_experiment: tuple[float, float, float] | None = None,
                               **parameters) -> Path:
    """``PileSoil.fmu`` (native) for a pile with its soil.

    Parameters
    ----------
    pile_soil : PileSoil, str or pathlib.Path
        A :class:`anvilwave.pile.model.PileSoil` (or the path of a TOML file with ``[pile]``
        and an optional ``[soil]``).
    out_path : str or pathlib.Path
        The ``.fmu`` or a folder (:func:`build_unit_fmu`).
    validate : bool, default True
        Check the FMU with fmpy (:func:`build_unit_fmu`).
    fmi_version : {2, 3}, default 2
        FMI version of the FMU (:func:`build_unit_fmu`).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] as :func:`build_unit_fmu`'s.
    **parameters
        ``static_head_load`` [N] and ``gravity`` [m/s^2].

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu``.
    """

    model = pile_soil if isinstance(pile_soil, PileSoil) else load_pile_soil(pile_soil)
    arrays, defaults = pile_soil_arrays(model)
    return build_unit_fmu("PileSoil", arrays, {**defaults, **parameters}, out_path,
                          validate=validate, explicit=set(parameters), fmi_version=fmi_version,
                          default_experiment=default_experiment)


def build_unit_fmu(kind: str, arrays: Mapping[str, np.ndarray], values: Mapping[str, Any],
                   out_path: str | Path, *, validate: bool = True,
                   explicit: set[str] | None = None, fmi_version: int = 2,
                   default_experiment: tuple[float, float, float] | None = None) -> Path:
    """Write a native unit FMU of ``kind`` with these kernel arrays and parameter start values.

    Nothing is written when the build fails. The FMU holds modelDescription.xml,
    resources/anvilwave_unit.txt, the shipped binaries (:func:`unit_binaries`) under
    binaries/<platform>/ and the C sources under sources/. Its GUID is derived from the
    content, and the archive has fixed timestamps and order: the same inputs give the same
    bytes.

    Parameters
    ----------
    kind : {"Ram", "PileSoil"}
        Unit kind.
    arrays : mapping of str to numpy.ndarray
        Kernel arrays [SI].
    values : mapping of str to Any
        Parameter start values [SI].
    out_path : str or pathlib.Path
        The ``.fmu`` or a folder (then ``<folder>/<kind>.fmu``).
    validate : bool, default True
        Check the FMU with fmpy (:func:`check_unit_fmu`, :func:`check_unit_fmu_3`).
    explicit : set of str or None, optional
        Names of ``values`` given by the caller: an unknown one among them is an error (None:
        every name of ``values``).
    fmi_version : {2, 3}, default 2
        3: an FMI 3.0 co-simulation FMU (the same binaries, which hold both APIs, under the
        FMI 3.0 platform folders).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s]: the system's, the FMU's ``DefaultExperiment`` (default
        :data:`anvilwave.fmu.native_build.DEFAULT_EXPERIMENT`); the Ram also gets it in its
        resource (array ``default_experiment``, checked; the ram's start does not depend on
        it).

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu``.

    Raises
    ------
    InputError
        If ``fmi_version``, a parameter or ``default_experiment`` is invalid.
    NativeBuildError
        If no current binary is shipped or the FMU does not pass its check.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """
    source = f"native {kind} FMU build"
    if fmi_version not in (2, 3):
        raise InputError(source, "fmi_version", f"must be 2 or 3, got {fmi_version!r}")
    variables = VARIABLES[kind]
    names = {v.name for v in variables if v.causality == "parameter"}
    for name in sorted(set(values) - names):
        if explicit is None or name in explicit:
            raise InputError(source, name, f"not a parameter of the native {kind} unit "
                                           f"(parameters: {', '.join(sorted(names))})")
    experiment = default_experiment_values(default_experiment, source)
    starts: dict[str, float] = {}
    for v in variables:
        if v.causality != "parameter":
            continue
        value = values[v.name]
        if v.type == "Boolean":
            if not isinstance(value, (bool, np.bool_)):
                raise InputError(source, v.name, f"must be true or false, got {value!r}")
            starts[v.name] = 1.0 if value else 0.0
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or \
                not math.isfinite(float(value)):
            raise InputError(source, v.name, f"must be a finite number, got {value!r}")
        starts[v.name] = float(value)
    if kind == "Ram" and default_experiment is not None:
        arrays = {**arrays, "default_experiment": np.array(experiment)}
    binaries = unit_binaries(kind)
    out_path = Path(out_path)
    target = out_path if out_path.suffix == ".fmu" else out_path / f"{kind}.fmu"
    content = resource_text(kind, "", starts, arrays)
    digest = hashlib.sha256(f"FMI {fmi_version}".encode())
    if default_experiment is not None:
        digest.update(" ".join(x.hex() for x in experiment).encode())
    digest.update(content.encode())
    digest.update(sources_digest(kind).encode())
    for platform in sorted(binaries):
        digest.update(binaries[platform].read_bytes())
    guid = "{" + str(uuid.UUID(bytes=digest.digest()[:16], version=4)) + "}"
    with tempfile.TemporaryDirectory(prefix="anvilwave_native_unit_") as scratch:
        stage = Path(scratch) / "fmu"
        (stage / "resources").mkdir(parents=True)
        (stage / "resources" / RESOURCE).write_text(resource_text(kind, guid, starts, arrays),
                                                    encoding="ascii")
        sources = stage / "sources"
        sources.mkdir()
        for name in unit_sources(kind):
            shutil.copyfile(NATIVE_DIR / name, sources / name)
        for platform, path in binaries.items():
            folder = stage / "binaries" / (platform if fmi_version == 2
                                           else FMI3_PLATFORMS[platform])
            folder.mkdir(parents=True)
            shutil.copyfile(path, folder / f"{kind}{PLATFORMS[platform]['suffix']}")
        describe = unit_model_description if fmi_version == 2 else unit_model_description_3
        (stage / "modelDescription.xml").write_bytes(describe(kind, guid, starts, experiment))
        archive = Path(scratch) / f"{kind}.fmu"
        _zip(stage, archive)
        if validate:
            if fmi_version == 2:
                check_unit_fmu(archive, stage, kind, guid)
            else:
                check_unit_fmu_3(archive, kind)
        target.parent.mkdir(parents=True, exist_ok=True)
        part = target.with_name(target.name + ".part")
        shutil.copyfile(archive, part)
        part.replace(target)
    return target


def package_version() -> str:
    """The installed anvilwave version.

    Returns
    -------
    str
        The version ("unknown" when not installed).
    """
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("anvilwave")
    except PackageNotFoundError:
        return "unknown"


def unit_model_description(kind: str, guid: str, starts: Mapping[str, float],
                           experiment: tuple[float, float, float] = DEFAULT_EXPERIMENT) -> bytes:
    """``modelDescription.xml`` of a native unit (FMI 2.0 co-simulation, with its sources).

    Parameters
    ----------
    kind : {"Ram", "PileSoil"}
        Unit kind.
    guid : str
        GUID of the FMU.
    starts : mapping of str to float
        Parameter start values [SI] (Booleans as 0.0 or 1.0).
    experiment : tuple of float, default DEFAULT_EXPERIMENT
        (start, stop, step) of the ``DefaultExperiment`` [s].

    Returns
    -------
    bytes
        Content of the file (UTF-8).

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """
    variables = VARIABLES[kind]
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "2.0", "modelName": kind, "guid": guid, "description": DESCRIPTIONS[kind],
        "author": AUTHOR, "version": package_version(), "license": LICENSE,
        "copyright": f"{AUTHOR}, {LICENSE} licence",
        "generationTool": GENERATION_TOOL, "variableNamingConvention": "structured"})
    cs = ET.SubElement(root, "CoSimulation", {
        "modelIdentifier": kind, "needsExecutionTool": "false",
        "canHandleVariableCommunicationStepSize": "true", "canInterpolateInputs": "false",
        "maxOutputDerivativeOrder": "0", "canRunAsynchronuously": "false",
        "canBeInstantiatedOnlyOncePerProcess": "false",
        "canNotUseMemoryManagementFunctions": "true", "canGetAndSetFMUstate": "false",
        "canSerializeFMUstate": "false", "providesDirectionalDerivative": "false"})
    files = ET.SubElement(cs, "SourceFiles")
    for name in (*COMMON_SOURCES, *MODEL_SOURCES[kind]):
        ET.SubElement(files, "File", name=name)
    mv = description_body(root, {v.unit for v in variables if v.unit is not None}, experiment)
    index: dict[str, int] = {}
    for position, v in enumerate(variables, start=1):
        index[v.name] = position
        sv = ET.SubElement(mv, "ScalarVariable", {
            "name": v.name, "valueReference": str(v.vr), "description": v.description,
            "causality": v.causality,
            "variability": "fixed" if v.causality == "parameter" else "continuous"})
        if v.type == "Boolean":
            ET.SubElement(sv, "Boolean", start="true" if starts[v.name] else "false")
            continue
        typed = {"unit": v.unit}
        if v.causality == "parameter":
            typed["start"] = repr(starts[v.name])
        elif v.causality == "input":
            typed["start"] = "0.0"
        ET.SubElement(sv, "Real", typed)
    structure = ET.SubElement(root, "ModelStructure")
    outputs = ET.SubElement(structure, "Outputs")
    initial = ET.SubElement(structure, "InitialUnknowns")
    parameters = " ".join(str(index[v.name]) for v in variables if v.causality == "parameter")
    for v in variables:
        if v.causality == "output":  # states: no feedthrough
            ET.SubElement(outputs, "Unknown", index=str(index[v.name]), dependencies="")
            ET.SubElement(initial, "Unknown", index=str(index[v.name]),
                          dependencies=parameters)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def unit_model_description_3(kind: str, token: str, starts: Mapping[str, float],
                             experiment: tuple[float, float, float] = DEFAULT_EXPERIMENT
                             ) -> bytes:
    """``modelDescription.xml`` of a native unit as FMI 3.0 co-simulation.

    The variables and value references of the FMI 2.0 unit, Float64, and the independent
    variable ``time``.

    Parameters
    ----------
    kind : {"Ram", "PileSoil"}
        Unit kind.
    token : str
        Instantiation token of the FMU.
    starts : mapping of str to float
        Parameter start values [SI] (Booleans as 0.0 or 1.0).
    experiment : tuple of float, default DEFAULT_EXPERIMENT
        (start, stop, step) of the ``DefaultExperiment`` [s].

    Returns
    -------
    bytes
        Content of the file (UTF-8).

    References
    ----------
    Modelica Association. Functional Mock-up Interface, FMI 3.0. https://fmi-standard.org
    """
    variables = VARIABLES[kind]
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "3.0", "modelName": kind, "instantiationToken": token,
        "description": DESCRIPTIONS[kind], "author": AUTHOR, "version": package_version(),
        "license": LICENSE, "copyright": f"{AUTHOR}, {LICENSE} licence",
        "generationTool": GENERATION_TOOL, "variableNamingConvention": "structured"})
    ET.SubElement(root, "CoSimulation", {"modelIdentifier": kind, **FMI3_COSIMULATION})
    mv = description_body(root, {v.unit for v in variables if v.unit is not None} | {"s"},
                          experiment)  # "s": time
    ET.SubElement(mv, "Float64", name="time", valueReference="0", causality="independent",
                  variability="continuous", description="Simulation time [s]", unit="s")
    for v in variables:
        attrs = {"name": v.name, "valueReference": str(v.vr), "description": v.description,
                 "causality": v.causality,
                 "variability": "fixed" if v.causality == "parameter" else "continuous"}
        if v.type == "Boolean":
            attrs["start"] = "true" if starts[v.name] else "false"
            ET.SubElement(mv, "Boolean", attrs)
            continue
        attrs["unit"] = v.unit
        if v.causality == "parameter":
            attrs["start"] = repr(starts[v.name])
        elif v.causality == "input":
            attrs["start"] = "0.0"
        ET.SubElement(mv, "Float64", attrs)
    structure = ET.SubElement(root, "ModelStructure")
    for v in variables:
        if v.causality == "output":  # states: no feedthrough
            ET.SubElement(structure, "Output", valueReference=str(v.vr), dependencies="")
    for v in variables:
        if v.causality == "output":
            ET.SubElement(structure, "InitialUnknown", valueReference=str(v.vr))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def check_unit_fmu_3(archive: Path, kind: str, outputs: list[str] | None = None) -> None:
    """fmpy's validation of an FMI 3.0 unit and one short simulation.

    Skipped without fmpy; the simulation is skipped off linux64.

    Parameters
    ----------
    archive : pathlib.Path
        The ``.fmu``.
    kind : str
        Unit kind (model identifier).
    outputs : list of str or None, optional
        The outputs that must be finite (default: those of :data:`VARIABLES` of ``kind``).

    Raises
    ------
    NativeBuildError
        If the FMU does not validate or simulate, or its outputs are not finite.
    """
    try:
        from fmpy import simulate_fmu
        from fmpy.validation import validate_fmu
    except ImportError:
        return
    problems = validate_fmu(str(archive))
    if problems:
        raise NativeBuildError(f"{archive.name} does not validate: " + "; ".join(problems))
    if not (sys.platform.startswith("linux") and sys.maxsize > 2**32):
        return
    try:
        result = simulate_fmu(str(archive), stop_time=2e-5, step_size=1e-5,
                              output_interval=1e-5)
    except Exception as exc:  # noqa: BLE001 - reported as a build error
        raise NativeBuildError(f"{archive.name} does not simulate: {exc}") from None
    if outputs is None:
        outputs = [v.name for v in VARIABLES[kind] if v.causality == "output"]
    if not all(np.all(np.isfinite(result[name])) for name in outputs):
        raise NativeBuildError(f"{archive.name}: outputs are not finite")


def check_unit_fmu(archive: Path, stage: Path, kind: str, guid: str) -> None:
    """fmpy's validation, then instantiate, initialize and step the staged FMU once.

    Skipped without fmpy; the run is skipped when the build machine is not linux64.

    Parameters
    ----------
    archive : pathlib.Path
        The ``.fmu``.
    stage : pathlib.Path
        The unpacked FMU (the folder the archive was made from).
    kind : {"Ram", "PileSoil"}
        Unit kind.
    guid : str
        GUID of the FMU.

    Raises
    ------
    NativeBuildError
        If the FMU does not validate, instantiate or initialize, or its outputs are not
        finite.
    """
    outputs = [v.vr for v in VARIABLES[kind] if v.causality == "output"]
    check_staged_fmu(archive, stage, kind, guid, outputs,
                     run=sys.platform.startswith("linux") and sys.maxsize > 2**32)


if __name__ == "__main__":  # python -m anvilwave.fmu.native_units [platform ...]
    done = rebuild_binaries(tuple(sys.argv[1:]) or None)
    for name, kinds in done.items():
        for path in kinds.values():
            print(f"{name}: {path}")
