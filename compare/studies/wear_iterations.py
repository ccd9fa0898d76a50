"""Speed against error for the wear scene: what each pymunk solver iteration count costs and how far the
grains' force is from its converged value (same seed, same substrate, same grains).

    python -m compare.studies.wear_iterations [--duration S] [--seeds 0,1,2] [--smoke]

Error = |mean grains' force / the same seed's at 30 iterations - 1| (the grains' force is the quantity
the solver gets wrong first; the block's speed follows it). Cost = loop microseconds per step, measured in
this run against the particle-free twin at the same iteration count and against `pads_friction_patches` at
its own 2 iterations (pymunk's iteration count is global to a space: the grains' contacts set it for all
30 pads). A second table runs grains ten times heavier (min_mass = 1e-3 kg, the pads' mass), which the
solver converges in fewer iterations but whose force differs (see the [wear] docs).
"""
import argparse
import time

import engine_sim
from benchmarks.bench_engine import loop_ratio
from compare.analysis.balances import balances as _balances
from engine_sim import load_scenario, shipped_scenarios

ITERATIONS = (4, 8, 10, 12, 15, 20, 30)
REFERENCE = 30


def grain_runs(sc, iterations, seeds, duration):
    """{(iterations, seed): (mean grains' force N, mean speed m/s, energy residual / drive work)}."""
    out = {}
    for it in iterations:
        for seed in seeds:
            tr = engine_sim.run(sc.with_run(iterations=it), duration=duration, seed=seed)
            resid = _balances(tr)["energy_balance_rel"]
            out[it, seed] = (float(tr.p_force.sum(axis=1).mean()), float(tr.v.mean()), resid)
    return out


def table(sc, iterations, seeds, duration, steps, us_ref, reference=REFERENCE):
    runs = grain_runs(sc, sorted(set(iterations) | {reference}), seeds, duration)
    lines = ["| iterations | loop us/step | vs. no particles, same iterations | vs. pads_friction_patches (2 its) "
             f"| grains' force (N), per seed | error vs. {reference} its, worst seed | energy residual, worst |",
             "|---|---|---|---|---|---|---|"]
    for it in iterations:
        _, us = loop_ratio(sc.with_run(iterations=it), steps)
        _, us0 = loop_ratio(sc.with_run(iterations=it).with_wear(count=0), steps)
        f = [runs[it, s][0] for s in seeds]
        err = max(abs(runs[it, s][0] / runs[reference, s][0] - 1) for s in seeds)
        res = max(abs(runs[it, s][2]) for s in seeds)
        lines.append(f"| {it} | {us:.1f} | {us / us0:.2f} | {us / us_ref:.2f} | {', '.join(f'{x:.3f}' for x in f)} "
                     f"| {err * 100:.1f} % | {res * 100:.2f} % |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--duration", type=float, default=6.0, help="simulated seconds per run (default 6)")
    ap.add_argument("--seeds", default="0,1,2")
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    wear = load_scenario(shipped_scenarios()["pads_with_wear"])
    patches = load_scenario(shipped_scenarios()["pads_friction_patches"])
    seeds = [int(s) for s in a.seeds.split(",")]
    steps = 3000 if a.smoke else 30_000
    if a.smoke:
        iterations, seeds, duration, reference = (20,), seeds[:1], 0.3, 20
    else:
        iterations, duration, reference = ITERATIONS, a.duration, REFERENCE
    t0 = time.perf_counter()
    _, us_ref = loop_ratio(patches, steps)
    print(f"pads_friction_patches at {patches.run.iterations} iterations: {us_ref:.1f} us/step\n")
    print(f"grains of min_mass = {wear.wear.min_mass:g} kg (the shipped pads_with_wear), {duration:g} s runs")
    print(table(wear, iterations, seeds, duration, steps, us_ref, reference))
    if not a.smoke:
        heavy = wear.with_wear(min_mass=1e-3)
        print(f"\ngrains of min_mass = 1e-3 kg (converge sooner, but push harder), {duration:g} s runs")
        print(table(heavy, (4, 8), seeds, duration, steps, us_ref, reference))
    print(f"\n{time.perf_counter() - t0:.0f} s wall")


if __name__ == "__main__":
    main()
