"""Substrate tracks, generated ahead of the pads and dropped behind them (memory independent of length).

Each pad runs on its own track (its own random stream), as the contact lines of a 2D interface do; the
tracks are offset in y so each pad's broad phase only meets its own segments. Works in scene units.
"""
from __future__ import annotations

from collections import deque

import numpy as np
import pymunk

__all__ = ["PatchTrack"]

_CHUNK = 32  # patches generated at a time


class PatchTrack:
    """A flat track of friction patches (model I's renewal, section 3).

    Patch boundaries lie at (j + r_j) a, so the distance between renewals is a (1 + r - r'), exactly the
    interval law behind eq. (A8); each patch has mu = mu0 (1 + alpha (r - 1/2)), so the force on a pad
    sliding under load N_pad changes to mu0 N_pad + alpha mu0 N_pad (r - 1/2) (eq. 5).

    Parameters are in scene units (mm). ``rng`` is this track's own generator.
    """

    def __init__(self, space: pymunk.Space, y: float, a: float, mu0: float, alpha: float, radius: float,
                 shape_filter: pymunk.ShapeFilter, rng: np.random.Generator, x_start: float):
        self.space, self.y, self.a, self.mu0, self.alpha, self.radius = space, y, a, mu0, alpha, radius
        self.filter = shape_filter
        self.rng = rng
        self.segments: deque = deque()
        self._j = int(np.floor(x_start / a)) - 2
        self._x_end = (self._j + rng.random()) * a
        self.generated = 0
        self.removed = 0

    def _extend(self):
        j = self._j + 1 + np.arange(_CHUNK)
        bounds = (j + self.rng.random(_CHUNK)) * self.a
        mus = self.mu0 * (1.0 + self.alpha * (self.rng.random(_CHUNK) - 0.5))
        new = []
        x0 = self._x_end
        for x1, mu in zip(bounds, mus):
            s = pymunk.Segment(self.space.static_body, (x0, self.y), (x1, self.y), self.radius)
            s.friction = float(mu)
            s.filter = self.filter
            new.append(s)
            x0 = x1
        prev = self.segments[-1] if self.segments else None
        for i, s in enumerate(new):
            a_prev = (prev.a if prev is not None else s.a - (s.b - s.a))
            b_next = new[i + 1].b if i + 1 < len(new) else s.b + (s.b - s.a)
            s.set_neighbors(a_prev, b_next)
            prev = s
        self.space.add(*new)
        self.segments.extend(new)
        self._j = int(j[-1])
        self._x_end = float(bounds[-1])
        self.generated += len(new)

    def maintain(self, x: float, ahead: float, behind: float):
        """Keep segments covering [x - behind, x + ahead]; add ahead, remove behind."""
        while self._x_end < x + ahead:
            self._extend()
        old = []
        while self.segments and self.segments[0].b.x < x - behind:
            old.append(self.segments.popleft())
        if old:
            self.space.remove(*old)
            self.removed += len(old)

    def friction_at(self, x: float) -> float:
        """mu of the patch under x (scene units), or nan outside the generated range."""
        for s in self.segments:
            if s.a.x <= x < s.b.x:
                return s.friction
        return float("nan")
