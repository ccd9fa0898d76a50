"""Pre-whitening of a series before its spectral estimate (:func:`compare.analysis.spectra.series_spectrum`): the
trend removed, the number of differences chosen (given, or from a pilot slope and checked on the pre-whitened
estimate), the Welch estimate and the raw periodogram of the differenced series re-coloured by the difference
filter's exact gain, in the eq. (2) convention. Each step is appended to the caller's ``steps`` (the provenance)."""
from __future__ import annotations

import numpy as np

from .estimators import auto_order, difference_gain, line_fit, periodogram, pilot_gamma, welch

__all__ = ["detrended", "prewhitening_order", "welch_recoloured", "checked_order", "periodogram_recoloured"]


def detrended(t, y, detrend: str, quantity: str, name: str, steps: list):
    """(z, v): ``y`` less its fitted line y0 + v t ("linear"), its mean ("constant", v = 0) or as is ("none");
    what was removed goes to ``steps``."""
    if detrend == "linear":
        v, y0 = line_fit(t - t[0], y)
        z = y - (y0 + v * (t - t[0]))
        if quantity == "x":  # a position's slope is the mean sliding velocity
            steps.append(f"removed fitted line {name}0 + v t, mean velocity v = {v:.6g} m/s")
        else:  # a force's or mu's slope is a drift rate, not a velocity
            rate_unit = {"F": "N/s", "mu": "1/s"}.get(quantity, "per s")
            steps.append(f"removed fitted line {name}0 + r t, drift rate r = {v:.6g} {rate_unit}")
    elif detrend == "constant":
        v = 0.0
        z = y - y.mean()
        steps.append(f"removed mean {y.mean():.6g}")
    elif detrend == "none":
        v = 0.0
        z = y
    else:
        raise ValueError(f"detrend must be 'linear', 'constant' or 'none' (got {detrend!r})")
    return z, v


def prewhitening_order(prewhiten, z, dt: float, steps: list):
    """(k, pilot gamma or None, automatic): the number of differences taken before the Welch estimate, given
    (0-6) or chosen from a pilot slope of ``z`` ("auto")."""
    auto = prewhiten == "auto"
    pilot = None
    if auto:
        pilot = pilot_gamma(z, dt)
        k = auto_order(pilot)
        steps.append(f"pilot slope gamma ~ {pilot:.2f} -> pre-whitening order {k}")
    else:
        try:
            k = int(prewhiten)
        except (TypeError, ValueError):
            raise ValueError(f"prewhiten must be a non-negative integer or 'auto' (got {prewhiten!r})") from None
        if not 0 <= k <= 6:
            raise ValueError(f"prewhiten must be between 0 and 6 (got {k})")
    return k, pilot, auto


def welch_recoloured(z, dt: float, nperseg: int, k: int):
    """(z differenced k times, segment length, segments, omega, C): the Welch estimate of the differenced series
    in the eq. (2) convention, divided by the difference filter's gain."""
    zk = np.diff(z, n=k) / dt**k if k else z
    nps = min(nperseg, len(zk))
    f, S, n_segments = welch(zk, dt, nps)
    omega = 2.0 * np.pi * f
    C = S / (4.0 * np.pi)
    if k:
        C = C / difference_gain(omega, dt, k)
    return zk, nps, n_segments, omega, C


def checked_order(z, dt: float, nperseg: int, k: int, estimate: tuple, steps: list):
    """(k, estimate): the automatic order checked once on the pre-whitened ``estimate`` (:func:`welch_recoloured`'s
    tuple at order ``k``), and the estimate redone at the new order if it changes.

    The pilot (a short Hann estimate of the velocity) can miss by one order near the k boundaries (gamma 6 read as
    7.1-7.4 in 10 % of 2^16-sample series), and an over-differenced series (a rising spectrum) leaks through the
    rectangular window of the raw periodogram; the slope of the pre-whitened estimate itself is unbiased.
    """
    omega, C = estimate[3], estimate[4]
    keep = (omega >= 4 * omega[0]) & (omega <= omega[-1] / 16)
    if keep.sum() >= 4 and np.all(C[keep] > 0):
        refined = -float(np.polyfit(np.log(omega[keep]), np.log(C[keep]), 1)[0])
        k2 = auto_order(refined)
        if k2 != k:
            steps.append(f"slope of the order-{k} estimate gamma ~ {refined:.2f} -> pre-whitening order {k2}")
            return k2, welch_recoloured(z, dt, nperseg, k2)
    return k, estimate


def periodogram_recoloured(zk, dt: float, k: int, steps: list):
    """(d_omega, P): the raw periodogram (rectangular window) of the series differenced ``k`` times, divided by the
    difference filter's gain: the ordinates of the Whittle fit."""
    d_omega, P = periodogram(zk, dt)
    if k:
        P = P / difference_gain(d_omega * np.arange(1, len(P) + 1), dt, k)
    n_raw = int(round(2.0 * np.pi / (d_omega * dt)))
    steps.append(f"raw periodogram (rectangular window) of the {'differenced ' if k else ''}series over "
                 f"{n_raw} samples{f' (the last {len(zk) - n_raw} dropped for a fast FFT length)' if n_raw < len(zk) else ''}"
                 f", re-coloured alike: for the Whittle fit")
    return d_omega, P
