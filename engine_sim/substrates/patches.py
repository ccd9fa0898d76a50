"""Friction patches on flat tracks (model I's substrate, section 3), optionally with cavities for wear particles."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..substrate import PatchTrack
from .substrate import SUBSTRATES, Substrate, SubstrateSpec


@dataclass(frozen=True)
class PatchesSpec(SubstrateSpec):
    """A flat track of friction patches: boundaries at (j + r_j) a (renewal intervals a (1 + r - r'), model I's
    tau0 (1 + r - r')), each patch with mu = mu0 (1 + alpha (r - 1/2)). Cavities where wear particles get trapped:
    with probability ``pit_p`` per patch, a flat-bottomed pit of depth ``pit_depth`` (m), width uniform in
    [pit_width_min, pit_width_max] (m, between the walls' centre lines: the opening is narrower by 2
    segment_radius)."""

    kind: str = "patches"
    alpha: float = 1.0
    pit_p: float = 0.0
    pit_width_min: float = 0.15e-3
    pit_width_max: float = 0.35e-3
    pit_depth: float = 0.06e-3


@SUBSTRATES.register
class Patches(Substrate):
    name = "patches"
    Spec = PatchesSpec
    hosts_wear = True
    non_negative = frozenset({"alpha", "pit_p", "pit_depth"})

    @classmethod
    def validate(cls, s, sc, where=""):
        if s.pit_p > 0 and (s.pit_p > 1 or not 0 < s.pit_width_min <= s.pit_width_max or s.pit_width_max > 0.45 * s.a):
            raise ValueError(f"substrate pits: pit_p must lie in [0, 1] and 0 < pit_width_min <= pit_width_max <= 0.45 a "
                             f"(got {s.pit_p!r}, {s.pit_width_min!r}, {s.pit_width_max!r} m)")
        if s.alpha >= 2:
            raise ValueError(f"substrate.alpha = {s.alpha!r} must be < 2 (patch friction stays positive)")

    def pad_depth(self, fraction, pad_radius):
        """The dip of a pad into the widest pit: it rests on the pit's rims (a disc of the pad's plus the walls'
        radius across the opening) or, in a pit wider than that disc, on its floor (m)."""
        s = self.spec
        if s.pit_p <= 0:
            return 0.0
        r, half = pad_radius + s.segment_radius, s.pit_width_max / 2
        dip = r - math.sqrt(r * r - half * half) if half < r else s.pit_depth
        return min(dip, s.pit_depth)

    def relief(self, pad_radius):
        """Pits (their depth) or a flat track; grains need no exaggeration of their own."""
        return self.spec.pit_depth if self.spec.pit_p > 0 else 0.0

    def scene_inputs(self):
        s = self.spec
        return {**super().scene_inputs(), "floor": (s.pit_depth if s.pit_p > 0 else 0.0, "length"),
                "ahead": (max(8 * s.a, self.sc.wear.ahead + 2 * s.a), "length"), "behind": (4 * s.a, "length"),
                "x_start": (-10 * s.a, "length"), "pit_width_min": (s.pit_width_min, "length"),
                "pit_width_max": (s.pit_width_max, "length"), "pit_depth": (s.pit_depth, "length")}

    def floor_depth(self):
        return self.own.floor

    def mu_range(self, mu0):
        return mu0 * (1 - self.spec.alpha / 2), mu0 * (1 + self.spec.alpha / 2)

    def margins(self, scene):
        return self.own.ahead + scene.run_ahead, self.own.behind

    def x_start(self, scene):
        return self.own.x_start

    def build(self, space, y, shape_filter, rng, mu, x_start):
        s, o = self.spec, self.own
        return PatchTrack(space, y, o.a, mu, s.alpha, o.segment_radius, shape_filter, rng, x_start=x_start,
                          pit_p=s.pit_p, pit_width=(o.pit_width_min, o.pit_width_max), pit_depth=o.pit_depth)
