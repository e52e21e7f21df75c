"""The driving stack as one anvil unit: the anvil and the anvil ring, two modal bodies.

Each body is a Mode Displacement Method ROM (:class:`anvilwave.anvil_rom.rom.ModalAnvil`, its
own free-free modes truncated at the system's fmax, its static correction); the unit keeps
the anvil's outward interface, ram in, pile out (DESIGN.md). Three compression-only contacts,
ram-anvil (top of the anvil), the seat anvil-ring (the anvil's bottom port on the ring's top
port) and ring-pile (the ring's bottom port), and Coulomb friction at the seat along the
radius.

Displacements of the ports (z down; the anvil a, the ring r; m the modal sums, R the residual
flexibility of each body between its axial ports 0 (top), 1 (bottom) and its radial ports 2
(top), 3 (bottom), the radial participations of the modal file)::

    u_a,top = m + Ra00 F_r - Ra01 F_s - Ra03 T       u_a,bot = m + Ra01 F_r - Ra11 F_s - Ra13 T
    u_r,top = m + Rr00 F_s - Rr01 F_p + Rr02 T       u_r,bot = m + Rr01 F_s - Rr11 F_p + Rr12 T

with F_r, F_s, F_p the three normal forces (compression positive) and T the seat's friction
force (the anvil pushed by -T along the radius, the ring by +T). The overlaps d = (u_ram -
u_a,top, u_a,bot - u_r,top, u_r,bot - u_pile) and F_i = k_i d_i (+ dashpot) make the normal
forces a 3 x 3 linear complementarity problem A F = g + e T, F >= 0, with

    A = diag(1 / k) + [[Ra00, -Ra01, 0], [-Ra01, Ra11 + Rr00, -Rr01], [0, -Rr01, Rr11]]
    e = [Ra03, -(Ra13 + Rr02), Rr12]

solved by :func:`anvilwave.anvil_rom.rings.contact_lcp` (the rings' pivoting) with the
dashpots folded into an equivalent overlap d + (c / k) d', as the anvil unit does. The seat's
relative radial displacement is w = w_modal + e . F - (Ra33 + Rr22) T: the stick spring k_t
of :func:`anvilwave.anvil_rom.contact.coulomb_friction` in series with the two bodies'
radial residual flexibility is the pair's effective spring k_eff = 1 / (1 / k_t + Ra33 +
Rr22), driven by w0 = w_modal + e . F. Each step: the normal forces at t_n with the friction
force of the step before (the e T coupling, the Poisson part of the static correction, lags
one step), then T_n by return mapping on the increment of w0 under the cone mu F_s,n, then
both bodies' modes advanced exactly with the four forces held.

Kernel data (:class:`StackState`): ``parameters`` [k_ram, c_ram, k_seat, c_seat, k_pile, c_pile,
mu, k_eff, gravity, h]; per body a table (n, 9): a, b, c, m_e (the step coefficients of
:func:`anvilwave.anvil_rom.rom.modal_transition`), p_top, p_bottom, p_grav, omega, p_radial
(at the seat) and a state [q (n) at t_n, q (n) at t_n-1].
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from anvilwave.anvil_rom.contact import coulomb_friction
from anvilwave.anvil_rom.fem.elasticity import interface_vectors
from anvilwave.anvil_rom.fem.geometry import AnvilSpec, Interfaces
from anvilwave.anvil_rom.fem.modalfile import ModalData
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes, modal_data_from_modes
from anvilwave.anvil_rom.rings import contact_lcp
from anvilwave.anvil_rom.rom import ModalAnvil, residual_flexibility
from anvilwave.anvil_rom.unit import GRAVITY, AnvilUnit, ContactParameters
from anvilwave.inputs import InputError


class StackState(NamedTuple):
    """The stack kernels' arrays (module docstring).

    Parameters
    ----------
    parameters : numpy.ndarray
        [k_ram, c_ram, k_seat, c_seat, k_pile, c_pile, mu, k_eff, gravity, h] [N/m, N s/m,
        N/m, N s/m, N/m, N s/m, -, N/m, m/s^2, s].
    anvil_coefficients : numpy.ndarray
        The anvil's table, shape (n_a, 9): a, b, c, m_e, p_top, p_bottom, p_grav, omega,
        p_radial at the seat.
    ring_coefficients : numpy.ndarray
        The ring's table, shape (n_r, 9), the same columns (p_top: the seat).
    anvil_state : numpy.ndarray
        q of the anvil at t_n and t_n-1, shape (2 n_a,) [m kg^1/2].
    ring_state : numpy.ndarray
        q of the ring at t_n and t_n-1, shape (2 n_r,) [m kg^1/2].
    flexibility : numpy.ndarray
        A of the normal contacts, shape (3, 3) [m/N].
    coupling : numpy.ndarray
        e, the friction force's share of the overlaps, shape (3,) [m/N].
    forces : numpy.ndarray
        [F_ram, F_seat, F_pile, T] of the last evaluation [N].
    friction : numpy.ndarray
        [T (stick spring force) [N], w0 at the last update [m], dissipated energy [J],
        dashpot work [J], started (1.0 once w0 is set) [-], dashpot power at the last
        :func:`stack_forces` [W]] (a master may read the forces more than once a step).
    active : numpy.ndarray
        The normal contacts' active set (1.0: closed), shape (3,).
    work : numpy.ndarray
        Scratch, shape (3, 4).
    interface : numpy.ndarray
        Modal sums of the state, [u_a,top, v_a,top, u_a,bot, v_a,bot, w_a,rad, u_r,top,
        v_r,top, u_r,bot, v_r,bot, w_r,rad] [m, m/s].
    """

    parameters: np.ndarray
    anvil_coefficients: np.ndarray
    ring_coefficients: np.ndarray
    anvil_state: np.ndarray
    ring_state: np.ndarray
    flexibility: np.ndarray
    coupling: np.ndarray
    forces: np.ndarray
    friction: np.ndarray
    active: np.ndarray
    work: np.ndarray
    interface: np.ndarray


@dataclass(frozen=True)
class StackBody:
    """One modal body of the stack with its radial participation at the seat.

    Parameters
    ----------
    rom : ModalAnvil
        The body's ROM (two axial ports: top, bottom).
    participation_radial : numpy.ndarray
        Radial participation of the kept modes at the seat port, shape (n,) [kg^-1/2].
    residual : numpy.ndarray
        Residual flexibility between the ports (axial top, axial bottom, radial top, radial
        bottom), shape (4, 4) [m/N] (zeros without static correction).
    """

    rom: ModalAnvil
    participation_radial: np.ndarray
    residual: np.ndarray

    @classmethod
    def from_modal_data(cls, data: ModalData, seat: str, fmax: float,
                        static_correction: bool = True, source: str = "modal data"
                        ) -> StackBody:
        """The body from a modal file with the radial keys, truncated at ``fmax``.

        Parameters
        ----------
        data : ModalData
            Modes with the radial keys (``modal_data_from_modes(radial=True)``).
        seat : {"bottom", "top"}
            Which port is the seat: the anvil's bottom port or the ring's top port.
        fmax : float
            Highest frequency kept [Hz] (the system's).
        static_correction : bool, default True
            Add the residual flexibility of the truncated modes.
        source : str, default "modal data"
            Name of the input the errors refer to.

        Returns
        -------
        StackBody
            The body.

        Raises
        ------
        InputError
            If ``data`` has no radial keys or ``seat`` is neither port.
        """
        if data.radial_flexibility is None:
            raise InputError(source, "radial_flexibility", "a stack body needs the radial "
                                                           "participations at its ports")
        if seat not in ("top", "bottom"):
            raise InputError(source, "seat", f"must be 'top' or 'bottom', got {seat!r}")
        rom = ModalAnvil.from_modal_data(data, fmax=fmax, static_correction=static_correction,
                                         source=source)
        keep = np.asarray(data.frequencies) <= rom.fmax
        radial = np.vstack([data.participation_ram_radial, data.participation_pile_radial])
        radial = radial[:, keep]
        residual = np.zeros((4, 4))
        if static_correction:
            residual = residual_flexibility(data.radial_flexibility, rom.omega,
                                            rom.participation_ram, rom.participation_pile,
                                            *radial)
        return cls(rom, radial[1 if seat == "bottom" else 0], residual)


def stack_modal_data(spec: AnvilSpec, interfaces: Interfaces, fmax: float) -> ModalData:
    """Free-free modes of one stack body with its stack ports and their radial participations.

    :func:`anvilwave.anvil_rom.fem.pipeline.compute_anvil_modes` on ``spec`` with ``interfaces``,
    projected with the radial keys (``modal_data_from_modes(radial=True)``).

    Parameters
    ----------
    spec : AnvilSpec
        The body (anvil or ring outline).
    interfaces : Interfaces
        Its two ports: the top face r <= ``ram_contact_radius`` and the bottom ring
        ``pile_contact_radius`` +- ``pile_contact_width`` / 2 [m].
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    ModalData
        The modes with the radial keys.
    """
    spec = AnvilSpec(spec.name, spec.material, spec.outline, spec.mesh_file, interfaces,
                     spec.mesh_size, fmax, spec.damping_ratio, spec.source)
    modes = compute_anvil_modes(spec, fmax)
    _, _, a_top, a_bottom = interface_vectors(modes.model, interfaces)
    return modal_data_from_modes(spec, modes.model, modes.modes, modes.b_ram, modes.b_pile,
                                 (a_top, a_bottom), radial=True)


@dataclass
class StackUnit:
    """The anvil and the anvil ring as one unit between the ram and the pile.

    Without a ring it is the anvil unit (:class:`anvilwave.anvil_rom.unit.AnvilUnit`, the
    same kernels on the same arrays). With one, the kernels of this module (module
    docstring); the arrays are :attr:`state` (:class:`StackState`).

    Parameters
    ----------
    anvil : StackBody or ModalAnvil
        The anvil (a ModalAnvil: the single-body unit, no ring).
    contact : ContactParameters
        Ram and pile contact springs and dashpots (the pile's: on the ring with one).
    ring : StackBody or None, default None
        The anvil ring; None: the anvil alone on the pile.
    seat_stiffness : float, default 0.0
        Normal penalty spring of the seat [N/m] (> 0 with a ring).
    seat_damping : float, default 0.0
        Dashpot of the seat [N s/m].
    seat_friction : float, default 0.0
        Coulomb coefficient of the seat [-].
    tangential_stiffness : float or None, default None
        Stick spring k_t of the seat [N/m]; None: the seat's normal spring (as the reference
        FEA's pairs).
    gravity : float, default GRAVITY
        Gravitational acceleration [m/s^2].

    Raises
    ------
    InputError
        If a ring is given without a positive seat stiffness, or a coefficient is negative.
    """

    anvil: StackBody | ModalAnvil
    contact: ContactParameters
    ring: StackBody | None = None
    seat_stiffness: float = 0.0
    seat_damping: float = 0.0
    seat_friction: float = 0.0
    tangential_stiffness: float | None = None
    gravity: float = GRAVITY

    def __post_init__(self):
        self._h = None
        if self.ring is None:
            rom = self.anvil.rom if isinstance(self.anvil, StackBody) else self.anvil
            self.single = AnvilUnit(rom, self.contact, gravity=self.gravity)
            self.state = None
            return
        self.single = None
        for key in ("seat_stiffness",):
            value = getattr(self, key)
            if not (np.isfinite(value) and value > 0.0):
                raise InputError("stack", key, f"must be positive [N/m], got {value!r}")
        for key in ("seat_damping", "seat_friction"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value >= 0.0):
                raise InputError("stack", key, f"must be >= 0, got {value!r}")
        a, r, c = self.anvil, self.ring, self.contact
        Ra, Rr = a.residual, r.residual
        k = np.array([c.ram_stiffness, self.seat_stiffness, c.pile_stiffness])
        A = np.diag(1.0 / k) + np.array([[Ra[0, 0], -Ra[0, 1], 0.0],
                                         [-Ra[0, 1], Ra[1, 1] + Rr[0, 0], -Rr[0, 1]],
                                         [0.0, -Rr[0, 1], Rr[1, 1]]])
        e = np.array([Ra[0, 3], -(Ra[1, 3] + Rr[0, 2]), Rr[1, 2]])
        kt = self.seat_stiffness if self.tangential_stiffness is None \
            else self.tangential_stiffness
        k_eff = 1.0 / (1.0 / kt + Ra[3, 3] + Rr[2, 2])
        P = np.array([c.ram_stiffness, c.ram_damping, self.seat_stiffness, self.seat_damping,
                      c.pile_stiffness, c.pile_damping, self.seat_friction, k_eff,
                      self.gravity, 1.0])
        self.state = StackState(P, _table(a), _table(r), np.zeros(2 * a.rom.n_modes),
                                np.zeros(2 * r.rom.n_modes), A, e, np.zeros(4), np.zeros(6),
                                np.zeros(3), np.zeros((3, 4)), np.zeros(10))
        self.set_step(1e-5)

    def set_step(self, h: float) -> None:
        """Prepare the step coefficients for a step ``h`` [s] (the half-step rates kept).

        Parameters
        ----------
        h : float
            Time step [s].
        """
        if self.single is not None:
            self.single.set_step(h)
            return
        if h == self._h:
            return
        s = self.state
        for body, C, S in ((self.anvil, s.anvil_coefficients, s.anvil_state),
                           (self.ring, s.ring_coefficients, s.ring_state)):
            n = body.rom.n_modes
            if self._h is not None:
                S[n:] = S[:n] - (S[:n] - S[n:]) * (h / self._h)
            C[:, :4] = body.rom.transition(h)
        s.parameters[9] = h
        self._h = h

    @property
    def total_mass(self) -> float:
        """Mass of the stack [kg].

        Returns
        -------
        float
            Anvil plus ring [kg].
        """
        if self.single is not None:
            return self.single.anvil.total_mass
        return self.anvil.rom.total_mass + self.ring.rom.total_mass

    def rest_on_pile(self, pile_head_displacement: float = 0.0) -> tuple[float, float]:
        """Static equilibrium on the pile under gravity (ram not yet touching); sets the state.

        Frictionless rest (T = 0): the seat carries the anvil's weight, the pile the stack's.

        Parameters
        ----------
        pile_head_displacement : float, default 0.0
            Displacement of the pile head [m].

        Returns
        -------
        u_top : float
            The anvil's top face at rest [m] (the ram touches it there).
        force_pile : float
            Pile contact force at rest, the stack's weight [N].
        """
        if self.single is not None:
            return self.single.rest_on_pile(pile_head_displacement)
        s = self.state
        g = self.gravity
        w_a = self.anvil.rom.total_mass * g
        w = self.total_mass * g
        Ra, Rr = self.anvil.residual, self.ring.residual
        qa = self.anvil.rom.static_modal_coordinates(0.0, w_a)
        qr = _static_coordinates(self.ring.rom, w_a, w)
        pr, pa = self.ring.rom, self.anvil.rom
        # the ring's bottom port sits on the pile spring, the anvil's seat on the seat spring
        u_rb = pile_head_displacement + w / self.contact.pile_stiffness
        qr[0] = (u_rb - (pr.participation_pile[1:] @ qr[1:] + Rr[0, 1] * w_a - Rr[1, 1] * w)
                 ) / pr.participation_pile[0]
        u_rt = pr.participation_ram @ qr + Rr[0, 0] * w_a - Rr[0, 1] * w
        u_ab = u_rt + w_a / self.seat_stiffness
        qa[0] = (u_ab - (pa.participation_pile[1:] @ qa[1:] - Ra[1, 1] * w_a)
                 ) / pa.participation_pile[0]
        for q, S in ((qa, s.anvil_state), (qr, s.ring_state)):
            S[:q.size] = q
            S[q.size:] = q
        s.forces[:] = 0.0, w_a, w, 0.0
        s.friction[:] = 0.0
        s.active[:] = 0.0, 1.0, 1.0
        u_top = float(pa.participation_ram @ qa - Ra[0, 1] * w_a)
        return u_top, w

    def forces(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """Contact forces (F_ram, F_pile) [N] for the neighbour states (feedthrough).

        The seat's normal force and the friction force held are kept for :meth:`step`.

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
        if self.single is not None:
            return self.single.forces(u_ram, v_ram, u_pile, v_pile)
        return stack_forces(self.state, u_ram, v_ram, u_pile, v_pile)

    def step(self, force_ram: float, force_pile: float, h: float) -> None:
        """Advance over ``h`` (friction update, then the modes with the forces held).

        Parameters
        ----------
        force_ram : float
            Ram contact force held over the step [N] (from :meth:`forces`).
        force_pile : float
            Pile contact force held over the step [N] (from :meth:`forces`).
        h : float
            Time step [s].
        """
        if self.single is not None:
            self.single.step(force_ram, force_pile, h)
            return
        self.set_step(h)
        stack_step(self.state)

    @property
    def friction_energy(self) -> float:
        """Energy the seat friction has dissipated [J].

        Returns
        -------
        float
            The sum of :func:`anvilwave.anvil_rom.contact.coulomb_friction`'s dissipation [J].
        """
        return 0.0 if self.state is None else float(self.state.friction[2])

    @property
    def dashpot_work(self) -> float:
        """Energy the contact dashpots have dissipated [J] (with a ring).

        The power (F - F_elastic) . d' of each step's forces over its step, to t_n, and the
        present power over half a step (the trapezoid rule of the power, which the scheme's
        work pairing F_n (u_n+1 - u_n-1) / 2 needs; with it the Table 1 balance at 20 us
        goes from 0.55 % to 0.40 % of the blow, measured).

        Returns
        -------
        float
            The dissipated work [J] (0 without a ring: the anvil unit's own bookkeeping).
        """
        if self.state is None:
            return 0.0
        fr, h = self.state.friction, self.state.parameters[9]
        return float(fr[3] + 0.5 * h * fr[5])

    def energy(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """(kinetic, potential) energy of the stack [J] in the conserved (shadow) form.

        Per mode m_e ((q_n - q_n-1) / h)^2 / 2 + w^2 q_n q_n-1 / 2 - g p_grav (q_n + q_n-1) / 2,
        plus the complementary energy of the massless part (contact springs, residual
        flexibility, stick spring), X^T C X / 2 with X = [F_ram, F_seat, F_pile, T] and
        C = [[A, -e], [-e^T, 1 / k_eff]] at the present forces (dashpots left out).

        Parameters
        ----------
        u_ram : float
            Ram toe displacement [m].
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
        if self.single is not None:
            return self.single.energy(u_ram, v_ram, u_pile, v_pile)
        return stack_energy(self.state, u_ram, v_ram, u_pile, v_pile)


def _table(body: StackBody) -> np.ndarray:
    """The (n, 9) table of a body (step coefficients set by ``set_step``)."""
    rom = body.rom
    C = np.zeros((rom.n_modes, 9))
    C[:, 4] = rom.participation_ram
    C[:, 5] = rom.participation_pile
    C[:, 6] = rom.participation_gravity
    C[:, 7] = rom.omega
    C[:, 8] = body.participation_radial
    return C


def _static_coordinates(rom: ModalAnvil, force_top: float, force_bottom: float) -> np.ndarray:
    """Flexible coordinates of a body under its two port forces (the rigid one 0)."""
    return rom.static_modal_coordinates(force_top, force_bottom)


@njit(cache=True)
def stack_interface(state):
    """Modal sums of both bodies at t_n into ``state.interface`` (:class:`StackState`).

    Parameters
    ----------
    state : StackState
        The stack's arrays (``interface`` written).
    """
    h = state.parameters[9]
    for body in range(2):
        C = state.anvil_coefficients if body == 0 else state.ring_coefficients
        S = state.anvil_state if body == 0 else state.ring_state
        n = C.shape[0]
        ut = 0.0
        vt = 0.0
        ub = 0.0
        vb = 0.0
        w = 0.0
        for j in range(n):
            q = S[j]
            qd = (q - S[n + j]) / h
            ut += C[j, 4] * q
            vt += C[j, 4] * qd
            ub += C[j, 5] * q
            vb += C[j, 5] * qd
            w += C[j, 8] * q
        o = 5 * body
        state.interface[o] = ut
        state.interface[o + 1] = vt
        state.interface[o + 2] = ub
        state.interface[o + 3] = vb
        state.interface[o + 4] = w


@njit(cache=True)
def _normal_forces(state, u_ram, v_ram, u_pile, v_pile, with_dashpots, out):
    """The 3 x 3 complementarity problem of the normal forces into ``out`` (module
    docstring), the friction force held; ``with_dashpots`` False: the elastic parts."""
    P, x = state.parameters, state.interface
    T = state.friction[0]
    e = state.coupling
    d = np.empty(3)
    rate = np.empty(3)
    d[0] = u_ram - x[0]
    rate[0] = v_ram - x[1]
    d[1] = x[2] - x[5]
    rate[1] = x[3] - x[6]
    d[2] = x[7] - u_pile
    rate[2] = x[8] - v_pile
    g = np.empty(3)
    for i in range(3):
        g[i] = d[i] + e[i] * T
        if with_dashpots:
            g[i] += P[2 * i + 1] / P[2 * i] * rate[i]
    contact_lcp(state.flexibility, g, out, state.active, state.work)
    return rate


@njit(cache=True)
def stack_forces(state, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, F_pile) [N] at t_n for the neighbour states (feedthrough).

    The three normal forces are kept in ``state.forces`` for :func:`stack_step`.

    Parameters
    ----------
    state : StackState
        The stack's arrays (``interface``, ``forces``, ``active`` written).
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
    stack_interface(state)
    F = np.empty(3)
    rate = _normal_forces(state, u_ram, v_ram, u_pile, v_pile, True, F)
    state.forces[:3] = F
    if state.parameters[1] > 0.0 or state.parameters[3] > 0.0 or state.parameters[5] > 0.0:
        active = state.active.copy()
        Fe = np.empty(3)
        _normal_forces(state, u_ram, v_ram, u_pile, v_pile, False, Fe)
        state.active[:] = active
        power = 0.0
        for i in range(3):
            power += (F[i] - Fe[i]) * rate[i]
        state.friction[5] = power  # booked over the step by stack_step
    return F[0], F[2]


@njit(cache=True)
def stack_step(state):
    """Update the seat friction at t_n, then advance both bodies over h with the forces held.

    The friction force by return mapping (:func:`anvilwave.anvil_rom.contact.coulomb_friction`)
    on the increment of w0 = w_modal + e . F under the cone mu F_seat (module docstring),
    its dissipation added to ``state.friction[2]``; then every mode of each body by the exact
    step with its port forces (anvil: F_ram on top, -F_seat below, -T radially at the seat;
    ring: F_seat on top, -F_pile below, +T radially) and gravity held.

    Parameters
    ----------
    state : StackState
        The stack's arrays after :func:`stack_forces` at t_n (states and ``friction``
        written).
    """
    P, x, F, fr = state.parameters, state.interface, state.forces, state.friction
    e = state.coupling
    w0 = x[4] - x[9] + e[0] * F[0] + e[1] * F[1] + e[2] * F[2]
    if fr[4] == 0.0:
        fr[1] = w0
        fr[4] = 1.0
    T, dissipated = coulomb_friction(fr[0], w0 - fr[1], F[1], P[6], P[7])
    fr[0] = T
    fr[1] = w0
    fr[2] += dissipated
    fr[3] += fr[5] * P[9]
    F[3] = T
    gravity = P[8]
    for body in range(2):
        C = state.anvil_coefficients if body == 0 else state.ring_coefficients
        S = state.anvil_state if body == 0 else state.ring_state
        top = F[0] if body == 0 else F[1]
        bottom = F[1] if body == 0 else F[2]
        radial = -T if body == 0 else T
        n = C.shape[0]
        for j in range(n):
            f = C[j, 4] * top - C[j, 5] * bottom + C[j, 8] * radial + C[j, 6] * gravity
            q = S[j]
            S[j] = C[j, 0] * q + C[j, 1] * S[n + j] + C[j, 2] * f
            S[n + j] = q


@njit(cache=True)
def stack_energy(state, u_ram, v_ram, u_pile, v_pile):
    """(kinetic, potential) energy of the stack [J] (:meth:`StackUnit.energy`).

    Parameters
    ----------
    state : StackState
        The stack's arrays (``interface``, ``active`` written; the kept forces unchanged).
    u_ram : float
        Ram toe displacement [m].
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
    P = state.parameters
    h = P[9]
    kinetic = 0.0
    total = 0.0
    for body in range(2):
        C = state.anvil_coefficients if body == 0 else state.ring_coefficients
        S = state.anvil_state if body == 0 else state.ring_state
        n = C.shape[0]
        for j in range(n):
            q, qp = S[j], S[n + j]
            rate = (q - qp) / h
            kinetic += 0.5 * C[j, 3] * rate * rate
            total += 0.5 * C[j, 7] ** 2 * q * qp - P[8] * C[j, 6] * 0.5 * (q + qp)
    stack_interface(state)
    active = state.active.copy()
    F = np.empty(3)
    _normal_forces(state, u_ram, v_ram, u_pile, v_pile, False, F)
    state.active[:] = active
    A, e = state.flexibility, state.coupling
    T = state.friction[0]
    for i in range(3):
        for j in range(3):
            total += 0.5 * F[i] * A[i, j] * F[j]
        total -= F[i] * e[i] * T
    total += 0.5 * T * T / P[7]
    return kinetic, total
