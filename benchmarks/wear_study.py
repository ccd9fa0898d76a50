"""Issue 17, item 3: the wear study's results as committed tables (Markdown + CSV + figure) from a sweep folder.

    frictionnoise sweep scenarios/sweeps/wear_study_quick.toml --workers 1 -o /tmp/wear_study_quick
    python -m benchmarks.wear_study /tmp/wear_study_quick --wall S --command "..." [--out benchmarks/results/wear_study_quick]

Reads the sweep's stored tasks (compare.sweep.load_results), computes the cells (compare.wear_study.cells) and writes
PREFIX.md (the command, the wall time, the cell table, the answer in numbers, the projected wall time of the full
study from the measured cost per simulated second), PREFIX.csv (one row per cell) and PREFIX.png (the figure).
"""
from __future__ import annotations

import argparse
import csv
import io
import json
from pathlib import Path

import numpy as np

from compare import plots
from compare.sweep import expand, load_results, load_sweep
from compare.wear_study import answer, cells, gamma_figure

_COLS = ("track", "size", "count", "n", "gamma", "gamma_err", "delta_gamma", "delta_gamma_err", "Cx_ratio_bands",
         "fit_CF_grains", "fit_CF_friction", "trapped_frac", "moving_frac", "covered_fraction", "F_g_mean",
         "B2_ratio_bands", "energy_resid_max", "energy_flagged", "left_interface", "wall_per_sim_s", "substeps")


def _cell_text(v):
    if isinstance(v, dict):
        return f"{v['exponent']:.2f} +- {v['err']:.2f}"
    if isinstance(v, list):
        return ", ".join(f"{x:.2f}" for x in v)
    if isinstance(v, float):
        return f"{v:.3g}"
    return "-" if v is None else str(v)


def projected_wall(results, full_spec) -> float:
    """Seconds on one core for every task of ``full_spec``: each task's simulated time (duration + warm-up) times the
    wall seconds per simulated second measured in the quick study's cell of the same count and size (the count's
    mean when the cell was not run; counts in between interpolated linearly)."""
    from compare.sweep import _build
    per = {}
    for r in results:
        w = r.get("wear")
        if w:
            per.setdefault(int(w["count"]), []).append(w["wall_per_sim_s"])
    counts = sorted(per)
    rate = np.array([np.mean(per[c]) for c in counts])
    total = 0.0
    for params, _ in expand(full_spec):
        sc, _ = _build(full_spec, params)
        total += (sc.run.duration + sc.run.warmup) * float(np.interp(sc.wear.count, counts, rate))
    return total


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder", help="the sweep's output folder")
    ap.add_argument("--wall", type=float, required=True, help="the sweep's measured wall time (s)")
    ap.add_argument("--command", required=True)
    ap.add_argument("--sweep", default="scenarios/sweeps/wear_study_quick.toml")
    ap.add_argument("--full", default="scenarios/sweeps/wear_study.toml")
    ap.add_argument("--out", default="benchmarks/results/wear_study_quick")
    a = ap.parse_args(argv)
    results = load_results(a.folder)
    rows = cells(results)
    spec, full = load_sweep(a.sweep), load_sweep(a.full)
    out = Path(a.out)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(_COLS)
    for r in rows:
        w.writerow([json.dumps(r.get(c)) if isinstance(r.get(c), (list, dict)) else r.get(c, "") for c in _COLS])
    out.with_suffix(".csv").write_text(buf.getvalue())
    plots.save_figure(gamma_figure(rows), out.with_suffix(".png"))
    proj = projected_wall(results, full)
    sim = sum("wear" in r for r in results)
    L = [f"# Wear study ({spec.name}): does debris steepen the spectrum? (issue 17, item 3)", "",
         f"Command: `{a.command}`  ", f"Wall time: {a.wall:.0f} s for {sim} tasks on one worker (2 shared cores).  ",
         f"Sweep: `{a.sweep}`: {spec.description.replace(chr(10), ' ')}", "",
         "gamma: Whittle fit of C_x over 3-30 v/a (v the law's speed, a = 1 mm: 15-150 rad/s), mean over seeds, +- the "
         "larger of the seed scatter's 95 % half-width (t quantile) and the per-seed 95 % intervals combined; rise: "
         "gamma minus the particle-free twin's (same track and seed), paired, with the same interval rule; C_x / twin: "
         "paired ratio per band (3 log bands over 15-150 rad/s), geometric mean over seeds; C_F exponents: C_F ~ "
         "omega^-exponent over the same band (grains' summed force on the pads; the pads' whole friction force); "
         "covered: grains' summed diameters over the tracks' grain windows (30 x 7 mm); B2: the grains' measured C_F over "
         "eq. (B2) built from the cell's own trap/move episodes, per band (1 = model II exact). Energy residuals above 1 % "
         "are flagged.", "",
         "| " + " | ".join(_COLS) + " |", "|" + "---|" * len(_COLS)]
    for r in rows:
        L.append("| " + " | ".join(_cell_text(r.get(c)) for c in _COLS) + " |")
    L += ["", "## Answer (computed)", "", answer(rows).replace("&plusmn;", "+-"), "",
          f"## Full study projection", "",
          f"`{a.full}`: {len(expand(full))} tasks; at the cost per simulated second measured here per particle count, "
          f"{proj:.0f} s on one core ({proj / 3600:.1f} h), about {proj / 7200:.1f} h on two free cores.", ""]
    out.with_suffix(".md").write_text("\n".join(L) + "\n")
    print(out.with_suffix(".md").read_text())


if __name__ == "__main__":
    main()
