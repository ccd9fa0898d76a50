"""engine_sim.run: simulate a scenario and record it (SI trace)."""
from __future__ import annotations

import time
from importlib import metadata as _md
from pathlib import Path

from .record import EngineTrace, Recorder
from .scenario import Scenario, load_scenario
from .scene import Scene

__all__ = ["run"]

_MAINTAIN_EVERY = 64  # output steps between substrate maintenance (the margin ahead covers 200 outputs)


def _version() -> str:
    try:
        return _md.version("frictionnoise")
    except _md.PackageNotFoundError:
        return "0+unknown"


def run(scenario, duration: float | None = None, seed: int | None = None, progress=None) -> EngineTrace:
    """Run a scenario (a path or a :class:`Scenario`) and return its trace.

    ``duration`` and ``seed`` override the scenario's ``[run]`` values. The warm-up (``run.warmup``) is
    simulated first and not recorded. ``progress(t_done, t_total)`` is called now and then (seconds).
    """
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(Path(scenario))
    if duration is not None:
        if not duration > 0:
            raise ValueError(f"duration must be positive (got {duration!r})")
        sc = sc.with_run(duration=float(duration))
    scene = Scene(sc, seed)
    n_sub = scene.n_sub
    n_warm = int(round(sc.run.warmup / sc.run.dt_out))
    n_out = int(round(sc.run.duration / sc.run.dt_out)) + 1
    total = (n_warm + n_out) * sc.run.dt_out
    t0 = time.perf_counter()
    for k in range(n_warm):
        scene.advance(n_sub)
        if k % _MAINTAIN_EVERY == 0:
            scene.maintain()
    rec = Recorder(scene, n_out)
    for k in range(n_out):
        rec.sample()
        if k + 1 < n_out:
            scene.advance(n_sub)
        if k % _MAINTAIN_EVERY == 0:
            scene.maintain()
            if progress is not None and k % (_MAINTAIN_EVERY * 16) == 0:
                progress((n_warm + k) * sc.run.dt_out, total)
    wall = time.perf_counter() - t0
    if progress is not None:
        progress(total, total)
    seed_used = scene.seed
    meta = {
        "producer": "engine_sim", "scenario": sc.to_dict(), "seed": scene.seed, "version": _version(),
        "wall_s": wall, "steps": scene.steps, "us_per_step": wall / max(scene.steps, 1) * 1e6,
        "steady_velocity_law": sc.steady_velocity, "drive_force": sc.drive_force if sc.drive.kind != "velocity" else None,
        "segments_generated": sum(t.generated for t in scene.tracks),
        "segments_live": sum(len(t.segments) for t in scene.tracks),
    }
    return rec.trace(meta)
