"""engine_sim.run: simulate a scenario and record it (SI trace)."""
from __future__ import annotations

import math
import os
import signal
import threading
import time
from contextlib import contextmanager
from pathlib import Path

from frictionnoise.base import check_seconds, check_seed, package_version

from .checkpoint import Checkpoint, CheckpointError, round_trip
from .epoch import default_epoch
from .loop import MAINTAIN_EVERY, Loop, warm_up
from .record import EngineTrace, Recorder
from .regime import LOST_CONTACT_S, PARTIAL_LOSS_FRACTION
from .sample_layout import F_N
from .scenario import Scenario, load_scenario
from .scene import Scene, describe

__all__ = ["run", "CheckpointError", "TraceSizeError", "warm_up", "MAINTAIN_EVERY"]

_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Interrupts:
    """SIGINT and SIGTERM deferred to the loop's consistent points (between output steps, where the loop's counter
    and the recorder's agree and no pymunk step or round trip is half done). A KeyboardInterrupt raised anywhere
    else could leave a checkpoint whose counters disagree by one sample, and resuming from it would write past the
    recorder's buffers."""

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
    and two entries per wear particle) exceed half the memory available now, with one line that says what to do
    rather than numpy's allocation error."""
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


def _load_recorder_kernel(sc, seed):
    """Load (or compile) the recorder's numba kernel before signals are deferred: the first sample of a process
    loads it (under a second from numba's cache, about 9 s compiling in a fresh clone), and a deferred Ctrl-C
    would wait for that load. A one-sample Recorder on a throwaway Scene (a few hundredths of a second), once per
    process, outside the deferral, where a Ctrl-C interrupts at once."""
    from .reduction import reduce_sample
    if not reduce_sample.signatures:
        Recorder(Scene(sc, seed), 1).sample()


def _run_key(sc, n_out: int, seed: int, epoch) -> dict:
    """What identifies a run for its checkpoint: scenario (without duration and seed, compared on their own),
    duration, seed, epoch and version."""
    scen = sc.to_dict()
    scen["run"] = {k: v for k, v in scen["run"].items() if k not in ("duration", "seed")}
    return {"scenario": scen, "duration": n_out * sc.run.dt_out, "seed": seed, "epoch": epoch,
            "version": package_version()}


def _start(sc, seed, n_warm: int, n_out: int, epoch, interrupts):
    """A fresh scene warmed up, its recorder and its epoch in output steps."""
    scene = Scene(sc, seed)
    warm_up(scene, n_warm, interrupts)
    rec = Recorder(scene, n_out)
    ep = epoch if epoch is not None else default_epoch(scene, sc.run.dt_out)
    return scene, rec, 0, max(1, int(round(ep / sc.run.dt_out)))


def _record(scene, rec, k: int, n_out: int, e_out: int, interrupts, checkpoint, report=None):
    """The recorded loop (:class:`engine_sim.loop.Loop`) from sample k; at every epoch the round trip
    (:func:`engine_sim.checkpoint.round_trip`). Returns (scene, recorder, stop, round-trip wall seconds); stop:
    None (the whole run), "interrupt" (stopped by SIGINT/SIGTERM, the latest epoch offered to the checkpoint) or
    "contact_lost" (:class:`ContactWatch`)."""
    # every maintenance: a log's progress lines need fresh figures
    loop = Loop(scene, rec, n_out, k, on_maintain=report)
    round_trip_s = 0.0
    watch = ContactWatch(scene.sc.run.dt_out, scene.sc.pads.N)
    try:
        while loop.k < n_out:
            interrupts.check()  # the one place a signal takes effect: here loop.k == rec.k
            loop.step()
            k = loop.k
            r = loop.recorder
            stop = watch.see(r.n_contact[r.k - 1], r.out[r.k - 1, F_N], r.k - 1)
            if stop is not None:
                return loop.scene, loop.recorder, stop, round_trip_s, watch
            # an epoch: continue from the restored copy, as a resumed run will (not before the last sample, which no
            # step follows: that round trip would be wasted, and it would wake every sleeping grain the last sample
            # reads)
            if k % e_out == 0 and k + 1 < n_out:
                t_rt = time.perf_counter()
                loop.scene, loop.recorder = round_trip(loop.scene, loop.recorder, k, n_out, checkpoint)
                round_trip_s += time.perf_counter() - t_rt
    except KeyboardInterrupt:
        if loop.recorder.k == 0:
            raise  # nothing recorded yet
        checkpoint.on_interrupt()
        return loop.scene, loop.recorder, "interrupt", round_trip_s, watch
    return loop.scene, loop.recorder, None, round_trip_s, watch


class ContactWatch:
    """Watches the recorded samples for a scene that has left its regime, over runs of more than
    :data:`engine_sim.regime.LOST_CONTACT_S` of recorded samples in a row:

    - no pad on its track: the run has lost its load (the block lifted off, or every pad thrown off its track); it
      stops, ``"contact_lost"``;
    - the summed normal force F_n below zero: the pads are pushed through their tracks (pymunk resolves an overlap
      beyond its slop from whichever side is nearer); it stops, ``"pushed_through"``;
    - at least :data:`engine_sim.regime.PARTIAL_LOSS_FRACTION` of the pads off their tracks while others keep
      theirs: the load rests on fewer pads than the scene has; the run goes on and :attr:`warnings` says when
      (once).

    :meth:`see` takes each sample and returns the stop, or None; :attr:`start` holds the first sample of the run
    that stopped it."""

    def __init__(self, dt_out: float, n_pads: int = 0):
        self.dt_out = dt_out
        self.limit = max(1, int(round(LOST_CONTACT_S / dt_out)))
        self.n_pads = n_pads
        self.partial_at = max(1, math.ceil(PARTIAL_LOSS_FRACTION * n_pads))
        self.runs = {"contact_lost": 0, "pushed_through": 0, "partial": 0}
        self.start = {}
        self.warnings = []

    def _count(self, key, hit: bool, k: int) -> bool:
        if hit:
            if self.runs[key] == 0:
                self.start[key] = k
            self.runs[key] += 1
        else:
            self.runs[key] = 0
        return self.runs[key] > self.limit

    def lost(self, n_contact) -> bool:
        """Whether no pad has touched its track for longer than the limit (one sample at a time)."""
        return self.see(n_contact, 1.0, 0) == "contact_lost"

    def see(self, n_contact, F_n, k: int):
        """Take sample ``k`` (its contact count and summed normal force, any unit); return the stop or None."""
        n_off = self.n_pads - int(n_contact)
        if self._count("contact_lost", n_contact == 0, k):
            return "contact_lost"
        if self._count("pushed_through", F_n < 0, k):
            return "pushed_through"
        if self._count("partial", 0 < n_contact and n_off >= self.partial_at, k) and not self.warnings:
            t0 = self.start["partial"] * self.dt_out
            self.warnings.append(f"{n_off} of {self.n_pads} pads lost contact with their tracks for longer than "
                                 f"{LOST_CONTACT_S:g} s from t = {t0:.3f} s (recorded time) while the others kept "
                                 "theirs: the load rested on fewer pads than the scene has")
        return None


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
    ``metadata["partial"] = True`` (``metadata["stopped_by"] = "interrupt"``). A run whose pads all leave their
    tracks for longer than :data:`engine_sim.regime.LOST_CONTACT_S` (0.1 s) of recorded time stops there and
    returns the trace so far, marked partial, ``metadata["stopped_by"] = "contact_lost"`` and
    ``metadata["stop_reason"]`` saying why, from when and the time it stopped (recorded time); one whose summed
    normal force stays negative as long (pads pushed through their tracks) likewise, ``"pushed_through"``. A run
    with a tenth of its pads or more off their tracks as long, while others keep theirs, goes on and says so in
    ``metadata["warnings"]`` (:class:`ContactWatch`).

    Parameters
    ----------
    scenario : str, pathlib.Path or Scenario
        The scenario file or object.
    duration : float, optional
        Recorded simulated time (Units: s); default the scenario's.
    seed : int, optional
        Seed of the substrate and the scene; default the scenario's.
    progress : callable, optional
        ``progress(t_done, t_total)`` (Units: s of simulated time).
    checkpoint : str, optional
        Checkpoint file to write to and resume from.
    checkpoint_every : float, optional
        Simulated seconds between checkpoints (Units: s; rounded to whole epochs, at least one).
    epoch : float, optional
        Simulated seconds between the state round trips (Units: s); default the scene's.
    on_plan : callable, optional
        ``on_plan(epoch_s, every_s)`` is told the epoch and checkpoint interval (Units: s).

    Returns
    -------
    EngineTrace
        The recorded arrays in SI units and the metadata.
    """
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(Path(scenario))
    if duration is not None:
        sc = sc.with_run(duration=check_seconds("duration", duration))
    if epoch is not None:
        check_seconds("epoch", epoch)
    dt_out = sc.run.dt_out
    n_warm = int(round(sc.run.warmup / dt_out))
    n_out = int(round(sc.run.duration / dt_out)) + 1
    _check_trace_size(sc, n_out)
    total = (n_warm + n_out) * dt_out
    seed_used = sc.run.seed if seed is None else check_seed("seed", seed)
    ckpt = Checkpoint(checkpoint, _run_key(sc, n_out, seed_used, epoch), checkpoint_every)
    ckpt.remove_partial_writes()
    t0 = time.perf_counter()
    _load_recorder_kernel(sc, seed)
    intr = _Interrupts()
    with intr.deferred():
        resumed = ckpt.resume(n_out)
        scene, rec, k0, e_out = resumed or _start(sc, seed, n_warm, n_out, epoch, intr)
        ckpt.plan(e_out, dt_out)
        if on_plan is not None:
            on_plan(e_out * dt_out, ckpt.every * dt_out if ckpt.every else None)
        report = None if progress is None else (lambda k: progress((n_warm + k) * dt_out, total))
        scene, rec, stop, round_trip_s, watch = _record(scene, rec, k0, n_out, e_out, intr, ckpt, report)
    partial = stop is not None
    wall = time.perf_counter() - t0
    if progress is not None and not partial:
        progress(total, total)
    meta = {
        "producer": "engine_sim", "scenario": sc.to_dict(), "seed": scene.seed, "version": package_version(),
        "wall_s": wall, "steps": scene.steps, "us_per_step": wall / max(scene.steps, 1) * 1e6,
        "steady_velocity_law": sc.steady_velocity, "drive_force": sc.drive_force if sc.drive_part.constant_force else None,
        "segments_generated": sum(t.generated for t in scene.tracks),
        "segments_live": sum(len(t.segments) for t in scene.tracks),
        "partial": partial, "resumed_from_checkpoint": resumed is not None, "scene": describe(sc),
        "epoch_s": e_out * dt_out, "epoch_given": epoch is not None, "round_trips_s": round_trip_s,
        "checkpoint_every_s": ckpt.every * dt_out if ckpt.every else None,
    }
    if stop in ("contact_lost", "pushed_through"):
        t_from = rec.t[watch.start[stop]] - rec.t[0]
        t_stop = rec.t[rec.k - 1] - rec.t[0]
        what = ("contact lost: no pad touched its track" if stop == "contact_lost" else
                "pads pushed through their tracks: the summed normal force F_n stayed negative")
        cause = ("the block lifted off, or its pads thrown off their tracks" if stop == "contact_lost" else
                 "the load or a vibration drove the pads through the track segments")
        meta["stopped_by"] = stop
        meta["stop_reason"] = (f"{what} from t = {t_from:.3f} s for longer than {LOST_CONTACT_S:g} s ({cause}); the "
                               f"run stopped at t = {t_stop:.3f} s (recorded time, after the warm-up)")
    elif partial:
        meta["stopped_by"] = "interrupt"
        meta["interrupted_by"] = signal.Signals(intr.signum).name if intr.signum else "KeyboardInterrupt"
        meta["checkpoint_at_s"] = ckpt.saved_k * dt_out if (ckpt.path is not None and ckpt.saved_k) else None
    meta["warnings"] = list(watch.warnings)
    meta.update(scene.wear.run_metadata())
    meta.update(scene.substrate.provenance())
    return rec.trace(meta)
