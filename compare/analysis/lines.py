"""Spectral lines in a displacement record, found and subtracted before its spectral families are fitted: a nuisance
term of every family (a drive's or the mains' frequency, the shaken substrate of model_Iv), not a mechanism.

A deterministic sinusoid is no part of a Gaussian noise's spectrum: its power sits in one Fourier ordinate (and in
the taper's leakage about it) far above the noise, 1.7e8 times the local median on a 60 s record of model_Iv's
reference, whose leakage still stands 2e5 above it a hundred ordinates away; the Whittle likelihood of any family
then answers the line, not the noise. So a line is subtracted, not masked.

Finding: the twice-differenced periodogram (:func:`compare.analysis.family_fit.record_for`) over its running median
of :data:`WINDOW` ordinates; under a smooth spectrum an ordinate is exponential, exceeding c times the median
(ln 2 times the mean) with probability 2^-c, so an ordinate above c = log2(n / :data:`FALSE`) of n is a line at a
family-wise false-alarm rate :data:`FALSE`. Ordinates within half a window of either end are not searched (the
median there is not centred, and a corner, the renewal's or the floor's rise, stands out against it: lines below
WINDOW pi / T, 10 rad/s on a 60 s record, go unseen). The broadest features of the families (a resonance of quality Q has
half-width omega_c / (2 Q), hundreds of ordinates on a long record; the window's zeros of model III) stand no more
than a few times the median over the window.

Subtracting: the line's frequency is refined between the neighbouring ordinates by the largest tapered Fourier
amplitude of the twice-differenced record, then its amplitude and phase are fitted and subtracted by
:func:`compare.analysis.harmonics.remove_harmonics` (the fundamental alone: a harmonic that stands out is found as
a line of its own, where it aliases). At most :data:`MAX_LINES` lines are removed. A line whose amplitude or phase
wanders leaves a skirt after subtraction: model_Iv's vibration mixes with the block's noise (the friction is not
linear in the shaken speed) into sidebands standing 9-10 times the record's level within 70 rad/s of its 3000 rad/s
line (60 s records; 86-103 times the median within 1 rad/s of it). The skirt, the contiguous bins
:data:`SKIRT_BIN` wide about the line whose mean stands above :data:`SKIRT` times their neighbourhood's median, is
left out of every family's likelihood alike (:func:`compare.analysis.family_fit.without`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage, optimize, signal

from .family_fit import ORDER, record_for
from .harmonics import remove_harmonics

__all__ = ["Line", "remove_lines", "WINDOW", "FALSE", "MAX_LINES", "SKIRT", "SKIRT_BIN", "SKIRT_SPAN"]

WINDOW = 201  # ordinates of the running median a line stands out against
FALSE = 1e-3  # family-wise chance that a record without a line shows one (at 1e-2: 4 of 200 noise records)
MAX_LINES = 4
SKIRT = 1.5  # a line's skirt: bins about it whose mean stands this many times their neighbourhood's median
SKIRT_BIN = 0.005  # relative width of those bins (100 ordinates at 3000 rad/s on a 60 s record: a 10 % scatter)
SKIRT_SPAN = 51  # bins of the neighbourhood (+-12 % in frequency)


@dataclass(frozen=True)
class Line:
    """A line found and subtracted: ``omega`` (rad/s), ``amplitude`` (m, of the displacement's sinusoid) and
    ``excess`` (its ordinate over the running median, before subtraction)."""

    omega: float
    amplitude: float
    excess: float

    def to_dict(self) -> dict:
        """summary.json's form: ``omega_rad_s``, ``amplitude_m``, ``excess``."""
        return {"omega_rad_s": self.omega, "amplitude_m": self.amplitude, "excess": self.excess}


def _excess(rec) -> np.ndarray:
    """Each ordinate over the running median of :data:`WINDOW` about it; 0 within half a window of either end."""
    med = ndimage.median_filter(rec.periodogram, size=min(WINDOW, len(rec.omega) | 1), mode="nearest")
    excess = rec.periodogram / np.maximum(med, 1e-300)
    half = WINDOW // 2
    excess[:half], excess[-half:] = 0.0, 0.0  # a window whole on both sides: a corner is no line
    return excess


def _strongest(x, dt: float, skirts=()):
    """(ordinate index, its excess over the running median, the record) of the periodogram's highest excess outside
    the ``skirts`` already found ((low, high), rad/s)."""
    rec = record_for(x, dt)
    excess = _excess(rec)
    for lo, hi in skirts:
        excess[(rec.omega >= lo) & (rec.omega <= hi)] = 0.0
    j = int(np.argmax(excess))
    return j, float(excess[j]), rec


def _refine(y, dt: float, lo: float, hi: float) -> float:
    """The frequency (rad/s) in [lo, hi] of the largest Hann-tapered Fourier amplitude of the differenced series
    ``y``: within a small fraction of an ordinate's spacing."""
    h = signal.windows.hann(len(y))
    hy = h * y
    t = np.arange(len(y)) * dt

    def minus_amplitude(w):
        return -abs(np.dot(hy, np.exp(-1j * w * t)))

    res = optimize.minimize_scalar(minus_amplitude, bounds=(lo, hi), method="bounded",
                                   options={"xatol": 1e-9 * hi})
    return float(res.x)


def _skirt(rec, w: float, step: float) -> tuple:
    """The skirt (low, high) (rad/s) about a subtracted line at ``w``: the contiguous bins :data:`SKIRT_BIN` wide
    (relative) about it whose mean ordinate stands above :data:`SKIRT` times the running median of
    :data:`SKIRT_SPAN` bins about them; the line's own ordinate and two each side at least (the taper's leakage)."""
    om, I = rec.omega, rec.periodogram
    nb = max(2, int(math.log(om[-1] / om[0]) / SKIRT_BIN) + 1)
    edges = np.geomspace(om[0], om[-1] * (1 + 1e-12), nb + 1)
    idx = np.clip(np.searchsorted(edges, om, side="right") - 1, 0, nb - 1)
    cnt = np.bincount(idx, minlength=nb)
    mean = np.bincount(idx, weights=I, minlength=nb) / np.maximum(cnt, 1)
    ok = cnt > 0
    base = np.interp(np.arange(nb), np.nonzero(ok)[0],
                     ndimage.median_filter(mean[ok], size=min(SKIRT_SPAN, int(ok.sum()) | 1), mode="nearest"))
    high = ok & (mean > SKIRT * base)
    b = int(np.clip(np.searchsorted(edges, w, side="right") - 1, 0, nb - 1))
    lo = hi = b
    while lo > 0 and high[lo - 1]:
        lo -= 1
    while hi < nb - 1 and high[hi + 1]:
        hi += 1
    if lo == hi and not high[b]:  # no skirt: the taper's leakage only
        return w - 2.5 * step, w + 2.5 * step
    return min(float(edges[lo]), w - 2.5 * step), max(float(edges[hi + 1]), w + 2.5 * step)


def remove_lines(x, dt: float):
    """Find and subtract the spectral lines of record ``x`` (module docstring).

    Parameters
    ----------
    x : array_like
        Displacement record (Units: m), uniformly sampled.
    dt : float
        Sampling step (Units: s).

    Returns
    -------
    (numpy.ndarray, list of Line, list of tuple)
        The record less its lines; the lines, strongest first; and each line's skirt, (low, high) (rad/s): the
        ordinates about it that stand out still (an amplitude that wanders spreads a line), for a fit to leave out
        (:func:`compare.analysis.family_fit.without`).
    """
    x = np.asarray(x, dtype=float)
    t = np.arange(len(x)) * dt
    lines, skirts = [], []
    for _ in range(MAX_LINES):
        j, excess, rec = _strongest(x, dt, skirts)
        if excess < math.log2(len(rec.omega) / FALSE):
            break
        step = rec.omega[1] - rec.omega[0]
        y = np.diff(x, n=ORDER)[: rec.n]
        w = _refine(y, dt, rec.omega[j] - step, rec.omega[j] + step)
        x, fit = remove_harmonics(t, x, w, harmonics=1, order=ORDER)
        lines.append(Line(w, float(fit.amplitude[0]), excess))
        skirts.append(_skirt(record_for(x, dt), w, step))
    return x, lines, skirts
