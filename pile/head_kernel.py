"""The pile head as an axisymmetric FE tube: its ring kernel.

A 1D pile meets the anvil with a flat head: every ring of the wall moves with the head's one
displacement. The real wall dishes and turns under the anvil's rings and radiates bending
waves down the shell, and that is what keeps a 1D head from the reference FEA's pile-head
force above 1.6 kHz (``benchmarks/study_pile_port.py``). The ring kernel carries it: the
linear response of the pile top's K equal-width rings, each loaded by a uniform pressure of
its own, of an axisymmetric FE tube of the pile's section.

G (steps, K, K) [m/N]: G[k, i, j] is the mean axial displacement of ring i, k steps after the
peak of a force on ring j that rises linearly from 0 one step before to 1 and falls back to 0
one step after (a hat). A ring force history given by its values F_n at the steps, linear in
between, then moves the rings by u_n = sum_k G[k] F_(n-k): G[0] acts at once (the head's
instantaneous compliance), the rest is the history. By reciprocity every G[k] is symmetric.

The tube is the reference FEA's pile (:mod:`anvilwave.fea`): quadratic 9-node elements, one
across each ring, ``axial_size`` along, HRZ-lumped mass, integrated with central differences at
the largest substep that divides the step within 0.9 of the stable one. It is free at both
ends, so G is the pile's until its toe reflection returns, 2 L / c0 after the load.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla
import skfem
from numba import njit

from anvil_rom.fe import AxisymmetricModel, annulus_vectors, assemble
from anvil_rom.geometry import Material

SAFETY = 0.9
"""Fraction of the stable central-difference step the substeps use [-]."""


def tube_model(material: Material, r_in: float, r_out: float, length: float, rings: int,
               axial_size: float) -> AxisymmetricModel:
    """An axisymmetric tube r_in..r_out [m], z = 0 (its top) to ``length`` [m]: one quadratic
    9-node element across each of ``rings`` equal-width rings, elements of at most
    ``axial_size`` [m] along."""
    axial = max(1, int(np.ceil(length / axial_size - 1e-9)))
    mesh = skfem.MeshQuad.init_tensor(np.linspace(r_in, r_out, rings + 1),
                                      np.linspace(0.0, length, axial + 1))
    return assemble(mesh, material)


def stable_step(stiffness: sp.csr_matrix, mass: np.ndarray) -> float:
    """The central-difference stability limit 2 / omega_max [s] of K and the lumped M
    (Lanczos on M^-1/2 K M^-1/2)."""
    scale = sp.diags(1.0 / np.sqrt(mass))
    A = (scale @ stiffness @ scale).tocsr()
    start = np.random.default_rng(0).standard_normal(A.shape[0])
    largest = sla.eigsh(A, k=1, which="LA", tol=1e-4, v0=start, ncv=min(40, A.shape[0] - 1),
                        return_eigenvectors=False)[0]
    return 2.0 / np.sqrt(largest * (1.0 + 1e-3))


@njit(cache=True)
def hat_responses(indptr, indices, data, inverse_mass, loads, steps, substeps, dt):
    """Central differences of M u'' = -K u + loads f(t) for every load column at once (K in
    CSR, M lumped; f the hat of unit peak at t = h = ``substeps`` dt, 0 at 0 and at 2 h): the
    loads' own displacements loads^T u at t = h, 2 h, ... (``steps``, loads, loads)."""
    n, m = loads.shape
    u = np.zeros((n, m))
    v = np.zeros((n, m))
    out = np.zeros((steps, m, m))
    for s in range(steps):  # from s h to (s + 1) h
        for q in range(substeps):
            f = max(0.0, 1.0 - abs((s * substeps + q + 0.5) / substeps - 1.0))
            for i in range(n):
                for j in range(m):
                    acc = f * loads[i, j]
                    for p in range(indptr[i], indptr[i + 1]):
                        acc -= data[p] * u[indices[p], j]
                    v[i, j] += dt * inverse_mass[i] * acc
            for i in range(n):
                for j in range(m):
                    u[i, j] += dt * v[i, j]
        for k in range(m):
            for j in range(m):
                acc = 0.0
                for i in range(n):
                    acc += loads[i, k] * u[i, j]
                out[s, k, j] = acc
    return out


def ring_kernel(material: Material, r_in: float, r_out: float, length: float, step: float,
                steps: int, rings: int = 3, axial_size: float = 0.1) -> np.ndarray:
    """The ring kernel G (``steps``, ``rings``, ``rings``) [m/N] (module docstring) of a tube
    of the pile's section r_in..r_out [m] and ``length`` [m] at the time ``step`` [s]."""
    model = tube_model(material, r_in, r_out, length, rings, axial_size)
    mass = model.lumped_mass()
    K = model.stiffness.tocsr()
    loads, _ = annulus_vectors(model, 0.0, r_in, r_out, rings)
    substeps = int(np.ceil(step / (SAFETY * stable_step(K, mass))))
    return hat_responses(K.indptr, K.indices, K.data, 1.0 / mass, np.ascontiguousarray(loads),
                         int(steps), substeps, step / substeps)
