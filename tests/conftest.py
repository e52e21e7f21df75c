"""Shared fixtures: small anvil models built once per test session."""

from __future__ import annotations

import os
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse.linalg  # noqa: F401  (its OpenBLAS loaded, for the limit below)
from packaging.requirements import Requirement

import anvilwave
from anvilwave.anvil_rom.fem.elasticity import assemble
from anvilwave.anvil_rom.fem.geometry import STEEL
from anvilwave.anvil_rom.fem.mesh import mesh_outline, to_skfem
from anvilwave.output.examples import EXAMPLES_DIR

# One BLAS thread in each test process (numpy's and scipy's OpenBLAS; threadpoolctl): the suite
# runs one worker per core (``-n 2``), and each worker's OpenBLAS threads on every core then
# fight the other worker's (two shift-invert Lanczos solves of the ram's 502 modes side by side:
# 107 s each with OpenBLAS's default threads, 47-52 s with one). Process-local, not an
# environment variable: the commands the tests run in subprocesses (the docs' shown outputs)
# keep the library's default, as a user's run does (BLAS's sums, split by thread, move the last
# digits; the XL installation ends one blow apart).
try:
    from threadpoolctl import threadpool_limits
except ImportError:  # the wheel's check in .ci/run installs pytest alone: one process there
    pass
else:
    threadpool_limits(limits=1, user_api="blas")

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = EXAMPLES_DIR
"""The shipped examples: the checkout's, or the installed package's where the tests run against
an installed wheel (``.ci/run``)."""
FROM_CHECKOUT = Path(anvilwave.__file__).resolve().parent == ROOT / "anvilwave"
"""Whether the anvilwave under test is this checkout (else an installed distribution)."""
DEMO_IN_WHEEL = os.environ.get("ANVILWAVE_CI_DEMO") == "wheel"
"""``.ci/run`` runs the demo's tests (tests/test_compare.py) against the installed wheel,
outside the checkout, instead of in the checkout: the demo runs once."""
SHARED = ROOT.parent / "shared"
"""The shared reference data beside the repository (never copied into it)."""
NEEDS_SHARED = {"grlweap_s4000.toml"}
"""Example files that read data from the shared folder."""


def example_systems() -> list[str]:
    """Names of the example system files that can be loaded here (those reading the shared
    folder only when it is present)."""
    names = sorted(p.name for p in EXAMPLES.glob("*.toml")
                   if not p.name.startswith("campaign_"))  # campaign files: test_campaign
    if not (SHARED / "reference").is_dir():
        names = [n for n in names if n not in NEEDS_SHARED]
    return names


def assert_within_issue_bounds(m: dict) -> None:
    """The comparison bounds the issue sets on a ROM's metrics against the FEA
    (:func:`anvilwave.analyses.compare.metrics`, every series low-passed at 5 kHz): pile peak within
    3 %, ram peak within 5 %, normalised RMS of both within 10 %; the raw peaks against the
    FEA's band peaks, pile within 5 %, ram within 10 %."""
    assert abs(m["peak_anvil_pile_force_error [-]"]) <= 0.03
    assert abs(m["peak_ram_anvil_force_error [-]"]) <= 0.05
    assert m["anvil_pile_force_normalised_rms_error [-]"] <= 0.10
    assert m["ram_anvil_force_normalised_rms_error [-]"] <= 0.10
    assert abs(m["peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]"]) <= 0.05
    assert abs(m["peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"]) <= 0.10


def cylinder_model(length: float, diameter: float = 1.0, size: float = 0.05):
    """Assembled FE model of a free solid steel cylinder (half-section r <= D/2, 0 <= z <= L)."""
    outline = np.array([[0.0, 0.0], [diameter / 2, 0.0], [diameter / 2, length], [0.0, length]])
    return assemble(to_skfem(mesh_outline(outline, size)), STEEL)


@pytest.fixture(scope="session")
def examples_dir() -> Path:
    return EXAMPLES


@pytest.fixture(scope="session", autouse=True)
def modal_cache(tmp_path_factory) -> Path:
    """The modal-data cache of the test session (anvilwave.config.cache): a folder of the session's
    temporary tree, shared by the xdist workers (so concurrent writes are exercised), never
    the user's cache. Tests that check the cache itself point it elsewhere."""
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent
    path = root / "anvilwave-cache"
    saved = os.environ.get("ANVILWAVE_CACHE_DIR")
    os.environ["ANVILWAVE_CACHE_DIR"] = str(path)
    yield path
    if saved is None:
        os.environ.pop("ANVILWAVE_CACHE_DIR", None)
    else:
        os.environ["ANVILWAVE_CACHE_DIR"] = saved


HEAVY_MODULES = ("test_modal_ram", "test_ram_annuli", "test_example_numbers", "test_cache",
                 "test_driveability", "test_installation", "test_readme_outputs",
                 "test_tube_head", "test_study_pile_port", "test_compare", "test_setup",
                 "test_campaign", "test_stack")
"""Test modules with the longest tests (minutes under load): collected first, so that with
``--dist worksteal`` (pyproject) the two workers start on them and end together, instead of one
starting a long test when the other is done."""


def pytest_collection_modifyitems(session, config, items):
    """Put the tests of :data:`HEAVY_MODULES` first, in that order (stable: each module's tests
    stay together and in their order, so module fixtures are built once per worker)."""
    rank = {name: i for i, name in enumerate(HEAVY_MODULES)}
    def key(item) -> int:
        module = getattr(item, "module", None)
        name = module.__name__.rsplit(".", 1)[-1] if module is not None else ""
        return rank.get(name, len(HEAVY_MODULES))

    items.sort(key=key)


PLAIN_HOST_PACKAGES = ("fmpy", "numpy", "scipy", "numba")
"""What a Python needs to run the pythonfmu units (their anvilwave and pythonfmu code is in the
FMU): the Python of the tests that take the FMUs to a host without anvilwave."""


def _distribution_closure(names) -> list:
    """The installed distributions ``names`` need, with their requirements' (markers evaluated
    for this Python; extras not followed): importlib.metadata's view of this venv."""
    seen: dict[str, metadata.Distribution] = {}
    todo = list(names)
    while todo:
        name = todo.pop()
        key = name.lower().replace("_", "-")
        if key in seen:
            continue
        dist = metadata.distribution(name)
        seen[key] = dist
        for text in dist.requires or []:
            req = Requirement(text)
            if req.marker is None or req.marker.evaluate({"extra": ""}):
                todo.append(req.name)
    return list(seen.values())


@pytest.fixture(scope="session")
def plain_python(tmp_path_factory) -> Path:
    """A venv with only :data:`PLAIN_HOST_PACKAGES` and what they require (no anvilwave, no
    pythonfmu, no pip): its python.

    The venv is made without pip, and its site-packages gets links to the files of exactly
    those distributions as this Python has them installed (each distribution's RECORD names its
    top-level files and folders). So the packages are the tests' own (same versions, nothing
    downloaded), and nothing else is importable there: not anvilwave (its editable finder is a
    ``.pth`` file of this venv that is not linked), not pythonfmu.
    """
    folder = tmp_path_factory.mktemp("plain-fmu-host") / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(folder)], check=True)
    python = folder / "bin" / "python"
    site = Path(subprocess.run([str(python), "-I", "-c", "import sysconfig; "
                                "print(sysconfig.get_paths()['purelib'])"], check=True,
                               capture_output=True, text=True).stdout.strip())
    for dist in _distribution_closure(PLAIN_HOST_PACKAGES):
        base = Path(dist.locate_file(""))
        tops = {Path(f).parts[0] for f in dist.files or [] if not Path(f).is_absolute()}
        for top in sorted(tops - {"..", "__pycache__"}):
            if (base / top).exists() and not (site / top).exists():
                (site / top).symlink_to(base / top)
    probe = subprocess.run([str(python), "-I", "-c", "import " + ", ".join(PLAIN_HOST_PACKAGES)
                            + "\ntry:\n import anvilwave\nexcept ImportError: pass\n"
                            "else: raise SystemExit('anvilwave importable')\n"
                            "try:\n import pythonfmu\nexcept ImportError: pass\n"
                            "else: raise SystemExit('pythonfmu importable')"],
                           capture_output=True, text=True)
    assert probe.returncode == 0, probe.stderr
    return python
    subprocess.run([sys.executable, "-m", "venv", "--clear", str(folder)], check=True)
    pip = subprocess.run([str(python), "-m", "pip", "install", "-q", *PLAIN_HOST_PACKAGES],
                         capture_output=True, text=True, timeout=1800)
    if pip.returncode != 0 or subprocess.run(probe, capture_output=True).returncode != 0:
        lines = (pip.stderr or pip.stdout).strip().splitlines()
        pytest.skip("a venv with " + ", ".join(PLAIN_HOST_PACKAGES) + " cannot be made (pip "
                    "cannot reach a package index?): " + (lines[-1] if lines else "no output"))
    return python
