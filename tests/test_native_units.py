"""The native Ram and PileSoil FMUs (anvilwave/fmu/native_units.py, the generic C binaries)
against the numba kernels they re-implement, and their FMI hygiene.

One formula, two implementations: the C units and the Python kernels run the same blow (the
same held input series, the same steps) and their outputs are compared. The C code performs
the kernels' operations in the same order without floating-point contraction, so on this
machine the series agree to the last bit. The tolerance rtol = 1e-12 (atol 1e-12 of each
signal's peak, for values crossing zero) leaves room for what may differ elsewhere and only
in the last bits: another libm's sqrt in the stable-step bounds (the sub-step count is an
integer, so the steps only change if h / dt_stable sits within an ulp of an integer) and
another LAPACK under scipy's static solve (the static state; its errors ~1e-16 relative stay
that small through the linear, dissipative step).
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import tomllib
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")

from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402

from anvilwave.fmu import native_units as nu  # noqa: E402
from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS, OUT_OF_REACH_TIME  # noqa: E402
from anvilwave.hammer.database import load_hammer  # noqa: E402
from anvilwave.hammer.ram import ram_advance, stable_time_step  # noqa: E402
from anvilwave.inputs import InputError, Table  # noqa: E402
from anvilwave.pile import kernels  # noqa: E402
from anvilwave.pile.model import PileSoil, initial_state, substeps  # noqa: E402

from .conftest import EXAMPLES  # noqa: E402

H = 1e-5  # communication step [s]
STEPS = 1500
RTOL = 1e-12  # module docstring


def _pile_soil() -> PileSoil:
    tables = tomllib.loads((EXAMPLES / "table1.toml").read_text())
    return PileSoil.from_tables(Table(tables["pile"], "table1.toml", "pile"),
                                Table(tables["soil"], "table1.toml", "soil"))


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("native_units")
    hammer = load_hammer("illustrative_5500kj", 9.81)
    return {"Ram": nu.build_native_ram_fmu(hammer, out, v_impact=6.0, gravity=9.81,
                                           contact_displacement=1e-3, contact_time=0.0),
            "PileSoil": nu.build_native_pile_soil_fmu(_pile_soil(), out,
                                                      static_head_load=3.19e6, gravity=9.81)}


class Unit:
    """A native unit under fmpy, messages collected."""

    def __init__(self, path: Path, guid: str | None = None):
        self.md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.folder = extract(str(path))
        self.messages: list[str] = []
        from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE

        self.fmu = FMU2Slave(guid=guid or self.md.guid, unzipDirectory=self.folder,
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName="test")
        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        from fmpy import calloc, free
        from fmpy.fmi2 import fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE

        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)

    def _log(self, env, name, status, category, message):
        self.messages.append(message.decode())

    def instantiate(self):
        self.fmu.instantiate(callbacks=self._callbacks)

    def start(self, t0: float = 0.0, **parameters):
        self.instantiate()
        self.fmu.setupExperiment(startTime=t0)
        self.fmu.enterInitializationMode()
        if parameters:
            self.fmu.setReal([self.vr[n] for n in parameters], list(parameters.values()))
        self.fmu.exitInitializationMode()

    def run(self, input_name: str, series: np.ndarray, outputs: list[str], t0: float = 0.0):
        vin = [self.vr[input_name]]
        vout = [self.vr[n] for n in outputs]
        out = np.empty((len(series), len(vout)))
        t = t0
        for n, value in enumerate(series):
            self.fmu.setReal(vin, [float(value)])
            self.fmu.doStep(t, H)
            t += H
            out[n] = self.fmu.getReal(vout)
        return out

    def close(self):
        try:
            self.fmu.terminate()
        except FMICallException:
            pass
        self.fmu.freeInstance()
        shutil.rmtree(self.folder, ignore_errors=True)


def _force_series(peak: float, offset: float = 0.0) -> np.ndarray:
    t = np.arange(STEPS) * H
    return offset + peak * np.sin(np.pi * t / 4e-3).clip(0.0) * (t < 8e-3)


def _close(actual: np.ndarray, expected: np.ndarray) -> None:
    scale = np.max(np.abs(expected), axis=0)
    np.testing.assert_allclose(actual, expected, rtol=RTOL, atol=0.0 + 1e-12 * scale.max())
    for column in range(expected.shape[1]):
        np.testing.assert_allclose(actual[:, column], expected[:, column], rtol=RTOL,
                                   atol=1e-12 * scale[column])


def test_native_ram_reproduces_the_numba_kernel(built):
    """Ram.fmu (C) and ram_advance (numba) on the same held toe forces: the same toe series."""
    hammer = load_hammer("illustrative_5500kj", 9.81)
    forces = _force_series(2.0e8)
    unit = Unit(built["Ram"])
    try:
        unit.start(t0=-0.5 * H)
        got = unit.run("F_toe", forces, ["u_toe", "v_toe"], t0=-0.5 * H)
    finally:
        unit.close()
    mass = hammer.ram.mass.copy()
    stiffness = hammer.ram.stiffness
    u = np.full(mass.size, 1e-3 - 6.0 * FIRST_CONTACT_STEPS * H)  # placed at the first step
    v = np.full(mass.size, 6.0)
    n_sub = substeps(H, float(stable_time_step(mass, stiffness)))
    assert mass.size > 1 and n_sub >= 1
    expected = np.empty((STEPS, 2))
    for n, force in enumerate(forces):
        ram_advance(mass * 9.81, 1.0 / mass, stiffness, u, v, float(force), H, n_sub)
        expected[n] = u[-1], v[-1]
    assert np.ptp(expected[:, 1]) > 1.0  # the blow reverses the ram: the test can fail
    _close(got, expected)


PILE_OUTPUTS = ["u_head", "v_head", "F_gauge", "v_gauge", "u_head_total", "u_pile_toe",
                "max_compression_stress", "max_tension_stress"]


def test_native_pile_soil_reproduces_the_numba_kernels(built):
    """PileSoil.fmu (C: static preload, sweep, outputs) against static_equilibrium,
    pile_advance and the output kernels on the same held head forces (Table 1's pile and
    soil, plastic soil flow in the blow)."""
    forces = _force_series(2.0e8, 3.19e6)
    unit = Unit(built["PileSoil"])
    try:
        unit.start()
        at_rest = unit.fmu.getReal([unit.vr[n] for n in PILE_OUTPUTS])
        got = unit.run("F_head", forces, PILE_OUTPUTS)
    finally:
        unit.close()
    model = _pile_soil()
    arrays = model.arrays()
    state = initial_state(arrays, head_force=3.19e6, gravity=9.81)
    u, v, offset, energy = (np.array(a) for a in state)
    face0 = kernels.head_displacement(arrays.probes, u)
    sweep = kernels.sweep_arrays(arrays.pile, arrays.soil, 9.81)
    n_sub = substeps(H, float(kernels.stable_time_step(arrays.pile, arrays.soil)))
    factor = model.stress_factors()
    extremes = np.zeros(2)
    kernels.update_stress_extremes(factor, u, extremes)
    assert at_rest[4] == pytest.approx(face0, rel=RTOL)  # the static settlement
    expected = np.empty((STEPS, len(PILE_OUTPUTS)))
    for n, force in enumerate(forces):
        kernels.pile_advance(*sweep, u, v, offset, energy, float(force), H, n_sub, None)
        kernels.update_stress_extremes(factor, u, extremes)
        face = kernels.head_displacement(arrays.probes, u)
        expected[n] = (face - face0, kernels.head_velocity(arrays.probes, v),
                       kernels.gauge_force(arrays.pile, arrays.probes, u, v),
                       kernels.gauge_velocity(arrays.probes, v), face, u[-1], *extremes)
    assert np.any(offset != 0.0)  # the soil yielded: the plastic branch is compared too
    _close(got, expected)


def test_same_inputs_give_byte_identical_fmus(built, tmp_path):
    """A rebuild with the same inputs: the same bytes (content GUID, fixed zip dates/order)."""
    again = nu.build_native_pile_soil_fmu(_pile_soil(), tmp_path, static_head_load=3.19e6,
                                          gravity=9.81)
    assert again.read_bytes() == built["PileSoil"].read_bytes()
    other = nu.build_native_pile_soil_fmu(_pile_soil(), tmp_path / "other.fmu",
                                          static_head_load=3.0e6, gravity=9.81)
    assert read_model_description(str(other)).guid != \
        read_model_description(str(again)).guid


def test_the_fmu_travels_with_both_binaries_and_its_metadata(built):
    with zipfile.ZipFile(built["Ram"]) as zf:
        names = set(zf.namelist())
    assert {"binaries/linux64/Ram.so", "binaries/win64/Ram.dll",
            "resources/anvilwave_unit.txt", "sources/ram_model.c"} <= names
    md = read_model_description(str(built["Ram"]))
    assert md.license == "MIT" and md.author and md.version
    assert not fmpy.validation.validate_fmu(str(built["Ram"]))


@pytest.mark.parametrize("case", ["nan input", "inf parameter", "huge step", "nan step",
                                  "step before init", "negative head load"])
def test_bad_calls_are_fmi2_errors_with_the_reason_logged(built, case):
    unit = Unit(built["PileSoil"])
    try:
        if case == "step before init":
            unit.instantiate()
            with pytest.raises(FMICallException):
                unit.fmu.doStep(0.0, H)
            expected = "fmi2DoStep: not allowed in state instantiated"
        elif case == "negative head load":
            unit.instantiate()
            unit.fmu.setupExperiment(startTime=0.0)
            unit.fmu.enterInitializationMode()
            unit.fmu.setReal([unit.vr["static_head_load"]], [-1.0])
            with pytest.raises(FMICallException):
                unit.fmu.exitInitializationMode()
            expected = "static_head_load: must be at least 0 N"
        elif case == "inf parameter":
            unit.instantiate()
            with pytest.raises(FMICallException):
                unit.fmu.setReal([unit.vr["gravity"]], [math.inf])
            expected = "gravity must be finite"
        else:
            unit.start()
            if case == "nan input":
                with pytest.raises(FMICallException):
                    unit.fmu.setReal([unit.vr["F_head"]], [math.nan])
                expected = "F_head must be finite"
            else:
                h = 1e300 if case == "huge step" else math.nan
                with pytest.raises(FMICallException):
                    unit.fmu.doStep(0.0, h)
                expected = ("is larger than" if case == "huge step"
                            else "must be finite and positive")
        assert any(expected in m for m in unit.messages), unit.messages
    finally:
        unit.close()


def test_a_wrong_guid_is_refused_with_the_reason(built):
    unit = Unit(built["Ram"], guid="{00000000-0000-4000-8000-000000000000}")
    try:
        with pytest.raises(Exception):  # noqa: B017 - fmpy raises on a NULL instance
            unit.instantiate()
        assert any("does not match the resource's" in m for m in unit.messages)
    finally:
        shutil.rmtree(unit.folder, ignore_errors=True)


def test_native_modal_ram_reproduces_the_modal_unit(tmp_path):
    """Table 1's modal ram (125 toe modes): Ram.fmu (C) against ModalRamUnit (numba) on the
    same held toe forces, with a change of step half-way (the state rescaled). The numba toe
    sum may be reassociated (vectorised), the C sum runs in order: they agree to rounding of
    the sum's terms: |du| <= n eps max|u| (the reassociation bound of a sum of n terms whose
    magnitudes sum to ~|u|, the rigid mode dominating), and the half-step velocity
    (u_n+1 - u_n) / h has |dv| <= 2 |du| / h."""
    from anvilwave.config.system import load_system
    from anvilwave.hammer.modal_ram import ModalRamUnit

    hammer = load_system(EXAMPLES / "table1.toml").hammer
    assert hammer.ram.is_modal_unit
    path = nu.build_native_ram_fmu(hammer, tmp_path, v_impact=6.0, contact_displacement=2e-3,
                                   contact_mid_step=False)  # at contact_time 0 = the start
    forces = _force_series(2.0e8)
    steps = [H] * (STEPS // 2) + [0.5 * H] * (STEPS - STEPS // 2)
    unit = Unit(path)
    got = np.empty((STEPS, 2))
    try:
        unit.start(t0=0.0)
        t = 0.0
        for n, (force, h) in enumerate(zip(forces, steps, strict=True)):
            unit.fmu.setReal([unit.vr["F_toe"]], [float(force)])
            unit.fmu.doStep(t, h)
            t += h
            got[n] = unit.fmu.getReal([unit.vr["u_toe"], unit.vr["v_toe"]])
    finally:
        unit.close()
    reference = ModalRamUnit(hammer.ram.modes, 9.81)
    expected = np.empty((STEPS, 2))
    for n, (force, h) in enumerate(zip(forces, steps, strict=True)):
        if n == 0:
            reference.start(2e-3, 6.0, h)
        else:
            reference.set_step(h)
        expected[n] = reference.step(float(force))
    assert np.ptp(expected[:, 1]) > 1.0
    du = hammer.ram.modes.n_modes * np.finfo(float).eps * np.abs(expected[:, 0]).max()
    np.testing.assert_allclose(got[:, 0], expected[:, 0], rtol=0, atol=du)
    np.testing.assert_allclose(got[:, 1], expected[:, 1], rtol=0, atol=2.0 * du / min(steps))
    print(f"\nmodal ram: max |du| {np.abs(got[:, 0] - expected[:, 0]).max():.2e} m "
          f"(bound {du:.2e}), max |dv| {np.abs(got[:, 1] - expected[:, 1]).max():.2e} m/s")


START_FRACTIONS = (0.0, -0.5, -0.25, -0.999)
"""Masters' start times over their step h: OMSimulator's 0, the engine's -h/2, and anywhere
else on the grid."""
START_TIMES = tuple(f * H for f in START_FRACTIONS)


@pytest.mark.parametrize("mid_step", [True, False])
def test_native_ram_equals_the_pythonfmu_ram_from_any_start(tmp_path, mid_step):
    """One formula, two implementations: the native Ram and the pythonfmu Ram built with the
    same parameters and DefaultExperiment give the same toe series on the same held forces
    (rtol 1e-12; bitwise on this machine), from the start times of START_TIMES, with
    contact_mid_step on (the default: the first contact mid third step, so every start gives
    the same series) and off (the contact at contact_time). Before the first step both report
    the toe OUT_OF_REACH_TIME of free flight before the contact (mid step: whatever the
    DefaultExperiment's step h_d, here not the master's) or at contact_time's free-flight
    position (off)."""
    pytest.importorskip("pythonfmu")
    from anvilwave.fmu.fmi_build import build_ram_fmu

    hammer = load_hammer("illustrative_5500kj", 9.81)
    h_d = 0.5 * H  # the DefaultExperiment's step: not the master's
    experiment = (-0.5 * h_d, 0.02, h_d)
    parameters = {"v_impact": 6.0, "contact_displacement": 1e-3, "contact_time": 0.0,
                  "contact_mid_step": mid_step}
    paths = {"native": nu.build_native_ram_fmu(hammer, tmp_path / "native",
                                               default_experiment=experiment, **parameters),
             "python": build_ram_fmu(tmp_path / "python", hammer,
                                     default_experiment=experiment, **parameters)}
    vrs = {}
    for name, path in paths.items():
        md = read_model_description(str(path))
        vrs[name] = {v.name: (v.valueReference, v.type, v.start) for v in md.modelVariables
                     if v.name != "hammer"}
        assert (float(md.defaultExperiment.startTime), float(md.defaultExperiment.stopTime),
                float(md.defaultExperiment.stepSize)) == experiment
    assert vrs["native"]["contact_mid_step"] == vrs["python"]["contact_mid_step"] == \
        (6, "Boolean", "true" if mid_step else "false")
    assert {n: v[:2] for n, v in vrs["native"].items()} == \
        {n: v[:2] for n, v in vrs["python"].items()}  # same value references and types
    forces = _force_series(2.0e8)[:600]
    series = {}
    for t0 in START_TIMES:
        for name, path in paths.items():
            unit = Unit(path)
            try:
                unit.start(t0=t0)
                first = unit.fmu.getReal([unit.vr["u_toe"], unit.vr["v_toe"]])
                series[name, t0] = first, unit.run("F_toe", forces, ["u_toe", "v_toe"], t0=t0)
            finally:
                unit.close()
        (first, got), (first_python, expected) = series["native", t0], series["python", t0]
        assert np.ptp(expected[:, 1]) > 1.0  # the blow reverses the ram
        _close(got, expected)
        np.testing.assert_allclose(first, first_python, rtol=RTOL)
        offset = -OUT_OF_REACH_TIME if mid_step else t0
        np.testing.assert_allclose(first, [1e-3 + 6.0 * offset, 6.0], rtol=RTOL)
    exact = all(np.array_equal(series["native", t][1], series["python", t][1])
                for t in START_TIMES)
    print(f"\nnative vs pythonfmu Ram (contact_mid_step {mid_step}): bitwise equal from every "
          f"start: {exact}")
    if mid_step:  # the same series from every start, to the bit
        for t0 in START_TIMES[1:]:
            assert np.array_equal(series["native", t0][1], series["native", 0.0][1])
    else:  # the contact at contact_time 0: a start further from it gives another series
        assert not np.array_equal(series["native", -0.25 * H][1],
                                  series["native", -0.5 * H][1])


@pytest.fixture(scope="module")
def table1_fmus(tmp_path_factory):
    """The FMUs of Table 1 as ``build-fmus`` makes them by default: native anvils, native Ram
    and PileSoil."""
    from anvilwave.config.system import load_system
    from anvilwave.engine.fmus import build_system_fmus, load_anvil_modal_data

    cfg = load_system(EXAMPLES / "table1.toml")
    fmus = build_system_fmus(cfg, tmp_path_factory.mktemp("table1_native"),
                             load_anvil_modal_data(cfg), native_anvil=True)
    assert fmus["ram_implementation"] == fmus["pile_soil_implementation"] == "native"
    return cfg, fmus


def test_native_fmus_default_experiment_is_the_systems(table1_fmus):
    """Every FMU of the system (native anvils, Ram, PileSoil) has the SSP's DefaultExperiment:
    from -step/2 to the blow's duration at the SSP's step."""
    cfg, fmus = table1_fmus
    step = fmus["ssp_step"]
    for kind in ("Ram", "Anvil", "AnvilLumped", "PileSoil"):
        experiment = read_model_description(str(fmus[kind])).defaultExperiment
        assert (float(experiment.startTime), float(experiment.stopTime),
                float(experiment.stepSize)) == (-FIRST_CONTACT_STEPS * step, float(cfg.duration),
                                                step), kind


@pytest.mark.parametrize("exchange", ["design", "jacobi"])
def test_native_system_peaks_do_not_depend_on_the_start_time(table1_fmus, exchange):
    """The native units of Table 1 (modal ram, ROM and lumped anvils) under the fmpy master
    at the SSP's step, from the start times of START_TIMES (OMSimulator's 0 among them), with
    the ram's contact_mid_step (the SSP's default; the master would otherwise set
    contact_time): the peak ram-anvil and anvil-pile forces of the first 6 ms agree to 1e-9
    (measured: the same bits for F_ram, F_pile within 3e-13 under the Jacobi order whose
    extrapolation sees the time grid), and equal, within 0.5 %, the engine's start (-h/2, the
    contact at contact_time 0), which a start elsewhere with contact_mid_step off misses by
    1.5 to 5 % (measured at the SSP step).

    At other master steps (2 and 4 h_d, h_d the DefaultExperiment's): the ram places its first
    contact from the master's first step, so the peaks are the engine's at that step within
    0.01 % (tests/test_fmu_system.py, test_ram_first_contact_at_multiples_of_the_default_step;
    -4.3 % at 4 h_d when the ram placed it from h_d)."""
    from anvilwave.fmu.fmi_master import BlowMaster

    cfg, fmus = table1_fmus
    h = fmus["ssp_step"]
    n = int(round(6e-3 / h))
    starts = [f * h for f in START_FRACTIONS]
    for anvil in ("Anvil", "AnvilLumped"):
        peaks = {}
        for t0 in starts:
            for mid_step in (True, False):
                parameters = {"ram": {"contact_mid_step": mid_step, "contact_time": 0.0},
                              "anvil": {"input_extrapolation": exchange == "jacobi"}}
                with BlowMaster(fmus["Ram"], fmus[anvil], fmus["PileSoil"], parameters,
                                exchange=exchange) as master:
                    blow = master.run_blows(1, n, h, start_time=t0)[0]
                peaks[t0, mid_step] = np.array([blow["F_ram"].max(), blow["F_pile"].max()])
        engine = peaks[-0.5 * h, False]
        assert engine[0] > 1e8  # the impact
        for t0 in starts:
            off = peaks[t0, False] / engine - 1.0
            print(f"\n{exchange} {anvil} start {t0 / h:+.3f} h: F_ram "
                  f"{peaks[t0, True][0] / 1e6:.3f} MN, F_pile "
                  f"{peaks[t0, True][1] / 1e6:.3f} MN (mid step; engine start "
                  f"{engine[0] / 1e6:.3f}, {engine[1] / 1e6:.3f} MN); contact_mid_step off: "
                  f"{off[0]:+.2%}, {off[1]:+.2%}")
            np.testing.assert_allclose(peaks[t0, True], peaks[starts[0], True], rtol=1e-9)
            np.testing.assert_allclose(peaks[t0, True], engine, rtol=5e-3)


def test_the_boolean_parameter_follows_the_fmi_rules(built):
    """contact_mid_step through fmi2GetBoolean / fmi2SetBoolean: set before initialization,
    fixed after it (fmi2Error, the reason logged); not a Real (fmi2GetReal refuses vr 6)."""
    unit = Unit(built["Ram"])
    vr = unit.vr["contact_mid_step"]
    try:
        unit.instantiate()
        assert unit.fmu.getBoolean([vr]) == [True]
        unit.fmu.setBoolean([vr], [False])
        assert unit.fmu.getBoolean([vr]) == [False]
        with pytest.raises(FMICallException):
            unit.fmu.getReal([vr])
        assert any("fmi2GetReal: unknown value reference 6" in m for m in unit.messages)
        unit.fmu.setupExperiment(startTime=0.0)
        unit.fmu.enterInitializationMode()
        unit.fmu.exitInitializationMode()
        with pytest.raises(FMICallException):
            unit.fmu.setBoolean([vr], [True])
        assert any("contact_mid_step is fixed after initialization" in m
                   for m in unit.messages)
        unit.fmu.reset()  # the build's value again
        assert unit.fmu.getBoolean([vr]) == [True]
    finally:
        unit.close()


def test_a_modal_ram_without_its_rigid_mode_is_not_native():
    modes = type("Modes", (), {"omega": np.array([10.0, 20.0])})()
    ram = type("Modal", (), {"is_modal_unit": True, "modes": modes})()
    supported, reason = nu.native_ram_support(ram)
    assert not supported and "rigid-body mode" in reason


def test_unknown_parameter_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="soil_model: not a parameter of the native PileSoil"):
        nu.build_native_pile_soil_fmu(_pile_soil(), tmp_path, soil_model="smith")


# ---------------------------------------------------------------------------- binaries
def test_shipped_binaries_are_built_from_the_current_sources():
    recorded = json.loads((nu.BINARIES_DIR / nu.DIGEST_FILE).read_text())
    assert {kind: recorded[kind] for kind in nu.BINARY_KINDS} == \
        {kind: nu.sources_digest(kind) for kind in nu.BINARY_KINDS}
    for kind in nu.BINARY_KINDS:
        assert (nu.BINARIES_DIR / "linux64" / f"{kind}.so").is_file()
        assert (nu.BINARIES_DIR / "win64" / f"{kind}.dll").is_file()


# The oldest glibc the Linux binaries load on: 2.14 (2011; CentOS 7 has 2.17). A symbol taken
# from a newer version (exp@GLIBC_2.29 by default with gcc 12) raises the floor silently.
GLIBC_FLOOR = (2, 14)


def test_linux_binaries_load_on_glibc_2_14():
    """Every glibc symbol version the shipped Linux binaries need (the version names in their
    dynamic string table, which an ELF file lists only for the versions it requires) is at
    most :data:`GLIBC_FLOOR`."""
    import re
    for kind in nu.BINARY_KINDS:
        data = (nu.BINARIES_DIR / "linux64" / f"{kind}.so").read_bytes()
        versions = {tuple(int(p) for p in m.group(1).split(b"."))
                    for m in re.finditer(rb"GLIBC_(\d+(?:\.\d+)+)\x00", data)}
        assert versions, f"{kind}.so names no glibc version: the check reads the wrong bytes"
        assert max(versions) <= GLIBC_FLOOR, f"{kind}.so needs glibc {max(versions)}"


@pytest.mark.parametrize("platform", list(nu.PLATFORMS))
def test_sources_compile_warning_free_and_equal_the_shipped_binary(platform, tmp_path):
    """-Wall -Wextra -pedantic -Werror with gcc and mingw-w64; a fresh build is the shipped
    file byte for byte when the compiler is the version that built them (recorded beside
    them), and the shipped file exports the FMI functions."""
    if nu.platform_compiler(platform) is None:
        pytest.skip(f"no compiler for {platform}: {', '.join(nu.PLATFORMS[platform]['compilers'])}")
    recorded = json.loads((nu.BINARIES_DIR / nu.DIGEST_FILE).read_text())["compilers"]
    same_compiler = recorded.get(platform) == nu.compiler_version(platform)
    suffix = nu.PLATFORMS[platform]["suffix"]
    for kind in nu.BINARY_KINDS:
        fresh = nu.compile_unit(kind, platform, tmp_path / f"{kind}{suffix}")
        shipped = nu.BINARIES_DIR / platform / f"{kind}{suffix}"
        assert fresh.stat().st_size > 0  # compiled warning-free (-Werror)
        if same_compiler:
            assert fresh.read_bytes() == shipped.read_bytes(), \
                f"{shipped} is not the build of the current sources: rebuild the binaries"
        objdump = shutil.which("x86_64-w64-mingw32-objdump" if platform == "win64"
                               else "objdump")
        if objdump:
            listing = subprocess.run([objdump, "-p" if platform == "win64" else "-T",
                                      str(shipped)], capture_output=True, text=True).stdout
            for name in ("fmi2Instantiate", "fmi2DoStep", "fmi2GetReal", "fmi2SetReal",
                         "fmi2FreeInstance", "fmi3InstantiateCoSimulation", "fmi3DoStep",
                         "fmi3GetFloat64"):
                assert name in listing


UNIT_HOST = Path(__file__).resolve().parent / "c_host" / "unit_host.c"


def test_the_win64_binaries_run_under_wine_with_the_linux_numbers(built, table1_fmus,
                                                                  tmp_path):
    """tests/c_host/unit_host.c cross-compiled with mingw-w64 runs the shipped win64 DLLs of
    an FMU under Wine (Ram, PileSoil, and Table 1's Anvil and AnvilLumped, one DLL for both,
    reading its modal data from the resources folder); 2000 steps of a constant input give
    the linux64 binary's outputs (the same operations; rtol 1e-12 as above: the two C
    runtimes' exp and cos may differ in the last bit)."""
    mingw, wine = shutil.which("x86_64-w64-mingw32-gcc"), shutil.which("wine")
    gcc = nu.platform_compiler("linux64")
    if not (mingw and wine and gcc):
        pytest.skip("needs x86_64-w64-mingw32-gcc, wine and gcc (apt-get install mingw-w64 "
                    "wine64)")
    include = str(nu.NATIVE_DIR)
    for compiler, exe, libs in ((mingw, tmp_path / "unit_host.exe", []),
                                (gcc, tmp_path / "unit_host", ["-ldl"])):
        run = subprocess.run([compiler, "-std=c99", "-O2", "-I", include, "-o", str(exe),
                              str(UNIT_HOST), *libs], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
    cases = {"Ram": ("F_toe", 1e7, "u_toe", "v_toe"),
             "PileSoil": ("F_head", 3.5e6, "u_head", "F_gauge"),
             # the ram toe held 0.1 mm down: the anvil pressed onto the pile, ringing
             "Anvil": ("u_ram", 1e-4, "u_top", "u_bottom"),
             "AnvilLumped": ("u_ram", 1e-4, "u_top", "u_bottom")}
    fmus = {**table1_fmus[1], **built}
    for kind, (name_in, value, out1, out2) in cases.items():
        folder = tmp_path / kind
        with zipfile.ZipFile(fmus[kind]) as zf:
            zf.extractall(folder)
        md = read_model_description(str(fmus[kind]))
        vr = {v.name: v.valueReference for v in md.modelVariables}
        tail = [md.guid, str(vr[name_in]), repr(value), str(vr[out1]), str(vr[out2]), "2000",
                "1e-5"]
        linux = subprocess.run([str(tmp_path / "unit_host"),
                                str(folder / "binaries" / "linux64" / f"{kind}.so"),
                                f"file://{folder}/resources", *tail],
                               capture_output=True, text=True, timeout=120)
        windows = subprocess.run([wine, str(tmp_path / "unit_host.exe"),
                                  f"{kind}\\binaries\\win64\\{kind}.dll",
                                  f"file:///Z:{folder}/resources", *tail], cwd=tmp_path,
                                 capture_output=True, text=True, timeout=600,
                                 env={"WINEDEBUG": "-all", "HOME": str(Path.home()),
                                      "PATH": "/usr/bin:/bin"})
        assert linux.returncode == 0, linux.stderr
        assert windows.returncode == 0, windows.stdout + windows.stderr
        assert "unit_host: ok" in windows.stdout
        a = np.array(linux.stdout.split()[:2], dtype=float)
        b = np.array(windows.stdout.split()[:2], dtype=float)
        assert np.all(a != 0.0)
        np.testing.assert_allclose(b, a, rtol=RTOL)
        print(f"\n{kind}: linux64 {a[0]:.17g} {a[1]:.17g}; win64 under Wine "
              f"{b[0]:.17g} {b[1]:.17g}")


@pytest.mark.parametrize("kind", nu.UNIT_KINDS)
def test_fmi3_units_validate_and_equal_the_fmi2_units(built, tmp_path, kind):
    """The FMI 3.0 variant (the same binaries, the fmi3 API) validates with fmpy and, under
    fmpy.simulate_fmu with the same input, gives the FMI 2.0 unit's outputs bit for bit (one
    model behind both APIs)."""
    from fmpy import simulate_fmu
    from fmpy.validation import validate_fmu

    if kind == "Ram":
        path = nu.build_native_ram_fmu(load_hammer("illustrative_5500kj", 9.81), tmp_path,
                                       fmi_version=3, v_impact=6.0, gravity=9.81,
                                       contact_displacement=1e-3, contact_time=0.0)
        name_in, value = "F_toe", 1e7
    else:
        path = nu.build_native_pile_soil_fmu(_pile_soil(), tmp_path, fmi_version=3,
                                             static_head_load=3.19e6, gravity=9.81)
        name_in, value = "F_head", 3.5e6
    md = read_model_description(str(path))
    assert md.fmiVersion == "3.0" and md.license == "MIT"
    assert not validate_fmu(str(path))
    with zipfile.ZipFile(path) as zf:
        names = set(zf.namelist())
    assert {f"binaries/x86_64-linux/{kind}.so", f"binaries/x86_64-windows/{kind}.dll"} <= names
    signal = np.array([(0.0, value), (1.0, value)], dtype=[("time", float), (name_in, float)])
    outputs = [v.name for v in nu.VARIABLES[kind] if v.causality == "output"]
    runs = [simulate_fmu(str(p), stop_time=2e-3, step_size=1e-5, output_interval=1e-5,
                         input=signal, output=outputs) for p in (path, built[kind])]
    assert len(runs[0]) == len(runs[1]) == 201
    for name in outputs:
        assert np.array_equal(runs[0][name], runs[1][name]), name
    assert np.ptp(runs[0][outputs[0]]) > 0.0


def test_build_fmus_fmi3_builds_every_unit_as_fmi3(table1_fmus, tmp_path, capsys):
    """``build-fmus --fmi-version 3``: the four native units (anvils included) as FMI 3.0
    FMUs that validate with fmpy; the anvils give the FMI 2.0 build's outputs bit for bit
    under fmpy.simulate_fmu (a ram toe pressing 0.1 mm, as the Wine test). The pythonfmu
    anvils have no FMI 3.0 variant: ``--python-anvil --fmi-version 3`` is refused, one line,
    exit 2, nothing written."""
    from anvilwave.cli import main

    out = tmp_path / "fmus"
    assert main(["build-fmus", str(EXAMPLES / "table1.toml"), "--out", str(out),
                 "--fmi-version", "3"]) == 0
    for kind in ("Ram", "Anvil", "AnvilLumped", "PileSoil"):
        md = read_model_description(str(out / f"{kind}.fmu"))
        assert md.fmiVersion == "3.0", kind
        assert not fmpy.validation.validate_fmu(str(out / f"{kind}.fmu")), kind
    signal = np.array([(0.0, 1e-4), (1.0, 1e-4)], dtype=[("time", float), ("u_ram", float)])
    outputs = ["F_ram", "F_pile", "u_top", "u_bottom"]
    for kind in ("Anvil", "AnvilLumped"):
        runs = [fmpy.simulate_fmu(str(p), start_time=0.0, stop_time=2e-3, step_size=1e-5,
                                  output_interval=1e-5, input=signal, output=outputs)
                for p in (out / f"{kind}.fmu", table1_fmus[1][kind])]
        for name in outputs:
            assert np.array_equal(runs[0][name], runs[1][name]), (kind, name)
        assert runs[0]["F_ram"].max() > 0.0
    capsys.readouterr()
    refused = tmp_path / "refused"
    assert main(["build-fmus", str(EXAMPLES / "table1.toml"), "--out", str(refused),
                 "--fmi-version", "3", "--python-anvil"]) == 2
    message = capsys.readouterr().err.strip()
    assert "FMI 3.0 anvils are the native anvils" in message and "\n" not in message
    assert not refused.exists()


def test_the_shipped_binaries_are_package_data():
    """Every shipped binary and its digest file match a package-data pattern of pyproject.toml
    (so the wheel carries them: build-fmus needs no compiler after pip install)."""
    import fnmatch

    project = tomllib.loads((nu.NATIVE_DIR.parents[2] / "pyproject.toml").read_text())
    patterns = project["tool"]["setuptools"]["package-data"]["anvilwave.fmu"]
    files = [nu.BINARIES_DIR / nu.DIGEST_FILE] + [
        nu.BINARIES_DIR / platform / f"{kind}{spec['suffix']}"
        for platform, spec in nu.PLATFORMS.items() for kind in nu.BINARY_KINDS]
    for path in files:
        relative = path.relative_to(nu.NATIVE_DIR.parent).as_posix()
        assert any(fnmatch.fnmatch(relative, p) for p in patterns), relative
    sources = [name for kind in nu.BINARY_KINDS for name in nu.unit_sources(kind)]
    assert all(any(fnmatch.fnmatch(f"native/{name}", p) for p in patterns) for name in sources)
