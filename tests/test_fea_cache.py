"""The reference FEA's cache (anvilwave/fea/cache.py): a hit gives the computed result to the
bit without running the FEA, the key follows every field the FEA reads and ignores what it does
not (the anvil's ROM interfaces), and a damaged entry is a miss."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import anvilwave.fea.cache as fea_cache
from anvilwave.anvil_rom.fem.geometry import Interfaces
from anvilwave.config.cache import FEA_SUFFIX, cache_info, clear_cache

from .test_fea import _table1


@pytest.fixture()
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ANVILWAVE_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache"


def _small(**overrides):
    # the smoke test's coarse stack, 1 ms: a few seconds
    return _table1(mesh_size=0.25, pile_wall_elements=2, truncate_length=4.0, duration=1e-3,
                   output_interval=1e-5, **overrides)


def _fields(result) -> dict:
    return {f.name: getattr(result, f.name) for f in dataclasses.fields(result)}


def test_a_hit_is_the_computed_result_and_runs_no_fea(private_cache, monkeypatch):
    config = _small()
    computed = fea_cache.cached_impact_fea(config)
    entries = list(private_cache.glob("*" + FEA_SUFFIX))
    assert len(entries) == 1

    def no_fea(*args, **kwargs):
        raise AssertionError("the FEA ran on a cache hit")

    monkeypatch.setattr(fea_cache, "run_impact_fea", no_fea)
    fractions = []
    read = fea_cache.cached_impact_fea(config, progress=fractions.append)
    assert fractions == [1.0]
    a, b = _fields(computed), _fields(read)
    for name in fea_cache.ARRAYS + fea_cache.SCALARS:
        assert np.array_equal(a[name], b[name]), name
    assert a["energies"].keys() == b["energies"].keys()
    assert all(np.array_equal(a["energies"][k], b["energies"][k]) for k in a["energies"])
    assert read.anvil_ring_force is None and read.sleeve_force is None
    assert {k: list(v) if isinstance(v, tuple) else v for k, v in a["info"].items()} == b["info"]
    row, = cache_info()["files"]
    assert row["fea_output_samples"] == computed.time.size
    assert clear_cache()[0] == 1 and not list(private_cache.glob("*" + FEA_SUFFIX))


def test_the_key_follows_what_the_fea_reads():
    config = _small()
    key = fea_cache.fea_key(config)
    # the ROM's interfaces of the anvil are not read by the FEA (its faces come from the ram
    # radius and the pile section)
    other_ports = dataclasses.replace(config, anvil=dataclasses.replace(
        config.anvil, interfaces=Interfaces(0.5, 3.9, 0.14), name="renamed"))
    assert fea_cache.fea_key(other_ports) == key
    for change in ({"impact_velocity": 6.0}, {"mesh_size": 0.2}, {"ram_anvil_friction": 0.2},
                   {"duration": 2e-3}):
        assert fea_cache.fea_key(dataclasses.replace(config, **change)) != key, change
    thicker = np.array(config.anvil.outline, float)
    thicker[thicker[:, 1] == thicker[:, 1].max(), 1] += 0.01
    assert fea_cache.fea_key(dataclasses.replace(
        config, anvil=dataclasses.replace(config.anvil, outline=thicker))) != key


def test_a_damaged_entry_is_a_miss_and_is_replaced(private_cache):
    config = _small()
    fea_cache.cached_impact_fea(config)
    entry, = private_cache.glob("*" + FEA_SUFFIX)
    entry.write_bytes(entry.read_bytes()[:100])
    result = fea_cache.cached_impact_fea(config)
    assert np.isfinite(result.anvil_pile_force).all() and result.anvil_pile_force.max() > 0.0
    assert fea_cache._read(entry).n_steps == result.n_steps
