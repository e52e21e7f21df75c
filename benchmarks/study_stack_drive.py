"""What the anvil ring and the seat friction change in the XL monopile's drive: pile-head force
and blow count, for the docs: docs/data/stack_drive.json.

Run: python benchmarks/study_stack_drive.py [--docs] (about a minute on 2 cores)

The system is anvilwave/examples/xl_monopile_drive.toml (the paper's Table 1 hammer, anvil and
pile in an illustrative North Sea profile) with its ``[anvil] file`` replaced by
``[[anvil.bodies]]``: the anvil alone (the file's system to the bit), then the anvil and the
illustrative ring anvilwave/examples/anvils/xl8_ring.toml with the seat friction coefficient
mu 0, 0.1 and 0.3 (the stack's defaults otherwise: eight seat rings, three pile rings on the 1D
head, the ram face in six annuli), and the ring at mu 0 and 0.3 with the options of
anvilwave/examples/table1_ring.toml (:data:`TUBE_CASES`: the seat in 32 rings, the pile rings
on the FE tube head; the options the ROM stack meets the FEA stack with). Every case runs
through ``anvilwave.drive`` (the engine's compiled loop):

* the blow at ``SERIES_DEPTH`` (the drive's time series, one blow from rest): the pile-head
  force low-passed at 5 kHz, its peak, the peak's time after the ram's first contact, its
  10-90 % rise time (to 90 % of that peak: where the peak moves to a later hump, so does the
  rise's end), and its third-octave band levels to 4 kHz against the anvil alone's (the
  largest difference and its band);
* the blow count at ``DEPTHS`` (one blow from rest per depth).

Also measured (printed and kept in the file's values, not in the docs): the wall time of one
Table 1 ring blow in the compiled loop against the per-step Python runner
(:func:`anvilwave.analyses.stack_blow.run_stack_blow`), in one run, as a ratio.
"""

from __future__ import annotations

import argparse
import dataclasses
import tempfile
import time
from pathlib import Path

import numpy as np
from doc_data import system_inputs, write_doc_data

import anvilwave
from anvilwave.analyses.compare import lowpass
from anvilwave.analyses.stack_blow import run_stack_blow, stack_unit
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.pile.post.spectra import band_numbers_between, third_octave_band_energies

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
SYSTEM = EXAMPLES / "xl_monopile_drive.toml"
RING = EXAMPLES / "anvils" / "xl8_ring.toml"
CASES = {"anvil alone": None, "ring, mu 0": 0.0, "ring, mu 0.1": 0.1, "ring, mu 0.3": 0.3}
"""Case -> the seat friction coefficient (None: no ring)."""
TUBE_CASES = {"ring, mu 0, tube head": 0.0, "ring, mu 0.3, tube head": 0.3}
"""Case -> the seat friction coefficient, with table1_ring.toml's stack options
(:data:`TUBE_OPTIONS`)."""
TUBE_OPTIONS = ('pile_head = "tube"\n', "seat_rings = 32\n")
"""The ``[anvil]`` and the ring body's lines of table1_ring.toml's stack."""
DEPTHS = (10.0, 20.0, 30.0)
"""[m] tip depths of the blow counts."""
SERIES_DEPTH = 20.0
"""[m] the tip depth of the pile-head force compared."""
CUTOFF = 5000.0  # [Hz] the low-pass of the peak and the rise (the ROM's fmax)
TOP_BAND = 4000.0  # [Hz] the highest band compared


def stack_system(folder: Path, mu: float | None, name: str = "system.toml",
                 tube: bool = False) -> Path:
    """SYSTEM with ``[[anvil.bodies]]``: the anvil, and with ``mu`` the ring at that seat
    friction (``tube``: with :data:`TUBE_OPTIONS`); its other files named by absolute path,
    written into ``folder``."""
    text = SYSTEM.read_text()
    anvil = 'file = "anvils/xl8.toml"\n'
    assert text.count(anvil) == 1
    bodies = f'[[anvil.bodies]]\nfile = "{EXAMPLES / "anvils" / "xl8.toml"}"\n'
    if mu is not None:
        bodies += f'[[anvil.bodies]]\nfile = "{RING}"\nseat_friction = {mu!r}\n'
    if tube:
        bodies = TUBE_OPTIONS[0] + bodies + TUBE_OPTIONS[1]
    text = text.replace(anvil, "").replace('cpt = "soil/', f'cpt = "{EXAMPLES / "soil"}/')
    head, tail = text.split("[anvil.classic]", 1)
    path = Path(folder) / name
    path.write_text(f"{head}{bodies}\n[anvil.classic]{tail}")
    return path


def first_crossing(t, f, level):
    """First time [s] ``f`` exceeds ``level`` (linear interpolation)."""
    i = int(np.argmax(f > level))
    return float(t[i - 1] + (level - f[i - 1]) / (f[i] - f[i - 1]) * (t[i] - t[i - 1]))


def head_figures(columns: dict) -> dict:
    """Peak, 10-90 % rise and band levels of a blow's pile-head force."""
    t = columns["time [s]"]
    force = columns["anvil_pile_force [N]"]
    contact = float(t[int(np.argmax(columns["ram_anvil_force [N]"] > 0.0))])
    head = lowpass(t, force, CUTOFF)
    rise = head - head[0]
    peak = float(rise.max())
    bands = third_octave_band_energies(force - force[0], float(t[1] - t[0]),
                                       band_numbers_between(8.9, TOP_BAND))
    return {"peak_pile_head_force [N]": float(head.max()),
            "peak_time [s]": float(t[int(np.argmax(head))]) - contact,
            "rise_10_90 [s]": first_crossing(t, rise, 0.9 * peak)
            - first_crossing(t, rise, 0.1 * peak),
            "band_centre [Hz]": [float(x) for x in bands.centre_frequency],
            "band_lower_edge [Hz]": [float(x) for x in bands.lower_frequency],
            "band_level [dB]": [float(x) for x in bands.level],
            "valid_from [Hz]": float(bands.valid_range[0])}


def run_case(path: Path) -> dict:
    """The drive of one case at DEPTHS and its blow at SERIES_DEPTH."""
    cfg = load_system(path)
    settings = dataclasses.replace(cfg.drive, depths=np.array(DEPTHS),
                                   time_series_depths=(SERIES_DEPTH,))
    result = anvilwave.drive(dataclasses.replace(cfg, drive=settings), workers=1)
    return {"blow_count [1/m]": {f"{r['depth [m]']:g}": float(r["blow_count [1/m]"])
                                 for r in result.rows},
            **head_figures(result.time_series[SERIES_DEPTH])}


def band_change(row: dict, reference: dict) -> tuple[float, float]:
    """The largest band-level change [dB] against ``reference`` to TOP_BAND, and its band."""
    levels, ref = np.array(row["band_level [dB]"]), np.array(reference["band_level [dB]"])
    centre, lower = np.array(row["band_centre [Hz]"]), np.array(row["band_lower_edge [Hz]"])
    inside = (lower >= row["valid_from [Hz]"]) & (centre <= TOP_BAND)
    change = np.where(inside, levels - ref, 0.0)
    worst = int(np.argmax(np.abs(change)))
    return float(change[worst]), float(centre[worst])


def docs_tables(values: dict) -> tuple[dict, dict]:
    """The docs' table and quoted numbers from the values (tests/test_doc_tables.py)."""
    runs = values["runs"]
    alone = runs["anvil alone"]
    rows = []
    for name, row in runs.items():
        change, at = band_change(row, alone) if name != "anvil alone" else (None, None)
        rows.append([name, row["peak_pile_head_force [N]"],
                     row["peak_pile_head_force [N]"] / alone["peak_pile_head_force [N]"] - 1.0,
                     row["peak_time [s]"], row["rise_10_90 [s]"], change, at,
                     *(row["blow_count [1/m]"][f"{d:g}"] for d in DEPTHS)])
    table = {"columns": ["case", f"pile-head peak ({SERIES_DEPTH:g} m)", "against the anvil",
                         "peak after first contact", "rise 10-90 %",
                         "largest band change to 4 kHz [dB]", "at [Hz]",
                         *(f"blows/m at {d:g} m" for d in DEPTHS)],
             "formats": ["", "MN0", "pct+", "ms2", "ms2", "dB+", "int",
                         *("per_m0" for _ in DEPTHS)],
             "rows": rows}
    counts = {name: np.array([row["blow_count [1/m]"][f"{d:g}"] for d in DEPTHS])
              for name, row in runs.items()}
    changes = [counts[name] / counts["anvil alone"] - 1.0 for name in runs
               if name != "anvil alone"]
    peak = {name: row["peak_pile_head_force [N]"] / alone["peak_pile_head_force [N]"] - 1.0
            for name, row in runs.items()}
    subs = {"peak_change_mu0": [peak["ring, mu 0"], "pct+"],
            "peak_change_mu03": [peak["ring, mu 0.3"], "pct+"],
            **{f"peak_change_tube_mu{m}": [peak[name], "pct+"]
               for m, name in zip(("0", "03"), TUBE_CASES, strict=True) if name in peak},
            "blow_count_change_max": [float(np.max(np.abs(changes))), "pct"]}
    return {"cases": table}, subs


def loop_speed() -> dict:
    """One Table 1 ring blow (mu 0.2): the compiled loop's wall time and the Python runner's,
    in one run (the engine compiled and warm first)."""
    with tempfile.TemporaryDirectory() as tmp:
        head, tail = (EXAMPLES / "table1.toml").read_text().replace(
            'file = "anvils/xl8.toml"\n', "", 1).split("[pile]\n", 1)
        path = Path(tmp) / "table1_ring.toml"
        path.write_text(f'{head}[[anvil.bodies]]\nfile = "{EXAMPLES / "anvils" / "xl8.toml"}"\n'
                        f'[[anvil.bodies]]\nfile = "{RING}"\nseat_friction = 0.2\n\n[pile]\n'
                        f"{tail}")
        cfg = load_system(path)
    engine = build_engine(cfg)
    engine.blow(record=False)
    compiled = min(engine.blow(record=False).wall_time for _ in range(3))
    st = cfg.anvil.stack
    unit = stack_unit(cfg, st.ring, seat_friction=st.seat_friction)
    run_stack_blow(cfg, unit, duration=1e-3)
    start = time.perf_counter()
    run_stack_blow(cfg, unit)
    python = time.perf_counter() - start
    return {"compiled_loop [s]": compiled, "python_runner [s]": python,
            "ratio [-]": python / compiled}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--docs", action="store_true", help="write docs/data/stack_drive.json")
    args = parser.parse_args(argv)
    runs = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, mu, tube in [*((n, m, False) for n, m in CASES.items()),
                               *((n, m, True) for n, m in TUBE_CASES.items())]:
            start = time.perf_counter()
            runs[name] = run_case(stack_system(Path(tmp), mu, f"{len(runs)}.toml", tube))
            print(f"{name}: {time.perf_counter() - start:.0f} s", flush=True)
    values = {"runs": runs, "depths [m]": list(DEPTHS), "series_depth [m]": SERIES_DEPTH,
              "loop_speed": loop_speed()}
    tables, subs = docs_tables(values)
    for row in tables["cases"]["rows"]:
        change = "" if row[5] is None else f"{row[5]:+6.2f} dB @{row[6]:5.0f} Hz"
        counts = " ".join(f"{c:6.1f}" for c in row[7:])
        print(f"{row[0]:24s} {row[1] / 1e6:7.1f} MN {row[2] * 100:+6.2f} % peak at "
              f"{row[3] * 1e3:5.2f} ms, rise {row[4] * 1e3:5.2f} ms {change:18s} {counts}")
    s = values["loop_speed"]
    print(f"one Table 1 ring blow: compiled loop {s['compiled_loop [s]'] * 1e3:.1f} ms, "
          f"Python runner {s['python_runner [s]'] * 1e3:.0f} ms ({s['ratio [-]']:.0f}x)")
    if args.docs:
        write_doc_data("stack_drive", about="The anvil ring and its seat friction in the XL "
                       "monopile's drive (benchmarks/study_stack_drive.py)",
                       inputs=[*system_inputs(SYSTEM), RING, EXAMPLES / "table1.toml"],
                       tables=tables, substitutions=subs, values=values)


if __name__ == "__main__":
    main()
