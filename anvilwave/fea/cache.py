"""The reference FEA's results kept in the cache directory: one FEA per configuration and code.

A reference FEA of Table 1 takes a minute or more; ``compare``, the tests and the studies run
the same one again and again (the anvil's ROM settings, its interfaces and ports, do not enter
the FEA). :func:`cached_impact_fea` keeps each result in the modal-data cache directory
(:func:`anvilwave.config.cache.cache_dir`, ``anvilwave cache info`` and ``clear`` list and
remove it), keyed by :func:`fea_key`: every field of the :class:`~anvilwave.fea.impact.FeaConfig`
(an anvil by its geometry hash: outline or mesh file, material), the source of
:mod:`anvilwave.fea` and the modal analysis's code version (meshing and elasticity). The
result read back equals the computed one to the bit, the wall times included (they are the
FEA's own cost, not the read's).
"""

from __future__ import annotations

import dataclasses
import hashlib
import io
import json
from pathlib import Path

import numpy as np

from anvilwave.anvil_rom.fem.geometry import AnvilSpec
from anvilwave.config.cache import FEA_SUFFIX, cache_dir, cached_entry, code_version, write_atomic
from anvilwave.fea.impact import FeaConfig, FeaResult, run_impact_fea

ARRAYS = ("time", "ram_anvil_force", "anvil_pile_force", "pile_head_velocity", "gauge_force",
          "gauge_velocity", "ram_velocity")
"""The result's array fields, stored as they are."""
OPTIONAL_ARRAYS = ("anvil_ring_force", "sleeve_force")
"""Array fields that are None without a ring or a sleeve."""
SCALARS = ("n_dof", "n_steps", "time_step", "critical_time_step", "wall_time", "setup_time")
"""The result's scalar fields."""


def _describe(value):
    """A JSON-able description of a configuration value (an anvil by its geometry hash)."""
    if isinstance(value, AnvilSpec):
        return {"anvil": value.geometry_hash()}
    if dataclasses.is_dataclass(value):
        return {f.name: _describe(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, np.ndarray):
        return hashlib.sha256(np.ascontiguousarray(value, dtype=float).tobytes()).hexdigest()
    if isinstance(value, (list, tuple)):
        return [_describe(v) for v in value]
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def _fea_source() -> str:
    h = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def fea_key(config: FeaConfig) -> str:
    """Cache key (hex SHA-256) of the reference FEA of ``config``.

    Parameters
    ----------
    config : FeaConfig
        The FEA configuration.

    Returns
    -------
    str
        The key, 64 hex digits.
    """
    description = {"config": _describe(config), "fea source": _fea_source(),
                   "code": code_version()}
    text = json.dumps(description, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def _jsonable(value):
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not stored")


def _write(result: FeaResult, fh) -> None:
    arrays = {name: getattr(result, name) for name in ARRAYS}
    arrays.update({name: getattr(result, name) for name in OPTIONAL_ARRAYS
                   if getattr(result, name) is not None})
    arrays.update({"energy " + name: values for name, values in result.energies.items()})
    meta = {"scalars": {name: getattr(result, name) for name in SCALARS}, "info": result.info,
            "energies": list(result.energies)}
    arrays["meta"] = np.frombuffer(json.dumps(meta, default=_jsonable).encode(), np.uint8)
    np.savez(fh, **arrays)


def _read(path: Path) -> FeaResult:
    with np.load(path, allow_pickle=False) as npz:
        meta = json.loads(npz["meta"].tobytes().decode())
        fields = {name: npz[name] for name in ARRAYS}
        fields.update({name: npz[name] if name in npz.files else None
                       for name in OPTIONAL_ARRAYS})
        fields["energies"] = {name: npz["energy " + name] for name in meta["energies"]}
    return FeaResult(**fields, **meta["scalars"], info=meta["info"])


def cached_impact_fea(config: FeaConfig, progress=None) -> FeaResult:
    """:func:`~anvilwave.fea.impact.run_impact_fea` of ``config``, from the cache or computed.

    Parameters
    ----------
    config : FeaConfig
        The FEA configuration.
    progress : callable, optional
        Called with the fraction in [0, 1] while the FEA steps; with 1.0 on a cache hit.

    Returns
    -------
    FeaResult
        The result (on a hit, the one stored: its info's tuples read back as lists).
    """
    path = cache_dir() / (fea_key(config) + FEA_SUFFIX)

    def read(warn: bool):
        if not path.is_file():
            return None
        try:
            result = _read(path)
        except Exception:  # a truncated or foreign entry is a miss, replaced
            return None
        if progress is not None:
            progress(1.0)
        return result

    def store(result) -> None:
        buffer = io.BytesIO()
        try:
            _write(result, buffer)
        except TypeError:  # an info value JSON cannot hold: not cached
            return
        write_atomic(path, lambda fh: fh.write(buffer.getvalue()))

    return cached_entry(path, read, lambda: run_impact_fea(config, progress=progress), store)


__all__ = ["cached_impact_fea", "fea_key"]
