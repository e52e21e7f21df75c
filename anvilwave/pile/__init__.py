"""Pile and soil: a non-uniform 1D pile (Smith lumped masses and springs), soil models on the
shaft and toe (Smith, Smith-viscous, Lysmer toe), SRD from unit resistances, static
equilibrium, and the numba kernels the FMU and the in-process engine call.

Method choice: Smith's lumped chain integrated by the leapfrog (semi-implicit Euler). At
Courant number 1 on a uniform pile it is identical to the Method of Characteristics (both are
exact on the characteristic grid), and unlike MoC it takes any sub-step, non-uniform segment
lengths and lumped soil springs without re-gridding, so MoC is not implemented. MoC would be
better where sections of different wave speed make the segment travel times unequal (the chain
then disperses in the sections run below Courant 1); for steel piles all sections share c.
"""

from anvilwave.pile.kernels import (
    ENERGY_KINETIC,
    ENERGY_SIZE,
    ENERGY_STRAIN,
    WORK_GRAVITY,
    WORK_HEAD,
    WORK_HEAD_SHORTENING,
    WORK_PILE_DAMPING,
    WORK_SOIL_DAMPING,
    WORK_SOIL_STATIC,
    energy_residual,
    gauge_force,
    gauge_velocity,
    head_displacement,
    head_face_work,
    head_velocity,
    pile_step,
    soil_forces,
    soil_resistance,
    spring_force,
    stable_time_step,
    toe_displacement,
    toe_resistance,
    toe_velocity,
    top_force,
    update_energy,
)
from anvilwave.pile.model import (
    PileSoil,
    PileSoilArrays,
    PileSoilState,
    initial_state,
    load_pile_soil,
    substeps,
)
from anvilwave.pile.pile import PileSpec, Section, load_pile, pile_from_table
from anvilwave.pile.soil.models import MODELS, SoilSpec, soil_from_table
from anvilwave.pile.soil.srd import SoilResistanceTable
from anvilwave.pile.static import static_equilibrium

__all__ = [
    "ENERGY_KINETIC", "ENERGY_SIZE", "ENERGY_STRAIN", "MODELS", "WORK_GRAVITY", "WORK_HEAD",
    "WORK_HEAD_SHORTENING",
    "WORK_PILE_DAMPING", "WORK_SOIL_DAMPING", "WORK_SOIL_STATIC", "PileSoil", "PileSoilArrays",
    "PileSoilState", "PileSpec", "Section", "SoilResistanceTable", "SoilSpec",
    "energy_residual", "gauge_force", "gauge_velocity", "head_displacement", "head_face_work",
    "head_velocity", "initial_state", "load_pile", "load_pile_soil", "pile_from_table", "pile_step",
    "soil_forces", "soil_from_table", "soil_resistance", "spring_force", "stable_time_step",
    "static_equilibrium", "substeps", "toe_displacement", "toe_resistance", "toe_velocity",
    "top_force", "update_energy",
]
