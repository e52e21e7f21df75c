"""The PileSoil component: validated parameters -> kernel arrays -> initial state.

Typical use (an FMU wrapper or the in-process engine)::

    model = load_pile_soil("pile.toml")             # or PileSoil.from_tables(pile_t, soil_t)
    arrays = model.arrays()                         # pile, soil, probes parameter arrays
    state = initial_state(arrays, head_force=W, gravity=9.81)
    n_sub = substeps(h, stable_time_step(arrays.pile, arrays.soil))
    pile_step(arrays.pile, arrays.soil, *state, F_head, 9.81, h, n_sub)   # every step
    u_head = head_displacement(arrays.probes, state.u)                    # outputs
    f_gauge = gauge_force(arrays.pile, arrays.probes, state.u, state.v)

``state`` unpacks in the kernel order ``u, v, soil_offset, energy``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np

from anvilwave.inputs import Table
from anvilwave.pile.kernels import ENERGY_SIZE, HEAD_EXTRAPOLATION, PILE_STIFFNESS, update_energy
from anvilwave.pile.pile import PileSpec, pile_from_table, pile_parameters, probe_parameters
from anvilwave.pile.soil.models import SoilSpec, soil_from_table, soil_parameters
from anvilwave.pile.static import static_equilibrium


class PileSoilArrays(NamedTuple):
    """Parameter arrays of the kernels (layouts in :mod:`anvilwave.pile.kernels`).

    Parameters
    ----------
    pile : numpy.ndarray
        (PILE_ROWS, N) pile parameters.
    soil : numpy.ndarray
        (SOIL_ROWS, N + 1) soil parameters, toe last.
    probes : numpy.ndarray
        (PROBE_SIZE,) probe settings.
    """

    pile: np.ndarray   # (PILE_ROWS, N)
    soil: np.ndarray   # (SOIL_ROWS, N + 1)
    probes: np.ndarray  # (PROBE_SIZE,)


class PileSoilState(NamedTuple):
    """State arrays, in the argument order of :func:`anvilwave.pile.kernels.pile_step`.

    Parameters
    ----------
    u : numpy.ndarray
        (N,) displacement [m], positive down.
    v : numpy.ndarray
        (N,) velocity [m/s], positive down.
    soil_offset : numpy.ndarray
        (N + 1,) plastic offset of the soil springs [m], toe last.
    energy : numpy.ndarray
        (ENERGY_SIZE,) energies and works [J].
    """

    u: np.ndarray            # (N,) displacement [m], positive down
    v: np.ndarray            # (N,) velocity [m/s], positive down
    soil_offset: np.ndarray  # (N + 1,) plastic offset of the soil springs [m], toe last
    energy: np.ndarray       # (ENERGY_SIZE,) energies and works [J]


@dataclass(frozen=True, eq=False)
class PileSoil:
    """A pile with (optionally) its soil.

    Parameters
    ----------
    pile : PileSpec
        The pile sections and discretisation settings.
    soil : SoilSpec or None, default None
        The soil model, SRD and penetration; None for a pile without soil (free toe).
    """

    pile: PileSpec
    soil: SoilSpec | None = None

    @classmethod
    def from_tables(cls, pile_table: Table, soil_table: Table | None,
                    srd_optional: bool = False,
                    default_penetration: float | None = None) -> PileSoil:
        """From the ``[pile]`` and (optional) ``[soil]`` tables of an input file.

        Parameters
        ----------
        pile_table : Table
            The ``[pile]`` table.
        soil_table : Table or None
            The ``[soil]`` table (None: no soil).
        srd_optional : bool, default False
            See :func:`anvilwave.pile.soil.models.soil_from_table`.
        default_penetration : float or None, default None
            See :func:`anvilwave.pile.soil.models.soil_from_table` [m].

        Returns
        -------
        PileSoil
            The pile and its soil.
        """
        pile = pile_from_table(pile_table)
        soil = (soil_from_table(soil_table, pile.length, srd_optional, default_penetration)
                if soil_table is not None else None)
        return cls(pile, soil)

    def arrays(self, extrapolate_head: bool = False) -> PileSoilArrays:
        """The kernel parameter arrays (float64, C-contiguous).

        Parameters
        ----------
        extrapolate_head : bool, default False
            The head outputs (``head_displacement``, ``head_velocity``) are the face extrapolated
            from the two top masses when True; when False (the system default) they are those of the
            top mass, and whatever bears on the pile does so through the top half segment,
            :meth:`head_contact_stiffness`, in its contact spring (Smith's chain: the neighbour, the
            contact and the pile form one regular chain).

        Returns
        -------
        PileSoilArrays
            The pile, soil and probe arrays.
        """
        seg = self.pile.discretise()
        probes = probe_parameters(self.pile, seg)
        if not extrapolate_head:
            probes[HEAD_EXTRAPOLATION] = 0.0
        return PileSoilArrays(
            np.ascontiguousarray(pile_parameters(self.pile, seg)),
            np.ascontiguousarray(soil_parameters(self.soil, self.pile, seg)),
            probes,
        )

    def stress_factors(self) -> np.ndarray:
        """Spring stiffness / steel area of each pile spring [N/m^3].

        The smaller area of the two segments a spring joins is taken: the stress of spring i is
        this times u_i - u_i+1.

        Returns
        -------
        numpy.ndarray
            (N - 1,) factors [N/m^3].
        """
        seg = self.pile.discretise()
        stiffness = pile_parameters(self.pile, seg)[PILE_STIFFNESS, :-1]
        return np.ascontiguousarray(stiffness / np.minimum(seg.area[:-1], seg.area[1:]))

    def head_contact_stiffness(self) -> float:
        """Stiffness of the top half segment, 2 E A / dx [N/m].

        The pile's side of the contact spring when the head outputs are those of the top mass.

        Returns
        -------
        float
            The stiffness [N/m].
        """
        seg = self.pile.discretise()
        return float(2.0 * seg.youngs_modulus[0] * seg.area[0] / seg.length[0])


def load_pile_soil(path: str | Path) -> PileSoil:
    """Read a file with a ``[pile]`` table and an optional ``[soil]`` table (nothing else).

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.

    Returns
    -------
    PileSoil
        The pile and its soil.

    Raises
    ------
    InputError
        If the file holds other tables or a key breaks its rule.
    """
    root = Table.from_file(path)
    model = PileSoil.from_tables(root.table("pile"), root.table("soil", required=False))
    root.finish()
    return model


def initial_state(arrays: PileSoilArrays, head_force: float = 0.0,
                  gravity: float = 0.0) -> PileSoilState:
    """State at rest in static equilibrium (:func:`anvilwave.pile.static.static_equilibrium`).

    The energy works start at 0; the strain energy is that of the static state.

    Parameters
    ----------
    arrays : PileSoilArrays
        The kernel parameter arrays.
    head_force : float, default 0.0
        Weight resting on the pile head at t = 0 [N] (hammer/anvil weight).
    gravity : float, default 0.0
        Gravitational acceleration on the pile masses [m/s^2]; use the same value in
        :func:`anvilwave.pile.kernels.pile_step`.

    Returns
    -------
    PileSoilState
        The state at rest.
    """
    u, offset = static_equilibrium(arrays.pile, arrays.soil, head_force, gravity)
    v = np.zeros_like(u)
    energy = np.zeros(ENERGY_SIZE)
    update_energy(arrays.pile, u, v, energy, 0.0)
    return PileSoilState(u, v, offset, energy)


def substeps(h: float, dt_stable: float) -> int:
    """Number of sub-steps so that h / n_sub <= dt_stable.

    Parameters
    ----------
    h : float
        The step [s].
    dt_stable : float
        The stable step of the pile [s].

    Returns
    -------
    int
        Number of sub-steps n_sub (>= 1).
    """
    return max(1, math.ceil(h / dt_stable - 1e-9))
