"""The recorder's reduction: one output sample from pymunk's raw batch buffers, in numba kernels (scene units).

:func:`reduce_sample` reads the bodies ``[px, py, vx, vy, w]`` by id and the arbiters ``[a_id, b_id, count] x
[Jx, Jy, nx, ny, pax, pay, pbx, pby, d1]`` (J the impulse on body A over the last step) and writes one row of the
recorder's buffers. It is a sequence of small kernels, each one job: the bodies' states (:func:`read_bodies`), the
contact forces and the friction power at the contacts (:func:`contacts`), the sliding bodies' forces, drag and
energies (:func:`sliders`), the grains' states and energies (:func:`grains`), the springs' energy and damping
(:func:`springs`), the drive (:func:`drive`) and the momentum of the bodies with energy (:func:`momentum`, which a
shaken substrate's inertial force works on). The friction law's velocity part is the form the shipped laws share
(:func:`law_drag`) plus, for a law of another form, its values at the sample, which the law's own kernel computes
(:meth:`engine_sim.laws.Law.recorded_drag`) at the sliders' velocities (:func:`slider_velocities`). The running sums (kinetic and potential energy, dissipated power)
are handed from kernel to kernel, so every sum is taken in one fixed order. Columns and parameters are read by the
names of :mod:`engine_sim.sample_layout`.
"""
from __future__ import annotations

import numba
import numpy as np

from .contact_order import arbiter_keys, arbiter_order, body_of
from .means import means, spring_forces
from .sample_layout import (  # the layout's names, frozen into the kernels as constants
    X, V, F_T, F_N, F_DRAG, F_DRIVE, PEN, POWER_IN, POWER_OUT, MECH, PAIRS, P_PEN, STALE, MOM_X, MOM_Y, DRIVE_K,
    ANCHOR_X, DRIVE_REST, ANCHOR_V, X0, DT, MASS, GRAV, V_TRAP, DT_OUT, PULLED, VIB_LX, VIB_LY, PAIR_MID, BLOCK,
    SLIDER, GRAIN, DRIVE_BODY, STATIC, AF, JX, JY, NX, NY, PAX, PAY, PBX, PBY, DIST, G_MASS, G_MOMENT, G_R,
    G_ASLEEP, G_X, G_Y, STALE_TOL,
)

__all__ = ["reduce_sample", "slider_velocities"]


@numba.njit(cache=True)
def read_bodies(ids, fl, tab, grain, n_sl, n_d):
    """The bodies' states from the body buffer: block (x, y, vx, vy), sliders P (x, y, vx, vy), the drive's bodies D
    (x, vx, vy) and grains Q (x, y, vx, vy, w). Bodies absent from the buffer are asleep, at rest: sliders read zero,
    grains their last known place. A grain flagged asleep reads at rest; its place is remembered in ``grain``."""
    n_p = grain.shape[0]
    blk = np.zeros(4)
    P = np.zeros((n_sl, 4))
    D = np.zeros((n_d, 3))
    Q = np.zeros((n_p, 5))
    for j in range(n_p):
        Q[j, 0], Q[j, 1] = grain[j, G_X], grain[j, G_Y]
    for r in range(ids.shape[0]):
        kind, i = body_of(tab, ids[r])
        f0 = 5 * r  # the body's five floats in the buffer (x, y, vx, vy, w)
        if kind == BLOCK:
            for q in range(4):
                blk[q] = fl[f0 + q]
        elif kind == SLIDER:
            for q in range(4):
                P[i, q] = fl[f0 + q]
        elif kind == GRAIN:
            for q in range(5):
                Q[i, q] = fl[f0 + q]
            if grain[i, G_ASLEEP] > 0:
                Q[i, 2] = Q[i, 3] = Q[i, 4] = 0.0
            grain[i, G_X], grain[i, G_Y] = fl[f0], fl[f0 + 1]
        elif kind == DRIVE_BODY:
            D[i, 0], D[i, 1], D[i, 2] = fl[f0], fl[f0 + 2], fl[f0 + 3]
    return blk, P, D, Q


@numba.njit(cache=True)
def contact_velocity(kind, i, Vm, Q, blk, px, py):
    """Velocity (vx, vy) of body (kind, i) at the contact point (px, py): grains rotate, the others do not; a
    slider's is its mean over the last step (``Vm``, :func:`step_mean_velocity`)."""
    if kind == SLIDER:
        return Vm[i, 0], Vm[i, 1]
    if kind == GRAIN:
        return Q[i, 2] - Q[i, 4] * (py - Q[i, 1]), Q[i, 3] + Q[i, 4] * (px - Q[i, 0])
    if kind == BLOCK:
        return blk[2], blk[3]
    return 0.0, 0.0


@numba.njit(cache=True)
def contacts(ai, af, key, grain, Q, dt, k, p_force, n_sl):
    """Contact forces of the arbiters, in a fixed order (:func:`arbiter_order`); ``key``: each arbiter's bodies as
    (kind, index) pairs (:func:`arbiter_keys`).

    Returns per slider the (x, y) contact force (ft, fn, on the slider) and whether it touches its track;
    per grain whether it presses on its pad (its force on the pad, against sliding, goes to ``p_force[k]``); the
    deepest pad-track and grain-track overlaps; the pad-track contact pairs; the stale grain arbiters skipped; and
    the arbiters counted, in order, for :func:`friction_power`. The normal part of the power is left
    out: after a step of a few solver iterations the bodies keep a small residual normal velocity at resting contacts
    (pymunk's position bias fixes the error and does no recorded work), and its product with the normal force reads
    as a spurious 5-6 % of the drive's work once grains slide on tracks; resting contacts do no work, and inelastic
    impacts are rare here."""
    n_p = grain.shape[0]
    ft = np.zeros(n_sl)
    fn = np.zeros(n_sl)
    touch = np.zeros(n_sl, dtype=np.bool_)
    p_touch = np.zeros(n_p, dtype=np.bool_)
    pen = 0.0
    p_pen = 0.0
    pairs = 0
    stale_count = 0
    used = np.empty(ai.shape[0] // 3, dtype=np.int64)
    n_used = 0
    kinds = np.empty(2, dtype=np.int64)  # per arbiter: kind and index of bodies A and B
    idx = np.empty(2, dtype=np.int64)
    for r in arbiter_order(key, af):  # sums over several contacts of one pad must not depend on the batch's order
        if ai[3 * r + 2] <= 0:
            continue
        a0 = AF * r
        Fx, Fy = af[a0 + JX] / dt, af[a0 + JY] / dt  # on A; B feels minus this
        for s in range(2):
            kinds[s], idx[s] = key[r, 2 * s], key[r, 2 * s + 1]
        # a sleeping grain's cached arbiter holds stale contact data; asleep, a grain only rests on its track
        if (kinds[0] == GRAIN and grain[idx[0], G_ASLEEP] > 0) or (kinds[1] == GRAIN and grain[idx[1], G_ASLEEP] > 0):
            continue
        # pymunk re-lists a woken grain's cached arbiters (after a restore every grain wakes) with contact points from
        # before it slept or was moved, until the next step recomputes them: skip (and count) them
        if (kinds[0] == GRAIN or kinds[1] == GRAIN) and stale(kinds, idx, af, a0, Q, grain):  # pads never go stale
            stale_count += 1
            continue
        used[n_used] = r
        n_used += 1
        for s in range(2):
            if kinds[s] != SLIDER:
                continue
            sg = 1.0 if s == 0 else -1.0
            i = idx[s]
            other = kinds[1 - s]
            ft[i] += sg * Fx
            fn[i] += sg * Fy
            if other == GRAIN:  # a grain pressing on the pad
                j = idx[1 - s]
                p_force[k, j] -= sg * Fx
                p_touch[j] = True
            elif other == STATIC:  # the pad on its track
                pen = max(pen, -af[a0 + DIST])  # contact distance < 0: overlap depth
                touch[i] = True
                pairs += 1
        if (kinds[0] == GRAIN and kinds[1] == STATIC) or (kinds[1] == GRAIN and kinds[0] == STATIC):  # grain on track
            p_pen = max(p_pen, -af[a0 + DIST])
    return ft, fn, touch, p_touch, pen, p_pen, pairs, stale_count, used[:n_used]


@numba.njit(cache=True)
def friction_power(used, af, key, Vm, Q, blk, dt):
    """The friction power at the contacts ``used`` (:func:`contacts`; ``key``: :func:`arbiter_keys`): tangential
    force times tangential slip, the sliders' velocities ``Vm`` (in a shaken scene their means over the last step,
    :func:`step_mean_velocity`)."""
    pout = 0.0
    kinds = np.empty(2, dtype=np.int64)
    idx = np.empty(2, dtype=np.int64)
    for r in used:
        a0 = AF * r
        Fx, Fy = af[a0 + JX] / dt, af[a0 + JY] / dt  # on A; B feels minus this
        tx, ty = -af[a0 + NY], af[a0 + NX]  # contact tangent
        px, py = af[a0 + PAX], af[a0 + PAY]
        Ft = Fx * tx + Fy * ty
        for s in range(2):
            kinds[s], idx[s] = key[r, 2 * s], key[r, 2 * s + 1]
        for s in range(2):
            if kinds[s] == STATIC:  # at rest: no power (Ft is finite)
                continue
            sg = 1.0 if s == 0 else -1.0
            vx, vy = contact_velocity(kinds[s], idx[s], Vm, Q, blk, px, py)
            pout -= sg * Ft * (vx * tx + vy * ty)
    return pout


@numba.njit(cache=True)
def law_drag(c, bN, vc, vx):
    """The velocity part the shipped laws share, on a slider at speed vx: c v + b N_pad ln(1 + |v|/v_c) sign(v)
    (``c``, ``bN``, ``vc``: its row of ``sl``, columns 1-3, from :meth:`engine_sim.laws.Law.drag_terms`; scalars, as
    an array argument costs a reference count per call)."""
    f_v = c * vx
    if bN > 0.0:
        f_v += np.sign(vx) * bN * np.log1p(abs(vx) / vc)
    return f_v


@numba.njit(cache=True)
def slider_velocities(ids, fl, tab, v):
    """Each sliding body's x velocity from the body buffer into ``v`` (zero for a body absent from it: asleep, at
    rest), as :func:`read_bodies` reads it: what a law's velocity part is evaluated at
    (:meth:`engine_sim.laws.Law.recorded_drag`)."""
    v[:] = 0.0
    for r in range(ids.shape[0]):
        kind, i = body_of(tab, ids[r])
        if kind == SLIDER:
            v[i] = fl[5 * r + 2]


@numba.njit(cache=True)
def step_mean_velocity(blk, P, sl, sp, ft, fn, fv, prm):
    """Each slider's mean velocity over the last pymunk step, v - dv / 2, dv = (the step's impulses) / m: contacts
    (``ft``, ``fn``: x, y forces), springs (elastic at the present places, where pymunk evaluated them; damping
    -c_eff dt v_rel along them), the law's drag -f_v dt (:func:`law_drag` plus ``fv``, the law's own velocity
    part per slider at the sample), a vibration's field and gravity. A step's impulse J does
    J . (v_before + v_after) / 2; J . v_after over-counts J^2 / 2m, in the law's dampers (c dt / 4) sum dv^2, which
    a vibration makes large. Used in shaken scenes only (``pair_mid``; docs/results/vibration.md)."""
    n_sl = P.shape[0]
    dt = prm[DT]
    F0 = np.zeros((n_sl, 2))
    F1 = np.zeros((n_sl, 2))
    L0 = np.empty(sp.shape[0])
    L1 = np.empty(sp.shape[0])
    spring_forces(sp, blk, P, dt, F0, F1, L0, L1)
    for r in range(sp.shape[0]):
        c = sp[r, 8]
        if c == 0.0:
            continue
        a, b = int(sp[r, 0]), int(sp[r, 1])
        ax, ay, avx, avy = (blk[0], blk[1], blk[2], blk[3]) if a < 0 else (P[a, 0], P[a, 1], P[a, 2], P[a, 3])
        dx = P[b, 0] + sp[r, 4] - (ax + sp[r, 2])
        dy = P[b, 1] + sp[r, 5] - (ay + sp[r, 3])
        ln = np.sqrt(dx * dx + dy * dy)
        f = -c * ((P[b, 2] - avx) * dx + (P[b, 3] - avy) * dy) / (ln * ln)  # damping force on b per unit of (dx, dy)
        F0[b, 0] += f * dx
        F0[b, 1] += f * dy
        if a >= 0:
            F0[a, 0] -= f * dx
            F0[a, 1] -= f * dy
    Vm = np.empty((n_sl, 2))
    for i in range(n_sl):
        m = sl[i, 0]
        f_v = law_drag(sl[i, 1], sl[i, 2], sl[i, 3], P[i, 2]) + fv[i]
        Vm[i, 0] = P[i, 2] - 0.5 * ((F0[i, 0] + ft[i] - f_v) * dt / m + prm[VIB_LX])
        Vm[i, 1] = P[i, 3] - 0.5 * ((F0[i, 1] + fn[i]) * dt / m + prm[VIB_LY] - prm[GRAV] * dt)
    return Vm


@numba.njit(cache=True)
def sliders(P, Vm, sl, fv, ft, fn, touch, g, k, pad_force, micro_force, ke, pe, pout):
    """Per sliding body (the pads first, then any micro-pads): its tangential force against sliding into
    ``pad_force[k]`` or ``micro_force[k]``, and the sums: the tangential and normal contact force, the friction law's
    velocity part and its power (the form the shipped laws share, :func:`law_drag`, with ``sl``: mass, c, b N_pad,
    v_c per body; plus ``fv``, a law's own part at the sample, :meth:`~engine_sim.laws.Law.recorded_drag`), the pads touching their track; the bodies' kinetic and potential
    energy added to ``ke``, ``pe``. The law's power pairs its force with the step's mean velocity ``Vm``
    (:func:`friction_power`)."""
    N = pad_force.shape[1]
    sft = 0.0
    sfn = 0.0
    drag = 0.0
    nc = 0
    for i in range(sl.shape[0]):
        if i < N:
            pad_force[k, i] = -ft[i]
            nc += touch[i]
        else:
            micro_force[k, i - N] = -ft[i]
        sft -= ft[i]
        sfn += fn[i]
        m_p = sl[i, 0]
        f_v = law_drag(sl[i, 1], sl[i, 2], sl[i, 3], P[i, 2]) + fv[i]  # the law's velocity part on this body
        drag += f_v
        pout += f_v * Vm[i, 0]
        ke += 0.5 * m_p * (P[i, 2] ** 2 + P[i, 3] ** 2)
        pe += m_p * g * P[i, 1]
    return sft, sfn, drag, nc, ke, pe, pout


@numba.njit(cache=True)
def grains(grain, Q, prev, p_touch, g, v_trap, dt_out, k, p_state, ke, pe):
    """Each grain's state into ``p_state[k]``: 0 idle (not touching its pad), 1 trapped (touching, its mean speed
    since the previous sample, from its places ``prev`` then, below ``v_trap``), 2 moving; its kinetic and
    potential energy added to ``ke``, ``pe``."""
    for j in range(grain.shape[0]):
        m, I = grain[j, G_MASS], grain[j, G_MOMENT]
        ke += 0.5 * m * (Q[j, 2] ** 2 + Q[j, 3] ** 2) + 0.5 * I * Q[j, 4] ** 2
        pe += m * g * Q[j, 1]
        if p_touch[j]:
            speed = np.sqrt((Q[j, 0] - prev[j, 0]) ** 2 + (Q[j, 1] - prev[j, 1]) ** 2) / dt_out
            p_state[k, j] = 1 if speed < v_trap else 2
        else:
            p_state[k, j] = 0
    return ke, pe


@numba.njit(cache=True)
def springs(bs, pp, blk, P, Vm, pe, pout):
    """The springs' elastic energy added to ``pe`` and their damping power c (relative speed along the spring)^2 to
    ``pout``: block-slider springs ``bs`` (slider, anchor on the block, anchor on the slider, rest, k, c) and
    slider-slider springs ``pp`` (slider a, slider b, anchors, rest, k, c); the sliders' velocities are their means
    over the last step ``Vm``, paired with the damping force at the sample."""
    bx, by, bvx, bvy = blk[0], blk[1], blk[2], blk[3]
    for r in range(bs.shape[0]):
        i = int(bs[r, 0])
        ddx = bx + bs[r, 1] - (P[i, 0] + bs[r, 3])
        ddy = by + bs[r, 2] - (P[i, 1] + bs[r, 4])
        ln = np.sqrt(ddx * ddx + ddy * ddy)
        d = ln - bs[r, 5]
        pe += 0.5 * bs[r, 6] * d * d
        if bs[r, 7] > 0.0:
            vr = ((bvx - P[i, 2]) * ddx + (bvy - P[i, 3]) * ddy) / ln
            vm = ((bvx - Vm[i, 0]) * ddx + (bvy - Vm[i, 1]) * ddy) / ln
            pout += bs[r, 7] * vr * vm
    for r in range(pp.shape[0]):
        i = int(pp[r, 0])
        j2 = int(pp[r, 1])
        ddx = P[i, 0] + pp[r, 2] - (P[j2, 0] + pp[r, 4])
        ddy = P[i, 1] + pp[r, 3] - (P[j2, 1] + pp[r, 5])
        ln = np.sqrt(ddx * ddx + ddy * ddy)
        d = ln - pp[r, 6]
        pe += 0.5 * pp[r, 7] * d * d
        if pp[r, 8] > 0.0:
            vr = ((P[i, 2] - P[j2, 2]) * ddx + (P[i, 3] - P[j2, 3]) * ddy) / ln
            vm = ((Vm[i, 0] - Vm[j2, 0]) * ddx + (Vm[i, 1] - Vm[j2, 1]) * ddy) / ln
            pout += pp[r, 8] * vr * vm
    return pe, pout


@numba.njit(cache=True)
def drive(prm, hx, hvx, pe):
    """The drive spring's force on the body it pulls (at hx, speed hvx), its power into the scene and its elastic
    energy added to ``pe``. A velocity drive's work enters through its anchor's motion (anchor_v); the far anchor of
    a constant force is at rest and its work enters through the body's motion. (Leonardo's slider: the spring pulls
    the hanging mass, whose rope pulls the block.)"""
    dk, dx_anchor, dv = prm[DRIVE_K], prm[ANCHOR_X], prm[ANCHOR_V]
    stretch = prm[DRIVE_REST] - abs(dx_anchor - hx)  # > 0: compressed, pushes the body away from the anchor
    f_drive = dk * stretch * (1.0 if hx > dx_anchor else -1.0)
    if dv != 0.0:
        p_in = f_drive * dv
        pe += 0.5 * dk * stretch * stretch
    else:
        p_in = f_drive * hvx
    return f_drive, p_in, pe


@numba.njit(cache=True)
def momentum(M, blk, P, sl, Q, grain, D, dm):
    """Total momentum (x, y) of the block, the sliding bodies, the grains and the drive's own bodies (masses: M,
    column 0 of ``sl``, of the grain table and ``dm``); bodies absent from the buffer are asleep, at rest."""
    px, py = M * blk[2], M * blk[3]
    for i in range(sl.shape[0]):
        px += sl[i, 0] * P[i, 2]
        py += sl[i, 0] * P[i, 3]
    for j in range(grain.shape[0]):
        px += grain[j, G_MASS] * Q[j, 2]
        py += grain[j, G_MASS] * Q[j, 3]
    for j in range(dm.shape[0]):
        px += dm[j] * D[j, 1]
        py += dm[j] * D[j, 2]
    return px, py


@numba.njit(cache=True)
def reduce_sample(ids, fl, ai, af, tab, grain, bs, pp, prm, sl, fv, dm, k, out, pad_force, micro_force, n_contact,
                  p_state, p_force, sp, ms, ls, lt):
    """Row ``k`` of the recorder's buffers from the raw batch buffers (module docstring); ``grain``: the grain
    table (its places are updated), ``bs``, ``pp``: the springs (:func:`springs`), ``sl``: the sliders' law terms
    (:func:`sliders`), ``fv``: a law's own velocity part per slider at this sample (zeros for the shipped laws;
    :func:`slider_velocities`, :meth:`engine_sim.laws.Law.recorded_drag`), ``dm``: masses of the drive's bodies. One
    array per output keeps the argument list short enough for numba's dispatch, which runs every output step. Then
    the forces as means over the output step (:func:`engine_sim.means.means`; ``sp``, ``ms``, ``ls``, ``lt``: its
    springs, state and the law's impulse totals)."""
    g = prm[GRAV]
    prev = grain[:, G_X:G_Y + 1].copy()  # places at the previous sample: a grain's state is judged on its mean speed
    blk, P, D, Q = read_bodies(ids, fl, tab, grain, sl.shape[0], dm.shape[0])
    pulled = int(prm[PULLED])
    hx, hvx = (blk[0], blk[2]) if pulled < 0 else (D[pulled, 0], D[pulled, 1])  # the body the drive spring pulls
    key = arbiter_keys(ai, tab)
    ft, fn, touch, p_touch, pen, p_pen, pairs, n_stale, used = contacts(ai, af, key, grain, Q, prm[DT], k, p_force,
                                                                        sl.shape[0])
    Vm = step_mean_velocity(blk, P, sl, sp, ft, fn, fv, prm) if prm[PAIR_MID] > 0.0 else P[:, 2:4].copy()
    pout = friction_power(used, af, key, Vm, Q, blk, prm[DT])
    ke = 0.5 * prm[MASS] * (blk[2] * blk[2] + blk[3] * blk[3])
    pe = prm[MASS] * g * blk[1]  # constant unless the block is free vertically (asperity field)
    for j in range(dm.shape[0]):
        ke += 0.5 * dm[j] * D[j, 1] * D[j, 1]
    sft, sfn, f_drag, nc, ke, pe, pout = sliders(P, Vm, sl, fv, ft, fn, touch, g, k, pad_force, micro_force, ke, pe,
                                                 pout)
    ke, pe = grains(grain, Q, prev, p_touch, g, prm[V_TRAP], prm[DT_OUT], k, p_state, ke, pe)
    pe, pout = springs(bs, pp, blk, P, Vm, pe, pout)
    f_drive, p_in, pe = drive(prm, hx, hvx, pe)
    out[k, X] = blk[0] - prm[X0]
    out[k, V] = blk[2]
    out[k, F_T] = sft
    out[k, F_N] = sfn
    out[k, F_DRAG] = f_drag
    out[k, F_DRIVE] = f_drive
    out[k, PEN] = pen
    out[k, POWER_IN] = p_in
    out[k, POWER_OUT] = pout
    out[k, MECH] = ke + pe
    out[k, PAIRS] = pairs
    out[k, P_PEN] = max(p_pen, 0.0)
    out[k, STALE] = n_stale
    out[k, MOM_X], out[k, MOM_Y] = momentum(prm[MASS], blk, P, sl, Q, grain, D, dm)
    n_contact[k] = nc
    means(blk, P, D, sp, prm, sl, dm, ms, ls, lt, k, out, pad_force, micro_force)


@numba.njit(cache=True)
def stale(kinds, idx, af, a0, Q, grain):
    """True if this arbiter's contact data are not those of the bodies' present places, by more than STALE_TOL of a
    grain's radius: a fresh contact's grain point lies on the grain's circle, and its two points lie on one line
    along the normal (pymunk puts them on the surfaces, along the normal through the circle's centre). A cached
    arbiter whose contact memory was reused fails the first; one whose grain was moved since fails the second, unless
    the grain moved along that normal (straight into or off its track): both tests pass then, and the distance reads
    the move. The run loop moves grains (recycling) only before a step, so that case needs a hand-made move."""
    tol = 0.0
    for s in range(2):
        if kinds[s] == GRAIN:
            j = idx[s]
            tol = max(tol, STALE_TOL * grain[j, G_R])
            qx, qy = af[a0 + PAX + 2 * s], af[a0 + PAY + 2 * s]
            if abs(np.hypot(qx - Q[j, 0], qy - Q[j, 1]) - grain[j, G_R]) > STALE_TOL * grain[j, G_R]:
                return True
    if tol == 0.0:  # no grain: pads and tracks never sleep, their arbiters are fresh
        return False
    nx, ny = af[a0 + NX], af[a0 + NY]
    return abs((af[a0 + PBX] - af[a0 + PAX]) * ny - (af[a0 + PBY] - af[a0 + PAY]) * nx) > tol
