"""Identification of a 400 s displacement record at 1 kHz: wall time of `compare.analysis.identify.identify` over
every registered model's family (target: 15 s on 2 cores).

    python -m benchmarks.bench_identify [--smoke]
    python -m pytest benchmarks/bench_identify.py   # the harness's entry (test_identify)

The record is model I's reference case with a white sensor floor of 1e-24 m^2 s; --smoke uses 40 s. Prints the
wall and CPU time of one call after a warm-up on a short record (numba's kernels compiled or loaded), the ranking's
head and the load average.
"""
import argparse
import math
import os
import time

import numpy as np

import reduced_models as rm
from compare.analysis.identify import identify


def _record(T: float, dt: float):
    """Model I's reference case, T s at step dt, with the white sensor floor; (x, drive speed)."""
    p = rm.spring_block.SpringBlockParams.reference()
    tr = rm.spring_block.simulate(p, T, dt, seed=0)
    return tr.x + np.random.default_rng(1).normal(0.0, math.sqrt(2 * math.pi * 1e-24 / dt), len(tr.x)), p.v


def test_identify(benchmark, smoke):
    """The harness's entry: one identification over every registered family (a 10 s record at smoke size, the
    400 s of the target at full size), after a warm-up on a short record; one round at smoke size, three at full."""
    dt = 1e-3
    x, v = _record(10.0 if smoke else 400.0, dt)
    identify(x[:4096], dt, v)  # warm-up: numba's kernels compiled or loaded
    ranking = benchmark.pedantic(identify, args=(x, dt, v), rounds=1 if smoke else 3, iterations=1)
    assert ranking and ranking[0].model in rm.MODELS


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    T, dt = (40.0 if a.smoke else 400.0), 1e-3
    x, v = _record(T, dt)
    identify(x[:8192], dt, v)  # warm-up
    w0, c0 = time.perf_counter(), time.process_time()
    ranking = identify(x, dt, v)
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"identify, {T:g} s at 1 kHz ({len(x)} samples), {len(ranking)} models: wall {wall:.2f} s, CPU {cpu:.2f} s "
          f"(load average {os.getloadavg()[0]:.1f}); best {ranking[0].model} ({ranking[0].verdict})")


if __name__ == "__main__":
    main()
