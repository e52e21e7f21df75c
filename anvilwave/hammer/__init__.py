"""Hammer models for anvilwave: ram rods, impact velocity, cushions, driving system, database.

Modules
-------
impact          impact velocity from rated energy or stroke and efficiency
ram             the ram as a lumped-mass rod (or rigid) and its time-stepping kernels
cushion         compression-only cushion force with restitution and round-out
driving_system  the classic hammer cushion / helmet / pile cushion system (model "classic"),
                with GRLWEAP's ram bottom spring, hammer damping and assembly chain
database        hammer files (anvilwave/hammer/data/*.toml) with cited sources

All quantities are SI; z points down, displacement and velocity are positive downward and
forces positive in compression (DESIGN.md).
"""

from anvilwave.hammer.cushion import (
    cushion_force,
    hysteresis_loss,
    loading_compression,
    loading_force,
    loading_work,
    recoverable_energy,
)
from anvilwave.hammer.database import Hammer, HammerSource, available_hammers, load_hammer
from anvilwave.hammer.driving_system import (
    Cushion,
    DrivingSystem,
    driving_system_energy,
    driving_system_forces,
    driving_system_losses,
    driving_system_stable_time_step,
    driving_system_step,
    grlweap_2010_hammer_damping,
    interface_time_step,
    series_stiffness,
)
from anvilwave.hammer.impact import (
    GRAVITY,
    equivalent_stroke,
    impact_velocity_from_energy,
    impact_velocity_from_stroke,
)
from anvilwave.hammer.ram import (
    RamRod,
    gravity_potential_energy,
    kinetic_energy,
    momentum,
    ram_step,
    required_substeps,
    spring_forces,
    stable_time_step,
    strain_energy,
    toe_spring_force,
)
from anvilwave.hammer.ram_table import ram_from_table

__all__ = [
    "GRAVITY",
    "Cushion",
    "DrivingSystem",
    "Hammer",
    "HammerSource",
    "RamRod",
    "available_hammers",
    "cushion_force",
    "driving_system_energy",
    "driving_system_forces",
    "driving_system_losses",
    "driving_system_stable_time_step",
    "driving_system_step",
    "equivalent_stroke",
    "gravity_potential_energy",
    "grlweap_2010_hammer_damping",
    "hysteresis_loss",
    "impact_velocity_from_energy",
    "impact_velocity_from_stroke",
    "interface_time_step",
    "kinetic_energy",
    "load_hammer",
    "loading_compression",
    "loading_force",
    "loading_work",
    "momentum",
    "ram_from_table",
    "ram_step",
    "recoverable_energy",
    "required_substeps",
    "series_stiffness",
    "spring_forces",
    "stable_time_step",
    "strain_energy",
    "toe_spring_force",
]
