"""The figures engineers read: footer on every figure, driveability in GRLWEAP's layout
(refusal and allowable-stress lines, self-weight penetration, pile runs as gaps), weld damage,
campaign figures and their sizes. Small synthetic columns; no simulation."""

from __future__ import annotations

import json
import re
from pathlib import Path
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.figure  # noqa: E402
import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from anvilwave.output import campaign_plots, figure_style, pda_plots, plots  # noqa: E402
from anvilwave.output.tables import write_csv  # noqa: E402

PACKAGE = Path(__file__).resolve().parents[1] / "anvilwave"
DATE = "2024-01-02"
EPOCH = "1704196800"  # 2024-01-02T12:00:00Z


@pytest.fixture
def saved(monkeypatch):
    """Every figure saved: its texts at the moment of saving (and the date fixed)."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    seen = []
    original = matplotlib.figure.Figure.savefig

    def savefig(self, *args, **kwargs):
        seen.append([t.get_text() for t in self.texts])
        return original(self, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    return seen


@pytest.fixture
def captured(monkeypatch):
    """The figure of the next save_figure call, kept open for inspection."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    figures = []
    original = figure_style.save_figure

    def keep(fig, path, dpi=110, tight=True):
        figures.append(fig)
        figure_style.footer(fig)
        fig.savefig(path, dpi=dpi, bbox_inches="tight" if tight else None)
        return Path(path)

    for module in (plots, campaign_plots, pda_plots):
        monkeypatch.setattr(module, "save_figure", keep)
    yield figures
    del original


def drive_columns(runs=(15.0,)):
    """Driveability columns: no blows above the self-weight penetration (5 m) and at the pile
    runs, a refusal (infinite count) at the last depth."""
    z = np.arange(0.0, 31.0, 1.0)
    bpq = np.where(z < 5.0, 0.0, 4.0 + 3.0 * z)
    bpq[np.isin(z, runs)] = 0.0
    bpq[-1] = np.inf
    driven = bpq > 0
    nan = np.full(z.size, np.nan)
    srd = 1e6 * (0.5 + z)
    energy = np.full(z.size, 2e6)
    return {
        "depth [m]": z, "srd [N]": srd, "srd_shaft [N]": 0.7 * srd, "srd_toe [N]": 0.3 * srd,
        "blow_count [1/m]": 4.0 * bpq, "blows_per_0.25m [-]": bpq,
        "set [m]": np.where(driven, 1.0 / (4.0 * np.where(driven, bpq, 1.0)), nan),
        "energy_setting [J]": energy,
        "enthru [J]": np.where(driven, 0.8 * energy, nan),
        "max_compression_stress [Pa]": np.where(driven, 250e6, nan),
        "max_tension_stress [Pa]": np.where(driven, -60e6, nan),
        "max_pile_head_force [N]": np.where(driven, 200e6, nan),
        "stroke [m]": energy / (100e3 * 9.81),
    }


SUMMARY = {"anvil_model": "rom", "refusal_criterion [blows/0.25m]": 250.0,
           "self_weight_penetration [m]": 5.0, "pile_run_depths [m]": [15.0],
           "refusal_depth [m]": 30.0, "yield_strength [Pa]": 355e6,
           "allowable_driving_stress [Pa]": 0.9 * 355e6}


def _lines(fig, gid):
    return [line for ax in fig.axes for line in ax.get_lines() if line.get_gid() == gid]


def test_footer_reads_version_and_date(monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    text = figure_style.footer_text()
    assert re.fullmatch(r"anvilwave \S+ \u00b7 2024-01-02", text), text
    assert figure_style.version() in text
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "not a number")
    assert re.fullmatch(r"\d{4}-\d{2}-\d{2}", figure_style.figure_date())


def test_figures_are_saved_only_through_save_figure():
    """Every savefig of the package goes through figure_style.save_figure (footer and
    cropping), except the fmpy example, which imports nothing of anvilwave."""
    callers = sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py")
                     if ".savefig(" in p.read_text())
    assert callers == ["examples/fmpy_cosim.py", "output/figure_style.py"]


def test_every_figure_saved_carries_the_footer(tmp_path, saved):
    plots.plot_driveability(drive_columns(), SUMMARY, tmp_path / "d.png")
    t = np.linspace(0.0, 0.02, 200)
    force = 1e8 * np.sin(np.pi * t / 0.02)
    blow = {"time [s]": t, "ram_anvil_force [N]": force, "anvil_pile_force [N]": force,
            "gauge_force [N]": force, "pile_head_velocity [m/s]": force / 1e8,
            "gauge_velocity [m/s]": force / 1e8}
    plots.plot_columns(blow, tmp_path / "i.png")
    columns = {"time [s]": t}
    for who in ("measured", "lumped", "rom"):
        columns[f"{who}_force [N]"] = force
        columns[f"{who}_velocity [m/s]"] = force / 1e8
    pda_plots.plot_compare_pda(columns, "force [N]", tmp_path / "p.png", "Fig. 4")
    assert len(saved) == 3
    for texts in saved:
        assert f"anvilwave {figure_style.version()} \u00b7 {DATE}" in texts


def test_driveability_has_refusal_allowable_and_self_weight_lines(tmp_path, captured):
    path = plots.plot_driveability(drive_columns(), SUMMARY, tmp_path / "driveability.png")
    (fig,) = captured
    (refusal,) = _lines(fig, "refusal")
    assert refusal.get_xdata()[0] == 250.0 and "refusal" in refusal.get_label()
    (allowable,) = _lines(fig, "allowable")
    assert allowable.get_xdata()[0] == pytest.approx(0.9 * 355.0)
    assert "0.9 fy" in allowable.get_label()
    swp = _lines(fig, "self_weight_penetration")
    assert len(swp) == 5 and all(line.get_ydata()[0] == 5.0 for line in swp)
    assert any("self-weight penetration" in line.get_label() for line in swp)
    assert [line.get_ydata()[0] for line in _lines(fig, "pile_run")] == [15.0]
    # depth down: the depth axis is inverted
    assert fig.axes[0].yaxis_inverted()
    labels = [ax.get_xlabel() for ax in fig.axes[:5]]
    assert labels[1] == "blows / 0.25 m" and labels[3] == "ENTHRU [kJ]"
    assert labels[4] == "stroke [m]" and "MPa" in labels[2]
    width, height = _png_size(path)
    assert 1700 <= width <= 2000 and 700 <= height <= 850


def test_no_blow_count_curve_holds_a_zero(tmp_path, captured):
    """At the depths without blows (above the self-weight penetration, pile runs) the curves
    have gaps, and a refusal is drawn at the refusal's edge, not at infinity."""
    columns = drive_columns()
    plots.plot_driveability(columns, SUMMARY, tmp_path / "d.png",
                            others={"lumped": drive_columns(runs=(12.0, 13.0))})
    (fig,) = captured
    curves = _lines(fig, "blow_count")
    assert len(curves) == 2
    for line in curves:
        x, z = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        assert not np.any(x == 0.0)
        assert np.all(np.isnan(x[z < 5.0]))
        assert np.isfinite(x).sum() > 10 and np.nanmax(x) <= 1.05 * 250.0
    x = np.asarray(curves[0].get_xdata(), float)
    assert np.isnan(x[15])


def test_installation_weld_damage_as_bars_with_decade_ticks(tmp_path, captured):
    blows = [{"tip_depth [m]": 5.0 + 0.01 * k, "max_compression_stress [Pa]": 2e8,
              "max_tension_stress [Pa]": -5e7} for k in range(300)]
    fatigue = [{"depth_below_head [m]": d, "damage [-]": dm}
               for d, dm in ((10.0, 3e-4), (20.0, 2e-3), (30.0, 0.0), (40.0, 1.5e-3))]
    spectra = [{"tip_depth [m]": 6.0, "band_centre [Hz]": f, "band_energy_level [dB]": 150.0,
                "valid [-]": 1} for f in (100.0, 125.0, 160.0)]
    path = plots.plot_installation({"blows": blows, "fatigue": fatigue, "spectra": spectra,
                                    "summary": {"start_depth [m]": 5.0}},
                                   tmp_path / "installation.png")
    (fig,) = captured
    ax = fig.axes[2]
    bars = [c for c in ax.collections if c.get_gid() == "weld_damage"]
    assert len(bars) == 1 and len(bars[0].get_segments()) == 4
    assert ax.get_xscale() == "log"
    low, high = ax.get_xlim()
    decades = [t for t in ax.get_xticks() if low / 1.001 <= t <= high * 1.001]
    assert len(decades) >= 4  # at least three decades, a labelled tick at each
    assert not any(line.get_linestyle() not in ("None", "") for line in ax.get_lines())
    assert _png_size(path)[0] >= 1500


def _campaign(tmp_path):
    out = tmp_path / "campaign"
    rows = []
    for bound, factor in (("lower", 0.8), ("best", 1.0), ("upper", 1.25)):
        name = f"P1_{bound}"
        folder = out / "cases" / name
        folder.mkdir(parents=True)
        c = drive_columns()
        write_csv({"depth [m]": c["depth [m]"],
                   "blows_per_0.25m [-]": np.where(np.isfinite(c["blows_per_0.25m [-]"]),
                                                   factor * c["blows_per_0.25m [-]"], 1e9)},
                  folder / "driveability.csv")
        (folder / "summary.json").write_text(json.dumps(
            {"refusal_criterion [blows/0.25m]": 250.0}))
        rows.append({"case": name, "status": "ok", "position": "P1", "bound": bound,
                     "hammer": "S-4000", "anvil_model": "rom",
                     "max_blow_count [1/m]": 4.0 * 250.0 * factor,
                     "refusal_depth [m]": 30.0 if bound != "lower" else None})
    campaign = SimpleNamespace(name="farm", axes=("position", "bound", "hammer", "anvil_model"),
                               bounds=("lower", "best", "upper"),
                               positions=[SimpleNamespace(name="P1")])
    return campaign, rows, out


def test_campaign_figures(tmp_path, captured):
    campaign, rows, out = _campaign(tmp_path)
    paths = campaign_plots.plot_campaign(campaign, rows, out)
    envelope, risk = captured
    for line in _lines(envelope, "blow_count"):
        x = np.asarray(line.get_xdata(), float)
        assert not np.any(x == 0.0) and np.isnan(x[15])
    assert len(_lines(envelope, "refusal")) == 1
    assert "refusal criterion" in risk.axes[-1].get_ylabel()  # the colour bar's label
    png = [p for p in paths if p.suffix == ".png"]
    assert [p.name for p in png] == ["envelope_P1.png", "refusal_risk.png"]
    assert _png_size(png[1])[0] >= 1200
    assert envelope._suptitle.get_text().startswith("farm: blow count envelopes")


def test_save_figure_keeps_what_overflows_the_figure(tmp_path):
    """A title wider than the figure is not clipped: the image is cropped to the content."""
    plt = plots._pyplot()
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.set_title("a title much wider than a three-inch figure could ever hold, " * 2)
    path = figure_style.save_figure(fig, tmp_path / "wide.png", dpi=100)
    assert _png_size(path)[0] > 300
    assert not list(tmp_path.glob(".*.part"))


def _png_size(path) -> tuple[int, int]:
    image = matplotlib.image.imread(path)
    return image.shape[1], image.shape[0]
