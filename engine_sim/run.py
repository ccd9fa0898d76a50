"""engine_sim.run: simulate a scenario and record it (SI trace)."""
from __future__ import annotations

import pickle
import signal
import threading
import time
from contextlib import contextmanager
from pathlib import Path

from frictionnoise import atomic_write, package_version

from . import units as U
from .record import EngineTrace, Recorder
from .scenario import Scenario, load_scenario
from .scene import Scene, describe

__all__ = ["run"]

_MAINTAIN_EVERY = 64  # output steps between substrate maintenance (the margin ahead covers 200 outputs)


def _warm_up(scene, n_out: int, interrupts=None):
    """Run n_out output steps unrecorded, maintaining the substrate as the recorded loop does."""
    for k in range(n_out):
        if interrupts is not None:
            interrupts.check()
        if k % _MAINTAIN_EVERY == 0:
            scene.maintain()
        scene.advance(scene.n_sub)


class _Interrupts:
    """SIGINT deferred to the loop's consistent points (between output steps, where the loop's counter and the
    recorder's agree and no pymunk step is half done). A KeyboardInterrupt raised anywhere else left a checkpoint
    whose counters disagreed by one sample; resuming from it wrote past the recorder's buffers (heap corruption)."""

    def __init__(self):
        self.pending = False

    def _handler(self, signum, frame):
        self.pending = True

    @contextmanager
    def deferred(self):
        if threading.current_thread() is not threading.main_thread():
            yield self  # signals reach the main thread only; nothing to defer here
            return
        old = signal.signal(signal.SIGINT, self._handler)
        try:
            yield self
        finally:
            signal.signal(signal.SIGINT, old)

    def check(self):
        if self.pending:
            raise KeyboardInterrupt


def _snapshot(scene, rec, k) -> bytes:
    if rec.k != k:
        raise RuntimeError(f"snapshot at an inconsistent point (loop at sample {k}, recorder at {rec.k})")
    # Scene and Recorder pickle through their own state methods (the recorder carries its scene)
    return pickle.dumps({"recorder": rec, "k": k}, protocol=pickle.HIGHEST_PROTOCOL)


def _restore(data: bytes, n_out: int):
    state = pickle.loads(data)
    if not isinstance(state, dict) or not isinstance(state.get("recorder"), Recorder):
        raise ValueError("checkpoint holds no recorder (written by another version?): delete it and run again")
    rec = state["recorder"]
    scene = rec.scene
    if not (rec.k == state["k"] and 0 <= rec.k < n_out and rec.t.shape[0] == n_out):
        raise ValueError(f"checkpoint is inconsistent (loop at sample {state['k']}, recorder at {rec.k}, "
                         f"{n_out} samples): delete it and run again")
    return scene, rec, state["k"]


def _write_atomic(path: Path, key: dict, data: bytes):
    atomic_write(path, pickle.dumps({"key": key, "data": data}, protocol=pickle.HIGHEST_PROTOCOL))


def run(scenario, duration: float | None = None, seed: int | None = None, progress=None, *,
        checkpoint: str | None = None, checkpoint_every: float | None = None) -> EngineTrace:
    """Run a scenario (a path or a :class:`Scenario`) and return its trace.

    ``duration`` and ``seed`` override the scenario's ``[run]`` values. The warm-up (``run.warmup``) is
    simulated first and not recorded. ``progress(t_done, t_total)`` is called now and then (seconds).

    ``checkpoint``/``checkpoint_every``: every that many simulated seconds the whole scene is pickled to the
    file (atomically) and, since a restored pymunk space is not an exact continuation of the live one, the run
    itself continues from the restored copy; a run started with an existing checkpoint of the same scenario,
    duration and seed resumes from it, and the trace is identical bit for bit to an uninterrupted run.
    Ctrl-C (KeyboardInterrupt) stops at the next output step, writes a checkpoint if one is configured and
    returns the trace so far with ``metadata["partial"] = True``.
    """
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(Path(scenario))
    if duration is not None:
        if not duration > 0:
            raise ValueError(f"duration must be positive (got {duration!r})")
        sc = sc.with_run(duration=float(duration))
    n_warm = int(round(sc.run.warmup / sc.run.dt_out))
    n_out = int(round(sc.run.duration / sc.run.dt_out)) + 1
    total = (n_warm + n_out) * sc.run.dt_out
    every = max(1, int(round(checkpoint_every / sc.run.dt_out))) if checkpoint_every else None
    ck_path = Path(checkpoint) if checkpoint else None
    key = {"scenario": sc.to_dict(), "seed": seed, "n_out": n_out, "every": every}
    t0 = time.perf_counter()
    resumed = False
    intr = _Interrupts()
    with intr.deferred():
        if ck_path is not None and ck_path.exists():
            try:
                with open(ck_path, "rb") as fh:
                    saved = pickle.load(fh)
                if not isinstance(saved, dict) or "data" not in saved:
                    raise ValueError("not a checkpoint")
            except (OSError, EOFError, ValueError, TypeError, AttributeError, ImportError, pickle.UnpicklingError) as e:
                raise ValueError(f"{ck_path}: not a readable checkpoint ({type(e).__name__}: {e}); delete it and run "
                                 "again") from None
            if saved.get("key") != key:
                raise ValueError(f"{ck_path}: checkpoint of a different run (scenario, duration, seed or interval "
                                 "differ)")
            scene, rec, k0 = _restore(saved["data"], n_out)
            resumed = True
        else:
            scene = Scene(sc, seed)
            _warm_up(scene, n_warm, intr)
            rec = Recorder(scene, n_out)
            k0 = 0
        n_sub = scene.n_sub
        partial = False
        k = k0
        try:
            while k < n_out:
                intr.check()  # the one place a Ctrl-C takes effect: here k == rec.k
                rec.sample()
                # maintenance (substrate streaming, particle recycling) right after a sample and before the next
                # steps: pymunk recomputes a cached arbiter's contact points from the bodies' current positions,
                # so a particle moved between a step and a sample would report a bogus overlap
                if k % _MAINTAIN_EVERY == 0:
                    scene.maintain()
                    if progress is not None and k % (_MAINTAIN_EVERY * 16) == 0:
                        progress((n_warm + k) * sc.run.dt_out, total)
                if k + 1 < n_out:
                    scene.advance(n_sub)
                k += 1
                if every and k % every == 0 and k < n_out:
                    data = _snapshot(scene, rec, k)
                    if ck_path is not None:
                        _write_atomic(ck_path, key, data)
                    scene, rec, k = _restore(data, n_out)  # continue from the copy, exactly as a resumed run will
        except KeyboardInterrupt:
            if rec.k == 0:
                raise  # nothing recorded yet
            partial = True
            if ck_path is not None and every:
                _write_atomic(ck_path, key, _snapshot(scene, rec, k))
    wall = time.perf_counter() - t0
    if progress is not None and not partial:
        progress(total, total)
    meta = {
        "producer": "engine_sim", "scenario": sc.to_dict(), "seed": scene.seed, "version": package_version(),
        "wall_s": wall, "steps": scene.steps, "us_per_step": wall / max(scene.steps, 1) * 1e6,
        "steady_velocity_law": sc.steady_velocity, "drive_force": sc.drive_force if sc.drive.kind != "velocity" else None,
        "segments_generated": sum(t.generated for t in scene.tracks),
        "segments_live": sum(len(t.segments) for t in scene.tracks),
        "partial": partial, "resumed_from_checkpoint": resumed, "scene": describe(sc),
    }
    if scene.wear is not None:
        w = scene.wear
        meta["wear"] = {"count": w.count, "recycled": w.recycled, "left_interface": w.lost,
                        "radii_m": (w.r / U.LENGTH).tolist(), "track": w.track.tolist(),
                        "asleep_at_end": int(sum(b.is_sleeping for b in w.bodies))}
    return rec.trace(meta)
