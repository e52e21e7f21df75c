"""Meshing of the anvil half-section with gmsh, and import of existing meshes with meshio.

The FE model works on a scikit-fem triangle or quadrilateral mesh (linear or quadratic
geometry); coordinates are (r, z) [m] with z pointing down.
"""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import skfem

from anvilwave.anvil_rom.fem.geometry import (
    AnvilSpec,
    Interfaces,
    estimated_triangles,
    mesh_budget_rule,
)
from anvilwave.inputs import InputError, note_input

_TRI = ("triangle", "triangle6")
_QUAD = ("quad", "quad8", "quad9")


def split_outline_at_interfaces(outline: np.ndarray, interfaces: Interfaces | None) -> np.ndarray:
    """Insert polygon vertices where the interface regions end on the top and bottom faces.

    The ram face ends at ``ram_contact_radius`` on the top (minimum z) face (and, split into
    annuli, at their edges) and the pile ring spans ``pile_ring`` on the bottom (maximum z)
    face; putting vertices there makes element edges coincide with the interface limits, so
    the interface load vectors are exact.

    Parameters
    ----------
    outline : numpy.ndarray
        Polygon vertices, rows (r, z) [m].
    interfaces : Interfaces or None
        The interfaces; None returns ``outline`` unchanged.

    Returns
    -------
    numpy.ndarray
        The outline with the inserted vertices [m].
    """
    if interfaces is None:
        return outline
    ztop, zbot = outline[:, 1].min(), outline[:, 1].max()
    outline = split_outline_at_radii(outline, ztop, interfaces.ram_annulus_edges[1:])
    return split_outline_at_radii(outline, zbot, interfaces.pile_ring)


def split_outline_at_radii(outline: np.ndarray, z: float, radii) -> np.ndarray:
    """``outline`` with a vertex inserted at each of ``radii`` [m] on its horizontal edges.

    The edges are those at height ``z`` [m] (where an edge spans that radius).

    Parameters
    ----------
    outline : numpy.ndarray
        Polygon vertices, rows (r, z) [m].
    z : float
        Height of the horizontal edges [m].
    radii : sequence of float
        Radii of the new vertices [m].

    Returns
    -------
    numpy.ndarray
        The outline with the inserted vertices [m].
    """
    tol = 1e-9 * max(np.ptp(outline, axis=0).max(), 1.0)
    points = [tuple(p) for p in outline]
    for rcut in radii:
        out = []
        n = len(points)
        for i in range(n):
            a, b = points[i], points[(i + 1) % n]
            out.append(a)
            horizontal = abs(a[1] - z) < tol and abs(b[1] - z) < tol
            if horizontal and min(a[0], b[0]) + tol < rcut < max(a[0], b[0]) - tol:
                out.append((rcut, z))
        points = out
    return np.array(points, dtype=float)


def split_outline_at_heights(outline: np.ndarray, r: float, heights) -> np.ndarray:
    """``outline`` with a vertex inserted at each of ``heights`` [m] on its vertical edges.

    The edges are those at radius ``r`` [m] (where an edge spans that height): the bands of a
    cylindrical face (:func:`anvilwave.anvil_rom.fem.elasticity.band_vectors`).

    Parameters
    ----------
    outline : numpy.ndarray
        Polygon vertices, rows (r, z) [m].
    r : float
        Radius of the vertical edges [m].
    heights : sequence of float
        Heights of the new vertices [m].

    Returns
    -------
    numpy.ndarray
        The outline with the inserted vertices [m].
    """
    swapped = split_outline_at_radii(np.asarray(outline, float)[:, ::-1], r, heights)
    return np.ascontiguousarray(swapped[:, ::-1])


def mesh_outline(outline: np.ndarray, size: float | None, *, point_sizes=None,
                 edge_divisions: dict[int, int] | None = None) -> meshio.Mesh:
    """Mesh a closed (r, z) polygon with gmsh into quadratic (6-node) triangles.

    Parameters
    ----------
    outline : (n, 2) array
        Polygon vertices (r, z) [m], not repeating the first point.
    size : float
        Target element size [m] (everywhere, unless ``point_sizes`` is given).
    point_sizes : (n,) array, optional
        Target size at each vertex [m]; gmsh interpolates between them (local refinement).
    edge_divisions : {i: m}, optional
        Split edge i (vertex i to i + 1) into exactly m equal elements.

    Returns
    -------
    meshio.Mesh
        The ``triangle6`` mesh, unreferenced points dropped.

    Raises
    ------
    ValueError
        If the mesh at ``size`` would exceed the mesh budget (:func:`mesh_budget_rule`).
    """
    import gmsh

    if size is not None:
        rule = mesh_budget_rule(estimated_triangles(outline, size), size)
        if rule is not None:
            raise ValueError(f"mesh size {size:g} m {rule}")
    if not gmsh.isInitialized():
        gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("anvil")
    sizes = np.full(len(outline), size) if point_sizes is None else np.asarray(point_sizes)
    try:
        tags = [gmsh.model.geo.addPoint(r, z, 0.0, h)
                for (r, z), h in zip(outline, sizes, strict=True)]
        lines = [gmsh.model.geo.addLine(tags[i], tags[(i + 1) % len(tags)])
                 for i in range(len(tags))]
        loop = gmsh.model.geo.addCurveLoop(lines)
        gmsh.model.geo.addPlaneSurface([loop])
        for edge, count in (edge_divisions or {}).items():
            gmsh.model.geo.mesh.setTransfiniteCurve(lines[edge], int(count) + 1)
        gmsh.model.geo.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 1)
        gmsh.model.mesh.generate(2)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        etypes, _, enodes = gmsh.model.mesh.getElements(dim=2)
    finally:
        gmsh.model.remove()
    xyz = np.asarray(coords).reshape(-1, 3)
    index = np.zeros(int(np.max(node_tags)) + 1, dtype=np.int64)
    index[np.asarray(node_tags, dtype=np.int64)] = np.arange(len(node_tags))
    cells = []
    for etype, conn in zip(etypes, enodes, strict=True):
        if etype != 9:  # 9 = 6-node triangle
            raise RuntimeError(f"gmsh produced unexpected element type {etype}")
        cells.append(("triangle6", index[np.asarray(conn, dtype=np.int64).reshape(-1, 6)]))
    return _compact(meshio.Mesh(xyz[:, :2], cells))


def read_mesh(path: str | Path, source: str = "", key: str = "mesh") -> meshio.Mesh:
    """Read an existing 2D axisymmetric mesh (x = r, y = z) with meshio; keep its 2D cells.

    Parameters
    ----------
    path : str or Path
        The mesh file (anything meshio reads).
    source : str, default ""
        The input file named in errors (default: ``path``).
    key : str, default "mesh"
        The key named in errors.

    Returns
    -------
    meshio.Mesh
        The mesh of one 2D cell type, unreferenced points dropped.

    Raises
    ------
    InputError
        If meshio cannot read the file, it has no or mixed 2D cells, it is not in the (r, z)
        plane, or a radius is negative.
    """
    try:
        mesh = meshio.read(path)
    except Exception as exc:  # meshio raises many kinds of errors for unreadable files
        raise InputError(source or path, key, f"meshio cannot read {path}: {exc}") from None
    note_input(path)
    cells = [(c.type, c.data) for c in mesh.cells if c.type in _TRI + _QUAD]
    kinds = {("tri" if t in _TRI else "quad") for t, _ in cells}
    if not cells:
        raise InputError(source or path, key, f"{path} holds no triangle or quadrilateral cells")
    if len(kinds) > 1 or len({t for t, _ in cells}) > 1:
        raise InputError(source or path, key, f"{path} mixes element types; use one type")
    points = np.asarray(mesh.points, dtype=float)
    if points.shape[1] == 3:
        if np.any(np.abs(points[:, 2]) > 1e-12 * max(np.abs(points).max(), 1.0)):
            raise InputError(source or path, key, "the mesh must lie in the (r, z) plane (third "
                                                  "coordinate zero)")
        points = points[:, :2]
    ctype = cells[0][0]
    conn = np.concatenate([c for _, c in cells])
    used = np.unique(conn)
    if np.any(points[used, 0] < -1e-9 * np.abs(points).max()):
        raise InputError(source or path, key, "all radii (x coordinates) must be >= 0")
    return _compact(meshio.Mesh(points, [(ctype, conn)]))


def _compact(mesh: meshio.Mesh) -> meshio.Mesh:
    """Drop unreferenced points (gmsh keeps geometry points) and renumber."""
    ctype, conn = mesh.cells[0].type, mesh.cells[0].data
    used, inverse = np.unique(conn, return_inverse=True)
    return meshio.Mesh(mesh.points[used], [(ctype, inverse.reshape(conn.shape))])


def to_skfem(mesh: meshio.Mesh) -> skfem.Mesh:
    """Convert a 2D meshio mesh to a scikit-fem mesh.

    Linear meshes keep their straight-edged geometry; the FE model always puts quadratic
    Lagrange elements on them (see :func:`anvilwave.anvil_rom.fem.elasticity.element_for`).

    Parameters
    ----------
    mesh : meshio.Mesh
        The 2D mesh.

    Returns
    -------
    skfem.Mesh
        The scikit-fem mesh.
    """
    from skfem.io.meshio import from_meshio

    ctype = mesh.cells[0].type
    return from_meshio(meshio.Mesh(np.asarray(mesh.points)[:, :2], [(ctype, mesh.cells[0].data)]))


def build_mesh(spec: AnvilSpec) -> meshio.Mesh:
    """The mesh of an anvil spec: gmsh for an outline, meshio for a mesh file.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil.

    Returns
    -------
    meshio.Mesh
        Its mesh.
    """
    if spec.outline is not None:
        outline = split_outline_at_interfaces(spec.outline, spec.interfaces)
        return mesh_outline(outline, spec.mesh_size)
    return read_mesh(spec.mesh_file, spec.source, "mesh")
