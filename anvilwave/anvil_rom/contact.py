"""Compression-only contact between the anvil and its neighbours (ram, pile)."""

from __future__ import annotations

from numba import njit


@njit(cache=True, inline='always')
def contact_force(penetration, penetration_rate, stiffness, damping):
    """Force of a compression-only penalty contact [N], positive in compression.

    F = max(0, k d + c d') while the bodies overlap (d > 0), else 0; the dashpot may only push,
    never pull, so the contact releases without adhesion and lift-off and re-impact are possible.

    Parameters
    ----------
    penetration : float
        Overlap d = u_upper - u_lower of the two faces [m] (z down).
    penetration_rate : float
        d' [m/s].
    stiffness : float
        Contact stiffness k [N/m].
    damping : float
        Contact dashpot c [N s/m].

    Returns
    -------
    float
        The contact force F [N].
    """
    if penetration <= 0.0:
        return 0.0
    force = stiffness * penetration + damping * penetration_rate
    return force if force > 0.0 else 0.0
