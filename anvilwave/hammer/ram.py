"""The ram as a non-uniform 1D elastic rod of lumped masses and springs (or a rigid body).

Discretisation (Smith 1960): the ram, top to toe, is cut into segments of length dx_j, area A_j,
modulus E; segment j becomes a mass m_j = rho A_j dx_j at its centre, and neighbouring centres
are joined by the two half segments in series, 1 / k = dx_j / (2 E A_j) + dx_j+1 / (2 E A_j+1).
So n segments carry n masses and n - 1 springs; mass 0 is the top segment and mass n - 1 the toe
segment. The half segment below the toe mass, ``toe_stiffness`` = 2 E A / dx, joins the toe mass
to the striking face: it is the ram's side of the contact spring, as in Smith's model, so that
ram, contact and the neighbour form one regular chain (a rod striking a rod of the same section
is then exactly the uniform chain, dispersion free at the Courant number 1). The lumping keeps
the total mass and the centre of mass exactly, and the springs in series with the toe half
segment and the top half segment give the static stiffness E A / L of a uniform ram. A rigid ram
is n = 1 (no toe spring: the contact stiffness must then be given).

Time stepping: leapfrog (symplectic Euler, v += dt a; u += dt v), second order for the staggered
velocity, stable for dt < 2 / omega_max; for a uniform chain omega_max = 2 c / dx, and at the
Courant number c dt / dx = 1 the scheme propagates waves without dispersion.

Sign conventions: z down; u, v positive downward; spring force N_j = k_j (u_j - u_{j+1}) is
positive in compression; the toe force F_toe (contact with the anvil) is positive in compression
and pushes the toe mass upward.

References
----------
Smith, E.A.L. (1960). Pile-driving analysis by the wave equation. Journal of the Soil Mechanics
    and Foundations Division, ASCE, 86(SM4), 35-61.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from anvilwave.anvil_rom.chain import chain_modes

STEEL_ELASTIC_MODULUS = 210e9
"""Young's modulus of steel [Pa] (DESIGN.md)."""
STEEL_DENSITY = 7850.0
"""Density of steel [kg/m^3] (DESIGN.md)."""
DEFAULT_SEGMENT_LENGTH = 0.5
"""Default ram element length [m]; cut-off frequency c / (pi dx) = 3.3 kHz in steel."""


# --------------------------------------------------------------------------- discretisation
def lump_rod(lengths, areas, elastic_modulus: float, density: float,
             segment_length: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Lumped masses, springs and toe half-segment spring of a rod of uniform sections (top first).

    Each section of length L_s is cut into ceil(L_s / segment_length) equal segments; each
    segment's mass rho A dx sits at its centre, centres are joined by two half segments in
    series, and the toe half segment 2 E A / dx joins the last mass to the striking face.

    Parameters
    ----------
    lengths : array_like
        Section lengths [m], top to toe.
    areas : array_like
        Section cross-section areas [m^2].
    elastic_modulus : float
        Young's modulus E [Pa].
    density : float
        Density rho [kg/m^3].
    segment_length : float
        Largest element length dx [m].

    Returns
    -------
    mass : numpy.ndarray
        (n,) segment masses [kg], top first.
    stiffness : numpy.ndarray
        (n - 1,) springs between them [N/m].
    toe_stiffness : float
        The toe half segment 2 E A / dx [N/m].
    """
    element_dx = []
    element_area = []
    for length, area in zip(np.asarray(lengths, float), np.asarray(areas, float), strict=True):
        count = max(1, math.ceil(length / segment_length - 1e-9))
        element_dx += [length / count] * count
        element_area += [area] * count
    dx = np.array(element_dx)
    area = np.array(element_area)
    half = 2.0 * elastic_modulus * area / dx  # stiffness of a half segment
    stiffness = 1.0 / (1.0 / half[:-1] + 1.0 / half[1:])
    mass = density * area * dx
    return mass, stiffness, float(half[-1])


def circle_area(outer_diameter: float, inner_diameter: float = 0.0) -> float:
    """Area [m^2] of a solid (inner 0) or hollow circular section.

    Parameters
    ----------
    outer_diameter : float
        Outer diameter [m].
    inner_diameter : float, default 0.0
        Inner diameter [m] (0 for a solid section).

    Returns
    -------
    float
        The section area [m^2].
    """
    return 0.25 * math.pi * (outer_diameter**2 - inner_diameter**2)


@dataclass(frozen=True, eq=False)
class RamRod:
    """A ram as n lumped masses (top first) joined by n - 1 springs; rigid when n = 1.

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg], node 0 at the top, node n - 1 at the toe.
    stiffness : numpy.ndarray
        (n - 1,) spring stiffnesses [N/m]; spring j joins nodes j and j + 1.
    length : float, default nan
        Ram length [m] (nan when built from explicit segments or as a rigid body).
    toe_diameter : float, default nan
        Diameter of the striking face [m] (nan if unknown); the anvil ROM needs it.
    toe_stiffness : float, default nan
        Half segment between the toe mass and the striking face [N/m], the ram's side of the
        contact spring (nan for a rigid ram or explicit segments: give a contact stiffness).
        For a modal ram, the residual flexibility of its truncated modes at the toe, inverted.
    sections : numpy.ndarray or None, default None
        (s, 3) the ram's shape, top to toe: rows [length, outer diameter, inner diameter] [m]
        (None when built from explicit segments or as a rigid body); the modal ram is built
        from it.
    elastic_modulus : float, default nan
        Young's modulus of ``sections`` [Pa] (nan when unknown).
    density : float, default nan
        Density of ``sections`` [kg/m^3] (nan when unknown).
    fmax : float, default nan
        Frequency content [Hz] of a modal ram (:mod:`anvilwave.hammer.modal_ram`); nan for a
        Smith rod.
    modes : anvilwave.hammer.modal_ram.RamToeModes or None, default None
        A modal ram run as the modal unit (:class:`anvilwave.hammer.modal_ram.ModalRamUnit`):
        its toe modes; ``mass`` is then the one total mass (the ram's weight and impact energy)
        and ``stiffness`` empty. None for a Smith rod and for a modal ram realised as a chain.

    Raises
    ------
    ValueError
        If ``mass`` is not a non-empty 1D array, ``stiffness`` does not have one entry fewer,
        or a mass or stiffness is not finite and positive.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    length: float = math.nan
    toe_diameter: float = math.nan
    toe_stiffness: float = math.nan
    sections: np.ndarray | None = None
    elastic_modulus: float = math.nan
    density: float = math.nan
    fmax: float = math.nan
    modes: object = None

    def __post_init__(self):
        mass = np.ascontiguousarray(self.mass, dtype=np.float64).copy()
        stiffness = np.ascontiguousarray(self.stiffness, dtype=np.float64).copy()
        if mass.ndim != 1 or mass.size < 1:
            raise ValueError("mass must be a 1D array with at least one entry")
        if stiffness.shape != (mass.size - 1,):
            raise ValueError(f"stiffness must have {mass.size - 1} entries, got {stiffness.size}")
        if not (np.all(np.isfinite(mass)) and np.all(mass > 0.0)):
            raise ValueError("masses must be finite and positive")
        if not (np.all(np.isfinite(stiffness)) and np.all(stiffness > 0.0)):
            raise ValueError("stiffnesses must be finite and positive")
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "stiffness", stiffness)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def rigid(cls, mass: float, toe_diameter: float = math.nan) -> RamRod:
        """A rigid ram (one mass, no spring).

        Parameters
        ----------
        mass : float
            Ram mass [kg].
        toe_diameter : float, default nan
            Diameter of the striking face [m] (nan if unknown).

        Returns
        -------
        RamRod
            The rigid ram.
        """
        return cls(np.array([float(mass)]), np.zeros(0), math.nan, toe_diameter)

    @classmethod
    def from_profile(cls, lengths, outer_diameters, inner_diameters=None, *,
                     elastic_modulus: float = STEEL_ELASTIC_MODULUS,
                     density: float = STEEL_DENSITY,
                     segment_length: float = DEFAULT_SEGMENT_LENGTH) -> RamRod:
        """A ram of circular sections, top to toe.

        Parameters
        ----------
        lengths : array_like
            Section lengths [m], top to toe.
        outer_diameters : array_like
            Outer diameter of each section [m].
        inner_diameters : array_like or None, default None
            Inner diameter of each section [m]; None for solid sections (0).
        elastic_modulus : float, default STEEL_ELASTIC_MODULUS
            Young's modulus E [Pa].
        density : float, default STEEL_DENSITY
            Density rho [kg/m^3].
        segment_length : float, default DEFAULT_SEGMENT_LENGTH
            Largest element length dx [m] (:func:`lump_rod`).

        Returns
        -------
        RamRod
            The lumped ram, with its ``sections``, length and toe diameter.
        """
        lengths = np.asarray(lengths, float)
        outer = np.asarray(outer_diameters, float)
        inner = np.zeros_like(outer) if inner_diameters is None else np.asarray(
            inner_diameters, float)
        areas = [circle_area(o, i) for o, i in zip(outer, inner, strict=True)]
        mass, stiffness, toe = lump_rod(lengths, areas, elastic_modulus, density,
                                        segment_length)
        sections = np.column_stack([lengths, outer, inner])
        return cls(mass, stiffness, float(lengths.sum()), float(outer[-1]), toe, sections,
                   float(elastic_modulus), float(density))

    @classmethod
    def uniform(cls, length: float, diameter: float, **kwargs) -> RamRod:
        """A solid cylinder of given length and diameter (steel unless told otherwise).

        Parameters
        ----------
        length : float
            Ram length [m].
        diameter : float
            Ram diameter [m].
        **kwargs
            Keywords of :meth:`from_profile` (``elastic_modulus`` [Pa], ``density`` [kg/m^3],
            ``segment_length`` [m]).

        Returns
        -------
        RamRod
            The lumped cylinder.
        """
        return cls.from_profile([length], [diameter], **kwargs)

    @classmethod
    def from_segments(cls, masses, stiffnesses, toe_diameter: float = math.nan) -> RamRod:
        """A ram from explicit masses (top first) and the springs between them.

        Parameters
        ----------
        masses : array_like
            (n,) segment masses [kg], top first.
        stiffnesses : array_like
            (n - 1,) springs between them [N/m].
        toe_diameter : float, default nan
            Diameter of the striking face [m] (nan if unknown).

        Returns
        -------
        RamRod
            The ram (no shape, no toe half segment).
        """
        return cls(np.asarray(masses, float), np.asarray(stiffnesses, float), math.nan,
                   toe_diameter)

    # ------------------------------------------------------------------ properties
    @property
    def n_masses(self) -> int:
        """Number of lumped masses n [-]."""
        return self.mass.size

    @property
    def total_mass(self) -> float:
        """Ram mass [kg]."""
        return float(self.mass.sum())

    @property
    def is_modal(self) -> bool:
        """True for a modal ram (:mod:`anvilwave.hammer.modal_ram`)."""
        return not math.isnan(self.fmax)

    @property
    def is_modal_unit(self) -> bool:
        """True for a modal ram run as the modal unit (``modes`` given)."""
        return self.modes is not None

    @property
    def is_rigid(self) -> bool:
        """True for a rigid ram: one mass and no toe modes."""
        return self.mass.size == 1 and self.modes is None

    @property
    def static_stiffness(self) -> float:
        """Stiffness between the top mass and the striking face [N/m].

        The springs and the toe half segment in series (inf when rigid; without the toe half
        segment if unknown).
        """
        if self.is_rigid:
            return math.inf
        toe = 0.0 if math.isnan(self.toe_stiffness) else 1.0 / self.toe_stiffness
        return float(1.0 / (np.sum(1.0 / self.stiffness) + toe))

    @property
    def toe_mass(self) -> float:
        """The toe's mass for a force step [kg].

        1 / sum_j p_toe,j^2 of a modal ram's modes, else the toe node's mass (the whole mass
        when rigid). A force step dF on the toe changes its velocity by -dF t / m over the
        first instants t, before the ram's modes (or springs) spread it: a modal unit's toe
        coordinate is u = sum_j p_toe,j q_j with q_j'' = -p_toe,j F + ... at t = 0. Its modes
        up to fmax cannot carry the rod's -dF / Z within about 1 / (2 fmax).
        """
        if self.modes is not None:
            return float(1.0 / np.sum(np.square(self.modes.participation)))
        return float(self.mass[-1])

    @property
    def toe_impedance(self) -> float:
        """Bar impedance of the striking face's section, E A / c = A sqrt(E rho) [N s/m].

        nan when the ram has no shape: explicit segments, rigid, toe modes alone.
        """
        if self.sections is None:
            return math.nan
        outer, inner = self.sections[-1, 1], self.sections[-1, 2]
        return circle_area(outer, inner) * math.sqrt(self.elastic_modulus * self.density)

    def stable_time_step(self) -> float:
        """Largest stable leapfrog step [s] (Gershgorin bound; inf when rigid).

        Returns
        -------
        float
            The stable step [s] (:func:`stable_time_step`).
        """
        return stable_time_step(self.mass, self.stiffness)

    def initial_state(self, impact_velocity: float) -> tuple[np.ndarray, np.ndarray]:
        """The state at the first contact t = 0: undeformed, every mass at the impact velocity.

        A falling ram carries no internal force (gravity accelerates all masses alike), so
        u = 0 and v = impact velocity is its exact state at impact.

        Parameters
        ----------
        impact_velocity : float
            Impact velocity [m/s], positive down.

        Returns
        -------
        u : numpy.ndarray
            (n,) displacements [m] (zeros).
        v : numpy.ndarray
            (n,) velocities [m/s] (all the impact velocity).
        """
        return np.zeros(self.n_masses), np.full(self.n_masses, float(impact_velocity))


# --------------------------------------------------------------------------- kernels
@njit(cache=True, inline='always')
def ram_advance(weight, inverse_mass, stiffness, u, v, toe_force, h, n_sub):
    """Advance the ram over a communication step h [s] in n_sub leapfrog sub-steps, in place.

    The physics of :func:`ram_step` on arrays prepared once. One sweep per sub-step:
    the spring below mass i is evaluated before u_i moves and carried to mass i + 1, so every
    force is that of the displacements at the start of the sub-step.

    Parameters
    ----------
    weight : numpy.ndarray
        (n,) weight m g of every mass [N], top first.
    inverse_mass : numpy.ndarray
        (n,) inverse mass 1 / m of every mass [1/kg].
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m], positive down; updated in place.
    v : numpy.ndarray
        (n,) velocities [m/s], positive down; updated in place.
    toe_force : float
        Contact force on the toe, held over the step [N], compression positive (pushes the toe
        up).
    h : float
        Communication step [s].
    n_sub : int
        Number of sub-steps [-] (h / n_sub below :func:`stable_time_step`).
    """
    dt = h / n_sub
    last = u.shape[0] - 1
    for _ in range(n_sub):
        from_above = 0.0
        for i in range(last):
            spring = stiffness[i] * (u[i] - u[i + 1])
            v_new = v[i] + dt * (from_above + weight[i] - spring) * inverse_mass[i]
            v[i] = v_new
            u[i] += dt * v_new
            from_above = spring
        v_new = v[last] + dt * (from_above + weight[last] - toe_force) * inverse_mass[last]
        v[last] = v_new
        u[last] += dt * v_new


@njit(cache=True)
def ram_step(mass, stiffness, u, v, toe_force, gravity, h, n_sub):
    """Advance the ram over a communication step h [s] in n_sub leapfrog sub-steps.

    Works in place on u, v. The toe force is held constant over the step. Each sub-step is the
    symplectic Euler (leapfrog) update v += dt a(u); u += dt v, so v is the velocity half a
    sub-step before u. The leapfrog form matters for the coupling: the master holds the contact
    force computed from the displacements at t_n, and a velocity-Verlet step with that held
    force (u += h v + h^2 a / 2, v += h a) would be unstable for the contact spring (energy
    growth (w h)^2 / 2 per step); leapfrog keeps it stable up to w h < 2. A convenience form of
    :func:`ram_advance` that prepares its arrays on every call.

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg], top first.
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m], positive down; updated in place.
    v : numpy.ndarray
        (n,) velocities [m/s], positive down; updated in place.
    toe_force : float
        Contact force on the toe [N], positive in compression (pushes the toe up).
    gravity : float
        Gravitational acceleration [m/s^2] (0 to switch it off).
    h : float
        Communication step [s].
    n_sub : int
        Number of sub-steps [-] (h / n_sub below :func:`stable_time_step`).
    """
    ram_advance(mass * gravity, 1.0 / mass, stiffness, u, v, toe_force, h, n_sub)


@njit(cache=True, fastmath={"reassoc"})
def leapfrog_energies(mass, stiffness, u, v, gravity, dt):
    """Kinetic, strain and gravity potential energy [J] in the leapfrog's conserved (shadow) form.

    With v the velocity of the last sub-step dt (u_prev = u - dt v): kinetic sum m v^2 / 2,
    strain sum k e e_prev / 2 and gravity potential -sum m g (u + u_prev) / 2, whose sum changes
    exactly by the work of the external forces for the central-difference scheme (Belytschko,
    Liu & Moran 2000, sec. 6.2), instead of oscillating by O(dt) like the plain energies.
    The sums may be added in any order (fastmath reassociation only: their last bits).

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg].
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m].
    v : numpy.ndarray
        (n,) velocities of the last sub-step [m/s].
    gravity : float
        Gravitational acceleration [m/s^2].
    dt : float
        The sub-step [s].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    strain : float
        Strain energy of the springs [J].
    potential : float
        Gravity potential relative to u = 0 [J].

    References
    ----------
    Belytschko, T., Liu, W.K. & Moran, B. (2000). Nonlinear Finite Elements for Continua and
        Structures. Wiley, ch. 6.
    """
    last = mass.shape[0] - 1
    kinetic = 0.5 * mass[last] * v[last] * v[last]
    strain = 0.0
    potential = -(mass[last] * gravity * (u[last] - 0.5 * dt * v[last]))
    for i in range(last):
        kinetic += 0.5 * mass[i] * v[i] * v[i]
        potential -= mass[i] * gravity * (u[i] - 0.5 * dt * v[i])
        e = u[i] - u[i + 1]
        strain += 0.5 * stiffness[i] * e * (e - dt * (v[i] - v[i + 1]))
    return kinetic, strain, potential


@njit(cache=True)
def stable_time_step(mass, stiffness):
    """Stable step of the leapfrog for the chain [s]: 2 / omega_max, inf for one mass.

    omega_max^2 is bounded by Gershgorin's theorem twice over, and the smaller bound is used:
    the row sums of M^-1 K, 2 (k_{i-1} + k_i) / m_i, and the discs of the symmetric
    M^-1/2 K M^-1/2, (k_{i-1} + k_i) / m_i + k_{i-1} / sqrt(m_{i-1} m_i) + k_i / sqrt(m_i m_{i+1}).
    The first is exact for a long uniform chain, 4 k / m = (2 c / dx)^2;
    both are conservative otherwise.

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg].
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].

    Returns
    -------
    float
        The stable step [s] (inf when there is no spring).
    """
    n = mass.shape[0]
    row_sum = 0.0
    disc = 0.0
    for i in range(n):
        k_sum = 0.0
        off = 0.0
        if i > 0:
            k_sum += stiffness[i - 1]
            off += stiffness[i - 1] / (math.sqrt(mass[i - 1]) * math.sqrt(mass[i]))
        if i < n - 1:
            k_sum += stiffness[i]
            off += stiffness[i] / (math.sqrt(mass[i]) * math.sqrt(mass[i + 1]))
        row_sum = max(row_sum, 2.0 * k_sum / mass[i])
        disc = max(disc, k_sum / mass[i] + off)
    omega2 = min(row_sum, disc)
    if omega2 == 0.0:
        return np.inf
    return 2.0 / math.sqrt(omega2)


@njit(cache=True)
def required_substeps(h, stable_step, safety=0.9):
    """Smallest n_sub with h / n_sub <= safety * stable_step (at least 1).

    Parameters
    ----------
    h : float
        Communication step [s].
    stable_step : float
        Stable sub-step [s] (may be inf).
    safety : float, default 0.9
        Fraction of the stable step to use [-].

    Returns
    -------
    int
        The number of sub-steps [-].
    """
    if not stable_step < np.inf:
        return 1
    n = int(math.ceil(h / (safety * stable_step) - 1e-12))
    return n if n > 1 else 1


@njit(cache=True)
def spring_forces(stiffness, u, out):
    """Spring forces N_j = k_j (u_j - u_{j+1}) [N] (compression positive) into ``out``.

    Parameters
    ----------
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m].
    out : numpy.ndarray
        (n - 1,) array that receives the spring forces [N].
    """
    for j in range(stiffness.shape[0]):
        out[j] = stiffness[j] * (u[j] - u[j + 1])


@njit(cache=True)
def toe_spring_force(stiffness, u):
    """Force in the lowest ram spring [N], compression positive (0 for a rigid ram).

    Parameters
    ----------
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m].

    Returns
    -------
    float
        The force [N].
    """
    n = stiffness.shape[0]
    if n == 0:
        return 0.0
    return stiffness[n - 1] * (u[n - 1] - u[n])


@njit(cache=True)
def kinetic_energy(mass, v):
    """Kinetic energy sum(m v^2) / 2 [J].

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg].
    v : numpy.ndarray
        (n,) velocities [m/s].

    Returns
    -------
    float
        The kinetic energy [J].
    """
    energy = 0.0
    for i in range(mass.shape[0]):
        energy += 0.5 * mass[i] * v[i] * v[i]
    return energy


@njit(cache=True)
def strain_energy(stiffness, u):
    """Strain energy of the springs sum(k (u_j - u_{j+1})^2) / 2 [J].

    Parameters
    ----------
    stiffness : numpy.ndarray
        (n - 1,) springs [N/m].
    u : numpy.ndarray
        (n,) displacements [m].

    Returns
    -------
    float
        The strain energy [J].
    """
    energy = 0.0
    for j in range(stiffness.shape[0]):
        d = u[j] - u[j + 1]
        energy += 0.5 * stiffness[j] * d * d
    return energy


@njit(cache=True)
def gravity_potential_energy(mass, u, gravity):
    """Gravitational potential energy relative to u = 0 [J]: -g sum(m u) (z down).

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg].
    u : numpy.ndarray
        (n,) displacements [m], positive down.
    gravity : float
        Gravitational acceleration [m/s^2].

    Returns
    -------
    float
        The potential energy [J].
    """
    energy = 0.0
    for i in range(mass.shape[0]):
        energy -= gravity * mass[i] * u[i]
    return energy


@njit(cache=True)
def momentum(mass, v):
    """Axial momentum sum(m v) [kg m/s], positive down.

    Parameters
    ----------
    mass : numpy.ndarray
        (n,) nodal masses [kg].
    v : numpy.ndarray
        (n,) velocities [m/s].

    Returns
    -------
    float
        The momentum [kg m/s].
    """
    total = 0.0
    for i in range(mass.shape[0]):
        total += mass[i] * v[i]
    return total


def max_angular_frequency(mass, stiffness) -> float:
    """Exact largest natural angular frequency of the free chain [rad/s] (scipy; for checks).

    Parameters
    ----------
    mass : array_like
        (n,) nodal masses [kg].
    stiffness : array_like
        (n - 1,) springs [N/m].

    Returns
    -------
    float
        The largest angular frequency [rad/s] (0 for one mass).
    """

    mass = np.asarray(mass, float)
    if mass.size == 1:
        return 0.0
    return float(chain_modes(mass, stiffness)[0].max())
