"""Speed against error for the engine scene: wall time per simulated second against the error of C_x
relative to a converged run with the same seed (same substrate, same forces), with the Pareto front.

    python -m benchmarks.work_precision [--duration S] [--smoke] [--out DIR]

Error = mean over 8 log bands in 2-1000 rad/s of |ln C_x / C_x(reference)|; the reference uses dt = 2.5e-5 s
and 20 solver iterations. The reduced models' work-precision table is in bench_spring_block (model I is
exact, so its error is sampling noise at every output step).
"""
import argparse
import time
from pathlib import Path

import numpy as np

import engine_sim
from compare.spectra import band_average, displacement_spectrum
from engine_sim import load_scenario, shipped_scenarios


def pareto(points):
    """Indices of points not dominated in (cost, error), both smaller-is-better."""
    keep = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            keep.append(i)
    return keep


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--duration", type=float, default=20.0)
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--out", default=None, help="folder for work_precision.png and .md")
    a = ap.parse_args(argv)
    T = 1.0 if a.smoke else a.duration
    base = load_scenario(shipped_scenarios()["pads_friction_patches"])
    d = ("default", base.run.dt, base.run.iterations)
    settings = [("reference", 2.5e-5, 20)] + ([d] if a.smoke else
                [d, ("", 1e-4, 5), ("", 1e-4, 10), ("", 5e-5, 2), ("", 5e-5, 10), ("", 2.5e-5, 2)])
    rows = []
    ref = None
    for label, dt, it in settings:
        sc = base.with_run(dt=dt, dt_out=1e-3, iterations=it, duration=T, warmup=0.5)
        t0 = time.perf_counter()
        tr = engine_sim.run(sc, seed=0)
        wall = time.perf_counter() - t0
        spec = displacement_spectrum(tr.t, tr.x, nperseg=min(2**12, len(tr.t) // 2))
        if ref is None:
            ref = spec
            err = 0.0
        else:
            edges = np.logspace(np.log10(max(2.0, 4 * spec.omega_min)), 3, 9)
            err = float(np.mean(np.abs(np.log(band_average(spec, edges) / band_average(ref, edges)))))
        rows.append((label, dt, it, wall / T, err))
    pts = [(r[3], r[4]) for r in rows[1:]]
    front = {i + 1 for i in pareto(pts)}
    lines = ["| setting | dt (s) | iterations | wall s per simulated s | C_x error vs reference | Pareto front |",
             "|---|---|---|---|---|---|"]
    for i, (label, dt, it, cost, err) in enumerate(rows):
        mark = "reference" if i == 0 else ("yes" if i in front else "")
        lines.append(f"| {label} | {dt:g} | {it} | {cost:.3f} | {err:.4f} | {mark} |")
    print("\n".join(lines))
    if a.out:
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "work_precision.md").write_text("\n".join(lines) + "\n")
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5.5, 4), dpi=110)
        for i, (label, dt, it, cost, err) in enumerate(rows[1:], start=1):
            ax.plot(cost, max(err, 1e-4), "o", color="tab:red" if i in front else "0.5")
            ax.annotate(f"dt={dt:g}, it={it}{' (default)' if label == 'default' else ''}", (cost, max(err, 1e-4)), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall s per simulated s")
        ax.set_ylabel("band-averaged |ln C_x / C_x,ref|")
        ax.set_title("Engine work-precision (red: Pareto front)", fontsize=9)
        fig.tight_layout()
        fig.savefig(out / "work_precision.png")


if __name__ == "__main__":
    main()
