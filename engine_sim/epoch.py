"""The run's epoch: how often every run passes its scene through a pickle round trip.

A pymunk space restored from a pickle is not an exact continuation of the live one (the constraints'
accumulated impulses and the order of arbiters and of the spatial index are not saved). So every run,
checkpointed or not, continues from a restored copy at fixed epochs; checkpoints fall on epochs and a resumed
run takes the same path as an uninterrupted one. The epoch sets two costs: the round trips' share of the
wall time (shorter epochs cost more) and the most simulated time a kill can lose (one epoch at the shortest
checkpoint interval).

The default epoch follows from a cost model of the round trip and of the stepping, both read from the scene
when recording starts (a deterministic function of scenario and seed, so every run of it has the same epoch),
with constants measured on the shipped scenes (pymunk 7.3.1, 2-core machine; benchmarks/bench_epoch.py
measures the actual ratio). The target share is 3.5 %, below the 5 % budget, because timings on a shared
machine vary by a few tens of percent (measured shares at the default epochs: 1.3-3.2 %).
"""
from __future__ import annotations

import math

__all__ = ["default_epoch", "TARGET_SHARE"]

TARGET_SHARE = 0.035  # estimated round trip / stepping over one epoch

# round trip (dumps + loads + set_neighbors), ms: a base, per shape (pymunk pickles every shape through Python
# __getstate__/__setstate__; substrate segments are most of them) and per dynamic body beyond the block and pads
# (wear grains: their arbiters are pickled too). Measured under load (bench_epoch): patches 270 ms / 636 shapes,
# rough profile 1850 ms / 5066, wear 860 ms / 1750 shapes + 50 grains, asperity field 29 ms / 73 shapes.
_RT_BASE_MS, _RT_SHAPE_MS, _RT_BODY_MS = 20.0, 0.4, 6.0
# stepping, ms per 10 pymunk steps: base, per solver iteration, per shape (broad phase), per extra body.
# Measured per output step (10 steps): patches 0.63 (2 iterations), rough 2.3-3.4 (10), asperity 1.0-1.3 (10),
# wear 4.2-4.5 (20)
_ST_BASE_MS, _ST_ITER_MS, _ST_SHAPE_MS, _ST_BODY_MS = 0.35, 0.08, 0.00015, 0.05


def _extra_bodies(scene) -> int:
    return max(0, len(scene.space.bodies) - 1 - len(scene.pads) - len(scene.drive.bodies))


def estimated_costs(scene) -> tuple[float, float]:
    """(round trip [ms], stepping [ms per output step]) by the cost model, for the scene as it is now."""
    shapes, extra = len(scene.space.shapes), _extra_bodies(scene)
    rt = _RT_BASE_MS + _RT_SHAPE_MS * shapes + _RT_BODY_MS * extra
    step = scene.n_sub / 10 * (_ST_BASE_MS + _ST_ITER_MS * scene.space.iterations + _ST_SHAPE_MS * shapes
                               + _ST_BODY_MS * extra)
    return rt, step


def default_epoch(scene, dt_out: float) -> float:
    """The default epoch (simulated seconds, a whole number, at least 1) for a scene at the start of recording:
    the shortest whole number of seconds whose estimated round-trip share is at most :data:`TARGET_SHARE`."""
    rt, step = estimated_costs(scene)
    outputs = rt / (TARGET_SHARE * step)
    return float(max(1, math.ceil(outputs * dt_out)))
