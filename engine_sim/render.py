"""Headless rendering of a scene (matplotlib Agg, collections updated in place: ~20-60 ms a frame).

Draws a window around the block: each track's friction patches coloured by mu, the pads, their
tangential springs to the block, the block, and the time. The only matplotlib importer of engine_sim.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from . import units as U  # noqa: E402

__all__ = ["SceneRenderer"]


class SceneRenderer:
    """Draws frames of a :class:`~engine_sim.scene.Scene`; call :meth:`frame` after stepping."""

    def __init__(self, scene, window: float | None = None, dpi: int = 90):
        self.scene = scene
        self._pads = set(scene.pads)
        sc = scene.sc
        self.window = (window or 12 * sc.substrate.a) * U.LENGTH  # mm either side of the block
        self.fig, self.ax = plt.subplots(figsize=(7.0, 5.0), dpi=dpi)
        ax = self.ax
        ys = np.array(scene.pad_y)
        self.ylim = (ys.min() - 3.0, scene.y_block + 4.0)
        ax.set_ylim(*self.ylim)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm): one track per pad")
        mu0, al = sc.friction.mu0, sc.substrate.alpha
        self.norm = matplotlib.colors.Normalize(mu0 * (1 - al / 2), mu0 * (1 + al / 2) + 1e-12)
        self.tracks = LineCollection([], cmap="viridis", norm=self.norm, linewidths=3)
        ax.add_collection(self.tracks)
        self.springs = LineCollection([], colors="0.4", linewidths=0.6)
        ax.add_collection(self.springs)
        self.pads = ax.scatter([], [], s=18, c="tab:red", zorder=3)
        self.block = Rectangle((0, ys.max() + 1.0), 8.0, self.ylim[1] - ys.max() - 2.0, color="tab:blue", alpha=0.35)
        ax.add_patch(self.block)
        self.text = ax.text(0.02, 0.01, "", transform=ax.transAxes, va="bottom", fontsize=9,
                            bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        cb = self.fig.colorbar(self.tracks, ax=ax, fraction=0.04)
        cb.set_label("patch friction coefficient")
        self.fig.tight_layout()

    def frame(self) -> np.ndarray:
        """Update the artists to the scene's state and render; returns the RGBA image."""
        s = self.scene
        bx = s.block.position.x
        lo, hi = bx - self.window, bx + self.window
        segs, mus = [], []
        for tr in s.tracks:
            for seg in tr.segments:
                if seg.b.x >= lo and seg.a.x <= hi:
                    segs.append(((seg.a.x, seg.a.y), (seg.b.x, seg.b.y)))
                    mus.append(seg.friction)
        self.tracks.set_segments(segs)
        self.tracks.set_array(np.asarray(mus))
        pads = np.array([(p.position.x, p.position.y) for p in s.pads])
        self.pads.set_offsets(pads)
        anchors = [c.a.local_to_world(c.anchor_a) for c in s.space.constraints
                   if getattr(c, "a", None) is s.block and c.b in self._pads and c.anchor_a.x < 0]
        self.springs.set_segments([((a.x, a.y), (p[0], p[1])) for a, p in zip(anchors, pads)])
        self.block.set_x(bx - 5.0)
        self.block.set_width(5.0)
        self.ax.set_xlim(lo, hi)
        self.text.set_text(f"t = {s.time:.3f} s   x = {bx:.3f} mm   v = {s.block.velocity.x * 1e3:.3f} mm/s")
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())

    def save_png(self, path: Path):
        self.fig.savefig(path)

    def close(self):
        plt.close(self.fig)
