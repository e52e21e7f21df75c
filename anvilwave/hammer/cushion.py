"""Force law of a wave-equation cushion: compression-only spring with restitution and round-out.

Smith (1960) models hammer and pile cushions as weightless springs that carry compression
only and lose energy through a coefficient of restitution e: loading follows the stiffness k,
unloading from the largest compression reached follows the steeper line k / e^2, so that of the
energy stored at the turning point only the fraction e^2 comes back; (1 - e^2) is dissipated in
every loading-unloading cycle. Reloading runs back up the unloading line to the turning point
and then continues on the loading curve (Smith 1960; Hirsch, Lowery, Coyle & Samson 1970).

Round-out (GRLWEAP background report, Pile Dynamics Inc.): uneven cushion or pile-top surfaces
make a contact soft at first. anvilwave lets the loading stiffness grow linearly from 0 to k
over the round-out compression r, i.e. F = k c^2 / (2 r) for 0 <= c <= r and F = k (c - r / 2)
beyond: force and stiffness are continuous (the exact GRLWEAP curve may differ in detail).

References
----------
Smith, E.A.L. (1960). Pile-driving analysis by the wave equation. Journal of the Soil Mechanics
    and Foundations Division, ASCE, 86(SM4), 35-61.
Hirsch, T.J., Lowery, L.L., Coyle, H.M. & Samson, C.H. (1970). Pile-driving analysis by
    one-dimensional wave theory: state of the art. Highway Research Record 333, 33-54.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def loading_force(compression, stiffness, round_out):
    """Force on the loading (virgin) curve [N], compression positive.

    Parameters
    ----------
    compression : float
        Compression c of the cushion [m] (shortening; <= 0 means no contact).
    stiffness : float
        Cushion stiffness k [N/m] (E A / t of the cushion material).
    round_out : float
        Round-out compression r [m]; 0 for a linear spring.

    Returns
    -------
    float
        The loading-curve force [N].
    """
    if compression <= 0.0:
        return 0.0
    if compression < round_out:
        return 0.5 * stiffness * compression * compression / round_out
    return stiffness * (compression - 0.5 * round_out)


@njit(cache=True)
def cushion_force(compression, max_compression, stiffness, restitution, round_out):
    """Cushion force [N] (compression positive, never tension) with Smith's restitution law.

    The force is that of the unloading line through the turning point
    (c_p, F_L(c_p)) with slope k / e^2, where c_p = max(c, c_max) is the largest compression
    reached so far: F = max(0, F_L(c_p) - (k / e^2) (c_p - c)). On first loading (c >= c_max)
    this is the loading curve F_L(c). The caller keeps c_max up to date
    (c_max = max(c_max, c) after each accepted step); this function does not change it.

    Parameters
    ----------
    compression : float
        Current compression c [m].
    max_compression : float
        Largest compression reached so far c_max [m] (0 for a fresh cushion).
    stiffness : float
        Loading stiffness k [N/m].
    restitution : float
        Coefficient of restitution e [-], 0 < e <= 1 (1: elastic).
    round_out : float
        Round-out compression r [m].

    Returns
    -------
    float
        The cushion force [N].

    References
    ----------
    Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech.
    Found. Div. 86(4), 35-61.
    """
    if compression <= 0.0:
        return 0.0
    peak = compression if compression > max_compression else max_compression
    force = loading_force(peak, stiffness, round_out)
    force -= stiffness / (restitution * restitution) * (peak - compression)
    return force if force > 0.0 else 0.0


@njit(cache=True)
def recoverable_energy(force, stiffness, restitution):
    """Strain energy [J] the cushion gives back if unloaded from the force F: e^2 F^2 / (2 k).

    The unloading line has slope k / e^2, so the triangle under it holds F^2 e^2 / (2 k). On
    the loading curve of a linear cushion (no round-out) this is e^2 times the work done on it.

    Parameters
    ----------
    force : float
        Current cushion force F [N].
    stiffness : float
        Loading stiffness k [N/m].
    restitution : float
        Coefficient of restitution e [-].

    Returns
    -------
    float
        The recoverable strain energy [J].
    """
    return 0.5 * force * force * restitution * restitution / stiffness


@njit(cache=True)
def loading_compression(force, stiffness, round_out):
    """Compression [m] on the loading curve that carries the force F (inverse of loading_force).

    Parameters
    ----------
    force : float
        Force F >= 0 [N].
    stiffness : float
        Loading stiffness k [N/m].
    round_out : float
        Round-out compression r [m].

    Returns
    -------
    float
        The compression [m].
    """
    if force <= 0.0:
        return 0.0
    if force < 0.5 * stiffness * round_out:
        return math.sqrt(2.0 * round_out * force / stiffness)
    return force / stiffness + 0.5 * round_out


@njit(cache=True)
def loading_work(compression, stiffness, round_out):
    """Work [J] done on a cushion loaded along the loading curve from 0 to the compression c.

    The integral of :func:`loading_force`: k c^3 / (6 r) within the round-out (c <= r), and
    k r^2 / 6 + k ((c^2 - r^2) / 2 - r (c - r) / 2) beyond it; k c^2 / 2 without round-out.

    Parameters
    ----------
    compression : float
        Compression c [m] (<= 0: no work).
    stiffness : float
        Loading stiffness k [N/m].
    round_out : float
        Round-out compression r [m].

    Returns
    -------
    float
        The work done on the cushion [J].
    """
    if compression <= 0.0:
        return 0.0
    if compression < round_out:
        return stiffness * compression**3 / (6.0 * round_out)
    r = round_out
    return stiffness * (r * r / 6.0 + 0.5 * (compression * compression - r * r)
                        - 0.5 * r * (compression - r))


@njit(cache=True)
def hysteresis_loss(max_compression, stiffness, restitution, round_out):
    """Energy [J] a cushion has dissipated once it has been compressed to c_max (Smith's law).

    Loading follows the loading curve up to c_max, unloading and reloading run on the one line
    of slope k / e^2 through (c_max, F_L(c_max)), so whatever the path below c_max the work
    done on the cushion minus what it can still give back is the area between the loading curve
    and that line: W_L(c_max) - e^2 F_L(c_max)^2 / (2 k) (:func:`loading_work`,
    :func:`recoverable_energy`). Without round-out this is (1 - e^2) k c_max^2 / 2; with
    round-out and e = 1 it is k r^2 / 24 once c_max >= r (the unloading line is straight).

    Parameters
    ----------
    max_compression : float
        Largest compression reached c_max [m].
    stiffness : float
        Loading stiffness k [N/m].
    restitution : float
        Coefficient of restitution e [-].
    round_out : float
        Round-out compression r [m].

    Returns
    -------
    float
        The dissipated energy [J].
    """
    if max_compression <= 0.0:
        return 0.0
    force = loading_force(max_compression, stiffness, round_out)
    return (loading_work(max_compression, stiffness, round_out)
            - recoverable_energy(force, stiffness, restitution))
