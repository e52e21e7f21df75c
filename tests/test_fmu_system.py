"""The system FMUs (Ram, Anvil, AnvilLumped, PileSoil), system.ssp and the FMI engine.

Built once per module from anvilwave/examples/table1.toml (anvil modes ~2-5 s, four FMUs ~3 s),
with the
native anvils when a C compiler is found (else the pythonfmu anvils, and the tests that need
the native ones say so). The FMU chain under the fmpy master (``run_fmi``) must reproduce the
in-process engine (``build_engine(cfg).run()``): both run the same kernels (the native anvil:
the same operations in C) with the same initialisation, sub-stepping and step order, so they
agree to round-off. The tolerance of 1e-9 x peak is therefore loose; what is left (~1e-12
measured) is the order of floating-point sums (the anvil's top face at rest is read back from
the anvil unit instead of reused, the anvil starts on the pile head of the blow in the frame of
the first blow, numpy's dot against a plain sum in C).
"""

from __future__ import annotations

import ctypes
import dataclasses
import json
import shutil
import subprocess
import sys
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from fmpy import calloc, extract, free, read_model_description, simulate_fmu  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import (  # noqa: E402
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.validation import validate_fmu  # noqa: E402

from anvilwave.config.system import load_system  # noqa: E402
from anvilwave.engine.direct import COLUMNS, build_engine  # noqa: E402
from anvilwave.engine.fmi import run_fmi  # noqa: E402
from anvilwave.engine.fmus import SSP_STEP_DIVISOR, build_system_fmus, load_anvil_modal_data  # noqa: E402
from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS, OUT_OF_REACH_TIME  # noqa: E402
from anvilwave.fmu.fmi_build import (  # noqa: E402
    SHIM_INNER_LIBRARY,
    build_ram_fmu,
    hammer_toml,
    pile_soil_toml,
)
from anvilwave.fmu.fmi_master import BlowMaster, CosimulationError  # noqa: E402
from anvilwave.hammer.database import load_hammer  # noqa: E402
from anvilwave.inputs import InputError  # noqa: E402
from anvilwave.pile.model import PileSoil, load_pile_soil  # noqa: E402

from .conftest import EXAMPLES  # noqa: E402
from .doc_tables import SAME_RUN, benchmark, doc_data  # noqa: E402

KINDS = ("Ram", "Anvil", "AnvilLumped", "PileSoil")
FORCES = ("ram_anvil_force [N]", "anvil_pile_force [N]")


@pytest.fixture(scope="module")
def system(tmp_path_factory):
    """Table 1 system: its anvil modes, its four FMUs and system.ssp, built once."""
    cfg = load_system(EXAMPLES / "table1.toml")
    modal = load_anvil_modal_data(cfg)
    out = tmp_path_factory.mktemp("system_fmus")
    fmus = build_system_fmus(cfg, out, modal, native_anvil=None, native_units=False)
    return {"cfg": cfg, "modal": modal, "fmus": fmus, "out": out}


def native(system) -> None:
    """Skip (with the reason) when the anvils could not be built natively (no current shipped
    binaries)."""
    if system["fmus"]["anvil_implementation"] != "native":
        pytest.skip("the native anvil FMUs need their shipped binaries (python -m "
                    "anvilwave.fmu.native_units rebuilds them)")


@pytest.fixture(scope="module")
def direct(system):
    """The in-process engine's blows for the ROM and the lumped anvil."""
    cfg, modal = system["cfg"], system["modal"]
    return {model: build_engine(cfg.with_anvil_model(model), modal).run()
            for model in ("rom", "lumped")}


def relative_difference(a: np.ndarray, b: np.ndarray) -> float:
    """max |a - b| / max |b|."""
    return float(np.abs(a - b).max() / np.abs(b).max())


def assert_same_blows(fmi, direct, tolerance=1e-9):
    """Every column of every blow within ``tolerance`` x its peak."""
    assert len(fmi) == len(direct)
    for f, d in zip(fmi, direct, strict=True):
        assert f.time_step == d.time_step and f.n_steps == d.n_steps
        assert list(f.columns) == list(d.columns) == list(COLUMNS)
        np.testing.assert_array_equal(f.columns["time [s]"], d.columns["time [s]"])
        for name in COLUMNS[1:]:
            scale = max(np.abs(d.columns[name]).max(), 1e-300)
            diff = np.abs(f.columns[name] - d.columns[name]).max()
            assert diff <= tolerance * scale, (name, diff, scale)


# ---------------------------------------------------------------------------- the files
@pytest.mark.parametrize("kind", KINDS)
def test_fmus_validate_without_problems(system, kind):
    assert validate_fmu(str(system["fmus"][kind])) == []
    md = read_model_description(str(system["fmus"][kind]))
    assert all("[" in v.description for v in md.modelVariables)
    assert all(v.unit for v in md.modelVariables if v.type == "Real"
               and v.causality in ("input", "output"))
    assert {u.variable.name for u in md.initialUnknowns} == {u.variable.name for u in md.outputs}


def test_interfaces_are_the_design_contract(system):
    names = {}
    for kind in KINDS:
        md = read_model_description(str(system["fmus"][kind]))
        names[kind] = {c: {v.name for v in md.modelVariables if v.causality == c}
                       for c in ("input", "output")}
    assert names["Ram"] == {"input": {"F_toe"}, "output": {"u_toe", "v_toe"}}
    for anvil in ("Anvil", "AnvilLumped"):
        assert names[anvil] == {"input": {"u_ram", "v_ram", "u_pile", "v_pile"},
                                "output": {"F_ram", "F_pile", "u_top", "u_bottom"}}
    assert names["PileSoil"]["input"] == {"F_head"}
    assert {"u_head", "v_head", "F_gauge", "v_gauge"} <= names["PileSoil"]["output"]
    # the states are not feedthrough: ram and pile outputs depend on no input
    for kind in ("Ram", "PileSoil"):
        md = read_model_description(str(system["fmus"][kind]))
        assert all(not u.dependencies for u in md.outputs)
    # resources: the ram's segments, the pile/soil tables, the modal data (native: binary)
    modes = ("modal_data.bin" if system["fmus"]["anvil_implementation"] == "native"
             else "xl8_modes.npz")
    for kind, resource in (("Ram", "hammer.toml"), ("PileSoil", "pile_soil.toml"),
                           ("Anvil", modes)):
        with zipfile.ZipFile(system["fmus"][kind]) as zf:
            assert f"resources/{resource}" in zf.namelist()


@pytest.mark.parametrize("kind", KINDS)
def test_each_fmu_runs_alone_with_fmpy_simulate(system, kind):
    result = simulate_fmu(str(system["fmus"][kind]), stop_time=2e-3, step_size=1e-5)
    names = result.dtype.names[1:]
    assert all(np.all(np.isfinite(result[n])) for n in names)
    parameters = system["fmus"]["parameters"]
    t = result["time"]
    if kind == "Ram":  # free fall from the start: v = v0 + g (t - t0), no input force
        v0, g = parameters["Ram"]["v_impact"], parameters["Ram"]["gravity"]
        np.testing.assert_allclose(result["v_toe"], v0 + g * (t - t[0]), rtol=1e-9)
    elif kind == "PileSoil":  # at rest under the anvil weight, unloaded at t = 0: it rebounds
        assert result["u_head"][0] == 0.0 and result["u_head"][-1] < 0.0
    else:  # the anvil at rest on the pile: the contact force is its weight
        weight = system["modal"].total_mass * 9.81
        np.testing.assert_allclose(result["F_pile"], weight, rtol=1e-9)


def test_system_ssp_is_valid_ssp_1_0(system):
    from fmpy.ssp.ssd import read_ssd

    fmus = system["fmus"]
    ssd = read_ssd(str(fmus["ssp"]), validate=True)  # against the SSP 1.0 schema
    assert ssd.version == "1.0"
    assert sorted(e.name for e in ssd.system.elements) == ["Anvil", "PileSoil", "Ram"]
    connections = {(c.startElement, c.startConnector, c.endElement, c.endConnector)
                   for c in ssd.system.connections}
    assert connections == {("Ram", "u_toe", "Anvil", "u_ram"), ("Ram", "v_toe", "Anvil", "v_ram"),
                           ("PileSoil", "u_head", "Anvil", "u_pile"),
                           ("PileSoil", "v_head", "Anvil", "v_pile"),
                           ("Anvil", "F_ram", "Ram", "F_toe"),
                           ("Anvil", "F_pile", "PileSoil", "F_head")}
    with zipfile.ZipFile(fmus["ssp"]) as zf:
        assert {"resources/Ram.fmu", "resources/Anvil.fmu", "resources/PileSoil.fmu"} <= set(
            zf.namelist())
        xml = zf.read("SystemStructure.ssd").decode()
    # every parameter value of the build is in the SSP (exactly, repr round trip), the anvil's
    # input extrapolation for Jacobi masters among them, and each is the FMU's own default
    # (for tools that ignore the bindings)
    assert fmus["parameters"]["Anvil"]["input_extrapolation"] is True
    for kind in ("Ram", "Anvil", "PileSoil"):
        md = read_model_description(str(fmus[kind]))
        starts = {v.name: v.start for v in md.modelVariables if v.causality == "parameter"}
        for name, value in fmus["parameters"][kind].items():
            text = ("true" if value else "false") if isinstance(value, bool) else repr(value)
            assert f'<ssv:Parameter name="{name}">' in xml and f'value="{text}"' in xml
            assert str(starts[name]).lower() in (text, repr(float(value)) if not
                                                 isinstance(value, bool) else text)
    step = round(fmus["time_step"] * 1e9 / SSP_STEP_DIVISOR) * 1e-9
    assert f'baseStepSize="{step!r}"' in xml and "osp:FixedStepAlgorithm" in xml
    assert f'stepSize="{step!r}"' in xml and "oms:FixedStepMaster" in xml  # OMSimulator's
    assert SSP_STEP_DIVISOR <= 4  # the SSP step is at least h/4 of the fmpy master's h
    start = -FIRST_CONTACT_STEPS * fmus["ssp_step"]  # the engine's time axis: contact at 0
    assert f'startTime="{start!r}"' in xml
    assert 'name="anvilwave_table1"' in xml  # an identifier (OMSimulator)
    assert "<ssc:String" not in xml  # OMSimulator imports no String connector
    # the pythonfmu FMUs' DefaultExperiment is the SSP's
    for kind in ("Ram", "PileSoil"):
        experiment = read_model_description(str(fmus[kind])).defaultExperiment
        assert (float(experiment.startTime), float(experiment.stopTime),
                float(experiment.stepSize)) == (start, system["cfg"].duration,
                                                fmus["ssp_step"])


def test_build_rejects_an_anvil_model_without_fmus(system, tmp_path):
    cfg = system["cfg"]
    classic = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, model="classic"))
    with pytest.raises(InputError, match="'rom' or 'lumped'"):
        build_system_fmus(classic, tmp_path, system["modal"])
    assert list(tmp_path.iterdir()) == []


def test_embedded_resources_read_back_exactly(system, tmp_path):
    """hammer.toml and pile_soil.toml give the engine's arrays bit for bit (floats by repr)."""
    cfg = system["cfg"]
    (tmp_path / "hammer.toml").write_text(hammer_toml(cfg.hammer))
    hammer = load_hammer(tmp_path / "hammer.toml")
    assert np.array_equal(hammer.ram.mass, cfg.hammer.ram.mass)
    assert np.array_equal(hammer.ram.stiffness, cfg.hammer.ram.stiffness)
    assert hammer.impact_velocity == cfg.hammer.impact_velocity
    soil = dataclasses.replace(cfg.pile_soil.soil, model="lysmer-toe", toe_shear_modulus=8e7,
                               toe_density=1900.0)
    for model in (cfg.pile_soil, PileSoil(cfg.pile_soil.pile, soil)):
        (tmp_path / "pile.toml").write_text(pile_soil_toml(model))
        for a, b in zip(load_pile_soil(tmp_path / "pile.toml").arrays(), model.arrays(),
                        strict=True):
            assert np.array_equal(a, b)


def test_ram_fmu_from_the_hammer_database(system, tmp_path):
    """A Ram.fmu naming a database hammer; v_impact 0 takes the hammer's impact velocity."""
    path = build_ram_fmu(tmp_path, "illustrative_s2")
    hammer = load_hammer("illustrative_s2")
    fmu = Driven(path)
    try:
        fmu.fmu.setupExperiment(startTime=0.0)
        fmu.fmu.enterInitializationMode()
        fmu.fmu.exitInitializationMode()
        v = hammer.impact_velocity
        assert fmu.get("v_toe") == v
        # contact_displacement 0 reached in the middle of the third step (contact_mid_step):
        # before the first step the toe is out of reach, OUT_OF_REACH_TIME of free flight away
        np.testing.assert_allclose(fmu.get("u_toe"), -OUT_OF_REACH_TIME * v, rtol=1e-12)
        h = 4e-5
        fmu.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=h)
        # free flight over the step from -2.5 v h: at -1.5 v h, up to gravity (g h^2 / 2)
        np.testing.assert_allclose(fmu.get("u_toe"), -1.5 * v * h, rtol=0, atol=2 * 9.81 * h * h)
    finally:
        fmu.close()


# ---------------------------------------------------------------------------- equivalence
@pytest.mark.parametrize("model", ["rom", "lumped"])
def test_fmi_engine_equals_direct_engine(system, direct, model):
    """The native Anvil and AnvilLumped from ONE build equal the direct engine to 1e-9 of the
    peak: swapping the anvil changes no other unit."""
    native(system)
    cfg = system["cfg"].with_anvil_model(model)
    fmi = run_fmi(cfg, system["out"], fmus=system["fmus"])
    assert_same_blows(fmi, direct[model])
    f, d = fmi[0], direct[model][0]
    report = ", ".join(
        f"{name.split()[0]} {relative_difference(f.columns[name], d.columns[name]):.1e}"
        for name in FORCES)
    print(f"\n{model}: max |fmi - direct| / peak: {report}; h = {f.time_step:.4g} s, "
          f"{f.n_steps} steps; fmi {f.microseconds_per_step:.1f} us/step, direct "
          f"{1e6 * d.wall_time / d.n_steps:.1f} us/step")
    assert np.abs(d.columns["ram_anvil_force [N]"]).max() > 1e8  # the impact happened


def test_consecutive_blows_keep_the_pile_state(system):
    cfg = dataclasses.replace(system["cfg"], blows=3, duration=0.012)
    fmi = run_fmi(cfg, system["out"], fmus=system["fmus"])
    direct_blows = build_engine(cfg, system["modal"]).run()
    assert_same_blows(fmi, direct_blows)
    # the permanent set accumulates: each blow starts deeper than the one before
    starts = [b.columns["pile_head_displacement [m]"][0] for b in fmi]
    assert starts[0] < starts[1] < starts[2]


def test_soil_model_is_a_parameter_of_the_pile_fmu(system):
    """lysmer-toe swapped in by a parameter of the same PileSoil.fmu equals the engine with
    that soil; the toe differs from the smith-viscous toe (the wave reaches it at ~15 ms)."""
    cfg = system["cfg"]
    soil = dataclasses.replace(cfg.pile_soil.soil, model="lysmer-toe", toe_shear_modulus=1.0e8,
                               toe_density=2000.0, toe_poisson_ratio=0.3)
    lysmer = dataclasses.replace(cfg, pile_soil=PileSoil(cfg.pile_soil.pile, soil))
    fmi = run_fmi(lysmer, system["out"], fmus=system["fmus"],
                  parameters={"pile": {"soil_model": "lysmer-toe"}})
    assert_same_blows(fmi, build_engine(lysmer, system["modal"]).run())
    smith = run_fmi(cfg, system["out"], fmus=system["fmus"])
    toe = "pile_toe_displacement [m]"
    assert np.abs(fmi[0].columns[toe] - smith[0].columns[toe]).max() > 1e-5


def test_reset_then_second_run_is_identical(system):
    fmus = system["fmus"]
    with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"]) as master:
        first = master.run_blows(2, 400, 2.5e-5)
        second = master.run_blows(2, 400, 2.5e-5)  # fmi2Reset of all three units
    for a, b in zip(first, second, strict=True):
        assert np.array_equal(a.data, b.data, equal_nan=True)


def test_two_anvil_instances_with_their_own_parameters(system):
    """Two masters, so two Anvil instances of one FMU in one process, run in turn."""
    fmus, cfg = system["fmus"], system["cfg"]
    h, n = 2.5e-5, 400
    with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"]) as a, \
            BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"],
                       {"anvil": {"fmax": 3000.0, "static_correction": False}}) as b:
        first_a = a.run_blows(1, n, h)[0]
        only_b = b.run_blows(1, n, h)[0]
        again_a = a.run_blows(1, n, h)[0]
    assert np.array_equal(first_a.data, again_a.data, equal_nan=True)
    other = dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, fmax=3000.0,
                                                               static_correction=False),
                                time_step=h, duration=n * h)
    expected = build_engine(other, system["modal"]).run()[0]
    for name, column in (("F_ram", "ram_anvil_force [N]"), ("F_pile", "anvil_pile_force [N]")):
        assert relative_difference(only_b[name], expected.columns[column]) < 1e-6
        assert relative_difference(first_a[name], only_b[name]) > 1e-3


# ---------------------------------------------------------------------------- robustness
class Driven:
    """One FMU instance through fmpy's FMU2Slave, its log collected."""

    def __init__(self, path: Path):
        from fmpy.logging import addLoggerProxy

        md = read_model_description(str(path))
        self.variables = {v.name: v for v in md.modelVariables}
        self.messages: list[tuple[int, str]] = []
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(
            lambda env, inst, status, cat, msg: self.messages.append((status, msg.decode())))
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(ctypes.byref(self.callbacks))
        self.unzip = extract(str(path))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier,
                             instanceName="robust")
        self.fmu.instantiate(callbacks=self.callbacks)

    def set(self, **values):
        for name, value in values.items():
            var = self.variables[name]
            setter = {"Real": self.fmu.setReal, "Boolean": self.fmu.setBoolean,
                      "String": self.fmu.setString}[var.type]
            setter([var.valueReference], [value])

    def get(self, name):
        return self.fmu.getReal([self.variables[name].valueReference])[0]

    def close(self):
        try:
            self.fmu.terminate()
        except FMICallException:
            pass
        self.fmu.freeInstance()
        shutil.rmtree(self.unzip, ignore_errors=True)


@pytest.mark.parametrize("kind, parameters, reason", [
    ("Ram", {"mass": -5.0}, "mass: must be positive"),
    ("Ram", {"v_impact": -1.0}, "v_impact: must be in (0, 50] m/s"),
    ("Ram", {"hammer": "no_such_hammer"}, "is neither a hammer of the database"),
    ("PileSoil", {"segment_length": -0.5}, "pile.segment_length: must be greater than 0"),
    ("PileSoil", {"soil_model": "clay"}, "soil.model: must be one of"),
    ("PileSoil", {"static_head_load": -1.0}, "static_head_load: must be at least 0 N"),
    ("PileSoil", {"pile_soil_file": "missing.toml"}, "file not found"),
    ("Anvil", {"fmax": 100.0}, "below the first flexible mode"),
    ("AnvilLumped", {"mass": -5.0}, "mass: must be positive"),
])
def test_invalid_parameters_give_fmi2error_and_the_host_survives(system, kind, parameters,
                                                                 reason):
    path = system["fmus"][kind]
    with zipfile.ZipFile(path) as zf:
        names = zf.namelist()  # the status shim or a native unit returns fmi2Error at once
        at_once = f"binaries/linux64/{SHIM_INNER_LIBRARY}" in names or "sources/" in str(names)
    fmu = Driven(path)
    try:
        fmu.fmu.setupExperiment(startTime=0.0)
        fmu.set(**parameters)
        fmu.fmu.enterInitializationMode()
        if at_once:
            with pytest.raises(FMICallException) as error:
                fmu.fmu.exitInitializationMode()
            assert error.value.status == 3  # fmi2Error, not fmi2Fatal
        else:
            fmu.fmu.exitInitializationMode()
            with pytest.raises(FMICallException):
                fmu.fmu.doStep(0.0, 1e-5)
        assert any(status == 3 and reason in text for status, text in fmu.messages), \
            fmu.messages
        # the instance is intact: reset, initialize with the build defaults and step
        fmu.fmu.reset()
        fmu.fmu.setupExperiment(startTime=0.0)
        fmu.fmu.enterInitializationMode()
        fmu.fmu.exitInitializationMode()
        for n in range(3):
            fmu.fmu.doStep(n * 1e-5, 1e-5)
        output = {"Ram": "v_toe", "PileSoil": "v_head"}.get(kind, "F_pile")
        assert np.isfinite(fmu.get(output))
    finally:
        fmu.close()


def test_master_reports_the_reason_of_a_unit_error(system):
    fmus = system["fmus"]
    with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"],
                    {"pile": {"soil_model": "clay"}}) as master:
        with pytest.raises(CosimulationError, match="soil.model: must be one of"):
            master.run_blows(1, 10, 2.5e-5)


# ---------------------------------------------------------------------------- libcosim
FMI_TOOLS = benchmark("doc_fmi_tools")  # the tool runs of docs/data/fmi_tools.json
run_libcosim = FMI_TOOLS.run_libcosim


def fmpy_run(system, exchange: str, step_ns: int, n_steps: int, start_ns: int,
             anvil: dict | None = None):
    """The fmpy master on the SSP's units and parameter values, on libcosim's time grid."""
    fmus = system["fmus"]
    ram = system["fmus"]["parameters"]["Ram"]
    parameters = {"ram": {"contact_displacement": ram["contact_displacement"],
                          "contact_time": 0.0, "contact_mid_step": True},  # the SSP's start
                  "anvil": dict(anvil or {})}
    with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"], parameters,
                    exchange=exchange) as master:
        return master.run_blows(1, n_steps, step_ns * 1e-9, start_time=start_ns * 1e-9)[0]


def ssp_step_ns(system) -> int:
    """The step written into system.ssp in whole nanoseconds (libcosim's time unit)."""
    return max(1, round(system["fmus"]["ssp_step"] * 1e9))


@pytest.fixture(scope="module")
def libcosim_blow(system, tmp_path_factory):
    """libcosim (OSP, a Jacobi master) on system.ssp of Table 1 at the SSP's own step over the
    whole blow: (time [ns], F_ram [N], F_pile [N]) after every step."""
    pytest.importorskip("libcosimpy")
    step_ns = ssp_step_ns(system)
    n_steps = int(round(system["cfg"].duration / (step_ns * 1e-9)))
    return run_libcosim(system["fmus"]["ssp"], 0, n_steps,
                        tmp_path_factory.mktemp("libcosim") / "lc.npy")


def test_libcosim_runs_system_ssp_in_its_jacobi_exchange_order(system, libcosim_blow):
    """libcosim loads system.ssp and simulates the 25 ms blow at the step written into it.

    Its fixed-step algorithm steps every unit, then reads every output and passes it on: the
    anvil's forces are read after its step with its inputs of the step before. The fmpy master
    in that same exchange order (``exchange="jacobi"``, with the SSP's
    ``input_extrapolation``) reproduces libcosim to round-off: band 1e-9 x peak.
    """
    lc = libcosim_blow
    step_ns = ssp_step_ns(system)
    assert np.all(np.diff(lc[:, 0]) == step_ns)
    jacobi = fmpy_run(system, "jacobi", step_ns, len(lc), int(lc[0, 0]) - step_ns,
                      {"input_extrapolation": True})
    np.testing.assert_allclose(lc[:, 0] * 1e-9, jacobi.time[1:], rtol=0, atol=1e-12)
    for j, name in ((1, "F_ram"), (2, "F_pile")):
        reference = jacobi[name][1:]
        assert np.abs(reference).max() > 1e8  # the impact
        assert relative_difference(lc[:, j], reference) <= 1e-9


def test_libcosim_on_system_ssp_matches_the_fmpy_master(system, libcosim_blow):
    """The must-show of the Jacobi coupling: libcosim on system.ssp of the default Table 1
    system (modal ram unit, ROM anvil, ram-impedance contact dashpot), at the step written into
    the SSP (h/4 of the fmpy master's h), gives the peak ram and pile forces within 1 % of the
    fmpy master (DESIGN.md order) at its own step h, and within 1 % of it on the same step.

    Measured: ram +0.14 % and pile -0.06 % against the fmpy master at h, -0.03 % and -0.00 %
    on the same step. The whole time series stay within 0.12 % of the peaks on the same step
    (3.1 % before the anvil's extrapolation took the ram toe's response to the force changes,
    ``ram_toe_mass``: the dashpot's share of the contact force follows the neighbours'
    velocities; band 1 %). With table1.toml's 0.25 m pile segments the fmpy master's own peaks
    move by < 0.5 % from h to h/4; with the former 0.5 m segments the pile peak at h was 3.9 %
    above its converged value, and libcosim 3.3 % off it. The peaks are those of
    docs/data/fmi_tools.json (benchmarks/doc_fmi_tools.py, the same SSP and tool: tolerance
    :data:`tests.doc_tables.SAME_RUN`).
    """
    lc = libcosim_blow
    fmus = system["fmus"]
    assert fmus["ssp_step"] >= fmus["time_step"] / 4
    step_ns = ssp_step_ns(system)
    design = fmpy_run(system, "design", step_ns, len(lc), int(lc[0, 0]) - step_ns)
    h = fmus["time_step"]
    with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"]) as master:
        coarse = master.run_blows(1, int(round(system["cfg"].duration / h)), h)[0]
    for j, name in ((1, "F_ram"), (2, "F_pile")):
        peak, same, own = lc[:, j].max(), design[name].max(), coarse[name].max()
        band = np.abs(lc[:, j] - design[name][1:]).max() / same
        print(f"\n{name}: libcosim at h/{h / fmus['ssp_step']:.0f} {peak / 1e6:.2f} MN, fmpy "
              f"master on the same step {same / 1e6:.2f} MN ({peak / same - 1:+.3%}; "
              f"band {band:.2%}), fmpy master at h {own / 1e6:.2f} MN ({peak / own - 1:+.3%})")
        assert abs(peak / own - 1.0) <= 0.01
        assert abs(peak / same - 1.0) <= 0.01
        assert band <= 0.01  # measured 0.12 % (see above)
        assert peak == pytest.approx(doc_data("fmi_tools")["values"]["rom"]["libcosim"][j - 1],
                                     **SAME_RUN)


def test_input_extrapolation_converges_and_leaves_the_design_order_alone(system):
    """The fmpy master in libcosim's Jacobi exchange with ``input_extrapolation`` (and the
    SSP's ``ram_toe_mass``) against the DESIGN order on the same step: the largest force
    difference over the first 6 ms (impact, lift-off and re-impact of the anvil) falls at least
    3x per halving of the step from h/4 (measured 1.2e-3, 1.2e-4, 2.3e-5: 10x and 5x; without
    the toe's response to the force changes the contact dashpot's force followed the
    extrapolated velocities to first order where a contact closes: 3.1e-2, 1.5e-2, 7.1e-3);
    with the option off it is a one-step lag, tens of % at h/4. In the DESIGN order the option
    changes no bit.
    """
    h = system["fmus"]["time_step"]
    errors = {}
    for divisor in (4, 8, 16):
        step_ns = round(h * 1e9 / divisor)
        n = int(round(6e-3 / (step_ns * 1e-9)))
        design = fmpy_run(system, "design", step_ns, n, -step_ns // 2)
        jacobi = fmpy_run(system, "jacobi", step_ns, n, -step_ns // 2,
                          {"input_extrapolation": True})
        errors[divisor] = max(relative_difference(jacobi[f], design[f])
                              for f in ("F_ram", "F_pile"))
        if divisor == 4:
            lagging = fmpy_run(system, "jacobi", step_ns, n, -step_ns // 2,
                               {"input_extrapolation": False})
            assert max(relative_difference(lagging[f], design[f])
                       for f in ("F_ram", "F_pile")) > 0.1
            same = fmpy_run(system, "design", step_ns, n, -step_ns // 2,
                            {"input_extrapolation": False})
            assert np.array_equal(same.data, design.data, equal_nan=True)
    print("\nJacobi with input extrapolation vs DESIGN order, max |dF| / peak: "
          + ", ".join(f"h/{d}: {e:.2e}" for d, e in errors.items()))
    assert errors[4] <= 0.01
    assert errors[4] >= 3.0 * errors[8] and errors[8] >= 3.0 * errors[16]


# ---------------------------------------------------------------------------- outputs
def test_fmi_results_write_like_the_engines(system, tmp_path):
    """The columns of run_fmi are those of the engine (names, units, order): one writer."""
    fmi = run_fmi(system["cfg"], system["out"], fmus=system["fmus"], duration=1e-3)
    header = list(fmi[0].columns)
    assert header == list(COLUMNS)
    table = np.column_stack([fmi[0].columns[n] for n in header])
    path = tmp_path / "fmi.csv"
    np.savetxt(path, table, delimiter=",", header=",".join(header), comments="")
    assert path.read_text().splitlines()[0].startswith("time [s],")
    json.dumps({"wall_time [s]": fmi[0].wall_time, "time_step [s]": fmi[0].time_step})


# ---------------------------------------------------------------------------- the user's side
def test_fmpy_cosim_example_swaps_the_anvil_with_fmpy_alone(direct, tmp_path):
    """anvilwave/examples/fmpy_cosim.py on the FMUs of ``anvilwave build-fmus
    anvilwave/examples/table1.toml``: its
    own master loop (fmpy only: ``import anvilwave`` is made to fail) runs Anvil.fmu, then
    AnvilLumped.fmu swapped in, and plots the pile-head force. Its loop is the DESIGN order with
    the engine's initialisation, so its peaks are the direct engine's (printed to 1 kN)."""
    from anvilwave.cli import main

    fmus, figure = tmp_path / "fmus", tmp_path / "pile_head_force.png"
    assert main(["build-fmus", str(EXAMPLES / "table1.toml"), "--out", str(fmus)]) == 0
    script = EXAMPLES / "fmpy_cosim.py"
    code = ("import runpy, sys; sys.modules['anvilwave'] = None; "
            f"sys.argv = [{str(script)!r}, {str(fmus)!r}, '--plot', {str(figure)!r}]; "
            f"runpy.run_path({str(script)!r}, run_name='__main__')")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    print("\n" + run.stdout)
    peaks = {line.split(":")[0]: float(line.split("force ")[1].split(" MN")[0])
             for line in run.stdout.splitlines() if "peak pile-head force" in line}
    assert list(peaks) == ["Anvil.fmu (modal ROM)", "AnvilLumped.fmu (rigid)"]
    for (label, peak), model in zip(peaks.items(), ("rom", "lumped"), strict=True):
        expected = direct[model][0].columns["anvil_pile_force [N]"].max() / 1e6
        assert peak == pytest.approx(expected, abs=1.5e-3), label  # printed to 1 kN
    assert figure.stat().st_size > 10_000


def test_build_fmus_needs_no_c_compiler(system, direct, tmp_path, monkeypatch, capsys):
    """build-fmus on a machine without a C compiler (PATH without cc, gcc or mingw-w64, CC
    unset) writes the four native FMUs, each with its Linux x86-64 and Windows x64 binary (the
    shipped ones), valid for fmpy; under the fmpy master of ``impact --engine fmi``
    (:func:`run_fmi`) they give the direct engine's blows to 1e-9 of each column's peak, the
    tolerance of test_fmi_engine_equals_direct_engine (the same kernels in the same order:
    round-off only)."""
    from anvilwave.cli import main

    bare = tmp_path / "bin"
    bare.mkdir()
    monkeypatch.setenv("PATH", str(bare))
    monkeypatch.delenv("CC", raising=False)
    assert not any(shutil.which(name) for name in ("cc", "gcc", "x86_64-w64-mingw32-gcc"))
    out = tmp_path / "fmus"
    assert main(["build-fmus", str(EXAMPLES / "table1.toml"), "--out", str(out)]) == 0
    assert "anvils: native, ram: native, pile/soil: native" in capsys.readouterr().out
    built = {kind: out / f"{kind}.fmu" for kind in KINDS}
    for kind, path in built.items():
        assert validate_fmu(str(path)) == [], kind
        with zipfile.ZipFile(path) as zf:
            names = set(zf.namelist())
        assert {f"binaries/linux64/{kind}.so", f"binaries/win64/{kind}.dll",
                "resources/anvilwave_unit.txt"} <= names, kind
    monkeypatch.undo()
    fmus = {**system["fmus"], **built}
    for model in ("rom", "lumped"):
        fmi = run_fmi(system["cfg"].with_anvil_model(model), tmp_path, fmus=fmus)
        assert_same_blows(fmi, direct[model])
        print(f"\n{model}: peak ram-anvil force {fmi[0].columns[FORCES[0]].max() / 1e6:.3f} MN "
              f"(direct {direct[model][0].columns[FORCES[0]].max() / 1e6:.3f} MN)")


def test_python_anvils_give_the_native_numbers(system, tmp_path):
    """native_anvil=False (build-fmus --python-anvil) builds the pythonfmu anvils under the
    same names; swapped into the fmpy master they give the native anvil's forces (one formula,
    two implementations). 1e-11 of the peak over 400 coupled steps: the kernels agree to
    1e-13 on the same inputs (tests/test_native_anvil.py); numpy's BLAS dot products and
    vectorised exp against the C loops differ in the last bit, and the contact exchanges
    carry those bits forward (2e-12 seen)."""
    native(system)
    python = build_system_fmus(system["cfg"], tmp_path, system["modal"], ssp=False,
                               native_anvil=False)
    assert python["anvil_implementation"] == "pythonfmu"
    fmus = system["fmus"]
    for kind in ("Anvil", "AnvilLumped"):
        with zipfile.ZipFile(python[kind]) as zf:
            assert "resources/pythonfmu/__init__.py" in zf.namelist()
        blows = []
        for anvil in (fmus[kind], python[kind]):
            with BlowMaster(fmus["Ram"], anvil, fmus["PileSoil"]) as master:
                blows.append(master.run_blows(1, 400, fmus["time_step"])[0])
        for name in ("F_ram", "F_pile"):
            assert relative_difference(blows[1][name], blows[0][name]) <= 1e-11, (kind, name)


STEP_MULTIPLES = (1, 2, 4)
"""Master steps over the FMUs' DefaultExperiment step h_d (the SSP's: the engine's step / 4)."""


@pytest.fixture(scope="module")
def native_ram_system(system, tmp_path_factory):
    """Table 1's FMUs with the native Ram (and PileSoil), when they can be built here."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fmus = build_system_fmus(system["cfg"], tmp_path_factory.mktemp("native_ram"),
                                 system["modal"], native_anvil=None, ssp=False)
    if fmus["ram_implementation"] != "native":
        pytest.skip("the native Ram is not built here (its shipped binaries are not current)")
    return fmus


@pytest.mark.parametrize("ram", ["pythonfmu", "native"])
def test_ram_first_contact_at_multiples_of_the_default_step(system, native_ram_system, ram):
    """The ram places its first contact (contact_mid_step) from the master's first step, not
    from its DefaultExperiment: Table 1 (modal ram, ROM anvil) under the fmpy master (DESIGN.md
    order) at h = 1, 2 and 4 h_d, from the SSP's start (-2.5 h), 0 and 0.37 h, gives the peak
    ram-anvil and anvil-pile forces of the engine run at the same step h (the reference: the
    step changes the discretisation) within 1e-3. Measured: +0.002 %, +0.003 %, +0.006 % at
    1, 2, 4 h_d for both, from every start (the same bits), pythonfmu and native Ram alike:
    the ram flies 2 steps longer than the engine's (which starts h/2 before the contact), so
    gravity adds 2 g h to its impact velocity, 2 g h / v = 6.5e-5 at 20 us. Before the ram
    deferred its placement to the first step, the ram peak at 4 h_d was -4.3 % (it placed the
    toe h_d / 2 before the contact whatever the master's step). The issue's bar is 0.5 %."""
    native(system)  # the ROM anvil of both systems is the native one
    fmus = system["fmus"] if ram == "pythonfmu" else native_ram_system
    assert fmus["ram_implementation"] == ram
    cfg, h_d = system["cfg"], system["fmus"]["ssp_step"]
    assert read_model_description(str(fmus["Ram"])).defaultExperiment.stepSize == repr(h_d)
    for multiple in STEP_MULTIPLES:
        h = multiple * h_d
        blow = build_engine(dataclasses.replace(cfg, time_step=h), system["modal"]).run()[0]
        engine = np.array([blow.columns[name].max() for name in FORCES])
        n = int(round(cfg.duration / h)) + 3  # the contact 2 steps later than the engine's
        for start in (-FIRST_CONTACT_STEPS * h, 0.0, 0.37 * h):
            with BlowMaster(fmus["Ram"], fmus["Anvil"], fmus["PileSoil"],
                            {"ram": {"contact_mid_step": True}}) as master:
                record = master.run_blows(1, n, h, start_time=start)[0]
            peaks = np.array([np.nanmax(record["F_ram"]), np.nanmax(record["F_pile"])])
            print(f"\n{ram} Ram, h = {multiple} h_d, start {start / h:+.2f} h: peaks "
                  f"{peaks[0] / 1e6:.3f}, {peaks[1] / 1e6:.3f} MN, against the engine "
                  f"{100 * (peaks[0] / engine[0] - 1):+.4f} %, "
                  f"{100 * (peaks[1] / engine[1] - 1):+.4f} %")
            np.testing.assert_allclose(peaks, engine, rtol=1e-3)
