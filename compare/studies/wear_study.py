"""The wear study's results as committed tables (Markdown + CSV + figure) from a sweep folder.

    frictionnoise sweep scenarios/sweeps/wear_study_quick.toml --serial -o /tmp/wear_study_quick
    python -m compare.studies.wear_study /tmp/wear_study_quick --wall S --out docs/results/wear_study_quick
    python -m compare.studies.wear_study /tmp/wear_study --sweep scenarios/sweeps/wear_study.toml --workers 2 --wall S \
        --command "..." --mass-folder /tmp/wear_study_mass --mass-sweep scenarios/sweeps/wear_study_mass.toml \
        --out docs/results/wear_study

Reads the sweep's stored tasks (compare.sweep.load_results), computes the cells (compare.wear_study.cells) and writes
PREFIX.md (the commands, the cell table, the answer in numbers, then the cost: the wall time, each cell's wall
seconds per simulated second; the quick page points to the full study's page for its cost), PREFIX.csv (one row per cell) and
PREFIX.png (the figure). The quick study's page is docs/results/wear_study_quick.md: its seeded table holds no
timing, so a rerun of the same commands writes the same rows (tests/project/test_study_pages.py rebuilds two).
With ``--mass-folder`` (a sweep of the same cells at another grain mass), the change of gamma per decade of mass
(compare.wear_study.mass_sensitivity) widens every cell's interval (compare.wear_study.widen), in the table and
the answer.
"""
from __future__ import annotations

import argparse
import csv
import io
import json
from pathlib import Path

import numpy as np

from compare.report import plots
from compare.sweep import expand, load_results, load_sweep
from compare.report.wear_study import answer, cells, gamma_figure, mass_sensitivity, mass_split, widen
from engine_sim.shipped import shipped_file

_COLS = ("track", "size", "count", "n", "gamma", "gamma_err", "flagged_fits", "delta_gamma", "delta_gamma_err",
         "gamma_err_total", "delta_gamma_err_total", "Cx_ratio_bands", "fit_CF_grains", "fit_CF_friction",
         "trapped_frac", "moving_frac", "covered_fraction", "F_g_mean", "F_g_trapped", "F_g_moving", "regime_fractions",
         "B2_ratio_bands", "energy_resid_max", "energy_flagged", "left_interface", "wall_per_sim_s", "substeps")
_TABLE_COLS = tuple(c for c in _COLS if c != "wall_per_sim_s")  # the page's table: the seeded columns


def _cell_text(v):
    if isinstance(v, dict) and "exponent" in v:
        return f"{v['exponent']:.2f} +- {v['err']:.2f}"
    if isinstance(v, dict):
        return ", ".join(f"{k} {x:.2f}" for k, x in v.items())
    if isinstance(v, list):
        return ", ".join(f"{x:.2f}" for x in v)
    if isinstance(v, float):
        return f"{v:.3g}"
    return "-" if v is None else str(v)


def _grain_mass(results) -> float:
    """The grains' mass (kg) of a sweep's tasks with grains (the grain step rule's lightest grain, one per sweep)."""
    masses = {r["wear"]["grain_step"]["m_grain"] for r in results if r.get("wear", {}).get("count")}
    if len(masses) != 1:
        raise SystemExit(f"expected one grain mass in the sweep, found {sorted(masses)}")
    return masses.pop()


def _light_limit_lines(rows, split, sens) -> list:
    """The light-grain limit read in the 30-pad scene: the moving part's share of the grains' force per cell at the
    study's mass and, with a second mass, how each part moves with it (compare.wear_study.mass_split)."""
    grains = [r for r in rows if r["count"] > 0 and "F_g_trapped" in r]
    if not grains:
        return []
    L = ["## Light-grain limit in the 30-pad scene (computed)", "",
         "Only the trapped part of the grains' force has a light limit (one pad: `python -m compare.studies."
         "wear_light_limit`); the moving "
         "(pushed or wedged) part goes with the grains' mass. Share of the grains' mean force that is moving, at the "
         "study's mass, per track: "
         + "; ".join(f"{t}: {min(sh):.2f}-{max(sh):.2f} over {len(sh)} cells" for t in ("smooth", "cavities")
                     if (sh := [r["F_g_moving"] / (r["F_g_moving"] + r["F_g_trapped"]) for r in grains
                                if r["track"] == t and r["F_g_moving"] + r["F_g_trapped"] > 0])) + ".", ""]
    if split:
        m0, m1 = sens["mass_kg"], sens["other_mass_kg"]
        L += [f"Paired by seed, {m1:g} kg against {m0:g} kg: the trapped and moving parts' ratios (geometric mean over "
              "seeds), the moving share at each mass, the C_x band levels' ratio.", "",
              f"| track | size | count | seeds | F trapped (mN) {m0:g} / {m1:g} | trapped ratio | F moving (mN) "
              f"{m0:g} / {m1:g} | moving ratio | moving share {m0:g} / {m1:g} | C_x ratio per band |",
              "|---|---|---|---|---|---|---|---|---|---|"]
        for r in split:
            L.append(f"| {r['track']} | {r['size']} | {r['count']} | {len(r['seeds'])} | "
                     f"{1e3 * r['F_trapped'][0]:.1f} / {1e3 * r['F_trapped'][1]:.1f} | {r['trapped_ratio']:.2f} | "
                     f"{1e3 * r['F_moving'][0]:.1f} / {1e3 * r['F_moving'][1]:.1f} | {r['moving_ratio']:.2f} | "
                     f"{r['moving_share'][0]:.2f} / {r['moving_share'][1]:.2f} | "
                     f"{', '.join(f'{x:.2f}' for x in r['Cx_ratio_bands'])} |")
        tr = np.array([x for r in split for x in r["trapped_ratio_per_seed"]])
        mv = np.array([x for r in split for x in r["moving_ratio_per_seed"]])
        L += ["", f"Pooled over {tr.size} paired runs: trapped ratio {np.exp(np.mean(np.log(tr))):.2f} (per run "
              f"{tr.min():.2f}-{tr.max():.2f}), moving ratio {np.exp(np.nanmean(np.log(mv))):.2f} ({np.nanmin(mv):.2f}-"
              f"{np.nanmax(mv):.2f}); a part proportional to the mass would read {m1 / m0:g}.", ""]
    return L


def table_lines(rows) -> list:
    """The cell table as Markdown lines (header, rule, one line per cell) of the seeded columns: every column of the
    CSV but the timing (wall_per_sim_s), so that a rerun writes the same lines."""
    return (["| " + " | ".join(_TABLE_COLS) + " |", "|" + "---|" * len(_TABLE_COLS)]
            + ["| " + " | ".join(_cell_text(r.get(c)) for c in _TABLE_COLS) + " |" for r in rows])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder", help="the sweep's output folder")
    ap.add_argument("--wall", type=float, required=True, help="the sweep's measured wall time (s)")
    ap.add_argument("--command", default=None,
                    help="the commands that made the folder and this page, as the page states them (default: the "
                         "sweep's and this study's, with the folder written FOLDER)")
    ap.add_argument("--load", default=None, help="the machine's load while the sweep ran (for the cost section)")
    ap.add_argument("--sweep", default="scenarios/sweeps/wear_study_quick.toml")
    ap.add_argument("--full", default="scenarios/sweeps/wear_study.toml")
    ap.add_argument("--out", default="docs/results/wear_study_quick",
                    help="the files' prefix (PREFIX.md, .csv, .png)")
    ap.add_argument("--workers", type=int, default=1, help="the sweep's worker processes (for the text)")
    ap.add_argument("--mass-folder", default=None, help="a sweep of the same cells at another grain mass")
    ap.add_argument("--mass-sweep", default="scenarios/sweeps/wear_study_mass.toml")
    ap.add_argument("--mass-wall", type=float, default=None, help="that sweep's wall time (s)")
    a = ap.parse_args(argv)
    spec, full = load_sweep(shipped_file(a.sweep)), load_sweep(shipped_file(a.full))
    results = load_results(a.folder, spec)  # the grid's own tasks (a reused folder keeps an old grid's files)
    rows = cells(results)
    sens = split = None
    if a.mass_folder:
        other = load_results(a.mass_folder, load_sweep(shipped_file(a.mass_sweep)))
        split = mass_split(results, other)
        m0 = _grain_mass(results)
        m1 = _grain_mass(other)
        sens = mass_sensitivity(rows, cells(other), decades=float(np.log10(m1 / m0)))
        sens.update(mass_kg=m0, other_mass_kg=m1)
        rows = widen(rows, sens)
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(_COLS)
    for r in rows:
        w.writerow([json.dumps(r.get(c)) if isinstance(r.get(c), (list, dict)) else r.get(c, "") for c in _COLS])
    out.with_suffix(".csv").write_text(buf.getvalue())
    plots.save_figure(gamma_figure(rows), out.with_suffix(".png"))
    sim = sum("wear" in r for r in results)
    command = a.command or (f"frictionnoise sweep {a.sweep} --serial -o FOLDER; python -m compare.studies.wear_study "
                            f"FOLDER --wall S --out {a.out}")
    L = [f"# Wear study ({spec.name}): does debris steepen the spectrum?", "",
         f"Reproduce: `{command}` (S: the sweep's wall time, for the cost section). The tables hold no timing: the "
         "same commands write the same rows on any machine (seeded runs).", "",
         f"Sweep: `{a.sweep}`: {spec.description.replace(chr(10), ' ')}", "",
         "gamma: the record model's exponent of x(t) over 3-30 v/a (v the law's speed, a = 1 mm: 15-150 rad/s; "
         "compare.analysis.record_model.fit_series: C_x = A omega^-gamma + a white floor, debiased Whittle likelihood "
         "of the whole record, profile 95 % interval), mean over seeds (flagged_fits: the seeds whose fit the record "
         "model flags as not one power law over the band: a bend, a split or halves that differ), +- the "
         "larger of the seed scatter's 95 % half-width (t quantile) and the per-seed 95 % intervals combined; rise: "
         "gamma minus the particle-free twin's (same track and seed), paired, with the same interval rule; C_x / twin: "
         "paired ratio per band (3 log bands over 15-150 rad/s), geometric mean over seeds; C_F exponents: C_F ~ "
         "omega^-exponent over the same band by the same fit of the force's running sum (grains' summed force on "
         "the pads; the pads' whole friction force); "
         "covered: grains' summed diameters over the tracks' grain windows (30 x 7 mm); B2: the grains' measured C_F over "
         "eq. (B2) built from the cell's own trap/move episodes, per band (1 = model II exact); F_g_trapped / F_g_moving: "
         "the grains' mean force on the pads while trapped / moving (N; only the trapped part has a light-grain limit, "
         "`python -m compare.studies.wear_light_limit`); regime_fractions: the cell's grains by "
         "engine_sim.wear.wedge_regime; err_total columns: the 95 % half-width with one decade of grain mass added in "
         "quadrature (when measured). Energy residuals above 1 % are flagged.", ""]
    L += table_lines(rows)
    L += ["", f"![gamma against the particle count per track and size]({out.name}.png)", "",
          "## Answer (computed)", "", answer(rows).replace("&plusmn;", "+-"), ""]
    if sens is not None:
        L += ["## Grain mass systematic (computed)", "",
              f"`{a.mass_sweep}`: the same cells and "
              f"seeds at {sens['other_mass_kg']:g} kg against {sens['mass_kg']:g} kg ({sens['decades']:+.0f} decade), paired "
              "by seed; change of gamma per decade of grain mass, pooled per track, with its 95 % interval (seed scatter), "
              "and the systematic half-width it implies for one decade (|change| + interval):", ""]
        for track, t in sens["tracks"].items():
            L.append(f"- {track}: {t['per_decade']:+.3f} +- {t['err']:.3f} per decade ({t['n']} pairs): systematic "
                     f"+-{t['systematic']:.3f}")
        L += ["", "| track | size | count | per seed (per decade) | mean |", "|---|---|---|---|---|"]
        for c in sens["cells"]:
            L.append(f"| {c['track']} | {c['size']} | {c['count']} | {', '.join(f'{x:+.2f}' for x in c['per_decade'])} | "
                     f"{c['mean']:+.3f} |")
        L.append("")
    L += _light_limit_lines(rows, split, sens)
    L += ["## Cost (timings: machine and load dependent, not reproduced by a rerun)", "",
          f"Wall time: {a.wall:.0f} s ({a.wall / 3600:.2f} h) for {sim} tasks on {a.workers} worker"
          f"{'s' if a.workers > 1 else ''} (2 cores{f', load {a.load}' if a.load else ''})"
          f"{f'; the mass sweep {a.mass_wall:.0f} s' if a.mass_wall else ''}. Wall seconds per simulated second, "
          "per cell: " + "; ".join(f"{r['track']} {r['size']} {r['count']}: {r['wall_per_sim_s']:.3g}" for r in rows)
          + ".", ""]
    if a.full != a.sweep:
        L += [f"The full study (`{a.full}`, {len(expand(full))} tasks of 30 s) has its cost measured on its own page, "
              "[the wear study](wear_study); its larger counts cost more per simulated second than any cell run "
              "here, so this page's costs do not project it.", ""]
    out.with_suffix(".md").write_text("\n".join(L).rstrip("\n") + "\n")
    print(out.with_suffix(".md").read_text())


if __name__ == "__main__":
    main()
