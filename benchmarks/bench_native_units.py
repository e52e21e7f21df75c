"""Speed of the native Ram and PileSoil FMUs against the pythonfmu units, as ratios.

Run: python benchmarks/bench_native_units.py [--steps 5000]

Each unit of Table 1 (the modal ram of illustrative_5500kj and its rod form; Table 1's pile
and soil) is built both ways and stepped under fmpy's FMU2Slave with a held input
(setReal, doStep, getReal per step, the master's calls), after 100 warm-up steps. The
microseconds per step of each and the ratio pythonfmu / native are printed; the ratio is what
to compare between machines (fmpy's ctypes calls are in both).
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
import time
import tomllib
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from anvilwave.config.system import load_system
from anvilwave.fmu.fmi_build import build_pile_soil_fmu, build_ram_fmu
from anvilwave.fmu.native_units import build_native_pile_soil_fmu, build_native_ram_fmu
from anvilwave.hammer.database import load_hammer
from anvilwave.inputs import Table
from anvilwave.pile.model import PileSoil

ROOT = Path(__file__).resolve().parents[1]


def microseconds_per_step(path: Path, name_in: str, value: float, outputs: list[str],
                          steps: int, h: float = 1e-5) -> float:
    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    folder = extract(str(path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=folder, instanceName="bench",
                    modelIdentifier=md.coSimulation.modelIdentifier)
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        vin, vout = [vr[name_in]], [vr[n] for n in outputs]
        t = 0.0
        for _ in range(100):
            fmu.setReal(vin, [value])
            fmu.doStep(t, h)
            fmu.getReal(vout)
            t += h
        start = time.perf_counter()
        for _ in range(steps):
            fmu.setReal(vin, [value])
            fmu.doStep(t, h)
            fmu.getReal(vout)
            t += h
        return (time.perf_counter() - start) / steps * 1e6
    finally:
        fmu.terminate()
        fmu.freeInstance()
        shutil.rmtree(folder, ignore_errors=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=5000)
    args = parser.parse_args()
    cfg = load_system(ROOT / "anvilwave" / "examples" / "table1.toml")
    tables = tomllib.loads((ROOT / "anvilwave" / "examples" / "table1.toml").read_text())
    pile = PileSoil.from_tables(Table(tables["pile"], "table1", "pile"),
                                Table(tables["soil"], "table1", "soil"))
    rod = load_hammer("illustrative_5500kj", 9.81)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        cases = {
            "Ram (modal, Table 1)": (
                build_native_ram_fmu(cfg.hammer, out / "n_modal" / "Ram.fmu", v_impact=6.0),
                build_ram_fmu(out / "p_modal", cfg.hammer, v_impact=6.0),
                "F_toe", 1e7, ["u_toe", "v_toe"]),
            "Ram (rod)": (
                build_native_ram_fmu(rod, out / "n_rod" / "Ram.fmu", v_impact=6.0),
                build_ram_fmu(out / "p_rod", rod, v_impact=6.0), "F_toe", 1e7,
                ["u_toe", "v_toe"]),
            "PileSoil (Table 1)": (
                build_native_pile_soil_fmu(pile, out / "n_pile" / "PileSoil.fmu",
                                           static_head_load=3.19e6),
                build_pile_soil_fmu(out / "p_pile", pile, static_head_load=3.19e6),
                "F_head", 3.5e6, ["u_head", "v_head", "F_gauge", "v_gauge"]),
        }
        for name, (native, python, name_in, value, outputs) in cases.items():
            a = microseconds_per_step(native, name_in, value, outputs, args.steps)
            b = microseconds_per_step(python, name_in, value, outputs, args.steps)
            print(f"{name:22s} native {a:8.1f} us/step, pythonfmu {b:8.1f} us/step, "
                  f"pythonfmu / native {b / a:5.1f}")


if __name__ == "__main__":
    main()
