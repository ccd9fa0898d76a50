"""95 % intervals of a spectral family's fit (:mod:`compare.analysis.family_fit`): the curvature of the grouped
negative log-likelihood at its maximum, for a corner its profile likelihood, and for a comb of zeros (model III's
window) the debiased likelihood's."""
from __future__ import annotations

import math

import numpy as np
from scipy import optimize, stats

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


def _profile_end(rise, step, bound):
    """Where ``rise`` (the profile's negative log-likelihood above its maximum, a function of the signed distance t
    of the parameter from its fitted value) reaches :data:`_PROFILE_DROP`.

    Searched from ``step`` (the curvature's end, signed; widened by doubling while the rise stays below, then
    bisected). Returns the signed distance t, or None where the rise stays below it before ``bound`` (the distance to
    the search box's end)."""
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


def _profile(grouped, q, i, direction, free, bounds, per, f0):
    """The profile likelihood of parameter ``i`` above its maximum ``f0``, as a function of its signed distance t
    from ``q[i]``: at each t the parameters ``free`` (the identified ones and the floor, ``i`` excluded) are fitted
    again by L-BFGS-B within ``bounds`` on the likelihood per ordinate (``per``), started on the quadratic
    approximation's profile line ``q + t direction``; the rest are held where the fit left them. The line alone
    (the likelihood evaluated along it, not re-fitted) ended model II's omega_hi intervals short: 15 of 20 records
    of its first confusion cell (60 s) covered against 19 of 20 re-fitted (docs/results/identification.md)."""
    lo = np.array([b[0] for b in bounds])
    hi = np.array([b[1] for b in bounds])
    sub_bounds = [bounds[j] for j in free]

    def rise(t):
        start = np.clip(q + t * direction, lo, hi)
        start[i] = q[i] + t
        best = grouped(start)
        if free:
            def f(s):
                r = start.copy()
                r[free] = s
                return grouped(r) * per

            res = optimize.minimize(f, start[free], method="L-BFGS-B", bounds=sub_bounds, options=_STOP)
            best = min(best, res.fun / per)
        return best - f0

    return rise


_STOP = {"ftol": 1e-11, "gtol": 1e-9, "maxiter": 500}  # as the fit's own descent (family_fit)


def intervals(fam, grouped, q, ident, neutral, bounds, corners, per: float = 1.0) -> dict:
    """95 % intervals of the identified parameters from the curvature over every free parameter and the floor, so
    that an identified parameter's interval carries its correlation with the ones the band does not pin down (a
    resonance above the band still tilts its top); the held ones stay out. None for the others.

    A corner (a name in ``corners``) gets the interval of its profile likelihood instead (:func:`_profile`, the
    other parameters fitted again at each step; ``per`` is one over the number of ordinates, the scale the fit's
    descent works on): the likelihood of a corner is far from quadratic over its interval (model I's renewal
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
            if cov_id is not None:
                free = [int(idx[j]) for j in sub if idx[j] != i]
            else:
                free = [j for j in idx if j != i] if cov is not None else []
            rise = _profile(grouped, q, i, direction, free, bounds, per, f0)
            down = _profile_end(rise, -_Z95 * err[k], bounds[i][0] - q[i])
            up = _profile_end(rise, _Z95 * err[k], bounds[i][1] - q[i])
            if down is None or up is None:
                continue
            lo, hi = q[i] + down, q[i] + up
        if not (p.log and hi - lo > _WIDEST):
            intervals[p.name] = (10.0**lo, 10.0**hi) if p.log else (lo, hi)
    return intervals


COMB_EXACT_N = 2**19  # records up to this many samples get a comb's place read on the debiased likelihood
_COMB_REACH = 8.0  # the debiased search's reach, in the grouped interval's half-widths (the bias reached 4 of them)


def comb_on_debiased(record, spectrum, q, i, interval, nll_of=None):
    """A comb of zeros placed by parameter ``i`` (model III's window w), read again on the debiased Whittle
    likelihood, the other parameters held at the grouped maximum ``q``: (log10 value, (low, high)) or None.

    The grouped likelihood leaves out the taper's leakage, which fills each zero and moves its minimum toward the
    side where the spectrum falls (the spectrum near a zero, (omega - omega_k)^2 g(omega) with g falling, convolved
    with the leakage kernel, has its minimum above omega_k): on the 60 s records of model III's confusion cell the
    grouped fit read w 24 ppm low (-10 to -34 ppm over 18 seeds, a scatter of 7 ppm) with intervals of +-9 ppm. On
    the debiased likelihood (:meth:`compare.analysis.whittle.WhittleRecord.negloglik`, eq. 8 of Sykulski et al. 2019)
    the minimum lies at -5 to +5 ppm. The value is found by Brent within :data:`_COMB_REACH` times the grouped interval about
    ``q[i]``; the 95 % ends where that likelihood rises by chi2_1(0.95) / 2, the others held (the zeros' positions
    are nearly orthogonal to the level and the floor, which set their depth). ``nll_of(q)`` is the debiased
    negative log-likelihood (default: ``record.negloglik(spectrum, q, images=None)``)."""
    if nll_of is None:
        def nll_of(r):
            return record.negloglik(spectrum, r, images=None)

    def f(value):
        r = np.array(q, dtype=float)
        r[i] = value
        val = nll_of(r)
        return val if math.isfinite(val) else 1e300

    lo, hi = interval
    a, b = q[i] - _COMB_REACH * (q[i] - lo), q[i] + _COMB_REACH * (hi - q[i])
    res = optimize.minimize_scalar(f, bounds=(a, b), method="bounded", options={"xatol": 1e-8})
    best, f0 = float(res.x), float(res.fun)
    ends = []
    for wall, step in ((a, lo - q[i]), (b, hi - q[i])):
        inner, outer = best, best + step
        for _ in range(8):
            if (outer - wall) * (outer - best) >= 0:  # at or beyond the bracket's end
                outer = wall
            if f(outer) - f0 >= _PROFILE_DROP:
                break
            if outer == wall:
                return None
            inner, outer = outer, outer + 2 * (outer - inner)
        else:
            return None
        ends.append(optimize.brentq(lambda t: f(t) - f0 - _PROFILE_DROP, min(inner, outer), max(inner, outer),
                                    xtol=1e-8))
    return best, (ends[0], ends[1])
