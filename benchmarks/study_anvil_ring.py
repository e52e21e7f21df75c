"""Anvil-ring study: what an anvil ring and contact friction change in the reference FEA's
Table 1 blow.

Run: python benchmarks/study_anvil_ring.py [--out results/study_ring] [--mesh-size 0.1]
     [--truncate 10] [--friction 0 0.1 0.2 0.3] [--sleeve CLEARANCE]
     [--sleeve-friction MU ...] [--seat-only MU ...] [--rom] [--contact-factor ALPHA]
     [--reference-meshes H ...] [--docs | --docs-from STUDY_JSON]

``--docs`` runs what docs/validation.md shows (frictions 0, 0.1, 0.2, 0.3; the sleeve 1 mm off
at 0 and 0.2; friction 0.2 on the seat only; the ROM) and writes docs/data/anvil_ring.json;
``--docs-from`` rewrites that file from an earlier run's study.json.

``--contact-factor`` scales the FEA's penalty contacts (alpha E / h per area; the ROM's seat
penalty then at the same length h / alpha). ``--reference-meshes`` runs the ring runs at mu 0
and 0.2 again at those mesh sizes: the study mesh's run against the finer of each pair (the
ROM's figures), the first-order estimate of the study mesh's own error, the observed order of
the pile-head RMS difference from the first two, and (with ``--rom``) the ROM against each
finer run (``reference_error``, ``reference_order`` in study.json; ``--docs`` takes 0.07 and
0.05 m).

With ``--rom`` the ring-less run is also run with the anvil unit alone (the baseline) and
every ring run (not the "+sleeve" ones, whose ring-pile contact has friction) with the ROM
stack of anvilwave/examples/table1_ring.toml
(:data:`ROM_SYSTEM`, :func:`rom_stack_options`: anvil and ring each their own modes to the
system's 5 kHz with static correction, the ram face in six annuli, the seat in 32 rings, the
ring's pile port in three rings on the FE tube head; the seat friction coefficient of the run,
the ring-pile contact frictionless) between the modal ram and the pile without soil
(:func:`anvilwave.analyses.stack_blow.run_stack_blow`, the system's 20 us step), and compared
with the FEA run (both low-passed at 5 kHz, the ROM shifted by its
half-step start): peak pile-head and ram force, the RMS of the difference over the window
relative to the FEA signal's RMS, the largest band-level difference from 50 Hz to 4 kHz, and
the ROM unit's energy balance (its energy change plus friction and dashpot dissipation
against the work the ram and the pile did on it, largest over the blow, as a fraction of the
blow's kinetic energy). The ROM's reference runs (:data:`REFERENCE_RUNS`: the ring at mu 0,
and mu 0.2 on the seat only, the FEA with the ROM's contacts; with ``--sleeve`` the ring in the
sleeve at each sleeve coefficient, on the seat and against the sleeve, the ring-pile contact
frictionless, and the ROM's sleeve across the same clearance, each body's outer face in
8 bands) are also run with one approximation changed at a time (:data:`ROM_VARIANTS`,
:data:`SLEEVE_VARIANTS`), against the same FEA run. The FEA runs
are read through the FEA cache (:func:`anvilwave.fea.cache.cached_impact_fea`): a rerun with
the same inputs and code takes the ROM's time only.

The paper's Table 1 stack (anvilwave/examples/table1.toml through
:func:`anvilwave.analyses.compare.fea_config`: the 275 t, D 1.8 m ram at 6.16 m/s, the xl8
anvil, the 8000 x 140 mm pile) in the reference FEA, once as today (the anvil on the pile)
and once with the illustrative anvil ring anvilwave/examples/anvils/xl8_ring.toml between
anvil and pile, for each friction coefficient (the same on the anvil-ring seat and the
ring-pile contact; with ``--sleeve`` each ring run also once inside a rigid guiding sleeve
that radial clearance [m] off the anvil's and ring's 4.15 m outer radius, the same coefficient
against it, "+sleeve", and once with the ROM's contacts, "sleeve"). The pile is cut at
``--truncate`` m below its head with the absorbing "shell" boundary (a 10 m cut changes the
anvil-pile force by at most 2.6 % of its peak against the full 80 m pile,
anvilwave.fea.impact.absorbing_speeds); the window is the system's 25 ms.

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
from anvilwave.fea.cache import cached_impact_fea
from anvilwave.pile.post.spectra import band_numbers_between, third_octave_band_energies

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
CUTOFF = 5000.0  # [Hz] the comparison low-pass
TOP_BAND = 4000.0  # [Hz] highest band compared
ROM_SYSTEM = EXAMPLES / "table1_ring.toml"
"""The system whose stack options the ROM runs (:func:`rom_stack_options`)."""
FMU_VARIANT = f"the FMU's: 1 ram port, 1D pile head, seat in {SEAT_RINGS} rings"
"""The variant that AnvilStack.fmu runs (one ram port, the 1D head, the default seat)."""
ROM_VARIANTS = {
    "1D pile head": {"pile_head": "rod"},
    f"seat in {SEAT_RINGS} rings": {"seat_rings": SEAT_RINGS},
    "seat in 16 rings": {"seat_rings": 16},
    "seat in 64 rings": {"seat_rings": 64},
    f"1D pile head, seat in {SEAT_RINGS} rings": {"pile_head": "rod", "seat_rings": SEAT_RINGS},
    "1 ram port": {"ram_annuli": 1},
    FMU_VARIANT: {"ram_annuli": 1, "pile_head": "rod", "seat_rings": SEAT_RINGS},
    "1 seat ring, 1 pile ring, 1D pile head": {"seat_rings": 1, "pile_rings": 1,
                                               "pile_head": "rod"},
    "ring's modes to 12 kHz": {"ring_fmax": 12000.0},
    "no static correction": {"static_correction": False},
}
"""ROM variants of the reference runs (keyword -> stack_unit, or the system's static
correction), each one approximation (or the FMU's set of them) away from :data:`ROM_SYSTEM`'s
stack."""
SLEEVE_VARIANTS = {
    "sleeve in 4 bands each": {"sleeve_bands": (4, 4)},
    "sleeve in 16 bands each": {"sleeve_bands": (16, 16)},
    "ring's modes to 8 kHz": {"ring_fmax": 8000.0},
    "1D pile head": {"pile_head": "rod"},
    "1 ram port": {"ram_annuli": 1},
}
"""ROM variants of the reference runs in the sleeve (the sleeve's bands, the ring's own
truncation, the pile head, the ram face), each one approximation away."""
DOCS_FRICTION = (0.0, 0.1, 0.2, 0.3)
DOCS_SLEEVE = (0.001, (0.0, 0.2))
DOCS_SEAT_ONLY = (0.2,)
DOCS_MESH = 0.1
"""[m] the reference FEA's mesh in the docs' run."""
DOCS_REFERENCE_MESHES = (0.07, 0.05)
"""[m] the finer meshes the docs' run also runs the ROM's two reference cases on: the
reference's own mesh error, and the ROM (its seat penalty at each mesh's) against them."""
REFERENCE_RUNS = ("ring, mu 0", "seat only, mu 0.2", "sleeve, mu 0", "sleeve, mu 0.2")
"""The ROM's reference runs, friction 0 and 0.2 with the ROM's contacts (the seat's friction,
and in the sleeve the sleeve's; the ring-pile contact frictionless), without and with the
sleeve: their FEA is repeated on the other meshes, and the ROM is run with each of
:data:`ROM_VARIANTS` (:data:`SLEEVE_VARIANTS` in the sleeve) against them."""


def rom_stack_options(cfg) -> dict:
    """The stack options of a system with ``[[anvil.bodies]]`` as :func:`stack_unit`'s
    keywords (the seat friction is each run's)."""
    st = cfg.anvil.stack
    return {"seat_rings": st.seat_rings, "pile_rings": st.pile_rings,
            "ram_annuli": st.ram_annuli, "pile_head": cfg.anvil.pile_head}


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


def sleeve_options(config) -> dict:
    """The ROM stack's sleeve keywords of an FEA configuration (:func:`stack_unit`'s: its
    clearance off the bodies' outer radius and its coefficient; {} without a sleeve)."""
    if config.sleeve_radius is None:
        return {}
    outer = float(max(config.anvil.outline[:, 0].max(), config.ring.outline[:, 0].max()))
    return {"sleeve_clearance": config.sleeve_radius - outer,
            "sleeve_friction": config.sleeve_friction}


def rom_against_fea(cfg, ring, mu, fea, penalty_size, **variant):
    """The ROM stack's blow against the FEA run ``fea`` (module docstring); ``penalty_size``:
    the FEA's penalty length [m] (its mesh size over its contact stiffness factor), the seat's
    and the sleeve's; ``variant``: keywords of :func:`stack_unit` (the sleeve's among them),
    or ``static_correction`` of the system's anvil."""
    start = time.perf_counter()
    if "static_correction" in variant:
        cfg = dataclasses.replace(cfg, anvil=dataclasses.replace(
            cfg.anvil, static_correction=variant.pop("static_correction")))
    options = {} if ring is None else rom_stack_options(cfg) | variant
    blow = run_stack_blow(cfg, stack_unit(cfg, ring, seat_friction=mu,
                                          penalty_size=penalty_size, **options))
    wall = time.perf_counter() - start
    h = float(blow.time[1] - blow.time[0])
    rom_t = blow.time - 0.5 * h  # first contact at t = 0, as the FEA
    row = {"rom_wall_time [s]": wall,
           **series_against_fea(rom_t, blow.pile_force, blow.ram_force, fea)}
    row["rom_friction_energy [-]"] = blow.friction_energy / blow.input_energy
    row["rom_energy_balance [-]"] = float(np.abs(blow.energy_residual).max()
                                          / blow.input_energy)
    return row


def reference_error(other: dict, study: dict, h_other: float, h: float) -> dict:
    """The reference FEA's own mesh error, per run name: the coarser of the two meshes' runs
    against the finer's (the same figures as the ROM's), and their first-order extrapolation
    to the study mesh's error (the penalty contacts' compliance, E / h per area, is the
    leading error and falls as h: err(h) ~ d * h / |h_other - h| when ``h_other`` is finer,
    d * h / (h_other - h) when coarser)."""
    scale = h / abs(h_other - h)
    coarse, fine = (study, other) if h_other < h else (other, study)
    out = {}
    for name in other:
        d = series_against_fea(coarse[name].time, coarse[name].anvil_pile_force,
                               coarse[name].ram_anvil_force, fine[name])
        d = {k: v for k, v in d.items() if k != "band_error [dB]"}
        d["estimated_error_at_study_mesh"] = {
            key: abs(d[key]) * scale for key in ("pile_peak_error [-]", "ram_peak_error [-]",
                                                  "pile_rms_error [-]", "ram_rms_error [-]",
                                                  "band_error_max [dB]")}
        out[name] = d
    return out


def observed_order(pairs) -> float:
    """Order p of differences that fall as h^p, from two (h_a, h_b, d) pairs, d = C |h_a^p -
    h_b^p|: the p in (0, 4] whose ratio |h_a1^p - h_b1^p| / |h_a2^p - h_b2^p| is d1 / d2 (the
    ratio is monotonic in p; the end of the range when d1 / d2 is beyond it)."""
    (a1, b1, d1), (a2, b2, d2) = pairs
    p = np.linspace(1e-4, 4.0, 4000)
    ratio = np.abs(a1**p - b1**p) / np.abs(a2**p - b2**p)
    if ratio[0] > ratio[-1]:
        p, ratio = p[::-1], ratio[::-1]
    return float(np.interp(d1 / d2, ratio, p))


def observed_orders(blocks: dict, meshes, h: float) -> dict:
    """Observed order of the pile-head RMS difference per reference run, from the study mesh
    ``h`` against the first two ``meshes``, and the study mesh's error at that order,
    d1 h^p / |h^p - h1^p| with h1 the finer mesh against the finest; None at p < 0.25 (not in
    the asymptotic range)."""
    h1, h2 = meshes[:2]
    out = {}
    for name in blocks[f"mesh {h1:g} m"]:
        d1 = blocks[f"mesh {h1:g} m"][name]["pile_rms_error [-]"]
        d2 = blocks[f"mesh {h2:g} m"][name]["pile_rms_error [-]"]
        p = observed_order([(h, h1, d1), (h, h2, d2)])
        finest, d = (h1, d1) if h1 < h2 else (h2, d2)
        out[name] = {"order [-]": p, "pile_rms_error_at_study_mesh [-]":
                     d * h**p / abs(h**p - finest**p) if p >= 0.25 else None}
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
    if args.sleeve is not None:
        for mu in args.sleeve_friction or args.friction:
            cases[f"sleeve, mu {mu:g}"] = dataclasses.replace(
                base, ring=ring, seat_friction=mu, pile_friction=0.0,
                sleeve_radius=outer + args.sleeve, sleeve_friction=mu)
    rows = {}
    system = without_soil(load_system(EXAMPLES / "table1.toml"))
    ring_system = without_soil(load_system(ROM_SYSTEM))
    roms = {}
    fine = {}
    for name, config in cases.items():
        start = time.perf_counter()
        result = cached_impact_fea(config)
        if name in REFERENCE_RUNS:
            fine[name] = result
        rows[name] = summary(result)
        print(f"{name}: {time.perf_counter() - start:.0f} s", flush=True)
        if args.rom and not name.startswith("+sleeve"):
            body, cfg = (None, system) if config.ring is None else (ring, ring_system)
            sleeve = sleeve_options(config)
            roms[name] = rom_against_fea(cfg, body, config.seat_friction, result, penalty,
                                         **sleeve)
            rows[name]["rom"] = roms[name]
            if name in REFERENCE_RUNS:
                rows[name]["rom_variants"] = {
                    v: rom_against_fea(ring_system, ring, config.seat_friction, result,
                                       penalty, **sleeve, **kw)
                    for v, kw in (SLEEVE_VARIANTS if sleeve else ROM_VARIANTS).items()}
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
            other = {}
            for name in REFERENCE_RUNS:
                if name in fine:
                    start = time.perf_counter()
                    other[name] = cached_impact_fea(dataclasses.replace(
                        cases[name], mesh_size=h))
                    print(f"{name} at mesh {h:g} m: {time.perf_counter() - start:.0f} s",
                          flush=True)
            block = reference_error(other, fine, h, args.mesh_size)
            if args.rom and h < args.mesh_size:
                for name, result in other.items():
                    block[name]["rom"] = rom_against_fea(
                        ring_system, ring, cases[name].seat_friction, result,
                        h / args.contact_factor, **sleeve_options(cases[name]))
            study["reference_error"][f"mesh {h:g} m"] = block
        if len(args.reference_meshes) >= 2:
            study["reference_order"] = observed_orders(study["reference_error"],
                                                       args.reference_meshes[:2],
                                                       args.mesh_size)
            print("observed orders of the reference's pile-head RMS difference:",
                  study["reference_order"])
        for label, block in study["reference_error"].items():
            for name, d in block.items():
                e = d["estimated_error_at_study_mesh"]
                print(f"{name} {args.mesh_size:g} m against {label}: "
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
            "seat only, mu 0.2": "ring, mu 0.2 on the seat only",
            "sleeve, mu 0.2": "ring + sleeve 1 mm off, mu 0.2 on the seat and the sleeve"}
"""The FEA runs of the docs' table, study name -> row label."""

ROM_ROWS = {"no ring": "no ring (the anvil unit; the runner does not book its ram dashpot's "
                       "work)", "ring, mu 0": "ring, mu 0",
            "seat only, mu 0.2": "ring, mu 0.2 on the seat",
            "ring, mu 0.2": "ring, mu 0.2 (FEA: also on the ring-pile contact)",
            "sleeve, mu 0": "ring + sleeve 1 mm off, mu 0",
            "sleeve, mu 0.2": "ring + sleeve 1 mm off, mu 0.2 on the seat and the sleeve"}
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
            default = text == label and name in REFERENCE_RUNS
            rom.append({"bold": True, "cells": row} if default else row)
    tables = {}
    if reference:
        rows, roms = [], []
        for label, block in reference.items():
            for name, d in block.items():
                order = (orders or {}).get(name, {}).get("order [-]")
                if "rom" in d:
                    v = d["rom"]
                    roms.append([f"{name}, FEA {label}", v["pile_peak_error [-]"],
                                 v["ram_peak_error [-]"], v["pile_rms_error [-]"],
                                 v["ram_rms_error [-]"],
                                 _band(v["band_error_max [dB]"], v["band_error_at [Hz]"])])
                rows.append([f"{name}, {label}", d["pile_peak_error [-]"],
                             d["ram_peak_error [-]"], d["pile_rms_error [-]"],
                             d["ram_rms_error [-]"],
                             _band(d["band_error_max [dB]"], d["band_error_at [Hz]"]),
                             None if order is None else f"{order:.2f}"])
        tables["reference"] = {
            "columns": ["reference FEA", "pile peak", "ram peak", "pile RMS", "ram RMS",
                        "bands", "observed order"],
            "formats": [None, "pct+", "pct+", "pct1", "pct1", None, None], "rows": rows}
        if roms:
            tables["rom_reference"] = {
                "columns": ["ROM against", "pile peak", "ram peak", "pile RMS", "ram RMS",
                            "bands"],
                "formats": [None, "pct+", "pct+", "pct1", "pct1", None], "rows": roms}
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
                   inputs=[*system_inputs(EXAMPLES / "table1.toml"), ROM_SYSTEM,
                           EXAMPLES / "anvils" / "xl8_ring.toml"],
                   tables=docs_tables(study["runs"], study.get("reference_error"),
                                      study.get("reference_order")),
                   substitutions=docs_substitutions(study), values=study, command=command)


def docs_substitutions(study: dict) -> dict:
    """The numbers docs/validation.md quotes from the reference's own mesh error: the observed
    order and the first-order pile-head RMS error of the study mesh, from the finest mesh."""
    out = {}
    orders = study.get("reference_order", {})
    blocks = study.get("reference_error", {})
    if not blocks:
        return out
    finest = min(blocks, key=lambda label: float(label.split()[1]))
    for name, key in (("ring, mu 0", "mu0"), ("seat only, mu 0.2", "mu02")):
        if name in orders:
            out[f"reference_order_{key}"] = [orders[name]["order [-]"], "f2"]
        if name in blocks[finest]:
            e = blocks[finest][name]["estimated_error_at_study_mesh"]["pile_rms_error [-]"]
            out[f"reference_rms_{key}"] = [e, "pct1"]
    return out


if __name__ == "__main__":
    main()
