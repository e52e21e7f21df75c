"""Set-up of the shaft resistance during a pause in driving, and its remoulding by the blows
that follow.

Set-up: after a pause of duration t the shaft resistance is Q(t) = Q0 F(t), with
F(t) = 1 + A log10(t / t0) for t > t0 and 1 before (Skov & Denver 1988,
:func:`skov_denver_1988_setup`); A and t0 by soil type (:data:`SKOV_DENVER_1988`): sand
A = 0.2, t0 = 0.5 day; clay A = 0.6, t0 = 1 day.

Remoulding: the blows after the restart shear the soil along the shaft again; the gain F - 1
decays exponentially with the penetration s since the restart over a remoulding length L_r,
F(s) = 1 + (F(t) - 1) exp(-s / L_r) (:func:`remoulded_setup`): after 3 L_r 95 % of the gain
is gone. L_r is a model parameter (``[installation] remoulding_length``, default 0.5 m, an
assumption of this model, not a published constant), to be set from restrike records where
they exist.

The factor applies to the shaft resistance of the segments that were in the ground at the
pause (those embedded above the pause's tip depth); shaft newly embedded after the restart
and the toe are unchanged.

References
----------
Skov, R., Denver, H. (1988). Time-dependence of bearing capacity of piles. Proc. 3rd Int.
Conf. on the Application of Stress-Wave Theory to Piles, Ottawa, 879-888.
"""

from __future__ import annotations

import math

import numpy as np

SKOV_DENVER_1988 = {"sand": (0.2, 0.5 * 86400.0), "clay": (0.6, 86400.0)}
"""(A [-], t0 [s]) of Skov & Denver (1988) by soil type: sand A = 0.2, t0 = 0.5 day; clay
A = 0.6, t0 = 1 day."""

DEFAULT_REMOULDING_LENGTH = 0.5
"""Penetration over which the blows after a restart remould the set-up gain (e-folding) [m]."""


def skov_denver_1988_setup(duration: float, a: float, t0: float):
    """Set-up factor Q(t) / Q0 = 1 + A log10(t / t0) of the shaft resistance after a pause.

    Parameters
    ----------
    duration : float or ndarray
        Pause t [s], >= 0.
    a : float
        Set-up factor A [-] (sand 0.2, clay 0.6: :data:`SKOV_DENVER_1988`).
    t0 : float
        Reference time t0 [s] (sand 0.5 day, clay 1 day), > 0.

    Returns
    -------
    float or ndarray
        The factor [-]; 1 for t <= t0 (the relation holds from t0 on).

    Raises
    ------
    ValueError
        If A < 0, t0 <= 0 or a duration is negative.

    References
    ----------
    Skov, R., Denver, H. (1988). Time-dependence of bearing capacity of piles. Proc. 3rd Int.
    Conf. on the Application of Stress-Wave Theory to Piles, Ottawa, 879-888.
    """
    if a < 0.0 or t0 <= 0.0:
        raise ValueError(f"need A >= 0 and t0 > 0, got A = {a!r}, t0 = {t0!r} s")
    t = np.asarray(duration, dtype=float)
    if np.any(t < 0.0):
        raise ValueError("pause durations must not be negative [s]")
    factor = 1.0 + a * np.log10(np.maximum(t, t0) / t0)
    return float(factor) if factor.ndim == 0 else factor


def skov_denver_1988_for(soil_type: str, duration: float) -> float:
    """:func:`skov_denver_1988_setup` with the A and t0 of a soil type.

    Parameters
    ----------
    soil_type : {"sand", "clay"}
        The soil type (a key of :data:`SKOV_DENVER_1988`).
    duration : float or ndarray
        Pause t [s], >= 0.

    Returns
    -------
    float or ndarray
        The set-up factor [-].

    Raises
    ------
    ValueError
        If the soil type has no set-up values, or the duration is negative.
    """
    try:
        a, t0 = SKOV_DENVER_1988[soil_type]
    except KeyError:
        raise ValueError(f"no Skov & Denver (1988) set-up for soil type {soil_type!r}; "
                         f"choose one of {tuple(SKOV_DENVER_1988)}") from None
    return skov_denver_1988_setup(duration, a, t0)


def remoulded_setup(factor: float, penetration: float, remoulding_length: float) -> float:
    """Set-up factor left after the blows since a restart have driven ``penetration``.

    1 + (F - 1) exp(-s / L_r) (module docstring).

    Parameters
    ----------
    factor : float
        F, the set-up factor at the restart [-].
    penetration : float
        s, the penetration since the restart [m], >= 0.
    remoulding_length : float
        L_r [m], > 0.

    Returns
    -------
    float
        The remaining factor [-].

    Raises
    ------
    ValueError
        If ``remoulding_length`` is not positive.
    """
    if remoulding_length <= 0.0:
        raise ValueError(f"remoulding_length must be positive [m], got {remoulding_length!r}")
    return 1.0 + (factor - 1.0) * math.exp(-max(penetration, 0.0) / remoulding_length)
