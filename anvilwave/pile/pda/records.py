"""PDA gauge records: reading force/velocity records and converting raw gauge channels.

Gauge record CSV (one blow): a header row, then one row per sample, columns

    time [s], force [N], velocity [m/s]

(``gauge_force [N]`` and ``gauge_velocity [m/s]``, the names of the simulated gauge signals,
are accepted in place of ``force [N]`` and ``velocity [m/s]``; other columns are ignored).

Raw channels CSV: ``time [s]``, two strain channels ``strain_1``, ``strain_2`` in ``[-]`` or
``[microstrain]`` and two accelerometer channels ``acceleration_1``, ``acceleration_2`` in
``[m/s^2]`` or ``[g]`` (g = 9.80665 m/s^2, standard gravity), e.g. ``strain_1 [microstrain]``.
The two gauges of each kind sit on opposite sides of the pile, so that averaging removes
bending. Conversion (:func:`gauge_record_from_raw`):

* strain: each channel times its calibration factor (``strain_calibration``, e.g. the ratio of
  the gauge factor set on the recorder to the actual gauge factor; 1 by default), then
  F = E A (eps_1 + eps_2)/2 (:func:`strain_to_force`);
* acceleration: each channel times its calibration factor, averaged, then integrated to velocity
  with a drift correction (:func:`acceleration_to_velocity`): (1) the mean acceleration of the
  samples before the impact (the accelerometers' offset while the pile is at rest) is removed;
  (2) the result is integrated from the record start with the trapezoidal rule, v = 0 at the
  start (the pile is at rest before the blow); (3) a linear velocity drift that starts at the
  impact is removed so that the velocity at the end of the record equals the final rest value
  ``final_velocity`` (default 0: the pile is at rest again at the end of the record). Step (3)
  removes exactly a constant offset change of the accelerometer at the impact (a "zero shift",
  the usual drift of piezo-resistive and piezo-electric accelerometers under shock).
  The impact is the foot of the force rise: the first sample at which |F| reaches
  ``onset_fraction`` (default 2 %) of its maximum, walked back while |F| keeps decreasing;
  or ``impact_time`` [s] when it is given.

Bad records stop with one :class:`anvilwave.inputs.InputError` ``(file, column, rule)``:
missing file or column, a value that is not a finite number (NaN, inf, text, empty cell), time
not increasing strictly, channels of different lengths (a column that ends before the others),
fewer than 3 samples, a constant (dead) channel, and a clipped channel: a run of at least
``clip_run`` (default 8) consecutive samples exactly equal to the channel's maximum, or to its
minimum, where that extreme is a signal peak (at least a quarter of the peak-to-peak range away
from the channel's median) and not the resting baseline.

References
----------
ASTM D4945-17. Standard test method for high-strain dynamic testing of deep foundations
(force from averaged strains times E A; velocity from integrated acceleration).
Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity. ASCE J.
Geotech. Eng. 111(3), 367-383.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from anvilwave.inputs import InputError

STANDARD_GRAVITY = 9.80665
"""g [m/s^2] for accelerations recorded in [g] (ISO 80000-3)."""

TIME_COLUMN = "time [s]"
FORCE_COLUMNS = ("force [N]", "gauge_force [N]")
VELOCITY_COLUMNS = ("velocity [m/s]", "gauge_velocity [m/s]")
STRAIN_UNITS = {"-": 1.0, "microstrain": 1.0e-6}
"""Strain column units and their factor to [-]."""
ACCELERATION_UNITS = {"m/s^2": 1.0, "g": STANDARD_GRAVITY}
"""Acceleration column units and their factor to [m/s^2]."""

CLIP_RUN = 8
"""Default shortest run of samples pinned at an extreme that marks a channel as clipped [-]."""


@dataclass(frozen=True, eq=False)
class GaugeRecord:
    """Force and velocity at the gauges against time.

    Parameters
    ----------
    time : numpy.ndarray
        t [s], strictly increasing.
    force : numpy.ndarray
        F [N], compression positive.
    velocity : numpy.ndarray
        v [m/s], downward positive.
    source : str, default "<arrays>"
        Where the record came from.
    """

    time: np.ndarray
    force: np.ndarray
    velocity: np.ndarray
    source: str = "<arrays>"


# ---------------------------------------------------------------------------------- conversion
def strain_to_force(strain_1, strain_2, area: float, elastic_modulus: float):
    """Gauge force F = E A (eps_1 + eps_2)/2 [N] (ASTM D4945).

    Parameters
    ----------
    strain_1 : array_like
        Axial strain of the first gauge [-], shortening positive.
    strain_2 : array_like
        Axial strain of the opposite gauge [-], shortening positive.
    area : float
        A, steel cross-section at the gauges [m^2].
    elastic_modulus : float
        E [Pa].

    Returns
    -------
    numpy.ndarray
        Gauge force F [N].

    References
    ----------
    ASTM D4945-17. Standard test method for high-strain dynamic testing of deep foundations.
    """
    return elastic_modulus * area * 0.5 * (np.asarray(strain_1) + np.asarray(strain_2))


def impact_index(force, onset_fraction: float = 0.02) -> int:
    """Index of the foot of the force rise (see the module notes).

    Parameters
    ----------
    force : array_like
        F [N].
    onset_fraction : float, default 0.02
        Threshold as a fraction of max |F| [-].

    Returns
    -------
    int
        Index of the impact sample [-].
    """
    a = np.abs(np.asarray(force, dtype=float))
    i = int(np.argmax(a >= onset_fraction * a.max()))
    while i > 0 and a[i - 1] < a[i]:
        i -= 1
    return i


def acceleration_to_velocity(time, acceleration, impact: int, final_velocity: float = 0.0):
    """Velocity from acceleration with the drift correction of the module notes [m/s].

    Parameters
    ----------
    time : array_like
        t [s], strictly increasing.
    acceleration : array_like
        a [m/s^2], downward positive.
    impact : int
        Index of the impact sample [-]; samples before it are the rest period.
    final_velocity : float, default 0.0
        Velocity at the end of the record [m/s] (0: at rest).

    Returns
    -------
    numpy.ndarray
        Velocity v [m/s].
    """
    t = np.asarray(time, dtype=float)
    a = np.asarray(acceleration, dtype=float)
    if impact > 0:
        a = a - np.mean(a[:impact])
    v = np.concatenate(([0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(t))))
    if t[-1] > t[impact]:
        ramp = np.clip((t - t[impact]) / (t[-1] - t[impact]), 0.0, 1.0)
        v = v - (v[-1] - final_velocity) * ramp
    return v


# ---------------------------------------------------------------------------------- checks
def check_channel(values, source: str, column: str, clip_run: int = CLIP_RUN) -> np.ndarray:
    """A channel as a float array, or the InputError of its first broken rule.

    Parameters
    ----------
    values : array_like
        The channel samples.
    source : str
        The file (or other source) named in the error.
    column : str
        The column named in the error.
    clip_run : int, default CLIP_RUN
        Shortest run of samples pinned at an extreme that marks the channel as clipped [-].

    Returns
    -------
    numpy.ndarray
        The channel as floats.

    Raises
    ------
    InputError
        If a sample is not finite, or the channel is constant or clipped.
    """
    x = np.asarray(values, dtype=float)
    bad = np.nonzero(~np.isfinite(x))[0]
    if bad.size:
        raise InputError(source, column, f"sample {bad[0]}: {x[bad[0]]!r} is not a finite number")
    if x.size and x.max() == x.min():
        raise InputError(source, column, f"is constant ({x[0]:g}): a dead channel")
    if x.size:
        median, quarter = float(np.median(x)), 0.25 * float(x.max() - x.min())
        for extreme, is_peak in ((x.max(), x.max() - median >= quarter),
                                 (x.min(), median - x.min() >= quarter)):
            run = _longest_run(x == extreme)
            if is_peak and run >= clip_run:
                raise InputError(source, column,
                                 f"is clipped: {run} consecutive samples pinned at {extreme:g}")
    return x


def check_gauge_record(time, force, velocity, source: str = "<arrays>",
                       clip_run: int = CLIP_RUN) -> GaugeRecord:
    """Validate arrays as a gauge record (rules of the module notes).

    Parameters
    ----------
    time : array_like
        t [s], strictly increasing.
    force : array_like
        F [N].
    velocity : array_like
        v [m/s].
    source : str, default "<arrays>"
        Where the record came from.
    clip_run : int, default CLIP_RUN
        See the module notes [-].

    Returns
    -------
    GaugeRecord
        The validated record.

    Raises
    ------
    InputError
        At the first broken rule.
    """
    columns = {TIME_COLUMN: time, FORCE_COLUMNS[0]: force, VELOCITY_COLUMNS[0]: velocity}
    checked = _check_columns(columns, source, clip_run)
    return GaugeRecord(checked[TIME_COLUMN], checked[FORCE_COLUMNS[0]],
                       checked[VELOCITY_COLUMNS[0]], str(source))


def _check_columns(columns: dict, source: str, clip_run: int) -> dict[str, np.ndarray]:
    n = len(columns[TIME_COLUMN])
    for name, values in columns.items():
        if len(values) != n:
            raise InputError(source, name, f"has {len(values)} samples but {TIME_COLUMN} has "
                                           f"{n} (channels of different lengths)")
    if n < 3:
        raise InputError(source, TIME_COLUMN, f"needs at least 3 samples, got {n}")
    out = {}
    for name, values in columns.items():
        if name == TIME_COLUMN:
            out[name] = np.asarray(values, dtype=float)
            bad = np.nonzero(~np.isfinite(out[name]))[0]
            if bad.size:
                raise InputError(source, name, f"sample {bad[0]}: {out[name][bad[0]]!r} is not a "
                                               "finite number")
        else:
            out[name] = check_channel(values, source, name, clip_run)
    step = np.diff(out[TIME_COLUMN])
    bad = np.nonzero(step <= 0.0)[0]
    if bad.size:
        i = int(bad[0]) + 1
        raise InputError(source, TIME_COLUMN, f"must increase strictly: sample {i} "
                                              f"({out[TIME_COLUMN][i]:g}) follows "
                                              f"{out[TIME_COLUMN][i - 1]:g}")
    return out


def _longest_run(mask: np.ndarray) -> int:
    if not np.any(mask):
        return 0
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return int(np.max(np.nonzero(edges == -1)[0] - np.nonzero(edges == 1)[0]))


# ---------------------------------------------------------------------------------- files
def read_gauge_record(path: str | Path, clip_run: int = CLIP_RUN) -> GaugeRecord:
    """Read and validate a gauge record CSV (``time [s]``, ``force [N]``, ``velocity [m/s]``).

    Parameters
    ----------
    path : str or Path
        The CSV file.
    clip_run : int, default CLIP_RUN
        See the module notes [-].

    Returns
    -------
    GaugeRecord
        The validated record.

    Raises
    ------
    InputError
        At the first broken rule.
    """
    header, columns = _read_csv(path)
    names = {TIME_COLUMN: TIME_COLUMN,
             "force": _pick(path, header, FORCE_COLUMNS),
             "velocity": _pick(path, header, VELOCITY_COLUMNS)}
    data = _columns(path, header, columns, list(names.values()))
    checked = _check_columns(data, str(path), clip_run)
    return GaugeRecord(checked[TIME_COLUMN], checked[names["force"]],
                       checked[names["velocity"]], str(path))


@dataclass(frozen=True, eq=False)
class RawChannels:
    """Raw gauge channels in SI units (before calibration factors).

    Parameters
    ----------
    time : numpy.ndarray
        t [s].
    strain : numpy.ndarray
        Strains of the two gauges, shape (n, 2) [-].
    acceleration : numpy.ndarray
        Accelerations of the two accelerometers, shape (n, 2) [m/s^2].
    columns : tuple of str
        The four channel column names as in the file.
    source : str
        The file.
    """

    time: np.ndarray
    strain: np.ndarray
    acceleration: np.ndarray
    columns: tuple[str, str, str, str]
    source: str


def read_raw_channels(path: str | Path, clip_run: int = CLIP_RUN) -> RawChannels:
    """Read and validate a raw channels CSV (module notes), converted to [-] and [m/s^2].

    Parameters
    ----------
    path : str or Path
        The CSV file.
    clip_run : int, default CLIP_RUN
        See the module notes [-].

    Returns
    -------
    RawChannels
        The channels in SI units.

    Raises
    ------
    InputError
        At the first broken rule.
    """
    header, columns = _read_csv(path)
    picked, factors = [], []
    for base, units in (("strain_1", STRAIN_UNITS), ("strain_2", STRAIN_UNITS),
                        ("acceleration_1", ACCELERATION_UNITS),
                        ("acceleration_2", ACCELERATION_UNITS)):
        name = _pick(path, header, tuple(f"{base} [{unit}]" for unit in units))
        picked.append(name)
        factors.append(units[name[len(base) + 2:-1]])
    data = _columns(path, header, columns, [TIME_COLUMN, *picked])
    checked = _check_columns(data, str(path), clip_run)
    scaled = [checked[name] * factor for name, factor in zip(picked, factors, strict=True)]
    return RawChannels(checked[TIME_COLUMN], np.column_stack(scaled[:2]),
                       np.column_stack(scaled[2:]), tuple(picked), str(path))


def gauge_record_from_raw(path: str | Path, *, area: float, elastic_modulus: float,
                          strain_calibration: tuple[float, float] = (1.0, 1.0),
                          acceleration_calibration: tuple[float, float] = (1.0, 1.0),
                          impact_time: float | None = None, final_velocity: float = 0.0,
                          onset_fraction: float = 0.02,
                          clip_run: int = CLIP_RUN) -> GaugeRecord:
    """Force and velocity at the gauges from a raw channels CSV (module notes).

    Parameters
    ----------
    path : str or Path
        The CSV file.
    area : float
        Steel cross-section A at the gauges [m^2].
    elastic_modulus : float
        E [Pa].
    strain_calibration : tuple of float, default (1.0, 1.0)
        Factors on strain_1, strain_2 [-].
    acceleration_calibration : tuple of float, default (1.0, 1.0)
        Factors on acceleration_1, acceleration_2 [-].
    impact_time : float, optional
        Start of the impact [s] (default: detected from the force).
    final_velocity : float, default 0.0
        Velocity at the end of the record [m/s].
    onset_fraction : float, default 0.02
        Impact detection threshold, fraction of max |F| [-].
    clip_run : int, default CLIP_RUN
        See the module notes [-].

    Returns
    -------
    GaugeRecord
        Force and velocity at the gauges.

    Raises
    ------
    ValueError
        If ``area`` or ``elastic_modulus`` is not positive.
    InputError
        At the first broken rule of the file, or an impact time outside the record.

    References
    ----------
    ASTM D4945-17. Standard test method for high-strain dynamic testing of deep foundations.
    """
    if not (area > 0.0 and elastic_modulus > 0.0):
        raise ValueError("area and elastic_modulus must be positive")
    raw = read_raw_channels(path, clip_run)
    strain = raw.strain * np.asarray(strain_calibration, dtype=float)
    acceleration = raw.acceleration * np.asarray(acceleration_calibration, dtype=float)
    force = strain_to_force(strain[:, 0], strain[:, 1], area, elastic_modulus)
    if impact_time is None:
        impact = impact_index(force, onset_fraction)
    else:
        if not raw.time[0] <= impact_time < raw.time[-1]:
            raise InputError(path, TIME_COLUMN, f"the impact time {impact_time:g} s is outside "
                                                "the record")
        impact = int(np.searchsorted(raw.time, impact_time))
    velocity = acceleration_to_velocity(raw.time, acceleration.mean(axis=1), impact,
                                        final_velocity)
    return GaugeRecord(raw.time, force, velocity, str(path))


def _read_csv(path: str | Path) -> tuple[list[str], list[list[str]]]:
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as stream:
            rows = list(csv.reader(stream))
    except FileNotFoundError:
        raise InputError(path, "", "file not found") from None
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise InputError(path, "", f"cannot be read as CSV ({exc})") from None
    while rows and not any(cell.strip() for cell in rows[-1]):
        rows.pop()  # trailing blank lines
    if not rows:
        raise InputError(path, "", "is empty")
    return [cell.strip() for cell in rows[0]], rows[1:]


def _pick(path, header: list[str], choices: tuple[str, ...]) -> str:
    present = [name for name in choices if name in header]
    if len(present) != 1:
        rule = ("is missing" if not present
                else f"is given {len(present)} times ({', '.join(present)})")
        raise InputError(path, choices[0], f"{rule}; the header must have one of "
                                           f"{', '.join(choices)}")
    return present[0]


def _columns(path, header: list[str], rows: list[list[str]], names: list[str]
             ) -> dict[str, np.ndarray]:
    out = {}
    for name in names:
        if name not in header:
            raise InputError(path, name, "column is missing from the header")
        j = header.index(name)
        cells = [row[j].strip() if j < len(row) else "" for row in rows]
        while cells and cells[-1] == "":
            cells.pop()  # a shorter channel: caught as different lengths
        values = np.empty(len(cells))
        for i, cell in enumerate(cells):
            if cell == "":
                raise InputError(path, name, f"line {i + 2}: empty value")
            try:
                values[i] = float(cell)
            except ValueError:
                raise InputError(path, name, f"line {i + 2}: {cell!r} is not a number"
                                 ) from None
            if not math.isfinite(values[i]):
                raise InputError(path, name, f"line {i + 2}: {cell!r} is not a finite number")
        out[name] = values
    return out


__all__ = [
    "ACCELERATION_UNITS", "CLIP_RUN", "FORCE_COLUMNS", "STANDARD_GRAVITY", "STRAIN_UNITS",
    "TIME_COLUMN", "VELOCITY_COLUMNS", "GaugeRecord", "RawChannels", "acceleration_to_velocity",
    "check_channel", "check_gauge_record", "gauge_record_from_raw", "impact_index",
    "read_gauge_record", "read_raw_channels", "strain_to_force",
]
