"""GRLWEAP's conventions as options, each on a small case whose answer follows from the
convention: the table a tip depth takes among SRD tables per tip depth, the weight on the soil
for the pile-run check, and the blow window ending at the toe's first maximum."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from anvilwave.analyses.drive import analyse_depth, driving_weight, summarise, toe_rebound_time
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.inputs import InputError
from anvilwave.pile.soil.profile import TipDepthTables, tip_table_resistance

from .test_driveability import _rigid_pile_system, _table_srd

# two tables: tip 1 m (shaft 10 Pa, toe 100 Pa) and tip 2 m (shaft 20 Pa, toe stepping at 2 m
# from 200 Pa above the step to 300 Pa below it)
TIPS = np.array([1.0, 2.0])
TABLES = (np.array([[0.0, 10.0, 100.0], [5.0, 10.0, 100.0]]),
          np.array([[0.0, 20.0, 200.0], [2.0, 20.0, 200.0], [2.0, 20.0, 300.0],
                    [5.0, 20.0, 300.0]]))


@pytest.mark.parametrize("tip, shaft, toe", [
    (1.0, 10.0, 100.0),   # on a table depth: that table exactly
    (2.0, 20.0, 200.0),   # on a table depth, at its step: the toe above the step
    (1.5, 20.0, 200.0),   # between: the nearest table at or below the tip (table 2)
    (1.0 + 1e-6, 20.0, 200.0),  # just below table 1 (beyond the 1e-9 m round-off): table 2
    (0.5, 10.0, 100.0),   # above the first table: the first table
])
def test_grlweap_rule_takes_the_table_at_or_below_the_tip(tip, shaft, toe):
    s, t = tip_table_resistance(TIPS, TABLES, tip, [0.25, 0.75], rule="grlweap")
    np.testing.assert_array_equal(s, [shaft, shaft])
    assert t == toe


def test_interpolate_rule_blends_and_takes_the_toe_below_a_step():
    s, t = tip_table_resistance(TIPS, TABLES, 1.5, [0.25], rule="interpolate")
    assert s[0] == pytest.approx(15.0) and t == pytest.approx(0.5 * 100.0 + 0.5 * 200.0)
    assert tip_table_resistance(TIPS, TABLES, 2.0, [], rule="interpolate")[1] == 300.0
    with pytest.raises(ValueError, match="tip-table rule"):
        TipDepthTables(TIPS, TABLES, rule="nearest")


def test_srd_tip_table_rule_is_read_and_checked(tmp_path):
    text = _rigid_pile_system(tmp_path).read_text()
    rows = "[[0.0, 0.0, 1.0e6], [2.0, 0.0, 1.0e6]]"
    good = text + ('\n[srd]\nmethod = "tip-table"\ntip_table_rule = "grlweap"\n'
                   f"[[srd.tables]]\ntip_depth = 1.0\nrows = {rows}\n")
    (tmp_path / "g.toml").write_text(good)
    assert load_system(tmp_path / "g.toml").srd.method_object.rule == "grlweap"
    (tmp_path / "b.toml").write_text(good.replace('"grlweap"', '"nearest"'))
    with pytest.raises(InputError, match="srd.tip_table_rule"):
        load_system(tmp_path / "b.toml")


@pytest.fixture(scope="module")
def rigid(tmp_path_factory):
    cfg = load_system(_rigid_pile_system(tmp_path_factory.mktemp("rigid")))
    return cfg, build_engine(cfg)


def test_grlweap_weight_on_soil_leaves_out_the_ram(rigid):
    cfg, engine = rigid
    head = 1234.0
    ram = float(np.sum(cfg.hammer.ram.mass)) * cfg.gravity
    assert driving_weight(cfg, head, "all") - driving_weight(cfg, head, "grlweap") == \
        pytest.approx(ram, rel=1e-12)
    # an SRD between the two weights: a pile run with the ram's weight, a blow without it
    g = replace(cfg, gravity=9.81)
    weights = [driving_weight(g, 5e3, rule) for rule in ("all", "grlweap")]
    srd = 0.5 * sum(weights)
    rows = [{"depth [m]": d, "srd [N]": s, "blow_count [1/m]": n,
             "max_compression_stress [Pa]": 1.0, "max_tension_stress [Pa]": 0.0}
            for d, s, n in ((1.0, 10 * srd, 50.0), (2.0, srd, 20.0), (3.0, 10 * srd, 60.0))]
    runs = {rule: summarise(rows, g, replace(cfg.drive, weight_on_soil=rule),
                            5e3)["pile_run_depths [m]"] for rule in ("all", "grlweap")}
    assert runs == {"all": [2.0], "grlweap": []}


def test_toe_rebound_window_ends_at_the_rigid_piles_closed_form_maximum(rigid):
    """The rigid pile of test_driveability (M = 2000 kg, v_p = 2.953 m/s, a Smith toe of
    Ru = 500 kN, quake 2.5 mm, no damping): elastic until the quake, t1 = asin(q w / v_p) / w
    (w = sqrt(Ru / (q M))), then decelerated by Ru to rest, t2 = M v1 / Ru: the toe's first
    maximum at t1 + t2 = 12.24 ms. The toe-rebound window ends there and keeps the set."""
    cfg, engine = rigid
    settings = replace(cfg.drive, window="toe-rebound")
    m, ru, q = 2000.0, 500e3, 0.0025
    vp = 2 * 1000.0 * math.sqrt(2 * 9.81) / 3000.0
    w = math.sqrt(ru / (q * m))
    v1 = math.sqrt(vp**2 - (w * q) ** 2)
    t_max = math.asin(q * w / vp) / w + m * v1 / ru
    assert t_max == pytest.approx(0.01224, abs=1e-5)
    ps = engine.with_pile_soil(cfg.pile_soil)
    blow = ps.blow(state=ps.static_state(), duration=0.03, record=True, energy=False)
    # 0.2 ms: the ~0.1 ms contact (the closed form transfers the momentum at once) delays the
    # pile's motion by about half of it, plus one record interval
    assert toe_rebound_time(blow) == pytest.approx(t_max, abs=2e-4)
    fixed = analyse_depth(engine, cfg, _table_srd(cfg), cfg.drive, 1.0).row
    window = analyse_depth(engine, cfg, _table_srd(cfg), settings, 1.0).row
    # the same maximum toe displacement: the set differs by the toe's motion in one step
    assert window["set [m]"] == pytest.approx(fixed["set [m]"], rel=1e-4)


def test_toe_rebound_window_needs_smiths_set(tmp_path):
    text = _rigid_pile_system(tmp_path).read_text()
    (tmp_path / "w.toml").write_text(text.replace('set_rule = "grlweap"',
                                                  'set_rule = "permanent"\n'
                                                  'window = "toe-rebound"'))
    with pytest.raises(InputError, match="driveability.window"):
        load_system(tmp_path / "w.toml")
