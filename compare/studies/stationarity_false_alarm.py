"""False alarms of the stationarity verdict analyze states: how often the record model's split-half test
(compare.analysis.record_model, level TEST_LEVEL = 1 %) flags an exactly stationary record; rebuilds
docs/results/stationarity.md.

Records: exact sampled omega^-gamma processes (compare.analysis.synthetic.power_law_record, dt = 1 ms, A = 1) for
gamma = 2, 4, 6, without a floor and with the "dominant" floor of docs/results/exponent_coverage.md (it meets the
power law at the geometric middle of the resolved band), fitted by fit_record as analyze fits them (automatic band,
floor term, split-half test on). Beside it, on the same records, the band test of
compare.analysis.band_stationarity (eight log-spaced bands, each against F(2m, 2m) widened by the level scatter the
record's quarters show, Bonferroni at 1 %, a factor 1.5), as `fn.identify` runs it (compare.analysis.identify.
record_stationarity), which analyze states only when the split-half test has not run. Then records of a mechanism, not a power law: model I's reference
case (reduced_models.spring_block, SpringBlockParams.reference()), 60 s at 1 kHz with a sensor's white floor of
79 pm rms, both tests on each.

    python -m compare.studies.stationarity_false_alarm --seeds 100 --lengths 4096 --seeds-long 25 --lengths-long 16384 \
        --gammas-long 4 --model-I-seeds 40   # the page's cells (--resume ROWS keeps the cells stored in ROWS)
    python -m compare.studies.stationarity_false_alarm --quick --out t.md   # smoke: 3 seeds at 4096, a few seconds
    python -m compare.studies.stationarity_false_alarm --page-from ROWS     # the page of the cells stored in ROWS

Binomial criterion: the pooled count of flags is compared with Binomial(records, 0.01); the rate is rejected as above
its nominal 1 % when P(X >= count) < 0.001 (one-sided: a test that alarms less often than its level only loses
power), and the page gives the count's Clopper-Pearson 95 % interval.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from scipy import stats

from compare.analysis.identify import record_stationarity
from compare.analysis.record_model import TEST_LEVEL, fit_record, split_half_references
from compare.analysis.synthetic import power_law_record
from compare.studies.exponent_coverage import floor_rms
from compare.studies.study_page import write_page

DT = 1e-3
GAMMAS = (2.0, 4.0, 6.0)
FLOORS = ("none", "dominant")
PAGE = Path(__file__).resolve().parents[2] / "docs" / "results" / "stationarity.md"
REJECT_P = 0.001


def _record_row(x, row: dict) -> None:
    """Fit one record as analyze does and add its split-half p, each reference's p alone
    (:func:`compare.analysis.record_model.split_half_references`: chi2 alone, the quarters alone) and the band test's
    verdict to the cell's ``row``."""
    f = fit_record(x, DT)
    p_chi2, p_quarters = split_half_references(*f.stationarity_lr)
    row["split_half_p"].append(float(f.stationarity_p))
    row["halves_chi2_p"].append(p_chi2)
    row["quarters_f_p"].append(p_quarters)
    row["band_test_flags"] += not record_stationarity(x, DT)["stationary"]


def _empty_row(seeds, **key) -> dict:
    return dict(key, seeds=[int(s) for s in seeds], split_half_p=[], halves_chi2_p=[], quarters_f_p=[],
                band_test_flags=0)


def cell(n: int, gamma: float, floor: str, seeds) -> dict:
    """One cell's records: the split-half p of each (nan when not run), each reference's alone, and the band test's
    verdicts."""
    rms = floor_rms(n, gamma, floor)
    row = _empty_row(seeds, n=n, gamma=gamma, floor=floor)
    for s in seeds:
        _record_row(power_law_record(n, DT, gamma, floor_rms=rms, seed=int(s)), row)
    return row


MODEL_I_DURATION = 60.0  # s
MODEL_I_FLOOR = 1e-24  # m^2 s: a sensor's white floor of rms sqrt(2 pi B / dt) = 79 pm at 1 kHz
MODEL_I_SEED0 = 100  # model I's seeds run from here


def model_I_cell(seeds, duration: float = MODEL_I_DURATION) -> dict:
    """Model I's records (the reference case, ``duration`` seconds at 1 kHz, white floor :data:`MODEL_I_FLOOR`):
    the split-half p of each and the band test's verdicts."""
    import math

    import numpy as np

    import reduced_models as rm

    p = rm.spring_block.SpringBlockParams.reference()
    row = _empty_row(seeds, model="model_I", n=0, duration=duration)
    for s in seeds:
        tr = rm.MODELS["model_I"].simulate(p, duration, DT, seed=int(s))
        noise = np.random.default_rng(int(s) + 1000).normal(0.0, math.sqrt(2 * math.pi * MODEL_I_FLOOR / DT), len(tr.x))
        row["n"] = len(tr.x)
        _record_row(tr.x + noise, row)
    return row


def binomial(count: int, records: int, level: float = TEST_LEVEL) -> tuple:
    """(one-sided p of a count this high or higher under Binomial(records, level), Clopper-Pearson 95 % interval)."""
    p = float(stats.binom.sf(count - 1, records, level)) if count else 1.0
    lo = float(stats.beta.ppf(0.025, count, records - count + 1)) if count else 0.0
    hi = float(stats.beta.ppf(0.975, count + 1, records - count)) if count < records else 1.0
    return p, (lo, hi)


def page(rows: list, seconds: float, note: str = "") -> list:
    """The markdown page of the cells ``rows`` (``note``: how they were measured, for a page written from stored
    cells)."""
    lines = ["# How often analyze calls a stationary record not stationary", "",
             "Regenerate: `python -m compare.studies.stationarity_false_alarm --seeds 100 --lengths 4096 --seeds-long "
             "25 --lengths-long 16384 --gammas-long 4 --model-I-seeds 40` (the records, the test and the criterion: "
             "the module's docstring).", "",
             "analyze states one stationarity verdict: the record model's **split-half test** (the power law and "
             "floor fitted to each half of the record apart and to both with shared parameters, twice the likelihood "
             "gain LR_h; read against chi2 with 3 degrees of freedom, the law for independent Gaussian periodogram "
             "ordinates, and against the same gain LR_w among each half's four quarters, summed over the halves, "
             "F = (LR_h / 3) / (LR_w / 18) against F(3, 18); its p-value the larger of the two; flagged below p = "
             f"{TEST_LEVEL:g}). Its false alarms, on "
             "exact stationary omega^-gamma records (`power_law_record`, dt = 1 ms), without a floor and with a "
             "floor dominant over the upper half of the band. Beside it, on the same records: each of its two "
             "references alone, and the band test of "
             "`compare.analysis.band_stationarity` (eight log-spaced bands, each band's ratio of the halves' levels "
             "against F(2m, 2m), widened by the level scatter the record's quarters show; Bonferroni at 1 %, a "
             "ratio beyond 1.5), as `fn.identify` runs it when it is not told the verdict; analyze states it only "
             "for a fit without the split-half test.", "",
             "| samples | gamma | floor | records | split-half flags (p < 0.01) | LR_h against chi2 alone | "
             "against the quarters alone | band-test flags |",
             "|---|---|---|---|---|---|---|---|"]
    models = [r for r in rows if "model" in r]
    rows = [r for r in rows if "model" not in r]
    tot = band = flags = chi2 = quarters = 0
    for r in rows:
        f = sum(p < TEST_LEVEL for p in r["split_half_p"])
        c = sum(p < TEST_LEVEL for p in r["halves_chi2_p"])
        q = sum(p < TEST_LEVEL for p in r["quarters_f_p"])
        k = len(r["split_half_p"])
        lines.append(f"| {r['n']} | {r['gamma']:g} | {r['floor']} | {k} | {f} | {c} | {q} | {r['band_test_flags']} |")
        tot, flags, band, chi2, quarters = tot + k, flags + f, band + r["band_test_flags"], chi2 + c, quarters + q
    p, (lo, hi) = binomial(flags, tot)
    pb, (lob, hib) = binomial(band, tot)
    pc, (loc, hic) = binomial(chi2, tot)
    pq, (loq, hiq) = binomial(quarters, tot)
    verdict = "rejected" if p < REJECT_P else "not rejected"
    lines += ["", f"**Pooled split-half false-alarm rate: {flags}/{tot} = {100 * flags / tot:.2f} %** (Clopper-Pearson "
                  f"95 %: {100 * lo:.2f}-{100 * hi:.2f} %), against its nominal {100 * TEST_LEVEL:g} %: P(X >= {flags}) "
                  f"= {p:.3g} under Binomial({tot}, {TEST_LEVEL:g}), {verdict} at p < {REJECT_P:g} (one-sided: a rate "
                  f"above the level). LR_h against chi2 alone: {chi2}/{tot} = {100 * chi2 / tot:.2f} % "
                  f"({100 * loc:.2f}-{100 * hic:.2f} %, P(X >= {chi2}) = {pc:.2g}); against the quarters alone: "
                  f"{quarters}/{tot} = {100 * quarters / tot:.2f} % ({100 * loq:.2f}-{100 * hiq:.2f} %, P(X >= "
                  f"{quarters}) = {pq:.2g}: a floor the quarters do not resolve takes degrees of freedom the F "
                  "reference counts). The band test on the same records: "
                  f"{band}/{tot} = {100 * band / tot:.2f} % ({100 * lob:.2f}-{100 * hib:.2f} %), P(X >= {band}) = "
                  f"{pb:.2g} at its nominal 1 %: {'rejected: it alarms more often than its stated level' if pb < REJECT_P else 'not rejected'}.", "",
              "What each tests: the split-half test asks whether the two halves have the same power law and floor "
              "(three parameters) over the band the exponent was fitted on, measuring the scatter of such fits by "
              "the quarters of the same record; the band test asks whether any of eight "
              "frequency bands changed its level by more than a factor 1.5 between halves, beyond what the "
              "scatter of the ordinates and of the quarters' levels allows, a shape-free check over all frequencies. analyze names no mechanism when the split-half test flags the record; the band test "
              "is stated only for a fit without a split-half test (`--method whittle` or `lsq`).", ""]
    for r in models:
        f = sum(p < TEST_LEVEL for p in r["split_half_p"])
        c = sum(p < TEST_LEVEL for p in r["halves_chi2_p"])
        q = sum(p < TEST_LEVEL for p in r["quarters_f_p"])
        k = len(r["split_half_p"])
        p, (lo, hi) = binomial(f, k)
        pc, _ = binomial(c, k)
        pq, _ = binomial(q, k)
        pb, _ = binomial(r["band_test_flags"], k)
        lines += [f"**Records of a mechanism: {r['model']}'s reference case**, {r['duration']:g} s at 1 kHz "
                  f"({r['n']} samples), a white floor of 79 pm rms, seeds {r['seeds'][0]}-{r['seeds'][-1]}: the "
                  f"split-half test flags **{f} of {k}** ({100 * f / k:.1f} %, Clopper-Pearson 95 % "
                  f"{100 * lo:.1f}-{100 * hi:.1f} %; P(X >= {f}) = {p:.2g} at its nominal 1 %: "
                  f"{'rejected' if p < REJECT_P else 'not rejected'}); LR_h against chi2 alone {c} of {k} "
                  f"(P = {pc:.2g}: {'rejected' if pc < REJECT_P else 'not rejected'}), against the quarters alone "
                  f"{q} of {k} (P = {pq:.2g}); the band test "
                  f"{r['band_test_flags']} of {k} (P = {pb:.2g}). "
                  "Model I's contact renewals are not Gaussian noise: its periodogram's ordinates correlate across "
                  "frequencies, and a likelihood ratio of its fits scatters more than chi2 allows, at the halves' "
                  "scale and the quarters' alike; the quarters' ratio measures that scatter on the record itself."
                  + (" On these records the split-half test still alarms more often than its level: its flag on a "
                     "record of a mechanism is weak evidence that the record changed." if p < REJECT_P else ""), ""]
    lines += [f"Measured in {seconds / 60:.1f} min." if seconds == seconds else
              "Written from the stored cells (`--page-from`)." + (f" {note}" if note else "")]
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seeds", type=int, default=200, help="records per cell at --lengths")
    ap.add_argument("--lengths", type=int, nargs="+", default=[4096])
    ap.add_argument("--seeds-long", type=int, default=50, help="records per cell at --lengths-long")
    ap.add_argument("--lengths-long", type=int, nargs="*", default=[16384])
    ap.add_argument("--gammas-long", type=float, nargs="+", default=list(GAMMAS), help="exponents at --lengths-long")
    ap.add_argument("--model-I-seeds", type=int, default=40, help="model I's records (60 s at 1 kHz each)")
    ap.add_argument("--resume", type=Path, default=None, help="keep the cells stored in this file, run the others")
    ap.add_argument("--quick", action="store_true", help="3 records per cell at 4096 samples, one of model I (10 s)")
    ap.add_argument("--out", type=Path, default=PAGE)
    ap.add_argument("--rows", type=Path, default=Path("study-results") / "stationarity_rows.json")
    ap.add_argument("--page-from", type=Path, default=None, help="write the page of the cells stored in this file")
    ap.add_argument("--note", default="", help="with --page-from: how the stored cells were measured")
    a = ap.parse_args(argv)
    if a.page_from is not None:
        rows = json.loads(a.page_from.read_text())
        write_page(a.out, page(rows, float("nan"), a.note), load=False)
        return
    plan = [(n, a.seeds, GAMMAS) for n in a.lengths] + [(n, a.seeds_long, a.gammas_long) for n in a.lengths_long]
    if a.quick:
        plan = [(4096, 3, GAMMAS)]
    rows, t0 = (json.loads(a.resume.read_text()) if a.resume else []), time.perf_counter()
    done = {(r["n"], r["gamma"], r["floor"]) for r in rows}
    a.rows.parent.mkdir(parents=True, exist_ok=True)
    for n, seeds, gammas in plan:
        for gamma in gammas:
            for floor in FLOORS:
                if (n, gamma, floor) in done:
                    continue
                rows.append(cell(n, gamma, floor, range(seeds)))
                a.rows.write_text(json.dumps(rows))
                r = rows[-1]
                print(f"n = {n}, gamma = {gamma:g}, floor {floor}: {sum(p < TEST_LEVEL for p in r['split_half_p'])}"
                      f"/{seeds} split-half flags, {r['band_test_flags']} band-test flags "
                      f"({time.perf_counter() - t0:.0f} s)", flush=True)
    if not any("model" in r for r in rows) and (a.model_I_seeds > 0 or a.quick):
        seeds = range(MODEL_I_SEED0, MODEL_I_SEED0 + (1 if a.quick else a.model_I_seeds))
        rows.append(model_I_cell(seeds, 10.0 if a.quick else MODEL_I_DURATION))
        a.rows.write_text(json.dumps(rows))
        r = rows[-1]
        print(f"model I, {r['n']} samples: {sum(p < TEST_LEVEL for p in r['split_half_p'])}/{len(seeds)} split-half "
              f"flags, {r['band_test_flags']} band-test flags ({time.perf_counter() - t0:.0f} s)", flush=True)
    write_page(a.out, page(rows, time.perf_counter() - t0))


if __name__ == "__main__":
    main()
