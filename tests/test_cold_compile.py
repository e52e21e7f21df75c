"""The compiled blow loop on an empty numba cache (a clean clone, a fresh install).

The loop (:func:`anvilwave.engine.direct._blow`) runs without numba's reference counting, and
the functions it calls that numba compiles while compiling it inherit that setting: on an empty
cache, a callee that allocates an array fails to type ("Only accept returning of array passed
into the function as argument"), while on a warm cache the callee is loaded as it was compiled
before and the failure stays hidden. So the loop is compiled here in a subprocess with an empty
``NUMBA_CACHE_DIR``, for the pile port in rings with the energy bookkeeping: the variant whose
callees are the most (the ring contact problem, its energy, the ram face and tube head kernels,
which take the same argument types for one ram port or annuli, 1D or tube head). Its blow must
be this process's blow (compiled or loaded here) to the bit.
"""

from __future__ import annotations

import dataclasses
import dis
import hashlib
import json
import os
import subprocess
import sys
import types

import numpy as np
import pytest
from numba.core.registry import CPUDispatcher

import anvilwave.engine.direct as engine_direct
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine

from .conftest import EXAMPLES, ROOT

DURATION = 0.004  # [s] 160 steps of Table 1: the impact (the contact problem active)
CHILD = ("import json; from tests.test_cold_compile import ring_blow_digests; "
         "print(json.dumps(ring_blow_digests()))")


def ring_blow_digests() -> dict[str, str]:
    """SHA-256 of each recorded series of Table 1's blow (DURATION) with the pile port in three
    rings, the energy bookkeeping on."""
    cfg = load_system(EXAMPLES / "table1.toml")
    spec = cfg.anvil.spec
    cfg = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=3))))
    result = build_engine(cfg).blow(duration=DURATION, record=True, energy=True)
    assert np.max(result.columns["anvil_pile_force [N]"]) > 0.0  # the rings carried the blow
    return {k: hashlib.sha256(np.ascontiguousarray(v).tobytes()).hexdigest()
            for k, v in (result.columns | result.energies).items()}


@pytest.mark.slow  # the child compiles the loop cold: 65 s at a load average of 6 on 2 cores
def test_ring_loop_compiles_on_an_empty_numba_cache_and_blows_the_same(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    child = subprocess.run([sys.executable, "-c", CHILD], cwd=ROOT, env=env,
                           capture_output=True, text=True, timeout=900, check=False)
    assert child.returncode == 0, child.stderr[-4000:]
    assert any((tmp_path / "numba").rglob("*.nbi")), "the subprocess did not use the empty cache"
    cold = json.loads(child.stdout.strip().splitlines()[-1])
    assert cold == ring_blow_digests()


ALLOCATING = {"zeros", "empty", "ones", "full", "array", "copy", "zeros_like", "empty_like",
              "ones_like", "full_like", "arange", "linspace", "concatenate", "stack", "hstack",
              "vstack", "dot", "outer", "astype", "flatten"}
"""Names whose call makes a new array (numpy's constructors, ``.copy()``, ``.astype()``)."""


def loop_functions(root) -> dict[str, CPUDispatcher]:
    """Every compiled function ``root`` reaches through the globals its code loads (a module's
    attribute too), inlined or not, by qualified name."""
    found: dict[str, CPUDispatcher] = {}
    stack = [root]
    while stack:
        function = stack.pop()
        name = f"{function.py_func.__module__}.{function.py_func.__qualname__}"
        if name in found:
            continue
        found[name] = function
        space = function.py_func.__globals__
        loaded = None
        for instruction in dis.get_instructions(function.py_func):
            value = None
            if instruction.opname == "LOAD_GLOBAL":
                value = space.get(instruction.argval)
            elif instruction.opname in ("LOAD_ATTR", "LOAD_METHOD") and loaded is not None:
                value = getattr(loaded, instruction.argval, None)
            loaded = value if isinstance(value, types.ModuleType) else None
            if isinstance(value, CPUDispatcher):
                stack.append(value)
    return found


def allocations(function: CPUDispatcher) -> list[str]:
    """The calls of ALLOCATING names in ``function``'s own code, as 'line: name'."""
    return [f"{instruction.positions.lineno}: {instruction.argval}"
            for instruction in dis.get_instructions(function.py_func)
            if instruction.opname in ("LOAD_ATTR", "LOAD_METHOD")
            and instruction.argval in ALLOCATING]


def test_nothing_the_loop_calls_allocates_an_array():
    """The cheap check of every variant of the loop (the subprocess above compiles one): the
    code of each function the loop reaches calls no array constructor. It reads names, not
    types (an array expression such as a + b is not seen); a name found here fails to compile
    on an empty cache."""
    reached = loop_functions(engine_direct._blow)
    assert {"anvilwave.anvil_rom.rings.ring_unit_energy_at",
            "anvilwave.anvil_rom.unit.modal_unit_energy_at",
            "anvilwave.hammer.driving_system.driving_system_step",
            "anvilwave.pile.kernels.pile_advance"} <= set(reached)
    found = {name: lines for name, function in reached.items()
             if (lines := allocations(function))}
    assert found == {}
