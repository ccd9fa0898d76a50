"""Model II's closed form, eq. (B2): the parallel kernel against the direct per-frequency quadrature, one run.

    python -m benchmarks.bench_wear_spectrum [--smoke]
    python -m pytest benchmarks/bench_wear_spectrum.py   # the harness's entry (test_b2_kernel_against_quadrature)

The frequencies of a 400 s record at 1 kHz (2e5 periodogram ordinates; 2e3 with --smoke), independently drawn
mean times (96 x 96 quadrature nodes); the direct sum is timed on a tenth of them and scaled. Prints both times
and their ratio, and the largest relative difference between the two.
"""
import argparse
import time

import numpy as np

from reduced_models.wear_particle import WearParticleParams, theory_force_spectrum
from tests.reduced_models.test_wear_particle_spectrum import reference_b2


def _cpu(fn, *a) -> float:
    """This process's CPU time for one call."""
    t0 = time.process_time()
    fn(*a)
    return time.process_time() - t0


def _frequencies(n: int) -> np.ndarray:
    """The periodogram frequencies (rad/s) of a record of 2 n samples at 1 kHz."""
    return 2 * np.pi * np.arange(1, n + 1) / (2 * n * 1e-3)


def test_b2_kernel_against_quadrature(benchmark, ratio, smoke):
    """The harness's entry: the kernel at a record's frequencies (2e3 at smoke size, 2e4 at full size) timed by the
    harness, and in the same run the direct quadrature's time on a tenth of them, scaled, over the kernel's (the
    speed-up the performance page quotes); both give the same spectrum."""
    w = _frequencies(2_000 if smoke else 20_000)
    P = WearParticleParams()
    theory_force_spectrum(P, w[:10])  # compile (or load the cache)
    fast = benchmark(theory_force_spectrum, P, w)
    t_fast = min(_cpu(theory_force_spectrum, P, w) for _ in range(5))
    sub = w[::10]
    t0 = time.process_time()
    slow = reference_b2(P, sub)
    t_slow = (time.process_time() - t0) * len(w) / len(sub)
    # the same double sum over 96 x 96 nodes in another order: equal to rounding (1.3e-14 measured at 2e5
    # frequencies); 1e-12 leaves room for the summation order's growth with the node count, nothing for an error
    assert np.max(np.abs(fast[::10] / slow - 1)) < 1e-12
    ratio("direct quadrature / kernel (CPU)", t_slow / max(t_fast, 1e-9))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    n = 2_000 if a.smoke else 200_000
    w = _frequencies(n)
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
