"""Native (C) anvil FMU vs pythonfmu anvil FMU through fmpy: microseconds per fmi2DoStep.

Run: python benchmarks/bench_native_anvil.py [MODES.npz] [--steps N] [--repeat N]

Builds ``Anvil.fmu`` twice from the same modal data, natively (:mod:`anvilwave.fmu.native_build`)
and
with pythonfmu (:mod:`anvilwave.fmu.fmi_build`), then in ONE process drives each through fmpy's
``FMU2Slave`` (ctypes) on the same blow (a ram toe hitting the anvil, a pile head that
oscillates), after a warm-up (numba compiles the pythonfmu kernels on first use):

- ``doStep``: fmi2DoStep alone, inputs held (the contact forces are evaluated in the step);
- ``exchange``: the master's per-step exchange, fmi2SetReal (4 inputs), fmi2GetReal
  (4 outputs), fmi2DoStep;
- ``raw``: fmi2DoStep called through its bare ctypes function (no fmpy wrapper: no status
  check, no argument conversion), inputs held.

Times are the best of ``--repeat`` runs (the median in brackets); the ratio pythonfmu /
native is printed in the same run. Both go through fmpy, so both include its ctypes cost; for
scale, the last line is the native exchange in the plain C host of the tests
(``tests/c_host/fmi_host.c``, compiled here), without Python in the loop.
The default modal data are those of the tests (s2 anvil, mesh 0.03 m, modes to 20 kHz).
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CONTACTS = {"ram_contact_stiffness": 2.0e10, "pile_contact_stiffness": 3.0e10}  # [N/m]


def _modal_data(path: Path | None):
    from anvilwave.anvil_rom.fem.modalfile import load_modal_data

    if path is not None:
        return load_modal_data(path)
    from anvilwave.anvil_rom.fem.geometry import load_anvil
    from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes

    spec = load_anvil(ROOT / "anvilwave" / "examples" / "anvils" / "s2.toml")
    spec = type(spec)(**{**spec.__dict__, "mesh_size": 0.03})
    return compute_anvil_modes(spec, fmax=20000.0).modal_data


def _inputs(u_top0: float, n: int, h: float) -> np.ndarray:
    t = np.arange(n) * h
    w = 2 * np.pi * 400.0
    return np.column_stack([u_top0 - 1e-6 + 4.0 * t - 1.5e4 * t**2, 4.0 - 3.0e4 * t,
                            2.0e-4 * np.sin(w * t), 2.0e-4 * w * np.cos(w * t)])


def _time(path: Path, inputs: np.ndarray, h: float, repeat: int) -> dict[str, list[float]]:
    """Seconds per step of each loop, one value per run."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(path))
    var = {v.name: v.valueReference for v in md.modelVariables}
    vr_in = [var[n] for n in ("u_ram", "v_ram", "u_pile", "v_pile")]
    vr_out = [var[n] for n in ("F_ram", "F_pile", "u_top", "u_bottom")]
    unzip = extract(str(path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bench")
    fmu.instantiate()
    times: dict[str, list[float]] = {"doStep": [], "exchange": [], "raw": []}
    raw_step = fmu.dll.fmi2DoStep
    try:
        for run in range(repeat + 1):  # run 0 warms up
            fmu.reset()
            fmu.setupExperiment(startTime=0.0)
            fmu.enterInitializationMode()
            fmu.exitInitializationMode()
            rows = [list(map(float, row)) for row in inputs]
            set_real, get_real, do_step = fmu.setReal, fmu.getReal, fmu.doStep
            start = time.perf_counter()
            for n, row in enumerate(rows):
                set_real(vr_in, row)
                get_real(vr_out)
                do_step(n * h, h)
            exchange = time.perf_counter() - start
            set_real(vr_in, rows[0])
            start = time.perf_counter()
            for n in range(len(rows)):
                do_step(n * h, h)
            alone = time.perf_counter() - start
            component = fmu.component
            start = time.perf_counter()
            for n in range(len(rows)):
                raw_step(component, n * h, h, 1)
            raw = time.perf_counter() - start
            if run > 0:
                times["exchange"].append(exchange / len(rows))
                times["doStep"].append(alone / len(rows))
                times["raw"].append(raw / len(rows))
        fmu.terminate()
    finally:
        fmu.freeInstance()
    return times


def _c_host(native: Path, inputs: np.ndarray, h: float, tmp: Path) -> str:
    """The native exchange timed by the C host (its own report line), or why not."""
    from fmpy import read_model_description

    from anvilwave.fmu.native_build import NATIVE_DIR, NativeBuildError, find_compiler

    try:
        compiler = find_compiler()
    except NativeBuildError as exc:
        return f"C host: not run ({exc})"
    exe = tmp / "fmi_host"
    build = subprocess.run([*compiler.split(), "-std=c99", "-O2", "-I", str(NATIVE_DIR), "-o",
                            str(exe), str(ROOT / "tests" / "c_host" / "fmi_host.c"), "-ldl",
                            "-lm"], capture_output=True, text=True)
    if build.returncode != 0:
        return f"C host: does not compile ({build.stderr.strip()})"
    unzip = tmp / "native_unzipped"
    with zipfile.ZipFile(native) as zf:
        zf.extractall(unzip)
    md = read_model_description(str(native))
    var = {v.name: v.valueReference for v in md.modelVariables}
    t0 = [float(x) for x in inputs[0]]
    w = 2 * np.pi * 400.0
    signals = {"u_ram": f"{t0[0]!r},4,-1.5e4,0,0,0", "v_ram": "4,-3e4,0,0,0,0",
               "u_pile": "0,0,0,2e-4,0,400", "v_pile": f"0,0,0,0,{2e-4 * w!r},400"}
    cmd = [str(exe), str(unzip), md.coSimulation.modelIdentifier, md.guid,
           "--inputs", ",".join(str(var[n]) for n in ("u_ram", "v_ram", "u_pile", "v_pile")),
           "--outputs", ",".join(str(var[n]) for n in ("F_ram", "F_pile", "u_top", "u_bottom")),
           "--instances", "1", "--steps", str(len(inputs)), "--step-size", repr(h)]
    for name, signal in signals.items():
        cmd += ["--signal", f"{var[name]}={signal}"]
    run = subprocess.run(cmd, env={}, capture_output=True, text=True)
    found = re.search(r"([0-9.]+) us per instance step", run.stdout)
    if run.returncode != 0 or found is None:
        return f"C host: failed ({run.stdout.strip()} {run.stderr.strip()})"
    return (f"native in the C host (no Python, no ctypes): {float(found.group(1)):.2f} us per "
            "exchange (set inputs, get outputs, fmi2DoStep)")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("modes", nargs="?", type=Path, help="modal-data .npz (default: s2)")
    parser.add_argument("--steps", type=int, default=20000, help="steps per run (20000)")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs per FMU (3)")
    args = parser.parse_args(argv)

    from anvilwave.anvil_rom.fem.modalfile import save_modal_data
    from anvilwave.anvil_rom.rom import ModalAnvil
    from anvilwave.anvil_rom.unit import AnvilUnit, ContactParameters
    from anvilwave.fmu.fmi_build import build_anvil_fmu
    from anvilwave.fmu.native_build import build_native_anvil_fmu

    start = time.perf_counter()
    data = _modal_data(args.modes)
    unit = AnvilUnit(ModalAnvil.from_modal_data(data),
                     ContactParameters(CONTACTS["ram_contact_stiffness"],
                                       CONTACTS["pile_contact_stiffness"]))
    u_top0, _ = unit.rest_on_pile(0.0)
    h = 1e-6
    inputs = _inputs(u_top0, args.steps, h)
    with tempfile.TemporaryDirectory(prefix="bench_native_") as tmp:
        tmp = Path(tmp)
        native = build_native_anvil_fmu(data, tmp / "native", **CONTACTS)
        python = build_anvil_fmu(save_modal_data(data, tmp / "modes.npz"), tmp / "python",
                                 **CONTACTS)
        print(f"Anvil.fmu, {data.n_modes} modes, built natively and with pythonfmu in "
              f"{time.perf_counter() - start:.1f} s (not timed); {args.steps} steps of "
              f"{h:g} s, best of {args.repeat} (median)")
        results = {"native": _time(native, inputs, h, args.repeat),
                   "pythonfmu": _time(python, inputs, h, args.repeat)}
        host = _c_host(native, inputs, h, tmp)
    loops = ("doStep", "exchange", "raw")
    print(f"{'FMU':10s}" + "".join(f"{loop + ' [us]':>20s}" for loop in loops))
    best = {}
    for name, times in results.items():
        best[name] = {k: min(v) for k, v in times.items()}
        cells = [f"{1e6 * min(times[k]):9.2f} ({1e6 * statistics.median(times[k]):7.2f})"
                 for k in loops]
        print(f"{name:10s}" + "".join(f"{cell:>20s}" for cell in cells))
    ratio = {k: best["pythonfmu"][k] / best["native"][k] for k in loops}
    print("ratio pythonfmu / native: " + ", ".join(f"{k} {ratio[k]:.1f}" for k in loops))
    print(host)


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    main()
