"""FMI engine vs in-process engine: wall time per 25 ms Table 1 blow, as multiples of real time.

Run: python benchmarks/bench_fmi.py [SYSTEM.toml] [--repeat N]

Builds the system's FMUs once (not timed), then in ONE process times, for the ROM and the
lumped anvil,

- ``direct``: :meth:`anvilwave.engine.Engine.run` (one jitted loop per blow);
- ``fmi``: :func:`anvilwave.fmi_engine.run_fmi`, the Ram, Anvil and PileSoil FMUs (pythonfmu) under
  the fmpy master with its numba-compiled DESIGN.md loop;
- ``fmi-py``: the same master with the loop interpreted by Python (for reference).

Each time is the stepping of one blow alone (``wall_time``: no build, no compilation, no
initialisation), the best of ``--repeat`` runs, with the median in brackets (a shared 2-core
machine is noisy). "x real time" is wall time / simulated time: below 1 is faster than real
time. The ratio fmi / direct is the price of the FMI interfaces.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _best(times: list[float]) -> tuple[float, float]:
    return min(times), statistics.median(times)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("system", nargs="?", type=Path, default=ROOT / "examples" / "table1.toml")
    parser.add_argument("--repeat", type=int, default=5, help="runs per engine (default 5)")
    args = parser.parse_args(argv)

    from anvilwave.engine import build_engine
    from anvilwave.fmi_engine import run_fmi
    from anvilwave.fmus import build_system_fmus, load_anvil_modal_data
    from anvilwave.system import load_system
    from fmu.fmi_master import BlowMaster

    cfg = load_system(args.system)
    cfg = dataclasses.replace(cfg, blows=1)
    start = time.perf_counter()
    modal = load_anvil_modal_data(cfg)
    with tempfile.TemporaryDirectory(prefix="bench_fmi_") as tmp:
        fmus = build_system_fmus(cfg, tmp, modal)
        print(f"system {args.system.name}: anvil modes and the four FMUs built in "
              f"{time.perf_counter() - start:.1f} s (not timed below)")
        print(f"{'anvil':7s} {'engine':7s} {'h [us]':>7s} {'steps':>6s} {'blow [ms]':>16s} "
              f"{'us/step':>8s} {'x real time':>12s}")
        for model in ("rom", "lumped"):
            c = cfg.with_anvil_model(model)
            engine = build_engine(c, modal)
            engine.run()  # compile / load the cached loop
            direct = [engine.run()[0].wall_time for _ in range(args.repeat)]
            fmi = [run_fmi(c, tmp, fmus=fmus)[0].wall_time for _ in range(args.repeat + 1)][1:]
            h = engine.time_step
            n = int(round(c.duration / h))
            kind = fmus["anvil"] if model == cfg.anvil.model else \
                {"rom": "Anvil", "lumped": "AnvilLumped"}[model]
            with BlowMaster(fmus["Ram"], fmus[kind], fmus["PileSoil"], compiled=False) as m:
                interpreted = [m.run_blows(1, n, h)[0].wall_time for _ in range(args.repeat)]
            simulated = n * h
            rows = {"direct": _best(direct), "fmi": _best(fmi), "fmi-py": _best(interpreted)}
            for name, (best, median) in rows.items():
                print(f"{model:7s} {name:7s} {1e6 * h:7.2f} {n:6d} "
                      f"{1e3 * best:7.2f} ({1e3 * median:6.2f}) {1e6 * best / n:8.2f} "
                      f"{best / simulated:12.4f}")
            print(f"{model:7s} ratio fmi / direct = {rows['fmi'][0] / rows['direct'][0]:.1f} "
                  f"(fmi-py / direct = {rows['fmi-py'][0] / rows['direct'][0]:.1f}); "
                  f"real-time multiples: direct {rows['direct'][0] / simulated:.4f}, "
                  f"fmi {rows['fmi'][0] / simulated:.4f}")


if __name__ == "__main__":
    sys.exit(main())
