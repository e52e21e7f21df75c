"""Build the native anvil FMUs: FMI 2.0 co-simulation in C, no Python at run time.

:func:`build_native_anvil_fmu` writes ``Anvil.fmu`` (the Mode Displacement Method ROM) or
``AnvilLumped.fmu`` (the rigid lumped mass) with the variables of the pythonfmu units of
:mod:`anvilwave.fmu.units.anvil` (same names, value references, types, causalities and parameters,
so
the two can be swapped) and the numerics of :mod:`anvilwave.anvil_rom.unit`, in C
(``anvilwave/fmu/native/anvil_model.c``; the FMI layer is ``anvilwave/fmu/native/anvil_fmu.c``).
The FMU holds

- ``modelDescription.xml`` with ``UnitDefinitions`` (SI base-unit exponents), the ``unit`` of
  every Real, ``ModelStructure`` (``Outputs``: the forces are a direct feedthrough of the
  inputs; ``InitialUnknowns``) and the ``SourceFiles`` of a source FMU;
- ``sources/``: every ``.c`` / ``.h`` needed (the FMI 2.0 headers, BSD-2-Clause, keep their
  license text), the generated ``anvil_config.h`` (model identifier, GUID, variable table with
  the build's start values) and ``buildDescription.xml`` (FMI 3.0 format, as FMI 2.0.4 allows);
- ``resources/modal_data.bin`` (ROM only): the modal data in the documented little-endian
  binary format ``anvilwave-modal`` version 1 (version 2 with a pile port in rings;
  ``anvilwave/fmu/native/anvil_model.h``,
  :func:`modal_resource_bytes`), read by ``fmi2Instantiate`` from ``fmuResourceLocation``;
- ``binaries/linux64/<modelIdentifier>.so`` compiled from ``sources/`` with the system C
  compiler (``compiler``, else ``$CC``, else ``cc`` / ``gcc`` on the PATH), without
  floating-point contraction so that the numbers are those of the Python kernels.

The modal data come as physics objects or plain arrays, never from system files: a
:class:`~anvilwave.anvil_rom.fem.modalfile.ModalData` (all stored modes are embedded; ``fmax`` [Hz],
``damping_ratio`` [-] and ``static_correction`` stay run-time parameters, as in the pythonfmu
Anvil), a :class:`~anvilwave.anvil_rom.rom.ModalAnvil` (the ROM as it is: its modes, circular
frequencies bit for bit, its damping ratio, and its static correction through the elastic
flexibility it implies, G = R + sum p p^T / omega^2), a mapping of plain arrays with the
ModalData names (``frequencies``, ``participation_ram``, ``participation_pile``,
``participation_gravity``, ``elastic_flexibility``, ``total_mass``, ``fmax``,
``damping_ratio``), or the path of a modal-data ``.npz`` file. The lumped anvil also takes a
mass [kg].

Build-time checks: parameter names and types, and the values through the same physics objects
the Python units build (:class:`~anvilwave.anvil_rom.unit.ContactParameters`,
:meth:`~anvilwave.anvil_rom.rom.ModalAnvil.from_modal_data`,
:meth:`~anvilwave.anvil_rom.rom.ModalAnvil.rigid`):
:class:`~anvilwave.inputs.InputError`, nothing written. A missing compiler or an unsupported
platform: :class:`NativeBuildError` naming what is missing. With ``validate`` the FMU is checked
with ``fmpy.validation.validate_fmu`` and instantiated, initialized and stepped once.
"""

from __future__ import annotations

import ctypes
import hashlib
import json
import math
import numbers
import os
import shutil
import struct
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

from anvilwave.anvil_rom.fem.modalfile import ModalData, check_modal_data, load_modal_data
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.unit import ContactParameters
from anvilwave.fmu.coupling import INPUT_EXTRAPOLATION_DESCRIPTION
from anvilwave.inputs import InputError

NATIVE_DIR = Path(__file__).resolve().parent / "native"
"""The C sources and headers of the native anvil FMU."""
C_SOURCES = ("anvil_fmu.c", "anvil_model.c", "fmu_common.c")
C_HEADERS = ("anvil_fmu.h", "anvil_model.h", "fmu_common.h", "fmi2Functions.h",
             "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")
CONFIG_HEADER = "anvil_config.h"
MODAL_RESOURCE = "modal_data.bin"
"""Name of the embedded modal data in ``resources/`` (start value of ``modal_data_file``)."""
MODAL_MAGIC = b"anvilwave-modal\x00"
MODAL_VERSION = 1
MODAL_VERSION_RINGS = 2
"""Version 2: version 1 and the rings of a pile port split across the wall."""
MODAL_HEADER_BYTES = 80
PLATFORM = "linux64"
CFLAGS = ("-shared", "-fPIC", "-O2", "-std=c99", "-ffp-contract=off", "-fvisibility=hidden",
          "-Wall", "-Wextra")
"""Compiler options (``-ffp-contract=off``: no fused multiply-add, as in the Python kernels)."""
GRAVITY = 9.81  # [m/s^2], anvil_rom.unit.GRAVITY


class NativeBuildError(RuntimeError):
    """The native FMU cannot be built here.

    No C compiler, an unsupported platform, the compiler failed, or the built FMU does not pass
    its check.
    """


# ---------------------------------------------------------------------------- variables
@dataclass(frozen=True)
class Variable:
    """An FMI variable of the native anvil FMUs.

    Parameters
    ----------
    name : str
        FMI variable name.
    slot : str
        The ``AnvilSlot`` of ``anvilwave/fmu/native/anvil_fmu.h`` without its ``ANVIL_`` prefix.
    kind : {"Real", "Boolean", "String"}
        FMI type.
    causality : {"parameter", "input", "output"}
        ``"parameter"`` (variability fixed), ``"input"`` or ``"output"`` (continuous).
    unit : str or None
        A unit of :data:`UNITS` or None.
    description : str
        FMI variable description.
    """

    name: str
    slot: str
    kind: str
    causality: str
    unit: str | None
    description: str


def _parameter(name, unit, description, kind="Real"):
    return Variable(name, name.upper(), kind, "parameter", unit, description)


_ROM_PARAMETERS = (
    _parameter("modal_data_file", None,
               "Modal-data file (anvilwave-modal binary, anvilwave/fmu/native/anvil_model.h); "
               "a relative "
               "name is looked up in the FMU resources, where the build embeds it [-]",
               "String"),
    _parameter("fmax", "Hz", "Frequency content of the ROM: modes up to fmax are kept, 0 keeps "
                             "all modes of the file [Hz]"),
    _parameter("damping_ratio", "1", "Modal damping ratio of the flexible modes [-]"),
    _parameter("static_correction", None, "Add the residual flexibility of the truncated modes "
                                          "(static correction) [-]", "Boolean"),
)
_LUMPED_PARAMETERS = (
    _parameter("mass", "kg", "Anvil mass (the FE model's total mass) [kg]"),
)
_COMMON = (
    _parameter("ram_contact_stiffness", "N/m", "Ram-anvil compression-only contact spring [N/m]"),
    _parameter("pile_contact_stiffness", "N/m",
               "Anvil-pile compression-only contact spring [N/m]"),
    _parameter("ram_contact_damping", "N.s/m", "Ram-anvil contact dashpot [N s/m]"),
    _parameter("pile_contact_damping", "N.s/m", "Anvil-pile contact dashpot [N s/m]"),
    _parameter("gravity", "m/s2", "Gravitational acceleration, 0 switches it off [m/s^2]"),
    _parameter("start_at_rest", None, "Start in static equilibrium on the pile under gravity "
                                      "(else undeformed at zero displacement) [-]", "Boolean"),
    _parameter("initial_pile_head_displacement", "m",
               "Pile head displacement the anvil rests on at the start, positive down [m]"),
    _parameter("input_extrapolation", None, INPUT_EXTRAPOLATION_DESCRIPTION, "Boolean"),
    Variable("u_ram", "U_RAM", "Real", "input", "m", "Ram toe displacement, positive down [m]"),
    Variable("v_ram", "V_RAM", "Real", "input", "m/s", "Ram toe velocity, positive down [m/s]"),
    Variable("u_pile", "U_PILE", "Real", "input", "m", "Pile head displacement, positive down [m]"),
    Variable("v_pile", "V_PILE", "Real", "input", "m/s",
             "Pile head velocity, positive down [m/s]"),
    Variable("F_ram", "F_RAM", "Real", "output", "N",
             "Ram-anvil contact force, compression positive [N]"),
    Variable("F_pile", "F_PILE", "Real", "output", "N",
             "Anvil-pile contact force, compression positive [N]"),
    Variable("u_top", "U_TOP", "Real", "output", "m",
             "Anvil top face displacement (ram contact), positive down [m]"),
    Variable("u_bottom", "U_BOTTOM", "Real", "output", "m",
             "Anvil bottom ring displacement (pile contact), positive down [m]"),
)
INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")
OUTPUTS = ("F_ram", "F_pile", "u_top", "u_bottom")

FEEDTHROUGH = {
    # the static correction couples the two contacts: every output sees every input
    "Anvil": {name: INPUTS for name in OUTPUTS},
    # a rigid body has no static correction: each force sees only its own contact
    "AnvilLumped": {"F_ram": ("u_ram", "v_ram"), "F_pile": ("u_pile", "v_pile"),
                    "u_top": (), "u_bottom": ()},
}
"""Inputs each output depends on directly (ModelStructure/Outputs), per model identifier."""

FALLBACKS: dict[str, Any] = {
    "ram_contact_damping": 0.0, "pile_contact_damping": 0.0, "gravity": GRAVITY,
    "start_at_rest": True, "initial_pile_head_displacement": 0.0, "static_correction": False,
    "modal_data_file": MODAL_RESOURCE, "input_extrapolation": False,
}
"""Start values of parameters the build does not set (contact stiffnesses have none)."""

UNITS: dict[str, dict[str, int]] = {
    "m": {"m": 1}, "m/s": {"m": 1, "s": -1}, "m/s2": {"m": 1, "s": -2},
    "N": {"kg": 1, "m": 1, "s": -2}, "N/m": {"kg": 1, "s": -2}, "N.s/m": {"kg": 1, "s": -1},
    "Hz": {"s": -1}, "kg": {"kg": 1}, "1": {},
}
"""SI base-unit exponents of the anvil's units (as in
:data:`anvilwave.fmu.fmi_build.UNIT_DEFINITIONS`)."""

DESCRIPTIONS = {
    "Anvil": "anvilwave anvil (native): Mode Displacement Method ROM with compression-only ram "
             "and pile contacts (SI units, z down, compression positive)",
    "AnvilLumped": "anvilwave anvil (native): rigid lumped mass with compression-only ram and "
                   "pile contacts (SI units, z down, compression positive)",
}


def anvil_variables(lumped: bool = False) -> tuple[Variable, ...]:
    """The variables of the native Anvil (or AnvilLumped) FMU.

    Parameters
    ----------
    lumped : bool, default False
        The AnvilLumped FMU's variables instead of the Anvil (ROM) FMU's.

    Returns
    -------
    tuple of Variable
        The variables; the value reference of each is its position (as in the pythonfmu units).
    """
    return (_LUMPED_PARAMETERS if lumped else _ROM_PARAMETERS) + _COMMON


# ---------------------------------------------------------------------------- modal data
@dataclass(frozen=True)
class NativeModalData:
    """The content of the ``anvilwave-modal`` binary resource.

    The layout is in ``anvilwave/fmu/native/anvil_model.h``. It has the attributes
    :func:`anvilwave.anvil_rom.fem.modalfile.check_modal_data` and
    :meth:`anvilwave.anvil_rom.rom.ModalAnvil.from_modal_data` read. The (n,) arrays have mode
    0 the rigid-body mode.

    Parameters
    ----------
    frequencies : numpy.ndarray
        Natural frequencies, shape (n,) [Hz].
    omega : numpy.ndarray
        Circular frequencies (= 2 pi frequencies), shape (n,) [rad/s].
    participation_ram : numpy.ndarray
        Participation of the ram port, shape (n,) [kg^-1/2].
    participation_pile : numpy.ndarray
        Participation of the pile port, shape (n,) [kg^-1/2].
    participation_gravity : numpy.ndarray
        Participation of gravity, shape (n,) [kg^1/2].
    elastic_flexibility : numpy.ndarray
        Elastic flexibility of the ports, shape (2, 2) [m/N].
    total_mass : float
        Total mass [kg].
    fmax : float
        Frequency content of the data [Hz].
    damping_ratio : float
        Modal damping ratio [-].
    participation_rings : numpy.ndarray or None, default None
        With a pile port in K rings (version 2): participation of the rings, shape (K, n)
        [kg^-1/2]; None for one port.
    ring_flexibility : numpy.ndarray or None, default None
        With rings: flexibility of the ram port and the rings, shape (K + 1, K + 1) [m/N];
        None for one port.
    ring_areas : numpy.ndarray or None, default None
        With rings: ring areas, shape (K,) [m^2]; None for one port.
    """

    frequencies: np.ndarray
    omega: np.ndarray
    participation_ram: np.ndarray
    participation_pile: np.ndarray
    participation_gravity: np.ndarray
    elastic_flexibility: np.ndarray
    total_mass: float
    fmax: float
    damping_ratio: float
    participation_rings: np.ndarray | None = None
    ring_flexibility: np.ndarray | None = None
    ring_areas: np.ndarray | None = None

    @property
    def n_modes(self) -> int:
        """Number of modes n.

        Returns
        -------
        int
            Number of modes n [-].
        """
        return len(self.frequencies)


def modal_resource_bytes(data: NativeModalData) -> bytes:
    """The ``anvilwave-modal`` file of ``data``.

    An 80-byte header + 40 bytes per mode, little-endian, version 1; with rings version 2, the
    rings after the modes (layout in ``anvilwave/fmu/native/anvil_model.h``).

    Parameters
    ----------
    data : NativeModalData
        The modal data.

    Returns
    -------
    bytes
        Content of the file.

    Raises
    ------
    ValueError
        If a per-mode array does not have shape (n,).
    """
    n = data.n_modes
    scalars = [data.total_mass, data.fmax, data.damping_ratio,
               *np.asarray(data.elastic_flexibility, dtype=float).reshape(4)]
    arrays = [data.frequencies, data.omega, data.participation_ram, data.participation_pile,
              data.participation_gravity]
    for a in arrays:
        if np.shape(a) != (n,):
            raise ValueError(f"every per-mode array must have shape ({n},)")
    rings = data.participation_rings
    body = (np.asarray(scalars, dtype="<f8").tobytes()
            + np.concatenate([np.asarray(a, dtype="<f8") for a in arrays]).tobytes())
    if rings is None:
        return MODAL_MAGIC + struct.pack("<II", MODAL_VERSION, n) + body
    K = len(rings)
    trailer = np.concatenate([np.asarray(rings, dtype="<f8").reshape(K * n),
                              np.asarray(data.ring_flexibility, dtype="<f8").reshape(
                                  (K + 1) ** 2),
                              np.asarray(data.ring_areas, dtype="<f8").reshape(K)])
    return (MODAL_MAGIC + struct.pack("<II", MODAL_VERSION_RINGS, n) + body
            + struct.pack("<II", K, 0) + trailer.tobytes())


def read_modal_resource(source: str | Path | bytes) -> NativeModalData:
    """Read an ``anvilwave-modal`` file (a path or its bytes).

    Only the layout is checked here; the physical rules are checked by the FMU at
    initialization and by :func:`anvilwave.anvil_rom.fem.modalfile.check_modal_data`.

    Parameters
    ----------
    source : str, pathlib.Path or bytes
        Path of the file, or its content.

    Returns
    -------
    NativeModalData
        The modal data of the file.

    Raises
    ------
    InputError
        If the file is malformed.
    """
    name = "<bytes>" if isinstance(source, bytes | bytearray) else str(source)
    raw = bytes(source) if isinstance(source, bytes | bytearray) else Path(source).read_bytes()
    if len(raw) < MODAL_HEADER_BYTES or raw[:16] != MODAL_MAGIC:
        raise InputError(name, "", "not an anvilwave-modal file")
    version, n = struct.unpack("<II", raw[16:24])
    if version not in (MODAL_VERSION, MODAL_VERSION_RINGS):
        raise InputError(name, "version", f"format version {version} is not supported")
    end = MODAL_HEADER_BYTES + 40 * n
    rings = {}
    if version == MODAL_VERSION_RINGS:
        if len(raw) < end + 8:
            raise InputError(name, "", f"{len(raw)} bytes: no ring count after {n} modes")
        (K,) = struct.unpack("<I", raw[end:end + 4])
        size = end + 8 + 8 * (K * n + (K + 1) ** 2 + K)
        if K < 2 or len(raw) != size:
            raise InputError(name, "", f"{len(raw)} bytes, expected {size} for {n} modes and "
                                       f"{K} rings (at least 2)")
        trailer = np.frombuffer(raw, dtype="<f8", offset=end + 8).astype(float)
        rings = {"participation_rings": trailer[:K * n].reshape(K, n).copy(),
                 "ring_flexibility": trailer[K * n:K * n + (K + 1) ** 2].reshape(K + 1,
                                                                               K + 1).copy(),
                 "ring_areas": trailer[K * n + (K + 1) ** 2:].copy()}
    elif len(raw) != end:
        raise InputError(name, "", f"{len(raw)} bytes, expected {end} for {n} modes")
    scalars = np.frombuffer(raw, dtype="<f8", count=7, offset=24).astype(float)
    body = np.frombuffer(raw, dtype="<f8", count=5 * n, offset=MODAL_HEADER_BYTES).astype(float)
    arrays = body.reshape(5, n)
    return NativeModalData(arrays[0].copy(), arrays[1].copy(), arrays[2].copy(), arrays[3].copy(),
                           arrays[4].copy(), scalars[3:].reshape(2, 2).copy(), float(scalars[0]),
                           float(scalars[1]), float(scalars[2]), **rings)


def native_modal_data(modal, source: str = "native Anvil FMU build") -> NativeModalData:
    """The modal data of a ROM build, checked like a modal-data file.

    Parameters
    ----------
    modal : ModalData, ModalAnvil, mapping or path
        A ModalData, a ModalAnvil, a mapping of plain arrays (ModalData names) or a modal-data
        ``.npz`` path.
    source : str, default "native Anvil FMU build"
        Name of the source in error messages.

    Returns
    -------
    NativeModalData
        The modal data.

    Raises
    ------
    InputError
        If the data are missing, of the wrong kind or fail the checks of a modal-data file.
    """

    if isinstance(modal, str | os.PathLike):
        modal = load_modal_data(modal)
    if isinstance(modal, ModalAnvil):
        omega = np.asarray(modal.omega, dtype=float)
        p_ram = np.asarray(modal.participation_ram, dtype=float)
        p_pile = np.asarray(modal.participation_pile, dtype=float)
        flexible = omega > 0.0
        P = np.vstack([p_ram[flexible], p_pile[flexible]])
        # the elastic flexibility this ROM implies: its residual + its kept flexible modes
        G = np.asarray(modal.residual_flexibility, dtype=float) + (P / omega[flexible] ** 2) @ P.T
        G = 0.5 * (G + G.T)
        frequencies = omega / (2.0 * np.pi)
        rings = {}
        if modal.participation_rings is not None:  # the ring flexibility it implies, likewise
            P_rings = np.vstack([p_ram, modal.participation_rings])[:, flexible]
            G_rings = (np.asarray(modal.residual_rings, dtype=float)
                       + (P_rings / omega[flexible] ** 2) @ P_rings.T)
            rings = {"participation_rings": np.asarray(modal.participation_rings, dtype=float),
                     "ring_flexibility": 0.5 * (G_rings + G_rings.T),
                     "ring_areas": np.asarray(modal.ring_areas, dtype=float)}
        data = NativeModalData(frequencies, omega, p_ram, p_pile,
                               np.asarray(modal.participation_gravity, dtype=float), G,
                               float(modal.total_mass),
                               float(max(modal.fmax, frequencies[-1])),
                               float(modal.damping_ratio), **rings)
    else:
        if isinstance(modal, Mapping):
            keys = ("frequencies", "participation_ram", "participation_pile",
                    "participation_gravity", "elastic_flexibility", "total_mass", "fmax",
                    "damping_ratio")
            missing = [k for k in keys if k not in modal]
            if missing:
                raise InputError(source, missing[0], "is missing from the modal arrays")
            unknown = sorted(set(modal) - set(keys) - {"omega"})
            if unknown:
                raise InputError(source, unknown[0], f"is not a modal array (arrays: "
                                                     f"{', '.join(keys)})")
        elif not isinstance(modal, ModalData):
            raise InputError(source, "modal", f"must be a ModalData, a ModalAnvil, a mapping of "
                                              f"modal arrays or a .npz path, got "
                                              f"{type(modal).__name__}")
        get = modal.__getitem__ if isinstance(modal, Mapping) else modal.__getattribute__
        frequencies = np.asarray(get("frequencies"), dtype=float)
        try:
            scalars = [float(get(k)) for k in ("total_mass", "fmax", "damping_ratio")]
        except (TypeError, ValueError):
            raise InputError(source, "total_mass / fmax / damping_ratio",
                             "must be numbers") from None
        # omega as ModalAnvil.from_modal_data computes it (a mapping may give its own)
        omega = (np.asarray(modal["omega"], dtype=float)
                 if isinstance(modal, Mapping) and "omega" in modal
                 else 2.0 * np.pi * frequencies)
        rings = {}
        if isinstance(modal, ModalData) and modal.participation_rings is not None:
            rings = {key: np.asarray(getattr(modal, key), dtype=float)
                     for key in ("participation_rings", "ring_flexibility", "ring_areas")}
        data = NativeModalData(frequencies, omega,
                               np.asarray(get("participation_ram"), dtype=float),
                               np.asarray(get("participation_pile"), dtype=float),
                               np.asarray(get("participation_gravity"), dtype=float),
                               np.asarray(get("elastic_flexibility"), dtype=float), *scalars,
                               **rings)
    if data.frequencies.ndim != 1:
        raise InputError(source, "frequencies", "must be a 1D array")
    check_modal_data(data, source)
    w = 2.0 * np.pi * data.frequencies
    if data.omega.shape != w.shape or not np.all(np.abs(data.omega - w) <= 1e-12 * w):
        raise InputError(source, "omega", "must be 2 pi times the frequencies [rad/s]")
    return data


# ---------------------------------------------------------------------------- the build
def build_native_anvil_fmu(modal, out_path: str | Path, *, lumped: bool = False,
                           compiler: str | None = None, validate: bool = True,
                           default_experiment: tuple[float, float, float] | None = None,
                           **parameters) -> Path:
    """Build the native ``Anvil.fmu`` (ROM) or, with ``lumped``, ``AnvilLumped.fmu``.

    Parameters
    ----------
    modal : ModalData, ModalAnvil, mapping, path or float
        The anvil's modal data: a :class:`~anvilwave.anvil_rom.fem.modalfile.ModalData`, a
        :class:`~anvilwave.anvil_rom.rom.ModalAnvil`, a mapping of plain arrays with the
        ModalData names, or a modal-data ``.npz`` path (module docstring); for ``lumped`` also
        a mass [kg].
    out_path : str or pathlib.Path
        The ``.fmu`` file to write, or a folder (then ``<folder>/Anvil.fmu`` or
        ``AnvilLumped.fmu``). Written in one step; nothing is written when the build fails.
    lumped : bool, default False
        The rigid lumped-mass anvil (mass default: the modal data's total mass [kg]).
    compiler : str or None, optional
        C compiler command (default: ``$CC``, else ``cc`` or ``gcc`` on the PATH).
    validate : bool, default True
        Check the FMU with fmpy (``validate_fmu``, then instantiate, initialize and step it
        once); needs fmpy.
    default_experiment : tuple of float or None, optional
        (start time, stop time, step) [s] of the system the FMU is built for, its
        ``DefaultExperiment`` (as :func:`anvilwave.fmu.fmi_build.build_fmu`'s; default
        :data:`DEFAULT_EXPERIMENT`).
    **parameters
        Start values of the FMU parameters, SI units: ``ram_contact_stiffness`` [N/m] and
        ``pile_contact_stiffness`` [N/m] (required), ``ram_contact_damping``,
        ``pile_contact_damping`` [N s/m], ``gravity`` [m/s^2], ``start_at_rest``,
        ``initial_pile_head_displacement`` [m], ``input_extrapolation`` (default off; on for
        Jacobi-type masters, see :mod:`anvilwave.fmu.coupling`); ROM: ``fmax`` [Hz] (default
        the data's; 0 keeps all modes), ``damping_ratio`` [-] (default the data's),
        ``static_correction`` (default off, on for a ModalAnvil that has one); lumped: ``mass``
        [kg].

    Returns
    -------
    pathlib.Path
        The path of the ``.fmu``.

    Raises
    ------
    InputError
        If the modal data, a parameter or ``default_experiment`` is invalid.
    NativeBuildError
        If no C compiler is found, the platform is not supported, the compiler fails or the
        built FMU does not pass its check.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """
    model = "AnvilLumped" if lumped else "Anvil"
    source = f"native {model} FMU build"
    variables = anvil_variables(lumped)
    data, defaults = _modal_defaults(modal, lumped, source)
    values = _start_values(variables, {**defaults, **parameters}, source, set(parameters))
    _check_physics(data, values, lumped)
    experiment = default_experiment_values(default_experiment, source)
    cc = find_compiler(compiler)
    out_path = Path(out_path)
    target = out_path if out_path.suffix == ".fmu" else out_path / f"{model}.fmu"
    with tempfile.TemporaryDirectory(prefix="anvilwave_native_") as scratch:
        stage = Path(scratch) / "fmu"
        sources = stage / "sources"
        sources.mkdir(parents=True)
        resource = b""
        if data is not None:
            resource = modal_resource_bytes(data)
            (stage / "resources").mkdir()
            (stage / "resources" / MODAL_RESOURCE).write_bytes(resource)
        for name in C_SOURCES + C_HEADERS:
            shutil.copyfile(NATIVE_DIR / name, sources / name)
        guid = _guid(model, variables, values, resource, sources,
                     None if default_experiment is None else experiment)
        (sources / CONFIG_HEADER).write_text(config_header(model, guid, variables, values),
                                             encoding="ascii")
        (sources / "buildDescription.xml").write_bytes(build_description(model))
        (stage / "modelDescription.xml").write_bytes(
            model_description(model, guid, variables, values, experiment))
        binary = stage / "binaries" / PLATFORM / f"{model}.so"
        compile_binary(cc, sources, binary)
        archive = Path(scratch) / f"{model}.fmu"
        _zip(stage, archive)
        if validate:
            _validate(archive, stage, model, guid)
        target.parent.mkdir(parents=True, exist_ok=True)
        part = target.with_name(target.name + ".part")
        shutil.copyfile(archive, part)
        part.replace(target)
    return target


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


def find_compiler(compiler: str | None = None) -> str:
    """The C compiler command: ``compiler``, else ``$CC``, else ``cc`` or ``gcc`` on the PATH.

    Parameters
    ----------
    compiler : str or None, optional
        C compiler command to use.

    Returns
    -------
    str
        The compiler command.

    Raises
    ------
    NativeBuildError
        Naming what is missing (the compiler, or a supported platform).
    """
    if not (sys.platform.startswith("linux") and sys.maxsize > 2**32):
        raise NativeBuildError(f"the native anvil FMU is built for {PLATFORM} only (this is "
                               f"{sys.platform}); its sources/ can be compiled by the importing "
                               "tool")
    wanted = compiler or os.environ.get("CC")
    if wanted:
        found = shutil.which(wanted.split()[0]) if wanted.split() else None
        if found is None:
            origin = "compiler argument" if compiler else "$CC"
            raise NativeBuildError(f"C compiler {wanted!r} (from the {origin}) not found: "
                                   "install it or name another one")
        return wanted
    found = shutil.which("cc") or shutil.which("gcc")
    if found is None:
        raise NativeBuildError("no C compiler found (neither $CC nor cc or gcc on the PATH): "
                               "install gcc (e.g. apt-get install gcc) or pass compiler=...")
    return found


def compile_binary(compiler: str, sources: Path, binary: Path) -> Path:
    """Compile the ``.c`` files of ``sources`` into the shared library ``binary``.

    Parameters
    ----------
    compiler : str
        C compiler command.
    sources : pathlib.Path
        Folder of the C sources and headers.
    binary : pathlib.Path
        The shared library to write.

    Returns
    -------
    pathlib.Path
        ``binary``.

    Raises
    ------
    NativeBuildError
        If the compiler cannot run or fails.
    """
    binary.parent.mkdir(parents=True, exist_ok=True)
    files = sorted(str(p) for p in sources.glob("*.c"))
    cmd = [*compiler.split(), *CFLAGS, "-I", str(sources), "-o", str(binary), *files, "-lm",
           "-Wl,-z,defs"]
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    except OSError as exc:
        raise NativeBuildError(f"cannot run the C compiler {compiler!r}: {exc}") from None
    if run.returncode != 0 or not binary.is_file():
        raise NativeBuildError(f"compiling {binary.name} failed ({' '.join(cmd)}):\n"
                               f"{run.stderr.strip()}")
    return binary


# ---------------------------------------------------------------------------- parameters
def _modal_defaults(modal, lumped: bool, source: str):
    """(modal data or None, parameter defaults) of the build."""
    if lumped:
        if isinstance(modal, numbers.Real) and not isinstance(modal, bool):
            return None, {"mass": float(modal)}

        if isinstance(modal, ModalAnvil):
            return None, {"mass": float(modal.total_mass)}
        return None, {"mass": native_modal_data(modal, source).total_mass}

    data = native_modal_data(modal, source)
    defaults: dict[str, Any] = {"fmax": data.fmax, "damping_ratio": data.damping_ratio}
    if isinstance(modal, ModalAnvil):
        defaults["static_correction"] = bool(np.any(modal.residual_flexibility != 0.0))
    return data, defaults


def _start_values(variables, given: dict[str, Any], source: str, explicit: set[str]
                  ) -> dict[str, Any]:
    """Checked start values of every parameter (build value, else fallback)."""
    declared = {v.name: v for v in variables if v.causality == "parameter"}
    for name in given:
        if name not in declared:
            raise InputError(source, name, f"is not a parameter of this FMU (parameters: "
                                           f"{', '.join(sorted(declared))})")
    if "modal_data_file" in explicit:
        raise InputError(source, "modal_data_file", "is set by the build (the embedded modal "
                                                    "data); a host may name another file at "
                                                    "run time")
    values: dict[str, Any] = {}
    for name, var in declared.items():
        value = given.get(name, FALLBACKS.get(name))
        if value is None:
            raise InputError(source, name, "has no default: set it when building the FMU")
        if var.kind == "Real":
            ok = (isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
                  and math.isfinite(value))
            rule, plain = "must be a finite number", float
        elif var.kind == "Boolean":
            ok, rule, plain = isinstance(value, bool | np.bool_), "must be true or false", bool
        else:
            ok, rule, plain = isinstance(value, str), "must be a string", str
        if not ok:
            raise InputError(source, name, f"{rule}, got {value!r}")
        values[name] = plain(value)
    return values


def _check_physics(data, values: dict[str, Any], lumped: bool) -> None:
    """The rules of the Python units, through their physics objects (InputError)."""

    ContactParameters(values["ram_contact_stiffness"], values["pile_contact_stiffness"],
                      values["ram_contact_damping"], values["pile_contact_damping"])
    if lumped:
        ModalAnvil.rigid(values["mass"])
    else:
        ModalAnvil.from_modal_data(data, fmax=values["fmax"] or None,
                                   damping_ratio=values["damping_ratio"],
                                   static_correction=values["static_correction"],
                                   source="native Anvil FMU build")


# ---------------------------------------------------------------------------- files
def _guid(model: str, variables, values: dict[str, Any], resource: bytes, sources: Path,
          experiment: tuple[float, float, float] | None = None) -> str:
    """A GUID from the content (same inputs, same GUID: reproducible builds)."""
    digest = hashlib.sha256()
    digest.update(model.encode())
    if experiment is not None:
        digest.update(" ".join(x.hex() for x in experiment).encode())
    digest.update(json.dumps([[v.name, v.kind, v.causality, v.unit] for v in variables]).encode())
    digest.update(json.dumps({k: (v.hex() if isinstance(v, float) else v)
                              for k, v in values.items()}, sort_keys=True).encode())
    digest.update(resource)
    for path in sorted(sources.iterdir()):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return str(uuid.UUID(bytes=digest.digest()[:16], version=4))


def config_header(model: str, guid: str, variables, values: dict[str, Any]) -> str:
    """``anvil_config.h``: model identifier, GUID and the variable table with start values.

    Parameters
    ----------
    model : str
        Model identifier, ``"Anvil"`` or ``"AnvilLumped"``.
    guid : str
        GUID of the FMU.
    variables : sequence of Variable
        The FMU's variables, in value-reference order.
    values : dict of str to Any
        Start values of the parameters [SI].

    Returns
    -------
    str
        Content of the header.
    """
    lines = [
        f"/* anvil_config.h -- the {model} FMU of this build: model identifier, GUID and its",
        " * variables (value reference, type, causality, slot, name, start value). Written by",
        " * anvilwave/fmu/native_build.py together with modelDescription.xml, which holds the",
        " * same table;",
        " * rebuild rather than edit. */",
        "#ifndef ANVIL_CONFIG_H",
        "#define ANVIL_CONFIG_H",
        "",
        '#include "anvil_fmu.h"',
        "",
        f'#define ANVIL_MODEL_IDENTIFIER "{model}"',
        f'#define ANVIL_GUID "{guid}"',
        f"#define ANVIL_LUMPED {1 if model == 'AnvilLumped' else 0}",
        "",
        "static const AnvilVariable ANVIL_VARIABLES[] = {",
        "    /* {vr, type, causality, slot, name, Real start, Boolean start, String start} */",
    ]
    for vr, v in enumerate(variables):
        value = values.get(v.name)
        real = boolean = "0"
        string = "NULL"
        comment = ""
        if v.kind == "Real":
            start = float(value) if v.causality == "parameter" else 0.0
            real = start.hex()
            comment = f" /* {start!r} */"
        elif v.kind == "Boolean":
            boolean = "1" if value else "0"
        else:
            string = json.dumps(value, ensure_ascii=True)
        lines.append(f"    {{{vr}, ANVIL_{v.kind.upper()}, ANVIL_{v.causality.upper()}, "
                     f"ANVIL_{v.slot},")
        lines.append(f"     \"{v.name}\", {real}{comment}, {boolean}, {string}}},")
    lines += ["};", "", "#endif /* ANVIL_CONFIG_H */", ""]
    return "\n".join(lines)


def model_description(model: str, guid: str, variables, values: dict[str, Any],
                      experiment: tuple[float, float, float] = DEFAULT_EXPERIMENT) -> bytes:
    """``modelDescription.xml`` (FMI 2.0 co-simulation, source FMU).

    Parameters
    ----------
    model : str
        Model identifier, ``"Anvil"`` or ``"AnvilLumped"``.
    guid : str
        GUID of the FMU.
    variables : sequence of Variable
        The FMU's variables, in value-reference order.
    values : dict of str to Any
        Start values of the parameters [SI].
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
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "2.0", "modelName": model, "guid": guid,
        "description": DESCRIPTIONS[model], "generationTool": "anvilwave fmu.native_build",
        "variableNamingConvention": "structured"})
    cs = ET.SubElement(root, "CoSimulation", {
        "modelIdentifier": model, "needsExecutionTool": "false",
        "canHandleVariableCommunicationStepSize": "true", "canInterpolateInputs": "false",
        "maxOutputDerivativeOrder": "0", "canRunAsynchronuously": "false",
        "canBeInstantiatedOnlyOncePerProcess": "false",
        "canNotUseMemoryManagementFunctions": "true", "canGetAndSetFMUstate": "false",
        "canSerializeFMUstate": "false", "providesDirectionalDerivative": "false"})
    files = ET.SubElement(cs, "SourceFiles")
    for name in C_SOURCES:
        ET.SubElement(files, "File", name=name)
    units = ET.SubElement(root, "UnitDefinitions")
    used = {v.unit for v in variables if v.unit is not None}
    for name, exponents in UNITS.items():
        if name in used:
            unit = ET.SubElement(units, "Unit", name=name)
            ET.SubElement(unit, "BaseUnit", {k: str(e) for k, e in exponents.items()})
    categories = ET.SubElement(root, "LogCategories")
    for name, text in (("logStatusError", "Errors (always reported)"),
                       ("logStatusWarning", "Warnings (always reported)"),
                       ("logCalls", "Every FMI call, with debug logging on")):
        ET.SubElement(categories, "Category", name=name, description=text)
    ET.SubElement(root, "DefaultExperiment", startTime=repr(experiment[0]),
                  stopTime=repr(experiment[1]), stepSize=repr(experiment[2]))
    mv = ET.SubElement(root, "ModelVariables")
    index = {}
    for vr, v in enumerate(variables):
        index[v.name] = vr + 1
        attrs = {"name": v.name, "valueReference": str(vr), "description": v.description,
                 "causality": v.causality,
                 "variability": "fixed" if v.causality == "parameter" else "continuous"}
        sv = ET.SubElement(mv, "ScalarVariable", attrs)
        typed: dict[str, str] = {}
        if v.causality == "parameter":
            value = values[v.name]
            typed["start"] = ("true" if value else "false") if v.kind == "Boolean" else (
                repr(float(value)) if v.kind == "Real" else value)
        elif v.causality == "input":
            typed["start"] = "0.0"
        if v.unit is not None:
            typed["unit"] = v.unit
        ET.SubElement(sv, v.kind, typed)
    structure = ET.SubElement(root, "ModelStructure")
    outputs = ET.SubElement(structure, "Outputs")
    initial = ET.SubElement(structure, "InitialUnknowns")
    parameters = [index[v.name] for v in variables if v.causality == "parameter"]
    for name in OUTPUTS:
        inputs = sorted(index[i] for i in FEEDTHROUGH[model][name])
        ET.SubElement(outputs, "Unknown", index=str(index[name]),
                      dependencies=" ".join(map(str, inputs)))
        ET.SubElement(initial, "Unknown", index=str(index[name]),
                      dependencies=" ".join(map(str, sorted(inputs + parameters))))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def build_description(model: str) -> bytes:
    """``sources/buildDescription.xml`` (FMI 3.0 format, optional in an FMI 2.0.4 source FMU).

    Parameters
    ----------
    model : str
        Model identifier, ``"Anvil"`` or ``"AnvilLumped"``.

    Returns
    -------
    bytes
        Content of the file (UTF-8).

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4 and FMI 3.0. https://fmi-standard.org
    """
    root = ET.Element("fmiBuildDescription", fmiVersion="3.0")
    config = ET.SubElement(root, "BuildConfiguration", modelIdentifier=model,
                           description="Compile the files into one shared library; keep "
                                       "floating-point contraction off so that the results "
                                       "equal those of anvilwave's Python kernels")
    files = ET.SubElement(config, "SourceFileSet", language="C99",
                          compilerOptions="-ffp-contract=off")
    for name in C_SOURCES:
        ET.SubElement(files, "SourceFile", name=name)
    ET.SubElement(config, "Library", name="m", external="true",
                  description="the C math library (exp, cos, sqrt)")
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def _zip(stage: Path, archive: Path) -> None:
    """The FMU archive of ``stage``: sorted entries with a fixed date (reproducible)."""
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zf:
        for path in sorted(p for p in stage.rglob("*") if p.is_file()):
            info = zipfile.ZipInfo(path.relative_to(stage).as_posix(), (1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = (0o755 if path.suffix == ".so" else 0o644) << 16
            zf.writestr(info, path.read_bytes())


def _validate(archive: Path, stage: Path, model: str, guid: str) -> None:
    """fmpy's validation, then instantiate, initialize and step the staged anvil FMU once
    (:func:`check_staged_fmu` with the anvil's output references)."""
    names = [v.name for v in anvil_variables(model == "AnvilLumped")]
    check_staged_fmu(archive, stage, model, guid, [names.index(name) for name in OUTPUTS],
                     moment="at rest")


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

