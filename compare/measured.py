"""Measured x(t) (e.g. a laser displacement sensor log) read from CSV and checked, ready for the spectra.

Rules: a header row names the columns; every data row must be numeric (the error gives its line number);
time must increase strictly; a step more than 3x the median step is a gap and an error (a spectrum over a
gap is not defined); smaller irregularities are resampled onto a uniform grid by linear interpolation, with
a warning that says how much they were.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["MeasuredData", "DataFileError", "read_displacement_csv", "X_UNITS"]

X_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6}
_GAP = 3.0  # a step > 3 median steps is a gap
_JITTER_OK = 1e-6  # relative step spread below which no resampling is needed


class DataFileError(ValueError):
    """A malformed data file: the message names the file, the line and the problem."""


@dataclass(frozen=True)
class MeasuredData:
    t: np.ndarray  # s, uniform
    x: np.ndarray  # m
    source: str
    resampled: bool
    warning: str | None
    n_rows: int


def read_displacement_csv(path, time_col: str | None = None, x_col: str | None = None, x_unit: str = "m") -> MeasuredData:
    """Read time [s] and displacement (``x_unit``) columns; default columns: the first two."""
    path = Path(path)
    if x_unit not in X_UNITS:
        raise DataFileError(f"x unit must be one of {', '.join(X_UNITS)} (got {x_unit!r})")
    if not path.exists():
        raise DataFileError(f"{path}: no such file")
    try:
        text = path.read_text()
    except UnicodeDecodeError:
        raise DataFileError(f"{path}: not a text file") from None
    rows = list(csv.reader(line for line in text.splitlines()))
    if not rows:
        raise DataFileError(f"{path}: empty file")
    header = [h.strip() for h in rows[0]]
    try:
        [float(h) for h in header]
        raise DataFileError(f"{path}, line 1: expected a header row naming the columns (got numbers)")
    except ValueError:
        pass
    def col(name, default):
        if name is None:
            if len(header) <= default:
                raise DataFileError(f"{path}, line 1: need at least two columns (found {len(header)})")
            return default
        if name not in header:
            raise DataFileError(f"{path}, line 1: no column {name!r}; columns are: {', '.join(header)}")
        return header.index(name)
    it, ix = col(time_col, 0), col(x_col, 1)
    t, x = [], []
    for lineno, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            continue
        try:
            tv, xv = float(row[it]), float(row[ix])
        except (ValueError, IndexError):
            raise DataFileError(f"{path}, line {lineno}: non-numeric or missing value in {row!r}") from None
        if not (math.isfinite(tv) and math.isfinite(xv)):
            raise DataFileError(f"{path}, line {lineno}: NaN or infinite value")
        if t and tv <= t[-1]:
            raise DataFileError(f"{path}, line {lineno}: time {tv!r} does not increase (previous {t[-1]!r})")
        t.append(tv)
        x.append(xv)
    if len(t) < 64:
        raise DataFileError(f"{path}: only {len(t)} data rows; need at least 64 for a spectrum")
    t = np.asarray(t)
    x = np.asarray(x) * X_UNITS[x_unit]
    steps = np.diff(t)
    med = float(np.median(steps))
    gaps = np.flatnonzero(steps > _GAP * med)
    if gaps.size:
        i = int(gaps[0])
        raise DataFileError(f"{path}, line {i + 3}: gap of {steps[i]:.4g} s after t = {t[i]:.6g} s "
                            f"({steps[i] / med:.1f} median steps); split the record at the gap")
    spread = float(np.max(np.abs(steps - med)) / med)
    warning = None
    resampled = False
    if spread > _JITTER_OK:
        n = int(round((t[-1] - t[0]) / med)) + 1
        tu = t[0] + np.arange(n) * med
        tu = tu[tu <= t[-1]]
        x = np.interp(tu, t, x)
        warning = (f"{path}: non-uniform sampling (steps deviate from the median {med:.4g} s by up to "
                   f"{100 * spread:.2g} %); resampled onto a uniform grid by linear interpolation")
        t = tu
        resampled = True
    return MeasuredData(t=t - t[0], x=x, source=str(path), resampled=resampled, warning=warning, n_rows=len(steps) + 1)
