"""Reference impact FEA: ram + anvil + pile top, axisymmetric, explicit (the paper's Fig. 1).

The ram (solid steel cylinder), the anvil (an :class:`~anvilwave.anvil_rom.fem.geometry.AnvilSpec`
outline)
and the pile (steel tube, to full length or truncated with an absorbing boundary) are three
axisymmetric elastic bodies (see :mod:`anvilwave.fea.bodies`) that touch through
compression-only node-to-node penalty contacts on conforming faces (lift-off and re-impact
allowed), integrated with central differences (:mod:`anvilwave.fea.solver`). Optionally an
anvil ring (``FeaConfig.ring``) sits between anvil and pile, and any contact carries Coulomb
friction along its faces (``*_friction``, :func:`anvilwave.anvil_rom.contact.coulomb_friction`).

Elements: quadratic (6-node triangles in the anvil, 9-node quadrilaterals in the ram and the
pile tube), HRZ-lumped. Against linear elements at the same number of DOFs they halve the phase
error of the waves (dispersion O((kh)^4) instead of O((kh)^2)) and do not lock in bending (the
anvil's bending wave lifts it off the pile); the price, a stable step of ~0.4 h / c_p instead
of ~h / c_p, is paid back by elements twice as large. With ``mesh_size`` = 0.1 m (node spacing
5 cm) a 10 kHz shear wave (0.32 m) has 6 nodes per wavelength, a 5 kHz one 13; halving the
size changes the Table 1 forces by ~1 % RMS (peaks by < 0.5 %, pile force; 2 % ram force).

Stack (z down, t = 0 at first ram-anvil contact): the anvil top face is z = 0, the ram lies on
it (z in [-L_ram, 0]) moving down at ``impact_velocity``, stress free; the pile top touches the
anvil bottom face. At t = 0 anvil and pile are in static equilibrium under gravity: the static
problem (anvil + modelled pile, contacts closed where compressed, pile bottom supported
axially) is solved once with a sparse direct solver, and the support reaction is then held as
a constant force at the pile bottom. (A gravity ramp would need a long damped run to settle and
leave residual vibrations; the static solve is exact, ~0.1 s, and gives zero acceleration of
anvil and pile at t = 0.) The ram falls under gravity too (lumped weights: no stress from it).
With a truncated pile, the bottom also carries a viscous (Lysmer-type) dashpot that absorbs the
down-going wave: the cut behaves like the rest of an infinitely long pile (statically it
carries the weight above it, dynamically its impedance). Without truncation the pile toe is
free apart from the constant support force (no soil: the paper's 25 ms window ends before the
toe reflection of an 80 m pile returns, 2 L / c0 = 31 ms after it left the head).

Outputs follow DESIGN.md: compression positive, velocities positive down, SI units.
"""

from __future__ import annotations

import numbers
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from anvilwave.anvil_rom.fem.geometry import STEEL, AnvilSpec, Interfaces, Material
from anvilwave.anvil_rom.fem.mesh import (
    mesh_outline,
    split_outline_at_interfaces,
    split_outline_at_radii,
    to_skfem,
)
from anvilwave.fea.bodies import (
    Body,
    ContactSet,
    Face,
    contact_between,
    dashpot_damping,
    face,
    graded_vertices,
    make_body,
    section_force_row,
    sleeve_contact,
    static_preload,
    tensor_body,
    vertex_radii,
)
from anvilwave.fea.solver import ExplicitSystem, HighPassDashpots, Transient, integrate
from anvilwave.inputs import InputError

DEFAULT_CONTACT_STIFFNESS_FACTOR = 1.0
"""alpha in the penalty stiffness per unit area alpha * E / h [-] (h: element size at the face).

A penalty layer of stiffness alpha E / h per area is as compliant as a slab of the body's own
material h / alpha thick: alpha = 1 adds one element layer of compliance (a delay of about
h / c0 = 20 us for h = 0.1 m, 0.1 % of a 13.8 m ram's compliance). It leaves the stable step of
the Table 1 stack unchanged (the small anvil elements at the pile ring set it) and keeps the
pair frequency below the chatter limit (:data:`anvilwave.fea.solver.CONTACT_PHASE_LIMIT`); a
stiffer penalty shortens the step there as 1 / sqrt(alpha).
"""


def absorbing_speeds(material: Material, kind: str = "bar") -> tuple[float, float]:
    """Wave speeds [m/s] of the dashpot boundary (axial, radial).

    ``kind`` = "bar": axial rho c0 with c0 = sqrt(E / rho), radial rho c_s: the impedance
    E A / c0 of a bar wave (and of the 1D pile models). A bar or a pile wall has free lateral
    faces, so its long waves travel at c0, not at the dilatational speed c_p of an unbounded
    solid: the classical Lysmer rho c_p is mismatched by (c_p - c0) / (c_p + c0) = 7.4 % and
    reflects that much (measured 7.8 %, tests/test_fea.py), rho c0 reflects 1.6 % of a sharp
    pulse in a solid bar (its Pochhammer-Chree ringing). In a large-radius tube the content
    above the ring frequency c0 / (2 pi R) travels as a plate wave, c_pl = c0 / sqrt(1 - nu^2),
    2.4 % impedance mismatch: rho c0 reflects 3.8 % of a sharp pulse in the 8 m pile.
    ``kind`` = "plate": axial rho c_pl, c_pl = c0 / sqrt(1 - nu^2), radial rho c_s: the speed of
    a wall whose hoop strain is held by its radial inertia (a large-radius tube above its ring
    frequency c0 / (2 pi R)).
    ``kind`` = "shell": "bar" plus, on the axial DOFs, high-pass dashpots (see
    :func:`absorbing_boundary`) that raise the impedance to rho c_pl above the ring frequency:
    1.7 % reflection of the sharp pulse in the 8 m pile; in the Table 1 run a 10 m pile cut
    changes the anvil-pile force by at most 2.6 % of its peak (RMS 1.3 %) against the full
    80 m pile.
    ``kind`` = "p": Lysmer & Kuhlemeyer (1969), axial rho c_p, radial rho c_s.

    Parameters
    ----------
    material : Material
        Material of the cut body.
    kind : {"bar", "plate", "shell", "p"}
        The boundary kind (see above).

    Returns
    -------
    axial : float
        Wave speed on the axial DOFs [m/s].
    radial : float
        Wave speed on the radial DOFs [m/s].

    Raises
    ------
    ValueError
        If ``kind`` is unknown.

    References
    ----------
    Lysmer, J., Kuhlemeyer, R.L. (1969). Finite dynamic model for infinite media. J. Eng. Mech.
    Div. 95(4), 859-877. https://doi.org/10.1061/JMCEA3.0001144
    """
    c_s = material.shear_wave_speed
    if kind in ("bar", "shell"):
        return material.bar_wave_speed, c_s
    if kind == "plate":
        return material.bar_wave_speed / np.sqrt(1.0 - material.poisson_ratio**2), c_s
    if kind == "p":
        E, nu, rho = material.youngs_modulus, material.poisson_ratio, material.density
        return float(np.sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)), c_s
    raise ValueError(f"unknown absorbing boundary kind {kind!r}: use bar, plate, shell or p")


def absorbing_boundary(f: Face, material: Material, n: int, kind: str = "bar"
                       ) -> tuple[np.ndarray, HighPassDashpots | None]:
    """Dashpots (and for "shell" high-pass dashpots) of the absorbing pile cut on face ``f``.

    "shell": the axial impedance of a thin tube of mid-radius R rises from rho c0 A below the
    ring frequency omega_r = c0 / R (hoop strain free, bar wave) to rho c_pl A above it (hoop
    strain held by the radial inertia, plate wave); a dashpot rho (c_pl - c0) a_i to a free
    mass, corner rate omega_r, added to the rho c0 a_i dashpot follows that rise (the membrane
    shell's stop band near omega_r, where the true impedance swings from 0 to infinity, is not
    represented).

    Parameters
    ----------
    f : Face
        The cut face.
    material : Material
        Material of the pile.
    n : int
        Number of global DOFs.
    kind : {"bar", "plate", "shell", "p"}
        The boundary kind, see :func:`absorbing_speeds`.

    Returns
    -------
    damping : numpy.ndarray
        Diagonal damping, shape (n,) [N s/m].
    high_pass : HighPassDashpots or None
        The high-pass dashpots ("shell"), else None.

    Raises
    ------
    ValueError
        If "shell" is asked for a face on the axis (not a tube).
    """
    c_ax, c_rad = absorbing_speeds(material, kind)
    damping = dashpot_damping(f, material, n, c_ax, c_rad)
    if kind != "shell":
        return damping, None
    c_pl = absorbing_speeds(material, "plate")[0]
    radius = float(np.sum(f.weights * f.radii) / f.area)
    if f.radii.min() <= 0.0:
        raise ValueError("the 'shell' boundary needs a tube (no axis on the face)")
    return damping, HighPassDashpots(f.axial_dofs.copy(),
                                     material.density * (c_pl - c_ax) * f.weights,
                                     c_ax / radius)


# --------------------------------------------------------------------------- configuration


@dataclass(frozen=True)
class FeaConfig:
    """Ram + anvil + pile impact configuration.

    Parameters
    ----------
    ram_radius : float
        Radius of the solid cylindrical ram [m].
    ram_length : float
        Ram length [m].
    impact_velocity : float
        Ram velocity at first contact, downward [m/s].
    anvil : AnvilSpec
        The anvil (its outline; its own ``interfaces`` are not used: the ram radius and the
        pile section define the contact faces).
    pile_outer_diameter : float
        Pile top outer diameter [m].
    pile_wall_thickness : float
        Pile wall thickness [m].
    pile_length : float
        Pile length [m].
    truncate_length : float, optional
        Modelled pile length with an absorbing bottom [m]; None: full length.
    gauge_depth : float, default 1.0
        Depth of the strain-gauge section below the pile top [m].
    duration : float, default 0.025
        Simulated time [s].
    mesh_size : float, default 0.1
        Element size in the anvil and the ram [m] (quadratic elements).
    pile_wall_elements : int, default 3
        Quadratic elements through the pile wall [-] (also on the anvil's bearing ring, whose
        nodes the pile shares).
    pile_axial_size : float, optional
        Axial element size of the pile [m]; None: ``mesh_size``.
    ram_axial_size : float, optional
        Axial element size of the ram [m]; None: ``mesh_size``.
    gravity : float, default 9.81
        Gravitational acceleration [m/s^2] (0 switches the preload off).
    material : Material, default STEEL
        Steel of the ram and the pile (the anvil has its own).
    output_interval : float, default 1e-5
        Output time step [s].
    contact_stiffness_factor : float, default DEFAULT_CONTACT_STIFFNESS_FACTOR
        alpha of the penalty stiffness alpha E / h per area [-].
    absorbing_boundary : {"shell", "bar", "plate", "p"}
        See :func:`absorbing_speeds` and :func:`absorbing_boundary`.
    time_step_safety : float, default 0.9
        Fraction of the critical step used [-].
    ring : AnvilSpec, optional
        An anvil ring between the anvil and the pile (its outline, a polygon off the axis
        with a flat top face, the seat under the anvil's flat bottom face, and a flat bottom
        face carrying the pile wall); None: the anvil bears on the pile directly.
    ram_anvil_friction : float, default 0.0
        Coulomb coefficient between the ram face and the anvil [-].
    seat_friction : float, default 0.0
        Coulomb coefficient on the anvil-ring seat [-] (needs ``ring``).
    pile_friction : float, default 0.0
        Coulomb coefficient between the pile head and the body on it (anvil or ring) [-].
    sleeve_radius : float, optional
        Inner radius of a rigid guiding sleeve around the anvil (and the ring) [m], at least
        their outer radii: the radial clearance closes as they bulge; None: no sleeve. The
        static preload is solved without it (a clearance below the bulge under the weight
        starts the blow with the sleeve pressed).
    sleeve_friction : float, default 0.0
        Coulomb coefficient against the sleeve (axial sliding) [-].

    Attributes
    ----------
    modelled_pile_length : float
        Length of pile in the model [m].
    pile_ring : tuple of float
        Inner and outer radius of the pile wall [m].

    Raises
    ------
    InputError
        If a value breaks its rule (checked on construction).
    """

    ram_radius: float
    ram_length: float
    impact_velocity: float
    anvil: AnvilSpec
    pile_outer_diameter: float
    pile_wall_thickness: float
    pile_length: float
    truncate_length: float | None = None
    gauge_depth: float = 1.0
    duration: float = 0.025
    mesh_size: float = 0.1
    pile_wall_elements: int = 3
    pile_axial_size: float | None = None
    ram_axial_size: float | None = None
    gravity: float = 9.81
    material: Material = STEEL
    output_interval: float = 1e-5
    contact_stiffness_factor: float = DEFAULT_CONTACT_STIFFNESS_FACTOR
    absorbing_boundary: str = "shell"
    time_step_safety: float = 0.9
    ring: AnvilSpec | None = None
    ram_anvil_friction: float = 0.0
    seat_friction: float = 0.0
    pile_friction: float = 0.0
    sleeve_radius: float | None = None
    sleeve_friction: float = 0.0

    def __post_init__(self):
        src = "FeaConfig"
        positive = ("ram_radius", "ram_length", "impact_velocity", "pile_outer_diameter",
                    "pile_wall_thickness", "pile_length", "gauge_depth", "duration", "mesh_size",
                    "output_interval", "contact_stiffness_factor")
        for key in positive:
            value = getattr(self, key)
            if not (isinstance(value, numbers.Real) and np.isfinite(value) and value > 0):
                raise InputError(src, key, f"must be a positive number, got {value!r}")
        for key in ("truncate_length", "pile_axial_size", "ram_axial_size"):
            value = getattr(self, key)
            if value is not None and not (np.isfinite(value) and value > 0):
                raise InputError(src, key, f"must be positive or None, got {value!r}")
        if not (np.isfinite(self.gravity) and self.gravity >= 0):
            raise InputError(src, "gravity", f"must be >= 0, got {self.gravity!r}")
        if int(self.pile_wall_elements) != self.pile_wall_elements or self.pile_wall_elements < 1:
            raise InputError(src, "pile_wall_elements", "must be a positive integer")
        if not 0 < self.time_step_safety <= 1:
            raise InputError(src, "time_step_safety", "must be in (0, 1]")
        if self.pile_wall_thickness >= 0.5 * self.pile_outer_diameter:
            raise InputError(src, "pile_wall_thickness", "must be less than the pile radius")
        if self.anvil.outline is None:
            raise InputError(src, "anvil", "the reference FEA needs an anvil outline (a "
                                           "[geometry] polygon), not a mesh file")
        # a contact radius that nearly, but not exactly, meets an outline vertex would leave a
        # sliver element there and a stable step a thousand times smaller
        top = self.anvil.outline[:, 1].min()
        for r in self.anvil.outline[np.abs(self.anvil.outline[:, 1] - top) < 1e-12, 0]:
            gap = abs(r - self.ram_radius)
            if 0.0 < gap < 0.1 * self.mesh_size:
                raise InputError(src, "ram_radius", f"{self.ram_radius:g} m is {gap:.2g} m "
                                                    f"from the anvil's top-face vertex at r = "
                                                    f"{r:g} m: make them equal")
        if self.truncate_length is not None and self.truncate_length > self.pile_length:
            raise InputError(src, "truncate_length", "must not exceed pile_length")
        if self.gauge_depth >= self.modelled_pile_length:
            raise InputError(src, "gauge_depth", "must lie inside the modelled pile length")
        n_out = self.duration / self.output_interval
        if abs(n_out - round(n_out)) > 1e-6 * n_out:
            raise InputError(src, "duration", "must be a whole number of output_interval")
        absorbing_speeds(self.material, self.absorbing_boundary)
        for key in ("ram_anvil_friction", "seat_friction", "pile_friction", "sleeve_friction"):
            value = getattr(self, key)
            if not (isinstance(value, numbers.Real) and np.isfinite(value) and value >= 0):
                raise InputError(src, key, f"must be a number >= 0, got {value!r}")
        if self.ring is None and self.seat_friction > 0:
            raise InputError(src, "seat_friction", "needs a ring (the seat is the anvil-ring "
                                                   "contact)")
        if self.ring is not None and (self.ring.outline is None
                                      or self.ring.outline[:, 0].min() <= 0.0):
            raise InputError(src, "ring", "the reference FEA needs the ring as an outline (a "
                                          "[geometry] polygon off the axis)")
        if self.sleeve_radius is not None:
            outer = max(self.anvil.outline[:, 0].max(), 0.0 if self.ring is None
                        else self.ring.outline[:, 0].max())
            if not (np.isfinite(self.sleeve_radius) and self.sleeve_radius >= outer):
                raise InputError(src, "sleeve_radius", f"must be at least the outer radius "
                                                       f"{outer:g} m of the anvil (and ring)")
        elif self.sleeve_friction > 0:
            raise InputError(src, "sleeve_friction", "needs a sleeve (sleeve_radius)")

    @property
    def modelled_pile_length(self) -> float:
        """Length of pile in the model [m]."""
        return self.pile_length if self.truncate_length is None else self.truncate_length

    @property
    def pile_ring(self) -> tuple[float, float]:
        """Inner and outer radius of the pile wall [m]."""
        r_out = 0.5 * self.pile_outer_diameter
        return r_out - self.pile_wall_thickness, r_out


@dataclass
class FeaResult:
    """Time histories on the output grid (DESIGN.md conventions) and run statistics.

    Parameters
    ----------
    time : numpy.ndarray
        Output times [s].
    ram_anvil_force : numpy.ndarray
        Ram-anvil contact resultant [N], compression positive.
    anvil_pile_force : numpy.ndarray
        Anvil-pile contact resultant [N], compression positive.
    pile_head_velocity : numpy.ndarray
        Area-weighted mean axial velocity of the pile top face [m/s].
    gauge_force : numpy.ndarray
        Axial force across the pile section at ``gauge_depth`` [N].
    gauge_velocity : numpy.ndarray
        Mean axial velocity on that section [m/s].
    ram_velocity : numpy.ndarray
        Mean (momentum / mass) ram velocity [m/s].
    energies : dict of str to numpy.ndarray
        Name -> energy history [J], see :class:`anvilwave.fea.solver.Transient`.
    n_dof : int
        Number of DOFs [-].
    n_steps : int
        Number of time steps [-].
    time_step : float
        Time step [s].
    critical_time_step : float
        Critical (stable) time step [s].
    wall_time : float
        Wall time of the stepping alone [s].
    setup_time : float
        Wall time of meshing, assembly, statics and stable step [s].
    info : dict
        Masses, preload, ...
    anvil_ring_force : numpy.ndarray, optional
        Anvil-ring seat resultant [N] with a ring (``anvil_pile_force`` is then the ring-pile
        force, the force into the pile head); None without.
    sleeve_force : numpy.ndarray, optional
        Radial resultant of the sleeve on the anvil and the ring [N] (sum of the node forces,
        inward positive); None without a sleeve.
    """

    time: np.ndarray
    ram_anvil_force: np.ndarray
    anvil_pile_force: np.ndarray
    pile_head_velocity: np.ndarray
    gauge_force: np.ndarray
    gauge_velocity: np.ndarray
    ram_velocity: np.ndarray
    energies: dict[str, np.ndarray]
    n_dof: int
    n_steps: int
    time_step: float
    critical_time_step: float
    wall_time: float
    setup_time: float
    info: dict = field(default_factory=dict)
    anvil_ring_force: np.ndarray | None = None
    sleeve_force: np.ndarray | None = None

    def to_columns(self) -> dict[str, np.ndarray]:
        """CSV columns named ``name [unit]`` (DESIGN.md), energies included.

        Returns
        -------
        dict of str to numpy.ndarray
            The columns.
        """
        cols = {
            "time [s]": self.time,
            "ram_anvil_force [N]": self.ram_anvil_force,
            "anvil_pile_force [N]": self.anvil_pile_force,
            "pile_head_velocity [m/s]": self.pile_head_velocity,
            "gauge_force [N]": self.gauge_force,
            "gauge_velocity [m/s]": self.gauge_velocity,
            "ram_velocity [m/s]": self.ram_velocity,
        }
        if self.anvil_ring_force is not None:
            cols["anvil_ring_force [N]"] = self.anvil_ring_force
        if self.sleeve_force is not None:
            cols["sleeve_force [N]"] = self.sleeve_force
        for name, values in self.energies.items():
            cols[f"{name}_energy [J]"] = values
        return cols


# --------------------------------------------------------------------------- model building


@dataclass
class ImpactModel:
    """The assembled stack before time stepping (inspect it, or pass it to :func:`integrate`).

    Parameters
    ----------
    system : ExplicitSystem
        The assembled system with its initial state.
    bodies : dict of str to Body
        The bodies by name.
    faces : dict of str to Face
        The named faces (contacts, boundaries, probes).
    info : dict
        Masses, preload, element counts, ...
    """

    system: ExplicitSystem
    bodies: dict[str, Body]
    faces: dict[str, Face]
    info: dict


def _place(bodies: list[Body]) -> int:
    offset = 0
    for b in bodies:
        b.offset = offset
        offset += b.n_dof
    return offset


def _global(bodies: list[Body]) -> tuple[sp.csr_matrix, np.ndarray]:
    K = sp.block_diag([b.model.stiffness for b in bodies], format="csr")
    M = np.concatenate([b.lumped_mass for b in bodies])
    return K, M


def mean_velocity_weights(f: Face, n: int) -> np.ndarray:
    """Weights w with w @ v = area-weighted mean axial velocity of a face [-].

    Parameters
    ----------
    f : Face
        The face.
    n : int
        Number of global DOFs.

    Returns
    -------
    numpy.ndarray
        w, shape (n,) [-].
    """
    w = np.zeros(n)
    w[f.axial_dofs] = f.weights / f.area
    return w


def body_velocity_weights(body: Body, n: int) -> np.ndarray:
    """Weights w with w @ v = momentum / mass, the mean axial velocity of a body [-].

    Parameters
    ----------
    body : Body
        The body.
    n : int
        Number of global DOFs.

    Returns
    -------
    numpy.ndarray
        w, shape (n,) [-].
    """
    w = np.zeros(n)
    ez = body.axial_indicator()
    w[body.offset:body.offset + body.n_dof] = body.lumped_mass * ez / body.mass
    return w


def _flat_face_radii(outline: np.ndarray, z: float, tol: float) -> np.ndarray:
    """Radii of the outline vertices on the line z [m]."""
    return outline[np.abs(outline[:, 1] - z) < tol, 0]


def _edge_divisions(outline: np.ndarray, tol: float, segments) -> dict[int, int]:
    """{edge: count} for the horizontal outline edges that are one of ``segments``.

    ``segments`` holds (z, r_lo, r_hi, count) [m, m, m, -]: an edge at height z from r_lo to
    r_hi gets exactly ``count`` elements.
    """
    divisions = {}
    for i, (a, b) in enumerate(zip(outline, np.roll(outline, -1, axis=0), strict=True)):
        lo, hi = sorted((a[0], b[0]))
        for z, r_lo, r_hi, count in segments:
            if (abs(a[1] - z) < tol and abs(b[1] - z) < tol and abs(lo - r_lo) < tol
                    and abs(hi - r_hi) < tol):
                divisions[i] = count
    return divisions


def _point_sizes(outline: np.ndarray, tol: float, size: float, refined) -> np.ndarray:
    """gmsh target size per outline vertex: ``size``, smaller at the (z, r, size) points."""
    sizes = np.full(len(outline), size)
    for z, r, local in refined:
        at = (np.abs(outline[:, 1] - z) < tol) & (np.abs(outline[:, 0] - r) < tol)
        sizes[at] = min(local, size)
    return sizes


def ring_seat(config: FeaConfig) -> tuple[np.ndarray, float, float]:
    """The anvil ring of ``config`` placed in the stack, and its seat on the anvil.

    The ring outline is shifted so that its flat top face lies on the anvil's flat bottom
    face (z = the anvil height); the seat is the radial overlap of the two faces.

    Parameters
    ----------
    config : FeaConfig
        The configuration (with a ring).

    Returns
    -------
    outline : numpy.ndarray
        The ring outline in stack coordinates, rows (r, z) [m].
    seat_inner : float
        Inner radius of the seat [m].
    seat_outer : float
        Outer radius of the seat [m].

    Raises
    ------
    InputError
        If the faces do not overlap or the pile wall does not lie on the ring's bottom face.
    """
    src = "FeaConfig"
    anvil = np.asarray(config.anvil.outline, float)
    height = anvil[:, 1].max() - anvil[:, 1].min()
    outline = np.asarray(config.ring.outline, float).copy()
    outline[:, 1] += height - outline[:, 1].min()
    tol = 1e-9 * max(np.ptp(outline, axis=0).max(), np.ptp(anvil, axis=0).max(), 1.0)
    a_bot = _flat_face_radii(anvil - [0.0, anvil[:, 1].min()], height, tol)
    r_top = _flat_face_radii(outline, height, tol)
    r_bot = _flat_face_radii(outline, outline[:, 1].max(), tol)
    lo, hi = max(a_bot.min(), r_top.min()), min(a_bot.max(), r_top.max())
    if len(a_bot) < 2 or len(r_top) < 2 or hi - lo < 10 * tol:
        raise InputError(src, "ring", "the ring's flat top face must overlap the anvil's flat "
                                      "bottom face (the seat)")
    r_in, r_out = config.pile_ring
    if len(r_bot) < 2 or r_in < r_bot.min() - tol or r_out > r_bot.max() + tol:
        raise InputError(src, "pile_outer_diameter", "the pile wall ring must lie on the "
                                                     "ring's flat bottom face")
    return outline, float(lo), float(hi)


def build_impact_model(config: FeaConfig) -> ImpactModel:
    """Mesh, assemble and preload the ram + anvil (+ ring) + pile stack of ``config``.

    With ``config.ring`` the anvil rests on the ring through the seat (the radial overlap of
    the anvil's flat bottom face and the ring's flat top face) and the ring on the pile
    wall. The seat gets node-to-node pairs at a spacing of at most ``mesh_size`` on both
    bodies (the two outlines share those vertices), the ring's bottom face the pile wall's
    ``pile_wall_elements`` vertices.

    Parameters
    ----------
    config : FeaConfig
        The configuration.

    Returns
    -------
    ImpactModel
        The assembled stack.

    Raises
    ------
    InputError
        If the ram face or the pile ring does not lie on the anvil's (ring's) flat faces.
    """
    src = "FeaConfig"
    spec = config.anvil
    outline = np.asarray(spec.outline, float).copy()
    z_top, z_bot = outline[:, 1].min(), outline[:, 1].max()
    outline[:, 1] -= z_top
    height = z_bot - z_top
    r_in, r_out = config.pile_ring
    tol = 1e-9 * max(np.ptp(outline, axis=0).max(), 1.0)
    top_r = _flat_face_radii(outline, 0.0, tol)
    bot_r = _flat_face_radii(outline, height, tol)
    if len(top_r) < 2 or top_r.min() > tol or config.ram_radius > top_r.max() + tol:
        raise InputError(src, "ram_radius", "the ram face r <= ram_radius must lie on the anvil's "
                                            "flat top face starting at the axis")
    if config.ring is None and (len(bot_r) < 2 or r_in < bot_r.min() - tol
                                or r_out > bot_r.max() + tol):
        raise InputError(src, "pile_outer_diameter", "the pile wall ring must lie on the anvil's "
                                                     "flat bottom face")
    wall_size = config.pile_wall_thickness / config.pile_wall_elements
    ram_face = (0.0, 0.0, config.ram_radius,
                int(np.ceil(config.ram_radius / config.mesh_size - 1e-9)))
    wall_face = [(r_in, min(wall_size, config.mesh_size)), (r_out, min(wall_size,
                                                                      config.mesh_size))]
    # exact element counts on the contact edges (the ram face, the pile ring, the seat)
    if config.ring is None:
        itf = Interfaces(config.ram_radius, 0.5 * (r_in + r_out), config.pile_wall_thickness)
        outline = split_outline_at_interfaces(outline, itf)
        sizes = _point_sizes(outline, tol, config.mesh_size,
                             [(height, r, s) for r, s in wall_face])
        divisions = _edge_divisions(outline, tol, [
            ram_face, (height, r_in, r_out, config.pile_wall_elements)])
    else:
        ring_outline, seat_in, seat_out = ring_seat(config)
        seat_r = graded_vertices(seat_in, seat_out, config.mesh_size)
        seat_size = float(np.diff(seat_r).max())
        seat_edges = [(height, a, b, 1) for a, b in zip(seat_r[:-1], seat_r[1:], strict=True)]
        outline = split_outline_at_radii(outline, 0.0, [config.ram_radius])
        outline = split_outline_at_radii(outline, height, seat_r)
        sizes = _point_sizes(outline, tol, config.mesh_size,
                             [(height, r, seat_size) for r in seat_r])
        divisions = _edge_divisions(outline, tol, [ram_face, *seat_edges])
        ring_bottom_z = float(ring_outline[:, 1].max())
        ring_outline = split_outline_at_radii(ring_outline, height, seat_r)
        ring_outline = split_outline_at_radii(ring_outline, ring_bottom_z, (r_in, r_out))
        ring_tol = 1e-9 * max(np.ptp(ring_outline, axis=0).max(), 1.0)
        ring = make_body("ring", to_skfem(mesh_outline(
            ring_outline, None,
            point_sizes=_point_sizes(ring_outline, ring_tol, config.mesh_size,
                                     [*((height, r, seat_size) for r in seat_r),
                                      *((ring_bottom_z, r, s) for r, s in wall_face)]),
            edge_divisions=_edge_divisions(ring_outline, ring_tol, [
                *seat_edges, (ring_bottom_z, r_in, r_out, config.pile_wall_elements)]))),
            config.ring.material)
    anvil = make_body("anvil", to_skfem(mesh_outline(outline, None, point_sizes=sizes,
                                                     edge_divisions=divisions)),
                      spec.material)
    # the ram and the pile copy the radial vertex positions of the faces they touch
    a_top = face(anvil, 0.0, 0.0, config.ram_radius)
    if config.ring is None:
        pile_z = height
        on_pile = face(anvil, height, r_in, r_out)
    else:
        pile_z = ring_bottom_z
        on_pile = face(ring, pile_z, r_in, r_out)
    ram_dz = config.ram_axial_size or config.mesh_size
    pile_dz = config.pile_axial_size or config.mesh_size
    ram = tensor_body("ram", vertex_radii(a_top), graded_vertices(-config.ram_length, 0.0, ram_dz),
                      config.material)
    pile_len = config.modelled_pile_length
    gauge_z = pile_z + config.gauge_depth
    pile = tensor_body("pile", vertex_radii(on_pile),
                       graded_vertices(pile_z, pile_z + pile_len, pile_dz, fixed=(gauge_z,)),
                       config.material)
    bodies = [ram, anvil, pile] if config.ring is None else [ram, anvil, ring, pile]
    n = _place(bodies)
    a_top = face(anvil, 0.0, 0.0, config.ram_radius)
    if config.ring is None:
        a_ring = on_pile = face(anvil, height, r_in, r_out)
    else:
        a_ring = face(anvil, height, seat_in, seat_out)
        ring_top = face(ring, height, seat_in, seat_out)
        on_pile = face(ring, pile_z, r_in, r_out)
    ram_bottom = face(ram, 0.0)
    pile_top = face(pile, pile_z)
    pile_bottom = face(pile, pile_z + pile_len)
    gauge = face(pile, gauge_z)

    E = min(config.material.youngs_modulus, spec.material.youngs_modulus)
    alpha = config.contact_stiffness_factor
    c_ram = contact_between("ram_anvil", ram_bottom, a_top,
                            alpha * E / min(ram_dz, config.mesh_size),
                            friction_coefficient=config.ram_anvil_friction)
    if config.ring is None:
        c_pile = contact_between("anvil_pile", a_ring, pile_top,
                                 alpha * E / min(pile_dz, wall_size),
                                 friction_coefficient=config.pile_friction)
        contacts = [c_ram, c_pile]
    else:
        E_ring = min(E, config.ring.material.youngs_modulus)
        c_pile = contact_between("ring_pile", on_pile, pile_top,
                                 alpha * E_ring / min(pile_dz, wall_size),
                                 friction_coefficient=config.pile_friction)
        c_seat = contact_between("anvil_ring", a_ring, ring_top, alpha * E_ring / seat_size,
                                 friction_coefficient=config.seat_friction)
        contacts = [c_ram, c_pile, c_seat]
    static_contacts = contacts[1:]
    if config.sleeve_radius is not None:
        k_sleeve = alpha * E / config.mesh_size
        contacts.append(sleeve_contact("anvil_sleeve", anvil, float(outline[:, 0].max()),
                                       config.sleeve_radius, k_sleeve,
                                       config.sleeve_friction))
        if config.ring is not None:
            contacts.append(sleeve_contact("ring_sleeve", ring,
                                           float(ring_outline[:, 0].max()),
                                           config.sleeve_radius, k_sleeve,
                                           config.sleeve_friction))

    K, M = _global(bodies)
    g = config.gravity
    f = np.concatenate([b.gravity_force(g) for b in bodies])
    damping, high_pass = np.zeros(n), None
    if config.truncate_length is not None:
        damping, high_pass = absorbing_boundary(pile_bottom, config.material, n,
                                                config.absorbing_boundary)

    # static preload of anvil (+ ring) + pile under gravity, pile bottom supported axially,
    # without friction (at rest nothing has slipped; the stick springs start unloaded)
    u0 = np.zeros(n)
    preload = seat_preload = 0.0
    if g > 0.0:
        ap = np.arange(anvil.offset, n)  # anvil, ring and pile DOFs (the ram comes first)

        def sub(idx):
            return idx - anvil.offset

        sub_contacts = [ContactSet(c.name, sub(c.upper_dofs), sub(c.lower_dofs), c.stiffness,
                                   c.damping, c.gap, c.radii) for c in static_contacts]
        u_ap, reaction = static_preload(K[ap][:, ap], f[ap], sub_contacts,
                                        sub(pile_bottom.axial_dofs))
        u0[ap] = u_ap
        f[ap] += reaction  # the support reaction becomes a constant force on the pile bottom
        overlap = u0[c_pile.upper_dofs] - u0[c_pile.lower_dofs]
        preload = float(np.sum(c_pile.stiffness * np.maximum(overlap, 0.0)))
        if config.ring is not None:
            overlap = u0[c_seat.upper_dofs] - u0[c_seat.lower_dofs]
            seat_preload = float(np.sum(c_seat.stiffness * np.maximum(overlap, 0.0)))
    # the rigidly shifted, stress-free ram touches the (sagged) anvil face at its highest point
    shift = float(np.min(u0[a_top.axial_dofs]))
    ez_ram = ram.axial_indicator()
    u0[ram.offset:ram.offset + ram.n_dof] = shift * ez_ram
    v0 = np.zeros(n)
    v0[ram.offset:ram.offset + ram.n_dof] = config.impact_velocity * ez_ram

    system = ExplicitSystem(
        stiffness=K, mass=M, damping=damping, force=f, contacts=contacts, displacement=u0,
        velocity=v0, high_pass=high_pass,
        force_probes={"gauge_force": section_force_row(pile, gauge_z, n)},
        velocity_probes={"pile_head_velocity": mean_velocity_weights(pile_top, n),
                         "gauge_velocity": mean_velocity_weights(gauge, n),
                         "ram_velocity": body_velocity_weights(ram, n)},
    )
    info = {
        "ram_mass [kg]": ram.mass, "anvil_mass [kg]": anvil.mass, "pile_mass [kg]": pile.mass,
        "static_anvil_pile_force [N]": preload, "anvil_height [m]": height,
        "ram_radial_elements": len(vertex_radii(a_top)) - 1,
        "pile_wall_elements": len(vertex_radii(on_pile)) - 1,
        "anvil_elements": anvil.model.mesh.t.shape[1],
        "contact_stiffness_ram_anvil [N/m]": float(c_ram.stiffness.sum()),
        "contact_stiffness_anvil_pile [N/m]": float(c_pile.stiffness.sum()),
        "modelled_pile_length [m]": pile_len,
        "absorbing_boundary": config.absorbing_boundary if config.truncate_length else "none",
    }
    faces = {"ram_bottom": ram_bottom, "anvil_top": a_top, "anvil_ring": a_ring,
             "pile_top": pile_top, "pile_bottom": pile_bottom, "gauge": gauge}
    if config.ring is not None:
        info.update({
            "ring_mass [kg]": ring.mass, "ring_height [m]": pile_z - height,
            "ring_elements": ring.model.mesh.t.shape[1],
            "seat_radii [m]": (seat_in, seat_out), "seat_pairs": len(c_seat.radii),
            "static_anvil_ring_force [N]": seat_preload,
            "contact_stiffness_anvil_ring [N/m]": float(c_seat.stiffness.sum()),
        })
        faces.update({"ring_top": ring_top, "ring_bottom": on_pile})
    if config.sleeve_radius is not None:
        info["sleeve_clearance [m]"] = config.sleeve_radius - float(outline[:, 0].max())
    return ImpactModel(system, {b.name: b for b in bodies}, faces, info)


def run_impact_fea(config: FeaConfig, progress: Callable[[float], None] | None = None
                   ) -> FeaResult:
    """Build and integrate the ram + anvil + pile impact of ``config``.

    Parameters
    ----------
    config : FeaConfig
        The configuration.
    progress : callable, optional
        Called with the fraction in [0, 1] during the time stepping.

    Returns
    -------
    FeaResult
        Time histories and run statistics.
    """
    start = time.perf_counter()
    model = build_impact_model(config)
    tr = integrate(model.system, config.duration, config.output_interval,
                   safety=config.time_step_safety, progress=progress)
    setup = time.perf_counter() - start - tr.wall_time
    return _result(tr, model.system.n_dof, setup, model.info,
                   [c.name for c in model.system.contacts])


def _result(tr: Transient, n_dof: int, setup: float, info: dict,
            names: list[str] | None = None) -> FeaResult:
    zeros = np.zeros_like(tr.time)
    force = tr.contact_force
    names = names or []
    sleeve = [i for i, name in enumerate(names) if name.endswith("_sleeve")]
    seat = [i for i, name in enumerate(names) if name == "anvil_ring"]
    return FeaResult(
        time=tr.time,
        ram_anvil_force=force[:, 0],
        anvil_pile_force=force[:, 1] if force.shape[1] > 1 else zeros,
        pile_head_velocity=tr.probes.get("pile_head_velocity", zeros),
        gauge_force=tr.probes.get("gauge_force", zeros),
        gauge_velocity=tr.probes.get("gauge_velocity", zeros),
        ram_velocity=tr.probes.get("ram_velocity", zeros),
        energies=tr.energies, n_dof=n_dof, n_steps=tr.n_steps, time_step=tr.time_step,
        critical_time_step=2.0 / tr.omega_max, wall_time=tr.wall_time, setup_time=setup,
        info=info, anvil_ring_force=force[:, seat[0]] if seat else None,
        sleeve_force=force[:, sleeve].sum(axis=1) if sleeve else None)


# --------------------------------------------------------------------------- two-bar impact


def run_bar_impact(striker_length: float, rod_length: float, outer_radius: float,
                   impact_velocity: float, *, inner_radius: float = 0.0,
                   radial_elements: int = 4, axial_size: float | None = None,
                   truncated: bool = False, gauge_depth: float | None = None,
                   duration: float | None = None, output_interval: float = 2e-6,
                   material: Material = STEEL,
                   contact_stiffness_factor: float = DEFAULT_CONTACT_STIFFNESS_FACTOR,
                   contact_stiffness_per_area: float | None = None,
                   absorbing_boundary_kind: str = "bar", time_step_safety: float = 0.9
                   ) -> FeaResult:
    """Coaxial striker hitting a rod of the same section (bars or tubes), no gravity.

    The closed-form check of the machinery (reference/closed-form-impacts.md, case 3): a
    rectangular force pulse Z v / 2 lasting 2 L_striker / c0 with 1D theory.

    Parameters
    ----------
    striker_length : float
        Striker length [m].
    rod_length : float
        Rod length [m].
    outer_radius : float
        Outer radius [m].
    impact_velocity : float
        Striker velocity at contact [m/s].
    inner_radius : float, default 0.0
        Inner radius [m] (0: solid bars).
    radial_elements : int, default 4
        Quadratic elements across the section [-].
    axial_size : float, optional
        Axial element size [m] (None: the radial one).
    truncated : bool, default False
        Dashpot (absorbing) boundary at the rod's far end, else free.
    gauge_depth : float, optional
        Gauge section below the rod top [m] (None: mid-rod).
    duration : float, optional
        Simulated time [s] (None: 2 L_striker / c0 + the travel to the gauge, x 1.5).
    output_interval : float, default 2e-6
        Output time step [s].
    material : Material, default STEEL
        Material of both bars.
    contact_stiffness_factor : float, default DEFAULT_CONTACT_STIFFNESS_FACTOR
        alpha of the penalty alpha E / axial size [-], used when
        ``contact_stiffness_per_area`` is None.
    contact_stiffness_per_area : float, optional
        Penalty [N/m^3]; None: contact_stiffness_factor * E / axial size (a mesh-independent
        value makes the contact problem itself fixed under refinement).
    absorbing_boundary_kind : {"bar", "plate", "shell", "p"}
        Kind of the absorbing boundary, see :func:`absorbing_speeds`.
    time_step_safety : float, default 0.9
        Fraction of the critical step used [-].

    Returns
    -------
    FeaResult
        ``ram_anvil_force`` is the striker-rod contact force; ``pile_head_velocity`` the rod top
        velocity; ``ram_velocity`` the striker's mean velocity.
    """
    c0 = material.bar_wave_speed
    dr = (outer_radius - inner_radius) / radial_elements
    dz = axial_size or dr
    gauge_depth = 0.5 * rod_length if gauge_depth is None else gauge_depth
    if duration is None:
        duration = 1.5 * (2.0 * striker_length + gauge_depth) / c0
    duration = output_interval * max(1, round(duration / output_interval))
    radii = np.linspace(inner_radius, outer_radius, radial_elements + 1)
    striker = tensor_body("striker", radii, graded_vertices(-striker_length, 0.0, dz), material)
    rod = tensor_body("rod", radii, graded_vertices(0.0, rod_length, dz, fixed=(gauge_depth,)),
                      material)
    bodies = [striker, rod]
    n = _place(bodies)
    K, M = _global(bodies)
    s_bottom, r_top, r_bottom = face(striker, 0.0), face(rod, 0.0), face(rod, rod_length)
    gauge = face(rod, gauge_depth)
    k_area = (contact_stiffness_factor * material.youngs_modulus / dz
              if contact_stiffness_per_area is None else contact_stiffness_per_area)
    contact = contact_between("striker_rod", s_bottom, r_top, k_area)
    damping, high_pass = np.zeros(n), None
    if truncated:
        damping, high_pass = absorbing_boundary(r_bottom, material, n, absorbing_boundary_kind)
    v0 = np.zeros(n)
    v0[:striker.n_dof] = impact_velocity * striker.axial_indicator()
    system = ExplicitSystem(
        stiffness=K, mass=M, damping=damping, force=np.zeros(n), contacts=[contact],
        displacement=np.zeros(n), velocity=v0, high_pass=high_pass,
        force_probes={"gauge_force": section_force_row(rod, gauge_depth, n)},
        velocity_probes={"pile_head_velocity": mean_velocity_weights(r_top, n),
                         "gauge_velocity": mean_velocity_weights(gauge, n),
                         "ram_velocity": body_velocity_weights(striker, n)},
    )
    start = time.perf_counter()
    tr = integrate(system, duration, output_interval, safety=time_step_safety)
    setup = time.perf_counter() - start - tr.wall_time
    info = {"striker_mass [kg]": striker.mass, "rod_mass [kg]": rod.mass,
            "area [m^2]": s_bottom.area, "bar_wave_speed [m/s]": c0}
    return _result(tr, n, setup, info)
