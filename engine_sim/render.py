"""Headless rendering of a scene (a matplotlib Figure on its own Agg canvas, collections updated in place: ~20-60 ms a frame).

Draws a window around the block: the substrate (friction patches coloured by mu, or the rough profile, or the
asperity caps), the pads or feet, their tangential springs to the block, the block, wear particles coloured by
state (trapped: at rest on the substrate; moving), and the time. The only matplotlib importer of engine_sim.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib.colors
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import EllipseCollection, LineCollection
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from . import units as U

__all__ = ["SceneRenderer"]

_STATE_COLORS = np.array([[0.6, 0.6, 0.6, 1.0], [0.12, 0.47, 0.71, 1.0], [0.89, 0.10, 0.11, 1.0]])  # out, trapped, moving


class SceneRenderer:
    """Draws frames of a :class:`~engine_sim.scene.Scene`; call :meth:`frame` after stepping."""

    def __init__(self, scene, window: float | None = None, dpi: int = 90):
        self.scene = scene
        sc = scene.sc
        self.asperities = scene.asperities
        self.zoom = scene.wear is not None  # grains of tens of um: zoom onto the first pad's track
        if window is None:
            window = (0.65 * sc.pads.N * sc.pads.foot_length if self.asperities
                      else 0.6 * sc.wear.ahead if self.zoom else 12 * sc.substrate.a)
        self.window = window * U.LENGTH  # mm either side of the block
        # a Figure on its own Agg canvas: importing or rendering never changes the program's matplotlib backend
        self.fig = Figure(figsize=(7.0, 5.0), dpi=dpi)
        FigureCanvasAgg(self.fig)
        self.ax = self.fig.subplots()
        ax = self.ax
        ys = np.array(scene.pad_y)
        if self.asperities:  # micrometre relief under a centimetre sole: the axes zoom onto the interface
            h = scene.substrate.top()
            self.ylim = (-3 * h, 4 * h)
            ax.set_ylabel("y (mm): asperity caps and feet")
        elif self.zoom:
            surf = scene.track_surface[0]
            self.ylim = (surf - 0.3, surf + 0.9)
            ax.set_ylabel("y (mm): the first pad's track")
            ax.set_aspect("equal", adjustable="box")
        else:
            self.ylim = (ys.min() - 3.0, scene.y_block + 4.0)
            ax.set_ylabel("y (mm): one track per pad")
        ax.set_ylim(*self.ylim)
        ax.set_xlabel("x (mm)")
        mu_lo, mu_hi = scene.substrate.mu_range(sc.friction.mu0)
        self.q_pad = scene.q_pad  # pad-track friction = shape friction x q_pad
        self.norm = matplotlib.colors.Normalize(mu_lo, mu_hi + 1e-12)
        self.tracks = LineCollection([], cmap="viridis", norm=self.norm, linewidths=3 if not self.asperities else 1.5)
        ax.add_collection(self.tracks)
        self.springs = LineCollection([], colors="0.4", linewidths=0.6)
        ax.add_collection(self.springs)
        self.feet = LineCollection([], colors="tab:red", linewidths=3)
        ax.add_collection(self.feet)
        self.pads = ax.scatter([], [], s=18, c="tab:red", zorder=3)
        top = self.ylim[1] - 0.06 * (self.ylim[1] - self.ylim[0]) if self.asperities else ys.max() + 1.0
        self.block = Rectangle((0, top), 8.0, self.ylim[1] - top, color="tab:blue", alpha=0.35)
        ax.add_patch(self.block)
        self.particles = None
        self.text = ax.text(0.02, 0.01, "", transform=ax.transAxes, va="bottom", fontsize=9,
                            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        if mu_hi > mu_lo:
            cb = self.fig.colorbar(self.tracks, ax=ax, fraction=0.04)
            cb.set_label("patch friction coefficient")
        else:
            self.tracks.set_cmap(matplotlib.colors.ListedColormap(["0.25"]))
        self.fig.tight_layout()

    def _substrate(self, lo, hi):
        """Ask the substrate part to draw each track within [lo, hi]."""
        segs, mus = [], []
        for tr in self.scene.tracks:
            s, m = self.scene.substrate.draw(tr, lo, hi, self.q_pad)
            segs += s
            mus += m
        return segs, mus

    def frame(self) -> np.ndarray:
        """Update the artists to the scene's state and render; returns the RGBA image."""
        s = self.scene
        bx = s.block.position.x
        lo, hi = bx - self.window, bx + self.window
        segs, mus = self._substrate(lo, hi)
        self.tracks.set_segments(segs)
        self.tracks.set_array(np.asarray(mus))
        pads = np.array([(p.position.x, p.position.y) for p in s.pads])
        if self.asperities:
            feet = []
            for p in s.pads:
                for sh in p.shapes:
                    a, b = p.local_to_world(sh.a), p.local_to_world(sh.b)
                    feet.append(((a.x, a.y - sh.radius), (b.x, b.y - sh.radius)))  # the sole's underside
            self.feet.set_segments(feet)
        elif self.zoom:  # pads at their true size
            if not hasattr(self, "_pad_disc"):
                d = 2 * s.sc.pads.radius * 1e3
                self._pad_disc = EllipseCollection(d, d, 0.0, units="xy", offsets=pads, offset_transform=self.ax.transData,
                                                   facecolors="tab:orange", alpha=0.6, zorder=3)
                self.ax.add_collection(self._pad_disc)
            self._pad_disc.set_offsets(pads)
        else:
            self.pads.set_offsets(pads)
            anchors = [c.a.local_to_world(c.anchor_a) for c in s.tangential_springs]
            self.springs.set_segments([((a.x, a.y), (p[0], p[1])) for a, p in zip(anchors, pads)])
        wear = getattr(s, "wear", None)
        if wear is not None and wear.count:
            xy, r, state = wear.snapshot()
            if self.particles is None:
                self.particles = EllipseCollection(2 * r, 2 * r, 0.0, units="xy", offsets=xy,
                                                   offset_transform=self.ax.transData, zorder=4)
                self.ax.add_collection(self.particles)
            self.particles.set_offsets(xy)
            self.particles.set_facecolor(_STATE_COLORS[state])
        half = (s.width / 2) if self.asperities else 2.5
        self.block.set_x(bx - half)
        self.block.set_width(2 * half)
        self.ax.set_xlim(lo, hi)
        self.text.set_text(f"t = {s.time:.3f} s   x = {bx:.3f} mm   v = {s.block.velocity.x * 1e3:.3f} mm/s")
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())

    def save_png(self, path: Path):
        self.fig.savefig(path)

    def close(self):
        self.fig.clear()
