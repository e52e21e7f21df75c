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
same point: equal to the fmpy master to the CSV's digits) and for the Jacobi masters, libcosim
and fmpy's SSP runner (measured -0.065 % and -0.064 %, 934.60 MN against 935.20 MN). Their
difference is the Jacobi exchange, not a tool or a unit: the fmpy master in the same
exchange order with the SSP's ``input_extrapolation`` gives the same series (libcosim to
round-off). The toe of the elastic ram slows within the step where the contact force jumps;
an anvil that has the ram's state of the point before cannot see that, and its extrapolation
from past points overshot the jump, then undershot (+2.18 %, 955.60 MN, before the anvil's
``ram_toe_mass``, anvilwave/fmu/coupling.py). With the toe's response to the force changes in
the extrapolation the difference converges with the step: -0.69 % at h/2, -0.065 % at h/4,
-0.0056 % at h/8 (test_the_jacobi_lumped_ram_peak_converges_with_the_step).

OMSimulator is a test host found at ROOT/../shared/tools/omsimulator (skipped where
absent); its command line runs 0 - 1 s whatever the SSP says (its library runs the SSP's
window), which the ram's placement of the first contact (contact_mid_step) makes
irrelevant. The units are those ``build-fmus`` makes by default: native anvils, Ram and
PileSoil. The runs are those of benchmarks/doc_fmi_tools.py, and every tool's peaks are
checked against docs/data/fmi_tools.json, the figures of docs/fmi.md's tool table.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS  # noqa: E402
from anvilwave.fmu.fmi_master import BlowMaster  # noqa: E402

from .doc_tables import SAME_RUN, benchmark, doc_data  # noqa: E402

TOOLS = benchmark("doc_fmi_tools")  # the runs of docs/data/fmi_tools.json


@pytest.fixture(scope="module")
def systems(tmp_path_factory):
    """system.ssp of Table 1 (ROM anvil) and its copy with AnvilLumped (and the Ram built for
    the lumped anvil's top face at rest), benchmarks/doc_fmi_tools.py's; the fmpy master's
    peaks of both (at h, and the lumped anvil's ram force on the SSP step in the DESIGN order
    and in the Jacobi exchange)."""
    built = TOOLS.build_systems(tmp_path_factory.mktemp("ssp_tools"))
    step = built["step"]
    engine = {model: tuple(TOOLS.fmpy_master(built, model)[f].max() for f in TOOLS.FORCES)
              for model in TOOLS.MODELS}
    engine["lumped_ram_on_the_ssp_step"] = \
        TOOLS.fmpy_master(built, "lumped", "design", step)["F_ram"].max()
    engine["lumped_ram_jacobi_on_the_ssp_step"] = \
        TOOLS.fmpy_master(built, "lumped", "jacobi", step)["F_ram"].max()
    fmus = built["fmus"]
    print(f"\nunits: anvil {fmus['anvil_implementation']}, ram {fmus['ram_implementation']}, "
          f"pile/soil {fmus['pile_soil_implementation']}")
    return {**built, "engine": engine, "lumped_units": built["units"]["lumped"],
            "out": built["fmus"]["ssp"].parent}


def check_peaks(tool: str, model: str, peaks, systems, jacobi=None, tolerances=None,
                stored: str | None = None) -> None:
    """Peaks (F_ram, F_pile) [N] within 1 % of the FMI engine's (module docstring); for a
    Jacobi master (``jacobi``: its tolerance against the fmpy master in the Jacobi exchange on
    the SSP step) also the lumped anvil's F_ram within ``jacobi`` of the Jacobi one; with
    ``stored`` (the tool's key in docs/data/fmi_tools.json) the peaks the file holds, which
    docs/fmi.md shows: the same SSP, units and tool, a deterministic run, so SAME_RUN
    (tests/doc_tables.py)."""
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
    if stored is not None:
        file = doc_data("fmi_tools")["values"][model][stored]
        assert list(peaks) == pytest.approx(file, **SAME_RUN), \
            "docs/data/fmi_tools.json: run python benchmarks/doc_fmi_tools.py"


def omsimulator(tmp_path_factory) -> Path:
    try:
        return TOOLS.omsimulator_binary(tmp_path_factory.getbasetemp() / "oms")
    except FileNotFoundError as error:
        pytest.skip(str(error))


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
    data, column = TOOLS.read_oms_csv(result)
    steps = np.diff(data[:, 0])
    assert np.allclose(steps[steps > 0], systems["step"], rtol=1e-6)
    assert data[0, 0] == 0.0 and data[-1, 0] == pytest.approx(1.0)  # its command line's
    check_peaks("OMSimulator", "rom", TOOLS.oms_peaks(data, column), systems,
                stored="omsimulator")


@pytest.mark.slow
@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_omsimulator_runs_the_window_of_system_ssp(systems, model, tmp_path, tmp_path_factory):
    """OMSimulator's library on the SSP as written (a Lua script: import, instantiate,
    initialize, simulate; nothing set): it runs the SSP's DefaultExperiment, start -2.5 steps
    to the stop time, at the SSP's step (docs/fmi.md), and gives the engine's peaks."""
    binary = omsimulator(tmp_path_factory)
    run = TOOLS.run_omsimulator(binary, systems["ssp"][model], tmp_path)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "error" not in run.stdout.lower(), run.stdout[-3000:]
    data, column = TOOLS.read_oms_csv(tmp_path / "oms.csv")
    steps = np.diff(data[:, 0])
    steps = steps[steps > 0]
    # the window is 5002.5 steps: the last one is the half step to the stop time
    assert np.allclose(steps[:-1], systems["step"], rtol=1e-6) and steps[-1] <= systems["step"]
    assert data[0, 0] == pytest.approx(-FIRST_CONTACT_STEPS * systems["step"], rel=1e-9)
    assert data[-1, 0] == pytest.approx(systems["duration"], rel=1e-9)
    check_peaks("OMSimulator", model, TOOLS.oms_peaks(data, column), systems,
                stored="omsimulator")


@pytest.mark.slow
@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_fmpy_ssp_runner_runs_system_ssp(systems, model):
    """fmpy's own SSP runner ignores the SSP's bindings and experiment: it gets the step and
    stop time as arguments; the FMUs' defaults are the SSP's values. It never reads the units'
    outputs before the first step (every input is 0 there), so the anvil's outputs at the
    first two points come from zero inputs: the ram's two contact-free steps
    (``contact_mid_step``) and the anvil's acting with the forces its neighbours hold while
    they came from the start's inputs (anvilwave/fmu/coupling.py, step 4) make that
    irrelevant. Peak F_ram within 1 % of the engine (measured +0.14 % ROM; the lumped anvil:
    -0.06 % against the fmpy master on the SSP step, +3e-6 against the fmpy master in the
    Jacobi exchange, which starts at the SSP's start time) and F_pile within 1 % (-0.06 % ROM,
    +0.004 % lumped); before, the missed first-contact impulse came back as a spike in F_ram
    (+66 % ROM, +75 % lumped)."""
    peaks = TOOLS.fmpy_ssp_peaks(systems["ssp"][model], systems["duration"], systems["step"])
    check_peaks("fmpy simulate_ssp", model, peaks, systems,
                jacobi=3e-5,  # measured 3.0e-6: its start, 0 with zero inputs (docstring)
                stored="fmpy_simulate_ssp")


@pytest.mark.slow
def test_libcosim_runs_the_lumped_system_ssp(systems, tmp_path):
    """libcosim on the AnvilLumped SSP (the ROM one: tests/test_fmu_system.py), in a subprocess
    (a crash on its worker threads must not take the session down)."""
    pytest.importorskip("libcosimpy")
    n = int(round(systems["duration"] / systems["step"]))
    forces = TOOLS.run_libcosim(systems["ssp"]["lumped"], 0, n, tmp_path / "lc.npy")[:, 1:]
    check_peaks("libcosim", "lumped", forces.max(axis=0), systems,
                jacobi=1e-9,  # the same exchange and start: round-off (measured 4e-16)
                stored="libcosim")


@pytest.mark.slow
def test_the_jacobi_lumped_ram_peak_converges_with_the_step(systems):
    """The lumped anvil's ram force peak in the Jacobi exchange (input extrapolation on, as the
    SSP, with its ``ram_toe_mass``) against the DESIGN order, fmpy master on both, the SSP's
    start and contact placement, over the first 150 us (the impact). Measured -0.69 % at h/2,
    -0.065 % at the SSP's h/4, -0.0056 % at h/8: about 11x per halving, the bands 4x (a
    second-order coupling error would fall 4x). Without the toe's response to the force
    changes (``ram_toe_mass`` 0) the Jacobi peak is +2.18 % at h/4 (module docstring): it
    must stay above 1 %, so that the toe mass is what brings the exchange within 1 %; without
    the contact dashpot -0.011 % at h/4 (-0.11 % without the toe mass; band 1 %)."""
    units, step = systems["lumped_units"], systems["step"]

    def peak(exchange, divisor, anvil):
        h = step / divisor
        with BlowMaster(*units, {"ram": systems["ram_as_in_the_ssp"]["lumped"],
                                 "anvil": anvil},
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
