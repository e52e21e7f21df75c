"""Tests of anvilwave/pile/post/spectra.py: one-third-octave bands (IEC 61260-1 base ten), band
energies of a
force pulse against their closed form, Parseval, and the valid band.

Check pulse (/work/shared/reference/driveability-fatigue-pda-spectra.md, "Force spectra"):
F(t) = F0 (e^(-a t) - e^(-b t)) for t >= 0, 0 < a < b. Its Fourier transform is

    F(w) = F0 (1/(a + i w) - 1/(b + i w)) = F0 (b - a) / ((a + i w)(b + i w)),
    |F(w)|^2 = F0^2 (b - a)^2 / ((a^2 + w^2)(b^2 + w^2))
             = F0^2 (b - a)^2 / (b^2 - a^2) (1/(a^2 + w^2) - 1/(b^2 + w^2)),

so the energy in the band [f1, f2] on both sides of the spectrum (w = 2 pi f, df = dw / 2 pi) is

    E = 2 int_f1^f2 |F|^2 df = (1/pi) int_w1^w2 |F|^2 dw
      = F0^2 (b - a) / (pi (a + b)) [ (atan(w2/a) - atan(w1/a)) / a
                                     - (atan(w2/b) - atan(w1/b)) / b ],

and over all frequencies (w1 = 0, w2 -> inf) E = F0^2 (b - a)^2 / (2 a b (a + b)), which is
int_0^inf F^2 dt worked out in the time domain (Parseval).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from anvilwave.pile.post.spectra import (
    band_numbers_between,
    energy_level,
    energy_spectral_density,
    fourier_amplitude_spectrum,
    iec_61260_1_2014_band_centre,
    iec_61260_1_2014_band_edges,
    integrate_piecewise_linear,
    signal_energy,
    third_octave_band_energies,
    valid_band,
)

F0, A, B = 10.0e6, 200.0, 4000.0  # [N], [1/s], [1/s]: 10 MN, rise ~0.8 ms, decay 5 ms
DT, DURATION = 1.0e-6, 0.25  # [s]: 1 MHz sampling; e^(-a T) = e^-50, the pulse is complete


def closed_form_band_energy(f1, f2):
    """Both-sided energy of the check pulse between f1 and f2 [Hz] (module docstring) [N^2 s]."""
    w1, w2 = 2.0 * np.pi * np.asarray(f1), 2.0 * np.pi * np.asarray(f2)
    return (F0 ** 2 * (B - A) / (np.pi * (A + B))
            * ((np.arctan(w2 / A) - np.arctan(w1 / A)) / A
               - (np.arctan(w2 / B) - np.arctan(w1 / B)) / B))


def closed_form_total_energy() -> float:
    return F0 ** 2 * (B - A) ** 2 / (2.0 * A * B * (A + B))


@pytest.fixture(scope="module")
def pulse() -> np.ndarray:
    t = np.arange(round(DURATION / DT)) * DT  # time from the sample count
    return F0 * (np.exp(-A * t) - np.exp(-B * t))


@pytest.fixture(scope="module")
def bands_10hz_20khz(pulse):
    return third_octave_band_energies(pulse, DT, np.arange(-20, 14))


def test_iec_61260_band_frequencies():
    assert iec_61260_1_2014_band_centre(0) == 1000.0
    assert iec_61260_1_2014_band_centre(-20) == pytest.approx(10.0, rel=1e-14)
    # base ten: 10 bands per decade; nominal 20 kHz is exactly 19952.6 Hz
    assert iec_61260_1_2014_band_centre(13) == pytest.approx(19952.623, rel=1e-7)
    lower, upper = iec_61260_1_2014_band_edges(0)
    assert lower == pytest.approx(891.2509, rel=1e-7)  # 1000 x 10^(-1/20)
    assert upper == pytest.approx(1122.0185, rel=1e-7)  # 1000 x 10^(+1/20)
    # contiguous bands: the upper edge of n is the lower edge of n + 1
    lo, hi = iec_61260_1_2014_band_edges(np.arange(-20, 14))
    np.testing.assert_allclose(hi[:-1], lo[1:], rtol=1e-14)
    np.testing.assert_array_equal(band_numbers_between(8.0, 25_000.0), np.arange(-20, 14))


def test_band_energies_match_the_closed_form(bands_10hz_20khz):
    bands = bands_10hz_20khz  # 10 Hz ... 20 kHz
    expected = energy_level(closed_form_band_energy(bands.lower_frequency,
                                                    bands.upper_frequency))
    # The highest band here is centred at 1/50 of the sampling rate, where aliasing of the
    # pulse onset (a kink: spectrum ~ 1/f^2, relative error ~ 2 zeta(2) (f dt)^2 in amplitude)
    # leaves 0.011 dB; the 16 frequency steps across the 10 Hz band make the linear
    # interpolation of the ESD good to ~1e-5 dB. The reference quotes 0.02 dB for such an FFT.
    np.testing.assert_allclose(bands.level, expected, rtol=0.0, atol=0.02)
    assert np.all(bands.valid)
    assert bands.frequency_step < 0.1 * (bands.upper_frequency[0] - bands.lower_frequency[0])


def test_levels_degrade_towards_a_tenth_of_the_sampling_rate(pulse):
    """Why the valid band stops at ~fs/10: the check pulse is 0.28 dB high in the band centred
    at fs/10 (100 kHz at 1 MHz), the first band flagged invalid; below, within 0.2 dB."""
    bands = third_octave_band_energies(pulse, DT)
    error = bands.level - energy_level(closed_form_band_energy(bands.lower_frequency,
                                                               bands.upper_frequency))
    assert bands.valid_range == pytest.approx((1.0 / DURATION, 0.1 / DT), rel=1e-12)
    at_tenth = np.argmin(np.abs(bands.centre_frequency - 0.1 / DT))
    assert not bands.valid[at_tenth] and bands.valid[at_tenth - 1]
    assert 0.2 < error[at_tenth] < 0.35  # aliasing, as stated in the module notes
    assert np.max(np.abs(error[bands.valid])) < 0.2


def test_parseval(pulse, bands_10hz_20khz):
    frequency, esd = energy_spectral_density(pulse, DT, n_fft=3 * pulse.size)
    df = frequency[1]
    total = integrate_piecewise_linear(df, esd, 0.0, frequency[-1])
    # discrete identity (trapezoid of the one-sided ESD = sum F^2 dt): round-off only
    assert total == pytest.approx(signal_energy(pulse, DT), rel=1e-12)
    # sampled energy against int F^2 dt: F(0) = 0 and (F^2)'(0) = 0, so the rectangle sum is
    # exact up to O(dt^4) terms and the e^(-2 a T) truncation: 1e-10 is round-off margin
    assert signal_energy(pulse, DT) == pytest.approx(closed_form_total_energy(), rel=1e-10)
    # bands + the rest of the spectrum add up to the total (partial bins at every edge)
    bands = bands_10hz_20khz
    frequency, esd = energy_spectral_density(pulse, DT, n_fft=round(1.0 / (bands.frequency_step
                                                                          * DT)))
    rest = (integrate_piecewise_linear(bands.frequency_step, esd, 0.0, bands.lower_frequency[0])
            + integrate_piecewise_linear(bands.frequency_step, esd, bands.upper_frequency[-1],
                                         frequency[-1]))
    assert bands.energy.sum() + rest == pytest.approx(bands.total_energy, rel=1e-12)


def test_amplitude_spectrum_at_zero_frequency(pulse):
    frequency, amplitude = fourier_amplitude_spectrum(pulse, DT)
    # |F(0)| = int F dt = F0 (1/a - 1/b); the rectangle sum is exact to O(dt^2) (F(0) = 0):
    # relative (a dt)^2-type error ~1e-7 at most
    assert frequency[0] == 0.0
    assert amplitude[0] == pytest.approx(F0 * (1.0 / A - 1.0 / B), rel=1e-6)
    # and at 1 kHz (w = 2 pi 1000): |F| from the closed form, zero padding to a 1 Hz grid
    frequency, amplitude = fourier_amplitude_spectrum(pulse, DT, n_fft=round(1.0 / DT))
    k = int(np.argmin(np.abs(frequency - 1000.0)))
    w = 2.0 * np.pi * frequency[k]
    exact = F0 * (B - A) / math.sqrt((A * A + w * w) * (B * B + w * w))
    # aliases add in phase (F ~ -F0 (b - a) / w^2 far above b): 2 zeta(2) (f dt)^2 = 3.3e-6
    assert amplitude[k] == pytest.approx(exact, rel=1e-5)


def test_piecewise_linear_integral_partial_bins():
    # density 2 + 3 f on a 0.5 Hz grid: the exact integral over [0.3, 2.2] is
    # 2 (1.9) + 1.5 (2.2^2 - 0.3^2) = 3.8 + 7.125 = 10.925, whatever the bin boundaries
    f = np.arange(0.0, 3.01, 0.5)
    assert integrate_piecewise_linear(0.5, 2.0 + 3.0 * f, 0.3, 2.2) == pytest.approx(
        10.925, rel=1e-14)
    assert integrate_piecewise_linear(0.5, 2.0 + 3.0 * f, 0.6, 0.9) == pytest.approx(
        2.0 * 0.3 + 1.5 * (0.81 - 0.36), rel=1e-14)  # both limits inside one bin
    with pytest.raises(ValueError, match="outside"):
        integrate_piecewise_linear(0.5, f, 0.0, 5.0)


def test_valid_band_and_bad_input(pulse):
    assert valid_band(1e-5, 0.2) == pytest.approx((5.0, 10_000.0), rel=1e-12)
    with pytest.raises(ValueError, match="Nyquist"):
        third_octave_band_energies(pulse, DT, [60])  # 1 GHz band
    with pytest.raises(ValueError, match="non-finite"):
        third_octave_band_energies(np.array([0.0, np.nan, 1.0]), DT)
    with pytest.raises(ValueError, match="FFT needs"):
        third_octave_band_energies(pulse, DT, [-40])  # 0.1 Hz band at 1 MHz: too big
    bands = third_octave_band_energies(pulse, DT, np.arange(-20, -17))
    assert list(bands.columns()) == [
        "band_centre_frequency [Hz]", "band_lower_frequency [Hz]", "band_upper_frequency [Hz]",
        "band_energy [N^2 s]", "band_level [dB re 1 N^2 s]", "valid [-]"]
