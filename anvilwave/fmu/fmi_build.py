"""Build the anvilwave FMUs (FMI 2.0 co-simulation, pythonfmu) and make them validate cleanly.

``build_fmu(kind, out_dir, parameters, resources)`` does, in a scratch folder:

1. checks the parameters against the slave (unknown name, wrong type, a value the component
   rejects: :class:`~anvilwave.inputs.InputError`, nothing written);
2. writes them as the FMU's parameter defaults (``resources/anvilwave_parameters.json``) next to
   the embedded resource files (e.g. the modal-data ``.npz`` of ``Anvil.fmu``);
3. runs the pythonfmu build of the kind's slave script; each FMU type has a script with a module
   name of its own (pythonfmu runs the first loaded module of a name for every FMU in a process);
4. post-processes ``modelDescription.xml``: ``UnitDefinitions`` with SI base-unit exponents,
   ``unit`` attributes, a complete ``ModelStructure`` (``Outputs`` and ``InitialUnknowns`` with
   their dependencies; no ``Derivatives``: co-simulation without exposed states), so that
   ``fmpy validate`` reports no problem;
5. on Linux, installs the status shim (``anvilwave/fmu/units/fmi2_status_shim.c``, compiled with the
   system C compiler) as the FMU binary in front of the pythonfmu library, so that an error
   logged by a slave is returned as ``fmi2Error`` (stock pythonfmu cannot return it; see
   :mod:`anvilwave.fmu.units.base`), and so that the FMU runs in a host that is not Python: the shim
   loads the libpython of the Python that built the FMU (recorded in
   ``resources/anvilwave_python.txt``, :func:`python_runtime`), initializes it with that
   Python's executable (a venv's: its site-packages, so numpy, scipy and numba import), never
   finalizes it,
   and works around pythonfmu 0.7.0's double release of its Python state at unload (the
   "free(): corrupted unsorted chunks" abort of C hosts at exit). Without a compiler the stock
   binary stays and a warning says so: a slave error is then reported as ``fmi2Discard`` by
   the next ``fmi2DoStep``, and only Python hosts can load the FMU;
6. checks the result with ``fmpy.validation.validate_fmu`` (when fmpy is installed) and moves
   the ``.fmu`` into ``out_dir`` in one step.

The FMUs carry the Python code they run, so that they run in a Python without anvilwave and
without pythonfmu (:mod:`anvilwave.fmu.vendoring`): the import closure of the slave class
inside anvilwave (its module-level imports followed; no command line, analyses, output layer or
matplotlib) is copied into ``resources/anvilwave_fmu_<digest>/`` with its imports renamed to
that package, the slave script imports its classes from it, and pythonfmu's build adds its own
Python part (``resources/pythonfmu/``). ``<digest>`` comes from the copied files: a package
name per code, so that it never clashes with an installed anvilwave and two FMUs of different
builds in one process each run their own code. When the process already has an anvilwave whose
files are byte for byte those of the FMU (fmpy in the venv that built it), the package's modules
are that anvilwave's (:mod:`anvilwave.fmu.units.vendor_init`): one copy in the process, its
numba kernels cached as usual. The licence texts of anvilwave and pythonfmu are in
``documentation/licenses/`` (and beside the code in ``resources/``). Identical builds stay
byte-identical: the copied files are read in sorted order, no ``.pyc``, fixed zip timestamps.

The host Python needs numpy, scipy and numba (of versions that run anvilwave's code) and nothing
else. In a Python host (fmpy, libcosimpy) that is the host's Python; in a C host it is the
Python that built the FMU, or, when that one is gone, the first ``python3.X`` of the same
version on the PATH (the shim logs a warning naming it). The first instantiation in a process
without an identical anvilwave compiles the units' numba kernels (seconds; their cache goes
beside the FMU's extracted copy).

Helpers per FMU type: :func:`build_anvil_fmu` (``Anvil.fmu`` / ``AnvilLumped.fmu`` from a
modal-data file), :func:`build_ram_fmu` (``Ram.fmu`` from a hammer: its segments embedded as
``hammer.toml``, or a database name), :func:`build_pile_soil_fmu` (``PileSoil.fmu`` with
the
``[pile]`` / ``[soil]`` tables embedded as ``pile_soil.toml``). The resource files are written
with floats in ``repr`` form, so the units read back the engine's arrays bit for bit. A whole
system file: :func:`anvilwave.engine.fmus.build_system_fmus`.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import importlib.util
import inspect
import json
import math
import numbers
import os
import shutil
import subprocess
import sys
import tempfile
import uuid
import warnings
import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.anvil_rom.fem.modalfile import load_modal_data
from anvilwave.fmu.units.base import DEFAULTS_FILE, UnitSlave
from anvilwave.fmu.vendoring import (
    PACKAGE_PREFIX,
    license_text,
    pythonfmu_license_text,
    vendored_unit,
)
from anvilwave.hammer.database import Hammer, available_hammers
from anvilwave.hammer.modal_ram import toe_modes_table
from anvilwave.inputs import InputError, toml_dumps
from anvilwave.pile.model import PileSoil, load_pile_soil

UNITS_DIR = Path(__file__).resolve().parent / "units"
SHIM_SOURCE = UNITS_DIR / "fmi2_status_shim.c"
SHIM_INNER_LIBRARY = "pythonfmu-export.so"  # must match INNER_LIBRARY in the shim source
RUNTIME_FILE = "anvilwave_python.txt"  # must match RUNTIME_FILE in the shim source
GUID_FILE = "anvilwave_guid.txt"  # must match GUID_FILE in the shim source
AUTHOR = "anvilwave"
"""``author`` of the FMUs' modelDescription.xml (with ``version``: anvilwave's, and
``license``: the project's)."""
LICENSE = "MIT"
LICENSE_FILES = {"anvilwave": "documentation/licenses/anvilwave.txt",
                 "pythonfmu": "documentation/licenses/pythonfmu.txt"}
"""Licence texts in the pythonfmu FMUs (the FMI 3.0 layout; also in ``resources/`` beside the
code they cover: ``resources/anvilwave_fmu_<digest>/LICENSE``, ``resources/pythonfmu/LICENSE``)."""
FORMAT = "anvilwave-fmu-parameters"

KINDS: dict[str, Path] = {
    "Anvil": UNITS_DIR / "anvilwave_anvil_rom.py",
    "AnvilLumped": UNITS_DIR / "anvilwave_anvil_lumped.py",
    "AnvilStack": UNITS_DIR / "anvilwave_anvil_stack.py",
    "Ram": UNITS_DIR / "anvilwave_ram.py",
    "PileSoil": UNITS_DIR / "anvilwave_pile_soil.py",
}
"""Slave script of each FMU type. A new type registers its script here (unique module name)."""

# SI base-unit exponents of every unit the FMUs use (FMI 2.0 <BaseUnit>).
UNIT_DEFINITIONS: dict[str, dict[str, int]] = {
    "m": {"m": 1},
    "m/s": {"m": 1, "s": -1},
    "m/s2": {"m": 1, "s": -2},
    "N": {"kg": 1, "m": 1, "s": -2},
    "N/m": {"kg": 1, "s": -2},
    "N.s/m": {"kg": 1, "s": -1},
    "Hz": {"s": -1},
    "Pa": {"kg": 1, "m": -1, "s": -2},
    "s/m": {"s": 1, "m": -1},
    "kg/m3": {"kg": 1, "m": -3},
    "kg": {"kg": 1},
    "s": {"s": 1},
    "1": {},
}


def build_fmu(kind: str | Path, out_dir: str | Path, parameters: dict[str, Any] | None = None,
              resources: Iterable[str | Path] = (), *, status_shim: bool | None = None,
              validate: bool = True,
              default_experiment: tuple[float, float, float] | None = None) -> Path:
    """Build one FMU and return its path ``out_dir/<kind>.fmu``.

    Parameters
    ----------
    kind : str or pathlib.Path
        An FMU type of :data:`KINDS` (``"Anvil"``, ``"AnvilLumped"``) or the path of a slave
        script (a :class:`anvilwave.fmu.units.base.UnitSlave` subclass in a module with a unique
        name).
    out_dir : str or pathlib.Path
        Folder for the ``.fmu`` (created).
    parameters : dict of str to Any, optional
        Parameter defaults of this build, ``{name: value}`` (SI units, see the slave).
    resources : iterable of str or pathlib.Path, default ()
        Files embedded in the FMU's ``resources`` folder; a string parameter may name them
        (relative names are looked up there at run time).
    status_shim : bool or None, optional
        Install the fmi2Error status shim: ``None`` when possible (Linux with a C compiler),
        ``True`` required, ``False`` never.
    validate : bool, default True
        Run ``fmpy.validation.validate_fmu`` on the result (needs fmpy).
    default_experiment : tuple of float or None, optional
        (start time, stop time, step) [s] of the system the FMU is built for: its
        ``DefaultExperiment`` (default: the slave class's), and the step the ram places its
        first contact with before the first ``fmi2DoStep`` (:mod:`anvilwave.fmu.units.ram`).

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu``, ``out_dir/<kind>.fmu``.

    Raises
    ------
    InputError
        If ``kind``, a parameter, a resource or ``default_experiment`` is invalid.
    RuntimeError
        If the status shim is required but cannot be built, or the FMU does not validate.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """
    script = _script(kind)
    parameters = dict(parameters or {})
    out_dir = Path(out_dir)
    with tempfile.TemporaryDirectory(prefix="anvilwave_fmu_") as scratch:
        scratch = Path(scratch)
        stage = scratch / "resources"
        stage.mkdir()
        cls = _slave_class(script)
        parameters = _checked_parameters(cls, parameters)
        staged = _stage_resources(resources, stage, script)
        defaults = stage / _defaults_file()
        content: dict[str, Any] = {"format": FORMAT, "version": 1, "parameters": parameters}
        if default_experiment is not None:
            start, stop, step = (float(x) for x in default_experiment)
            if not (math.isfinite(start) and stop > start and step > 0.0):
                raise InputError("build_fmu", "default_experiment",
                                 f"must be (start, stop > start, step > 0) [s], got "
                                 f"{default_experiment!r}")
            content["default_experiment"] = {"start_time": start, "stop_time": stop,
                                             "step_size": step}
        defaults.write_text(json.dumps(content, indent=2, allow_nan=False) + "\n")
        staged.append(defaults)
        runtime = stage / RUNTIME_FILE
        runtime.write_text(python_runtime_text(), encoding="utf-8")
        staged.append(runtime)
        slave = _checked_slave(cls, stage)
        built = _pythonfmu_build(script, scratch / "build", staged)
        shim = _compile_shim(scratch, status_shim)
        final = scratch / built.name
        _post_process(built, final, slave, shim, content.get("default_experiment"), script)
        if validate:
            _validate(final)
        out_dir.mkdir(parents=True, exist_ok=True)
        target = out_dir / final.name
        part = out_dir / (final.name + ".part")
        shutil.copyfile(final, part)
        part.replace(target)
    return target


def build_anvil_fmu(modal_data_file: str | Path, out_dir: str | Path, *, lumped: bool = False,
                    default_experiment: tuple[float, float, float] | None = None,
                    **parameters) -> Path:
    """``Anvil.fmu`` (modal ROM) or, with ``lumped``, ``AnvilLumped.fmu`` from a modal-data file.

    The ROM embeds the file and defaults ``fmax`` [Hz] and ``damping_ratio`` [-] to the file's;
    the lumped anvil defaults its ``mass`` [kg] to the file's total mass.

    Parameters
    ----------
    modal_data_file : str or pathlib.Path
        The modal-data file (``.npz``).
    out_dir : str or pathlib.Path
        Folder for the ``.fmu`` (created).
    lumped : bool, default False
        Build ``AnvilLumped.fmu`` (the rigid lumped-mass anvil) instead of ``Anvil.fmu``.
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] of the system the FMU is built for (:func:`build_fmu`).
    **parameters
        Other parameters (``ram_contact_stiffness`` [N/m], ``pile_contact_stiffness`` [N/m],
        ...) as keywords.

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu`` (``out_dir/<kind>.fmu``).
    """

    path = Path(modal_data_file)
    data = load_modal_data(path)
    if lumped:
        return build_fmu("AnvilLumped", out_dir, {"mass": data.total_mass, **parameters},
                         default_experiment=default_experiment)
    defaults = {"modal_data_file": path.name, "fmax": data.fmax,
                "damping_ratio": data.damping_ratio}
    return build_fmu("Anvil", out_dir, {**defaults, **parameters}, [path],
                     default_experiment=default_experiment)


def build_anvil_stack_fmu(stack_data_file: str | Path, out_dir: str | Path, *,
                          default_experiment: tuple[float, float, float] | None = None,
                          **parameters) -> Path:
    """``AnvilStack.fmu`` (the anvil and the anvil ring) from a stack data file.

    The file (:func:`anvilwave.anvil_rom.stack.save_stack_data`) is embedded.

    Parameters
    ----------
    stack_data_file : str or pathlib.Path
        The stack data file (``.npz``).
    out_dir : str or pathlib.Path
        Folder for the ``.fmu`` (created).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] of the system the FMU is built for (:func:`build_fmu`).
    **parameters
        Other parameters (``seat_friction`` [-], ``ram_contact_stiffness`` [N/m], ...) as
        keywords.

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu`` (``out_dir/AnvilStack.fmu``).
    """
    path = Path(stack_data_file)
    return build_fmu("AnvilStack", out_dir, {"stack_data_file": path.name, **parameters},
                     [path], default_experiment=default_experiment)


HAMMER_RESOURCE = "hammer.toml"
PILE_SOIL_RESOURCE = "pile_soil.toml"


def build_ram_fmu(out_dir: str | Path, hammer=None, *,
                  default_experiment: tuple[float, float, float] | None = None,
                  **parameters) -> Path:
    """``Ram.fmu`` for a hammer.

    Parameters
    ----------
    out_dir : str or pathlib.Path
        Folder for the ``.fmu`` (created).
    hammer : Hammer, str, pathlib.Path or None, optional
        A :class:`anvilwave.hammer.database.Hammer` (its ram is embedded as ``hammer.toml``, the
        segment masses [kg] and springs [N/m] written exactly; ``v_impact`` [m/s] and ``mass``
        [kg] default to the hammer's), the name of a database hammer (nothing embedded), the
        path of a hammer TOML file (embedded), or None (the default database hammer).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] of the system (:func:`build_fmu`); the same keyword for the
        other helpers.
    **parameters
        Further parameters of the Ram FMU (``v_impact`` [m/s], ``gravity`` [m/s^2],
        ``contact_displacement`` [m], ``contact_mid_step``, ``contact_time`` [s], ``mass``
        [kg]).

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu`` (``out_dir/<kind>.fmu``).

    Raises
    ------
    InputError
        If ``hammer`` is neither a database hammer nor a ``.toml`` file.
    """

    with tempfile.TemporaryDirectory(prefix="anvilwave_ram_") as tmp:
        resources = []
        defaults: dict[str, Any] = {}
        if isinstance(hammer, Hammer):
            path = Path(tmp) / HAMMER_RESOURCE
            path.write_text(hammer_toml(hammer), encoding="utf-8")
            resources.append(path)
            defaults = {"hammer": HAMMER_RESOURCE, "v_impact": hammer.impact_velocity,
                        "mass": hammer.ram.total_mass}
        elif hammer is not None:

            if str(hammer) in available_hammers():
                defaults = {"hammer": str(hammer)}
            else:
                path = Path(hammer)
                if path.suffix != ".toml" or not path.is_file():
                    raise InputError("build_ram_fmu", "hammer",
                                     f"{str(hammer)!r} is neither a database hammer "
                                     f"({', '.join(available_hammers())}) nor a .toml file")
                resources.append(path)
                defaults = {"hammer": path.name}
        return build_fmu("Ram", out_dir, {**defaults, **parameters}, resources,
                         default_experiment=default_experiment)


def build_pile_soil_fmu(out_dir: str | Path, pile_soil, *,
                        default_experiment: tuple[float, float, float] | None = None,
                        **parameters) -> Path:
    """``PileSoil.fmu`` for a pile with its soil.

    Parameters
    ----------
    out_dir : str or pathlib.Path
        Folder for the ``.fmu`` (created).
    pile_soil : PileSoil, str or pathlib.Path
        A :class:`anvilwave.pile.model.PileSoil` (written exactly as ``pile_soil.toml``; the
        scalar settings become the parameter defaults) or the path of a TOML file with
        ``[pile]`` and an optional ``[soil]`` table (embedded; its scalar settings become the
        defaults likewise).
    default_experiment : tuple of float or None, optional
        (start, stop, step) [s] of the system the FMU is built for (:func:`build_fmu`).
    **parameters
        Further parameters (``static_head_load`` [N], ``gravity`` [m/s^2], ``soil_model``,
        ``gauge_depth`` [m], ...; see :mod:`anvilwave.fmu.units.pile_soil`).

    Returns
    -------
    pathlib.Path
        Path of the ``.fmu`` (``out_dir/<kind>.fmu``).
    """

    with tempfile.TemporaryDirectory(prefix="anvilwave_pile_") as tmp:
        if isinstance(pile_soil, PileSoil):
            model = pile_soil
            path = Path(tmp) / PILE_SOIL_RESOURCE
            path.write_text(pile_soil_toml(model), encoding="utf-8")
        else:
            path = Path(pile_soil)
            model = load_pile_soil(path)
        defaults = {"pile_soil_file": path.name, **pile_soil_parameters(model)}
        return build_fmu("PileSoil", out_dir, {**defaults, **parameters}, [path],
                         default_experiment=default_experiment)


def pile_soil_parameters(model) -> dict[str, Any]:
    """The scalar settings of a :class:`anvilwave.pile.model.PileSoil` as PileSoil FMU parameters.

    Parameters
    ----------
    model : PileSoil
        The pile with its soil.

    Returns
    -------
    dict of str to Any
        FMU parameter name -> value [SI].
    """
    pile, soil = model.pile, model.soil
    values: dict[str, Any] = {"segment_length": pile.segment_length,
                              "gauge_depth": pile.gauge_depth,
                              "material_damping": pile.material_damping}
    if soil is not None:
        values.update(soil_model=soil.model, penetration=soil.penetration,
                      quake_shaft=soil.quake_shaft, damping_shaft=soil.damping_shaft,
                      friction_perimeter=soil.friction_perimeter, toe_area=soil.toe_area)
        if soil.model == "lysmer-toe":
            values.update(toe_shear_modulus=soil.toe_shear_modulus,
                          toe_density=soil.toe_density,
                          toe_poisson_ratio=soil.toe_poisson_ratio)
        else:
            values.update(quake_toe=soil.quake_toe, damping_toe=soil.damping_toe)
    return {k: float(v) if isinstance(v, numbers.Real) else v for k, v in values.items()}


# ---------------------------------------------------------------------------- TOML resources
def hammer_toml(hammer) -> str:
    """A hammer file (TOML) that reads back as ``hammer``'s ram exactly.

    Parameters
    ----------
    hammer : Hammer
        The hammer (:class:`anvilwave.hammer.database.Hammer`).

    Returns
    -------
    str
        The TOML text: the segment masses [kg] and springs [N/m] (or a modal ram's toe modes)
        and the impact velocity [m/s].
    """
    ram = hammer.ram
    if ram.is_modal_unit:  # the toe modes of a modal ram (hammer.modal_ram)

        ram_table: dict[str, Any] = toe_modes_table(ram.modes)
    else:
        ram_table = {"segment_masses": [float(m) for m in ram.mass],
                     "segment_stiffnesses": [float(k) for k in ram.stiffness]}
    if math.isfinite(ram.toe_diameter):
        ram_table["diameter"] = float(ram.toe_diameter)
    root = {"name": hammer.name, "manufacturer": hammer.manufacturer,
            "description": f"Written by anvilwave from the hammer {hammer.name!r} "
                           "(its ram model).",
            "impact_velocity": float(hammer.impact_velocity), "ram": ram_table}
    return "# anvilwave Ram FMU resource: the ram of a system file (segments or toe modes).\n" \
        + toml_dumps(root)


def pile_soil_toml(model) -> str:
    """A pile/soil file (``[pile]``, ``[soil]``) that reads back as ``model`` exactly.

    Parameters
    ----------
    model : PileSoil
        The pile with its soil.

    Returns
    -------
    str
        The TOML text.

    Raises
    ------
    ValueError
        If the soil is given by capacities per segment (it has no SRD table to embed).
    """
    pile, soil = model.pile, model.soil
    sections = [{"length": s.length, "outer_diameter": s.outer_diameter,
                 "wall_thickness": s.wall_thickness, "youngs_modulus": s.youngs_modulus,
                 "density": s.density} for s in pile.sections]
    root: dict[str, Any] = {"pile": {"segment_length": pile.segment_length,
                                     "gauge_depth": pile.gauge_depth,
                                     "material_damping": pile.material_damping,
                                     "sections": sections}}
    if pile.material_damping_model != "segment":
        root["pile"]["material_damping_model"] = pile.material_damping_model
    if soil is not None and soil.capacities is not None:
        raise ValueError("a PileSoil FMU embeds its SRD table: a soil given by capacities per "
                         "segment (a drive analysis depth) has none")
    if soil is not None:
        table: dict[str, Any] = {
            "model": soil.model, "penetration": soil.penetration,
            "quake_shaft": soil.quake_shaft, "damping_shaft": soil.damping_shaft,
            "friction_perimeter": soil.friction_perimeter, "toe_area": soil.toe_area,
            "srd": np.column_stack([soil.srd.depth, soil.srd.unit_shaft_friction,
                                    soil.srd.unit_toe_resistance]).tolist(),
        }
        if soil.model == "lysmer-toe":
            table.update(toe_shear_modulus=soil.toe_shear_modulus, toe_density=soil.toe_density,
                         toe_poisson_ratio=soil.toe_poisson_ratio)
        else:
            table.update(quake_toe=soil.quake_toe, damping_toe=soil.damping_toe)
        root["soil"] = table
    return ("# anvilwave PileSoil FMU resource: the [pile] and [soil] tables of a system file.\n"
            "# The FMU parameters of the same names replace the scalar values here.\n"
            + toml_dumps(root))


# ---------------------------------------------------------------------------- Python runtime
def python_runtime() -> dict[str, Any]:
    """The Python that builds the FMUs, as the status shim needs it to run them in a C host.

    ``executable``: ``sys.executable`` (a venv's python as such, not resolved: initialized with
    it as program name, Python finds the venv and its site-packages); ``library``: its shared
    libpython (``sysconfig`` ``LIBDIR`` / ``INSTSONAME``; None for a Python without one, whose
    FMUs run in Python hosts only); ``version``: ``"3.X"``; ``site``: its site-packages folders
    (numpy, scipy, numba; the units' anvilwave code is inside the FMU).

    Returns
    -------
    dict of str to Any
        ``executable``, ``library``, ``version`` and ``site``, as above.
    """
    import site
    import sysconfig

    version = f"{sys.version_info[0]}.{sys.version_info[1]}"
    library = None
    name = sysconfig.get_config_var("INSTSONAME") or f"libpython{version}.so.1.0"
    folders = [sysconfig.get_config_var("LIBDIR"), sysconfig.get_config_var("LIBPL")]
    multiarch = sysconfig.get_config_var("MULTIARCH")
    if folders[0] and multiarch:
        folders.append(str(Path(folders[0]) / multiarch))
    for folder in filter(None, folders):
        if (Path(folder) / name).is_file():
            library = str(Path(folder) / name)
            break
    sites = [p for p in site.getsitepackages() if Path(p).is_dir()]
    return {"executable": sys.executable, "library": library, "version": version,
            "site": sites}


def python_runtime_text(runtime: dict[str, Any] | None = None) -> str:
    """``resources/anvilwave_python.txt``: :func:`python_runtime` as ``key = value`` lines.

    Parameters
    ----------
    runtime : dict of str to Any or None, optional
        A :func:`python_runtime` result (default: this Python's).

    Returns
    -------
    str
        Content of the file.
    """
    runtime = python_runtime() if runtime is None else runtime
    lines = ["# anvilwave: the Python that built this FMU. A host that is not Python loads its",
             "# library and runs the unit in it (anvilwave/fmu/units/fmi2_status_shim.c).",
             f"executable = {runtime['executable'] or ''}",
             f"library = {runtime['library'] or ''}",
             f"version = {runtime['version']}"]
    lines += [f"site = {folder}" for folder in runtime["site"]]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------- steps
def _defaults_file() -> str:

    return DEFAULTS_FILE


def _script(kind: str | Path) -> Path:
    if isinstance(kind, str) and kind in KINDS:
        return KINDS[kind]
    path = Path(kind)
    if path.suffix != ".py" or not path.is_file():
        raise InputError("build_fmu", "kind", f"must be one of {sorted(KINDS)} or a slave "
                                              f"script (.py), got {str(kind)!r}")
    return path


def _stage_resources(resources, stage: Path, script: Path) -> list[Path]:
    reserved = {_defaults_file(), script.name, "slavemodule.txt", "pythonfmu", RUNTIME_FILE,
                GUID_FILE}
    staged = []
    for res in resources:
        res = Path(res)
        if not res.is_file():
            raise InputError(str(res), "", "resource file not found")
        if res.name in reserved or res.name.startswith(PACKAGE_PREFIX) or \
                (stage / res.name).exists():
            raise InputError(str(res), "", f"resource name {res.name!r} is reserved or "
                                           "given twice")
        shutil.copy2(res, stage / res.name)
        staged.append(stage / res.name)
    return staged


def _slave_class(script: Path):
    """The slave class of a script (the deepest Fmi2Slave subclass it defines or imports)."""
    from pythonfmu import Fmi2Slave


    name = f"_anvilwave_build_{script.stem}"
    spec = importlib.util.spec_from_file_location(name, script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    classes = [obj for obj in vars(module).values()
               if inspect.isclass(obj) and issubclass(obj, Fmi2Slave)
               and not inspect.isabstract(obj)]
    if not classes:
        raise InputError(str(script), "", "defines no Fmi2Slave class")
    depth = max(len(c.__mro__) for c in classes)
    deepest = [c for c in classes if len(c.__mro__) == depth]
    if len(deepest) > 1:
        raise InputError(str(script), "", f"ambiguous slave classes {deepest}")
    if not issubclass(deepest[0], UnitSlave):
        raise InputError(str(script), "", "the slave must derive from fmu.units.base.UnitSlave")
    return deepest[0]


def _checked_parameters(cls, parameters: dict[str, Any]) -> dict[str, Any]:
    """Names and types of the build parameters, as plain JSON values."""
    from pythonfmu import Boolean, Real, String

    source = f"{cls.kind or cls.__name__} FMU build"
    probe = cls(instance_name="build_check", resources=None)
    declared = {v.name: v for v in probe.vars.values()}
    checked = {}
    for name, value in parameters.items():
        var = declared.get(name)
        if var is None or name not in probe.parameters:
            raise InputError(source, name, f"is not a parameter of this FMU (parameters: "
                                           f"{', '.join(sorted(probe.parameters))})")
        if isinstance(var, Real):
            ok = (isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
                  and math.isfinite(value))
            rule, plain = "must be a finite number", float
        elif isinstance(var, Boolean):
            ok, rule, plain = isinstance(value, bool | np.bool_), "must be true or false", bool
        elif isinstance(var, String):
            ok, rule, plain = isinstance(value, str), "must be a string", str
        else:
            ok, rule, plain = False, "has an unsupported type", None
        if not ok:
            raise InputError(source, name, f"{rule}, got {value!r}")
        checked[name] = plain(value)
    return checked


def _checked_slave(cls, stage: Path):
    """The slave on the staged resources, its component built once (as at initialization)."""
    probe = cls(instance_name="build_check", resources=str(stage))
    probe.exit_initialization_mode()
    errors = [msg.msg for msg in probe.log_queue if msg.status >= 3]
    if errors:
        raise InputError(f"{cls.kind or cls.__name__} FMU build", "", "; ".join(errors))
    return probe


def _pythonfmu_build(script: Path, dest: Path, project_files: list[Path]) -> Path:
    """pythonfmu's build, without leaving its sys.path / sys.modules changes behind."""
    from pythonfmu import FmuBuilder

    saved_path = list(sys.path)
    had_module = script.stem in sys.modules
    try:
        return Path(FmuBuilder.build_FMU(script, dest=dest, project_files=project_files))
    finally:
        sys.path[:] = saved_path
        if not had_module:
            sys.modules.pop(script.stem, None)


def _compile_shim(scratch: Path, wanted: bool | None) -> Path | None:
    if wanted is False:
        return None
    reason = None
    compiler = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not sys.platform.startswith("linux"):
        reason = "the status shim is only built on Linux"
    elif compiler is None:
        reason = "no C compiler (cc) found"
    else:
        out = scratch / "shim.so"
        cmd = [compiler, "-shared", "-fPIC", "-O2", "-fvisibility=hidden", "-o", str(out),
               str(SHIM_SOURCE), "-ldl", "-lpthread"]
        try:
            run = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as exc:  # e.g. $CC names no program
            reason = f"cannot run the C compiler {compiler!r}: {exc}"
        else:
            if run.returncode == 0:
                return out
            reason = f"compiling the status shim failed: {run.stderr.strip()}"
    if wanted:
        raise RuntimeError(reason)
    warnings.warn(f"{reason}; the FMU keeps the stock pythonfmu binary (a slave error is "
                  "reported as fmi2Discard by the next fmi2DoStep, not as fmi2Error)",
                  stacklevel=3)
    return None


def _post_process(built: Path, final: Path, slave, shim: Path | None,
                  experiment: dict[str, float] | None = None,
                  script: Path | None = None) -> None:
    with zipfile.ZipFile(built) as zin:
        root = ET.fromstring(zin.read("modelDescription.xml"))
        identifier = root.find("CoSimulation").get("modelIdentifier")
        complete_model_description(root, slave.fmi_units, slave.fmi_dependencies)
        if experiment is not None:
            node = root.find("DefaultExperiment")
            if node is None:
                node = ET.SubElement(root, "DefaultExperiment")
            node.attrib.clear()
            node.set("startTime", repr(experiment["start_time"]))
            node.set("stopTime", repr(experiment["stop_time"]))
            node.set("stepSize", repr(experiment["step_size"]))
        binary = f"binaries/linux64/{identifier}.so"
        files: dict[str, bytes] = {}
        for item in sorted(zin.infolist(), key=lambda i: i.filename):
            if item.filename == "modelDescription.xml" or item.is_dir():
                continue
            data = zin.read(item.filename)
            if shim is not None and item.filename == binary:
                files[f"binaries/linux64/{SHIM_INNER_LIBRARY}"] = data
                data = shim.read_bytes()
            files[item.filename] = data
    if script is not None:  # the unit's anvilwave code, the script importing it (vendoring)
        _, vendored = vendored_unit(script)
        files.update(vendored)
        files[LICENSE_FILES["anvilwave"]] = license_text()
        pythonfmu_license = pythonfmu_license_text()
        if pythonfmu_license is not None:
            files[LICENSE_FILES["pythonfmu"]] = pythonfmu_license
            files["resources/pythonfmu/LICENSE"] = pythonfmu_license
    _exact_start_values(root, slave.parameters)
    root.attrib.pop("generationDateAndTime", None)  # identical builds, identical files
    root.set("author", AUTHOR)
    root.set("version", anvilwave_version())
    root.set("license", LICENSE)
    root.set("guid", "")
    ET.indent(root, space="  ")
    guid = content_guid(ET.tostring(root, encoding="UTF-8"), files)
    root.set("guid", guid)
    files[f"resources/{GUID_FILE}"] = (guid + "\n").encode()
    files["modelDescription.xml"] = ET.tostring(root, encoding="UTF-8", xml_declaration=True)
    with zipfile.ZipFile(final, "w", zipfile.ZIP_DEFLATED) as zout:
        for name in ["modelDescription.xml", *sorted(set(files) - {"modelDescription.xml"})]:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            zout.writestr(info, files[name])


def _exact_start_values(root: ET.Element, values: dict[str, Any]) -> None:
    """Parameter start values as the unit reads them (``repr`` of a float: pythonfmu writes 16
    significant digits, so an SSP tool comparing with them would see another number)."""
    for var in root.find("ModelVariables").findall("ScalarVariable"):
        name = var.get("name")
        if var.get("causality") != "parameter" or name not in values:
            continue
        for node in var:
            if "start" in node.attrib:
                value = values[name]
                node.set("start", ("true" if value else "false") if isinstance(value, bool)
                         else repr(float(value)) if node.tag == "Real" else str(value))


def content_guid(model_description: bytes, files: dict[str, bytes]) -> str:
    """The GUID of an FMU from its content.

    A name-based UUID (RFC 4122 version 5 layout) of the SHA-256 of the model description (its
    ``guid`` empty) and of every other file (name and bytes), so that identical builds get
    identical GUIDs and any change a new one.

    Parameters
    ----------
    model_description : bytes
        ``modelDescription.xml`` with an empty ``guid``.
    files : dict of str to bytes
        Every other file of the FMU: name -> content.

    Returns
    -------
    str
        The GUID, in braces.

    References
    ----------
    Leach, P., Mealling, M. and Salz, R. (2005). A Universally Unique IDentifier (UUID) URN
    Namespace. RFC 4122, IETF.
    """
    digest = hashlib.sha256(model_description)
    for name in sorted(files):
        digest.update(b"\0" + name.encode() + b"\0" + len(files[name]).to_bytes(8, "little"))
        digest.update(files[name])
    return "{" + str(uuid.UUID(bytes=digest.digest()[:16], version=5)) + "}"


def anvilwave_version() -> str:
    """The installed anvilwave's version.

    Returns
    -------
    str
        The version (``0+unknown`` for a checkout that is not installed).
    """
    try:
        return importlib.metadata.version("anvilwave")
    except importlib.metadata.PackageNotFoundError:
        return "0+unknown"


def complete_model_description(root: ET.Element, units: dict[str, str],
                               dependencies: dict[str, tuple[str, ...]]) -> None:
    """Add what pythonfmu leaves out of a modelDescription.xml (in place).

    At initialization each output may depend on its inputs and on every parameter.

    Parameters
    ----------
    root : xml.etree.ElementTree.Element
        Root of the model description, completed in place.
    units : dict of str to str
        Variable name -> unit name (a key of :data:`UNIT_DEFINITIONS`).
    dependencies : dict of str to tuple of str
        Output name -> names of the inputs it depends on directly (feedthrough).

    Raises
    ------
    ValueError
        If a unit has no definition.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """
    variables = root.find("ModelVariables").findall("ScalarVariable")
    index = {v.get("name"): i + 1 for i, v in enumerate(variables)}
    for v in variables:
        unit = units.get(v.get("name"))
        real = v.find("Real")
        if unit is not None and real is not None:
            if unit not in UNIT_DEFINITIONS:
                raise ValueError(f"{v.get('name')}: unit {unit!r} has no definition")
            real.set("unit", unit)
    # UnitDefinitions go right after ModelExchange / CoSimulation (FMI 2.0 schema order)
    old = root.find("UnitDefinitions")
    if old is not None:
        root.remove(old)
    definitions = ET.Element("UnitDefinitions")
    for name, exponents in UNIT_DEFINITIONS.items():
        unit = ET.SubElement(definitions, "Unit", name=name)
        ET.SubElement(unit, "BaseUnit", {k: str(e) for k, e in exponents.items()})
    position = max(i for i, child in enumerate(root)
                   if child.tag in ("ModelExchange", "CoSimulation")) + 1
    root.insert(position, definitions)

    parameters = [index[v.get("name")] for v in variables if v.get("causality") == "parameter"]
    outputs = [v for v in variables if v.get("causality") == "output"]
    structure = root.find("ModelStructure")
    for child in list(structure):
        structure.remove(child)
    if outputs:
        out_node = ET.SubElement(structure, "Outputs")
        init_node = ET.SubElement(structure, "InitialUnknowns")
        for v in outputs:
            name = v.get("name")
            inputs = sorted(index[i] for i in dependencies.get(name, ()))
            ET.SubElement(out_node, "Unknown", index=str(index[name]),
                          dependencies=" ".join(map(str, inputs)))
            ET.SubElement(init_node, "Unknown", index=str(index[name]),
                          dependencies=" ".join(map(str, sorted(inputs + parameters))))


def _validate(fmu: Path) -> None:
    try:
        from fmpy.validation import validate_fmu
    except ImportError:  # fmpy is optional for building
        return
    problems = validate_fmu(str(fmu))
    if problems:
        raise RuntimeError(f"{fmu.name} does not validate: " + "; ".join(problems))
