"""Helpers for users' own pytest suites: assert spectral slopes and levels with readable failures.

Example
-------
>>> from compare.testing import assert_spectral_slope
>>> assert_spectral_slope(trace.t, trace.x, expected=4.0, tol=0.2, band=(5.0, 200.0))
"""
from __future__ import annotations

import math

import numpy as np

from .fits import METHODS, PowerLawFit, fit_power_law
from .record_model import RecordFit, band_end_words, fit_series
from .spectra import Spectrum, band_average, displacement_spectrum

__all__ = ["assert_spectral_slope", "assert_spectrum_matches", "SpectralAssertionError", "SLOPE_METHODS"]

# the estimators assert_spectral_slope offers: the record model of the time record (the default: the exponent the
# report, compare and analyze quote) and the band fits of a Welch spectrum (compare.analysis.fits.METHODS)
SLOPE_METHODS = ("record", *METHODS)


class SpectralAssertionError(AssertionError):
    """A spectral check failed; the message carries the measured numbers."""


def assert_spectral_slope(t, x, expected: float, tol: float, band=None, method: str = "record",
                          allow_flagged: bool = False, discrete: bool = False,
                          **spectrum_kwargs) -> RecordFit | PowerLawFit:
    """Assert that C_x of x(t) falls as omega^-gamma with ``abs(gamma - expected) <= tol`` and that the fit carries
    no flag (the spectrum is one power law over the band).

    For pytest: on failure it raises :class:`SpectralAssertionError`, an AssertionError whose message of a few lines
    gives the measured gamma with its 95 % interval, the expected value and tolerance, the band and the fit's flags;
    pytest shows the caller's line, not this helper's source.

    Parameters
    ----------
    t : array_like
        Uniform sample times (Units: s).
    x : array_like
        Positions (Units: m).
    expected : float
        The expected exponent gamma (dimensionless).
    tol : float
        The allowed deviation of the fitted gamma; choose it from the fit's own interval, not from one seed.
    band : tuple of float, optional
        Fit band (Units: rad/s). With ``"record"`` the likelihood sums over the record's Fourier ordinates inside
        it; default the record model's own band (where one power law holds, up to where a floor takes over). With
        the band fits, default the automatic band of :func:`compare.fits.fit_power_law`.
    method : {"record", "whittle", "lsq"}, optional
        ``"record"`` (default): the record model, C_x = A omega^-gamma plus a white floor fitted to the whole time
        record by the debiased Whittle likelihood (:func:`compare.analysis.record_model.fit_series`, without its
        split-half stationarity test), the exponent the report, ``compare`` and ``analyze`` quote. ``"whittle"`` or
        ``"lsq"``: a band fit of the Welch spectrum (:func:`compare.fits.fit_power_law`), faster on long records
        (about 30x on 3e5 samples: 0.1 s against 2.8 s of CPU), but its automatic band needs 32768 samples for a
        decade and a sensor's white floor biases it.
    allow_flagged : bool, optional
        False (default): a fit flagged as not a power law (``fit.flags``: band under a decade, curved residuals, not
        stationary, a bend, gamma at the fit's limit) fails, whatever its gamma, because its gamma describes no single
        power law. True: only gamma is checked; the flags still appear in a failure's message.
    discrete : bool, optional
        With ``"record"``: x is a discrete-time process (a simulation's cumulative sum of random steps, whose
        spectrum is (2 sin(omega dt / 2) / dt)^-gamma): fit that form (:func:`compare.analysis.record_model.fit_record`)
        rather than the continuous law folded at Nyquist, which reads such a walk low with a floor near Nyquist.
    **spectrum_kwargs
        With a band fit only: passed to :func:`compare.spectra.displacement_spectrum` (``detrend``, ``prewhiten``,
        ``nperseg``).

    Returns
    -------
    RecordFit or PowerLawFit
        The fit, when the assertion holds.
    """
    __tracebackhide__ = True  # pytest: the failure points at the caller's line
    if method not in SLOPE_METHODS:
        raise ValueError(f"method {method!r}: choose one of {', '.join(SLOPE_METHODS)}")
    if discrete and method != "record":
        raise ValueError(f"discrete applies to method='record' (the record model), not to {method!r}")
    if method == "record":
        if spectrum_kwargs:
            raise ValueError(f"{', '.join(sorted(spectrum_kwargs))}: Welch spectrum options, used by the band fits "
                             "only (method='whittle' or 'lsq'); the record model fits the record itself")
        fit = fit_series(t, x, band=band, stationarity=False, discrete=discrete)
        counted = "Fourier ordinates in the likelihood, those above the band where the floor is fitted included"
    else:
        fit = fit_power_law(displacement_spectrum(t, x, **spectrum_kwargs), band=band, method=method)
        counted = "periodogram ordinates" if fit.method == "whittle" else "log bins"
    off = not abs(fit.gamma - expected) <= tol
    flagged = bool(fit.flags) and not allow_flagged
    if off or flagged:
        raise SpectralAssertionError(_slope_message(fit, expected, tol, counted, off, flagged))
    return fit


def _slope_message(fit, expected: float, tol: float, counted: str, off: bool, flagged: bool) -> str:
    """The failure of :func:`assert_spectral_slope` in a few lines: why, the exponent with its interval against the
    expectation, the band, the flags."""
    if isinstance(fit, RecordFit):
        low, high, how = fit.gamma_low, fit.gamma_high, "record model, debiased Whittle, profile likelihood"
    else:
        low, high = fit.gamma - fit.gamma_err, fit.gamma + fit.gamma_err
        how = f"band fit of a Welch spectrum, {fit.method}"
    why = []
    if off:
        why.append(f"gamma is off by {fit.gamma - expected:+.3f} (tolerance {tol:g})")
    if flagged:
        why.append("the fit is flagged NOT A POWER LAW (pass allow_flagged=True to check gamma alone)")
    flags = "; ".join(fit.flags) if fit.flags else "none"
    lines = [
        f"spectral slope: {' and '.join(why)}",
        f"  measured gamma = {fit.gamma:.3f} +- {fit.gamma_err:.3f}, 95 % interval [{low:.3f}, {high:.3f}] ({how})",
        f"  expected gamma = {expected:g} +- {tol:g}",
        f"  band {fit.band[0]:.4g}-{fit.band[1]:.4g} rad/s ({math.log10(fit.band[1] / fit.band[0]):.2f} decades, "
        f"{'auto' if fit.band_auto else 'given'}; {fit.n_points} {counted})",
        f"  flags: {flags}",
    ]
    if isinstance(fit, RecordFit):
        # what the record model says ends the band (a floor, a departure), and its notes: among them the hint that a
        # floor near Nyquist is a discrete-time process read as a continuous one
        lines.append("  band end: " + band_end_words(fit.band_end, fit.floor_rms, fit.crossover, fit.band[1],
                                                      fit.gamma, [s[:3] for s in fit.segments],
                                                      f" {fit.record_unit}" if fit.record_unit else "").lstrip("; "))
        lines += [f"  note: {n}" for n in fit.notes]
    return "\n".join(lines)


def assert_spectrum_matches(spectrum: Spectrum, theory, edges, rtol: float) -> np.ndarray:
    """Assert that the band averages of a spectrum and of a prediction agree within ``rtol``.

    Both are averaged over the same ordinates (:func:`compare.spectra.band_average`); on failure
    :class:`SpectralAssertionError` lists the bands outside 1 +- rtol with their ratios.

    Parameters
    ----------
    spectrum : Spectrum
        The measured or simulated spectrum.
    theory : callable or array_like
        The prediction: a function of omega (Units: rad/s) or an array on ``spectrum.omega``, in the spectrum's unit.
    edges : array_like
        Band edges (Units: rad/s), increasing.
    rtol : float
        The allowed relative deviation of each band's ratio from 1.

    Returns
    -------
    numpy.ndarray
        The per-band ratios spectrum / theory.
    """
    __tracebackhide__ = True  # pytest: the failure points at the caller's line
    vals = theory(spectrum.omega) if callable(theory) else np.asarray(theory)
    ratio = band_average(spectrum, edges) / band_average(spectrum, edges, vals)
    bad = np.flatnonzero(np.abs(ratio - 1.0) > rtol)
    if bad.size:
        rows = ", ".join(f"[{edges[i]:.3g}, {edges[i + 1]:.3g}): {ratio[i]:.3f}" for i in bad)
        raise SpectralAssertionError(
            f"spectrum/theory outside 1 +- {rtol:g} in {bad.size} of {len(ratio)} bands: {rows}"
        )
    return ratio
