"""The numba kernel of model Ib: exact propagation of a small linear system between renewals of two
families of piecewise-constant forces (macro and micro), O(1) work per renewal.

The modal state q evolves as in :mod:`reduced_models._exact`; a renewal of family l changes its force sum
F_l by df and the modal forcing by B_l df (no re-summing). Renewal times are the times at which the block's
position v t + zeta(t) reaches the renewal positions of either family, merged on the fly; each is found by
Newton iteration on the exact solution, started from the current velocity, and the exponentials of the
accepted iterate are reused to advance the state (one evaluation per Newton step, none extra).
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["run_two_level", "sort_windows"]


@numba.njit(cache=True, inline="always", _nrt=False)
def _order(u, w, count, order):
    """argsort of row w of u (values in [0, 1)) into ``order``: counting sort on floor(u n) (about one value
    per bucket), then insertion sort, which finds the result nearly sorted: O(n) on average."""
    n = u.shape[1]
    for b in range(n + 1):
        count[b] = 0
    for i in range(n):
        count[min(int(u[w, i] * n), n - 1) + 1] += 1
    for b in range(n):
        count[b + 1] += count[b]
    for i in range(n):
        b = min(int(u[w, i] * n), n - 1)
        order[count[b]] = i
        count[b] += 1
    for i in range(1, n):
        o = order[i]
        j = i - 1
        while j >= 0 and u[w, order[j]] > u[w, o]:
            order[j + 1] = order[j]
            j -= 1
        order[j + 1] = o


@numba.njit(cache=True, _nrt=False)
def sort_windows(r_pos, r_val, j0, length, amp, pos, idx, val, count, order):
    """Renewal events of consecutive windows j0, j0 + 1, ... of ``length``: row w of r_pos holds each contact's
    uniform position in window j0 + w; sorted within the window. val = amp (r_val - 0.5). count (n + 1) and
    order (n): scratch."""
    n_w, nc = r_pos.shape
    for w in range(n_w):
        _order(r_pos, w, count, order)
        for c in range(nc):
            i = order[c]
            pos[w * nc + c] = (j0 + w + r_pos[w, i]) * length
            idx[w * nc + c] = i
            val[w * nc + c] = amp * (r_val[w, i] - 0.5)


@numba.njit(cache=True, inline="always", _nrt=False)
def _eval(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, h, er, pr, ec, pc):
    """(zeta, zeta') a time h ahead; fills er/ec = e^{lambda h} and pr/pc = phi_1(lambda h) h = (e^{lambda h}
    - 1) / lambda for _commit. ilr, ilc: 1/lambda (0 for lambda = 0); lcr, lci: the complex modes' lambda.
    One transcendental per real mode (expm1 near 0, exp elsewhere; none for the translation mode lambda = 0
    or where e^x underflows), three per complex mode (e^{x+iy} - 1 = expm1(x) cos y - 2 sin^2(y/2)
    + i e^x sin y, half-angle forms), complex products written out: all accurate to rounding, 2.4x faster
    than numba's complex exp and division."""
    z = 0.0
    dz = 0.0
    for k in range(lr.shape[0]):
        lam = lr[k]
        x = lam * h
        if lam == 0.0:
            e = 1.0
            p = h
        else:
            if -0.5 < x < 0.5:
                em1 = math.expm1(x)
                e = em1 + 1.0
            elif x < -745.0:  # e^x underflows to 0 (and libm's underflow path is slow)
                e = 0.0
                em1 = -1.0
            else:
                e = math.exp(x)
                em1 = e - 1.0
            p = em1 * ilr[k]
        er[k] = e
        pr[k] = p
        z += cr[k] * (e * qr[k] + p * gr[k])
        dz += cr[k] * (lam * e * qr[k] + e * gr[k])
    for k in range(lcr.shape[0]):
        x = lcr[k] * h
        y = lci[k] * h
        sh = math.sin(0.5 * y)
        ch = math.cos(0.5 * y)
        if -0.5 < x < 0.5:
            xm1 = math.expm1(x)
            ex = xm1 + 1.0
        else:
            ex = math.exp(x)
            xm1 = ex - 1.0
        s2 = 2.0 * sh * sh
        em1r = xm1 * (1.0 - s2) - s2
        em1i = ex * 2.0 * sh * ch
        il = ilc[k]
        pr_ = em1r * il.real - em1i * il.imag
        pi_ = em1r * il.imag + em1i * il.real
        er_ = em1r + 1.0
        ei_ = em1i
        ec[k] = complex(er_, ei_)
        pc[k] = complex(pr_, pi_)
        q = qc[k]; g = gc[k]; c = cc[k]
        # w = e q + p g
        wr = er_ * q.real - ei_ * q.imag + pr_ * g.real - pi_ * g.imag
        wi = er_ * q.imag + ei_ * q.real + pr_ * g.imag + pi_ * g.real
        z += c.real * wr - c.imag * wi
        # d = lam e q + e g = e (lam q + g)
        lq_r = lcr[k] * q.real - lci[k] * q.imag + g.real
        lq_i = lcr[k] * q.imag + lci[k] * q.real + g.imag
        dr = er_ * lq_r - ei_ * lq_i
        di = er_ * lq_i + ei_ * lq_r
        dz += c.real * dr - c.imag * di
    return z, dz


@numba.njit(cache=True, inline="always", _nrt=False)
def _commit(qr, gr, qc, gc, er, pr, ec, pc):
    for k in range(qr.shape[0]):
        qr[k] = er[k] * qr[k] + pr[k] * gr[k]
    for k in range(qc.shape[0]):
        qc[k] = ec[k] * qc[k] + pc[k] * gc[k]


@numba.njit(cache=True, inline="always", _nrt=False)
def _to_event(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, v, t, x0, dz0, acc, s, h_left, er, pr, ec, pc, tol,
              stats):
    """Advance the state to the first time in (0, h_left] at which v t + zeta reaches s, or to h_left if it
    does not. x0, dz0: position and zeta' now; acc: an estimate of zeta'' (the first guess solves
    x0 + (v + dz0) h + acc h^2 / 2 = s; Newton iterations on the exact solution follow until the position is
    within tol). Returns (h, hit, zeta, zeta') at the end of the advance."""
    d0 = v + dz0
    gap = s - x0
    disc = d0 * d0 + 2.0 * acc * gap
    if gap <= 0.0:
        h = 0.0
    elif d0 > 0.0 and disc > 0.0:
        h = 2.0 * gap / (d0 + math.sqrt(disc))
    else:
        h = h_left
    lo, hi = 0.0, h_left
    if h >= h_left:  # the linear guess says "not in this step": check at the step's end
        z, dz = _eval(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, h_left, er, pr, ec, pc)
        stats[0] += 1
        f = v * (t + h_left) + z - s
        if f < 0.0:
            _commit(qr, gr, qc, gc, er, pr, ec, pc)
            return h_left, False, z, dz
        h = h_left - f / (v + dz) if v + dz > 0.0 else 0.5 * h_left
        if not (0.0 < h < h_left):
            h = 0.5 * h_left
    for _ in range(200):
        z, dz = _eval(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, h, er, pr, ec, pc)
        stats[0] += 1
        f = v * (t + h) + z - s
        if abs(f) <= tol or abs(f) <= 4.4e-16 * abs(s) or hi - lo <= 1e-15 * h_left:  # tol or rounding of s
            break
        if f < 0.0:
            lo = h
        else:
            hi = h
        d = v + dz
        h_new = h - f / d if d > 0.0 else 0.5 * (lo + hi)
        if not (lo < h_new < hi):
            h_new = 0.5 * (lo + hi)
        h = h_new
    _commit(qr, gr, qc, gc, er, pr, ec, pc)
    return h, True, z, dz


@numba.njit(cache=True, inline="always", _nrt=False)
def _renew(f, i, new, Br, Bc, gr, gc):
    """Contact i's force becomes ``new``: the modal forcing moves by B df; returns df for the force sum."""
    df = new - f[i]
    f[i] = new
    for j in range(gr.shape[0]):
        gr[j] += Br[j] * df
    for j in range(gc.shape[0]):
        gc[j] += Bc[j] * df
    return df


@numba.njit(cache=True, _nrt=False)
def run_two_level(lr, ilr, cr, B1r, B2r, lcr, lci, ilc, cc, B1c, B2c, qr, gr, qc, gc, f1, f2, sums, v, dt, k0, k1,
                  pos1, idx1, val1, ptr1, pos2, idx2, val2, ptr2, boundary, tol,
                  x_out, f_out, f2_out, ev_time, ev_count, store2, ev2_time, ev2_count, stats, er, pr, ec, pc):
    """Step output intervals k0..k1-1; stop early (return k) when the block nears the loaded boundary.

    f1, f2: each contact's current force (macro, micro); sums = [F1, F2], their sums, kept up to date.
    Returns (k_reached, ptr1, ptr2, ev_count, ev2_count). x_out[k]: position at t_k; f_out[k], f2_out[k]:
    mean of F1 + F2 and of F2 over [t_k, t_k + dt). Macro renewal times go to ev_time; micro ones to
    ev2_time only if store2. stats[0] counts evaluations of the exact solution (Newton iterates). er, pr
    (real, len nr), ec, pc (complex, len nc): scratch. Compiled without numba's reference counting (nothing is
    allocated inside): with it, the atomic increments on every array passed to the inlined helpers take half
    of the time per renewal (perf).
    """
    nr = lr.shape[0]
    nc = lcr.shape[0]
    n1 = pos1.shape[0]
    n2 = pos2.shape[0]
    F1 = sums[0]
    F2 = sums[1]
    z, dz = _eval(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, 0.0, er, pr, ec, pc)
    acc = 0.0  # zeta'' from the last two accepted iterates (finite difference; only steers the first guess)
    for k in range(k0, k1):
        t = k * dt
        x = v * t + z
        x_out[k] = x
        if x + 4.0 * v * dt > boundary:
            sums[0] = F1
            sums[1] = F2
            return k, ptr1, ptr2, ev_count, ev2_count
        h_left = dt
        imp1 = 0.0
        imp2 = 0.0
        while True:
            s1 = pos1[ptr1] if ptr1 < n1 else np.inf
            s2 = pos2[ptr2] if ptr2 < n2 else np.inf
            s = min(s1, s2)
            if s == np.inf:
                z, dz = _eval(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, h_left, er, pr, ec, pc)
                _commit(qr, gr, qc, gc, er, pr, ec, pc)
                imp1 += F1 * h_left
                imp2 += F2 * h_left
                break
            dz_old = dz
            h, hit, z, dz = _to_event(lr, ilr, cr, qr, gr, lcr, lci, ilc, cc, qc, gc, v, t, v * t + z, dz, acc, s, h_left,
                                      er, pr, ec, pc, tol, stats)
            if h > 0.0:
                acc = (dz - dz_old) / h
            imp1 += F1 * h
            imp2 += F2 * h
            t += h
            h_left -= h
            if not hit:
                break
            if s1 <= s2:
                F1 += _renew(f1, idx1[ptr1], val1[ptr1], B1r, B1c, gr, gc)
                ev_time[ev_count] = t
                ev_count += 1
                ptr1 += 1
            else:
                F2 += _renew(f2, idx2[ptr2], val2[ptr2], B2r, B2c, gr, gc)
                if store2:
                    ev2_time[ev2_count] = t
                ev2_count += 1
                ptr2 += 1
            # zeta and zeta' are state components: a new force changes neither (zeta' = row 0 of A y + B f,
            # and B has no row-0 entry), so the values at the accepted iterate carry on.
            if h_left <= 0.0:
                break
        f_out[k] = (imp1 + imp2) / dt
        f2_out[k] = imp2 / dt
    sums[0] = F1
    sums[1] = F2
    return k1, ptr1, ptr2, ev_count, ev2_count
