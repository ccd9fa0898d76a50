"""Models II and III: wall time (targets: model III with 1e7 grid steps <= 1 s; model II with
1000 particles and 1e6 output samples <= 5 s, on the 2-core machine).

    python -m benchmarks.bench_models_2_3 [--smoke]
    python -m pytest benchmarks/bench_models_2_3.py     # the harness's entries (model II, model III)

Best and median of 3 after a warm-up; model III's first calls also pay the kernel's zeroing of fresh
80 MB arrays, which the median shows.
"""
import argparse
import time

import numpy as np

from reduced_models import asperity_force, wear_particle


def _time(fn, repeat):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return min(ts), float(np.median(ts))


def test_model_III(benchmark, smoke):
    """The harness's entry: model III, 10^5 grid steps (10^4 under --bench-smoke), 300 asperities."""
    p3 = asperity_force.AsperityForceParams.reference(300)
    asperity_force.simulate(p3, 1000 * p3.dt, seed=0)  # warm-up
    n3 = 10**4 if smoke else 10**5
    benchmark(asperity_force.simulate, p3, n3 * p3.dt, seed=0)


def test_model_II(benchmark, smoke):
    """The harness's entry: model II, 1000 particles, 10^5 samples at 1 kHz (10^4 under --bench-smoke)."""
    p2 = wear_particle.WearParticleParams.one_over_f(1000)
    wear_particle.simulate(p2, 1.0, 1e-3, seed=0)  # warm-up
    n2 = 10**4 if smoke else 10**5
    benchmark(wear_particle.simulate, p2, n2 * 1e-3, 1e-3, seed=0)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    scale = 0.01 if a.smoke else 1.0
    p3 = asperity_force.AsperityForceParams.reference(300)
    n3 = int(1e7 * scale)
    asperity_force.simulate(p3, 1000 * p3.dt, seed=0)
    b3, m3 = _time(lambda: asperity_force.simulate(p3, n3 * p3.dt, seed=0), 3)
    p2 = wear_particle.WearParticleParams.one_over_f(1000)
    n2 = int(1e6 * scale)
    wear_particle.simulate(p2, 1.0, 1e-3, seed=0)
    b2, m2 = _time(lambda: wear_particle.simulate(p2, n2 * 1e-3, 1e-3, seed=0), 3)
    print(f"model III, {n3:.0e} grid steps: best {b3:.2f} s, median {m3:.2f} s (target 1 s at 1e7)")
    print(f"model II, 1000 particles (tau 10 ms-100 s), {n2:.0e} samples at 1 kHz: best {b2:.2f} s, "
          f"median {m2:.2f} s (target 5 s at 1e6)")


if __name__ == "__main__":
    main()
