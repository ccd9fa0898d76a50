"""Recording a scene at the output rate, in bulk (pymunk.batch), and the trace it produces (SI units).

Per output sample: the block's position and velocity; per pad, the tangential and normal contact force
(arbiter impulse of the last step / dt) and whether it touches its track; the drive's work and the power
dissipated by the friction law (Coulomb part -f_t v and viscous part c v^2), integrated by trapezoids, and
the mechanical energy, for the energy balance W_drive = dissipated + change of mechanical energy.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numba
import numpy as np
import pymunk.batch as B

from . import units as U

__all__ = ["EngineTrace", "Recorder"]

_COLS = ("x", "v", "F_t", "F_n", "F_drag", "F_drive", "penetration", "power_in", "power_out", "mech")


@dataclass(frozen=True)
class EngineTrace:
    """A recorded scene run (SI units). ``t`` [s], ``x`` [m] (block position from its start), ``v`` [m/s];
    ``F_t``, ``F_n`` [N]: summed tangential and normal contact force on the pads (tangential positive
    against the sliding direction, i.e. the Coulomb part of the friction law); ``F_drag`` [N]: the viscous
    part c sum v_pad, so F_t + F_drag is the whole friction force; ``F_drive`` [N]: the drive's force on the block; ``pad_force`` [N] (samples x pads), tangential; ``n_contact``: pads
    touching their track; ``penetration`` [m]: the deepest overlap of any pad with its track (pymunk's
    contact distance; 0 when no contact overlaps); ``work_drive``, ``dissipated``, ``mech_energy`` [J] cumulative from the first
    sample; ``metadata``: scenario, seed, version, timings."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F_t: np.ndarray
    F_n: np.ndarray
    F_drag: np.ndarray
    F_drive: np.ndarray
    pad_force: np.ndarray
    n_contact: np.ndarray
    penetration: np.ndarray
    work_drive: np.ndarray
    dissipated: np.ndarray
    mech_energy: np.ndarray
    metadata: dict = field(default_factory=dict)


class Recorder:
    """Samples a :class:`~engine_sim.scene.Scene` into preallocated arrays."""

    _BODY = B.BodyFields.BODY_ID | B.BodyFields.POSITION | B.BodyFields.VELOCITY
    _ARB = (B.ArbiterFields.BODY_A_ID | B.ArbiterFields.BODY_B_ID | B.ArbiterFields.CONTACT_COUNT
            | B.ArbiterFields.TOTAL_IMPULSE | B.ArbiterFields.DISTANCE_1)

    def __init__(self, scene, n_samples: int):
        self.scene = scene
        N = len(scene.pads)
        self.k = 0
        self.t = np.empty(n_samples)
        # scalar channels per sample, columns in _COLS order (one array: numba's dispatch cost grows with
        # the number of arguments, and this kernel runs every output step)
        self.out = np.empty((n_samples, len(_COLS)))
        self.pad_force = np.empty((n_samples, N))
        self.n_contact = np.empty(n_samples, dtype=np.int32)
        ids = np.array([pad.id for pad in scene.pads], dtype=np.int64)
        self._order = np.argsort(ids)
        self._sorted_ids = ids[self._order]
        self.block_id = scene.block.id
        self._bbuf = B.Buffer()
        self._abuf = B.Buffer()
        sc = scene.sc
        self.m_p = sc.pads.mass * U.MASS
        self.M = sc.block.M * U.MASS
        self.c = sc.friction.c * U.DAMPING
        self.x0 = None
        # scalars for the kernel: drive k, anchor x, rest, anchor v, x0, dt, c, m_p, M, g
        self._prm = np.array([0.0, 0.0, 0.0, 0.0, 0.0, scene.dt, self.c, self.m_p, self.M, -scene.space.gravity.y])
        # Springs with energy, as (body a is block?, anchors, rest length, stiffness) arrays for vectorised
        # lengths; drag springs (stiffness 0) store none. Pad-pad springs use both pad positions.
        bs, pp = [], []
        index = {pad: i for i, pad in enumerate(scene.pads)}
        for c in scene.space.constraints:
            if not hasattr(c, "stiffness") or c.stiffness <= 0:
                continue
            if c.a is scene.block and c.b in index:
                bs.append((index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness))
            elif c.a in index and c.b in index:
                pp.append((index[c.a], index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness))
            elif c.a is scene.block and c is scene.drive_spring:
                self._drive_spring = c
        self._bs = np.array(bs).reshape(-1, 7)
        self._pp = np.array(pp).reshape(-1, 8)

    def sample(self):
        sc, k = self.scene, self.k
        self._bbuf.clear()
        B.get_space_bodies(sc.space, self._BODY, self._bbuf)
        self._abuf.clear()
        B.get_space_arbiters(sc.space, self._ARB, self._abuf)
        ids = np.frombuffer(self._bbuf.int_buf(), dtype=np.int64)
        fl = np.frombuffer(self._bbuf.float_buf())
        ai = np.frombuffer(self._abuf.int_buf(), dtype=np.int64)
        af = np.frombuffer(self._abuf.float_buf())
        if self.x0 is None:
            self.x0 = float(sc.block.position.x)
        drive_k, drive_x, drive_rest, drive_v = self._drive_state()
        prm = self._prm
        prm[0], prm[1], prm[2], prm[3], prm[4] = drive_k, drive_x, drive_rest, drive_v, self.x0
        _reduce(ids, fl, ai, af, self._sorted_ids, self._order, self.block_id, self._bs, self._pp, prm, k,
                self.out, self.pad_force, self.n_contact)
        self.t[k] = sc.steps * sc.dt / U.TIME
        self.k += 1

    def _drive_state(self):
        """(stiffness, anchor x, rest length, anchor speed) of the drive spring, scene units."""
        s = self._drive_spring
        anchor = s.b.local_to_world(s.anchor_b).x
        return s.stiffness, anchor, s.rest_length, s.b.velocity.x

    def trace(self, metadata: dict) -> EngineTrace:
        n = self.k
        t = self.t[:n]
        o = {c: self.out[:n, i] for i, c in enumerate(_COLS)}
        dt_s = np.diff(t) * U.TIME
        cum = lambda p: np.concatenate([[0.0], np.cumsum(0.5 * (p[1:n] + p[: n - 1]) * dt_s)]) / U.ENERGY
        return EngineTrace(
            t=t - t[0], x=(o["x"] - o["x"][0]) / U.LENGTH, v=o["v"] / U.VELOCITY, F_t=o["F_t"].copy(),
            F_n=o["F_n"].copy(), F_drag=o["F_drag"].copy(), F_drive=o["F_drive"].copy(),
            pad_force=self.pad_force[:n], n_contact=self.n_contact[:n],
            penetration=o["penetration"] / U.LENGTH, work_drive=cum(o["power_in"]),
            dissipated=cum(o["power_out"]), mech_energy=(o["mech"] - o["mech"][0]) / U.ENERGY,
            metadata=metadata,
        )


@numba.njit(cache=True)
def _reduce(ids, fl, ai, af, sorted_ids, order, block_id, bs, pp, prm, k, out, pad_force, n_contact):
    """One sample from the raw batch buffers (scene units): bodies [px, py, vx, vy] by id, arbiters
    [a_id, b_id, count] x [Jx, Jy, d1]; contact forces per pad, penetration, powers, mechanical energy."""
    dk, dx_anchor, drest, dv, x0 = prm[0], prm[1], prm[2], prm[3], prm[4]
    dt, c, m_p, M, g = prm[5], prm[6], prm[7], prm[8], prm[9]
    N = sorted_ids.shape[0]
    P = np.zeros((N, 4))
    bx = by = bvx = bvy = 0.0
    for r in range(ids.shape[0]):
        bid = ids[r]
        if bid == block_id:
            bx, by, bvx, bvy = fl[4 * r], fl[4 * r + 1], fl[4 * r + 2], fl[4 * r + 3]
            continue
        j = np.searchsorted(sorted_ids, bid)
        if j < N and sorted_ids[j] == bid:
            i = order[j]
            for q in range(4):
                P[i, q] = fl[4 * r + q]
    ft = np.zeros(N)
    fn = np.zeros(N)
    touch = np.zeros(N, dtype=np.bool_)
    pen = 0.0
    for r in range(ai.shape[0] // 3):
        if ai[3 * r + 2] <= 0:
            continue
        sign = 1.0
        j = np.searchsorted(sorted_ids, ai[3 * r])
        if not (j < N and sorted_ids[j] == ai[3 * r]):
            j = np.searchsorted(sorted_ids, ai[3 * r + 1])
            sign = -1.0
            if not (j < N and sorted_ids[j] == ai[3 * r + 1]):
                continue
        i = order[j]
        ft[i] += sign * af[3 * r] / dt
        fn[i] += sign * af[3 * r + 1] / dt
        pen = max(pen, -af[3 * r + 2])  # contact distance < 0: overlap depth
        touch[i] = True
    sft = 0.0
    sfn = 0.0
    sv = 0.0
    pout = 0.0
    ke = 0.5 * M * (bvx * bvx + bvy * bvy)
    pe = 0.0
    nc = 0
    for i in range(N):
        pad_force[k, i] = -ft[i]
        sft -= ft[i]
        sfn += fn[i]
        sv += P[i, 2]
        pout += -ft[i] * P[i, 2] + c * P[i, 2] * P[i, 2]
        ke += 0.5 * m_p * (P[i, 2] ** 2 + P[i, 3] ** 2)
        pe += m_p * g * P[i, 1]
        nc += touch[i]
    for r in range(bs.shape[0]):
        i = int(bs[r, 0])
        ddx = bx + bs[r, 1] - (P[i, 0] + bs[r, 3])
        ddy = by + bs[r, 2] - (P[i, 1] + bs[r, 4])
        d = np.sqrt(ddx * ddx + ddy * ddy) - bs[r, 5]
        pe += 0.5 * bs[r, 6] * d * d
    for r in range(pp.shape[0]):
        i = int(pp[r, 0])
        j2 = int(pp[r, 1])
        ddx = P[i, 0] + pp[r, 2] - (P[j2, 0] + pp[r, 4])
        ddy = P[i, 1] + pp[r, 3] - (P[j2, 1] + pp[r, 5])
        d = np.sqrt(ddx * ddx + ddy * ddy) - pp[r, 6]
        pe += 0.5 * pp[r, 7] * d * d
    # drive spring: force on the block dk (rest - length); its work enters through the anchor's motion
    # (velocity drive) or, for the far constant-force anchor at rest, through the block's motion.
    stretch = drest - abs(dx_anchor - bx)  # > 0: compressed, pushes the block away from the anchor
    f_drive = dk * stretch * (1.0 if bx > dx_anchor else -1.0)
    if dv != 0.0:
        p_in = f_drive * dv
        pe += 0.5 * dk * stretch * stretch
    else:
        p_in = f_drive * bvx
    # columns: see _COLS
    out[k, 0] = bx - x0
    out[k, 1] = bvx
    out[k, 2] = sft
    out[k, 3] = sfn
    out[k, 4] = c * sv
    out[k, 5] = f_drive
    out[k, 6] = pen
    out[k, 7] = p_in
    out[k, 8] = pout
    out[k, 9] = ke + pe
    n_contact[k] = nc
