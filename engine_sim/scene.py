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

import numpy as np
import pymunk

from . import units as U
from .scenario import G, Scenario
from .substrate import PatchTrack, SelfAffineTrack, self_affine_kernel

__all__ = ["Scene", "corrected_drag"]

_FAR = 1e9  # mm: the drag springs' static anchors, so their axis stays horizontal over any run


def corrected_drag(c: float, m: float, dt: float) -> float:
    """Damping to give pymunk so a body of mass m feels a steady drag c at step dt (scene units)."""
    x = c * dt / m
    return (m / dt) * math.log1p(x)


class Scene:
    """A built pymunk space for a scenario. Use :meth:`advance` to step; all state is in scene units."""

    def __init__(self, sc: Scenario, seed: int | None = None):
        self.sc = sc
        self.seed = sc.run.seed if seed is None else int(seed)
        p, fr, sub = sc.pads, sc.friction, sc.substrate
        self.dt = sc.run.dt * U.TIME
        self.n_sub = int(round(sc.run.dt_out / sc.run.dt))
        space = pymunk.Space()
        space.gravity = (0.0, -G * U.ACCEL)
        space.iterations = sc.run.iterations
        space.collision_slop = 1e-4  # mm; pymunk's default 0.1 mm is larger than the physics here
        self.space = space

        m_p = p.mass * U.MASS
        R = p.radius * U.LENGTH
        rs = sub.segment_radius * U.LENGTH
        dy = p.track_spacing * U.LENGTH
        self.y_block = 10.0
        v0 = sc.steady_velocity * U.VELOCITY

        block = pymunk.Body(sc.block.M * U.MASS, float("inf"))
        block.position = (0.0, self.y_block)
        block.velocity = (v0, 0.0)
        groove = pymunk.GrooveJoint(space.static_body, block, (-_FAR, self.y_block), (_FAR, self.y_block), (0, 0))
        space.add(block, groove)
        self.block = block

        load = sc.normal_load_per_pad - p.mass * G  # carried by the normal spring (N)
        k0 = p.k0 * U.STIFFNESS
        kn = p.k_normal * U.STIFFNESS
        Lt, Ln = 5.0, 5.0  # spring lengths (mm); only their direction matters
        pre = load / kn  # pre-compression (mm)
        c_set = corrected_drag(fr.c * U.DAMPING, m_p, self.dt)
        seeds = np.random.SeedSequence(self.seed).spawn(p.N)
        if sub.kind == "self_affine":
            dx_s = sub.lambda_s * U.LENGTH / 4
            kernel = self_affine_kernel(sub.hurst, sub.lambda_r * U.LENGTH, sub.lambda_s * U.LENGTH, dx_s, sub.rms_slope)
        self.pads, self.tracks, self.pad_y = [], [], []
        for i in range(p.N):
            yt = -i * dy
            yp = yt + rs + R
            flt = pymunk.ShapeFilter(categories=1 << (i % 32), mask=1 << (i % 32))
            pad = pymunk.Body(m_p, float("inf"))
            pad.position = (0.0, yp)
            pad.velocity = (v0, 0.0)
            shape = pymunk.Circle(pad, R)
            shape.friction = 1.0  # arbiter friction = pad x patch: the patch carries mu
            shape.filter = flt
            space.add(pad, shape)
            ry = yp - self.y_block
            space.add(pymunk.DampedSpring(block, pad, (-Lt, ry), (0, 0), Lt, k0, p.c0 * U.DAMPING))
            space.add(pymunk.DampedSpring(block, pad, (0.0, ry + Ln), (0, 0), Ln + pre, kn, 0.0))
            space.add(pymunk.DampedSpring(pad, space.static_body, (0, 0), (_FAR, yp), 0.0, 0.0, c_set))
            if sub.kind == "self_affine":
                track = SelfAffineTrack(space, yt, kernel, dx_s, fr.mu0, rs, flt, np.random.default_rng(seeds[i]),
                                        x_start=-4.0 * p.radius * U.LENGTH, chunk_points=64)
            else:
                track = PatchTrack(space, yt, sub.a * U.LENGTH, fr.mu0, sub.alpha, rs, flt,
                                   np.random.default_rng(seeds[i]), x_start=-10 * sub.a * U.LENGTH)
            self.pads.append(pad)
            self.tracks.append(track)
            self.pad_y.append(yp)
        if p.k1 > 0 or p.c1 > 0:
            for i in range(p.N - 1):
                a, b = self.pads[i], self.pads[i + 1]
                # anchor on pad i+1 at pad i's height so the coupling acts along x (tracks are offset in y)
                off = self.pad_y[i] - self.pad_y[i + 1]
                space.add(pymunk.DampedSpring(a, b, (0, 0), (-Lt, off), Lt, p.k1 * U.STIFFNESS, p.c1 * U.DAMPING))

        # The drive is a spring from the block to an anchor: for a constant force a soft spring anchored
        # _FAR behind, compressed by _FAR so it pushes with F; over a metre of sliding its force changes
        # by 1 m / _FAR = 1e-6 relative (no per-step Python needed). For a constant velocity, the anchor
        # is a kinematic body moving at v with the spring stiffness k_drive.
        if sc.drive.kind in ("force", "tilted"):
            F = sc.drive_force * U.FORCE
            kd = F / _FAR
            anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            anchor.position = (-_FAR, self.y_block)  # behind: the compressed spring pushes the block forward
            rest = _FAR + _FAR  # length _FAR, compression _FAR: force kd * _FAR = F
        else:
            kd = sc.drive.k_drive * U.STIFFNESS
            F_ss = p.N * (fr.mu0 * sc.normal_load_per_pad + fr.c * sc.drive.v)
            anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            anchor.position = (Lt + F_ss / kd, self.y_block)
            anchor.velocity = (v0, 0.0)
            rest = Lt
        self.drive_spring = pymunk.DampedSpring(block, anchor, (0, 0), (0, 0), rest, kd, 0.0)
        space.add(anchor, self.drive_spring)
        self.driver = anchor
        if sub.kind == "patches":
            self.ahead = 8 * sub.a * U.LENGTH + 200 * v0 * self.dt * self.n_sub
            self.behind = 4 * sub.a * U.LENGTH
        else:  # a pad touches the profile within its radius; keep a few radii either side
            self.ahead = 4 * p.radius * U.LENGTH + 200 * v0 * self.dt * self.n_sub
            self.behind = 2 * p.radius * U.LENGTH
        self.maintain()
        self.steps = 0

    @property
    def time(self) -> float:
        """Simulated time (s)."""
        return self.steps * self.dt / U.TIME

    def maintain(self):
        """Generate substrate ahead of each pad and drop it behind (call at least every few output steps)."""
        for pad, tr in zip(self.pads, self.tracks):
            tr.maintain(pad.position.x, self.ahead, self.behind)

    def advance(self, n: int):
        """n pymunk steps; no Python runs inside a step (the drive is a spring)."""
        step, dt = self.space.step, self.dt
        for _ in range(n):
            step(dt)
        self.steps += n
