"""The ram as a Mode Displacement Method ROM: the anvil's method applied to the ram.

A 1D rod (Smith's chain, :mod:`anvilwave.hammer.ram`) has no lateral inertia: every frequency
travels at
the bar speed c = sqrt(E / rho). A real ram of 1.8 m diameter is not slender for the 1-3 kHz
content of an impact: the radial motion that Poisson's ratio couples to the axial strain
(Love 1927; Pochhammer-Chree) slows and disperses its high frequencies, and the ram's first
radial-axial modes (near 1.6 kHz for 1.8 m) shape the tail of the wave it returns to the
anvil. Against the axisymmetric FEA of the Table 1 impact the 1D ram puts the pile's peak force
about 5 % high; with Poisson's ratio set to 0 in the FEA's ram the 1D ram matches it.

Here the ram gets the anvil's treatment: its section (the hammer's ``sections``) is meshed and
assembled like an anvil (:mod:`anvilwave.anvil_rom`), its free-free modes up to fmax (the same
single
parameter) are projected on the striking face (uniform pressure on the toe), and they run as a
modal unit (:class:`ModalRamUnit`, kernel :func:`modal_ram_advance`), like the anvil's:

* every mode is advanced exactly over a step with the toe force held
  (:func:`anvilwave.anvil_rom.rom.modal_transition`): unconditionally stable, no sub-steps, and no
  limit
  on the number of modes (fmax 10 kHz builds for the Table 1 ram, 20 kHz for the IHC S-800's);
* the residual flexibility of the truncated modes at the toe (inertia relief, as the anvil's
  static correction) is massless and in series with the contact: it becomes the ram's side of
  the contact spring, ``toe_stiffness`` = 1 / r_toe, the role the toe half segment 2 E A / dx
  plays in Smith's ram. The static toe compliance is then exact whatever fmax.

The same modes can also be realised as the equivalent spring-mass chain
(:mod:`anvilwave.anvil_rom.chain`, ``realisation="chain"``): the same driving-point receptance sum
p_j^2 / (omega_j^2 - w^2) and total mass, run by the leapfrog ram kernel. The chain is kept for
the classic driving system (whose kernel steps a ram chain) and as the unit's cross-check; it
stops at about 500 modes (its masses fall by 1e-70 per 125 modes: double-precision range).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit

from anvilwave.anvil_rom.arrays import aligned_zeros
from anvilwave.anvil_rom.chain import chain_from_modes
from anvilwave.anvil_rom.fem.geometry import AnvilSpec, Interfaces, Material, validate_outline
from anvilwave.anvil_rom.rom import modal_transition, residual_flexibility
from anvilwave.hammer.ram import RamRod
from anvilwave.inputs import InputError

DEFAULT_POISSON_RATIO = 0.3
"""Poisson's ratio of the ram [-] (steel, DESIGN.md)."""
ELEMENTS_PER_SHEAR_WAVELENGTH = 6.0
"""Default mesh: target quadratic elements per shear wavelength at fmax. The modal analysis
refuses fewer than 4 on the LONGEST edge
(:func:`anvilwave.anvil_rom.fem.modes.mesh_resolvable_frequency`),
and gmsh's longest edges exceed the target size by up to about 40 %."""
ELEMENTS_PER_RADIUS = 6
"""Default mesh: at least this many elements across the toe radius (and across a wall)."""


def ram_outline(sections: np.ndarray) -> np.ndarray:
    """Half-section polygon (r, z) [m] of a ram of stacked circular sections, z down from the top.

    Parameters
    ----------
    sections : numpy.ndarray
        (s, 3) rows [length, outer diameter, inner diameter] [m], top first.

    Returns
    -------
    numpy.ndarray
        (p, 2) polygon vertices (r, z) [m], without repeated or collinear points.
    """
    sections = np.asarray(sections, float)
    z = np.concatenate(([0.0], np.cumsum(sections[:, 0])))
    outer = 0.5 * sections[:, 1]
    inner = 0.5 * sections[:, 2]
    pts = [(inner[0], 0.0)]
    for i, r in enumerate(outer):  # down the outside
        pts += [(r, z[i]), (r, z[i + 1])]
    for i in range(len(inner) - 1, -1, -1):  # up the inside (the axis for a solid ram)
        pts += [(inner[i], z[i + 1]), (inner[i], z[i])]
    out = [pts[0]]
    for p in pts[1:]:
        if not np.allclose(p, out[-1]):
            out.append(p)
    if np.allclose(out[-1], out[0]):
        out.pop()
    # drop the middle point of three on one straight line
    keep = []
    n = len(out)
    for i in range(n):
        a, b, c = np.array(out[i - 1]), np.array(out[i]), np.array(out[(i + 1) % n])
        cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
        if abs(cross) > 1e-12:
            keep.append(out[i])
    return np.array(keep)


def default_mesh_size(sections: np.ndarray, material: Material, fmax: float) -> float:
    """Default element size [m] of a ram's mesh for a frequency content fmax.

    ELEMENTS_PER_SHEAR_WAVELENGTH per shear wavelength at fmax and ELEMENTS_PER_RADIUS across
    the toe radius and the thinnest wall, whichever is smaller.

    Parameters
    ----------
    sections : numpy.ndarray
        (s, 3) rows [length, outer diameter, inner diameter] [m], top first.
    material : anvilwave.anvil_rom.fem.geometry.Material
        The ram's material (its shear wave speed [m/s]).
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    float
        The element size [m].
    """
    sections = np.asarray(sections, float)
    walls = 0.5 * (sections[:, 1] - sections[:, 2])
    return float(min(material.shear_wave_speed / (ELEMENTS_PER_SHEAR_WAVELENGTH * fmax),
                     walls.min() / ELEMENTS_PER_RADIUS))


REALISATIONS = ("unit", "chain")
"""How a modal ram runs: the modal unit (default) or the equivalent chain."""


def modal_ram(ram: RamRod, fmax: float, *, poisson_ratio: float = DEFAULT_POISSON_RATIO,
              mesh_size: float | None = None, source: str = "hammer",
              modes: Callable | None = None, realise: Callable | None = None,
              realisation: str = "unit", annuli: int = 1) -> RamRod:
    """The modal ROM of ``ram`` (given by its sections) up to ``fmax`` [Hz], as a RamRod.

    Errors name ``source`` and the key: a ram without sections (rigid, explicit segments) has
    no shape to mesh. The system layer passes its modal-data cache for ``modes`` and
    ``realise``.

    Parameters
    ----------
    ram : RamRod
        The ram, with its ``sections`` (its shape) and material.
    fmax : float
        Frequency content [Hz]: the modes up to it are kept.
    poisson_ratio : float, default DEFAULT_POISSON_RATIO
        Poisson's ratio of the ram [-], in [0, 0.5).
    mesh_size : float or None, default None
        Element size [m]; None for :func:`default_mesh_size`.
    source : str, default "hammer"
        What the errors name as the input's source.
    modes : callable or None, default None
        ``modes(spec, fmax) -> ModalData`` of the ram's section; None to compute them
        (:func:`anvilwave.anvil_rom.fem.pipeline.compute_anvil_modes`).
    realise : callable or None, default None
        ``realise(omega, participation) -> (mass, stiffness)`` of the equivalent chain (for
        ``realisation="chain"``); None for :func:`anvilwave.anvil_rom.chain.chain_from_modes`.
    realisation : {"unit", "chain"}, default "unit"
        "unit": the RamRod carries the toe modes (:attr:`RamRod.modes`, for
        :class:`ModalRamUnit`); "chain": the masses and springs of the equivalent chain.
    annuli : int, default 1
        The toe also in that many annuli [-] (:func:`modal_ram_modes`).

    Returns
    -------
    RamRod
        The modal ram (its shape kept, ``fmax`` and the residual ``toe_stiffness`` set).

    Raises
    ------
    ValueError
        If ``realisation`` is not one of REALISATIONS.
    anvilwave.inputs.InputError
        If the ram has no shape, or ``fmax`` or ``poisson_ratio`` is out of range
        (:func:`modal_ram_modes`).
    """
    if realisation not in REALISATIONS:
        raise ValueError(f"realisation must be one of {REALISATIONS}, got {realisation!r}")
    toe_modes = modal_ram_modes(ram, fmax, poisson_ratio=poisson_ratio, mesh_size=mesh_size,
                                source=source, modes=modes, annuli=annuli)
    if realisation == "unit":
        return _as_unit(ram, toe_modes)
    return modal_ram_chain(ram, toe_modes, realise)


def _as_unit(ram: RamRod, toe_modes: RamToeModes) -> RamRod:
    """``ram`` (its shape kept) run as the modal unit of ``toe_modes``: one total mass (the
    weight and the impact energy), no springs, the residual toe stiffness."""
    return dataclasses.replace(ram, mass=np.array([toe_modes.total_mass]), stiffness=np.zeros(0),
                               toe_stiffness=toe_modes.toe_stiffness, fmax=toe_modes.fmax,
                               modes=toe_modes)


def modal_ram_chain(ram: RamRod, toe_modes: RamToeModes, realise: Callable | None = None
                    ) -> RamRod:
    """``ram`` realised as the chain of its toe modes (:func:`modal_ram`, "chain").

    Parameters
    ----------
    ram : RamRod
        The ram whose shape the result keeps.
    toe_modes : RamToeModes
        Its toe modes (:func:`modal_ram_modes`).
    realise : callable or None, default None
        ``realise(omega, participation) -> (mass, stiffness)``; None for
        :func:`anvilwave.anvil_rom.chain.chain_from_modes`.

    Returns
    -------
    RamRod
        The chain ram: masses [kg] and springs [N/m] top first, the residual toe stiffness
        [N/m] and ``fmax`` [Hz] of the modes.
    """
    mass, stiffness = _chain(toe_modes, realise)
    return dataclasses.replace(ram, mass=mass[::-1].copy(), stiffness=stiffness[::-1].copy(),
                               toe_stiffness=toe_modes.toe_stiffness, fmax=toe_modes.fmax,
                               modes=None)


def ram_from_toe_modes(toe_modes: RamToeModes, toe_diameter: float = math.nan) -> RamRod:
    """A modal-unit RamRod of given toe modes (no shape: the modes are the ram).

    Parameters
    ----------
    toe_modes : RamToeModes
        The toe modes.
    toe_diameter : float, default nan
        Diameter of the striking face [m] (nan if unknown).

    Returns
    -------
    RamRod
        The ram run as the modal unit: one total mass [kg], no springs.
    """
    return _as_unit(RamRod.rigid(toe_modes.total_mass, float(toe_diameter)), toe_modes)


def toe_modes_table(toe_modes: RamToeModes) -> dict:
    """The TOML table (``[ram]`` with ``kind = "modal"``) that reads back as ``toe_modes`` exactly.

    Parameters
    ----------
    toe_modes : RamToeModes
        The toe modes.

    Returns
    -------
    dict
        The table (:func:`toe_modes_from_table` reads it): ``kind``, ``fmax`` [Hz], ``mass``
        [kg], ``toe_stiffness`` [N/m], ``frequencies`` [Hz], ``omega`` [rad/s],
        ``participation`` [kg^-1/2], ``participation_gravity`` [kg^1/2].
    """
    return {"kind": "modal", "fmax": toe_modes.fmax, "mass": toe_modes.total_mass,
            "toe_stiffness": toe_modes.toe_stiffness,
            "frequencies": (toe_modes.omega / (2.0 * np.pi)).tolist(),
            "omega": toe_modes.omega.tolist(),
            "participation": toe_modes.participation.tolist(),
            "participation_gravity": toe_modes.participation_gravity.tolist()}


def toe_modes_from_table(table) -> RamToeModes:
    """Toe modes from a ``[ram]`` table with ``kind = "modal"`` (errors name the key).

    Parameters
    ----------
    table : anvilwave.inputs.Table
        The table, with ``omega`` [rad/s] (exactly one 0: the rigid-body mode; ``frequencies``
        [Hz] beside it for the reader), ``participation`` [kg^-1/2], ``participation_gravity``
        [kg^1/2], ``mass`` [kg], ``toe_stiffness`` [N/m] and ``fmax`` [Hz].

    Returns
    -------
    RamToeModes
        The toe modes (read-only arrays).

    Raises
    ------
    anvilwave.inputs.InputError
        If a key is missing or invalid: the arrays of unequal length or not finite, ``omega``
        negative or without exactly one 0, the rigid-body mode not moving the toe.
    """
    omega = table.array("omega")
    table.array("frequencies")  # for the reader; omega is exact
    n = omega.size
    participation = table.array("participation")
    gravity = table.array("participation_gravity")
    for key, values in (("participation", participation), ("participation_gravity", gravity)):
        if values.shape != (n,):
            raise table.error(key, f"must have one entry per mode ({n}), got {values.size}")
        if not np.all(np.isfinite(values)):
            raise table.error(key, "must be finite")
    if not np.all(np.isfinite(omega)) or np.any(omega < 0.0) or np.count_nonzero(omega == 0.0) != 1:
        raise table.error("omega", "must be finite and >= 0 with exactly one 0 (the rigid-body "
                                   "mode)")
    rigid = int(np.flatnonzero(omega == 0.0)[0])
    if participation[rigid] == 0.0:
        raise table.error("participation", "the rigid-body mode must move the toe")
    mass = table.number("mass", gt=0.0, unit="kg")
    toe_stiffness = table.number("toe_stiffness", gt=0.0, unit="N/m")
    fmax = table.number("fmax", gt=0.0, unit="Hz")
    for a in (omega, participation, gravity):
        a.flags.writeable = False
    return RamToeModes(omega, participation, gravity, total_mass=mass,
                       toe_stiffness=toe_stiffness, fmax=fmax)


@dataclass(frozen=True, eq=False)
class RamToeModes:
    """The ram's free-free modes seen at its toe (one port).

    Parameters
    ----------
    omega : numpy.ndarray
        (n,) circular frequencies [rad/s]; exactly one 0 (the rigid-body mode).
    participation : numpy.ndarray
        (n,) b_toe^T phi_j at the toe [kg^-1/2].
    participation_gravity : numpy.ndarray
        (n,) phi_j^T M e_z [kg^1/2] (only the rigid mode's is non-zero).
    total_mass : float
        Ram mass [kg].
    toe_stiffness : float
        1 / residual toe flexibility of the truncated modes [N/m].
    fmax : float
        Frequency content [Hz].
    annulus_participation : numpy.ndarray or None, default None
        (J, n) the toe split into J > 1 equal-width annuli from the axis, uniform pressure on
        each [kg^-1/2], or None (one port); area-weighted they add up to ``participation``.
    annulus_residual : numpy.ndarray or None, default None
        (J, J) residual flexibility of the truncated modes between the annuli [m/N]
        (area-weighted on both sides: 1 / ``toe_stiffness``), or None.
    annulus_areas : numpy.ndarray or None, default None
        (J,) areas of the annuli [m^2], the inner disc first, or None.
    """

    omega: np.ndarray
    participation: np.ndarray
    participation_gravity: np.ndarray
    total_mass: float
    toe_stiffness: float
    fmax: float
    annulus_participation: np.ndarray | None = None
    annulus_residual: np.ndarray | None = None
    annulus_areas: np.ndarray | None = None

    @property
    def n_annuli(self) -> int:
        """Annuli of the toe port (1: one port)."""
        return 1 if self.annulus_areas is None else int(self.annulus_areas.size)

    @property
    def n_modes(self) -> int:
        """Number of modes n [-], the rigid-body mode included."""
        return int(self.omega.size)


def modal_ram_modes(ram: RamRod, fmax: float, *, poisson_ratio: float = DEFAULT_POISSON_RATIO,
                    mesh_size: float | None = None, source: str = "hammer",
                    modes: Callable | None = None, annuli: int = 1) -> RamToeModes:
    """The toe modes of ``ram`` up to ``fmax`` [Hz], no chain: any number of modes.

    No double-precision range limit, unlike the chain. ``annuli`` > 1 also projects them on
    that many equal-width annuli of the toe (the mesh has vertices at their edges), for a ram
    face in annuli (:class:`anvilwave.anvil_rom.rings.RamFace`). Cached per ram and fmax.

    Parameters
    ----------
    ram : RamRod
        The ram, with its ``sections`` and material.
    fmax : float
        Frequency content [Hz].
    poisson_ratio : float, default DEFAULT_POISSON_RATIO
        Poisson's ratio of the ram [-], in [0, 0.5).
    mesh_size : float or None, default None
        Element size [m]; None for :func:`default_mesh_size`.
    source : str, default "hammer"
        What the errors name as the input's source.
    modes : callable or None, default None
        ``modes(spec, fmax) -> ModalData`` of the ram's section; None to compute them.
    annuli : int, default 1
        Number of equal-width annuli of the toe [-] (1: one port).

    Returns
    -------
    RamToeModes
        The toe modes and the residual toe stiffness.

    Raises
    ------
    anvilwave.inputs.InputError
        If the ram has no shape (rigid or explicit segments), ``fmax`` is not positive,
        ``poisson_ratio`` is outside [0, 0.5), the outline is invalid or a ram face in annuli
        has a hollow toe.
    """
    if ram.sections is None or not math.isfinite(ram.elastic_modulus):
        raise InputError(source, "ram", "a modal ram needs the ram's shape (diameter and mass "
                                        "or length, or a profile), not a rigid mass or "
                                        "explicit segments")
    if not (math.isfinite(fmax) and fmax > 0.0):
        raise InputError(source, "fmax", f"must be positive, got {fmax!r} Hz")
    if not 0.0 <= poisson_ratio < 0.5:
        raise InputError(source, "poisson_ratio", f"must be in [0, 0.5), got {poisson_ratio!r}")
    material = Material(ram.elastic_modulus, poisson_ratio, ram.density)
    size = default_mesh_size(ram.sections, material, fmax) if mesh_size is None else mesh_size
    return _toe_modes(np.ascontiguousarray(ram.sections, float).tobytes(),
                      ram.sections.shape[0], material, float(fmax), float(size), source, modes,
                      int(annuli))


@lru_cache(maxsize=16)
def _chain(toe_modes: RamToeModes, realise: Callable | None
           ) -> tuple[np.ndarray, np.ndarray]:
    """Chain masses and springs (toe first) of the toe modes; cached per modes."""
    mass, stiffness = (chain_from_modes if realise is None else realise)(
        toe_modes.omega, toe_modes.participation)
    mass.flags.writeable = False
    stiffness.flags.writeable = False
    return mass, stiffness


@lru_cache(maxsize=16)
def _toe_modes(sections_bytes: bytes, n_sections: int, material: Material, fmax: float,
               mesh_size: float, source: str, modes: Callable | None, annuli: int = 1
               ) -> RamToeModes:
    """The toe modes and the toe stiffness (and with ``annuli`` > 1 the toe's annuli); cached
    per ram and fmax."""
    sections = np.frombuffer(sections_bytes).reshape(n_sections, 3)
    outline = ram_outline(sections)
    validate_outline(outline, source, "ram")
    outer, inner = 0.5 * sections[-1, 1], 0.5 * sections[-1, 2]
    toe = Interfaces(ram_contact_radius=0.5 * sections[0, 1],
                     pile_contact_radius=0.5 * (outer + inner), pile_contact_width=outer - inner,
                     pile_rings=annuli)
    if annuli > 1:  # vertices at the annuli's edges: each facet in one annulus
        if inner > 0.0:
            raise InputError(source, "ram", "a ram face in annuli needs a solid toe")
        from anvilwave.anvil_rom.fem.mesh import split_outline_at_radii  # lazy: FEM (skfem)

        outline = split_outline_at_radii(outline, outline[:, 1].max(),
                                         np.linspace(0.0, outer, annuli + 1)[1:-1])
    spec = AnvilSpec("ram", material, outline=outline, interfaces=toe, mesh_size=mesh_size,
                     fmax=fmax, source=source)
    if modes is None:
        from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes  # lazy: FEM (skfem)

        data = compute_anvil_modes(spec, fmax=fmax).modal_data
    else:
        data = modes(spec, fmax)
    omega = 2.0 * np.pi * np.asarray(data.frequencies)
    p_toe = np.asarray(data.participation_pile)
    r = residual_flexibility(data.elastic_flexibility, omega, data.participation_ram, p_toe)
    arrays = [omega, p_toe, np.asarray(data.participation_gravity, float)]
    face = {}
    if annuli > 1:
        P = np.asarray(data.participation_rings)
        residual = residual_flexibility(data.ring_flexibility, omega, data.participation_ram,
                                        *P)[1:, 1:]
        face = {"annulus_participation": P, "annulus_residual": 0.5 * (residual + residual.T),
                "annulus_areas": np.asarray(data.ring_areas, float)}
    for a in [*arrays, *face.values()]:
        a.flags.writeable = False
    return RamToeModes(*arrays, total_mass=float(data.total_mass),
                       toe_stiffness=float(1.0 / r[1, 1]), fmax=float(fmax), **face)


# ------------------------------------------------------------------------- the modal unit
class ModalRamUnit:
    """The modal ram as a unit: its toe modes advanced exactly with the toe force held.

    Kernel data (float64, 64-byte aligned, the n modes padded with inert ones to a multiple
    of 8 columns, so that every row and both halves of S start on a cache line): ``C`` (9,
    n_padded), rows a, b, c, m_e, p_toe, p_grav, omega of the modes for the step
    (:func:`anvilwave.anvil_rom.rom.modal_transition`, undamped: b = -1), then c p_grav g and
    c p_toe (the step's constant load and force coefficient, set with the step); the rigid-body
    mode is mode 0, the only one gravity loads (p_grav of a free-free flexible mode is
    phi^T M e_z = 0 by orthogonality to the rigid translation; the FE value, ~1e-12 of the rigid
    mode's, is dropped); the padding columns are all zero (they stay at rest and carry nothing).
    ``S`` (2 n_padded) holds q at t_n and at t_n-1 in its two halves, which swap roles every
    step (the kernel writes q_n+1 over q_n-1); ``toe`` = [u_toe, v_toe, half] [m, m/s, -]: the
    toe state (modal part; the residual flexibility is the contact's series spring
    ``toe_stiffness``, as for the chain) and which half of S is t_n (0: the first). Velocities
    are half-step values (q_n - q_n-1) / h, as in the leapfrog units.

    Parameters
    ----------
    toe_modes : RamToeModes
        The ram's toe modes (:func:`modal_ram_modes`).
    gravity : float, default 9.81
        Gravitational acceleration [m/s^2].

    Attributes
    ----------
    modes : RamToeModes
        The toe modes.
    gravity : float
        Gravitational acceleration [m/s^2].
    C : numpy.ndarray
        (9, n_padded) kernel coefficients (above).
    S : numpy.ndarray
        (2 n_padded,) modal coordinates at t_n and t_n-1 [m kg^1/2].
    toe : numpy.ndarray
        [u_toe [m], v_toe [m/s], half [-]].
    h : float
        The step [s] of the coefficients (nan before the first).
    """

    def __init__(self, toe_modes: RamToeModes, gravity: float = 9.81):
        self.modes = toe_modes
        self.gravity = float(gravity)
        n = toe_modes.n_modes
        rigid = int(np.flatnonzero(toe_modes.omega == 0.0)[0])
        order = np.r_[rigid, np.delete(np.arange(n), rigid)]  # the rigid mode first
        width = -(-n // 8) * 8
        # one row per quantity: contiguous sweeps over the modes
        self.C = aligned_zeros((9, width))
        self.C[4, :n] = toe_modes.participation[order]
        self.C[5, 0] = toe_modes.participation_gravity[rigid]
        self.C[6, :n] = toe_modes.omega[order]
        self.S = aligned_zeros(2 * width)
        self.toe = np.zeros(3)
        self.h = math.nan

    @property
    def toe_stiffness(self) -> float:
        """The ram's side of the contact spring, 1 / residual toe flexibility [N/m]."""
        return self.modes.toe_stiffness

    def modal_coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """The modal coordinates at t_n and at t_n-1, rigid-body mode first.

        Returns
        -------
        now : numpy.ndarray
            (n,) q at t_n [m kg^1/2] (a view into ``S``).
        previous : numpy.ndarray
            (n,) q at t_n-1 [m kg^1/2] (a view into ``S``).
        """
        n = self.modes.n_modes
        width = self.C.shape[1]
        now = 0 if self.toe[2] == 0.0 else width
        return self.S[now:now + n], self.S[width - now:width - now + n]

    def set_step(self, h: float) -> None:
        """Use the step h [s] from now on.

        The state keeps its displacement q_n and its half-step rate (q_n - q_n-1) / h (a master
        that changes its step).

        Parameters
        ----------
        h : float
            The new step [s].
        """
        if h == self.h:
            return
        if math.isfinite(self.h):
            q, previous = self.modal_coordinates()
            previous[:] = q - h * (q - previous) / self.h
        self._coefficients(h)

    def _coefficients(self, h: float) -> None:
        C = self.C
        n = self.modes.n_modes
        C[:4, :n] = modal_transition(C[6, :n], 0.0, h).T
        C[7] = C[2] * C[5] * self.gravity
        C[8] = C[2] * C[4]
        self.h = float(h)

    def start(self, toe_displacement: float, velocity: float, h: float) -> None:
        """Start from undeformed rigid motion: the exact state of a falling ram.

        Parameters
        ----------
        toe_displacement : float
            Toe displacement at t_n [m], positive down.
        velocity : float
            Velocity of the ram [m/s], positive down (the toe was h velocity higher at t_n-1).
        h : float
            The step [s].
        """
        if h != self.h:
            self._coefficients(h)
        p = self.C[4, 0]
        self.S[:] = 0.0
        self.S[0] = toe_displacement / p
        self.S[self.C.shape[1]] = (toe_displacement - h * velocity) / p
        self.toe[:] = toe_displacement, velocity, 0.0

    def step(self, toe_force: float) -> tuple[float, float]:
        """Advance over h with the toe force held.

        Parameters
        ----------
        toe_force : float
            Force on the toe [N], compression positive (pushes the toe up).

        Returns
        -------
        u_toe : float
            The new toe displacement [m].
        v_toe : float
            The new toe half-step velocity [m/s].
        """
        modal_ram_advance(self.C, self.S, toe_force, self.h, self.toe)
        return float(self.toe[0]), float(self.toe[1])

    def energies(self) -> tuple[float, float, float]:
        """Kinetic, strain and gravity potential energy [J] (:func:`modal_ram_energies`).

        Returns
        -------
        kinetic : float
            Kinetic energy [J].
        strain : float
            Strain energy [J].
        potential : float
            Gravity potential [J].
        """
        return modal_ram_energies(self.C, self.S, self.toe, self.gravity, self.h)


@njit(cache=True, fastmath={"reassoc"})
def modal_ram_advance(coefficients, state, toe_force, h, toe):
    """Advance every toe mode over h [s] with ``toe_force`` [N] held, in place.

    ``coefficients`` and ``state`` are the unit's C and S (so called in the formulas,
    :class:`ModalRamUnit`); the new modal (u_toe, v_toe) are written into ``toe`` and its
    ``half`` is flipped.

    eta_j,n+1 = a eta_j,n - eta_j,n-1 + c (p_grav,j g - p_toe,j F): exact per undamped mode
    for a held force, at any h (unconditionally stable; no sub-steps); gravity loads the rigid
    mode 0 only. The toe's half-step velocity is (u_toe,n+1 - u_toe,n) / h with u_toe =
    sum p_toe,j eta_j. One sweep: the modes do not depend on each other, and the toe sum may be
    reassociated (``fastmath`` reassoc only: no other IEEE rule is relaxed), so the sweep is
    vectorised with the sum in vector lanes. The order of that sum is the compiler's (within
    1e-14 of the terms' magnitudes of the exactly rounded sum, tested): the engine and the Ram
    FMU, which both run this kernel, agree to rounding, not necessarily bit for bit. Not
    inlined: an inlined copy would take its caller's IEEE rules and lose the vectorisation.

    Parameters
    ----------
    coefficients : numpy.ndarray
        (9, n_padded) the unit's C [-], [kg^-1/2], [rad/s] and the step's coefficients.
    state : numpy.ndarray
        (2 n_padded,) the unit's S, modal coordinates at t_n and t_n-1 [m kg^1/2]; updated in
        place.
    toe_force : float
        Force on the toe, held over the step [N], compression positive (pushes the toe up).
    h : float
        The step [s] (that of the coefficients).
    toe : numpy.ndarray
        [u_toe [m], v_toe [m/s], half [-]]; updated in place.
    """
    C, S = coefficients, state
    n = C.shape[1]
    now = 0 if toe[2] == 0.0 else n
    old = n - now
    a = C[0]
    force = C[8]
    p = C[4]
    q = S[now:now + n]
    q_new = S[old:old + n]  # holds q_n-1 until overwritten
    q_new[0] -= C[7, 0]  # gravity on the rigid mode (the sweep subtracts q_n-1)
    u = 0.0
    for j in range(n):
        x = a[j] * q[j] - q_new[j] - force[j] * toe_force
        q_new[j] = x
        u += p[j] * x
    toe[1] = (u - toe[0]) / h
    toe[0] = u
    toe[2] = 1.0 - toe[2]


@njit(cache=True)
def modal_ram_energies(coefficients, state, toe, gravity, h):
    """Kinetic, strain and gravity potential energy [J] of the modal ram in its conserved form.

    The conserved (shadow) form of the two-step scheme, as the anvil's
    (:func:`anvilwave.anvil_rom.unit.modal_unit_energy`): sum m_e ((q_n - q_n-1) / h)^2 / 2,
    sum w^2 q_n q_n-1 / 2 and -g sum p_grav (q_n + q_n-1) / 2. The residual flexibility is the
    contact's series spring: its energy is the contact's.

    Parameters
    ----------
    coefficients : numpy.ndarray
        (9, n_padded) the unit's C [-], [kg^-1/2], [rad/s].
    state : numpy.ndarray
        (2 n_padded,) the unit's S [m kg^1/2].
    toe : numpy.ndarray
        [u_toe [m], v_toe [m/s], half [-]].
    gravity : float
        Gravitational acceleration [m/s^2].
    h : float
        The step [s].

    Returns
    -------
    kinetic : float
        Kinetic energy [J].
    strain : float
        Strain energy [J].
    potential : float
        Gravity potential [J].
    """
    C, S = coefficients, state
    n = C.shape[1]
    now = 0 if toe[2] == 0.0 else n
    old = n - now
    kinetic = 0.0
    strain = 0.0
    potential = 0.0
    for j in range(n):
        q, qp = S[now + j], S[old + j]
        rate = (q - qp) / h
        kinetic += 0.5 * C[3, j] * rate * rate
        strain += 0.5 * C[6, j] ** 2 * q * qp
        potential -= gravity * C[5, j] * 0.5 * (q + qp)
    return kinetic, strain, potential
