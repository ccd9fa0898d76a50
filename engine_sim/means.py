"""Forces as means over the output step, from the momenta and places read at its two ends (scene units).

:func:`means` ends :func:`engine_sim.reduction.reduce_sample`, on the bodies' states it read, and overwrites the
forces of that row (F_t, F_n, F_drag, F_drive, the pads' and micro-pads' forces) with their means over the pymunk steps
since the previous sample, then keeps this sample's state for the next. pymunk steps by semi-implicit Euler (it moves
a body with its velocity, then updates the velocity by the step's impulses), so over the output step each body's
momentum changes by exactly the impulses on it: nothing needs reading in between. :func:`drive_force` and
:func:`spring_forces` give the smooth forces (springs) the means integrate by quadrature.
"""
from __future__ import annotations

import numba
import numpy as np

from .sample_layout import (DRIVE_K, DRIVE_REST, ANCHOR_V, ANCHOR_X, DT, F_DRAG, F_DRIVE, F_N, F_T, GRAV, GUIDED,
                        LAW_AFTER, MASS, MEANS, PULLED, STEPS, VIB_BX, VIB_BY, VIB_X, VIB_Y, W0, W1, W2, W3)

__all__ = ["means", "drive_force", "spring_forces"]

@numba.njit(cache=True)
def drive_force(dk, rest, ax, hx):
    """The drive spring's force on the body it pulls, at hx, its anchor at ax (> 0 pushes towards +x)."""
    return dk * (rest - abs(ax - hx)) * (1.0 if hx > ax else -1.0)


@numba.njit(cache=True)
def spring_forces(sp, blk, P, dt, F0, F1, L0, L1):
    """The springs' elastic forces on the sliders added to ``F0`` (n_sl x 2) at the sample's places and to ``F1`` one
    step on (X + V dt, where pymunk's next step puts every body before it evaluates a spring), and each spring's
    length there in ``L0``, ``L1``. ``sp`` rows: body a (-1: the block), body b (a slider), anchors on a and b, rest
    length, stiffness, damping (DampedSpring's order: the force pushes b away from a when compressed)."""
    for r in range(sp.shape[0]):
        a, b = int(sp[r, 0]), int(sp[r, 1])
        if a < 0:
            ax, ay, avx, avy = blk[0], blk[1], blk[2], blk[3]
        else:
            ax, ay, avx, avy = P[a, 0], P[a, 1], P[a, 2], P[a, 3]
        dx = P[b, 0] + sp[r, 4] - (ax + sp[r, 2])
        dy = P[b, 1] + sp[r, 5] - (ay + sp[r, 3])
        ex = dx + dt * (P[b, 2] - avx)
        ey = dy + dt * (P[b, 3] - avy)
        k, rest = sp[r, 7], sp[r, 6]
        l0 = np.sqrt(dx * dx + dy * dy)
        l1 = np.sqrt(ex * ex + ey * ey)
        L0[r], L1[r] = l0, l1
        f0, f1 = k * (rest - l0) / l0, k * (rest - l1) / l1
        F0[b, 0] += f0 * dx
        F0[b, 1] += f0 * dy
        F1[b, 0] += f1 * ex
        F1[b, 1] += f1 * ey
        if a >= 0:
            F0[a, 0] -= f0 * dx
            F0[a, 1] -= f0 * dy
            F1[a, 0] -= f1 * ex
            F1[a, 1] -= f1 * ey


@numba.njit(cache=True)
def means(blk, P, D, sp, prm, sl, dm, ms, ls, lt, k, out, pad_force, micro_force):
    """The forces of row ``k`` as means over the output step since the previous sample, from the momenta read at its
    two ends (no per-step reads); then this sample's state into ``ms``, ``ls`` for the next (module docstring).

    Each body's momentum changes over the step by the impulses on it. The sliding system (block, sliders, the drive's
    bodies) feels, besides its contact forces: the drive spring (a smooth function of two places: integrated with the
    weights w0..w3 from its values at both ends and one step after each, exact for a cubic in the step index); the
    law's dampers c v (pymunk applies a damper's impulse last in a step, as -c dt v with v the step's final velocity,
    so over the steps it sums to -c (dx + dv dt) exactly); a law's per-step impulses (``lt``: the law's running totals per slider, less those at the previous sample,
    kept in ``ms``);
    gravity; a vibration's known impulses (``prm``). Its internal springs cancel, so the total tangential contact
    force F_t is exact, and the normal F_n too when the block is free vertically; a guided block's guide adds an
    unknown vertical impulse, so then F_n is the sum over the sliders of the per-slider balance. A slider's own
    balance also takes its springs' impulses: elastic (the same quadrature) and damping (-c_eff times the change of
    the spring's length one step on, along the spring: exact for a damper applied last in a step, as above)."""
    n_sl = P.shape[0]
    dt = prm[DT]
    lj = np.empty(n_sl)  # the law's impulses on each slider over the output step
    for i in range(n_sl):
        lj[i] = lt[i] - ms[1 + i, 8]
        ms[1 + i, 8] = lt[i]
    F0 = np.zeros((n_sl, 2))
    F1 = np.zeros((n_sl, 2))
    L0 = np.empty(sp.shape[0])
    L1 = np.empty(sp.shape[0])
    spring_forces(sp, blk, P, dt, F0, F1, L0, L1)
    pulled = int(prm[PULLED])
    hx, hvx = (blk[0], blk[2]) if pulled < 0 else (D[pulled, 0], D[pulled, 1])
    dk, rest, ax, av = prm[DRIVE_K], prm[DRIVE_REST], prm[ANCHOR_X], prm[ANCHOR_V]
    fd0 = drive_force(dk, rest, ax, hx)
    fd1 = drive_force(dk, rest, ax + av * dt, hx + hvx * dt)
    m_s = prm[MASS]
    px, py = prm[MASS] * blk[2], prm[MASS] * blk[3]
    for i in range(n_sl):
        px += sl[i, 0] * P[i, 2]
        py += sl[i, 0] * P[i, 3]
        m_s += sl[i, 0]
    m_x = m_s
    for j in range(dm.shape[0]):
        px += dm[j] * D[j, 1]
        m_x += dm[j]
    n_steps = prm[STEPS]
    if prm[MEANS] > 0.0 and n_steps > 0.0:
        T = n_steps * dt
        w0, w1, w2, w3 = prm[W0], prm[W1], prm[W2], prm[W3]
        g = prm[GRAV]
        vx_, vy_ = prm[VIB_X], prm[VIB_Y]
        after = prm[LAW_AFTER] > 0.0
        f_drive = w0 * ms[0, 2] + w1 * ms[0, 3] + w2 * fd0 + w3 * fd1
        # damping impulses of the springs on each slider: -c_eff (length one step on, now - then) along the spring
        JD = np.zeros((n_sl, 2))
        for r in range(sp.shape[0]):
            c = sp[r, 8]
            if c == 0.0:
                continue
            a, b = int(sp[r, 0]), int(sp[r, 1])
            ax_, ay_ = (blk[0], blk[1]) if a < 0 else (P[a, 0], P[a, 1])
            dx = P[b, 0] + sp[r, 4] - (ax_ + sp[r, 2])
            dy = P[b, 1] + sp[r, 5] - (ay_ + sp[r, 3])
            dl = L1[r] - ls[r]
            if after:  # the damper saw the velocities before the law's impulses: the motion less their share
                dl -= dt * (lj[b] / sl[b, 0] * dx - (0.0 if a < 0 else lj[a] / sl[a, 0] * dx)) / L0[r]
            j = -c * dl / L0[r]
            JD[b, 0] += j * dx
            JD[b, 1] += j * dy
            if a >= 0:
                JD[a, 0] -= j * dx
                JD[a, 1] -= j * dy
        drag = 0.0  # the law's impulses on the sliders (x), dampers and per-step parts
        fn = 0.0
        N = pad_force.shape[1]
        for i in range(n_sl):
            m = sl[i, 0]
            moved = P[i, 0] - ms[1 + i, 0] + (P[i, 2] - ms[1 + i, 2]) * dt
            if after:  # the damper saw the velocity before the law's impulses
                moved -= lj[i] / m * dt
            jd = -sl[i, 1] * moved + lj[i]
            drag += jd
            jsx = T * (w0 * ms[1 + i, 4] + w1 * ms[1 + i, 6] + w2 * F0[i, 0] + w3 * F1[i, 0])
            jsy = T * (w0 * ms[1 + i, 5] + w1 * ms[1 + i, 7] + w2 * F0[i, 1] + w3 * F1[i, 1])
            cx = m * (P[i, 2] - ms[1 + i, 2] - vx_) - jsx - JD[i, 0] - jd
            cy = m * (P[i, 3] - ms[1 + i, 3] - vy_ + g * T) - jsy - JD[i, 1]
            if i < N:
                pad_force[k, i] = -cx / T
            else:
                micro_force[k, i - N] = -cx / T
            fn += cy / T
        if prm[GUIDED] == 0.0:  # the system's own vertical balance: exact
            fn = (py - ms[0, 1] + m_s * (g * T - vy_) - prm[VIB_BY]) / T
        cx = px - ms[0, 0] - m_x * vx_ - prm[VIB_BX] - f_drive * T - drag
        out[k, F_T] = -cx / T
        out[k, F_N] = fn
        out[k, F_DRAG] = -drag / T
        out[k, F_DRIVE] = f_drive
    ms[0, 0], ms[0, 1], ms[0, 2], ms[0, 3] = px, py, fd0, fd1
    for i in range(n_sl):
        for q in range(4):
            ms[1 + i, q] = P[i, q]
        ms[1 + i, 4], ms[1 + i, 5], ms[1 + i, 6], ms[1 + i, 7] = F0[i, 0], F0[i, 1], F1[i, 0], F1[i, 1]
    for r in range(sp.shape[0]):
        ls[r] = L1[r]

