"""The band test of stationarity: whether a record's two halves share one spectrum, band by band, without a model.

The record is cut into halves; each half's twice-differenced periodogram (:func:`compare.analysis.family_fit.
record_for`) is averaged over ``bands`` log-spaced bands from the half's lowest frequency to Nyquist, and each band's
ratio r_b = B2 / B1 (second half over first) is tested.

Reference. With independent exponential ordinates of one expectation, m_b of them in each half's band, r_b follows
F(2 m_b, 2 m_b) exactly, and ln r_b has variance 2 psi'(m_b) (psi' the trigamma function: 3.29 for one ordinate,
2 / m_b for many). Where the expectation varies across the band (a slope left by the differencing, a floor rising as
omega^4) m_b is the effective count (sum mu)^2 / sum mu^2 of the band's fitted power law mu.
A mechanism's record need not be Gaussian noise: model I's contact renewals move a whole band's level together, and
every band's together (the level of N T v / a renewals scatters by sqrt(1.8 / (N T v / a)) whatever the band's
width), which no count of ordinates averages away. That common scatter is measured on the record itself: cut into
:data:`SEGMENTS` equal segments, each segment's log level averaged over the bands every segment resolves (at least
:data:`MIN_ORDINATES` ordinates) scatters within its half by tau_seg^2 beyond the ordinates' own noise (six degrees
of freedom for eight segments); a level's scatter falls as 1 / length, so each half's common level scatters by
tau_seg^2 / 4 and ln r_b takes 2 psi'(m_b) + tau^2 with tau^2 = tau_seg^2 / 2 (clipped at 0). Each band's p-value
is that of F(2 m', 2 m') with 2 psi'(m') = 2 psi'(m_b) + tau^2 (m' = m_b when tau = 0: the exact law), or, where
larger, that of Student's t for ln r_b / sqrt(2 psi'(m_b) + tau^2) with Satterthwaite's degrees of freedom
6 (2 psi'(m_b) + tau^2)^2 / tau^4 (tau^2 is an estimate of six degrees of freedom; the first p-value holds where
the ordinates' noise dominates, the second where the level scatter does); a band is flagged when its p-value is below level / bands (Bonferroni) and its ratio beyond :data:`FACTOR` either way. A
level that drifts within each half widens tau as well: the test is for halves that differ, not for drifts.

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
MIN_ORDINATES = 16  # ordinates a band needs in every segment to enter the estimate of the level scatter
SEGMENTS = 8  # segments the level scatter is measured on (four a half: six degrees of freedom within the halves)


def _kept(record, edges, skirts):
    """The ordinates inside the bands and outside the skirts: (omega, periodogram, band index)."""
    w, p = record.omega, record.periodogram
    keep = np.ones(len(w), bool)
    for lo, hi in skirts:
        keep &= ~((w >= lo) & (w <= hi))
    keep &= (w >= edges[0]) & (w <= edges[-1])
    return w[keep], p[keep], np.searchsorted(edges[1:-1], w[keep], side="right")


def _band_sums(record, edges, skirts):
    """Per band: the number of ordinates and the sum of the periodogram, skirts left out."""
    _, p, idx = _kept(record, edges, skirts)
    nb = len(edges) - 1
    return np.bincount(idx, minlength=nb).astype(float), np.bincount(idx, weights=p, minlength=nb)


def _effective_counts(halves, edges, skirts) -> np.ndarray:
    """Per band, the number of equal exponential ordinates whose mean scatters as the band's mean does: the
    ordinates' expectations mu_i differ across a band (a power law's slope after differencing, a floor's omega^4),
    and a mean of exponentials with means mu_i has the variance of (sum mu)^2 / sum mu^2 equal ones. mu_i is the
    power law of the band fitted by least squares to the log of both halves' ordinates summed (their shared
    expectation's shape); a band of fewer than three ordinates keeps its count."""
    (w, p1, idx), (_, p2, _) = (_kept(r, edges, skirts) for r in halves)
    k = min(len(p1), len(p2))
    w, both, idx = w[:k], p1[:k] + p2[:k], idx[:k]
    out = np.bincount(idx, minlength=len(edges) - 1).astype(float)
    for b in np.flatnonzero(out >= 3):
        sel = (idx == b) & (both > 0)
        if sel.sum() < 3:
            continue
        lw = np.log(w[sel])
        slope = np.polyfit(lw, np.log(both[sel]), 1)[0]
        mu = np.exp(slope * (lw - lw.mean()))
        out[b] = min(out[b], mu.sum() ** 2 / (mu * mu).sum())
    return out


def _m_effective(m: float, extra: float) -> float:
    """The m' whose log-F variance 2 psi'(m') is 2 psi'(m) + extra."""
    if extra <= 0:
        return m
    target = float(special.polygamma(1, m)) + extra / 2
    # psi'(m') = target; psi'(u) ~ 1/u for large u, 1/u^2 for small: bracket and solve
    return optimize.brentq(lambda u: float(special.polygamma(1, u)) - target, 1e-6, m)


def _level_scatter(x, dt, edges, skirts) -> float:
    """tau_seg^2 / 4 * 2 = the halves' share of the common level scatter in ln r (module docstring): the record cut
    into :data:`SEGMENTS` equal segments, each segment's mean log level over the bands every segment resolves with at
    least :data:`MIN_ORDINATES` ordinates, its scatter within each half (SEGMENTS - 2 degrees of freedom) less what
    the ordinates' own noise gives; 0 where no band qualifies or the scatter is below that noise."""
    n = len(x) // SEGMENTS
    sums = [_band_sums(record_for(x[j * n:(j + 1) * n], dt), edges, skirts) for j in range(SEGMENTS)]
    counts = np.array([c for c, _ in sums])
    levels = np.array([t for _, t in sums])
    use = (counts.min(axis=0) >= MIN_ORDINATES) & (levels.min(axis=0) > 0)
    if not use.any():
        return 0.0
    ell = np.log(levels[:, use] / counts[:, use])
    u = ell.mean(axis=1)  # each segment's common log level
    noise = float(np.mean(special.polygamma(1, counts[:, use]).sum(axis=1) / use.sum() ** 2))
    half = SEGMENTS // 2
    ss = sum(float(((u[k:k + half] - u[k:k + half].mean()) ** 2).sum()) for k in (0, half))
    tau_seg2 = max(0.0, ss / (SEGMENTS - 2) - noise)
    # a half holds SEGMENTS / 2 segments (the scatter of a level falls as 1 / length); ln r takes two halves
    return 2 * tau_seg2 / half


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
        (second half over first, per band), ``p_values`` (per band, before Bonferroni), ``level_scatter`` (tau:
        the scatter of the halves' common log-level ratio beyond the ordinates' noise, measured on the segments) and ``bands`` (rad/s).
    """
    x = np.asarray(x, dtype=float)
    h = len(x) // 2
    halves = [record_for(x[i * h:(i + 1) * h], dt) for i in range(2)]
    w = halves[0].omega
    edges = np.geomspace(w[0], w[-1] * (1 + 1e-12), bands + 1)
    (m1, s1), (m2, s2) = (_band_sums(r, edges, skirts) for r in halves)
    m = np.minimum(np.minimum(m1, m2), _effective_counts(halves, edges, skirts))
    ok = (m > 0) & (s1 > 0) & (s2 > 0)
    ratio = np.where(ok, (s2 / np.maximum(m2, 1)) / np.where(s1 > 0, s1 / np.maximum(m1, 1), 1.0), np.nan)
    tau2 = _level_scatter(x, dt, edges, skirts)
    p = np.ones(bands)
    for b in np.flatnonzero(ok):
        me = _m_effective(float(m[b]), tau2)
        cdf = float(stats.f.cdf(ratio[b], 2 * me, 2 * me))
        p[b] = min(1.0, 2 * min(cdf, 1 - cdf))
        if tau2 > 0:  # tau^2 is itself an estimate: Student's t with Satterthwaite's degrees of freedom
            var = 2 * float(special.polygamma(1, m[b])) + tau2
            nu = (SEGMENTS - 2) * var * var / (tau2 * tau2)
            p[b] = max(p[b], float(2 * stats.t.sf(abs(math.log(ratio[b])) / math.sqrt(var), nu)))
    bad = ok & (p < level / bands) & (np.abs(np.log(np.where(ok, ratio, 1.0))) > math.log(FACTOR))
    return {"stationary": not bool(bad.any()), "ratios": [float(r) for r in ratio], "p_values": [float(v) for v in p],
            "level_scatter": math.sqrt(tau2), "bands": [[float(edges[i]), float(edges[i + 1])] for i in range(bands)]}
