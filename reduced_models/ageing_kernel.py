"""The integrator of :mod:`reduced_models.ageing`: the right-hand side, a contact's renewal and the adaptive
Dormand-Prince 5(4) loop with dense output and renewal events (numba). Pure kernels; the physics and the parameters
are documented in :mod:`reduced_models.ageing`."""
from __future__ import annotations

import math

import numba
import numpy as np

from . import rate_state as _rs

__all__ = ["speed", "rhs", "dense", "renew", "record", "run"]

_DP = _rs.DORMAND_PRINCE  # the Dormand-Prince 5(4) tableau, one copy
_A21 = _DP["a21"]
_A31, _A32 = _DP["a31"], _DP["a32"]
_A41, _A42, _A43 = _DP["a41"], _DP["a42"], _DP["a43"]
_A51, _A52, _A53, _A54 = _DP["a51"], _DP["a52"], _DP["a53"], _DP["a54"]
_A61, _A62, _A63, _A64, _A65 = _DP["a61"], _DP["a62"], _DP["a63"], _DP["a64"], _DP["a65"]
_A71, _A73, _A74, _A75, _A76 = _DP["a71"], _DP["a73"], _DP["a74"], _DP["a75"], _DP["a76"]
_E1, _E3, _E4, _E5, _E6, _E7 = _DP["e1"], _DP["e3"], _DP["e4"], _DP["e5"], _DP["e6"], _DP["e7"]
_D1, _D3, _D4, _D5, _D6, _D7 = _DP["d1"], _DP["d3"], _DP["d4"], _DP["d5"], _DP["d6"], _DP["d7"]

# pars: 0 N, 1 v, 2 k0, 3 M, 4 c0, 5 F_drive, 6 f_n, 7 mu_v, 8 A, 9 B, 10 D_c, 11 law (0 ageing, 1 slip),
#       12 linear_direct (0/1)


@numba.njit(cache=True, inline="always")
def speed(D, fA, v, lin):
    """Contact speed v_i from the direct-effect force D_i, and the force's slope dD/dv_i."""
    if lin:
        return v * (1.0 + D / fA), fA / v
    vi = v * math.exp(D / fA)
    return vi, fA / vi


@numba.njit(cache=True, fastmath=True, error_model="numpy")
def rhs(y, out, pars, vi, gi):
    """Time derivative of y = (z, u, s_i, D_i, q_i); vi, gi scratch for the contact speeds and slopes."""
    N = int(pars[0])
    v, k0, M, c0, Fd, fn, A, B, Dc = (pars[1], pars[2], pars[3], pars[4], pars[5], pars[6], pars[8], pars[9],
                                      pars[10])
    law, lin = int(pars[11]), int(pars[12])
    fA = fn * A
    u = y[1]
    total = 0.0
    if lin:
        for i in range(N):
            vi[i] = v * (1.0 + y[2 + N + i] / fA)
            gi[i] = fA / v
    else:
        for i in range(N):
            vi[i] = v * math.exp(y[2 + N + i] / fA)
            gi[i] = fA / vi[i]
    for i in range(N):
        total += k0 * y[2 + i] + c0 * (u - vi[i])
    du = (Fd - total) / M
    out[0] = u - v
    out[1] = du
    for i in range(N):
        q = y[2 + 2 * N + i]
        if law == 0:  # q = v theta / D_c
            dq = (v / Dc) * (1.0 - (vi[i] / v) * q)
            dphi = dq / q
        else:  # q = ln(v theta / D_c)
            lnv = y[2 + N + i] / fA if not lin else math.log(vi[i] / v)
            dq = -(vi[i] / Dc) * (lnv + q)
            dphi = dq
        out[2 + i] = u - vi[i]
        out[2 + N + i] = (k0 * (u - vi[i]) + c0 * du - fn * B * dphi) / (1.0 + c0 / gi[i])
        out[2 + 2 * N + i] = dq


@numba.njit(cache=True, error_model="numpy")
def dense(y, ynew, k1, k3, k4, k5, k6, k7, h, th, j):
    th1 = 1.0 - th
    r2 = ynew[j] - y[j]
    r3 = h * k1[j] - r2
    r4 = r2 - h * k7[j] - r3
    r5 = h * (_D1 * k1[j] + _D3 * k3[j] + _D4 * k4[j] + _D5 * k5[j] + _D6 * k6[j] + _D7 * k7[j])
    return y[j] + th * (r2 + th1 * (r3 + th * (r4 + th1 * r5)))


@numba.njit(cache=True, error_model="numpy")
def renew(y, fr, i, new_f, pars, reset_q):
    """Contact i renews: its random force becomes new_f and (reset_q is finite) its state restarts at reset_q; the
    spring stretch and the block are continuous, so the direct-effect force D_i jumps to keep the contact's balance
    D_i + c0 v_i = const - (change of random force) - f_n B (change of ln state) (Newton; monotone in D_i)."""
    N = int(pars[0])
    v, c0, fn, A, B = pars[1], pars[4], pars[6], pars[8], pars[9]
    law, lin = int(pars[11]), int(pars[12])
    fA = fn * A
    D = y[2 + N + i]
    vi, _ = speed(D, fA, v, lin)
    dstate = 0.0
    if reset_q == reset_q:  # not nan
        q = y[2 + 2 * N + i]
        if law == 0:
            dstate = math.log(reset_q / q)
            y[2 + 2 * N + i] = reset_q
        else:
            dstate = math.log(reset_q) - q
            y[2 + 2 * N + i] = math.log(reset_q)
    R = D + c0 * vi - (new_f - fr[i]) - fn * B * dstate
    Dn = D + (R - D - c0 * vi) / (1.0 + c0 * vi / fA)
    for _ in range(50):
        vn, g = speed(Dn, fA, v, lin)
        res = Dn + c0 * vn - R
        Dn -= res / (1.0 + c0 / g)
        if abs(res) <= 1e-14 * (abs(R) + fA):
            break
    y[2 + N + i] = Dn
    fr[i] = new_f


@numba.njit(cache=True, error_model="numpy")
def record(y, ynew, k1, k3, k4, k5, k6, k7, h, t, t_stop, k_out, k_stop, dt_out, v, xs, fsum, F):
    """Block positions at the output times in (t, t_stop] from the step's dense output, and the random force F
    (constant on (t, t_stop]) integrated over the output intervals [j dt_out, (j + 1) dt_out). Returns k_out."""
    while k_out < k_stop and k_out * dt_out <= t_stop:
        th = (k_out * dt_out - t) / h
        xs[k_out] = v * k_out * dt_out + dense(y, ynew, k1, k3, k4, k5, k6, k7, h, th, 0)
        k_out += 1
    a = t
    while a < t_stop:
        j = int(a / dt_out)
        b = min(t_stop, (j + 1) * dt_out)
        if b <= a:  # a sits on a grid point up to rounding
            j += 1
            b = min(t_stop, (j + 1) * dt_out)
        if j < fsum.shape[0]:
            fsum[j] += F * (b - a)
        a = b
    return k_out


@numba.njit(cache=True, error_model="numpy")
def run(y, fr, t, h, k_out, k_stop, dt_out, xs, fsum, pos, idx, val, ptr, n_pos, pars, tol, scale, reset_q,
         ev_time, ev_count, max_steps, counters):
    """Integrate until the output index reaches k_stop or the renewals loaded run out (ptr == n_pos). Writes x at
    the output times and the random force sum averaged over each output interval; renewals when v t + z reaches
    pos[ptr]. Returns (t, h, k_out, ptr, ev_count, status): 0 ok, 1 too many steps, 2 step underflow."""
    n = y.shape[0]
    v = pars[1]
    k1, k2, k3, k4 = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    k5, k6, k7 = np.empty(n), np.empty(n), np.empty(n)
    yt, ynew = np.empty(n), np.empty(n)
    vi, gi = np.empty(fr.shape[0]), np.empty(fr.shape[0])
    F = 0.0
    for i in range(fr.shape[0]):
        F += fr[i]
    rhs(y, k1, pars, vi, gi)
    steps = 0
    while k_out < k_stop and ptr < n_pos:
        if steps >= max_steps:
            return t, h, k_out, ptr, ev_count, 1
        if h <= 1e-12 * max(1.0, t):
            return t, h, k_out, ptr, ev_count, 2
        for i in range(n):
            yt[i] = y[i] + h * _A21 * k1[i]
        rhs(yt, k2, pars, vi, gi)
        for i in range(n):
            yt[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        rhs(yt, k3, pars, vi, gi)
        for i in range(n):
            yt[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        rhs(yt, k4, pars, vi, gi)
        for i in range(n):
            yt[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        rhs(yt, k5, pars, vi, gi)
        for i in range(n):
            yt[i] = y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i])
        rhs(yt, k6, pars, vi, gi)
        for i in range(n):
            ynew[i] = y[i] + h * (_A71 * k1[i] + _A73 * k3[i] + _A74 * k4[i] + _A75 * k5[i] + _A76 * k6[i])
        rhs(ynew, k7, pars, vi, gi)
        steps += 1
        err = 0.0
        for i in range(n):
            e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
            err += (e / (tol * (scale[i] + 1e-3 * abs(ynew[i])))) ** 2
        err = math.sqrt(err / n)
        if not (err <= 1.0):
            counters[1] += 1
            h *= 0.2 if not (err < 1e300) else max(0.2, 0.9 * err ** -0.2)
            continue
        counters[0] += 1
        t_new = t + h
        # renewal inside the step? the block's displacement v t + z is increasing across a step (u > 0)
        th_ev = 2.0
        if v * t_new + ynew[0] >= pos[ptr]:
            lo, hi = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if v * (t + mid * h) + dense(y, ynew, k1, k3, k4, k5, k6, k7, h, mid, 0) >= pos[ptr]:
                    hi = mid
                else:
                    lo = mid
                if (hi - lo) * h < 1e-13:
                    break
            th_ev = hi
        t_stop = t_new if th_ev > 1.0 else t + th_ev * h
        k_out = record(y, ynew, k1, k3, k4, k5, k6, k7, h, t, t_stop, k_out, k_stop, dt_out, v, xs, fsum, F)
        if th_ev <= 1.0:
            for j in range(n):
                yt[j] = dense(y, ynew, k1, k3, k4, k5, k6, k7, h, th_ev, j)
            for j in range(n):
                y[j] = yt[j]
            while ptr < n_pos and v * t_stop + y[0] >= pos[ptr]:
                i = idx[ptr]
                F += val[ptr] - fr[i]
                renew(y, fr, i, val[ptr], pars, reset_q)
                ev_time[ev_count] = t_stop
                ev_count += 1
                ptr += 1
            t = t_stop
            rhs(y, k1, pars, vi, gi)
            h = max(h * th_ev, 1e-3 * h) if th_ev < 0.5 else h
        else:
            for j in range(n):
                y[j] = ynew[j]
                k1[j] = k7[j]
            t = t_new
            h *= 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
    return t, h, k_out, ptr, ev_count, 0
