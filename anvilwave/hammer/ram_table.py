"""Reading a ram from a hammer file's ``[ram]`` table: a rod, a rigid body or a modal ram's
toe modes (:func:`ram_from_table`)."""

from __future__ import annotations

import math

import numpy as np

from anvilwave.hammer.modal_ram import ram_from_toe_modes, toe_modes_from_table
from anvilwave.hammer.ram import (
    DEFAULT_SEGMENT_LENGTH,
    STEEL_DENSITY,
    STEEL_ELASTIC_MODULUS,
    RamRod,
    circle_area,
)
from anvilwave.inputs import Table


def ram_from_table(table: Table) -> RamRod:
    """Read a ram from a TOML table (errors name the key and the rule).

    Parameters
    ----------
    table : anvilwave.inputs.Table
        The ``[ram]`` table. ``kind`` is "rod" (default), "rigid" or "modal".

        * rigid: ``mass`` [kg], optional ``diameter`` [m] of the striking face.
        * modal: the toe modes of a modal ram
          (:func:`anvilwave.hammer.modal_ram.toe_modes_from_table`: what a Ram FMU embeds),
          optional ``diameter`` [m].
        * rod, one of: ``diameter`` [m] with ``mass`` [kg] or ``length`` [m], a uniform solid
          cylinder; ``profile`` = [[length, outer_diameter], ...] or [[length, outer, inner],
          ...] [m], top to toe, optionally with ``mass`` [kg] (then the density is the one that
          gives it); ``segment_masses`` [kg] (top first) and ``segment_stiffnesses`` [N/m]
          (n - 1 springs), optional ``diameter`` [m]. With the first two: ``elastic_modulus``
          [Pa] (210e9), ``density`` [kg/m^3] (7850), ``segment_length`` [m] (0.5).

    Returns
    -------
    RamRod
        The ram.

    Raises
    ------
    anvilwave.inputs.InputError
        If a key is missing, invalid, unknown or contradicts another (e.g. ``density`` with
        ``profile`` and ``mass``, both or neither of ``mass`` and ``length``).
    """
    kind = table.string("kind", "rod", choices=("rod", "rigid", "modal"))
    if kind == "modal":

        diameter = _optional(table.number("diameter", None, gt=0, unit="m"))
        modes = toe_modes_from_table(table)
        table.finish()
        return ram_from_toe_modes(modes, diameter)
    if kind == "rigid":
        mass = table.number("mass", gt=0, unit="kg")
        diameter = _optional(table.number("diameter", None, gt=0, unit="m"))
        table.finish()
        return RamRod.rigid(mass, diameter)

    if table.has("segment_masses") or table.has("segment_stiffnesses"):
        masses = table.array("segment_masses")
        stiffnesses = table.array("segment_stiffnesses", min_rows=0)
        if np.any(masses <= 0):
            raise table.error("segment_masses", "must all be greater than 0 kg")
        if np.any(stiffnesses <= 0):
            raise table.error("segment_stiffnesses", "must all be greater than 0 N/m")
        if stiffnesses.size != masses.size - 1:
            raise table.error("segment_stiffnesses",
                              f"must have one entry fewer than segment_masses "
                              f"({masses.size - 1}), got {stiffnesses.size}")
        diameter = _optional(table.number("diameter", None, gt=0, unit="m"))
        table.finish()
        return RamRod.from_segments(masses, stiffnesses, diameter)

    elastic_modulus = table.number("elastic_modulus", STEEL_ELASTIC_MODULUS, gt=0, unit="Pa")
    segment_length = table.number("segment_length", DEFAULT_SEGMENT_LENGTH, gt=0, unit="m")
    if table.has("profile"):
        lengths, outer, inner = _profile(table)
        volume = float(sum(circle_area(o, i) * L for L, o, i in zip(lengths, outer, inner,
                                                                     strict=True)))
        if table.has("mass"):
            if table.has("density"):
                raise table.error("density", "cannot be given together with profile and mass "
                                  "(the density is derived from them)")
            density = table.number("mass", gt=0, unit="kg") / volume
        else:
            density = table.number("density", STEEL_DENSITY, gt=0, unit="kg/m^3")
        table.finish()
        return RamRod.from_profile(lengths, outer, inner, elastic_modulus=elastic_modulus,
                                   density=density, segment_length=segment_length)

    density = table.number("density", STEEL_DENSITY, gt=0, unit="kg/m^3")
    diameter = table.number("diameter", gt=0, unit="m")
    if table.has("mass") == table.has("length"):
        raise table.error("length", "give exactly one of mass and length with diameter "
                          "(or a profile, or segment_masses)")
    area = circle_area(diameter)
    if table.has("mass"):
        length = table.number("mass", gt=0, unit="kg") / (density * area)
    else:
        length = table.number("length", gt=0, unit="m")
    table.finish()
    return RamRod.uniform(length, diameter, elastic_modulus=elastic_modulus, density=density,
                          segment_length=segment_length)


def _profile(table: Table) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    raw = table.data["profile"]
    columns = len(raw[0]) if isinstance(raw, list) and raw and isinstance(raw[0], list) else 2
    if columns not in (2, 3):
        raise table.error("profile", "rows must be [length, outer_diameter] or "
                          "[length, outer_diameter, inner_diameter] [m]")
    rows = table.array("profile", columns=columns)
    lengths, outer = rows[:, 0], rows[:, 1]
    inner = rows[:, 2] if columns == 3 else np.zeros_like(outer)
    if np.any(lengths <= 0):
        raise table.error("profile", "section lengths must be greater than 0 m")
    if np.any(outer <= 0):
        raise table.error("profile", "outer diameters must be greater than 0 m")
    if np.any(inner < 0) or np.any(inner >= outer):
        raise table.error("profile", "inner diameters must be at least 0 m and below the "
                          "outer diameter")
    return lengths, outer, inner


def _optional(value: float | None) -> float:
    return math.nan if value is None else value
