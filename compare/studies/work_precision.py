"""Speed against error for the engine scene: wall time per simulated second against the error of C_x
relative to a converged run with the same seed (same substrate, same forces), with the Pareto front.

    python -m compare.studies.work_precision [--duration S] [--smoke] [--out DIR]

Error = mean over 8 log bands in 2-1000 rad/s of |ln C_x / C_x(reference)|; the reference uses dt = 2.5e-5 s
and 20 solver iterations. The reduced models' work-precision table is in bench_spring_block (model I is
exact, so its error is sampling noise at every output step).
"""
import argparse
from pathlib import Path

from compare.analysis.work_precision import engine_work_precision
from engine_sim import load_scenario, shipped_scenarios

SETTINGS = [(1e-4, 2), (1e-4, 5), (1e-4, 10), (5e-5, 2), (5e-5, 10), (2.5e-5, 2)]


def table(rows) -> str:
    lines = ["| dt (s) | iterations | wall s per simulated s | C_x error vs reference | Pareto front |",
             "|---|---|---|---|---|"]
    for r in rows:
        mark = "reference" if r["pareto"] is None else ("yes" if r["pareto"] else "")
        d = " (default)" if r["default"] else ""
        lines.append(f"| {r['dt']:g}{d} | {r['iterations']} | {r['cost']:.3f} | {r['error']:.4f} | {mark} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--duration", type=float, default=20.0)
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--out", default=None, help="folder for work_precision.md and .png")
    a = ap.parse_args(argv)
    base = load_scenario(shipped_scenarios()["pads_friction_patches"])
    rows = engine_work_precision(base, SETTINGS[:1] if a.smoke else SETTINGS, 1.0 if a.smoke else a.duration)
    print(table(rows))
    if a.out:
        from compare.report import plots
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "work_precision.md").write_text(table(rows) + "\n")
        plots.save_figure(plots.work_precision_figure(rows), out / "work_precision.png")


if __name__ == "__main__":
    main()
