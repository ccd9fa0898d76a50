"""The likelihood of a power law plus a white floor, profiled (module ``compare.analysis.power_floor``): the engine of
:func:`compare.analysis.record_model.fit_record`.

For a record's differenced periodogram (:class:`compare.analysis.whittle.WhittleRecord`) and the model
C^(s)(omega) = A sum_m abs(omega + 2 pi m / dt)^-gamma + B (a discrete-time record's: A (2 sin(omega dt / 2) /
dt)^-gamma + B), :class:`PowerFloorProfile` gives the debiased Whittle
negative log-likelihood with A and the floor's share at their best for each gamma (A in closed form, the share by a
bounded one-dimensional search), so :func:`minimum` and :func:`interval` work on a function of gamma alone.
:func:`bend_p` is the score test for changes of slope, :func:`level_cov` the Fisher covariance of (gamma, ln A).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.polynomial import chebyshev
from scipy import optimize, stats

from .whittle import WhittleRecord

__all__ = ["PowerFloorProfile", "minimum", "interval", "bend_p", "level_cov", "keep_band", "above_rounding"]

_CHI2_95 = float(stats.chi2.ppf(0.95, 1))
INTERPOLATE_FROM = 2**14  # samples from which minimum() and interval() search on an interpolant in gamma
INTERPOLATION_TOL = 1e-3  # nll units: an interpolant this far off moves gamma and its ends by < 1e-3 of the half-width
# (an error e in the nll shifts an end by e / slope, the slope there being about 3.84 / half-width)
_RATIO_RANGE = (-100.0, 100.0)  # ln of the floor's share of the mean expected periodogram: a floor that meets an
# omega^-gamma law mid-band has a share of about (n / 2)^(gamma / 2) (e^30 at gamma 6 and 2^16 samples)


def _hurwitz_tail(q: np.ndarray, log_q: np.ndarray, gamma: float) -> np.ndarray:
    """zeta(gamma, q) for q >= 3 by Euler-Maclaurin, to the q^(-gamma-3) term; the next term, below
    gamma (gamma + 1) ... (gamma + 4) q^(-gamma-5) / 30240, is under 1e-6 of the folded sum (>= 2^gamma) for
    1 < gamma <= 13. ``log_q`` is ln q: one exponential per call."""
    c3 = gamma * (gamma + 1.0) * (gamma + 2.0) / 720.0
    inv_q = 1.0 / q
    return np.exp(-gamma * log_q) * (q / (gamma - 1.0) + 0.5 + inv_q * (gamma / 12.0 - c3 * inv_q * inv_q))


def _fold_table(rec: WhittleRecord) -> tuple:
    """The logarithms of u, 1 - u, 1 + u, 2 - u, 2 + u, 3 - u and of the Hurwitz tails' q = 3 + u, 4 - u on the
    record's fine grid: computed once per record and kept on it."""
    table = rec.__dict__.get("_power_fold_table")
    if table is None:
        u = rec.grid_u
        logs = [np.log(u), np.log(1.0 - u), np.log(1.0 + u), np.log(2.0 - u), np.log(2.0 + u), np.log(3.0 - u)]
        tails = [np.log(3.0 + u), np.log(4.0 - u)]
        table = rec.__dict__["_power_fold_table"] = (logs, tails)
    return table


def _sine_log(rec: WhittleRecord) -> np.ndarray:
    """ln(sin(pi u) / pi) on the record's fine grid, computed once per record and kept on it."""
    table = rec.__dict__.get("_sine_log")
    if table is None:
        table = rec.__dict__["_sine_log"] = np.log(np.sin(np.pi * rec.grid_u) / np.pi)
    return table


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
        b = rec.white_expected()[self.keep]  # closed form: exact where the differenced floor is tiny
        self.b_mean = float(b.mean())
        self.b = b / self.b_mean
        self._cache = {}
        self._local = None

    def fold(self, gamma: float) -> np.ndarray:
        """sum_m abs(u + m)^-gamma over all integers m, u in (0, 1/2] (the power law folded at Nyquist); for a
        discrete-time record (``rec.discrete``) (sin(pi u) / pi)^-gamma, the same law's discrete form
        (2 sin(omega dt / 2) / dt)^-gamma in these units, which it equals as u -> 0."""
        if self.rec.discrete:
            return np.exp(-gamma * _sine_log(self.rec))
        logs, tails = _fold_table(self.rec)
        s = sum(np.exp(-gamma * lg) for lg in logs)
        u = self.rec.grid_u
        return s + _hurwitz_tail(3.0 + u, tails[0], gamma) + _hurwitz_tail(4.0 - u, tails[1], gamma)

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

    def interpolate(self, lo: float, hi: float, nodes: int) -> None:
        """From now on take ``unit(gamma)`` for gamma in [lo, hi] from a Chebyshev interpolant of ln a_j through
        ``nodes`` exact evaluations (Chebyshev points of [lo, hi]); ``interpolate(0, 0, 0)`` ends it. ln a_j is an
        analytic function of gamma on a window away from gamma = 1 (the folded sum's pole), so the interpolant
        converges geometrically with the nodes; :func:`minimum` and :func:`interval` check it against exact
        evaluations at their results."""
        if nodes <= 0:
            self._local = None
            return
        x = np.cos(math.pi * (np.arange(nodes) + 0.5) / nodes)
        mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        vals = []
        for g in mid + half * x:
            a, am = self.unit(float(g))
            vals.append(np.log(a) + math.log(am))
        self._local = (lo, hi, mid, half, chebyshev.chebfit(x, np.array(vals), nodes - 1))

    def interpolate_through(self, nodes) -> None:
        """:meth:`interpolate` through given gammas (sorted, distinct; exact values of :meth:`unit` kept from a
        scan cost nothing)."""
        nodes = np.asarray(nodes, dtype=float)
        lo, hi = float(nodes[0]), float(nodes[-1])
        mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
        vals = []
        for g in nodes:
            a, am = self.unit(float(g))
            vals.append(np.log(a) + math.log(am))
        self._local = (lo, hi, mid, half, chebyshev.chebfit((nodes - mid) / half, np.array(vals), len(nodes) - 1))

    def _unit_at(self, gamma: float):
        """:meth:`unit`, or its interpolant inside the window of :meth:`interpolate`."""
        w = self._local
        if w is None or not w[0] <= gamma <= w[1]:
            return self.unit(gamma)
        a = np.exp(chebyshev.chebval((gamma - w[2]) / w[3], w[4]))
        am = float(a.mean())
        return a / am, am

    def exact_at(self, gamma: float):
        """:meth:`at` with the exact expected periodogram (no interpolant)."""
        w, self._local = self._local, None
        try:
            return self.at(gamma)
        finally:
            self._local = w

    def _nll_ratio(self, a, t):
        S = a + (math.exp(t) * self.b if t is not None else 0.0)
        return self.m * math.log(float(np.mean(self.P / S))) + float(np.sum(np.log(S)))

    def at(self, gamma: float):
        """(nll, ln ratio or None): the negative log-likelihood with A and the floor at their best for ``gamma``."""
        a, _ = self._unit_at(gamma)
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


def _interpolating(prof: PowerFloorProfile) -> bool:
    """Whether :func:`minimum` and :func:`interval` search on an interpolant (:meth:`PowerFloorProfile.interpolate`):
    for records of at least :data:`INTERPOLATE_FROM` samples, where an exact expected periodogram (two FFTs of the
    record's length and four times it) costs more than the profile's floor search."""
    return prof.rec.n >= INTERPOLATE_FROM


def _chebyshev_window(prof: PowerFloorProfile, lo: float, hi: float) -> None:
    """An interpolant on [lo, hi] with one node per 0.15 in gamma, at least five (the nll of an interpolant through
    five nodes over 0.66 is within 1e-7 of the exact one on a long record)."""
    prof.interpolate(lo, hi, max(5, int(math.ceil((hi - lo) / 0.15))))


def minimum(prof: PowerFloorProfile, lo: float, hi: float, start: float | None):
    """(gamma, nll, ln ratio) at the profile's minimum on [lo, hi]: a coarse scan, then Brent around its best.

    For a long record (:func:`_interpolating`) Brent runs on an interpolant of the expected periodogram over the
    bracket, through the scan's three points and two more; the nll returned is the exact one at the result, and when
    it differs from the interpolant's by more than :data:`INTERPOLATION_TOL` the search is repeated exactly. The
    interpolant is left on the profile for :func:`interval`, which ends it."""
    grid = np.linspace(lo, hi, 13)
    if start is not None and lo < start < hi:
        grid = np.sort(np.append(grid, start))
    vals = [prof.exact_at(g)[0] for g in grid]
    i = int(np.argmin(vals))
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    if _interpolating(prof):
        m = float(grid[i]) if 0 < i < len(grid) - 1 else 0.5 * (a + b)
        prof.interpolate_through([a, 0.5 * (a + m), m, 0.5 * (m + b), b])
        r = optimize.minimize_scalar(lambda g: prof.at(g)[0], bounds=(a, b), method="bounded",
                                     options={"xatol": 1e-5})
        g = float(r.x) if r.fun <= vals[i] else float(grid[i])
        nll, t = prof.exact_at(g)
        if abs(nll - prof.at(g)[0]) <= INTERPOLATION_TOL:
            return g, nll, t  # the interpolant stays for interval()
        prof.interpolate(0.0, 0.0, 0)
    r = optimize.minimize_scalar(lambda g: prof.at(g)[0], bounds=(a, b), method="bounded", options={"xatol": 1e-5})
    g = float(r.x) if r.fun <= vals[i] else float(grid[i])
    nll, t = prof.at(g)
    return g, nll, t


def interval(prof: PowerFloorProfile, g: float, nll: float, lo: float, hi: float) -> tuple[float, float, bool, bool]:
    """The 95 % profile interval around g on [lo, hi]: (low, high, low reached the wall, high reached the wall).

    For a long record (:func:`_interpolating`) the ends are found on an interpolant over g +- 2.5 times the
    curvature's half-width (:func:`minimum`'s when it covers that, else :func:`_chebyshev_window`) and checked
    exactly: when the exact profile at either end is off the cut by more than :data:`INTERPOLATION_TOL`, the ends
    are searched again exactly."""
    h = 1e-2
    w = prof._local if _interpolating(prof) else None
    # the curvature sets the first step only; inside minimum()'s interpolant it costs no exact evaluation
    at = prof.at if w is not None and w[0] <= g - h and g + h <= w[1] else prof.exact_at
    curv = (at(min(g + h, hi))[0] - 2 * nll + at(max(g - h, lo))[0]) / h**2
    step = 2.0 / math.sqrt(curv) if curv > 0 else 0.5
    try:
        if _interpolating(prof):
            low, high = max(lo, g - 2.5 * step), min(hi, g + 2.5 * step)
            if w is None or not (w[0] <= low and high <= w[1]):
                _chebyshev_window(prof, low, high)
            ends = _ends(prof, g, nll, lo, hi, step)
            cut = nll + 0.5 * _CHI2_95
            if all(wall or abs(prof.exact_at(e)[0] - cut) <= INTERPOLATION_TOL for e, wall in ends):
                return ends[0][0], ends[1][0], ends[0][1], ends[1][1]
    finally:
        prof.interpolate(0.0, 0.0, 0)
    ends = _ends(prof, g, nll, lo, hi, step)
    return ends[0][0], ends[1][0], ends[0][1], ends[1][1]


def _ends(prof: PowerFloorProfile, g: float, nll: float, lo: float, hi: float, step: float) -> list:
    """[(low end, at the wall), (high end, at the wall)]: steps doubling from ``step`` until the profile rises
    chi2_1(0.95) / 2 above ``nll`` or reaches the wall, then brentq."""
    cut = nll + 0.5 * _CHI2_95

    def excess(x):
        return prof.at(x)[0] - cut

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
    return out


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
