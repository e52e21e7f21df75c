"""Tests of anvilwave/pile/post/fatigue.py: DNV-RP-C203 (2016) S-N curves, rainflow counting (ASTM
E1049-85),
Miner's sum and the blow-by-blow streaming count.

Reference values are from /work/shared/reference/driveability-fatigue-pda-spectra.md; the other
hand values are worked out in the comments (log10 arithmetic on the tabulated log a).
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np
import pytest

from anvilwave.pile.post.fatigue import (
    DNV_RP_C203_TABLES,
    REFERENCE_THICKNESS_TUBULAR_JOINT,
    RainflowStream,
    StreamingMinerDamage,
    dnv_rp_c203_2016_cycles_to_failure,
    dnv_rp_c203_2016_effective_thickness,
    dnv_rp_c203_2016_thickness_factor,
    dnv_rp_c203_cycles_to_failure,
    miner_1945_damage,
    rainflow_cycles,
    rainflow_damage,
    sn_curve,
)

MPA = 1.0e6
ASTM_HISTORY = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]
ASTM_COUNTS = {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}  # ASTM E1049-85 Fig. 6


def _histogram(ranges, counts) -> dict[float, float]:
    out: dict[float, float] = defaultdict(float)
    for r, c in zip(ranges, counts, strict=True):
        out[float(r)] += float(c)
    return dict(out)


# ---------------------------------------------------------------------------------- S-N curves
# The reference hand values are given to 5 significant digits: relative tolerance 5e-5 is half a
# unit in the last digit (3.4e-5 of 1.4588e6) with margin.
@pytest.mark.parametrize(("thickness", "scf", "expected"), [
    (0.025, 1.0, 1.4588e6),   # log N = 12.164 - 3 log 100 = 6.164
    (0.080, 1.0, 7.2596e5),   # 100 (80/25)^0.2 = 126.19 MPa
    (0.080, 1.2, 4.2011e5),   # 1.2 x 126.19 MPa
])
def test_dnv_d_curve_in_air_hand_values(thickness, scf, expected):
    n = dnv_rp_c203_2016_cycles_to_failure(100.0 * MPA, "D", "air", thickness, scf)
    assert n == pytest.approx(expected, rel=5e-5)


@pytest.mark.parametrize(("stress", "environment", "expected"), [
    # air below the 1e7 limit (52.63 MPa): m = 5, log N = 15.606 - 5 log 40 = 7.59570
    (40.0, "air", 3.9418e7),
    # seawater with CP, N <= 1e6: log N = 11.764 - 3 log 100 = 5.764
    (100.0, "seawater-cp", 5.8076e5),
    # seawater with CP: 11.764 - 3 log 60 = 6.429 > 6 -> m = 5 line: 15.606 - 5 log 60 = 6.71524
    (60.0, "seawater-cp", 5.1909e6),
    # free corrosion, one slope m = 3: log N = 11.687 - 3 log 30 = 7.25564
    (30.0, "free-corrosion", 1.8015e7),
])
def test_dnv_d_curve_segments_and_environments(stress, environment, expected):
    n = dnv_rp_c203_2016_cycles_to_failure(stress * MPA, "D", environment, 0.025)
    assert n == pytest.approx(expected, rel=5e-5)  # 5 significant digits, as above


def test_thickness_correction_rules():
    # thinner than t_ref: no correction (it only ever penalises thick sections)
    assert dnv_rp_c203_2016_thickness_factor(0.010, 0.2) == 1.0
    assert dnv_rp_c203_2016_thickness_factor(0.080, 0.2) == pytest.approx(3.2 ** 0.2, rel=1e-15)
    # tubular joints: t_ref = 32 mm; D at 100 MPa, t = 40 mm: 100 x 1.25^0.2 = 104.56 MPa,
    # log N = 12.164 - 3 log 104.56 = 6.10584 -> N = 1.2760e6
    n = dnv_rp_c203_2016_cycles_to_failure(
        100.0 * MPA, "D", "air", 0.040, reference_thickness=REFERENCE_THICKNESS_TUBULAR_JOINT)
    assert n == pytest.approx(1.2760e6, rel=5e-5)
    # k = 0 (B1): thickness has no effect
    assert (dnv_rp_c203_2016_cycles_to_failure(200.0 * MPA, "B1", "air", 0.1)
            == dnv_rp_c203_2016_cycles_to_failure(200.0 * MPA, "B1", "air", 0.02))
    # t_eff = min(14 mm + 0.66 L, t)
    assert dnv_rp_c203_2016_effective_thickness(0.08, 0.03) == pytest.approx(0.0338, abs=1e-15)
    assert dnv_rp_c203_2016_effective_thickness(0.02, 0.10) == pytest.approx(0.02, abs=1e-15)


@pytest.mark.parametrize("name", list(DNV_RP_C203_TABLES["2016"]))
def test_2016_table_is_self_consistent(name):
    """The typed columns check each other (a typo in one number breaks the test).

    The tabulated log a are rounded to 3 decimals (5e-4 in log N) and the limit to 4 digits:
    a tolerance of 2.5e-3 in log N (and 0.05 % on the limit, 5e-4 / 3 in log S) covers the
    rounding and catches any wrong digit but the last.
    """
    sn = DNV_RP_C203_TABLES["2016"][name]
    limit = 10.0 ** ((sn.log_a1_air - 7.0) / sn.m1)  # first segment reaches 1e7 at the limit
    assert limit == pytest.approx(sn.fatigue_limit_air, rel=5e-4)
    assert sn.log_a2 - 5.0 * math.log10(sn.fatigue_limit_air) == pytest.approx(7.0, abs=2.5e-3)
    # seawater with CP: its first segment meets the same m = 5 line at N = 1e6
    s_cp = (sn.log_a1_seawater_cp - 6.0) / sn.m1
    assert sn.log_a2 - 5.0 * s_cp == pytest.approx(6.0, abs=2.5e-3)
    # the curve is continuous at the slope change up to that rounding
    s = 10.0 ** s_cp * MPA
    below = dnv_rp_c203_2016_cycles_to_failure(s * (1 - 1e-9), name, "seawater-cp", 0.025)
    above = dnv_rp_c203_2016_cycles_to_failure(s * (1 + 1e-9), name, "seawater-cp", 0.025)
    assert math.log10(below) == pytest.approx(math.log10(above), abs=2.5e-3)


def test_editions_and_bad_options():
    assert (dnv_rp_c203_cycles_to_failure(1e8, "D", "air", 0.03, edition="2016")
            == dnv_rp_c203_2016_cycles_to_failure(1e8, "D", "air", 0.03))
    for kwargs, word in [
        ({"edition": "2024"}, "edition"),       # no 2024 values are typed (none invented)
        ({"curve": "Z"}, "curve"),
        ({"environment": "water"}, "environment"),
    ]:
        args = {"stress_range": 1e8, "curve": "D", "environment": "air", "thickness": 0.03}
        args.update(kwargs)
        with pytest.raises(ValueError, match=word):
            dnv_rp_c203_cycles_to_failure(**args)
    with pytest.raises(ValueError, match="negative"):
        dnv_rp_c203_2016_cycles_to_failure(-1.0, "D", "air", 0.03)
    assert np.isinf(dnv_rp_c203_2016_cycles_to_failure(0.0, "D", "air", 0.03))


# ---------------------------------------------------------------------------------- rainflow
def test_astm_e1049_example():
    assert _histogram(*rainflow_cycles(ASTM_HISTORY)) == ASTM_COUNTS


@pytest.mark.parametrize("cuts", [[], [1, 2, 3, 4, 5, 6, 7, 8], [3], [2, 5, 6], [4, 4, 8]])
def test_astm_e1049_example_streamed(cuts):
    stream = RainflowStream()
    ranges, counts = [], []
    for block in np.split(np.array(ASTM_HISTORY), cuts):
        r, c = stream.add(block)
        ranges += r.tolist()
        counts += c.tolist()
    r, c = stream.residue_cycles()
    assert _histogram(ranges + r.tolist(), counts + c.tolist()) == ASTM_COUNTS
    # the residue at the end is short: only the reversals not closed yet are kept
    assert len(stream.residue) <= 5


def test_constant_amplitude_gives_n_over_big_n():
    n_cycles = 1000
    history = np.tile([0.0, 80.0 * MPA], n_cycles + 1)[: 2 * n_cycles + 1]  # 1000 cycles
    big_n = dnv_rp_c203_2016_cycles_to_failure(80.0 * MPA, "D", "air", 0.04)
    d = rainflow_damage(history, sn_curve("D", "air", 0.04))
    assert d == pytest.approx(n_cycles / big_n, rel=1e-12)  # same numbers summed: round-off


def _blows(n_blows: int, n_sections: int, seed: int) -> list[np.ndarray]:
    """Blow-like histories: a compression peak, tension reflections, a decaying tail and a
    residual stress that drifts from blow to blow (so cycles close across blows)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 0.06, 400)
    out = []
    for _ in range(n_blows):
        cols = []
        for j in range(n_sections):
            residual = rng.normal(0.0, 10.0 * MPA)
            peak = (150.0 + 30.0 * rng.random() + 20.0 * j) * MPA
            s = (peak * np.exp(-((t - 0.005) / 0.002) ** 2)
                 - 0.4 * peak * np.exp(-((t - 0.020) / 0.002) ** 2)
                 + 0.2 * peak * np.sin(2 * np.pi * 90.0 * t) * np.exp(-t / 0.01)
                 + residual)
            cols.append(s + rng.normal(0.0, 0.5 * MPA, t.size))
        out.append(np.column_stack(cols))
    return out


def test_streamed_blows_equal_the_whole_sequence():
    blows = _blows(60, 3, seed=3)
    functions = [sn_curve("D", "seawater-cp", 0.08, scf=1.2), sn_curve("F", "air", 0.06),
                 sn_curve("C1", "free-corrosion", 0.03)]
    acc = StreamingMinerDamage(functions)
    for blow in blows:
        acc.add_blow(blow)
    whole = np.vstack(blows)
    expected = [rainflow_damage(whole[:, j], functions[j]) for j in range(3)]
    # same cycles, summed in the same order up to the residue: round-off only
    np.testing.assert_allclose(acc.damage(), expected, rtol=1e-12)
    assert acc.blows == 60
    assert np.all(acc.closed_damage <= acc.damage())
    # memory: the residue stays short however many blows went through
    assert max(len(s.residue) for s in acc.streams) < 50


def test_streaming_equals_whole_on_random_splits():
    """Random walks (with repeated values and plateaus) split at random points, one sample
    blocks and empty blocks included: identical damage for every split."""
    rng = np.random.default_rng(7)
    fn = sn_curve("E", "air", 0.025)
    for _ in range(300):
        n = int(rng.integers(1, 200))
        x = np.round(rng.normal(size=n).cumsum(), int(rng.integers(0, 2))) * 20.0 * MPA
        cuts = np.sort(rng.integers(0, n + 1, size=int(rng.integers(0, 12))))
        acc = StreamingMinerDamage(fn, n_sections=1)
        for block in np.split(x, cuts):
            acc.add_blow(block)
        expected = rainflow_damage(x, fn)
        assert acc.damage()[0] == pytest.approx(expected, rel=1e-12, abs=1e-300)


def test_one_blow_times_blows_underestimates():
    """The reference's point: blows start and end at the residual stress, so the largest range
    of a blow (compression peak to tension trough) only closes with the next blow. Counting one
    blow and multiplying loses it: here blow = [0, 100, -50, 0] MPa, D curve in air: one blow
    = half cycles of 100, 150 and 50 MPa; the sequence = one full 150 MPa cycle per blow:
    single / whole = 0.5 (100^3 + 150^3 + 10^(12.164 - 15.606) 50^5) / 150^3 = 0.665."""
    blow = np.array([0.0, 100.0, -50.0, 0.0]) * MPA
    n_blows = 2000
    fn = sn_curve("D", "air", 0.025)
    single = rainflow_damage(blow, fn) * n_blows
    whole = rainflow_damage(np.tile(blow, n_blows), fn)
    acc = StreamingMinerDamage(fn, n_sections=1)
    for _ in range(n_blows):
        acc.add_blow(blow)
    assert acc.damage()[0] == pytest.approx(whole, rel=1e-12)
    n_150 = dnv_rp_c203_2016_cycles_to_failure(150.0 * MPA, "D", "air", 0.025)
    # the whole sequence: n_blows - 1 full 150 MPa cycles plus half cycles at its two ends,
    # i.e. n_blows / N(150) within 1 / n_blows = 5e-4
    assert whole == pytest.approx(n_blows / n_150, rel=1e-3)
    assert single / whole == pytest.approx(0.66488, rel=1e-3)  # 33.5 % less (reference: 23 %)
    # and on the realistic blows above
    blows = _blows(40, 1, seed=5)
    d_single = sum(rainflow_damage(b[:, 0], fn) for b in blows)
    d_whole = rainflow_damage(np.concatenate([b[:, 0] for b in blows]), fn)
    assert d_single < 0.8 * d_whole  # 31 % less with these blows


def test_miner_sum_and_input_checks():
    assert miner_1945_damage([0.5, 1.0], [1e6, 2e6]) == pytest.approx(1e-6, rel=1e-15)
    acc = StreamingMinerDamage(sn_curve("D", "air", 0.03), n_sections=2)
    with pytest.raises(ValueError, match="shape"):
        acc.add_blow(np.zeros((10, 3)))
    with pytest.raises(ValueError, match="non-finite"):
        acc.add_blow(np.full((10, 2), np.nan))
    with pytest.raises(ValueError, match="n_sections"):
        StreamingMinerDamage(sn_curve("D", "air", 0.03))
    assert acc.damage().tolist() == [0.0, 0.0]
