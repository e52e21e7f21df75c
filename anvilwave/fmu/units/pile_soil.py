"""The pile/soil FMU slave: FMI variables mapped onto :class:`anvilwave.pile.model.PileSoil` and
its kernels.

Interface (DESIGN.md, the contract): input ``F_head`` [N] (anvil-pile contact force,
compression positive, pushes the head down); outputs ``u_head`` [m], ``v_head`` [m/s] (pile
head), ``F_gauge`` [N], ``v_gauge`` [m/s] (PDA gauge location). Two more outputs for results:
``u_head_total`` [m] and ``u_pile_toe`` [m], and the running stress extremes over the pile
``max_compression_stress`` and ``max_tension_stress`` [Pa] (since the instance started, the
states after every step, as the in-process engine folds them). All outputs are states: no
feedthrough.

``u_head`` is the head displacement RELATIVE to its static position at initialization (the
pile in static equilibrium under ``static_head_load`` and gravity): the quantity the anvil's
pile contact takes (an anvil resting on the pile at ``u_pile = 0``), exactly what the
in-process engine hands its anvil unit. ``u_head_total`` is the head displacement from the
undeformed pile (static settlement included), ``u_pile_toe`` the toe's.

The pile and soil are read from a TOML file with a ``[pile]`` table and an optional ``[soil]``
table (``pile_soil_file``; a relative name is looked up in the FMU resources, where
:func:`anvilwave.fmu.fmi_build.build_pile_soil_fmu` embeds it): the sections and the SRD table live
there.
The scalar settings are FMU parameters and replace the file's values of the same keys
(``segment_length``, ``gauge_depth``, ``material_damping`` of ``[pile]``; ``soil_model``
(key ``model``), ``penetration``, quakes, dampings, ``friction_perimeter``, ``toe_area`` and
the ``lysmer-toe`` constants of ``[soil]``); their defaults are the values the FMU was built
with. Each combination is validated like a system file
(:meth:`anvilwave.pile.model.PileSoil.from_tables`).

Stepping: :func:`anvilwave.pile.kernels.pile_advance` with ``F_head`` held, sub-stepped within the
stable
limit, ``n_sub = pile.model.substeps(h, stable_time_step)``, as in the in-process engine; any
communication step is accepted. The soil state (permanent set) carries on over consecutive
blows for as long as the instance lives (a master resets only the ram and the anvil).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
from numba import njit
from pythonfmu import DefaultExperiment

from anvilwave.fmu.units.base import UnitSlave
from anvilwave.inputs import InputError, Table, read_toml
from anvilwave.pile.kernels import (
    gauge_force,
    gauge_velocity,
    head_displacement,
    head_velocity,
    pile_advance,
    stable_time_step,
    sweep_arrays,
    toe_displacement,
    update_stress_extremes,
)
from anvilwave.pile.model import PileSoil, initial_state, substeps
from anvilwave.pile.soil.models import MODELS

PILE_KEYS = ("segment_length", "gauge_depth", "material_damping")
"""FMU parameters that set the ``[pile]`` key of the same name."""
SOIL_KEYS = {"soil_model": "model", "penetration": "penetration",
             "quake_shaft": "quake_shaft", "quake_toe": "quake_toe",
             "damping_shaft": "damping_shaft", "damping_toe": "damping_toe",
             "friction_perimeter": "friction_perimeter", "toe_area": "toe_area",
             "toe_shear_modulus": "toe_shear_modulus", "toe_density": "toe_density",
             "toe_poisson_ratio": "toe_poisson_ratio"}
"""FMU parameter -> ``[soil]`` key it sets."""
LYSMER_ONLY = ("toe_shear_modulus", "toe_density", "toe_poisson_ratio")
SMITH_TOE_ONLY = ("quake_toe", "damping_toe")


class PileSoilState:
    """Kernel arrays and state of a pile with its soil, resting under a head load.

    Parameters
    ----------
    model : PileSoil
        The validated pile with its soil.
    head_load : float
        Static head load the pile rests under at the start, compression positive [N].
    gravity : float
        Gravitational acceleration [m/s^2].
    """

    def __init__(self, model: PileSoil, head_load: float, gravity: float):
        self.arrays = model.arrays()
        self.gravity = float(gravity)
        state = initial_state(self.arrays, head_force=head_load, gravity=gravity)
        self.u, self.v, self.offset, self.energy = (np.array(a) for a in state)
        self.face0 = float(head_displacement(self.arrays.probes, self.u))
        self.stable_step = float(stable_time_step(self.arrays.pile, self.arrays.soil))
        self.stress_factor = model.stress_factors()
        self.extremes = np.zeros(2)  # [largest compression, largest tension] stress [Pa]
        update_stress_extremes(self.stress_factor, self.u, self.extremes)
        self._h = math.nan
        self._n_sub = 1
        # the step's arrays, prepared once (pile.kernels.sweep_arrays), as the engine does
        self.sweep = sweep_arrays(self.arrays.pile, self.arrays.soil, self.gravity)
        # compile (or load) the kernel now, on copies, not inside the first doStep
        pile_advance(*self.sweep, self.u.copy(), self.v.copy(), self.offset.copy(),
                     self.energy.copy(), 0.0, 1e-9, 1, None)

    def step(self, head_force: float, h: float) -> None:
        """Advance over h with the head force held (:func:`anvilwave.pile.kernels.pile_advance`).

        The head works of ``energy`` are kept, the other works are not summed: the FMU does not
        output them. The running stress extremes are updated after the step.

        Parameters
        ----------
        head_force : float
            Anvil-pile contact force on the head, compression positive [N].
        h : float
            Communication step [s].
        """
        if h != self._h:
            self._n_sub = substeps(h, self.stable_step)
            self._h = h
        pile_advance(*self.sweep, self.u, self.v, self.offset, self.energy, head_force, h,
                     self._n_sub, None)
        update_stress_extremes(self.stress_factor, self.u, self.extremes)


class PileSoilSlave(UnitSlave):
    """The pile with its soil (``PileSoil.fmu``).

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """

    kind = "PileSoil"
    description = ("anvilwave pile and soil: Smith lumped pile with soil springs (leapfrog, "
                   "sub-stepped within its stable limit), head force in, head and gauge "
                   "signals out (SI units, z down, compression positive)")
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=0.02, step_size=1e-5)
    parameter_fallbacks: ClassVar[dict] = {
        "pile_soil_file": None,
        "static_head_load": 0.0,
        "gravity": 9.81,
        "segment_length": 0.5,
        "gauge_depth": 1.0,
        "material_damping": 0.01,
        "soil_model": "smith-viscous",
        "penetration": 0.0,
        "quake_shaft": 0.0025,
        "quake_toe": 0.0025,
        "damping_shaft": 0.65,
        "damping_toe": 0.5,
        "friction_perimeter": "outside+inside",
        "toe_area": "annulus",
        "toe_shear_modulus": 1.0e8,
        "toe_density": 2000.0,
        "toe_poisson_ratio": 0.3,
    }

    def register_variables(self) -> None:
        """Register the pile/soil parameters, input ``F_head`` and the eight outputs."""
        p = self.add_parameter
        p("pile_soil_file", None, "Pile and soil file (TOML: [pile] with its [[pile.sections]], "
                                  "optional [soil] with its srd table); a relative name is "
                                  "looked up in the FMU resources [-]", str)
        p("static_head_load", "N", "Weight resting on the pile head at the start (anvil, "
                                   "helmet), in static equilibrium [N]")
        p("gravity", "m/s2", "Gravitational acceleration on the pile masses, 0 switches it "
                             "off [m/s^2]")
        p("segment_length", "m", "Target pile segment length [m]")
        p("gauge_depth", "m", "Depth of the PDA gauges below the pile head [m]")
        p("material_damping", "1", "Pile material damping, fraction of critical of one "
                                   "segment [-]")
        p("soil_model", None, f"Soil model: {', '.join(MODELS)} [-]", str)
        p("penetration", "m", "Embedded length below the mudline [m]")
        p("quake_shaft", "m", "Shaft quake [m]")
        p("quake_toe", "m", "Toe quake (smith, smith-viscous) [m]")
        p("damping_shaft", "s/m", "Smith damping factor J on the shaft [s/m]")
        p("damping_toe", "s/m", "Smith damping factor J at the toe (smith, smith-viscous) [s/m]")
        p("friction_perimeter", None, "Shaft friction perimeter: outside+inside or outside [-]",
          str)
        p("toe_area", None, "Toe bearing area: annulus or plugged [-]", str)
        p("toe_shear_modulus", "Pa", "Soil shear modulus below the toe (lysmer-toe; the "
                                     "default is an illustrative dense sand) [Pa]")
        p("toe_density", "kg/m3", "Soil density below the toe (lysmer-toe) [kg/m^3]")
        p("toe_poisson_ratio", "1", "Soil Poisson's ratio below the toe (lysmer-toe) [-]")
        self.add_input("F_head", "N", "Anvil-pile contact force on the head, compression "
                                      "positive (pushes the head down) [N]")
        o = self.add_output
        o("u_head", "m", "Pile head displacement relative to its static position at the start "
                         "(the anvil contact's input), positive down [m]")
        o("v_head", "m/s", "Pile head velocity, positive down [m/s]")
        o("F_gauge", "N", "Axial force at the gauge depth, compression positive [N]")
        o("v_gauge", "m/s", "Pile velocity at the gauge depth, positive down [m/s]")
        o("u_head_total", "m", "Pile head displacement from the undeformed pile (static "
                               "settlement included), positive down [m]")
        o("u_pile_toe", "m", "Pile toe displacement from the undeformed pile, positive "
                             "down [m]")
        o("max_compression_stress", "Pa", "Largest axial compressive stress in the pile since "
                                          "the start, over all springs [Pa]")
        o("max_tension_stress", "Pa", "Largest axial tensile stress in the pile since the "
                                      "start, over all springs (negative) [Pa]")

    # ------------------------------------------------------------------ mapping
    def build_component(self) -> PileSoilState:
        """The pile with its soil at rest under ``static_head_load`` [N] and gravity.

        Returns
        -------
        PileSoilState
            Kernel arrays and state of the pile with its soil.

        Raises
        ------
        InputError
            If ``static_head_load`` or ``gravity`` is out of range, or the pile/soil file or
            the parameters are invalid.
        """
        par = self.parameters
        name = self.instance_name
        for key in ("static_head_load", "gravity"):
            if not math.isfinite(par[key]):
                raise InputError(name, key, f"must be finite, got {par[key]!r}")
        if par["static_head_load"] < 0.0:
            raise InputError(name, "static_head_load",
                             f"must be at least 0 N, got {par['static_head_load']:g}")
        if not 0.0 <= par["gravity"] <= 20.0:
            raise InputError(name, "gravity", f"must be in [0, 20] m/s^2, got {par['gravity']:g}")
        model = self.pile_soil_model()
        return PileSoilState(model, par["static_head_load"], par["gravity"])

    def pile_soil_model(self) -> PileSoil:
        """The validated pile and soil: the file's tables with the parameters applied.

        Returns
        -------
        PileSoil
            The pile with its soil.

        Raises
        ------
        InputError
            If the file has an unknown or malformed table, or a value is invalid.
        """
        par = self.parameters
        path = self.resource_path(par["pile_soil_file"])
        root = read_toml(path)
        source = f"{self.instance_name} ({path.name})"
        unknown = sorted(set(root) - {"pile", "soil"})
        if unknown:
            raise InputError(source, unknown[0], "unknown table (allowed: pile, soil)")
        pile = dict(_table(root, "pile", source))
        for key in PILE_KEYS:
            pile[key] = par[key]
        soil = root.get("soil")
        if soil is not None:
            soil = dict(_table(root, "soil", source))
            for parameter, key in SOIL_KEYS.items():
                soil[key] = par[parameter]
            drop = SMITH_TOE_ONLY if soil["model"] == "lysmer-toe" else LYSMER_ONLY
            for key in drop:
                soil.pop(key, None)
        return PileSoil.from_tables(Table(pile, source, "pile"),
                                    None if soil is None else Table(soil, source, "soil"))

    def compute_outputs(self, inputs, outputs) -> None:
        """The eight outputs from the pile state (all states: no feedthrough).

        Parameters
        ----------
        inputs : list of float
            (F_head,) [N] (unused: the outputs are states).
        outputs : list of float
            (u_head, v_head, F_gauge, v_gauge, u_head_total, u_pile_toe,
            max_compression_stress, max_tension_stress) [SI], filled in place.
        """
        c = self.component
        outputs[:6] = pile_outputs(c.arrays.pile, c.arrays.probes, c.u, c.v, c.face0)
        outputs[6:] = c.extremes

    def advance(self, h: float) -> None:
        """Advance the pile over ``h`` with ``F_head`` held.

        Parameters
        ----------
        h : float
            Communication step [s].
        """
        self.component.step(self.inputs[0], h)


@njit(cache=True)
def pile_outputs(pile, probes, u, v, face0):
    """The six kinematic and gauge outputs in one call: the engine's output kernels.

    Parameters
    ----------
    pile : numpy.ndarray
        Pile kernel arrays (``PileSoilArrays.pile``).
    probes : numpy.ndarray
        Probe data of the head and gauge (``PileSoilArrays.probes``).
    u : numpy.ndarray
        Mass displacements, positive down [m].
    v : numpy.ndarray
        Mass velocities, positive down [m/s].
    face0 : float
        Static head position at the start [m].

    Returns
    -------
    u_head : float
        Head displacement relative to the static head position face0, positive down [m].
    v_head : float
        Head velocity, positive down [m/s].
    F_gauge : float
        Axial force at the gauge depth, compression positive [N].
    v_gauge : float
        Velocity at the gauge depth, positive down [m/s].
    u_head_total : float
        Head displacement from the undeformed pile, positive down [m].
    u_pile_toe : float
        Toe displacement, positive down [m].
    """
    face = head_displacement(probes, u)
    return (face - face0, head_velocity(probes, v), gauge_force(pile, probes, u, v),
            gauge_velocity(probes, v), face, toe_displacement(u))


def _table(root: dict, name: str, source: str) -> dict:
    value = root.get(name)
    if not isinstance(value, dict):
        raise InputError(source, name, "must be a table" if value is not None
                         else "is required but missing")
    return value
