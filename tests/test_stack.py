"""The driving stack as one unit (anvil + anvil ring, two modal bodies, seat friction) on the
paper's Table 1: without a ring it is the anvil unit's blow to the bit; the ring stack rests in
exact equilibrium, balances its energy with friction on, and keeps the reference FEA stack's
peaks within the issue's bars."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import lowpass, without_soil
from anvilwave.analyses.stack_blow import RAM_ANNULI, run_stack_blow, stack_unit, with_ram_annuli
from anvilwave.anvil_rom import stack
from anvilwave.anvil_rom.fem.geometry import load_anvil
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.inputs import InputError

from .doc_tables import SAME_RUN, doc_data

EXAMPLES = Path(__file__).resolve().parents[1] / "anvilwave" / "examples"


@pytest.fixture(scope="module")
def table1():
    return without_soil(load_system(EXAMPLES / "table1.toml"))


@pytest.fixture(scope="module")
def ring():
    return load_anvil(EXAMPLES / "anvils" / "xl8_ring.toml")


def test_without_ring_the_stack_is_the_anvil_units_blow_to_the_bit(table1):
    engine = build_engine(table1)
    stack = run_stack_blow(table1, stack_unit(table1, None), duration=0.01)
    anvil = run_stack_blow(table1, engine.anvil.unit, duration=0.01)
    assert np.array_equal(stack.ram_force, anvil.ram_force)
    assert np.array_equal(stack.pile_force, anvil.pile_force)
    # and the runner is the in-process engine's blow (its records at t = -h/2 + n h): the same
    # pile-head force to the bit
    head = engine.blow(duration=0.01).columns["anvil_pile_force [N]"]
    assert np.array_equal(head[:anvil.pile_force.size], anvil.pile_force)


def test_ring_stack_rests_in_equilibrium(table1, ring):
    """At rest on the pile with the ram out of reach, the seat rings carry the anvil's weight
    and the pile rings the stack's, and nothing moves over 200 steps (the static state is the
    scheme's fixed point: to 1e-9 of the weights, the rounding of the modal sums)."""
    unit = stack_unit(table1, ring)
    unit.set_step(2e-5)
    _, weight = unit.rest_on_pile(0.0)
    anvil_weight = unit.anvil.total_mass * table1.gravity
    for _ in range(200):
        f_ram, f_pile = unit.forces(-1.0, 0.0, 0.0, 0.0)
        unit.step(f_ram, f_pile, 2e-5)
    assert f_ram == 0.0
    assert f_pile == pytest.approx(weight, rel=1e-9)
    assert unit.seat_force == pytest.approx(anvil_weight, rel=1e-9)
    assert unit.friction_energy == 0.0


@pytest.mark.parametrize("mu", [0.0, 0.2])
def test_ring_stack_energy_balance(table1, ring, mu):
    """The unit's energy change (with the default ram face in six annuli, what the face adds
    to the ram unit's) plus friction and dashpot dissipation against the work the ram and the
    pile did on it, over the first 8 ms (the main pulse), at 10 us: within 0.5 % of the blow
    (the issue's bar; with one ram port measured over 25 ms 0.15 % at 10 us and 0.40 % at the
    system's 20 us: the massless part's energy, not in shadow form, errs at first order in h;
    leaving the face's energy out fails it at mu 0)."""
    blow = run_stack_blow(table1, stack_unit(table1, ring, seat_friction=mu), h=1e-5,
                          duration=0.008)
    assert np.abs(blow.energy_residual).max() < 5e-3 * blow.input_energy
    if mu == 0.0:
        assert blow.friction_energy == 0.0
    else:
        assert blow.friction_energy > 1e-3 * blow.input_energy


def test_friction_zero_is_frictionless_and_coulomb_bounds_hold(table1, ring):
    """mu = 0 gives no tangential force at all; with friction |T| <= mu F_seat on every seat
    ring every step."""
    unit = stack_unit(table1, ring, seat_friction=0.2)
    blow_state = []
    unit.set_step(2e-5)
    u_top, _ = unit.rest_on_pile(0.0)
    u_ram = u_top + 1e-4  # a ram pressed 0.1 mm into the top face, held
    for _ in range(300):
        f_ram, f_pile = unit.forces(u_ram, 0.0, 0.0, 0.0)
        unit.step(f_ram, f_pile, 2e-5)
        blow_state.append(unit.state.forces.copy())
    F = np.array(blow_state)
    J, S = unit.ram_annuli, unit.seat_rings
    N = J + S + unit.pile_rings
    T, seat = F[:, N:], F[:, J:J + S]
    assert np.all(np.abs(T) <= 0.2 * seat * (1 + 1e-12))
    assert np.abs(T).max() > 0.0


@pytest.mark.slow
@pytest.mark.parametrize("mu", [0.0, 0.2])
def test_rom_stack_peaks_within_the_issues_bars(table1, ring, mu):
    """The ROM stack's 25 ms blow on Table 1 (eight seat rings, three pile rings), low-passed
    at 5 kHz on the FEA's 10 us grid as benchmarks/study_anvil_ring.py does: its peaks are the
    docs' data file's (the same run, tests/doc_tables.SAME_RUN; the seat penalty at the data
    file's FEA mesh, as the study takes it), and against the stored FEA
    stack's peaks of that run (docs/data/anvil_ring.json, the FEA of the same coefficient on
    the seat and the ring-pile contact) within the issue's bars, pile 3 % and ram 5 %. The FEA
    is not rerun here (10-40 s each; its own checks are tests/test_fea_ring.py); the ROM's two
    blows take a few seconds once the bodies' modes are cached."""
    values = doc_data("anvil_ring")["values"]
    stored = values["runs"][f"ring, mu {mu:g}"]["rom"]
    penalty = values["mesh_size [m]"] / values.get("contact_stiffness_factor [-]", 1.0)
    blow = run_stack_blow(table1, stack_unit(table1, ring, seat_friction=mu,
                                             penalty_size=penalty))
    t = np.arange(2501) * 1e-5  # the FEA's output grid over the 25 ms
    shifted = blow.time - 0.5 * (blow.time[1] - blow.time[0])  # first contact at t = 0
    for name, series, bar in (("pile", blow.pile_force, 0.03), ("ram", blow.ram_force, 0.05)):
        peak = lowpass(t, np.interp(t, shifted, series), 5000.0).max()
        assert peak == pytest.approx(stored[f"{name}_peak_rom [N]"], **SAME_RUN)
        assert abs(peak / stored[f"{name}_peak_fea [N]"] - 1.0) < bar, name


def test_more_friction_sweeps_change_nothing(table1, ring, monkeypatch):
    """The seat pairs' Gauss-Seidel sweeps are converged: twice as many change the pile-head
    force by less than 1e-6 of its peak over the main pulse at mu 0.2 (measured 7e-8 from 8 to
    32 sweeps; 4 sweeps were 3.8e-5 off)."""
    blows = []
    for sweeps in (stack.FRICTION_SWEEPS, 2 * stack.FRICTION_SWEEPS):
        monkeypatch.setattr(stack, "FRICTION_SWEEPS", sweeps)
        unit = stack_unit(table1, ring, seat_friction=0.2)
        blows.append(run_stack_blow(table1, unit, duration=0.008).pile_force)
    assert np.abs(blows[0] - blows[1]).max() < 1e-6 * blows[1].max()


def test_forces_read_twice_change_nothing(table1, ring):
    """A master may read the feedthrough more than once a step: the same state, dissipation
    and dashpot work as reading it once (bit for bit)."""
    units = [stack_unit(table1, ring, seat_friction=0.2) for _ in range(2)]
    for unit in units:
        unit.set_step(2e-5)
        u_top, _ = unit.rest_on_pile(0.0)
    for i in range(200):
        u_ram, v_ram = u_top + 6.0 * 2e-5 * min(i, 20) - 6.0e-5, 6.0 if i < 20 else 0.0
        for reads, unit in enumerate(units, start=1):
            for _ in range(reads):
                f_ram, f_pile = unit.forces(u_ram, v_ram, 0.0, 0.0)
            unit.step(f_ram, f_pile, 2e-5)
    a, b = (u.state for u in units)
    assert np.array_equal(a.anvil_state, b.anvil_state)
    assert np.array_equal(a.energies, b.energies)
    assert a.energies[1] > 0.0  # the ram dashpot worked


@pytest.fixture(scope="module")
def table1_annuli(table1):
    return with_ram_annuli(table1, 6)


def test_one_ram_port_balances_its_energy(table1, ring):
    """test_ring_stack_energy_balance (the default ram face in six annuli: the ram's flexible
    modes carried twice, their offsets from the ram unit's toe, what the face adds to the ram
    unit's energy) with the one ram port at mu 0.2: within the same 0.5 % of the blow."""
    blow = run_stack_blow(table1, stack_unit(table1, ring, seat_friction=0.2, ram_annuli=1),
                          h=1e-5, duration=0.008)
    assert np.abs(blow.energy_residual).max() < 5e-3 * blow.input_energy
    assert blow.friction_energy > 1e-3 * blow.input_energy


def test_ram_face_in_annuli_rests_and_its_forces_sum_to_the_ram_force(table1_annuli, ring):
    """At rest the annuli carry nothing and the ram touches the face's highest annulus; pressed
    into the face the ram force is the sum of the J annulus forces, each compression-only."""
    unit = stack_unit(table1_annuli, ring, ram_annuli=6)
    unit.set_step(2e-5)
    u_top, weight = unit.rest_on_pile(0.0)
    assert unit.forces(u_top - 1e-9, 0.0, 0.0, 0.0)[0] == 0.0
    assert unit.forces(u_top + 1e-7, 0.0, 0.0, 0.0)[0] > 0.0
    for _ in range(100):
        f_ram, f_pile = unit.forces(u_top + 1e-4, 0.0, 0.0, 0.0)
        unit.step(f_ram, f_pile, 2e-5)
    F = unit.state.forces[:6]
    assert np.all(F >= 0.0)
    assert f_ram == pytest.approx(F.sum(), rel=1e-12)
    assert np.abs(unit.state.ram_offsets[0]).max() > 0.0  # the ram's face deforms


def test_ram_face_in_annuli_is_the_ring_stacks_default(table1, ring):
    """With a ring the default is RAM_ANNULI annuli, the ram's modes in as many kept on the
    unit; without one the ram face in annuli is the engine's, an input error here."""
    unit = stack_unit(table1, ring)
    assert unit.ram_annuli == RAM_ANNULI and unit.ram_modes.n_annuli == RAM_ANNULI
    assert stack_unit(table1, ring, ram_annuli=1).ram_face is None
    with pytest.raises(InputError, match="ram_annuli"):
        stack_unit(with_ram_annuli(table1, 6), None, ram_annuli=6)


@pytest.mark.slow
@pytest.mark.parametrize("mu", [0.0, 0.2])
def test_one_ram_port_keeps_the_fea_peaks_within_the_issues_bars(table1, ring, mu):
    """As test_rom_stack_peaks_within_the_issues_bars with the one ram port (the data file's
    "1 ram port" variant, the same run), against the stored FEA stack's peaks
    (docs/data/anvil_ring.json): pile 3 %, ram 5 %."""
    values = doc_data("anvil_ring")["values"]
    run = values["runs"][f"ring, mu {mu:g}"]
    stored = run["rom_variants"]["1 ram port"]
    penalty = values["mesh_size [m]"] / values.get("contact_stiffness_factor [-]", 1.0)
    blow = run_stack_blow(table1, stack_unit(table1, ring, seat_friction=mu,
                                             penalty_size=penalty, ram_annuli=1))
    t = np.arange(2501) * 1e-5
    shifted = blow.time - 0.5 * (blow.time[1] - blow.time[0])
    for name, series, bar in (("pile", blow.pile_force, 0.03), ("ram", blow.ram_force, 0.05)):
        peak = lowpass(t, np.interp(t, shifted, series), 5000.0).max()
        assert peak == pytest.approx(stored[f"{name}_peak_rom [N]"], **SAME_RUN)
        assert abs(peak / run["rom"][f"{name}_peak_fea [N]"] - 1.0) < bar, name
