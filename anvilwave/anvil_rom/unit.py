"""The anvil as a system component: modal ROM (or rigid mass) plus its two contacts.

This is what the Anvil / AnvilLumped FMUs and the in-process engine both run. Inputs are the
ram toe and pile head states, outputs the two contact forces (feedthrough, evaluated at the
same instant) and the interface displacements; the step advances the modes exactly with the
forces held.

Kernel data layout (float64 arrays, shared by every anvil-like unit so the engine can call any
of them through the same signature):

- ``P`` parameters: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h]
- ``C`` (n, 8) per-mode table: step coefficients a, b, c, m_e for the step h
  (:func:`anvilwave.anvil_rom.rom.modal_transition`), then p_ram, p_pile, p_grav, omega
- ``S`` state: [q (n) at t_n, q (n) at t_n-1]

The kernels take them as ``parameters``, ``coefficients`` and ``state`` and call them P, C, S
in their formulas.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from anvilwave.anvil_rom.rings import (
    RamFace,
    RingState,
    ring_faces,
    ring_interface,
    ring_matrix,
    ring_static_rest,
    ring_unit_advance,
    ring_unit_outputs,
)
from anvilwave.anvil_rom.rom import ModalAnvil, anvil_contact_forces, modal_interface, modal_step
from anvilwave.inputs import InputError

GRAVITY = 9.81  # [m/s^2]


@dataclass(frozen=True)
class ContactParameters:
    """Penalty contacts of the anvil.

    Parameters
    ----------
    ram_stiffness : float
        Compression-only contact spring between the ram toe and the top face [N/m].
    pile_stiffness : float
        Compression-only contact spring between the bottom face and the pile head [N/m].
    ram_damping : float, default 0.0
        Dashpot of the ram contact [N s/m].
    pile_damping : float, default 0.0
        Dashpot of the pile contact [N s/m].

    Raises
    ------
    InputError
        If a stiffness is not positive and finite or a damping not >= 0 and finite.
    """

    ram_stiffness: float
    pile_stiffness: float
    ram_damping: float = 0.0
    pile_damping: float = 0.0

    def __post_init__(self):
        for name in ("ram_stiffness", "pile_stiffness"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0.0):
                raise InputError("anvil contact", name, f"must be positive [N/m], got {value!r}")
        for name in ("ram_damping", "pile_damping"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0.0):
                raise InputError("anvil contact", name, f"must be >= 0 [N s/m], got {value!r}")


@dataclass
class AnvilUnit:
    """Modal (or rigid) anvil with its ram and pile contacts.

    The kernel arrays ``P``, ``C``, ``S`` (module docstring) and, with the pile port in
    rings, ``rings`` (:class:`anvilwave.anvil_rom.rings.RingState`) are built on creation.

    Parameters
    ----------
    anvil : ModalAnvil
        The ROM (``ModalAnvil.from_modal_data``) or the rigid mass (``ModalAnvil.rigid``).
    contact : ContactParameters
        Contact springs and dashpots.
    gravity : float, default GRAVITY
        Gravitational acceleration [m/s^2] (0 to switch gravity off).
    head : tuple or None, default None
        A tube head under the rings (:func:`anvilwave.pile.head_kernel.head_correction`):
        (D, springs), D (L, K, K) [m/N] what the tube adds to the 1D head at each lag (at lag 0
        without the contact springs), springs (K,) [N/m] the rings' contacts on the tube;
        None: the 1D head.
    ram_face : RamFace or None, default None
        The ram's face in annuli (:class:`anvilwave.anvil_rom.rings.RamFace`) when the anvil's
        ram port is in annuli; None: one port.

    Raises
    ------
    ValueError
        If the ram port is in annuli without a ``ram_face`` (or with one of another number of
        annuli), or if ``head`` does not match the rings.
    """

    anvil: ModalAnvil
    contact: ContactParameters
    gravity: float = GRAVITY
    head: tuple | None = None
    ram_face: RamFace | None = None

    def __post_init__(self):
        r = self.anvil.residual_flexibility
        c = self.contact
        self.P = np.array([c.ram_stiffness, c.ram_damping, c.pile_stiffness, c.pile_damping,
                           r[0, 0], r[0, 1], r[1, 1], self.gravity, 1.0])
        n = self.anvil.n_modes
        self.C = np.zeros((n, 8))
        self.C[:, 4] = self.anvil.participation_ram
        self.C[:, 5] = self.anvil.participation_pile
        self.C[:, 6] = self.anvil.participation_gravity
        self.C[:, 7] = self.anvil.omega
        self._h = None
        self.S = np.zeros(2 * n)
        self.rings = None
        if self.anvil.n_rings > 1:
            self.rings = self._ring_arrays()
        self.set_step(1e-5)

    def _ring_arrays(self) -> RingState:
        """The ring kernels' data (:class:`anvilwave.anvil_rom.rings.RingState`): the pile contact's
        spring and dashpot shared by ring area (on a tube head: its springs, its D[0] in A); the
        ram contact one port, or with the ram face in annuli (:attr:`ram_face`) the ram's residual
        flexibility between them and its dashpot shared by annulus area."""
        a, c = self.anvil, self.contact
        shares = a.ring_areas / a.ring_areas.sum()
        K = shares.size
        J = a.n_annuli
        springs = c.pile_stiffness * shares
        D = np.zeros((1, K, K))
        if self.head is not None:
            D, springs = (np.ascontiguousarray(x, dtype=float) for x in self.head)
            if D.ndim != 3 or D.shape[1:] != (K, K) or springs.shape != (K,):
                raise ValueError(f"the tube head needs ({K}, {K}) lags and {K} springs for "
                                 f"{K} rings, got {D.shape} and {springs.shape}")
        self.ring_springs = springs
        face = self.ram_face
        if J > 1 and face is None:
            raise ValueError(f"the anvil's ram port is in {J} annuli: it needs the ram face "
                             "(set_ram_face)")
        if face is not None and face.n_annuli != J:
            raise ValueError(f"the ram face has {face.n_annuli} annuli, the anvil's ram port "
                             f"{J}")
        if J == 1:
            A = ring_matrix(c.ram_stiffness, springs, a.residual_rings)
            T_ram = np.array([c.ram_damping / c.ram_stiffness])
            RQ = a.participation_ram[:, None]
            Wr = np.ones(1)
            Cr, Pr, pr = np.zeros((0, 5)), np.zeros((0, 1)), np.zeros(0)
        else:
            A = ring_matrix(face.residual, springs, a.residual_rings)
            Wr = a.ram_annulus_areas / a.ram_annulus_areas.sum()
            T_ram = c.ram_damping * Wr * np.diag(face.residual)  # c_a / k_a, k_a = 1 / R_aa
            RQ = a.participation_ram_annuli.T
            Cr, Pr, pr = face.coefficients(self._h or 1e-5), face.participation.T, face.toe
        A[J:, J:] += 0.5 * (D[0] + D[0].T)
        T = np.r_[T_ram, c.pile_damping * shares / springs]
        m = J + K
        scratch = np.zeros((m, m + 6))
        return RingState(
            participation=np.ascontiguousarray(a.participation_rings.T), flexibility=A,
            dashpot_ratios=T, ring_shares=shares, forces=np.zeros(m), elastic_forces=np.zeros(m),
            ring_modal=np.zeros((2, K)), scratch=scratch, residual=a.residual_rings,
            head_kernel=D, head_history=np.zeros((D.shape[0], K)), head_shift=np.zeros((2, K)),
            head_rest=np.zeros(K), head_count=np.zeros(2),
            face_participation=np.ascontiguousarray(RQ), face_modal=np.zeros((2, J)),
            annulus_shares=Wr, ram_coefficients=Cr, ram_participation=np.ascontiguousarray(Pr),
            ram_toe_participation=pr, ram_state=np.zeros((4, pr.size)),
            ram_offsets=np.zeros((3, J)), face_before=np.zeros((2, J)),
            ring_before=np.zeros((2, K)))

    def set_head(self, head: tuple) -> tuple[float, float]:
        """Put the rings on a tube head and rest on it afresh.

        Parameters
        ----------
        head : tuple
            (D, springs) as the field ``head``: D (L, K, K) [m/N], springs (K,) [N/m].

        Returns
        -------
        u_top : float
            Top face at rest [m] (:meth:`rest_on_pile`).
        weight : float
            Pile contact force at rest [N].

        Raises
        ------
        ValueError
            If the pile port is not in rings, or ``head`` does not match the rings.
        """
        if self.rings is None:
            raise ValueError("a tube head needs the pile port in rings")
        self.head = head
        self.rings = self._ring_arrays()
        return self.rest_on_pile(0.0)

    def set_ram_face(self, face: RamFace) -> tuple[float, float]:
        """Put the ram face in annuli (the ram's, as the anvil's ram port) and rest afresh.

        Parameters
        ----------
        face : RamFace
            The ram's toe in as many annuli as the anvil's ram port.

        Returns
        -------
        u_top : float
            Top face at rest [m] (:meth:`rest_on_pile`).
        weight : float
            Pile contact force at rest [N].

        Raises
        ------
        ValueError
            If the pile port is not in rings, or ``face`` has another number of annuli.
        """
        if self.rings is None:
            raise ValueError("a ram face in annuli needs the pile port in rings")
        self.ram_face = face
        self.rings = self._ring_arrays()
        return self.rest_on_pile(0.0)

    def restart_head(self, rings: RingState | None = None) -> None:
        """Start the tube head's history afresh from the present ring forces (a blow's start).

        Its changes are measured from them; the ram face's annuli start at rest (the ram's
        flexible modes are at rest at impact).

        Parameters
        ----------
        rings : RingState or None, default None
            The ring arrays to restart (written); None: the unit's own ``rings``.
        """
        rings = self.rings if rings is None else rings
        F, D, shift, rest = rings.forces, rings.head_kernel, rings.head_shift, rings.head_rest
        count = rings.head_count
        J = rings.face_modal.shape[1]
        rest[:] = F[J:]
        count[:] = 0.0
        shift[0] = -(D[0] @ rest)
        shift[1] = shift[0]
        rings.ram_state[:] = 0.0
        rings.ram_offsets[:] = 0.0

    @property
    def n_modes(self) -> int:
        """Number of modes of the anvil, the rigid-body mode included.

        Returns
        -------
        int
            n [-].
        """
        return self.anvil.n_modes

    def set_step(self, h: float) -> None:
        """Prepare the step coefficients for a step ``h`` [s].

        The two-step state is rescaled so that the half-step velocity is kept across a change
        of step size.

        Parameters
        ----------
        h : float
            Time step [s].
        """
        if h != self._h:
            n = self.n_modes
            if self._h is not None:
                q, q_prev = self.S[:n], self.S[n:]
                q_prev[:] = q - (q - q_prev) * (h / self._h)
            self.C[:, :4] = self.anvil.transition(h)
            self.P[8] = h
            self._h = h
            if self.ram_face is not None and self.rings is not None:
                self.rings.ram_coefficients[:] = self.ram_face.coefficients(h)

    def rest_on_pile(self, pile_head_displacement: float = 0.0) -> tuple[float, float]:
        """Static equilibrium on the pile under gravity (ram not yet touching).

        Sets the state. The ram toe touches the top face when its displacement equals the
        returned u_top.

        Parameters
        ----------
        pile_head_displacement : float, default 0.0
            Displacement of the pile head the anvil rests on [m].

        Returns
        -------
        u_top : float
            Top face at rest [m] (with rings: the face's highest annulus).
        force_pile : float
            Pile contact force at rest, the anvil's weight [N].
        """
        force_pile = self.anvil.total_mass * self.gravity
        if self.rings is not None:
            return self._rest_on_rings(pile_head_displacement, force_pile)
        q = self.anvil.static_modal_coordinates(0.0, force_pile)
        p_ram, p_pile = self.anvil.participation_ram, self.anvil.participation_pile
        r = self.anvil.residual_flexibility
        u_bottom_target = pile_head_displacement + force_pile / self.contact.pile_stiffness
        u_bottom_flex = p_pile @ q - r[1, 1] * force_pile
        q[0] = (u_bottom_target - u_bottom_flex) / p_pile[0]
        n = self.n_modes
        self.S[:n] = q
        self.S[n:] = q
        u_top = float(p_ram @ q - r[0, 1] * force_pile)
        return u_top, force_pile

    def _rest_on_rings(self, pile_head_displacement: float, weight: float
                       ) -> tuple[float, float]:
        """:meth:`rest_on_pile` with the pile port split into rings (the rings' forces, and
        which of them carry the weight, from :func:`anvilwave.anvil_rom.rings.ring_static_rest`)."""
        a = self.anvil
        rings = self.rings
        RP, F, scratch, RQ = (rings.participation, rings.forces, rings.scratch,
                              rings.face_participation)
        J = RQ.shape[1]
        forces, u0 = ring_static_rest(a.omega, a.participation_rings, self.ring_springs,
                                      a.residual_rings[J:, J:], weight)
        q = np.zeros(a.n_modes)
        flexible = a.omega > 0.0
        q[flexible] = -(forces @ a.participation_rings[:, flexible]) / a.omega[flexible] ** 2
        q[0] = (u0 + pile_head_displacement) / RP[0, 0]
        n = self.n_modes
        self.S[:n] = q
        self.S[n:] = q
        F[:J] = 0.0
        F[J:] = forces
        scratch[:, :2] = np.r_[np.zeros(J), forces > 0.0][:, None]  # the active sets to start
        self.restart_head()
        # the ram touches the face's highest annulus first (one port: the face's mean)
        u_top = float(np.min(q @ RQ - a.residual_rings[:J, J:] @ forces))
        return u_top, weight

    def forces(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """Contact forces (F_ram, F_pile) [N] for the given neighbour states (feedthrough).

        With rings F_pile is the sum of the ring forces, which are kept for :meth:`step`.

        Parameters
        ----------
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
        f_ram : float
            Ram contact force [N].
        f_pile : float
            Pile contact force [N].
        """
        if self.rings is not None:
            f_ram, f_pile, _, _ = ring_unit_outputs(self.P, self.C, self.S, self.rings, u_ram,
                                                    v_ram, u_pile, v_pile)
            return f_ram, f_pile
        return modal_unit_forces(self.P, self.C, self.S, u_ram, v_ram, u_pile, v_pile)

    def step(self, force_ram: float, force_pile: float, h: float) -> None:
        """Advance the modes over ``h`` [s] with the contact forces held.

        With rings the pile force is split as the ring forces of the last :meth:`forces` (by
        area if they were all zero).

        Parameters
        ----------
        force_ram : float
            Ram contact force held over the step [N] (compression positive).
        force_pile : float
            Pile contact force held over the step [N] (compression positive).
        h : float
            Time step [s].

        Raises
        ------
        ValueError
            With the ram face in annuli (it runs in the in-process engine only).
        """
        self.set_step(h)
        if self.rings is not None:
            self._ring_forces(force_ram, force_pile)
            ring_unit_advance(self.P, self.C, self.S, force_ram, self.rings, np.zeros(4))
            return
        modal_unit_step(self.P, self.C, self.S, force_ram, force_pile)

    def outputs(self, force_ram: float, force_pile: float) -> tuple[float, float, float, float]:
        """(u_top, v_top, u_bottom, v_bottom) [m, m/s], static correction included.

        With rings: u_bottom and v_bottom the rings' area-weighted means, the ring forces split
        as in :meth:`step`.

        Parameters
        ----------
        force_ram : float
            Ram contact force [N].
        force_pile : float
            Pile contact force [N].

        Returns
        -------
        u_top : float
            Top face displacement [m].
        v_top : float
            Top face velocity [m/s].
        u_bottom : float
            Bottom face displacement [m].
        v_bottom : float
            Bottom face velocity [m/s].

        Raises
        ------
        ValueError
            With the ram face in annuli (it runs in the in-process engine only).
        """
        if self.rings is not None:
            return self._ring_outputs(force_ram, force_pile)
        return modal_unit_outputs(self.P, self.C, self.S, force_ram, force_pile)

    def _ring_forces(self, force_ram: float, force_pile: float) -> None:
        """The ring forces for a held pile force: those of the last contact problem scaled
        to ``force_pile``, or split by area when they were all zero; F_ram = ``force_ram``."""
        F, shares = self.rings.forces, self.rings.ring_shares
        if self.rings.face_modal.shape[1] > 1:
            raise ValueError("a ram face in annuli runs in the in-process engine only")
        total = F[1:].sum()
        F[1:] = F[1:] * (force_pile / total) if total > 0.0 else force_pile * shares
        F[0] = force_ram

    def _ring_outputs(self, force_ram: float, force_pile: float):
        self._ring_forces(force_ram, force_pile)
        ring = self.rings.ring_modal
        ring_interface(self.C, self.S, self.rings, self.P[8])
        n = self.n_modes
        _, vt, _, _ = modal_interface(self.C[:, 4], self.C[:, 5], self.S[:n], self.S[n:],
                                      self.P[8])
        u_top, u_bottom = ring_faces(self.rings)
        return u_top, vt, u_bottom, float(self.rings.ring_shares @ ring[1])

    def energy(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """(kinetic, potential) energy of the unit [J] for the given neighbour states.

        Potential = modal strain + gravity potential of the anvil + the energy stored in the
        two contact springs and in the residual flexibility.

        Parameters
        ----------
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

        Raises
        ------
        ValueError
            With the pile port in rings (the in-process engine books that energy).
        """
        if self.rings is not None:
            raise ValueError("the energy of a pile port in rings is booked by the in-process "
                             "engine (anvil_rom.rings.ring_unit_energy_at)")
        return modal_unit_energy(self.P, self.C, self.S, u_ram, v_ram, u_pile, v_pile)


@njit(cache=True)
def modal_unit_outputs(parameters, coefficients, state, force_ram, force_pile):
    """Interface (u_top, v_top, u_bottom, v_bottom) [m, m/s], static correction included.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    force_ram : float
        Ram contact force at t_n [N] (compression positive).
    force_pile : float
        Pile contact force at t_n [N] (compression positive).

    Returns
    -------
    ut : float
        Top face displacement [m].
    vt : float
        Top face velocity [m/s].
    ub : float
        Bottom face displacement [m].
    vb : float
        Bottom face velocity [m/s].
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    ut, vt, ub, vb = modal_interface(C[:, 4], C[:, 5], S[:n], S[n:], P[8])
    ut += P[4] * force_ram - P[5] * force_pile
    ub += P[5] * force_ram - P[6] * force_pile
    return ut, vt, ub, vb


@njit(cache=True)
def modal_unit_forces(parameters, coefficients, state, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, F_pile) [N] of the state for the neighbour states (feedthrough).

    :func:`anvilwave.anvil_rom.rom.anvil_contact_forces` of the modal interface sums.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
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
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    ut, vt, ub, vb = modal_interface(C[:, 4], C[:, 5], S[:n], S[n:], P[8])
    return anvil_contact_forces(u_ram, v_ram, u_pile, v_pile, ut, vt, ub, vb,
                                P[0], P[1], P[2], P[3], P[4], P[5], P[6])


@njit(cache=True)
def modal_unit_step(parameters, coefficients, state, force_ram, force_pile):
    """Advance the modes over h (``P[8]``) with the contact forces held, in place.

    :func:`anvilwave.anvil_rom.rom.modal_step` on the kernel arrays.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2]; advanced to t_n+1 and t_n
        (written).
    force_ram : float
        Ram contact force held over the step [N] (compression positive).
    force_pile : float
        Pile contact force held over the step [N] (compression positive).
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    modal_step(C, C[:, 4], C[:, 5], C[:, 6], S[:n], S[n:], force_ram, force_pile, P[7])


@njit(cache=True)
def modal_unit_energy(parameters, coefficients, state, u_ram, v_ram, u_pile, v_pile):
    """(kinetic, potential) [J] in the conserved (shadow) form of the two-step scheme.

    kinetic = sum m_e ((q_n - q_n-1) / h)^2 / 2; potential = sum w^2 q_n q_n-1 / 2
    - g p_grav (q_n + q_n-1) / 2 + the contact springs, k d_n d_n-1 / 2 each (with static
    correction: F_n^T (K_c^-1 + R) F_n-1 / 2, contacts and residual flexibility together). The
    contact dashpots, if any, are not counted.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
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
    interface = np.empty(4)
    modal_unit_interface(P, C, S, interface)
    f_ram, f_pile = modal_unit_contact(P, interface, u_ram, v_ram, u_pile, v_pile)
    return modal_unit_energy_at(P, C, S, interface, u_ram, v_ram, u_pile, v_pile, f_ram, f_pile)


@njit(cache=True, fastmath={"reassoc"})
def modal_unit_energy_at(parameters, coefficients, state, interface, u_ram, v_ram, u_pile, v_pile,
                         f_ram, f_pile):
    """:func:`modal_unit_energy` in one sweep over the modes, given interface and forces.

    Given the interface displacements of the state (``interface[0]``, ``interface[2]``,
    :func:`modal_unit_interface`) and the contact forces of these neighbour states.
    The sums may be added in any order (fastmath reassociation only: their last bits).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    interface : numpy.ndarray
        The modal (u_top, v_top, u_bottom, v_bottom) of the state, shape (4,) [m, m/s]
        (:func:`modal_unit_interface`).
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    f_ram : float
        Ram contact force at these neighbour states [N].
    f_pile : float
        Pile contact force at these neighbour states [N].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    potential : float
        Potential energy [J].
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    h = P[8]
    inverse_step = 1.0 / h
    kinetic = 0.0
    potential = 0.0
    ut_prev = 0.0
    ub_prev = 0.0
    vt = 0.0
    vb = 0.0
    for j in range(n):
        q, qp = S[j], S[n + j]
        rate = (q - qp) * inverse_step
        kinetic += 0.5 * C[j, 3] * rate * rate
        potential += 0.5 * C[j, 7] ** 2 * q * qp - P[7] * C[j, 6] * 0.5 * (q + qp)
        ut_prev += C[j, 4] * qp
        ub_prev += C[j, 5] * qp
        vt += C[j, 4] * rate
        vb += C[j, 5] * rate
    ut, ub = interface[0], interface[2]
    if P[4] == 0.0 and P[5] == 0.0 and P[6] == 0.0:
        # contact springs in the same shadow form, k d_n d_n-1 / 2 (d_n-1 = d_n - h d')
        potential += _shadow_contact(u_ram - ut, v_ram - vt, h, P[0])
        potential += _shadow_contact(ub - u_pile, vb - v_pile, h, P[2])
    else:
        # complementary energy of contacts + residual flexibility, F_n^T A F_n-1 / 2 with
        # A = [[1/k_ram + r00, -r01], [-r01, 1/k_pile + r11]] and F_n-1 the forces one step
        # earlier (neighbours moved back by h v, modes at q_n-1)
        fr0, fp0 = anvil_contact_forces(u_ram - h * v_ram, 0.0, u_pile - h * v_pile, 0.0,
                                        ut_prev, 0.0, ub_prev, 0.0, P[0], 0.0, P[2], 0.0,
                                        P[4], P[5], P[6])
        a11 = 1.0 / P[0] + P[4]
        a22 = 1.0 / P[2] + P[6]
        potential += 0.5 * (a11 * f_ram * fr0 - P[5] * (f_ram * fp0 + f_pile * fr0)
                            + a22 * f_pile * fp0)
    return kinetic, potential


# ------------------------------------------------------------------ the engine's form
# The step and the interface sums of the new state in one sweep over the modes, the contact
# forces from those sums: the in-process engine's loop and the FMU give the same numbers as
# modal_unit_step / modal_unit_forces / modal_unit_outputs, with one pass over the modes a step.
@njit(cache=True)
def modal_unit_interface(parameters, coefficients, state, interface):
    """Modal parts (u_top, v_top, u_bottom, v_bottom) [m, m/s] of the state into ``interface``.

    :func:`anvilwave.anvil_rom.rom.modal_interface` on the kernel arrays.

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2].
    interface : numpy.ndarray
        Receives the modal (u_top, v_top, u_bottom, v_bottom) of the state, shape (4,)
        [m, m/s] (written).
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    inverse_step = 1.0 / P[8]
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for j in range(n):
        qd = (S[j] - S[n + j]) * inverse_step
        ut += C[j, 4] * S[j]
        vt += C[j, 4] * qd
        ub += C[j, 5] * S[j]
        vb += C[j, 5] * qd
    interface[0] = ut
    interface[1] = vt
    interface[2] = ub
    interface[3] = vb


@njit(cache=True, inline='always')
def modal_unit_advance(parameters, coefficients, state, force_ram, force_pile, interface):
    """:func:`modal_unit_step`, then :func:`modal_unit_interface` of the new state.

    In one sweep over the modes (the same arithmetic).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    coefficients : numpy.ndarray
        ``C``: the per-mode table, shape (n, 8): a, b, c, m_e, p_ram, p_pile, p_grav, omega
        (module docstring).
    state : numpy.ndarray
        ``S``: q at t_n and at t_n-1, shape (2 n,) [m kg^1/2]; advanced to t_n+1 and t_n
        (written).
    force_ram : float
        Ram contact force held over the step [N] (compression positive).
    force_pile : float
        Pile contact force held over the step [N] (compression positive).
    interface : numpy.ndarray
        Receives the modal (u_top, v_top, u_bottom, v_bottom) of the new state, shape (4,)
        [m, m/s] (written).
    """
    P, C, S = parameters, coefficients, state
    n = C.shape[0]
    gravity = P[7]
    inverse_step = 1.0 / P[8]
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for j in range(n):
        p_ram = C[j, 4]
        p_pile = C[j, 5]
        f = p_ram * force_ram - p_pile * force_pile + C[j, 6] * gravity
        q = S[j]
        q_new = C[j, 0] * q + C[j, 1] * S[n + j] + C[j, 2] * f
        qd = (q_new - q) * inverse_step
        S[n + j] = q
        S[j] = q_new
        ut += p_ram * q_new
        vt += p_ram * qd
        ub += p_pile * q_new
        vb += p_pile * qd
    interface[0] = ut
    interface[1] = vt
    interface[2] = ub
    interface[3] = vb


@njit(cache=True, inline='always')
def modal_unit_dashpot_power(parameters, interface, u_ram, v_ram, u_pile, v_pile, f_ram, f_pile):
    """(F_e,ram, F_e,pile, power): elastic contact forces [N] and dashpot power [W].

    The contact forces without the dashpots (the elastic parts, whose complementary energy the
    contacts store) and the power the dashpots dissipate at the contact forces ``f_ram``,
    ``f_pile`` of :func:`modal_unit_contact`.

    With the dashpots folded into an equivalent overlap (:func:`anvilwave.anvil_rom.rom.
    anvil_contact_forces`) the force is F = A^-1 (d + T d') with T = diag(c / k): its elastic
    part A^-1 d stores d^T A^-1 d / 2, whose rate is F_e . d', so the rest, (F - F_e) . d',
    is dissipated (d' the relative velocities of the modal faces, rest to the contacts).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    interface : numpy.ndarray
        The modal (u_top, v_top, u_bottom, v_bottom) of the state, shape (4,) [m, m/s]
        (:func:`modal_unit_interface`).
    u_ram : float
        Ram toe displacement [m] (positive down).
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    f_ram : float
        Ram contact force at these neighbour states [N].
    f_pile : float
        Pile contact force at these neighbour states [N].

    Returns
    -------
    fe_ram : float
        Elastic part of the ram contact force [N].
    fe_pile : float
        Elastic part of the pile contact force [N].
    power : float
        Power dissipated by the contact dashpots [W].
    """
    P = parameters
    fe_ram, fe_pile = anvil_contact_forces(u_ram, 0.0, u_pile, 0.0, interface[0], 0.0,
                                           interface[2], 0.0, P[0], 0.0, P[2], 0.0, P[4], P[5],
                                           P[6])
    power = ((f_ram - fe_ram) * (v_ram - interface[1])
             + (f_pile - fe_pile) * (interface[3] - v_pile))
    return fe_ram, fe_pile, power


@njit(cache=True, inline='always')
def modal_unit_contact(parameters, interface, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, F_pile) [N] from the interface sums (:func:`modal_unit_forces`).

    Parameters
    ----------
    parameters : numpy.ndarray
        ``P``: [k_ram, c_ram, k_pile, c_pile, r00, r01, r11, gravity, h] [N/m, N s/m, N/m, N s/m,
        m/N, m/N, m/N, m/s^2, s] (module docstring).
    interface : numpy.ndarray
        The modal (u_top, v_top, u_bottom, v_bottom) of the state, shape (4,) [m, m/s]
        (:func:`modal_unit_interface`).
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
    f_ram : float
        Ram contact force [N].
    f_pile : float
        Pile contact force [N].
    """
    P = parameters
    return anvil_contact_forces(u_ram, v_ram, u_pile, v_pile, interface[0], interface[1],
                                interface[2], interface[3], P[0], P[1], P[2], P[3], P[4], P[5],
                                P[6])


@njit(cache=True)
def _shadow_contact(overlap, rate, h, stiffness):
    previous = overlap - h * rate
    if overlap <= 0.0 or previous <= 0.0:
        return 0.5 * stiffness * max(overlap, 0.0) ** 2
    return 0.5 * stiffness * overlap * previous
