"""Leonardo da Vinci's slider (paper Fig. 7): a hanging mass pulls the block through a rope over an ideal pulley."""
from __future__ import annotations

from dataclasses import dataclass

import pymunk

from frictionnoise.base import G

from .drive import DRIVES, FAR, Drive, DriveSpec


@dataclass(frozen=True)
class LeonardoSpec(DriveSpec):
    """hanging_mass (kg): F = m_h g; if unset, chosen so the friction law slides the block at ``v`` (m/s);
    rope_length (m): the rope, a joint that can go slack."""

    kind: str = "leonardo"
    v: float = 5e-3
    hanging_mass: float | None = None
    rope_length: float = 0.2


@DRIVES.register
class Leonardo(Drive):
    """The pulley (massless, frictionless) turns the rope without changing its tension, so the hanging mass's
    motion along the rope is represented unfolded, on a horizontal groove ahead of the block: its weight m_h g is
    the far constant-force spring (its vertical weight is carried by the groove), its inertia m_h a real body, and
    the rope a SlideJoint that holds at most rope_length."""

    name = "leonardo"
    scene_units = {"rope_length": "length"}
    Spec = LeonardoSpec
    positive = frozenset({"v", "hanging_mass", "rope_length"})

    def side_label(self):
        return f"rope to a hanging mass {self.extra_mass:.3g} kg: F = {self.force():.3g} N"

    def force(self):
        s = self.spec
        if s.hanging_mass is not None:
            return s.hanging_mass * G
        return self.sc.pads.N * self.sc.column_force(s.v)

    @property
    def extra_mass(self):
        s = self.spec
        return s.hanging_mass if s.hanging_mass is not None else self.sc.drive_force / G

    def build(self, scene):
        L_rope = self.own.rope_length
        y = scene.y_block
        hang = pymunk.Body(self.own.extra_mass, float("inf"))
        hang.position = (L_rope, y)
        hang.velocity = (scene.v_law, 0.0)
        scene.space.add(hang, pymunk.GrooveJoint(scene.space.static_body, hang, (-FAR, y), (FAR, y), (0, 0)),
                        pymunk.SlideJoint(scene.block, hang, (0, 0), (0, 0), 0.0, L_rope))
        self.bodies, self.pulled = [hang], 0
        self._far_spring(scene, hang)

    def draw(self, scene, lo, hi):
        """The rope from the block over a pulley at the window's right edge down to the hanging mass, drawn folded
        as in the paper's Fig. 7 (the mass a fixed 30 mm below the pulley)."""
        hang = self.bodies[0]
        bx, y = scene.block.position.x, scene.y_block
        px, py = hi - 2.0, y
        my = py - 30.0
        slack = self.own.rope_length - (hang.position.x - bx)  # mm
        label = f"hanging mass {self.extra_mass:.3g} kg, rope slack {slack * 1e3:+.2f} um"
        return {
            "rope": ("line", ([bx + 2.5, px, px + 1.2, px + 1.2], [y, py + 1.2, py, my + 8.0]),
                     {"color": "0.15", "lw": 1.2, "zorder": 5}),
            "pulley": ("circle", ((px, py), 1.2), {"facecolor": "0.85", "edgecolor": "0.2", "zorder": 5}),
            "mass": ("rect", ((px + 1.2 - 1.5, my), 3.0, 8.0),
                     {"facecolor": "tab:brown", "edgecolor": "0.2", "alpha": 0.9, "zorder": 5}),
            "label": ("caption", label, {}),  # on the time line: drawn at the mass it covered the tracks
        }
