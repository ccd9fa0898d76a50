"""A table as read (:class:`Sheet`, and :class:`SheetError` for what cannot be read), the registry of layouts
(:data:`LAYOUTS`, :func:`layout`) and the parsing of text tables the layouts share (separators, decimal commas,
units rows, blocks). :mod:`compare.io.layouts` registers the readers; :mod:`compare.io.sheets` reads a file by them
and re-exports these names."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from engine_sim.quantities import UnitError, parse_unit, split_header
from engine_sim.text_file import decode, split_lines

__all__ = ["Sheet", "Layout", "LAYOUTS", "layout", "SheetError", "to_float", "is_pattern"]

_SEPARATORS = (";", "\t", ",")
_BLOCK_LOOKAHEAD = 60  # lines of text a block may open with before its header is repeated


class SheetError(ValueError):
    """A table that cannot be read: one line naming the file and the place (line, cell, channel)."""


@dataclass
class Sheet:
    """A table as read: ``header`` (column names as written), ``units_row`` (one cell per column, "" where none),
    ``rows`` (cells: text or numbers) with ``keys`` (each row's place, for :meth:`where`), ``blocks`` (row index,
    place, title) where a new block of the export begins, ``info`` (the layout's facts, for the record's
    provenance) and ``dc`` (decimal commas)."""

    src: str
    layout: str
    header: list
    units_row: list
    rows: list
    keys: list
    header_key: object
    units_key: object = None
    blocks: list = field(default_factory=list)
    info: dict = field(default_factory=dict)
    dc: bool = False
    place: Callable = None  # place(key, column or None) -> "line 12", "sheet 'Run', cell C7", ...
    parsed: list = field(default_factory=list)
    units: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.place is None:
            self.place = lambda key, col=None: f"line {key}"
        self.parsed = [split_header(str(h)) for h in self.header]

    @property
    def width(self) -> int:
        return len(self.header)

    def where(self, key, col=None) -> str:
        """``file, place`` of row ``key`` (and column ``col``): what a refusal names."""
        return f"{self.src}, {self.place(key, col)}"


@dataclass(frozen=True)
class Layout:
    """A registered layout: ``detect(path, head)`` (head: the first 4 kB, or None for a folder or pattern) says
    whether it reads the file; ``read(path, src)`` reads it into a :class:`Sheet`."""

    name: str
    detect: Callable
    read: Callable
    what: str


LAYOUTS: dict = {}


def layout(name: str, what: str):
    """Register a reader under ``name`` (checked in the order registered, the first that detects wins)."""
    def deco(cls_or_fn):
        LAYOUTS[name] = Layout(name, cls_or_fn.detect, cls_or_fn.read, what)
        return cls_or_fn
    return deco


def is_pattern(p: str) -> bool:
    return any(c in p for c in "*?[")






# ----------------------------------------------------------------------------------------------- cells and rows
def to_float(cell, decimal_comma: bool = False) -> float:
    """A cell's number (ValueError if it holds none)."""
    if isinstance(cell, (int, float)) and not isinstance(cell, bool):
        return float(cell)
    if cell is None:
        raise ValueError("empty")
    c = str(cell).strip()
    if decimal_comma:
        c = c.replace(",", ".")
    return float(c)


def _is_numeric(cell, decimal_comma: bool = False) -> bool:
    try:
        to_float(cell, decimal_comma)
        return True
    except ValueError:
        return False


def split_cells(line: str, sep: str) -> list:
    return [c.strip().strip('"') for c in line.split(sep)]


def _unitish(cell) -> bool:
    """Whether a units-row cell reads as a unit (blank, a pure-number mark, or any unit pint knows)."""
    c = str(cell if cell is not None else "").strip().strip("[](){}").strip()
    if not c:
        return True
    try:
        parse_unit(c, ("length", "force", "stress", "time", "velocity", "dimensionless"))
        return True
    except UnitError as e:
        return "not a unit pint knows" not in str(e)


def _numeric_row(cells, dc) -> bool:
    return len(cells) >= 2 and any(str(c).strip() for c in cells) and all(
        _is_numeric(c, dc) for c in cells if str(c if c is not None else "").strip())


def first_run(records, dc):
    """(length, width, index) of the first run of numeric records of one width >= 2 at least 5 long (or the
    longest run), or None."""
    run_start, run_len, width, found = None, 0, None, None
    for j, (_, cells) in enumerate(records):
        ok = _numeric_row(cells, dc)
        if ok and width is not None and len(cells) == width:
            run_len += 1
        elif ok:
            run_start, run_len, width = j, 1, len(cells)
        else:
            run_start, run_len, width = None, 0, None
        if run_len and (found is None or run_len > found[0]):
            found = (run_len, width, run_start)
        if found and found[0] >= 5:
            break
    return found


def tabulate(src, name, records, first, dc, place, info) -> Sheet:
    """The sheet of ``records`` ((key, cells) of the non-blank rows) whose data begin at ``records[first]``: the
    header row above it, an optional units row between, the data and any later block (text, then the header
    again)."""
    width = len(records[first][1])
    above = records[:first]
    header_j = units_j = None
    if above:
        cells = above[-1][1]
        unitish = [_unitish(c) or (str(c)[:1] in "[(" and str(c)[-1:] in "])") for c in cells]
        known = sum(1 for c in cells if str(c).strip() and _unitish(c))
        if len(cells) == width and len(above) >= 2 and known >= 1 and (all(unitish) or 2 * known >= width):
            units_j, header_j = len(above) - 1, len(above) - 2
        else:
            header_j = len(above) - 1
    if header_j is None:
        raise SheetError(f"{src}, {place(records[first][0])}: expected a header row naming the columns above the "
                         "first row of numbers")
    header = [str(c) for c in records[header_j][1]]
    if len(header) != width:
        raise SheetError(f"{src}, {place(records[header_j][0])}: the header has {len(header)} columns, the data "
                         f"{width}" + (f" (separator {info['separator']})" if "separator" in info else ""))
    units_row = [str(c if c is not None else "") for c in records[units_j][1]] if units_j is not None else [""] * width
    rows, keys, blocks = [], [], []
    j = first
    while j < len(records):
        key, cells = records[j]
        if any(_is_numeric(c, dc) for c in cells):
            if any(str(c).strip() for c in cells[width:]):  # trailing empty cells (a closing separator) are none
                raise SheetError(f"{src}, {place(key)}: {len(cells)} cells where the header has {width} (a stray "
                                 "separator, or a value written with the separator inside it)")
            rows.append(cells)
            keys.append(key)
            j += 1
            continue
        # a row of text: a new block if the header follows within its opening lines, else a bad row
        nxt = next((m for m in range(j, min(j + _BLOCK_LOOKAHEAD, len(records)))
                    if [str(c) for c in records[m][1]] == header), None)
        if nxt is None or any(_numeric_row(records[m][1], dc) for m in range(j, nxt)):
            text = " ".join(str(c) for c in cells if str(c).strip())[:60]
            raise SheetError(f"{src}, {place(key)}: {text!r} is not a row of numbers (the data began at "
                             f"{place(records[first][0])}; a new block must repeat the header)")
        title = " ".join(str(c) for c in cells if str(c).strip())
        j = nxt + 1
        if units_j is not None and j < len(records) and not _numeric_row(records[j][1], dc):
            j += 1  # the block's own units row
        if j < len(records):
            blocks.append((len(rows), records[j][0], title))
    info = dict(info, preamble_lines=header_j, header_line=records[header_j][0],
                units_row_line=None if units_j is None else records[units_j][0], first_data_line=records[first][0],
                blocks=len(blocks) + 1)
    return Sheet(src, name, header, units_row, rows, keys, records[header_j][0],
                 None if units_j is None else records[units_j][0], blocks, info, dc, place)


# ----------------------------------------------------------------------------------------------- text layouts
def text_lines(path: Path, src: str) -> list:
    """The lines of a text file, decoded and split as grep -n numbers them; SheetError for a binary one."""
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise SheetError(f"{src}: cannot be read ({e.strerror or e})") from None
    dec = decode(raw)
    if dec is None:
        raise SheetError(f"{src}: binary file (NUL bytes or control characters), not a text table")
    return split_lines(dec[0])


def is_text(head) -> bool:
    return head is not None and decode(head) is not None


def detect_separator(lines: list) -> tuple:
    """(separator, decimal_comma, records, first): for each separator (and decimal mark), the table starts at the
    first run of rows that are fully numeric with the same width >= 2 and at least 5 rows long (or the longest
    run); the separator whose table is longest, then widest, wins."""
    kept = [(i + 1, line) for i, line in enumerate(lines) if line.strip() and not line.strip().startswith("#")]
    best = None
    for sep in _SEPARATORS:
        for dc in ((False, True) if sep != "," else (False,)):
            records = [(n, split_cells(line, sep)) for n, line in kept]
            found = first_run(records, dc)
            if found is None:
                continue
            key = (min(found[0], 5), found[1], -found[2])
            if best is None or key > best[0]:
                best = (key, sep, dc, records, found[2])
    if best is None:
        raise ValueError("no table of numbers with at least two columns found")
    return best[1:]


SEPARATOR_NAMES = {";": "semicolon", "\t": "tab", ",": "comma"}
