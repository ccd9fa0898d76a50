"""Where the report's time goes: each study's wall time, run one after another in this process, with the machine's
load (``uptime``) before and after, and the whole report's wall time with its worker pool.

    python -m benchmarks.bench_report [--quick] [--full] [--workers N] [--only KEY ...] [--json out.json]

Each study is seeded on its own, so its time alone is what it costs inside the report; the pool's total is bounded
below by the longest study and by the sum over the cores. Run it twice: the first run fills numba's disk cache
(the report states times with a warm cache). Timings on a loaded machine say so: the load averages are printed.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import time


def load() -> str:
    """The machine's load as ``uptime`` prints it."""
    return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()


def per_study(quick: bool, seed: int, only=None) -> list:
    """[(label, wall seconds, CPU seconds)] of each study of the quick or full report, run in this process. CPU
    seconds hardly depend on the load (a loaded machine stretches the wall time, not the work)."""
    from compare.report import studies
    from compare.report.build import run_studies

    chosen = [s for s in studies.selected(quick) if not only or s.key in only or s.label in only]
    rows = []
    for st in chosen:
        t0, c0 = time.perf_counter(), time.process_time()
        run_studies([st], quick, seed, workers=1)
        rows.append((st.label, time.perf_counter() - t0, time.process_time() - c0))
        print(f"  {st.label:32s} {rows[-1][1]:7.1f} s wall {rows[-1][2]:7.1f} s CPU", flush=True)
    return rows


def whole(quick: bool, seed: int, workers: int) -> float:
    """Wall seconds of the whole report (computation only, no files) with ``workers`` processes."""
    from compare.report.build import build_report

    t0 = time.perf_counter()
    build_report(quick=quick, seed=seed, workers=workers)
    return time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the quick report (default: both)")
    ap.add_argument("--full", action="store_true", help="the full report (default: both)")
    ap.add_argument("--workers", type=int, default=2, help="processes for the whole-report run (0: skip it)")
    ap.add_argument("--only", nargs="*", help="study keys or labels to time")
    ap.add_argument("--whole-only", action="store_true", help="only the whole report with its worker pool")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", help="write the timings here")
    args = ap.parse_args(argv)
    modes = [m for m, on in (("quick", args.quick), ("full", args.full)) if on] or ["quick", "full"]
    out = {"cpus": os.cpu_count(), "modes": {}}
    for mode in modes:
        quick = mode == "quick"
        before = load()
        print(f"{mode} report, studies one by one ({before})", flush=True)
        rows = [] if args.whole_only else per_study(quick, args.seed, args.only)
        entry = {"load_before": before, "studies": {k: {"wall_s": w, "cpu_s": c} for k, w, c in rows},
                 "sum_s": sum(r[1] for r in rows), "sum_cpu_s": sum(r[2] for r in rows), "load_after": load()}
        print(f"  {'sum':32s} {entry['sum_s']:7.1f} s wall {entry['sum_cpu_s']:7.1f} s CPU ({entry['load_after']})")
        if args.workers and not args.only:
            entry["whole_s"] = whole(quick, args.seed, args.workers)
            entry["workers"] = args.workers
            entry["load_whole"] = load()
            print(f"  whole {mode} report, {args.workers} workers: {entry['whole_s']:.1f} s ({entry['load_whole']})")
        out["modes"][mode] = entry
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=2)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
