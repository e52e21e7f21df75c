"""The anvilwave code a pythonfmu unit carries in its ``resources/`` (it runs without anvilwave).

:func:`vendored_unit` collects the import closure of a slave script inside anvilwave (the modules
its module-level imports reach, and theirs; function-local imports, which the project marks
``# lazy:`` and keeps off the units' paths, are not followed), with the data files of
:data:`PACKAGE_DATA`, and writes it as the package ``anvilwave_fmu_<digest>``: every
``anvilwave`` import of the copied modules and of the script renamed to it, the packages on the
way given an empty ``__init__.py`` (their own would import the rest of anvilwave), and the
package's ``__init__.py`` the module :mod:`anvilwave.fmu.units.vendor_init`, which decides at
import whether the package's modules are the FMU's copies or those of an anvilwave with the same
files already in the process (see there). ``<digest>`` is the first 16 hex digits of
:func:`~anvilwave.fmu.units.vendor_init.closure_digest` of the original files (that module
included): the same code, the same package name and bytes; any change, another name.

The closure of the Ram takes 21 modules (the lumped and modal ram, the pile model for its
sub-steps, the hammer database with its data), the PileSoil's 10, the anvils' 9;
none imports the command line, the analyses, the output layer or matplotlib: the units need the
standard library, numpy, scipy, numba and pythonfmu (which pythonfmu's build puts into the FMU).
"""

from __future__ import annotations

import ast
import importlib.metadata
import json
import re
from pathlib import Path

from anvilwave.fmu.units import vendor_init

PACKAGE_ROOT = Path(__file__).resolve().parents[1]
"""The anvilwave package folder whose files are copied."""
PACKAGE_PREFIX = "anvilwave_fmu_"
"""Vendored package names: this prefix and the first 16 hex digits of the closure digest."""
PACKAGE_DATA: dict[str, tuple[str, ...]] = {"hammer.database": ("hammer/data",)}
"""Data folders a module reads beside itself (relative to the package), copied with it."""
RUNTIME_MODULE = "fmu/units/vendor_init.py"
"""The file that becomes the vendored package's ``__init__.py``."""
STUB_INIT = '"""A part of anvilwave copied into this FMU (see the package\'s __init__)."""\n'
"""``__init__.py`` of the packages on the way to the copied modules."""


def _module_file(name: str) -> tuple[Path, bool] | None:
    """File of the anvilwave module ``name`` (dotted, relative) and whether it is a package."""
    path = PACKAGE_ROOT.joinpath(*name.split("."))
    if (path / "__init__.py").is_file():
        return path / "__init__.py", True
    if path.with_suffix(".py").is_file():
        return path.with_suffix(".py"), False
    return None


def _module_level_imports(tree: ast.AST):
    """Import statements executed when the module is imported (not inside functions)."""
    stack = list(ast.iter_child_nodes(tree))
    while stack:
        node = stack.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
            continue
        if isinstance(node, ast.Import | ast.ImportFrom):
            yield node
        stack.extend(ast.iter_child_nodes(node))


def _project_imports(source: str, origin: str) -> set[str]:
    """The anvilwave modules (relative dotted names) the module-level imports of ``source``
    load, a package's ``__init__`` only when a name is taken from it."""
    found = set()
    for node in _module_level_imports(ast.parse(source, origin)):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names if a.name.split(".")[0] == "anvilwave"]
            for name in names:
                if name == "anvilwave":
                    raise ValueError(f"{origin}: imports the anvilwave package itself")
                found.add(name.split(".", 1)[1])
            continue
        if node.level or not node.module or node.module.split(".")[0] != "anvilwave":
            if node.level:
                raise ValueError(f"{origin}:{node.lineno}: relative import")
            continue
        if node.module == "anvilwave":
            raise ValueError(f"{origin}:{node.lineno}: imports from the anvilwave package "
                             "itself (its __init__ imports everything)")
        module = node.module.split(".", 1)[1]
        for alias in node.names:
            if _module_file(f"{module}.{alias.name}") is not None:
                found.add(f"{module}.{alias.name}")
            else:
                found.add(module)
    return found


def import_closure(script: Path) -> list[str]:
    """The anvilwave modules a slave script needs, its module-level imports followed.

    Parameters
    ----------
    script : pathlib.Path
        The slave script (``anvilwave/fmu/units/anvilwave_<unit>.py``).

    Returns
    -------
    list of str
        Module names relative to the anvilwave package (``"fmu.units.ram"``), sorted.

    Raises
    ------
    ValueError
        If a module imports the anvilwave package itself, uses a relative import or names a
        module that is not there.
    """
    todo = sorted(_project_imports(script.read_text(encoding="utf-8"), str(script)))
    seen: set[str] = set()
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        found = _module_file(name)
        if found is None:
            raise ValueError(f"{script}: imports anvilwave.{name}, which is not there")
        seen.add(name)
        todo.extend(sorted(_project_imports(found[0].read_text(encoding="utf-8"),
                                            str(found[0])) - seen))
    return sorted(seen)


def rewrite_imports(source: str, package: str, origin: str = "<source>") -> str:
    """``source`` with every ``anvilwave`` import (module level or not) taken from ``package``.

    Only the import statements change (``from anvilwave.x import y`` -> ``from package.x import
    y``, ``import anvilwave.x as y`` -> ``import package.x as y``); text elsewhere is kept.

    Parameters
    ----------
    source : str
        Python source.
    package : str
        The vendored package's name.
    origin : str, default "<source>"
        Name of the source in error messages.

    Returns
    -------
    str
        The rewritten source.

    Raises
    ------
    ValueError
        If ``import anvilwave.x`` has no ``as`` (its uses would name anvilwave).
    """
    lines = source.splitlines(keepends=True)
    for node in ast.walk(ast.parse(source, origin)):
        if isinstance(node, ast.ImportFrom) and node.module and \
                node.module.split(".")[0] == "anvilwave" and not node.level:
            pattern = r"(\bfrom\s+)anvilwave\b"
        elif isinstance(node, ast.Import) and any(a.name.split(".")[0] == "anvilwave"
                                                  for a in node.names):
            if any(a.asname is None for a in node.names if a.name.split(".")[0] == "anvilwave"):
                raise ValueError(f"{origin}:{node.lineno}: 'import anvilwave...' without 'as'")
            pattern = r"(\bimport\s+|,\s*)anvilwave\b"
        else:
            continue
        row = node.lineno - 1
        new, count = re.subn(pattern, rf"\g<1>{package}", lines[row])
        if count == 0:
            raise ValueError(f"{origin}:{node.lineno}: cannot rewrite the import")
        lines[row] = new
    return "".join(lines)


def license_text() -> bytes:
    """anvilwave's licence text (the checkout's ``LICENSE`` or the installed distribution's).

    Returns
    -------
    bytes
        The licence text.

    Raises
    ------
    RuntimeError
        If neither is found.
    """
    checkout = PACKAGE_ROOT.parent / "LICENSE"
    if checkout.is_file():
        return checkout.read_bytes()
    try:
        for file in importlib.metadata.distribution("anvilwave").files or ():
            if file.name.upper().startswith("LICENSE"):
                return Path(file.locate()).read_bytes()
    except importlib.metadata.PackageNotFoundError:
        pass
    raise RuntimeError("anvilwave's LICENSE is not found (neither in the checkout nor in the "
                       "installed distribution): the FMU would carry its code without it")


def pythonfmu_license_text() -> bytes | None:
    """pythonfmu's licence text from its installed distribution, if it has one.

    Returns
    -------
    bytes or None
        The licence text, or None when the distribution has no licence file.
    """
    try:
        files = importlib.metadata.distribution("pythonfmu").files or ()
    except importlib.metadata.PackageNotFoundError:
        return None
    for file in files:
        if file.name.upper().startswith(("LICENSE", "LICENCE", "COPYING")):
            return Path(file.locate()).read_bytes()
    return None


def vendored_unit(script: Path) -> tuple[str, dict[str, bytes]]:
    """The vendored package of a slave script and the script rewritten to use it.

    Parameters
    ----------
    script : pathlib.Path
        The slave script.

    Returns
    -------
    package : str
        The package name, ``anvilwave_fmu_<digest>``.
    files : dict of str to bytes
        FMU archive names (``resources/...``) -> content: the package's files (modules
        rewritten, stub and runtime ``__init__.py``, ``manifest.json``, ``LICENSE``) and the
        rewritten script ``resources/<script name>``.
    """
    modules = import_closure(script)
    originals: dict[str, bytes] = {}
    for name in modules:
        path, _ = _module_file(name)
        originals[path.relative_to(PACKAGE_ROOT).as_posix()] = path.read_bytes()
        for folder in PACKAGE_DATA.get(name, ()):
            for data in sorted((PACKAGE_ROOT / folder).rglob("*")):
                if data.is_file() and "__pycache__" not in data.parts and data.suffix != ".pyc":
                    originals[data.relative_to(PACKAGE_ROOT).as_posix()] = data.read_bytes()
    originals[RUNTIME_MODULE] = (PACKAGE_ROOT / RUNTIME_MODULE).read_bytes()
    digest = vendor_init.closure_digest(originals)
    package = PACKAGE_PREFIX + digest[:16]
    base = f"resources/{package}"
    files: dict[str, bytes] = {}
    for name, data in originals.items():
        if name == RUNTIME_MODULE:
            continue
        if name.endswith(".py"):
            data = rewrite_imports(data.decode("utf-8"), package, name).encode("utf-8")
        files[f"{base}/{name}"] = data
    packages = sorted({".".join(m.split(".")[:i]) for m in modules
                       for i in range(1, m.count(".") + 1)})
    for name in packages:
        init = f"{base}/{name.replace('.', '/')}/__init__.py"
        files.setdefault(init, STUB_INIT.encode())
    files[f"{base}/__init__.py"] = originals[RUNTIME_MODULE]
    manifest = {"format": vendor_init.FORMAT, "version": 1, "digest": digest,
                "files": sorted(originals), "modules": sorted(set(modules) | set(packages))}
    files[f"{base}/{vendor_init.MANIFEST_FILE}"] = (json.dumps(manifest, indent=1) + "\n"
                                                    ).encode()
    files[f"{base}/LICENSE"] = license_text()
    files[f"resources/{script.name}"] = rewrite_imports(
        script.read_text(encoding="utf-8"), package, str(script)).encode("utf-8")
    return package, files
