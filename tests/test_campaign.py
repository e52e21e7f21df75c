"""Campaigns on dask.distributed (LocalCluster, 2 worker processes): every case exactly once,
a killed worker, reruns, failing cases; the campaign file's checks and the examples.

The campaigns here are tiny (a 2 m x 20 m pile, the 86 kJ illustrative ram with the lumped s2
anvil, 8 depths): a case takes a fraction of a second, so the tests measure the machinery, not
the physics (tests/test_driveability.py does that)."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
import tomllib
from pathlib import Path

import pytest

from anvilwave.analyses.batch import (
    CAMPAIGN_KEYS,
    KEY_PREFIX,
    load_campaign,
    read_campaign_csv,
    run_campaign,
)
from anvilwave.inputs import InputError, Table
from anvilwave.inputs import toml_dumps as toml_text
from anvilwave.output.writer import result_command

from .conftest import EXAMPLES

BASE = """
[simulation]
duration = 0.02           # [s]
gravity = 9.81

[hammer]
database = "illustrative_s2"

[anvil]
model = "lumped"
file = "{anvil}"

[pile]
segment_length = 0.5
gauge_depth = 1.0
[[pile.sections]]
length = 20.0
outer_diameter = 2.0
wall_thickness = 0.05

[soil]
model = "smith-viscous"
damping_shaft = 0.16
damping_toe = 0.5

[srd]
method = "alm-hamre-2001"
cpt = "cpt_good.csv"
[[srd.layers]]
top = 0.0
bottom = 15.0
soil = "sand"
submerged_unit_weight = 10.0e3
interface_friction_angle = 29.0

[driveability]
start = 2.0
stop = 9.0
step = 1.0
blows_per_depth = {blows}
"""

POSITION = """
[[positions]]
name = "{name}"
water_depth = 20.0
target_penetration = {target}
[positions.pile]
[[positions.pile.sections]]
length = {length}
outer_diameter = 2.0
wall_thickness = 0.05
[positions.srd]
method = "alm-hamre-2001"
cpt = "{cpt}"
[[positions.srd.layers]]
top = 0.0
bottom = 15.0
soil = "sand"
submerged_unit_weight = 10.0e3
interface_friction_angle = 29.0
"""


def _cpt(path: Path, bottom: float = 15.0) -> None:
    """A synthetic sand CPT: qc = 4 + 1.2 z [MPa], friction ratio 0.8 %."""
    lines = ["depth [m],qc [MPa],fs [MPa],u2 [MPa]"]
    for i in range(int(bottom / 0.5) + 1):
        qc = 4.0 + 0.6 * i
        lines.append(f"{0.5 * i:.1f},{qc:.3f},{0.008 * qc:.4f},0.0")
    path.write_text("\n".join(lines) + "\n")


def write_campaign(folder: Path, positions=(("P1", 8.0), ("P2", 9.0)),
                   bounds=("lower", "best", "upper"), blows: int = 1, extra: str = "",
                   cpts: dict | None = None) -> Path:
    """A tiny campaign in ``folder``: positions (name, target [m]) with good CPTs unless
    ``cpts`` gives another file for a position."""
    folder.mkdir(parents=True, exist_ok=True)
    _cpt(folder / "cpt_good.csv")
    _cpt(folder / "cpt_short.csv", bottom=5.0)  # ends above the targets
    (folder / "base.toml").write_text(BASE.format(anvil=EXAMPLES / "anvils" / "s2.toml",
                                                  blows=blows))
    text = ('[campaign]\nname = "tiny"\nsystem = "base.toml"\n\n[axes]\nbounds = ['
            + ", ".join(f'"{b}"' for b in bounds) + "]\n" + extra)
    for name, target in positions:
        text += POSITION.format(name=name, target=target, length=20.0,
                                cpt=(cpts or {}).get(name, "cpt_good.csv"))
    path = folder / "campaign.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def cluster():
    """A LocalCluster of 2 worker processes shared by the tests that pass its address."""
    import logging

    import dask
    from dask.distributed import LocalCluster

    with dask.config.set({"distributed.scheduler.allowed-failures": 3}):
        c = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                         dashboard_address=":0", silence_logs=logging.ERROR)
    yield c
    c.close()


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """The tiny campaign run once on the default LocalCluster (workers=2)."""
    folder = tmp_path_factory.mktemp("campaign")
    path = write_campaign(folder)
    out = folder / "out"
    result = run_campaign(path, out, workers=2, progress=False)
    return path, out, result


def _names_of(out: Path) -> list[str]:
    return [r["case"] for r in read_campaign_csv(out / "campaign.csv")]


# ----------------------------------------------------------------------------- on dask
def test_campaign_completes_with_every_case_exactly_once(finished):
    path, out, result = finished
    cases = [c.name for c in load_campaign(path).cases]
    assert len(cases) == 6 and result.workers == 2
    assert result.ok == 6 and result.error == 0 and result.ran == 6
    rows = read_campaign_csv(out / "campaign.csv")
    assert [r["case"] for r in rows] == cases  # each once, in the campaign's order
    assert result_command(out) == "batch"  # marked: another command will not write into it
    header = list(rows[0])
    assert header == ["case", "position", "bound", "hammer", "anvil_model", "status",
                      "refusal_depth [m]", "total_blows [-]", "max_blow_count [1/m]",
                      "max_compression_stress [Pa]", "max_tension_stress [Pa]",
                      "driving_time [s]", "wall_time [s]", "error"]
    for r in rows:
        assert r["status"] == "ok" and r["error"] == ""
        assert r["total_blows [-]"] > 0 and r["max_blow_count [1/m]"] > 0
        assert r["max_compression_stress [Pa]"] > 0 >= r["max_tension_stress [Pa]"]
        folder = out / "cases" / r["case"]
        assert sorted(p.name for p in folder.iterdir()) == [
            "driveability.csv", "driveability.png", "summary.json", "system.toml"]
        summary = json.loads((folder / "summary.json").read_text())
        assert summary["case"] == r["case"] and summary["bound"] == r["bound"]
    # the bounds order the blow counts of a position (SRD x 0.8, 1, 1.25)
    p1 = {r["bound"]: r["total_blows [-]"] for r in rows if r["position"] == "P1"}
    assert p1["lower"] < p1["best"] < p1["upper"]
    # a case's system.toml is a complete system file with its axes' values
    one = tomllib.loads((out / "cases" / rows[0]["case"] / "system.toml").read_text())
    assert one["driveability"]["bound"] == "lower" and one["driveability"]["stop"] == 8.0


def test_campaign_plots(finished):
    _, out, _ = finished
    plots = out / "plots"
    assert (plots / "envelope_P1.png").stat().st_size > 10_000
    assert (plots / "envelope_P2.png").stat().st_size > 10_000
    assert (plots / "refusal_risk.png").stat().st_size > 10_000
    risk = (plots / "refusal_risk.csv").read_text().splitlines()
    assert len(risk) == 3 and risk[0].startswith("position,hammer,anvil_model,status")
    assert not list(plots.glob(".*"))  # no partial file left


def test_rerun_does_nothing_new(finished):
    path, out, _ = finished
    stamps = {p: p.stat().st_mtime_ns for p in (out / "cases").rglob("*")}
    before = (out / "campaign.csv").read_text()
    result = run_campaign(path, out, progress=False, plots=False)
    assert result.ran == 0 and result.skipped == 6 and result.ok == 6
    assert result.workers == 0  # no cluster started
    assert {p: p.stat().st_mtime_ns for p in (out / "cases").rglob("*")} == stamps
    assert (out / "campaign.csv").read_text() == before


def test_a_changed_case_runs_again_alone(tmp_path, cluster):
    path = write_campaign(tmp_path, positions=(("P1", 8.0),), bounds=("best",))
    out = tmp_path / "out"
    run_campaign(path, out, scheduler=cluster.scheduler_address, progress=False, plots=False)
    write_campaign(tmp_path, positions=(("P1", 8.0), ("P2", 7.0)), bounds=("best",))
    result = run_campaign(path, out, scheduler=cluster.scheduler_address, progress=False,
                          plots=False)
    assert result.ran == 1 and result.skipped == 1 and result.ok == 2
    path.write_text(path.read_text().replace("target_penetration = 7.0",
                                             "target_penetration = 6.0"))
    result = run_campaign(path, out, scheduler=cluster.scheduler_address, progress=False,
                          plots=False)
    assert result.ran == 1 and result.skipped == 1
    rows = read_campaign_csv(out / "campaign.csv")
    assert [r["case"] for r in rows] == ["P1_best_illustrative_s2_lumped",
                                         "P2_best_illustrative_s2_lumped"]
    csv_p2 = (out / "cases" / rows[1]["case"] / "driveability.csv").read_text().splitlines()
    assert csv_p2[-1].startswith("6,")  # the new target is the last depth


def test_a_worker_killed_mid_case_still_gives_a_complete_campaign(tmp_path, cluster):
    from dask.distributed import Client

    # longer cases (40 blows per depth): a case is still running when it is found
    path = write_campaign(tmp_path, blows=40, bounds=("lower", "upper"))
    out = tmp_path / "out"
    names = [c.name for c in load_campaign(path).cases]

    def executing(dask_worker):  # run on each worker (a local function: sent by value)
        return os.getpid(), [str(ts.key) for ts in dask_worker.state.executing]

    results: list = []
    runner = threading.Thread(target=lambda: results.append(run_campaign(
        path, out, scheduler=cluster.scheduler_address, progress=False, plots=False)))
    killed = None
    with Client(cluster.scheduler_address) as client:
        runner.start()
        deadline = time.monotonic() + 120.0
        while killed is None and runner.is_alive() and time.monotonic() < deadline:
            for pid, keys in client.run(executing).values():
                for key in keys:
                    case = next((n for n in names if key.startswith(f"{KEY_PREFIX}{n}-")),
                                None)
                    folder = out / "cases" / str(case)
                    # mid-case: started (system.toml written) and not finished (no summary)
                    if case and (folder / "system.toml").exists() and \
                            not (folder / "summary.json").exists():
                        os.kill(pid, signal.SIGKILL)
                        killed = (case, pid)
                        break
                if killed:
                    break
            time.sleep(0.02)
        runner.join(180.0)
        alive = set(client.run(os.getpid).values())
    assert killed is not None, "no case was caught running"
    assert not runner.is_alive()
    assert killed[1] not in alive  # that worker process is gone (its nanny started another)
    (result,) = results
    assert result.ok == len(names) and result.error == 0
    assert _names_of(out) == names  # complete, every case once
    summary = json.loads((out / "cases" / killed[0] / "summary.json").read_text())
    assert summary["worker_pid"] != killed[1]  # the killed case ran again elsewhere
    assert not list((out / "cases").glob("*/.partial-*"))


def test_a_bad_case_is_recorded_with_its_error_while_the_others_succeed(tmp_path, cluster):
    path = write_campaign(
        tmp_path, positions=(("P1", 8.0), ("NOCPT", 8.0), ("SHORT", 8.0)), bounds=("best",),
        cpts={"NOCPT": "missing_cpt.csv", "SHORT": "cpt_short.csv"})
    out = tmp_path / "out"
    result = run_campaign(path, out, scheduler=cluster.scheduler_address, progress=False,
                          plots=True)
    assert result.ok == 1 and result.error == 2
    rows = {r["position"]: r for r in read_campaign_csv(out / "campaign.csv")}
    assert rows["P1"]["status"] == "ok" and rows["P1"]["total_blows [-]"] > 0
    # a position whose CPT file is missing: found before the run, named with its file
    assert rows["NOCPT"]["status"] == "error"
    assert "missing_cpt.csv" in rows["NOCPT"]["error"]
    # a CPT that ends above the target penetration: found by the case in its worker
    assert rows["SHORT"]["status"] == "error"
    assert "ends at 5 m" in rows["SHORT"]["error"]
    assert rows["SHORT"]["total_blows [-]"] is None
    error = json.loads((out / "cases" / rows["SHORT"]["case"] / "error.json").read_text())
    assert error["status"] == "error" and "Traceback" in error["traceback"]
    assert not (out / "cases" / rows["SHORT"]["case"] / "summary.json").exists()
    assert (out / "plots" / "refusal_risk.png").exists()
    # a rerun tries the failed cases again (their input may have been fixed), not P1
    (tmp_path / "missing_cpt.csv").write_text((tmp_path / "cpt_good.csv").read_text())
    result = run_campaign(path, out, scheduler=cluster.scheduler_address, progress=False,
                          plots=False)
    assert result.ran == 2 and result.skipped == 1
    assert result.ok == 2 and result.error == 1


# ----------------------------------------------------------------------------- the file
def test_toml_text_round_trips():
    data = {"a": 1, "b": 2.5e-5, "c": "x \"y\"", "d": [[0.0, 1e6], [10.0, 2e6]],
            "e": True, "t": {"k": [1, 2], "u": {"v": "w"}},
            "arr": [{"x": 1.0, "sub": {"y": 2}}, {"x": 3.0}], "dotted key": -0.0}
    assert tomllib.loads(toml_text(data)) == data


@pytest.mark.slow  # with an empty modal-data cache: the base's modal ram (about 30 s)
def test_the_example_campaigns_compose_their_cases():
    small = load_campaign(EXAMPLES / "campaign_small.toml")
    assert len(small.cases) == 12
    assert small.axes == ("position", "bound", "hammer", "anvil_model")
    assert all(p.error is None for p in small.positions)
    case = next(c for c in small.cases if c.name == "B07_upper_IL5500_lumped")
    system = tomllib.loads(case.system_text)
    assert system["anvil"]["model"] == "lumped"
    assert system["driveability"]["bound"] == "upper"
    assert system["driveability"]["stop"] == 40.0
    assert system["srd"]["water_depth"] == 34.0
    assert [s["wall_thickness"] for s in system["pile"]["sections"]] == [0.14, 0.11]
    farm = load_campaign(EXAMPLES / "campaign_farm.toml")
    assert len(farm.cases) == 6 * 3 * 2 * 2
    assert all(p.error is None for p in farm.positions)
    s4000 = tomllib.loads(next(c for c in farm.cases if "S4000" in c.name).system_text)
    assert s4000["hammer"]["database"] == "ihc_s4000"
    assert s4000["anvil"]["file"].endswith("xl8_s4000.toml")
    assert max(e for _, e in s4000["driveability"]["energy"]) == 4.0e6


@pytest.mark.slow  # as above
def test_every_campaign_key_the_examples_use_is_documented():
    Table.record = used = []
    try:
        for name in ("campaign_small.toml", "campaign_farm.toml"):
            load_campaign(EXAMPLES / name)
    finally:
        Table.record = None
    keys = {k for f, k in used  # the campaign files' keys (not the base's, the srd files')
            if Path(f).name in ("campaign_small.toml", "campaign_farm.toml")}
    assert "positions.srd.layers.top" in keys and "axes.hammers.anvil" in keys

    def documented(key):
        return key in CAMPAIGN_KEYS or any(
            p.endswith(".*") and key.startswith(p[:-1]) for p in CAMPAIGN_KEYS)

    assert not sorted(k for k in keys if not documented(k))


@pytest.mark.parametrize(
    ("change", "key", "rule"),
    [
        (("[axes]", "[axes]\ncolour = 1"), "axes.colour", "unknown key"),
        (('bounds = ["lower", "best", "upper"]', 'bounds = ["low"]'), "axes.bounds",
         "must be one of"),
        (('bounds = ["lower", "best", "upper"]', 'bounds = ["best", "best"]'), "axes.bounds",
         "twice"),
        (('[axes]', '[axes]\nanvil_models = ["classic"]'), "axes.anvil_models",
         "[anvil.classic]"),
        (('name = "P2"', 'name = "P1"'), "positions[1].name", "used twice"),
        (('name = "P2"', 'name = "P 2"'), "positions[1].name", "letters, digits"),
        (("target_penetration = 9.0", "target_penetration = -9.0"),
         "positions[1].target_penetration", "greater than 0"),
        (("water_depth = 20.0\ntarget_penetration = 9.0", "target_penetration = 9.0"),
         "positions[1].water_depth", "required"),
        (("water_depth = 20.0\ntarget_penetration = 9.0",
          'water_depth = 20.0\nsrd_file = "s.toml"\ntarget_penetration = 9.0'),
         "positions[1].srd", "exactly one"),
        (('system = "base.toml"', 'system = "nowhere.toml"'), "campaign.system",
         "not found"),
        (("[axes]", '[axes]\n[[axes.hammers]]\nname = "H"\ndatabase = "illustrative_s2"\n'
                    "energy = [[0.0, 1.0e6]]"), "axes.hammers[0].energy",
         "above the rated energy"),
        (("[axes]", '[axes]\n[[axes.hammers]]\nname = "H"\ndatabase = "no_such_hammer"'),
         "axes.hammers[0].database", "must be one of"),
        (("[axes]", '[axes]\n[[axes.energy_schedules]]\nname = "E"\n'
                    "fraction = [[0.0, 1.5]]"), "axes.energy_schedules[0].fraction",
         "at most 1"),
    ],
)
def test_a_bad_campaign_file_names_file_key_and_rule(tmp_path, change, key, rule):
    path = write_campaign(tmp_path)
    text = path.read_text()
    old, new = change
    assert old in text
    path.write_text(text.replace(old, new, 1) if old != 'name = "P2"' else
                    text.replace(old, new))
    with pytest.raises(InputError) as info:
        load_campaign(path)
    message = str(info.value)
    assert len(message.splitlines()) == 1
    assert message.startswith(str(path)) and key in message and rule in message, message


def test_a_bad_position_only_fails_its_own_cases(tmp_path):
    """Bad data of one position (a typo in its pile table) is recorded for its cases, named
    with the campaign file and key; the campaign still loads."""
    path = write_campaign(tmp_path)
    text = path.read_text()
    i = text.index('name = "P2"')
    text = text[:i] + text[i:].replace("wall_thickness = 0.05", "wall_thicknes = 0.05", 1)
    path.write_text(text)
    campaign = load_campaign(path)
    bad = {p.name: p.error for p in campaign.positions}
    assert bad["P1"] is None
    assert bad["P2"].startswith(f"{path}: positions[1].pile.sections[0].wall_thickness: is "
                                "required but missing")
    assert all((c.error is None) == (c.axes["position"] == "P1") for c in campaign.cases)
