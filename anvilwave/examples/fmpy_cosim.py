"""Your own co-simulation of the anvilwave FMUs, with fmpy only (no anvilwave import).

The FMUs come from ``anvilwave build-fmus anvilwave/examples/table1.toml --out DIR``. This script
loads
Ram.fmu, an anvil and PileSoil.fmu from DIR, connects them in its own master loop (the step
order of DESIGN.md: ram and pile states -> anvil -> contact forces at t_n -> every unit steps
over [t_n, t_n + h]), runs the blow once with the modal anvil (Anvil.fmu) and once with the
rigid lumped-mass anvil swapped in (AnvilLumped.fmu; same variables, nothing else changes), and
plots the pile-head force (the anvil-pile contact force) of both.

Run: ``python anvilwave/examples/fmpy_cosim.py DIR [--plot pile_head_force.png]`` (a few seconds;
without --plot the figure opens in a window). ``--pile OTHER.fmu`` swaps in another pile/soil
unit (e.g. a PileSoil.fmu built from a system file with other soil).
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


class Unit:
    """One FMU instance: Real (and Boolean) variables by name."""

    def __init__(self, path: Path, name: str):
        md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.folder = extract(str(path))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.folder, instanceName=name,
                             modelIdentifier=md.coSimulation.modelIdentifier)
        self.fmu.instantiate()

    def start(self, start_time: float, **parameters: float | bool) -> None:
        self.fmu.setupExperiment(startTime=start_time)
        self.set(**parameters)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def set(self, **values: float | bool) -> None:
        flags = {n: v for n, v in values.items() if isinstance(v, bool)}
        reals = {n: v for n, v in values.items() if n not in flags}
        if flags:
            self.fmu.setBoolean([self.vr[n] for n in flags], list(flags.values()))
        if reals:
            self.fmu.setReal([self.vr[n] for n in reals], list(reals.values()))

    def get(self, *names: str) -> list[float]:
        return self.fmu.getReal([self.vr[n] for n in names])

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.folder, ignore_errors=True)


def blow(ram_fmu: Path, anvil_fmu: Path, pile_fmu: Path, step: float, duration: float):
    """One blow: time [s] and the pile-head force [N] at t_n = t0 + n h, t0 = -h/2."""
    ram, anvil, pile = Unit(ram_fmu, "ram"), Unit(anvil_fmu, "anvil"), Unit(pile_fmu, "pile")
    try:
        t0 = -0.5 * step  # the ram touches the anvil half a step after the start
        pile.start(t0)
        anvil.start(t0)
        # the anvil rests on the pile head; its top face is where the ram strikes
        head, = pile.get("u_head")
        anvil.set(u_ram=head - 1.0, v_ram=0.0, u_pile=head, v_pile=0.0)  # ram well clear
        top, = anvil.get("u_top")
        # the engine's start: the first contact at 0 (contact_mid_step off; on, the ram would
        # place it mid first step itself, from its DefaultExperiment's step before that step)
        ram.start(t0, contact_displacement=top, contact_time=0.0, contact_mid_step=False)
        n = int(round(duration / step))
        force = np.empty(n + 1)
        for k in range(n + 1):
            t = t0 + k * step  # from the step count, never accumulated
            u_toe, v_toe = ram.get("u_toe", "v_toe")
            u_head, v_head = pile.get("u_head", "v_head")
            anvil.set(u_ram=u_toe, v_ram=v_toe, u_pile=u_head, v_pile=v_head)
            f_ram, force[k] = anvil.get("F_ram", "F_pile")
            if k == n:
                break
            ram.set(F_toe=f_ram)
            pile.set(F_head=force[k])
            for unit in (ram, anvil, pile):
                unit.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
        return t0 + step * np.arange(n + 1), force
    finally:
        for unit in (ram, anvil, pile):
            unit.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fmus", type=Path, help="folder written by anvilwave build-fmus")
    parser.add_argument("--pile", type=Path, default=None,
                        help="another pile/soil FMU for a third run")
    parser.add_argument("--step", type=float, default=20e-6,
                        help="communication step h [s] (default 20 us, table1.toml's)")
    parser.add_argument("--duration", type=float, default=0.025, help="[s] (default 25 ms)")
    parser.add_argument("--plot", type=Path, default=None, help="write the figure (PNG)")
    args = parser.parse_args()

    folder = args.fmus
    runs = {"Anvil.fmu (modal ROM)": (folder / "Anvil.fmu", folder / "PileSoil.fmu"),
            "AnvilLumped.fmu (rigid)": (folder / "AnvilLumped.fmu", folder / "PileSoil.fmu")}
    if args.pile is not None:
        runs[f"Anvil.fmu on {args.pile.name}"] = (folder / "Anvil.fmu", args.pile)
    results = {}
    for label, (anvil, pile) in runs.items():
        time, force = blow(folder / "Ram.fmu", anvil, pile, args.step, args.duration)
        results[label] = (time, force)
        print(f"{label}: peak pile-head force {force.max() / 1e6:.3f} MN at "
              f"{time[force.argmax()] * 1e3:.3f} ms")

    import matplotlib

    if args.plot is not None:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, (time, force) in results.items():
        ax.plot(time * 1e3, force / 1e6, label=label)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("pile-head force [MN]")
    ax.set_title("anvilwave FMUs, co-simulated with fmpy")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    if args.plot is not None:
        fig.savefig(args.plot, dpi=120)
        print(f"figure: {args.plot}")
    else:
        plt.show()


if __name__ == "__main__":
    main()
