"""The scene's cost with the rate_state friction law against the linear law, in one run: pads_rate_state as
shipped, and the same scene with the linear law (mu0 = the rate_state scene's mean friction coefficient at its speed,
c = its steady slope, so both slide at the same speed); the project's loop (steps, recording at the output rate,
substrate maintenance), with the log law's twin for reference, interleaved so drifts in machine speed hit both; best of ``--repeat``. The machine load
(os.getloadavg) is printed beside the timings.

    python -m benchmarks.bench_rate_state_scene [--steps N] [--repeat R]
    python -m pytest benchmarks/bench_rate_state_scene.py   # the harness's entry (test_rate_state_against_linear_law)
"""
import argparse
import os
import time
from dataclasses import replace

from engine_sim import Scene, load_scenario
from engine_sim.laws import FrictionSpec
from engine_sim.record import Recorder
from engine_sim.loop import Loop, warm_up


def linear_twin(sc):
    """The scene with the linear law sliding at the same speed with the same slope."""
    v, load = sc.steady_velocity, sc.normal_load_per_pad
    c = sc.friction_slope(v)
    mu = (sc.law_force(v) - c * v) / load
    return replace(sc, friction=FrictionSpec(law="linear", mu0=mu, c=c))


def log_twin(sc):
    """The scene with the log law at the rate_state law's steady state: b = A - B, v_c = v_ss (its per-step force
    written through pymunk.batch as well, without a state)."""
    from engine_sim.laws.log import LogSpec

    law = sc.law_part
    return replace(sc, friction=LogSpec(mu0=sc.friction.mu0, c=0.0, b=sc.friction.A - sc.friction.B,
                                        v_c=law.steady_v_c()))


def loop_cost(scenes, n_steps: int, repeat: int):
    """Best-of-``repeat`` microseconds per step of the project's loop on each scene, interleaved."""
    built = []
    for sc in scenes:
        s = Scene(sc)
        warm_up(s, -(-2000 // s.n_sub))
        n_out = max(1, n_steps // s.n_sub)
        built.append((Loop(s, Recorder(s, n_out * repeat + 1)), n_out))
    best = [float("inf")] * len(built)
    for _ in range(repeat):
        for j, (loop, n_out) in enumerate(built):
            loop.k = 0  # every turn starts with a maintenance, as a chunk of the run's loop does
            t0 = time.perf_counter()
            loop.run(n_out)
            best[j] = min(best[j], (time.perf_counter() - t0) / (n_out * loop.scene.n_sub) * 1e6)
    return best


def test_rate_state_against_linear_law(benchmark, ratio, smoke):
    """The harness's entry: one output step of pads_rate_state's loop timed by the harness, and in the same run its
    cost per step over its linear and log twins' (``loop_cost``, interleaved; 400 steps best of 1 at smoke size,
    20000 best of 3 at full size)."""
    sc = load_scenario("pads_rate_state")
    rs_us, lin_us, log_us = loop_cost([sc, linear_twin(sc), log_twin(sc)], 400 if smoke else 20_000,
                                      1 if smoke else 3)
    ratio("rate_state / linear law, loop per step", rs_us / lin_us)
    ratio("rate_state / log law, loop per step", rs_us / log_us)
    rounds = 3 if smoke else 20
    scene = Scene(sc)
    warm_up(scene, -(-200 // scene.n_sub))
    loop = Loop(scene, Recorder(scene, rounds + 2))
    benchmark.pedantic(loop.run, args=(1,), rounds=rounds, warmup_rounds=1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--steps", type=int, default=20_000)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    sc = load_scenario("pads_rate_state")
    lin, log = linear_twin(sc), log_twin(sc)
    load0 = os.getloadavg()
    rs_us, lin_us, log_us = loop_cost([sc, lin, log], a.steps, a.repeat)
    load1 = os.getloadavg()
    print(f"pads_rate_state (N = {sc.pads.N}, dt = {sc.run.dt:g} s), {a.steps} steps x best of {a.repeat}")
    print(f"rate_state law: {rs_us:.1f} us/step; linear law (mu0 = {lin.friction.mu0:.4g}, c = {lin.friction.c:.4g} N s/m): "
          f"{lin_us:.1f} us/step; ratio {rs_us / lin_us:.2f}")
    print(f"log law at the same steady state (per-step forces through pymunk.batch, no state): {log_us:.1f} us/step; "
          f"rate_state / log {rs_us / log_us:.2f}")
    print(f"load average (1, 5, 15 min) before {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}, after {load1[0]:.2f} "
          f"{load1[1]:.2f} {load1[2]:.2f} (2 cores)")


if __name__ == "__main__":
    main()
