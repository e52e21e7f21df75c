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
    """The ring unit's arrays (float64) for m = J + K contacts.

    The ram face's J annuli come first, then the pile port's K rings. A NamedTuple: the
    compiled kernels read its fields by name (numba compiles and caches functions taking it
    like any tuple of arrays). The short names (``A``, ``F``, ...) are those of the formulas
    (module docstring).

    Parameters
    ----------
    participation : numpy.ndarray
        ``RP``: the rings' modal participations p_k, shape (n, K) [kg^-1/2].
    flexibility : numpy.ndarray
        ``A``: the complementarity problem's matrix C + D R D, shape (m, m) [m/N] (module
        docstring).
    dashpot_ratios : numpy.ndarray
        ``T``: the contacts' dashpot over spring ratios c / k, shape (m,) [s].
    ring_shares : numpy.ndarray
        ``W``: the rings' area shares, shape (K,) [-].
    forces : numpy.ndarray
        ``F``: the contact forces at t_n, shape (m,) [N] (written).
    elastic_forces : numpy.ndarray
        ``E``: their elastic parts (without the dashpots), shape (m,) [N] (written).
    ring_modal : numpy.ndarray
        ``ring``: the rings' modal (u, v) of the state, shape (2, K) [m, m/s] (written).
    scratch : numpy.ndarray
        The solvers' scratch, shape (m, m + 6): the active sets of the forces and of their
        elastic parts, the overlaps, the active set and the forces a step before (the energy's,
        :func:`ring_unit_energy_at`), the elimination (m, m + 1). Allocated with the unit: the
        compiled blow loop allocates nothing.
    residual : numpy.ndarray
        ``R``: the residual flexibility between the ram annuli and the rings, shape (m, m)
        [m/N].
    head_kernel : numpy.ndarray
        ``D``: the tube head's correction at each lag, shape (L, K, K) [m/N] (:func:`head_push`;
        one lag of zeros on the 1D head).
    head_history : numpy.ndarray
        The ring forces' changes since the rest, shape (L, K) [N] (written).
    head_shift : numpy.ndarray
        The head's shift of the rings' pile side, now and a step before, shape (2, K) [m]
        (written).
    head_rest : numpy.ndarray
        The ring forces at the blow's start, shape (K,) [N] (written).
    head_count : numpy.ndarray
        The steps in the history [-] and the work handed to the tube head [J], shape (2,)
        (written).
    face_participation : numpy.ndarray
        ``RQ``: the anvil's participations on the ram face's annuli, shape (n, J) [kg^-1/2].
    face_modal : numpy.ndarray
        ``face``: their modal (u, v) of the state, shape (2, J) [m, m/s] (written).
    annulus_shares : numpy.ndarray
        ``Wr``: the annuli's area shares, shape (J,) [-].
    ram_coefficients : numpy.ndarray
        ``Cr``: the ram's flexible modes' step coefficients a, b, c, m_e, omega^2, shape
        (n_r, 5) [-, -, s^2, -, rad^2/s^2] (:meth:`RamFace.coefficients`).
    ram_participation : numpy.ndarray
        ``Pr``: the ram's flexible modes on its annuli, shape (n_r, J) [kg^-1/2].
    ram_toe_participation : numpy.ndarray
        ``pr``: the same on the whole toe, shape (n_r,) [kg^-1/2].
    ram_state : numpy.ndarray
        The ram modes T and U now and a step before, shape (4, n_r) [m kg^1/2]
        (:func:`ram_face_advance`) (written).
    ram_offsets : numpy.ndarray
        The annuli's offsets from the ram unit's toe now and a step before [m] and their rate
        [m/s], shape (3, J) (written).
    face_before : numpy.ndarray
        The energy's scratch (:func:`ring_unit_energy_at`): the anvil's modal displacement at
        the ram face's annuli a step before, row 0 of shape (2, J) [m] (written; row 1 unused).
    ring_before : numpy.ndarray
        The same at the rings, row 0 of shape (2, K) [m] (written; row 1 unused).
    """

    participation: np.ndarray
    flexibility: np.ndarray
    dashpot_ratios: np.ndarray
    ring_shares: np.ndarray
    forces: np.ndarray
    elastic_forces: np.ndarray
    ring_modal: np.ndarray
    scratch: np.ndarray
    residual: np.ndarray
    head_kernel: np.ndarray
    head_history: np.ndarray
    head_shift: np.ndarray
    head_rest: np.ndarray
    head_count: np.ndarray
    face_participation: np.ndarray
    face_modal: np.ndarray
    annulus_shares: np.ndarray
    ram_coefficients: np.ndarray
    ram_participation: np.ndarray
    ram_toe_participation: np.ndarray
    ram_state: np.ndarray
    ram_offsets: np.ndarray
    face_before: np.ndarray
    ring_before: np.ndarray


STATE = ("forces", "elastic_forces", "ring_modal", "scratch", "head_history", "head_shift",
         "head_rest", "head_count", "face_modal", "ram_state", "ram_offsets", "face_before",
         "ring_before")
"""The fields of :class:`RingState` that change as the unit runs; the rest is data."""


def copy_ring_state(rings: RingState) -> RingState:
    """``rings`` with its changing arrays (:data:`STATE`) copied and its data shared.

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays.

    Returns
    -------
    RingState
        A state that runs apart from ``rings`` on the same data.
    """
    return rings._replace(**{name: getattr(rings, name).copy() for name in STATE})


@dataclass(frozen=True, eq=False)
class RamFace:
    """The ram's toe in J equal-width annuli, as the anvil's ram port in annuli sees it.

    The ram's flexible modes (the rigid one moves every annulus alike and is left out).

    Parameters
    ----------
    omega : numpy.ndarray
        Circular frequencies of the flexible modes, shape (n,) [rad/s] (all > 0).
    participation : numpy.ndarray
        b_a^T phi_j on each annulus, shape (J, n) [kg^-1/2].
    toe : numpy.ndarray
        The same on the whole toe (the ram unit's), their area-weighted mean, shape (n,)
        [kg^-1/2].
    residual : numpy.ndarray
        The truncated modes' flexibility between the annuli, shape (J, J) [m/N].
    areas : numpy.ndarray
        Areas of the annuli, shape (J,) [m^2].
    """

    omega: np.ndarray
    participation: np.ndarray
    toe: np.ndarray
    residual: np.ndarray
    areas: np.ndarray

    @classmethod
    def of(cls, omega, participation, toe, residual, areas) -> RamFace:
        """From a ram's modes with its rigid-body mode (omega = 0), which is dropped.

        Parameters
        ----------
        omega : array_like
            Circular frequencies, shape (n,) [rad/s], the rigid-body mode's 0 included.
        participation : array_like
            b_a^T phi_j on each annulus, shape (J, n) [kg^-1/2].
        toe : array_like
            The same on the whole toe, shape (n,) [kg^-1/2].
        residual : array_like
            The truncated modes' flexibility between the annuli, shape (J, J) [m/N].
        areas : array_like
            Areas of the annuli, shape (J,) [m^2].

        Returns
        -------
        RamFace
            The face with the flexible modes only.
        """
        omega = np.asarray(omega, float)
        flexible = omega > 0.0
        return cls(omega[flexible], np.asarray(participation, float)[:, flexible],
                   np.asarray(toe, float)[flexible], np.asarray(residual, float),
                   np.asarray(areas, float))

    @property
    def n_annuli(self) -> int:
        """Number of annuli of the face.

        Returns
        -------
        int
            J [-].
        """
        return int(self.areas.size)

    def coefficients(self, h: float) -> np.ndarray:
        """[a, b, c, m_e, omega^2] of the modes for the step ``h`` (undamped: the ram unit's).

        Parameters
        ----------
        h : float
            Time step [s].

        Returns
        -------
        numpy.ndarray
            Shape (n, 5) [-, -, s^2, -, rad^2/s^2]
            (:func:`anvilwave.anvil_rom.rom.modal_transition`, then omega^2).
        """
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
    """The forces F >= 0 [N] with A F - g >= 0 and F (A F - g) = 0 (module docstring), in place.

    Murty's least-index principal pivoting from the given active set.

    Parameters
    ----------
    A : numpy.ndarray
        The problem's matrix, symmetric positive definite, shape (m, m) [m/N].
    g : numpy.ndarray
        The overlaps, shape (m,) [m].
    F : numpy.ndarray
        Receives the forces, shape (m,) [N] (written).
    active : numpy.ndarray
        The active set to start from (1.0: in contact), shape (m,); receives the solution's
        (written).
    work : numpy.ndarray
        Scratch, shape (m, m + 1).

    Returns
    -------
    int
        The number of pivots [-].

    Raises
    ------
    RuntimeError
        If the pivoting does not end within MAX_PIVOTS_PER_CONTACT pivots per contact.
    """
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
    """The overlaps g of the ram face's J annuli and of the K rings, dashpots folded in.

    The ram side of annulus a is the ram's toe plus its ``offset`` and ``rate``
    (:func:`ram_face_advance`; zeros for one port); the rings' pile side is moved down by
    ``shift`` (the tube head's correction, :func:`head_push`; zeros for the 1D head).

    Parameters
    ----------
    g : numpy.ndarray
        Receives the overlaps, shape (J + K,) [m] (written).
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    face : numpy.ndarray
        The anvil's modal (u, v) at the ram face's annuli, shape (2, J) [m, m/s].
    ring : numpy.ndarray
        The anvil's modal (u, v) at the rings, shape (2, K) [m, m/s].
    T : numpy.ndarray
        The contacts' dashpot over spring ratios c / k, shape (J + K,) [s].
    elastic : bool
        True: the overlaps without the dashpots.
    shift : numpy.ndarray
        Shift of the rings' pile side, shape (K,) [m].
    offset : numpy.ndarray
        The annuli's offsets from the ram toe, shape (J,) [m].
    rate : numpy.ndarray
        Their rates, shape (J,) [m/s].
    """
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
    """After a step with the ring forces held: the tube head's history and its next shift.

    After a step with the ring forces ``rings`` F held: their change since the rest (``rings``
    rest) into the tube head's history and its next shift, sum over m >= 1 of D[m] (F_(n+1-m) -
    F_rest) - D[0] F_rest, with D the dynamic head correction
    (:func:`anvilwave.pile.head_kernel.head_correction` without its contact springs, which are
    in A); the shift before is kept as the previous one (for the energy). The work of the forces
    on the step that just ended, their trapezoid (F_n-1 + F_n) / 2 over its shift's change, is
    added to ``rings`` count[1] [J] (the energy the rings hand to the tube head beyond the 1D
    head and beyond D[0], whose part is the contacts' complementary energy; the held force's
    rectangle F_n over the next change booked +1.8 % of the Table 1 blow at fmax 10 kHz and 10
    us, where the rings chatter: the kernel's tube is loaded by forces that vary linearly over a
    step). A kernel of one step (the 1D head: D = 0) leaves the shift at zero.

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    """
    head_push_forces(rings.forces, rings.face_modal.shape[1], rings.head_kernel,
                     rings.head_history, rings.head_shift, rings.head_rest, rings.head_count)


@njit(cache=True, inline='always')
def head_push_forces(F, first, D, history, shift, rest, count):
    """:func:`head_push` on a force array whose pile rings start at index ``first``.

    The single anvil's rings and the stack's pile rings
    (:func:`anvilwave.anvil_rom.stack.stack_head_push`) share it.

    Parameters
    ----------
    F : numpy.ndarray
        The contact forces held over the step [N]; the K rings at ``first`` .. ``first + K``.
    first : int
        Index of the first pile ring in ``F`` [-].
    D : numpy.ndarray
        The tube head's correction at each lag, shape (L, K, K) [m/N].
    history : numpy.ndarray
        The rings' force changes since the rest, shape (L, K) [N] (written).
    shift : numpy.ndarray
        The rings' pile-side shift now and a step before, shape (2, K) [m] (written).
    rest : numpy.ndarray
        The rings' forces at rest, shape (K,) [N].
    count : numpy.ndarray
        The steps in the history [-] and the work handed to the tube [J], shape (2,)
        (written).
    """
    L = D.shape[0]
    K = D.shape[1]
    n = int(count[0])
    if n < L:
        for k in range(K):
            history[n, k] = F[first + k] - rest[k]
        n += 1
        count[0] = n
    work = 0.0
    for k in range(K):
        # the interval just ended: the trapezoid of the forces before and now over its shift
        before = rest[k] + (history[n - 2, k] if n >= 2 else 0.0)
        work += 0.5 * (before + F[first + k]) * (shift[0, k] - shift[1, k])
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
    """Contact forces (F_ram, F_pile) [N] of the neighbour states.

    The sums over the ram face's annuli and over the rings, whose forces are left in
    ``rings`` F (the faces' modal states are ``rings`` ring and face).

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].

    Returns
    -------
    ram : float
        Ram contact force, the sum over the annuli [N].
    total : float
        Pile contact force, the sum over the rings [N].
    """
    A, T, F, ring = rings.flexibility, rings.dashpot_ratios, rings.forces, rings.ring_modal
    scratch, face, offsets = rings.scratch, rings.face_modal, rings.ram_offsets
    m = F.shape[0]
    J = face.shape[1]
    active = scratch[:, 0]
    g = scratch[:, 2]
    work = scratch[:, 5:]
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
    """The contact forces without the dashpots and the power [W] the dashpots dissipate.

    The elastic parts go into ``rings`` E (their complementary energy the contacts store); the
    power is at the forces ``rings`` F
    (:func:`anvilwave.anvil_rom.unit.modal_unit_dashpot_power` for rings).

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].

    Returns
    -------
    ram : float
        Elastic part of the ram contact force [N].
    total : float
        Elastic sum of the ring forces [N].
    power : float
        Power dissipated by the contact dashpots [W].
    """
    A, T, F, E = rings.flexibility, rings.dashpot_ratios, rings.forces, rings.elastic_forces
    ring, scratch = rings.ring_modal, rings.scratch
    face, offsets = rings.face_modal, rings.ram_offsets
    m = F.shape[0]
    J = face.shape[1]
    active = scratch[:, 1]
    g = scratch[:, 2]
    work = scratch[:, 5:]
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
    """The rings' and the ram face annuli's modal (u, v) [m, m/s] of the state.

    Into ``rings`` ring (2, K) and face (2, J).

    Parameters
    ----------
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8) (:mod:`anvilwave.anvil_rom.unit`).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    h : float
        Time step [s].
    """
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
    """Advance the ram face's annuli over h with their forces held.

    The annuli's forces are ``rings`` F[:J]: the ram's flexible modes driven by the annuli's
    forces (T) and, as the ram unit drives them, by their sum on the whole toe (U), both from
    rest at the blow's start; the annuli's offsets from the toe, sum_j P_aj T_j - p_j U_j (the
    ram unit's toe is sum p_j U_j + the rigid mode, which moves every annulus alike), into
    ``rings`` offsets (now, before, rate). With one port (no modes) the offsets stay zero.

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    h : float
        Time step [s].
    """
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
    """(kinetic, strain) [J] the ram's face in annuli adds to the ram unit's energies.

    In the shadow form of :func:`anvilwave.hammer.modal_ram.modal_ram_energies`: E(T) - E(U)
    (:func:`ram_face_advance`: the ram's true flexible state is T, the unit's U).

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`).
    h : float
        Time step [s].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    strain : float
        Strain energy [J].
    """
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
    """Advance the modes over h with the ram force and the ring forces (``rings`` F) held.

    :func:`anvilwave.anvil_rom.unit.modal_unit_advance` with the pile load split over the rings
    and, with J > 1 annuli, the ram load over the annuli (with one port ``force_ram``), then the
    interface sums of the new state: ``interface`` (u_top, v_top, u_bottom, v_bottom; the
    bottom as the whole ring's mean), ``rings`` ring and face; then the ram face's annuli
    (:func:`ram_face_advance`) and the tube head (:func:`head_push`).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: the one-port unit's parameters (:mod:`anvilwave.anvil_rom.unit`; ``P[7]`` gravity
        [m/s^2], ``P[8]`` the step h [s]).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8) (:mod:`anvilwave.anvil_rom.unit`).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2]; advanced to t_n+1 and t_n
        (written).
    force_ram : float
        Ram contact force held over the step [N] (one port).
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    interface : numpy.ndarray
        Receives the modal (u_top, v_top, u_bottom, v_bottom) of the new state, shape (4,)
        [m, m/s] (written).
    """
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
    """(kinetic, potential) [J] of the ring unit in the shadow form of the two-step scheme.

    The conserved form (:func:`anvilwave.anvil_rom.unit.modal_unit_energy_at`): the modes'
    kinetic and strain energies and gravity potential, and the complementary energy of the
    contacts and the residual flexibility, F_n^T A F_n-1 / 2 with F_n the elastic forces
    (``rings`` E, from :func:`ring_elastic_forces`) and F_n-1 those one step earlier (neighbours
    moved back by h v, modes at q_n-1); with the ram face in annuli also what they add to the
    ram unit's energy (:func:`ram_face_energy`).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: the one-port unit's parameters (:mod:`anvilwave.anvil_rom.unit`; ``P[7]`` gravity
        [m/s^2], ``P[8]`` the step h [s]).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8) (:mod:`anvilwave.anvil_rom.unit`).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its scratch (``scratch`` beyond the active
        sets, ``face_before``, ``ring_before``) is written, nothing else.
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    potential : float
        Potential energy [J].
    """
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
    face, previous = rings.face_before, rings.ring_before  # every work array is the unit's
    for a in range(J):
        face[0, a] = 0.0
    for k in range(K):
        previous[0, k] = 0.0
    for j in range(n):
        q, qp = S[j], S[n + j]
        rate = (q - qp) * inverse_step
        kinetic += 0.5 * C[j, 3] * rate * rate
        potential += 0.5 * C[j, 7] ** 2 * q * qp - P[7] * C[j, 6] * 0.5 * (q + qp)
        for a in range(J):
            face[0, a] += RQ[j, a] * qp
        for k in range(K):
            previous[0, k] += RP[j, k] * qp
    g = scratch[:, 2]
    ring_overlaps(g, u_ram - h * v_ram, 0.0, u_pile - h * v_pile, 0.0, face, previous,
                  rings.dashpot_ratios, True, rings.head_shift[1], offsets[1], offsets[2])
    active = scratch[:, 3]
    F0 = scratch[:, 4]
    for i in range(m):  # from the forces' active set at t_n, which stays as it is
        active[i] = scratch[i, 0]
    contact_lcp(A, g, F0, active, scratch[:, 5:])
    for i in range(m):
        for j in range(m):
            potential += 0.5 * E[i] * A[i, j] * F0[j]
    return kinetic, potential


def ring_matrix(contact_ram, contact_rings: np.ndarray, residual: np.ndarray
                ) -> np.ndarray:
    """A = C + D R D (module docstring) of the contacts and the residual flexibility.

    C is block-diagonal, the ram block, then diag(1 / k) of the rings.

    Parameters
    ----------
    contact_ram : float or numpy.ndarray
        The ram contact's spring [N/m], or, for a ram face in J annuli, the ram's residual
        flexibility between them, shape (J, J) [m/N] (the contacts' ram side).
    contact_rings : numpy.ndarray
        The ring contact stiffnesses, shape (K,) [N/m].
    residual : numpy.ndarray
        R, the residual flexibility between the ram face's annuli and the rings, shape
        (J + K, J + K) [m/N].

    Returns
    -------
    numpy.ndarray
        A, shape (J + K, J + K) [m/N].
    """
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
    """Ring forces [N] and the rigid displacement [m] of an anvil at rest on a flat pile head.

    The pile head is fixed. The rings in contact satisfy F_k / k_k + sum_l G_kl F_l = u0,
    with G_kl = sum_j p_kj p_lj / w_j^2 + R_kl the rings' flexible static response and u0 the
    rigid translation (the same at every ring), and sum F = weight; a ring whose force would
    be tensile is open (under its own weight a wide anvil dishes: the outer ring can lift),
    with u0 - (G F)_k <= 0 there. Solved by active sets from all rings in contact.

    Parameters
    ----------
    omega : numpy.ndarray
        Circular frequencies of the anvil's modes, shape (n,) [rad/s] (0: rigid).
    participation_rings : numpy.ndarray
        The rings' modal participations, shape (K, n) [kg^-1/2], the rigid mode first.
    ring_stiffness : numpy.ndarray
        The rings' contact springs k_k, shape (K,) [N/m].
    residual_rings : numpy.ndarray
        The residual flexibility between the rings, shape (K, K) [m/N].
    weight : float
        The anvil's weight [N].

    Returns
    -------
    forces : numpy.ndarray
        The ring forces, shape (K,) [N].
    u0 : float
        The rigid displacement [m].

    Raises
    ------
    RuntimeError
        If the active set does not settle within 4 K changes.
    """
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
    """(u_top, u_bottom) [m] with the static correction at the forces ``rings`` F.

    The ram face's and the rings' area-weighted means (the whole face's and the whole ring's
    displacements), from their modal parts (``rings`` face and ring) and the residual
    flexibility ``rings`` R (``residual``).

    Parameters
    ----------
    rings : RingState
        The ring unit's arrays (:class:`RingState`).

    Returns
    -------
    u_top : float
        Displacement of the top face [m].
    u_bottom : float
        Displacement of the bottom face (the ring) [m].
    """
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
    """(F_ram, F_pile, u_top, u_bottom) [N, N, m, m] of the ring unit for the neighbour states.

    From its state alone (the anvil FMU's feedthrough): the faces' modal sums, the rings'
    contact problem (forces left in ``rings`` F; F_pile their sum) and the faces.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: the one-port unit's parameters (:mod:`anvilwave.anvil_rom.unit`; ``P[7]`` gravity
        [m/s^2], ``P[8]`` the step h [s]).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8) (:mod:`anvilwave.anvil_rom.unit`).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    rings : RingState
        The ring unit's arrays (:class:`RingState`); its changing fields are written.
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].

    Returns
    -------
    force_ram : float
        Ram contact force [N].
    force_pile : float
        Pile contact force, the sum of the ring forces [N].
    u_top : float
        Displacement of the top face [m].
    u_bottom : float
        Displacement of the bottom face [m].
    """
    P, C, S = parameters, coefficients, state
    ring_interface(C, S, rings, P[8])
    force_ram, force_pile = ring_contact(rings, u_ram, v_ram, u_pile, v_pile)
    u_top, u_bottom = ring_faces(rings)
    return force_ram, force_pile, u_top, u_bottom
