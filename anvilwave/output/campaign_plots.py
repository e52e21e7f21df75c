"""Campaign figures and tables (matplotlib, Agg): kept apart from running the cases.

``DIR/plots/envelope_<position>.png``
    Blow count (blows per 0.25 m) against the tip depth of one position: a panel per hammer
    (x energy schedule), in it for every anvil model the best-estimate SRD as a line and the
    lower-upper bound band shaded; the refusal criterion marked. Depths where the pile runs
    under its own weight (no blows) are gaps in the curves, not blow counts of 0.
``DIR/plots/refusal_risk.png`` and ``refusal_risk.csv``
    Positions (rows) against hammer x anvil model (x energy schedule) (columns): each cell's
    colour is the largest blow count over the bounds divided by the refusal criterion (1 or
    more: refusal), its text the maximum blows per 0.25 m of each bound and, where a bound
    refuses, the shallowest refusal depth. The CSV holds the same numbers.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from pathlib import Path

import numpy as np

from anvilwave.output.figure_style import save_figure
from anvilwave.output.plots import blows_for_plot
from anvilwave.output.tables import read_csv

BOUND_STYLE = {"lower": ":", "best": "-", "upper": "--"}


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


RISK_DPI = 110
"""Resolution of the campaign figures [dots per inch]."""
RISK_MIN_WIDTH = 11.5
"""Smallest width of the refusal-risk figure [in] (1265 px at :data:`RISK_DPI`)."""


def _combo_axes(campaign) -> list[str]:
    return [a for a in campaign.axes if a not in ("position", "bound")]


def _combo_label(row: dict, names: list[str]) -> str:
    return " / ".join(str(row[a]) for a in names)


def _summary(out: Path, case: str) -> dict:
    try:
        return json.loads((out / "cases" / case / "summary.json").read_text())
    except (OSError, ValueError):
        return {}


def _blows(out: Path, case: str) -> tuple[np.ndarray, np.ndarray] | None:
    """Tip depth [m] and blows per 0.25 m of a finished case."""

    try:
        c = read_csv(out / "cases" / case / "driveability.csv")
    except (OSError, ValueError, StopIteration):
        return None
    return c["depth [m]"], c["blows_per_0.25m [-]"]


def plot_campaign(campaign, rows: list[dict], out_dir: str | Path) -> list[Path]:
    """Every campaign figure and table into ``out_dir/plots`` (module docstring).

    Parameters
    ----------
    campaign : Campaign
        The campaign.
    rows : list of dict
        One row per case (status, position, bound, ...).
    out_dir : str or Path
        The campaign result folder.

    Returns
    -------
    list of Path
        The written figures and tables.
    """
    out = Path(out_dir)
    folder = out / "plots"
    folder.mkdir(parents=True, exist_ok=True)
    ok = [r for r in rows if r["status"] == "ok"]
    refusal = {r["case"]: _summary(out, r["case"]).get("refusal_criterion [blows/0.25m]")
               for r in ok}
    paths = []
    for position in (p.name for p in campaign.positions):
        mine = [r for r in ok if r["position"] == position]
        if mine:
            paths.append(plot_envelopes(campaign, mine, out, refusal,
                                        folder / f"envelope_{position}.png"))
    if rows:
        paths += plot_refusal_risk(campaign, rows, refusal, folder / "refusal_risk.png")
    return paths


def plot_envelopes(campaign, rows: list[dict], out: Path, refusal: dict, path: Path) -> Path:
    """Blow count envelopes (lower / best / upper) against depth of one position.

    A panel per hammer (x energy schedule), a colour per anvil model.

    Parameters
    ----------
    campaign : Campaign
        The campaign.
    rows : list of dict
        The finished cases of the position.
    out : Path
        The campaign result folder.
    refusal : dict
        Refusal criterion [blows/0.25m] per case.
    path : Path
        The PNG file.

    Returns
    -------
    Path
        The written figure.
    """
    plt = _pyplot()
    panel_axes = [a for a in _combo_axes(campaign) if a != "anvil_model"]
    panels = list(dict.fromkeys(_combo_label(r, panel_axes) for r in rows))
    models = list(dict.fromkeys(r["anvil_model"] for r in rows))
    criterion = next((v for v in refusal.values() if v), 250.0)
    fig, axes = plt.subplots(1, len(panels), figsize=(1.0 + 5.0 * len(panels), 7.0),
                             sharey=True, squeeze=False, constrained_layout=True)
    top = 1.0
    for ax, panel in zip(axes[0], panels, strict=True):
        for k, model in enumerate(models):
            color = f"C{k % 10}"
            curves = {}
            for r in rows:
                if _combo_label(r, panel_axes) == panel and r["anvil_model"] == model:
                    data = _blows(out, r["case"])
                    if data is not None:
                        curves[r["bound"]] = (data[0], blows_for_plot(data[1], criterion))
            if "lower" in curves and "upper" in curves and \
                    curves["lower"][0].shape == curves["upper"][0].shape:
                ax.fill_betweenx(curves["lower"][0], curves["lower"][1], curves["upper"][1],
                                 color=color, alpha=0.15, lw=0)
            for bound in campaign.bounds:
                if bound in curves:
                    z, n = curves[bound]
                    ax.plot(n, z, BOUND_STYLE[bound], color=color,
                            lw=1.8 if bound == "best" else 1.0, label=f"{model} anvil: {bound}",
                            gid="blow_count")
                    if np.isfinite(n).any():
                        top = max(top, float(np.nanmax(n)))
        ax.set_title(panel, fontsize=10)
        ax.set_xlabel("blows / 0.25 m (band: lower to upper SRD)")
        ax.grid(True, alpha=0.3)
    for ax in axes[0]:
        ax.axvline(criterion, color="r", lw=1.0, ls="--", gid="refusal",
                   label=f"refusal {criterion:g} blows / 0.25 m")
        ax.set_xlim(0.0, 1.1 * max(top, criterion))
        ax.legend(fontsize=7, loc="lower left")
    axes[0][0].invert_yaxis()
    axes[0][0].set_ylabel("tip depth below mudline [m]")
    fig.suptitle(f"{campaign.name}: blow count envelopes, position {rows[0]['position']}")
    return save_figure(fig, path, dpi=RISK_DPI)


def refusal_risk_table(campaign, rows: list[dict], refusal: dict) -> list[dict]:
    """One row per position x hammer x anvil model (x energy schedule).

    Max blows per 0.25 m and refusal depth of each bound, the refusal criterion and the risk
    (the largest max blow count over the bounds / the criterion).

    Parameters
    ----------
    campaign : Campaign
        The campaign.
    rows : list of dict
        One row per case.
    refusal : dict
        Refusal criterion [blows/0.25m] per case.

    Returns
    -------
    list of dict
        The table rows.
    """
    names = _combo_axes(campaign)
    table: dict[tuple, dict] = {}
    for r in rows:
        key = (r["position"], *(r[a] for a in names))
        entry = table.setdefault(key, {"position": r["position"], **{a: r[a] for a in names},
                                       "status": "ok"})
        b = r["bound"]
        if r["status"] != "ok":  # error, or pending (an interrupted run)
            entry["status"] = r["status"]
            continue
        count = r.get("max_blow_count [1/m]")
        entry[f"max_blows_per_0.25m_{b} [-]"] = None if count is None else 0.25 * count
        entry[f"refusal_depth_{b} [m]"] = r.get("refusal_depth [m]")
        criterion = refusal.get(r["case"])
        if criterion:
            entry["refusal_criterion [blows/0.25m]"] = criterion
    for entry in table.values():
        counts = [entry.get(f"max_blows_per_0.25m_{b} [-]") for b in campaign.bounds]
        counts = [c for c in counts if c is not None]
        criterion = entry.get("refusal_criterion [blows/0.25m]")
        entry["risk [-]"] = max(counts) / criterion if counts and criterion else None
    return list(table.values())


def plot_refusal_risk(campaign, rows: list[dict], refusal: dict, path: Path) -> list[Path]:
    """The refusal-risk matrix (PNG) and its table (CSV beside it).

    Parameters
    ----------
    campaign : Campaign
        The campaign.
    rows : list of dict
        One row per case.
    refusal : dict
        Refusal criterion [blows/0.25m] per case.
    path : Path
        The PNG file; the CSV takes its name with ``.csv``.

    Returns
    -------
    list of Path
        The PNG and the CSV.
    """
    plt = _pyplot()
    names = _combo_axes(campaign)
    table = refusal_risk_table(campaign, rows, refusal)
    positions = [p.name for p in campaign.positions]
    combos = list(dict.fromkeys(_combo_label(e, names) for e in table))
    risk = np.full((len(positions), len(combos)), np.nan)
    text = [["" for _ in combos] for _ in positions]
    for e in table:
        i, j = positions.index(e["position"]), combos.index(_combo_label(e, names))
        if e["risk [-]"] is not None:
            risk[i, j] = e["risk [-]"]
        parts = [f"{b[0].upper()} {e[f'max_blows_per_0.25m_{b} [-]']:.0f}"
                 for b in campaign.bounds if e.get(f"max_blows_per_0.25m_{b} [-]") is not None]
        refused = [(e[f"refusal_depth_{b} [m]"], b) for b in campaign.bounds
                   if e.get(f"refusal_depth_{b} [m]") is not None]
        cell = " ".join(parts)
        if refused:
            depth, bound = min(refused)
            cell += f"\nrefusal {bound} {depth:g} m"
        if e["status"] != "ok":
            cell += f"\n({e['status']})"
        text[i][j] = cell
    width = max(RISK_MIN_WIDTH, 3.0 + 2.2 * len(combos))
    height = max(4.0, 2.0 + 0.42 * len(positions))
    fig, ax = plt.subplots(figsize=(width, height), constrained_layout=True)
    image = ax.imshow(np.ma.masked_invalid(risk), cmap="RdYlGn_r", vmin=0.0, vmax=1.2,
                      aspect="auto")
    ax.set_facecolor("0.85")  # cells without a result
    for i in range(len(positions)):
        for j in range(len(combos)):
            ax.text(j, i, text[i][j], ha="center", va="center", fontsize=7.5)
    ax.set_xticks(range(len(combos)), combos, fontsize=8, rotation=20, ha="right")
    ax.set_yticks(range(len(positions)), positions, fontsize=8)
    ax.set_xlabel(" / ".join(names))
    ax.set_ylabel("position")
    bar = fig.colorbar(image, ax=ax, fraction=0.04, pad=0.02)
    bar.set_label("max blows per 0.25 m / refusal criterion\n(worst bound; 1 = refusal)",
                  fontsize=8)
    ax.set_title(f"{campaign.name}: refusal risk (cells: max blows / 0.25 m per bound "
                 f"{'/'.join(b[0].upper() for b in campaign.bounds)})", fontsize=9)
    save_figure(fig, path, dpi=RISK_DPI)
    csv_path = path.with_suffix(".csv")
    columns = ["position", *names, "status"]
    for b in campaign.bounds:
        columns += [f"max_blows_per_0.25m_{b} [-]", f"refusal_depth_{b} [m]"]
    columns += ["refusal_criterion [blows/0.25m]", "risk [-]"]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for e in table:
        writer.writerow(["" if e.get(c) is None else
                         (f"{e[c]:.6g}" if isinstance(e[c], float) and math.isfinite(e[c])
                          else str(e[c])) for c in columns])
    tmp = csv_path.with_name(f".{csv_path.name}.part")
    tmp.write_text(buffer.getvalue())
    os.replace(tmp, csv_path)
    return [path, csv_path]
