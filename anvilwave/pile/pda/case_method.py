"""PDA analysis of gauge records: the Case method (RTL, RSP, RMX), transferred energy (EMX),
maximum force and stresses (FMX, CSX, TSX) and the BTA integrity factor.

Signs follow the project conventions: force positive in compression, velocity positive downward,
time t from the record's start. The gauges sit at the top of a pile of uniform impedance
Z = E A / c over the length L below them (t2 = t1 + 2L/c is when a wave leaving the gauges at t1
is back after reflection at the toe).

Wave decomposition (d'Alembert; Rausche, Goble & Likins 1985): at the gauges
F = WD + WU and Z v = WD - WU, so WD = (F + Z v)/2 is the wave travelling down and
WU = (F - Z v)/2 the wave travelling up.

t1 (:func:`first_peak_index`): the time of the first peak of Z v (``t1_signal="velocity"``, the
default: the impact peak, as the Case method is commonly applied) or of F
(``t1_signal="force"``). The first peak is the first local maximum whose prominence
(``scipy.signal.find_peaks``) is at least ``peak_prominence`` (default 0.1) of the signal's
maximum, so that noise ripples on the rise are not taken; if there is none, the global
maximum. t1 is a sample time (no interpolation between samples); t2 = t1 + 2L/c is
interpolated linearly.

Case method (Goble, Likins & Rausche 1975; Rausche, Goble & Likins 1985):
* RTL = WD(t1) + WU(t2), the total soil resistance;
* RSP(Jc) = (1 - Jc)/2 (F1 + Z v1) + (1 + Jc)/2 (F2 - Z v2) = RTL - Jc (2 WD(t1) - RTL), the
  static resistance after subtracting a viscous toe damping Jc Z v_toe (Jc the Case damping
  factor: clean sand 0.10-0.15, silty sand 0.15-0.25, silt 0.25-0.40, silty clay 0.40-0.70,
  clay 0.70-1.00);
* RMX = the largest RSP(Jc) as t1 is moved later, sample by sample, from the first peak over a
  window of ``rmx_window`` [s] (default one wave round trip 2L/c; a choice of this
  implementation, set it to match another convention), limited to the record (t1 + 2L/c must
  stay inside it).

EMX = max over t of the running integral of F v dt (trapezoidal rule), the energy transferred
past the gauges (ENTHRU). FMX = max F, CSX = FMX / A.

TSX, the largest tension stress below the gauges (:func:`max_tension_along_pile`): the pile
between the gauges and the toe is taken uniform and soil-free as far as the waves are concerned,
so that the measured waves travel unchanged: the force at depth x below the gauges at time t is
F(x, t) = WD(t - x/c) + WU(t + x/c) (the wave down that passed the gauges x/c earlier plus the
wave up that will reach them x/c later). TSX is the largest -F(x, t) / A over depths x in
[0, L] (a grid of spacing no more than c dt) and over the times at which both waves are
recorded; 0 when there is no tension. The estimate is exact on a soil-free uniform pile. Shaft
resistance that is active between the gauges and x makes the true force at x more tensile
than F(x, t) by up to that resistance (its upward compression wave is in the measured WU but
not yet in the wave up at x, and its downward tension wave is not in the measured WD), so TSX
underestimates the tension below soil that is active during the tension wave; in easy driving,
where tension matters, the activated shaft resistance is small.

BTA (Rausche & Goble 1979): an impedance change from Z to beta Z at depth x reflects the wave
down with the force ratio r = (beta - 1)/(beta + 1), arriving at the gauges 2x/c later. With
t0 the start of the impact (the last sample before t1 where WD <= ``onset_fraction`` WD(t1),
default 0: the foot of the rise), the reflection of the rise t0 -> t1 arrives between
tr = t0 + 2x/c and tx = t1 + 2x/c. Taking the resistance above x as R_x = 2 WU(tr) (its upward
wave, in the wave up before the reflection) and the wave reaching x as WD(t1) - R_x/2 gives
alpha = (WU(tr) - WU(tx)) / (WD(t1) - WU(tr)), beta = (1 - alpha)/(1 + alpha) (Rausche & Goble
1979). beta(x) is evaluated for every sample tx with t1 + (t1 - t0) <= tx < t0 + 2L/c - 4 sigma
- dt (after the reflection of a change one rise length below the gauges; before the toe
reflection reaches back through the filter of standard deviation sigma, truncated at 4 sigma),
i.e. x = c (tx - t1)/2 below the gauges; BTA = min(1, min beta(x)) at the depth of the minimum
(BTA = 1 with no depth when min beta is within 1e-9 of 1, i.e. round-off). The wave up is
low-passed first (:func:`bta_lowpass`: a Gaussian, -3 dB at :data:`BTA_CUTOFF` = 2 kHz, no
overshoot, so a step reflection keeps its height), as PDA software filters before BTA:
unfiltered, the minimum over the samples reads the gauges' noise as impedance drops (2 % noise
gave 0.79 on the shipped intact synthetic record, 0.97 filtered).
Classes: 1.0 uniform, 0.8-1.0 slightly damaged, 0.6-0.8 damaged, < 0.6 broken.

References
----------
Goble, G.G., Likins, G.E., Rausche, F. (1975). Bearing capacity of piles from dynamic
measurements. Final report to the Ohio Department of Transportation, Case Western Reserve
University, Cleveland.
Rausche, F., Goble, G.G. (1979). Determination of pile damage by top measurements. In: Behavior
of Deep Foundations, ASTM STP 670, ASTM, Philadelphia.
Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity. ASCE J.
Geotech. Eng. 111(3), 367-383.
ASTM D4945-17. Standard test method for high-strain dynamic testing of deep foundations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d
from scipy.signal import find_peaks

BTA_CUTOFF = 2000.0
"""Cut-off of the low-pass filter of the waves for BTA [Hz] (module notes)."""

T1_SIGNALS = ("velocity", "force")
"""Signals whose first peak can define t1."""

_BETA_ROUND_OFF = 1e-9  # beta closer to 1 than this is a uniform pile (floating-point noise)


# ---------------------------------------------------------------------------------- formulas
def pile_impedance(elastic_modulus, area, wave_speed):
    """Pile impedance Z = E A / c [N s/m].

    Parameters
    ----------
    elastic_modulus : float or array_like
        E [Pa].
    area : float or array_like
        A, steel cross-section [m^2].
    wave_speed : float or array_like
        c [m/s].

    Returns
    -------
    float or numpy.ndarray
        Impedance Z [N s/m].
    """
    return elastic_modulus * area / wave_speed


def wave_down(force, velocity, impedance):
    """Wave travelling down WD = (F + Z v)/2 [N] (Rausche, Goble & Likins 1985).

    Parameters
    ----------
    force : float or array_like
        F [N], compression positive.
    velocity : float or array_like
        v [m/s], downward positive.
    impedance : float
        Z [N s/m].

    Returns
    -------
    float or numpy.ndarray
        Wave down WD [N].
    """
    return 0.5 * (np.asarray(force) + impedance * np.asarray(velocity))


def wave_up(force, velocity, impedance):
    """Wave travelling up WU = (F - Z v)/2 [N] (Rausche, Goble & Likins 1985).

    Parameters
    ----------
    force : float or array_like
        F [N], compression positive.
    velocity : float or array_like
        v [m/s], downward positive.
    impedance : float
        Z [N s/m].

    Returns
    -------
    float or numpy.ndarray
        Wave up WU [N].
    """
    return 0.5 * (np.asarray(force) - impedance * np.asarray(velocity))


def rausche_goble_likins_1985_total_resistance(wave_down_t1, wave_up_t2):
    """Case method total resistance RTL = WD(t1) + WU(t2) [N].

    Parameters
    ----------
    wave_down_t1 : float or array_like
        WD at t1 [N].
    wave_up_t2 : float or array_like
        WU at t2 = t1 + 2L/c [N].

    Returns
    -------
    float or numpy.ndarray
        Total resistance RTL [N].
    """
    return wave_down_t1 + wave_up_t2


def rausche_goble_likins_1985_static_resistance(force_t1, velocity_t1, force_t2, velocity_t2,
                                                impedance, case_damping):
    """Case method static resistance RSP [N].

    RSP = (1 - Jc)/2 (F1 + Z v1) + (1 + Jc)/2 (F2 - Z v2).

    Parameters
    ----------
    force_t1 : float or array_like
        F at t1 [N].
    velocity_t1 : float or array_like
        v at t1 [m/s].
    force_t2 : float or array_like
        F at t2 = t1 + 2L/c [N].
    velocity_t2 : float or array_like
        v at t2 [m/s].
    impedance : float
        Z [N s/m].
    case_damping : float
        Jc [-].

    Returns
    -------
    float or numpy.ndarray
        Static resistance RSP [N].
    """
    return (0.5 * (1.0 - case_damping) * (force_t1 + impedance * velocity_t1)
            + 0.5 * (1.0 + case_damping) * (force_t2 - impedance * velocity_t2))


def rausche_goble_1979_beta(wave_down_t1, wave_up_tr, wave_up_tx):
    """Impedance ratio beta = Z_below / Z_above at a change (Rausche & Goble 1979) [-].

    alpha = (WU(tr) - WU(tx)) / (WD(t1) - WU(tr)), beta = (1 - alpha)/(1 + alpha).

    Parameters
    ----------
    wave_down_t1 : float or array_like
        WD at t1 [N].
    wave_up_tr : float or array_like
        WU at tr = t0 + 2x/c, the reflection of the impact start [N].
    wave_up_tx : float or array_like
        WU at tx = t1 + 2x/c, the reflection of the impact peak [N].

    Returns
    -------
    float or numpy.ndarray
        Impedance ratio beta [-].
    """
    alpha = (wave_up_tr - wave_up_tx) / (wave_down_t1 - wave_up_tr)
    return (1.0 - alpha) / (1.0 + alpha)


def transferred_energy(time, force, velocity):
    """Running integral of F v dt from the record start (trapezoidal rule) [J].

    Parameters
    ----------
    time : array_like
        t [s], increasing.
    force : array_like
        F [N].
    velocity : array_like
        v [m/s].

    Returns
    -------
    numpy.ndarray
        Transferred energy at each sample [J], 0 at the first.
    """
    t = np.asarray(time, dtype=float)
    p = np.asarray(force, dtype=float) * np.asarray(velocity, dtype=float)
    return np.concatenate(([0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))))


def first_peak_index(signal, peak_prominence: float = 0.1) -> int:
    """Index of the first peak of a signal (see the module notes on t1).

    Parameters
    ----------
    signal : array_like
        Samples [any unit].
    peak_prominence : float, default 0.1
        Smallest prominence of the peak, as a fraction of the signal's maximum [-].

    Returns
    -------
    int
        Index of the first peak.

    Raises
    ------
    ValueError
        If the signal never becomes positive.
    """
    s = np.asarray(signal, dtype=float)
    top = float(np.max(s))
    if not top > 0.0:
        raise ValueError("the signal that defines t1 never becomes positive")
    # padded below the signal at both ends, so that a peak on the first (or last) sample is
    # a peak too (find_peaks alone never returns an endpoint)
    low = float(np.min(s)) - abs(top)
    peaks, _ = find_peaks(np.concatenate(([low], s, [low])), prominence=peak_prominence * top)
    return int(peaks[0]) - 1 if peaks.size else int(np.argmax(s))


def max_tension_along_pile(time, wave_down_gauge, wave_up_gauge, wave_speed: float,
                           length: float) -> tuple[float, float, float]:
    """Largest tension force below the gauges from WD and WU superposed (module notes) [N].

    Parameters
    ----------
    time : array_like
        t [s], increasing.
    wave_down_gauge : array_like
        WD at the gauges [N].
    wave_up_gauge : array_like
        WU at the gauges [N].
    wave_speed : float
        c [m/s].
    length : float
        L below the gauges [m].

    Returns
    -------
    tension : float
        Largest tension force [N] (>= 0).
    depth : float
        Its depth below the gauges [m].
    time : float
        Its time [s].
    """
    t = np.asarray(time, dtype=float)
    wd = np.asarray(wave_down_gauge, dtype=float)
    wu = np.asarray(wave_up_gauge, dtype=float)
    step = float(np.min(np.diff(t)))
    n_depths = max(1, int(np.ceil(length / (wave_speed * step) - 1e-9)))
    best = (0.0, 0.0, float(t[0]))
    for x in np.linspace(0.0, length, n_depths + 1):
        delay = x / wave_speed
        inside = (t - delay >= t[0]) & (t + delay <= t[-1])
        if not np.any(inside):
            continue
        ts = t[inside]
        force = np.interp(ts - delay, t, wd) + np.interp(ts + delay, t, wu)
        k = int(np.argmin(force))
        if -force[k] > best[0]:
            best = (float(-force[k]), float(x), float(ts[k]))
    return best


# ---------------------------------------------------------------------------------- analysis
@dataclass(frozen=True)
class CaseMethodResult:
    """PDA quantities of one blow record.

    Parameters
    ----------
    rtl : float
        Total resistance RTL [N].
    rsp : float
        Static resistance RSP(Jc) at t1 [N].
    rmx : float
        Largest RSP(Jc) as t1 moves later [N].
    emx : float
        Largest transferred energy EMX [J].
    fmx : float
        Largest force at the gauges [N].
    csx : float
        FMX / A [Pa].
    tsx : float
        Largest tension stress below the gauges [Pa] (>= 0).
    bta : float
        Integrity factor beta [-] (<= 1).
    bta_depth : float
        Depth of the BTA minimum below the gauges [m] (NaN when BTA = 1).
    t1 : float
        Time t1 [s].
    t2 : float
        t1 + 2L/c [s].
    rmx_t1 : float
        t1 of RMX [s].
    tsx_depth : float
        Depth of the largest tension below the gauges [m].
    case_damping : float
        Jc [-].
    impedance : float
        Z [N s/m].
    """

    rtl: float
    rsp: float
    rmx: float
    emx: float
    fmx: float
    csx: float
    tsx: float
    bta: float
    bta_depth: float
    t1: float
    t2: float
    rmx_t1: float
    tsx_depth: float
    case_damping: float
    impedance: float

    def summary(self) -> dict[str, float]:
        """The PDA summary, named ``NAME [unit]`` (JSON-ready).

        Returns
        -------
        dict
            ``{NAME [unit]: value}``.
        """
        return {"RTL [N]": self.rtl, "RSP [N]": self.rsp, "RMX [N]": self.rmx,
                "EMX [J]": self.emx, "FMX [N]": self.fmx, "CSX [Pa]": self.csx,
                "TSX [Pa]": self.tsx, "BTA [-]": self.bta}

    def details(self) -> dict[str, float]:
        """Times, depths and parameters behind the summary, named ``name [unit]``.

        Returns
        -------
        dict
            ``{name [unit]: value}``.
        """
        return {"t1 [s]": self.t1, "t2 [s]": self.t2, "rmx_t1 [s]": self.rmx_t1,
                "bta_depth [m]": self.bta_depth, "tsx_depth [m]": self.tsx_depth,
                "case_damping [-]": self.case_damping, "impedance [N s/m]": self.impedance}


def case_method(time, force, velocity, *, area: float, elastic_modulus: float,
                wave_speed: float, length_below_gauges: float, case_damping: float,
                t1_signal: str = "velocity", rmx_window: float | None = None,
                peak_prominence: float = 0.1, onset_fraction: float = 0.0,
                bta_cutoff: float | None = BTA_CUTOFF) -> CaseMethodResult:
    """Case method and PDA summary of a gauge record (see the module notes for each quantity).

    Parameters
    ----------
    time : array_like
        t [s], strictly increasing (uniform sampling not required).
    force : array_like
        Gauge force F [N], compression positive.
    velocity : array_like
        Gauge velocity v [m/s], downward positive.
    area : float
        Steel cross-section A at the gauges [m^2].
    elastic_modulus : float
        E [Pa].
    wave_speed : float
        c [m/s].
    length_below_gauges : float
        L [m].
    case_damping : float
        Jc [-] (>= 0).
    t1_signal : {"velocity", "force"}
        ``"velocity"`` (first peak of Z v) or ``"force"`` (first peak of F).
    rmx_window : float or None, default None
        How far t1 is moved later for RMX [s] (default 2L/c).
    peak_prominence : float, default 0.1
        See :func:`first_peak_index` [-].
    onset_fraction : float, default 0.0
        Impact start for BTA, fraction of WD(t1) [-].
    bta_cutoff : float or None, default BTA_CUTOFF
        Cut-off of the wave up's low-pass filter for BTA [Hz] (None: unfiltered, the
        formula on the samples).

    Returns
    -------
    CaseMethodResult
        The PDA quantities of the record.

    Raises
    ------
    ValueError
        If the arrays are not 1-D of one length (>= 3), contain non-finite values, time
        does not increase strictly, a pile property is not positive, ``case_damping`` or
        ``rmx_window`` is negative, ``t1_signal`` is unknown, the signal never becomes positive or
        the record ends before t1 + 2L/c.
    """
    t = np.asarray(time, dtype=float)
    f = np.asarray(force, dtype=float)
    v = np.asarray(velocity, dtype=float)
    if not (t.ndim == f.ndim == v.ndim == 1 and t.size == f.size == v.size and t.size >= 3):
        raise ValueError("time, force and velocity must be 1D arrays of one length (>= 3)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(f)) and np.all(np.isfinite(v))):
        raise ValueError("the record contains non-finite values")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("time must increase strictly")
    for name, value in (("area", area), ("elastic_modulus", elastic_modulus),
                        ("wave_speed", wave_speed), ("length_below_gauges", length_below_gauges)):
        if not value > 0.0:
            raise ValueError(f"{name} must be positive, got {value!r}")
    if case_damping < 0.0:
        raise ValueError(f"case_damping must not be negative, got {case_damping!r}")
    if t1_signal not in T1_SIGNALS:
        raise ValueError(f"unknown t1_signal {t1_signal!r}; choose one of {T1_SIGNALS}")

    z = pile_impedance(elastic_modulus, area, wave_speed)
    wd, wu = wave_down(f, v, z), wave_up(f, v, z)
    round_trip = 2.0 * length_below_gauges / wave_speed
    i1 = first_peak_index(z * v if t1_signal == "velocity" else f, peak_prominence)
    t1 = float(t[i1])
    t2 = t1 + round_trip
    if t2 > t[-1]:
        raise ValueError(f"the record ends at {t[-1]:g} s, before t1 + 2L/c = {t2:g} s")

    def rsp_at(i):  # RSP with t1 at sample(s) i, F and v interpolated at t2 = t1 + 2L/c
        later = t[i] + round_trip
        return rausche_goble_likins_1985_static_resistance(
            f[i], v[i], np.interp(later, t, f), np.interp(later, t, v), z, case_damping)

    rtl = float(rausche_goble_likins_1985_total_resistance(wd[i1], np.interp(t2, t, wu)))
    rsp = float(rsp_at(i1))

    window = round_trip if rmx_window is None else float(rmx_window)
    if window < 0.0:
        raise ValueError(f"rmx_window must not be negative, got {rmx_window!r}")
    movable = np.nonzero((t >= t1) & (t <= t1 + window) & (t + round_trip <= t[-1]))[0]
    rsp_moved = rsp_at(movable)
    k = int(np.argmax(rsp_moved))
    rmx, rmx_t1 = float(rsp_moved[k]), float(t[movable][k])

    emx = float(np.max(transferred_energy(t, f, v)))
    fmx = float(np.max(f))
    tension, tsx_depth, _ = max_tension_along_pile(t, wd, wu, wave_speed, length_below_gauges)
    bta, bta_depth = _bta(t, wd, wu, i1, round_trip, wave_speed, onset_fraction,
                          bta_cutoff)
    return CaseMethodResult(
        rtl=rtl, rsp=rsp, rmx=rmx, emx=emx, fmx=fmx, csx=fmx / area, tsx=tension / area,
        bta=bta, bta_depth=bta_depth, t1=t1, t2=t2, rmx_t1=rmx_t1, tsx_depth=tsx_depth,
        case_damping=float(case_damping), impedance=float(z))


def bta_lowpass(time, signal, cutoff: float | None = BTA_CUTOFF) -> np.ndarray:
    """``signal`` low-passed for BTA by a Gaussian filter.

    The Gaussian filter has no overshoot, so a step reflection keeps its height, and zero phase;
    its gain is -3 dB at ``cutoff`` (standard deviation sqrt(ln 2) / (2 pi cutoff) [s]), on the
    record's mean sample spacing. The signal is unchanged with ``cutoff`` None or when the filter
    is narrower than a sample.

    Parameters
    ----------
    time : array_like
        t [s], increasing.
    signal : array_like
        Samples [any unit].
    cutoff : float or None, default BTA_CUTOFF
        -3 dB frequency [Hz] (None: no filtering).

    Returns
    -------
    numpy.ndarray
        The filtered signal [unit of ``signal``].
    """
    s = np.asarray(signal, dtype=float)
    if cutoff is None:
        return s
    t = np.asarray(time, dtype=float)
    dt = (t[-1] - t[0]) / (t.size - 1)
    sigma = math.sqrt(math.log(2.0)) / (2.0 * math.pi * cutoff) / dt
    if sigma < 0.5:
        return s
    return gaussian_filter1d(s, sigma, mode="nearest", truncate=4.0)


def _bta(t, wd, wu, i1, round_trip, wave_speed, onset_fraction,
         cutoff) -> tuple[float, float]:
    wu = bta_lowpass(t, wu, cutoff)  # the reflections; WD(t1) and the onset from the record
    below = np.nonzero(wd[:i1] <= onset_fraction * wd[i1])[0]
    i0 = int(below[-1]) if below.size else 0
    rise = t[i1] - t[i0]
    # depths from the rise's length below the gauges (a change closer reflects into the rise
    # itself) to the toe, less the filter's reach (4 sigma and a sample) ahead of the toe
    # reflection
    spread = 0.0
    if cutoff is not None:
        spread = 4.0 * math.sqrt(math.log(2.0)) / (2.0 * math.pi * cutoff) + float(
            (t[-1] - t[0]) / (t.size - 1))
    k = np.nonzero((t > t[i1]) & (t >= t[i1] + rise) & (t < t[i0] + round_trip - spread))[0]
    if k.size == 0:
        return 1.0, float("nan")
    wu_x = wu[k]
    wu_r = np.interp(t[k] - rise, t, wu)
    ok = wd[i1] - wu_r > 0.0  # beta is undefined once the resistance exceeds the wave down
    if not np.any(ok):
        return 1.0, float("nan")
    beta = rausche_goble_1979_beta(wd[i1], wu_r[ok], wu_x[ok])
    j = int(np.argmin(beta))
    if beta[j] >= 1.0 - _BETA_ROUND_OFF:
        return 1.0, float("nan")
    return float(beta[j]), float(0.5 * wave_speed * (t[k[ok][j]] - t[i1]))


__all__ = [
    "T1_SIGNALS", "CaseMethodResult", "case_method", "first_peak_index",
    "max_tension_along_pile", "pile_impedance", "rausche_goble_1979_beta",
    "rausche_goble_likins_1985_static_resistance", "rausche_goble_likins_1985_total_resistance",
    "transferred_energy", "wave_down", "wave_up",
]
