"""The modal-data cache: computed once, reused by later calls and processes, keyed by what the
modes depend on, written atomically; the lumped anvil needs no modes at all."""

from __future__ import annotations

import os
import threading
import time

import numpy as np
import pytest

import anvilwave.anvil_rom.fem.pipeline as pipeline
import anvilwave.config.cache as cache
from anvilwave.anvil_rom.fem.geometry import STEEL, AnvilSpec, Interfaces
from anvilwave.anvil_rom.fem.pipeline import solid_mass
from anvilwave.cli import main
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine

from .conftest import EXAMPLES, cylinder_model


def disc(**changes) -> AnvilSpec:
    """A small steel disc with a ram face and a pile ring (a few modes below 10 kHz)."""
    values = {"name": "disc", "material": STEEL,
              "outline": np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.3], [0.0, 0.3]]),
              "interfaces": Interfaces(0.2, 0.4, 0.1), "mesh_size": 0.06, "fmax": 10000.0}
    values.update(changes)
    return AnvilSpec(**values)


@pytest.fixture
def cache_dir(tmp_path, monkeypatch):
    directory = tmp_path / "cache"
    monkeypatch.setenv(cache.ENVIRONMENT_VARIABLE, str(directory))
    return directory


@pytest.fixture(scope="module")
def disc_modes():
    return pipeline.compute_anvil_modes(disc()).modal_data


def test_cache_directory_follows_the_environment(tmp_path, monkeypatch):
    monkeypatch.delenv(cache.ENVIRONMENT_VARIABLE, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache.cache_dir() == tmp_path / "xdg" / "anvilwave"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache.cache_dir() == tmp_path / "home" / ".cache" / "anvilwave"
    monkeypatch.setenv(cache.ENVIRONMENT_VARIABLE, str(tmp_path / "mine"))
    assert cache.cache_dir() == tmp_path / "mine"


def test_computed_once_then_read(cache_dir, disc_modes, monkeypatch):
    calls = []

    def compute(spec, fmax=None):
        calls.append(fmax)
        return type("Result", (), {"modal_data": disc_modes})

    monkeypatch.setattr(pipeline, "compute_anvil_modes", compute)
    first = cache.cached_modal_data(disc())
    second = cache.cached_modal_data(disc())
    assert calls == [10000.0]
    files = list(cache_dir.iterdir())
    assert [f.suffix for f in files] == [".npz"]  # no temporary file left behind
    for name in ("frequencies", "participation_ram", "participation_pile"):
        np.testing.assert_array_equal(getattr(second, name), getattr(first, name))
    assert second.total_mass == first.total_mass


def test_key_covers_what_the_modes_depend_on(monkeypatch):
    base = cache.modal_key(disc(), 10000.0)
    assert cache.modal_key(disc(), 10000.0) == base
    others = [cache.modal_key(disc(), 12000.0),
              cache.modal_key(disc(damping_ratio=0.02), 10000.0),
              cache.modal_key(disc(mesh_size=0.05), 10000.0),
              cache.modal_key(disc(material=type(STEEL)(200e9, 0.3, 7850.0)), 10000.0),
              cache.modal_key(disc(interfaces=Interfaces(0.25, 0.4, 0.1)), 10000.0),
              cache.modal_key(disc(outline=disc().outline * 1.01), 10000.0)]
    assert len({base, *others}) == 1 + len(others)
    # another code version (a changed modal analysis, another gmsh) is another entry
    monkeypatch.setattr(cache, "code_version", lambda: "another version")
    assert cache.modal_key(disc(), 10000.0) != base


def test_a_broken_entry_is_computed_again(cache_dir, disc_modes, monkeypatch):
    monkeypatch.setattr(pipeline, "compute_anvil_modes",
                        lambda spec, fmax=None: type("R", (), {"modal_data": disc_modes}))
    cache.cached_modal_data(disc())
    (entry,) = cache_dir.glob("*.npz")
    entry.write_bytes(b"not a zip file")
    data = cache.cached_modal_data(disc())
    assert data.n_modes == disc_modes.n_modes
    assert entry.stat().st_size > 100  # replaced by a complete file


def test_concurrent_writers_leave_one_complete_file(cache_dir, disc_modes, monkeypatch):
    """Workers computing the same entry at once (dask on one node) each write a temporary
    file and rename it: the entry is always complete and no temporary file remains."""
    monkeypatch.setattr(pipeline, "compute_anvil_modes",
                        lambda spec, fmax=None: type("R", (), {"modal_data": disc_modes}))
    errors = []

    def work():
        try:
            for _ in range(5):
                cache._store(disc_modes, cache_dir / "same.npz")
                assert cache.cached_modal_data(disc()).n_modes == disc_modes.n_modes
        except Exception as exc:  # reported below
            errors.append(exc)

    threads = [threading.Thread(target=work) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert not list(cache_dir.glob("*.part"))
    from anvilwave.anvil_rom.fem.modalfile import load_modal_data

    assert load_modal_data(cache_dir / "same.npz").n_modes == disc_modes.n_modes


def test_concurrent_askers_compute_an_entry_once(cache_dir):
    """Six threads asking for one missing tube-head kernel at once (each its own open lock
    file, as six processes would have): one computes it, the others wait on the entry's lock and
    read what it stored; every one gets the same kernel."""
    calls = []
    barrier = threading.Barrier(6)
    kernels, errors = [], []
    original = cache.ring_kernel

    def counted(*args):
        calls.append(1)
        time.sleep(0.3)  # long enough that the others reach the lock while it computes
        return original(*args)

    def work():
        try:
            barrier.wait()
            kernels.append(cache.cached_ring_kernel(STEEL, 0.95, 1.0, 2.0, 2e-5, 20, 2))
        except Exception as exc:  # reported below
            errors.append(exc)

    cache.ring_kernel = counted
    try:
        threads = [threading.Thread(target=work) for _ in range(6)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        cache.ring_kernel = original
    assert not errors and len(kernels) == 6
    assert len(calls) == 1
    for kernel in kernels[1:]:
        np.testing.assert_array_equal(kernel, kernels[0])


LOCK_HOLDER = """
import sys, time
from pathlib import Path
import numpy as np
from anvilwave.config.cache import entry_lock, write_atomic
path = Path(sys.argv[1])
with entry_lock(path):
    print("locked", flush=True)
    if sys.argv[2] == "store":
        time.sleep(1.0)
        write_atomic(path, lambda fh: np.save(fh, np.arange(3.0)))
    else:
        time.sleep(600)
"""


def _read_npy(path):
    return (lambda warn: np.load(path) if path.is_file() else None)


def test_another_process_waits_for_the_entry_and_reads_it(cache_dir):
    """A process computing an entry holds its lock; a second asker waits, then reads the
    first's result instead of computing it."""
    import subprocess
    import sys

    path = cache_dir / "entry.npy"
    holder = subprocess.Popen([sys.executable, "-c", LOCK_HOLDER, str(path), "store"],
                              stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"

        def refuse():
            raise AssertionError("computed although another process was computing it")

        value = cache.cached_entry(path, _read_npy(path), refuse, lambda v: None)
        np.testing.assert_array_equal(value, np.arange(3.0))
    finally:
        holder.kill()
        holder.wait()


def test_a_killed_process_does_not_hold_the_lock(cache_dir):
    """The lock of a process killed while computing is released by the system: the next asker
    computes the entry instead of waiting for ever (bounded here by a 60 s join)."""
    import subprocess
    import sys

    path = cache_dir / "entry.npy"
    holder = subprocess.Popen([sys.executable, "-c", LOCK_HOLDER, str(path), "hold"],
                              stdout=subprocess.PIPE, text=True)
    assert holder.stdout.readline().strip() == "locked"
    holder.kill()
    holder.wait()
    got = []

    def ask():
        got.append(cache.cached_entry(path, _read_npy(path), lambda: np.ones(2),
                                      lambda v: np.save(path, v)))

    thread = threading.Thread(target=ask, daemon=True)
    thread.start()
    thread.join(60.0)
    assert got and np.array_equal(got[0], np.ones(2))
    np.testing.assert_array_equal(np.load(path), np.ones(2))


def test_the_modal_ram_chain_is_cached(cache_dir, monkeypatch):
    omega = 2 * np.pi * np.array([0.0, 1000.0, 2300.0])
    p = np.array([1 / np.sqrt(1000.0), 0.02, 0.015])
    mass, stiffness = cache.cached_chain(omega, p)
    assert mass.sum() == pytest.approx(1000.0, rel=1e-9)
    monkeypatch.setattr("anvilwave.config.cache.chain_from_modes",
                        lambda *a: (_ for _ in ()).throw(AssertionError("realised again")))
    again = cache.cached_chain(omega, p)
    np.testing.assert_array_equal(again[0], mass)
    np.testing.assert_array_equal(again[1], stiffness)


def test_the_tube_head_kernel_is_cached_and_listed(cache_dir, monkeypatch, capsys):
    """A tube head's ring kernel (:func:`anvilwave.pile.head_kernel.ring_kernel`) is computed once,
    read
    back unchanged, and listed by ``anvilwave cache info``."""
    args = (STEEL, 0.95, 1.0, 2.0, 2e-5, 50, 2)
    kernel = cache.cached_ring_kernel(*args)
    assert kernel.shape == (50, 2, 2)
    monkeypatch.setattr("anvilwave.config.cache.ring_kernel",
                        lambda *a: (_ for _ in ()).throw(AssertionError("computed again")))
    np.testing.assert_array_equal(cache.cached_ring_kernel(*args), kernel)
    assert main(["cache", "info"]) == 0
    assert "tube head kernel, 2 rings, 50 steps" in capsys.readouterr().out


def test_cli_cache_info_and_clear(cache_dir, disc_modes, monkeypatch, capsys):
    monkeypatch.setattr(pipeline, "compute_anvil_modes",
                        lambda spec, fmax=None: type("R", (), {"modal_data": disc_modes}))
    cache.cached_modal_data(disc())
    assert main(["cache", "info"]) == 0
    out = capsys.readouterr().out
    assert str(cache_dir) in out and "1 entry," in out
    assert f"{disc_modes.n_modes:4d} modes" in out
    assert main(["cache", "clear"]) == 0
    assert "removed 1 entry" in capsys.readouterr().out
    assert not list(cache_dir.glob("*"))


def test_lumped_anvil_needs_no_modes(monkeypatch):
    """The rigid anvil's mass is the solid's (density x revolved volume): building its engine
    solves no eigenvalue problem, and the mass is the FE model's total mass to round-off."""
    cfg = load_system(EXAMPLES / "table1.toml").with_anvil_model("lumped")

    def refuse(*args, **kwargs):
        raise AssertionError("the lumped anvil must not compute modes")

    monkeypatch.setattr(pipeline, "compute_anvil_modes", refuse)
    engine = build_engine(cfg)
    mass = engine.anvil.unit.anvil.total_mass
    # the FE mass of anvilwave/examples/anvils/xl8.toml (its modal data, computed elsewhere)
    assert mass == pytest.approx(325334.5387463, rel=1e-12)
    assert engine.blow(duration=0.002, record=False).max_pile_head_force > 0.0


def test_solid_mass_is_the_fe_total_mass():
    spec = disc(outline=np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 2.0], [0.0, 2.0]]))
    model = cylinder_model(2.0, 1.0, size=0.1)
    assert solid_mass(spec) == pytest.approx(model.total_mass(), rel=1e-12)
    assert solid_mass(spec) == pytest.approx(7850.0 * np.pi * 0.25 * 2.0, rel=1e-14)


def test_cache_is_used_by_the_engine_in_a_new_process(tmp_path, modal_cache):
    """`anvilwave impact` in a new process reads the anvil's and the modal ram's modes from
    the cache: a copy of the session's filled cache is not rewritten."""
    import shutil
    import subprocess
    import sys

    args = [sys.executable, "-m", "anvilwave", "impact", str(EXAMPLES / "table1.toml")]
    env = dict(os.environ, ANVILWAVE_CACHE_DIR=str(modal_cache))
    subprocess.run(args + ["--out", str(tmp_path / "a")], env=env, check=True,
                   capture_output=True)  # fills the session's cache if it was not yet
    mine = tmp_path / "cache"
    shutil.copytree(modal_cache, mine, ignore=shutil.ignore_patterns("*.part"))
    entries = {p.name: p.stat().st_mtime_ns for p in mine.iterdir()}
    assert len(entries) >= 2  # anvil modes, ram modes (and other tests' entries)
    env["ANVILWAVE_CACHE_DIR"] = str(mine)
    subprocess.run(args + ["--out", str(tmp_path / "b")], env=env, check=True,
                   capture_output=True)
    assert {p.name: p.stat().st_mtime_ns for p in mine.iterdir()} == entries
