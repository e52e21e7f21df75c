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

from anvilwave_inputs import InputError
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
    from anvilwave.fea.impact import FeaConfig

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


def comparison_bandwidth(cfg: SystemConfig) -> float:
    """The frequency band [Hz] in which the models are compared: the cut-off c / (pi dx) of the
    pile's lumped chain (the highest frequency a Smith pile of this segment length carries; the
    ROM's fmax when lower). Above it the 1D models represent nothing by construction, and the
    FEA's contact faces ring at 25-50 kHz with an amplitude set by its penalty stiffness."""
    seg = cfg.pile_soil.pile.discretise()
    cutoff = float(np.min(seg.wave_speed / (np.pi * seg.length)))
    if cfg.anvil.fmax is not None:
        cutoff = min(cutoff, cfg.anvil.fmax)
    return cutoff


def lowpass(time_s: np.ndarray, signal: np.ndarray, cutoff: float) -> np.ndarray:
    """Zero-phase 4th-order Butterworth low-pass at ``cutoff`` [Hz] of a uniformly sampled
    signal (scipy sosfiltfilt: no time shift, so arrival times are kept)."""
    from scipy.signal import butter, sosfiltfilt

    fs = 1.0 / float(time_s[1] - time_s[0])
    if cutoff >= 0.5 * fs:
        return signal
    return sosfiltfilt(butter(4, cutoff, fs=fs, output="sos"), signal)


def band_limited(columns: dict[str, np.ndarray], key: str, grid: np.ndarray,
                 cutoff: float) -> np.ndarray:
    """Column ``key`` interpolated onto the uniform ``grid`` [s] and low-passed at ``cutoff``
    [Hz] (:func:`lowpass`)."""
    return lowpass(grid, np.interp(grid, columns["time [s]"], columns[key]), cutoff)


def lift_off_intervals(time_s: np.ndarray, force: np.ndarray, min_duration: float = 5e-5
                       ) -> list[list[float]]:
    """Intervals [start, end] [s] in which the anvil-pile contact is open (force zero) after it
    first carried load, lasting at least ``min_duration`` [s]: the anvil lifting off the pile
    and re-impacting."""
    open_ = force <= 0.0
    intervals = []
    start = None
    for i in range(1, len(force)):
        if open_[i] and not open_[i - 1]:
            start = time_s[i]
        elif not open_[i] and open_[i - 1] and start is not None:
            if time_s[i] - start >= min_duration:
                intervals.append([float(start), float(time_s[i])])
            start = None
    return intervals


def arrival_time(time_s: np.ndarray, force: np.ndarray, preload: float = 0.0) -> float:
    """First time [s] the force exceeds preload + ARRIVAL_FRACTION (peak - preload)."""
    level = preload + ARRIVAL_FRACTION * (force.max() - preload)
    above = np.flatnonzero(force > level)
    return float(time_s[above[0]]) if above.size else math.nan


def metrics(run: ModelRun, reference: ModelRun | None, preload: float,
            bandwidth: float) -> dict:
    """Peaks (raw and in the comparison band), arrival time and errors against ``reference``.

    All band-limited measures use the reference's uniform time grid: the model is interpolated
    onto it and both are low-passed at ``bandwidth`` [Hz].
    """
    grid = (reference or run).columns["time [s]"]
    grid = np.linspace(grid[0], grid[-1], len(grid))

    def band(columns, key):
        return band_limited(columns, key, grid, bandwidth)

    c = run.columns
    out = {
        "peak_ram_anvil_force [N]": float(band(c, "ram_anvil_force [N]").max()),
        "peak_anvil_pile_force [N]": float(band(c, "anvil_pile_force [N]").max()),
        "peak_ram_anvil_force_unfiltered [N]": float(c["ram_anvil_force [N]"].max()),
        "peak_anvil_pile_force_unfiltered [N]": float(c["anvil_pile_force [N]"].max()),
        "pile_force_arrival_time [s]": arrival_time(grid, band(c, "anvil_pile_force [N]"),
                                                    preload),
        "wall_time [s]": run.wall_time,
        "anvil_lift_off_intervals [s]": lift_off_intervals(c["time [s]"],
                                                           c["anvil_pile_force [N]"]),
    }
    if reference is not None:
        r = reference.columns
        ref = metrics(reference, None, preload, bandwidth)
        for key in ("ram_anvil_force [N]", "anvil_pile_force [N]", "gauge_force [N]"):
            name = key.split(" ")[0]
            model, truth = band(c, key), band(r, key)
            out[f"{name}_normalised_rms_error [-]"] = float(
                np.sqrt(np.mean((model - truth) ** 2)) / np.abs(truth).max())
        for key in ("peak_ram_anvil_force [N]", "peak_anvil_pile_force [N]",
                    "peak_ram_anvil_force_unfiltered [N]",
                    "peak_anvil_pile_force_unfiltered [N]"):
            out[key.replace(" [N]", "_error [-]")] = out[key] / ref[key] - 1.0
        out["pile_force_arrival_error [s]"] = (out["pile_force_arrival_time [s]"]
                                               - ref["pile_force_arrival_time [s]"])
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

            blow = run_fmi(cfg.with_anvil_model("rom"), work_dir / "fmus")[0]
        else:
            blow = build_engine(cfg.with_anvil_model(model)).run()[0]
        runs[model] = ModelRun(model, blow.columns, blow.wall_time,
                               {"time_step [s]": blow.time_step,
                                "total_time [s]": time.perf_counter() - start,
                                "engine": rom_engine if model == "rom" else "direct"})
    if fea:
        from anvilwave.fea.impact import run_impact_fea

        config = fea_config(cfg, mesh_size=fea_mesh_size)
        result = run_impact_fea(config, progress=progress)
        runs["fea"] = ModelRun("fea", result.to_columns(), result.wall_time,
                               {"n_dof": result.n_dof, "n_steps": result.n_steps,
                                "time_step [s]": result.time_step,
                                "setup_time [s]": result.setup_time})
    return runs


def compare(runs: dict[str, ModelRun], preload: float, bandwidth: float) -> dict:
    """comparison.json content: per model the metrics, the errors against the FEA."""
    reference = runs.get("fea")
    out = {name: metrics(run, reference if name != "fea" else None, preload, bandwidth)
           for name, run in runs.items()}
    out["comparison_bandwidth [Hz]"] = bandwidth
    for name, run in runs.items():
        out[name].update(run.info)
    if reference is not None:
        out["fea_over_rom_wall_time [-]"] = reference.wall_time / max(runs["rom"].wall_time,
                                                                      1e-12)
    return out


def plot_comparison(runs: dict[str, ModelRun], key: str, path, title: str,
                    bandwidth: float | None = None):
    """Fig. 2 (ram impact force) or Fig. 3 (pile-top force): FEA vs ROM vs lumped.

    bandwidth : low-pass every curve at this frequency [Hz] (:func:`lowpass`), the band in
        which the models are compared; None plots the raw series. Above it no model is
        meaningful: the 1D chains end at their cut-off, and the contacts ring at modes set by
        the truncation (a modal ram's face, 5.6 t on its residual spring, at 5.2 kHz for Table
        1) or by a penalty (the FEA's faces at 25-50 kHz).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"fea": ("k", "-", "FEA (reference)"), "rom": ("tab:red", "--", "ROM anvil"),
              "lumped": ("tab:blue", "-.", "lumped-mass anvil")}
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    for name, run in runs.items():
        color, ls, label = styles.get(name, ("0.5", ":", name))
        t, f = run.columns["time [s]"], run.columns[key]
        if bandwidth is not None:
            t = np.linspace(t[0], t[-1], len(t))
            f = band_limited(run.columns, key, t, bandwidth)
        ax.plot(t * 1e3, f / 1e6, color=color, ls=ls, lw=1.4 if name == "fea" else 1.2,
                label=label)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("force [MN]")
    if bandwidth is not None:
        title += (f"\n(low-passed at {bandwidth:.0f} Hz, the comparison band; "
                  "raw series in the CSVs)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.savefig(path, dpi=120)
    plt.close(fig)
