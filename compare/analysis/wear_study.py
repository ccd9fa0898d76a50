"""The wear study's statistics: do wear particles steepen an omega^-4 spectrum, as section 10 of Xu, Zhou &
Persson (Soft Matter 21, 7594, 2025) proposes, and do cavities reduce their effect (section 11)?

A sweep with ``[analysis] wear = true`` uses three parts:

- :func:`expand_factors`: the study's named factors in a sweep grid, ``study.size`` (narrow, broad, power) and
  ``study.track`` (smooth, cavities), written as the scenario fields they stand for;
- :func:`task_stats`: what one scenario task returns beside its C_x fit: C_x band levels (3 log bands over the fit
  band, 3-30 v/a), the exponents of C_F for the grains' summed force on the pads and for the pads' whole friction
  force, the time fractions trapped and moving, the covered length fraction, model II (eq. B2) built from the
  task's own episodes against the grains' measured C_F per band, the energy residual (flagged above 1 %), the grain
  step rule, the cost;
- :func:`cells`, :func:`mass_sensitivity`, :func:`mass_split` and :func:`widen`: per cell (count, size, track) over
  seeds, gamma with its 95 % interval, the rise of gamma against the particle-free twin (same track and seed) with
  its interval, the C_x level against the twin, model II per cell, and the grain-mass systematic.

Pure numerics; the pages and the figure are :mod:`compare.report.wear_study`'s.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["SIZES", "TRACKS", "expand_factors", "task_stats", "cells", "mass_sensitivity", "mass_split", "widen", "mean_interval",
           "N_BANDS", "REGIMES"]

# The size distributions: radii (m) in [20, 200] um; r_min = 20 um is the tunnelling limit at dt = 1e-4 s.
SIZES = {
    "narrow": {"wear.distribution": "lognormal", "wear.r_median": 50e-6, "wear.sigma": 0.2, "wear.r_min": 20e-6,
               "wear.r_max": 200e-6},
    "broad": {"wear.distribution": "lognormal", "wear.r_median": 50e-6, "wear.sigma": 0.8, "wear.r_min": 20e-6,
              "wear.r_max": 200e-6},
    "power": {"wear.distribution": "power", "wear.exponent": 3.0, "wear.r_min": 20e-6, "wear.r_max": 200e-6},
}
# Track types: smooth patches (the base scene) or a flat-bottomed cavity in every other patch (the scenario's pit
# widths and depth); their particle-free exponents: `python -m compare.studies.wear_base_scene`, and the quick
# study's page docs/results/wear_study_quick.md.
TRACKS = {"smooth": {"substrate.pit_p": 0.0}, "cavities": {"substrate.pit_p": 0.5}}
_FACTORS = {"study.size": SIZES, "study.track": TRACKS}
N_BANDS = 3  # log bands of C_x and C_F over the fit band
REGIMES = ("trapped", "wedged", "pushed")  # engine_sim.wear.wedge_regime: what the pad's front does to a grain


def expand_factors(model: dict) -> dict:
    """Scenario parameters with ``study.size`` and ``study.track`` replaced by the fields they stand for.
    Raises ValueError naming the factor for an unknown value or key."""
    out = {}
    for k, v in model.items():
        if k.startswith("study."):
            table = _FACTORS.get(k)
            if table is None:
                raise ValueError(f"unknown study factor {k!r}; valid: {', '.join(sorted(_FACTORS))}")
            if v not in table:
                raise ValueError(f"{k} = {v!r}: valid values are {', '.join(table)}")
            out.update(table[v])
        else:
            out[k] = v
    return out


def _fit(t, y, band, force: bool):
    """The record model's gamma of one record over ``band`` (a force through its running sum), or the error."""
    from .record_model import fit_series
    try:
        f = fit_series(t, y, band=band, quantity="F" if force else "x", integrate=force)
        return {"gamma": f.gamma, "gamma_err": f.gamma_err, "power_law": f.power_law}
    except ValueError as e:
        return {"error": str(e)}


def _nperseg(n: int) -> int:
    """Welch segment length: the pipeline's default, raised to 2^floor(log2(n / 2)) up to 2048 samples, so a short
    run (3 s at 1 ms) resolves the band's bottom (3 v/a = 15 rad/s needs segments of 0.42 s or more) in the band
    levels. The exponents are the record model's, on the record itself, whatever the segment length."""
    from .estimators import default_nperseg
    return max(default_nperseg(n), min(2048, 2 ** int(math.floor(math.log2(max(n, 2) / 2)))))


def task_stats(tr, sc, band) -> dict:
    """One scenario task's wear statistics (JSON-ready, SI): see the module docstring. ``band`` (rad/s) is the
    task's C_x fit band; the C_F exponents are fitted over it too (C_F ~ omega^-exponent)."""
    from .spectra import band_average, displacement_spectrum, force_series_spectrum
    from .balances import balances
    from .episodes import episodes, model_II_from_episodes

    edges = np.logspace(np.log10(band[0]), np.log10(band[1]), N_BANDS + 1)
    nper = _nperseg(tr.t.size)
    sx = displacement_spectrum(tr.t, tr.x, nperseg=nper)
    bal = balances(tr)
    gs = tr.metadata["scene"].get("grain_step", {})
    w = sc.wear
    out = {"edges": edges.tolist(), "Cx_bands": band_average(sx, edges).tolist(), "fit_x": _fit(tr.t, tr.x, band, False),
           "nperseg": nper, "fit_CF_friction": _fit(tr.t, tr.F_t, band, True),
           "energy_balance_rel": bal["energy_balance_rel"], "energy_flag": bool(abs(bal["energy_balance_rel"]) > 0.01),
           "force_balance_rel": bal["force_balance_rel"], "count": int(w.count), "grain_step": gs,
           "wall_per_sim_s": float(tr.metadata["wall_s"]) / (sc.run.duration + sc.run.warmup)}
    if tr.p_force.shape[1] == 0:
        return out
    Fg = tr.p_force.sum(axis=1)
    sg = force_series_spectrum(tr.t, Fg, nperseg=nper)
    dt_out = float(tr.t[1] - tr.t[0])
    ep = episodes(tr.p_state, tr.p_force, dt_out)
    pred = model_II_from_episodes(ep, float(tr.t[-1] - tr.t[0]), sg.omega)
    radii = np.asarray(tr.metadata["wear"]["radii_m"])
    from engine_sim.wear import wedge_regime
    regimes = [wedge_regime(r, sc.pads.radius, w.mu_pad, w.mu_track)[0] for r in radii]
    out.update({
        "fit_CF_grains": _fit(tr.t, Fg, band, True), "CFg_bands": band_average(sg, edges).tolist(),
        "B2_bands": band_average(sg, edges, pred).tolist(), "F_g_mean": float(Fg.mean()),
        # the grains' force split by their state: in the light limit only the trapped part survives (a pushed or wedged
        # grain's force falls with its mass; python -m compare.studies.wear_light_limit)
        "F_g_trapped": float((tr.p_force * (tr.p_state == 1)).sum(axis=1).mean()),
        "F_g_moving": float((tr.p_force * (tr.p_state == 2)).sum(axis=1).mean()),
        # at the mean patch friction; the patches' spread moves a grain between regimes (engine_sim.wear.regime_shares)
        "regime_fractions": {k: regimes.count(k) / len(regimes) for k in REGIMES},
        "trapped_frac": float(np.mean(tr.p_state == 1)), "moving_frac": float(np.mean(tr.p_state == 2)),
        # grains' summed diameters over the length of the tracks' windows they live in (behind + ahead of each pad)
        "covered_fraction": float(2 * radii.sum() / (sc.pads.N * (w.ahead + w.behind))),
        "grain_overlap_max_m": float(tr.particle_penetration.max()),
        "left_interface": int(tr.metadata["wear"]["left_interface"]), "episodes": int(ep["tau"].size),
    })
    return out


def _t95(n: int) -> float:
    from scipy.stats import t
    return float(t.ppf(0.975, n - 1)) if n > 1 else float("inf")


def mean_interval(x, errs):
    """Mean of per-seed values and its 95 % half-width: the larger of the seed scatter's (t quantile) and the
    per-seed intervals' (errs, 95 % each, combined in quadrature over the mean)."""
    x, errs = np.asarray(x, float), np.asarray(errs, float)
    n = x.size
    fit_part = float(np.sqrt(np.sum(errs**2)) / n)
    seed_part = _t95(n) * float(x.std(ddof=1)) / math.sqrt(n) if n > 1 else float("nan")
    return float(x.mean()), max(fit_part, seed_part) if n > 1 else fit_part, seed_part, fit_part


def _key(r):
    p = r["params"]
    return (int(p.get("wear.count", r["wear"]["count"])), p.get("study.size", "-"), p.get("study.track", "-"))


def cells(results: list) -> list:
    """Per cell (count, size, track): seeds, gamma and its interval, the rise against the particle-free twin (same
    track and seed, paired), the C_x level against the twin per band (paired ratio, geometric mean over seeds),
    C_F exponents, fractions, model II (grains' C_F / B2 per band, geometric mean over seeds), energy flags, cost."""
    ok = [dict(r, fit=r["wear"]["fit_x"]) for r in results if "gamma" in r.get("wear", {}).get("fit_x", {})]
    twins = {}
    for r in ok:
        c, _, track = _key(r)
        if c == 0:
            twins.setdefault((track, r["seed"]), r)
    by = {}
    for r in ok:
        c, size, track = _key(r)
        key = (0, "-", track) if c == 0 else (c, size, track)  # the twin is one run per track and seed, whatever the size
        if c == 0 and any(x["seed"] == r["seed"] for x in by.get(key, [])):
            continue
        by.setdefault(key, []).append(r)
    out = []
    for (count, size, track), rs in sorted(by.items(), key=lambda kv: (kv[0][2], kv[0][1], kv[0][0])):
        rs = sorted(rs, key=lambda r: r["seed"])
        g, ge = [r["fit"]["gamma"] for r in rs], [r["fit"]["gamma_err"] for r in rs]
        gm, gi, g_seed, g_fit = mean_interval(g, ge)
        row = {"count": count, "size": size, "track": track, "seeds": [r["seed"] for r in rs], "n": len(rs),
               "gamma": gm, "gamma_err": gi, "gamma_err_seeds": g_seed, "gamma_err_fits": g_fit,
               "gamma_per_seed": g, "flagged_fits": sum(not r["fit"].get("power_law", True) for r in rs),
               "energy_resid_max": max(abs(r["wear"]["energy_balance_rel"]) for r in rs),
               "energy_flagged": sum(r["wear"]["energy_flag"] for r in rs),
               "wall_per_sim_s": float(np.mean([r["wear"]["wall_per_sim_s"] for r in rs])),
               "substeps": rs[0]["wear"]["grain_step"].get("substeps")}
        for name in ("fit_CF_friction", "fit_CF_grains"):
            fs = [r["wear"].get(name, {}) for r in rs]
            if all("gamma" in f for f in fs):
                m, i, _, _ = mean_interval([f["gamma"] for f in fs], [f["gamma_err"] for f in fs])
                row[name] = {"exponent": m, "err": i}
        paired = [(r, twins.get((track, r["seed"]))) for r in rs]
        paired = [(r, t) for r, t in paired if t is not None]
        if count > 0 and paired:
            d = [r["fit"]["gamma"] - t["fit"]["gamma"] for r, t in paired]
            de = [math.hypot(r["fit"]["gamma_err"], t["fit"]["gamma_err"]) for r, t in paired]
            dm, di, d_seed, d_fit = mean_interval(d, de)
            ratio = np.exp(np.mean([np.log(np.asarray(r["wear"]["Cx_bands"]) / np.asarray(t["wear"]["Cx_bands"]))
                                    for r, t in paired], axis=0))
            row.update({"delta_gamma": dm, "delta_gamma_err": di, "delta_gamma_err_seeds": d_seed,
                        "delta_gamma_err_fits": d_fit, "delta_gamma_per_seed": d, "Cx_ratio_bands": ratio.tolist()})
        if count > 0:
            row["B2_ratio_bands"] = np.exp(np.mean([np.log(np.asarray(r["wear"]["CFg_bands"]) / np.asarray(r["wear"]["B2_bands"]))
                                                    for r in rs], axis=0)).tolist()
            for q in ("trapped_frac", "moving_frac", "covered_fraction", "F_g_mean", "F_g_trapped", "F_g_moving"):
                if all(q in r["wear"] for r in rs):
                    row[q] = float(np.mean([r["wear"][q] for r in rs]))
            if all("regime_fractions" in r["wear"] for r in rs):
                row["regime_fractions"] = {k: float(np.mean([r["wear"]["regime_fractions"][k] for r in rs])) for k in REGIMES}
            row["left_interface"] = sum(r["wear"]["left_interface"] for r in rs)
            row["grain_overlap_max_m"] = max(r["wear"]["grain_overlap_max_m"] for r in rs)
        out.append(row)
    return out


def mass_sensitivity(rows: list, rows_other: list, decades: float) -> dict:
    """How gamma moves with the grains' mass: cells run at another mass (``rows_other``, ``decades`` decades of mass
    away, signed: +1 for ten times heavier) against the same cells of ``rows``, paired by seed (same seed: same
    substrate, radii and starting places). Per track: the pooled change of gamma per decade with its 95 % interval
    (seed scatter, t quantile) and the systematic half-width it implies for one decade, |change| + interval (the
    largest shift the pairs allow at 95 %); per cell: its own mean change. The particle-free twins carry no grains,
    so a rise against them moves as gamma does. The pooled interval treats the pairs as independent, though the
    cells of one seed share its substrate, and pools cells whose changes may differ: read it as the scale of the mass
    effect, not its law. One decade is what was measured; the light limit lies further (a pushed grain's force needs
    about 1e-7 kg to vanish, two decades below the study's 1e-5 kg), so the widened interval is a floor on the mass
    uncertainty, not a bound."""
    if not decades:
        raise ValueError("mass_sensitivity: the two sweeps have the same grain mass (decades = 0)")
    other = {(r["count"], r["size"], r["track"]): r for r in rows_other if r["count"] > 0}
    out = {"decades": decades, "cells": [], "tracks": {}}
    for r in rows:
        o = other.get((r["count"], r["size"], r["track"]))
        if o is None:
            continue
        g = dict(zip(r["seeds"], r["gamma_per_seed"]))
        d = [(go - g[s]) / decades for s, go in zip(o["seeds"], o["gamma_per_seed"]) if s in g]
        if d:
            out["cells"].append({"count": r["count"], "size": r["size"], "track": r["track"], "per_decade": d,
                                 "mean": float(np.mean(d))})
    for track in TRACKS:
        d = [x for c in out["cells"] if c["track"] == track for x in c["per_decade"]]
        if len(d) > 1:
            m, _, seed_part, _ = mean_interval(d, [0.0] * len(d))
            out["tracks"][track] = {"per_decade": m, "err": seed_part, "n": len(d), "systematic": abs(m) + seed_part}
    return out


def mass_split(results: list, results_other: list) -> list:
    """The grains' force split by state at two grain masses, per cell (count, size, track), paired by seed: the mean
    trapped and moving parts at each mass (N), their ratios other / this (geometric mean over the seeds; per seed
    too), the moving part's share of the grains' force, and the C_x band levels' ratio. In the light limit the
    moving part vanishes (a pushed or wedged grain's force goes with its mass) and the trapped part stays
    (``python -m compare.studies.wear_light_limit``, one pad): so the trapped part is this scene's light-limit
    estimate of the grains' force, a trapped ratio near 1 says it holds in the 30-pad scene too, and the moving share is how
    far the total sits above it."""
    def by_seed(rs):
        out = {}
        for r in rs:
            w = r.get("wear", {})
            if w.get("count") and "F_g_trapped" in w:
                c, size, track = _key(r)
                out.setdefault((c, size, track), {})[r["seed"]] = w
        return out

    a, b = by_seed(results), by_seed(results_other)
    rows = []
    for key in sorted(set(a) & set(b), key=lambda k: (k[2], k[1], k[0])):
        seeds = sorted(set(a[key]) & set(b[key]))
        if not seeds:
            continue
        wa, wb = [a[key][s] for s in seeds], [b[key][s] for s in seeds]

        def ratio(q):
            per = [y[q] / x[q] if x[q] > 0 else float("nan") for x, y in zip(wa, wb)]
            return per, float(np.exp(np.mean(np.log(per))))

        tr_per, tr = ratio("F_g_trapped")
        mv_per, mv = ratio("F_g_moving")
        cx = np.exp(np.mean([np.log(np.asarray(y["Cx_bands"]) / np.asarray(x["Cx_bands"])) for x, y in zip(wa, wb)],
                            axis=0))
        share = [float(np.mean([w["F_g_moving"] / (w["F_g_moving"] + w["F_g_trapped"]) for w in ws])) for ws in (wa, wb)]
        rows.append({"count": key[0], "size": key[1], "track": key[2], "seeds": seeds,
                     "F_trapped": [float(np.mean([w["F_g_trapped"] for w in ws])) for ws in (wa, wb)],
                     "F_moving": [float(np.mean([w["F_g_moving"] for w in ws])) for ws in (wa, wb)],
                     "trapped_ratio": tr, "trapped_ratio_per_seed": tr_per, "moving_ratio": mv,
                     "moving_ratio_per_seed": mv_per, "moving_share": share, "Cx_ratio_bands": cx.tolist()})
    return rows


def widen(rows: list, sens: dict) -> list:
    """The cells with their gamma and rise intervals widened by one decade of grain mass: the track's systematic
    half-width (:func:`mass_sensitivity`) added in quadrature to the statistical one (``*_err_total``)."""
    out = []
    for r in rows:
        t = sens["tracks"].get(r["track"])
        if t is None or r["count"] == 0:
            out.append(r)
            continue
        r = dict(r, mass_systematic=t["systematic"], gamma_err_total=math.hypot(r["gamma_err"], t["systematic"]))
        if "delta_gamma" in r:
            r["delta_gamma_err_total"] = math.hypot(r["delta_gamma_err"], t["systematic"])
        out.append(r)
    return out
