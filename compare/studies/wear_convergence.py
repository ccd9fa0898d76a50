"""Do the wear grains' results converge in grain mass and solver settings?

    python -m compare.studies.wear_convergence [--duration S] [--seeds 0,1,2] [--masses 1e-5,1e-6,...]
                                         [--settings 20:1e-4,40:1e-4,20:5e-5] [--out PREFIX] [--smoke]

The dt of a setting is the scenario's ``run.dt``; the scene cuts it into substeps by the grain step rule
(``engine_sim.wear.grain_step``: omega_g dt <= 0.6 for the lightest grain), and the table's dt column is the
pymunk step actually taken (two runs with the same pymunk step are the same run, whether the step is run.dt or
a substep of it). Rows whose energy residual exceeds 1 % are flagged.

Runs ``pads_with_wear`` (50 grains) over grain mass (``wear.min_mass``) x solver settings (``run.iterations``,
``run.dt``) x paired seeds (same seed: same substrate and grain radii), one run at a time, and tabulates per run:

- F_g: the grains' mean force on the pads (sum over grains of ``p_force``, mean over time) [N];
- C_Fg band levels: the spectrum of that summed force (``force_series_spectrum``) averaged over fixed log bands;
- C_x band levels: the block's displacement spectrum (``displacement_spectrum``) over 3 fixed log bands spanning
  3-30 v/a (v the drive's set speed, v/a = 5 rad/s here: 15-150 rad/s);
- the energy balance residual (relative to the drive's work), the deepest grain overlap with a track, grains that
  left the interface (through the track or over the pad), the trapped/moving time fractions, the mean speed;
- cost: wall seconds per simulated second (warm-up included) and microseconds per step.

Every finished run is written to ``PREFIX.json`` at once (a rerun with the same arguments skips finished runs),
and the Markdown table ``PREFIX.md`` is rewritten, so a partial sweep leaves a partial table. Progress lines go
to stderr. The verdict applies the convergence criterion: at the two lightest masses, doubling the iterations and
halving dt change each result by less than 3 % (paired by seed, the change of the 3-seed means), and the two
masses agree within 5 %; next to every change the seed-to-seed scatter (standard error of the 3-seed mean) says
whether 3 % is resolvable at this run length.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

import engine_sim
from compare.analysis.spectra import band_average, displacement_spectrum, force_series_spectrum
from compare.analysis.balances import balances
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.wear import grain_step

MASSES = (1e-3, 1e-4, 1e-5, 1e-6)
SETTINGS = ((20, 1e-4), (40, 1e-4), (20, 5e-5))  # (iterations, dt): reference, doubled iterations, halved dt
BASE = (20, 1e-4)
REFERENCES = (BASE, (20, 2.5e-5))  # settings from which "its x2" and "dt / 2" are tabulated
NPERSEG = 1024  # 1.024 s segments at dt_out = 1 ms: d_omega = 6.1 rad/s, ~11 half-overlapping segments in 6 s
FG_EDGES = (15.0, 60.0, 240.0, 960.0)  # rad/s, the grains' force spectrum
CX_EDGES_VA = (3.0, 3.0 * 10 ** (1 / 3), 3.0 * 10 ** (2 / 3), 30.0)  # x v/a, the block's C_x
QUANTITIES = ("F_g", "CFg_0", "CFg_1", "CFg_2", "Cx_0", "Cx_1", "Cx_2", "v_mean")


def _key(mass, it, dt, seed):
    return f"m={mass:g}|it={it}|dt={dt:g}|seed={seed}"


def step_taken(sc, mass, dt) -> float:
    """The pymunk step (s) a run with grain mass ``mass`` and run.dt ``dt`` takes under the grain step rule."""
    return grain_step(sc.with_wear(min_mass=mass).with_run(dt=dt))["dt_step"]


def measure(sc, mass, it, dt, seed, duration) -> dict:
    """One run's row (see the module docstring); ``dt`` is run.dt, the row's "dt" the pymunk step taken."""
    s = sc.with_wear(min_mass=mass).with_run(iterations=it, dt=dt, duration=duration)
    gs = grain_step(s)
    t0 = time.perf_counter()
    tr = engine_sim.run(s, seed=seed)
    wall = time.perf_counter() - t0
    Fg = tr.p_force.sum(axis=1)
    va = s.drive.v / s.substrate.a
    cx_edges = [e * va for e in CX_EDGES_VA]
    sF = force_series_spectrum(tr.t, Fg, nperseg=NPERSEG)
    sx = displacement_spectrum(tr.t, tr.x, nperseg=NPERSEG)
    cF = band_average(sF, FG_EDGES)
    cx = band_average(sx, cx_edges)
    bal = balances(tr)
    wm = tr.metadata.get("wear", {})
    return {
        "mass": mass, "iterations": it, "dt": gs["dt_step"], "run_dt": dt, "substeps": gs["substeps"],
        "omega_g_dt": gs["omega_g_dt"], "seed": seed, "duration": duration,
        "F_g": float(Fg.mean()), "F_g_rms": float(Fg.std()),
        **{f"CFg_{i}": float(c) for i, c in enumerate(cF)}, **{f"Cx_{i}": float(c) for i, c in enumerate(cx)},
        "v_mean": float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])),
        "energy_balance_rel": bal["energy_balance_rel"], "force_balance_rel": bal["force_balance_rel"],
        "grain_overlap_max_m": float(tr.particle_penetration.max()),
        "pad_overlap_max_m": float(tr.penetration.max()),
        "left_interface": int(wm.get("left_interface", -1)), "recycled": int(wm.get("recycled", -1)),
        "trapped_frac": float(np.mean(tr.p_state == 1)), "moving_frac": float(np.mean(tr.p_state == 2)),
        "wall_s": wall, "wall_per_sim_s": wall / (duration + s.run.warmup),
        "us_per_step": float(tr.metadata["us_per_step"]),
        "fg_edges": list(FG_EDGES), "cx_edges": cx_edges,
    }


def _stats(vals):
    v = np.asarray(vals, float)
    if v.size == 0:
        return float("nan"), float("nan")
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(v.size)) if v.size > 1 else float("nan")


def _cell(runs, mass, it, dt, seeds):
    return [runs[_key(mass, it, dt, s)] for s in seeds if _key(mass, it, dt, s) in runs]


def paired_change(runs, a, b, seeds, q):
    """Relative change of quantity q from cell a to cell b ((mass, it, dt) each), paired by seed: the ratio of the
    means over the seeds both hold, and the scatter of the per-seed ratios (standard error)."""
    common = [s for s in seeds if _key(*a, s) in runs and _key(*b, s) in runs]
    if not common:
        return float("nan"), float("nan"), 0
    xa = np.array([runs[_key(*a, s)][q] for s in common])
    xb = np.array([runs[_key(*b, s)][q] for s in common])
    ch = float(xb.mean() / xa.mean() - 1)
    per = xb / xa - 1
    se = float(per.std(ddof=1) / math.sqrt(per.size)) if per.size > 1 else float("nan")
    return ch, se, len(common)


def markdown(runs, masses, settings, seeds, meta) -> str:
    L = [f"# Wear grains: convergence in grain mass and solver settings", "",
         "Commands (in this order; finished runs are kept, a later command adds cells): "
         + "; ".join(f"`{c}`" for c in meta.get("commands", [meta.get("command", "")])) + "  ", f"Scene: pads_with_wear (50 grains), {meta['duration']:g} s recorded per run "
         f"(+ 1 s warm-up), seeds {', '.join(map(str, seeds))} (paired: same substrate and grain radii per seed).  ",
         f"Wall time so far: {meta['wall_total_s']:.0f} s; runs finished: {len(runs)}; started {meta['started']}, "
         f"last update {meta['updated']}.", "",
         f"F_g: grains' summed force on the pads, mean over time (N). C_Fg bands (rad/s): "
         f"{', '.join(f'{FG_EDGES[i]:g}-{FG_EDGES[i + 1]:g}' for i in range(3))}; C_x bands: 3-30 v/a in 3 log bands "
         f"(15-32-70-150 rad/s), Welch nperseg {NPERSEG}. Each entry: mean over seeds +- standard error of the mean "
         "(n seeds). Energy residual: worst |residual| / drive work over seeds; overlap: deepest grain-track overlap "
         "over seeds; lost: grains that left the interface (through the track or over the pad), summed over seeds.", "",
         "| mass (kg) | its | dt (s) | n | F_g (N) | C_Fg 15-60 | C_Fg 60-240 | C_Fg 240-960 | C_x 15-32 | C_x 32-70 "
         "| C_x 70-150 | v (mm/s) | energy resid. worst | overlap max (um) | lost | trapped / moving | wall s / sim s |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    masses = sorted(masses, reverse=True)
    for m in masses:
        for it, dt in settings:
            c = _cell(runs, m, it, dt, seeds)
            if not c:
                continue

            def f(q, scale=1.0, fmt=".3g"):
                mu, se = _stats([r[q] * scale for r in c])
                return f"{mu:{fmt}} +- {se:.2g}"
            L.append(f"| {m:g} | {it} | {dt:g} | {len(c)} | {f('F_g', fmt='.4f')} | {f('CFg_0')} | {f('CFg_1')} | {f('CFg_2')} "
                     f"| {f('Cx_0')} | {f('Cx_1')} | {f('Cx_2')} | {f('v_mean', 1e3, '.4f')} "
                     f"| {100 * max(abs(r['energy_balance_rel']) for r in c):.2f} %"
                     f"{' (> 1 %: flagged)' if max(abs(r['energy_balance_rel']) for r in c) > 0.01 else ''} "
                     f"| {1e6 * max(r['grain_overlap_max_m'] for r in c):.2f} | {sum(r['left_interface'] for r in c)} "
                     f"| {np.mean([r['trapped_frac'] for r in c]):.3f} / {np.mean([r['moving_frac'] for r in c]):.3f} "
                     f"| {np.mean([r['wall_per_sim_s'] for r in c]):.2f} |")
    L += ["", "## Paired changes (3-seed means, paired by seed)", "",
          "Change = mean(b) / mean(a) - 1 over the seeds both cells hold; +- the standard error of the per-seed ratios "
          "(what one seed's chaos contributes: a change smaller than about 2x this cannot be told from zero).", "",
          "| mass (kg) | comparison | " + " | ".join(QUANTITIES) + " |", "|---|---|" + "---|" * len(QUANTITIES)]
    comps = []
    for ref in REFERENCES:
        named = {(2 * ref[0], ref[1]): f"its x2 (from {ref[0]}, {ref[1]:g})", (ref[0], ref[1] / 2): f"dt / 2 (from {ref[0]}, {ref[1]:g})"}
        comps += [(named[st], ref, st) for st in settings if st in named]
    comps += [(f"{st[0]} its, dt {st[1]:g} vs {BASE[0]}, {BASE[1]:g}", BASE, st) for st in settings
              if st != BASE and not any(c[2] == st and c[1] == BASE for c in comps)]
    for m in masses:
        for name, (ia, da), (ib, db) in comps:
            row = [paired_change(runs, (m, ia, da), (m, ib, db), seeds, q) for q in QUANTITIES]
            if row[0][2] == 0:
                continue
            L.append(f"| {m:g} | {name} ({row[0][2]} seeds) | " + " | ".join(f"{100 * c:+.1f} +- {100 * s:.1f} %" for c, s, _ in row) + " |")
    by_mass = sorted(masses, reverse=True)
    for ref in REFERENCES:
        for i in range(len(by_mass) - 1):
            a = by_mass[i]
            b = next((m for m in by_mass[i + 1:] if _cell(runs, m, *ref, seeds)), None)
            if b is None or not _cell(runs, a, *ref, seeds):
                continue
            row = [paired_change(runs, (a,) + ref, (b,) + ref, seeds, q) for q in QUANTITIES]
            if row[0][2] == 0:
                continue
            L.append(f"| {a:g} -> {b:g} | lighter grains at {ref[0]} its, dt {ref[1]:g} ({row[0][2]} seeds) | "
                     + " | ".join(f"{100 * c:+.1f} +- {100 * s:.1f} %" for c, s, _ in row) + " |")
    L += ["", "## Seed-to-seed scatter (relative standard deviation of one run, per quantity, at 20 its, dt 1e-4)", ""]
    for m in masses:
        c = _cell(runs, m, *BASE, seeds)
        if len(c) > 1:
            L.append(f"- {m:g} kg: " + ", ".join(
                f"{q} {100 * np.std([r[q] for r in c], ddof=1) / abs(np.mean([r[q] for r in c])):.1f} %" for q in QUANTITIES))
    if meta.get("verdict"):
        L += ["", "## Verdict (computed)", "", meta["verdict"]]
    if meta.get("discussion"):
        L += ["", "## Discussion", "", meta["discussion"]]
    return "\n".join(L) + "\n"


def verdict(runs, masses, seeds) -> str:
    """The convergence criterion at the two lightest masses run, and which masses hold the energy balance
    (|resid| < 1 %) with no grain lost."""
    ok = []
    for m in masses:
        c = [r for r in runs.values() if r["mass"] == m]
        if c and max(abs(r["energy_balance_rel"]) for r in c) < 0.01 and sum(r["left_interface"] for r in c) == 0:
            ok.append(m)
    lines = [f"Masses that hold the energy balance within 1 % with no grain lost, over every setting run: "
             f"{', '.join(f'{m:g}' for m in ok) or 'none'}."]
    run_masses = sorted({r["mass"] for r in runs.values()})
    if len(run_masses) < 2:
        return " ".join(lines)
    m1, m2 = run_masses[:2]
    lines.append(f"Criterion at the two lightest masses run, {m1:g} and {m2:g} kg (3 % settings, 5 % between masses):")
    worst = {}
    for m in (m1, m2):
        for name, b in (("its x2", (2 * BASE[0], BASE[1])), ("dt / 2", (BASE[0], BASE[1] / 2))):
            for q in QUANTITIES:
                ch, se, n = paired_change(runs, (m,) + BASE, (m,) + b, seeds, q)
                if n:
                    worst.setdefault(q, []).append((abs(ch), se, f"{m:g} {name}"))
    for q in QUANTITIES:
        w = worst.get(q)
        ch, se, n = paired_change(runs, (m2,) + BASE, (m1,) + BASE, seeds, q)
        if not w:
            continue
        a, s, where = max(w)
        lines.append(f"{q}: largest settings change at {m1:g}/{m2:g} kg {100 * a:.1f} % +- {100 * s:.1f} ({where}) -> "
                     f"{'< 3 %' if a < 0.03 else 'NOT < 3 %'}; {m2:g} -> {m1:g} kg {100 * ch:+.1f} % +- {100 * se:.1f} -> "
                     f"{'within 5 %' if abs(ch) < 0.05 else 'NOT within 5 %'}.")
    return "  \n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--duration", type=float, default=6.0, help="recorded simulated seconds per run (default 6)")
    ap.add_argument("--seeds", default="0,1,2")
    ap.add_argument("--masses", default=",".join(f"{m:g}" for m in MASSES), help="kg, run in this order")
    ap.add_argument("--settings", default=",".join(f"{i}:{d:g}" for i, d in SETTINGS), help="iterations:dt,...")
    ap.add_argument("--out", default="study-results/wear_convergence", help="PREFIX of PREFIX.json / PREFIX.md")
    ap.add_argument("--smoke", action="store_true", help="one short run per setting at one mass (CI, < 30 s)")
    ap.add_argument("--rewrite", action="store_true", help="only rewrite PREFIX.md (and the verdict) from PREFIX.json")
    a = ap.parse_args(argv)
    seeds = [int(s) for s in a.seeds.split(",")]
    masses = [float(m) for m in a.masses.split(",")]
    settings = [(int(s.split(":")[0]), float(s.split(":")[1])) for s in a.settings.split(",")]
    duration = a.duration
    out = Path(a.out)
    if a.smoke:
        seeds, masses, settings, duration = seeds[:1], [1e-4], [BASE, (40, 1e-4)], 1.5
        out = Path("/tmp/wear_convergence_smoke")
    sc = load_scenario(shipped_scenarios()["pads_with_wear"]).with_run(warmup=0.5 if a.smoke else 1.0)
    jpath, mpath = out.with_suffix(".json"), out.with_suffix(".md")
    runs, meta = {}, {}
    if jpath.exists() and not a.smoke:
        saved = json.loads(jpath.read_text())
        if saved.get("meta", {}).get("duration") == duration:
            runs, meta = saved["runs"], saved["meta"]
    meta.setdefault("started", time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()))
    meta.setdefault("wall_total_s", 0.0)
    meta["duration"] = duration
    if not a.rewrite:
        cmd = "python -m compare.studies.wear_convergence " + " ".join(argv if argv is not None else sys.argv[1:])
        meta["commands"] = list(dict.fromkeys(meta.get("commands", [meta["command"]] if "command" in meta else []) + [cmd]))
    if a.rewrite:
        masses = sorted({r["mass"] for r in runs.values()}, reverse=True)
        settings = sorted({(r["iterations"], r["dt"]) for r in runs.values()}, key=lambda x: (x[0], -x[1]))
        meta["verdict"] = verdict(runs, masses, seeds)
        jpath.write_text(json.dumps({"meta": meta, "runs": runs}, indent=1))
        mpath.write_text(markdown(runs, masses, settings, seeds, meta))
        return runs
    t_start = time.perf_counter()
    todo = [(m, it, dt, s) for m in masses for (it, dt) in settings for s in seeds
            if _key(m, it, step_taken(sc, m, dt), s) not in runs]
    for n, (m, it, dt, s) in enumerate(todo, 1):
        try:
            row = measure(sc, m, it, dt, s, duration)
        except Exception as e:  # a mass the solver cannot hold is a result, not a crash
            row = {"mass": m, "iterations": it, "dt": dt, "seed": s, "error": f"{type(e).__name__}: {e}"}
        if "error" in row:
            print(f"[{time.strftime('%H:%M:%S')}] {n}/{len(todo)} m={m:g} it={it} dt={dt:g} seed={s}: {row['error']}",
                  file=sys.stderr, flush=True)
            meta.setdefault("errors", []).append(row)
        else:
            runs[_key(m, it, row["dt"], s)] = row
            print(f"[{time.strftime('%H:%M:%S')}] {n}/{len(todo)} m={m:g} it={it} dt={dt:g} seed={s}: F_g {row['F_g']:.4f} N, "
                  f"resid {100 * row['energy_balance_rel']:+.2f} %, overlap {1e6 * row['grain_overlap_max_m']:.2f} um, "
                  f"lost {row['left_interface']}, {row['wall_s']:.0f} s wall ({row['wall_per_sim_s']:.2f} s/s)",
                  file=sys.stderr, flush=True)
        meta["wall_total_s"] += time.perf_counter() - t_start
        t_start = time.perf_counter()
        meta["updated"] = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
        all_m = sorted({r["mass"] for r in runs.values()}, reverse=True)
        all_st = sorted({(r["iterations"], r["dt"]) for r in runs.values()}, key=lambda x: (x[0], -x[1]))
        meta["verdict"] = verdict(runs, all_m, seeds)
        jpath.write_text(json.dumps({"meta": meta, "runs": runs}, indent=1))
        mpath.write_text(markdown(runs, all_m, all_st, seeds, meta))
    if a.smoke:
        print(mpath.read_text())
    return runs


if __name__ == "__main__":
    main()
