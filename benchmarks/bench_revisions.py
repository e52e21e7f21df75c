"""The engine's blows of two code revisions, in one run: microseconds per step and their ratio.

Run: python benchmarks/bench_revisions.py BASE [OTHER] [--rounds R] [--repeat N] [--compile C]

BASE and OTHER are git revisions (OTHER by default the working tree this file is in, with its
uncommitted changes) or folders holding a checkout (reused with its numba cache). Each revision
is checked out with ``git worktree`` into a temporary folder (removed at the end) and runs in
subprocesses of this Python (the same environment), ``PYTHONPATH`` pointing at that checkout,
so that only the code differs. The subprocesses alternate, BASE, OTHER, BASE, OTHER, ... (R
rounds), and each one steps every blow kind N times, the kinds interleaved; the machine may be
shared, so a subprocess reports per kind the minimum and the median of its N blows' wall times
(the stepping only, as :meth:`anvilwave.engine.direct.Engine.blow` times it: compilation and
start-up excluded).

The blow kinds are benchmarks/bench_engine.py's: the Table 1 blow for each ram model (the modal
ram unit, its chain, the hammer's Smith rod) and anvil model (rom, lumped, classic, none), recorded
with the energy bookkeeping and as the summary only, the pile port in three rings (1D and tube
head) and anvilwave/examples/table1_interfaces.toml (three rings on the tube head and the ram
port in six annuli), and a blow of anvilwave/examples/xl_monopile_drive.toml at a tip depth of
25 m (its soil acting, summary only, as the driveability analysis runs it).

Printed per kind: each revision's microseconds per step (the minimum over all its blows, and
the median of its subprocesses' medians) and OTHER / BASE as the ratio of the minima and the
median and range of the per-round ratios of the medians. With ``--compile C`` the cold
compilation of the Table 1 blow's loop (ROM anvil, recorded, energy bookkeeping) is timed too:
C subprocesses per revision, alternated, each with an empty numba cache (``NUMBA_CACHE_DIR``),
the first blow's wall time (compiling every kernel it runs) minus a warm blow's.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import anvilwave
from anvilwave.config.cache import cached_chain
from anvilwave.config.drive import load_srd_source, pile_soil_at
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.modal_ram import modal_ram_chain

ROOT = Path(__file__).resolve().parents[1]
WORKING_TREE = "working tree"


def _kinds():
    """The blow kinds: name -> (engine, blow options)."""
    examples = Path(anvilwave.__file__).parent / "examples"
    cfg = load_system(examples / "table1.toml")
    rod = dataclasses.replace(cfg, hammer=load_hammer("illustrative_5500kj"))
    chain = dataclasses.replace(cfg, hammer=dataclasses.replace(
        cfg.hammer, ram=modal_ram_chain(cfg.hammer.ram, cfg.hammer.ram.modes, cached_chain)))
    kinds = {}
    modal = None
    for ram, base in (("unit", cfg), ("chain", chain), ("rod", rod)):
        for anvil in ("rom", "lumped", "classic", "none"):
            engine = build_engine(base.with_anvil_model(anvil), modal)
            modal = engine.modal if modal is None else modal
            kinds[f"{ram} {anvil}"] = (engine, {})
            kinds[f"{ram} {anvil} summary"] = (engine, {"record": False})
    spec = cfg.anvil.spec
    ringed = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=3))))
    kinds["3 rings"] = (build_engine(ringed), {})
    tube = dataclasses.replace(ringed, anvil=dataclasses.replace(ringed.anvil, pile_head="tube"))
    kinds["3 rings, tube head"] = (build_engine(tube), {})
    kinds["table1_interfaces"] = (build_engine(load_system(examples /
                                                           "table1_interfaces.toml")), {})
    xl = load_system(examples / "xl_monopile_drive.toml")
    srd = xl.srd if xl.srd is not None else load_srd_source(None, xl.source, xl.pile_soil)
    pile_soil, _, _ = pile_soil_at(xl.pile_soil, srd, 25.0, 1.0)
    kinds["xl drive 25 m summary"] = (build_engine(xl).with_pile_soil(pile_soil),
                                      {"record": False})
    return kinds


def child_blows(repeat: int) -> dict:
    """Per kind (steps, minimum and median wall time of ``repeat`` blows [s])."""
    kinds = _kinds()
    walls = {name: [] for name in kinds}
    for engine, options in kinds.values():
        engine.blow(**options)  # compile or load the variant
    for _ in range(repeat):
        for name, (engine, options) in kinds.items():
            walls[name].append(engine.blow(**options).wall_time)
    return {name: (kinds[name][0].blow(**kinds[name][1]).n_steps, min(w), statistics.median(w))
            for name, w in walls.items()}


def child_compile() -> dict:
    """The Table 1 blow's first wall time (compiling its loop) and a warm one's [s]."""
    examples = Path(anvilwave.__file__).parent / "examples"
    engine = build_engine(load_system(examples / "table1.toml"))
    start = time.perf_counter()
    engine.blow()
    first = time.perf_counter() - start
    start = time.perf_counter()
    engine.blow()
    return {"first": first, "warm": time.perf_counter() - start}


def _start_child(checkout: Path, mode: str, repeat: int,
                 cache_dir: str | None = None) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(checkout))
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    return subprocess.Popen([sys.executable, __file__, "--child", mode, "--repeat", str(repeat)],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _run_child(checkout: Path, mode: str, repeat: int, cache_dir: str | None = None) -> dict:
    return _child_result(checkout, _start_child(checkout, mode, repeat, cache_dir))


def _child_result(checkout: Path, child: subprocess.Popen) -> dict:
    stdout, stderr = child.communicate()
    if child.returncode != 0:
        sys.exit(f"bench_revisions: the {checkout} subprocess failed:\n{stderr}")
    payload = json.loads(stdout.strip().splitlines()[-1])
    if Path(payload.pop("anvilwave")).resolve() != (checkout / "anvilwave").resolve():
        sys.exit(f"bench_revisions: the subprocess did not import anvilwave from {checkout}")
    return payload


@contextlib.contextmanager
def _checkouts(revisions: list[str]):
    """A folder per revision: a temporary git worktree, or this working tree."""
    with tempfile.TemporaryDirectory(prefix="bench_revisions_") as tmp:
        made = []
        try:
            folders = []
            for k, rev in enumerate(revisions):
                if rev == WORKING_TREE or Path(rev).is_dir():
                    folders.append(ROOT if rev == WORKING_TREE else Path(rev).resolve())
                    continue
                folder = Path(tmp) / f"rev{k}"
                subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", "-q",
                                str(folder), rev], check=True)
                made.append(folder)
                folders.append(folder)
            yield folders
        finally:
            for folder in made:
                subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                                str(folder)], check=False)


def _label(rev: str) -> str:
    if rev == WORKING_TREE:
        return rev
    folder = Path(rev).is_dir()
    sha = subprocess.run(["git", "-C", rev if folder else str(ROOT), "rev-parse", "--short",
                          "HEAD" if folder else rev],
                         capture_output=True, text=True, check=True).stdout.strip()
    return f"{rev} ({sha})" if sha != rev else rev


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("base", nargs="?", help="the reference revision (e.g. main)")
    parser.add_argument("other", nargs="?", default=WORKING_TREE,
                        help="the revision compared with it (default: this working tree)")
    parser.add_argument("--rounds", type=int, default=4,
                        help="subprocesses per revision, alternated")
    parser.add_argument("--repeat", type=int, default=15, help="blows per kind per subprocess")
    parser.add_argument("--compile", type=int, default=0,
                        help="cold compilations of the Table 1 loop per revision (0: none)")
    parser.add_argument("--child", choices=("blows", "compile"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        payload = child_blows(args.repeat) if args.child == "blows" else child_compile()
        payload["anvilwave"] = str(Path(anvilwave.__file__).parent)
        print(json.dumps(payload))
        return
    if args.base is None:
        parser.error("give the reference revision (e.g. main)")
    revisions = [args.base, args.other]
    labels = [_label(rev) for rev in revisions]
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"A = {labels[0]}, B = {labels[1]}; {args.rounds} rounds of A, B subprocesses, "
          f"{args.repeat} blows per kind in each; load average {load:.2f} on "
          f"{os.cpu_count()} cores")
    with _checkouts(revisions) as folders:
        # compile or load every kernel once, untimed (both revisions at once)
        warming = [_start_child(folder, "blows", 1) for folder in folders]
        for folder, child in zip(folders, warming, strict=True):
            _child_result(folder, child)
        runs = ([], [])
        for _ in range(args.rounds):
            for folder, results in zip(folders, runs, strict=True):
                results.append(_run_child(folder, "blows", args.repeat))
        compiles = ([], [])
        for _ in range(args.compile):
            for folder, results in zip(folders, compiles, strict=True):
                with tempfile.TemporaryDirectory(prefix="numba_cache_") as cache:
                    results.append(_run_child(folder, "compile", 1, cache))
    print(f"\n{'blow kind':24s} {'steps':>5s} {'A us/step':>20s} {'B us/step':>20s} "
          f"{'B/A of min':>10s} {'B/A median (range)':>24s}")
    print(f"{'':24s} {'':5s} {'min':>9s} {'median':>10s} {'min':>9s} {'median':>10s}")
    worst = 0.0
    for name in runs[0][0] if args.rounds else ():
        steps = runs[0][0][name][0]
        per_step = [[(r[name][1] / steps * 1e6, r[name][2] / steps * 1e6) for r in rev_runs]
                    for rev_runs in runs]
        lows = [min(p[0] for p in rev) for rev in per_step]
        medians = [statistics.median(p[1] for p in rev) for rev in per_step]
        ratios = [b[1] / a[1] for a, b in zip(*per_step, strict=True)]
        worst = max(worst, lows[1] / lows[0])
        print(f"{name:24s} {steps:5d} {lows[0]:9.2f} {medians[0]:10.2f} {lows[1]:9.2f} "
              f"{medians[1]:10.2f} {lows[1] / lows[0]:10.3f} {statistics.median(ratios):8.3f} "
              f"({min(ratios):.3f}-{max(ratios):.3f})")
    if args.rounds:
        print(f"\nlargest B/A of the minima: {worst:.3f}")
    if args.compile:
        print("\ncold compilation of the Table 1 blow's loop (first blow - warm blow, empty "
              "numba cache) [s]:")
        for label, results in zip(labels, compiles, strict=True):
            times = [r["first"] - r["warm"] for r in results]
            print(f"  {label}: min {min(times):.2f}, median {statistics.median(times):.2f} "
                  f"over {len(times)}")


if __name__ == "__main__":
    main()
