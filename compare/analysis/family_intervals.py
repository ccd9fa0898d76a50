"""95 % intervals of a spectral family's fit (:mod:`compare.analysis.family_fit`): the curvature of the grouped
negative log-likelihood at its maximum, and for a corner the likelihood along its profile line."""
from __future__ import annotations

import math

import numpy as np
from scipy import stats

__all__ = ["intervals", "hessian", "errors"]

_Z95 = float(stats.norm.ppf(0.975))
_WIDEST = 2.0  # a scale whose 95 % interval spans more than two decades is not identified


def hessian(f, q, h=1e-3):
    """Finite-difference curvature of ``f`` at ``q`` (step ``h`` on the fitted scale)."""
    n = len(q)
    H = np.empty((n, n))
    f0 = f(q)
    for i in range(n):
        for j in range(i, n):
            ei, ej = np.eye(n)[i] * h, np.eye(n)[j] * h
            if i == j:
                H[i, i] = (f(q + ei) - 2 * f0 + f(q - ei)) / h**2
            else:
                H[i, j] = H[j, i] = (f(q + ei + ej) - f(q + ei - ej) - f(q - ei + ej) + f(q - ei - ej)) / (4 * h**2)
    return H


def errors(H) -> np.ndarray:
    """Standard errors from the curvature H of a negative log-likelihood; a parameter along a flat or negative
    direction (the record does not constrain it) gets NaN and the others are read with it left out, the flattest
    first."""
    keep = list(range(len(H)))
    err = np.full(len(H), np.nan)
    while keep:
        sub = H[np.ix_(keep, keep)]
        ev = np.linalg.eigvalsh(sub) if np.all(np.isfinite(sub)) else np.array([-1.0])
        if ev.min() > 1e-10 * max(ev.max(), 1e-300):
            err[keep] = np.sqrt(np.diag(np.linalg.inv(sub)))
            return err
        keep.pop(int(np.argmin(np.abs(np.diag(sub)) / np.sqrt(np.abs(np.diag(sub)).max() + 1e-300)))
                 if np.all(np.isfinite(np.diag(sub))) else 0)
    return err


def _inverse(H):
    """The inverse of a curvature matrix, or None where it is not positive definite."""
    try:
        if np.all(np.isfinite(H)) and np.linalg.eigvalsh(H).min() > 0:
            return np.linalg.inv(H)
    except np.linalg.LinAlgError:
        pass
    return None


_PROFILE_DROP = float(stats.chi2.ppf(0.95, 1)) / 2  # the profile's 95 % drop in log-likelihood


def _profile_end(grouped, q, direction, step, bound, f0):
    """Where the negative log-likelihood along the profile's line rises by :data:`_PROFILE_DROP` above ``f0``.

    The line is the quadratic approximation's profile path through the maximum ``q``: moving one parameter by t
    moves every free one by t ``direction`` (a column of the inverse curvature over its diagonal element); along it
    the likelihood itself is evaluated, so a corner's far-from-quadratic shape counts. Searched from ``step`` (the
    curvature's end, signed; widened by doubling while the rise stays below, then bisected). Returns the signed
    distance t, or None where the rise stays below it before ``bound`` (the distance to the search box's end)."""
    def rise(t):
        return grouped(q + t * direction) - f0

    inner, outer = 0.0, step
    for _ in range(6):
        if abs(outer) >= abs(bound):
            outer = bound
            if rise(outer) < _PROFILE_DROP:
                return None
            break
        if rise(outer) >= _PROFILE_DROP:
            break
        inner, outer = outer, 2 * outer
    else:
        return None
    for _ in range(6):
        mid = 0.5 * (inner + outer)
        if rise(mid) >= _PROFILE_DROP:
            outer = mid
        else:
            inner = mid
    return outer


def intervals(fam, grouped, q, ident, neutral, bounds, corners) -> dict:
    """95 % intervals of the identified parameters from the curvature over every free parameter and the floor, so
    that an identified parameter's interval carries its correlation with the ones the band does not pin down (a
    resonance above the band still tilts its top); the held ones stay out. None for the others.

    A corner (a name in ``corners``) gets the interval of the likelihood along its profile's line instead
    (:func:`_profile_end`): the likelihood of a corner is far from quadratic over its interval (model I's renewal
    length at 60 s: a drop of 1.5 at 14 % from the maximum where the curvature's 95 % end lies at 7 %), and the
    curvature's intervals covered it in 6 of 8 records. A corner whose likelihood does not drop by the 95 % amount
    on one side before the search box's end is not identified (the record bounds it on one side only)."""
    idx = [i for i in range(len(q) - 1) if i not in neutral] + [len(q) - 1]

    def nll_sub(s):
        r = q.copy()
        r[idx] = s
        return grouped(r)

    H = hessian(nll_sub, q[idx])
    err = errors(H)
    try:
        cov = np.linalg.inv(H) if np.all(np.isfinite(err)) else None
    except np.linalg.LinAlgError:
        cov = None
    intervals = {p.name: None for p in fam.params}
    for k, i in enumerate(idx[:-1]):
        p = fam.params[i]
        if not ident[i] or not math.isfinite(err[k]):
            continue
        lo, hi = q[i] - _Z95 * err[k], q[i] + _Z95 * err[k]
        if p.name in corners:
            direction = np.zeros(len(q))
            sub = [j for j, m in enumerate(idx) if m == len(q) - 1 or ident[m]]  # identified ones and the floor
            while len(sub) > 1 and _inverse(H[np.ix_(sub, sub)]) is None:
                # a direction the record does not constrain (a floor far below the family): held, the flattest
                sub.pop(int(np.argmin([H[j, j] for j in sub])))
            cov_id = _inverse(H[np.ix_(sub, sub)]) if k in sub else None
            if cov_id is not None:
                # the profile's line through the identified parameters only, the others held where the fit left
                # them: a corner outside the band (model II's omega_lo below a record's lowest ordinate) is free
                # along a flat direction, and the line through it ran into the search box's end within 2 % of
                # omega_hi's value (model II at 100 Hz, 300 s: 83 [81, 86] rad/s against the 100 built); with no
                # inverse of the whole curvature the corner alone moved, the others held (1 kHz, 60 s: 107 [106,
                # 109], now [87, 133])
                c = sub.index(k)
                direction[np.asarray(idx)[sub]] = cov_id[:, c] / cov_id[c, c]
            elif cov is not None:
                direction[idx] = cov[:, k] / cov[k, k]
            else:
                direction[i] = 1.0  # the others held: the conditional likelihood
            f0 = grouped(q)
            down = _profile_end(grouped, q, direction, -_Z95 * err[k], bounds[i][0] - q[i], f0)
            up = _profile_end(grouped, q, direction, _Z95 * err[k], bounds[i][1] - q[i], f0)
            if down is None or up is None:
                continue
            lo, hi = q[i] + down, q[i] + up
        if not (p.log and hi - lo > _WIDEST):
            intervals[p.name] = (10.0**lo, 10.0**hi) if p.log else (lo, hi)
    return intervals
