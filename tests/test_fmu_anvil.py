"""Anvil FMUs built with pythonfmu and driven through fmpy; the generic master on a 3-unit chain.

The FMUs are built once per module from a coarse modal-data file of the s2 anvil (mesh 0.03 m,
modes to 20 kHz: about 50 modes, computed in well under a second).
"""

from __future__ import annotations

import ctypes
import importlib.util
import shutil
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

from anvilwave.anvil_rom.fem.geometry import load_anvil  # noqa: E402
from anvilwave.anvil_rom.fem.modalfile import load_modal_data, save_modal_data  # noqa: E402
from anvilwave.anvil_rom.rom import ModalAnvil  # noqa: E402
from anvilwave.anvil_rom.unit import AnvilUnit, ContactParameters  # noqa: E402
from anvilwave.config.cache import cached_modal_data  # noqa: E402
from anvilwave.fmu.fmi_build import SHIM_INNER_LIBRARY, build_anvil_fmu, build_fmu  # noqa: E402
from anvilwave.fmu.fmi_master import ChainMaster, CosimulationError  # noqa: E402
from anvilwave.inputs import InputError  # noqa: E402

from .conftest import EXAMPLES  # noqa: E402

CONTACTS = {"ram_contact_stiffness": 2.0e10, "pile_contact_stiffness": 3.0e10}  # [N/m]
INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")
OUTPUTS = ("F_ram", "F_pile", "u_top", "u_bottom")

# Throwaway Ram and PileSoil units with the DESIGN.md interfaces, for the master. Each script
# has a module name of its own (pythonfmu runs the first loaded module of a name).
RAM_SCRIPT = '''"""Test Ram FMU: a rigid ram in free flight (exact, force held over the step)."""

from anvilwave.fmu.units.base import UnitSlave, pin_namespace

pin_namespace(globals())


class RigidBody:
    def __init__(self, mass, velocity, gravity):
        self.mass, self.u, self.v, self.gravity = mass, 0.0, velocity, gravity

    def step(self, force, h):
        a = self.gravity - force / self.mass
        self.u += self.v * h + 0.5 * a * h * h
        self.v += a * h


class TestRigidRam(UnitSlave):
    kind = "TestRigidRam"
    parameter_fallbacks = {"mass": 1000.0, "v_impact": 5.0, "gravity": 9.81}

    def register_variables(self):
        self.add_parameter("mass", "kg", "Ram mass [kg]")
        self.add_parameter("v_impact", "m/s", "Impact velocity [m/s]")
        self.add_parameter("gravity", "m/s2", "Gravitational acceleration [m/s^2]")
        self.add_input("F_toe", "N", "Ram-anvil force on the toe, compression positive [N]")
        self.add_output("u_toe", "m", "Toe displacement, positive down [m]")
        self.add_output("v_toe", "m/s", "Toe velocity, positive down [m/s]")

    def build_component(self):
        p = self.parameters
        return RigidBody(p["mass"], p["v_impact"], p["gravity"])

    def compute_outputs(self, inputs, outputs):
        outputs[0] = self.component.u
        outputs[1] = self.component.v

    def advance(self, h):
        self.component.step(self.inputs[0], h)
'''

PILE_SCRIPT = '''"""Test PileSoil FMU: a dashpot Z, v = F / Z (force of the step held)."""

from anvilwave.fmu.units.base import UnitSlave, pin_namespace

pin_namespace(globals())


class Dashpot:
    def __init__(self, impedance):
        self.impedance, self.u, self.v, self.force = impedance, 0.0, 0.0, 0.0

    def step(self, force, h):
        self.force = force
        self.v = force / self.impedance
        self.u += self.v * h


class TestDashpotPile(UnitSlave):
    kind = "TestDashpotPile"
    parameter_fallbacks = {"impedance": 1.0e7}

    def register_variables(self):
        self.add_parameter("impedance", "N.s/m", "Pile impedance E A / c [N s/m]")
        self.add_input("F_head", "N", "Anvil-pile force on the head, compression positive [N]")
        self.add_output("u_head", "m", "Head displacement, positive down [m]")
        self.add_output("v_head", "m/s", "Head velocity, positive down [m/s]")
        self.add_output("F_gauge", "N", "Gauge force, compression positive [N]")
        self.add_output("v_gauge", "m/s", "Gauge velocity, positive down [m/s]")

    def build_component(self):
        return Dashpot(self.parameters["impedance"])

    def compute_outputs(self, inputs, outputs):
        c = self.component
        outputs[0], outputs[1], outputs[2], outputs[3] = c.u, c.v, c.force, c.v

    def advance(self, h):
        self.component.step(self.inputs[0], h)
'''


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The modal-data file and the four FMUs, built once."""
    root = tmp_path_factory.mktemp("fmu_anvil")
    spec = load_anvil(EXAMPLES / "anvils" / "s2.toml")
    spec = type(spec)(**{**spec.__dict__, "mesh_size": 0.03})
    # the session's modal-data cache: the same entry as test_native_anvil's
    modal = save_modal_data(cached_modal_data(spec, 20000.0),
                            root / "modes.npz")
    out = root / "fmus"
    scripts = {}
    for name, text in (("anvilwave_test_rigid_ram.py", RAM_SCRIPT),
                       ("anvilwave_test_dashpot_pile.py", PILE_SCRIPT)):
        scripts[name] = root / name
        scripts[name].write_text(text)
    return {
        "modal": modal,
        "data": load_modal_data(modal),
        "Anvil": build_anvil_fmu(modal, out, **CONTACTS),
        "AnvilLumped": build_anvil_fmu(modal, out, lumped=True, **CONTACTS),
        "Ram": build_fmu(scripts["anvilwave_test_rigid_ram.py"], out),
        "Pile": build_fmu(scripts["anvilwave_test_dashpot_pile.py"], out),
        "scripts": scripts,
        "root": root,
    }


class Driven:
    """One FMU instance driven through fmpy's FMU2Slave, with its log collected."""

    def __init__(self, path: Path, name: str = "instance"):
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
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate(callbacks=self.callbacks)
        self.vr_in = [self.variables[n].valueReference for n in INPUTS]
        self.vr_out = [self.variables[n].valueReference for n in OUTPUTS]

    def set(self, **values):
        for name, value in values.items():
            var = self.variables[name]
            setter = {"Real": self.fmu.setReal, "Boolean": self.fmu.setBoolean,
                      "String": self.fmu.setString}[var.type]
            setter([var.valueReference], [value])

    def initialize(self, **parameters):
        self.fmu.setupExperiment(startTime=0.0)
        self.set(**parameters)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def run(self, inputs: np.ndarray, steps: np.ndarray) -> np.ndarray:
        """Outputs read after setting inputs[n], then a step of steps[n] [s] (master order)."""
        out = np.empty((len(inputs), 4))
        t = np.concatenate([[0.0], np.cumsum(steps)])
        for n in range(len(inputs)):
            self.fmu.setReal(self.vr_in, list(inputs[n]))
            out[n] = self.fmu.getReal(self.vr_out)
            self.fmu.doStep(t[n], steps[n])
        return out

    def close(self):
        try:
            self.fmu.terminate()
        except FMICallException:
            pass
        self.fmu.freeInstance()
        shutil.rmtree(self.unzip, ignore_errors=True)


def reference_unit(data, fmax=None, static_correction=False, ram_contact_damping=0.0,
                   lumped=False):
    """The AnvilUnit object the FMU should reproduce, resting on the pile."""
    anvil = (ModalAnvil.rigid(data.total_mass) if lumped else
             ModalAnvil.from_modal_data(data, fmax=fmax, damping_ratio=data.damping_ratio,
                                        static_correction=static_correction))
    contact = ContactParameters(CONTACTS["ram_contact_stiffness"],
                                CONTACTS["pile_contact_stiffness"], ram_damping=ram_contact_damping)
    unit = AnvilUnit(anvil, contact)
    unit.rest_on_pile(0.0)
    return unit


def run_reference(unit, inputs, steps):
    out = np.empty((len(inputs), 4))
    for n, (u_ram, v_ram, u_pile, v_pile) in enumerate(inputs):
        force_ram, force_pile = unit.forces(u_ram, v_ram, u_pile, v_pile)
        u_top, _, u_bottom, _ = unit.outputs(force_ram, force_pile)
        out[n] = force_ram, force_pile, u_top, u_bottom
        unit.step(force_ram, force_pile, steps[n])
    return out


def blow_inputs(u_top0, n=1500):
    """A ram toe that hits the anvil, decelerates and lifts off; a pile head that oscillates.

    Steps alternate between 1 and 2.5 us: the anvil must take any communication step.
    """
    steps = np.where(np.arange(n) % 2 == 0, 1.0e-6, 2.5e-6)
    t = np.concatenate([[0.0], np.cumsum(steps)[:-1]])
    u_ram = u_top0 - 1e-6 + 4.0 * t - 1.5e4 * t**2
    v_ram = 4.0 - 3.0e4 * t
    w = 2 * np.pi * 400.0
    u_pile = 2.0e-4 * np.sin(w * t)
    v_pile = 2.0e-4 * w * np.cos(w * t)
    return np.column_stack([u_ram, v_ram, u_pile, v_pile]), steps


def assert_same(actual, expected):
    # The FMU runs the very same kernels in the same order, so the numbers agree to the last
    # bit; the tolerance only admits round-off (1e-12 of the largest value of each column).
    scale = np.abs(expected).max(axis=0)
    np.testing.assert_allclose(actual, expected, rtol=1e-12, atol=0.0)
    assert np.all(np.abs(actual - expected) <= 1e-12 * scale)


# ---------------------------------------------------------------------------- the FMU files
@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped", "Ram", "Pile"])
def test_fmus_validate_without_problems(built, kind):
    assert validate_fmu(str(built[kind])) == []


def test_model_description_units_and_structure(built):
    md = read_model_description(str(built["Anvil"]))
    var = {v.name: v for v in md.modelVariables}
    assert {n: var[n].unit for n in INPUTS + OUTPUTS} == {
        "u_ram": "m", "v_ram": "m/s", "u_pile": "m", "v_pile": "m/s",
        "F_ram": "N", "F_pile": "N", "u_top": "m", "u_bottom": "m"}
    assert var["fmax"].unit == "Hz" and var["pile_contact_damping"].unit == "N.s/m"
    units = {u.name: u.baseUnit for u in md.unitDefinitions}
    assert (units["N"].kg, units["N"].m, units["N"].s) == (1, 1, -2)
    assert all("[" in v.description for v in md.modelVariables)
    # the contact forces are a direct feedthrough of all four inputs (static correction couples
    # the two contacts); for the rigid anvil each force sees only its own contact
    deps = {u.variable.name: {d.name for d in u.dependencies} for u in md.outputs}
    assert deps["F_ram"] == deps["F_pile"] == set(INPUTS)
    lumped = read_model_description(str(built["AnvilLumped"]))
    deps = {u.variable.name: {d.name for d in u.dependencies} for u in lumped.outputs}
    assert deps == {"F_ram": {"u_ram", "v_ram"}, "F_pile": {"u_pile", "v_pile"},
                    "u_top": set(), "u_bottom": set()}
    assert {u.variable.name for u in md.initialUnknowns} == set(OUTPUTS)
    with zipfile.ZipFile(built["Anvil"]) as zf:
        names = set(zf.namelist())
    assert {"resources/modes.npz", "resources/anvilwave_anvil_rom.py"} <= names


@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
def test_simulate_alone_rests_on_the_pile(built, kind):
    result = simulate_fmu(str(built[kind]), stop_time=1e-3)
    weight = built["data"].total_mass * 9.81
    assert np.all(result["F_ram"] == 0.0)  # the ram (u_ram = 0) is above the top face
    # static equilibrium is exact up to round-off, and stays so
    np.testing.assert_allclose(result["F_pile"], weight, rtol=1e-9)
    np.testing.assert_allclose(result["u_top"], result["u_top"][0], rtol=1e-9)


def test_build_rejects_bad_parameters_and_writes_nothing(built, tmp_path):
    with pytest.raises(InputError, match="mass"):
        build_fmu("AnvilLumped", tmp_path, {"mass": -1.0, **CONTACTS})
    with pytest.raises(InputError, match="not a parameter"):
        build_anvil_fmu(built["modal"], tmp_path, stiffness=1.0, **CONTACTS)
    with pytest.raises(InputError, match="first flexible mode"):
        build_anvil_fmu(built["modal"], tmp_path, fmax=100.0, **CONTACTS)
    with pytest.raises(InputError, match="'mass' has no default"):
        build_fmu("AnvilLumped", tmp_path, CONTACTS)
    with pytest.raises(InputError, match="must be true or false"):
        build_anvil_fmu(built["modal"], tmp_path, static_correction="yes", **CONTACTS)
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------- exactness
@pytest.mark.parametrize("lumped", [False, True])
def test_fmu_gives_exactly_the_anvil_unit_results(built, lumped):
    options = {} if lumped else {"fmax": 8000.0, "static_correction": True}
    unit = reference_unit(built["data"], lumped=lumped, **options)
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0])
    expected = run_reference(unit, inputs, steps)
    assert expected[:, 0].max() > 1e6 and expected[-1, 0] == 0.0  # impact, then lift-off
    fmu = Driven(built["AnvilLumped" if lumped else "Anvil"])
    try:
        fmu.initialize(**options)
        actual = fmu.run(inputs, steps)
    finally:
        fmu.close()
    assert_same(actual, expected)


def test_reset_then_second_run_is_identical(built):
    unit = reference_unit(built["data"])
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0], n=600)
    fmu = Driven(built["Anvil"])
    try:
        fmu.initialize(static_correction=True)
        first = fmu.run(inputs, steps)
        fmu.fmu.reset()
        fmu.initialize(static_correction=True)
        second = fmu.run(inputs, steps)
    finally:
        fmu.close()
    assert np.array_equal(first, second)


def test_two_instances_keep_their_own_parameters(built):
    options_b = {"fmax": 5000.0, "static_correction": True, "ram_contact_damping": 2.0e5}
    unit_a, unit_b = reference_unit(built["data"]), reference_unit(built["data"], **options_b)
    inputs, steps = blow_inputs(unit_a.outputs(0.0, 0.0)[0], n=600)
    expected_a = run_reference(unit_a, inputs, steps)
    expected_b = run_reference(unit_b, inputs, steps)
    a, b = Driven(built["Anvil"], "a"), Driven(built["Anvil"], "b")
    try:
        a.initialize()
        b.initialize(**options_b)
        out_a, out_b = np.empty_like(expected_a), np.empty_like(expected_b)
        t = np.concatenate([[0.0], np.cumsum(steps)])
        for n in range(len(inputs)):  # interleaved, call by call
            for fmu, out in ((a, out_a), (b, out_b)):
                fmu.fmu.setReal(fmu.vr_in, list(inputs[n]))
                out[n] = fmu.fmu.getReal(fmu.vr_out)
                fmu.fmu.doStep(t[n], steps[n])
    finally:
        a.close()
        b.close()
    assert_same(out_a, expected_a)
    assert_same(out_b, expected_b)
    assert np.abs(out_a[:, 0] - out_b[:, 0]).max() > 1e-3 * np.abs(out_a[:, 0]).max()


def test_two_builds_in_one_process_keep_their_own_defaults(built, tmp_path):
    """Same slave module name, different builds: the defaults come from each FMU's resources."""
    other = build_anvil_fmu(built["modal"], tmp_path, ram_contact_stiffness=5.0e9,
                            pile_contact_stiffness=CONTACTS["pile_contact_stiffness"])
    first, second = Driven(built["Anvil"], "first"), Driven(other, "second")
    try:
        stiffness = [d.fmu.getReal([d.variables["ram_contact_stiffness"].valueReference])[0]
                     for d in (first, second)]
    finally:
        first.close()
        second.close()
    assert stiffness == [CONTACTS["ram_contact_stiffness"], 5.0e9]


# ---------------------------------------------------------------------------- robustness
def _has_status_shim(path: Path) -> bool:
    with zipfile.ZipFile(path) as zf:
        return f"binaries/linux64/{SHIM_INNER_LIBRARY}" in zf.namelist()


@pytest.mark.parametrize("kind, parameters, reason", [
    ("Anvil", {"fmax": 100.0}, "below the first flexible mode"),
    ("Anvil", {"modal_data_file": "missing.npz"}, "modal-data file not found"),
    ("Anvil", {"pile_contact_stiffness": -1.0}, "pile_stiffness: must be positive"),
    ("AnvilLumped", {"mass": -5.0}, "mass: must be positive"),
    ("AnvilLumped", {"ram_toe_mass": -1.0}, "ram_toe_mass: must be >= 0 [kg], got -1"),
])
def test_invalid_parameters_give_fmi2error_with_the_reason(built, kind, parameters, reason):
    fmu = Driven(built[kind])
    try:
        fmu.fmu.setupExperiment(startTime=0.0)
        fmu.set(**parameters)
        fmu.fmu.enterInitializationMode()
        if _has_status_shim(built[kind]):
            with pytest.raises(FMICallException) as error:
                fmu.fmu.exitInitializationMode()
            assert error.value.status == 3  # fmi2Error, not fmi2Fatal
        else:  # stock pythonfmu binary: the error shows at the first step (fmi2Discard)
            fmu.fmu.exitInitializationMode()
            with pytest.raises(FMICallException):
                fmu.fmu.doStep(0.0, 1e-6)
        assert any(status == 3 and reason in text for status, text in fmu.messages), \
            fmu.messages
        # the instance is intact: reset, initialize with the build defaults and step
        fmu.fmu.reset()
        fmu.initialize()
        fmu.fmu.doStep(0.0, 1e-6)
        weight = built["data"].total_mass * 9.81
        assert fmu.fmu.getReal([fmu.vr_out[1]])[0] == pytest.approx(weight, rel=1e-9)
    finally:
        fmu.close()


def test_error_during_a_step_is_reported_and_the_host_survives(built):
    fmu = Driven(built["Anvil"])
    try:
        fmu.initialize()
        with pytest.raises(FMICallException) as error:
            fmu.fmu.doStep(0.0, -1e-6)
        assert error.value.status == (3 if _has_status_shim(built["Anvil"]) else 2)
        assert any("communication step" in text for _, text in fmu.messages)
    finally:
        fmu.close()


# ---------------------------------------------------------------------------- the master
def _load_script(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_master_runs_the_chain_in_the_design_step_order(built):
    """The fmpy master on Ram - Anvil - Pile FMUs equals the same chain run in Python."""
    ram_mass, v_impact, impedance, h, n_steps = 300.0, 5.0, 2.0e7, 1.0e-6, 3000
    parameters = {"ram": {"mass": ram_mass, "v_impact": v_impact},
                  "anvil": {"static_correction": True}, "pile": {"impedance": impedance}}
    with ChainMaster(built["Ram"], built["Anvil"], built["Pile"], parameters) as master:
        result = master.run(n_steps, h)
        again = master.run(n_steps, h, record_every=7)
    # the same chain in Python, with the test units' own component classes
    ram = _load_script(built["scripts"]["anvilwave_test_rigid_ram.py"], "_ram").RigidBody(
        ram_mass, v_impact, 9.81)
    pile = _load_script(built["scripts"]["anvilwave_test_dashpot_pile.py"], "_pile").Dashpot(
        impedance)
    anvil = AnvilUnit(ModalAnvil.from_modal_data(built["data"], static_correction=True),
                      ContactParameters(**{k.replace("_contact", ""): v
                                           for k, v in CONTACTS.items()}))
    anvil.rest_on_pile(0.0)
    expected = np.empty((n_steps + 1, 11))
    for n in range(n_steps + 1):
        force_ram, force_pile = anvil.forces(ram.u, ram.v, pile.u, pile.v)
        u_top, _, u_bottom, _ = anvil.outputs(force_ram, force_pile)
        expected[n] = (n * h, ram.u, ram.v, pile.u, pile.v, pile.force, pile.v, force_ram,
                       force_pile, u_top, u_bottom)
        if n < n_steps:
            ram.step(force_ram, h)
            anvil.step(force_ram, force_pile, h)
            pile.step(force_pile, h)
    assert result.data.shape == (n_steps + 1, 11)
    assert result.header[:2] == ["time [s]", "ram_toe_displacement [m]"]
    assert result["ram_anvil_force"].max() > 1e6  # the blow happened
    assert_same(result.data, expected)
    rows = list(range(0, n_steps + 1, 7)) + [n_steps]
    assert np.array_equal(again.data, result.data[rows])  # reset between runs
    print(f"\nfmpy master, 3 pythonfmu units: {result.microseconds_per_step:.1f} us per step")


def test_master_reports_a_unit_error(built):
    parameters = {"anvil": {"fmax": 100.0}}
    with ChainMaster(built["Ram"], built["Anvil"], built["Pile"], parameters) as master:
        with pytest.raises(CosimulationError, match="first flexible mode"):
            master.run(10, 1e-6)
