"""The report's account of a record's time line: where its time stamps break (line, time, size) and each uniform
segment (or, for a force record, each uniform piece of a stroke) with its own fit."""
from __future__ import annotations

from .html import esc, paragraphs, table

__all__ = ["timeline_html", "pieces_html"]


def _own(f: dict) -> str:
    """A piece's own exponent with its 95 % half-width, or why it has none."""
    fit = f.get("fit")
    return (f"{fit['gamma']:.3f} &plusmn; {fit['gamma_err']:.3f}" + (" (not a power law)" if fit["flags"] else "")
            if fit else esc(f.get("why", "too short: not analysed")))


def _breaks(timeline) -> str:
    """The blocks of the export (no fault of the clock), then the breaks of its time stamps, each described."""
    blocks = [e for e in timeline.events if e.kind == "block"]
    clock = [e for e in timeline.events if e.kind != "block"]
    said = []
    if blocks:
        said.append(f"The export is made of {len(blocks) + 1} blocks, each read on its own (not a fault of the "
                    "clock): " + "; ".join(esc(e.describe()) for e in blocks) + ".")
    if clock:
        said.append(f"The time stamps break {len(clock)} time{'s' if len(clock) > 1 else ''}: "
                    + "; ".join(esc(e.describe()) for e in clock) + ".")
    return " ".join(said)


def timeline_html(timeline, fits, notes=()) -> str:
    """HTML: the breaks as a list, then a table of the segments (rows, step, own exponent, in the combined
    spectrum or not). ``fits``: compare.analysis.segments.segment_fits of the same segments."""
    rows = []
    for i, (seg, f) in enumerate(zip(timeline.segments, fits or [{}] * len(timeline.segments))):
        own = _own(f)
        rows.append([str(i + 1), f"{seg.start + 1}-{seg.stop}", str(seg.n), f"{seg.dt:.4g}", own,
                     "yes" if f.get("in_combined") else "no"])
    text = paragraphs([_breaks(timeline)]
                      + [esc(n) for n in notes])
    return "\n" + text + "\n" + table("Uniform segments of the record (rows counted from the first data row)",
                                      ["#", "rows", "samples", "step (s)", "own exponent (95 %)",
                                       "in the combined spectrum"], rows)


def pieces_html(timeline, fits) -> str:
    """HTML: the breaks, then a table of the uniform pieces of a force record's strokes (stroke, rows, times, step,
    own exponent, in the combined spectrum or not). ``fits``: the ``piece_fits`` of compare.analysis.force."""
    rows = [[str(i + 1), str(f["stroke"]), f"{f['start_row'] + 1}-{f['stop_row']}", f"{f['t_start_s']:.6g}",
             f"{f['t_stop_s']:.6g}", str(f["n"]), f"{f['dt_s']:.4g}", _own(f), "yes" if f["in_combined"] else "no"]
            for i, f in enumerate(fits)]
    return "\n" + paragraphs([_breaks(timeline)]) + "\n" + table(
        "Uniform pieces: every used stroke cut where the time stamps break (rows counted from the first data row)",
        ["#", "stroke", "rows", "first stamp (s)", "last stamp (s)", "samples", "step (s)", "own exponent (95 %)",
         "in the combined spectrum"], rows)
