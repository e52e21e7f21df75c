"""The compiled blow loop on an empty numba cache (a clean clone, a fresh install).

The loop (:func:`anvilwave.engine.direct._blow`) runs without numba's reference counting, and
the functions it calls that numba compiles while compiling it inherit that setting: on an empty
cache, a callee that allocates an array fails to type ("Only accept returning of array passed
into the function as argument"), while on a warm cache the callee is loaded as it was compiled
before and the failure stays hidden. The test below reads the code of every function the loop
reaches for array constructors, so a developer's warm cache does not hide one. The typing
itself on an empty cache is what every clean clone does (CI runs the suite in one, its numba
caches empty): the ring, annuli, tube-head and engine tests compile the loop cold there.
"""

from __future__ import annotations

import dis
import types

from numba.core.registry import CPUDispatcher

import anvilwave.engine.direct as engine_direct

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
    """Every variant of the loop: the code of each function the loop reaches calls no array
    constructor. It reads names, not
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
