"""One blow of a system with the driving stack (:class:`anvilwave.anvil_rom.stack.StackUnit`),
stepped in-process in DESIGN.md's coupling order, for the comparison with the reference FEA
stack while the engine's loop does not yet take the stack.

The ram is the system's modal ram unit (:class:`anvilwave.hammer.modal_ram.ModalRamUnit`), the
pile/soil the pile unit's kernel (:class:`anvilwave.fmu.units.pile_soil.PileSoilState`), the
anvil any unit with ``forces``/``step``/``rest_on_pile``/``energy`` (the stack, or the anvil
unit itself). From t_n to t_n+1: read the ram toe and the pile head (states), the anvil unit's
two contact forces (feedthrough, at t_n), then every unit steps over h with its force held.
The ram starts half a step before the first contact, as the engine's blow.
"""

from __future__ import annotations

import dataclasses
import hashlib

import numpy as np

from anvilwave.anvil_rom.fem.geometry import AnvilSpec
from anvilwave.anvil_rom.rings import RamFace
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.stack import Face, StackBody, StackBodyData, StackUnit, stack_body_data
from anvilwave.anvil_rom.unit import ContactParameters
from anvilwave.config.cache import cache_dir, cached_modal_data, modal_key
from anvilwave.config.system import SystemConfig
from anvilwave.engine.direct import anvil_modal_data, contact_stiffnesses
from anvilwave.fmu.units.pile_soil import PileSoilState, pile_outputs
from anvilwave.hammer.modal_ram import ModalRamUnit, modal_ram
from anvilwave.inputs import InputError


@dataclasses.dataclass
class StackBlow:
    """Records of one blow (every step).

    Parameters
    ----------
    time : numpy.ndarray
        t_n [s], 0 half a step before the first contact.
    ram_force : numpy.ndarray
        Ram-anvil contact force [N].
    pile_force : numpy.ndarray
        Force into the pile head [N].
    energy_residual : numpy.ndarray
        Energy balance of the anvil unit, (E_n + D_n - E_0 - W_n) [J]: its energy, the
        friction and dashpot dissipation, the work the ram and the pile did on it.
    friction_energy : float
        Energy the seat friction dissipated [J].
    input_energy : float
        The ram's kinetic energy at impact [J].
    """

    time: np.ndarray
    ram_force: np.ndarray
    pile_force: np.ndarray
    energy_residual: np.ndarray
    friction_energy: float
    input_energy: float


SEAT_RINGS = 8
"""Seat rings of the ROM stack by default: the seat's 0.55 m on Table 1 in 0.07 m rings, at
least one element edge each on the bodies' 0.05 m meshes (``benchmarks/study_anvil_ring.py``
compares one seat ring with the default against the FEA stack)."""

RAM_ANNULI = 6
"""The ram face of the ring stack in this many annuli by default: against the FEA stack at
mu 0 and 0.2 it puts the pile-head RMS from 15.7 / 10.4 % to 12.6 / 9.1 % and the first ram
contact's impulse nearer the FEA's (``benchmarks/study_anvil_ring.py``, its "1 ram port"
variant the one port)."""

PILE_RINGS = 3
"""Rings of the ring's bottom face on the pile wall by default (one element edge each on the
ring's 0.05 m mesh across the 0.14 m wall)."""


def stack_faces(anvil: AnvilSpec, ring: AnvilSpec, seat_rings: int = SEAT_RINGS,
                pile_rings: int = PILE_RINGS, ram_annuli: int = 1
                ) -> tuple[tuple[Face, ...], tuple[Face, ...]]:
    """The ports of the two bodies (:mod:`anvilwave.anvil_rom.stack`'s order).

    The seat is the radial overlap of the anvil's flat bottom face and the ring's flat top
    face, in ``seat_rings`` rings (axial and radial on both bodies); the anvil's ram face is
    its file's, in ``ram_annuli`` equal-width annuli from the axis; the ring's bottom port is
    the anvil file's pile ring, in ``pile_rings``.

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

    Returns
    -------
    anvil_faces : tuple of Face
        Ram face (J annuli), the seat's S axial and S radial rings.
    ring_faces : tuple of Face
        The seat's S axial and S radial rings, the pile wall's K axial rings.

    Raises
    ------
    InputError
        If a body is not an outline or the faces do not overlap.
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


def stack_unit(cfg: SystemConfig, ring: AnvilSpec | None, *, seat_friction: float = 0.0,
               seat_stiffness: float | None = None, penalty_size: float = 0.1,
               seat_rings: int = SEAT_RINGS, pile_rings: int = PILE_RINGS,
               ring_fmax: float | None = None, ram_annuli: int | None = None) -> StackUnit:
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

    Returns
    -------
    StackUnit
        The unit (not yet at rest).

    Raises
    ------
    InputError
        If J > 1 without a ring or without a modal ram, or with the ram toe and the anvil's
        ram face of other radii (to 1 mm).
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
    anvil_faces, ring_faces = stack_faces(s.spec, ring, seat_rings, pile_rings, int(ram_annuli))
    ring_fmax = fmax if ring_fmax is None else float(ring_fmax)
    anvil = StackBody.from_data(cached_stack_data(s.spec, anvil_faces, fmax), fmax,
                                s.static_correction, _damping(s.damping_ratio, s.spec))
    body = StackBody.from_data(cached_stack_data(ring, ring_faces, ring_fmax), ring_fmax,
                               s.static_correction, _damping(s.damping_ratio, ring))
    if seat_stiffness is None:
        seat = anvil_faces[1]
        seat_stiffness = ring.material.youngs_modulus / penalty_size * np.pi * (
            seat.r_out**2 - seat.r_in**2)
    return StackUnit(anvil, contact, body, seat_rings=seat_rings, pile_rings=pile_rings,
                     seat_stiffness=float(seat_stiffness), seat_friction=seat_friction,
                     gravity=cfg.gravity, ram_face=face, ram_modes=modes)


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


def run_stack_blow(cfg: SystemConfig, unit, h: float | None = None,
                   duration: float | None = None) -> StackBlow:
    """One blow of ``cfg`` with ``unit`` as the anvil, at the fixed step ``h``.

    Parameters
    ----------
    cfg : SystemConfig
        The system (a modal ram).
    unit : StackUnit or AnvilUnit
        The anvil unit (``forces``, ``step``, ``set_step``, ``rest_on_pile``, ``energy``).
    h : float, optional
        Step [s]; default the system's ``time_step``.
    duration : float, optional
        Window [s]; default the system's.

    Returns
    -------
    StackBlow
        The records.
    """
    h = float(cfg.time_step if h is None else h)
    duration = float(cfg.duration if duration is None else duration)
    n = int(round(duration / h))
    unit.set_step(h)
    weight = unit.total_mass * cfg.gravity if hasattr(unit, "total_mass") \
        else unit.anvil.total_mass * cfg.gravity
    pile = PileSoilState(cfg.pile_soil, weight, cfg.gravity)
    u_top0, _ = unit.rest_on_pile(0.0)
    modes = getattr(unit, "ram_modes", None)  # the stack's ram face's, where it has one
    ram = ModalRamUnit(cfg.hammer.ram.modes if modes is None else modes, cfg.gravity)
    velocity = float(cfg.impact_velocity)
    ram.start(u_top0 - 0.5 * h * velocity, velocity, h)
    mass = float(ram.modes.total_mass)
    time = np.arange(n) * h
    f_ram = np.empty(n)
    f_pile = np.empty(n)
    residual = np.empty(n)
    arrays = pile.arrays
    work = 0.0
    e0 = None
    u_r, v_r = float(ram.toe[0]), float(ram.toe[1])
    out = pile_outputs(arrays.pile, arrays.probes, pile.u, pile.v, pile.face0)
    u_p, v_p = out[0], out[1]
    for i in range(n):
        fr, fp = unit.forces(u_r, v_r, u_p, v_p)
        f_ram[i], f_pile[i] = fr, fp
        energy = sum(unit.energy(u_r, v_r, u_p, v_p)) + unit_losses(unit)
        if e0 is None:
            e0 = energy
        residual[i] = energy - e0 - work
        unit.step(fr, fp, h)
        ram.step(fr)
        pile.step(fp, h)
        u_r1, v_r1 = float(ram.toe[0]), float(ram.toe[1])
        out = pile_outputs(arrays.pile, arrays.probes, pile.u, pile.v, pile.face0)
        # F_n against (u_n+1 - u_n-1) / 2: the central-difference scheme's work pairing
        work += 0.5 * h * (fr * (v_r1 + v_r) - fp * (out[1] + v_p))
        u_r, v_r, u_p, v_p = u_r1, v_r1, out[0], out[1]
    friction = float(getattr(unit, "friction_energy", 0.0))
    return StackBlow(time, f_ram, f_pile, residual, friction, 0.5 * mass * velocity**2)


def unit_losses(unit) -> float:
    """Friction and dashpot dissipation an anvil unit has booked so far [J].

    Parameters
    ----------
    unit : StackUnit or AnvilUnit
        The unit.

    Returns
    -------
    float
        Dissipated energy [J] (0 for a unit that books none).
    """
    return float(getattr(unit, "friction_energy", 0.0) + getattr(unit, "dashpot_work", 0.0))
