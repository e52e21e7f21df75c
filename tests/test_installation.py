"""Blow-by-blow installation: outputs, fatigue from the whole sequence, spectra, and the
comparison with the per-depth driveability."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from anvilwave.cli import main
from anvilwave.config.system import load_system

from .conftest import EXAMPLES


@pytest.fixture(scope="module")
def short_install(tmp_path_factory):
    """xl_monopile_drive.toml installed from its self-weight penetration to 40 m (about
    1600 blows, some 15 s here)."""
    tmp = tmp_path_factory.mktemp("install")
    shutil.copytree(EXAMPLES / "anvils", tmp / "anvils")
    shutil.copytree(EXAMPLES / "soil", tmp / "soil")
    text = (EXAMPLES / "xl_monopile_drive.toml").read_text()
    assert "[installation]" in text
    path = tmp / "install.toml"
    path.write_text(text)
    assert main(["install", str(path), "--out", str(tmp / "out")]) == 0
    return tmp / "out", load_system(path)


def test_installation_writes_its_outputs(short_install):
    out, cfg = short_install
    summary = json.loads((out / "summary.json").read_text())
    for key in ("total_blows [-]", "final_depth [m]", "driving_time [s]", "max_damage [-]",
                "wall_time [s]", "spectra_valid_band [Hz]"):
        assert key in summary
    assert summary["final_depth [m]"] >= 40.0 and summary["stopped_by"] == "target depth"
    blows = np.genfromtxt(out / "blows.csv", delimiter=",", names=True)
    assert blows.size == summary["total_blows [-]"]
    tip = blows["tip_depth_m"]
    assert np.all(np.diff(tip) >= 0.0)
    # each blow starts where the previous one left the tip
    assert np.allclose(tip[1:], tip[:-1] + blows["set_m"][:-1])
    fatigue = np.genfromtxt(out / "fatigue.csv", delimiter=",", names=True, dtype=None,
                            encoding="utf-8")
    assert fatigue.size == 8
    assert np.all(np.isfinite(fatigue["damage_"])) and np.all(fatigue["damage_"] > 0.0)
    spectra = np.genfromtxt(out / "spectra.csv", delimiter=",", names=True)
    assert spectra.size > 10 and np.all(np.isfinite(spectra["band_energy_level_dB"]))
    assert (out / "installation.png").exists()


def test_installation_total_blows_follow_the_driveability(short_install):
    """Total blows: every blow simulated against one blow per depth, within 15 % (the
    issue's bound). The installation carries the residual stresses and the soil springs'
    plastic offsets from blow to blow: the pile starts each blow pre-compressed with its toe
    already loaded, so it needs fewer blows than a pile that starts every depth from rest."""
    from anvilwave.analyses.drive import run_driveability
    from anvilwave.engine.direct import build_engine

    out, cfg = short_install
    summary = json.loads((out / "summary.json").read_text())
    drive = run_driveability(cfg, cfg.srd, cfg.drive, build_engine(cfg), workers=1)
    total = drive.summary["total_blows [-]"]
    assert summary["total_blows [-]"] == pytest.approx(total, rel=0.15)
