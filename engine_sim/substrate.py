"""Substrate tracks, generated ahead of the pads and dropped behind them (memory independent of length).

Each pad runs on its own track (its own random stream), as the contact lines of a 2D interface do; the
tracks are offset in y so each pad's broad phase only meets its own segments. Works in scene units.
"""
from __future__ import annotations

from collections import deque

import numpy as np
import pymunk

from .static_segments import add_segments, remove_shapes, segment_b as _segment_b

__all__ = ["PatchTrack", "SelfAffineTrack", "BumpTrack", "self_affine_kernel"]

_CHUNK = 32  # patches generated at a time


def _points(p: np.ndarray) -> list:
    """The rows of an (n, 2) array as (x, y) tuples of floats (tuples of floats leave the garbage collector's
    care, lists do not)."""
    it = iter(p.ravel().tolist())
    return list(zip(it, it))


class StreamedTrack:
    """Segments generated ahead of a pad and dropped behind it. Subclasses implement ``_extend`` (add the next
    chunk via ``_link_and_add``) and ``_frontier`` (x up to which the track exists)."""

    def _init_stream(self, space, shape_filter, rng):
        self.space, self.filter, self.rng = space, shape_filter, rng
        self.segments: deque = deque()
        self.neighbors: deque = deque()  # (a_prev, b_next) per segment: pickling a space drops them
        self.generated = 0
        self.removed = 0

    def _link_and_add(self, a: np.ndarray, b: np.ndarray, frictions: list):
        """Add straight segments from a[i] to b[i] ((n, 2) arrays) with their frictions, each linked with
        set_neighbors to the one before and the one after (so pads do not catch on joints; a chunk's last segment
        and a track's first look past their own far end, extrapolated)."""
        if not len(a):
            return
        a_prev = np.empty_like(a)
        a_prev[1:] = a[:-1]
        a_prev[0] = self.segments[-1].a if self.segments else a[0] - (b[0] - a[0])
        b_next = np.empty_like(b)
        b_next[:-1] = b[1:]
        b_next[-1] = b[-1] + (b[-1] - a[-1])
        na, nb = _points(a_prev), _points(b_next)
        new = add_segments(self.space, self.space.static_body, _points(a), _points(b), self.radius, frictions,
                           self.filter, na, nb)
        self.neighbors.extend(zip(na, nb))
        self.segments.extend(new)
        self.generated += len(new)

    def _add_polyline(self, xs: np.ndarray, ys: np.ndarray):
        """Straight segments through the points (xs, ys) (continuing from the last point added), friction
        self.mu0, linked."""
        pts = np.column_stack([xs, ys])
        if self._last is not None:
            pts = np.concatenate([[self._last], pts])
        self._link_and_add(pts[:-1], pts[1:], [self.mu0] * (len(pts) - 1))
        self._last = tuple(pts[-1].tolist())

    def maintain(self, x: float, ahead: float, behind: float):
        """Keep segments covering [x - behind, x + ahead]; add ahead, remove behind."""
        while self._frontier() < x + ahead:
            self._extend()
        old = []
        while self.segments and self._end_x(self.segments[0]) < x - behind:
            old.append(self.segments.popleft())
            if self.neighbors:
                self.neighbors.popleft()
        if old:
            remove_shapes(self.space, old)  # and off the static body's list of its shapes, which would keep them alive
            self.removed += len(old)

    @staticmethod
    def _end_x(shape) -> float:
        return _segment_b(shape._shape).x

    def restore_neighbors(self):
        """Re-apply set_neighbors after unpickling (pymunk does not save them)."""
        for seg, (a, b) in zip(self.segments, self.neighbors):
            seg.set_neighbors(a, b)


class PatchTrack(StreamedTrack):
    """A flat track of friction patches (model I's renewal, section 3), optionally with cavities.

    Patch boundaries lie at (j + r_j) a, so the distance between renewals is a (1 + r - r'), exactly the
    interval law behind eq. (A8); each patch has mu = mu0 (1 + alpha (r - 1/2)), so the force on a pad
    sliding under load N_pad changes to mu0 N_pad + alpha mu0 N_pad (r - 1/2) (eq. 5).

    Cavities (for wear particles): with probability ``pit_p`` a patch holds a flat-bottomed pit of depth
    ``pit_depth`` at a random place, its width (between the wall centre lines; the walls are as thick as the
    segments) uniform in ``pit_width`` = (min, max), in the patch's friction. Flat bottoms, because a grain wedged between the two walls of a V-shaped
    pit under a pad sinks up to 65 um into them at 2 solver iterations.

    Parameters are in scene units (mm). ``rng`` is this track's own generator.
    """

    def __init__(self, space: pymunk.Space, y: float, a: float, mu0: float, alpha: float, radius: float,
                 shape_filter: pymunk.ShapeFilter, rng: np.random.Generator, x_start: float,
                 pit_p: float = 0.0, pit_width: tuple = (0.0, 0.0), pit_depth: float = 0.0):
        self._init_stream(space, shape_filter, rng)
        self.y, self.a, self.mu0, self.alpha, self.radius = y, a, mu0, alpha, radius
        self.pit_p, self.pit_width, self.pit_depth = pit_p, pit_width, pit_depth
        self.pits = 0
        self._j = int(np.floor(x_start / a)) - 2
        self._x_end = (self._j + rng.random()) * a

    def _frontier(self) -> float:
        return self._x_end

    def _extend(self):
        j = self._j + 1 + np.arange(_CHUNK)
        bounds = (j + self.rng.random(_CHUNK)) * self.a
        mus = self.mu0 * (1.0 + self.alpha * (self.rng.random(_CHUNK) - 0.5))
        if self.pit_p > 0:  # drawn only when pits exist, so a pit-free track keeps its random stream
            has_pit = self.rng.random(_CHUNK) < self.pit_p
            widths = self.pit_width[0] + self.rng.random(_CHUNK) * (self.pit_width[1] - self.pit_width[0])
            where = self.rng.random(_CHUNK)
        if self.pit_p > 0:
            ends, fr = self._with_pits(bounds.tolist(), mus.tolist(), has_pit, widths, where)
            e = np.array(ends, dtype=float).reshape(-1, 2, 2)
            self._link_and_add(e[:, 0], e[:, 1], fr)
        else:  # flat patches end to end: a from the previous bound, b to the next
            a = np.empty((_CHUNK, 2))
            a[0, 0] = self._x_end
            a[1:, 0] = bounds[:-1]
            a[:, 1] = self.y
            b = np.empty((_CHUNK, 2))
            b[:, 0] = bounds
            b[:, 1] = self.y
            self._link_and_add(a, b, mus.tolist())
        self._j = int(j[-1])
        self._x_end = float(bounds[-1])


    def _with_pits(self, bounds: list, mus: list, has_pit, widths, where):
        """Segment ends ((ax, ay), (bx, by)) and frictions of the chunk's patches from the last bound to each of
        ``bounds``, a patch flagged in ``has_pit`` and wider than twice its pit's width holding the pit (its
        width from ``widths``, its place from ``where``)."""
        ends, fr = [], []
        x0 = self._x_end
        y = self.y
        for c, (x1, mu) in enumerate(zip(bounds, mus)):
            if has_pit[c] and x1 - x0 > 2 * widths[c]:
                w, d = float(widths[c]), self.pit_depth
                xa = x0 + 0.5 * w + float(where[c]) * (x1 - x0 - 2 * w)
                xb = xa + w
                ends += [((x0, y), (xa, y)), ((xa, y), (xa, y - d)), ((xa, y - d), (xb, y - d)), ((xb, y - d), (xb, y)),
                         ((xb, y), (x1, y))]
                fr += [mu] * 5
                self.pits += 1
            else:
                ends.append(((x0, y), (x1, y)))
                fr.append(mu)
            x0 = x1
        return ends, fr


def self_affine_kernel(hurst: float, lambda_r: float, lambda_s: float, dx: float, rms_slope: float):
    """FIR kernel K (scene units) such that the line profile h = K * w (w: unit white noise per grid point,
    spacing dx) is self-affine with Hurst exponent H: its 1D power spectrum falls as C_1D(q) ~ q^-(1+2H) for
    2 pi/lambda_r < q < 2 pi/lambda_s (flat below the roll-off, cut above), scaled to the rms slope.

    ``hurst`` is the *line's* exponent: a line scan of an isotropic surface whose 2D spectrum is q^-2(1+H) has
    the 1D spectrum q^-(1+2H) (Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), eq. 13);
    the amplitude filter is therefore q^-(1/2+H) (the 2D exponent q^-(1+H) applied to a line would make a profile
    of Hurst exponent H + 1/2). Length: 8 roll-off
    wavelengths (the kernel's tails are below 1e-3 of its peak there)."""
    n = int(2 ** np.ceil(np.log2(8 * lambda_r / dx)))
    q = 2 * np.pi * np.fft.rfftfreq(n, dx)
    qr, qs = 2 * np.pi / lambda_r, 2 * np.pi / lambda_s
    amp = (np.maximum(q, qr) / qr) ** (-(0.5 + hurst))  # flat below the roll-off; |amp|^2 ~ q^-(1+2H)
    amp[q > qs] = 0.0
    amp[0] = 0.0  # zero mean height
    k = np.fft.irfft(amp, n)
    k = np.roll(k, n // 2)  # centred, so the filter is non-causal but finite
    slope = np.diff(k) / dx
    return k * (rms_slope / np.sqrt(np.sum(slope**2)))


class SelfAffineTrack(StreamedTrack):
    """A randomly rough self-affine track, streamed: white noise filtered by a fixed FIR kernel, keeping the
    last kernel-length of noise between chunks, so the profile is exactly stationary across chunk joins.
    Straight segments between grid points, consecutive segments linked with set_neighbors; friction mu0."""

    def __init__(self, space, y, kernel, dx, mu0, radius, shape_filter, rng, x_start, chunk_points=256):
        self._init_stream(space, shape_filter, rng)
        self.y, self.k, self.dx, self.mu0, self.radius = y, kernel, dx, mu0, radius
        self.chunk = chunk_points
        self._noise = rng.standard_normal(len(kernel) - 1)
        self._x_next = x_start  # x of the next profile point to generate
        self._last = None  # last generated point (x, y)

    def _frontier(self) -> float:
        return self._x_next

    def _extend(self):
        w = np.concatenate([self._noise, self.rng.standard_normal(self.chunk)])
        h = np.convolve(w, self.k, mode="valid")  # chunk_points heights
        self._noise = w[-(len(self.k) - 1):]
        xs = self._x_next + self.dx * np.arange(self.chunk)
        self._add_polyline(xs, self.y + h)
        self._x_next = float(xs[-1] + self.dx)


class BumpTrack(StreamedTrack):
    """Sparse random asperities (the substrate of model III, section 6): the axis is cut into cells of length
    ``cell``; each cell holds a bump with probability p, a static circle of radius ``bump_radius`` centred in
    the cell whose top stands r h_max above the datum y (r uniform in [0, 1], as model III's cell force
    r f0). There is no floor between bumps: a pad touches the substrate only on a bump. Friction mu0."""

    def __init__(self, space, y, cell, p, bump_radius, h_max, mu0, shape_filter, rng, x_start):
        self._init_stream(space, shape_filter, rng)
        self.y, self.cell, self.p, self.r, self.h_max, self.mu0 = y, cell, p, bump_radius, h_max, mu0
        self._j = int(np.floor(x_start / cell))

    def _frontier(self) -> float:
        return self._j * self.cell

    @staticmethod
    def _end_x(shape) -> float:
        return shape.body.local_to_world(shape.offset).x + shape.radius

    def _extend(self):
        j = self._j + np.arange(_CHUNK * 8)
        hit = self.rng.random(j.size) < self.p
        heights = self.rng.random(j.size) * self.h_max
        centres = [((jj + 0.5) * self.cell, self.y + h - self.r) for jj, h in zip(j[hit].tolist(), heights[hit].tolist())]
        new = []
        for c in centres:
            bump = pymunk.Circle(self.space.static_body, self.r, c)
            bump.friction = self.mu0
            bump.filter = self.filter
            new.append(bump)
        if new:
            self.space.add(*new)
        self.segments.extend(new)
        self.generated += len(new)
        self._j = int(j[-1]) + 1
