"""Figures (matplotlib, Agg backend): kept apart from the computations."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from anvilwave.config.drive import DEFAULT_REFUSAL
from anvilwave.output.figure_style import save_figure
from anvilwave.output.tables import blow_count_profile
from anvilwave.pile.pile import ALLOWABLE_DRIVING_STRESS_RATIO, DEFAULT_YIELD_STRENGTH


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


MODE_SHAPE_SCALE = 0.08
"""The largest displacement of a drawn mode shape, as a fraction of the anvil's size [-]."""


def plot_modes(result, path: str | Path, n_shapes: int = 5) -> Path:
    """Mesh and the first flexible mode shapes of an anvil (``AnvilModes``) as PNG.

    Parameters
    ----------
    result : AnvilModes
        The modal analysis of the anvil.
    path : str or Path
        The PNG file.
    n_shapes : int, default 5
        Number of flexible mode shapes shown (at most those available).

    Returns
    -------
    Path
        The written figure.
    """
    import matplotlib.tri as mtri

    plt = _pyplot()
    model, modes = result.model, result.modes
    mesh = model.mesh
    nv = mesh.t.max() + 1
    r, z = mesh.p[0, :nv], mesh.p[1, :nv]
    n_shapes = min(n_shapes, modes.n_modes - 1)
    ncols = min(3, n_shapes + 1)
    nrows = -(-(n_shapes + 1) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 2.4 * nrows),
                             constrained_layout=True, squeeze=False)
    for ax in axes.flat[n_shapes + 1:]:
        ax.set_visible(False)
    axes = axes.flat[: n_shapes + 1]
    tri = mtri.Triangulation(r, z, mesh.t.T)
    axes[0].triplot(tri, lw=0.2, color="0.3")
    if result.b_ram is not None:
        for vec, color, label in ((result.b_ram, "tab:red", "ram face"),
                                  (result.b_pile, "tab:blue", "pile ring")):
            loaded = np.abs(model.nodal(vec)[:, 1]) > 0
            xy = model.node_coordinates[loaded]
            axes[0].plot(xy[:, 0], xy[:, 1], ".", ms=3,
                         color=color, label=label)
        axes[0].legend(loc="lower left", fontsize=7)
    axes[0].set_title(f"{result.spec.name}: {model.n_dof} DOF", fontsize=9)
    extent = max(np.ptp(r), np.ptp(z))
    drawn = MODE_SHAPE_SCALE * extent  # the largest displacement of each shape, as drawn [m]
    image = None
    for k, ax in enumerate(axes[1:], start=1):
        disp = model.nodal(modes.shapes[:, k])[:nv]
        mag = np.hypot(disp[:, 0], disp[:, 1])
        peak = max(float(mag.max()), 1e-300)
        scale = drawn / peak
        dtri = mtri.Triangulation(r + scale * disp[:, 0], z + scale * disp[:, 1], mesh.t.T)
        image = ax.tripcolor(dtri, mag / peak, shading="gouraud", cmap="viridis", vmin=0.0,
                             vmax=1.0)
        ax.triplot(tri, lw=0.15, color="0.7", alpha=0.5)
        ax.set_title(f"mode {k + 1}: {modes.frequencies[k]:.1f} Hz (shape x {scale:.3g})",
                     fontsize=9)
    for ax in axes:
        ax.set_aspect("equal")
        ax.invert_yaxis()
        ax.set_xlabel("r [m]")
    axes[0].set_ylabel("z [m] (down)")
    if image is not None:
        bar = fig.colorbar(image, ax=list(axes[1:]), shrink=0.8)
        bar.set_label("|displacement| / largest of the mode [-]", fontsize=8)
    fig.suptitle(f"Free-free modes of {result.spec.name}: deformed shapes drawn with their "
                 f"largest displacement {drawn:.3g} m ({MODE_SHAPE_SCALE:.0%} of the anvil's "
                 f"size; scale factor on the mass-normalised shape in each title)", fontsize=9)
    return save_figure(fig, path)


def plot_impact_blows(blows, path: str | Path, title: str = "") -> Path:
    """Forces and pile-head velocity of one or more blows against time (ms) as PNG.

    Parameters
    ----------
    blows : sequence
        Blows, each with ``columns`` (CSV columns named ``name [unit]``).
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
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True, constrained_layout=True)
    for i, blow in enumerate(blows):
        c = blow.columns
        t = c["time [s]"] * 1e3
        tag = f" (blow {i + 1})" if len(blows) > 1 else ""
        alpha = 1.0 if i == len(blows) - 1 else 0.4
        for name, label in (("ram_anvil_force [N]", "ram-anvil contact"),
                            ("anvil_pile_force [N]", "anvil-pile contact"),
                            ("gauge_force [N]", "pile at gauge")):
            ax1.plot(t, c[name] / 1e6, label=label + tag, alpha=alpha)
        ax2.plot(t, c["pile_head_velocity [m/s]"], label="pile head" + tag, alpha=alpha)
        ax2.plot(t, c["gauge_velocity [m/s]"], label="pile at gauge" + tag, alpha=alpha)
    ax1.set_ylabel("force [MN] (compression +)")
    ax1.set_title(title)
    ax2.set_ylabel("velocity [m/s] (down +)")
    ax2.set_xlabel("time [ms] (0 = first ram-anvil contact)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    return save_figure(fig, path)


def plot_columns(columns: dict, path: str | Path, title: str = "") -> Path:
    """Forces and pile-head velocity of one set of time series (CSV columns) as PNG.

    Parameters
    ----------
    columns : dict
        CSV columns named ``name [unit]``.
    path : str or Path
        The PNG file.
    title : str, default ""
        Figure title.

    Returns
    -------
    Path
        The written figure.
    """
    from types import SimpleNamespace

    return plot_impact_blows([SimpleNamespace(columns=columns)], path, title=title)


DRIVEABILITY_PANELS = ("SRD [MN]", "blows / 0.25 m", "stress [MPa]", "ENTHRU [kJ]",
                       "stroke [m]")
"""The x-axis labels of the driveability panels, left to right (GRLWEAP's layout: every
quantity against the tip depth, depth down)."""


REFUSAL_IN_VIEW = 4.0
"""The blow-count axis reaches the refusal criterion when it is at most this many times the
largest blow count drawn; beyond, an arrow at the axis' edge points to it [-]."""


def blows_for_plot(blows, refusal: float | None = None) -> np.ndarray:
    """Blow counts as plotted: no blows (the pile runs) as gaps, beyond refusal at its edge.

    A depth where the pile runs under its own weight has a blow count of 0 in the tables
    (GRLWEAP's convention); a curve drawn through it would show a pile that drives with no
    blows. The plots leave it out (NaN): the curve has a gap there. An infinite count (no
    set: refusal) is drawn at 1.05 times the refusal criterion.

    Parameters
    ----------
    blows : array_like
        Blow counts (any unit, e.g. blows per 0.25 m) [-].
    refusal : float or None, default None
        Refusal criterion in the unit of ``blows`` [-]; None keeps infinite counts.

    Returns
    -------
    numpy.ndarray
        The counts to plot.
    """
    n = np.array(blows, dtype=float)
    n[n <= 0.0] = np.nan
    if refusal:
        n = np.minimum(n, 1.05 * refusal)
    return n


def plot_driveability(columns: dict, summary: dict, path: str | Path, title: str = "",
                      others: dict | None = None) -> Path:
    """Driveability against the tip depth, as GRLWEAP draws it (depth down).

    Five panels sharing the depth axis: SRD [MN] (total, shaft, toe); blow count [blows/0.25
    m] with the refusal criterion (a vertical line); the largest compression and tension
    stress along the pile [MPa] (both as magnitudes) with the allowable driving stress 0.9 fy
    (``[pile] yield_strength``); ENTHRU and the energy setting [kJ]; the equivalent stroke
    [m]. A horizontal line marks the self-weight penetration; depths where the pile runs
    under its own weight are gaps in the curves (:func:`blows_for_plot`), marked by a dotted
    line; a refusal depth is a red line.

    Parameters
    ----------
    columns : dict
        Driveability CSV columns named ``name [unit]``.
    summary : dict
        The run's summary (anvil model, refusal criterion, self-weight penetration, pile runs,
        allowable driving stress).
    path : str or Path
        The PNG file.
    title : str, default ""
        Figure title.
    others : dict, optional
        ``{label: columns}`` overlays further runs (other anvil models).

    Returns
    -------
    Path
        The written figure.
    """
    plt = _pyplot()
    fig, axes = plt.subplots(1, 5, figsize=(17, 7), sharey=True, constrained_layout=True)
    runs = {summary.get("anvil_model", "run"): columns, **(others or {})}
    refusal = summary.get("refusal_criterion [blows/0.25m]") or DEFAULT_REFUSAL
    allowable = summary.get("allowable_driving_stress [Pa]")
    if allowable is None:
        allowable = ALLOWABLE_DRIVING_STRESS_RATIO * summary.get("yield_strength [Pa]",
                                                                 DEFAULT_YIELD_STRENGTH)
    fy = allowable / ALLOWABLE_DRIVING_STRESS_RATIO
    top_blows, top_stress = 1.0, allowable
    for k, (label, c) in enumerate(runs.items()):
        z = c["depth [m]"]
        style = dict(color=f"C{k}", lw=1.5)
        if k == 0:
            axes[0].plot(c["srd [N]"] / 1e6, z, label="total", **style)
            axes[0].plot(c["srd_shaft [N]"] / 1e6, z, "--", color="C7", label="shaft")
            axes[0].plot(c["srd_toe [N]"] / 1e6, z, ":", color="C7", label="toe")
        bpq = blows_for_plot(c["blows_per_0.25m [-]"], refusal)
        axes[1].plot(bpq, z, ".-", ms=3, label=label, gid="blow_count", **style)
        if np.isfinite(bpq).any():
            top_blows = max(top_blows, float(np.nanmax(bpq)))
        compression = c["max_compression_stress [Pa]"] / 1e6
        tension = -c["max_tension_stress [Pa]"] / 1e6
        axes[2].plot(compression, z, label=f"{label}: compression", **style)
        axes[2].plot(tension, z, ":", color=f"C{k}", lw=1.5, label=f"{label}: tension")
        for values in (compression, tension):
            if np.isfinite(values).any():
                top_stress = max(top_stress, 1e6 * float(np.nanmax(values)))
        axes[3].plot(c["enthru [J]"] / 1e3, z, label=f"{label}: ENTHRU", **style)
        if k == 0:
            axes[3].plot(c["energy_setting [J]"] / 1e3, z, "--", color="C7",
                         label="energy setting")
            if "stroke [m]" in c:
                axes[4].plot(c["stroke [m]"], z, color="C7", lw=1.5,
                             label="equivalent stroke E / (m g)")
    axes[1].axvline(refusal, color="r", lw=1.2, ls="--", gid="refusal",
                    label=f"refusal {refusal:g} blows / 0.25 m")
    if refusal <= REFUSAL_IN_VIEW * top_blows:
        axes[1].set_xlim(0.0, 1.1 * max(top_blows, refusal))
    else:  # far beyond the curves: the axis keeps them readable, an arrow points to refusal
        axes[1].set_xlim(0.0, 1.15 * top_blows)
        axes[1].annotate(f"refusal {refusal:g} \u2192", xy=(1.0, 0.97), xycoords="axes fraction",
                         ha="right", va="top", color="r", fontsize=8, gid="refusal_note")
    axes[2].axvline(allowable / 1e6, color="r", lw=1.2, ls="--", gid="allowable",
                    label=f"allowable 0.9 fy = {allowable / 1e6:.0f} MPa "
                          f"(fy {fy / 1e6:.0f} MPa)")
    axes[2].set_xlim(0.0, 1.1 * top_stress / 1e6)
    for ax in axes[3:]:
        ax.set_xlim(left=0.0)
    swp = summary.get("self_weight_penetration [m]")
    if swp is not None:
        for k, ax in enumerate(axes):
            ax.axhline(swp, color="tab:brown", lw=1.0, ls="-.", gid="self_weight_penetration",
                       label=f"self-weight penetration {swp:.1f} m" if k == 1 else None)
    for k, depth in enumerate(summary.get("pile_run_depths [m]") or []):
        axes[1].axhline(depth, color="0.5", lw=0.8, ls=":", gid="pile_run",
                        label="pile run (no blows)" if k == 0 else None)
    if summary.get("refusal_depth [m]") is not None:
        for k, ax in enumerate(axes):
            ax.axhline(summary["refusal_depth [m]"], color="r", lw=0.8, gid="refusal_depth",
                       label=f"refusal at {summary['refusal_depth [m]']:g} m" if k == 1
                       else None)
    for ax, label in zip(axes, DRIVEABILITY_PANELS, strict=True):
        ax.set_xlabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    axes[2].set_xlabel("max stress along the pile [MPa]\n(compression, tension as magnitude)")
    axes[0].set_ylabel("tip depth below mudline [m]")
    axes[0].invert_yaxis()
    fig.suptitle(title or "driveability")
    return save_figure(fig, path)


def plot_installation(result: dict, path: str | Path, title: str = "",
                      driveability: dict | None = None) -> Path:
    """Blow count and stresses against the tip depth, fatigue and force band levels.

    Fatigue damage against the position along the pile, pile-head force band levels of the
    chosen depths.

    Parameters
    ----------
    result : dict
        The installation result: ``blows``, ``fatigue``, ``spectra`` and ``summary``.
    path : str or Path
        The PNG file.
    title : str, default ""
        Figure title.
    driveability : dict, optional
        Driveability CSV columns overlaid on the blow count (one blow per depth).

    Returns
    -------
    Path
        The written figure.
    """

    plt = _pyplot()
    fig, axes = plt.subplots(1, 4, figsize=(15, 6), constrained_layout=True)
    rows = result["blows"]
    z, n = blow_count_profile(rows)
    ax = axes[0]
    ax.step(blows_for_plot(n), z, where="post", label="installation (every blow)",
            gid="blow_count")
    if driveability is not None:
        ax.plot(blows_for_plot(driveability["blows_per_0.25m [-]"]), driveability["depth [m]"],
                "o-", ms=3, label="driveability (one blow per depth)", gid="blow_count")
    start = result.get("summary", {}).get("start_depth [m]")
    if start is not None:
        ax.axhline(start, color="tab:brown", lw=1.0, ls="-.", gid="self_weight_penetration",
                   label=f"start depth {start:.1f} m")
    ax.set_xlabel("blows / 0.25 m")
    ax.set_ylabel("tip depth below mudline [m]")
    ax.invert_yaxis()
    ax.legend(fontsize=7)
    ax = axes[1]
    tip = np.array([r["tip_depth [m]"] for r in rows])
    ax.plot([r["max_compression_stress [Pa]"] / 1e6 for r in rows], tip, lw=0.8,
            label="max compression")
    ax.plot([r["max_tension_stress [Pa]"] / 1e6 for r in rows], tip, lw=0.8,
            label="max tension")
    ax.set_xlabel("stress along the pile per blow [MPa]")
    ax.invert_yaxis()
    ax.legend(fontsize=7)
    ax = axes[2]
    fat = result["fatigue"]
    d = np.array([r["depth_below_head [m]"] for r in fat], dtype=float)
    dmg = np.array([r["damage [-]"] for r in fat], dtype=float)
    plot_weld_damage(ax, d, dmg)
    ax = axes[3]
    spectra = result["spectra"]
    depths = sorted({r["tip_depth [m]"] for r in spectra})
    for k, depth in enumerate(depths):
        sel = [r for r in spectra if r["tip_depth [m]"] == depth and r["valid [-]"]]
        ax.semilogx([r["band_centre [Hz]"] for r in sel],
                    [r["band_energy_level [dB]"] for r in sel], "o-", ms=3, color=f"C{k}",
                    label=f"tip {depth:.1f} m")
    ax.set_xlabel("one-third-octave band centre [Hz]")
    ax.set_ylabel("pile-head force band energy [dB re 1 N^2 s]")
    if depths:
        ax.legend(fontsize=7)
    for a in axes:
        a.grid(True, alpha=0.3, which="major")
    fig.suptitle(title or "installation")
    return save_figure(fig, path)


def plot_weld_damage(ax, depth, damage) -> None:
    """Miner's damage of each fatigue section (weld) as a bar against its depth below the head.

    Horizontal bars (stems) from the axis to each section's damage, one marker per section, on
    a logarithmic axis of at least three decades with a tick at every decade (a damage of 0
    is drawn at the axis' left end, hollow); the largest is labelled.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw in.
    depth : array_like
        Depth of each section below the pile head [m].
    damage : array_like
        Miner's damage of each section over the installation [-].
    """
    from matplotlib.ticker import LogFormatterMathtext, LogLocator

    depth = np.asarray(depth, dtype=float)
    damage = np.asarray(damage, dtype=float)
    positive = damage[damage > 0.0]
    if positive.size:
        top = float(np.ceil(np.log10(positive.max())))
        high = 10.0 ** top
        low = 10.0 ** min(float(np.floor(np.log10(positive.min()))), top - 3.0)
    else:
        low, high = 1e-6, 1.0
    shown = np.where(damage > 0.0, damage, low)
    ax.hlines(depth, low, shown, color="tab:purple", lw=1.2, gid="weld_damage")
    ax.plot(shown[damage > 0.0], depth[damage > 0.0], "o", ms=4, color="tab:purple",
            label="Miner damage per section")
    if (damage <= 0.0).any():
        ax.plot(shown[damage <= 0.0], depth[damage <= 0.0], "o", ms=4, mfc="none",
                color="tab:purple", label="no damage")
    ax.set_xscale("log")
    ax.set_xlim(low, high)
    ax.xaxis.set_major_locator(LogLocator(base=10.0, numticks=12))
    ax.xaxis.set_major_formatter(LogFormatterMathtext())
    ax.xaxis.set_minor_locator(LogLocator(base=10.0, subs=np.arange(2, 10) * 0.1, numticks=12))
    if positive.size:
        k = int(np.argmax(damage))
        ax.annotate(f"max {damage[k]:.3g}\nat {depth[k]:.1f} m", (damage[k], depth[k]),
                    xytext=(-4, 8), textcoords="offset points", ha="right", fontsize=7)
    ax.set_xlabel("Miner damage of the installation [-]")
    ax.set_ylabel("position below the pile head [m]")
    if not ax.yaxis_inverted():
        ax.invert_yaxis()
    ax.legend(fontsize=7, loc="lower left")
