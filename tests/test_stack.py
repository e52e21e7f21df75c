"""The driving stack as one unit (anvil + anvil ring, two modal bodies, seat friction) on the
paper's Table 1: without a ring it is the anvil unit's blow to the bit; the ring stack rests in
exact equilibrium, balances its energy with friction on, and meets the issue's bars against the
reference FEA stack (peaks, RMS, band levels); its tube head's lag 0 is the closed form of
springs in series."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import fea_config, without_soil
from anvilwave.analyses.stack_blow import RAM_ANNULI, run_stack_blow, stack_unit, with_ram_annuli
from anvilwave.anvil_rom import stack
from anvilwave.anvil_rom.fem.geometry import load_anvil
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.fea.cache import cached_impact_fea
from anvilwave.inputs import InputError

from .doc_tables import SAME_RUN, benchmark, doc_data

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


def study_against_fea(run: str, variants: dict) -> tuple[dict, dict]:
    """benchmarks/study_anvil_ring.py's ROM stack of each of ``variants`` (label -> keywords of
    table1_ring.toml's options; {} the stack itself) against its FEA stack of the reference run
    ``run`` on the data file's mesh (through the FEA cache: a first run computes it, 5-15 s at
    0.1 m), as the study computes it; and the data file's figures of that run."""
    script = benchmark("study_anvil_ring")
    values = doc_data("anvil_ring")["values"]
    h = values["mesh_size [m]"]
    factor = values.get("contact_stiffness_factor [-]", 1.0)
    ring = load_anvil(EXAMPLES / "anvils" / "xl8_ring.toml")
    mu = float(run.rsplit(" ", 1)[1])
    sleeve = {}
    if run.startswith("sleeve"):  # the study's sleeve, with the ROM's contacts
        sleeve = {"sleeve_radius": 4.15 + script.DOCS_SLEEVE[0], "sleeve_friction": mu}
    config = dataclasses.replace(
        fea_config(load_system(EXAMPLES / "table1.toml"), mesh_size=h,
                   truncate_length=values["truncate_length [m]"]),
        contact_stiffness_factor=factor, ring=ring, seat_friction=mu,
        pile_friction=mu if run.startswith("ring") else 0.0, **sleeve)
    fea = cached_impact_fea(config)
    system = without_soil(load_system(script.ROM_SYSTEM))
    rows = {label: script.rom_against_fea(system, ring, mu, fea, h / factor,
                                          **script.sleeve_options(config), **kw)
            for label, kw in variants.items()}
    return rows, values["runs"][run]


@pytest.mark.slow
@pytest.mark.parametrize("run", ["ring, mu 0", "seat only, mu 0.2"])
def test_rom_stack_meets_the_issues_bars_against_the_fea_stack(run):
    """The issue's bars, ROM stack against FEA stack on Table 1 with the ring, every series
    low-passed at 5 kHz, recomputed here (the FEA through its cache, the ROM of
    table1_ring.toml: seat in 32 rings, ram face in six annuli, three pile rings on the tube
    head): peak pile force within 3 %, ram force within 5 %, RMS of the difference within 10 %
    of the signal's, band levels within 1.5 dB from 50 Hz to 4 kHz, at friction 0 and at
    seat friction 0.2 (the FEA with the ROM's contacts: the ring-pile contact frictionless in
    both), and the ROM unit's energy balance within 0.5 % of the blow. The figures are the docs'
    data file's (the same run, SAME_RUN). At friction 0 also the FMU's stack against the same
    FEA run."""
    script = benchmark("study_anvil_ring")
    fmu = script.FMU_VARIANT
    rows, stored = study_against_fea(run, {"stack": {}} | (
        {fmu: script.ROM_VARIANTS[fmu]} if run == "ring, mu 0" else {}))
    row = rows["stack"]
    assert abs(row["pile_peak_error [-]"]) < 0.03
    assert abs(row["ram_peak_error [-]"]) < 0.05
    assert row["pile_rms_error [-]"] < 0.10
    assert row["ram_rms_error [-]"] < 0.10
    assert row["band_error_max [dB]"] < 1.5
    assert row["rom_energy_balance [-]"] < 0.005
    if run.startswith("seat only"):
        assert row["rom_friction_energy [-]"] > 1e-3  # the seat slides
    for key in ("pile_peak_rom [N]", "ram_peak_rom [N]", "pile_peak_fea [N]",
                "pile_rms_error [-]", "band_error_max [dB]"):
        assert row[key] == pytest.approx(stored["rom"][key], **SAME_RUN), key
    if fmu in rows:
        # the stack AnvilStack.fmu runs (one ram port, the 1D head, the default seat rings):
        # the data file's variant, and at friction 0 the FEA stack's peaks within the bars (its
        # RMS, bands and seat-friction case: docs/validation.md says which bars it misses)
        f = rows[fmu]
        assert abs(f["pile_peak_error [-]"]) < 0.03
        assert abs(f["ram_peak_error [-]"]) < 0.05
        for key in ("pile_peak_rom [N]", "ram_peak_rom [N]", "band_error_max [dB]"):
            assert f[key] == pytest.approx(stored["rom_variants"][fmu][key], **SAME_RUN), key


@pytest.mark.slow
@pytest.mark.parametrize("run", ["sleeve, mu 0", "sleeve, mu 0.2"])
def test_rom_stack_in_the_sleeve_against_the_fea_stack(run):
    """The ring stack in a rigid sleeve 1 mm off the rims, ROM against FEA on the data file's
    mesh (0.1 m; the FEA through its cache), with the ROM's contacts (friction on the seat and
    against the sleeve, the ring-pile contact frictionless): the peaks within the issue's 3 %
    and 5 %, both RMS within 10 %, the balance within 0.5 % with the sleeve's friction on (at
    mu 0.2 it takes a fifth of the blow); the bands are over the 1.5 dB bar on this mesh
    (measured 2.0 and 2.2 dB, bounded here at 2.5 dB), where the FEA itself is 3.6 dB from its
    0.05 m run at mu 0 (docs/validation.md: the ROM against the finer references). The
    figures are the data file's."""
    rows, stored = study_against_fea(run, {"stack": {}})
    row = rows["stack"]
    assert abs(row["pile_peak_error [-]"]) < 0.03
    assert abs(row["ram_peak_error [-]"]) < 0.05
    assert row["pile_rms_error [-]"] < 0.10
    assert row["ram_rms_error [-]"] < 0.10
    assert row["band_error_max [dB]"] < 2.5
    assert row["rom_energy_balance [-]"] < 0.005
    if run.endswith("0.2"):
        assert row["rom_friction_energy [-]"] > 0.15
    for key in ("pile_peak_rom [N]", "ram_peak_rom [N]", "pile_peak_fea [N]",
                "pile_rms_error [-]", "band_error_max [dB]"):
        assert row[key] == pytest.approx(stored["rom"][key], **SAME_RUN), key


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


def test_tube_heads_lag_zero_is_a_spring_in_series(table1, ring):
    """A tube head of one lag, D[0] = diag(d), is a compliance d in series with each pile
    ring's contact spring k (closed form: 1 / (1 / k + d)). Without gravity (the tube's
    correction is measured from the rest forces, here zero) the stack with that head and the
    stack on the 1D head with those series springs give the same blow to round-off (1e-9 of
    the peak; the sums differ in order only); with d = 0 the blow is the 1D head's."""
    K = 3
    springs = np.array([2.0e11, 3.0e11, 4.0e11])
    d = np.array([1.0e-12, 2.0e-12, 5.0e-12])
    series = 1.0 / (1.0 / springs + d)
    weightless = dataclasses.replace(table1, gravity=0.0)
    forces = []
    for head in ((np.diag(d)[None], springs), (np.zeros((1, K, K)), series),
                 (np.zeros((1, K, K)), springs)):
        unit = stack_unit(weightless, ring, seat_friction=0.2, ram_annuli=1)
        unit.set_step(2e-5)
        unit.set_head(head)
        forces.append(run_stack_blow(weightless, unit, duration=0.006).pile_force)
    assert np.abs(forces[0] - forces[1]).max() < 1e-9 * forces[1].max()
    assert np.abs(forces[0] - forces[2]).max() > 1e-3 * forces[2].max()  # d matters
    unit = stack_unit(table1, ring, ram_annuli=1)
    with pytest.raises(InputError, match="pile_head"):
        unit.set_head((np.zeros((1, 2, 2)), springs))
