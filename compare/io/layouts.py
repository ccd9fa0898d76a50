"""The registered layouts of :mod:`compare.io.sheets`, in the order they are tried: a folder or glob of per-stroke
files, LabVIEW TDMS, xlsx, the look program's ASCII export, delimited text (see :mod:`compare.io.sheets` for what
each reads). Imported by :mod:`compare.io.sheets`, which reads a file by them."""
from __future__ import annotations

import glob as _glob
from pathlib import Path

from .sheet import (Sheet, SheetError, detect_separator, first_run, is_pattern, is_text, SEPARATOR_NAMES,
                    tabulate, layout, text_lines)

def _needs(src, what, package, extra) -> SheetError:
    return SheetError(f"{src}: {what}; reading it needs {package} (pip install 'frictionnoise[{extra}]')")


def _unreadable(src, what, e) -> SheetError:
    return SheetError(f"{src}: not a readable {what} ({type(e).__name__}: {' '.join(str(e).split())[:160]})")


@layout("folder", "a folder or glob of per-stroke text files")
class _Folder:
    @staticmethod
    def detect(path, head):
        return head is None

    @staticmethod
    def read(path, src):
        files = sorted(_glob.glob(src)) if is_pattern(src) else sorted(
            str(f) for f in Path(path).iterdir() if f.is_file() and not f.name.startswith("."))
        if not files:
            raise SheetError(f"{src}: no files match the pattern" if is_pattern(src) else
                             f"{src}: is a folder, not a file, and holds no files (a folder of per-stroke files is "
                             "read as one record)")
        first = None
        for f in files:
            s = _Delimited.read(Path(f), f)
            if first is None:
                first = s
                rows, keys, blocks = [], [], []
            elif s.header != first.header:
                raise SheetError(f"{f}, line {s.header_key}: columns {', '.join(s.header)} differ from the first "
                                 f"file's ({Path(files[0]).name}: {', '.join(first.header)})")
            name = Path(f).name
            if rows:
                blocks.append((len(rows), (name, s.keys[0]), name))
            blocks += [(len(rows) + r, (name, k), t) for r, k, t in s.blocks]
            rows += s.rows
            keys += [(name, k) for k in s.keys]

        def place(key, col=None):
            return f"{key[0]}, line {key[1]}" if isinstance(key, tuple) else f"line {key}"

        info = dict(first.info, files=len(files))
        return Sheet(src, "folder", first.header, first.units_row, rows, keys, (Path(files[0]).name, first.header_key),
                     None if first.units_key is None else (Path(files[0]).name, first.units_key), blocks, info,
                     first.dc, place)


@layout("tdms", "LabVIEW TDMS")
class _Tdms:
    @staticmethod
    def detect(path, head):
        return head is not None and head[:4] == b"TDSm"

    @staticmethod
    def read(path, src):
        try:
            from nptdms import TdmsFile
        except ImportError:
            raise _needs(src, "a LabVIEW TDMS file", "npTDMS", "tdms") from None
        try:
            f = TdmsFile.read(str(path))
        except Exception as e:  # npTDMS raises many kinds on a damaged file; the user gets one line
            raise _unreadable(src, "TDMS file", e) from None
        for g in f.groups():
            chans = [c for c in g.channels() if len(c) > 0]
            if len(chans) >= 1 and len({len(c) for c in chans}) == 1:
                break
        else:
            raise SheetError(f"{src}: no group holds channels of one length")
        header = [c.name for c in chans]
        units = [str(c.properties.get("unit_string", "")) for c in chans]
        cols = [c[:] for c in chans]
        if not any("time" in h.lower() for h in header) and "wf_increment" in chans[0].properties:
            import numpy as np

            dt = float(chans[0].properties["wf_increment"])
            header, units = ["time"] + header, ["s"] + units
            cols = [float(chans[0].properties.get("wf_start_offset", 0.0)) + dt * np.arange(len(cols[0]))] + cols
        names = header

        def place(key, col=None):
            what = "its properties" if key == "properties" else f"value {key + 1}"
            return f"group {g.name!r}" + (f", {what}" if col is None else f", channel {names[col]!r}, {what}")

        rows = [list(r) for r in zip(*cols)]
        return Sheet(src, "tdms", header, units, rows, list(range(len(rows))), "properties", "properties", [],
                     {"group": g.name, "channels": len(header)}, False, place)


@layout("xlsx", "an xlsx workbook")
class _Xlsx:
    @staticmethod
    def detect(path, head):
        if head is None or head[:4] != b"PK\x03\x04":
            return False
        import zipfile

        try:
            with zipfile.ZipFile(path) as z:
                return any(n.startswith("xl/") for n in z.namelist())
        except (zipfile.BadZipFile, OSError):
            return False

    @staticmethod
    def read(path, src):
        try:
            import openpyxl
            from openpyxl.utils import get_column_letter
        except ImportError:
            raise _needs(src, "an xlsx workbook", "openpyxl", "xlsx") from None
        try:
            wb = openpyxl.load_workbook(path, read_only=True, data_only=True)
        except Exception as e:  # openpyxl raises many kinds on a damaged workbook
            raise _unreadable(src, "xlsx workbook", e) from None
        errors = []
        for ws in wb.worksheets:
            records = []
            for r, row in enumerate(ws.iter_rows(values_only=True), 1):
                cells = ["" if c is None else c for c in row]
                while cells and cells[-1] == "":
                    cells.pop()
                if cells:
                    records.append((r, cells))
            found = first_run(records, False)
            if found is None:
                errors.append(ws.title)
                continue
            title = ws.title

            def place(key, col=None, title=title):
                return f"sheet {title!r}, " + (f"row {key}" if col is None else f"cell {get_column_letter(col + 1)}{key}")

            return tabulate(src, "xlsx", records, found[2], False, place, {"sheet": title})
        raise SheetError(f"{src}: no table of numbers with at least two columns on any sheet "
                         f"({', '.join(repr(t) for t in errors)})")


@layout("look-ascii", "the look program's ASCII export")
class _LookAscii:
    @staticmethod
    def detect(path, head):
        return is_text(head) and b"number of records" in head.lower()

    @staticmethod
    def read(path, src):
        lines = text_lines(path, src)
        at = next((i for i, ln in enumerate(lines) if "number of records" in ln.lower()), None)
        if at is None:
            raise SheetError(f"{src}: no 'number of records = N' line")
        try:
            n = int(lines[at].split("=", 1)[1].strip())
        except (IndexError, ValueError):
            raise SheetError(f"{src}, line {at + 1}: expected 'number of records = N', got {lines[at].strip()!r}") from None
        rest = [(i + 1, ln.split()) for i, ln in enumerate(lines) if i > at and ln.strip()]
        if len(rest) < 4:
            raise SheetError(f"{src}, line {at + 1}: names, units and recs rows expected after it")
        (hn, names), (un, units), (rn, recs) = rest[:3]
        strip = (lambda cells, label: cells[1:] if cells and cells[0].lower().rstrip(":") == label else cells)
        names, units, recs = strip(names, "name"), strip(units, "units"), strip(recs, "recs")
        if not (len(names) == len(units) == len(recs)):
            raise SheetError(f"{src}, line {un}: {len(names)} names, {len(units)} units and {len(recs)} record "
                             "counts; the look export writes one of each per column")
        units = ["" if u.lower() in ("no_units", "none", "-") else u for u in units]
        data = rest[3:]
        if len(data) != n:
            raise SheetError(f"{src}, line {at + 1}: number of records = {n} but {len(data)} data rows follow")
        return Sheet(src, "look-ascii", names, units, [c for _, c in data], [k for k, _ in data], hn, un, [],
                     {"records": n, "header_line": hn, "units_row_line": un, "first_data_line": data[0][0]}, False)


@layout("delimited", "delimited text")
class _Delimited:
    @staticmethod
    def detect(path, head):
        return is_text(head)

    @staticmethod
    def read(path, src):
        lines = text_lines(path, src)
        try:
            sep, dc, records, first = detect_separator(lines)
        except ValueError as e:
            raise SheetError(f"{src}: {e}") from None
        sheet = tabulate(src, "delimited", records, first, dc, lambda key, col=None: f"line {key}",
                         {"separator": SEPARATOR_NAMES[sep], "decimal_comma": dc})
        # the preamble as the file holds it: every non-blank line above the header, "#" comment lines included
        # (the table's records leave those out)
        above = [line for line in lines[:sheet.header_key - 1] if line.strip()]
        sheet.info.update(preamble_lines=len(above),
                          comment_lines=sum(1 for line in above if line.strip().startswith("#")))
        return sheet
