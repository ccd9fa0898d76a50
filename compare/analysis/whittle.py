"""The debiased Whittle likelihood of a sampled record (module ``compare.analysis.whittle``).

Public surface: :class:`WhittleRecord` (a record's periodogram, kept once), :func:`negloglik` (the negative
log-likelihood of a model spectrum), :func:`maximum_likelihood` and :func:`profile_interval` (the fit and a
parameter's profile-likelihood interval), :func:`folded` (aliasing of a continuous model), :func:`order_for` (the
differencing order for a spectral slope).

The record ``x`` (n samples, step ``dt``) is differenced ``k`` times, ``y = diff(x, k) / dt^k``, and the periodogram
of ``y`` with a taper h (sum h_t^2 = 1; a Tukey taper, :data:`TAPER`) is taken at the Fourier frequencies
omega_j = 2 pi j / (n dt), j = 1 .. ceil(n/2) - 1, in the eq. (2) convention of Xu, Zhou & Persson (2025):
I_j = dt abs(sum_t h_t y_t e^{-i omega_j t dt})^2 / (2 pi) (h_t = n^-1/2 without a taper). A model
C_x(omega) (Units: m^2 s for a displacement) enters through the *expected* periodogram of the differenced record
(Sykulski, Olhede, Guillaumin, Lilly & Early 2019, Biometrika 106, 251, eq. 8):

.. math:: \\bar I_j = \\frac{dt}{2\\pi}\\sum_{|\\tau|<n} \\Big(\\sum_t h_t h_{t+|\\tau|}\\Big) c_y(\\tau)
          e^{-i\\omega_j\\tau dt},\\qquad
          c_y(\\tau) = \\int_{-\\pi/dt}^{\\pi/dt} \\left|\\frac{2\\sin(\\omega dt/2)}{dt}\\right|^{2k}
          C_x^{(s)}(\\omega)\\, e^{i\\omega\\tau dt}\\, d\\omega,

where C_x^{(s)} is the spectrum of the *sampled* record (the continuous one folded at the Nyquist frequency,
:func:`folded`). The expectation is exact for a finite record: the window's leakage and aliasing are in the model,
not in the data, so steep spectra need no band cut. c_y is computed by
an inverse FFT of the differenced model on a grid at least ``oversample`` times finer than the Fourier frequencies (a
periodic trapezoid rule, exact for trigonometric polynomials such as a differenced white floor); its zero-frequency
ordinate is taken from its neighbour. An error there changes c_y by a constant: that moves no Fourier ordinate j >= 1
without a taper, and with the Tukey taper only the lowest few, by that constant times the taper's spectral window.

The negative log-likelihood is the Whittle one with the debiased mean, sum_j [ln Ibar_j + I_j / Ibar_j]: every
ordinate exponential with mean Ibar_j. Differencing until the differenced spectrum is roughly flat (:func:`order_for`)
keeps the ordinates nearly uncorrelated, so the likelihood's curvature is close to the Fisher information and the
profile-likelihood interval (:func:`profile_interval`) holds its level; ``docs/results/exponent_coverage.md``
measures that.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy import fft as sp_fft
from scipy import optimize, signal, stats

from .estimators import fast_length

__all__ = ["WhittleRecord", "WhittleFit", "negloglik", "maximum_likelihood", "profile_interval", "folded",
           "order_for", "MAX_ORDER", "TAPER"]

MAX_ORDER = 6  # differences beyond six leave a record dominated by rounding of its steepest ordinates
_OVERSAMPLE = 2  # autocovariance grid of at least 2 * oversample * n points: lag aliasing at lags >= 3n, beyond the
# record; the grid is the next length the FFT transforms fast (a record of 2 * 11^2 * 3719 samples would otherwise
# make every expected periodogram ten times dearer)
# Tukey taper: a cosine over 5 % of the record at each end. It cuts the rectangular window's far sidelobes (power
# falling as 1/distance^2), through which the rising spectrum of a differenced white floor swamps the lowest ordinates
# (by about n / 25 when the floor meets an omega^-4 law mid-band), while neighbouring ordinates stay nearly
# uncorrelated: the power correlation of adjacent ones is 0.0044 (0.019 at a 20 % taper, 0.44 for Hann).
TAPER = 0.1


def order_for(gamma: float) -> int:
    """The differencing order k for a spectrum C_x ~ omega^-gamma: the smallest k >= 1 with gamma - 2k <= 1/2.

    The differenced spectrum then behaves as omega^(2k - gamma) with 2k - gamma in [-1/2, 3/2): integrable at zero
    (so its autocovariance exists) and no steeper than omega^-1/2, so its periodogram ordinates are nearly
    uncorrelated.

    Parameters
    ----------
    gamma : float
        The spectral exponent (dimensionless).

    Returns
    -------
    int
        k between 1 and :data:`MAX_ORDER`.
    """
    if not math.isfinite(gamma):
        raise ValueError(f"gamma must be finite (got {gamma!r})")
    return int(min(MAX_ORDER, max(1, math.ceil((gamma - 0.5) / 2.0))))


def folded(spectrum, dt: float, images: int = 3):
    """The sampled record's spectrum from a continuous one: C^(s)(omega) = sum_m C(abs(omega + 2 pi m / dt)).

    Parameters
    ----------
    spectrum : callable
        ``spectrum(omega, params)``: the continuous two-sided spectrum (eq. 2 convention) at omega > 0.
    dt : float
        Sampling step (Units: s).
    images : int, optional
        Images summed on each side (abs(m) <= images). A spectrum falling as omega^-gamma near Nyquist leaves out
        about (2 images + 1)^-gamma of the Nyquist level per side.

    Returns
    -------
    callable
        ``f(omega, params)`` for 0 < omega <= pi / dt.
    """
    step = 2.0 * math.pi / dt

    def f(omega, params):
        omega = np.asarray(omega, dtype=float)
        total = np.asarray(spectrum(omega, params), dtype=float).copy()
        for m in range(1, images + 1):
            total = total + spectrum(m * step + omega, params) + spectrum(m * step - omega, params)
        return total

    return f


class WhittleRecord:
    """A record's differenced periodogram and the machinery of its expected value.

    Parameters
    ----------
    x : array_like
        Uniformly sampled record (e.g. Units: m), at least 16 samples after differencing.
    dt : float
        Sampling step (Units: s).
    order : int
        Differencing order k (0-6); :func:`order_for` gives it for a slope.
    oversample : int, optional
        Fineness of the autocovariance grid (multiples of 2n).
    taper : float, optional
        Fraction of the record in the Tukey taper's cosine ends (:data:`TAPER`); 0 for none (rectangular).
    discrete : bool, optional
        The record is of a discrete-time process (a cumulative sum of random steps, a simulation's update rule), whose
        power law is (2 sin(omega dt / 2) / dt)^-gamma, rather than of a continuous one sampled, whose power law is
        folded at Nyquist (default): the form :class:`compare.analysis.power_floor.PowerFloorProfile` fits.

    Attributes
    ----------
    omega : ndarray
        Fourier frequencies omega_j (Units: rad/s), j = 1 .. ceil(n/2) - 1.
    periodogram : ndarray
        I_j of the tapered, differenced record (Units: those of x^2 s / s^2k).
    n : int
        Samples of the differenced record used (the last few dropped for a fast FFT length, at most 0.5 %).
    memo : dict
        Expected periodograms kept by their users (e.g. per exponent), so that fits over several bands of one
        record compute each once.
    """

    def __init__(self, x, dt: float, order: int, *, oversample: int = _OVERSAMPLE, taper: float = TAPER,
                 discrete: bool = False):
        x = np.asarray(x, dtype=float)
        if x.ndim != 1:
            raise ValueError(f"the record must be one-dimensional (got shape {x.shape})")
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError(f"dt must be positive (got {dt!r})")
        order = int(order)
        if not 0 <= order <= MAX_ORDER:
            raise ValueError(f"differencing order must be between 0 and {MAX_ORDER} (got {order})")
        if not np.all(np.isfinite(x)):
            raise ValueError(f"the record holds {int(np.sum(~np.isfinite(x)))} NaN/inf values")
        y = np.diff(x, n=order) / dt**order if order else x - x.mean()
        n = fast_length(len(y))
        if n < 16:
            raise ValueError(f"only {len(x)} samples: too few for a spectral fit (at least {16 + order})")
        y = y[:n]
        if not 0.0 <= taper <= 1.0:
            raise ValueError(f"taper must be a fraction between 0 and 1 (got {taper!r})")
        h = signal.windows.tukey(n, taper) if taper > 0 else np.ones(n)
        h = h / math.sqrt(float(np.sum(h * h)))  # sum h^2 = 1: the periodogram keeps the eq. (2) level
        Y = sp_fft.rfft(h * (y - np.sum(h * y) / np.sum(h)))
        m = (n + 1) // 2 - 1  # j = 1 .. ceil(n/2) - 1: every ordinate two degrees of freedom
        self.dt = float(dt)
        self.order = order
        self.n = n
        self.periodogram = (Y.real[1:m + 1] ** 2 + Y.imag[1:m + 1] ** 2) * (dt / (2.0 * math.pi))
        self.taper = float(taper)
        self.discrete = bool(discrete)
        self.omega = 2.0 * math.pi / (n * dt) * np.arange(1, m + 1)
        self.L = sp_fft.next_fast_len(2 * oversample * n, real=True)
        self._h = h
        self.memo = {}  # expected periodograms by key, shared by every fit of this record (power_floor's profiles)

    # The fine grid of the expected periodogram (:meth:`expected_from_grid`) and the taper's lag weights and Gram
    # matrix are computed when first asked for and kept: the grouped fits of compare.analysis.family_fit use the
    # periodogram only, and the grid's arrays and FFT are four times the record's length.
    @functools.cached_property
    def grid_u(self) -> np.ndarray:
        """omega dt / (2 pi) on the fine grid, (0, 1/2]."""
        return np.arange(1, self.L // 2 + 1) / self.L

    @functools.cached_property
    def grid_omega(self) -> np.ndarray:
        """The fine grid's angular frequencies (Units: rad/s)."""
        return 2.0 * math.pi * self.grid_u / self.dt

    @functools.cached_property
    def gain(self) -> np.ndarray:
        """The differencing gain (2 sin(omega dt / 2) / dt)^(2k) on the fine grid."""
        return np.abs(2.0 * np.sin(math.pi * self.grid_u) / self.dt) ** (2 * self.order)

    @functools.cached_property
    def _lag_weight(self) -> np.ndarray:
        """sum_t h_t h_{t+tau} (1 - tau/n untapered): any transform length >= 2n - 1 leaves no circular wrap, so the
        next fast one is taken."""
        size = sp_fft.next_fast_len(2 * self.n, real=True)
        H = sp_fft.rfft(self._h, size)
        return sp_fft.irfft(H.real**2 + H.imag**2, size)[: self.n]

    @functools.cached_property
    def _taper_gram(self) -> np.ndarray:
        """G_mm' of :meth:`white_expected`: the Gram matrix of the taper's backward differences (B - 1)^m h."""
        v = [np.concatenate([self._h, np.zeros(self.order)])]  # the zero-padded taper
        for _ in range(self.order):
            v.append(np.concatenate([[0.0], v[-1][:-1]]) - v[-1])
        V = np.array(v)
        return V @ V.T

    def expected_from_grid(self, values: np.ndarray) -> np.ndarray:
        """Ibar_j from the sampled record's (undifferenced) spectrum on :attr:`grid_omega` (eq. 8 of Sykulski et
        al. 2019, with the differencing gain applied here).

        Parameters
        ----------
        values : ndarray
            C_x^(s) at ``grid_omega`` (Units: those of x^2 s).

        Returns
        -------
        ndarray
            The expected periodogram at :attr:`omega`.
        """
        S = np.empty(self.L // 2 + 1)
        S[1:] = self.gain * values
        S[0] = S[1]  # the zero-frequency value (finite for 2k >= gamma) from its neighbour, one grid step away
        c = sp_fft.irfft(S, self.L)[: self.n]  # c_y(tau) dt / (2 pi): the 2 pi / dt of the integral cancels below
        F = sp_fft.rfft(c * self._lag_weight)
        return 2.0 * F.real[1: len(self.omega) + 1] - c[0]

    def white_expected(self) -> np.ndarray:
        r"""Ibar_j of a white sampled record of unit level (C_x^(s) = 1), in closed form.

        With y_t = sum_i d_i e_{t+i} (d the k-th difference) and z = exp(-i omega dt), the tapered transform is
        sum_s e_s z^s [(z^-1 S - 1)^k h]_s (S the shift h_s -> h_{s-1}, h zero outside the record), and
        z^-1 S - 1 = z^-1 (S - 1) + (z^-1 - 1), so

        .. math:: \bar I_j = dt^{-2k} \sum_{m, m'} \bar c_m c_{m'} G_{mm'},\quad
                  c_m = \binom{k}{m} z^{-m} (z^{-1} - 1)^{k - m},\quad G_{mm'} = \sum_s [(S-1)^m h]_s [(S-1)^{m'} h]_s.

        Every term is computed from small quantities (sines of omega dt / 2, differences of the taper), so the value
        keeps its relative precision where the differenced floor is 1e-20 of its Nyquist level, far below the
        rounding of the FFT route of :meth:`expected_from_grid` (about 1e-16 of the largest ordinate).

        Returns
        -------
        ndarray
            The expected periodogram at :attr:`omega` (Units: those of the level times s^-2k).
        """
        k = self.order
        half = 0.5 * self.omega * self.dt
        w = 2j * np.sin(half) * np.exp(1j * half)  # z^-1 - 1
        zinv = np.exp(1j * self.omega * self.dt)
        c = np.column_stack([math.comb(k, m) * zinv**m * w ** (k - m) for m in range(k + 1)])
        q = np.einsum("jm,mn,jn->j", c.conj(), self._taper_gram, c).real
        return q / self.dt ** (2 * k)

    def expected(self, spectrum, params, *, images: int | None = 3) -> np.ndarray:
        """Ibar_j for a model spectrum.

        Parameters
        ----------
        spectrum : callable
            ``spectrum(omega, params)``: C_x of the continuous process (Units: m^2 s for a displacement) at
            omega > 0 (rad/s); with ``images=None`` the sampled record's spectrum on (0, pi/dt] instead.
        params : sequence
            Passed to ``spectrum``.
        images : int or None, optional
            Aliasing images folded in (:func:`folded`); None when ``spectrum`` is already the sampled one.

        Returns
        -------
        ndarray
            The expected periodogram at :attr:`omega`.
        """
        f = spectrum if images is None else folded(spectrum, self.dt, images)
        return self.expected_from_grid(np.asarray(f(self.grid_omega, params), dtype=float))

    def negloglik_of(self, expected: np.ndarray) -> float:
        """sum_j [ln Ibar_j + I_j / Ibar_j] for an expected periodogram (inf where it is not positive)."""
        if not np.all(expected > 0):
            return math.inf
        return float(np.sum(np.log(expected) + self.periodogram / expected))

    def negloglik(self, spectrum, params, *, images: int | None = 3) -> float:
        """The debiased Whittle negative log-likelihood of a model (see :meth:`expected`)."""
        return self.negloglik_of(self.expected(spectrum, params, images=images))


def negloglik(x, dt: float, spectrum, params, order: int, *, images: int | None = 3) -> float:
    """Debiased Whittle negative log-likelihood of a record under a model spectrum.

    Parameters
    ----------
    x : array_like
        Uniformly sampled record (e.g. positions, Units: m).
    dt : float
        Sampling step (Units: s).
    spectrum : callable
        ``spectrum(omega, params) -> C_x`` (eq. 2 convention, Units: m^2 s for positions) of the continuous
        process at omega > 0 (rad/s); folded at Nyquist with ``images`` images (None: already the sampled one).
    params : sequence
        The model's parameters.
    order : int
        Differencing order k; the gain (2 sin(omega dt/2)/dt)^(2k) is applied to the model.
    images : int or None, optional
        Aliasing images (:func:`folded`).

    Returns
    -------
    float
        sum_j [ln Ibar_j + I_j / Ibar_j] (dimensionless up to a constant; compare only at one record and order).
    """
    return WhittleRecord(x, dt, order).negloglik(spectrum, params, images=images)


@dataclass(frozen=True)
class WhittleFit:
    """Maximum of the debiased Whittle likelihood: ``params`` and the negative log-likelihood ``nll`` there."""

    params: tuple
    nll: float
    converged: bool


def maximum_likelihood(record: WhittleRecord, spectrum, start, *, bounds=None, images: int | None = 3,
                       fixed: dict | None = None) -> WhittleFit:
    """Maximum-likelihood parameters of a model spectrum for one record.

    Parameters
    ----------
    record : WhittleRecord
        The record (its differencing order set).
    spectrum : callable
        ``spectrum(omega, params)`` as in :func:`negloglik`. Scale parameters are best passed as logarithms.
    start : sequence of float
        Starting parameters.
    bounds : sequence of (low, high), optional
        Box bounds (None for a side without one).
    images : int or None, optional
        As in :meth:`WhittleRecord.expected`.
    fixed : dict, optional
        {index: value} held fixed (the profile likelihood uses it).

    Returns
    -------
    WhittleFit
        The parameters (fixed ones included) and the negative log-likelihood.
    """
    start = np.asarray(start, dtype=float)
    fixed = dict(fixed or {})
    free = [i for i in range(len(start)) if i not in fixed]

    def full(p):
        q = start.copy()
        q[free] = p
        for i, v in fixed.items():
            q[i] = v
        return q

    def f(p):
        v = record.negloglik(spectrum, full(p), images=images)
        return v if math.isfinite(v) else 1e300

    b = None if bounds is None else [bounds[i] for i in free]
    if not free:
        q = full(np.array([]))
        return WhittleFit(tuple(map(float, q)), f(np.array([])), True)
    res = optimize.minimize(f, start[free], method="L-BFGS-B" if b is not None else "BFGS", bounds=b)
    if res.success:
        return WhittleFit(tuple(map(float, full(res.x))), float(res.fun), True)
    # a quasi-Newton stall (a flat direction, a floor at its bound): polish without gradients
    res2 = optimize.minimize(f, res.x, method="Nelder-Mead", bounds=b,
                             options={"xatol": 1e-6, "fatol": 1e-6, "maxiter": 2000})
    best = res2 if res2.fun <= res.fun else res
    return WhittleFit(tuple(map(float, full(best.x))), float(best.fun), bool(res2.success))


def profile_interval(record: WhittleRecord, spectrum, fit: WhittleFit, index: int, *, bounds=None,
                     level: float = 0.95, step: float = 0.1, images: int | None = 3) -> tuple[float, float]:
    """The profile-likelihood interval of one parameter: where 2 [nll_profile(p) - nll_min] <= chi2_1(level).

    The other parameters are re-maximised at each trial value (:func:`maximum_likelihood` with ``fixed``). A
    nuisance parameter resting on a bound (a floor of zero) is allowed: the profile is taken over the bounded
    set, which keeps the likelihood-ratio interval valid there (Self & Liang 1987), unlike a Wald interval.

    Parameters
    ----------
    record, spectrum, fit
        The record, model and its maximum-likelihood fit.
    index : int
        Which parameter.
    bounds : sequence of (low, high), optional
        The parameters' bounds; the interval stops at the parameter's own bound (returned as that bound).
    level : float, optional
        Confidence level.
    step : float, optional
        First step away from the estimate when bracketing (the parameter's units); doubled until bracketed.
    images : int or None, optional
        As in :meth:`WhittleRecord.expected`.

    Returns
    -------
    (float, float)
        Low and high ends.
    """
    cut = fit.nll + 0.5 * float(stats.chi2.ppf(level, 1))
    p_hat = fit.params[index]
    lo_b, hi_b = (-math.inf, math.inf) if bounds is None else (
        -math.inf if bounds[index][0] is None else bounds[index][0],
        math.inf if bounds[index][1] is None else bounds[index][1])

    def excess(v):
        g = maximum_likelihood(record, spectrum, fit.params, bounds=bounds, images=images, fixed={index: v})
        return g.nll - cut

    ends = []
    for sign, wall in ((-1, lo_b), (1, hi_b)):
        s = step
        inner = p_hat
        while True:
            trial = p_hat + sign * s
            if (sign < 0 and trial <= wall) or (sign > 0 and trial >= wall):
                trial = wall
            e = excess(trial)
            if e > 0:
                ends.append(optimize.brentq(excess, min(inner, trial), max(inner, trial), xtol=1e-5))
                break
            if trial == wall or s > 1e6:
                ends.append(float(trial))
                break
            inner, s = trial, 2 * s
    return float(ends[0]), float(ends[1])
