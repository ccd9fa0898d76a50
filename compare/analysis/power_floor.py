"""The likelihood of a power law plus a white floor, profiled (module ``compare.analysis.power_floor``): the engine of
:func:`compare.analysis.record_model.fit_record`.

For a record's differenced periodogram (:class:`compare.analysis.whittle.WhittleRecord`) and the model
C^(s)(omega) = A sum_m abs(omega + 2 pi m / dt)^-gamma + B, :class:`PowerFloorProfile` gives the debiased Whittle
negative log-likelihood with A and the floor's share at their best for each gamma (A in closed form, the share by a
bounded one-dimensional search), so :func:`minimum` and :func:`interval` work on a function of gamma alone.
:func:`bend_p` is the score test for changes of slope, :func:`level_cov` the Fisher covariance of (gamma, ln A).
"""
from __future__ import annotations

import math

import numpy as np
from scipy import optimize, stats

from .whittle import WhittleRecord

__all__ = ["PowerFloorProfile", "minimum", "interval", "bend_p", "level_cov", "keep_band", "above_rounding"]

_CHI2_95 = float(stats.chi2.ppf(0.95, 1))
_RATIO_RANGE = (-100.0, 100.0)  # ln of the floor's share of the mean expected periodogram: a floor that meets an
# omega^-gamma law mid-band has a share of about (n / 2)^(gamma / 2) (e^30 at gamma 6 and 2^16 samples)


def _hurwitz_tail(q: np.ndarray, gamma: float) -> np.ndarray:
    """zeta(gamma, q) for q >= 3 by Euler-Maclaurin, to the q^(-gamma-3) term; the next term, below
    gamma (gamma + 1) ... (gamma + 4) q^(-gamma-5) / 30240, is under 1e-6 of the folded sum (>= 2^gamma) for
    1 < gamma <= 13."""
    return (q ** (1.0 - gamma) / (gamma - 1.0) + 0.5 * q**-gamma + gamma / 12.0 * q ** (-gamma - 1.0)
            - gamma * (gamma + 1.0) * (gamma + 2.0) / 720.0 * q ** (-gamma - 3.0))


def above_rounding(e: np.ndarray) -> np.ndarray:
    """An expected periodogram with ordinates below the FFT's rounding (1e-13 of its largest: a differenced floor's
    omega^2k at the lowest frequencies of a long record) raised to that level, so that none is zero or negative."""
    return np.maximum(e, 1e-13 * float(np.max(e)))


class PowerFloorProfile:
    """The power law + floor likelihood of one (or two equally long) differenced periodograms, profiled over A and
    the floor for each gamma.

    Parameters
    ----------
    records : list of WhittleRecord
        One record, or equally long ones sharing the model (their periodograms averaged, the likelihood counted
        once per record).
    floor : bool
        Fit the white floor (else B = 0).
    keep : ndarray of bool, optional
        The Fourier ordinates the likelihood sums over (:func:`keep_band`); default all.
    """

    def __init__(self, records, floor: bool, keep=None):
        self.records = records
        rec = records[0]
        self.rec = rec
        self.floor = floor
        self.count = len(records)
        self.keep = np.ones(len(rec.omega), dtype=bool) if keep is None else keep
        self.omega = rec.omega[self.keep]
        self.P = np.mean([r.periodogram for r in records], axis=0)[self.keep]
        self.m = len(self.P)
        u = rec.grid_u
        self._logs = [np.log(u), np.log(1.0 - u), np.log(1.0 + u), np.log(2.0 - u), np.log(2.0 + u),
                      np.log(3.0 - u)]
        self._tails = (3.0 + u, 4.0 - u)
        b = rec.white_expected()[self.keep]  # closed form: exact where the differenced floor is tiny
        self.b_mean = float(b.mean())
        self.b = b / self.b_mean
        self._cache = {}

    def fold(self, gamma: float) -> np.ndarray:
        """sum_m abs(u + m)^-gamma over all integers m, u in (0, 1/2] (the power law folded at Nyquist)."""
        s = sum(np.exp(-gamma * lg) for lg in self._logs)
        return s + _hurwitz_tail(self._tails[0], gamma) + _hurwitz_tail(self._tails[1], gamma)

    def unit(self, gamma: float):
        """(a / mean(a), mean(a)): the expected periodogram of omega^-gamma with A = (2 pi / dt)^gamma."""
        hit = self._cache.get(gamma)
        if hit is None:
            full = self.rec.memo.get(("power", gamma))
            if full is None:
                full = above_rounding(self.rec.expected_from_grid(self.fold(gamma)))
                if len(self.rec.memo) * full.size > 2**23:  # 64 MB of kept vectors at most
                    self.rec.memo.clear()
                self.rec.memo[("power", gamma)] = full
            a = full[self.keep]
            am = float(a.mean())
            hit = (a / am, am)
            if len(self._cache) > 256:
                self._cache.clear()
            self._cache[gamma] = hit
        return hit

    def _nll_ratio(self, a, t):
        S = a + (math.exp(t) * self.b if t is not None else 0.0)
        return self.m * math.log(float(np.mean(self.P / S))) + float(np.sum(np.log(S)))

    def at(self, gamma: float):
        """(nll, ln ratio or None): the negative log-likelihood with A and the floor at their best for ``gamma``."""
        a, _ = self.unit(gamma)
        best = (self._nll_ratio(a, None), None)
        if self.floor:
            grid = np.linspace(*_RATIO_RANGE, 41)
            vals = [self._nll_ratio(a, t) for t in grid]
            i = int(np.argmin(vals))
            if vals[i] < best[0]:
                lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
                r = optimize.minimize_scalar(lambda t: self._nll_ratio(a, t), bounds=(lo, hi), method="bounded",
                                             options={"xatol": 1e-6})
                if r.fun < best[0]:
                    best = (float(r.fun), float(r.x))
        return self.count * (best[0] + self.m), best[1]

    def levels(self, gamma: float, t):
        """(A, B) in the record's units for ``gamma`` and the ln floor share ``t`` (None: no floor)."""
        a, am = self.unit(gamma)
        S = a + (math.exp(t) * self.b if t is not None else 0.0)
        alpha = float(np.mean(self.P / S))
        A = alpha / am * (2.0 * math.pi / self.rec.dt) ** gamma
        B = 0.0 if t is None else alpha * math.exp(t) / self.b_mean
        return A, B


def minimum(prof: PowerFloorProfile, lo: float, hi: float, start: float | None):
    """(gamma, nll, ln ratio) at the profile's minimum on [lo, hi]: a coarse scan, then Brent around its best."""
    grid = np.linspace(lo, hi, 13)
    if start is not None and lo < start < hi:
        grid = np.sort(np.append(grid, start))
    vals = [prof.at(g)[0] for g in grid]
    i = int(np.argmin(vals))
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    r = optimize.minimize_scalar(lambda g: prof.at(g)[0], bounds=(a, b), method="bounded", options={"xatol": 1e-5})
    g = float(r.x) if r.fun <= vals[i] else float(grid[i])
    nll, t = prof.at(g)
    return g, nll, t


def interval(prof: PowerFloorProfile, g: float, nll: float, lo: float, hi: float) -> tuple[float, float, bool, bool]:
    """The 95 % profile interval around g on [lo, hi]: (low, high, low reached the wall, high reached the wall)."""
    cut = nll + 0.5 * _CHI2_95

    def excess(x):
        return prof.at(x)[0] - cut

    h = 1e-2
    curv = (prof.at(min(g + h, hi))[0] - 2 * nll + prof.at(max(g - h, lo))[0]) / h**2
    step = 2.0 / math.sqrt(curv) if curv > 0 else 0.5
    out = []
    for sign, wall in ((-1.0, lo), (1.0, hi)):
        inner, s = g, step
        while True:
            trial = g + sign * s
            trial = max(trial, wall) if sign < 0 else min(trial, wall)
            if excess(trial) > 0:
                out.append((optimize.brentq(excess, min(inner, trial), max(inner, trial), xtol=1e-5), False))
                break
            if trial == wall:
                out.append((wall, True))
                break
            inner, s = trial, 2.0 * s
    return out[0][0], out[1][0], out[0][1], out[1][1]


def bend_p(prof: PowerFloorProfile, gamma: float, t) -> float:
    """p-value of Rao's efficient-score test for changes of slope within the band, at the fit.

    Under the model each r_j = I_j / Ibar_j has mean 1 and variance 1 / count (nearly independent ordinates of a
    nearly flat differenced spectrum), and a parameter theta's score is sum (r_j - 1) d ln Ibar_j / d theta. The
    alternative adds a change of exponent at knots kappa every half decade inside the band: the power law times
    prod (omega / kappa)_+^-delta, whose derivatives at delta = 0 are f_j ln(omega_j / kappa)_+ (f_j the power
    law's share of Ibar_j). With X the derivatives for (gamma, ln A, floor) and Q those of the knots made orthogonal
    to X, the statistic s^T (Q^T Q / count)^-1 s (s = Q^T (r - 1)) is chi2 with one degree per knot under the model.
    """
    a, _ = prof.unit(gamma)
    share = math.exp(t) if t is not None else 0.0
    S = a + share * prof.b
    f = a / S
    h = 1e-3
    dlna = (np.log(prof.unit(gamma + h)[0]) - np.log(prof.unit(gamma - h)[0])) / (2 * h)
    lw = np.log(prof.omega)
    cols = [f * dlna, np.ones_like(f)]
    if prof.floor:
        cols.append(prof.b / S)
    X = np.column_stack(cols)
    decades = (lw[-1] - lw[0]) / math.log(10)
    n_knots = max(1, int(math.floor(2 * decades)) - 1)
    knots = lw[0] + (lw[-1] - lw[0]) * np.arange(1, n_knots + 1) / (n_knots + 1)
    Q = np.column_stack([f * np.maximum(lw - kn, 0.0) for kn in knots])
    Q = Q - X @ np.linalg.lstsq(X, Q, rcond=None)[0]
    alpha = float(np.mean(prof.P / S))
    r = prof.P / (alpha * S)
    score = Q.T @ (r - 1.0)
    V = Q.T @ Q / prof.count
    try:
        stat = float(score @ np.linalg.solve(V, score))
    except np.linalg.LinAlgError:
        return 1.0
    return float(stats.chi2.sf(stat, len(knots)))


def level_cov(prof: PowerFloorProfile, gamma: float, t) -> tuple:
    """(var gamma, cov(gamma, ln A), var ln A) from the Whittle Fisher information at the fit, the floor profiled out:
    F = X^T X count, X_j = d ln Ibar_j / d(gamma, ln A, B) (A the physical prefactor)."""
    a, am = prof.unit(gamma)
    share = math.exp(t) if t is not None else 0.0
    S = a + share * prof.b
    f = a / S
    h = 1e-3
    raw = [np.log(prof.unit(g)[0] * prof.unit(g)[1]) for g in (gamma + h, gamma - h)]
    dlnraw = (raw[0] - raw[1]) / (2 * h) - math.log(2.0 * math.pi / prof.rec.dt)
    cols = [f * dlnraw, f]
    if prof.floor:
        cols.append(prof.b / S)
    X = np.column_stack(cols)
    try:
        cov = np.linalg.inv(X.T @ X * prof.count)
    except np.linalg.LinAlgError:
        return ()
    return float(cov[0, 0]), float(cov[0, 1]), float(cov[1, 1])


def keep_band(rec: WhittleRecord, band):
    """The Fourier ordinates inside ``band`` (rad/s), or all of them; ValueError when fewer than 8 are inside."""
    if band is None:
        return None
    lo, hi = map(float, band)
    if not 0 < lo < hi:
        raise ValueError(f"band must satisfy 0 < low < high (got {band!r})")
    keep = (rec.omega >= lo * (1 - 1e-12)) & (rec.omega <= hi * (1 + 1e-12))
    if keep.sum() < 8:
        raise ValueError(f"band ({lo:.4g}, {hi:.4g}) rad/s holds {int(keep.sum())} Fourier frequencies of the record "
                         f"(they run from {rec.omega[0]:.4g} to {rec.omega[-1]:.4g} rad/s in steps of "
                         f"{rec.omega[0]:.4g}); widen it to at least 8, or leave --band out")
    return keep
