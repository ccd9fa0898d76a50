"""The record model C_x(omega) = A omega^-gamma + B, fitted by the debiased Whittle likelihood (module
``compare.analysis.record_model``).

A sampled record is the physical spectrum A omega^-gamma folded at Nyquist (exactly, by Hurwitz zeta sums) plus a
sensor's white floor B (a level of the sampled record, Units: m^2 s; rms sqrt(2 pi B / dt)). :func:`fit_record`
differences the record k times (:func:`compare.analysis.whittle.order_for` of a pilot slope, raised while the
exponent's interval reaches the order's limit 2k + 1), and maximises the debiased Whittle likelihood
(:mod:`compare.analysis.whittle`) over all Fourier ordinates: A and the floor's share are profiled out exactly for
each gamma, so the likelihood is a function of gamma alone, and the 95 % interval is where twice its rise stays
below chi2_1(0.95) = 3.84. The floor is bounded at zero, not log-parametrised, so a record without one is fitted at
B = 0 and the interval stays valid there.

Reported with the exponent: the **identified band**, from the lowest fitted Fourier frequency to where the power law
falls to the floor (omega_x = (A / B)^(1/gamma), or the highest when the floor never takes over); the floor and its
crossover; a **bend test** (Rao's efficient score for changes of the exponent at knots every half decade inside the
band, :func:`_bend_p`); and a **split-half test** of stationarity: the model fitted to each half of the record apart
and to both with shared parameters, twice the log-likelihood gain chi2 with 3 degrees of freedom (2 without a floor).

Without a band given, a record whose spectrum bends (bend test p < :data:`TEST_LEVEL`: a corner, the other side of a
crossover between mechanisms) is fitted over a narrower band: a quarter decade is taken off the end whose removal
leaves the larger p-value, until the test passes or the band would span less than a decade. A record still failing
either test is flagged (``flags``; ``power_law`` False).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import optimize, stats

from .whittle import MAX_ORDER, WhittleRecord, order_for

__all__ = ["RecordFit", "fit_record", "TEST_LEVEL", "GAMMA_MIN", "check_record"]

TEST_LEVEL = 0.01  # the bend and split-half tests reject (and the band is narrowed, or the fit flagged) below it
GAMMA_MIN = 1.05  # a sampled omega^-gamma with gamma <= 1 has infinite variance (its folded sum diverges)
_CHI2_95 = float(stats.chi2.ppf(0.95, 1))
_Z_95 = float(stats.norm.ppf(0.975))
_HEADROOM = 0.95  # gamma < 2k + 0.95: the differenced spectrum's zero-frequency peak omega^-0.95 is still integrable
_RATIO_RANGE = (-25.0, 25.0)  # ln of the floor's share of the mean expected periodogram


def _hurwitz_tail(q: np.ndarray, gamma: float) -> np.ndarray:
    """zeta(gamma, q) for q >= 3 by Euler-Maclaurin, to the q^(-gamma-3) term; the next term, below
    gamma (gamma + 1) ... (gamma + 4) q^(-gamma-5) / 30240, is under 1e-6 of the folded sum (>= 2^gamma) for
    1 < gamma <= 13."""
    return (q ** (1.0 - gamma) / (gamma - 1.0) + 0.5 * q**-gamma + gamma / 12.0 * q ** (-gamma - 1.0)
            - gamma * (gamma + 1.0) * (gamma + 2.0) / 720.0 * q ** (-gamma - 3.0))


def _above_rounding(e: np.ndarray) -> np.ndarray:
    """An expected periodogram with ordinates below the FFT's rounding (1e-13 of its largest: a differenced floor's
    omega^2k at the lowest frequencies of a long record) raised to that level, so that none is zero or negative."""
    return np.maximum(e, 1e-13 * float(np.max(e)))


class _Profile:
    """The power law + floor likelihood of one (or two equally long) differenced periodograms, profiled over A and
    the floor for each gamma."""

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
        b = _above_rounding(rec.expected_from_grid(np.ones_like(u)))[self.keep]
        self.b_mean = float(b.mean())
        self.b = b / self.b_mean
        self._cache = {}

    def fold(self, gamma: float) -> np.ndarray:
        """sum_m |u + m|^-gamma over all integers m, u in (0, 1/2] (the power law folded at Nyquist)."""
        s = sum(np.exp(-gamma * lg) for lg in self._logs)
        return s + _hurwitz_tail(self._tails[0], gamma) + _hurwitz_tail(self._tails[1], gamma)

    def unit(self, gamma: float):
        """(a / mean(a), mean(a)): the expected periodogram of omega^-gamma with A = (2 pi / dt)^gamma."""
        hit = self._cache.get(gamma)
        if hit is None:
            a = _above_rounding(self.rec.expected_from_grid(self.fold(gamma)))[self.keep]
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
            grid = np.linspace(*_RATIO_RANGE, 11)
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


@dataclass(frozen=True)
class RecordFit:
    """A record's C_x = A omega^-gamma + B fitted by the debiased Whittle likelihood (:func:`fit_record`).

    ``gamma_low``/``gamma_high``: the 95 % profile-likelihood interval; ``gamma_err`` its half-width. ``prefactor``
    A (Units: C's unit times (rad/s)^gamma); ``floor`` B (C's unit) and ``floor_rms`` sqrt(2 pi B / dt) (the
    record's unit); ``crossover`` where A omega^-gamma = B (rad/s; inf without a floor); ``band`` the identified band
    (rad/s): from the lowest Fourier frequency to the crossover or Nyquist. ``stationarity_p``: the split-half test's
    p-value; ``bend_p``: the bend test's.
    """

    gamma: float
    gamma_low: float
    gamma_high: float
    prefactor: float
    floor: float
    floor_rms: float
    crossover: float
    band: tuple
    order: int
    n_samples: int
    nll: float
    stationarity_p: float
    bend_p: float
    quantity: str = "x"
    flags: tuple = ()
    notes: tuple = field(default=())
    method: str = "record"
    band_auto: bool = True
    n_points: int = 0

    @property
    def gamma_err(self) -> float:
        """Half-width of the 95 % interval."""
        return 0.5 * (self.gamma_high - self.gamma_low)

    @property
    def power_law(self) -> bool:
        """False when a flag says the record is not a stationary power law (see ``flags``)."""
        return not self.flags

    @property
    def decades(self) -> float:
        """Width of the identified band (decades)."""
        return math.log10(self.band[1] / self.band[0])

    def level(self, omega):
        """The fitted power law A omega^-gamma at ``omega`` (rad/s), without the floor."""
        return self.prefactor * np.asarray(omega, dtype=float) ** (-self.gamma)

    def derived(self, power: float, factor: float, quantity: str) -> "RecordFit":
        """The fit of factor * omega^power * C (e.g. C_mu = omega^4 C_x / g^2): gamma and its interval less
        ``power``, the prefactor times ``factor``; floor, crossover and band stay those of the fitted record."""
        return replace(self, gamma=self.gamma - power, gamma_low=self.gamma_low - power,
                       gamma_high=self.gamma_high - power, prefactor=self.prefactor * factor, quantity=quantity)

    def to_dict(self) -> dict:
        """JSON-ready: every field plus ``gamma_err``, ``power_law``, ``decades`` and ``confidence``."""
        return {"gamma": self.gamma, "gamma_err": self.gamma_err, "gamma_se": self.gamma_err / 1.96, "gamma_interval": [self.gamma_low, self.gamma_high],
                "confidence": 0.95, "prefactor": self.prefactor, "floor": self.floor, "floor_rms": self.floor_rms,
                "crossover": None if math.isinf(self.crossover) else self.crossover,
                "band": [self.band[0], self.band[1]], "decades": self.decades, "differencing_order": self.order,
                "n_samples": self.n_samples, "stationarity_p": self.stationarity_p,
                "bend_p": self.bend_p, "quantity": self.quantity, "method": self.method,
                "power_law": self.power_law, "flags": list(self.flags), "notes": list(self.notes),
                "band_auto": self.band_auto, "n_points": self.n_points}

    def __str__(self) -> str:
        flag = f" [NOT A POWER LAW: {'; '.join(self.flags)}]" if self.flags else ""
        floor = (f"; floor {self.floor_rms:.3g} rms, over the power law above {self.crossover:.3g} rad/s"
                 if self.floor > 0 and math.isfinite(self.crossover) else
                 f"; floor {self.floor_rms:.3g} rms" if self.floor > 0 else "; no floor resolved")
        return (f"gamma = {self.gamma:.3f} +- {self.gamma_err:.3f} (95 % [{self.gamma_low:.3f}, {self.gamma_high:.3f}], "
                f"debiased Whittle) over {self.band[0]:.3g}-{self.band[1]:.3g} rad/s ({self.decades:.1f} decades)"
                f"{floor}{flag}")


def _minimise(prof: _Profile, lo: float, hi: float, start: float | None):
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


def _interval(prof: _Profile, g: float, nll: float, lo: float, hi: float) -> tuple[float, float, bool, bool]:
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


def _bend_p(prof: _Profile, gamma: float, t) -> float:
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


def _pilot(x: np.ndarray, dt: float) -> float:
    """A first slope: the Whittle fit of a power law alone to the once-differenced record's periodogram over its
    lowest decade (where a floor is least), plus 2; clipped to [GAMMA_MIN, 2 MAX_ORDER]."""
    rec = WhittleRecord(x, dt, 1)
    m = max(8, len(rec.omega) // 10)
    lw = np.log(rec.omega[:m])
    lp = np.log(np.maximum(rec.periodogram[:m], 1e-300))
    slope = float(np.polyfit(lw, lp, 1)[0])
    return float(np.clip(2.0 - slope, GAMMA_MIN + 0.1, 2 * MAX_ORDER))


def _keep(rec: WhittleRecord, band):
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


def _fit_order(x, dt, k, floor, band):
    rec = WhittleRecord(x, dt, k)
    prof = _Profile([rec], floor, _keep(rec, band))
    lo, hi = max(GAMMA_MIN, 2 * k - 3.0), 2 * k + _HEADROOM
    g, nll, t = _minimise(prof, lo, hi, None)
    g_lo, g_hi, wall_lo, wall_hi = _interval(prof, g, nll, lo, hi)
    return rec, prof, (g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi)


def _split_half_p(x, dt, k, floor, g0, band) -> float:
    """p-value of the split-half likelihood-ratio test of stationarity (module docstring)."""
    h = len(x) // 2
    halves = [WhittleRecord(x[:h], dt, k), WhittleRecord(x[h:2 * h], dt, k)]
    keep = _keep(halves[0], band) if band is not None else None
    lo, hi = max(GAMMA_MIN, 2 * k - 3.0), 2 * k + _HEADROOM
    apart = sum(_minimise(_Profile([r], floor, keep), lo, hi, g0)[1] for r in halves)
    together = _minimise(_Profile(halves, floor, keep), lo, hi, g0)[1]
    lr = max(0.0, 2.0 * (together - apart))
    return float(stats.chi2.sf(lr, 3 if floor else 2))


def _narrowed(x, dt, k, floor, omega, bend):
    """Narrow the band a quarter decade at a time from the end whose removal leaves the larger bend-test p-value,
    while the test rejects and the band spans more than a decade. Returns (record, profile, result, p, band)."""
    lo, hi = float(omega[0]), float(omega[-1])
    step = 10 ** 0.25
    best = None
    while True:
        trials = []
        for b in ((lo * step, hi), (lo, hi / step)):
            if b[1] / b[0] < 10 * (1 - 1e-9):
                continue
            rec, prof, res = _fit_order(x, dt, k, floor, b)
            trials.append((_bend_p(prof, res[0], res[2]), b, rec, prof, res))
        if not trials:
            break
        p, (lo, hi), rec, prof, res = max(trials, key=lambda tr: tr[0])
        best = (rec, prof, res, p, (lo, hi))
        if p >= TEST_LEVEL:
            break
    if best is None:
        rec, prof, res = _fit_order(x, dt, k, floor, (lo, hi))
        best = (rec, prof, res, bend, (lo, hi))
    return best


def check_record(x, name: str = "x", unit: str = "") -> None:
    """ValueError, in one line saying what would help, for a record no spectrum can be fitted to: too few samples,
    a constant channel, or one that changes in fewer than half its steps (written at the file's resolution).

    Parameters
    ----------
    x : ndarray
        The record.
    name, unit : str
        How the message names the channel and its unit.
    """
    n = len(x)
    if n < 32:
        raise ValueError(f"{name}: only {n} samples; a spectral fit needs at least 32 (a longer record)")
    steps = np.diff(x)
    if not np.any(steps):
        raise ValueError(f"{name} is constant ({x[0]:.6g} {unit}) over all {n} samples: a saturated or disconnected "
                         "sensor has no spectrum (check the channel)".replace(" )", ")"))
    still = float(np.mean(steps == 0))
    if still > 0.5:
        q = float(np.min(np.abs(steps[steps != 0])))
        raise ValueError(f"{name} stays the same in {100 * still:.0f} % of its {n - 1} steps (smallest change "
                         f"{q:.3g} {unit}): the record is at the file's resolution and its spectrum is the rounding's; "
                         "export it with more digits (a finer unit or more decimals)".replace(" )", ")"))


def fit_record(x, dt: float, *, floor: bool = True, order: int | None = None, band=None, quantity: str = "x",
               stationarity: bool = True) -> RecordFit:
    """Fit C_x = A omega^-gamma + B to a uniformly sampled record by the debiased Whittle likelihood.

    Parameters
    ----------
    x : array_like
        The record (e.g. positions, Units: m), uniformly sampled, trend removed or not (differencing removes
        polynomials of degree below k).
    dt : float
        Sampling step (Units: s).
    floor : bool, optional
        Fit a white floor B >= 0 (default); False fits the power law alone.
    order : int, optional
        Differencing order k; default from a pilot slope (:func:`compare.analysis.whittle.order_for`), raised while
        the interval reaches the order's limit 2k + 1.
    band : tuple of float, optional
        (low, high) (Units: rad/s): the likelihood over the Fourier ordinates inside only (the expectation still
        holds every frequency's leakage); default all of them.
    quantity : str, optional
        What the record is of (``"x"``, ``"F"``, ...), carried to the result.
    stationarity : bool, optional
        Run the split-half test (three more fits on the halves).

    Returns
    -------
    RecordFit
        gamma with its 95 % profile interval, A, B, the crossover, the identified band, flags and notes.
    """
    x = np.asarray(x, dtype=float)
    check_record(x, quantity)
    notes = []
    auto = band is None
    if order is None:
        k = order_for(_pilot(x, dt))
        while True:
            rec, prof, res = _fit_order(x, dt, k, floor, band)
            if res[6] and k < MAX_ORDER:
                k += 1
                continue
            if order_for(res[0]) < k:  # over-differenced: the order the estimate itself asks for
                k = order_for(res[0])
                rec, prof, res = _fit_order(x, dt, k, floor, band)
            break
    else:
        k = int(order)
        rec, prof, res = _fit_order(x, dt, k, floor, band)
    g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi = res
    bend = _bend_p(prof, g, t)
    if band is None and bend < TEST_LEVEL:
        rec, prof, res, bend, trimmed = _narrowed(x, dt, k, floor, rec.omega, bend)
        g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi = res
        notes.append(f"one power law does not fit every frequency (bend test p < {TEST_LEVEL:g}); fitted over "
                     f"{trimmed[0]:.3g}-{trimmed[1]:.3g} rad/s, the widest band where it does")
        band = trimmed
    if wall_hi or wall_lo:
        notes.append(f"the 95 % interval reaches the fitted range's {'upper' if wall_hi else 'lower'} limit "
                     f"{hi if wall_hi else lo:.2f} at differencing order {k}")
    A, B = prof.levels(g, t)
    w0, w1 = float(prof.omega[0]), float(prof.omega[-1])
    cross = (A / B) ** (1.0 / g) if B > 0 else math.inf
    band_out = (w0, float(min(cross, w1)))
    flags = []
    if band_out[1] <= w0 * 1.0001:
        notes.append("the floor lies above the power law at every fitted frequency: gamma is not identified")
        band_out = (w0, w0 * 1.0001)
    p = _split_half_p(x, dt, k, floor, g, band) if stationarity and len(x) >= 64 + 2 * k else math.nan
    if p < TEST_LEVEL:
        flags.append(f"not stationary: the halves' spectra differ (split-half likelihood ratio, p = {p:.2g})")
    if bend < TEST_LEVEL:
        flags.append(f"the spectrum bends within the band (bend test p = {bend:.2g})")
    return RecordFit(gamma=g, gamma_low=float(g_lo), gamma_high=float(g_hi), prefactor=A, floor=B,
                     floor_rms=math.sqrt(2.0 * math.pi * B / dt), crossover=cross, band=band_out, order=k,
                     n_samples=len(x), nll=nll, stationarity_p=p, bend_p=bend, quantity=quantity,
                     flags=tuple(flags), notes=tuple(notes), band_auto=auto, n_points=prof.m)
