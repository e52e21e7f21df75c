"""Building blocks of the reference impact FEA: bodies, faces, contacts, boundaries, probes.

Every body is an axisymmetric solid assembled with
:func:`anvilwave.anvil_rom.fem.elasticity.assemble` (quadratic
Lagrange elements, 2 pi r weighting, u_r = 0 on the axis) and HRZ-lumped. Bodies touch along
horizontal faces whose nodes sit at the SAME radii on both sides (conforming meshes), so a
contact is a set of node pairs. Cylinders and tubes are structured (r, z) tensor meshes of
9-node quadrilaterals whose radial vertex positions are copied from the anvil face they touch;
the anvil is meshed with gmsh (6-node triangles) with a finer size on the pile bearing ring.

Coordinates (r, z) [m], z DOWN; each body has its own z origin: z is the position in the stack
(the anvil top face is at z = 0, the ram lies above it at z < 0, the pile below).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla
import skfem

from anvilwave.anvil_rom.fem.elasticity import (
    AxisymmetricModel,
    _stiffness_form,
    assemble,
    lame_parameters,
)
from anvilwave.anvil_rom.fem.geometry import Material

_GAUSS3 = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


# --------------------------------------------------------------------------- bodies


@dataclass
class Body:
    """One elastic body of the stack.

    Parameters
    ----------
    name : str
        Label used in messages and outputs.
    model : AxisymmetricModel
        Assembled axisymmetric FE model (K, consistent M on the free DOFs).
    lumped_mass : numpy.ndarray
        HRZ lumped mass, shape (n_dof,) [kg].
    offset : int, default 0
        Index of the body's first DOF in the global vector.
    """

    name: str
    model: AxisymmetricModel
    lumped_mass: np.ndarray
    offset: int = 0

    @property
    def n_dof(self) -> int:
        """Number of free degrees of freedom of the body [-]."""
        return self.model.n_dof

    @property
    def mass(self) -> float:
        """Total mass [kg]."""
        return self.model.total_mass()

    def node_free_dofs(self) -> np.ndarray:
        """(n_nodes, 2) local free-DOF index of (u_r, u_z) of every node, -1 where removed.

        Returns
        -------
        numpy.ndarray
            The indices, shape (n_nodes, 2).
        """
        inverse = np.full(self.model.basis.N, -1, dtype=np.int64)
        inverse[self.model.free_dofs] = np.arange(self.model.n_dof)
        return inverse[self.model.node_dofs]

    def axial_indicator(self) -> np.ndarray:
        """(n_dof,) 1 on axial DOFs, 0 on radial ones.

        Returns
        -------
        numpy.ndarray
            The indicator, shape (n_dof,).
        """
        return self.model.axial_free

    def gravity_force(self, gravity: float) -> np.ndarray:
        """Nodal weight [N] from the LUMPED mass, so a free body falls without stress.

        Parameters
        ----------
        gravity : float
            Gravitational acceleration [m/s^2].

        Returns
        -------
        numpy.ndarray
            Nodal weight on the axial DOFs, shape (n_dof,) [N].
        """
        return self.lumped_mass * self.axial_indicator() * gravity


def make_body(name: str, mesh: skfem.Mesh, material: Material) -> Body:
    """Assemble and HRZ-lump one body.

    Parameters
    ----------
    name : str
        Label of the body.
    mesh : skfem.Mesh
        Its axisymmetric (r, z) mesh [m].
    material : Material
        Its material.

    Returns
    -------
    Body
        The assembled body (offset 0).
    """
    model = assemble(mesh, material)
    return Body(name, model, model.lumped_mass())


def tensor_body(name: str, r_vertices: np.ndarray, z_vertices: np.ndarray,
                material: Material) -> Body:
    """A solid cylinder or tube as a structured mesh of 9-node quadrilaterals.

    Parameters
    ----------
    name : str
        Label of the body.
    r_vertices : numpy.ndarray
        Increasing radial vertex coordinates [m]; r_vertices[0] = 0 for a solid cylinder (its
        axis nodes get u_r = 0).
    z_vertices : numpy.ndarray
        Increasing axial vertex coordinates [m].
    material : Material
        Its material.

    Returns
    -------
    Body
        The assembled body.
    """
    mesh = skfem.MeshQuad.init_tensor(np.asarray(r_vertices, float),
                                      np.asarray(z_vertices, float))
    return make_body(name, mesh, material)


def graded_vertices(start: float, stop: float, size: float, fixed=()) -> np.ndarray:
    """Vertex coordinates from start to stop [m] with spacing <= size, through ``fixed`` points.

    Parameters
    ----------
    start : float
        First coordinate [m].
    stop : float
        Last coordinate [m].
    size : float
        Largest spacing [m].
    fixed : sequence of float, default ()
        Coordinates that must be vertices [m] (those outside (start, stop) are ignored).

    Returns
    -------
    numpy.ndarray
        The increasing vertex coordinates [m].
    """
    knots = np.unique(np.concatenate([[start, stop], [x for x in fixed if start < x < stop]]))
    parts = [np.linspace(a, b, max(1, int(np.ceil((b - a) / size - 1e-9))) + 1)[:-1]
             for a, b in zip(knots[:-1], knots[1:], strict=True)]
    return np.concatenate([*parts, [stop]])


# --------------------------------------------------------------------------- faces


@dataclass
class Face:
    """The nodes of one body on a horizontal line z = const, r_min <= r <= r_max, sorted by r.

    Parameters
    ----------
    body : str
        Name of the body.
    z : float
        Position of the line [m].
    radii : numpy.ndarray
        Node radii, shape (n,) [m] (vertices and edge mid-nodes alternate).
    axial_dofs : numpy.ndarray
        GLOBAL axial DOF indices, shape (n,).
    radial_dofs : numpy.ndarray
        GLOBAL radial DOF indices, shape (n,) (-1 on the axis).
    weights : numpy.ndarray
        Integral of 2 pi r N_i dr over the line, shape (n,) [m^2]; sum = the face area. A
        uniform pressure p gives the nodal forces p * weights; the area-weighted mean of a nodal
        field is weights @ x / weights.sum().
    """

    body: str
    z: float
    radii: np.ndarray
    axial_dofs: np.ndarray
    radial_dofs: np.ndarray
    weights: np.ndarray

    @property
    def area(self) -> float:
        """Face area [m^2]."""
        return float(self.weights.sum())


def line_weights(radii: np.ndarray) -> np.ndarray:
    """Integral of 2 pi r N_i dr for the quadratic shape functions of a line of nodes [m^2].

    The integrand is cubic, so 3-point Gauss is exact.

    Parameters
    ----------
    radii : numpy.ndarray
        2m + 1 sorted node radii: vertex, mid-node, vertex, ... (exact midpoints) [m].

    Returns
    -------
    numpy.ndarray
        The weight of each node [m^2].

    Raises
    ------
    ValueError
        If the number of nodes is not 2m + 1 (m >= 1) or the mid-nodes are not at the edge
        midpoints.
    """
    radii = np.asarray(radii, float)
    if len(radii) < 3 or len(radii) % 2 == 0:
        raise ValueError("a quadratic line needs 2m + 1 nodes")
    r0, rm, r1 = radii[:-2:2], radii[1:-1:2], radii[2::2]
    if not np.allclose(rm, 0.5 * (r0 + r1), rtol=0.0, atol=1e-9 * max(radii.max(), 1.0)):
        raise ValueError("mid-nodes are not at the edge midpoints")
    xi, w = _GAUSS3
    shape = np.stack([0.5 * xi * (xi - 1.0), 1.0 - xi**2, 0.5 * xi * (xi + 1.0)])  # (3 nodes, 3 qp)
    r_q = 0.5 * (r0 + r1)[:, None] + 0.5 * (r1 - r0)[:, None] * xi[None, :]     # (m, qp)
    jac = 0.5 * (r1 - r0)[:, None]
    local = np.einsum("eq,aq,q->ea", 2.0 * np.pi * r_q * jac, shape, w)          # (m, 3)
    out = np.zeros(len(radii))
    np.add.at(out, np.arange(0, len(radii) - 2, 2), local[:, 0])
    np.add.at(out, np.arange(1, len(radii) - 1, 2), local[:, 1])
    np.add.at(out, np.arange(2, len(radii), 2), local[:, 2])
    # the axis node's weight is exactly 0 (integrand r N_0); drop its round-off
    return np.where(np.abs(out) < 1e-12 * out.max(), 0.0, out)


def face(body: Body, z: float, r_min: float = 0.0, r_max: float = np.inf) -> Face:
    """The nodes of ``body`` on the line z [m] with r_min <= r <= r_max, as a :class:`Face`.

    Parameters
    ----------
    body : Body
        The body.
    z : float
        Position of the line [m].
    r_min : float, default 0.0
        Smallest radius [m].
    r_max : float, default numpy.inf
        Largest radius [m].

    Returns
    -------
    Face
        The face, nodes sorted by radius.

    Raises
    ------
    ValueError
        If there are no element edges on the line.
    """
    xy = body.model.node_coordinates
    scale = max(np.abs(xy).max(), 1.0)
    tol = 1e-7 * scale
    on = (np.abs(xy[:, 1] - z) < tol) & (xy[:, 0] >= r_min - tol) & (xy[:, 0] <= r_max + tol)
    nodes = np.flatnonzero(on)
    if len(nodes) < 3:
        raise ValueError(f"{body.name}: no element edges on z = {z:g} m, "
                         f"{r_min:g} <= r <= {r_max:g} m")
    nodes = nodes[np.argsort(xy[nodes, 0])]
    radii = xy[nodes, 0]
    dofs = body.node_free_dofs()[nodes]
    radial = np.where(dofs[:, 0] >= 0, dofs[:, 0] + body.offset, -1)
    return Face(body.name, float(z), radii, dofs[:, 1] + body.offset, radial, line_weights(radii))


def sleeve_contact(name: str, body: Body, radius: float, sleeve_radius: float,
                   stiffness_per_area: float, friction_coefficient: float = 0.0
                   ) -> ContactSet:
    """Compression-only contact of a body's outer face with a rigid guiding cylinder (sleeve).

    The face is the body's nodes on r = ``radius``, the sleeve's inner radius
    ``sleeve_radius`` [m]. Each node on the face pairs with the fixed wall: overlap
    u_r - (sleeve_radius - radius) (the radial clearance closes as the body bulges), the
    force pushes the node inwards, and friction acts along the wall (on the axial DOF). Pair
    stiffness = stiffness_per_area times the node's share of the face area, 2 pi radius times
    the integral of N_i dz.

    Parameters
    ----------
    name : str
        Label of the contact.
    body : Body
        The body (its global offset set).
    radius : float
        Radius of its outer face [m].
    sleeve_radius : float
        Inner radius of the sleeve [m] (>= ``radius``).
    stiffness_per_area : float
        Penalty stiffness per unit area [N/m^3].
    friction_coefficient : float, default 0.0
        Coulomb coefficient against the sleeve [-].

    Returns
    -------
    ContactSet
        The node-to-wall pairs (``lower_dofs`` -1).

    Raises
    ------
    ValueError
        If the body has no element edges on r = ``radius``.
    """
    xy = body.model.node_coordinates
    tol = 1e-7 * max(np.abs(xy).max(), 1.0)
    nodes = np.flatnonzero(np.abs(xy[:, 0] - radius) < tol)
    if len(nodes) < 3:
        raise ValueError(f"{body.name}: no element edges on r = {radius:g} m")
    nodes = nodes[np.argsort(xy[nodes, 1])]
    z = xy[nodes, 1]
    # vertices and mid-nodes alternate along z (a face broken by a gap in z shows as a
    # mid-node off its edge's midpoint and is refused)
    weights = 2.0 * np.pi * radius * _line_integrals(z)
    dofs = body.node_free_dofs()[nodes] + body.offset
    n = len(nodes)
    k = stiffness_per_area * weights
    gap = np.full(n, float(sleeve_radius - radius))
    if friction_coefficient <= 0.0:
        return ContactSet(name, dofs[:, 0], np.full(n, -1), k, np.zeros(n), gap,
                          np.full(n, float(radius)))
    return ContactSet(name, dofs[:, 0], np.full(n, -1), k, np.zeros(n), gap,
                      np.full(n, float(radius)), float(friction_coefficient), dofs[:, 1],
                      np.full(n, -1), k.copy())


def _line_integrals(x: np.ndarray) -> np.ndarray:
    """Integral of N_i dx of the quadratic shape functions of a line of 2m + 1 nodes [m]."""
    x = np.asarray(x, float)
    if len(x) < 3 or len(x) % 2 == 0:
        raise ValueError("a quadratic line needs 2m + 1 nodes")
    length = x[2::2] - x[:-2:2]
    if not np.allclose(x[1:-1:2], 0.5 * (x[:-2:2] + x[2::2]), rtol=0.0,
                       atol=1e-9 * max(np.abs(x).max(), 1.0)):
        raise ValueError("mid-nodes are not at the edge midpoints")
    out = np.zeros(len(x))
    out[:-2:2] += length / 6.0
    out[1:-1:2] += 4.0 * length / 6.0
    out[2::2] += length / 6.0
    return out


def vertex_radii(f: Face) -> np.ndarray:
    """Vertex radii of a face (every other node) [m]: the radial grid of a matching body.

    Parameters
    ----------
    f : Face
        The face.

    Returns
    -------
    numpy.ndarray
        The vertex radii [m].
    """
    return f.radii[::2]


# --------------------------------------------------------------------------- contacts


@dataclass
class ContactSet:
    """Node-to-node compression-only penalty contact between two conforming faces.

    The overlap of pair i is d_i = u_upper_i - u_lower_i - gap_i (z down, u the axial
    displacement from the undeformed stack); the pair force follows
    :func:`anvilwave.anvil_rom.contact.contact_force` and pushes the upper node up, the lower
    down. With a friction coefficient mu > 0 each pair also carries Coulomb friction
    (:func:`anvilwave.anvil_rom.contact.coulomb_friction`) along the face, here the radial
    direction of the horizontal faces: relative slip u_r upper - u_r lower, capped by
    mu times the pair's normal force.

    Parameters
    ----------
    name : str
        Label of the contact.
    upper_dofs : numpy.ndarray
        Global axial DOFs of the upper face's nodes, shape (n,).
    lower_dofs : numpy.ndarray
        Global axial DOFs of the lower face's nodes, shape (n,); -1: a rigid fixed wall (the
        sleeve; the "upper" DOFs are then the bodies' normal DOFs towards it).
    stiffness : numpy.ndarray
        Pair stiffness, shape (n,) [N/m].
    damping : numpy.ndarray
        Pair dashpot, shape (n,) [N s/m].
    gap : numpy.ndarray
        Initial geometric gap, shape (n,) [m] (0: the faces touch in the undeformed stack).
    radii : numpy.ndarray
        Radius of each pair, shape (n,) [m].
    friction_coefficient : float, default 0.0
        Coulomb coefficient mu of the pairs [-] (0: frictionless, no tangential force).
    upper_tangential : numpy.ndarray, optional
        Global tangential (radial) DOFs of the upper nodes, shape (n,), -1 on the axis;
        needed when mu > 0.
    lower_tangential : numpy.ndarray, optional
        Same for the lower nodes.
    tangential_stiffness : numpy.ndarray, optional
        Stick spring of each pair, shape (n,) [N/m]; needed when mu > 0.
    """

    name: str
    upper_dofs: np.ndarray
    lower_dofs: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    gap: np.ndarray
    radii: np.ndarray
    friction_coefficient: float = 0.0
    upper_tangential: np.ndarray | None = None
    lower_tangential: np.ndarray | None = None
    tangential_stiffness: np.ndarray | None = None

    def overlap(self, u: np.ndarray) -> np.ndarray:
        """Overlap d = u_upper - u_lower - gap of each pair [m] (u_lower = 0 at a wall).

        Parameters
        ----------
        u : numpy.ndarray
            Global displacement [m].

        Returns
        -------
        numpy.ndarray
            The overlaps, shape (n,) [m].
        """
        lower = self.lower_dofs
        if np.all(lower >= 0):
            return u[self.upper_dofs] - u[lower] - self.gap
        return u[self.upper_dofs] - np.where(lower >= 0, u[np.maximum(lower, 0)], 0.0) - self.gap

    @property
    def has_friction(self) -> bool:
        """Whether the pairs carry friction (mu > 0) [-]."""
        return self.friction_coefficient > 0.0

    def tangential_matrix(self, n: int) -> sp.csr_matrix:
        """Stiffness matrix of the stick springs (all pairs sticking), shape (n, n) [N/m].

        Parameters
        ----------
        n : int
            Number of global DOFs.

        Returns
        -------
        scipy.sparse.csr_matrix
            The matrix (zero without friction); axis nodes (DOF -1) have no tangential DOF.
        """
        if not self.has_friction:
            return sp.csr_matrix((n, n))
        rows, cols, vals = [], [], []
        for i, j, k in zip(self.upper_tangential, self.lower_tangential,
                           self.tangential_stiffness, strict=True):
            dofs = [(d, sign) for d, sign in ((i, 1.0), (j, -1.0)) if d >= 0]
            for a, sa in dofs:
                for b, sb in dofs:
                    rows.append(a)
                    cols.append(b)
                    vals.append(sa * sb * k)
        return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


def contact_between(name: str, upper: Face, lower: Face, stiffness_per_area: float,
                    damping_per_area: float = 0.0, friction_coefficient: float = 0.0
                    ) -> ContactSet:
    """Pair the nodes of two conforming faces; pair stiffness = stiffness_per_area * weight.

    With friction the stick spring of a pair equals its normal penalty spring: the same
    one-element-layer compliance in shear as in compression (the normal penalty's choice,
    :data:`anvilwave.fea.impact.DEFAULT_CONTACT_STIFFNESS_FACTOR`), so the stable step and the
    pair frequency limit stay set by springs of the same size.

    Parameters
    ----------
    name : str
        Label of the contact.
    upper : Face
        The upper face.
    lower : Face
        The lower face (same node radii).
    stiffness_per_area : float
        Penalty stiffness per unit contact area [N/m^3] (e.g. alpha E / h).
    damping_per_area : float, default 0.0
        Contact dashpot per unit area [N s/m^3] (0: elastic contact).
    friction_coefficient : float, default 0.0
        Coulomb coefficient of the pairs [-] (radial slip along the horizontal faces).

    Returns
    -------
    ContactSet
        The node pairs, gap 0.

    Raises
    ------
    ValueError
        If the faces are not conforming (node radii differ).
    """
    if len(upper.radii) != len(lower.radii) or not np.allclose(
            upper.radii, lower.radii, rtol=0.0, atol=1e-7 * max(upper.radii.max(), 1.0)):
        raise ValueError(f"{name}: the faces of {upper.body} and {lower.body} are not conforming "
                         "(node radii differ)")
    weights = 0.5 * (upper.weights + lower.weights)
    if friction_coefficient <= 0.0:
        return ContactSet(name, upper.axial_dofs.copy(), lower.axial_dofs.copy(),
                          stiffness_per_area * weights, damping_per_area * weights,
                          np.zeros(len(weights)), upper.radii.copy())
    return ContactSet(name, upper.axial_dofs.copy(), lower.axial_dofs.copy(),
                      stiffness_per_area * weights, damping_per_area * weights,
                      np.zeros(len(weights)), upper.radii.copy(), float(friction_coefficient),
                      upper.radial_dofs.copy(), lower.radial_dofs.copy(),
                      stiffness_per_area * weights)


def contact_matrix(contact: ContactSet, n: int, active: np.ndarray | None = None) -> sp.csr_matrix:
    """Stiffness matrix of the closed (or ``active``) pairs of a contact set (n x n).

    Parameters
    ----------
    contact : ContactSet
        The contact set.
    n : int
        Number of global DOFs.
    active : numpy.ndarray, optional
        Factor (1 closed, 0 open) per pair; all closed when None.

    Returns
    -------
    scipy.sparse.csr_matrix
        The contact stiffness matrix, shape (n, n) [N/m].
    """
    k = contact.stiffness if active is None else contact.stiffness * active
    i, j = contact.upper_dofs, contact.lower_dofs
    if np.any(j < 0):  # pairs on a rigid wall: a spring to ground
        wall = j < 0
        return (contact_matrix(dataclasses.replace(
            contact, upper_dofs=i[~wall], lower_dofs=j[~wall], stiffness=k[~wall]), n)
            + sp.csr_matrix((k[wall], (i[wall], i[wall])), shape=(n, n)))
    rows = np.concatenate([i, j, i, j])
    cols = np.concatenate([i, j, j, i])
    vals = np.concatenate([k, k, -k, -k])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


# --------------------------------------------------------------------------- boundaries, probes


def dashpot_damping(f: Face, material: Material, n: int, axial_speed: float,
                    radial_speed: float) -> np.ndarray:
    """Diagonal dashpot coefficients [N s/m] of a viscous (Lysmer-type) boundary on a face.

    c_i = rho * speed * weight_i on the axial (and radial) DOF of each face node: a traction
    -rho c v, which absorbs a plane wave travelling at ``speed`` [m/s] normal to the face.

    Parameters
    ----------
    f : Face
        The boundary face.
    material : Material
        Material of the body (its density is used).
    n : int
        Number of global DOFs.
    axial_speed : float
        Wave speed absorbed on the axial DOFs [m/s].
    radial_speed : float
        Wave speed absorbed on the radial DOFs [m/s].

    Returns
    -------
    numpy.ndarray
        Dashpot coefficient per global DOF, shape (n,) [N s/m].
    """
    c = np.zeros(n)
    c[f.axial_dofs] += material.density * axial_speed * f.weights
    radial = f.radial_dofs >= 0
    c[f.radial_dofs[radial]] += material.density * radial_speed * f.weights[radial]
    return c


def section_force_row(body: Body, z: float, n: int) -> np.ndarray:
    """Row vector g with g @ u = axial force across the section z [N], positive compression.

    The force the part below the section exerts on the section nodes is -(K_below u); the one
    the part above exerts is -(K_above u). Averaging the two one-sided values,
    N = 1/2 sum_i [(K_below u)_zi - (K_above u)_zi], cancels the inertia of the section nodes to
    first order; statically both equal the section resultant. (Nodal-force recovery is exact
    for the resultant, unlike averaging element stresses.)

    Parameters
    ----------
    body : Body
        The body cut by the section.
    z : float
        Position of the section [m].
    n : int
        Number of global DOFs.

    Returns
    -------
    numpy.ndarray
        g, shape (n,) [N/m].

    Raises
    ------
    ValueError
        If the section is not inside the body.
    """
    model = body.model
    mesh, basis = model.mesh, model.basis
    centroid_z = mesh.p[1, mesh.t].mean(axis=0)
    lam, mu = lame_parameters(model.material)
    below = np.flatnonzero(centroid_z > z)
    above = np.flatnonzero(centroid_z < z)
    if len(below) == 0 or len(above) == 0:
        raise ValueError(f"{body.name}: the section z = {z:g} m is not inside the body")
    sec = face(body, z)
    local_z = sec.axial_dofs - body.offset
    full_z = model.free_dofs[local_z]
    rows = []
    for elements in (below, above):
        sub = skfem.Basis(mesh, basis.elem, intorder=4, elements=elements)
        K = _stiffness_form.assemble(sub, lam=lam, mu=mu).tocsr()
        rows.append(np.asarray(K[full_z].sum(axis=0)).ravel()[model.free_dofs])
    g = np.zeros(n)
    g[body.offset:body.offset + body.n_dof] = 0.5 * (rows[0] - rows[1])
    return g


# --------------------------------------------------------------------------- statics


def static_preload(stiffness: sp.spmatrix, force: np.ndarray, contacts: list[ContactSet],
                   supported: np.ndarray, max_iterations: int = 20
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Static equilibrium with compression-only contacts and fixed DOFs (active-set iteration).

    Solves (K + K_contact(active)) u = f with u = 0 on ``supported`` DOFs; pairs in tension are
    released and separated pairs that overlap are closed until the active set is stable.

    Parameters
    ----------
    stiffness : scipy.sparse.spmatrix
        Global stiffness K [N/m].
    force : numpy.ndarray
        Load f [N].
    contacts : list of ContactSet
        The contacts.
    supported : numpy.ndarray
        Indices of the fixed DOFs.
    max_iterations : int, default 20
        Most active-set iterations.

    Returns
    -------
    u : numpy.ndarray
        Displacements [m].
    reaction : numpy.ndarray
        Support reaction r [N] (nonzero only on ``supported``): the force the supports exert,
        K u + contact - f = r there.

    Raises
    ------
    RuntimeError
        If the contact active set does not converge.
    """
    n = stiffness.shape[0]
    free = np.setdiff1d(np.arange(n), supported)
    active = [np.ones(len(c.stiffness)) for c in contacts]
    for _ in range(max_iterations):
        A = stiffness.tocsr()
        for c, a in zip(contacts, active, strict=True):
            A = A + contact_matrix(c, n, a)
        A = A.tocsr()
        u = np.zeros(n)
        u[free] = sla.spsolve(A[free][:, free].tocsc(), force[free])
        changed = False
        new_active = []
        for c in contacts:
            overlap = u[c.upper_dofs] - u[c.lower_dofs] - c.gap
            a = (overlap > 0.0).astype(float)
            new_active.append(a)
        for a_old, a_new in zip(active, new_active, strict=True):
            changed |= not np.array_equal(a_old, a_new)
        active = new_active
        if not changed:
            reaction = np.zeros(n)
            reaction[supported] = (A @ u - force)[supported]
            return u, reaction
    raise RuntimeError("static preload: contact active set did not converge")
