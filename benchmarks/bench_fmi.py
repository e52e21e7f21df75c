"""FMI engine vs in-process engine: wall time per 25 ms Table 1 blow, as multiples of real time.

Run: python benchmarks/bench_fmi.py [SYSTEM.toml] [--repeat N]

Builds the system's FMUs once (not timed): the native anvils (C, ``build_system_fmus``'s
default) and the pythonfmu anvils (``native_anvil=False``), with the same pythonfmu Ram and
PileSoil. Then in ONE process times, for the ROM and the lumped anvil,

- ``direct``: :meth:`anvilwave.engine.direct.Engine.run` (one jitted loop per blow);
- ``fmi``: :func:`anvilwave.engine.fmi.run_fmi`, Ram, the native Anvil and PileSoil under the
  fmpy master with its numba-compiled DESIGN.md loop;
- ``fmi-pyanvil``: the same with the pythonfmu anvil (the FMI engine before the native anvil);
- ``fmi-jacobi``: the native-anvil chain under the same loop in the Jacobi exchange order.

Each time is the stepping of one blow alone (``wall_time``: no build, no compilation, no
initialisation), the best of ``--repeat`` runs, with the median in brackets (a shared 2-core
machine is noisy); "us/step" is per 3-unit communication step. "x real time" is wall time /
simulated time: below 1 is faster than real time. The ratios: fmi-pyanvil / fmi is the native
anvil's gain, fmi / direct the price of the FMI interfaces.
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
EXAMPLES = ROOT / "anvilwave" / "examples"


def _best(times: list[float]) -> tuple[float, float]:
    return min(times), statistics.median(times)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("system", nargs="?", type=Path, default=EXAMPLES / "table1.toml")
    parser.add_argument("--repeat", type=int, default=5, help="runs per engine (default 5)")
    args = parser.parse_args(argv)

    from anvilwave.config.system import load_system
    from anvilwave.engine.direct import build_engine
    from anvilwave.engine.fmi import run_fmi
    from anvilwave.engine.fmus import build_system_fmus, load_anvil_modal_data
    from anvilwave.fmu.fmi_master import BlowMaster

    cfg = load_system(args.system)
    cfg = dataclasses.replace(cfg, blows=1)
    start = time.perf_counter()
    modal = load_anvil_modal_data(cfg)
    with tempfile.TemporaryDirectory(prefix="bench_fmi_") as tmp:
        fmus = build_system_fmus(cfg, tmp, modal)
        python = build_system_fmus(cfg, Path(tmp) / "python_anvil", modal, ssp=False,
                                   native_anvil=False)
        pyanvil = {**fmus, "Anvil": python["Anvil"], "AnvilLumped": python["AnvilLumped"]}
        print(f"system {args.system.name}: anvil modes and the FMUs (native and pythonfmu "
              f"anvils) built in {time.perf_counter() - start:.1f} s (not timed below)")
        print(f"{'anvil':7s} {'engine':11s} {'h [us]':>7s} {'steps':>6s} {'blow [ms]':>16s} "
              f"{'us/step':>8s} {'x real time':>12s}")
        for model in ("rom", "lumped"):
            c = cfg.with_anvil_model(model)
            engine = build_engine(c, modal)
            engine.run()  # compile / load the cached loop
            direct = [engine.run()[0].wall_time for _ in range(args.repeat)]
            fmi = [run_fmi(c, tmp, fmus=fmus)[0].wall_time for _ in range(args.repeat + 1)][1:]
            fmi_pyanvil = [run_fmi(c, tmp, fmus=pyanvil)[0].wall_time
                           for _ in range(args.repeat + 1)][1:]
            h = engine.time_step
            n = int(round(c.duration / h))
            kind = fmus["anvil"] if model == cfg.anvil.model else \
                {"rom": "Anvil", "lumped": "AnvilLumped"}[model]
            with BlowMaster(fmus["Ram"], fmus[kind], fmus["PileSoil"],
                            exchange="jacobi") as m:
                jacobi = [m.run_blows(1, n, h)[0].wall_time for _ in range(args.repeat)]
            simulated = n * h
            rows = {"direct": _best(direct), "fmi": _best(fmi),
                    "fmi-pyanvil": _best(fmi_pyanvil), "fmi-jacobi": _best(jacobi)}
            for name, (best, median) in rows.items():
                print(f"{model:7s} {name:11s} {1e6 * h:7.2f} {n:6d} "
                      f"{1e3 * best:7.2f} ({1e3 * median:6.2f}) {1e6 * best / n:8.2f} "
                      f"{best / simulated:12.4f}")
            print(f"{model:7s} native anvil: {1e6 * rows['fmi'][0] / n:.2f} us/step against "
                  f"{1e6 * rows['fmi-pyanvil'][0] / n:.2f} us/step with the pythonfmu anvil, "
                  f"ratio fmi-pyanvil / fmi = {rows['fmi-pyanvil'][0] / rows['fmi'][0]:.2f}; "
                  f"fmi / direct = {rows['fmi'][0] / rows['direct'][0]:.1f}")


if __name__ == "__main__":
    sys.exit(main())
