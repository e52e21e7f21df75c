"""Tests of anvilwave/pile/pda/case_method.py (Case method, EMX, FMX/CSX/TSX, BTA) and
anvilwave/pile/pda/records.py (gauge
records, raw channels) on records built exactly, without the simulator.

Exact records: a uniform (or two-impedance) steel pile of length L below the gauges, free of
soil, is solved with the method of characteristics on a lattice of cells c dt long (waves move
one cell per time step, so the solution is exact at the samples: d'Alembert). Above the gauges
the pile continues into a matched rod that brings the prescribed down-going pulse p(t) and lets
the up-going waves leave (no head reflection), so the wave down at the gauges is p(t) for all t.
The checks are those of /work/shared/reference/driveability-fatigue-pda-spectra.md (PDA):
no soil -> RTL = 0 and EMX = integral of F^2/Z before 2L/c; all resistance at a rigid-plastic
toe R_t with a toe dashpot Jc Z v_toe -> RSP(Jc) = R_t; an impedance step to beta Z at depth x
-> BTA = beta at x.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from anvilwave.inputs import InputError
from anvilwave.pile.pda.case_method import (
    case_method,
    first_peak_index,
    rausche_goble_1979_beta,
    rausche_goble_likins_1985_static_resistance,
    rausche_goble_likins_1985_total_resistance,
    transferred_energy,
    wave_down,
    wave_up,
)
from anvilwave.pile.pda.records import (
    STANDARD_GRAVITY,
    check_gauge_record,
    gauge_record_from_raw,
    read_gauge_record,
    read_raw_channels,
)

E, RHO = 210e9, 7850.0  # [Pa], [kg/m^3] steel
C = math.sqrt(E / RHO)  # [m/s] 5172.19
AREA = math.pi * (2.0 - 0.05) * 0.05  # [m^2] D = 2 m, wall 50 mm
Z = E * AREA / C  # [N s/m] 12.43652e6
LENGTH = 40.0  # [m] below the gauges
CELLS = 200  # 0.2 m cells: dt = 0.2 / c
DT = LENGTH / CELLS / C  # [s] 38.67 us; 2L/c = 400 dt = 15.47 ms
PULSE_START, PULSE_STEPS = 20, 100  # [-] the pulse starts at 20 dt and lasts 100 dt (3.9 ms)
P = 8.0e6  # [N] pulse amplitude
N_STEPS = 1200  # [-] 46 ms: t1 + 2L/c + the RMX window of 2L/c fits in

# the rounding of sums of a few numbers of order P: 1e-12 relative (1e-5 N on 8 MN)
EXACT = 1e-12


def pulse(n: np.ndarray) -> np.ndarray:
    """p = P sin^2(pi (n - n_s) / m) for n_s <= n <= n_s + m, else 0 [N]: smooth, zero at its
    start and end, peak P at n_s + m/2 (a sample)."""
    phase = (np.asarray(n, dtype=float) - PULSE_START) / PULSE_STEPS
    return np.where((phase >= 0) & (phase <= 1), P * np.sin(np.pi * phase) ** 2, 0.0)


def free_toe(d: float, z: float) -> float:
    return -d  # F = 0 at the toe


def fixed_toe(d: float, z: float) -> float:
    return d  # v = 0 at the toe


def rigid_plastic_toe(capacity: float, case_damping: float) -> Callable[[float, float], float]:
    """Toe resistance R_t + Jc Z v_toe while the toe moves down, 0 <= F <= R_t while it rests.

    With d the wave arriving at the toe and u the reflected one, F = d + u and Z v = d - u. At
    rest (v = 0) u = d and F = 2d, possible while 0 <= 2d <= R_t. Moving:
    d + u = R_t + Jc (d - u) -> u = (R_t - (1 - Jc) d) / (1 + Jc), Z v = (2d - R_t)/(1 + Jc) > 0
    exactly when 2d > R_t (rigid-plastic: no quake, so no other state). Tension: the toe lifts
    off, u = -d.
    """

    def toe(d: float, z: float) -> float:
        if d < 0.0:
            return -d
        if 2.0 * d <= capacity:
            return d
        return (capacity - (1.0 - case_damping) * d) / (1.0 + case_damping)

    return toe


def characteristics_record(impedances: np.ndarray, toe: Callable[[float, float], float]):
    """Exact gauge force and velocity on a lattice pile (module docstring).

    impedances : Z of each of the CELLS cells from the gauges down [N s/m].
    toe : reflected wave at the toe as a function of (arriving wave, toe cell impedance) [N].
    Returns time [s], force [N], velocity [m/s] at the gauges (node 0).
    """
    z = np.asarray(impedances, dtype=float)
    n_cells = z.size
    down = np.zeros(n_cells + 1)  # wave arriving at node j from above
    up = np.zeros(n_cells + 1)  # wave arriving at node j from below
    za, zb = z[:-1], z[1:]  # impedances above / below the internal nodes 1..n-1
    p = pulse(np.arange(N_STEPS))
    force, velocity = np.zeros(N_STEPS), np.zeros(N_STEPS)
    for n in range(N_STEPS):
        down_out = np.empty(n_cells)  # leaving nodes 0..n-1 downward
        up_out = np.empty(n_cells)  # leaving nodes 1..n upward
        down_out[0] = p[n]  # matched rod above the gauges: the pulse passes, WU leaves
        force[n] = p[n] + up[0]
        velocity[n] = (p[n] - up[0]) / z[0]
        # internal nodes: continuity of force and velocity between Za above and Zb below
        d_in, u_in = down[1:n_cells], up[1:n_cells]
        down_out[1:] = (2.0 * zb * d_in + (za - zb) * u_in) / (za + zb)
        up_out[:-1] = down_out[1:] + u_in - d_in
        up_out[-1] = toe(down[n_cells], z[-1])
        down[1:] = down_out  # one cell per step
        up[:-1] = up_out
    return np.arange(N_STEPS) * DT, force, velocity


def analyse(record, case_damping: float = 0.0, **kwargs):
    return case_method(*record, area=AREA, elastic_modulus=E, wave_speed=C,
                       length_below_gauges=LENGTH, case_damping=case_damping, **kwargs)


T_PEAK = (PULSE_START + PULSE_STEPS // 2) * DT  # [s] the pulse peak: t1


# ---------------------------------------------------------------------------------- Case method
def test_lattice_is_exact():
    """The helper itself: on a free-toe pile the wave up at the gauges is -p(t - 2L/c)."""
    t, f, v = characteristics_record(np.full(CELLS, Z), free_toe)
    np.testing.assert_allclose(wave_down(f, v, Z), pulse(np.arange(N_STEPS)), rtol=0, atol=1e-6)
    np.testing.assert_allclose(wave_up(f, v, Z), -pulse(np.arange(N_STEPS) - 2 * CELLS),
                               rtol=0, atol=1e-6)  # 1e-6 N on 8 MN: round-off


def test_no_soil_gives_zero_resistance_and_emx_of_the_pulse():
    record = characteristics_record(np.full(CELLS, Z), free_toe)
    result = analyse(record, case_damping=0.4)
    t, f, v = record
    assert result.t1 == pytest.approx(T_PEAK, rel=EXACT)
    assert result.t2 == pytest.approx(T_PEAK + 2 * LENGTH / C, rel=EXACT)
    assert abs(result.rtl) <= EXACT * P  # RTL = WD(t1) + WU(t2) = P - P
    # EMX = integral F^2 / Z dt before 2L/c (there F = Z v): from the record ...
    before = t <= 2 * LENGTH / C
    energy_before = float(np.sum(0.5 * (f[before][1:] ** 2 + f[before][:-1] ** 2) * DT)) / Z
    assert result.emx == pytest.approx(energy_before, rel=EXACT)
    # ... and in closed form: int P^2 sin^4 = 3/8 P^2 T_p, integrated exactly by the trapezoid
    # rule (a trigonometric polynomial of degree 4 sampled 100 times per period)
    assert result.emx == pytest.approx(3.0 / 8.0 * P ** 2 * PULSE_STEPS * DT / Z, rel=1e-12)
    # the free toe reflects the pulse as a tension wave of the same size: TSX = P / A
    assert result.fmx == pytest.approx(P, rel=EXACT)
    assert result.csx == pytest.approx(P / AREA, rel=EXACT)
    assert result.tsx == pytest.approx(P / AREA, rel=EXACT)
    assert result.bta == 1.0 and math.isnan(result.bta_depth)  # uniform pile
    assert set(result.summary()) == {"RTL [N]", "RSP [N]", "RMX [N]", "EMX [J]", "FMX [N]",
                                     "CSX [Pa]", "TSX [Pa]", "BTA [-]"}


def test_fixed_toe_reads_as_twice_the_wave_down():
    """A fixed toe holds F = 2 WD with v_toe = 0: RTL = RSP(any Jc) = 2 P, no tension."""
    result = analyse(characteristics_record(np.full(CELLS, Z), fixed_toe), case_damping=0.5)
    assert result.rtl == pytest.approx(2 * P, rel=EXACT)
    assert result.rsp == pytest.approx(2 * P, rel=EXACT)
    assert result.tsx <= EXACT * P / AREA  # no tension: round-off only


@pytest.mark.parametrize(("capacity", "case_damping"), [(12e6, 0.3), (9e6, 0.1), (15e6, 0.7)])
def test_rigid_plastic_toe_with_dashpot_gives_rsp_equal_to_capacity(capacity, case_damping):
    """All resistance at a rigid-plastic toe R_t with a dashpot Jc Z v_toe: RSP(Jc) = R_t, and
    RMX(Jc) = R_t too (when the toe rests, RSP = 2 WD <= R_t). 2 P = 16 MN > R_t: it moves."""
    record = characteristics_record(np.full(CELLS, Z), rigid_plastic_toe(capacity, case_damping))
    result = analyse(record, case_damping=case_damping)
    assert result.rsp == pytest.approx(capacity, rel=EXACT)
    assert result.rmx == pytest.approx(capacity, rel=EXACT)
    # RTL is the whole toe force, R_t plus the dashpot: R_t + Jc (2P - R_t)/(1 + Jc)
    assert result.rtl == pytest.approx(capacity + case_damping * (2 * P - capacity)
                                       / (1 + case_damping), rel=EXACT)
    # another Jc misses R_t: RSP(J) = R_t + (Jc - J) Z v_toe
    other = analyse(record, case_damping=case_damping + 0.1)
    assert other.rsp < capacity - 1e4


@pytest.mark.parametrize(("beta", "depth"), [(0.7, 15.0), (0.5, 24.0), (0.9, 32.0)])
def test_impedance_step_gives_bta(beta, depth):
    """Z -> beta Z at depth x, free toe, no soil: BTA = beta at x. The step reflects
    r = (beta - 1)/(beta + 1) of the wave down; the onset t0 is the pulse start (WD = 0), so
    WU(tr) = 0 and WU(tx) = r P: exact. Depths beyond c T_p / 2 = 10 m keep the reflection off
    the impact peak, and below L - c (t1 - t0)/2 = 35 m the toe reflection is not reached."""
    cells_above = round(depth / (LENGTH / CELLS))
    impedances = np.where(np.arange(CELLS) < cells_above, Z, beta * Z)
    record = characteristics_record(impedances, free_toe)
    result = analyse(record, bta_cutoff=None)  # the formula on the samples
    assert result.bta == pytest.approx(beta, rel=EXACT)
    assert result.bta_depth == pytest.approx(depth, abs=1e-9)  # x = c (tx - t1)/2, on the grid
    # low-passed as by default (no overshoot): the same step within 1 %, its depth within the
    # filter's reach
    filtered = analyse(record)
    assert filtered.bta == pytest.approx(beta, rel=0.01)
    assert filtered.bta_depth == pytest.approx(depth, abs=2.0)


def test_rmx_window_and_t1_choice():
    record = characteristics_record(np.full(CELLS, Z), rigid_plastic_toe(12e6, 0.3))
    # window 0: RMX is RSP at t1
    assert analyse(record, 0.3, rmx_window=0.0).rmx == pytest.approx(12e6, rel=EXACT)
    # t1 from the force: same peak here (no reflection before 2L/c)
    assert analyse(record, 0.3, t1_signal="force").t1 == pytest.approx(T_PEAK, rel=EXACT)
    with pytest.raises(ValueError, match="t1_signal"):
        analyse(record, 0.3, t1_signal="strain")
    t, f, v = record
    with pytest.raises(ValueError, match="before t1"):
        analyse((t[:400], f[:400], v[:400]))  # ends before t1 + 2L/c


def test_case_formulas_agree():
    """RSP from forces/velocities and RTL from the waves are one formula: Jc = 0 -> RSP = RTL."""
    f1, v1, f2, v2 = 5e6, 0.3, 2e6, -0.1
    rtl = rausche_goble_likins_1985_total_resistance(wave_down(f1, v1, Z), wave_up(f2, v2, Z))
    assert rausche_goble_likins_1985_static_resistance(f1, v1, f2, v2, Z, 0.0) == pytest.approx(
        rtl, rel=1e-15)
    # beta: a reflection of -P/3 from a wave of P -> alpha = 1/3, beta = 0.5
    assert rausche_goble_1979_beta(P, 0.0, -P / 3) == pytest.approx(0.5, rel=1e-15)
    # first peak skips ripple below the prominence
    s = np.array([0.0, 0.05, 0.04, 0.5, 1.0, 0.6, 0.9, 0.2])
    assert first_peak_index(s) == 4
    assert transferred_energy([0, 1, 2], [1, 1, 1], [2, 2, 2])[-1] == pytest.approx(4.0)


# ---------------------------------------------------------------------------------- records
def _write_csv(path, header: list[str], columns: list[np.ndarray]) -> None:
    lines = [",".join(header)]
    lines += [",".join(repr(float(x)) for x in row) for row in zip(*columns, strict=True)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def test_gauge_record_csv_round_trip(tmp_path):
    t, f, v = characteristics_record(np.full(CELLS, Z), free_toe)
    path = tmp_path / "blow.csv"
    _write_csv(path, ["time [s]", "force [N]", "velocity [m/s]"], [t, f, v])
    record = read_gauge_record(path)
    np.testing.assert_array_equal(record.force, f)  # repr round-trips floats exactly
    path2 = tmp_path / "sim.csv"
    _write_csv(path2, ["time [s]", "gauge_force [N]", "gauge_velocity [m/s]", "extra [-]"],
               [t, f, v, t])
    np.testing.assert_array_equal(read_gauge_record(path2).velocity, v)


def _known_raw_record():
    """Force and velocity known in closed form, and the raw channels they come from.

    v(t) = V sin^2(pi (t - ts)/Tv) for ts <= t <= ts + Tv (returns to rest), a = dv/dt =
    V pi/Tv sin(2 pi (t - ts)/Tv); F(t) = P sin^2(pi (t - ts)/Tf), Tf = 6 ms.
    """
    dt, n = 1.0e-5, 5000  # 100 kHz, 50 ms
    t = np.arange(n) * dt
    ts, tv, tf, amplitude = 0.002, 0.008, 0.006, 3.0
    s = t - ts
    on_v, on_f = (s >= 0) & (s <= tv), (s >= 0) & (s <= tf)
    velocity = np.where(on_v, amplitude * np.sin(np.pi * s / tv) ** 2, 0.0)
    acceleration = np.where(on_v, amplitude * np.pi / tv * np.sin(2 * np.pi * s / tv), 0.0)
    force = np.where(on_f, P * np.sin(np.pi * s / tf) ** 2, 0.0)
    return t, force, velocity, acceleration, ts


def test_raw_channels_convert_to_the_known_force_and_velocity(tmp_path):
    t, force, velocity, acceleration, ts = _known_raw_record()
    strain = force / (E * AREA)
    bending = 40e-6 * np.sin(2 * np.pi * 30.0 * t)  # opposite on the two gauges: cancels
    calibration = (1.03, 0.98)  # the file holds strain / calibration
    strain_1 = (strain + bending) / calibration[0] * 1e6  # [microstrain]
    strain_2 = (strain - bending) / calibration[1] * 1e6
    # accelerometers: offsets at rest, and a zero shift of 0.8 m/s^2 from the impact on
    shift = np.where(t >= ts, 0.8, 0.0)
    accel_1 = (acceleration + 0.3 + shift) / STANDARD_GRAVITY  # [g]
    accel_2 = acceleration - 0.1 + shift  # [m/s^2]
    path = tmp_path / "raw.csv"
    _write_csv(path, ["time [s]", "strain_1 [microstrain]", "strain_2 [microstrain]",
                      "acceleration_1 [g]", "acceleration_2 [m/s^2]"],
               [t, strain_1, strain_2, accel_1, accel_2])
    raw = read_raw_channels(path)
    np.testing.assert_allclose(raw.strain[:, 0] * calibration[0], strain + bending, rtol=1e-12)
    record = gauge_record_from_raw(path, area=AREA, elastic_modulus=E,
                                   strain_calibration=calibration)
    # force: exact up to the decimal round trip of the CSV (1e-12 of the peak)
    np.testing.assert_allclose(record.force, force, rtol=0, atol=1e-9 * P)
    # velocity: the offsets are removed exactly (mean at rest) and the zero shift by the linear
    # drift from the impact (detected at the foot of the rise, ts, within one sample). What
    # remains: the trapezoidal rule, |error| <= dt^2/12 (max a' - min a') = 1e-10/12 x
    # 4 V (pi/Tv)^2 = 1.54e-5 m/s, plus at most half a step of the zero shift where the ramp
    # starts, 0.8 dt / 2 = 4e-6 m/s: 3e-5 m/s (1e-5 of the 3 m/s peak).
    np.testing.assert_allclose(record.velocity, velocity, rtol=0, atol=3e-5)
    # the same with the impact time given
    given = gauge_record_from_raw(path, area=AREA, elastic_modulus=E,
                                  strain_calibration=calibration, impact_time=ts)
    np.testing.assert_allclose(given.velocity, velocity, rtol=0, atol=3e-5)
    # uncorrected, the zero shift would leave 0.8 m/s^2 x 48 ms = 0.038 m/s at the end
    assert abs(record.velocity[-1]) < 1e-12


@pytest.mark.parametrize(("mutate", "column", "words"), [
    (lambda c: c[1].__setitem__(100, np.nan), "force [N]", "not a finite number"),
    (lambda c: c[0].__setitem__(50, c[0][49]), "time [s]", "increase strictly"),
    (lambda c: c[1].__setitem__(slice(300, 312), c[1].max()), "force [N]", "clipped"),
    (lambda c: c[2].__setitem__(slice(None), 0.25), "velocity [m/s]", "constant"),
])
def test_bad_gauge_records(tmp_path, mutate, column, words):
    t, f, v = characteristics_record(np.full(CELLS, Z), free_toe)
    columns = [t.copy(), f.copy(), v.copy()]
    mutate(columns)
    path = tmp_path / "bad.csv"
    _write_csv(path, ["time [s]", "force [N]", "velocity [m/s]"], columns)
    with pytest.raises(InputError) as caught:
        read_gauge_record(path)
    assert caught.value.source == str(path) and caught.value.key == column
    assert words in caught.value.rule
    with pytest.raises(InputError, match=words):  # the same rules on arrays
        check_gauge_record(*columns)


def test_bad_files(tmp_path):
    t, f, v = characteristics_record(np.full(CELLS, Z), free_toe)
    # channels of different lengths: velocity ends 10 samples early
    lines = ["time [s],force [N],velocity [m/s]"]
    lines += [f"{a},{b},{c}" for a, b, c in zip(t.tolist(), f.tolist(), v.tolist(), strict=True)]
    lines[-10:] = [f"{a},{b}," for a, b in zip(t[-10:].tolist(), f[-10:].tolist(), strict=True)]
    path = tmp_path / "short.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(InputError, match="different lengths") as caught:
        read_gauge_record(path)
    assert caught.value.key == "velocity [m/s]"
    with pytest.raises(InputError, match="different lengths"):
        check_gauge_record(t, f, v[:-1])
    # text in a number column, a missing column, a missing file
    path.write_text("time [s],force [N],velocity [m/s]\n0,1,2\n1,x,3\n2,1,1\n", encoding="utf-8")
    with pytest.raises(InputError, match="line 3: 'x' is not a number"):
        read_gauge_record(path)
    path.write_text("time [s],force [kN],velocity [m/s]\n0,1,2\n", encoding="utf-8")
    with pytest.raises(InputError, match="force \\[N\\]: is missing"):
        read_gauge_record(path)
    with pytest.raises(InputError, match="file not found"):
        read_gauge_record(tmp_path / "none.csv")
    # a clipped raw accelerometer (pinned at its maximum for 20 samples)
    time, force, velocity, acceleration, _ = _known_raw_record()
    acceleration = acceleration.copy()
    top = acceleration.max()
    acceleration[np.argmax(acceleration):np.argmax(acceleration) + 20] = top
    strain = force / (E * AREA)
    raw = tmp_path / "clipped.csv"
    _write_csv(raw, ["time [s]", "strain_1 [-]", "strain_2 [-]", "acceleration_1 [m/s^2]",
                     "acceleration_2 [m/s^2]"],
               [time, strain, strain, acceleration, np.where(time > 0.001, 1.0, 0.0) + velocity])
    with pytest.raises(InputError, match="acceleration_1 \\[m/s\\^2\\]: is clipped"):
        gauge_record_from_raw(raw, area=AREA, elastic_modulus=E)
