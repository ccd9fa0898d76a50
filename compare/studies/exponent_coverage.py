"""Coverage of the exponent's 95 % interval on records as laboratories take them; rebuilds
docs/results/exponent_coverage.md.

Records: exact sampled omega^-gamma processes (compare.analysis.synthetic.power_law_record, dt = 1 ms, A = 1) for
gamma = 2, 4, 6, with a white floor that is absent, meets the power law at Nyquist ("at Nyquist"), or meets it at the
geometric middle of the resolved band ("dominant": the floor is above the power law over the upper half of the
decades). Every record is fitted by the record model (compare.analysis.record_model.fit_record, debiased Whittle with
a floor) and by the spectrum-and-band estimator that analyze used before it (compare.analysis.fits.fit_power_law on
displacement_spectrum, automatic band). The Cramer-Rao half-width is 1.96 sqrt([F^-1]_gamma,gamma) with F the
Whittle Fisher information of the true debiased expected periodogram for (gamma, ln A, B) over all ordinates, the
floor free (also where it is zero: the bound of an estimator that does not know there is none), and known (the
bound of one told the floor).

    python -m compare.studies.exponent_coverage --seeds 200       # the page (minutes per cell at 2^16)
    python -m compare.studies.exponent_coverage --quick --out t.md  # CI smoke: 2 seeds at 2^10, a few seconds
    python -m compare.studies.exponent_coverage --seeds 80 --lengths 12,14 --rows a.json   # runs in pieces,
    python -m compare.studies.exponent_coverage --combine a.json b.json                    # then one page

Binomial criterion: a cell is rejected when its coverage count is below the 0.0005 or above the 0.9995 quantile of
Binomial(seeds, 0.95) (two-sided p < 0.001).
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np
from scipy import stats

from compare.analysis.fits import fit_power_law
from compare.analysis.power_floor import PowerFloorProfile
from compare.analysis.record_model import fit_record
from compare.analysis.spectra import displacement_spectrum
from compare.analysis.synthetic import power_law_record
from compare.analysis.whittle import WhittleRecord, order_for

DT = 1e-3
GAMMAS = (2.0, 4.0, 6.0)
FLOORS = ("none", "at Nyquist", "dominant")
PAGE = Path(__file__).resolve().parents[2] / "docs" / "results" / "exponent_coverage.md"
CRITERION = ("Columns: coverage of the 95 % profile-likelihood interval; a cell is rejected when its count of covering "
             "intervals lies outside the 0.0005-0.9995 quantiles of Binomial(seeds, 0.95) (two-sided p < 0.001); bias "
             "the mean estimate less the truth; the ratio is the median half-width over the Cramer-Rao half-width with "
             "the floor free; flagged: the record model's flags (bend or split test, split-half; the split-half test is "
             "skipped here and runs in the model I-like records below); min decades: the narrowest identified band; old: "
             "fit_power_law's automatic band on the Welch spectrum, its 95 % half-width (in brackets: over the Cramer-Rao "
             "half-width with the floor free) and flags. With fewer seeds than 1000 per cell the coverage criterion is the "
             "binomial one; the bias criterion (|mean bias| below a quarter of the median half-width) is read only where "
             "the mean's own scatter, half-width / (1.96 sqrt(seeds)), is below that quarter (seeds >= 62); with fewer "
             "seeds a cell does not test it.")


def floor_rms(n: int, gamma: float, where: str) -> float:
    """The floor's rms (m) for A = 1: B = omega_x^-gamma at the crossover omega_x, rms = sqrt(2 pi B / dt)."""
    if where == "none":
        return 0.0
    w1, wn = 2 * math.pi / (n * DT), math.pi / DT
    wx = wn if where == "at Nyquist" else math.sqrt(w1 * wn)
    return math.sqrt(2 * math.pi * wx ** -gamma / DT)


def cramer_rao(n: int, gamma: float, rms: float, floor_free: bool = True) -> float:
    """1.96 sqrt([F^-1]_gg): F_ab = sum_j d ln Ibar_j/da d ln Ibar_j/db over the Fourier ordinates of the true
    debiased expectation (the Whittle information; exact for independent exponential ordinates)."""
    k = order_for(gamma)
    rec = WhittleRecord(np.zeros(n), DT, k)
    prof = PowerFloorProfile([rec], True)
    B = rms**2 * DT / (2 * math.pi)
    a, am = prof.unit(gamma)
    scale = (2 * math.pi / DT) ** -gamma
    pw = a * am * scale
    fl = prof.b * prof.b_mean * B  # prof.b is the unit floor's expectation over its mean
    S = pw + fl
    h = 1e-4
    dg = (np.log(prof.unit(gamma + h)[0] * prof.unit(gamma + h)[1] * (2 * math.pi / DT) ** -(gamma + h))
          - np.log(prof.unit(gamma - h)[0] * prof.unit(gamma - h)[1] * (2 * math.pi / DT) ** -(gamma - h))) / (2 * h)
    # d ln Ibar / d gamma at fixed A (C = A omega^-gamma): the power term's share times d ln(power term)/d gamma
    cols = [pw / S * dg, pw / S] + ([prof.b / S] if floor_free else [])  # d ln Ibar / d(gamma, ln A[, B])
    X = np.column_stack(cols)
    F = X.T @ X
    return 1.96 * math.sqrt(float(np.linalg.inv(F)[0, 0]))


def cell(n: int, gamma: float, where: str, seeds: int, old: bool, first: int = 0) -> dict:
    rms = floor_rms(n, gamma, where)
    t = np.arange(n) * DT
    new_g, new_lo, new_hi, new_flag, dec = [], [], [], 0, []
    old_g, old_h, old_flag = [], [], 0
    t0 = time.perf_counter()
    for seed in range(first, first + seeds):
        x = power_law_record(n, DT, gamma, floor_rms=rms, seed=seed)
        f = fit_record(x, DT, stationarity=False)
        new_g.append(f.gamma)
        new_lo.append(f.gamma_low)
        new_hi.append(f.gamma_high)
        new_flag += bool(f.flags)
        dec.append(f.decades)
        if old:
            try:
                o = fit_power_law(displacement_spectrum(t, x))
                old_g.append(o.gamma)
                old_h.append(o.gamma_err)
                old_flag += bool(o.flags)
            except ValueError:
                old_g.append(math.nan)
                old_h.append(math.nan)
                old_flag += 1
    wall = time.perf_counter() - t0
    g, lo, hi = np.array(new_g), np.array(new_lo), np.array(new_hi)
    hits = int(np.sum((lo <= gamma) & (gamma <= hi)))
    qlo, qhi = stats.binom.ppf(0.0005, seeds, 0.95), stats.binom.ppf(0.9995, seeds, 0.95)
    row = {"n": n, "gamma": gamma, "floor": where, "seeds": seeds, "hits": hits, "coverage": hits / seeds,
           "rejected": not (qlo <= hits <= qhi), "bias": float(g.mean() - gamma),
           "median_half": float(np.median(0.5 * (hi - lo))), "cr_half": cramer_rao(n, gamma, rms),
           "cr_known": cramer_rao(n, gamma, rms, floor_free=False),
           "flag_rate": new_flag / seeds, "min_decades": float(np.min(dec)), "wall_s": wall}
    if old:
        og, oh = np.array(old_g), np.array(old_h)
        ok = np.isfinite(og)
        row.update({"old_coverage": float(np.mean(np.abs(og[ok] - gamma) <= oh[ok])) if ok.any() else math.nan,
                    "old_bias": float(np.mean(og[ok]) - gamma) if ok.any() else math.nan,
                    "old_median_half": float(np.median(oh[ok])) if ok.any() else math.nan,
                    "old_flag_rate": old_flag / seeds})
    return row


def model1_like(records: int, floor_nm: float = 20.0) -> dict:
    """Records like scenarios/data/model1_synthetic_um.csv: 20000 samples at 100 Hz of a Gaussian process with
    model I's closed-form spectrum for the parameters that made that file (SpringBlockParams.reference(), its
    family in compare.analysis.families: omega^-2 below v/a, the renewal bump near 2 rad/s, the block's resonance
    at 548 rad/s folded to 80 rad/s), plus a white floor of ``floor_nm`` nm rms; fitted as analyze fits them
    (automatic band, stationarity test on). Coverage counts intervals holding 4, the exponent of the theory's
    omega^-4 range."""
    from compare.analysis.families import family_of
    from compare.analysis.synthetic import spectrum_record
    from reduced_models.spring_block import SpringBlockParams

    fam = family_of("model_I")
    theta, v = fam.from_model(SpringBlockParams.reference())
    dt = 0.01
    hits = flagged = 0
    halves, gammas, bands = [], [], []
    t0 = time.perf_counter()
    for seed in range(records):
        x = spectrum_record(20000, dt, lambda w: fam.spectrum(theta, w, v), 2, floor_rms=floor_nm * 1e-9, seed=seed)
        f = fit_record(x, dt)
        hits += f.gamma_low <= 4.0 <= f.gamma_high
        flagged += bool(f.flags)
        halves.append(f.gamma_err)
        gammas.append(f.gamma)
        bands.append(f.band)
    b = np.array(bands)
    return {"records": records, "floor_nm": floor_nm, "hits": hits, "flagged": flagged,
            "median_half": float(np.median(halves)), "mean_gamma": float(np.mean(gammas)),
            "band_low": [float(np.min(b[:, 0])), float(np.max(b[:, 0]))],
            "band_high": [float(np.min(b[:, 1])), float(np.max(b[:, 1]))], "wall_s": time.perf_counter() - t0}


def model1_text(m: dict) -> str:
    return (f"\n## Records like the shipped model I file\n\n{m['records']} records of 20000 samples at 100 Hz drawn "
            "from model I's closed-form spectrum for the parameters that made `scenarios/data/model1_synthetic_um.csv` "
            "(ω⁻² below v/a = 0.5 rad/s, the renewal bump near 2 rad/s, the resonance at 548 rad/s folded to "
            f"80 rad/s), with a {m['floor_nm']:g} nm rms white floor, fitted as `analyze` fits them (no `--band`): "
            f"the interval covers 4 in {m['hits']} ({100 * m['hits'] / m['records']:.0f} %), {m['flagged']} flagged "
            f"({100 * m['flagged'] / m['records']:.0f} %), mean γ {m['mean_gamma']:.3f}, median half-width "
            f"{m['median_half']:.3f}; the identified bands start at {m['band_low'][0]:.3g}-{m['band_low'][1]:.3g} "
            f"rad/s and end at {m['band_high'][0]:.3g}-{m['band_high'][1]:.3g} rad/s.\n")


def table(rows) -> str:
    head = ("| n | γ | floor | seeds | coverage | rejected (p<0.001) | bias | median half-width | Cramér-Rao, floor "
            "free / known | ratio | flagged | min decades | old coverage | old bias | old half-width | old flagged |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    out = []
    for r in rows:
        out.append(f"| 2^{int(math.log2(r['n']))} | {r['gamma']:g} | {r['floor']} | {r['seeds']} | "
                   f"{100 * r['coverage']:.1f} % | {'yes' if r['rejected'] else 'no'} | {r['bias']:+.4f} | "
                   f"{r['median_half']:.4f} | {r['cr_half']:.4f} / {r.get('cr_known', r['cr_half']):.4f} | "
                   f"{r['median_half'] / r['cr_half']:.2f} | "
                   f"{100 * r['flag_rate']:.0f} % | {r['min_decades']:.2f} | "
                   + (f"{100 * r['old_coverage']:.1f} % | {r['old_bias']:+.4f} | {r['old_median_half']:.4f} "
                      f"({r['old_median_half'] / r['cr_half']:.1f}×) | "
                      f"{100 * r['old_flag_rate']:.0f} % |" if "old_coverage" in r else "not run | | | |"))
    return head + "\n".join(out) + "\n"


def pooled(rows) -> str:
    hits, total = sum(r["hits"] for r in rows), sum(r["seeds"] for r in rows)
    lo = stats.beta.ppf(0.025, hits, total - hits + 1) if hits > 0 else 0.0
    hi = stats.beta.ppf(0.975, hits + 1, total - hits) if hits < total else 1.0
    return f"pooled coverage {100 * hits / total:.1f} % ({hits}/{total}; 95 % Clopper-Pearson {100 * lo:.1f}-{100 * hi:.1f} %)"


def claims(rows) -> str:
    """The page's claims read off its rows: cells rejected, the bias criterion (and where the seeds resolve it), the
    half-width over the Cramer-Rao bound, the narrowest band on a clean power law, and the old estimator beside."""
    rejected = [r for r in rows if r["rejected"]]
    biased = [r for r in rows if abs(r["bias"]) >= r["median_half"] / 4]
    resolved = [r for r in rows if r["seeds"] >= 62]
    failed = [r for r in biased if r["seeds"] >= 62]
    untested = [r for r in biased if r["seeds"] < 62]
    ratio = [r["median_half"] / r["cr_half"] for r in rows]
    clean = [r["min_decades"] for r in rows if r["floor"] == "none"]
    old = [r["old_median_half"] / r["cr_half"] for r in rows
           if "old_median_half" in r and math.isfinite(r["old_median_half"])]
    by_n = []
    for n in sorted({r["n"] for r in rows}):
        hits, seeds = sum(r["hits"] for r in rows if r["n"] == n), sum(r["seeds"] for r in rows if r["n"] == n)
        by_n.append(f"2^{int(math.log2(n))} {100 * hits / seeds:.1f} % ({hits}/{seeds})")
    text = (f"by length {', '.join(by_n)}; {len(rejected)} of {len(rows)} cells rejected at p < 0.001"
            + (" (" + ", ".join(f"2^{int(math.log2(r['n']))} γ {r['gamma']:g} {r['floor']}" for r in rejected) + ")"
               if rejected else "")
            + f"; |mean bias| below a quarter of the median half-width in {len(resolved) - len(failed)} of the "
            f"{len(resolved)} cells with 62 seeds or more"
            + (" (not in " + ", ".join(f"2^{int(math.log2(r['n']))} γ {r['gamma']:g} {r['floor']}" for r in failed) + ")"
               if failed else "")
            + (f", and in {len(rows) - len(resolved) - len(untested)} of the {len(rows) - len(resolved)} with fewer, "
               "which do not test it" if len(rows) > len(resolved) else "")
            + f"; median half-width over the Cramér-Rao bound {min(ratio):.2f}-{max(ratio):.2f}")
    if clean:
        text += f"; the narrowest band on a clean power law spans {min(clean):.2f} decades"
    if old:
        text += f"; the old estimator's median half-width {min(old):.1f}-{max(old):.1f}× the bound"
    return text


def merged(rows) -> list:
    """Rows of the same cell from runs on other seeds made one: counts added, means weighted by seeds, and the
    median half-width as the seed-weighted mean of the runs' medians."""
    out = {}
    for r in rows:
        key = (r["n"], r["gamma"], r["floor"])
        if key not in out:
            out[key] = dict(r)
            continue
        m, s0, s1 = out[key], out[key]["seeds"], r["seeds"]
        for k in ("bias", "median_half", "flag_rate", "old_coverage", "old_bias", "old_median_half", "old_flag_rate"):
            if k in m and k in r:
                m[k] = (m[k] * s0 + r[k] * s1) / (s0 + s1)
        m["hits"] += r["hits"]
        m["seeds"] = s0 + s1
        m["coverage"] = m["hits"] / m["seeds"]
        m["min_decades"] = min(m["min_decades"], r["min_decades"])
        qlo, qhi = stats.binom.ppf(0.0005, m["seeds"], 0.95), stats.binom.ppf(0.9995, m["seeds"], 0.95)
        m["rejected"] = not (qlo <= m["hits"] <= qhi)
    return list(out.values())


def write_page(rows, commands, wall, model1=None, path=PAGE) -> None:
    """The page (docs/results/exponent_coverage.md unless ``path``) from the rows of one or more runs (and the
    model I-like records)."""
    Path(path).write_text(
        "# Exponent coverage on lab-length records\n\n"
        f"Reproduce: {commands} ({wall / 60:.0f} min of wall time, one process at a time on 2 shared cores); `--quick --out FILE` writes "
        "the same table for 2 seeds at 2^10 samples in a few seconds (a smoke test, not a measurement).\n\n" + (__doc__.split("\n\n", 1)[1].split("    python -m")[0])
        + "\n" + CRITERION + f"\n\nResult: {pooled(rows)}; {claims(rows)}.\n\n" + table(rows) + (model1_text(model1) if model1 else ""))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="every cell at 2^10 samples with 2 seeds (a smoke test)")
    ap.add_argument("--out", default=None, metavar="MD", help="write the page here (default: the docs page; "
                    "--quick writes only here)")
    ap.add_argument("--seeds", type=int, default=200, help="seeds per cell")
    ap.add_argument("--lengths", default="12,14,16", help="log2 of the record lengths, comma-separated")
    ap.add_argument("--no-old", action="store_true", help="skip the spectrum-and-band estimator")
    ap.add_argument("--first-seed", type=int, default=0, help="seeds first-seed .. first-seed + seeds - 1")
    ap.add_argument("--rows", default=None, metavar="JSON", help="write the rows here instead of the page")
    ap.add_argument("--model1", type=int, default=0, metavar="N",
                    help="instead: N records like the shipped model I file (coverage and flags)")
    ap.add_argument("--combine", nargs="+", default=None, metavar="JSON",
                    help="write the page from the rows of earlier --rows runs (runs nothing)")
    args = ap.parse_args(argv)
    if args.combine:
        parts = [json.loads(Path(f).read_text()) for f in args.combine]
        rows = merged([r for p in parts for r in p.get("rows", [])])
        m1 = next((p["model1"] for p in parts if "model1" in p), None)
        write_page(rows, " and ".join(f"`{p['command']}`" for p in parts), sum(p["wall_s"] for p in parts), m1,
                   args.out or PAGE)
        return 0
    if args.model1:
        m = model1_like(args.model1)
        print(model1_text(m))
        if args.rows:
            Path(args.rows).write_text(json.dumps({"model1": m, "wall_s": m["wall_s"], "command":
                                                   f"python -m compare.studies.exponent_coverage --model1 {args.model1}"}))
        return 0
    lengths = [2**10] if args.quick else [2 ** int(s) for s in args.lengths.split(",")]
    seeds = 2 if args.quick else args.seeds
    rows = []
    t0 = time.perf_counter()
    cmd = ("python -m compare.studies.exponent_coverage --quick" if args.quick else
           f"python -m compare.studies.exponent_coverage --seeds {seeds} --lengths {args.lengths}"
           + (" --no-old" if args.no_old else "") + (f" --first-seed {args.first_seed}" if args.first_seed else ""))
    for n in lengths:
        for g in GAMMAS:
            for where in FLOORS:
                rows.append(cell(n, g, where, seeds, not args.no_old, args.first_seed))
                print(table(rows[-1:]).splitlines()[-1], flush=True)
                if args.rows and not args.quick:  # every cell as it ends: a long run can be stopped and combined
                    Path(args.rows).write_text(json.dumps(
                        {"rows": rows, "command": cmd, "wall_s": time.perf_counter() - t0}, indent=1))
    wall = time.perf_counter() - t0
    print(pooled(rows))
    if args.rows or (args.quick and not args.out):
        return 0
    write_page(rows, f"`{cmd}`", wall, path=args.out or PAGE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
