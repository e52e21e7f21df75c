"""The system configuration file: hammer, anvil, pile and soil, and the simulation settings.

A system file is TOML (every key is checked; units in brackets)::

    [simulation]
    duration = 0.025            # [s] simulated time of one blow
    time_step = 5e-6            # [s] optional; default: automatic, below every stable limit
    output_interval = 1e-5      # [s] optional; default: every step
    gravity = 9.81              # [m/s^2]
    blows = 1                   # consecutive blows (the FMI master and the direct engine)

    [hammer]
    database = "illustrative_5500kj"   # a hammer of anvilwave/hammer/data, or file =
    "my_hammer.toml"
    energy = 5.5e6              # [J] optional blow energy (default: the rated energy)
                                # or impact_velocity = 6.0 [m/s]
    ram_model = "modal"         # optional: "rod" (default, Smith's 1D chain) or "modal" (the
                                # ram's own Mode Displacement Method ROM up to the anvil's
                                # fmax, anvilwave/hammer/modal_ram.py)
    ram_mesh_size = 0.1         # [m] optional, modal ram only (default: from fmax and radius)

    [anvil]
    model = "rom"               # "rom" (Mode Displacement Method), "lumped" (rigid FE mass),
                                # "classic" (cushion-helmet system, see [anvil.classic]), or
                                # "none" (the ram bears on the pile through the contact spring)
    file = "anvils/xl8.toml"    # anvil geometry (rom, lumped)
    fmax = 5000.0               # [Hz] optional, ROM frequency content
    damping_ratio = 0.0         # [-] optional
    static_correction = true    # optional
    pile_port_rings = 3         # optional (rom only): the pile port split into this many
                                # rings across the pile wall (default 1;
                                # anvilwave/anvil_rom/rings.py)
    ram_port_annuli = 6         # optional (with pile_port_rings >= 2 and the modal ram): the
                                # ram port split into this many equal-width annuli (default 1)
    ram_contact_stiffness = 1e12    # [N/m] optional, default: the ram's toe half segment
    ram_contact_damping = "ram-impedance"   # [N s/m] optional (default 0), a number or the
                                # ram's toe bar impedance A sqrt(E rho)
    pile_contact_stiffness = 1e12   # [N/m] optional, default: the pile's top half segment

    [[anvil.bodies]]            # instead of file: the driving stack, top first (rom only)
    file = "anvils/xl8.toml"    # the anvil (its [interfaces]: the ram face, the pile ring)
    [[anvil.bodies]]
    file = "anvils/xl8_ring.toml"   # the anvil ring, its flat top face the seat
    seat_friction = 0.1         # [-] Coulomb coefficient of the seat (this body on the one above)
    seat_rings = 8              # optional: the seat in this many equal-width rings (default 8)
    # with a ring, pile_port_rings (default 3) is the ring's pile port and ram_port_annuli
    # (default 6) the anvil's ram face; one body is the same system as file = (to the bit);
    # [anvil] sleeve_clearance = 0.001 [m] (optional) guides both bodies' outer faces in a
    # rigid sleeve, sleeve_friction its Coulomb coefficient, sleeve_bands = [8, 8] the faces'
    # bands (anvil, ring)

    [pile]      # see anvilwave/pile/pile.py          [soil]      # see
    anvilwave/pile/soil/models.py
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from anvilwave.anvil_rom.fem.geometry import DEFAULT_FMAX, AnvilSpec, load_anvil
from anvilwave.config.budget import check_run_budget
from anvilwave.config.cache import cached_modal_data
from anvilwave.config.drive import load_drive_settings, load_srd_source, pile_soil_at
from anvilwave.config.install import load_install_settings
from anvilwave.hammer.database import Hammer, available_hammers, load_hammer
from anvilwave.hammer.driving_system import DrivingSystem
from anvilwave.hammer.modal_ram import modal_ram
from anvilwave.inputs import InputError, Table
from anvilwave.pile.model import PileSoil

ANVIL_MODELS = ("rom", "lumped", "classic", "none")

STACK_SEAT_RINGS = 8
"""Seat rings of a stack by default: Table 1's 0.55 m seat in 0.07 m rings, at least one
element edge each on the bodies' 0.05 m meshes (``benchmarks/study_anvil_ring.py``)."""

STACK_PILE_RINGS = 3
"""Rings of the ring's pile port by default (one element edge each on the ring's 0.05 m mesh
across the 0.14 m wall)."""

STACK_SLEEVE_BANDS = (8, 8)
"""The anvil's and the ring's outer faces in this many equal-height bands against a guiding
sleeve by default (Table 1's 0.45 m and 0.5 m faces; ``benchmarks/study_anvil_ring.py``)."""

STACK_RAM_ANNULI = 6
"""The anvil's ram face in this many annuli by default with a ring: the variant that matches
the reference FEA stack best (``benchmarks/study_anvil_ring.py``)."""


@dataclass(frozen=True)
class StackSettings:
    """The driving stack below the ram: the anvil (``AnvilSettings.spec``), then the ring.

    Parameters
    ----------
    ring : AnvilSpec
        The anvil ring (an outline off the axis, its flat top face the seat).
    seat_friction : float
        Coulomb coefficient of the anvil-ring seat [-].
    seat_rings : int
        The seat in this many equal-width rings [-].
    pile_rings : int
        The ring's pile port in this many rings across the pile wall [-].
    ram_annuli : int
        The anvil's ram face in this many equal-width annuli [-].
    sleeve_clearance : float or None, default None
        Radial clearance of a rigid, fixed guiding sleeve around the anvil and the ring [m];
        None: no sleeve.
    sleeve_friction : float, default 0.0
        Coulomb coefficient against the sleeve [-].
    sleeve_bands : tuple of int, default STACK_SLEEVE_BANDS
        The anvil's and the ring's outer faces in this many bands against it [-].
    """

    ring: AnvilSpec
    seat_friction: float
    seat_rings: int
    pile_rings: int
    ram_annuli: int
    sleeve_clearance: float | None = None
    sleeve_friction: float = 0.0
    sleeve_bands: tuple[int, int] = STACK_SLEEVE_BANDS

RAM_MODELS = ("rod", "modal")


@dataclass(frozen=True)
class AnvilSettings:
    """How the anvil unit is modelled (see the module docstring).

    Parameters
    ----------
    model : {"rom", "lumped", "classic", "none"}
        The anvil model.
    spec : AnvilSpec or None, default None
        The anvil geometry of the anvil file (rom, lumped).
    fmax : float or None, default None
        Frequency content of the ROM [Hz]; default the anvil file's.
    damping_ratio : float or None, default None
        Modal damping ratio [-]; default the anvil file's.
    static_correction : bool, default True
        Residual flexibility of the truncated modes.
    mass : float or None, default None
        Lumped anvil mass [kg]; default the FE mass.
    ram_contact_stiffness : float or None, default None
        Ram contact spring [N/m]; default the ram's toe half segment.
    pile_contact_stiffness : float or None, default None
        Pile contact spring [N/m]; default the pile's top half segment.
    ram_contact_damping : float, default 0.0
        Dashpot parallel to the ram contact [N s/m].
    pile_contact_damping : float, default 0.0
        Dashpot parallel to the pile contact [N s/m].
    classic : DrivingSystem or None, default None
        The classic driving system (model "classic").
    pile_head : {"rod", "tube"}
        "rod" (the 1D pile's flat head) or "tube" (the rings on an FE tube head).
    stack : StackSettings or None, default None
        The anvil ring below the anvil (``[[anvil.bodies]]`` with two bodies); None: the
        anvil alone.
    """

    model: str
    spec: AnvilSpec | None = None
    fmax: float | None = None
    damping_ratio: float | None = None
    static_correction: bool = True
    mass: float | None = None
    ram_contact_stiffness: float | None = None
    pile_contact_stiffness: float | None = None
    ram_contact_damping: float = 0.0
    pile_contact_damping: float = 0.0
    classic: DrivingSystem | None = None
    pile_head: str = "rod"
    stack: StackSettings | None = None


@dataclass(frozen=True)
class SystemConfig:
    """A validated system file.

    Parameters
    ----------
    source : str
        The system file, for messages.
    duration : float
        Simulated time of one blow [s].
    time_step : float or None
        Master step [s], None for automatic.
    output_interval : float or None
        Spacing of the recorded samples [s], None for every step.
    gravity : float
        Gravitational acceleration [m/s^2].
    blows : int
        Number of consecutive blows [-].
    hammer : Hammer
        The hammer (:mod:`anvilwave.hammer.database`).
    impact_velocity : float
        Ram velocity at first contact [m/s].
    anvil : AnvilSettings
        How the anvil is modelled.
    pile_soil : PileSoil
        The pile and its soil.
    drive : DriveSettings, optional
        The ``[driveability]`` settings (:class:`anvilwave.config.drive.DriveSettings`).
    srd : SrdSource, optional
        The ``[srd]`` source of a drive analysis (:class:`anvilwave.config.drive.SrdSource`).
    install : InstallSettings, optional
        The ``[installation]`` settings (:class:`anvilwave.config.install.InstallSettings`).
    """

    source: str
    duration: float
    time_step: float | None
    output_interval: float | None
    gravity: float
    blows: int
    hammer: Hammer
    impact_velocity: float
    anvil: AnvilSettings
    pile_soil: PileSoil
    drive: object = None
    srd: object = None
    install: object = None

    @property
    def blow_energy(self) -> float:
        """Blow energy of the system's impact velocity [J].

        m v^2 / (2 efficiency) (the kinetic energy where the hammer has no efficiency).
        """
        kinetic = 0.5 * float(np.sum(self.hammer.ram.mass)) * self.impact_velocity**2
        eff = self.hammer.efficiency
        return kinetic / eff if eff == eff and eff > 0 else kinetic

    def with_energy(self, energy: float) -> SystemConfig:
        """The same system at another blow energy (the hammer's efficiency applies).

        Parameters
        ----------
        energy : float
            Blow energy [J].

        Returns
        -------
        SystemConfig
            The system at that energy.

        Raises
        ------
        InputError
            If ``energy`` is not positive.
        """
        if not energy > 0.0:
            raise InputError(self.source, "hammer.energy", f"must be positive, got {energy!r}")
        return replace(self, impact_velocity=self.hammer.impact_velocity_at(energy))

    def with_anvil_model(self, model: str) -> SystemConfig:
        """The same system with another anvil model.

        Parameters
        ----------
        model : {"rom", "lumped", "classic", "none"}
            The anvil model.

        Returns
        -------
        SystemConfig
            The system with that anvil model.

        Raises
        ------
        InputError
            If the model needs an anvil file or a classic driving system the system lacks.
        """
        if model == self.anvil.model:
            return self
        if model in ("rom", "lumped") and self.anvil.spec is None:
            raise InputError(self.source, "anvil.file", f"the {model!r} anvil needs an anvil "
                                                         "geometry file")
        if model == "classic" and self.anvil.classic is None:
            raise InputError(self.source, "anvil.classic", "the 'classic' anvil needs an "
                                                           "[anvil.classic] table")
        return replace(self, anvil=replace(self.anvil, model=model,
                                           stack=self.anvil.stack if model == "rom" else None))


def load_system(path: str | Path) -> SystemConfig:
    """Read and validate a system file.

    Parameters
    ----------
    path : str or pathlib.Path
        The system file (TOML, module docstring).

    Returns
    -------
    SystemConfig
        The validated system.

    Raises
    ------
    InputError
        If a key breaks its rule (the message names the file, the key and the rule).
    """
    root = Table.from_file(path)
    source = str(path)

    sim = root.table("simulation")
    duration = sim.number("duration", gt=0.0, le=10.0, unit="s")
    time_step = sim.number("time_step", None, gt=0.0, unit="s")
    output_interval = sim.number("output_interval", None, gt=0.0, unit="s")
    gravity = sim.number("gravity", 9.81, ge=0.0, le=20.0, unit="m/s^2")
    blows = sim.integer("blows", 1, ge=1)
    sim.finish()
    if output_interval is not None and output_interval > duration:
        raise sim.error("output_interval", "must not exceed the duration")

    hammer, velocity, ram_options = _hammer(root.table("hammer"), gravity)
    anvil = _anvil(root.table("anvil"), hammer, source)
    drive = srd = None
    if root.has("driveability"):

        drive = load_drive_settings(root.table("driveability"), source)
    install = None
    if root.has("installation"):

        install = load_install_settings(root.table("installation"))
    srd_table = root.table("srd", required=False)
    pile_soil = PileSoil.from_tables(
        root.table("pile"), root.table("soil", required=False),
        srd_optional=srd_table is not None,
        default_penetration=float(drive.depths[-1]) if drive is not None else None)
    if srd_table is not None:

        if pile_soil.soil is None:
            raise root.error("soil", "an [srd] table needs a [soil] table (soil model, quakes "
                                     "and dampings)")
        srd = load_srd_source(srd_table, source, pile_soil)
        if pile_soil.soil.srd is None:  # the impact's soil: the [srd] at the penetration
            try:
                pile_soil = pile_soil_at(pile_soil, srd, pile_soil.soil.penetration, 1.0)[0]
            except ValueError as exc:
                raise InputError(source, "srd", str(exc)) from None
    root.finish()
    check_depths(source, pile_soil, srd, drive, install, hammer)
    config = SystemConfig(source, duration, time_step, output_interval, gravity, blows, hammer,
                          velocity, anvil, pile_soil, drive, srd, install)
    check_run_budget(config)  # before the modal ram's modes: a bomb stops in milliseconds
    if anvil.spec is not None and getattr(anvil.spec.interfaces, "ram_annuli", 1) > 1 and (
            ram_options["ram_model"] != "modal"):
        raise InputError(source, "anvil.ram_port_annuli", "the ram face in annuli is the modal "
                                                          "ram's: it needs [hammer] ram_model = "
                                                          "'modal'")
    if anvil.stack is not None:
        check_stack(config, ram_options["ram_model"])
    if ram_options["ram_model"] == "modal":
        config = replace(config, hammer=_modal_hammer(hammer, anvil,
                                                      ram_options["ram_mesh_size"], source))
    return config


def depth_limit(pile_soil, srd) -> tuple[float, str]:
    """The deepest tip depth a drive can analyse and what sets it.

    Parameters
    ----------
    pile_soil : PileSoil
        The pile and its soil.
    srd : SrdSource or None
        The ``[srd]`` source.

    Returns
    -------
    limit : float
        The deepest tip depth [m]: the pile's length, or the bottom of the ``[srd]`` soil
        profile if shallower.
    what : str
        What sets it, for messages.
    """
    limit, what = float(pile_soil.pile.length), "the pile's length"
    profile = getattr(srd, "profile", None)
    if profile is not None and getattr(profile, "layers", None) and profile.bottom < limit:
        limit, what = float(profile.bottom), "the bottom of the [srd] soil profile"
    return limit, what


def check_depths(source: str, pile_soil, srd, drive, install, hammer) -> None:
    """Refuse depths below the pile or the soil profile and energies above the rated one.

    The depths of ``[driveability]`` and ``[installation]`` that lie below the pile or the soil
    profile, beyond the drive, and blow energies above the hammer's rated energy.

    Parameters
    ----------
    source : str
        The system file, for messages.
    pile_soil : PileSoil
        The pile and its soil.
    srd : SrdSource or None
        The ``[srd]`` source.
    drive : DriveSettings or None
        The ``[driveability]`` settings.
    install : InstallSettings or None
        The ``[installation]`` settings.
    hammer : Hammer
        The hammer.

    Raises
    ------
    InputError
        One error naming the key, the row and the value.
    """
    limit, what = depth_limit(pile_soil, srd)
    length = float(pile_soil.pile.length)

    def below(key: str, values, bound: float, rule: str) -> None:
        for i, v in enumerate(np.atleast_1d(np.asarray(values, dtype=float))):
            if v < 0.0:
                raise InputError(source, key, f"row {i + 1}: {v:g} m is negative (depths are "
                                              "positive below the mudline or the head)")
            if v > bound + 1e-9:
                raise InputError(source, key, f"row {i + 1}: {v:g} m lies beyond {rule}")

    last = None
    if drive is not None:
        below("driveability.depths", drive.depths, limit, f"{what}, {limit:g} m")
        last = float(drive.depths[-1])
        below("driveability.time_series_depths", drive.time_series_depths, last,
              f"the last tip depth of [driveability], {last:g} m")
        rated = getattr(hammer, "rated_energy", math.nan)
        if drive.energy_schedule is not None and rated == rated:
            for i, e in enumerate(drive.energy_schedule[:, 1]):
                if e > rated * (1 + 1e-9):
                    raise InputError(source, "driveability.energy",
                                     f"row {i + 1}: {e:g} J is above the hammer's rated "
                                     f"energy, {rated:g} J ([hammer] rated_energy)")
    if install is not None:
        for key, value in (("start_depth", install.start_depth),
                           ("target_depth", install.target_depth)):
            if value is not None and value > limit + 1e-9:
                raise InputError(source, f"installation.{key}",
                                 f"{value:g} m lies beyond {what}, {limit:g} m")
        if (install.start_depth is not None and install.target_depth is not None
                and install.start_depth >= install.target_depth):
            raise InputError(source, "installation.start_depth",
                             f"{install.start_depth:g} m must be shallower than the "
                             f"target_depth, {install.target_depth:g} m")
        if install.weld_depths is not None:
            below("installation.weld_depths", install.weld_depths, length,
                  f"the pile's toe, {length:g} m below the head")
        target = install.target_depth if install.target_depth is not None else last
        if target is not None:
            below("installation.spectra_depths", install.spectra_depths, target,
                  f"the target depth, {target:g} m")


def _modal_hammer(hammer: Hammer, anvil: AnvilSettings, mesh_size: float | None,
                  source: str) -> Hammer:
    """The hammer with its ram replaced by the ram's modal ROM at the anvil's fmax."""
    if anvil.fmax is not None:
        fmax = anvil.fmax
    else:
        fmax = anvil.spec.fmax if anvil.spec is not None else DEFAULT_FMAX
    try:
        annuli = getattr(getattr(anvil.spec, "interfaces", None), "ram_annuli", 1)
        if anvil.stack is not None:
            annuli = anvil.stack.ram_annuli
        ram = modal_ram(hammer.ram, fmax, mesh_size=mesh_size, source=source,
                        modes=cached_modal_data, annuli=annuli)
    except InputError as exc:
        if exc.key == "fmax":  # the mesh does not resolve fmax
            key = "hammer.ram_mesh_size" if mesh_size is not None else "anvil.fmax"
        elif exc.key == "modes":  # more modes below fmax than one chain can carry
            key = "anvil.fmax"
        else:
            key = "hammer.ram_model"
        raise InputError(source, key, f"modal ram of {hammer.name}: {exc.rule}") from None
    return replace(hammer, ram=ram)


def _hammer(table: Table, gravity: float) -> tuple[Hammer, float, dict]:
    if table.has("database") == table.has("file"):
        raise table.error("database", "give exactly one of database = \"name\" (one of "
                                      f"{', '.join(available_hammers())}) or file = \"path\"")
    if table.has("database"):
        name = table.string("database", choices=available_hammers())
        hammer = load_hammer(name, gravity)
    else:
        path = table.path("file")
        if not path.exists():
            raise table.error("file", f"hammer file {path} not found")
        hammer = load_hammer(path, gravity)
    if table.has("energy") and table.has("impact_velocity"):
        raise table.error("impact_velocity", "give either energy or impact_velocity, not both")
    if table.has("energy"):
        energy = table.number("energy", gt=0.0, unit="J")
        if hammer.rated_energy == hammer.rated_energy and energy > hammer.rated_energy * 1.0001:
            raise table.error("energy", f"exceeds the rated energy of {hammer.name} "
                                        f"({hammer.rated_energy / 1e3:g} kJ)")
        velocity = hammer.impact_velocity_at(energy)
    else:
        velocity = table.number("impact_velocity", hammer.impact_velocity, gt=0.0, le=50.0,
                                unit="m/s")
    options = {"ram_model": table.string("ram_model", "rod", choices=RAM_MODELS),
               "ram_mesh_size": table.number("ram_mesh_size", None, gt=0.0, le=1.0, unit="m")}
    if options["ram_mesh_size"] is not None and options["ram_model"] != "modal":
        raise table.error("ram_mesh_size", "applies to ram_model = \"modal\" only")
    table.finish()
    return hammer, velocity, options


CONTACT_DAMPING_RULES = ("ram-impedance",)
"""Named values of ``ram_contact_damping``: "ram-impedance" is the bar impedance E A / c of the
ram's striking section (:attr:`anvilwave.hammer.ram.RamRod.toe_impedance`)."""


def _ram_contact_damping(table: Table, hammer: Hammer, source: str) -> float:
    """``ram_contact_damping`` [N s/m]: a number, or "ram-impedance" (the ram's toe bar
    impedance A sqrt(E rho): a dashpot that lets what the modes above fmax would carry away
    from the contact, as waves into the ram, leave the contact instead of ringing in it)."""
    if isinstance(table.data.get("ram_contact_damping"), str):
        table.string("ram_contact_damping", choices=CONTACT_DAMPING_RULES)
        value = hammer.ram.toe_impedance
        if not np.isfinite(value):
            raise InputError(source, "anvil.ram_contact_damping",
                             "\"ram-impedance\" needs a ram given by its shape (diameter and "
                             "mass or length, or a profile)")
        return float(value)
    return table.number("ram_contact_damping", 0.0, ge=0.0, unit="N s/m")


def _anvil(table: Table, hammer: Hammer, source: str) -> AnvilSettings:
    model = table.string("model", choices=ANVIL_MODELS)
    spec = None
    bodies = table.tables("bodies", required=False)
    if table.has("file") and table.has("bodies"):
        raise table.error("bodies", "give either file = (one anvil) or [[anvil.bodies]] (the "
                                    "stack), not both")
    if table.has("bodies") and not 1 <= len(bodies) <= 2:
        raise table.error("bodies", f"{len(bodies)} bodies: give the anvil, then optionally "
                                    "the anvil ring (one or two [[anvil.bodies]])")
    if table.has("file"):
        spec = _anvil_file(table)
    elif bodies:
        spec = _anvil_file(bodies[0])
        bodies[0].finish()
    elif model in ("rom", "lumped"):
        raise table.error("file", f"is required for the {model!r} anvil")
    ring_table = bodies[1] if len(bodies) == 2 else None
    classic_table = table.table("classic", required=False)
    classic = DrivingSystem.from_table(classic_table) if classic_table is not None else None
    if model == "classic" and classic is None:
        raise table.error("classic", "is required for the 'classic' anvil")
    settings = AnvilSettings(
        model=model,
        spec=spec,
        fmax=table.number("fmax", None, gt=0.0, unit="Hz"),
        damping_ratio=table.number("damping_ratio", None, ge=0.0, lt=1.0),
        static_correction=table.boolean("static_correction", True),
        mass=table.number("mass", None, gt=0.0, unit="kg"),
        ram_contact_stiffness=table.number("ram_contact_stiffness", None, gt=0.0, unit="N/m"),
        pile_contact_stiffness=table.number("pile_contact_stiffness", None, gt=0.0, unit="N/m"),
        ram_contact_damping=_ram_contact_damping(table, hammer, source),
        pile_contact_damping=table.number("pile_contact_damping", 0.0, ge=0.0, unit="N s/m"),
        classic=classic,
    )
    if ring_table is not None:
        stack = _stack(table, ring_table, model, settings, spec)
        head = table.string("pile_head", "rod", choices=("rod", "tube"))
        if head == "tube" and stack.pile_rings < 2:
            raise table.error("pile_head", "'tube' puts the ring's pile rings on an FE tube "
                                           "head: it needs pile_port_rings >= 2")
        settings = replace(settings, stack=stack, pile_head=head)
        table.finish()
        return settings
    rings = table.integer("pile_port_rings", 1, ge=1)
    if rings > 1:
        if model != "rom":
            raise table.error("pile_port_rings", "splits the ROM's pile port: it needs model = "
                                                 "'rom'")
        settings = replace(settings, spec=replace(
            spec, interfaces=replace(spec.interfaces, pile_rings=rings)))
    annuli = table.integer("ram_port_annuli", 1, ge=1)
    if annuli > 1:
        if rings < 2:
            raise table.error("ram_port_annuli", "splits the ram port with the pile port in "
                                                 "rings: it needs pile_port_rings >= 2")
        if settings.ram_contact_stiffness is not None:
            raise table.error("ram_port_annuli", "the annuli's contacts are the modal ram's "
                                                 "residual flexibility: omit "
                                                 "ram_contact_stiffness")
        settings = replace(settings, spec=replace(settings.spec, interfaces=replace(
            settings.spec.interfaces, ram_annuli=annuli)))
    head = table.string("pile_head", "rod", choices=("rod", "tube"))
    if head == "tube" and rings < 2:
        raise table.error("pile_head", "'tube' puts the rings on an FE tube head: it needs "
                                       "pile_port_rings >= 2")
    settings = replace(settings, pile_head=head)
    table.finish()
    return settings


def _anvil_file(table: Table) -> AnvilSpec:
    """The anvil file of ``table``'s ``file`` key (it must have its [interfaces])."""
    path = table.path("file")
    if not path.exists():
        raise table.error("file", f"anvil file {path} not found")
    spec = load_anvil(path)
    if spec.interfaces is None:
        raise table.error("file", f"{path} has no [interfaces]: the ROM needs them")
    return spec


def _stack(table: Table, body: Table, model: str, settings: AnvilSettings,
           anvil: AnvilSpec) -> StackSettings:
    """The second ``[[anvil.bodies]]`` (the ring) and the stack's port counts of ``table``."""
    if model != "rom":
        raise table.error("bodies", f"the stack of two bodies is the ROM's: it needs model = "
                                    f"'rom', not {model!r}")
    path = body.path("file")
    if not path.exists():
        raise body.error("file", f"anvil ring file {path} not found")
    ring = load_anvil(path)
    friction = body.number("seat_friction", 0.0, ge=0.0, le=2.0)
    seat_rings = body.integer("seat_rings", STACK_SEAT_RINGS, ge=1)
    body.finish()
    if ring.outline is None or anvil.outline is None:
        which, name = (body, "file") if ring.outline is None else (table, "bodies")
        raise which.error(name, "a stack body must be an outline ([geometry] points)")
    ring_pts = np.asarray(ring.outline, float)
    anvil_pts = np.asarray(anvil.outline, float)
    top = ring_pts[np.isclose(ring_pts[:, 1], ring_pts[:, 1].min())][:, 0]
    bottom = anvil_pts[np.isclose(anvil_pts[:, 1], anvil_pts[:, 1].max())][:, 0]
    if not min(top.max(), bottom.max()) > max(top.min(), bottom.min()):
        raise body.error("file", f"{path}: the ring's flat top face must overlap the anvil's "
                                 "flat bottom face (the seat)")
    wall_in, wall_out = anvil.interfaces.pile_ring
    if wall_in < ring_pts[:, 0].min() - 1e-9 or wall_out > ring_pts[:, 0].max() + 1e-9:
        raise body.error("file", f"{path}: the pile ring of the anvil's [interfaces] "
                                 f"({wall_in:g} to {wall_out:g} m) must lie under the ring's "
                                 "bottom face")
    rings = table.integer("pile_port_rings", STACK_PILE_RINGS, ge=1)
    annuli = table.integer("ram_port_annuli", STACK_RAM_ANNULI, ge=1)
    if annuli > 1 and settings.ram_contact_stiffness is not None:
        raise table.error("ram_port_annuli", "the annuli's contacts are the modal ram's "
                                             "residual flexibility: omit ram_contact_stiffness")
    clearance = table.number("sleeve_clearance", None, ge=0.0, le=0.1, unit="m")
    sleeve_friction = table.number("sleeve_friction", 0.0, ge=0.0, le=2.0)
    if clearance is None and sleeve_friction > 0.0:
        raise table.error("sleeve_friction", "needs a sleeve: set sleeve_clearance")
    bands = STACK_SLEEVE_BANDS
    if table.has("sleeve_bands"):
        if clearance is None:
            raise table.error("sleeve_bands", "needs a sleeve: set sleeve_clearance")
        values = table.array("sleeve_bands")
        if (values.shape != (2,) or not np.all(values == np.round(values))
                or values.min() < 1 or values.max() > 64):
            raise table.error("sleeve_bands", "must be two whole numbers from 1 to 64 (the "
                                              f"anvil's and the ring's), got {values.tolist()}")
        bands = (int(values[0]), int(values[1]))
    for spec, which in ((anvil, table), (ring, body)):
        if clearance is not None:
            pts = np.asarray(spec.outline, float)
            z = pts[np.isclose(pts[:, 0], pts[:, 0].max()), 1]
            if not z.max() > z.min():
                raise which.error("sleeve_clearance" if which is table else "file",
                                  f"{spec.source}: the sleeve guides the bodies' outer faces, "
                                  "but this body has no vertical face at its outer radius")
    return StackSettings(ring, float(friction), int(seat_rings), int(rings), int(annuli),
                         None if clearance is None else float(clearance),
                         float(sleeve_friction), bands)


def check_stack(config: SystemConfig, ram_model: str) -> None:
    """Refuse a stack the analyses cannot run (the rod ram, a ram toe off the ram face).

    The stack runs the modal ram, and its ram face in annuli is the ram toe's face (to 1 mm).

    Parameters
    ----------
    config : SystemConfig
        The system with ``anvil.stack``.
    ram_model : str
        The ``[hammer] ram_model``.

    Raises
    ------
    InputError
        Naming ``hammer.ram_model`` or ``anvil.ram_port_annuli``.
    """
    if ram_model != "modal":
        raise InputError(config.source, "hammer.ram_model", "the stack ([[anvil.bodies]] with "
                                                            "a ring) runs the modal ram: it "
                                                            "needs ram_model = 'modal'")
    if config.anvil.stack.ram_annuli > 1:
        toe = 0.5 * config.hammer.ram.toe_diameter
        radius = config.anvil.spec.interfaces.ram_contact_radius
        if not abs(toe - radius) <= 1e-3:
            raise InputError(config.source, "anvil.ram_port_annuli",
                             f"the annuli are the ram toe's (radius {toe:g} m) and the anvil's "
                             f"ram face's ({radius:g} m): they must be the same face (to 1 mm);"
                             " set ram_port_annuli = 1")
