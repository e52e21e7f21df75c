"""Quakes and Smith dampings per soil layer: the segment values follow from the layer rule
(hand cases), the GRLWEAP rows' layers, the values by soil type against their published
imperial figures, and bad rows named by key."""

from __future__ import annotations

import numpy as np
import pytest

from anvilwave.config.drive import grlweap_rows_to_layers
from anvilwave.inputs import InputError, Table
from anvilwave.pile.kernels import SOIL_CAPACITY, SOIL_DASHPOT, SOIL_SMITH, SOIL_STIFFNESS
from anvilwave.pile.pile import PileSpec, Section
from anvilwave.pile.soil.models import (
    SoilLayers,
    SoilSpec,
    smith_damping_by_soil_type,
    soil_from_table,
    soil_parameters,
    toe_quake,
)
from anvilwave.pile.soil.srd import SoilResistanceTable

# a 10 m pile of 1 m segments embedded 6 m: segments 5..10 below the mudline at 4 m
PILE = PileSpec((Section(10.0, 1.0, 0.02),), segment_length=1.0)
SRD = SoilResistanceTable.from_rows(np.array([[0.0, 50e3, 5e6], [20.0, 50e3, 5e6]]))
# layer 1: 0-3 m, layer 2: 3-6 m (the tip on its bottom); quakes and dampings all different
LAYERS = SoilLayers(np.array([[0.0, 3.0, 0.002, 0.004, 0.2, 0.4],
                              [3.0, 6.0, 0.003, 0.006, 0.6, 0.8]]))


def _soil(model: str, layers=LAYERS) -> SoilSpec:
    return SoilSpec(model=model, penetration=6.0, srd=SRD, quake_shaft=0.0025,
                    quake_toe=0.0025, damping_shaft=0.65, damping_toe=0.5, layers=layers)


def test_each_segment_takes_its_layer_and_the_toe_the_tips():
    p = soil_parameters(_soil("smith-viscous"), PILE)
    cap = p[SOIL_CAPACITY]
    embedded = cap[:-1] > 0.0
    assert embedded.sum() == 6
    # segment middles at 0.5, 1.5, 2.5 m in layer 1 and 3.5, 4.5, 5.5 m in layer 2
    quake = cap[:-1][embedded] / p[SOIL_STIFFNESS, :-1][embedded]
    np.testing.assert_allclose(quake, [0.002] * 3 + [0.003] * 3, rtol=1e-12)
    np.testing.assert_allclose(p[SOIL_DASHPOT, :-1][embedded] / cap[:-1][embedded],
                               [0.2] * 3 + [0.6] * 3, rtol=1e-12)
    # the tip at 6 m lies on layer 2's bottom: layer 2's toe values
    assert cap[-1] / p[SOIL_STIFFNESS, -1] == pytest.approx(0.006, rel=1e-12)
    assert p[SOIL_DASHPOT, -1] / cap[-1] == pytest.approx(0.8, rel=1e-12)
    assert toe_quake(_soil("smith"), PILE) == pytest.approx(0.006)
    # Smith (not viscous): J per segment in its own row
    smith = soil_parameters(_soil("smith"), PILE)
    np.testing.assert_allclose(smith[SOIL_SMITH, :-1][embedded], [0.2] * 3 + [0.6] * 3)


def test_depths_outside_the_layers_keep_the_scalars():
    shallow = SoilLayers(np.array([[0.0, 2.0, 0.002, 0.004, 0.2, 0.4]]))
    p = soil_parameters(_soil("smith-viscous", shallow), PILE)
    embedded = p[SOIL_CAPACITY, :-1] > 0.0
    quake = p[SOIL_CAPACITY, :-1][embedded] / p[SOIL_STIFFNESS, :-1][embedded]
    np.testing.assert_allclose(quake, [0.002] * 2 + [0.0025] * 4, rtol=1e-12)
    assert toe_quake(_soil("smith", shallow), PILE) == 0.0025
    # no layers: the scalars everywhere, as before
    plain = soil_parameters(_soil("smith-viscous", None), PILE)
    assert np.allclose(plain[SOIL_CAPACITY, :-1][embedded]
                       / plain[SOIL_STIFFNESS, :-1][embedded], 0.0025)


def test_grlweap_rows_give_layers_from_each_row_down():
    # rows: depth, shaft quake [mm], toe quake [mm], Js, Jt; a step at 2 m
    rows = np.array([[0.0, 2.5, 2.5, 0.25, 0.5], [2.0, 2.5, 2.5, 0.25, 0.5],
                     [2.0, 3.0, 5.0, 0.65, 0.5], [10.0, 3.0, 5.0, 0.65, 0.5]])
    layers = grlweap_rows_to_layers(rows)
    assert layers.values([1.0, 2.0, 5.0, 50.0], 2, 0.0).tolist() == [0.0025, 0.003, 0.003,
                                                                     0.003]
    assert layers.values([1.0, 5.0], 4, 0.0).tolist() == [0.25, 0.65]
    # the toe on the step takes the layer above it
    assert layers.values(2.0, 3, 0.0, upper=True)[0] == 0.0025


def test_smith_damping_by_soil_type_is_the_imperial_recommendation():
    ft = 0.3048  # [m]
    # 0.05 s/ft (sand) and 0.2 s/ft (clay) on the shaft, 0.15 s/ft at the toe; rounded to
    # 0.01 s/m (0.164 -> 0.16, 0.656 -> 0.65, 0.492 -> 0.5): 3 % at most
    assert smith_damping_by_soil_type("sand") == pytest.approx((0.05 / ft, 0.15 / ft),
                                                               rel=0.03)
    assert smith_damping_by_soil_type("clay") == pytest.approx((0.2 / ft, 0.15 / ft),
                                                               rel=0.03)
    with pytest.raises(ValueError, match="unknown soil type"):
        smith_damping_by_soil_type("peat")


@pytest.mark.parametrize("rows, rule", [
    ([[0.0, 3.0, 0.002, 0.004, 0.2, 0.4], [2.0, 6.0, 0.003, 0.006, 0.6, 0.8]], "overlap"),
    ([[0.0, 3.0, 0.0, 0.004, 0.2, 0.4]], "quakes must be positive"),
    ([[3.0, 1.0, 0.002, 0.004, 0.2, 0.4]], "top < bottom"),
    ([[0.0, 3.0, 0.002, 0.004, -0.2, 0.4]], "dampings must not be negative"),
])
def test_bad_layers_name_the_key_and_rule(rows, rule):
    table = Table({"model": "smith", "penetration": 6.0, "srd": [[0.0, 1.0, 1.0],
                                                                  [10.0, 1.0, 1.0]],
                   "layers": rows}, "sys.toml", "soil")
    with pytest.raises(InputError, match=f"soil.layers.*{rule}"):
        soil_from_table(table, 10.0)


def test_srd_layers_give_smith_dampings_by_soil_type(tmp_path):
    """``[srd] layer_parameters = "soil-type"``: sand 0-5 m, clay below; every segment takes
    the Smith shaft damping of its layer's type, the toe in clay 0.5 s/m, the [soil] quakes;
    the set-up's installation and drive analyses see them through pile_soil_at."""
    from anvilwave.config.drive import pile_soil_at
    from anvilwave.config.system import load_system

    from .test_setup import HAMMER, SYSTEM

    (tmp_path / "hammer.toml").write_text(HAMMER)
    text = SYSTEM.format(pauses="") + '''
[srd]
method = "stevens-1982"
layer_parameters = "soil-type"
[[srd.layers]]
top = 0.0
bottom = 5.0
soil = "sand"
submerged_unit_weight = 10.0e3
interface_friction_angle = 29.0
[[srd.layers]]
top = 5.0
bottom = 30.0
soil = "clay"
submerged_unit_weight = 9.0e3
undrained_shear_strength = 60.0e3
plasticity_index = 0.3
'''
    path = tmp_path / "layers.toml"
    path.write_text(text)
    cfg = load_system(path)
    ps, _, _ = pile_soil_at(cfg.pile_soil, cfg.srd, 8.0, 1.0)
    p = soil_parameters(ps.soil, ps.pile)
    cap = p[SOIL_CAPACITY, :-1]
    embedded = cap > 0.0
    # 20 m pile, tip at 8 m: 8 embedded 1 m segments, middles 0.5 ... 7.5 m
    np.testing.assert_allclose(p[SOIL_DASHPOT, :-1][embedded] / cap[embedded],
                               [0.16] * 5 + [0.65] * 3, rtol=1e-12)
    assert p[SOIL_DASHPOT, -1] / p[SOIL_CAPACITY, -1] == pytest.approx(0.5)
    np.testing.assert_allclose(cap[embedded] / p[SOIL_STIFFNESS, :-1][embedded], 0.0025)
    path.write_text(text.replace('"soil-type"', '"file"'))
    with pytest.raises(InputError, match="srd.layer_parameters"):
        load_system(path)
