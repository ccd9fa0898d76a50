"""Sparse random asperities under an elastic sole (model III's substrate, sections 6-7)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..substrate import BumpTrack
from .substrate import SUBSTRATES, Substrate, SubstrateSpec


@dataclass(frozen=True)
class AsperitiesSpec(SubstrateSpec):
    """Cells of length ``cell`` (m), each holding with probability ``p`` a bump (a circular cap of radius
    ``bump_radius``, much larger than its height, so caps may overlap) whose top stands r ``h_max`` above the datum
    (r uniform in [0, 1]); one track shared by all feet of the sole (see PadSpec); ``a`` is unused."""

    kind: str = "asperities"
    cell: float = 0.1e-3
    p: float = 0.1
    bump_radius: float = 0.04e-3
    h_max: float = 0.02e-3


@SUBSTRATES.register
class Asperities(Substrate):
    name = "asperities"
    Spec = AsperitiesSpec
    arrangement = "sole"
    positive = Substrate.positive | {"cell", "p", "bump_radius"}
    reduced_model = "model_III"  # a flat block on sparse asperities
    quick_duration = 16.0  # model III's corner 2 pi v / w lies near 4 rad/s: resolving below it takes 8 s segments
    non_negative = frozenset({"h_max"})

    @classmethod
    def validate(cls, s, sc, where=""):
        if s.p > 1:
            raise ValueError(f"substrate.p = {s.p!r} is a probability per cell and must be <= 1")
        if s.bump_radius < 5 * s.h_max:
            raise ValueError(f"substrate.bump_radius = {s.bump_radius!r} m must exceed 5 h_max = {5 * s.h_max:.3g} m: "
                             "a foot meeting a bump up to h_max above it must climb a flank less steep than 1/mu0")
        p = sc.pads
        if p.foot_length < 2.5 * p.radius:
            raise ValueError(f"pads.foot_length = {p.foot_length!r} m must exceed 2.5 pad radii = {2.5 * p.radius:.3g} m")

    def pad_depth(self, fraction, pad_radius):
        """The asperity tops reach h_max above the datum; a foot between them follows them down to it (m)."""
        return self.spec.h_max

    def scene_inputs(self):
        return {**super().scene_inputs(), "cell": (self.spec.cell, "length"),
                "bump_radius": (self.spec.bump_radius, "length"), "h_max": (self.spec.h_max, "length")}

    def top(self):
        return self.own.h_max

    def margins(self, scene):  # around the whole sole
        half = scene.width / 2 + 2 * self.ctx.pad_radius
        return half + scene.run_ahead, half

    def x_start(self, scene):
        return -scene.width

    def build(self, space, y, shape_filter, rng, mu, x_start):
        o = self.own
        return BumpTrack(space, y, o.cell, self.spec.p, o.bump_radius, o.h_max, mu, shape_filter, rng, x_start=x_start)

    def relief(self, pad_radius):
        return self.spec.h_max

    def side(self, track, lo, hi, xs, q_pad):
        """The bumps as pymunk has them, whole circles: their upper envelope (below the datum between bumps, where
        the scene has no floor), one friction everywhere."""
        from ..side_view import circle_envelope

        caps = [sh for sh in track.segments if abs(sh.offset.x - 0.5 * (lo + hi)) < 0.5 * (hi - lo) + sh.radius]
        c = np.array([(sh.offset.x, sh.offset.y) for sh in caps]).reshape(-1, 2)
        r = np.array([sh.radius for sh in caps])
        return circle_envelope(c, r, xs), []

    def draw(self, track, lo, hi, q_pad):
        """Each bump as its cap above the datum (the part of its circle a foot can touch, closed on the datum
        line), and the datum line itself."""
        segs, mus = [((lo, track.y), (hi, track.y))], [self.sc.friction.mu0]
        for sh in track.segments:
            c, r = sh.offset, sh.radius
            h = c.y + r - track.y  # the cap's height above the datum
            if h <= 0 or c.x + r < lo or c.x - r > hi:
                continue
            half = np.sqrt(max(2 * r * h - h * h, 0.0))
            xs = np.linspace(c.x - half, c.x + half, 17)
            segs.append(np.column_stack([xs, np.maximum(c.y + np.sqrt(np.maximum(r * r - (xs - c.x) ** 2, 0.0)), track.y)]))
            mus.append(sh.friction * q_pad)
        return segs, mus
