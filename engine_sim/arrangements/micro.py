"""Pads that carry micro-pads: the scene of model Ib (the paper's Fig. 1c and sections 10-11).

Each pad (a miniblock, on its own track of friction patches of renewal length a, as in "tracks") carries n
micro-pads (microblocks), each spring-mounted on it (tangential k2, c2; a pre-compressed normal spring) and
sliding on a micro-track of its own: friction patches of renewal length a2 and contrast alpha2. Model Ib:

    m x_i''   = -k0 (x_i - x) - ... - f_i(t) - sum_j [k2 (x_i - y_ij) + c2 (x_i' - y_ij')]
    m2 y_ij'' = -k2 (y_ij - x_i) - c2 (y_ij' - x_i') - c_micro y_ij' - mu0 N2 - f_ij(t)

Loads: a pad column (pad and its micro-pads) carries L = M g cos(theta) / N + (m + n m2) g; its micro-pads carry
``micro_share`` L together (N2 = micro_share L / n each) and the pad's own contact the rest, N1 = (1 -
micro_share) L. Every sliding body follows the scenario's friction law, with viscous slope c (pads) or micro_c
(micro-pads). Micro-tracks lie between pad i's track and pad i+1's (``micro_spacing`` apart) and share one
ShapeFilter category (bit 31) that no pad uses, so micro-pads meet only their own tracks.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk

from frictionnoise.base import G
from frictionnoise.base import check_number

from ..substrates.patches import Patches, PatchesSpec
from functools import cached_property

from ..regime import SPRING_DAMPING_X, SPRING_OMEGA_DT, Limit, load_limit, mass_limit
from .arrangement import ARRANGEMENTS, LT, PadSpec
from .tracks import Tracks

_MICRO_BIT = 31


@dataclass(frozen=True)
class MicroSpec(PadSpec):
    """The pads of "tracks" plus, per pad: n_micro micro-pads of micro_mass (kg) and micro_radius (m), held by a
    tangential spring micro_k (N/m, the k2 of model Ib) with damping micro_c_spring (N s/m) and a normal spring
    micro_k_normal (N/m); their micro-tracks: renewal length micro_a (m, a2) and patch contrast micro_alpha (mu =
    mu0 (1 + micro_alpha (r - 1/2)), as the patches substrate states its alpha), micro_spacing (m) apart in y; the
    micro-pads' viscous slope micro_c (N s/m each) and their share of the column's load micro_share.

    micro_c_spring > 0 together with micro_c > 0 puts two dampers on one micro-pad; pymunk iterates their impulses
    within a step, so the drag departs from the c v the recorder reads (force and energy balance off by 1.1 % at
    micro_c_spring = 0.16, micro_c = 2.5, 2 iterations; 1e-5 with either one zero, measured)."""

    arrangement: str = "micro"
    n_micro: int = 4
    micro_mass: float = 1e-4
    micro_radius: float = 0.1e-3
    micro_k: float = 300.0
    micro_c_spring: float = 0.0
    micro_k_normal: float = 100.0
    micro_a: float = 0.1e-3
    micro_alpha: float = 1.0
    micro_spacing: float = 1e-3
    micro_c: float = 1.25
    micro_share: float = 0.5


@ARRANGEMENTS.register
class Micro(Tracks):
    name = "micro"
    also_fits = ("model_Ib",)  # micro-pads: the multiscale model beside model I
    Spec = MicroSpec
    hosts_wear = False
    positive = Tracks.positive | {"n_micro", "micro_mass", "micro_radius", "micro_k", "micro_k_normal", "micro_a",
                                  "micro_spacing"}
    non_negative = Tracks.non_negative | {"micro_c_spring", "micro_alpha", "micro_c", "micro_share"}

    @classmethod
    def validate(cls, p, sc):
        super().validate(p, sc)
        if p.N > _MICRO_BIT:
            raise ValueError(f"pads.N = {p.N} must be at most {_MICRO_BIT} with micro-pads (one filter bit per pad "
                             "track, one for the micro-tracks)")
        check_number("pads.micro_share", p.micro_share, below=1, why="the pad keeps a contact of its own")
        check_number("pads.micro_alpha", p.micro_alpha, below=2, why="patch friction stays positive")
        room = p.track_spacing - p.n_micro * p.micro_spacing
        if room < 2.5 * (p.radius + sc.substrate.segment_radius):
            raise ValueError(f"pads.micro_spacing = {p.micro_spacing:.3g} m: n_micro micro-tracks must fit between two "
                             f"pad tracks (n_micro micro_spacing + 2.5 (pad + segment radius) <= track_spacing)")
        if p.micro_spacing < 2.5 * (p.micro_radius + sc.substrate.segment_radius):
            raise ValueError(f"pads.micro_spacing = {p.micro_spacing:.3g} m must exceed 2.5 (micro_radius + segment "
                             f"radius) = {2.5 * (p.micro_radius + sc.substrate.segment_radius):.3g} m")
        a = cls(p, sc)
        if not a.micro_load() > p.micro_mass * G:
            raise ValueError(f"pads.micro_share = {p.micro_share!r} leaves a micro-pad {a.micro_load():.3g} N, less than "
                             "its own weight: its normal spring would pull it off its track")

    def dt_limit(self):
        """omega dt < 0.3 for the pad (k0 + k_normal + 4 k1 + n (micro_k + micro_k_normal) on its mass) and for a
        micro-pad (micro_k + micro_k_normal on micro_mass); spring damping c dt / m < 0.1 for both."""
        p = self.spec
        k = p.k0 + p.k_normal + 4 * p.k1 + p.n_micro * (p.micro_k + p.micro_k_normal)
        lim = min(SPRING_OMEGA_DT / math.sqrt(k / p.mass),
                  SPRING_OMEGA_DT / math.sqrt((p.micro_k + p.micro_k_normal) / p.micro_mass))
        c = p.c0 + p.c_normal + 2 * p.c1 + p.n_micro * p.micro_c_spring
        if c > 0:
            lim = min(lim, SPRING_DAMPING_X * p.mass / c)
        if p.micro_c_spring > 0:
            lim = min(lim, SPRING_DAMPING_X * p.micro_mass / p.micro_c_spring)
        return lim

    # ------------------------------------------------------------------ loads and friction (SI)
    @property
    def column_mass(self):
        return self.spec.mass + self.spec.n_micro * self.spec.micro_mass

    def micro_load(self) -> float:
        """N2: the normal load on one micro-pad's contact (N)."""
        return self.spec.micro_share * self.sc.normal_load_per_pad / self.spec.n_micro

    def pad_load(self):
        """N1: the normal load on the pad's own contact (N)."""
        return self.sc.normal_load_per_pad - self.spec.n_micro * self.micro_load()

    def column_force(self, v):
        law, p = self.sc.law_part, self.spec
        return law.force(v, self.pad_load(), self.sc.friction.c) + p.n_micro * law.force(v, self.micro_load(), p.micro_c)

    def column_slope(self, v):
        law, p = self.sc.law_part, self.spec
        return law.slope(v, self.pad_load(), self.sc.friction.c) + p.n_micro * law.slope(v, self.micro_load(), p.micro_c)

    def column_friction(self, load):
        """The pad's friction under N1 and its micro-pads' under N2, each on its stickiest patch (N)."""
        return self._pad_friction((1 - self.spec.micro_share) * load) + self.spec.n_micro * self._micro_friction(load)

    def _pad_friction(self, n1):
        sc = self.sc
        mu0 = sc.friction.mu0
        v = max(sc.steady_velocity, 0.0)
        return sc.law_part.force(v, n1, sc.friction.c) + (sc.substrate_part.mu_range(mu0)[1] - mu0) * n1

    def _micro_friction(self, load):
        """One micro-pad's largest friction under the column load ``load`` (N): its micro-track's stickiest patch."""
        sc, p = self.sc, self.spec
        n2 = p.micro_share * load / p.n_micro
        v = max(sc.steady_velocity, 0.0)
        return sc.law_part.force(v, n2, p.micro_c) + sc.friction.mu0 * p.micro_alpha / 2 * n2

    def contact_load(self, load):
        return (1 - self.spec.micro_share) * load

    def limits(self):
        """The pads' limits, and the micro-pads' tangential spring (micro_k) against their largest friction."""
        out = super().limits()
        sc, p = self.sc, self.spec
        f = self._micro_friction(sc.normal_load_per_pad)
        L_max = load_limit(self._micro_friction, p.micro_k * LT)
        out.append(Limit("block.M", sc.block.M, mass_limit(sc, L_max), "kg",
                         f"a micro-pad's largest friction {f:.4g} N stretches its tangential spring (micro_k = "
                         f"{p.micro_k:.4g} N/m) by {f / p.micro_k * 1e3:.3g} mm; beyond its length "
                         f"{LT * 1e3:.3g} mm the micro-pad passes the spring's anchor",
                         fix=f"raise pads.micro_k above {f / LT:.4g} N/m"))
        return out

    def sliders(self, sc):
        return [(self.pad_load(), self.spec.mass), (self.micro_load(), self.spec.micro_mass)]

    def describe(self):
        """``micro``: what model Ib needs of the micro level (SI): n, mass, k, c (the micro spring's damping),
        length_scale a2, friction_law (keys as the pads'), patch_contrast alpha2."""
        p, law = self.spec, self.sc.law_part
        return {"micro": {"n": p.n_micro, "mass": p.micro_mass, "k": p.micro_k, "c": p.micro_c_spring,
                          "length_scale": p.micro_a, "friction_law": law.describe(self.micro_load(), p.micro_c),
                          "patch_contrast": p.micro_alpha}}

    # ------------------------------------------------------------------ build (scene units)
    @cached_property
    def micro_substrate(self):
        """The micro-tracks' substrate part (patches of a2, alpha2), bound by the scene's builder with this part."""
        s = self.sc.substrate
        return Patches(PatchesSpec(a=self.spec.micro_a, alpha=self.spec.micro_alpha, segment_radius=s.segment_radius),
                       self.sc)

    def subparts(self) -> list:
        return [self.micro_substrate]

    def scene_inputs(self) -> dict:
        """The pads' values and the micro-pads': their mass, radius, spacing and springs, their contact's load N2,
        their normal spring's pre-load, and the micro-tracks' margins (the patches' own, 8 a2 ahead and 4 a2 behind,
        without the room for wear particles, none here)."""
        p = self.spec
        return {**super().scene_inputs(), "micro_mass": (p.micro_mass, "mass"),
                "micro_radius": (p.micro_radius, "length"), "micro_spacing": (p.micro_spacing, "length"),
                "micro_k": (p.micro_k, "stiffness"), "micro_c_spring": (p.micro_c_spring, "damping"),
                "micro_k_normal": (p.micro_k_normal, "stiffness"), "micro_c": (p.micro_c, "damping"),
                "micro_load": (self.micro_load(), "force"),
                "micro_preload": (self.micro_load() - p.micro_mass * G, "force"),
                "pad_load": (self.pad_load(), "force"),
                "micro_ahead": (8 * p.micro_a, "length"), "micro_behind": (4 * p.micro_a, "length")}

    def build(self, scene):
        """The pads and their tracks as "tracks" builds them (the pad's own load N1), then per pad its micro-pads,
        their springs, friction law and micro-tracks; the micro-pads join the sliding bodies after the pads."""
        super().build(scene)
        p, o = self.spec, self.own
        LT, LN = o.LT, o.LN
        space = scene.space
        n = p.n_micro
        sub = self.micro_substrate
        self.micro_pads, self.micro_tracks = [], []
        m2, r2 = o.micro_mass, o.micro_radius
        rs = self.ctx.segment_radius
        N2 = o.micro_load
        pre = o.micro_preload / o.micro_k_normal + scene.slop
        flt = pymunk.ShapeFilter(categories=1 << _MICRO_BIT, mask=1 << _MICRO_BIT)
        seeds = np.random.SeedSequence(scene.seed).spawn(p.N + 1 + p.N * n)[p.N + 1:]  # after the tracks' and grains'
        x_start = sub.x_start(scene)
        for i, pad in enumerate(scene.pads):
            y_track = scene.track_surface[i] - rs  # pad i's track line
            for j in range(n):
                yt = y_track - (j + 1) * o.micro_spacing
                body = pymunk.Body(m2, float("inf"))
                body.position = (pad.position.x, yt + rs + r2)
                body.velocity = (scene.v_law, 0.0)
                shape = pymunk.Circle(body, r2)
                shape.friction = scene.q_pad
                shape.filter = flt
                space.add(body, shape)
                ry = body.position.y - pad.position.y
                tangential = pymunk.DampedSpring(pad, body, (-LT, ry), (0, 0), LT, o.micro_k, o.micro_c_spring)
                normal = pymunk.DampedSpring(pad, body, (0, ry + LN), (0, 0), LN + pre, o.micro_k_normal, 0.0)
                space.add(tangential, normal)
                scene.slider_springs += [tangential, normal]
                scene.law.build(scene, body, o.micro_c)
                self.micro_tracks.append(sub.build(space, yt, flt, np.random.default_rng(seeds[i * n + j]),
                                                   scene.mu_track, x_start))
                self.micro_pads.append(body)
        scene.sliders += self.micro_pads
        scene.slider_load += [N2] * len(self.micro_pads)
        scene.slider_c += [o.micro_c] * len(self.micro_pads)
        scene.slider_load[:p.N] = [o.pad_load] * p.N
        scene.tracks += self.micro_tracks
        self.micro_ahead = o.micro_ahead + scene.run_ahead  # the micro-tracks' margins (scene_inputs)
        self.micro_behind = o.micro_behind
        self._index(scene)

    @staticmethod
    def _index(scene):
        """A spatial hash (1 mm cells) instead of pymunk's bounding-box trees: with 120 micro-pads over ~5000 track
        segments a step costs 1.6-1.8 ms with the trees and 0.38-0.43 ms with the hash (measured, same trajectory).
        pymunk does not pickle the choice: it is made again on restoring."""
        scene.space.use_spatial_hash(1.0, 2000)

    def restore(self, scene):
        super().restore(scene)
        self._index(scene)

    def _pad_preload(self):
        """The pad's normal spring carries the block's share (the micro-pads' springs press on the pad)."""
        return self.sc.normal_load_per_pad - self.column_mass * G

    def maintain(self, scene):
        super().maintain(scene)
        for b, tr in zip(self.micro_pads, self.micro_tracks):
            tr.maintain(b.position.x, self.micro_ahead, self.micro_behind)

    # ------------------------------------------------------------------ drawing
    SIDE_PADS = 4

    def side_layout(self, scene):
        """Slots holding a pad's window and, to its right, one window per micro-pad over its own micro-track."""
        lay = super().side_layout(scene)
        ms = 8 * self.own.micro_radius
        win = lay.slot
        lay.slot = win + self.spec.n_micro * ms
        lay.pad_win, lay.pad_at = win, -0.5 * self.spec.n_micro * ms
        lay.__post_init__()
        return lay

    def side(self, scene, lay, q_pad):
        """The pads' side view, and each pad's micro-pads (true contact arcs) over pieces of their micro-tracks, hung
        from an arm on the pad by their normal springs."""
        from ..side_view import cap_outline, zigzag

        shapes = super().side(scene, lay, q_pad)
        p = self.spec
        n, bx = p.n_micro, scene.block.position.x
        r2 = self.own.micro_radius
        ms = 8 * r2
        hc = min(r2, 0.3 / lay.E)
        fills, lines, pucks, springs, arms = shapes["substrate"][1], shapes["surface"][1], [], [], []
        band, mus = shapes["friction"][1], list(shapes["friction"][2]["array"])
        for i in range(lay.n_show):
            pad_poly = shapes["pads"][1][i]
            arm_y = pad_poly[-1, 1] - 0.3 * lay.body
            x_right = pad_poly[:, 0].max()
            first = lay.x0[i] + lay.pad_at + lay.pad_win / 2
            arms.append(np.array([(x_right, arm_y), (first + (n - 0.5) * ms, arm_y)]))
            for j in range(n):
                body, tr = self.micro_pads[i * n + j], self.micro_tracks[i * n + j]
                datum = tr.y + tr.radius
                c = first + (j + 0.5) * ms
                xs = bx + np.linspace(-0.46 * ms, 0.46 * ms, 200)
                top, spans = scene.substrate.side(tr, xs[0], xs[-1], xs, q_pad)
                xd, yd = xs - bx + c, np.maximum(lay.y(top - datum), lay.floor)
                fills.append(np.column_stack([np.r_[xd[0], xd, xd[-1]], np.r_[lay.floor, yd, lay.floor]]))
                lines.append(np.column_stack([xd, yd]))
                for xa, xb, mu in spans if p.micro_alpha > 0 else ():  # the micro-patches' friction, as the pads'
                    m = (xs >= xa) & (xs <= xb)
                    if m.sum() >= 2:
                        band.append(np.vstack([np.column_stack([xd[m], yd[m]]),
                                               np.column_stack([xd[m], yd[m] - 0.08])[::-1]]))
                        mus.append(mu)
                px = body.position.x - bx + c
                arc = cap_outline(px, body.position.y - datum, r2, hc)
                arc[:, 1] = lay.y(arc[:, 1])
                y_top = arc[-1, 1] + 0.5 * lay.body
                pucks.append(np.vstack([arc, [(arc[-1, 0], y_top), (arc[0, 0], y_top)]]))
                springs.append(zigzag((px, y_top), (px, arm_y), coils=3, width=0.08 * ms))
        shapes["friction"][2]["array"] = np.array(mus)
        shapes["micro_arm"] = ("segments", arms, {"colors": "0.3", "linewidths": 1.2, "zorder": 3})
        shapes["micro_springs"] = ("segments", springs, {"colors": "tab:pink", "linewidths": 0.9, "zorder": 3,
                                                         "label": f"micro-pad normal spring {p.micro_k_normal:.4g} N/m"})
        shapes["micro_pads"] = ("polys", pucks, {"facecolors": "gold", "edgecolors": "k", "linewidths": 0.6,
                                                 "zorder": 4, "label": f"micro-pad (radius {p.micro_radius * 1e3:.3g} mm)"})
        return shapes

    def side_note(self, lay):
        return (f"pads 1-{lay.n_show} of {self.spec.N}, each over its own track, with its {self.spec.n_micro} micro-pads "
                "over theirs")

    def view(self, scene):
        """The whole block (every pad on its track, as "tracks" draws it) and a second panel enlarging column 1:
        its pad, micro-pads and micro-tracks, 40 a2 either side of the block."""
        v = super().view(scene)
        p = self.spec
        top, ms = scene.track_surface[0], self.own.micro_spacing
        zoom = {"window": 40 * p.micro_a, "ylim": (top - (p.n_micro + 0.6) * ms, v["block_top"] + 0.8),
                "track_width": 3, "zoomed": True, "ylabel": "y (mm): column 1",
                "title": f"column 1 of {p.N} (dashed box), enlarged: its pad and {p.n_micro} micro-pads on their "
                         "tracks"}
        return {**v, "zoom": zoom, "ylabel": f"y (mm): {p.N} columns, each a pad track and {p.n_micro} micro-tracks",
                "track_label": "pad track / micro-track (colour: patch friction)"}

    def draw(self, scene, lo, hi, view):
        shapes = super().draw(scene, lo, hi, view)
        big = view.get("zoomed", False)
        xy = np.array([(b.position.x, b.position.y) for b in self.micro_pads])
        pads = scene.pads
        n = self.spec.n_micro
        links = [((pads[k // n].position.x, pads[k // n].position.y), (q[0], q[1])) for k, q in enumerate(xy)]
        shapes["pads"][2].update(label="pad (macro contact)", s=60 if big else 14)
        shapes["micro_springs"] = ("segments", links, {"colors": "0.5", "linewidths": 0.8 if big else 0.3,
                                                       "label": "micro-pad spring"})
        shapes["micro_pads"] = ("points", xy, {"s": 30 if big else 4, "c": "tab:orange", "zorder": 3,
                                               "edgecolors": "k" if big else "none", "linewidths": 0.5,
                                               "label": "micro-pad (micro contact)"})
        return shapes
