"""An imposed vibration: the substrate or the block shaken harmonically, along the sliding direction or normal to it
(the ``[vibration]`` section of a scenario).

``target = "substrate"``: the tracks move as ``s(t) = A sin(omega t)`` along ``direction`` together with the rig
that holds the block (its guide rides with them: a guided block keeps its height above the tracks); the drive's
anchor stays in the laboratory. The scene is solved in the substrate's frame, where the tracks stay the static
segments they are: every body then feels the uniform inertial acceleration ``-s''(t)``, applied as a modulation of
the space's gravity (one call per step, no shape moved), and the drive's anchor moves by ``-s(t)``: the velocity
drive's anchor rides that field itself, a dynamic body of mass ``ANCHOR_MASS`` held on its line by a groove joint
to the static body (the field's normal part would pull it down), so the step sets nothing on it. The drive
spring's pull moves it by at most ``F T^2 / (2 ANCHOR_MASS)``: 1e-13 m for 2 N over 100 s. Its kinetic energy
and its share of the inertial force stay out of the energy balance (the recorder's body table holds the block,
the sliding bodies, the grains and the drive's own bodies, not the drive's anchor); its velocity at a sample, like
every body's, is the one that moves it over the next step, the anchor speed the drive's work is read from.
The gravity of step n is ``A omega_d^2 sin(omega t_n)`` with ``omega_d = 2 sin(omega dt / 2) / dt``, the second
difference of ``s`` over the step: a body left to it follows ``-s(t_{n-1}) - s(dt)`` exactly (pymunk moves a body
with the velocity of its previous step, then updates the velocity: the motion runs one step, a phase omega dt,
behind the field, and the drive's riding anchor with it), so the laboratory's motion in the substrate's frame
carries no discretisation drift.

``target = "block"``: a shaker on the block: the harmonic force ``M A omega_d^2 sin(omega t)`` along
``direction``, the force that would move the free block by ``A`` (normal: only for a block free vertically,
which the arrangement does not guide).

Positions, velocities and every recorded force are relative to the substrate (the friction law acts on the
relative velocity). The recorder adds two channels: the displacement ``s(t)`` of the shaken part at each sample
(laboratory position = recorded position + s for the substrate target) and the vibration's power, the inertial
force's ``m a . v`` summed over every body (substrate target) or the shaker's force times the block's velocity,
whose integral (``work_vibration``) enters the energy balance beside the drive's work.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pymunk

from frictionnoise.base import G

from .parts import Part
from .sample_layout import VIB_COLS  # the recorder's columns this part writes (Vibration.record)

__all__ = ["VibrationSpec", "Vibration", "MIN_STEPS_PER_PERIOD", "VIB_COLS", "ANCHOR_MASS"]

MIN_STEPS_PER_PERIOD = 20  # pymunk steps per vibration period the loader demands
# g (scene units; 1e17 kg): the velocity drive's anchor under a shaken substrate, a dynamic body that follows the
# inertial field; a drive force F over a run of T shifts it by F T^2 / (2 ANCHOR_MASS) (2 N, 100 s: 1e-13 m, 1e-6 of
# the smallest amplitude swept); pymunk applies gravity whatever the mass, so the mass sets only that feedback
ANCHOR_MASS = 1e20
_FAR = 1e9  # mm: the anchor's groove reaches this far either way


@dataclass(frozen=True)
class VibrationSpec:
    """target: "substrate" or "block"; direction: "parallel" (along sliding, x) or "normal" (y); amplitude: A (m),
    >= 0 (0: no vibration, the scene is its unshaken twin bit for bit); frequency: f (Hz), > 0, with at least
    20 pymunk steps per period."""

    target: str = "substrate"
    direction: str = "parallel"
    amplitude: float = 0.0
    frequency: float = 50.0


class Vibration(Part):
    """The vibration part: validation, build, stepping (it wraps the friction law's stepping), recording and
    drawing. Inactive (no object built, no cost) when the amplitude is 0."""

    Spec: ClassVar[type] = VibrationSpec
    positive: ClassVar[frozenset] = frozenset({"frequency"})
    non_negative: ClassVar[frozenset] = frozenset({"amplitude"})
    choices: ClassVar[dict] = {"target": ("substrate", "block"), "direction": ("parallel", "normal")}

    scene_units: ClassVar[dict] = {"amplitude": "length"}

    def __init__(self, spec, scenario):
        super().__init__(spec, scenario)
        self.active = spec.amplitude > 0

    def scene_inputs(self) -> dict:
        """The amplitude and the angular frequency ``omega`` = 2 pi frequency."""
        return {**super().scene_inputs(), "omega": (2 * math.pi * self.spec.frequency, "rate")}

    # ------------------------------------------------------------------ scenario side (SI)
    @classmethod
    def validate(cls, spec, sc) -> None:
        """Raise ValueError (naming the field) for a vibration the scene cannot carry."""
        steps = 1.0 / (spec.frequency * sc.run.dt)
        if steps < MIN_STEPS_PER_PERIOD:
            raise ValueError(f"vibration.frequency = {spec.frequency:.6g} Hz leaves {steps:.3g} steps of run.dt = "
                             f"{sc.run.dt:.3g} s per period; at least {MIN_STEPS_PER_PERIOD} are needed (frequency "
                             f"<= {1.0 / (MIN_STEPS_PER_PERIOD * sc.run.dt):.6g} Hz)")
        if spec.amplitude > 0 and sc.drive_part.extra_mass > 0:
            raise ValueError("vibration.target: a drive that moves a mass of its own (the hanging mass of Leonardo's "
                             "slider) is not supported under vibration")
        if spec.amplitude > 0 and spec.target == "block" and type(sc.law_part).advance is not _plain_advance():
            raise ValueError(f"vibration.target = 'block' needs a friction law that writes no body forces (the "
                             f"{sc.friction.law!r} law writes every body's force each step, over the shaker's)")
        if spec.amplitude > 0 and spec.target == "block" and spec.direction == "normal" and sc.arrangement_part.guided:
            raise ValueError("vibration.direction = 'normal' with target 'block' needs a block free vertically; the "
                             f"arrangement {sc.pads.arrangement!r} guides it (its guide would take the force)")

    def limits(self) -> list:
        """A normal vibration's regime limits (:class:`engine_sim.regime.Limit`), none for a parallel one:

        - its peak relative normal speed A omega, over one step, against the track's segment radius: pymunk has no
          continuous collision detection, and a pad that approaches a segment faster than about 1.2-1.5 segment radii
          per step passes through it; the limit keeps A omega dt below one radius;
        - its amplitude against the pads' normal spring travel: the shaken part may move by A relative to the part
          that does not follow it, opening or closing each normal spring by up to A; beyond its length less its
          pre-compression, LN - F_s / k_normal, the spring passes through its own anchor."""
        from .arrangements import LN
        from .regime import Limit

        s, sc = self.spec, self.sc
        if not self.active or s.direction != "normal":
            return []
        w = 2 * math.pi * s.frequency
        rs = sc.substrate.segment_radius
        dt = sc.run.dt
        ln = LN
        p = sc.pads
        F_s = max(sc.normal_load_per_pad - p.mass * G, 0.0) if sc.arrangement_part.preloaded else 0.0
        travel = ln - F_s / p.k_normal
        return [
            Limit("vibration.amplitude", s.amplitude, rs / (w * dt), "m",
                  f"its peak normal speed A omega = {s.amplitude * w:.4g} m/s moves a pad {s.amplitude * w * dt * 1e6:.3g} "
                  f"um per step of run.dt = {dt:.3g} s, beyond the track's segment radius {rs * 1e6:.3g} um, where "
                  "pymunk lets a pad pass through the segment",
                  fix=f"lower run.dt below {rs / (s.amplitude * w):.3g} s"),
            Limit("vibration.amplitude", s.amplitude, travel, "m",
                  f"a normal excursion of A beyond the pads' normal spring travel {travel * 1e3:.4g} mm (its length "
                  f"{ln * 1e3:.3g} mm less its pre-compression) drives a pad through its spring's anchor"),
        ]

    def describe(self) -> dict:
        """``metadata["scene"]["vibration"]``: the spec (SI) and the velocity amplitude A omega (m/s)."""
        s = self.spec
        return {"target": s.target, "direction": s.direction, "amplitude": s.amplitude, "frequency": s.frequency,
                "velocity_amplitude": s.amplitude * 2 * math.pi * s.frequency}

    # ------------------------------------------------------------------ scene side (scene units)
    def build(self, scene) -> None:
        """Scene-unit constants; for the substrate target, the velocity drive's moving anchor made a body that rides
        the inertial field (:func:`_ride_the_field`) and every body's velocity, the anchor's too, shifted by the
        substrate's at t = 0 (so the laboratory's motion starts as -s(t))."""
        if not self.active:
            return
        s = self.spec
        dt = scene.dt
        self.dt = dt
        self.A = self.own.amplitude  # mm
        self.w = self.own.omega  # rad/ms
        self.wd2 = (2 * math.sin(self.w * dt / 2) / dt) ** 2  # discrete omega^2 (1/ms^2)
        self.axis = 0 if s.direction == "parallel" else 1
        self.g0 = tuple(scene.space.gravity)
        self.pseudo = s.target == "substrate"
        self.block = scene.block
        self.M = scene.block.mass
        self.anchor, self.v_anchor, self.groove = None, 0.0, None
        self.plain = type(scene.law).advance is _plain_advance()
        if self.pseudo:
            anchor = scene.drive.spring.b if scene.drive.spring is not None else None
            if self.axis == 0 and anchor is not None and anchor.body_type == pymunk.Body.KINEMATIC \
                    and anchor.velocity.x != 0.0:  # a moving anchor (velocity drive): it stays in the laboratory
                self.anchor, self.v_anchor = anchor, anchor.velocity.x
                self.groove = _ride_the_field(scene.space, anchor)
            u0 = self._s(1) / dt  # mean substrate velocity over the first step
            for b in scene.space.bodies:  # the riding anchor among them
                if b.body_type == pymunk.Body.DYNAMIC:
                    v = list(b.velocity)
                    v[self.axis] -= u0
                    b.velocity = tuple(v)

    def _s(self, n) -> float:
        """Displacement of the shaken part after n steps (mm)."""
        return self.A * math.sin(self.w * n * self.dt)

    def impulses(self, n0: int, n1: int) -> tuple[float, float, float, float, float, float]:
        """The vibration's impulses over steps n0 .. n1 - 1 (scene units; step n feels the acceleration
        A omega_d^2 sin(omega t_n), see :meth:`advance`): (x, y) per unit mass on every body (substrate target),
        (x, y) on the block alone (block target), then (x, y) per unit mass on every body over step n1 - 1 alone
        (substrate target; for the step's mean velocity, :func:`engine_sim.reduction.step_mean_velocity`). One call
        a sample: the recorder's cost per shaken sample is the part's budget."""
        if not self.active or n1 <= 0:
            return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        th = self.w * self.dt
        a_dt = self.A * self.wd2 * self.dt
        last = a_dt * math.sin(th * (n1 - 1)) if self.pseudo else 0.0
        if n1 <= n0:
            j = 0.0
        else:  # sum_{n=n0}^{n1-1} sin(th n) in closed form (a per-sample numpy sum cost 5-10 us, 0.5-1 us per step)
            half = 0.5 * th
            j = a_dt * math.sin(half * (n1 - n0)) * math.sin(half * (n0 + n1 - 1)) / math.sin(half)
        if self.pseudo:
            return (j, 0.0, 0.0, 0.0, last, 0.0) if self.axis == 0 else (0.0, j, 0.0, 0.0, 0.0, last)
        j *= self.M
        return (0.0, 0.0, j, 0.0, 0.0, 0.0) if self.axis == 0 else (0.0, 0.0, 0.0, j, 0.0, 0.0)

    def displacement(self, steps: int) -> float:
        """s(t) at the scene's step count (mm)."""
        return self._s(steps) if self.active else 0.0

    def advance(self, scene, n: int) -> None:
        """n steps, each after setting the step's inertial acceleration (substrate target) or shaker force (block
        target); the law steps the space (in one loop when it needs no Python inside a step, else one step at a
        time). sin(omega t_n) by the two-term recurrence, re-anchored on math.sin at every call (its rounding over
        one call of tens of steps is ~1e-15). One pymunk setter per step (the velocity drive's anchor rides the
        field, :func:`_ride_the_field`), each loop specialised so a step does no other attribute lookup or branch:
        the setter is the part's cost (bench_vibration.py). pymunk's gravity setter wakes every sleeping body: in
        the substrate's frame a resting grain feels the inertial force, so no grain sleeps while the substrate is
        shaken."""
        if not self.active:
            scene.law.advance(scene, n)
            return
        k0 = scene.steps
        th = self.w * self.dt
        c2 = 2.0 * math.cos(th)
        s_prev, s_cur = math.sin(th * (k0 - 1)), math.sin(th * k0)
        K = self.A * self.wd2  # acceleration amplitude (mm/ms^2)
        space, dt, law = scene.space, self.dt, scene.law
        if self.plain:  # the law needs no Python inside a step: step the space here
            step, arg = space.step, dt
        else:
            step, arg = (lambda _: law.advance(scene, 1)), None
        if not self.pseudo:
            block, KM = self.block, K * self.M
            for _ in range(n):
                block.force = (KM * s_cur, 0.0) if self.axis == 0 else (0.0, KM * s_cur)
                step(arg)
                s_prev, s_cur = s_cur, c2 * s_cur - s_prev
            return
        gx, gy = self.g0
        if self.axis == 0:
            for _ in range(n):
                space.gravity = (gx + K * s_cur, gy)
                step(arg)
                s_prev, s_cur = s_cur, c2 * s_cur - s_prev
        else:
            for _ in range(n):
                space.gravity = (gx, gy + K * s_cur)
                step(arg)
                s_prev, s_cur = s_cur, c2 * s_cur - s_prev
        space.gravity = self.g0  # samples and pickles see the plain gravity (the recorder's potential energy)

    def record(self, scene, px: float, py: float) -> tuple[float, float]:
        """(displacement s [mm], power [N mm/ms]) at the present sample; ``px``, ``py``: the momentum of the bodies
        the recorder keeps the energy of (the block, the sliding bodies, the grains, the drive's own bodies; not the
        drive's anchor), which the substrate's inertial force works on.

        The acceleration paired with the sampled velocities is the mean of the field of the step just taken and of
        the step to come, a sin(omega (t_n - dt/2)) cos(omega dt/2): a body that only follows the field (velocity
        ~ cos(omega (t_n - dt/2))) then takes no mean power. Paired with the field of the step to come alone it
        took a mean of about m A^2 omega^4 dt / 4: at 1 kHz, dt 2.5e-5 s and A = 2.7 um, with the 0.13 kg of block
        and pads that ride with the substrate, 0.8 of the drive's power."""
        if not self.active:
            return 0.0, 0.0
        th = self.w * self.dt
        n = scene.steps
        sn = math.sin(th * n)
        a = self.A * self.wd2 * 0.5 * (sn + math.sin(th * (n - 1)))
        if self.pseudo:
            return self.A * sn, a * (px if self.axis == 0 else py)
        v = self.block.velocity
        return self.A * sn, self.M * a * (v.x if self.axis == 0 else v.y)

    # ------------------------------------------------------------------ drawing (scene units)
    def draw(self, scene, lo: float, hi: float) -> dict:
        """A dial at the window's lower left whose hand turns with the vibration's phase, and a caption."""
        if not self.active:
            return {}
        s = self.spec
        ph = self.w * scene.steps * self.dt
        y0, y1 = scene.arrangement.view(scene)["ylim"]
        r = 0.06 * (hi - lo)
        cx, cy = lo + 1.3 * r, y0 + 1.3 * r * (y1 - y0) / (hi - lo) * 1.0
        ry = r * (y1 - y0) / (hi - lo)
        th = np.linspace(0, 2 * np.pi, 41)
        what = "substrate" if self.pseudo else "block"
        return {
            "vib_dial": ("line", (cx + r * np.cos(th), cy + ry * np.sin(th)), {"color": "tab:purple", "lw": 1.0}),
            "vib_hand": ("segments", [((cx, cy), (cx + r * math.sin(ph), cy + ry * math.cos(ph)))],
                         {"colors": "tab:purple", "linewidths": 2.0, "label": f"{what} vibration phase"}),
            "vib_caption": ("caption", f"{what} {s.direction} {_length(s.amplitude)} at {s.frequency:.4g} Hz: "
                                       f"s = {_length(s.amplitude * math.sin(ph), s.amplitude, '+')}", {}),
        }


def _length(x: float, scale: float | None = None, sign: str = "") -> str:
    """``x`` (m) in the unit of ``scale`` (m; default ``x``): um below 1 mm, mm below 1 m, else m."""
    a = abs(x if scale is None else scale)
    if a < 1e-3:
        return f"{x * 1e6:{sign}.4g} um"
    return f"{x * 1e3:{sign}.4g} mm" if a < 1.0 else f"{x:{sign}.4g} m"


def _ride_the_field(space, anchor):
    """Make the kinematic ``anchor`` a dynamic body of mass ``ANCHOR_MASS`` that follows the space's gravity (the
    inertial field of the shaken substrate) by itself, with its velocity kept, on a groove joint along x to the
    static body that carries the field's normal part; the joint, returned."""
    anchor.body_type = pymunk.Body.DYNAMIC
    anchor.mass, anchor.moment = ANCHOR_MASS, float("inf")
    y = anchor.position.y
    groove = pymunk.GrooveJoint(space.static_body, anchor, (-_FAR, y), (_FAR, y), (0, 0))
    space.add(groove)
    return groove


def _plain_advance():
    from .laws import Law
    return Law.advance
