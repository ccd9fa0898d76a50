"""An imposed vibration: the substrate or the block shaken harmonically, along the sliding direction or normal to it
(the ``[vibration]`` section of a scenario).

``target = "substrate"``: the tracks move as ``s(t) = A sin(omega t)`` along ``direction`` together with the rig
that holds the block (its guide rides with them: a guided block keeps its height above the tracks); the drive's
anchor stays in the laboratory. The scene is solved in the substrate's frame, where the tracks stay the static
segments they are: every body then feels the uniform inertial acceleration ``-s''(t)``, applied as a modulation of
the space's gravity (one call per step, no constraint, no shape moved), and the drive's anchor moves by ``-s(t)``
(the velocity drive's kinematic anchor gets the step's mean velocity, so its position is exact at every step).
The gravity of step n is ``A omega_d^2 sin(omega t_n)`` with ``omega_d = 2 sin(omega dt / 2) / dt``, the second
difference of ``s`` over the step: a body left to it follows ``-s(t_n)`` exactly at every step (pymunk's
semi-implicit Euler), so the laboratory's motion in the substrate's frame carries no discretisation drift.

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

import numba
import numpy as np
import pymunk

from . import units as U

__all__ = ["VibrationSpec", "Vibration", "MIN_STEPS_PER_PERIOD", "VIB_COLS"]

MIN_STEPS_PER_PERIOD = 20  # pymunk steps per vibration period the loader demands
VIB_COLS = ("vib_disp", "vib_power")  # the recorder's columns after reduction.COLS, written by Vibration.record


@dataclass(frozen=True)
class VibrationSpec:
    """target: "substrate" or "block"; direction: "parallel" (along sliding, x) or "normal" (y); amplitude: A (m),
    >= 0 (0: no vibration, the scene is its unshaken twin bit for bit); frequency: f (Hz), > 0, with at least
    20 pymunk steps per period."""

    target: str = "substrate"
    direction: str = "parallel"
    amplitude: float = 0.0
    frequency: float = 50.0


class Vibration:
    """The vibration part: validation, build, stepping (it wraps the friction law's stepping), recording and
    drawing. Inactive (no object built, no cost) when the amplitude is 0."""

    Spec: ClassVar[type] = VibrationSpec
    positive: ClassVar[frozenset] = frozenset({"frequency"})
    non_negative: ClassVar[frozenset] = frozenset({"amplitude"})
    choices: ClassVar[dict] = {"target": ("substrate", "block"), "direction": ("parallel", "normal")}

    def __init__(self, spec, scenario):
        self.spec, self.sc = spec, scenario
        self.active = spec.amplitude > 0

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

    def describe(self) -> dict:
        """``metadata["scene"]["vibration"]``: the spec (SI) and the velocity amplitude A omega (m/s)."""
        s = self.spec
        return {"target": s.target, "direction": s.direction, "amplitude": s.amplitude, "frequency": s.frequency,
                "velocity_amplitude": s.amplitude * 2 * math.pi * s.frequency}

    # ------------------------------------------------------------------ scene side (scene units)
    def build(self, scene) -> None:
        """Scene-unit constants; for the substrate target, every body's velocity shifted by the substrate's at
        t = 0 (so the laboratory's motion starts as -s(t)) and the velocity drive's anchor set moving."""
        if not self.active:
            return
        s = self.spec
        dt = scene.dt
        self.dt = dt
        self.A = s.amplitude * U.LENGTH  # mm
        self.w = 2 * math.pi * s.frequency / U.TIME  # rad/ms
        self.wd2 = (2 * math.sin(self.w * dt / 2) / dt) ** 2  # discrete omega^2 (1/ms^2)
        self.axis = 0 if s.direction == "parallel" else 1
        self.g0 = tuple(scene.space.gravity)
        self.pseudo = s.target == "substrate"
        self.block = scene.block
        self.M = scene.block.mass
        self.anchor, self.v_anchor = None, 0.0
        self.plain = type(scene.law).advance is _plain_advance()
        if self.pseudo:
            u0 = self._s(1) / dt  # mean substrate velocity over the first step
            for b in scene.space.bodies:
                if b.body_type == pymunk.Body.DYNAMIC:
                    v = list(b.velocity)
                    v[self.axis] -= u0
                    b.velocity = tuple(v)
            anchor = scene.drive.spring.b if scene.drive.spring is not None else None
            if self.axis == 0 and anchor is not None and anchor.body_type == pymunk.Body.KINEMATIC \
                    and anchor.velocity.x != 0.0:  # a moving anchor (velocity drive): it stays in the laboratory
                self.anchor, self.v_anchor = anchor, anchor.velocity.x

    def _s(self, n) -> float:
        """Displacement of the shaken part after n steps (mm)."""
        return self.A * math.sin(self.w * n * self.dt)

    def impulses(self, n0: int, n1: int) -> tuple[float, float, float, float]:
        """The vibration's impulses over steps n0 .. n1 - 1 (scene units; step n feels the acceleration
        A omega_d^2 sin(omega t_n), see :meth:`advance`): (x, y) per unit mass on every body (substrate target),
        then (x, y) on the block alone (block target)."""
        if not self.active or n1 <= n0:
            return 0.0, 0.0, 0.0, 0.0
        th = self.w * self.dt
        n = np.arange(n0, n1)
        j = self.A * self.wd2 * self.dt * float(np.sum(np.sin(th * n)))
        if self.pseudo:
            return (j, 0.0, 0.0, 0.0) if self.axis == 0 else (0.0, j, 0.0, 0.0)
        j *= self.M
        return (0.0, 0.0, j, 0.0) if self.axis == 0 else (0.0, 0.0, 0.0, j)

    def displacement(self, steps: int) -> float:
        """s(t) at the scene's step count (m)."""
        return self._s(steps) / U.LENGTH if self.active else 0.0

    def advance(self, scene, n: int) -> None:
        """n steps, each after setting the step's inertial acceleration (substrate target) or shaker force (block
        target) and the anchor's velocity; the law steps the space (in one loop when it needs no Python inside a
        step, else one step at a time). sin(omega t_n) by the two-term recurrence, re-anchored on math.sin at every
        call (its rounding over one call of tens of steps is ~1e-15). One pymunk setter per step (two with a moving
        anchor), each loop specialised so a step does no other attribute lookup or branch: the setters are the
        part's cost (bench_vibration.py). pymunk's gravity setter wakes every sleeping body: in the substrate's
        frame a resting grain feels the inertial force, so no grain sleeps while the substrate is shaken."""
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
        anchor, va, Kv = self.anchor, self.v_anchor, self.A / dt  # the laboratory moves by -s
        if anchor is not None:  # parallel only: the anchor's step-mean velocity in the substrate's frame
            for _ in range(n):
                s_next = c2 * s_cur - s_prev
                space.gravity = (gx + K * s_cur, gy)
                anchor.velocity = (va - Kv * (s_next - s_cur), 0.0)
                step(arg)
                s_prev, s_cur = s_cur, s_next
        elif self.axis == 0:
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

    def record(self, scene, ids, fl, tab, slider_terms, grain_table, drive_mass) -> tuple[float, float]:
        """(displacement s [mm], power [N mm/ms]) at the present sample, from the recorder's body buffer (ids,
        [px, py, vx, vy, w] per body) and body table (kind, index: 0 block, 1 slider, 2 particle, 3 drive body)."""
        if not self.active:
            return 0.0, 0.0
        n = scene.steps
        s = self._s(n)
        a = self.A * self.wd2 * math.sin(self.w * n * self.dt)
        if self.pseudo:
            P = _momentum(ids, fl, tab, self.M, slider_terms, grain_table, drive_mass, self.axis)
            return s, a * P
        v = self.block.velocity
        return s, self.M * a * (v.x if self.axis == 0 else v.y)

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
            "vib_caption": ("caption", f"{what} {s.direction} {s.amplitude * 1e6:.3g} um at {s.frequency:.4g} Hz: "
                                       f"s = {self._s(scene.steps) * 1e3:+.1f} um", {}),
        }


def _plain_advance():
    from .laws import Law
    return Law.advance


@numba.njit(cache=True)
def _momentum(ids, fl, tab, M, slider_terms, part, drive_mass, axis):
    """Total momentum along ``axis`` of the bodies in the recorder's table (scene units); masses: the block's M,
    column 0 of the sliders' terms and of the particles' table, the drive's bodies'. Bodies absent from the
    buffer are asleep (at rest)."""
    tab_ids = tab[:, 0]
    P = 0.0
    for r in range(ids.shape[0]):
        t = np.searchsorted(tab_ids, ids[r])
        if t >= tab.shape[0] or tab_ids[t] != ids[r]:
            continue
        kind, i = tab[t, 1], tab[t, 2]
        v = fl[5 * r + 2 + axis]
        if kind == 0:
            P += M * v
        elif kind == 1:
            P += slider_terms[i, 0] * v
        elif kind == 2:
            P += part[i, 0] * v
        else:
            P += drive_mass[i] * v
    return P
