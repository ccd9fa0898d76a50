"""Headless rendering of a scene (a matplotlib Figure on its own Agg canvas, collections updated in place: ~20-60 ms a frame).

Draws a window around the block: the substrate (friction patches coloured by mu, or the rough profile, or the
asperity caps), the pads or feet, their springs, the block, the drive's own bodies, wear particles coloured by
state (trapped: at rest on the substrate; moving), and the time. The parts say what to draw as named shapes in
scene units, ``name -> (kind, data, style)`` with kind one of "points" (xy array), "segments" (list of point
pairs), "polys" (list of vertex lists), "line" ((xs, ys)), "circle" ((centre, radius)), "rect" ((corner, width,
height)), "text" ((position, string)); style is passed to matplotlib. The only matplotlib importer of engine_sim.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib.colors
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Rectangle

from . import units as U
from .record import Recorder

__all__ = ["SceneRenderer"]

_STATE_COLORS = np.array([[0.6, 0.6, 0.6, 1.0], [0.12, 0.47, 0.71, 1.0], [0.89, 0.10, 0.11, 1.0]])  # idle, trapped, moving
_STATE_NAMES = ("idle", "trapped", "moving")


class SceneRenderer:
    """Draws frames of a :class:`~engine_sim.scene.Scene`; call :meth:`observe` after every output step (grain
    states are the recorder's: one classifier for traces and frames) and :meth:`frame` to draw."""

    def __init__(self, scene, window: float | None = None, dpi: int = 90):
        self.scene = scene
        sc = scene.sc
        self.zoom = scene.wear is not None  # grains of tens of um: zoom onto the first pad's track
        # grain states come from a recorder that keeps only its latest sample (the trace's own classifier)
        self._rec = Recorder(scene, 1) if scene.wear is not None else None
        view = scene.arrangement.view(scene)
        if self.zoom:
            surf = scene.track_surface[0]
            view = {**view, "window": 0.6 * sc.wear.ahead, "ylim": (surf - 0.3, surf + 0.9),
                    "ylabel": "y (mm): the first pad's track", "block_top": view["block_top"]}
        self.view = view
        self.window = (view["window"] if window is None else window) * U.LENGTH  # mm either side of the block
        # a Figure on its own Agg canvas: importing or rendering never changes the program's matplotlib backend
        self.fig = Figure(figsize=(7.0, 5.0), dpi=dpi)
        FigureCanvasAgg(self.fig)
        self.ax = ax = self.fig.subplots()
        self.ylim = view["ylim"]
        ax.set_ylabel(view["ylabel"])
        if self.zoom:
            ax.set_aspect("equal", adjustable="box")
        ax.set_ylim(*self.ylim)
        ax.set_xlabel("x (mm)")
        mu_lo, mu_hi = scene.substrate.mu_range(sc.friction.mu0)
        self.q_pad = scene.q_pad  # pad-track friction = shape friction x q_pad
        self.norm = matplotlib.colors.Normalize(mu_lo, mu_hi + 1e-12)
        self.tracks = LineCollection([], cmap="viridis", norm=self.norm, linewidths=view["track_width"])
        ax.add_collection(self.tracks)
        top = view["block_top"]
        self.block = Rectangle((0, top), 8.0, self.ylim[1] - top, color="tab:blue", alpha=0.35, zorder=4)
        ax.add_patch(self.block)
        self._artists = {}
        self.particles = None
        self.text = ax.text(0.02, 0.01, "", transform=ax.transAxes, va="bottom", fontsize=9, zorder=6,
                            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        if self._rec is not None:
            ax.legend([Line2D([], [], ls="", marker="o", ms=7, mfc=c, mec="none") for c in _STATE_COLORS],
                      [f"grain {n}" for n in _STATE_NAMES], loc="upper right", fontsize=8, framealpha=0.85)
        self.fig.tight_layout()
        if mu_hi > mu_lo:  # a colour bar exactly as tall as the axes (also when their aspect is fixed)
            self.fig.subplots_adjust(right=0.86)
            cb = self.fig.colorbar(self.tracks, cax=ax.inset_axes([1.03, 0.0, 0.035, 1.0]))
            cb.set_label("patch friction coefficient")
        else:
            self.tracks.set_cmap(matplotlib.colors.ListedColormap(["0.25"]))

    def observe(self):
        """Sample the scene after an output step (the recorder classifies grains on their mean speed over it)."""
        if self._rec is not None:
            self._rec.k = 0  # keep only the latest sample
            self._rec.sample()

    def _shapes(self, shapes: dict):
        """Create (first time) or update the artists of the parts' named shapes."""
        ax = self.ax
        for name, (kind, data, style) in shapes.items():
            art = self._artists.get(name)
            if art is None:
                art = self._artists[name] = _new_artist(ax, kind, data, style)
            _update_artist(art, kind, data)

    def frame(self) -> np.ndarray:
        """Update the artists to the scene's state and render; returns the RGBA image."""
        s = self.scene
        bx = s.block.position.x
        lo, hi = bx - self.window, bx + self.window
        segs, mus = s.arrangement.draw_tracks(s, lo, hi, self.q_pad)
        self.tracks.set_segments(segs)
        self.tracks.set_array(np.asarray(mus))
        if self.zoom:  # pads at their true size
            pads = np.array([(p.position.x, p.position.y) for p in s.pads])
            self._shapes({"pad_discs": ("discs", (pads, 2 * s.R_pad), {"facecolors": "tab:orange", "alpha": 0.6,
                                                                        "zorder": 3})})
        else:
            self._shapes(s.arrangement.draw(s, lo, hi, self.view))
        self._shapes(s.drive.draw(s, lo, hi))
        if self._rec is not None:
            if self._rec.k == 0:
                self.observe()
            xy, r = s.wear.snapshot()
            if self.particles is None:
                self.particles = EllipseCollection(2 * r, 2 * r, 0.0, units="xy", offsets=xy,
                                                   offset_transform=self.ax.transData, zorder=4)
                self.ax.add_collection(self.particles)
            self.particles.set_offsets(xy)
            self.particles.set_facecolor(_STATE_COLORS[self.states])
        half = self.view["block_half"]
        self.block.set_x(bx - half)
        self.block.set_width(2 * half)
        self.ax.set_xlim(lo, hi)
        v = s.block.velocity.x / U.VELOCITY * U.LENGTH  # mm/s
        self.text.set_text(f"t = {s.time:.3f} s   x = {bx:.3f} mm   v = {v:.3f} mm/s")
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())

    @property
    def states(self) -> np.ndarray:
        """The grains' states at the latest observed output step (0 idle, 1 trapped, 2 moving), as recorded."""
        return self._rec.p_state[0].astype(int)

    def save_png(self, path: Path):
        self.fig.savefig(path)

    def close(self):
        self.fig.clear()


def _new_artist(ax, kind, data, style):
    if kind == "points":
        return ax.scatter([], [], **style)
    if kind == "segments":
        return ax.add_collection(LineCollection([], **style))
    if kind == "polys":
        return ax.add_collection(PolyCollection([], **style))
    if kind == "discs":
        xy, d = data
        return ax.add_collection(EllipseCollection(d, d, 0.0, units="xy", offsets=xy, offset_transform=ax.transData,
                                                   **style))
    if kind == "line":
        return ax.add_line(Line2D([], [], **style))
    if kind == "circle":
        return ax.add_patch(Circle((0, 0), data[1], **style))
    if kind == "rect":
        return ax.add_patch(Rectangle((0, 0), data[1], data[2], **style))
    if kind == "text":
        return ax.text(0, 0, "", **style)
    raise ValueError(f"unknown shape kind {kind!r}")


def _update_artist(art, kind, data):
    if kind in ("points", "discs"):
        art.set_offsets(data[0] if kind == "discs" else data)
    elif kind == "segments":
        art.set_segments(data)
    elif kind == "polys":
        art.set_verts(data)
    elif kind == "line":
        art.set_data(*data)
    elif kind == "circle":
        art.center = data[0]
    elif kind == "rect":
        art.set_xy(data[0])
    elif kind == "text":
        art.set_position(data[0])
        art.set_text(data[1])
