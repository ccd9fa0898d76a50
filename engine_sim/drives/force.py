"""A constant force on the block (model I's F_drive, eq. (A1))."""
from __future__ import annotations

from dataclasses import dataclass

from .drive import DRIVES, Drive, DriveSpec


@dataclass(frozen=True)
class ForceSpec(DriveSpec):
    """force (N): if unset, chosen so the friction law slides the block at ``v`` (m/s): F = N f(v)."""

    kind: str = "force"
    v: float = 5e-3
    force: float | None = None


@DRIVES.register
class Force(Drive):
    name = "force"
    Spec = ForceSpec
    positive = frozenset({"v"})

    def force(self):
        s = self.spec
        if s.force is not None:
            return s.force
        return self.sc.pads.N * self.sc.column_force(s.v)
