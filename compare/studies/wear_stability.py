"""Stability of the wear grains: many grains at the lightest shipped mass, a long run.

The wear study's base scene (``scenarios/sweeps/pads_with_wear_study.toml``: grains of 1e-5 kg, 4 substeps of
2.5e-5 s under the grain step rule) with ``--count`` grains (default 1000) for ``--duration`` simulated seconds.
Reported: grains that left the interface (through the track or over the pad: the wear part's own count, which
recycles them), the deepest grain-track and pad-track overlaps, the energy balance residual relative to the
drive's work (must stay within 1 %), the force balance, the grain states' time fractions and the cost in wall
seconds per simulated second. The issue asks for 1000 grains over 60 s; what was run is in the results file.

    python -m compare.studies.wear_stability [--count 1000] [--duration 60] [--seed 0] [--json OUT] [--smoke]

``--smoke`` (CI): 100 grains, 0.2 s.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

import engine_sim
from compare.analysis.balances import balances
from engine_sim import load_scenario
from engine_sim.shipped import SCENARIO_DIR
from engine_sim.wear import grain_step

BASE = SCENARIO_DIR / "sweeps" / "pads_with_wear_study.toml"


def measure(count: int, duration: float, seed: int, progress=None) -> dict:
    sc = load_scenario(BASE).with_wear(count=count).with_run(duration=duration)
    gs = grain_step(sc)
    t0 = time.perf_counter()
    tr = engine_sim.run(sc, seed=seed, progress=progress)
    wall = time.perf_counter() - t0
    bal = balances(tr)
    wm = tr.metadata.get("wear", {})
    return {
        "count": count, "duration_s": duration, "warmup_s": sc.run.warmup, "seed": seed,
        "m_grain_kg": gs["m_grain"], "substeps": gs["substeps"], "dt_step_s": gs["dt_step"],
        "omega_g_dt": gs["omega_g_dt"],
        "left_interface": int(wm.get("left_interface", -1)), "recycled": int(wm.get("recycled", -1)),
        "grain_overlap_max_m": float(np.max(tr.particle_penetration)),
        "stale_arbiters_skipped": int(tr.metadata.get("stale_arbiters_skipped", -1)),
        "pad_overlap_max_m": float(np.max(tr.penetration)),
        "energy_balance_rel": float(bal["energy_balance_rel"]), "force_balance_rel": float(bal["force_balance_rel"]),
        "trapped_frac": float(np.mean(tr.p_state == 1)), "moving_frac": float(np.mean(tr.p_state == 2)),
        "v_mean_m_s": float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])),
        "partial": bool(tr.metadata.get("partial", False)),
        "wall_s": wall, "wall_per_sim_s": wall / (duration + sc.run.warmup),
    }


R_MIN = 20e-6  # m: the smallest grain radius; an overlap as deep as a grain means a grain inside its track


def holds(r: dict) -> bool:
    """No grain lost through the track or over the pad, none overlapping its track by a grain's radius, the energy
    balance within 1 %."""
    return r["left_interface"] == 0 and r["grain_overlap_max_m"] < R_MIN and abs(r["energy_balance_rel"]) <= 0.01


def verdict(r: dict) -> str:
    ok = holds(r)
    return (f"{r['count']} grains of {r['m_grain_kg']:g} kg, {r['duration_s']:g} s (+{r['warmup_s']:g} s warm-up), "
            f"seed {r['seed']}: left the interface {r['left_interface']}, deepest grain overlap "
            f"{1e6 * r['grain_overlap_max_m']:.2f} um, pad overlap {1e6 * r['pad_overlap_max_m']:.2f} um, energy "
            f"residual {100 * r['energy_balance_rel']:+.3f} %, force balance {100 * r['force_balance_rel']:+.3f} %, "
            f"trapped / moving {r['trapped_frac']:.3f} / {r['moving_frac']:.3f}, {r['wall_per_sim_s']:.1f} wall s "
            f"per simulated s: {'holds' if ok else 'FAILS'} (no grain lost, no overlap of a grain radius "
            f"{1e6 * R_MIN:.0f} um, energy within 1 %)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", default=None)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    count, duration = (100, 0.2) if a.smoke else (a.count, a.duration)
    r = measure(count, duration, a.seed)
    print(verdict(r))
    if a.json:
        Path(a.json).write_text(json.dumps(r, indent=1))
    return 0 if holds(r) or a.smoke else 1


if __name__ == "__main__":
    sys.exit(main())
