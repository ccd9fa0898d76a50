"""Measured series (displacement-sensor logs, tribometer force exports) read from instrument files and checked.

The table is read by its layout (:mod:`compare.io.sheets`: delimited text with preambles, units rows and
several blocks, the look program's ASCII export, a folder of per-stroke files, xlsx, TDMS); here its columns are
given their roles (time, displacement, friction force, normal force, friction coefficient, direction) and their
units (:mod:`engine_sim.quantities`, pint: from the header, the units row or an option; a unit the file states
and a different option is an error; ``units`` on the result says which unit was used for each column and where
it came from).

Only what cannot be read is refused, with a :class:`DataFileError` naming the file, the place (line, cell,
channel) and the reason: a non-numeric or infinite value in a column that is used. A row with NaN in a used column
is dropped and counted. Time stamps are kept as written (from the first sample's) and their breaks found
(:mod:`compare.analysis.timeline`: rate changes, gaps, repeated or backward stamps, a new block of the export,
each with its line, time and size): such a record is analysed segment by segment, or put on one grid on request
(``resample``) behind a stated anti-alias filter. A jittering clock without breaks is resampled onto a uniform
grid by linear interpolation, with a one-line warning giving the steps' spread; the resampling is kept in
``layout``.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from engine_sim.quantities import UnitError, parse_unit
from engine_sim.shipped import shipped_file

from .sheets import Sheet, SheetError, read_sheet, to_float

__all__ = ["MeasuredData", "DataFileError", "read_measured", "read_displacement_csv", "units_line"]

_JITTER_OK = 1e-6  # relative step spread below which no resampling is needed
_MIN_ROWS = 64


class DataFileError(ValueError):
    """A malformed data file: the message names the file, the line and the problem (one line)."""


@dataclass(frozen=True)
class MeasuredData:
    """A measured record in SI units, uniformly sampled or in uniform segments (``segmented``).

    ``t`` (s, starting at 0), and whichever of ``x`` (m), ``F`` (friction force, N), ``N`` (normal force, N),
    ``direction`` (the raw direction column) the file held and the caller asked for. ``units`` maps each
    quantity read to ``{"column", "unit", "from"}`` where ``from`` is "header", "units row" or "argument".
    ``blocks``: the blocks of a multi-block export (a UMT's steps, a folder's files), each with its title, the
    place of its first row and its rows ``start:stop`` of ``t``; ``note`` says so in one line.
    """

    t: np.ndarray
    x: np.ndarray | None
    source: str
    resampled: bool
    warning: str | None
    n_rows: int
    F: np.ndarray | None = None
    N: np.ndarray | None = None
    direction: np.ndarray | None = None
    mu: np.ndarray | None = None  # a friction-coefficient column as written (a pure number)
    units: dict = field(default_factory=dict)
    layout: dict = field(default_factory=dict)
    timeline: object = None  # compare.analysis.timeline.Timeline of the time stamps as written
    note: str | None = None  # what the file is made of, not a fault: the blocks of a multi-block export
    blocks: tuple = ()  # the export's blocks (two or more): {"block", "title", "place", "start", "stop"}, rows of t

    @property
    def segmented(self) -> bool:
        """True when ``t`` holds the stamps as written, in uniform segments between breaks (``timeline.events``):
        analyse segment by segment (compare.analysis.segments)."""
        return self.timeline is not None and bool(self.timeline.events) and not self.resampled


# ----------------------------------------------------------------------------- columns of a sheet
def _find(tab: Sheet, name: str | None, default: int | None, what: str) -> int | None:
    """The index of the column ``name`` (its full header or its name without the unit), else ``default``."""
    if name is None:
        if default is None:
            return None
        if tab.width <= default:
            raise DataFileError(f"{tab.where(tab.header_key)}: need at least {default + 1} columns for the "
                                f"{what} (found {tab.width})")
        return default
    for k, h in enumerate(tab.header):
        if name == h or name == tab.parsed[k][0]:
            return k
    raise DataFileError(f"{tab.where(tab.header_key)}: no {what} column {name!r}; columns are: "
                        f"{', '.join(tab.header)}")


_ROLE = {"time": "time", "x": "length", "force": "force", "mu": "dimensionless"}
_EXAMPLES = {"time": "s, ms, min", "length": "m, mm, um, in", "force": "N, mN, gf, kip"}


def _unit_scale(tab: Sheet, k: int, kind: str, given: str | None, flag: str, key: str,
                area: float | None = None) -> float:
    """The SI factor of column ``k`` (role ``kind``: time, x, force or mu), from its header, the units row or the
    ``given`` option (engine_sim.quantities: pint, with the column's role fixing the dimension); an option that
    differs from a unit the file states is an error, never an override. A stress on a force column becomes a
    force only with the contact ``area`` (m^2). Records the choice in ``tab.units[key]``."""
    header = tab.header
    role = _ROLE[kind]
    roles = (role, "stress") if role == "force" else (role,)
    _, hunit, _ = tab.parsed[k]
    origin, where = "header", tab.where(tab.header_key, k)
    if hunit is None and tab.units_row[k].strip():
        hunit, origin, where = tab.units_row[k], "units row", tab.where(tab.units_key, k)
    file_u = given_u = None
    if hunit is not None:
        try:
            file_u = parse_unit(hunit, roles)
        except UnitError as e:
            raise DataFileError(f"{where}: column {header[k]!r} is in {e.unit}, {e.reason}") from None
    if given is not None:
        try:
            given_u = parse_unit(given, roles)
        except UnitError as e:
            raise DataFileError(f"{flag} {given}: {e}") from None
    if file_u is not None and given_u is not None and (
            file_u.role != given_u.role or not math.isclose(file_u.factor, given_u.factor, rel_tol=1e-12)):
        raise DataFileError(f"{where}: the {origin} gives column {header[k]!r} in {file_u.written} "
                            f"but {flag} {given} was given; an option never overrides a unit the file states")
    if file_u is None and given_u is None:
        if role == "dimensionless":  # a friction coefficient is a pure number
            tab.units[key] = {"column": header[k], "unit": "1", "from": "role"}
            return 1.0
        raise DataFileError(f"{tab.where(tab.header_key, k)}: column {header[k]!r} names no unit (no units row "
                            f"either); give {flag} (any {role} unit: {_EXAMPLES[role]})")
    u = file_u if file_u is not None else given_u
    factor = u.factor
    entry = {"column": header[k], "unit": u.written, "from": origin if file_u is not None else "argument"}
    if u.rule:
        entry["rule"] = u.rule
    if u.role == "stress":
        if area is None:
            raise DataFileError(f"{where}: column {header[k]!r} is a stress ({u.written}), not a "
                                "force; a stress becomes a force only with the contact area: give --contact-area "
                                "(m^2)")
        factor *= area
        entry["rule"] = f"stress x contact area {area:g} m^2"
    tab.units[key] = entry
    return factor


def _rows(tab: Sheet, cols: dict) -> tuple[dict, list, list]:
    """({key: values in the file's units}, [row index kept], [row index dropped]): every data row's numbers. A row
    with NaN in a used column is dropped and counted (its time step then shows as a gap in
    compare.analysis.timeline, which splits the record there); an infinite or non-numeric value is an error."""
    values = {k: [] for k in cols}
    kept, dropped = [], []
    for r, cells in enumerate(tab.rows):
        row = {}
        for key, (k, _) in cols.items():
            try:
                v = to_float(cells[k], tab.dc)
            except IndexError:
                raise DataFileError(f"{tab.where(tab.keys[r])}: {len(cells)} fields, column {tab.header[k]!r} "
                                    "missing") from None
            except ValueError:
                raise DataFileError(f"{tab.where(tab.keys[r], k)}: non-numeric value {cells[k]!r} in column "
                                    f"{tab.header[k]!r}") from None
            if math.isinf(v):
                raise DataFileError(f"{tab.where(tab.keys[r], k)}: infinite value in column {tab.header[k]!r}")
            row[key] = v
        if any(math.isnan(v) for v in row.values()):
            dropped.append(r)
            continue
        for key, v in row.items():
            values[key].append(v)
        kept.append(r)
    if len(kept) < _MIN_ROWS:
        raise DataFileError(f"{tab.src}: only {len(kept)} data rows"
                            + (f" ({len(dropped)} more with NaN dropped)" if dropped else "")
                            + f"; need at least {_MIN_ROWS} for a spectrum")
    return values, kept, dropped


def _timeline(t: np.ndarray, lines, blocks: list):
    """The time line of stamps ``t`` (compare.analysis.timeline), each block of the export on its own: a block
    boundary ((row, title) pairs) is a break of kind "block" whatever the stamps do across it."""
    from dataclasses import replace

    from ..analysis.timeline import MIN_ROWS, Segment, TimeEvent, Timeline, find_segments

    if not blocks:
        return find_segments(t, lines=lines)
    starts = [0] + [r for r, _ in blocks] + [t.size]
    titles = [""] + [title for _, title in blocks]
    segs, events = [], []
    for j, (a, b) in enumerate(zip(starts[:-1], starts[1:])):
        if b <= a:
            continue
        tl = find_segments(t[a:b], lines=None if lines is None else lines[a:b])
        if a > 0:
            events.append(TimeEvent("block", a, None if lines is None else int(lines[a]), float(t[a - 1]),
                                    float(t[a] - t[a - 1]), f"{titles[j] or 'a new block'} begins: read on its own",
                                    float(t[a])))
        segs += [Segment(s.start + a, s.stop + a, s.dt, s.spread) for s in tl.segments]
        events += [replace(e, row=e.row + a) for e in tl.events]
    return Timeline(tuple(segs), tuple(events), tuple(k for k, s in enumerate(segs) if s.n < MIN_ROWS))


def _uniform(src: str, t: np.ndarray, arr: dict, lines, resample: float | None, blocks: list = ()):
    """(t, arr, warning, resampled, timeline). A block boundary of the export is a break of the time line but
    no fault of its clock: the warning counts only the clock's breaks (the blocks are the record's ``note``).
    Breaks in the time stamps (compare.analysis.timeline: rate changes, gaps, repeated or backward stamps) leave
    the record as written, in uniform segments, unless ``resample`` (s) asks for one grid
    (compare.analysis.segments.resample_record, its filter stated in the warning); a jittered grid without breaks
    is resampled onto a uniform one (linear interpolation; a direction label takes the nearest earlier sample)."""
    from ..analysis.segments import resample_record
    from ..analysis.timeline import MIN_ROWS

    tl = _timeline(t, lines, list(blocks))
    if resample is not None:
        label = arr.pop("direction", None)
        tu, arr, statement = resample_record(t, arr, tl, resample)
        if label is not None:
            arr["direction"] = label[np.clip(np.searchsorted(t, tu, side="right") - 1, 0, len(t) - 1)]
        return tu, arr, f"{src}: {statement}", True, tl
    if tl.events:
        if not tl.usable():
            raise DataFileError(f"{src}: no stretch of {MIN_ROWS} uniformly sampled rows between the breaks of its "
                                f"time stamps (first: {tl.events[0].describe()}); give --resample DT")
        kinds = {}
        for e in tl.events:
            if e.kind != "block":
                kinds[e.kind] = kinds.get(e.kind, 0) + 1
        if not kinds:
            return t, arr, None, False, tl
        said = ", ".join(f"{n} {k}{'s' if n > 1 else ''}" for k, n in kinds.items())
        n = len(tl.usable())
        return t, arr, (f"{src}: non-uniform time stamps ({said}): analysed as {n} uniform segment"
                        f"{'s' if n > 1 else ''}, each on its own and together (--resample DT puts them on one "
                        "grid)"), False, tl
    steps = np.diff(t)
    med = float(np.median(steps))
    spread = float(np.max(np.abs(steps - med)) / med)
    if spread <= _JITTER_OK:
        return t, arr, None, False, tl
    n = int(round((t[-1] - t[0]) / med)) + 1
    tu = t[0] + np.arange(n) * med
    tu = tu[tu <= t[-1]]
    for key in arr:
        if key == "direction":  # a label: nearest earlier sample, not an interpolation
            arr[key] = arr[key][np.clip(np.searchsorted(t, tu, side="right") - 1, 0, len(t) - 1)]
        else:
            arr[key] = np.interp(tu, t, arr[key])
    warning = (f"{src}: jittering clock, no samples missing: steps {steps.min():.4g}-{steps.max():.4g} s around "
               f"the median {med:.4g} s (spread {100 * spread:.2g} %); resampled onto a uniform {med:.4g} s grid by "
               "linear interpolation, which low-passes a steep spectrum near the Nyquist frequency (--resample DT: "
               "a grid of your choosing behind a stated filter)")
    return tu, arr, warning, True, tl


def read_measured(path, *, time_col: str | None = None, x_col: str | None = None, force_col: str | None = None,
                  normal_col: str | None = None, direction_col: str | None = None,
                  time_unit: str | None = None, x_unit: str | None = None, force_unit: str | None = None,
                  require_x: bool = True, resample: float | None = None, mu_col: str | None = None,
                  contact_area: float | None = None) -> MeasuredData:
    """Read a measured record: time and displacement and/or friction force (optional normal force, direction).

    Parameters
    ----------
    path : str or pathlib.Path
        The text file (CSV, ;- or tab-separated; preamble, units row, decimal commas and latin-1 are read).
    time_col, x_col, force_col, normal_col, direction_col : str, optional
        Column names (the full header text or its name without the unit: ``"F"`` finds ``F [N]``). Defaults:
        time is the first column; with ``require_x`` and no ``force_col``, displacement is the second.
    mu_col : str, optional
        A friction-coefficient column (a pure number, or a units row's ``%``): analysed as mu.
    time_unit, x_unit, force_unit : str, optional
        Units, required when neither the header nor a units row names them: any unit pint reads whose dimension
        fits the column (``s``, ``ms``; ``mm``, ``in``; ``N``, ``gf``, ``kip``); a unit the file states and a
        different one given here is an error. ``normal_col`` uses the force unit rules; a mass unit on a force
        column is its weight (``g`` is gram-force, :mod:`engine_sim.quantities`).
    contact_area : float, optional
        The contact area (m^2) that turns a stress column (``MPa``) into a force; without it a stress is refused.
    resample : float, optional
        A uniform step (s) to put the whole record on, behind a stated anti-alias filter, when its time stamps
        break (rate changes, gaps, repeated or backward stamps); without it such a record is returned as written,
        ``segmented``, with its ``timeline``.
    require_x : bool, optional
        Whether a displacement column is required (False for force data).

    Returns
    -------
    MeasuredData
        The record in SI units (s, m, N), with the units read and where from: on a uniform time grid, or as
        written with its ``timeline`` of breaks when the stamps break and ``resample`` is None.
    """
    if resample is not None and not (resample > 0 and math.isfinite(resample)):
        raise DataFileError(f"the resampling step must be a positive number of seconds (got {resample!r})")
    path = Path(path) if os.path.lexists(path) else Path(shipped_file(path))  # scenarios/... as the docs write it
    src = str(path)
    if contact_area is not None and not (contact_area > 0 and math.isfinite(contact_area)):
        raise DataFileError(f"the contact area must be a positive number of m^2 (got {contact_area!r})")
    try:
        tab = read_sheet(path)
    except SheetError as e:
        raise DataFileError(str(e)) from None
    it = _find(tab, time_col, 0, "time")
    ix = _find(tab, x_col, 1 if (require_x and force_col is None) else None, "displacement")
    iF = _find(tab, force_col, None, "force")
    iN = _find(tab, normal_col, None, "normal force")
    iD = _find(tab, direction_col, None, "direction")
    iM = _find(tab, mu_col, None, "friction coefficient")
    cols = {"t": (it, _unit_scale(tab, it, "time", time_unit, "--time-unit", "time"))}
    if ix is not None:
        cols["x"] = (ix, _unit_scale(tab, ix, "x", x_unit, "--x-unit", "x"))
    if iF is not None:
        cols["F"] = (iF, _unit_scale(tab, iF, "force", force_unit, "--force-unit", "force", contact_area))
    if iN is not None:
        cols["N"] = (iN, _unit_scale(tab, iN, "force", force_unit, "--force-unit", "normal", contact_area))
    if iM is not None:
        cols["mu"] = (iM, _unit_scale(tab, iM, "mu", None, "--mu-col", "mu"))
    if iD is not None:
        cols["direction"] = (iD, 1.0)
    values, kept, dropped = _rows(tab, cols)
    arr = {key: np.asarray(values[key]) * cols[key][1] for key in cols}
    keys = [tab.keys[r] for r in kept]
    lines = np.asarray(keys) if tab.layout in ("delimited", "look-ascii") else None  # text: breaks by line
    blocks = [(int(np.searchsorted(kept, r)), title) for r, _, title in tab.blocks]
    t_file = arr.pop("t")
    t0 = float(t_file[0])  # one time origin everywhere: the first sample kept, the breaks' times included
    t, arr, warning, resampled, timeline = _uniform(src, t_file - t0, arr, lines, resample, blocks)
    parts, note = _blocks(tab, kept, t_file - t0, t, blocks, resampled)
    layout = dict(tab.info, layout=tab.layout, time_origin_s=t0, nan_rows_dropped=len(dropped),
                  nan_places=[tab.place(tab.keys[r]) for r in dropped[:20]],
                  resampling=warning[len(src) + 2:] if resampled and warning else None)
    if dropped:
        places = [tab.place(tab.keys[r]) for r in dropped[:5]]
        said = (f"{src}: {len(dropped)} row{'s' if len(dropped) > 1 else ''} with NaN dropped ("
                f"{', '.join(places)}{', ...' if len(dropped) > 5 else ''})")
        warning = said if warning is None else f"{said}; {warning}"
    return MeasuredData(t=t - t[0], x=arr.get("x"), source=src, resampled=resampled, warning=warning,
                        n_rows=len(kept), F=arr.get("F"), N=arr.get("N"), direction=arr.get("direction"),
                        mu=arr.get("mu"),
                        units=tab.units, layout=layout, timeline=timeline, note=note, blocks=parts)


def _blocks(tab: Sheet, kept: list, t_rows: np.ndarray, t: np.ndarray, blocks: list, resampled: bool):
    """(blocks, note) of a multi-block export: each block's title, the place of its first row and its rows of the
    record ``t`` (the rows as written, or the stretch of the uniform grid from a block's first stamp to its last
    when resampled), and one line saying the record is made of them; ((), None) for one block. A block left without
    rows (every row NaN) is not listed."""
    rows = [0] + [r for r, _ in blocks]
    ends = rows[1:] + [len(t_rows)]
    if resampled:  # the grid's samples from a block's first stamp to its last (a pause between blocks in neither)
        half = 0.5 * float(t[1] - t[0])  # a grid point within half a step of a stamp is that stamp's
        first = [int(np.searchsorted(t, t_rows[r] - half, side="left")) for r in rows]
        last = [int(np.searchsorted(t, t_rows[e - 1] + half, side="left")) if e > r else f
                for r, e, f in zip(rows, ends, first)]
    else:
        first, last = rows, ends
    titles = [""] + [title for _, title in blocks]
    parts = tuple({"block": k + 1, "title": titles[k], "place": tab.place(tab.keys[kept[r]]), "start": a, "stop": b}
                  for k, (r, a, b) in enumerate(zip(rows, first, last)) if b > a)
    if len(parts) < 2:
        return (), None
    opened = "; ".join(p["place"] if p["title"] and p["title"] in p["place"] else  # a folder's file names its block
                       f"{p['title'] or 'block ' + str(p['block'])} at {p['place']}" for p in parts[1:4])
    note = (f"{tab.src}: an export of {len(parts)} blocks (then {opened}{'; ...' if len(parts) > 4 else ''}): "
            "blocks of the export, not breaks of its clock; each block "
            + ("put on the one grid with the rest (--resample)" if resampled else
               "analysed as its own segment, on its own and together with the others"))
    return parts, note


def read_displacement_csv(path, time_col: str | None = None, x_col: str | None = None,
                          x_unit: str | None = None, time_unit: str | None = None) -> MeasuredData:
    """Read time and displacement columns (default: the first two); see :func:`read_measured`."""
    return read_measured(path, time_col=time_col, x_col=x_col, x_unit=x_unit, time_unit=time_unit)


def units_line(data: MeasuredData) -> str:
    """One line saying which unit each column was read in and where the unit came from."""
    said = {"argument": "as given", "role": "a pure number"}
    parts = [f"{v['column']!r} in {v['unit']} ({said.get(v['from'], 'from the ' + v['from'])}"
             + (f"; {v['rule']}" if v.get("rule") else "") + ")" for v in data.units.values()]
    line = "read " + ", ".join(parts)
    skipped = (data.layout or {}).get("preamble_lines") or 0
    if skipped:
        line += (f"; {skipped} non-blank preamble line{'s' if skipped > 1 else ''} above the header (line "
                 f"{data.layout['header_line']}) skipped")
    return line
