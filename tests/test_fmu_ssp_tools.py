"""system.ssp of Table 1 in third-party SSP tools, as written: OMSimulator, libcosim, fmpy.

Each tool runs the SSP (ROM anvil, and the same system with AnvilLumped in its place) with its
own master and settings; the peak ram-anvil and anvil-pile forces must be within 1 % of the
FMI engine (the fmpy master, DESIGN.md order, at the engine's step h, ``impact --engine
fmi``). The SSP's step is h/4 and its anvil extrapolates its inputs (Jacobi masters), so the
tools' peaks differ from the engine's by the step's effect on the explicit coupling (< 0.5 %
measured for the ROM between h and h/4) plus the extrapolation's error (< 0.3 %): 1 % bounds
both.

Exception, the lumped anvil's ram force. Its rise after the contact of a rigid 325 t anvil
behind a 5.9e12 N/m contact spring and the ram-impedance dashpot (1.03e8 N s/m: the force
jumps by c v at the contact) is not resolved by the steps (peak 1002 MN at h, 935 MN at h/4
under the same fmpy master: -6.7 % from the step alone), so it is compared with the fmpy master
on the SSP's own step: within 1 % for OMSimulator (which gives the anvil the ram's state of the
same point), 3 % for the Jacobi masters, libcosim and fmpy's SSP runner (measured +2.18 % for
both, 955.60 MN against 935.18 MN). That is the Jacobi exchange, not a tool or a unit: the
fmpy master in the same exchange order with the SSP's ``input_extrapolation`` gives the same
series (libcosim to 4e-12 x peak, F_ram and F_pile). The toe of the elastic ram slows by about
F/Z within the step where the contact force jumps; an anvil that has the ram's state of the
point before cannot know it, and its extrapolation from past points overshoots the jump, then
undershoots (F_ram after the first contact, design/Jacobi at h/4: 728/728, 823/909, 888/812,
924/887, 935/956 MN, the peak 22.5 us after the contact). The difference is the step's: peak
+71 % at h, +24 % at h/2, +2.18 % at h/4, -0.054 % at h/8, -0.005 % at h/16, and without the
dashpot -0.11 % at h/4 (test_the_jacobi_lumped_ram_peak_converges_with_the_step).

OMSimulator is a test host found at ROOT/../shared/tools/omsimulator (skipped where
absent); its command line runs 0 - 1 s whatever the SSP says (its library runs the SSP's
window), which the ram's placement of the first contact (contact_mid_step) makes
irrelevant. The units are those ``build-fmus`` makes by
default: native anvils, Ram and PileSoil (measured with them: OMSimulator ROM F_ram +0.17 %,
F_pile -0.06 %; lumped F_ram +0.000 % of the fmpy master on the SSP step, F_pile +0.003 %).
"""

from __future__ import annotations

import csv
import subprocess
import tarfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from anvilwave.config.system import load_system  # noqa: E402
from anvilwave.engine.fmus import (  # noqa: E402
    build_system_fmus,
    load_anvil_modal_data,
    system_parameters,
)
from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS  # noqa: E402
from anvilwave.fmu.fmi_build import build_ram_fmu  # noqa: E402
from anvilwave.fmu.fmi_master import BlowMaster  # noqa: E402
from anvilwave.fmu.native_units import build_native_ram_fmu  # noqa: E402
from anvilwave.fmu.ssp import write_ssp  # noqa: E402

from .conftest import EXAMPLES, SHARED  # noqa: E402

OMS_DIR = SHARED / "tools" / "omsimulator"


@pytest.fixture(scope="module")
def systems(tmp_path_factory):
    """system.ssp of Table 1 (ROM anvil) and its copy with AnvilLumped (and the Ram built for
    the lumped anvil's top face at rest); the FMI engine's peaks of both."""
    cfg = load_system(EXAMPLES / "table1.toml")
    modal = load_anvil_modal_data(cfg)
    out = tmp_path_factory.mktemp("ssp_tools")
    fmus = build_system_fmus(cfg, out, modal, native_anvil=None)
    lumped_cfg = cfg.with_anvil_model("lumped")
    lumped = system_parameters(lumped_cfg, modal)
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
    h = fmus["time_step"]
    n = int(round(cfg.duration / h))
    engine = {}
    for model, anvil, ram_fmu in (("rom", fmus["Anvil"], fmus["Ram"]),
                                  ("lumped", fmus["AnvilLumped"], ram)):
        with BlowMaster(ram_fmu, anvil, fmus["PileSoil"]) as master:
            blow = master.run_blows(1, n, h)[0]
        engine[model] = (blow["F_ram"].max(), blow["F_pile"].max())
    with BlowMaster(ram, fmus["AnvilLumped"], fmus["PileSoil"]) as master:  # docstring
        fine = master.run_blows(1, int(round(cfg.duration / step)), step)[0]
    engine["lumped_ram_on_the_ssp_step"] = fine["F_ram"].max()
    lumped_units = (ram, fmus["AnvilLumped"], fmus["PileSoil"])
    ram_as_in_the_ssp = {"contact_displacement": lumped["Ram"]["contact_displacement"],
                         "contact_time": 0.0, "contact_mid_step": True}
    with BlowMaster(*lumped_units, {"ram": ram_as_in_the_ssp,
                                    "anvil": {"input_extrapolation": True}},
                    exchange="jacobi") as master:
        jacobi = master.run_blows(1, int(round(cfg.duration / step)) + 2, step,
                                  start_time=experiment[0])[0]
    engine["lumped_ram_jacobi_on_the_ssp_step"] = jacobi["F_ram"].max()
    print(f"\nunits: anvil {fmus['anvil_implementation']}, ram {fmus['ram_implementation']}, "
          f"pile/soil {fmus['pile_soil_implementation']}")
    return {"ssp": {"rom": fmus["ssp"], "lumped": ssp_lumped}, "engine": engine,
            "lumped_units": lumped_units, "ram_as_in_the_ssp": ram_as_in_the_ssp,
            "duration": float(cfg.duration), "step": step, "out": out}


def check_peaks(tool: str, model: str, peaks, systems, jacobi=None, tolerances=None) -> None:
    """Peaks (F_ram, F_pile) [N] within 1 % of the FMI engine's (module docstring); for a
    Jacobi master (``jacobi``: its tolerance against the fmpy master in the Jacobi exchange on
    the SSP step) also the lumped anvil's F_ram within ``jacobi`` of the Jacobi one."""
    references = dict(zip(("F_ram", "F_pile"), systems["engine"][model], strict=True))
    tolerances = dict(tolerances or {"F_ram": 0.01, "F_pile": 0.01})
    what = {"F_ram": "FMI engine", "F_pile": "FMI engine"}
    if model == "lumped":
        references["F_ram"] = systems["engine"]["lumped_ram_on_the_ssp_step"]
        what["F_ram"] = "fmpy master on the SSP step"
        if jacobi is not None:  # the Jacobi exchange against the same master: module docstring
            same = systems["engine"]["lumped_ram_jacobi_on_the_ssp_step"]
            print(f"\n{tool} lumped F_ram: fmpy master in the Jacobi exchange {same / 1e6:.2f} "
                  f"MN ({peaks[0] / same - 1:+.1e})")
            assert abs(peaks[0] / same - 1.0) <= jacobi
    for name, peak in zip(("F_ram", "F_pile"), peaks, strict=True):
        reference = references[name]
        print(f"\n{tool} {model} {name}: {peak / 1e6:.2f} MN, {what[name]} "
              f"{reference / 1e6:.2f} MN ({peak / reference - 1:+.3%})")
        assert np.isfinite(peak)
        assert abs(peak / reference - 1.0) <= tolerances[name]


def omsimulator(tmp_path_factory) -> Path:
    archives = sorted(OMS_DIR.glob("omsimulator-*.tgz")) if OMS_DIR.is_dir() else []
    if not archives:
        pytest.skip(f"OMSimulator (a test host) not found in {OMS_DIR}")
    target = tmp_path_factory.getbasetemp() / "oms"
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


@pytest.mark.slow
def test_omsimulator_runs_system_ssp_from_its_command_line(systems, tmp_path, tmp_path_factory):
    """A plain ``OMSimulator system.ssp``: no start, stop or step on its command line (only
    where the result goes). Its fixed step is the SSP's (the oms annotation), checked in the
    result's time column. Its command line replaces the SSP's start and stop times by its own
    (0 and 1 s: the library reads ``ssd:DefaultExperiment``, the command line then sets its
    flags' values; test_omsimulator_runs_the_window_of_system_ssp runs the SSP's window): the
    ram's start does not depend on the start time and the blow is over long before 1 s, so
    the peaks are those of the SSP's window (measured +0.17 % ROM F_ram, -0.06 % F_pile;
    7.5 s for the 200,000 steps)."""
    binary = omsimulator(tmp_path_factory)
    result = tmp_path / "oms.csv"
    run = subprocess.run([str(binary), str(systems["ssp"]["rom"]), f"--resultFile={result}",
                          f"--tempDir={tmp_path}"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=900)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "error" not in run.stdout.lower(), run.stdout[-3000:]
    data, column = read_oms_csv(result)
    steps = np.diff(data[:, 0])
    assert np.allclose(steps[steps > 0], systems["step"], rtol=1e-6)
    assert data[0, 0] == 0.0 and data[-1, 0] == pytest.approx(1.0)  # its command line's
    check_peaks("OMSimulator", "rom", (data[:, column["Ram.F_toe"]].max(),
                                       data[:, column["PileSoil.F_head"]].max()), systems)


OMS_LUA = """model, status = oms_importFile("{ssp}")
oms_setResultFile(model, "{result}", 1)
oms_instantiate(model)
oms_initialize(model)
oms_simulate(model)
oms_terminate(model)
oms_delete(model)
"""


@pytest.mark.slow
@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_omsimulator_runs_the_window_of_system_ssp(systems, model, tmp_path, tmp_path_factory):
    """OMSimulator's library on the SSP as written (a Lua script: import, instantiate,
    initialize, simulate; nothing set): it runs the SSP's DefaultExperiment, start -2.5 steps
    to the stop time, at the SSP's step (docs/fmi.md), and gives the engine's peaks."""
    binary = omsimulator(tmp_path_factory)
    result = tmp_path / "oms.csv"
    script = tmp_path / "run.lua"
    script.write_text(OMS_LUA.format(ssp=systems["ssp"][model], result=result))
    run = subprocess.run([str(binary), str(script), f"--tempDir={tmp_path}"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=900)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "error" not in run.stdout.lower(), run.stdout[-3000:]
    data, column = read_oms_csv(result)
    steps = np.diff(data[:, 0])
    steps = steps[steps > 0]
    # the window is 5002.5 steps: the last one is the half step to the stop time
    assert np.allclose(steps[:-1], systems["step"], rtol=1e-6) and steps[-1] <= systems["step"]
    assert data[0, 0] == pytest.approx(-FIRST_CONTACT_STEPS * systems["step"], rel=1e-9)
    assert data[-1, 0] == pytest.approx(systems["duration"], rel=1e-9)
    check_peaks("OMSimulator", model, (data[:, column["Ram.F_toe"]].max(),
                                       data[:, column["PileSoil.F_head"]].max()), systems)


@pytest.mark.slow
@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_fmpy_ssp_runner_runs_system_ssp(systems, model):
    """fmpy's own SSP runner ignores the SSP's bindings and experiment: it gets the step and
    stop time as arguments; the FMUs' defaults are the SSP's values. It never reads the units'
    outputs before the first step (every input is 0 there), so the anvil's outputs at the
    first two points come from zero inputs: the ram's two contact-free steps
    (``contact_mid_step``) and the anvil's acting with the forces its neighbours hold while
    they came from the start's inputs (anvilwave/fmu/coupling.py, step 4) make that
    irrelevant. Peak F_ram within 1 % of the engine (measured -0.09 % ROM; the lumped anvil:
    module docstring, +2.18 % against the fmpy master on the SSP step, +2.9e-6 against the
    fmpy master in the Jacobi exchange, which starts at the SSP's start time) and F_pile within
    1 % (-0.06 % ROM, +0.004 % lumped); before, the missed first-contact impulse came back as
    a spike in F_ram (+66 % ROM, +75 % lumped)."""
    from fmpy.ssp.simulation import simulate_ssp

    result = simulate_ssp(str(systems["ssp"][model]), start_time=0.0,
                          stop_time=systems["duration"], step_size=systems["step"])
    check_peaks("fmpy simulate_ssp", model, (result["Ram.F_toe"].max(),
                                             result["PileSoil.F_head"].max()), systems,
                jacobi=3e-5)  # measured 2.9e-6: its start, 0 with zero inputs (docstring)


LIBCOSIM_RUN = """
import sys
import numpy as np
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver

log_output_level(CosimLogLevel.WARNING)
ssp, n_steps, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
execution = CosimExecution.from_ssp_file(ssp)
index = {i.name.decode(): i.index for i in execution.slave_infos()}
refs = {v.name.decode(): v.reference for v in execution.slave_variables(index["Anvil"])}
observer = CosimObserver.create_last_value()
execution.add_observer(observer)
rows = []
for n in range(n_steps):
    if not execution.step(1):
        raise SystemExit(f"libcosim step {n} failed")
    rows.append(observer.last_real_values(index["Anvil"], [refs["F_ram"], refs["F_pile"]]))
np.save(out, np.array(rows))
"""


@pytest.mark.slow
def test_libcosim_runs_the_lumped_system_ssp(systems, tmp_path):
    """libcosim on the AnvilLumped SSP (the ROM one: tests/test_fmu_system.py), in a subprocess
    (a crash on its worker threads must not take the session down)."""
    import sys

    pytest.importorskip("libcosimpy")
    n = int(round(systems["duration"] / systems["step"]))
    out = tmp_path / "lc.npy"
    run = subprocess.run([sys.executable, "-c", LIBCOSIM_RUN, str(systems["ssp"]["lumped"]),
                          str(n), str(out)], capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, run.stderr[-3000:]
    forces = np.load(out)
    check_peaks("libcosim", "lumped", forces.max(axis=0), systems,
                jacobi=1e-9)  # the same exchange and start: round-off (measured 1e-15)


@pytest.mark.slow
def test_the_jacobi_lumped_ram_peak_converges_with_the_step(systems):
    """The lumped anvil's ram force peak in the Jacobi exchange (input extrapolation on, as the
    SSP, with its ``ram_toe_mass``) against the DESIGN order, fmpy master on both, the SSP's
    start and contact placement, over the first 150 us (the impact). Measured -0.69 % at h/2,
    -0.065 % at the SSP's h/4, -0.0056 % at h/8: about 11x per halving, the bands 4x (a
    second-order coupling error would fall 4x). Without the toe's response to the force
    changes (``ram_toe_mass`` 0) the Jacobi peak is +2.18 % at h/4 (module docstring): it
    must stay above 1 %, so that the toe mass is what brings the exchange within 1 %; without
    the contact dashpot -0.11 % at h/4 with or without it (band 1 %)."""
    units, step = systems["lumped_units"], systems["step"]

    def peak(exchange, divisor, anvil):
        h = step / divisor
        with BlowMaster(*units, {"ram": systems["ram_as_in_the_ssp"], "anvil": anvil},
                        exchange=exchange) as master:
            blow = master.run_blows(1, int(round(150e-6 / h)), h,
                                    start_time=-FIRST_CONTACT_STEPS * h)[0]
        return blow["F_ram"].max()

    def difference(divisor, **anvil):
        jacobi = peak("jacobi", divisor, {"input_extrapolation": True, **anvil})
        design = peak("design", divisor, anvil)
        print(f"\nlumped F_ram peak at the SSP step / {divisor} {anvil}: Jacobi "
              f"{jacobi / 1e6:.2f} MN, DESIGN order {design / 1e6:.2f} MN "
              f"({jacobi / design - 1:+.4%})")
        return abs(jacobi / design - 1.0)

    coarse, ssp, fine = difference(0.5), difference(1), difference(2)
    assert ssp <= 5e-3  # within 1 % with room: measured 6.5e-4
    assert fine <= ssp / 4 and ssp <= coarse / 4
    assert difference(1, ram_toe_mass=0.0) >= 1e-2
    assert difference(1, ram_contact_damping=0.0) <= 1e-2
