"""The package of a pythonfmu unit's own copy of anvilwave (this file is its ``__init__.py``).

A pythonfmu FMU carries in its ``resources/`` the anvilwave code its slave class runs (the
import closure, :mod:`anvilwave.fmu.vendoring`) as the package ``anvilwave_fmu_<digest>``: a
name of its own, so that it never shadows nor is shadowed by an installed anvilwave, and one
per content (``<digest>``: the first 16 hex digits of :func:`closure_digest` of the copied
files), so that FMUs of different builds in one process each run their own code and FMUs of
the same code share one copy. pythonfmu puts the FMU's ``resources`` folder on ``sys.path``;
the slave script imports its classes from the package.

On import the package reads its ``manifest.json`` (``MANIFEST_FILE``: the digest, the copied
files and modules) and looks for an anvilwave in the process (imported or importable). When
that anvilwave's copies of the files are byte for byte the FMU's (the same digest), the
package's modules are that anvilwave's (``sys.modules`` aliases: one copy of the code in the
process, its compiled numba kernels cached on disk as usual); otherwise, or when it cannot be
imported, they are the FMU's own copies. The files use only the Python standard library, numpy,
scipy, numba and pythonfmu (the latter inside the FMU too).

In the anvilwave package itself (no manifest beside it) importing this module does nothing.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import json
import sys
from pathlib import Path

MANIFEST_FILE = "manifest.json"
"""The vendored package's manifest, beside this file in the FMU."""
FORMAT = "anvilwave-fmu-vendored"
"""``format`` of the manifest."""


def closure_digest(files: dict[str, bytes]) -> str:
    """SHA-256 of a set of files: each name and its bytes, in name order.

    Parameters
    ----------
    files : dict of str to bytes
        File path relative to the anvilwave package (``/`` separated) -> content.

    Returns
    -------
    str
        The hex digest (64 digits).
    """
    digest = hashlib.sha256()
    for name in sorted(files):
        data = files[name]
        digest.update(name.encode() + b"\0" + len(data).to_bytes(8, "little"))
        digest.update(data)
    return digest.hexdigest()


def installed_root() -> Path | None:
    """The folder of the anvilwave imported or importable in this process, if any.

    Returns
    -------
    pathlib.Path or None
        The package folder (``.../anvilwave``), or None without one.
    """
    module = sys.modules.get("anvilwave")
    if module is not None and getattr(module, "__file__", None):
        return Path(module.__file__).resolve().parent
    try:
        spec = importlib.util.find_spec("anvilwave")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(next(iter(spec.submodule_search_locations))).resolve()


def same_files(root: Path, files: list[str], digest: str) -> bool:
    """Whether ``root`` holds ``files`` with exactly the content of the given digest.

    Parameters
    ----------
    root : pathlib.Path
        An anvilwave package folder.
    files : list of str
        Paths relative to it.
    digest : str
        The :func:`closure_digest` of the files as copied into the FMU.

    Returns
    -------
    bool
        True when every file is there and the digests agree.
    """
    content = {}
    for name in files:
        try:
            content[name] = (root / name).read_bytes()
        except OSError:
            return False
    return closure_digest(content) == digest


def bind(package: str, manifest: dict) -> str:
    """Make ``package``'s modules the installed anvilwave's when its files are the same.

    Parameters
    ----------
    package : str
        The vendored package's name (``anvilwave_fmu_<digest>``).
    manifest : dict
        Its manifest: ``digest``, ``files`` (relative paths), ``modules`` (dotted names
        relative to the package, intermediate packages included).

    Returns
    -------
    str
        ``"installed"`` (the aliases are in ``sys.modules``) or ``"vendored"`` (the FMU's
        own copies are imported as usual).
    """
    root = installed_root()
    if root is None or not same_files(root, manifest["files"], manifest["digest"]):
        return "vendored"
    aliases = {}
    try:
        for name in manifest["modules"]:
            aliases[f"{package}.{name}"] = importlib.import_module(f"anvilwave.{name}")
    except Exception:  # noqa: BLE001 - an installed anvilwave that does not import
        return "vendored"
    sys.modules.update(aliases)
    return "installed"


def _activate() -> str | None:
    path = Path(__file__).with_name(MANIFEST_FILE)
    if not path.is_file():  # the anvilwave package's own copy of this module
        return None
    manifest = json.loads(path.read_text(encoding="utf-8"))
    if manifest.get("format") != FORMAT:
        raise ImportError(f"{path}: not an {FORMAT} manifest")
    return bind(__name__, manifest)


SOURCE = _activate()
"""Where this package's modules come from: ``"installed"``, ``"vendored"``, or None (in
anvilwave itself)."""
