"""The scene's unit system (mm, g, ms) and every conversion between it and SI. Nothing else converts units.

In mm-g-ms units a force is g mm / ms^2 = 1 N, a velocity mm/ms = 1 m/s and a damping g/ms = 1 N s/m, so
those pass through unchanged; lengths scale by 1e3, masses by 1e3, times by 1e3, rates by 1e-3, stiffness by 1e-3
(N/m -> N/mm), accelerations by 1e-3 and energies by 1e3 (J -> N mm).

The scene's builder (:class:`engine_sim.scene.Scene`) converts each part's SI spec once, by the dimensions the part
declares (``scene_units``: field -> dimension), into a :class:`SceneValues` that the part reads while it builds and
steps; the recorder converts the samples back to SI (:mod:`engine_sim.record`) and the drawings label scene values
in SI (:mod:`engine_sim.render`, :mod:`engine_sim.side_render`). ``tests/engine_sim/test_units_boundary.py`` checks that no
other module holds a conversion.
"""
from __future__ import annotations

__all__ = ["DIMENSIONS", "SceneValues", "to_scene", "to_si", "scene_values"]

LENGTH = 1e3   # scene units per metre
MASS = 1e3     # per kilogram
TIME = 1e3     # per second
STIFFNESS = MASS / TIME**2   # N/m -> g/ms^2 (= N/mm)
ACCEL = LENGTH / TIME**2     # m/s^2 -> mm/ms^2
ENERGY = MASS * LENGTH**2 / TIME**2  # J -> g mm^2/ms^2 (= N mm)
VELOCITY = LENGTH / TIME     # = 1
FORCE = MASS * LENGTH / TIME**2  # = 1
DAMPING = MASS / TIME        # = 1

# dimension -> (SI -> scene, scene -> SI); a rate (1/s -> 1/ms) divides by TIME, the others multiply by their factor
_CONVERT = {
    "length": (lambda v: v * LENGTH, lambda v: v / LENGTH),
    "mass": (lambda v: v * MASS, lambda v: v / MASS),
    "time": (lambda v: v * TIME, lambda v: v / TIME),
    "rate": (lambda v: v / TIME, lambda v: v * TIME),
    "stiffness": (lambda v: v * STIFFNESS, lambda v: v / STIFFNESS),
    "acceleration": (lambda v: v * ACCEL, lambda v: v / ACCEL),
    "energy": (lambda v: v * ENERGY, lambda v: v / ENERGY),
    "velocity": (lambda v: v * VELOCITY, lambda v: v / VELOCITY),
    "force": (lambda v: v * FORCE, lambda v: v / FORCE),
    "damping": (lambda v: v * DAMPING, lambda v: v / DAMPING),
}
DIMENSIONS = tuple(_CONVERT)


def to_scene(value, dim: str):
    """``value`` (SI, a number or an array) in scene units, for the dimension ``dim`` (one of :data:`DIMENSIONS`)."""
    return _CONVERT[dim][0](value)


def to_si(value, dim: str):
    """``value`` (scene units, a number or an array) in SI, for the dimension ``dim``."""
    return _CONVERT[dim][1](value)


class SceneValues:
    """An immutable set of named values in scene units (a part's spec as the scene uses it, or what a part is
    handed of its neighbours). Read as attributes (plain instance attributes: a read costs what any attribute
    read costs); ``fields()`` lists the names."""

    def __init__(self, **values):
        self.__dict__.update(values)

    def __getattr__(self, name):  # only for a name that is not there
        raise AttributeError(f"no scene value {name!r} (has {', '.join(self.__dict__)})")

    def __setattr__(self, name, value):
        raise AttributeError("scene values are immutable")

    def __delattr__(self, name):
        raise AttributeError("scene values are immutable")

    def fields(self) -> tuple:
        return tuple(self.__dict__)

    def __repr__(self):
        return "SceneValues(" + ", ".join(f"{k}={v!r}" for k, v in self.__dict__.items()) + ")"


def scene_values(inputs: dict) -> SceneValues:
    """``inputs`` (name -> (SI value, dimension), as a part's ``scene_inputs()`` gives them) in scene units; a None
    value stays None."""
    return SceneValues(**{name: None if v is None else to_scene(v, dim) for name, (v, dim) in inputs.items()})
