"""Lumped-anvil conventions study: when does a lumped anvil overestimate the pile force?

Run: python benchmarks/study_lumped_conventions.py [--out results/study_lumped]

Ligthart & Orlando report for their 8 m anvil that the rigid lumped-mass anvil OVERESTIMATES
the peak pile-head force against the FEA, and that the FEA (and their ROM) show a ~4 ms wave
propagation time through the anvil, ending in an "almost stepwise" pile-force increase (the
anvil lifts off the pile and re-impacts). With anvilwave's xl8 anvil (Table 1) the rigid
lumped anvil comes out ~20 % LOW instead. This study runs several lumped-anvil conventions and
the ROM against the same reference FEA, for the xl8 and three variants of its proportions, and
records which of them reproduce the paper's two statements.

Every case is the Table 1 system on the free pile of the comparison
(:func:`anvilwave.analyses.compare.without_soil`, via :func:`study_anvil_size.case_config`): the 8
m x
140 mm x 80 m pile in the paper's 0.5 m segments (comparison band 3.3 kHz), a 275 t uniform
steel ram at 6.16 m/s, here a Smith rod of 0.5 m segments (the classic programs' ram; the FEA
does not depend on the 1D ram model), contacts without dashpots, the automatic time step, a
25 ms window: the setting of the paper's lumped-mass programs. These are fixed here whatever
anvilwave/examples/table1.toml sets (0.25 m segments, modal ram, a contact dashpot).

The anvils are the xl8 outline, (r, z) = (0, 0), (r_top, 0), (4.15, 0.75 s), (4.15, 1.2 s),
(0, 1.2 s), with thickness scale s and top-face radius r_top, struck by a 275 t ram of
diameter D (length from the mass):

* ``xl8``: s = 1, r_top = 0.9 m = the ram's radius, D = 1.8 m (Table 1).
* ``xl8_thin``: s = 0.8, a thinner, more flexible anvil whose ROM pile force arrives at ~4 ms,
  as in the paper.
* ``xl8_thick``: s = 2, a squat anvil, eight times stiffer in bending, twice the mass.
* ``xl8_widetop``: s = 1 with a flat top face of radius 3.0 m (wider than the 0.9 m ram):
  a thick slab out to near the pile wall, struck at its centre.

The anvil models (all against the same FEA run of the case, default FEA mesh, 0.1 m; the FEA
is cached as CSV in --out and reused on a rerun):

* ``rom``: the Mode Displacement Method anvil (fmax 5 kHz, static correction on).
* ``1 lumped``: today's lumped anvil, the rigid FE mass between the contacts of the system, i.e.
  the ram's toe half segment and the pile's top half segment 2 E A / dx
  (:func:`anvilwave.engine.direct.contact_stiffnesses`). This IS already the Smith-style convention
  3
  of the issue (pile half segment as the pile-side spring), so 3 is not run separately.
* ``2a series``: the rigid mass with the anvil's static through-flexibility f = G_rr - 2 G_rp
  + G_pp (G: the inertia-relief flexibility between the ram face and the pile ring of the
  modal data, the elastic shortening of the anvil under a self-equilibrated pair of interface
  forces) added in series with the contacts, split between the ram and the pile side in the
  ratio G_rr : G_pp.
* ``2b static``: the rigid mass with the full 2 x 2 flexibility G as the massless feedthrough
  of the ROM's static correction: the ROM truncated to its rigid-body mode (a quasi-static
  anvil). Unlike 2a it keeps the cross term G_rp < 0: a force on the ram face lifts the pile
  ring relative to the rigid motion (the anvil "cups"), so lift-off and re-impact can occur.
* ``2c two-mass``: the anvil as two masses joined by one spring (a helmet-mass split): total
  mass and static through-stiffness 1 / f kept, the split chosen so that the pair's frequency
  equals that of the anvil mode carrying most of f (the first bending mode, 96 % for xl8), the
  heavier mass on the side the mode moves less.
* ``3 EA/dx``: as 1, but the pile-side contact E A / dx (GRLWEAP's first pile segment) instead
  of Smith's half segment: a contact-stiffness sensitivity.
* ``4a classic``: ``--anvil classic`` as in Table 1's [anvil.classic] (GRLWEAP-like helmet, no
  cushion material): the FE mass as the helmet between a steel "hammer cushion" of the ram's
  toe half segment (restitution 1) and the steel pile contact 2 E A / dx.
* ``4b classic GRLWEAP``: the helmet with GRLWEAP's hammer cushion of a large hydraulic hammer
  (IHC S-4000 of anvilwave/examples/grlweap_s4000.toml: 38,487 kN/mm, restitution 0.8, round-out 3
  mm)
  in series with the ram's toe half segment, and the pile contact E A / dx with 3 mm round-out.
  (GRLWEAP's hammer damping is left out.)

Per case and model it writes (study.json, table.md; and prints) the peak pile-head force
(anvil-pile contact) low-passed at the comparison band (:func:`anvilwave.analyses.compare.metrics`,
:func:`anvilwave.analyses.compare.comparison_bandwidth`: 3.3 kHz), its error against the FEA and
whether the model over- or underestimates, the pile-force arrival time
(:func:`anvilwave.analyses.compare.arrival_time`: 20 % of the peak), the time and rate of the
steepest
rise of the band-limited pile force (the "almost stepwise increase") and the longest early
lift-off of the anvil from the pile (raw contact force); and the peaks again low-passed at
0.5, 1 and 2 kHz (BANDS: does the verdict depend on the band?). Plots of the pile force go to
fig_<case>.png.
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import math
import time
from pathlib import Path

import numpy as np
from doc_data import system_inputs, write_doc_data
from study_anvil_size import FULL_WINDOW, Case, geometry_numbers
from study_anvil_size import case_config as size_case_config

from anvilwave.analyses.compare import (
    ModelRun,
    band_limited,
    comparison_bandwidth,
    fea_config,
    metrics,
)
from anvilwave.anvil_rom.fem.modalfile import ModalData
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes
from anvilwave.config.system import SystemConfig
from anvilwave.engine.direct import build_engine, contact_stiffnesses
from anvilwave.fea.impact import FeaConfig, run_impact_fea
from anvilwave.hammer.driving_system import Cushion
from anvilwave.hammer.ram import RamRod
from anvilwave.output.tables import read_csv, write_csv

ROOT = Path(__file__).resolve().parents[1]
RAM_MASS = 275000.0
"""Mass of every ram of the study [kg] (Table 1's illustrative 5500 kJ ram)."""
RAM_SEGMENT = 0.5
"""Segment length of the Smith rod rams [m]."""
PILE_SEGMENT = 0.5
"""Pile segment length [m], the paper's: the comparison band c / (pi dx) is 3.3 kHz."""
XL8_OUTLINE = np.array([[0.0, 0.0], [0.9, 0.0], [4.15, 0.75], [4.15, 1.2], [0.0, 1.2]])
"""anvilwave/examples/anvils/xl8.toml, (r, z) [m], z down."""
GRLWEAP_HAMMER_CUSHION = Cushion(3.8487e10, 0.8, 0.003)
"""GRLWEAP's hammer cushion of the IHC S-4000 (anvilwave/examples/grlweap_s4000.toml) [N/m, -,
m]."""
GRLWEAP_ROUND_OUT = 0.003
"""Round-out of GRLWEAP's steel helmet-pile contact [m] (anvilwave/examples/grlweap_s4000.toml)."""
EARLY = 0.012
"""Lift-off intervals ending before this time [s] count as the early lift-off."""
BANDS = (500.0, 1000.0, 2000.0)
"""Lower low-pass bands [Hz] at which the peaks are also compared (band sensitivity)."""
BAND_MODELS = ("rom", "lumped", "static", "classic_grlweap")
"""Models shown in the band-sensitivity table."""


@dataclasses.dataclass(frozen=True)
class Proportions:
    """An anvil of the xl8 family and its ram.

    thickness_scale : s, multiplies the cone height 0.75 m and the bottom depth 1.2 m [-].
    top_radius : radius of the flat top face [m]; None: the ram's radius.
    ram_diameter : diameter of the 275 t uniform ram [m] (length from the mass).
    """

    name: str
    description: str
    thickness_scale: float = 1.0
    top_radius: float | None = None
    ram_diameter: float = 1.8


CASES = (
    Proportions("xl8", "Table 1 anvil (s 1, top face = ram face 0.9 m)"),
    Proportions("xl8_thin", "thinner, flexible (s 0.8)", thickness_scale=0.8),
    Proportions("xl8_thick", "squat, bending-stiff (s 2)", thickness_scale=2.0),
    Proportions("xl8_widetop", "flat top face r 3.0 m > ram 0.9 m", top_radius=3.0),
)

MODELS = {
    "rom": "ROM",
    "lumped": "1 lumped (today)",
    "series": "2a lumped + anvil flex. in series",
    "static": "2b lumped + anvil flex. matrix",
    "two_mass": "2c two-mass anvil",
    "ea_dx": "3 lumped, pile contact EA/dx",
    "classic": "4a classic (Table 1)",
    "classic_grlweap": "4b classic, GRLWEAP cushion",
}
"""Short name -> table label of the 1D anvil models (module docstring)."""


def ram_length(diameter: float, density: float) -> float:
    """Length [m] of a solid cylinder of RAM_MASS, diameter [m] and density [kg/m^3]."""
    return RAM_MASS / (density * math.pi * 0.25 * diameter**2)


def base_config() -> SystemConfig:
    """Table 1 on the free pile, rod ram, automatic step, 25 ms (study_anvil_size's xl8), with
    the paper's pile segments (PILE_SEGMENT) and contacts without dashpots, whatever
    anvilwave/examples/table1.toml says about those."""
    cfg = size_case_config(Case("xl8", "table1.toml", 1.0, FULL_WINDOW))
    pile = dataclasses.replace(cfg.pile_soil.pile, segment_length=PILE_SEGMENT)
    anvil = dataclasses.replace(cfg.anvil, ram_contact_damping=0.0, pile_contact_damping=0.0)
    return dataclasses.replace(cfg, anvil=anvil,
                               pile_soil=dataclasses.replace(cfg.pile_soil, pile=pile))


def case_config(case: Proportions, base: SystemConfig) -> SystemConfig:
    """The base system with the case's anvil outline and ram."""
    spec = base.anvil.spec
    r_ram = 0.5 * case.ram_diameter
    outline = XL8_OUTLINE.copy()
    outline[1, 0] = r_ram if case.top_radius is None else case.top_radius
    outline[2:, 1] *= case.thickness_scale
    interfaces = dataclasses.replace(spec.interfaces, ram_contact_radius=r_ram)
    spec = dataclasses.replace(spec, name=case.name, outline=outline, interfaces=interfaces,
                               source=f"{case.name} (study_lumped_conventions)")
    old = base.hammer.ram
    ram = RamRod.uniform(ram_length(case.ram_diameter, old.density), case.ram_diameter,
                         elastic_modulus=old.elastic_modulus, density=old.density,
                         segment_length=RAM_SEGMENT)
    return dataclasses.replace(base, hammer=dataclasses.replace(base.hammer, ram=ram),
                               anvil=dataclasses.replace(base.anvil, spec=spec))


# ----------------------------------------------------------------------------- conventions


def through_flexibility(modal: ModalData) -> float:
    """Static shortening of the anvil per unit force pair on its faces [m/N]:
    G_rr - 2 G_rp + G_pp of the inertia-relief flexibility G."""
    g = np.asarray(modal.elastic_flexibility)
    return float(g[0, 0] - 2.0 * g[0, 1] + g[1, 1])


def _synthetic_modal(modal: ModalData, frequencies, p_ram, p_pile, flexibility) -> ModalData:
    """Modal data of a hand-made anvil with the FE mass of ``modal`` (rigid mode first)."""
    gravity = np.zeros(len(frequencies))
    gravity[0] = math.sqrt(modal.total_mass)
    return dataclasses.replace(
        modal, frequencies=np.asarray(frequencies, float),
        participation_ram=np.asarray(p_ram, float), participation_pile=np.asarray(p_pile, float),
        participation_gravity=gravity, elastic_flexibility=np.asarray(flexibility, float),
        source="study_lumped_conventions")


def rigid_static_modal(modal: ModalData) -> ModalData:
    """Convention 2b: the rigid-body mode alone, all of G left to the static correction.

    A second mode with zero participation at fmax is a placeholder (the ROM needs a flexible
    mode): it is never excited and shows at neither interface, so the residual flexibility is
    the whole G.
    """
    s = 1.0 / math.sqrt(modal.total_mass)
    return _synthetic_modal(modal, [0.0, modal.fmax], [s, 0.0], [s, 0.0],
                            modal.elastic_flexibility)


def dominant_mode(modal: ModalData) -> tuple[int, float]:
    """Index of the flexible mode carrying most of the through-flexibility, and its share."""
    omega = 2.0 * np.pi * np.asarray(modal.frequencies)[1:]
    share = (modal.participation_ram[1:] - modal.participation_pile[1:]) ** 2 / omega**2
    j = int(np.argmax(share))
    return j + 1, float(share[j] / through_flexibility(modal))


def two_mass_modal(modal: ModalData) -> tuple[ModalData, dict]:
    """Convention 2c: two masses m_top + m_bot = M on one spring k = 1 / f.

    m_top m_bot = k M / omega^2 for the frequency omega of the dominant mode; when no real
    split exists (omega^2 < 4 k / M) the masses are equal and the frequency follows. The
    heavier mass goes to the interface the dominant mode moves less. Its modes (mass-normalised):
    the rigid one, and (m_bot, -m_top) / sqrt(m_top m_bot M) at omega.
    """
    total = modal.total_mass
    k = 1.0 / through_flexibility(modal)
    j, share = dominant_mode(modal)
    omega = 2.0 * np.pi * float(modal.frequencies[j])
    disc = 1.0 - 4.0 * k / (total * omega**2)
    if disc >= 0.0:
        light = 0.5 * total * (1.0 - math.sqrt(disc))
    else:
        light = 0.5 * total
        omega = math.sqrt(4.0 * k / total)
    heavy = total - light
    top_moves_less = abs(modal.participation_ram[j]) < abs(modal.participation_pile[j])
    m_top, m_bot = (heavy, light) if top_moves_less else (light, heavy)
    c = 1.0 / math.sqrt(m_top * m_bot * total)
    rigid = 1.0 / math.sqrt(total)
    p = np.array([m_bot * c, -m_top * c])
    data = _synthetic_modal(modal, [0.0, omega / (2.0 * np.pi)], [rigid, p[0]], [rigid, p[1]],
                            np.outer(p, p) / omega**2)
    info = {"top_mass [kg]": m_top, "bottom_mass [kg]": m_bot, "spring [N/m]": k,
            "frequency [Hz]": omega / (2.0 * np.pi), "fitted_mode": j,
            "fitted_mode_share_of_flexibility [-]": share}
    return data, info


def convention_systems(cfg: SystemConfig, modal: ModalData
                       ) -> tuple[dict[str, tuple[SystemConfig, ModalData]], dict]:
    """Every 1D anvil model of a case (MODELS) as (system, modal data) for build_engine, and
    the numbers that define them."""
    k_ram, k_pile_half = contact_stiffnesses(cfg)
    k_pile_full = 0.5 * cfg.pile_soil.head_contact_stiffness()
    anvil = cfg.anvil
    g = np.asarray(modal.elastic_flexibility)
    f = through_flexibility(modal)
    f_top = f * g[0, 0] / (g[0, 0] + g[1, 1])
    f_bot = f - f_top
    k_top = 1.0 / (1.0 / k_ram + f_top)
    k_bot = 1.0 / (1.0 / k_pile_half + f_bot)

    def anvil_as(**changes) -> SystemConfig:
        return dataclasses.replace(cfg, anvil=dataclasses.replace(anvil, **changes))

    helmet = dataclasses.replace(anvil.classic, helmet_mass=modal.total_mass)
    two_mass, two_mass_info = two_mass_modal(modal)
    systems = {
        "rom": (cfg, modal),
        "lumped": (anvil_as(model="lumped"), modal),
        "series": (anvil_as(model="lumped", ram_contact_stiffness=k_top,
                            pile_contact_stiffness=k_bot), modal),
        "static": (cfg, rigid_static_modal(modal)),
        "two_mass": (cfg, two_mass),
        "ea_dx": (anvil_as(model="lumped", pile_contact_stiffness=k_pile_full), modal),
        "classic": (anvil_as(model="classic", classic=dataclasses.replace(
            helmet, hammer_cushion=Cushion(k_ram, 1.0), pile_cushion=Cushion(k_pile_half))),
                    modal),
        "classic_grlweap": (anvil_as(model="classic", classic=dataclasses.replace(
            helmet, hammer_cushion=GRLWEAP_HAMMER_CUSHION, ram_bottom_stiffness=k_ram,
            pile_cushion=Cushion(k_pile_full, 1.0, GRLWEAP_ROUND_OUT))), modal),
    }
    numbers = {"ram_contact_stiffness [N/m]": k_ram,
               "pile_contact_stiffness_half_segment [N/m]": k_pile_half,
               "pile_contact_stiffness_full_segment [N/m]": k_pile_full,
               "anvil_through_flexibility [m/N]": f,
               "anvil_through_stiffness [N/m]": 1.0 / f,
               "elastic_flexibility [m/N]": g.tolist(),
               "series_ram_side_stiffness [N/m]": k_top,
               "series_pile_side_stiffness [N/m]": k_bot,
               "two_mass": two_mass_info}
    return systems, numbers


# ----------------------------------------------------------------------------- FEA (cached)


def fea_key(config: FeaConfig) -> str:
    """A digest of everything that defines the FEA run (anvil: outline hash and interfaces)."""
    fields = {f.name: getattr(config, f.name) for f in dataclasses.fields(config)
              if f.name != "anvil"}
    text = json.dumps(fields, sort_keys=True, default=repr)
    text += config.anvil.geometry_hash() + repr(config.anvil.interfaces)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def cached_fea(cfg: SystemConfig, name: str, out: Path) -> tuple[ModelRun, dict]:
    """The case's reference FEA (default mesh), from ``out`` when an identical run is there."""
    config = fea_config(cfg)
    stem = out / f"fea_{name}_{fea_key(config)}"
    csv, info_path = stem.with_suffix(".csv"), stem.with_suffix(".json")
    if csv.exists() and info_path.exists():
        info = json.loads(info_path.read_text())
        info["cached"] = True
        return ModelRun("fea", read_csv(csv), info["wall_time [s]"], info), info
    result = run_impact_fea(config)
    info = {"n_dof": result.n_dof, "n_steps": result.n_steps, "time_step [s]": result.time_step,
            "wall_time [s]": result.wall_time, "setup_time [s]": result.setup_time,
            "mesh_size [m]": config.mesh_size}
    columns = result.to_columns()
    write_csv(columns, csv.with_suffix(".part"))
    csv.with_suffix(".part").replace(csv)
    info_path.write_text(json.dumps(info, indent=2) + "\n")
    info["cached"] = False
    return ModelRun("fea", columns, result.wall_time, info), info


# ----------------------------------------------------------------------------- measures


def rise_and_lift_off(run: ModelRun, grid: np.ndarray, band: float, lift_offs: list
                      ) -> dict:
    """The steepest rise of the band-limited pile force up to its peak (time [s], rate [N/s])
    and the longest lift-off interval ending before EARLY [s]."""
    force = band_limited(run.columns, "anvil_pile_force [N]", grid, band)
    rate = np.gradient(force, grid)
    i = int(np.argmax(rate[:int(np.argmax(force)) + 1]))
    early = [iv for iv in lift_offs if iv[1] <= EARLY]
    longest = max(early, key=lambda iv: iv[1] - iv[0]) if early else None
    return {"steepest_rise_time [s]": float(grid[i]), "steepest_rise_rate [N/s]": float(rate[i]),
            "early_lift_off [s]": longest}


def run_case(case: Proportions, base: SystemConfig, out: Path) -> dict:
    """FEA, ROM and every lumped convention of one case, with their measures."""
    cfg = case_config(case, base)
    modal = compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax).modal_data
    band = comparison_bandwidth(cfg)
    fea, fea_info = cached_fea(cfg, case.name, out)
    preload = float(fea.columns["anvil_pile_force [N]"][0])
    grid = fea.columns["time [s]"]
    grid = np.linspace(grid[0], grid[-1], len(grid))
    systems, numbers = convention_systems(cfg, modal)
    row = {"description": case.description, "thickness_scale [-]": case.thickness_scale,
           "top_radius [m]": case.top_radius or 0.5 * case.ram_diameter,
           "bandwidth [Hz]": band, "fea": fea_info, **geometry_numbers(cfg, modal), **numbers}
    runs = {"fea": fea}
    fea_metrics = metrics(fea, None, preload, band)
    row["models"] = {"fea": {**fea_metrics, **rise_and_lift_off(
        fea, grid, band, fea_metrics["anvil_lift_off_intervals [s]"])}}
    for name, (system, data) in systems.items():
        blow = build_engine(system, modal=data).run()[0]
        run = ModelRun(name, blow.columns, blow.wall_time, {})
        runs[name] = run
        m = metrics(run, fea, preload, band)
        m["time_step [s]"] = blow.time_step
        m.update(rise_and_lift_off(run, grid, band, m["anvil_lift_off_intervals [s]"]))
        row["models"][name] = m
    row["peak_pile_force_by_band [N]"] = {
        f"{b:.0f}": {name: float(band_limited(run.columns, "anvil_pile_force [N]", grid,
                                              b).max()) for name, run in runs.items()}
        for b in (*BANDS, band)}
    plot_case(case, runs, band, out / f"fig_{case.name}.png")
    return row


def plot_case(case: Proportions, runs: dict[str, ModelRun], band: float, path: Path) -> None:
    """Pile-head force of the FEA, the ROM and the lumped conventions (band-limited)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4.8), constrained_layout=True)
    for name, run in runs.items():
        t = run.columns["time [s]"]
        grid = np.linspace(t[0], t[-1], len(t))
        force = band_limited(run.columns, "anvil_pile_force [N]", grid, band)
        style = {"fea": ("k", "-", 2.0), "rom": ("tab:red", "--", 1.5)}.get(name,
                                                                          (None, "-", 0.9))
        ax.plot(grid * 1e3, force / 1e6, color=style[0], ls=style[1], lw=style[2],
                label="FEA" if name == "fea" else MODELS[name])
    ax.set_xlim(0.0, 15.0)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("pile-head force [MN]")
    ax.set_title(f"{case.name}: {case.description} (low-passed at {band:.0f} Hz)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- tables


def _ms(value: float | None) -> str:
    return "-" if value is None or not math.isfinite(value) else f"{value * 1e3:.2f}"


def detail_table(results: dict) -> str:
    """One row per case and model (markdown)."""
    lines = ["| case | model | pile peak [MN] | error vs FEA | lumped | arrival [ms] | "
             "steepest rise [ms] | rise rate [MN/ms] | early lift-off [ms] |",
             "|---|---|---:|---:|---|---:|---:|---:|---|"]
    for case, row in results.items():
        for name, m in row["models"].items():
            label = "FEA" if name == "fea" else MODELS[name]
            error = m.get("peak_anvil_pile_force_error [-]")
            err = "-" if error is None else f"{100.0 * error:+.1f} %"
            verdict = "-" if error is None else ("over" if error > 0.0 else "under")
            lift = m["early_lift_off [s]"]
            lift_text = "-" if lift is None else f"{_ms(lift[0])}-{_ms(lift[1])}"
            lines.append(
                f"| {case} | {label} | {m['peak_anvil_pile_force [N]'] / 1e6:.0f} | {err} | "
                f"{verdict} | {_ms(m['pile_force_arrival_time [s]'])} | "
                f"{_ms(m['steepest_rise_time [s]'])} | "
                f"{m['steepest_rise_rate [N/s]'] / 1e9:.0f} | {lift_text} |")
    return "\n".join(lines)


def summary_table(results: dict) -> str:
    """One row per case: its numbers and the pile-peak error of every model (markdown)."""
    names = list(MODELS)
    head = ("| case | anvil t | f1 Hz | f1 T_ram | k_anvil GN/m | FEA peak MN | FEA arrival ms "
            "| ROM arrival ms | " + " | ".join(MODELS[n] for n in names) + " |")
    lines = [head, "|---|---:|---:|---:|---:|---:|---:|---:|" + "---:|" * len(names)]
    for case, row in results.items():
        models = row["models"]
        errors = " | ".join(f"{100.0 * models[n]['peak_anvil_pile_force_error [-]']:+.1f} %"
                            for n in names)
        lines.append(
            f"| {case} | {row['anvil_mass [kg]'] / 1e3:.0f} | "
            f"{row['anvil_first_flexible_frequency [Hz]']:.0f} | "
            f"{row['f1_times_ram_return_time [-]']:.2f} | "
            f"{row['anvil_through_stiffness [N/m]'] / 1e9:.1f} | "
            f"{models['fea']['peak_anvil_pile_force [N]'] / 1e6:.0f} | "
            f"{_ms(models['fea']['pile_force_arrival_time [s]'])} | "
            f"{_ms(models['rom']['pile_force_arrival_time [s]'])} | {errors} |")
    return "\n".join(lines)


def band_table(results: dict) -> str:
    """Peak pile force of the FEA and errors of BAND_MODELS at each low-pass band (markdown)."""
    lines = ["| case | band [Hz] | FEA peak [MN] | "
             + " | ".join(MODELS[n] for n in BAND_MODELS) + " |",
             "|---|---:|---:|" + "---:|" * len(BAND_MODELS)]
    for case, row in results.items():
        for band, peaks in row["peak_pile_force_by_band [N]"].items():
            errors = " | ".join(f"{100.0 * (peaks[n] / peaks['fea'] - 1.0):+.1f} %"
                                for n in BAND_MODELS)
            lines.append(f"| {case} | {band} | {peaks['fea'] / 1e6:.0f} | {errors} |")
    return "\n".join(lines)


DOCS_COLUMNS = {
    "ROM": "rom", "1 rigid mass (today)": "lumped",
    "2a + anvil flexibility in series": "series",
    "2b + anvil 2×2 static flexibility": "static", "2c two-mass anvil": "two_mass",
    "3 pile spring EA/dx": "ea_dx", "4a classic (Table 1)": "classic",
    "4b classic, GRLWEAP cushion": "classic_grlweap",
}
"""docs/validation.md's columns of pile-peak errors: label -> model of :data:`MODELS`."""
RIGID = ("lumped", "ea_dx", "classic", "classic_grlweap")
"""The rigid-mass conventions (1, 3, 4a, 4b)."""


def docs_table(results: dict) -> tuple[dict, dict]:
    """docs/validation.md's table (the FEA's peak and arrival, every model's pile-peak error)
    and the numbers its text quotes, from the study's results (study.json's ``cases``)."""
    rows = []
    for case, row in results.items():
        models = row["models"]
        rows.append([case, models["fea"]["peak_anvil_pile_force [N]"],
                     models["fea"]["pile_force_arrival_time [s]"],
                     *[models[m]["peak_anvil_pile_force_error [-]"]
                       for m in DOCS_COLUMNS.values()]])
    table = {"columns": ["anvil", "FEA peak", "FEA arrival", *DOCS_COLUMNS],
             "formats": [None, "MN0", "ms2", *["pct+"] * len(DOCS_COLUMNS)], "rows": rows}
    rigid = [r["models"][m]["peak_anvil_pile_force_error [-]"]
             for r in results.values() for m in RIGID]
    subs = {"xl8_lumped": [-results["xl8"]["models"]["lumped"][
                "peak_anvil_pile_force_error [-]"], "pct"],
            "rigid_min": [min(rigid), "pct+sig2"], "rigid_max": [max(rigid), "pct+sig2"]}
    subs.update(quoted_numbers(results))
    return {"errors": table}, subs


def quoted_numbers(results: dict) -> dict:
    """The figures docs/validation.md's text quotes beside the table, from the study's results:
    how much stiffer the contacts are than the anvil, how little the pile-contact convention
    (3 against 1) moves the peak, the thin anvil's rigid mass in a 500 Hz band, every case's
    re-impact (the FEA's steepest rise) and the ROM's distance to it, the first bending mode's
    share of the flexibility, the rim's lift-off, and the flexible massless anvil's (2b)
    errors."""
    ratios = [r[key] / r["anvil_through_stiffness [N/m]"] for r in results.values()
              for key in ("ram_contact_stiffness [N/m]",
                          "pile_contact_stiffness_full_segment [N/m]")]
    peak = {case: {m: v["peak_anvil_pile_force_error [-]"] for m, v in r["models"].items()
                   if m != "fea"} for case, r in results.items()}
    thin_500 = results["xl8_thin"]["peak_pile_force_by_band [N]"]["500"]
    rise = {case: r["models"]["fea"]["steepest_rise_time [s]"] for case, r in results.items()}
    lift = [r["models"]["fea"]["early_lift_off [s]"][0] for r in results.values()]
    share = [r["two_mass"]["fitted_mode_share_of_flexibility [-]"] for r in results.values()]
    static = [peak[c]["static"] for c in results if c != "xl8_thin"]
    subs = {
        "contact_stiffness_ratio_min": [min(ratios), "int"],
        "contact_stiffness_ratio_max": [max(ratios), "int"],
        "pile_contact_convention_max": [
            max(abs(p["ea_dx"] - p["lumped"]) for p in peak.values()), "pct"],
        "thin_lumped_500_hz": [thin_500["lumped"] / thin_500["fea"] - 1.0, "pct+"],
        "rom_rise_offset_max": [max(abs(r["models"]["rom"]["steepest_rise_time [s]"]
                                        - rise[c]) for c, r in results.items()), "ms"],
        "bending_share_min": [min(share), "pct"], "bending_share_max": [max(share), "pct"],
        "lift_off_min": [min(lift), "ms"], "lift_off_max": [max(lift), "ms"],
        "static_min": [min(static), "pct+"], "static_max": [max(static), "pct+"],
        "static_thin": [peak["xl8_thin"]["static"], "pct+"],
    }
    for case, rise_time in rise.items():
        subs[f"{case}_reimpact"] = [rise_time, "ms"]
    return subs


def write_docs(results: dict, command: str | None = None) -> None:
    """docs/data/study_lumped_conventions.json from the study's results."""
    tables, subs = docs_table(results)
    write_doc_data("study_lumped_conventions", about="pile-peak errors of the ROM and of the "
                   "lumped-mass conventions against one FEA per anvil (docs/validation.md, "
                   "\"Does a lumped anvil overestimate the pile force?\")",
                   inputs=system_inputs(ROOT / "anvilwave" / "examples" / "table1.toml"),
                   tables=tables, substitutions=subs, values=results, command=command)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_lumped")
    parser.add_argument("--docs-from", type=Path, default=None, metavar="STUDY_JSON",
                        help="only rewrite docs/data/study_lumped_conventions.json from the "
                             "study.json of an earlier run of this script")
    args = parser.parse_args()
    if args.docs_from is not None:
        write_docs(json.loads(args.docs_from.read_text())["cases"],
                   command="python benchmarks/study_lumped_conventions.py")
        return
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    base = base_config()
    results = {}
    for case in CASES:
        case_start = time.perf_counter()
        results[case.name] = run_case(case, base, args.out)
        fea = results[case.name]["fea"]
        print(f"{case.name}: FEA {fea['n_dof']} DOF, {fea['wall_time [s]']:.0f} s"
              f"{' (cached)' if fea['cached'] else ''}; case {time.perf_counter() - case_start:.0f}"
              " s", flush=True)
    total = time.perf_counter() - start
    tables = (f"Pile-peak error of each anvil model against the FEA (band-limited at "
              f"{results['xl8']['bandwidth [Hz]']:.0f} Hz; + = overestimates)\n\n"
              f"{summary_table(results)}\n\nPer model\n\n{detail_table(results)}\n\n"
              f"Band sensitivity of the pile peak (+ = overestimates the FEA)\n\n"
              f"{band_table(results)}\n")
    (args.out / "table.md").write_text(tables)
    (args.out / "study.json").write_text(json.dumps(
        {"cases": results, "total_time [s]": total}, indent=2, default=float) + "\n")
    write_docs(json.loads(json.dumps(results, default=float)))
    print("\n" + tables)
    print(f"total {total:.0f} s")


if __name__ == "__main__":
    main()
