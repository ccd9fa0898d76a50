"""Measured series (displacement-sensor logs, tribometer force exports) read from text files and checked.

What is read (instrument exports as they come):

- metadata preamble lines before the header row (anything that is not a numeric table), ignored and counted;
- a header row naming the columns, optionally followed by a units row (``s;mm;N`` or ``[s] [mm] [N]``);
- ``,``, ``;`` or tab separators (the one that splits the numeric rows consistently); decimal commas when the
  separator is ``;`` or tab;
- units of time, position and force from the column header when it names one (``x_um``, ``x [mm]``,
  ``F(N)``, ``t/s``) or from the units row; otherwise the unit must be given (``time_unit``, ``x_unit``,
  ``force_unit``); a header unit that contradicts a given unit is an error naming both. ``units`` on the result
  says which unit was used for each column and where it came from.

Only what cannot be read is refused, with a :class:`DataFileError` naming the file, the line and the reason:
a non-numeric or missing value in a column that is used. Time stamps are kept as written and their breaks found
(:mod:`compare.analysis.timeline`: rate changes, gaps, repeated or backward stamps, each with its line, time and
size): such a record is analysed segment by segment, or put on one grid on request (``resample``) behind a stated
anti-alias filter. Jitter without breaks is resampled onto a uniform grid by linear interpolation, with a warning
that says how much it was. Blank lines and ``#`` comments inside the table are skipped.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from engine_sim.quantities import UnitError, parse_unit, split_header
from engine_sim.text_file import decode, split_lines

__all__ = ["MeasuredData", "DataFileError", "read_measured", "read_displacement_csv", "units_line"]

_JITTER_OK = 1e-6  # relative step spread below which no resampling is needed
_MIN_ROWS = 64
_SEPARATORS = (";", "\t", ",")


class DataFileError(ValueError):
    """A malformed data file: the message names the file, the line and the problem (one line)."""


@dataclass(frozen=True)
class MeasuredData:
    """A measured record in SI units, uniformly sampled or in uniform segments (``segmented``).

    ``t`` (s, starting at 0), and whichever of ``x`` (m), ``F`` (friction force, N), ``N`` (normal force, N),
    ``direction`` (the raw direction column) the file held and the caller asked for. ``units`` maps each
    quantity read to ``{"column", "unit", "from"}`` where ``from`` is "header", "units row" or "argument".
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

    @property
    def segmented(self) -> bool:
        """True when ``t`` holds the stamps as written, in uniform segments between breaks (``timeline.events``):
        analyse segment by segment (compare.analysis.segments)."""
        return self.timeline is not None and bool(self.timeline.events) and not self.resampled


# ----------------------------------------------------------------------------- parsing helpers
def _unitish(cell: str) -> bool:
    """Whether a units-row cell reads as a unit (blank, a pure-number mark, or any unit pint knows)."""
    c = cell.strip().strip("[](){}").strip()
    if not c:
        return True
    try:
        parse_unit(c, ("length", "force", "stress", "time", "velocity", "dimensionless"))
        return True
    except UnitError as e:
        return "not a unit pint knows" not in str(e)


def _to_float(cell: str, decimal_comma: bool) -> float:
    c = cell.strip()
    if decimal_comma:
        c = c.replace(",", ".")
    return float(c)


def _is_numeric(cell: str, decimal_comma: bool) -> bool:
    try:
        _to_float(cell, decimal_comma)
        return True
    except ValueError:
        return False


def _split(line: str, sep: str) -> list[str]:
    return [c.strip().strip('"') for c in line.split(sep)]


def _detect_layout(lines: list[str]) -> tuple[str, bool, int]:
    """(separator, decimal_comma, index of the first numeric data row) or raise ValueError with the reason.

    For each separator (and decimal mark), the table starts at the first run of rows that are fully numeric
    with the same width >= 2 and at least 5 rows long (or the longest run, in a short file); the separator
    whose table is longest, then widest, wins.
    """
    rows = [(i, line) for i, line in enumerate(lines) if line.strip() and not line.strip().startswith("#")]
    best = None
    for sep in _SEPARATORS:
        for dc in ((False, True) if sep != "," else (False,)):
            run_start, run_len, width = None, 0, None
            found = None  # (length, width, start)
            for i, line in rows:
                cells = _split(line, sep)
                ok = len(cells) >= 2 and any(cells) and all(_is_numeric(c, dc) for c in cells if c)
                if ok and width is not None and len(cells) == width:
                    run_len += 1
                elif ok:
                    run_start, run_len, width = i, 1, len(cells)
                else:
                    run_start, run_len, width = None, 0, None
                if run_len and (found is None or run_len > found[0]):
                    found = (run_len, width, run_start)
                if found and found[0] >= 5:
                    break
            if found is None:
                continue
            key = (min(found[0], 5), found[1], -found[2])
            if best is None or key > best[0]:
                best = (key, sep, dc, found[2])
    if best is None:
        raise ValueError("no table of numbers with at least two columns found")
    return best[1], best[2], best[3]


# ----------------------------------------------------------------------------- the reader
def _read_lines(path: Path, src: str) -> list:
    """The file's lines, decoded (UTF-8, else Latin-1); DataFileError for a missing, empty or binary file."""
    if not path.exists():
        raise DataFileError(f"{src}: no such file")
    if path.is_dir():
        raise DataFileError(f"{src}: is a folder, not a data file")
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise DataFileError(f"{src}: cannot be read ({e.strerror or e})") from None
    if not raw.strip():
        raise DataFileError(f"{src}: empty file")
    dec = decode(raw)  # UTF-8, UTF-16 with a BOM, else latin-1 (a micro sign as 0xB5)
    if dec is None:
        raise DataFileError(f"{src}: binary file (NUL bytes or control characters), not a text table")
    return split_lines(dec[0])  # numbered as grep -n numbers them: CR CR LF is one line end


@dataclass
class _Table:
    """The layout of a text table: its lines, separator, decimal comma, first numeric row (0-based), width, and
    the header row and optional units row above it."""

    src: str
    lines: list
    sep: str
    dc: bool
    first: int
    width: int
    header_i: int = 0
    units_i: int | None = None
    header: list = field(default_factory=list)
    parsed: list = field(default_factory=list)
    units_row: list = field(default_factory=list)
    units: dict = field(default_factory=dict)  # what each column was read in and where the unit came from

    def data_lines(self):
        """Indices of the data rows: from the first numeric row on, blank and ``#`` lines skipped."""
        for i in range(self.first, len(self.lines)):
            s = self.lines[i].strip()
            if s and not s.startswith("#"):
                yield i


def _table(lines: list, src: str) -> _Table:
    """Locate the table, its header row and an optional units row above the first numeric row."""
    try:
        sep, dc, first = _detect_layout(lines)
    except ValueError as e:
        raise DataFileError(f"{src}: {e}") from None
    tab = _Table(src, lines, sep, dc, first, len(_split(lines[first], sep)))
    above = [i for i in range(first) if lines[i].strip() and not lines[i].strip().startswith("#")]
    header_i = units_i = None
    if above:
        last = above[-1]
        cells = _split(lines[last], sep)
        unitish = [_unitish(c) or (c[0] in "[(" and c[-1] in "])") for c in cells]
        known = sum(1 for c in cells if c and _unitish(c))
        if len(cells) == tab.width and len(above) >= 2 and known >= 1 and (all(unitish) or 2 * known >= tab.width):
            units_i = last
            header_i = above[-2]
        else:
            header_i = last
    if header_i is None:
        raise DataFileError(f"{src}, line {first + 1}: expected a header row naming the columns above the "
                            "first row of numbers")
    tab.header_i, tab.units_i = header_i, units_i
    tab.header = _split(lines[header_i], sep)
    if len(tab.header) != tab.width:
        raise DataFileError(f"{src}, line {header_i + 1}: the header has {len(tab.header)} columns, the data "
                            f"{tab.width} (separator {sep!r})")
    tab.units_row = _split(lines[units_i], sep) if units_i is not None else [""] * tab.width
    tab.parsed = [split_header(h) for h in tab.header]
    return tab


def _find(tab: _Table, name: str | None, default: int | None, what: str) -> int | None:
    """The index of the column ``name`` (its full header or its name without the unit), else ``default``."""
    if name is None:
        if default is None:
            return None
        if tab.width <= default:
            raise DataFileError(f"{tab.src}, line {tab.header_i + 1}: need at least {default + 1} columns for the "
                                f"{what} (found {tab.width})")
        return default
    for k, h in enumerate(tab.header):
        if name == h or name == tab.parsed[k][0]:
            return k
    raise DataFileError(f"{tab.src}, line {tab.header_i + 1}: no {what} column {name!r}; columns are: "
                        f"{', '.join(tab.header)}")


_ROLE = {"time": "time", "x": "length", "force": "force", "mu": "dimensionless"}
_EXAMPLES = {"time": "s, ms, min", "length": "m, mm, um, in", "force": "N, mN, gf, kip"}


def _unit_scale(tab: _Table, k: int, kind: str, given: str | None, flag: str, key: str,
                area: float | None = None) -> float:
    """The SI factor of column ``k`` (role ``kind``: time, x, force or mu), from its header, the units row or the
    ``given`` option (engine_sim.quantities: pint, with the column's role fixing the dimension); an option that
    differs from a unit the file states is an error, never an override. A stress on a force column becomes a
    force only with the contact ``area`` (m^2). Records the choice in ``tab.units[key]``."""
    src, header = tab.src, tab.header
    role = _ROLE[kind]
    roles = (role, "stress") if role == "force" else (role,)
    _, hunit, _ = tab.parsed[k]
    origin, line = "header", tab.header_i + 1
    if hunit is None and tab.units_row[k].strip():
        hunit, origin, line = tab.units_row[k], "units row", tab.units_i + 1
    file_u = given_u = None
    if hunit is not None:
        try:
            file_u = parse_unit(hunit, roles)
        except UnitError as e:
            raise DataFileError(f"{src}, line {line}: column {header[k]!r} is in {e.unit}, {e.reason}") from None
    if given is not None:
        try:
            given_u = parse_unit(given, roles)
        except UnitError as e:
            raise DataFileError(f"{flag} {given}: {e}") from None
    if file_u is not None and given_u is not None and (
            file_u.role != given_u.role or not math.isclose(file_u.factor, given_u.factor, rel_tol=1e-12)):
        raise DataFileError(f"{src}, line {line}: the {origin} gives column {header[k]!r} in {file_u.written} "
                            f"but {flag} {given} was given; an option never overrides a unit the file states")
    if file_u is None and given_u is None:
        if role == "dimensionless":  # a friction coefficient is a pure number
            tab.units[key] = {"column": header[k], "unit": "1", "from": "role"}
            return 1.0
        raise DataFileError(f"{src}, line {tab.header_i + 1}: column {header[k]!r} names no unit (no units row "
                            f"either); give {flag} (any {role} unit: {_EXAMPLES[role]})")
    u = file_u if file_u is not None else given_u
    factor = u.factor
    entry = {"column": header[k], "unit": u.written, "from": origin if file_u is not None else "argument"}
    if u.rule:
        entry["rule"] = u.rule
    if u.role == "stress":
        if area is None:
            raise DataFileError(f"{src}, line {line}: column {header[k]!r} is a stress ({u.written}), not a "
                                "force; a stress becomes a force only with the contact area: give --contact-area "
                                "(m^2)")
        factor *= area
        entry["rule"] = f"stress x contact area {area:g} m^2"
    tab.units[key] = entry
    return factor


def _rows(tab: _Table, cols: dict) -> tuple[dict, list, list]:
    """({key: values in the file's units}, [line index of each row], [line index of each row dropped]): every data
    row's numbers. A row with NaN in a used column is dropped and counted (its time step then shows as a gap in
    compare.analysis.timeline, which splits the record there); an infinite or non-numeric value is an error."""
    src, lines = tab.src, tab.lines
    values = {k: [] for k in cols}
    line_of, dropped = [], []
    for i in tab.data_lines():
        cells = _split(lines[i], tab.sep)
        row = {}
        for key, (k, _) in cols.items():
            try:
                v = _to_float(cells[k], tab.dc)
            except IndexError:
                raise DataFileError(f"{src}, line {i + 1}: {len(cells)} fields, column {tab.header[k]!r} missing") from None
            except ValueError:
                raise DataFileError(f"{src}, line {i + 1}: non-numeric value {cells[k]!r} in column "
                                    f"{tab.header[k]!r}") from None
            if math.isinf(v):
                raise DataFileError(f"{src}, line {i + 1}: infinite value in column {tab.header[k]!r}")
            row[key] = v
        if any(math.isnan(v) for v in row.values()):
            dropped.append(i)
            continue
        for key, v in row.items():
            values[key].append(v)
        line_of.append(i)
    if len(line_of) < _MIN_ROWS:
        raise DataFileError(f"{src}: only {len(line_of)} data rows"
                            + (f" ({len(dropped)} more with NaN dropped)" if dropped else "")
                            + f"; need at least {_MIN_ROWS} for a spectrum")
    return values, line_of, dropped


def _uniform(src: str, t: np.ndarray, arr: dict, line_of: list, resample: float | None):
    """(t, arr, warning, resampled, timeline). Breaks in the time stamps (compare.analysis.timeline: rate changes,
    gaps, repeated or backward stamps) leave the record as written, in uniform segments, unless ``resample`` (s)
    asks for one grid (compare.analysis.segments.resample_record, its filter stated in the warning); a jittered
    grid without breaks is resampled onto a uniform one (linear interpolation; a direction label takes the
    nearest earlier sample)."""
    from ..analysis.segments import resample_record
    from ..analysis.timeline import MIN_ROWS, find_segments

    tl = find_segments(t, lines=np.asarray(line_of) + 1)
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
            kinds[e.kind] = kinds.get(e.kind, 0) + 1
        said = ", ".join(f"{n} {k}{'s' if n > 1 else ''}" for k, n in kinds.items())
        return t, arr, (f"{src}: non-uniform time stamps ({said}): analysed as {len(tl.usable())} uniform segments, "
                        "each on its own and together (--resample DT puts them on one grid)"), False, tl
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
    path = Path(path)
    src = str(path)
    if contact_area is not None and not (contact_area > 0 and math.isfinite(contact_area)):
        raise DataFileError(f"the contact area must be a positive number of m^2 (got {contact_area!r})")
    tab = _table(_read_lines(path, src), src)
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
    values, line_of, dropped = _rows(tab, cols)
    arr = {key: np.asarray(values[key]) * cols[key][1] for key in cols}
    t, arr, warning, resampled, timeline = _uniform(src, arr.pop("t"), arr, line_of, resample)
    layout = {"separator": {";": "semicolon", "\t": "tab", ",": "comma"}[tab.sep], "decimal_comma": tab.dc,
              "preamble_lines": sum(1 for i in range(tab.header_i) if tab.lines[i].strip()),
              "header_line": tab.header_i + 1, "units_row_line": None if tab.units_i is None else tab.units_i + 1,
              "first_data_line": tab.first + 1, "nan_rows_dropped": len(dropped),
              "resampling": warning[len(src) + 2:] if resampled and warning else None,
              "nan_lines": [i + 1 for i in dropped[:20]]}
    if dropped:
        said = (f"{src}: {len(dropped)} row{'s' if len(dropped) > 1 else ''} with NaN dropped (line"
                f"{'s' if len(dropped) > 1 else ''} {', '.join(str(i + 1) for i in dropped[:5])}"
                f"{', ...' if len(dropped) > 5 else ''})")
        warning = said if warning is None else f"{said}; {warning}"
    return MeasuredData(t=t - t[0], x=arr.get("x"), source=src, resampled=resampled, warning=warning,
                        n_rows=len(line_of), F=arr.get("F"), N=arr.get("N"), direction=arr.get("direction"),
                        mu=arr.get("mu"),
                        units=tab.units, layout=layout, timeline=timeline)


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
