"""Line scans as instruments write them: a profile file read into positions and heights in metres, with the units
the file states and the line of any problem.

Text exports (stylus profilometers, confocal and white-light microscopes, AFM software) are tables of position and
height after a preamble of scan parameters, often latin-1 (the micro sign) with CR or CRLF line ends, units in the
column header (``Lateral(µm)``, ``Total Profile (Å)``, ``x [mm]``, ``x_mm``) and empty trailing columns. They are
read here by a small table reader that knows where every number came from, so that an error names the line
(:class:`ProfileError`). SurfaceTopography (``SurfaceTopography.read_topography``, Pastewka group, MIT), the field's
reference reader, reads the same exports but cannot say where a problem is and misreads bad files without a word:
a non-number in the data makes its text reader skip everything above it as a header, a height column in an unknown
unit is read in the lateral unit, and positions in metres pass its uniform-grid test (an absolute tolerance of 1e-6
file units) whatever their order. It is used for what the table reader cannot do: binary formats (Dektak OPDx,
Keyence VK, Zygo, X3P, SUR, ...: every format ``read_topography`` knows) and the units of text headers it knows
(Gwyddion's ``# Lateral units:`` lines, HFM). It is an optional dependency (``pip install 'frictionnoise[profiles]'``):
a plain table or a profilometer CSV needs nothing beyond numpy, and a file that needs it says so.

NPY files hold an array of shape (n, 2) or (2, n): positions and heights, in the units the scenario declares (an
NPY file states none).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .quantities import UnitError, parse_unit, split_header
from .text_file import decode, split_lines

__all__ = ["ProfileError", "LineScanFile", "read_line_scan", "unit_factor"]

_MIN_POINTS = 8


class ProfileError(ValueError):
    """A profile file that cannot be used: one line naming the file, and the line of the file where it can."""


@dataclass(frozen=True)
class LineScanFile:
    """A line scan as read: positions ``x`` and heights ``h`` (m, as in the file: not shifted, not sorted), where
    each unit came from (``x_unit_from``, ``height_unit_from``), the reader and the preamble's key-value pairs."""

    path: str
    x: np.ndarray
    h: np.ndarray
    x_unit: str
    height_unit: str
    x_unit_from: str
    height_unit_from: str
    reader: str
    data_lines: tuple = ()  # (first, last) line numbers of the data in a text file
    metadata: dict = field(default_factory=dict)
    spacing: float | None = None  # the point spacing (m) the preamble states, if it states one
    sha256: str = ""  # of the file's bytes


_SPACING_KEYS = re.compile(r"^(resolution|spacing|sampling interval|x[ _-]?step|step size|x[ _-]?spacing|dx)\b",
                           re.IGNORECASE)
_PER_POINT = re.compile(r"\s*/\s*(pt|point|pts|points|sample)\s*$", re.IGNORECASE)


def spacing_from_metadata(meta: dict):
    """The point spacing (m) a preamble states (``Resolution,0.156,µm/pt``, ``Spacing: 20 nm``), or None."""
    for key, value in meta.items():
        if not _SPACING_KEYS.match(str(key).strip()):
            continue
        parts = str(value).replace(",", " ").split(None, 1)
        if len(parts) != 2:
            continue
        try:
            number = float(parts[0])
            unit = parse_unit(_PER_POINT.sub("", parts[1]).strip(), "length")
        except (ValueError, UnitError):
            continue
        if number > 0:
            return number * unit.factor
    return None


def unit_factor(unit: str) -> float:
    """Metres per ``unit`` (any length unit pint reads, :mod:`engine_sim.quantities`; a UnitError otherwise)."""
    return parse_unit(unit, "length").factor


def _fail(path, msg, line=None):
    where = f"{path}: line {line}: " if line is not None else f"{path}: "
    return ProfileError(where + msg)


# ----------------------------------------------------------------------------------------------------- text tables
_SEP = re.compile(r"\s*[,;\t]\s*|\s+")


def _cells(line: str) -> list:
    """The cells of a row: split at commas, semicolons, tabs or runs of spaces; empty cells at its end dropped."""
    cells = _SEP.split(line.strip())
    while cells and cells[-1] == "":
        cells.pop()
    return cells


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _numbers(cells) -> tuple | None:
    if len(cells) < 2:
        return None
    try:
        return float(cells[0]), float(cells[1])
    except ValueError:
        return None


def _unit_in_name(name: str):
    """(unit, unknown) stated by a column name (:func:`engine_sim.quantities.split_header`): a bracketed unit
    ('Lateral(µm)', 'z [nm]') or a trailing one ('x_mm', 'Lateral um', 'Raw Micrometer'); ``unknown`` is a stated
    unit that is not a length ('Height (V)')."""
    _, unit, _ = split_header(name)
    if unit is None:
        return None, None
    try:
        parse_unit(unit, "length")
    except UnitError:
        return None, unit
    return unit, None


def _read_table(path: Path, text: str, encoding: str):
    """Positions and heights (file units), their line numbers, the header line and the preamble of a text table."""
    lines = split_lines(text)  # numbered as grep -n numbers them (CR CR LF is one line end)
    rows, nums, first = [], [], None
    preamble = []
    for i, line in enumerate(lines, 1):
        cells = _cells(line)
        if not cells:
            continue
        v = _numbers(cells)
        if first is None:
            if v is not None and any(_numbers(_cells(nxt)) is not None for nxt in _next_nonempty(lines, i)):
                first = i
            else:
                preamble.append((i, line.strip(), cells))
                continue
        if v is None:
            raise _fail(path, f"{line.strip()[:60]!r} is not a position and a height (the data began at line "
                              f"{first})", i)
        rows.append(i)
        nums.append(v)
    if first is None:
        single = [(i, s) for i, s, c in preamble if _numbers(c) is not None]
        if single:
            raise _fail(path, f"one point ({single[0][1][:40]!r}); a line scan needs at least {_MIN_POINTS}",
                        single[0][0])
        ones = [i for i, _, c in preamble if len(c) == 1 and _is_number(c[0])]
        if len(ones) >= _MIN_POINTS:
            raise _fail(path, f"one column of numbers (from line {ones[0]}); a line scan needs two, positions and "
                              "heights", ones[0])
        raise _fail(path, f"no rows of numbers (read as {encoding} text, {len(lines)} lines)")
    # names and values may hold spaces: the header and the preamble are split at the data's own delimiter
    delim = next((d for d in ",;\t" if d in lines[first - 1]), None)

    def split(s, cells):
        out = [c.strip() for c in s.split(delim)] if delim else cells
        while out and out[-1] == "":
            out.pop()
        return out

    preamble = [(i, s, split(s, c)) for i, s, c in preamble]
    header = preamble[-1] if preamble else None
    meta = {c[0]: " ".join(c[1:]) for _, _, c in preamble[:-1] if len(c) >= 2}
    return np.array(nums, dtype=float), np.array(rows), header, meta


def _next_nonempty(lines, i):
    """The first non-empty line after line i (1-based), as a one-element list (or none)."""
    for line in lines[i:]:
        if line.strip():
            return [line]
    return []


def _header_units(path, header):
    """Units the header line states for the two columns: [(unit or None), (unit or None)]."""
    if header is None:
        return [None, None]
    line, _, cells = header
    out = []
    for col, name in enumerate(cells[:2]):
        unit, unknown = _unit_in_name(name)
        if unknown is not None:
            raise _fail(path, f"column {col + 1} ({name!r}) is in {unknown!r}, not a length unit (any length unit "
                              "pint reads: m, mm, um, µm, nm, A, in, ...)", line)
        out.append(unit)
    return out + [None] * (2 - len(out))


# ------------------------------------------------------------------------------------------- SurfaceTopography
def _surface_topography(path: Path, why: str):
    try:
        from SurfaceTopography import read_topography
    except ImportError:
        raise _fail(path, f"{why}; reading it needs SurfaceTopography (pip install 'frictionnoise[profiles]' or "
                          "pip install SurfaceTopography)") from None
    import warnings

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t = read_topography(str(path))
    except Exception as e:  # its readers raise many kinds; one line is what the user gets
        msg = " ".join(str(e).split())
        raise _fail(path, f"SurfaceTopography cannot read it ({type(e).__name__}: {msg[:200]})") from None
    return t


def _st_units(path: Path):
    """SurfaceTopography's lateral unit for a text file whose header names none (its readers know instrument
    headers such as Gwyddion's '# Lateral units:'), or None if it is not installed or finds none."""
    try:
        import SurfaceTopography  # noqa: F401
    except ImportError:
        return None
    try:
        t = _surface_topography(path, "")
    except ProfileError:
        return None
    return t.unit


# ----------------------------------------------------------------------------------------------------- the reader
def _length_factor(unit: str) -> float:
    """Metres per ``unit`` (engine_sim.quantities: any length unit pint reads; A is the angstrom)."""
    return parse_unit(unit, "length").factor


def _resolve_unit(path, what, file_unit, declared, line):
    field_name = "x_unit" if what == "positions" else "height_unit"
    if file_unit is not None:
        try:
            _length_factor(file_unit)
        except UnitError as e:
            raise _fail(path, f"the file gives the {what} in {file_unit!r}: {e.reason}", line) from None
    if file_unit is not None:
        if declared and not np.isclose(_length_factor(declared), _length_factor(file_unit), rtol=1e-12, atol=0):
            raise _fail(path, f"the header gives the {what} in {file_unit} but substrate.{field_name} = "
                              f"{declared!r}; remove substrate.{field_name} or correct it", line)
        return file_unit, f"the file (line {line})"
    if declared:
        return declared, f"substrate.{field_name}"
    raise _fail(path, f"no unit for the {what}: the file states none; set substrate.{field_name} (m, mm, um, nm)",
                line)


def read_line_scan(path, x_unit: str = "", height_unit: str = "") -> LineScanFile:
    """Read a line scan: positions and heights in metres.

    Parameters
    ----------
    path : str or Path
        The profile: a text export (any preamble; columns position, height, more columns ignored), an NPY array
        of shape (n, 2) or (2, n), or any line scan SurfaceTopography reads.
    x_unit, height_unit : str
        Units of the two columns ("" if the file states them); a unit the file states wins only if it agrees.

    Returns
    -------
    LineScanFile
        Raw positions and heights (m), at least 8 points, finite, positions strictly increasing.

    Raises
    ------
    ProfileError
        One line naming the file and, for a text file, the line: no rows of numbers, one point, a non-number in the
        data, NaN heights, positions not increasing, an unknown unit or no unit at all.
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise _fail(path, f"cannot be read ({e.strerror or e})") from None
    rows = None
    if path.suffix.lower() == ".npy":
        try:
            arr = np.load(path, allow_pickle=False)
        except (ValueError, OSError) as e:
            raise _fail(path, f"not a readable NPY array ({e})") from None
        arr = arr.T if arr.ndim == 2 and arr.shape[0] == 2 and arr.shape[1] != 2 else arr
        if arr.ndim != 2 or arr.shape[1] != 2:
            raise _fail(path, f"expected two columns x, h (got an array of shape {arr.shape})")
        xu, xfrom = _resolve_unit(path, "positions", None, x_unit, None)
        hu, hfrom = _resolve_unit(path, "heights", None, height_unit, None)
        xy, reader, meta = arr.astype(float), "numpy (.npy)", {}
    else:
        dec = decode(raw)
        if dec is None:  # a binary instrument format
            t = _surface_topography(path, "not a text table")
            if t.dim != 1:
                raise _fail(path, f"a {t.dim}D topography of {t.nb_grid_pts} points; line_scan needs a line scan")
            unit = t.unit
            if unit is None and not (x_unit and height_unit):
                raise _fail(path, "the file states no unit; set substrate.x_unit and substrate.height_unit")
            xu, xfrom = _resolve_unit(path, "positions", unit, x_unit, None)
            hu, hfrom = _resolve_unit(path, "heights", unit, height_unit, None)
            xfrom = hfrom = f"the file ({type(t).__name__} of SurfaceTopography)"
            xy = np.column_stack([np.asarray(t.positions(), float), np.asarray(t.heights(), float)])
            reader, meta = f"SurfaceTopography {t.info.get('source', '')}".strip(), dict(t.info.get("raw_metadata", {}))
        else:
            text, enc = dec
            xy, rows, header, meta = _read_table(path, text, enc)
            hline = header[0] if header else None
            fx, fh = _header_units(path, header)
            if fx is None and not x_unit:
                fx = _st_units(path)
                if fx is not None:
                    hline = "header, read by SurfaceTopography"
                    fh = fh or fx
            xu, xfrom = _resolve_unit(path, "positions", fx, x_unit, hline)
            hu, hfrom = _resolve_unit(path, "heights", fh, height_unit, hline)
            reader = f"table ({enc} text, data lines {rows[0]}-{rows[-1]})"
    x, h = xy[:, 0] * _length_factor(xu), xy[:, 1] * _length_factor(hu)
    where = (lambda i: int(rows[i])) if rows is not None else (lambda i: None)
    point = (lambda i: "") if rows is not None else (lambda i: f"point {i + 1}: ")
    if x.size < _MIN_POINTS:
        raise _fail(path, f"{x.size} point{'s' if x.size != 1 else ''}; a line scan needs at least {_MIN_POINTS}",
                    where(0))
    bad = np.flatnonzero(~np.isfinite(h))
    if bad.size:
        raise _fail(path, f"{point(bad[0])}height {xy[bad[0], 1]:g} is not a number ({bad.size} of "
                          f"{h.size} heights); fill or cut the gaps before using the scan", where(bad[0]))
    bad = np.flatnonzero(~np.isfinite(x))
    if bad.size:
        raise _fail(path, f"{point(bad[0])}position {xy[bad[0], 0]:g} is not a number", where(bad[0]))
    back = np.flatnonzero(np.diff(x) <= 0)
    if back.size:
        i = back[0] + 1
        raise _fail(path, f"{point(i)}position {xy[i, 0]:g} does not increase (previous {xy[i - 1, 0]:g}; "
                          f"{back.size} of {x.size - 1} steps); positions must increase strictly", where(i))
    import hashlib

    return LineScanFile(str(path), x, h, xu, hu, xfrom, hfrom, reader,
                        (int(rows[0]), int(rows[-1])) if rows is not None else (), meta,
                        spacing_from_metadata(meta), hashlib.sha256(raw).hexdigest())
