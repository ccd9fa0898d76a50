"""The pymunk scene: a block on spring-mounted pads sliding over random substrate tracks.

Only what changes the result is modelled: the block is a body without a shape, guided horizontally by a
groove joint; each pad is a circle (moment = inf, it cannot roll) held by a tangential spring (k0, c0) and a
pre-compressed normal spring; its velocity-strengthening friction is Coulomb friction on the patch (in the
contact solver) plus a viscous drag c v to the ground, a zero-stiffness DampedSpring to a far static anchor.
No Python runs per step: even the constant drive force is a spring (see below), since pymunk clears
body forces after every step.

pymunk damps exponentially per step, which makes the steady mobility too small by x/(e^x - 1),
x = c dt / m (DESIGN.md); the drag is set to c_set = (m/dt) ln(1 + c dt / m), for which the per-step
update v <- (v + F dt/m) e^{-x} has the steady velocity F / c exactly.
"""
from __future__ import annotations

import math

import numba
import numpy as np
import pymunk
import pymunk.batch as B

from . import units as U
from .scenario import G, Scenario
from .substrates import substrate_kind
from .wear import Wear, grain_step, pad_friction_split

__all__ = ["Scene", "corrected_drag", "describe"]

_FAR = 1e9  # mm: the drag springs' static anchors, so their axis stays horizontal over any run


def corrected_drag(c: float, m: float, dt: float) -> float:
    """Damping to give pymunk so a body of mass m feels a steady drag c at step dt (scene units)."""
    x = c * dt / m
    return (m / dt) * math.log1p(x)


def describe(sc: Scenario) -> dict:
    """What an analysis needs to know of a scenario's scene, in SI units, so it never reads the scenario's layout
    (``compare.extract`` takes it from a trace's ``metadata["scene"]``):

    effective_mass: the mass the drive accelerates (kg; Leonardo's slider adds the hanging mass, rope taut);
    friction_law: the law's parameters per pad, for its slope dF/dv at any speed (law, c [N s/m], b, v_c [m/s],
    load_per_pad [N]); friction_slope: that slope at the law's steady speed (N s/m); omega_star = N c / M (rad/s)
    and response: "viscous" if omega_star lies above the fit band's top 30 v/a (model I's C_x ~ C_f / omega^2
    there), else "inertial" (C_x = C_F / (M^2 omega^4)); length_scale: the substrate's renewal length a (m);
    pads: N, mass (kg), k0 (N/m), c0 (N s/m), foot_length (m); contact_width: the sole's width N foot_length
    (m; 0 for pads on tracks); substrate: the substrate part's own spec; grain_step: the grain step rule's substeps
    and step (:func:`engine_sim.wear.grain_step`)."""
    part = substrate_kind(sc.substrate.kind)
    fr, p = sc.friction, sc.pads
    M = sc.block.M + (sc.hanging_mass if sc.drive.kind == "leonardo" else 0.0)
    v = sc.steady_velocity
    c = sc.friction_slope(v)
    a = part(sc.substrate, sc).length_scale
    omega_star = p.N * c / M
    return {
        "effective_mass": M, "block_mass": sc.block.M, "friction_slope": c, "omega_star": omega_star,
        "friction_law": {"law": fr.law, "c": fr.c, "b": fr.b, "v_c": fr.v_c, "load_per_pad": sc.normal_load_per_pad},
        "response": "viscous" if omega_star > 30 * v / a else "inertial", "length_scale": a,
        "pads": {"N": p.N, "mass": p.mass, "k0": p.k0, "c0": p.c0, "foot_length": p.foot_length},
        "contact_width": p.N * p.foot_length if part.shared else 0.0,
        "substrate": sc.to_dict()["substrate"], "grain_step": grain_step(sc),
    }


class Scene:
    """A built pymunk space for a scenario. Use :meth:`advance` to step; all state is in scene units."""

    def __init__(self, sc: Scenario, seed: int | None = None):
        self.sc = sc
        self.seed = sc.run.seed if seed is None else int(seed)
        p, fr, sub = sc.pads, sc.friction, sc.substrate
        k_g = grain_step(sc)["substeps"]  # grains: run.dt cut so omega_g dt <= 0.6 (engine_sim.wear.grain_step)
        self.dt = sc.run.dt * U.TIME / k_g
        self.n_sub = int(round(sc.run.dt_out / sc.run.dt)) * k_g
        space = pymunk.Space()
        space.gravity = (0.0, -G * U.ACCEL)
        space.iterations = sc.run.iterations
        self.slop = 1e-4  # mm; pymunk's default 0.1 mm is larger than the physics here
        space.collision_slop = self.slop
        self.space = space

        m_p = p.mass * U.MASS
        R = p.radius * U.LENGTH
        rs = sub.segment_radius * U.LENGTH
        dy = p.track_spacing * U.LENGTH
        self.y_block = 10.0
        v0 = sc.steady_velocity * U.VELOCITY
        # scene-unit values, converted once here and read by the recorder, the particles and the renderer
        self.m_pad, self.R_pad, self.M, self.v_law = m_p, R, sc.block.M * U.MASS, v0
        self.c_drag = fr.c * U.DAMPING  # the linear law's c (the value the law asks for, before pymunk's correction)
        self.v_trap = sc.wear.trapped_speed * v0  # a grain touching its pad is trapped below this mean speed

        self.substrate = substrate_kind(sub.kind)(sub, sc)  # the substrate part: builds and draws the tracks
        self.asperities = self.substrate.shared  # one track under a sole of feet (free vertically)
        self.run_ahead = 200 * v0 * self.dt * self.n_sub  # the tracks' margin ahead beyond the part's own
        block = pymunk.Body(sc.block.M * U.MASS, float("inf"))
        block.position = (0.0, self.y_block)
        block.velocity = (v0, 0.0)
        space.add(block)
        if not self.asperities:  # guided horizontally; on asperities the block rests on its feet (free in y)
            space.add(pymunk.GrooveJoint(space.static_body, block, (-_FAR, self.y_block), (_FAR, self.y_block), (0, 0)))
        self.block = block

        load = sc.normal_load_per_pad - p.mass * G  # carried by the normal spring (N)
        k0 = p.k0 * U.STIFFNESS
        kn = p.k_normal * U.STIFFNESS
        # Spring lengths (mm). The normal spring is long so that a pad's tangential lag (f / k0, about 0.05 mm)
        # tilts it negligibly: at 5 mm the tilt lengthened it enough to drop the load by 0.13 % and added a
        # geometric tangential stiffness F_n / Ln of 1.5 % of k0; at 100 mm both are 20x smaller.
        Lt, Ln = 5.0, 100.0
        # pre-compression (mm); the pads rest one collision slop into their tracks, which the rest length absorbs.
        # On asperities the springs are relaxed: the feet that stand on bumps carry the block between them.
        pre = 0.0 if self.asperities else load / kn + self.slop
        c_set = corrected_drag(fr.c * U.DAMPING, m_p, self.dt)
        seeds = np.random.SeedSequence(self.seed).spawn(p.N + 1)  # one per track, the last for the wear particles
        wear = sc.wear
        # pymunk multiplies shape frictions: with particles the pads carry q and the tracks mu / q (see wear.py)
        q_pad, f_particle = pad_friction_split(fr.mu0, wear.mu_pad, wear.mu_track) if wear.count else (1.0, 0.0)
        mu_track = fr.mu0 / q_pad
        self.q_pad = q_pad
        foot = p.foot_length * U.LENGTH
        self.width = p.N * foot if self.asperities else 0.0  # the block's contact width w (mm)
        x_start = self.substrate.x_start(self)
        self.pads, self.tracks, self.pad_y, self.pad_x, self.tangential_springs = [], [], [], [], []
        # the springs that store energy, as built (the recorder asks for them): block-pad, then pad-pad
        self.block_pad_springs, self.pad_pad_springs = [], []
        self.track_surface, self.track_filter = [], []
        for i in range(p.N):
            pad = pymunk.Body(m_p, float("inf"))
            if self.asperities:
                xp = (i - (p.N - 1) / 2) * foot
                yp = self.substrate.top() + R + 1e-3  # the feet start just above the highest bump
                flt = pymunk.ShapeFilter(group=1)  # feet do not collide with each other
                half = foot / 2 - R - 0.05 * foot  # a small gap between neighbouring feet
                shape = pymunk.Segment(pad, (-half, 0.0), (half, 0.0), R)
            else:
                xp, yt = 0.0, -i * dy
                yp = yt + rs + R
                flt = pymunk.ShapeFilter(categories=1 << (i % 32), mask=1 << (i % 32))
                shape = pymunk.Circle(pad, R)
            pad.position = (xp, yp)
            pad.velocity = (v0, 0.0)
            shape.friction = q_pad  # arbiter friction = pad x substrate: the substrate carries mu (/ q_pad)
            shape.filter = flt
            space.add(pad, shape)
            ry = yp - self.y_block
            tangential = pymunk.DampedSpring(block, pad, (xp - Lt, ry), (0, 0), Lt, k0, p.c0 * U.DAMPING)
            self.tangential_springs.append(tangential)
            normal = pymunk.DampedSpring(block, pad, (xp, ry + Ln), (0, 0), Ln + pre, kn, p.c_normal * U.DAMPING)
            space.add(tangential, normal)
            self.block_pad_springs += [tangential, normal]
            if fr.c > 0:
                space.add(pymunk.DampedSpring(pad, space.static_body, (0, 0), (_FAR, yp), 0.0, 0.0, c_set))
            if not self.asperities:  # each pad on its own track, its own random stream
                self.tracks.append(self.substrate.build(space, yt, flt, np.random.default_rng(seeds[i]), mu_track, x_start))
            elif i == 0:  # one track shared by the sole's feet
                self.tracks.append(self.substrate.build(space, 0.0, pymunk.ShapeFilter(), np.random.default_rng(seeds[0]),
                                                        fr.mu0, x_start))
            self.pads.append(pad)
            self.pad_y.append(yp)
            self.pad_x.append(xp)
            self.track_filter.append(flt)
            self.track_surface.append(yp - R)
        if p.k1 > 0 or p.c1 > 0:
            for i in range(p.N - 1):
                a, b = self.pads[i], self.pads[i + 1]
                if self.asperities:  # side by side: a spring of rest length foot between foot centres
                    coupling = pymunk.DampedSpring(a, b, (0, 0), (0, 0), foot, p.k1 * U.STIFFNESS, p.c1 * U.DAMPING)
                else:
                    # anchor on pad i+1 at pad i's height so the coupling acts along x (tracks are offset in y)
                    off = self.pad_y[i] - self.pad_y[i + 1]
                    coupling = pymunk.DampedSpring(a, b, (0, 0), (-Lt, off), Lt, p.k1 * U.STIFFNESS, p.c1 * U.DAMPING)
                space.add(coupling)
                self.pad_pad_springs.append(coupling)

        # The drive is a spring from the block to an anchor: for a constant force a soft spring anchored
        # _FAR behind, compressed by _FAR so it pushes with F; over a metre of sliding its force changes
        # by 1 m / _FAR = 1e-6 relative (no per-step Python needed). For a constant velocity, the anchor
        # is a kinematic body moving at v with the spring stiffness k_drive.
        self.hanging = None
        if sc.drive.kind in ("force", "tilted", "leonardo"):
            F = sc.drive_force * U.FORCE
            kd = F / _FAR
            anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            anchor.position = (-_FAR, self.y_block)  # behind: the compressed spring pushes the block forward
            rest = _FAR + _FAR  # length _FAR, compression _FAR: force kd * _FAR = F
        else:
            kd = sc.drive.k_drive * U.STIFFNESS
            F_ss = p.N * sc.law_force(sc.drive.v)
            anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            anchor.position = (Lt + F_ss / kd, self.y_block)
            anchor.velocity = (v0, 0.0)
            rest = Lt
        pulled = block
        if sc.drive.kind == "leonardo":
            # Leonardo's slider: the hanging mass m_h pulls a rope over an ideal (massless, frictionless)
            # pulley, which turns the rope without changing its tension. The hanging mass's motion along the
            # rope is therefore represented unfolded, on a horizontal groove ahead of the block: its weight
            # m_h g is the far constant-force spring (its vertical weight is carried by the groove), its
            # inertia m_h is a real body, and the rope is a SlideJoint that holds at most rope_length (it can
            # go slack, as a rope does).
            L_rope = sc.drive.rope_length * U.LENGTH
            hang = pymunk.Body(sc.hanging_mass * U.MASS, float("inf"))
            hang.position = (L_rope, self.y_block)
            hang.velocity = (v0, 0.0)
            space.add(hang, pymunk.GrooveJoint(space.static_body, hang, (-_FAR, self.y_block), (_FAR, self.y_block), (0, 0)),
                      pymunk.SlideJoint(block, hang, (0, 0), (0, 0), 0.0, L_rope))
            self.hanging = hang
            pulled = hang
        self.drive_spring = pymunk.DampedSpring(pulled, anchor, (0, 0), (0, 0), rest, kd, 0.0)
        space.add(anchor, self.drive_spring)
        self.driver = anchor
        self.ahead, self.behind = self.substrate.margins(self)
        self.wear = None
        if wear.count:
            self.wear = Wear(self, wear, np.random.default_rng(seeds[-1]), f_particle)
            # idle particles at rest sleep until a pad reaches them (pads and block never rest)
            space.sleep_time_threshold = 20.0  # ms
            space.idle_speed_threshold = 2e-3  # mm/ms = 2 mm/s: a resting grain gains g dt = 1e-3 mm/ms per step before its contact stops it
        self.maintain()
        self.steps = 0
        # log law: the velocity part b N_pad ln(1 + v / v_c) per pad, applied as a force each step
        self.log_law = None
        if fr.law == "log":
            self.log_law = (fr.b * (sc.normal_load_per_pad * U.FORCE), fr.v_c * U.VELOCITY)
        self._pad_ids = np.array(sorted(pad.id for pad in self.pads), dtype=np.int64)

    # ------------------------------------------------------------------ pickling (checkpoints)
    def __getstate__(self):
        state = self.__dict__.copy()
        del state["_pad_ids"]  # pymunk ids are addresses: a restored body has a new one
        return state

    def __setstate__(self, state):
        """A restored scene: segment neighbours re-applied (pymunk does not save them) and body ids re-read."""
        self.__dict__.update(state)
        for tr in self.tracks:
            tr.restore_neighbors()
        self._pad_ids = np.array(sorted(pad.id for pad in self.pads), dtype=np.int64)

    @property
    def time(self) -> float:
        """Simulated time (s)."""
        return self.steps * self.dt / U.TIME

    def maintain(self):
        """Generate substrate ahead of each pad and drop it behind (call at least every few output steps)."""
        if self.asperities:
            self.tracks[0].maintain(self.block.position.x, self.ahead, self.behind)
            return
        if self.wear is not None:  # first: grains behind their pad leave before the track under them is dropped
            self.wear.maintain()
        for pad, tr in zip(self.pads, self.tracks):
            tr.maintain(pad.position.x, self.ahead, self.behind)

    def advance(self, n: int):
        """n pymunk steps. With the linear law no Python runs inside a step (drive and drag are springs);
        the log law reads the bodies' velocities and writes the pads' friction forces in bulk each step."""
        step, dt = self.space.step, self.dt
        if self.log_law is None:
            for _ in range(n):
                step(dt)
        else:
            bN, vc = self.log_law
            space, rd, wr = self.space, B.Buffer(), B.Buffer()
            B.get_space_bodies(space, B.BodyFields.BODY_ID, rd)
            is_pad = np.isin(np.frombuffer(rd.int_buf(), dtype=np.int64), self._pad_ids)
            f = np.zeros(2 * is_pad.size)
            for _ in range(n):
                rd.clear()
                B.get_space_bodies(space, B.BodyFields.VELOCITY, rd)
                vel = np.frombuffer(rd.float_buf())
                if vel.shape[0] != f.shape[0]:  # the kernel reads vel and writes f by body index, unchecked (numba)
                    raise RuntimeError(f"log law: {vel.shape[0] // 2} bodies in the space, {is_pad.size} expected")
                _log_forces(vel, is_pad, bN, vc, f)
                wr.clear()
                wr.set_float_buf(f.tobytes())
                B.set_space_bodies(space, B.BodyFields.FORCE, wr)
                step(dt)
        self.steps += n


@numba.njit(cache=True)
def _log_forces(vel, is_pad, bN, vc, out):
    """out[2i] = -b N_pad ln(1 + |v_x| / v_c) sign(v_x) for pads (the log law's velocity part), 0 otherwise."""
    for i in range(is_pad.shape[0]):
        out[2 * i + 1] = 0.0
        if is_pad[i]:
            vx = vel[2 * i]
            out[2 * i] = -np.sign(vx) * bN * np.log1p(abs(vx) / vc)
        else:
            out[2 * i] = 0.0
