"""The report's account of a record's time line: where its time stamps break (line, time, size) and each uniform
segment with its own fit."""
from __future__ import annotations

from .html import esc, paragraphs, table

__all__ = ["timeline_html"]


def timeline_html(timeline, fits, notes=()) -> str:
    """HTML: the breaks as a list, then a table of the segments (rows, step, own exponent, in the combined
    spectrum or not). ``fits``: compare.analysis.segments.segment_fits of the same segments."""
    breaks = "; ".join(esc(e.describe()) for e in timeline.events)
    rows = []
    for i, (seg, f) in enumerate(zip(timeline.segments, fits or [{}] * len(timeline.segments))):
        fit = f.get("fit")
        own = (f"{fit['gamma']:.3f} &plusmn; {fit['gamma_err']:.3f}" + (" (not a power law)" if fit["flags"] else "")
               if fit else esc(f.get("why", "too short: not analysed")))
        rows.append([str(i + 1), f"{seg.start + 1}-{seg.stop}", str(seg.n), f"{seg.dt:.4g}", own,
                     "yes" if f.get("in_combined") else "no"])
    text = paragraphs([f"The time stamps break {len(timeline.events)} time(s): {breaks}."]
                      + [esc(n) for n in notes])
    return "\n" + text + "\n" + table("Uniform segments of the record (rows counted from the first data row)",
                                      ["#", "rows", "samples", "step (s)", "own exponent (95 %)",
                                       "in the combined spectrum"], rows)
