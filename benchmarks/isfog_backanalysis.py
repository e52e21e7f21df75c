"""ISFOG 2020 pile driving prediction event: back-analysis of the calibration piles and blind
prediction of the prediction piles (2.48 m jacket pin piles, North Sea; issue 16).

Run: python benchmarks/isfog_backanalysis.py [--data ../shared/reference/isfog2020] --out DIR

The records lie in ``../shared/reference/isfog2020/`` beside the repository (read its README);
they are read from there and never copied into the repository. Without them this script
prints a message and exits with status 0 (a benchmark, not a test).

Model (the same for every pile; nothing is tuned per pile)
----------------------------------------------------------
* Soil: the pile's CPT (the 0.5 m series of its foundation, for every pile;
  ``--prediction-cpt fullres``: the full-resolution CPT for the prediction piles, first 0.3 m
  of every push dropped). Sand and clay
  layers from Robertson's (2009) soil behaviour type index, Ic < 2.6 sand
  (:func:`anvilwave.pile.soil.cpt_classification.soil_layers_from_cpt`). ASSUMED submerged unit
  weights
  10 kN/m^3 (sand) and 9 kN/m^3 (clay); sea water 10.05 kN/m^3 for u0 below the mudline; the
  water depth plays no part (the cone is zeroed at the seabed). Full-resolution CPTs: layers
  thinner than 0.5 m are merged into their neighbours and the toe resistance is averaged over
  1 m centred on the tip, the resolution of the calibration CPTs (their half-metre values are
  means of 1 m).
* SRD: Alm & Hamre (2001) from the CPT (qt with a net area ratio of 0.8), with friction
  fatigue, rebuilt for every tip depth; coring pile (toe on the steel annulus), the method's
  default faces (sand 0.5 outside + 0.5 inside, clay 1.0 + 1.0), the sand toe factor 0.10 of
  the 2018 revision in practice (``--sand-toe-factor 0.15`` for the 2001 paper's; on these
  records 0.10 lowers the RMSE and the depth trend of the residuals: the 0.15 toe makes the
  shallow dense sand, where the toe dominates, too hard against the deeper metres), ASSUMED
  constant-volume interface friction angle 29 deg in sand.
* Soil model: Smith-viscous springs and dashpots, quakes 2.5 mm shaft and toe (GRLWEAP for
  the coring toe of an open pile), Smith damping 0.16 s/m in sand and 0.65 s/m in clay on the
  shaft (one factor per tip depth: the mean weighted by the segments' static resistance, which
  keeps the total shaft dashpot), 0.5 s/m at the toe.
* Pile: D 2.48 m with the given bottom wall thickness over its whole length (the upper wall
  make-up is not given: ASSUMED uniform), length = final penetration + 10 m stick-up
  (ASSUMED), steel 210 GPa, 7850 kg/m^3, segments of 0.5 m.
* Hammer: IHC S-800 class hydraulic hammer (800 kJ, 40 t ram, efficiency 0.95;
anvilwave/hammer/data):
  the README's class for a 2.48 m pile is a hydraulic hammer of about 500-1200 kJ, and the
  S-800 is a usual hammer for 2-3 m jacket pin piles. The fit must keep the largest blow
  energy (0.89 E_ref: the largest normalised energy of the records) within its rating; it
  does with the SRD multiplier, not with the energy alone (E_ref would be about 1.3 MJ). A
  heavier ram (``--hammer ihc_s1800``, 90 t) fits the records as well, with the energy alone
  inside its rating: the blow counts do not tell the class apart (see the note on the fit).
  The classic driving system (GRLWEAP's model of a hydrohammer, no cushion material): the
  steel striker contact as a stiff "hammer cushion", helmet (anvil + pile sleeve), the hammer
  housing resting on it, the steel helmet-pile contact. The values are class ESTIMATES scaled
  from GRLWEAP's S-4000 model (anvilwave/examples/grlweap_s4000.toml) by the ram's face area
  (contact)
  and mass (masses, housing spring); see :func:`driving_system`.
* Driving: one blow per tip depth from static equilibrium under the hammer's weight, blow
  window 0.2 s (the pile has come to rest), the permanent set (the default rule of
  :mod:`anvilwave.analyses.drive`). Where the SRD does not carry the weight of pile and
  hammer the pile runs: blow count 0. The blow energy at depth z is the normalised hammer energy
  of the record at z times ONE reference energy E_ref [J], and the SRD is scaled by at most
  ONE global multiplier; both are fitted on all calibration piles at once.

Fit (fast): for each calibration pile and whole-metre depth the blow count is simulated on a
grid of reference energies (7, log-spaced, 150-3200 kJ) and SRD multipliers (6, 0.25-1.4), in
parallel over the piles; during the fit log(blow count) is interpolated in log(E_ref)
(piecewise cubic) and log(multiplier) (linear) instead of re-simulating
(:class:`GridInterpolator`). The
misfit is the root mean square of (predicted - measured) blow count [blows/m] over every
whole-metre record of the calibration piles. The fit with the energy alone (multiplier 1)
is reported beside it. Finally every calibration and prediction pile is simulated directly
at the fitted values (the calibration RMSE reported is that of the direct runs; the
interpolation error is reported too).
E_ref and the multiplier are nearly interchangeable (a harder soil driven with more energy
gives about the same sets: the misfit has a long valley, E_ref rising about as the
multiplier), so the energy-only fit is reported beside the two-parameter one, and the hammer
class decides which end of the valley is plausible: the largest blow energy must stay within
the hammer's rating (``largest_blow_energy_within_rating`` in the summary).

Predictive back-analysis (``--cross-validate``)
-----------------------------------------------
Leave one foundation out: the piles of one foundation share its CPT, so each fold holds out
every pile of one foundation (``cpt_group``), fits on the piles of all the others and
predicts the held-out records. Every pile, calibration and prediction, has the same CPT
processing: the 0.5 m series of its foundation. The score (RMSE and bias = mean of predicted
- measured, in blows/m, over the same records for every step) is set against the naive
baseline computed the same way, which knows no soil: at each depth, the mean measured blow
count of the piles of the other foundations driven at that depth (records at depths no
other foundation reached are left out of both scores). The steps
(:data:`PREDICTIVE_STEPS`), each scored by the same cross-validation:

A. one E_ref and one SRD multiplier fitted in blows/m (the model above);
B. the fit in log(N + 5) (the blow count is a steep, nonlinear function of the SRD);
C. separate multipliers on the sand shaft, clay shaft and toe SRD, each a deviation from the
   common multiplier with a Gaussian (ridge) prior in log space, sd ln 2
   (:func:`fit_regularised`: the faces' rule alone changes the shaft by 2 between codes);
D. the blow energy from the recorded ENTHRU (0.65 or 1.0 x the hammer energy for six piles
   instead of the usual 0.75);
E. an energy law E_ref x setting^b (b about 1, prior sd 0.25): tried, not kept;
F. residual stress: three blows per depth, each from the state the last left, as the
   ratio of the third blow's count to the single blow's at the final parameters;
G. F stacked with the naive baseline: baseline + w (physics - baseline), w fitted by least
   squares on the training foundations (their baselines leave each of them out in turn);
H. D with the hammer held physical: every fold's E_ref at most the S-800's rating over the
   largest blow energy per unit E_ref of its training records (ENTHRU factor x setting), so
   that no blow asks more than the rated energy;
I. H + ONE factor r on Alm & Hamre's friction-fatigue rate k (the shaft friction decaying
   with the distance h from the tip as exp(-r k h); r = 1 the paper's, a weak Gaussian prior
   on log r, sd ln 4), fitted with the other parameters on the training foundations only;
J. I stacked with the naive baseline as in G (a blend, not physics);
K. I with the hammer class a discrete choice per fold: the S-800 or a heavier ram (IHC S-1800,
   90 t, :data:`ALTERNATIVE_HAMMERS`), each simulated on the second grid and fitted with E_ref
   held within its own rating; the class of the least training objective is kept
   (:func:`fit_step`);
L. I + the soil's dynamic values per soil type as fitted parameters (:data:`DYNAMICS`): the
   Smith shaft damping in sand and in clay, the toe's damping and quake in sand and in clay,
   each a ratio to the model's value with a Gaussian prior on its log (sd ln 2,
   :data:`DYNAMICS_SD`) about GRLWEAP's and Smith's customary values (quakes 2.5 mm, the coring
   toe of an open pile; dampings 0.16 s/m sand, 0.65 s/m clay shaft, 0.5 s/m toe: Hannigan et
   al. 2016, FHWA-NHI-16-009); they enter the surface through one more grid per group with
   the values changed (:data:`SENSITIVITY_FACTORS`, :meth:`ResponseSurface.with_dynamics`);
M. I with the toe from the CPT averaged about the tip (``Step.toe_average``): where the tip
   stands in sand, Alm & Hamre's sand toe applied to qt averaged from 1.5 D above to 1.5 D
   below the tip (:data:`TOE_HALF_WINDOW_DIAMETERS`; the base rule of ICP-05 and UWA-05:
   Jardine et al. 2005, Lehane et al. 2005; Schneider et al. 2008,
   doi:10.1061/(ASCE)1090-0241(2008)134:9(1227)) instead of qt at the tip (the model's, on
   the 0.5 m series: the base of an open pile is governed by the soil over a zone of about
   1.5 D about the tip, not by the reading at it); a tip in clay keeps the clay toe at its own
   qt (``AlmHamre2001(toe_qt_half_window=1.5 D)``). It fits the second grid simulated again
   with that toe (the shaft, and so the fatigue tables, unchanged);
N. the final step as blow-by-blow installations: every held-out pile driven with its fold's
   fit from 0.5 m above its first record depth to 0.5 m below its last, each blow from the
   state the last left (the residual stress kept), the blow energy the record's at the tip,
   the SRD rebuilt every 0.1 m, the blows counted in the metre of their tip
   (:func:`install_pile`); direct runs, scored beside the per-depth model's direct runs at
   the same fits;
O. I with the SRD at the pile estimated from its foundation's CPT and the site's: the CPT
   stands at the foundation, not at its piles, so per soil class the foundation's SRD at the
   tip depth is kriged towards the mean of the foundations at that depth
   (:func:`simple_kriging_one_sample`, :meth:`ResponseSurface.with_site_weight`), with the
   correlation between the soil at the CPT and at the piles chosen per fold among
   0.25-1 by the training objective (1: I); a step of the surface (the prediction piles and
   N drive with the SRD of their foundation's CPT).

What bounds them (:func:`departures_from_the_depth_mean`): the piles of one foundation share
its CPT, so the pile-to-pile spread about their mean at each depth is beyond any model of
the soil; and a model beats the depth mean only where its departures from its own depth
mean follow the foundations' departures from the records' (correlation above half the ratio
of their spreads). Both are reported for the final step, with its departures split into the
soil's part (the blow energy of every record at the site's mean at its depth) and the
energy's (:func:`departure_parts`).

Cost: the blow counts of every calibration record are simulated on a grid of common SRD
multipliers x reference energies, twice (grid 1 at the method's SRD; grid 2 at the SRD
distribution of the all-pile fit of step D on grid 1, so that the folds' class multipliers are small
deviations about it); the folds fit on a :class:`ResponseSurface` (bilinear in log count, log
multiplier, log energy), whose error against direct runs at the final values is reported. The
fatigue factor enters the surface through each record's sand and clay shaft SRD computed
(statically, :func:`shaft_by_class`) at the factors :data:`FATIGUE_RATES`: the change of the
SRD's total, like the class multipliers; the change of its distribution along the shaft is
what the direct runs at the final values check. The final model (the fit of I's parameters on
all calibration piles, on the averaged toe's grid if :data:`FINAL_STEP` has ``toe_average``:
the last physics step) predicts the prediction piles from direct runs. Outputs:
``cross_validation_steps.csv`` (per step: CV RMSE, bias, the baseline's, the folds' parameter
ranges), ``cross_validation_records.csv`` (every record:
measured, baseline, each step's prediction), ``cross_validation_piles.csv`` (per pile: RMSE
and bias of the baseline and of every step over its scored records),
``prediction_piles_blowcount.csv`` (the final model's blow count, beside it the blend with the
depth mean of the calibration foundations and that mean) and ``isfog_backanalysis.json``;
``--cache DIR`` keeps the grids' and direct runs' blow counts, keyed by all their inputs, so
that a rerun only fits; with ``--docs``, the docs' data file
``docs/data/isfog_backanalysis.json`` too (benchmarks/doc_data.py's format: the table and the
quoted numbers of docs/validation.md, the summary as its values). ``--docs-from RESULT_JSON``
writes the docs' data file from an earlier run's ``isfog_backanalysis.json`` without running.

Outputs in DIR: ``calibration_fit.csv`` (RMSE and bias = mean of predicted - measured, per
pile and overall),
``calibration_summary.json`` (fitted values, RMSE, bias, ranges, assumptions, run time),
``calibration_blowcount.csv`` (every calibration record: measured and predicted),
``prediction_piles_blowcount.csv`` (``location_id``, ``z [m]``, ``blowcount [blows/m]`` at
every whole metre where the prediction piles were driven: where their record gives a hammer
energy), ``prediction_details.csv``, ``calibration_profiles.png``, ``calibration_fit.png``,
``prediction_piles.png``.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import os
import shlex
import sys
import tempfile
import time
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

import numpy as np
from doc_data import write_doc_data

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_DATA = ROOT.parent / "shared" / "reference" / "isfog2020"

REFUSAL_COUNT = 1000.0
"""Blow count reported for a refusal (set below the engine's smallest set) [blows/m]: the
refusal criterion of 250 blows/0.25 m."""
COUNT_FLOOR = 1.0
"""Blow counts below this [blows/m] (a pile run: 0) enter the log interpolation as this."""
HALF_METRE_OPTIONS = dict(missing="interpolate", negative_fs="zero")
"""Reading of the 0.5 m CPT series (three foundations have a slightly negative fs at 0.5 m:
zero drift of the sleeve, set to 0)."""
FULLRES_OPTIONS = dict(push_column="push (derived)", skip_push_start=0.3,
                       missing="interpolate", duplicate_depths="average", negative_fs="zero")
"""Cleaning of the full-resolution CPTs (their README: drop the first ~0.3 m of every push)."""
PREDICTION_CSV_COLUMNS = ("location_id", "z [m]", "blowcount [blows/m]")
"""Columns of prediction_piles_blowcount.csv (blow count 0: the pile runs under the weight of
pile and hammer, its SRD being below it)."""


# ----------------------------------------------------------------------------- model
@dataclass(frozen=True)
class Model:
    """Every assumption of the back-analysis (module docstring), the same for every pile."""

    hammer: str = "ihc_s800"
    stick_up: float = 10.0              # [m] pile length = final penetration + stick-up
    outer_diameter: float = 2.48        # [m]
    segment_length: float = 0.5         # [m]
    gauge_depth: float = 2.0            # [m] below the pile head
    duration: float = 0.2               # [s] blow window
    sand_unit_weight: float = 10.0e3    # [N/m^3] submerged
    clay_unit_weight: float = 9.0e3     # [N/m^3] submerged
    sand_delta: float = 29.0            # [deg] constant-volume interface friction angle
    ic_boundary: float = 2.6            # [-] Robertson (2009)
    quake_shaft: float = 0.0025         # [m]
    quake_toe: float = 0.0025           # [m]
    damping_sand: float = 0.16          # [s/m] Smith shaft damping, sand
    damping_clay: float = 0.65          # [s/m] Smith shaft damping, clay
    damping_toe: float = 0.5            # [s/m]
    net_area_ratio: float = 0.8         # [-] cone
    fullres_min_layer: float = 0.5      # [m] thinnest layer kept from a full-resolution CPT
    fullres_toe_window: float = 1.0     # [m] toe averaging window, full-resolution CPT
    sand_toe_factor: float = 0.10       # [-] the 2018 revision (0.15: Alm & Hamre 2001)
    fatigue_rate: float = 1.0           # [-] factor on Alm & Hamre's friction-fatigue rate k
    faces: str | None = None            # friction faces; None: the coring default
    blows_per_depth: int = 1            # > 1: each blow starts from the state the last left
    srd_sand: float = 1.0               # [-] multiplier of the shaft SRD in sand
    srd_clay: float = 1.0               # [-] multiplier of the shaft SRD in clay
    srd_toe: float = 1.0                # [-] multiplier of the toe SRD
    # the toe's quake and damping where the toe stands in clay (None: quake_toe, damping_toe,
    # the values in sand); fields added later than the cache's keys, so they enter a key only
    # when set (:func:`model_key`)
    quake_toe_clay: float | None = field(default=None, repr=False)   # [m]
    damping_toe_clay: float | None = field(default=None, repr=False)  # [s/m]
    # the toe from qt averaged over the tip +- this many diameters D (ICP-05 / UWA-05: 1.5;
    # None: qt at the tip, or the full-resolution CPT's toe window), :func:`srd_source`
    toe_qt_half_window_diameters: float | None = field(default=None, repr=False)  # [-]

    def toe_dynamics(self, toe_in_sand: bool) -> tuple[float, float]:
        """(quake [m], Smith damping [s/m]) of the toe standing in sand or clay."""
        if toe_in_sand:
            return self.quake_toe, self.damping_toe
        return (self.quake_toe if self.quake_toe_clay is None else self.quake_toe_clay,
                self.damping_toe if self.damping_toe_clay is None else self.damping_toe_clay)


def model_key(model: Model) -> str:
    """The text of ``model`` in a cache key: its repr, and each field left out of the repr
    (added later) only when it is set, so that the keys of runs without it stay valid."""
    extra = [f"{f.name}={getattr(model, f.name)!r}" for f in fields(model)
             if not f.repr and getattr(model, f.name) is not None]
    return repr(model) + ("" if not extra else "+" + ",".join(extra))


@dataclass(frozen=True)
class PileRecord:
    """One pile of the records: geometry, CPT and the whole-metre depths it was driven at.

    depths : whole-metre tip depths [m]; energy : normalised hammer energy there [-];
    measured : blow count there [blows/m] (None for a prediction pile);
    cpt_file, cpt_options : where and how its CPT is read; fullres : a full-resolution CPT.
    """

    location_id: str
    cpt_group: str
    wall_thickness: float
    final_penetration: float
    depths: np.ndarray
    energy: np.ndarray
    measured: np.ndarray | None
    cpt_file: str
    cpt_options: dict
    fullres: bool = False
    enthru: np.ndarray | None = None


def driving_system(model: Model) -> dict:
    """The classic driving system of the hammer class (GRLWEAP's model of a hydrohammer),
    ESTIMATES scaled from GRLWEAP's IHC S-4000 model (anvilwave/examples/grlweap_s4000.toml: hammer
    cushion 3.8487e10 N/m for a ram face of 1.23044 m, CoR 0.8, round-out 3 mm; housing
    2 x 109.25 t on springs of 2.11e11 N/m for a 201.5 t ram; helmet 1.3 x the ram mass for a
    3.5 m pile): the striker contact by the ram's face area, the housing (one mass) and its
    spring by the ram mass, the helmet (anvil and pile sleeve of a 2.48 m pile) = the ram
    mass. Returns the ``[anvil.classic]`` values (SI)."""
    from anvilwave.hammer.database import load_hammer

    hammer = load_hammer(model.hammer)
    ram_mass = float(np.sum(hammer.ram.mass))
    face = (float(hammer.ram.toe_diameter) / 1.23044) ** 2
    return {"hammer": hammer.name, "rated_energy [J]": float(hammer.rated_energy),
            "ram_mass [kg]": ram_mass, "efficiency [-]": float(hammer.efficiency),
            "helmet_mass [kg]": ram_mass,
            "hammer_cushion_stiffness [N/m]": 3.8487e10 * face,
            "hammer_cushion_restitution [-]": 0.8, "hammer_cushion_round_out [m]": 0.003,
            "assembly_mass [kg]": 1.08 * ram_mass,
            "assembly_stiffness [N/m]": 2.109736e11 * ram_mass / 201_544.0,
            "assembly_restitution [-]": 0.85, "assembly_round_out [m]": 0.003}


def system_toml(pile: PileRecord, model: Model) -> str:
    """The system file of one pile (its SRD is rebuilt per tip depth, :func:`simulate_pile`;
    the ``[soil] srd`` rows are a placeholder)."""
    ds = driving_system(model)
    length = pile.final_penetration + model.stick_up
    t = pile.wall_thickness
    area = math.pi * (model.outer_diameter - t) * t
    contact = 210e9 * area / model.segment_length  # GRLWEAP: E A / dx of the first segment
    return f"""
[simulation]
duration = {model.duration!r}
gravity = 9.81

[hammer]
database = "{model.hammer}"

[anvil]
model = "classic"

[anvil.classic]
helmet_mass = {ds["helmet_mass [kg]"]!r}
assembly_mass = {ds["assembly_mass [kg]"]!r}
assembly_stiffness = {ds["assembly_stiffness [N/m]"]!r}
assembly_restitution = {ds["assembly_restitution [-]"]!r}
assembly_round_out = {ds["assembly_round_out [m]"]!r}
pile_contact_stiffness = {contact!r}
pile_contact_round_out = 0.003

[anvil.classic.hammer_cushion]
stiffness = {ds["hammer_cushion_stiffness [N/m]"]!r}
restitution = {ds["hammer_cushion_restitution [-]"]!r}
round_out = {ds["hammer_cushion_round_out [m]"]!r}

[pile]
segment_length = {model.segment_length!r}
gauge_depth = {model.gauge_depth!r}

[[pile.sections]]
length = {length!r}
outer_diameter = {model.outer_diameter!r}
wall_thickness = {t!r}
youngs_modulus = 210e9
density = 7850.0

[soil]
model = "smith-viscous"
penetration = {pile.final_penetration!r}
quake_shaft = {model.quake_shaft!r}
quake_toe = {model.quake_toe!r}
damping_shaft = {model.damping_sand!r}
damping_toe = {model.damping_toe!r}
srd = [[0.0, 1.0, 1.0], [{length!r}, 1.0, 1.0]]
"""


def soil_profile(pile: PileRecord, model: Model):
    """The pile's CPT and its Robertson (2009) sand / clay layers."""
    from anvilwave.pile.soil.cpt import read_cpt_csv
    from anvilwave.pile.soil.cpt_classification import soil_layers_from_cpt
    from anvilwave.pile.soil.profile import SoilProfile

    cpt = read_cpt_csv(pile.cpt_file, **pile.cpt_options)
    layers, _ = soil_layers_from_cpt(
        cpt, sand_unit_weight=model.sand_unit_weight, clay_unit_weight=model.clay_unit_weight,
        sand_interface_friction_angle=model.sand_delta, net_area_ratio=model.net_area_ratio,
        boundary=model.ic_boundary,
        min_layer_thickness=model.fullres_min_layer if pile.fullres else 0.0)
    return SoilProfile(layers, cpt=cpt, net_area_ratio=model.net_area_ratio)


def srd_source(pile: PileRecord, model: Model, profile, fatigue_rate: float | None = None):
    """The Alm & Hamre (2001) SRD source of a pile (``fatigue_rate``: the factor on the
    friction-fatigue rate, default the model's). The unit toe resistance: the method's at qt
    of the tip; with ``model.toe_qt_half_window_diameters`` (n) the method's toe formula at
    the tip applied to qt averaged over the tip +- n D (ICP-05 / UWA-05 practice, n = 1.5:
    ``AlmHamre2001(toe_qt_half_window=n D)``), else for a full-resolution CPT the unit toe
    averaged over ``model.fullres_toe_window``."""
    from anvilwave.config.drive import SrdSource
    from anvilwave.pile.soil.profile import AlmHamre2001

    rate = model.fatigue_rate if fatigue_rate is None else fatigue_rate
    n = model.toe_qt_half_window_diameters
    half = 0.0 if n is None else n * model.outer_diameter
    return SrdSource("alm-hamre-2001", profile, AlmHamre2001(
        sand_toe_factor=model.sand_toe_factor,
        toe_window=model.fullres_toe_window if pile.fullres and half == 0.0 else 0.0,
        fatigue_rate_factor=rate, toe_qt_half_window=half), "coring", model.faces)


def shaft_by_class(job: tuple) -> dict:
    """Sand and clay shaft SRD [N] of one pile at every depth for every friction-fatigue rate
    factor (no blows: the static SRD only).

    job : (PileRecord, Model, rate factors [-]). Returns ``sand`` and ``clay``, each of shape
    (depths, rates), with the model's class multipliers applied as in :func:`simulate_pile`.
    """
    from anvilwave.config.drive import pile_soil_at

    pile, model, rates = job
    cfg = pile_system(pile, model)
    profile = soil_profile(pile, model)
    seg = cfg.pile_soil.pile.discretise()
    length = cfg.pile_soil.pile.length
    out = {k: np.zeros((len(pile.depths), len(rates))) for k in ("sand", "clay")}
    for ir, rate in enumerate(rates):
        srd = srd_source(pile, model, profile, float(rate))
        for iz, tip in enumerate(pile.depths):
            ps, _, _ = pile_soil_at(cfg.pile_soil, srd, float(tip), 1.0)
            cap_shaft = ps.soil.capacities[0]
            sand = segment_is_sand(profile, seg, length, float(tip))
            out["sand"][iz, ir] = float(np.sum(cap_shaft[sand])) * model.srd_sand
            out["clay"][iz, ir] = float(np.sum(cap_shaft[~sand])) * model.srd_clay
    return out


def segment_is_sand(profile, seg, pile_length: float, tip: float) -> np.ndarray:
    """Per pile segment: is the soil at the middle of its embedded part sand (Robertson)."""
    top = np.clip(seg.top - (pile_length - tip), 0.0, tip)
    bottom = np.clip(seg.top + seg.length - (pile_length - tip), 0.0, tip)
    return np.asarray(profile.is_sand[profile.layer_index(0.5 * (top + bottom))], bool)


def toe_in_sand(profile, tip: float) -> bool:
    """Does the toe at ``tip`` [m] stand in sand (Robertson; the deeper layer on a
    boundary)?"""
    return bool(profile.is_sand[int(np.asarray(profile.layer_index(tip)).reshape(-1)[0])])


def toe_classes(piles, model: Model) -> np.ndarray:
    """Per record of ``piles`` (their depths in order): does the toe stand in sand."""
    out = []
    for p in piles:
        profile = soil_profile(p, model)
        out.extend(toe_in_sand(profile, float(z)) for z in p.depths)
    return np.array(out, bool)


def shaft_damping(profile, seg, pile_length: float, tip: float, shaft: np.ndarray,
                  model: Model) -> float:
    """Smith shaft damping of a tip depth [s/m]: the sand and clay factors weighted by the
    static resistance of each segment (sum J_i R_i / sum R_i, the total dashpot kept)."""
    total = float(np.sum(shaft))
    if total <= 0.0:
        return model.damping_sand
    sand = segment_is_sand(profile, seg, pile_length, tip)
    j = np.where(sand, model.damping_sand, model.damping_clay)
    return float(np.sum(j * shaft) / total)


def pile_system(pile: PileRecord, model: Model):
    """The :class:`~anvilwave.config.system.SystemConfig` of one pile (:func:`system_toml`)."""
    from anvilwave.config.system import load_system

    with tempfile.TemporaryDirectory(prefix="isfog_") as tmp:
        path = Path(tmp) / f"{pile.location_id}.toml"
        path.write_text(system_toml(pile, model))
        return load_system(path)


def pile_engine(pile: PileRecord, model: Model) -> tuple:
    """What a pile's blows need: (its system, its engine, its soil profile, its SRD source,
    the weight of pile and hammer on the soil [N])."""
    from anvilwave.analyses.drive import driving_weight
    from anvilwave.engine.direct import build_engine

    cfg = pile_system(pile, model)
    engine = build_engine(cfg)
    profile = soil_profile(pile, model)
    return (cfg, engine, profile, srd_source(pile, model, profile),
            driving_weight(cfg, engine.static_head_force))


def soil_at_tip(cfg, srd, profile, model: Model, tip: float) -> tuple:
    """The pile and soil of one tip depth [m] with the model's class multipliers and soil
    dynamics: (PileSoil with that soil, its shaft capacities per segment [N] and toe capacity
    [N], per segment: in sand, the Smith shaft damping [s/m], the toe quake [m])."""
    from anvilwave.config.drive import pile_soil_at

    ps, _, _ = pile_soil_at(cfg.pile_soil, srd, tip, 1.0)
    cap_shaft, cap_toe = ps.soil.capacities
    seg = cfg.pile_soil.pile.discretise()
    length = cfg.pile_soil.pile.length
    sand = segment_is_sand(profile, seg, length, tip)
    cap_shaft = cap_shaft * np.where(sand, model.srd_sand, model.srd_clay)
    cap_toe = cap_toe * model.srd_toe
    j = shaft_damping(profile, seg, length, tip, cap_shaft, model)
    quake_toe, damping_toe = model.toe_dynamics(toe_in_sand(profile, tip))
    soil = replace(ps.soil, capacities=(cap_shaft, cap_toe), damping_shaft=j,
                   quake_toe=quake_toe, damping_toe=damping_toe)
    return replace(ps, soil=soil), cap_shaft, cap_toe, sand, j, quake_toe


def simulate_pile(job: tuple) -> dict:
    """Blow counts of one pile at every depth for every (multiplier, reference energy).

    job : (PileRecord, Model, reference energies [J], SRD multipliers [-]).
    Returns arrays of shape (multipliers, energies, depths): ``count`` [blows/m] (refusal:
    :data:`REFUSAL_COUNT`; a pile run: 0), ``enthru`` [J], ``compression`` and ``tension``
    [Pa]; and per depth ``srd_shaft``, ``srd_toe`` [N] (multiplier 1), ``damping_shaft``
    [s/m] and ``run_multiplier`` [-], the SRD multiplier at and below which the pile runs
    under its weight (the SRD scales with the multiplier, so the threshold is exact).
    """
    from anvilwave.analyses.drive import blow_count, set_of_blow

    pile, model, energies, multipliers = job
    cfg, engine, profile, srd, weight = pile_engine(pile, model)
    shape = (len(multipliers), len(energies), len(pile.depths))
    out = {k: np.full(shape, np.nan) for k in ("count", "enthru", "compression", "tension")}
    per_depth = {k: np.zeros(len(pile.depths)) for k in ("srd_shaft", "srd_toe",
                                                          "srd_shaft_sand", "damping_shaft",
                                                          "run_multiplier")}
    for iz, tip in enumerate(pile.depths):
        ps, cap_shaft, cap_toe, sand, j, quake_toe = soil_at_tip(
            cfg, srd, profile, model, float(tip))
        shaft, toe = float(np.sum(cap_shaft)), float(cap_toe)
        per_depth["srd_shaft"][iz], per_depth["srd_toe"][iz] = shaft, toe
        per_depth["srd_shaft_sand"][iz] = float(np.sum(cap_shaft[sand]))
        per_depth["damping_shaft"][iz] = j
        per_depth["run_multiplier"][iz] = weight / (shaft + toe) if shaft + toe > 0 else np.inf
        for im, m in enumerate(multipliers):
            if m * (shaft + toe) <= weight:  # the pile runs under the weight: no blows
                out["count"][im, :, iz] = 0.0
                continue
            soil = replace(ps.soil, capacities=(m * cap_shaft, m * cap_toe))
            eng = engine.with_pile_soil(replace(ps, soil=soil))
            try:
                state = eng.static_state()
            except ValueError:  # no static equilibrium under the weight: a run
                out["count"][im, :, iz] = 0.0
                continue
            for ie, e_ref in enumerate(energies):
                velocity = cfg.hammer.impact_velocity_at(float(pile.energy[iz] * e_ref))
                blow, start = None, state
                for _ in range(model.blows_per_depth):
                    blow = eng.blow(state=start, impact_velocity=velocity,
                                    duration=model.duration, record=False, energy=False)
                    start = blow.final_state
                count = blow_count(set_of_blow(blow, "permanent", quake_toe))
                out["count"][im, ie, iz] = min(count, REFUSAL_COUNT)
                out["enthru"][im, ie, iz] = blow.emx_gauge
                out["compression"][im, ie, iz] = blow.max_compression_stress
                out["tension"][im, ie, iz] = blow.max_tension_stress
    return {**out, **per_depth}


INSTALL_SRD_UPDATE = 0.1
"""Tip advance [m] after which the installation's SRD is rebuilt at the tip
(:func:`install_pile`)."""
INSTALL_RUN_STEP = 0.05
"""Step [m] by which the installation's tip runs through soil that does not carry the
weight of pile and hammer."""


def install_pile(job: tuple) -> dict:
    """Blow-by-blow installation of one pile over its record (the residual stress kept).

    job : (PileRecord, Model, reference energy E_ref [J]). The installation starts at rest,
    in static equilibrium under the weight of pile and hammer, 0.5 m above the first record
    depth, and drives blow after blow, each from the state the last left (the shaft and the
    toe keep their residual loads), to 0.5 m below the last; the blow energy at the tip is
    the record's normalised energy (linear between its whole metres) times E_ref; the SRD
    (the model's class multipliers and soil dynamics, :func:`soil_at_tip`) is rebuilt every
    :data:`INSTALL_SRD_UPDATE` of penetration. Where the SRD does not carry the weight the
    tip runs (in steps of :data:`INSTALL_RUN_STEP`, no blows) and the state restarts from
    static equilibrium below. Returns ``count`` [blows/m] per record depth z: the blows
    struck with the tip in [z - 0.5, z + 0.5) m (the record's whole-metre count;
    :data:`REFUSAL_COUNT` from a window that takes more blows on), and ``blows`` [-], the
    blows struck.
    """
    pile, model, e_ref = job
    cfg, engine, profile, srd, weight = pile_engine(pile, model)
    depths = np.asarray(pile.depths, float)
    edges = np.append(depths - 0.5, depths[-1] + 0.5)
    counts = np.zeros(depths.size)
    tip, end = float(edges[0]), float(edges[-1])
    eng = state = None
    built_at = -np.inf
    blows = 0
    while tip < end:
        if state is None or tip - built_at >= INSTALL_SRD_UPDATE:
            ps, cap_shaft, cap_toe, *_ = soil_at_tip(cfg, srd, profile, model, tip)
            built_at = tip
            if float(np.sum(cap_shaft)) + float(cap_toe) <= weight:
                tip, state = tip + INSTALL_RUN_STEP, None  # the pile runs: no blow
                continue
            eng = engine.with_pile_soil(ps)
            if state is None:
                try:
                    state = eng.static_state()
                except ValueError:  # no static equilibrium under the weight: a run
                    tip += INSTALL_RUN_STEP
                    continue
        window = int(np.searchsorted(edges, tip, side="right")) - 1
        if counts[window] >= REFUSAL_COUNT:
            counts[window:] = REFUSAL_COUNT
            break
        energy = float(np.interp(tip, depths, pile.energy)) * e_ref
        blow = eng.blow(state=state, impact_velocity=cfg.hammer.impact_velocity_at(energy),
                        duration=model.duration, record=False, energy=False)
        state = blow.final_state
        counts[window] += 1.0
        blows += 1
        tip += max(float(blow.permanent_set), 0.0)
    return {"count": counts, "blows": np.array(blows)}


def _install(job: tuple) -> dict:
    """:func:`install_pile`, its errors named after the pile (and picklable)."""
    try:
        return install_pile(job)
    except Exception as exc:
        raise RuntimeError(f"pile {job[0].location_id}: {type(exc).__name__}: {exc}") from None


def cached_jobs(cache: Path | None, tag: str, function, jobs: list, workers: int) -> list[dict]:
    """``function`` over ``jobs`` (each (PileRecord, Model, numbers...)) in ``workers``
    processes, each job's result read from / written to ``cache`` under a name hashing its
    inputs (as :func:`cached`, one file per job: the jobs may have different models)."""
    def path_of(job):
        p, model, *rest = job
        key = repr((tag, _Raw(model_key(model)), [np.asarray(r, float).tolist() for r in rest],
                    _pile_key(p)))
        return Path(cache) / f"{tag}-{hashlib.sha256(key.encode()).hexdigest()[:20]}.npz"

    paths = [path_of(j) for j in jobs] if cache is not None else [None] * len(jobs)
    todo = [i for i, p in enumerate(paths) if p is None or not p.exists()]
    done = dict(zip(todo, _map(function, [jobs[i] for i in todo], workers), strict=True))
    out = []
    for i, path in enumerate(paths):
        if i in done:
            if path is not None:
                Path(cache).mkdir(parents=True, exist_ok=True)
                np.savez(path, **{k: np.asarray(v) for k, v in done[i].items()})
            out.append(done[i])
        else:
            with np.load(path) as z:
                out.append({k: z[k] for k in z.files})
    return out


# ----------------------------------------------------------------------------- records
def _rows(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def _pile_records(data: Path, kind: str, only: list[str] | None
                  ) -> tuple[Path, list[tuple[dict, list[dict]]]]:
    """The half-metre series file of the ``kind`` ("calibration" or "prediction") piles and,
    per pile of its summary file (only those in ``only`` when given), (summary row, its
    series rows); an unknown name in ``only`` stops the run naming it."""
    series = data / f"{kind}_piles_0p5m.csv"
    by_pile: dict[str, list[dict]] = {}
    for row in _rows(series):
        by_pile.setdefault(row["location_id"], []).append(row)
    summaries = [s for s in _rows(data / f"{kind}_piles.csv")
                 if not only or s["location_id"] in only]
    missing = sorted(set(only or ()) - {s["location_id"] for s in summaries})
    if missing:
        raise SystemExit(f"unknown {kind} piles: {', '.join(missing)}")
    return series, [(s, by_pile[s["location_id"]]) for s in summaries]


def _number(text: str) -> float:
    return float(text) if text.strip() else math.nan


def _whole_metre(z: float) -> bool:
    return abs(z - round(z)) < 1e-6


def calibration_piles(data: Path, only: list[str] | None = None) -> list[PileRecord]:
    """The calibration piles: blow counts at the whole metres between their first and last
    blow-count depth (calibration_piles.csv), with the normalised hammer energy there."""
    series, records = _pile_records(data, "calibration", only)
    piles = []
    for summary, rows in records:
        pid = summary["location_id"]
        first = float(summary["first blowcount depth [m]"])
        last = float(summary["last blowcount depth [m]"])
        z, energy, measured, enthru = [], [], [], []
        for row in rows:
            depth = float(row["z [m]"])
            count = _number(row["blowcount [blows/m]"])
            e = _number(row["normalised hammer energy [-]"])
            if (_whole_metre(depth) and first - 1e-6 <= depth <= last + 1e-6
                    and math.isfinite(count) and math.isfinite(e) and e > 0.0):
                z.append(depth)
                energy.append(e)
                measured.append(count)
                enthru.append(_number(row["normalised ENTHRU [-]"]))
        piles.append(PileRecord(
            pid, summary["cpt_group"], float(summary["bottom wall thickness [mm]"]) / 1e3,
            float(summary["final penetration [m]"]), np.array(z), np.array(energy),
            np.array(measured), str(series), {"rows_where": {"location_id": pid},
                                              **HALF_METRE_OPTIONS},
            enthru=np.array(enthru)))
    return piles


def prediction_piles(data: Path, only: list[str] | None = None,
                     cpt: str = "0p5m") -> list[PileRecord]:
    """The prediction piles at every whole metre where their record gives a hammer energy
    (from the first to the last such depth: where they were driven). ``cpt``: "0p5m" (the
    0.5 m series, the processing of the calibration piles) or "fullres"."""
    series, records = _pile_records(data, "prediction", only)
    piles = []
    for summary, pile_rows in records:
        pid = summary["location_id"]
        rows = [(float(r["z [m]"]), _number(r["normalised hammer energy [-]"]),
                 _number(r["normalised ENTHRU [-]"])) for r in pile_rows]
        driven = [z for z, e, _ in rows if math.isfinite(e) and e > 0.0]
        first, last = math.ceil(min(driven) - 1e-6), math.floor(max(driven) + 1e-6)
        known = [(z, e, t) for z, e, t in rows if math.isfinite(e) and math.isfinite(t)]
        z_all, e_all, t_all = (np.array(c) for c in zip(*known, strict=True))
        depths = np.arange(first, last + 1, dtype=float)
        energy = np.interp(depths, z_all, e_all)  # whole metres carry their own value
        enthru = np.interp(depths, z_all, t_all)
        group = summary["cpt_group"]
        fullres = data / f"cpt_fullres_{group.replace('/', '-')}.csv"
        if cpt == "fullres" and fullres.exists():
            source, options, is_full = str(fullres), dict(FULLRES_OPTIONS), True
        else:
            source, options, is_full = (str(series), {"rows_where": {"location_id": pid},
                                                      **HALF_METRE_OPTIONS}, False)
        piles.append(PileRecord(pid, group, float(summary["bottom wall thickness [mm]"]) / 1e3,
                                float(summary["final penetration [m]"]), depths, energy, None,
                                source, options, is_full, enthru))
    return piles


# ----------------------------------------------------------------------------- runs
def run_piles(piles, model: Model, energies, multipliers, workers: int) -> list[dict]:
    """:func:`simulate_pile` for every pile, over ``workers`` processes."""
    return _map(_simulate, [(p, model, np.asarray(energies, float),
                             np.asarray(multipliers, float)) for p in piles], workers)


def _map(function, jobs: list, workers: int) -> list:
    """``function`` over ``jobs``, in ``workers`` processes (forked) or in this one."""
    if workers <= 1 or len(jobs) <= 1:
        return [function(j) for j in jobs]
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(min(workers, len(jobs)),
                             mp_context=mp.get_context("fork")) as pool:
        return list(pool.map(function, jobs))


def cached(cache: Path | None, tag: str, run, piles, model: Model, *grid) -> list[dict]:
    """``run(piles, model, *grid)`` (a list of per-pile dicts of arrays), read from / written
    to ``cache`` (a folder; None: no cache) under a name that hashes every input of the run:
    the piles' records, the model and the grid (the results depend on nothing else but the
    code and the records' files)."""
    if cache is None:
        return run(piles, model, *grid)
    key = repr((tag, _Raw(model_key(model)), [np.asarray(g, float).tolist() for g in grid],
                [_pile_key(p) for p in piles]))
    path = Path(cache) / f"{tag}-{hashlib.sha256(key.encode()).hexdigest()[:20]}.npz"
    if path.exists():
        with np.load(path) as z:
            n = int(z["piles"])
            return [{k.split("/", 1)[1]: z[k] for k in z.files if k.startswith(f"{i}/")}
                    for i in range(n)]
    results = run(piles, model, *grid)
    Path(cache).mkdir(parents=True, exist_ok=True)
    arrays = {f"{i}/{k}": np.asarray(v) for i, r in enumerate(results) for k, v in r.items()}
    np.savez(path, piles=len(results), **arrays)
    return results


def _pile_key(p: PileRecord) -> tuple:
    """What a pile's runs depend on, in a cache key: its name, CPT file, geometry, record
    depths and energy trace."""
    return (p.location_id, p.cpt_file, p.final_penetration, p.wall_thickness,
            p.depths.tolist(), p.energy.tolist())


class _Raw(str):
    """A string whose repr is itself (a model's key inside a cache key reads as its repr)."""

    def __repr__(self) -> str:
        return str(self)


def run_shaft_by_class(piles, model: Model, rates, workers: int) -> list[dict]:
    """:func:`shaft_by_class` for every pile, over ``workers`` processes."""
    return _map(shaft_by_class, [(p, model, np.asarray(rates, float)) for p in piles], workers)


def _simulate(job: tuple) -> dict:
    """:func:`simulate_pile`, its errors named after the pile (and picklable)."""
    try:
        return simulate_pile(job)
    except Exception as exc:
        raise RuntimeError(f"pile {job[0].location_id}: {type(exc).__name__}: {exc}") from None


def warm_up(model: Model, pile: PileRecord) -> None:
    """Load the compiled kernels once in this process (the pool's forks inherit them)."""
    short = replace(pile, depths=pile.depths[-1:], energy=pile.energy[-1:],
                    measured=None if pile.measured is None else pile.measured[-1:])
    simulate_pile((short, replace(model, duration=0.01), np.array([5e5]), np.array([1.0])))


# ----------------------------------------------------------------------------- fit
class GridInterpolator:
    """log(blow count) between the grid's nodes: shape-preserving piecewise cubic (PCHIP) in
    log(E_ref), linear in log(multiplier).

    energies : (nE,) reference energies [J]; multipliers : (nm,) [-]; counts : (nm, nE, n)
    blow counts of n records [blows/m]; run_multiplier : (n,) the multiplier at and below
    which each record's pile runs under its weight (blow count 0 there, exactly). The blow
    count jumps at that threshold (from 0 to tens of blows/m at the small energies of the
    first metres), so between a run node and the next one it is extrapolated from the two
    nodes above instead of interpolated.
    """

    def __init__(self, energies, multipliers, counts, run_multiplier=None):
        self.le = np.log(np.asarray(energies, float))
        self.lm = np.log(np.asarray(multipliers, float))
        self.lc = np.log(np.clip(np.asarray(counts, float), COUNT_FLOOR, REFUSAL_COUNT))
        self.run = (np.zeros(self.lc.shape[-1]) if run_multiplier is None
                    else np.asarray(run_multiplier, float))
        self._energy = None
        if self.le.size > 1:
            from scipy.interpolate import PchipInterpolator

            self._energy = [PchipInterpolator(self.le, self.lc[m], axis=0)
                            for m in range(self.lm.size)]

    @staticmethod
    def _weights(nodes: np.ndarray, x: float) -> tuple[int, float]:
        if nodes.size == 1:
            return 0, 0.0
        x = float(np.clip(x, nodes[0], nodes[-1]))
        i = int(np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2))
        return i, (x - nodes[i]) / (nodes[i + 1] - nodes[i])

    def __call__(self, energy: float, multiplier: float = 1.0) -> np.ndarray:
        """Blow counts [blows/m] at a reference energy [J] and SRD multiplier [-]."""
        x = float(np.clip(math.log(energy), self.le[0], self.le[-1]))
        im, wm = self._weights(self.lm, math.log(multiplier))

        def at(m):
            return self.lc[m, 0] if self._energy is None else self._energy[m](x)

        if self.lm.size == 1:
            lc = at(im)
        else:
            low, high = at(im), at(im + 1)
            lc = (1 - wm) * low + wm * high
            # the blow count jumps from 0 to a finite value at the run threshold: where the
            # lower node is a run, extrapolate from the two nodes above it instead
            lm = self.lm[im] + wm * (self.lm[im + 1] - self.lm[im])
            below = np.exp(self.lm[im]) <= self.run
            if np.any(below):
                slope = 0.0
                if im + 2 < self.lm.size:
                    slope = (at(im + 2) - high) / (self.lm[im + 2] - self.lm[im + 1])
                lc = np.where(below, high + slope * (lm - self.lm[im + 1]), lc)
        return np.where(multiplier <= self.run, 0.0, np.exp(lc))


def rmse(predicted, measured) -> float:
    d = np.asarray(predicted, float) - np.asarray(measured, float)
    return float(np.sqrt(np.mean(d * d)))


def fit(interp: GridInterpolator, measured: np.ndarray, with_multiplier: bool) -> dict:
    """E_ref (and the SRD multiplier) minimising the RMSE of the blow counts [blows/m]:
    a scan of the grid's box (log-spaced, 241 x 121 points), refined by Nelder-Mead inside it."""
    from scipy.optimize import minimize

    le, lm = interp.le, interp.lm
    if not with_multiplier or lm.size == 1:
        m_fixed = 1.0 if lm.size > 1 else float(np.exp(lm[0]))
        if lm.size > 1 and not (lm[0] - 1e-12 <= 0.0 <= lm[-1] + 1e-12):
            raise SystemExit("the energy-only fit needs the multiplier 1 inside the grid")
        lm_scan = np.array([math.log(m_fixed)])
    else:
        lm_scan = np.linspace(lm[0], lm[-1], 121)
    le_scan = np.linspace(le[0], le[-1], 241)
    best = (math.inf, 0.0, 0.0)
    for y in lm_scan:
        for x in le_scan:
            r = rmse(interp(math.exp(x), math.exp(y)), measured)
            if r < best[0]:
                best = (r, x, y)

    def objective(p):
        x = float(np.clip(p[0], le[0], le[-1]))
        y = float(np.clip(p[1], lm_scan[0], lm_scan[-1])) if lm_scan.size > 1 else lm_scan[0]
        return rmse(interp(math.exp(x), math.exp(y)), measured)

    start = [best[1], best[2]] if lm_scan.size > 1 else [best[1]]
    res = minimize(objective, start, method="Nelder-Mead",
                   options={"xatol": 1e-4, "fatol": 1e-6})
    x = float(np.clip(res.x[0], le[0], le[-1]))
    y = float(np.clip(res.x[1], lm_scan[0], lm_scan[-1])) if lm_scan.size > 1 else lm_scan[0]
    if objective([x, y]) > best[0]:
        x, y = best[1], best[2]
    predicted = interp(math.exp(x), math.exp(y))
    at_edge = bool(np.isclose(x, le[0]) or np.isclose(x, le[-1])
                   or (lm_scan.size > 1 and (np.isclose(y, lm[0]) or np.isclose(y, lm[-1]))))
    curve = [[float(math.exp(v)), rmse(interp(math.exp(v), math.exp(y)), measured)]
             for v in le_scan[::4]]
    return {"E_ref [J]": math.exp(x), "srd_multiplier [-]": math.exp(y),
            "rmse_interpolated [blows/m]": rmse(predicted, measured),
            "bias_interpolated [blows/m]": float(np.mean(predicted - measured)),
            "at_grid_edge": at_edge, "rmse_curve": curve}


def naive_baseline(train, held_out) -> list[np.ndarray]:
    """The baseline of the cross-validation: for each held-out pile, at each of its depths, the
    mean measured blow count [blows/m] of the ``train`` piles driven at that depth (NaN where
    none was)."""
    by_depth: dict[float, list[float]] = {}
    for p in train:
        for z, n in zip(p.depths, p.measured, strict=True):
            by_depth.setdefault(round(float(z), 6), []).append(float(n))
    return [np.array([float(np.mean(by_depth[round(float(z), 6)]))
                      if round(float(z), 6) in by_depth else math.nan for z in p.depths])
            for p in held_out]


def records_by_foundation_and_depth(group, depth) -> dict:
    """(foundation, depth [m] to 1e-6 m) -> the indices of its records, in order, for records
    of foundations ``group`` (n,) at depths ``depth`` (n,)."""
    members: dict = {}
    for i, key in enumerate(zip(np.asarray(group).tolist(),
                                np.round(np.asarray(depth, float), 6).tolist(), strict=True)):
        members.setdefault(key, []).append(i)
    return {k: np.asarray(v) for k, v in members.items()}


def departures_from_the_depth_mean(piles, groups, predicted) -> dict:
    """How much of the foundations' departures from the depth mean a model's predictions
    carry (the bound the naive baseline sets on a model of the records).

    piles : the records' piles (their measured counts) in the order of ``predicted``;
    groups : their foundations; predicted : per record, the model's blow count [blows/m]
    (a cross-validation's: every record predicted with its foundation held out).

    The departure of a record is its count minus the baseline (the mean of the other
    foundations at its depth, :func:`record_baselines`); the model's departure is its
    prediction minus the same mean of its own predictions of the other foundations. A
    model that keeps its departures and takes the depth trend from the records (the
    baseline plus its departure) beats the baseline exactly when its departures correlate
    with the measured ones by more than half the ratio of their spreads (in the records'
    own statistics: the mean square of d_m - d_p is below that of d_m when
    2 cov(d_m, d_p) > var(d_p)). The piles of one foundation share its CPT: the spread of
    their counts about the foundation's mean at each depth (pooled, n - 1 per depth) is what
    no model of the foundation's soil can give.

    Returns ``records [-]``, ``within_foundation_sd [blows/m]``, ``measured_sd``,
    ``model_sd`` [blows/m] (the departures' RMS), ``correlation [-]`` (measured and model
    departures), ``foundation_correlation [-]`` (the model's departure against the
    foundation's, its piles' mean at the depth, less the baseline), ``needed_correlation [-]``
    (model_sd / (2 measured_sd)) and ``trend_from_records_rmse [blows/m]`` (the baseline plus
    the model's departure, against the measured counts).
    """
    measured = np.concatenate([p.measured for p in piles])
    predicted = np.asarray(predicted, float)
    split = np.split(predicted, np.cumsum([p.depths.size for p in piles])[:-1])
    baseline = record_baselines(piles, groups)
    model_baseline = record_baselines([replace(p, measured=v) for p, v in
                                       zip(piles, split, strict=True)], groups)
    ok = np.isfinite(baseline) & np.isfinite(model_baseline) & np.isfinite(predicted)
    members = records_by_foundation_and_depth(
        np.concatenate([[p.cpt_group] * p.depths.size for p in piles]),
        np.concatenate([p.depths for p in piles]))
    mean_of = {k: float(np.mean(measured[v])) for k, v in members.items()}
    foundation = np.empty(measured.size)
    for k, v in members.items():
        foundation[v] = mean_of[k]
    spread = sum(float(np.sum((measured[v] - mean_of[k]) ** 2)) for k, v in members.items())
    dof = sum(len(v) - 1 for v in members.values())
    d_m = (measured - baseline)[ok]
    d_p = (predicted - model_baseline)[ok]
    d_f = (foundation - baseline)[ok]
    measured_sd = float(np.sqrt(np.mean(d_m * d_m)))
    model_sd = float(np.sqrt(np.mean(d_p * d_p)))

    def corr(a, b):  # about zero, as the mean squares above (NaN: no departures)
        scale = float(np.sqrt(np.sum(a * a) * np.sum(b * b)))
        return float(np.sum(a * b)) / scale if scale > 0.0 else math.nan

    return {"records [-]": int(ok.sum()),
            "within_foundation_sd [blows/m]": math.sqrt(spread / dof) if dof else math.nan,
            "measured_sd [blows/m]": measured_sd, "model_sd [blows/m]": model_sd,
            "correlation [-]": corr(d_m, d_p), "foundation_correlation [-]": corr(d_f, d_p),
            "needed_correlation [-]": model_sd / (2.0 * measured_sd),
            "trend_from_records_rmse [blows/m]": rmse(baseline[ok] + d_p, measured[ok])}


def departure_parts(whole: dict, soil: dict, energy: dict) -> dict:
    """A model's departures from its depth mean split in two parts that add up to them, the
    soil's (the model with every record's blow energy at the site's mean at its depth) and
    the energy's (the rest): each a :func:`departures_from_the_depth_mean` of the same
    records. Returns each part's RMS [blows/m] and correlation with the measured departures
    [-], and the two parts' correlation with each other [-] (from
    var(a + b) = var(a) + var(b) + 2 cov(a, b), the departures' means about zero as there)."""
    s, e = soil["model_sd [blows/m]"], energy["model_sd [blows/m]"]
    w = whole["model_sd [blows/m]"]
    return {"soil_part_sd [blows/m]": s, "soil_part_correlation [-]": soil["correlation [-]"],
            "energy_part_sd [blows/m]": e,
            "energy_part_correlation [-]": energy["correlation [-]"],
            "soil_energy_correlation [-]": ((w * w - s * s - e * e) / (2.0 * s * e)
                                            if s > 0.0 and e > 0.0 else math.nan)}


def per_pile_table(piles, predicted: list[np.ndarray]) -> list[dict]:
    rows = []
    for p, pred in zip(piles, predicted, strict=True):
        rows.append({"location_id": p.location_id, "cpt_group": p.cpt_group,
                     "points [-]": len(p.depths),
                     "rmse [blows/m]": rmse(pred, p.measured),
                     "bias [blows/m]": float(np.mean(pred - p.measured)),
                     "measured_mean [blows/m]": float(np.mean(p.measured)),
                     "predicted_mean [blows/m]": float(np.mean(pred))})
    every_p = np.concatenate(predicted)
    every_m = np.concatenate([p.measured for p in piles])
    rows.append({"location_id": "overall", "cpt_group": "",
                 "points [-]": int(every_m.size), "rmse [blows/m]": rmse(every_p, every_m),
                 "bias [blows/m]": float(np.mean(every_p - every_m)),
                 "measured_mean [blows/m]": float(np.mean(every_m)),
                 "predicted_mean [blows/m]": float(np.mean(every_p))})
    return rows


# ----------------------------------------------------------------------------- prediction
LOG_OFFSET = 5.0
"""Offset of the log misfit [blows/m]: log(N + 5) - log(N_measured + 5) keeps the shallow
records (a few blows/m, or 0 where the pile runs) from dominating the log fit."""
RESIDUAL_SCALE = {"log": 0.35, "blows": 20.0}
"""Typical misfit of one record (log: [-], blows: [blows/m]; about the records' own scatter
between piles under one CPT) that weighs the prior against the data in the fit."""
PRIOR_SD = math.log(2.0)
"""Prior standard deviation [-] of the log of each soil class's SRD multiplier about the
common one: a class's SRD within a factor 2 of the others' (the faces' rule alone changes
the shaft by 2 between codes, srd-methods.md)."""
CLASSES = ("sand", "clay", "toe")
EXPONENT_SD = 0.25
"""Prior standard deviation [-] of the exponent b of the energy law E = E_ref setting^b
about 1 (a blow energy proportional to the hammer's setting)."""
FATIGUE_RATES = tuple(2.0 ** np.arange(-4.0, 2.5, 1.0))
"""Factors on Alm & Hamre's friction-fatigue rate k at which each record's sand and clay
shaft SRD is computed (1/16 ... 4: from almost no fatigue to a decay four times as fast);
between them the SRD is interpolated linearly in log(factor), and the fit stays within."""
DYNAMICS = ("damping_sand", "damping_clay", "damping_toe_sand", "damping_toe_clay",
            "quake_toe_sand", "quake_toe_clay")
"""The soil's dynamic values that a step may fit, each as its ratio to the model's: the Smith
shaft damping in sand and in clay, and the toe's damping and quake where the toe stands in sand
and in clay (the model's: GRLWEAP's and Smith's customary values, :class:`Model`)."""
SENSITIVITY_FACTORS = {"damping_shaft": 2.0, "damping_toe": 2.0, "quake_toe": 4.0}
"""Per group of :data:`DYNAMICS`, the factor on the model's values of the grid that gives the
slope of log(blow count) in the log of the value (the shaft dampings of sand and clay together,
the toe's damping, the toe's quake: 2.5 to 10 mm, towards GRLWEAP's D/120 = 21 mm of a
plugged displacement toe)."""
DYNAMICS_GROUP = {"damping_sand": "damping_shaft", "damping_clay": "damping_shaft",
                  "damping_toe_sand": "damping_toe", "damping_toe_clay": "damping_toe",
                  "quake_toe_sand": "quake_toe", "quake_toe_clay": "quake_toe"}
DYNAMICS_SD = math.log(2.0)
"""Prior standard deviation [-] of the log of each dynamic value's ratio to the model's: the
customary values within a factor 2 at one standard deviation (the quakes 2.5 mm, the Smith
dampings 0.16 s/m sand and 0.65 s/m clay on the shaft, 0.5 s/m at the toe: GRLWEAP's and
Hannigan et al. 2016, :data:`anvilwave.pile.soil.models.SOIL_TYPE_SMITH_DAMPING`)."""
DYNAMICS_RANGE = (0.5, None)
"""Range of each dynamic ratio the fit may take [-]: from half the model's value (the slope
extrapolated) to its grid's factor (:data:`SENSITIVITY_FACTORS`, interpolated)."""
FATIGUE_SD = math.log(4.0)
"""Prior standard deviation [-] of log(fatigue rate factor) about 0 (the paper's rate): a
weak prior, the rate within a factor 4 of the paper's at one standard deviation."""


def simple_kriging_one_sample(sample, mean, correlation):
    """Simple kriging of a stationary random field at a point from one sample elsewhere.

    The best linear unbiased estimate of the field at the point, its mean known, from one
    reading: ``mean + correlation (sample - mean)``, with the estimation variance
    sigma^2 (1 - correlation^2) (Fenton & Griffiths 2008, Risk Assessment in Geotechnical
    Engineering, Wiley, ch. 4, doi:10.1002/9780470284704).

    Parameters
    ----------
    sample : array_like
        The reading at the sampled point [any unit].
    mean : array_like
        The field's mean [same unit].
    correlation : float
        The correlation coefficient between the field at the sample and at the point [-],
        in [0, 1].

    Returns
    -------
    numpy.ndarray
        The estimate at the point [same unit].
    """
    if not 0.0 <= correlation <= 1.0:
        raise ValueError(f"correlation must be in [0, 1], got {correlation!r}")
    sample, mean = np.asarray(sample, float), np.asarray(mean, float)
    return mean + correlation * (sample - mean)


def site_estimate(values, group, depth, weight: float) -> np.ndarray:
    """Per record, ``values`` (n,) or (n, k) estimated at its pile from its foundation's
    and the site's: at each depth the foundation's value (the mean of its piles' records
    there) kriged towards the mean of the foundations there (each foundation once) with the
    correlation ``weight`` (:func:`simple_kriging_one_sample`); what differs between the
    piles of one foundation (their walls) is kept. group, depth : (n,) each record's
    foundation and depth [m]."""
    values = np.asarray(values, float)
    out = values.copy()
    at_depth: dict = {}
    members_of = records_by_foundation_and_depth(group, depth)
    for key in sorted(members_of):  # (foundation, depth): each depth's foundations in order
        rows = members_of[key]
        at_depth.setdefault(key[1], []).append((rows, values[rows].mean(axis=0)))
    for members in at_depth.values():
        site = np.mean([foundation for _, foundation in members], axis=0)
        for rows, foundation in members:
            out[rows] = values[rows] + (simple_kriging_one_sample(foundation, site, weight)
                                        - foundation)
    return out


class ResponseSurface:
    """Blow counts of many records as a function of one reference energy and the SRD
    multipliers of sand shaft, clay shaft and toe, from a grid of direct runs.

    Each record (pile, tip depth) was simulated on a grid of common SRD multipliers x
    reference energies (:func:`simulate_pile`); the per-class multipliers enter through the
    record's effective multiplier m = (m_sand R_sand + m_clay R_clay + m_toe R_toe) / R (the
    distribution of the SRD between shaft and toe is that of multiplier 1, an approximation
    checked against direct runs, :func:`main`). log(blow count) is interpolated bilinearly in
    log(m) and log(energy); grid nodes where the pile runs under its weight are replaced by
    the extrapolation of the two nodes above (the count jumps from 0 there), and the count is
    0 exactly where m R is below the weight.

    energies, multipliers : grid [J], [-]; counts : (n, multipliers, energies) [blows/m];
    run : (n,) multiplier at and below which each record runs [-]; sand, clay, toe : (n,) SRD
    at multiplier 1 [N]; energy_factor : (n,) factor on the reference energy of each record
    [-] (1: the normalised hammer energy; ENTHRU / (0.75 x hammer energy) to drive with the
    recorded ENTHRU); setting : (n,) normalised hammer energy of each record [-] (for an
    energy law E = E_ref setting^b, b != 1); rates, sand_rate, clay_rate : friction-fatigue
    rate factors (r,) [-] and the sand and clay shaft SRD of each record at each (n, r) [N]
    (:func:`shaft_by_class`): a rate factor other than the grid's enters, like the class
    multipliers, through the effective multiplier (its change of the SRD's total; the change
    of its distribution along the shaft is checked against direct runs, :func:`main`).
    """

    def __init__(self, energies, multipliers, counts, run, sand, clay, toe,
                 energy_factor=None, setting=None, rates=None, sand_rate=None,
                 clay_rate=None):
        self.le = np.log(np.asarray(energies, float))
        self.lm = np.log(np.asarray(multipliers, float))
        lc = np.log(np.clip(np.asarray(counts, float), COUNT_FLOOR, REFUSAL_COUNT))
        self.run = np.asarray(run, float)
        for k in range(lc.shape[0]):
            ok = np.exp(self.lm) > self.run[k]
            if ok.all():
                continue
            if not ok.any():
                lc[k] = math.log(COUNT_FLOOR)
                continue
            i0 = int(np.argmax(ok))
            slope = ((lc[k, i0 + 1] - lc[k, i0]) / (self.lm[i0 + 1] - self.lm[i0])
                     if i0 + 1 < self.lm.size else np.zeros_like(lc[k, i0]))
            lc[k, :i0] = lc[k, i0][None, :] + np.multiply.outer(self.lm[:i0] - self.lm[i0],
                                                                slope)
        self.lc = lc
        self.sand, self.clay, self.toe = (np.asarray(v, float) for v in (sand, clay, toe))
        self.energy_factor = (np.ones(lc.shape[0]) if energy_factor is None
                              else np.asarray(energy_factor, float))
        self.setting = (np.ones(lc.shape[0]) if setting is None
                        else np.asarray(setting, float))
        self.lr = None if rates is None else np.log(np.asarray(rates, float))
        self.sand_rate = None if rates is None else np.asarray(sand_rate, float)
        self.clay_rate = None if rates is None else np.asarray(clay_rate, float)

    slopes: dict | None = None
    toe_sand: np.ndarray | None = None
    shaft_damping: tuple = (1.0, 1.0)
    grid_total: np.ndarray | None = None  # (n,) the SRD [N] the grid's multipliers scale

    def subset(self, rows) -> ResponseSurface:
        """The surface of the records ``rows`` (a boolean mask or indices)."""
        s = object.__new__(ResponseSurface)
        s.le, s.lm, s.lr = self.le, self.lm, self.lr
        s.shaft_damping = self.shaft_damping
        for k in ("lc", "run", "sand", "clay", "toe", "energy_factor", "setting"):
            setattr(s, k, getattr(self, k)[rows])
        for k in ("sand_rate", "clay_rate", "toe_sand", "grid_total"):
            v = getattr(self, k)
            setattr(s, k, None if v is None else v[rows])
        s.slopes = None if self.slopes is None else {k: v[rows] for k, v in self.slopes.items()}
        return s

    def with_dynamics(self, perturbed: dict, toe_sand, shaft_damping) -> ResponseSurface:
        """The surface with the soil's dynamic parameters (:data:`DYNAMICS`) as variables.

        perturbed : per group of :data:`SENSITIVITY_FACTORS`, the surface of the same records
        and grid with that group's values multiplied by its factor (direct runs); toe_sand :
        (n,) does each record's toe stand in sand; shaft_damping : the grid's Smith shaft
        dampings (sand, clay) [s/m]. log(blow count) is taken linear in the log of each value
        (the slope per node from the two grids), a value entering each record as the toe's
        (by its soil class) or as the shaft's SRD-weighted damping (:func:`shaft_damping`).
        """
        s = self.subset(slice(None))
        s.slopes = {g: (perturbed[g].lc - self.lc) / math.log(SENSITIVITY_FACTORS[g])
                    for g in perturbed}
        s.toe_sand = np.asarray(toe_sand, bool)
        s.shaft_damping = tuple(float(v) for v in shaft_damping)
        return s

    def exposures(self, dynamics: dict) -> dict:
        """Per sensitivity group, the log of each record's value over the grid's [-] at the
        ratios ``dynamics`` (name of :data:`DYNAMICS` -> value / the grid's value)."""
        def ratio(name):
            return float(dynamics.get(name, 1.0))

        out = {}
        if self.slopes is None:
            return out
        if "damping_shaft" in self.slopes:
            js, jc = self.shaft_damping
            base = js * self.sand + jc * self.clay
            new = js * ratio("damping_sand") * self.sand + jc * ratio("damping_clay") * self.clay
            out["damping_shaft"] = np.log(np.where(base > 0, new / np.where(base > 0, base, 1),
                                                   1.0))
        for group in ("damping_toe", "quake_toe"):
            if group in self.slopes:
                out[group] = np.log(np.where(self.toe_sand, ratio(f"{group}_sand"),
                                             ratio(f"{group}_clay")))
        return out

    def with_energy_factor(self, factor) -> ResponseSurface:
        s = self.subset(slice(None))
        s.energy_factor = np.asarray(factor, float)
        return s

    def with_site_weight(self, weight: float, group, depth) -> ResponseSurface:
        """The surface with each record's SRD estimated at its pile from its foundation's CPT
        and the site's (:func:`site_estimate`): per class (sand shaft, clay shaft at every
        fatigue rate, toe) the foundation's SRD at the tip depth moved towards the mean of the
        foundations at that depth, with the correlation ``weight`` [-] between the soil at
        the foundation's CPT and at its piles (1: the CPT's soil, the surface unchanged).
        group, depth : (n,) each record's foundation and tip depth [m]. The grid's
        multipliers keep scaling the SRD they were simulated at (:attr:`grid_total`), so the
        estimate enters, like the class multipliers, through the effective multiplier."""
        s = self.subset(slice(None))
        if s.grid_total is None:
            s.grid_total = self.sand + self.clay + self.toe
        for k in ("sand", "clay", "toe", "sand_rate", "clay_rate"):
            v = getattr(self, k)
            if v is not None:
                setattr(s, k, np.maximum(site_estimate(v, group, depth, weight), 0.0))
        return s

    def shaft_at_rate(self, rate: float | None) -> tuple[np.ndarray, np.ndarray]:
        """Sand and clay shaft SRD [N] of every record at the fatigue rate factor ``rate``
        (None: the grid's own), linear in log(rate) between the tabulated factors."""
        if rate is None:
            return self.sand, self.clay
        if self.lr is None:
            raise ValueError("this surface has no friction-fatigue tables")
        i, w = self._cell(self.lr, math.log(rate))
        return ((1 - w) * self.sand_rate[:, i] + w * self.sand_rate[:, i + 1],
                (1 - w) * self.clay_rate[:, i] + w * self.clay_rate[:, i + 1])

    def effective_multiplier(self, m_sand: float, m_clay: float, m_toe: float,
                             rate: float | None = None) -> np.ndarray:
        total = self.sand + self.clay + self.toe if self.grid_total is None else \
            self.grid_total
        sand, clay = self.shaft_at_rate(rate)
        return ((m_sand * sand + m_clay * clay + m_toe * self.toe)
                / np.where(total > 0, total, 1.0))

    @staticmethod
    def _cell(nodes, x):
        x = np.clip(x, nodes[0], nodes[-1])
        i = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
        return i, (x - nodes[i]) / (nodes[i + 1] - nodes[i])

    def __call__(self, e_ref: float, m_sand: float = 1.0, m_clay: float | None = None,
                 m_toe: float | None = None, exponent: float = 1.0,
                 rate: float | None = None, dynamics: dict | None = None) -> np.ndarray:
        """Blow counts [blows/m] of every record at E_ref [J] and the class multipliers [-]
        (clay and toe default to the sand one); blow energy E_ref setting^exponent; the
        shaft at the friction-fatigue rate factor ``rate`` (None: the grid's); the soil's
        dynamic values at the ratios ``dynamics`` to the grid's (:meth:`exposures`)."""
        m = self.effective_multiplier(m_sand, m_sand if m_clay is None else m_clay,
                                      m_sand if m_toe is None else m_toe, rate)
        im, wm = self._cell(self.lm, np.log(m))
        ie, we = self._cell(self.le, np.log(e_ref * self.energy_factor)
                            + (exponent - 1.0) * np.log(self.setting))
        k = np.arange(self.lc.shape[0])

        def bilinear(a):
            return ((1 - wm) * ((1 - we) * a[k, im, ie] + we * a[k, im, ie + 1])
                    + wm * ((1 - we) * a[k, im + 1, ie] + we * a[k, im + 1, ie + 1]))

        lc = bilinear(self.lc)
        for group, x in (self.exposures(dynamics) if dynamics else {}).items():
            lc = lc + x * bilinear(self.slopes[group])
        return np.where(m <= self.run, 0.0, np.exp(lc))


def misfit(predicted, measured, space: str) -> np.ndarray:
    """Residuals of the fit: in blows/m (``"blows"``) or of log(N + LOG_OFFSET) (``"log"``)."""
    if space == "log":
        return np.log(predicted + LOG_OFFSET) - np.log(measured + LOG_OFFSET)
    return np.asarray(predicted, float) - np.asarray(measured, float)


def fit_regularised(surface: ResponseSurface, measured, classes: tuple = (),
                    space: str = "log", prior_sd: float = PRIOR_SD,
                    n_eff: float = 1.0, exponent: bool = False, fatigue: bool = False,
                    e_max: float | None = None, dynamics: tuple = ()) -> dict:
    """E_ref, a common SRD multiplier, (``classes``, a subset of :data:`CLASSES`) the
    deviations of the classes' multipliers from it, (``exponent``) the exponent b of the
    energy law E = E_ref setting^b, (``fatigue``) the factor r on the friction-fatigue
    rate and (``dynamics``, a subset of :data:`DYNAMICS`) the ratios g of the soil's dynamic
    values to the model's, minimising

        mean(r^2) / s^2 + [sum(d_c^2) / prior_sd^2 + (b - 1)^2 / EXPONENT_SD^2
                           + log(r)^2 / FATIGUE_SD^2 + sum(log(g)^2) / DYNAMICS_SD^2] / n_eff

    with E_ref at most ``e_max`` [J] when given (the hammer's rating over the largest
    blow energy per unit E_ref of the records),

    (a Gaussian MAP estimate: r the :func:`misfit` in ``space``, s its
    :data:`RESIDUAL_SCALE`, d_c = log(m_c) - log(m) the class deviations with a prior of
    standard deviation ``prior_sd`` about the common multiplier, b about 1 (the energy
    proportional to the setting), n_eff the number of independent observations: the
    foundations, whose piles share one CPT). E_ref and the common multiplier are not penalised
    (the data fix their valley). Nelder-Mead from the best of a coarse start grid, restarted
    twice. Returns the values and the objective."""
    from scipy.optimize import minimize

    measured = np.asarray(measured, float)
    s2 = RESIDUAL_SCALE[space] ** 2
    nc = len(classes)
    ib = 2 + nc                            # index of b in the parameter vector
    ir = ib + (1 if exponent else 0)       # index of log(r)
    lr_range = ((surface.lr[0], surface.lr[-1]) if fatigue and surface.lr is not None
                else (0.0, 0.0))
    if fatigue and surface.lr is None:
        raise ValueError("a fit of the fatigue rate needs a surface with fatigue tables")
    le_max = math.inf if e_max is None else math.log(e_max)
    ig = ir + (1 if fatigue else 0)        # index of the first log(g)
    if dynamics and surface.slopes is None:
        raise ValueError("a fit of the soil's dynamics needs a surface with_dynamics")
    g_range = [(math.log(DYNAMICS_RANGE[0]),
                math.log(SENSITIVITY_FACTORS[DYNAMICS_GROUP[name]])) for name in dynamics]

    def clipped_g(p):
        return [min(max(float(v), lo), hi)
                for v, (lo, hi) in zip(p[ig:ig + len(dynamics)], g_range, strict=True)]

    def unpack(p):
        d = dict(zip(classes, p[2:2 + nc], strict=True))
        b = float(p[ib]) if exponent else 1.0
        rate = math.exp(min(max(float(p[ir]), lr_range[0]), lr_range[1])) if fatigue else None
        return (math.exp(min(float(p[0]), le_max)),
                *(math.exp(p[1] + d.get(c, 0.0)) for c in CLASSES), b, rate,
                {name: math.exp(v) for name, v in zip(dynamics, clipped_g(p), strict=True)})

    def objective(p):
        r = misfit(surface(*unpack(p)), measured, space)
        penalty = float(np.sum(np.asarray(p[2:2 + nc]) ** 2)) / prior_sd ** 2
        if exponent:
            penalty += (float(p[ib]) - 1.0) ** 2 / EXPONENT_SD ** 2
        if fatigue:
            lr = float(p[ir])
            # the prior on the clipped value; beyond the table a growing penalty brings the
            # simplex back (the SRD is flat there)
            clipped = min(max(lr, lr_range[0]), lr_range[1])
            penalty += clipped ** 2 / FATIGUE_SD ** 2 + 100.0 * (lr - clipped) ** 2
        if dynamics:
            lg = np.asarray(p[ig:ig + len(dynamics)], float)
            gc = np.asarray(clipped_g(p))
            penalty += float(np.sum(gc * gc)) / DYNAMICS_SD ** 2 + 100.0 * float(
                np.sum((lg - gc) ** 2))
        if e_max is not None and p[0] > le_max:
            penalty += 100.0 * (float(p[0]) - le_max) ** 2
        return float(np.mean(r * r)) / s2 + penalty / n_eff

    tail = np.r_[np.zeros(nc), [1.0] if exponent else []]
    starts = [np.r_[min(math.log(e), le_max), math.log(m), tail, [lr0] if fatigue else [],
                    np.zeros(len(dynamics))]
              for e in (250e3, 500e3, 1000e3) for m in (0.3, 0.5, 0.8)
              for lr0 in ((math.log(0.25), 0.0, math.log(2.0)) if fatigue else (0.0,))]
    res = None
    p0 = min(starts, key=objective)
    for _ in range(3):  # restarted: a fresh simplex where the last one shrank in a valley
        res = minimize(objective, p0 if res is None else res.x, method="Nelder-Mead",
                       options={"xatol": 1e-5, "fatol": 1e-12, "maxfev": 6000,
                                "adaptive": True})
    e_ref, m_sand, m_clay, m_toe, b, rate, ratios = unpack(res.x)
    at_edge = bool(not (surface.le[0] < math.log(e_ref) < surface.le[-1]))
    out = {"E_ref [J]": e_ref, "srd_sand [-]": m_sand, "srd_clay [-]": m_clay,
           "srd_toe [-]": m_toe, "energy_exponent [-]": b, "objective [-]": float(res.fun),
           "energy_at_grid_edge": at_edge}
    if e_max is not None:
        out["E_ref_max [J]"] = e_max
        out["energy_at_rating"] = bool(math.log(e_ref) >= le_max - 1e-6)
    if fatigue:
        out["fatigue_rate [-]"] = rate
        out["fatigue_rate_at_table_edge"] = bool(
            not (lr_range[0] + 1e-6 < math.log(rate) < lr_range[1] - 1e-6))
    for name, (lo, hi) in zip(dynamics, g_range, strict=True):
        out[f"{name} [-]"] = ratios[name]
        out[f"{name}_at_range_edge"] = bool(not (lo + 1e-6 < math.log(ratios[name])
                                                 < hi - 1e-6))
    return out


def predict_with(surface: ResponseSurface, fitted: dict) -> np.ndarray:
    """Blow counts [blows/m] of the surface's records at the fitted values."""
    return surface(fitted["E_ref [J]"], fitted["srd_sand [-]"], fitted["srd_clay [-]"],
                   fitted["srd_toe [-]"], fitted.get("energy_exponent [-]", 1.0),
                   fitted.get("fatigue_rate [-]"), fitted_dynamics(fitted))


def fitted_dynamics(fitted: dict) -> dict:
    """The ratios of the soil's dynamic values to the model's in a fit (:data:`DYNAMICS`)."""
    return {name: fitted[f"{name} [-]"] for name in DYNAMICS if f"{name} [-]" in fitted}


def stacking_weight(physics, baseline, measured) -> float:
    """Weight w in [0, 1] of the least-squares blend baseline + w (physics - baseline) [-]."""
    d = np.asarray(physics, float) - np.asarray(baseline, float)
    den = float(np.sum(d * d))
    if den <= 0.0:
        return 1.0
    return float(np.clip(np.sum(d * (np.asarray(measured, float) - baseline)) / den, 0.0, 1.0))


@dataclass(frozen=True)
class Step:
    """One step of the stepwise back-analysis: what the model drives with and fits."""

    name: str
    space: str = "log"              # the fit's misfit: "blows" or "log"
    classes: tuple = ()             # soil classes with their own SRD multiplier
    energy: str = "hammer"          # "hammer" (normalised hammer energy) or "enthru"
    exponent: bool = False          # fit the exponent of the energy law
    residual_stress: bool = False   # apply the multi-blow (residual stress) ratio
    stacked: bool = False           # blend with the depth mean of the other foundations
    energy_cap: bool = False        # the largest blow energy within the hammer's rating
    fatigue: bool = False           # fit the factor on the friction-fatigue rate
    hammers: tuple = ()             # hammer classes chosen between per fold (their surfaces)
    dynamics: tuple = ()            # the soil's dynamic values fitted (of DYNAMICS)
    toe_average: bool = False       # the toe from qt averaged over the tip +- 1.5 D (ICP-05)
    site_weights: tuple = ()        # the SRD at the pile kriged from the foundation's and
                                    # the site's, the correlation chosen among these per fold


STEPS = (
    Step("A: one E_ref, one SRD multiplier, fit in blows/m (the calibration fit of drive.md)",
         space="blows"),
    Step("B: as A, fit in log blow count", space="log"),
    Step("C: + sand / clay shaft and toe multipliers (ridge)", classes=CLASSES),
    Step("D: + drive with the recorded ENTHRU", classes=CLASSES, energy="enthru"),
)


def _scores(predicted, measured) -> dict:
    r = np.asarray(predicted, float) - np.asarray(measured, float)
    return {"rmse [blows/m]": float(np.sqrt(np.mean(r * r))), "bias [blows/m]": float(np.mean(r))}


def record_baselines(piles, groups) -> np.ndarray:
    """Per record of ``piles``: the naive baseline with the record's foundation held out
    (:func:`naive_baseline`; NaN where no other foundation was driven to that depth)."""
    out = []
    by_group = {g: [p for p in piles if p.cpt_group == g] for g in groups}
    for p in piles:
        others = [q for g, qs in by_group.items() if g != p.cpt_group for q in qs]
        out.append(naive_baseline(others, [p])[0])
    return np.concatenate(out) if out else np.zeros(0)


def largest_energy_per_e_ref(surface: ResponseSurface) -> float:
    """The largest blow energy per unit E_ref of the surface's records [-] (energy factor x
    normalised hammer energy)."""
    return float(np.max(surface.energy_factor * surface.setting))


def fit_step(step: Step, surfaces: dict, measured, n_eff: float) -> tuple[str, dict]:
    """The fit of ``step`` on ``measured``: ``surfaces`` maps each hammer class to (its
    :class:`ResponseSurface` of the records, its rated energy [J] or None); a step with
    ``hammers`` fits each of them (E_ref within its own rating with ``energy_cap``) and keeps
    the one of the least objective (the same data, misfit and priors: a discrete MAP choice),
    else the first; a step with ``site_weights`` likewise chooses among ``surfaces`` keyed
    by the weights (:meth:`ResponseSurface.with_site_weight`), the fit keeping its weight as
    ``site_weight [-]``. Returns (the hammer class or the weight, the fit)."""
    best = None
    for choice in (step.hammers or step.site_weights or list(surfaces)[:1]):
        surf, rated = surfaces[choice]
        e_max = rated / largest_energy_per_e_ref(surf) if step.energy_cap else None
        fitted = fit_regularised(surf, measured, step.classes, step.space, n_eff=n_eff,
                                 exponent=step.exponent, fatigue=step.fatigue, e_max=e_max,
                                 dynamics=step.dynamics)
        if step.site_weights:
            fitted["site_weight [-]"] = float(choice)
        if best is None or fitted["objective [-]"] < best[1]["objective [-]"]:
            best = (choice, fitted)
    return best


def stepwise_cross_validation(piles, surface: ResponseSurface, enthru_factor, steps=STEPS,
                              stress_ratio=None, rated_energy: float | None = None,
                              hammer_surfaces: dict | None = None
                              ) -> tuple[list[dict], dict]:
    """Leave-one-foundation-out cross-validation of every step of ``steps`` on the records of
    ``piles`` (their :class:`ResponseSurface`), against the naive baseline computed the same
    way (every held-out record scored where the baseline exists, the same records for every
    step). enthru_factor : per record, the energy factor of the ``"enthru"`` steps;
    stress_ratio : per record, multi-blow / single-blow blow count (steps with
    ``residual_stress``); rated_energy : the hammer's rating [J] (steps with ``energy_cap``:
    E_ref at most the rating over the largest blow energy per unit E_ref of the training
    records); hammer_surfaces : per hammer class by name, (its surface of the same records,
    its rating [J]), for the steps with ``hammers`` (:func:`fit_step`; the other steps fit
    ``surface``). Returns (a row per step; the predictions per step, the baseline, the
    measured counts, the records' foundations and depths [m], the scored records and per step
    the fit of every fold, foundation -> (hammer class, fit))."""
    measured = np.concatenate([p.measured for p in piles])
    group = np.concatenate([[p.cpt_group] * len(p.depths) for p in piles])
    depth = np.concatenate([p.depths for p in piles])
    groups = sorted(set(group.tolist()))
    baseline = record_baselines(piles, groups)
    ok = np.isfinite(baseline)
    rows, predictions, folds = [], {}, {}
    every = {"": (surface, rated_energy), **(hammer_surfaces or {})}
    for step in steps:
        surfs = {h: (s.with_energy_factor(enthru_factor) if step.energy == "enthru" else s, r)
                 for h, (s, r) in every.items()}
        if step.site_weights:  # the site's mean from every foundation's CPT (inputs all)
            surfs = {w: (surfs[""][0].with_site_weight(w, group, depth), rated_energy)
                     for w in step.site_weights}
        predicted = np.full(measured.size, np.nan)
        fold_fits = {}  # foundation -> (hammer class, fit)
        for g in groups:
            train, test = group != g, group == g
            hammer, fitted = fit_step(step, {h: (s.subset(train), r)
                                             for h, (s, r) in surfs.items()},
                                      measured[train], len(groups) - 1)
            sub = surfs[hammer][0].subset(train)
            pred = predict_with(surfs[hammer][0].subset(test), fitted)
            if step.residual_stress:
                pred = pred * stress_ratio[test]
            if step.stacked:
                train_piles = [p for p in piles if p.cpt_group != g]
                inner = record_baselines(train_piles, [x for x in groups if x != g])
                phys = predict_with(sub, fitted)
                if step.residual_stress:
                    phys = phys * stress_ratio[train]
                good = np.isfinite(inner)
                w = stacking_weight(phys[good], inner[good], measured[train][good])
                fitted["stacking_weight [-]"] = w
                base = baseline[test]
                pred = np.where(np.isfinite(base), base + w * (pred - base), pred)
            predicted[test] = pred
            fold_fits[g] = (hammer, fitted)
        predictions[step.name] = predicted
        folds[step.name] = fold_fits
        chosen = [h for h, _ in fold_fits.values()]
        fits = [f for _, f in fold_fits.values()]
        row = {"step": step.name, **_scores(predicted[ok], measured[ok]),
               "rmse_baseline [blows/m]": _scores(baseline[ok], measured[ok])["rmse [blows/m]"],
               "bias_baseline [blows/m]": _scores(baseline[ok], measured[ok])["bias [blows/m]"],
               "points [-]": int(ok.sum()), "folds [-]": len(groups)}
        if step.hammers:
            for h in step.hammers:
                row[f"folds with {h} [-]"] = chosen.count(h)
        for key in ("E_ref [J]", "srd_sand [-]", "srd_clay [-]", "srd_toe [-]",
                    "energy_exponent [-]", "fatigue_rate [-]", "stacking_weight [-]",
                    "site_weight [-]", *(f"{name} [-]" for name in DYNAMICS)):
            if key in fits[0]:
                values = [f[key] for f in fits]
                row[f"{key} folds median"] = float(np.median(values))
                row[f"{key} folds min"] = float(np.min(values))
                row[f"{key} folds max"] = float(np.max(values))
        rows.append(row)
    return rows, {"predictions": predictions, "baseline": baseline, "measured": measured,
                  "group": group, "depth": depth, "scored": ok, "fits": folds}


# ----------------------------------------------------------------------------- stepwise run
PREDICTIVE_STEPS = (
    ("grid1", Step("A: one E_ref, one SRD multiplier, fit in blows/m "
                   "(the calibration fit of drive.md)", space="blows")),
    ("grid1", Step("B: as A, fit in log blow count")),
    ("grid2", Step("C: + sand shaft, clay shaft and toe multipliers (ridge)", classes=CLASSES)),
    ("grid2", Step("D: + drive with the recorded ENTHRU", classes=CLASSES, energy="enthru")),
    ("grid2", Step("E: + energy law E_ref setting^b (tried, not kept)", classes=CLASSES,
                   energy="enthru", exponent=True)),
    ("grid2", Step("F: D + residual stress (3 blows per depth)", classes=CLASSES,
                   energy="enthru", residual_stress=True)),
    ("grid2", Step("G: F stacked with the depth mean of the other foundations",
                   classes=CLASSES, energy="enthru", residual_stress=True, stacked=True)),
    ("grid2", Step("H: D with the largest blow energy within the hammer's rating",
                   classes=CLASSES, energy="enthru", energy_cap=True)),
    ("grid2", Step("I: H + friction-fatigue rate factor (one parameter)", classes=CLASSES,
                   energy="enthru", energy_cap=True, fatigue=True)),
    ("grid2", Step("J: I stacked with the depth mean of the other foundations",
                   classes=CLASSES, energy="enthru", energy_cap=True, fatigue=True,
                   stacked=True)),
    ("grid2", Step("K: I with the hammer class chosen per fold (S-800 or S-1800)",
                   classes=CLASSES, energy="enthru", energy_cap=True, fatigue=True,
                   hammers=("ihc_s800", "ihc_s1800"))),
    ("grid2", Step("L: I + Smith dampings and toe quake per soil type (priors)",
                   classes=CLASSES, energy="enthru", energy_cap=True, fatigue=True,
                   dynamics=DYNAMICS)),
    ("grid2", Step("M: I + toe from qt averaged over the tip +- 1.5 D (ICP-05 / UWA-05)",
                   classes=CLASSES, energy="enthru", energy_cap=True, fatigue=True,
                   toe_average=True)),
    ("grid2", Step("O: I with the SRD at the pile kriged from its foundation's CPT and the "
                   "site's (spatial variability)", classes=CLASSES, energy="enthru",
                   energy_cap=True, fatigue=True, site_weights=(0.25, 0.5, 0.625, 0.75,
                                                                0.875, 1.0))),
)
"""The steps of the stepwise back-analysis (grid1: the grid at the method's SRD; grid2: the
grid at the SRD distribution of the all-pile fit of D, see :func:`predictive_backanalysis`;
a step with ``toe_average`` fits the second grid simulated with the toe from qt averaged over
the tip +- :data:`TOE_HALF_WINDOW_DIAMETERS` D). The final model is :data:`FINAL_STEP`, the
last physics step (no blend with the baseline)."""
TOE_HALF_WINDOW_DIAMETERS = 1.5
"""Half-window of the toe's qt average about the tip of the ``toe_average`` steps, in pile
diameters [-] (ICP-05, UWA-05: :data:`anvilwave.pile.soil.srd_methods.ICP_05_TOE_HALF_WINDOW`)."""
FINAL_STEP = "I"
"""The step whose all-pile fit predicts the prediction piles (direct runs)."""
INSTALLATION_STEP = ("N: {final} as a blow-by-blow installation (residual stress kept), "
                     "each fold's fit")
"""The name of the step that drives every held-out pile blow by blow, from 0.5 m above its
first record depth to 0.5 m below its last, with its fold's fit of :data:`FINAL_STEP`
(:func:`install_pile`; direct runs, not the surface)."""
ALTERNATIVE_HAMMERS = ("ihc_s1800",)
"""Hammer classes simulated beside the model's on the second grid (step K chooses between
them per fold): a heavier ram (90 t against 40 t) of a larger rating."""
GRID2_MULTIPLIERS = (0.3, 0.45, 0.65, 0.9, 1.25, 1.7)
"""Common SRD multipliers of the second grid, about the class multipliers of the first fit."""
RESIDUAL_STRESS_BLOWS = 3
"""Blows per depth of the residual-stress runs (each from the state the last left) [-]."""


def sensitivity_models(model: Model) -> dict:
    """Per group of :data:`SENSITIVITY_FACTORS`, ``model`` with that group's values
    multiplied by its factor (the grids of :meth:`ResponseSurface.with_dynamics`)."""
    f = SENSITIVITY_FACTORS
    return {"damping_shaft": replace(model, damping_sand=f["damping_shaft"] * model.damping_sand,
                                     damping_clay=f["damping_shaft"] * model.damping_clay),
            "damping_toe": replace(model, damping_toe=f["damping_toe"] * model.damping_toe),
            "quake_toe": replace(model, quake_toe=f["quake_toe"] * model.quake_toe)}


def record_surface(piles, results, energies, multipliers, rates=None,
                   fatigue=None) -> ResponseSurface:
    """The :class:`ResponseSurface` of the records of ``piles`` from their
    :func:`simulate_pile` ``results`` on the grid (and, with ``rates``, their
    :func:`shaft_by_class` ``fatigue`` results at those fatigue rate factors)."""
    def cat(key):
        return np.concatenate([r[key] for r in results])

    counts = np.concatenate([np.transpose(r["count"], (2, 0, 1)) for r in results])
    sand = cat("srd_shaft_sand")
    tables = {}
    if rates is not None:
        tables = {"rates": rates, "sand_rate": np.concatenate([f["sand"] for f in fatigue]),
                  "clay_rate": np.concatenate([f["clay"] for f in fatigue])}
    return ResponseSurface(energies, multipliers, counts, cat("run_multiplier"), sand,
                           cat("srd_shaft") - sand, cat("srd_toe"),
                           setting=np.concatenate([p.energy for p in piles]), **tables)


def enthru_factor(piles) -> np.ndarray:
    """Per record: ENTHRU / (0.75 x hammer energy) [-] (1 where the record gives no ENTHRU):
    the factor on the blow energy that drives with the recorded ENTHRU (0.75: the records'
    usual ratio, absorbed in E_ref)."""
    out = []
    for p in piles:
        f = (p.enthru / p.energy / 0.75 if p.enthru is not None else np.ones(p.depths.size))
        out.append(np.where(np.isfinite(f) & (f > 0), f, 1.0))
    return np.concatenate(out)


def final_model(model: Model, fitted: dict) -> Model:
    """``model`` with the fitted class multipliers (on its own)."""
    return replace(model, srd_sand=model.srd_sand * fitted["srd_sand [-]"],
                   srd_clay=model.srd_clay * fitted["srd_clay [-]"],
                   srd_toe=model.srd_toe * fitted["srd_toe [-]"])


def fold_model(model: Model, fitted: dict) -> tuple[Model, float]:
    """(``model`` with a fit's class multipliers and friction-fatigue rate factor, the fit's
    E_ref [J]): what a direct run at the fit drives with."""
    out = final_model(model, fitted)
    if "fatigue_rate [-]" in fitted:
        out = replace(out, fatigue_rate=fitted["fatigue_rate [-]"])
    return out, float(fitted["E_ref [J]"])


def _enthru_piles(piles):
    """The piles with their blow energy trace the recorded ENTHRU / 0.75."""
    return [replace(p, energy=p.energy * f)
            for p, f in zip(piles, np.split(enthru_factor(piles),
                                            np.cumsum([p.depths.size for p in piles])[:-1]),
                            strict=True)]


def per_pile_scores(piles, records: dict, steps: list[str], scored) -> list[dict]:
    """RMSE and bias [blows/m] of every step and of the baseline per pile, over the pile's
    scored records (``records``: measured, baseline and every step's predictions per record,
    in the order of the piles' records; ``scored``: the records with a baseline)."""
    rows, k = [], 0
    for p in piles:
        n = p.depths.size
        ok = scored[k:k + n]
        m = records["measured"][k:k + n][ok]
        row = {"location_id": p.location_id, "cpt_group": p.cpt_group, "points [-]": int(
            ok.sum())}
        for name, values in [("naive", records["baseline"]),
                             *[(st, records["predictions"][st]) for st in steps]]:
            label = name.split(":")[0]
            sc = _scores(values[k:k + n][ok], m) if ok.any() else {
                "rmse [blows/m]": math.nan, "bias [blows/m]": math.nan}
            row[f"{label} rmse [blows/m]"] = sc["rmse [blows/m]"]
            row[f"{label} bias [blows/m]"] = sc["bias [blows/m]"]
        rows.append(row)
        k += n
    return rows


def predictive_backanalysis(args, model: Model, calibration, prediction, out: Path,
                            energies, multipliers) -> int:
    """The stepwise back-analysis (``--cross-validate``): every step of
    :data:`PREDICTIVE_STEPS` cross-validated leave one foundation out against the naive
    baseline, the final step (:data:`FINAL_STEP`) fitted on all calibration piles and the
    prediction piles predicted with it (direct runs). Writes ``isfog_backanalysis.json``,
    ``cross_validation_steps.csv``, ``cross_validation_records.csv`` and
    ``cross_validation_piles.csv`` in ``out`` (and, with ``--docs``, the docs' data file)."""
    start = time.perf_counter()
    times = {}
    cache = args.cache
    measured = np.concatenate([p.measured for p in calibration])
    groups = sorted({p.cpt_group for p in calibration})
    n_cal = len(calibration)
    ds = driving_system(model)
    rated = ds["rated_energy [J]"]
    warm_up(model, calibration[0])

    def grid_runs(piles, mdl, e, m):
        return run_piles(piles, mdl, e, m, args.workers)

    def shafts(piles, mdl, rates):
        return run_shaft_by_class(piles, mdl, rates, args.workers)

    # grid 1: the method's SRD distribution (the calibration piles' records only: the folds
    # fit on them; the prediction piles are run directly at the final values)
    t = time.perf_counter()
    g1 = cached(cache, "grid1", grid_runs, calibration, model, energies, multipliers)
    times["grid1 [s]"] = time.perf_counter() - t
    surf1 = record_surface(calibration, g1, energies, multipliers)
    factor = enthru_factor(calibration)
    first = fit_regularised(surf1.with_energy_factor(factor), measured, CLASSES, "log",
                            n_eff=len(groups))
    # grid 2: the SRD distribution of the first fit (the effective multiplier of the surface
    # then only has to carry the folds' small deviations from it)
    model2 = final_model(model, first)
    t = time.perf_counter()
    m2 = np.asarray(GRID2_MULTIPLIERS)
    e2 = np.geomspace(energies[0], energies[-1] * 1.25, energies.size)
    g2 = cached(cache, "grid2", grid_runs, calibration, model2, e2, m2)
    times["grid2 [s]"] = time.perf_counter() - t
    # the sand and clay shaft SRD of every record at each fatigue rate factor (static)
    t = time.perf_counter()
    rates = np.asarray(FATIGUE_RATES)
    fat = cached(cache, "fatigue", shafts, calibration, model2, rates)
    times["fatigue_srd [s]"] = time.perf_counter() - t
    surf2 = record_surface(calibration, g2, e2, m2, rates, fat)
    # the other hammer classes at the same SRD distribution (step K), and the grids with the
    # soil's dynamic values changed that make them variables of the surface (step L)
    t = time.perf_counter()
    hammer_surfaces = {model.hammer: (surf2, rated)}
    for hammer in ALTERNATIVE_HAMMERS:
        other = replace(model2, hammer=hammer)
        g = cached(cache, f"grid2_{hammer}", grid_runs, calibration, other, e2, m2)
        hammer_surfaces[hammer] = (record_surface(calibration, g, e2, m2, rates, fat),
                                   driving_system(other)["rated_energy [J]"])
    perturbed = {}
    for name, other in sensitivity_models(model2).items():
        g = cached(cache, f"sens_{name}", grid_runs, calibration, other, e2, m2)
        perturbed[name] = record_surface(calibration, g, e2, m2, rates, fat)
    surf2 = surf2.with_dynamics(perturbed, toe_classes(calibration, model2),
                                (model2.damping_sand, model2.damping_clay))
    # the second grid with the toe from qt averaged over the tip +- 1.5 D (the toe_average
    # steps; the shaft, and so the fatigue tables, are the same)
    model2_toe = replace(model2, toe_qt_half_window_diameters=TOE_HALF_WINDOW_DIAMETERS)
    g = cached(cache, "grid2_toe", grid_runs, calibration, model2_toe, e2, m2)
    surf2_toe = record_surface(calibration, g, e2, m2, rates, fat)
    times["other_grids [s]"] = time.perf_counter() - t
    at_one = int(np.argmin(np.abs(np.log(rates))))
    fatigue_table_check = float(np.max(np.abs(surf2.sand_rate[:, at_one] + surf2.clay_rate[
        :, at_one] - surf2.sand - surf2.clay) / np.maximum(surf2.sand + surf2.clay, 1.0)))
    surf2f = surf2.with_energy_factor(factor)
    # step D's fit on every calibration pile: its direct runs give the residual-stress ratio
    fit_d = fit_regularised(surf2f, measured, CLASSES, "log", n_eff=len(groups))
    model_d = final_model(model2, fit_d)
    piles_e = _enthru_piles(calibration + prediction)
    t = time.perf_counter()
    one = cached(cache, "direct_d1", grid_runs, piles_e[:n_cal], model_d,
                 [fit_d["E_ref [J]"]], [1.0])
    several = cached(cache, "direct_d3", grid_runs, piles_e[:n_cal],
                     replace(model_d, blows_per_depth=RESIDUAL_STRESS_BLOWS),
                     [fit_d["E_ref [J]"]], [1.0])
    direct1 = np.concatenate([r["count"][0, 0] for r in one])
    directn = np.concatenate([r["count"][0, 0] for r in several])
    stress_ratio = np.where(direct1 > 0, directn / np.where(direct1 > 0, direct1, 1.0), 1.0)
    # the final step's fit on every calibration pile (I's fit: the class multipliers, the
    # fatigue rate and E_ref within the rating; on the averaged toe's grid if the final step
    # has toe_average) and its direct runs (every pile)
    final_step = next(st for _, st in PREDICTIVE_STEPS if st.name.split(":")[0] == FINAL_STEP)
    surf_final = (surf2_toe if final_step.toe_average else surf2).with_energy_factor(factor)
    e_max = rated / largest_energy_per_e_ref(surf_final)
    final = fit_regularised(surf_final, measured, CLASSES, "log", n_eff=len(groups),
                            fatigue=True, e_max=e_max)
    model_f = replace(final_model(model2_toe if final_step.toe_average else model2, final),
                      fatigue_rate=final["fatigue_rate [-]"])
    direct_f = cached(cache, "direct_final", grid_runs, piles_e, model_f,
                      [final["E_ref [J]"]], [1.0])
    install_f = cached_jobs(cache, "install_final", _install,
                            [(p, model_f, final["E_ref [J]"]) for p in piles_e], args.workers)
    times["direct [s]"] = time.perf_counter() - t
    final_cal = np.concatenate([r["count"][0, 0] for r in direct_f[:n_cal]])
    install_cal = np.concatenate([r["count"] for r in install_f[:n_cal]])
    surface_at_final = predict_with(surf_final, final)
    surface_at_d = predict_with(surf2f, fit_d)
    # the steps
    t = time.perf_counter()
    rows, records, fold_fits = [], None, {}
    for which, step in PREDICTIVE_STEPS:
        surf = surf1 if which == "grid1" else surf2_toe if step.toe_average else surf2
        r, res = stepwise_cross_validation(calibration, surf, factor, [step], stress_ratio,
                                           rated, hammer_surfaces)
        rows += r
        if records is None:
            records = {"measured": res["measured"], "baseline": res["baseline"],
                       "scored": res["scored"], "group": res["group"], "depth": res["depth"],
                       "predictions": {}}
        records["predictions"][step.name] = res["predictions"][step.name]
        fold_fits[step.name] = res["fits"][step.name]
        print(f"{step.name}: CV RMSE {r[0]['rmse [blows/m]']:.1f}, bias "
              f"{r[0]['bias [blows/m]']:+.1f} blows/m (naive "
              f"{r[0]['rmse_baseline [blows/m]']:.1f}, "
              f"{r[0]['bias_baseline [blows/m]']:+.1f})", flush=True)
    times["cross_validation [s]"] = time.perf_counter() - t
    # the final step as blow-by-blow installations: every held-out pile driven with its
    # fold's fit (direct runs), beside the per-depth model's direct runs at the same fits
    t = time.perf_counter()
    folds_final = fold_fits[final_step.name]
    fold_models = [fold_model(model2_toe if final_step.toe_average else model2,
                              folds_final[p.cpt_group][1]) for p in calibration]
    installed = cached_jobs(cache, "install_cv", _install,
                            [(p, m, e) for p, (m, e) in zip(piles_e[:n_cal], fold_models,
                                                            strict=True)], args.workers)
    per_depth = cached_jobs(cache, "direct_cv", _simulate,
                            [(p, m, [e], [1.0]) for p, (m, e) in zip(piles_e[:n_cal],
                                                                     fold_models, strict=True)],
                            args.workers)
    times["installation_cv [s]"] = time.perf_counter() - t
    install_name = INSTALLATION_STEP.format(final=FINAL_STEP)
    install_cv = np.concatenate([r["count"] for r in installed])
    direct_cv = np.concatenate([r["count"][0, 0] for r in per_depth])
    records["predictions"][install_name] = install_cv
    ok_cv = records["scored"]
    base_scores = _scores(records["baseline"][ok_cv], measured[ok_cv])
    rows.append({"step": install_name, **_scores(install_cv[ok_cv], measured[ok_cv]),
                 "rmse_baseline [blows/m]": base_scores["rmse [blows/m]"],
                 "bias_baseline [blows/m]": base_scores["bias [blows/m]"],
                 "points [-]": int(ok_cv.sum()), "folds [-]": len(groups),
                 "blows [-]": int(sum(int(r["blows"]) for r in installed))})
    install_row = rows[-1]
    direct_cv_scores = _scores(direct_cv[ok_cv], measured[ok_cv])
    both = (direct_cv > 0) & (install_cv > 0)  # both driven (a run has no blows): a ratio
    print(f"{install_name}: CV RMSE {install_row['rmse [blows/m]']:.1f}, bias "
          f"{install_row['bias [blows/m]']:+.1f} blows/m (the per-depth model's direct runs "
          f"at the same fits {direct_cv_scores['rmse [blows/m]']:.1f}, "
          f"{direct_cv_scores['bias [blows/m]']:+.1f})", flush=True)

    def letter(name):
        return name.split(":")[0]

    rows.sort(key=lambda row: letter(row["step"]))  # N, the installations, before O
    step_names = sorted([*(st.name for _, st in PREDICTIVE_STEPS), install_name], key=letter)
    departures = departures_from_the_depth_mean(
        calibration, groups, records["predictions"][final_step.name])
    # the final step's departures split: its folds' predictions with every record's blow
    # energy at the site's mean at its depth (the soil's part) and the rest (the energy's)
    surf_cv = (surf2_toe if final_step.toe_average else surf2).with_energy_factor(factor)
    group_rec = records["group"]
    held = site_estimate(factor * surf_cv.setting, group_rec, records["depth"], 0.0)
    surf_held = surf_cv.with_energy_factor(held / surf_cv.setting)
    soil_part = np.full(measured.size, np.nan)
    for g, (_, fitted) in folds_final.items():
        soil_part[group_rec == g] = predict_with(surf_held.subset(group_rec == g), fitted)
    departures.update(departure_parts(
        departures,
        departures_from_the_depth_mean(calibration, groups, soil_part),
        departures_from_the_depth_mean(
            calibration, groups, records["predictions"][final_step.name] - soil_part)))
    for row in rows:  # every step's departures against the records' (the same bound)
        dep = departures_from_the_depth_mean(calibration, groups,
                                             records["predictions"][row["step"]])
        row["departure_correlation [-]"] = dep["correlation [-]"]
        row["departure_needed_correlation [-]"] = dep["needed_correlation [-]"]
    record_rows = []
    k = 0
    for p in calibration:
        for z, n in zip(p.depths, p.measured, strict=True):
            rec = {"location_id": p.location_id, "cpt_group": p.cpt_group, "z [m]": float(z),
                   "measured [blows/m]": float(n),
                   "naive [blows/m]": float(records["baseline"][k])}
            for name in step_names:
                rec[name.split(":")[0]] = float(records["predictions"][name][k])
            record_rows.append(rec)
            k += 1
    pile_rows = per_pile_scores(calibration, records, step_names, records["scored"])
    write_csv(out / "cross_validation_steps.csv", rows)
    write_csv(out / "cross_validation_records.csv", record_rows)
    write_csv(out / "cross_validation_piles.csv", pile_rows)
    # the final model's predictions: its direct runs, and beside them the blend with the
    # depth mean of every calibration foundation (weight fitted on them, inner baseline)
    inner = record_baselines(calibration, groups)
    good = np.isfinite(inner)
    weight_g = stacking_weight(directn[good], inner[good], measured[good])
    weight = stacking_weight(final_cal[good], inner[good], measured[good])
    pred_rows = []
    for p, r, ri in zip(prediction, direct_f[n_cal:], install_f[n_cal:], strict=True):
        base = naive_baseline(calibration, [p])[0]
        physics = r["count"][0, 0]
        blend = np.where(np.isfinite(base), base + weight * (physics - base), physics)
        for i, z in enumerate(p.depths):
            pred_rows.append({"location_id": p.location_id, "z [m]": float(z),
                              "blowcount [blows/m]": float(physics[i]),
                              "installation [blows/m]": float(ri["count"][i]),
                              "stacked [blows/m]": float(blend[i]),
                              "naive [blows/m]": float(base[i])})
    write_csv(out / "prediction_piles_blowcount.csv", pred_rows)
    max_energy = float(max(np.max(p.energy) for p in piles_e) * final["E_ref [J]"])
    max_energy_d = float(max(np.max(p.energy) for p in piles_e) * fit_d["E_ref [J]"])
    per_pile = {}
    for row in pred_rows:
        per_pile.setdefault(row["location_id"], []).append(row["blowcount [blows/m]"])
    final_row = next(r for r in rows if r["step"].split(":")[0] == FINAL_STEP)
    pile_rmse = [r[f"{FINAL_STEP} rmse [blows/m]"] for r in pile_rows if r["points [-]"]]
    pile_naive = [r["naive rmse [blows/m]"] for r in pile_rows if r["points [-]"]]
    summary = {
        "steps": [{k: v for k, v in r.items()} for r in rows],
        "final_step": final_row["step"],
        "cv_rmse [blows/m]": final_row["rmse [blows/m]"],
        "cv_bias [blows/m]": final_row["bias [blows/m]"],
        "naive_rmse [blows/m]": final_row["rmse_baseline [blows/m]"],
        "naive_bias [blows/m]": final_row["bias_baseline [blows/m]"],
        "cv_points [-]": final_row["points [-]"], "cv_folds [-]": final_row["folds [-]"],
        "piles_final_below_naive [-]": int(np.sum(np.asarray(pile_rmse)
                                                  < np.asarray(pile_naive))),
        "piles_scored [-]": len(pile_rmse),
        "first_fit": first, "fit_d": fit_d, "final_fit": final,
        "fatigue_rates [-]": rates.tolist(),
        "fatigue_table_vs_grid_max_rel [-]": fatigue_table_check,
        "srd_multipliers_d [-]": {"sand": model_d.srd_sand, "clay": model_d.srd_clay,
                                  "toe": model_d.srd_toe},
        "final_srd_multipliers [-]": {"sand": model_f.srd_sand, "clay": model_f.srd_clay,
                                      "toe": model_f.srd_toe},
        "installation_cv": {
            "step": install_name,
            "per_depth_direct_rmse [blows/m]": direct_cv_scores["rmse [blows/m]"],
            "per_depth_direct_bias [blows/m]": direct_cv_scores["bias [blows/m]"],
            "installation_over_per_depth_5_50_95 [-]": np.percentile(
                install_cv[both] / direct_cv[both], [5, 50, 95]).tolist(),
            "blows [-]": install_row["blows [-]"]},
        "departures_final": departures,
        "stacking_weight_g [-]": weight_g,
        "stacking_weight_final [-]": weight,
        "surface_vs_direct_at_d": {
            "rms [blows/m]": rmse(surface_at_d, direct1),
            "bias [blows/m]": float(np.mean(surface_at_d - direct1))},
        "surface_vs_direct_at_final": {
            "rms [blows/m]": rmse(surface_at_final, final_cal),
            "bias [blows/m]": float(np.mean(surface_at_final - final_cal))},
        "calibration_direct": {
            "rmse_single_blow_d [blows/m]": rmse(direct1, measured),
            "bias_single_blow_d [blows/m]": float(np.mean(direct1 - measured)),
            "rmse_residual_stress_d [blows/m]": rmse(directn, measured),
            "bias_residual_stress_d [blows/m]": float(np.mean(directn - measured)),
            "rmse_final [blows/m]": rmse(final_cal, measured),
            "bias_final [blows/m]": float(np.mean(final_cal - measured)),
            "rmse_installation_final [blows/m]": rmse(install_cal, measured),
            "bias_installation_final [blows/m]": float(np.mean(install_cal - measured)),
            "residual_stress_ratio_5_50_95 [-]": np.percentile(
                stress_ratio[direct1 > 0], [5, 50, 95]).tolist()},
        "largest_blow_energy_d [J]": max_energy_d,
        "largest_blow_energy [J]": max_energy,
        "hammer_rated_energy [J]": rated,
        "prediction_piles_mean_blowcount [blows/m]": {
            k: float(np.mean(v)) for k, v in per_pile.items()},
        "prediction_points [-]": len(pred_rows),
        "cpt": "the 0.5 m series of each pile's foundation, for every pile (calibration and "
               "prediction)",
        "model": {k: getattr(model_f, k) for k in Model.__dataclass_fields__},
        "times": times, "wall_time [s]": time.perf_counter() - start,
        "workers [-]": args.workers,
    }
    summary = _jsonable(summary)
    (out / "isfog_backanalysis.json").write_text(json.dumps(summary, indent=2) + "\n")
    if args.docs:
        write_cross_validation_docs(summary, Path(os.path.abspath(args.data)),
                                    {p.location_id: p.cpt_group for p in prediction},
                                    docs_command(args.argv))
    print(f"\n{'step':<70} {'CV RMSE':>8} {'bias':>6} {'naive':>6} {'bias':>6}")
    for r in rows:
        print(f"{r['step']:<70} {r['rmse [blows/m]']:8.1f} {r['bias [blows/m]']:+6.1f} "
              f"{r['rmse_baseline [blows/m]']:6.1f} {r['bias_baseline [blows/m]']:+6.1f}")
    print(f"\nfinal fit ({FINAL_STEP}, all {n_cal} calibration piles): E_ref "
          f"{final['E_ref [J]'] / 1e3:.0f} kJ (at most {e_max / 1e3:.0f}), fatigue rate x"
          f"{final['fatigue_rate [-]']:.2f}, SRD x sand {model_f.srd_sand:.2f}, clay "
          f"{model_f.srd_clay:.2f}, toe {model_f.srd_toe:.2f}; largest blow energy "
          f"{max_energy / 1e3:.0f} kJ (rating {rated / 1e3:.0f} kJ); direct RMSE "
          f"{rmse(final_cal, measured):.1f} blows/m, surface vs direct "
          f"{rmse(surface_at_final, final_cal):.1f}")
    print("prediction piles, predicted blow count [blows/m] at every whole metre driven:")
    for p in prediction:
        counts = [f"{r['blowcount [blows/m]']:.0f}" for r in pred_rows
                  if r["location_id"] == p.location_id]
        print(f"  {p.location_id} ({p.depths[0]:g}-{p.depths[-1]:g} m, mean "
              f"{np.mean(per_pile[p.location_id]):.1f}): {' '.join(counts)}")
    print(f"wall time {summary['wall_time [s]']:.0f} s; results in {out}")
    return 0


# ----------------------------------------------------------------------------- output
def write_csv(path: Path, rows: list[dict]) -> None:
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(dict.fromkeys(k for r in rows
                                                                      for k in r)))
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                             for k, v in row.items()})


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.generic):
        return _jsonable(x.item())
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def plot_calibration(path: Path, piles, predicted, table, summary) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    order = np.argsort([r["rmse [blows/m]"] for r in table[:-1]])
    picks = list(dict.fromkeys(int(order[int(round(q * (len(order) - 1)))])
                               for q in np.linspace(0.0, 1.0, min(8, len(order)))))
    cols = 4
    rows = -(-len(picks) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 4.2 * rows), squeeze=False,
                             sharey=True)
    for ax in axes.flat[len(picks):]:
        ax.set_visible(False)
    for ax, k in zip(axes.flat, picks, strict=False):
        p = piles[k]
        ax.plot(p.measured, p.depths, "o", ms=3, color="0.3", label="measured")
        ax.plot(predicted[k], p.depths, "-", color="C3", label="predicted")
        ax.set_title(f"{p.location_id} ({p.cpt_group})\nRMSE {table[k]['rmse [blows/m]']:.0f}, "
                     f"bias {table[k]['bias [blows/m]']:+.0f} blows/m", fontsize=8)
        ax.set_xlabel("blow count [blows/m]")
        ax.grid(alpha=0.3)
    axes[0, 0].invert_yaxis()
    for ax in axes[:, 0]:
        ax.set_ylabel("tip depth below mudline [m]")
    axes[0, 0].legend(fontsize=7)
    fit_ = summary["fit"]
    fig.suptitle(f"ISFOG 2020 calibration piles, from best to worst fit: E_ref "
                 f"{fit_['E_ref [J]'] / 1e3:.0f} kJ, SRD x {fit_['srd_multiplier [-]']:.2f}",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fit(path: Path, piles, predicted, table, summary) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4.6))
    every_m = np.concatenate([p.measured for p in piles])
    every_p = np.concatenate(predicted)
    a.plot(every_m, every_p, ".", ms=3, alpha=0.4)
    top = max(every_m.max(), every_p.max()) * 1.05
    a.plot([0, top], [0, top], "k-", lw=0.8)
    a.set_xlim(0, top)
    a.set_ylim(0, top)
    a.set_xlabel("measured blow count [blows/m]")
    a.set_ylabel("predicted blow count [blows/m]")
    over = table[-1]
    a.set_title(f"{over['points [-]']} records of {len(piles)} piles: RMSE "
                f"{over['rmse [blows/m]']:.1f}, bias {over['bias [blows/m]']:+.1f} blows/m",
                fontsize=9)
    a.grid(alpha=0.3)
    r = np.array([t["rmse [blows/m]"] for t in table[:-1]])
    s = np.array([t["bias [blows/m]"] for t in table[:-1]])
    b.plot(s, r, "o", ms=4)
    for t in table[:-1]:
        b.annotate(t["location_id"], (t["bias [blows/m]"], t["rmse [blows/m]"]), fontsize=5)
    b.axvline(0.0, color="k", lw=0.8)
    b.set_xlabel("bias per pile [blows/m]")
    b.set_ylabel("RMSE per pile [blows/m]")
    b.grid(alpha=0.3)
    for key, label in (("fit_energy_and_multiplier", "fitted multiplier"),
                       ("fit_energy_only", "multiplier 1")):
        if key in summary:
            curve = np.array(summary[key]["rmse_curve"])
            c.semilogx(curve[:, 0] / 1e3, curve[:, 1],
                       label=f"{label} ({summary[key]['srd_multiplier [-]']:.2f})")
    c.axvline(summary["fit"]["E_ref [J]"] / 1e3, color="k", lw=0.8)
    c.set_xlabel("reference energy E_ref [kJ]")
    c.set_ylabel("RMSE (grid interpolation) [blows/m]")
    c.legend(fontsize=8)
    c.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_predictions(path: Path, piles, results, e_ref: float) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = min(3, len(piles))
    rows = -(-len(piles) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 4.2 * rows), squeeze=False,
                             sharey=True)
    for ax in axes.flat[len(piles):]:
        ax.set_visible(False)
    for ax, p, r in zip(axes.flat, piles, results, strict=False):
        ax.plot(r["count"][0, 0], p.depths, "-o", ms=3, color="C3", label="blow count")
        ax.set_xlabel("predicted blow count [blows/m]")
        ax.set_title(f"{p.location_id} ({p.cpt_group}, t {p.wall_thickness * 1e3:.0f} mm)",
                     fontsize=9)
        ax.grid(alpha=0.3)
        twin = ax.twiny()
        twin.plot(p.energy * e_ref / 1e3, p.depths, "--", color="C0", lw=0.8)
        twin.set_xlabel("blow energy [kJ]", color="C0", fontsize=8)
    axes[0, 0].invert_yaxis()
    for ax in axes[:, 0]:
        ax.set_ylabel("tip depth below mudline [m]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ----------------------------------------------------------------------------- docs data
PHYSICS_STEPS = "ABCDFHIKLMNO"
"""The physics steps of the back-analysis (E tried and not kept; G and J blends)."""
OWN_CPT_STEPS = PHYSICS_STEPS.replace("O", "")
"""The physics steps whose soil is the foundation's own CPT (O kriges it towards the
site's)."""
DOCS_NAME = "isfog_backanalysis"
"""docs/data/isfog_backanalysis.json: the cross-validation's table and quoted numbers."""
STEP_COLUMNS = {
    "step": (None, "step"),
    "CV RMSE [blows/m]": ("f1", "rmse [blows/m]"),
    "CV bias [blows/m]": ("f1", "bias [blows/m]"),
    "naive RMSE [blows/m]": ("f1", "rmse_baseline [blows/m]"),
    "naive bias [blows/m]": ("f1", "bias_baseline [blows/m]"),
}
"""The columns of docs/validation.md's cross-validation table: (format, key of a step)."""


def records_inputs(data: Path, hammer: str) -> list[Path]:
    """The files a run reads: the records (CSV files of ``data``) and the hammer's file
    (``data`` unresolved: the data file names the records as ``../shared/...``)."""
    return [*sorted(Path(data).glob("*.csv")),
            ROOT / "anvilwave" / "hammer" / "data" / f"{hammer}.toml"]


def _range_text(values) -> str:
    """``64-68``: the smallest and largest value, rounded down and up to whole numbers."""
    return f"{math.floor(min(values)):d}-{math.ceil(max(values)):d}"


def prediction_means_text(means: dict, groups: dict) -> str:
    """``64-68 blows/m (AA-AC), 67-72 (CD-CF) and 59-60 (CJ-CL)``: the range of the
    prediction piles' mean blow counts per foundation (``groups``: pile -> foundation)."""
    by_group: dict[str, list[str]] = {}
    for pile in sorted(means):
        by_group.setdefault(groups[pile], []).append(pile)
    parts = [f"{_range_text([means[p] for p in piles])}"
             + (" blows/m" if i == 0 else "") + f" ({piles[0]}-{piles[-1]})"
             for i, piles in enumerate(by_group.values())]
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def cross_validation_docs(summary: dict, groups: dict) -> tuple[dict, dict]:
    """The table and the substitutions of docs/validation.md's section from the summary of a
    ``--cross-validate`` run (its ``isfog_backanalysis.json``); ``groups``: prediction pile
    -> foundation."""
    steps = {s["step"].split(":")[0]: s for s in summary["steps"]}
    table = {"columns": list(STEP_COLUMNS), "formats": [f for f, _ in STEP_COLUMNS.values()],
             "rows": [[s[k] for _, k in STEP_COLUMNS.values()] for s in summary["steps"]]}
    score = {k: s["rmse [blows/m]"] for k, s in steps.items()}
    final_fit, model = summary["final_fit"], summary["model"]
    fit_d, srd_d = summary["fit_d"], summary["srd_multipliers_d [-]"]
    ratio = summary["calibration_direct"]["residual_stress_ratio_5_50_95 [-]"]
    direct = summary["calibration_direct"]
    surface = summary["surface_vs_direct_at_final"]
    surface_d = summary["surface_vs_direct_at_d"]
    installation = summary["installation_cv"]
    departures = summary["departures_final"]
    means = summary["prediction_piles_mean_blowcount [blows/m]"]
    naive = summary["naive_rmse [blows/m]"]
    subs = {
        "points": [summary["cv_points [-]"], "int"],
        "training_foundations": [summary["cv_folds [-]"] - 1, "int"],
        "cv_time": [summary["times"]["cross_validation [s]"], "int"],
        "c_gain": [score["C"] - score["B"], "int"],
        "srd_sand": [srd_d["sand"], "f2"],
        "srd_clay": [srd_d["clay"], "f2"],
        "srd_toe": [srd_d["toe"], "f2"],
        "sand_toe_factor": [model["sand_toe_factor"], "f2"],
        "e_ref": [fit_d["E_ref [J]"], "kJ0"],
        "d_gain": [score["D"] - score["C"], "f1"],
        "energy_exponent": [steps["E"]["energy_exponent [-] folds median"], "f2"],
        "e_gain": [score["E"] - score["D"], "f1"],
        "residual_stress_p5": [ratio[0] - 1.0, "pct+sig2"],
        "residual_stress_p95": [ratio[2] - 1.0, "pct+sig2"],
        "f_change": [score["F"] - score["D"], "f1+"],
        "stacking_weight": [summary["stacking_weight_g [-]"], "f2"],
        "stacking_weight_folds": [steps["G"]["stacking_weight [-] folds median"], "f2"],
        "g_rmse": [score["G"], "f1"],
        "largest_blow_energy_d": [summary["largest_blow_energy_d [J]"], "kJ0"],
        "rated_energy": [summary["hammer_rated_energy [J]"], "kJ0"],
        "h_change": [score["H"] - score["D"], "f1+"],
        "e_ref_max": [final_fit["E_ref_max [J]"], "kJ0"],
        "i_gain": [score["I"] - score["H"], "f1+"],
        "fatigue_rate": [final_fit["fatigue_rate [-]"], "f2"],
        "fatigue_rate_folds_min": [steps["I"]["fatigue_rate [-] folds min"], "f2"],
        "fatigue_rate_folds_max": [steps["I"]["fatigue_rate [-] folds max"], "f2"],
        "final_srd_sand": [model["srd_sand"], "f2"],
        "final_srd_clay": [model["srd_clay"], "f2"],
        "final_srd_toe": [model["srd_toe"], "f2"],
        "final_e_ref": [final_fit["E_ref [J]"], "kJ0"],
        "largest_blow_energy": [summary["largest_blow_energy [J]"], "kJ0"],
        "cv_rmse": [summary["cv_rmse [blows/m]"], "f1"],
        "cv_bias": [summary["cv_bias [blows/m]"], "f1+"],
        "naive_rmse": [naive, "f1"],
        "naive_bias": [summary["naive_bias [blows/m]"], "f1+"],
        "final_minus_naive": [summary["cv_rmse [blows/m]"] - naive, "f1+"],
        "best_physics": [min(score[k] for k in PHYSICS_STEPS), "f1"],
        "k_change": [score["K"] - score["I"], "f1+"],
        "k_heavier_folds": [steps["K"]["folds with ihc_s1800 [-]"], "int"],
        "l_change": [score["L"] - score["I"], "f1+"],
        "l_damping_sand": [steps["L"]["damping_sand [-] folds median"], "f2"],
        "l_damping_clay": [steps["L"]["damping_clay [-] folds median"], "f2"],
        "l_damping_toe_sand": [steps["L"]["damping_toe_sand [-] folds median"], "f2"],
        "l_quake_toe_sand": [steps["L"]["quake_toe_sand [-] folds median"], "f2"],
        "m_rmse": [score["M"], "f1"],
        "m_bias": [steps["M"]["bias [blows/m]"], "f1+"],
        "m_change": [score["M"] - score["I"], "f1+"],
        "m_minus_naive": [score["M"] - naive, "f1+"],
        "o_rmse": [score["O"], "f1"],
        "o_bias": [steps["O"]["bias [blows/m]"], "f1+"],
        "o_change": [score["O"] - score["I"], "f1+"],
        "o_minus_naive": [score["O"] - naive, "f1+"],
        "o_weight_median": [steps["O"]["site_weight [-] folds median"], "f3"],
        "o_weight_min": [steps["O"]["site_weight [-] folds min"], "f3"],
        "o_weight_max": [steps["O"]["site_weight [-] folds max"], "f3"],
        "o_departure_correlation": [steps["O"]["departure_correlation [-]"], "f2"],
        "o_departure_needed_correlation": [steps["O"]["departure_needed_correlation [-]"],
                                           "f2"],
        "soil_part_sd": [departures["soil_part_sd [blows/m]"], "f1"],
        "soil_part_correlation": [departures["soil_part_correlation [-]"], "f2"],
        "energy_part_sd": [departures["energy_part_sd [blows/m]"], "f1"],
        "energy_part_correlation": [departures["energy_part_correlation [-]"], "f2+"],
        "soil_energy_correlation": [departures["soil_energy_correlation [-]"], "f2+"],
        "j_rmse": [score["J"], "f1"],
        "n_rmse": [score["N"], "f1"],
        "n_bias": [steps["N"]["bias [blows/m]"], "f1+"],
        "n_minus_naive": [score["N"] - naive, "f1+"],
        "n_blows": [steps["N"]["blows [-]"], "int"],
        "n_direct_rmse": [installation["per_depth_direct_rmse [blows/m]"], "f1"],
        "n_change_direct": [score["N"] - installation["per_depth_direct_rmse [blows/m]"],
                            "f1+"],
        "n_ratio_p5": [installation["installation_over_per_depth_5_50_95 [-]"][0] - 1.0,
                       "pct+sig2"],
        "n_ratio_p95": [installation["installation_over_per_depth_5_50_95 [-]"][2] - 1.0,
                        "pct+sig2"],
        "final_installation_rmse": [direct["rmse_installation_final [blows/m]"], "f1"],
        "within_foundation_sd": [departures["within_foundation_sd [blows/m]"], "f1"],
        "departure_sd_measured": [departures["measured_sd [blows/m]"], "f1"],
        "departure_sd_model": [departures["model_sd [blows/m]"], "f1"],
        "departure_correlation": [departures["correlation [-]"], "f2"],
        "departure_correlation_foundation": [departures["foundation_correlation [-]"], "f2"],
        "departure_needed_correlation": [departures["needed_correlation [-]"], "f2"],
        "trend_from_records_rmse": [departures["trend_from_records_rmse [blows/m]"], "f1"],
        "departure_correlation_physics_min": [min(
            steps[k]["departure_correlation [-]"] for k in OWN_CPT_STEPS), "f2"],
        "departure_correlation_physics_max": [max(
            steps[k]["departure_correlation [-]"] for k in OWN_CPT_STEPS), "f2"],
        "piles_below_naive": [summary["piles_final_below_naive [-]"], "int"],
        "piles_scored": [summary["piles_scored [-]"], "int"],
        "final_direct_rmse": [direct["rmse_final [blows/m]"], "f1"],
        "surface_rms": [surface["rms [blows/m]"], "f1"],
        "surface_bias": [surface["bias [blows/m]"], "f1+"],
        "surface_rms_d": [surface_d["rms [blows/m]"], "f1"],
        "prediction_piles": [len(means), "int"],
        "prediction_means": [prediction_means_text(means, groups), None],
    }
    return {"steps": table}, subs


def write_cross_validation_docs(summary: dict, data: Path, groups: dict, command: str) -> Path:
    """docs/data/isfog_backanalysis.json (benchmarks/doc_data.py's format) from the summary of
    a ``--cross-validate`` run; ``command``: the command that computed it."""
    tables, subs = cross_validation_docs(summary, groups)
    return write_doc_data(
        DOCS_NAME, about="the ISFOG 2020 back-analysis cross-validated leave one foundation "
        "out, step by step, against the naive depth-mean baseline (docs/validation.md, \"Does "
        "the back-analysis predict?\")",
        inputs=records_inputs(data, summary["model"]["hammer"]), tables=tables,
        substitutions=subs, values=summary, command=command)


CALIBRATION_DOCS = "isfog_calibration"
"""docs/data/isfog_calibration.json: the calibration fit of docs/drive.md."""


def calibration_docs(summary: dict) -> tuple[dict, dict]:
    """The table and the substitutions of docs/drive.md's calibration fit from the summary of
    a default run (its ``calibration_summary.json``): the two-parameter fit's RMSE and bias
    from the direct runs, the energy-only fit's from the grid's interpolation (it is not run
    directly); the largest blow energy of each is the records' largest normalised energy
    times its E_ref."""
    both, alone = summary["fit_energy_and_multiplier"], summary["fit_energy_only"]
    largest = summary["largest_blow_energy [J]"] / summary["E_ref [J]"]
    table = {"columns": ["fit", "E_ref", "SRD multiplier", "largest blow energy",
                         "RMSE [blows/m]", "bias [blows/m]"],
             "formats": [None, "kJ0", "f2", "kJ0", "f1", "f1"],
             "rows": [["energy and multiplier (default; direct runs)", both["E_ref [J]"],
                       both["srd_multiplier [-]"], largest * both["E_ref [J]"],
                       summary["rmse [blows/m]"], summary["bias [blows/m]"]],
                      ["energy only (interpolated)", alone["E_ref [J]"],
                       alone["srd_multiplier [-]"], largest * alone["E_ref [J]"],
                       alone["rmse_interpolated [blows/m]"],
                       alone["bias_interpolated [blows/m]"]]]}
    rmse_range, bias_range = (summary["rmse_per_pile_range [blows/m]"],
                              summary["bias_per_pile_range [blows/m]"])
    subs = {
        "wall_time": [summary["wall_time [s]"], "int"],
        "blows": [len(summary["grid_energies [J]"]) * len(summary["grid_multipliers [-]"])
                  * summary["calibration_records [-]"], "int"],
        "rated_energy": [summary["driving_system"]["rated_energy [J]"], "kJ0"],
        "rmse_min": [rmse_range[0], "int"], "rmse_max": [rmse_range[1], "int"],
        "rmse_median": [summary["rmse_per_pile_median [blows/m]"], "int"],
        "bias_min": [bias_range[0], "int+"], "bias_max": [bias_range[1], "int+"],
        "workers": [summary["workers [-]"], "int"],
    }
    return {"fits": table}, subs


def write_calibration_docs(summary: dict, data: Path, command: str) -> Path:
    """docs/data/isfog_calibration.json from the summary of a default run."""
    tables, subs = calibration_docs(summary)
    return write_doc_data(
        CALIBRATION_DOCS, about="the ISFOG 2020 calibration fit: one E_ref and one SRD "
        "multiplier on every calibration pile (docs/drive.md)",
        inputs=records_inputs(data, summary["model"]["hammer"]), tables=tables,
        substitutions=subs, values=summary, command=command)


def docs_command(argv: list[str]) -> str:
    """The command of a ``--cross-validate --docs`` run with the arguments ``argv`` (without
    ``--docs-from FILE`` and ``--cache DIR``, which change no result; with ``--docs``)."""
    rest, skip = [], False
    for arg in argv:
        if skip:
            skip = False
        elif arg in ("--docs-from", "--cache"):
            skip = True
        elif (not arg.startswith(("--docs-from=", "--cache=")) and arg != "--docs"):
            rest.append(arg)
    return shlex.join(["python", "benchmarks/isfog_backanalysis.py", *rest, "--docs"])


# ----------------------------------------------------------------------------- main
def _list(text: str | None) -> list[str] | None:
    return [t.strip() for t in text.split(",") if t.strip()] if text else None


def parse_args(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", type=Path, default=DEFAULT_DATA,
                        help="the ISFOG 2020 records (default: ../shared/reference/isfog2020 "
                             "beside the repository)")
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "isfog_backanalysis")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                        help="processes over the piles (default: the machine's cores)")
    parser.add_argument("--hammer", default=Model.hammer, help="hammer of anvilwave/hammer/data")
    parser.add_argument("--piles", help="calibration piles to use, e.g. AD,AE (default: all)")
    parser.add_argument("--prediction-piles", help="prediction piles (default: all)")
    parser.add_argument("--prediction-cpt", choices=("fullres", "0p5m"), default="0p5m",
                        help="CPT of the prediction piles (default: the 0.5 m series, the "
                             "processing of the calibration piles)")
    parser.add_argument("--energies", type=int, default=7,
                        help="reference energies of the grid (log-spaced)")
    parser.add_argument("--energy-range", default="150e3,3200e3",
                        help="smallest and largest reference energy of the grid [J]")
    parser.add_argument("--multipliers", default="0.25,0.35,0.5,0.7,1.0,1.4",
                        help="SRD multipliers of the grid; '1' fits the energy alone")
    parser.add_argument("--fit", choices=("energy", "energy+multiplier"),
                        default="energy+multiplier", help="the fit used for the predictions")
    parser.add_argument("--cross-validate", action="store_true",
                        help="leave-one-foundation-out cross-validation against the naive "
                             "baseline (mean of the other foundations at each depth)")
    parser.add_argument("--docs", action="store_true",
                        help="also write the docs' data file: docs/data/isfog_calibration.json"
                             " (with --cross-validate: isfog_backanalysis.json; the summary "
                             "stays in --out)")
    parser.add_argument("--cache", type=Path, metavar="DIR",
                        help="with --cross-validate: keep the grids' and the direct runs' "
                             "blow counts in DIR and reuse them when every input is the same "
                             "(a rerun then only fits)")
    parser.add_argument("--docs-from", type=Path, metavar="RESULT_JSON",
                        help="only rewrite the docs' data file from the summary of an earlier "
                             "run (isfog_backanalysis.json of --cross-validate, else "
                             "calibration_summary.json) made with the other arguments given "
                             "(the command it records)")
    parser.add_argument("--sand-toe-factor", type=float, default=Model.sand_toe_factor,
                        help="Alm & Hamre sand toe factor (0.10: 2018 revision; 0.15: 2001)")
    parser.add_argument("--segment-length", type=float, default=Model.segment_length,
                        help="pile segment length [m]")
    parser.add_argument("--duration", type=float, default=Model.duration,
                        help="blow window [s]")
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    return args


def main(argv=None) -> int:
    args = parse_args(argv)
    data = args.data.resolve()
    needed = ("calibration_piles.csv", "calibration_piles_0p5m.csv", "prediction_piles.csv",
              "prediction_piles_0p5m.csv")
    if not all((data / n).exists() for n in needed):
        print(f"isfog_backanalysis: skipped, the ISFOG 2020 records were not found in {data} "
              "(expected beside the repository in ../shared/reference/isfog2020; give "
              "--data DIR)")
        return 0
    if args.docs_from is not None:
        try:
            summary = json.loads(args.docs_from.read_text())
            summary["model"]["hammer"]
            if "steps" not in summary:
                summary["fit_energy_only"], summary["rmse_per_pile_range [blows/m]"]
        except (OSError, ValueError, KeyError, TypeError) as exc:
            print(f"isfog_backanalysis: --docs-from {args.docs_from}: not the summary of a run "
                  f"(isfog_backanalysis.json or calibration_summary.json; {exc!r})",
                  file=sys.stderr)
            return 2
        if "steps" in summary:
            groups = {p.location_id: p.cpt_group for p in prediction_piles(data)}
            write_cross_validation_docs(summary, Path(os.path.abspath(args.data)), groups,
                                        docs_command(args.argv))
        else:
            write_calibration_docs(summary, Path(os.path.abspath(args.data)),
                                   docs_command(args.argv))
        return 0
    start = time.perf_counter()
    times = {}
    model = replace(Model(), hammer=args.hammer, segment_length=args.segment_length,
                    duration=args.duration, sand_toe_factor=args.sand_toe_factor)
    try:
        e_low, e_high = (float(v) for v in args.energy_range.split(","))
        multipliers = np.array(sorted(float(v) for v in args.multipliers.split(",")))
    except ValueError:
        raise SystemExit("--energy-range takes two energies [J] and --multipliers a list of "
                         "numbers, comma-separated") from None
    if not (0.0 < e_low <= e_high) or np.any(multipliers <= 0.0) or args.energies < 1 \
            or args.workers < 1:
        raise SystemExit("energies and multipliers must be positive, --energies and --workers "
                         "at least 1")
    energies = np.geomspace(e_low, e_high, args.energies) if args.energies > 1 else \
        np.array([math.sqrt(e_low * e_high)])
    with_multiplier = args.fit == "energy+multiplier" and multipliers.size > 1
    if not with_multiplier and multipliers.size > 1 and not np.any(np.isclose(multipliers, 1)):
        raise SystemExit("--fit energy needs the multiplier 1 among --multipliers")
    calibration = calibration_piles(data, _list(args.piles))
    prediction = prediction_piles(data, _list(args.prediction_piles), args.prediction_cpt)
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    print(f"{len(calibration)} calibration piles ({sum(len(p.depths) for p in calibration)} "
          f"records), {len(prediction)} prediction piles; grid {energies.size} energies x "
          f"{multipliers.size} multipliers; {args.workers} workers")
    if args.cross_validate:
        return predictive_backanalysis(args, model, calibration, prediction, out, energies,
                                       multipliers)

    t = time.perf_counter()
    warm_up(model, calibration[0])
    times["warm_up [s]"] = time.perf_counter() - t
    t = time.perf_counter()
    grid = run_piles(calibration, model, energies, multipliers, args.workers)
    times["grid [s]"] = time.perf_counter() - t
    blows = energies.size * multipliers.size * sum(len(p.depths) for p in calibration)
    print(f"grid: {blows} blows in {times['grid [s]']:.1f} s")

    measured = np.concatenate([p.measured for p in calibration])
    interp = GridInterpolator(energies, multipliers,
                              np.concatenate([g["count"] for g in grid], axis=2),
                              np.concatenate([g["run_multiplier"] for g in grid]))
    t = time.perf_counter()
    fits = {}
    if multipliers.size > 1:
        fits["fit"] = fit(interp, measured, True)
    if multipliers.size == 1 or np.any(np.isclose(multipliers, 1.0)):
        fits["fit_energy_only"] = fit(interp, measured, False)
    chosen = fits["fit"] if with_multiplier else fits["fit_energy_only"]
    times["fit [s]"] = time.perf_counter() - t
    e_ref, mult = chosen["E_ref [J]"], chosen["srd_multiplier [-]"]
    print(f"fit: E_ref {e_ref / 1e3:.1f} kJ, SRD multiplier {mult:.3f} (interpolated RMSE "
          f"{chosen['rmse_interpolated [blows/m]']:.1f} blows/m)")

    t = time.perf_counter()
    direct = run_piles(calibration + prediction, model, [e_ref], [mult], args.workers)
    times["direct [s]"] = time.perf_counter() - t
    cal_direct, pred_direct = direct[:len(calibration)], direct[len(calibration):]
    predicted = [r["count"][0, 0] for r in cal_direct]
    table = per_pile_table(calibration, predicted)
    write_csv(out / "calibration_fit.csv", table)

    details = []
    for p, r, g in zip(calibration, cal_direct, grid, strict=True):
        interp_p = GridInterpolator(energies, multipliers, g["count"],
                                    g["run_multiplier"])(e_ref, mult)
        for k, z in enumerate(p.depths):
            details.append({
                "location_id": p.location_id, "z [m]": float(z),
                "normalised_hammer_energy [-]": float(p.energy[k]),
                "energy_setting [J]": float(p.energy[k] * e_ref),
                "blowcount_measured [blows/m]": float(p.measured[k]),
                "blowcount [blows/m]": float(r["count"][0, 0, k]),
                "blowcount_interpolated [blows/m]": float(interp_p[k]),
                "srd [N]": float(mult * (r["srd_shaft"][k] + r["srd_toe"][k])),
                "srd_shaft [N]": float(mult * r["srd_shaft"][k]),
                "srd_toe [N]": float(mult * r["srd_toe"][k]),
                "damping_shaft [s/m]": float(r["damping_shaft"][k]),
                "enthru [J]": float(r["enthru"][0, 0, k]),
                "max_compression_stress [Pa]": float(r["compression"][0, 0, k]),
                "max_tension_stress [Pa]": float(r["tension"][0, 0, k])})
    write_csv(out / "calibration_blowcount.csv", details)

    pred_rows, pred_details = [], []
    for p, r in zip(prediction, pred_direct, strict=True):
        for k, z in enumerate(p.depths):
            count = float(r["count"][0, 0, k])
            pred_rows.append(dict(zip(PREDICTION_CSV_COLUMNS, (p.location_id, float(z), count),
                                      strict=True)))
            pred_details.append({
                "location_id": p.location_id, "z [m]": float(z),
                "normalised_hammer_energy [-]": float(p.energy[k]),
                "energy_setting [J]": float(p.energy[k] * e_ref),
                "blowcount [blows/m]": count,
                "srd [N]": float(mult * (r["srd_shaft"][k] + r["srd_toe"][k])),
                "srd_shaft [N]": float(mult * r["srd_shaft"][k]),
                "srd_toe [N]": float(mult * r["srd_toe"][k]),
                "damping_shaft [s/m]": float(r["damping_shaft"][k]),
                "enthru [J]": float(r["enthru"][0, 0, k]),
                "max_compression_stress [Pa]": float(r["compression"][0, 0, k]),
                "max_tension_stress [Pa]": float(r["tension"][0, 0, k]),
                "cpt": Path(p.cpt_file).name})
    if pred_rows:
        write_csv(out / "prediction_piles_blowcount.csv", pred_rows)
        write_csv(out / "prediction_details.csv", pred_details)

    every_direct = np.concatenate(predicted)
    every_interp = np.array([d["blowcount_interpolated [blows/m]"] for d in details])
    enthru = np.array([d["enthru [J]"] / d["energy_setting [J]"] for d in details])
    per_pile = table[:-1]
    ds = driving_system(model)
    max_energy = float(max(p.energy.max() for p in calibration + prediction) * e_ref)
    summary = {
        "fit": chosen,
        "fit_used_for_predictions": "energy+multiplier" if with_multiplier else "energy",
        "E_ref [J]": e_ref, "srd_multiplier [-]": mult,
        "rmse [blows/m]": table[-1]["rmse [blows/m]"],
        "bias [blows/m]": table[-1]["bias [blows/m]"],
        "rmse_per_pile_range [blows/m]": [min(r["rmse [blows/m]"] for r in per_pile),
                                          max(r["rmse [blows/m]"] for r in per_pile)],
        "bias_per_pile_range [blows/m]": [min(r["bias [blows/m]"] for r in per_pile),
                                          max(r["bias [blows/m]"] for r in per_pile)],
        "rmse_per_pile_median [blows/m]": float(np.median([r["rmse [blows/m]"]
                                                           for r in per_pile])),
        "interpolation_error_rms [blows/m]": rmse(every_interp, every_direct),
        "calibration_piles [-]": len(calibration), "calibration_records [-]": int(measured.size),
        "prediction_piles [-]": len(prediction), "prediction_records [-]": len(pred_rows),
        "largest_blow_energy [J]": max_energy,
        "largest_blow_energy_within_rating": bool(max_energy <= ds["rated_energy [J]"] * 1.0001),
        "enthru_over_energy_median [-]": float(np.nanmedian(enthru)) if enthru.size else None,
        "grid_energies [J]": energies.tolist(), "grid_multipliers [-]": multipliers.tolist(),
        "driving_system": ds,
        "model": {k: getattr(model, k) for k in Model.__dataclass_fields__},
        "assumptions": {
            "pile": "D 2.48 m, the bottom wall thickness over the whole length (uniform), "
                    f"length = final penetration + {model.stick_up:g} m stick-up",
            "soil": "Robertson (2009) Ic < 2.6 sand, else clay; submerged unit weights "
                    f"{model.sand_unit_weight / 1e3:g} (sand) and "
                    f"{model.clay_unit_weight / 1e3:g} kN/m^3 (clay); water depth irrelevant",
            "srd": "Alm & Hamre (2001) from the CPT, coring, delta "
                   f"{model.sand_delta:g} deg, sand toe factor {model.sand_toe_factor:g}, "
                   "one global multiplier",
            "hammer": f"{ds['hammer']}, classic driving system (estimates scaled from "
                      "GRLWEAP's S-4000 model)",
            "energy": "blow energy = normalised hammer energy x E_ref (one value for all)",
            "prediction_depths": "every whole metre where the prediction record gives a "
                                 "hammer energy",
            "prediction_cpt": args.prediction_cpt,
        },
        "data": os.path.relpath(Path(data).resolve(), ROOT),  # no absolute path in a result
        "times": times,
        "workers [-]": args.workers,
    }
    for key, label in (("fit", "fit_energy_and_multiplier"),
                       ("fit_energy_only", "fit_energy_only")):
        if key in fits:
            summary[label] = fits[key]
    t = time.perf_counter()
    plot_calibration(out / "calibration_profiles.png", calibration, predicted, table, summary)
    plot_fit(out / "calibration_fit.png", calibration, predicted, table, summary)
    if prediction:
        plot_predictions(out / "prediction_piles.png", prediction, pred_direct, e_ref)
    times["plots [s]"] = time.perf_counter() - t
    summary["wall_time [s]"] = time.perf_counter() - start
    summary = _jsonable(summary)
    (out / "calibration_summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    if args.docs:
        write_calibration_docs(summary, Path(os.path.abspath(args.data)),
                               docs_command(args.argv))
    print(f"calibration ({len(calibration)} piles, {measured.size} records, direct runs): "
          f"RMSE {summary['rmse [blows/m]']:.1f} blows/m, bias "
          f"{summary['bias [blows/m]']:+.1f} blows/m; per pile RMSE "
          f"{summary['rmse_per_pile_range [blows/m]'][0]:.1f}-"
          f"{summary['rmse_per_pile_range [blows/m]'][1]:.1f}, bias "
          f"{summary['bias_per_pile_range [blows/m]'][0]:+.1f} to "
          f"{summary['bias_per_pile_range [blows/m]'][1]:+.1f}")
    print(f"wall time {summary['wall_time [s]']:.1f} s; results in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
