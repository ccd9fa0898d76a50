"""The strokes of a friction-force record: where a reciprocating test reverses, what is cut at each reversal, and
the stroke-averaged spectrum.

Tribometers run at constant speed and record the friction force. A reciprocating test reverses every stroke;
the reversal (stop, stick, re-start) is a transient that does not belong to the sliding noise, so the record is
split into strokes, a stated length is cut at both ends of each, each stroke is detrended by its own line, and
the spectra of the strokes are averaged (:func:`compare.analysis.spectra.average_spectra`). A continuous
(pin-on-disc) record is one stroke.

Strokes are found, in this order of preference, from a direction column (runs of equal value), from the
position (the velocity's reversals, with hysteresis: a turn counts once the position has come back from its
extreme by 2 % of the range, and by ten times its noise; an amplitude that ramps up and down is followed) or,
for force-only files,
from the sign of the friction force (with hysteresis at half its median magnitude: the friction force opposes
the motion). These are row labels, whatever the time stamps; the cut and the stroke lengths are times. In a record
whose time stamps break (:mod:`compare.analysis.timeline`) a stroke's duration is read on its clock (a gap inside
a stroke is part of it), and the stroke is split where the time line breaks: :func:`stroke_pieces`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .spectra import Spectrum, average_spectra, series_spectrum
from .timeline import Segment

__all__ = ["Strokes", "find_strokes", "stroke_spectrum", "stroke_pieces", "elapsed"]

_KEEP_FRACTION = 0.8  # a stroke shorter than this share of the median (after the cut) is partial: dropped
_DEFAULT_CUT = 0.1  # share of the median stroke duration cut at each end, unless a cut is given
_MIN_STROKE_ROWS = 64  # a stroke with fewer rows after the cut carries no spectrum


@dataclass(frozen=True)
class Strokes:
    """Stroke split of a record. ``segments`` are the (start, stop) row ranges used, after the cut and trimmed to
    one common duration ``used_s``; ``numbers`` the stroke number (1-based, counting every stroke found) of each."""

    method: str
    found: int
    segments: list
    dropped: list  # (stroke number, reason)
    cut_s: float
    duration_s: float  # median stroke duration before the cut
    used_s: float  # common length of every used stroke after the cut
    numbers: tuple = ()


def _runs(labels: np.ndarray) -> np.ndarray:
    """Boundaries (including 0 and len) of runs of equal labels."""
    change = np.flatnonzero(labels[1:] != labels[:-1]) + 1
    return np.concatenate([[0], change, [len(labels)]])


def _hysteresis(y: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """+1 after y rose above ``hi``, -1 after it fell below ``lo``; before the first crossing, the first state."""
    s = np.where(y > hi, 1, np.where(y < lo, -1, 0))
    idx = np.where(s != 0, np.arange(len(s)), 0)
    np.maximum.accumulate(idx, out=idx)
    state = s[idx]
    first = np.flatnonzero(s)
    if first.size:
        state[: first[0]] = s[first[0]]
    return state


def _reversal_distance(x: np.ndarray) -> float:
    """How far (file units) the position must come back from an extreme for the turn to count as a reversal: 2 %
    of its range, and at least ten times its noise (the noise from the second difference, which a smooth motion
    leaves near zero: for white noise of rms s its rms is sqrt(6) s)."""
    p1, p99 = np.percentile(x, [1, 99])
    d2 = np.diff(x, 2)
    noise = 1.4826 * float(np.median(np.abs(d2 - np.median(d2)))) / np.sqrt(6.0) if d2.size else 0.0
    return max(0.02 * float(p99 - p1), 10.0 * noise)


def _position_boundaries(x: np.ndarray) -> np.ndarray:
    """Turning points of a back-and-forth position: the velocity's reversals, with hysteresis. Walking the
    record, the extreme reached in the current direction is kept; once the position has come back from it by the
    reversal distance (:func:`_reversal_distance`) the extreme is a turning point and the direction flips. Strokes
    of any amplitude above that distance are found (an amplitude that ramps up and down, too), and no stroke holds
    a reversal."""
    h = _reversal_distance(x)
    bounds = [0]
    ext_i, state = 0, 0  # state: +1 moving up, -1 moving down, 0 not yet known
    lo_i = hi_i = 0
    for i in range(1, x.size):
        v = x[i]
        if state >= 0 and v > x[hi_i]:
            hi_i = i
        if state <= 0 and v < x[lo_i]:
            lo_i = i
        if state == 0:
            if x[hi_i] - v >= h and hi_i > 0:
                state, ext_i, lo_i = -1, hi_i, i
                bounds.append(hi_i)
            elif v - x[lo_i] >= h and lo_i > 0:
                state, ext_i, hi_i = 1, lo_i, i
                bounds.append(lo_i)
            elif x[hi_i] - x[0] >= h:
                state = 1
            elif x[0] - x[lo_i] >= h:
                state = -1
        elif state > 0 and x[hi_i] - v >= h:
            bounds.append(hi_i)
            state, lo_i = -1, i
        elif state < 0 and v - x[lo_i] >= h:
            bounds.append(lo_i)
            state, hi_i = 1, i
    bounds.append(x.size)
    return np.unique(np.asarray(bounds))


def _monotone(x: np.ndarray) -> bool:
    d = np.diff(x)
    return bool(np.all(d >= 0) or np.all(d <= 0)) or abs(x[-1] - x[0]) > 0.8 * np.ptp(x)


def _boundaries(data) -> tuple:
    """(method, row boundaries of the strokes) of a record (see the module docstring)."""
    n = len(data.t)
    if data.direction is not None:
        method, bounds = "direction column", _runs(np.asarray(data.direction))
    elif data.x is not None and np.ptp(data.x) > 0 and not _monotone(data.x):
        method, bounds = "sign of the position's derivative", _position_boundaries(np.asarray(data.x))
    elif data.F is not None:
        h = 0.5 * float(np.median(np.abs(data.F)))
        state = _hysteresis(np.asarray(data.F), -h, h)
        method, bounds = "sign of the friction force", _runs(state)
    else:
        method, bounds = "continuous", np.array([0, n])  # nothing to split by
    if len(bounds) <= 2:
        method = f"one stroke: no reversal in the {method}" if method != "continuous" else "one stroke"
        bounds = np.array([0, n])
    return method, bounds


def elapsed(t) -> np.ndarray:
    """The clock of a record as written: the stamps ``t`` (s), with every backward step counted as no time, so
    that it never decreases (equal to ``t`` when the stamps never step back)."""
    t = np.asarray(t, float)
    back = np.concatenate([[0.0], np.cumsum(np.maximum(-np.diff(t), 0.0))])
    return t + back


def _cut_rows(bounds, cut, dt):
    """Uniform stamps: (inner row ranges, cut in s) with ``round(cut / dt)`` rows removed at each end."""
    c = int(round(cut / dt))
    return [(int(a) + c, int(b) - c) for a, b in zip(bounds[:-1], bounds[1:])], c * dt


def _cut_times(bounds, cut, tau, tol):
    """Stamps that break: the inner row ranges of the strokes, ``cut`` seconds of clock removed at each end."""
    ext = np.append(tau, tau[-1] + tol * 2)
    return [(int(np.searchsorted(tau, ext[a] + cut - tol)), int(np.searchsorted(tau, ext[b] - cut - tol)))
            for a, b in zip(bounds[:-1], bounds[1:])]


def find_strokes(data, *, cut: float | None = None) -> Strokes:
    """Split a record into strokes (see the module docstring); ``cut`` seconds are removed at both ends.

    ``data`` has ``t`` (s), ``F`` (N) and optionally ``x``, ``direction`` and ``segmented`` (stamps that break:
    durations and the cut are read on :func:`elapsed`, a gap inside a stroke counts as part of it). A stroke
    shorter than 80 % of the median after the cut (or under 64 rows) is partial and dropped; every used stroke is
    trimmed to the shortest used one.
    """
    t = np.asarray(data.t, float)
    n = len(t)
    method, bounds = _boundaries(data)
    broken = bool(getattr(data, "segmented", False))
    if broken:
        tau = elapsed(t)
        steps = np.diff(tau)
        tol = 0.5 * float(np.min(steps[steps > 0]))
        ext = np.append(tau, tau[-1] + 2 * tol)
        lengths = ext[bounds[1:]] - ext[bounds[:-1]]
    else:
        dt = float(t[1] - t[0])
        lengths = np.diff(bounds) * dt
    found = len(lengths)
    dur = float(np.median(lengths))
    cut_s = (0.0 if found == 1 else _DEFAULT_CUT * dur) if cut is None else float(cut)
    if cut_s < 0:
        raise ValueError(f"cut must be >= 0 s (got {cut_s})")
    if broken:
        inner = _cut_times(bounds, cut_s, tau, tol)
        span = [max(float(ext[b] - ext[a]), 0.0) if b > a else 0.0 for a, b in inner]
    else:
        inner, cut_s = _cut_rows(bounds, cut_s, dt)
        span = [max(b - a, 0) * dt for a, b in inner]
    med = float(np.median(span))
    kept, numbers, dropped = [], [], []
    for i, ((a, b), s) in enumerate(zip(inner, span), start=1):
        if s < _KEEP_FRACTION * med or b - a < _MIN_STROKE_ROWS:
            dropped.append((i, f"partial: {s:.4g} s after the cut, median {med:.4g} s"))
        else:
            kept.append((a, b))
            numbers.append(i)
    if not kept:
        raise ValueError(f"no stroke is long enough after cutting {cut_s:.4g} s at each end "
                         f"({found} strokes of median {dur:.4g} s)")
    used = min(s for (a, b), s in zip(inner, span) if (a, b) in kept)
    if broken:
        segs = [(a, int(np.searchsorted(tau, tau[a] + used - tol))) for a, _ in kept]
    else:
        L = int(round(used / dt))
        segs = [(a, a + L) for a, _ in kept]
    return Strokes(method=method, found=found, segments=segs, dropped=dropped, cut_s=cut_s,
                   duration_s=dur, used_s=used, numbers=tuple(numbers))


def stroke_spectrum(t, y, strokes: Strokes, quantity: str, unit: str, prewhiten, nperseg) -> Spectrum:
    """Spectra of every stroke of a uniformly sampled record (each detrended by its own line, same pre-whitening
    order), averaged.

    By default each stroke is one Welch segment (the longest resolved wavelength; averaging comes from the
    strokes); a continuous record keeps the usual segment length.
    """
    a0, b0 = strokes.segments[0]
    if nperseg is None and len(strokes.segments) > 1:
        nperseg = b0 - a0  # one Hann segment per stroke: the strokes supply the averaging
    first = series_spectrum(t[a0:b0], y[a0:b0], quantity=quantity, unit=unit, detrend="linear",
                            prewhiten=prewhiten, nperseg=nperseg, name=quantity)
    k = first.provenance["prewhiten_order"]
    specs = [first] + [series_spectrum(t[a:b], y[a:b], quantity=quantity, unit=unit, detrend="linear",
                                       prewhiten=k, nperseg=first.provenance["nperseg"], name=quantity)
                       for a, b in strokes.segments[1:]]
    return specs[0] if len(specs) == 1 else average_spectra(specs, label="strokes")


def stroke_pieces(strokes: Strokes, timeline) -> list:
    """The uniform pieces of the used strokes of a record whose time stamps break: every used stroke intersected
    with every usable segment of ``timeline`` (compare.analysis.timeline.Timeline).

    Returns
    -------
    list of (int, Segment)
        The stroke number and the piece (rows ``start`` to ``stop``, exclusive, at its segment's step ``dt``),
        in row order; pieces of fewer than two rows are left out.
    """
    out = []
    for num, (a, b) in zip(strokes.numbers or range(1, len(strokes.segments) + 1), strokes.segments):
        for s in timeline.usable():
            lo, hi = max(a, s.start), min(b, s.stop)
            if hi - lo >= 2:
                out.append((num, Segment(lo, hi, s.dt, s.spread)))
    return out
