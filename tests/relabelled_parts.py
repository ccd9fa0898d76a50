"""A substrate and a drive added as a user's plugin: this module alone, named in a scenario's ``plugins``.

Each is a shipped part under a new name (``relabelled_patches``: friction patches; ``relabelled_velocity``: a
constant-velocity drive), so a scene built of them is the shipped one, bit for bit: what the test of the plugin
machinery checks.
"""
from __future__ import annotations

from dataclasses import dataclass

from engine_sim.drives import DRIVES
from engine_sim.drives.velocity import Velocity, VelocitySpec
from engine_sim.substrates import SUBSTRATES
from engine_sim.substrates.patches import Patches, PatchesSpec


@dataclass(frozen=True)
class RelabelledPatchesSpec(PatchesSpec):
    kind: str = "relabelled_patches"


@SUBSTRATES.register
class RelabelledPatches(Patches):
    """Friction patches under another name."""

    name = "relabelled_patches"
    Spec = RelabelledPatchesSpec


@dataclass(frozen=True)
class RelabelledVelocitySpec(VelocitySpec):
    kind: str = "relabelled_velocity"


@DRIVES.register
class RelabelledVelocity(Velocity):
    """A constant-velocity drive under another name."""

    name = "relabelled_velocity"
    Spec = RelabelledVelocitySpec
