"""The demo's figures for the docs: docs/data/demo.json (docs/demo.md, docs/validation.md).

Run: python benchmarks/doc_demo.py [--demo DIR] [--substitutions-only]

DIR is the folder of an ``anvilwave demo --out DIR`` run (default: run the demo into a
temporary folder first, about a minute and a half). From its comparison.json and summary.json:
the ROM (FMUs) and the lumped anvil against the FEA, the anvil's lift-off intervals, the
interfaces-resolved ROM (the demo's step 4) and the pile-head force band levels of all three.
Then, with the in-process engine against the demo's FEA (fea.csv), the Table 1 variants the
docs quote: Smith's rod ram instead of the modal ram, each ram without the ram-impedance contact
dashpot, the pile port in three rings (``pile_port_rings = 3``), and three rings on the tube head
(``pile_head = "tube"``). Every error is in the demo's comparison band (5 kHz), as in
:func:`anvilwave.analyses.compare.metrics`. tests/test_compare.py checks the file against its
own demo run.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
from doc_data import DOC_DATA, system_inputs, write_doc_data

from anvilwave.analyses.compare import ModelRun, band_levels, metrics, without_soil
from anvilwave.cli import main as anvilwave_main
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.output.examples import EXAMPLES_DIR
from anvilwave.output.tables import read_csv

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = EXAMPLES_DIR  # the installed package's (the checkout's in an editable install)
TABLE1 = EXAMPLES / "table1.toml"
INTERFACES = EXAMPLES / "table1_interfaces.toml"
SPECTRA_BANDS = (100.0, 251.0, 501.0, 1000.0, 1259.0, 1585.0, 1995.0, 2512.0, 3162.0, 3981.0)
"""[Hz] the one-third-octave bands (nominal centres) of the docs' band-level table."""

VARIANTS = {
    # name: (what it changes, [(key of [hammer] or [anvil], TOML value)])
    "rod_ram": ("Smith's rod ram", [("hammer", "ram_model", '"rod"')]),
    "modal_ram_no_dashpot": ("no ram contact dashpot",
                             [("anvil", "ram_contact_damping", "0.0")]),
    "rod_ram_no_dashpot": ("Smith's rod ram, no ram contact dashpot",
                           [("hammer", "ram_model", '"rod"'),
                            ("anvil", "ram_contact_damping", "0.0")]),
    "pile_rings_3": ("pile_port_rings = 3", [("anvil", "pile_port_rings", "3")]),
    "pile_rings_3_tube": ('pile_port_rings = 3, pile_head = "tube"',
                          [("anvil", "pile_port_rings", "3"), ("anvil", "pile_head", '"tube"')]),
}
"""The Table 1 variants run against the demo's FEA (the in-process engine)."""


def variant_text(text: str, changes: list[tuple[str, str, str]]) -> str:
    """table1.toml's text with ``key = value`` set in its ``[table]`` (replaced, or added as the
    table's first key), the anvil file as an absolute path."""
    text = text.replace('file = "anvils/', f'file = "{EXAMPLES.as_posix()}/anvils/')
    for table, key, value in changes:
        line = re.compile(rf"^{key}\s*=.*$", re.M)
        start = text.index(f"[{table}]\n")
        end = text.find("\n[", start + 1)
        body = text[start:end]
        if line.search(body):
            body = line.sub(f"{key} = {value}", body, count=1)
        else:
            body = body.replace(f"[{table}]\n", f"[{table}]\n{key} = {value}\n", 1)
        text = text[:start] + body + text[end:]
    return text


def variant_config(name: str):
    """The free-pile system of a variant of Table 1 (:data:`VARIANTS`)."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"table1_{name}.toml"
        path.write_text(variant_text(TABLE1.read_text(), VARIANTS[name][1]))
        return without_soil(load_system(path))


def run_variant(name: str, fea: ModelRun, bandwidth: float) -> tuple[dict, ModelRun]:
    """A variant's metrics against the demo's FEA, and its run."""
    blow = build_engine(variant_config(name)).run()[0]
    run = ModelRun("rom", blow.columns, blow.wall_time, {"engine": "direct"})
    preload = float(fea.columns["anvil_pile_force [N]"][0])
    return metrics(run, fea, preload, bandwidth), run


def band_deviations(spectra: dict, model: str) -> list[float | None]:
    """A model's band-level deviations from the FEA [dB] at :data:`SPECTRA_BANDS`."""
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    deviation = spectra["deviation_from_fea [dB]"][model]
    out = []
    for band in SPECTRA_BANDS:
        i = int(np.argmin(np.abs(centre - band)))
        assert abs(centre[i] / band - 1.0) < 0.01, (band, centre[i])
        out.append(deviation[i])
    return out


def _bands_between(spectra: dict, model: str, low: float, high: float):
    """|deviation| [dB] and centres [Hz] of a model's valid bands with nominal centres from
    ``low`` to ``high`` [Hz]."""
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool)
    deviation = np.array([np.nan if d is None else d
                          for d in spectra["deviation_from_fea [dB]"][model]])
    inside = valid & (centre >= 0.99 * low) & (centre <= 1.01 * high)
    return np.abs(deviation[inside]), centre[inside]


def band_extreme(spectra: dict, model: str, low: float, high: float) -> tuple[float, float]:
    """The largest |deviation| [dB] of a model's valid bands from ``low`` to ``high`` [Hz],
    and that band's centre [Hz]."""
    deviation, centre = _bands_between(spectra, model, low, high)
    i = int(np.nanargmax(deviation))
    return float(deviation[i]), float(centre[i])


def band_smallest(spectra: dict, model: str, low: float, high: float) -> float:
    """The smallest |deviation| [dB] of a model's valid bands from ``low`` to ``high`` [Hz]."""
    return float(np.nanmin(_bands_between(spectra, model, low, high)[0]))


COMPARISON_COLUMNS = {
    "peak ram force": ("pct+", "peak_ram_anvil_force_error [-]"),
    "peak pile force": ("pct+", "peak_anvil_pile_force_error [-]"),
    "raw ram peak": ("pct+", "peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"),
    "raw pile peak": ("pct+", "peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]"),
    "pile force arrival": ("ms+", "pile_force_arrival_error [s]"),
    "RMS ram force": ("pct", "ram_anvil_force_normalised_rms_error [-]"),
    "RMS pile force": ("pct", "anvil_pile_force_normalised_rms_error [-]"),
}
"""The columns of docs/demo.md's table: (format, metric)."""


def value_substitutions(values: dict) -> dict:
    """The numbers the prose quotes that follow from the file's ``values`` alone (the ROM's,
    the rod ram's and the rings' errors, the band levels from 1.6 to 4 kHz), so that
    tests/test_doc_tables.py can recompute them from the stored values."""
    upper = [i for i, b in enumerate(SPECTRA_BANDS) if 1500.0 < b < 4100.0]
    subs = {}
    quoted = {"rom": ("pile_peak", "ram_peak", "rms_ram", "rms_pile"),
              "rod_ram": ("pile_peak", "rms_ram"), "tube": ("pile_peak", "ram_peak"),
              "rings3": ("pile_peak", "ram_peak", "rms_ram", "rms_pile")}
    keys = {"pile_peak": ("peak_anvil_pile_force_error [-]", "pct+"),
            "ram_peak": ("peak_ram_anvil_force_error [-]", "pct+"),
            "rms_ram": ("ram_anvil_force_normalised_rms_error [-]", "pct"),
            "rms_pile": ("anvil_pile_force_normalised_rms_error [-]", "pct")}
    runs = {"rom": values["rom"], "rod_ram": values["variants"]["rod_ram"],
            "rings3": values["variants"]["pile_rings_3"],
            "tube": values["variants"]["pile_rings_3_tube"]}
    for name, figures in quoted.items():
        for figure in figures:
            key, fmt = keys[figure]
            suffix = f"{figure}_error" if figure.endswith("peak") else figure
            subs[f"{name}_{suffix}"] = [runs[name][key], fmt]
    subs["rom_raw_ram"] = [
        values["rom"]["peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"], "pct+"]
    subs["ram_modes"] = [values["summary"]["ram_modes"], "int"]
    for name, key in (("rom", "rom"), ("rings3", "pile_rings_3")):
        levels = [values["spectra"][key][i] for i in upper]
        subs[f"{name}_bands_1k6_4k_min"] = [min(levels), "dB+"]
        subs[f"{name}_bands_1k6_4k_max"] = [max(levels), "dB+"]
    return subs


def comparison_row(label: str, m: dict) -> list:
    return [label, *(m[key] for _, key in COMPARISON_COLUMNS.values())]


def lift_off(intervals: list) -> list[float]:
    """The open interval around 2 ms (the anvil's first lift-off) [s]."""
    return next(iv for iv in intervals if iv[0] < 2e-3 < iv[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--demo", type=Path, default=None,
                        help="the folder of an `anvilwave demo --out DIR` run")
    parser.add_argument("--substitutions-only", action="store_true",
                        help="only recompute the quoted numbers that follow from the stored "
                             "values of docs/data/demo.json")
    args = parser.parse_args()
    if args.substitutions_only:
        rewrite_value_substitutions()
        return
    with tempfile.TemporaryDirectory() as folder:
        demo = args.demo
        if demo is None:
            demo = Path(folder) / "demo"
            if anvilwave_main(["demo", "--out", str(demo)]) != 0:
                sys.exit("the demo failed")
        write(demo)


def write(demo: Path) -> None:
    cmp = json.loads((demo / "comparison.json").read_text())
    summary = json.loads((demo / "summary.json").read_text())
    resolved = json.loads((demo / "interfaces" / "comparison.json").read_text())
    fea = ModelRun("fea", read_csv(demo / "fea.csv"), 0.0, {})
    bandwidth = cmp["comparison_bandwidth [Hz]"]
    variants, runs = {}, {"fea": fea}
    for name in VARIANTS:
        variants[name], runs[name] = run_variant(name, fea, bandwidth)
        print(f"{name}: pile peak {variants[name]['peak_anvil_pile_force_error [-]']:+.4f}, "
              f"ram peak {variants[name]['peak_ram_anvil_force_error [-]']:+.4f}", flush=True)
    ring_spectra = band_levels(runs, bandwidth)
    spectra = cmp["pile_head_force_spectra"]
    rom_label = (f"ROM (fmax {summary['anvil_fmax [Hz]'] / 1e3:g} kHz, "
                 f"{summary['anvil_modes']} anvil modes, {summary['ram_modes']} ram modes)")
    comparison = {
        "columns": ["", *COMPARISON_COLUMNS],
        "formats": [None, *(f for f, _ in COMPARISON_COLUMNS.values())],
        "rows": [comparison_row(rom_label, cmp["rom"]),
                 comparison_row("lumped-mass anvil", cmp["lumped"]),
                 comparison_row("ROM with Smith's rod ram (in-process engine)",
                                variants["rod_ram"])]}
    comparison["rows"][2][5] = None  # the arrival: the docs compare it for the modal ram only
    spectra_table = {
        "columns": ["band [Hz]", *(f"{b:.0f}" for b in SPECTRA_BANDS)],
        "formats": [None, *["dB+"] * len(SPECTRA_BANDS)],
        "rows": [
            ["ROM", *band_deviations(spectra, "rom")],
            ["ROM, `pile_port_rings = 3`", *band_deviations(ring_spectra, "pile_rings_3")],
            ['ROM, three rings, `pile_head = "tube"` (direct engine)',
             *band_deviations(ring_spectra, "pile_rings_3_tube")],
            {"bold": False, "cells": [
                "**ROM, `anvilwave/examples/table1_interfaces.toml`** (three rings on the tube "
                "head, six ram annuli; direct engine)",
                *band_deviations(resolved["pile_head_force_spectra"], "rom")]},
            ["lumped", *band_deviations(spectra, "lumped")],
        ]}
    fea_open = lift_off(cmp["fea"]["anvil_lift_off_intervals [s]"])
    rom_open = lift_off(cmp["rom"]["anvil_lift_off_intervals [s]"])
    interfaces = summary["interfaces_rom_vs_fea"]
    subs = {
        "fea_lift_off_start_ms": [fea_open[0] * 1e3, "f1"],
        "fea_lift_off_end_ms": [fea_open[1] * 1e3, "f1"],
        "rom_lift_off_start_ms": [rom_open[0] * 1e3, "f1"],
        "rom_lift_off_end_ms": [rom_open[1] * 1e3, "f1"],
        "fea_arrival_ms": [cmp["fea"]["pile_force_arrival_time [s]"] * 1e3, "f1"],
        "lumped_ram_peak": [cmp["lumped"]["peak_ram_anvil_force_error [-]"], "pct+"],
        "interfaces_max_band_db": [interfaces["max_abs_band_deviation_to_4_kHz [dB]"], "dB2"],
        "interfaces_ram_peak": [interfaces["peak_ram_anvil_force_error [-]"], "pct+"],
        "interfaces_pile_peak": [interfaces["peak_anvil_pile_force_error [-]"], "pct+sig2"],
        "interfaces_rms_ram": [interfaces["ram_anvil_force_normalised_rms_error [-]"], "pct"],
        "interfaces_rms_pile": [interfaces["anvil_pile_force_normalised_rms_error [-]"], "pct"],
        "interfaces_raw_ram": [
            interfaces["peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"], "pct+"],
        "interfaces_raw_pile": [
            interfaces["peak_anvil_pile_force_unfiltered_vs_reference_band_error [-]"], "pct+"],
    }
    top = spectra["valid_band [Hz]"][1]
    tube_worst, tube_band = band_extreme(ring_spectra, "pile_rings_3_tube", 0.0, 4000.0)
    subs.update({
        "rom_bands_to_1k_max": [band_extreme(spectra, "rom", 0.0, 1259.0)[0], "dB"],
        "rom_bands_above_1k_max": [band_extreme(spectra, "rom", 1259.0, top)[0], "dB"],
        "lumped_from_316_min": [band_smallest(spectra, "lumped", 316.0, top), "sig2"],
        "lumped_from_316_max": [band_extreme(spectra, "lumped", 316.0, top)[0], "sig2"],
        "tube_bands_1k_4k_max": [band_extreme(ring_spectra, "pile_rings_3_tube", 1000.0,
                                              4000.0)[0], "dB"],
        "tube_bands_to_4k_max": [tube_worst, "dB"],
        "tube_worst_band": [tube_band, "int"],
        "interfaces_worst_band": [interfaces["at_band [Hz]"], "int"],
    })
    for name in ("modal_ram_no_dashpot", "rod_ram_no_dashpot"):
        m = variants[name]
        subs[f"{name}_pile_peak"] = [m["peak_anvil_pile_force_error [-]"], "pct+"]
        subs[f"{name}_ram_peak"] = [m["peak_ram_anvil_force_error [-]"], "pct+"]
        if name == "modal_ram_no_dashpot":
            subs[f"{name}_raw_ram"] = [
                m["peak_ram_anvil_force_unfiltered_vs_reference_band_error [-]"], "pct+"]
    values = {"rom": cmp["rom"], "lumped": cmp["lumped"], "interfaces": interfaces,
              "variants": variants, "summary": {k: summary[k] for k in (
                  "anvil_modes", "ram_modes", "anvil_fmax [Hz]")},
              "spectra": {"rom": band_deviations(spectra, "rom"),
                          "lumped": band_deviations(spectra, "lumped"),
                          "interfaces": band_deviations(resolved["pile_head_force_spectra"],
                                                        "rom"),
                          **{n: band_deviations(ring_spectra, n) for n in
                             ("pile_rings_3", "pile_rings_3_tube")}}}
    subs.update(value_substitutions(values))
    write_doc_data(
        "demo", about="The demo's Table 1 comparison (anvilwave demo) and the Table 1 variants "
        "run against its FEA: errors against the FEA, every series low-passed at 5 kHz.",
        inputs=system_inputs(TABLE1) + system_inputs(INTERFACES),
        command="python benchmarks/doc_demo.py",
        tables={"comparison": comparison, "spectra": spectra_table}, substitutions=subs,
        values=values)


def rewrite_value_substitutions() -> None:
    """Set docs/data/demo.json's :func:`value_substitutions` from its stored values (no rerun:
    the values, the inputs and their hashes stay as the last run wrote them)."""
    path = DOC_DATA / "demo.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    data["substitutions"].update(value_substitutions(data["values"]))
    path.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {path.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
