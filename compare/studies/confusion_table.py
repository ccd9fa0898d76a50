"""Rebuild docs/results/identification.md: the confusion table of `identify` over compare.analysis.confusion's cells.

    python -m compare.studies.confusion_table [--quick | --smoke] [--seeds N] [--durations S ...] [--out PATH]

Default: every cell of CELLS (models I, II, III and Ib at two or one parameter points, 60, 300 and 900 s at 1 kHz)
with 100 seeds each (seeds 0-99), written to docs/results/identification.md. --quick: three 10 s cells, one seed
(a CI smoke, seconds per record); --smoke: three 30 s cells, 2 seeds; both written to the path given by --out
(default: printed only). Each count carries its 95 % Clopper-Pearson interval, against which a cell with fewer than
100 seeds is read.
"""
import argparse
import os
import time
from pathlib import Path

from compare.analysis.confusion import CELLS, FLOOR, QUICK_CELLS, SMOKE_CELLS, binomial_interval, run_cell


def _pct(k, n, interval=False):
    if not n:
        return "n/a"
    if not interval:
        return f"{k}/{n}"
    lo, hi = binomial_interval(k, n)
    return f"{k}/{n} ({100 * lo:.0f}-{100 * hi:.0f} %)"


def table(rows, seeds: int, wall: float, command: str = "python -m compare.studies.confusion_table") -> str:
    lines = [
        "# Identification: the confusion table",
        "",
        "Records simulated by each model's exact simulator at 1 kHz with a white sensor floor of "
        f"{FLOOR:g} m² s, identified by `compare.analysis.identify.identify` (every registered model's family fitted, "
        f"ranked by BIC, Vuong's test against the best, Holm-adjusted at 5 %). Seeds 0-{seeds - 1} per cell. Rebuilt "
        f"by `{command}` ({wall:.0f} s wall at load {os.getloadavg()[0]:.1f}).",
        "",
        "Columns: *first or indist.*: the true model not rejected, ranked first or indistinguishable from the first; "
        "*alone*: the true model first with verdict \"fits\" (model_Iv, model I's family plus a line, counts as model "
        "I); *wrong alone*: another model first with \"fits\" and the true one rejected; *coincides*: another model "
        "first with \"fits\" and the true one not rejected (its own feature unseen on this band: one family there); "
        "*indist.*: the first not named alone; *coverage*: the "
        "true family's identified parameters whose 95 % interval holds the value the record was built with. "
        "Brackets: the count's 95 % Clopper-Pearson interval; a criterion \"at least p0\" is shown by a cell whose "
        "interval's low end reaches p0.",
        "",
        "| model | parameters | T (s) | first or indist. | alone | wrong alone | coincides | indist. | coverage | "
        "ranked first |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    cov_k = cov_n = 0
    for cell, r in rows:
        n = r["n"]
        cov_k += r["covered"]
        cov_n += r["intervals"]
        best = ", ".join(f"{m} {k}" for m, k in sorted(r["best"].items(), key=lambda kv: -kv[1]))
        lines.append(f"| {cell.model} | {cell.label} | {cell.duration:g} | "
                     f"{_pct(r['first_or_indistinguishable'], n, True)} | "
                     f"{_pct(r['alone'], n, True)} | {_pct(r['wrong_alone'], n, True)} | {_pct(r['coincides'], n)} | "
                     f"{_pct(r['indistinguishable'], n)} | "
                     f"{_pct(r['covered'], r['intervals'])} | {best} |")
    lines += ["", f"Pooled coverage of the identified parameters' 95 % intervals: {_pct(cov_k, cov_n, True)}"
              + (f", {100 * cov_k / cov_n:.0f} % (asked: 90-98 %)." if cov_n else "."), ""]
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--quick", action="store_true", help="three 10 s cells, one seed: a CI smoke")
    ap.add_argument("--seeds", type=int, default=None)
    ap.add_argument("--out", default=None)
    ap.add_argument("--durations", type=float, nargs="+", default=None, help="only the cells of these lengths (s)")
    a = ap.parse_args(argv)
    cells = QUICK_CELLS if a.quick else SMOKE_CELLS if a.smoke else CELLS
    if a.durations:
        cells = tuple(c for c in cells if c.duration in a.durations)
    seeds = a.seeds or (1 if a.quick else 2 if a.smoke else 100)
    out = a.out or (None if a.smoke or a.quick else "docs/results/identification.md")
    t0 = time.perf_counter()
    rows = []
    for cell in cells:
        rows.append((cell, run_cell(cell, range(seeds))))
        print(f"{cell.model} {cell.label} {cell.duration:g} s: {rows[-1][1]}", flush=True)
    import sys

    command = " ".join(["python -m compare.studies.confusion_table", *(sys.argv[1:] if argv is None else argv)])
    text = table(rows, seeds, time.perf_counter() - t0, command)
    if out:
        Path(out).write_text(text)
        print(f"wrote {out}")
    else:
        print(text)


if __name__ == "__main__":
    main()
