"""Anvil-size study: lumped-mass and ROM anvils against the FEA for anvils of three pile sizes.

Run: python benchmarks/study_anvil_size.py [--out results/study_size] [--series both]

Two series, each of a 2 m, a 5.5 m and an 8 m pile, every ram striking at 6.16 m/s:

* "scaled": the s2, m55 and xl8 anvils on their piles (anvilwave/examples/size_s2.toml,
   size_m55.toml,
  table1.toml: the same configuration at scales 0.25, 0.6875 and 1), struck by their
  illustrative rams (scaled with the rest). The window (25 ms at full scale) and the FEA
  element size scale with the anvil, so the three cases differ in size only: under geometric
  similarity the wave problem is scale-free and the errors come out the same at every size.
* "class": class-typical systems, in which the ram does not scale with the pile:
  anvilwave/examples/size_s2_class.toml (IHC S-800, 40 t, D 0.95 m ram on the 2 m pile) and
  size_m55_class.toml (MENCK MHU 1900S, 95 t, D 1.26 m on the 5.5 m pile), whose anvils keep the
  xl8 proportions scaled with the pile but a top face of the ram's radius, and the xl8 case
  (table1.toml) with its 275 t illustrative ram. Every ram is a Smith rod of segments
  0.5 m x D / 8 (:func:`case_config`). The FEA element size scales with the pile
  (0.1 m x D / 8); the window is 25 ms, long enough for the impact of the long class rams,
  but ends before the pile toe reflection reaches the gauge ((2 L - gauge depth) / c0 after
  impact: 15.2 ms for the 40 m pile of s2_class, 22.8 ms for the 60 m pile of m55_class). The
  FEA's toe is free and the 1D models' rests on a stiff elastic bearing
  (anvilwave.analyses.compare.without_soil), so after the reflection the models differ by their
  boundary, not
  by their anvil.

Per case it prints and writes (study.json) the errors of both anvil models against the FEA in
the case's comparison band, and what should govern the lumped error: the anvil's overhang from
the ram face to the pile wall, (r_pile - r_ram) / r_pile (r_pile: the pile wall mid radius),
and the anvil's first flexible frequency f1 times the ram's wave return time 2 L_ram / c
(f1 T_ram large: the anvil is stiff over the time of the impact and acts as a rigid mass).
With both series (the default) it also writes the table of docs/validation.md,
docs/data/study_anvil_size.json (benchmarks/doc_data.py; checked by tests/test_doc_tables.py).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import time
from pathlib import Path

from doc_data import system_inputs, write_doc_data

import anvilwave
from anvilwave.analyses.compare import (
    ModelRun,
    comparison_bandwidth,
    fea_config,
    metrics,
    without_soil,
)
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes
from anvilwave.config.system import SystemConfig, load_system
from anvilwave.engine.direct import build_engine
from anvilwave.fea.impact import run_impact_fea
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.ram import RamRod

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = Path(anvilwave.__file__).resolve().parent / "examples"
"""The example files of the anvilwave that runs (the checkout's, or an installed wheel's)."""
PACKAGE = EXAMPLES.parent
FULL_WINDOW = 0.025
"""The paper's window at full scale (8 m pile) [s]."""


@dataclasses.dataclass(frozen=True)
class Case:
    """One configuration of the study.

    scale : pile diameter / 8 m; sets the FEA element size (0.1 m x scale) and output interval.
    window : simulated time [s]; None: 25 ms or, when shorter, until the toe reflection
        reaches the gauge (:func:`toe_window`).
    hammer : a database hammer replacing the file's (None: as in the file).
    """

    name: str
    file: str
    scale: float
    window: float | None
    hammer: str | None = None


SERIES = {
    "scaled": (Case("s2", "size_s2.toml", 0.25, FULL_WINDOW * 0.25),
               Case("m55", "size_m55.toml", 0.6875, FULL_WINDOW * 0.6875),
               Case("xl8", "table1.toml", 1.0, FULL_WINDOW)),
    "class": (Case("s2_class", "size_s2_class.toml", 0.25, None),
              Case("m55_class", "size_m55_class.toml", 0.6875, None),
              Case("xl8", "table1.toml", 1.0, None, hammer="illustrative_5500kj")),
}


def toe_window(cfg: SystemConfig) -> float:
    """25 ms, or the time [s] (rounded down to 0.1 ms) at which the wave that leaves the pile
    head at impact returns from the toe to the gauge, when that is shorter."""
    pile = cfg.pile_soil.pile
    down = sum(s.length / s.wave_speed for s in pile.sections)
    to_gauge = pile.gauge_depth / pile.sections[0].wave_speed
    return min(FULL_WINDOW, math.floor((2.0 * down - to_gauge) / 1e-4) * 1e-4)


def case_config(case: Case) -> SystemConfig:
    """The free-pile system of a case, with its window (and hammer, when replaced).

    Every ram is a Smith rod of segments 0.5 m x scale, the pile keeps its file's segments but
    none finer than the paper's 0.5 m x scale, the contacts have no dashpot (the setting of the
    classic programs, whatever the system file sets: table1.toml has 0.25 m segments and a
    contact dashpot), and the step is the automatic one: the ram's cut-off then stays above the
    comparison band of the case, and the scaled series is similar down to its discretisation.
    """
    cfg = without_soil(load_system(EXAMPLES / case.file))
    segment = max(cfg.pile_soil.pile.segment_length, 0.5 * case.scale)
    pile = dataclasses.replace(cfg.pile_soil.pile, segment_length=segment)
    cfg = dataclasses.replace(
        cfg, pile_soil=dataclasses.replace(cfg.pile_soil, pile=pile),
        anvil=dataclasses.replace(cfg.anvil, ram_contact_damping=0.0))
    hammer = cfg.hammer if case.hammer is None else load_hammer(case.hammer, cfg.gravity)
    ram = hammer.ram
    rod = RamRod.from_profile(ram.sections[:, 0], ram.sections[:, 1], ram.sections[:, 2],
                              elastic_modulus=ram.elastic_modulus, density=ram.density,
                              segment_length=0.5 * case.scale)
    cfg = dataclasses.replace(cfg, hammer=dataclasses.replace(hammer, ram=rod),
                              impact_velocity=hammer.impact_velocity, time_step=None)
    window = toe_window(cfg) if case.window is None else case.window
    return dataclasses.replace(cfg, duration=round(window / 1e-5) * 1e-5)


def geometry_numbers(cfg: SystemConfig, modal) -> dict:
    """Masses and the dimensionless numbers of the ram, anvil and pile of a case."""
    ram = cfg.hammer.ram
    section = cfg.pile_soil.pile.sections[0]
    r_pile = 0.5 * (section.outer_diameter - section.wall_thickness)
    r_ram = 0.5 * ram.toe_diameter
    f1 = float(modal.frequencies[1])
    return_time = 2.0 * ram.length / math.sqrt(ram.elastic_modulus / ram.density)
    return {
        "hammer": cfg.hammer.name,
        "anvil_mass [kg]": float(modal.total_mass),
        "ram_mass [kg]": float(cfg.hammer.ram_mass),
        "ram_length [m]": float(ram.length),
        "ram_diameter [m]": float(ram.toe_diameter),
        "pile_diameter [m]": float(section.outer_diameter),
        "ram_over_pile_diameter [-]": float(ram.toe_diameter / section.outer_diameter),
        "anvil_overhang_ratio [-]": float((r_pile - r_ram) / r_pile),
        "anvil_first_flexible_frequency [Hz]": f1,
        "ram_wave_return_time [s]": return_time,
        "f1_times_ram_return_time [-]": f1 * return_time,
    }


def _computed_modes(spec, fmax):
    return compute_anvil_modes(spec, fmax=fmax).modal_data


def run_case(case: Case, reference: ModelRun | None = None, modes=_computed_modes) -> dict:
    """A case's row: its FEA (or ``reference``, an FEA run of the same case given, e.g. the
    demo's for xl8), its geometry numbers and the errors of both anvil models against the FEA.
    ``modes(spec, fmax)`` gives the anvil's modal data (default: computed)."""
    cfg = case_config(case)
    modal = modes(cfg.anvil.spec, cfg.anvil.fmax)
    row = {"window [s]": cfg.duration, "fea_mesh_size [m]": 0.1 * case.scale}
    if reference is None:
        fea = run_impact_fea(fea_config(cfg, mesh_size=0.1 * case.scale,
                                        output_interval=1e-5 * case.scale))
        reference = ModelRun("fea", fea.to_columns(), fea.wall_time, {})
        row.update({"fea_dof": fea.n_dof, "fea_wall_time [s]": fea.wall_time})
    ref = reference
    preload = float(ref.columns["anvil_pile_force [N]"][0])
    band = comparison_bandwidth(cfg)
    row.update({"bandwidth [Hz]": band, **geometry_numbers(cfg, modal)})
    for model in ("rom", "lumped"):
        blow = build_engine(cfg.with_anvil_model(model), modal=modal).run()[0]
        row[model] = metrics(ModelRun(model, blow.columns, blow.wall_time, {}), ref, preload,
                             band)
    return row


def print_table(series: str, table: dict) -> None:
    print(f"\n{series} series")
    print(f"{'anvil':9s} {'m_anv t':>7s} {'m_ram t':>7s} {'Dr/Dp':>5s} {'overh':>5s} "
          f"{'f1 Hz':>6s} {'f1 Tr':>5s} {'model':6s} {'ram pk':>7s} {'pile pk':>7s} "
          f"{'RMS ram':>7s} {'RMS pile':>8s} {'arrival':>9s}")
    for name, row in table.items():
        for model in ("rom", "lumped"):
            m = row[model]
            print(f"{name:9s} {row['anvil_mass [kg]'] / 1e3:7.2f} "
                  f"{row['ram_mass [kg]'] / 1e3:7.2f} "
                  f"{row['ram_over_pile_diameter [-]']:5.3f} "
                  f"{row['anvil_overhang_ratio [-]']:5.3f} "
                  f"{row['anvil_first_flexible_frequency [Hz]']:6.1f} "
                  f"{row['f1_times_ram_return_time [-]']:5.3f} {model:6s} "
                  f"{m['peak_ram_anvil_force_error [-]']:+7.3f} "
                  f"{m['peak_anvil_pile_force_error [-]']:+7.3f} "
                  f"{m['ram_anvil_force_normalised_rms_error [-]']:7.3f} "
                  f"{m['anvil_pile_force_normalised_rms_error [-]']:8.3f} "
                  f"{m['pile_force_arrival_error [s]'] * 1e3:+8.3f}ms")


DOC_METRICS = {
    "ram peak": ("pct+", "peak_ram_anvil_force_error [-]"),
    "pile peak": ("pct+", "peak_anvil_pile_force_error [-]"),
    "RMS ram": ("pct", "ram_anvil_force_normalised_rms_error [-]"),
    "RMS pile": ("pct", "anvil_pile_force_normalised_rms_error [-]"),
    "arrival": ("ms+", "pile_force_arrival_error [s]"),
}
"""The error columns of docs/validation.md's table: (format, metric)."""


def _hammer_text(name: str) -> str:
    """A database hammer's name, short: "illustrative" for the scaled series' rams."""
    return "illustrative" if "illustrative" in name else name.replace("Hydrohammer ", "")


def _mass_text(mass: float) -> str:
    tonnes = mass / 1e3
    return f"{tonnes:.0f} t" if tonnes >= 9.95 else f"{tonnes:.1f} t"


def doc_rows(results: dict) -> list:
    """The table's rows: per case its ROM and lumped rows; a case of both series with the same
    results (xl8: its toe window is longer than 25 ms) once, as "both"."""
    rows = []
    scaled, classes = results["scaled"], results["class"]
    cases = [("scaled", n, r) for n, r in scaled.items()]
    for name, row in classes.items():
        if name in scaled and all(row[m][k] == scaled[name][m][k] for m in ("rom", "lumped")
                                  for _, k in DOC_METRICS.values()):
            cases = [("both" if c[1] == name else c[0], *c[1:]) for c in cases]
        else:
            cases.append(("class", name, row))
    for series, name, row in cases:
        label = f"{name} ({_hammer_text(row['hammer'])}, {_mass_text(row['ram_mass [kg]'])})"
        head = [series, label, row["anvil_overhang_ratio [-]"],
                row["f1_times_ram_return_time [-]"]]
        for model, lead in (("rom", head), ("lumped", [None] * 4)):
            label = "ROM" if model == "rom" else "lumped"
            rows.append([*lead, label, *(row[model][k] for _, k in DOC_METRICS.values())])
    return rows


def write_docs_table(results: dict) -> None:
    """docs/data/study_anvil_size.json: the table of docs/validation.md and the figures its
    prose quotes."""
    table = {"columns": ["series", "anvil (hammer)", "overhang", "f1·T_ram", "model",
                         *DOC_METRICS],
             "formats": [None, None, "f2", "f2", None, *(f for f, _ in DOC_METRICS.values())],
             "rows": doc_rows(results)}
    scaled, classes = results["scaled"], results["class"]
    small, wide = classes["s2_class"], [classes["m55_class"], classes["xl8"]]

    def span(rows, model, key, pick):
        return pick(r[model][key] for r in rows)

    pile, ram = "peak_anvil_pile_force_error [-]", "peak_ram_anvil_force_error [-]"
    rms_ram, rms_pile = ("ram_anvil_force_normalised_rms_error [-]",
                         "anvil_pile_force_normalised_rms_error [-]")
    arrival = "pile_force_arrival_error [s]"
    every = [*scaled.values(), *classes.values()]
    subs = {
        "scaled_lumped_rms_min": [min(span(scaled.values(), "lumped", k, min)
                                      for k in (rms_ram, rms_pile)), "pct"],
        "scaled_lumped_rms_max": [max(span(scaled.values(), "lumped", k, max)
                                      for k in (rms_ram, rms_pile)), "pct"],
        "scaled_lumped_pile_min": [-span(scaled.values(), "lumped", pile, max), "pct"],
        "scaled_lumped_pile_max": [-span(scaled.values(), "lumped", pile, min), "pct"],
        "small_f1t": [small["f1_times_ram_return_time [-]"], "sig2"],
        "small_overhang": [small["anvil_overhang_ratio [-]"], "f2"],
        "small_lumped_pile": [abs(small["lumped"][pile]), "pct"],
        "small_lumped_arrival": [abs(small["lumped"][arrival]), "ms"],
        "wide_overhang_min": [min(r["anvil_overhang_ratio [-]"] for r in wide), "f2"],
        "wide_f1t_max": [max(r["f1_times_ram_return_time [-]"] for r in wide), "sig2"],
        "wide_lumped_pile_min": [-span(wide, "lumped", pile, max), "pct"],
        "wide_lumped_pile_max": [-span(wide, "lumped", pile, min), "pct"],
        "wide_lumped_arrival_min": [-span(wide, "lumped", arrival, max), "ms"],
        "wide_lumped_arrival_max": [-span(wide, "lumped", arrival, min), "ms"],
        "wide_lumped_ram_min": [span(wide, "lumped", ram, min), "pct"],
        "rom_rms_max_but_small_ram": [max(
            max(r["rom"][rms_pile] for r in every),
            max(r["rom"][rms_ram] for r in every if r is not small)), "pct"],
        "small_rom_rms_ram": [small["rom"][rms_ram], "pct"],
    }
    inputs = [p for case in (*SERIES["scaled"], *SERIES["class"])
              for p in system_inputs(EXAMPLES / case.file)]
    inputs += [PACKAGE / "hammer" / "data" / f"{c.hammer}.toml"
               for c in SERIES["class"] if c.hammer]
    write_doc_data(
        "study_anvil_size", about="The anvil-size study (docs/validation.md, \"The anvil-size "
        "study\"): the ROM and the lumped anvil against each case's FEA in its comparison band.",
        inputs=inputs, tables={"size": table}, substitutions=subs, values=results,
        command="python benchmarks/study_anvil_size.py")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_size")
    parser.add_argument("--series", choices=("scaled", "class", "both"), default="both")
    parser.add_argument("--docs-from", type=Path, default=None, metavar="STUDY_JSON",
                        help="only rewrite docs/data/study_anvil_size.json from the study.json "
                             "of an earlier run of both series")
    args = parser.parse_args()
    if args.docs_from is not None:
        write_docs_table(json.loads(args.docs_from.read_text()))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    names = ("scaled", "class") if args.series == "both" else (args.series,)
    results = {}
    for series in names:
        results[series] = {}
        for case in SERIES[series]:
            start = time.perf_counter()
            row = run_case(case)
            results[series][case.name] = row
            print(f"{series} {case.name}: FEA {row['fea_dof']} DOF in "
                  f"{row['fea_wall_time [s]']:.1f} s, case {time.perf_counter() - start:.1f} s",
                  flush=True)
    (args.out / "study.json").write_text(json.dumps(results, indent=2) + "\n")
    if len(names) == 2:
        write_docs_table(results)
    for series, table in results.items():
        print_table(series, table)


if __name__ == "__main__":
    main()
