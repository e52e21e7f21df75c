"""Anvil description: material, half-section outline (or an external mesh), interfaces.

An anvil file is TOML::

    [material]
    youngs_modulus = 210e9      # [Pa]
    poisson_ratio = 0.3         # [-]
    density = 7850.0            # [kg/m^3]
    [geometry]                  # closed polygon of the half-section, (r, z) [m], z down, r >= 0
    points = [[0.0, 0.0], [0.9, 0.0], [4.15, 0.75], [4.15, 1.2], [0.0, 1.2]]
    [interfaces]                # optional for `modes`, required for the ROM
    ram_contact_radius = 0.9    # [m] the top face r <= this carries the ram
    pile_contact_radius = 3.93  # [m] mid-radius of the pile wall on the bottom face
    pile_contact_width = 0.14   # [m]
    [mesh]
    size = 0.05                 # [m] target element size
    [modes]                     # optional
    fmax = 5000.0               # [Hz] frequency content of the ROM
    damping_ratio = 0.0         # [-] modal damping ratio

Instead of ``[geometry]`` a top-level ``mesh = "file.msh"`` names an existing 2D axisymmetric
mesh (anything meshio reads: Gmsh .msh, Abaqus .inp, ...), coordinates (r, z) in metres.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from anvilwave.inputs import InputError, Table

DEFAULT_FMAX = 5000.0
"""Default frequency content of the modal anvil [Hz] (see the fmax study in the README)."""


MAX_ELEMENTS = 1_000_000
"""Largest FE mesh (quadratic triangles) this machine class takes: about 4 million DOF, whose
sparse factorisation for the eigenvalue count needs some tens of GB."""


def estimated_triangles(outline: np.ndarray, size: float) -> float:
    """Number of triangles of a mesh of the polygon at the target size [-].

    Its area over the area of an equilateral triangle of side ``size`` [m].

    Parameters
    ----------
    outline : numpy.ndarray
        Closed polygon, rows (r, z) [m].
    size : float
        Target element size [m].

    Returns
    -------
    float
        The estimated number of triangles [-].
    """
    r, z = np.asarray(outline, dtype=float).T
    area = 0.5 * abs(np.dot(r, np.roll(z, -1)) - np.dot(z, np.roll(r, -1)))
    return float(area / (math.sqrt(3.0) / 4.0 * size**2))


def mesh_budget_rule(elements: float, size: float) -> str | None:
    """The rule broken by a mesh of ``elements`` triangles at ``size`` [m], or None if it fits.

    The rule states the estimated size (elements, DOF, memory) and the smallest size that fits.

    Parameters
    ----------
    elements : float
        Estimated number of triangles [-].
    size : float
        Target element size [m].

    Returns
    -------
    str or None
        The broken rule, or None within :data:`MAX_ELEMENTS`.
    """
    if elements <= MAX_ELEMENTS:
        return None
    dof = 4.0 * elements
    memory = dof * 30 * 8 * 10 / 2**30   # ~30 non-zeros per row, K and factor fill ~10x
    smallest = size * math.sqrt(elements / MAX_ELEMENTS)
    return (f"gives a mesh too big for this machine: about {elements:.3g} elements, "
            f"{dof:.3g} DOF, {memory:.3g} GiB for the eigenvalue solution (limit "
            f"{MAX_ELEMENTS:.0e} elements); use a size of at least {smallest:.3g} m")


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus [Pa].
    poisson_ratio : float
        Poisson's ratio [-].
    density : float
        Mass density [kg/m^3].
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float

    @property
    def shear_wave_speed(self) -> float:
        """Shear wave speed c_s = sqrt(G / rho) [m/s]."""
        shear_modulus = self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
        return float(np.sqrt(shear_modulus / self.density))

    @property
    def bar_wave_speed(self) -> float:
        """One-dimensional bar wave speed c_0 = sqrt(E / rho) [m/s]."""
        return float(np.sqrt(self.youngs_modulus / self.density))


STEEL = Material(210e9, 0.3, 7850.0)


@dataclass(frozen=True)
class Interfaces:
    """Where the ram and the pile touch the anvil.

    Parameters
    ----------
    ram_contact_radius : float
        Radius of the top face region r <= R that carries the ram [m].
    pile_contact_radius : float
        Mid-radius of the pile wall bearing on the bottom face [m].
    pile_contact_width : float
        Radial width of the pile wall bearing ring [m].
    pile_rings : int, default 1
        The pile port split into this many equal-width rings across the wall, each its own
        uniform pressure and contact [-] (1: one port; see :mod:`anvilwave.anvil_rom.rings`).
    ram_annuli : int, default 1
        The ram port split into this many equal-width annuli from the axis to
        ``ram_contact_radius``, each its own uniform pressure and contact [-] (1: one port;
        with pile rings only, :mod:`anvilwave.anvil_rom.rings`).
    """

    ram_contact_radius: float
    pile_contact_radius: float
    pile_contact_width: float
    pile_rings: int = 1
    ram_annuli: int = 1

    @property
    def ram_annulus_edges(self) -> np.ndarray:
        """The ram annuli's edges [m], from the axis to the ram contact radius."""
        return np.linspace(0.0, self.ram_contact_radius, self.ram_annuli + 1)

    @property
    def pile_ring(self) -> tuple[float, float]:
        """Inner and outer radius of the pile bearing ring [m]."""
        half = 0.5 * self.pile_contact_width
        return self.pile_contact_radius - half, self.pile_contact_radius + half


@dataclass(frozen=True)
class AnvilSpec:
    """Everything needed to build the FE model of an anvil.

    Parameters
    ----------
    name : str
        Name of the anvil (the file stem when read from a file).
    material : Material
        Its material.
    outline : numpy.ndarray, optional
        Closed polygon of the half-section, rows (r, z) [m]; None with ``mesh_file``.
    mesh_file : Path, optional
        Existing 2D axisymmetric mesh read with meshio; None with ``outline``.
    interfaces : Interfaces, optional
        Where the ram and the pile touch the anvil.
    mesh_size : float, default 0.05
        Target element size for gmsh [m].
    fmax : float, default DEFAULT_FMAX
        Frequency content of the modal ROM [Hz].
    damping_ratio : float, default 0.0
        Modal damping ratio [-].
    source : str, default "<memory>"
        Where the spec came from.
    extra : dict
        Further entries (empty by default).
    """

    name: str
    material: Material
    outline: np.ndarray | None = None
    mesh_file: Path | None = None
    interfaces: Interfaces | None = None
    mesh_size: float = 0.05
    fmax: float = DEFAULT_FMAX
    damping_ratio: float = 0.0
    source: str = "<memory>"
    extra: dict = field(default_factory=dict)

    def geometry_hash(self) -> str:
        """SHA-256 of what defines the FE model (outline or mesh file, material, mesh size).

        Returns
        -------
        str
            The hex digest.
        """
        h = hashlib.sha256()
        if self.outline is not None:
            h.update(np.ascontiguousarray(self.outline, dtype=float).tobytes())
        elif self.mesh_file is not None and Path(self.mesh_file).exists():
            h.update(Path(self.mesh_file).read_bytes())
        h.update(np.array([self.material.youngs_modulus, self.material.poisson_ratio,
                           self.material.density, self.mesh_size]).tobytes())
        return h.hexdigest()


def load_anvil(path: str | Path) -> AnvilSpec:
    """Read and validate an anvil file (see the module docstring for the format).

    Parameters
    ----------
    path : str or Path
        The anvil TOML file.

    Returns
    -------
    AnvilSpec
        The validated anvil.

    Raises
    ------
    InputError
        If an entry is missing or breaks its rule.
    """
    root = Table.from_file(path)
    mat = root.table("material")
    material = Material(
        youngs_modulus=mat.number("youngs_modulus", gt=0.0, unit="Pa"),
        poisson_ratio=mat.number("poisson_ratio", ge=0.0, lt=0.5),
        density=mat.number("density", gt=0.0, unit="kg/m^3"),
    )
    mat.finish()

    outline = mesh_file = None
    if root.has("geometry") and isinstance(root.data.get("mesh"), str):
        raise root.error("mesh", "give either [geometry] points or mesh = \"file\", not both")
    if isinstance(root.data.get("mesh"), str):
        mesh_file = root.path("mesh")
        if not mesh_file.exists():
            raise root.error("mesh", f"mesh file {mesh_file} not found")
        mesh_size = 0.05
    else:
        geo = root.table("geometry")
        outline = geo.array("points", columns=2, min_rows=3)
        geo.finish()
        validate_outline(outline, root.source, "geometry.points")
        mesh_table = root.table("mesh")
        mesh_size = mesh_table.number("size", gt=0.0, unit="m")
        mesh_table.finish()
        extent = np.ptp(outline, axis=0).max()
        if mesh_size > 0.5 * extent:
            raise mesh_table.error("size",
                                   f"must be at most half the anvil size ({0.5 * extent:g} m)")
        rule = mesh_budget_rule(estimated_triangles(outline, mesh_size), mesh_size)
        if rule is not None:
            raise mesh_table.error("size", rule)

    interfaces = None
    itab = root.table("interfaces", required=False)
    if itab is not None:
        interfaces = Interfaces(
            ram_contact_radius=itab.number("ram_contact_radius", gt=0.0, unit="m"),
            pile_contact_radius=itab.number("pile_contact_radius", gt=0.0, unit="m"),
            pile_contact_width=itab.number("pile_contact_width", gt=0.0, unit="m"),
        )
        if interfaces.pile_ring[0] <= 0.0:
            raise itab.error("pile_contact_width", "must be less than twice pile_contact_radius")
        if outline is not None:
            rmax = outline[:, 0].max()
            if interfaces.ram_contact_radius > rmax:
                raise itab.error("ram_contact_radius",
                                 f"must not exceed the anvil radius {rmax:g} m")
            if interfaces.pile_ring[1] > rmax + 1e-12:
                raise itab.error("pile_contact_radius",
                                 f"ring outer radius {interfaces.pile_ring[1]:g} m exceeds the "
                                 f"anvil radius {rmax:g} m")
        itab.finish()

    fmax, damping = DEFAULT_FMAX, 0.0
    mtab = root.table("modes", required=False)
    if mtab is not None:
        fmax = mtab.number("fmax", DEFAULT_FMAX, gt=0.0, unit="Hz")
        damping = mtab.number("damping_ratio", 0.0, ge=0.0, lt=1.0)
        mtab.finish()
    root.finish()
    return AnvilSpec(
        name=Path(path).stem, material=material, outline=outline, mesh_file=mesh_file,
        interfaces=interfaces, mesh_size=mesh_size, fmax=fmax, damping_ratio=damping,
        source=str(path),
    )


def polygon_area(points: np.ndarray) -> float:
    """Signed area of a closed polygon (shoelace) [m^2]; positive counter-clockwise in (r, z).

    Parameters
    ----------
    points : numpy.ndarray
        Polygon vertices, rows (r, z) [m].

    Returns
    -------
    float
        Signed area [m^2].
    """
    r, z = points[:, 0], points[:, 1]
    return 0.5 * float(np.sum(r * np.roll(z, -1) - np.roll(r, -1) * z))


def revolved_volume(points: np.ndarray) -> float:
    """Volume of the solid obtained by revolving a closed (r, z) polygon about the z axis [m^3].

    Pappus: V = 2 pi * A * r_centroid, with the centroid from the shoelace formula; exact for
    polygons.

    Parameters
    ----------
    points : numpy.ndarray
        Polygon vertices, rows (r, z) [m].

    Returns
    -------
    float
        Volume [m^3].
    """
    r, z = points[:, 0], points[:, 1]
    r1, z1 = np.roll(r, -1), np.roll(z, -1)
    cross = r * z1 - r1 * z
    area = 0.5 * np.sum(cross)
    first_moment_r = np.sum((r + r1) * cross) / 6.0  # = A * r_centroid
    return float(abs(2.0 * np.pi * first_moment_r)) if area != 0 else 0.0




def validate_outline(points: np.ndarray, source: str, key: str) -> None:
    """Check that an (r, z) outline is a simple polygon in r >= 0 with a non-zero area.

    Parameters
    ----------
    points : numpy.ndarray
        Polygon vertices, rows (r, z) [m].
    source : str
        The file named in errors.
    key : str
        The key named in errors.

    Raises
    ------
    InputError
        If a radius is negative, two consecutive points coincide, the area is zero, or two edges
        cross.
    """
    if np.any(points[:, 0] < 0.0):
        raise InputError(source, key, "all radii r must be >= 0 (the z axis is r = 0)")
    n = len(points)
    seg = np.linalg.norm(points - np.roll(points, -1, axis=0), axis=1)
    scale = np.ptp(points, axis=0).max()
    if np.any(seg <= 1e-9 * max(scale, 1e-30)):
        i = int(np.argmin(seg))
        raise InputError(source, key, f"points {i} and {(i + 1) % n} coincide (do not repeat "
                                      "the first point at the end)")
    if abs(polygon_area(points)) <= 1e-12 * scale**2:
        raise InputError(source, key, "the polygon has zero area")
    for i in range(n):
        a0, a1 = points[i], points[(i + 1) % n]
        for j in range(i + 1, n):
            if j == i or (j + 1) % n == i or j == (i + 1) % n:
                continue
            b0, b1 = points[j], points[(j + 1) % n]
            if _segments_intersect(a0, a1, b0, b1):
                raise InputError(source, key, f"edges {i}-{(i + 1) % n} and {j}-{(j + 1) % n} "
                                              "cross: the polygon must be simple")


def _segments_intersect(p1, p2, q1, q2) -> bool:
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    d1, d2 = orient(q1, q2, p1), orient(q1, q2, p2)
    d3, d4 = orient(p1, p2, q1), orient(p1, p2, q2)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True

    def on_segment(a, b, c):
        return (min(a[0], b[0]) <= c[0] <= max(a[0], b[0])
                and min(a[1], b[1]) <= c[1] <= max(a[1], b[1]))

    return any(
        d == 0 and on_segment(a, b, c)
        for d, a, b, c in ((d1, q1, q2, p1), (d2, q1, q2, p2), (d3, p1, p2, q1), (d4, p1, p2, q2))
    )
