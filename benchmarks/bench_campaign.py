"""Campaign speed-up: 2 workers against 1 on anvilwave/examples/campaign_small.toml, measured in
one run,
the memory of each worker, and what a wind-farm campaign costs from the measured seconds per
case.

Run: python benchmarks/bench_campaign.py [--campaign FILE] [--workers 2] [--repeat 1]

Each run is a whole ``run_campaign`` (as ``anvilwave batch`` does it) into an empty folder: a
LocalCluster of worker processes started, the cases run, campaign.csv and the plots written.
The modal data (anvil and ram modes) and the compiled kernels are on disk first (one case is
run in this process before timing), as on every run after the first on a machine. The runs
alternate (1 worker, then N workers, ``--repeat`` times) and the shortest of each is used.
The speed-up is the 1-worker wall time over the N-worker one (target: at least 1.6 with 2
workers on this 2-core machine). Other processes using the cores lower it: then a case takes
longer in each of the N workers than alone, and the benchmark says so (each run prints the
mean time of a case in its worker and the load average). Memory: the peak
resident set size of each worker process (its cases' summaries record it) and of this driver
process (which also hosts the scheduler).

The projection for a 100-position x 3-bound x 2-hammer x 2-anvil campaign (1200 cases of the
same kind, an 8 m monopile to 36-40 m at 0.25 m steps with 5 blows per depth) uses the
measured seconds per case: on this machine with N workers at the measured speed-up, and on a
64-core cluster (64 single-threaded workers, the cases in ceil(1200 / 64) rounds at the
1-worker seconds per case, plus the measured serial part: campaign checks and plots).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import shutil
import statistics
import tempfile
from pathlib import Path

from anvilwave.analyses.batch import load_campaign, run_campaign, run_case

ROOT = Path(__file__).resolve().parents[1]
FARM_CASES = 100 * 3 * 2 * 2
CLUSTER_CORES = 64


def warm_up(campaign_path: Path, scratch: Path) -> None:
    """One case in this process: modal data and compiled kernels on disk before timing."""
    campaign = load_campaign(campaign_path)
    seen = set()
    for case in campaign.cases:
        if case.axes["anvil_model"] in seen:
            continue
        seen.add(case.axes["anvil_model"])
        folder = scratch / "warm-up" / case.name
        run_case({"name": case.name, "dir": str(folder), "axes": case.axes,
                  "system_text": case.system_text, "input_sha256": case.input_sha256,
                  "plots": True})


def measure(campaign_path: Path, scratch: Path, workers: int, k: int) -> dict:
    out = scratch / f"w{workers}-{k}"
    load = os.getloadavg()[0]
    result = run_campaign(campaign_path, out, workers=workers, progress=False)
    load = max(load, os.getloadavg()[0])
    summaries = [json.loads(p.read_text()) for p in sorted(out.glob("cases/*/summary.json"))]
    rss: dict[int, float] = {}
    for s in summaries:
        rss[s["worker_pid"]] = max(rss.get(s["worker_pid"], 0.0), s["worker_max_rss [B]"])
    case_time = [s["wall_time [s]"] for s in summaries]
    shutil.rmtree(out, ignore_errors=True)
    return {"workers": workers, "wall [s]": result.wall_time, "ok": result.ok,
            "cases": result.cases, "case wall [s]": case_time, "rss [B]": rss,
            "load": load}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaign", type=Path, default=ROOT / "anvilwave" / "examples" /
                        "campaign_small.toml")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="bench-campaign-") as tmp:
        scratch = Path(tmp)
        warm_up(args.campaign, scratch)
        runs = {1: [], args.workers: []}
        for k in range(args.repeat):
            for w in (1, args.workers):
                runs[w].append(measure(args.campaign, scratch, w, k))
                r = runs[w][-1]
                print(f"  {w} worker(s): {r['wall [s]']:6.1f} s, {r['ok']}/{r['cases']} ok, "
                      f"a case {statistics.mean(r['case wall [s]']):.2f} s in its worker, "
                      f"load average up to {r['load']:.1f}")
    one = min(runs[1], key=lambda r: r["wall [s]"])
    many = min(runs[args.workers], key=lambda r: r["wall [s]"])
    n = one["cases"]
    speed_up = one["wall [s]"] / many["wall [s]"]
    per_case = statistics.mean(one["case wall [s]"])
    serial = max(one["wall [s]"] - sum(one["case wall [s]"]), 0.0)
    print(f"\ncampaign {args.campaign.name}: {n} cases")
    print(f"1 worker : {one['wall [s]']:7.1f} s  ({one['wall [s]'] / n:.2f} s per case end to "
          f"end; a case in its worker {per_case:.2f} s mean, "
          f"{min(one['case wall [s]']):.2f}-{max(one['case wall [s]']):.2f} s)")
    print(f"{args.workers} workers: {many['wall [s]']:7.1f} s  (a case in its worker "
          f"{statistics.mean(many['case wall [s]']):.2f} s mean)")
    print(f"speed-up {args.workers} workers / 1: {speed_up:.2f}  (parallel efficiency "
          f"{speed_up / args.workers:.0%}; target >= 1.6 for 2 workers)")
    print(f"serial part (campaign checks, cluster start, campaign.csv, plots): {serial:.1f} s")
    slowdown = statistics.mean(many["case wall [s]"]) / per_case
    if slowdown > 1.2:
        print(f"NOTE: a case took {slowdown:.2f} times longer with {args.workers} workers than "
              f"alone: the workers did not get {args.workers} cores (other processes used "
              f"them: load average up to {many['load']:.1f} on {os.cpu_count()} cores); "
              "the speed-up above is the machine's, not the campaign's")
    for label, r in (("1 worker", one), (f"{args.workers} workers", many)):
        mib = ", ".join(f"{v / 2**20:.0f}" for v in r["rss [B]"].values())
        print(f"peak memory per worker ({label}): {mib} MiB")
    driver = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory of the driver (and scheduler) process: {driver:.0f} MiB")

    here = FARM_CASES * one["wall [s]"] / n / speed_up
    rounds = math.ceil(FARM_CASES / CLUSTER_CORES)
    cluster = rounds * per_case + serial
    print(f"\n{FARM_CASES} cases (100 positions x 3 bounds x 2 hammers x 2 anvils):")
    print(f"  this machine, {args.workers} workers: {FARM_CASES} x {one['wall [s]'] / n:.2f} s "
          f"/ {speed_up:.2f} = {here / 3600:.2f} h")
    print(f"  {CLUSTER_CORES}-core cluster: {rounds} rounds x {per_case:.2f} s + {serial:.0f} s "
          f"= {cluster / 60:.1f} min (plus the batch jobs' queueing and start); "
          f"{FARM_CASES * per_case / 3600:.2f} core-hours")


if __name__ == "__main__":
    main()
