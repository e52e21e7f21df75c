"""The pythonfmu units (Ram, PileSoil, the Python anvil) in a plain C host.

tests/c_host/fmi_host.c loads an FMU binary with dlopen, runs two instances, resets them and
reruns (bitwise the same), terminates, frees, dlcloses and exits. The host has no Python: the
environment is the user's venv ``bin`` on the PATH and nothing else (no LD_PRELOAD, no
PYTHONPATH, no PYTHONHOME). The FMU's status shim (anvilwave/fmu/units/fmi2_status_shim.c) loads the
libpython recorded at build time (resources/anvilwave_python.txt), initializes it with the
venv's python as program name (its site-packages, so anvilwave imports) and never finalizes it,
and releases pythonfmu's Python state once (pythonfmu 0.7.0 releases it twice at exit).
Before: "undefined symbol: _Py_NoneStruct" without LD_PRELOAD; with libpython preloaded, an
abort at exit, "free(): corrupted unsorted chunks".

Needs the system C compiler (for the host and the shim); skipped with the reason without one.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from fmpy import read_model_description  # noqa: E402

from anvilwave.fmu.fmi_build import (  # noqa: E402
    RUNTIME_FILE,
    SHIM_INNER_LIBRARY,
    build_fmu,
    build_pile_soil_fmu,
    build_ram_fmu,
    toml_dumps,
)
from anvilwave.fmu.native_build import NativeBuildError, find_compiler  # noqa: E402

from .conftest import EXAMPLES, ROOT  # noqa: E402

HOST_SOURCE = ROOT / "tests" / "c_host" / "fmi_host.c"
VENV_BIN = Path(sys.executable).parent
CONTACTS = {"ram_contact_stiffness": 5.9e12, "pile_contact_stiffness": 2.9e12}  # [N/m]

# inputs and outputs of each unit, and the input signals c0,c1,c2,a,b,f:
# c0 + c1 t + c2 t^2 + a sin(2 pi f t) + b cos(2 pi f t)
UNITS = {
    "Ram": (("F_toe",), ("u_toe", "v_toe"), {"F_toe": "0,0,0,1e8,0,500"}),
    "PileSoil": (("F_head",), ("u_head", "v_head", "F_gauge", "v_gauge"),
                 {"F_head": "3.19e6,0,0,1e8,0,500"}),
    "AnvilLumped": (("u_ram", "v_ram", "u_pile", "v_pile"), ("F_ram", "F_pile", "u_top",
                                                               "u_bottom"),
                    {"u_ram": "-2e-5,4,-1.5e4,0,0,0", "v_ram": "4,-3e4,0,0,0,0",
                     "u_pile": "0,0,0,2e-4,0,400", "v_pile": "0,0,0,0,0.5026548245743669,400"}),
}


def _compiler() -> str:
    try:
        return find_compiler()
    except NativeBuildError as exc:
        pytest.skip(f"the C host and the status shim need a C compiler: {exc}")


@pytest.fixture(scope="module")
def host(tmp_path_factory) -> Path:
    """tests/c_host/fmi_host.c compiled with the system compiler."""
    compiler = _compiler()
    exe = tmp_path_factory.mktemp("c_host") / "fmi_host"
    run = subprocess.run([*compiler.split(), "-std=c99", "-O2", "-I", str(ROOT / "anvilwave" /
    "fmu" / "native"),
                          "-o", str(exe), str(HOST_SOURCE), "-ldl", "-lm"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        pytest.fail(f"the C host does not compile:\n{run.stderr}")
    return exe


@pytest.fixture(scope="module")
def fmus(tmp_path_factory) -> dict[str, Path]:
    """Ram (the database hammer), PileSoil (Table 1's pile and soil) and the pythonfmu
    AnvilLumped, each built with the status shim."""
    _compiler()
    out = tmp_path_factory.mktemp("pythonfmu_units")
    tables = tomllib.loads((EXAMPLES / "table1.toml").read_text())
    pile_file = out / "table1_pile_soil.toml"
    pile_file.write_text(toml_dumps({"pile": tables["pile"], "soil": tables["soil"]}))
    built = {"Ram": build_ram_fmu(out, "illustrative_5500kj", v_impact=6.0),
             "PileSoil": build_pile_soil_fmu(out, pile_file, static_head_load=3.19e6),
             "AnvilLumped": build_fmu("AnvilLumped", out, {"mass": 3.25e5, **CONTACTS})}
    for path in built.values():
        with zipfile.ZipFile(path) as zf:
            names = zf.namelist()
        assert f"binaries/linux64/{SHIM_INNER_LIBRARY}" in names  # the shim is in front
        assert f"resources/{RUNTIME_FILE}" in names
    return built


def unpack(path: Path, folder: Path) -> Path:
    with zipfile.ZipFile(path) as zf:
        zf.extractall(folder)
    return folder


def host_command(host: Path, fmu_dir: Path, md, kind: str, csv: Path, steps: int = 2000,
                 instances: int = 2) -> list[str]:
    inputs, outputs, signals = UNITS[kind]
    vr = {v.name: v.valueReference for v in md.modelVariables}
    command = [str(host), str(fmu_dir), md.coSimulation.modelIdentifier, md.guid,
               "--inputs", ",".join(str(vr[n]) for n in inputs),
               "--outputs", ",".join(str(vr[n]) for n in outputs),
               "--steps", str(steps), "--step-size", "1e-5", "--instances", str(instances),
               "--csv", str(csv)]
    for name, signal in signals.items():
        command += ["--signal", f"{vr[name]}={signal}"]
    return command


@pytest.mark.parametrize("kind", list(UNITS))
def test_pythonfmu_unit_in_a_c_host_with_the_venv_on_the_path(host, fmus, tmp_path, kind):
    """Two instances, 2000 steps, fmi2Reset and a bitwise-identical rerun, clean exit 0; the
    host's outputs are those of fmpy running the same FMU on the same inputs."""
    fmu_dir = unpack(fmus[kind], tmp_path / kind)
    md = read_model_description(str(fmus[kind]))
    csv = tmp_path / "host.csv"
    env = {"PATH": f"{VENV_BIN}:/usr/bin:/bin"}
    run = subprocess.run(host_command(host, fmu_dir, md, kind, csv), env=env,
                         capture_output=True, text=True, timeout=300)
    print("\n" + run.stdout + run.stderr)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.count("rerun after fmi2Reset bitwise identical: yes") == 2
    assert run.stdout.rstrip().endswith("fmi_host: ok")
    assert "corrupted" not in run.stderr and "undefined symbol" not in run.stderr
    # the same FMU under fmpy in this Python, on the inputs the host used: the same numbers
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    n_in = len(UNITS[kind][0])
    expected = fmpy_outputs(fmus[kind], kind, table[:, 0], table[:, 1:1 + n_in])
    assert np.array_equal(table[:, 1 + n_in:], expected)


def fmpy_outputs(path: Path, kind: str, time: np.ndarray, inputs: np.ndarray) -> np.ndarray:
    """The outputs of ``path`` under fmpy: inputs set, outputs read, step (the host's order)."""
    from fmpy import extract
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    folder = extract(str(path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=folder, instanceName="reference",
                    modelIdentifier=md.coSimulation.modelIdentifier)
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        vr_in = [vr[n] for n in UNITS[kind][0]]
        vr_out = [vr[n] for n in UNITS[kind][1]]
        out = np.empty((len(time), len(vr_out)))
        for n, t in enumerate(time):
            fmu.setReal(vr_in, list(inputs[n]))
            out[n] = fmu.getReal(vr_out)
            fmu.doStep(t, 1e-5)
        fmu.terminate()
    finally:
        fmu.freeInstance()
    return out


def _runtime(fmu_dir: Path, **changes: str) -> None:
    """Rewrite keys of the FMU's resources/anvilwave_python.txt (a moved or missing Python)."""
    path = fmu_dir / "resources" / RUNTIME_FILE
    lines = []
    for line in path.read_text().splitlines():
        key = line.split("=")[0].strip()
        lines.append(f"{key} = {changes[key]}" if key in changes else line)
    path.write_text("\n".join(lines) + "\n")


def test_the_python_that_built_it_gone_the_one_on_the_path_runs_it(host, fmus, tmp_path):
    """The recorded Python is gone: the python3.X of the venv on the PATH runs the unit, and
    the host is told which (a warning)."""
    fmu_dir = unpack(fmus["Ram"], tmp_path / "Ram")
    _runtime(fmu_dir, executable="/gone/bin/python", library="/gone/lib/libpython.so.1.0")
    md = read_model_description(str(fmus["Ram"]))
    run = subprocess.run(host_command(host, fmu_dir, md, "Ram", tmp_path / "host.csv", 200, 1),
                         env={"PATH": f"{VENV_BIN}:/usr/bin:/bin"}, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "the Python that built this FMU (/gone/bin/python) is gone: running its unit in " \
           f"{VENV_BIN}/python" in run.stderr


@pytest.mark.parametrize("kind", ["Ram", "PileSoil"])
def test_the_builders_venv_gone_a_python_without_anvilwave_runs_it(host, fmus, tmp_path, kind,
                                                                  plain_python):
    """The Python that built the FMU and its site-packages gone, only a venv with fmpy, numpy,
    scipy and numba on the PATH (no anvilwave, no pythonfmu): the shim starts that venv's
    python, the unit runs its own copy of its anvilwave code (resources/anvilwave_fmu_*) and
    gives the outputs of fmpy in this Python on the same inputs, bitwise."""
    fmu_dir = unpack(fmus[kind], tmp_path / kind)
    _runtime(fmu_dir, executable="/gone/bin/python", library="/gone/lib/libpython.so.1.0",
             site="/gone/lib/site-packages")
    md = read_model_description(str(fmus[kind]))
    csv = tmp_path / "host.csv"
    run = subprocess.run(host_command(host, fmu_dir, md, kind, csv, 200, 1),
                         env={"PATH": f"{plain_python.parent}:/usr/bin:/bin"},
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"running its unit in {plain_python.parent}/python" in run.stderr
    assert "No module named" not in run.stderr
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    n_in = len(UNITS[kind][0])
    expected = fmpy_outputs(fmus[kind], kind, table[:, 0], table[:, 1:1 + n_in])
    assert np.array_equal(table[:, 1 + n_in:], expected)


def test_no_python_at_all_is_a_clear_error(host, fmus, tmp_path):
    """No recorded Python and none on the PATH: fmi2Instantiate fails with the reason, the
    host exits normally (status 1, no crash)."""
    fmu_dir = unpack(fmus["Ram"], tmp_path / "Ram")
    _runtime(fmu_dir, executable="/gone/bin/python", library="/gone/lib/libpython.so.1.0")
    md = read_model_description(str(fmus["Ram"]))
    run = subprocess.run(host_command(host, fmu_dir, md, "Ram", tmp_path / "host.csv", 20, 1),
                         env={"PATH": str(tmp_path / "empty")}, capture_output=True,
                         text=True, timeout=120)
    print("\n" + run.stderr)
    assert run.returncode == 1
    version = f"{sys.version_info[0]}.{sys.version_info[1]}"
    assert (f"cannot start Python: this FMU runs its unit in Python {version} with anvilwave "
            f"installed: the Python that built it (/gone/bin/python, library "
            f"/gone/lib/libpython.so.1.0) is gone and no python{version} is on the PATH"
            in run.stderr)


SYSTEM_HOST_SOURCE = ROOT / "tests" / "c_host" / "system_host.c"


def test_native_three_unit_system_in_a_c_host_with_an_empty_environment_equals_the_engine(
        tmp_path):
    """Ram, Anvil and PileSoil, all native (no Python inside), run by tests/c_host/
    system_host.c (the DESIGN.md exchange order of fmi_master.BlowMaster) with an empty
    environment: the peak contact forces equal the in-process engine's to 1e-9 of the peaks
    (the same kernels in C and numba, the same exchange; the bound is the issue's)."""
    from anvilwave.config.system import load_system
    from anvilwave.engine.direct import build_engine
    from anvilwave.engine.fmus import build_system_fmus, load_anvil_modal_data

    compiler = _compiler()
    exe = tmp_path / "system_host"
    run = subprocess.run([*compiler.split(), "-std=c99", "-O2", "-I",
                          str(ROOT / "anvilwave" / "fmu" / "native"), "-o", str(exe),
                          str(SYSTEM_HOST_SOURCE), "-ldl"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    cfg = load_system(EXAMPLES / "size_s2.toml")  # a rod ram (Table 1's is modal)
    modal = load_anvil_modal_data(cfg)
    fmus = build_system_fmus(cfg, tmp_path / "fmus", modal, ssp=False, native_anvil=True,
                             native_units=True)
    assert fmus["ram_implementation"] == fmus["pile_soil_implementation"] == "native"
    kind = fmus["anvil"]
    folders, mds = {}, {}
    for role in ("Ram", kind, "PileSoil"):
        folders[role] = unpack(fmus[role], tmp_path / role)
        mds[role] = read_model_description(str(fmus[role]))
        assert not list(folders[role].rglob("*.py"))  # nothing of Python inside

    def vrs(role, names):
        vr = {v.name: v.valueReference for v in mds[role].modelVariables}
        return ",".join(str(vr[n]) for n in names)

    h = float(fmus["time_step"])
    steps = int(round(cfg.duration / h))
    csv = tmp_path / "system.csv"
    command = [str(exe), str(folders["Ram"]), mds["Ram"].guid, str(folders[kind]), kind,
               mds[kind].guid, str(folders["PileSoil"]), mds["PileSoil"].guid, str(steps),
               repr(h), str(csv),
               "--vr", vrs("Ram", ("F_toe", "u_toe", "v_toe", "contact_displacement",
                                   "contact_time", "contact_mid_step")),
               "--vr", vrs(kind, ("u_ram", "v_ram", "u_pile", "v_pile", "F_ram", "F_pile",
                                  "u_top", "u_bottom", "initial_pile_head_displacement")),
               "--vr", vrs("PileSoil", ("F_head", "u_head", "v_head"))]
    run = subprocess.run(command, env={}, capture_output=True, text=True, timeout=600)
    print("\n" + run.stdout + run.stderr)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.rstrip().endswith("system_host: ok")
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    blow = build_engine(cfg, modal).run(blows=1)[0]
    for column, name in ((1, "ram_anvil_force [N]"), (2, "anvil_pile_force [N]")):
        expected = blow.columns[name].max()
        assert expected > 1e6  # a real blow: the test can fail
        difference = table[:, column].max() - expected
        print(f"{name}: peak {expected:.6e} N, host - engine {difference:.3e} N")
        assert abs(table[:, column].max() - expected) <= 1e-9 * expected, (
            name, table[:, column].max(), expected)
