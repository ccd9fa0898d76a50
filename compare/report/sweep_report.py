"""The report of a parameter sweep (``frictionnoise sweep``): the results table, failures, and the velocity
analysis when v varies (paper section 2, eq. 6, Fig. 15). Beside its pipeline, ``compare.sweep``."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from frictionnoise.base import package_version

from ..analysis.fits import flag_mark
from .html import esc, span, json_text, page, paragraphs, table
from .study import Figure, StudyResult

__all__ = ["build_sweep_report", "write_sweep_outputs"]


def build_sweep_report(spec, results: list, failures: list):
    """Results (StudyResult list) and summary of a sweep."""
    from . import plots
    from ..analysis.spectra import Spectrum
    from ..analysis.velocity import velocity_analysis

    keys = [k for k in spec.grid if k != "seed"]
    summary = {"version": package_version(), "sweep": spec.name, "target": spec.target, "grid": spec.grid,
               "fixed": spec.fixed, "n_results": len(results), "n_failures": len(failures),
               "results": [{**{k: r["params"].get(k) for k in keys}, "seed": r["seed"], **({"gamma": r["fit"].get("gamma"),
                            "gamma_err": r["fit"].get("gamma_err"), "band": r["fit"].get("band"),
                            "power_law": r["fit"].get("power_law", True), "flags": r["fit"].get("flags", [])} if "gamma" in r["fit"] else
                            {"fit_error": r["fit"].get("error")}), "mean_velocity": r.get("mean_velocity"),
                            "wall_s": r["wall_s"]} for r in results],
               "failures": [{"params": f["params"], "seed": f["seed"], "error": f["error"]} for f in failures]}
    text = paragraphs([esc(spec.description)]) if spec.description else ""
    rows = [[*(f"{r['params'].get(k):.4g}" if isinstance(r["params"].get(k), float) else str(r["params"].get(k)) for k in keys),
             str(r["seed"]), (f"{r['fit']['gamma']:.3f} &plusmn; {r['fit']['gamma_err']:.3f}{flag_mark(r['fit'])}" if "gamma" in r["fit"] else "-"),
             (f"{span(r['fit']['band'][0], r['fit']['band'][1])}" if "band" in r["fit"] else esc(r["fit"].get("error", ""))),
             f"{r['wall_s']:.2f}"] for r in results]
    text += table("Runs", [*keys, "seed", "gamma (95 %)", "band (rad/s)", "wall (s)"], rows)
    if failures:
        text += table("Failed tasks (rerun the sweep to retry them)", ["parameters", "seed", "error"],
                      [[esc(json.dumps(f["params"])), str(f["seed"]), esc(f["error"])] for f in failures])
    out = [StudyResult("results", f"Sweep {spec.name} ({spec.target})", {}, html=text)]
    if spec.analysis.get("wear"):  # the wear study's cells, figure and answer (compare/report/wear_study.py)
        from .wear_study import study_sections
        sections, summary["wear_study"] = study_sections(spec, results)
        out += sections
    if "vibration.amplitude" in keys:  # a vibration sweep with its unshaken twins (compare/report/vibration.py)
        from .vibration import cells, section
        rows = cells(results)
        if rows:
            out.append(section(rows))
            summary["vibration"] = rows
    vs = sorted({float(r["v"]) for r in results}) if results and all("v" in r for r in results) else []
    if "v" in keys and len(vs) >= 2:
        a = spec.analysis
        va = velocity_analysis(results, tuple(a.get("omega_ref", (70.0, 140.0))), a.get("omega_max"))
        summary["velocity_analysis"] = va
        mk = lambda r: Spectrum(omega=np.asarray(r["omega"]), C=np.asarray(r["C"]), quantity="x", unit="m^2 s",  # noqa: E731
                                n_avg=np.asarray(r["n_avg"]), dof=2.0, provenance={"log_mean_C": np.log(r["C"])})
        first = {}
        for r in sorted(results, key=lambda r: r["v"]):
            first.setdefault(r["v"], r)
        f1 = plots.spectrum_figure([(mk(r), f"v = {1e3 * v:g} mm/s") for v, r in first.items()],
                                   title="C_x in the frequency domain", band=tuple(va["omega_ref"]))
        dist = []
        for v, r in first.items():
            w = np.asarray(r["omega"])
            dist.append((Spectrum(omega=w / v, C=np.asarray(r["C"]) * v, quantity="x", unit="m^3", n_avg=np.asarray(r["n_avg"]),
                                  dof=2.0), f"v = {1e3 * v:g} mm/s"))
        f2 = plots.spectrum_figure(dist, title="distance domain: v C_x against q = omega / v", ylabel=r"$v\,C_x$ (m$^3$)")
        f2.axes[0].set_xlabel(r"$q = \omega / v$ (1/m)")
        f3 = plots.level_figure(np.asarray(va["velocities"]), np.exp(va["ln_C_at_omega_ref"]), va["exponent"],
                                va["exponent_err"], va["omega_ref"])
        text = paragraphs([
            f"C_x averaged over {va['omega_ref'][0]:g}-{va['omega_ref'][1]:g} rad/s grows as v^{va['exponent']:.3f} &plusmn; "
            f"{va['exponent_err']:.3f} (95 %); eq. (6) predicts v^3 for model I when eta1 follows steady sliding; the "
            "paper measures v^(5/3) for rubber on concrete (Fig. 15).",
            f"Collapse: the mean spread (std of ln C across velocities) is {va['spread_frequency_domain']:.3f} in the "
            f"frequency domain and {va['spread_distance_domain']:.3f} in the distance domain (q = omega / v, C_s = v C_x): "
            f"the distance domain reduces it {va['collapse_gain']:.1f}x.",
        ])
        figs = (Figure("sweep_frequency_domain", plots.figure_png_bytes(f1),
                       f"C_x at each of {len(first)} velocities in the frequency domain; the shaded band is where the level "
                       f"is read (spread of ln C across velocities {va['spread_frequency_domain']:.2f})."),
                Figure("sweep_distance_domain", plots.figure_png_bytes(f2),
                       f"The same spectra in the distance domain (v C_x against q = omega / v): spread "
                       f"{va['spread_distance_domain']:.2f}, {va['collapse_gain']:.1f}x smaller than in frequency."),
                Figure("sweep_level_vs_v", plots.figure_png_bytes(f3),
                       f"C_x at fixed omega against v: v^{va['exponent']:.2f} ± {va['exponent_err']:.2f} (eq. 6 for model I: "
                       "v^3; rubber on concrete, paper Fig. 15: v^(5/3))."))
        out.append(StudyResult("velocity_analysis", "Velocity analysis (paper section 2, eq. 6, Fig. 15)", va, figs, text))
    return out, summary


def write_sweep_outputs(out_dir, results, summary):
    """index.html, summary.json, results.csv/.json and figures/ beside the task cache (each file atomic)."""
    import csv
    import io

    out = Path(out_dir)
    (out / "figures").mkdir(parents=True, exist_ok=True)

    from frictionnoise.base import atomic_write as atomic

    for r in results:
        for f in r.figures:
            atomic(out / "figures" / f"{f.name}.png", f.png)
    rows = summary["results"]
    buf = io.StringIO()
    if rows:
        cols = list(dict.fromkeys(k for r in rows for k in r))
        w = csv.DictWriter(buf, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({k: json.dumps(v) if isinstance(v, list) else v for k, v in r.items()})
    atomic(out / "results.csv", buf.getvalue().encode())
    atomic(out / "results.json", json_text(rows, indent=1).encode())
    atomic(out / "summary.json", json_text(summary).encode())
    atomic(out / "index.html", page(results, {"version": summary["version"], "seed": "per task", "quick": False},
                                    title=f"frictionnoise sweep {summary.get('sweep', '')}").encode())
    return out
