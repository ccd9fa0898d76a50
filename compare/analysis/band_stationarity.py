"""The band test of stationarity: whether a record's two halves share one spectrum, band by band, without a model.

The record is cut into halves; each half's twice-differenced periodogram (:func:`compare.analysis.family_fit.
record_for`) is averaged over ``bands`` log-spaced bands from the half's lowest frequency to Nyquist, and each band's
ratio r_b = B2 / B1 (second half over first) is tested.

Reference. With independent exponential ordinates, m_b of them in each half's band, r_b follows F(2 m_b, 2 m_b)
exactly, and ln r_b has variance 2 psi'(m_b) (psi' the trigamma function: 3.29 for one ordinate, 2 / m_b for many).
A mechanism's record need not be Gaussian noise: model I's contact renewals move a whole band's level together (the
level of N T v / a renewals scatters by sqrt(1.8 / (N T v / a)) whatever the band's width), which no count of
ordinates averages away. That extra variance tau^2 of a band's log level scales as 1 / length, and it is measured on
the record itself: the two quarters of each half give e = ln(Q2 / Q1) and ln(Q4 / Q3), of variance
2 psi'(m_q) + 2 tau_q^2, where the halves' ln r_b has 2 psi'(m_b) + tau_q^2 (tau_h^2 = tau_q^2 / 2). tau_q^2 is
estimated from the bands of at least :data:`MIN_ORDINATES` quarter ordinates (where psi' is small and the estimate
precise) and clipped at 0. Each band's p-value is that of F(2 m', 2 m') with 2 psi'(m') = 2 psi'(m_b) + tau_q^2
(m' = m_b when tau_q = 0: the exact law); a band is flagged when its p-value is below level / bands (Bonferroni)
and its ratio beyond :data:`FACTOR` either way.

Ordinates inside ``skirts`` (a removed line's skirt, :func:`compare.analysis.lines.remove_lines`: the line mixed
with the block's noise, different in each half) are left out of every band, as they are of the families'
likelihood.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import optimize, special, stats

from .family_fit import record_for

__all__ = ["stationarity", "FACTOR", "MIN_ORDINATES"]

FACTOR = 1.5  # a band is flagged only when its halves' levels differ by more than this factor
MIN_ORDINATES = 16  # quarter ordinates a band needs to enter the estimate of the level scatter tau_q^2


def _band_sums(record, edges, skirts):
    """Per band: the number of ordinates and the sum of the periodogram, skirts left out."""
    w, p = record.omega, record.periodogram
    keep = np.ones(len(w), bool)
    for lo, hi in skirts:
        keep &= ~((w >= lo) & (w <= hi))
    keep &= (w >= edges[0]) & (w <= edges[-1])
    idx = np.searchsorted(edges[1:-1], w[keep], side="right")
    nb = len(edges) - 1
    return np.bincount(idx, minlength=nb).astype(float), np.bincount(idx, weights=p[keep], minlength=nb)


def _m_effective(m: float, extra: float) -> float:
    """The m' whose log-F variance 2 psi'(m') is 2 psi'(m) + extra."""
    if extra <= 0:
        return m
    target = float(special.polygamma(1, m)) + extra / 2
    # psi'(m') = target; psi'(u) ~ 1/u for large u, 1/u^2 for small: bracket and solve
    return optimize.brentq(lambda u: float(special.polygamma(1, u)) - target, 1e-6, m)


def stationarity(x, dt: float, bands: int = 8, level: float = 0.01, skirts=()) -> dict:
    """Whether a record's two halves share one spectrum (module docstring: the band test).

    Parameters
    ----------
    x : array_like
        The record (Units: m).
    dt : float
        Sampling step (Units: s).
    bands : int, optional
        Number of log-spaced bands from each half's lowest frequency to Nyquist.
    level : float, optional
        Family-wise level (Bonferroni over the bands).
    skirts : sequence of (float, float), optional
        Frequency spans left out (rad/s): removed lines' skirts.

    Returns
    -------
    dict
        ``stationary`` (bool: no band differs both significantly and by more than :data:`FACTOR`), ``ratios``
        (second half over first, per band), ``p_values`` (per band, before Bonferroni), ``level_scatter`` (tau_q,
        the quarters' relative level scatter beyond Gaussian noise, on the log scale) and ``bands`` (rad/s).
    """
    x = np.asarray(x, dtype=float)
    h = len(x) // 2
    q = h // 2
    halves = [record_for(x[i * h:(i + 1) * h], dt) for i in range(2)]
    quarters = [record_for(x[i * q:(i + 1) * q], dt) for i in range(4)]
    w = halves[0].omega
    edges = np.geomspace(w[0], w[-1] * (1 + 1e-12), bands + 1)
    (m1, s1), (m2, s2) = (_band_sums(r, edges, skirts) for r in halves)
    m = np.minimum(m1, m2)
    ok = (m > 0) & (s1 > 0) & (s2 > 0)
    ratio = np.where(ok, (s2 / np.maximum(m2, 1)) / np.where(s1 > 0, s1 / np.maximum(m1, 1), 1.0), np.nan)
    # the quarters' level scatter beyond Gaussian noise, from the bands they resolve well
    terms = []
    qs = [_band_sums(r, edges, skirts) for r in quarters]
    for (ma, sa), (mb, sb) in ((qs[0], qs[1]), (qs[2], qs[3])):
        mq = np.minimum(ma, mb)
        use = (mq >= MIN_ORDINATES) & (sa > 0) & (sb > 0)
        e = np.log((sb[use] / mb[use]) / (sa[use] / ma[use]))
        terms.extend(e * e - 2 * special.polygamma(1, mq[use]))
    tau2 = max(0.0, float(np.mean(terms)) / 2) if terms else 0.0
    p = np.ones(bands)
    for b in np.flatnonzero(ok):
        me = _m_effective(float(m[b]), tau2)
        cdf = float(stats.f.cdf(ratio[b], 2 * me, 2 * me))
        p[b] = min(1.0, 2 * min(cdf, 1 - cdf))
    bad = ok & (p < level / bands) & (np.abs(np.log(np.where(ok, ratio, 1.0))) > math.log(FACTOR))
    return {"stationary": not bool(bad.any()), "ratios": [float(r) for r in ratio], "p_values": [float(v) for v in p],
            "level_scatter": math.sqrt(tau2), "bands": [[float(edges[i]), float(edges[i + 1])] for i in range(bands)]}
