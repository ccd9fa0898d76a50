"""Records with exactly known spectra: a sampled omega^-gamma process plus a white sensor floor.

:func:`power_law_record` draws the record a sensor would write when the physical displacement has the continuous
spectrum C_x(omega) = A omega^-gamma (eq. 2 convention) and the sensor adds white noise of rms ``floor_rms``. The
record's k-th difference (k = :func:`compare.analysis.whittle.order_for` (gamma)) is stationary with spectrum

.. math:: S_y(\\omega) = \\left|\\frac{2\\sin(\\omega dt/2)}{dt}\\right|^{2k} A \\left(\\frac{2\\pi}{dt}\\right)^{-\\gamma}
          [\\zeta(\\gamma, u) + \\zeta(\\gamma, 1 - u)],\\qquad u = \\frac{\\omega dt}{2\\pi},

(the continuous spectrum folded at Nyquist; zeta is Hurwitz's). It is drawn by circulant embedding (Davies & Harte
1987) over 2n points and summed k times. For even gamma = 2k, S_y is a trigonometric polynomial (for gamma = 4,
A (2 + cos omega dt) / 3): its autocovariance ends after k lags, the embedding is exact and so is the record. For
other gamma the circulant's autocovariance is that of S_y sampled on the 2n-point grid (lag aliasing beyond the record,
and the integrable peak of S_y at zero frequency left out for gamma > 2k).
"""
from __future__ import annotations

import math

import numpy as np
from scipy import special

from .whittle import folded, order_for

__all__ = ["power_law_record", "sampled_power_law", "spectrum_record"]


def sampled_power_law(omega, gamma: float, prefactor: float, dt: float) -> np.ndarray:
    """The sampled record's spectrum of C_x = A omega^-gamma: sum_m A abs(omega + 2 pi m / dt)^-gamma, exactly.

    Parameters
    ----------
    omega : array_like
        Frequencies in (0, pi/dt] (Units: rad/s).
    gamma : float
        Exponent (> 1: a smaller one sums to infinity).
    prefactor : float
        A (Units: m^2 s (rad/s)^gamma for a displacement).
    dt : float
        Sampling step (Units: s).

    Returns
    -------
    ndarray
        C_x^(s)(omega) (Units: those of A (rad/s)^-gamma).
    """
    if not gamma > 1:
        raise ValueError(f"gamma must exceed 1 for a sampled power law (got {gamma!r})")
    u = np.asarray(omega, dtype=float) * dt / (2.0 * math.pi)
    return prefactor * (2.0 * math.pi / dt) ** (-gamma) * (special.zeta(gamma, u) + special.zeta(gamma, 1.0 - u))


def power_law_record(n: int, dt: float, gamma: float, *, prefactor: float = 1.0, floor_rms: float = 0.0,
                     seed: int = 0) -> np.ndarray:
    """n samples of an omega^-gamma process, as a sensor with a white floor records it (module docstring).

    Parameters
    ----------
    n : int
        Samples.
    dt : float
        Sampling step (Units: s).
    gamma : float
        Exponent (> 1).
    prefactor : float, optional
        A of C_x = A omega^-gamma (Units: m^2 s (rad/s)^gamma).
    floor_rms : float, optional
        The sensor's white noise (Units: m); its level is floor_rms^2 dt / (2 pi) (m^2 s).
    seed : int, optional
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    ndarray
        The record (Units: m), starting at 0 before the floor is added.
    """
    if n < 16:
        raise ValueError(f"n must be at least 16 (got {n})")
    rng = np.random.default_rng(seed)
    k = order_for(gamma)
    m = 2 * n
    u = np.arange(m // 2 + 1) / m
    S = np.empty(m // 2 + 1)
    w = 2.0 * math.pi * u[1:] / dt
    S[1:] = np.abs(2.0 * np.sin(math.pi * u[1:]) / dt) ** (2 * k) * sampled_power_law(w, gamma, prefactor, dt)
    S[0] = prefactor if gamma == 2 * k else 0.0  # the limit of S_y at zero frequency
    return _drawn(S, n, k, dt, floor_rms, rng)


def spectrum_record(n: int, dt: float, spectrum, order: int, *, floor_rms: float = 0.0, images: int = 8,
                    seed: int = 0) -> np.ndarray:
    """n samples of a Gaussian process with continuous spectrum ``spectrum(omega)``, as a sensor with a white
    floor records it.

    The k-th difference (k = ``order``) has the spectrum abs(2 sin(omega dt / 2) / dt)^2k C^(s)(omega), C^(s) the
    continuous spectrum folded at Nyquist with ``images`` images per side (:func:`compare.analysis.whittle.folded`);
    it is drawn by circulant embedding over 2n points (its autocovariance that of the spectrum sampled on that grid)
    and summed k times, as in :func:`power_law_record`. The spectrum must fall no faster than omega^-2k near zero.

    Parameters
    ----------
    n : int
        Samples (at least 16).
    dt : float
        Sampling step (Units: s).
    spectrum : callable
        C_x(omega) of the continuous process at omega > 0 (rad/s) (Units: m^2 s for a displacement).
    order : int
        Differencing order k (0-6).
    floor_rms : float, optional
        The sensor's white noise (Units: m).
    images : int, optional
        Aliasing images folded in on each side.
    seed : int, optional
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    ndarray
        The record (Units: m), starting at 0 before the floor is added.
    """
    if n < 16:
        raise ValueError(f"n must be at least 16 (got {n})")
    rng = np.random.default_rng(seed)
    m = 2 * n
    u = np.arange(m // 2 + 1) / m
    w = 2.0 * math.pi * u[1:] / dt
    S = np.empty(m // 2 + 1)
    S[1:] = np.abs(2.0 * np.sin(math.pi * u[1:]) / dt) ** (2 * order) * folded(lambda o, p: spectrum(o), dt, images)(w, ())
    S[0] = S[1]  # the differenced spectrum's limit at zero frequency, one grid step away
    return _drawn(S, n, order, dt, floor_rms, rng)


def _drawn(S: np.ndarray, n: int, k: int, dt: float, floor_rms: float, rng) -> np.ndarray:
    """n samples of the process whose k-th difference has the one-sided grid spectrum ``S`` (2n points, m^2 s per
    (s^k)^2), drawn by circulant embedding and summed k times, plus a white floor of rms ``floor_rms`` (m)."""
    m = 2 * n
    lam = np.concatenate([S, S[-2:0:-1]]) * (2.0 * math.pi / dt)  # circulant eigenvalues (full circle)
    xi = rng.standard_normal(m) + 1j * rng.standard_normal(m)
    x = np.fft.fft(np.sqrt(lam / m) * xi).real[: n - k]
    for _ in range(k):
        x = np.concatenate([[0.0], np.cumsum(x) * dt])  # diff(x) / dt is the previous series
    if floor_rms:
        x = x + floor_rms * rng.standard_normal(n)
    return x
