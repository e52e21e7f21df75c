"""system.ssp of Table 1 in third-party SSP tools: the peaks of docs/fmi.md's tool table.

Run: python benchmarks/doc_fmi_tools.py [--out DIR]  (writes docs/data/fmi_tools.json)

``build-fmus`` of anvilwave/examples/table1.toml (native units by default) gives ``system.ssp``
(ROM anvil); the same system with ``AnvilLumped`` in its place (and the Ram built for the
lumped anvil's top face at rest) is ``system_lumped.ssp``. Each is run as written by

* OMSimulator's library (a Lua script: import, instantiate, initialize, simulate; the SSP's
  DefaultExperiment and step), from ``../shared/tools/omsimulator/`` (a test host, read by
  path; the script stops with a message where it is absent);
* libcosim (libcosimpy, at the SSP's OSP step), in a subprocess;
* fmpy's ``simulate_ssp`` (step and stop time as arguments: it reads neither the SSP's
  experiment nor its bindings);

and against them the fmpy master (:class:`anvilwave.fmu.fmi_master.BlowMaster`): in the
DESIGN.md order at the engine's step h (``impact --engine fmi``), in that order on the SSP's
step, and in libcosim's Jacobi exchange on the SSP's step. The table gives each tool's peak
ram-anvil and anvil-pile force against ``impact --engine fmi``, except the lumped anvil's ram
force, against the fmpy master on the SSP's step (its rise is not resolved by the engine's
step h: docs/fmi.md). Every run is deterministic (same FMUs, same tool, same inputs): the
tests that run the tools (tests/test_fmu_ssp_tools.py, tests/test_fmu_system.py) check their
peaks against this file.
"""

from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import tarfile
import tempfile
import textwrap
from pathlib import Path

import numpy as np
from doc_data import ROOT, system_inputs, write_doc_data

from anvilwave.config.system import load_system
from anvilwave.engine.fmus import build_system_fmus, load_anvil_modal_data, system_parameters
from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS
from anvilwave.fmu.fmi_build import build_ram_fmu
from anvilwave.fmu.fmi_master import BlowMaster
from anvilwave.fmu.native_units import build_native_ram_fmu
from anvilwave.fmu.ssp import write_ssp

SYSTEM = ROOT / "anvilwave" / "examples" / "table1.toml"
OMS_DIR = ROOT.parent / "shared" / "tools" / "omsimulator"
MODELS = ("rom", "lumped")
FORCES = ("F_ram", "F_pile")

LIBCOSIM_RUN = textwrap.dedent('''
    """Run an SSP with libcosim (libcosimpy): F_ram, F_pile of the Anvil after every step."""
    import sys
    import numpy as np
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.WARNING)
    ssp, step_ns, n_steps, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    # step_ns 0: the SSP's own osp:FixedStepAlgorithm base step
    execution = CosimExecution.from_ssp_file(ssp, step_ns or None)
    index = {i.name.decode(): i.index for i in execution.slave_infos()}
    refs = {v.name.decode(): v.reference for v in execution.slave_variables(index["Anvil"])}
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    rows = []
    for n in range(n_steps):
        if not execution.step(1):
            raise SystemExit(f"libcosim step {n} failed")
        rows.append([execution.status().current_time,
                     *observer.last_real_values(index["Anvil"],
                                                [refs["F_ram"], refs["F_pile"]])])
    np.save(out, np.array(rows))
''')
"""The libcosim run (``python -c LIBCOSIM_RUN SSP STEP_NS N_STEPS OUT.npy``)."""

OMS_LUA = """model, status = oms_importFile("{ssp}")
oms_setResultFile(model, "{result}", 1)
oms_instantiate(model)
oms_initialize(model)
oms_simulate(model)
oms_terminate(model)
oms_delete(model)
"""
"""OMSimulator's library on an SSP as written: its DefaultExperiment, nothing set."""


def build_systems(out: Path) -> dict:
    """The FMUs of Table 1 (``build-fmus``), system.ssp and system_lumped.ssp in ``out``.

    Returns
    -------
    dict
        ``fmus`` (:func:`anvilwave.engine.fmus.build_system_fmus`' result), ``ssp``
        {model: path}, ``units`` {model: (Ram, Anvil, PileSoil FMU paths)},
        ``ram_as_in_the_ssp`` {model: the Ram's start parameters of its SSP}, ``duration`` [s],
        ``step`` (the SSP's) [s], ``time_step`` (the engine's h) [s].
    """
    cfg = load_system(SYSTEM)
    modal = load_anvil_modal_data(cfg)
    fmus = build_system_fmus(cfg, out, modal, native_anvil=None)
    lumped = system_parameters(cfg.with_anvil_model("lumped"), modal)
    step = fmus["ssp_step"]
    experiment = (-FIRST_CONTACT_STEPS * step, float(cfg.duration), step)
    if fmus["ram_implementation"] == "native":  # the Ram of build-fmus (the default)
        ram = build_native_ram_fmu(cfg.hammer, out / "lumped" / "Ram.fmu",
                                   default_experiment=experiment, **lumped["Ram"])
    else:
        ram = build_ram_fmu(out / "lumped", cfg.hammer, default_experiment=experiment,
                            **lumped["Ram"])
    ssp_lumped = write_ssp(out / "system_lumped.ssp",
                           {"Ram": ram, "Anvil": fmus["AnvilLumped"],
                            "PileSoil": fmus["PileSoil"]},
                           {"Ram": lumped["Ram"], "Anvil": lumped["AnvilLumped"],
                            "PileSoil": lumped["PileSoil"]},
                           name="anvilwave table1 lumped", start_time=experiment[0],
                           stop_time=cfg.duration, step_size=step)
    return {"fmus": fmus, "ssp": {"rom": fmus["ssp"], "lumped": ssp_lumped},
            "units": {"rom": (fmus["Ram"], fmus["Anvil"], fmus["PileSoil"]),
                      "lumped": (ram, fmus["AnvilLumped"], fmus["PileSoil"])},
            "ram_as_in_the_ssp": {
                model: {"contact_displacement": ram["contact_displacement"],
                        "contact_time": 0.0, "contact_mid_step": True}
                for model, ram in (("rom", fmus["parameters"]["Ram"]),
                                   ("lumped", lumped["Ram"]))},
            "duration": float(cfg.duration), "step": step, "time_step": fmus["time_step"]}


def fmpy_master(systems: dict, model: str, exchange: str = "design",
                step: float | None = None, **anvil) -> dict:
    """The fmpy master's blow: at the engine's h from its start (``step`` None, ``impact
    --engine fmi``), or on ``step`` [s] from the SSP's start with the SSP's ram start, in the
    ``exchange`` order (Jacobi: with the SSP's anvil parameters, and ``anvil``'s)."""
    units = systems["units"][model]
    if step is None:
        h = systems["time_step"]
        with BlowMaster(*units) as master:
            return master.run_blows(1, int(round(systems["duration"] / h)), h)[0]
    with BlowMaster(*units, {"ram": systems["ram_as_in_the_ssp"][model],
                             "anvil": {"input_extrapolation": True, **anvil}},
                    exchange=exchange) as master:
        return master.run_blows(1, int(round(systems["duration"] / step)) + 2, step,
                                start_time=-FIRST_CONTACT_STEPS * step)[0]


def omsimulator_binary(target: Path) -> Path:
    """OMSimulator unpacked from ../shared/tools/omsimulator into ``target`` (once).

    Raises
    ------
    FileNotFoundError
        When no OMSimulator archive is there.
    """
    archives = sorted(OMS_DIR.glob("omsimulator-*.tgz")) if OMS_DIR.is_dir() else []
    if not archives:
        raise FileNotFoundError(f"OMSimulator (a test host) not found in {OMS_DIR}")
    binary = target / "omsinstall" / "bin" / "OMSimulator"
    if not binary.is_file():
        with tarfile.open(archives[-1]) as tf:
            tf.extractall(target, filter="tar")
    return binary


def read_oms_csv(path: Path) -> tuple[np.ndarray, dict[str, int]]:
    """OMSimulator's CSV result: the data and a column per ``Unit.variable``."""
    with path.open() as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    column = {name.rsplit(".", 2)[-2] + "." + name.rsplit(".", 1)[-1]: j
              for j, name in enumerate(header) if "." in name}
    return data, column


def run_omsimulator(binary: Path, ssp: Path, folder: Path) -> subprocess.CompletedProcess:
    """OMSimulator's library on ``ssp`` (:data:`OMS_LUA`), its result ``folder``/oms.csv."""
    script = folder / "run.lua"
    script.write_text(OMS_LUA.format(ssp=ssp, result=folder / "oms.csv"))
    return subprocess.run([str(binary), str(script), f"--tempDir={folder}"],
                          capture_output=True, text=True, cwd=folder, timeout=900)


def oms_peaks(data: np.ndarray, column: dict[str, int]) -> list[float]:
    """(F_ram, F_pile) peaks [N] of an OMSimulator result (the Ram's and PileSoil's inputs)."""
    return [float(data[:, column["Ram.F_toe"]].max()),
            float(data[:, column["PileSoil.F_head"]].max())]


def run_libcosim(ssp: Path, step_ns: int, n_steps: int, out: Path) -> np.ndarray:
    """(time [ns], F_ram [N], F_pile [N]) after each of n_steps libcosim steps (step_ns 0:
    the SSP's own step), in a subprocess (a crash on its worker threads stays there).

    Raises
    ------
    RuntimeError
        With libcosim's message when the run fails.
    """
    run = subprocess.run([sys.executable, "-c", LIBCOSIM_RUN, str(ssp), str(step_ns),
                          str(n_steps), str(out)], capture_output=True, text=True, timeout=900)
    if run.returncode != 0:
        raise RuntimeError(f"libcosim on {ssp}: {run.stderr[-3000:]}")
    return np.load(out)


def fmpy_ssp_peaks(ssp: Path, duration: float, step: float) -> list[float]:
    """(F_ram, F_pile) peaks [N] of fmpy's ``simulate_ssp`` from 0 to ``duration``."""
    from fmpy.ssp.simulation import simulate_ssp  # lazy: fmpy is a test extra

    result = simulate_ssp(str(ssp), start_time=0.0, stop_time=duration, step_size=step)
    return [float(result["Ram.F_toe"].max()), float(result["PileSoil.F_head"].max())]


def measure(systems: dict, scratch: Path) -> dict:
    """Every run of the module docstring: ``values`` of docs/data/fmi_tools.json."""
    step = systems["step"]
    n_steps = int(round(systems["duration"] / step))
    binary = omsimulator_binary(scratch / "oms")
    values = {"ssp_step [s]": step, "time_step [s]": systems["time_step"],
              "ram_toe_mass [kg]": systems["fmus"]["parameters"]["Anvil"]["ram_toe_mass"]}
    for model in MODELS:
        ssp = systems["ssp"][model]
        engine = fmpy_master(systems, model)
        same = fmpy_master(systems, model, "design", step)
        jacobi = fmpy_master(systems, model, "jacobi", step)
        no_toe = fmpy_master(systems, model, "jacobi", step, ram_toe_mass=0.0)
        folder = scratch / f"oms_{model}"
        folder.mkdir(exist_ok=True)
        run = run_omsimulator(binary, ssp, folder)
        if run.returncode != 0:
            raise RuntimeError(f"OMSimulator on {ssp}: {run.stdout[-3000:]}{run.stderr[-3000:]}")
        lc = run_libcosim(ssp, 0, n_steps, scratch / f"lc_{model}.npy")
        # libcosim's rows are after each step from the SSP's start, as same's from row 1 on
        lc_band = max(float(np.abs(lc[:, j] - same[f][1:len(lc) + 1]).max() / same[f].max())
                      for j, f in ((1, "F_ram"), (2, "F_pile")))
        values[model] = {
            "fmpy_master_h": [float(engine[f].max()) for f in FORCES],
            "fmpy_master_ssp_step": [float(same[f].max()) for f in FORCES],
            "fmpy_master_jacobi_ssp_step": [float(jacobi[f].max()) for f in FORCES],
            "fmpy_master_jacobi_ssp_step_no_toe_mass": [float(no_toe[f].max())
                                                        for f in FORCES],
            "omsimulator": oms_peaks(*read_oms_csv(folder / "oms.csv")),
            "libcosim": [float(lc[:, 1].max()), float(lc[:, 2].max())],
            "libcosim_band_same_step [-]": lc_band,
            "fmpy_simulate_ssp": fmpy_ssp_peaks(ssp, systems["duration"], step),
        }
    return values


TOOLS = {"omsimulator": "OMSimulator 2.1.1", "libcosim": "libcosim (libcosimpy)",
         "fmpy_simulate_ssp": "fmpy `simulate_ssp`"}
"""Tool key of the values -> its name in the table."""
ANVILS = {"rom": "Anvil (ROM)", "lumped": "AnvilLumped"}


def reference(values: dict, model: str) -> list[float]:
    """The peaks (F_ram, F_pile) [N] a tool is compared with (module docstring)."""
    v = values[model]
    if model == "lumped":
        return [v["fmpy_master_ssp_step"][0], v["fmpy_master_h"][1]]
    return list(v["fmpy_master_h"])


def errors(values: dict, tool: str, model: str) -> list[float]:
    """A tool's peak errors (F_ram, F_pile) [-] against :func:`reference`."""
    return [p / r - 1.0 for p, r in zip(values[model][tool], reference(values, model),
                                         strict=True)]


def docs_table(values: dict) -> tuple[dict, dict]:
    """docs/fmi.md's tool table and the numbers its prose quotes, from the values."""
    rows = [[TOOLS[tool], ANVILS[model], *errors(values, tool, model)]
            for tool in TOOLS for model in MODELS]
    table = {"columns": ["tool (SSP step 5 us)", "anvil", "ram-anvil peak", "anvil-pile peak"],
             "formats": [None, None, "pct+3", "pct+3"], "rows": rows}
    rom, lumped = values["rom"], values["lumped"]
    same = [p / r - 1.0 for p, r in zip(rom["libcosim"], rom["fmpy_master_ssp_step"],
                                         strict=True)]
    subs = {
        "libcosim_rom_ram": [errors(values, "libcosim", "rom")[0], "pct+2"],
        "libcosim_rom_pile": [errors(values, "libcosim", "rom")[1], "pct+2"],
        "libcosim_rom_ram_same_step": [same[0], "pct+2"],
        "libcosim_rom_pile_same_step": [same[1], "pct+2"],
        "libcosim_rom_band": [rom["libcosim_band_same_step [-]"], "pct"],
        "lumped_ram_h": [lumped["fmpy_master_h"][0], "MN0"],
        "lumped_ram_ssp_step": [lumped["fmpy_master_ssp_step"][0], "MN2"],
        "lumped_ram_omsimulator": [lumped["omsimulator"][0], "MN2"],
        "lumped_ram_jacobi": [lumped["fmpy_master_jacobi_ssp_step"][0], "MN2"],
        "lumped_ram_libcosim": [errors(values, "libcosim", "lumped")[0], "pct+3"],
        "lumped_ram_jacobi_no_toe_mass": [
            lumped["fmpy_master_jacobi_ssp_step_no_toe_mass"][0]
            / lumped["fmpy_master_ssp_step"][0] - 1.0, "pct+2"],
        "ram_toe_mass": [values["ram_toe_mass [kg]"], "t1"],
    }
    return {"tools": table}, subs


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=None,
                        help="folder for the FMUs and the tools' results (default: a "
                             "temporary one)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="anvilwave_fmi_tools_") as scratch:
        out = args.out or Path(scratch)
        out.mkdir(parents=True, exist_ok=True)
        systems = build_systems(out / "fmus")
        work = out / "runs"
        work.mkdir(exist_ok=True)
        values = measure(systems, work)
    tables, subs = docs_table(values)
    for row in tables["tools"]["rows"]:
        print(f"{row[0]:24s} {row[1]:12s} F_ram {row[2]:+.3%}  F_pile {row[3]:+.3%}")
    write_doc_data("fmi_tools", about="system.ssp of Table 1 in OMSimulator, libcosim and "
                   "fmpy's SSP runner against the fmpy master (docs/fmi.md, \"Taking the FMUs "
                   "to another machine\", and the Masters paragraph)",
                   inputs=[*system_inputs(SYSTEM),
                           ROOT / "anvilwave" / "fmu" / "native" / "binaries" / "SOURCES.sha256"],
                   tables=tables, substitutions=subs, values=values)


if __name__ == "__main__":
    main()
