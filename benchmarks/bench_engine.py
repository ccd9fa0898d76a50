"""Engine scene cost: microseconds per step, simulated seconds per wall second, and the ratio of the
project's loop (spring drive, recording at the output rate, substrate maintenance) to a bare
`space.step` loop on the same space, measured in the same run (targets: ratio <= 1.15;
pads_friction_patches gives C_x over two decades above v/a in <= 3 min).

    python -m benchmarks.bench_engine [--steps N] [--smoke]
"""
import argparse
import time

import numpy as np

import engine_sim
from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum
from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.record import Recorder
from engine_sim.run import MAINTAIN_EVERY


def loop_ratio(sc, n_steps: int, repeat: int = 3):
    """Best-of-`repeat` microseconds per step of a bare space.step loop and of the project's loop.

    Both run in chunks of MAINTAIN_EVERY output steps on the same scene; the bare loop's substrate is
    maintained outside its timer (without it the pads run off their tracks and the steps get cheaper),
    the project's loop pays for its maintenance and its recording.
    """
    scene = Scene(sc)
    scene.advance(2000)
    n_sub = scene.n_sub
    chunk = MAINTAIN_EVERY
    n_chunks = max(1, n_steps // (n_sub * chunk))
    rec = Recorder(scene, n_chunks * chunk * repeat + 1)
    rec.sample()
    step, dt = scene.space.step, scene.dt
    bare, full = [], []
    for _ in range(repeat):  # interleaved, so drifts in machine speed hit both
        tb = 0.0
        for _ in range(n_chunks):
            scene.maintain()
            t0 = time.perf_counter()
            for _ in range(chunk * n_sub):
                step(dt)
            tb += time.perf_counter() - t0
        scene.steps += n_chunks * chunk * n_sub
        bare.append(tb)
        t0 = time.perf_counter()
        for _ in range(n_chunks):
            scene.maintain()
            for _ in range(chunk):
                scene.advance(n_sub)
                rec.sample()
        full.append(time.perf_counter() - t0)
    n = n_chunks * chunk * n_sub
    return min(bare) / n * 1e6, min(full) / n * 1e6


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--steps", type=int, default=50_000)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    steps = 3000 if a.smoke else a.steps
    print("| scenario | bare us/step | loop us/step | loop / bare | simulated s per wall s |")
    print("|---|---|---|---|---|")
    for name, path in shipped_scenarios().items():
        sc = load_scenario(path)
        b, f = loop_ratio(sc, steps)
        print(f"| {name} | {b:.1f} | {f:.1f} | {f / b:.3f} | {sc.run.dt / (f * 1e-6):.2f} |")
    # what the wear particles cost (target: 50 particles at most 2x the particle-free step)
    wear = load_scenario(shipped_scenarios()["pads_with_wear"])
    patches = load_scenario(shipped_scenarios()["pads_friction_patches"])
    print("\n| wear particles | loop us/step | vs. no particles, same settings | vs. pads_friction_patches |")
    print("|---|---|---|---|")
    _, f_ref = loop_ratio(patches, steps)
    _, f0 = loop_ratio(wear.with_wear(count=0), steps)
    for n in (0, 50, 200):
        _, f = loop_ratio(wear.with_wear(count=n, ahead=max(wear.wear.ahead, 2.5e-3 + 4e-4 * -(-n // wear.pads.N))), steps)
        print(f"| {n} | {f:.1f} | {f / f0:.2f} | {f / f_ref:.2f} |")
    if not a.smoke:
        sc = load_scenario(shipped_scenarios()["pads_friction_patches"])
        t0 = time.perf_counter()
        tr = engine_sim.run(sc)
        spec = displacement_spectrum(tr.t, tr.x)
        w0 = sc.steady_velocity / sc.substrate.a
        fit = fit_power_law(spec, band=(3 * w0, 30 * w0))
        wall = time.perf_counter() - t0
        print(f"\npads_friction_patches, {sc.run.duration:g} s: spectrum {spec.omega_min:.3g}-{spec.omega_max:.0f} rad/s "
              f"({np.log10(spec.omega_max / w0):.1f} decades above v/a = {w0:g} rad/s) in {wall:.1f} s wall; {fit}")


if __name__ == "__main__":
    main()
