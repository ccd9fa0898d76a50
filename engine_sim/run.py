"""engine_sim.run: simulate a scenario and record it (SI trace)."""
from __future__ import annotations

import os
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
from .epoch import default_epoch
from .scene import Scene, describe

__all__ = ["run", "CheckpointError", "TraceSizeError"]

_MAINTAIN_EVERY = 64  # output steps between substrate maintenance (the margin ahead covers 200 outputs)


def _warm_up(scene, n_out: int, interrupts=None):
    """Run n_out output steps unrecorded, maintaining the substrate as the recorded loop does."""
    for k in range(n_out):
        if interrupts is not None:
            interrupts.check()
        if k % _MAINTAIN_EVERY == 0:
            scene.maintain()
        scene.advance(scene.n_sub)


class CheckpointError(ValueError):
    """A checkpoint file that is corrupt or belongs to another run; the message says which and what to do."""


_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Interrupts:
    """SIGINT and SIGTERM deferred to the loop's consistent points (between output steps, where the loop's counter
    and the recorder's agree and no pymunk step or round trip is half done). A KeyboardInterrupt raised anywhere
    else left a checkpoint whose counters disagreed by one sample; resuming from it wrote past the recorder's
    buffers (heap corruption)."""

    def __init__(self):
        self.signum = None

    def _handler(self, signum, frame):
        self.signum = signum

    @contextmanager
    def deferred(self):
        if threading.current_thread() is not threading.main_thread():
            yield self  # signals reach the main thread only; nothing to defer here
            return
        old = {s: signal.signal(s, self._handler) for s in _SIGNALS}
        try:
            yield self
        finally:
            for s, h in old.items():
                signal.signal(s, h)

    def check(self):
        if self.signum is not None:
            raise KeyboardInterrupt


class TraceSizeError(ValueError):
    """The trace of the asked run would not fit in this machine's memory; nothing was started."""


def _check_trace_size(sc, n_out: int):
    """Refuse a run whose recorder buffers (per sample: 12 scalar channels, time, recycling work, one force per pad
    and two entries per wear particle) exceed half the memory available now: numpy's allocation error was a
    20-line traceback for `--duration 1e7`."""
    n_p = sc.wear.count
    need = n_out * 8.0 * (14 + sc.pads.N + 1.125 * n_p)
    try:
        avail = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):  # no such figure on this platform: do not guess
        return
    if need > 0.5 * avail:
        raise TraceSizeError(f"a run of {sc.run.duration:g} s at dt_out = {sc.run.dt_out:g} s needs "
                             f"{need / 2**30:.3g} GiB of trace buffers; {avail / 2**30:.3g} GiB are free (use a shorter "
                             "--duration or split the run)")


_REC_ARRAYS = ("t", "out", "pad_force", "n_contact", "p_state", "p_force", "recycle", "micro_force")
_FORMAT = "frictionnoise-checkpoint-4"  # 4: the recorder holds micro_force


def _rec_state(rec, k) -> dict:
    """The recorder's state at sample k: rows below k of its buffers (by reference) and its small mutable parts."""
    if rec.k != k:
        raise RuntimeError(f"epoch at an inconsistent point (loop at sample {k}, recorder at {rec.k})")
    return {"k": k, "x0": rec.x0, "part": rec._part.copy(), "arrays": {a: getattr(rec, a) for a in _REC_ARRAYS}}


def _rebind(scene_bytes: bytes, rs: dict, n_out: int):
    """The scene restored from its pickle and a recorder on it holding ``rs``: the one path by which every run
    continues at an epoch, live or resumed from a file."""
    scene = pickle.loads(scene_bytes)  # Scene.__setstate__ re-applies segment neighbours and re-reads body ids
    rec = Recorder(scene, n_out)
    k = rs["k"]
    for a in _REC_ARRAYS:
        src = rs["arrays"][a]
        dst = getattr(rec, a)
        if src.shape[1:] != dst.shape[1:] or src.shape[0] < k or src.dtype != dst.dtype:
            raise CheckpointError(f"recorder array {a!r} of shape {src.shape} does not fit {dst.shape}")
        if src.shape[0] == dst.shape[0]:
            setattr(rec, a, src)  # live: keep the buffers
        else:
            dst[:k] = src[:k]
    rec._part, rec.k, rec.x0 = rs["part"].copy(), k, rs["x0"]
    return scene, rec


def _write_checkpoint(path: Path, key: dict, e_out: int, scene_bytes: bytes, rs: dict):
    k = rs["k"]
    rec = {"k": k, "x0": rs["x0"], "part": rs["part"], "arrays": {a: v[:k] for a, v in rs["arrays"].items()}}
    _write_atomic(path, {"format": _FORMAT, "key": key, "epoch_outputs": e_out, "scene": scene_bytes, "rec": rec})


def _read_checkpoint(path: Path, key: dict, n_out: int):
    what = "delete it (or write to another -o folder) and run again"
    try:
        with open(path, "rb") as fh:
            saved = pickle.load(fh)
        if not isinstance(saved, dict) or saved.get("format") != _FORMAT:
            raise ValueError("not a checkpoint of this version")
        rs, e_out = saved["rec"], saved["epoch_outputs"]
        if not (isinstance(rs, dict) and 0 < rs["k"] < n_out and isinstance(e_out, int) and e_out > 0
                and rs["k"] % e_out == 0):
            raise ValueError(f"sample counter {rs.get('k')!r} is not an epoch in 1..{n_out - 1}")
    except Exception as e:  # anything unpickling junk can raise
        raise CheckpointError(f"{path}: not a readable checkpoint ({type(e).__name__}: {e}); {what}") from None
    old = saved.get("key", {})
    if old != key:
        diff = [f for f in key if old.get(f) != key[f]]
        raise CheckpointError(f"{path}: checkpoint of another run ({', '.join(diff) or 'key'} {'differs' if len(diff) == 1 else 'differ'}); {what}")
    try:
        scene, rec = _rebind(saved["scene"], rs, n_out)
    except Exception as e:
        raise CheckpointError(f"{path}: not a readable checkpoint ({type(e).__name__}: {e}); {what}") from None
    return scene, rec, rs["k"], e_out


def _write_atomic(path: Path, obj):
    """A pickle written atomically (the one writer: created 0666 less the umask)."""
    atomic_write(path, pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))


def _every(e_out: int, dt_out: float, checkpoint_every: float | None) -> int | None:
    """The checkpoint interval in output steps: the whole number of epochs nearest ``checkpoint_every``, at
    least one."""
    if not checkpoint_every:
        return None
    return e_out * max(1, int(round(checkpoint_every / (e_out * dt_out))))


def _load_recorder_kernel(sc, seed):
    """Load (or compile) the recorder's numba kernel before signals are deferred: the first sample of a process
    loads it (0.7 s from numba's cache, about 9 s compiling in a fresh clone), and a Ctrl-C landing in that load
    waited for it (1.3-9 s to the exit). A one-sample Recorder on a throwaway Scene, once per process (measured
    0.03 s for pads_friction_patches), outside the deferral, where a Ctrl-C interrupts at once."""
    from .reduction import reduce_sample
    if not reduce_sample.signatures:
        Recorder(Scene(sc, seed), 1).sample()


def run(scenario, duration: float | None = None, seed: int | None = None, progress=None, *,
        checkpoint: str | None = None, checkpoint_every: float | None = None, epoch: float | None = None,
        on_plan=None) -> EngineTrace:
    """Run a scenario (a path or a :class:`Scenario`) and return its trace.

    ``duration`` and ``seed`` override the scenario's ``[run]`` values. The warm-up (``run.warmup``) is
    simulated first and not recorded. ``progress(t_done, t_total)`` is called now and then (seconds).

    Exact continuation: every ``epoch`` simulated seconds of the recorded part (default: the scene's, see
    :mod:`engine_sim.epoch`), every run pickles its scene and continues from the restored copy, since a
    restored pymunk space is not an exact continuation of the live one. The epoch is part of the run's
    definition (in its metadata); whether, how often and where a run is checkpointed or interrupted is not: the
    bits are the same. ``checkpoint``/``checkpoint_every``: the epochs nearest every ``checkpoint_every``
    seconds (at least one epoch) are also written to the file (atomically); a run started with a checkpoint of
    the same scenario, duration, seed, epoch and version resumes from it. A checkpoint of another run or a
    corrupt one raises :class:`CheckpointError`. SIGINT or SIGTERM (KeyboardInterrupt) stops at the next output
    step, writes the latest epoch as checkpoint if one is configured and returns the trace so far with
    ``metadata["partial"] = True``. ``on_plan(epoch_s, every_s)`` is told the epoch and checkpoint interval.
    """
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(Path(scenario))
    if duration is not None:
        if not duration > 0:
            raise ValueError(f"duration must be positive (got {duration!r})")
        sc = sc.with_run(duration=float(duration))
    if epoch is not None and not (epoch > 0 and epoch < float("inf")):
        raise ValueError(f"epoch must be positive (got {epoch!r})")
    n_warm = int(round(sc.run.warmup / sc.run.dt_out))
    n_out = int(round(sc.run.duration / sc.run.dt_out)) + 1
    _check_trace_size(sc, n_out)
    total = (n_warm + n_out) * sc.run.dt_out
    ck_path = Path(checkpoint) if checkpoint else None
    if ck_path is not None:  # a write cut short by SIGKILL leaves its temporary file: never read, removed here
        for stale in ck_path.parent.glob(f".{ck_path.name}.*.tmp"):
            stale.unlink(missing_ok=True)
    seed_used = sc.run.seed if seed is None else int(seed)
    t0 = time.perf_counter()
    resumed = False
    _load_recorder_kernel(sc, seed)
    intr = _Interrupts()
    with intr.deferred():
        scen = sc.to_dict()
        scen["run"] = {k: v for k, v in scen["run"].items() if k not in ("duration", "seed")}  # compared on their own
        key = {"scenario": scen, "duration": n_out * sc.run.dt_out, "seed": seed_used, "epoch": epoch,
               "version": package_version()}
        if ck_path is not None and ck_path.exists():
            scene, rec, k0, e_out = _read_checkpoint(ck_path, key, n_out)
            every = _every(e_out, sc.run.dt_out, checkpoint_every)
            resumed = True
        else:
            scene = Scene(sc, seed)
            _warm_up(scene, n_warm, intr)
            rec = Recorder(scene, n_out)
            k0 = 0
            ep = epoch if epoch is not None else default_epoch(scene, sc.run.dt_out)
            e_out = max(1, int(round(ep / sc.run.dt_out)))
            every = _every(e_out, sc.run.dt_out, checkpoint_every)
        if on_plan is not None:
            on_plan(e_out * sc.run.dt_out, every * sc.run.dt_out if every else None)
        n_sub = scene.n_sub
        partial = False
        k = k0
        last = None  # (scene bytes, recorder state) of the latest epoch, kept for a checkpoint on interrupt
        saved_k = k0 if resumed else 0
        round_trip_s = 0.0
        try:
            while k < n_out:
                intr.check()  # the one place a signal takes effect: here k == rec.k
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
                # an epoch: continue from the restored copy, as a resumed run will (not before the last sample, which
                # no step follows: that round trip was wasted, and it woke every sleeping grain the last sample reads)
                if k % e_out == 0 and k + 1 < n_out:
                    t_rt = time.perf_counter()
                    scene_bytes = pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL)
                    rs = _rec_state(rec, k)
                    if ck_path is not None and every:
                        if k % every == 0:
                            _write_checkpoint(ck_path, key, e_out, scene_bytes, rs)
                            saved_k = k
                        else:
                            last = (scene_bytes, rs)
                    scene, rec = _rebind(scene_bytes, rs, n_out)
                    round_trip_s += time.perf_counter() - t_rt
        except KeyboardInterrupt:
            if rec.k == 0:
                raise  # nothing recorded yet
            partial = True
            if ck_path is not None and every and last is not None and last[1]["k"] > saved_k:
                _write_checkpoint(ck_path, key, e_out, *last)  # rows below the epoch are unchanged since
                saved_k = last[1]["k"]
    wall = time.perf_counter() - t0
    if progress is not None and not partial:
        progress(total, total)
    meta = {
        "producer": "engine_sim", "scenario": sc.to_dict(), "seed": scene.seed, "version": package_version(),
        "wall_s": wall, "steps": scene.steps, "us_per_step": wall / max(scene.steps, 1) * 1e6,
        "steady_velocity_law": sc.steady_velocity, "drive_force": sc.drive_force if sc.drive_part.constant_force else None,
        "segments_generated": sum(t.generated for t in scene.tracks),
        "segments_live": sum(len(t.segments) for t in scene.tracks),
        "partial": partial, "resumed_from_checkpoint": resumed, "scene": describe(sc),
        "epoch_s": e_out * sc.run.dt_out, "epoch_given": epoch is not None, "round_trips_s": round_trip_s,
        "checkpoint_every_s": every * sc.run.dt_out if every else None,
    }
    if partial:
        meta["interrupted_by"] = signal.Signals(intr.signum).name if intr.signum else "KeyboardInterrupt"
        meta["checkpoint_at_s"] = saved_k * sc.run.dt_out if (ck_path is not None and saved_k) else None
    meta.update(scene.wear.run_metadata())
    return rec.trace(meta)
