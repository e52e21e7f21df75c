"""The modal ram: the chain realisation of a one-port modal ROM, the ram built with it, and the
modal ram unit (exact per mode, no chain)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.linalg import eigh

from anvilwave.analyses.compare import (
    ModelRun,
    comparison_bandwidth,
    lowpass,
    metrics,
    without_soil,
)
from anvilwave.analyses.impact import energy_balance
from anvilwave.anvil_rom.chain import chain_from_modes, chain_modes
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.modal_ram import (
    ModalRamUnit,
    RamToeModes,
    modal_ram,
    modal_ram_chain,
    modal_ram_modes,
    ram_outline,
    toe_modes_from_table,
    toe_modes_table,
)
from anvilwave.hammer.ram import RamRod
from anvilwave.inputs import InputError

from .conftest import EXAMPLES

C0 = math.sqrt(210e9 / 7850.0)


def dense_chain_modes(mass, stiffness):
    """Frequencies [rad/s] and first-mass participations of a chain, by a dense generalised
    eigensolver (independent of the tridiagonal route of chain_modes)."""
    n = len(mass)
    K = np.zeros((n, n))
    for i, k in enumerate(stiffness):
        K[i:i + 2, i:i + 2] += k * np.array([[1.0, -1.0], [-1.0, 1.0]])
    lam, vec = eigh(K, np.diag(mass))
    return np.sqrt(np.clip(lam, 0.0, None)), vec[0]


def test_chain_recovers_a_known_chain():
    """The Jacobi inverse eigenvalue problem has one solution: the modes of a random chain
    (dense eigensolver) give back its masses and springs. Tolerance 1e-8: the forward solve is
    accurate to ~1e-13 relative, and the inverse problem of 12 well-separated modes amplifies
    that by far less than 1e5."""
    rng = np.random.default_rng(7)
    mass = rng.uniform(1.0, 3.0, 12)
    stiffness = rng.uniform(1e3, 4e3, 11)
    omega, p = dense_chain_modes(mass, stiffness)
    omega[0] = 0.0
    m, k = chain_from_modes(omega, p)
    np.testing.assert_allclose(m, mass, rtol=1e-8)
    np.testing.assert_allclose(k, stiffness, rtol=1e-8)


def test_chain_of_a_uniform_rod_keeps_its_modes():
    """A free-free uniform rod (L 10 m, 1000 kg): modes n pi c / L, end participations
    sqrt(2 / M) (1 / sqrt(M) rigid). The realised chain carries exactly these, checked with the
    dense solver: frequencies and participations within 1e-7 (double-precision eigensolution
    of masses spanning many decades), total mass to 1e-12."""
    L, M, n = 10.0, 1000.0, 30
    omega = np.arange(n) * np.pi * C0 / L
    p = np.full(n, math.sqrt(2.0 / M))
    p[0] = 1.0 / math.sqrt(M)
    m, k = chain_from_modes(omega, p)
    assert m.sum() == pytest.approx(M, rel=1e-12)
    w, q = chain_modes(m, k)
    np.testing.assert_allclose(w[1:], omega[1:], rtol=1e-9)
    np.testing.assert_allclose(np.abs(q), p, rtol=1e-9)


def test_chain_refuses_bad_modal_data():
    with pytest.raises(InputError, match="rigid-body mode"):
        chain_from_modes(np.array([1.0, 2.0]), np.array([1.0, 1.0]))
    with pytest.raises(InputError, match="must match"):
        chain_from_modes(np.array([0.0, 2.0]), np.array([1.0]))


def test_ram_outline_of_a_stepped_hollow_ram():
    sections = np.array([[1.0, 1.0, 0.0], [2.0, 0.8, 0.2]])
    outline = ram_outline(sections)
    expected = [(0.0, 0.0), (0.5, 0.0), (0.5, 1.0), (0.4, 1.0), (0.4, 3.0), (0.1, 3.0),
                (0.1, 1.0), (0.0, 1.0)]
    np.testing.assert_allclose(outline, expected)


@pytest.fixture(scope="module")
def slender():
    """A slender steel ram, D 0.2 m x L 4 m, modal up to 3 kHz (about five axial modes)."""
    from anvilwave.config.cache import cached_chain, cached_modal_data

    rod = RamRod.uniform(4.0, 0.2)  # modes and chain from the session's modal-data cache
    return rod, modal_ram(rod, 3000.0, realisation="chain", modes=cached_modal_data,
                          realise=cached_chain)


def test_slender_modal_ram_is_the_1d_rod(slender):
    """For L / D = 20 the modal ram must be the 1D rod: mass rho V to round-off; the first
    three axial frequencies n c / (2 L) within 2e-4 (the Rayleigh-Love lateral-inertia
    lowering, nu^2 (n pi r_g / L)^2 / 2 with r_g^2 = r^2 / 2, is 1.3e-3 at n = 3 and the P2 mesh
    error is below 1e-4; so the bound is 1.5e-3 + n-scaled); end participations of the axial
    modes sqrt(2 / M) within 1 %."""
    rod, ram = slender
    assert ram.total_mass == pytest.approx(rod.total_mass, rel=1e-10)
    w, p = dense_chain_modes(ram.mass[::-1], ram.stiffness[::-1])
    # flexible rod modes (the rigid mode of the dense chain solve is 0 only to round-off)
    axial = (np.abs(p) ** 2 > 0.5 * (2.0 / ram.total_mass)) & (w > 2 * np.pi * 10.0)
    f = w[axial][:3] / (2 * np.pi)
    for n, fn in enumerate(f, start=1):
        rod_f = n * C0 / (2 * 4.0)
        love = 0.3**2 * (n * math.pi * 0.1 / math.sqrt(2) / 4.0) ** 2 / 2
        assert fn / rod_f - 1 == pytest.approx(-love, abs=2e-4)
    np.testing.assert_allclose(np.abs(p[axial][:3]), math.sqrt(2.0 / ram.total_mass), rtol=0.01)


def test_modal_ram_static_toe_compliance_is_exact(slender):
    """Inertia relief of a free rod loaded at its toe: the mean toe displacement relative to
    the rigid motion is L / (3 E A) (1D); the modal chain's flexible modes plus the residual
    (1 / toe_stiffness) must give it within 1 % (the 3D end effect under a uniform pressure on
    a 0.2 m face adds ~0.1 %)."""
    _, ram = slender
    w, p = dense_chain_modes(ram.mass[::-1], ram.stiffness[::-1])
    flexible = np.sum(p[1:] ** 2 / w[1:] ** 2)
    total = flexible + 1.0 / ram.toe_stiffness
    area = math.pi * 0.1**2
    assert total == pytest.approx(4.0 / (3 * 210e9 * area), rel=0.01)
    assert ram.fmax == 3000.0
    # the modal unit carries the same toe modes: the same compliance without a chain
    from anvilwave.config.cache import cached_modal_data

    unit = modal_ram(RamRod.uniform(4.0, 0.2), 3000.0, modes=cached_modal_data)
    assert unit.is_modal_unit and unit.stiffness.size == 0
    modes = unit.modes
    flexible_unit = np.sum(modes.participation[1:] ** 2 / modes.omega[1:] ** 2)
    assert flexible_unit + 1.0 / unit.toe_stiffness == pytest.approx(total, rel=1e-9)


def test_modal_ram_refuses_a_ram_without_shape():
    with pytest.raises(InputError, match="needs the ram's shape"):
        modal_ram(RamRod.rigid(1000.0, 0.5), 3000.0)


def test_system_file_ram_model(tmp_path):
    table1 = (EXAMPLES / "table1.toml").read_text().replace(
        '"anvils/xl8.toml"', f'"{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"')
    cfg = load_system(EXAMPLES / "table1.toml")
    rod = load_hammer("illustrative_5500kj").ram
    assert cfg.hammer.ram.fmax == 5000.0
    assert cfg.hammer.ram.total_mass == pytest.approx(rod.total_mass, rel=1e-12)
    assert math.isfinite(cfg.hammer.ram.toe_stiffness)
    bad = tmp_path / "bad.toml"
    bad.write_text(table1.replace('ram_model = "modal"', 'ram_model = "modal"\n'
                                                         'ram_mesh_size = 0.5'))
    with pytest.raises(InputError, match="hammer.ram_mesh_size"):
        load_system(bad)
    bad.write_text(table1.replace('ram_model = "modal"', 'ram_model = "3d"'))
    with pytest.raises(InputError, match="ram_model"):
        load_system(bad)
    bad.write_text(table1.replace('ram_model = "modal"', 'ram_mesh_size = 0.1'))
    with pytest.raises(InputError, match="ram_mesh_size.*modal"):
        load_system(bad)


@pytest.fixture(scope="module")
def table1_runs(table1_unit_runs):
    """Table 1 without soil, ROM anvil, with the modal and with the rod ram (the modal ram's
    blow is the system's own, run once by table1_unit_runs)."""
    _, blows, cfg, _ = table1_unit_runs
    rod = dataclasses.replace(cfg, hammer=load_hammer("illustrative_5500kj"))
    return {"modal": blows["unit"], "rod": build_engine(rod).run()[0]}, cfg


def test_modal_ram_energy_balance(table1_runs):
    """The modal ram unit keeps the engine's energy bookkeeping, the contact dashpot's work
    booked: residual within 0.5 % of the impact energy (the bound of the engine tests;
    measured -7.5e-4 with 1.6 % of the energy taken by the dashpot)."""
    runs, _ = table1_runs
    blow = runs["modal"]
    assert abs(energy_balance(blow)["residual_relative [-]"]) < 5e-3


def test_modal_ram_removes_the_rod_rams_peak_excess(table1_runs):
    """Against each other (no FEA here; test_compare.py has it): the rod ram's pile peak is
    0.5-3 % above the modal ram's, the lateral-inertia effect measured against the FEA in the
    5 kHz band (+2.0 % rod, +1.0 % modal, both with table1.toml's ram-impedance contact
    dashpot; without it +6.3 % and +2.3 %, the rest being the contact's ringing above fmax).
    The first ram-anvil peak (before 2 ms) agrees within 5 %: both rams are the same rod at low
    frequency."""
    runs, cfg = table1_runs
    band = comparison_bandwidth(cfg)
    ref = ModelRun("modal", runs["modal"].columns, 0.0, {})
    m = metrics(ModelRun("rod", runs["rod"].columns, 0.0, {}), ref, 0.0, band)
    assert 0.005 < m["peak_anvil_pile_force_error [-]"] < 0.03
    first = []
    for r in runs.values():
        t = r.columns["time [s]"]
        force = lowpass(t, r.columns["ram_anvil_force [N]"], band)
        first.append(force[t < 2e-3].max())
    assert 0.0 < first[1] / first[0] - 1.0 < 0.05


def rod_toe_modes(length: float, area: float, n_modes: int) -> RamToeModes:
    """Closed-form toe modes of a free-free uniform steel rod (1D): omega_n = n pi c / L,
    p_n = sqrt(2 / M) (-1)^n (p_0 = 1 / sqrt(M)); the residual toe flexibility of the modes
    above n_modes is L / (3 E A) - sum_kept p_n^2 / omega_n^2 (inertia relief)."""
    mass = 7850.0 * area * length
    n = np.arange(n_modes + 1)
    omega = n * math.pi * C0 / length
    p = np.sqrt(2.0 / mass) * (-1.0) ** n
    p[0] = 1.0 / math.sqrt(mass)
    gravity = np.zeros(n.size)
    gravity[0] = math.sqrt(mass)
    residual = length / (3 * 210e9 * area) - np.sum(p[1:] ** 2 / omega[1:] ** 2)
    return RamToeModes(omega, p, gravity, mass, 1.0 / residual, C0 * n_modes / (2 * length))


def test_toe_mass_is_the_first_response_to_a_force_step():
    """RamRod.toe_mass: for the closed-form modes of a uniform rod with N flexible modes,
    1 / sum p^2 = M / (2 N + 1); the modal unit, at rest, given a force step F, gets the mean
    toe velocity -F h / toe_mass over its first step (its per-mode c = 2 (1 - cos w h) / w^2
    is h^2 (1 - (w h)^2 / 12): 1e-4 at the highest mode's w h = 0.033, so 2e-4); a Smith rod's
    toe mass is its toe node's."""
    length, area, n_modes, h, force = 2.0, 0.1, 40, 1e-7, 1.0e6
    modes = rod_toe_modes(length, area, n_modes)
    ram = RamRod(np.array([modes.total_mass]), np.zeros(0), modes=modes)
    assert ram.toe_mass == pytest.approx(modes.total_mass / (2 * n_modes + 1), rel=1e-12)
    unit = ModalRamUnit(modes, gravity=0.0)
    unit.start(0.0, 0.0, h)
    _, velocity = unit.step(force)
    assert velocity == pytest.approx(-force * h / ram.toe_mass, rel=2e-4)
    rod = RamRod.from_segments([1000.0, 2000.0, 300.0], [1e10, 2e10])
    assert rod.toe_mass == 300.0


def test_modal_ram_unit_rod_strikes_a_stiff_wall():
    """A uniform rod (L 2 m, A 0.1 m^2) at v0 = 5 m/s against a stiff wall spring: the force is
    the impedance plateau E A v0 / c for 2 L / c, then the rod leaves (Saint-Venant). With 400
    modes (133 kHz) and the residual toe spring in series with the wall, exact per mode at
    h = 0.1 us: the plateau's mean within 0.5 % (the truncation rings about it), the contact
    time within 2 %, and the energy (modes + contact spring, gravity off) kept within 0.1 %
    through the impact (the shadow energies of the scheme are conserved for a held force up to
    the contact's O(h^2) exchange)."""
    length, area, velocity = 2.0, 0.1, 5.0
    modes = rod_toe_modes(length, area, 400)
    wall = 50 * 210e9 * area / length
    k = 1.0 / (1.0 / wall + 1.0 / modes.toe_stiffness)
    unit = ModalRamUnit(modes, gravity=0.0)
    h = 1e-7
    unit.start(0.0, velocity, h)
    u, _ = 0.0, velocity
    steps = int(1.2 * 2 * length / C0 / h)
    force = np.zeros(steps)
    energy = np.zeros(steps)
    for i in range(steps):
        force[i] = k * u if u > 0.0 else 0.0
        kinetic, strain, _ = unit.energies()
        energy[i] = kinetic + strain + 0.5 * force[i] ** 2 / k
        u, _ = unit.step(force[i])
    plateau = 210e9 * area * velocity / C0
    t = np.arange(steps) * h
    duration = 2 * length / C0
    inside = (t > 0.1 * duration) & (t < 0.9 * duration)
    assert force[inside].mean() == pytest.approx(plateau, rel=5e-3)
    contact = t[force > 0.5 * plateau]
    assert contact[-1] - contact[0] == pytest.approx(duration, rel=0.02)
    initial = 0.5 * modes.total_mass * velocity**2
    assert np.max(np.abs(energy / initial - 1.0)) < 1e-3


@pytest.fixture(scope="module")
def table1_unit_runs():
    """Table 1 without soil at table1.toml's step (20 us): the ram as the modal unit (the
    system's) and as its chain, the same 125 modes below 5 kHz."""
    cfg = without_soil(load_system(EXAMPLES / "table1.toml"))
    modes = cfg.hammer.ram.modes
    chain = dataclasses.replace(cfg, hammer=dataclasses.replace(
        cfg.hammer, ram=modal_ram_chain(cfg.hammer.ram, modes)))
    engines = {"chain": build_engine(chain), "unit": build_engine(cfg)}
    assert engines["chain"].ram_modes is None and engines["unit"].ram_modes is modes
    blows = {name: engine.run()[0] for name, engine in engines.items()}
    return engines, blows, cfg, modes


def test_modal_ram_unit_in_the_engine(table1_unit_runs):
    """The unit and the chain carry the same modes: in the 5 kHz comparison band their pile
    and ram peaks agree within 0.5 % and the RMS differences are below 2 % (measured: ram peak
    +0.07 %, pile +0.02 %, RMS 0.9 % ram and 0.4 % pile, with table1.toml's contact dashpot;
    the chain's leapfrog and the exact modes integrate the content near fmax differently). The
    unit's energy residual is within 0.5 % of the impact energy (measured -7.5e-4), its coupled
    limit within 10 % of the chain's, and the ram no longer sub-steps."""
    engines, blows, cfg, modes = table1_unit_runs
    band = comparison_bandwidth(cfg)
    chain = ModelRun("chain", blows["chain"].columns, 0.0, {})
    m = metrics(ModelRun("unit", blows["unit"].columns, 0.0, {}), chain, 0.0, band)
    assert abs(m["peak_anvil_pile_force_error [-]"]) < 0.005
    assert abs(m["peak_ram_anvil_force_error [-]"]) < 0.005
    assert m["anvil_pile_force_normalised_rms_error [-]"] < 0.02
    assert m["ram_anvil_force_normalised_rms_error [-]"] < 0.02
    assert abs(energy_balance(blows["unit"])["residual_relative [-]"]) < 5e-3
    unit, chain_engine = engines["unit"], engines["chain"]
    assert unit.limits["anvil coupling"] == pytest.approx(
        chain_engine.limits["anvil coupling"], rel=0.1)
    assert unit.limits["ram"] == math.inf
    assert unit.config.hammer.ram.toe_stiffness == modes.toe_stiffness
    assert blows["unit"].input_energy == pytest.approx(blows["chain"].input_energy, rel=1e-12)


def test_modal_ram_unit_needs_no_chain_and_falls_freely():
    """The modal unit needs no chain, which beyond about 500 modes would need masses spanning
    more than 1e290 (chain_from_modes refuses it after about a minute of multiple precision;
    benchmarks/study_fmax.py): the Table 1 ram's 502 modes at 10 kHz run as the unit in a whole
    blow in tests/test_ram_annuli.py::test_no_worse_at_fmax_10_khz. Here its 5 kHz modes (the
    session's modal-data cache) in free flight under gravity: the unit's toe follows the falling
    ram to round-off (the rigid mode's recurrence is exact for a constant load): started with
    the half-step velocity v0 over [-h, 0], u(t) = v0 t + g t (t + h) / 2 and the half-step
    velocity over [t - h, t] is v0 + g t."""
    from anvilwave.config.cache import cached_modal_data

    ram = load_hammer("illustrative_5500kj").ram
    modes = modal_ram_modes(ram, 5000.0, modes=cached_modal_data)
    assert modes.n_modes > 100
    unit = ModalRamUnit(modes)
    h, v0, g = 1e-5, 6.0, 9.81
    unit.start(0.0, v0, h)
    for _ in range(100):
        u, v = unit.step(0.0)
    t = 100 * h
    assert u == pytest.approx(v0 * t + 0.5 * g * t * (t + h), rel=1e-9)
    assert v == pytest.approx(v0 + g * t, rel=1e-9)
    u, v = unit.step(1e6)
    assert math.isfinite(u) and v == pytest.approx(6.0, abs=0.02)


def test_toe_modes_table_reads_back_exactly_and_refuses_bad_tables(tmp_path):
    """The [ram] kind = "modal" table that Ram.fmu embeds: written and read back, every array
    and number is the same float (TOML writes shortest round-trip reprs); each broken key is
    one InputError naming it."""
    from anvilwave.inputs import Table, toml_dumps

    modes = rod_toe_modes(2.0, 0.1, 12)
    path = tmp_path / "ram.toml"
    path.write_text(toml_dumps({"ram": toe_modes_table(modes)}), encoding="utf-8")
    back = toe_modes_from_table(Table.from_file(path).table("ram"))
    for name in ("omega", "participation", "participation_gravity"):
        np.testing.assert_array_equal(getattr(back, name), getattr(modes, name))
    assert (back.total_mass, back.toe_stiffness, back.fmax) == (
        modes.total_mass, modes.toe_stiffness, modes.fmax)
    bad = {"omega": modes.omega + 1.0,  # no rigid-body mode
           "participation": modes.participation[:-1],
           "participation_gravity": np.full(modes.n_modes, np.nan),
           "mass": -1.0, "toe_stiffness": 0.0}
    for key, value in bad.items():
        table = toe_modes_table(modes)
        table[key] = value.tolist() if isinstance(value, np.ndarray) else value
        path.write_text(toml_dumps({"ram": table}), encoding="utf-8")
        with pytest.raises(InputError, match=key):
            toe_modes_from_table(Table.from_file(path).table("ram"))


def test_modal_ram_unit_changes_its_step_in_free_flight():
    """A master that changes its step: the unit keeps q_n and the half-step rate, so a rod in
    free flight under gravity follows its exact parabola to round-off across a switch from h1
    to h2 (its rigid mode is exact for a constant load at any step; the flexible modes stay at
    rest)."""
    modes = rod_toe_modes(2.0, 0.1, 20)
    unit = ModalRamUnit(modes, gravity=9.81)
    h1, h2, v0, g = 1e-5, 2.5e-6, 5.0, 9.81
    unit.start(0.0, v0, h1)
    for _ in range(40):
        unit.step(0.0)
    unit.set_step(h2)
    for _ in range(80):
        u, v = unit.step(0.0)
    t = 40 * h1 + 80 * h2
    # the rate kept over the switch is the one of the last h1 step; from there on the parabola
    # through that rate: the offset g (h1 - h2) t' / 2 of the second part, exact
    t1 = 40 * h1
    u1 = v0 * t1 + 0.5 * g * t1 * (t1 + h1)
    rate1 = v0 + g * t1
    expected = u1 + (rate1 + 0.5 * g * h2) * (t - t1) + 0.5 * g * (t - t1) ** 2
    assert u == pytest.approx(expected, rel=1e-10)
    assert v == pytest.approx(rate1 + g * (t - t1), rel=1e-10)
    q, _ = unit.modal_coordinates()
    assert np.all(np.abs(q[1:]) < 1e-12 * abs(q[0]))


def test_unit_arrays_aligned_and_padded():
    """The unit's kernel arrays start on a cache line (64 bytes), rows and both halves of S
    included, with the modes padded to a multiple of 8 by inert columns: 14 modes -> 16, the
    padding stays exactly at rest through steps under a varying force, and the toe
    displacement the vectorised (reassociated) sum gives equals the exactly rounded sum of
    p_j q_j over the 14 modes to 1e-14 of its size (reassociation moves only the last bits)."""
    from anvilwave.anvil_rom.arrays import ALIGNMENT, aligned_zeros

    modes = rod_toe_modes(2.0, 0.1, 13)  # the rigid mode and 13 elastic ones
    n = modes.n_modes
    unit = ModalRamUnit(modes, gravity=9.81)
    unit.start(0.0, 5.0, 1e-6)
    width = unit.C.shape[1]
    assert width == 16
    for row in unit.C:
        assert row.ctypes.data % ALIGNMENT == 0
    assert unit.S.ctypes.data % ALIGNMENT == 0 and (unit.S.ctypes.data + 8 * width) % 64 == 0
    rng = np.random.default_rng(3)
    for force in rng.uniform(0.0, 1e7, 200):
        u, _ = unit.step(force)
        q, previous = unit.modal_coordinates()
        assert q.size == previous.size == n == 14
        exact = math.fsum(unit.C[4, :n] * q)
        assert abs(u - exact) <= 1e-14 * math.fsum(np.abs(unit.C[4, :n] * q))
    assert not unit.S[n:width].any() and not unit.S[width + n:].any()
    for shape, dtype in (((7,), np.float64), ((3, 5), np.float64), ((9,), np.int64)):
        a = aligned_zeros(shape, dtype)
        assert a.shape == shape and a.dtype == dtype and a.flags.c_contiguous
        assert a.ctypes.data % ALIGNMENT == 0 and not a.any()
