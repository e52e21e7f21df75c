"""Driveability speed: seconds per depth and per blow, measured in one run.

Run: python benchmarks/bench_drive.py [--shared ../shared] [--workers N]

Cases: ``anvilwave/examples/xl_monopile_drive.toml`` with the ROM anvil (39 depths, the modal ram)
and
``anvilwave/examples/grlweap_s4000.toml`` (50 depths; needs the GRLWEAP benchmark input under
``--shared``/reference/grlweap-s4000, skipped with a message when absent). For each: the wall
time of the whole analysis (engine built and compiled kernels loaded first, as a second run of
the command would), depths, blows, seconds per depth and per blow, the stepping's share, and
the speed-up of the parallel run over one worker on the same case.
Target (issue 16): each case within 60 s here.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

from anvilwave.analyses.drive import run_driveability
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine

ROOT = Path(__file__).resolve().parents[1]


def measure(path: Path, workers: int | None) -> dict:
    cfg = load_system(path)
    start = time.perf_counter()
    engine = build_engine(cfg)
    build = time.perf_counter() - start
    # the first blow of a process compiles (or loads) the loop: warm up before timing, as a
    # second run of the command finds it cached
    warm = replace(cfg.drive, depths=cfg.drive.depths[-1:])
    run_driveability(cfg, cfg.srd, warm, engine, workers=1)
    out = {}
    for label, w in (("1 worker", 1), ("parallel", workers)):
        result = run_driveability(cfg, cfg.srd, cfg.drive, engine, workers=w)
        out[label] = result.summary
    s = out["parallel"]
    depths = s["depths_analysed [-]"]
    blows = depths * cfg.drive.blows_per_depth
    return {"case": path.name, "build [s]": build, "wall [s]": s["wall_time [s]"],
            "depths": depths, "blows": blows,
            "s/depth": s["wall_time [s]"] / depths, "s/blow": s["wall_time [s]"] / blows,
            "workers": s["workers [-]"],
            "speed-up": out["1 worker"]["wall_time [s]"] / s["wall_time [s]"]}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--shared", type=Path, default=ROOT.parent / "shared")
    parser.add_argument("--workers", type=int, default=None)
    args = parser.parse_args()
    cases = [ROOT / "anvilwave" / "examples" / "xl_monopile_drive.toml"]
    if (args.shared / "reference" / "grlweap-s4000" / "model.json").exists():
        cases.append(ROOT / "anvilwave" / "examples" / "grlweap_s4000.toml")
    else:
        print(f"grlweap_s4000: skipped, {args.shared}/reference/grlweap-s4000/model.json "
              "not found")
    print(f"{'case':24s} {'build [s]':>9s} {'wall [s]':>8s} {'depths':>6s} {'s/depth':>8s} "
          f"{'s/blow':>7s} {'workers':>7s} {'speed-up':>8s} {'<= 60 s':>7s}")
    for path in cases:
        r = measure(path, args.workers)
        print(f"{r['case']:24s} {r['build [s]']:9.2f} {r['wall [s]']:8.2f} {r['depths']:6d} "
              f"{r['s/depth']:8.3f} {r['s/blow']:7.3f} {r['workers']:7d} {r['speed-up']:8.2f} "
              f"{'met' if r['build [s]'] + r['wall [s]'] <= 60 else 'MISSED':>7s}")


if __name__ == "__main__":
    main()
