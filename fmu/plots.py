"""Figures (matplotlib, Agg backend): kept apart from the computations."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_modes(result, path: str | Path, n_shapes: int = 5) -> Path:
    """Mesh and the first flexible mode shapes of an anvil (``AnvilModes``) as PNG."""
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
