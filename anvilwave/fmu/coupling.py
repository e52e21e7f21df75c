"""Coupling of the anvil unit under Jacobi-type masters: input extrapolation.

A Jacobi-type master (OSP libcosim, most SSP runners) steps every unit, then reads every output
and sets every input: the anvil's forces are read after its step while its inputs are still
those of the step before, so ram and pile hold forces that lag the contacts by one step (a
first-order error that the stiff contacts amplify: 77 % on the Table 1 ram peak at h/4). With
the anvil's parameter ``input_extrapolation`` on (:class:`InputExtrapolation` in the pythonfmu
anvils of :mod:`anvilwave.fmu.units.anvil`; the native anvil does the same operations in the same
order
in ``anvilwave/fmu/native/anvil_unit.c``):

1. inputs set at a new communication point t_in keep the velocities of the point before
   (t_in - d): a = (v - v_before) / d is the neighbour's acceleration (0 at the first point,
   and 0 while the point before is the start time: inputs there are a master's initial values,
   e.g. the zeros fmpy's SSP runner sets before it has read any output, not the neighbours'
   states, so a difference across them is no acceleration; a neighbour in free flight has none);
2. the outputs at the unit's time t use the inputs extrapolated over the age s = t - t_in,
   :func:`extrapolated_input`: u + s (v + a d / 2) + a s^2 / 2 and v + a s (the velocity inputs
   are the neighbours' half-step values, their mean velocity over their last step, so that
   v + a d / 2 is the velocity at t_in; for a leapfrog neighbour this predicts its next step
   exactly when its acceleration does not change). With the parameter ``ram_toe_mass`` m > 0
   the ram's extrapolation adds the toe's response to the change of the F_ram it holds: a
   holds the deceleration by the force over the step that gave v, the toe holds since t_in
   the force read there, so dv = -(F_held - F) s / m (exact for a leapfrog mass; ``build-fmus``
   sets m from the ram model, :attr:`anvilwave.hammer.ram.RamRod.toe_mass`);
3. ``fmi2DoStep`` advances the anvil with the forces at the step start (inputs extrapolated to
   it: s = 0 when they were just set) and keeps their difference to the forces of the last
   output read since the step before (what the neighbours hold over this step) as an impulse
   correction, added to the force outputs until the next step: the neighbours get back in the
   next step the impulse they missed, so that anvil, ram and pile exchange the same momentum;
4. except when that output came from the inputs of the start time (a master's initial values:
   the zeros of fmpy's SSP runner, or the ram's initial outputs, out of reach): then the step
   applies the forces the neighbours hold, with no correction. A Jacobi master's neighbours
   hold over the second step the outputs of the first point, computed from the start's inputs
   whatever the states were: the anvil acts with them too, so that the system starts, in
   every master, from the neighbours' real states at the second point (with the ram's
   ``contact_mid_step``, half a step before the first contact: the engine's start). Giving
   back an impulse missed there instead made a spike in the ram force (+66 % on the Table 1
   peak under fmpy's SSP runner, +75 % with the lumped anvil).

With inputs set at the unit's own time before the outputs are read (the DESIGN.md order of the
fmpy master) the age is 0 and the correction 0: the results are bitwise those with the option
off. Right after a separation the correction can make a force output slightly negative for one
step (an impulse of the coupling, not a tension in the contact).

Measured on Table 1 (benchmarks/doc_fmi_tools.py, docs/data/fmi_tools.json, checked by
tests/test_fmu_system.py and tests/test_fmu_ssp_tools.py): under libcosim at h/4 of the
engine's step the ROM's peak forces are within 0.03 % of the DESIGN order on the same step
(F_ram -0.029 %, F_pile -0.001 %) and within 0.15 % of the fmpy master at h (+0.142 %, -0.060
%), the whole series within 0.12 % of the peaks; the lumped anvil's ram peak is -0.065 % of the
DESIGN order on the same step (F_pile +0.004 % of the engine), libcosim and fmpy's SSP runner
alike. The ram toe's response is what the lumped anvil needs: in the step where the contact
dashpot's force jumps, the toe slows under the force it holds, which an extrapolation from the
points before cannot see; without it the ram peak was +2.18 % at h/4 (the overshoot and
undershoot that follow had not died out at the rigid anvil's peak, four steps after the
contact), and the ROM's series 3.1 %. The toe mass is the toe's first response, not the rod's
impedance E A / c: a modal ram with modes up to 5 kHz (Table 1's, m = 5.6 t) follows a force
step at 5 us with 9 % of the -dF/Z of a rod, and with Z in place of m the exchange is unstable.
With the toe mass the lumped ram peak converges with the step about 11x per halving (-0.69 % at
h/2, -0.065 % at h/4, -0.0056 % at h/8). Without the impulse correction the ram peak was 1.6 %
off at h/4 (3.3 % with a linear extrapolation), before the toe mass; sub-stepping the anvil
with the extrapolated inputs gains nothing (the forces the neighbours hold over their step set
the error).
"""

from __future__ import annotations

import math

from anvilwave.inputs import InputError

FIRST_CONTACT_STEPS = 2.5
"""The ram's ``contact_mid_step``: communication steps from the start to the first contact [-]
(:mod:`anvilwave.fmu.units.ram`, ``anvilwave/fmu/native/ram_model.c``)."""

OUT_OF_REACH_TIME = 1.0
"""The ram's ``contact_mid_step``: free flight to the contact reported before the first step [s]."""

INPUT_EXTRAPOLATION_DESCRIPTION = (
    "For Jacobi-type masters (every unit steps, then the outputs are exchanged): extrapolate "
    "the neighbour displacements from their velocities to the unit's time and give the "
    "neighbours back the contact impulse they missed; off: the inputs as they are (DESIGN.md "
    "step order, where it changes nothing) [-]")
"""Description of the ``input_extrapolation`` parameter of the anvil FMUs."""

RAM_TOE_MASS_DESCRIPTION = (
    "With input_extrapolation: the ram toe's mass for a force step (its velocity changes by "
    "-dF t/m over a time t after a step dF), whose response to the changes of the ram force "
    "the extrapolated ram state includes; 0: none [kg]")
"""Description of the ``ram_toe_mass`` parameter of the anvil FMUs."""


def check_ram_toe_mass(value: float, source: str) -> float:
    """The ``ram_toe_mass`` parameter of an anvil unit, checked: finite and >= 0.

    The native anvil (``anvilwave/fmu/native/anvil_unit.c``, ``start``) applies the same rule
    with the same reason.

    Parameters
    ----------
    value : float
        The ram toe's mass for a force step [kg] (0: none).
    source : str
        What the value belongs to, for the error (the unit or the build).

    Returns
    -------
    float
        The value [kg].

    Raises
    ------
    InputError
        If the value is not finite or negative.
    """
    value = float(value)
    if not (math.isfinite(value) and value >= 0.0):
        raise InputError(source, "ram_toe_mass", f"must be >= 0 [kg], got {value:g}")
    return value


def approach_input(u_ram: float, v_ram: float, u_top: float, v_top: float, h: float,
                   touched: bool) -> tuple[float, float]:
    """The ram toe as the anvil's contact sees it before the first contact.

    Until the ram contact has carried a force (``touched``), at a communication point after a
    step h a toe that is open by more than it closes in one step (gap u_top - u_ram > 0 and
    > (v_ram - v_top) h) is taken out of reach (1 m above the top face, at its velocity): the
    contact dashpot's lead across the gap (the equivalent overlap d + c d'/k of the static
    correction) starts at most a step before the first contact, as in the engine, which
    starts half a step before it. So a master that gives the anvil the ram's state at the
    second point (the DESIGN.md order, OMSimulator) and a Jacobi one, whose anvil acts from the
    third point on (step 4 of the module docstring), start alike from the ram's
    ``contact_mid_step`` (the first contact mid third step). The native anvil
    (``anvilwave/fmu/native/anvil_unit.c``, ``approach_input``) does the same operations.

    Parameters
    ----------
    u_ram : float
        Ram toe displacement [m], positive down.
    v_ram : float
        Ram toe velocity [m/s], positive down.
    u_top : float
        Anvil top face displacement of the modes (no contact force) [m].
    v_top : float
        Anvil top face velocity of the modes [m/s].
    h : float
        The last communication step [s]; 0 before the first step (nothing changed).
    touched : bool
        The ram contact has carried a force.

    Returns
    -------
    u_ram : float
        The toe displacement the contact sees [m].
    v_ram : float
        The toe velocity the contact sees [m/s].
    """
    if touched or h == 0.0:
        return u_ram, v_ram
    gap = u_top - u_ram
    if gap > 0.0 and gap > (v_ram - v_top) * h:
        return u_top - 1.0, v_top
    return u_ram, v_ram


def extrapolated_input(displacement: float, velocity: float, previous_velocity: float,
                       age: float, interval: float, force: float = 0.0,
                       force_after: float = 0.0, toe_mass: float = 0.0) -> tuple[float, float]:
    """A neighbour's displacement and velocity ``age`` after they were received.

    a = (velocity - previous_velocity) / interval (0 for interval 0) extrapolates the
    velocity. With the neighbour's toe mass m > 0 (the mass its contact face has for a force
    step: its velocity changes by -dF t / m in the first instants t after a step dF, before
    its waves or modes spread the force) the extrapolation adds the toe's response to the
    change of the contact force since the values were received: a already holds the
    deceleration by ``force``, the force held over the step that gave ``velocity``, so
    dv = -(``force_after`` - ``force``) age / m is added to the velocity and age dv to the
    displacement. For a leapfrog mass under a held force that is exact. The native anvil
    (``anvilwave/fmu/native/anvil_unit.c``, ``extrapolated_input``) does the same operations in
    the same order.

    Parameters
    ----------
    displacement : float
        The neighbour's displacement u as received [m].
    velocity : float
        The neighbour's half-step velocity v (its mean velocity over its last step) [m/s].
    previous_velocity : float
        The velocity received ``interval`` earlier [m/s].
    age : float
        Time since the values were received [s].
    interval : float
        Time between the two velocities [s]; 0: no acceleration.
    force : float, default 0.0
        Contact force on the neighbour over the step that gave ``velocity`` [N], positive
        against its velocity (compression on a ram toe moving down).
    force_after : float, default 0.0
        Contact force on the neighbour since the values were received [N], same sense.
    toe_mass : float, default 0.0
        The neighbour's toe mass m [kg]; 0: no response to the forces.

    Returns
    -------
    displacement : float
        u + age (v + a interval / 2) + a age^2 / 2 + age dv [m]; exactly u at age 0.
    velocity : float
        v + a age + dv [m/s]; exactly v at age 0.
    """
    if age == 0.0:
        return displacement, velocity
    acceleration = (velocity - previous_velocity) / interval if interval > 0.0 else 0.0
    u = (displacement + age * (velocity + 0.5 * interval * acceleration)
         + 0.5 * acceleration * age * age)
    v = velocity + acceleration * age
    if toe_mass > 0.0:
        change = -(force_after - force) * age / toe_mass
        u = u + age * change
        v = v + change
    return u, v


class InputExtrapolation:
    """State of the input extrapolation of an anvil unit (module docstring, steps 1-3).

    Parameters
    ----------
    time : float
        The unit's communication point [s]: the start time, then the end of each step
        (current communication point + step size).
    ram_toe_mass : float, default 0.0
        The ram toe's mass for a force step [kg] (:func:`extrapolated_input`: the toe's
        response to the changes of the F_ram the ram holds); 0: none.
    """

    def __init__(self, time: float, ram_toe_mass: float = 0.0):
        self.ram_toe_mass = ram_toe_mass
        self.start = time  # the start time [s] (step 1: no acceleration across it)
        self.time = time
        self.input_time = time  # when the inputs were last set [s]
        self.interval = 0.0  # from the point before to input_time [s] (0: no point before)
        self.previous_velocity = (0.0, 0.0)  # v_ram, v_pile at the point before [m/s]
        self.correction = [0.0, 0.0]  # impulse correction of F_ram, F_pile [N]
        self.evaluated = None  # (F_ram, F_pile) of the last output evaluation, uncorrected [N]
        self.sent = None  # ... of the last output read since the last step [N]
        self.evaluated_at_start = False  # that evaluation used the start time's inputs
        self.sent_at_start = False  # ... the one read since the last step (step 4)
        self.output_ram = 0.0  # F_ram output of the last evaluation, corrected [N]
        self.sent_output = 0.0  # ... of the last one read since the last step [N]
        self.held = 0.0  # the F_ram output the ram holds over the last step [N]
        # F_ram the ram held over the step that gave the inputs and since them
        # (extrapolated_input's force and force_after) [N]
        self.ram_forces = [0.0, 0.0]

    def note_inputs(self, inputs) -> None:
        """Before new inputs are stored: at a new point keep the velocities of the last one.

        Parameters
        ----------
        inputs : list of float
            The inputs still held, (u_ram, v_ram, u_pile, v_pile) [m, m/s, m, m/s].
        """
        if self.time > self.input_time:
            self.previous_velocity = (inputs[1], inputs[3])
            self.ram_forces[0] = self.held
            self.interval = self.time - self.input_time if self.input_time > self.start else 0.0
            self.input_time = self.time

    def extrapolated(self, inputs) -> tuple[float, float, float, float]:
        """(u_ram, v_ram, u_pile, v_pile) at the unit's time (:func:`extrapolated_input`).

        Parameters
        ----------
        inputs : list of float
            The inputs as set, (u_ram, v_ram, u_pile, v_pile) [m, m/s, m, m/s].

        Returns
        -------
        tuple of float
            The extrapolated (u_ram, v_ram, u_pile, v_pile) [m, m/s, m, m/s].
        """
        age = self.time - self.input_time
        u_ram, v_ram = extrapolated_input(inputs[0], inputs[1], self.previous_velocity[0], age,
                                          self.interval, *self.ram_forces, self.ram_toe_mass)
        u_pile, v_pile = extrapolated_input(inputs[2], inputs[3], self.previous_velocity[1], age,
                                            self.interval)
        return u_ram, v_ram, u_pile, v_pile

    def evaluate(self, force_ram: float, force_pile: float) -> None:
        """An output evaluation gave these forces (uncorrected).

        Parameters
        ----------
        force_ram : float
            Ram-anvil contact force [N].
        force_pile : float
            Anvil-pile contact force [N].
        """
        self.evaluated = (force_ram, force_pile)
        self.evaluated_at_start = self.input_time == self.start
        self.output_ram = force_ram + self.correction[0]

    def read(self) -> None:
        """The outputs were read: the neighbours hold the forces of the last evaluation."""
        if self.evaluated is not None:
            self.sent = self.evaluated
            self.sent_at_start = self.evaluated_at_start
            self.sent_output = self.output_ram

    def step_forces(self, force_ram: float, force_pile: float) -> tuple[float, float]:
        """The forces a step applies (module docstring, steps 3 and 4).

        Parameters
        ----------
        force_ram : float
            Ram-anvil contact force at the step start, from the extrapolated inputs [N].
        force_pile : float
            Anvil-pile contact force at the step start, from the extrapolated inputs [N].

        Returns
        -------
        tuple of float
            (F_ram, F_pile) [N]: the forces given, or those the neighbours hold when they were
            computed from the start time's inputs.
        """
        if self.sent is not None and self.sent_at_start:
            return self.sent
        return force_ram, force_pile

    def stepped(self, force_ram: float, force_pile: float) -> None:
        """The step applies these forces: the impulse correction follows from them.

        The correction is their difference to the forces read since the last step (none read:
        no correction). The F_ram output read since the last step is what the ram holds over
        this one (none read: the one before); from the inputs' time, ``force_after`` of
        :func:`extrapolated_input`.

        Parameters
        ----------
        force_ram : float
            Ram-anvil contact force the step applies [N].
        force_pile : float
            Anvil-pile contact force the step applies [N].
        """
        if self.sent is None:
            self.correction[:] = (0.0, 0.0)
        else:
            self.correction[:] = (force_ram - self.sent[0], force_pile - self.sent[1])
            self.held = self.sent_output
        if self.time == self.input_time:
            self.ram_forces[1] = self.held
        self.sent = None
