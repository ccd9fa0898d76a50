"""What every scene part shares: a registry per family and the field rules the loader applies.

A part family (substrates, pad arrangements, drives, friction laws) is a base class with a frozen SI spec; each
kind is one subclass with ``name`` (the value of the section's discriminating key), ``Spec`` (its own spec class),
``positive`` / ``non_negative`` / ``choices`` (field checks made by the loader, by field name) and the behaviour
the scene, the recorder and the renderer ask of it. The scene never checks a kind.
"""
from __future__ import annotations

__all__ = ["Registry"]


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
