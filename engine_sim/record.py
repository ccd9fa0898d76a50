"""Recording a scene at the output rate, in bulk (pymunk.batch), and the trace it produces (SI units).

Per output sample: the block's position and velocity; per sliding body (the pads, and the micro-pads they may
carry; ``Scene.sliders``), the tangential and normal contact force
(arbiter impulse of the last step / dt) and whether it touches its track; the drive's work and the power
dissipated by the friction law (Coulomb part -f_t v and viscous part c v^2), integrated by trapezoids, and
the mechanical energy, for the energy balance W_drive (+ W_recycle) = dissipated + change of mechanical energy.
Dissipation is measured, not inferred: at every contact the friction power -F_t (v_A(p) - v_B(p))_t (tangential
force times slip at the contact point p, rotation included), plus the friction law's drag and the springs' damping. With the
log law the velocity part b N_pad ln(1 + v/v_c) enters the drag force and its power. With wear particles: per
particle and sample its state (0 idle: not touching its pad; 1 trapped: touching and slower than the trapped
threshold; 2 moving) and the tangential force it exerts on its pad.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numba
import numpy as np
import pymunk.batch as B

from . import units as U

__all__ = ["EngineTrace", "Recorder"]

_COLS = ("x", "v", "F_t", "F_n", "F_drag", "F_drive", "penetration", "power_in", "power_out", "mech", "pairs",
         "p_pen", "stale", "vib_disp", "vib_power")  # the last two written by the vibration part, not by _reduce
_AF = 9  # floats per arbiter in the batch buffer: impulse (2), normal (2), point A 1 (2), point B 1 (2), distance 1
# A grain's contact point lies on its circle (pymunk computes contacts from the positions the step ends with); one
# farther than this fraction of the radius off it belongs to a stale arbiter (see _reduce)
_STALE_TOL = 0.01


@dataclass(frozen=True)
class EngineTrace:
    """A recorded scene run (SI units). ``t`` [s], ``x`` [m] (block position from its start), ``v`` [m/s];
    ``F_t``, ``F_n`` [N]: summed tangential and normal contact force on the sliding bodies (pads and any micro-pads;
    tangential positive against the sliding direction, i.e. the Coulomb part of the friction law); ``F_drag`` [N]:
    the velocity part of the law summed over them (c v, plus b N_pad ln(1 + v/v_c) for the log law), so F_t + F_drag
    is the whole friction force; ``F_drive`` [N]: the drive's force (for Leonardo's slider the hanging weight); ``pad_force`` [N] (samples x pads), tangential (the N pads only); ``n_contact``: pads
    touching their track; ``n_pairs``: pad-substrate contact pairs (a foot may stand on several asperities); ``penetration`` [m]: the deepest overlap of any pad with its track (pymunk's
    contact distance; 0 when no contact overlaps); ``work_drive``, ``dissipated``, ``mech_energy`` [J] cumulative from the first
    sample; ``work_recycle`` [J]: energy moved into the scene by recycling wear particles (their change of potential
    energy minus the kinetic energy taken away); ``p_state`` (samples x particles, int8: 0 idle, 1 trapped,
    2 moving), ``p_force`` [N] (samples x particles): tangential force of each particle on its pad, positive
    against sliding; ``particle_penetration`` [m]: the deepest overlap of any particle with its track (contact distance);
    ``micro_force`` [N] (samples x micro-pads): tangential contact force of each sliding body beyond the pads (the
    micro-pads, pad by pad: columns i n .. (i + 1) n - 1 belong to pad i; no columns in other scenes);
    ``metadata``: scenario, seed, version, timings, particle counts."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F_t: np.ndarray
    F_n: np.ndarray
    F_drag: np.ndarray
    F_drive: np.ndarray
    pad_force: np.ndarray
    n_contact: np.ndarray
    n_pairs: np.ndarray
    penetration: np.ndarray
    work_drive: np.ndarray
    dissipated: np.ndarray
    mech_energy: np.ndarray
    work_recycle: np.ndarray
    p_state: np.ndarray
    p_force: np.ndarray
    particle_penetration: np.ndarray
    micro_force: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    metadata: dict = field(default_factory=dict)
    # [vibration] (engine_sim/vibration.py): s(t) of the shaken part [m] (0 without vibration) and the work it
    # did [J] (the inertial force on every body in the substrate's frame, or the shaker's force on the block)
    vibration: np.ndarray = field(default_factory=lambda: np.zeros(0))
    work_vibration: np.ndarray = field(default_factory=lambda: np.zeros(0))


class Recorder:
    """Samples a :class:`~engine_sim.scene.Scene` into preallocated arrays."""

    _BODY = (B.BodyFields.BODY_ID | B.BodyFields.POSITION | B.BodyFields.VELOCITY
             | B.BodyFields.ANGULAR_VELOCITY)
    _ARB = (B.ArbiterFields.BODY_A_ID | B.ArbiterFields.BODY_B_ID | B.ArbiterFields.CONTACT_COUNT
            | B.ArbiterFields.TOTAL_IMPULSE | B.ArbiterFields.NORMAL | B.ArbiterFields.POINT_A_1
            | B.ArbiterFields.POINT_B_1 | B.ArbiterFields.DISTANCE_1)

    def __init__(self, scene, n_samples: int):
        self.scene = scene
        N = len(scene.pads)
        wear = scene.wear
        n_p = wear.count if wear is not None else 0
        self.k = 0
        self.t = np.empty(n_samples)
        # scalar channels per sample, columns in _COLS order (one array: numba's dispatch cost grows with
        # the number of arguments, and this kernel runs every output step)
        self.out = np.empty((n_samples, len(_COLS)))
        self.pad_force = np.empty((n_samples, N))
        self.micro_force = np.empty((n_samples, len(scene.sliders) - N))
        self.n_contact = np.empty(n_samples, dtype=np.int32)
        self.p_state = np.zeros((n_samples, n_p), dtype=np.int8)
        self.p_force = np.zeros((n_samples, n_p))
        self.recycle = np.zeros(n_samples)
        # per particle: mass, moment, radius, asleep (set each sample), last known (x, y)
        if wear is not None:
            moment = np.where(np.isfinite(wear.moment), wear.moment, 0.0)  # locked grains: no rotational energy
            self._part = np.column_stack([wear.mass, moment, wear.r, np.zeros(n_p),
                                          np.zeros(n_p), np.zeros(n_p)]).astype(float)
            for j, b in enumerate(wear.bodies):
                self._part[j, 4:6] = b.position.x, b.position.y
        else:
            self._part = np.zeros((0, 6))
        self.x0 = None
        self._tables()

    def _tables(self):
        """What the kernel needs of the scene, asked of its parts (bodies, springs, scene-unit constants); pymunk ids
        are addresses, so this is rebuilt after unpickling."""
        scene = self.scene
        drive = scene.drive
        # body table: sorted ids -> (kind, index); kinds 0 block, 1 sliding body (pads first), 2 particle, 3 a body of
        # the drive's (Leonardo's hanging mass)
        rows = [(scene.block.id, 0, 0)] + [(b.id, 1, i) for i, b in enumerate(scene.sliders)]
        if scene.wear is not None:
            rows += [(b.id, 2, j) for j, b in enumerate(scene.wear.bodies)]
        rows += [(b.id, 3, j) for j, b in enumerate(drive.bodies)]
        rows.sort()
        self._tab = np.array(rows, dtype=np.int64).reshape(-1, 3)
        self._bbuf = B.Buffer()
        self._abuf = B.Buffer()
        # scalars for the kernel: drive k, anchor x, rest, anchor v, x0, dt, M, g, trapped-speed threshold, output
        # step, index of the pulled body among the drive's (-1: the block)
        self._prm = np.array([0.0, 0.0, 0.0, 0.0, 0.0, scene.dt, scene.M, -scene.space.gravity.y, scene.v_trap,
                              scene.dt * scene.n_sub, float(drive.pulled)])
        self._drive_spring = drive.spring
        self._drive_mass = np.array([b.mass for b in drive.bodies], dtype=float)
        # springs with energy as arrays for vectorised lengths: (slider, anchors, rest length, stiffness, damping);
        # slider-slider springs use both positions; springs without stiffness (pure dampers) store none
        index = {b: i for i, b in enumerate(scene.sliders)}
        bs = [(index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness, c.damping)
              for c in scene.block_springs if c.stiffness > 0]
        pp = [(index[c.a], index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness, c.damping)
              for c in scene.slider_springs if c.stiffness > 0]
        self._bs = np.array(bs).reshape(-1, 8)
        self._pp = np.array(pp).reshape(-1, 9)

    def __getstate__(self):
        state = self.__dict__.copy()
        for k in ("_tab", "_bbuf", "_abuf", "_prm", "_drive_spring", "_drive_mass", "_bs", "_pp"):
            del state[k]  # derived from the scene (pymunk ids change on unpickling; batch buffers do not pickle)
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._tables()

    def sample(self):
        sc, k = self.scene, self.k
        if not 0 <= k < self.t.shape[0]:  # _reduce writes row k unchecked (numba): never past the buffers
            raise IndexError(f"recorder full: sample {k} of {self.t.shape[0]}")
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
        self._prm[0:5] = (*self._drive_state(), self.x0)
        if sc.wear is not None:  # recycling moved particles since the last sample: their new places
            for j, b in enumerate(sc.wear.bodies):
                self._part[j, 3] = b.is_sleeping
            self.recycle[k] = sc.wear.recycle_work
        _reduce(ids, fl, ai, af, self._tab, self._part, self._bs, self._pp, self._prm, sc.slider_terms,
                self._drive_mass, k, self.out, self.pad_force, self.micro_force, self.n_contact, self.p_state,
                self.p_force)
        vib = getattr(sc, "vibration", None)
        self.out[k, 13:15] = (0.0, 0.0) if vib is None else vib.record(
            sc, ids, fl, self._tab, sc.slider_terms, self._part, self._drive_mass)
        self.t[k] = sc.steps * sc.dt / U.TIME
        self.k += 1

    def _drive_state(self):
        """(stiffness, anchor x, rest length, anchor speed) of the drive spring, scene units (its anchor body
        does not rotate, so the anchor point is the body's position plus the fixed offset)."""
        s = self._drive_spring
        b = s.b
        return s.stiffness, b.position.x + s.anchor_b.x, s.rest_length, b.velocity.x

    def trace(self, metadata: dict) -> EngineTrace:
        n = self.k
        t = self.t[:n]
        o = {c: self.out[:n, i] for i, c in enumerate(_COLS)}
        dt_s = np.diff(t) * U.TIME
        cum = lambda p: np.concatenate([[0.0], np.cumsum(0.5 * (p[1:n] + p[: n - 1]) * dt_s)]) / U.ENERGY
        if self.scene.wear is not None:  # grains' stale arbiters left out of the samples (see _reduce)
            metadata = {**metadata, "stale_arbiters_skipped": int(o["stale"].sum())}
        return EngineTrace(
            t=t - t[0], x=(o["x"] - o["x"][0]) / U.LENGTH, v=o["v"] / U.VELOCITY, F_t=o["F_t"].copy(),
            F_n=o["F_n"].copy(), F_drag=o["F_drag"].copy(), F_drive=o["F_drive"].copy(),
            pad_force=self.pad_force[:n], n_contact=self.n_contact[:n], n_pairs=o["pairs"].astype(np.int32),
            penetration=o["penetration"] / U.LENGTH, work_drive=cum(o["power_in"]),
            dissipated=cum(o["power_out"]), mech_energy=(o["mech"] - o["mech"][0]) / U.ENERGY,
            work_recycle=(self.recycle[:n] - self.recycle[0]) / U.ENERGY,
            p_state=self.p_state[:n], p_force=self.p_force[:n] / U.FORCE,
            particle_penetration=o["p_pen"] / U.LENGTH, micro_force=self.micro_force[:n] / U.FORCE, metadata=metadata,
            vibration=o["vib_disp"] / U.LENGTH, work_vibration=cum(o["vib_power"]),
        )


@numba.njit(cache=True)
def _reduce(ids, fl, ai, af, tab, part, bs, pp, prm, sl, dm, k, out, pad_force, micro_force, n_contact, p_state,
            p_force):
    """One sample from the raw batch buffers (scene units): bodies [px, py, vx, vy, w] by id, arbiters
    [a_id, b_id, count] x [Jx, Jy, nx, ny, pax, pay, pbx, pby, d1] with J the impulse on body A; contact forces per
    sliding body and per particle, penetrations, powers, mechanical energy. Bodies absent from the buffer are asleep (at
    rest). sl: per sliding body (mass, c, b N_pad, v_c), the law's velocity part c v + b N_pad ln(1 + |v|/v_c)
    sign(v); the first pad_force.shape[1] are the pads whose forces are recorded; dm: masses of the drive's
    bodies."""
    dk, dx_anchor, drest, dv, x0 = prm[0], prm[1], prm[2], prm[3], prm[4]
    dt, M, g, v_trap, dt_out = prm[5], prm[6], prm[7], prm[8], prm[9]
    pulled = int(prm[10])
    N = pad_force.shape[1]
    n_sl = sl.shape[0]
    n_p = part.shape[0]
    n_d = dm.shape[0]
    n_tab = tab.shape[0]
    tab_ids = tab[:, 0].copy()
    P = np.zeros((n_sl, 4))
    D = np.zeros((n_d, 2))  # the drive's bodies: x, vx
    Q = np.zeros((n_p, 5))  # particles: x, y, vx, vy, w
    for j in range(n_p):
        Q[j, 0], Q[j, 1] = part[j, 4], part[j, 5]
    prev = part[:, 4:6].copy()  # places at the previous sample: a grain's state is judged on its mean speed since
    bx = by = bvx = bvy = 0.0
    for r in range(ids.shape[0]):
        t = np.searchsorted(tab_ids, ids[r])
        if t >= n_tab or tab_ids[t] != ids[r]:
            continue
        kind, i = tab[t, 1], tab[t, 2]
        f = fl[5 * r: 5 * r + 5]
        if kind == 0:
            bx, by, bvx, bvy = f[0], f[1], f[2], f[3]
        elif kind == 1:
            for q in range(4):
                P[i, q] = f[q]
        elif kind == 2:
            for q in range(5):
                Q[i, q] = f[q]
            if part[i, 3] > 0:  # asleep: at rest
                Q[i, 2] = Q[i, 3] = Q[i, 4] = 0.0
            part[i, 4], part[i, 5] = f[0], f[1]
        else:
            D[i, 0], D[i, 1] = f[0], f[2]
    hx, hvx = (bx, bvx) if pulled < 0 else (D[pulled, 0], D[pulled, 1])  # the body the drive spring pulls
    ft = np.zeros(n_sl)
    fn = np.zeros(n_sl)
    touch = np.zeros(n_sl, dtype=np.bool_)
    p_touch = np.zeros(n_p, dtype=np.bool_)
    pen = 0.0
    p_pen = 0.0
    pairs = 0
    stale = 0
    pout = 0.0
    kinds = np.empty(2, dtype=np.int64)  # per arbiter: kind and index of bodies A and B (-1: static)
    idx = np.empty(2, dtype=np.int64)
    for r in _arbiter_order(ai, af, tab):  # sums over several contacts of one pad must not depend on the batch's order
        if ai[3 * r + 2] <= 0:
            continue
        a0 = _AF * r  # batch order: impulse (2), normal (2), point A 1 (2), point B 1 (2), distance 1
        Fx, Fy = af[a0] / dt, af[a0 + 1] / dt  # on A; B feels minus this
        tx, ty = -af[a0 + 3], af[a0 + 2]  # contact tangent
        px, py = af[a0 + 4], af[a0 + 5]
        for s in range(2):
            kinds[s], idx[s] = -1, 0
            t = np.searchsorted(tab_ids, ai[3 * r + s])
            if t < n_tab and tab_ids[t] == ai[3 * r + s]:
                kinds[s], idx[s] = tab[t, 1], tab[t, 2]
        # a sleeping grain's cached arbiter holds stale contact data (overlaps of tens of mm were read);
        # asleep, a grain only rests on its track: skip its arbiters
        if (kinds[0] == 2 and part[idx[0], 3] > 0) or (kinds[1] == 2 and part[idx[1], 3] > 0):
            continue
        # a stale arbiter: pymunk re-lists a woken grain's cached arbiters (after a restore every grain wakes) with
        # contact points from before it slept or was moved, until the next step recomputes them; its distance is then
        # measured from the grain's new place (overlaps of 15 and 85 mm were read at epoch samples). A fresh contact
        # is geometrically the bodies' present one: skip (and count) an arbiter that is not (_stale)
        if _stale(kinds, idx, af, a0, Q, part):
            stale += 1
            continue
        # friction power: tangential force x tangential slip at the contact point. The normal part is left out:
        # after a step of a few solver iterations the bodies keep a small residual normal velocity at resting
        # contacts (the position error is then fixed by pymunk's bias, which does no recorded work), and its
        # product with the normal force read as a spurious 5-6 % of the drive's work once grains slid on tracks
        # (measured); resting contacts do no work, and inelastic impacts are rare here.
        Ft = Fx * tx + Fy * ty
        for s in range(2):
            sg = 1.0 if s == 0 else -1.0
            if kinds[s] == 1:
                vx, vy = P[idx[s], 2], P[idx[s], 3]
            elif kinds[s] == 2:
                j = idx[s]
                vx = Q[j, 2] - Q[j, 4] * (py - Q[j, 1])
                vy = Q[j, 3] + Q[j, 4] * (px - Q[j, 0])
            elif kinds[s] == 0:
                vx, vy = bvx, bvy
            else:
                vx, vy = 0.0, 0.0
            pout -= sg * Ft * (vx * tx + vy * ty)
        for s in range(2):
            if kinds[s] != 1:
                continue
            sg = 1.0 if s == 0 else -1.0
            i = idx[s]
            other = kinds[1 - s]
            ft[i] += sg * Fx
            fn[i] += sg * Fy
            if other == 2:  # a particle pressing on the pad
                j = idx[1 - s]
                p_force[k, j] -= sg * Fx
                p_touch[j] = True
            elif other == -1:  # the pad on its track
                pen = max(pen, -af[a0 + 8])  # contact distance < 0: overlap depth
                touch[i] = True
                pairs += 1
        if (kinds[0] == 2 and kinds[1] == -1) or (kinds[1] == 2 and kinds[0] == -1):  # a particle on its track
            p_pen = max(p_pen, -af[a0 + 8])
    sft = 0.0
    sfn = 0.0
    fv = 0.0
    ke = 0.5 * M * (bvx * bvx + bvy * bvy)
    pe = M * g * by  # constant unless the block is free vertically (asperity field)
    for j in range(n_d):
        ke += 0.5 * dm[j] * D[j, 1] * D[j, 1]
    nc = 0
    for i in range(n_sl):
        if i < N:
            pad_force[k, i] = -ft[i]
            nc += touch[i]
        else:
            micro_force[k, i - N] = -ft[i]
        sft -= ft[i]
        sfn += fn[i]
        vx = P[i, 2]
        m_p, bN = sl[i, 0], sl[i, 2]
        f_v = sl[i, 1] * vx  # the law's velocity part on this body (drag, along its velocity)
        if bN > 0.0:
            f_v += np.sign(vx) * bN * np.log1p(abs(vx) / sl[i, 3])
        fv += f_v
        pout += f_v * vx
        ke += 0.5 * m_p * (P[i, 2] ** 2 + P[i, 3] ** 2)
        pe += m_p * g * P[i, 1]
    for j in range(n_p):
        m, I = part[j, 0], part[j, 1]
        ke += 0.5 * m * (Q[j, 2] ** 2 + Q[j, 3] ** 2) + 0.5 * I * Q[j, 4] ** 2
        pe += m * g * Q[j, 1]
        if p_touch[j]:  # trapped: its mean speed over the last output step below the threshold
            speed = np.sqrt((Q[j, 0] - prev[j, 0]) ** 2 + (Q[j, 1] - prev[j, 1]) ** 2) / dt_out
            p_state[k, j] = 1 if speed < v_trap else 2
        else:
            p_state[k, j] = 0
    for r in range(bs.shape[0]):
        i = int(bs[r, 0])
        ddx = bx + bs[r, 1] - (P[i, 0] + bs[r, 3])
        ddy = by + bs[r, 2] - (P[i, 1] + bs[r, 4])
        ln = np.sqrt(ddx * ddx + ddy * ddy)
        d = ln - bs[r, 5]
        pe += 0.5 * bs[r, 6] * d * d
        if bs[r, 7] > 0.0:  # spring damping: power c (relative speed along the spring)^2
            vr = ((bvx - P[i, 2]) * ddx + (bvy - P[i, 3]) * ddy) / ln
            pout += bs[r, 7] * vr * vr
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
            pout += pp[r, 8] * vr * vr
    # drive spring: force on the driven body dk (rest - length); its work enters through the anchor's motion
    # (velocity drive) or, for the far constant-force anchor at rest, through the body's motion.
    # (Leonardo's slider: the spring pulls the hanging mass, whose rope pulls the block)
    stretch = drest - abs(dx_anchor - hx)  # > 0: compressed, pushes the body away from the anchor
    f_drive = dk * stretch * (1.0 if hx > dx_anchor else -1.0)
    if dv != 0.0:
        p_in = f_drive * dv
        pe += 0.5 * dk * stretch * stretch
    else:
        p_in = f_drive * hvx
    # columns: see _COLS
    out[k, 0] = bx - x0
    out[k, 1] = bvx
    out[k, 2] = sft
    out[k, 3] = sfn
    out[k, 4] = fv
    out[k, 5] = f_drive
    out[k, 6] = pen
    out[k, 7] = p_in
    out[k, 8] = pout
    out[k, 9] = ke + pe
    out[k, 10] = pairs
    out[k, 11] = max(p_pen, 0.0)
    out[k, 12] = stale
    n_contact[k] = nc


@numba.njit(cache=True)
def _stale(kinds, idx, af, a0, Q, part):
    """True if this arbiter's contact data are not those of the bodies' present places, by more than _STALE_TOL of a
    grain's radius: a fresh contact's grain point lies on the grain's circle, and its two points lie on one line
    along the normal (pymunk puts them on the surfaces, along the normal through the circle's centre). A cached
    arbiter whose contact memory was reused fails the first; one whose grain was moved since fails the second, unless
    the grain moved along that normal (straight into or off its track): both tests pass then, and the distance reads
    the move. The run loop moves grains (recycling) only before a step, so that case needs a hand-made move."""
    tol = 0.0
    for s in range(2):
        if kinds[s] == 2:
            j = idx[s]
            tol = max(tol, _STALE_TOL * part[j, 2])
            qx, qy = af[a0 + 4 + 2 * s], af[a0 + 5 + 2 * s]
            if abs(np.hypot(qx - Q[j, 0], qy - Q[j, 1]) - part[j, 2]) > _STALE_TOL * part[j, 2]:
                return True
    if tol == 0.0:  # no grain: pads and tracks never sleep, their arbiters are fresh
        return False
    nx, ny = af[a0 + 2], af[a0 + 3]
    return abs((af[a0 + 6] - af[a0 + 4]) * ny - (af[a0 + 7] - af[a0 + 5]) * nx) > tol


@numba.njit(cache=True)
def _less(key, af, r, q):
    """Arbiter r before q: by the bodies' (kind, index), then contact point and impulse (all deterministic)."""
    for c in range(4):
        if key[r, c] != key[q, c]:
            return key[r, c] < key[q, c]
    for c in (4, 5, 0, 1):
        if af[_AF * r + c] != af[_AF * q + c]:
            return af[_AF * r + c] < af[_AF * q + c]
    return False


@numba.njit(cache=True)
def _arbiter_order(ai, af, tab):
    """The arbiters in a fixed order (insertion sort, tens of rows). pymunk's batch lists them in its hash set's
    order and names bodies by address, both of which vary from run to run: the last bits of per-pad and summed
    forces and of the friction power did. Bodies are keyed by their (kind, index) in the body table (-1, 0:
    static)."""
    n = ai.shape[0] // 3
    tab_ids = tab[:, 0]
    key = np.empty((n, 4), dtype=np.int64)
    for r in range(n):
        for s in range(2):
            key[r, 2 * s], key[r, 2 * s + 1] = -1, 0
            t = np.searchsorted(tab_ids, ai[3 * r + s])
            if t < tab.shape[0] and tab_ids[t] == ai[3 * r + s]:
                key[r, 2 * s], key[r, 2 * s + 1] = tab[t, 1], tab[t, 2]
    order = np.arange(n)
    for i in range(1, n):
        r = order[i]
        j = i - 1
        while j >= 0 and _less(key, af, r, order[j]):
            order[j + 1] = order[j]
            j -= 1
        order[j + 1] = r
    return order
