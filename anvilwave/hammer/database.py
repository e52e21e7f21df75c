"""Hammer data: one TOML file per hammer under anvilwave/hammer/data/, each citing its source.

A hammer file (or a ``[hammer]`` table of a configuration) holds::

    name = "IHC S-4000"            # shown in results
    manufacturer = "IHC IQIP"
    description = "..."            # optional
    rated_energy = 4.0e6           # [J] maximum blow energy
    efficiency = 0.95              # [-] hammer efficiency
    stroke = 2.04                  # [m] optional; default the equivalent stroke E / (m g)
    # impact_velocity = 6.0        # [m/s] instead of rated_energy / stroke and efficiency
    [ram]                          # see hammer.ram_table.ram_from_table
    [source]                       # document, year, optional url, estimates, checked

The impact velocity comes from, in this order: ``impact_velocity``; ``rated_energy`` with
``efficiency`` (v = sqrt(2 eta E / m)); ``stroke`` with ``efficiency`` (v = sqrt(2 eta g h)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from anvilwave.hammer.impact import (
    GRAVITY,
    equivalent_stroke,
    impact_velocity_from_energy,
    impact_velocity_from_stroke,
)
from anvilwave.hammer.ram import RamRod
from anvilwave.hammer.ram_table import ram_from_table
from anvilwave.inputs import InputError, Table

DATA_DIR = Path(__file__).with_name("data")
"""Folder of the hammer files that ship with anvilwave."""


@dataclass(frozen=True)
class HammerSource:
    """Where a hammer's figures come from.

    Parameters
    ----------
    document : str
        Title and publisher of the brochure, datasheet or report.
    year : int
        Year of the document (0 if unknown).
    url : str, default ""
        Where it was published ("" if none).
    estimates : str, default ""
        Which values are estimates and how they were derived.
    checked : str, default ""
        Which figures were checked against which other source.
    """

    document: str
    year: int
    url: str = ""
    estimates: str = ""
    checked: str = ""

    @classmethod
    def from_table(cls, table: Table) -> HammerSource:
        """Read a ``[source]`` table.

        Parameters
        ----------
        table : Table
            The table.

        Returns
        -------
        HammerSource
            The source.

        Raises
        ------
        InputError
            If ``document`` is blank or a key is missing or invalid.
        """
        document = table.string("document")
        if not document.strip():
            raise table.error("document", "must name the source document")
        year = table.integer("year", ge=0)
        url = table.string("url", "")
        estimates = table.string("estimates", "")
        checked = table.string("checked", "")
        table.finish()
        return cls(document, year, url, estimates, checked)


@dataclass(frozen=True, eq=False)
class Hammer:
    """An impact hammer: its ram and how fast the ram strikes.

    Parameters
    ----------
    name : str
        Hammer name.
    manufacturer : str
        Maker ("" for illustrative hammers).
    ram : RamRod
        The ram model.
    impact_velocity : float
        Ram velocity just before impact at the rated energy [m/s].
    rated_energy : float, default nan
        Rated (maximum) blow energy [J]; nan if the file gives a velocity only.
    efficiency : float, default nan
        Hammer efficiency [-] (nan when the impact velocity is given directly).
    stroke : float, default nan
        Ram stroke [m]: as given, else the equivalent stroke E / (m g) (nan if unknown).
    source : HammerSource or None
        The cited source (None for a configuration without one).
    description : str, default ""
        Free text.

    Attributes
    ----------
    ram_mass : float
        Ram mass [kg].
    """

    name: str
    manufacturer: str
    ram: RamRod
    impact_velocity: float
    rated_energy: float = math.nan
    efficiency: float = math.nan
    stroke: float = math.nan
    source: HammerSource | None = None
    description: str = ""

    @property
    def ram_mass(self) -> float:
        """Ram mass [kg]."""
        return self.ram.total_mass

    def impact_velocity_at(self, energy: float) -> float:
        """Impact velocity [m/s] when the hammer is run at a blow energy [J] below its rating.

        Parameters
        ----------
        energy : float
            Blow energy [J].

        Returns
        -------
        float
            Impact velocity [m/s].

        Raises
        ------
        ValueError
            If the hammer has no efficiency (impact velocity given directly).
        """
        if math.isnan(self.efficiency):
            raise ValueError(f"{self.name}: no efficiency (impact velocity was given directly)")
        return impact_velocity_from_energy(energy, self.ram_mass, self.efficiency)

    @classmethod
    def from_table(cls, table: Table, gravity: float = GRAVITY,
                   require_source: bool = False) -> Hammer:
        """Read a hammer from a TOML table; gravity [m/s^2] for stroke conversions.

        Parameters
        ----------
        table : Table
            The hammer table.
        gravity : float, default GRAVITY
            Gravitational acceleration for stroke conversions [m/s^2].
        require_source : bool, default False
            Whether a ``[source]`` table is required.

        Returns
        -------
        Hammer
            The validated hammer.

        Raises
        ------
        InputError
            If an entry is missing, invalid or contradictory.
        """
        name = table.string("name")
        manufacturer = table.string("manufacturer", "")
        description = table.string("description", "")
        ram = ram_from_table(table.table("ram"))
        mass = ram.total_mass
        rated_energy = table.number("rated_energy", None, gt=0, unit="J")
        stroke = table.number("stroke", None, gt=0, unit="m")
        if table.has("impact_velocity"):
            if table.has("efficiency"):
                raise table.error("efficiency", "has no effect when impact_velocity is given")
            velocity = table.number("impact_velocity", gt=0, unit="m/s")
            efficiency = math.nan
        else:
            if rated_energy is None and stroke is None:
                raise table.error("rated_energy", "is required (or stroke, or impact_velocity)")
            efficiency = table.number("efficiency", gt=0, le=1)
            if rated_energy is not None:
                velocity = impact_velocity_from_energy(rated_energy, mass, efficiency)
            else:
                velocity = impact_velocity_from_stroke(stroke, efficiency, gravity)
        if stroke is None and rated_energy is not None:
            stroke = (equivalent_stroke(rated_energy, mass, gravity) if gravity > 0.0
                      else math.nan)
        source_table = table.table("source", required=require_source)
        source = HammerSource.from_table(source_table) if source_table is not None else None
        table.finish()
        return cls(name, manufacturer, ram, velocity,
                   math.nan if rated_energy is None else rated_energy, efficiency,
                   math.nan if stroke is None else stroke, source, description)


def available_hammers() -> list[str]:
    """Names (file stems) of the hammers in the shipped database, sorted.

    Returns
    -------
    list of str
        The hammer names.
    """
    return sorted(path.stem for path in DATA_DIR.glob("*.toml"))


def hammer_path(name: str | Path) -> Path:
    """The file of a database hammer (by name) or the given path to a hammer file.

    Parameters
    ----------
    name : str or Path
        Database name, or a path to a hammer file.

    Returns
    -------
    Path
        The hammer file.

    Raises
    ------
    InputError
        If the name is neither a file nor a database hammer.
    """
    path = Path(name)
    if path.suffix == ".toml" or path.exists():
        return path
    candidate = DATA_DIR / f"{name}.toml"
    if not candidate.exists():
        raise InputError("hammer database", str(name),
                         f"unknown hammer (available: {', '.join(available_hammers())})")
    return candidate


def load_hammer(name: str | Path, gravity: float = GRAVITY) -> Hammer:
    """Load a hammer by database name (e.g. "ihc_s4000") or from a TOML file path.

    Files of the shipped database must cite a ``[source]``.

    Parameters
    ----------
    name : str or Path
        Database name or TOML file path.
    gravity : float, default GRAVITY
        Gravitational acceleration for stroke conversions [m/s^2].

    Returns
    -------
    Hammer
        The validated hammer.
    """
    path = hammer_path(name)
    shipped = path.resolve().parent == DATA_DIR.resolve()
    return Hammer.from_table(Table.from_file(path), gravity, require_source=shipped)
