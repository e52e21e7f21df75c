"""Anvil-size study: lumped-mass and ROM anvils against the FEA for the s2, m55 and xl8 anvils.

Run: python benchmarks/study_anvil_size.py [--out results/study_size]
Each anvil sits on its pile (examples/size_s2.toml, size_m55.toml, table1.toml: the same
configuration at scales 0.25, 0.6875 and 1), struck by its illustrative ram at the same
velocity. The window (25 ms at full scale) and the FEA element size scale with the anvil, so
the three cases differ in size only. Prints and writes (study.json) the errors of both anvil
models against the FEA in each case's comparison band: where the lumped mass stops being
adequate shows as its errors growing with the anvil size.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from pathlib import Path

from anvil_rom.fea import run_impact_fea
from fmu.compare import (
    ModelRun,
    comparison_bandwidth,
    fea_config,
    metrics,
    without_soil,
)
from fmu.engine import build_engine
from fmu.system import load_system

ROOT = Path(__file__).resolve().parents[1]
CASES = (("s2", "size_s2.toml", 0.25), ("m55", "size_m55.toml", 0.6875),
         ("xl8", "table1.toml", 1.0))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_size")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    table = {}
    for name, file, scale in CASES:
        cfg = without_soil(load_system(ROOT / "examples" / file))
        cfg = dataclasses.replace(cfg, duration=round(0.025 * scale / 1e-5) * 1e-5)
        fea = run_impact_fea(fea_config(cfg, mesh_size=0.1 * scale,
                                        output_interval=1e-5 * scale))
        ref = ModelRun("fea", fea.to_columns(), fea.wall_time, {})
        preload = float(ref.columns["anvil_pile_force [N]"][0])
        band = comparison_bandwidth(cfg)
        row = {"bandwidth [Hz]": band, "fea_dof": fea.n_dof, "fea_wall_time [s]": fea.wall_time,
               "anvil_mass [kg]": None}
        for model in ("rom", "lumped"):
            engine = build_engine(cfg.with_anvil_model(model))
            blow = engine.run()[0]
            m = metrics(ModelRun(model, blow.columns, blow.wall_time, {}), ref, preload, band)
            row[model] = m
            row["anvil_mass [kg]"] = engine.modal.total_mass
        table[name] = row
        print(f"{name}: FEA {fea.n_dof} DOF in {fea.wall_time:.1f} s", flush=True)
    (args.out / "study.json").write_text(json.dumps(table, indent=2) + "\n")
    print(f"{'anvil':5s} {'model':7s} {'ram pk':>7s} {'pile pk':>7s} {'RMS ram':>7s} "
          f"{'RMS pile':>8s} {'arrival':>9s}")
    for name, row in table.items():
        for model in ("rom", "lumped"):
            m = row[model]
            print(f"{name:5s} {model:7s} {m['peak_ram_anvil_force_error [-]']:+7.3f} "
                  f"{m['peak_anvil_pile_force_error [-]']:+7.3f} "
                  f"{m['ram_anvil_force_normalised_rms_error [-]']:7.3f} "
                  f"{m['anvil_pile_force_normalised_rms_error [-]']:8.3f} "
                  f"{m['pile_force_arrival_error [s]'] * 1e3:+8.3f}ms")


if __name__ == "__main__":
    main()
