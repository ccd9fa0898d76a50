"""Helpers for users' own pytest suites: assert spectral slopes and levels with readable failures.

Example
-------
>>> from compare.testing import assert_spectral_slope
>>> assert_spectral_slope(trace.t, trace.x, expected=4.0, tol=0.2, band=(5.0, 200.0))
"""
from __future__ import annotations

import numpy as np

from .fits import PowerLawFit, fit_power_law
from .spectra import Spectrum, band_average, displacement_spectrum

__all__ = ["assert_spectral_slope", "assert_spectrum_matches", "SpectralAssertionError"]


class SpectralAssertionError(AssertionError):
    """A spectral check failed; the message carries the measured numbers."""


def assert_spectral_slope(t, x, expected: float, tol: float, band=None, method: str | None = None,
                          **spectrum_kwargs) -> PowerLawFit:
    """Assert that C_x of x(t) falls as omega^-gamma with ``abs(gamma - expected) <= tol``.

    For pytest: on failure it raises :class:`SpectralAssertionError`, an AssertionError whose message carries the
    measured gamma, its 95 % interval, the band and the method.

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
        Fit band (Units: rad/s); default the automatic band of :func:`compare.fits.fit_power_law`.
    method : {"whittle", "lsq"}, optional
        The fit method; default :data:`compare.fits.DEFAULT_METHOD`.
    **spectrum_kwargs
        Passed to :func:`compare.spectra.displacement_spectrum` (``detrend``, ``prewhiten``, ``nperseg``).

    Returns
    -------
    PowerLawFit
        The fit, when the assertion holds.
    """
    spec = displacement_spectrum(t, x, **spectrum_kwargs)
    fit = fit_power_law(spec, band=band, method=method)
    if not abs(fit.gamma - expected) <= tol:
        raise SpectralAssertionError(
            f"spectral slope: measured gamma = {fit.gamma:.3f} +- {fit.gamma_err:.3f} (95 % CI, {fit.method}) over "
            f"{fit.band[0]:.4g}-{fit.band[1]:.4g} rad/s ({'auto' if fit.band_auto else 'given'} band, "
            f"{fit.n_points} {'periodogram ordinates' if fit.method == 'whittle' else 'log bins'}); expected "
            f"{expected:g} +- {tol:g}; off by {fit.gamma - expected:+.3f}"
        )
    return fit


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
    vals = theory(spectrum.omega) if callable(theory) else np.asarray(theory)
    ratio = band_average(spectrum, edges) / band_average(spectrum, edges, vals)
    bad = np.flatnonzero(np.abs(ratio - 1.0) > rtol)
    if bad.size:
        rows = ", ".join(f"[{edges[i]:.3g}, {edges[i + 1]:.3g}): {ratio[i]:.3f}" for i in bad)
        raise SpectralAssertionError(
            f"spectrum/theory outside 1 +- {rtol:g} in {bad.size} of {len(ratio)} bands: {rows}"
        )
    return ratio
