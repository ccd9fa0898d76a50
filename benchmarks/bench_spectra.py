"""Spectrum + power-law fit of 10^7 samples (target: <= 2 s on the 2-core machine).

    python -m benchmarks.bench_spectra [--samples N] [--repeat R]
    python -m pytest benchmarks/bench_spectra.py      # the harness's entry (test_spectrum_and_fit)

Reports the best of R runs after one warm-up (the first scipy.fft call pays ~1 s of setup).
"""
import argparse
import time

import numpy as np

from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum


def run(n: int, repeat: int) -> dict:
    rng = np.random.default_rng(0)
    dt = 1e-3
    t = np.arange(n) * dt
    x = 5e-4 * t + np.cumsum(np.cumsum(rng.standard_normal(n))) * 1e-12
    displacement_spectrum(t[: 1 << 16], x[: 1 << 16])  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        spec = displacement_spectrum(t, x)
        fit = fit_power_law(spec)
        times.append(time.perf_counter() - t0)
    return {"samples": n, "best_s": min(times), "median_s": float(np.median(times)), "gamma": fit.gamma,
            "gamma_err": fit.gamma_err, "prewhiten_order": spec.provenance["prewhiten_order"]}


def record(n: int):
    """A displacement record of ``n`` samples at 1 kHz: drift plus an integrated random walk (gamma = 4)."""
    rng = np.random.default_rng(0)
    t = np.arange(n) * 1e-3
    return t, 5e-4 * t + np.cumsum(np.cumsum(rng.standard_normal(n))) * 1e-12


def test_spectrum_and_fit(benchmark, smoke):
    """The harness's entry: spectrum and power-law fit of 10^6 samples (10^5 under --bench-smoke)."""
    t, x = record(10**5 if smoke else 10**6)
    displacement_spectrum(t[: 1 << 12], x[: 1 << 12])  # warm-up (the first scipy.fft call's setup)
    fit = benchmark(lambda: fit_power_law(displacement_spectrum(t, x)))
    assert abs(fit.gamma - 4.0) < 0.5  # the random walk integrated twice: omega^-4 (a wide check: only that it ran)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--samples", type=int, default=10**7)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    r = run(a.samples, a.repeat)
    print(f"spectrum + fit of {r['samples']:.0e} samples: best {r['best_s']:.2f} s, median {r['median_s']:.2f} s "
          f"(gamma = {r['gamma']:.3f} +- {r['gamma_err']:.3f}, pre-whitening order {r['prewhiten_order']})")
    return r


if __name__ == "__main__":
    main()
