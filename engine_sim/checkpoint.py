"""A run's epochs and checkpoint files.

At every epoch (:mod:`engine_sim.epoch`) a run pickles its scene and continues from the restored copy with a
recorder rebound to it (:func:`round_trip`): a restored pymunk space is not an exact continuation of the live one,
so every run takes this path, and a run resumed from a file takes the same. :class:`Checkpoint` writes some of those
epochs to a file (atomically) and reads one back; a run without a file has a Checkpoint that writes nothing.
"""
from __future__ import annotations

import pickle
from pathlib import Path

from frictionnoise.base import atomic_write

from .record import Recorder

__all__ = ["CheckpointError", "Checkpoint", "recorder_state", "restore", "round_trip", "checkpoint_interval"]

_REC_ARRAYS = ("t", "out", "pad_force", "n_contact", "p_state", "p_force", "recycle", "micro_force")
# the layout of a checkpoint file: the scene always holds a grains part, the recorder its micro-pad forces and the
# momentum columns; a shaken velocity drive's anchor is a dynamic body riding the inertial field
_FORMAT = "frictionnoise-checkpoint-6"
_WHAT = "delete it (or write to another -o folder) and run again"


class CheckpointError(ValueError):
    """A checkpoint file that is corrupt or belongs to another run; the message says which and what to do."""


def recorder_state(rec, k) -> dict:
    """The recorder's state at sample k: rows below k of its buffers (by reference) and its small mutable parts."""
    if rec.k != k:
        raise RuntimeError(f"epoch at an inconsistent point (loop at sample {k}, recorder at {rec.k})")
    return {"k": k, "x0": rec.x0, "part": rec.grain_table.copy(), "arrays": {a: getattr(rec, a) for a in _REC_ARRAYS}}


def restore(scene_bytes: bytes, rs: dict, n_out: int):
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
    rec.grain_table, rec.k, rec.x0 = rs["part"].copy(), k, rs["x0"]
    return scene, rec


def round_trip(scene, rec, k: int, n_out: int, checkpoint: "Checkpoint"):
    """The epoch at sample k: the scene pickled, offered to ``checkpoint``, and the run's (scene, recorder) continued
    from the restored copy."""
    scene_bytes = pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL)
    rs = recorder_state(rec, k)
    checkpoint.at_epoch(scene_bytes, rs)
    return restore(scene_bytes, rs, n_out)


def checkpoint_interval(e_out: int, dt_out: float, checkpoint_every: float | None) -> int | None:
    """The checkpoint interval in output steps: the whole number of epochs nearest ``checkpoint_every``, at
    least one; None without ``checkpoint_every``."""
    if not checkpoint_every:
        return None
    return e_out * max(1, int(round(checkpoint_every / (e_out * dt_out))))


class Checkpoint:
    """The checkpoint file of one run (``path`` None: none). ``key`` identifies the run (scenario, duration, seed,
    epoch, version); a file of another run is refused. After :meth:`plan`, :meth:`at_epoch` writes the epochs that
    fall on the interval and keeps the latest other one, which :meth:`on_interrupt` writes."""

    def __init__(self, path, key: dict, checkpoint_every: float | None):
        self.path = Path(path) if path else None
        self.key, self.checkpoint_every = key, checkpoint_every
        self.every = None  # output steps between writes
        self.e_out = None
        self.saved_k = 0  # the sample of the latest epoch in the file
        self._last = None  # (scene bytes, recorder state) of the latest epoch not written

    def remove_partial_writes(self):
        """A write cut short by SIGKILL leaves its temporary file: never read, removed here."""
        if self.path is not None:
            for stale in self.path.parent.glob(f".{self.path.name}.*.tmp"):
                stale.unlink(missing_ok=True)

    def plan(self, e_out: int, dt_out: float):
        """Fix the epoch (output steps) and derive the interval of writes."""
        self.e_out = e_out
        self.every = checkpoint_interval(e_out, dt_out, self.checkpoint_every)

    def resume(self, n_out: int):
        """(scene, recorder, sample, epoch outputs) from the file, or None if there is none to resume from."""
        if self.path is None or not self.path.exists():
            return None
        path = self.path
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
            raise CheckpointError(f"{path}: not a readable checkpoint ({type(e).__name__}: {e}); {_WHAT}") from None
        old = saved.get("key", {})
        if old != self.key:
            diff = [f for f in self.key if old.get(f) != self.key[f]]
            raise CheckpointError(f"{path}: checkpoint of another run ({', '.join(diff) or 'key'} "
                                  f"{'differs' if len(diff) == 1 else 'differ'}); {_WHAT}")
        try:
            scene, rec = restore(saved["scene"], rs, n_out)
        except Exception as e:
            raise CheckpointError(f"{path}: not a readable checkpoint ({type(e).__name__}: {e}); {_WHAT}") from None
        self.saved_k = rs["k"]
        return scene, rec, rs["k"], e_out

    @property
    def writes(self) -> bool:
        return self.path is not None and bool(self.every)

    def at_epoch(self, scene_bytes: bytes, rs: dict):
        """An epoch's state: written if it falls on the interval, else kept for :meth:`on_interrupt`."""
        if not self.writes:
            return
        if rs["k"] % self.every == 0:
            self._write(scene_bytes, rs)
        else:
            self._last = (scene_bytes, rs)

    def on_interrupt(self):
        """Write the latest epoch if it is newer than the file's (rows below it are unchanged since)."""
        if self.writes and self._last is not None and self._last[1]["k"] > self.saved_k:
            self._write(*self._last)

    def _write(self, scene_bytes: bytes, rs: dict):
        k = rs["k"]
        rec = {"k": k, "x0": rs["x0"], "part": rs["part"], "arrays": {a: v[:k] for a, v in rs["arrays"].items()}}
        obj = {"format": _FORMAT, "key": self.key, "epoch_outputs": self.e_out, "scene": scene_bytes, "rec": rec}
        atomic_write(self.path, pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))  # created 0666 less the umask
        self.saved_k = k
