"""Tests of anvilwave/pile/soil/profile.py and anvilwave/pile/soil/cpt.py: stresses, qt, SRD
distributions per tip depth,
user tables per tip depth, and CPT file reading (good files, bad files, the ISFOG 2020 CPTs).

Hand values are worked in the comments; the Alm & Hamre distributions are checked against an
independent adaptive quadrature (scipy.integrate.quad) of the pure formulas.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from anvilwave.inputs import InputError
from anvilwave.pile.soil import srd_methods as sm
from anvilwave.pile.soil.cpt import read_cpt_csv
from anvilwave.pile.soil.profile import (
    AlmHamre2001,
    Cpt,
    SoilLayer,
    SoilProfile,
    Stevens1982,
    TipDepthTables,
    campanella_1982_total_cone_resistance,
    srd_distribution,
    srd_versus_depth,
    tip_table_resistance,
    toe_bearing_area,
)

KPA = 1e3
SHARED = Path(__file__).resolve().parents[2] / "shared"
ISFOG = SHARED / "reference" / "isfog2020"
needs_isfog = pytest.mark.skipif(
    not ISFOG.is_dir(), reason=f"ISFOG 2020 reference data not found at {ISFOG} (the shared "
                               "folder beside the repository)")

D, T = 2.0, 0.05  # [m] outer diameter and wall of the test pile
PERIMETER_OUT = math.pi * D
PERIMETER_IN = math.pi * (D - 2 * T)
ANNULUS = math.pi / 4 * (D ** 2 - (D - 2 * T) ** 2)


def sand(top, bottom, gamma=10e3, delta=25.0):
    return SoilLayer(top, bottom, "sand", gamma, interface_friction_angle=delta)


def linear_cpt(depth_end=40.0, qc_top=5e6, qc_bottom=25e6, fs_top=20e3, fs_bottom=200e3):
    """A CPT with qc and fs linear in depth (two readings), u2 = 0."""
    return Cpt(np.array([0.0, depth_end]), np.array([qc_top, qc_bottom]),
               np.array([fs_top, fs_bottom]), np.zeros(2))


def segments_below_mudline(pile_length, tip, dx=0.5):
    """Tops below the mudline and lengths of equal segments of a pile with its tip at tip."""
    n = round(pile_length / dx)
    return np.arange(n) * dx - (pile_length - tip), np.full(n, dx)


# ---------------------------------------------------------------- profile
def test_vertical_effective_stress_against_hand_value():
    profile = SoilProfile([sand(0, 5, 8e3), sand(5, 12, 10e3), sand(12, 20, 9e3)])
    # 5 m x 8 kN/m3 + 7 m x 10 kN/m3 + 3 m x 9 kN/m3 = 40 + 70 + 27 = 137 kPa at 15 m
    assert profile.vertical_effective_stress(15.0) == pytest.approx(137 * KPA, rel=1e-14)
    np.testing.assert_allclose(profile.vertical_effective_stress([0.0, 5.0, 12.0, 20.0]),
                               np.array([0.0, 40.0, 110.0, 182.0]) * KPA, rtol=1e-14)
    # on a boundary the deeper layer is taken (same stress either way)
    np.testing.assert_array_equal(profile.layer_index([0.0, 4.99, 5.0, 20.0]), [0, 0, 1, 2])
    with pytest.raises(ValueError, match="within the soil profile"):
        profile.vertical_effective_stress(20.5)


def test_undrained_strength_linear_in_a_layer():
    clay = SoilLayer(4.0, 10.0, "clay", 7e3, undrained_shear_strength=30e3,
                     undrained_shear_strength_gradient=2e3, plasticity_index=0.3)
    profile = SoilProfile([sand(0, 4), clay])
    assert profile.undrained_shear_strength(7.0) == pytest.approx(36e3)  # 30 + 2 x 3 kPa
    assert np.isnan(profile.undrained_shear_strength(2.0))  # not given in the sand


def test_total_cone_resistance():
    # qt = qc + (1 - a) u2 = 10 MPa + 0.2 x 0.5 MPa = 10.1 MPa
    assert campanella_1982_total_cone_resistance(10e6, 0.5e6) == pytest.approx(10.1e6)
    assert campanella_1982_total_cone_resistance(10e6, 0.5e6, 1.0) == 10e6
    cpt = Cpt([0.0, 10.0], [10e6, 20e6], [0.1e6, 0.2e6], [0.5e6, 1.0e6])
    profile = SoilProfile([sand(0, 10)], cpt, net_area_ratio=0.75)
    # at 5 m: qc 15 MPa, u2 0.75 MPa -> 15 + 0.25 x 0.75 = 15.1875 MPa
    assert profile.qt(5.0) == pytest.approx(15.1875e6, rel=1e-14)
    # at the readings: 10 + 0.25 x 0.5 and 20 + 0.25 x 1.0 MPa, read-only
    readings = profile.qt_readings
    assert readings == pytest.approx([10.125e6, 20.25e6], rel=1e-14)
    with pytest.raises(ValueError):
        readings[0] = 0.0
    with pytest.raises(ValueError, match="needs a CPT"):
        _ = SoilProfile([sand(0, 10)]).qt_readings


def test_profile_and_layer_validation():
    with pytest.raises(ValueError, match="must start where layer 0 ends"):
        SoilProfile([sand(0, 5), sand(6, 10)])
    with pytest.raises(ValueError, match="mudline"):
        SoilProfile([sand(1, 5)])
    with pytest.raises(ValueError, match="fraction"):
        SoilLayer(0, 5, "clay", 8e3, undrained_shear_strength=20e3, plasticity_index=30.0)
    with pytest.raises(ValueError, match="soil_type"):
        SoilLayer(0, 5, "silt", 8e3)
    with pytest.raises(ValueError, match="increase"):
        Cpt([0.0, 2.0, 1.0], [1e6] * 3, [1e4] * 3, [0.0] * 3)


# ---------------------------------------------------------------- Stevens distributions
def test_stevens_distribution_total_against_hand_integral():
    # One sand layer, gamma' = 10 kN/m3, delta = 25 deg, K = 0.5: f = a z with
    # a = 0.5 x 10e3 x tan 25 = 2331.538 Pa/m, below f_L = 81 kPa down to z* = 34.741 m.
    profile = SoilProfile([sand(0, 60)])
    a = 0.5 * 10e3 * math.tan(math.radians(25.0))
    tops, lengths = segments_below_mudline(30.0, 20.0)
    result = srd_distribution(profile, "stevens-1982", 20.0, tops, lengths, D, T)
    # coring: outside + inside friction, a 20^2 / 2 x pi (D + D - 2t) = 5.7133 MN; linear
    # integrand, so Gauss is exact: round-off only
    assert result.srd_shaft == pytest.approx(a * 20.0 ** 2 / 2 * (PERIMETER_OUT + PERIMETER_IN),
                                             rel=1e-12)
    assert result.srd_shaft == pytest.approx(5.7133e6, rel=1e-4)
    # the 10 m sticking up above the mudline carry nothing
    assert np.all(result.shaft[:20] == 0.0) and np.all(result.embedded_length[:20] == 0.0)
    # toe: Nq(25) sigma'v0 = 20 x 200 kPa = 4 MPa < q_L = 4.8 MPa, on the annulus
    assert result.srd_toe == pytest.approx(4.0e6 * ANNULUS, rel=1e-12)
    assert result.srd == pytest.approx(result.srd_shaft + result.srd_toe)

    # deeper than z*: f = min(a z, 81 kPa); integral a z*^2 / 2 + f_L (p - z*). The kink at z*
    # falls inside one 0.1 m Gauss piece: its error is below a h^2 / 4 ~ 6 N/m against
    # 2.6 MN/m, so 1e-5 is ample.
    z_star = 81e3 / a
    deep = srd_distribution(profile, "stevens-1982", 50.0, [0.0], [50.0], D, T,
                            pile_mode="plugged")
    exact = (a * z_star ** 2 / 2 + 81e3 * (50.0 - z_star)) * PERIMETER_OUT
    assert deep.srd_shaft == pytest.approx(exact, rel=1e-5)
    # plugged: toe on the full section, 20 x 500 kPa = 10 MPa capped at q_L = 4.8 MPa
    assert deep.srd_toe == pytest.approx(4.8e6 * math.pi / 4 * D ** 2, rel=1e-12)


def test_segment_spanning_a_layer_boundary_takes_each_layer_share():
    # delta 20 deg above 10.3 m, 30 deg below (gamma' 10 then 8 kN/m3); the segment
    # [10, 10.5] m spans the boundary: 0.3 m in the upper layer, 0.2 m in the lower one.
    profile = SoilProfile([sand(0, 10.3, 10e3, 20.0), sand(10.3, 30, 8e3, 30.0)])
    k = 0.5
    upper = k * 10e3 * math.tan(math.radians(20.0)) * (10.3 ** 2 - 10.0 ** 2) / 2
    sv_b = 103e3  # sigma'v0 at 10.3 m
    lower = k * math.tan(math.radians(30.0)) * (sv_b * 0.2 + 8e3 * 0.2 ** 2 / 2)
    result = srd_distribution(profile, Stevens1982(), 10.5, [10.0], [0.5], D, T,
                              faces="outside")
    assert result.shaft[0] == pytest.approx((upper + lower) * PERIMETER_OUT, rel=1e-12)
    # a single mid-point sample (10.25 m, upper layer) would be 10 % lower: the test bites
    midpoint = k * 102.5e3 * math.tan(math.radians(20.0)) * 0.5 * PERIMETER_OUT
    assert result.shaft[0] / midpoint > 1.09


def test_stevens_bounds_and_clay():
    clay = SoilLayer(5, 20, "clay", 8e3, undrained_shear_strength=50e3,
                     undrained_shear_strength_gradient=2e3, plasticity_index=0.3)
    profile = SoilProfile([sand(0, 5), clay])
    lower = srd_distribution(profile, Stevens1982(bound="lower"), 4.0, [0.0], [4.0], D, T)
    upper = srd_distribution(profile, Stevens1982(bound="upper"), 4.0, [0.0], [4.0], D, T)
    assert upper.srd_shaft == pytest.approx(lower.srd_shaft * 0.7 / 0.5, rel=1e-12)  # K ratio
    # clay toe 9 su at 15 m: su = 50 + 2 x 10 = 70 kPa -> 630 kPa on the annulus
    result = srd_distribution(profile, "stevens-1982", 15.0, [0.0], [15.0], D, T)
    assert result.srd_toe == pytest.approx(630e3 * ANNULUS, rel=1e-12)
    # the clay friction integrated by quad from the pure function (sigma'v0 = 50 + 8 (z - 5))
    def clay_f(z):
        return sm.semple_gemeinhardt_1981_clay_friction(50e3 + 2e3 * (z - 5), 50e3 + 8e3 * (z - 5),
                                                        0.3)
    sand_part = 0.5 * 10e3 * math.tan(math.radians(25.0)) * 5.0 ** 2 / 2
    expected = (sand_part + quad(clay_f, 5.0, 15.0, epsabs=0, epsrel=1e-12)[0]) * (
        PERIMETER_OUT + PERIMETER_IN)
    # smooth integrand except the alpha kink (psi = 1 is not reached) and the OCR floor kink;
    # 3 Gauss points per 0.1 m: 1e-6 is ample
    assert result.srd_shaft == pytest.approx(expected, rel=1e-6)
    with pytest.raises(ValueError, match="plasticity_index"):
        bad = SoilProfile([sand(0, 5), SoilLayer(5, 20, "clay", 8e3)])
        srd_distribution(bad, "stevens-1982", 10.0, [0.0], [10.0], D, T)


# ---------------------------------------------------------------- Alm & Hamre distributions
def alm_hamre_reference(z, tip, qt, fs, sv, is_sand, delta):
    """Unit friction of one face from the pure functions (0.5 sand, 1.0 clay)."""
    if is_sand:
        fs_i = sm.alm_hamre_2001_sand_initial_friction(qt, sv, delta)
        fs_res = sm.alm_hamre_2001_sand_residual_friction(fs_i)
        factor = 0.5
    else:
        fs_i = fs
        fs_res = sm.alm_hamre_2001_clay_residual_friction(qt, sv)
        factor = 1.0
    k = sm.alm_hamre_2001_friction_fatigue_k(qt, sv)
    return factor * sm.alm_hamre_2001_degraded_friction(fs_i, fs_res, k, z, tip)


def test_alm_hamre_distribution_against_independent_quadrature():
    # sand (gamma' 10 kN/m3, delta 29 deg) to 8 m, clay (gamma' 8 kN/m3) below; qc 5 -> 25 MPa
    # and fs 20 -> 200 kPa linear over 0-40 m.
    cpt = linear_cpt()
    profile = SoilProfile([sand(0, 8, 10e3, 29.0), SoilLayer(8, 40, "clay", 8e3)], cpt)
    tip = 17.3

    def unit(z):
        qt = 5e6 + 0.5e6 * z
        fs = 20e3 + 4.5e3 * z
        if z < 8.0:
            return alm_hamre_reference(z, tip, qt, fs, 10e3 * z, True, 29.0)
        return alm_hamre_reference(z, tip, qt, fs, 80e3 + 8e3 * (z - 8.0), False, 29.0)

    tops, lengths = segments_below_mudline(25.0, tip, dx=0.5)
    result = srd_distribution(profile, "alm-hamre-2001", tip, tops, lengths, D, T)
    per_length = (quad(unit, 0.0, 8.0, epsabs=0, epsrel=1e-12, limit=200)[0]
                  + quad(unit, 8.0, tip, epsabs=0, epsrel=1e-12, limit=200)[0])
    expected = per_length * (PERIMETER_OUT + PERIMETER_IN)
    # quad is asked for 1e-12; the Gauss pieces are 0.1 m on a smooth integrand, graded
    # geometrically at the mudline where sigma'v0^0.13 and sqrt(qt / sigma'v0) are singular
    # (measured difference 8e-10; 1e-7 leaves room for round-off on other platforms, and a
    # single ungraded first piece would already miss by 1e-6)
    assert result.srd_shaft == pytest.approx(expected, rel=1e-7)
    # per segment too: the segment containing the layer boundary at 8 m
    seg = int(np.flatnonzero((tops < 8.0) & (tops + lengths > 8.0))[0])
    seg_expected = (quad(unit, tops[seg], 8.0, epsrel=1e-12)[0]
                    + quad(unit, 8.0, tops[seg] + lengths[seg], epsrel=1e-12)[0])
    assert result.shaft[seg] == pytest.approx(seg_expected * (PERIMETER_OUT + PERIMETER_IN),
                                              rel=1e-9)
    # toe in clay at 17.3 m: 0.6 qt on the annulus
    assert result.srd_toe == pytest.approx(0.6 * (5e6 + 0.5e6 * tip) * ANNULUS, rel=1e-12)


def test_alm_hamre_sand_toe_and_options():
    cpt = linear_cpt()
    profile = SoilProfile([sand(0, 40, 10e3, 28.0)], cpt)
    tip = 10.0
    qt, sv = 10e6, 100e3  # at 10 m
    base = srd_distribution(profile, "alm-hamre-2001", tip, [0.0], [tip], D, T)
    assert base.srd_toe == pytest.approx(sm.alm_hamre_2001_sand_toe(qt, sv) * ANNULUS, rel=1e-12)
    revised = srd_distribution(profile, AlmHamre2001(sand_toe_factor=0.10), tip, [0.0], [tip],
                               D, T)
    assert revised.srd_toe == pytest.approx(base.srd_toe * 2 / 3, rel=1e-12)
    plugged = srd_distribution(profile, "alm-hamre-2001", tip, [0.0], [tip], D, T,
                               pile_mode="plugged")
    assert plugged.srd_toe == pytest.approx(base.srd_toe * D ** 2 / (D ** 2 - (D - 2 * T) ** 2))
    # plugged: outside only; coring: outside + inside with the same factor 0.5 in sand
    assert plugged.srd_shaft == pytest.approx(
        base.srd_shaft * PERIMETER_OUT / (PERIMETER_OUT + PERIMETER_IN), rel=1e-12)
    # factor 1.0 outside only is twice the default 0.5 outside only
    full = srd_distribution(profile, AlmHamre2001(sand_outside_factor=1.0), tip, [0.0], [tip],
                            D, T, faces="outside")
    assert full.srd_shaft == pytest.approx(2 * plugged.srd_shaft, rel=1e-12)
    upper = srd_distribution(profile, "alm-hamre-2001", tip, [0.0], [tip], D, T,
                             bound_multiplier=1.25)
    assert upper.srd == pytest.approx(1.25 * base.srd, rel=1e-12)
    # a toe window over a linear qt: close to the point value (the toe law is smooth)
    window = srd_distribution(profile, AlmHamre2001(toe_window=1.0), tip, [0.0], [tip], D, T)
    assert window.srd_toe == pytest.approx(base.srd_toe, rel=5e-3)


def test_friction_fatigue_lowers_the_shaft_resistance_of_a_segment_as_the_tip_passes():
    profile = SoilProfile([sand(0, 40, 10e3, 28.0)], linear_cpt())
    method = AlmHamre2001()
    shafts = []
    for tip in (5.5, 6.0, 8.0, 12.0, 20.0, 35.0):
        # the same piece of pile wall, [5, 5.5] m below the mudline, for deeper and deeper tips
        result = srd_distribution(profile, method, tip, [5.0], [0.5], D, T)
        shafts.append(result.shaft[0])
    assert np.all(np.diff(shafts) < 0.0)
    # the unit friction at 5.25 m falls from fs,i at the tip to 0.2 fs,i (the sand residual)
    # far behind it: exp(-k h) = exp(-0.15 x 395) is nil
    out_near, _ = method.unit_friction(profile, np.array([5.25]), 5.25)
    out_far, _ = method.unit_friction(profile, np.array([5.25]), 400.0)
    assert out_far[0] == pytest.approx(0.2 * out_near[0], rel=1e-12)


def test_friction_fatigue_rate_factor_against_the_closed_form_shaft_resistance():
    # Clay with qt = a z (u2 = 0), fs = c and sigma'v0 = gamma z: k = r sqrt(a / gamma) / 80
    # is constant, fs,res = 0.004 a z (1 - 0.0025 a / gamma) = b z, and the shaft resistance
    # per unit perimeter with the tip at p is, with kappa = k and h = p - z,
    #   int_0^p [b z + (c - b z) exp(-kappa h)] dz
    #   = b p^2 / 2 + c (1 - e) / kappa - b [p (1 - e) / kappa - (1 - e (1 + kappa p)) / kappa^2]
    # with e = exp(-kappa p). a = 0.2 MPa/m, gamma = 8 kN/m3: sqrt(25) / 80 = 0.0625 1/m.
    a, c, gamma, tip = 0.2e6, 60e3, 8e3, 23.0
    cpt = Cpt(np.array([0.0, 40.0]), np.array([0.0, 40.0 * a]), np.full(2, c), np.zeros(2))
    profile = SoilProfile([SoilLayer(0, 40, "clay", gamma)], cpt)
    b = 0.004 * a * (1.0 - 0.0025 * a / gamma)
    tops, lengths = segments_below_mudline(30.0, tip, dx=0.5)
    for rate in (0.5, 1.0, 3.0):
        kappa = rate * math.sqrt(a / gamma) / 80.0
        e = math.exp(-kappa * tip)
        per_length = (b * tip ** 2 / 2 + c * (1 - e) / kappa
                      - b * (tip * (1 - e) / kappa - (1 - e * (1 + kappa * tip)) / kappa ** 2))
        result = srd_distribution(profile, AlmHamre2001(fatigue_rate_factor=rate), tip, tops,
                                  lengths, D, T)
        # Gauss quadrature of a smooth integrand on 0.1 m pieces: 1e-9 is round-off room
        assert result.srd_shaft == pytest.approx(per_length * (PERIMETER_OUT + PERIMETER_IN),
                                                 rel=1e-9)
    # a faster decay leaves less friction behind the tip
    slow = srd_distribution(profile, AlmHamre2001(fatigue_rate_factor=0.5), tip, tops, lengths,
                            D, T).srd_shaft
    fast = srd_distribution(profile, AlmHamre2001(fatigue_rate_factor=3.0), tip, tops, lengths,
                            D, T).srd_shaft
    assert fast < slow
    for bad in (0.0, -0.5, float("nan")):
        with pytest.raises(ValueError, match="fatigue_rate_factor"):
            AlmHamre2001(fatigue_rate_factor=bad)


def test_alm_hamre_needs_a_cpt_reaching_the_tip():
    profile = SoilProfile([sand(0, 60)], linear_cpt(depth_end=20.0))
    with pytest.raises(ValueError, match="CPT"):
        srd_distribution(profile, "alm-hamre-2001", 25.0, [0.0], [25.0], D, T)
    with pytest.raises(ValueError, match="needs a CPT"):
        srd_distribution(SoilProfile([sand(0, 60)]), "alm-hamre-2001", 5.0, [0.0], [5.0], D, T)


def test_segments_must_not_reach_below_the_tip_and_zero_penetration():
    profile = SoilProfile([sand(0, 60)])
    with pytest.raises(ValueError, match="below the tip"):
        srd_distribution(profile, "stevens-1982", 10.0, [0.0, 10.0], [10.0, 5.0], D, T)
    none = srd_distribution(profile, "stevens-1982", 0.0, [-10.0], [10.0], D, T)
    assert none.srd == 0.0


def test_srd_versus_depth_matches_distribution():
    profile = SoilProfile([sand(0, 60)])
    shaft, toe = srd_versus_depth(profile, "stevens-1982", [5.0, 20.0], D, T)
    a = 0.5 * 10e3 * math.tan(math.radians(25.0))
    np.testing.assert_allclose(shaft, a * np.array([25.0, 400.0]) / 2
                               * (PERIMETER_OUT + PERIMETER_IN), rtol=1e-12)
    assert toe[1] == pytest.approx(4.0e6 * ANNULUS)
    assert toe_bearing_area(D, T, "plugged") == pytest.approx(math.pi)


# ---------------------------------------------------------------- user tables per tip depth
def test_tip_depth_tables_interpolate_between_tip_depths():
    # tip 10 m: uniform 20 kPa, toe 2 MPa; tip 20 m: uniform 40 kPa, toe 4 MPa
    tables = TipDepthTables([10.0, 20.0], [[[0.0, 20e3, 2e6], [10.0, 20e3, 2e6]],
                                           [[0.0, 40e3, 4e6], [20.0, 40e3, 4e6]]])
    shaft, toe = tip_table_resistance(tables.tip_depths, tables.tables, 15.0, [3.0, 12.0])
    np.testing.assert_allclose(shaft, [30e3, 30e3])  # halfway: the mean
    assert toe == pytest.approx(3e6)
    result = srd_distribution(None, tables, 15.0, [0.0], [15.0], D, T, faces="outside")
    assert result.srd_shaft == pytest.approx(30e3 * 15.0 * PERIMETER_OUT, rel=1e-12)
    assert result.srd_toe == pytest.approx(3e6 * ANNULUS, rel=1e-12)
    with pytest.raises(ValueError, match="beyond the last table"):
        srd_distribution(None, tables, 21.0, [0.0], [21.0], D, T)


def test_single_table_is_a_per_depth_table():
    # linear 0 -> 100 kPa over 0-20 m with a step at 10 m (repeated depth); toe 1 -> 5 MPa
    rows = [[0.0, 0.0, 1e6], [10.0, 50e3, 3e6], [10.0, 80e3, 3e6], [20.0, 100e3, 5e6]]
    tables = TipDepthTables([20.0], [rows])
    result = srd_distribution(None, tables, 15.0, [0.0, 7.5], [7.5, 7.5], D, T,
                              faces="outside")
    # [0, 7.5]: 0.5 x 7.5 x 37.5 kPa; [7.5, 15]: 2.5 m of 37.5 -> 50 kPa and 5 m of 80 -> 90
    first = 0.5 * 7.5 * 37.5e3
    second = 2.5 * (37.5e3 + 50e3) / 2 + 5.0 * (80e3 + 90e3) / 2
    np.testing.assert_allclose(result.shaft, np.array([first, second]) * PERIMETER_OUT,
                               rtol=1e-12)
    assert result.srd_toe == pytest.approx(4e6 * ANNULUS, rel=1e-12)


# ---------------------------------------------------------------- CPT files
def write(tmp_path, text, name="cpt.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


GOOD = """# a CPT with units in the header
depth [m],qc [MPa],fs [kPa],u2 [kPa]
0.5,2.0,10,5
1.0,4.0,20,10
1.5,6.0,30,-2
"""


def test_read_cpt_with_units_in_the_header(tmp_path):
    cpt = read_cpt_csv(write(tmp_path, GOOD))
    np.testing.assert_allclose(cpt.depth, [0.5, 1.0, 1.5])
    np.testing.assert_allclose(cpt.qc, [2e6, 4e6, 6e6])
    np.testing.assert_allclose(cpt.fs, [10e3, 20e3, 30e3])
    np.testing.assert_allclose(cpt.u2, [5e3, 10e3, -2e3])
    assert cpt.source.endswith("cpt.csv")


def test_read_cpt_with_units_as_arguments_and_sea_level_depths(tmp_path):
    text = "Depth,QC,FS\n30.5,2000,0.01\n31.0,4000,0.02\n"
    cpt = read_cpt_csv(write(tmp_path, text), qc_unit="kPa", fs_unit="MPa",
                       depth_reference="sea-level", water_depth=30.0)
    np.testing.assert_allclose(cpt.depth, [0.5, 1.0])
    np.testing.assert_allclose(cpt.qc, [2e6, 4e6])
    np.testing.assert_allclose(cpt.fs, [10e3, 20e3])
    np.testing.assert_array_equal(cpt.u2, [0.0, 0.0])  # no u2 column: qt = qc


BAD_FILES = [
    # (content, options, column named in the error, words of the rule)
    ("depth [m],qc [MPa],u2 [kPa]\n1,2,3\n2,3,4\n", {}, "fs", "missing"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n0.5,3,4\n", {}, "depth [m]", "increase"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n1,3,4\n", {}, "depth [m]", "repeats"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,-3,4\n", {}, "qc [MPa]", "negative"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,,4\n", {}, "qc [MPa]", "missing"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,3,nan\n", {}, "fs [kPa]", "NaN"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,abc,4\n", {}, "qc [MPa]", "not a number"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2000,30\n2,3500,40\n", {}, "qc [MPa]", "look like kPa"),
    ("depth [m],qc,fs [kPa]\n1,2000,30\n2,3500,40\n", {}, "qc", "look like kPa"),
    ("depth [m],qc [MPa],fs\n1,2,3\n2,3,4\n", {}, "fs", "unit not stated"),
    ("depth [m],qc [MPa],fs [psi]\n1,2,3\n2,3,4\n", {}, "fs [psi]", "unknown unit"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,3,4\n", {"qc_unit": "kPa"}, "qc [MPa]",
     "header states"),
    ("depth [m],qc [MPa],fs [kPa]\n10,2,3\n12,3,4\n",
     {"depth_reference": "sea-level", "water_depth": 11.0}, "depth [m]", "above the mudline"),
    ("depth [m],qc [MPa],fs [kPa]\n1,2,3\n2,3,4\n", {"depth_reference": "sea-level"},
     "water_depth", "water depth"),
]


@pytest.mark.parametrize("content, options, column, rule", BAD_FILES)
def test_bad_cpt_file_gives_one_input_error_naming_file_and_column(tmp_path, content, options,
                                                                   column, rule):
    path = write(tmp_path, content)
    with pytest.raises(InputError) as error:
        read_cpt_csv(path, **options)
    assert error.value.source == str(path)
    assert error.value.key == column
    assert rule in error.value.rule
    message = str(error.value)
    assert "\n" not in message and str(path) in message and column in message


def test_missing_cpt_file(tmp_path):
    path = tmp_path / "nowhere.csv"
    with pytest.raises(InputError, match="file not found") as error:
        read_cpt_csv(path)
    assert error.value.source == str(path)


def test_cleaning_options(tmp_path):
    text = ("z [m],qc [MPa],fs [MPa],u2 [MPa],push [-]\n"
            "0.0,0.1,,,1\n0.2,0.5,-0.001,,1\n0.4,5,0.02,0.01,1\n0.6,6,,0.03,1\n0.8,7,0.04,,1\n"
            "0.8,9,0.06,0.05,1\n1.0,0.2,0.01,0.0,2\n1.4,8,0.05,0.02,2\n")
    path = write(tmp_path, text)
    cpt = read_cpt_csv(path, push_column="push", skip_push_start=0.3, missing="interpolate",
                       duplicate_depths="average")
    np.testing.assert_allclose(cpt.depth, [0.4, 0.6, 0.8, 1.4])
    np.testing.assert_allclose(cpt.qc, np.array([5, 6, 8, 8]) * 1e6)  # 0.8 m: mean of 7, 9
    np.testing.assert_allclose(cpt.fs, np.array([0.02, 0.035, 0.05, 0.05]) * 1e6)
    np.testing.assert_allclose(cpt.u2, np.array([0.01, 0.03, 0.05, 0.02]) * 1e6)
    dropped = read_cpt_csv(path, push_column="push", skip_push_start=0.3, missing="drop",
                           duplicate_depths="average")
    np.testing.assert_allclose(dropped.depth, [0.4, 0.8, 1.4])
    with pytest.raises(InputError, match="negative") as error:
        read_cpt_csv(path, missing="interpolate", duplicate_depths="average")
    assert error.value.key == "fs [MPa]"
    zeroed = read_cpt_csv(path, missing="interpolate", duplicate_depths="average",
                          negative_fs="zero")
    assert zeroed.fs[1] == 0.0


# ---------------------------------------------------------------- ISFOG 2020 CPTs
ISFOG_OPTIONS = dict(push_column="push (derived)", skip_push_start=0.3, missing="interpolate",
                     duplicate_depths="average", negative_fs="zero")


@needs_isfog
@pytest.mark.parametrize("group, location", [("AA-AB-AC", "AA"), ("CD-CE-CF", "CD"),
                                             ("CJ-CK-CL", "CJ")])
def test_isfog_full_resolution_cpts_read(group, location):
    path = ISFOG / f"cpt_fullres_{group}.csv"
    cpt = read_cpt_csv(path, **ISFOG_OPTIONS)
    assert cpt.depth[0] >= 0.3 and cpt.depth[-1] > 39.0
    assert np.all(np.diff(cpt.depth) > 0.0)
    # the organisers' 0.5 m series of the same CPT (processed independently): the depth-mean
    # qc agrees within 5 % (measured 0.0 %, 2.8 % and 3.9 %; the 0.5 m series is a 1 m
    # average, so peaks and gaps weigh differently)
    half = read_cpt_csv(ISFOG / "prediction_piles_0p5m.csv", rows_where={"location_id": location})

    def mean(c):
        return np.trapezoid(c.qc, c.depth) / (c.depth[-1] - c.depth[0])
    assert mean(cpt) == pytest.approx(mean(half), rel=0.05)


@needs_isfog
def test_isfog_half_metre_cpts_match_the_pile_summaries():
    # every prediction pile: the CPT max depth and qc max of prediction_piles.csv (printed to
    # 0.01 MPa, hence the tolerance)
    with open(ISFOG / "prediction_piles.csv", newline="") as handle:
        piles = list(csv.DictReader(handle))
    assert len(piles) == 9
    for pile in piles:
        cpt = read_cpt_csv(ISFOG / "prediction_piles_0p5m.csv",
                           rows_where={"location_id": pile["location_id"]})
        assert cpt.depth[-1] == pytest.approx(float(pile["CPT max depth [m]"]))
        assert cpt.qc.max() / 1e6 == pytest.approx(float(pile["qc max [MPa]"]), abs=0.0051)


@needs_isfog
def test_alm_hamre_srd_on_an_isfog_cpt_is_sane():
    cpt = read_cpt_csv(ISFOG / "cpt_fullres_AA-AB-AC.csv", **ISFOG_OPTIONS)
    profile = SoilProfile([sand(0.0, 40.0, 10e3, 29.0)], cpt)
    tips = np.arange(1.0, 34.5, 1.0)
    shaft, toe = srd_versus_depth(profile, "alm-hamre-2001", tips, 2.48, 0.055)
    assert np.all(np.isfinite(shaft)) and np.all(toe > 0.0)
    assert np.all(shaft > 0.0)
    # friction fatigue: the total shaft resistance may fall when the tip enters a weaker
    # layer, but over the drive it grows (fresh friction near the tip)
    assert shaft[-1] > 5 * shaft[4]
    # order of magnitude of a 2.48 m pin pile at 34 m in dense North Sea sand: tens of MN
    assert 10e6 < shaft[-1] + toe[-1] < 200e6


def test_alm_hamre_toe_from_qt_averaged_about_the_tip():
    # ICP-05 / UWA-05: the sand toe formula on qt averaged over the tip +- h (u2 = 0: qt = qc)
    # qc 10 MPa to 4 m, rising to 20 MPa at 6 m; tip 5 m in sand, h = 3 m: qt,avg = 15 MPa
    # (tests/test_srd_methods.py, by hand), sigma'v0 = 10 kN/m^3 x 5 m = 50 kPa
    cpt = Cpt(np.array([0.0, 4.0, 6.0, 40.0]), np.array([10e6, 10e6, 20e6, 20e6]),
              np.full(4, 50e3), np.zeros(4))
    profile = SoilProfile([sand(0, 40, 10e3, 28.0)], cpt)
    method = AlmHamre2001(sand_toe_factor=0.10, toe_qt_half_window=3.0)
    expected = 0.10 * 15e6 * (15e6 / 50e3) ** 0.2
    assert method.unit_toe(profile, 5.0) == pytest.approx(expected, rel=1e-12)
    # the point toe at 5 m has the same qt here (halfway up the ramp): only the window differs
    assert AlmHamre2001(sand_toe_factor=0.10).unit_toe(profile, 5.0) == pytest.approx(
        expected, rel=1e-12)
    # at 3 m the window [0, 6] m reaches the dense layer: qt,avg = (10 x 4 + 15 x 2) / 6
    qt_avg = (10e6 * 4.0 + 15e6 * 2.0) / 6.0
    assert method.unit_toe(profile, 3.0) == pytest.approx(
        0.10 * qt_avg * (qt_avg / 30e3) ** 0.2, rel=1e-12)
    # a tip in clay keeps the clay toe at its own qt (0.6 qt)
    clay = SoilLayer(5.0, 40.0, "clay", 8e3, undrained_shear_strength=100e3)
    layered = SoilProfile([sand(0, 5, 10e3, 28.0), clay], cpt)
    assert method.unit_toe(layered, 7.0) == pytest.approx(0.6 * 20e6, rel=1e-12)
    # the two averages exclude each other
    with pytest.raises(ValueError, match="exclude"):
        AlmHamre2001(toe_window=1.0, toe_qt_half_window=3.0)
    with pytest.raises(ValueError):
        AlmHamre2001(toe_qt_half_window=-1.0)
