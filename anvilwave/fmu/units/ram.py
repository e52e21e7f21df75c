"""The ram FMU slave: FMI variables mapped onto a :class:`anvilwave.hammer.ram.RamRod` and its
kernel.

Interface (DESIGN.md, the contract): input ``F_toe`` [N] (ram-anvil contact force, compression
positive, pushes the toe up); outputs ``u_toe`` [m], ``v_toe`` [m/s] (toe mass, z down). The
outputs are states: no feedthrough of ``F_toe``.

The ram is either the lumped chain of :mod:`anvilwave.hammer.ram` stepped by
:func:`anvilwave.hammer.ram.ram_advance` (the kernel of the in-process engine) with ``F_toe`` held
over
each communication step, sub-stepped within the chain's stable limit (``n_sub =
pile.model.substeps(h, stable_time_step)``, exactly as the engine does), or a modal ram (a
hammer file whose ``[ram]`` has ``kind = "modal"``: the toe modes of
:mod:`anvilwave.hammer.modal_ram`), stepped by the engine's modal ram unit
(:class:`anvilwave.hammer.modal_ram.ModalRamUnit`: every mode exact over the step for the held
force, no
sub-steps). Any communication step ``h`` is accepted.

Start: every mass moves at ``v_impact`` and the ram is undeformed, in free flight towards the
anvil; its toe reaches ``contact_displacement`` (the anvil top face at rest: the ``u_top``
output of the anvil after its initialization) at the first contact. With ``contact_mid_step``
(the default) the first contact falls in the middle of the third communication step
(:data:`anvilwave.fmu.coupling.FIRST_CONTACT_STEPS` steps after the start), whatever the
master's start time t_s and step h: at its first ``fmi2DoStep`` the unit places its free flight
so that the toe is at contact_displacement - 2.5 v_impact h at t_s. Before that step (the
outputs at t_s) it does not know h and reports the toe
:data:`~anvilwave.fmu.coupling.OUT_OF_REACH_TIME` of free flight before the contact, out of
reach of any contact for any step. The two contact-free steps make the start the same for every
master: the anvil's outputs at the first two communication points come from inputs that are
either the ram's initial outputs (out of reach) or a master's initial values (the zeros of
fmpy's SSP runner), never from the ram's state near the contact, and a Jacobi-type master's
anvil sees the ram's real state from the second point on
(:mod:`anvilwave.fmu.coupling`). The contact then starts half a step after a communication point,
as the in-process engine starts (half a step before the first contact), so the results do not
depend on where a master starts or on where the contact would fall on its time grid: a contact
force sampled at the steps' ends and held over them is off by up to a step's worth of impulse
at the first contact when that falls anywhere but mid-step (+36 % on the lumped anvil's ram
peak of Table 1 at 20 us for a contact on a communication point, measured). With
``contact_mid_step`` off the toe reaches ``contact_displacement`` at ``contact_time`` instead:
u = contact_displacement + v_impact (t - contact_time) from the start time on.

The ram data come from a hammer: ``hammer`` names a hammer of the database
(``anvilwave/hammer/data``,
e.g. ``"illustrative_5500kj"``) or a hammer TOML file (a relative name is looked up in the
FMU's resources, where :func:`anvilwave.fmu.fmi_build.build_ram_fmu` embeds it).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
from pythonfmu import DefaultExperiment

from anvilwave.fmu.coupling import FIRST_CONTACT_STEPS, OUT_OF_REACH_TIME
from anvilwave.fmu.units.base import UnitSlave
from anvilwave.hammer.database import available_hammers, load_hammer
from anvilwave.hammer.modal_ram import ModalRamUnit
from anvilwave.hammer.ram import ram_advance, stable_time_step
from anvilwave.inputs import InputError
from anvilwave.pile.model import substeps

DEFAULT_HAMMER = "illustrative_5500kj"


class RamState:
    """The ram's arrays and state (the kernel's arguments), built from the parameters.

    Parameters
    ----------
    mass : numpy.ndarray
        Lumped masses, shape (n,), top first, the toe last [kg].
    stiffness : numpy.ndarray
        The n - 1 springs between the masses [N/m].
    gravity : float
        Gravitational acceleration [m/s^2].
    """

    def __init__(self, mass: np.ndarray, stiffness: np.ndarray, gravity: float):
        self.mass = np.ascontiguousarray(mass, dtype=np.float64)
        self.stiffness = np.ascontiguousarray(stiffness, dtype=np.float64)
        self.gravity = float(gravity)
        self.u = np.zeros_like(self.mass)
        self.v = np.zeros_like(self.mass)
        self.stable_step = float(stable_time_step(self.mass, self.stiffness))
        self._h = math.nan
        self._n_sub = 1
        # the step's arrays, prepared once, as the engine does
        self.weight = self.mass * self.gravity
        self.inverse_mass = 1.0 / self.mass
        # compile (or load) the kernel now, on copies, not inside the first doStep
        ram_advance(self.weight, self.inverse_mass, self.stiffness, self.u.copy(),
                    self.v.copy(), 0.0, 1e-9, 1)

    def start(self, displacement: float, velocity: float) -> None:
        """Start every mass at ``displacement`` with ``velocity``, undeformed.

        Parameters
        ----------
        displacement : float
            Displacement of every mass, positive down [m].
        velocity : float
            Velocity of every mass, positive down [m/s].
        """
        self.u[:] = displacement
        self.v[:] = velocity

    def step(self, toe_force: float, h: float) -> None:
        """Advance over ``h`` with ``toe_force`` held, sub-stepped within the stable limit.

        Parameters
        ----------
        toe_force : float
            Ram-anvil contact force on the toe, compression positive [N].
        h : float
            Communication step [s].
        """
        if h != self._h:
            self._n_sub = substeps(h, self.stable_step)
            self._h = h
        ram_advance(self.weight, self.inverse_mass, self.stiffness, self.u, self.v, toe_force,
                    h, self._n_sub)


class ModalRamState:
    """A modal ram's unit behind the interface of :class:`RamState`.

    The unit is the engine's :class:`anvilwave.hammer.modal_ram.ModalRamUnit`.

    Parameters
    ----------
    toe_modes : object
        The hammer's toe modes (``hammer.ram.modes``), as ``ModalRamUnit`` takes them.
    gravity : float
        Gravitational acceleration [m/s^2].
    """

    def __init__(self, toe_modes, gravity: float):
        self.unit = ModalRamUnit(toe_modes, gravity)
        self._start: tuple[float, float] | None = None
        self.u = np.zeros(1)  # the toe state, as RamState's last entries
        self.v = np.zeros(1)
        # compile (or load) the kernel now, not inside the first doStep (start() at the first
        # step sets the whole state again)
        self.unit.start(0.0, 1.0, 1e-6)
        self.unit.step(0.0)

    def start(self, displacement: float, velocity: float) -> None:
        """Start the toe at ``displacement`` with ``velocity``; the state is set at the first step.

        Parameters
        ----------
        displacement : float
            Toe displacement, positive down [m].
        velocity : float
            Toe velocity, positive down [m/s].
        """
        # the two-step state needs the step: it is set up at the first step
        self._start = (displacement, velocity)
        self.u[0] = displacement
        self.v[0] = velocity

    def step(self, toe_force: float, h: float) -> None:
        """Advance over ``h`` with ``toe_force`` held (every mode exact over the step).

        Parameters
        ----------
        toe_force : float
            Ram-anvil contact force on the toe, compression positive [N].
        h : float
            Communication step [s].
        """
        unit = self.unit
        if self._start is not None:
            unit.start(self._start[0], self._start[1], h)
            self._start = None
        else:
            unit.set_step(h)
        self.u[0], self.v[0] = unit.step(toe_force)


class RamSlave(UnitSlave):
    """The ram (``Ram.fmu``): a lumped rod of the hammer database or an embedded hammer file.

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    kind = "Ram"
    description = ("anvilwave ram: lumped-mass rod (leapfrog, sub-stepped within its stable "
                   "limit) or modal ram unit (toe modes, exact per mode), struck face force "
                   "in, toe state out (SI units, z down)")
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.02, step_size=1e-5)
    parameter_fallbacks: ClassVar[dict] = {
        "hammer": DEFAULT_HAMMER,
        "v_impact": 0.0,
        "mass": 0.0,
        "gravity": 9.81,
        "contact_displacement": 0.0,
        "contact_time": 0.0,
        "contact_mid_step": True,
    }

    def register_variables(self) -> None:
        """Register the ram's parameters, input ``F_toe`` and outputs ``u_toe``, ``v_toe``."""
        p = self.add_parameter
        p("hammer", None, "Hammer: a name of the hammer database (anvilwave/hammer/data) "
                          "or a hammer TOML "
                          "file; a relative file name is looked up in the FMU resources [-]", str)
        p("v_impact", "m/s", "Ram velocity at the first contact, positive down; 0 takes the "
                             "hammer's impact velocity at its rated energy [m/s]")
        p("mass", "kg", "Ram mass; the segment masses are scaled to it (the density that gives "
                        "it); 0 keeps the hammer's mass [kg]")
        p("gravity", "m/s2", "Gravitational acceleration on the ram masses, 0 switches it off "
                             "[m/s^2]")
        p("contact_displacement", "m", "Toe displacement at the first contact (the anvil top "
                                       "face at rest), positive down [m]")
        p("contact_time", "s", "Time of the first contact when contact_mid_step is off; the ram "
                               "starts at the experiment's start time in free flight at "
                               "v_impact towards it [s]")
        p("contact_mid_step", None, "The first contact in the middle of the third "
                                    "communication step, whatever the start time and step "
                                    "(as the engine starts; contact_time is then unused) [-]",
          bool)
        self.add_input("F_toe", "N", "Ram-anvil contact force on the toe, compression positive "
                                     "(pushes the toe up) [N]")
        self.add_output("u_toe", "m", "Ram toe displacement, positive down [m]")
        self.add_output("v_toe", "m/s", "Ram toe velocity (leapfrog half-step value), positive "
                                        "down [m/s]")

    # ------------------------------------------------------------------ mapping
    def build_component(self) -> RamState:
        """The ram from the hammer, scaled to ``mass`` [kg], with its impact velocity.

        Returns
        -------
        RamState or ModalRamState
            The lumped ram, or the modal ram of a hammer with ``kind = "modal"``.

        Raises
        ------
        InputError
            If ``gravity``, ``mass``, ``v_impact``, ``contact_displacement`` or
            ``contact_time`` is out of range, or ``hammer`` names no hammer.
        """
        par = self.parameters
        name = self.instance_name
        gravity = par["gravity"]
        if not (math.isfinite(gravity) and 0.0 <= gravity <= 20.0):
            raise InputError(name, "gravity", f"must be in [0, 20] m/s^2, got {gravity!r}")
        hammer = self._hammer(par["hammer"], gravity)
        mass = hammer.ram.mass
        wanted = par["mass"]
        if not (math.isfinite(wanted) and wanted >= 0.0):
            raise InputError(name, "mass", f"must be positive (or 0: the hammer's), got "
                                           f"{wanted!r} kg")
        if wanted > 0.0 and wanted != hammer.ram.total_mass:
            if hammer.ram.is_modal_unit:
                raise InputError(name, "mass", f"a modal ram keeps its own mass "
                                               f"({hammer.ram.total_mass:.6g} kg): give 0, got "
                                               f"{wanted!r} kg")
            mass = mass * (wanted / hammer.ram.total_mass)
        velocity = par["v_impact"]
        if velocity == 0.0:
            velocity = hammer.impact_velocity
        if not (math.isfinite(velocity) and 0.0 < velocity <= 50.0):
            raise InputError(name, "v_impact", f"must be in (0, 50] m/s, got {velocity!r}")
        for key in ("contact_displacement", "contact_time"):
            if not math.isfinite(par[key]):
                raise InputError(name, key, f"must be finite, got {par[key]!r}")
        self.velocity = velocity
        if hammer.ram.is_modal_unit:
            return ModalRamState(hammer.ram.modes, gravity)
        return RamState(mass, hammer.ram.stiffness, gravity)

    def _hammer(self, name: str, gravity: float):
        if name in available_hammers():
            return load_hammer(name, gravity)
        path = self.resource_path(name)
        if path.suffix != ".toml" or not path.is_file():
            raise InputError(self.instance_name, "hammer",
                             f"{name!r} is neither a hammer of the database "
                             f"({', '.join(available_hammers())}) nor a hammer file (.toml) "
                             "in the FMU resources")
        return load_hammer(path, gravity)

    def start_component(self) -> None:
        """Free flight at ``v_impact`` towards the anvil, placed as the module docstring says."""
        par = self.parameters
        self.placed = not par["contact_mid_step"]
        if self.placed:
            offset = self.start_time - par["contact_time"]
        else:  # until the first step tells h (module docstring)
            offset = -OUT_OF_REACH_TIME
        self.component.start(par["contact_displacement"] + self.velocity * offset,
                             self.velocity)

    def compute_outputs(self, inputs, outputs) -> None:
        """(u_toe, v_toe) [m, m/s]: the toe state (no feedthrough).

        Parameters
        ----------
        inputs : list of float
            (F_toe,) [N] (unused: the outputs are states).
        outputs : list of float
            (u_toe, v_toe) [m, m/s], filled in place.
        """
        ram = self.component
        outputs[0] = ram.u[-1]
        outputs[1] = ram.v[-1]

    def advance(self, h: float) -> None:
        """Advance the ram over ``h`` with ``F_toe`` held (first contact mid-step if asked).

        Parameters
        ----------
        h : float
            Communication step [s].
        """
        if not self.placed:  # the first contact in the middle of the third step
            self.component.start(self.parameters["contact_displacement"]
                                 - self.velocity * (FIRST_CONTACT_STEPS * h), self.velocity)
            self.placed = True
        self.component.step(self.inputs[0], h)
