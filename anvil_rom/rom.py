"""The Mode Displacement Method anvil (modal ROM) and the rigid lumped-mass anvil.

Each retained mode j obeys (Ligthart & Orlando, eq. 8; DESIGN.md)::

    eta_j'' + 2 xi omega_j eta_j' + omega_j^2 eta_j
        = p_ram_j F_ram - p_pile_j F_pile + p_grav_j g

with p_ram = b_ram^T phi_j, p_pile = b_pile^T phi_j, p_grav = phi_j^T M e_z, and the interface
displacements are u_top = sum p_ram_j eta_j, u_bottom = sum p_pile_j eta_j. Over a step of
length h with the forces held constant each mode is advanced EXACTLY by its 2x2 transition
matrix (zero-order hold), so the integration is unconditionally stable for any h.

The optional static correction adds the residual flexibility R of the truncated modes,
R = G_elastic - sum_kept p p^T / omega^2 (inertia relief), as a feedthrough from the interface
forces to the interface displacements; then the static response is exact whatever fmax.

The rigid lumped-mass anvil is the same object with only the rigid-body mode.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numba import njit

from .contact import contact_force
from .inputs import InputError
from .modalfile import ModalData


@dataclass(frozen=True)
class ModalAnvil:
    """Modal ROM of an anvil between the ram face and the pile ring.

    omega : (n,) circular frequencies [rad/s]; omega[0] = 0 is the rigid-body mode.
    participation_ram, participation_pile : (n,) b^T phi at the interfaces [kg^-1/2].
    participation_gravity : (n,) phi^T M e_z [kg^1/2].
    damping_ratio : modal damping ratio of the flexible modes [-].
    residual_flexibility : (2, 2) static correction [m/N] (zeros without it).
    total_mass : [kg].
    fmax : frequency content [Hz].
    """

    omega: np.ndarray
    participation_ram: np.ndarray
    participation_pile: np.ndarray
    participation_gravity: np.ndarray
    damping_ratio: float
    residual_flexibility: np.ndarray
    total_mass: float
    fmax: float

    @property
    def n_modes(self) -> int:
        return len(self.omega)

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies [Hz]."""
        return self.omega / (2.0 * np.pi)

    @classmethod
    def from_modal_data(cls, data: ModalData, fmax: float | None = None,
                        damping_ratio: float | None = None, static_correction: bool = False,
                        source: str = "modal data") -> ModalAnvil:
        """Truncate stored modes at ``fmax`` [Hz] (default: all stored) into a ROM.

        Raises :class:`InputError` when fmax exceeds the stored content or keeps no flexible mode.
        """
        freqs = np.asarray(data.frequencies)
        fmax = data.fmax if fmax is None else float(fmax)
        if not np.isfinite(fmax) or fmax <= 0.0:
            raise InputError(source, "fmax", f"must be positive, got {fmax:g} Hz")
        if fmax > data.fmax * (1 + 1e-12):
            raise InputError(source, "fmax", f"{fmax:g} Hz exceeds the {data.fmax:g} Hz the modes "
                                             "were computed for; recompute the modes")
        if len(freqs) < 2 or fmax < freqs[1]:
            first = freqs[1] if len(freqs) > 1 else float("nan")
            raise InputError(source, "fmax", f"{fmax:g} Hz is below the first flexible mode "
                                             f"({first:.1f} Hz): the ROM would be a rigid body; "
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
        return cls(omega, p_ram, p_pile, data.participation_gravity[keep], damping, residual,
                   data.total_mass, fmax)

    @classmethod
    def rigid(cls, mass: float) -> ModalAnvil:
        """The rigid lumped-mass anvil of the classic programs: one rigid-body mode [kg]."""
        if not np.isfinite(mass) or mass <= 0.0:
            raise InputError("anvil", "mass", f"must be positive, got {mass!r} kg")
        s = 1.0 / np.sqrt(mass)
        return cls(np.zeros(1), np.array([s]), np.array([s]), np.array([np.sqrt(mass)]), 0.0,
                   np.zeros((2, 2)), float(mass), 0.0)

    def transition(self, h: float) -> np.ndarray:
        """(n, 6) exact zero-order-hold step coefficients for a step ``h`` [s].

        Row j: [a11, a12, a21, a22, b1, b2] with
        eta(t+h) = a11 eta + a12 eta' + b1 f,  eta'(t+h) = a21 eta + a22 eta' + b2 f.
        """
        return modal_transition(self.omega, self.damping_ratio, h)

    def static_modal_coordinates(self, force_ram: float, force_pile: float) -> np.ndarray:
        """Flexible-mode coordinates in static equilibrium under the interface forces [N].

        The rigid coordinate is returned as 0 (it is fixed by the supports, not the anvil).
        """
        q = np.zeros(self.n_modes)
        flexible = self.omega > 0.0
        load = self.participation_ram * force_ram - self.participation_pile * force_pile
        q[flexible] = load[flexible] / self.omega[flexible] ** 2
        return q


def residual_flexibility(elastic_flexibility: np.ndarray, omega: np.ndarray,
                         participation_ram: np.ndarray, participation_pile: np.ndarray
                         ) -> np.ndarray:
    """Flexibility of the truncated modes between the interfaces [m/N].

    R = G - sum over kept flexible modes of p p^T / omega^2, with G the inertia-relief
    flexibility of the full FE model (all flexible modes).
    """
    flexible = omega > 0.0
    P = np.vstack([participation_ram[flexible], participation_pile[flexible]])
    return np.asarray(elastic_flexibility) - (P / omega[flexible] ** 2) @ P.T


def modal_transition(omega: np.ndarray, damping_ratio: float, h: float) -> np.ndarray:
    """Exact step coefficients of eta'' + 2 xi w eta' + w^2 eta = f with f held over ``h`` [s].

    From the matrix exponential of the augmented system [[A, B], [0, 0]] h with
    A = [[0, 1], [-w^2, -2 xi w]], B = [0, 1]^T (the rigid mode w = 0 gives the exact
    eta(t+h) = eta + h eta' + h^2 f / 2).
    """
    out = np.empty((len(omega), 6))
    for j, w in enumerate(omega):
        aug = np.zeros((3, 3))
        aug[0, 1] = 1.0
        aug[1, 0] = -w * w
        aug[1, 1] = -2.0 * damping_ratio * w
        aug[1, 2] = 1.0
        E = scipy.linalg.expm(aug * h)
        out[j] = E[0, 0], E[0, 1], E[1, 0], E[1, 1], E[0, 2], E[1, 2]
    return out


@njit(cache=True)
def modal_step(coef, p_ram, p_pile, p_grav, q, qd, force_ram, force_pile, gravity):
    """Advance all modal coordinates over one step with the forces held (in place).

    coef : (n, 6) from :func:`modal_transition`; q, qd : modal displacement and velocity;
    force_ram, force_pile : interface forces [N] (compression positive); gravity [m/s^2].
    """
    for j in range(q.shape[0]):
        f = p_ram[j] * force_ram - p_pile[j] * force_pile + p_grav[j] * gravity
        q0 = q[j]
        q[j] = coef[j, 0] * q0 + coef[j, 1] * qd[j] + coef[j, 4] * f
        qd[j] = coef[j, 2] * q0 + coef[j, 3] * qd[j] + coef[j, 5] * f


@njit(cache=True)
def modal_interface(p_ram, p_pile, q, qd):
    """Modal part of (u_top, v_top, u_bottom, v_bottom) [m, m/s]."""
    ut = 0.0
    vt = 0.0
    ub = 0.0
    vb = 0.0
    for j in range(q.shape[0]):
        ut += p_ram[j] * q[j]
        vt += p_ram[j] * qd[j]
        ub += p_pile[j] * q[j]
        vb += p_pile[j] * qd[j]
    return ut, vt, ub, vb


@njit(cache=True)
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
