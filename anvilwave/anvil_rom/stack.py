"""The driving stack as one anvil unit: the anvil and the anvil ring, two modal bodies.

Each body is a Mode Displacement Method ROM (its own free-free modes truncated at the system's
fmax, its static correction); the unit keeps the anvil's outward interface, ram in, pile out
(DESIGN.md). Its contacts, each between a port of one side and a port of the other:

* the ram on the anvil's top face: one port, compression-only, with the ram contact's dashpot;
  or J equal-width annuli from the axis (``ram_face``,
  :class:`anvilwave.anvil_rom.rings.RamFace`), each a compression-only contact between the
  same annulus of the ram's toe and of the anvil's top face, coupled as the anvil unit couples
  them (:mod:`anvilwave.anvil_rom.rings`): the ram's side of annulus a sits at the ram unit's
  toe plus its offset (:func:`anvilwave.anvil_rom.rings.ram_face_advance`, the ram's flexible
  modes driven by the annuli's forces and by their sum), the ram's residual flexibility
  between the annuli in G in place of the contact spring, the dashpot shared by annulus area;
* the seat, the anvil's flat bottom face on the ring's flat top face where they overlap, in S
  equal-width rings (:func:`annulus_vectors` on both faces): per ring a compression-only normal
  contact on the two bodies' axial participations, and a Coulomb friction pair on their radial
  participations (the two faces slide along the radius as the bodies bulge);
* the ring's bottom face on the pile wall in K equal-width rings (compression-only, the pile's
  contact spring and dashpot shared by ring area, on the 1D pile head); or on the tube head
  (``[anvil] pile_head = "tube"``, :meth:`StackUnit.set_head`): the pile's top section as an
  axisymmetric FE tube under the rings, the tube's contact springs, and what the tube adds to
  the 1D head at each lag, D (:func:`anvilwave.pile.head_kernel.head_correction`), as the
  single anvil's rings have it (:func:`anvilwave.anvil_rom.rings.head_push`): D[0] in A, the
  rings' pile side moved down by the history's shift (:func:`stack_head_push`);
* with a guiding sleeve (``sleeve_clearance``), each body's outer cylindrical face in L
  equal-height bands (:class:`Band`, :func:`anvilwave.anvil_rom.fem.elasticity.band_vectors`):
  per band a compression-only radial contact with the rigid, fixed sleeve across the
  clearance (the band's mean radial displacement less the clearance; the bodies bulge into
  it under the blow, Poisson), and a Coulomb pair on its axial participation (the bodies
  slide down along the sleeve).

With one seat ring and one pile ring the faces close at once over their width; in the FEA they
close and slide unevenly (the anvil comes down tilted on the seat, the ring rocks on the pile
wall); ``benchmarks/study_anvil_ring.py`` compares one port each with the rings against the
FEA stack.

Every contact c has an upper side (the anvil, or the ram) and a lower one (the ring, or the
pile); its relative displacement is s_c = u_upper - u_lower (z down; along the radius for a
friction pair) and its force X_c pushes the upper side by -X_c and the lower by +X_c. With Q_b
the modal loads of body b per unit contact force (its port participations through the
incidence of the contacts) and R_b its residual flexibility between its ports::

    s = s_ext - sum_b Q_b^T q_b - G X,      G = sum_b B_b^T R_b B_b

(B_b the incidence, s_ext the ram's and the pile's displacements). The normal forces F solve
the complementarity problem A F = g, F >= 0 (:func:`anvilwave.anvil_rom.rings.contact_lcp`),
A = diag(1 / k) + G_NN, g = s_N (modal) - G_NT T + (c / k) s_N' with the friction forces T of
the step before (the dashpots folded into an equivalent overlap, as the anvil unit does). Then
each friction pair by :func:`anvilwave.anvil_rom.contact.coulomb_friction` under the cone
mu F_s: its stick spring k_t in series with the two bodies' radial residual flexibility, the
pair's k_eff = 1 / (1 / k_t + G_tt), driven by w = s_t (modal) - G_tN F - sum_(u != t) G_tu T_u
(Gauss-Seidel sweeps over the pairs, each from the step's start); then both bodies' modes are
advanced exactly with all forces held. Energy: per mode the shadow form, plus the complementary
energy X^T (G + diag(1 / k)) X / 2 of the massless part (contact and stick springs, residual
flexibility); friction and dashpot dissipation are booked.

Contact order: 0 .. J - 1 the ram (J = 1: the one port; annuli inner to outer), J .. J + S - 1
the seat rings (inner to outer), J + S .. J + S + K - 1 the pile rings, then the sleeve's
normal contacts (the anvil's L_a bands, then the ring's L_r, top down): N in all; then the
friction pairs, the S seat rings' and the L_a + L_r bands'. Ports: the anvil [J ram face
annuli, S seat rings axial, S radial, L_a bands radial, L_a axial], the ring [S seat rings
axial, S radial, K pile rings axial, L_r bands radial, L_r axial].
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from anvilwave.anvil_rom.contact import coulomb_friction
from anvilwave.anvil_rom.fem.elasticity import annulus_vectors, band_vectors
from anvilwave.anvil_rom.fem.geometry import AnvilSpec
from anvilwave.anvil_rom.fem.mesh import split_outline_at_heights, split_outline_at_radii
from anvilwave.anvil_rom.fem.modes import elastic_flexibility
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes
from anvilwave.anvil_rom.rings import (
    RamFace,
    contact_lcp,
    head_push_forces,
    ram_face_advance,
    ram_face_energy,
)
from anvilwave.anvil_rom.rom import ModalAnvil, modal_transition
from anvilwave.anvil_rom.unit import GRAVITY, AnvilUnit, ContactParameters
from anvilwave.inputs import InputError

FRICTION_SWEEPS = 8
"""Gauss-Seidel sweeps over the seat's friction pairs a step (their coupling through the
radial residual flexibility); ``tests/test_stack.py`` checks that more sweeps change the blow
by less than 1e-6 of its peak."""


@dataclass(frozen=True)
class Face:
    """Ports on a flat face of a body: ``count`` equal-width annuli from ``r_in`` to ``r_out``.

    Parameters
    ----------
    direction : {"axial", "radial"}
        Uniform pressures (axial) or uniform radial tractions (radial) on the annuli.
    side : {"top", "bottom"}
        The body's top (smallest z) or bottom (largest z) face.
    r_in : float
        Inner radius [m].
    r_out : float
        Outer radius [m].
    count : int
        Number of annuli [-].
    """

    direction: str
    side: str
    r_in: float
    r_out: float
    count: int


@dataclass(frozen=True)
class Band:
    """Ports on a body's outer cylindrical face: ``count`` equal-height bands along it.

    Parameters
    ----------
    direction : {"radial", "axial"}
        Uniform radial tractions (the sleeve's normal pressure) or uniform axial tractions
        (the friction along it) on the bands.
    radius : float
        Radius of the face [m].
    z_top : float
        Its upper end [m] (z down).
    z_bottom : float
        Its lower end [m].
    count : int
        Number of bands [-].
    """

    direction: str
    radius: float
    z_top: float
    z_bottom: float
    count: int


def outer_band_face(outline, count: int, direction: str) -> Band:
    """The bands of an outline's outer cylindrical face (its vertical edge at the largest r).

    Parameters
    ----------
    outline : array_like
        Polygon vertices, rows (r, z) [m].
    count : int
        Number of bands [-].
    direction : {"radial", "axial"}
        As :class:`Band`.

    Returns
    -------
    Band
        The face from the top to the bottom of the edge at r = max r.

    Raises
    ------
    ValueError
        If the outline has no vertical edge at its largest radius.
    """
    pts = np.asarray(outline, float)
    r = pts[:, 0].max()
    z = pts[np.isclose(pts[:, 0], r), 1]
    if not z.max() > z.min():
        raise ValueError(f"the outline has no vertical edge at its outer radius {r:g} m")
    return Band(direction, float(r), float(z.min()), float(z.max()), int(count))


@dataclass(frozen=True)
class StackBodyData:
    """A body's modes projected on its ports (the stack's modal file, cached by the caller).

    Parameters
    ----------
    frequencies : numpy.ndarray
        Natural frequencies, shape (n,) [Hz] (0: the axial rigid-body mode).
    participation : numpy.ndarray
        The ports' participations b^T phi, shape (ports, n) [kg^-1/2].
    flexibility : numpy.ndarray
        Inertia-relief flexibility between the ports (all modes), shape (ports, ports) [m/N].
    participation_gravity : numpy.ndarray
        phi^T M e_z, shape (n,) [kg^1/2].
    total_mass : float
        Mass [kg].
    areas : numpy.ndarray
        Area of each port, shape (ports,) [m^2].
    """

    frequencies: np.ndarray
    participation: np.ndarray
    flexibility: np.ndarray
    participation_gravity: np.ndarray
    total_mass: float
    areas: np.ndarray


def stack_body_data(spec: AnvilSpec, faces: tuple[Face | Band, ...], fmax: float
                    ) -> StackBodyData:
    """Free-free modes of one stack body to ``fmax`` on the annuli of ``faces``.

    The outline gets a vertex at every annulus edge (the load vectors exact on the mesh),
    :func:`anvilwave.anvil_rom.fem.pipeline.compute_anvil_modes` solves the modes, and each
    face's annuli are :func:`anvilwave.anvil_rom.fem.elasticity.annulus_vectors` (axial or
    radial) with their inertia-relief flexibility
    (:func:`anvilwave.anvil_rom.fem.modes.elastic_flexibility`).

    Parameters
    ----------
    spec : AnvilSpec
        The body (an outline).
    faces : tuple of Face or Band
        Its ports, in order.
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    StackBodyData
        Modes and ports.

    Raises
    ------
    InputError
        If the body is not an outline, or an annulus has no element edge.
    """
    if spec.outline is None:
        raise InputError(spec.source, "geometry", "a stack body must be an outline")
    outline = np.asarray(spec.outline, float)
    z_top, z_bottom = outline[:, 1].min(), outline[:, 1].max()
    for f in faces:
        if isinstance(f, Band):
            outline = split_outline_at_heights(outline, f.radius,
                                               np.linspace(f.z_top, f.z_bottom, f.count + 1))
            continue
        outline = split_outline_at_radii(outline, z_top if f.side == "top" else z_bottom,
                                         np.linspace(f.r_in, f.r_out, f.count + 1))
    spec = dataclasses.replace(spec, outline=outline, interfaces=None, fmax=fmax)
    result = compute_anvil_modes(spec, fmax)
    model, modes = result.model, result.modes
    columns, areas = [], []
    for f in faces:
        if isinstance(f, Band):
            B, A = band_vectors(model, f.radius, f.z_top, f.z_bottom, f.count,
                                radial=f.direction == "radial")
            where = f"{f.count} bands from z {f.z_top:g} to {f.z_bottom:g} m"
        else:
            z = model.mesh.p[1].min() if f.side == "top" else model.mesh.p[1].max()
            B, A = annulus_vectors(model, z, f.r_in, f.r_out, f.count,
                                   radial=f.direction == "radial")
            where = f"{f.count} annuli from {f.r_in:g} to {f.r_out:g} m"
        if np.any(A == 0.0):
            raise InputError(spec.source, "mesh.size", f"{where} need as many element edges: "
                                                       "refine the mesh")
        columns.append(B)
        areas.append(A)
    B = np.column_stack(columns)
    G = elastic_flexibility(model, B)
    return StackBodyData(np.asarray(modes.frequencies, float), B.T @ modes.shapes,
                         0.5 * (G + G.T), modes.shapes.T @ (model.mass @ model.axial_free),
                         float(model.total_mass()), np.concatenate(areas))


@dataclass(frozen=True)
class StackBody:
    """One modal body of the stack: its kept modes and the residual flexibility of its ports.

    Parameters
    ----------
    omega : numpy.ndarray
        Circular frequencies of the kept modes, shape (n,) [rad/s].
    participation : numpy.ndarray
        The ports' participations, shape (ports, n) [kg^-1/2].
    residual : numpy.ndarray
        Residual flexibility between the ports, shape (ports, ports) [m/N] (zeros without
        static correction).
    participation_gravity : numpy.ndarray
        shape (n,) [kg^1/2].
    total_mass : float
        Mass [kg].
    areas : numpy.ndarray
        Port areas, shape (ports,) [m^2].
    damping_ratio : float, default 0.0
        Modal damping ratio of the flexible modes [-].
    """

    omega: np.ndarray
    participation: np.ndarray
    residual: np.ndarray
    participation_gravity: np.ndarray
    total_mass: float
    areas: np.ndarray
    damping_ratio: float = 0.0

    @classmethod
    def from_data(cls, data: StackBodyData, fmax: float, static_correction: bool = True,
                  damping_ratio: float = 0.0) -> StackBody:
        """The body truncated at ``fmax`` with its static correction.

        Parameters
        ----------
        data : StackBodyData
            The body's modes and ports.
        fmax : float
            Highest frequency kept [Hz].
        static_correction : bool, default True
            Add the residual flexibility of the truncated modes
            (:func:`anvilwave.anvil_rom.rom.residual_flexibility`).
        damping_ratio : float, default 0.0
            Modal damping ratio [-].

        Returns
        -------
        StackBody
            The body.
        """
        keep = np.asarray(data.frequencies) <= fmax * (1 + 1e-12)
        omega = 2.0 * np.pi * np.asarray(data.frequencies)[keep]
        P = np.asarray(data.participation)[:, keep]
        residual = np.zeros_like(data.flexibility)
        if static_correction:
            flexible = omega > 0.0
            residual = data.flexibility - (P[:, flexible] / omega[flexible] ** 2) @ P[:, flexible].T
        return cls(omega, P, residual, np.asarray(data.participation_gravity)[keep],
                   float(data.total_mass), np.asarray(data.areas), float(damping_ratio))

    @property
    def n_modes(self) -> int:
        """Number of kept modes.

        Returns
        -------
        int
            n [-].
        """
        return int(self.omega.size)


class StackState(NamedTuple):
    """The stack kernels' arrays (module docstring); m contacts, N = J + S + K normal ones.

    Parameters
    ----------
    parameters : numpy.ndarray
        [gravity [m/s^2], h [s], S [-], K [-]].
    anvil_coefficients : numpy.ndarray
        The anvil's modes, shape (n_a, 6): a, b, c, m_e (:func:`modal_transition`), omega,
        p_grav.
    ring_coefficients : numpy.ndarray
        The ring's, shape (n_r, 6).
    anvil_loads : numpy.ndarray
        Q of the anvil, its modal loads per unit contact force, shape (n_a, m) [kg^-1/2].
    ring_loads : numpy.ndarray
        Q of the ring, shape (n_r, m) [kg^-1/2].
    anvil_state : numpy.ndarray
        q of the anvil at t_n and t_n-1, shape (2 n_a,) [m kg^1/2].
    ring_state : numpy.ndarray
        q of the ring at t_n and t_n-1, shape (2 n_r,) [m kg^1/2].
    external : numpy.ndarray
        The ram's (row 0) and the pile's (row 1) share of each contact's s, shape (2, m).
    stiffness : numpy.ndarray
        k of each contact (friction pairs: k_t), shape (m,) [N/m].
    ratios : numpy.ndarray
        c / k of the normal contacts, shape (N,) [s].
    friction_pairs : numpy.ndarray
        Per pair [mu, k_eff, its normal contact], shape (P, 3) [-, N/m, -] (P = S + L_a + L_r).
    coupling : numpy.ndarray
        G, shape (m, m) [m/N].
    flexibility : numpy.ndarray
        A, shape (N, N) [m/N].
    forces : numpy.ndarray
        X of the last evaluation, shape (m,) [N].
    relative : numpy.ndarray
        s from the modes and the neighbours (no G X) and its rate, shape (2, m) [m, m/s].
    slip : numpy.ndarray
        w of each pair at its last update, shape (S,) [m].
    energies : numpy.ndarray
        [friction dissipation [J], dashpot work to t_n [J], started (1.0 once w is set) [-],
        dashpot power at the last :func:`stack_forces` [W]].
    active : numpy.ndarray
        The normal contacts' active set (1.0: closed), shape (N,).
    work : numpy.ndarray
        Scratch, shape (N, N + 9): the complementarity problem's (columns 0 .. N + 2) and the
        kernels' vectors (N + 3 .. N + 8), so that no kernel allocates (the engine's blow loop
        runs without reference counting, :func:`anvilwave.engine.direct.run_blow`).
    ram_coefficients : numpy.ndarray
        The ram's flexible modes for the face in annuli, shape (n_f, 5)
        (:meth:`anvilwave.anvil_rom.rings.RamFace.coefficients`; n_f = 0 for one port).
    ram_participation : numpy.ndarray
        Their participations on the annuli, shape (n_f, J) [kg^-1/2].
    ram_toe_participation : numpy.ndarray
        Theirs on the whole toe (the ram unit's), shape (n_f,) [kg^-1/2].
    ram_state : numpy.ndarray
        T and U now and a step before, shape (4, n_f) [m kg^1/2]
        (:func:`anvilwave.anvil_rom.rings.ram_face_advance`).
    ram_offsets : numpy.ndarray
        The annuli's offsets from the ram unit's toe now and a step before [m] and their rate
        [m/s], shape (3, J) (zeros for one port).
    head_kernel : numpy.ndarray
        D, what the tube head adds to the 1D head under the pile rings at each lag, shape
        (L, K, K) [m/N] (one lag of zeros on the 1D head; :func:`stack_head_push`).
    head_history : numpy.ndarray
        The pile rings' forces less their rest, every step of the blow, shape (L, K) [N].
    head_shift : numpy.ndarray
        The shift of the pile rings' pile side now and a step before, shape (2, K) [m].
    head_rest : numpy.ndarray
        The pile rings' forces at rest, shape (K,) [N].
    head_count : numpy.ndarray
        The steps in the history [-] and the work handed to the tube head [J], shape (2,).
    clearance : numpy.ndarray
        Each contact's gap at zero displacement, subtracted from its s: the sleeve's radial
        clearance on its normal contacts, 0 elsewhere, shape (m,) [m].
    """

    parameters: np.ndarray
    anvil_coefficients: np.ndarray
    ring_coefficients: np.ndarray
    anvil_loads: np.ndarray
    ring_loads: np.ndarray
    anvil_state: np.ndarray
    ring_state: np.ndarray
    external: np.ndarray
    stiffness: np.ndarray
    ratios: np.ndarray
    friction_pairs: np.ndarray
    coupling: np.ndarray
    flexibility: np.ndarray
    forces: np.ndarray
    relative: np.ndarray
    slip: np.ndarray
    energies: np.ndarray
    active: np.ndarray
    work: np.ndarray
    ram_coefficients: np.ndarray
    ram_participation: np.ndarray
    ram_toe_participation: np.ndarray
    ram_state: np.ndarray
    ram_offsets: np.ndarray
    head_kernel: np.ndarray
    head_history: np.ndarray
    head_shift: np.ndarray
    head_rest: np.ndarray
    head_count: np.ndarray
    clearance: np.ndarray


def stack_incidence(seat_rings: int, pile_rings: int, ram_annuli: int = 1,
                    sleeve_bands: tuple[int, int] = (0, 0)
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Incidence of the contacts on the two bodies' ports and the neighbours (module docstring).

    Parameters
    ----------
    seat_rings : int
        S [-].
    pile_rings : int
        K [-].
    ram_annuli : int, default 1
        J [-].
    sleeve_bands : tuple of int, default (0, 0)
        L_a, L_r: the anvil's and the ring's outer faces in this many bands against the
        sleeve [-].

    Returns
    -------
    anvil : numpy.ndarray
        B of the anvil, shape (J + 2 S + 2 L_a, m): -1 where the anvil is a contact's upper
        side, +1 where it is the lower one.
    ring : numpy.ndarray
        B of the ring, shape (2 S + K + 2 L_r, m).
    external : numpy.ndarray
        The ram's (+1) and the pile's (-1) share of each contact's s, shape (2, m).
    """
    S, K, J = seat_rings, pile_rings, ram_annuli
    La, Lr = (int(n) for n in sleeve_bands)
    N = J + S + K + La + Lr
    m = N + S + La + Lr
    Ba, Br = np.zeros((J + 2 * S + 2 * La, m)), np.zeros((2 * S + K + 2 * Lr, m))
    ext = np.zeros((2, m))
    for a in range(J):
        Ba[a, a] = 1.0
        ext[0, a] = 1.0
    for s in range(S):
        Ba[J + s, J + s], Br[s, J + s] = -1.0, 1.0  # the seat's normal contact
        Ba[J + S + s, N + s], Br[S + s, N + s] = -1.0, 1.0  # its friction
    for k in range(K):
        Br[2 * S + k, J + S + k] = -1.0
        ext[1, J + S + k] = -1.0
    for b in range(La):  # the anvil on the fixed sleeve: its upper side, radially and axially
        Ba[J + 2 * S + b, J + S + K + b] = -1.0
        Ba[J + 2 * S + La + b, N + S + b] = -1.0
    for b in range(Lr):
        Br[2 * S + K + b, J + S + K + La + b] = -1.0
        Br[2 * S + K + Lr + b, N + S + La + b] = -1.0
    return Ba, Br, ext


@dataclass
class StackUnit:
    """The anvil and the anvil ring as one unit between the ram and the pile.

    Without a ring it is the anvil unit (:class:`anvilwave.anvil_rom.unit.AnvilUnit`, the
    same kernels on the same arrays). With one, the kernels of this module (module
    docstring); the arrays are :attr:`state` (:class:`StackState`).

    Parameters
    ----------
    anvil : StackBody or ModalAnvil
        The anvil, ports [J ram face annuli, S seat rings axial, S radial] (a ModalAnvil: the
        single-body unit, no ring).
    contact : ContactParameters
        Ram and pile contact springs and dashpots (the pile's: on the ring with one, shared by
        the pile rings' areas).
    ring : StackBody or None, default None
        The anvil ring, ports [S seat rings axial, S radial, K pile rings axial]; None: the
        anvil alone on the pile.
    seat_rings : int, default 1
        S [-].
    pile_rings : int, default 1
        K [-].
    seat_stiffness : float, default 0.0
        Normal penalty of the whole seat [N/m] (> 0 with a ring), shared by the seat rings'
        areas.
    seat_damping : float, default 0.0
        Dashpot of the whole seat [N s/m], shared likewise.
    seat_friction : float, default 0.0
        Coulomb coefficient of the seat [-].
    tangential_stiffness : float or None, default None
        Stick spring of the whole seat [N/m], shared likewise; None: the seat's normal spring
        (as the reference FEA's pairs).
    gravity : float, default GRAVITY
        Gravitational acceleration [m/s^2].
    ram_face : RamFace or None, default None
        The ram's toe in J annuli (:class:`anvilwave.anvil_rom.rings.RamFace`), the anvil's
        ram port in as many; None: the one ram port. With it the ram contacts' spring is the
        ram's residual flexibility between the annuli (the one port's ``ram_stiffness`` is
        the toe's), the dashpot shared by annulus area.
    ram_modes : object or None, default None
        The modal ram's toe modes the face is of
        (:class:`anvilwave.hammer.modal_ram.RamToeModes`), for the runner's ram unit to run
        the same modes; None: the system's.
    head : tuple or None, default None
        The pile rings on a tube head: (D, springs), D (L, K, K) [m/N] what the tube adds to
        the 1D head at each lag (:func:`anvilwave.pile.head_kernel.head_correction`), springs
        (K,) [N/m] the rings' contact springs in place of the pile's shared by area
        (:func:`anvilwave.pile.head_kernel.tube_contact_stiffness`); None: the 1D head.
    sleeve_clearance : float or None, default None
        Radial clearance between the bodies' outer faces and a rigid, fixed guiding sleeve
        [m] (>= 0); None: no sleeve.
    sleeve_bands : tuple of int, default (0, 0)
        L_a, L_r: the anvil's and the ring's outer faces in this many equal-height bands
        against the sleeve [-] (each a compression-only radial contact across the clearance
        and a Coulomb pair along the axis; the bodies' ports after their others: L radial,
        then L axial).
    sleeve_stiffness : float, default 0.0
        The sleeve contact's penalty per unit area [N/m^3] (> 0 with a sleeve), each band's
        spring this times its area; the stick spring the same.
    sleeve_friction : float, default 0.0
        Coulomb coefficient against the sleeve [-].

    Raises
    ------
    InputError
        If a ring is given without a positive seat stiffness, a coefficient is negative, the
        bodies' ports do not match the rings, the bands and the ram face, ``head`` does not
        match the pile rings, or a sleeve has no bands or no positive stiffness.
    """

    anvil: StackBody | ModalAnvil
    contact: ContactParameters
    ring: StackBody | None = None
    seat_rings: int = 1
    pile_rings: int = 1
    seat_stiffness: float = 0.0
    seat_damping: float = 0.0
    seat_friction: float = 0.0
    tangential_stiffness: float | None = None
    gravity: float = GRAVITY
    ram_face: RamFace | None = None
    ram_modes: object | None = None
    head: tuple | None = None
    sleeve_clearance: float | None = None
    sleeve_bands: tuple[int, int] = (0, 0)
    sleeve_stiffness: float = 0.0
    sleeve_friction: float = 0.0

    def __post_init__(self):
        self._h = None
        self.ram_annuli = 1 if self.ram_face is None else self.ram_face.n_annuli
        if self.ring is None:
            self.single = AnvilUnit(self.anvil, self.contact, gravity=self.gravity,
                                    ram_face=self.ram_face)
            self.state = None
            return
        self.single = None
        if not (np.isfinite(self.seat_stiffness) and self.seat_stiffness > 0.0):
            raise InputError("stack", "seat_stiffness",
                             f"must be positive [N/m], got {self.seat_stiffness!r}")
        for key in ("seat_damping", "seat_friction", "sleeve_friction"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value >= 0.0):
                raise InputError("stack", key, f"must be >= 0, got {value!r}")
        S, K = int(self.seat_rings), int(self.pile_rings)
        La, Lr = (0, 0) if self.sleeve_clearance is None else (int(n) for n in self.sleeve_bands)
        if self.sleeve_clearance is not None:
            gap = self.sleeve_clearance
            if not (np.isfinite(gap) and gap >= 0.0):
                raise InputError("stack", "sleeve_clearance", f"must be >= 0 [m], got {gap!r}")
            if min(La, Lr) < 1 or not (np.isfinite(self.sleeve_stiffness)
                                       and self.sleeve_stiffness > 0.0):
                raise InputError("stack", "sleeve_bands", "a sleeve needs at least one band on "
                                                          "each body and a positive "
                                                          "sleeve_stiffness")
        elif self.sleeve_friction > 0.0:
            raise InputError("stack", "sleeve_friction", "needs a sleeve (sleeve_clearance)")
        face = self.ram_face
        J = 1 if face is None else face.n_annuli
        a, r, c = self.anvil, self.ring, self.contact
        if (a.participation.shape[0] != J + 2 * S + 2 * La
                or r.participation.shape[0] != 2 * S + K + 2 * Lr):
            raise InputError("stack", "seat_rings", f"the bodies' ports do not match {J} ram "
                                                    f"annuli, {S} seat and {K} pile rings and "
                                                    f"{La} + {Lr} sleeve bands")
        Ba, Br, ext = stack_incidence(S, K, J, (La, Lr))
        G = Ba.T @ a.residual @ Ba + Br.T @ r.residual @ Br
        seat_share = r.areas[:S] / r.areas[:S].sum()
        pile_share = r.areas[2 * S:2 * S + K] / r.areas[2 * S:2 * S + K].sum()
        band_areas = np.concatenate([a.areas[J + 2 * S:J + 2 * S + La],
                                     r.areas[2 * S + K:2 * S + K + Lr]])
        kt = self.seat_stiffness if self.tangential_stiffness is None \
            else self.tangential_stiffness
        if face is None:
            k_ram = np.array([c.ram_stiffness])
            ram_ratios = np.array([c.ram_damping]) / k_ram
            Cr, Pr, pr = np.zeros((0, 5)), np.zeros((0, 1)), np.zeros(0)
        else:
            G[:J, :J] += face.residual  # the ram's side of the annuli: its contact spring
            k_ram = np.full(J, np.inf)
            # c_a / k_a with c_a the dashpot's area share and k_a = 1 / R_aa (the anvil unit's)
            ram_ratios = c.ram_damping * (a.areas[:J] / a.areas[:J].sum()) * np.diag(face.residual)
            Cr, Pr, pr = face.coefficients(1e-5), face.participation.T, face.toe
        pile_springs = c.pile_stiffness * pile_share
        D = np.zeros((1, K, K))
        if self.head is not None:
            D, pile_springs = (np.ascontiguousarray(x, dtype=float) for x in self.head)
            if D.ndim != 3 or D.shape[1:] != (K, K) or pile_springs.shape != (K,):
                raise InputError("stack", "pile_head", f"the tube head needs ({K}, {K}) lags "
                                                       f"and {K} springs for {K} pile rings, "
                                                       f"got {D.shape} and {pile_springs.shape}")
        k_sleeve = self.sleeve_stiffness * band_areas
        k = np.concatenate([k_ram, self.seat_stiffness * seat_share, pile_springs, k_sleeve,
                            kt * seat_share, k_sleeve])
        N = J + S + K + La + Lr
        P = S + La + Lr
        ratios = np.concatenate([ram_ratios,
                                 self.seat_damping * seat_share / k[J:J + S],
                                 c.pile_damping * pile_share / k[J + S:J + S + K],
                                 np.zeros(La + Lr)])
        A = np.diag(1.0 / k[:N]) + G[:N, :N]
        tube = slice(J + S, J + S + K)
        A[tube, tube] += 0.5 * (D[0] + D[0].T)  # the tube's lag 0 (zero on the 1D head)
        t = np.arange(N, N + P)
        pairs = np.column_stack([np.repeat([float(self.seat_friction),
                                            float(self.sleeve_friction)], [S, La + Lr]),
                                 1.0 / (1.0 / k[t] + G[t, t]),
                                 np.concatenate([np.arange(J, J + S),
                                                 np.arange(J + S + K, N)]).astype(float)])
        clearance = np.zeros(N + P)
        if La + Lr:
            clearance[J + S + K:N] = float(self.sleeve_clearance)
        self.state = StackState(
            np.array([self.gravity, 1.0, S, K], float), _table(a), _table(r),
            np.ascontiguousarray(a.participation.T @ Ba),
            np.ascontiguousarray(r.participation.T @ Br), np.zeros(2 * a.n_modes),
            np.zeros(2 * r.n_modes), ext, k, ratios, pairs, G, A, np.zeros(N + P),
            np.zeros((2, N + P)), np.zeros(P), np.zeros(4), np.zeros(N),
            np.zeros((N, N + 9)),
            np.ascontiguousarray(Cr), np.ascontiguousarray(Pr), np.ascontiguousarray(pr),
            np.zeros((4, pr.size)), np.zeros((3, J)), D, np.zeros((D.shape[0], K)),
            np.zeros((2, K)), np.zeros(K), np.zeros(2), clearance)
        self.set_step(1e-5)

    def set_head(self, head: tuple) -> tuple[float, float]:
        """Put the pile rings on a tube head and rest on it afresh.

        Parameters
        ----------
        head : tuple
            (D, springs) as the field ``head``: D (L, K, K) [m/N], springs (K,) [N/m].

        Returns
        -------
        u_top : float
            The anvil's top face at rest [m] (:meth:`rest_on_pile`).
        force_pile : float
            Pile contact force at rest [N].

        Raises
        ------
        InputError
            If the stack has no ring, or ``head`` does not match the pile rings.
        """
        if self.ring is None:
            raise InputError("stack", "pile_head", "the stack's tube head is under the ring's "
                                                   "pile rings: it needs the ring")
        h = self._h
        self.head = head
        self.__post_init__()
        if h is not None:
            self.set_step(h)
        return self.rest_on_pile(0.0)

    def restart_head(self, state: StackState | None = None) -> None:
        """Start the tube head's history afresh from the present pile-ring forces.

        At a blow's start: its changes are measured from them, the shift is -D[0] F_rest (the
        rest is the same on the tube and the 1D head), the work handed to the tube zero.

        Parameters
        ----------
        state : StackState or None, default None
            The arrays to restart (written); None: the unit's own.
        """
        s = self.state if state is None else state
        J, S = self.ram_annuli, self.seat_rings
        N = J + S + self.pile_rings
        s.head_rest[:] = s.forces[J + S:N]
        s.head_count[:] = 0.0
        s.head_history[:] = 0.0
        s.head_shift[0] = -(s.head_kernel[0] @ s.head_rest)
        s.head_shift[1] = s.head_shift[0]

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
        for body, C, Q in ((self.anvil, s.anvil_coefficients, s.anvil_state),
                           (self.ring, s.ring_coefficients, s.ring_state)):
            n = body.n_modes
            if self._h is not None:
                Q[n:] = Q[:n] - (Q[:n] - Q[n:]) * (h / self._h)
            C[:, :4] = modal_transition(body.omega, body.damping_ratio, h)
        if self.ram_face is not None:
            s.ram_coefficients[:] = self.ram_face.coefficients(h)
        s.parameters[1] = h
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
        return self.anvil.total_mass + self.ring.total_mass

    def rest_on_pile(self, pile_head_displacement: float = 0.0) -> tuple[float, float]:
        """Static equilibrium on the pile under gravity (ram not yet touching); sets the state.

        Frictionless rest (T = 0): the seat rings carry the anvil's weight, the pile rings the
        stack's; which rings carry is found by active set (a ring in tension opens, an
        overlapping open one closes).

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
        S, K, J = self.seat_rings, self.pile_rings, self.ram_annuli
        N = s.active.size
        closed = list(range(J, J + S + K))  # the sleeve's bands start open
        for _ in range(4 * N):
            X, q, gap = _static(self, closed, pile_head_displacement)
            opening = [i for i in closed if X[i] < 0.0]
            closing = [i for i in range(J, N) if i not in closed and gap[i] > 0.0]
            if not opening and not closing:
                break
            closed = sorted(set(closed) - set(opening[:1]) | set(closing[:1]))
        else:
            raise RuntimeError("stack rest: the active set did not settle")
        for qq, Q in zip(q, (s.anvil_state, s.ring_state), strict=True):
            Q[:qq.size] = qq
            Q[qq.size:] = qq
        s.forces[:] = X
        s.active[:] = [1.0 if i in closed else 0.0 for i in range(N)]
        s.slip[:] = 0.0
        s.energies[:] = 0.0
        s.ram_state[:] = 0.0  # the ram's face from rest at the blow's start
        s.ram_offsets[:] = 0.0
        self.restart_head()
        # the ram touches the face's highest annulus first (one port: the face's mean)
        return float(-gap[:J].max()), float(X[J + S:J + S + K].sum())

    def forces(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """Contact forces (F_ram, F_pile) [N] for the neighbour states (feedthrough).

        The seat's normal forces and the friction forces held are kept for :meth:`step`.

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
        stack_step(self.state, FRICTION_SWEEPS)

    @property
    def seat_force(self) -> float:
        """The seat's normal force of the last evaluation [N] (0 without a ring).

        Returns
        -------
        float
            The sum over the seat rings [N].
        """
        if self.state is None:
            return 0.0
        J = self.ram_annuli
        return float(self.state.forces[J:J + self.seat_rings].sum())

    @property
    def friction_energy(self) -> float:
        """Energy the seat's and the sleeve's friction has dissipated [J].

        Returns
        -------
        float
            The sum of :func:`anvilwave.anvil_rom.contact.coulomb_friction`'s dissipation [J].
        """
        return 0.0 if self.state is None else float(self.state.energies[0])

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
        e, h = self.state.energies, self.state.parameters[1]
        return float(e[1] + 0.5 * h * e[3])

    def energy(self, u_ram: float, v_ram: float, u_pile: float, v_pile: float
               ) -> tuple[float, float]:
        """(kinetic, potential) energy of the stack [J] in the conserved (shadow) form.

        Per mode m_e ((q_n - q_n-1) / h)^2 / 2 + w^2 q_n q_n-1 / 2 - g p_grav (q_n + q_n-1) / 2,
        plus the complementary energy X^T (G + diag(1 / k)) X / 2 of the massless part at the
        present forces (normal forces without the dashpots; module docstring); with the ram
        face in annuli also what it adds to the ram unit's energies
        (:func:`anvilwave.anvil_rom.rings.ram_face_energy`).

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
    """The (n, 6) table of a body (step coefficients set by ``set_step``)."""
    C = np.zeros((body.n_modes, 6))
    C[:, 4] = body.omega
    C[:, 5] = body.participation_gravity
    return C


def _static(unit: StackUnit, closed: list, pile: float):
    """Static state with the normal contacts ``closed`` carrying (the others and the ram
    open, no friction): (X, [q_anvil, q_ring], s - G X of every contact)."""
    s = unit.state
    g = unit.gravity
    bodies = ((unit.anvil, s.anvil_loads), (unit.ring, s.ring_loads))

    def residual(z):
        X = np.zeros(s.forces.size)
        X[closed] = z[2:]
        q, equations = [], []
        for b, (body, Q) in enumerate(bodies):
            f = Q @ X + body.participation_gravity * g
            rigid = body.omega == 0.0
            qq = np.where(rigid, z[b], f / np.where(rigid, 1.0, body.omega) ** 2)
            equations.append(f[rigid][0])
            q.append(qq)
        gap = (s.external[1] * pile - s.anvil_loads.T @ q[0] - s.ring_loads.T @ q[1]
               - s.coupling @ X - s.clearance)
        equations.extend(X[closed] / s.stiffness[closed] - gap[closed])
        return np.array(equations), X, q, gap

    n = 2 + len(closed)
    r0 = residual(np.zeros(n))[0]
    J = np.column_stack([residual(e)[0] - r0 for e in np.eye(n)])  # linear: exact
    _, X, q, gap = residual(np.linalg.solve(J, -r0))
    return X, q, gap


@njit(cache=True)
def stack_relative(state, u_ram, v_ram, u_pile, v_pile):
    """Each contact's s and rate from the modes and the neighbours into ``state.relative``.

    s_c = s_ext - sum_b Q_b^T q_b at t_n, its rate with (q_n - q_n-1) / h (module docstring;
    the G X part is the complementarity problem's).

    Parameters
    ----------
    state : StackState
        The stack's arrays (``relative`` written).
    u_ram : float
        Ram toe displacement [m].
    v_ram : float
        Ram toe velocity [m/s].
    u_pile : float
        Pile head displacement [m].
    v_pile : float
        Pile head velocity [m/s].
    """
    h = state.parameters[1]
    x, ext = state.relative, state.external
    m = x.shape[1]
    for c in range(m):
        x[0, c] = ext[0, c] * u_ram + ext[1, c] * u_pile - state.clearance[c]
        x[1, c] = ext[0, c] * v_ram + ext[1, c] * v_pile
    offsets = state.ram_offsets
    if offsets.shape[1] > 1:  # the ram face in annuli: each at the toe plus its offset
        for a in range(offsets.shape[1]):
            x[0, a] += offsets[0, a]
            x[1, a] += offsets[2, a]
    shift = state.head_shift
    first = offsets.shape[1] + int(state.parameters[2])
    if state.head_kernel.shape[0] > 1:  # the tube head: the pile rings' pile side moved down
        for k in range(shift.shape[1]):
            x[0, first + k] -= shift[0, k]
    for body in range(2):
        Q = state.anvil_loads if body == 0 else state.ring_loads
        S = state.anvil_state if body == 0 else state.ring_state
        n = Q.shape[0]
        for j in range(n):
            q = S[j]
            qd = (q - S[n + j]) / h
            for c in range(m):
                x[0, c] -= Q[j, c] * q
                x[1, c] -= Q[j, c] * qd


@njit(cache=True)
def _normal_forces(state, with_dashpots, out, active):
    """The normal forces' complementarity problem into ``out`` (module docstring), the
    friction forces held; ``with_dashpots`` False: the elastic parts."""
    x, G, X = state.relative, state.coupling, state.forces
    N = out.shape[0]
    m = X.shape[0]
    g = state.work[:, N + 2]
    for i in range(N):
        g[i] = x[0, i]
        for t in range(N, m):
            g[i] -= G[i, t] * X[t]
        if with_dashpots:
            g[i] += state.ratios[i] * x[1, i]
    contact_lcp(state.flexibility, g, out, active, state.work[:, :N + 1])


@njit(cache=True)
def stack_forces(state, u_ram, v_ram, u_pile, v_pile):
    """Contact forces (F_ram, F_pile) [N] at t_n for the neighbour states (feedthrough).

    The normal forces are kept in ``state.forces`` for :func:`stack_step`, the dashpots'
    power in ``state.energies[3]``.

    Parameters
    ----------
    state : StackState
        The stack's arrays (``relative``, ``forces``, ``active``, ``energies`` written).
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
    stack_relative(state, u_ram, v_ram, u_pile, v_pile)
    N = state.active.shape[0]
    F = state.work[:, N + 3]
    _normal_forces(state, True, F, state.active)
    power = 0.0
    damped = False
    for i in range(N):
        if state.ratios[i] > 0.0:
            damped = True
    if damped:
        Fe = state.work[:, N + 4]
        start = state.work[:, N + 5]  # the active set, a copy (the elastic solve's own)
        for i in range(N):
            start[i] = state.active[i]
        _normal_forces(state, False, Fe, start)
        for i in range(N):
            power += (F[i] - Fe[i]) * state.relative[1, i]
    state.energies[3] = power  # booked over the step by stack_step
    for i in range(N):
        state.forces[i] = F[i]
    S = int(state.parameters[2])
    J = state.ram_offsets.shape[1]
    ram = F[0]
    for a in range(1, J):
        ram += F[a]
    pile = 0.0
    for i in range(J + S, J + S + int(state.parameters[3])):
        pile += F[i]
    return ram, pile


@njit(cache=True)
def stack_step(state, sweeps):
    """Update the friction pairs at t_n, then advance both bodies over h with the forces held.

    Each pair's force by return mapping (:func:`anvilwave.anvil_rom.contact.coulomb_friction`)
    on the increment of its w under the cone mu F_n of its normal contact (module docstring),
    ``sweeps`` Gauss-Seidel sweeps over the pairs, the dissipation added to
    ``state.energies[0]``; then
    every mode of each body by the exact step with all contact forces and gravity held; then,
    with the ram face in annuli, their offsets from the ram's toe
    (:func:`anvilwave.anvil_rom.rings.ram_face_advance`, the annuli's forces held).

    Parameters
    ----------
    state : StackState
        The stack's arrays after :func:`stack_forces` at t_n (states, ``forces``, ``slip``,
        ``energies``, ``ram_state``, ``ram_offsets`` written).
    sweeps : int
        Gauss-Seidel sweeps [-].
    """
    P, x, X, G, e = state.parameters, state.relative, state.forces, state.coupling, state.energies
    N = state.active.shape[0]
    m = X.shape[0]
    S = m - N  # the friction pairs, the seat's and the sleeve's
    J = state.ram_offsets.shape[1]
    base = state.work[:S, N + 6]
    T0 = state.work[:S, N + 7]  # the friction forces at the step's start
    dissipated = state.work[:S, N + 8]
    for p in range(S):
        t = N + p
        base[p] = x[0, t]
        for i in range(N):
            base[p] -= G[t, i] * X[i]
        T0[p] = X[t]
        dissipated[p] = 0.0
    if e[2] == 0.0:
        for p in range(S):
            w = base[p]
            for u in range(S):
                if u != p:
                    w -= G[N + p, N + u] * T0[u]
            state.slip[p] = w
        e[2] = 1.0
    for _ in range(sweeps):
        for p in range(S):
            w = base[p]
            for u in range(S):
                if u != p:
                    w -= G[N + p, N + u] * X[N + u]
            X[N + p], dissipated[p] = coulomb_friction(
                T0[p], w - state.slip[p], X[int(state.friction_pairs[p, 2])],
                state.friction_pairs[p, 0], state.friction_pairs[p, 1])
    for p in range(S):
        w = base[p]
        for u in range(S):
            if u != p:
                w -= G[N + p, N + u] * X[N + u]
        state.slip[p] = w
        e[0] += dissipated[p]
    e[1] += e[3] * P[1]
    gravity = P[0]
    for body in range(2):
        C = state.anvil_coefficients if body == 0 else state.ring_coefficients
        Q = state.anvil_loads if body == 0 else state.ring_loads
        Z = state.anvil_state if body == 0 else state.ring_state
        n = C.shape[0]
        for j in range(n):
            f = C[j, 5] * gravity
            for c in range(m):
                f += Q[j, c] * X[c]
            q = Z[j]
            Z[j] = C[j, 0] * q + C[j, 1] * Z[n + j] + C[j, 2] * f
            Z[n + j] = q
    if J > 1:
        ram_face_advance(state, P[1])
    if state.head_kernel.shape[0] > 1:
        stack_head_push(state)


@njit(cache=True)
def stack_head_push(state):
    """After a step with the forces held: the tube head's history and its next shift.

    The single anvil's rule (:func:`anvilwave.anvil_rom.rings.head_push`, one function:
    :func:`anvilwave.anvil_rom.rings.head_push_forces`) on the stack's pile contacts
    J + S .. N - 1: their forces less their rest into the history, the next shift sum over
    m >= 1 of D[m] (F_(n+1-m) - F_rest) - D[0] F_rest, and the work of the forces on the step
    that ended (their trapezoid over its shift's change) added to ``head_count[1]``.

    Parameters
    ----------
    state : StackState
        The stack's arrays (``head_history``, ``head_shift``, ``head_count`` written).
    """
    head_push_forces(state.forces, state.ram_offsets.shape[1] + int(state.parameters[2]),
                     state.head_kernel, state.head_history, state.head_shift, state.head_rest,
                     state.head_count)


@njit(cache=True)
def stack_energy(state, u_ram, v_ram, u_pile, v_pile):
    """(kinetic, potential) energy of the stack [J] (:meth:`StackUnit.energy`).

    Parameters
    ----------
    state : StackState
        The stack's arrays (``relative`` written; the kept forces and active set unchanged).
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
    h = P[1]
    kinetic = 0.0
    total = 0.0
    for body in range(2):
        C = state.anvil_coefficients if body == 0 else state.ring_coefficients
        Z = state.anvil_state if body == 0 else state.ring_state
        n = C.shape[0]
        for j in range(n):
            q, qp = Z[j], Z[n + j]
            rate = (q - qp) / h
            kinetic += 0.5 * C[j, 3] * rate * rate
            total += 0.5 * C[j, 4] ** 2 * q * qp - P[0] * C[j, 5] * 0.5 * (q + qp)
    if state.ram_offsets.shape[1] > 1:  # what the ram's face in annuli adds to the ram unit's
        face_kinetic, face_strain = ram_face_energy(state, h)
        kinetic += face_kinetic
        total += face_strain
    stack_relative(state, u_ram, v_ram, u_pile, v_pile)
    N = state.active.shape[0]
    F = state.work[:, N + 4]
    start = state.work[:, N + 5]  # the active set, a copy (the kept one unchanged)
    for i in range(N):
        start[i] = state.active[i]
    _normal_forces(state, False, F, start)
    G, k, X = state.coupling, state.stiffness, state.forces
    m = X.shape[0]
    for i in range(m):  # X with its normal part the elastic forces F
        xi = F[i] if i < N else X[i]
        total += 0.5 * xi * xi / k[i]
        for j in range(m):
            xj = F[j] if j < N else X[j]
            total += 0.5 * xi * G[i, j] * xj
    D = state.head_kernel  # the tube head: its lag 0's complementary energy, the work handed
    first = state.ram_offsets.shape[1] + int(P[2])  # on (zeros on the 1D head)
    for k in range(D.shape[1]):
        for l in range(D.shape[1]):
            total += 0.25 * F[first + k] * (D[0, k, l] + D[0, l, k]) * F[first + l]
    total += state.head_count[1]
    return kinetic, total


@njit(cache=True)
def stack_interface(state):
    """The stack's outward faces at t_n: the anvil's ram face and the ring's pile port.

    Each the mean over its ports of the face's displacement, the kept modes' plus the residual
    flexibility's share under the forces of the last :func:`stack_forces` (module docstring:
    the ram port's u_ram - s, the pile rings' u_pile + s), and of the modes' rate: the records'
    and the FMU's ``u_top`` and ``u_bottom``; at rest ``u_top`` is where
    :meth:`StackUnit.rest_on_pile` puts the ram's first touch (one port). With the ram face in
    annuli the ram's own residual flexibility between them is in the same coupling, and only
    the other contacts' share is added.

    Parameters
    ----------
    state : StackState
        The stack's arrays.

    Returns
    -------
    u_top : float
        The anvil's ram face [m] (positive down).
    v_top : float
        Its velocity [m/s].
    u_bottom : float
        The ring's pile port [m].
    v_bottom : float
        Its velocity [m/s].
    """
    h = state.parameters[1]
    J = state.ram_offsets.shape[1]
    S = int(state.parameters[2])
    n_a = state.anvil_loads.shape[0]
    n_r = state.ring_loads.shape[0]
    G, X = state.coupling, state.forces
    m = X.shape[0]
    first = 0 if J == 1 else J
    u_top = 0.0
    v_top = 0.0
    for a in range(J):  # the anvil is the ram contacts' lower side: Q = +participation
        for j in range(n_a):
            q = state.anvil_state[j]
            u_top += state.anvil_loads[j, a] * q / J
            v_top += state.anvil_loads[j, a] * (q - state.anvil_state[n_a + j]) / (h * J)
        for c in range(first, m):
            u_top += G[a, c] * X[c] / J
    u_bottom = 0.0
    v_bottom = 0.0
    K = int(state.parameters[3])
    for c in range(J + S, J + S + K):  # the ring is the pile contacts' upper side: Q = -part.
        for j in range(n_r):
            q = state.ring_state[j]
            u_bottom -= state.ring_loads[j, c] * q / K
            v_bottom -= state.ring_loads[j, c] * (q - state.ring_state[n_r + j]) / (h * K)
        for i in range(m):
            u_bottom -= G[c, i] * X[i] / K
    return u_top, v_top, u_bottom, v_bottom


STACK_FIELDS = ("omega", "participation", "residual", "participation_gravity", "total_mass",
                "areas", "damping_ratio")
"""The arrays of a :class:`StackBody` in a stack data file (:func:`save_stack_data`)."""


def save_stack_data(path, unit: StackUnit) -> None:
    """Write a stack's bodies, seat and sleeve (one ram port) to ``path`` (``.npz``), for the FMU.

    Parameters
    ----------
    path : str or pathlib.Path
        The file written.
    unit : StackUnit
        A stack with a ring and the one ram port.

    Raises
    ------
    InputError
        If the stack has no ring or its ram face is in annuli (the FMU's one toe port).
    """
    if unit.ring is None or unit.ram_face is not None:
        raise InputError("stack", "ram_annuli", "the stack data file is of an anvil and a ring "
                                                "with the one ram port")
    arrays = {f"{b}_{f}": np.asarray(getattr(body, f), float)
              for b, body in (("anvil", unit.anvil), ("ring", unit.ring)) for f in STACK_FIELDS}
    kt = unit.seat_stiffness if unit.tangential_stiffness is None else unit.tangential_stiffness
    gap = np.nan if unit.sleeve_clearance is None else unit.sleeve_clearance
    np.savez(path, seat=np.array([unit.seat_rings, unit.pile_rings, unit.seat_stiffness,
                                  unit.seat_damping, kt], float),
             sleeve=np.array([gap, *unit.sleeve_bands, unit.sleeve_stiffness], float), **arrays)


def load_stack_data(path) -> tuple[StackBody, StackBody, dict]:
    """The bodies and seat of a stack data file (:func:`save_stack_data`).

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.npz`` file.

    Returns
    -------
    anvil : StackBody
        The anvil.
    ring : StackBody
        The anvil ring.
    seat : dict
        ``seat_rings``, ``pile_rings`` [-], ``seat_stiffness`` [N/m], ``seat_damping``
        [N s/m], ``tangential_stiffness`` [N/m], ``sleeve_clearance`` [m] (None: no sleeve),
        ``sleeve_bands`` [-], ``sleeve_stiffness`` [N/m^3]: :class:`StackUnit`'s keywords (the
        sleeve's friction coefficient is the caller's, as the seat's).
    """
    with np.load(path) as npz:
        bodies = [StackBody(*(float(npz[f"{b}_{f}"]) if npz[f"{b}_{f}"].ndim == 0
                              else np.array(npz[f"{b}_{f}"]) for f in STACK_FIELDS))
                  for b in ("anvil", "ring")]
        seat = npz["seat"]
        sleeve = npz["sleeve"] if "sleeve" in npz else np.array([np.nan, 0.0, 0.0, 0.0])
    return bodies[0], bodies[1], {"seat_rings": int(seat[0]), "pile_rings": int(seat[1]),
                                  "seat_stiffness": float(seat[2]),
                                  "seat_damping": float(seat[3]),
                                  "tangential_stiffness": float(seat[4]),
                                  "sleeve_clearance": None if np.isnan(sleeve[0])
                                  else float(sleeve[0]),
                                  "sleeve_bands": (int(sleeve[1]), int(sleeve[2])),
                                  "sleeve_stiffness": float(sleeve[3])}
