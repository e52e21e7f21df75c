"""In-process engine speed: the Table 1 blow (25 ms) for every anvil and ram model, the cost of
recording and of the energy bookkeeping, and the per-blow overhead of a run of 100 blows.

Run: python benchmarks/bench_engine.py [--repeat N] [--blows B]

All figures come from this one run (ratios, not absolute targets: the machine may be shared).
For each ram model (table1.toml's modal ram as the modal unit, the same modes realised as their
chain, and the hammer's Smith rod) and anvil model (rom, lumped, classic, none; the classic
driving system runs a modal ram as its chain): the degrees of freedom stepped (ram masses or
modes + anvil modes or masses + pile masses), the master step, and for the blow as `anvilwave
impact` runs it (every step recorded, the energy bookkeeping every ENERGY_STEPS steps) the
microseconds per step, the nanoseconds per degree of freedom and step, and the simulated time
over the wall time of the stepping (x real time; compilation and start-up excluded: the engine
compiles or loads the loop before timing). Then, per model, the wall time of each way of running
a blow relative to the summary-only blow (record=False: the maxima, EMX and set computed inside
the loop): recording the time series, the energy bookkeeping at its default interval and at
every step. Finally a run of B consecutive blows against B times one blow's stepping (the per-
blow overhead: state copies, result objects). The modal ram unit's wall time over the chain's is
printed per anvil model (the issue's bound: at most 1; both run in the one compiled loop, so the
ratio is the two ram kernels' difference), with the two ram kernels alone, the pile port in
three rings (``[anvil] pile_port_rings = 3``) against the one port, the three rings on the
tube head (``pile_head = "tube"``) against them on the 1D head, and on that head the ram port
in six annuli (``ram_port_annuli = 6``, anvilwave/examples/table1_interfaces.toml) against one.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import time
from pathlib import Path

import numpy as np
from numba import njit

from anvilwave.anvil_rom.arrays import aligned_zeros
from anvilwave.config.cache import cached_chain
from anvilwave.config.system import load_system
from anvilwave.engine.direct import ENERGY_STEPS, build_engine
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.modal_ram import ModalRamUnit, modal_ram_advance, modal_ram_chain
from anvilwave.hammer.ram import ram_advance

ROOT = Path(__file__).resolve().parents[1]
PAIRS = 5
"""Pairs of engines for the unit/chain ratio: where the allocator puts a pair's arrays moves
the ratio of one pair by a few per cent."""
MODES = {
    "summary only": {"record": False, "energy": False},
    "recording": {"record": True, "energy": False},
    "+ energy": {"record": True, "energy": True},
    "+ energy every step": {"record": True, "energy": True, "energy_interval": "step"},
}


def degrees_of_freedom(engine) -> int:
    anvil = engine.anvil
    if anvil.kind in ("rom", "lumped"):
        n_anvil = anvil.unit.n_modes
    elif anvil.kind == "classic":
        n_anvil = 1 + int(anvil.unit.assembly_chain[0].size)
    else:
        n_anvil = 0
    n_ram = engine.ram_modes.n_modes if engine.ram_modes is not None else engine.ram_mass.size
    return n_ram + n_anvil + engine.pile_arrays.pile.shape[1]


def time_blows(engine, repeat: int, **options) -> float:
    """Median wall time of the stepping of one blow [s] over ``repeat`` blows."""
    if options.get("energy_interval") == "step":
        options["energy_interval"] = engine.time_step
    engine.blow(**options)  # compile or load this variant
    return statistics.median(engine.blow(**options).wall_time for _ in range(repeat))


def alternated_ratio(first, second, repeat: int) -> float:
    """Median wall time of ``first``'s blows over ``second``'s, their blows alternated so that
    both see the same machine."""
    for engine in (first, second):
        engine.blow()
    walls = ([], [])
    for _ in range(repeat):
        for engine, wall in zip((first, second), walls, strict=True):
            wall.append(engine.blow().wall_time)
    return statistics.median(walls[0]) / statistics.median(walls[1])


@njit(cache=True)
def _drive_unit(C, S, toe, forces, h, sweeps):
    for _ in range(sweeps):
        for f in forces:
            modal_ram_advance(C, S, f, h, toe)


@njit(cache=True)
def _drive_chain(weight, inverse_mass, stiffness, u, v, forces, h, n_sub, sweeps):
    for _ in range(sweeps):
        for f in forces:
            ram_advance(weight, inverse_mass, stiffness, u, v, f, h, n_sub)


def ram_kernel_ratio(unit_engine, chain_engine, repeat: int, sweeps: int = 40) -> float:
    """The two ram kernels alone, as the engine calls them (the modal unit's
    :func:`anvilwave.hammer.modal_ram.modal_ram_advance`, the chain's
    :func:`anvilwave.hammer.ram.ram_advance` at
    its sub-steps), each driven by the unit engine's recorded ram force of one blow, ``sweeps``
    times over: median wall time of the unit's runs over the chain's, alternated."""
    blow = unit_engine.blow()
    forces = np.asarray(blow.columns["ram_anvil_force [N]"], float)
    h = unit_engine.time_step
    unit = ModalRamUnit(unit_engine.ram_modes, unit_engine.config.gravity)
    unit.start(0.0, unit_engine.config.hammer.impact_velocity, h)
    weight, inverse_mass, stiffness, _ = chain_engine._ram
    u = aligned_zeros(weight.size)  # as the engine's blows allocate them
    v = aligned_zeros(weight.size)
    n_sub = chain_engine._ram_nsub
    runs = (lambda: _drive_unit(unit.C, unit.S, unit.toe, forces, h, sweeps),
            lambda: _drive_chain(weight, inverse_mass, stiffness, u, v, forces, h, n_sub,
                                 sweeps))
    walls = ([], [])
    for run in runs:
        run()  # compile or load
    for _ in range(repeat):
        for run, wall in zip(runs, walls, strict=True):
            start = time.perf_counter()
            run()
            wall.append(time.perf_counter() - start)
    return statistics.median(walls[0]) / statistics.median(walls[1])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--blows", type=int, default=100)
    args = parser.parse_args()
    cfg = load_system(ROOT / "anvilwave" / "examples" / "table1.toml")
    rod = dataclasses.replace(cfg, hammer=load_hammer("illustrative_5500kj"))
    chain = dataclasses.replace(cfg, hammer=dataclasses.replace(
        cfg.hammer, ram=modal_ram_chain(cfg.hammer.ram, cfg.hammer.ram.modes, cached_chain)))
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"Table 1 blow, {cfg.duration * 1e3:g} ms; medians of {args.repeat} blows; load "
          f"average {load:.2f} on {os.cpu_count()} cores")
    rows = []
    modal = None
    for ram_name, base in (("unit", cfg), ("chain", chain), ("rod", rod)):
        for anvil in ("rom", "lumped", "classic", "none"):
            engine = build_engine(base.with_anvil_model(anvil), modal)
            modal = engine.modal if modal is None else modal
            walls = {mode: time_blows(engine, args.repeat, **dict(options))
                     for mode, options in MODES.items()}
            steps = int(round(cfg.duration / engine.time_step))
            rows.append((ram_name, anvil, degrees_of_freedom(engine), engine.time_step, steps,
                         walls))
    print(f"\n{'ram':5s} {'anvil':7s} {'DOF':>4s} {'step [us]':>9s} {'steps':>5s} "
          f"{'us/step':>8s} {'ns/DOF':>7s} {'x real':>7s} {'x real (summary)':>16s}")
    for ram, anvil, dof, h, steps, walls in rows:
        wall = walls["+ energy"]
        print(f"{ram:5s} {anvil:7s} {dof:4d} {h * 1e6:9.2f} {steps:5d} {wall / steps * 1e6:8.3f} "
              f"{wall / steps / dof * 1e9:7.2f} {steps * h / wall:7.1f} "
              f"{steps * h / walls['summary only']:16.1f}")
    print(f"\nwall time relative to the summary-only blow (energy bookkeeping: every "
          f"{ENERGY_STEPS} steps by default)")
    print(f"{'ram':5s} {'anvil':7s} " + " ".join(f"{m:>20s}" for m in MODES))
    for ram, anvil, _, _, _, walls in rows:
        base = walls["summary only"]
        print(f"{ram:5s} {anvil:7s} " + " ".join(f"{walls[m] / base:20.2f}" for m in MODES))
    # the modal ram unit against its chain: blows of the two engines alternated, so that both
    # see the same machine (the tables above run the models one after the other), over several
    # pairs of engines built afresh (each pair lands at other addresses)
    print(f"\nmodal ram unit / its chain, median wall time of alternated blows (recorded, energy "
          f"bookkeeping); median and range over {PAIRS} pairs of engines")
    for anvil in ("rom", "lumped", "classic"):
        ratios = []
        for _ in range(PAIRS):
            pair = [build_engine(base.with_anvil_model(anvil), modal) for base in (cfg, chain)]
            ratios.append(alternated_ratio(*pair, 3 * args.repeat))
        note = " (both the chain: the control)" if anvil == "classic" else ""
        print(f"  {anvil:7s} {statistics.median(ratios):.3f} ({min(ratios):.3f}-"
              f"{max(ratios):.3f}){note}")
        if anvil == "rom":
            ratio = ram_kernel_ratio(*pair, args.repeat)
            print(f"  the ram kernels alone, driven by the blow's ram force: {ratio:.3f}")

    # the pile port in three rings (pile_port_rings = 3) against the one port: alternated
    spec = cfg.anvil.spec
    ringed = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=3))))
    ringed_engine = build_engine(ringed)
    ratio = alternated_ratio(ringed_engine, build_engine(cfg, modal), args.repeat)
    print(f"\npile port in three rings / one port: {ratio:.3f} (median wall time of alternated "
          "blows, ROM anvil, recorded, energy bookkeeping)")
    tube = dataclasses.replace(ringed, anvil=dataclasses.replace(ringed.anvil, pile_head="tube"))
    tube_engine = build_engine(tube)
    ratio = alternated_ratio(tube_engine, ringed_engine, args.repeat)
    print(f"three rings on the tube head / on the 1D head: {ratio:.3f} (pile_head = \"tube\": "
          "the head's convolution over the blow)")
    # the same with the ram port in six annuli (anvilwave/examples/table1_interfaces.toml)
    faces = load_system(ROOT / "anvilwave" / "examples" / "table1_interfaces.toml")
    faces_engine = build_engine(faces)
    ratio = alternated_ratio(faces_engine, tube_engine, args.repeat)
    blow = faces_engine.blow()
    print(f"six ram annuli / one ram port, three rings on the tube head: {ratio:.3f} "
          f"(ram_port_annuli = 6: the ram's modes twice, a 9-contact problem); the blow "
          f"{faces.duration / blow.wall_time:.1f}x real time")

    # B consecutive blows of the default model against B x one blow's stepping (best of three
    # runs: on a shared machine a run of B blows is likelier to be interrupted than one blow)
    engine = build_engine(dataclasses.replace(cfg, blows=args.blows), modal)
    print()
    for record in (True, False):
        engine.run(blows=2, record=record)
        best = None
        for _ in range(3):
            start, cpu = time.perf_counter(), time.thread_time()
            results = engine.run(record=record)
            total, cpu = time.perf_counter() - start, time.thread_time() - cpu
            stepping = statistics.median(r.wall_time for r in results)
            if best is None or total / stepping < best[0] / best[2]:
                best = (total, cpu, stepping)
        total, cpu, stepping = best
        print(f"{args.blows} blows (record={record}): {total * 1e3:.1f} ms = "
              f"{total / (args.blows * stepping):.3f} x {args.blows} x one blow's stepping "
              f"({stepping * 1e3:.3f} ms), {cpu / (args.blows * stepping):.3f} x in CPU time; "
              f"overhead {1e3 * (total / args.blows - stepping):.3f} ms per blow")
    rom = next(r for r in rows if r[:2] == ("unit", "rom"))
    factor = cfg.duration / rom[5]["+ energy"]
    print(f"\nTable 1 default blow (modal ram unit, ROM anvil, recorded, energy bookkeeping): "
          f"{factor:.1f}x faster than real time")


if __name__ == "__main__":
    main()
