"""The anvil FMU slaves: FMI variables mapped onto :class:`anvilwave.anvil_rom.unit.AnvilUnit`.

Interface (DESIGN.md, the contract): inputs ``u_ram`` [m], ``v_ram`` [m/s] (ram toe),
``u_pile`` [m], ``v_pile`` [m/s] (pile head); outputs ``F_ram``, ``F_pile`` [N] (contact forces,
compression positive) and ``u_top``, ``u_bottom`` [m] (anvil interface displacements); z down.

``AnvilStack.fmu`` (:class:`AnvilStackSlave`) is the driving stack, the anvil and the anvil
ring (:class:`anvilwave.anvil_rom.stack.StackUnit`), behind the same interface: ``F_ram`` on the
anvil's ram face, ``F_pile`` the sum of the ring's pile rings, ``u_top`` and ``u_bottom`` the
faces of :func:`anvilwave.anvil_rom.stack.stack_interface`.

An anvil whose modal data split the pile port into rings (``pile_port_rings``,
:mod:`anvilwave.anvil_rom.rings`) keeps this interface: ``F_pile`` is the sum of the ring forces and
``u_bottom`` the rings' area-weighted mean displacement.

The forces are a direct feedthrough of the inputs: they are evaluated from the inputs set at the
current communication point (``AnvilUnit.forces``), so a master that sets the ram and pile
states and then reads the forces gets the forces at that instant. ``fmi2DoStep`` holds these
forces over the step (``AnvilUnit.step``). The anvil accepts any communication step ``h`` in one
step, without sub-stepping: the modal integration is unconditionally stable and exact for free
vibration and for a held force at any ``h`` (see :mod:`anvilwave.anvil_rom.rom`; a change of ``h``
is
handled by ``AnvilUnit.set_step``). Sub-steps inside the anvil could not help the explicit
exchange anyway, since the forces are held over the whole communication step: its stability
limit (``AnvilUnit.stable_time_step``) is for the master to respect.

At the end of initialization the anvil rests on the pile in static equilibrium under gravity
(``start_at_rest``, default on; ``AnvilUnit.rest_on_pile``) with the pile head at
``initial_pile_head_displacement`` [m]; the ram touches the top face when its toe displacement
equals the ``u_top`` output.

Input extrapolation (parameter ``input_extrapolation``, default off; ``system.ssp`` turns it
on): for Jacobi-type masters, which read the anvil's forces after its step with the inputs of
the step before, the inputs are extrapolated to the unit's time and the contact impulse the
neighbours missed is given back (:mod:`anvilwave.fmu.coupling`); with ``ram_toe_mass`` (the
ram toe's mass for a force step [kg], default 0: none) the ram toe's state is extrapolated
with its response to the changes of the force it holds. In the DESIGN.md order it changes no
bit.
"""

from __future__ import annotations

from typing import ClassVar

from numba import njit
from pythonfmu import DefaultExperiment

from anvilwave.anvil_rom.fem.modalfile import load_modal_data
from anvilwave.anvil_rom.rings import ring_unit_outputs
from anvilwave.anvil_rom.rom import ModalAnvil
from anvilwave.anvil_rom.stack import StackUnit, load_stack_data, stack_interface
from anvilwave.anvil_rom.unit import (
    GRAVITY,
    AnvilUnit,
    ContactParameters,
    modal_unit_forces,
    modal_unit_outputs,
    modal_unit_step,
)
from anvilwave.fmu.coupling import (
    INPUT_EXTRAPOLATION_DESCRIPTION,
    RAM_TOE_MASS_DESCRIPTION,
    InputExtrapolation,
    approach_input,
    check_ram_toe_mass,
)
from anvilwave.fmu.units.base import UnitSlave
from anvilwave.inputs import InputError

INPUTS = ("u_ram", "v_ram", "u_pile", "v_pile")


@njit(cache=True)
def anvil_outputs(P, C, S, u_ram, v_ram, u_pile, v_pile):
    """The anvil's four outputs in one call.

    The contact forces of :meth:`AnvilUnit.forces` and the interface displacements of
    :meth:`AnvilUnit.outputs`.

    Parameters
    ----------
    P : numpy.ndarray
        Scalar data of the unit, ``AnvilUnit.P``: contact stiffnesses and dashpots, residual
        flexibility, gravity, step [SI].
    C : numpy.ndarray
        Per-mode data of the unit, ``AnvilUnit.C``, shape (n, 8) [SI].
    S : numpy.ndarray
        Modal state of the unit, ``AnvilUnit.S``, shape (2 n,) [m].
    u_ram : float
        Ram toe displacement, positive down [m].
    v_ram : float
        Ram toe velocity, positive down [m/s].
    u_pile : float
        Pile head displacement, positive down [m].
    v_pile : float
        Pile head velocity, positive down [m/s].

    Returns
    -------
    F_ram : float
        Ram-anvil contact force, compression positive [N].
    F_pile : float
        Anvil-pile contact force, compression positive [N].
    u_top : float
        Anvil top face displacement, positive down [m].
    u_bottom : float
        Anvil bottom ring displacement, positive down [m].
    """
    force_ram, force_pile = modal_unit_forces(P, C, S, u_ram, v_ram, u_pile, v_pile)
    u_top, _, u_bottom, _ = modal_unit_outputs(P, C, S, force_ram, force_pile)
    return force_ram, force_pile, u_top, u_bottom


class AnvilSlaveBase(UnitSlave):
    """Variables and mapping shared by the ROM anvil and the lumped (rigid) anvil.

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.02, step_size=1e-5)
    extrapolation: InputExtrapolation | None = None  # with input_extrapolation, once built
    touched = False  # the ram contact has carried a force (approach_input)
    last_step = 0.0  # the last communication step [s] (0: none yet)

    parameter_fallbacks: ClassVar[dict] = {
        "ram_contact_stiffness": None,
        "pile_contact_stiffness": None,
        "ram_contact_damping": 0.0,
        "pile_contact_damping": 0.0,
        "gravity": GRAVITY,
        "start_at_rest": True,
        "initial_pile_head_displacement": 0.0,
        "input_extrapolation": False,
        "ram_toe_mass": 0.0,
    }
    # inputs each output depends on directly (subclasses narrow it when they can)
    feedthrough: ClassVar[dict[str, tuple[str, ...]]] = {
        "F_ram": INPUTS, "F_pile": INPUTS, "u_top": INPUTS, "u_bottom": INPUTS,
    }

    def register_variables(self) -> None:
        """Register the anvil's parameters, inputs and outputs (module docstring)."""
        self.register_anvil_parameters()
        p = self.add_parameter
        p("ram_contact_stiffness", "N/m", "Ram-anvil compression-only contact spring [N/m]")
        p("pile_contact_stiffness", "N/m", "Anvil-pile compression-only contact spring [N/m]")
        p("ram_contact_damping", "N.s/m", "Ram-anvil contact dashpot [N s/m]")
        p("pile_contact_damping", "N.s/m", "Anvil-pile contact dashpot [N s/m]")
        p("gravity", "m/s2", "Gravitational acceleration, 0 switches it off [m/s^2]")
        p("start_at_rest", None, "Start in static equilibrium on the pile under gravity (else "
                                 "undeformed at zero displacement) [-]", bool)
        p("initial_pile_head_displacement", "m",
          "Pile head displacement the anvil rests on at the start, positive down [m]")
        p("input_extrapolation", None, INPUT_EXTRAPOLATION_DESCRIPTION, bool)
        i = self.add_input
        i("u_ram", "m", "Ram toe displacement, positive down [m]")
        i("v_ram", "m/s", "Ram toe velocity, positive down [m/s]")
        i("u_pile", "m", "Pile head displacement, positive down [m]")
        i("v_pile", "m/s", "Pile head velocity, positive down [m/s]")
        o = self.add_output
        o("F_ram", "N", "Ram-anvil contact force, compression positive [N]",
          self.feedthrough["F_ram"])
        o("F_pile", "N", "Anvil-pile contact force, compression positive [N]",
          self.feedthrough["F_pile"])
        o("u_top", "m", "Anvil top face displacement (ram contact), positive down [m]",
          self.feedthrough["u_top"])
        o("u_bottom", "m", "Anvil bottom ring displacement (pile contact), positive down [m]",
          self.feedthrough["u_bottom"])
        p("ram_toe_mass", "kg", RAM_TOE_MASS_DESCRIPTION)

    def register_anvil_parameters(self) -> None:
        """Register the parameters of the anvil model itself.

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it.
        """
        raise NotImplementedError

    def make_anvil(self) -> ModalAnvil:
        """The anvil model from the parameters.

        Returns
        -------
        ModalAnvil
            The modal (or rigid) anvil.

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it.
        """
        raise NotImplementedError

    # ------------------------------------------------------------------ mapping
    def build_component(self) -> AnvilUnit:
        """The anvil unit: the anvil model with its contacts and gravity.

        Returns
        -------
        AnvilUnit
            The anvil with its ram and pile contacts.

        Raises
        ------
        InputError
            If ``gravity`` is not finite or ``ram_toe_mass`` is negative or not finite.
        """
        contact, gravity = self.contacts()
        return AnvilUnit(self.make_anvil(), contact, gravity)

    def contacts(self) -> tuple[ContactParameters, float]:
        """The ram and pile contacts and gravity of the parameters, checked.

        Returns
        -------
        contact : ContactParameters
            Springs [N/m] and dashpots [N s/m].
        gravity : float
            Gravitational acceleration [m/s^2].

        Raises
        ------
        InputError
            If ``gravity`` is not finite or ``ram_toe_mass`` is negative or not finite.
        """
        par = self.parameters
        contact = ContactParameters(
            ram_stiffness=par["ram_contact_stiffness"],
            pile_stiffness=par["pile_contact_stiffness"],
            ram_damping=par["ram_contact_damping"],
            pile_damping=par["pile_contact_damping"])
        gravity = par["gravity"]
        if not abs(gravity) < float("inf"):
            raise InputError(self.instance_name, "gravity", f"must be finite, got {gravity!r}")
        check_ram_toe_mass(par["ram_toe_mass"], self.instance_name)
        return contact, gravity

    def top_face(self) -> tuple[float, float]:
        """The anvil's top face (the ram contact) now, without contact forces.

        Returns
        -------
        u_top : float
            Displacement [m].
        v_top : float
            Velocity [m/s].
        """
        u_top, v_top, _, _ = self.component.outputs(0.0, 0.0)
        return u_top, v_top

    def start_component(self) -> None:
        """Initial state: at rest on the pile, the step kernel compiled, extrapolation set up.

        With ``start_at_rest`` the anvil is put in static equilibrium on the pile head at
        ``initial_pile_head_displacement`` [m]; with ``input_extrapolation`` an
        :class:`~anvilwave.fmu.coupling.InputExtrapolation` starts at the start time.
        """
        if self.parameters["start_at_rest"]:
            self.component.rest_on_pile(self.parameters["initial_pile_head_displacement"])
        self.warm_up()
        self.extrapolation = (InputExtrapolation(self.start_time,
                                                 self.parameters["ram_toe_mass"])
                              if self.parameters["input_extrapolation"] else None)
        self.touched = False
        self.last_step = 0.0

    def warm_up(self) -> None:
        """Compile (or load) the step kernel now, on copies, not inside the first doStep."""
        unit = self.component
        modal_unit_step(unit.P, unit.C, unit.S.copy(), 0.0, 0.0)

    def approached(self, u_ram, v_ram, u_pile, v_pile) -> tuple[float, float, float, float]:
        """The inputs as the contacts see them before the first contact (``approach_input``).

        Parameters
        ----------
        u_ram : float
            Ram toe displacement [m].
        v_ram : float
            Ram toe velocity [m/s].
        u_pile : float
            Pile head displacement [m].
        v_pile : float
            Pile head velocity [m/s].

        Returns
        -------
        tuple of float
            (u_ram, v_ram, u_pile, v_pile) [m, m/s, m, m/s].
        """
        if self.touched or self.last_step == 0.0:
            return u_ram, v_ram, u_pile, v_pile
        u_top, v_top = self.top_face()
        u_ram, v_ram = approach_input(u_ram, v_ram, u_top, v_top, self.last_step, self.touched)
        return u_ram, v_ram, u_pile, v_pile

    def compute_outputs(self, inputs, outputs) -> None:
        """(F_ram, F_pile, u_top, u_bottom) [N, N, m, m] from the current inputs.

        With input extrapolation the inputs are extrapolated to the unit's time and the impulse
        correction is added to the forces.

        Parameters
        ----------
        inputs : list of float
            (u_ram, v_ram, u_pile, v_pile) [m, m/s, m, m/s].
        outputs : list of float
            (F_ram, F_pile, u_top, u_bottom) [N, N, m, m], filled in place.
        """
        x = self.extrapolation
        state = self.approached(*(inputs if x is None else x.extrapolated(inputs)))
        outputs[:] = self.unit_outputs(*state)
        if x is None:
            return
        x.evaluate(outputs[0], outputs[1])
        outputs[0] += x.correction[0]
        outputs[1] += x.correction[1]

    def unit_outputs(self, u_ram, v_ram, u_pile, v_pile) -> tuple[float, float, float, float]:
        """The unit's (F_ram, F_pile, u_top, u_bottom) [N, N, m, m] for these inputs.

        Parameters
        ----------
        u_ram : float
            Ram toe displacement [m].
        v_ram : float
            Ram toe velocity [m/s].
        u_pile : float
            Pile head displacement [m].
        v_pile : float
            Pile head velocity [m/s].

        Returns
        -------
        tuple of float
            The four outputs [N, N, m, m].
        """
        unit = self.component
        if unit.rings is not None:  # the pile port in rings: F_pile their sum
            return ring_unit_outputs(unit.P, unit.C, unit.S, unit.rings, u_ram, v_ram, u_pile,
                                     v_pile)
        return anvil_outputs(unit.P, unit.C, unit.S, u_ram, v_ram, u_pile, v_pile)

    def advance(self, h: float) -> None:
        """Advance the anvil over one step with the contact forces held (``AnvilUnit.step``).

        Parameters
        ----------
        h : float
            Communication step [s].
        """
        x = self.extrapolation
        unit = self.component
        if x is None:
            force_ram, force_pile = self.outputs[0], self.outputs[1]
        else:
            force_ram, force_pile = x.step_forces(
                *unit.forces(*self.approached(*x.extrapolated(self.inputs))))
            x.stepped(force_ram, force_pile)
        unit.step(force_ram, force_pile, h)
        if force_ram > 0.0:
            self.touched = True
        self.last_step = h

    # input extrapolation: the unit's time, the inputs' time, the forces read
    def set_real(self, vrs, values):
        """Set Real variables (fmi2SetReal), noting the inputs' time for the extrapolation.

        Parameters
        ----------
        vrs : list of int
            Value references.
        values : list of float
            The values [SI].

        Returns
        -------
        None
            What :meth:`UnitSlave.set_real` returns (nothing).
        """
        if self.extrapolation is not None:
            self.extrapolation.note_inputs(self.inputs)
        return super().set_real(vrs, values)

    def get_real(self, vrs):
        """Values of Real variables (fmi2GetReal), noting the forces read for the extrapolation.

        Parameters
        ----------
        vrs : list of int
            Value references.

        Returns
        -------
        list of float
            The values [SI].
        """
        values = super().get_real(vrs)
        if self.extrapolation is not None:
            self.extrapolation.read()
        return values

    def do_step(self, current_time: float, step_size: float) -> bool:
        """Advance over one communication step (fmi2DoStep), then move the extrapolation's time.

        Parameters
        ----------
        current_time : float
            Communication point at the step start [s].
        step_size : float
            Communication step h [s].

        Returns
        -------
        bool
            ``True`` on success; ``False`` (fmi2Discard) after an error, which is logged.
        """
        done = super().do_step(current_time, step_size)
        if done and self.extrapolation is not None:
            self.extrapolation.time = current_time + step_size
        return done


class AnvilROMSlave(AnvilSlaveBase):
    """The Mode Displacement Method anvil from an embedded modal-data file (``Anvil.fmu``).

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    kind = "Anvil"
    description = ("anvilwave anvil: Mode Displacement Method ROM with compression-only ram and "
                   "pile contacts (SI units, z down, compression positive)")
    parameter_fallbacks: ClassVar[dict] = {
        **AnvilSlaveBase.parameter_fallbacks,
        "modal_data_file": None,
        "fmax": 0.0,
        "damping_ratio": None,
        "static_correction": False,
    }

    def register_anvil_parameters(self) -> None:
        """Register ``modal_data_file``, ``fmax``, ``damping_ratio`` and ``static_correction``."""
        p = self.add_parameter
        p("modal_data_file", None, "Modal-data file (.npz); a relative name is looked up in the "
                                   "FMU resources, where the build embeds it [-]", str)
        p("fmax", "Hz", "Frequency content of the ROM: modes up to fmax are kept, 0 keeps all "
                        "modes of the file [Hz]")
        p("damping_ratio", "1", "Modal damping ratio of the flexible modes [-]")
        p("static_correction", None, "Add the residual flexibility of the truncated modes "
                                     "(static correction) [-]", bool)

    def make_anvil(self) -> ModalAnvil:
        """The ROM from the modal-data file, modes up to ``fmax`` [Hz] (0: all).

        Returns
        -------
        ModalAnvil
            The Mode Displacement Method anvil.
        """
        par = self.parameters
        path = self.resource_path(par["modal_data_file"])
        data = load_modal_data(path)
        fmax = par["fmax"] if par["fmax"] != 0.0 else None
        return ModalAnvil.from_modal_data(data, fmax=fmax, damping_ratio=par["damping_ratio"],
                                          static_correction=par["static_correction"],
                                          source=str(path))


class AnvilLumpedSlave(AnvilSlaveBase):
    """The rigid lumped-mass anvil of the classic programs (``AnvilLumped.fmu``).

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    kind = "AnvilLumped"
    description = ("anvilwave anvil: rigid lumped mass with compression-only ram and pile "
                   "contacts (SI units, z down, compression positive)")
    parameter_fallbacks: ClassVar[dict] = {**AnvilSlaveBase.parameter_fallbacks, "mass": None}
    # a rigid body has no static correction: each force sees only its own contact
    feedthrough: ClassVar[dict[str, tuple[str, ...]]] = {
        "F_ram": ("u_ram", "v_ram"), "F_pile": ("u_pile", "v_pile"), "u_top": (), "u_bottom": (),
    }

    def register_anvil_parameters(self) -> None:
        """Register ``mass`` [kg]."""
        self.add_parameter("mass", "kg", "Anvil mass (the FE model's total mass) [kg]")

    def make_anvil(self) -> ModalAnvil:
        """The rigid anvil of mass ``mass`` [kg].

        Returns
        -------
        ModalAnvil
            The rigid anvil.
        """
        return ModalAnvil.rigid(self.parameters["mass"])


class AnvilStackSlave(AnvilSlaveBase):
    """The driving stack, anvil and anvil ring, from an embedded stack data file.

    ``AnvilStack.fmu``: :func:`anvilwave.anvil_rom.stack.load_stack_data`'s bodies with the
    seat's Coulomb coefficient ``seat_friction``; the interface of the other anvils (module
    docstring).

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    kind = "AnvilStack"
    description = ("anvilwave driving stack: the anvil and the anvil ring, two Mode "
                   "Displacement Method ROMs with compression-only contacts and Coulomb seat "
                   "friction (SI units, z down, compression positive)")
    parameter_fallbacks: ClassVar[dict] = {
        **AnvilSlaveBase.parameter_fallbacks,
        "stack_data_file": None,
        "seat_friction": 0.0,
        "sleeve_friction": 0.0,
    }

    def register_anvil_parameters(self) -> None:
        """Register ``stack_data_file``, ``seat_friction`` and ``sleeve_friction``."""
        p = self.add_parameter
        p("stack_data_file", None, "Stack data file (.npz, the bodies' modes on their ports); "
                                   "a relative name is looked up in the FMU resources [-]", str)
        p("seat_friction", "1", "Coulomb coefficient of the anvil-ring seat [-]")
        p("sleeve_friction", "1", "Coulomb coefficient against the guiding sleeve (a stack "
                                  "data file with a sleeve) [-]")

    def build_component(self) -> StackUnit:
        """The stack with its contacts, seat friction and gravity.

        Returns
        -------
        StackUnit
            The anvil and the ring between the ram and the pile.

        Raises
        ------
        InputError
            If ``gravity`` is not finite, ``ram_toe_mass``, ``seat_friction`` or
            ``sleeve_friction`` is negative or not finite, or ``sleeve_friction`` is set
            without a sleeve in the data file.
        """
        par = self.parameters
        contact, gravity = self.contacts()
        anvil, ring, seat = load_stack_data(self.resource_path(par["stack_data_file"]))
        try:
            return StackUnit(anvil, contact, ring, seat_friction=par["seat_friction"],
                             sleeve_friction=par["sleeve_friction"], gravity=gravity, **seat)
        except InputError as exc:
            raise InputError(self.instance_name, exc.key, exc.rule) from None

    def warm_up(self) -> None:
        """Nothing ahead: the stack's kernels compile (or load) at their first call."""

    def top_face(self) -> tuple[float, float]:
        """The anvil's ram face now (:func:`anvilwave.anvil_rom.stack.stack_interface`).

        Returns
        -------
        u_top : float
            Displacement [m].
        v_top : float
            Velocity [m/s].
        """
        u_top, v_top, _, _ = stack_interface(self.component.state)
        return u_top, v_top

    def unit_outputs(self, u_ram, v_ram, u_pile, v_pile) -> tuple[float, float, float, float]:
        """The stack's forces (:meth:`anvilwave.anvil_rom.stack.StackUnit.forces`) and faces.

        Parameters
        ----------
        u_ram : float
            Ram toe displacement [m].
        v_ram : float
            Ram toe velocity [m/s].
        u_pile : float
            Pile head displacement [m].
        v_pile : float
            Pile head velocity [m/s].

        Returns
        -------
        tuple of float
            (F_ram, F_pile, u_top, u_bottom) [N, N, m, m].
        """
        unit = self.component
        f_ram, f_pile = unit.forces(u_ram, v_ram, u_pile, v_pile)
        u_top, _, u_bottom, _ = stack_interface(unit.state)
        return f_ram, f_pile, u_top, u_bottom
