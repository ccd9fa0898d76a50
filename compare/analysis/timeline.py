"""The time line of a measured record as a recorder wrote it: uniform stretches (segments), and where they break.

Recorders change their sample rate within a run, drop samples and, now and then, repeat a time stamp or step back
(a clock reset, two buffers written in the wrong order). :func:`find_segments` walks the time stamps once and
splits the record where the step leaves its segment's own step by more than the jitter allowed: a **gap** (one long
step, then the old step again: samples missing), a **rate change** (a new step that lasts), a **repeated** stamp
(step 0), a **backward** one (step < 0) or one **short step** (then the old step again). One step within half a
step of the rate, the rate kept after it, is the clock's jitter (a logger's step wandering by 20 %), not a break:
no sample is missing. Each event is reported with its row, its line's time and the stamp before it, and its size;
the stretches between are analysed on their own and together (:mod:`compare.analysis.segments`).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["TimeEvent", "Segment", "Timeline", "find_segments", "JITTER", "MIN_ROWS"]

JITTER = 0.25  # a step within 25 % of its segment's step is jitter of the same rate, resampled inside the segment
MIN_ROWS = 64  # a segment shorter than this carries no spectrum of its own
_LOOK = 8  # steps looked at to set a segment's step and to tell a gap from a rate change


@dataclass(frozen=True)
class TimeEvent:
    """Where the time line breaks. kind: "gap", "rate change", "repeated", "backward", "short step" (or "block": a
    new block of a multi-block export, set by its reader); row: index
    of the sample after the break (0-based, into the record's rows); line: its line in the file (if known);
    time (s): the stamp before the break; size (s): the step taken (gap, repeated, backward, short step: the jump;
    rate change: the new step); detail: one phrase for a report; time_after (s): the stamp of the sample after
    the break, the one on ``line``."""

    kind: str
    row: int
    line: int | None
    time: float
    size: float
    detail: str
    time_after: float = float("nan")

    def describe(self) -> str:
        """``line L at t = <stamp on line L>, after t = <stamp before>: kind (detail)``: the time printed with the
        line is that line's own."""
        where = f"line {self.line}" if self.line is not None else f"row {self.row + 1}"
        return f"{where} at t = {self.time_after:.6g} s, after t = {self.time:.6g} s: {self.kind} ({self.detail})"


@dataclass(frozen=True)
class Segment:
    """Rows ``start`` to ``stop`` (exclusive) sampled at one rate: step ``dt`` (s, the median step), ``spread``
    the largest relative deviation of a step from it."""

    start: int
    stop: int
    dt: float
    spread: float

    @property
    def n(self) -> int:
        return self.stop - self.start


@dataclass(frozen=True)
class Timeline:
    """Segments of a record (every row belongs to one), the events between them, and the segments too short to
    analyse on their own (indices into ``segments``)."""

    segments: tuple
    events: tuple
    short: tuple = field(default=())

    @property
    def uniform(self) -> bool:
        return not self.events

    def usable(self) -> list:
        return [s for i, s in enumerate(self.segments) if i not in self.short]

    def summary(self) -> dict:
        return {"segments": [{"start_row": s.start, "stop_row": s.stop, "n": s.n, "dt_s": s.dt, "spread": s.spread,
                              "used": i not in self.short} for i, s in enumerate(self.segments)],
                "events": [{"kind": e.kind, "row": e.row, "line": e.line, "time_s": e.time,
                            "time_after_s": e.time_after, "size_s": e.size,
                            "detail": e.detail} for e in self.events]}


def _typical(steps: np.ndarray) -> float:
    pos = steps[steps > 0]
    return float(np.median(pos)) if pos.size else float("nan")


def _jitter(step: float, ref: float, after: np.ndarray, jitter: float) -> bool:
    """Whether one step off its segment's rate is the clock's jitter, not a break: longer than 0.6 ``ref`` and
    shorter than 1.5 ``ref`` (no sample missing: a gap starts at 1.5, where rounding counts one; a half step is a
    sample too many, a short step), and the steps after it keep the rate (their median within ``jitter``). A
    logger wandering by +-20 % steps between 0.67 and 1.5 times its neighbours' step."""
    if not (step > 0 and np.isfinite(ref) and 0.6 < step / ref < 1.5):
        return False
    nxt = _typical(after)
    return bool(np.isfinite(nxt) and abs(nxt / ref - 1.0) <= jitter)


def find_segments(t, lines=None, *, jitter: float = JITTER, min_rows: int = MIN_ROWS) -> Timeline:
    """Split time stamps ``t`` (s, in file order) into uniformly sampled segments.

    Parameters
    ----------
    t : array_like
        Time stamps as written (not sorted).
    lines : array_like of int, optional
        The file line of each row, for the report.
    jitter : float
        Relative step deviation still counted as the same rate.
    min_rows : int
        Segments with fewer rows are listed in ``short``.

    Returns
    -------
    Timeline
        A segment ends before the first step that is not within ``jitter`` of its step (the median of its first
        steps). That step is a *repeated* stamp (0), a *backward* one (< 0), a *gap* if the steps after it return to
        the segment's step (the samples missing are counted), else a *rate change* to the median of the steps after
        it.
    """
    t = np.asarray(t, dtype=float)
    n = t.size
    d = np.diff(t)
    line = (lambda i: int(lines[i])) if lines is not None else (lambda i: None)
    segments, events = [], []
    s = 0
    while s < n:
        ref = _typical(d[s:s + _LOOK])
        i = s
        while i < n - 1:
            step = d[i]
            if step > 0 and np.isfinite(ref) and abs(step / ref - 1.0) <= jitter:
                i += 1
                continue
            if not np.isfinite(ref) and step > 0:  # a one-row segment so far: take this step as its rate
                ref = step
                i += 1
                continue
            if _jitter(step, ref, d[i + 1:i + 1 + _LOOK], jitter):
                i += 1
                continue
            break
        stop = i + 1
        seg_steps = d[s:i]
        dt = _typical(seg_steps) if seg_steps.size else float("nan")
        spread = float(np.max(np.abs(seg_steps / dt - 1.0))) if seg_steps.size else 0.0
        segments.append(Segment(s, stop, dt, spread))
        if stop >= n:
            break
        step = d[i]
        after = _typical(d[stop:stop + _LOOK])
        if step == 0:
            ev = TimeEvent("repeated", stop, line(stop), float(t[i]), 0.0, "the same time stamp twice")
        elif step < 0:
            ev = TimeEvent("backward", stop, line(stop), float(t[i]), float(step),
                           f"the clock steps back by {-step:.4g} s")
        elif np.isfinite(after) and np.isfinite(ref) and abs(after / ref - 1.0) <= jitter and step > ref:
            missing = int(round(step / ref)) - 1
            ev = TimeEvent("gap", stop, line(stop), float(t[i]), float(step),
                           f"a step of {step:.4g} s where {ref:.4g} s was the rule: about {missing} "
                           f"sample{'' if missing == 1 else 's'} missing")
        elif np.isfinite(after) and np.isfinite(ref) and abs(after / ref - 1.0) <= jitter:
            ev = TimeEvent("short step", stop, line(stop), float(t[i]), float(step),
                           f"one step of {step:.4g} s where {ref:.4g} s was the rule")
        else:
            new = after if np.isfinite(after) else step
            ev = TimeEvent("rate change", stop, line(stop), float(t[i]), float(new),
                           f"step {ref:.4g} s -> {new:.4g} s ({1 / ref:.4g} -> {1 / new:.4g} Hz)")
        events.append(replace(ev, time_after=float(t[stop])))
        s = stop
    short = tuple(k for k, seg in enumerate(segments) if seg.n < min_rows)
    return Timeline(tuple(segments), tuple(events), short)
