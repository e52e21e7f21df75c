"""Modal analysis speed: `anvilwave modes anvilwave/examples/anvils/xl8.toml` at the default mesh
and fmax.

Run: python benchmarks/bench_modes.py
Prints the command's total wall time (process start to finish: imports, meshing, assembly,
Sturm count, Lanczos, flexibility, plots, files) and the solver's own wall_time from
modes.json, with n_dof and n_modes. Target: at most 30 s on a 2-core machine.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    anvil = ROOT / "anvilwave" / "examples" / "anvils" / "xl8.toml"
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "anvilwave.cli", "modes", str(anvil), "--out", tmp],
                       check=True, cwd=ROOT, stdout=subprocess.DEVNULL)
        total = time.perf_counter() - start
        summary = json.loads((Path(tmp) / "modes.json").read_text())
    print(f"anvil                 xl8 (default mesh {summary['n_dof']} DOF)")
    print(f"fmax [Hz]             {summary['fmax [Hz]']:g}")
    print(f"n_modes               {summary['n_modes']} (Sturm count {summary['sturm_count']})")
    print(f"modal analysis [s]    {summary['wall_time [s]']:.2f}")
    print(f"whole command [s]     {total:.2f}  (target <= 30 s: "
          f"{'met' if total <= 30 else 'MISSED'}, ratio target / time = {30 / total:.1f})")


if __name__ == "__main__":
    main()
