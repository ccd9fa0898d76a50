"""A tilted plane: gravity drives, F = M g sin(theta), and the pads carry M g cos(theta)."""
from __future__ import annotations

import math
from dataclasses import dataclass

from frictionnoise.base import G

from .drive import DRIVES, Drive, DriveSpec


@dataclass(frozen=True)
class TiltedSpec(DriveSpec):
    """theta: the slope (rad), in (0, pi/2)."""

    kind: str = "tilted"
    theta: float | None = None


@DRIVES.register
class Tilted(Drive):
    name = "tilted"
    Spec = TiltedSpec

    @classmethod
    def validate(cls, s, sc):
        if s.theta is None or not 0 < s.theta < math.pi / 2:
            raise ValueError(f"drive.theta must lie in (0, pi/2) rad for a tilted plane (got {s.theta!r})")
        super().validate(s, sc)

    def load_factor(self):
        return math.cos(self.spec.theta) if self.spec.theta else 1.0

    def side_label(self):
        return f"slope {self.spec.theta:.3g} rad: F = M g sin(theta) = {self.force():.3g} N"

    def force(self):
        return self.sc.block.M * G * math.sin(self.spec.theta)
