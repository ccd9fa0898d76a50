"""Substrate kinds, one class each: its spec (a frozen SI dataclass, the ``[substrate]`` section of a scenario),
validation, build (the tracks, in scene units), length scale and drawing. The scene, the loader and the renderer
ask the part; none of them checks kinds.

A new kind is one module here defining a :class:`Substrate` subclass decorated with ``@SUBSTRATES.register`` (its
base imported from :mod:`engine_sim.substrates.substrate`), and one import line below (see ``line_scan.py``).
"""
from .substrate import SUBSTRATES, Substrate, SubstrateSpec, substrate_kind  # noqa: F401

# the kinds shipped: each module registers its class
from . import patches, self_affine, asperities, line_scan  # noqa: F401

__all__ = ["SubstrateSpec", "Substrate", "SUBSTRATES", "substrate_kind"]
