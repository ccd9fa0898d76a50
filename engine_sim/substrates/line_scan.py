"""A measured line scan as the pads' tracks: heights against position as an instrument exports them (read by
:mod:`engine_sim.profile_file`, with the units the file states), on a uniform grid, detrended on request, reduced to
what a pad can feel of it (:func:`read_profile`: closed by the pad's disc and resampled at the coarsest spacing
that leaves the pad's path within the contact's resolution), and mirrored or tiled to any sliding distance.

This module is the whole of the kind (spec, checks, build, streamed track): with its import line in
``substrates/__init__.py`` and a scenario file (``engine_sim/scenarios/line_scan_example.toml``) it is the
extension point the README's architecture section describes.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..profile_file import ProfileError, read_line_scan
from ..shipped import SCENARIO_DIR
from ..substrate import StreamedTrack
from .substrate import SUBSTRATES, Substrate, SubstrateSpec
from .self_affine import sliding_limit

__all__ = ["LineScanSpec", "LineScan", "read_profile", "TrackProfile", "ProfileTrack", "pad_path", "pad_closing"]

_UNITS = ("", "m", "mm", "um", "µm", "nm", "A", "Å")  # "": the unit the file states

# the contact solver's slop (Scene.slop, 1e-4 mm): pymunk leaves overlaps below it uncorrected, so heights the
# pad's path changes by less than this are below what the scene resolves
CONTACT_SLOP = 1e-7  # m
_FILLED = 1e-3  # a point the pad's closing raises by more than this fraction of the tolerance counts as filled
_EVAL_POINTS = 1 << 17  # the spacing rule is judged on at most this many points of the profile (cost bound)
_CLOSING_WORK = 4e8  # points x disc width above which a profile is first pooled to its bins' maxima (cost bound)
# segments a track may hold over the stretch the scene keeps around its pad (Substrate.margins: 4 pad radii ahead,
# 2 behind): the spacing is never finer than 6 R / TRACK_SEGMENTS, so a track's set-up lays at most this many
# segments however fine the file's grid (pymunk adds some 10^5 static segments a second)
TRACK_SEGMENTS = 20_000
_KEPT_RADII = 6.0


@dataclass(frozen=True)
class LineScanSpec(SubstrateSpec):
    """file: the profile (an instrument's text export with its preamble and units, an NPY array of shape (n, 2),
    or any line scan SurfaceTopography reads; see :mod:`engine_sim.profile_file`); a relative name is looked up
    beside the scenario file, then in the current folder, then in the shipped ``scenarios/profiles/`` (also when
    written ``scenarios/profiles/<file>``).
    x_unit, height_unit: the columns' units ("m", "mm", "um", "nm", "A"), or "" for the units the file states
    (a unit the file states and a different one declared here is an error). dx: the track's grid spacing (m);
    0: the coarsest spacing the pads cannot tell from the file's (see :func:`pad_profile`). path_tolerance (m):
    how far (rms) the pad's path over the resampled track may stray from its path over the file's profile (default:
    the contact solver's slop, 0.1 um). detrend: "linear" (least-squares line removed), "mean" or "none".
    extend: "mirror" (the profile, then its reflection, repeated: no step at the joins) or "tile" (repeated as is).
    short_scan: what to do with a scan shorter than a pad's diameter or the renewal length ``a``: "refuse" (an
    error naming both lengths) or "repeat" (the scan repeated by ``extend`` until it is long enough, with a
    warning: a pad then slides over the same few points again and again). Every pad's track is the same profile entered at its own random place (its own random stream), so the pads'
    forces are not in step. ``a`` is the renewal length used for the fit band."""

    kind: str = "line_scan"
    file: str = ""
    x_unit: str = ""
    height_unit: str = ""
    dx: float = 0.0
    path_tolerance: float = CONTACT_SLOP
    detrend: str = "linear"
    extend: str = "mirror"
    short_scan: str = "refuse"


# ------------------------------------------------------------------------------------ what a pad can feel of a profile
def _disc(radius: float, dx: float, reach: float) -> np.ndarray:
    """The lower half of a disc of ``radius`` as a structuring element on a grid of spacing dx, out to ``reach``
    either side: s(y) = sqrt(R^2 - y^2) - R (m; 0 at its centre)."""
    m = int(min(radius, reach) / dx)
    y = np.arange(-m, m + 1) * dx
    return np.sqrt(radius**2 - y**2) - radius


def _reach(radius: float, h: np.ndarray) -> float:
    """How far either side of a point a disc of ``radius`` resting on the profile can touch it: beyond
    y* = sqrt(2 R p - p^2), p the profile's peak-to-valley height, the disc's edge is higher above its lowest point
    than any height difference on the profile, so no point there can hold it up."""
    p = float(np.ptp(h)) if h.size else 0.0
    return radius if p >= radius else float(np.sqrt(2 * radius * p - p * p))


_MODES = {"mirror": "mirror", "tile": "wrap"}  # how the profile continues past its ends, as the track continues it


def pad_path(h: np.ndarray, dx: float, radius: float, extend: str = "mirror") -> np.ndarray:
    """Height of the lowest point of a rigid disc of ``radius`` resting on the profile h (grid spacing dx), above
    each grid point: the morphological dilation max_y [h(x - y) + sqrt(R^2 - y^2) - R] over |y| <= R (m), the
    profile continued past its ends as the track continues it (``extend``: "mirror" or "tile")."""
    from scipy import ndimage

    return ndimage.grey_dilation(h, structure=_disc(radius, dx, _reach(radius, h)), mode=_MODES[extend])


def pad_closing(h: np.ndarray, dx: float, radius: float, extend: str = "mirror") -> np.ndarray:
    """The profile as a rigid disc of ``radius`` touches it: the morphological closing of h by the disc (dilation,
    then erosion by the same disc). Valleys narrower than the disc are filled with arcs of its radius; where the
    disc touches, the profile is unchanged. A disc's path over the closing is its path over h (the closing is the
    largest profile with that path), which is why a stylus tip's and a pad's tracing are the same operation."""
    from scipy import ndimage

    s, mode = _disc(radius, dx, _reach(radius, h)), _MODES[extend]
    return ndimage.grey_erosion(ndimage.grey_dilation(h, structure=s, mode=mode), structure=s, mode=mode)


def _path_error(closed: np.ndarray, path: np.ndarray, k: int, dx: float, radius: float, margin: int,
                extend: str) -> float:
    """rms (m) of the disc's path over every k-th point of the closing (linear between them) less its path over
    the profile, away from the ends (margin points) where the disc leaves the profile."""
    idx = np.arange(closed.size)
    back = np.interp(idx, idx[::k], closed[::k])
    last = (closed.size - 1) // k * k  # beyond the last kept point the interpolation is flat
    hi = min(last, closed.size - margin)
    if hi - margin < 2 * k:
        return float("inf")
    d = pad_path(back, dx, radius, extend)[margin:hi] - path[margin:hi]
    return float(np.sqrt(np.mean(d * d)))


@dataclass(frozen=True)
class TrackProfile:
    """A profile as the track uses it: grid spacing ``dx`` (m), heights ``h`` (m, read-only), the file's spacing
    ``native_dx``, the rms change of a pad's path ``path_error`` (m) and ``note``, one line saying what was done."""

    dx: float
    h: np.ndarray
    native_dx: float
    path_error: float
    note: str
    sha256: str = ""  # of the profile file's bytes


def _spacing_from_pad(closed, path, dx, radius, tol, cap, extend):
    """The largest k (grid spacing k dx <= cap) whose path error is at most tol, by bisection (the error grows
    with k, up to the profile's own irregularity), and that error. k is also bounded by what the profile can
    judge (two kept points inside its margins), so the error returned is always finite."""
    margin = int(_reach(radius, closed) / dx) + 1
    k_hi = max(1, min(int(cap / dx), (min(closed.size, path.size) - 2 * margin - 1) // 2))
    if k_hi == 1:
        return 1, 0.0
    err = {1: 0.0}
    if _path_error(closed, path, k_hi, dx, radius, margin, extend) <= tol:
        return k_hi, _path_error(closed, path, k_hi, dx, radius, margin, extend)
    lo, hi = 1, k_hi  # err(lo) <= tol < err(hi)
    while hi - lo > 1:
        mid = int(round(np.sqrt(lo * hi))) if hi > 2 * lo else (lo + hi) // 2
        mid = min(max(mid, lo + 1), hi - 1)
        e = _path_error(closed, path, mid, dx, radius, margin, extend)
        if e <= tol:
            lo, err[mid] = mid, e
        else:
            hi = mid
    return lo, err.get(lo, 0.0)


def _um(v: float) -> str:
    return f"{v * 1e6:.3g} um"


def _length(v: float) -> str:
    return f"{v * 1e3:.3g} mm" if v >= 1e-4 else _um(v)


def _cover(src: str, grid: np.ndarray, hg: np.ndarray, need: float, what: str, short_scan: str, extend: str):
    """(grid, heights, note) of a scan at least ``need`` (m) long: a shorter one refused (a ProfileError naming
    both lengths) or, with short_scan "repeat", repeated by ``extend`` to twice ``need`` with a warning."""
    length = float(grid[-1] - grid[0])
    if length >= need:
        return grid, hg, ""
    if short_scan != "repeat":
        raise ProfileError(f"{src}: the scan is {_length(length)} long, shorter than {what} ({_length(need)}): a "
                           "pad would slide over the same few points again and again; use a longer scan, or set "
                           "substrate.short_scan = \"repeat\" to repeat it anyway")
    copies = int(np.ceil(2 * need / length))
    back = hg[::-1] if extend == "mirror" else hg
    parts = [hg if i % 2 == 0 else back for i in range(copies)]
    parts = [parts[0]] + [p[1:] if extend == "mirror" else p for p in parts[1:]]
    hg = np.concatenate(parts)
    dx = (grid[-1] - grid[0]) / (grid.size - 1)
    grid = grid[0] + dx * np.arange(hg.size)
    return grid, hg, (f"; WARNING: the scan ({_length(length)}) is shorter than {what} ({_length(need)}) and "
                      f"is repeated {copies} times (substrate.short_scan = \"repeat\")")


def _native_spacing(f) -> tuple:
    """(spacing (m), uniform, note) of a scan's positions: the spacing the preamble states when the positions
    agree with it (their span within 1 % of (n - 1) spacings), else their mean step (the median of positions
    rounded in the export is the rounding's step, not the scan's). Positions within half a step of that uniform
    grid are the grid as written with rounding (the heights kept as they are); others are interpolated onto it."""
    x = f.x
    span = float(x[-1] - x[0])
    mean = span / (x.size - 1)
    native, said = mean, "their mean step"
    if f.spacing is not None and abs(f.spacing * (x.size - 1) - span) <= 0.01 * span:
        native, said = f.spacing, "the spacing the file states"
    off = float(np.max(np.abs(x - (x[0] + native * np.arange(x.size)))))
    if off <= 1e-6 * native:
        return native, True, ""
    if off < 0.5 * native:
        return native, True, (f" (positions as written stray up to {_um(off)} from a uniform grid at {said}, "
                              f"{_um(native)}: rounding in the export, read as that grid)")
    return native, False, f" (non-uniform positions interpolated to {said}, {_um(native)})"


@functools.lru_cache(maxsize=8)
def _profile(path: str, stamp: tuple, x_unit: str, height_unit: str, dx: float, detrend: str, extend: str,
             radius: float, tol: float, cap: float, a: float = 0.0, short_scan: str = "refuse") -> TrackProfile:
    f = read_line_scan(path, x_unit, height_unit)
    x, h = f.x, f.h
    native, uniform, how = _native_spacing(f)
    grid = x[0] + native * np.arange(x.size if uniform else int(np.floor((x[-1] - x[0]) / native + 1e-9)) + 1)
    hg = h.copy() if uniform else np.interp(grid, x, h)
    if detrend == "linear":
        hg = hg - np.polyval(np.polyfit(grid - grid[0], hg, 1), grid - grid[0])
    elif detrend == "mean":
        hg = hg - hg.mean()
    name = Path(path).name
    need, what = 2 * radius, "a pad's diameter with the track's thickness"  # a point probe (radius 0) needs none
    if radius > 0 and a > need:
        need, what = a, "the renewal length substrate.a"
    grid, hg, repeated = _cover(path, grid, hg, need, what, short_scan, extend)
    how += repeated
    if radius <= 0:  # a point probe: the file's heights on the grid
        step = dx if dx > 0 else native
        out = hg.copy() if dx <= 0 else np.interp(
            grid[0] + step * np.arange(int(np.floor((grid[-1] - grid[0]) / step + 1e-9)) + 1), grid, hg)
        note = f"{name}: profile on a {_um(step)} grid{how}"
        out.setflags(write=False)
        return TrackProfile(float(step), out, native, 0.0, note, f.sha256)
    file_dx = native
    width = 2 * _reach(radius, hg) / native  # points under the disc: the closing costs n x width
    if hg.size * width > _CLOSING_WORK:  # a pad touches only peaks: keep each bin's highest point
        b = int(np.ceil(hg.size * width / _CLOSING_WORK))
        hg = np.maximum.reduceat(hg, np.arange(0, hg.size, b))
        grid = grid[::b]
        native *= b
        how += f" (first pooled to the highest point of every {b} points, {_um(native)}: the pad touches only peaks)"
    closed = pad_closing(hg, native, radius, extend)
    filled = float(np.mean(closed - hg > _FILLED * tol))
    n_eval = min(closed.size, _EVAL_POINTS)
    path_ref = pad_path(hg[:n_eval], native, radius, extend)
    margin = int(_reach(radius, closed) / native) + 1
    finest = _KEPT_RADII * cap / TRACK_SEGMENTS  # the segment budget's spacing (m)
    if 0 < dx < finest * (1 - 1e-9):
        raise ProfileError(f"{path}: substrate.dx = {dx:.3g} m would lay more than {TRACK_SEGMENTS} segments over "
                           f"the {_length(_KEPT_RADII * cap)} a track keeps around its pad; use at least "
                           f"{finest:.3g} m")
    if dx > 0:
        k = dx / native
        if abs(k - round(k)) < 1e-6 and round(k) >= 1:
            k = int(round(k))
            step, out = k * native, closed[::k].copy()
            err = _path_error(closed[:n_eval], path_ref, k, native, radius, margin, extend)
        else:
            step, k, err = dx, None, float("nan")
            out = np.interp(grid[0] + dx * np.arange(int(np.floor((grid[-1] - grid[0]) / dx + 1e-9)) + 1), grid,
                            closed)
        moved = f"; the pad's path moves {_um(err)} rms" if k is not None else ""
        what = f"resampled from {_um(file_dx)} to {_um(step)} as substrate.dx asks{moved}"
    else:
        k, err = _spacing_from_pad(closed[:n_eval], path_ref, native, radius, tol, cap, extend)
        k_min = int(np.ceil(finest / native * (1 - 1e-9)))
        budget = ""
        if k < k_min:
            k = k_min
            err = _path_error(closed[:n_eval], path_ref, k, native, radius, margin, extend)
            budget = (f"; coarsened to {_um(k * native)} to lay at most {TRACK_SEGMENTS} segments per track (its "
                      f"path moves {_um(err)} rms)" if np.isfinite(err) else
                      f"; coarsened to {_um(k * native)} to lay at most {TRACK_SEGMENTS} segments per track")
        step, out = k * native, closed[::k].copy()
        if budget:
            what = f"resampled from {_um(file_dx)}{budget}"
        elif k > 1:
            what = (f"resampled from {_um(file_dx)} to {_um(step)}: the pad cannot resolve shorter wavelengths (its "
                    f"path moves {_um(err)} rms; substrate.path_tolerance {_um(tol)})")
        else:
            e2 = _path_error(closed[:n_eval], path_ref, 2, native, radius, margin, extend)
            said = (f"at {_um(2 * native)} its path would move {_um(e2)} rms" if np.isfinite(e2) else
                    "the scan is too short to judge a coarser grid")
            what = (f"kept at its spacing {_um(native)}: the pad feels shorter wavelengths ({said}; "
                    f"substrate.path_tolerance {_um(tol)})")
    note = (f"{name}: profile {what}{how}; the pad (radius {_um(radius)} with the track's thickness) bridges the "
            f"valleys under {100 * filled:.0f} % of the points")
    out.setflags(write=False)
    return TrackProfile(float(step), out, file_dx, err, note, f.sha256)


def read_profile(spec: LineScanSpec, pad_radius: float = 0.0) -> TrackProfile:
    """The spec's profile as a track uses it (cached per file): read with its units (:func:`read_line_scan`),
    on a uniform grid, detrended, then, for a pad of radius ``pad_radius`` (m; with the track's segment radius
    added), closed by the pad's disc (:func:`pad_closing`) and resampled at the coarsest spacing k dx (a whole
    number k of the file's spacing, at most the pad's radius) at which the pad's path stays within
    ``spec.path_tolerance`` (rms) of its path over the file's profile, unless ``spec.dx`` sets the spacing.
    ``pad_radius = 0``: a point probe (no closing; the file's spacing or ``spec.dx``)."""
    p = Path(spec.file)
    try:
        st = p.stat()
    except OSError as e:
        raise ProfileError(f"{p}: cannot be read ({e.strerror or e})") from None
    radius = pad_radius + spec.segment_radius if pad_radius > 0 else 0.0
    return _profile(str(p), (st.st_mtime_ns, st.st_size), spec.x_unit, spec.height_unit, spec.dx, spec.detrend,
                    spec.extend, radius, spec.path_tolerance, pad_radius, spec.a, spec.short_scan)


def _find(name: str, where: str) -> Path:
    p = Path(name)
    if p.is_absolute():
        return p
    places = ([Path(where).parent] if where else []) + [Path.cwd(), SCENARIO_DIR / "profiles"]
    if p.parts[:1] == ("scenarios",):  # a shipped file as the docs write it, scenarios/profiles/...
        places.append(SCENARIO_DIR.parent)
    for base in places:
        if (base / p).exists():
            return (base / p).resolve()
    raise ValueError(f"substrate.file = {name!r}: not found beside the scenario, in the current folder or among the "
                     "shipped profiles (scenarios/profiles/, `frictionnoise scenarios --all` lists them)")


@SUBSTRATES.register
class LineScan(Substrate):
    name = "line_scan"
    Spec = LineScanSpec
    positive = Substrate.positive | {"path_tolerance"}
    non_negative = frozenset({"dx"})
    quick_duration = 8.0  # streaming its short segments costs about 1 wall s per simulated s
    choices = {"x_unit": tuple(_UNITS), "height_unit": tuple(_UNITS), "detrend": ("linear", "mean", "none"),
               "extend": ("mirror", "tile"), "short_scan": ("refuse", "repeat")}

    @classmethod
    def prepare(cls, spec, where=""):
        if not spec.file:
            raise ValueError("substrate.file must name the profile (CSV or NPY) of a line_scan substrate")
        return replace(spec, file=str(_find(spec.file, where)))

    @classmethod
    def validate(cls, s, sc, where=""):
        if s.dx > 2 * sc.pads.radius:
            raise ValueError(f"substrate.dx = {s.dx:.3g} m is coarser than a pad (diameter {2 * sc.pads.radius:.3g} m)")
        prof = read_profile(s, sc.pads.radius)  # a ProfileError (a ValueError) names the file and the line
        dx, h = prof.dx, prof.h
        slope = float(np.sqrt(np.mean(np.diff(h) ** 2)) / dx)
        limit = sliding_limit(sc.friction.mu0)
        if slope > limit:
            raise ValueError(f"substrate.file {s.file!r}: rms slope {slope:.3g} (at dx = {dx:.3g} m) exceeds the sliding "
                             f"limit {limit:.3g} = 1/(6 mu0); resample coarser (substrate.dx) or lower friction.mu0")

    def __init__(self, spec, scenario):
        super().__init__(spec, scenario)
        self.profile = read_profile(spec, scenario.pads.radius)

    def scene_inputs(self):
        return {**super().scene_inputs(), "dx": (self.profile.dx, "length"), "h": (self.profile.h, "length")}

    def pad_depth(self, fraction, pad_radius):
        """The depth below the datum exceeded on ``fraction`` of the pad's path over the track's profile (m; the
        path of the lowest point of the pad's disc, with the track's thickness, :func:`pad_path`)."""
        path = pad_path(self.profile.h, self.profile.dx, pad_radius + self.spec.segment_radius, self.spec.extend)
        return max(0.0, -float(np.quantile(path, fraction)))

    def notes(self) -> list:
        return [self.profile.note]

    def provenance(self) -> dict:
        p = self.profile
        return {"profile": {"file": self.spec.file, "sha256": p.sha256, "file_spacing_m": p.native_dx,
                            "track_spacing_m": p.dx, "path_error_m": p.path_error, "resampling": p.note}}

    def build(self, space, y, shape_filter, rng, mu, x_start):
        return ProfileTrack(space, y, self.own.h, self.own.dx, self.spec.extend, mu, self.own.segment_radius,
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
        self._add_polyline(xs, self.y + self._heights(self._j, self.chunk))
        self._j += self.chunk
        self._x_next = float(xs[-1] + self.dx)
