"""Soil classification from a CPT (Robertson's Ic) and the ISFOG 2020 back-analysis benchmark
(benchmarks/isfog_backanalysis.py) on two calibration piles with a coarse setting."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import replace

import numpy as np
import pytest

from anvilwave.pile.soil.cpt_classification import (
    merge_thin_layers,
    robertson_1990_normalised_cone_resistance,
    robertson_1990_normalised_friction_ratio,
    robertson_1990_soil_behaviour_type_index,
    robertson_2009_is_sand,
    robertson_2009_soil_behaviour_type_index,
    robertson_2009_stress_exponent,
    robertson_wride_1998_soil_behaviour_type_index,
    soil_layers_from_cpt,
)
from anvilwave.pile.soil.profile import Cpt

from .conftest import SHARED
from .doc_tables import benchmark, doc_data

ISFOG = SHARED / "reference" / "isfog2020"


# ---------------------------------------------------------------- Robertson, by hand
def test_robertson_1990_normalisation_and_ic_by_hand():
    # qt 10 MPa, fs 50 kPa, sigma_v0 200 kPa, sigma'v0 100 kPa:
    # Q = 9800 / 100 = 98; F = 100 x 50 / 9800 = 0.510204 %;
    # Ic = sqrt((3.47 - 1.991226)^2 + (-0.292256 + 1.22)^2) = sqrt(2.186772 + 0.860709)
    #    = 1.745704 (sand-like)
    q = robertson_1990_normalised_cone_resistance(10e6, 200e3, 100e3)
    f = robertson_1990_normalised_friction_ratio(50e3, 10e6, 200e3)
    assert q == pytest.approx(98.0, rel=1e-12)
    assert f == pytest.approx(0.5102041, rel=1e-6)
    assert robertson_wride_1998_soil_behaviour_type_index(q, f) == pytest.approx(1.745704,
                                                                                 abs=1e-6)
    assert robertson_1990_soil_behaviour_type_index(10e6, 50e3, 200e3, 100e3) == \
        pytest.approx(1.745704, abs=1e-6)
    # sigma'v0 = pa: Qtn = Q for any n, so the 2009 index is the same; n = 0.381 Ic - 0.1
    ic, n = robertson_2009_soil_behaviour_type_index(10e6, 50e3, 200e3, 100e3)
    assert ic == pytest.approx(1.745704, abs=1e-6)
    assert n == pytest.approx(0.381 * 1.745704 + 0.05 - 0.15, abs=1e-6)
    assert robertson_2009_stress_exponent(4.0, 300e3) == 1.0  # n is capped at 1


def test_robertson_2009_iteration_by_hand():
    # qt 10 MPa, fs 50 kPa, sigma_v0 400 kPa, sigma'v0 200 kPa: F = 0.520833 %; the fixed
    # point of n = 0.381 Ic + 0.05 x 2 - 0.15 with Qtn = 96 x 0.5^n, iterated by hand (plain
    # arithmetic, 200 steps): Qtn = 59.5981, Ic = 1.936399, n = 0.687768. Robertson (1990)
    # (n = 1): Q = 48, Ic = 2.019174.
    ic, n = robertson_2009_soil_behaviour_type_index(10e6, 50e3, 400e3, 200e3)
    assert ic == pytest.approx(1.936399, abs=1e-5)
    assert n == pytest.approx(0.687768, abs=1e-5)
    assert robertson_1990_soil_behaviour_type_index(10e6, 50e3, 400e3, 200e3) == \
        pytest.approx(2.019174, abs=1e-6)
    # a soft clay: qt 1.5 MPa, fs 50 kPa, sigma_v0 190 kPa, sigma'v0 90 kPa -> n = 1 (capped),
    # Qtn = 1310 / 90 = 14.5556, F = 3.816794 %, Ic = 2.927155
    ic, n = robertson_2009_soil_behaviour_type_index(1.5e6, 50e3, 190e3, 90e3)
    assert n == 1.0
    assert ic == pytest.approx(2.927155, abs=1e-6)
    assert list(robertson_2009_is_sand([1.936399, 2.927155, 2.6])) == [True, False, False]


def test_chart_limits_keep_ic_finite():
    # zero sleeve friction and qt below sigma_v0 (next to the mudline) stay on the chart
    ic = robertson_wride_1998_soil_behaviour_type_index([0.0, -5.0, 5000.0], [0.0, 50.0, 0.0])
    assert np.all(np.isfinite(ic))
    # Q = 1000 (clipped from 5000), F = 0.1 %: sqrt(0.47^2 + 0.22^2)
    assert ic[2] == pytest.approx(math.hypot(0.47, 0.22), abs=1e-12)


def test_merge_thin_layers():
    sand = np.array([True, True, False, True, True, False, False, False])
    tops = np.arange(8) * 0.5
    bottoms = tops + 0.5
    # the single clay reading (0.5 m) joins the sand around it; the 1.5 m clay stays
    merged = merge_thin_layers(sand, tops, bottoms, 1.0)
    assert list(merged) == [True] * 5 + [False] * 3
    assert list(merge_thin_layers(sand, tops, bottoms, 0.0)) == list(sand)


def test_soil_layers_from_a_synthetic_cpt():
    # dense sand (qc 30 MPa, fs 0.2 MPa) over a clay (qc 1.5 MPa, fs 0.06 MPa) over sand
    z = np.arange(0.5, 12.01, 0.5)
    clay = (z > 4.2) & (z < 7.8)
    qc = np.where(clay, 1.5e6, 30e6)
    fs = np.where(clay, 0.06e6, 0.2e6)
    cpt = Cpt(z, qc, fs, np.zeros_like(z))
    layers, ic = soil_layers_from_cpt(cpt, sand_unit_weight=10e3, clay_unit_weight=9e3,
                                      sand_interface_friction_angle=29.0)
    assert [layer.soil_type for layer in layers] == ["sand", "clay", "sand"]
    assert [(layer.top, layer.bottom) for layer in layers] == [(0.0, 4.25), (4.25, 7.75),
                                                               (7.75, 12.0)]
    assert layers[0].submerged_unit_weight == 10e3 and layers[1].submerged_unit_weight == 9e3
    assert layers[0].interface_friction_angle == 29.0
    assert layers[1].interface_friction_angle is None
    assert np.all(ic[clay] > 2.6) and np.all(ic[~clay] < 2.6)


# ---------------------------------------------------------------- the benchmark
def _benchmark():
    return benchmark("isfog_backanalysis")


def test_benchmark_without_the_records_exits_cleanly(tmp_path, capsys):
    out = tmp_path / "out"
    assert _benchmark().main(["--data", str(tmp_path / "absent"), "--out", str(out)]) == 0
    assert "not found" in capsys.readouterr().out
    assert not out.exists()


def _csv(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


@pytest.mark.skipif(not (ISFOG / "calibration_piles_0p5m.csv").exists(),
                    reason=f"the ISFOG 2020 records are not in {ISFOG} (they are read from "
                           "../shared beside the repository, never copied into it)")
def test_backanalysis_on_two_calibration_piles(tmp_path, monkeypatch):
    out = tmp_path / "isfog"
    monkeypatch.setattr(benchmark("doc_data"), "DOC_DATA", tmp_path / "data")
    bench = _benchmark()
    code = bench.main(["--data", str(ISFOG), "--out", str(out), "--piles", "AD,AE",
                       "--prediction-piles", "AA", "--energies", "3",
                       "--multipliers", "0.7,1.0", "--segment-length", "1.0",
                       "--duration", "0.12", "--workers", "1", "--docs"])
    assert code == 0
    docs = json.loads((tmp_path / "data" / "isfog_calibration.json").read_text())
    assert docs["values"] == json.loads((out / "calibration_summary.json").read_text())
    assert docs["tables"]["fits"]["rows"][0][4] == docs["values"]["rmse [blows/m]"]
    assert docs["substitutions"]["blows"][0] == 3 * 2 * 47
    fit = _csv(out / "calibration_fit.csv")
    assert [r["location_id"] for r in fit] == ["AD", "AE", "overall"]
    assert {"rmse [blows/m]", "bias [blows/m]", "points [-]"} <= set(fit[0])
    summary = json.loads((out / "calibration_summary.json").read_text())
    for key in ("rmse [blows/m]", "bias [blows/m]", "E_ref [J]", "srd_multiplier [-]"):
        assert math.isfinite(summary[key]), key
    assert summary["E_ref [J]"] > 0 and 0.7 <= summary["srd_multiplier [-]"] <= 1.0
    assert summary["rmse [blows/m]"] == pytest.approx(float(fit[-1]["rmse [blows/m]"]),
                                                      rel=1e-5)
    assert "fit_energy_only" in summary and "fit_energy_and_multiplier" in summary
    points = _csv(out / "calibration_blowcount.csv")
    assert len(points) == int(fit[-1]["points [-]"]) == 47  # AD: 3-26 m, AE: 4-26 m
    prediction = _csv(out / "prediction_piles_blowcount.csv")
    assert list(prediction[0]) == ["location_id", "z [m]", "blowcount [blows/m]"]
    z = [float(r["z [m]"]) for r in prediction]
    assert {r["location_id"] for r in prediction} == {"AA"}
    assert z == list(np.arange(z[0], z[-1] + 1.0))  # every whole metre driven
    assert all(math.isfinite(float(r["blowcount [blows/m]"])) for r in prediction)
    for name in ("calibration_profiles.png", "calibration_fit.png", "prediction_piles.png"):
        assert (out / name).stat().st_size > 0


@pytest.mark.skipif(not (ISFOG / "calibration_piles_0p5m.csv").exists(),
                    reason=f"the ISFOG 2020 records are not in {ISFOG} (they are read from "
                           "../shared beside the repository, never copied into it)")
def test_stepwise_backanalysis_on_two_foundations(tmp_path, monkeypatch):
    out = tmp_path / "isfog"
    monkeypatch.setattr(benchmark("doc_data"), "DOC_DATA", tmp_path / "data")
    bench = _benchmark()
    argv = ["--data", str(ISFOG), "--out", str(out), "--piles", "AD,AI",
            "--prediction-piles", "AA", "--energies", "2", "--multipliers", "0.5,1.0",
            "--segment-length", "1.0", "--duration", "0.12", "--workers", "1",
            "--cross-validate"]
    assert bench.main([*argv, "--docs"]) == 0
    summary = json.loads((out / "isfog_backanalysis.json").read_text())
    docs = json.loads((tmp_path / "data" / "isfog_backanalysis.json").read_text())
    assert docs["values"] == summary
    assert docs["command"] == "python benchmarks/isfog_backanalysis.py " + " ".join(
        [*argv, "--docs"])
    final = [row for row in docs["tables"]["steps"]["rows"]
             if row[0].split(":")[0] == bench.FINAL_STEP]
    assert final[0][1] == summary["cv_rmse [blows/m]"]
    # --docs-from writes the same file from the summary, without running
    first = (tmp_path / "data" / "isfog_backanalysis.json").read_text()
    (tmp_path / "data" / "isfog_backanalysis.json").unlink()
    assert bench.main([*argv, "--docs-from", str(out / "isfog_backanalysis.json")]) == 0
    assert (tmp_path / "data" / "isfog_backanalysis.json").read_text() == first
    steps = summary["steps"]
    assert [s["step"].split(":")[0] for s in steps] == list("ABCDEFGHIJKLMNO")
    # one baseline for every step, computed on the same records
    assert len({(s["rmse_baseline [blows/m]"], s["points [-]"]) for s in steps}) == 1
    assert all(math.isfinite(s["rmse [blows/m]"]) for s in steps)
    final = "ABCDEFGHIJKLMNO".index(bench.FINAL_STEP)
    assert summary["cv_rmse [blows/m]"] == steps[final]["rmse [blows/m]"]
    assert summary["cv_folds [-]"] == 2
    # the energy-capped steps keep every fold's largest blow within the rating: E_ref at most
    # 800 kJ over the largest energy factor x setting of the fold's training pile
    cal = bench.calibration_piles(ISFOG, ["AD", "AI"])
    caps = [800e3 / float(np.max(bench.enthru_factor([p]) * p.energy)) for p in cal]
    for step in (steps[7], steps[8], steps[9], steps[11], steps[12]):  # H-J, L, M: S-800
        assert step["E_ref [J] folds max"] <= max(caps) * (1 + 1e-9)
    # K: every fold chose one of the two classes, its E_ref within that class's rating
    k = steps[10]
    assert k["folds with ihc_s800 [-]"] + k["folds with ihc_s1800 [-]"] == 2
    assert k["E_ref [J] folds max"] <= max(caps) * 1800e3 / 800e3 * (1 + 1e-9)
    assert summary["largest_blow_energy [J]"] <= summary["hammer_rated_energy [J]"] * (1 + 1e-6)
    # the fatigue tables at the paper's rate are the grid's own SRD (the same computation)
    assert summary["fatigue_table_vs_grid_max_rel [-]"] < 1e-9
    records = _csv(out / "cross_validation_records.csv")
    assert len(records) == 24 + 23  # AD: 3-26 m, AI: 3-25 m
    piles = _csv(out / "cross_validation_piles.csv")
    assert [r["location_id"] for r in piles] == ["AD", "AI"]
    # per pile, the baseline's and each step's scores over the pile's scored records (those
    # with a baseline: AD's 26 m has none, AI was driven to 25 m)
    for r in piles:
        mine = [x for x in records if x["location_id"] == r["location_id"]
                and math.isfinite(float(x["naive [blows/m]"]))]
        assert int(r["points [-]"]) == len(mine) == {"AD": 23, "AI": 23}[r["location_id"]]
        err = [float(x["I"]) - float(x["measured [blows/m]"]) for x in mine]
        # the CSV files keep 6 significant digits: each count (< 1000 blows/m, the refusal
        # count) within 5e-4 of its value, and so the scores within 1e-3
        assert float(r["I rmse [blows/m]"]) == pytest.approx(
            math.sqrt(np.mean(np.square(err))), abs=1e-3)
        assert float(r["I bias [blows/m]"]) == pytest.approx(np.mean(err), abs=1e-3)
    prediction = _csv(out / "prediction_piles_blowcount.csv")
    z = [float(r["z [m]"]) for r in prediction]
    assert z == list(np.arange(z[0], z[-1] + 1.0))
    assert all(float(r["blowcount [blows/m]"]) >= 0.0 for r in prediction)
    assert all(float(r["installation [blows/m]"]) >= 0.0 for r in prediction)
    # N, the installations: every blow struck is counted in the metre of its tip (the record
    # depths' windows [z - 0.5, z + 0.5) tile the driven span), no pile refused here
    n = steps[13]
    counts = [float(x["N"]) for x in records]
    assert all(c == int(c) and c < bench.REFUSAL_COUNT for c in counts)
    assert sum(counts) == n["blows [-]"] == summary["installation_cv"]["blows [-]"] > 0
    # the blow after blow and the per-depth model, the same fits: the residual stress moves
    # the counts, it does not make another pile of them (their ratio within a factor 2 over
    # 5-95 % of the records)
    ratio = summary["installation_cv"]["installation_over_per_depth_5_50_95 [-]"]
    assert 0.5 < ratio[0] <= ratio[1] <= ratio[2] < 2.0
    # O: every fold chose its weight among the step's; the final step's departures are split
    # into the soil's and the energy's parts
    o = steps[14]
    weights = next(st for _, st in bench.PREDICTIVE_STEPS if st.name.startswith("O")
                   ).site_weights
    assert {o["site_weight [-] folds min"], o["site_weight [-] folds max"]} <= set(weights)
    parts = summary["departures_final"]
    assert all(math.isfinite(parts[k]) for k in (
        "soil_part_sd [blows/m]", "energy_part_sd [blows/m]", "soil_energy_correlation [-]"))


def _synthetic_piles(bench):
    """Three foundations of two piles, driven at 1-3 m (foundation C only to 2 m), measured
    blow counts by hand."""
    measured = {"A1": [10, 20, 30], "A2": [12, 22, 32], "B1": [20, 40, 60],
                "B2": [22, 42, 62], "C1": [5, 6], "C2": [7, 8]}
    piles = []
    for name, counts in measured.items():
        z = np.arange(1.0, len(counts) + 1.0)
        piles.append(bench.PileRecord(name, name[0], 0.05, 3.0, z, np.ones(z.size),
                                      np.array(counts, float), "", {}))
    return piles


def test_naive_baseline_is_the_mean_of_the_other_foundations_at_each_depth():
    bench = _benchmark()
    piles = _synthetic_piles(bench)
    base = bench.naive_baseline([p for p in piles if p.cpt_group != "A"],
                                [p for p in piles if p.cpt_group == "A"])
    # at 1 m: (20 + 22 + 5 + 7) / 4; at 2 m: (40 + 42 + 6 + 8) / 4; at 3 m only B: 61
    np.testing.assert_allclose(base[0], [13.5, 24.0, 61.0])
    c = bench.naive_baseline([p for p in piles if p.cpt_group == "C"],
                             [p for p in piles if p.cpt_group == "A"])
    assert math.isnan(c[0][2])  # no other foundation driven to 3 m


def test_stepwise_cross_validation_scores_a_perfect_model_against_the_baseline():
    """A surface whose blow counts are the measured ones at every grid node: each fold
    predicts its held-out piles exactly (RMSE 0), while the baseline's error follows by
    hand; the stacked step then keeps the physics (weight 1)."""
    bench = _benchmark()
    piles = _synthetic_piles(bench)
    measured = np.concatenate([p.measured for p in piles])
    n = measured.size
    counts = np.broadcast_to(measured[:, None, None], (n, 2, 2)).copy()
    surface = bench.ResponseSurface([1e5, 1e6], [0.5, 1.0], counts, np.zeros(n),
                                    np.ones(n), np.zeros(n), np.zeros(n))
    steps = [bench.Step("log"), bench.Step("classes", classes=bench.CLASSES),
             bench.Step("stacked", stacked=True)]
    rows, res = bench.stepwise_cross_validation(piles, surface, np.ones(n), steps)
    assert [r["step"] for r in rows] == ["log", "classes", "stacked"]
    for r in rows:
        assert r["rmse [blows/m]"] == pytest.approx(0.0, abs=1e-9)
        assert r["points [-]"] == n and r["folds [-]"] == 3
    assert rows[2]["stacking_weight [-] folds min"] == pytest.approx(1.0)
    # the baseline per record: A at 1-3 m (13.5, 24, 61), B (8.5, 14, 31), C (16, 31)
    base = np.array([13.5, 24.0, 61.0] * 2 + [(10 + 12 + 5 + 7) / 4, (20 + 22 + 6 + 8) / 4,
                                               31.0] * 2 + [16.0, 31.0] * 2)
    np.testing.assert_allclose(res["baseline"], base)
    expected = math.sqrt(np.mean((base - measured) ** 2))
    assert rows[0]["rmse_baseline [blows/m]"] == pytest.approx(expected)
    assert rows[0]["bias_baseline [blows/m]"] == pytest.approx(np.mean(base - measured))


def test_simple_kriging_one_sample_by_hand():
    bench = _benchmark()
    # mean 10, reading 20: the estimate moves from the mean by the correlation's share
    assert bench.simple_kriging_one_sample(20.0, 10.0, 0.3) == pytest.approx(13.0)
    assert bench.simple_kriging_one_sample(20.0, 10.0, 1.0) == 20.0  # at the sample
    assert bench.simple_kriging_one_sample(20.0, 10.0, 0.0) == 10.0  # no correlation
    with pytest.raises(ValueError, match="correlation"):
        bench.simple_kriging_one_sample(20.0, 10.0, 1.5)


def test_site_estimate_by_hand():
    """At 1 m foundation A's piles read 10 and 12 (mean 11), B's one pile 21: the site's
    mean is 16, and with the correlation 0.5 A's mean goes to 13.5 and B's to 18.5, each
    pile keeping its difference from its foundation's mean; at 2 m A alone: unchanged."""
    bench = _benchmark()
    values = np.array([10.0, 12.0, 21.0, 7.0])
    group = np.array(["A", "A", "B", "A"])
    depth = np.array([1.0, 1.0, 1.0, 2.0])
    np.testing.assert_allclose(bench.site_estimate(values, group, depth, 0.5),
                               [12.5, 14.5, 18.5, 7.0])
    np.testing.assert_allclose(bench.site_estimate(values, group, depth, 1.0), values)
    # columns (the fatigue tables) each on their own
    two = np.stack([values, 2.0 * values], axis=1)
    np.testing.assert_allclose(bench.site_estimate(two, group, depth, 0.0),
                               [[15.0, 30.0], [17.0, 34.0], [16.0, 32.0], [7.0, 14.0]])


def test_site_weight_step_finds_the_weight_the_records_were_made_with():
    """Records made by a known law at the SRD kriged with the weight 0.5 towards the site's
    mean: the step that chooses the weight per fold among 0.25, 0.5 and 1 takes 0.5 in every
    fold and predicts the held-out foundations to the interpolation's error, and the weight
    1 is the surface unchanged."""
    bench = _benchmark()
    piles = _synthetic_piles(bench)
    n = sum(p.depths.size for p in piles)
    group = np.concatenate([[p.cpt_group] * p.depths.size for p in piles])
    depth = np.concatenate([p.depths for p in piles])
    level = {"A": 1.0, "B": 3.0, "C": 0.4}  # the foundations' CPTs differ in level
    total = np.array([level[g] * (1.0 + 0.3 * z) for g, z in zip(group, depth, strict=True)])
    rng = np.random.default_rng(3)
    share = rng.dirichlet([2.0, 2.0, 2.0], size=n) * total[:, None] * 1e6
    energies = np.geomspace(100e3, 3200e3, 81)
    multipliers = np.geomspace(0.05, 20.0, 121)
    le = np.log(energies / 500e3)
    lc = 3.0 + 2.0 * np.log(multipliers)[:, None] - le[None, :] - 0.5 * le[None, :] ** 2
    counts = np.broadcast_to(np.exp(lc), (n, *lc.shape)).copy()
    surface = bench.ResponseSurface(energies, multipliers, counts, np.zeros(n),
                                    share[:, 0], share[:, 1], share[:, 2])
    np.testing.assert_array_equal(surface.with_site_weight(1.0, group, depth)(600e3, 0.7),
                                  surface(600e3, 0.7))
    truth = surface.with_site_weight(0.5, group, depth)(600e3, 0.7)
    piles = [replace(p, measured=v) for p, v in zip(
        piles, np.split(truth, np.cumsum([p.depths.size for p in piles])[:-1]), strict=True)]
    step = bench.Step("O", site_weights=(0.25, 0.5, 1.0))
    rows, res = bench.stepwise_cross_validation(piles, surface, np.ones(n), [step])
    chosen = [fit["site_weight [-]"] for _, fit in res["fits"]["O"].values()]
    assert chosen == [0.5, 0.5, 0.5]
    # the held-out counts to 1 % (the bilinear interpolation of the quadratic in log E on 81
    # nodes errs by < 1e-3 in log N; the extrapolated E_ref of a two-foundation fit adds
    # little: a tolerance of 1 %)
    scored = res["scored"]
    np.testing.assert_allclose(res["predictions"]["O"][scored], truth[scored], rtol=1e-2)
    assert rows[0]["site_weight [-] folds median"] == 0.5


def test_departure_parts_by_hand():
    bench = _benchmark()

    def dep(sd, corr=0.0):
        return {"model_sd [blows/m]": sd, "correlation [-]": corr}

    # 3 and 4 adding up to an RMS of 5: uncorrelated; to 1: opposed (-1); to 7: together
    for whole, expected in ((5.0, 0.0), (1.0, -1.0), (7.0, 1.0)):
        parts = bench.departure_parts(dep(whole), dep(3.0, 0.4), dep(4.0, -0.1))
        assert parts["soil_energy_correlation [-]"] == pytest.approx(expected)
    assert parts["soil_part_sd [blows/m]"] == 3.0
    assert parts["soil_part_correlation [-]"] == 0.4
    assert parts["energy_part_correlation [-]"] == -0.1


# ---------------------------------------------------------------- the regularised fit
def _synthetic_surface(bench, n=60, seed=1):
    """A known blow-count law on a grid: log N = 3 + 2 log m - log(E/E0) - 0.5 log(E/E0)^2
    (E0 = 500 kJ; the curvature in log E separates E_ref from the common multiplier), m the
    record's effective multiplier; records with random sand / clay / toe SRD and energy
    factors 0.3-1 and settings 0.2-0.9 (the normalised energies of a record set)."""
    rng = np.random.default_rng(seed)
    energies = np.geomspace(100e3, 3200e3, 81)
    multipliers = np.geomspace(0.1, 2.0, 9)
    share = rng.dirichlet([1.0, 1.0, 1.0], size=n) * 5e6
    factor = rng.uniform(0.3, 1.0, n)
    setting = rng.uniform(0.2, 0.9, n)
    le = np.log(energies / 500e3)
    lc = (3.0 + 2.0 * np.log(multipliers)[:, None] - le[None, :] - 0.5 * le[None, :] ** 2)
    counts = np.broadcast_to(np.exp(lc), (n, *lc.shape)).copy()
    surface = bench.ResponseSurface(energies, multipliers, counts, np.zeros(n),
                                    share[:, 0], share[:, 1], share[:, 2], factor, setting)
    return surface


def test_regularised_fit_recovers_known_parameters():
    bench = _benchmark()
    surface = _synthetic_surface(bench)
    truth = (600e3, 0.6, 0.3, 0.9)
    measured = surface(*truth)
    # a vanishing prior: the exact values come back (the linear interpolation of the
    # quadratic in log E on 81 nodes errs by < 1e-3 in log N: tolerance 1 %)
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0)
    got = [fitted[k] for k in ("E_ref [J]", "srd_sand [-]", "srd_clay [-]", "srd_toe [-]")]
    np.testing.assert_allclose(got, truth, rtol=1e-2)
    np.testing.assert_allclose(bench.predict_with(surface, fitted), measured, rtol=1e-2)
    # the blows/m misfit finds them too
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "blows", prior_sd=100.0)
    got = [fitted[k] for k in ("E_ref [J]", "srd_sand [-]", "srd_clay [-]", "srd_toe [-]")]
    np.testing.assert_allclose(got, truth, rtol=1e-2)


def test_regularised_fit_recovers_the_energy_law_exponent():
    bench = _benchmark()
    surface = _synthetic_surface(bench)
    measured = surface(600e3, 0.6, 0.3, 0.9, 0.8)
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                   n_eff=1e6, exponent=True)
    assert fitted["energy_exponent [-]"] == pytest.approx(0.8, abs=0.01)
    assert fitted["E_ref [J]"] == pytest.approx(600e3, rel=2e-2)


def _fatigue_surface(bench, n=60, seed=2):
    """The synthetic surface with fatigue tables: each record's sand and clay shaft SRD at
    the rate factor r is its value at r = 1 times (1 + a) / (1 + a r^0.7), a per record
    (0.2-2: how much of its shaft lies far behind the tip)."""
    surface = _synthetic_surface(bench, n, seed)
    rng = np.random.default_rng(seed + 10)
    rates = np.asarray(bench.FATIGUE_RATES)
    a = rng.uniform(0.2, 2.0, n)
    shape = (1.0 + a[:, None]) / (1.0 + a[:, None] * rates[None, :] ** 0.7)
    return bench.ResponseSurface(
        np.exp(surface.le), np.exp(surface.lm), np.exp(surface.lc), surface.run, surface.sand,
        surface.clay, surface.toe, surface.energy_factor, surface.setting, rates,
        surface.sand[:, None] * shape, surface.clay[:, None] * shape)


def test_regularised_fit_recovers_the_fatigue_rate_factor():
    bench = _benchmark()
    surface = _fatigue_surface(bench)
    # at the grid's own rate (r = 1 is a table node) the tables change nothing
    np.testing.assert_allclose(surface(600e3, 0.6, 0.3, 0.9, rate=1.0),
                               surface(600e3, 0.6, 0.3, 0.9), rtol=1e-12)
    # a node of the table: the SRD is the tabulated one, so the fit can recover r exactly
    # (up to the 1 % of the interpolation in log E, test above)
    measured = surface(600e3, 0.6, 0.3, 0.9, rate=0.25)
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                   n_eff=1e6, fatigue=True)
    assert fitted["fatigue_rate [-]"] == pytest.approx(0.25, rel=2e-2)
    assert fitted["E_ref [J]"] == pytest.approx(600e3, rel=2e-2)
    np.testing.assert_allclose(bench.predict_with(surface, fitted), measured, rtol=2e-2)
    with pytest.raises(ValueError, match="fatigue"):
        bench.fit_regularised(_synthetic_surface(bench), measured, fatigue=True)


def test_energy_cap_holds_e_ref_at_the_rating():
    bench = _benchmark()
    surface = _synthetic_surface(bench)
    measured = surface(600e3, 0.6, 0.3, 0.9)
    # the truth is above the cap: E_ref stops at it and the multipliers move along the valley
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                   e_max=450e3)
    assert fitted["E_ref [J]"] == pytest.approx(450e3, rel=1e-9)
    assert fitted["energy_at_rating"]
    # a cap above the truth changes nothing
    free = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                 e_max=2e6)
    assert free["E_ref [J]"] == pytest.approx(600e3, rel=1e-2) and not free["energy_at_rating"]
    # the largest blow energy per unit E_ref: energy factor x setting, by hand
    s = bench.ResponseSurface([1e5, 1e6], [0.5, 1.0], np.ones((2, 2, 2)), np.zeros(2),
                              np.ones(2), np.zeros(2), np.zeros(2), [1.0, 1.3], [0.8, 0.7])
    assert bench.largest_energy_per_e_ref(s) == pytest.approx(0.91)


def test_strong_prior_pulls_the_class_multipliers_together():
    bench = _benchmark()
    surface = _synthetic_surface(bench)
    measured = surface(600e3, 0.6, 0.3, 0.9)
    free = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0)
    tight = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=1e-3)

    def spread(f):
        return np.ptp(np.log([f["srd_sand [-]"], f["srd_clay [-]"], f["srd_toe [-]"]]))

    assert spread(free) == pytest.approx(math.log(0.9 / 0.3), rel=2e-2)
    assert spread(tight) < 0.01  # one multiplier for all: the prior dominates
    assert tight["objective [-]"] > free["objective [-]"]


def test_response_surface_runs_below_the_weight_and_extrapolates_above():
    bench = _benchmark()
    # one record, log N = log(10) + log(m) at both energies; the pile runs at m <= 0.4
    mult = np.array([0.25, 0.5, 1.0])
    counts = np.array([[[0.0, 0.0], [5.0, 5.0], [10.0, 10.0]]])
    s = bench.ResponseSurface([1e5, 1e6], mult, counts, [0.4], [1.0], [0.0], [0.0])
    assert s(3e5, 0.39)[0] == 0.0
    # between the run node (0.25) and 0.5: extrapolated from 0.5 and 1.0, 10 m
    assert s(3e5, 0.45)[0] == pytest.approx(4.5, rel=1e-9)
    assert s(3e5, 0.7)[0] == pytest.approx(7.0, rel=1e-9)
    # the effective multiplier of a record: SRD-weighted class multipliers
    s2 = bench.ResponseSurface([1e5, 1e6], mult, counts, [0.0], [1.0], [1.0], [2.0])
    assert s2.effective_multiplier(1.0, 0.5, 0.25)[0] == pytest.approx((1 + 0.5 + 0.5) / 4)


def test_model_key_keeps_the_keys_of_earlier_runs():
    bench = _benchmark()
    model = bench.Model()
    # the fields added later (the toe's values in clay) leave the key of a run without them
    assert bench.model_key(model) == repr(model)
    set_ = bench.replace(model, quake_toe_clay=0.005)
    assert bench.model_key(set_) == repr(model) + "+quake_toe_clay=0.005"
    assert bench.model_key(set_) != bench.model_key(bench.replace(model, damping_toe_clay=0.005))
    # the toe's quake and damping by its soil class: clay's where set, else sand's
    assert model.toe_dynamics(True) == model.toe_dynamics(False) == (0.0025, 0.5)
    both = bench.replace(model, quake_toe_clay=0.005, damping_toe_clay=0.3)
    assert both.toe_dynamics(False) == (0.005, 0.3) and both.toe_dynamics(True) == (0.0025, 0.5)
    # so does the toe's qt window (step M)
    toe = bench.replace(model, toe_qt_half_window_diameters=1.5)
    assert bench.model_key(toe) == repr(model) + "+toe_qt_half_window_diameters=1.5"


def test_toe_average_step_takes_qt_over_the_tip_plus_minus_1p5_diameters():
    """Step M's toe (ICP-05 / UWA-05): the model's toe_qt_half_window_diameters gives the SRD
    method a half-window of 1.5 D = 3.72 m about the tip, whatever the CPT; without it the
    0.5 m series keep qt at the tip and a full-resolution CPT its 1 m toe window."""
    from anvilwave.pile.soil import srd_methods as sm
    from anvilwave.pile.soil.profile import Cpt, SoilLayer, SoilProfile

    bench = _benchmark()
    assert bench.TOE_HALF_WINDOW_DIAMETERS == sm.ICP_05_TOE_HALF_WINDOW
    steps = {st.name.split(":")[0]: st for _, st in bench.PREDICTIVE_STEPS}
    assert steps["M"].toe_average and not steps["I"].toe_average
    assert bench.replace(steps["M"], name=steps["I"].name, toe_average=False) == steps["I"]
    model = bench.Model()
    toe = bench.replace(model, toe_qt_half_window_diameters=bench.TOE_HALF_WINDOW_DIAMETERS)
    # qc 10 MPa to 4 m, 20 MPa from 6 m (a ramp between), sand throughout
    cpt = Cpt(np.array([0.0, 4.0, 6.0, 40.0]), np.array([10e6, 10e6, 20e6, 20e6]),
              np.full(4, 50e3), np.zeros(4))
    profile = SoilProfile([SoilLayer(0.0, 40.0, "sand", 10e3, interface_friction_angle=29.0)],
                          cpt, net_area_ratio=model.net_area_ratio)
    pile = bench.PileRecord("X", "X", 0.05, 30.0, np.array([8.0]), np.ones(1), None, "", {})
    method = bench.srd_source(pile, toe, profile).method_object
    assert method.toe_qt_half_window == pytest.approx(1.5 * 2.48)
    assert method.toe_window == 0.0
    # tip 8 m, window [4.28, 11.72] m: qt 20 MPa except the ramp's last 1.72 m (mean 15.7)
    qt_avg = (20e6 * (7.44 - 1.72) + 1.72 * 0.5 * (20e6 + (10e6 + 10e6 * 0.28 / 2.0))) / 7.44
    assert method.unit_toe(profile, 8.0) == pytest.approx(
        0.10 * qt_avg * (qt_avg / 80e3) ** 0.2, rel=1e-12)
    plain = bench.srd_source(pile, model, profile).method_object
    assert plain.toe_qt_half_window == 0.0 and plain.toe_window == 0.0
    full = bench.replace(pile, fullres=True)
    assert bench.srd_source(full, model, profile).method_object.toe_window == 1.0
    assert bench.srd_source(full, toe, profile).method_object.toe_window == 0.0


def _dynamics_surface(bench, n=60, seed=3):
    """The synthetic surface and, per group of the dynamic values, a grid of the same records
    with log N shifted by a known slope per record (0-0.6 per unit log of the value, x the
    log of the group's factor); toes in sand on the even records, in clay on the odd."""
    surface = _synthetic_surface(bench, n, seed)
    rng = np.random.default_rng(seed + 20)
    slopes = {g: rng.uniform(0.0, 0.6, n) for g in bench.SENSITIVITY_FACTORS}
    perturbed = {}
    for g, f in bench.SENSITIVITY_FACTORS.items():
        counts = np.exp(surface.lc + slopes[g][:, None, None] * math.log(f))
        perturbed[g] = bench.ResponseSurface(np.exp(surface.le), np.exp(surface.lm), counts,
                                             surface.run, surface.sand, surface.clay,
                                             surface.toe, surface.energy_factor,
                                             surface.setting)
    toe_sand = np.arange(n) % 2 == 0
    return surface.with_dynamics(perturbed, toe_sand, (0.16, 0.65)), perturbed, slopes


def test_dynamics_surface_is_the_perturbed_grid_at_its_factor():
    bench = _benchmark()
    surface, perturbed, slopes = _dynamics_surface(bench)
    args = (600e3, 0.6, 0.3, 0.9)
    base = surface(*args)
    # the model's values (every ratio 1) change nothing
    np.testing.assert_allclose(surface(*args, dynamics={n: 1.0 for n in bench.DYNAMICS}), base,
                               rtol=1e-12)
    # the toe's quake x4 in sand: the sand-toe records are the perturbed grid's, the others
    # stay; x2 (half the log): the geometric mean of the two
    sand = surface.toe_sand
    at = surface(*args, dynamics={"quake_toe_sand": 4.0})
    np.testing.assert_allclose(at[sand], perturbed["quake_toe"](*args)[sand], rtol=1e-12)
    np.testing.assert_allclose(at[~sand], base[~sand], rtol=1e-12)
    half = surface(*args, dynamics={"quake_toe_sand": 2.0})
    np.testing.assert_allclose(half[sand], np.sqrt(base * at)[sand], rtol=1e-12)
    # the shaft dampings enter as the record's SRD-weighted damping, by hand
    got = surface(*args, dynamics={"damping_clay": 2.0})
    x = np.log((0.16 * surface.sand + 1.3 * surface.clay)
               / (0.16 * surface.sand + 0.65 * surface.clay))
    np.testing.assert_allclose(np.log(got / base), slopes["damping_shaft"] * x, atol=1e-12)
    # the toe's damping in clay: only the clay-toe records move
    got = surface(*args, dynamics={"damping_toe_clay": 2.0})
    np.testing.assert_allclose(np.log(got / base)[~sand],
                               slopes["damping_toe"][~sand] * math.log(2.0), atol=1e-12)
    np.testing.assert_allclose(got[sand], base[sand], rtol=1e-12)
    # a subset keeps every record's slopes and toe class
    sub = surface.subset(np.arange(10))
    np.testing.assert_allclose(sub(*args, dynamics={"quake_toe_sand": 4.0}), at[:10],
                               rtol=1e-12)


def test_regularised_fit_recovers_a_dynamic_value():
    bench = _benchmark()
    surface, _, _ = _dynamics_surface(bench)
    measured = surface(600e3, 0.6, 0.3, 0.9, dynamics={"damping_sand": 1.6})
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                   n_eff=1e6, dynamics=("damping_sand",))
    # the value's slope differs between records, so it is told apart from the multipliers
    # (tolerance: the 1 % of the interpolation in log E of the synthetic surface)
    assert fitted["damping_sand [-]"] == pytest.approx(1.6, rel=2e-2)
    assert not fitted["damping_sand_at_range_edge"]
    np.testing.assert_allclose(bench.predict_with(surface, fitted), measured, rtol=2e-2)
    # beyond the range (x2 at most, the grid's factor) the fit stops at its edge
    measured = surface(600e3, 0.6, 0.3, 0.9, dynamics={"damping_sand": 2.0})
    fitted = bench.fit_regularised(surface, measured, bench.CLASSES, "log", prior_sd=100.0,
                                   n_eff=1e6, dynamics=("damping_sand",))
    assert fitted["damping_sand [-]"] == pytest.approx(2.0, rel=2e-2)
    with pytest.raises(ValueError, match="dynamics"):
        bench.fit_regularised(_synthetic_surface(bench), measured, dynamics=("damping_sand",))


def test_fit_step_chooses_the_hammer_class_that_made_the_data():
    bench = _benchmark()
    light = _synthetic_surface(bench)
    # a second class whose blow count grows less steeply with the multiplier (log N = ...
    # + 1.2 log m instead of 2 log m): the two shapes cannot be matched by E_ref and m alone
    heavy = bench.ResponseSurface(np.exp(light.le), np.exp(light.lm),
                                  np.exp(light.lc - 0.8 * light.lm[None, :, None]), light.run,
                                  light.sand, light.clay, light.toe, light.energy_factor,
                                  light.setting)
    surfaces = {"light": (light, 800e3), "heavy": (heavy, 1800e3)}
    step = bench.Step("K", classes=bench.CLASSES, hammers=("light", "heavy"))
    for truth in ("light", "heavy"):
        measured = surfaces[truth][0](600e3, 0.6, 0.3, 0.9)
        hammer, fitted = bench.fit_step(step, surfaces, measured, 1e6)
        assert hammer == truth
        assert fitted["E_ref [J]"] == pytest.approx(600e3, rel=2e-2)
    # a step without a choice fits the first class; the cap is that class's rating
    capped = bench.Step("H", classes=bench.CLASSES, energy_cap=True)
    hammer, fitted = bench.fit_step(capped, surfaces, surfaces["light"][0](600e3, 0.6, 0.3, 0.9),
                                    1e6)
    assert hammer == "light"
    assert fitted["E_ref_max [J]"] == pytest.approx(800e3 / bench.largest_energy_per_e_ref(light))


def test_departures_from_the_depth_mean_by_hand():
    """The bound the depth mean sets: synthetic records, each foundation's departure known."""
    bench = _benchmark()
    piles = _synthetic_piles(bench)
    groups = ["A", "B", "C"]
    measured = np.concatenate([p.measured for p in piles])
    # a model equal to the records: its departures are the measured ones
    exact = bench.departures_from_the_depth_mean(piles, groups, measured)
    assert exact["correlation [-]"] == pytest.approx(1.0)
    assert exact["model_sd [blows/m]"] == pytest.approx(exact["measured_sd [blows/m]"])
    assert exact["trend_from_records_rmse [blows/m]"] == pytest.approx(0.0, abs=1e-12)
    assert exact["needed_correlation [-]"] == pytest.approx(0.5)
    # the two piles of a foundation differ by 2 blows/m at each depth: sd sqrt(2) about
    # their mean (one degree of freedom per depth)
    assert exact["within_foundation_sd [blows/m]"] == pytest.approx(math.sqrt(2.0))
    # every record has another foundation at its depth; A1 at 1 m departs from the others'
    # mean (20 + 22 + 5 + 7) / 4 = 13.5 by 10 - 13.5
    assert exact["records [-]"] == 16
    baseline = bench.record_baselines(piles, groups)
    assert baseline[0] == 13.5
    assert exact["measured_sd [blows/m]"] == pytest.approx(bench.rmse(baseline, measured))
    # a model that knows only the depth trend: no departures, the baseline's own score
    trend = np.concatenate([p.depths * 10.0 for p in piles])
    flat = bench.departures_from_the_depth_mean(piles, groups, trend)
    assert flat["model_sd [blows/m]"] == pytest.approx(0.0, abs=1e-12)
    assert flat["trend_from_records_rmse [blows/m]"] == pytest.approx(
        bench.rmse(baseline, measured))
    # departures of twice the measured: the mean square identity of the docstring,
    # |d_m - d_p|^2 = sd_m^2 + sd_p^2 - 2 r sd_m sd_p, with sd_p = 2 sd_m and r = 1
    double = bench.departures_from_the_depth_mean(piles, groups, 2.0 * measured)
    assert double["correlation [-]"] == pytest.approx(1.0)
    assert double["needed_correlation [-]"] == pytest.approx(1.0)
    assert double["trend_from_records_rmse [blows/m]"] == pytest.approx(
        double["measured_sd [blows/m]"])


def test_stacking_weight_by_hand():
    bench = _benchmark()
    base = np.array([10.0, 20.0, 30.0])
    # measured halfway between baseline and physics: w = 0.5
    assert bench.stacking_weight(base + 4.0, base, base + 2.0) == pytest.approx(0.5)
    assert bench.stacking_weight(base + 4.0, base, base - 2.0) == 0.0  # clipped to [0, 1]
    assert bench.stacking_weight(base, base, base + 1.0) == 1.0


def test_docs_data_file_is_the_runs_summary():
    """docs/data/isfog_backanalysis.json: its table (docs/validation.md, "Does the
    back-analysis predict?") and quoted numbers are those of the run's summary, which the file
    keeps as its values: derived again here from them. The run itself (the whole
    cross-validation, about 30 minutes on 2 cores) is beyond the suite; the two-foundation run
    above checks that a run writes its summary into the file unchanged."""
    bench = _benchmark()
    data = doc_data("isfog_backanalysis")
    summary = data["values"]
    steps = summary["steps"]
    assert [s["step"].split(":")[0] for s in steps] == list("ABCDEFGHIJKLMNO")
    table = data["tables"]["steps"]
    assert [row[0] for row in table["rows"]] == [s["step"] for s in steps]
    assert [row[1] for row in table["rows"]] == [s["rmse [blows/m]"] for s in steps]
    assert [row[4] for row in table["rows"]] == [s["bias_baseline [blows/m]"] for s in steps]
    groups = {"AA": "AA/AB/AC", "AB": "AA/AB/AC", "AC": "AA/AB/AC", "CD": "CD/CE/CF",
              "CE": "CD/CE/CF", "CF": "CD/CE/CF", "CJ": "CJ/CK/CL", "CK": "CJ/CK/CL",
              "CL": "CJ/CK/CL"}
    tables, subs = bench.cross_validation_docs(summary, groups)
    assert tables == data["tables"]
    assert subs == data["substitutions"]
    # the quoted gains by hand: C against B, D against C
    assert subs["c_gain"][0] == steps[2]["rmse [blows/m]"] - steps[1]["rmse [blows/m]"]
    assert subs["d_gain"][0] == steps[3]["rmse [blows/m]"] - steps[2]["rmse [blows/m]"]
    # the final step, scored against the same baseline
    final = steps["ABCDEFGHIJKLMNO".index(bench.FINAL_STEP)]
    assert summary["final_step"] == final["step"]
    assert summary["cv_rmse [blows/m]"] == final["rmse [blows/m]"]
    assert subs["final_minus_naive"][0] == (final["rmse [blows/m]"]
                                            - final["rmse_baseline [blows/m]"])
    # N, the installations, against the baseline and the per-depth model at the same fits
    installation = summary["installation_cv"]
    assert installation["step"] == steps[13]["step"]
    assert subs["n_minus_naive"][0] == (steps[13]["rmse [blows/m]"]
                                        - steps[13]["rmse_baseline [blows/m]"])
    assert subs["n_change_direct"][0] == (steps[13]["rmse [blows/m]"]
                                          - installation["per_depth_direct_rmse [blows/m]"])
    # M against I and the baseline
    assert subs["m_change"][0] == steps[12]["rmse [blows/m]"] - steps[8]["rmse [blows/m]"]
    assert subs["m_minus_naive"][0] == (steps[12]["rmse [blows/m]"]
                                        - steps[12]["rmse_baseline [blows/m]"])
    # O against I and the baseline
    assert subs["o_change"][0] == steps[14]["rmse [blows/m]"] - steps[8]["rmse [blows/m]"]
    assert subs["o_minus_naive"][0] == (steps[14]["rmse [blows/m]"]
                                        - steps[14]["rmse_baseline [blows/m]"])
    # H and I keep the largest blow within the rating
    assert summary["largest_blow_energy [J]"] <= summary["hammer_rated_energy [J]"] * (1 + 1e-6)


def test_prediction_means_text_by_hand():
    bench = _benchmark()
    means = {"AA": 65.6, "AB": 67.6, "AC": 64.3, "CJ": 59.7, "CK": 59.4}
    groups = {"AA": "A", "AB": "A", "AC": "A", "CJ": "C", "CK": "C"}
    assert bench.prediction_means_text(means, groups) == "64-68 blows/m (AA-AC) and 59-60 (CJ-CK)"
    assert bench.prediction_means_text({"AA": 3.0}, {"AA": "A"}) == "3-3 blows/m (AA-AA)"


def test_calibration_docs_data_file_is_the_runs_summary():
    """docs/data/isfog_calibration.json (drive.md's calibration fit): its table and quoted
    numbers are those of the run's summary, kept as its values, derived again here. The run
    (85 piles, about 88,000 blows, minutes on 2 cores) is beyond the suite; the two-pile run
    above checks that a run writes its summary into the file."""
    bench = _benchmark()
    data = doc_data("isfog_calibration")
    summary = data["values"]
    tables, subs = bench.calibration_docs(summary)
    assert tables == data["tables"] and subs == data["substitutions"]
    both, alone = tables["fits"]["rows"]
    assert alone[2] == 1.0  # the energy-only fit keeps the method's SRD
    # one records' largest normalised energy behind both fits' largest blow
    assert both[3] / both[1] == pytest.approx(alone[3] / alone[1], rel=1e-12)
    assert summary["largest_blow_energy [J]"] == pytest.approx(both[3], rel=1e-12)
