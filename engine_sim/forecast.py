"""What a run will cost before it starts: a short probe of the scene (build, then a few output steps with their
recording and substrate maintenance) projected to the run's length."""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .loop import Loop
from .record import Recorder
from .scene import Scene

__all__ = ["Forecast", "forecast", "LONG_RUN_S"]

LONG_RUN_S = 60.0  # a run projected to take longer than this says so before it starts
_PROBE_OUTPUTS = 64  # one substrate-maintenance interval of engine_sim.run
_PROBE_WALL = 1.0  # s: the probe stops early past this (a slow scene is known slow after one output step)


@dataclass(frozen=True)
class Forecast:
    """Projected wall time ``wall_s`` (s) of a run of ``simulated_s`` simulated seconds (warm-up included):
    ``build_s`` to build the scene, then ``per_simulated_s`` wall seconds per simulated second, measured over
    ``probe_outputs`` output steps on this machine as loaded now."""

    wall_s: float
    simulated_s: float
    build_s: float
    per_simulated_s: float
    probe_outputs: int

    def line(self) -> str:
        """One line for the user: the projection and what it rests on."""
        w = self.wall_s
        when = f"{w / 3600:.1f} h" if w >= 5400 else f"{w / 60:.1f} min" if w >= 90 else f"{w:.0f} s"
        return (f"projected wall time about {when}: {self.simulated_s:g} s simulated (warm-up included) at "
                f"{self.per_simulated_s:.3g} wall s per simulated s, measured over {self.probe_outputs} output steps "
                f"on this machine as loaded now, plus twice {self.build_s:.1f} s to build the scene")


def forecast(sc, duration: float | None = None, seed: int | None = None) -> Forecast:
    """Probe a scenario's scene and project the wall time of ``engine_sim.run(sc, duration, seed)``.

    The probe builds the scene (timed), steps its first output step (its sample loads the recorder's kernel;
    untimed), then times the next 63 output steps with their recording one by one (:class:`engine_sim.loop.Loop`),
    stopping early after one second, and the substrate maintenance that follows them (the segments generated for
    the distance slid); the projection takes the median output step. It costs at most about one second plus one
    scene build."""
    dur = sc.run.duration if duration is None else float(duration)
    n_out = int(round((sc.run.warmup + dur) / sc.run.dt_out)) + 1
    t0 = time.perf_counter()
    scene = Scene(sc, seed)
    build = time.perf_counter() - t0
    loop = Loop(scene, Recorder(scene, _PROBE_OUTPUTS + 2))
    loop.step()  # the first sample (it loads the recorder's kernel) and the first maintenance
    times = []
    start = time.perf_counter()
    while len(times) < _PROBE_OUTPUTS - 1 and time.perf_counter() - start < _PROBE_WALL:
        t0 = time.perf_counter()
        loop.step()  # output steps 1 .. 63: a sample and its steps, no maintenance
        times.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    scene.maintain()  # outside the loop: one maintenance timed apart from the output steps, to project each
    k = len(times)
    # the median step: a moment of contention from other processes does not set the projection
    per_out = float(np.median(times)) + (time.perf_counter() - t0) / k
    # a run builds the scene twice in a fresh process (once to load the recorder's kernel, engine_sim.run)
    return Forecast(wall_s=2 * build + per_out * n_out, simulated_s=sc.run.warmup + dur, build_s=build,
                    per_simulated_s=per_out / sc.run.dt_out, probe_outputs=k)
