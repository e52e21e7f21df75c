"""Installation fatigue: DNV-RP-C203 S-N curves, rainflow counting and Miner's sum.

S-N curves (DNV-RP-C203, April 2016 edition: the tables of S-N curves in air, in seawater with
cathodic protection and for free corrosion; the values are typed in :data:`DNV_RP_C203_TABLES`
under the edition key ``"2016"``). For a stress range Δσ the number
of cycles to failure follows from

    log10 N = log10 a - m log10(Δσ (t / t_ref)^k SCF),     Δσ in MPa,

with the two-slope ("bilinear") curves in air (m1 and log a1 for N <= 1e7, m = 5 and log a2
beyond) and in seawater with cathodic protection (m1 and log a1,CP for N <= 1e6, the same m = 5
line as in air beyond), and the single-slope (m = 3) curve for free corrosion. The thickness
correction (t / t_ref)^k applies for t > t_ref only (t_ref = 25 mm, 32 mm for tubular joints).

The October 2024 edition changes the B1, B2, C, C1 and C2 curves. Only the 2016 values are
typed here; a 2024 table is added as another key of :data:`DNV_RP_C203_TABLES` (and, should a
formula change, a ``dnv_rp_c203_2024_...`` function) without touching the 2016 data.

Rainflow counting is ASTM E1049-85 (2011), section 5.4.4, as implemented by the ``rainflow``
package (``rainflow.extract_cycles``); nothing here re-implements the counting rules.

Streaming (an installation is thousands of blows): :class:`RainflowStream` counts a stress
history that arrives block by block (one block per blow) and gives exactly the cycles of the
whole concatenated history, including the cycles that close across blows. Between blocks it
keeps only the ASTM residue (the reversals not yet closed, a short list whose ranges decrease
from the bottom up) and the last sample; of each new block only its turning points are kept. The
counting of each block is done by ``rainflow.extract_cycles`` on ``residue + new turning points
+ last sample``: the cycles it yields while the last sample has not yet been read are exactly
the cycles the whole-sequence count closes at those reversals (the ASTM stack is replayed, and
re-reading the residue closes nothing because its ranges decrease); the count is stopped there,
before the package counts the residue as half cycles. At the end (:meth:`RainflowStream.
residue_cycles`) the residue plus the last sample is handed to ``extract_cycles`` unstopped, which
closes it as half cycles per ASTM 5.4.4. Counting one blow and multiplying by the number of
blows instead loses the cycles that close across blows and underestimates the damage.
The stop relies on ``extract_cycles`` reading its input lazily, one reversal at a time (as the
``rainflow`` 3.x generators do); the streaming tests, which compare with the whole-sequence
count, would catch a version that reads eagerly.

Miner's rule: D = sum_i n_i / N_i (Palmgren 1924; Miner 1945).

References
----------
DNV (2016). DNV-RP-C203 Fatigue design of offshore steel structures. April 2016 edition,
section 2.4 (S-N curves in air, in seawater with cathodic protection, for free corrosion;
thickness effect).
ASTM E1049-85 (reapproved 2011). Standard practices for cycle counting in fatigue analysis,
section 5.4.4 Rainflow counting.
Miner, M.A. (1945). Cumulative damage in fatigue. J. Appl. Mech. 12(3), A159-A164.
Palmgren, A. (1924). Die Lebensdauer von Kugellagern. VDI-Zeitschrift 68, 339-341.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import rainflow

ENVIRONMENTS = ("air", "seawater-cp", "free-corrosion")
"""Environment options: in air, in seawater with cathodic protection, free corrosion."""

REFERENCE_THICKNESS = 0.025
"""t_ref for welded connections other than tubular joints [m] (DNV-RP-C203 2016)."""

REFERENCE_THICKNESS_TUBULAR_JOINT = 0.032
"""t_ref for tubular joints [m] (DNV-RP-C203 2016)."""

_MPA = 1.0e6  # [Pa] per MPa: the tables are in MPa


@dataclass(frozen=True)
class SNCurve:
    """One S-N curve of a DNV-RP-C203 table (stress ranges in MPa inside the formula).

    Parameters
    ----------
    name : str
        Curve name, e.g. ``"D"``.
    m1 : float
        Negative inverse slope of the first segment [-].
    log_a1_air : float
        log10 a1 in air, for N <= 1e7 [-] (a in cycles MPa^m).
    log_a2 : float
        log10 a2 of the m = 5 segment (air for N > 1e7, seawater with CP for N > 1e6) [-].
    fatigue_limit_air : float
        Stress range at N = 1e7 in air, as tabulated [MPa] (a check on the data).
    log_a1_seawater_cp : float
        log10 a1 in seawater with cathodic protection, N <= 1e6 [-].
    log_a_free_corrosion : float
        log10 a of the m = 3 curve for free corrosion [-].
    thickness_exponent : float
        k of the thickness correction [-].

    References
    ----------
    DNV (2016). DNV-RP-C203 Fatigue design of offshore steel structures. April 2016 edition,
    section 2.4.
    """

    name: str
    m1: float
    log_a1_air: float
    log_a2: float
    fatigue_limit_air: float
    log_a1_seawater_cp: float
    log_a_free_corrosion: float
    thickness_exponent: float


M2 = 5.0
"""Negative inverse slope of the high-cycle segment of the two-slope curves [-]."""

M_FREE_CORROSION = 3.0
"""Negative inverse slope of the free-corrosion curves [-]."""

SLOPE_CHANGE_CYCLES = {"air": 1.0e7, "seawater-cp": 1.0e6}
"""Number of cycles at which the two-slope curves change from m1 to m = 5 [-]."""


def _table(rows) -> dict[str, SNCurve]:
    return {row[0]: SNCurve(*row) for row in rows}


DNV_RP_C203_TABLES: dict[str, dict[str, SNCurve]] = {
    # DNV-RP-C203 April 2016: S-N curves in air, in seawater with cathodic protection and for
    # free corrosion; k, the thickness exponent, from the air / seawater tables.
    # name, m1, log a1 air, log a2, limit at 1e7 [MPa], log a1 CP, log a free corr., k
    "2016": _table([
        ("B1", 4.0, 15.117, 17.146, 106.97, 14.917, 12.436, 0.00),
        ("B2", 4.0, 14.885, 16.856, 93.59, 14.685, 12.262, 0.00),
        ("C", 3.0, 12.592, 16.320, 73.10, 12.192, 12.115, 0.05),
        ("C1", 3.0, 12.449, 16.081, 65.50, 12.049, 11.972, 0.10),
        ("C2", 3.0, 12.301, 15.835, 58.48, 11.901, 11.824, 0.15),
        ("D", 3.0, 12.164, 15.606, 52.63, 11.764, 11.687, 0.20),
        ("E", 3.0, 12.010, 15.350, 46.78, 11.610, 11.533, 0.20),
        ("F", 3.0, 11.855, 15.091, 41.52, 11.455, 11.378, 0.25),
        ("F1", 3.0, 11.699, 14.832, 36.84, 11.299, 11.222, 0.25),
        ("F3", 3.0, 11.546, 14.576, 32.75, 11.146, 11.068, 0.25),
        ("G", 3.0, 11.398, 14.330, 29.24, 10.998, 10.921, 0.25),
        ("W1", 3.0, 11.261, 14.101, 26.32, 10.861, 10.784, 0.25),
        ("W2", 3.0, 11.107, 13.845, 23.39, 10.707, 10.630, 0.25),
        ("W3", 3.0, 10.970, 13.617, 21.05, 10.570, 10.493, 0.25),
    ]),
}
"""S-N tables per DNV-RP-C203 edition (key: edition name)."""

EDITIONS = tuple(DNV_RP_C203_TABLES)
"""Available DNV-RP-C203 editions."""


# ---------------------------------------------------------------------------------- S-N curves
def dnv_rp_c203_curve(curve: str, edition: str = "2016") -> SNCurve:
    """The S-N curve ``curve`` (e.g. ``"D"``) of a DNV-RP-C203 ``edition`` (e.g. ``"2016"``).

    Parameters
    ----------
    curve : str
        S-N curve name, e.g. ``"D"`` (see :data:`DNV_RP_C203_TABLES`).
    edition : str, default "2016"
        DNV-RP-C203 edition, one of :data:`EDITIONS`.

    Returns
    -------
    SNCurve
        The tabulated curve.

    Raises
    ------
    ValueError
        If the edition or the curve is unknown.
    """
    if edition not in DNV_RP_C203_TABLES:
        raise ValueError(f"unknown DNV-RP-C203 edition {edition!r}; choose one of {EDITIONS}")
    table = DNV_RP_C203_TABLES[edition]
    if curve not in table:
        raise ValueError(f"unknown S-N curve {curve!r} in DNV-RP-C203 {edition}; choose one of "
                         f"{tuple(table)}")
    return table[curve]


def dnv_rp_c203_2016_thickness_factor(thickness, thickness_exponent: float,
                                      reference_thickness: float = REFERENCE_THICKNESS):
    """Thickness correction (t / t_ref)^k of DNV-RP-C203 (2016) [-].

    Parameters
    ----------
    thickness : float or array_like
        t, plate or wall thickness through which a crack grows [m] (or t_eff, see
        :func:`dnv_rp_c203_2016_effective_thickness`).
    thickness_exponent : float
        k of the S-N curve [-].
    reference_thickness : float, default REFERENCE_THICKNESS
        t_ref [m]: 0.025 for welded connections other than tubular joints, 0.032 for tubular
        joints.

    Returns
    -------
    numpy.ndarray
        The factor (t / t_ref)^k [-]; 1 for t <= t_ref (the correction applies to thicker
        sections only).

    References
    ----------
    DNV (2016). DNV-RP-C203 Fatigue design of offshore steel structures. April 2016 edition,
    section 2.4 (thickness effect).
    """
    t = np.asarray(thickness, dtype=float)
    return (np.maximum(t, reference_thickness) / reference_thickness) ** thickness_exponent


def dnv_rp_c203_2016_effective_thickness(thickness, weld_length):
    """Effective thickness t_eff = min(14 mm + 0.66 L, t) of DNV-RP-C203 (2016) [m].

    For transverse butt welds, cruciform joints and transverse fillet-welded attachments, the
    thickness in the thickness correction is replaced by t_eff.

    Parameters
    ----------
    thickness : float or array_like
        t [m].
    weld_length : float or array_like
        L, the attachment length of the weld detail [m].

    Returns
    -------
    numpy.ndarray
        t_eff [m].

    References
    ----------
    DNV (2016). DNV-RP-C203 Fatigue design of offshore steel structures. April 2016 edition,
    section 2.4 (thickness effect).
    """
    return np.minimum(0.014 + 0.66 * np.asarray(weld_length, dtype=float),
                      np.asarray(thickness, dtype=float))


def dnv_rp_c203_2016_cycles_to_failure(stress_range, curve: str, environment: str, thickness,
                                       scf: float = 1.0, *,
                                       reference_thickness: float = REFERENCE_THICKNESS):
    """Number of cycles to failure N of DNV-RP-C203 (April 2016) [-].

    log10 N = log10 a - m log10(Δσ (t/t_ref)^k SCF) with Δσ in MPa (the S-N relation with the
    thickness correction). In air: m1, log a1 for N <= 1e7, m = 5, log a2 for N > 1e7. In
    seawater with cathodic protection: m1, log a1,CP for N <= 1e6, m = 5 and the same log a2 as
    in air for N > 1e6. Free corrosion: m = 3, one segment, no fatigue limit. The segment is
    chosen from N of the first segment, as the tables state it (so the rounding of the
    tabulated log a leaves a step of at most 2.5e-3 in log N at the slope change).

    Parameters
    ----------
    stress_range : float or array_like
        Δσ, nominal (hot-spot with ``scf``) stress range(s) [Pa]; 0 gives N = inf.
    curve : str
        S-N curve name, e.g. ``"D"`` (see :data:`DNV_RP_C203_TABLES`).
    environment : {"air", "seawater-cp", "free-corrosion"}
        The environment.
    thickness : float or array_like
        t (or t_eff) [m].
    scf : float, default 1.0
        Stress concentration factor [-].
    reference_thickness : float, default REFERENCE_THICKNESS
        t_ref [m] (0.025; 0.032 for tubular joints).

    Returns
    -------
    numpy.ndarray
        Cycles to failure N [-].

    Raises
    ------
    ValueError
        If the curve or environment is unknown, ``scf`` or a thickness is not positive, or a
        stress range is negative or not finite.

    References
    ----------
    DNV (2016). DNV-RP-C203 Fatigue design of offshore steel structures. April 2016 edition,
    section 2.4 (S-N curves in air, in seawater with cathodic protection, for free corrosion;
    thickness effect).
    """
    return _cycles_to_failure(dnv_rp_c203_curve(curve, "2016"), stress_range, environment,
                              thickness, scf, reference_thickness)


def dnv_rp_c203_cycles_to_failure(stress_range, curve: str, environment: str, thickness,
                                  scf: float = 1.0, *, edition: str = "2016",
                                  reference_thickness: float = REFERENCE_THICKNESS):
    """N of DNV-RP-C203 for a named ``edition`` [-].

    Every edition in :data:`DNV_RP_C203_TABLES` is evaluated with the 2016 form of the S-N
    relation (two slopes, thickness correction, SCF); an edition that changes the form itself
    needs its own ``dnv_rp_c203_<edition>_cycles_to_failure`` dispatched here.

    Parameters
    ----------
    stress_range : float or array_like
        Δσ, nominal (hot-spot with ``scf``) stress range(s) [Pa]; 0 gives N = inf.
    curve : str
        S-N curve name, e.g. ``"D"`` (see :data:`DNV_RP_C203_TABLES`).
    environment : {"air", "seawater-cp", "free-corrosion"}
        The environment.
    thickness : float or array_like
        t (or t_eff) [m].
    scf : float, default 1.0
        Stress concentration factor [-].
    edition : str, default "2016"
        One of :data:`EDITIONS`.
    reference_thickness : float, default REFERENCE_THICKNESS
        t_ref [m] (0.025; 0.032 for tubular joints).

    Returns
    -------
    numpy.ndarray
        Cycles to failure N [-].

    See Also
    --------
    dnv_rp_c203_2016_cycles_to_failure : The same parameters.
    """
    return _cycles_to_failure(dnv_rp_c203_curve(curve, edition), stress_range, environment,
                              thickness, scf, reference_thickness)


def _cycles_to_failure(sn: SNCurve, stress_range, environment: str, thickness, scf: float,
                       reference_thickness: float):
    if environment not in ENVIRONMENTS:
        raise ValueError(f"unknown environment {environment!r}; choose one of {ENVIRONMENTS}")
    if scf <= 0.0:
        raise ValueError(f"the stress concentration factor must be positive, got {scf!r}")
    if np.any(np.asarray(thickness) <= 0.0) or reference_thickness <= 0.0:
        raise ValueError("thicknesses must be positive [m]")
    s = np.asarray(stress_range, dtype=float) / _MPA
    if np.any(s < 0.0) or not np.all(np.isfinite(s)):
        raise ValueError("stress ranges must be finite and not negative [Pa]")
    s = s * dnv_rp_c203_2016_thickness_factor(thickness, sn.thickness_exponent,
                                              reference_thickness) * scf
    with np.errstate(divide="ignore"):
        log_s = np.log10(s)  # -inf for a zero range -> N = inf
    if environment == "free-corrosion":
        log_n = sn.log_a_free_corrosion - M_FREE_CORROSION * log_s
    else:
        log_a1 = sn.log_a1_air if environment == "air" else sn.log_a1_seawater_cp
        log_n1 = log_a1 - sn.m1 * log_s
        log_n2 = sn.log_a2 - M2 * log_s
        log_n = np.where(log_n1 <= np.log10(SLOPE_CHANGE_CYCLES[environment]), log_n1, log_n2)
    return 10.0 ** log_n


def sn_curve(curve: str, environment: str, thickness: float, scf: float = 1.0, *,
             edition: str = "2016", reference_thickness: float = REFERENCE_THICKNESS
             ) -> Callable[[np.ndarray], np.ndarray]:
    """A function stress range [Pa] -> cycles to failure [-] with the detail data bound.

    The parameters are checked here, once.

    Parameters
    ----------
    curve : str
        S-N curve name, e.g. ``"D"`` (see :data:`DNV_RP_C203_TABLES`).
    environment : {"air", "seawater-cp", "free-corrosion"}
        The environment.
    thickness : float
        t (or t_eff) [m].
    scf : float, default 1.0
        Stress concentration factor [-].
    edition : str, default "2016"
        One of :data:`EDITIONS`.
    reference_thickness : float, default REFERENCE_THICKNESS
        t_ref [m] (0.025; 0.032 for tubular joints).

    Returns
    -------
    callable
        ``cycles_to_failure(stress_range)``, stress range [Pa] -> N [-].

    See Also
    --------
    dnv_rp_c203_cycles_to_failure : The function bound.
    """
    dnv_rp_c203_cycles_to_failure(1.0e6, curve, environment, thickness, scf, edition=edition,
                                  reference_thickness=reference_thickness)

    def cycles_to_failure(stress_range):
        return dnv_rp_c203_cycles_to_failure(stress_range, curve, environment, thickness, scf,
                                             edition=edition,
                                             reference_thickness=reference_thickness)

    return cycles_to_failure


# ---------------------------------------------------------------------------------- counting
def miner_1945_damage(cycle_counts, cycles_to_failure) -> float:
    """Miner's sum D = sum_i n_i / N_i [-] (Palmgren 1924; Miner 1945).

    Parameters
    ----------
    cycle_counts : array_like
        n_i, counted cycles (0.5 for half cycles) [-].
    cycles_to_failure : array_like
        N_i, cycles to failure at the same stress ranges [-] (inf -> no damage).

    Returns
    -------
    float
        The damage D [-].

    References
    ----------
    Miner, M.A. (1945). Cumulative damage in fatigue. J. Appl. Mech. 12(3), A159-A164.
    https://doi.org/10.1115/1.4009458
    Palmgren, A. (1924). Die Lebensdauer von Kugellagern. VDI-Zeitschrift 68, 339-341.
    """
    n = np.asarray(cycle_counts, dtype=float)
    big_n = np.asarray(cycles_to_failure, dtype=float)
    return float(np.sum(n / big_n))


def rainflow_cycles(stress_history) -> tuple[np.ndarray, np.ndarray]:
    """Rainflow ranges [unit of the history] and counts [-] of a whole history (ASTM E1049-85).

    Uses ``rainflow.extract_cycles``; the last sample is passed twice, which changes nothing
    for the package except that a history of exactly two distinct samples gives its half cycle
    (the package reports no cycle for a two-sample series).

    Parameters
    ----------
    stress_history : array_like
        The history [any unit]; must be finite.

    Returns
    -------
    ranges : numpy.ndarray
        Cycle ranges [unit of the history].
    counts : numpy.ndarray
        Cycle counts, 0.5 or 1 [-].

    References
    ----------
    ASTM E1049-85 (reapproved 2011). Standard practices for cycle counting in fatigue analysis,
    section 5.4.4 Rainflow counting.
    """
    x = _as_history(stress_history)
    if x.size < 2:
        return np.empty(0), np.empty(0)
    cycles = [(rng, count) for rng, _, count, _, _ in rainflow.extract_cycles(np.r_[x, x[-1]])]
    return _as_arrays(cycles)


def rainflow_damage(stress_history, cycles_to_failure: Callable) -> float:
    """Miner's sum of a whole stress history counted by rainflow [-].

    Parameters
    ----------
    stress_history : array_like
        Stress at one section against time [Pa].
    cycles_to_failure : callable
        Function stress range [Pa] -> N [-] (e.g. from :func:`sn_curve`).

    Returns
    -------
    float
        The damage D [-].
    """
    ranges, counts = rainflow_cycles(stress_history)
    if ranges.size == 0:
        return 0.0
    return miner_1945_damage(counts, cycles_to_failure(ranges))


def _as_history(values) -> np.ndarray:
    x = np.asarray(values, dtype=float).ravel()
    if not np.all(np.isfinite(x)):
        raise ValueError("the stress history contains non-finite values")
    return x


def _as_arrays(cycles) -> tuple[np.ndarray, np.ndarray]:
    if not cycles:
        return np.empty(0), np.empty(0)
    arr = np.asarray(cycles, dtype=float)
    return arr[:, 0], arr[:, 1]


def turning_points(last_value: float, direction: float, block: np.ndarray):
    """Confirmed reversals of a block continuing a history (the rule of ``rainflow.reversals``).

    Repeated values are dropped; a point is a reversal where the sign of the change flips. The
    last sample is never confirmed here (the next block decides), exactly as
    ``rainflow.reversals`` treats the interior of one series.

    Parameters
    ----------
    last_value : float
        The last sample of the history so far [any unit].
    direction : float
        Sign of the last non-zero change of the history so far (+1, -1; 0 if none) [-].
    block : numpy.ndarray
        The new samples [same unit].

    Returns
    -------
    reversals : numpy.ndarray
        The confirmed reversals [same unit].
    last_value : float
        The new last value [same unit].
    direction : float
        The new direction [-].
    """
    s = np.concatenate(([last_value], np.asarray(block, dtype=float)))
    s = s[np.r_[True, s[1:] != s[:-1]]]
    if s.size == 1:
        return np.empty(0), float(last_value), float(direction)
    change = np.sign(np.diff(s))
    incoming = np.r_[direction, change[:-1]]
    return s[:-1][incoming * change < 0.0], float(s[-1]), float(change[-1])


class RainflowStream:
    """Rainflow counting (ASTM E1049-85) of one history that arrives block by block.

    ``add(block)`` returns the cycles closed by that block; :meth:`residue_cycles` the half
    cycles (and the cycles the last sample closes) if the history ended now, without changing
    the state. The union equals ``rainflow_cycles`` of the concatenated blocks. Memory: the
    residue (a few reversals) and the last sample.

    Attributes
    ----------
    residue : list of float
        The ASTM residue, the reversals not yet closed [unit of the history].
    last_value : float or None
        The last sample so far (None before the first block) [unit of the history].
    direction : float
        Sign of the last non-zero change so far (0 if none) [-].

    References
    ----------
    ASTM E1049-85 (reapproved 2011). Standard practices for cycle counting in fatigue analysis,
    section 5.4.4 Rainflow counting.
    """

    def __init__(self):
        self.residue: list[float] = []
        self.last_value: float | None = None
        self.direction = 0.0

    def add(self, block) -> tuple[np.ndarray, np.ndarray]:
        """Count a new block [unit of the history].

        Parameters
        ----------
        block : array_like
            The new samples [unit of the history].

        Returns
        -------
        ranges : numpy.ndarray
            Ranges of the cycles the block closes [unit of the history].
        counts : numpy.ndarray
            Their counts [-].
        """
        x = _as_history(block)
        if x.size == 0:
            return _as_arrays([])
        if self.last_value is None:
            self.residue = [float(x[0])]
            self.last_value = float(x[0])
            x = x[1:]
        reversals, self.last_value, self.direction = turning_points(
            self.last_value, self.direction, x)
        if reversals.size == 0:
            return _as_arrays([])
        series = self.residue + reversals.tolist() + [self.last_value]
        stopped = False

        def source():
            nonlocal stopped
            yield from series
            stopped = True  # the package asks beyond the last sample: stop before the residue

        cycles, removed = [], set()
        for rng, _, count, i_start, i_end in rainflow.extract_cycles(source()):
            if stopped:
                break
            cycles.append((rng, count))
            removed.add(i_start)  # a half cycle drops the starting point ...
            if count == 1.0:
                removed.add(i_end)  # ... a full cycle drops its two reversals
        self.residue = [series[i] for i in range(len(series) - 1) if i not in removed]
        return _as_arrays(cycles)

    def residue_cycles(self) -> tuple[np.ndarray, np.ndarray]:
        """Cycles of the residue if the history ended now (ASTM: half cycles); state unchanged.

        Returns
        -------
        ranges : numpy.ndarray
            Ranges [unit of the history].
        counts : numpy.ndarray
            Counts [-].
        """
        if self.last_value is None:
            return _as_arrays([])
        series = list(self.residue)
        if self.direction != 0.0:
            series += [self.last_value, self.last_value]  # see rainflow_cycles on the repeat
        cycles = [(rng, count) for rng, _, count, _, _ in rainflow.extract_cycles(series)]
        return _as_arrays(cycles)


class StreamingMinerDamage:
    """Miner damage of several sections whose stress histories arrive blow by blow.

    ``add_blow(stress)`` takes the stress of one blow, shape (n_samples, n_sections) [Pa]
    (a 1D array for a single section). :meth:`damage` is the damage of the whole sequence so far
    with the open residue closed as half cycles (ASTM), :attr:`closed_damage` without it;
    :attr:`closed_cycles` counts the closed cycles [-] and :attr:`blows` the blows added [-].

    Parameters
    ----------
    cycles_to_failure : callable or sequence of callable
        One function stress range [Pa] -> N [-] for all sections, or one per section (e.g.
        :func:`sn_curve` with each section's curve, thickness and SCF).
    n_sections : int, optional
        Number of sections [-] (taken from ``cycles_to_failure`` if it is a sequence).

    Attributes
    ----------
    closed_damage : numpy.ndarray
        Miner's sum of the closed cycles per section [-].
    closed_cycles : numpy.ndarray
        Number of closed cycles per section [-].
    blows : int
        Number of blows added [-].
    n_sections : int
        Number of sections [-].

    Raises
    ------
    ValueError
        If ``n_sections`` is missing (or < 1) with a single function, or differs from the number
        of functions.
    """

    def __init__(self, cycles_to_failure: Callable | Sequence[Callable],
                 n_sections: int | None = None):
        if callable(cycles_to_failure):
            if n_sections is None or n_sections < 1:
                raise ValueError("n_sections must be given (>= 1) with a single S-N function")
            functions = [cycles_to_failure] * n_sections
        else:
            functions = list(cycles_to_failure)
            if n_sections is not None and n_sections != len(functions):
                raise ValueError("n_sections differs from the number of S-N functions")
        self.cycles_to_failure = functions
        self.streams = [RainflowStream() for _ in functions]
        self.closed_damage = np.zeros(len(functions))
        self.closed_cycles = np.zeros(len(functions))
        self.blows = 0

    @property
    def n_sections(self) -> int:
        """Number of sections [-]."""
        return len(self.streams)

    def add_blow(self, stress) -> None:
        """Count one blow: stress [Pa], shape (n_samples, n_sections) or (n_samples,).

        Parameters
        ----------
        stress : array_like
            The stress of the blow at each section [Pa].

        Raises
        ------
        ValueError
            If the shape does not match the number of sections.
        """
        s = np.asarray(stress, dtype=float)
        if s.ndim == 1:
            s = s[:, None]
        if s.ndim != 2 or s.shape[1] != self.n_sections:
            raise ValueError(f"a blow's stress must have shape (n_samples, {self.n_sections}), "
                             f"got {np.shape(stress)}")
        for j, stream in enumerate(self.streams):
            ranges, counts = stream.add(s[:, j])
            if ranges.size:
                self.closed_damage[j] += miner_1945_damage(
                    counts, self.cycles_to_failure[j](ranges))
                self.closed_cycles[j] += counts.sum()
        self.blows += 1

    def damage(self) -> np.ndarray:
        """Miner's sum per section [-], the residue counted as half cycles (history ends now).

        Returns
        -------
        numpy.ndarray
            Damage per section [-].
        """
        total = self.closed_damage.copy()
        for j, stream in enumerate(self.streams):
            ranges, counts = stream.residue_cycles()
            if ranges.size:
                total[j] += miner_1945_damage(counts, self.cycles_to_failure[j](ranges))
        return total


__all__ = [
    "DNV_RP_C203_TABLES", "EDITIONS", "ENVIRONMENTS", "M2", "M_FREE_CORROSION",
    "REFERENCE_THICKNESS", "REFERENCE_THICKNESS_TUBULAR_JOINT", "SLOPE_CHANGE_CYCLES",
    "RainflowStream", "SNCurve", "StreamingMinerDamage", "dnv_rp_c203_2016_cycles_to_failure",
    "dnv_rp_c203_2016_effective_thickness", "dnv_rp_c203_2016_thickness_factor",
    "dnv_rp_c203_curve", "dnv_rp_c203_cycles_to_failure", "miner_1945_damage",
    "rainflow_cycles", "rainflow_damage", "sn_curve", "turning_points",
]
