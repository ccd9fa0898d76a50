"""An elastic sole: N flat feet side by side on one shared track, under a block free vertically (load
redistribution: the block's weight is shared by whichever feet stand on asperities; section 7)."""
from __future__ import annotations

import math

import numpy as np
import pymunk

from ..regime import dt_limit
from .arrangement import ARRANGEMENTS, Arrangement, PadSpec, track_rng


@ARRANGEMENTS.register
class Sole(Arrangement):
    """Feet of ``foot_length`` (ends rounded with ``radius``), normal springs relaxed (the feet that stand on bumps
    carry the block between them), lateral springs of rest length foot_length between foot centres."""

    name = "sole"
    Spec = PadSpec
    guided = False

    preloaded = False  # relaxed normal springs: the feet that stand on bumps carry the block

    def limits(self):
        """The feet's tangential springs and contact thickness (the mean foot load), and run.dt against the block's
        vertical mode on its N normal springs."""
        p, M = self.spec, self.sc.block.M
        return super().limits() + [dt_limit("run.dt", self.sc, math.sqrt(p.N * p.k_normal / M), p.N * p.c_normal / M,
                                            f"the block on its {p.N} normal foot springs")]

    def contact_width(self):
        return self.spec.N * self.spec.foot_length

    def width(self):
        return self.spec.N * self.own.foot_length

    def build(self, scene):
        p, o = self.spec, self.own
        space = scene.space
        m_p, R = o.mass, o.radius
        foot = o.foot_length
        x_start = scene.substrate.x_start(scene)
        for i in range(p.N):
            pad = pymunk.Body(m_p, float("inf"))
            xp = (i - (p.N - 1) / 2) * foot
            yp = scene.substrate.top() + R + 1e-3  # the feet start just above the highest bump
            flt = pymunk.ShapeFilter(group=1)  # feet do not collide with each other
            half = foot / 2 - R - 0.05 * foot  # a small gap between neighbouring feet
            shape = pymunk.Segment(pad, (-half, 0.0), (half, 0.0), R)
            pad.position = (xp, yp)
            pad.velocity = (scene.v_law, 0.0)
            shape.friction = scene.q_pad
            shape.filter = flt
            space.add(pad, shape)
            self._mount(scene, pad, xp, yp, 0.0)
            scene.law.build(scene, pad, o.c)
            if i == 0:  # one track shared by the sole's feet
                scene.tracks.append(scene.substrate.build(space, 0.0, pymunk.ShapeFilter(), track_rng(scene, 0),
                                                          scene.mu_track, x_start))  # mu0: no grains on a sole
            self._add_pad(scene, pad, yp, xp, flt, R)
        if p.k1 > 0 or p.c1 > 0:
            for i in range(p.N - 1):
                c = pymunk.DampedSpring(scene.pads[i], scene.pads[i + 1], (0, 0), (0, 0), foot, o.k1, o.c1)
                space.add(c)
                scene.slider_springs.append(c)

    def maintain(self, scene):
        scene.tracks[0].maintain(scene.block.position.x, scene.ahead, scene.behind)

    def side_layout(self, scene):
        """The whole sole over its one track, at the exaggeration that shows h_max at about half a display mm."""
        from ..side_view import SideLayout, nice_exaggeration

        p = self.spec
        relief = self.own.relief
        E = nice_exaggeration(relief, 0.5)
        w = scene.width
        hc = min(self.own.radius, 0.3 / E)
        lay = SideLayout(E=E, slot=w / p.N, n_show=p.N, contact=E * (relief + hc), body=0.025 * w,
                         spring=0.1 * w, block=0.05 * w, floor=-0.04 * w)
        lay.x0 = np.zeros(p.N)  # one continuous track: true positions, no slots
        return lay

    def side(self, scene, lay, q_pad):
        """The feet as pymunk has them (capsules: flat undersides, rounded ends) up to the contact zone's top, their
        normal springs to the block, and the asperities under them, in true positions across the whole sole."""
        from ..side_view import body_outline, capsule_outline, zigzag

        bx = scene.block.position.x
        tr = scene.tracks[0]
        half = 0.5 * lay.width + 0.05 * lay.width
        xs = bx + np.linspace(-half, half, 2000)
        top, _ = scene.substrate.side(tr, xs[0], xs[-1], xs, q_pad)
        xd = xs - bx
        yd = np.maximum(lay.y(top - tr.y), lay.floor)
        fill = np.column_stack([np.r_[xd[0], xd, xd[-1]], np.r_[lay.floor, yd, lay.floor]])
        feet, springs = [], []
        R = self.own.radius
        hc = min(R, 0.3 / lay.E)
        for pad in scene.pads:
            for sh in pad.shapes:
                a, b = pad.local_to_world(sh.a), pad.local_to_world(sh.b)
                out = capsule_outline(a.x - bx, b.x - bx, 0.5 * (a.y + b.y) - tr.y, R, hc)
                out[:, 1] = lay.y(out[:, 1])
                y_top = out[0, 1] + lay.body
                # its true shape, heights exaggerated, true length (rounded ends included)
                feet.append(body_outline(min(a.x, b.x) - bx, max(a.x, b.x) - bx, 0.5 * (a.y + b.y) - tr.y, R, lay.E,
                                         y_top))
                xm = 0.5 * (a.x + b.x) - bx
                springs.append(zigzag((xm, y_top), (xm, lay.block_bottom), coils=4, width=0.3 * lay.slot))
        return {
            "substrate": ("polys", [fill], {"facecolors": "0.82", "edgecolors": "none", "zorder": 1,
                                            "label": "substrate: asperity caps"}),
            "surface": ("segments", _pieces(xd, yd, yd > lay.floor), {"colors": "k", "linewidths": 0.8, "zorder": 2}),
            "normal": ("segments", springs, {"colors": "tab:purple", "linewidths": 0.8, "zorder": 3,
                                             "label": f"normal spring k_normal = {self.spec.k_normal:.4g} N/m"}),
            "pads": ("polys", feet, {"facecolors": "tab:orange", "edgecolors": "k", "linewidths": 0.6, "zorder": 4,
                                     "label": f"foot {0.9 * self.spec.foot_length * 1e3:.3g} mm on a {self.spec.foot_length * 1e3:.3g} "
                                              f"mm pitch (true shape, heights x{lay.E})"}),
            "block": ("rect", ((-lay.width / 2, lay.block_bottom), lay.width, lay.block),
                      {"facecolor": "tab:blue", "alpha": 0.45, "edgecolor": "tab:blue", "zorder": 2,
                       "label": f"block M = {self.sc.block.M:.4g} kg, free vertically"}),
        }

    def side_note(self, lay):
        return (f"the whole sole: {self.spec.N} feet on one track (tangential springs k0 = {self.spec.k0:.4g} N/m not "
                "drawn)")

    def view(self, scene):
        """Micrometre relief under a centimetre sole: the axes zoom onto the interface."""
        h = scene.substrate.top()
        ylim = (-0.5 * h, 3 * h)
        return {"window": 0.65 * self.spec.N * self.spec.foot_length, "ylim": ylim,
                "ylabel": "y (mm, exaggerated): asperity caps under the feet", "track_width": 1.5,
                "block_top": ylim[1] - 0.12 * (ylim[1] - ylim[0]), "block_half": scene.width / 2}

    def draw(self, scene, lo, hi, view):
        """Feet filled from their underside up into the block, which rests on them."""
        top = view["ylim"][1]
        feet = []
        for p in scene.pads:
            for sh in p.shapes:
                a, b = p.local_to_world(sh.a), p.local_to_world(sh.b)
                bot = 0.5 * (a.y + b.y) - sh.radius
                feet.append([(a.x, bot), (b.x, bot), (b.x, top), (a.x, top)])
        return {"feet": ("polys", feet, {"facecolors": (0.84, 0.15, 0.16, 0.35), "edgecolors": "tab:red",
                                         "linewidths": 1.5, "zorder": 3, "label": "foot of the sole"})}


def _pieces(x, y, keep) -> list:
    """The runs of the polyline (x, y) where ``keep`` holds, as (n, 2) arrays: the caps' envelope drawn where a cap
    reaches above the drawing's base, none between (the scene has no floor there)."""
    edges = np.flatnonzero(np.diff(np.r_[0, keep.astype(int), 0]))
    return [np.column_stack([x[a:b], y[a:b]]) for a, b in zip(edges[::2], edges[1::2]) if b - a >= 2]
