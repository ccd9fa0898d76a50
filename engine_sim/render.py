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
        self.asperities = scene.asperities
        self.zoom = scene.wear is not None  # grains of tens of um: zoom onto the first pad's track
        # grain states come from a recorder that keeps only its latest sample (the trace's own classifier)
        self._rec = Recorder(scene, 1) if scene.wear is not None else None
        if window is None:
            window = (0.65 * sc.pads.N * sc.pads.foot_length if self.asperities
                      else 0.6 * sc.wear.ahead if self.zoom else 12 * sc.substrate.a)
        self.window = window * U.LENGTH  # mm either side of the block
        # a Figure on its own Agg canvas: importing or rendering never changes the program's matplotlib backend
        self.fig = Figure(figsize=(7.0, 5.0), dpi=dpi)
        FigureCanvasAgg(self.fig)
        self.ax = ax = self.fig.subplots()
        ys = np.array(scene.pad_y)
        if self.asperities:  # micrometre relief under a centimetre sole: the axes zoom onto the interface
            h = scene.substrate.top()
            self.ylim = (-0.5 * h, 3 * h)
            ax.set_ylabel("y (mm, exaggerated): asperity caps under the feet")
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
        # feet of the sole: filled from their underside up into the block, which rests on them
        self.feet = PolyCollection([], facecolors=(0.84, 0.15, 0.16, 0.35), edgecolors="tab:red", linewidths=1.5, zorder=3)
        ax.add_collection(self.feet)
        self.pads = ax.scatter([], [], s=18, c="tab:red", zorder=3)
        top = self.ylim[1] - 0.12 * (self.ylim[1] - self.ylim[0]) if self.asperities else ys.max() + 1.0
        self.block = Rectangle((0, top), 8.0, self.ylim[1] - top, color="tab:blue", alpha=0.35, zorder=4)
        ax.add_patch(self.block)
        self.particles = None
        self.text = ax.text(0.02, 0.01, "", transform=ax.transAxes, va="bottom", fontsize=9, zorder=6,
                            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        self._leonardo = self._add_pulley() if scene.hanging is not None else None
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

    def _add_pulley(self):
        """Leonardo's slider: the rope from the block over a pulley at the window's edge to the hanging mass (the
        scene carries the hanging mass unfolded on a line ahead; drawn here folded, as in the paper's Fig. 7)."""
        ax = self.ax
        rope = Line2D([], [], color="0.15", lw=1.2, zorder=5)
        ax.add_line(rope)
        pulley = Circle((0, 0), 1.2, facecolor="0.85", edgecolor="0.2", zorder=5)
        ax.add_patch(pulley)
        mass = Rectangle((0, 0), 3.0, 8.0, facecolor="tab:brown", edgecolor="0.2", alpha=0.9, zorder=5)
        ax.add_patch(mass)
        label = ax.text(0, 0, f"hanging mass\n{self.scene.hanging.mass / U.MASS:.3g} kg", fontsize=8, ha="right",
                        va="center", zorder=6, bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        return rope, pulley, mass, label

    def observe(self):
        """Sample the scene after an output step (the recorder classifies grains on their mean speed over it)."""
        if self._rec is not None:
            self._rec.k = 0  # keep only the latest sample
            self._rec.sample()

    def _substrate(self, lo, hi):
        """Ask the substrate part to draw each track within [lo, hi]."""
        segs, mus = [], []
        for tr in self.scene.tracks:
            s, m = self.scene.substrate.draw(tr, lo, hi, self.q_pad)
            segs += s
            mus += m
        return segs, mus

    def _draw_leonardo(self, bx, hi):
        rope, pulley, mass, label = self._leonardo
        s = self.scene
        y = s.y_block
        px, py = hi - 2.0, y
        pulley.center = (px, py)
        used = s.hanging.position.x - bx  # the rope's span between block and hanging mass (mm)
        my = py - 30.0  # the hanging mass drawn a fixed 30 mm below the pulley (it follows the block)
        rope.set_data([bx + 2.5, px, px + 1.2, px + 1.2], [y, py + 1.2, py, my + 8.0])
        mass.set_xy((px + 1.2 - 1.5, my))
        label.set_position((px - 1.0, my + 4.0))
        slack = s.sc.drive.rope_length * U.LENGTH - used
        label.set_text(f"hanging mass {s.hanging.mass / U.MASS:.3g} kg\nrope slack {slack / U.LENGTH * 1e6:+.2f} um")

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
                    bot = 0.5 * (a.y + b.y) - sh.radius  # the foot's underside, filled up into the block
                    feet.append([(a.x, bot), (b.x, bot), (b.x, self.ylim[1]), (a.x, self.ylim[1])])
            self.feet.set_verts(feet)
        elif self.zoom:  # pads at their true size
            if not hasattr(self, "_pad_disc"):
                d = 2 * s.R_pad
                self._pad_disc = EllipseCollection(d, d, 0.0, units="xy", offsets=pads, offset_transform=self.ax.transData,
                                                   facecolors="tab:orange", alpha=0.6, zorder=3)
                self.ax.add_collection(self._pad_disc)
            self._pad_disc.set_offsets(pads)
        else:
            self.pads.set_offsets(pads)
            anchors = [c.a.local_to_world(c.anchor_a) for c in s.tangential_springs]
            self.springs.set_segments([((a.x, a.y), (p[0], p[1])) for a, p in zip(anchors, pads)])
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
        half = (s.width / 2) if self.asperities else 2.5
        self.block.set_x(bx - half)
        self.block.set_width(2 * half)
        if self._leonardo is not None:
            self._draw_leonardo(bx, hi)
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
