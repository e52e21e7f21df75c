"""Axisymmetric linear elasticity with scikit-fem: stiffness, mass, interface vectors.

Displacement u = (u_r, u_z) on the (r, z) half-section, z down. The strains of a solid of
revolution without torsion are (Timoshenko & Goodier, Theory of Elasticity, sec. 114)::

    eps_rr = du_r/dr,  eps_zz = du_z/dz,  eps_tt = u_r / r,  gamma_rz = du_r/dz + du_z/dr

and every integral carries the circumference 2 pi r, so K and M describe the whole body (the
total mass is rho times the revolved volume). Nodes on the axis r = 0 have u_r = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla
import skfem
from skfem import BilinearForm, LinearForm

from anvilwave.anvil_rom.fem.geometry import Interfaces, Material


def lame_parameters(material: Material) -> tuple[float, float]:
    """Lamé parameters (lambda, mu) [Pa] of an isotropic material.

    Parameters
    ----------
    material : Material
        The material.

    Returns
    -------
    lam : float
        First Lamé parameter lambda [Pa].
    mu : float
        Shear modulus mu [Pa].
    """
    E, nu = material.youngs_modulus, material.poisson_ratio
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def _strains(u, r):
    """(eps_rr, eps_zz, eps_tt, gamma_rz) of a vector field evaluated at quadrature points."""
    g = u.grad
    return g[0, 0], g[1, 1], u[0] / r, g[0, 1] + g[1, 0]


@BilinearForm
def _stiffness_form(u, v, w):
    r = w.x[0]
    eu, ev = _strains(u, r), _strains(v, r)
    tr_u, tr_v = eu[0] + eu[1] + eu[2], ev[0] + ev[1] + ev[2]
    energy = (w.lam * tr_u * tr_v
              + 2.0 * w.mu * (eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2])
              + w.mu * eu[3] * ev[3])
    return 2.0 * np.pi * r * energy


@BilinearForm
def _mass_form(u, v, w):
    return 2.0 * np.pi * w.x[0] * w.rho * (u[0] * v[0] + u[1] * v[1])


@LinearForm
def _axial_pressure_form(v, w):
    return 2.0 * np.pi * w.x[0] * v[1]


@LinearForm
def _radial_traction_form(v, w):
    return 2.0 * np.pi * w.x[0] * v[0]


@dataclass
class AxisymmetricModel:
    """Assembled FE model of an axisymmetric solid.

    Parameters
    ----------
    mesh : skfem.Mesh
        The (r, z) mesh [m].
    basis : skfem.Basis
        The scikit-fem basis (full DOF numbering).
    material : Material
        The material.
    stiffness : scipy.sparse.csr_matrix
        Stiffness on the free DOFs (axis u_r removed), shape (n, n) [N/m].
    mass : scipy.sparse.csr_matrix
        Consistent mass on the free DOFs, shape (n, n) [kg].
    free_dofs : numpy.ndarray
        Indices of the free DOFs in the full scikit-fem DOF numbering.

    Attributes
    ----------
    n_dof : int
        Number of free degrees of freedom.
    axial_free : numpy.ndarray
        Unit axial translation on the free DOFs.
    node_dofs : numpy.ndarray
        (n_nodes, 2) DOF indices (u_r, u_z) of every mesh node.
    node_coordinates : numpy.ndarray
        (n_nodes, 2) coordinates (r, z) of the mesh nodes [m].
    """

    mesh: skfem.Mesh
    basis: skfem.Basis
    material: Material
    stiffness: sp.csr_matrix
    mass: sp.csr_matrix
    free_dofs: np.ndarray

    @property
    def n_dof(self) -> int:
        """Number of free degrees of freedom."""
        return len(self.free_dofs)

    @property
    def axial_free(self) -> np.ndarray:
        """Unit axial translation (rigid-body direction) on the free DOFs."""
        e = np.zeros(self.basis.N)
        e[self.basis.nodal_dofs[1]] = 1.0
        if self.basis.facet_dofs.size:
            e[self.basis.facet_dofs[1]] = 1.0
        if getattr(self.basis, "interior_dofs", np.empty((0, 0))).size:
            e[self.basis.interior_dofs[1]] = 1.0
        return e[self.free_dofs]

    def total_mass(self) -> float:
        """Total mass from the mass matrix, e_z^T M e_z [kg].

        Returns
        -------
        float
            The total mass [kg].
        """
        e = self.axial_free
        return float(e @ (self.mass @ e))

    def expand(self, x_free: np.ndarray) -> np.ndarray:
        """Free-DOF vector(s) -> full DOF vector(s) with zeros on the axis.

        Parameters
        ----------
        x_free : numpy.ndarray
            Vector(s) on the free DOFs, shape (n,) or (n, k).

        Returns
        -------
        numpy.ndarray
            Vector(s) on the full DOF numbering, shape (N,) or (N, k).
        """
        x_free = np.asarray(x_free)
        out = np.zeros((self.basis.N,) + x_free.shape[1:])
        out[self.free_dofs] = x_free
        return out

    def nodal(self, x_free: np.ndarray) -> np.ndarray:
        """(n_nodes, 2) displacement (u_r, u_z) at the mesh nodes from a free-DOF vector.

        Parameters
        ----------
        x_free : numpy.ndarray
            Displacement on the free DOFs [m].

        Returns
        -------
        numpy.ndarray
            Nodal displacements, shape (n_nodes, 2) [m].
        """
        full = self.expand(x_free)
        return full[self.node_dofs]

    @property
    def node_dofs(self) -> np.ndarray:
        """(n_nodes, 2) DOF indices (u_r, u_z) of every mesh node (mesh.doflocs order)."""
        b = self.basis
        parts = [b.nodal_dofs.T]
        if b.facet_dofs.size:
            parts.append(b.facet_dofs.T)
        if getattr(b, "interior_dofs", np.empty((0, 0))).size:
            parts.append(b.interior_dofs.T)
        return np.vstack(parts)

    @property
    def node_coordinates(self) -> np.ndarray:
        """(n_nodes, 2) coordinates (r, z) [m] of the rows of :meth:`nodal`."""
        return self.basis.doflocs[:, self.node_dofs[:, 0]].T

    def lumped_mass(self) -> np.ndarray:
        """Diagonal (HRZ) lumped mass on the free DOFs [kg].

        Hinton, Rock & Zienkiewicz (1976): diagonal of the consistent mass scaled so that each
        direction keeps the total mass. Row-sum lumping gives zero or negative corner masses
        for quadratic triangles; HRZ keeps every entry positive.

        Returns
        -------
        numpy.ndarray
            The lumped mass per free DOF [kg].

        References
        ----------
        Hinton, E., Rock, T., Zienkiewicz, O.C. (1976). A note on mass lumping and related
        processes in the finite element method. Earthquake Eng. Struct. Dyn. 4(3), 245-249.
        https://doi.org/10.1002/eqe.4290040305
        """
        diag = self.mass.diagonal()
        e = self.axial_free
        total = self.total_mass()
        axial = e > 0
        out = np.empty_like(diag)
        out[axial] = diag[axial] * total / diag[axial].sum()
        radial = ~axial
        if radial.any():
            out[radial] = diag[radial] * total / (diag[radial].sum() + _axis_radial_diag(self))
        return out


def _axis_radial_diag(model: AxisymmetricModel) -> float:
    """Part of the radial mass diagonal that sits on the (removed) axis DOFs."""
    full = _mass_form.assemble(model.basis, rho=model.material.density).diagonal()
    removed = np.setdiff1d(np.arange(model.basis.N), model.free_dofs)
    return float(full[removed].sum())


def element_for(mesh: skfem.Mesh) -> skfem.Element:
    """Quadratic Lagrange vector element matching the mesh type.

    Parameters
    ----------
    mesh : skfem.Mesh
        A triangle or quadrilateral mesh.

    Returns
    -------
    skfem.Element
        ``ElementVector(ElementTriP2())`` or ``ElementVector(ElementQuad2())``.

    Raises
    ------
    TypeError
        For an unsupported mesh type.
    """
    if isinstance(mesh, skfem.MeshTri2 | skfem.MeshTri1):
        return skfem.ElementVector(skfem.ElementTriP2())
    if isinstance(mesh, skfem.MeshQuad2 | skfem.MeshQuad1):
        return skfem.ElementVector(skfem.ElementQuad2())
    raise TypeError(f"unsupported mesh type {type(mesh).__name__}")


def assemble(mesh: skfem.Mesh, material: Material, intorder: int = 4) -> AxisymmetricModel:
    """Assemble K and the consistent M of an axisymmetric solid, axis u_r removed.

    Parameters
    ----------
    mesh : skfem.Mesh
        Mesh in (r, z) [m].
    material : Material
        Linear elastic material.
    intorder : int, default 4
        Quadrature order (4 integrates the P2 mass exactly on straight triangles except for
        the 1/r hoop term, which is smooth away from the axis).

    Returns
    -------
    AxisymmetricModel
        The assembled model.

    References
    ----------
    Timoshenko, S.P., Goodier, J.N. Theory of Elasticity, sec. 114 (strains of a solid of
    revolution).
    """
    basis = skfem.Basis(mesh, element_for(mesh), intorder=intorder)
    lam, mu = lame_parameters(material)
    K = _stiffness_form.assemble(basis, lam=lam, mu=mu)
    M = _mass_form.assemble(basis, rho=material.density)
    tol = 1e-9 * max(np.abs(mesh.p).max(), 1.0)
    axis_facets = mesh.facets_satisfying(lambda x: np.abs(x[0]) < tol, boundaries_only=True)
    axis_dofs = basis.get_dofs(axis_facets).nodal.get("u^1", np.empty(0, dtype=np.int64))
    axis_dofs = np.union1d(axis_dofs, basis.get_dofs(axis_facets).facet.get("u^1", []))
    # any node exactly on the axis (also isolated ones) gets u_r = 0
    on_axis = np.abs(basis.doflocs[0]) < tol
    radial = np.zeros(basis.N, dtype=bool)
    radial[basis.nodal_dofs[0]] = True
    if basis.facet_dofs.size:
        radial[basis.facet_dofs[0]] = True
    axis_dofs = np.union1d(axis_dofs, np.flatnonzero(on_axis & radial)).astype(np.int64)
    free = np.setdiff1d(np.arange(basis.N), axis_dofs)
    return AxisymmetricModel(mesh, basis, material, K[free][:, free].tocsr(),
                             M[free][:, free].tocsr(), free)


def face_load_vector(model: AxisymmetricModel, select) -> tuple[np.ndarray, float]:
    """Unit-resultant axial load vector of a uniform pressure on selected boundary facets.

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    select : callable
        (r, z) -> bool on facet midpoints, choosing the loaded facets.

    Returns
    -------
    b : numpy.ndarray
        (n_free,) vector with sum over axial DOFs equal to 1 (a pressure 1/A [Pa] on area A).
    area : float
        Loaded area A = integral of 2 pi r ds [m^2].
    """
    fbasis = _facet_basis(model, select)
    if fbasis is None:
        return np.zeros(model.n_dof), 0.0
    raw = _axial_pressure_form.assemble(fbasis)
    area = float(raw.sum())  # integral of 2 pi r N_i, summed over the partition of unity
    return raw[model.free_dofs] / area, area


def _facet_basis(model: AxisymmetricModel, select):
    """scikit-fem facet basis of the boundary facets whose midpoints ``select`` (None: none)."""
    mesh = model.mesh
    facets = mesh.facets_satisfying(lambda x: select(x[0], x[1]), boundaries_only=True)
    if len(facets) == 0:
        return None
    return skfem.FacetBasis(mesh, model.basis.elem, facets=facets, intorder=4)


def face_radial_vector(model: AxisymmetricModel, select) -> tuple[np.ndarray, float]:
    """Load/output vector of a uniform radial traction on selected boundary facets.

    A traction 1 / A [Pa] outward (along +r) on the area A: c. The same vector gives the
    area-weighted mean radial displacement of the facets, c^T x = (1 / A) integral of u_r dA
    (collocated, like :func:`face_load_vector` axially): what a friction traction along a
    horizontal face works on. Axisymmetric, its resultant vanishes (a self-balanced load).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    select : callable
        (r, z) -> bool on facet midpoints, choosing the loaded facets.

    Returns
    -------
    c : numpy.ndarray
        (n_free,) vector, non-zero on radial DOFs only.
    area : float
        Loaded area A = integral of 2 pi r ds [m^2].
    """
    fbasis = _facet_basis(model, select)
    if fbasis is None:
        return np.zeros(model.n_dof), 0.0
    area = float(_axial_pressure_form.assemble(fbasis).sum())
    return _radial_traction_form.assemble(fbasis)[model.free_dofs] / area, area


def interface_vectors(model: AxisymmetricModel, interfaces: Interfaces
                      ) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Load/output vectors of the ram face (top) and the pile ring (bottom).

    The same vector gives the force-weighted mean axial displacement, u = b^T x (collocated,
    passive).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    interfaces : Interfaces
        Where the ram and the pile touch.

    Returns
    -------
    b_ram : numpy.ndarray
        Unit-resultant uniform pressure on the ram face, shape (n_free,).
    b_pile : numpy.ndarray
        Unit-resultant uniform pressure on the pile ring, shape (n_free,).
    a_ram : float
        Ram face area [m^2].
    a_pile : float
        Pile ring area [m^2].
    """
    on_ram, on_pile = _interface_selectors(model, interfaces)
    b_ram, a_ram = face_load_vector(model, on_ram)
    b_pile, a_pile = face_load_vector(model, on_pile)
    return b_ram, b_pile, a_ram, a_pile


def radial_interface_vectors(model: AxisymmetricModel, interfaces: Interfaces
                             ) -> tuple[np.ndarray, np.ndarray]:
    """Radial load/output vectors of the ram face and the pile ring (:func:`face_radial_vector`).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    interfaces : Interfaces
        Where the ram and the pile touch.

    Returns
    -------
    c_ram : numpy.ndarray
        Uniform radial traction 1 / A on the ram face, shape (n_free,).
    c_pile : numpy.ndarray
        Uniform radial traction 1 / A on the pile ring, shape (n_free,).
    """
    on_ram, on_pile = _interface_selectors(model, interfaces)
    return face_radial_vector(model, on_ram)[0], face_radial_vector(model, on_pile)[0]


def _interface_selectors(model: AxisymmetricModel, interfaces: Interfaces):
    """(r, z) -> bool facet selectors of the ram face (top) and the pile ring (bottom)."""
    z = model.mesh.p[1]
    scale = max(np.ptp(model.mesh.p, axis=1).max(), 1.0)
    tol = 1e-7 * scale
    ztop, zbot = z.min(), z.max()
    r_in, r_out = interfaces.pile_ring

    def on_ram(r, zz):
        return (np.abs(zz - ztop) < tol) & (r <= interfaces.ram_contact_radius + tol)

    def on_pile(r, zz):
        return (np.abs(zz - zbot) < tol) & (r >= r_in - tol) & (r <= r_out + tol)

    return on_ram, on_pile


def ring_vectors(model: AxisymmetricModel, interfaces: Interfaces
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Load/output vectors of the pile ring split into ``interfaces.pile_rings`` rings.

    The rings are equal-width across the wall (:func:`annulus_vectors` on the bottom face).
    Their area-weighted sum is the whole ring's vector (:func:`interface_vectors`). A ring
    with no facet (a mesh coarser than the rings) has area 0.

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    interfaces : Interfaces
        Where the pile touches, and ``pile_rings``.

    Returns
    -------
    B : numpy.ndarray
        Unit-resultant uniform pressures, shape (n_free, K).
    areas : numpy.ndarray
        The ring areas, shape (K,) [m^2].
    """
    r_in, r_out = interfaces.pile_ring
    return annulus_vectors(model, model.mesh.p[1].max(), r_in, r_out, interfaces.pile_rings)


def ram_annulus_vectors(model: AxisymmetricModel, interfaces: Interfaces
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Load/output vectors of the ram face split into ``interfaces.ram_annuli`` annuli.

    Equal-width annuli from the axis to the ram contact radius (:func:`annulus_vectors` on the
    top face).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    interfaces : Interfaces
        Where the ram touches, and ``ram_annuli``.

    Returns
    -------
    B : numpy.ndarray
        Unit-resultant uniform pressures, shape (n_free, J).
    areas : numpy.ndarray
        The annuli's areas, shape (J,) [m^2].
    """
    return annulus_vectors(model, model.mesh.p[1].min(), 0.0, interfaces.ram_contact_radius,
                           interfaces.ram_annuli)


def annulus_vectors(model: AxisymmetricModel, z: float, r_lo: float, r_hi: float, count: int,
                    radial: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Unit-resultant uniform pressures on ``count`` equal-width annuli from r_lo to r_hi [m].

    On the boundary face at height z [m] (each facet to the annulus holding its midpoint).
    With ``radial``, each annulus's uniform radial traction 1 / A instead
    (:func:`face_radial_vector`: the area-weighted mean radial displacement of the annulus,
    what a friction traction on it works on).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    z : float
        Height of the boundary face [m].
    r_lo : float
        Inner radius [m].
    r_hi : float
        Outer radius [m].
    count : int
        Number of annuli.
    radial : bool, default False
        The radial tractions instead of the axial pressures.

    Returns
    -------
    B : numpy.ndarray
        Unit-resultant uniform pressures (or radial tractions), shape (n_free, count).
    areas : numpy.ndarray
        The annuli's areas, shape (count,) [m^2] (0 for an annulus without facet).
    """
    scale = max(np.ptp(model.mesh.p, axis=1).max(), 1.0)
    tol = 1e-7 * scale
    edges = np.linspace(r_lo, r_hi, count + 1)
    columns, areas = [], []
    for k in range(count):
        lo = edges[k] - (tol if k == 0 else 0.0)
        hi = edges[k + 1] + (tol if k == count - 1 else 0.0)
        b, a = (face_radial_vector if radial else face_load_vector)(
            model, lambda r, zz, lo=lo, hi=hi: (np.abs(zz - z) < tol) & (r >= lo) & (r < hi))
        columns.append(b)
        areas.append(a)
    return np.column_stack(columns), np.array(areas)


def band_vectors(model: AxisymmetricModel, r: float, z_top: float, z_bottom: float,
                 count: int, radial: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Unit-resultant uniform tractions on ``count`` equal-height bands of a cylindrical face.

    The boundary face at radius r [m] from z_top to z_bottom [m] (each facet to the band
    holding its midpoint): each band's uniform radial traction 1 / A outward
    (:func:`face_radial_vector`, the area-weighted mean radial displacement of the band, what
    a guiding sleeve's normal pressure works on), or with ``radial`` False its uniform axial
    traction (:func:`face_load_vector`, what a friction traction along the sleeve works on).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    r : float
        Radius of the cylindrical face [m].
    z_top : float
        Upper end of the face [m] (z down).
    z_bottom : float
        Lower end [m].
    count : int
        Number of bands.
    radial : bool, default True
        The radial tractions; False: the axial ones.

    Returns
    -------
    B : numpy.ndarray
        Unit-resultant tractions, shape (n_free, count).
    areas : numpy.ndarray
        The bands' areas 2 pi r dz, shape (count,) [m^2] (0 for a band without facet).
    """
    scale = max(np.ptp(model.mesh.p, axis=1).max(), 1.0)
    tol = 1e-7 * scale
    edges = np.linspace(z_top, z_bottom, count + 1)
    columns, areas = [], []
    for k in range(count):
        lo = edges[k] - (tol if k == 0 else 0.0)
        hi = edges[k + 1] + (tol if k == count - 1 else 0.0)
        b, a = (face_radial_vector if radial else face_load_vector)(
            model, lambda rr, zz, lo=lo, hi=hi: (np.abs(rr - r) < tol) & (zz >= lo) & (zz < hi))
        columns.append(b)
        areas.append(a)
    return np.column_stack(columns), np.array(areas)


def max_eigenvalue(stiffness: sp.spmatrix, mass: np.ndarray, tol: float = 1e-4) -> float:
    """Largest eigenvalue omega_max^2 of M^-1 K [rad^2/s^2], M diagonal.

    Lanczos (ARPACK, which="LA") on the symmetric M^-1/2 K M^-1/2; if it does not converge,
    the Gershgorin bound max_i sum_j |A_ij| (never below the true value) is used instead.

    Parameters
    ----------
    stiffness : scipy.sparse.spmatrix
        K [N/m].
    mass : numpy.ndarray
        Diagonal of M [kg].
    tol : float, default 1e-4
        Relative tolerance of the Lanczos iteration (the result is raised by 10 tol).

    Returns
    -------
    float
        omega_max^2 [rad^2/s^2].
    """
    s = 1.0 / np.sqrt(mass)
    A = (sp.diags(s) @ stiffness @ sp.diags(s)).tocsr()
    v0 = np.random.default_rng(0).standard_normal(A.shape[0])
    try:
        lam = sla.eigsh(A, k=1, which="LA", tol=tol, v0=v0, ncv=min(40, A.shape[0] - 1),
                        maxiter=20 * A.shape[0], return_eigenvectors=False)
        return float(lam[0]) * (1.0 + 10.0 * tol)
    except sla.ArpackNoConvergence:
        return float(np.abs(A).sum(axis=1).max())
