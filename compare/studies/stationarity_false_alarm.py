"""False alarms of the stationarity verdict analyze states: how often the record model's split-half likelihood-ratio
test (compare.analysis.record_model, level TEST_LEVEL = 1 %) flags an exactly stationary record; rebuilds
docs/results/stationarity.md.

Records: exact sampled omega^-gamma processes (compare.analysis.synthetic.power_law_record, dt = 1 ms, A = 1) for
gamma = 2, 4, 6, without a floor and with the "dominant" floor of docs/results/exponent_coverage.md (it meets the
power law at the geometric middle of the resolved band), fitted by fit_record as analyze fits them (automatic band,
floor term, split-half test on). Beside it, on the same records, the band test of
compare.analysis.identify.stationarity (eight log-spaced bands, Bonferroni at 1 %, a factor 1.5), which analyze no
longer states when the split-half test has run.

    python -m compare.studies.stationarity_false_alarm --seeds 100 --lengths 4096 --seeds-long 25 --lengths-long 16384 \
        --gammas-long 4 --resume ROWS   # the page's cells; ROWS: an earlier run's --rows file, whose cells are kept
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

from compare.analysis.identify import stationarity
from compare.analysis.record_model import TEST_LEVEL, fit_record
from compare.analysis.synthetic import power_law_record
from compare.studies.exponent_coverage import floor_rms
from compare.studies.study_page import write_page

DT = 1e-3
GAMMAS = (2.0, 4.0, 6.0)
FLOORS = ("none", "dominant")
PAGE = Path(__file__).resolve().parents[2] / "docs" / "results" / "stationarity.md"
REJECT_P = 0.001


def cell(n: int, gamma: float, floor: str, seeds) -> dict:
    """One cell's records: the split-half p of each (nan when not run), and the band test's verdicts."""
    rms = floor_rms(n, gamma, floor)
    ps, band_flags = [], 0
    for s in seeds:
        x = power_law_record(n, DT, gamma, floor_rms=rms, seed=int(s))
        ps.append(float(fit_record(x, DT).stationarity_p))
        band_flags += not stationarity(x, DT)["stationary"]
    return {"n": n, "gamma": gamma, "floor": floor, "seeds": [int(s) for s in seeds], "split_half_p": ps,
            "band_test_flags": int(band_flags)}


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
             "25 --lengths-long 16384 --gammas-long 4` (one cell was stored with 200 seeds by a first run and kept "
             "with `--resume`; the records, the test and the criterion: the module's docstring).", "",
             "analyze states one stationarity verdict: the record model's **split-half likelihood-ratio test** (the "
             "power law and floor fitted to each half of the record apart and to both with shared parameters; twice "
             f"the gain is chi2 with 3 degrees of freedom; flagged below p = {TEST_LEVEL:g}). Its false alarms, on "
             "exact stationary omega^-gamma records (`power_law_record`, dt = 1 ms), without a floor and with a "
             "floor dominant over the upper half of the band. Beside it, the band test of "
             "`compare.analysis.identify.stationarity` on the same records (eight log-spaced bands, Bonferroni at "
             "1 %, a ratio beyond 1.5): `fn.identify` still runs it when it is not told the verdict, analyze does "
             "not.", "",
             "| samples | gamma | floor | records | split-half flags (p < 0.01) | band-test flags |",
             "|---|---|---|---|---|---|"]
    tot = band = flags = 0
    for r in rows:
        f = sum(p < TEST_LEVEL for p in r["split_half_p"])
        k = len(r["split_half_p"])
        lines.append(f"| {r['n']} | {r['gamma']:g} | {r['floor']} | {k} | {f} | {r['band_test_flags']} |")
        tot, flags, band = tot + k, flags + f, band + r["band_test_flags"]
    p, (lo, hi) = binomial(flags, tot)
    pb, (lob, hib) = binomial(band, tot)
    verdict = "rejected" if p < REJECT_P else "not rejected"
    lines += ["", f"**Pooled split-half false-alarm rate: {flags}/{tot} = {100 * flags / tot:.2f} %** (Clopper-Pearson "
                  f"95 %: {100 * lo:.2f}-{100 * hi:.2f} %), against its nominal {100 * TEST_LEVEL:g} %: P(X >= {flags}) "
                  f"= {p:.3g} under Binomial({tot}, {TEST_LEVEL:g}), {verdict} at p < {REJECT_P:g} (one-sided: a rate "
                  "above the level). The band test on the same records: "
                  f"{band}/{tot} = {100 * band / tot:.2f} % ({100 * lob:.2f}-{100 * hib:.2f} %), P(X >= {band}) = "
                  f"{pb:.2g} at its nominal 1 %: {'rejected: it alarms more often than its stated level' if pb < REJECT_P else 'not rejected'}.", "",
              "What each tests: the split-half test asks whether the two halves have the same power law and floor "
              "(three parameters) over the band the exponent was fitted on; the band test asks whether any of eight "
              "frequency bands changed its level by more than a factor 1.5 between halves, a shape-free check over "
              "all frequencies. analyze names no mechanism when the split-half test flags the record; the band test "
              "is stated only for a fit without a split-half test (`--method whittle` or `lsq`).", "",
              f"Measured in {seconds / 60:.1f} min." if seconds == seconds else
              "Written from the stored cells (`--page-from`)." + (f" {note}" if note else "")]
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seeds", type=int, default=200, help="records per cell at --lengths")
    ap.add_argument("--lengths", type=int, nargs="+", default=[4096])
    ap.add_argument("--seeds-long", type=int, default=50, help="records per cell at --lengths-long")
    ap.add_argument("--lengths-long", type=int, nargs="*", default=[16384])
    ap.add_argument("--gammas-long", type=float, nargs="+", default=list(GAMMAS), help="exponents at --lengths-long")
    ap.add_argument("--resume", type=Path, default=None, help="keep the cells stored in this file, run the others")
    ap.add_argument("--quick", action="store_true", help="3 records per cell at 4096 samples")
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
    write_page(a.out, page(rows, time.perf_counter() - t0))


if __name__ == "__main__":
    main()
