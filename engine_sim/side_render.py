"""Headless side view of a scene (a matplotlib Figure on its own Agg canvas): the block on its spring-mounted pads
over the substrate, as the parts draw themselves (``side`` methods; geometry in :mod:`engine_sim.side_view`).

The vertical exaggeration of the contact zone is printed on the frame, with scale bars for both directions; the
springs' lengths and the block's height are schematic (the frame says so). With :mod:`engine_sim.render` (the
per-pad track map), one of the two matplotlib importers of engine_sim.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib.colors
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from . import units as U

__all__ = ["SideRenderer"]


class SideRenderer:
    """Side-view frames of a :class:`~engine_sim.scene.Scene`; call :meth:`observe` after every output step (the
    grains' states are the recorder's) and :meth:`frame` to draw. ``layout`` and ``shapes`` hold the latest
    frame's geometry (display mm) for tests to read."""

    def __init__(self, scene, dpi: int = 90):
        self.scene = scene
        sc = scene.sc
        self._grains = scene.wear.observer(scene)
        self.layout = scene.arrangement.side_layout(scene)
        mu_lo, mu_hi = scene.substrate.mu_range(sc.friction.mu0)
        self.coloured = mu_hi > mu_lo
        self.norm = matplotlib.colors.Normalize(mu_lo, mu_hi + 1e-12)
        lay = self.layout
        # the drawing's limits (display mm): x from -w/2 - 0.1 slot to the drive's arrow past w/2, y from
        # the scale bars below the substrate's base to the block's top; the figure as tall as their aspect asks,
        # plus three title lines and the key
        H = lay.top - lay.floor
        # the vertical scale bar: true um drawn about 0.5 display mm
        self._um = _round_length(U.to_si(0.5 / lay.E, "length") * 1e6)
        self._bar_y = lay.floor - 0.05 * H - lay.E * U.to_scene(self._um * 1e-6, "length")
        self.xlim = (-lay.width / 2 - 0.1 * lay.slot, lay.width / 2 + 0.3 * lay.slot + lay.drive_len)
        self.ylim = (self._bar_y - 0.06 * H, lay.top + 0.04 * H)
        aspect = (self.ylim[1] - self.ylim[0]) / (self.xlim[1] - self.xlim[0])
        self.fig = Figure(figsize=(11.0, min(8.0, 0.98 * 11.0 * aspect + 1.24)), dpi=dpi)
        FigureCanvasAgg(self.fig)
        self.ax = self.fig.subplots()
        self.shapes = {}
        self.exaggeration_text = ""

    def observe(self):
        """Sample the scene after an output step (grain states, as the recorder classifies them)."""
        self._grains.observe()

    @property
    def states(self) -> np.ndarray:
        return self._grains.states

    def frame(self) -> np.ndarray:
        """Draw the scene's state; returns the RGBA image."""
        s, lay, ax = self.scene, self.layout, self.ax
        ax.clear()
        shapes = dict(s.arrangement.side(s, lay, s.q_pad))
        shapes.update(s.wear.side(s, lay, self.states))
        shapes.update(s.drive.side(s, lay))
        self.shapes = shapes
        for name, (kind, data, style) in shapes.items():
            _draw(ax, kind, data, dict(style), self.norm)
        self._scale_bars()
        ax.set_xlim(*self.xlim)
        ax.set_ylim(*self.ylim)
        ax.set_aspect("equal")
        ax.set_axis_off()
        v = U.to_scene(U.to_si(s.block.velocity.x, "velocity"), "length")  # scene lengths (mm) per s
        vib = getattr(s, "vibration", None)
        caption = ""
        if vib is not None and vib.active:
            caption = next((d for k, d, _ in vib.draw(s, -1.0, 1.0).values() if k == "caption"), "")
        self.exaggeration_text = (f"vertical exaggeration x{lay.E} (substrate relief, contact arcs, grains); "
                                  "springs and block heights schematic")
        ax.set_title(f"{s.sc.name}   t = {s.time:.3f} s   x = {s.block.position.x:.3f} mm   v = {v:.3f} mm/s"
                     + (f"   {caption}" if caption else "") + f"\n{self.exaggeration_text}\n"
                     f"{s.arrangement.side_note(lay)}", loc="left", fontsize=9)
        self._key()
        h = self.fig.get_figheight()
        self._colourbar(h)
        self.fig.subplots_adjust(left=0.01, right=0.99, top=1 - 0.62 / h, bottom=0.62 / h)
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())

    def _scale_bars(self):
        """A horizontal bar of a round length in mm and a vertical one of a round true height (um) at the
        exaggeration, at the lower left, below the substrate's base."""
        lay, ax = self.layout, self.ax
        x, y, um = -lay.width / 2, self._bar_y, self._um
        h = lay.E * U.to_scene(um * 1e-6, "length")
        mm = _round_length(0.1 * lay.width)
        ax.plot([x, x + mm], [y, y], color="k", lw=2, solid_capstyle="butt")
        ax.text(x + mm / 2, y - 0.01 * (lay.top - lay.floor), f"{mm:g} mm", ha="center", va="top", fontsize=8)
        xb = x + mm + 0.02 * lay.width
        ax.plot([xb, xb], [y, y + h], color="k", lw=2, solid_capstyle="butt")
        ax.text(xb + 0.01 * lay.width, y + h / 2, f"{um:g} um" + (f" (drawn x{lay.E})" if lay.E > 1 else ""),
                ha="left", va="center", fontsize=8)

    def _colourbar(self, h: float):
        """The friction coefficient's colour scale, labelled, at the frame's upper right (once per renderer): the
        band under each track's surface takes its colour from it."""
        if not self.coloured or getattr(self, "cbar", None) is not None:
            return
        cax = self.fig.add_axes((0.70, 1 - 0.36 / h, 0.28, 0.1 / h))
        sm = matplotlib.cm.ScalarMappable(norm=self.norm, cmap="viridis")
        self.cbar = self.fig.colorbar(sm, cax=cax, orientation="horizontal")
        self.cbar.ax.tick_params(labelsize=7, length=2, pad=1)
        self.cbar.ax.set_title("friction coefficient of the track (band under its surface)", fontsize=8, pad=2)

    def _key(self):
        handles, labels = [], []
        for kind, _, style in self.shapes.values():
            lab = style.get("label")
            if not lab or lab in labels:
                continue
            if kind == "polys" or kind == "rect":
                fc = style.get("facecolors", style.get("facecolor", "0.5"))
                handles.append(Patch(facecolor=fc, edgecolor=style.get("edgecolors", style.get("edgecolor", "none")),
                                     alpha=style.get("alpha")))
            else:
                handles.append(Line2D([], [], color=style.get("colors", style.get("color", "0.2")), lw=2))
            labels.append(lab)
        handles.append(Line2D([], [], color="k", lw=1))
        labels.append("surface the pads touch")
        for label, colour in self.scene.wear.key():
            handles.append(Line2D([], [], ls="", marker="o", ms=7, mfc=colour, mec="none"))
            labels.append(label)
        self.fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 4), fontsize=8, frameon=False)

    def save_png(self, path: Path):
        self.fig.savefig(path)

    def close(self):
        self.fig.clear()


def _round_length(x: float) -> float:
    """The largest of 1, 2, 5 x 10^k not above x."""
    k = np.floor(np.log10(x))
    for m in (5, 2, 1):
        if m * 10**k <= x:
            return float(m * 10**k)
    return float(10**k)


def _draw(ax, kind, data, style, norm):
    if kind == "segments":
        arr = style.pop("array", None)
        style.pop("label", None)
        lc = LineCollection(data, **style)
        if arr is not None:
            arr = np.asarray(arr, float)
            if np.isnan(arr).all():
                lc.set_color("0.15")
            else:
                lc.set_array(arr)
                lc.set_cmap("viridis")
                lc.set_norm(norm)
        ax.add_collection(lc)
    elif kind == "polys":
        style.pop("label", None)
        arr = style.pop("array", None)
        pc = PolyCollection(data, **style)
        if arr is not None and len(arr):
            pc.set_array(np.asarray(arr, float))
            pc.set_cmap("viridis")
            pc.set_norm(norm)
        ax.add_collection(pc)
    elif kind == "rect":
        style.pop("label", None)
        ax.add_patch(Rectangle(*data, **style))
    elif kind == "text":
        ax.text(*data[0], data[1], **style)
    elif kind == "line":
        style.pop("label", None)
        ax.plot(*data, **style)
    else:
        raise ValueError(f"unknown shape kind {kind!r}")
