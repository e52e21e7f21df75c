"""Force spectra for noise studies: Fourier amplitude, energy spectral density, one-third-octave
band energies and levels.

Conventions. The Fourier transform of a force pulse F(t) [N] is F(f) = integral F(t)
e^(-i 2 pi f t) dt [N s = N/Hz]; for a record sampled at t_n = n dt it is approximated by
dt x DFT(F_n) of the record zero-padded to ``n_fft`` samples (padding adds frequency points, the
spacing becomes 1 / (n_fft dt); it adds no information). The energy of the pulse is
E = integral F(t)^2 dt = integral over all f of |F(f)|^2 df [N^2 s] (Parseval). For a real force
|F(-f)| = |F(f)|, so both sides of the spectrum are folded into the one-sided energy spectral
density ESD(f) = 2 |F(f)|^2 [N^2 s/Hz], f >= 0 (the factor 2 also at f = 0 and at the Nyquist
frequency, so that the trapezoidal integral of the sampled ESD over [0, f_Nyquist] equals
sum F_n^2 dt exactly, the discrete Parseval identity).

Band energy = integral of ESD over the band edges [N^2 s]: the ESD is taken piecewise linear
between its frequency points and integrated exactly between the edges, partial bins included.
The padding is chosen so that the lowest requested band spans at least ``bins_per_band``
frequency steps. Level L = 10 log10(E / 1 N^2 s) [dB re 1 N^2 s].

One-third-octave bands (IEC 61260-1:2014, base-ten system, G = 10^(3/10), b = 3): band number
n has the exact mid-band frequency f_m = 1000 x 10^(n/10) Hz and the edges f_m x 10^(+-1/20)
(n = 0 is the 1 kHz band, n = -20 the 10 Hz band, n = 13 the 20 kHz band).

Valid band (:func:`valid_band`). Upper limit: sampling at 1/dt folds the spectrum above the
Nyquist frequency back onto the band (aliasing of the pulse onset, whose spectrum decays only as
1/f for a force jump and 1/f^2 for a kink); band levels above about a tenth of the sampling rate
are not trustworthy (the check pulse F0 (e^-at - e^-bt), a kink at the onset, is off by
0.28 dB in the band centred at a tenth of the sampling rate, 0.05 dB at 1/25 and 0.003 dB at
1/100: the error grows as (f dt)^2). Lower limit: 1 / T, the lowest frequency one full
period of which fits in the record of duration T; below it the spectrum depends on where the
record was cut, unless the force has returned to zero inside the record (then the bands below
are exact too, but the helper cannot know it). State the valid band with every spectrum.

References
----------
IEC 61260-1:2014. Electroacoustics - Octave-band and fractional-octave-band filters - Part 1:
Specifications. (Base-ten system: exact mid-band and band-edge frequencies.)
Parseval / Rayleigh energy theorem, e.g. Bracewell, R.N. (2000). The Fourier Transform and Its
Applications, 3rd ed., McGraw-Hill.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

REFERENCE_ENERGY = 1.0
"""Reference of the band levels [N^2 s] (levels in dB re 1 N^2 s)."""

MAX_FFT_SIZE = 2 ** 25
"""Largest zero-padded FFT length accepted [-] (about 0.5 GB of work arrays)."""

THIRD_OCTAVE_HALF_WIDTH = 10.0 ** (1.0 / 20.0)
"""Ratio of the upper edge to the mid-band frequency of a one-third-octave band [-]."""


# ---------------------------------------------------------------------------------- bands
def iec_61260_1_2014_band_centre(band_number):
    """Exact mid-band frequency f_m = 1000 x 10^(n/10) of one-third-octave band n [Hz].

    IEC 61260-1:2014, base-ten system, b = 3; n = 0 is 1 kHz.

    Parameters
    ----------
    band_number : int or array_like
        n, integer band index [-] (scalar or array).

    Returns
    -------
    numpy.ndarray
        Mid-band frequency f_m [Hz].

    References
    ----------
    IEC 61260-1:2014. Electroacoustics - Octave-band and fractional-octave-band filters - Part 1:
    Specifications.
    """
    return 1000.0 * 10.0 ** (np.asarray(band_number, dtype=float) / 10.0)


def iec_61260_1_2014_band_edges(band_number):
    """Lower and upper edge frequencies f_m x 10^(-1/20), f_m x 10^(+1/20) of band n [Hz].

    IEC 61260-1:2014, base-ten system, b = 3.

    Parameters
    ----------
    band_number : int or array_like
        n, integer band index [-] (scalar or array).

    Returns
    -------
    lower : numpy.ndarray
        Lower edge frequency [Hz].
    upper : numpy.ndarray
        Upper edge frequency [Hz].

    References
    ----------
    IEC 61260-1:2014. Electroacoustics - Octave-band and fractional-octave-band filters - Part 1:
    Specifications.
    """
    centre = iec_61260_1_2014_band_centre(band_number)
    return centre / THIRD_OCTAVE_HALF_WIDTH, centre * THIRD_OCTAVE_HALF_WIDTH


def band_numbers_between(lowest_frequency: float, highest_frequency: float) -> np.ndarray:
    """Numbers of the one-third-octave bands lying wholly within [lowest, highest] [Hz].

    Parameters
    ----------
    lowest_frequency : float
        Lowest frequency [Hz].
    highest_frequency : float
        Highest frequency [Hz].

    Returns
    -------
    numpy.ndarray
        The band numbers n [-].

    Raises
    ------
    ValueError
        Unless 0 < lowest_frequency < highest_frequency.
    """
    if not 0.0 < lowest_frequency < highest_frequency:
        raise ValueError("need 0 < lowest_frequency < highest_frequency [Hz]")
    first = math.ceil(10.0 * math.log10(lowest_frequency * THIRD_OCTAVE_HALF_WIDTH / 1000.0)
                      - 1e-9)
    last = math.floor(10.0 * math.log10(highest_frequency / THIRD_OCTAVE_HALF_WIDTH / 1000.0)
                      + 1e-9)
    return np.arange(first, last + 1)


def valid_band(time_step: float, duration: float, *, upper_fraction: float = 0.1,
               min_periods: float = 1.0) -> tuple[float, float]:
    """Frequency range in which the spectrum of a sampled record is trustworthy [Hz].

    Parameters
    ----------
    time_step : float
        Sampling interval dt [s].
    duration : float
        Record duration T [s] (before any zero padding).
    upper_fraction : float, default 0.1
        Upper limit as a fraction of the sampling rate 1/dt [-] (aliasing of the pulse onset;
        default a tenth, see the module notes).
    min_periods : float, default 1.0
        Periods of the lowest frequency that must fit in the record [-].

    Returns
    -------
    lowest : float
        ``min_periods / T`` [Hz].
    highest : float
        ``upper_fraction / dt`` [Hz].

    Raises
    ------
    ValueError
        If ``time_step`` or ``duration`` is not positive.
    """
    if time_step <= 0.0 or duration <= 0.0:
        raise ValueError("time_step and duration must be positive [s]")
    return min_periods / duration, upper_fraction / time_step


# ---------------------------------------------------------------------------------- spectra
def _check_force(force, time_step: float) -> np.ndarray:
    f = np.asarray(force, dtype=float)
    if f.ndim != 1 or f.size < 2:
        raise ValueError("force must be a 1D array of at least 2 samples [N]")
    if not np.all(np.isfinite(f)):
        raise ValueError("force contains non-finite values")
    if not time_step > 0.0:
        raise ValueError("time_step must be positive [s]")
    return f


def _fft_size(n_samples: int, n_fft: int | None) -> int:
    n = n_samples if n_fft is None else int(n_fft)
    if n < n_samples:
        raise ValueError(f"n_fft ({n}) must be at least the number of samples ({n_samples})")
    n = scipy.fft.next_fast_len(n, real=True)
    while n % 2:  # even: the Nyquist frequency is a frequency point
        n = scipy.fft.next_fast_len(n + 1, real=True)
    if n > MAX_FFT_SIZE:
        raise ValueError(f"the zero-padded FFT needs {n} points (more than {MAX_FFT_SIZE}); "
                         "raise the lowest band or resample the record")
    return n


def fourier_amplitude_spectrum(force, time_step: float, n_fft: int | None = None):
    """|F(f)| of a sampled force pulse, f >= 0 [N s].

    Parameters
    ----------
    force : array_like
        F_n, samples at t_n = n dt [N].
    time_step : float
        dt [s].
    n_fft : int, optional
        Zero-padded FFT length [-] (default: the record length); rounded up to the next even
        length with small prime factors (``scipy.fft.next_fast_len``).

    Returns
    -------
    frequency : numpy.ndarray
        k / (n_fft dt), k = 0..n_fft/2 [Hz].
    amplitude : numpy.ndarray
        |F(f)| [N s].
    """
    f = _check_force(force, time_step)
    n = _fft_size(f.size, n_fft)
    return scipy.fft.rfftfreq(n, time_step), time_step * np.abs(scipy.fft.rfft(f, n))


def energy_spectral_density(force, time_step: float, n_fft: int | None = None):
    """One-sided energy spectral density ESD(f) = 2 |F(f)|^2, f >= 0 [N^2 s/Hz].

    The trapezoidal integral of the result over [0, f_Nyquist] equals sum F_n^2 dt (discrete
    Parseval, see the module notes).

    Parameters
    ----------
    force : array_like
        F_n, samples at t_n = n dt [N].
    time_step : float
        dt [s].
    n_fft : int, optional
        Zero-padded FFT length [-], as in :func:`fourier_amplitude_spectrum`.

    Returns
    -------
    frequency : numpy.ndarray
        Frequency points [Hz].
    esd : numpy.ndarray
        ESD(f) [N^2 s/Hz].
    """
    frequency, amplitude = fourier_amplitude_spectrum(force, time_step, n_fft)
    return frequency, 2.0 * amplitude ** 2


def signal_energy(force, time_step: float) -> float:
    """Energy of a sampled force, sum F_n^2 dt [N^2 s] (rectangle rule; equals the ESD total).

    Parameters
    ----------
    force : array_like
        F_n [N].
    time_step : float
        dt [s].

    Returns
    -------
    float
        The energy [N^2 s].
    """
    f = _check_force(force, time_step)
    return float(np.dot(f, f) * time_step)


def integrate_piecewise_linear(frequency_step: float, density, lower: float,
                               upper: float) -> float:
    """Exact integral over [lower, upper] of a density sampled at k df, linear between [N^2 s].

    Partial intervals at both ends are integrated as trapezoids on the interpolated end values;
    whole intervals are summed separately (no difference of cumulative sums, so a weak band is
    not lost in the round-off of a strong total).

    Parameters
    ----------
    frequency_step : float
        df [Hz].
    density : array_like
        Values at f = k df, k = 0..K [N^2 s/Hz].
    lower : float
        Lower integration limit, 0 <= lower <= upper [Hz].
    upper : float
        Upper integration limit, upper <= K df [Hz].

    Returns
    -------
    float
        The integral [N^2 s].

    Raises
    ------
    ValueError
        If the limits lie outside the spectrum.
    """
    e = np.asarray(density, dtype=float)
    top = (e.size - 1) * frequency_step
    if not 0.0 <= lower <= upper <= top * (1.0 + 1e-12):
        raise ValueError(f"limits [{lower}, {upper}] Hz outside the spectrum [0, {top}] Hz")
    upper = min(upper, top)

    k_lo = min(int(lower // frequency_step), e.size - 2)
    k_hi = min(int(upper // frequency_step), e.size - 2)

    def value(f: float, k: int) -> float:  # linear between k df and (k + 1) df
        return float(e[k] + (e[k + 1] - e[k]) * (f / frequency_step - k))

    if k_lo == k_hi:
        return (upper - lower) * 0.5 * (value(lower, k_lo) + value(upper, k_lo))
    first = ((k_lo + 1) * frequency_step - lower) * 0.5 * (value(lower, k_lo) + e[k_lo + 1])
    last = (upper - k_hi * frequency_step) * 0.5 * (e[k_hi] + value(upper, k_hi))
    inner = e[k_lo + 1:k_hi + 1]
    middle = frequency_step * (inner.sum() - 0.5 * (inner[0] + inner[-1]))
    return float(first + middle + last)


def energy_level(energy):
    """Level 10 log10(E / 1 N^2 s) [dB re 1 N^2 s]; -inf for a zero energy.

    Parameters
    ----------
    energy : float or array_like
        E [N^2 s].

    Returns
    -------
    numpy.ndarray
        The level [dB re 1 N^2 s].
    """
    with np.errstate(divide="ignore"):
        return 10.0 * np.log10(np.asarray(energy, dtype=float) / REFERENCE_ENERGY)


@dataclass(frozen=True)
class BandEnergies:
    """One-third-octave band energies of a force record.

    Parameters
    ----------
    band_number : numpy.ndarray
        IEC 61260-1 band index n [-].
    centre_frequency : numpy.ndarray
        Mid-band frequency f_m [Hz].
    lower_frequency : numpy.ndarray
        Lower band edge [Hz].
    upper_frequency : numpy.ndarray
        Upper band edge [Hz].
    energy : numpy.ndarray
        Band energy, both sides of the spectrum [N^2 s].
    level : numpy.ndarray
        10 log10(energy / 1 N^2 s) [dB re 1 N^2 s].
    valid : numpy.ndarray
        Band wholly inside :func:`valid_band` [-].
    valid_range : tuple of float
        (lowest, highest) trustworthy frequency [Hz].
    frequency_step : float
        Spacing of the zero-padded spectrum [Hz].
    total_energy : float
        sum F_n^2 dt of the record [N^2 s].
    """

    band_number: np.ndarray
    centre_frequency: np.ndarray
    lower_frequency: np.ndarray
    upper_frequency: np.ndarray
    energy: np.ndarray
    level: np.ndarray
    valid: np.ndarray
    valid_range: tuple[float, float]
    frequency_step: float
    total_energy: float

    def columns(self) -> dict[str, np.ndarray]:
        """Columns for a CSV, named ``name [unit]``.

        Returns
        -------
        dict of str to numpy.ndarray
            The band columns.
        """
        return {
            "band_centre_frequency [Hz]": self.centre_frequency,
            "band_lower_frequency [Hz]": self.lower_frequency,
            "band_upper_frequency [Hz]": self.upper_frequency,
            "band_energy [N^2 s]": self.energy,
            "band_level [dB re 1 N^2 s]": self.level,
            "valid [-]": self.valid.astype(int),
        }


def third_octave_band_energies(force, time_step: float, band_numbers=None, *,
                               bins_per_band: int = 16, lowest_frequency: float = 10.0,
                               upper_fraction: float = 0.1) -> BandEnergies:
    """One-third-octave band energies and levels of a sampled force pulse.

    Parameters
    ----------
    force : array_like
        F_n, samples at t_n = n dt, the pulse and its decay [N].
    time_step : float
        dt [s].
    band_numbers : array_like of int, optional
        IEC 61260-1 band indices n [-]; default: every band from the one at
        ``lowest_frequency`` up to the last one below the Nyquist frequency (invalid ones are
        computed and flagged, see ``valid``).
    bins_per_band : int, default 16
        Frequency steps of the zero-padded spectrum across the lowest band [-].
    lowest_frequency : float, default 10.0
        Nominal lowest band for the default band list [Hz] (10 Hz: n = -20).
    upper_fraction : float, default 0.1
        Upper limit of the valid band as a fraction of 1/dt [-].

    Returns
    -------
    BandEnergies
        The band energies, levels and validity.

    Raises
    ------
    ValueError
        If the band numbers are not integers or reach above the Nyquist frequency.

    References
    ----------
    IEC 61260-1:2014. Electroacoustics - Octave-band and fractional-octave-band filters - Part 1:
    Specifications.
    """
    f = _check_force(force, time_step)
    nyquist = 0.5 / time_step
    if band_numbers is None:
        first = round(10.0 * math.log10(lowest_frequency / 1000.0))
        band_numbers = band_numbers_between(iec_61260_1_2014_band_edges(first)[0], nyquist)
    n = np.atleast_1d(np.asarray(band_numbers))
    if n.size == 0 or not np.issubdtype(n.dtype, np.integer):
        raise ValueError("band_numbers must be integers")
    lower, upper = iec_61260_1_2014_band_edges(n)
    if np.any(upper > nyquist):
        raise ValueError(f"bands above the Nyquist frequency {nyquist:g} Hz requested")
    width = float(np.min(upper - lower))
    n_fft = max(f.size, math.ceil(bins_per_band / (width * time_step)))
    frequency, esd = energy_spectral_density(f, time_step, _fft_size(f.size, n_fft))
    df = float(frequency[1])
    energy = np.array([integrate_piecewise_linear(df, esd, lo, hi)
                       for lo, hi in zip(lower, upper, strict=True)])
    low_valid, high_valid = valid_band(time_step, f.size * time_step,
                                       upper_fraction=upper_fraction)
    return BandEnergies(
        band_number=n, centre_frequency=iec_61260_1_2014_band_centre(n),
        lower_frequency=lower, upper_frequency=upper, energy=energy,
        level=energy_level(energy), valid=(lower >= low_valid) & (upper <= high_valid),
        valid_range=(low_valid, high_valid), frequency_step=df,
        total_energy=signal_energy(f, time_step))


__all__ = [
    "MAX_FFT_SIZE", "REFERENCE_ENERGY", "THIRD_OCTAVE_HALF_WIDTH", "BandEnergies",
    "band_numbers_between", "energy_level", "energy_spectral_density",
    "fourier_amplitude_spectrum", "iec_61260_1_2014_band_centre", "iec_61260_1_2014_band_edges",
    "integrate_piecewise_linear", "signal_energy", "third_octave_band_energies", "valid_band",
]
