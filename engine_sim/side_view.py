"""The side view's geometry (numpy only; engine_sim.side_render draws it): a block on its spring-mounted pads over
the substrate, as a physicist sketches it.

Coordinates are display millimetres: x is the true position (mm) relative to the block, shifted per pad slot
(pads on tracks of their own are shown side by side, each over the piece of its own track under it); y is the
true height above the pad's track datum (mm) times the vertical exaggeration ``E`` in the contact zone: the
substrate's relief, the pads' contact arcs and the grains are drawn to that one affine scale, which keeps every
contact a contact (an affine map keeps tangency), so nothing is drawn inside a body it touches. Above the contact
zone the pads' bodies, the springs and the block are schematic (fixed display heights), as the frame says.

Every part answers for its own shapes (``side`` methods on the substrate, arrangement, drive and wear parts), in
the renderer's shape vocabulary (``engine_sim.render``: name -> (kind, data, style)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SideLayout", "zigzag", "capsule_envelope", "circle_envelope", "nice_exaggeration", "cap_outline",
           "capsule_outline", "body_outline"]

_NICE = (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000)


def nice_exaggeration(relief: float, target: float) -> int:
    """The largest of 1, 2, 5, 10, ... with ``relief`` x E at most ``target`` (both mm), at least 1."""
    if relief <= 0:
        return 1
    fit = [e for e in _NICE if e * relief <= target]
    return fit[-1] if fit else 1


def zigzag(p0, p1, coils: int = 5, width: float = 0.2, lead: float = 0.15) -> np.ndarray:
    """A spring's zig-zag from p0 to p1 (display mm): straight leads of ``lead`` of the length at both ends, then
    ``coils`` full turns of half-width ``width`` across the axis; an (n, 2) polyline."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    d = p1 - p0
    length = float(np.hypot(*d))
    if length == 0:
        return np.array([p0, p1])
    u = d / length
    nrm = np.array([-u[1], u[0]])
    k = 2 * coils
    s = np.concatenate([[0.0, lead], lead + (1 - 2 * lead) * (np.arange(k) + 0.5) / k, [1 - lead, 1.0]])
    off = np.concatenate([[0.0, 0.0], width * np.where(np.arange(k) % 2 == 0, 1.0, -1.0), [0.0, 0.0]])
    return p0 + np.outer(s * length, u) + np.outer(off, nrm)


def capsule_envelope(a: np.ndarray, b: np.ndarray, radius: float, xs: np.ndarray) -> np.ndarray:
    """The upper envelope, at the points xs, of segments a[i] -> b[i] ((n, 2) arrays) thickened by ``radius``: the
    surface a pad touches (pymunk's segment shapes are capsules); -inf where none reaches."""
    top = np.full(xs.shape, -np.inf)
    if not len(a):
        return top
    for (ax, ay), (bx, by) in zip(a, b):
        x0, x1 = min(ax, bx) - radius, max(ax, bx) + radius
        i0, i1 = np.searchsorted(xs, x0), np.searchsorted(xs, x1, side="right")
        if i1 <= i0:
            continue
        x = xs[i0:i1]
        # the capsule's top above x: the highest point of the discs of ``radius`` along the segment
        dx, dy = bx - ax, by - ay
        if dx * dx + dy * dy == 0:
            y = ay + np.sqrt(np.maximum(radius**2 - (x - ax) ** 2, 0.0))
        elif abs(dx) > 1e-15:
            n = math.hypot(dx, dy)
            # the straight part: the line offset by radius along the upward normal
            ox, oy = -dy / n * radius, dx / n * radius
            if oy < 0:
                ox, oy = -ox, -oy
            t = (x - ax - ox) / dx
            y_line = np.where((t >= 0) & (t <= 1), ay + oy + t * dy, -np.inf)
            y_end = np.maximum(ay + np.sqrt(np.maximum(radius**2 - (x - ax) ** 2, 0.0)) - np.where(np.abs(x - ax) > radius, np.inf, 0),
                               by + np.sqrt(np.maximum(radius**2 - (x - bx) ** 2, 0.0)) - np.where(np.abs(x - bx) > radius, np.inf, 0))
            y = np.maximum(y_line, y_end)
        else:  # a vertical segment (a pit's wall): its upper end's disc
            yt = max(ay, by)
            y = yt + np.sqrt(np.maximum(radius**2 - (x - ax) ** 2, 0.0))
        top[i0:i1] = np.maximum(top[i0:i1], y)
    return top


def circle_envelope(centres: np.ndarray, radii, xs: np.ndarray) -> np.ndarray:
    """The upper envelope of circles at the points xs; -inf where none reaches."""
    top = np.full(xs.shape, -np.inf)
    for (cx, cy), r in zip(centres, np.broadcast_to(radii, (len(centres),))):
        m = np.abs(xs - cx) <= r
        top[m] = np.maximum(top[m], cy + np.sqrt(r * r - (xs[m] - cx) ** 2))
    return top


def cap_outline(cx: float, cy: float, r: float, h: float, n: int = 41) -> np.ndarray:
    """The lower arc of a circle (centre, radius r, true mm) up to height h above its lowest point: (n, 2)."""
    h = min(h, r)
    half = math.sqrt(max(r * r - (r - h) ** 2, 0.0))
    x = np.linspace(cx - half, cx + half, n)
    return np.column_stack([x, cy - np.sqrt(np.maximum(r * r - (x - cx) ** 2, 0.0))])


def capsule_outline(ax: float, bx: float, y: float, r: float, h: float, n: int = 15) -> np.ndarray:
    """The lower outline of a horizontal capsule (axis from ax to bx at height y, radius r) up to height h above
    its bottom: the rounded ends' lower arcs and the flat underside; (2n, 2), left to right."""
    h = min(h, r)
    phi = math.acos(max(-1.0, min(1.0, (r - h) / r))) if r > 0 else 0.0
    left = np.linspace(1.5 * math.pi - phi, 1.5 * math.pi, n)
    right = np.linspace(1.5 * math.pi, 1.5 * math.pi + phi, n)
    pl = np.column_stack([ax + r * np.cos(left), y + r * np.sin(left)])
    pr = np.column_stack([bx + r * np.cos(right), y + r * np.sin(right)])
    return np.concatenate([pl, pr])


def body_outline(ax: float, bx: float, y: float, r: float, E: float, y_top: float, n: int = 41) -> np.ndarray:
    """A pad's (``ax == bx``: a circle) or a foot's (a horizontal capsule, axis ax -> bx) outline in display mm, its
    true shape (axis at true height ``y``, radius ``r``, mm) with heights times ``E`` up to the display height
    ``y_top``, closed by a flat top there: the affine image of the body (every contact stays a contact) and its
    true width wherever the image reaches its equator; above the equator, vertical sides at the true width."""
    phi = np.linspace(math.pi, 2 * math.pi, n)  # the lower half, left to right
    x = np.where(phi < 1.5 * math.pi, ax, bx) + r * np.cos(phi)
    yd = E * (y + r * np.sin(phi))
    keep = yd <= y_top
    x, yd = x[keep], yd[keep]
    if E * y <= y_top:  # the equator below the top: the sides rise vertically from it at the true width
        left = [(ax - r, y_top), (ax - r, E * y)]
        right = [(bx + r, E * y), (bx + r, y_top)]
    else:  # cut where the true outline reaches the top's true height
        half = math.sqrt(max(r * r - (y_top / E - y) ** 2, 0.0))
        left, right = [(ax - half, y_top)], [(bx + half, y_top)]
    return np.vstack([left, np.column_stack([x, yd]), right])


@dataclass
class SideLayout:
    """Where things go in the side view (display mm): ``E`` the vertical exaggeration of the contact zone,
    ``slot`` the width shown around each pad (mm), ``n_show`` the pads shown, ``x0`` each shown pad's slot centre,
    ``contact`` the contact zone's display height above the datum (pads' true arcs up to it), ``body`` the pads'
    schematic body height above it, ``spring`` the normal springs' display length and ``block`` the block's
    display thickness; ``floor`` the substrate's drawn base below the datum."""

    E: int
    slot: float
    n_show: int
    contact: float
    body: float = 0.35
    spring: float = 1.4
    block: float = 0.9
    floor: float = -0.6

    pad_win: float = 0.0  # width of the window around each pad (mm; 0: the slot)
    pad_at: float = 0.0  # offset of that window's centre from the slot's centre (display mm)

    def __post_init__(self):
        self.x0 = (np.arange(self.n_show) - (self.n_show - 1) / 2) * self.slot
        self.pad_win = self.pad_win or self.slot

    def y(self, y_true):
        """Display y of a true height above the datum (mm), in the contact zone."""
        return self.E * np.asarray(y_true, float)

    @property
    def drive_len(self) -> float:
        """The display length of the drive's arrow or spring at the block's front (mm)."""
        return max(0.6 * self.slot, 0.06 * self.width)

    @property
    def width(self) -> float:
        return self.n_show * self.slot

    @property
    def block_bottom(self) -> float:
        return self.contact + self.body + self.spring

    @property
    def top(self) -> float:
        return self.block_bottom + self.block
