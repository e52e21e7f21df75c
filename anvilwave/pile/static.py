"""Static equilibrium of the pile and soil before a blow.

Before the first ram-anvil contact (t = 0) the hammer weight W (anvil, and whatever else rests
on the pile) bears on the head, and with gravity switched on the pile's own weight acts on every
mass. :func:`static_equilibrium` returns the displacements and the soil plastic offsets that
balance these loads, so a blow starts at rest without spurious oscillation *provided the
dynamic run uses the same loads*: head force W before contact and the same ``gravity`` in
:func:`anvilwave.pile.kernels.pile_step` (gravity = 0 in both ignores the pile self-weight, i.e.
assumes
it was already carried by the soil in the reference state u = 0).

The soil springs start unstressed at u = 0 (offset 0). The loads are applied in one monotonic
step; springs whose force would exceed their capacity are made plastic (force = capacity,
offset u - quake) by an active-set iteration on the tridiagonal system
(K_pile + K_soil,elastic) u = f - R_plastic. If the loads exceed the soil capacity the pile
would plunge and a ValueError is raised.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded

from anvilwave.pile.kernels import (
    PILE_MASS,
    PILE_STIFFNESS,
    SOIL_CAPACITY,
    SOIL_STIFFNESS,
)


def static_loads(pile: np.ndarray, head_force: float, gravity: float) -> np.ndarray:
    """Static load on each mass [N]: m_i g, plus the head force W [N] on the top mass.

    Parameters
    ----------
    pile : numpy.ndarray
        Pile parameter array of the kernels (:mod:`anvilwave.pile.kernels`).
    head_force : float
        Head force W [N].
    gravity : float
        Gravitational acceleration g [m/s^2].

    Returns
    -------
    numpy.ndarray
        The load on each mass, shape (N,) [N].
    """
    loads = pile[PILE_MASS] * gravity
    loads[0] += head_force
    return loads


def static_equilibrium(pile: np.ndarray, soil: np.ndarray, head_force: float, gravity: float,
                       max_iterations: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """Displacements u (N,) [m] and soil offsets (N+1,) [m] in equilibrium with the loads.

    Parameters
    ----------
    pile : numpy.ndarray
        Pile parameter array of the kernels (:mod:`anvilwave.pile.kernels`).
    soil : numpy.ndarray
        Soil parameter array of the kernels (:mod:`anvilwave.pile.kernels`).
    head_force : float
        Weight resting on the head [N] (compression +).
    gravity : float
        Gravitational acceleration on the pile masses [m/s^2] (0: none).
    max_iterations : int, default 200
        Most active-set iterations [-].

    Returns
    -------
    u : numpy.ndarray
        Displacements, shape (N,) [m].
    offset : numpy.ndarray
        Soil plastic offsets, shape (N+1,) [m].

    Raises
    ------
    ValueError
        If the loads exceed the soil capacity (no static equilibrium), or the iteration does not
        converge.
    """
    n = pile.shape[1]
    loads = static_loads(pile, head_force, gravity)
    if not np.any(loads):
        return np.zeros(n), np.zeros(n + 1)
    k = pile[PILE_STIFFNESS, :-1]
    k_soil = soil[SOIL_STIFFNESS].copy()
    capacity = soil[SOIL_CAPACITY]
    plastic = np.zeros(n + 1, dtype=bool)
    for _ in range(max_iterations):
        ks = np.where(plastic, 0.0, k_soil)
        diag = np.zeros(n)
        diag[:-1] += k
        diag[1:] += k
        diag += ks[:n]
        diag[-1] += ks[n]
        rhs = loads - np.where(plastic, capacity, 0.0)[:n]
        rhs[-1] -= capacity[n] if plastic[n] else 0.0
        bands = np.zeros((3, n))
        bands[0, 1:] = -k
        bands[1] = diag
        bands[2, :-1] = -k
        if np.count_nonzero(ks) == 0:
            raise ValueError("the static loads exceed the soil capacity (or there is no soil): "
                             "no static equilibrium")
        u = solve_banded((1, 1), bands, rhs)
        u_soil = np.append(u, u[-1])
        force = k_soil * u_soil
        newly = (~plastic) & (force > capacity * (1.0 + 1e-12)) & (k_soil > 0.0)
        if not newly.any():
            break
        plastic |= newly
    else:
        raise ValueError("static equilibrium did not converge")
    offset = np.zeros(n + 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        quake = np.where(k_soil > 0.0, capacity / np.where(k_soil > 0.0, k_soil, 1.0), 0.0)
    offset[plastic] = u_soil[plastic] - quake[plastic]
    return u, offset
