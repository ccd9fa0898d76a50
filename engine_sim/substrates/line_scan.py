"""A measured line scan as the pads' tracks: heights against position from a CSV or NPY file, units declared,
resampled to a uniform grid, detrended on request, and mirrored or tiled to any sliding distance.

This module is the whole of the kind (spec, checks, build, streamed track): with its import line in
``substrates/__init__.py`` and a scenario file (``scenarios/line_scan_example.toml``) it is the extension point
the README's architecture section describes.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path

import numpy as np

from .. import units as U
from ..substrate import StreamedTrack
from . import SUBSTRATES, Substrate, SubstrateSpec
from .self_affine import sliding_limit

__all__ = ["LineScanSpec", "LineScan", "read_profile", "ProfileTrack"]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}  # metres per unit


@dataclass(frozen=True)
class LineScanSpec(SubstrateSpec):
    """file: the profile, two columns x and h (a CSV with an optional header row, or an NPY array of shape (n, 2));
    a relative name is looked up beside the scenario file, then in the shipped ``scenarios/profiles/``.
    x_unit, height_unit: "m", "mm", "um" or "nm". dx: resampling step (m; 0: the file's mean spacing), by linear
    interpolation. detrend: "linear" (least-squares line removed), "mean" or "none". extend: "mirror" (the profile,
    then its reflection, repeated: no step at the joins) or "tile" (repeated as is). Every pad's track is the same
    profile entered at its own random place (its own random stream), so the pads' forces are not in step.
    ``a`` is the renewal length used for the fit band."""

    kind: str = "line_scan"
    file: str = ""
    x_unit: str = "m"
    height_unit: str = "m"
    dx: float = 0.0
    detrend: str = "linear"
    extend: str = "mirror"


def _read_xy(path: Path) -> np.ndarray:
    if path.suffix.lower() == ".npy":
        arr = np.load(path, allow_pickle=False)
        arr = arr.T if arr.ndim == 2 and arr.shape[0] == 2 and arr.shape[1] != 2 else arr
    else:
        rows = []
        for n, line in enumerate(path.read_text().splitlines(), 1):
            cells = [c for c in line.replace(";", ",").replace("\t", ",").split(",") if c.strip()]
            if not cells or line.lstrip().startswith("#"):
                continue
            try:
                rows.append([float(c) for c in cells[:2]])
            except ValueError:
                if rows:
                    raise ValueError(f"{path}: line {n} is not two numbers: {line.strip()[:60]!r}") from None
                continue  # a header row
        arr = np.array(rows, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{path}: expected two columns x, h (got shape {arr.shape})")
    return arr


@functools.lru_cache(maxsize=8)
def _profile(path: str, mtime: float, x_unit: str, height_unit: str, dx: float, detrend: str):
    xy = _read_xy(Path(path))
    x, h = xy[:, 0] * _UNITS[x_unit], xy[:, 1] * _UNITS[height_unit]
    if x.size < 8 or not np.all(np.isfinite(xy)) or not np.all(np.diff(x) > 0):
        raise ValueError(f"{path}: needs at least 8 finite rows with x strictly increasing")
    step = dx if dx > 0 else (x[-1] - x[0]) / (x.size - 1)
    grid = x[0] + step * np.arange(int(np.floor((x[-1] - x[0]) / step + 1e-9)) + 1)
    hr = np.interp(grid, x, h)
    if detrend == "linear":
        hr = hr - np.polyval(np.polyfit(grid - grid[0], hr, 1), grid - grid[0])
    elif detrend == "mean":
        hr = hr - hr.mean()
    hr.setflags(write=False)
    return float(step), hr


def read_profile(spec: LineScanSpec):
    """(dx, heights) in metres: the spec's file resampled to a uniform grid and detrended (cached per file)."""
    p = Path(spec.file)
    return _profile(str(p), p.stat().st_mtime, spec.x_unit, spec.height_unit, spec.dx, spec.detrend)


def _find(name: str, where: str) -> Path:
    p = Path(name)
    if p.is_absolute():
        return p
    places = ([Path(where).parent] if where else []) + [Path.cwd(), Path(str(resources.files("scenarios"))) / "profiles"]
    for base in places:
        if (base / p).exists():
            return (base / p).resolve()
    raise ValueError(f"substrate.file = {name!r}: not found beside the scenario, in the current folder or among the "
                     "shipped profiles (scenarios/profiles/)")


@SUBSTRATES.register
class LineScan(Substrate):
    name = "line_scan"
    Spec = LineScanSpec
    non_negative = frozenset({"dx"})
    quick_duration = 8.0  # streaming its short segments costs about 1 wall s per simulated s
    choices = {"x_unit": tuple(_UNITS), "height_unit": tuple(_UNITS), "detrend": ("linear", "mean", "none"),
               "extend": ("mirror", "tile")}

    @classmethod
    def prepare(cls, spec, where=""):
        if not spec.file:
            raise ValueError("substrate.file must name the profile (CSV or NPY) of a line_scan substrate")
        return replace(spec, file=str(_find(spec.file, where)))

    @classmethod
    def validate(cls, s, sc, where=""):
        try:
            dx, h = read_profile(s)
        except OSError as e:
            raise ValueError(f"substrate.file = {s.file!r}: cannot be read ({e.strerror or e})") from None
        slope = float(np.sqrt(np.mean(np.diff(h) ** 2)) / dx)
        limit = sliding_limit(sc.friction.mu0)
        if slope > limit:
            raise ValueError(f"substrate.file {s.file!r}: rms slope {slope:.3g} (at dx = {dx:.3g} m) exceeds the sliding "
                             f"limit {limit:.3g} = 1/(6 mu0); resample coarser (substrate.dx) or lower friction.mu0")
        if dx > 2 * sc.pads.radius:
            raise ValueError(f"substrate.dx = {dx:.3g} m is coarser than a pad (diameter {2 * sc.pads.radius:.3g} m)")

    def __init__(self, spec, scenario):
        super().__init__(spec, scenario)
        dx, h = read_profile(spec)
        self.dx, self.h = dx * U.LENGTH, h * U.LENGTH

    def build(self, space, y, shape_filter, rng, mu, x_start):
        return ProfileTrack(space, y, self.h, self.dx, self.spec.extend, mu, self.spec.segment_radius * U.LENGTH,
                            shape_filter, rng, x_start)


class ProfileTrack(StreamedTrack):
    """A fixed profile streamed as straight segments between its grid points (scene units), continued without end
    by mirroring or tiling, entered at a random index; consecutive segments linked with set_neighbors."""

    def __init__(self, space, y, heights, dx, extend, mu, radius, shape_filter, rng, x_start, chunk_points=64):
        self._init_stream(space, shape_filter, rng)
        self.y, self.h, self.dx, self.mu0, self.radius, self.chunk = y, heights, dx, mu, radius, chunk_points
        n = heights.size
        self.period = 2 * (n - 1) if extend == "mirror" else n
        self.mirror = extend == "mirror"
        self.entry = self._j = int(rng.integers(self.period))  # where this track enters the profile
        self._x_next = x_start
        self._last = None

    def _frontier(self):
        return self._x_next

    def _heights(self, j0: int, m: int) -> np.ndarray:
        k = (j0 + np.arange(m)) % self.period
        if self.mirror:
            k = np.where(k < self.h.size, k, self.period - k)
        return self.h[k]

    def _extend(self):
        xs = self._x_next + self.dx * np.arange(self.chunk)
        self._add_polyline([(float(a), float(self.y + b)) for a, b in zip(xs, self._heights(self._j, self.chunk))])
        self._j += self.chunk
        self._x_next = float(xs[-1] + self.dx)
