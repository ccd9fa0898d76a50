"""The base of every pad arrangement: the ``[pads]`` section's spec (:class:`PadSpec`), the class an arrangement
subclasses (:class:`Arrangement`), the registry (:data:`ARRANGEMENTS`) and the pad springs' lengths ``LT`` and ``LN``.
:mod:`engine_sim.arrangements` re-exports them and imports the shipped arrangements, so an arrangement's module here
imports its base from this module."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pymunk

from frictionnoise.base import G

from ..parts import Part, Registry
from ..regime import (HANG_FRACTION, SOFTENING, SPRING_DAMPING_X, SPRING_OMEGA_DT, Limit, dt_limit, load_limit,
                      mass_limit)

__all__ = ["PadSpec", "Arrangement", "ARRANGEMENTS", "arrangement_kind", "track_rng", "LT", "LN"]

ARRANGEMENTS = Registry("pad arrangement", key="arrangement")

# Spring lengths (m). The normal spring is long so that a pad's tangential lag (f / k0, about 0.05 mm) tilts it
# negligibly: at 5 mm the tilt lengthened it enough to drop the load by 0.13 % and added a geometric tangential
# stiffness F_n / Ln of 1.5 % of k0; at 100 mm both are 20x smaller.
LT, LN = 5e-3, 0.1


@dataclass(frozen=True)
class PadSpec:
    """Spring-mounted pads (asperity contact regions).

    N: number of pads; mass (kg);
    radius (m); k0: tangential spring to the block (N/m); c0: its damping (N s/m); k_normal: normal spring (N/m),
    pre-compressed to carry M g cos(theta) / N on tracks; k1: lateral spring between neighbouring pads (N/m, free
    ends); c1: its damping (N s/m); track_spacing: offset of the tracks in y (m), which keeps each pad's broad
    phase to its own track; c_normal: damping of the normal spring (N s/m); foot_length: a foot's length (m) in a
    sole (the contact width is N foot_length); arrangement: "tracks" (each pad on its own track), "sole" (an
    elastic sole of feet on one shared track) or another registered name; unset: the substrate's own
    (``Substrate.arrangement``)."""

    N: int = 30
    mass: float = 1e-3
    radius: float = 0.3e-3
    k0: float = 3333.0
    c0: float = 0.0
    k_normal: float = 833.0
    k1: float = 0.0
    c1: float = 0.0
    track_spacing: float = 5e-3
    c_normal: float = 0.0
    foot_length: float = 1e-3
    arrangement: str = "tracks"


class SideMixin:
    """The side view of pads on tracks of their own (``engine_sim.side_view``): the first ``SIDE_PADS`` pads side
    by side, each in a slot over the piece of its own track under it, hung from the block by a normal spring
    (vertical) and a tangential spring (horizontal, from a post under the block), all in display millimetres."""

    SIDE_PADS: ClassVar[int] = 8

    def side_layout(self, scene):
        """The layout (:class:`engine_sim.side_view.SideLayout`): the exaggeration that shows the substrate's
        relief at about half a display millimetre, slots of 8 pad radii."""
        from ..side_view import SideLayout, nice_exaggeration

        p = self.spec
        R, relief = self.own.radius, self.own.relief
        E = min(nice_exaggeration(relief, 0.5), scene.wear.side_exaggeration)
        n_show = min(p.N, self.SIDE_PADS, scene.wear.side_pads)
        hc = min(R, 0.3 / E)  # true height of the pad's arc drawn (mm)
        # a slot reaches at most as far behind the pad as its track is kept (Scene.behind)
        slot = 2 * min(4 * R, 0.98 * scene.behind)
        return SideLayout(E=E, slot=slot, n_show=n_show, contact=E * (relief + hc),
                          body=0.15 * slot, spring=0.6 * slot, block=0.3 * slot, floor=-max(0.25 * slot, E * relief))

    def side_tracks(self, scene, lay, n_points: int = 400):
        """Per shown pad: (slot centre, the pad's track index, its datum height, x of the points in scene units)."""
        bx = scene.block.position.x
        xs = bx + np.linspace(-0.48 * lay.pad_win, 0.48 * lay.pad_win, n_points)  # a gap between neighbouring tracks
        return [(lay.x0[i] + lay.pad_at, i, scene.track_surface[i], xs) for i in range(lay.n_show)]

    def side(self, scene, lay, q_pad) -> dict:
        """Shapes of the side view (display mm): substrate pieces, their surface (coloured by friction where it
        varies), the pads (true contact arcs, schematic bodies), their springs and the block."""
        from ..side_view import body_outline, cap_outline, zigzag

        bx = scene.block.position.x
        R = self.own.radius
        hc = min(R, 0.3 / lay.E)
        lo, hi = scene.substrate.mu_range(self.sc.friction.mu0)
        coloured = hi > lo
        fills, lines, band, mus, pucks, normal, tangential, posts = [], [], [], [], [], [], [], []
        for x0, i, datum, xs in self.side_tracks(scene, lay):
            top, spans = scene.substrate.side(scene.tracks[i], xs[0], xs[-1], xs, q_pad)
            xd = xs - bx + x0
            yd = np.maximum(lay.y(top - datum), lay.floor)
            fills.append(np.column_stack([np.r_[xd[0], xd, xd[-1]], np.r_[lay.floor, yd, lay.floor]]))
            lines.append(np.column_stack([xd, yd]))
            for xa, xb, mu in spans if coloured else ():  # the friction as a band under the surface, span by span
                m = (xs >= max(xa, xs[0])) & (xs <= min(xb, xs[-1]))
                if m.sum() >= 2:
                    band.append(np.vstack([np.column_stack([xd[m], yd[m]]),
                                           np.column_stack([xd[m], yd[m] - 0.08])[::-1]]))
                    mus.append(mu)
            pad = scene.pads[i]
            px, py = pad.position.x - bx + x0, pad.position.y - datum
            arc = cap_outline(px, py, R, hc)
            arc[:, 1] = lay.y(arc[:, 1])
            y_top = arc[-1, 1] + lay.body
            pucks.append(body_outline(px, px, py, R, lay.E, y_top))  # its true shape, heights exaggerated
            normal.append(zigzag((px, y_top), (px, lay.block_bottom), coils=5, width=0.05 * lay.pad_win))
            post_x = x0 - 0.42 * lay.pad_win
            y_mid = arc[-1, 1] + 0.5 * lay.body
            posts.append(np.array([(post_x, lay.block_bottom), (post_x, y_mid)]))
            tangential.append(zigzag((post_x, y_mid), (px - R, y_mid), coils=4, width=0.025 * lay.pad_win))
        shapes = {
            "substrate": ("polys", fills, {"facecolors": "0.82", "edgecolors": "none", "zorder": 1,
                                           "label": "substrate (each pad's own track)"}),
            "surface": ("segments", lines, {"colors": "k", "linewidths": 0.8, "zorder": 2}),
            "friction": ("polys", band, {"array": np.array(mus), "edgecolors": "none", "zorder": 1.5}),
            "posts": ("segments", posts, {"colors": "0.3", "linewidths": 1.2, "zorder": 3}),
            "tangential": ("segments", tangential, {"colors": "tab:green", "linewidths": 1.0, "zorder": 3,
                                                    "label": f"tangential spring k0 = {self.spec.k0:.4g} N/m"}),
            "normal": ("segments", normal, {"colors": "tab:purple", "linewidths": 1.0, "zorder": 3,
                                            "label": f"normal spring k_normal = {self.spec.k_normal:.4g} N/m"}),
            "pads": ("polys", pucks, {"facecolors": "tab:orange", "edgecolors": "k", "linewidths": 0.8, "zorder": 4,
                                      "label": f"pad radius {self.spec.radius * 1e3:.3g} mm (true shape, heights "
                                               f"x{lay.E})"}),
        }
        shapes["block"] = ("rect", ((-lay.width / 2 + 0.05 * lay.slot, lay.block_bottom), lay.width - 0.1 * lay.slot,
                                    lay.block), {"facecolor": "tab:blue", "alpha": 0.45, "edgecolor": "tab:blue",
                                                 "zorder": 2, "label": f"block M = {self.sc.block.M:.4g} kg"})
        return shapes

    def side_note(self, lay) -> str:
        """What the side view shows of the arrangement, in a line."""
        n = self.spec.N
        if n == 1:
            return "one pad on its track"
        shown = f"pads 1-{lay.n_show} of {n}" if lay.n_show < n else f"all {n} pads"
        return f"{shown}, each over its own track"


class Arrangement(SideMixin, Part):
    """One pad arrangement (the base holds what tracks and sole share)."""

    name: ClassVar[str] = ""
    Spec: ClassVar[type] = PadSpec
    positive: ClassVar[frozenset] = frozenset({"N", "mass", "radius", "k0", "k_normal", "track_spacing", "foot_length"})
    non_negative: ClassVar[frozenset] = frozenset({"c0", "k1", "c1", "c_normal"})
    choices: ClassVar[dict] = {}
    guided: ClassVar[bool] = True  # the block runs in a horizontal groove (else it rests on its feet, free in y)
    hosts_wear: ClassVar[bool] = False  # pads on flat tracks of their own, where wear particles can sit
    also_fits: ClassVar[tuple] = ()  # keys of reduced_models.MODELS compared beside the fitting model, same trace

    scene_units: ClassVar[dict] = {"mass": "mass", "radius": "length", "k0": "stiffness", "c0": "damping",
                                   "k_normal": "stiffness", "k1": "stiffness", "c1": "damping",
                                   "track_spacing": "length", "c_normal": "damping", "foot_length": "length"}

    def scene_inputs(self) -> dict:
        """The spec's lengths, masses, stiffnesses and dampings, the springs' lengths LT and LN, the load on a pad
        column (``load``) and on the pad's normal spring (``preload``), the friction law's c (``c``) and the
        substrate's relief under a pad (``relief``, for the side view)."""
        sc = self.sc
        return {**super().scene_inputs(), "LT": (LT, "length"), "LN": (LN, "length"),
                "load": (sc.normal_load_per_pad, "force"), "preload": (self._pad_preload(), "force"),
                "c": (sc.friction.c, "damping"), "relief": (sc.substrate_part.relief(self.spec.radius), "length")}

    def _pad_preload(self) -> float:
        """The force of the pad's normal spring (N): the block's share of the load."""
        return self.sc.normal_load_per_pad - self.spec.mass * G

    # ------------------------------------------------------------------ scenario side (SI)
    @classmethod
    def validate(cls, p, sc) -> None:
        if p.N > 32 and p.track_spacing < 4 * p.radius:
            raise ValueError(f"pads.track_spacing = {p.track_spacing:.3g} m must exceed 4 pad radii when N > 32")
        if p.track_spacing < 2.5 * (p.radius + sc.substrate.segment_radius):
            raise ValueError(f"pads.track_spacing = {p.track_spacing:.3g} m must exceed 2.5 (pad + segment radius) "
                             f"= {2.5 * (p.radius + sc.substrate.segment_radius):.3g} m")

    def dt_limit(self) -> float:
        """Largest stable and accurate step (s): omega dt < 0.3 for the stiffest pad spring, and the spring
        damping c0 dt / m < 0.1."""
        p = self.spec
        k = p.k0 + p.k_normal + 4 * p.k1
        lim = SPRING_OMEGA_DT / math.sqrt(k / p.mass)
        c = p.c0 + p.c_normal + 2 * p.c1
        if c > 0:
            lim = min(lim, SPRING_DAMPING_X * p.mass / c)
        return lim

    @property
    def column_mass(self) -> float:
        """Mass of one pad column below the block (kg): its weight adds to the load on the substrate."""
        return self.spec.mass

    def column_force(self, v: float) -> float:
        """Steady friction of one pad column at sliding speed v (N): the law's force on the pad."""
        return self.sc.law_force(v)

    def column_slope(self, v: float) -> float:
        """dF/dv of one pad column (N s/m)."""
        sc = self.sc
        return sc.law_part.slope(v, sc.normal_load_per_pad, sc.friction.c)

    def pad_load(self) -> float:
        """Normal load on one pad's own contact (N)."""
        return self.sc.normal_load_per_pad

    def sliders(self, sc) -> list:
        """(load [N], mass [kg]) of each kind of sliding body (for the friction law's explicit-update limit)."""
        return [(sc.normal_load_per_pad, self.spec.mass)]

    def contact_width(self) -> float:
        """The block's contact width w (m; 0 for pads on separate tracks)."""
        return 0.0

    def width(self) -> float:
        """The contact width in scene units (mm)."""
        return 0.0

    def describe(self) -> dict:
        """Entries of the arrangement's own in ``metadata["scene"]``."""
        return {}

    # ------------------------------------------------------------------ regimes (SI; engine_sim.regime)
    preloaded: ClassVar[bool] = True  # normal springs pre-compressed to carry the load (else relaxed, as a sole's)

    def column_friction(self, load: float) -> float:
        """The largest steady friction of one pad column under the column load ``load`` (N): the friction law's
        force at the steady speed with the Coulomb part raised to the stickiest patch's mu (N)."""
        sc = self.sc
        mu0 = sc.friction.mu0
        mu_hi = sc.substrate_part.mu_range(mu0)[1]
        v = max(sc.steady_velocity, 0.0)
        return sc.law_part.force(v, load, sc.friction.c) + (mu_hi - mu0) * load

    def contact_load(self, load: float) -> float:
        """The normal load on a pad's own contact (N) under the column load ``load``."""
        return load

    def limits(self) -> list:
        """The pads' regime limits (:class:`engine_sim.regime.Limit`): the tangential spring's length LT against
        the pad's largest friction; for pre-compressed normal springs, their compression against their length LN
        and their softening F_s / LN against k0, and the load against the relief under the pad; the contact's
        thickness against a step's fall under the load; run.dt against the block's modes on its pads."""
        sc, p = self.sc, self.spec
        L, M = sc.normal_load_per_pad, sc.block.M
        col_w = self.column_mass * G
        lt, ln = LT, LN  # m
        out = []

        def by_mass(L_max, why, fix=""):
            return Limit("block.M", M, mass_limit(sc, L_max), "kg", why, fix=fix)

        # The pad lags x behind its normal spring's anchor, so the pre-compressed normal spring (force F_s, length
        # LN) tilts by x / LN and pushes the pad backwards with F_s x / LN: k0 x = f + F_s x / LN, and the lag is
        # x = f / (k0 - F_s / LN). The run starts with the drive already carrying the steady friction f0 per pad,
        # released at once on the block, which lurches on its pads' springs: the block's share of one pad, M / N on
        # k0, reaches at most f0 / sqrt(k0 M / N) (an undamped release), and the friction law's viscous part
        # c v_lurch adds to the stickiest patch's friction f. The lag x must stay below LT, where the pad passes its
        # tangential spring's anchor.
        spring_push = (lambda load: max(load - col_w, 0.0) / ln) if self.preloaded else (lambda load: 0.0)
        v_ss = max(sc.steady_velocity, 0.0)

        def lurch(load):
            m_share = max(load - col_w, 0.0) / (G * sc.drive_part.load_factor()) if sc.drive_part.load_factor() > 0 \
                else M / p.N
            f0 = sc.law_part.force(v_ss, load, sc.friction.c)
            return f0 / math.sqrt(p.k0 * m_share) if m_share > 0 else 0.0

        def friction(load):
            return self.column_friction(load) + sc.law_part.force(v_ss + lurch(load), load, sc.friction.c) \
                - sc.law_part.force(v_ss, load, sc.friction.c)

        def lag(load):
            k_eff = p.k0 - spring_push(load)
            return friction(load) / k_eff if k_eff > 0 else math.inf

        x = lag(L)
        L_lag = load_limit(lag, lt)
        k_need = friction(L) / lt + spring_push(L)
        out.append(by_mass(L_lag, f"a pad column's largest friction {friction(L):.4g} N (the stickiest patch at the "
                                  f"start's lurch, {lurch(L) * 1e3:.3g} mm/s), against its tangential spring k0 = "
                                  f"{p.k0:.4g} N/m less the tilted normal spring's push {spring_push(L):.4g} N/m, lags "
                                  f"the pad {x * 1e3:.3g} mm; beyond the spring's length {lt * 1e3:.3g} mm the pad "
                                  "passes its anchor", f"raise pads.k0 above {k_need:.4g} N/m"))
        if self.preloaded:
            F_s = L - col_w
            out.append(by_mass(ln * p.k_normal + col_w, f"the normal spring's pre-compression {F_s / p.k_normal * 1e3:.3g} "
                                                       f"mm (load / k_normal) must stay below its length {ln * 1e3:.3g} mm",
                               f"raise pads.k_normal above {F_s / ln:.4g} N/m"))
            out.append(by_mass(SOFTENING * p.k0 * ln + col_w,
                               f"the pre-compressed normal spring (force {F_s:.4g} N, length {ln * 1e3:.3g} mm) softens "
                               f"the pad's tangential stiffness by F_s / LN = {F_s / ln:.4g} N/m, more than "
                               f"{SOFTENING:g} k0", f"raise pads.k0 above {F_s / ln / SOFTENING:.4g} N/m"))
            depth = sc.substrate_part.pad_depth(HANG_FRACTION, p.radius)
            if depth > 0:
                N_pad = self.contact_load(L)
                out.append(Limit("pads.k_normal", p.k_normal, N_pad / depth, "N/m",
                                 f"a pad's load {N_pad:.4g} N / k_normal = {N_pad / p.k_normal * 1e6:.3g} um must "
                                 f"cover the depth it follows below the track's datum, {depth * 1e6:.3g} um on "
                                 f"{100 * (1 - HANG_FRACTION):g} % of its path, or it hangs over the valleys",
                                 fix="raise block.M"))
        if sc.substrate_part.pad_depth(HANG_FRACTION, p.radius) > 0:
            dt = sc.run.dt / _substeps(sc)
            rs = sc.substrate.segment_radius
            N_pad = self.contact_load(L)
            out.append(by_mass(load_limit(self.contact_load, rs * p.mass / dt**2),
                               f"a pad falls (N_pad / m) dt^2 = {N_pad / p.mass * dt * dt * 1e6:.3g} um in one step "
                               f"under its load; beyond the segment radius {rs * 1e6:.3g} um a pad leaving a rough "
                               "track for a step lands past the segment's centre line",
                               f"lower run.dt below {math.sqrt(rs * p.mass / N_pad):.3g} s"))
        out.append(dt_limit("run.dt", sc, math.sqrt(p.N * p.k0 / M), p.N * p.c0 / M,
                            f"the block on its {p.N} tangential pad springs"))
        return out

    # ------------------------------------------------------------------ scene side (scene units)
    def build(self, scene) -> None:
        raise NotImplementedError

    def _mount(self, scene, pad, xp, yp, pre):
        """The pad's tangential spring (k0, c0) and its normal spring (k_normal, pre-compressed by ``pre`` mm) to
        the block, anchored at the pad's height LT behind and LN above it."""
        o = self.own
        LT, LN = o.LT, o.LN
        ry = yp - scene.y_block
        tangential = pymunk.DampedSpring(scene.block, pad, (xp - LT, ry), (0, 0), LT, o.k0, o.c0)
        normal = pymunk.DampedSpring(scene.block, pad, (xp, ry + LN), (0, 0), LN + pre, o.k_normal, o.c_normal)
        scene.space.add(tangential, normal)
        scene.block_springs += [tangential, normal]
        return tangential

    def _add_pad(self, scene, pad, yp, xp, flt, R):
        scene.pads.append(pad)
        scene.sliders.append(pad)
        scene.slider_load.append(self.own.load)
        scene.slider_c.append(self.own.c)
        scene.pad_y.append(yp)
        scene.pad_x.append(xp)
        scene.track_filter.append(flt)
        scene.track_surface.append(yp - R)

    def maintain(self, scene) -> None:
        """Generate substrate ahead of each pad and drop it behind."""
        for pad, tr in zip(scene.pads, scene.tracks):
            tr.maintain(pad.position.x, scene.ahead, scene.behind)

    def restore(self, scene) -> None:
        """After unpickling: segment neighbours re-applied (pymunk does not save them)."""
        for tr in scene.tracks:
            tr.restore_neighbors()

    # ------------------------------------------------------------------ drawing (scene units)
    def view(self, scene) -> dict:
        """The renderer's window: half width (m) around the block, y limits (mm), y label, track line width, the
        block's top (mm) and half width (mm)."""
        ys = np.array(scene.pad_y)
        return {"window": 12 * self.sc.substrate.a, "ylim": (ys.min() - 3.0, scene.y_block + 4.0),
                "ylabel": "y (mm): one track per pad", "track_width": 3, "block_top": ys.max() + 1.0,
                "block_half": 2.5}

    def draw_tracks(self, scene, lo, hi, q_pad):
        """Polylines and their friction coefficients within [lo, hi] (asked of the substrate part)."""
        segs, mus = [], []
        for tr in scene.tracks:
            s, m = scene.substrate.draw(tr, lo, hi, q_pad)
            segs += s
            mus += m
        return segs, mus

    def draw(self, scene, lo, hi, view) -> dict:
        """Pads as points and their tangential springs to the block (render.py's shapes)."""
        pads = np.array([(p.position.x, p.position.y) for p in scene.pads])
        anchors = [scene.block.local_to_world(c.anchor_a) for c in scene.block_springs[::2]]
        return {"springs": ("segments", [((a.x, a.y), (q[0], q[1])) for a, q in zip(anchors, pads)],
                            {"colors": "0.4", "linewidths": 0.6, "label": "pad spring"}),
                "pads": ("points", pads, {"s": 18, "c": "tab:red", "zorder": 3, "label": "pad"})}


def _substeps(sc) -> int:
    from ..wear import grain_step
    return grain_step(sc)["substeps"]


def arrangement_kind(name: str):
    """The Arrangement class registered as ``name`` (KeyError if none)."""
    return ARRANGEMENTS[name]


def track_rng(scene, i: int):
    """The generator of track i (one stream per pad track; the scene's wear particles take stream N)."""
    return np.random.default_rng(scene.seeds[i])
