"""The system layer: the public API, the layering contract, resource guards, the key schema."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from anvilwave.inputs import Table

from .conftest import EXAMPLES, ROOT, example_systems
from .example_numbers import SCRIPT_API_FIRST_PEAK, first_printed_peak, load_numbers

BIN = Path(sys.executable).parent


def _run(*args, timeout=120):
    return subprocess.run([sys.executable, *args], capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT)


def test_import_anvilwave_gives_the_public_api():
    r = _run("-c", "import anvilwave; print(sorted(anvilwave.__all__))")
    assert r.returncode == 0, r.stderr
    for name in ("load_system", "simulate", "compute_anvil_modes", "build_fmus", "InputError",
                 "Blow"):
        assert name in r.stdout


def test_script_api_example_runs_and_prints_its_table():
    r = _run(str(EXAMPLES / "script_api.py"), timeout=300)
    assert r.returncode == 0, r.stderr
    lines = [ln for ln in r.stdout.splitlines() if ln.strip()]
    assert len(lines) == 7  # header + 3 energies x 2 anvils
    peaks = [float(ln.split()[2]) for ln in lines[1:]]
    # the peak pile force grows with the energy for each anvil (a physical check on the sweep)
    assert peaks[0] < peaks[2] < peaks[4] and peaks[1] < peaks[3] < peaks[5]
    # its first peak (3500 kJ, ROM) is the stored one of tests/data/example_numbers.json
    # (python -m tests.regenerate_example_numbers): printed to 0.1 MN, so within half of that
    stored = load_numbers()[SCRIPT_API_FIRST_PEAK]
    assert first_printed_peak(r.stdout) == pytest.approx(stored, abs=0.05 + 1e-9)


def test_layering_contract_is_kept():
    exe = BIN / "lint-imports"
    if not exe.exists():
        exe = shutil.which("lint-imports")
    assert exe, "import-linter is a test dependency (pip install -e '.[test]')"
    r = subprocess.run([str(exe)], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "KEPT" in r.stdout and "BROKEN" not in r.stdout


def _bomb(tmp_path: Path, kind: str) -> Path:
    table1 = (EXAMPLES / "table1.toml").read_text()
    shutil.copytree(EXAMPLES / "anvils", tmp_path / "anvils")
    if kind == "blows":
        text = table1.replace("[simulation]\n", "[simulation]\nblows = 1000000000\n", 1)
    elif kind == "segments":
        text = re.sub(r"segment_length = [0-9.e-]+", "segment_length = 1.0e-6", table1)
    else:
        anvil = (EXAMPLES / "anvils" / "xl8.toml").read_text()
        (tmp_path / "anvils" / "bomb.toml").write_text(
            re.sub(r"\nsize = [0-9.e-]+", "\nsize = 1.0e-5", anvil))
        text = table1.replace("anvils/xl8.toml", "anvils/bomb.toml")
    assert text != table1
    path = tmp_path / f"{kind}.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("kind, key", [("blows", "simulation.blows"),
                                       ("segments", "pile.segment_length"),
                                       ("mesh", "mesh.size")])
def test_resource_bombs_are_refused_with_their_estimate(tmp_path, kind, key, monkeypatch):
    system = _bomb(tmp_path, kind)
    r = _run("-m", "anvilwave", "impact", str(system), "--out", str(tmp_path / "out"))
    assert r.returncode == 2, r.stdout + r.stderr
    message = r.stderr.strip()
    assert "Traceback" not in message and len(message.splitlines()) == 1
    assert key in message and "too big for this machine" in message
    # the estimate: sizes and a limit are named
    assert re.search(r"\d(\.\d+)?e\+\d+", message)
    assert not (tmp_path / "out").exists()  # nothing half-written
    # refused before any work: in-process, meshing, the modal analysis and the engine build
    # are made to fail loudly, and the command still stops with the budget's message
    import gmsh

    from anvilwave import cli
    from anvilwave.analyses import impact
    from anvilwave.anvil_rom.fem import pipeline

    def no_work(*args, **kwargs):
        raise AssertionError("work started before the budget check")

    monkeypatch.setattr(gmsh, "initialize", no_work)
    monkeypatch.setattr(pipeline, "free_free_modes", no_work)
    monkeypatch.setattr(impact, "build_engine", no_work)
    assert cli.main(["impact", str(system), "--out", str(tmp_path / "out2")]) == 2
    assert not (tmp_path / "out2").exists()


def test_every_key_the_examples_use_is_documented():
    from anvilwave.anvil_rom.fem.geometry import load_anvil
    from anvilwave.config.schema import documented
    from anvilwave.config.system import load_system

    Table.record = used = []
    try:
        for name in example_systems():
            load_system(EXAMPLES / name)
        for path in sorted((EXAMPLES / "anvils").glob("*.toml")):
            load_anvil(path)
    finally:
        Table.record = None
    # hammer files (anvilwave/hammer/data, each citing its source) are their own format
    system_keys = {k for f, k in used if Path(f).parent == EXAMPLES}
    anvil_keys = {k for f, k in used if Path(f).parent == EXAMPLES / "anvils"}
    assert system_keys and anvil_keys
    missing = sorted(k for k in system_keys if not documented("system", k))
    missing += sorted(k for k in anvil_keys if not documented("anvil", k))
    assert not missing, f"keys accepted but not in anvilwave/config/schema.py: {missing}"
