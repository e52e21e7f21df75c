"""The anvil's pile port split into rings (anvilwave/anvil_rom/rings.py, ``[anvil]
pile_port_rings``):
the contact solver against enumeration, the rest on the pile, the one-port limit in the
engine, the energy balance, the modal-data keys and the refusals."""

from __future__ import annotations

import dataclasses
import itertools
from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import without_soil
from anvilwave.analyses.impact import total_energy
from anvilwave.anvil_rom.fem.modalfile import load_modal_data, save_modal_data
from anvilwave.anvil_rom.rings import contact_lcp, ring_static_rest
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.config.system import load_system
from anvilwave.engine.direct import anvil_modal_data, build_engine, contact_stiffnesses
from anvilwave.inputs import InputError

EXAMPLES = Path(__file__).resolve().parents[1] / "anvilwave" / "examples"


def system_text(extra: str, model: str = "rom") -> str:
    """table1.toml with its anvil file by absolute path, another anvil model and extra
    [anvil] keys."""
    text = (EXAMPLES / "table1.toml").read_text()
    text = text.replace('file = "anvils/xl8.toml"',
                        f'file = "{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"\n{extra}')
    return text.replace('model = "rom"', f'model = "{model}"', 1)


@pytest.fixture(scope="module")
def table1():
    return without_soil(load_system(EXAMPLES / "table1.toml"))


def with_rings(cfg, rings: int):
    spec = cfg.anvil.spec
    return dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=rings))))


def enumerate_lcp(A, g):
    """The complementary solution by trying every active set (A positive definite: unique)."""
    m = g.size
    for active in itertools.product((False, True), repeat=m):
        a = np.array(active)
        F = np.zeros(m)
        if a.any():
            F[a] = np.linalg.solve(A[np.ix_(a, a)], g[a])
        w = A @ F - g
        if np.all(F[a] >= 0.0) and np.all(w[~a] >= -1e-12 * np.abs(g).max()):
            return F
    raise AssertionError("no complementary active set")


def test_contact_lcp_equals_enumeration():
    """Murty's pivoting from random starting sets on random positive definite problems of 1-7
    contacts (the ram and up to six rings), gaps of both signs: the enumeration's forces to
    1e-9 of the largest (6x6 eliminations of condition ~1e3)."""
    rng = np.random.default_rng(11)
    for _ in range(300):
        m = int(rng.integers(1, 8))
        B = rng.normal(size=(m, m))
        A = np.diag(rng.uniform(0.5, 2.0, m)) + 0.5 * B @ B.T / m
        g = rng.normal(size=m)
        F = np.zeros(m)
        active = rng.integers(0, 2, m).astype(float)
        contact_lcp(A, g, F, active, np.zeros((m, m + 1)))
        expected = enumerate_lcp(A, g)
        np.testing.assert_allclose(F, expected, atol=1e-9 * max(np.abs(expected).max(), 1.0))
        assert np.array_equal(active != 0.0, F > 0.0) or np.allclose(F[active != 0.0], 0.0)


def test_rest_on_identical_rings_splits_by_stiffness():
    """Rings with the same participations close by the same amount: each carries its share of
    the contact stiffness of the weight, and the rigid displacement is W / k plus the static
    flexible deflection (closed form)."""
    omega = np.array([0.0, 2e3, 5e3])
    p = np.array([0.01, 0.02, -0.03])
    rings = np.vstack([p, p, p])
    k = 1e12 * np.array([0.2, 0.3, 0.5])
    r = 1e-13
    forces, u0 = ring_static_rest(omega, rings, k, np.full((3, 3), r), 1e6)
    np.testing.assert_allclose(forces, 1e6 * k / k.sum(), rtol=1e-12)
    flexible = (p[1:] ** 2 / omega[1:] ** 2).sum() + r
    assert u0 == pytest.approx(1e6 / k.sum() + flexible * 1e6, rel=1e-12)


def test_xl8_rests_on_its_inner_rings(table1):
    """Table 1's xl8 on three rings under its weight dishes: its outer ring lifts (all rings
    in contact would need -0.91 MN there). The solution is complementary: the forces add up to
    the weight, the rings in contact meet the head (F/k + G F = u0), the open one clears it."""
    data = anvil_modal_data(with_rings(table1, 3))
    anvil = ModalAnvil.from_modal_data(data, static_correction=True)
    _, k_pile = contact_stiffnesses(table1)
    k = k_pile * anvil.ring_areas / anvil.ring_areas.sum()
    weight = anvil.total_mass * table1.gravity
    forces, u0 = ring_static_rest(anvil.omega, anvil.participation_rings, k,
                                  anvil.residual_rings[1:, 1:], weight)
    flexible = anvil.omega > 0.0
    Pk = anvil.participation_rings[:, flexible]
    G = (Pk / anvil.omega[flexible] ** 2) @ Pk.T + anvil.residual_rings[1:, 1:]
    assert forces.sum() == pytest.approx(weight, rel=1e-12)
    assert forces[0] > 0.0 and forces[1] > 0.0 and forces[2] == 0.0
    closing = forces / k + G @ forces - u0
    np.testing.assert_allclose(closing[:2], 0.0, atol=1e-9 * u0)
    assert u0 - G[2] @ forces < 0.0


def test_two_identical_half_rings_are_the_one_port(table1):
    """The one port's modal data given as two rings with its own participations and
    flexibility and half its area each: the ring unit (its complementarity solver, rest, step
    and energies) must run the one-port Table 1 blow again. Both ring forces are then half the
    port's force; time series and energies to 1e-9 of their largest values (round-off of a
    different elimination, carried over 1250 contact steps)."""
    data = anvil_modal_data(table1)
    G = np.asarray(data.elastic_flexibility)
    area = float(data.interface_areas[1])
    rings = dataclasses.replace(
        data, participation_rings=np.vstack([data.participation_pile] * 2),
        ring_flexibility=np.array([[G[0, 0], G[0, 1], G[0, 1]], [G[0, 1], G[1, 1], G[1, 1]],
                                   [G[0, 1], G[1, 1], G[1, 1]]]),
        ring_areas=np.array([0.5 * area, 0.5 * area]))
    one = build_engine(table1, modal=data).blow(energy_interval=1e-4)
    two_engine = build_engine(table1, modal=rings)
    assert two_engine.anvil.unit.rings is not None
    two = two_engine.blow(energy_interval=1e-4)
    for name, series in one.columns.items():
        scale = max(np.abs(series).max(), 1e-30)
        np.testing.assert_allclose(two.columns[name], series, atol=1e-9 * scale, err_msg=name)
    for name, series in one.energies.items():
        scale = max(np.abs(series).max(), 1e-30)
        np.testing.assert_allclose(two.energies[name], series, atol=1e-9 * scale, err_msg=name)


def test_table1_rings_energy_balance(table1):
    """Table 1 (modal ram unit, contact dashpot) with three rings: the total energy (modal
    unit, rings' contacts and residual flexibility, pile, dashpot work) stays within 0.5 % of
    the impact energy over the blow (measured: -0.17 % to +0.25 %, -0.05 % at the end; one
    port: the same to 1e-5), the bound of the one-port unit's balance test."""
    blow = build_engine(with_rings(table1, 3)).blow(energy_interval=2e-5)
    total = total_energy(blow.energies)
    drift = (total - total[0]) / blow.input_energy
    assert np.abs(drift).max() <= 5e-3
    assert blow.max_pile_head_force > 1e8


def test_ring_keys_round_trip_and_refusals(table1, tmp_path):
    data = anvil_modal_data(with_rings(table1, 3))
    assert data.participation_rings.shape == (3, data.n_modes)
    path = save_modal_data(data, tmp_path / "rings.npz")
    back = load_modal_data(path)
    for key in ("participation_rings", "ring_flexibility", "ring_areas"):
        np.testing.assert_array_equal(getattr(back, key), getattr(data, key))
    with pytest.raises(InputError, match="ring_areas.*sum to the pile ring"):
        dataclasses.replace(data, ring_areas=data.ring_areas * 1.01)
    with pytest.raises(InputError, match="ring_flexibility: must be given with"):
        dataclasses.replace(data, ring_flexibility=None)
    with pytest.raises(InputError, match="participation_rings.*add up to participation_pile"):
        dataclasses.replace(data, participation_rings=data.participation_rings[::-1] * 1.1)
    one = load_modal_data(save_modal_data(anvil_modal_data(table1), tmp_path / "one.npz"))
    assert one.participation_rings is None  # a one-port file holds no ring keys


def test_pile_port_rings_refusals(table1, tmp_path):
    lumped = tmp_path / "lumped.toml"
    lumped.write_text(system_text("pile_port_rings = 3", model="lumped"))
    with pytest.raises(InputError, match="pile_port_rings.*needs model = 'rom'"):
        load_system(lumped)
    zero = tmp_path / "zero.toml"
    zero.write_text(system_text("pile_port_rings = 0"))
    with pytest.raises(InputError, match="pile_port_rings"):
        load_system(zero)
    fine = tmp_path / "seven.toml"
    fine.write_text(system_text("pile_port_rings = 7"))
    with pytest.raises(InputError, match="pile_port_rings: 7 rings across the pile wall"):
        build_engine(load_system(fine))  # the xl8 mesh has three edges across the wall


@pytest.mark.parametrize("native", [None, False])
def test_fmi_engine_with_rings_equals_direct(table1, tmp_path, native):
    """The FMI engine on a system with three rings (F_pile the rings' sum) gives the direct
    engine's blow with the native C anvil (its shipped binary) and with the pythonfmu
    anvil: forces to 1e-9 of their peaks (measured ~1e-11: round-off of the separate calls)."""
    from anvilwave.engine.fmi import run_fmi

    ringed = with_rings(table1, 3)
    direct = build_engine(ringed).blow()
    fmi = run_fmi(ringed, tmp_path / "fmus", native_anvil=native)[0]
    for name in ("ram_anvil_force [N]", "anvil_pile_force [N]", "pile_head_velocity [m/s]"):
        a = np.asarray(direct.columns[name])
        b = np.interp(direct.columns["time [s]"], fmi.columns["time [s]"], fmi.columns[name])
        np.testing.assert_allclose(b, a, atol=1e-9 * np.abs(a).max(), err_msg=name)


def test_ring_unit_energy_method_refuses(table1):
    """AnvilUnit.energy books one port's contacts: a ring unit refuses it (the engine books
    the rings' energy)."""
    unit = build_engine(with_rings(table1, 3)).anvil.unit
    with pytest.raises(ValueError, match="energy of a pile port in rings"):
        unit.energy(0.0, 0.0, 0.0, 0.0)
