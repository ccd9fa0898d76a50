"""Headless rendering of a scene (a matplotlib Figure on its own Agg canvas, collections updated in place:
~20-100 ms a frame; pads_multiscale's two panels ~290 ms).

Draws a window around the block: the substrate (friction patches coloured by mu, or the rough profile, or the
asperity caps), the pads or feet, their springs, the block, the drive's own bodies, wear particles coloured by
state (trapped: at rest on the substrate; moving), the time above the axes and a key below them. The parts say
what to draw as named shapes in scene units, ``name -> (kind, data, style)`` with kind one of "points" (xy array),
"segments" (list of point pairs), "polys" (list of vertex lists), "line" ((xs, ys)), "circle" ((centre, radius)),
"rect" ((corner, width, height)), "text" ((position, string)), "caption" (a string added to the time line above
the axes, for a part's numbers that would cover the scene); style is passed to matplotlib, and a shape whose
style has a "label" gets an entry in the key. With :mod:`engine_sim.side_render` (the side view), one of the two
matplotlib importers of engine_sim (an import contract in pyproject.toml).
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

__all__ = ["SceneRenderer"]


class SceneRenderer:
    """Draws frames of a :class:`~engine_sim.scene.Scene`; call :meth:`observe` after every output step (grain
    states are the recorder's: one classifier for traces and frames) and :meth:`frame` to draw.

    Layout: the scene's axes (and, when the arrangement's view asks with a ``zoom`` entry, a second panel
    enlarging part of it, framed in the first); the time line as the first panel's title and the key (the parts'
    labelled shapes, the tracks, the block) below the axes, so no text lies over the scene."""

    def __init__(self, scene, window: float | None = None, dpi: int = 90):
        self.scene = scene
        sc = scene.sc
        self._grains = scene.wear.observer(scene)  # the grains' states, by the recorder's own classifier
        view = scene.wear.view(scene, scene.arrangement.view(scene))
        self.zoom = view.get("true_size", False)  # pads drawn at their true size, axes of equal aspect
        self.view = view
        inset = view.get("zoom")
        # a Figure on its own Agg canvas: importing or rendering never changes the program's matplotlib backend
        self.fig = Figure(figsize=(11.0, 5.6) if inset else (7.0, 5.4), dpi=dpi)
        FigureCanvasAgg(self.fig)
        axes = self.fig.subplots(1, 2, width_ratios=(1, 1.25)) if inset else [self.fig.subplots()]
        self.ax = axes[0]
        mu_lo, mu_hi = scene.substrate.mu_range(sc.friction.mu0)
        self.q_pad = scene.q_pad  # pad-track friction = shape friction x q_pad
        self.norm = matplotlib.colors.Normalize(mu_lo, mu_hi + 1e-12)
        self.coloured = mu_hi > mu_lo  # tracks coloured by their friction, with a colour bar
        self.panels = [self._panel(axes[0], view, window)]
        if inset:
            self.panels.append(self._panel(axes[1], {**view, **inset}, None))
            lo, hi = inset["ylim"]
            self.frame_box = Rectangle((0, lo), 2 * U.to_scene(inset["window"], "length"), hi - lo, fill=False, ec="k", lw=1.0,
                                       ls="--", zorder=7)
            self.ax.add_patch(self.frame_box)
            axes[1].set_title(inset["title"], loc="left", fontsize=9)
        self.window = self.panels[0]["window"]
        self.ylim = view["ylim"]
        if self.zoom:
            self.ax.set_aspect("equal", adjustable="box")
        # the time line: above the axes, not over the scene (a placeholder of its size for the layout)
        self.text = self.ax.set_title("t = 0.000 s   x = 0.000 mm   v = 0.000 mm/s", loc="left", fontsize=9)
        self._legend = None
        self.fig.tight_layout(rect=(0, 0.09, 1, 1))  # the bottom 9 %: the key
        if mu_hi > mu_lo:  # a colour bar exactly as tall as the last axes (also when their aspect is fixed)
            self.fig.subplots_adjust(right=0.89 if inset else 0.86)
            cb = self.fig.colorbar(self.panels[-1]["tracks"], cax=axes[-1].inset_axes([1.03, 0.0, 0.035, 1.0]))
            cb.set_label("patch friction coefficient")
        else:
            for pn in self.panels:
                pn["tracks"].set_cmap(matplotlib.colors.ListedColormap(["0.25"]))

    def _panel(self, ax, view, window):
        """One axes with its window (mm either side of the block), tracks and block."""
        ax.set_ylabel(view["ylabel"])
        ax.set_ylim(*view["ylim"])
        ax.set_xlabel("x (mm)")
        tracks = LineCollection([], cmap="viridis", norm=self.norm, linewidths=view["track_width"])
        ax.add_collection(tracks)
        top = view["block_top"]
        block = Rectangle((0, top), 8.0, view["ylim"][1] - top, color="tab:blue", alpha=0.35, zorder=4)
        ax.add_patch(block)
        return {"ax": ax, "view": view, "window": U.to_scene(view["window"] if window is None else window, "length"),
                "tracks": tracks, "block": block, "artists": {}}

    def _key(self):
        """The key below the axes: what each colour and mark is (the parts' labelled shapes first)."""
        handles, labels = [], []
        for art in self.panels[-1]["artists"].values():
            lab = art.get_label()
            if lab and not lab.startswith("_") and lab not in labels:
                if isinstance(art, EllipseCollection):  # no legend handle of its own: a disc marker of its colour
                    art = Line2D([], [], ls="", marker="o", ms=9, mfc=art.get_facecolor()[0], mec="none")
                handles.append(art)
                labels.append(lab)
        if self.coloured:
            handles.append(Line2D([], [], color=matplotlib.cm.viridis(0.6), lw=3))
            labels.append(self.view.get("track_label", "track (colour: patch friction)"))
        else:  # one friction coefficient: grey tracks, no colour bar
            handles.append(Line2D([], [], color="0.25", lw=3))
            labels.append("track")
        handles.append(Rectangle((0, 0), 1, 1, color="tab:blue", alpha=0.35))
        labels.append("block")
        for label, colour in self.scene.wear.key():
            handles.append(Line2D([], [], ls="", marker="o", ms=7, mfc=colour, mec="none"))
            labels.append(label)
        self._legend = self.fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 5), fontsize=8,
                                       frameon=False, bbox_to_anchor=(0.5, 0.0))

    def observe(self):
        """Sample the scene after an output step (the recorder classifies grains on their mean speed over it)."""
        self._grains.observe()

    @staticmethod
    def _shapes(panel, shapes: dict):
        """Create (first time) or update the artists of the parts' named shapes."""
        for name, (kind, data, style) in shapes.items():
            if kind == "caption":
                panel["caption"] = data
                continue
            art = panel["artists"].get(name)
            if art is None:
                art = panel["artists"][name] = _new_artist(panel["ax"], kind, data, style)
            _update_artist(art, kind, data)

    def frame(self) -> np.ndarray:
        """Update the artists to the scene's state and render; returns the RGBA image."""
        s = self.scene
        bx = s.block.position.x
        for k, pn in enumerate(self.panels):
            lo, hi = bx - pn["window"], bx + pn["window"]
            segs, mus = s.arrangement.draw_tracks(s, lo, hi, self.q_pad)
            pn["tracks"].set_segments(segs)
            pn["tracks"].set_array(np.asarray(mus))
            if self.zoom:  # pads at their true size
                pads = np.array([(p.position.x, p.position.y) for p in s.pads])
                self._shapes(pn, {"pad_discs": ("discs", (pads, 2 * s.R_pad), {"facecolors": "tab:orange",
                                                                                "alpha": 0.6, "zorder": 3,
                                                                                "label": "pad"})})
            else:
                self._shapes(pn, s.arrangement.draw(s, lo, hi, pn["view"]))
            if k == 0:
                self._shapes(pn, s.drive.draw(s, lo, hi))
                if getattr(s, "vibration", None) is not None:  # [vibration]: its phase dial and caption
                    self._shapes(pn, s.vibration.draw(s, lo, hi))
                self._shapes(pn, s.wear.draw(self.states))
            half = pn["view"]["block_half"]
            pn["block"].set_x(bx - half)
            pn["block"].set_width(2 * half)
            pn["ax"].set_xlim(lo, hi)
        if len(self.panels) > 1:
            self.frame_box.set_x(bx - self.panels[1]["window"])
        if self._legend is None:
            self._key()
        v = U.to_scene(U.to_si(s.block.velocity.x, "velocity"), "length")  # scene lengths (mm) per s
        caption = self.panels[0].get("caption")
        self.text.set_text(f"t = {s.time:.3f} s   x = {bx:.3f} mm   v = {v:.3f} mm/s" + (f"   {caption}" if caption else ""))
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())

    @property
    def states(self) -> np.ndarray:
        """The grains' states at the latest observed output step (0 idle, 1 trapped, 2 moving), as recorded."""
        return self._grains.states

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
    if kind == "discs":  # (centres, diameters[, face colours])
        xy, d = data[:2]
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
    if kind == "points":
        art.set_offsets(data)
    elif kind == "discs":
        art.set_offsets(data[0])
        if len(data) > 2:
            art.set_facecolor(data[2])
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
