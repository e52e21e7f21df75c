"""Signal matching physics: the pile below the gauges driven by a measured signal, the match
quality, and the static load test of a pile with its soil springs.

The forward model (:func:`run_prescribed_head`, a numba loop over the record; no Python per
step) is the pile-and-soil model of :mod:`anvilwave.pile.kernels` cut at the gauges: its first
segment
starts at the gauge depth, its chain ends half a segment beyond the end masses (the chain
represents the full length below the gauges) and the gauge section is a massless face joined
to the top mass by the top half segment, a spring of stiffness k_h = 2 E A / dx (the contact of
Smith's chain, as in the impact engine). One of two signals measured at the gauges drives the
face (Rausche, Goble & Likins 1985; CAPWAP's two options):

* ``IMPOSED_VELOCITY`` (0): the face displacement is the integral of the measured velocity
  (linear between samples); the computed output is the gauge force F = k_h (u_face - u_0).
* ``IMPOSED_WAVE_DOWN`` (1): the pile above the gauges is a semi-infinite rod of impedance Z
  carrying the measured wave down WD, so the face force is F = P + 2 WD - Z v_face (P the force
  at rest, below); the massless face is advanced implicitly (backward Euler: unconditionally
  stable), u' = (u + dt (P + 2 WD' + k_h u_0) / Z) / (1 + dt k_h / Z). The outputs are the
  force and the face velocity, hence the computed wave up.

Between two samples the kernel takes equal sub-steps no longer than ``dt_max`` (the pile's
stable step, :func:`anvilwave.pile.kernels.stable_time_step`, with k_h added on the top mass), each
one
call of :func:`anvilwave.pile.kernels.pile_step` with the face force held. The run starts at rest
in the
static equilibrium of the pile below the gauges under its own weight and the force at rest P on
the face (the hammer and the pile above the gauges: the weights a PDA zeroes its gauges under),
so that the soil springs carry what they carry in the real pile before the blow; the computed
force minus P is what the zeroed gauges read.

Match quality (this implementation's definition, in the structure of CAPWAP's match quality:
absolute differences of the computed and measured wave up summed in four time intervals and
normalised; Rausche, Goble & Likins 1985). With t0 the impact (the foot of the wave down,
:func:`impact_foot`), T = 2L/c and t_r the rise time (t1 - t0, t1 the first peak of the wave
down, :func:`anvilwave.pile.pda.case_method.first_peak_index`):

* I1 = [t0, t0 + T): the wave up before the toe reflection (shaft resistance);
* I2 = [t0 + T, t0 + T + 2 t_r): the toe reflection of the rise (toe resistance and quake);
* I3 = [t0 + T + 2 t_r, t0 + 2T): the rest of the first round trip (unloading, damping);
* I4 = [t0 + 2T, t0 + 3T): the second round trip (rebound and set);

each clipped to the record (an empty interval is dropped),
MQ = sum_k (1 / n_k) sum_{i in I_k} |WU_c(t_i) - WU_m(t_i)| / max WD_m, i.e. the sum over the
intervals of the mean absolute wave-up error relative to the peak wave down (0 for a perfect
match; with imposed velocity WU_c - WU_m = (F_c - F_m) / 2). The least-squares residuals are the
same differences weighted by 1 / (max WD_m sqrt(n_k)).

Static load test (:func:`static_load_test`): the soil springs elastic-perfectly-plastic
(capacity R_u, stiffness R_u / quake, no damping, starting unstressed, no gravity: the load
measured from the pile at rest), the face pushed down in increments; at each settlement the
equilibrium is solved with an active set (springs at capacity carry R_u), as in
:func:`anvilwave.pile.static.static_equilibrium`. Under a monotonic push every spring loads
monotonically, so the plastic set only grows.

References
----------
Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity. ASCE J.
Geotech. Eng. 111(3), 367-383.
Rausche, F., Moses, F., Goble, G.G. (1972). Soil resistance predictions from pile dynamics.
ASCE J. Soil Mech. Found. Div. 98(SM9), 917-937 (the CAPWAP method).
Smith, E.A.L. (1960). Pile driving analysis by the wave equation. ASCE J. Soil Mech. Found.
Div. 86(4), 35-61.
Davisson, M.T. (1972). High capacity piles. Proc. Lecture Series on Innovations in Foundation
Construction, ASCE Illinois Section, Chicago, 81-112.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numba import njit
from scipy.linalg import solve_banded

from anvilwave.pile.kernels import (
    ENERGY_SIZE,
    PILE_STIFFNESS,
    SOIL_CAPACITY,
    SOIL_STIFFNESS,
    pile_step,
    stable_time_step,
)
from anvilwave.pile.pile import PileSpec, Section

IMPOSED_VELOCITY = 0
IMPOSED_WAVE_DOWN = 1
IMPOSED = {"velocity": IMPOSED_VELOCITY, "wave_down": IMPOSED_WAVE_DOWN}
"""Names of the imposed signals and their kernel codes."""

DAVISSON_OFFSET = 0.00381
"""Davisson's (1972) offset, 0.15 in [m]."""


# ---------------------------------------------------------------------------------- the pile
def pile_below_gauges(pile: PileSpec, segment_length: float | None = None) -> PileSpec:
    """The pile from the gauge depth down (sections cut at the gauges), gauges at its head.

    Parameters
    ----------
    pile : PileSpec
        The whole pile.
    segment_length : float, optional
        Segment length of the cut pile [m] (default: the pile's own).

    Returns
    -------
    PileSpec
        The pile below the gauges (gauge depth 0).

    Raises
    ------
    ValueError
        If the gauges are at or below the pile toe.
    """
    sections, top = [], 0.0
    for s in pile.sections:
        bottom = top + s.length
        if bottom > pile.gauge_depth + 1e-12:
            sections.append(replace(s, length=bottom - max(top, pile.gauge_depth)))
        top = bottom
    if not sections:
        raise ValueError("the gauges are at or below the pile toe")
    return PileSpec(tuple(sections),
                    pile.segment_length if segment_length is None else segment_length,
                    0.0, pile.material_damping, pile.material_damping_model)


def sections_above_gauges(pile: PileSpec) -> tuple[Section, ...]:
    """The pile's sections (cut) between the head and the gauges, head first.

    Parameters
    ----------
    pile : PileSpec
        The whole pile.

    Returns
    -------
    tuple of Section
        The sections above the gauges.
    """
    out, top = [], 0.0
    for s in pile.sections:
        if top >= pile.gauge_depth - 1e-12:
            break
        out.append(replace(s, length=min(s.length, pile.gauge_depth - top)))
        top += s.length
    return tuple(out)


def face_stiffness(pile: PileSpec) -> float:
    """Stiffness of the top half segment of a pile, k_h = 2 E A / dx [N/m].

    Parameters
    ----------
    pile : PileSpec
        The pile (its first segment is used).

    Returns
    -------
    float
        k_h [N/m].
    """
    seg = pile.discretise()
    return float(2.0 * seg.youngs_modulus[0] * seg.area[0] / seg.length[0])


def forward_time_step(pile_arrays: np.ndarray, soil_arrays: np.ndarray,
                      head_stiffness: float) -> float:
    """Largest stable sub-step of :func:`run_prescribed_head` [s].

    The pile's stable step with the face spring k_h [N/m] on the top mass (the face taken as
    fixed).

    Parameters
    ----------
    pile_arrays : numpy.ndarray
        Pile parameter array of the kernels.
    soil_arrays : numpy.ndarray
        Soil parameter array of the kernels.
    head_stiffness : float
        k_h [N/m].

    Returns
    -------
    float
        The stable sub-step [s].
    """
    soil = soil_arrays.copy()
    soil[SOIL_STIFFNESS, 0] += head_stiffness
    return float(stable_time_step(pile_arrays, soil))


def face_displacement(time, velocity, start: float = 0.0) -> np.ndarray:
    """Displacement from a velocity record by the trapezoidal rule [m], ``start`` at t[0].

    Parameters
    ----------
    time : array_like
        t [s].
    velocity : array_like
        v [m/s].
    start : float, default 0.0
        Displacement at the first sample [m].

    Returns
    -------
    numpy.ndarray
        Displacement at the samples [m].
    """
    t = np.asarray(time, dtype=float)
    v = np.asarray(velocity, dtype=float)
    return start + np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))))


# ---------------------------------------------------------------------------------- kernel
@njit(cache=True)
def run_prescribed_head(pile, soil, u, v, soil_offset, imposed, time, signal, face_start,
                        head_stiffness, impedance, preload, gravity, dt_max, force_out,
                        velocity_out):
    """Drive the pile below the gauges with a measured signal (module notes).

    The state arrays and the output arrays are written in place.

    Parameters
    ----------
    pile : numpy.ndarray
        Kernel pile parameter array of the pile below the gauges.
    soil : numpy.ndarray
        Kernel soil parameter array of the pile below the gauges.
    u : numpy.ndarray
        Initial displacements (static equilibrium), advanced in place [m].
    v : numpy.ndarray
        Initial velocities, advanced in place [m/s].
    soil_offset : numpy.ndarray
        Initial soil plastic offsets, advanced in place [m].
    imposed : int
        IMPOSED_VELOCITY or IMPOSED_WAVE_DOWN.
    time : numpy.ndarray
        Sample times t_k [s], increasing.
    signal : numpy.ndarray
        Face displacement at t_k [m] (imposed velocity: face_start plus the integral of the
        velocity) or the measured wave down at t_k [N] (imposed wave down).
    face_start : float
        Face displacement at t_0 [m].
    head_stiffness : float
        k_h [N/m].
    impedance : float
        Z of the pile at the gauges [N s/m].
    preload : float
        Force on the face at rest P [N].
    gravity : float
        Gravitational acceleration [m/s^2].
    dt_max : float
        Largest sub-step [s] (:func:`forward_time_step`).
    force_out : numpy.ndarray
        Out: computed face force at t_k, shape (n,) [N] (compression +), includes P.
    velocity_out : numpy.ndarray
        Out: face velocity at t_k, shape (n,) [m/s] (the mean over the sub-step before t_k).

    References
    ----------
    Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity.
    J. Geotech. Eng. 111(3), 367-383. https://doi.org/10.1061/(ASCE)0733-9410(1985)111:3(367)
    """
    n = time.size
    energy = np.zeros(ENERGY_SIZE)
    u_face = face_start
    v_face = 0.0
    for k in range(n):
        force_out[k] = head_stiffness * (u_face - u[0])
        velocity_out[k] = v_face
        if k == n - 1:
            break
        step = time[k + 1] - time[k]
        n_sub = max(1, int(math.ceil(step / dt_max - 1e-9)))
        dt = step / n_sub
        for j in range(n_sub):
            f_head = head_stiffness * (u_face - u[0])
            pile_step(pile, soil, u, v, soil_offset, energy, f_head, gravity, dt, 1)
            w = (j + 1.0) / n_sub
            target = signal[k] + w * (signal[k + 1] - signal[k])
            if imposed == 0:
                new = target
            else:
                new = ((u_face + dt / impedance * (preload + 2.0 * target
                                                   + head_stiffness * u[0]))
                       / (1.0 + dt * head_stiffness / impedance))
            v_face = (new - u_face) / dt
            u_face = new


# ---------------------------------------------------------------------------------- quality
def impact_foot(wave_down_signal, crossing: float = 0.1, foot: float = 0.02) -> int:
    """Index of the impact t0 in a noisy record.

    The last sample at or below ``foot`` of the peak before the signal first reaches
    ``crossing`` of its peak (fractions [-]); noise of a few per cent before the impact does not
    trigger it.

    Parameters
    ----------
    wave_down_signal : array_like
        The wave down WD [N] (or any signal that rises at the impact).
    crossing : float, default 0.1
        Fraction of the peak that marks the rise [-].
    foot : float, default 0.02
        Fraction of the peak that marks the foot [-].

    Returns
    -------
    int
        Index of t0 [-].
    """
    s = np.asarray(wave_down_signal, dtype=float)
    top = float(np.max(s))
    rise = int(np.argmax(s >= crossing * top))
    below = np.nonzero(s[:rise] <= foot * top)[0]
    return int(below[-1]) if below.size else 0


def match_intervals(time, impact_time: float, round_trip: float, rise_time: float
                    ) -> list[tuple[str, np.ndarray]]:
    """The four intervals of the match quality (module notes) as boolean masks over ``time``.

    Empty intervals are left out.

    Parameters
    ----------
    time : array_like
        Sample times [s].
    impact_time : float
        t0 [s].
    round_trip : float
        T = 2L/c [s].
    rise_time : float
        t_r = t1 - t0 [s].

    Returns
    -------
    list of tuple of (str, numpy.ndarray)
        ``[(name, mask)]`` for I1 .. I4.
    """
    t = np.asarray(time, dtype=float)
    toe_end = min(impact_time + round_trip + 2.0 * max(rise_time, 0.0),
                  impact_time + 2.0 * round_trip)
    edges = [("I1_shaft", impact_time, impact_time + round_trip),
             ("I2_toe", impact_time + round_trip, toe_end),
             ("I3_unloading", toe_end, impact_time + 2.0 * round_trip),
             ("I4_second_round_trip", impact_time + 2.0 * round_trip,
              impact_time + 3.0 * round_trip)]
    out = []
    for name, start, end in edges:
        mask = (t >= start) & (t < end)
        if np.any(mask):
            out.append((name, mask))
    return out


def match_quality(computed_wave_up, measured_wave_up, intervals, peak_wave_down: float
                  ) -> tuple[float, dict[str, float]]:
    """Match quality MQ [-] (module notes) and its term per interval.

    Parameters
    ----------
    computed_wave_up : array_like
        WU_c at the samples [N].
    measured_wave_up : array_like
        WU_m at the samples [N].
    intervals : list of tuple of (str, numpy.ndarray)
        From :func:`match_intervals`.
    peak_wave_down : float
        max WD_m [N] (> 0).

    Returns
    -------
    quality : float
        MQ [-].
    terms : dict of str to float
        The term of each interval [-].

    References
    ----------
    Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity.
    J. Geotech. Eng. 111(3), 367-383. https://doi.org/10.1061/(ASCE)0733-9410(1985)111:3(367)
    """
    error = np.abs(np.asarray(computed_wave_up) - np.asarray(measured_wave_up))
    terms = {name: float(np.mean(error[mask]) / peak_wave_down) for name, mask in intervals}
    return float(sum(terms.values())), terms


def match_residuals(computed_wave_up, measured_wave_up, intervals, peak_wave_down: float
                    ) -> np.ndarray:
    """Least-squares residuals (WU_c - WU_m) / (max WD_m sqrt(n_k)) over the intervals [-].

    Parameters
    ----------
    computed_wave_up : array_like
        WU_c at the samples [N].
    measured_wave_up : array_like
        WU_m at the samples [N].
    intervals : list of tuple of (str, numpy.ndarray)
        From :func:`match_intervals`.
    peak_wave_down : float
        max WD_m [N] (> 0).

    Returns
    -------
    numpy.ndarray
        The residuals of all intervals, concatenated [-].
    """
    diff = np.asarray(computed_wave_up) - np.asarray(measured_wave_up)
    parts = [diff[mask] / (peak_wave_down * math.sqrt(np.count_nonzero(mask)))
             for _, mask in intervals]
    return np.concatenate(parts)


# ---------------------------------------------------------------------------------- static test
def static_load_test(pile_arrays: np.ndarray, soil_arrays: np.ndarray, head_stiffness: float,
                     settlements) -> np.ndarray:
    """Load on the face [N] at each face settlement of a quasi-static push (module notes).

    Parameters
    ----------
    pile_arrays : numpy.ndarray
        Kernel pile parameter array.
    soil_arrays : numpy.ndarray
        Kernel soil parameter array (capacity and stiffness rows used).
    head_stiffness : float
        k_h between the face and the top mass [N/m].
    settlements : array_like
        Face settlements [m], increasing from 0.

    Returns
    -------
    numpy.ndarray
        Load on the face at each settlement [N].
    """
    n = pile_arrays.shape[1]
    k = pile_arrays[PILE_STIFFNESS, :-1]
    k_soil = soil_arrays[SOIL_STIFFNESS]
    capacity = soil_arrays[SOIL_CAPACITY]
    plastic = k_soil <= 0.0  # springs without soil never carry load
    loads = np.zeros(len(settlements))
    for m, s in enumerate(np.asarray(settlements, dtype=float)):
        for _ in range(n + 2):
            ks = np.where(plastic, 0.0, k_soil)
            fixed = np.where(plastic & (k_soil > 0.0), capacity, 0.0)
            diag = np.zeros(n)
            diag[:-1] += k
            diag[1:] += k
            diag += ks[:n]
            diag[-1] += ks[n]
            diag[0] += head_stiffness
            rhs = -fixed[:n]
            rhs[-1] -= fixed[n]
            rhs[0] += head_stiffness * s
            bands = np.zeros((3, n))
            bands[0, 1:] = -k
            bands[1] = diag
            bands[2, :-1] = -k
            u = solve_banded((1, 1), bands, rhs)
            force = k_soil * np.append(u, u[-1])
            newly = (~plastic) & (force > capacity * (1.0 + 1e-12))
            if not newly.any():
                break
            plastic |= newly
        loads[m] = head_stiffness * (s - u[0])
    return loads


def davisson_1972_offset_limit(load, length: float, area: float, elastic_modulus: float,
                               diameter: float):
    """Davisson's (1972) failure line: settlement Q L / (A E) + 0.15 in + D / 120 [m].

    Parameters
    ----------
    load : float or array_like
        Q [N].
    length : float
        Pile length L [m].
    area : float
        A [m^2].
    elastic_modulus : float
        E [Pa].
    diameter : float
        Pile toe diameter D [m].

    Returns
    -------
    numpy.ndarray
        The settlement on the failure line [m].

    References
    ----------
    Davisson, M.T. (1972). High capacity piles. Proc. Lecture Series on Innovations in
    Foundation Construction, ASCE Illinois Section, Chicago, 81-112.
    """
    return (np.asarray(load) * length / (area * elastic_modulus) + DAVISSON_OFFSET
            + diameter / 120.0)


def davisson_capacity(settlements, loads, length: float, area: float, elastic_modulus: float,
                      diameter: float) -> float:
    """Load where a load-settlement curve first reaches Davisson's line [N] (NaN if never).

    Linear interpolation between the points.

    Parameters
    ----------
    settlements : array_like
        Settlements of the curve [m].
    loads : array_like
        Loads of the curve [N].
    length : float
        Pile length L [m].
    area : float
        A [m^2].
    elastic_modulus : float
        E [Pa].
    diameter : float
        Pile toe diameter D [m].

    Returns
    -------
    float
        The Davisson capacity [N], NaN if the line is never reached.

    References
    ----------
    Davisson, M.T. (1972). High capacity piles. Proc. Lecture Series on Innovations in
    Foundation Construction, ASCE Illinois Section, Chicago, 81-112.
    """
    s = np.asarray(settlements, dtype=float)
    q = np.asarray(loads, dtype=float)
    gap = s - davisson_1972_offset_limit(q, length, area, elastic_modulus, diameter)
    above = np.nonzero(gap >= 0.0)[0]
    if above.size == 0:
        return math.nan
    i = int(above[0])
    if i == 0:
        return float(q[0])
    w = -gap[i - 1] / (gap[i] - gap[i - 1])
    return float(q[i - 1] + w * (q[i] - q[i - 1]))


__all__ = [
    "DAVISSON_OFFSET", "IMPOSED", "IMPOSED_VELOCITY", "IMPOSED_WAVE_DOWN", "davisson_capacity",
    "davisson_1972_offset_limit", "face_displacement", "face_stiffness", "forward_time_step",
    "impact_foot", "match_intervals", "match_quality", "match_residuals", "pile_below_gauges",
    "run_prescribed_head", "sections_above_gauges", "static_load_test",
]
