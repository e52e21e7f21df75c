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

from anvilwave.config.system import SystemConfig
from anvilwave.engine.direct import build_engine
from anvilwave.engine.fmi import run_fmi
from anvilwave.fea.cache import cached_impact_fea
from anvilwave.fea.impact import FeaConfig
from anvilwave.inputs import InputError
from anvilwave.output.figure_style import save_figure
from anvilwave.output.progress import Step
from anvilwave.pile.model import PileSoil
from anvilwave.pile.post.spectra import band_numbers_between, third_octave_band_energies
from anvilwave.pile.soil.models import SoilSpec
from anvilwave.pile.soil.srd import SoilResistanceTable

ARRIVAL_FRACTION = 0.2
"""The pile force 'arrives' when it first exceeds this fraction of its peak (above the static
preload): a threshold clear of the preload (1 % of the peak) and of the lift-off dip."""


def without_soil(cfg: SystemConfig) -> SystemConfig:
    """The same system on a pile without shaft resistance, standing on an elastic toe bearing.

    Unit toe resistance 1 GPa, no damping: the comparison's common ground with the FEA.

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    SystemConfig
        A copy with the toe-only soil.
    """

    toe_only = SoilSpec(model="smith-viscous", penetration=0.0,
                        srd=SoilResistanceTable.from_rows(np.array([[0.0, 0.0, 1.0e9]])),
                        damping_shaft=0.0, damping_toe=0.0)
    return dataclasses.replace(cfg, pile_soil=PileSoil(cfg.pile_soil.pile, toe_only))


def fea_config(cfg: SystemConfig, *, mesh_size: float | None = None,
               truncate_length: float | None = None, output_interval: float = 1e-5):
    """The reference FEA configuration of a system (uniform cylindrical ram, first pile section).

    With the system's driving stack (``[[anvil.bodies]]``) the FEA's anvil ring and seat
    friction are the stack's (``FeaConfig.ring``, ``seat_friction``).

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    mesh_size : float, optional
        Element size of the FEA [m] (None: the :class:`FeaConfig` default).
    truncate_length : float, optional
        Modelled pile length with an absorbing cut [m] (None: full length).
    output_interval : float, default 1e-5
        Output time step [s].

    Returns
    -------
    FeaConfig
        The FEA configuration.

    Raises
    ------
    InputError
        If the ram is not given as a cylinder (diameter and length).
    """

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
    stack = cfg.anvil.stack
    if stack is not None:
        kwargs.update(ring=stack.ring, seat_friction=stack.seat_friction)
    return FeaConfig(
        ram_radius=0.5 * ram.toe_diameter, ram_length=ram.length,
        impact_velocity=cfg.impact_velocity, anvil=cfg.anvil.spec,
        pile_outer_diameter=section.outer_diameter, pile_wall_thickness=section.wall_thickness,
        pile_length=pile_length, truncate_length=truncate,
        gauge_depth=cfg.pile_soil.pile.gauge_depth, duration=duration,
        gravity=cfg.gravity, output_interval=output_interval, **kwargs)


@dataclass
class ModelRun:
    """One model's time series (CSV columns) and its wall time of the stepping [s].

    Parameters
    ----------
    name : str
        Model name ("rom", "lumped", "fea").
    columns : dict of str to numpy.ndarray
        Time series named ``name [unit]``.
    wall_time : float
        Wall time of the stepping [s].
    info : dict
        Run statistics (time step, setup time, engine, ...).
    """

    name: str
    columns: dict[str, np.ndarray]
    wall_time: float
    info: dict


def comparison_bandwidth(cfg: SystemConfig) -> float:
    """The frequency band [Hz] in which the models are compared.

    The cut-off c / (pi dx) of the pile's lumped chain (the highest frequency a Smith pile of
    this segment length carries; the ROM's fmax when lower). Above it the 1D models represent
    nothing by construction, and the FEA's contact faces ring at 25-50 kHz with an amplitude set
    by its penalty stiffness.

    Parameters
    ----------
    cfg : SystemConfig
        The system.

    Returns
    -------
    float
        The comparison bandwidth [Hz].
    """
    seg = cfg.pile_soil.pile.discretise()
    cutoff = float(np.min(seg.wave_speed / (np.pi * seg.length)))
    if cfg.anvil.fmax is not None:
        cutoff = min(cutoff, cfg.anvil.fmax)
    return cutoff


def lowpass(time_s: np.ndarray, signal: np.ndarray, cutoff: float) -> np.ndarray:
    """Zero-phase 4th-order Butterworth low-pass at ``cutoff`` [Hz] of a uniformly sampled signal.

    scipy sosfiltfilt: no time shift, so arrival times are kept.

    Parameters
    ----------
    time_s : numpy.ndarray
        Uniform sample times [s].
    signal : numpy.ndarray
        The signal.
    cutoff : float
        Cut-off frequency [Hz]; at or above the Nyquist frequency the signal is returned as is.

    Returns
    -------
    numpy.ndarray
        The filtered signal.
    """
    from scipy.signal import butter, sosfiltfilt

    fs = 1.0 / float(time_s[1] - time_s[0])
    if cutoff >= 0.5 * fs:
        return signal
    return sosfiltfilt(butter(4, cutoff, fs=fs, output="sos"), signal)


def band_limited(columns: dict[str, np.ndarray], key: str, grid: np.ndarray,
                 cutoff: float) -> np.ndarray:
    """Column ``key`` interpolated onto the uniform ``grid`` [s] and low-passed at ``cutoff`` [Hz].

    See :func:`lowpass`.

    Parameters
    ----------
    columns : dict of str to numpy.ndarray
        Time series with a ``time [s]`` column.
    key : str
        The column.
    grid : numpy.ndarray
        Uniform time grid [s].
    cutoff : float
        Cut-off frequency [Hz].

    Returns
    -------
    numpy.ndarray
        The band-limited column on ``grid``.
    """
    return lowpass(grid, np.interp(grid, columns["time [s]"], columns[key]), cutoff)


def lift_off_intervals(time_s: np.ndarray, force: np.ndarray, min_duration: float = 5e-5
                       ) -> list[list[float]]:
    """Intervals [start, end] [s] in which the anvil-pile contact is open (force zero).

    Only after it first carried load, lasting at least ``min_duration`` [s]: the anvil lifting
    off the pile and re-impacting.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s].
    force : numpy.ndarray
        Anvil-pile contact force [N].
    min_duration : float, default 5e-5
        Shortest interval reported [s].

    Returns
    -------
    list of list of float
        The [start, end] intervals [s].
    """
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
    """First time [s] the force exceeds preload + ARRIVAL_FRACTION (peak - preload).

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times [s].
    force : numpy.ndarray
        The force [N].
    preload : float, default 0.0
        Static preload [N].

    Returns
    -------
    float
        The arrival time [s], NaN if never.
    """
    level = preload + ARRIVAL_FRACTION * (force.max() - preload)
    above = np.flatnonzero(force > level)
    return float(time_s[above[0]]) if above.size else math.nan


def metrics(run: ModelRun, reference: ModelRun | None, preload: float,
            bandwidth: float) -> dict:
    """Peaks (raw and in the comparison band), arrival time and errors against ``reference``.

    All band-limited measures use the reference's uniform time grid: the model is interpolated
    onto it and both are low-passed at ``bandwidth`` [Hz].

    Parameters
    ----------
    run : ModelRun
        The model run.
    reference : ModelRun or None
        The reference (FEA) run; None gives no errors.
    preload : float
        Static anvil-pile preload [N].
    bandwidth : float
        Comparison bandwidth [Hz].

    Returns
    -------
    dict
        Metrics named ``name [unit]``.
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
        # what a user reads (the model's raw output) against the reference in the band
        for name in ("ram_anvil_force", "anvil_pile_force"):
            out[f"peak_{name}_unfiltered_vs_reference_band_error [-]"] = (
                out[f"peak_{name}_unfiltered [N]"] / ref[f"peak_{name} [N]"] - 1.0)
        out["pile_force_arrival_error [s]"] = (out["pile_force_arrival_time [s]"]
                                               - ref["pile_force_arrival_time [s]"])
    return out


ANVIL_NAMES = {"rom": "ROM anvil", "lumped": "lumped-mass anvil"}
"""How the progress lines name the anvil models."""


def run_models(cfg: SystemConfig, work_dir, *, rom_engine: str = "fmi", fea=True,
               fea_mesh_size: float | None = None, progress=None) -> dict[str, ModelRun]:
    """Run the ROM, the lumped anvil and (optionally) the FEA on a free-pile copy of ``cfg``.

    Parameters
    ----------
    cfg : SystemConfig
        The system (its soil is replaced, :func:`without_soil`).
    work_dir : Path
        Working folder (the FMUs are built in ``work_dir / "fmus"``).
    rom_engine : {"fmi", "direct"}
        Engine of the ROM run ("fmi": through the FMUs).
    fea : bool, default True
        Whether to run the reference FEA.
    fea_mesh_size : float, optional
        Element size of the FEA [m].
    progress : callable, optional
        Progress callback of the FEA (fraction in [0, 1]).

    Returns
    -------
    dict of str to ModelRun
        The runs by model name ("rom", "lumped", "fea").
    """

    cfg = without_soil(cfg)
    runs = {}
    talk = progress is not None
    for model in ("rom", "lumped"):
        start = time.perf_counter()
        what = ("the ROM anvil through the FMUs (fmpy co-simulation)" if model == "rom"
                and rom_engine == "fmi" else f"the {ANVIL_NAMES[model]} (in-process engine)")
        with Step(f"    running {what}...", enabled=talk):
            if model == "rom" and rom_engine == "fmi":
                blow = run_fmi(cfg.with_anvil_model("rom"), work_dir / "fmus")[0]
            else:
                blow = build_engine(cfg.with_anvil_model(model)).run()[0]
        runs[model] = ModelRun(model, blow.columns, blow.wall_time,
                               {"time_step [s]": blow.time_step,
                                "total_time [s]": time.perf_counter() - start,
                                "engine": rom_engine if model == "rom" else "direct"})
    if fea:
        config = fea_config(cfg, mesh_size=fea_mesh_size)
        setup = Step("    running the reference FEA: meshing ram, anvil and pile top and "
                     "assembling...", enabled=talk).__enter__()

        def stepping(fraction: float) -> None:
            setup.__exit__(None, None, None)  # the stepping has started: its bar takes over
            progress(fraction)

        result = cached_impact_fea(config, progress=stepping if talk else None)
        setup.__exit__(None, None, None)
        runs["fea"] = ModelRun("fea", result.to_columns(), result.wall_time,
                               {"n_dof": result.n_dof, "n_steps": result.n_steps,
                                "time_step [s]": result.time_step,
                                "setup_time [s]": result.setup_time})
    return runs


def compare(runs: dict[str, ModelRun], preload: float, bandwidth: float) -> dict:
    """comparison.json content: per model the metrics, the errors against the FEA.

    Parameters
    ----------
    runs : dict of str to ModelRun
        The runs by model name.
    preload : float
        Static anvil-pile preload [N].
    bandwidth : float
        Comparison bandwidth [Hz].

    Returns
    -------
    dict
        The comparison content.
    """
    reference = runs.get("fea")
    out = {name: metrics(run, reference if name != "fea" else None, preload, bandwidth)
           for name, run in runs.items()}
    out["comparison_bandwidth [Hz]"] = bandwidth
    for name, run in runs.items():
        out[name].update(run.info)
    if reference is not None:
        out["fea_over_rom_wall_time [-]"] = reference.wall_time / max(runs["rom"].wall_time,
                                                                      1e-12)
    out["pile_head_force_spectra"] = band_levels(runs, bandwidth)
    return out


SPECTRUM_KEY = "anvil_pile_force [N]"
"""The force whose spectra are compared: the pile-head (anvil-pile contact) force."""


def band_levels(runs: dict[str, ModelRun], bandwidth: float,
                key: str = SPECTRUM_KEY) -> dict:
    """One-third-octave band levels of ``key`` of every model and their deviations from the FEA's.

    For comparison.json (:func:`anvilwave.pile.post.spectra.third_octave_band_energies`), in
    [dB]. Each model's own samples are used (no resampling, which would filter its top bands);
    the force is taken relative to its value at the first sample (the static weight on the pile
    carries no sound). The bands run from 10 Hz to the lowest Nyquist frequency of the models.
    The valid band is where every model's spectrum is trustworthy
    (:func:`anvilwave.pile.post.spectra.valid_band`: from 1 / T of the shortest record up to a
    tenth of the lowest sampling rate) and no higher than ``bandwidth`` [Hz], the comparison
    band of the 1D models (:func:`comparison_bandwidth`).

    Parameters
    ----------
    runs : dict of str to ModelRun
        The runs by model name.
    bandwidth : float
        Comparison bandwidth [Hz].
    key : str, default SPECTRUM_KEY
        The force column.

    Returns
    -------
    dict
        Band centres [Hz], valid band [Hz], levels [dB re 1 N^2 s] and deviations from the
        FEA [dB].
    """

    def step(run):
        t = run.columns["time [s]"]
        return float(t[-1] - t[0]) / (len(t) - 1)

    nyquist = min(0.5 / step(run) for run in runs.values())
    numbers = band_numbers_between(8.9, nyquist)
    bands = {}
    for name, run in runs.items():
        force = np.asarray(run.columns[key], float)
        bands[name] = third_octave_band_energies(force - force[0], step(run), numbers)
    low = max(b.valid_range[0] for b in bands.values())
    high = min(min(b.valid_range[1] for b in bands.values()), bandwidth)
    first = next(iter(bands.values()))
    valid = (first.lower_frequency >= low) & (first.upper_frequency <= high)

    def listed(values):
        return [float(x) if math.isfinite(x) else None for x in values]

    out = {
        "force": key,
        "band_centre_frequency [Hz]": listed(first.centre_frequency),
        "valid_band [Hz]": [low, high],
        "valid [-]": valid.astype(int).tolist(),
        "band_level [dB re 1 N^2 s]": {name: listed(b.level) for name, b in bands.items()},
    }
    if "fea" in bands:
        reference = bands["fea"].level
        deviation = {name: b.level - reference for name, b in bands.items() if name != "fea"}
        out["deviation_from_fea [dB]"] = {name: listed(d) for name, d in deviation.items()}
        out["max_abs_deviation_in_valid_band [dB]"] = {
            name: float(np.max(np.abs(d[valid]))) if valid.any() else None
            for name, d in deviation.items()}
    return out


def plot_spectra(spectra: dict, path, title: str = "Pile-head force, one-third-octave bands"):
    """Band levels of every model (:func:`band_levels` output) with the valid band shaded out.

    The lower panel shows the deviations from the FEA [dB].

    Parameters
    ----------
    spectra : dict
        Output of :func:`band_levels`.
    path : str or Path
        The PNG file.
    title : str, default "Pile-head force, one-third-octave bands"
        Figure title.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"fea": ("k", "o", "FEA (reference)"), "rom": ("tab:red", "s", "ROM anvil"),
              "lumped": ("tab:blue", "^", "lumped-mass anvil")}
    centre = np.asarray(spectra["band_centre_frequency [Hz]"], float)
    low, high = spectra["valid_band [Hz]"]
    deviations = spectra.get("deviation_from_fea [dB]", {})
    fig, axes = plt.subplots(2 if deviations else 1, 1, figsize=(9, 6.5 if deviations else 4.5),
                             sharex=True, constrained_layout=True, squeeze=False)
    ax = axes[0, 0]
    for name, level in spectra["band_level [dB re 1 N^2 s]"].items():
        color, marker, label = styles.get(name, ("0.5", "x", name))
        ax.semilogx(centre, np.array(level, float), color=color, marker=marker, ms=3.5,
                    lw=1.2, label=label)
    ax.set_ylabel("band level [dB re 1 N$^2$ s]")
    ax.set_title(f"{title}\n(valid band {low:.0f}-{high:.0f} Hz, unshaded)")
    if deviations:
        dev_ax = axes[1, 0]
        for name, dev in deviations.items():
            color, marker, label = styles.get(name, ("0.5", "x", name))
            dev_ax.semilogx(centre, np.array(dev, float), color=color, marker=marker, ms=3.5,
                            lw=1.2, label=f"{label} - FEA")
        dev_ax.axhspan(-1.0, 1.0, color="tab:green", alpha=0.2, zorder=1, label="+-1 dB")
        dev_ax.set_ylabel("deviation from FEA [dB]")
        dev_ax.set_ylim(-25.0, 15.0)
        dev_ax.legend(fontsize=8)
    for row in axes[:, 0]:
        row.axvspan(centre.min() / 1.2, low, color="0.92", zorder=0)
        row.axvspan(high, centre.max() * 1.2, color="0.92", zorder=0)
        row.grid(alpha=0.3, which="both")
    axes[0, 0].legend(fontsize=8)
    axes[-1, 0].set_xlabel("one-third-octave band centre frequency [Hz]")
    save_figure(fig, path, dpi=120)


def plot_comparison(runs: dict[str, ModelRun], key: str, path, title: str,
                    bandwidth: float | None = None):
    """Fig. 2 (ram impact force) or Fig. 3 (pile-top force): FEA vs ROM vs lumped.

    Parameters
    ----------
    runs : dict of str to ModelRun
        The runs by model name.
    key : str
        The force column shown.
    path : str or Path
        The PNG file.
    title : str
        Figure title.
    bandwidth : float, optional
        Low-pass every curve at this frequency [Hz] (:func:`lowpass`), the band in which the
        models are compared; None plots the raw series. Above it no model is meaningful: the
        1D chains end at their cut-off, and the contacts ring at modes set by the truncation (a
        modal ram's face, 5.6 t on its residual spring, at 5.2 kHz for Table 1) or by a penalty
        (the FEA's faces at 25-50 kHz).
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
    save_figure(fig, path, dpi=120)
