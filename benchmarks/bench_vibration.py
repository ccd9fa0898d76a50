"""What a [vibration] adds to a scene's step: the project's loop (stepping, recording, maintenance) on
pads_friction_patches and constant_velocity without and with each kind of vibration, microseconds per step,
alternating chunks on the two scenes, minimum and median. Target: at most 5 % (one run; say the load).

    python -m benchmarks.bench_vibration [--chunks N]
"""
import argparse
import os
import time
import tomllib

import numpy as np

from engine_sim import Scene, scenario_from_dict, shipped_scenarios
from engine_sim.record import Recorder

VIBRATIONS = {
    "substrate parallel": {"target": "substrate", "direction": "parallel", "amplitude": 2e-4, "frequency": 10.0},
    "substrate normal": {"target": "substrate", "direction": "normal", "amplitude": 2e-6, "frequency": 50.0},
    "block parallel": {"target": "block", "direction": "parallel", "amplitude": 2e-4, "frequency": 10.0},
}


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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--chunks", type=int, default=200)
    a = ap.parse_args(argv)
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
