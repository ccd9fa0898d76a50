"""Step costs of scenes measured side by side, so that a ratio of costs does not depend on what else the
machine is doing (a report's stages may run in parallel processes)."""
from __future__ import annotations

import time

from .loop import MAINTAIN_EVERY, Loop, warm_up
from .record import Recorder
from .scene import Scene

__all__ = ["step_costs"]


def step_costs(scenarios, seed: int | None = None, warmup: float = 1.0, chunks: int = 8) -> list[float]:
    """Microseconds per step of each scenario's loop (steps, recording at the output rate, maintenance).

    Every scene is first run ``warmup`` simulated seconds (to its steady state: grains placed ahead of the pads
    need that long to meet them and fall asleep), then the scenes take turns in chunks of MAINTAIN_EVERY
    output steps, ``chunks`` turns each; a scene's cost is its fastest chunk. Taking turns every few tens of ms
    exposes all scenes to the same load from other processes, and the fastest chunk drops the moments of
    contention."""
    scenes = [Scene(sc, seed) for sc in scenarios]
    loops = []
    for s in scenes:
        warm_up(s, int(round(warmup / s.sc.run.dt_out)))
        loops.append(Loop(s, Recorder(s, chunks * MAINTAIN_EVERY + 1)))
    best = [float("inf")] * len(scenes)
    for _ in range(chunks):
        for i, loop in enumerate(loops):
            t0 = time.perf_counter()
            loop.run(MAINTAIN_EVERY)  # one maintenance, then MAINTAIN_EVERY samples and their steps
            best[i] = min(best[i], (time.perf_counter() - t0) / (MAINTAIN_EVERY * loop.scene.n_sub))
    return [b * 1e6 for b in best]
