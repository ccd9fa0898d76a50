"""Spectra of a record sampled in uniform stretches (see :mod:`compare.analysis.timeline`): each segment on its
own, all of them together (their Welch estimates on one common window, averaged), or the whole record resampled
onto one grid behind a stated anti-alias filter; and the test that tells a periodic record (stick-slip, a sawtooth)
from a power law."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .estimators import default_nperseg
from .spectra import Spectrum, series_spectrum

__all__ = ["SegmentSpectra", "segment_spectra", "piece_spectra", "segment_fits", "resample_record", "line_power_flag", "with_line_flag",
           "LINE_FACTOR", "LINE_SHARE"]

LINE_FACTOR = 10.0  # an ordinate this many times its neighbourhood's median is a spectral line
LINE_SHARE = 0.5  # a band whose lines carry more than this share of its power is not a power law
_NEIGHBOURHOOD = 0.25  # decades either side over which the continuum (median) is taken


@dataclass(frozen=True)
class SegmentSpectra:
    """Per-segment spectra (``per_segment``: list of (Segment, Spectrum or None when it is shorter than one
    window)), their combination ``combined`` and what was done (``notes``)."""

    per_segment: list
    combined: Spectrum
    window_s: float
    used: tuple
    notes: tuple


def _uniform(t, y, dt):
    """A segment with jitter onto its own uniform grid (linear interpolation)."""
    n = int(math.floor((t[-1] - t[0]) / dt + 1e-9)) + 1
    tu = t[0] + dt * np.arange(n)
    return tu, np.interp(tu, t, y)


def segment_spectra(t, y, timeline, *, quantity: str, unit: str, detrend: str, name: str = "y") -> SegmentSpectra:
    """Spectra of each usable segment of ``timeline`` (compare.analysis.timeline.Timeline) and their combination:
    :func:`piece_spectra` of its usable segments with the default common window."""
    usable = timeline.usable()
    if not usable:
        raise ValueError(f"no segment has {min(s.n for s in timeline.segments)}+ rows of uniform sampling")
    return piece_spectra(t, y, usable, quantity=quantity, unit=unit, detrend=detrend, name=name)


def piece_spectra(t, y, pieces, *, quantity: str, unit: str, detrend: str, name: str = "y", span: float | None = None,
                  window: float | None = None, prewhiten="auto") -> SegmentSpectra:
    """Spectra of uniformly sampled pieces of a record, each on its own and all combined on one common window.

    Parameters
    ----------
    t, y : array_like
        The record's time stamps (s) as written, and its values.
    pieces : list of compare.analysis.timeline.Segment
        Row ranges sampled at one step each (a timeline's usable segments, or the strokes cut at its breaks).
    quantity, unit, detrend, name
        As in :func:`compare.analysis.spectra.series_spectrum`.
    span : float, optional
        The duration (s) a piece must cover to enter the combination with one window: the common window is ``span``
        less the ``k`` samples of the slowest piece that pre-whitening of order ``k`` takes (one Hann window per
        stroke, as :func:`compare.analysis.strokes.stroke_spectrum` uses on a uniform record).
    window : float, optional
        The common window T (s) itself. Default (neither given): the default Welch window of the longest piece.
    prewhiten : int or "auto"
        The pre-whitening order of every piece; "auto" picks it from the longest.

    Returns
    -------
    SegmentSpectra
        Every piece gets the pre-whitening order of the longest and its own spectrum at its default window (None
        below 64 rows). Combined: each piece at least one window long is estimated with a Hann window of the same
        duration T (``nperseg_i = T / dt_i``), so that all estimates share the frequency grid 2 pi j / T up to the
        lowest piece's Nyquist frequency; they are averaged weighted by their number of Welch windows, and the
        degrees of freedom add. Shorter pieces are named in ``notes``.
    """
    from .timeline import MIN_ROWS

    t = np.asarray(t, float)
    y = np.asarray(y, float)
    notes = []
    series = []
    for s in pieces:
        ts, ys = t[s.start:s.stop], y[s.start:s.stop]
        if s.spread > 1e-6:
            ts, ys = _uniform(ts, ys, s.dt)
            notes.append(f"rows {s.start + 1}-{s.stop}: steps deviate up to {100 * s.spread:.2g} % from {s.dt:.4g} s; "
                         "resampled onto that step by linear interpolation")
        series.append((s, ts, ys))
    longest = max(series, key=lambda r: r[1][-1] - r[1][0])
    k = prewhiten if prewhiten != "auto" else series_spectrum(
        longest[1], longest[2], quantity=quantity, unit=unit, detrend=detrend, name=name).provenance["prewhiten_order"]
    per = []
    for s, ts, ys in series:
        per.append((s, series_spectrum(ts, ys, quantity=quantity, unit=unit, detrend=detrend, prewhiten=k, name=name)
                    if ts.size >= max(MIN_ROWS, 8 + k) else None))
    if window is not None:
        T = float(window)
    elif span is not None:
        T = float(span) - k * max(s.dt for s, _, _ in series)
    else:
        T = min(default_nperseg(longest[1].size), longest[1].size - k) * longest[0].dt
    parts, used = [], []
    for idx, (s, ts, ys) in enumerate(series):
        nps = int(round(T / s.dt))
        if ts.size - k < nps:
            notes.append(f"rows {s.start + 1}-{s.stop} ({ts[-1] - ts[0]:.4g} s) are shorter than the common window "
                         f"{T:.4g} s: in the segment table, not in the combined spectrum")
            continue
        parts.append(series_spectrum(ts, ys, quantity=quantity, unit=unit, detrend=detrend, prewhiten=k,
                                     nperseg=nps, name=name))
        used.append(idx)
    if not parts:
        raise ValueError(f"no uniform piece covers the common window of {T:.4g} s (the longest: "
                         f"{longest[1][-1] - longest[1][0]:.4g} s, rows {longest[0].start + 1}-{longest[0].stop})")
    ref = max(parts, key=lambda p: p.provenance["dt"])  # the lowest Nyquist frequency sets the common grid
    w = ref.omega
    acc, weight, exact = np.zeros_like(w), 0.0, True
    for p in parts:
        m = np.searchsorted(p.omega, w[-1] * (1 + 1e-9), side="right")
        if m >= w.size and np.allclose(p.omega[:w.size], w, rtol=1e-9, atol=0):
            C = p.C[:w.size]
        else:  # window lengths not whole multiples of each other's steps: log-log interpolation onto the grid
            exact = False
            C = np.exp(np.interp(np.log(w), np.log(p.omega), np.log(np.maximum(p.C, 1e-300))))
        nw = p.provenance["n_segments"]
        acc += nw * C
        weight += nw
    C = acc / weight
    prov = dict(ref.provenance)
    prov["steps"] = list(ref.provenance["steps"][:-1]) + [
        f"{len(parts)} uniform segments, each estimated with a Hann window of {T:.4g} s "
        f"({', '.join(str(p.provenance['nperseg']) for p in parts)} samples), "
        f"pre-whitening order {k}; averaged weighted by their Welch windows ({int(weight)} in all)"
        + ("" if exact else "; estimates interpolated (log-log) onto the grid of the slowest segment")]
    prov.update(n_records=len(parts), n_segments=int(weight), segment_window_s=T,
                n_samples=int(sum(p.provenance["n_samples"] for p in parts)),
                duration=float(sum(p.provenance["duration"] for p in parts)),
                mean_velocity=float(sum(p.provenance["mean_velocity"] * p.provenance["duration"] for p in parts)
                                    / sum(p.provenance["duration"] for p in parts)))
    combined = replace(ref, C=C, dof=sum(p.dof for p in parts), provenance=prov, periodogram=None,
                       periodogram_domega=0.0, periodogram_count=1)
    return SegmentSpectra(per, combined, T, tuple(used), tuple(notes))


def resample_record(t, columns: dict, timeline, dt: float):
    """The record on one uniform grid of step ``dt`` (s): each segment sampled faster than ``dt`` is first low-passed
    by a zero-phase Butterworth filter of order 8 at 0.8 of the new Nyquist frequency (so nothing above it folds
    back), then every column is interpolated linearly onto the grid; gaps and the joins between segments are
    bridged by straight lines. Repeated and backward stamps: the rows that do not advance the time are dropped.

    Returns (t_uniform, columns_uniform, statement), the statement one line saying what was done."""
    from scipy import signal

    t = np.asarray(t, float)
    keep = np.ones(t.size, bool)
    top = -np.inf
    for i, v in enumerate(t):  # rows whose stamp does not pass every earlier one
        if v <= top:
            keep[i] = False
        else:
            top = v
    filtered = {}
    f_cut = 0.8 * 0.5 / dt
    lowpassed = 0
    for key, y in columns.items():
        y = np.asarray(y, float).copy()
        for s in timeline.segments:
            if s.n > 27 and np.isfinite(s.dt) and s.dt < dt * (1 - 1e-9):
                sos = signal.butter(8, f_cut, fs=1.0 / s.dt, output="sos")
                y[s.start:s.stop] = signal.sosfiltfilt(sos, y[s.start:s.stop])
                lowpassed += key == next(iter(columns))
        filtered[key] = y
    tk = t[keep]
    n = int(math.floor((tk[-1] - tk[0]) / dt + 1e-9)) + 1
    tu = tk[0] + dt * np.arange(n)
    out = {key: np.interp(tu, tk, y[keep]) for key, y in filtered.items()}
    bridged = sum(e.size for e in timeline.events if e.kind == "gap")
    statement = (f"resampled onto a uniform {dt:.4g} s grid: {lowpassed} faster segment(s) low-passed first "
                 f"(zero-phase Butterworth, order 8, at {f_cut:.4g} Hz = 0.8 of the new Nyquist frequency), then "
                 f"linear interpolation; {bridged:.4g} s of gaps bridged by straight lines; {int((~keep).sum())} rows "
                 "whose "
                 "time did not advance dropped")
    return tu, out, statement


def line_power_flag(spectrum: Spectrum, band) -> str | None:
    """A flag when spectral lines carry most of the power in ``band`` (rad/s): an ordinate of the Welch estimate
    more than ``LINE_FACTOR`` times the median of its neighbourhood (a quarter decade either side) is a line; a
    power-law (broadband) spectrum puts a vanishing share there (an ordinate of a Welch estimate with 2 or more
    degrees of freedom exceeds 10 times its median with probability below 2^-10), a periodic record (stick-slip,
    a sawtooth) nearly all."""
    w, C = spectrum.omega, spectrum.C
    m = (w >= band[0]) & (w <= band[1])
    if m.sum() < 8:
        return None
    lw = np.log10(w)
    cont = np.array([np.median(C[(lw >= a - _NEIGHBOURHOOD) & (lw <= a + _NEIGHBOURHOOD)]) for a in lw[m]])
    Cb = C[m]
    dw = np.gradient(w[m])
    lines = Cb > LINE_FACTOR * cont
    share = float(np.sum((Cb * dw)[lines]) / np.sum(Cb * dw))
    if share > LINE_SHARE:
        return (f"spectral lines carry {100 * share:.0f} % of the power in the band: a periodic record (stick-slip, "
                "a sawtooth), not a power law")
    return None


def with_line_flag(fit, spectrum: Spectrum):
    """``fit`` (a compare.analysis.fits.PowerLawFit) with :func:`line_power_flag`'s flag added when it applies."""
    flag = line_power_flag(spectrum, fit.band)
    return replace(fit, flags=tuple(fit.flags) + (flag,)) if flag else fit


def segment_fits(ss: SegmentSpectra, band=None, method: str | None = None) -> list:
    """One dict per segment: its rows, times, step, and its own power-law fit (or why there is none)."""
    from .fits import fit_power_law

    out = []
    for idx, (s, sp) in enumerate(ss.per_segment):
        row = {"start_row": s.start, "stop_row": s.stop, "n": s.n, "dt_s": s.dt, "in_combined": idx in ss.used}
        if sp is None:
            row["fit"] = None
            row["why"] = "too short for a spectrum"
        else:
            try:
                f = with_line_flag(fit_power_law(sp, band=band, method=method), sp)
            except ValueError as e:
                row["fit"], row["why"] = None, str(e)
            else:
                row["fit"] = f.to_dict()
        out.append(row)
    return out
