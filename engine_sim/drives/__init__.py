"""Drives, one class each: its spec (the ``[drive]`` section, SI), validation, the drive force and the normal load
it leaves on the pads, build (a spring from the pulled body to an anchor body, plus any bodies of its own), the
recorded terms (that spring and those bodies: the recorder reads the drive's force, power and energy from them)
and its drawing.

A new drive is one module here with a :class:`Drive` subclass decorated with ``@DRIVES.register`` (its base
imported from :mod:`engine_sim.drives.drive`) and one import line below.
"""
from .drive import DRIVES, FAR, Drive, DriveSpec, drive_kind  # noqa: F401

# the drives shipped: each module registers its class
from . import force, tilted, velocity, leonardo  # noqa: F401

__all__ = ["DriveSpec", "Drive", "DRIVES", "drive_kind", "FAR"]
