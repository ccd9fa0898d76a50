"""Model Ib (multiscale): speed of the exact two-level solver and a work-precision table.

    python -m benchmarks.bench_multiscale [--smoke]
    python -m pytest benchmarks/bench_multiscale.py   # the harness's entry (test_model_Ib_against_model_I)

The reference case (13.5 million renewals in 900 s) at dt_out = 1 ms is timed best of 3 (wall and CPU time of
this process, which is what a loaded machine distorts least), beside model I's reduced solver in the same
run. No explicit baseline: the micro friction rate eta3 = 2e10 1/s makes an explicit integrator stable only
for dt < 2 / eta3 = 1e-10 s, 9e12 steps for 900 s.

Work-precision: the solver is exact between renewals; what it trades is the tolerance to which each
renewal crossing is located (``crossing_tol``, a fraction of a2) and the output step. Errors:

- ``traj_err``: max |x - x_ref| over a 30 s run against crossing_tol = 1e-12 (rounding-limited), same seed,
  relative to the rms of zeta;
- ``spec_err``: band-averaged |ln(C_x / C_x(theory))| over 8 log bands from 1 rad/s to omega_N / 3, 900 s
  (10 s in smoke mode): sampling noise, the floor any solver reaches.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from compare.analysis.spectra import band_average, displacement_spectrum
from reduced_models import multiscale as ms
from reduced_models import spring_block as m1


def timed(fn, *a, repeat=3, **k):
    """Best of ``repeat``: (wall s, CPU s of this process, result)."""
    best_w, best_c, out = np.inf, np.inf, None
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        out = fn(*a, **k)
        best_w, best_c = min(best_w, time.perf_counter() - w0), min(best_c, time.process_time() - c0)
    return best_w, best_c, out


def spectral_error(p, t, x) -> float:
    spec = displacement_spectrum(t, x)
    top = np.pi / (t[1] - t[0]) / 3
    edges = np.geomspace(max(1.0, 4 * spec.omega_min), top, 9)
    r = band_average(spec, edges) / band_average(spec, edges, ms.theory_spectrum(p, spec.omega))
    return float(np.mean(np.abs(np.log(r))))


def test_model_Ib_against_model_I(benchmark, ratio, smoke):
    """The harness's entry: model Ib's exact solver on the reference case (1 s at 1 kHz at smoke size, 30 s at full
    size) timed by the harness, and in the same run its CPU time over model I's reduced solver on the same block
    (best of 3 each), with the CPU time per renewal."""
    p = ms.MultiscaleParams.reference()
    T = 1.0 if smoke else 30.0
    ms.simulate(p, 0.5, 1e-3, seed=0)  # JIT warm-up (or cache load)
    m1.simulate(p.macro, 0.5, 1e-3, seed=0)
    tr = benchmark(ms.simulate, p, T, 1e-3, seed=0)
    assert len(tr.x) == round(T / 1e-3)
    _, c, tr = timed(ms.simulate, p, T, 1e-3, seed=0)
    _, c1, _ = timed(m1.simulate, p.macro, T, 1e-3, seed=0)
    ratio("model Ib / model I (CPU)", c / c1)
    ratio("CPU ns per renewal", c / (tr.metadata["n_micro_renewals"] + tr.metadata["n_renewals"]) * 1e9)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--smoke", action="store_true", help="tiny run for CI (< 30 s)")
    a = ap.parse_args(argv)
    p = ms.MultiscaleParams.reference()
    T = 10.0 if a.smoke else 900.0
    T_err = 2.0 if a.smoke else 30.0
    ms.simulate(p, 0.5, 1e-3, seed=0)  # JIT warm-up (or cache load)
    m1.simulate(p.macro, 0.5, 1e-3, seed=0)
    rep = 1 if a.smoke else 3
    w, c, tr = timed(ms.simulate, p, T, 1e-3, seed=0, repeat=rep)
    n_ren = tr.metadata["n_micro_renewals"] + tr.metadata["n_renewals"]
    w1, c1, _ = timed(m1.simulate, p.macro, T, 1e-3, seed=0, repeat=rep)
    print(f"model Ib, reference case, {T:g} s at 1 kHz: {w:.2f} s wall, {c:.2f} s CPU (best of {rep}); "
          f"{n_ren / 1e6:.2f} M renewals, {c / n_ren * 1e9:.0f} ns CPU per renewal, "
          f"{tr.metadata['n_evaluations'] / n_ren:.2f} evaluations of the exact solution per renewal")
    print(f"model I (reduced 2-DOF solver), same run: {w1:.3f} s wall, {c1:.3f} s CPU; Ib / I = {c / c1:.1f}x CPU "
          f"for {n_ren / tr.metadata['n_renewals']:.0f}x the renewals")

    ref = ms.simulate(p, T_err, 1e-3, seed=1, crossing_tol=1e-12)
    zrms = np.std(ref.x - p.v * ref.t)
    rows = []
    for tol in (1e-3, 1e-6, 1e-9):
        wt, ct, run = timed(ms.simulate, p, T_err, 1e-3, seed=1, crossing_tol=tol, repeat=1)
        err = np.max(np.abs(run.x - ref.x)) / zrms
        rows.append((f"crossing_tol = {tol:g} a2" + (" (default)" if tol == 1e-6 else ""), ct / T_err, err,
                     run.metadata["n_evaluations"] / (run.metadata["n_micro_renewals"] + run.metadata["n_renewals"]),
                     np.nan))
    for dt_out in ((1e-3,) if a.smoke else (1e-2, 1e-3, 1e-4)):
        Tw = T if dt_out >= 1e-3 else T / 3
        wt, ct, run = timed(ms.simulate, p, Tw, dt_out, seed=0, repeat=1)
        short = ms.simulate(p, T_err, dt_out, seed=1)
        step = max(1, int(round(dt_out / 1e-3)))
        fine, coarse = (ref.x[::step], short.x) if dt_out >= 1e-3 else (short.x[:: int(round(1e-3 / dt_out))], ref.x)
        n = min(len(fine), len(coarse))
        err = np.max(np.abs(fine[:n] - coarse[:n])) / zrms
        rows.append((f"dt_out = {dt_out:g} s", ct / Tw, err,
                     run.metadata["n_evaluations"] / (run.metadata["n_micro_renewals"] + run.metadata["n_renewals"]),
                     spectral_error(p, run.t, run.x)))
    print()
    print(f"| setting | CPU s per simulated s | traj_err (vs crossing_tol 1e-12, same seed) | evaluations per renewal "
          f"| spec_err vs theory, {T:g} s (dt_out = 0.1 ms: {T / 3:g} s) |")
    print("|---|---|---|---|---|")
    for name, cost, terr, evals, serr in rows:
        s = "-" if np.isnan(serr) else f"{serr:.3f}"
        print(f"| {name} | {cost:.3g} | {terr:.2g} | {evals:.2f} | {s} |")


if __name__ == "__main__":
    main()
