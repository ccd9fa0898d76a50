"""Pads each on its own track (model I's N independent contacts): tracks offset in y, one ShapeFilter category
per pad, so the pads' forces are independent as the contacts of a real 2D interface are."""
from __future__ import annotations

import pymunk


from .arrangement import ARRANGEMENTS, Arrangement, PadSpec, track_rng


@ARRANGEMENTS.register
class Tracks(Arrangement):
    name = "tracks"
    Spec = PadSpec
    hosts_wear = True

    def build(self, scene):
        p, o = self.spec, self.own
        space = scene.space
        m_p, R = o.mass, o.radius
        rs = self.ctx.segment_radius
        dy = o.track_spacing
        kn = o.k_normal
        load = o.preload  # carried by the normal spring (N)
        # pre-compression (mm); the pads rest one collision slop into their tracks, which the rest length absorbs
        pre = load / kn + scene.slop
        x_start = scene.substrate.x_start(scene)
        for i in range(p.N):
            pad = pymunk.Body(m_p, float("inf"))
            xp, yt = 0.0, -i * dy
            yp = yt + rs + R
            flt = pymunk.ShapeFilter(categories=1 << (i % 32), mask=1 << (i % 32))
            shape = pymunk.Circle(pad, R)
            pad.position = (xp, yp)
            pad.velocity = (scene.v_law, 0.0)
            shape.friction = scene.q_pad  # arbiter friction = pad x substrate: the substrate carries mu (/ q_pad)
            shape.filter = flt
            space.add(pad, shape)
            self._mount(scene, pad, xp, yp, pre)
            scene.law.build(scene, pad, o.c)
            scene.tracks.append(scene.substrate.build(space, yt, flt, track_rng(scene, i), scene.mu_track, x_start))
            self._add_pad(scene, pad, yp, xp, flt, R)
        self._couple(scene)

    def _couple(self, scene):
        """Lateral springs k1 between neighbours, anchored on pad i+1 at pad i's height so they act along x."""
        p, o = self.spec, self.own
        if p.k1 > 0 or p.c1 > 0:
            for i in range(p.N - 1):
                a, b = scene.pads[i], scene.pads[i + 1]
                off = scene.pad_y[i] - scene.pad_y[i + 1]
                c = pymunk.DampedSpring(a, b, (0, 0), (-o.LT, off), o.LT, o.k1, o.c1)
                scene.space.add(c)
                scene.slider_springs.append(c)

