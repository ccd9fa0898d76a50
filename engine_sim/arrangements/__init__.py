"""Pad arrangements, one class each: how the block meets the substrate. Its spec (the ``[pads]`` section, SI),
validation (the spring time-step limit among it), the friction of one pad column at speed v (for the drive force
and the steady speed), build (pads, their springs, the friction law's part on every sliding body, the tracks),
maintenance of the tracks, what it records (the sliding bodies, their loads, the springs that store energy), its
share of ``describe()`` and its drawing.

The scene reads back, after :meth:`Arrangement.build`: ``pads`` (the N bodies whose contact forces are the trace's
``pad_force``), ``sliders`` (every body under the friction law, pads first), ``slider_load`` and ``slider_c``
(each one's normal load [N] and viscous slope [N s/m]), ``block_springs`` (block to slider) and ``slider_springs``
(slider to slider), ``tracks``, ``track_surface`` and ``track_filter`` (per pad, for the wear particles).

A new arrangement is one module here with an :class:`Arrangement` subclass decorated with
``@ARRANGEMENTS.register`` and one import line below.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pymunk

from frictionnoise.base import G

from .. import units as U
from ..parts import Registry

__all__ = ["PadSpec", "Arrangement", "ARRANGEMENTS", "arrangement_kind", "SPRING_OMEGA_DT", "SPRING_DAMPING_X"]

ARRANGEMENTS = Registry("pad arrangement", key="arrangement")

# Explicit spring forces are accurate for omega dt < 0.3 (DESIGN.md, measured on pymunk 7.3).
SPRING_OMEGA_DT = 0.3
# Spring damping is exact-exponential but its effect is slowed by x/(e^x - 1), x = c dt / m: keep x < 0.1.
SPRING_DAMPING_X = 0.1

# Spring lengths (mm). The normal spring is long so that a pad's tangential lag (f / k0, about 0.05 mm) tilts it
# negligibly: at 5 mm the tilt lengthened it enough to drop the load by 0.13 % and added a geometric tangential
# stiffness F_n / Ln of 1.5 % of k0; at 100 mm both are 20x smaller.
LT, LN = 5.0, 100.0


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


class Arrangement:
    """One pad arrangement (the base holds what tracks and sole share)."""

    name: ClassVar[str] = ""
    Spec: ClassVar[type] = PadSpec
    positive: ClassVar[frozenset] = frozenset({"N", "mass", "radius", "k0", "k_normal", "track_spacing", "foot_length"})
    non_negative: ClassVar[frozenset] = frozenset({"c0", "k1", "c1", "c_normal"})
    choices: ClassVar[dict] = {}
    guided: ClassVar[bool] = True  # the block runs in a horizontal groove (else it rests on its feet, free in y)
    hosts_wear: ClassVar[bool] = False  # pads on flat tracks of their own, where wear particles can sit
    also_fits: ClassVar[tuple] = ()  # keys of reduced_models.MODELS compared beside the fitting model, same trace

    def __init__(self, spec, scenario):
        self.spec, self.sc = spec, scenario

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
        """The contact width in scene units (mm), converted once."""
        return 0.0

    def describe(self) -> dict:
        """Entries of the arrangement's own in ``metadata["scene"]``."""
        return {}

    # ------------------------------------------------------------------ scene side (scene units)
    def build(self, scene) -> None:
        raise NotImplementedError

    def _mount(self, scene, pad, xp, yp, pre):
        """The pad's tangential spring (k0, c0) and its normal spring (k_normal, pre-compressed by ``pre`` mm) to
        the block, anchored at the pad's height LT behind and LN above it."""
        p = self.spec
        ry = yp - scene.y_block
        tangential = pymunk.DampedSpring(scene.block, pad, (xp - LT, ry), (0, 0), LT, p.k0 * U.STIFFNESS, p.c0 * U.DAMPING)
        normal = pymunk.DampedSpring(scene.block, pad, (xp, ry + LN), (0, 0), LN + pre, p.k_normal * U.STIFFNESS,
                                     p.c_normal * U.DAMPING)
        scene.space.add(tangential, normal)
        scene.block_springs += [tangential, normal]
        return tangential

    def _add_pad(self, scene, pad, yp, xp, flt, R):
        scene.pads.append(pad)
        scene.sliders.append(pad)
        scene.slider_load.append(scene.sc.normal_load_per_pad)
        scene.slider_c.append(scene.sc.friction.c)
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


def arrangement_kind(name: str):
    """The Arrangement class registered as ``name`` (KeyError if none)."""
    return ARRANGEMENTS[name]


def track_rng(scene, i: int):
    """The generator of track i (one stream per pad track; the scene's wear particles take stream N)."""
    return np.random.default_rng(scene.seeds[i])


from . import tracks, sole, micro  # noqa: E402,F401
