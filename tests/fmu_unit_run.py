"""Run one Ram or PileSoil FMU under fmpy on fixed inputs and save its outputs (no anvilwave).

``python fmu_unit_run.py FMU KIND OUT.npy [--import-anvilwave] [--unzipped DIR]``: 400 steps of
10 us, the inputs set, the outputs read, the step taken (the DESIGN.md order). Prints one JSON
line: where the unit's anvilwave code came from (``vendored`` / ``installed``, the
``SOURCE`` of the FMU's ``anvilwave_fmu_<digest>`` package) and the top-level modules of
anvilwave, matplotlib and pythonfmu in the process. Run by tests/test_fmu_portable.py in
Pythons with and without anvilwave; it imports only fmpy and numpy.
"""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

STEPS, STEP = 400, 1e-5
# input: c0 + a sin(2 pi f t) [N] (as tests/test_fmu_c_host.py)
UNITS = {"Ram": ("F_toe", 0.0, ("u_toe", "v_toe")),
         "PileSoil": ("F_head", 3.19e6, ("u_head", "v_head", "F_gauge", "v_gauge"))}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("fmu")
    parser.add_argument("kind", choices=sorted(UNITS))
    parser.add_argument("out")
    parser.add_argument("--import-anvilwave", action="store_true")
    parser.add_argument("--unzipped")
    args = parser.parse_args()
    if args.import_anvilwave:
        import anvilwave  # noqa: F401 - an anvilwave imported before the FMU loads
    md = read_model_description(args.fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    folder = args.unzipped or extract(args.fmu)
    name, offset, outputs = UNITS[args.kind]
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=folder, instanceName="portable",
                    modelIdentifier=md.coSimulation.modelIdentifier)
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    result = np.empty((STEPS, len(outputs)))
    for n in range(STEPS):
        t = n * STEP
        fmu.setReal([vr[name]], [offset + 1e8 * np.sin(2.0 * np.pi * 500.0 * t)])
        result[n] = fmu.getReal([vr[o] for o in outputs])
        fmu.doStep(t, STEP)
    fmu.terminate()
    fmu.freeInstance()
    np.save(args.out, result)
    packages = [m for m in sys.modules if m.startswith("anvilwave_fmu_") and "." not in m]
    print(json.dumps({"source": [sys.modules[p].SOURCE for p in packages],
                      "modules": sorted({m.split(".")[0] for m in sys.modules
                                         if m.split(".")[0] in ("anvilwave", "matplotlib",
                                                                "pythonfmu")}),
                      "pythonfmu": sys.modules["pythonfmu"].__file__}))


if __name__ == "__main__":
    main()
