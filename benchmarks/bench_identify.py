"""Identification of a 400 s displacement record at 1 kHz: wall time of `compare.analysis.identify.identify` over
every registered model's family (target: 15 s on 2 cores).

    python -m benchmarks.bench_identify [--smoke]
    python -m pytest benchmarks/bench_identify.py [--bench-smoke]    # the harness's entry

The record is model I's reference case with a white sensor floor of 1e-24 m^2 s; --smoke uses 40 s, --bench-smoke
10 s (a record long enough for every family to be ranked).
The script prints the wall and CPU time of one call after a warm-up on a short record (numba's kernels compiled or
loaded), the ranking's head and the load average; the harness's entry times the call (wall clock, pytest-benchmark's
default timer) and stores the CPU/wall ratio and the load average with the run.
"""
import argparse
import math
import os
import time

import numpy as np

import reduced_models as rm
from compare.analysis.identify import identify


def record(duration: float, dt: float = 1e-3):
    """Model I's reference case over ``duration`` (s) at step ``dt`` (s) with the white floor, and its speed (m/s)."""
    p = rm.spring_block.SpringBlockParams.reference()
    tr = rm.spring_block.simulate(p, duration, dt, seed=0)
    return tr.x + np.random.default_rng(1).normal(0.0, math.sqrt(2 * math.pi * 1e-24 / dt), len(tr.x)), p.v


def test_identify_400s(benchmark, smoke, ratio):
    """The harness's entry: identification of 400 s at 1 kHz (10 s under --bench-smoke), every registered family;
    one round at smoke size, three at full size."""
    dt = 1e-3
    x, v = record(10.0 if smoke else 400.0, dt)
    identify(x[:8192], dt, v)  # warm-up
    c0 = time.process_time()
    ranking = benchmark.pedantic(identify, args=(x, dt, v), rounds=1 if smoke else 3, iterations=1)
    ratio("cpu_over_wall", (time.process_time() - c0) / benchmark.stats.stats.total)
    benchmark.extra_info["load_average"] = os.getloadavg()[0]  # the machine's load: a wall time reads with it
    assert ranking[0].model == "model_I"  # only that it ran on the record it was given


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    T, dt = (40.0 if a.smoke else 400.0), 1e-3
    x, v = record(T, dt)
    identify(x[:8192], dt, v)  # warm-up
    w0, c0 = time.perf_counter(), time.process_time()
    ranking = identify(x, dt, v)
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"identify, {T:g} s at 1 kHz ({len(x)} samples), {len(ranking)} models: wall {wall:.2f} s, CPU {cpu:.2f} s "
          f"(load average {os.getloadavg()[0]:.1f}); best {ranking[0].model} ({ranking[0].verdict})")


if __name__ == "__main__":
    main()
