"""Speed and numbers against a reference commit: no loss of speed, and the quick report's summary.json identical
to 1e-12 relative or each difference explained.

Both commits are checked out in temporary git worktrees and run by this interpreter (the same venv) with
PYTHONPATH set to their worktree and the worktree as working folder; each child reports where it imported
engine_sim from, and a child that imported the other tree (or an installed copy) stops the benchmark. Measured,
the two commits taking turns (ref, head, ref, head, ...) so that a drift in the machine's speed hits both:

- the engine's loop / bare-step ratio per shipped scene (``benchmarks.bench_engine.loop_ratio`` of each tree,
  best of 3 inside each call), ``--repeats`` calls per commit;
- the wall time of ``frictionnoise report --quick --seed K --workers 1`` (``--repeats`` runs per commit), in all
  and per study (each study's own wall_s from summary.json), with the studies both commits run summed apart from
  the studies only head has;
- the quick report's summary.json of the two commits (same seed): the relative difference per numeric key, the
  keys that differ by more than ``--rtol`` (default 1e-12), timings listed apart (they differ by nature), and
  the keys only one commit has; each differing key assigned to its cause by ``benchmarks.summary_causes`` (keys
  no rule explains are listed), and where the two commits' traces part (first differing sample of x) for the
  scenes those rules rest on.

    python -m benchmarks.bench_vs_ref [--ref c9e0afb] [--head HEAD] [--repeats 3] [--steps 50000] [--seed 0]
                                      [--workers 1] [--skip-engine] [--json OUT] [--smoke]

``--smoke`` (CI): one repeat, 3000 steps on one scene, and `frictionnoise analyze` of the shipped synthetic
model I file in place of the quick report: it checks that the worktrees, the isolation and the diff work, in
about a minute. The full run takes about 3 x 2 quick reports (15-20 min on 2 idle cores): run it on a quiet
machine.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_ENGINE = """
import json, sys
import engine_sim
from benchmarks.bench_engine import loop_ratio
from engine_sim import load_scenario, shipped_scenarios
steps, only = int(sys.argv[1]), sys.argv[2:]
out = {"where": engine_sim.__file__, "scenes": {}}
for name, path in shipped_scenarios().items():
    if only and name not in only:
        continue
    bare, loop = loop_ratio(load_scenario(path), steps)
    out["scenes"][name] = {"bare_us": bare, "loop_us": loop, "ratio": loop / bare}
print(json.dumps(out))
"""
_WHERE = "import engine_sim; print(engine_sim.__file__)"
_TRACE = """
import sys, numpy as np, engine_sim
from engine_sim import load_scenario, shipped_scenarios
sc = load_scenario(shipped_scenarios()[sys.argv[1]]).with_run(duration=float(sys.argv[2]), seed=0)
np.save(sys.argv[3], engine_sim.run(sc).x)
"""
# where the two commits' traces part (the summary_causes rules rest on these), with the quick report's durations
_FIRST_DIFF = {"asperity_field": 6.0, "pads_with_wear": 0.5, "pads_rough_profile": 0.3, "pads_friction_patches": 12.0,
               "tilted_plane": 12.0}
# summary keys that hold timings or speeds: they differ between any two runs, so they are listed apart
_TIMING = re.compile(r"(wall|_s_per_|per_wall|us_per|seconds|elapsed|cost|speed_ratio|steps_per_s|timing)", re.I)


def _git(*args, cwd=ROOT) -> str:
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True).stdout.strip()


def _env(tree: Path) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(tree)
    env.setdefault("MPLBACKEND", "Agg")
    env.pop("PYTHONSTARTUP", None)
    return env


def _run(tree: Path, args: list, **kw) -> subprocess.CompletedProcess:
    r = subprocess.run([sys.executable, *args], cwd=tree, env=_env(tree), capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise SystemExit(f"bench_vs_ref: {' '.join(map(str, args[:3]))} failed in {tree}:\n{r.stderr[-3000:]}")
    return r


def _check_isolated(tree: Path):
    where = Path(_run(tree, ["-c", _WHERE]).stdout.strip())
    if not where.is_relative_to(tree):
        raise SystemExit(f"bench_vs_ref: {tree} imported engine_sim from {where}, not from its worktree")


def flatten(d, prefix="") -> dict:
    """The numbers of a nested summary as {"a/b[2]/c": value} (booleans and strings left out, None kept)."""
    out = {}
    if isinstance(d, dict):
        for k, v in d.items():
            out.update(flatten(v, f"{prefix}/{k}" if prefix else str(k)))
    elif isinstance(d, (list, tuple)):
        for i, v in enumerate(d):
            out.update(flatten(v, f"{prefix}[{i}]"))
    elif d is None or (isinstance(d, (int, float)) and not isinstance(d, bool)):
        out[prefix] = d
    return out


def rel_diff(a, b) -> float:
    """|a - b| / max(|a|, |b|); 0 for equal values (None and NaN equal themselves), inf for None against a number."""
    if a is None or b is None:
        return 0.0 if a is b else math.inf
    if math.isnan(a) or math.isnan(b):
        return 0.0 if math.isnan(a) and math.isnan(b) else math.inf
    if a == b:
        return 0.0
    return abs(a - b) / max(abs(a), abs(b))


def diff_summaries(ref: dict, head: dict, rtol: float = 1e-12) -> dict:
    """Per-key relative differences of two summaries: the keys beyond ``rtol`` (timings apart) and the keys
    only one of them has."""
    fr, fh = flatten(ref), flatten(head)
    common = sorted(set(fr) & set(fh))
    rel = {k: rel_diff(fr[k], fh[k]) for k in common}
    beyond = {k: rel[k] for k in common if rel[k] > rtol}
    return {"compared": len(common), "rtol": rtol,
            "differ": {k: {"ref": fr[k], "head": fh[k], "rel": v} for k, v in beyond.items() if not _TIMING.search(k)},
            "timings_differ": sorted(k for k in beyond if _TIMING.search(k)),
            "only_ref": sorted(set(fr) - set(fh)), "only_head": sorted(set(fh) - set(fr)),
            "max_rel": max((v for k, v in rel.items() if not _TIMING.search(k)), default=0.0)}


def first_difference(trees: dict, tmp: Path, name: str, duration: float) -> dict:
    """Run one shipped scene in both trees (seed 0) and find the first recorded sample whose x differs."""
    import numpy as np
    xs = {}
    for k, tree in trees.items():
        out = tmp / f"x_{k}_{name}.npy"
        _run(tree, ["-c", _TRACE, name, str(duration), str(out)])
        xs[k] = np.load(out)
    n = min(len(x) for x in xs.values())
    bad = np.nonzero(xs["ref"][:n] != xs["head"][:n])[0]
    return {"samples": int(n), "first_differing_sample": int(bad[0]) if len(bad) else None,
            "max_abs_dx_m": float(np.abs(xs["ref"][:n] - xs["head"][:n]).max())}


def study_walls(summary: dict) -> dict:
    """{study: wall_s} of one quick report's summary (scenes under scenarios/, the models at the top level)."""
    out = {f"scene {k}": v["wall_s"] for k, v in summary.get("scenarios", {}).items()
           if isinstance(v, dict) and isinstance(v.get("wall_s"), (int, float))}
    out.update({k: v["wall_s"] for k, v in summary.items()
                if k != "scenarios" and isinstance(v, dict) and isinstance(v.get("wall_s"), (int, float))})
    return out


def _spread(xs) -> str:
    return f"{statistics.median(xs):.3f} [{min(xs):.3f}-{max(xs):.3f}]"


def _overlap(a, b) -> bool:
    """Do the ranges of two samples overlap (the issue's test: differ by no more than their spread)?"""
    return min(a) <= max(b) and min(b) <= max(a)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ref", default="c9e0afb", help="reference commit (default: %(default)s)")
    ap.add_argument("--head", default="HEAD", help="commit to compare with it (default: %(default)s)")
    ap.add_argument("--repeats", type=int, default=3, help="runs per commit, taking turns (default: %(default)s)")
    ap.add_argument("--steps", type=int, default=50_000, help="steps per loop_ratio call (default: %(default)s)")
    ap.add_argument("--seed", type=int, default=0, help="the quick report's seed (default: %(default)s)")
    ap.add_argument("--rtol", type=float, default=1e-12, help="relative difference listed (default: %(default)s)")
    ap.add_argument("--json", default=None, help="also write the results here")
    ap.add_argument("--smoke", action="store_true", help="a short check that the script runs (CI)")
    ap.add_argument("--workers", type=int, default=1,
                    help="the quick report's --workers (default: %(default)s, so that each study's wall time is "
                         "its own)")
    ap.add_argument("--skip-engine", action="store_true", help="skip the loop/bare-step part")
    a = ap.parse_args(argv)
    if a.repeats < 1:
        ap.error("--repeats must be at least 1")
    repeats, steps = (1, 3000) if a.smoke else (a.repeats, a.steps)
    only = ["pads_friction_patches"] if a.smoke else []
    head = _git("rev-parse", "--verify", f"{a.head}^{{commit}}")
    try:
        ref = _git("rev-parse", "--verify", "--quiet", f"{a.ref}^{{commit}}")
    except subprocess.CalledProcessError:
        if not a.smoke:
            raise SystemExit(f"bench_vs_ref: no commit {a.ref} in this clone (a shallow one? git fetch --unshallow)")
        ref = head  # a shallow CI clone: the smoke still checks the machinery, head against itself
        print(f"bench_vs_ref: no commit {a.ref} in this clone; smoke run of head against itself")
    commits = {"ref": ref, "head": head}
    tmp = Path(tempfile.mkdtemp(prefix="bench_vs_ref-"))
    trees = {k: tmp / k for k in commits}
    results: dict = {"commits": commits, "repeats": repeats, "steps": steps, "seed": a.seed, "smoke": a.smoke}
    try:
        for k, c in commits.items():
            _git("worktree", "add", "--detach", "--quiet", str(trees[k]), c)
            _check_isolated(trees[k])
        print(f"ref {commits['ref'][:10]}  head {commits['head'][:10]}  ({repeats} repeats, taking turns)")

        engine = {k: [] for k in commits}
        for i in range(0 if a.skip_engine else repeats):
            for k in commits:
                out = json.loads(_run(trees[k], ["-c", _ENGINE, str(steps), *only]).stdout.splitlines()[-1])
                engine[k].append(out["scenes"])
        scenes = [s for s in engine["head"][0] if s in engine["ref"][0]] if engine["head"] else []
        table = {}
        if scenes:
            print("\n| scene | loop/bare ref | loop/bare head | ranges overlap |\n|---|---|---|---|")
        for s in scenes:
            r = [e[s]["ratio"] for e in engine["ref"]]
            h = [e[s]["ratio"] for e in engine["head"]]
            table[s] = {"ref": r, "head": h, "overlap": _overlap(r, h)}
            print(f"| {s} | {_spread(r)} | {_spread(h)} | {'yes' if _overlap(r, h) else 'NO'} |")
        extra = sorted(set(engine["head"][0]) ^ set(engine["ref"][0])) if engine["head"] else []
        if extra:
            print(f"scenes in one commit only: {', '.join(extra)}")
        results["engine_loop_over_bare"] = table

        if a.smoke:  # a cheap deterministic report of both commits in place of the quick report
            cmd = ["-m", "compare.cli", "analyze", "scenarios/data/model1_synthetic_um.csv", "--mass", "1",
                   "--x-unit", "um", "--band", "5", "50"]
            label = "analyze (smoke)"
        else:
            cmd = ["-m", "compare.cli", "report", "--quick", "--seed", str(a.seed), "--workers", str(a.workers)]
            label = "report --quick"
        walls = {k: [] for k in commits}
        summaries, stage_walls = {}, {k: [] for k in commits}
        for i in range(repeats):
            for k in commits:
                out = tmp / f"{k}-report-{i}"
                t0 = time.perf_counter()
                _run(trees[k], [*cmd, "-o", str(out)])
                walls[k].append(time.perf_counter() - t0)
                summary = json.loads((out / "summary.json").read_text())
                summaries.setdefault(k, summary)
                if not a.smoke:
                    stage_walls[k].append(study_walls(summary))
        print(f"\n{label} wall s: ref {_spread(walls['ref'])}, head {_spread(walls['head'])}, "
              f"head / ref {statistics.median(walls['head']) / statistics.median(walls['ref']):.3f}, ranges "
              f"{'overlap' if _overlap(walls['ref'], walls['head']) else 'DO NOT overlap'}")
        print("  each run (the first of each commit includes numba's compilation into its fresh worktree's cache): "
              + "; ".join(f"{k} " + ", ".join(f"{w:.1f}" for w in walls[k]) for k in commits))
        results["report_wall_s"] = {**walls, "overlap": _overlap(walls["ref"], walls["head"])}
        if stage_walls["head"]:
            common = sorted(set(stage_walls["ref"][0]) & set(stage_walls["head"][0]))
            print("\nper study (the report's own wall_s per study, --workers "
                  f"{a.workers}):\n| study | ref s | head s | ranges overlap |\n|---|---|---|---|")
            per = {}
            for st in common + ["common studies, summed"]:
                if st in common:
                    r, h = ([w[st] for w in stage_walls[k]] for k in ("ref", "head"))
                else:
                    r, h = ([sum(w[c] for c in common) for w in stage_walls[k]] for k in ("ref", "head"))
                per[st] = {"ref": r, "head": h, "overlap": _overlap(r, h)}
                print(f"| {st} | {_spread(r)} | {_spread(h)} | {'yes' if _overlap(r, h) else 'NO'} |")
            new = {st: [w[st] for w in stage_walls["head"]] for st in sorted(set(stage_walls["head"][0]) - set(common))}
            for st, h in new.items():
                print(f"| {st} (head only) | - | {_spread(h)} | - |")
            results["study_wall_s"] = {"common": per, "head_only": new}

        d = diff_summaries(summaries["ref"], summaries["head"], a.rtol)
        results["summary_diff"] = d
        print(f"\nsummary.json: {d['compared']} numbers in both, largest relative difference {d['max_rel']:.3g} "
              f"(timings aside); {len(d['differ'])} beyond {a.rtol:g}:")
        for k, v in sorted(d["differ"].items(), key=lambda kv: -kv[1]["rel"]):
            print(f"  {k}: ref {v['ref']!r} head {v['head']!r} (rel {v['rel']:.3g})")
        print(f"timings that differ (by nature): {len(d['timings_differ'])}")
        for side in ("only_ref", "only_head"):
            if d[side]:
                print(f"keys in {side.split('_')[1]} only ({len(d[side])}): {', '.join(d[side][:40])}"
                      + (" ..." if len(d[side]) > 40 else ""))
        if not a.smoke:
            from benchmarks.summary_causes import explain
            e = explain(d)
            results["causes"] = e
            print("\ncauses (benchmarks/summary_causes.py):")
            for cause, keys in e["causes"].items():
                print(f"  {len(keys):4d}  {cause}")
            print(f"  unexplained differing keys: {len(e['unexplained'])} {e['unexplained'][:20]}")
            print(f"  keys only in head: {e['new_in_head']['explained']} new studies/flags, unexplained "
                  f"{e['new_in_head']['unexplained'][:20]}; keys only in ref: {e['only_ref'][:20]}")
            fd = {name: first_difference(trees, tmp, name, dur) for name, dur in _FIRST_DIFF.items()}
            results["first_difference"] = fd
            print("\nwhere the traces part (x, seed 0, the quick report's spectral settings aside):")
            for name, r in fd.items():
                print(f"  {name}: {r['samples']} samples, first differing sample {r['first_differing_sample']}, "
                      f"max |dx| {r['max_abs_dx_m']:.3g} m")
        if a.json:
            Path(a.json).write_text(json.dumps(results, indent=1, default=str))
    finally:
        for t in trees.values():
            if t.exists():
                subprocess.run(["git", "worktree", "remove", "--force", str(t)], cwd=ROOT, capture_output=True)
        shutil.rmtree(tmp, ignore_errors=True)
        subprocess.run(["git", "worktree", "prune"], cwd=ROOT, capture_output=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
