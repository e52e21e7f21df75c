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
Run with the default system and no --fea-csv or --segment-length, it also writes the table of
docs/validation.md, docs/data/study_fmax.json (benchmarks/doc_data.py; checked by
tests/test_compare.py).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from pathlib import Path

import numpy as np
from doc_data import system_inputs, write_doc_data

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
from anvilwave.config.system import SystemConfig, load_system
from anvilwave.engine.direct import build_engine
from anvilwave.fea.impact import run_impact_fea
from anvilwave.hammer.modal_ram import modal_ram_modes
from anvilwave.inputs import InputError
from anvilwave.output.examples import EXAMPLES_DIR
from anvilwave.output.tables import read_csv, write_csv

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = EXAMPLES_DIR  # the installed package's (the checkout's in an editable install)
FMAX = (500.0, 1000.0, 2000.0, 3000.0, 5000.0, 7500.0, 10000.0)
BANDS = (3300.0, 5000.0)
"""Bands of the errors [Hz]: the paper's 0.5 m pile chain's cut-off and the default fmax."""


def study_config(system: Path = EXAMPLES / "table1.toml") -> SystemConfig:
    """The study's free-pile system: the automatic step at every fmax (it follows fmax and the
    coupling limit)."""
    return dataclasses.replace(without_soil(load_system(system)), time_step=None)


def study_row(cfg: SystemConfig, fea: ModelRun, modal, fmax: float, correction: bool) -> dict:
    """One row of the study: the ROM at ``fmax`` (its modes truncated from ``modal``, the modal
    ram at the same fmax) against the FEA run ``fea``. Raises InputError when the ram's mesh
    cannot resolve fmax."""
    preload = float(fea.columns["anvil_pile_force [N]"][0])  # the anvil weight at t = 0
    bandwidth = comparison_bandwidth(dataclasses.replace(
        cfg, anvil=dataclasses.replace(cfg.anvil, fmax=None)))
    anvil = dataclasses.replace(cfg.anvil, fmax=fmax, static_correction=correction)
    case = dataclasses.replace(cfg, anvil=anvil)
    ram_modes = None
    if cfg.hammer.ram.is_modal:  # the same fmax for the ram
        ram_modes = modal_ram_modes(cfg.hammer.ram, fmax, modes=cached_modal_data)
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
    return {"fmax [Hz]": fmax, "static_correction": correction,
            "n_modes": engine.anvil.unit.n_modes,
            "ram_modes": None if ram_modes is None else len(ram_modes.omega),
            "time_step [s]": engine.time_step,
            "realtime_factor [-]": cfg.duration / blow.wall_time, **m,
            **level_errors, "bands": by_band}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--system", type=Path, default=EXAMPLES / "table1.toml")
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_fmax")
    parser.add_argument("--fea-csv", type=Path, default=None,
                        help="reuse an FEA time series (fea.csv of `anvilwave compare`)")
    parser.add_argument("--segment-length", type=float, default=None,
                        help="pile segment length [m] (default: the system file's)")
    parser.add_argument("--docs-from", type=Path, default=None, metavar="STUDY_JSON",
                        help="only rewrite docs/data/study_fmax.json from the study.json of an "
                             "earlier default run of this script")
    args = parser.parse_args()
    if args.docs_from is not None:
        rows = json.loads(args.docs_from.read_text())["rom"]
        write_docs_table(args.system, rows, load_system(args.system).duration,
                         command="python benchmarks/study_fmax.py")
        return
    args.out.mkdir(parents=True, exist_ok=True)
    cfg = study_config(args.system)
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
            try:
                rows.append(study_row(cfg, fea, modal, fmax, correction))
            except InputError as exc:  # the ram's mesh cannot resolve fmax
                print(f"fmax {fmax:g} Hz skipped: {exc}", flush=True)
    lumped = build_engine(cfg.with_anvil_model("lumped"), modal=modal).run()[0]
    m_lumped = metrics(ModelRun("lumped", lumped.columns, lumped.wall_time, {}), fea, preload,
                       bandwidth)
    (args.out / "study.json").write_text(json.dumps(
        {"bandwidth [Hz]": bandwidth, "rom": rows, "lumped": m_lumped}, indent=2) + "\n")
    if (args.system == EXAMPLES / "table1.toml" and args.fea_csv is None
            and args.segment_length is None):
        write_docs_table(args.system, rows, cfg.duration)
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


DOC_BAND = "5000 Hz"
"""The band of the docs' table: every series low-passed at the default fmax."""
DOC_COLUMNS = {
    # column: (format, key of a row's metrics in DOC_BAND, or of the row itself)
    "fmax [Hz]": ("int", "fmax [Hz]"),
    "anvil modes": ("int", "n_modes"),
    "ram peak": ("pct+", "peak_ram_anvil_force_error [-]"),
    "pile peak": ("pct+", "peak_anvil_pile_force_error [-]"),
    "RMS ram": ("pct", "ram_anvil_force_normalised_rms_error [-]"),
    "RMS pile": ("pct", "anvil_pile_force_normalised_rms_error [-]"),
    "raw ram": ("pct+", "peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"),
    "raw pile": ("pct+", "peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]"),
    "bands ≤ 1.26 kHz": ("dB", "max_band_level_deviation_to_1259_Hz [dB]"),
    "bands ≤ 4 kHz": ("dB", "max_band_level_deviation_to_3981_Hz [dB]"),
}
"""The columns of docs/validation.md's table (the rows keep the run's real-time factor too, but
the docs do not show it: a study's wall times on a shared machine are not a speed measurement,
benchmarks/bench_engine.py is)."""


ROW_KEYS = ("fmax [Hz]", "n_modes", "ram_modes", "time_step [s]", "realtime_factor [-]",
            "max_band_level_deviation_to_1259_Hz [dB]", "max_band_level_deviation_to_3981_Hz [dB]")
"""The keys of a row's own (the others are errors in a band)."""


def doc_cell(row: dict, key: str):
    """A figure of a row: its own, or an error in :data:`DOC_BAND`."""
    return row[key] if key in ROW_KEYS else row["bands"][DOC_BAND][key]


def write_docs_table(system: Path, rows: list[dict], duration: float,
                     command: str | None = None) -> None:
    """docs/data/study_fmax.json: the table of docs/validation.md (static correction on, the
    default fmax in bold) and the numbers its prose quotes."""
    on = [r for r in rows if r["static_correction"]]
    off = [r for r in rows if not r["static_correction"] and r["fmax [Hz]"] >= 5000.0]
    default = next(r for r in on if r["fmax [Hz]"] == 5000.0)
    top = max(on, key=lambda r: r["fmax [Hz]"])
    from_default = [r for r in on if r["fmax [Hz]"] >= 5000.0]
    table = {"columns": list(DOC_COLUMNS), "formats": [f for f, _ in DOC_COLUMNS.values()],
             "rows": [{"bold": r is default, "cells": [doc_cell(r, k) for _, k in
                                                       DOC_COLUMNS.values()]} for r in on]}

    def over(selection, key, pick):
        return pick(doc_cell(r, key) for r in selection)

    ram_off = "peak_ram_anvil_force_error [-]"
    rms_ram = "ram_anvil_force_normalised_rms_error [-]"
    subs = {
        "default_ram_peak": [doc_cell(default, ram_off), "pct+"],
        "top_ram_peak": [doc_cell(top, ram_off), "pct+"],
        "default_pile_peak": [doc_cell(default, "peak_anvil_pile_force_error [-]"), "pct+"],
        "top_pile_peak": [doc_cell(top, "peak_anvil_pile_force_error [-]"), "pct+"],
        "top_fmax_khz": [top["fmax [Hz]"] / 1e3, "sig2"],
        "top_ram_modes": [top["ram_modes"], "int"],
        "no_correction_ram_peak_min": [over(off, ram_off, min), "pct"],
        "no_correction_ram_peak_max": [over(off, ram_off, max), "pct"],
        "no_correction_rms_ram_max": [over(off, rms_ram, max), "pct"],
        "bands_to_1k_max_from_default": [
            over(from_default, "max_band_level_deviation_to_1259_Hz [dB]", max), "dB"],
        "bands_to_4k_max": [over(on, "max_band_level_deviation_to_3981_Hz [dB]", max), "dB"],
        "default_time_step_us": [default["time_step [s]"] * 1e6, "f1"],
    }
    write_doc_data(
        "study_fmax", about="The fmax study on Table 1 (docs/validation.md, \"The fmax study\"): "
        "errors of the ROM against the FEA, every series low-passed at 5 kHz.",
        inputs=system_inputs(system),
        tables={"fmax": table}, substitutions=subs,
        values={"rom": rows, "duration [s]": duration}, command=command)


if __name__ == "__main__":
    main()
