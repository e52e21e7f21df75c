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

The ram port can be split the same way (``Interfaces.ram_annuli``, J equal-width annuli from
the axis to the ram radius): under the ram's edge the contact pressure peaks, which one uniform
port cannot carry. Each annulus is its own contact between the same annulus of the ram's toe
and of the anvil's top face. The ram unit (:class:`anvilwave.hammer.modal_ram.ModalRamUnit`, and
its FMU)
keeps its one toe driven by the sum of the annulus forces; the ring unit carries the ram's
flexible modes twice, T driven by the annulus forces (the ram's true state) and U by their sum
as the ram unit drives them, both from rest at impact (:class:`RamFace`,
:func:`ram_face_advance`), and annulus a sits at the unit's toe plus
sum_j (P_aj T_j - p_j U_j): exact for the linear ram, whose rigid mode moves every annulus
alike. The contacts' ram side is the ram's residual flexibility between the annuli.

With the static correction, the contact forces F = (F_1 .. F_J, F_J+1 .. F_J+K) of the ram
annuli (J = 1: the one ram port) and the rings at an instant solve one linear complementarity
problem (Cottle, Pang & Stone 1992)::

    w = A F - g >= 0,   F >= 0,   F . w = 0,
    A = C + D R D,   D = diag(1, .., 1, -1, .., -1)

with C block-diagonal (the ram's side: 1 / k_ram for one port, the ram's residual flexibility
between its annuli for J > 1; then diag(1 / k) of the rings), g the overlaps of the modal faces
(the dashpots folded in as an equivalent overlap d + c d' / k, as for the one port,
:func:`anvilwave.anvil_rom.rom.anvil_contact_forces`) and R the anvil's residual flexibility
between the
ram annuli and the rings. A is symmetric positive definite, so the solution is unique, and
Murty's least-index principal pivoting (Murty 1974) reaches it in finitely many pivots; it
starts from the previous step's active set, which is nearly always the answer. With J = K = 1
this is the one-port problem.

Kernel data (float64, besides the one-port unit's P, C, S of :mod:`anvilwave.anvil_rom.unit`), m =
J + K: one :class:`RingState`, whose fields carry the names above (``A`` is ``flexibility``,
``F`` is ``forces``, ...; the short names stay inside the formulas, as in the text).
:data:`STATE` names the fields that change as the unit runs; :func:`copy_ring_state` copies
them and shares the rest.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from anvilwave.anvil_rom.rom import modal_transition

MAX_PIVOTS_PER_CONTACT = 50
"""Murty's pivoting is finite for a positive definite A; this bounds it all the same."""


class RingState(NamedTuple):
    """The ring unit's arrays (float64), m = J + K contacts: the ram face's J annuli, then the
    pile port's K rings. A NamedTuple: the compiled kernels read its fields by name (numba
    compiles and caches functions taking it like any tuple of arrays)."""

    participation: np.ndarray
    """RP (n, K): the rings' modal participations p_k [kg^-1/2]."""
    flexibility: np.ndarray
    """A (m, m): the complementarity problem's matrix C + D R D [m/N] (module docstring)."""
    dashpot_ratios: np.ndarray
    """T (m): the contacts' dashpot over spring ratios c / k [s]."""
    ring_shares: np.ndarray
    """W (K): the rings' area shares [-]."""
    forces: np.ndarray
    """F (m): the contact forces at t_n [N] (written)."""
    elastic_forces: np.ndarray
    """E (m): their elastic parts (without the dashpots) [N] (written)."""
    ring_modal: np.ndarray
    """ring (2, K): the rings' modal (u, v) of the state [m, m/s] (written)."""
    scratch: np.ndarray
    """(m, m + 4): the solvers' scratch: the active sets of the forces and of their elastic
    parts, the overlaps, the elimination."""
    residual: np.ndarray
    """R (m, m): the residual flexibility between the ram annuli and the rings [m/N]."""
    head_kernel: np.ndarray
    """D (L, K, K): the tube head's correction at each lag [m/N] (:func:`head_push`; one lag
    of zeros on the 1D head)."""
    head_history: np.ndarray
    """(L, K): the ring forces' changes since the rest [N] (written)."""
    head_shift: np.ndarray
    """(2, K): the head's shift of the rings' pile side, now and a step before [m] (written)."""
    head_rest: np.ndarray
    """(K): the ring forces at the blow's start [N] (written)."""
    head_count: np.ndarray
    """(2): the steps in the history and the work handed to the tube head [J] (written)."""
    face_participation: np.ndarray
    """RQ (n, J): the anvil's participations on the ram face's annuli [kg^-1/2]."""
    face_modal: np.ndarray
    """face (2, J): their modal (u, v) of the state [m, m/s] (written)."""
    annulus_shares: np.ndarray
    """Wr (J): the annuli's area shares [-]."""
    ram_coefficients: np.ndarray
    """Cr (n_r, 5): the ram's flexible modes' step coefficients a, b, c, m_e, omega^2
    (:meth:`RamFace.coefficients`)."""
    ram_participation: np.ndarray
    """Pr (n_r, J): the ram's flexible modes on its annuli [kg^-1/2]."""
    ram_toe_participation: np.ndarray
    """pr (n_r): the same on the whole toe [kg^-1/2]."""
    ram_state: np.ndarray
    """(4, n_r): the ram modes T and U now and a step before (:func:`ram_face_advance`)
    (written)."""
    ram_offsets: np.ndarray
    """(3, J): the annuli's offsets from the ram unit's toe now, a step before [m] and their
    rate [m/s] (written)."""


STATE = ("forces", "elastic_forces", "ring_modal", "scratch", "head_history", "head_shift",
         "head_rest", "head_count", "face_modal", "ram_state", "ram_offsets")
"""The fields of :class:`RingState` that change as the unit runs; the rest is data."""


def copy_ring_state(rings: RingState) -> RingState:
    """``rings`` with its changing arrays (:data:`STATE`) copied and its data shared."""
    return rings._replace(**{name: getattr(rings, name).copy() for name in STATE})


@dataclass(frozen=True, eq=False)
class RamFace:
    """The ram's toe in J equal-width annuli, as the anvil's ram port in annuli sees it: the
    ram's flexible modes (the rigid one moves every annulus alike and is left out).

    omega : (n,) circular frequencies [rad/s] (all > 0). participation : (J, n) b_a^T phi_j
    on each annulus [kg^-1/2]. toe : (n,) on the whole toe (the ram unit's), their
    area-weighted mean. residual : (J, J) the truncated modes' flexibility between the
    annuli [m/N]. areas : (J,) [m^2].
    """

    omega: np.ndarray
    participation: np.ndarray
    toe: np.ndarray
    residual: np.ndarray
    areas: np.ndarray

    @classmethod
    def of(cls, omega, participation, toe, residual, areas) -> RamFace:
        """From a ram's modes with its rigid-body mode (omega = 0), which is dropped."""
        omega = np.asarray(omega, float)
        flexible = omega > 0.0
        return cls(omega[flexible], np.asarray(participation, float)[:, flexible],
                   np.asarray(toe, float)[flexible], np.asarray(residual, float),
                   np.asarray(areas, float))

    @property
    def n_annuli(self) -> int:
        return int(self.areas.size)

    def coefficients(self, h: float) -> np.ndarray:
        """(n, 5) [a, b, c, m_e, omega^2] of the modes for the step ``h`` [s]
        (:func:`anvilwave.anvil_rom.rom.modal_transition`, undamped: the ram unit's)."""
        return np.column_stack([modal_transition(self.omega, 0.0, h), self.omega ** 2])


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
def ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, face, ring, T, elastic, shift, offset, rate):
    """The overlaps g (J + K) of the ram face's J annuli (``face`` (2, J) the anvil's modal
    (u, v) there; the ram's toe u_ram, v_ram plus its annuli's ``offset`` and ``rate`` (J),
    :func:`ram_face_advance`; zeros for one port) and of the K rings, with the dashpots
    folded in (``elastic``: without them); ``shift`` (K) [m] moves the rings' pile side down
    (the tube head's correction, :func:`head_push`; zeros for the 1D head)."""
    J = face.shape[1]
    K = ring.shape[1]
    for a in range(J):
        g[a] = u_ram + offset[a] - face[0, a]
        if not elastic:
            g[a] += T[a] * (v_ram + rate[a] - face[1, a])
    for k in range(K):
        g[J + k] = ring[0, k] - u_pile - shift[k]
        if not elastic:
            g[J + k] += T[J + k] * (ring[1, k] - v_pile)


@njit(cache=True, inline='always')
def head_push(rings):
    """After a step with the ring forces ``rings`` F held: their change since the rest
    (``rings`` rest) into the tube head's history and its next shift, sum over m >= 1 of
    D[m] (F_(n+1-m) - F_rest) - D[0] F_rest, with D the dynamic head correction
    (:func:`anvilwave.pile.head_kernel.head_correction` without its contact springs, which are in
    A);
    the shift before is kept as the previous one (for the energy). The work of the forces on
    the step that just ended, their trapezoid (F_n-1 + F_n) / 2 over its shift's change, is
    added to ``rings`` count[1] [J] (the energy the rings hand to the tube head beyond the 1D
    head and beyond D[0], whose part is the contacts' complementary energy; the held force's
    rectangle F_n over the next change booked +1.8 % of the Table 1 blow at fmax 10 kHz and
    10 us, where the rings chatter: the kernel's tube is loaded by forces that vary linearly
    over a step). A kernel of one step (the 1D head: D = 0) leaves the shift at zero."""
    F, D, history = rings.forces, rings.head_kernel, rings.head_history
    shift, rest, count = rings.head_shift, rings.head_rest, rings.head_count
    J = rings.face_modal.shape[1]
    L = D.shape[0]
    K = D.shape[1]
    n = int(count[0])
    if n < L:
        for k in range(K):
            history[n, k] = F[J + k] - rest[k]
        n += 1
        count[0] = n
    work = 0.0
    for k in range(K):
        # the interval just ended: the trapezoid of the forces before and now over its shift
        before = rest[k] + (history[n - 2, k] if n >= 2 else 0.0)
        work += 0.5 * (before + F[J + k]) * (shift[0, k] - shift[1, k])
        shift[1, k] = shift[0, k]
        total = 0.0
        for l in range(K):
            total -= D[0, k, l] * rest[l]
        for m in range(1, min(n, L - 1) + 1):
            for l in range(K):
                total += D[m, k, l] * history[n - m, l]
        shift[0, k] = total
    count[1] += work


@njit(cache=True, inline='always')
def ring_contact(rings, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, F_pile) [N] of the neighbour states: the sums over the ram
    face's annuli and over the rings, whose forces are left in ``rings`` F (the faces' modal
    states are ``rings`` ring and face)."""
    A, T, F, ring = rings.flexibility, rings.dashpot_ratios, rings.forces, rings.ring_modal
    scratch, face, offsets = rings.scratch, rings.face_modal, rings.ram_offsets
    m = F.shape[0]
    J = face.shape[1]
    active = scratch[:, 0]
    g = scratch[:, 2]
    work = scratch[:, 3:]
    ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, face, ring, T, False, rings.head_shift[0],
                  offsets[0], offsets[2])
    contact_lcp(A, g, F, active, work)
    ram = 0.0
    for a in range(J):
        ram += F[a]
    total = 0.0
    for k in range(J, m):
        total += F[k]
    return ram, total


@njit(cache=True, inline='always')
def ring_elastic_forces(rings, u_ram, v_ram, u_pile, v_pile):
    """The contact forces without the dashpots into ``rings`` E (their elastic parts, whose
    complementary energy the contacts store) and the power [W] the dashpots dissipate at the
    forces ``rings`` F (:func:`anvilwave.anvil_rom.unit.modal_unit_dashpot_power` for rings).
    Returns
    (elastic F_ram, elastic sum of the ring forces, power)."""
    A, T, F, E = rings.flexibility, rings.dashpot_ratios, rings.forces, rings.elastic_forces
    ring, scratch = rings.ring_modal, rings.scratch
    face, offsets = rings.face_modal, rings.ram_offsets
    m = F.shape[0]
    J = face.shape[1]
    active = scratch[:, 1]
    g = scratch[:, 2]
    work = scratch[:, 3:]
    ring_overlaps(g, u_ram, v_ram, u_pile, v_pile, face, ring, T, True, rings.head_shift[0],
                  offsets[0], offsets[2])
    contact_lcp(A, g, E, active, work)
    power = 0.0
    ram = 0.0
    for a in range(J):
        power += (F[a] - E[a]) * (v_ram + offsets[2, a] - face[1, a])
        ram += E[a]
    total = 0.0
    for k in range(J, m):
        power += (F[k] - E[k]) * (ring[1, k - J] - v_pile)
        total += E[k]
    return ram, total, power


@njit(cache=True)
def ring_interface(coefficients, state, rings, h):
    """The rings' and the ram face annuli's modal (u, v) [m, m/s] of the state into
    ``rings`` ring (2, K) and face (2, J)."""
    C, S = coefficients, state
    _port_sums(C.shape[0], S, rings.participation, h, rings.ring_modal)
    _port_sums(C.shape[0], S, rings.face_participation, h, rings.face_modal)


@njit(cache=True, inline='always')
def _port_sums(n, S, participations, h, out):
    """The modal (u, v) [m, m/s] of the state S (2 n) at ports of ``participations`` (n, ports)
    into ``out`` (2, ports)."""
    inverse_step = 1.0 / h
    for k in range(participations.shape[1]):
        u = 0.0
        v = 0.0
        for j in range(n):
            u += participations[j, k] * S[j]
            v += participations[j, k] * ((S[j] - S[n + j]) * inverse_step)
        out[0, k] = u
        out[1, k] = v


@njit(cache=True, inline='always')
def ram_face_advance(rings, h):
    """The ram face's annuli over h with their forces (``rings`` F[:J]) held: the ram's
    flexible modes driven by the annuli's forces (T) and, as the ram unit drives them, by
    their sum on the whole toe (U), both from rest at the blow's start; the annuli's offsets
    from the toe, sum_j P_aj T_j - p_j U_j (the ram unit's toe is sum p_j U_j + the rigid
    mode, which moves every annulus alike), into ``rings`` offsets (now, before, rate). With
    one port (no modes) the offsets stay zero."""
    F, Cr, Pr = rings.forces, rings.ram_coefficients, rings.ram_participation
    pr, state, offsets = rings.ram_toe_participation, rings.ram_state, rings.ram_offsets
    nr = Cr.shape[0]
    J = Pr.shape[1]
    total = 0.0
    for a in range(J):
        total += F[a]
        offsets[1, a] = offsets[0, a]
        offsets[0, a] = 0.0
    for j in range(nr):
        drive = 0.0
        for a in range(J):
            drive -= Pr[j, a] * F[a]
        t = Cr[j, 0] * state[0, j] + Cr[j, 1] * state[1, j] + Cr[j, 2] * drive
        u = Cr[j, 0] * state[2, j] + Cr[j, 1] * state[3, j] - Cr[j, 2] * pr[j] * total
        state[1, j] = state[0, j]
        state[0, j] = t
        state[3, j] = state[2, j]
        state[2, j] = u
        for a in range(J):
            offsets[0, a] += Pr[j, a] * t - pr[j] * u
    inverse_step = 1.0 / h
    for a in range(J):
        offsets[2, a] = (offsets[0, a] - offsets[1, a]) * inverse_step


@njit(cache=True, inline='always')
def ram_face_energy(rings, h):
    """(kinetic, strain) [J] the ram's face in annuli adds to the ram unit's, in the shadow
    form of :func:`anvilwave.hammer.modal_ram.modal_ram_energies`: E(T) - E(U)
    (:func:`ram_face_advance`:
    the ram's true flexible state is T, the unit's U)."""
    Cr, state = rings.ram_coefficients, rings.ram_state
    kinetic = 0.0
    strain = 0.0
    inverse_step = 1.0 / h
    for j in range(Cr.shape[0]):
        rt = (state[0, j] - state[1, j]) * inverse_step
        ru = (state[2, j] - state[3, j]) * inverse_step
        kinetic += 0.5 * Cr[j, 3] * (rt * rt - ru * ru)
        strain += 0.5 * Cr[j, 4] * (state[0, j] * state[1, j] - state[2, j] * state[3, j])
    return kinetic, strain


@njit(cache=True, inline='always')
def ring_unit_advance(parameters, coefficients, state, force_ram, rings, interface):
    """Advance the modes over h with the ram force and the ring forces (``rings`` F) held
    (:func:`anvilwave.anvil_rom.unit.modal_unit_advance` with the pile load split over the rings
    and,
    with J > 1 annuli, the ram load over the annuli; with one port ``force_ram``), then the
    interface sums of the new state: ``interface`` (u_top, v_top, u_bottom, v_bottom; the
    bottom as the whole ring's mean), ``rings`` ring and face; then the ram face's annuli
    (:func:`ram_face_advance`) and the tube head (:func:`head_push`)."""
    P, C, S = parameters, coefficients, state
    RP, F, ring = rings.participation, rings.forces, rings.ring_modal
    RQ, face = rings.face_participation, rings.face_modal
    n = C.shape[0]
    K = RP.shape[1]
    J = RQ.shape[1]
    gravity = P[7]
    inverse_step = 1.0 / P[8]
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for k in range(K):
        ring[0, k] = 0.0
        ring[1, k] = 0.0
    for a in range(J):
        face[0, a] = 0.0
        face[1, a] = 0.0
    for j in range(n):
        f = C[j, 6] * gravity
        if J == 1:
            f += C[j, 4] * force_ram
        else:
            for a in range(J):
                f += RQ[j, a] * F[a]
        for k in range(K):
            f -= RP[j, k] * F[J + k]
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
        for a in range(J):
            face[0, a] += RQ[j, a] * q_new
            face[1, a] += RQ[j, a] * qd
    interface[0] = ut
    interface[1] = vt
    interface[2] = ub
    interface[3] = vb
    ram_face_advance(rings, P[8])
    head_push(rings)


@njit(cache=True)
def ring_unit_energy_at(parameters, coefficients, state, rings, u_ram, v_ram, u_pile, v_pile):
    """(kinetic, potential) [J] of the ring unit in the conserved (shadow) form of the
    two-step scheme (:func:`anvilwave.anvil_rom.unit.modal_unit_energy_at`): the modes' kinetic and
    strain energies and gravity potential, and the complementary energy of the contacts and
    the residual flexibility, F_n^T A F_n-1 / 2 with F_n the elastic forces (``rings`` E, from
    :func:`ring_elastic_forces`) and F_n-1 those one step earlier (neighbours moved back by
    h v, modes at q_n-1); with the ram face in annuli also what they add to the ram unit's
    energy (:func:`ram_face_energy`)."""
    P, C, S = parameters, coefficients, state
    RP, A, E, scratch = rings.participation, rings.flexibility, rings.elastic_forces, rings.scratch
    RQ, offsets = rings.face_participation, rings.ram_offsets
    n = C.shape[0]
    K = RP.shape[1]
    J = RQ.shape[1]
    m = J + K
    h = P[8]
    inverse_step = 1.0 / h
    kinetic, potential = ram_face_energy(rings, h)
    previous = np.zeros((2, K))
    face = np.zeros((2, J))
    for j in range(n):
        q, qp = S[j], S[n + j]
        rate = (q - qp) * inverse_step
        kinetic += 0.5 * C[j, 3] * rate * rate
        potential += 0.5 * C[j, 7] ** 2 * q * qp - P[7] * C[j, 6] * 0.5 * (q + qp)
        for a in range(J):
            face[0, a] += RQ[j, a] * qp
        for k in range(K):
            previous[0, k] += RP[j, k] * qp
    g = np.empty(m)
    ring_overlaps(g, u_ram - h * v_ram, 0.0, u_pile - h * v_pile, 0.0, face, previous,
                  rings.dashpot_ratios, True, rings.head_shift[1], offsets[1], offsets[2])
    F0 = np.zeros(m)
    active = scratch[:, 0].copy()
    contact_lcp(A, g, F0, active, np.empty((m, m + 1)))
    for i in range(m):
        for j in range(m):
            potential += 0.5 * E[i] * A[i, j] * F0[j]
    return kinetic, potential


def ring_matrix(contact_ram, contact_rings: np.ndarray, residual: np.ndarray
                ) -> np.ndarray:
    """A = C + D R D (module docstring) of the ram contact [N/m] (or, for a ram face in J
    annuli, the ram's residual flexibility between them (J, J) [m/N]: the contacts' ram
    side), the ring contact stiffnesses (K) [N/m] and the residual flexibility R (J + K,
    J + K) [m/N] between the ram face's annuli and the rings; C is block-diagonal, the ram
    block, then diag(1 / k) of the rings."""
    ram = np.atleast_2d(contact_ram)
    if ram.shape == (1, 1):
        ram = 1.0 / ram
    J = ram.shape[0]
    signs = np.r_[np.ones(J), -np.ones(len(contact_rings))]
    A = signs[:, None] * residual * signs
    A[:J, :J] += ram
    A[J:, J:] += np.diag(1.0 / np.asarray(contact_rings, float))
    return A


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
def ring_faces(rings):
    """(u_top, u_bottom) [m] with the static correction at the forces ``rings`` F: the ram
    face's and the rings' area-weighted means (the whole face's and the whole ring's
    displacements), from their modal parts (``rings`` face and ring) and the residual
    flexibility ``rings`` R (``residual``)."""
    W, F, ring, R = rings.ring_shares, rings.forces, rings.ring_modal, rings.residual
    face, Wr = rings.face_modal, rings.annulus_shares
    m = F.shape[0]
    J = face.shape[1]
    u_top = 0.0
    for a in range(J):
        u = face[0, a]
        for b in range(J):
            u += R[a, b] * F[b]
        for k in range(J, m):
            u -= R[a, k] * F[k]
        u_top += Wr[a] * u
    u_bottom = 0.0
    for k in range(J, m):
        u = ring[0, k - J]
        for b in range(J):
            u += R[k, b] * F[b]
        for l in range(J, m):
            u -= R[k, l] * F[l]
        u_bottom += W[k - J] * u
    return u_top, u_bottom


@njit(cache=True)
def ring_unit_outputs(parameters, coefficients, state, rings, u_ram, v_ram, u_pile, v_pile):
    """(F_ram, F_pile, u_top, u_bottom) [N, N, m, m] of the ring unit for the neighbour
    states, from its state alone (the anvil FMU's feedthrough): the faces' modal sums, the
    rings' contact problem (forces left in ``rings`` F; F_pile their sum) and the faces."""
    P, C, S = parameters, coefficients, state
    ring_interface(C, S, rings, P[8])
    force_ram, force_pile = ring_contact(rings, u_ram, v_ram, u_pile, v_pile)
    u_top, u_bottom = ring_faces(rings)
    return force_ram, force_pile, u_top, u_bottom
