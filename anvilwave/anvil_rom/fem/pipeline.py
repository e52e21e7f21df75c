"""Anvil file -> mesh -> FE model -> modes -> modal data: the stages in one place."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import meshio
import numpy as np

from anvilwave.anvil_rom.fem.calculix import modes_from_calculix
from anvilwave.anvil_rom.fem.elasticity import (
    AxisymmetricModel,
    assemble,
    interface_vectors,
    radial_interface_vectors,
    ram_annulus_vectors,
    ring_vectors,
)
from anvilwave.anvil_rom.fem.geometry import AnvilSpec, revolved_volume
from anvilwave.anvil_rom.fem.mesh import build_mesh, read_mesh, to_skfem
from anvilwave.anvil_rom.fem.modalfile import ModalData
from anvilwave.anvil_rom.fem.modes import (
    ModeSet,
    elastic_flexibility,
    free_free_modes,
    mesh_resolvable_frequency,
)
from anvilwave.inputs import InputError


@dataclass
class AnvilModes:
    """Result of the modal analysis of an anvil.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil.
    mesh : meshio.Mesh
        Its mesh.
    model : AxisymmetricModel
        The assembled FE model.
    modes : ModeSet
        The free-free modes.
    modal_data : ModalData or None
        The modal data (ROM); None without interfaces.
    b_ram : numpy.ndarray or None
        Unit-resultant load vector of the ram face; None without interfaces.
    b_pile : numpy.ndarray or None
        Unit-resultant load vector of the pile ring; None without interfaces.
    wall_time : float
        Wall time of the analysis [s].
    """

    spec: AnvilSpec
    mesh: meshio.Mesh
    model: AxisymmetricModel
    modes: ModeSet
    modal_data: ModalData | None
    b_ram: np.ndarray | None
    b_pile: np.ndarray | None
    wall_time: float


def check_fmax(model: AxisymmetricModel, fmax: float, source: str, key: str = "fmax") -> None:
    """Refuse an fmax the mesh cannot resolve (see :func:`mesh_resolvable_frequency`).

    Parameters
    ----------
    model : AxisymmetricModel
        The assembled model.
    fmax : float
        Requested frequency content [Hz].
    source : str
        The file named in errors.
    key : str, default "fmax"
        The key named in errors.

    Raises
    ------
    InputError
        If ``fmax`` is above what the mesh resolves.
    """
    limit = mesh_resolvable_frequency(model)
    if fmax > limit:
        raise InputError(source, key, f"{fmax:g} Hz is above what the mesh resolves ({limit:.0f} "
                                      "Hz, four quadratic elements per shear wavelength): refine "
                                      "the mesh (mesh.size) or lower fmax")


def modal_data_from_modes(spec: AnvilSpec, model: AxisymmetricModel, modes: ModeSet,
                          b_ram: np.ndarray, b_pile: np.ndarray, areas: tuple[float, float],
                          source: str = "anvilwave", radial: bool = False) -> ModalData:
    """Project modes on the interfaces and pack them with the static flexibility.

    With ``spec.interfaces.pile_rings`` > 1 also on the pile's rings
    (:func:`anvilwave.anvil_rom.fem.elasticity.ring_vectors`), with the flexibility between the
    ram face and the rings; with ``ram_annuli`` > 1 also on the ram face's annuli
    (:func:`anvilwave.anvil_rom.fem.elasticity.ram_annulus_vectors`), the flexibility then
    between the annuli and the rings.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil (with interfaces).
    model : AxisymmetricModel
        The assembled model.
    modes : ModeSet
        Its modes.
    b_ram : numpy.ndarray
        Unit-resultant load vector of the ram face.
    b_pile : numpy.ndarray
        Unit-resultant load vector of the pile ring.
    areas : tuple of float
        Ram face and pile ring areas [m^2].
    source : str, default "anvilwave"
        Who computed the modes.
    radial : bool, default False
        Also the radial participation of the modes at the ram face and the pile ring and the
        4 x 4 flexibility with it (the optional radial keys of the modal file, for ports with
        friction; :func:`anvilwave.anvil_rom.fem.elasticity.radial_interface_vectors`).

    Returns
    -------
    ModalData
        The modal data.

    Raises
    ------
    InputError
        If the ram port is split into annuli without pile rings, or a ring or annulus has no
        element edge.
    """
    itf = spec.interfaces
    B = np.column_stack([b_ram, b_pile])
    rings = {}
    if itf.ram_annuli > 1 and itf.pile_rings < 2:
        raise InputError(spec.source, "ram_port_annuli",
                         "the ram port splits into annuli with the pile port in rings only "
                         "(pile_port_rings >= 2)")
    if itf.pile_rings > 1:
        B_rings, ring_areas = _split_port(ring_vectors(model, itf), spec, "pile_port_rings",
                                          itf.pile_rings, "rings", "the pile wall")
        B = np.column_stack([B, B_rings])
    if itf.ram_annuli > 1:
        B_annuli, annulus_areas = _split_port(ram_annulus_vectors(model, itf), spec,
                                              "ram_port_annuli", itf.ram_annuli, "annuli",
                                              "the ram face")
        B = np.column_stack([B, B_annuli])
    participation = B.T @ modes.shapes
    e = model.axial_free
    gravity = modes.shapes.T @ (model.mass @ e)
    flex = elastic_flexibility(model, B)
    flex = 0.5 * (flex + flex.T)
    if radial:
        C = np.column_stack(radial_interface_vectors(model, itf))
        ports = np.column_stack([b_ram, b_pile, C])
        radial_flex = elastic_flexibility(model, ports)
        radial_flex = 0.5 * (radial_flex + radial_flex.T)
        radial_flex[:2, :2] = flex[:2, :2]
        radial_part = C.T @ modes.shapes
        radial_keys = {"participation_ram_radial": radial_part[0],
                       "participation_pile_radial": radial_part[1],
                       "radial_flexibility": radial_flex}
    else:
        radial_keys = {}
    if itf.pile_rings > 1:
        K = itf.pile_rings
        ram_ports = [0] if itf.ram_annuli == 1 else list(range(2 + K, B.shape[1]))
        ports = np.r_[ram_ports, 2:2 + K]  # the ram face (or its annuli), then the rings
        rings = {"participation_rings": participation[2:2 + K],
                 "ring_flexibility": flex[np.ix_(ports, ports)], "ring_areas": ring_areas}
        if itf.ram_annuli > 1:
            rings.update(participation_ram_annuli=participation[2 + K:],
                         ram_annulus_areas=annulus_areas)
        flex = flex[:2, :2]
    mat = spec.material
    return ModalData(
        frequencies=modes.frequencies, participation_ram=participation[0],
        participation_pile=participation[1], participation_gravity=gravity,
        elastic_flexibility=flex, total_mass=model.total_mass(), fmax=modes.fmax,
        damping_ratio=spec.damping_ratio,
        material=np.array([mat.youngs_modulus, mat.poisson_ratio, mat.density]),
        interfaces=np.array([itf.ram_contact_radius, itf.pile_contact_radius,
                             itf.pile_contact_width]),
        interface_areas=np.array(areas), n_dof=model.n_dof, geometry_hash=spec.geometry_hash(),
        source=source, **rings, **radial_keys,
    )


def _split_port(vectors: tuple[np.ndarray, np.ndarray], spec: AnvilSpec, key: str,
                count: int, parts: str, where: str) -> tuple[np.ndarray, np.ndarray]:
    """A port's (load vectors, areas) split into ``count`` ``parts`` across ``where``
    (:func:`anvilwave.anvil_rom.fem.elasticity.annulus_vectors`), refused under ``key`` when a part
    has no facet (a
    mesh coarser than the parts)."""
    if np.any(vectors[1] == 0.0):
        raise InputError(spec.source, key, f"{count} {parts} across {where} need at least as "
                                           "many element edges there: refine the mesh "
                                           f"(mesh.size) or use fewer {parts}")
    return vectors


def compute_anvil_modes(spec: AnvilSpec, fmax: float | None = None) -> AnvilModes:
    """Mesh, assemble and solve the free-free modes of an anvil up to ``fmax`` [Hz].

    The modal data (ROM) is built when the spec has interfaces.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil.
    fmax : float, optional
        Frequency content [Hz] (default: the spec's).

    Returns
    -------
    AnvilModes
        Mesh, model, modes and modal data.
    """
    start = time.perf_counter()
    fmax = spec.fmax if fmax is None else fmax
    mesh = build_mesh(spec)
    model = assemble(to_skfem(mesh), spec.material)
    check_fmax(model, fmax, spec.source)
    modes = free_free_modes(model, fmax)
    return _finish(spec, mesh, model, modes, "anvilwave", start)


def anvil_modes_from_calculix(spec: AnvilSpec, job: str | Path, fmax: float | None = None
                              ) -> AnvilModes:
    """The same result from a CalculiX run ``job``.frd / ``job``.dat of the anvil.

    The mesh is the one in the .frd; material and interfaces come from the anvil spec; only
    modes up to ``fmax`` [Hz] (default: the spec's) are kept, and a Sturm count of the FE model
    on that mesh proves CalculiX found all of them.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil.
    job : str or Path
        The CalculiX job name (without extension).
    fmax : float, optional
        Frequency content [Hz] (default: the spec's).

    Returns
    -------
    AnvilModes
        Mesh, model, modes and modal data.

    Raises
    ------
    InputError
        If a result file is missing.
    """

    start = time.perf_counter()
    job = Path(job)
    frd, dat = job.with_name(job.name + ".frd"), job.with_name(job.name + ".dat")
    for path in (frd, dat):
        if not path.exists():
            raise InputError(str(path), "", "CalculiX result file not found")
    fmax = spec.fmax if fmax is None else fmax
    result = modes_from_calculix(frd, dat, spec.material, fmax=fmax)
    return _finish(spec, result.mesh, result.model, result.modes, "calculix", start)


def _finish(spec, mesh, model, modes, source, start) -> AnvilModes:
    data = b_ram = b_pile = None
    if spec.interfaces is not None:
        b_ram, b_pile, a_ram, a_pile = interface_vectors(model, spec.interfaces)
        if a_ram == 0.0:
            raise InputError(spec.source, "interfaces.ram_contact_radius",
                             "no boundary edge of the top face lies inside this radius")
        if a_pile == 0.0:
            raise InputError(spec.source, "interfaces.pile_contact_radius",
                             "no boundary edge of the bottom face lies in the pile ring")
        data = modal_data_from_modes(spec, model, modes, b_ram, b_pile, (a_ram, a_pile),
                                     source=source)
    return AnvilModes(spec, mesh, model, modes, data, b_ram, b_pile, time.perf_counter() - start)


def solid_mass(spec: AnvilSpec) -> float:
    """Mass of the anvil [kg] without its modes.

    Density times the revolved volume of the outline (:func:`revolved_volume`), which is the FE
    model's total mass e_z^T M e_z (its straight-edged elements tile the outline exactly; they
    agree to round-off); for an anvil given as a mesh file, the assembled mass matrix's total.

    Parameters
    ----------
    spec : AnvilSpec
        The anvil.

    Returns
    -------
    float
        The mass [kg].
    """
    if spec.outline is not None:
        return float(spec.material.density * revolved_volume(np.asarray(spec.outline, float)))
    mesh = read_mesh(spec.mesh_file, spec.source, "mesh")
    return assemble(to_skfem(mesh), spec.material).total_mass()
