"""Ram impact velocity from the hammer's rated energy or stroke.

A hammer's rated energy E is the potential energy of its ram at the rated (equivalent) stroke,
E = m g h. Only a part of it reaches the ram as kinetic energy just before impact; wave-equation
programs account for the losses (friction, hydraulic back-pressure, misalignment) with a hammer
efficiency eta, so that the impact velocity is v = sqrt(2 eta E / m) = sqrt(2 eta g h).
GRLWEAP recommends eta = 0.95 for hydraulic hammers that monitor the ram velocity before impact
(F. Rausche & A. Klesney, "Hammer types, efficiencies and models in GRLWEAP", PDCA conference,
2007).
"""

from __future__ import annotations

import math

GRAVITY = 9.81
"""Gravitational acceleration [m/s^2] used by anvilwave unless a configuration says otherwise."""


def impact_velocity_from_energy(rated_energy: float, ram_mass: float,
                                efficiency: float = 1.0) -> float:
    """Ram velocity just before impact [m/s]: v = sqrt(2 eta E / m).

    Parameters
    ----------
    rated_energy : float
        Rated (potential) energy of the blow E [J].
    ram_mass : float
        Ram mass m [kg].
    efficiency : float
        Hammer efficiency eta [-], the part of E that is kinetic energy at impact.

    Returns
    -------
    float
        Impact velocity v [m/s].
    """
    return math.sqrt(2.0 * efficiency * rated_energy / ram_mass)


def impact_velocity_from_stroke(stroke: float, efficiency: float = 1.0,
                                gravity: float = GRAVITY) -> float:
    """Ram velocity just before impact [m/s] after a fall: v = sqrt(2 eta g h).

    Parameters
    ----------
    stroke : float
        (Equivalent) fall height of the ram h [m].
    efficiency : float
        Hammer efficiency eta [-].
    gravity : float
        Gravitational acceleration g [m/s^2].

    Returns
    -------
    float
        Impact velocity v [m/s].
    """
    return math.sqrt(2.0 * efficiency * gravity * stroke)


def equivalent_stroke(rated_energy: float, ram_mass: float, gravity: float = GRAVITY) -> float:
    """Fall height [m] whose potential energy equals the rated energy: h = E / (m g).

    For hydraulic hammers that accelerate the ram on the down-stroke this is not the travel of
    the ram but the stroke a free-fall hammer would need for the same energy (the
    "equivalent stroke" of wave-equation programs).

    Parameters
    ----------
    rated_energy : float
        Rated energy E [J].
    ram_mass : float
        Ram mass m [kg].
    gravity : float
        Gravitational acceleration g [m/s^2].

    Returns
    -------
    float
        Equivalent stroke h [m].
    """
    return rated_energy / (ram_mass * gravity)
