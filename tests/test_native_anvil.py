"""The native (C) anvil FMUs of :mod:`anvilwave.fmu.native_build`: the numbers of the Python
kernels, a
clean validation, errors as fmi2Error with the reason, a plain C host without Python, and the
FMI 3.0 variant bit for bit.

The FMUs are built once per module from a coarse modal-data file of the s2 anvil (mesh 0.03 m,
modes to 20 kHz: about 50 modes), as in ``test_fmu_anvil.py``. Building needs no C compiler
(the shipped binaries); the tests that compile the sources or a C host skip without one.
"""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")

from fmpy import calloc, extract, free, read_model_description, simulate_fmu  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import (  # noqa: E402
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.model_description import read_build_description  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

from anvilwave.anvil_rom.fem.geometry import load_anvil  # noqa: E402
from anvilwave.anvil_rom.rom import ModalAnvil  # noqa: E402
from anvilwave.anvil_rom.unit import AnvilUnit, ContactParameters  # noqa: E402
from anvilwave.config.cache import cached_modal_data  # noqa: E402
from anvilwave.fmu.native_build import (  # noqa: E402
    MODAL_RESOURCE,
    NativeBuildError,
    build_native_anvil_fmu,
    find_compiler,
    modal_resource_bytes,
    native_modal_data,
    read_modal_resource,
)
from anvilwave.inputs import InputError  # noqa: E402

from .conftest import EXAMPLES, ROOT  # noqa: E402

CONTACTS = {"ram_contact_stiffness": 2.0e10, "pile_contact_stiffness": 3.0e10}  # [N/m]
INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")
OUTPUTS = ("F_ram", "F_pile", "u_top", "u_bottom")
HOST_SOURCE = ROOT / "tests" / "c_host" / "fmi_host.c"
NATIVE_DIR = ROOT / "anvilwave" / "fmu" / "native"


def _compiler() -> str:
    try:
        return find_compiler()
    except NativeBuildError as exc:
        pytest.skip(f"native FMUs need a C compiler: {exc}")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The modal data and the native Anvil / AnvilLumped FMUs, built once."""
    root = tmp_path_factory.mktemp("native_anvil")
    spec = load_anvil(EXAMPLES / "anvils" / "s2.toml")
    spec = type(spec)(**{**spec.__dict__, "mesh_size": 0.03})
    data = cached_modal_data(spec, 20000.0)  # the session's cache: shared with test_fmu_anvil
    out = root / "fmus"
    return {
        "data": data,
        "Anvil": build_native_anvil_fmu(data, out, **CONTACTS),
        "AnvilLumped": build_native_anvil_fmu(data, out, lumped=True, **CONTACTS),
        "root": root,
    }


class Driven:
    """One FMU instance driven through fmpy's FMU2Slave, with its log collected."""

    def __init__(self, path: Path, name: str = "instance", guid: str | None = None,
                 instantiate: bool = True):
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
        self.fmu = FMU2Slave(guid=guid or md.guid, unzipDirectory=self.unzip,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        if instantiate:
            self.fmu.instantiate(callbacks=self.callbacks)
        self.vr_in = [self.variables[n].valueReference for n in INPUTS]
        self.vr_out = [self.variables[n].valueReference for n in OUTPUTS]

    def vr(self, name: str) -> int:
        return self.variables[name].valueReference

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

    def errors(self) -> list[str]:
        return [text for status, text in self.messages if status >= 3]

    def close(self):
        try:
            self.fmu.terminate()
        except FMICallException:
            pass
        self.fmu.freeInstance()
        shutil.rmtree(self.unzip, ignore_errors=True)


def reference_unit(anvil: ModalAnvil, ram_contact_damping: float = 0.0) -> AnvilUnit:
    """The Python AnvilUnit the FMU should reproduce, resting on the pile."""
    contact = ContactParameters(CONTACTS["ram_contact_stiffness"],
                                CONTACTS["pile_contact_stiffness"], ram_damping=ram_contact_damping)
    unit = AnvilUnit(anvil, contact)
    unit.rest_on_pile(0.0)
    return unit


def run_reference(unit: AnvilUnit, inputs: np.ndarray, steps) -> np.ndarray:
    """The master's order on the Python kernels: forces and outputs at t_n, then the step."""
    steps = np.broadcast_to(steps, (len(inputs),))
    out = np.empty((len(inputs), 4))
    for n, (u_ram, v_ram, u_pile, v_pile) in enumerate(inputs):
        force_ram, force_pile = unit.forces(u_ram, v_ram, u_pile, v_pile)
        u_top, _, u_bottom, _ = unit.outputs(force_ram, force_pile)
        out[n] = force_ram, force_pile, u_top, u_bottom
        unit.step(force_ram, force_pile, float(steps[n]))
    return out


def blow_inputs(u_top0: float, n: int = 1000):
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


def run_native(path: Path, parameters: dict, inputs: np.ndarray, steps) -> np.ndarray:
    """The outputs of one instance of the FMU at ``path`` (initialized with ``parameters``)
    driven through the blow (:meth:`Driven.run`)."""
    fmu = Driven(path)
    try:
        fmu.initialize(**parameters)
        return fmu.run(inputs, steps)
    finally:
        fmu.close()


def relative_difference(actual: np.ndarray, expected: np.ndarray) -> float:
    """Largest difference relative to the largest value of its column."""
    scale = np.abs(expected).max(axis=0)
    return float((np.abs(actual - expected) / scale).max())


# ---------------------------------------------------------------------------- exactness
ROM_CASES = {
    # name: (FMU parameters, ModalAnvil.from_modal_data options, ram contact dashpot [N s/m])
    "all modes": ({}, {}, 0.0),
    "fmax 8 kHz, static correction": ({"fmax": 8000.0, "static_correction": True},
                                      {"fmax": 8000.0, "static_correction": True}, 0.0),
    "damped, dashpot, static correction": (
        {"damping_ratio": 0.02, "static_correction": True, "ram_contact_damping": 2.0e5},
        {"damping_ratio": 0.02, "static_correction": True}, 2.0e5),
}


@pytest.mark.parametrize("case", list(ROM_CASES))
def test_rom_outputs_equal_the_python_kernels(built, case):
    parameters, options, dashpot = ROM_CASES[case]
    data = built["data"]
    options = {"damping_ratio": data.damping_ratio, **options}
    unit = reference_unit(ModalAnvil.from_modal_data(data, **options), dashpot)
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0])
    expected = run_reference(unit, inputs, steps)
    assert expected[:, 0].max() > 1e6 and expected[-1, 0] == 0.0  # impact, then lift-off
    difference = relative_difference(run_native(built["Anvil"], parameters, inputs, steps),
                                     expected)
    print(f"\nnative Anvil vs Python kernels ({case}): max relative difference {difference:.2e}")
    # Same formulas in the same order; what is left is round-off: numpy's BLAS dot (the rest
    # state) and its SIMD exp (damped modes) may differ from a plain sum / libm in the last
    # bit, and the contact events and step changes of this blow carry that forward.
    assert difference <= 1e-12


def test_lumped_outputs_equal_the_python_kernels(built):
    unit = reference_unit(ModalAnvil.rigid(built["data"].total_mass))
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0])
    expected = run_reference(unit, inputs, steps)
    fmu = Driven(built["AnvilLumped"])
    try:
        fmu.initialize()
        actual = fmu.run(inputs, steps)
    finally:
        fmu.close()
    difference = relative_difference(actual, expected)
    print(f"\nnative AnvilLumped vs Python kernels: max relative difference {difference:.2e}")
    assert difference <= 1e-12


def run_jacobi(fmu: Driven, inputs: np.ndarray, steps: np.ndarray) -> np.ndarray:
    """A Jacobi master's order (libcosim's): the outputs read after each step, with the inputs
    of the step before, then the new inputs, then the step."""
    out = np.empty((len(inputs), 4))
    t = np.concatenate([[0.0], np.cumsum(steps)])
    fmu.fmu.setReal(fmu.vr_in, list(inputs[0]))
    for n in range(len(inputs)):
        out[n] = fmu.fmu.getReal(fmu.vr_out)
        fmu.fmu.setReal(fmu.vr_in, list(inputs[n]))
        fmu.fmu.doStep(t[n], steps[n])
    return out


def test_extrapolated_input_is_exact_for_a_constant_acceleration():
    """Closed form: a neighbour at constant acceleration a, reported like the Ram and PileSoil
    units (displacement at t_n, velocity the mean over the last step d, i.e. at t_n - d / 2),
    is extrapolated exactly to any age."""
    from anvilwave.fmu.coupling import extrapolated_input

    u0, v0, a, d = 1.0e-4, 5.0, -3.0e4, 2.5e-6  # [m, m/s, m/s^2, s]

    def u(t):
        return u0 + v0 * t + 0.5 * a * t * t

    t_n = 4 * d
    for age in (0.0, 0.3 * d, d, 2.5 * d):
        displacement, velocity = extrapolated_input(u(t_n), v0 + a * (t_n - 0.5 * d),
                                                    v0 + a * (t_n - 1.5 * d), age, d)
        assert displacement == pytest.approx(u(t_n + age), rel=1e-14, abs=1e-18)
        assert velocity == pytest.approx(v0 + a * (t_n + age - 0.5 * d), rel=1e-14)
    assert extrapolated_input(0.25, 3.0, 99.0, 0.0, d) == (0.25, 3.0)  # age 0: as received
    assert extrapolated_input(0.25, 3.0, 99.0, d, 0.0) == (0.25 + d * 3.0, 3.0)  # no history


def test_extrapolated_input_follows_a_leapfrog_mass_through_a_force_change():
    """Closed form: a toe mass m stepped by the leapfrog of the Ram unit (half-step velocity
    v_n+1/2 = v_n-1/2 + (W - F_n) h / m, u_n+1 = u_n + h v_n+1/2) under a held force that
    changes at every step. Given the force over the step that gave the received velocity and
    the force held since, the extrapolation with the toe mass predicts the next point to
    round-off (the linear extrapolation of v alone misses (F_after - F) h / m); without the
    forces it is that linear extrapolation, bit for bit."""
    from anvilwave.fmu.coupling import extrapolated_input

    m, h, weight = 5.6e3, 5.0e-6, 5.6e3 * 9.81  # [kg, s, N]
    forces = [0.0, 3.0e8, 9.0e8, 8.5e8, 2.0e8]  # F_n held over [t_n, t_n+1] [N]
    u, v = [0.0], [6.0]  # u_n, v_n-1/2 (v[n] the mean over the step ending at t_n)
    for force in forces:
        v.append(v[-1] + (weight - force) * h / m)
        u.append(u[-1] + h * v[-1])
    for n in range(2, len(forces)):  # received at t_n: u_n, v_n-1/2, v_n-3/2
        predicted = extrapolated_input(u[n], v[n], v[n - 1], h, h, forces[n - 1], forces[n], m)
        assert predicted[0] == pytest.approx(u[n + 1], rel=1e-13, abs=1e-17)
        assert predicted[1] == pytest.approx(v[n + 1], rel=1e-13)
        linear = extrapolated_input(u[n], v[n], v[n - 1], h, h)
        assert abs(linear[1] - v[n + 1]) > 1e-3 * abs(forces[n] - forces[n - 1]) * h / m
        assert extrapolated_input(u[n], v[n], v[n - 1], h, h, forces[n - 1], forces[n]) == linear
    assert extrapolated_input(0.25, 3.0, 99.0, 0.0, h, 1e8, 2e8, m) == (0.25, 3.0)  # age 0


@pytest.mark.parametrize("lumped", [False, True])
@pytest.mark.parametrize("ram_toe_mass", [0.0, 200.0])
def test_input_extrapolation_equals_the_python_unit(built, tmp_path, lumped, ram_toe_mass):
    """One formula, two implementations: with input_extrapolation (and a ram toe mass, or
    none) the native FMU and the pythonfmu FMU give the same outputs in a Jacobi master's
    order (1e-12 of the peak; the steps alternate 1 and 2.5 us, so the extrapolation interval
    changes every step), different from the plain feedthrough there; in the DESIGN order the
    option changes no bit."""
    pytest.importorskip("pythonfmu")
    from anvilwave.anvil_rom.fem.modalfile import save_modal_data
    from anvilwave.fmu.fmi_build import build_anvil_fmu

    modal = save_modal_data(built["data"], tmp_path / "modes.npz")
    python_fmu = build_anvil_fmu(modal, tmp_path, lumped=lumped, **CONTACTS)
    native_fmu = built["AnvilLumped" if lumped else "Anvil"]
    data = built["data"]
    anvil = ModalAnvil.rigid(data.total_mass) if lumped else ModalAnvil.from_modal_data(data)
    inputs, steps = blow_inputs(reference_unit(anvil).outputs(0.0, 0.0)[0])
    results = {}
    for name, path in (("native", native_fmu), ("python", python_fmu)):
        for extrapolation in (True, False):
            for order in ("jacobi", "design"):
                fmu = Driven(path, name=f"{name}_{order}")
                try:
                    fmu.initialize(input_extrapolation=extrapolation,
                                   ram_toe_mass=ram_toe_mass)
                    run = run_jacobi if order == "jacobi" else Driven.run
                    results[name, extrapolation, order] = run(fmu, inputs, steps)
                finally:
                    fmu.close()
    jacobi = results["native", True, "jacobi"]
    assert jacobi[:, 0].max() > 1e6  # the impact
    difference = relative_difference(results["python", True, "jacobi"], jacobi)
    print(f"\nnative vs pythonfmu {'AnvilLumped' if lumped else 'Anvil'} with input "
          f"extrapolation (Jacobi order): max relative difference {difference:.2e}")
    assert difference <= 1e-12
    assert relative_difference(results["native", False, "jacobi"], jacobi) > 1e-3
    if ram_toe_mass > 0.0:  # the toe's response is in both, not ignored by both (measured 8e-6)
        fmu = Driven(native_fmu, name="native_no_toe_mass")
        try:
            fmu.initialize(input_extrapolation=True, ram_toe_mass=0.0)
            effect = relative_difference(run_jacobi(fmu, inputs, steps), jacobi)
            print(f"\nram_toe_mass {ram_toe_mass} kg against none: {effect:.2e}")
            assert effect > 1e-6
        finally:
            fmu.close()
    for name in ("native", "python"):
        assert np.array_equal(results[name, True, "design"], results[name, False, "design"])


@pytest.mark.parametrize("lumped", [False, True])
def test_no_input_acceleration_across_the_start_point(built, tmp_path, lumped):
    """The inputs set at the start time are a master's initial values (fmpy's SSP runner sets
    zeros there before it has read any output), not the neighbours' states: the native anvil,
    like the Python one (anvilwave/fmu/coupling.py, note_inputs), takes no acceleration from a
    difference across the start point (interval 0 while the point before is the start).

    Jacobi order from a start t_s != 0 with zero inputs over the first step, then the blow's:
    the native and pythonfmu FMUs agree to 1e-12 of the peak; an acceleration across the start
    (the zeros to the ram's 4 m/s over one step) moves the ram displacement that the anvil
    extrapolates by v d / 2 = 2 um at the second point, a contact force far off that.
    """
    pytest.importorskip("pythonfmu")
    from anvilwave.anvil_rom.fem.modalfile import save_modal_data
    from anvilwave.fmu.fmi_build import build_anvil_fmu

    modal = save_modal_data(built["data"], tmp_path / "modes.npz")
    python_fmu = build_anvil_fmu(modal, tmp_path, lumped=lumped, **CONTACTS)
    native_fmu = built["AnvilLumped" if lumped else "Anvil"]
    data = built["data"]
    anvil = ModalAnvil.rigid(data.total_mass) if lumped else ModalAnvil.from_modal_data(data)
    inputs, steps = blow_inputs(reference_unit(anvil).outputs(0.0, 0.0)[0], n=400)
    inputs[:, 0] += 2e-6  # in contact from the first step on
    t_s = -1.25e-6
    t = t_s + np.concatenate([[0.0], np.cumsum(steps)])
    results = {}
    for name, path in (("native", native_fmu), ("python", python_fmu)):
        fmu = Driven(path, name=name)
        try:
            fmu.fmu.setupExperiment(startTime=t_s)
            fmu.set(input_extrapolation=True)
            fmu.fmu.enterInitializationMode()
            fmu.fmu.exitInitializationMode()
            fmu.fmu.setReal(fmu.vr_in, [0.0, 0.0, 0.0, 0.0])  # the runner's start values
            fmu.fmu.doStep(t[0], steps[0])
            out = np.empty((len(inputs) - 1, 4))
            for n in range(1, len(inputs)):  # Jacobi: outputs, then the new inputs, the step
                out[n - 1] = fmu.fmu.getReal(fmu.vr_out)
                fmu.fmu.setReal(fmu.vr_in, list(inputs[n]))
                fmu.fmu.doStep(t[n], steps[n])
            results[name] = out
        finally:
            fmu.close()
    assert results["native"][:, 0].max() > 1e6  # the impact
    difference = relative_difference(results["python"], results["native"])
    print(f"\nnative vs pythonfmu {'AnvilLumped' if lumped else 'Anvil'}, zero inputs at the "
          f"start {t_s} s (Jacobi order): max relative difference {difference:.2e}")
    assert difference <= 1e-12


def test_a_modal_anvil_is_embedded_as_it_is(built, tmp_path):
    """A ModalAnvil (truncated, damped, with static correction) gives that ROM's numbers."""
    anvil = ModalAnvil.from_modal_data(built["data"], fmax=8000.0, damping_ratio=0.01,
                                       static_correction=True)
    path = build_native_anvil_fmu(anvil, tmp_path / "rom.fmu", **CONTACTS)
    unit = reference_unit(anvil)
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0])
    expected = run_reference(unit, inputs, steps)
    fmu = Driven(path)
    try:
        assert fmu.fmu.getBoolean([fmu.vr("static_correction")]) == [True]
        fmu.initialize()
        actual = fmu.run(inputs, steps)
    finally:
        fmu.close()
    difference = relative_difference(actual, expected)
    print(f"\nnative Anvil from a ModalAnvil: max relative difference {difference:.2e}")
    assert difference <= 1e-12


def test_two_instances_interleaved_keep_their_own_parameters(built):
    options_b = {"fmax": 5000.0, "static_correction": True, "ram_contact_damping": 2.0e5}
    data = built["data"]
    unit_a = reference_unit(ModalAnvil.from_modal_data(data))
    unit_b = reference_unit(ModalAnvil.from_modal_data(data, fmax=5000.0,
                                                       static_correction=True), 2.0e5)
    inputs, steps = blow_inputs(unit_a.outputs(0.0, 0.0)[0], n=600)
    expected = [run_reference(unit_a, inputs, steps), run_reference(unit_b, inputs, steps)]
    a, b = Driven(built["Anvil"], "a"), Driven(built["Anvil"], "b")
    try:
        a.initialize()
        b.initialize(**options_b)
        out = [np.empty_like(expected[0]), np.empty_like(expected[1])]
        t = np.concatenate([[0.0], np.cumsum(steps)])
        for n in range(len(inputs)):  # call by call, one instance after the other
            for fmu, result in zip((a, b), out, strict=True):
                fmu.fmu.setReal(fmu.vr_in, list(inputs[n]))
                result[n] = fmu.fmu.getReal(fmu.vr_out)
                fmu.fmu.doStep(t[n], steps[n])
    finally:
        a.close()
        b.close()
    for actual, reference in zip(out, expected, strict=True):
        assert relative_difference(actual, reference) <= 1e-12
    assert np.abs(out[0][:, 0] - out[1][:, 0]).max() > 1e-3 * np.abs(out[0][:, 0]).max()


def test_reset_restores_the_build_values_and_reruns_identically(built):
    unit = reference_unit(ModalAnvil.from_modal_data(built["data"]))
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0], n=600)
    fmu = Driven(built["Anvil"])
    try:
        fmu.initialize(static_correction=True, fmax=9000.0)
        first = fmu.run(inputs, steps)
        fmu.fmu.reset()
        assert fmu.fmu.getReal([fmu.vr("fmax")]) == [built["data"].fmax]
        assert fmu.fmu.getBoolean([fmu.vr("static_correction")]) == [False]
        fmu.initialize(static_correction=True, fmax=9000.0)
        second = fmu.run(inputs, steps)
    finally:
        fmu.close()
    assert np.array_equal(first, second)


@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
def test_simulated_alone_it_rests_on_the_pile(built, kind):
    result = simulate_fmu(str(built[kind]), stop_time=1e-3)
    weight = built["data"].total_mass * 9.81
    assert np.all(result["F_ram"] == 0.0)  # the ram (u_ram = 0) is above the top face
    np.testing.assert_allclose(result["F_pile"], weight, rtol=1e-9)
    np.testing.assert_allclose(result["u_top"], result["u_top"][0], rtol=1e-9)


# ---------------------------------------------------------------------------- the FMU files
@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
def test_fmus_validate_without_problems(built, kind):
    assert validate_fmu(str(built[kind])) == []
    run = subprocess.run([sys.executable, "-m", "fmpy", "validate", str(built[kind])],
                         capture_output=True, text=True)
    assert run.returncode == 0 and "No problems found" in run.stdout, run.stdout + run.stderr


def test_model_description_units_structure_and_sources(built):
    md = read_model_description(str(built["Anvil"]))
    var = {v.name: v for v in md.modelVariables}
    assert {n: var[n].unit for n in INPUTS + OUTPUTS} == {
        "u_ram": "m", "v_ram": "m/s", "u_pile": "m", "v_pile": "m/s",
        "F_ram": "N", "F_pile": "N", "u_top": "m", "u_bottom": "m"}
    assert all(v.unit is not None for v in md.modelVariables
               if v.type == "Real" and v.name != "damping_ratio") and var["damping_ratio"].unit
    units = {u.name: u.baseUnit for u in md.unitDefinitions}
    assert (units["N"].kg, units["N"].m, units["N"].s) == (1, 1, -2)
    assert (units["N.s/m"].kg, units["N.s/m"].s) == (1, -1)
    assert all("[" in v.description for v in md.modelVariables)
    # the contact forces are a direct feedthrough of the four inputs
    deps = {u.variable.name: {d.name for d in u.dependencies} for u in md.outputs}
    assert deps["F_ram"] == deps["F_pile"] == set(INPUTS)
    initial = {u.variable.name: {d.name for d in u.dependencies} for u in md.initialUnknowns}
    parameters = {v.name for v in md.modelVariables if v.causality == "parameter"}
    assert set(initial) == set(OUTPUTS)
    assert initial["F_ram"] == set(INPUTS) | parameters
    lumped = read_model_description(str(built["AnvilLumped"]))
    deps = {u.variable.name: {d.name for d in u.dependencies} for u in lumped.outputs}
    assert deps == {"F_ram": {"u_ram", "v_ram"}, "F_pile": {"u_pile", "v_pile"},
                    "u_top": set(), "u_bottom": set()}
    cs = md.coSimulation
    assert not cs.needsExecutionTool and cs.canHandleVariableCommunicationStepSize
    with zipfile.ZipFile(built["Anvil"]) as zf:
        names = set(zf.namelist())
        build_xml = zf.read("sources/buildDescription.xml")
    source_files = md.buildConfigurations[0].sourceFileSets[0].sourceFiles  # <SourceFiles>
    assert source_files == ["unit_core.c", "unit_fmu.c", "unit_fmi3.c", "fmu_common.c",
                            "anvil_unit.c", "anvil_model.c"]
    assert {f"sources/{f}" for f in source_files} <= names
    assert {"binaries/linux64/Anvil.so", "binaries/win64/Anvil.dll",
            f"resources/{MODAL_RESOURCE}", "resources/anvilwave_unit.txt",
            "sources/unit_core.h", "sources/fmi2Functions.h", "sources/fmi3Functions.h"} <= names
    with zipfile.ZipFile(built["AnvilLumped"]) as zf:  # one binary serves both anvils
        assert zf.read("binaries/linux64/AnvilLumped.so") == \
            (NATIVE_DIR / "binaries" / "linux64" / "Anvil.so").read_bytes()
    assert not any(n.endswith((".py", ".npz")) for n in names)  # no Python inside
    xml = built["root"] / "buildDescription.xml"
    xml.write_bytes(build_xml)
    configurations = read_build_description(str(xml))  # validated against the FMI 3 schema
    assert configurations[0].sourceFileSets[0].sourceFiles == source_files


@pytest.mark.parametrize("lumped", [False, True])
def test_same_interface_as_the_pythonfmu_unit(built, tmp_path, lumped):
    """Same names, value references, types, causalities, variabilities, units, structure."""
    pytest.importorskip("pythonfmu")
    from anvilwave.anvil_rom.fem.modalfile import save_modal_data
    from anvilwave.fmu.fmi_build import build_anvil_fmu

    modal = save_modal_data(built["data"], tmp_path / "modes.npz")
    python_fmu = build_anvil_fmu(modal, tmp_path, lumped=lumped, **CONTACTS)
    native = read_model_description(str(built["AnvilLumped" if lumped else "Anvil"]))
    python = read_model_description(str(python_fmu))
    assert native.coSimulation.modelIdentifier == python.coSimulation.modelIdentifier

    def table(md):
        rows = []
        for v in md.modelVariables:
            start = v.start
            if v.type == "Real" and start is not None:
                start = float(start)
            if v.name == "modal_data_file":
                start = None  # modes.npz there, modal_data.bin here
            rows.append((v.name, v.valueReference, v.type, v.causality, v.variability,
                         v.unit, start))
        return rows

    assert table(native) == table(python)
    for attribute in ("outputs", "initialUnknowns"):
        assert ([(u.variable.name, [d.name for d in u.dependencies])
                 for u in getattr(native, attribute)]
                == [(u.variable.name, [d.name for d in u.dependencies])
                    for u in getattr(python, attribute)])


def test_sources_compile_on_their_own(built, tmp_path):
    """sources/ is a complete source FMU: it compiles alone into a loadable FMI 2.0 binary."""
    compiler = _compiler()
    with zipfile.ZipFile(built["Anvil"]) as zf:
        zf.extractall(tmp_path)
    files = sorted(str(p) for p in (tmp_path / "sources").glob("*.c"))
    library = tmp_path / "again.so"
    run = subprocess.run([*compiler.split(), "-shared", "-fPIC", "-O2", "-ffp-contract=off",
                          "-o", str(library), *files, "-lm"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    lib = ctypes.CDLL(str(library))
    lib.fmi2GetVersion.restype = ctypes.c_char_p
    lib.fmi2GetTypesPlatform.restype = ctypes.c_char_p
    assert (lib.fmi2GetVersion(), lib.fmi2GetTypesPlatform()) == (b"2.0", b"default")


def test_plain_arrays_build_the_same_fmu_byte_for_byte(built, tmp_path):
    """A mapping of plain arrays is the ModalData's content; the build is reproducible."""
    data = built["data"]
    arrays = {name: getattr(data, name) for name in (
        "frequencies", "participation_ram", "participation_pile", "participation_gravity",
        "elastic_flexibility", "total_mass", "fmax", "damping_ratio")}
    again = build_native_anvil_fmu(arrays, tmp_path / "Anvil.fmu", **CONTACTS)
    assert again.read_bytes() == built["Anvil"].read_bytes()


def test_modal_resource_round_trip(built):
    data = native_modal_data(built["data"])
    back = read_modal_resource(modal_resource_bytes(data))
    for name in ("frequencies", "omega", "participation_ram", "participation_pile",
                 "participation_gravity", "elastic_flexibility"):
        assert np.array_equal(getattr(back, name), getattr(data, name))
    assert (back.total_mass, back.fmax, back.damping_ratio) == (
        data.total_mass, data.fmax, data.damping_ratio)
    assert len(modal_resource_bytes(data)) == 80 + 40 * data.n_modes


# ---------------------------------------------------------------------------- robustness
def _resource(data, **changes) -> bytes:
    """A modal-data resource with some values changed (to break a rule)."""
    native = native_modal_data(data)
    fields = {name: getattr(native, name) for name in native.__dataclass_fields__}
    return modal_resource_bytes(type(native)(**{**fields, **changes}))


BAD_FILES = {
    "bad.bin": (lambda data: b"not modal data at all" * 10,
                "not an anvilwave modal-data file"),
    "short.bin": (lambda data: _resource(data)[:-8], "malformed modal-data file"),
    "nan.bin": (lambda data: _resource(data, frequencies=np.full(data.n_modes, np.nan)),
                "frequencies: must be finite"),
    "mass.bin": (lambda data: _resource(data, total_mass=-1.0), "total_mass: must be positive"),
    "version.bin": (lambda data: _resource(data)[:16] + b"\x07" + _resource(data)[17:],
                    "format version 7 is not supported"),
}


@pytest.mark.parametrize("kind, parameters, reason", [
    ("Anvil", {"pile_contact_stiffness": -1.0}, "pile_contact_stiffness: must be positive"),
    ("Anvil", {"damping_ratio": -0.1}, "damping_ratio: must be in [0, 1)"),
    ("Anvil", {"fmax": 100.0}, "below the first flexible mode"),
    ("Anvil", {"fmax": 1e6}, "exceeds the 20000 Hz the modes were computed for"),
    ("Anvil", {"modal_data_file": "missing.bin"}, "modal-data file not found"),
    *[("Anvil", {"modal_data_file": name}, reason) for name, (_, reason) in BAD_FILES.items()],
    ("AnvilLumped", {"mass": -5.0}, "mass: must be positive"),
    ("AnvilLumped", {"ram_contact_damping": -1.0}, "ram_contact_damping: must be >= 0"),
    ("AnvilLumped", {"ram_toe_mass": -1.0}, "ram_toe_mass: must be >= 0 [kg], got -1"),
])
def test_invalid_parameters_give_fmi2error_with_the_reason(built, kind, parameters, reason):
    fmu = Driven(built[kind])
    try:
        name = parameters.get("modal_data_file")
        if name in BAD_FILES:
            (Path(fmu.unzip) / "resources" / name).write_bytes(BAD_FILES[name][0](built["data"]))
        fmu.fmu.setupExperiment(startTime=0.0)
        fmu.set(**parameters)
        fmu.fmu.enterInitializationMode()
        with pytest.raises(FMICallException) as error:
            fmu.fmu.exitInitializationMode()
        assert error.value.status == 3  # fmi2Error, not fmi2Fatal
        assert any(reason in text for text in fmu.errors()), fmu.messages
        with pytest.raises(FMICallException) as error:  # it does not step after the error
            fmu.fmu.doStep(0.0, 1e-6)
        assert error.value.status == 3 and "failed earlier" in fmu.errors()[-1]
        # the instance is intact: reset, initialize with the build values and step
        fmu.fmu.reset()
        fmu.initialize()
        fmu.fmu.doStep(0.0, 1e-6)
        weight = built["data"].total_mass * 9.81
        assert fmu.fmu.getReal([fmu.vr_out[1]])[0] == pytest.approx(weight, rel=1e-9)
    finally:
        fmu.close()


def test_calls_out_of_rule_give_fmi2error_and_the_host_survives(built):
    fmu = Driven(built["Anvil"])
    try:
        with pytest.raises(FMICallException):
            fmu.fmu.getInteger([0])
        assert "no Integer variable" in fmu.errors()[-1]
        with pytest.raises(FMICallException):
            fmu.fmu.getReal([999])
        assert "fmi2GetReal: unknown value reference 999" in fmu.errors()[-1]
        with pytest.raises(FMICallException):
            fmu.fmu.setReal([fmu.vr("static_correction")], [1.0])
        assert "a Boolean variable" in fmu.errors()[-1]
        with pytest.raises(FMICallException):
            fmu.fmu.doStep(0.0, 1e-6)  # not initialized
        assert "not allowed in state instantiated" in fmu.errors()[-1]
        fmu.initialize()
        with pytest.raises(FMICallException):
            fmu.fmu.setReal([fmu.vr("F_ram")], [1.0])
        assert "is an output" in fmu.errors()[-1]
        with pytest.raises(FMICallException):
            fmu.fmu.setReal([fmu.vr("fmax")], [9000.0])
        assert "fmax is fixed" in fmu.errors()[-1]
        fmu.fmu.reset()
        fmu.initialize()
        with pytest.raises(FMICallException) as error:
            fmu.fmu.doStep(0.0, -1e-6)
        assert error.value.status == 3
        assert "communication step must be finite and positive" in fmu.errors()[-1]
        fmu.fmu.reset()
        fmu.initialize()
        with pytest.raises(FMICallException):
            fmu.fmu.doStep(0.0, 1e300)  # a master's unit mistake, not a step of a blow
        assert "communication step 1e+300 s is larger than 1000 s" in fmu.errors()[-1]
    finally:
        fmu.close()


def test_a_wrong_guid_is_refused_with_the_reason(built):
    fmu = Driven(built["Anvil"], guid="{00000000-0000-0000-0000-000000000000}",
                 instantiate=False)
    try:
        with pytest.raises(Exception, match="(?i)instantiate"):
            fmu.fmu.instantiate(callbacks=fmu.callbacks)
    finally:
        fmu.fmu.freeLibrary()
        shutil.rmtree(fmu.unzip, ignore_errors=True)
    assert "does not match the resource's" in fmu.errors()[-1]


def test_debug_logging_traces_the_calls(built):
    fmu = Driven(built["AnvilLumped"])
    try:
        fmu.fmu.setDebugLogging(True, ["logCalls"])
        fmu.initialize(mass=1234.0)
        fmu.fmu.doStep(0.0, 1e-6)
        with pytest.raises(FMICallException):
            fmu.fmu.setDebugLogging(True, ["noSuchCategory"])
    finally:
        fmu.close()
    texts = [text for status, text in fmu.messages if status == 0]
    assert any("fmi2SetReal: mass = 1234" in t for t in texts)
    assert any("fmi2DoStep(t = 0, h = 9.99999" in t for t in texts)


def test_build_rejects_bad_input_and_writes_nothing(built, tmp_path):
    data = built["data"]
    with pytest.raises(InputError, match="mass"):
        build_native_anvil_fmu(data, tmp_path, lumped=True, mass=-1.0, **CONTACTS)
    with pytest.raises(InputError, match="not a parameter"):
        build_native_anvil_fmu(data, tmp_path, stiffness=1.0, **CONTACTS)
    with pytest.raises(InputError, match="first flexible mode"):
        build_native_anvil_fmu(data, tmp_path, fmax=100.0, **CONTACTS)
    with pytest.raises(InputError, match="ram_contact_stiffness: has no default"):
        build_native_anvil_fmu(data, tmp_path, pile_contact_stiffness=1e10)
    with pytest.raises(InputError, match="must be true or false"):
        build_native_anvil_fmu(data, tmp_path, static_correction="yes", **CONTACTS)
    with pytest.raises(InputError, match="modal_data_file"):
        build_native_anvil_fmu(data, tmp_path, modal_data_file="x.bin", **CONTACTS)
    with pytest.raises(InputError, match="participation_ram: is missing"):
        build_native_anvil_fmu({"frequencies": [0.0, 100.0]}, tmp_path, **CONTACTS)
    with pytest.raises(InputError, match=r"ram_toe_mass: must be >= 0 \[kg\], got -2"):
        build_native_anvil_fmu(data, tmp_path, ram_toe_mass=-2.0, **CONTACTS)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("case", ["a non-finite parameter", "a non-finite input"])
def test_non_finite_values_are_refused_when_set(built, case):
    """A non-finite Real is refused by fmi2SetReal (fmi2Error, the reason logged, the value
    not stored): the instance initializes and steps with the values it had."""
    fmu = Driven(built["Anvil"])
    try:
        fmu.fmu.setupExperiment(startTime=0.0)
        name = "gravity" if case == "a non-finite parameter" else "u_ram"
        with pytest.raises(FMICallException) as error:
            fmu.set(**{name: float("inf")})
        assert error.value.status == 3 and f"{name} must be finite" in fmu.errors()[-1]
        fmu.fmu.enterInitializationMode()
        fmu.fmu.exitInitializationMode()
        fmu.fmu.doStep(0.0, 1e-6)
        weight = built["data"].total_mass * 9.81
        assert fmu.fmu.getReal([fmu.vr_out[1]])[0] == pytest.approx(weight, rel=1e-9)
    finally:
        fmu.close()


# ---------------------------------------------------------------------------- a C host
@pytest.fixture(scope="module")
def c_host(tmp_path_factory):
    """tests/c_host/fmi_host.c compiled with the system compiler."""
    compiler = _compiler()
    exe = tmp_path_factory.mktemp("c_host") / "fmi_host"
    run = subprocess.run([*compiler.split(), "-std=c99", "-O2", "-Wall", "-Wextra",
                          "-I", str(NATIVE_DIR), "-o", str(exe), str(HOST_SOURCE), "-ldl",
                          "-lm"], capture_output=True, text=True)
    if run.returncode != 0:
        pytest.fail(f"the C host does not compile:\n{run.stderr}")
    return exe


def _host_arguments(md, inputs: dict[str, str], parameters: dict[str, str], csv: Path,
                    steps: int, step_size: float) -> list[str]:
    var = {v.name: v for v in md.modelVariables}
    args = ["--inputs", ",".join(str(var[n].valueReference) for n in INPUTS),
            "--outputs", ",".join(str(var[n].valueReference) for n in OUTPUTS),
            "--steps", str(steps), "--step-size", repr(step_size), "--csv", str(csv)]
    for name, value in parameters.items():
        kind = {"Real": "--real", "Boolean": "--boolean", "String": "--string"}[var[name].type]
        args += [kind, f"{var[name].valueReference}={value}"]
    for name, signal in inputs.items():
        args += ["--signal", f"{var[name].valueReference}={signal}"]
    return args


@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
def test_c_host_without_python_runs_two_instances_20000_steps(built, c_host, tmp_path, kind):
    """A plain C host, empty environment (no Python, no PYTHONHOME, no LD_PRELOAD): two
    instances, 20,000 steps, fmi2Reset and a bitwise-identical rerun, then the Python kernels
    on the inputs the host used."""
    fmu_dir = tmp_path / kind
    with zipfile.ZipFile(built[kind]) as zf:
        zf.extractall(fmu_dir)
    md = read_model_description(str(built[kind]))
    data = built["data"]
    if kind == "Anvil":
        parameters = {"fmax": "8000", "damping_ratio": "0", "start_at_rest": "1",
                      "ram_contact_stiffness": "2.5e10"}
        anvil = ModalAnvil.from_modal_data(data, fmax=8000.0, damping_ratio=0.0)
    else:
        parameters = {"mass": "4000", "ram_contact_stiffness": "2.5e10"}
        anvil = ModalAnvil.rigid(4000.0)
    unit = AnvilUnit(anvil, ContactParameters(2.5e10, CONTACTS["pile_contact_stiffness"]))
    unit.rest_on_pile(0.0)
    u_top0 = unit.outputs(0.0, 0.0)[0]
    w = 2 * np.pi * 400.0
    signals = {"u_ram": f"{float(u_top0) - 1e-6!r},4,-1.5e4,0,0,0", "v_ram": "4,-3e4,0,0,0,0",
               "u_pile": "0,0,0,2e-4,0,400", "v_pile": f"0,0,0,0,{2e-4 * w!r},400"}
    csv = tmp_path / "host.csv"
    cmd = [str(c_host), str(fmu_dir), md.coSimulation.modelIdentifier, md.guid,
           *_host_arguments(md, signals, parameters, csv, 20000, 1e-6)]
    run = subprocess.run(cmd, env={}, capture_output=True, text=True, timeout=120)
    print("\n" + run.stdout + run.stderr)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "rerun after fmi2Reset bitwise identical: yes" in run.stdout
    assert run.stdout.rstrip().endswith("fmi_host: ok") and run.stderr == ""
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert table.shape == (20000, 9)
    inputs, outputs = table[:, 1:5], table[:, 5:]
    # the same binary under fmpy, on the inputs the host used: the same bits
    fmu = Driven(built[kind])
    try:
        fmu.initialize(**{name: (value == "1" if fmu.variables[name].type == "Boolean"
                                 else float(value)) for name, value in parameters.items()})
        assert np.array_equal(fmu.run(inputs, np.full(len(inputs), 1e-6)), outputs)
    finally:
        fmu.close()
    # the Python kernels (with these parameters they do the very same operations: no BLAS
    # sums over more than 32 modes, no exp of a damped mode)
    expected = run_reference(unit, inputs, 1e-6)
    assert expected[:, 0].max() > 1e6  # the blow happened
    difference = relative_difference(outputs, expected)
    print(f"C host ({kind}) vs Python kernels: max relative difference {difference:.2e}")
    assert difference <= 1e-12


@pytest.fixture(scope="module")
def built_rings(built):
    """The s2 anvil with its pile port in two rings (its mesh has two edges across the 0.05 m
    wall; a version 2 resource), built once."""
    import dataclasses

    spec = load_anvil(EXAMPLES / "anvils" / "s2.toml")
    spec = dataclasses.replace(spec, mesh_size=0.03, interfaces=dataclasses.replace(
        spec.interfaces, pile_rings=2))
    data = cached_modal_data(spec, 20000.0)
    return {"data": data, "Anvil": build_native_anvil_fmu(data, built["root"] / "rings",
                                                          **CONTACTS)}


@pytest.mark.parametrize("case", ["fmax 8 kHz, static correction",
                                  "damped, dashpot, static correction"])
def test_ring_outputs_equal_the_python_kernels(built_rings, case):
    """The pile port in two rings (anvilwave/anvil_rom/rings.py) in C: the rest with the rings that
    carry the weight, the complementarity pivoting, the ring forces held over the step. The
    blow of the one-port test against the Python ring unit: round-off only (1e-12, as the
    one port; measured below 1e-13)."""
    parameters, options, dashpot = ROM_CASES[case]
    data = built_rings["data"]
    assert data.participation_rings.shape[0] == 2
    assert read_modal_resource(modal_resource_bytes(native_modal_data(data))
                               ).participation_rings.shape == (2, data.n_modes)
    options = {"damping_ratio": data.damping_ratio, **options}
    unit = reference_unit(ModalAnvil.from_modal_data(data, **options), dashpot)
    assert unit.rings is not None
    inputs, steps = blow_inputs(unit.outputs(0.0, 0.0)[0])
    expected = np.empty((len(inputs), 4))
    contact_sets = set()
    for n, state in enumerate(inputs):  # run_reference, noting which rings carry load
        force_ram, force_pile = unit.forces(*state)
        contact_sets.add(tuple(unit.rings[4][1:] > 0.0))
        u_top, _, u_bottom, _ = unit.outputs(force_ram, force_pile)
        expected[n] = force_ram, force_pile, u_top, u_bottom
        unit.step(force_ram, force_pile, float(steps[n]))
    assert expected[:, 0].max() > 1e6
    # the blow closes and opens the rings one at a time: the pivoting is exercised
    assert {(True, False), (False, True), (True, True)} <= contact_sets
    difference = relative_difference(
        run_native(built_rings["Anvil"], parameters, inputs, steps), expected)
    print(f"\nnative Anvil with rings vs Python ({case}): max relative difference "
          f"{difference:.2e}")
    assert difference <= 1e-12


# ---------------------------------------------------------------------------- FMI 3.0
@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
@pytest.mark.parametrize("extrapolation", [False, True])
def test_fmi3_anvil_validates_and_equals_the_fmi2_anvil(built, tmp_path, kind, extrapolation):
    """The FMI 3.0 anvil (the same binary, the fmi3 API) validates with fmpy and, under
    fmpy.simulate_fmu with the same ram toe input (a blow: closing at 4 m/s, then lifting),
    gives the FMI 2.0 anvil's outputs bit for bit, with and without input extrapolation (one
    model behind both APIs)."""
    path = build_native_anvil_fmu(built["data"], tmp_path, lumped=kind == "AnvilLumped",
                                  fmi_version=3, **CONTACTS)
    md = read_model_description(str(path))
    assert md.fmiVersion == "3.0" and md.coSimulation.modelIdentifier == kind
    assert not validate_fmu(str(path))
    with zipfile.ZipFile(path) as zf:
        names = set(zf.namelist())
    assert {f"binaries/x86_64-linux/{kind}.so", f"binaries/x86_64-windows/{kind}.dll",
            "sources/buildDescription.xml", "resources/anvilwave_unit.txt"} <= names
    variables = {v.name: v for v in md.modelVariables}
    if kind == "Anvil":
        assert variables["modal_data_file"].start == MODAL_RESOURCE
    t = np.linspace(0.0, 2e-3, 201)
    signal = np.array(list(zip(t, np.where(t < 1e-3, -1e-6 + 4.0 * t - 2.0e3 * t**2, -1e-3),
                               strict=True)), dtype=[("time", float), ("u_ram", float)])
    runs = [simulate_fmu(str(p), stop_time=2e-3, step_size=1e-5, output_interval=1e-5,
                         input=signal, output=list(OUTPUTS),
                         start_values={"input_extrapolation": extrapolation})
            for p in (path, built[kind])]
    assert len(runs[0]) == len(runs[1]) == 201
    for name in OUTPUTS:
        assert np.array_equal(runs[0][name], runs[1][name]), name
    assert runs[0]["F_ram"].max() > 1e6  # the blow happened


@pytest.mark.parametrize("kind", ["Anvil", "AnvilLumped"])
def test_every_start_value_reaches_its_variable(built, kind):
    """The binary's variable table and the build's: after fmi2Instantiate every parameter
    reads back (by its value reference and type) the start value of modelDescription.xml,
    which the binary took from resources/anvilwave_unit.txt by name (a name or reference that
    differed would read the table's default or fail)."""
    fmu = Driven(built[kind])
    try:
        parameters = [v for v in fmu.variables.values() if v.causality == "parameter"]
        assert len(parameters) == (4 if kind == "Anvil" else 1) + 9
        for v in parameters:
            if v.type == "Real":
                assert fmu.fmu.getReal([v.valueReference]) == [float(v.start)], v.name
            elif v.type == "Boolean":
                assert fmu.fmu.getBoolean([v.valueReference]) == [v.start in (True, "true")], \
                    v.name
            else:
                value = fmu.fmu.getString([v.valueReference])[0]
                assert (value.decode() if isinstance(value, bytes) else value) == v.start
        assert float(fmu.variables["ram_contact_stiffness"].start) == \
            CONTACTS["ram_contact_stiffness"]  # a build value, not a default
    finally:
        fmu.close()
