"""Where the report's time goes: each study's wall and CPU time, run one after another in this process, with the
machine's load (``uptime``) before and after, and the whole report's wall and CPU time with its worker pool.

    python -m benchmarks.bench_report [--quick [--all-scenes]] [--full] [--workers N] [--only KEY ...] [--json out.json]
    python -m pytest benchmarks/bench_report.py   # the harness's entry (test_a_study_against_its_stated_cost)

Each study is seeded on its own, so its time alone is what it costs inside the report; the pool's total is bounded
below by the longest study and by the sum over the cores. The whole report runs as a user runs it: `frictionnoise
report` in a fresh process, imports, worker start-up and files included. Run it twice: the first run fills numba's disk cache
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


def per_study(quick: bool, seed: int, only=None, all_scenes: bool = False) -> list:
    """[(label, wall seconds, CPU seconds)] of each study of the quick or full report, run in this process. CPU
    seconds hardly depend on the load (a loaded machine stretches the wall time, not the work)."""
    from compare.report import studies
    from compare.report.build import run_studies

    chosen = [s for s in studies.selected(quick, all_scenes) if not only or s.key in only or s.label in only]
    rows = []
    for st in chosen:
        t0, c0 = time.perf_counter(), time.process_time()
        run_studies([st], quick, seed, workers=1)
        rows.append((st.label, time.perf_counter() - t0, time.process_time() - c0))
        print(f"  {st.label:32s} {rows[-1][1]:7.1f} s wall {rows[-1][2]:7.1f} s CPU", flush=True)
    return rows


_WHOLE = """
import json, os, resource, sys, time
t0 = time.perf_counter()
from compare.cli import main
rc = main(sys.argv[1:])
wall = time.perf_counter() - t0


def live_children_cpu():
    # the workers are the fork server's children, which it has waited for: the CPU of this process's live children
    # (the fork server, the resource tracker) with their waited children, from /proc (utime, stime, cutime, cstime)
    tick, me, total = os.sysconf("SC_CLK_TCK"), os.getpid(), 0.0
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as fh:
                f = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(f[1]) == me:
            total += sum(int(x) for x in f[11:15]) / tick
    return total


own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
cpu = own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime + live_children_cpu()
print(json.dumps({"rc": rc, "wall_in_s": wall, "cpu_s": cpu}))
"""


def whole(quick: bool, seed: int, workers: int, all_scenes: bool = False) -> dict:
    """The whole `frictionnoise report` as a user runs it, in a fresh process (imports, worker start-up, the
    studies, the files): {"wall_s": from start to exit, "cpu_s": that process and its workers, user + system,
    "studies": each study's wall and CPU seconds inside the report (summary.json's study_seconds)}."""
    import sys
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        args = ["report", "-o", f"{tmp}/report", "--seed", str(seed), "--workers", str(workers)] + (["--quick"] if quick else []) \
            + (["--all-scenes"] if quick and all_scenes else [])
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-c", _WHOLE, *args], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if r.returncode != 0:
            raise RuntimeError(f"the report failed: {r.stderr[-2000:]}")
        with open(f"{tmp}/report/summary.json") as fh:
            studies = json.load(fh)["study_seconds"]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    return {"wall_s": wall, "cpu_s": out["cpu_s"], "studies": studies}


def schedule(costs: list, workers: int) -> float:
    """The longest worker's share when the studies go longest first to whichever worker is free (as the report's
    pool hands them out): the pool's wall time if each study took its CPU seconds."""
    ends = [0.0] * workers
    for c in sorted(costs, reverse=True):
        ends[ends.index(min(ends))] += c
    return max(ends)


HARNESS_STUDY = "models/model_ageing"  # the quick report's cheapest model study (a 300 s record and its fits)


def test_a_study_against_its_stated_cost(benchmark, ratio, smoke):
    """The harness's entry: one study of the quick report (model I with ageing contacts) run in this process, timed
    by the harness after a warm-up (numba's kernels compiled or loaded), and in the same run its CPU time (the
    least over the runs) over the cost its registry entry states, the figure the report's pool schedules by: a
    ratio far from 1 says the entry's cost is stale. One run at smoke size (no warm-up: a cold cache's compilation
    counts), three at full size."""
    from compare.report import studies
    from compare.report.build import run_studies

    study = next(s for s in studies.selected(True, True) if s.key == HARNESS_STUDY)
    cpu = []

    def once():
        c0 = time.process_time()
        run_studies([study], True, 0, workers=1)
        cpu.append(time.process_time() - c0)
    benchmark.pedantic(once, rounds=1 if smoke else 3, warmup_rounds=0 if smoke else 1)
    ratio("CPU / the registry's quick cost", min(cpu) / study.cost_in(True))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the quick report (default: both)")
    ap.add_argument("--full", action="store_true", help="the full report (default: both)")
    ap.add_argument("--all-scenes", action="store_true", help="the quick report of every scene (--quick --all-scenes)")
    ap.add_argument("--workers", type=int, default=2, help="processes for the whole-report run (0: skip it)")
    ap.add_argument("--only", nargs="*", help="study keys or labels to time")
    ap.add_argument("--whole-only", action="store_true", help="only the whole report with its worker pool")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=1, help="runs of the whole report")
    ap.add_argument("--json", help="write the timings here")
    args = ap.parse_args(argv)
    modes = [m for m, on in (("quick", args.quick), ("full", args.full)) if on] or ["quick", "full"]
    out = {"cpus": os.cpu_count(), "modes": {}}
    for mode in modes:
        quick = mode == "quick"
        before = load()
        print(f"{mode} report, studies one by one ({before})", flush=True)
        rows = [] if args.whole_only else per_study(quick, args.seed, args.only, args.all_scenes)
        entry = {"load_before": before, "studies": {k: {"wall_s": w, "cpu_s": c} for k, w, c in rows},
                 "sum_s": sum(r[1] for r in rows), "sum_cpu_s": sum(r[2] for r in rows), "load_after": load()}
        print(f"  {'sum':32s} {entry['sum_s']:7.1f} s wall {entry['sum_cpu_s']:7.1f} s CPU ({entry['load_after']})")
        if rows and args.workers:
            from compare.report import studies

            alone = {st.label for st in studies.selected(quick, args.all_scenes) if st.alone}
            entry["pool_cpu_bound_s"] = schedule([c for k, _, c in rows if k not in alone], args.workers)
            entry["alone_cpu_s"] = sum(c for k, _, c in rows if k in alone)
            print(f"  longest first on {args.workers} workers, the busiest ends after {entry['pool_cpu_bound_s']:.1f} CPU s"
                  + (f"; then {entry['alone_cpu_s']:.1f} CPU s alone" if alone else ""))
        for _ in range(args.repeat if args.workers and not args.only else 0):
            before = load()
            w = whole(quick, args.seed, args.workers, args.all_scenes)
            entry.setdefault("whole", []).append({**w, "load_before": before, "load_after": load()})
            entry.update(whole_s=w["wall_s"], whole_cpu_s=w["cpu_s"], workers=args.workers, load_whole=load())
            for k, v in sorted(w["studies"].items(), key=lambda kv: -kv[1]["cpu_s"]):
                print(f"    in the pool: {k:32s} {v['wall_s']:7.1f} s wall {v['cpu_s']:7.1f} s CPU")
            print(f"  whole {mode} report (`frictionnoise report{' --quick' if quick else ''}{' --all-scenes' if quick and args.all_scenes else ''} --workers {args.workers}`, "
                  f"a fresh process): {w['wall_s']:.1f} s wall, {w['cpu_s']:.1f} s CPU ({before} -> {entry['load_whole']})",
                  flush=True)
        out["modes"][mode] = entry
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=2)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
