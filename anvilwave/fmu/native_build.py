"""Build the native anvil FMUs: FMI 2.0 or 3.0 co-simulation in C, no Python at run time, no
C compiler at build time.

:func:`build_native_anvil_fmu` writes ``Anvil.fmu`` (the Mode Displacement Method ROM) or
``AnvilLumped.fmu`` (the rigid lumped mass) with the variables of the pythonfmu units of
:mod:`anvilwave.fmu.units.anvil` (same names, value references, types, causalities and
parameters, so the two can be swapped) and the numerics of :mod:`anvilwave.anvil_rom.unit`, in
C (``anvilwave/fmu/native/anvil_model.c``, the unit ``anvil_unit.c``, the FMI layers shared
with the Ram and PileSoil units ``unit_core.c``, ``unit_fmu.c``, ``unit_fmi3.c``). Like those
units (:mod:`anvilwave.fmu.native_units`) the anvil is a generic binary, compiled once per
platform and shipped with anvilwave (``anvilwave/fmu/native/binaries/``: ``Anvil.so`` for
Linux x86-64, ``Anvil.dll`` for Windows x64; one binary serves Anvil and AnvilLumped, the
resource's kind picks the model). The FMU holds

- ``modelDescription.xml`` with ``UnitDefinitions`` (SI base-unit exponents), the ``unit`` of
  every Real, ``ModelStructure`` (the forces are a direct feedthrough of the inputs) and, in
  FMI 2.0, the ``SourceFiles`` of a source FMU;
- ``resources/anvilwave_unit.txt``: what the build makes particular, in the ``anvilwave-unit``
  text format of ``anvilwave/fmu/native/fmu_common.h`` (the model identifier as its kind, the
  GUID, the start value of every Real and Boolean parameter as an exact hexadecimal float);
- ``resources/modal_data.bin`` (ROM only): the modal data in the documented little-endian
  binary format ``anvilwave-modal`` version 1 (version 2 with a pile port in rings;
  ``anvilwave/fmu/native/anvil_model.h``, :func:`modal_resource_bytes`), named by the String
  parameter ``modal_data_file``;
- ``binaries/linux64/<modelIdentifier>.so`` and ``binaries/win64/<modelIdentifier>.dll``
  (FMI 3.0: ``x86_64-linux``, ``x86_64-windows``), copies of the shipped binaries;
- ``sources/``: every ``.c`` / ``.h`` of the binary (the FMI headers, BSD-2-Clause, keep their
  license text) and ``buildDescription.xml``, so that a tool on another platform (macOS)
  compiles the FMU itself (``anvilwave/fmu/native/README.md``).

The modal data come as physics objects or plain arrays, never from system files: a
:class:`~anvilwave.anvil_rom.fem.modalfile.ModalData` (all stored modes are embedded; ``fmax``
[Hz], ``damping_ratio`` [-] and ``static_correction`` stay run-time parameters, as in the
pythonfmu Anvil), a :class:`~anvilwave.anvil_rom.rom.ModalAnvil` (the ROM as it is: its modes,
circular frequencies bit for bit, its damping ratio, and its static correction through the
elastic flexibility it implies, G = R + sum p p^T / omega^2), a mapping of plain arrays with
the ModalData names (``frequencies``, ``participation_ram``, ``participation_pile``,
``participation_gravity``, ``elastic_flexibility``, ``total_mass``, ``fmax``,
``damping_ratio``), or the path of a modal-data ``.npz`` file. The lumped anvil also takes a
mass [kg].

Build-time checks: parameter names and types, and the values through the same physics objects
the Python units build (:class:`~anvilwave.anvil_rom.unit.ContactParameters`,
:meth:`~anvilwave.anvil_rom.rom.ModalAnvil.from_modal_data`,
:meth:`~anvilwave.anvil_rom.rom.ModalAnvil.rigid`):
:class:`~anvilwave.inputs.InputError`, nothing written. Shipped binaries missing or built from
other sources: :class:`NativeBuildError`. With ``validate`` the FMU is checked with
``fmpy.validation.validate_fmu`` and, on Linux x86-64, run once.
"""

from __future__ import annotations

import hashlib
import json
import math
import numbers
import os
import shutil
import struct
import sys
import tempfile
import uuid
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from anvilwave.anvil_rom.fem.modalfile import ModalData, check_modal_data, load_modal_data
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.unit import ContactParameters
from anvilwave.fmu.coupling import (
    INPUT_EXTRAPOLATION_DESCRIPTION,
    RAM_TOE_MASS_DESCRIPTION,
    check_ram_toe_mass,
)
from anvilwave.fmu.native_units import (
    COMMON_SOURCES,
    DEFAULT_EXPERIMENT,
    FMI3_COSIMULATION,
    FMI3_PLATFORMS,
    MODEL_SOURCES,
    NATIVE_DIR,
    PLATFORMS,
    RESOURCE,
    NativeBuildError,
    _zip,
    check_staged_fmu,
    check_unit_fmu_3,
    default_experiment_values,
    description_body,
    resource_text,
    sources_digest,
    unit_binaries,
    unit_sources,
)
from anvilwave.inputs import InputError

MODAL_RESOURCE = "modal_data.bin"
"""Name of the embedded modal data in ``resources/`` (start value of ``modal_data_file``)."""
MODAL_MAGIC = b"anvilwave-modal\x00"
MODAL_VERSION = 1
MODAL_VERSION_RINGS = 2
"""Version 2: version 1 and the rings of a pile port split across the wall."""
MODAL_HEADER_BYTES = 80
GRAVITY = 9.81  # [m/s^2], anvil_rom.unit.GRAVITY


# ---------------------------------------------------------------------------- variables
@dataclass(frozen=True)
class Variable:
    """An FMI variable of the native anvil FMUs.

    Parameters
    ----------
    name : str
        FMI variable name.
    slot : str
        Its slot name in ``anvilwave/fmu/native/anvil_unit.c`` (the name in upper case).
    kind : {"Real", "Boolean", "String"}
        FMI type.
    causality : {"parameter", "input", "output"}
        ``"parameter"`` (variability fixed), ``"input"`` or ``"output"`` (continuous).
    unit : str or None
        A unit of :data:`anvilwave.fmu.native_units.UNITS` or None.
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
    _parameter("ram_toe_mass", "kg", RAM_TOE_MASS_DESCRIPTION),
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
    "modal_data_file": MODAL_RESOURCE, "input_extrapolation": False, "ram_toe_mass": 0.0,
}
"""Start values of parameters the build does not set (contact stiffnesses have none)."""

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
                           validate: bool = True, fmi_version: int = 2,
                           default_experiment: tuple[float, float, float] | None = None,
                           **parameters) -> Path:
    """Build the native ``Anvil.fmu`` (ROM) or, with ``lumped``, ``AnvilLumped.fmu``.

    No C compiler is needed: the FMU carries the shipped binaries (:func:`unit_binaries`).

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
    validate : bool, default True
        Check the FMU with fmpy (``validate_fmu``, then, on Linux x86-64, instantiate,
        initialize and step it once); needs fmpy.
    fmi_version : {2, 3}, default 2
        3: an FMI 3.0 co-simulation FMU (the same binaries, which hold both APIs, under the
        FMI 3.0 platform folders).
    default_experiment : tuple of float or None, optional
        (start time, stop time, step) [s] of the system the FMU is built for, its
        ``DefaultExperiment`` (as :func:`anvilwave.fmu.fmi_build.build_fmu`'s; default
        :data:`DEFAULT_EXPERIMENT`).
    **parameters
        Start values of the FMU parameters, SI units: ``ram_contact_stiffness`` [N/m] and
        ``pile_contact_stiffness`` [N/m] (required), ``ram_contact_damping``,
        ``pile_contact_damping`` [N s/m], ``gravity`` [m/s^2], ``start_at_rest``,
        ``initial_pile_head_displacement`` [m], ``input_extrapolation`` (default off; on for
        Jacobi-type masters, see :mod:`anvilwave.fmu.coupling`), ``ram_toe_mass`` [kg]
        (default 0; the extrapolation's ram toe mass,
        :func:`~anvilwave.fmu.coupling.extrapolated_input`); ROM: ``fmax`` [Hz] (default
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
        If the modal data, a parameter, ``fmi_version`` or ``default_experiment`` is invalid.
    NativeBuildError
        If no current binary is shipped or the built FMU does not pass its check.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4; Functional Mock-up Interface, FMI 3.0. https://fmi-standard.org
    """
    model = "AnvilLumped" if lumped else "Anvil"
    source = f"native {model} FMU build"
    if fmi_version not in (2, 3):
        raise InputError(source, "fmi_version", f"must be 2 or 3, got {fmi_version!r}")
    variables = anvil_variables(lumped)
    data, defaults = _modal_defaults(modal, lumped, source)
    values = _start_values(variables, {**defaults, **parameters}, source, set(parameters))
    _check_physics(data, values, lumped)
    experiment = default_experiment_values(default_experiment, source)
    binaries = unit_binaries(model)
    out_path = Path(out_path)
    target = out_path if out_path.suffix == ".fmu" else out_path / f"{model}.fmu"
    resource = modal_resource_bytes(data) if data is not None else b""
    starts = resource_starts(variables, values)
    guid = _guid(model, fmi_version, variables, values, resource, binaries,
                 None if default_experiment is None else experiment)
    with tempfile.TemporaryDirectory(prefix="anvilwave_native_") as scratch:
        stage = Path(scratch) / "fmu"
        (stage / "resources").mkdir(parents=True)
        if data is not None:
            (stage / "resources" / MODAL_RESOURCE).write_bytes(resource)
        (stage / "resources" / RESOURCE).write_text(resource_text(model, guid, starts, {}),
                                                    encoding="ascii")
        sources = stage / "sources"
        sources.mkdir()
        for name in unit_sources("Anvil"):
            shutil.copyfile(NATIVE_DIR / name, sources / name)
        (sources / "buildDescription.xml").write_bytes(build_description(model))
        for platform, path in binaries.items():
            folder = stage / "binaries" / (platform if fmi_version == 2
                                           else FMI3_PLATFORMS[platform])
            folder.mkdir(parents=True)
            shutil.copyfile(path, folder / f"{model}{PLATFORMS[platform]['suffix']}")
        describe = model_description if fmi_version == 2 else model_description_3
        (stage / "modelDescription.xml").write_bytes(
            describe(model, guid, variables, values, experiment))
        archive = Path(scratch) / f"{model}.fmu"
        _zip(stage, archive)
        if validate:
            if fmi_version == 2:
                _validate(archive, stage, model, guid)
            else:
                check_unit_fmu_3(archive, model, list(OUTPUTS))
        target.parent.mkdir(parents=True, exist_ok=True)
        part = target.with_name(target.name + ".part")
        shutil.copyfile(archive, part)
        part.replace(target)
    return target


def resource_starts(variables, values: dict[str, Any]) -> dict[str, float]:
    """The start values the resource holds: Real parameters, and Booleans as 0.0 or 1.0.

    The String parameter ``modal_data_file`` is not among them: its start value is always
    the embedded :data:`MODAL_RESOURCE` (the binary's table).

    Parameters
    ----------
    variables : sequence of Variable
        The FMU's variables.
    values : dict of str to Any
        Start values of the parameters [SI].

    Returns
    -------
    dict of str to float
        ``{name: start}`` [SI].
    """
    return {v.name: float(values[v.name]) for v in variables
            if v.causality == "parameter" and v.kind in ("Real", "Boolean")}


def find_compiler(compiler: str | None = None) -> str:
    """The C compiler command: ``compiler``, else ``$CC``, else ``cc`` or ``gcc`` on the PATH.

    Building FMUs needs none; this finds one for compiling an FMU's ``sources/`` or a C host.

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
        Naming what is missing.
    """
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
    check_ram_toe_mass(values["ram_toe_mass"], "native Anvil FMU build")
    if lumped:
        ModalAnvil.rigid(values["mass"])
    else:
        ModalAnvil.from_modal_data(data, fmax=values["fmax"] or None,
                                   damping_ratio=values["damping_ratio"],
                                   static_correction=values["static_correction"],
                                   source="native Anvil FMU build")


# ---------------------------------------------------------------------------- files
def _guid(model: str, fmi_version: int, variables, values: dict[str, Any], resource: bytes,
          binaries: dict[str, Path], experiment: tuple[float, float, float] | None = None
          ) -> str:
    """A GUID from the content (same inputs, same GUID: reproducible builds)."""
    digest = hashlib.sha256()
    digest.update(f"{model} FMI {fmi_version}".encode())
    if experiment is not None:
        digest.update(" ".join(x.hex() for x in experiment).encode())
    digest.update(json.dumps([[v.name, v.kind, v.causality, v.unit] for v in variables]).encode())
    digest.update(json.dumps({k: (v.hex() if isinstance(v, float) else v)
                              for k, v in values.items()}, sort_keys=True).encode())
    digest.update(resource)
    digest.update(sources_digest("Anvil").encode())
    for platform in sorted(binaries):
        digest.update(binaries[platform].read_bytes())
    return str(uuid.UUID(bytes=digest.digest()[:16], version=4))


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
    for name in (*COMMON_SOURCES, *MODEL_SOURCES["Anvil"]):
        ET.SubElement(files, "File", name=name)
    mv = description_body(root, {v.unit for v in variables if v.unit is not None}, experiment)
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


def model_description_3(model: str, token: str, variables, values: dict[str, Any],
                        experiment: tuple[float, float, float] = DEFAULT_EXPERIMENT) -> bytes:
    """``modelDescription.xml`` of the anvil as FMI 3.0 co-simulation.

    The variables and value references of the FMI 2.0 FMU (Reals as Float64) and the
    independent variable ``time``, whose value reference follows theirs.

    Parameters
    ----------
    model : str
        Model identifier, ``"Anvil"`` or ``"AnvilLumped"``.
    token : str
        Instantiation token of the FMU (the GUID of the resource).
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
    Modelica Association. Functional Mock-up Interface, FMI 3.0. https://fmi-standard.org
    """
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "3.0", "modelName": model, "instantiationToken": token,
        "description": DESCRIPTIONS[model], "generationTool": "anvilwave fmu.native_build",
        "variableNamingConvention": "structured"})
    ET.SubElement(root, "CoSimulation", {"modelIdentifier": model, **FMI3_COSIMULATION})
    mv = description_body(root, {v.unit for v in variables if v.unit is not None} | {"s"},
                          experiment)  # "s": time
    ET.SubElement(mv, "Float64", name="time", valueReference=str(len(variables)),
                  causality="independent", variability="continuous",
                  description="Simulation time [s]", unit="s")
    for vr, v in enumerate(variables):
        attrs = {"name": v.name, "valueReference": str(vr), "description": v.description,
                 "causality": v.causality,
                 "variability": "fixed" if v.causality == "parameter" else "continuous"}
        if v.kind == "String":
            ET.SubElement(ET.SubElement(mv, "String", attrs), "Start", value=values[v.name])
            continue
        if v.kind == "Boolean":
            attrs["start"] = "true" if values[v.name] else "false"
            ET.SubElement(mv, "Boolean", attrs)
            continue
        if v.unit is not None:
            attrs["unit"] = v.unit
        if v.causality == "parameter":
            attrs["start"] = repr(float(values[v.name]))
        elif v.causality == "input":
            attrs["start"] = "0.0"
        ET.SubElement(mv, "Float64", attrs)
    structure = ET.SubElement(root, "ModelStructure")
    vrs = {v.name: vr for vr, v in enumerate(variables)}
    for name in OUTPUTS:
        ET.SubElement(structure, "Output", valueReference=str(vrs[name]),
                      dependencies=" ".join(str(vrs[i]) for i in FEEDTHROUGH[model][name]))
    for name in OUTPUTS:
        ET.SubElement(structure, "InitialUnknown", valueReference=str(vrs[name]))
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
    for name in (*COMMON_SOURCES, *MODEL_SOURCES["Anvil"]):
        ET.SubElement(files, "SourceFile", name=name)
    ET.SubElement(config, "Library", name="m", external="true",
                  description="the C math library (exp, cos, sqrt)")
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def _validate(archive: Path, stage: Path, model: str, guid: str) -> None:
    """fmpy's validation, then instantiate, initialize and step the staged anvil FMU once
    (:func:`check_staged_fmu` with the anvil's output references)."""
    names = [v.name for v in anvil_variables(model == "AnvilLumped")]
    check_staged_fmu(archive, stage, model, guid, [names.index(name) for name in OUTPUTS],
                     run=sys.platform.startswith("linux") and sys.maxsize > 2**32,
                     moment="at rest")


