"""A constant pulling speed: the block is pulled through a spring whose far end moves at v."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import pymunk

from .drive import DRIVES, Drive, DriveSpec

_REST = 5.0  # mm: the drive spring's rest length


@dataclass(frozen=True)
class VelocitySpec(DriveSpec):
    """v: the anchor's speed (m/s); k_drive: the pulling spring's stiffness (N/m)."""

    kind: str = "velocity"
    v: float = 5e-3
    k_drive: float = 1e3


@DRIVES.register
class Velocity(Drive):
    name = "velocity"
    scene_units = {"k_drive": "stiffness"}
    Spec = VelocitySpec
    positive = frozenset({"v", "k_drive"})
    constant_force = False

    def limits(self):
        """run.dt against the drive spring on the block (omega = sqrt(k_drive / M))."""
        from ..regime import dt_limit

        return [dt_limit("run.dt", self.sc, math.sqrt(self.spec.k_drive / self.sc.block.M), 0.0,
                         "the block on its drive spring")]

    def side(self, scene, lay):
        """The drive spring (schematic length) from the block's front to its anchor, which moves at v."""
        from ..side_view import zigzag

        x0, y = lay.width / 2 - 0.05 * lay.slot, lay.block_bottom + 0.5 * lay.block
        x1 = x0 + lay.drive_len
        d = 0.12 * lay.block
        shapes = super().side(scene, lay)
        shapes["drive"] = ("segments", [zigzag((x0, y), (x1, y), coils=4, width=0.15 * lay.block),
                                        np.array([(x1, y - d), (x1 + 2 * d, y - d), (x1 + 2 * d, y + d), (x1, y + d),
                                                  (x1, y - d)])],
                           {"colors": "k", "linewidths": 1.2, "zorder": 5})
        return shapes

    def side_label(self):
        return f"pulled at v = {self.spec.v * 1e3:.3g} mm/s through k_drive = {self.spec.k_drive:.4g} N/m"

    def force(self):
        return self.sc.pads.N * self.sc.column_force(self.spec.v)

    def steady_velocity(self):
        return self.spec.v

    def build(self, scene):
        """The anchor, a kinematic body moving at v, starts ahead by the spring's steady stretch."""
        kd = self.own.k_drive
        F_ss = self.own.force  # the law's steady force at v, N columns
        anchor = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        anchor.position = (_REST + F_ss / kd, scene.y_block)
        anchor.velocity = (scene.v_law, 0.0)
        self.spring = pymunk.DampedSpring(scene.block, anchor, (0, 0), (0, 0), _REST, kd, 0.0)
        scene.space.add(anchor, self.spring)
