"""The Mode Displacement Method anvil (modal ROM) and the rigid lumped-mass anvil.

Each retained mode j obeys (Ligthart & Orlando, eq. 8; DESIGN.md)::

    eta_j'' + 2 xi omega_j eta_j' + omega_j^2 eta_j
        = p_ram_j F_ram - p_pile_j F_pile + p_grav_j g

with p_ram = b_ram^T phi_j, p_pile = b_pile^T phi_j, p_grav = phi_j^T M e_z, and the interface
displacements are u_top = sum p_ram_j eta_j, u_bottom = sum p_pile_j eta_j.

Each mode is advanced by the two-step trigonometric recurrence (Gautschi 1961; Hochbruck &
Lubich 1999, filter sinc^2)::

    eta_{n+1} = a eta_n + b eta_{n-1} + c f_n,
    a = 2 exp(-xi w h) cos(w_d h),  b = -exp(-2 xi w h),  c = (1 - a - b) / w^2

which is EXACT for free (damped) vibration and for a constant force, at any step h: the ROM is
unconditionally stable and its frequencies and static response carry no time-step error. For
the rigid-body mode it is the central-difference scheme (c = h^2), and for every mode it is the
central-difference scheme of a mode with the exact stiffness and a slightly larger modal mass
m_e = w^2 h^2 / (2 - a) >= 1 (undamped). That matters for the coupling: the ram and the pile
are integrated with the symplectic (leapfrog) scheme, and the contact forces are evaluated at
t_n and held; a one-step "exact zero-order-hold" update, u_{n+1} = u_n + h v_n + h^2 f_n / 2,
would make this explicit exchange unstable (energy grows by (w_c h)^2 / 2 per step in contact),
while the central-difference form keeps it stable up to w_c h < 2. Velocities are the
half-step values (eta_n - eta_{n-1}) / h, as in the leapfrog units.

The optional static correction adds the residual flexibility R of the truncated modes,
R = G_elastic - sum_kept p p^T / omega^2 (inertia relief), as a feedthrough from the interface
forces to the interface displacements; then the static response is exact whatever fmax.

The rigid lumped-mass anvil is the same object with only the rigid-body mode.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from anvilwave.anvil_rom.contact import contact_force
from anvilwave.anvil_rom.fem.modalfile import ModalData
from anvilwave.inputs import InputError


@dataclass(frozen=True)
class ModalAnvil:
    """Modal ROM of an anvil between the ram face and the pile ring.

    Parameters
    ----------
    omega : numpy.ndarray
        Circular frequencies, shape (n,) [rad/s]; omega[0] = 0 is the rigid-body mode.
    participation_ram : numpy.ndarray
        b_ram^T phi at the ram face, shape (n,) [kg^-1/2].
    participation_pile : numpy.ndarray
        b_pile^T phi at the pile ring, shape (n,) [kg^-1/2].
    participation_gravity : numpy.ndarray
        phi^T M e_z, shape (n,) [kg^1/2].
    damping_ratio : float
        Modal damping ratio of the flexible modes [-].
    residual_flexibility : numpy.ndarray
        Static correction between the ram face and the pile ring, shape (2, 2) [m/N] (zeros
        without it).
    total_mass : float
        Mass of the anvil [kg].
    fmax : float
        Frequency content of the ROM [Hz].
    participation_rings : numpy.ndarray or None, default None
        The pile port split into K rings (:mod:`anvilwave.anvil_rom.rings`), shape (K, n)
        [kg^-1/2]; None: one port.
    residual_rings : numpy.ndarray or None, default None
        Static correction between the ram face (J = 1) or its J annuli and the rings, shape
        (J + K, J + K) [m/N] (zeros without it); None: one port.
    ring_areas : numpy.ndarray or None, default None
        Areas of the rings, shape (K,) [m^2]; None: one port.
    participation_ram_annuli : numpy.ndarray or None, default None
        The ram port split into J > 1 annuli, shape (J, n) [kg^-1/2]; None: one port.
    ram_annulus_areas : numpy.ndarray or None, default None
        Areas of the ram port's annuli, shape (J,) [m^2]; None: one port.
    """

    omega: np.ndarray
    participation_ram: np.ndarray
    participation_pile: np.ndarray
    participation_gravity: np.ndarray
    damping_ratio: float
    residual_flexibility: np.ndarray
    total_mass: float
    fmax: float
    participation_rings: np.ndarray | None = None
    residual_rings: np.ndarray | None = None
    ring_areas: np.ndarray | None = None
    participation_ram_annuli: np.ndarray | None = None
    ram_annulus_areas: np.ndarray | None = None

    @property
    def n_annuli(self) -> int:
        """Annuli of the ram port (1: one port).

        Returns
        -------
        int
            J, the number of annuli of the ram port [-].
        """
        return (1 if self.participation_ram_annuli is None
                else int(self.participation_ram_annuli.shape[0]))

    @property
    def n_rings(self) -> int:
        """Rings of the pile port (1: one port).

        Returns
        -------
        int
            K, the number of rings of the pile port [-].
        """
        return 1 if self.participation_rings is None else int(self.participation_rings.shape[0])

    @property
    def n_modes(self) -> int:
        """Number of retained modes, the rigid-body mode included.

        Returns
        -------
        int
            n [-].
        """
        return len(self.omega)

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies [Hz].

        Returns
        -------
        numpy.ndarray
            omega / (2 pi), shape (n,) [Hz].
        """
        return self.omega / (2.0 * np.pi)

    @classmethod
    def from_modal_data(cls, data: ModalData, fmax: float | None = None,
                        damping_ratio: float | None = None, static_correction: bool = False,
                        source: str = "modal data") -> ModalAnvil:
        """Truncate stored modes at ``fmax`` [Hz] (default: all stored) into a ROM.

        Parameters
        ----------
        data : ModalData
            The stored modes of the anvil (:mod:`anvilwave.anvil_rom.fem.modalfile`).
        fmax : float, optional
            Highest frequency kept [Hz]; default: the frequency content of ``data``.
        damping_ratio : float, optional
            Modal damping ratio of the flexible modes [-], in [0, 1); default: that of
            ``data``.
        static_correction : bool, default False
            Add the residual flexibility of the truncated modes (module docstring).
        source : str, default "modal data"
            Name of the input the errors refer to.

        Returns
        -------
        ModalAnvil
            The ROM (with the pile port in rings, and the ram port in annuli, when ``data``
            has them).

        Raises
        ------
        InputError
            If ``fmax`` is not positive, exceeds the stored content or keeps no flexible mode,
            or if ``damping_ratio`` is outside [0, 1).
        """
        freqs = np.asarray(data.frequencies)
        fmax = data.fmax if fmax is None else float(fmax)
        if not np.isfinite(fmax) or fmax <= 0.0:
            raise InputError(source, "fmax", f"must be positive, got {fmax:g} Hz")
        if fmax > data.fmax * (1 + 1e-12):
            raise InputError(source, "fmax", f"{fmax:g} Hz exceeds the {data.fmax:g} Hz the modes "
                                             "were computed for; recompute the modes")
        if len(freqs) < 2 or fmax < freqs[1]:
            first = (f"{freqs[1]:.1f} Hz" if len(freqs) > 1
                     else f"none at or below the {data.fmax:g} Hz computed")
            raise InputError(source, "fmax", f"{fmax:g} Hz is below the first flexible mode "
                                             f"({first}): the ROM would be a rigid body; "
                                             "use the lumped anvil for that")
        damping = data.damping_ratio if damping_ratio is None else float(damping_ratio)
        if not 0.0 <= damping < 1.0:
            raise InputError(source, "damping_ratio", f"must be in [0, 1), got {damping:g}")
        keep = freqs <= fmax
        omega = 2.0 * np.pi * freqs[keep]
        p_ram, p_pile = data.participation_ram[keep], data.participation_pile[keep]
        residual = np.zeros((2, 2))
        if static_correction:
            residual = residual_flexibility(data.elastic_flexibility, omega, p_ram, p_pile)
        rings = {}
        if getattr(data, "participation_rings", None) is not None:  # a one-port record may lack it
            p_rings = np.asarray(data.participation_rings)[:, keep]
            p_faces = p_ram[None, :]
            if getattr(data, "participation_ram_annuli", None) is not None:
                p_faces = np.asarray(data.participation_ram_annuli)[:, keep]
                rings = {"participation_ram_annuli": p_faces,
                         "ram_annulus_areas": np.asarray(data.ram_annulus_areas, float)}
            m = p_faces.shape[0] + p_rings.shape[0]
            ring_residual = np.zeros((m, m))
            if static_correction:
                ring_residual = residual_flexibility(data.ring_flexibility, omega, *p_faces,
                                                     *p_rings)
            rings.update(participation_rings=p_rings, residual_rings=ring_residual,
                         ring_areas=np.asarray(data.ring_areas, float))
        return cls(omega, p_ram, p_pile, data.participation_gravity[keep], damping, residual,
                   data.total_mass, fmax, **rings)

    @classmethod
    def rigid(cls, mass: float) -> ModalAnvil:
        """The rigid lumped-mass anvil of the classic programs: one rigid-body mode.

        Parameters
        ----------
        mass : float
            Mass of the anvil [kg].

        Returns
        -------
        ModalAnvil
            The one-mode ROM (omega = 0, participations 1 / sqrt(mass), no static correction).

        Raises
        ------
        InputError
            If ``mass`` is not positive and finite.
        """
        if not np.isfinite(mass) or mass <= 0.0:
            raise InputError("anvil", "mass", f"must be positive, got {mass!r} kg")
        s = 1.0 / np.sqrt(mass)
        return cls(np.zeros(1), np.array([s]), np.array([s]), np.array([np.sqrt(mass)]), 0.0,
                   np.zeros((2, 2)), float(mass), 0.0)

    def transition(self, h: float) -> np.ndarray:
        """Step coefficients [a, b, c, m_e] of the modes for a step ``h`` (module docstring).

        Parameters
        ----------
        h : float
            Time step [s].

        Returns
        -------
        numpy.ndarray
            [a, b, c, m_e] per mode, shape (n, 4) [-, -, s^2, -] (:func:`modal_transition`).
        """
        return modal_transition(self.omega, self.damping_ratio, h)

    def static_modal_coordinates(self, force_ram: float, force_pile: float) -> np.ndarray:
        """Flexible-mode coordinates in static equilibrium under the interface forces.

        The rigid coordinate is returned as 0 (it is fixed by the supports, not the anvil).

        Parameters
        ----------
        force_ram : float
            Ram contact force on the top face [N] (compression positive).
        force_pile : float
            Pile contact force on the bottom face [N] (compression positive).

        Returns
        -------
        numpy.ndarray
            Modal coordinates q, shape (n,) [m kg^1/2].
        """
        q = np.zeros(self.n_modes)
        flexible = self.omega > 0.0
        load = self.participation_ram * force_ram - self.participation_pile * force_pile
        q[flexible] = load[flexible] / self.omega[flexible] ** 2
        return q


def residual_flexibility(elastic_flexibility: np.ndarray, omega: np.ndarray,
                         *participations: np.ndarray) -> np.ndarray:
    """Flexibility of the truncated modes between the interfaces [m/N].

    R = G - sum over kept flexible modes of p p^T / omega^2, with G the inertia-relief
    flexibility of the full FE model (all flexible modes) between the ports whose modal
    participations are given, in G's order (the anvil's: ram, pile).

    Parameters
    ----------
    elastic_flexibility : numpy.ndarray
        G, the inertia-relief flexibility between the ports, shape (m, m) [m/N].
    omega : numpy.ndarray
        Circular frequencies of the kept modes, shape (n,) [rad/s] (0: rigid, skipped).
    *participations : numpy.ndarray
        The modal participations p of each port, shape (n,) each [kg^-1/2], in G's order.

    Returns
    -------
    numpy.ndarray
        R, shape (m, m) [m/N].
    """
    flexible = omega > 0.0
    P = np.vstack([np.asarray(p)[flexible] for p in participations])
    return np.asarray(elastic_flexibility) - (P / omega[flexible] ** 2) @ P.T


def modal_transition(omega: np.ndarray, damping_ratio: float, h: float) -> np.ndarray:
    """Two-step coefficients [a, b, c, m_e] per mode for a step ``h`` [s] (module docstring).

    eta_{n+1} = a eta_n + b eta_{n-1} + c f_n is exact for free damped vibration (a, b from the
    roots exp(lambda h) of the mode) and for a constant force (c = (1 - a - b) / w^2, the static
    response f / w^2 reproduced exactly); m_e = w^2 h^2 / (2 - a) is the modal mass of the
    equivalent central-difference scheme (1 for the rigid mode), used for energies.

    Parameters
    ----------
    omega : numpy.ndarray
        Circular frequencies, shape (n,) [rad/s] (0: the rigid-body mode).
    damping_ratio : float
        Modal damping ratio xi of the flexible modes [-].
    h : float
        Time step [s].

    Returns
    -------
    numpy.ndarray
        [a, b, c, m_e] per mode, shape (n, 4) [-, -, s^2, -].
    """
    omega = np.asarray(omega, dtype=float)
    out = np.empty((len(omega), 4))
    for j, w in enumerate(omega):
        if w == 0.0:
            out[j] = 2.0, -1.0, h * h, 1.0
            continue
        wd = w * np.sqrt(1.0 - damping_ratio**2)
        decay = np.exp(-damping_ratio * w * h)
        a = 2.0 * decay * np.cos(wd * h)
        b = -decay * decay
        c = (1.0 - a - b) / (w * w)
        undamped_a = 2.0 * np.cos(w * h)
        m_e = (w * h) ** 2 / (2.0 - undamped_a) if undamped_a < 2.0 else 1.0
        out[j] = a, b, c, m_e
    return out


@njit(cache=True)
def modal_step(coef, p_ram, p_pile, p_grav, q, q_prev, force_ram, force_pile, gravity):
    """Advance all modal coordinates by one step (in place).

    Parameters
    ----------
    coef : numpy.ndarray
        [a, b, c, ...] per mode from :func:`modal_transition`, shape (n, >= 3)
        [-, -, s^2, ...].
    p_ram : numpy.ndarray
        Participations at the ram face, shape (n,) [kg^-1/2].
    p_pile : numpy.ndarray
        Participations at the pile ring, shape (n,) [kg^-1/2].
    p_grav : numpy.ndarray
        Gravity participations phi^T M e_z, shape (n,) [kg^1/2].
    q : numpy.ndarray
        Modal coordinates at t_n, shape (n,) [m kg^1/2]; becomes t_n+1 (written).
    q_prev : numpy.ndarray
        Modal coordinates at t_n-1, shape (n,) [m kg^1/2]; becomes t_n (written).
    force_ram : float
        Ram interface force at t_n [N] (compression positive).
    force_pile : float
        Pile interface force at t_n [N] (compression positive).
    gravity : float
        Gravitational acceleration [m/s^2].
    """
    for j in range(q.shape[0]):
        f = p_ram[j] * force_ram - p_pile[j] * force_pile + p_grav[j] * gravity
        q_new = coef[j, 0] * q[j] + coef[j, 1] * q_prev[j] + coef[j, 2] * f
        q_prev[j] = q[j]
        q[j] = q_new


@njit(cache=True)
def modal_interface(p_ram, p_pile, q, q_prev, h):
    """Modal part of (u_top, v_top, u_bottom, v_bottom) [m, m/s].

    v is the half-step velocity (q_n - q_n-1) / h of the step h [s].

    Parameters
    ----------
    p_ram : numpy.ndarray
        Participations at the ram face, shape (n,) [kg^-1/2].
    p_pile : numpy.ndarray
        Participations at the pile ring, shape (n,) [kg^-1/2].
    q : numpy.ndarray
        Modal coordinates at t_n, shape (n,) [m kg^1/2].
    q_prev : numpy.ndarray
        Modal coordinates at t_n-1, shape (n,) [m kg^1/2].
    h : float
        Time step [s].

    Returns
    -------
    ut : float
        Modal top-face displacement [m].
    vt : float
        Modal top-face half-step velocity [m/s].
    ub : float
        Modal bottom-face displacement [m].
    vb : float
        Modal bottom-face half-step velocity [m/s].
    """
    inverse_step = 1.0 / h
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for j in range(q.shape[0]):
        qd = (q[j] - q_prev[j]) * inverse_step
        ut += p_ram[j] * q[j]
        vt += p_ram[j] * qd
        ub += p_pile[j] * q[j]
        vb += p_pile[j] * qd
    return ut, vt, ub, vb


@njit(cache=True, inline='always')
def anvil_contact_forces(u_ram, v_ram, u_pile, v_pile, u_top, v_top, u_bot, v_bot,
                         k_ram, c_ram, k_pile, c_pile, r00, r01, r11):
    """Ram-anvil and anvil-pile contact forces at one instant [N].

    u_top, u_bot are the modal interface displacements; the static correction (residual
    flexibility r) adds u_top += r00 F_ram - r01 F_pile and u_bot += r01 F_ram - r11 F_pile, a
    feedthrough that makes the two compression-only contacts a 2x2 linear complementarity
    problem. Its matrix diag(1/k) + [[r00, -r01], [-r01, r11]] is positive definite, so the
    solution is unique; the four active sets are tried in turn (the dashpots then act on the
    equivalent overlap d + c d'/k). Without static correction (r = 0) this is two independent
    :func:`contact_force` evaluations.

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
    u_top : float
        Modal displacement of the top face [m].
    v_top : float
        Modal velocity of the top face [m/s].
    u_bot : float
        Modal displacement of the bottom face [m].
    v_bot : float
        Modal velocity of the bottom face [m/s].
    k_ram : float
        Ram contact spring [N/m].
    c_ram : float
        Ram contact dashpot [N s/m].
    k_pile : float
        Pile contact spring [N/m].
    c_pile : float
        Pile contact dashpot [N s/m].
    r00 : float
        Residual flexibility at the ram face [m/N].
    r01 : float
        Residual flexibility between the ram face and the pile ring [m/N].
    r11 : float
        Residual flexibility at the pile ring [m/N].

    Returns
    -------
    f_ram : float
        Ram-anvil contact force [N] (compression positive, >= 0).
    f_pile : float
        Anvil-pile contact force [N] (compression positive, >= 0).
    """
    if r00 == 0.0 and r01 == 0.0 and r11 == 0.0:
        return (contact_force(u_ram - u_top, v_ram - v_top, k_ram, c_ram),
                contact_force(u_bot - u_pile, v_bot - v_pile, k_pile, c_pile))
    # overlaps without the corrections, the dashpots folded in as an equivalent overlap
    g_ram = u_ram - u_top + c_ram / k_ram * (v_ram - v_top)
    g_pile = u_bot - u_pile + c_pile / k_pile * (v_bot - v_pile)
    a11 = 1.0 / k_ram + r00
    a22 = 1.0 / k_pile + r11
    # both in contact: [[a11, -r01], [-r01, a22]] F = g
    det = a11 * a22 - r01 * r01
    f_ram = (a22 * g_ram + r01 * g_pile) / det
    f_pile = (a11 * g_pile + r01 * g_ram) / det
    if f_ram > 0.0 and f_pile > 0.0:
        return f_ram, f_pile
    # ram only: valid if the pile ring stays open under the ram force alone
    f_ram = g_ram / a11
    if f_ram > 0.0 and g_pile + r01 * f_ram <= 0.0:
        return f_ram, 0.0
    f_pile = g_pile / a22
    if f_pile > 0.0 and g_ram + r01 * f_pile <= 0.0:
        return 0.0, f_pile
    return 0.0, 0.0
