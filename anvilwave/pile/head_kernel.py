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

from dataclasses import replace

import numpy as np
import skfem
from numba import njit

from anvilwave.anvil_rom.fem.elasticity import (
    AxisymmetricModel,
    annulus_vectors,
    assemble,
    max_eigenvalue,
)
from anvilwave.anvil_rom.fem.geometry import Material
from anvilwave.pile.kernels import (
    ENERGY_SIZE,
    HEAD_EXTRAPOLATION,
    SOIL_ROWS,
    head_displacement,
    pile_advance,
    sweep_arrays,
)
from anvilwave.pile.pile import pile_parameters, probe_parameters

SAFETY = 0.9
"""Fraction of the stable central-difference step the substeps use [-]."""


def tube_model(material: Material, r_in: float, r_out: float, length: float, rings: int,
               axial_size: float) -> AxisymmetricModel:
    """An axisymmetric tube r_in..r_out [m], z = 0 (its top) to ``length`` [m].

    One quadratic 9-node element across each of ``rings`` equal-width rings, elements of at most
    ``axial_size`` [m] along.

    Parameters
    ----------
    material : Material
        The tube's material.
    r_in : float
        Inner radius [m].
    r_out : float
        Outer radius [m].
    length : float
        Tube length [m].
    rings : int
        Number of equal-width rings (elements) across the wall [-].
    axial_size : float
        Largest element size along the axis [m].

    Returns
    -------
    AxisymmetricModel
        The assembled model.
    """
    axial = max(1, int(np.ceil(length / axial_size - 1e-9)))
    mesh = skfem.MeshQuad.init_tensor(np.linspace(r_in, r_out, rings + 1),
                                      np.linspace(0.0, length, axial + 1))
    return assemble(mesh, material)


@njit(cache=True)
def hat_responses(indptr, indices, data, inverse_mass, loads, steps, substeps, dt):
    """Central differences of M u'' = -K u + loads f(t) for every load column at once.

    K in CSR, M lumped; f the hat of unit peak at t = h = ``substeps`` dt, 0 at 0 and at 2 h.

    Parameters
    ----------
    indptr : numpy.ndarray
        CSR row pointers of K.
    indices : numpy.ndarray
        CSR column indices of K.
    data : numpy.ndarray
        CSR values of K [N/m].
    inverse_mass : numpy.ndarray
        Inverse lumped mass per degree of freedom, shape (n,) [1/kg].
    loads : numpy.ndarray
        Load vectors, one column per load, shape (n, loads) [-].
    steps : int
        Number of output steps h [-].
    substeps : int
        Central-difference substeps per step h [-].
    dt : float
        Substep [s].

    Returns
    -------
    numpy.ndarray
        The loads' own displacements loads^T u at t = h, 2 h, ..., shape
        (``steps``, loads, loads) [m/N].
    """
    n, m = loads.shape
    # the load columns in blocks of four, each summed in registers over one pass of a row of K
    # (the columns padded with zero loads to a multiple of four; every column's sums in the
    # order of a column-by-column product)
    width = 4 * ((m + 3) // 4)
    padded = np.zeros((n, width))
    padded[:, :m] = loads
    u = np.zeros((n, width))
    v = np.zeros((n, width))
    out = np.zeros((steps, m, m))
    for s in range(steps):  # from s h to (s + 1) h
        for q in range(substeps):
            f = max(0.0, 1.0 - abs((s * substeps + q + 0.5) / substeps - 1.0))
            for i in range(n):
                w = dt * inverse_mass[i]
                for b in range(0, width, 4):
                    a0 = f * padded[i, b]
                    a1 = f * padded[i, b + 1]
                    a2 = f * padded[i, b + 2]
                    a3 = f * padded[i, b + 3]
                    for p in range(indptr[i], indptr[i + 1]):
                        k = data[p]
                        c = indices[p]
                        a0 -= k * u[c, b]
                        a1 -= k * u[c, b + 1]
                        a2 -= k * u[c, b + 2]
                        a3 -= k * u[c, b + 3]
                    v[i, b] += w * a0
                    v[i, b + 1] += w * a1
                    v[i, b + 2] += w * a2
                    v[i, b + 3] += w * a3
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
    """The ring kernel G (``steps``, ``rings``, ``rings``) [m/N] (module docstring).

    Of a tube of the pile's section r_in..r_out [m] and ``length`` [m] at the time ``step`` [s].

    Parameters
    ----------
    material : Material
        The tube's material.
    r_in : float
        Inner radius [m].
    r_out : float
        Outer radius [m].
    length : float
        Tube length [m].
    step : float
        Time step of the kernel [s].
    steps : int
        Number of kernel steps [-].
    rings : int, default 3
        Number of equal-width rings across the wall [-].
    axial_size : float, default 0.1
        Largest element size along the axis [m].

    Returns
    -------
    numpy.ndarray
        G, shape (``steps``, ``rings``, ``rings``) [m/N].
    """
    model = tube_model(material, r_in, r_out, length, rings, axial_size)
    mass = model.lumped_mass()
    K = model.stiffness.tocsr()
    loads, _ = annulus_vectors(model, 0.0, r_in, r_out, rings)
    substeps = int(np.ceil(step / (SAFETY * 2.0 / np.sqrt(max_eigenvalue(K, mass)))))
    return hat_responses(K.indptr, K.indices, K.data, 1.0 / mass, np.ascontiguousarray(loads),
                         int(steps), substeps, step / substeps)


def echo_free_length(wave_speed: float, duration: float) -> float:
    """A pile length [m] whose toe echo comes back after ``duration`` [s].

    ceil(0.6 c T + 1 m) with c [m/s] the bar speed, so that even the tube's plate waves
    (c / sqrt(1 - nu^2), 5 % faster) take longer than T for the 2 L there and back; what
    :func:`rod_head_response` and the engine's tube take for a semi-infinite pile over a blow.

    Parameters
    ----------
    wave_speed : float
        Bar wave speed c [m/s].
    duration : float
        Duration T that must be echo free [s].

    Returns
    -------
    float
        The pile length [m].
    """
    return float(np.ceil(0.6 * wave_speed * duration + 1.0))


def tube_contact_stiffness(youngs_modulus: float, wall_thickness: float,
                           ring_areas: np.ndarray) -> np.ndarray:
    """The rings' contact springs on the tube head [N/m].

    E / h per unit area with h the element size across the wall (the wall over the number of
    rings), summed over each ring; the reference FEA's penalty (one element layer of compliance).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa].
    wall_thickness : float
        Wall thickness [m].
    ring_areas : numpy.ndarray
        Area of each ring [m^2].

    Returns
    -------
    numpy.ndarray
        Contact stiffness of each ring [N/m].
    """
    ring_areas = np.asarray(ring_areas, float)
    return youngs_modulus / (wall_thickness / ring_areas.size) * ring_areas


def rod_head_response(pile, step: float, steps: int, substeps: int,
                      extrapolation: float) -> np.ndarray:
    """The 1D pile's head output under a unit force held over the first step [m/N].

    The head output is :func:`anvilwave.pile.kernels.head_displacement` with the head
    ``extrapolation`` ratio of the pile's probes (0 for the top mass, the system's default), at the
    steps t_k = k ``step`` [s], k = 0 .. ``steps`` - 1, under a unit force [N] held over the first
    step: the pile's top section, continued so that no reflection returns within the steps (its
    segments and damping as the pile's, no soil, no gravity, ``substeps`` sub-steps a step as the
    pile's), so the semi-infinite 1D head as the kernels discretise it [m/N].

    Parameters
    ----------
    pile : PileSpec
        The pile; its top section is used.
    step : float
        Time step [s].
    steps : int
        Number of steps [-].
    substeps : int
        Sub-steps a step [-].
    extrapolation : float
        Head extrapolation ratio [-].

    Returns
    -------
    numpy.ndarray
        Head displacement per unit force at the steps, shape (``steps``,) [m/N].
    """
    top = pile.sections[0]
    pieces = max(1, int(np.ceil(top.length / pile.segment_length - 1e-9)))
    dx = top.length / pieces
    needed = echo_free_length(top.wave_speed, step * steps)
    long = replace(pile, sections=(replace(top, length=dx * np.ceil(needed / dx)),))
    params = pile_parameters(long)
    probes = probe_parameters(long)
    probes[HEAD_EXTRAPOLATION] = extrapolation
    n = params.shape[1]
    sweeps = sweep_arrays(params, np.zeros((SOIL_ROWS, n + 1)), 0.0)  # prepared once
    u, v, offset, energy = np.zeros(n), np.zeros(n), np.zeros(n + 1), np.zeros(ENERGY_SIZE)
    out = np.zeros(steps)
    for k in range(1, steps):
        pile_advance(*sweeps, u, v, offset, energy, 1.0 if k == 1 else 0.0, step, substeps)
        out[k] = head_displacement(probes, u)
    return out


def head_correction(tube: np.ndarray, rod: np.ndarray) -> np.ndarray:
    """What the tube head adds to the 1D head under K rings, D (steps, K, K) [m/N].

    D[k] = G[k] - g[k] 1 1^T, with G the tube's ring kernel (:func:`ring_kernel`) and g the
    1D head's response (:func:`rod_head_response`) at the same step. The 1D pile's head face
    plus sum_k D[k] (F_(n-k) - F_rest) moves the rings as the tube head would, with the 1D
    pile's own reflections (its soil, its toe); the rings' contact springs are the tube's
    (:func:`tube_contact_stiffness`) instead of the 1D head's.

    Parameters
    ----------
    tube : numpy.ndarray
        The tube's ring kernel G, shape (steps, K, K) [m/N].
    rod : numpy.ndarray
        The 1D head's response g, shape (steps,) [m/N].

    Returns
    -------
    numpy.ndarray
        D, shape (min of the two step counts, K, K) [m/N].
    """
    steps = min(tube.shape[0], rod.size)
    return tube[:steps] - rod[:steps, None, None] * np.ones((1,) + tube.shape[1:])
