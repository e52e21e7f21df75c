"""Anvil-ring study: what an anvil ring and contact friction change in the reference FEA's
Table 1 blow.

Run: python benchmarks/study_anvil_ring.py [--out results/study_ring] [--mesh-size 0.1]
     [--truncate 10] [--friction 0 0.1 0.2 0.3] [--sleeve CLEARANCE]
     [--sleeve-friction MU ...] [--seat-only MU ...] [--rom] [--docs | --docs-from STUDY_JSON]

``--docs`` runs what docs/validation.md shows (frictions 0, 0.1, 0.2, 0.3; the sleeve 1 mm off
at 0 and 0.2; friction 0.2 on the seat only; the ROM) and writes docs/data/anvil_ring.json;
``--docs-from`` rewrites that file from an earlier run's study.json.

With ``--rom`` the ring-less run is also run with the anvil unit alone (the baseline) and
every ring run with the ROM stack
(:class:`anvilwave.anvil_rom.stack.StackUnit`: anvil and ring each their own modes to the
system's 5 kHz with static correction, the seat in rings, the ring's pile port in rings, the
seat friction coefficient of the run; the ring-pile contact frictionless, as the ROM's 1D pile
head has no radial motion) between the modal ram and the 1D pile without soil
(:func:`anvilwave.analyses.stack_blow.run_stack_blow`, the system's 20 us step), and compared
with the FEA run (both low-passed at 5 kHz, the ROM shifted by its
half-step start): peak pile-head and ram force, the RMS of the difference over the window
relative to the FEA signal's RMS, the largest band-level difference from 50 Hz to 4 kHz, and
the ROM unit's energy balance (its energy change plus friction and dashpot dissipation
against the work the ram and the pile did on it, largest over the blow, as a fraction of the
blow's kinetic energy). The rings at mu 0 and 0.2 are also run with one approximation changed
at a time (:data:`ROM_VARIANTS`: one seat ring and one pile ring, one pile ring, the ring's
modes to 12 kHz, no static correction), against the same FEA run.

The paper's Table 1 stack (anvilwave/examples/table1.toml through
:func:`anvilwave.analyses.compare.fea_config`: the 275 t, D 1.8 m ram at 6.16 m/s, the xl8
anvil, the 8000 x 140 mm pile) in the reference FEA, once as today (the anvil on the pile)
and once with the illustrative anvil ring anvilwave/examples/anvils/xl8_ring.toml between
anvil and pile, for each friction coefficient (the same on the anvil-ring seat and the
ring-pile contact; with ``--sleeve`` each ring run also once inside a rigid guiding sleeve
that radial clearance [m] off the anvil's and ring's 4.15 m outer radius, the same coefficient
against it). The pile is cut at ``--truncate`` m below its head with the absorbing
"shell" boundary (a 10 m cut changes the anvil-pile force by at most 2.6 % of its peak
against the full 80 m pile, anvilwave.fea.impact.absorbing_speeds); the window is the
system's 25 ms.

Per run it prints and writes (study.json): the pile-head force (the force into the pile) low-
passed at 5 kHz, its peak, its rise (10 % to 90 % of the peak, first crossings) and the
largest deviation of its one-third-octave band levels from the reference run's, from the
lowest band above 1 / T (50 Hz) up to the 4 kHz band
(the ring-less stack for the ring at friction 0, the ring at friction 0 for the others), the
ram force peak, the energy the friction dissipated and the energy balance residual (both as
fractions of the blow's kinetic energy), and the wall time.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from anvilwave.analyses.compare import fea_config, lowpass, without_soil
from anvilwave.analyses.stack_blow import SEAT_RINGS, run_stack_blow, stack_unit
from anvilwave.anvil_rom.fem.geometry import load_anvil
from anvilwave.config.system import load_system
from anvilwave.fea.impact import run_impact_fea
from anvilwave.pile.post.spectra import band_numbers_between, third_octave_band_energies

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
CUTOFF = 5000.0  # [Hz] the comparison low-pass
TOP_BAND = 4000.0  # [Hz] highest band compared
ROM_VARIANTS = {
    "1 seat ring, 1 pile ring": {"seat_rings": 1, "pile_rings": 1},
    f"{SEAT_RINGS} seat rings, 1 pile ring": {"pile_rings": 1},
    "ring's modes to 12 kHz": {"ring_fmax": 12000.0},
    "no static correction": {"static_correction": False},
}
"""ROM variants of the ring runs at mu 0 and 0.2 (keyword -> stack_unit, or the system's
static correction), each one approximation away from the default stack."""
DOCS_FRICTION = (0.0, 0.1, 0.2, 0.3)
DOCS_SLEEVE = (0.001, (0.0, 0.2))
DOCS_SEAT_ONLY = (0.2,)


def first_crossing(t, f, level):
    """First time [s] ``f`` exceeds ``level`` (linear interpolation)."""
    i = int(np.argmax(f > level))
    return float(t[i - 1] + (level - f[i - 1]) / (f[i] - f[i - 1]) * (t[i] - t[i - 1]))


def summary(result):
    """The figures of one run."""
    t = result.time
    head = lowpass(t, result.anvil_pile_force, CUTOFF)
    ram = lowpass(t, result.ram_anvil_force, CUTOFF)
    rise = head - head[0]
    peak = float(rise.max())
    e = result.energies
    e0 = float(e["kinetic"][0])
    numbers = band_numbers_between(8.9, TOP_BAND)
    bands = third_octave_band_energies(result.anvil_pile_force - result.anvil_pile_force[0],
                                       float(t[1] - t[0]), numbers)
    return {
        "peak_pile_head_force [N]": float(head.max()),
        "pile_head_rise_10_90 [s]": first_crossing(t, rise, 0.9 * peak)
        - first_crossing(t, rise, 0.1 * peak),
        "peak_ram_force [N]": float(ram.max()),
        "friction_energy [-]": float(e["friction"][-1]) / e0 if "friction" in e else 0.0,
        "energy_balance_residual [-]": float(np.abs(e["total"] - e["total"][0]).max()) / e0,
        "wall_time [s]": result.wall_time + result.setup_time,
        "band_centre [Hz]": [float(x) for x in bands.centre_frequency],
        "band_level [dB]": [float(x) for x in bands.level],
        "band_lower_edge [Hz]": [float(x) for x in bands.lower_frequency],
        "valid_from [Hz]": float(bands.valid_range[0]),
    }


def rom_against_fea(cfg, ring, mu, fea, mesh_size, **variant):
    """The ROM stack's blow against the FEA run ``fea`` (module docstring); ``variant``:
    keywords of :func:`stack_unit`, or ``static_correction`` of the system's anvil."""
    start = time.perf_counter()
    if "static_correction" in variant:
        cfg = dataclasses.replace(cfg, anvil=dataclasses.replace(
            cfg.anvil, static_correction=variant.pop("static_correction")))
    blow = run_stack_blow(cfg, stack_unit(cfg, ring, seat_friction=mu, penalty_size=mesh_size,
                                          **variant))
    wall = time.perf_counter() - start
    t = fea.time
    h = float(blow.time[1] - blow.time[0])
    rom_t = blow.time - 0.5 * h  # first contact at t = 0, as the FEA
    row = {"rom_wall_time [s]": wall}
    numbers = band_numbers_between(8.9, TOP_BAND)
    for name, rom, ref in (("pile", blow.pile_force, fea.anvil_pile_force),
                           ("ram", blow.ram_force, fea.ram_anvil_force)):
        r = lowpass(t, np.interp(t, rom_t, rom), CUTOFF)
        f = lowpass(t, ref, CUTOFF)
        row[f"{name}_peak_rom [N]"] = float(r.max())
        row[f"{name}_peak_fea [N]"] = float(f.max())
        row[f"{name}_peak_error [-]"] = float(r.max() / f.max() - 1.0)
        row[f"{name}_rms_error [-]"] = float(np.sqrt(np.mean((r - f) ** 2) / np.mean(f**2)))
        if name == "pile":
            dt = float(t[1] - t[0])
            a = third_octave_band_energies(np.interp(t, rom_t, rom) - rom[0], dt, numbers)
            b = third_octave_band_energies(ref - ref[0], dt, numbers)
            inside = (b.lower_frequency >= b.valid_range[0]) & (b.centre_frequency <= TOP_BAND)
            deviation = np.where(inside, a.level - b.level, 0.0)
            worst = int(np.argmax(np.abs(deviation)))
            row["band_error_max [dB]"] = float(abs(deviation[worst]))
            row["band_error_at [Hz]"] = float(b.centre_frequency[worst])
            row["band_error [dB]"] = [float(x) for x in deviation]
    row["rom_friction_energy [-]"] = blow.friction_energy / blow.input_energy
    row["rom_energy_balance [-]"] = float(np.abs(blow.energy_residual).max()
                                          / blow.input_energy)
    return row


def main(argv=None):
    """Run the study and write ``study.json`` to ``--out`` (and the docs' file)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/study_ring")
    parser.add_argument("--mesh-size", type=float, default=0.1)
    parser.add_argument("--truncate", type=float, default=10.0)
    parser.add_argument("--friction", type=float, nargs="+", default=[0.0, 0.1, 0.2, 0.3])
    parser.add_argument("--sleeve", type=float, default=None)
    parser.add_argument("--sleeve-friction", type=float, nargs="+", default=None)
    parser.add_argument("--seat-only", type=float, nargs="*", default=[])
    parser.add_argument("--rom", action="store_true")
    parser.add_argument("--docs", action="store_true")
    parser.add_argument("--docs-from", type=Path, default=None)
    args = parser.parse_args(argv)
    if args.docs_from is not None:
        write_docs(json.loads(args.docs_from.read_text()),
                   "python benchmarks/study_anvil_ring.py --docs")
        return
    if args.docs:
        args.friction, args.rom = list(DOCS_FRICTION), True
        args.sleeve, args.sleeve_friction = DOCS_SLEEVE[0], list(DOCS_SLEEVE[1])
        args.seat_only = list(DOCS_SEAT_ONLY)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    base = fea_config(load_system(EXAMPLES / "table1.toml"), mesh_size=args.mesh_size,
                      truncate_length=args.truncate)
    ring = load_anvil(EXAMPLES / "anvils" / "xl8_ring.toml")
    cases = {"no ring": base}
    for mu in args.friction:
        cases[f"ring, mu {mu:g}"] = dataclasses.replace(base, ring=ring, seat_friction=mu,
                                                        pile_friction=mu)
    if args.sleeve is not None:
        outer = float(max(base.anvil.outline[:, 0].max(), ring.outline[:, 0].max()))
        for mu in args.sleeve_friction or args.friction:
            cases[f"+sleeve, mu {mu:g}"] = dataclasses.replace(
                base, ring=ring, seat_friction=mu, pile_friction=mu,
                sleeve_radius=outer + args.sleeve, sleeve_friction=mu)
    for mu in args.seat_only:
        cases[f"seat only, mu {mu:g}"] = dataclasses.replace(base, ring=ring, seat_friction=mu,
                                                             pile_friction=0.0)
    rows = {}
    system = without_soil(load_system(EXAMPLES / "table1.toml"))
    roms = {}
    for name, config in cases.items():
        start = time.perf_counter()
        result = run_impact_fea(config)
        rows[name] = summary(result)
        print(f"{name}: {time.perf_counter() - start:.0f} s", flush=True)
        if args.rom and not name.startswith("+sleeve"):
            body = None if config.ring is None else ring
            roms[name] = rom_against_fea(system, body, config.seat_friction, result,
                                         args.mesh_size)
            rows[name]["rom"] = roms[name]
            if name in ("ring, mu 0", "ring, mu 0.2"):
                rows[name]["rom_variants"] = {
                    v: rom_against_fea(system, ring, config.seat_friction, result,
                                       args.mesh_size, **kw) for v, kw in ROM_VARIANTS.items()}
    names = list(rows)
    for name in names[1:]:
        reference = rows[names[0] if name == names[1] else names[1]]
        levels = np.array(rows[name]["band_level [dB]"])
        ref = np.array(reference["band_level [dB]"])
        centre = np.array(rows[name]["band_centre [Hz]"])
        lower = np.array(rows[name]["band_lower_edge [Hz]"])
        inside = (lower >= rows[name]["valid_from [Hz]"]) & (centre <= TOP_BAND)
        deviation = np.where(inside, levels - ref, 0.0)
        worst = int(np.argmax(np.abs(deviation)))
        rows[name]["max_band_deviation_to_4kHz [dB]"] = float(abs(deviation[worst]))
        rows[name]["band_of_max_deviation [Hz]"] = float(centre[worst])
        rows[name]["band_deviation [dB]"] = [float(x) for x in deviation]
    print(f"{'case':18s} {'pile peak':>10s} {'rise':>8s} {'ram peak':>10s} {'bands':>7s} "
          f"{'friction':>9s} {'balance':>8s}")
    for name, r in rows.items():
        print(f"{name:18s} {r['peak_pile_head_force [N]'] / 1e6:8.1f}MN "
              f"{r['pile_head_rise_10_90 [s]'] * 1e3:6.2f}ms "
              f"{r['peak_ram_force [N]'] / 1e6:8.1f}MN "
              f"{r.get('max_band_deviation_to_4kHz [dB]', 0.0):5.2f}dB "
              f"@{r.get('band_of_max_deviation [Hz]', 0.0):5.0f}Hz "
              f"{r['friction_energy [-]'] * 100:7.2f} % "
              f"{r['energy_balance_residual [-]'] * 100:6.3f} %")
    if roms:
        print(f"{'ROM vs FEA':18s} {'pile peak':>10s} {'ram peak':>9s} {'pile rms':>9s} "
              f"{'ram rms':>8s} {'bands':>13s} {'friction':>9s} {'balance':>8s}")
    for name, r in roms.items():
        variants = rows[name].get("rom_variants", {})
        for label, v in [(name, r), *((f"  {k}", x) for k, x in variants.items())]:
            print(f"{label[:30]:30s} {v['pile_peak_error [-]'] * 100:+8.2f} % "
                  f"{v['ram_peak_error [-]'] * 100:+7.2f} % "
                  f"{v['pile_rms_error [-]'] * 100:7.2f} % "
                  f"{v['ram_rms_error [-]'] * 100:6.2f} % {v['band_error_max [dB]']:5.2f}dB "
                  f"@{v['band_error_at [Hz]']:5.0f}Hz "
                  f"{v['rom_friction_energy [-]'] * 100:7.2f} % "
                  f"{v['rom_energy_balance [-]'] * 100:6.3f} %")
    study = {"mesh_size [m]": args.mesh_size, "truncate_length [m]": args.truncate,
             "runs": rows}
    (out / "study.json").write_text(json.dumps(study, indent=1))
    if args.docs:
        write_docs(study)


FEA_ROWS = {"no ring": "anvil on the pile", "ring, mu 0": "ring, mu 0",
            "ring, mu 0.1": "ring, mu 0.1", "ring, mu 0.2": "ring, mu 0.2",
            "ring, mu 0.3": "ring, mu 0.3", "+sleeve, mu 0": "ring + sleeve 1 mm off, mu 0",
            "+sleeve, mu 0.2": "ring + sleeve 1 mm off, mu 0.2",
            "seat only, mu 0.2": "ring, mu 0.2 on the seat only"}
"""The FEA runs of the docs' table, study name -> row label."""

ROM_ROWS = {"no ring": "no ring (the anvil unit; the runner does not book its ram dashpot's "
                       "work)", "ring, mu 0": "ring, mu 0",
            "ring, mu 0.2": "ring, mu 0.2",
            "seat only, mu 0.2": "ring, mu 0.2 (FEA: seat only)"}
"""The ROM comparisons of the docs' table, study name -> row label (then each ring run's
:data:`ROM_VARIANTS` below it)."""


def _band(value, at):
    """A band cell: the level difference and its band."""
    centre = f"{at / 1e3:.3g} kHz" if at >= 1e3 else f"{at:.0f} Hz"
    return f"{value:.1f} dB ({centre})"


def docs_tables(runs: dict) -> dict:
    """The two tables of docs/validation.md from study.json's runs (the FEA runs, the ROM
    against them)."""
    fea = []
    for name, label in FEA_ROWS.items():
        if name not in runs:
            continue
        r = runs[name]
        band = r.get("max_band_deviation_to_4kHz [dB]")
        fea.append([label, r["peak_pile_head_force [N]"], r["pile_head_rise_10_90 [s]"],
                    r["peak_ram_force [N]"],
                    None if band is None else _band(band, r["band_of_max_deviation [Hz]"]),
                    r["friction_energy [-]"], r["energy_balance_residual [-]"]])
    rom = []
    for name, label in ROM_ROWS.items():
        if name not in runs or "rom" not in runs[name]:
            continue
        entries = [(label, runs[name]["rom"])]
        entries += [(f"{label}: {k}", v) for k, v in runs[name].get("rom_variants", {}).items()]
        for text, v in entries:
            row = [text, v["pile_peak_error [-]"], v["ram_peak_error [-]"],
                   v["pile_rms_error [-]"], v["ram_rms_error [-]"],
                   _band(v["band_error_max [dB]"], v["band_error_at [Hz]"]),
                   v["rom_friction_energy [-]"], v["rom_energy_balance [-]"]]
            default = text == label and name in ("ring, mu 0", "ring, mu 0.2")
            rom.append({"bold": True, "cells": row} if default else row)
    return {
        "fea": {"columns": ["stack", "pile-head peak", "rise 10-90 %", "ram peak", "bands",
                            "friction energy", "balance"],
                "formats": [None, "MN", "ms2", "MN", None, "pctsig2", "pctsig2"],
                "rows": fea},
        "rom": {"columns": ["stack", "pile peak", "ram peak", "pile RMS", "ram RMS", "bands",
                            "ROM friction energy", "ROM balance"],
                "formats": [None, "pct+", "pct+", "pct1", "pct1", None, "pctsig2", "pctsig2"],
                "rows": rom},
    }


def write_docs(study: dict, command: str | None = None) -> None:
    """docs/data/anvil_ring.json from a study.json (the FEA runs and the ROM against them)."""
    # lazy: benchmarks/doc_data.py is on the path when this runs as a script, not when the
    # tests load this file by its path
    from doc_data import system_inputs, write_doc_data

    write_doc_data("anvil_ring", about="the anvil ring and contact friction: the reference FEA "
                   "stack and the ROM stack against it (docs/validation.md, \"The anvil ring "
                   "and contact friction\")",
                   inputs=[*system_inputs(EXAMPLES / "table1.toml"),
                           EXAMPLES / "anvils" / "xl8_ring.toml"],
                   tables=docs_tables(study["runs"]), values=study, command=command)


if __name__ == "__main__":
    main()
