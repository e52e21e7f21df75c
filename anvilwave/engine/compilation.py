"""Compilation of the numba kernels as its own, announced step.

The time stepping is numba code cached on disk (``cache=True``): the first run after an install
compiles it (tens of seconds), every later run loads it. Without a word the first run would look
like a hung progress bar; :func:`announce_compilation` prints ``compiling kernels ...`` before
the step that compiles, and only when a kernel has no cache yet.
"""

from __future__ import annotations

import os
import sys

_announced = False


def _main_kernels():
    """The numba dispatchers of the three stepping loops (those that take long to compile)."""
    import importlib

    found = []
    for module, names in (("anvilwave.engine.direct", ("run_blow",)),
                          ("anvilwave.fea.solver", ("_advance",)),
                          ("anvilwave.fmu.fmi_master", ("_master_loop",))):
        mod = importlib.import_module(module)
        found += [getattr(mod, n) for n in names if hasattr(getattr(mod, n, None), "_cache")]
    return tuple(found)


def uncached(dispatchers=None) -> list[str]:
    """Names of the numba kernels that will be compiled on their first call.

    Those with no on-disk cache index yet.

    Parameters
    ----------
    dispatchers : iterable of numba dispatchers, optional
        The kernels (default: the engine's, the FEA's and the FMI master's loop).

    Returns
    -------
    list of str
        The kernels' names.
    """
    missing = []
    for fn in dispatchers if dispatchers is not None else _main_kernels():
        cache = getattr(fn, "_cache", None)
        index = getattr(getattr(cache, "_cache_file", None), "_index_path", None)
        if index is None or not os.path.exists(index):
            missing.append(getattr(fn, "__name__", str(fn)))
    return missing


def announce_compilation(dispatchers=None, stream=None) -> bool:
    """Print ``compiling kernels ...`` once per process if a kernel will be compiled.

    Parameters
    ----------
    dispatchers : iterable of numba dispatchers, optional
        The kernels (default: as :func:`uncached`).
    stream : file-like, optional
        Where to print (default: ``sys.stderr``).

    Returns
    -------
    bool
        Whether it printed.
    """
    global _announced
    if _announced or not uncached(dispatchers):
        return False
    _announced = True
    print("    compiling kernels ... (first run after an install: about a minute; numba caches "
          "them for every later run)", file=stream or sys.stderr, flush=True)
    return True
