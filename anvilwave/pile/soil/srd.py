"""Soil resistance to driving (SRD): from unit resistances against depth to forces per segment.

The SRD is a table of rows ``[depth below mudline [m], unit shaft friction [Pa], unit toe
resistance [Pa]]``, linear between rows (a repeated depth makes a step, for layer boundaries).
The pile head sticks up ``L - penetration`` above the mudline; only the part below it carries
shaft friction, and the toe resistance is taken at the toe depth (= penetration).

Each formula sits in one small function:

* :func:`shaft_perimeter` - friction perimeter of a tubular section (outside, or outside plus
  inside for a coring, unplugged open-ended pile: Stevens, Wiltsie & Turton 1982, the usual
  offshore practice with Alm & Hamre 2001 type SRD);
* :func:`toe_area` - steel annulus (coring) or the full cross-section (plugged);
* :func:`mean_unit_friction` - the exact mean of the piecewise-linear unit friction over the
  embedded part of a segment (equal to the value at the mid-depth of that part wherever the
  table is linear over it, i.e. the classic "interpolate at segment mid-depth");
* :func:`shaft_capacities` - unit friction x perimeter x embedded length, per segment;
* :func:`toe_capacity` - unit toe resistance at the toe x toe area.

References
----------
Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech. Found.
Div. 86(4), 35-61.
Stevens, R.S., Wiltsie, E.A., Turton, T.H. (1982). Evaluating pile drivability for hard clay,
very dense sand and rock. OTC 4205.
Alm, T., Hamre, L. (2001). Soil model for pile driveability predictions based on CPT
interpretations. Proc. 15th ICSMGE, Istanbul, 1297-1302.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PERIMETERS = ("outside+inside", "outside")
"""Friction perimeter options; the first is the default (coring open-ended pile)."""

TOE_AREAS = ("annulus", "plugged")
"""Toe bearing area options; the first is the default (steel annulus of a coring pile)."""


@dataclass(frozen=True, eq=False)
class SoilResistanceTable:
    """Unit soil resistance to driving against depth below the mudline.

    Parameters
    ----------
    depth : numpy.ndarray
        Depth below the mudline, shape (n,) [m], non-decreasing, starting at 0.
    unit_shaft_friction : numpy.ndarray
        Unit shaft friction, shape (n,) [Pa].
    unit_toe_resistance : numpy.ndarray
        Unit toe resistance, shape (n,) [Pa].
    """

    depth: np.ndarray
    unit_shaft_friction: np.ndarray
    unit_toe_resistance: np.ndarray

    @classmethod
    def from_rows(cls, rows: np.ndarray) -> SoilResistanceTable:
        """Build from an (n, 3) array of rows [depth [m], shaft [Pa], toe [Pa]] (not validated).

        Parameters
        ----------
        rows : numpy.ndarray
            The rows, shape (n, 3).

        Returns
        -------
        SoilResistanceTable
            The table.
        """
        rows = np.asarray(rows, dtype=float)
        return cls(rows[:, 0].copy(), rows[:, 1].copy(), rows[:, 2].copy())

    def check(self) -> str | None:
        """The first broken rule as a sentence, or None when the table is valid.

        Returns
        -------
        str or None
            The broken rule, or None.
        """
        if self.depth.size < 1:
            return "needs at least one row"
        if self.depth[0] != 0.0:
            return f"the first row must be at depth 0 m (the mudline), got {self.depth[0]:g} m"
        if np.any(np.diff(self.depth) < 0.0):
            return "depths must not decrease from one row to the next"
        if np.any(self.unit_shaft_friction < 0.0) or np.any(self.unit_toe_resistance < 0.0):
            return "unit resistances must not be negative"
        return None

    def cumulative_friction(self, depth: np.ndarray) -> np.ndarray:
        """Integral of the unit shaft friction from the mudline to ``depth`` [Pa m = N/m].

        Exact for the piecewise-linear table; held constant beyond the last row.

        Parameters
        ----------
        depth : numpy.ndarray
            Depth below the mudline [m] (negative depths count as 0).

        Returns
        -------
        numpy.ndarray
            The integral [N/m].
        """
        z = np.clip(np.asarray(depth, dtype=float), 0.0, None)
        zt, ft = self.depth, self.unit_shaft_friction
        if zt.size == 1:
            return ft[0] * z
        widths = np.diff(zt)
        nodes = np.concatenate(([0.0], np.cumsum(0.5 * widths * (ft[:-1] + ft[1:]))))
        # k: the last row at or above z (the deeper row of a step), so zt[k] <= z < zt[k + 1]
        k = np.clip(np.searchsorted(zt, z, side="right") - 1, 0, zt.size - 1)
        k_next = np.minimum(k + 1, zt.size - 1)
        z0, f0 = zt[k], ft[k]
        width = zt[k_next] - z0
        slope = np.where(width > 0.0, (ft[k_next] - f0) / np.where(width > 0.0, width, 1.0), 0.0)
        f1 = f0 + slope * (z - z0)
        return nodes[k] + 0.5 * (z - z0) * (f0 + f1)

    def toe_resistance(self, depth: float) -> float:
        """Unit toe resistance at ``depth`` below the mudline [Pa] (deeper side of a step).

        Parameters
        ----------
        depth : float
            Depth below the mudline [m].

        Returns
        -------
        float
            Unit toe resistance [Pa].
        """
        zt, qt = self.depth, self.unit_toe_resistance
        k = int(np.searchsorted(zt, depth, side="right")) - 1
        if k >= zt.size - 1:
            return float(qt[-1])
        if k < 0:
            return float(qt[0])
        z0, z1 = zt[k], zt[k + 1]
        return float(qt[k] + (qt[k + 1] - qt[k]) * (depth - z0) / (z1 - z0))


def shaft_perimeter(outer_diameter, wall_thickness, perimeter: str = "outside+inside"):
    """Friction perimeter of a tubular section [m].

    Parameters
    ----------
    outer_diameter : float or array_like
        Outer diameter D [m].
    wall_thickness : float or array_like
        Wall thickness t [m].
    perimeter : {"outside+inside", "outside"}
        ``"outside+inside"`` -> pi D + pi (D - 2t) (coring pile, Stevens et al. 1982);
        ``"outside"`` -> pi D (plugged or closed-ended pile, or inner friction neglected).

    Returns
    -------
    numpy.ndarray
        The friction perimeter [m].

    Raises
    ------
    ValueError
        If ``perimeter`` is unknown.

    References
    ----------
    Stevens, R.S., Wiltsie, E.A., Turton, T.H. (1982). Evaluating pile drivability for hard clay,
    very dense sand and rock. OTC 4205.
    """
    if perimeter == "outside":
        return np.pi * np.asarray(outer_diameter)
    if perimeter == "outside+inside":
        d = np.asarray(outer_diameter)
        return np.pi * d + np.pi * np.maximum(d - 2.0 * np.asarray(wall_thickness), 0.0)
    raise ValueError(f"unknown perimeter {perimeter!r}; choose one of {PERIMETERS}")


def toe_area(outer_diameter: float, wall_thickness: float, area: str = "annulus") -> float:
    """Toe bearing area [m^2].

    Parameters
    ----------
    outer_diameter : float
        Outer diameter D [m].
    wall_thickness : float
        Wall thickness t [m].
    area : {"annulus", "plugged"}
        ``"annulus"`` -> pi/4 (D^2 - (D - 2t)^2) (steel only, coring pile);
        ``"plugged"`` -> pi/4 D^2 (soil plug bears with the steel).

    Returns
    -------
    float
        The toe area [m^2].

    Raises
    ------
    ValueError
        If ``area`` is unknown.
    """
    d = outer_diameter
    if area == "plugged":
        return 0.25 * np.pi * d * d
    if area == "annulus":
        di = max(d - 2.0 * wall_thickness, 0.0)
        return 0.25 * np.pi * (d * d - di * di)
    raise ValueError(f"unknown toe area {area!r}; choose one of {TOE_AREAS}")


def embedded_lengths(top_depth, bottom_depth, mudline_depth: float) -> np.ndarray:
    """Length of each segment below the mudline [m].

    Parameters
    ----------
    top_depth : array_like
        Upper segment ends below the pile head [m].
    bottom_depth : array_like
        Lower segment ends below the pile head [m].
    mudline_depth : float
        Depth of the mudline below the pile head [m].

    Returns
    -------
    numpy.ndarray
        Embedded length per segment [m].
    """
    top = np.maximum(np.asarray(top_depth, dtype=float), mudline_depth)
    return np.maximum(np.asarray(bottom_depth, dtype=float) - top, 0.0)


def mean_unit_friction(table: SoilResistanceTable, top_depth, bottom_depth,
                       mudline_depth: float) -> np.ndarray:
    """Mean unit shaft friction over the embedded part of each segment [Pa] (0 when none).

    Parameters
    ----------
    table : SoilResistanceTable
        The SRD table.
    top_depth : array_like
        Upper segment ends, depth below the pile head [m].
    bottom_depth : array_like
        Lower segment ends, depth below the pile head [m].
    mudline_depth : float
        Depth of the mudline below the pile head, L - penetration [m].

    Returns
    -------
    numpy.ndarray
        Mean unit friction per segment [Pa].
    """
    length = embedded_lengths(top_depth, bottom_depth, mudline_depth)
    z_top = np.maximum(np.asarray(top_depth, dtype=float), mudline_depth) - mudline_depth
    z_bot = np.asarray(bottom_depth, dtype=float) - mudline_depth
    integral = table.cumulative_friction(np.maximum(z_bot, 0.0)) - table.cumulative_friction(z_top)
    safe = np.where(length > 0.0, length, 1.0)
    return np.where(length > 0.0, integral / safe, 0.0)


def shaft_capacities(table: SoilResistanceTable, top_depth, bottom_depth, mudline_depth: float,
                     outer_diameter, wall_thickness,
                     perimeter: str = "outside+inside") -> np.ndarray:
    """Static shaft resistance per segment [N]: mean unit friction x perimeter x embedded length.

    Parameters
    ----------
    table : SoilResistanceTable
        The SRD table.
    top_depth : array_like
        Upper segment ends below the pile head [m].
    bottom_depth : array_like
        Lower segment ends below the pile head [m].
    mudline_depth : float
        Depth of the mudline below the pile head [m].
    outer_diameter : array_like
        Outer diameter per segment [m].
    wall_thickness : array_like
        Wall thickness per segment [m].
    perimeter : {"outside+inside", "outside"}
        Friction perimeter (:func:`shaft_perimeter`).

    Returns
    -------
    numpy.ndarray
        Shaft resistance per segment [N].
    """
    length = embedded_lengths(top_depth, bottom_depth, mudline_depth)
    unit = mean_unit_friction(table, top_depth, bottom_depth, mudline_depth)
    return unit * shaft_perimeter(outer_diameter, wall_thickness, perimeter) * length


def toe_capacity(table: SoilResistanceTable, penetration: float, outer_diameter: float,
                 wall_thickness: float, area: str = "annulus") -> float:
    """Static toe resistance [N]: unit toe resistance at the toe (``penetration`` [m]) x area.

    Parameters
    ----------
    table : SoilResistanceTable
        The SRD table.
    penetration : float
        Toe depth below the mudline [m].
    outer_diameter : float
        Outer diameter [m].
    wall_thickness : float
        Wall thickness [m].
    area : {"annulus", "plugged"}
        Toe bearing area (:func:`toe_area`).

    Returns
    -------
    float
        Toe resistance [N].
    """
    return table.toe_resistance(penetration) * toe_area(outer_diameter, wall_thickness, area)
