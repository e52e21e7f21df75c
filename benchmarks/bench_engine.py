"""In-process engine speed: one Table 1 blow (25 ms) with the ROM and with the lumped anvil.

Run: python benchmarks/bench_engine.py [--repeat N]
Prints, for each anvil model, the simulated time / wall time of the time stepping alone
(compilation and start-up excluded: the engine compiles or loads the loop before timing), the
master step, the number of steps and microseconds per step, all measured in this one run.
Target (issue): the ROM blow at least 10 times faster than real time. table1.toml's ram is the
modal ram; "rom+rod" is the ROM anvil with the hammer's Smith rod ram, for the cost ratio.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
from pathlib import Path

from anvil_rom.pipeline import compute_anvil_modes
from anvilwave.engine import build_engine
from anvilwave.system import load_system
from hammer.database import load_hammer

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    cfg = load_system(ROOT / "examples" / "table1.toml")
    modal = compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax).modal_data
    rows = {}
    rod = dataclasses.replace(cfg, hammer=load_hammer("illustrative_5500kj"))  # table1's, rod
    cases = {"rom": cfg, "rom+rod": rod, "lumped": cfg.with_anvil_model("lumped"),
             "classic": cfg.with_anvil_model("classic")}
    for model, case in cases.items():
        engine = build_engine(case, modal=modal)
        walls = []
        for _ in range(args.repeat):
            blow = engine.run()[0]
            walls.append(blow.wall_time)
        wall = statistics.median(walls)
        rows[model] = (engine.time_step, blow.n_steps, wall)
    print(f"{'anvil':8s} {'step [us]':>9s} {'steps':>6s} {'wall [ms]':>9s} {'us/step':>8s} "
          f"{'real time x':>11s}")
    for model, (h, n, wall) in rows.items():
        print(f"{model:8s} {h * 1e6:9.2f} {n:6d} {wall * 1e3:9.3f} {wall / n * 1e6:8.2f} "
              f"{cfg.duration / wall:11.1f}")
    rom = cfg.duration / rows["rom"][2]
    print(f"ROM blow: {rom:.1f}x faster than real time (target >= 10x: "
          f"{'met' if rom >= 10 else 'MISSED'}); ROM / lumped wall-time ratio "
          f"{rows['rom'][2] / rows['lumped'][2]:.2f}; modal ram / rod ram wall-time ratio "
          f"{rows['rom'][2] / rows['rom+rod'][2]:.2f}")


if __name__ == "__main__":
    main()
