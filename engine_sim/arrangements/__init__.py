"""Pad arrangements, one class each: how the block meets the substrate. Its spec (the ``[pads]`` section, SI),
validation (the spring time-step limit among it), the friction of one pad column at speed v (for the drive force
and the steady speed), build (pads, their springs, the friction law's part on every sliding body, the tracks),
maintenance of the tracks, what it records (the sliding bodies, their loads, the springs that store energy), its
share of ``describe()`` and its drawing.

The scene reads back, after :meth:`Arrangement.build`: ``pads`` (the N bodies whose contact forces are the trace's
``pad_force``), ``sliders`` (every body under the friction law, pads first), ``slider_load`` and ``slider_c``
(each one's normal load [N] and viscous slope [N s/m]), ``block_springs`` (block to slider) and ``slider_springs``
(slider to slider), ``tracks``, ``track_surface`` and ``track_filter`` (per pad, for the wear particles).

A new arrangement is one module here with an :class:`Arrangement` subclass decorated with
``@ARRANGEMENTS.register`` (its base imported from :mod:`engine_sim.arrangements.arrangement`) and one import line
below.
"""
from ..regime import SPRING_DAMPING_X, SPRING_OMEGA_DT
from .arrangement import ARRANGEMENTS, LN, LT, Arrangement, PadSpec, arrangement_kind, track_rng  # noqa: F401

# the arrangements shipped: each module registers its class
from . import tracks, sole, micro  # noqa: F401

__all__ = ["PadSpec", "Arrangement", "ARRANGEMENTS", "arrangement_kind", "SPRING_OMEGA_DT", "SPRING_DAMPING_X",
           "LT", "LN", "track_rng"]
