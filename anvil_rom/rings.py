"""The anvil's pile port split into rings across the pile wall.

The one-port ROM loads the anvil's bottom face with a uniform pressure on the pile ring and
closes one contact on the mean displacement of that ring. After a lift-off an anvil returns
tilted across the wall (about 4 mrad across Table 1's 0.14 m) and the real ring closes from one
edge over a fraction of a millisecond; the one port closes it at once, a slap that puts the
pile-head force's 1.6-4 kHz band levels up to 8 dB above the FEA's
(``benchmarks/study_pile_port.py``). With K rings (``Interfaces.pile_rings``) each ring is a
uniform pressure of its own (its own modal participations p_k) and its own compression-only
contact on the pile head, with the pile's contact spring shared by ring area, so the rings
close one after the other as the tilted face comes down.

With the static correction, the contact forces F = (F_ram, F_1 .. F_K) at an instant solve one
linear complementarity problem (Cottle, Pang & Stone 1992)::

    w = A F - g >= 0,   F >= 0,   F . w = 0,
    A = diag(1 / k) + D R D,   D = diag(1, -1, .., -1)

with g the overlaps of the modal faces (the dashpots folded in as an equivalent overlap
d + c d' / k, as for the one port, :func:`anvil_rom.rom.anvil_contact_forces`) and R the
residual flexibility between the ram face and the rings. A is symmetric positive definite, so
the solution is unique, and Murty's least-index principal pivoting (Murty 1974) reaches it in
finitely many pivots; it starts from the previous step's active set, which is nearly always the
answer. With K = 1 this is the one-port problem.

Kernel data (float64, besides the one-port unit's P, C, S of :mod:`anvil_rom.unit`):
``RP`` (n, K) ring participations; ``A`` (1 + K, 1 + K); ``T`` (1 + K) dashpot ratios c / k;
``W`` (K) ring area shares; ``F`` (1 + K) the contact forces at t_n (written); ``E`` (1 + K)
their elastic parts; ``ring`` (2, K) the rings' modal (u, v) of the state; ``scratch``
(1 + K, 5 + K) for the solvers (the active sets of the forces and of their elastic parts,
overlaps, elimination); ``R`` (1 + K, 1 + K) the residual flexibility. The engine passes them
as one tuple in this order.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .rom import modal_interface

MAX_PIVOTS_PER_CONTACT = 50
"""Murty's pivoting is finite for a positive definite A; this bounds it all the same."""


@njit(cache=True, inline='always')
def _solve_active(A, g, F, active, work):
    """F_a = A_aa^-1 g_a on the active set (Gaussian elimination without pivoting: A_aa is
    positive definite), F = 0 elsewhere; ``work`` (m, m + 1) scratch."""
    m = g.shape[0]
    idx = 0
    for i in range(m):
        F[i] = 0.0
        if active[i] != 0.0:
            jdx = 0
            for j in range(m):
                if active[j] != 0.0:
                    work[idx, jdx] = A[i, j]
                    jdx += 1
            work[idx, m] = g[i]
            idx += 1
    size = idx
    for p in range(size):
        pivot = work[p, p]
        for r in range(p + 1, size):
            factor = work[r, p] / pivot
            for c in range(p, size):
                work[r, c] -= factor * work[p, c]
            work[r, m] -= factor * work[p, m]
    for p in range(size - 1, -1, -1):
        total = work[p, m]
        for c in range(p + 1, size):
            total -= work[p, c] * work[c, m]
        work[p, m] = total / work[p, p]
    idx = 0
    for i in range(m):
        if active[i] != 0.0:
            F[i] = work[idx, m]
            idx += 1


@njit(cache=True, inline='always')
def contact_lcp(A, g, F, active, work):
    """The forces F >= 0 [N] with A F - g >= 0 and F (A F - g) = 0 (module docstring), in
    place; ``active`` (m) holds the active set to start from (1.0: in contact) and receives
    the solution's; ``work`` (m, m + 1) scratch. Returns the number of pivots."""
    m = g.shape[0]
    for pivots in range(MAX_PIVOTS_PER_CONTACT * m):
        _solve_active(A, g, F, active, work)
        flip = -1
        for i in range(m):
            if active[i] != 0.0:
                if F[i] < 0.0:
                    flip = i
                    break
            else:
                w = -g[i]
                for j in range(m):
                    w += A[i, j] * F[j]
                if w < 0.0:
                    flip = i
                    break
        if flip < 0:
            return pivots
        active[flip] = 1.0 - active[flip]
    raise RuntimeError("ring contact: the complementarity pivoting did not end")


@njit(cache=True, inline='always')
def ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, ut, vt, ring, T, elastic, shift):
    """The overlaps g (1 + K) of the ram face and the rings, with the dashpots folded in
    (``elastic``: without them); ``shift`` (K) [m] moves the rings' pile side down (the tube
    head's correction, :func:`head_push`; zeros for the 1D head)."""
    K = ring.shape[1]
    g[0] = u_ram - ut
    if not elastic:
        g[0] += T[0] * (v_ram - vt)
    for k in range(K):
        g[1 + k] = ring[0, k] - u_pile - shift[k]
        if not elastic:
            g[1 + k] += T[1 + k] * (ring[1, k] - v_pile)


@njit(cache=True, inline='always')
def head_push(rings):
    """After a step with the ring forces ``rings`` F held: their change since the rest
    (``rings`` rest) into the tube head's history and its next shift, sum over m >= 1 of
    D[m] (F_(n+1-m) - F_rest) - D[0] F_rest, with D the dynamic head correction
    (:func:`pile.head_kernel.head_correction` without its contact springs, which are in A);
    the shift before is kept as the previous one (for the energy), and the work of the held
    forces on the shift's change is added to ``rings`` count[1] [J] (the energy the rings hand
    to the tube head beyond the 1D head and beyond D[0], whose part is the contacts'
    complementary energy). A kernel of one step (the 1D head: D = 0) leaves the shift at
    zero."""
    F, D, history, shift, rest, count = (rings[4], rings[9], rings[10], rings[11], rings[12],
                                         rings[13])
    L = D.shape[0]
    K = D.shape[1]
    n = int(count[0])
    if n < L:
        for k in range(K):
            history[n, k] = F[1 + k] - rest[k]
        n += 1
        count[0] = n
    work = 0.0
    for k in range(K):
        shift[1, k] = shift[0, k]
        total = 0.0
        for l in range(K):
            total -= D[0, k, l] * rest[l]
        for m in range(1, min(n, L - 1) + 1):
            for l in range(K):
                total += D[m, k, l] * history[n - m, l]
        shift[0, k] = total
        work += F[1 + k] * (shift[0, k] - shift[1, k])
    count[1] += work


@njit(cache=True, inline='always')
def ring_contact(rings, interface, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, sum of the ring forces) [N] of the neighbour states; the ring
    forces are left in ``rings`` F (rings = (RP, A, T, W, F, E, ring, scratch))."""
    A, T, F, ring, scratch = rings[1], rings[2], rings[4], rings[6], rings[7]
    m = F.shape[0]
    active = scratch[:, 0]
    g = scratch[:, 2]
    work = scratch[:, 3:]
    ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, interface[0], interface[1], ring, T, False,
                  rings[11][0])
    contact_lcp(A, g, F, active, work)
    total = 0.0
    for k in range(1, m):
        total += F[k]
    return F[0], total


@njit(cache=True, inline='always')
def ring_elastic_forces(rings, interface, u_ram, v_ram, u_pile, v_pile):
    """The contact forces without the dashpots into ``rings`` E (their elastic parts, whose
    complementary energy the contacts store) and the power [W] the dashpots dissipate at the
    forces ``rings`` F (:func:`anvil_rom.unit.modal_unit_dashpot_power` for rings). Returns
    (elastic F_ram, elastic sum of the ring forces, power)."""
    A, T, F, E, ring, scratch = rings[1], rings[2], rings[4], rings[5], rings[6], rings[7]
    m = F.shape[0]
    active = scratch[:, 1]
    g = scratch[:, 2]
    work = scratch[:, 3:]
    ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, interface[0], interface[1], ring, T, True,
                  rings[11][0])
    contact_lcp(A, g, E, active, work)
    power = (F[0] - E[0]) * (v_ram - interface[1])
    total = 0.0
    for k in range(1, m):
        power += (F[k] - E[k]) * (ring[1, k - 1] - v_pile)
        total += E[k]
    return E[0], total, power


@njit(cache=True)
def ring_interface(C, S, RP, h, ring):
    """The rings' modal (u, v) [m, m/s] of the state into ``ring`` (2, K)."""
    n = C.shape[0]
    K = RP.shape[1]
    inverse_step = 1.0 / h
    for k in range(K):
        u = 0.0
        v = 0.0
        for j in range(n):
            u += RP[j, k] * S[j]
            v += RP[j, k] * ((S[j] - S[n + j]) * inverse_step)
        ring[0, k] = u
        ring[1, k] = v


@njit(cache=True, inline='always')
def ring_unit_advance(P, C, S, force_ram, rings, interface):
    """Advance the modes over h with the ram force and the ring forces (``rings`` F) held
    (:func:`anvil_rom.unit.modal_unit_advance` with the pile load split over the rings), then
    the interface sums of the new state: ``interface`` (u_top, v_top, u_bottom, v_bottom; the
    bottom as the whole ring's mean) and ``rings`` ring."""
    RP, F, ring = rings[0], rings[4], rings[6]
    n = C.shape[0]
    K = RP.shape[1]
    gravity = P[7]
    inverse_step = 1.0 / P[8]
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for k in range(K):
        ring[0, k] = 0.0
        ring[1, k] = 0.0
    for j in range(n):
        f = C[j, 4] * force_ram + C[j, 6] * gravity
        for k in range(K):
            f -= RP[j, k] * F[1 + k]
        q = S[j]
        q_new = C[j, 0] * q + C[j, 1] * S[n + j] + C[j, 2] * f
        qd = (q_new - q) * inverse_step
        S[n + j] = q
        S[j] = q_new
        ut += C[j, 4] * q_new
        vt += C[j, 4] * qd
        ub += C[j, 5] * q_new
        vb += C[j, 5] * qd
        for k in range(K):
            ring[0, k] += RP[j, k] * q_new
            ring[1, k] += RP[j, k] * qd
    interface[0] = ut
    interface[1] = vt
    interface[2] = ub
    interface[3] = vb
    head_push(rings)


@njit(cache=True)
def ring_unit_energy_at(P, C, S, rings, u_ram, v_ram, u_pile, v_pile):
    """(kinetic, potential) [J] of the ring unit in the conserved (shadow) form of the
    two-step scheme (:func:`anvil_rom.unit.modal_unit_energy_at`): the modes' kinetic and
    strain energies and gravity potential, and the complementary energy of the contacts and
    the residual flexibility, F_n^T A F_n-1 / 2 with F_n the elastic forces (``rings`` E, from
    :func:`ring_elastic_forces`) and F_n-1 those one step earlier (neighbours moved back by
    h v, modes at q_n-1)."""
    RP, A, E, scratch = rings[0], rings[1], rings[5], rings[7]
    n = C.shape[0]
    K = RP.shape[1]
    m = K + 1
    h = P[8]
    inverse_step = 1.0 / h
    kinetic = 0.0
    potential = 0.0
    ut_prev = 0.0
    previous = np.zeros((2, K))
    for j in range(n):
        q, qp = S[j], S[n + j]
        rate = (q - qp) * inverse_step
        kinetic += 0.5 * C[j, 3] * rate * rate
        potential += 0.5 * C[j, 7] ** 2 * q * qp - P[7] * C[j, 6] * 0.5 * (q + qp)
        ut_prev += C[j, 4] * qp
        for k in range(K):
            previous[0, k] += RP[j, k] * qp
    g = np.empty(m)
    ring_overlaps(g, u_ram - h * v_ram, 0.0, u_pile - h * v_pile, 0.0, ut_prev, 0.0, previous,
                  rings[2], True, rings[11][1])
    F0 = np.zeros(m)
    active = scratch[:, 0].copy()
    contact_lcp(A, g, F0, active, np.empty((m, m + 1)))
    for i in range(m):
        for j in range(m):
            potential += 0.5 * E[i] * A[i, j] * F0[j]
    return kinetic, potential


def ring_matrix(contact_ram: float, contact_rings: np.ndarray, residual: np.ndarray
                ) -> np.ndarray:
    """A = diag(1 / k) + D R D (module docstring) of the ram contact stiffness [N/m], the ring
    contact stiffnesses (K) [N/m] and the residual flexibility R (1 + K, 1 + K) [m/N] between
    the ram face and the rings."""
    signs = np.r_[1.0, -np.ones(len(contact_rings))]
    return np.diag(1.0 / np.r_[contact_ram, contact_rings]) + signs[:, None] * residual * signs


def ring_static_rest(omega, participation_rings, ring_stiffness, residual_rings, weight
                     ) -> tuple[np.ndarray, float]:
    """Ring forces (K) [N] and the rigid displacement [m] of an anvil of ``weight`` [N] at rest
    on a fixed flat pile head. The rings in contact satisfy F_k / k_k + sum_l G_kl F_l = u0,
    with G_kl = sum_j p_kj p_lj / w_j^2 + R_kl the rings' flexible static response and u0 the
    rigid translation (the same at every ring), and sum F = weight; a ring whose force would
    be tensile is open (under its own weight a wide anvil dishes: the outer ring can lift),
    with u0 - (G F)_k <= 0 there. Solved by active sets from all rings in contact.
    ``participation_rings`` (K, n) with the rigid mode first; ``residual_rings`` (K, K)."""
    flexible = omega > 0.0
    Pk = participation_rings[:, flexible]
    G = (Pk / omega[flexible] ** 2) @ Pk.T + residual_rings
    K = ring_stiffness.size
    active = np.ones(K, bool)
    for _ in range(4 * K):
        idx = np.flatnonzero(active)
        a = idx.size
        M = np.zeros((a + 1, a + 1))
        M[:a, :a] = G[np.ix_(idx, idx)] + np.diag(1.0 / ring_stiffness[idx])
        M[:a, a] = -1.0
        M[a, :a] = 1.0
        solution = np.linalg.solve(M, np.r_[np.zeros(a), weight])
        forces = np.zeros(K)
        forces[idx] = solution[:a]
        u0 = float(solution[a])
        overlap = u0 - G @ forces
        if forces.min() < 0.0:
            active[int(np.argmin(forces))] = False
        elif np.any(~active & (overlap > 0.0)):
            active[int(np.argmax(np.where(active, -np.inf, overlap)))] = True
        else:
            return forces, u0
    raise RuntimeError("ring rest: the active set did not settle")


@njit(cache=True, inline='always')
def ring_faces(rings, ut):
    """(u_top, u_bottom) [m] with the static correction at the forces ``rings`` F: the ram
    face and the rings' area-weighted mean (the whole ring's displacement). ``ut`` is the ram
    face's modal part; ``rings`` R (its 9th entry) the residual flexibility."""
    W, F, ring, R = rings[3], rings[4], rings[6], rings[8]
    m = F.shape[0]
    u_top = ut + R[0, 0] * F[0]
    for k in range(1, m):
        u_top -= R[0, k] * F[k]
    u_bottom = 0.0
    for k in range(1, m):
        u = ring[0, k - 1] + R[k, 0] * F[0]
        for l in range(1, m):
            u -= R[k, l] * F[l]
        u_bottom += W[k - 1] * u
    return u_top, u_bottom


@njit(cache=True)
def ring_unit_outputs(P, C, S, rings, u_ram, v_ram, u_pile, v_pile):
    """(F_ram, F_pile, u_top, u_bottom) [N, N, m, m] of the ring unit for the neighbour
    states, from its state alone (the anvil FMU's feedthrough): the interface sums, the
    rings' contact problem (forces left in ``rings`` F; F_pile their sum) and the faces."""
    n = C.shape[0]
    ut, vt, _, _ = modal_interface(C[:, 4], C[:, 5], S[:n], S[n:], P[8])
    ring_interface(C, S, rings[0], P[8], rings[6])
    force_ram, force_pile = ring_contact(rings, (ut, vt), u_ram, v_ram, u_pile, v_pile)
    u_top, u_bottom = ring_faces(rings, ut)
    return force_ram, force_pile, u_top, u_bottom
