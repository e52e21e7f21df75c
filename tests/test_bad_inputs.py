"""Bad inputs of drive, install, pda, match, compare-pda, build-fmus, report and the output folder
(issue 30): each case is a small file made in the test; each gives one line on stderr naming
the file or option, the key, the row or table and the rule, exit status 2, no traceback, and
no output folder (or the one there unchanged).

:data:`BAD_INPUTS` lists the command-line cases by class (the docs state the count and the
classes from it); the faults (a write that fails, a killed run, Ctrl-C) and the PDA fixes are
tests of their own below.
"""

from __future__ import annotations

import errno
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from anvilwave import cli
from anvilwave.fmu.native_build import NativeBuildError
from anvilwave.inputs import InputError
from anvilwave.output.writer import (
    MARKER,
    ResultWriter,
    check_output,
    remove_stale_staging,
    result_command,
)
from anvilwave.pile.pda.case_method import case_method, first_peak_index

HAMMER = """
name = "drop hammer"
rated_energy = 9810.0     # [J] 1000 kg dropped 1 m
efficiency = 1.0
[ram]
kind = "rigid"
mass = 1000.0             # [kg]
"""

SYSTEM = """
[simulation]
duration = 0.01
gravity = 9.81

[hammer]
file = "hammer.toml"

[anvil]
model = "none"
ram_contact_stiffness = 2.0e10
pile_contact_stiffness = 2.0e10

[pile]
segment_length = 0.5
gauge_depth = 0.5
[[pile.sections]]
length = 10.0
outer_diameter = 0.7
wall_thickness = 0.03
youngs_modulus = 2.1e11
density = 7850.0

[soil]
model = "smith-viscous"
penetration = 5.0
quake_shaft = 0.0025
quake_toe = 0.0025
damping_shaft = 0.1
damping_toe = 0.3
toe_area = "plugged"
{soil_extra}
{extra}
"""

SRD_ROWS = "srd = [[0.0, 1e3, 1e6], [10.0, 2e4, 5e6]]"

DRIVE = "[driveability]\ndepths = [2.0, 4.0]\n"


def _system(tmp_path: Path, extra: str = DRIVE, soil_extra: str = SRD_ROWS) -> Path:
    (tmp_path / "hammer.toml").write_text(HAMMER)
    path = tmp_path / "system.toml"
    path.write_text(SYSTEM.format(extra=extra, soil_extra=soil_extra))
    return path


def _grl(tmp_path: Path, runs) -> str:
    """An [srd] tip-table reading a GRLWEAP model.json with ``runs``."""
    (tmp_path / "model.json").write_text(json.dumps({"soil_model": {"srd_tables_by_run":
                                                                    runs}}))
    return DRIVE + '[srd]\nmethod = "tip-table"\nfile = "model.json"\n'


def _run(tmp_path, cols=("soil_depth [m]", "unit_shaft_resistance [kPa]",
                         "toe_resistance [kN]"), rows=((0.0, 1.0, 100.0), (10.0, 20.0, 900.0)),
         tip=4.0):
    return {"tip_depth_the_table_was_built_for [m]": tip, "columns": list(cols),
            "rows": [list(r) for r in rows]}


def _cpt_huge(tmp_path: Path) -> str:
    (tmp_path / "cpt.csv").write_text("depth [m],qc [MPa],fs [kPa]\n0.0,1.0,10\n"
                                      + "1.0,\"" + "9" * 200_000 + "\",10\n")
    return (DRIVE + '[srd]\nmethod = "alm-hamre-2001"\ncpt = "cpt.csv"\n'
            '[[srd.layers]]\ntop = 0.0\nbottom = 20.0\nsoil = "sand"\n'
            'submerged_unit_weight = 10e3\ninterface_friction_angle = 29.0\n')


def _record(tmp_path: Path, n: int = 50, dt: float = 1e-4) -> Path:
    """A short gauge record (a half-sine pulse)."""
    t = np.arange(n) * dt
    f = 1e6 * np.sin(np.pi * np.clip(t / (10 * dt), 0, 1)) ** 2
    path = tmp_path / "record.csv"
    rows = "\n".join(f"{float(a)!r},{float(b)!r},{float(b) / 3e6!r}"
                     for a, b in zip(t, f, strict=True))
    path.write_text("time [s],force [N],velocity [m/s]\n" + rows + "\n")
    return path


# (class, id, extra of the system file or a builder (tmp_path) -> extra, extra arguments,
#  the command, words the one line must hold)
BAD_INPUTS = [
    # tracebacks before
    ("traceback", "time-series depth below the pile",
     DRIVE + "time_series_depths = [12.0]\n", [], "drive",
     ["driveability.time_series_depths", "row 1", "12 m"]),
    ("traceback", "bearing-graph depth below the pile", DRIVE, ["--bearing-graph", "12"],
     "drive", ["--bearing-graph", "12 m", "10 m"]),
    ("traceback", "installation target below the pile",
     DRIVE + "[installation]\ntarget_depth = 12.0\n", [], "install",
     ["installation.target_depth", "12 m", "pile"]),
    ("traceback", "installation start below the pile",
     DRIVE + "[installation]\nstart_depth = 11.0\n", [], "install",
     ["installation.start_depth", "11 m"]),
    ("traceback", "installation start below the target",
     DRIVE + "[installation]\nstart_depth = 3.0\ntarget_depth = 2.0\n", [], "install",
     ["installation.start_depth", "target_depth"]),
    ("traceback", "CPT file with a huge field", _cpt_huge, [], "drive",
     ["cpt.csv", "line 3"]),
    ("traceback", "GRLWEAP runs as a list", lambda p: _grl(p, [_run(p)]), [], "drive",
     ["model.json", "soil_model.srd_tables_by_run", "list"]),
    ("traceback", "GRLWEAP runs empty", lambda p: _grl(p, {}), [], "drive",
     ["model.json", "soil_model.srd_tables_by_run", "non-empty"]),
    ("traceback", "GRLWEAP empty rows", lambda p: _grl(p, {"1": _run(p, rows=())}), [],
     "drive", ["model.json", "srd_tables_by_run.1.rows"]),
    ("traceback", "GRLWEAP flat rows", lambda p: _grl(p, {"1": {**_run(p),
                                                                "rows": [0.0, 1.0, 2.0]}}),
     [], "drive", ["model.json", "srd_tables_by_run.1.rows", "shape"]),
    ("traceback", "GRLWEAP run not an object", lambda p: _grl(p, {"1": [1, 2]}), [], "drive",
     ["model.json", "srd_tables_by_run.1", "not a GRLWEAP table"]),
    # bad values accepted before
    ("accepted", "string in the depth schedule", "[driveability]\ndepths = [2.0, \"4\"]\n",
     [], "drive", ["driveability.depths", "row 2", "'4'"]),
    ("accepted", "string in the energy schedule",
     DRIVE + "energy = [[0.0, 5000.0], [3.0, \"6000\"]]\n", [], "drive",
     ["driveability.energy", "row 2", "column 2"]),
    ("accepted", "energy above the rated energy",
     DRIVE + "energy = [[0.0, 5000.0], [3.0, 20000.0]]\n", [], "drive",
     ["driveability.energy", "row 2", "rated"]),
    ("accepted", "negative time-series depth", DRIVE + "time_series_depths = [-1.0]\n", [],
     "drive", ["driveability.time_series_depths", "row 1", "negative"]),
    ("accepted", "negative bearing-graph depth", DRIVE, ["--bearing-graph", "-1"], "drive",
     ["--bearing-graph", "-1 m"]),
    ("accepted", "time-series depth beyond the last depth",
     DRIVE + "time_series_depths = [2.0, 5.0]\n", [], "drive",
     ["driveability.time_series_depths", "row 2", "last tip depth"]),
    ("accepted", "--workers -3", DRIVE, ["--workers", "-3"], "drive", ["--workers", "-3"]),
    ("accepted", "weld depth below the pile",
     DRIVE + "[installation]\nweld_depths = [1.0, 11.0]\n", [], "install",
     ["installation.weld_depths", "row 2", "11 m"]),
    ("accepted", "spectra depth beyond the target",
     DRIVE + "[installation]\ntarget_depth = 3.0\nspectra_depths = [2.0, 3.5]\n", [],
     "install", ["installation.spectra_depths", "row 2", "target"]),
    # vague or wrong messages before
    ("vague", "driveability depth beyond the pile", "[driveability]\ndepths = [2.0, 12.0]\n",
     [], "drive", ["driveability.depths", "row 2", "12 m", "pile's length, 10 m"]),
    ("vague", "GRLWEAP NaN in run 3",
     lambda p: _grl(p, {"1": _run(p, tip=2.0), "2": _run(p, tip=3.0),
                        "3": _run(p, rows=((0.0, float("nan"), 1.0), (10.0, 2.0, 3.0)))}),
     [], "drive", ["model.json", "srd_tables_by_run.3.rows", "row 1"]),
    ("vague", "GRLWEAP duplicate tip depth in run 3",
     lambda p: _grl(p, {"1": _run(p, tip=2.0), "2": _run(p, tip=3.0),
                        "3": _run(p, tip=3.0)}),
     [], "drive", ["model.json", "srd_tables_by_run.3", "duplicate"]),
    ("vague", "GRLWEAP negative value in run 3",
     lambda p: _grl(p, {"1": _run(p, tip=2.0), "2": _run(p, tip=3.0),
                        "3": _run(p, rows=((0.0, 1.0, 1.0), (10.0, -2.0, 3.0)))}),
     [], "drive", ["model.json", "srd_tables_by_run.3.rows", "row 2", "negative"]),
    ("vague", "GRLWEAP soil depths decreasing",
     lambda p: _grl(p, {"1": _run(p, rows=((5.0, 1.0, 1.0), (1.0, 2.0, 3.0)))}),
     [], "drive", ["model.json", "srd_tables_by_run.1.rows", "row 2", "must not decrease"]),
]
"""The command-line bad inputs: (class, case, system extra, arguments, command, words)."""

EXAMPLE_ANVILS = Path(__file__).resolve().parents[1] / "anvilwave" / "examples" / "anvils"
ANVIL = f'[[anvil.bodies]]\nfile = "{EXAMPLE_ANVILS / "xl8.toml"}"\n'
RING = f'[[anvil.bodies]]\nfile = "{EXAMPLE_ANVILS / "xl8_ring.toml"}"\n'
STACK_SYSTEM = """
[simulation]
duration = 0.01

[hammer]
database = "illustrative_5500kj"
{hammer}

[anvil]
model = "{model}"
{anvil}

[pile]
segment_length = 0.5
[[pile.sections]]
length = 80.0
outer_diameter = 8.0
wall_thickness = 0.14
"""

STACK_CASES = [
    ("file and bodies", {"anvil": f'file = "{EXAMPLE_ANVILS / "xl8.toml"}"\n' + ANVIL},
     ["anvil.bodies", "not both"]),
    ("three bodies", {"anvil": ANVIL + RING + RING}, ["anvil.bodies", "3 bodies"]),
    ("ring file missing", {"anvil": ANVIL + '[[anvil.bodies]]\nfile = "no_ring.toml"\n'},
     ["anvil.bodies[1].file", "no_ring.toml", "not found"]),
    ("negative seat friction", {"anvil": ANVIL + RING + "seat_friction = -0.1\n"},
     ["anvil.bodies[1].seat_friction", "-0.1"]),
    ("no seat ring", {"anvil": ANVIL + RING + "seat_rings = 0\n"},
     ["anvil.bodies[1].seat_rings"]),
    ("friction on the anvil", {"anvil": ANVIL + "seat_friction = 0.1\n" + RING},
     ["anvil.bodies[0]", "seat_friction"]),
    ("stack with the lumped anvil", {"anvil": ANVIL + RING, "model": "lumped"},
     ["anvil.bodies", "model = 'rom'"]),
    ("ring off the seat", {"anvil": ANVIL + '[[anvil.bodies]]\nfile = "ring.toml"\n',
                           "ring": [[4.2, 0.0], [4.5, 0.0], [4.5, 0.5], [4.2, 0.5]]},
     ["anvil.bodies[1].file", "ring.toml", "seat"]),
    ("pile wall beyond the ring", {"anvil": ANVIL + '[[anvil.bodies]]\nfile = "ring.toml"\n',
                                   "ring": [[3.0, 0.0], [3.9, 0.0], [3.9, 0.5], [3.0, 0.5]]},
     ["anvil.bodies[1].file", "pile ring", "3.86 to 4"]),
    ("stack on the tube head with one pile ring",
     {"anvil": 'pile_head = "tube"\npile_port_rings = 1\n' + ANVIL + RING},
     ["anvil.pile_head", "pile_port_rings >= 2"]),
    ("stack with the rod ram", {"anvil": ANVIL + RING, "hammer": ""},
     ["hammer.ram_model", "modal"]),
    ("negative sleeve clearance", {"anvil": "sleeve_clearance = -0.001\n" + ANVIL + RING},
     ["anvil.sleeve_clearance", "-0.001"]),
    ("sleeve friction without a sleeve", {"anvil": "sleeve_friction = 0.2\n" + ANVIL + RING},
     ["anvil.sleeve_friction", "sleeve_clearance"]),
    ("sleeve bands not whole numbers",
     {"anvil": "sleeve_clearance = 0.001\nsleeve_bands = [4.5, 4]\n" + ANVIL + RING},
     ["anvil.sleeve_bands", "two whole numbers", "4.5"]),
    ("sleeve without a ring",
     {"anvil": f'sleeve_clearance = 0.001\nfile = "{EXAMPLE_ANVILS / "xl8.toml"}"\n'},
     ["anvil.sleeve_clearance"]),
]
"""The driving stack's bad inputs ([[anvil.bodies]], test_bad_stack): (case, parts of the
system file, words)."""

OUTPUT_CASES = ["out is a file", "out below a file", "out holds another command's result",
                "read-only folder", "folder that cannot be looked into",
                "--force replaces another command's result whole",
                "a rerun replaces its result whole"]
"""Bad output folders (test_bad_output_folder)."""

FAULT_CASES = ["disk full while writing", "cache entry with scaled frequencies or mass",
               "file too large while writing",
               "write refused (permission) while writing", "native build fails",
               "Ctrl-C", "Ctrl-C on drive with workers",
               "killed drive: no orphan workers, staging removed by the rerun",
               "stale staging of a dead run removed", "match --zones too many",
               "compare-pda record shorter than 2L/c",
               "batch with a missing hammer anvil file: no half-made folder",
               "killed batch: no orphan workers, no staging",
               "Ctrl-C on batch with workers",
               "a real file-size limit while writing: the old result kept",
               "cache entry with frequencies off by 1e-6",
               "cache entry with modes not mass-normalised",
               "cache entry with a mode mixed with its neighbour",
               "Table 1 cache entry with scaled frequencies: recomputed, Table 1's peaks"]
"""The faults and refusals tested one by one below."""

PDA_CASES = ["BTA of an intact pile with 2 % noise", "impact peak on the first sample"]

REPORT_CASES = ["report of a missing folder", "report of a folder that is no result",
                "report of a file", "report --out below a file", "report --out is a folder"]
"""Bad arguments of ``anvilwave report`` (test_bad_report)."""

MISSING = "missing.toml"
EVERY_COMMAND_CASES = [
    ("modes", lambda t: ["modes", str(t / MISSING)], [MISSING]),
    ("impact", lambda t: ["impact", str(t / MISSING)], [MISSING]),
    ("build-fmus", lambda t: ["build-fmus", str(t / MISSING)], [MISSING]),
    ("fea", lambda t: ["fea", str(t / MISSING)], [MISSING]),
    ("compare", lambda t: ["compare", str(t / MISSING)], [MISSING]),
    ("demo", lambda t: ["demo", "--system", str(t / MISSING)], [MISSING]),
    ("drive", lambda t: ["drive", str(t / MISSING)], [MISSING]),
    ("install", lambda t: ["install", str(t / MISSING)], [MISSING]),
    ("batch", lambda t: ["batch", str(t / MISSING)], [MISSING]),
    ("pda", lambda t: ["pda", str(t / "missing.csv"), "--length", "4", "--area", "0.06",
                       "--jc", "0.3"],
     ["missing.csv"]),
    ("pda --length", lambda t: ["pda", str(_record(t)), "--length", "-4", "--area", "0.06",
                                "--jc", "0.3"],
     ["length", "positive", "-4"]),
    ("match", lambda t: ["match", str(t / "missing.csv"), str(_system(t))], ["missing.csv"]),
    ("compare-pda", lambda t: ["compare-pda", str(_record(t)), str(t / MISSING)], [MISSING]),
]
"""A missing or impossible input to every command that reads one
(test_every_command_refuses_a_missing_input)."""

CLASSES = sorted({c[0] for c in BAD_INPUTS} | {"output", "fault", "pda", "report", "missing",
                                                "stack"})
COUNT = (len(BAD_INPUTS) + len(OUTPUT_CASES) + len(FAULT_CASES) + len(PDA_CASES)
         + len(REPORT_CASES) + len(EVERY_COMMAND_CASES) + len(STACK_CASES))
"""Bad inputs and faults tested here."""


def _assert_one_line_exit_2(code, capsys, words, out: Path | None = None):
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert "\n" not in err and "Traceback" not in err, err
    assert err.startswith("anvilwave: error: "), err
    for w in words:
        assert w in err, (w, err)
    if out is not None:
        assert not out.exists()
        assert not list(out.parent.glob(".partial-*"))


@pytest.mark.parametrize("kind, case, extra, args, command, words", BAD_INPUTS,
                         ids=[c[1] for c in BAD_INPUTS])
def test_bad_input_gives_one_line_and_exit_2(tmp_path, capsys, kind, case, extra, args,
                                              command, words):
    system = _system(tmp_path, extra(tmp_path) if callable(extra) else extra)
    out = tmp_path / "out"
    code = cli.main([command, str(system), "--out", str(out), *args])
    _assert_one_line_exit_2(code, capsys, words, out)


def test_the_count_is_stated():
    """docs/system-file.md states the count and the classes of the cases tested here."""
    assert COUNT == len(BAD_INPUTS) + len(STACK_CASES) + 46 and COUNT >= 82
    assert CLASSES == ["accepted", "fault", "missing", "output", "pda", "report", "stack",
                       "traceback", "vague"]
    docs = (Path(__file__).resolve().parents[1] / "docs" / "system-file.md").read_text()
    words = {9: "nine"}
    assert f"runs {COUNT} such cases in {words[len(CLASSES)]} classes" in " ".join(docs.split())


@pytest.mark.parametrize("case, parts, words", STACK_CASES, ids=[c[0] for c in STACK_CASES])
def test_bad_stack(tmp_path, capsys, case, parts, words):
    """A bad driving stack ([[anvil.bodies]]) stops ``impact`` with one line naming the file,
    the body's key and the rule, exit 2, before any modes are computed."""
    if "ring" in parts:
        points = parts["ring"]
        (tmp_path / "ring.toml").write_text(
            "[material]\nyoungs_modulus = 210e9\npoisson_ratio = 0.3\ndensity = 7850.0\n"
            f"[geometry]\npoints = {points}\n[mesh]\nsize = 0.05\n")
    system = tmp_path / "system.toml"
    system.write_text(STACK_SYSTEM.format(hammer=parts.get("hammer", 'ram_model = "modal"'),
                                          model=parts.get("model", "rom"),
                                          anvil=parts["anvil"]))
    out = tmp_path / "out"
    code = cli.main(["impact", str(system), "--out", str(out)])
    _assert_one_line_exit_2(code, capsys, [str(system), *words], out)


@pytest.mark.parametrize("case", REPORT_CASES)
def test_bad_report(tmp_path, capsys, case):
    """A report of something that is no result folder, or to a file that cannot be written:
    one line, exit 2, nothing written."""
    result = tmp_path / "result"
    result.mkdir()
    (result / MARKER).write_text(json.dumps({"command": "pda"}))
    args, words = [str(result)], []
    if case == "report of a missing folder":
        args, words = [str(tmp_path / "missing")], ["missing", "no such result folder"]
    elif case == "report of a folder that is no result":
        (tmp_path / "plain").mkdir()
        args, words = [str(tmp_path / "plain")], ["plain", "not an anvilwave result", MARKER]
    elif case == "report of a file":
        (tmp_path / "file.csv").write_text("x\n")
        args, words = [str(tmp_path / "file.csv")], ["file.csv", "is a file"]
    elif case == "report --out below a file":
        (tmp_path / "taken").write_text("x")
        args += ["--out", str(tmp_path / "taken" / "r.html")]
        words = ["--out", "r.html", "cannot be written"]
    else:
        args += ["--out", str(tmp_path)]
        words = ["--out", "is a folder"]
    before = sorted(p.name for p in tmp_path.rglob("*"))
    code = cli.main(["report", *args])
    _assert_one_line_exit_2(code, capsys, words)
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


@pytest.mark.parametrize("case", OUTPUT_CASES)
def test_bad_output_folder(tmp_path, capsys, case):
    record = _record(tmp_path)
    if case == "out is a file":
        out = tmp_path / "taken"
        out.write_text("x")
        words = ["--out", "is a file"]
    elif case == "out below a file":
        (tmp_path / "taken").write_text("x")
        out = tmp_path / "taken" / "below"
        words = ["--out", "is a file"]
    else:
        out = tmp_path / "drive_result"
        out.mkdir()
        (out / MARKER).write_text(json.dumps({"command": "drive"}))
        (out / "driveability.csv").write_text("depth\n")
        words = ["--out", "anvilwave drive", "'pda'"]
    before = sorted(p.name for p in out.iterdir()) if out.is_dir() else None
    code = cli.main(["pda", str(record), "--length", "4", "--area", "0.06", "--jc", "0.3",
                     "--out", str(out)])
    err = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in err and all(w in err for w in words), err
    if before is not None:
        assert sorted(p.name for p in out.iterdir()) == before  # unchanged
    assert not list(tmp_path.glob(".partial-*"))


@pytest.mark.parametrize("error", [errno.ENOSPC, errno.EFBIG, errno.EACCES],
                         ids=["disk full", "file too large", "permission"])
def test_write_failure_is_one_line_and_leaves_nothing(tmp_path, capsys, monkeypatch, error):
    """The result fails to be written after the work ran: one line, exit 2, no staging."""
    import anvilwave.analyses.pda as pda

    def full(*_args, **_kwargs):
        raise OSError(error, os.strerror(error))

    monkeypatch.setattr(pda, "write_csv", full)
    record = _record(tmp_path)
    out = tmp_path / "out"
    code = cli.main(["pda", str(record), "--length", "4", "--area", "0.06", "--jc", "0.3",
                     "--out", str(out)])
    _assert_one_line_exit_2(code, capsys, ["--out", os.strerror(error), "not written"], out)


def test_writer_keeps_the_old_result_when_a_write_fails(tmp_path):
    out = tmp_path / "out"
    with ResultWriter(out, command="impact") as w:
        w.part("a.txt").write_text("old")
    with pytest.raises(InputError, match="--out"), ResultWriter(out, command="impact") as w:
        w.part("a.txt").write_text("new")
        raise OSError(errno.ENOSPC, "No space left on device")
    assert (out / "a.txt").read_text() == "old"
    assert not list(tmp_path.glob(".partial-*"))


def _in_child(work) -> tuple[int, str]:
    """Run ``work()`` in a forked child; its exit status and what it wrote to a pipe (the
    child may drop its privileges or lower its limits without touching this process)."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never returns into pytest
        os.close(read)
        code = 1
        try:
            message = work()
            code = 0
        except InputError as exc:
            message, code = str(exc), 2
        except BaseException as exc:  # noqa: BLE001 - reported to the parent
            message = f"{type(exc).__name__}: {exc}"
        finally:
            os.write(write, message.encode()[:4000])
            os._exit(code)
    os.close(write)
    with os.fdopen(read) as pipe:
        text = pipe.read()
    return os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]), text


@pytest.mark.skipif(not hasattr(os, "fork"), reason="forks a child")
@pytest.mark.parametrize("case", ["read-only folder", "folder that cannot be looked into"])
def test_a_read_only_output_folder_is_refused_before_any_work(case):
    """An output location the user may not write (a 0555 folder), or one below a folder the
    user may not even look into (0700, another owner): ``check_output``, which every command
    calls before its work, refuses it with one line naming --out. As root the child drops to
    'nobody', for whom the kernel enforces the modes."""
    import shutil
    import tempfile

    top = Path(tempfile.mkdtemp())  # /tmp: traversable by everyone, unlike pytest's tree
    try:
        top.chmod(0o755)
        locked = top / "locked"
        locked.mkdir()
        locked.chmod(0o555 if case == "read-only folder" else 0o700)
        target = locked / "res" if case == "read-only folder" else locked / "inner" / "res"

        def work():
            if os.geteuid() == 0:
                os.setgid(65534)
                os.setuid(65534)
            check_output(target, "impact")
            return "accepted"

        code, text = _in_child(work)
        locked.chmod(0o755)
        assert code == 2, text
        assert "--out" in text and "cannot be written" in text and "\n" not in text, text
        assert list(locked.iterdir()) == []
    finally:
        shutil.rmtree(top, ignore_errors=True)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="forks a child")
def test_a_full_disk_is_a_clean_stop_and_keeps_the_old_result(tmp_path):
    """A real write limit (RLIMIT_FSIZE, the kernel's 'File too large', as a full quota gives)
    hit while a result is written: one line naming --out, the old result kept, no staging."""
    import resource

    out = tmp_path / "out"
    with ResultWriter(out, command="impact") as w:
        w.part("impact.csv").write_text("old\n")

    def work():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # the kernel then returns EFBIG
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
        with ResultWriter(out, command="impact") as w:
            w.part("impact.csv").write_bytes(b"new\n" * 10_000)
        return "written"

    code, text = _in_child(work)
    assert code == 2, text
    assert "--out" in text and os.strerror(errno.EFBIG) in text and "not written" in text, text
    assert (out / "impact.csv").read_text() == "old\n"
    assert not list(tmp_path.glob(".partial-*"))


def test_force_replaces_another_commands_result_whole(tmp_path, capsys):
    """``--force`` lets ``pda`` write into a folder holding a ``drive`` result: the folder then
    holds the pda result only (marker, files), none of the drive's files."""
    record = _record(tmp_path)
    out = tmp_path / "res"
    out.mkdir()
    (out / MARKER).write_text(json.dumps({"command": "drive"}))
    (out / "driveability.csv").write_text("depth\n")
    (out / "time_series").mkdir()
    args = ["pda", str(record), "--length", "4", "--area", "0.06", "--jc", "0.3", "--out",
            str(out)]
    assert cli.main(args) == 2 and "--force" in capsys.readouterr().err
    assert cli.main(args + ["--force"]) == 0
    assert result_command(out) == "pda"
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [MARKER, "inputs", "inputs.json", "pda.csv", "pda.json", "pda.png"])
    assert not list(tmp_path.glob(".partial-*"))
    assert oct(out.stat().st_mode & 0o777) == oct(0o777 & ~_umask())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_a_rerun_replaces_its_result_whole(tmp_path):
    """A result folder written again holds the new result only: a file the earlier run wrote
    and this one does not (a time series of another depth, say) is gone."""
    out = tmp_path / "out"
    with ResultWriter(out, command="drive") as w:
        w.part("time_series_10m.csv").write_text("a")
        w.part("driveability.csv").write_text("old")
    with ResultWriter(out, command="drive") as w:
        w.part("driveability.csv").write_text("new")
    assert sorted(p.name for p in out.iterdir()) == [MARKER, "driveability.csv"]
    assert (out / "driveability.csv").read_text() == "new"
    assert not list(tmp_path.glob(".partial-*"))


def test_stale_staging_of_a_dead_run_is_removed(tmp_path):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f".partial-{dead.pid}-abc"
    (stale / "x").mkdir(parents=True)
    mine = tmp_path / f".partial-{os.getpid()}-live"
    mine.mkdir()
    with ResultWriter(tmp_path / "out", command="impact") as w:
        w.part("a.txt").write_text("a")
    assert not stale.exists() and mine.exists()  # a live process's staging is left alone


def test_native_build_failure_is_one_line(tmp_path, capsys, monkeypatch):
    def fails(*_args, **_kwargs):
        raise NativeBuildError("cc: error: unrecognized option\ncompilation terminated.")

    monkeypatch.setattr(cli.api, "build_fmus", fails)
    system = _system(tmp_path)
    out = tmp_path / "fmus"
    code = cli.main(["build-fmus", str(system), "--out", str(out)])
    _assert_one_line_exit_2(code, capsys, ["system.toml", "native anvil FMU",
                                           "--python-anvil"], out)


def test_ctrl_c_is_one_line(tmp_path, capsys, monkeypatch):
    def interrupted(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli.api, "pda", interrupted)
    record = _record(tmp_path)
    code = cli.main(["pda", str(record), "--length", "4", "--area", "0.06", "--jc", "0.3",
                     "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip()
    assert code == 130 and err == "anvilwave: interrupted"


def test_match_zones_beyond_the_segments_is_refused(tmp_path):
    from anvilwave.config.budget import check_match_budget

    with pytest.raises(InputError, match="--zones: 100000 zones on a pile of 20 segments"):
        check_match_budget(100000, 20, 5000, 2000)
    with pytest.raises(InputError, match=r"--zones: 300 zones need about .* forward runs"):
        check_match_budget(300, 4000, 20000, 2000)
    # the estimate (evaluations x cost per run, computed, not timed) stays below a minute
    assert check_match_budget(3, 200, 4000, 2000)["wall_time [s]"] < 60.0


def test_compare_pda_record_shorter_than_2l_over_c(tmp_path, capsys, monkeypatch):
    import anvilwave.analyses.pda as pda

    monkeypatch.setattr(pda, "compute_anvil_modes", None)  # never reached
    root = Path(__file__).resolve().parents[1]
    text = (root / "anvilwave" / "examples" / "table1.toml").read_text().replace(
        'file = "anvils/xl8.toml"', f'file = "{root}/anvilwave/examples/anvils/xl8.toml"')
    system = tmp_path / "t1.toml"
    system.write_text(text)
    record = _record(tmp_path, n=100, dt=1e-4)  # 10 ms < 2L/c = 30 ms
    out = tmp_path / "out"
    code = cli.main(["compare-pda", str(record), str(system), "--out", str(out)])
    _assert_one_line_exit_2(code, capsys, ["record.csv", "time [s]", "2L/c"], out)


# ------------------------------------------------------------------------------------ PDA
def _intact_record(noise: float, seed: int = 3):
    """A uniform free pile without soil, by characteristics: the pulse and its toe
    reflection, 2 % white noise of the peak on force and velocity."""
    length, c, area, e = 40.0, 5172.0, 0.1, 2.1e11
    z = e * area / c
    dt = 0.2 / c
    n = int(3 * 2 * length / c / dt)
    t = np.arange(n) * dt
    pulse = lambda s: np.where((s > 0) & (s < 2e-3), np.sin(np.pi * s / 2e-3) ** 2, 0.0)  # noqa: E731
    p = 8e6
    wd = p * pulse(t - 1e-3)
    wu = -p * pulse(t - 1e-3 - 2 * length / c)  # free toe: the wave back in tension
    f, v = wd + wu, (wd - wu) / z
    rng = np.random.default_rng(seed)
    f = f + noise * p * rng.standard_normal(n)
    v = v + noise * (p / z) * rng.standard_normal(n)
    return t, f, v, dict(area=area, elastic_modulus=e, wave_speed=c,
                         length_below_gauges=length, case_damping=0.0)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_bta_of_an_intact_pile_with_noise(seed):
    t, f, v, kw = _intact_record(0.02, seed)
    assert case_method(t, f, v, **kw).bta >= 0.95
    # unfiltered, the noise reads as damage
    assert case_method(t, f, v, bta_cutoff=None, **kw).bta < 0.95


def test_peak_on_the_first_sample():
    s = np.array([10.0, 8.0, 6.0, 7.0, 3.0, 1.0])
    assert first_peak_index(s) == 0
    t, f, v, kw = _intact_record(0.0)
    i = int(np.argmax(f))
    r = case_method(t[i:], f[i:], v[i:], **kw)  # the record starts at the impact peak
    assert r.t1 == pytest.approx(t[i]) and math.isfinite(r.rtl)


# ---------------------------------------------------------------------- killed runs
def _running(pid: int) -> bool:
    """Whether a process runs (exists and is not a zombie waiting for its reaper)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state != "Z"


def _running_after(pids: list[int], seconds: float) -> list[int]:
    """The processes of ``pids`` still running ``seconds`` [s] from now (polled: a loaded
    machine may take a moment to deliver the signals)."""
    deadline = time.monotonic() + seconds
    while True:
        alive = [p for p in pids if _running(p)]
        if not alive or time.monotonic() > deadline:
            return alive
        time.sleep(0.1)


def _children(pid: int) -> list[int]:
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                stat = (d / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                out.append(int(d.name))
    return out


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_killed_drive_leaves_no_worker_and_the_rerun_no_staging(tmp_path):
    system = _system(tmp_path, "[driveability]\nstart = 1.0\nstop = 10.0\nstep = 0.01\n"
                               "blows_per_depth = 5\n")
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "anvilwave", "drive", str(system), "--out", str(out),
           "--workers", "2"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers: list[int] = []
    for _ in range(1200):  # until its two workers run (startup and compilation first)
        workers = _children(proc.pid)
        if len(workers) >= 2 or proc.poll() is not None:
            break
        time.sleep(0.1)
    assert proc.poll() is None and len(workers) >= 2, "the drive ended before its workers ran"
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert _running_after(workers, 5.0) == []
    # the writer of the rerun removes a staging folder the killed run left
    remove_stale_staging(tmp_path)
    assert not list(tmp_path.glob(".partial-*"))


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_text().replace("\0", " ")
    except OSError:
        return ""


def _descendants(pid: int) -> list[int]:
    out, todo = [], [pid]
    while todo:
        kids = _children(todo.pop())
        out += kids
        todo += kids
    return out


def _start_batch(tmp_path: Path, **popen) -> subprocess.Popen:
    """``anvilwave batch`` of a tiny 9-case campaign on 2 workers, started in a process."""
    from .test_campaign import write_campaign

    path = write_campaign(tmp_path / "c", positions=(("P1", 8.0), ("P2", 9.0), ("P3", 9.5)))
    cmd = [sys.executable, "-m", "anvilwave", "batch", str(path), "--out",
           str(tmp_path / "campaign_out"), "--workers", "2"]
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, **popen)


def _batch_workers(pid: int) -> list[int]:
    """The LocalCluster's worker processes below ``pid`` (multiprocessing spawn)."""
    return [p for p in _descendants(pid) if "spawn_main" in _cmdline(p)]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_killed_batch_leaves_no_worker_and_no_staging(tmp_path):
    """``batch`` on its LocalCluster (2 worker processes) killed by SIGKILL while the cases
    run: 5 s later no process of it runs and no staging file or folder is left."""
    proc = _start_batch(tmp_path, stderr=subprocess.DEVNULL)
    for _ in range(1800):  # until both workers run (startup of the cluster first)
        if len(_batch_workers(proc.pid)) >= 2 or proc.poll() is not None:
            break
        time.sleep(0.1)
    assert proc.poll() is None and len(_batch_workers(proc.pid)) >= 2, \
        "the batch ended before its workers ran"
    family = _descendants(proc.pid)  # the workers and multiprocessing's resource tracker
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert _running_after(family, 5.0) == []
    left = [p for p in tmp_path.rglob("*") if p.name.startswith((".partial-", ".tmp"))
            or p.suffix == ".partial"]
    assert left == []


# ---------------------------------------------------------------------- the modal cache
def test_a_cache_entry_with_scaled_frequencies_is_computed_again(tmp_path, monkeypatch):
    """An entry valid as a file but holding another anvil's frequencies (scaled by 0.8) or
    mass is found by the checks on reading, warned about, computed again and replaced."""
    import dataclasses

    import anvilwave.config.cache as cache
    from anvilwave.anvil_rom.fem.geometry import STEEL, AnvilSpec, Interfaces

    monkeypatch.setenv(cache.ENVIRONMENT_VARIABLE, str(tmp_path / "cache"))
    spec = AnvilSpec(name="disc", material=STEEL,
                     outline=np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.3], [0.0, 0.3]]),
                     interfaces=Interfaces(0.2, 0.4, 0.1), mesh_size=0.06, fmax=10000.0)
    clean = cache.cached_modal_data(spec)
    assert cache.modal_data_mismatch(clean, spec, 10000.0) is None
    (entry,) = (tmp_path / "cache").glob("*.npz")
    k = cache._sampled_mode_index(clean.frequencies)
    assert k is not None
    mixed = clean.participation_ram.copy()
    mixed[k] = 0.5 * (mixed[k] + mixed[k - 1])
    for bad in (dataclasses.replace(clean, frequencies=clean.frequencies * 0.8),
                dataclasses.replace(clean, frequencies=clean.frequencies * (1.0 + 1e-6)),
                dataclasses.replace(clean, total_mass=clean.total_mass * 1.21,
                                    participation_gravity=clean.participation_gravity * 1.1),
                # modes no longer mass-normalised (scaled by 1.001), or mixed with a neighbour
                dataclasses.replace(clean, participation_ram=clean.participation_ram * 1.001,
                                    participation_pile=clean.participation_pile * 1.001),
                dataclasses.replace(clean, participation_ram=mixed)):
        cache._store(bad, entry)
        with pytest.warns(UserWarning, match="does not match its anvil"):
            again = cache.cached_modal_data(spec)
        np.testing.assert_allclose(again.frequencies, clean.frequencies, rtol=1e-9)
        assert again.total_mass == pytest.approx(clean.total_mass, rel=1e-12)
        assert cache.modal_data_mismatch(cache.load_modal_data(entry), spec, 10000.0) is None


def test_a_corrupted_table1_cache_entry_gives_the_table1_peaks(tmp_path, monkeypatch,
                                                               modal_cache):
    """Table 1's cached modal data with its frequencies scaled by 0.8 (a file valid as such,
    which once gave peaks of 0.0 MN) is found on reading, warned about and computed again:
    the blow then has Table 1's stored peak anvil-pile force (tests/data/example_numbers.json,
    the same 1e-6 as tests/test_example_numbers) and the clean run's ram-anvil peak."""
    import dataclasses
    import shutil

    import anvilwave.config.cache as cache
    from anvilwave.anvil_rom.fem.modalfile import load_modal_data
    from anvilwave.config.system import load_system
    from anvilwave.engine.direct import build_engine

    from .example_numbers import EXAMPLES, _short

    def peaks():
        blow = build_engine(_short(load_system(EXAMPLES / "table1.toml"))).run()[0]
        return (float(blow.columns["anvil_pile_force [N]"].max()),
                float(blow.columns["ram_anvil_force [N]"].max()))

    clean = peaks()  # the session cache: computed there once
    private = tmp_path / "cache"
    private.mkdir()
    for entry in modal_cache.glob("*" + cache.SUFFIX):
        shutil.copy2(entry, private)
    monkeypatch.setenv(cache.ENVIRONMENT_VARIABLE, str(private))
    corrupted = 0
    for entry in private.glob("*" + cache.SUFFIX):
        if entry.name.endswith(cache.CHAIN_SUFFIX):
            continue
        try:
            data = load_modal_data(entry)
        except InputError:
            continue
        cache._store(dataclasses.replace(data, frequencies=data.frequencies * 0.8), entry)
        corrupted += 1
    assert corrupted >= 1
    with pytest.warns(UserWarning, match="does not match its anvil"):
        again = peaks()
    stored = json.loads((Path(__file__).parent / "data" / "example_numbers.json").read_text())
    assert again[0] == pytest.approx(stored["blow/table1.toml"], rel=1e-6)
    assert again == pytest.approx(clean, rel=1e-12)


# ------------------------------------------------------------------------------ batch
def test_batch_with_a_missing_hammer_anvil_leaves_no_folder(tmp_path, capsys):
    """The campaign's hammer anvil file is missing: one line, exit 2, and the campaign folder
    this run would have made is not left half-made."""
    from .test_campaign import write_campaign

    path = write_campaign(tmp_path / "c")
    text = path.read_text().replace(
        "[axes]", '[axes]\n[[axes.hammers]]\nname = "H"\ndatabase = "illustrative_s2"\n'
                  '[axes.hammers.anvil]\nfile = "missing_anvil.toml"\n', 1)
    path.write_text(text)
    out = tmp_path / "campaign_out"
    code = cli.main(["batch", str(path), "--out", str(out), "--workers", "1"])
    _assert_one_line_exit_2(code, capsys, ["missing_anvil.toml"], out)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_on_drive_is_one_line_and_leaves_no_worker(tmp_path):
    system = _system(tmp_path, "[driveability]\nstart = 1.0\nstop = 10.0\nstep = 0.01\n"
                               "blows_per_depth = 5\n")
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "anvilwave", "drive", str(system), "--out", str(out),
           "--workers", "2"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True, text=True)
    workers: list[int] = []
    for _ in range(1200):
        workers = _children(proc.pid)
        if len(workers) >= 2 or proc.poll() is not None:
            break
        time.sleep(0.1)
    assert proc.poll() is None and len(workers) >= 2
    os.killpg(proc.pid, signal.SIGINT)  # as the terminal sends Ctrl-C: to the whole group
    _, err = proc.communicate(timeout=120)
    lines = [x for x in err.replace("\r", "\n").splitlines() if x.strip()]
    assert proc.returncode == 130 and "Traceback" not in err, err
    assert lines[-1] == "anvilwave: interrupted"
    assert [x for x in lines if x.startswith("anvilwave")] == ["anvilwave: interrupted"]
    assert _running_after(workers, 5.0) == []
    assert not out.exists() and not list(tmp_path.glob(".partial-*"))


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_on_batch_is_one_line_and_leaves_no_worker(tmp_path):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) while the LocalCluster's
    workers run the cases (its progress bar is up): one line, exit 130, no worker traceback,
    no worker left 5 s later. (A Ctrl-C in the seconds while the cluster starts is not
    delivered: the numerical libraries' threads take it, ignored; docs/batch.md says so.)"""
    import threading

    proc = _start_batch(tmp_path, stderr=subprocess.PIPE, start_new_session=True, text=True)
    err_parts: list[str] = []
    reader = threading.Thread(target=lambda: err_parts.extend(iter(
        lambda: proc.stderr.read(1), "")), daemon=True)
    reader.start()
    for _ in range(1800):  # until the bar is up: the cluster started, the cases run
        if "campaign tiny:" in "".join(err_parts) or proc.poll() is not None:
            break
        time.sleep(0.1)
    assert proc.poll() is None, "the batch ended before its cases ran"
    family = _descendants(proc.pid)
    assert len(_batch_workers(proc.pid)) >= 2
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(timeout=120)
    reader.join(timeout=10)
    err = "".join(err_parts)
    lines = [x for x in err.replace("\r", "\n").splitlines() if x.strip()]
    assert proc.returncode == 130 and "Traceback" not in err and "KeyboardInterrupt" not in err, err
    assert [x for x in lines if x.startswith("anvilwave")] == ["anvilwave: interrupted"], err
    assert _running_after(family, 5.0) == []


def test_drive_on_workers_equals_drive_in_process(tmp_path):
    """The depths run on 2 worker processes (in chunks, in order) give the rows of the
    in-process run to the bit: the same kernels on the same inputs."""
    import anvilwave
    from anvilwave.config.system import load_system

    cfg = load_system(_system(tmp_path, "[driveability]\nstart = 1.0\nstop = 10.0\nstep = 0.5\n"
                                        "blows_per_depth = 3\n"))
    serial = anvilwave.drive(cfg, workers=1)
    parallel = anvilwave.drive(cfg, workers=2)
    assert len(serial.rows) == len(parallel.rows) == 19
    for a, b in zip(serial.rows, parallel.rows, strict=True):
        assert a.keys() == b.keys()
        for key in a:
            assert a[key] == b[key] or (a[key] != a[key] and b[key] != b[key]), key



@pytest.mark.parametrize("case, argv, words", EVERY_COMMAND_CASES,
                         ids=[c[0] for c in EVERY_COMMAND_CASES])
def test_every_command_refuses_a_missing_input(tmp_path, capsys, case, argv, words):
    """Each command given an input file that is not there (or a negative pile length): one
    line naming it, exit 2, no output folder."""
    out = tmp_path / "out"
    code = cli.main([*argv(tmp_path), "--out", str(out)])
    _assert_one_line_exit_2(code, capsys, words, out)
