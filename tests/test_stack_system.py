"""The driving stack from the system file (``[[anvil.bodies]]``) in the engine's compiled blow
loop: one body is the system of ``[anvil] file`` to the bit; with the ring the loop's blow is
the Python runner's (:func:`anvilwave.analyses.stack_blow.run_stack_blow`) to the bit, its
energy balances with seat friction on (also on the tube head), and ``drive`` gives a blow count
per depth."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import fea_config
from anvilwave.analyses.drive import drive
from anvilwave.analyses.impact import energy_balance
from anvilwave.analyses.stack_blow import run_stack_blow, stack_unit
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.engine.fmi import run_fmi
from anvilwave.inputs import InputError

EXAMPLES = Path(__file__).resolve().parents[1] / "anvilwave" / "examples"
ANVIL = f'[[anvil.bodies]]\nfile = "{EXAMPLES / "anvils" / "xl8.toml"}"\n'
RING = f'[[anvil.bodies]]\nfile = "{EXAMPLES / "anvils" / "xl8_ring.toml"}"\n'


def with_bodies(tmp_path: Path, example: str, bodies: str, name: str = "system.toml",
                anvil_keys: str = "") -> Path:
    """``example`` with ``[anvil] file`` replaced by ``bodies`` (its other paths absolute),
    ``anvil_keys`` added to its ``[anvil]``."""
    text = (EXAMPLES / example).read_text()
    assert text.count('file = "anvils/xl8.toml"\n') == 1
    text = text.replace('file = "anvils/xl8.toml"\n', anvil_keys)
    text = text.replace('cpt = "soil/', f'cpt = "{EXAMPLES / "soil"}/')
    head, tail = text.split("[pile]\n", 1)
    path = tmp_path / name
    path.write_text(f"{head}{bodies}\n[pile]\n{tail}")
    return path


def test_one_body_is_the_anvil_file_to_the_bit(tmp_path):
    """``[[anvil.bodies]]`` with the anvil alone is ``[anvil] file``: the same configuration
    and the same Table 1 blow, every recorded column bit for bit."""
    one = load_system(with_bodies(tmp_path, "table1.toml", ANVIL))
    today = load_system(EXAMPLES / "table1.toml")
    assert one.anvil.stack is None
    assert repr(one.anvil) == repr(today.anvil)
    a = build_engine(one).blow(duration=0.005)
    b = build_engine(today).blow(duration=0.005)
    assert a.columns.keys() == b.columns.keys()
    for name in a.columns:
        assert np.array_equal(a.columns[name], b.columns[name]), name


@pytest.fixture(scope="module")
def ring_system(tmp_path_factory):
    """Table 1 with the ring, seat friction 0.3 (the study's largest)."""
    path = with_bodies(tmp_path_factory.mktemp("stack"), "table1.toml",
                       ANVIL + RING + "seat_friction = 0.3\n")
    return load_system(path)


@pytest.fixture(scope="module")
def engine_blow(ring_system):
    return build_engine(ring_system).blow()


def test_the_system_file_sets_the_stack(ring_system):
    stack = ring_system.anvil.stack
    assert (stack.seat_friction, stack.seat_rings, stack.pile_rings, stack.ram_annuli) == (
        0.3, 8, 3, 6)
    assert ring_system.hammer.ram.modes.n_annuli == 6  # the ram's toe in the face's annuli


def test_the_reference_fea_of_the_system_is_the_fea_stack(ring_system):
    """``anvilwave fea`` and ``compare`` of a system with the ring run the FEA stack: its ring
    and seat friction are the system file's."""
    config = fea_config(ring_system)
    assert config.ring is ring_system.anvil.stack.ring and config.seat_friction == 0.3
    assert fea_config(load_system(EXAMPLES / "table1.toml")).ring is None


def test_the_compiled_loop_is_the_python_runner_to_the_bit(ring_system, engine_blow):
    """The engine's loop with the stack and the per-step Python runner on the whole 25 ms
    blow: the same kernels (the modal ram unit's, the stack's, the pile's) on the same arrays
    in the same order, so nothing rounds differently and the tolerance is zero. The runner
    records from t = -h/2 on the same grid, one row fewer (the engine's last is t_N)."""
    st = ring_system.anvil.stack
    python = run_stack_blow(ring_system, stack_unit(
        ring_system, st.ring, seat_friction=st.seat_friction, seat_rings=st.seat_rings,
        pile_rings=st.pile_rings, ram_annuli=st.ram_annuli))
    n = python.pile_force.size
    assert engine_blow.columns["time [s]"].size == n + 1
    assert np.array_equal(engine_blow.columns["anvil_pile_force [N]"][:n], python.pile_force)
    assert np.array_equal(engine_blow.columns["ram_anvil_force [N]"][:n], python.ram_force)
    assert python.friction_energy > 0.01 * python.input_energy  # the seat slides


def test_the_compiled_loop_balances_its_energy_with_friction(engine_blow):
    """The whole system's balance (ram, stack with its friction and dashpot losses, pile and
    soil) within the issue's 0.5 % of the ram's energy at every energy row, mu 0.3."""
    balance = energy_balance(engine_blow)
    assert abs(balance["max_deviation_relative [-]"]) < 0.005
    assert abs(balance["residual_relative [-]"]) < 0.005


def test_the_tube_head_stack_is_the_python_runners_and_balances_its_energy():
    """table1_ring.toml (the ring's pile rings on the tube head, seat friction 0.2, the seat
    in 32 rings): the engine's loop and the Python runner give the same 10 ms blow to the bit
    (the same kernels: the tube's history and shift are the stack state's), the whole system's
    energy balances within the issue's 0.5 % (the work the rings hand to the tube booked), and
    the tube changes the blow against the 1D head (its history is not idle)."""
    cfg = load_system(EXAMPLES / "table1_ring.toml")
    st = cfg.anvil.stack
    assert cfg.anvil.pile_head == "tube" and st.seat_rings == 32
    engine = build_engine(cfg).blow(duration=0.01)
    options = {"seat_friction": st.seat_friction, "seat_rings": st.seat_rings,
               "pile_rings": st.pile_rings, "ram_annuli": st.ram_annuli}
    python = run_stack_blow(cfg, stack_unit(cfg, st.ring, pile_head="tube", **options),
                            duration=0.01)
    n = python.pile_force.size
    assert np.array_equal(engine.columns["anvil_pile_force [N]"][:n], python.pile_force)
    assert np.array_equal(engine.columns["ram_anvil_force [N]"][:n], python.ram_force)
    balance = energy_balance(engine)
    assert abs(balance["max_deviation_relative [-]"]) < 0.005
    assert np.abs(python.energy_residual).max() < 0.005 * python.input_energy
    rod = run_stack_blow(cfg, stack_unit(cfg, st.ring, **options), duration=0.01)
    assert np.abs(rod.pile_force - python.pile_force).max() > 0.01 * python.pile_force.max()


def test_the_stack_in_a_sleeve_is_the_python_runners_and_balances_its_energy(tmp_path):
    """Table 1's ring stack in a rigid sleeve 1 mm off the 4.15 m rims (``[anvil]
    sleeve_clearance``), friction 0.2 on the seat and against the sleeve: the system file sets
    the sleeve, the engine's loop gives the Python runner's 10 ms blow to the bit, the rims
    reach the sleeve and the sliding along it dissipates on top of the seat's, and the whole
    system's energy balances within the issue's 0.5 %."""
    path = with_bodies(tmp_path, "table1.toml", ANVIL + RING + "seat_friction = 0.2\n",
                       anvil_keys="sleeve_clearance = 0.001\nsleeve_friction = 0.2\n"
                                  "sleeve_bands = [4, 5]\n")
    cfg = load_system(path)
    st = cfg.anvil.stack
    assert (st.sleeve_clearance, st.sleeve_friction, st.sleeve_bands) == (0.001, 0.2, (4, 5))
    engine = build_engine(cfg).blow(duration=0.01)
    options = {"seat_friction": st.seat_friction, "seat_rings": st.seat_rings,
               "pile_rings": st.pile_rings, "ram_annuli": st.ram_annuli}
    unit = stack_unit(cfg, st.ring, sleeve_clearance=0.001, sleeve_friction=0.2,
                      sleeve_bands=(4, 5), **options)
    python = run_stack_blow(cfg, unit, duration=0.01)
    n = python.pile_force.size
    assert np.array_equal(engine.columns["anvil_pile_force [N]"][:n], python.pile_force)
    assert np.array_equal(engine.columns["ram_anvil_force [N]"][:n], python.ram_force)
    balance = energy_balance(engine)
    assert abs(balance["max_deviation_relative [-]"]) < 0.005
    assert np.abs(python.energy_residual).max() < 0.005 * python.input_energy
    seat_only = run_stack_blow(cfg, stack_unit(cfg, st.ring, **options), duration=0.01)
    # measured: 23 % of the blow with the sleeve, 3.6 % on the seat alone
    assert python.friction_energy > 3.0 * seat_only.friction_energy


def test_drive_gives_a_blow_count_per_depth_with_the_stack(tmp_path):
    """The XL monopile's drive with the ring stack at two depths: a finite positive blow count
    at each, and the stack's weight (anvil and ring) on the pile head."""
    path = with_bodies(tmp_path, "xl_monopile_drive.toml", ANVIL + RING + "seat_friction = 0.1\n")
    text = path.read_text()
    text = text.replace("start = 2.0 ", "start = 10.0").replace("stop = 40.0", "stop = 20.0")
    text = text.replace("step = 1.0\n", "step = 10.0\n").replace(
        "time_series_depths = [20.0, 40.0]\n", "")
    path.write_text(text.split("[installation]")[0])
    cfg = load_system(path)
    result = drive(cfg, workers=1)
    counts = np.array([row["blow_count [1/m]"] for row in result.rows])
    assert counts.size == 2 and np.all(np.isfinite(counts)) and np.all(counts > 0)
    engine = build_engine(cfg)
    assert engine.static_head_force == pytest.approx(
        engine.anvil.unit.total_mass * cfg.gravity, rel=1e-12)
    assert engine.anvil.unit.total_mass > build_engine(
        cfg.with_anvil_model("lumped")).static_head_force / cfg.gravity


def test_the_stack_fmu_under_fmpy_is_the_engines_blow(tmp_path):
    """``AnvilStack.fmu`` (the stack inside, ram in and pile out) with ``Ram.fmu`` and
    ``PileSoil.fmu`` under the fmpy master (:func:`anvilwave.engine.fmi.run_fmi`) against the
    in-process blow, Table 1 with the ring at mu 0.3 in a sleeve 1 mm off (mu 0.2 against
    it; the data file carries the sleeve, the FMU its coefficient) and the one ram port (the
    FMUs' one toe port), 10 ms. The FMUs run the same kernels; the master places the ram's
    first contact at the FMU's ``u_top`` at rest, the engine at the rest's own gap: the same
    sum in another order, an ulp apart, which the stiff contacts carry to 1e-12 of the peak
    forces (measured 7e-13). The bar, 1e-9 of the peaks, is that round-off with room, and
    30 000 times below the 3e-5 that a first contact off by the residual flexibility's share
    of u_top gave."""
    path = with_bodies(tmp_path, "table1.toml", ANVIL + RING + "seat_friction = 0.3\n",
                       anvil_keys="sleeve_clearance = 0.001\nsleeve_friction = 0.2\n")
    text = path.read_text().replace('model = "rom"', 'model = "rom"\nram_port_annuli = 1', 1)
    path.write_text(text)
    cfg = load_system(path)
    assert cfg.anvil.stack.sleeve_clearance == 0.001
    fmi = run_fmi(cfg, tmp_path / "fmus", duration=0.01, native_anvil=False)[0].columns
    engine = build_engine(cfg).blow(duration=0.01).columns
    for name in ("ram_anvil_force [N]", "anvil_pile_force [N]"):
        assert fmi[name].size == engine[name].size
        peak = np.abs(engine[name]).max()
        assert np.abs(fmi[name] - engine[name]).max() < 1e-9 * peak, name
    with pytest.raises(InputError, match="ram_port_annuli"):  # the stack's face in annuli
        run_fmi(load_system(with_bodies(tmp_path, "table1.toml", ANVIL + RING, "six.toml")),
                tmp_path / "six", duration=0.001, native_anvil=False)
