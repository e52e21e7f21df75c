"""Figures of the PDA analyses (matplotlib, Agg backend): practitioner units (MN, kJ, ms, mm)
on the axes, SI in the data."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from anvilwave.output.figure_style import save_figure
from anvilwave.pile.pda.signal_matching import davisson_1972_offset_limit


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_pda(columns: dict, result, path: str | Path, title: str = "") -> Path:
    """F and Z v, wave down and up, and the transferred energy of a record, with t1 and t2.

    Parameters
    ----------
    columns : dict
        pda.csv columns.
    result : CaseMethodResult
        The :class:`anvilwave.pile.pda.case_method.CaseMethodResult`.
    path : str or Path
        The PNG file.
    title : str, default ""
        Figure title.

    Returns
    -------
    Path
        The written figure.
    """
    plt = _pyplot()
    t = columns["time [s]"] * 1e3
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True, constrained_layout=True)
    ax = axes[0]
    ax.plot(t, columns["force [N]"] / 1e6, color="k", lw=1.1, label="F")
    ax.plot(t, columns["impedance_times_velocity [N]"] / 1e6, color="tab:red", lw=1.1,
            ls="--", label="Z v")
    ax.set_ylabel("force [MN]")
    ax = axes[1]
    ax.plot(t, columns["wave_down [N]"] / 1e6, color="tab:blue", lw=1.1, label="wave down")
    ax.plot(t, columns["wave_up [N]"] / 1e6, color="tab:orange", lw=1.1, label="wave up")
    ax.set_ylabel("force [MN]")
    ax = axes[2]
    ax.plot(t, columns["transferred_energy [J]"] / 1e3, color="tab:green", lw=1.2,
            label=f"integral of F v dt (EMX = {result.emx / 1e3:.1f} kJ)")
    ax.set_ylabel("energy [kJ]")
    ax.set_xlabel("time [ms]")
    for ax in axes:
        for mark, name, style in ((result.t1, "t1", ":"), (result.t2, "t1 + 2L/c", "-.")):
            ax.axvline(mark * 1e3, color="0.5", lw=0.8, ls=style,
                       label=name if ax is axes[0] else None)
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
    axes[0].set_title(f"{title}\nRTL {result.rtl / 1e6:.2f} MN, RMX {result.rmx / 1e6:.2f} MN, "
                      f"FMX {result.fmx / 1e6:.2f} MN, CSX {result.csx / 1e6:.0f} MPa, "
                      f"BTA {result.bta:.2f}")
    return save_figure(fig, path, dpi=120)


def plot_match(columns: dict, path: str | Path, title: str = "") -> Path:
    """Measured against computed force (top) and wave up (bottom) of a signal match.

    Parameters
    ----------
    columns : dict
        match.csv columns (measured and computed force and wave up).
    path : str or Path
        The PNG file.
    title : str, default ""
        Figure title.

    Returns
    -------
    Path
        The written figure.
    """
    plt = _pyplot()
    t = columns["time [s]"] * 1e3
    fig, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True, constrained_layout=True)
    for ax, key, label in ((axes[0], "force", "force"), (axes[1], "wave_up", "wave up")):
        ax.plot(t, columns[f"measured_{key} [N]"] / 1e6, color="k", lw=1.1,
                label=f"measured {label}")
        ax.plot(t, columns[f"computed_{key} [N]"] / 1e6, color="tab:red", lw=1.1, ls="--",
                label=f"computed {label}")
        ax.set_ylabel("force [MN]")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
    axes[1].set_xlabel("time [ms]")
    axes[0].set_title(title)
    return save_figure(fig, path, dpi=120)


def plot_static_load_test(result, cfg, path: str | Path) -> Path:
    """Simulated static load test: load against head settlement, with Davisson's line.

    Parameters
    ----------
    result : MatchResult
        The signal match (its static load test and fitted soil),
        :class:`anvilwave.analyses.match.MatchResult`.
    cfg : SystemConfig
        The system configuration (its pile).
    path : str or Path
        The PNG file.

    Returns
    -------
    Path
        The written figure.
    """

    plt = _pyplot()
    curve = result.static_load_test
    s, q = curve["settlement [m]"], curve["load [N]"]
    pile = cfg.pile_soil.pile
    top = pile.sections[0]
    line_q = np.linspace(0.0, float(q.max()) * 1.1, 50)
    line_s = davisson_1972_offset_limit(line_q, pile.length, top.area, top.youngs_modulus,
                                        pile.sections[-1].outer_diameter)
    fig, ax = plt.subplots(figsize=(7, 5.5), constrained_layout=True)
    ax.plot(q / 1e6, s * 1e3, color="k", lw=1.4, label="fitted soil (quasi-static push)")
    ax.plot(line_q / 1e6, line_s * 1e3, color="tab:blue", lw=1.0, ls="--",
            label="Davisson (1972) offset line")
    ax.axvline(result.soil.rut / 1e6, color="tab:red", lw=0.9, ls=":",
               label=f"Rut = {result.soil.rut / 1e6:.2f} MN")
    ax.set_xlabel("load [MN]")
    ax.set_ylabel("head settlement [mm]")
    ax.invert_yaxis()
    ax.set_ylim(float(s.max()) * 1e3, 0.0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left")
    ax.set_title("Simulated static load test")
    return save_figure(fig, path, dpi=120)


def plot_compare_pda(columns: dict, quantity: str, path: str | Path, title: str) -> Path:
    """Measured (solid), lumped anvil (dashed) and ROM anvil (dash-dotted).

    As in the paper's Fig. 4 and 5.

    Parameters
    ----------
    columns : dict
        Comparison columns (``measured_``, ``lumped_`` and ``rom_`` of the quantity).
    quantity : {"force [N]", "velocity [m/s]"}
        The quantity shown.
    path : str or Path
        The PNG file.
    title : str
        Figure title.

    Returns
    -------
    Path
        The written figure.
    """
    plt = _pyplot()
    name, unit = quantity.split(" ")
    scale, label = (1e-6, "force [MN]") if name == "force" else (1.0, "velocity [m/s]")
    t = columns["time [s]"] * 1e3
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    ax.plot(t, columns[f"measured_{name} {unit}"] * scale, color="k", lw=1.3,
            label="PDA measurement")
    ax.plot(t, columns[f"lumped_{name} {unit}"] * scale, color="tab:blue", lw=1.2, ls="--",
            label="lumped-mass anvil")
    ax.plot(t, columns[f"rom_{name} {unit}"] * scale, color="tab:red", lw=1.2, ls="-.",
            label="ROM anvil")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel(label)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    return save_figure(fig, path, dpi=120)
