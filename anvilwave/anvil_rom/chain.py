"""A one-port modal ROM realised as an equivalent spring-mass chain.

A body touched at one face only (a ram striking with its toe) is, seen from that face, fully
described by its modes: omega_j and the participations p_j = b^T phi_j at the face. The
driving-point receptance is

    u(w) / F(w) = sum_j p_j^2 / (omega_j^2 - w^2).

A chain of n masses joined by n - 1 springs, forced at its first mass, has exactly this
receptance when M^-1/2 K M^-1/2 is the Jacobi (tridiagonal) matrix that the Lanczos process
builds from diag(omega^2) and the start vector p / |p| (the Jacobi inverse eigenvalue problem:
Golub 1973; Gladwell, "Inverse Problems in Vibration", 2004, ch. 4). The chain carries the
same modes, each with the same participation at the face, and the same total mass (the
rigid-body mode fixes sqrt(m) as the null vector of the Jacobi matrix), so any consumer of a
lumped chain (the leapfrog ram kernel, the Ram FMU, the coupled stability bound) runs the
Mode Displacement Method ROM unchanged.

The realisation is exact but ill-conditioned in floating point: the masses fall off
exponentially along the chain (the 125 modes below 5 kHz of a 1.8 m x 13.8 m ram end in masses
of 1e-70 kg), and the null-vector recurrence cancels about as many digits. The Lanczos process
and the null vector are therefore computed in multiple precision (mpmath) and only the final
masses and springs are rounded to float64. The rounded chain is then checked against the modal
data (frequencies and participations, solved in double precision on its well-scaled Jacobi
form); if it misses, the precision is doubled (from 40 + n digits, which that ram passes).
The chain cannot be cut short (dropping the masses below 1e-30 of the largest changes the face's
impulse response by 3 % over 30 ms: the deep tail carries close modes whose beating shows late),
so float64's range bounds it: about 500 modes (RANGE).
"""

from __future__ import annotations

import numpy as np

from anvilwave.inputs import InputError

MAX_DIGITS = 1000
"""Give up beyond this precision [decimal digits]."""
RANGE = 1e-290
"""Smallest chain mass relative to the largest that float64 carries with room for the kernel's
products (the masses fall by about 1e-70 per 125 modes: about 500 modes is the limit, fmax
10 kHz for the 1.8 m x 13.8 m ram)."""
TOLERANCE = 1e-9
"""The rounded chain must reproduce every frequency (relative) and participation (relative to the
largest) to this tolerance."""
INVISIBLE = 1e-14
"""Modes whose squared participation is below this fraction of the largest one do not act at
the face (a mode with a node on it); they are left out rather than breaking the recurrence."""


def chain_from_modes(omega, participation, digits: int | None = None
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Masses [kg] and springs [N/m] of the chain with the given modes at its first mass.

    Parameters
    ----------
    omega : (n,) array_like
        Circular frequencies [rad/s]; exactly one must be 0 (the rigid-body mode).
    participation : (n,) array_like
        Participations at the face [kg^-1/2], b^T phi_j of mass-normalised modes (the rigid
        mode's is 1 / sqrt(total mass)).
    digits : int, optional
        Decimal digits of the multiple-precision arithmetic to start from (default 40 + n);
        doubled until the rounded chain reproduces the modes within TOLERANCE.

    Returns
    -------
    mass : (k,) numpy.ndarray
        Masses [kg], mass[0] at the face; k <= n (modes invisible at the face dropped).
    stiffness : (k - 1,) numpy.ndarray
        Springs [N/m], stiffness[i] between mass[i] and mass[i + 1].

    Raises
    ------
    InputError
        If the modes are malformed (no single rigid-body mode, mismatched shapes, a rigid mode
        that does not act at the face, equal frequencies), need masses beyond double precision,
        or no chain reproduces them within MAX_DIGITS digits.

    References
    ----------
    Golub, G.H. (1973). Some modified matrix eigenvalue problems. SIAM Review 15(2), 318-334.
    https://doi.org/10.1137/1015032
    Gladwell, G.M.L. (2004). Inverse Problems in Vibration, ch. 4.
    """
    omega = np.asarray(omega, float)
    p = np.asarray(participation, float)
    if omega.shape != p.shape or omega.ndim != 1:
        raise InputError("modal chain", "participation", "must match omega, one per mode")
    rigid = np.flatnonzero(omega == 0.0)
    if rigid.size != 1 or np.any(omega < 0.0) or not np.all(np.isfinite(omega)):
        raise InputError("modal chain", "omega", "needs exactly one rigid-body mode (0) and "
                                                 "finite positive flexible frequencies")
    visible = p**2 >= INVISIBLE * np.max(p**2)
    if not visible[rigid[0]]:
        raise InputError("modal chain", "participation", "the rigid-body mode must act at the "
                                                         "face (1 / sqrt(mass))")
    omega, p = omega[visible], p[visible]
    digits = 40 + omega.size if digits is None else int(digits)
    while True:
        mass, stiffness = _realise(omega**2, p, digits)
        if not mass.min() > RANGE * mass.max():
            raise InputError("modal chain", "modes", f"the {omega.size} modes need chain masses "
                                                    f"spanning more than {1 / RANGE:.0e}, beyond "
                                                    "double precision: lower fmax")
        if mass.size < omega.size:
            raise InputError("modal chain", "omega", "modes of equal frequency cannot all be "
                                                     "realised by one chain (merge them first)")
        if _reproduces(mass, stiffness, omega, p):
            return mass, stiffness
        digits *= 2
        if digits > MAX_DIGITS:
            raise InputError("modal chain", "omega", f"no chain reproduces these {omega.size} "
                                                     f"modes within {MAX_DIGITS} digits")


def _reproduces(mass, stiffness, omega, p) -> bool:
    if not (np.all(np.isfinite(mass)) and np.all(mass > 0.0) and np.all(np.isfinite(stiffness))
            and np.all(stiffness > 0.0)):
        return False
    w, q = chain_modes(mass, stiffness)
    order = np.argsort(omega)
    flexible = omega[order] > 0.0
    freq_ok = np.all(np.abs(w[flexible] - omega[order][flexible])
                     <= TOLERANCE * omega[order][flexible])
    part_ok = np.all(np.abs(np.abs(q) - np.abs(p[order])) <= TOLERANCE * np.abs(p).max())
    return bool(freq_ok and part_ok)


def _realise(lam_f, p_f, digits):
    """The chain in ``digits`` decimal digits, rounded to float64 (module docstring)."""
    import mpmath

    with mpmath.workdps(digits):
        lam = [mpmath.mpf(float(x)) for x in lam_f]
        norm = mpmath.sqrt(mpmath.fsum(mpmath.mpf(float(x)) ** 2 for x in p_f))
        q = [mpmath.mpf(float(x)) / norm for x in p_f]
        alpha, beta = _lanczos(lam, q)
        # null vector s of the Jacobi matrix with off-diagonals -beta: the rigid-body mode of
        # the chain, s_i = sqrt(m_i / c); the recurrence of its rows, exact in this precision
        s = [mpmath.mpf(1)]
        if len(alpha) > 1:
            s.append(alpha[0] / beta[0])
        for i in range(1, len(alpha) - 1):
            s.append((alpha[i] * s[i] - beta[i - 1] * s[i - 1]) / beta[i])
        scale = 1 / (norm**2 * s[0] ** 2)  # first mass: 1 / |p|^2
        mass = np.array([float(scale * x * x) for x in s])
        stiffness = np.array([float(beta[i] * scale * s[i] * s[i + 1])
                              for i in range(len(alpha) - 1)])
    return mass, stiffness


def _lanczos(lam, q):
    """Lanczos on diag(lam) from the unit vector q (mpmath lists).

    No reorthogonalisation: the orthogonality that the plain recurrence loses as Ritz values
    converge is a few tens of digits at most here, far inside the working precision, and the
    result is checked anyway (:func:`chain_from_modes`).

    Returns the diagonal alpha and the off-diagonal beta (> 0); stops at the dimension of the
    Krylov space (beta vanishing)."""
    import mpmath

    n = len(lam)
    eps = mpmath.mpf(10) ** (-(mpmath.mp.dps * 3) // 4)
    top = max(lam)
    alpha, beta = [], []
    prev = None
    while True:
        w = [lam[j] * q[j] for j in range(n)]
        a = mpmath.fsum(w[j] * q[j] for j in range(n))
        alpha.append(a)
        w = [w[j] - a * q[j] - (beta[-1] * prev[j] if prev is not None else 0)
             for j in range(n)]
        b = mpmath.sqrt(mpmath.fsum(x * x for x in w))
        if len(alpha) == n or b <= eps * top:
            return alpha, beta
        beta.append(b)
        prev, q = q, [x / b for x in w]


def chain_modes(mass, stiffness) -> tuple[np.ndarray, np.ndarray]:
    """Circular frequencies [rad/s] and participations at mass[0] [kg^-1/2] of a free chain.

    Solved on the symmetric tridiagonal form M^-1/2 K M^-1/2, whose entries (k_i-1 + k_i) / m_i
    and -k_i / sqrt(m_i m_i+1) stay well scaled however small the masses are.

    Parameters
    ----------
    mass : array_like
        Chain masses, shape (k,) [kg].
    stiffness : array_like
        Springs between consecutive masses, shape (k - 1,) [N/m].

    Returns
    -------
    omega : numpy.ndarray
        Circular frequencies, ascending [rad/s].
    participation : numpy.ndarray
        Participation of each mode at mass[0] [kg^-1/2].
    """
    from scipy.linalg import eigh_tridiagonal

    m = np.asarray(mass, float)
    k = np.asarray(stiffness, float)
    ksum = np.zeros_like(m)
    ksum[:-1] += k
    ksum[1:] += k
    diag = ksum / m
    root = np.sqrt(m)  # not sqrt(m_i m_i+1): that product underflows for the deep tail
    off = -k / (root[:-1] * root[1:])
    lam, vec = eigh_tridiagonal(diag, off)
    omega = np.sqrt(np.clip(lam, 0.0, None))
    participation = vec[0] / np.sqrt(m[0])
    return omega, participation
