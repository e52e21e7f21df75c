"""Contacts between the anvil and its neighbours: compression-only normal force, friction."""

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


@njit(cache=True, inline='always')
def coulomb_friction(tangential_force, slip_increment, normal_force, friction_coefficient,
                     tangential_stiffness):
    """Coulomb friction of one contact pair over one time step, by return mapping [N], [J].

    The pair carries a stick spring k_t in series with a Coulomb slider (a penalty
    regularisation of the stick condition only). The step's relative tangential motion
    ds is first taken as elastic, T* = T + k_t ds (elastic predictor); if |T*| <= mu F_n the
    pair sticks, T = T*; otherwise it slips and the force is returned to the cone,
    T = mu F_n sign(T*) (return mapping).

    Why this law and not a regularised one (T = mu F_n tanh(v / v_eps)): the friction force
    never exceeds mu F_n and equals it whenever the pair slides, so the slip phases are
    exact Coulomb whatever the step; stick is a true stick (no creep at v_eps under a steady
    tangential load, which a velocity regularisation allows) up to the elastic offset
    T / k_t, which the penalty makes as small as the normal penalty's overlap. For an
    explicit scheme the update is closed-form per pair (no iteration), and a released pair
    (F_n = 0) carries no tangential force. k_t enters the stable step like any spring
    (the caller checks the pair frequency with it).

    The energy dissipated in the step is the slider's work over its slip
    ds_p = (|T*| - |T|) / k_t, its force going linearly from the level at which it starts to
    slip to the end-of-step cone mu F_n: D = ds_p (T_start + mu F_n) / 2 with T_start the
    cone (a pair that sticks first, or already slides: D = mu F_n ds_p, the exact Coulomb
    work) or the stored force when the cone has shrunk below it (a normal force that drops
    sheds the stick spring's excess, D = (T_old^2 - T^2) / (2 k_t), its whole released energy,
    without any motion).

    Parameters
    ----------
    tangential_force : float
        Force T in the stick spring at the start of the step [N]; the pair pushes the upper
        (first) body by -T and the lower by +T along the tangent.
    slip_increment : float
        Relative tangential displacement of the step, ds = d(u_t upper - u_t lower) [m].
    normal_force : float
        Compressive normal force F_n of the pair at the end of the step [N] (<= 0: open).
    friction_coefficient : float
        Coulomb coefficient mu [-].
    tangential_stiffness : float
        Stick spring k_t [N/m] (> 0).

    Returns
    -------
    force : float
        The tangential force T at the end of the step [N], |T| <= mu max(F_n, 0).
    dissipated : float
        Energy dissipated by slip in the step [J] (>= 0).

    References
    ----------
    Simo, J.C., Hughes, T.J.R. (1998). Computational Inelasticity. Springer, ch. 1 (return
    mapping of the one-dimensional frictional/plastic model).
    Wriggers, P. (2006). Computational Contact Mechanics, 2nd ed. Springer (penalty
    regularised stick with a Coulomb slip cone).
    """
    trial = tangential_force + tangential_stiffness * slip_increment
    cap = friction_coefficient * normal_force if normal_force > 0.0 else 0.0
    if trial <= cap and trial >= -cap:
        return trial, 0.0
    if trial > 0.0:
        force, start = cap, max(cap, tangential_force)
    else:
        force, start = -cap, max(cap, -tangential_force)
    slip = (abs(trial) - cap) / tangential_stiffness
    return force, 0.5 * (start + cap) * slip
