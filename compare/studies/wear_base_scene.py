"""Is the particle-free twin of ``pads_with_wear`` at omega^-4, with and without cavities?

    python -m compare.studies.wear_base_scene [--duration S] [--seeds 0,1,2] [--geometries shipped,none,...]
                                         [--out PREFIX] [--smoke]

Runs ``pads_with_wear`` with ``wear.count = 0`` (its solver settings as shipped) for each cavity geometry and
seed, and fits gamma over 3-30 v/a, v the drive's set speed (15-150 rad/s at v = 5 mm/s, a = 1 mm), by the record
model as the wear study fits it (:func:`compare.analysis.record_model.fit_series`: C_x = A omega^-gamma plus a white
floor, the debiased Whittle likelihood of the whole record; the friction force through its running sum); C_x's band
levels from the Welch spectrum with the wear study's nperseg.
Per geometry: gamma per seed with its 95 % interval, the inverse-variance mean over seeds with its interval, and
the seed-to-seed standard deviation. Every finished run is written to ``PREFIX.json`` at once (a rerun skips
finished runs) and ``PREFIX.md`` is rewritten.

Geometries (substrate overrides; pit widths are between the wall centre lines, the opening is narrower by
2 segment radii = 0.1 mm; a pad of radius R dips w_open^2 / (8 R) into an opening w_open):
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

import engine_sim
from compare.analysis.record_model import fit_series
from compare.analysis.spectra import band_average, displacement_spectrum
from compare.analysis.balances import balances
from engine_sim import load_scenario, shipped_scenarios

GEOMETRIES = {
    "shipped": ({}, "as shipped: pit_p 0.5, width 0.15-0.35 mm (opening 0.05-0.25 mm, pad dips up to 26 um), depth 60 um"),
    "none": ({"pit_p": 0.0}, "no cavities (pit_p = 0): the pads_friction_patches track at 20 iterations"),
    "narrow": ({"pit_width_min": 0.20e-3, "pit_width_max": 0.22e-3},
               "pit_p 0.5, width 0.20-0.22 mm (opening 0.10-0.12 mm: holds a 50 um grain; pad dips 4-6 um), depth 60 um"),
    "narrow_sparse": ({"pit_p": 0.2, "pit_width_min": 0.20e-3, "pit_width_max": 0.22e-3},
                      "pit_p 0.2 (one patch in five), width 0.20-0.22 mm (opening 0.10-0.12 mm), depth 60 um"),
    "sparse": ({"pit_p": 0.2}, "pit_p 0.2, shipped widths 0.15-0.35 mm, depth 60 um"),
    "narrow_rare": ({"pit_p": 0.1, "pit_width_min": 0.20e-3, "pit_width_max": 0.22e-3},
                    "pit_p 0.1 (one patch in ten), width 0.20-0.22 mm (opening 0.10-0.12 mm), depth 60 um"),
    "narrow_a3": ({"a": 3e-3, "pit_p": 1.0, "pit_width_min": 0.20e-3, "pit_width_max": 0.22e-3},
                  "patches 3x longer (a = 3 mm, band 5-50 rad/s), a pit in every patch (one per 3 mm), width 0.20-0.22 mm "
                  "(opening 0.10-0.12 mm), depth 60 um: the pits' passage time (~w/v) sits 3x further above the band"),
    "none_a3": ({"a": 3e-3, "pit_p": 0.0}, "patches 3x longer (a = 3 mm, band 5-50 rad/s), no cavities: narrow_a3's twin"),
    "narrow_rarer": ({"pit_p": 0.05, "pit_width_min": 0.20e-3, "pit_width_max": 0.22e-3},
                     "pit_p 0.05 (one patch in twenty), width 0.20-0.22 mm (opening 0.10-0.12 mm), depth 60 um"),
}
__doc__ += "\n".join(f"    {k}: {v[1]}" for k, v in GEOMETRIES.items()) + "\n"


def scene(geometry: str, duration: float):
    sc = load_scenario(shipped_scenarios()["pads_with_wear"])
    sub = replace(sc.substrate, **GEOMETRIES[geometry][0])
    return replace(sc, substrate=sub).with_wear(count=0).with_run(duration=duration)


def nperseg_for(n: int) -> int:
    """The wear study's Welch segment (compare/studies/scene_wear.py, full report): min(2^13, 2^floor(log2(n/3)))."""
    return min(2**13, 1 << int(math.floor(math.log2(n / 3))))


def measure(geometry: str, seed: int, duration: float) -> dict:
    sc = scene(geometry, duration)
    t0 = time.perf_counter()
    tr = engine_sim.run(sc, seed=seed)
    wall = time.perf_counter() - t0
    va = sc.drive.v / sc.substrate.a
    band = (3 * va, 30 * va)
    nper = nperseg_for(len(tr.t))
    sx = displacement_spectrum(tr.t, tr.x, nperseg=nper)
    fit = fit_series(tr.t, tr.x, band=band)
    fitF = fit_series(tr.t, tr.F_t, band=band, quantity="F", integrate=True)
    edges = np.logspace(math.log10(band[0]), math.log10(band[1]), 4)
    return {"geometry": geometry, "seed": seed, "duration": duration, "band": list(band), "nperseg": nper,
            "gamma": fit.gamma, "gamma_err": fit.gamma_err, "power_law": bool(fit.power_law), "flags": list(fit.flags),
            "gamma_F": fitF.gamma, "gamma_F_err": fitF.gamma_err,
            "Cx_bands": band_average(sx, edges).tolist(), "band_edges": edges.tolist(),
            "v_mean": float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])),
            "energy_balance_rel": balances(tr)["energy_balance_rel"],
            "wall_s": wall, "wall_per_sim_s": wall / (duration + sc.run.warmup)}


def summary(rows):
    g = np.array([r["gamma"] for r in rows])
    se = np.array([r["gamma_err"] for r in rows]) / 1.96
    w = 1 / se**2
    mean = float(np.sum(w * g) / np.sum(w))
    err = float(1.96 / math.sqrt(np.sum(w)))
    sd = float(g.std(ddof=1)) if g.size > 1 else float("nan")
    # an interval that also holds the seed-to-seed scatter: 1.96 x max(inverse-variance se, sd / sqrt(n))
    err_scatter = float(1.96 * max(1 / math.sqrt(np.sum(w)), sd / math.sqrt(g.size))) if g.size > 1 else err
    return mean, err, sd, err_scatter


def markdown(runs, geometries, seeds, meta) -> str:
    L = ["# Particle-free base scene of the wear study: gamma with and without cavities", "",
         "Commands: " + "; ".join(f"`{c}`" for c in meta.get("commands", [meta.get("command", "")])) + "  ",
         f"Scene: pads_with_wear with wear.count = 0 (20 iterations, dt 1e-4 s as shipped), {meta['duration']:g} s recorded "
         f"per run (+ 1 s warm-up), seeds {', '.join(map(str, seeds))}. Band 3-30 v/a with v = 5 mm/s (set speed), "
         "a = 1 mm: 15-150 rad/s (a = 3 mm geometries: 5-50 rad/s). The record model (fit_series: a power law plus a "
         "white floor, debiased Whittle likelihood of the whole record, profile 95 % intervals; the friction force "
         "through its running sum).  ",
         f"Wall time: {meta['wall_total_s']:.0f} s for {len(runs)} runs; last update {meta['updated']}.", "",
         "| geometry | per seed: gamma +- 95 % | mean (inverse-variance) +- 95 % | seed sd | +- 95 % with seed scatter "
         "| C_F(friction) exponent, mean | v (mm/s) | wall s / sim s |",
         "|---|---|---|---|---|---|---|---|"]
    for g in geometries:
        rows = [runs[f"{g}|{s}"] for s in seeds if f"{g}|{s}" in runs]
        if not rows:
            continue
        mean, err, sd, err2 = summary(rows)
        per_seed = ", ".join("%.2f +- %.2f" % (r["gamma"], r["gamma_err"]) for r in rows)
        L.append(f"| {g} | {per_seed} | {mean:.2f} +- {err:.2f} "
                 f"| {sd:.2f} | {mean:.2f} +- {err2:.2f} "
                 f"| {np.mean([r['gamma_F'] for r in rows]):.2f} | {1e3 * np.mean([r['v_mean'] for r in rows]):.3f} "
                 f"| {np.mean([r['wall_per_sim_s'] for r in rows]):.2f} |")
    L += ["", "Geometries:", ""] + [f"- {g}: {GEOMETRIES[g][1]}" for g in geometries]
    if any(not r["power_law"] for r in runs.values()):
        L += ["", "Fits flagged not-a-power-law: " + "; ".join(f"{k}: {', '.join(r['flags'])}" for k, r in runs.items() if not r["power_law"])]
    if meta.get("discussion"):
        L += ["", "## Discussion", "", meta["discussion"]]
    return "\n".join(L) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--seeds", default="0,1,2")
    ap.add_argument("--geometries", default="shipped,none")
    ap.add_argument("--out", default="study-results/wear_base_scene")
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--rewrite", action="store_true", help="only rewrite PREFIX.md from PREFIX.json")
    a = ap.parse_args(argv)
    seeds = [int(s) for s in a.seeds.split(",")]
    geoms = a.geometries.split(",")
    duration, out = a.duration, Path(a.out)
    if a.smoke:
        seeds, geoms, duration, out = seeds[:1], geoms[:1], 8.0, Path("/tmp/wear_base_scene_smoke")
    jpath, mpath = out.with_suffix(".json"), out.with_suffix(".md")
    runs, meta = {}, {"wall_total_s": 0.0}
    if jpath.exists() and not a.smoke:
        saved = json.loads(jpath.read_text())
        if saved.get("meta", {}).get("duration") == duration:
            runs, meta = saved["runs"], saved["meta"]
    meta["duration"] = duration
    if a.rewrite:
        allg = list(dict.fromkeys(meta.get("geometries", []) + [k.split("|")[0] for k in runs]))
        mpath.write_text(markdown(runs, allg, sorted({int(k.split('|')[1]) for k in runs}), meta))
        return
    cmd = "python -m compare.studies.wear_base_scene " + " ".join(argv if argv is not None else sys.argv[1:])
    meta["commands"] = list(dict.fromkeys(meta.get("commands", [meta["command"]] if "command" in meta else []) + [cmd]))
    allg = list(dict.fromkeys(meta.get("geometries", []) + geoms))
    meta["geometries"] = allg
    for g in geoms:
        for s in seeds:
            if f"{g}|{s}" in runs:
                continue
            t0 = time.perf_counter()
            r = measure(g, s, duration)
            runs[f"{g}|{s}"] = r
            meta["wall_total_s"] += time.perf_counter() - t0
            meta["updated"] = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
            print(f"[{time.strftime('%H:%M:%S')}] {g} seed {s}: gamma {r['gamma']:.2f} +- {r['gamma_err']:.2f}, "
                  f"{r['wall_s']:.0f} s wall", file=sys.stderr, flush=True)
            jpath.write_text(json.dumps({"meta": meta, "runs": runs}, indent=1))
            mpath.write_text(markdown(runs, allg, sorted({int(k.split('|')[1]) for k in runs}), meta))
    if a.smoke:
        print(mpath.read_text())


if __name__ == "__main__":
    main()
