"""A per-step energy ledger of the sweep's vibrated_patches scene (docs/results/vibration.md, energy balance).

Steps the scene one pymunk step at a time with a recorder sampling every step, and books every impulse's work
exactly, J . (v_before + v_after) / 2 (the kinetic energy identity of pymunk's semi-implicit Euler): the springs' and
dampers' (their ``impulse`` along the spring at the step's places), gravity's and the field's (known), and the
contacts' applied impulse (each pad's momentum change less all of those). Prints, as fractions of the drive's work:
the recorder's residual; the law's dampers and the contacts paired with v_after (as the unshaken recorder) against
exact; the arbiters' reported impulses against the applied (phantoms); the position correction's motion against the
springs; the exact per-step dissipation and field work sampled every 10 and 20 steps (the output rate's folding).

    python -m compare.studies.energy_ledger [amplitude_m] [duration_s] [dt_s]
"""
from __future__ import annotations

import math
import sys
import tomllib

import numpy as np
import pymunk

from engine_sim import scenario_from_dict, units as U
from engine_sim.record import Recorder
from engine_sim.loop import MAINTAIN_EVERY, warm_up
from engine_sim.scenario import SCENARIO_DIR
from engine_sim.scene import Scene

KEYS = ("W_drive_mid", "W_field_mid", "W_damp_mid", "D_damp_after", "W_contact_mid", "D_contact_after",
        "phantom", "D_first_contact", "W_spring_mid", "bias_against_springs")


def _scene(A, duration, dt):
    d = tomllib.loads((SCENARIO_DIR / "sweeps" / "vibrated_patches.toml").read_text())
    d["run"] = {**d["run"], "dt": dt, "duration": duration, "warmup": 0.3}
    if A > 0:
        d["vibration"] = {**d["vibration"], "amplitude": A, "frequency": 1000.0}
    else:
        d.pop("vibration")
    sc = scenario_from_dict(d)
    scene = Scene(sc, sc.run.seed)
    warm_up(scene, int(round(sc.run.warmup / sc.run.dt_out)))
    return scene, int(round(duration / dt))


def _step(scene, bodies, m, springs, acc):
    """One step; its terms added to ``acc``; returns (exact dissipated power, exact field power) of the step."""
    dt, vib = scene.dt, scene.vibration
    V = np.array([tuple(b.velocity) for b in bodies])
    X = np.array([tuple(b.position) for b in bodies])
    a = vib.A * vib.wd2 * math.sin(vib.w * vib.dt * scene.steps) if vib is not None and vib.active else 0.0
    scene.advance(1)
    X1 = np.array([tuple(b.position) for b in bodies])
    V1 = np.array([tuple(b.velocity) for b in bodies])
    Vm = 0.5 * (V + V1)
    J = {"drive": np.zeros_like(V), "damp": np.zeros_like(V), "el": np.zeros_like(V)}
    for c, ia, ib, kind in springs:
        dv = c.b.local_to_world(c.anchor_b) - c.a.local_to_world(c.anchor_a)
        j = c.impulse * np.array(dv / dv.length)
        if ib >= 0:
            J[kind][ib] += j
        if ia >= 0:
            J[kind][ia] -= j
    g = np.array(scene.space.gravity)
    Jf = np.outer(m, [a, 0.0]) * dt
    Japp = m[:, None] * (V1 - V) - J["drive"] - J["damp"] - J["el"] - np.outer(m, g) * dt - Jf
    Japp[0] = 0.0  # the block: its groove's impulse; no contacts
    for i, p in enumerate(bodies[1:], start=1):
        arbs = []
        p.each_arbiter(lambda arb: arbs.append((np.array(tuple(arb.total_impulse)), np.array(tuple(arb.normal)),
                                                arb.is_first_contact)))
        if not arbs:
            continue
        t = np.array([-arbs[0][1][1], arbs[0][1][0]])
        rep = sum(Jr for Jr, _, _ in arbs)
        acc["phantom"] -= ((rep - Japp[i]) @ t) * (V1[i] @ t)  # the dissipation the phantoms add
        acc["W_contact_mid"] += (Japp[i] @ t) * (Vm[i] @ t)
        acc["D_contact_after"] -= (rep @ t) * (V1[i] @ t)
        if any(first for _, _, first in arbs):
            acc["D_first_contact"] -= (rep @ t) * (V1[i] @ t)
    acc["W_drive_mid"] += np.sum(J["drive"] * Vm)
    acc["W_field_mid"] += np.sum(Jf * Vm)
    acc["W_damp_mid"] += np.sum(J["damp"] * Vm)
    acc["D_damp_after"] += np.sum(scene.slider_terms[:, 1] * V1[1:, 0] ** 2) * dt
    acc["W_spring_mid"] += np.sum(J["el"] * Vm)
    acc["bias_against_springs"] += -np.sum(J["el"] / dt * (X1 - X - V * dt))
    return -(np.sum(J["damp"] * Vm) + np.sum(Japp * Vm)) / dt, np.sum(Jf * Vm) / dt


def _folded(P, q, dt):
    """Trapezoid of the per-step power P sampled every q steps less the exact sum over the same span, per phase."""
    out = []
    for off in range(q):
        ix = np.arange(off, P.size, q)
        out.append(np.sum(0.5 * (P[ix][1:] + P[ix][:-1])) * q * dt - np.sum(P[ix[0] + 1: ix[-1] + 1]) * dt)
    return np.array(out)


def ledger(A=2.72e-6, duration=1.0, dt=2.5e-5):
    scene, n = _scene(A, duration, dt)
    rec = Recorder(scene, n + 1)
    bodies = [scene.block] + list(scene.pads)
    m = np.array([b.mass for b in bodies])
    index = {b: i for i, b in enumerate(bodies)}
    springs = [(c, index.get(c.a, -1), index.get(c.b, -1),
                "drive" if c is scene.drive.spring else ("damp" if c.stiffness == 0.0 else "el"))
               for c in scene.space.constraints if isinstance(c, pymunk.DampedSpring)]
    acc = dict.fromkeys(KEYS, 0.0)
    P, Pf = np.zeros(n + 1), np.zeros(n + 1)
    rec.sample()
    # steps the scene itself: _step reads every body before and after each pymunk step, which Loop cannot hand out
    for k in range(n):
        P[k + 1], Pf[k + 1] = _step(scene, bodies, m, springs, acc)
        rec.sample()
        if (k + 1) % (MAINTAIN_EVERY * scene.n_sub) == 0:
            scene.maintain()
    P[0], Pf[0] = P[1], Pf[1]
    tr = rec.trace({})
    W = tr.work_drive[-1]
    res = (W + tr.work_vibration[-1] - tr.dissipated[-1] - tr.mech_energy[-1]) / W
    print(f"A = {A:.3g} m, dt = {dt:.3g} s, {duration:g} s: recorder sampled every step, residual / W_drive {res:+.3e}")
    for key in KEYS:
        print(f"  {key:22s} {acc[key] / U.ENERGY / W:+.3e} W_drive")
    for q in (10, 20):
        d, f = _folded(P, q, scene.dt), _folded(Pf, q, scene.dt)
        print(f"  sampled every {q} steps, rms over phases: dissipation {np.sqrt(np.mean(d ** 2)) / U.ENERGY / W:.2e}, "
              f"field work {np.sqrt(np.mean(f ** 2)) / U.ENERGY / W:.2e} W_drive")


if __name__ == "__main__":
    ledger(*(float(a) for a in sys.argv[1:]))
