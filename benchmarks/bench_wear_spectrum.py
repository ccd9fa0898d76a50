"""Model II's closed form, eq. (B2): the parallel kernel against the direct per-frequency quadrature, one run.

    python -m benchmarks.bench_wear_spectrum [--smoke]

The frequencies of a 400 s record at 1 kHz (2e5 periodogram ordinates; 2e3 with --smoke), independently drawn
mean times (96 x 96 quadrature nodes); the direct sum is timed on a tenth of them and scaled. Prints both times
and their ratio, and the largest relative difference between the two.
"""
import argparse
import time

import numpy as np

from reduced_models.wear_particle import WearParticleParams, theory_force_spectrum
from tests.reduced_models.test_wear_particle_spectrum import reference_b2


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    n = 2_000 if a.smoke else 200_000
    w = 2 * np.pi * np.arange(1, n + 1) / (2 * n * 1e-3)
    P = WearParticleParams()
    theory_force_spectrum(P, w[:10])  # compile (or load the cache)
    t0 = time.perf_counter()
    fast = theory_force_spectrum(P, w)
    t_fast = time.perf_counter() - t0
    sub = w[:: 10]
    t0 = time.perf_counter()
    slow = reference_b2(P, sub)
    t_slow = (time.perf_counter() - t0) * len(w) / len(sub)
    dev = float(np.max(np.abs(fast[::10] / slow - 1)))
    print(f"eq. (B2) at {n} frequencies, {96 * 96} node pairs: kernel {t_fast:.3f} s, direct loop {t_slow:.2f} s "
          f"(scaled from {len(sub)}): ratio {t_slow / t_fast:.0f}x; largest relative difference {dev:.1e}")


if __name__ == "__main__":
    main()
