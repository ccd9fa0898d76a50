"""Measured tables as rigs write them, read by layout into one :class:`Sheet`: a header, an optional units row,
rows of cells and the blocks they fall in, each row with the place it came from (a line of a text file, a cell of
a workbook, a value of a TDMS channel), so that every refusal names the file and the place.

Layouts are registered (:data:`LAYOUTS`, :func:`layout` and :class:`Sheet`, from :mod:`compare.io.sheet`; the
readers are in :mod:`compare.io.layouts`, imported here): each says from a file's first bytes whether it reads it, and
reads it. Text layouts share one decoder and line splitter (:mod:`engine_sim.text_file`: UTF-8, UTF-16 with a BOM,
latin-1; LF, CRLF, CR CR LF or CR ends; lines numbered as ``grep -n`` numbers them).

- ``delimited``: ``,``, ``;`` or tab separated text after any preamble; a header row, an optional units row of
  any units (a trailing empty cell for a unitless column), decimal commas with ``;`` or tab; several blocks, each
  opened by lines of text and the same header again (a CETR/Bruker UMT export's "Step No. 2"), read as segments.
- ``look-ascii``: the ASCII export of the look program of rock-friction laboratories (xlook): a
  ``number of records = N`` line, then rows of names, units and record counts, then whitespace-separated data.
- ``folder``: a folder, or a glob pattern, of per-stroke text files with the same columns: one record, a block
  per file (in name order).
- ``xlsx``: the first worksheet holding a table (openpyxl: ``pip install 'frictionnoise[xlsx]'``).
- ``tdms``: LabVIEW TDMS, the first group of channels of one length (npTDMS: ``pip install
  'frictionnoise[tdms]'``); a waveform's time from its ``wf_increment`` when no channel holds time.
"""
from __future__ import annotations

from pathlib import Path

from . import layouts  # noqa: F401  (registers the readers, in the order they are tried)
from .sheet import LAYOUTS, Layout, Sheet, SheetError, is_pattern, layout, to_float

__all__ = ["Sheet", "Layout", "LAYOUTS", "layout", "read_sheet", "SheetError", "binary_layout", "is_many", "to_float"]


def read_sheet(path) -> Sheet:
    """The table in ``path`` (a file, a folder or a glob pattern), read by the first registered layout that
    detects it; a :class:`SheetError` naming the file and the place for what cannot be read."""
    src = str(path)
    p = Path(path)
    if is_pattern(src) or p.is_dir():
        head = None
    else:
        if not p.exists():
            raise SheetError(f"{src}: no such file")
        try:
            with open(p, "rb") as fh:
                head = fh.read(4096)
        except OSError as e:
            raise SheetError(f"{src}: cannot be read ({e.strerror or e})") from None
        if not head.strip():
            raise SheetError(f"{src}: empty file")
    for lay in LAYOUTS.values():
        if lay.detect(p, head):
            return lay.read(p, src)
    raise SheetError(f"{src}: binary data in no layout this reader knows ("
                     + ", ".join(lay.what for lay in LAYOUTS.values()) + ")")


def binary_layout(path) -> str | None:
    """The name of the registered binary layout (xlsx, tdms) that reads the file ``path``, else None."""
    p = Path(path)
    try:
        with open(p, "rb") as fh:
            head = fh.read(4096)
    except OSError:
        return None
    for name in ("tdms", "xlsx"):
        if LAYOUTS[name].detect(p, head):
            return name
    return None


def is_many(path) -> bool:
    """Whether ``path`` names several files: a folder or a glob pattern."""
    return is_pattern(str(path)) or Path(path).is_dir()
