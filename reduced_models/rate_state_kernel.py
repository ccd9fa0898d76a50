"""The integrator of :mod:`reduced_models.rate_state`, numba: the spring-slider's right-hand side in log variables
and the adaptive Dormand-Prince 5(4) loop with dense output between output times. Pure kernels; the physics, the
parameters and the closed forms are documented and live in :mod:`reduced_models.rate_state`."""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["DORMAND_PRINCE", "rhs", "segment"]

DORMAND_PRINCE = {
    # Dormand & Prince 5(4): stage coefficients a_ij, the 5th-order weights (row 7), the error weights e_i = b_i - b*_i
    # and the dense-output weights d_i of Hairer's contd5 (Hairer, Norsett & Wanner, Solving ODEs I, II.5-6)
    "a21": 1 / 5, "a31": 3 / 40, "a32": 9 / 40, "a41": 44 / 45, "a42": -56 / 15, "a43": 32 / 9,
    "a51": 19372 / 6561, "a52": -25360 / 2187, "a53": 64448 / 6561, "a54": -212 / 729,
    "a61": 9017 / 3168, "a62": -355 / 33, "a63": 46732 / 5247, "a64": 49 / 176, "a65": -5103 / 18656,
    "a71": 35 / 384, "a73": 500 / 1113, "a74": 125 / 192, "a75": -2187 / 6784, "a76": 11 / 84,
    "e1": 71 / 57600, "e3": -71 / 16695, "e4": 71 / 1920, "e5": -17253 / 339200, "e6": 22 / 525, "e7": -1 / 40,
    "d1": -12715105075 / 11282082432, "d3": 87487479700 / 32700410799, "d4": -10690763975 / 1880347072,
    "d5": 701980252875 / 199316789632, "d6": -1453857185 / 822651844, "d7": 69997945 / 29380423,
}
_DP = DORMAND_PRINCE
_A21 = _DP["a21"]
_A31, _A32 = _DP["a31"], _DP["a32"]
_A41, _A42, _A43 = _DP["a41"], _DP["a42"], _DP["a43"]
_A51, _A52, _A53, _A54 = _DP["a51"], _DP["a52"], _DP["a53"], _DP["a54"]
_A61, _A62, _A63, _A64, _A65 = _DP["a61"], _DP["a62"], _DP["a63"], _DP["a64"], _DP["a65"]
_A71, _A73, _A74, _A75, _A76 = _DP["a71"], _DP["a73"], _DP["a74"], _DP["a75"], _DP["a76"]
_E1, _E3, _E4, _E5, _E6, _E7 = _DP["e1"], _DP["e3"], _DP["e4"], _DP["e5"], _DP["e6"], _DP["e7"]
_D1, _D3, _D4, _D5, _D6, _D7 = _DP["d1"], _DP["d3"], _DP["d4"], _DP["d5"], _DP["d6"], _DP["d7"]


@numba.njit(cache=True, error_model="numpy")
def rhs(y, out, sigma, k, A, B, Dc, V0, eta, Vlp, law):
    """(dpsi/dt, dphi/dt, ddelta/dt) of the slider in log variables (module docstring)."""
    V = V0 * math.exp(y[0])
    if law == 0:
        dphi = (V0 / Dc) * math.exp(-y[1]) - V / Dc
    else:
        dphi = -(V / Dc) * (y[0] + y[1])
    out[0] = (k * (Vlp - V) - sigma * B * dphi) / (sigma * A + eta * V)
    out[1] = dphi
    out[2] = V


@numba.njit(cache=True, error_model="numpy")
def segment(y, t, t_end, h, k_out, n_out, dt_out, out, pars, law, tol, max_steps, counters):
    """Integrate from t to t_end (DOPRI5, dense output), writing y at every output time k dt_out in (t, t_end].

    Returns (t, h, k_out, status): status 0 done, 1 too many steps, 2 step size underflow. ``counters`` adds
    (accepted, rejected) steps.
    """
    sigma, kk, A, B, Dc, V0, eta, Vlp = pars[0], pars[1], pars[2], pars[3], pars[4], pars[5], pars[6], pars[7]
    n = 3
    k1, k2, k3, k4 = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    k5, k6, k7 = np.empty(n), np.empty(n), np.empty(n)
    yt, ynew = np.empty(n), np.empty(n)
    rhs(y, k1, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
    steps = 0
    while t < t_end:
        if steps >= max_steps:
            return t, h, k_out, 1
        last = False
        if t + h >= t_end:
            h = t_end - t
            last = True
        if h <= 1e-14 * max(1.0, abs(t)):
            return t, h, k_out, 2
        for i in range(n):
            yt[i] = y[i] + h * _A21 * k1[i]
        rhs(yt, k2, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        for i in range(n):
            yt[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        rhs(yt, k3, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        for i in range(n):
            yt[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        rhs(yt, k4, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        for i in range(n):
            yt[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        rhs(yt, k5, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        for i in range(n):
            yt[i] = y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i])
        rhs(yt, k6, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        for i in range(n):
            ynew[i] = y[i] + h * (_A71 * k1[i] + _A73 * k3[i] + _A74 * k4[i] + _A75 * k5[i] + _A76 * k6[i])
        rhs(ynew, k7, sigma, kk, A, B, Dc, V0, eta, Vlp, law)
        steps += 1
        err = 0.0
        for i in range(n):
            e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
            sc = tol if i < 2 else tol * (Dc + max(abs(y[i]), abs(ynew[i])))
            err += (e / sc) ** 2
        err = math.sqrt(err / n)
        if not (err <= 1.0):  # also rejects nan
            counters[1] += 1
            fac = 0.2 if not (err < 1e300) else max(0.2, 0.9 * err ** -0.2)
            h *= fac
            continue
        counters[0] += 1
        t_new = t_end if last else t + h
        # dense output at the output times in (t, t_new]
        while k_out < n_out and k_out * dt_out <= t_new * (1.0 + 1e-14):
            th = (k_out * dt_out - t) / h
            th = min(max(th, 0.0), 1.0)
            th1 = 1.0 - th
            for i in range(n):
                r2 = ynew[i] - y[i]
                r3 = h * k1[i] - r2
                r4 = r2 - h * k7[i] - r3
                r5 = h * (_D1 * k1[i] + _D3 * k3[i] + _D4 * k4[i] + _D5 * k5[i] + _D6 * k6[i] + _D7 * k7[i])
                out[k_out, i] = y[i] + th * (r2 + th1 * (r3 + th * (r4 + th1 * r5)))
            k_out += 1
        for i in range(n):
            y[i] = ynew[i]
            k1[i] = k7[i]
        t = t_new
        fac = 10.0 if err == 0.0 else min(10.0, max(0.2, 0.9 * err ** -0.2))
        if not last:
            h *= fac
        else:
            h = h * fac if h * fac > 0 else h
    return t, h, k_out, 0
