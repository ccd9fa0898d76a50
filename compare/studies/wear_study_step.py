"""The wear study's one cell whose energy balance missed 1 %, rerun with a finer grain step.

    python -m compare.studies.wear_study_step [--duration 30] [--omega-dt 0.3] [--json study-results/wear_study_step.json]

The full study (`python -m compare.studies.wear_study` on the sweep wear_study.toml) flags 2 of 4 runs of the
cavity track with 100 broad grains (residuals 0.65-1.13 %) under the grain step rule (engine_sim.wear.grain_step: omega_g dt <= 0.6, 4 substeps). The
rule is set by the lightest grain squeezed by a pad's springs; there, grains of up to 200 um wedge in the 60 um deep
pits and carry most of a pad's load. This reruns the cell's four seeds with the rule's bound lowered (0.3: 7
substeps) and writes, per seed, the residual, the grains' mean force (trapped part beside it) and gamma at both
steps, the 4-substep values read from the study's task files. Two processes, one per pair of seeds.
"""
from __future__ import annotations

import argparse
import json
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from engine_sim.shipped import shipped_file

SWEEP = shipped_file("scenarios/sweeps/wear_study.toml")
CELL = {"wear.count": 100, "study.size": "broad", "study.track": "cavities"}


def _one(args) -> dict:
    seed, omega_dt, duration = args
    import engine_sim.wear as wear
    from compare.sweep import load_sweep, run_task

    wear.GRAIN_OMEGA_DT = omega_dt  # grain_step reads the bound when the scene is built
    r = run_task(load_sweep(SWEEP), dict(CELL, duration=duration), seed)
    if "error" in r:
        raise RuntimeError(r["error"])
    return _row(r)


def _row(r: dict) -> dict:
    w = r["wear"]
    return {"seed": r["seed"], "substeps": w["grain_step"]["substeps"], "energy_balance_rel": w["energy_balance_rel"],
            "F_g_mean": w["F_g_mean"], "F_g_trapped": w["F_g_trapped"], "gamma": r["fit"]["gamma"],
            "wall_s": r["wall_s"]}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--duration", type=float, default=30.0)
    ap.add_argument("--omega-dt", type=float, default=0.3)
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2, 3])
    ap.add_argument("--study", default=None, help="the full study's sweep folder (its 4-substep tasks)")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    base = {}
    if a.study:
        from compare.sweep import load_results, load_sweep

        base = {r["seed"]: _row(r) for r in load_results(a.study, load_sweep(SWEEP))
                if all(r["params"].get(k) == v for k, v in CELL.items()) and r["params"].get("duration", 30.0) == a.duration}
    with ProcessPoolExecutor(2) as ex:
        fine = list(ex.map(_one, [(s, a.omega_dt, a.duration) for s in a.seeds]))
    print(f"{CELL}, {a.duration:g} s; omega_g dt bound {a.omega_dt:g} ({fine[0]['substeps']} substeps) against the rule's 0.6")
    print("seed | residual % coarse / fine | F_g (N) coarse / fine | F_g trapped (N) coarse / fine | gamma coarse / fine")
    for f in fine:
        b = base.get(f["seed"])
        c = (lambda k, s=1.0: f"{s * b[k]:.3g}") if b else (lambda k, s=1.0: "-")
        print(f"{f['seed']} | {c('energy_balance_rel', 100)} / {100 * f['energy_balance_rel']:.3g} | {c('F_g_mean')} / "
              f"{f['F_g_mean']:.3g} | {c('F_g_trapped')} / {f['F_g_trapped']:.3g} | {c('gamma')} / {f['gamma']:.3f}")
    if base:
        d = np.array([f["gamma"] - base[f["seed"]]["gamma"] for f in fine if f["seed"] in base])
        print(f"gamma fine - coarse: mean {d.mean():+.3f}, per seed {', '.join(f'{x:+.2f}' for x in d)}")
    if a.json:
        Path(a.json).write_text(json.dumps({"cell": CELL, "duration": a.duration, "omega_dt_bound": a.omega_dt,
                                            "fine": fine, "coarse": [base[s] for s in a.seeds if s in base]},
                                           indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
