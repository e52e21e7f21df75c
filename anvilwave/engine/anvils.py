"""The system's anvil unit from its settings: the contact springs, the anvil's modal data, and
the driving stack (the anvil and the anvil ring, :class:`anvilwave.anvil_rom.stack.StackUnit`,
``[[anvil.bodies]]``) with its bodies' modes on their ports through the modal-data cache.

The stack's defaults are the system file's (:data:`anvilwave.config.system.STACK_SEAT_RINGS`,
``STACK_PILE_RINGS``, ``STACK_RAM_ANNULI``): ``SEAT_RINGS``, ``PILE_RINGS``, ``RAM_ANNULI``
here.
"""

from __future__ import annotations

import dataclasses
import hashlib

import numpy as np

from anvilwave.anvil_rom.fem.geometry import STEEL, AnvilSpec, Material
from anvilwave.anvil_rom.rings import RamFace
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.stack import (
    Band,
    Face,
    StackBody,
    StackBodyData,
    StackUnit,
    outer_band_face,
    stack_body_data,
)
from anvilwave.anvil_rom.unit import ContactParameters
from anvilwave.config.cache import cache_dir, cached_modal_data, cached_ring_kernel, modal_key
from anvilwave.config.system import (
    STACK_PILE_RINGS as PILE_RINGS,
)
from anvilwave.config.system import (
    STACK_RAM_ANNULI as RAM_ANNULI,
)
from anvilwave.config.system import (
    STACK_SEAT_RINGS as SEAT_RINGS,
)
from anvilwave.config.system import (
    STACK_SLEEVE_BANDS as SLEEVE_BANDS,
)
from anvilwave.config.system import SystemConfig
from anvilwave.hammer.modal_ram import modal_ram
from anvilwave.inputs import InputError
from anvilwave.pile.head_kernel import (
    echo_free_length,
    head_correction,
    rod_head_response,
    tube_contact_stiffness,
)
from anvilwave.pile.kernels import HEAD_EXTRAPOLATION
from anvilwave.pile.kernels import stable_time_step as pile_stable_time_step
from anvilwave.pile.model import substeps

__all__ = ["PILE_RINGS", "RAM_ANNULI", "SEAT_RINGS", "anvil_modal_data", "cached_stack_data",
           "contact_stiffnesses", "stack_faces", "stack_unit", "tube_head", "with_ram_annuli"]


def contact_stiffnesses(cfg: SystemConfig) -> tuple[float, float]:
    """Default (ram, pile) contact stiffnesses [N/m]: the half segments of the neighbours.

    The ram toe mass and the pile top mass sit half a segment from the faces they touch, so the
    contact springs are those half segments, 2 E A / dx (Smith 1960); a value in the system file
    replaces them (e.g. a cushion). A rigid ram has no half segment: its contact stiffness must
    be given.

    Parameters
    ----------
    cfg : SystemConfig
        The system configuration.

    Returns
    -------
    k_ram : float
        Ram contact stiffness [N/m].
    k_pile : float
        Pile contact stiffness [N/m].

    Raises
    ------
    InputError
        If the ram has no toe half segment (rigid, or explicit segments) and
        ``anvil.ram_contact_stiffness`` is not given.
    """
    s = cfg.anvil
    k_pile = s.pile_contact_stiffness or cfg.pile_soil.head_contact_stiffness()
    k_ram = s.ram_contact_stiffness
    if k_ram is None:
        k_ram = cfg.hammer.ram.toe_stiffness
        if not np.isfinite(k_ram):
            raise InputError(cfg.source, "anvil.ram_contact_stiffness",
                             "is required with a rigid ram or a ram given as explicit segments "
                             "(there is no toe half segment to take it from)")
    return float(k_ram), float(k_pile)


def anvil_modal_data(cfg: SystemConfig):
    """The modal data of the system's anvil, from the modal-data cache.

    :func:`anvilwave.config.cache.cached_modal_data`: computed once per machine.

    Parameters
    ----------
    cfg : SystemConfig
        The system configuration.

    Returns
    -------
    ModalData
        The anvil's modes up to ``anvil.fmax``.

    Raises
    ------
    InputError
        If the anvil's specification or ``anvil.fmax`` is invalid.
    """

    try:
        return cached_modal_data(cfg.anvil.spec, fmax=cfg.anvil.fmax)
    except InputError as exc:
        if exc.key != "fmax" or cfg.anvil.fmax is None:
            raise
        raise InputError(cfg.source, "anvil.fmax", exc.rule) from None



def stack_faces(anvil: AnvilSpec, ring: AnvilSpec, seat_rings: int = SEAT_RINGS,
                pile_rings: int = PILE_RINGS, ram_annuli: int = 1,
                sleeve_bands: tuple[int, int] = (0, 0)
                ) -> tuple[tuple[Face | Band, ...], tuple[Face | Band, ...]]:
    """The ports of the two bodies (:mod:`anvilwave.anvil_rom.stack`'s order).

    The seat is the radial overlap of the anvil's flat bottom face and the ring's flat top
    face, in ``seat_rings`` rings (axial and radial on both bodies); the anvil's ram face is
    its file's, in ``ram_annuli`` equal-width annuli from the axis; the ring's bottom port is
    the anvil file's pile ring, in ``pile_rings``; with a sleeve, each body's outer
    cylindrical face in its ``sleeve_bands`` (radial, then axial).

    Parameters
    ----------
    anvil : AnvilSpec
        The anvil (with its interfaces).
    ring : AnvilSpec
        The ring (an outline off the axis).
    seat_rings : int, default SEAT_RINGS
        S [-].
    pile_rings : int, default PILE_RINGS
        K [-].
    ram_annuli : int, default 1
        J [-].
    sleeve_bands : tuple of int, default (0, 0)
        L_a, L_r: the bands of the anvil's and the ring's outer faces (0: no sleeve ports).

    Returns
    -------
    anvil_faces : tuple of Face or Band
        Ram face (J annuli), the seat's S axial and S radial rings (then the L_a radial and
        L_a axial bands).
    ring_faces : tuple of Face or Band
        The seat's S axial and S radial rings, the pile wall's K axial rings (then the L_r
        radial and L_r axial bands).

    Raises
    ------
    InputError
        If a body is not an outline, the faces do not overlap, or a body with bands has no
        vertical outer face.
    """
    if ring.outline is None or anvil.outline is None:
        raise InputError(ring.source, "geometry", "the stack needs both bodies as outlines")
    pts = np.asarray(ring.outline, float)
    top = pts[np.isclose(pts[:, 1], pts[:, 1].min())][:, 0]
    apts = np.asarray(anvil.outline, float)
    bottom = apts[np.isclose(apts[:, 1], apts[:, 1].max())][:, 0]
    inner, outer = max(top.min(), bottom.min()), min(top.max(), bottom.max())
    if not outer > inner:
        raise InputError(ring.source, "geometry", "the ring's flat top face must overlap the "
                                                  "anvil's flat bottom face (the seat)")
    itf = anvil.interfaces
    wall_in, wall_out = itf.pile_ring
    anvil_faces = (Face("axial", "top", 0.0, itf.ram_contact_radius, ram_annuli),
                   Face("axial", "bottom", inner, outer, seat_rings),
                   Face("radial", "bottom", inner, outer, seat_rings))
    ring_faces = (Face("axial", "top", inner, outer, seat_rings),
                  Face("radial", "top", inner, outer, seat_rings),
                  Face("axial", "bottom", wall_in, wall_out, pile_rings))
    if min(sleeve_bands) > 0:
        bands = []
        for spec, count in ((anvil, sleeve_bands[0]), (ring, sleeve_bands[1])):
            try:
                bands.append(tuple(outer_band_face(spec.outline, int(count), d)
                                   for d in ("radial", "axial")))
            except ValueError as exc:
                raise InputError(spec.source, "geometry", f"the sleeve's bands: {exc}") from None
        anvil_faces, ring_faces = anvil_faces + bands[0], ring_faces + bands[1]
    return anvil_faces, ring_faces


def cached_stack_data(spec: AnvilSpec, faces: tuple[Face, ...], fmax: float) -> StackBodyData:
    """:func:`anvilwave.anvil_rom.stack.stack_body_data` through the modal-data cache folder.

    Parameters
    ----------
    spec : AnvilSpec
        The body.
    faces : tuple of Face
        Its stack ports.
    fmax : float
        Frequency content [Hz].

    Returns
    -------
    StackBodyData
        The modes on the ports.
    """
    key = hashlib.sha256((modal_key(spec, fmax) + repr(faces)).encode()).hexdigest()
    path = cache_dir() / f"stackbody-{key}.npz"
    if path.is_file():
        with np.load(path) as npz:
            return StackBodyData(npz["frequencies"], npz["participation"], npz["flexibility"],
                                 npz["participation_gravity"], float(npz["total_mass"]),
                                 npz["areas"])
    data = stack_body_data(spec, faces, fmax)
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(path.name + ".part.npz")
    np.savez(partial, **dataclasses.asdict(data))
    partial.replace(path)
    return data


def tube_head(cfg: SystemConfig, arrays, ring_areas: np.ndarray, h: float
              ) -> tuple[np.ndarray, np.ndarray]:
    """The tube head under a pile port in rings (``[anvil] pile_head = "tube"``).

    The pile's top section as an axisymmetric FE tube (:mod:`anvilwave.pile.head_kernel`,
    cached), its correction to the 1D head for the step ``h`` over the longest blow the file
    sets (``[simulation]`` or ``[driveability] duration``), and the tube's contact springs of
    the rings.

    Parameters
    ----------
    cfg : SystemConfig
        The system (its pile's top section, its durations).
    arrays : PileSoilArrays
        The pile/soil kernel arrays (``cfg.pile_soil.arrays()``).
    ring_areas : numpy.ndarray
        The pile rings' areas, shape (K,) [m^2].
    h : float
        Time step [s].

    Returns
    -------
    D : numpy.ndarray
        What the tube adds to the 1D head at each lag, shape (L, K, K) [m/N]
        (:func:`anvilwave.pile.head_kernel.head_correction`).
    springs : numpy.ndarray
        The rings' contact springs, shape (K,) [N/m]
        (:func:`anvilwave.pile.head_kernel.tube_contact_stiffness`).

    Raises
    ------
    InputError
        If the anvil's pile ring is not the pile's top wall (to 1 mm).
    """
    pile = cfg.pile_soil.pile
    top = pile.sections[0]
    r_out = 0.5 * top.outer_diameter
    r_in = r_out - top.wall_thickness
    ring = cfg.anvil.spec.interfaces.pile_ring
    if max(abs(ring[0] - r_in), abs(ring[1] - r_out)) > 1e-3:
        raise InputError(cfg.source, "anvil.pile_head",
                         f"the tube head is the pile's top section (walls {r_in:g} to {r_out:g} "
                         f"m), but the anvil's pile ring spans {ring[0]:g} to {ring[1]:g} m: "
                         "they must be the same ring (to 1 mm)")
    duration = max(cfg.duration, (cfg.drive.duration or 0.0) if cfg.drive is not None else 0.0)
    steps = int(round(duration / h)) + 1
    length = echo_free_length(top.wave_speed, duration)
    material = Material(top.youngs_modulus, STEEL.poisson_ratio, top.density)
    areas = np.asarray(ring_areas, float)
    tube = cached_ring_kernel(material, r_in, r_out, length, h, steps, areas.size)
    n_sub = substeps(h, float(pile_stable_time_step(arrays.pile, arrays.soil)))
    rod = rod_head_response(pile, h, steps, n_sub, float(arrays.probes[HEAD_EXTRAPOLATION]))
    return head_correction(tube, rod), tube_contact_stiffness(top.youngs_modulus,
                                                              top.wall_thickness, areas)


def stack_unit(cfg: SystemConfig, ring: AnvilSpec | None, *, seat_friction: float = 0.0,
               seat_stiffness: float | None = None, penalty_size: float = 0.1,
               seat_rings: int = SEAT_RINGS, pile_rings: int = PILE_RINGS,
               ring_fmax: float | None = None, ram_annuli: int | None = None,
               pile_head: str = "rod", sleeve_clearance: float | None = None,
               sleeve_friction: float = 0.0, sleeve_bands: tuple[int, int] = SLEEVE_BANDS
               ) -> StackUnit:
    """The system's anvil (and ``ring``) as a :class:`StackUnit` with the system's contacts.

    Parameters
    ----------
    cfg : SystemConfig
        The system (a ROM anvil with static correction, a modal ram).
    ring : AnvilSpec or None
        The anvil ring; None: the anvil alone, on its own ports (the engine's anvil unit).
    seat_friction : float, default 0.0
        Coulomb coefficient of the seat [-].
    seat_stiffness : float or None, default None
        The seat's penalty [N/m]; None: the reference FEA's, E / ``penalty_size`` per area of
        the seat (:data:`anvilwave.fea.impact.DEFAULT_CONTACT_STIFFNESS_FACTOR` = 1).
    penalty_size : float, default 0.1
        Element size the default seat penalty is taken at [m] (the FEA's mesh size).
    seat_rings : int, default SEAT_RINGS
        The seat in this many rings [-].
    pile_rings : int, default PILE_RINGS
        The ring's pile port in this many rings [-].
    ring_fmax : float or None, default None
        The ring's own truncation [Hz]; None: the system's fmax.
    ram_annuli : int or None, default None
        The ram face in this many equal-width annuli [-] (J contacts on the anvil's top face,
        :class:`anvilwave.anvil_rom.rings.RamFace`; the modal ram's toe modes in J annuli,
        :func:`with_ram_annuli`, kept on the unit for the runner); None: :data:`RAM_ANNULI`
        with a ring, the one port without. J > 1 needs the ring.
    pile_head : {"rod", "tube"}, default "rod"
        The ring's pile rings on the 1D pile's head, or on the tube head (:func:`tube_head` at
        the system's ``time_step``; the unit then at rest on it). "tube" needs the ring.
    sleeve_clearance : float or None, default None
        A rigid, fixed guiding sleeve this far [m] off the bodies' outer faces; None: none.
        Its penalty per area is the seat's, E / ``penalty_size`` (the reference FEA's).
    sleeve_friction : float, default 0.0
        Coulomb coefficient against the sleeve [-].
    sleeve_bands : tuple of int, default SLEEVE_BANDS
        The anvil's and the ring's outer faces in this many bands against the sleeve [-].

    Returns
    -------
    StackUnit
        The unit (not yet at rest).

    Raises
    ------
    InputError
        If J > 1 without a ring or without a modal ram, with the ram toe and the anvil's
        ram face of other radii (to 1 mm), or ``pile_head`` "tube" without a ring or a
        ``time_step``.
    """
    k_ram, k_pile = contact_stiffnesses(dataclasses.replace(
        cfg, hammer=dataclasses.replace(cfg.hammer, ram=dataclasses.replace(
            cfg.hammer.ram, toe_stiffness=cfg.hammer.ram.modes.toe_stiffness))))
    contact = ContactParameters(k_ram, k_pile, cfg.anvil.ram_contact_damping,
                                cfg.anvil.pile_contact_damping)
    s = cfg.anvil
    fmax = float(s.fmax)
    if ram_annuli is None:
        ram_annuli = 1 if ring is None else RAM_ANNULI
    if pile_head not in ("rod", "tube"):
        raise InputError(cfg.source, "anvil.pile_head", f"'rod' or 'tube', not {pile_head!r}")
    if pile_head == "tube" and (ring is None or cfg.time_step is None):
        raise InputError(cfg.source, "anvil.pile_head", "the stack's tube head is under the "
                                                        "ring at the system's time_step: it "
                                                        "needs the ring and a time_step")
    if ring is None:
        if ram_annuli > 1:
            raise InputError(cfg.source, "ram_annuli", "the ram face in annuli without a ring is "
                                                       "the engine's ([anvil] ram_port_annuli)")
        rom = ModalAnvil.from_modal_data(anvil_modal_data(cfg), fmax=fmax,
                                         damping_ratio=s.damping_ratio,
                                         static_correction=s.static_correction)
        return StackUnit(rom, contact, gravity=cfg.gravity)
    modes, face = None, None
    if ram_annuli > 1:
        modes = with_ram_annuli(cfg, int(ram_annuli)).hammer.ram.modes
        face = _ram_face(cfg, modes, int(ram_annuli))
    bands = (0, 0) if sleeve_clearance is None else tuple(int(n) for n in sleeve_bands)
    anvil_faces, ring_faces = stack_faces(s.spec, ring, seat_rings, pile_rings, int(ram_annuli),
                                          bands)
    ring_fmax = fmax if ring_fmax is None else float(ring_fmax)
    anvil = StackBody.from_data(cached_stack_data(s.spec, anvil_faces, fmax), fmax,
                                s.static_correction, _damping(s.damping_ratio, s.spec))
    body = StackBody.from_data(cached_stack_data(ring, ring_faces, ring_fmax), ring_fmax,
                               s.static_correction, _damping(s.damping_ratio, ring))
    if seat_stiffness is None:
        seat = anvil_faces[1]
        seat_stiffness = ring.material.youngs_modulus / penalty_size * np.pi * (
            seat.r_out**2 - seat.r_in**2)
    unit = StackUnit(anvil, contact, body, seat_rings=seat_rings, pile_rings=pile_rings,
                     seat_stiffness=float(seat_stiffness), seat_friction=seat_friction,
                     gravity=cfg.gravity, ram_face=face, ram_modes=modes,
                     sleeve_clearance=sleeve_clearance, sleeve_bands=bands,
                     sleeve_stiffness=ring.material.youngs_modulus / penalty_size,
                     sleeve_friction=sleeve_friction)
    if pile_head == "tube":
        h = float(cfg.time_step)
        unit.set_step(h)
        walls = body.areas[2 * seat_rings:2 * seat_rings + pile_rings]
        unit.set_head(tube_head(cfg, cfg.pile_soil.arrays(), walls, h))
    return unit


def with_ram_annuli(cfg: SystemConfig, annuli: int) -> SystemConfig:
    """The system with its modal ram's toe also in ``annuli`` equal-width annuli.

    The ram's modes again at the anvil's fmax on the ram's default mesh, with vertices at the
    annuli's edges (:func:`anvilwave.hammer.modal_ram.modal_ram`), so the ram unit and the
    stack's ram face (:func:`stack_unit` with ``ram_annuli``) run the same modes.

    Parameters
    ----------
    cfg : SystemConfig
        The system (a modal ram).
    annuli : int
        J [-] (the system unchanged where its ram's toe is already in J).

    Returns
    -------
    SystemConfig
        The system with the ram's toe modes in J annuli.
    """
    modes = getattr(cfg.hammer.ram, "modes", None)
    if modes is not None and modes.n_annuli == annuli:
        return cfg
    ram = modal_ram(cfg.hammer.ram, float(cfg.anvil.fmax), source=cfg.source,
                    modes=cached_modal_data, annuli=int(annuli))
    return dataclasses.replace(cfg, hammer=dataclasses.replace(cfg.hammer, ram=ram))


def _ram_face(cfg: SystemConfig, modes, annuli: int) -> RamFace:
    """The modal ram's toe ``modes`` in ``annuli`` annuli as the stack's ram face."""
    if modes is None or modes.n_annuli != annuli:
        raise InputError(cfg.source, "ram_annuli", f"the ram face in {annuli} annuli needs the "
                                                   "modal ram's toe in as many")
    toe = 0.5 * cfg.hammer.ram.toe_diameter
    radius = cfg.anvil.spec.interfaces.ram_contact_radius
    if not abs(toe - radius) <= 1e-3:
        raise InputError(cfg.source, "ram_annuli", f"the annuli are the ram toe's (radius "
                                                   f"{toe:g} m) and the anvil's ram face's "
                                                   f"({radius:g} m): they must be the same "
                                                   "face (to 1 mm)")
    return RamFace.of(modes.omega, modes.annulus_participation, modes.participation,
                      modes.annulus_residual, modes.annulus_areas)


def _damping(ratio: float | None, spec: AnvilSpec) -> float:
    """The system's modal damping ratio, or the body file's when the system sets none."""
    return float(spec.damping_ratio if ratio is None else ratio)


