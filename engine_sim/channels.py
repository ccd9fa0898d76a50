"""Recorded channels beyond the trace's fixed fields: one class each, named by a scenario or declared by a part.

A channel is what the recorder writes per output sample besides the fixed fields of
:class:`~engine_sim.record.EngineTrace`: a force, an impulse sum, a state or an energy term, with its own compiled
reduction from pymunk's body buffer. It is one :class:`Channel` subclass decorated with ``@CHANNELS.register``: its
``name`` (the trace's ``channels[name]``), ``kind``, ``columns``, ``quantity`` (its dimension, one of
:data:`engine_sim.units.DIMENSIONS`: the recorder converts the recorded values to SI by it), :meth:`Channel.table` (its
parameters, scene units) and ``reduction``, a numba kernel

    reduction(ids, fl, tab, table, out)

which writes this sample's ``columns`` values (scene units) into ``out``. ``ids`` are the pymunk body ids of the body
buffer and ``fl`` its floats, :data:`BODY_FLOATS` per body (x, y, vx, vy, angular velocity); ``tab`` is the
recorder's body table, which :func:`body_of` reads: a body id's kind (:data:`BLOCK`, :data:`SLIDER`, :data:`GRAIN`,
:data:`DRIVE_BODY`; :data:`STATIC` for any other body) and index within its kind. A body absent from the buffer is
asleep, at rest.

A scenario records a channel by naming it in its top-level ``channels`` list (its module named in ``plugins``,
:mod:`engine_sim.plugins`, unless shipped); a part (law, drive, substrate, arrangement) records its own by listing
their names in its class attribute ``channels``.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np

from .contact_order import body_of
from .parts import Registry
from .sample_layout import BLOCK, DRIVE_BODY, GRAIN, SLIDER, STATIC
from .units import DIMENSIONS

__all__ = ["CHANNELS", "Channel", "check_channel", "recorded_channels", "body_of", "BODY_FLOATS", "BLOCK", "SLIDER",
           "GRAIN", "DRIVE_BODY", "STATIC"]

BODY_FLOATS = 5  # floats per body in the body buffer: x, y, vx, vy, angular velocity (scene units)
KINDS = ("force", "impulse", "state", "energy")


def check_channel(cls) -> None:
    """ValueError, one line naming the channel, the field and the allowed values, unless ``cls`` declares a
    ``name``, a ``kind`` (one of :data:`KINDS`), a ``quantity`` (one of :data:`engine_sim.units.DIMENSIONS`),
    ``columns`` (an int >= 1) and a ``reduction``. ``kind`` and ``quantity`` have no default: each channel sets
    its own."""
    label = f"channel {getattr(cls, 'name', '') or cls.__name__!r}"
    if not isinstance(getattr(cls, "name", None), str) or not cls.name:
        raise ValueError(f"{label}: name must be a non-empty string (the key of trace.channels)")
    for field, allowed in (("kind", KINDS), ("quantity", DIMENSIONS)):
        value = getattr(cls, field, None)
        if value not in allowed:
            got = "is not set" if value is None else f"is {value!r}"
            raise ValueError(f"{label}: {field} {got}; one of {', '.join(allowed)}")
    cols = getattr(cls, "columns", None)
    if isinstance(cols, bool) or not isinstance(cols, int) or cols < 1:
        raise ValueError(f"{label}: columns is {cols!r}; an int >= 1 (values per sample)")
    if not callable(getattr(cls, "reduction", None)):
        raise ValueError(f"{label}: reduction is not set; a numba kernel reduction(ids, fl, tab, table, out)")


class _ChannelRegistry(Registry):
    """The channels' registry: :meth:`register` checks a channel's declaration (:func:`check_channel`) when its
    module registers it, so a plugin with a misdeclared channel fails as it loads, before any scene is built."""

    def register(self, cls):
        check_channel(cls)
        return super().register(cls)


CHANNELS = _ChannelRegistry("recorded channel", key="channels")


class Channel:
    """One recorded channel of a scene (module docstring). ``scene`` is the built scene it records."""

    name: ClassVar[str] = ""
    kind: ClassVar[str | None] = None  # one of KINDS: what the values are (each channel sets it)
    columns: ClassVar[int] = 1  # values per sample
    quantity: ClassVar[str | None] = None  # the dimension of its values, one of engine_sim.units.DIMENSIONS (set it)
    reduction = None  # the numba kernel reduction(ids, fl, tab, table, out) (module docstring)

    def __init__(self, scene):
        self.scene = scene

    @property
    def kernel(self):
        """The compiled reduction (read from the class: a numba function is not bound to the channel)."""
        return type(self).reduction

    def table(self) -> np.ndarray:
        """The reduction's parameters (scene units); none by default."""
        return np.zeros(0)


def recorded_channels(scene) -> list:
    """The channels recorded in ``scene``: those its scenario names (top-level ``channels``) then those its parts
    declare (their ``channels`` attribute), each once, as :class:`Channel` objects. ValueError names an unregistered
    channel or a misdeclared one (:func:`check_channel`: a class put into CHANNELS without ``register``)."""
    names = list(getattr(scene.sc, "channels", ()))
    for part in (scene.law, scene.drive, scene.substrate, scene.arrangement):
        names += [n for n in getattr(part, "channels", ()) if n not in names]
    for n in names:
        if n not in CHANNELS:
            raise ValueError(f"channels: {n!r} is not a registered channel (registered: "
                             f"{', '.join(CHANNELS) or 'none'}; name its module in the scenario's plugins)")
        check_channel(CHANNELS[n])
    return [CHANNELS[n](scene) for n in names]
