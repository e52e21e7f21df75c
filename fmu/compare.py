"""The paper's comparison: ROM anvil (through the FMUs), rigid lumped anvil and the reference
impact FEA on one configuration, with the error measures and Fig. 2 / Fig. 3.

Soil is left out of all three models here: the FEA models the pile top (with an absorbing cut)
and no soil; the 1D models see the same pile without shaft resistance, standing on an elastic
toe bearing (which carries the static weight): its toe reflection (2 L / c, 31 ms for 80 m)
falls outside the 25 ms window, as in the paper.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from anvil_rom.inputs import InputError
from pile.model import PileSoil

from .system import SystemConfig

ARRIVAL_FRACTION = 0.2
"""The pile force 'arrives' when it first exceeds this fraction of its peak (above the static
preload): a threshold clear of the preload (1 % of the peak) and of the lift-off dip."""


def without_soil(cfg: SystemConfig) -> SystemConfig:
    """The same system on a pile without shaft resistance, standing on an elastic toe bearing
    (unit toe resistance 1 GPa, no damping): the comparison's common ground with the FEA."""
    from pile.soil import SoilSpec
    from pile.srd import SoilResistanceTable

    toe_only = SoilSpec(model="smith-viscous", penetration=0.0,
                        srd=SoilResistanceTable.from_rows(np.array([[0.0, 0.0, 1.0e9]])),
                        damping_shaft=0.0, damping_toe=0.0)
    return dataclasses.replace(cfg, pile_soil=PileSoil(cfg.pile_soil.pile, toe_only))


def fea_config(cfg: SystemConfig, *, mesh_size: float | None = None,
               truncate_length: float | None = None, output_interval: float = 1e-5):
    """The reference FEA configuration of a system (uniform cylindrical ram, first pile section).

    truncate_length : modelled pile length with an absorbing cut [m] (None: full length).
    """
    from anvil_rom.fea import FeaConfig

    ram = cfg.hammer.ram
    if not (math.isfinite(ram.toe_diameter) and math.isfinite(ram.length)):
        raise InputError(cfg.source, "hammer", "the reference FEA needs a ram given as a "
                                               "cylinder (diameter and length)")
    section = cfg.pile_soil.pile.sections[0]
    kwargs = {}
    if mesh_size is not None:
        kwargs["mesh_size"] = mesh_size
    pile_length = cfg.pile_soil.pile.length
    truncate = None if truncate_length is None else min(truncate_length, pile_length)
    duration = round(cfg.duration / output_interval) * output_interval
    return FeaConfig(
        ram_radius=0.5 * ram.toe_diameter, ram_length=ram.length,
        impact_velocity=cfg.impact_velocity, anvil=cfg.anvil.spec,
        pile_outer_diameter=section.outer_diameter, pile_wall_thickness=section.wall_thickness,
        pile_length=pile_length, truncate_length=truncate,
        gauge_depth=cfg.pile_soil.pile.gauge_depth, duration=duration,
        gravity=cfg.gravity, output_interval=output_interval, **kwargs)


@dataclass
class ModelRun:
    """One model's time series (CSV columns) and its wall time of the stepping [s]."""

    name: str
    columns: dict[str, np.ndarray]
    wall_time: float
    info: dict


def arrival_time(time_s: np.ndarray, force: np.ndarray, preload: float = 0.0) -> float:
    """First time [s] the force exceeds preload + ARRIVAL_FRACTION (peak - preload)."""
    level = preload + ARRIVAL_FRACTION * (force.max() - preload)
    above = np.flatnonzero(force > level)
    return float(time_s[above[0]]) if above.size else math.nan


def normalised_rms_error(time_s: np.ndarray, force: np.ndarray, ref_time: np.ndarray,
                         ref_force: np.ndarray) -> float:
    """RMS of (model - reference) on the reference's time grid over the common window, divided
    by the reference's peak |force| [-]."""
    window = (ref_time >= max(time_s[0], ref_time[0])) & (ref_time <= min(time_s[-1],
                                                                          ref_time[-1]))
    model = np.interp(ref_time[window], time_s, force)
    return float(np.sqrt(np.mean((model - ref_force[window]) ** 2))
                 / np.abs(ref_force[window]).max())


def metrics(run: ModelRun, reference: ModelRun | None, preload: float) -> dict:
    c = run.columns
    t = c["time [s]"]
    out = {
        "peak_ram_anvil_force [N]": float(c["ram_anvil_force [N]"].max()),
        "peak_anvil_pile_force [N]": float(c["anvil_pile_force [N]"].max()),
        "pile_force_arrival_time [s]": arrival_time(t, c["anvil_pile_force [N]"], preload),
        "wall_time [s]": run.wall_time,
    }
    if reference is not None:
        r = reference.columns
        rt = r["time [s]"]
        for key in ("ram_anvil_force [N]", "anvil_pile_force [N]", "gauge_force [N]"):
            name = key.split(" ")[0]
            out[f"{name}_normalised_rms_error [-]"] = normalised_rms_error(t, c[key], rt, r[key])
        for key in ("peak_ram_anvil_force [N]", "peak_anvil_pile_force [N]"):
            ref = metrics(reference, None, preload)[key]
            out[key.replace(" [N]", "_error [-]")] = out[key] / ref - 1.0
        ref_arrival = arrival_time(rt, r["anvil_pile_force [N]"], preload)
        out["pile_force_arrival_error [s]"] = out["pile_force_arrival_time [s]"] - ref_arrival
    return out


def run_models(cfg: SystemConfig, work_dir, *, rom_engine: str = "fmi", fea=True,
               fea_mesh_size: float | None = None, progress=None) -> dict[str, ModelRun]:
    """Run the ROM, the lumped anvil and (optionally) the FEA on a free-pile copy of ``cfg``."""
    from .engine import build_engine

    cfg = without_soil(cfg)
    runs = {}
    for model in ("rom", "lumped"):
        start = time.perf_counter()
        if model == "rom" and rom_engine == "fmi":
            from .fmi_engine import run_fmi

            blow = run_fmi(cfg.with_anvil_model("rom"), work_dir / "fmus", anvil_model="rom")[0]
        else:
            blow = build_engine(cfg.with_anvil_model(model)).run()[0]
        runs[model] = ModelRun(model, blow.columns, blow.wall_time,
                               {"time_step [s]": blow.time_step,
                                "total_time [s]": time.perf_counter() - start,
                                "engine": rom_engine if model == "rom" else "direct"})
    if fea:
        from anvil_rom.fea import run_impact_fea

        config = fea_config(cfg, mesh_size=fea_mesh_size)
        result = run_impact_fea(config, progress=progress)
        runs["fea"] = ModelRun("fea", result.to_columns(), result.wall_time,
                               {"n_dof": result.n_dof, "n_steps": result.n_steps,
                                "time_step [s]": result.time_step,
                                "setup_time [s]": result.setup_time})
    return runs


def compare(runs: dict[str, ModelRun], preload: float) -> dict:
    """comparison.json content: per model the metrics, the errors against the FEA."""
    reference = runs.get("fea")
    out = {name: metrics(run, reference if name != "fea" else None, preload)
           for name, run in runs.items()}
    for name, run in runs.items():
        out[name].update(run.info)
    if reference is not None:
        out["fea_over_rom_wall_time [-]"] = reference.wall_time / max(runs["rom"].wall_time,
                                                                      1e-12)
    return out


def plot_comparison(runs: dict[str, ModelRun], key: str, path, title: str):
    """Fig. 2 (ram impact force) or Fig. 3 (pile-top force): FEA vs ROM vs lumped."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"fea": ("k", "-", "FEA (reference)"), "rom": ("tab:red", "--", "ROM anvil"),
              "lumped": ("tab:blue", "-.", "lumped-mass anvil")}
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    for name, run in runs.items():
        color, ls, label = styles.get(name, ("0.5", ":", name))
        ax.plot(run.columns["time [s]"] * 1e3, run.columns[key] / 1e6, color=color, ls=ls,
                lw=1.4 if name == "fea" else 1.2, label=label)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("force [MN]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.savefig(path, dpi=120)
    plt.close(fig)
