"""``anvilwave report``: one self-contained HTML file per result folder, checked in a real
headless browser (Debian's chromium, no network; the browser tests are skipped without
/usr/bin/chromium).

The results are tiny (the 1000 kg drop hammer on a 10 m pile of tests/test_bad_inputs.py,
no anvil): impact, drive, install, pda, match and batch run for real through the command line
with ``--report``. compare (the reference FEA) and compare-pda (the ROM anvil's modes) cost
tens of seconds, so their folders are written here as those commands lay them out (the
marker, the JSON summary, a figure): the report reads files only, so that tests its
formatting of them.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import pytest

import anvilwave
from anvilwave import cli
from anvilwave.output.report import CSS, REPORT_NAME, build_report
from anvilwave.output.writer import MARKER, file_sha256

from .test_bad_inputs import DRIVE, _record, _system

CHROMIUM = Path("/usr/bin/chromium")
NEEDS_CHROMIUM = pytest.mark.skipif(not CHROMIUM.exists(), reason="no /usr/bin/chromium "
                                    "(apt-get install chromium): the browser checks skipped")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--host-resolver-rules=MAP * ~NOTFOUND"]

CPT = "depth [m],qc [MPa],fs [MPa],u2 [MPa]\n" + "".join(
    f"{0.5 * i:.1f},{4 + 0.6 * i:.3f},{0.008 * (4 + 0.6 * i):.4f},0.0\n" for i in range(31))
SRD = """
[srd]
method = "alm-hamre-2001"
cpt = "cpt.csv"
[[srd.layers]]
top = 0.0
bottom = 15.0
soil = "sand"
submerged_unit_weight = 10.0e3
interface_friction_angle = 29.0
"""
CAMPAIGN = """[campaign]
name = "tiny"
system = "base.toml"
[axes]
bounds = ["best"]
[[positions]]
name = "P1"
water_depth = 20.0
target_penetration = 4.0
[positions.pile]
[[positions.pile.sections]]
length = 10.0
outer_diameter = 0.7
wall_thickness = 0.03
""" + SRD.replace("[srd]", "[positions.srd]").replace("[[srd.", "[[positions.srd.")

RED = (0.85, 0.05, 0.05)


def _red_figure(path: Path) -> None:
    """A figure whose middle is a solid red block (the colour the screenshot must show)."""
    fig, ax = plt.subplots(figsize=(6, 3), dpi=100)
    ax.add_patch(plt.Rectangle((0.2, 0.2), 0.6, 0.6, color=RED))
    ax.plot([0, 1], [0, 1], color="tab:blue")
    fig.savefig(path)
    plt.close(fig)


def _fake_result(folder: Path, command: str, summary_name: str, summary: dict,
                 figure: str) -> Path:
    folder.mkdir(parents=True)
    (folder / MARKER).write_text(json.dumps({"command": command}) + "\n")
    (folder / summary_name).write_text(json.dumps(summary, indent=2) + "\n")
    _red_figure(folder / figure)
    return folder


@pytest.fixture(scope="module")
def results(tmp_path_factory) -> dict[str, Path]:
    """A result folder of every kind, each with its report.html."""
    root = tmp_path_factory.mktemp("report")
    cwd = os.getcwd()
    os.chdir(root)  # relative arguments, as a user types them
    try:
        system = _system(root, DRIVE + "[installation]\ntarget_depth = 1.0\n")
        _record(root, n=120)
        (root / "cpt.csv").write_text(CPT)
        base = system.read_text().replace("srd = [[0.0, 1e3, 1e6], [10.0, 2e4, 5e6]]", "")
        (root / "base.toml").write_text(base + SRD)
        (root / "campaign.toml").write_text(CAMPAIGN)
        runs = {
            "impact": ["impact", "system.toml"],
            "drive": ["drive", "system.toml", "--workers", "1"],
            "install": ["install", "system.toml"],
            "pda": ["pda", "record.csv", "--length", "4", "--area", "0.06", "--jc", "0.3"],
            "match": ["match", "record.csv", "system.toml", "--zones", "1"],
            "batch": ["batch", "campaign.toml", "--workers", "1"],
        }
        out = {}
        for kind, args in runs.items():
            assert cli.main([*args, "--out", f"r_{kind}", "--report"]) in (0, 1), kind
            out[kind] = root / f"r_{kind}"
    finally:
        os.chdir(cwd)
    out["compare"] = _fake_result(root / "r_compare", "compare", "comparison.json", {
        "fea": {"peak_ram_anvil_force [N]": 4.6e8, "peak_anvil_pile_force [N]": 4.5e8,
                "wall_time [s]": 40.0},
        "rom": {"peak_ram_anvil_force [N]": 4.55e8, "peak_anvil_pile_force [N]": 4.53e8,
                "peak_anvil_pile_force_error [-]": 0.004, "wall_time [s]": 0.1},
        "comparison_bandwidth [Hz]": 5000.0, "system": "table1.toml"},
        "fig3_pile_force.png")
    out["compare-pda"] = _fake_result(root / "r_compare_pda", "compare-pda",
                                      "compare_pda.json",
                                      {"record": "pda_record_synthetic.csv",
                                       "system": "table1.toml",
                                       "rom": {"peak_force [N]": 4.4e8}},
                                      "fig4_pile_top_force.png")
    for kind in ("compare", "compare-pda"):
        anvilwave.report(out[kind])
    return out


KINDS = ["impact", "drive", "install", "pda", "match", "batch", "compare", "compare-pda"]
INPUTS = {"impact": ["system.toml", "hammer.toml"], "drive": ["system.toml", "hammer.toml"],
          "install": ["system.toml", "hammer.toml"], "pda": ["record.csv"],
          "match": ["record.csv", "system.toml", "hammer.toml"],
          "batch": ["campaign.toml", "base.toml", "hammer.toml", "cpt.csv"]}
UNITS = {"impact": ["MN", "MPa", "kJ", "mm"], "drive": ["blows/0.25 m", "blows/m", "MPa", "kJ"],
         "install": ["MPa", "h"], "pda": ["MN", "MPa", "kJ"], "match": ["MN"],
         "batch": ["blows/m", "MPa", "h"], "compare": ["MN"], "compare-pda": ["MN"]}
EXTERNAL = re.compile(r"""(?:src|href|url)\s*[=(]\s*["']?\s*(?:https?:|//|ftp:)""", re.I)


def _figures_in(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*.png") if "inputs" not in p.relative_to(folder).parts]


@pytest.mark.parametrize("kind", KINDS)
def test_the_report_holds_version_inputs_units_and_every_figure(results, kind):
    folder = results[kind]
    text = (folder / REPORT_NAME).read_text()
    assert f"anvilwave {anvilwave.__version__}" in text
    assert re.search(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d", text)  # date and time
    for name in INPUTS.get(kind, []):  # each input with its hash, the same as the file's
        assert name in text
        assert file_sha256(folder.parent / name) in text
        assert file_sha256(folder / "inputs" / name) == file_sha256(folder.parent / name)
    if "system.toml" in INPUTS.get(kind, []):
        assert "(as run)" in text and "[pile.sections]" in text  # the system file echoed
    for unit in UNITS[kind]:
        assert unit in text, unit
    images = re.findall(r"<img\s[^>]*src=\"([^\"]*)\"", text)
    assert len(images) == len(_figures_in(folder)) >= 1
    assert all(src.startswith("data:image/png;base64,") for src in images)
    assert not EXTERNAL.search(text) and "<link" not in text  # self-contained


@pytest.mark.parametrize("kind", list(INPUTS))
def test_a_result_records_its_inputs_without_absolute_paths(results, kind):
    folder = results[kind]
    manifest = json.loads((folder / "inputs.json").read_text())
    assert manifest["command"] == kind
    assert sorted(e["name"] for e in manifest["files"]) == sorted(INPUTS[kind])
    for e in manifest["files"]:
        assert e["sha256"] == file_sha256(folder / e["copy"])

    def strings(value):
        if isinstance(value, dict):
            for v in value.values():
                yield from strings(v)
        elif isinstance(value, list):
            for v in value:
                yield from strings(v)
        elif isinstance(value, str):
            yield value

    for path in folder.rglob("*.json"):
        found = [s for s in strings(json.loads(path.read_text())) if os.path.isabs(s)]
        assert not found, (path, found)


def test_report_out_option_and_api(results, tmp_path, capsys):
    out = tmp_path / "client.html"
    assert cli.main(["report", str(results["pda"]), "--out", str(out)]) == 0
    assert f"report -> {out}" in capsys.readouterr().out
    assert out.read_text().startswith("<!DOCTYPE html>")
    assert anvilwave.api.report(results["pda"]) == results["pda"] / REPORT_NAME


def test_a_folder_without_recorded_inputs_still_reports(tmp_path):
    folder = _fake_result(tmp_path / "r", "impact", "summary.json",
                          {"peak_anvil_pile_force [N]": 4.5e8, "system": "table1.toml"},
                          "impact.png")
    text = build_report(folder)
    assert "records no inputs" in text and "450.0" in text


def _chromium(args: list[str], tmp_path: Path) -> subprocess.CompletedProcess:
    profile = tmp_path / f"profile-{len(list(tmp_path.glob('profile-*')))}"
    return subprocess.run([str(CHROMIUM), *FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=120, check=True)


def _boxes(dom: str) -> list[tuple[int, int, int, int]]:
    match = re.search(r'data-figure-boxes="([^"]*)"', dom)
    assert match, "the page's script did not run"
    return [tuple(int(v) for v in b.split(",")) for b in match.group(1).split(";") if b]


@NEEDS_CHROMIUM
@pytest.mark.parametrize("kind", KINDS)
def test_chromium_decodes_every_figure(results, tmp_path, kind):
    report = results[kind] / REPORT_NAME
    dom = _chromium(["--dump-dom", report.as_uri()], tmp_path).stdout
    n = len(_figures_in(results[kind]))
    assert f'data-figures="{n}/{n}"' in dom


@NEEDS_CHROMIUM
@pytest.mark.parametrize("kind", ["impact", "compare"])
def test_chromium_screenshot_shows_the_figures(results, tmp_path, kind):
    """The page is not blank and each figure's place holds a figure: coloured, varied pixels
    (the tables and text are black and grey); the compare figure's red block is red."""
    report = results[kind] / REPORT_NAME
    boxes = _boxes(_chromium(["--dump-dom", report.as_uri()], tmp_path).stdout)
    height = max(top + h for _, top, _, h in boxes) + 50
    shot = tmp_path / "shot.png"
    _chromium([f"--screenshot={shot}", f"--window-size=1200,{height}", report.as_uri()],
              tmp_path)
    image = mpimg.imread(shot)[..., :3]
    assert image.std() > 0.05  # not blank
    for left, top, width, h in boxes:
        region = image[top:top + h, left:left + width]
        assert region.size and region.std() > 0.05
        colour = region.max(axis=2) - region.min(axis=2)
        assert (colour > 0.3).mean() > 0.002, (left, top, width, h)
        text = image[:boxes[0][1]]  # above the first figure: tables and text only
        assert (text.max(axis=2) - text.min(axis=2) > 0.3).mean() < 0.001
    if kind == "compare":
        left, top, width, h = boxes[0]
        middle = image[top + h // 3:top + 2 * h // 3, left + width // 3:left + 2 * width // 3]
        red = (middle[..., 0] > 0.7) & (middle[..., 1] < 0.2) & (middle[..., 2] < 0.2)
        assert red.mean() > 0.5


def test_the_ci_installs_chromium():
    ci = (Path(__file__).resolve().parents[1] / ".ci" / "run").read_text()
    assert "apt-get install -y -qq chromium" in ci


def test_the_style_fetches_nothing():
    """The inline style names no font file or image to fetch, and sets the A4 print page."""
    assert "@import" not in CSS and "url(" not in CSS and "@font-face" not in CSS
    assert "@media print" in CSS and "size: A4" in CSS
