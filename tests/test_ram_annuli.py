"""The ram face in annuli (``[anvil] ram_port_annuli``, anvilwave/anvil_rom/rings.py): the modal
ram's toe
annuli make up its toe, the annuli's offsets from the ram unit's toe are the ram's own annulus
displacements, the engine's blow is the pile-port study's closed loop with six ram annuli on the
FEA's pile, and anvilwave/examples/table1_interfaces.toml against the reference FEA (band levels,
peaks,
energy), then the refusals."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from anvilwave.analyses.compare import ModelRun, band_levels, fea_config, metrics, without_soil
from anvilwave.analyses.impact import total_energy
from anvilwave.anvil_rom.fem.modalfile import ModalData
from anvilwave.anvil_rom.rings import RamFace, RingState, ram_face_advance
from anvilwave.config.cache import cached_modal_data
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.modal_ram import ModalRamUnit, modal_ram_modes
from anvilwave.inputs import InputError

from .conftest import assert_within_issue_bounds
from .study_loop import loop_on_feas_pile

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
SYSTEM = EXAMPLES / "table1_interfaces.toml"


@pytest.fixture(scope="module")
def table1():
    return without_soil(load_system(SYSTEM))


@pytest.fixture(scope="module")
def blow(table1):
    return build_engine(table1).blow(energy_interval=2e-5)


def test_toe_annuli_make_up_the_toe(table1):
    """The Table 1 ram's toe in six annuli (the mesh has vertices at their edges): their areas
    are the equal-width annuli's exactly, their area-weighted participations are the toe's and
    their residual flexibility, area-weighted on both sides, is the toe's 1 / toe_stiffness
    (rounding: 1e-9)."""
    modes = table1.hammer.ram.modes
    assert modes.n_annuli == 6
    edges = np.linspace(0.0, 0.5 * table1.hammer.ram.toe_diameter, 7)
    exact = np.pi * np.diff(edges ** 2)
    assert np.abs(modes.annulus_areas - exact).max() <= 1e-9 * exact.sum()
    w = modes.annulus_areas / modes.annulus_areas.sum()
    assert np.abs(w @ modes.annulus_participation - modes.participation).max() <= (
        1e-12 * np.abs(modes.participation).max())
    assert abs(w @ modes.annulus_residual @ w * modes.toe_stiffness - 1.0) <= 1e-9


def test_offsets_are_the_rams_annulus_displacements(table1):
    """Against an independent integration of the ram: every mode of the Table 1 ram (fmax 3 kHz,
    the rigid one included) under smooth annulus forces (half-sines of different lengths and
    delays), solved by scipy's DOP853 to 1e-10; its annulus displacements minus the ram unit's
    toe (the unit driven by the forces' sum) are the offsets :func:`ram_face_advance` keeps, to
    5e-4 of their peak at a 2 us step (the two-step scheme is second order: measured 3.5e-4,
    8.8e-5 and 2.2e-5 at 4, 2 and 1 us; with the offsets' sign flipped the error is 2)."""
    ram = table1.hammer.ram
    modes = modal_ram_modes(ram, 3000.0, modes=cached_modal_data, annuli=3)
    face = RamFace.of(modes.omega, modes.annulus_participation, modes.participation,
                      modes.annulus_residual, modes.annulus_areas)
    duration, h = 2e-3, 2e-6
    lengths = np.array([0.8e-3, 0.5e-3, 0.3e-3])
    delays = np.array([0.0, 0.1e-3, 0.2e-3])
    peaks = np.array([1e8, 2e8, 1.5e8])

    def forces(t):
        x = (t - delays) / lengths
        return np.where((x > 0.0) & (x < 1.0), peaks * np.sin(np.pi * x), 0.0)

    P = modes.annulus_participation  # (J, n), the rigid mode included
    omega = modes.omega

    def rhs(t, y):
        n = omega.size
        q, v = y[:n], y[n:]
        return np.r_[v, -omega ** 2 * q - P.T @ forces(t)]

    steps = int(round(duration / h))
    t = np.arange(steps + 1) * h
    exact = solve_ivp(rhs, (0.0, duration), np.zeros(2 * omega.size), method="DOP853",
                      t_eval=t, rtol=1e-10, atol=1e-16)
    truth = P @ exact.y[:omega.size]  # (J, steps + 1)
    # the model: the ram unit with the sum, the ram face's offsets with the annuli
    unit = ModalRamUnit(modes, gravity=0.0)
    unit.start(0.0, 0.0, h)
    J = face.n_annuli
    m = J + 1
    rings = RingState(*(np.zeros(1) for _ in RingState._fields))._replace(
        forces=np.zeros(m), ram_coefficients=face.coefficients(h),
        ram_participation=np.ascontiguousarray(face.participation.T),
        ram_toe_participation=face.toe, ram_state=np.zeros((4, face.toe.size)),
        ram_offsets=np.zeros((3, J)))
    toe = np.zeros(steps + 1)
    offsets = np.zeros((J, steps + 1))
    for s in range(steps):
        f = forces(s * h)
        rings.forces[:J] = f
        unit.step(float(f.sum()))
        ram_face_advance(rings, h)
        toe[s + 1] = unit.toe[0]
        offsets[:, s + 1] = rings.ram_offsets[0]
    reference = truth - toe
    assert np.abs(offsets - reference).max() <= 5e-4 * np.abs(reference).max()


def test_engine_is_the_study_loop_with_six_ram_annuli(table1, blow):
    """The engine's blow against the pile-port study's closed loop (benchmarks/study_pile_port.py:
    other code, the anvil and the ram meshed afresh with six patches on their faces, the ram's
    whole modal state instead of the unit plus the annuli's offsets, the FEA's tube kernel as
    the whole pile instead of the 1D pile plus its correction) with the same six ram annuli:
    pile force within 0.5 % of its peak RMS (measured 0.33 %; the ram force 0.43 %)."""
    out, dt = loop_on_feas_pile(table1, [[k] for k in range(6)])
    t = np.arange(out.shape[0]) * dt
    engine = np.interp(t, blow.columns["time [s]"], blow.columns["anvil_pile_force [N]"])
    assert np.sqrt(np.mean((engine - out[:, 0]) ** 2)) <= 0.005 * out[:, 0].max()


@pytest.fixture(scope="module")
def against_fea(table1, blow):
    from anvilwave.fea.cache import cached_impact_fea

    fea = cached_impact_fea(fea_config(table1))
    return {"fea": ModelRun("fea", fea.to_columns(), fea.wall_time, {}),
            "rom": ModelRun("rom", blow.columns, 0.0, {})}


def test_band_levels_against_the_fea(against_fea):
    """Table 1 with its interfaces resolved against the reference FEA: every valid
    one-third-octave band of the pile-head force up to 4 kHz within 1 dB (measured 0.71 dB at
    most, 3.98 kHz; the one ram port on the same tube head: 1.25 dB at 398 Hz)."""
    spectra = band_levels(against_fea, 5000.0)
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool) & (centre <= 4000.0)
    deviation = np.array([np.nan if d is None else d
                          for d in spectra["deviation_from_fea [dB]"]["rom"]])
    assert valid.sum() >= 19  # the 50 Hz band (the lowest wholly above 1/T = 40 Hz) to 4 kHz
    assert np.abs(deviation[valid]).max() <= 1.0


def test_peaks_against_the_fea(against_fea):
    """The issue's bounds on the same run, every series low-passed at 5 kHz: pile peak within
    3 % (measured -0.04 %), ram peak within 5 % (-4.2 %), normalised RMS within 10 % (1.3 %,
    3.6 %); raw peaks against the FEA's 5 kHz ones: pile within 5 % (+0.3 %), ram within 10 %
    (+6.9 %)."""
    preload = float(against_fea["rom"].columns["anvil_pile_force [N]"][0])  # anvil's weight
    m = metrics(against_fea["rom"], against_fea["fea"], preload, 5000.0)
    assert_within_issue_bounds(m)


def test_energy_balance(blow):
    """The blow's total energy, what the annuli add to the ram unit's energy and what the rings
    hand to the tube head included, stays within 0.5 % of the impact energy (measured -0.21 %
    to +0.25 %, the tube head's with one ram port -0.19 % to +0.25 %)."""
    total = total_energy(blow.energies)
    drift = (total - total[0]) / blow.input_energy
    assert np.abs(drift).max() <= 5e-3


def test_no_worse_at_fmax_10_khz(against_fea, tmp_path):
    """The anvil's and the ram's modes to 10 kHz (172 and 502), half the step (10 us): every
    valid band to 4 kHz still within 1 dB of the FEA (measured 0.66 dB; 0.71 at fmax 5 kHz),
    the band peaks within the issue's bounds (pile +0.17 %, ram -0.89 %) and the energy within
    0.5 % (measured -0.10 %; it drifted +2.0 % while the tube head booked its work with the
    held force's rectangle, :func:`anvilwave.anvil_rom.rings.head_push`)."""
    path = _system(tmp_path, "fmax = 5000.0 ", "fmax = 10000.0", "fmax10.toml")
    step = 1e-5
    path.write_text(path.read_text().replace("time_step = 2.0e-5 ", f"time_step = {step!r} "))
    cfg = without_soil(load_system(path))
    assert cfg.time_step == step and cfg.anvil.fmax == 10000.0
    blow = build_engine(cfg).blow(energy_interval=2e-5)
    runs = {"fea": against_fea["fea"], "rom": ModelRun("rom", blow.columns, 0.0, {})}
    spectra = band_levels(runs, 5000.0)
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool) & (centre <= 4000.0)
    deviation = np.array([np.nan if d is None else d
                          for d in spectra["deviation_from_fea [dB]"]["rom"]])
    assert np.abs(deviation[valid]).max() <= 1.0
    m = metrics(runs["rom"], runs["fea"], float(blow.columns["anvil_pile_force [N]"][0]),
                5000.0)
    assert abs(m["peak_anvil_pile_force_error [-]"]) <= 0.03
    assert abs(m["peak_ram_anvil_force_error [-]"]) <= 0.05
    total = total_energy(blow.energies)
    assert np.abs((total - total[0]) / blow.input_energy).max() <= 5e-3


def test_one_annulus_is_the_one_port(tmp_path):
    """``ram_port_annuli = 1`` is the one port: the same blow to the bit."""
    text = SYSTEM.read_text().replace("ram_port_annuli = 6", "ram_port_annuli = 1").replace(
        'file = "anvils/xl8.toml"', f'file = "{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"')
    one = tmp_path / "one.toml"
    one.write_text(text)
    port = tmp_path / "port.toml"
    port.write_text(text.replace("ram_port_annuli = 1", ""))
    a = build_engine(without_soil(load_system(one))).blow()
    b = build_engine(without_soil(load_system(port))).blow()
    assert np.array_equal(a.columns["anvil_pile_force [N]"], b.columns["anvil_pile_force [N]"])


def _system(tmp_path, old, new, name="bad.toml"):
    text = SYSTEM.read_text().replace(
        'file = "anvils/xl8.toml"', f'file = "{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"')
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return path


def test_refusals(table1, tmp_path):
    with pytest.raises(InputError, match="ram_port_annuli.*pile_port_rings >= 2"):
        load_system(_no_rings(tmp_path))
    with pytest.raises(InputError, match="ram_port_annuli.*omit ram_contact_stiffness"):
        load_system(_system(tmp_path, "ram_port_annuli = 6",
                            "ram_port_annuli = 6\nram_contact_stiffness = 1e12"))
    with pytest.raises(InputError, match="anvil.ram_port_annuli.*ram_model = 'modal'"):
        load_system(_system(tmp_path, 'ram_model = "modal"', 'ram_model = "rod"'))
    from anvilwave.engine.fmus import build_system_fmus

    with pytest.raises(InputError, match="ram_port_annuli.*in-process engine only"):
        build_system_fmus(dataclasses.replace(table1, anvil=dataclasses.replace(
            table1.anvil, pile_head="rod")), tmp_path / "fmus")
    wider = dataclasses.replace(table1, hammer=dataclasses.replace(
        table1.hammer, ram=dataclasses.replace(table1.hammer.ram, toe_diameter=2.0)))
    with pytest.raises(InputError, match="ram_port_annuli.*same face"):
        build_engine(wider)


def _no_rings(tmp_path):
    text = SYSTEM.read_text().replace(
        'file = "anvils/xl8.toml"', f'file = "{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"')
    text = text.replace("pile_port_rings = 3", "").replace('pile_head = "tube"', "")
    path = tmp_path / "no_rings.toml"
    path.write_text(text)
    return path


def test_modal_data_annulus_keys(table1):
    """The modal-data record checks the annulus keys: both or none, with the ring keys; their
    areas make up the ram face and their participations add up to the face's."""
    from anvilwave.engine.direct import anvil_modal_data

    data = anvil_modal_data(table1)
    assert data.participation_ram_annuli.shape == (6, data.n_modes)
    assert data.ring_flexibility.shape == (9, 9)
    with pytest.raises(InputError, match="ram_annulus_areas.*other ram annulus"):
        dataclasses.replace(data, ram_annulus_areas=None)
    with pytest.raises(InputError, match="ram_annulus_areas.*sum to the ram face"):
        dataclasses.replace(data, ram_annulus_areas=data.ram_annulus_areas * 1.01)
    with pytest.raises(InputError, match="participation_ram_annuli.*add up"):
        dataclasses.replace(data, participation_ram_annuli=data.participation_ram_annuli * 1.01)
    with pytest.raises(InputError, match="ring_flexibility.*9x9"):
        dataclasses.replace(data, ring_flexibility=data.ring_flexibility[:4, :4])
    assert isinstance(data, ModalData)
