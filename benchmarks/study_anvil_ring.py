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
DOCS_MESH = 0.05
"""[m] the reference FEA's mesh in the docs' run (its penalty contacts E / h per area make its
error first order in h: 0.1 m is 7 % off 0.05 m in the pile-head RMS, docs/validation.md)."""
DOCS_REFERENCE_MESHES = (0.1, 0.07)
"""[m] the coarser meshes the docs' run also runs the ROM's two reference cases on, for the
reference's own mesh error."""
REFERENCE_RUNS = ("ring, mu 0", "ring, mu 0.2")
"""The runs whose FEA is repeated on the coarser meshes (the ROM's two bars)."""


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


def series_against_fea(t_model, pile, ram, fea):
    """A model's pile-head and ram force series against the FEA run ``fea`` (module
    docstring): both low-passed at 5 kHz on the FEA's grid, the peaks, the RMS of the
    difference relative to the FEA signal's, the pile-head band-level differences."""
    t = fea.time
    row = {}
    numbers = band_numbers_between(8.9, TOP_BAND)
    for name, model, ref in (("pile", pile, fea.anvil_pile_force),
                             ("ram", ram, fea.ram_anvil_force)):
        r = lowpass(t, np.interp(t, t_model, model), CUTOFF)
        f = lowpass(t, ref, CUTOFF)
        row[f"{name}_peak_rom [N]"] = float(r.max())
        row[f"{name}_peak_fea [N]"] = float(f.max())
        row[f"{name}_peak_error [-]"] = float(r.max() / f.max() - 1.0)
        row[f"{name}_rms_error [-]"] = float(np.sqrt(np.mean((r - f) ** 2) / np.mean(f**2)))
        if name == "pile":
            dt = float(t[1] - t[0])
            a = third_octave_band_energies(np.interp(t, t_model, model) - model[0], dt, numbers)
            b = third_octave_band_energies(ref - ref[0], dt, numbers)
            inside = (b.lower_frequency >= b.valid_range[0]) & (b.centre_frequency <= TOP_BAND)
            deviation = np.where(inside, a.level - b.level, 0.0)
            worst = int(np.argmax(np.abs(deviation)))
            row["band_error_max [dB]"] = float(abs(deviation[worst]))
            row["band_error_at [Hz]"] = float(b.centre_frequency[worst])
            row["band_error [dB]"] = [float(x) for x in deviation]
    return row


def rom_against_fea(cfg, ring, mu, fea, penalty_size, **variant):
    """The ROM stack's blow against the FEA run ``fea`` (module docstring); ``penalty_size``:
    the FEA's penalty length [m] (its mesh size over its contact stiffness factor), the seat's;
    ``variant``: keywords of :func:`stack_unit`, or ``static_correction`` of the system's
    anvil."""
    start = time.perf_counter()
    if "static_correction" in variant:
        cfg = dataclasses.replace(cfg, anvil=dataclasses.replace(
            cfg.anvil, static_correction=variant.pop("static_correction")))
    blow = run_stack_blow(cfg, stack_unit(cfg, ring, seat_friction=mu,
                                          penalty_size=penalty_size, **variant))
    wall = time.perf_counter() - start
    h = float(blow.time[1] - blow.time[0])
    rom_t = blow.time - 0.5 * h  # first contact at t = 0, as the FEA
    row = {"rom_wall_time [s]": wall,
           **series_against_fea(rom_t, blow.pile_force, blow.ram_force, fea)}
    row["rom_friction_energy [-]"] = blow.friction_energy / blow.input_energy
    row["rom_energy_balance [-]"] = float(np.abs(blow.energy_residual).max()
                                          / blow.input_energy)
    return row


def reference_error(coarse: dict, fine, h_coarse: float, h_fine: float) -> dict:
    """The reference FEA's own mesh error: the coarser mesh's runs against the study mesh's
    (the same figures as the ROM's), and their first-order extrapolation to the study mesh's
    error (the penalty contacts' compliance, E / h per area, is the leading error and falls as
    h: err(h_fine) ~ d * h_fine / (h_coarse - h_fine)), per run name."""
    scale = h_fine / (h_coarse - h_fine)
    out = {}
    for name, result in coarse.items():
        d = series_against_fea(result.time, result.anvil_pile_force, result.ram_anvil_force,
                               fine[name])
        d = {k: v for k, v in d.items() if k != "band_error [dB]"}
        d["estimated_error_at_study_mesh"] = {
            key: abs(d[key]) * scale for key in ("pile_peak_error [-]", "ram_peak_error [-]",
                                                  "pile_rms_error [-]", "ram_rms_error [-]",
                                                  "band_error_max [dB]")}
        out[name] = d
    return out


def observed_order(d1: float, d2: float, h1: float, h2: float, h: float) -> float:
    """Order p of a difference that falls as h^p: d1 = C (h1^p - h^p), d2 = C (h2^p - h^p),
    h1 > h2 > h, solved by bisection on p in (0, 4] (0 when the ratio is at or below its
    p -> 0 limit, log(h1 / h) / log(h2 / h))."""
    def ratio(p):
        return (h1**p - h**p) / (h2**p - h**p)
    target = d1 / d2
    if target <= np.log(h1 / h) / np.log(h2 / h):
        return 0.0
    lo, hi = 1e-6, 4.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) < target else (lo, mid)
    return 0.5 * (lo + hi)


def observed_orders(blocks: dict, meshes, h: float) -> dict:
    """Observed order of the pile-head RMS difference per reference run, from the two coarser
    meshes against the study mesh ``h``, and the study mesh's error at that order,
    d2 h^p / (h2^p - h^p) (None at p < 0.25: not in the asymptotic range)."""
    h1, h2 = sorted(meshes, reverse=True)
    out = {}
    for name in blocks[f"mesh {h1:g} m"]:
        d1 = blocks[f"mesh {h1:g} m"][name]["pile_rms_error [-]"]
        d2 = blocks[f"mesh {h2:g} m"][name]["pile_rms_error [-]"]
        p = observed_order(d1, d2, h1, h2, h)
        out[name] = {"order [-]": p, "pile_rms_error_at_study_mesh [-]":
                     d2 * h**p / (h2**p - h**p) if p >= 0.25 else None}
    return out


def main(argv=None):
    """Run the study and write ``study.json`` to ``--out`` (and the docs' file)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/study_ring")
    parser.add_argument("--mesh-size", type=float, default=0.1)
    parser.add_argument("--contact-factor", type=float, default=1.0)
    parser.add_argument("--reference-meshes", type=float, nargs="*", default=[])
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
        args.mesh_size, args.reference_meshes = DOCS_MESH, list(DOCS_REFERENCE_MESHES)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    base = dataclasses.replace(
        fea_config(load_system(EXAMPLES / "table1.toml"), mesh_size=args.mesh_size,
                   truncate_length=args.truncate), contact_stiffness_factor=args.contact_factor)
    penalty = args.mesh_size / args.contact_factor
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
    fine = {}
    for name, config in cases.items():
        start = time.perf_counter()
        result = run_impact_fea(config)
        if name in REFERENCE_RUNS:
            fine[name] = result
        rows[name] = summary(result)
        print(f"{name}: {time.perf_counter() - start:.0f} s", flush=True)
        if args.rom and not name.startswith("+sleeve"):
            body = None if config.ring is None else ring
            roms[name] = rom_against_fea(system, body, config.seat_friction, result,
                                         penalty)
            rows[name]["rom"] = roms[name]
            if name in ("ring, mu 0", "ring, mu 0.2"):
                rows[name]["rom_variants"] = {
                    v: rom_against_fea(system, ring, config.seat_friction, result,
                                       penalty, **kw) for v, kw in ROM_VARIANTS.items()}
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
             "contact_stiffness_factor [-]": args.contact_factor, "runs": rows}
    if args.reference_meshes:
        study["reference_error"] = {}
        for h in args.reference_meshes:
            coarse = {}
            for name in REFERENCE_RUNS:
                if name in fine:
                    start = time.perf_counter()
                    coarse[name] = run_impact_fea(dataclasses.replace(
                        cases[name], mesh_size=h))
                    print(f"{name} at mesh {h:g} m: {time.perf_counter() - start:.0f} s",
                          flush=True)
            study["reference_error"][f"mesh {h:g} m"] = reference_error(
                coarse, fine, h, args.mesh_size)
        if len(args.reference_meshes) >= 2:
            study["reference_order"] = observed_orders(study["reference_error"],
                                                       args.reference_meshes[:2],
                                                       args.mesh_size)
            print("observed orders of the reference's pile-head RMS difference:",
                  study["reference_order"])
        for label, block in study["reference_error"].items():
            for name, d in block.items():
                e = d["estimated_error_at_study_mesh"]
                print(f"{name} {label} against {args.mesh_size:g} m: "
                      f"pile {d['pile_peak_error [-]'] * 100:+.2f} % "
                      f"ram {d['ram_peak_error [-]'] * 100:+.2f} % "
                      f"pile RMS {d['pile_rms_error [-]'] * 100:.1f} % "
                      f"bands {d['band_error_max [dB]']:.1f} dB; estimated error of the "
                      f"study mesh: pile RMS {e['pile_rms_error [-]'] * 100:.1f} %, "
                      f"bands {e['band_error_max [dB]']:.1f} dB")
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


def docs_tables(runs: dict, reference: dict | None = None,
                orders: dict | None = None) -> dict:
    """The tables of docs/validation.md from study.json's runs (the FEA runs, the ROM against
    them) and, when given, its ``reference_error`` and ``reference_order`` (the reference
    FEA on coarser meshes against the study mesh)."""
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
    tables = {}
    if reference:
        rows = []
        for label, block in reference.items():
            for name, d in block.items():
                order = (orders or {}).get(name, {}).get("order [-]")
                rows.append([f"{name}, {label}", d["pile_peak_error [-]"],
                             d["ram_peak_error [-]"], d["pile_rms_error [-]"],
                             d["ram_rms_error [-]"],
                             _band(d["band_error_max [dB]"], d["band_error_at [Hz]"]),
                             None if order is None else f"{order:.2f}"])
        tables["reference"] = {
            "columns": ["reference FEA", "pile peak", "ram peak", "pile RMS", "ram RMS",
                        "bands", "observed order"],
            "formats": [None, "pct+", "pct+", "pct1", "pct1", None, None], "rows": rows}
    return tables | {
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
                   tables=docs_tables(study["runs"], study.get("reference_error"),
                                      study.get("reference_order")),
                   values=study, command=command)


if __name__ == "__main__":
    main()
