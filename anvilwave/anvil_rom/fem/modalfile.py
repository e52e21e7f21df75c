"""The modal-data file: the Mode Displacement Method anvil as data (``.npz``).

Format ``anvilwave-modal``, version 1. Every array is stored without pickling; the file is read
with ``allow_pickle=False`` and each key is checked on load. Keys (units in brackets):

=========================  ========  ==============================================================
key                        shape     meaning
=========================  ========  ==============================================================
format                     ()        the string ``"anvilwave-modal"``
version                    ()        integer format version (1)
frequencies                (n,)      natural frequencies [Hz], ascending; index 0 is the axial
                                     rigid-body mode (0 Hz)
participation_ram          (n,)      b_ram^T phi_j, mass-normalised modes [kg^-1/2]
participation_pile         (n,)      b_pile^T phi_j [kg^-1/2]
participation_gravity      (n,)      phi_j^T M e_z [kg^1/2] (only the rigid mode is non-zero)
elastic_flexibility        (2, 2)    inertia-relief flexibility between the ram face and the pile
                                     ring, all flexible modes [m/N] (for the static correction)
total_mass                 ()        [kg]
fmax                       ()        frequency content the modes were computed for [Hz]
damping_ratio              ()        default modal damping ratio [-]
material                   (3,)      Young's modulus [Pa], Poisson's ratio [-], density [kg/m^3]
interfaces                 (3,)      ram contact radius, pile contact radius, pile contact width [m]
interface_areas            (2,)      ram face area, pile ring area [m^2]
n_dof                      ()        DOFs of the FE model the modes came from
geometry_hash              ()        SHA-256 of the geometry / mesh and material
source                     ()        who computed the modes ("anvilwave", "calculix", ...)
=========================  ========  ==============================================================

Optional keys, present together when the pile port is split into K > 1 rings across the wall
(``pile_port_rings``, :mod:`anvilwave.anvil_rom.rings`):

=========================  ========  ==============================================================
participation_rings        (K, n)    b_ring,k^T phi_j, uniform pressure on each ring [kg^-1/2]
ring_flexibility           (K+1,     inertia-relief flexibility between the ram face and the
                           K+1)      rings, all flexible modes [m/N]
ring_areas                 (K,)      ring areas, inner ring first [m^2]
=========================  ========  ==============================================================

Optional keys, present together (and with the ring keys) when the ram port is split into J > 1
annuli (``ram_port_annuli``); ``ring_flexibility`` is then (J+K, J+K), the annuli first:

=========================  ========  ==============================================================
participation_ram_annuli   (J, n)    b_annulus,j^T phi_j, uniform pressure on each ram annulus
                                     [kg^-1/2]
ram_annulus_areas          (J,)      ram annulus areas, the innermost (a disc) first [m^2]
=========================  ========  ==============================================================

Optional keys, present together, for ports that carry friction (the radial participation of
the modes, :func:`anvilwave.anvil_rom.fem.elasticity.radial_interface_vectors`):

=========================  ========  ==============================================================
participation_ram_radial   (n,)      c_ram^T phi_j, uniform radial traction on the ram face
                                     [kg^-1/2] (0 for the axial rigid-body mode)
participation_pile_radial  (n,)      c_pile^T phi_j on the pile ring [kg^-1/2]
radial_flexibility         (4, 4)    inertia-relief flexibility between the ram face and the pile
                                     ring, axial then radial: [b_ram, b_pile, c_ram, c_pile],
                                     all flexible modes [m/N]; its axial block is
                                     elastic_flexibility
=========================  ========  ==============================================================
"""

from __future__ import annotations

import zipfile
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from anvilwave.inputs import InputError

FORMAT = "anvilwave-modal"
VERSION = 1


@dataclass(frozen=True)
class ModalData:
    """Modal description of an anvil between its two interfaces (see the module docstring).

    Checked on construction (:func:`check_modal_data`).

    Parameters
    ----------
    frequencies : numpy.ndarray
        Natural frequencies, shape (n,) [Hz], ascending; index 0 is the axial rigid-body mode
        (0 Hz).
    participation_ram : numpy.ndarray
        b_ram^T phi_j, mass-normalised modes, shape (n,) [kg^-1/2].
    participation_pile : numpy.ndarray
        b_pile^T phi_j, shape (n,) [kg^-1/2].
    participation_gravity : numpy.ndarray
        phi_j^T M e_z, shape (n,) [kg^1/2] (only the rigid mode is non-zero).
    elastic_flexibility : numpy.ndarray
        Inertia-relief flexibility between the ram face and the pile ring, all flexible modes,
        shape (2, 2) [m/N] (for the static correction).
    total_mass : float
        Total mass [kg].
    fmax : float
        Frequency content the modes were computed for [Hz].
    damping_ratio : float
        Default modal damping ratio [-].
    material : numpy.ndarray
        Young's modulus [Pa], Poisson's ratio [-], density [kg/m^3], shape (3,).
    interfaces : numpy.ndarray
        Ram contact radius, pile contact radius, pile contact width, shape (3,) [m].
    interface_areas : numpy.ndarray
        Ram face area, pile ring area, shape (2,) [m^2].
    n_dof : int
        DOFs of the FE model the modes came from.
    geometry_hash : str
        SHA-256 of the geometry / mesh and material.
    source : str
        Who computed the modes ("anvilwave", "calculix", ...).
    participation_rings : numpy.ndarray, optional
        b_ring,k^T phi_j, uniform pressure on each of K pile rings, shape (K, n) [kg^-1/2].
    ring_flexibility : numpy.ndarray, optional
        Inertia-relief flexibility between the ram face (or annuli) and the rings, all flexible
        modes, shape (K+1, K+1) or (J+K, J+K) [m/N].
    ring_areas : numpy.ndarray, optional
        Ring areas, inner ring first, shape (K,) [m^2].
    participation_ram_annuli : numpy.ndarray, optional
        b_annulus,j^T phi_j, uniform pressure on each of J ram annuli, shape (J, n) [kg^-1/2].
    ram_annulus_areas : numpy.ndarray, optional
        Ram annulus areas, the innermost (a disc) first, shape (J,) [m^2].
    participation_ram_radial : numpy.ndarray, optional
        c_ram^T phi_j, uniform radial traction on the ram face, shape (n,) [kg^-1/2].
    participation_pile_radial : numpy.ndarray, optional
        c_pile^T phi_j on the pile ring, shape (n,) [kg^-1/2].
    radial_flexibility : numpy.ndarray, optional
        Inertia-relief flexibility between [b_ram, b_pile, c_ram, c_pile], all flexible modes,
        shape (4, 4) [m/N].

    Attributes
    ----------
    n_modes : int
        Number of modes n.

    Raises
    ------
    InputError
        If the data break a rule of :func:`check_modal_data`.
    """

    frequencies: np.ndarray
    participation_ram: np.ndarray
    participation_pile: np.ndarray
    participation_gravity: np.ndarray
    elastic_flexibility: np.ndarray
    total_mass: float
    fmax: float
    damping_ratio: float
    material: np.ndarray
    interfaces: np.ndarray
    interface_areas: np.ndarray
    n_dof: int
    geometry_hash: str
    source: str
    participation_rings: np.ndarray | None = None
    ring_flexibility: np.ndarray | None = None
    ring_areas: np.ndarray | None = None
    participation_ram_annuli: np.ndarray | None = None
    ram_annulus_areas: np.ndarray | None = None
    participation_ram_radial: np.ndarray | None = None
    participation_pile_radial: np.ndarray | None = None
    radial_flexibility: np.ndarray | None = None

    @property
    def n_modes(self) -> int:
        """Number of modes n (rigid-body mode included)."""
        return len(self.frequencies)

    def __post_init__(self):
        check_modal_data(self, "<modal data>")


_SHAPES = {
    "frequencies": "n", "participation_ram": "n", "participation_pile": "n",
    "participation_gravity": "n", "elastic_flexibility": (2, 2), "total_mass": (),
    "fmax": (), "damping_ratio": (), "material": (3,), "interfaces": (3,),
    "interface_areas": (2,), "n_dof": (), "geometry_hash": (), "source": (),
    "participation_rings": "Kn", "ring_flexibility": "KK", "ring_areas": "K",
    "participation_ram_annuli": "Jn", "ram_annulus_areas": "J",
    "participation_ram_radial": "n", "participation_pile_radial": "n",
    "radial_flexibility": (4, 4),
}
RING_KEYS = ("participation_rings", "ring_flexibility", "ring_areas")
"""The optional keys of a pile port split into rings (all or none)."""
ANNULUS_KEYS = ("participation_ram_annuli", "ram_annulus_areas")
"""The optional keys of a ram port split into annuli (both or none, with the ring keys)."""
RADIAL_KEYS = ("participation_ram_radial", "participation_pile_radial", "radial_flexibility")
"""The optional keys of the ports' radial participation (all or none)."""


def check_modal_data(data: ModalData, source: str) -> None:
    """Physical sanity of modal data; raises :class:`InputError` naming the key.

    Parameters
    ----------
    data : ModalData
        The modal data.
    source : str
        The file named in errors.

    Raises
    ------
    InputError
        At the first broken rule.
    """
    f = np.asarray(data.frequencies)
    n = len(f)

    def bad(key, rule):
        return InputError(source, key, rule)

    if f.ndim != 1 or n < 1 or not np.all(np.isfinite(f)):
        raise bad("frequencies", "must be a non-empty 1D array of finite values")
    if f[0] != 0.0 or np.any(f[1:] <= 0.0) or np.any(np.diff(f) < 0.0):
        raise bad("frequencies", "must start with the rigid-body mode (0 Hz) followed by "
                                 "positive ascending frequencies")
    for key in ("participation_ram", "participation_pile", "participation_gravity"):
        arr = np.asarray(getattr(data, key))
        if arr.shape != (n,) or not np.all(np.isfinite(arr)):
            raise bad(key, f"must hold one finite value per mode ({n})")
    G = np.asarray(data.elastic_flexibility)
    if (G.shape != (2, 2) or not np.all(np.isfinite(G))
            or abs(G[0, 1] - G[1, 0]) > 1e-9 * abs(G).max()):
        raise bad("elastic_flexibility", "must be a finite symmetric 2x2 matrix [m/N]")
    if not (np.isfinite(data.total_mass) and data.total_mass > 0):
        raise bad("total_mass", "must be positive [kg]")
    if not (np.isfinite(data.fmax) and data.fmax >= f[-1] * (1 - 1e-9)):
        raise bad("fmax", "must be at least the highest stored frequency [Hz]")
    if not (0.0 <= data.damping_ratio < 1.0):
        raise bad("damping_ratio", "must be in [0, 1)")
    expected = np.sqrt(data.total_mass)
    if abs(abs(data.participation_gravity[0]) - expected) > 1e-6 * expected:
        raise bad("participation_gravity", "rigid-body entry must equal sqrt(total_mass) for "
                                           "mass-normalised modes")
    present = [getattr(data, key, None) is not None for key in RING_KEYS]
    if any(present) and not all(present):
        raise bad(RING_KEYS[present.index(False)], "must be given with the other ring keys "
                                                   f"({', '.join(RING_KEYS)})")
    annuli = [getattr(data, key, None) is not None for key in ANNULUS_KEYS]
    if any(annuli) and not (all(annuli) and all(present)):
        missing = [k for k, p in zip(ANNULUS_KEYS + RING_KEYS, annuli + present, strict=True)
                   if not p][0]
        raise bad(missing, "must be given with the other ram annulus and ring keys "
                           f"({', '.join(ANNULUS_KEYS + RING_KEYS)})")
    if all(present):
        _check_rings(data, n, bad)
    radial = [getattr(data, key, None) is not None for key in RADIAL_KEYS]
    if any(radial) and not all(radial):
        raise bad(RADIAL_KEYS[radial.index(False)], "must be given with the other radial keys "
                                                    f"({', '.join(RADIAL_KEYS)})")
    if all(radial):
        _check_radial(data, n, bad)


def _check_radial(data: ModalData, n: int, bad) -> None:
    """The radial keys: one finite value per mode, none in the axial rigid-body mode, and a
    finite symmetric flexibility whose axial block is ``elastic_flexibility``."""
    for key in RADIAL_KEYS[:2]:
        arr = np.asarray(getattr(data, key))
        if arr.shape != (n,) or not np.all(np.isfinite(arr)):
            raise bad(key, f"must hold one finite value per mode ({n})")
        if abs(arr[0]) > 1e-9 * max(np.abs(arr).max(), 1e-300):
            raise bad(key, "must be 0 in the axial rigid-body mode (it has no radial motion)")
    G = np.asarray(data.radial_flexibility)
    if (G.shape != (4, 4) or not np.all(np.isfinite(G))
            or np.abs(G - G.T).max() > 1e-9 * np.abs(G).max()):
        raise bad("radial_flexibility", "must be a finite symmetric 4x4 matrix [m/N]")
    axial = np.asarray(data.elastic_flexibility)
    if np.abs(G[:2, :2] - axial).max() > 1e-9 * np.abs(axial).max():
        raise bad("radial_flexibility", "its axial block [:2, :2] must equal "
                                        "elastic_flexibility")


def _check_rings(data: ModalData, n: int, bad) -> None:
    """The ring keys: shapes, finite and symmetric, and the rings make up the pile ring (areas
    sum to its area and the area-weighted ring participations to the ring's)."""
    areas = np.asarray(data.ring_areas)
    K = areas.size
    P = np.asarray(data.participation_rings)
    G = np.asarray(data.ring_flexibility)
    if areas.ndim != 1 or K < 2 or not np.all(np.isfinite(areas)) or np.any(areas <= 0.0):
        raise bad("ring_areas", "must hold two or more positive ring areas [m^2]")
    ring_area = getattr(data, "interface_areas", None)  # a native resource has none
    if ring_area is not None and abs(areas.sum() - ring_area[1]) > 1e-9 * ring_area[1]:
        raise bad("ring_areas", "must sum to the pile ring's area (interface_areas[1])")
    if P.shape != (K, n) or not np.all(np.isfinite(P)):
        raise bad("participation_rings", f"must have shape ({K}, {n}) (rings, modes), finite")
    combined = (areas / areas.sum()) @ P
    scale = np.abs(data.participation_pile).max()
    if np.abs(combined - data.participation_pile).max() > 1e-9 * scale:
        raise bad("participation_rings", "area-weighted, must add up to participation_pile")
    J = 1
    if getattr(data, "ram_annulus_areas", None) is not None:
        J = _check_annuli(data, n, bad)
    if (G.shape != (J + K, J + K) or not np.all(np.isfinite(G))
            or np.abs(G - G.T).max() > 1e-9 * np.abs(G).max()):
        raise bad("ring_flexibility", f"must be a finite symmetric {J + K}x{J + K} matrix [m/N]")


def _check_annuli(data: ModalData, n: int, bad) -> int:
    """The ram annulus keys, as the ring keys (their areas sum to the ram face's and their
    area-weighted participations to the face's); returns their number J."""
    areas = np.asarray(data.ram_annulus_areas)
    J = areas.size
    P = np.asarray(data.participation_ram_annuli)
    if areas.ndim != 1 or J < 2 or not np.all(np.isfinite(areas)) or np.any(areas <= 0.0):
        raise bad("ram_annulus_areas", "must hold two or more positive annulus areas [m^2]")
    face = getattr(data, "interface_areas", None)
    if face is not None and abs(areas.sum() - face[0]) > 1e-9 * face[0]:
        raise bad("ram_annulus_areas", "must sum to the ram face's area (interface_areas[0])")
    if P.shape != (J, n) or not np.all(np.isfinite(P)):
        raise bad("participation_ram_annuli", f"must have shape ({J}, {n}) (annuli, modes), "
                                              "finite")
    combined = (areas / areas.sum()) @ P
    if np.abs(combined - data.participation_ram).max() > 1e-9 * np.abs(
            data.participation_ram).max():
        raise bad("participation_ram_annuli", "area-weighted, must add up to participation_ram")
    return J


def write_modal_data(data: ModalData, fh) -> None:
    """Write modal data as the .npz modal-data file into the binary file object ``fh``.

    Parameters
    ----------
    data : ModalData
        The modal data.
    fh : file-like
        Binary file object open for writing.
    """
    arrays = {"format": np.array(FORMAT), "version": np.array(VERSION)}
    for fld in fields(ModalData):
        value = getattr(data, fld.name)
        if value is not None:  # the optional ring keys
            arrays[fld.name] = np.asarray(value)
    np.savez(fh, **arrays)


def save_modal_data(data: ModalData, path: str | Path) -> Path:
    """Write modal data to ``path`` (.npz), atomically (no half-written file on failure).

    Parameters
    ----------
    data : ModalData
        The modal data.
    path : str or Path
        The target file (its directory is created).

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "wb") as fh:
        write_modal_data(data, fh)
    tmp.replace(path)
    return path


def load_modal_data(path: str | Path) -> ModalData:
    """Read and validate a modal-data file; a corrupt or foreign file raises :class:`InputError`.

    Parameters
    ----------
    path : str or Path
        The .npz modal-data file.

    Returns
    -------
    ModalData
        The validated modal data.

    Raises
    ------
    InputError
        If the file is missing, unreadable, of another format or version, or a key is missing,
        misshapen or breaks a rule.
    """
    path = Path(path)
    src = str(path)
    if not path.exists():
        raise InputError(src, "", "modal-data file not found")
    try:
        with np.load(path, allow_pickle=False) as npz:
            content = {k: npz[k] for k in npz.files}
    except (OSError, ValueError, zipfile.BadZipFile, EOFError) as exc:
        raise InputError(src, "", f"not a readable .npz modal-data file ({exc})") from None
    if content.get("format", np.array("")).item() != FORMAT:
        raise InputError(src, "format", f"must be {FORMAT!r}: not an anvilwave modal-data file")
    version = int(content.get("version", np.array(-1)))
    if version != VERSION:
        raise InputError(src, "version", f"format version {version} is not supported (this "
                                         f"anvilwave reads version {VERSION})")
    kwargs = {}
    for fld in fields(ModalData):
        if fld.name not in content:
            if fld.name in RING_KEYS + ANNULUS_KEYS + RADIAL_KEYS:
                continue
            raise InputError(src, fld.name, "is missing")
        value = content[fld.name]
        shape = _SHAPES[fld.name]
        if not isinstance(shape, str) and value.shape != shape:
            raise InputError(src, fld.name, f"must have shape {shape}, got {value.shape}")
        if fld.name in ("geometry_hash", "source"):
            kwargs[fld.name] = str(value)
        elif fld.name == "n_dof":
            kwargs[fld.name] = int(value)
        elif shape == ():
            kwargs[fld.name] = float(value)
        else:
            kwargs[fld.name] = np.asarray(value, dtype=float)
    try:
        return ModalData(**kwargs)
    except InputError as exc:
        raise InputError(src, exc.key, exc.rule) from None
