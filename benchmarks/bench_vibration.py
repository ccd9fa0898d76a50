"""What a [vibration] adds to a scene's step: the project's loop (stepping, recording, maintenance) on
pads_friction_patches and constant_velocity without and with each kind of vibration, microseconds per step,
alternating chunks on the two scenes, minimum and median. Target: at most 5 % (one run; say the load).

    python -m benchmarks.bench_vibration [--chunks N] [--before-after]
"""
import argparse
import math
import os
import time
import types
import tomllib

import numpy as np

from engine_sim import Scene, scenario_from_dict, shipped_scenarios
from engine_sim.record import Recorder

VIBRATIONS = {
    "substrate parallel": {"target": "substrate", "direction": "parallel", "amplitude": 2e-4, "frequency": 10.0},
    "substrate normal": {"target": "substrate", "direction": "normal", "amplitude": 2e-6, "frequency": 50.0},
    "block parallel": {"target": "block", "direction": "parallel", "amplitude": 2e-4, "frequency": 10.0},
}
# the part at work with the motion it imposes far below everything else (1e-12 m): the loop's cost without the
# solver's response to the shaking (a shaken scene's contacts change, and with them the solver's work)
SILENT = {"target": "substrate", "direction": "parallel", "amplitude": 1e-12, "frequency": 10.0}


def scenario(name: str, vibration: dict | None):
    data = tomllib.loads(shipped_scenarios()[name].read_text())
    if vibration is not None:
        data["vibration"] = vibration
    return scenario_from_dict(data)


def paired(sc_a, sc_b, chunks: int, chunk: int = 16):
    """Microseconds per step of the project's loop (advance, sample, maintain) on two scenes, alternating chunks of
    ``chunk`` output steps so that both see the same machine; the minimum and the median over the chunks of each
    (the minimum is the figure least disturbed by other processes on a loaded machine). CPU time of this process
    (time.process_time), not wall time: on a shared machine the wall clock counts other processes' turns."""
    scenes = [Scene(sc_a), Scene(sc_b)]
    recs = []
    for s in scenes:
        s.advance(2000)
        recs.append(Recorder(s, chunks * chunk + 1))
        recs[-1].sample()
    times = [[], []]
    for _ in range(chunks):
        for i, (s, r) in enumerate(zip(scenes, recs)):
            s.maintain()
            t0 = time.process_time()
            for _ in range(chunk):
                s.advance(s.n_sub)
                r.sample()
            times[i].append((time.process_time() - t0) / (chunk * s.n_sub) * 1e6)
    return [(float(np.min(t)), float(np.median(t))) for t in times]


def own_work(name: str, vib: dict, reps: int = 300):
    """The part's own stepping work per pymunk step (us, CPU, minimum over ``reps`` output steps, ``space.step`` a
    no-op), (without vibration, before, after), measured in alternation."""
    scenes = [Scene(scenario(name, None)), Scene(scenario(name, vib)), Scene(scenario(name, vib))]
    scenes[1].vibration.advance = types.MethodType(advance_before, scenes[1].vibration)
    best = [math.inf] * 3
    for s in scenes:
        s.advance(100)
        s.space.step = lambda dt: None
    for _ in range(reps):
        for i, s in enumerate(scenes):
            t0 = time.process_time()
            s.advance(s.n_sub)
            best[i] = min(best[i], (time.process_time() - t0) / s.n_sub * 1e6)
    return best


def overhead(sc_vib, sc_base, reps: int = 300):
    """The vibration's own work per pymunk step (us, CPU, minimum over ``reps``): its stepping loop and the
    recorder's extra channel, with ``space.step`` replaced by a no-op, so the figure carries none of the solver's
    noise. Returns (advance with, advance without, sample with, sample without), the samples per output step."""
    out = []
    for sc in (sc_vib, sc_base):
        scene = Scene(sc)
        scene.advance(100)
        rec = Recorder(scene, reps + 1)
        scene.space.step = lambda dt: None
        ta, ts = [], []
        for _ in range(reps):
            t0 = time.process_time()
            scene.advance(scene.n_sub)
            ta.append((time.process_time() - t0) / scene.n_sub * 1e6)
            t0 = time.process_time()
            rec.sample()
            ts.append((time.process_time() - t0) * 1e6)
        out.append((min(ta), min(ts), scene.n_sub))
    (a1, s1, n), (a0, s0, _) = out
    return a1, a0, s1, s0, n


def advance_before(self, scene, n: int) -> None:
    """The part's stepping loop as it was before its loops were specialised (one loop for every case, the axis
    and the anchor tested and ``self`` read at each step), kept here as the baseline of ``--before-after``."""
    if not self.active:
        scene.law.advance(scene, n)
        return
    k0 = scene.steps
    th = self.w * self.dt
    c2 = 2.0 * math.cos(th)
    s_prev, s_cur = math.sin(th * (k0 - 1)), math.sin(th * k0)
    K = self.A * self.wd2
    space, dt, law = scene.space, self.dt, scene.law
    if self.plain:
        do, arg = space.step, dt
    else:
        do, arg = (lambda _: law.advance(scene, 1)), None
    if self.pseudo:
        gx, gy = self.g0
        anchor, va, Kv = self.anchor, self.v_anchor, self.A / dt
        for _ in range(n):
            s_next = c2 * s_cur - s_prev
            space.gravity = (gx + K * s_cur, gy) if self.axis == 0 else (gx, gy + K * s_cur)
            if anchor is not None:
                anchor.velocity = (va - Kv * (s_next - s_cur), 0.0)
            do(arg)
            s_prev, s_cur = s_cur, s_next
        space.gravity = self.g0
    else:
        block, KM = self.block, K * self.M
        for _ in range(n):
            block.force = (KM * s_cur, 0.0) if self.axis == 0 else (0.0, KM * s_cur)
            do(arg)
            s_prev, s_cur = s_cur, c2 * s_cur - s_prev


def before_after(name: str, vib: dict, chunks: int, chunk: int = 16):
    """us per step (CPU, minimum and median over alternating chunks) of the whole loop on three scenes of
    ``name`` built alike: without vibration, with it stepped by :func:`advance_before`, with it stepped by
    :meth:`engine_sim.vibration.Vibration.advance`; the three share the machine chunk by chunk."""
    scenes = [Scene(scenario(name, None)), Scene(scenario(name, vib)), Scene(scenario(name, vib))]
    scenes[1].vibration.advance = types.MethodType(advance_before, scenes[1].vibration)
    recs = []
    for s in scenes:
        s.advance(2000)
        recs.append(Recorder(s, chunks * chunk + 1))
        recs[-1].sample()
    times = [[], [], []]
    for _ in range(chunks):
        for i, (s, r) in enumerate(zip(scenes, recs)):
            s.maintain()
            t0 = time.process_time()
            for _ in range(chunk):
                s.advance(s.n_sub)
                r.sample()
            times[i].append((time.process_time() - t0) / (chunk * s.n_sub) * 1e6)
    return [(float(np.min(t)), float(np.median(t))) for t in times]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--chunks", type=int, default=200)
    ap.add_argument("--before-after", action="store_true",
                    help="only the loop before and after its specialisation, beside the unshaken scene")
    a = ap.parse_args(argv)
    if a.before_after:
        print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
        print("| scenario | vibration | without | before | after | before / without | after / without |")
        print("|---|---|---|---|---|---|---|")
        for name in ("pads_friction_patches", "constant_velocity"):
            for label, vib in (("substrate parallel, 1e-12 m", SILENT), ("substrate parallel", VIBRATIONS[
                    "substrate parallel"]), ("substrate normal", VIBRATIONS["substrate normal"])):
                (b, _), (f0, _), (f1, _) = before_after(name, vib, a.chunks)
                print(f"| {name} | {label} | {b:.2f} | {f0:.2f} | {f1:.2f} | {f0 / b:.3f} | {f1 / b:.3f} |")
        print("\nThe stepping loop's own work (space.step a no-op; CPU us per step, minimum of 300):\n")
        print("| scenario | vibration | without | before | after |")
        print("|---|---|---|---|---|")
        for name in ("pads_friction_patches", "constant_velocity"):
            for label in ("substrate parallel", "substrate normal"):
                b, f0, f1 = own_work(name, VIBRATIONS[label])
                print(f"| {name} | {label} | {b:.3f} | {f0:.3f} | {f1:.3f} |")
        print(f"load average after: {os.getloadavg()[0]:.2f}")
        return
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
    print("| scenario | vibration | us/step without (min, median) | with (min, median) | ratio of minima | ratio of medians |")
    print("|---|---|---|---|---|---|")
    for name in ("pads_friction_patches", "constant_velocity"):
        for label, vib in VIBRATIONS.items():
            (b0, b1), (f0, f1) = paired(scenario(name, None), scenario(name, vib), a.chunks)
            print(f"| {name} | {label} | {b0:.2f}, {b1:.2f} | {f0:.2f}, {f1:.2f} | {f0 / b0:.3f} | {f1 / b1:.3f} |")
    print("\nThe part's own work (space.step a no-op; CPU us, minimum of 300):\n")
    print("| scenario | vibration | stepping loop per step, with / without | sample, with / without | extra per step |")
    print("|---|---|---|---|---|")
    for name in ("pads_friction_patches", "constant_velocity"):
        for label, vib in VIBRATIONS.items():
            a1, a0, s1, s0, n = overhead(scenario(name, vib), scenario(name, None))
            print(f"| {name} | {label} | {a1:.2f} / {a0:.2f} | {s1:.1f} / {s0:.1f} | {a1 - a0 + (s1 - s0) / n:.2f} |")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
