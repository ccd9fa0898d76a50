"""What a [vibration] adds to a scene's step: the project's loop (stepping, recording, maintenance) on
pads_friction_patches and constant_velocity without and with each kind of vibration, microseconds per step,
alternating chunks on the two scenes, minimum and median. Target: at most 5 % (one run; say the load).

    python -m benchmarks.bench_vibration [--chunks N] [--before-after] [--engine [--rounds R]]
    python -m pytest benchmarks/bench_vibration.py   # the harness's entry, one per scene

``--engine``: bench_engine's measure (its ``loop_ratio``: the project's loop against a bare ``space.step`` loop on
the same scene, chunk by chunk, the thread's CPU clock) on each scene without and with the vibration, the scenes
in turn over ``R`` rounds; the part's share of the step is the shaken scene's loop / bare less the unshaken one's.
"""
import argparse
import math
import os
import time
import types
import tomllib

import numba
import numpy as np
import pymunk

from engine_sim import Scene, scenario_from_dict, shipped_scenarios
from engine_sim.loop import Loop, warm_up
from engine_sim.record import Recorder

WARM_STEPS = 2000  # pymunk steps of the scenes' unrecorded warm-up, maintained as a run's is (engine_sim.loop.warm_up)

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


def recording_loop(sc, capacity: int) -> Loop:
    """The project's loop (:class:`engine_sim.loop.Loop`) recording a scene of ``sc`` into ``capacity`` samples,
    after the warm-up (``WARM_STEPS``)."""
    s = Scene(sc)
    warm_up(s, -(-WARM_STEPS // s.n_sub))
    return Loop(s, Recorder(s, capacity))


def timed_chunk(loop: Loop, chunk: int) -> float:
    """Microseconds per pymunk step (CPU) of ``chunk`` output steps of the project's loop: each a sample, the
    maintenance every MAINTAIN_EVERY output steps, the pymunk steps."""
    t0 = time.process_time()
    loop.run(chunk)
    return (time.process_time() - t0) / (chunk * loop.scene.n_sub) * 1e6


def paired(sc_a, sc_b, chunks: int, chunk: int = 16):
    """Microseconds per step of the project's loop (:class:`engine_sim.loop.Loop`: sample, maintain, advance) on
    two scenes, alternating chunks of ``chunk`` output steps so that both see the same machine; the minimum and the
    median over the chunks of each (the minimum is the figure least disturbed by other processes on a loaded
    machine, and with 16-step chunks one in four holds a maintenance, so the minimum is a chunk without one). CPU
    time of this process (time.process_time), not wall time: on a shared machine the wall clock counts other
    processes' turns."""
    loops = [recording_loop(sc_a, chunks * chunk), recording_loop(sc_b, chunks * chunk)]
    times = [[], []]
    for _ in range(chunks):
        for i, loop in enumerate(loops):
            times[i].append(timed_chunk(loop, chunk))
    return [(float(np.min(t)), float(np.median(t))) for t in times]


def loop_cost(sc, chunks: int = 100, chunk: int = 16) -> float:
    """us per step (CPU, minimum over ``chunks`` chunks of ``chunk`` output steps) of the project's loop on a scene:
    the step cost a part's own work is set against (the minimum: the least disturbed, so the largest share)."""
    loop = recording_loop(sc, chunks * chunk)
    return min(timed_chunk(loop, chunk) for _ in range(chunks))


def own_work(name: str, vib: dict, reps: int = 300):
    """The part's own stepping work per pymunk step (us, CPU, minimum over ``reps`` output steps, ``space.step`` a
    no-op), (without vibration, before, after), measured in alternation. The riding anchor's cost (one more body
    and a groove joint) is inside ``space.step`` and so not in these figures: the whole loop's are the ones to read."""
    scenes = [Scene(scenario(name, None)), before_scene(scenario(name, vib)), Scene(scenario(name, vib))]
    for s in scenes:
        warm_up(s, -(-100 // s.n_sub))
    return stepping_minima(scenes, reps)


def stepping_minima(scenes, reps: int) -> list:
    """Each scene's stepping work per pymunk step with ``space.step`` made a no-op (us, CPU, minimum over ``reps``
    output steps, the scenes in alternation)."""
    # steps the scenes itself: it times the part's stepping (Scene.advance) alone, without the sample and the
    # maintenance that engine_sim.loop.Loop puts in every output step
    best = [math.inf] * len(scenes)
    for s in scenes:
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
    noise. Returns (advance with, advance without, sample with, sample without, the separate momentum kernel the
    recorder called before the main kernel summed the momentum), the samples per output step."""
    # steps the scenes itself: it times the stepping and the sample of one output step apart, which
    # engine_sim.loop.Loop runs as one
    out = []
    for sc in (sc_vib, sc_base):
        scene = Scene(sc)
        warm_up(scene, -(-100 // scene.n_sub))
        rec = Recorder(scene, reps + 1)
        scene.space.step = lambda dt: None
        ta, ts, tk = [], [], []
        for _ in range(reps):
            t0 = time.process_time()
            scene.advance(scene.n_sub)
            ta.append((time.process_time() - t0) / scene.n_sub * 1e6)
            t0 = time.process_time()
            rec.sample()
            ts.append((time.process_time() - t0) * 1e6)
            ids, fl = rec._bodies.read()
            t0 = time.process_time()
            _momentum_before(ids, fl, rec._tab, scene.M, scene.slider_terms, rec.grain_table, rec._drive_mass, 0)
            tk.append((time.process_time() - t0) * 1e6)
        out.append((min(ta), min(ts), min(tk), scene.n_sub))
    (a1, s1, k1, n), (a0, s0, _, _) = out
    return a1, a0, s1, s0, k1, n


@numba.njit(cache=True)
def _momentum_before(ids, fl, tab, M, slider_terms, part, drive_mass, axis):
    """The momentum sum as the part called it at each sample before :func:`engine_sim.reduction.momentum` joined the
    recorder's main kernel (its cost is mostly numba's dispatch of eight arguments)."""
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


def before_scene(sc):
    """A scene as the part built and stepped it before the velocity drive's anchor rode the inertial field: that
    anchor kinematic, given each step's mean velocity by a second setter in the loop (:func:`advance_before`). For
    a scene without a moving anchor the part is unchanged and so is the scene."""
    scene = Scene(sc)
    vib = scene.vibration
    if vib is not None and vib.active and vib.anchor is not None:
        scene.space.remove(vib.groove)
        vib.groove = None
        vib.anchor.body_type = pymunk.Body.KINEMATIC  # pymunk zeroes a non-dynamic body's velocity
        vib.anchor.velocity = (vib.v_anchor - vib._s(1) / vib.dt, 0.0)
        vib.advance = types.MethodType(advance_before, vib)
    return scene


def advance_before(self, scene, n: int) -> None:
    """The part's stepping loop with a kinematic anchor (two setters per step: gravity and the anchor's velocity),
    as it was before the anchor rode the field, kept here as the baseline of ``--before-after``."""
    k0 = scene.steps
    th = self.w * self.dt
    c2 = 2.0 * math.cos(th)
    s_prev, s_cur = math.sin(th * (k0 - 1)), math.sin(th * k0)
    K = self.A * self.wd2
    space, dt, law = scene.space, self.dt, scene.law
    if self.plain:
        step, arg = space.step, dt
    else:
        step, arg = (lambda _: law.advance(scene, 1)), None
    gx, gy = self.g0
    anchor, va, Kv = self.anchor, self.v_anchor, self.A / dt
    for _ in range(n):
        s_next = c2 * s_cur - s_prev
        space.gravity = (gx + K * s_cur, gy)
        anchor.velocity = (va - Kv * (s_next - s_cur), 0.0)
        step(arg)
        s_prev, s_cur = s_cur, s_next
    space.gravity = self.g0


def before_after(name: str, vib: dict, chunks: int, chunk: int = 16):
    """us per step (CPU) of the whole loop on three scenes of ``name``: without vibration, with it as before
    (:func:`before_scene`), with it as :class:`engine_sim.vibration.Vibration` builds and steps it; the three
    share the machine chunk by chunk, their order turning from chunk to chunk. Returns each scene's minimum over
    the chunks and, for before and after, the median over the chunks of the ratio to the unshaken scene's chunk
    of the same turn (a burst of load hits the three chunks of a turn alike, so the paired ratio scatters less
    than the minima do)."""
    loops = []
    for s in (Scene(scenario(name, None)), before_scene(scenario(name, vib)), Scene(scenario(name, vib))):
        warm_up(s, -(-WARM_STEPS // s.n_sub))
        loops.append(Loop(s, Recorder(s, chunks * chunk)))
    times = [[], [], []]
    for c in range(chunks):
        for i in (c % 3, (c + 1) % 3, (c + 2) % 3):
            times[i].append(timed_chunk(loops[i], chunk))
    t = np.array(times)
    return [float(x) for x in t.min(axis=1)], float(np.median(t[1] / t[0])), float(np.median(t[2] / t[0]))


def engine(rounds: int, steps: int = 50_000):
    """Rows (scenario, vibration, unshaken loop / bare, shaken loop / bare, difference) of bench_engine's
    ``loop_ratio``, the median over ``rounds`` rounds in which the scenes take turns."""
    from benchmarks.bench_engine import loop_ratio

    rows = []
    for name in ("pads_friction_patches", "constant_velocity"):
        cases = [("none", None), ("substrate parallel, 1e-12 m", SILENT)] + list(VIBRATIONS.items())
        cases = [(label, vib) for label, vib in cases if label != "block parallel"]
        ratios = {label: [] for label, _ in cases}
        for _ in range(rounds):
            for label, vib in cases:
                ratios[label].append(loop_ratio(scenario(name, vib), steps, ratio=True)[2])
        r0 = float(np.median(ratios["none"]))
        for label, _ in cases[1:]:
            r = float(np.median(ratios[label]))
            rows.append((name, label, r0, r, r - r0))
    return rows


def shaken_against_unshaken(benchmark, ratio, smoke, name):
    """The harness's entry on a scene: one chunk of the loop (16 output steps and their samples; a maintenance in
    one chunk of four) on the scene shaken along the sliding direction (10 Hz, 0.2 mm) timed by the harness, and in
    the same run the shaken loop's cost per step over the unshaken one's (``paired``: chunks in turns, the ratio of the minima; 10 chunks at smoke
    size, 200 at full size; the target: at most 1.05)."""
    vib, chunk = VIBRATIONS["substrate parallel"], 16
    (b, _), (f, _) = paired(scenario(name, None), scenario(name, vib), 10 if smoke else 200, chunk)
    ratio("shaken / unshaken loop per step", f / b)
    rounds = 5 if smoke else 50
    loop = recording_loop(scenario(name, vib), (rounds + 1) * chunk)
    benchmark.pedantic(loop.run, args=(chunk,), rounds=rounds, warmup_rounds=1)


# one entry per scene, without pytest's parametrize: compare.studies.step_ledger imports this module
def test_shaken_against_unshaken_patches(benchmark, ratio, smoke):
    shaken_against_unshaken(benchmark, ratio, smoke, "pads_friction_patches")


def test_shaken_against_unshaken_constant_velocity(benchmark, ratio, smoke):
    shaken_against_unshaken(benchmark, ratio, smoke, "constant_velocity")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--chunks", type=int, default=200)
    ap.add_argument("--before-after", action="store_true",
                    help="only the part before and after the velocity drive's anchor rode the inertial field, "
                         "beside the unshaken scene")
    ap.add_argument("--engine", action="store_true", help="bench_engine's loop / bare ratio with and without")
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args(argv)
    if a.engine:
        print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
        print("| scenario | vibration | loop / bare, unshaken | loop / bare, shaken | shaken less unshaken |")
        print("|---|---|---|---|---|")
        for name, label, r0, r, d in engine(a.rounds):
            print(f"| {name} | {label} | {r0:.3f} | {r:.3f} | {d:+.3f} |", flush=True)
        print(f"load average after: {os.getloadavg()[0]:.2f}")
        return
    if a.before_after:
        print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
        print("| scenario | vibration | without | before | after | before / without | after / without | "
              "paired: before / without | paired: after / without |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name in ("pads_friction_patches", "constant_velocity"):
            for label, vib in (("substrate parallel, 1e-12 m", SILENT), ("substrate parallel", VIBRATIONS[
                    "substrate parallel"]), ("substrate normal", VIBRATIONS["substrate normal"])):
                (b, f0, f1), r0, r1 = before_after(name, vib, a.chunks)
                print(f"| {name} | {label} | {b:.2f} | {f0:.2f} | {f1:.2f} | {f0 / b:.3f} | {f1 / b:.3f} | "
                      f"{r0:.3f} | {r1:.3f} |", flush=True)
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
    print("| scenario | vibration | stepping loop per step, with / without | sample, with / without | "
          "the former momentum kernel per sample | extra per step |")
    print("|---|---|---|---|---|---|")
    for name in ("pads_friction_patches", "constant_velocity"):
        for label, vib in VIBRATIONS.items():
            a1, a0, s1, s0, k1, n = overhead(scenario(name, vib), scenario(name, None))
            print(f"| {name} | {label} | {a1:.2f} / {a0:.2f} | {s1:.1f} / {s0:.1f} | {k1:.2f} | "
                  f"{a1 - a0 + (s1 - s0) / n:.2f} |")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
