"""Reference FEA speed on the Table 1 case, and FEA time / ROM time measured in one run.

Run: python benchmarks/bench_fea.py
Prints the FEA's DOF, steps, time step and wall time of the stepping (target: at most 2
minutes here; the paper: commercial FEA over 10 minutes per impact), the same blow with the
ROM (in-process engine and FMUs) and the ratios.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from anvilwave.analyses.compare import fea_config, without_soil
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.engine.fmi import run_fmi
from anvilwave.fea.impact import run_impact_fea

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    cfg = without_soil(load_system(ROOT / "anvilwave" / "examples" / "table1.toml"))
    fea = run_impact_fea(fea_config(cfg))
    engine = build_engine(cfg)
    direct = min(engine.run()[0].wall_time for _ in range(3))
    with tempfile.TemporaryDirectory() as tmp:
        fmi = min(run_fmi(cfg, tmp)[0].wall_time for _ in range(2))
    print(f"FEA      {fea.n_dof} DOF, {fea.n_steps} steps of {fea.time_step * 1e6:.2f} us: "
          f"{fea.wall_time:.1f} s stepping (+{fea.setup_time:.1f} s set-up); target <= 120 s: "
          f"{'met' if fea.wall_time <= 120 else 'MISSED'}")
    print(f"ROM      direct {direct * 1e3:.2f} ms, FMI {fmi * 1e3:.1f} ms for "
          f"{cfg.duration * 1e3:.0f} ms simulated ({engine.time_step * 1e6:.1f} us steps)")
    print(f"ratios   FEA / ROM direct = {fea.wall_time / direct:.0f}, FEA / ROM FMI = "
          f"{fea.wall_time / fmi:.0f}; FEA = {fea.wall_time / cfg.duration:.0f}x real time")


if __name__ == "__main__":
    main()
