"""The modal-data cache: the ROM of an anvil (or of a modal ram) computed once per machine.

The eigenvalue problem of an anvil takes seconds to minutes and its result depends only on the
anvil's geometry (outline or mesh file), material, mesh size, interfaces, fmax and damping
ratio, and on the code that computes it. :func:`cached_modal_data` keys the modal data by all
of these and keeps it as a modal-data file (:mod:`anvilwave.anvil_rom.fem.modalfile`) in a user
cache
directory, so that every later process, on this machine or on a cluster node sharing the
directory (dask workers), reads it in milliseconds instead of solving again. The modal ram's
spring-mass chain, realised from its modes in multiple precision, is kept the same way
(:func:`cached_chain`, an ``.npz`` of two arrays).

Where: ``$ANVILWAVE_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/anvilwave``, else
``~/.cache/anvilwave`` (the XDG / platformdirs convention). ``anvilwave cache info`` shows
the directory and its entries, ``anvilwave cache clear`` empties it; deleting the directory by
hand is as good.

The key (SHA-256) covers the anvil description, fmax, the damping ratio, the anvilwave
version, the modal-data format version, a hash of the source files of the modal analysis
(:data:`CODE_FILES`) and the versions of gmsh and scikit-fem, so a code or mesher change
computes afresh instead of reusing stale modes. Writes are atomic (a temporary file in the
same directory, then ``os.replace``): a reader never sees a half-written file. A file that
cannot be read (truncated, foreign) counts as a miss and is replaced.

An entry is computed once when several processes or threads ask for it at the same time (the
workers of a campaign or of a test session on a cold cache): the first takes an exclusive
lock on the entry's lock file (``<entry>.lock``, :func:`entry_lock`), the others wait on it
and then read what it wrote. The operating system releases the lock when its process ends,
however it ends, so a killed worker never blocks the others. Where no lock can be taken
(Windows, a file system without ``flock``, a read-only directory) each computes its own, as
if there were no lock, and the last complete file wins.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import tempfile
import threading
import warnings
import zipfile
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path

try:
    import fcntl
except ImportError:  # Windows: no entry locks (module docstring)
    fcntl = None

import numpy as np

import anvilwave.anvil_rom as anvil_rom
import anvilwave.anvil_rom.fem.pipeline as pipeline
from anvilwave.anvil_rom.chain import chain_from_modes
from anvilwave.anvil_rom.fem.elasticity import assemble, interface_vectors
from anvilwave.anvil_rom.fem.mesh import build_mesh, to_skfem
from anvilwave.anvil_rom.fem.modalfile import VERSION, load_modal_data, write_modal_data
from anvilwave.anvil_rom.fem.modes import inverse_iteration_mode
from anvilwave.anvil_rom.fem.pipeline import solid_mass
from anvilwave.inputs import InputError
from anvilwave.pile import head_kernel
from anvilwave.pile.head_kernel import ring_kernel

ENVIRONMENT_VARIABLE = "ANVILWAVE_CACHE_DIR"
"""Environment variable that overrides the cache directory."""
CACHE_VERSION = 1
"""Layout version of the cache entries (part of every key)."""
CODE_FILES = ("fem/geometry.py", "fem/mesh.py", "fem/elasticity.py", "fem/modes.py",
              "fem/pipeline.py", "fem/modalfile.py", "chain.py")
"""Source files of :mod:`anvilwave.anvil_rom` that define the modal data and the modal ram's chain
(hashed into every key)."""
SUFFIX = ".npz"


def cache_dir() -> Path:
    """The cache directory (module docstring); not created here.

    Returns
    -------
    pathlib.Path
        The directory.
    """
    override = os.environ.get(ENVIRONMENT_VARIABLE)
    if override:
        return Path(override).expanduser()
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg).expanduser() if xdg else Path.home() / ".cache"
    return base / "anvilwave"


@lru_cache(maxsize=1)
def code_version() -> str:
    """What the modal data depends on besides its inputs.

    Package, format and mesher versions and a hash of the modal analysis's source files.

    Returns
    -------
    str
        The version string.
    """
    from importlib import metadata


    def version(name: str) -> str:
        try:
            return metadata.version(name)
        except metadata.PackageNotFoundError:
            return "unknown"

    h = hashlib.sha256()
    root = Path(anvil_rom.__file__).parent
    for name in CODE_FILES:
        h.update(name.encode())
        h.update((root / name).read_bytes())
    return (f"anvilwave {version('anvilwave')}; modal format {VERSION}; "
            f"cache {CACHE_VERSION}; gmsh {version('gmsh')}; scikit-fem {version('scikit-fem')}; "
            f"source {h.hexdigest()[:16]}")


def modal_key(spec, fmax: float) -> str:
    """Cache key (hex SHA-256) of the modal data of ``spec`` up to ``fmax``.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil spec.
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    str
        The key, 64 hex digits.
    """
    itf = spec.interfaces
    description = {
        "geometry": spec.geometry_hash(),  # outline or mesh file, material, mesh size
        "interfaces": None if itf is None else [itf.ram_contact_radius, itf.pile_contact_radius,
                                                itf.pile_contact_width]
        + ([itf.pile_rings] if itf.pile_rings > 1 else [])  # one port: the keys of before
        + ([itf.ram_annuli] if itf.ram_annuli > 1 else []),
        "fmax": float(fmax),
        "damping_ratio": float(spec.damping_ratio),
        "code": code_version(),
    }
    text = json.dumps(description, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def cached_modal_data(spec, fmax: float | None = None):
    """The modal data of an anvil spec up to ``fmax``, from the cache or computed and stored.

    Computed by :func:`anvilwave.anvil_rom.fem.pipeline.compute_anvil_modes`. The spec needs its
    interfaces (the ROM is projected on them).

    Parameters
    ----------
    spec : AnvilSpec
        The anvil spec.
    fmax : float or None, default None
        Frequency content [Hz] (default: the spec's).

    Returns
    -------
    ModalData
        The modal data.
    """

    fmax = float(spec.fmax if fmax is None else fmax)
    path = cache_dir() / (modal_key(spec, fmax) + SUFFIX)

    def read(warn: bool):
        if not path.is_file():
            return None
        try:
            data = load_modal_data(path)
        except InputError:
            return None  # unreadable: computed again and replaced
        stamp = (str(path), path.stat().st_mtime_ns, path.stat().st_size)
        with _CHECK_LOCK:  # gmsh (meshing for the Sturm count) is not thread-safe
            reason = None if stamp in _VERIFIED else modal_data_mismatch(data, spec, fmax)
            if reason is None:
                _VERIFIED.add(stamp)
        if reason is None:
            return data
        if warn:
            warnings.warn(f"{path}: the cached modal data does not match its anvil "
                          f"({reason}): computed again", stacklevel=4)
        return None

    def compute():
        return pipeline.compute_anvil_modes(spec, fmax=fmax).modal_data  # patchable in tests

    def store(data) -> None:
        if data is not None:
            _store(data, path)

    return cached_entry(path, read, compute, store)


_CHECK_LOCK = threading.Lock()
_VERIFIED: set = set()
"""Cache files (path, mtime, size) this process has checked: checked once per process."""

MASS_TOLERANCE = 1e-6
"""Relative difference of a cached total mass from the anvil's solid mass that is a mismatch."""


def modal_data_mismatch(data, spec, fmax: float) -> str | None:
    """Why cached modal data does not belong to ``spec`` at ``fmax``, else None.

    Checked: fmax, the damping ratio and the geometry hash against the key's; the frequencies
    finite, increasing, within fmax; the total mass against the spec's solid mass
    (:func:`~anvilwave.anvil_rom.fem.pipeline.solid_mass`); and the frequencies against the FE
    eigenproblem, on one sampled flexible mode k (the middle one isolated from its
    neighbours), with one factorisation of K - sigma M at sigma just above its eigenvalue
    (:func:`~anvilwave.anvil_rom.fem.modes.inverse_iteration_mode`, no eigensolve): the Sturm
    count below sigma must be k + 1 (no cached mode missing or extra), the Rayleigh quotient of
    the mode must equal the cached eigenvalue, and the mass-normalised mode's ram, pile and
    gravity participations must equal the cached ones (the orthonormality of the cached modes
    on a sample: a scaled or mixed mode, or one not orthogonal to the rigid-body mode, differs).

    Parameters
    ----------
    data : ModalData
        The cached modal data.
    spec : AnvilSpec
        The anvil spec.
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    str or None
        The reason, or None when the data belongs to the spec.
    """
    f = np.asarray(data.frequencies, dtype=float)
    if not math.isclose(float(data.fmax), float(fmax), rel_tol=1e-12):
        return f"fmax {float(data.fmax):g} Hz, not {float(fmax):g} Hz"
    if not math.isclose(float(data.damping_ratio), float(spec.damping_ratio), rel_tol=1e-12,
                        abs_tol=1e-15):
        return f"damping ratio {float(data.damping_ratio):g}, not {spec.damping_ratio:g}"
    if str(data.geometry_hash) != str(spec.geometry_hash()):
        return "another geometry"
    if f.size < 1 or not np.all(np.isfinite(f)) or np.any(np.diff(f) < 0.0) or (
            f[-1] > fmax * (1 + 1e-9)):
        return "frequencies not finite, increasing and within fmax"
    mass = solid_mass(spec)
    if not math.isclose(float(data.total_mass), mass, rel_tol=MASS_TOLERANCE):
        return f"total mass {float(data.total_mass):.6g} kg, not {mass:.6g} kg"
    k = _sampled_mode_index(f)
    if k is None:
        return None
    lam = (2.0 * math.pi * f[k]) ** 2
    shift = lam * (1.0 + SAMPLE_SHIFT)
    model = assemble(to_skfem(build_mesh(spec)), spec.material)
    mode = inverse_iteration_mode(model.stiffness, model.mass, shift)
    if mode.count_below != k + 1:
        return (f"{k + 1} cached modes up to {f[k]:.6g} Hz, the FE model has "
                f"{mode.count_below}")
    if abs(mode.eigenvalue - lam) > EIGENVALUE_TOLERANCE * lam:
        return (f"mode {k} at {f[k]:.9g} Hz, the FE model's nearest at "
                f"{math.sqrt(max(mode.eigenvalue, 0.0)) / (2.0 * math.pi):.9g} Hz")
    if spec.interfaces is None:
        return None
    b_ram, b_pile, _, _ = interface_vectors(model, spec.interfaces)
    computed = np.array([b_ram @ mode.shape, b_pile @ mode.shape,
                         mode.shape @ (model.mass @ model.axial_free)])
    cached = np.array([data.participation_ram[k], data.participation_pile[k],
                       data.participation_gravity[k]])
    scale = max(float(np.linalg.norm(cached[:2])), 1e-300)
    sign = 1.0 if computed[:2] @ cached[:2] >= 0.0 else -1.0
    error = float(np.max(np.abs(sign * computed - cached))) / scale
    if not error <= PARTICIPATION_TOLERANCE:
        return (f"mode {k}: participations {cached[0]:.6g}, {cached[1]:.6g}, "
                f"{cached[2]:.3g} (ram, pile, gravity) are not those of the FE model's "
                f"mass-normalised mode ({sign * computed[0]:.6g}, {sign * computed[1]:.6g}, "
                f"{sign * computed[2]:.3g})")
    return None


SAMPLE_SHIFT = 1e-6
"""Relative offset of the sampling shift above the sampled eigenvalue (2 pi f_k)^2."""

SAMPLE_GAP = 1e-3
"""Least relative distance of the sampled eigenvalue from its neighbours: with
:data:`SAMPLE_SHIFT` the inverse iteration converges by 1e-3 per step or faster."""

EIGENVALUE_TOLERANCE = 1e-8
"""Relative difference of the sampled mode's Rayleigh quotient from the cached eigenvalue that
is a mismatch (both from the same FE model: they agree to the eigensolver's round-off, about
1e-12)."""

PARTICIPATION_TOLERANCE = 1e-6
"""Difference of the sampled mode's participations from the cached ones, relative to its port
participations, that is a mismatch (four inverse-iteration steps leave about 1e-12)."""


def _sampled_mode_index(f: np.ndarray) -> int | None:
    """The flexible mode to sample: the middle one of those isolated from their neighbours
    (relative eigenvalue gap :data:`SAMPLE_GAP`), or None when none is."""
    lam = f ** 2
    isolated = [k for k in range(1, f.size)
                if lam[k] > 0.0
                and (lam[k] - lam[k - 1]) > SAMPLE_GAP * lam[k]
                and (k + 1 == f.size or lam[k + 1] - lam[k] > SAMPLE_GAP * lam[k])]
    return isolated[len(isolated) // 2] if isolated else None


CHAIN_SUFFIX = ".chain.npz"


def cached_chain(omega, participation) -> tuple[np.ndarray, np.ndarray]:
    """:func:`anvilwave.anvil_rom.chain.chain_from_modes`, from the cache or realised and stored.

    Parameters
    ----------
    omega : numpy.ndarray
        Angular frequencies of the modes [rad/s].
    participation : numpy.ndarray
        Participation of the modes [kg^-1/2].

    Returns
    -------
    masses : numpy.ndarray
        Chain masses [kg].
    springs : numpy.ndarray
        Chain springs [N/m].
    """
    omega = np.ascontiguousarray(omega, dtype=float)
    participation = np.ascontiguousarray(participation, dtype=float)
    h = hashlib.sha256(b"chain")
    h.update(omega.tobytes())
    h.update(participation.tobytes())
    h.update(code_version().encode())
    path = cache_dir() / (h.hexdigest() + CHAIN_SUFFIX)

    def read(warn: bool):
        if path.is_file():
            try:
                with np.load(path, allow_pickle=False) as npz:
                    mass, stiffness = npz["mass"], npz["stiffness"]
                if mass.ndim == 1 and stiffness.shape == (mass.size - 1,):
                    return mass, stiffness
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                pass  # unreadable: realised again and replaced
        return None

    def store(chain) -> None:
        write_atomic(path, lambda fh: np.savez(fh, mass=chain[0], stiffness=chain[1]))

    return cached_entry(path, read, lambda: chain_from_modes(omega, participation), store)


KERNEL_SUFFIX = ".head.npz"
FEA_SUFFIX = ".fea.npz"
"""File name ending of a reference FEA's result (:mod:`anvilwave.fea.cache`)."""


def cached_ring_kernel(material, r_in: float, r_out: float, length: float, step: float,
                       steps: int, rings: int) -> np.ndarray:
    """:func:`anvilwave.pile.head_kernel.ring_kernel` of a tube, from the cache or computed.

    Stored when computed (it takes tens of seconds for a long tube).

    Parameters
    ----------
    material : Material
        The tube's material.
    r_in : float
        Inner radius [m].
    r_out : float
        Outer radius [m].
    length : float
        Tube length [m].
    step : float
        Time step of the kernel [s].
    steps : int
        Number of kernel steps [-].
    rings : int
        Number of equal-width rings across the wall [-].

    Returns
    -------
    numpy.ndarray
        G, shape (``steps``, ``rings``, ``rings``) [m/N].
    """

    description = [material.youngs_modulus, material.poisson_ratio, material.density, r_in,
                   r_out, length, step, int(steps), int(rings), code_version(),
                   hashlib.sha256(Path(head_kernel.__file__).read_bytes()).hexdigest()]
    key = hashlib.sha256(json.dumps(description).encode()).hexdigest()
    path = cache_dir() / (key + KERNEL_SUFFIX)

    def read(warn: bool):
        if path.is_file():
            try:
                with np.load(path, allow_pickle=False) as npz:
                    kernel = npz["kernel"]
                if kernel.shape == (int(steps), int(rings), int(rings)):
                    return kernel
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                pass  # unreadable: computed again and replaced
        return None

    def store(kernel) -> None:
        write_atomic(path, lambda fh: np.savez(fh, kernel=kernel))

    return cached_entry(path, read,
                        lambda: ring_kernel(material, r_in, r_out, length, step, steps, rings),
                        store)


def cached_entry(path: Path, read, compute, store):
    """A cache entry: read, or computed and stored once among concurrent askers.

    ``read(True)`` is tried first; on a miss the entry's lock is taken (:func:`entry_lock`),
    ``read(False)`` tried again (another process may have stored it meanwhile), and only then
    ``compute()`` called and its value handed to ``store``. ``read``'s argument says whether it
    may warn of an entry it rejects (once, on the first try).

    Parameters
    ----------
    path : pathlib.Path
        The entry's file.
    read : callable
        ``read(warn: bool)``: the stored value, or None on a miss.
    compute : callable
        ``compute()``: the value.
    store : callable
        ``store(value)``: writes it (atomically, :func:`write_atomic`).

    Returns
    -------
    object
        The value.
    """
    value = read(True)
    if value is not None:
        return value
    with entry_lock(path):
        value = read(False)
        if value is None:
            value = compute()
            store(value)
    return value


LOCK_SUFFIX = ".lock"
"""File name ending of an entry's lock file (``<entry>.lock``, :func:`entry_lock`)."""


@contextmanager
def entry_lock(path: Path):
    """Hold the exclusive lock of the cache entry ``path`` (module docstring).

    ``flock`` on ``<entry>.lock``, waited for while another process or thread holds it, and
    released on leaving (or by the operating system when the process ends), the lock file
    removed with it. Where no lock can be taken, nothing is held.

    Parameters
    ----------
    path : pathlib.Path
        The entry's file.

    Yields
    ------
    None
        While the lock is held.
    """
    handle = None
    lock = path.with_name(path.name + LOCK_SUFFIX)
    if fcntl is not None:
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            handle = open(lock, "ab")  # noqa: SIM115
        except OSError:
            handle = None
        if handle is not None:
            try:
                fcntl.flock(handle.fileno(), fcntl.LOCK_EX)
            except OSError:  # a file system without flock: no lock
                handle.close()
                handle = None
    try:
        yield
    finally:
        if handle is not None:
            # removed while held: an asker still waiting on it then finds the entry stored
            # (or, if it could not be stored, computes its own, as without a lock)
            try:
                lock.unlink(missing_ok=True)
            except OSError:
                pass
            handle.close()  # releases the lock


def write_atomic(path: Path, write) -> None:
    """Write a cache entry atomically, or not at all.

    ``write(file object)`` writes into a temporary file beside ``path``, which is then renamed
    onto ``path``; a cache that cannot be written is skipped (the value is only not reused).

    Parameters
    ----------
    path : pathlib.Path
        The entry's file.
    write : callable
        Called with the open binary file object.
    """
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=path.name[:16] + "-", suffix=".part", dir=path.parent)
        try:
            with os.fdopen(fd, "wb") as fh:
                write(fh)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
    except OSError:
        pass


def _store(data, path: Path) -> None:
    """Write modal data atomically (:func:`_write_atomic` of
    :func:`anvilwave.anvil_rom.fem.modalfile.write_modal_data`)."""

    write_atomic(path, lambda fh: write_modal_data(data, fh))


def cache_info() -> dict:
    """The contents of the cache.

    Returns
    -------
    dict
        ``{"directory": str, "entries": int, "bytes": int, "files": [...]}``; each file
        ``{"name", "bytes"}`` with ``"modes", "fmax [Hz]", "n_dof", "total_mass [kg]"`` (modal
        data), ``"chain_masses", "total_mass [kg]"`` (a modal ram's chain),
        ``"head_kernel_steps", "rings"`` (a tube head's ring kernel), ``"fea_output_samples"``
        (a reference FEA's result, :mod:`anvilwave.fea.cache`) or ``"unreadable"``.
    """
    directory = cache_dir()
    files = sorted(directory.glob("*" + SUFFIX)) if directory.is_dir() else []
    rows = []
    for path in files:
        row = {"name": path.name, "bytes": path.stat().st_size}
        try:
            if path.name.endswith(CHAIN_SUFFIX):
                with np.load(path, allow_pickle=False) as npz:
                    row.update({"chain_masses": int(npz["mass"].size),
                                "total_mass [kg]": float(npz["mass"].sum())})
            elif path.name.endswith(FEA_SUFFIX):
                with np.load(path, allow_pickle=False) as npz:
                    row.update({"fea_output_samples": int(npz["time"].size)})
            elif path.name.endswith(KERNEL_SUFFIX):
                with np.load(path, allow_pickle=False) as npz:
                    row.update({"head_kernel_steps": int(npz["kernel"].shape[0]),
                                "rings": int(npz["kernel"].shape[1])})
            else:

                data = load_modal_data(path)
                row.update({"modes": data.n_modes, "fmax [Hz]": data.fmax, "n_dof": data.n_dof,
                            "total_mass [kg]": data.total_mass})
        except Exception:  # an unreadable entry is listed as such
            row["unreadable"] = True
        rows.append(row)
    return {"directory": str(directory), "entries": len(rows),
            "bytes": int(sum(r["bytes"] for r in rows)), "files": rows}


def clear_cache() -> tuple[int, int]:
    """Delete every cache entry and stale temporary file (and the entries' lock files).

    Returns
    -------
    files : int
        Files removed [-].
    bytes : int
        Bytes removed [B].
    """
    directory = cache_dir()
    if not directory.is_dir():
        return 0, 0
    count = size = 0
    for path in directory.glob("*" + LOCK_SUFFIX):  # a killed holder's (empty), not counted
        path.unlink(missing_ok=True)
    for path in list(directory.glob("*" + SUFFIX)) + list(directory.glob("*.part")):
        try:
            size += path.stat().st_size
            path.unlink()
            count += 1
        except FileNotFoundError:
            pass
    return count, size
