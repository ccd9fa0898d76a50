"""Model I: exact modal propagation against an explicit integrator, and a work-precision table.

    python -m benchmarks.bench_spring_block [--explicit-seconds S] [--smoke]
    python -m pytest benchmarks/bench_spring_block.py   # the harness's entry (test_exact_against_explicit)

The explicit baseline (symplectic Euler, numba) lives only here. At the reference stiffness
(m eta1 = 333 N s/m on m = 1e-5 kg, i.e. a rate of 3.3e7 1/s) it is stable only for dt < 2/3.3e7 = 6e-8 s.
It uses the same renewal rule and random numbers as the exact solver (renewals located to within one
step), so its trajectory can be compared with the exact one for the same seed: that isolates the
integrator's error from sampling noise. Errors:

- ``traj_err``: max |x - x_exact| over the run, relative to the rms of zeta;
- ``spec_err``: band-averaged |ln(C_x / C_x(A10))| over 8 log bands in 1-1000 rad/s (or up to omega_N/3);
  for 900 s runs this is sampling noise, the floor any solver reaches.
"""
from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from compare.analysis.spectra import band_average, displacement_spectrum
from reduced_models.spring_block import SpringBlockParams, renewal_block, simulate, theory_spectrum


@numba.njit(cache=True)
def _explicit_run(p_arr, dt, n_sub, n_out, pos, idx, val, forces, x_out):
    """Symplectic Euler on (A1)-(A2) in deviation coordinates; k1 coupling with free ends."""
    N, M, m, k0, k1, eta0, eta1, v = int(p_arr[0]), p_arr[1], p_arr[2], p_arr[3], p_arr[4], p_arr[5], p_arr[6], p_arr[7]
    z = 0.0
    dz = 0.0
    zi = np.zeros(N)
    dzi = np.zeros(N)
    ptr = 0
    t = 0.0
    for k in range(n_out):
        x_out[k] = v * t + z
        for _ in range(n_sub):
            # renewals crossed during the last step
            while ptr < pos.shape[0] and v * t + z >= pos[ptr]:
                forces[idx[ptr]] = val[ptr]
                ptr += 1
            fb = 0.0
            for i in range(N):
                rel = zi[i] - z
                drel = dzi[i] - dz
                fb += k0 * rel + m * eta0 * drel
                lat = 0.0
                if i > 0:
                    lat += k1 * (zi[i] - zi[i - 1])
                if i < N - 1:
                    lat += k1 * (zi[i] - zi[i + 1])
                acc = (-k0 * rel - m * eta0 * drel - m * eta1 * dzi[i] - forces[i] - lat) / m
                dzi[i] += acc * dt
            dz += fb / M * dt
            for i in range(N):
                zi[i] += dzi[i] * dt
            z += dz * dt
            t += dt
    return ptr


def explicit_simulate(p: SpringBlockParams, duration: float, dt_out: float, dt: float, seed: int) -> np.ndarray:
    """The baseline: same random numbers as reduced_models.spring_block.simulate (first distance block)."""
    rng = np.random.default_rng(seed)
    forces = p.alpha * p.f_kin * (rng.random(p.N) - 0.5)
    pos, idx, val, boundary = renewal_block(p, rng, 0)
    if p.v * duration * 1.2 > boundary:
        raise ValueError("baseline run longer than one pre-generated distance block")
    n_out = int(round(duration / dt_out))
    n_sub = int(round(dt_out / dt))
    x = np.empty(n_out)
    arr = np.array([p.N, p.M, p.m, p.k0, p.k1, p.eta0, p.eta1, p.v])
    _explicit_run(arr, dt_out / n_sub, n_sub, n_out, pos, idx, val, forces, x)
    return x


def spectral_error(p, t, x) -> float:
    spec = displacement_spectrum(t, x)
    top = min(1000.0, np.pi / (t[1] - t[0]) / 3)
    edges = np.logspace(np.log10(max(1.0, 4 * spec.omega_min)), np.log10(top), 9)
    r = band_average(spec, edges) / band_average(spec, edges, theory_spectrum(p, spec.omega))
    return float(np.mean(np.abs(np.log(r))))


def timed(fn, *a, repeat=3, **k):
    best = np.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*a, **k)
        best = min(best, time.perf_counter() - t0)
    return best, out


def _cpu(fn, *a, **k) -> float:
    """CPU time of this process for one call (what a loaded machine distorts least)."""
    c0 = time.process_time()
    fn(*a, **k)
    return time.process_time() - c0


def test_exact_against_explicit(benchmark, ratio, smoke):
    """The harness's entry: the exact modal solver on the reference case (3 s at 1 kHz, 30 s at full size) timed
    by the harness, and in the same run the explicit integrator's cost per simulated second over the exact one's
    (the speed-up the docs quote)."""
    p = SpringBlockParams.reference()
    T = 3.0 if smoke else 30.0
    simulate(p, 1.0, 1e-3, seed=0)  # JIT warm-up
    explicit_simulate(p, 1e-3, 1e-3, 5e-8, 0)
    tr = benchmark(simulate, p, T, 1e-3, seed=0)
    assert len(tr.x) == round(T / 1e-3)
    T_exp = 0.01 if smoke else 0.05
    w_exp, _ = timed(explicit_simulate, p, T_exp, 1e-3, 5e-8, 0, repeat=1)
    w_exact, _ = timed(simulate, p, T, 1e-3, seed=0, repeat=3)
    ratio("explicit / exact, per simulated s", (w_exp / T_exp) / (w_exact / T))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--explicit-seconds", type=float, default=2.0, help="simulated seconds for the baseline")
    ap.add_argument("--smoke", action="store_true", help="tiny run for CI")
    a = ap.parse_args(argv)
    p = SpringBlockParams.reference()
    T_exp = 0.05 if a.smoke else a.explicit_seconds
    T_ref = 30.0 if a.smoke else 900.0
    simulate(p, 1.0, 1e-3, seed=0)  # JIT warm-up
    explicit_simulate(p, 1e-3, 1e-3, 5e-8, 0)

    wall, tr = timed(simulate, p, T_ref, 1e-3, seed=0, repeat=1 if a.smoke else 5)
    cpu = min(_cpu(simulate, p, T_ref, 1e-3, seed=0) for _ in range(1 if a.smoke else 5))
    print(f"exact modal solver (2-DOF block + sum of miniblocks), reference case, {T_ref:g} s at 1 kHz: {wall:.3f} s wall "
          f"({wall / T_ref * 1e3:.3f} ms per simulated s), {cpu:.3f} s CPU (best of 5 each)")
    simulate(p, 1.0, 1e-3, seed=0, contacts=[0])  # warm-up of the full system's path
    wall_full, full = timed(simulate, p, T_ref, 1e-3, seed=0, contacts=[0], repeat=1 if a.smoke else 5)
    print(f"full (N+1)-body system (what the solver propagated before; here with one miniblock's output): "
          f"{wall_full:.3f} s wall, {wall_full / wall:.1f}x the reduced run; max |x_reduced - x_full| = "
          f"{np.max(np.abs(tr.x - full.x)):.2g} m (zeta_rms {np.std(tr.x - p.v * tr.t):.2g} m), renewal times "
          f"within {np.max(np.abs(tr.events['times'] - full.events['times'])):.2g} s")

    w_exp, x_exp = timed(explicit_simulate, p, T_exp, 1e-3, 5e-8, 0, repeat=1)
    per_s_exp = w_exp / T_exp
    ref = simulate(p, T_exp, 1e-3, seed=0)
    print(f"explicit symplectic Euler, dt = 5e-8 s: {per_s_exp:.2f} s wall per simulated s "
          f"(extrapolated to {T_ref:g} s: {per_s_exp * T_ref:.0f} s)")
    print(f"speed ratio exact / explicit at equal simulated time: {per_s_exp * T_ref / wall:.0f}x")

    rows = []
    zrms = np.std(ref.x - p.v * ref.t)
    for dt in (5e-8, 2.5e-8):
        w, x = timed(explicit_simulate, p, T_exp, 1e-3, dt, 0, repeat=1)
        err = np.max(np.abs(x - ref.x)) / zrms
        rows.append(("explicit symplectic Euler", f"dt = {dt:g} s", w / T_exp, err, np.nan))
    for dt_out in ((1e-3,) if a.smoke else (1e-2, 1e-3, 1e-4)):
        w, tr = timed(simulate, p, T_ref, dt_out, seed=0, repeat=1)
        short = simulate(p, T_exp, dt_out, seed=0)
        step = int(round(dt_out / 1e-3)) if dt_out >= 1e-3 else 1
        fine = ref.x[::step] if dt_out >= 1e-3 else short.x[:: int(round(1e-3 / dt_out))]
        coarse = short.x if dt_out >= 1e-3 else ref.x
        n = min(len(fine), len(coarse))
        err = np.max(np.abs(fine[:n] - coarse[:n])) / zrms
        rows.append(("exact modal", f"dt_out = {dt_out:g} s", w / T_ref, err, spectral_error(p, tr.t, tr.x)))
    print()
    print("| solver | setting | wall s per simulated s | traj_err (vs exact, same seed) | spec_err vs (A10), 900 s |")
    print("|---|---|---|---|---|")
    for name, setting, cost, terr, serr in rows:
        s = "-" if np.isnan(serr) else f"{serr:.3f}"
        print(f"| {name} | {setting} | {cost:.3g} | {terr:.2g} | {s} |")


if __name__ == "__main__":
    main()
