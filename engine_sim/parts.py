"""What every scene part shares: a registry per family and the field rules the loader applies.

A part family (substrates, pad arrangements, drives, friction laws) is a base class with a frozen SI spec; each
kind is one subclass with ``name`` (the value of the section's discriminating key), ``Spec`` (its own spec class),
``positive`` / ``non_negative`` / ``choices`` (field checks made by the loader, by field name) and the behaviour
the scene, the recorder and the renderer ask of it. The scene never checks a kind.

Every part is a :class:`Part`: its spec is SI; the scene's builder (:class:`engine_sim.scene.Scene`) converts what
the part declares it needs in scene units (``scene_units``, or :meth:`Part.scene_inputs`) once and hands it, with
what the part needs of its neighbours (``ctx``, also in scene units) as the part's ``own`` and ``ctx``
attributes. Both are immutable (:class:`engine_sim.units.SceneValues`). A part's scenario-side methods answer in SI,
its scene-side ones (build, maintain, draw) in scene units.
"""
from __future__ import annotations

from typing import ClassVar

__all__ = ["Registry", "Part"]


class Part:
    """The base of every part family. ``scene_units``: the spec's fields the scene side reads, by dimension (field ->
    one of :data:`engine_sim.units.DIMENSIONS`). On a scene's own parts, the builder sets ``own`` (what
    :meth:`scene_inputs` names, in scene units) and then ``ctx`` (what the part needs of its neighbours, scene units);
    the scene-side methods read those, never a spec's SI value."""

    scene_units: ClassVar[dict] = {}

    def __init__(self, spec, scenario):
        self.spec, self.sc = spec, scenario

    def scene_inputs(self) -> dict:
        """name -> (SI value, dimension) of what the scene side reads in scene units: the fields ``scene_units``
        names, and what a part adds (derived values, its constants)."""
        return {name: (getattr(self.spec, name), dim) for name, dim in self.scene_units.items()}

    def subparts(self) -> list:
        """Parts this part builds with (e.g. the micro-pads' substrate), bound by the builder as this part is."""
        return []


class Registry(dict):
    """name -> part class, filled by :meth:`register` (a class decorator). ``key`` is the scenario key that names
    the kind in its section (``kind`` or ``law``)."""

    def __init__(self, family: str, key: str = "kind"):
        super().__init__()
        self.family, self.key = family, key

    def register(self, cls):
        self[cls.name] = cls
        return cls

    def of_spec(self, spec_cls):
        """The part class whose Spec is ``spec_cls``."""
        return next(k for k in self.values() if k.Spec is spec_cls)
