"""The pythonfmu Ram and PileSoil taken to a Python without anvilwave (and without pythonfmu).

Each pythonfmu FMU carries the anvilwave code its slave runs as the package
``anvilwave_fmu_<digest>`` (:mod:`anvilwave.fmu.vendoring`, :mod:`anvilwave.fmu.units.vendor_init`)
and pythonfmu's Python part. The units of Table 1's system (``build_system_fmus(...,
native_units=False)``) run under fmpy in a fresh venv with only fmpy, numpy, scipy and numba
(:func:`tests.conftest.plain_python`: a venv without pip whose site-packages links exactly
those distributions),
and in this Python: with anvilwave importable and byte-identical (the package's modules are
anvilwave's), and with anvilwave imported but taken as different (the FMU's own copies beside
it). The three runs execute the same Python source on the same inputs, so the outputs must be
bitwise equal: any difference is code that did not travel or a clash between the two copies.
"""

from __future__ import annotations

import json
import subprocess
import sys
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from anvilwave.config.system import load_system  # noqa: E402
from anvilwave.engine.fmus import build_system_fmus, load_anvil_modal_data  # noqa: E402
from anvilwave.fmu.fmi_build import LICENSE_FILES  # noqa: E402
from anvilwave.fmu.units.vendor_init import MANIFEST_FILE  # noqa: E402
from anvilwave.fmu.vendoring import PACKAGE_PREFIX  # noqa: E402

from .conftest import EXAMPLES, ROOT  # noqa: E402

RUNNER = ROOT / "tests" / "fmu_unit_run.py"
KINDS = ("Ram", "PileSoil")


@pytest.fixture(scope="module")
def units(tmp_path_factory) -> dict[str, Path]:
    """Table 1's pythonfmu Ram and PileSoil."""
    cfg = load_system(EXAMPLES / "table1.toml")
    out = tmp_path_factory.mktemp("portable_fmus")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # no C compiler: the pythonfmu anvils (not used here)
        fmus = build_system_fmus(cfg, out, load_anvil_modal_data(cfg), native_anvil=None,
                                 native_units=False, ssp=False)
    assert fmus["ram_implementation"] == fmus["pile_soil_implementation"] == "pythonfmu"
    return {kind: fmus[kind] for kind in KINDS}


def run_unit(python: Path, fmu: Path, kind: str, out: Path, *extra: str) -> dict:
    """tests/fmu_unit_run.py in ``python`` (isolated: no cwd, no PYTHONPATH), outside the
    checkout; its JSON report."""
    run = subprocess.run([str(python), "-I", str(RUNNER), str(fmu), kind, str(out), *extra],
                         capture_output=True, text=True, timeout=900, cwd=out.parent)
    assert run.returncode == 0, run.stdout + run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


def vendored_package(fmu: Path) -> str:
    with zipfile.ZipFile(fmu) as zf:
        names = zf.namelist()
    packages = {n.split("/")[1] for n in names if n.startswith("resources/" + PACKAGE_PREFIX)}
    assert len(packages) == 1, packages
    return packages.pop()


@pytest.mark.parametrize("kind", KINDS)
def test_the_fmu_carries_its_code_and_the_licences(units, kind):
    with zipfile.ZipFile(units[kind]) as zf:
        names = set(zf.namelist())
        package = vendored_package(units[kind])
        script = zf.read(f"resources/anvilwave_{'ram' if kind == 'Ram' else 'pile_soil'}.py")
        manifest = json.loads(zf.read(f"resources/{package}/{MANIFEST_FILE}"))
        licence = zf.read(LICENSE_FILES["anvilwave"])
    assert b"from anvilwave." not in script and f"from {package}.".encode() in script
    assert not any(n.endswith(".pyc") or "__pycache__" in n for n in names)
    assert {LICENSE_FILES["pythonfmu"], "resources/pythonfmu/LICENSE",
            f"resources/{package}/LICENSE", "resources/pythonfmu/fmi2slave.py"} <= names
    assert licence == (ROOT / "LICENSE").read_bytes()
    # the closure is the unit's, not anvilwave's command line, analyses, output or FEA
    assert not any(m.split(".")[0] in ("cli", "api", "analyses", "output", "fea", "engine",
                                       "config") for m in manifest["modules"])
    assert f"fmu/units/{'ram' if kind == 'Ram' else 'pile_soil'}.py" in manifest["files"]


@pytest.mark.parametrize("kind", KINDS)
def test_units_run_without_anvilwave_as_with_it(units, kind, plain_python, tmp_path):
    """Fresh venv (vendored code), this Python (anvilwave's identical modules), this Python
    with anvilwave imported and the FMU's copy taken as another version: bitwise the same."""
    plain = run_unit(plain_python, units[kind], kind, tmp_path / "plain.npy")
    assert plain["source"] == ["vendored"]
    assert "anvilwave" not in plain["modules"] and "matplotlib" not in plain["modules"]
    assert "/resources/pythonfmu/" in plain["pythonfmu"]  # the FMU's own pythonfmu
    here = run_unit(Path(sys.executable), units[kind], kind, tmp_path / "here.npy")
    assert here["source"] == ["installed"]
    # another build's code: the manifest's digest no longer that of the installed files
    folder = tmp_path / "unzipped"
    with zipfile.ZipFile(units[kind]) as zf:
        zf.extractall(folder)
    path = folder / "resources" / vendored_package(units[kind]) / MANIFEST_FILE
    manifest = json.loads(path.read_text())
    manifest["digest"] = "0" * 64
    path.write_text(json.dumps(manifest))
    beside = run_unit(Path(sys.executable), units[kind], kind, tmp_path / "beside.npy",
                      "--import-anvilwave", "--unzipped", str(folder))
    assert beside["source"] == ["vendored"] and "anvilwave" in beside["modules"]
    reference = np.load(tmp_path / "here.npy")
    assert np.all(np.isfinite(reference)) and np.abs(reference).max() > 0.0
    np.testing.assert_array_equal(np.load(tmp_path / "plain.npy"), reference)
    np.testing.assert_array_equal(np.load(tmp_path / "beside.npy"), reference)
