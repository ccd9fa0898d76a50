"""The autocorrelation of force series in sliding distance and its integral, the correlation length; the spectrum
of one such renewing force (eq. A8).

For forces that renew once per window a of sliding, at a uniform point of each window (eq. 5 of Xu, Zhou & Persson
2025), the renewal distances are a (1 + r - r') and the integral correlation length is <tau^2> / (2 <tau>) = 7 a / 12:
the estimators of model I's and model Ib's renewal lengths rest on it (``compare``'s parameter extraction and
:mod:`reduced_models.multiscale_fit`).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["autocorrelation", "correlation_integral", "correlation_length", "contact_force_spectrum"]


def autocorrelation(x: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, float]:
    """(rho, dx): the unbiased autocorrelation coefficient of the force columns ``f`` (samples x columns, or one
    series) at lags of 0, 1, ... samples, averaged over columns (by FFT, zero-padded to a power of two at least twice
    the length, so no lag wraps round), and the mean step dx of the sliding distance ``x`` (uniform steps assumed;
    Units: those of x)."""
    f = np.asarray(f, dtype=float)
    f = f[:, None] if f.ndim == 1 else f
    dx = float(np.mean(np.diff(x)))
    fz = f - f.mean(axis=0)
    n = len(fz)
    nfft = 1 << int(math.ceil(math.log2(2 * n)))
    F = np.fft.rfft(fz, nfft, axis=0)
    ac = np.fft.irfft(np.abs(F) ** 2, nfft, axis=0)[:n].mean(axis=1)
    ac /= (n - np.arange(n))  # unbiased: each lag's sum over its n - lag products
    return ac / ac[0], dx


def correlation_integral(rho: np.ndarray, dx: float, max_lag_distance: float | None = None,
                         window: float | None = None) -> float:
    """Int_0^{s0} rho(s) ds by trapezoids (Units: those of dx): with ``window``, s0 is that distance (to the nearest
    lag); else s0 is the first lag where rho <= 0, or ``max_lag_distance`` if rho stays positive up to it."""
    n = len(rho)
    if window is not None:
        end = min(n - 1, int(round(window / dx)))
        return float(np.trapezoid(rho[: end + 1], dx=dx))
    m = min(n - 1, int(max_lag_distance / dx))
    seg = rho[: m + 1]
    stop = np.flatnonzero(seg <= 0)
    end = int(stop[0]) if stop.size else m
    return float(np.trapezoid(seg[: end + 1], dx=dx))


def correlation_length(x: np.ndarray, f: np.ndarray, max_lag_distance: float, window: float | None = None) -> float:
    """Int_0^{s0} rho(s) ds (Units: those of x) of the force columns ``f`` against the sliding distance ``x``
    (:func:`autocorrelation`, :func:`correlation_integral`): up to the first zero of rho or ``max_lag_distance``, or,
    given ``window``, up to exactly that distance."""
    rho, dx = autocorrelation(x, f)
    return correlation_integral(rho, dx, max_lag_distance, window)


def contact_force_spectrum(v, a, amp, omega, closure):
    """C_f of one contact's renewing force, eq. (A8) (Units: N^2 s); closure as in
    :func:`reduced_models.multiscale.theory_spectrum`."""
    w = np.asarray(omega, dtype=float)
    tau0 = a / v
    if closure == "cumulant":
        mean_cos = np.exp(-(tau0**2 / 6.0) * w**2 / 2.0) * np.cos(w * tau0)
    elif closure == "exact":
        mean_cos = np.cos(w * tau0) * np.sinc(w * tau0 / (2 * np.pi)) ** 2
    else:
        raise ValueError(f"closure must be 'cumulant' or 'exact' (got {closure!r})")
    return v / (12.0 * np.pi * a) * amp**2 / w**2 * (1.0 - mean_cos)
