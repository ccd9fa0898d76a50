"""Exact propagation of a linear system driven by piecewise-constant forces (models I and Ib).

Between renewals the deviation equations of the spring-block models are linear with constant forcing,
``y' = A y + B f``, so in the eigenbasis of A (``q = V^-1 y``) each mode evolves as

    q_k(t + h) = e^{lambda_k h} q_k(t) + phi_1(lambda_k h) h g_k,     phi_1(z) = (e^z - 1) / z,

with ``g = V^-1 B f`` the modal forcing. The state is real, so of each conjugate pair of modes one is kept
with weight 2 on its output. This module holds the modal decomposition and the numba kernel shared by
:mod:`reduced_models.spring_block` (model I); it has no physics of its own.
"""
from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

__all__ = ["Modes", "modal_decomposition", "first_order"]


@dataclass(frozen=True)
class Modes:
    """Modal form: real modes (r) and one mode of each conjugate pair (c, weight 2 folded into the outputs).

    zeta = sum c0_r q_r + Re sum c0_c q_c;  q' = lambda q + B f.  ``C_r``, ``C_c`` are optional extra output
    rows (e.g. each miniblock's displacement), same convention as ``c0``.
    """

    lam_r: np.ndarray
    c0_r: np.ndarray
    B_r: np.ndarray
    lam_c: np.ndarray
    c0_c: np.ndarray
    B_c: np.ndarray
    C_r: np.ndarray
    C_c: np.ndarray


def first_order(Mdiag: np.ndarray, D: np.ndarray, K: np.ndarray) -> np.ndarray:
    """A of y' = A y for M q'' + D q' + K q = 0 with y = (q, q'), M diagonal."""
    n = len(Mdiag)
    minv = 1.0 / np.asarray(Mdiag, dtype=float)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -minv[:, None] * K
    A[n:, n:] = -minv[:, None] * D
    return A


def modal_decomposition(A: np.ndarray, B: np.ndarray, out_rows: np.ndarray | None = None) -> Modes:
    """Eigen-decomposition of y' = A y + B f with output zeta = y[0] and optional rows ``out_rows`` (R x n).

    Translation invariance gives one exact zero eigenvalue, which eig returns as ~1e-10: it is set to 0.
    """
    lam, V = np.linalg.eig(A)
    i0 = int(np.argmin(np.abs(lam)))
    lam[i0] = 0.0
    Vi = np.linalg.inv(V)
    Bm = Vi @ B
    c0 = V[0, :].copy()
    rows = np.zeros((0, A.shape[0])) if out_rows is None else np.asarray(out_rows, dtype=float)
    Cm = rows @ V
    scale = np.maximum(np.abs(lam), 1.0)
    real = np.abs(lam.imag) <= 1e-12 * scale
    upper = lam.imag > 1e-12 * scale
    if 2 * upper.sum() + real.sum() != len(lam):
        raise np.linalg.LinAlgError("eigenvalues of the spring-block system do not pair up; please report the parameters")
    return Modes(
        lam_r=np.ascontiguousarray(lam[real].real), c0_r=np.ascontiguousarray(c0[real].real),
        B_r=np.ascontiguousarray(Bm[real].real),
        lam_c=np.ascontiguousarray(lam[upper]), c0_c=np.ascontiguousarray(2.0 * c0[upper]),
        B_c=np.ascontiguousarray(Bm[upper]),
        C_r=np.ascontiguousarray(Cm[:, real].real), C_c=np.ascontiguousarray(2.0 * Cm[:, upper]),
    )


# ----------------------------------------------------------------------------- numba kernel
@numba.njit(cache=True)
def _phi1_r(z):
    """(e^z - 1) / z for real z, stable near 0."""
    if abs(z) < 1e-8:
        return 1.0 + 0.5 * z
    return np.expm1(z) / z


@numba.njit(cache=True)
def _phi1_c(z):
    if abs(z) < 1e-8:
        return 1.0 + 0.5 * z
    return (np.exp(z) - 1.0) / z


@numba.njit(cache=True, _nrt=False)
def _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h):
    """(zeta, zeta') of the big block a time h ahead of the modal state (exact, constant forcing)."""
    z = 0.0
    dz = 0.0
    for k in range(lr.shape[0]):
        e = np.exp(lr[k] * h)
        z += cr[k] * (e * qr[k] + _phi1_r(lr[k] * h) * h * gr[k])
        dz += cr[k] * (lr[k] * e * qr[k] + e * gr[k])
    for k in range(lc.shape[0]):
        e = np.exp(lc[k] * h)
        z += (cc[k] * (e * qc[k] + _phi1_c(lc[k] * h) * h * gc[k])).real
        dz += (cc[k] * (lc[k] * e * qc[k] + e * gc[k])).real
    return z, dz


@numba.njit(cache=True, _nrt=False)
def _advance(lr, qr, gr, lc, qc, gc, h):
    for k in range(lr.shape[0]):
        z = lr[k] * h
        qr[k] = np.exp(z) * qr[k] + _phi1_r(z) * h * gr[k]
    for k in range(lc.shape[0]):
        z = lc[k] * h
        qc[k] = np.exp(z) * qc[k] + _phi1_c(z) * h * gc[k]


@numba.njit(cache=True, _nrt=False)
def _crossing(lr, cr, qr, gr, lc, cc, qc, gc, v, t, s, h_max, f_hi):
    """Time h in (0, h_max] at which v (t + h) + zeta(t + h) reaches s (safeguarded Newton).

    f_hi is the (non-negative) overshoot at h_max; the root is bracketed in [0, h_max].
    """
    z0, dz0 = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    f_lo = v * t + z0 - s
    lo, hi = 0.0, h_max
    h = h_max * (-f_lo) / (f_hi - f_lo) if f_hi > f_lo else 0.5 * h_max
    for _ in range(100):
        z, dz = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h)
        f = v * (t + h) + z - s
        if f < 0.0:
            lo = h
        else:
            hi = h
        if hi - lo <= 1e-15 * h_max:
            break
        d = v + dz
        h_new = h - f / d if d > 0.0 else 0.5 * (lo + hi)
        if not (lo < h_new < hi):
            h_new = 0.5 * (lo + hi)
        if abs(h_new - h) <= 1e-14 * h_max:
            h = h_new
            break
        h = h_new
    return min(max(h, lo), hi)


@numba.njit(cache=True, _nrt=False)
def _outputs(Cr, qr, Cc, qc, out, k):
    for i in range(Cr.shape[0]):
        s = 0.0
        for j in range(Cr.shape[1]):
            s += Cr[i, j] * qr[j]
        for j in range(Cc.shape[1]):
            s += (Cc[i, j] * qc[j]).real
        out[k, i] = s


@numba.njit(cache=True, _nrt=False)
def run_renewals(lr, cr, Br, lc, cc, Bc, Cr, Cc, qr, gr, qc, gc, forces, v, dt, k0, k1, ev_pos, ev_idx, ev_val,
                 ptr, boundary, x_out, f_out, xc_out, ev_time, ev_count, Er, Pr, Ec, Pc, qnr, qnc):
    """Step output intervals k0..k1-1; stop early (return k) when the block nears the loaded boundary.

    Returns (k_reached, ptr, ev_count). x_out[k] = position at t_k, f_out[k] = mean summed force over
    [t_k, t_k + dt), xc_out[k] = the extra output rows (Cr, Cc) at t_k (none when Cr has no rows). Renewal i
    changes the modal forcing by B[:, i] times its force change. Er, Pr, qnr (real, len nr) and Ec, Pc, qnc
    (complex, len nc): scratch. Compiled without numba's reference counting (nothing is allocated inside; the
    atomic increments cost more than the arithmetic of the 4-mode reduced system).
    """
    nr = lr.shape[0]
    nc = lc.shape[0]
    for k in range(nr):
        Er[k] = np.exp(lr[k] * dt)
        Pr[k] = _phi1_r(lr[k] * dt) * dt
    for k in range(nc):
        Ec[k] = np.exp(lc[k] * dt)
        Pc[k] = _phi1_c(lc[k] * dt) * dt
    fsum = 0.0
    for i in range(forces.shape[0]):
        fsum += forces[i]
    n_ev = ev_pos.shape[0]
    n_rows = Cr.shape[0]
    zeta, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    for k in range(k0, k1):
        t = k * dt
        x_out[k] = v * t + zeta
        if x_out[k] + 4.0 * v * dt > boundary:
            return k, ptr, ev_count
        if n_rows > 0:
            _outputs(Cr, qr, Cc, qc, xc_out, k)
        # Fast path: one exact step with the precomputed propagator, kept if no renewal is crossed.
        zn = 0.0
        for j in range(nr):
            qnr[j] = Er[j] * qr[j] + Pr[j] * gr[j]
            zn += cr[j] * qnr[j]
        for j in range(nc):
            qnc[j] = Ec[j] * qc[j] + Pc[j] * gc[j]
            zn += (cc[j] * qnc[j]).real
        if ptr >= n_ev or v * (t + dt) + zn < ev_pos[ptr]:
            for j in range(nr):
                qr[j] = qnr[j]
            for j in range(nc):
                qc[j] = qnc[j]
            zeta = zn
            f_out[k] = fsum
            continue
        # Slow path: locate each renewal inside the step and propagate exactly to it.
        h_left = dt
        impulse = 0.0
        over = v * (t + dt) + zn - ev_pos[ptr]
        while True:
            h = _crossing(lr, cr, qr, gr, lc, cc, qc, gc, v, t, ev_pos[ptr], h_left, over)
            _advance(lr, qr, gr, lc, qc, gc, h)
            impulse += fsum * h
            t += h
            h_left -= h
            i = ev_idx[ptr]
            df = ev_val[ptr] - forces[i]
            forces[i] = ev_val[ptr]
            fsum = 0.0  # summed afresh, not incremented, so re-entering the kernel cannot change its bits
            for j in range(forces.shape[0]):
                fsum += forces[j]
            for j in range(nr):
                gr[j] += Br[j, i] * df
            for j in range(nc):
                gc[j] += Bc[j, i] * df
            ev_time[ev_count] = t
            ev_count += 1
            ptr += 1
            if ptr >= n_ev:
                break
            z_end, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h_left)
            over = v * (t + h_left) + z_end - ev_pos[ptr]
            if over < 0.0:
                break
        _advance(lr, qr, gr, lc, qc, gc, h_left)
        impulse += fsum * h_left
        f_out[k] = impulse / dt
        zeta, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    return k1, ptr, ev_count
