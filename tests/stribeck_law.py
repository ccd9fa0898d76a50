"""A Stribeck friction law, added as a user's plugin: this module alone, named in a scenario's ``plugins``.

    f(v) = N_pad (mu0 + dmu exp(-(v / v_s)^2)) + c v,    v >= 0 (odd in v),

friction that falls from mu0 + dmu at rest towards mu0 (the weakening branch), then rises with the viscous part c v
(the strengthening branch): dF/dv = c - 2 N_pad dmu (v / v_s^2) exp(-(v / v_s)^2). A steadily sliding pad needs
dF/dv > 0 at its operating point: a point on the weakening branch is refused at load (one line naming the fields).

The Coulomb part mu0 N_pad is pymunk's contact solver's, c v the linear law's corrected damper, and the Stribeck
bump g_s(v) = N_pad dmu exp(-(v / v_s)^2) sign(v) a force written once per step from the sliding bodies'
velocities (as the log law's velocity part), explicit: stable for max|g_s'| dt / m_pad = sqrt(2 / e) N_pad dmu dt /
(v_s m_pad) < 0.5 (checked at load). The recorder reads c v as the linear law's (``drag_terms``), the bump at each
sample from :func:`stribeck_drag` (``recorded_drag``) and its impulses per step from ``impulse_totals``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
import pymunk.batch as B

from engine_sim.laws import LAWS, FrictionSpec
from engine_sim.laws.linear import Linear

EXPLICIT = 0.5  # largest max|g_s'| dt / m_pad of the explicit per-step force


@dataclass(frozen=True)
class StribeckSpec(FrictionSpec):
    """dmu: the static excess mu_s - mu0 (>= 0); v_s (m/s): the Stribeck speed; c (N s/m): the viscous slope."""

    law: str = "stribeck"
    c: float = 3.0
    dmu: float = 0.5
    v_s: float = 2.5e-3


@numba.njit(cache=True)
def stribeck_drag(v, rows, out):
    """The bump N_pad dmu exp(-(v / v_s)^2) sign(v) per sliding body (``rows``: N_pad dmu, v_s; scene units): the
    kernel of :meth:`Stribeck.recorded_drag`."""
    for i in range(v.shape[0]):
        u = v[i] / rows[i, 1]
        out[i] = np.sign(v[i]) * rows[i, 0] * np.exp(-u * u)


@numba.njit(cache=True)
def _bump_forces(vel, ndmu, vs, out, acc):
    """out[2i] = -N_pad dmu exp(-(v_x / v_s)^2) sign(v_x) on sliding bodies (ndmu > 0), 0 otherwise; added to
    acc[i]."""
    for i in range(ndmu.shape[0]):
        out[2 * i + 1] = 0.0
        if ndmu[i] > 0.0:
            u = vel[2 * i] / vs
            out[2 * i] = -np.sign(vel[2 * i]) * ndmu[i] * np.exp(-u * u)
            acc[i] += out[2 * i]
        else:
            out[2 * i] = 0.0


@LAWS.register
class Stribeck(Linear):
    """The Stribeck law (module docstring)."""

    name = "stribeck"
    scene_units = {"v_s": "velocity"}  # the scene's builder hands v_s in scene units as self.own.v_s
    Spec = StribeckSpec
    per_step_impulses = True
    positive = frozenset({"v_s"})
    non_negative = frozenset({"mu0", "c", "dmu"})

    @classmethod
    def validate(cls, s, sc):
        super().validate(s, sc)  # c > 0
        v = sc.steady_velocity
        load = sc.normal_load_per_pad
        slope = s.c - 2 * load * s.dmu * v / s.v_s ** 2 * math.exp(-(v / s.v_s) ** 2)
        if not slope > 0:
            raise ValueError(f"friction: the operating point v = {v:.3g} m/s lies on the Stribeck law's weakening "
                             f"branch (dF/dv = {slope:.3g} N s/m < 0 with friction.c = {s.c:.3g}, friction.dmu = "
                             f"{s.dmu:.3g}, friction.v_s = {s.v_s:.3g} m/s); drive faster or raise friction.c")
        for load, m in sc.arrangement_part.sliders(sc):
            x = math.sqrt(2 / math.e) * load * s.dmu * sc.run.dt / (s.v_s * m)
            if x > EXPLICIT:
                raise ValueError(f"friction.v_s = {s.v_s:.3g} m/s is below the explicit-update limit "
                                 f"(sqrt(2/e) N_pad dmu dt / (v_s m_pad) = {x:.3g} must be < {EXPLICIT})")

    def force(self, v, load, c):
        s = self.spec
        return s.mu0 * load + c * v + load * s.dmu * math.exp(-(v / s.v_s) ** 2)

    def slope(self, v, load, c):
        s = self.spec
        return c - 2 * load * s.dmu * v / s.v_s ** 2 * math.exp(-(v / s.v_s) ** 2)

    def describe(self, load, c):
        s = self.spec
        return {"law": self.name, "c": c, "b": 0.0, "v_c": None, "load_per_pad": load, "dmu": s.dmu, "v_s": s.v_s}

    @classmethod
    def described_slope(cls, law, v):
        u = v / law["v_s"]
        return law["c"] - 2 * law["load_per_pad"] * law["dmu"] * u / law["v_s"] * math.exp(-u * u)

    def recorded_drag(self, scene):
        rows = [(self.spec.dmu * load, self.own.v_s) for load in scene.slider_load]
        return stribeck_drag, np.array(rows, dtype=float).reshape(-1, 2)

    def _per_body(self, scene):
        """N_pad dmu of each body of the space in the batch's order (0 for bodies that are not sliders) and its
        index among the sliders (-1 for the others)."""
        rd = B.Buffer()
        B.get_space_bodies(scene.space, B.BodyFields.BODY_ID, rd)
        ids = np.frombuffer(rd.int_buf(), dtype=np.int64)
        ndmu = {b.id: self.spec.dmu * load for b, load in zip(scene.sliders, scene.slider_load)}
        where = {b.id: k for k, b in enumerate(scene.sliders)}
        return (np.array([ndmu.get(int(i), 0.0) for i in ids]),
                np.array([where.get(int(i), -1) for i in ids], dtype=np.int64))

    def advance(self, scene, n):
        ndmu, idx = self._per_body(scene)
        vs = self.own.v_s
        step, dt, space, rd, wr = scene.space.step, scene.dt, scene.space, B.Buffer(), B.Buffer()
        f = np.zeros(2 * ndmu.size)
        acc = np.zeros(ndmu.size)
        for _ in range(n):
            rd.clear()
            B.get_space_bodies(space, B.BodyFields.VELOCITY, rd)
            _bump_forces(np.frombuffer(rd.float_buf()), ndmu, vs, f, acc)
            wr.clear()
            wr.set_float_buf(f.tobytes())
            B.set_space_bodies(space, B.BodyFields.FORCE, wr)
            step(dt)
        self._add_impulses(scene, idx, acc * dt)
