"""The fmax study on xl8 (the method's single parameter): error against the FEA and run time.

Run: python benchmarks/study_fmax.py [--out results/study_fmax] [--fea-csv FILE]
                                   [--segment-length 0.125]
For fmax in a range, the ROM of the Table 1 case (free pile, as in `anvilwave compare`) is run
with the in-process engine and compared with the reference FEA in the comparison band (the
pile chain's cut-off, 3.3 kHz for 0.5 m segments): peak ram and pile forces, normalised RMS
errors, arrival time, number of modes and the wall time of the time stepping (simulated time /
wall time), all measured in this one run. Writes study.json and prints a table.
With a modal ram (table1.toml's ram_model = "modal") fmax is the content of the ram's ROM too:
the one parameter of the method sets both, as in a run of the system file at that fmax. The ram
runs as the modal unit (hammer.modal_ram.ModalRamUnit): no chain, so no double-precision limit
on its number of modes (the chain stops below 10 kHz for this ram).
The master step is the automatic one at every fmax (table1.toml fixes h = 20 us instead).
Errors are given in two bands: 3.3 kHz (the cut-off of the paper's 0.5 m pile segments) and
5 kHz (the default fmax; table1.toml's 0.25 m segments cut off at 6.5 kHz). Per fmax also the
raw ROM peaks (what impact.csv holds) against the FEA's peaks in the 5 kHz band, and the largest
deviation of the one-third-octave band levels of the pile-head force from the FEA's
(:func:`anvilwave.analyses.compare.band_levels`) up to 1.26 kHz and up to 4 kHz.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from pathlib import Path

import numpy as np

from anvilwave.analyses.compare import (
    ModelRun,
    band_levels,
    comparison_bandwidth,
    fea_config,
    metrics,
    without_soil,
)
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes
from anvilwave.config.cache import cached_modal_data
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.fea.impact import run_impact_fea
from anvilwave.hammer.modal_ram import modal_ram_modes
from anvilwave.inputs import InputError
from anvilwave.output.tables import read_csv, write_csv

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
FMAX = (500.0, 1000.0, 2000.0, 3000.0, 5000.0, 7500.0, 10000.0)
BANDS = (3300.0, 5000.0)
"""Bands of the errors [Hz]: the paper's 0.5 m pile chain's cut-off and the default fmax."""


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--system", type=Path, default=EXAMPLES / "table1.toml")
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_fmax")
    parser.add_argument("--fea-csv", type=Path, default=None,
                        help="reuse an FEA time series (fea.csv of `anvilwave compare`)")
    parser.add_argument("--segment-length", type=float, default=None,
                        help="pile segment length [m] (default: the system file's)")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    # the automatic step at every fmax (it follows fmax and the coupling limit)
    cfg = dataclasses.replace(without_soil(load_system(args.system)), time_step=None)
    if args.segment_length is not None:
        pile_soil = cfg.pile_soil
        pile = dataclasses.replace(pile_soil.pile, segment_length=args.segment_length)
        cfg = dataclasses.replace(cfg, pile_soil=dataclasses.replace(pile_soil, pile=pile))
    if args.fea_csv is not None:
        fea = ModelRun("fea", read_csv(args.fea_csv), float("nan"), {})
    else:
        result = run_impact_fea(fea_config(cfg))
        fea = ModelRun("fea", result.to_columns(), result.wall_time, {})
        write_csv(fea.columns, args.out / "fea.csv")
    preload = float(fea.columns["anvil_pile_force [N]"][0])  # the anvil weight at t = 0
    bandwidth = comparison_bandwidth(dataclasses.replace(
        cfg, anvil=dataclasses.replace(cfg.anvil, fmax=None)))
    modal = compute_anvil_modes(cfg.anvil.spec, fmax=max(FMAX)).modal_data
    rows = []
    for correction in (True, False):
        for fmax in FMAX:
            anvil = dataclasses.replace(cfg.anvil, fmax=fmax, static_correction=correction)
            case = dataclasses.replace(cfg, anvil=anvil)
            ram_modes = None
            if cfg.hammer.ram.is_modal:  # the same fmax for the ram
                try:
                    ram_modes = modal_ram_modes(cfg.hammer.ram, fmax, modes=cached_modal_data)
                except InputError as exc:  # the ram's mesh cannot resolve fmax
                    print(f"fmax {fmax:g} Hz skipped: {exc}", flush=True)
                    continue
            engine = build_engine(case, modal=modal, ram_modes=ram_modes)
            blow = engine.run()[0]
            run = ModelRun("rom", blow.columns, blow.wall_time, {})
            m = metrics(run, fea, preload, bandwidth)
            by_band = {f"{band:.0f} Hz": metrics(run, fea, preload, band) for band in BANDS}
            spectra = band_levels({"rom": run, "fea": fea}, max(BANDS))
            deviation = np.array([np.nan if d is None else d
                                  for d in spectra["deviation_from_fea [dB]"]["rom"]])
            centre = np.array(spectra["band_centre_frequency [Hz]"])
            valid = np.array(spectra["valid [-]"], bool)
            level_errors = {f"max_band_level_deviation_to_{top:.0f}_Hz [dB]": float(
                np.nanmax(np.abs(deviation[valid & (centre <= top * 1.01)])))
                for top in (1259.0, 3981.0)}
            rows.append({"fmax [Hz]": fmax, "static_correction": correction,
                         "n_modes": engine.anvil.unit.n_modes,
                         "time_step [s]": engine.time_step,
                         "realtime_factor [-]": cfg.duration / blow.wall_time, **m,
                         **level_errors, "bands": by_band})
    lumped = build_engine(cfg.with_anvil_model("lumped"), modal=modal).run()[0]
    m_lumped = metrics(ModelRun("lumped", lumped.columns, lumped.wall_time, {}), fea, preload,
                       bandwidth)
    (args.out / "study.json").write_text(json.dumps(
        {"bandwidth [Hz]": bandwidth, "rom": rows, "lumped": m_lumped}, indent=2) + "\n")
    print(f"pile chain cut-off {bandwidth:.0f} Hz; errors against the FEA")
    print(f"{'fmax':>6s} {'corr':>4s} " + " ".join(
        f"{'ram pk ' + str(round(b / 1e3, 1)):>10s} {'pile pk':>7s} {'RMS ram':>7s} "
        f"{'RMS pile':>8s}" for b in BANDS))
    for r in rows:
        print(f"{r['fmax [Hz]']:6.0f} {str(r['static_correction'])[:4]:>4s} " + " ".join(
            f"{m['peak_ram_anvil_force_error [-]']:+10.3f} "
            f"{m['peak_anvil_pile_force_error [-]']:+7.3f} "
            f"{m['ram_anvil_force_normalised_rms_error [-]']:7.3f} "
            f"{m['anvil_pile_force_normalised_rms_error [-]']:8.3f}"
            for m in r["bands"].values()))
    five = f"{max(BANDS):.0f} Hz"
    print(f"\nraw ROM peaks against the FEA's {five} peaks; band-level deviations [dB]")
    print(f"{'fmax':>6s} {'corr':>4s} {'raw ram':>8s} {'raw pile':>8s} {'<=1.26k':>8s} "
          f"{'<=4k':>6s}")
    for r in rows:
        m = r["bands"][five]
        print(f"{r['fmax [Hz]']:6.0f} {str(r['static_correction'])[:4]:>4s} "
              f"{m['peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]']:+8.3f} "
              f"{m['peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]']:+8.3f} "
              f"{r['max_band_level_deviation_to_1259_Hz [dB]']:8.1f} "
              f"{r['max_band_level_deviation_to_3981_Hz [dB]']:6.1f}")
    print(f"\nin the {bandwidth:.0f} Hz band:")
    print(f"{'fmax':>6s} {'corr':>4s} {'modes':>5s} {'ram pk':>7s} {'pile pk':>7s} "
          f"{'RMS ram':>7s} {'RMS pile':>8s} {'arrival':>8s} {'x real':>6s}")
    for r in rows + [{"fmax [Hz]": 0, "static_correction": "-", "n_modes": 1,
                      "realtime_factor [-]": cfg.duration / lumped.wall_time, **m_lumped}]:
        label = f"{r['fmax [Hz]']:6.0f}" if r["fmax [Hz]"] else "lumped"
        print(f"{label:>6s} {str(r['static_correction'])[:4]:>4s} {r['n_modes']:5d} "
              f"{r['peak_ram_anvil_force_error [-]']:+7.3f} "
              f"{r['peak_anvil_pile_force_error [-]']:+7.3f} "
              f"{r['ram_anvil_force_normalised_rms_error [-]']:7.3f} "
              f"{r['anvil_pile_force_normalised_rms_error [-]']:8.3f} "
              f"{r['pile_force_arrival_error [s]'] * 1e3:+7.3f}ms "
              f"{r['realtime_factor [-]']:6.1f}")


if __name__ == "__main__":
    main()
