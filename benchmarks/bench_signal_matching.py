"""Signal matching: accuracy and wall time of the issue's recovery case over noise seeds, and
of the synthetic XL record matched from half its SRD, measured in one run.

Run: python benchmarks/bench_signal_matching.py [--seeds N]

1. Recovery (tests/test_signal_matching.py): a 2 m x 40 m pile simulated on 0.25 m segments,
   2 % noise (one record per seed), matched on 0.4 m from half the true SRD, imposing the
   velocity and the wave down; per seed the errors of Rut, shaft and toe and the time.
2. anvilwave/examples/pda_record_synthetic.csv (the ROM of anvilwave/examples/table1.toml, 78 m
   below the gauges)
   matched with table1's pile from half its SRD (the true soil is table1's).
Kernels are compiled (or loaded) before the timings.
"""

from __future__ import annotations

import argparse
import re
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import anvilwave  # noqa: E402
from anvilwave.analyses.match import MatchSettings, match_record  # noqa: E402
from anvilwave.pile.pda.records import check_gauge_record  # noqa: E402
from anvilwave.pile.soil.models import soil_capacities  # noqa: E402
from tests.test_signal_matching import write_system  # noqa: E402


def truth(cfg) -> np.ndarray:
    shaft, toe = soil_capacities(cfg.pile_soil.soil, cfg.pile_soil.pile)
    return np.array([shaft.sum() + toe, shaft.sum(), toe])


def fitted(result) -> np.ndarray:
    return np.array([result.soil.rut, result.soil.rut_shaft, result.soil.toe_resistance])


def recovery(seeds: int) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        true_cfg = anvilwave.load_system(write_system(folder, 0.25, 1.0))
        guess = anvilwave.load_system(write_system(folder, 0.4, 0.5))
    blow = anvilwave.simulate(true_cfg)[0]
    t = blow["time [s]"] - blow["time [s]"][0]
    f0 = blow["gauge_force [N]"] - blow["gauge_force [N]"][0]
    v0 = blow["gauge_velocity [m/s]"]
    exact = truth(true_cfg)
    print(f"recovery case: Rut {exact[0] / 1e6:.3f} MN (shaft {exact[1] / 1e6:.3f}, toe "
          f"{exact[2] / 1e6:.3f}); set {blow.summary['permanent_set [m]'] * 1e3:.2f} mm")
    for imposed in ("velocity", "wave_down"):
        errors, times = [], []
        for seed in range(1, seeds + 1):
            rng = np.random.default_rng(seed)
            f = f0 + 0.02 * np.abs(f0).max() * rng.standard_normal(f0.size)
            v = v0 + 0.02 * np.abs(v0).max() * rng.standard_normal(v0.size)
            start = time.perf_counter()
            result = match_record(check_gauge_record(t, f, v), guess,
                                  MatchSettings(imposed=imposed))
            times.append(time.perf_counter() - start)
            errors.append(fitted(result) / exact - 1.0)
        errors = np.array(errors)
        worst = np.abs(errors).max(axis=0)
        print(f"  imposed {imposed:9s}: {seeds} seeds, largest error Rut {worst[0]:.2%}, shaft "
              f"{worst[1]:.2%}, toe {worst[2]:.2%}; mean toe error {errors[:, 2].mean():+.2%}; "
              f"{np.mean(times):.2f} s per match (max {np.max(times):.2f} s)")


def synthetic_xl() -> None:
    from anvilwave.analyses.pda import load_record

    system = ROOT / "anvilwave" / "examples" / "table1.toml"
    text = system.read_text()
    xl8 = (ROOT / "anvilwave/examples/anvils/xl8.toml").as_posix()
    text = text.replace('"anvils/xl8.toml"', f'"{xl8}"')
    half = [[d, s / 2, q / 2] for d, s, q in tomllib.loads(text)["soil"]["srd"]]
    text = re.sub(r"^srd = .*$", f"srd = {half}", text, flags=re.M)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "table1_half_srd.toml"
        path.write_text(text)
        guess = anvilwave.load_system(path)
    exact = truth(anvilwave.load_system(system))
    record, _, _ = load_record(ROOT / "anvilwave" / "examples" / "pda_record_synthetic.csv")
    start = time.perf_counter()
    result = match_record(record, guess)
    wall = time.perf_counter() - start
    e = fitted(result) / exact - 1.0
    print(f"synthetic XL record from half its SRD: Rut {result.soil.rut / 1e6:.2f} MN "
          f"({e[0]:+.2%}), shaft {e[1]:+.2%}, toe {e[2]:+.2%}, MQ {result.match_quality:.3f} "
          f"(start {result.start_match_quality:.3f}), {result.info['evaluations']} runs, "
          f"{wall:.2f} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    args = parser.parse_args()
    recovery(args.seeds)
    synthetic_xl()


if __name__ == "__main__":
    main()
