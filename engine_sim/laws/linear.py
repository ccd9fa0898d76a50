"""The linear velocity-strengthening law f = mu N_pad + c v (model I's f_kin + m eta1 v, eq. (A1))."""
from __future__ import annotations

import math

import pymunk

from .law import LAWS, FrictionSpec, Law

_FAR = 1e9  # mm: the drag springs' static anchors, so their axis stays horizontal over any run


def corrected_drag(c: float, m: float, dt: float) -> float:
    """Damping to give pymunk so a body of mass m feels a steady drag c at step dt (scene units).

    pymunk damps exponentially per step, which makes the steady mobility too small by x/(e^x - 1), x = c dt / m
    (DESIGN.md); c_set = (m/dt) ln(1 + c dt / m) makes the per-step update v <- (v + F dt/m) e^{-x} reach the steady
    velocity F / c exactly."""
    x = c * dt / m
    return (m / dt) * math.log1p(x)


@LAWS.register
class Linear(Law):
    """f = mu N_pad + c v, c > 0: Coulomb friction in pymunk's contact solver plus a zero-stiffness damped spring
    from each sliding body to a far static anchor (no Python inside a step)."""

    name = "linear"
    Spec = FrictionSpec

    @classmethod
    def validate(cls, s, sc):
        if not s.c > 0:
            raise ValueError(f"friction.c must be > 0 for the linear law (got {s.c!r}): without velocity "
                             "strengthening the block has no steady sliding speed")

    def force(self, v, load, c):
        return self.spec.mu0 * load + c * v

    def slope(self, v, load, c):
        return c

    def build(self, scene, body, c):
        if c > 0:
            c_set = corrected_drag(c, body.mass, scene.dt)
            scene.space.add(pymunk.DampedSpring(body, scene.space.static_body, (0, 0), (_FAR, body.position.y),
                                                0.0, 0.0, c_set))
