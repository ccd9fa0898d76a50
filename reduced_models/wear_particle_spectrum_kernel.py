"""The sum of eq. (B2) over the quadrature nodes of model II's closed form (:mod:`reduced_models.wear_particle`),
numba, parallel over the frequencies. Computation only; the physics and the quadrature are documented in
:mod:`reduced_models.wear_particle` and :mod:`reduced_models.wear_particle_quadrature`."""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["LORENTZ", "CUMULANT", "TABLE", "one_minus_cos", "b2_sum", "telegraph_sum", "closure_terms"]

# How 1 - <cos omega T> of one duration law is evaluated at x = omega tau:
LORENTZ = 0   # exponential durations, exact: 1 - 1/(1 + x^2) = x^2 / (1 + x^2)
CUMULANT = 1  # 1 - exp(-s x^2 / 2) cos x: "fixed" durations exactly (s = 0), or the paper's cumulant closure
TABLE = 2     # one mean time only (a Pareto law): 1 - <cos omega T> given per frequency


@numba.njit(cache=True)
def one_minus_cos(mode, s, tab, x):
    """1 - <cos omega T> at x = omega tau for evaluation ``mode`` (module constants), cumulant factor ``s`` and
    tabulated value ``tab``; 1 - cos x is written 2 sin^2(x/2), free of cancellation at small x."""
    if mode == 0:
        x2 = x * x
        return x2 / (1.0 + x2)
    if mode == 1:
        a = 0.5 * s * x * x
        h = math.sin(0.5 * x)
        return -math.expm1(-a) + math.exp(-a) * 2.0 * h * h
    return tab


def _b2_loop(w, T, K, c2, mode, s, tab, out):
    for i in numba.prange(w.shape[0]):
        wi = w[i]
        tab_i = tab[i] if mode == TABLE else 0.0  # the table has one entry per frequency in mode TABLE only
        acc = 0.0
        for j in range(T.shape[0]):
            acc += K[j] * c2[j] * one_minus_cos(mode, s, tab_i, wi * T[j])
        out[i] += acc / (wi * wi)


# the same loop compiled twice: parallel over the frequencies for large sums; serial for small ones, where starting
# the threads costs more than the sum (18 ms against 0.1 ms for 384 frequencies x 60 times on a loaded machine)
_b2_parallel = numba.njit(parallel=True, cache=True)(_b2_loop)
_b2_serial = numba.njit(cache=True)(_b2_loop)
_PARALLEL_ABOVE = 2_000_000  # terms (frequencies x times)


def b2_sum(w, T, K, c2, mode, s, tab, out):
    """out[i] += sum_j K_j c2_j g(w_i T_j) / w_i^2, g = 1 - <cos omega T>, one state's half of the quadrature of
    eq. (B2) without its prefactor N / pi: ``T`` the distinct mean times of that state (Units: s), ``K`` their
    quadrature weights already divided by tau + tau' and summed over the other state's times, ``c2`` the squared
    force at each (Units: N^2); ``tab`` holds g per frequency for mode TABLE."""
    kernel = _b2_parallel if w.shape[0] * T.shape[0] > _PARALLEL_ABOVE else _b2_serial
    kernel(w, T, K, c2, mode, s, tab, out)


@numba.njit(parallel=True, cache=True)
def telegraph_sum(w, WK, tc, out):
    """out[i] = sum_j WK_j tc_j / (pi (1 + w_i^2 tc_j^2)), the random telegraph's Lorentzians with weights ``WK``
    (quadrature weight times (c_A - c_B)^2 p_A p_B) and correlation times ``tc`` (Units: s)."""
    for i in numba.prange(w.shape[0]):
        wi = w[i]
        acc = 0.0
        for j in range(tc.shape[0]):
            acc += WK[j] * tc[j] / (math.pi * (1.0 + (wi * tc[j]) ** 2))
        out[i] = acc


def closure_terms(law, closure: str, w: np.ndarray, tau: np.ndarray):
    """How :func:`b2_sum` evaluates 1 - <cos omega T> for ``law`` (a
    :class:`~reduced_models.wear_particle.DurationLaw`; ``tau`` its distinct mean times, Units: s):
    (mode, cumulant factor s, per-frequency table). The exact closure is 1/(1 + x^2) for exponential durations and
    cos x for fixed ones (the cumulant form with s = 0); a Pareto law has one mean time, so its <cos omega T> is
    tabulated per frequency. The cumulant closure is exp(-s x^2 / 2) cos x with s tau^2 the durations' variance."""
    none = np.zeros(1)
    if closure == "exact":
        if law.kind == "exponential":
            return LORENTZ, 0.0, none
        if law.kind == "fixed":
            return CUMULANT, 0.0, none
        return TABLE, 0.0, 1.0 - law.mean_cos(w, np.full(len(w), tau[0]))
    if law.kind == "exponential":
        return CUMULANT, 1.0, none
    if law.kind == "fixed":
        return CUMULANT, 0.0, none
    a = law.shape
    return CUMULANT, (1.0 / (a * (a - 2)) if a > 2 else math.inf), none
