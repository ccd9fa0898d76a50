"""The logarithmic rate-strengthening law of rubber and polymers, f = N_pad (mu + b ln(1 + v / v_c)) + c v."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
import pymunk.batch as B

from .law import LAWS, FrictionSpec
from .linear import Linear


def log_slope(law: dict, v: float) -> float:
    """dF/dv (N s/m) of the log law's describe() at speed v (m/s): c + b N_pad / (v_c + v) (c alone if b = 0)."""
    extra = law["b"] * law["load_per_pad"] / (law["v_c"] + v) if law["b"] else 0.0
    return law["c"] + extra


@dataclass(frozen=True)
class LogSpec(FrictionSpec):
    """mu rises by ``b`` per e-fold of speed above ``v_c`` (m/s); ``c`` (N s/m) optional (>= 0)."""

    law: str = "log"
    c: float = 0.0
    b: float = 0.05
    v_c: float = 1e-3


@LAWS.register
class Log(Linear):
    """The velocity part b N_pad ln(1 + v/v_c) is a force written once per step from the sliding bodies'
    velocities (pymunk.batch, about 11 us per step); explicit, so stable only for b N_pad dt / (v_c m) < 0.5
    (checked at load). The c v part is the linear law's corrected damper."""

    name = "log"
    scene_units = {"v_c": "velocity"}
    Spec = LogSpec
    per_step_impulses = True
    positive = frozenset({"v_c"})
    non_negative = frozenset({"mu0", "c", "b"})

    @classmethod
    def validate(cls, s, sc):
        if not (s.b > 0 or s.c > 0):
            raise ValueError("friction.b must be > 0 for the log law (or friction.c > 0)")
        for load, m in sc.arrangement_part.sliders(sc):
            x = s.b * load * sc.run.dt / (s.v_c * m)
            if x > 0.5:
                v_min = s.b * load * sc.run.dt / (0.5 * m)
                raise ValueError(f"friction.v_c = {s.v_c:.3g} m/s is below the explicit-update limit {v_min:.3g} m/s "
                                 f"(b N_pad dt / (v_c m_pad) = {x:.3g} must be < 0.5, or the pads chatter)")

    def force(self, v, load, c):
        s = self.spec
        f = s.mu0 * load + c * v
        f += s.b * load * math.log1p(v / s.v_c)
        return f

    def slope(self, v, load, c):
        s = self.spec
        return c + s.b * load / (s.v_c + v)

    def drag_terms(self, load, c):
        return c, self.spec.b * load, self.spec.v_c

    def describe(self, load, c):
        return {"law": self.name, "c": c, "b": self.spec.b, "v_c": self.spec.v_c, "load_per_pad": load}

    @classmethod
    def described_slope(cls, law, v):
        return log_slope(law, v)

    def _per_body(self, scene):
        """Per body of the space (in the batch's order, read once): b N_pad of the sliding body (scene units), 0
        for the others, and its index among the sliders (-1 for the others)."""
        rd = B.Buffer()
        B.get_space_bodies(scene.space, B.BodyFields.BODY_ID, rd)
        ids = np.frombuffer(rd.int_buf(), dtype=np.int64)
        bN = {b.id: self.spec.b * load for b, load in zip(scene.sliders, scene.slider_load)}
        where = {b.id: k for k, b in enumerate(scene.sliders)}
        self._bN = np.array([bN.get(int(i), 0.0) for i in ids])
        self._idx = np.array([where.get(int(i), -1) for i in ids], dtype=np.int64)

    def advance(self, scene, n):
        self._per_body(scene)  # in the batch's body order, read once per call (ids are addresses; order may change)
        vc = self.own.v_c
        step, dt, space, rd, wr = scene.space.step, scene.dt, scene.space, B.Buffer(), B.Buffer()
        bN = self._bN
        f = np.zeros(2 * bN.size)
        acc = np.zeros(bN.size)  # the forces' sum over the steps, per body: the recorder's mean drag
        for _ in range(n):
            rd.clear()
            B.get_space_bodies(space, B.BodyFields.VELOCITY, rd)
            vel = np.frombuffer(rd.float_buf())
            if vel.shape[0] != f.shape[0]:  # the kernel reads vel and writes f by body index, unchecked (numba)
                raise RuntimeError(f"log law: {vel.shape[0] // 2} bodies in the space, {bN.size} expected")
            _log_forces(vel, bN, vc, f, acc)
            wr.clear()
            wr.set_float_buf(f.tobytes())
            B.set_space_bodies(space, B.BodyFields.FORCE, wr)
            step(dt)
        self._add_impulses(scene, self._idx, acc * dt)

    def __getstate__(self):
        state = self.__dict__.copy()
        state.pop("_bN", None)
        state.pop("_idx", None)  # by body order of the live space: re-read on every advance
        return state


@numba.njit(cache=True)
def _log_forces(vel, bN, vc, out, acc):
    """out[2i] = -b N_pad ln(1 + |v_x| / v_c) sign(v_x) for sliding bodies (bN > 0), 0 otherwise; added to acc[i]."""
    for i in range(bN.shape[0]):
        out[2 * i + 1] = 0.0
        if bN[i] > 0.0:
            vx = vel[2 * i]
            out[2 * i] = -np.sign(vx) * bN[i] * np.log1p(abs(vx) / vc)
            acc[i] += out[2 * i]
        else:
            out[2 * i] = 0.0
