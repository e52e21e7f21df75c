"""Figures (matplotlib, Agg backend): kept apart from the computations."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from anvilwave.output.tables import blow_count_profile


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


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
    for k, ax in enumerate(axes[1:], start=1):
        disp = model.nodal(modes.shapes[:, k])[:nv]
        scale = 0.08 * extent / max(np.abs(disp).max(), 1e-300)
        mag = np.hypot(disp[:, 0], disp[:, 1])
        dtri = mtri.Triangulation(r + scale * disp[:, 0], z + scale * disp[:, 1], mesh.t.T)
        ax.tripcolor(dtri, mag, shading="gouraud", cmap="viridis")
        ax.triplot(tri, lw=0.15, color="0.7", alpha=0.5)
        ax.set_title(f"mode {k + 1}: {modes.frequencies[k]:.1f} Hz", fontsize=9)
    for ax in axes:
        ax.set_aspect("equal")
        ax.invert_yaxis()
        ax.set_xlabel("r [m]")
    axes[0].set_ylabel("z [m] (down)")
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


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
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


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


def plot_driveability(columns: dict, summary: dict, path: str | Path, title: str = "",
                      others: dict | None = None) -> Path:
    """SRD, blow count, stresses and ENTHRU against the tip depth (depth down), refusal marked.

    Parameters
    ----------
    columns : dict
        Driveability CSV columns named ``name [unit]``.
    summary : dict
        The run's summary (anvil model, refusal criterion).
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
    fig, axes = plt.subplots(1, 4, figsize=(14, 6), sharey=True)
    runs = {summary.get("anvil_model", "run"): columns, **(others or {})}
    for k, (label, c) in enumerate(runs.items()):
        z = c["depth [m]"]
        style = dict(color=f"C{k}", lw=1.5)
        if k == 0:
            axes[0].plot(c["srd [N]"] / 1e6, z, label="total", **style)
            axes[0].plot(c["srd_shaft [N]"] / 1e6, z, "--", color="C7", label="shaft")
            axes[0].plot(c["srd_toe [N]"] / 1e6, z, ":", color="C7", label="toe")
        bpq = np.minimum(c["blows_per_0.25m [-]"], 2 * summary["refusal_criterion "
                                                                 "[blows/0.25m]"])
        axes[1].plot(bpq, z, label=label, **style)
        axes[2].plot(c["max_compression_stress [Pa]"] / 1e6, z, label=f"{label} compression",
                     **style)
        axes[2].plot(c["max_tension_stress [Pa]"] / 1e6, z, ":", color=f"C{k}",
                     label=f"{label} tension")
        axes[3].plot(c["enthru [J]"] / 1e3, z, label=f"{label} ENTHRU", **style)
        if k == 0:
            axes[3].plot(c["energy_setting [J]"] / 1e3, z, "--", color="C7",
                         label="energy setting")
    refusal = summary.get("refusal_criterion [blows/0.25m]")
    top = max(float(np.nanmax(np.minimum(c["blows_per_0.25m [-]"], 2 * (refusal or 1e9))))
              for c in runs.values())
    if refusal and refusal <= 1.5 * top:
        axes[1].axvline(refusal, color="r", lw=1, ls="--", label="refusal")
    else:
        axes[1].set_title(f"(refusal at {refusal:g})" if refusal else "", fontsize=8)
    axes[1].set_xlim(0.0, 1.15 * max(top, 1.0) if not refusal or refusal > 1.5 * top
                     else 1.1 * refusal)
    if summary.get("refusal_depth [m]") is not None:
        for ax in axes:
            ax.axhline(summary["refusal_depth [m]"], color="r", lw=0.8)
    axes[0].set_xlabel("SRD [MN]")
    axes[1].set_xlabel("blows / 0.25 m")
    axes[2].set_xlabel("max stress along the pile [MPa]\n(compression +, tension -)")
    axes[3].set_xlabel("energy [kJ]")
    axes[0].set_ylabel("tip depth below mudline [m]")
    axes[0].invert_yaxis()
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle(title or "driveability")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


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
    fig, axes = plt.subplots(1, 4, figsize=(15, 6))
    rows = result["blows"]
    z, n = blow_count_profile(rows)
    ax = axes[0]
    ax.step(n, z, where="post", label="installation (every blow)")
    if driveability is not None:
        ax.plot(driveability["blows_per_0.25m [-]"], driveability["depth [m]"], "o-", ms=3,
                label="driveability (one blow per depth)")
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
    d = np.array([r["depth_below_head [m]"] for r in fat])
    dmg = np.array([r["damage [-]"] for r in fat])
    ax.semilogx(np.maximum(dmg, 1e-12), d, ".-", ms=3)
    ax.set_xlabel("Miner damage of the installation [-]")
    ax.set_ylabel("position below the pile head [m]")
    ax.invert_yaxis()
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
        a.grid(True, alpha=0.3, which="both")
    fig.suptitle(title or "installation")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
