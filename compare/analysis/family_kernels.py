"""The compiled loops of the spectral families' shapes (:mod:`compare.analysis.families`): model I's kind (model I,
Ib, the ageing model) and model III's window, one pass over the frequencies each. Computation only; the physics and
the equations are documented in :mod:`compare.analysis.families`.

A fit evaluates a shape thousands of times on a few thousand frequencies (every aliasing image, and for model III
every sub-point of every ordinate's cell: 4e5 frequencies for a 400 s record at 1 kHz); the same expressions written
as array operations pass over the frequencies a dozen times with a temporary array each, which cost 3-8 times as
much on a 400 s record (measured by ``benchmarks/bench_identify.py``'s ratio). A division by zero gives inf or nan,
as in numpy (numba's ``error_model="numpy"``): a fit's trial point may reach omega = 0 (a sub-point of the lowest
ordinate's cell) and its likelihood is then infinite, not an error.
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["contact_spectrum", "window_spectrum"]


@numba.njit(cache=True, error_model="numpy")
def _renewal(x):
    """1 - cos(x) sinc^2(x / 2), the renewal factor R of model I's family, sinc(u) = sin(u) / u."""
    h = 0.5 * x
    s = 1.0 if h == 0.0 else math.sin(h) / h
    return 1.0 - math.cos(x) * s * s


@numba.njit(cache=True, error_model="numpy")
def _contact_loop(w, L, a_v, L2, a2_v, omega3, omega_c, Q, omega_0, inv_omega_1, b, dc_v, out):
    # in real arithmetic (compiled complex division is the robust, slower one): with y = omega D_c / v,
    # c / c_inf = 1 - b / (1 + i y) = sr + i si; with u = omega / omega_0 the spring 1 - r^2 / (1 + i u) = pr + i pi_;
    # z = spring (1 + i k / slope) + i r / (Q slope), k = omega / omega_1, 1 / slope = conj(slope) / |slope|^2
    for i in range(w.shape[0]):
        wi = w[i]
        level = L * _renewal(wi * a_v)
        if L2 != 0.0:
            u3 = wi / omega3
            level += L2 * _renewal(wi * a2_v) / (1.0 + u3 * u3)
        y = wi * dc_v
        d = b / (1.0 + y * y)
        sr, si = 1.0 - d, d * y
        s2 = sr * sr + si * si
        r = wi / omega_c
        u = wi / omega_0
        e = r * r / (1.0 + u * u)
        pr, pi_ = 1.0 - e, e * u
        k = wi * inv_omega_1 / s2  # i k conj(slope) = k si + i k sr
        ar, ai = 1.0 + k * si, k * sr
        q = r / (Q * s2)  # i q conj(slope) = q si + i q sr
        zr = pr * ar - pi_ * ai + q * si
        zi = pr * ai + pi_ * ar + q * sr
        w2 = wi * wi
        out[i] = level / ((zr * zr + zi * zi) * s2 * w2 * w2)


def contact_spectrum(w, *, L, a_v, omega_c, Q, omega_0, inv_omega_1=0.0, L2=0.0, a2_v=0.0, omega3=1.0, b=0.0,
                     dc_v=0.0) -> np.ndarray:
    """C_x of model I's kind (Units: m^2 s) at angular frequencies ``w`` (rad/s, any shape):
    [L R(omega a / v) + L2 R(omega a2 / v) / (1 + (omega / omega3)^2)] G(omega) / (s(omega) omega^4), with
    R the renewal factor, G the block's response (both in :mod:`compare.analysis.families`) at the contacts' slope
    c(omega) / c = 1 - b / (1 + i omega D_c / v) and s(omega) that slope's squared modulus, the contacts' inertia
    1 / omega_1 (0: massless miniblocks).

    Keyword parameters in the families' units: ``a_v`` = a / v and ``a2_v`` = a2 / v (s), ``dc_v`` = D_c / v (s),
    ``inv_omega_1`` (s); ``L2 = 0`` leaves the micro level out, ``b = 0`` the slope constant."""
    w = np.asarray(w, dtype=float)
    flat = np.ascontiguousarray(w.ravel())
    out = np.empty_like(flat)
    _contact_loop(flat, float(L), float(a_v), float(L2), float(a2_v), float(omega3), float(omega_c), float(Q),
                  float(omega_0), float(inv_omega_1), float(b), float(dc_v), out)
    return out.reshape(w.shape)


@numba.njit(cache=True, error_model="numpy")
def _window_loop(w, L, width, two_pi_v, out):
    for i in range(w.shape[0]):
        wi = w[i]
        x = math.pi * (wi * width / two_pi_v)
        s = 1.0 if x == 0.0 else math.sin(x) / x
        w2 = wi * wi
        out[i] = L * s * s / (w2 * w2)


def window_spectrum(w, *, L: float, width: float, v: float) -> np.ndarray:
    """Model III's C_x = L sinc^2(omega w / (2 v)) / omega^4 (Units: m^2 s) at ``w`` (rad/s, any shape), ``width``
    the window w (m), ``v`` the speed (m/s)."""
    w = np.asarray(w, dtype=float)
    flat = np.ascontiguousarray(w.ravel())
    out = np.empty_like(flat)
    _window_loop(flat, float(L), float(width), 2.0 * math.pi * float(v), out)
    return out.reshape(w.shape)
