"""The ram as a Mode Displacement Method ROM: the anvil's method applied to the ram.

A 1D rod (Smith's chain, :mod:`hammer.ram`) has no lateral inertia: every frequency travels at
the bar speed c = sqrt(E / rho). A real ram of 1.8 m diameter is not slender for the 1-3 kHz
content of an impact: the radial motion that Poisson's ratio couples to the axial strain
(Love 1927; Pochhammer-Chree) slows and disperses its high frequencies, and the ram's first
radial-axial modes (near 1.6 kHz for 1.8 m) shape the tail of the wave it returns to the
anvil. Against the axisymmetric FEA of the Table 1 impact the 1D ram puts the pile's peak force
about 5 % high; with Poisson's ratio set to 0 in the FEA's ram the 1D ram matches it.

Here the ram gets the anvil's treatment: its section (the hammer's ``sections``) is meshed and
assembled like an anvil (:mod:`anvil_rom`), its free-free modes up to fmax (the same single
parameter) are projected on the striking face (uniform pressure on the toe), and

* the modes are realised as the equivalent spring-mass chain (:mod:`anvil_rom.chain`): the
  same driving-point receptance sum p_j^2 / (omega_j^2 - w^2), the same total mass, so the
  leapfrog ram kernel, the Ram FMU and the coupled stability bound run it unchanged;
* the residual flexibility of the truncated modes at the toe (inertia relief, as the anvil's
  static correction) becomes the ram's side of the contact spring, ``toe_stiffness``
  = 1 / r_toe, the role the toe half segment 2 E A / dx plays in Smith's ram. The static
  toe compliance is then exact whatever fmax.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from functools import lru_cache

import numpy as np

from anvil_rom.chain import chain_from_modes
from anvil_rom.geometry import AnvilSpec, Interfaces, Material, validate_outline
from anvil_rom.rom import residual_flexibility
from anvilwave_inputs import InputError

from .ram import RamRod

DEFAULT_POISSON_RATIO = 0.3
"""Poisson's ratio of the ram [-] (steel, DESIGN.md)."""
ELEMENTS_PER_SHEAR_WAVELENGTH = 6.0
"""Default mesh: target quadratic elements per shear wavelength at fmax. The modal analysis
refuses fewer than 4 on the LONGEST edge (:func:`anvil_rom.modes.mesh_resolvable_frequency`),
and gmsh's longest edges exceed the target size by up to about 40 %."""
ELEMENTS_PER_RADIUS = 6
"""Default mesh: at least this many elements across the toe radius (and across a wall)."""


def ram_outline(sections: np.ndarray) -> np.ndarray:
    """Half-section polygon (r, z) [m] of a ram of stacked circular sections, z down from the
    top face; rows of ``sections`` are [length, outer diameter, inner diameter] [m], top first.
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
    """Element size [m]: ELEMENTS_PER_SHEAR_WAVELENGTH per shear wavelength at fmax [Hz] and
    ELEMENTS_PER_RADIUS across the toe radius and the thinnest wall."""
    sections = np.asarray(sections, float)
    walls = 0.5 * (sections[:, 1] - sections[:, 2])
    return float(min(material.shear_wave_speed / (ELEMENTS_PER_SHEAR_WAVELENGTH * fmax),
                     walls.min() / ELEMENTS_PER_RADIUS))


def modal_ram(ram: RamRod, fmax: float, *, poisson_ratio: float = DEFAULT_POISSON_RATIO,
              mesh_size: float | None = None, source: str = "hammer",
              modes: Callable | None = None, realise: Callable | None = None) -> RamRod:
    """The modal ROM of ``ram`` (given by its sections) up to ``fmax`` [Hz], as a RamRod.

    poisson_ratio [-]; mesh_size [m] (default :func:`default_mesh_size`). Errors name
    ``source`` and the key: a ram without sections (rigid, explicit segments) has no shape to
    mesh. modes : ``modes(spec, fmax) -> ModalData`` of the ram's section (default: computed,
    :func:`anvil_rom.pipeline.compute_anvil_modes`); realise : ``realise(omega, participation)
    -> (mass, stiffness)`` of the chain (default :func:`anvil_rom.chain.chain_from_modes`). The
    system layer passes its modal-data cache for both.
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
    mass, stiffness, toe_stiffness = _modal_chain(
        np.ascontiguousarray(ram.sections, float).tobytes(), ram.sections.shape[0],
        material, float(fmax), float(size), source, modes, realise)
    return dataclasses.replace(ram, mass=mass[::-1].copy(), stiffness=stiffness[::-1].copy(),
                               toe_stiffness=toe_stiffness, fmax=float(fmax))


@lru_cache(maxsize=16)
def _modal_chain(sections_bytes: bytes, n_sections: int, material: Material, fmax: float,
                 mesh_size: float, source: str, modes: Callable | None,
                 realise: Callable | None = None) -> tuple[np.ndarray, np.ndarray, float]:
    """Chain masses and springs (toe first) and the toe stiffness; cached per ram and fmax."""
    sections = np.frombuffer(sections_bytes).reshape(n_sections, 3)
    outline = ram_outline(sections)
    validate_outline(outline, source, "ram")
    outer, inner = 0.5 * sections[-1, 1], 0.5 * sections[-1, 2]
    toe = Interfaces(ram_contact_radius=0.5 * sections[0, 1],
                     pile_contact_radius=0.5 * (outer + inner), pile_contact_width=outer - inner)
    spec = AnvilSpec("ram", material, outline=outline, interfaces=toe, mesh_size=mesh_size,
                     fmax=fmax, source=source)
    if modes is None:
        from anvil_rom.pipeline import compute_anvil_modes

        data = compute_anvil_modes(spec, fmax=fmax).modal_data
    else:
        data = modes(spec, fmax)
    omega = 2.0 * np.pi * np.asarray(data.frequencies)
    p_toe = np.asarray(data.participation_pile)
    r = residual_flexibility(data.elastic_flexibility, omega, data.participation_ram, p_toe)
    mass, stiffness = (chain_from_modes if realise is None else realise)(omega, p_toe)
    mass.flags.writeable = False
    stiffness.flags.writeable = False
    return mass, stiffness, float(1.0 / r[1, 1])
