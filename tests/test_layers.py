"""The layering inside anvilwave: no project module imported inside a function to dodge a
cycle (the import-linter contract in pyproject.toml only sees module-level imports as
edges of the graph it checks, so a hidden import would let a cycle back in), and the
contract covers the inner packages.

A lazy import of a project module is allowed only with a comment on its line that starts
with ``# lazy:`` and says why (e.g. a heavy optional dependency behind it).
"""

from __future__ import annotations

import ast
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "anvilwave"


def _local_project_imports(path: Path) -> list[tuple[int, str]]:
    """(line, statement) of every import of an anvilwave module inside a function of
    ``path`` that carries no ``# lazy:`` comment."""
    source = path.read_text()
    lines = source.splitlines()
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        for sub in ast.walk(node):
            if isinstance(sub, ast.ImportFrom):
                names = [sub.module or ""] if sub.level == 0 else ["anvilwave (relative)"]
            elif isinstance(sub, ast.Import):
                names = [a.name for a in sub.names]
            else:
                continue
            if any(n.split(".")[0] == "anvilwave" for n in names):
                if "# lazy:" not in lines[sub.lineno - 1]:
                    found.append((sub.lineno, lines[sub.lineno - 1].strip()))
    return sorted(set(found))


def test_no_function_local_import_of_a_project_module():
    unexplained = {str(p.relative_to(ROOT)): hits for p in sorted(PACKAGE.rglob("*.py"))
                   if (hits := _local_project_imports(p))}
    count = sum(len(v) for v in unexplained.values())
    assert count == 0, f"{count} function-local project imports: {unexplained}"


def test_the_counter_sees_a_hidden_import(tmp_path):
    """The check above can fail: a function-local import is found, a ``# lazy:`` one is
    not."""
    module = tmp_path / "m.py"
    module.write_text("def f():\n    from anvilwave.config import system\n\n"
                      "def g():\n    import anvilwave.engine  # lazy: numba\n")
    assert _local_project_imports(module) == [(2, "from anvilwave.config import system")]


def test_the_layers_contract_orders_the_inner_packages():
    """The contract names every subpackage of anvilwave, bottom layer last."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
    (contract,) = [c for c in config["contracts"] if c["type"] == "layers"]
    assert contract["containers"] == ["anvilwave"]
    layered = {name.strip() for layer in contract["layers"] for name in layer.split("|")}
    packages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()}
    modules = {p.stem for p in PACKAGE.glob("*.py")} - {"__init__", "__main__"}
    assert packages | modules == layered
    # the example scripts use the public API: the top layer; the input reader the bottom
    assert contract["layers"][-1] == "inputs" and contract["layers"][0] == "examples"
