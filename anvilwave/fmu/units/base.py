"""What every anvilwave FMU slave shares: variables with units, per-build defaults, errors.

A slave class only maps FMI variables onto a component object (ram, anvil, pile/soil) and calls
its methods; the physics lives in the component. :class:`UnitSlave` supplies the machinery:

- ``add_parameter`` / ``add_input`` / ``add_output`` register a pythonfmu variable together with
  its unit and (for outputs) the inputs it depends on directly (feedthrough). The unit and the
  dependencies are what :mod:`anvilwave.fmu.fmi_build` writes into ``modelDescription.xml``
  (``UnitDefinitions``, ``unit`` attributes, ``ModelStructure``), which pythonfmu cannot do.
- Parameter defaults come from ``resources/anvilwave_parameters.json`` of the instance's own
  FMU (written by the build), not from the script: pythonfmu runs the first loaded module of a
  given name for every FMU in a process, so anything build-specific baked into a script would
  leak from one FMU into another. The scripts are therefore identical for every build of a kind.
- Errors never leave Python as exceptions. pythonfmu 0.7.0 turns any exception raised in
  ``setup_experiment``, ``enter_initialization_mode``, ``exit_initialization_mode`` or
  ``do_step`` into ``fmi2Fatal`` and releases its reference to the slave (later calls on that
  instance are unsafe). Instead, the reason is logged with status ``fmi2Error``, the instance is
  marked failed, and ``do_step`` returns ``False`` (pythonfmu: ``fmi2Discard``). The status shim
  that :mod:`anvilwave.fmu.fmi_build` compiles into the FMU (``fmi2_status_shim.c``) turns any call
  during
  which an error was logged into ``fmi2Error``. ``fmi2Reset`` builds a fresh slave (pythonfmu
  calls ``__init__`` again), so a reset instance starts clean with the build defaults.

A slave script (what pythonfmu embeds and imports by module name) has a module name unique to
its FMU type (``anvilwave_<unit>.py``), calls ``pin_namespace(globals())`` and defines one
subclass of a :class:`UnitSlave` subclass; see ``anvilwave/fmu/units/anvilwave_anvil_rom.py``.

Time handling: the slaves accept any communication step ``h > 0``; each component integrates
its own way over it (the anvil ROM in one step, unconditionally stable; ram and pile in
sub-steps within their stable limits). ``fmi2SetupExperiment``'s start time is kept as
``start_time`` (the ram starts its free flight there).

Speed: ``get_real`` / ``set_real`` take a short cut when a call reads only outputs or writes
only inputs (the per-step exchange), and setting an input keeps the outputs of a unit without
feedthrough valid, so each output is computed once per step.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, ClassVar

from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String
from pythonfmu.enums import Fmi2Status

from anvilwave.inputs import InputError

DEFAULTS_FILE = "anvilwave_parameters.json"
"""Name of the per-build parameter defaults inside the FMU's ``resources`` folder."""

_PINNED_NAMESPACES: list[dict] = []


def pin_namespace(namespace: dict) -> None:
    """Hold one more reference to a slave script's module namespace (call with ``globals()``).

    Work-around for pythonfmu 0.7.0: at every ``fmi2Instantiate`` its C++ loader re-executes
    the script in the module's namespace and then releases a reference to that namespace that
    it never owned (``Py_DECREF`` of the borrowed ``PyModule_GetDict``). A script with few
    functions soon has its namespace freed under the loaded module and the host crashes at the
    second or third instantiation. Each execution of a script that calls this adds the
    reference the loader will take away.

    Parameters
    ----------
    namespace : dict
        The slave script's module namespace (``globals()``).
    """
    _PINNED_NAMESPACES.append(namespace)


_TYPES = {float: Real, bool: Boolean, str: String}


class UnitSlave(Fmi2Slave):
    """Base of the anvilwave slaves: register variables, build the component, guard errors.

    Subclasses implement

    - ``register_variables()``: call ``add_parameter`` / ``add_input`` / ``add_output``;
    - ``build_component()``: the component from the parameters (raise
      :class:`~anvilwave.inputs.InputError` on a bad value);
    - ``start_component()``: put it in its initial state (optional);
    - ``compute_outputs(inputs, outputs)``: fill the output list from the current inputs
      (feedthrough outputs are evaluated here, at the current time);
    - ``advance(h)``: advance the component over ``h`` [s] with the current inputs held.

    ``kind`` names the FMU type (e.g. ``"Anvil"``); ``parameter_fallbacks`` gives the default of
    each parameter when the build does not set it (``None``: the build must set it).

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.

    References
    ----------
    Modelica Association. Functional Mock-up Interface for Model Exchange and Co-Simulation,
    FMI 2.0.4. https://fmi-standard.org
    """

    kind: ClassVar[str] = ""
    parameter_fallbacks: ClassVar[dict[str, Any]] = {}

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.modelName = self.kind or type(self).__name__
        self.fmi_units: dict[str, str] = {}
        self.fmi_dependencies: dict[str, tuple[str, ...]] = {}
        self.parameters: dict[str, Any] = {}
        self.input_names: list[str] = []
        self.output_names: list[str] = []
        self.inputs: list[float] = []
        self.outputs: list[float] = []
        self._input_vr: dict[int, int] = {}  # value reference -> index in inputs
        self._output_vr: dict[int, int] = {}  # value reference -> index in outputs
        self._get_plans: dict[tuple, tuple | None] = {}
        self._set_plans: dict[tuple, tuple | None] = {}
        self._feedthrough = False  # does any output depend directly on an input?
        self.component = None
        self.start_time = 0.0
        self._time = 0.0
        self.default_step: float | None = None  # the build's DefaultExperiment step [s]
        self.failed = False
        self._initialized = False
        self._outputs_current = False
        self._defaults = self._read_defaults()
        self.register_variables()

    # ------------------------------------------------------------------ subclass interface
    def register_variables(self) -> None:
        """Register the unit's variables with ``add_parameter``, ``add_input``, ``add_output``.

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it.
        """
        raise NotImplementedError

    def build_component(self):
        """The component (ram, anvil, pile/soil) built from ``self.parameters``.

        Returns
        -------
        object
            The component the slave maps its variables onto.

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it (and raises
            :class:`~anvilwave.inputs.InputError` on a bad parameter value).
        """
        raise NotImplementedError

    def start_component(self) -> None:
        """Initial state of the component (default: as built)."""

    def compute_outputs(self, inputs: list[float], outputs: list[float]) -> None:
        """Fill ``outputs`` from the current inputs, at the current time.

        Parameters
        ----------
        inputs : list of float
            Input values, in registration order [SI].
        outputs : list of float
            Output values, in registration order, filled in place [SI].

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it.
        """
        raise NotImplementedError

    def advance(self, h: float) -> None:
        """Advance the component over one communication step with the current inputs held.

        Parameters
        ----------
        h : float
            Communication step [s].

        Raises
        ------
        NotImplementedError
            Always: a subclass implements it.
        """
        raise NotImplementedError

    # ------------------------------------------------------------------ registration
    def add_parameter(self, name: str, unit: str | None, description: str,
                      kind: type = float) -> None:
        """A fixed parameter (set before or during initialization) of type float, bool or str.

        Its default is the build's value, else ``parameter_fallbacks[name]``.

        Parameters
        ----------
        name : str
            FMI variable name.
        unit : str or None
            FMI unit (e.g. ``"N/m"``); ``None`` for none.
        description : str
            FMI variable description.
        kind : type, default float
            Python type of the value: ``float``, ``bool`` or ``str``.
        """
        value = self._defaults.get(name, self.parameter_fallbacks.get(name))
        if value is None:
            self._fail(f"parameter {name!r} has no default: set it when building the FMU")
            value = {float: 0.0, bool: False, str: ""}[kind]
        self.parameters[name] = kind(value)

        def setter(v, name=name, kind=kind):
            if self._initialized:
                self._fail(f"parameter {name!r} is fixed: it cannot change after initialization")
                return
            self.parameters[name] = kind(v)
            self.component = None  # rebuilt from the new value when needed

        var = _TYPES[kind](name, causality=Fmi2Causality.parameter,
                           variability=Fmi2Variability.fixed, description=description,
                           getter=lambda name=name: self.parameters[name], setter=setter)
        self._register(var, unit)

    def add_input(self, name: str, unit: str, description: str, start: float = 0.0) -> None:
        """A continuous Real input.

        Parameters
        ----------
        name : str
            FMI variable name.
        unit : str
            FMI unit (e.g. ``"m/s"``).
        description : str
            FMI variable description.
        start : float, default 0.0
            Start value [SI unit of the input].
        """
        index = len(self.inputs)
        self.input_names.append(name)
        self.inputs.append(float(start))

        def setter(v, index=index):
            self.inputs[index] = v
            self._outputs_current = False

        var = Real(name, causality=Fmi2Causality.input, variability=Fmi2Variability.continuous,
                   description=description, getter=lambda index=index: self.inputs[index],
                   setter=setter)
        self._register(var, unit)
        self._input_vr[var.value_reference] = index

    def add_output(self, name: str, unit: str, description: str,
                   depends_on: tuple[str, ...] = ()) -> None:
        """A continuous Real output.

        Parameters
        ----------
        name : str
            FMI variable name.
        unit : str
            FMI unit (e.g. ``"N"``).
        description : str
            FMI variable description.
        depends_on : tuple of str, default ()
            The (registered) inputs that feed through to it directly.

        Raises
        ------
        ValueError
            If ``depends_on`` names an input that is not registered.
        """
        index = len(self.outputs)
        self.output_names.append(name)
        self.outputs.append(math.nan)
        unknown = set(depends_on) - set(self.input_names)
        if unknown:
            raise ValueError(f"{name}: depends on unregistered inputs {sorted(unknown)}")
        self.fmi_dependencies[name] = tuple(depends_on)
        self._feedthrough = self._feedthrough or bool(depends_on)
        var = Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                   description=description, getter=lambda index=index: self._output(index))
        self._register(var, unit)
        self._output_vr[var.value_reference] = index

    def _register(self, var, unit: str | None) -> None:
        if unit is not None:
            self.fmi_units[var.name] = unit
        self.register_variable(var)

    # ------------------------------------------------------------------ FMI calls
    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        """Record the start time (``self.start_time``): the component starts there.

        Called by fmi2SetupExperiment.

        Parameters
        ----------
        start_time : float
            Start time of the experiment [s].
        stop_time : float or None, optional
            Stop time [s] (unused).
        tolerance : float or None, optional
            Tolerance [-] (unused).
        """
        if not self._initialized:
            self.start_time = self._time = float(start_time)
            self.component = None  # its initial state may depend on the start time

    def exit_initialization_mode(self):
        """Build and start the component (fmi2ExitInitializationMode); an error is logged."""
        self._guard("initialization", self._initialize)

    def do_step(self, current_time: float, step_size: float) -> bool:
        """Advance the unit over one communication step (fmi2DoStep).

        Parameters
        ----------
        current_time : float
            Communication point at the step start [s].
        step_size : float
            Communication step h [s], positive.

        Returns
        -------
        bool
            ``True`` on success; ``False`` (fmi2Discard) after an error, which is logged.
        """
        if self.failed:
            self._fail("failed earlier (see the previous error): reset or free it")
            return False
        try:  # _guard inlined: this runs every step
            self._step(step_size)
            return True
        except Exception:  # noqa: BLE001 - reported by _guard, which re-raises nothing
            return self._guard(f"step at t = {current_time:.9g} s", _reraise, sys.exc_info())

    # Fast paths of the per-step exchange (pythonfmu calls these once per fmi2GetReal /
    # fmi2SetReal): all outputs or all inputs go straight to the lists, anything else takes
    # pythonfmu's general route through the variables' getters and setters.
    def get_real(self, vrs):
        """Values of Real variables (fmi2GetReal); only outputs: straight from the output list.

        Parameters
        ----------
        vrs : list of int
            Value references.

        Returns
        -------
        list of float
            The values [SI]; NaN where the outputs could not be evaluated (the error logged).
        """
        key = tuple(vrs)
        plan = self._get_plans.get(key, False)
        if plan is False:
            index = self._output_vr
            plan = tuple(index[vr] for vr in key) if all(vr in index for vr in key) else None
            self._get_plans[key] = plan
        if plan is None:
            return super().get_real(vrs)
        if not self._outputs_current:
            if self.component is None and not self._guard("initialization",
                                                          self._ensure_component):
                return [math.nan] * len(plan)
            if not self._guard("outputs", self._refresh):
                return [math.nan] * len(plan)
        outputs = self.outputs
        values = [outputs[i] for i in plan]
        if not all(map(math.isfinite, values)):  # never fmi2OK with a NaN or an infinity
            bad = [self.output_names[i] for i, v in zip(plan, values, strict=True)
                   if not math.isfinite(v)]
            self._fail(f"outputs {bad} are not finite at t = {self.time_now():.9g} s "
                       f"(inputs {dict(zip(self.input_names, self.inputs, strict=True))})")
        return values

    def set_real(self, vrs, values):
        """Set Real variables (fmi2SetReal); only inputs: straight into the input list.

        A value that is not finite is rejected and logged as an error.

        Parameters
        ----------
        vrs : list of int
            Value references.
        values : list of float
            The values [SI].

        Returns
        -------
        None
            Nothing (as pythonfmu's ``Fmi2Slave.set_real``).
        """
        key = tuple(vrs)
        plan = self._set_plans.get(key, False)
        if plan is False:
            index = self._input_vr
            plan = tuple(index[vr] for vr in key) if all(vr in index for vr in key) else None
            self._set_plans[key] = plan
        if plan is None:
            return super().set_real(vrs, values)
        inputs = self.inputs
        for i, value in zip(plan, values, strict=False):
            if not math.isfinite(value):
                self._fail(f"input {self.input_names[i]!r} is not finite ({value!r})")
                continue
            inputs[i] = value
        if self._feedthrough:  # outputs that are states stay valid
            self._outputs_current = False

    # ------------------------------------------------------------------ internals
    def _initialize(self) -> None:
        if self.failed:
            raise InputError(self.instance_name, "", "cannot initialize (see the previous error)")
        self._ensure_component()
        self._initialized = True

    def _ensure_component(self) -> None:
        if self.component is None:
            self.component = self.build_component()
            self.start_component()
            self._outputs_current = False

    def time_now(self) -> float:
        """The unit's communication point (start time, then the end of the last step).

        Returns
        -------
        float
            Communication point [s].
        """
        return self._time

    def _step(self, h: float) -> None:
        if not (math.isfinite(h) and h > 0.0):
            raise InputError(self.instance_name, "communication step", f"must be positive, "
                                                                      f"got {h!r} s")
        if not self._outputs_current:
            self.compute_outputs(self.inputs, self.outputs)
        self.advance(h)
        self._time += h
        self._outputs_current = False

    def _refresh(self) -> None:
        if not self._outputs_current:
            self.compute_outputs(self.inputs, self.outputs)
            self._outputs_current = True

    def _output(self, index: int) -> float:
        if not self._outputs_current:
            if self.component is None and not self._guard("initialization",
                                                          self._ensure_component):
                return math.nan
            if not self._guard("outputs", self._refresh):
                return math.nan
        return self.outputs[index]

    def _guard(self, what: str, action: Callable, *args) -> bool:
        """Run ``action``; on any exception log it as an fmi2Error and mark the unit failed."""
        try:
            action(*args)
            return True
        except InputError as exc:  # a user error: its message is the whole story
            self._fail(f"{what}: {exc}")
        except Exception as exc:  # noqa: BLE001 - an exception reaching pythonfmu is fmi2Fatal
            self._fail(f"{what}: {type(exc).__name__}: {exc}")
        return False

    def _fail(self, message: str) -> None:
        self.failed = True
        self.log(f"{self.modelName} {self.instance_name}: {message}", Fmi2Status.error)

    def _read_defaults(self) -> dict[str, Any]:
        if not self.resources:
            return {}
        path = Path(self.resources) / DEFAULTS_FILE
        if not path.exists():
            return {}
        try:
            content = json.loads(path.read_text(encoding="utf-8"))
            step = (content.get("default_experiment") or {}).get("step_size")
            self.default_step = float(step) if step else None
            return dict(content["parameters"])
        except (OSError, ValueError, KeyError, TypeError) as exc:
            self.log(f"{path}: unreadable parameter defaults ({exc})", Fmi2Status.error)
            self.failed = True
            return {}

    def resource_path(self, name: str) -> Path:
        """A file named by a parameter: relative names are inside this FMU's resources.

        Parameters
        ----------
        name : str
            File name, absolute or relative to the FMU's ``resources`` folder.

        Returns
        -------
        pathlib.Path
            Path of the file.
        """
        path = Path(name)
        if not path.is_absolute() and self.resources:
            path = Path(self.resources) / path
        return path


def _reraise(exc_info) -> None:
    """Raise an exception caught earlier again (so that ``_guard`` reports it)."""
    raise exc_info[1].with_traceback(exc_info[2])
