"""Free-free modes of the anvil FE model: all modes up to fmax, with a proof of completeness.

The generalised eigenproblem (K - omega^2 M) phi = 0 is solved by shift-invert Lanczos
(``scipy.sparse.linalg.eigsh``) for exactly the number of eigenvalues below (2 pi fmax)^2 given
by Sylvester's law of inertia (a Sturm count): the number of negative pivots of an LDL^T
factorisation of K - sigma M equals the number of eigenvalues below sigma. Finding that many
modes, all below sigma and M-orthonormal, proves that none in [0, fmax] is missing.
More than :data:`SLICED_ABOVE` modes are solved in slices of the interval, each checked by its
own Sturm counts (:func:`_sliced_lanczos`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

from anvilwave.anvil_rom.fem.elasticity import AxisymmetricModel


class ModeSolveError(RuntimeError):
    """The eigen-solution failed a completeness or accuracy check."""


@dataclass
class ModeSet:
    """Mass-normalised free-free modes.

    Parameters
    ----------
    frequencies : numpy.ndarray
        Natural frequencies, shape (n,) [Hz]; index 0 is the axial rigid-body mode, set to
        exactly 0 (its computed value is kept in ``rigid_frequency_computed``).
    shapes : numpy.ndarray
        Mode shapes, shape (n_free, n), phi^T M phi = I.
    fmax : float
        The frequency content requested [Hz].
    sturm_count : int
        Number of eigenvalues below (2 pi fmax)^2 from the inertia of K - sigma M.
    rigid_frequency_computed : float
        The computed frequency of the rigid-body mode before it was set to 0 [Hz].

    Attributes
    ----------
    n_modes : int
        Number of modes n.
    """

    frequencies: np.ndarray
    shapes: np.ndarray
    fmax: float
    sturm_count: int
    rigid_frequency_computed: float

    @property
    def n_modes(self) -> int:
        """Number of modes n (rigid-body mode included)."""
        return len(self.frequencies)


def sturm_count(stiffness: sp.spmatrix, mass: sp.spmatrix, sigma: float) -> int:
    """Number of eigenvalues lambda = omega^2 [rad^2/s^2] of (K, M) below ``sigma``.

    Sylvester's law of inertia: the count equals the number of negative entries of D in
    K - sigma M = L D L^T. SuperLU with symmetric ordering and diagonal pivoting gives U = D L^T,
    so the signs of diag(U) are the inertia; a factorisation that had to pivot off the diagonal
    is detected and the shift nudged.

    Parameters
    ----------
    stiffness : scipy.sparse.spmatrix
        K [N/m].
    mass : scipy.sparse.spmatrix
        M [kg].
    sigma : float
        The shift [rad^2/s^2].

    Returns
    -------
    int
        The number of eigenvalues below ``sigma``.

    Raises
    ------
    ModeSolveError
        If no factorisation keeps symmetric pivots.
    """
    lu = _symmetric_factor(stiffness, mass, sigma)
    return int(np.count_nonzero(lu.U.diagonal() < 0.0))


def _symmetric_factor(stiffness: sp.spmatrix, mass: sp.spmatrix, sigma: float):
    """SuperLU factors of K - sigma M with symmetric pivots (the shift nudged if needed)."""
    for nudge in (0.0, 1e-9, -1e-9, 1e-7):
        shifted = sigma * (1.0 + nudge)
        A = (stiffness - shifted * mass).tocsc()
        lu = sla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                      options={"SymmetricMode": True})
        if np.array_equal(lu.perm_r, lu.perm_c):
            return lu
    raise ModeSolveError("Sturm count failed: the factorisation could not keep symmetric pivots")


@dataclass
class SampledMode:
    """One eigenpair of (K, M) near a shift, with the inertia below the shift.

    Parameters
    ----------
    count_below : int
        Number of eigenvalues below the shift (Sturm count).
    shape : numpy.ndarray
        The eigenvector nearest the shift, mass-normalised (phi^T M phi = 1), shape (n_free,).
    eigenvalue : float
        Its Rayleigh quotient phi^T K phi [rad^2/s^2].
    residual : float
        ||K phi - lambda M phi|| / ||K phi||, the relative residual of the pair.
    """

    count_below: int
    shape: np.ndarray
    eigenvalue: float
    residual: float


def inverse_iteration_mode(stiffness: sp.spmatrix, mass: sp.spmatrix, sigma: float,
                           iterations: int = 4) -> SampledMode:
    """The eigenpair of (K, M) nearest ``sigma`` by shift-invert inverse iteration.

    One symmetric factorisation K - sigma M = L D L^T gives both the inertia below the shift
    (the Sturm count of :func:`sturm_count`) and the iteration x <- (K - sigma M)^-1 M x, which
    converges to the eigenvector whose eigenvalue is nearest ``sigma`` by the factor
    |lambda_k - sigma| / |lambda_j - sigma| per step, lambda_j the next nearest (Golub & Van
    Loan 2013, sec. 8.2.2). With ``sigma`` a relative 1e-6 from a cached eigenvalue and its
    neighbours a relative 1e-3 or more away, four steps reach round-off. The start vector is
    fixed (a seeded random vector), so the result is reproducible.

    Parameters
    ----------
    stiffness : scipy.sparse.spmatrix
        K [N/m].
    mass : scipy.sparse.spmatrix
        M [kg].
    sigma : float
        The shift [rad^2/s^2].
    iterations : int, default 4
        Inverse-iteration steps.

    Returns
    -------
    SampledMode
        The inertia below ``sigma`` and the mass-normalised eigenpair nearest it.

    Raises
    ------
    ModeSolveError
        If no factorisation keeps symmetric pivots.

    References
    ----------
    Golub, G.H., Van Loan, C.F. (2013). Matrix Computations, 4th ed. Johns Hopkins University
    Press, sec. 8.2.2 (inverse iteration) and 8.4 (the symmetric-definite problem).
    """
    lu = _symmetric_factor(stiffness, mass, sigma)
    count = int(np.count_nonzero(lu.U.diagonal() < 0.0))
    x = np.random.default_rng(12345).standard_normal(stiffness.shape[0])
    for _ in range(iterations):
        x = lu.solve(mass @ x)
        x /= np.sqrt(x @ (mass @ x))
    kx, mx = stiffness @ x, mass @ x
    eigenvalue = float(x @ kx)
    residual = float(np.linalg.norm(kx - eigenvalue * mx) / max(np.linalg.norm(kx), 1e-300))
    return SampledMode(count, x, eigenvalue, residual)


def mesh_resolvable_frequency(model: AxisymmetricModel,
                              elements_per_wavelength: float = 4.0) -> float:
    """Highest frequency the mesh resolves [Hz]: shear wavelength c_s / f over the largest edge.

    With quadratic elements, four elements per shear wavelength keep the frequency error of the
    corresponding mode near 0.2 % (P2 dispersion error ~ (k h)^4 / 2880).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    elements_per_wavelength : float, default 4.0
        Elements per shear wavelength required [-].

    Returns
    -------
    float
        The frequency [Hz].
    """
    mesh = model.mesh
    edges = mesh.facets
    lengths = np.linalg.norm(mesh.p[:, edges[0]] - mesh.p[:, edges[1]], axis=0)
    return model.material.shear_wave_speed / (elements_per_wavelength * lengths.max())


SLICED_ABOVE = 300
"""Mode counts above which :func:`free_free_modes` solves the spectrum in slices [-]."""
SLICE_MODES = 128
"""Modes per slice of a sliced solve (about) [-]."""


def _sliced_lanczos(K, M, count: int, shift: float, lam_max: float, start: np.ndarray):
    """The ``count`` eigenpairs of (K, M) from ``shift`` to ``lam_max``, slice by slice.

    Spectrum slicing (Ericsson & Ruhe 1980, doi:10.1090/S0025-5718-1980-0583502-2): the interval
    is cut into slices of equal width in lambda (about equal counts: a 2D body's count grows as
    lambda, Weyl's law), the Sturm count at every cut gives each slice's number of eigenvalues
    n, and shift-invert Lanczos about the slice's midpoint asks for its n nearest eigenvalues,
    which are exactly the slice's (every eigenvalue inside is nearer the midpoint than every
    one outside). The Lanczos basis is then about 2 n instead of 2 ``count``, and its
    orthogonalisation, which grows as the square of the basis, costs a fraction of one solve
    for them all.

    Returns
    -------
    values : numpy.ndarray
        The eigenvalues, shape (count,) [rad^2/s^2].
    vectors : numpy.ndarray
        The eigenvectors, shape (n, count).

    Raises
    ------
    ModeSolveError
        If a slice's eigenvalues are not its Sturm count.
    """
    slices = int(np.ceil(count / SLICE_MODES))
    cuts = [shift, *(lam_max * i / slices for i in range(1, slices)), lam_max]
    below = [0, *(sturm_count(K, M, c) for c in cuts[1:-1]), count]
    Kc, Mc = K.tocsc(), M.tocsc()
    values, vectors = [], []
    for lo, hi, n_lo, n_hi in zip(cuts[:-1], cuts[1:], below[:-1], below[1:], strict=True):
        n = n_hi - n_lo
        if n == 0:
            continue
        w, v = sla.eigsh(Kc, k=n, M=Mc, sigma=0.5 * (lo + hi), which="LM", tol=1e-12,
                         v0=start)
        inside = (w >= lo) & (w < hi)
        if np.count_nonzero(inside) != n:
            raise ModeSolveError(f"Lanczos found {np.count_nonzero(inside)} eigenvalues in a "
                                 f"slice whose Sturm count is {n}")
        values.append(w[inside])
        vectors.append(v[:, inside])
    return np.concatenate(values), np.concatenate(vectors, axis=1)


def free_free_modes(model: AxisymmetricModel, fmax: float) -> ModeSet:
    """All free-free modes with f <= fmax plus the axial rigid-body mode, mass-normalised.

    Parameters
    ----------
    model : AxisymmetricModel
        Assembled axisymmetric FE model.
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    ModeSet
        The modes, complete up to ``fmax`` (proved by the Sturm count).

    Raises
    ------
    ModeSolveError
        If the rigid-body mode is missing, ``fmax`` asks for all DOFs, Lanczos misses modes, or
        the modes are not M-orthonormal.
    """
    K, M = model.stiffness, model.mass
    lam_max = (2.0 * np.pi * fmax) ** 2
    count = sturm_count(K, M, lam_max)
    if count < 1:
        raise ModeSolveError("no eigenvalue below fmax: the rigid-body mode is missing; the model "
                             "is constrained or the matrices are wrong")
    if count >= model.n_dof - 1:
        raise ModeSolveError(f"fmax {fmax:g} Hz asks for all {model.n_dof} DOFs: refine the mesh")
    # shift below zero: K - sigma M is then positive definite and the nearest eigenvalues to the
    # shift are exactly the lowest ones
    shift = -1e-3 * lam_max
    # a fixed start vector: ARPACK's own is drawn from a generator whose state is the process's
    # (it depends on the eigensolves before), so the modes, equal to round-off, and the blows
    # computed from them would differ from run to run in their last digits
    start = np.random.default_rng(0).standard_normal(K.shape[0])
    if count <= SLICED_ABOVE:
        values, vectors = sla.eigsh(K.tocsc(), k=count, M=M.tocsc(), sigma=shift, which="LM",
                                    tol=1e-12, v0=start)
    else:
        values, vectors = _sliced_lanczos(K, M, count, shift, lam_max, start)
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    if values.max() > lam_max * (1.0 + 1e-8):
        raise ModeSolveError("Lanczos returned an eigenvalue above fmax: modes below it are "
                             "missing")
    # rigid-body mode: the exact axial translation, mass-normalised
    e = model.axial_free
    total = float(e @ (M @ e))
    rigid_computed = float(np.sqrt(max(values[0], 0.0)) / (2.0 * np.pi))
    vectors[:, 0] = e / np.sqrt(total)
    values[0] = 0.0
    # keep flexible modes exactly M-orthogonal to the rigid one (they are, to round-off)
    Me = M @ vectors[:, 0]
    vectors[:, 1:] -= np.outer(vectors[:, 0], Me @ vectors[:, 1:])
    norms = np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
    vectors /= norms
    gram = vectors.T @ (M @ vectors)
    if np.abs(gram - np.eye(count)).max() > 1e-6:
        raise ModeSolveError("modes are not M-orthonormal: a repeated eigenvalue was not resolved")
    return ModeSet(np.sqrt(np.maximum(values, 0.0)) / (2.0 * np.pi), vectors, float(fmax), count,
                   rigid_computed)


def elastic_flexibility(model: AxisymmetricModel, loads: np.ndarray) -> np.ndarray:
    """Inertia-relief flexibility of a free-free body between load vectors [m/N].

    Each load f is made self-equilibrated against the rigid-body inertia, P f = f - M e (e^T f)
    / m, the body is held at one axial DOF, K u = P f is solved, and the rigid part is removed,
    u <- u - e (e^T M u) / m. Then G_ab = f_a^T u_b equals sum over ALL flexible modes of
    (f_a^T phi)(f_b^T phi) / omega^2 (Craig & Kurdila, Fundamentals of Structural Dynamics,
    sec. 14.6), which the static correction of a truncated ROM needs.

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    loads : numpy.ndarray
        Load vectors, shape (n_free, k).

    Returns
    -------
    numpy.ndarray
        G, shape (k, k) [m/N].

    References
    ----------
    Craig, R.R., Kurdila, A.J. Fundamentals of Structural Dynamics, sec. 14.6.
    """
    K, M = model.stiffness.tocsc(), model.mass
    e = model.axial_free
    m = float(e @ (M @ e))
    Me = M @ e
    P_loads = loads - np.outer(Me, e @ loads) / m
    # hold one axial DOF (the first one) to remove the singularity
    fixed = int(np.flatnonzero(e)[0])
    keep = np.setdiff1d(np.arange(model.n_dof), [fixed])
    u = np.zeros_like(P_loads)
    u[keep] = sla.splu(K[keep][:, keep].tocsc()).solve(np.ascontiguousarray(P_loads[keep]))
    u -= np.outer(e, Me @ u) / m
    return loads.T @ u
