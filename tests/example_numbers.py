"""One stored number per example file: the cases of tests/test_example_numbers.py and of
``python -m tests.regenerate_example_numbers`` (which rewrites tests/data/example_numbers.json).

Each case is a short, deterministic run of one example file:

* ``blow/<system>.toml``: the peak anvil-pile force [N] of a blow cut to BLOW_DURATION with the
  direct engine (the file's time step, segments and models; one blow);
* ``drive/<system>.toml`` (files with a ``[driveability]`` table) and ``campaign/<file>.toml``
  (the campaign's first case): the blow count [1/m] of one tip depth (the middle depth of the
  file's schedule), a full blow window as the file sets it;
* ``pda/<record>.csv``: the Case method's RMX [N] (Jc 0.4, 78 m below the gauges, the steel
  area of examples/table1.toml at the gauges: the record's own system);
* ``script/make_synthetic_pda_record.py``: the peak force [N] of the converted record the
  script writes, run with a short simulation into a temporary folder;
* ``script/script_api.py``: its first printed pile peak [MN] (3500 kJ, ROM anvil), checked by
  tests/test_system_layer.py (the script already runs there).

The modal data come from the modal-data cache (the test session's, see conftest), so a case
costs its time stepping only once another test (or case) has computed an anvil's modes.
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib.util
import io
import json
import math
import shutil
import tempfile
from pathlib import Path

import numpy as np

from .conftest import EXAMPLES, example_systems

DATA = Path(__file__).resolve().parent / "data" / "example_numbers.json"
"""The stored numbers (one JSON object: case name -> number)."""
BLOW_DURATION = 0.004
"""[s] short blows: the first anvil-pile force peak of every example (8 m anvils and smaller,
c = 5172 m/s) lies within the first 3 ms."""
PDA_AREA = math.pi * (8.0 - 0.14) * 0.14
"""[m^2] steel area at the gauges of examples/table1.toml (the synthetic records' system)."""
PDA_LENGTH = 78.0
"""[m] below the gauges (80 m pile, gauges 2 m below the head)."""
PDA_JC = 0.4
"""[-] Case damping of sand."""
PDA_RECORDS = ("pda_raw_synthetic.csv", "pda_record_synthetic.csv")
CAMPAIGNS = tuple(sorted(p.name for p in EXAMPLES.glob("campaign_*.toml")))
SCRIPT_API_FIRST_PEAK = "script/script_api.py"
"""The case that tests/test_system_layer.py checks on the script's printed table."""


def load_numbers() -> dict[str, float]:
    return json.loads(DATA.read_text()) if DATA.exists() else {}


def _short(cfg):
    return dataclasses.replace(cfg, duration=BLOW_DURATION, blows=1, output_interval=None)


def blow_peak(name: str) -> float:
    from anvilwave.config.system import load_system
    from anvilwave.engine.direct import build_engine

    blow = build_engine(_short(load_system(EXAMPLES / name))).run()[0]
    return float(blow.columns["anvil_pile_force [N]"].max())


def one_depth_blow_count(cfg) -> float:
    import anvilwave

    depths = np.asarray(cfg.drive.depths, dtype=float)
    depth = float(depths[depths.size // 2])
    settings = dataclasses.replace(cfg.drive, depths=np.array([depth]), time_series_depths=())
    result = anvilwave.drive(dataclasses.replace(cfg, drive=settings), workers=1)
    (row,) = result.rows
    assert row["depth [m]"] == depth
    return float(row["blow_count [1/m]"])


def drive_blow_count(name: str) -> float:
    from anvilwave.config.system import load_system

    return one_depth_blow_count(load_system(EXAMPLES / name))


def campaign_blow_count(name: str) -> float:
    from anvilwave.analyses.batch import load_campaign
    from anvilwave.config.system import load_system

    case = load_campaign(EXAMPLES / name).cases[0]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "system.toml"
        path.write_text(case.system_text)
        cfg = load_system(path)
        return one_depth_blow_count(cfg)


def pda_rmx(name: str) -> float:
    import anvilwave

    result = anvilwave.pda(EXAMPLES / name, length=PDA_LENGTH, area=PDA_AREA, jc=PDA_JC)
    return float(result.summary["RMX [N]"])


def synthetic_pda_record_peak() -> float:
    """examples/make_synthetic_pda_record.py, imported and run with a 12 ms simulation (the
    record ends at the first zero crossing of the velocity after 8 ms) into a temporary
    folder: the peak force of the converted record it writes."""
    spec = importlib.util.spec_from_file_location(
        "make_synthetic_pda_record", EXAMPLES / "make_synthetic_pda_record.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    with tempfile.TemporaryDirectory() as folder:
        script.DURATION, script.END_AFTER = 0.012, 0.008
        script.RAW = Path(folder) / "pda_raw_synthetic.csv"
        script.RECORD = Path(folder) / "pda_record_synthetic.csv"
        with contextlib.redirect_stdout(io.StringIO()) as out:
            script.main()
        assert "peak force" in out.getvalue()
        from anvilwave.analyses.pda import load_record

        record, _, _ = load_record(script.RECORD)
        return float(np.max(record.force))


def script_api_first_peak() -> float:
    """The first pile peak [MN] examples/script_api.py prints (3500 kJ, ROM anvil)."""
    import subprocess
    import sys

    run = subprocess.run([sys.executable, str(EXAMPLES / "script_api.py")], capture_output=True,
                         text=True, timeout=600, check=True)
    return first_printed_peak(run.stdout)


def first_printed_peak(stdout: str) -> float:
    lines = [ln for ln in stdout.splitlines() if ln.strip()]
    return float(lines[1].split()[2])


def has_drive(name: str) -> bool:
    return "[driveability]" in (EXAMPLES / name).read_text()


def cases() -> dict[str, tuple]:
    """Case name -> (function, argument...), in a stable order."""
    out: dict[str, tuple] = {}
    for name in example_systems():
        out[f"blow/{name}"] = (blow_peak, name)
    for name in example_systems():
        if has_drive(name):
            out[f"drive/{name}"] = (drive_blow_count, name)
    for name in CAMPAIGNS:
        out[f"campaign/{name}"] = (campaign_blow_count, name)
    for name in PDA_RECORDS:
        out[f"pda/{name}"] = (pda_rmx, name)
    out["script/make_synthetic_pda_record.py"] = (synthetic_pda_record_peak,)
    out[SCRIPT_API_FIRST_PEAK] = (script_api_first_peak,)
    return out


def compute(case: str) -> float:
    function, *args = cases()[case]
    return function(*args)


def check_soil_script(folder: Path) -> list[str]:
    """Run examples/make_synthetic_campaign_cpts.py on a copy in ``folder``: the names of the
    shipped examples/soil files it does not reproduce byte for byte (none expected)."""
    shutil.copy(EXAMPLES / "make_synthetic_campaign_cpts.py", folder)
    import subprocess
    import sys

    subprocess.run([sys.executable, str(folder / "make_synthetic_campaign_cpts.py")],
                   capture_output=True, text=True, timeout=120, check=True)
    written = sorted((folder / "soil").iterdir())
    assert written, "the script wrote nothing"
    return [p.name for p in written if p.read_bytes() != (EXAMPLES / "soil" / p.name).read_bytes()]
