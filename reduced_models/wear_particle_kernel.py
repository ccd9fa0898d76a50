"""The event-driven kernel of model II (:mod:`reduced_models.wear_particle`), numba: episode durations drawn from
their laws and the force, a sum of rectangles, integrated exactly per output bin. Computation only; the physics and
the parameters are documented in :mod:`reduced_models.wear_particle`."""
from __future__ import annotations

import numba
import numpy as np

__all__ = ["draw", "add_rect", "run"]


@numba.njit(cache=True)
def draw(kind, mean, shape):
    """One episode duration of law ``kind`` (0 exponential, 1 fixed, 2 Pareto of ``shape``) with mean ``mean``
    (Units: s), from numba's generator."""
    if kind == 0:
        return np.random.exponential(mean)
    if kind == 1:
        return mean
    scale = mean * (shape - 1.0) / shape
    return scale * (1.0 - np.random.random()) ** (-1.0 / shape)


@numba.njit(cache=True)
def add_rect(t1, t2, c, dt, n, part_i, part_m, diff_i, diff_m):
    """Add the rectangle c on [t1, t2) to per-bin integrals I_k = Int_bin F and first moments
    J_k = Int_bin (t_{k+1} - s) F(s) ds, O(1) per rectangle with difference arrays for whole bins."""
    if t2 <= 0.0 or t1 >= n * dt:
        return
    t1 = max(t1, 0.0)
    t2 = min(t2, n * dt)
    k1 = int(t1 / dt)
    k2 = int(t2 / dt)
    if k1 >= n:
        k1 = n - 1
    if k2 >= n:
        k2 = n - 1
    if k1 == k2:
        e = (k1 + 1) * dt
        part_i[k1] += c * (t2 - t1)
        part_m[k1] += c * 0.5 * ((e - t1) ** 2 - (e - t2) ** 2)
        return
    e1 = (k1 + 1) * dt
    part_i[k1] += c * (e1 - t1)
    part_m[k1] += c * 0.5 * (e1 - t1) ** 2
    s2 = k2 * dt
    part_i[k2] += c * (t2 - s2)
    part_m[k2] += c * 0.5 * (dt**2 - (dt - (t2 - s2)) ** 2)
    if k2 > k1 + 1:
        diff_i[k1 + 1] += c * dt
        diff_i[k2] -= c * dt
        diff_m[k1 + 1] += c * 0.5 * dt**2
        diff_m[k2] -= c * 0.5 * dt**2


@numba.njit(cache=True)
def run(seed, n, dt, kinds, shapes, tauA, tauB, cA, cB, telegraph, out_i, out_m, counts):
    """Every particle's alternating trapped (A) / sliding (B) episodes over n bins of dt (Units: s), from numba's
    generator seeded with ``seed``: the force integrals and first moments per bin added to ``out_i``, ``out_m``
    (:func:`add_rect`), the episodes of each state counted in ``counts``. Buffers are not checked here."""
    np.random.seed(seed)
    diff_i = np.zeros(n + 1)
    diff_m = np.zeros(n + 1)
    T = n * dt
    for p in range(tauA.shape[0]):
        # stationary start: state A with probability tauA / (tauA + tauB); for the exponential law the
        # residual duration is again exponential, for the others a uniform fraction of one draw
        state = 0 if np.random.random() < tauA[p] / (tauA[p] + tauB[p]) else 1
        t = 0.0
        first = True
        while t < T:
            mean = tauA[p] if state == 0 else tauB[p]
            d = draw(kinds[state], mean, shapes[state])
            if first and kinds[state] != 0:
                d *= np.random.random()
            first = False
            c = cA[p] if state == 0 else cB[p]
            if not telegraph and np.random.random() < 0.5:
                c = -c
            add_rect(t, t + d, c, dt, n, out_i, out_m, diff_i, diff_m)
            counts[state] += 1
            t += d
            state = 1 - state
    acc_i = 0.0
    acc_m = 0.0
    for k in range(n):
        acc_i += diff_i[k]
        acc_m += diff_m[k]
        out_i[k] += acc_i
        out_m[k] += acc_m
