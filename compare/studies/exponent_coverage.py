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

    python -m compare.studies.exponent_coverage --quick --out t.md  # CI smoke: 2 seeds at 2^10, a few seconds
    python -m compare.studies.exponent_coverage --seeds 20 --first-seed 100 --lengths 16 --workers 2 --rows a.json
    python -m compare.studies.exponent_coverage --combine p0.json p16.json p18.json a.json

The page is made of parts, each a JSON file of rows that carry their per-seed records (runs with --rows, which
store every seed over all cells as it ends, so a run can be stopped at any time; the page's earliest rows were read
back from the page with --from-page and carry none); --combine merges the rows of one cell over its parts' seeds and
writes the page, so more seeds are one more run on new seeds and one more --combine. The parts are the user's files
(none is tracked: the page is the record; --from-page reads its rows back into a part). --workers N fits the records in N processes; every record depends on its
cell and seed only, so the rows are those of one process.

Binomial criterion: a cell is rejected when its coverage count is below the 0.0005 or above the 0.9995 quantile of
Binomial(seeds, 0.95) (two-sided p < 0.001).
"""
from __future__ import annotations

import argparse
import functools
import json
import math
import os
import time
from concurrent.futures import ProcessPoolExecutor
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


@functools.lru_cache(maxsize=None)
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


def seed_record(n: int, gamma: float, where: str, seed: int, old: bool) -> dict:
    """One record of one cell fitted: the record model's estimate, interval, flags and band width (decades), and
    with ``old`` the spectrum-and-band estimator's estimate, half-width and flags (NaN where it fails). The record
    depends on (n, gamma, where, seed) only, so seeds can be run apart, in any order or process, and merged."""
    rms = floor_rms(n, gamma, where)
    x = power_law_record(n, DT, gamma, floor_rms=rms, seed=seed)
    f = fit_record(x, DT, stationarity=False)
    rec = {"seed": seed, "gamma": float(f.gamma), "low": float(f.gamma_low), "high": float(f.gamma_high),
           "flagged": bool(f.flags), "decades": float(f.decades)}
    if old:
        try:
            o = fit_power_law(displacement_spectrum(np.arange(n) * DT, x))
            rec.update({"old_gamma": float(o.gamma), "old_half": float(o.gamma_err), "old_flagged": bool(o.flags)})
        except ValueError:
            rec.update({"old_gamma": math.nan, "old_half": math.nan, "old_flagged": True})
    return rec


def summary(n: int, gamma: float, where: str, records: list, wall: float = 0.0) -> dict:
    """A cell's row from its seeds' records (taken in seed order; a seed given twice is an error): the count of
    intervals holding ``gamma`` and its binomial test, the mean bias, the median half-width beside the Cramer-Rao
    half-widths, the flag rate, the narrowest band and the old estimator's columns. The per-seed records travel
    with the row (``records``) so that runs on other seeds merge exactly."""
    records = sorted(records, key=lambda r: r["seed"])
    seeds = len(records)
    if len({r["seed"] for r in records}) != seeds:
        raise ValueError(f"cell 2^{int(math.log2(n))} gamma {gamma:g} {where}: a seed appears twice")
    rms = floor_rms(n, gamma, where)
    g = np.array([r["gamma"] for r in records])
    lo, hi = np.array([r["low"] for r in records]), np.array([r["high"] for r in records])
    hits = int(np.sum((lo <= gamma) & (gamma <= hi)))
    qlo, qhi = stats.binom.ppf(0.0005, seeds, 0.95), stats.binom.ppf(0.9995, seeds, 0.95)
    row = {"n": n, "gamma": gamma, "floor": where, "seeds": seeds, "hits": hits, "coverage": hits / seeds,
           "rejected": not (qlo <= hits <= qhi), "bias": float(g.mean() - gamma),
           "median_half": float(np.median(0.5 * (hi - lo))), "cr_half": cramer_rao(n, gamma, rms),
           "cr_known": cramer_rao(n, gamma, rms, floor_free=False),
           "flag_rate": sum(r["flagged"] for r in records) / seeds,
           "min_decades": float(np.min([r["decades"] for r in records])), "wall_s": wall}
    if all("old_gamma" in r for r in records):
        og, oh = np.array([r["old_gamma"] for r in records]), np.array([r["old_half"] for r in records])
        ok = np.isfinite(og)
        row.update({"old_coverage": float(np.mean(np.abs(og[ok] - gamma) <= oh[ok])) if ok.any() else math.nan,
                    "old_bias": float(np.mean(og[ok]) - gamma) if ok.any() else math.nan,
                    "old_median_half": float(np.median(oh[ok])) if ok.any() else math.nan,
                    "old_flag_rate": sum(r["old_flagged"] for r in records) / seeds})
    row["records"] = records
    return row


def _seed_task(task):
    """One seed_record call and its wall time (s), for a process pool."""
    t0 = time.perf_counter()
    return seed_record(*task), time.perf_counter() - t0


def cell(n: int, gamma: float, where: str, seeds: int, old: bool, first: int = 0, pool=None) -> dict:
    """The row of one cell over seeds ``first`` .. ``first + seeds - 1``, the records fitted in this process or,
    given ``pool`` (a concurrent.futures executor), spread over its workers; the row is the same either way."""
    t0 = time.perf_counter()
    tasks = [(n, gamma, where, seed, old) for seed in range(first, first + seeds)]
    records = [r for r, _ in (pool.map(_seed_task, tasks) if pool is not None else map(_seed_task, tasks))]
    return summary(n, gamma, where, records, time.perf_counter() - t0)


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
        if "line" in r:  # a row read back from the page (page_rows): printed as it stood
            out.append(r["line"])
            continue
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


def _where_narrowest(rows, where: str) -> str:
    """Where the narrowest band of the cells with floor ``where`` lies, as " (2^16 seed 40, γ 2 4 6)", when the
    per-seed records that reach it are at hand; "" otherwise."""
    cells = [r for r in rows if r["floor"] == where]
    low = min(r["min_decades"] for r in cells)
    hit = [(r, x) for r in cells for x in r.get("records", r.get("part_records", [])) if x["decades"] == low]
    if not hit:
        return ""
    n = {r["n"] for r, _ in hit}
    seeds = sorted({x["seed"] for _, x in hit})
    return (f" ({', '.join(f'2^{int(math.log2(v))}' for v in sorted(n))} seed {', '.join(map(str, seeds))}, "
            f"γ {' '.join(f'{g:g}' for g in sorted({r['gamma'] for r, _ in hit}))})")


def claims(rows) -> str:
    """The page's claims read off its rows: cells rejected, the bias criterion (and where the seeds resolve it), the
    half-width over the Cramer-Rao bound, the narrowest band on a clean power law, and the old estimator beside."""
    rejected = [r for r in rows if r["rejected"]]
    biased = [r for r in rows if abs(r["bias"]) >= r["median_half"] / 4]
    resolved = [r for r in rows if r["seeds"] >= 62]
    failed = [r for r in biased if r["seeds"] >= 62]
    untested = [r for r in biased if r["seeds"] < 62]
    ratio = [r.get("ratio", r["median_half"] / r["cr_half"]) for r in rows]
    clean = [r["min_decades"] for r in rows if r["floor"] == "none"]
    old = [r.get("old_ratio", r["old_median_half"] / r["cr_half"]) for r in rows
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
        text += (f"; the narrowest band on a clean power law spans {min(clean):.2f} decades"
                 f"{_where_narrowest(rows, 'none')}")
    if any(r["floor"] == "dominant" for r in rows):
        text += (f", under a dominant floor {min(r['min_decades'] for r in rows if r['floor'] == 'dominant'):.2f}"
                 f"{_where_narrowest(rows, 'dominant')}")
    if old:
        text += f"; the old estimator's median half-width {min(old):.1f}-{max(old):.1f}× the bound"
    return text


def page_rows(text: str, lengths) -> dict:
    """The rows of ``lengths`` (log2 of n) read back from a page's table, and its model I paragraph: counts
    (covering intervals, flags) recovered from the printed percentages, the Cramer-Rao half-widths recomputed
    (and checked against the printed ones), the other columns as printed (4 decimals) and the printed line kept
    (``line``), so that the page rebuilt from them prints those rows as they stood. Merged with runs on other seeds
    (which carry per-seed records) they give counts exactly and the median half-width approximately."""
    rows = []
    for line in text.splitlines():
        cols = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("| 2^") or int(cols[0][2:]) not in lengths:
            continue
        n, gamma, where, seeds = 2 ** int(cols[0][2:]), float(cols[1]), cols[2], int(cols[3])
        pct = lambda c: float(c.split("%")[0]) / 100  # noqa: E731
        count = lambda c: round(pct(c) * seeds)  # noqa: E731
        rms = floor_rms(n, gamma, where)
        r = {"n": n, "gamma": gamma, "floor": where, "seeds": seeds, "hits": count(cols[4]),
             "rejected": cols[5] == "yes",
             "bias": float(cols[6]), "median_half": float(cols[7]), "cr_half": cramer_rao(n, gamma, rms),
             "cr_known": cramer_rao(n, gamma, rms, floor_free=False), "ratio": float(cols[9]),
             "flag_rate": count(cols[10]) / seeds, "min_decades": float(cols[11]), "wall_s": 0.0, "line": line}
        r["coverage"] = r["hits"] / seeds
        if f"{r['cr_half']:.4f} / {r['cr_known']:.4f}" != cols[8]:
            raise ValueError(f"row {cols[:3]}: Cramer-Rao {cols[8]} printed, {r['cr_half']:.4f} computed")
        if cols[12] != "not run":
            r.update({"old_coverage": pct(cols[12]), "old_bias": float(cols[13]),
                      "old_median_half": float(cols[14].split()[0]),
                      "old_ratio": float(cols[14].split("(")[1].rstrip("×)")),
                      "old_flag_rate": count(cols[15]) / seeds})
        rows.append(r)
    head = "\n## Records like the shipped model I file"
    model1 = text.split(head, 1)
    return {"rows": rows, "model1_text": (head + model1[1]) if len(model1) > 1 else None}


def merged(rows) -> list:
    """Rows of the same cell from runs on other seeds made one. Where every part carries its per-seed records the
    row is summarised afresh from their union (exact: the same row as one run over all those seeds); otherwise
    counts are added, means weighted by seeds, and the median half-width taken as the seed-weighted mean of the
    parts' medians (an approximation, said so in the row's ``median_note``)."""
    out = {}
    for r in rows:
        key = (r["n"], r["gamma"], r["floor"])
        if key not in out:
            out[key] = dict(r)
            continue
        m, s0, s1 = out[key], out[key]["seeds"], r["seeds"]
        if "records" in m and "records" in r:
            out[key] = summary(r["n"], r["gamma"], r["floor"], m["records"] + r["records"],
                               m.get("wall_s", 0.0) + r.get("wall_s", 0.0))
            continue
        for k in ("bias", "median_half", "flag_rate", "old_coverage", "old_bias", "old_median_half", "old_flag_rate"):
            if k in m and k in r:
                m[k] = (m[k] * s0 + r[k] * s1) / (s0 + s1)
        m["part_records"] = m.get("part_records", []) + m.get("records", []) + r.get("records", [])
        for k in ("records", "line", "ratio", "old_ratio"):
            m.pop(k, None)
        m["median_note"] = "seed-weighted mean of the parts' medians"
        m["hits"] += r["hits"]
        m["seeds"] = s0 + s1
        m["coverage"] = m["hits"] / m["seeds"]
        m["min_decades"] = min(m["min_decades"], r["min_decades"])
        qlo, qhi = stats.binom.ppf(0.0005, m["seeds"], 0.95), stats.binom.ppf(0.9995, m["seeds"], 0.95)
        m["rejected"] = not (qlo <= m["hits"] <= qhi)
    return list(out.values())


def write_page(rows, commands, model1=None, path=PAGE) -> None:
    """The page (docs/results/exponent_coverage.md unless ``path``) from the rows of one or more runs (and the
    model I-like records: their dict, or their paragraph as a page printed it); ``commands`` says how."""
    m1 = model1_text(model1) if isinstance(model1, dict) else (model1 or "")
    approx = [r for r in rows if "median_note" in r]
    note = ("" if not approx else " In the " + ", ".join(
        sorted({f"2^{int(math.log2(r['n']))}" for r in approx})) + " rows the median half-widths (and the ratio beside "
        "them) are the seed-weighted means of the medians of parts of which one kept no per-seed records; "
        "the counts and "
        "flag rates are exact, the mean bias and narrowest band exact up to the printed digits of the part read back.")
    counts = sorted({r["seeds"] for r in rows}, reverse=True)
    note += " Covering counts not rejected: " + ", ".join(
        f"{int(stats.binom.ppf(0.0005, k, 0.95))}-{int(stats.binom.ppf(0.9995, k, 0.95))} of {k}" for k in counts) + "."
    Path(path).write_text(
        "# Exponent coverage on lab-length records\n\n"
        f"Reproduce: {commands}; `--quick --out FILE` writes the same table for 2 seeds at 2^10 samples in a few "
        "seconds (a smoke test, not a measurement).\n\n" + (__doc__.split("\n\n", 1)[1].split("    python -m")[0])
        + "\n" + CRITERION + note + f"\n\nResult: {pooled(rows)}; {claims(rows)}.\n\n" + table(rows) + m1)


def _minutes(seconds: float) -> str:
    return f"{seconds / 60:.0f} min" if seconds >= 60 else f"{seconds:.0f} s"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="every cell at 2^10 samples with 2 seeds (a smoke test)")
    ap.add_argument("--out", default=None, metavar="MD", help="write the page here (default: the docs page; "
                    "--quick writes only here)")
    ap.add_argument("--seeds", type=int, default=200, help="seeds per cell")
    ap.add_argument("--lengths", default="12,14,16", help="log2 of the record lengths, comma-separated")
    ap.add_argument("--no-old", action="store_true", help="skip the spectrum-and-band estimator")
    ap.add_argument("--first-seed", type=int, default=0, help="seeds first-seed .. first-seed + seeds - 1")
    ap.add_argument("--workers", type=int, default=1, metavar="N",
                    help="fit the records in N processes (the rows are the same as with one)")
    ap.add_argument("--rows", default=None, metavar="JSON", help="write the rows here instead of the page (with "
                    "--combine: the parts' rows merged, one part)")
    ap.add_argument("--model1", type=int, default=0, metavar="N",
                    help="instead: N records like the shipped model I file (coverage and flags)")
    ap.add_argument("--from-page", default=None, metavar="MD",
                    help="instead: read the rows of --lengths (and the model I paragraph) back from a page into --rows")
    ap.add_argument("--note", default=None, help="with --from-page: how those rows were made (the page quotes it)")
    ap.add_argument("--combine", nargs="+", default=None, metavar="JSON",
                    help="write the page from the rows of earlier --rows runs (runs nothing)")
    args = ap.parse_args(argv)
    if args.from_page:
        part = page_rows(Path(args.from_page).read_text(), [int(v) for v in args.lengths.split(",")])
        part.update({"command": args.note or f"rows {args.lengths} of {args.from_page}", "wall_s": 0.0})
        Path(args.rows or "page_rows.json").write_text(json.dumps(part, indent=1))
        return 0
    if args.combine:
        parts = [json.loads(Path(f).read_text()) for f in args.combine]
        rows = merged([r for p in parts for r in p.get("rows", [])])
        rows.sort(key=lambda r: (r["n"], GAMMAS.index(r["gamma"]), FLOORS.index(r["floor"])))
        m1 = next((p.get("model1") or p.get("model1_text") for p in parts if p.get("model1") or p.get("model1_text")),
                  None)
        how = "; ".join(f"`{p['command']}` ({_minutes(p['wall_s'])})" if p["wall_s"] else p["command"] for p in parts)
        if args.rows:  # the parts made one part (one file per cell-set instead of one per run)
            Path(args.rows).write_text(json.dumps({"rows": rows, "command": how, "wall_s": 0.0}))
            return 0
        write_page(rows, f"{how}; then `python -m compare.studies.exponent_coverage --combine "
                   + " ".join(args.combine) + "` writes the page from those parts (wall times of one process at a time "
                   "on 2 shared cores, loaded by other work)", m1, args.out or PAGE)
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
    cells = [(n, g, where) for n in lengths for g in GAMMAS for where in FLOORS]
    records, spent, rows = {c: [] for c in cells}, {c: 0.0 for c in cells}, []
    first = args.first_seed
    t0 = time.perf_counter()
    pool = ProcessPoolExecutor(args.workers) if args.workers > 1 else None
    try:  # seed by seed over every cell: a run stopped at any time leaves whole seeds in --rows
        for seed in range(first, first + seeds):
            tasks = [(*c, seed, not args.no_old) for c in cells]
            for c, (rec, s) in zip(cells, pool.map(_seed_task, tasks) if pool is not None else map(_seed_task, tasks)):
                records[c].append(rec)
                spent[c] += s
            rows = [summary(*c, records[c], spent[c]) for c in cells]
            cmd = ("python -m compare.studies.exponent_coverage --quick" if args.quick else
                   f"python -m compare.studies.exponent_coverage --seeds {seed - first + 1} --lengths {args.lengths}"
                   + (" --no-old" if args.no_old else "") + (f" --first-seed {first}" if first else ""))
            print(f"seed {seed} done ({time.perf_counter() - t0:.0f} s)", flush=True)
            if args.rows and not args.quick:  # replaced whole: a run stopped while writing keeps the last seed's
                part = Path(args.rows).with_suffix(".part")
                part.write_text(json.dumps({"rows": rows, "command": cmd, "wall_s": time.perf_counter() - t0}))
                os.replace(part, args.rows)
    finally:
        if pool is not None:
            pool.shutdown()
    print(table(rows), end="")
    wall = time.perf_counter() - t0
    print(pooled(rows))
    if args.rows or (args.quick and not args.out):
        return 0
    write_page(rows, f"`{cmd}` ({_minutes(wall)} of wall time)", path=args.out or PAGE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
