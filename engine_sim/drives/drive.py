"""The base of every drive: the fields every ``[drive]`` section has (:class:`DriveSpec`), the class a drive
subclasses (:class:`Drive`, itself the constant force) and the registry (:data:`DRIVES`). :mod:`engine_sim.drives`
re-exports them and imports the shipped drives, so a drive module here imports its base from this module."""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pymunk

from ..parts import Part, Registry

__all__ = ["DriveSpec", "Drive", "DRIVES", "drive_kind", "FAR"]

DRIVES = Registry("drive")

# mm: a constant force is a soft spring anchored FAR behind and compressed by FAR, so over a metre of sliding its
# force changes by 1 m / FAR = 1e-6 relative and no Python runs inside a step (pymunk clears body forces every step)
FAR = 1e9


@dataclass(frozen=True)
class DriveSpec:
    """Fields every drive has: kind, its registered name."""

    kind: str = "force"


class Drive(Part):
    """One drive. After :meth:`build`: ``spring`` (a DampedSpring from the pulled body to a kinematic anchor, body
    b), ``bodies`` (bodies of the drive's own that carry kinetic energy) and ``pulled`` (the index in ``bodies`` of
    the body the spring pulls, -1 for the block)."""

    name: ClassVar[str] = ""
    Spec: ClassVar[type] = DriveSpec
    positive: ClassVar[frozenset] = frozenset()
    non_negative: ClassVar[frozenset] = frozenset()
    choices: ClassVar[dict] = {}
    constant_force: ClassVar[bool] = True  # the drive force is set, the speed follows from the friction law

    def __init__(self, spec, scenario):
        super().__init__(spec, scenario)
        self.spring, self.bodies, self.pulled = None, [], -1

    def scene_inputs(self) -> dict:
        """The drive force (``force``) and the mass moved with the block (``extra_mass``), and the spec's fields
        ``scene_units`` names."""
        return {**super().scene_inputs(), "force": (self.force(), "force"), "extra_mass": (self.extra_mass, "mass")}

    @classmethod
    def validate(cls, spec, sc) -> None:
        """Raise ValueError (naming the field) if the drive cannot slide the scene."""
        if cls.constant_force and not sc.steady_velocity > 0:
            raise ValueError(f"drive force {sc.drive_force:.4g} N does not exceed the friction law's force as "
                             f"sliding starts, N f(0) = {sc.pads.N * sc.column_force(0.0):.4g} N: the block would not "
                             f"slide (a law whose force falls from rest reaches its strengthening branch under a "
                             f"velocity drive)")

    def limits(self) -> list:
        """The drive's regime limits (:class:`engine_sim.regime.Limit`; none for a constant force, whose far spring
        changes by 1e-6 over a metre)."""
        return []

    def load_factor(self) -> float:
        """The share of the block's weight pressing on the pads (cos theta on a slope)."""
        return 1.0

    def force(self) -> float:
        """The drive force (N); for a velocity drive the friction law's steady force at its speed."""
        raise NotImplementedError

    @property
    def extra_mass(self) -> float:
        """Mass the drive moves with the block (kg; the effective mass is the block's plus this)."""
        return 0.0

    def steady_velocity(self) -> float:
        """The friction law's steady speed under the drive, N f(v) = F (m/s); <= 0 if F does not exceed the
        law's force as sliding starts, N f(0) (f: the friction of one pad column, ``Scenario.column_force``)."""
        sc = self.sc
        target = sc.drive_force / sc.pads.N
        f0 = sc.column_force(0.0)
        if target <= f0:
            return (target - f0) / max(sc.friction_slope(0.0), 1e-300)
        hi = 1e-6
        while sc.column_force(hi) < target:
            hi *= 2.0
            if hi > 1e6:
                return float("inf")
        lo = 0.0
        for _ in range(200):  # bisection: f is increasing; 200 halvings reach double precision
            mid = 0.5 * (lo + hi)
            if sc.column_force(mid) < target:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    def build(self, scene) -> None:
        """A constant force F: the far compressed spring on the block (scene units)."""
        self._far_spring(scene, scene.block)

    def _far_spring(self, scene, pulled):
        F = self.own.force
        kd = F / FAR
        anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        anchor.position = (-FAR, scene.y_block)  # behind: the compressed spring pushes the body forward
        rest = FAR + FAR  # length FAR, compression FAR: force kd * FAR = F
        self.spring = pymunk.DampedSpring(pulled, anchor, (0, 0), (0, 0), rest, kd, 0.0)
        scene.space.add(anchor, self.spring)

    def draw(self, scene, lo: float, hi: float) -> dict:
        """Shapes to draw (see ``render.py``: name -> (kind, data, style)), scene units."""
        return {}

    def side(self, scene, lay) -> dict:
        """The side view's drive (display mm): an arrow on the block's front, labelled with the force."""
        x0, y = lay.width / 2 - 0.05 * lay.slot, lay.block_bottom + 0.5 * lay.block
        x1 = x0 + lay.drive_len
        head = 0.06 * lay.slot
        return {"drive": ("segments", [np.array([(x0, y), (x1, y)]), np.array([(x1 - head, y + head / 2), (x1, y),
                                                                               (x1 - head, y - head / 2)])],
                          {"colors": "k", "linewidths": 1.5, "zorder": 5}),
                "drive_label": ("text", ((x0 + 0.05 * lay.slot, lay.top + 0.05), f"drive: {self.side_label()}"),
                                {"fontsize": 8, "ha": "right", "va": "bottom", "zorder": 5})}

    def side_label(self) -> str:
        """The drive in a few words for the side view."""
        return f"F = {self.force():.3g} N"

    def describe(self) -> dict:
        return {}


def drive_kind(name: str):
    """The Drive class registered as ``name`` (KeyError if none)."""
    return DRIVES[name]
