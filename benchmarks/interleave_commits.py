"""The engine's loop / bare-step ratio per scene on two source trees, taking turns, to show no loss of
speed against an earlier commit: the two interleaved, >= 3 repeats each (>= 10 for the 95 % interval of the new
tree's ratio over the base's, turn by turn), so that a drift in the machine's speed hits both.

    python -m benchmarks.interleave_commits BASE_TREE NEW_TREE [--repeats 3] [--steps 20000] [--out FILE.md]

Each turn is one process per tree (cwd = the tree, so its own engine_sim is imported) that runs
``benchmarks.bench_engine.loop_ratio`` on every scene the tree ships; turns alternate base, new, base, new, ...
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

_CHILD = """
import json, sys
from benchmarks.bench_engine import loop_ratio
from engine_sim import load_scenario, shipped_scenarios
out = {}
only = sys.argv[2].split(",") if len(sys.argv) > 2 and sys.argv[2] else None
for name, path in shipped_scenarios().items():
    if only and name not in only:
        continue
    b, f = loop_ratio(load_scenario(path), int(sys.argv[1]), repeat=2)
    out[name] = [b, f]
print(json.dumps(out))
"""


def take_turns(child: str, args: list, base: str, new: str, repeats: int) -> dict:
    """{"base": [...], "new": [...], "load": [...]}: the JSON that ``child`` (Python source run with ``args``, cwd = the
    tree) prints last, per turn, and the one-minute load average as each turn starts; turns alternate base, new, base,
    new, ..."""
    runs = {"base": [], "new": [], "load": []}
    for r in range(repeats):
        for label, tree in (("base", base), ("new", new)):
            runs["load"].append(os.getloadavg()[0])
            p = subprocess.run([sys.executable, "-c", child, *args], cwd=tree, capture_output=True, text=True,
                               check=True)
            runs[label].append(json.loads(p.stdout.strip().splitlines()[-1]))
            print(f"turn {r + 1} {label} done", file=sys.stderr, flush=True)
    return runs


def _paired(runs: dict, name: str) -> str:
    """The new tree's loop/bare over the base's, turn by turn (a turn's two processes ran back to back, under
    about the same load): mean and Student's t 95 % interval over the turns."""
    from scipy.stats import t

    q = [(n[name][1] / n[name][0]) / (b[name][1] / b[name][0]) for b, n in zip(runs["base"], runs["new"])
         if name in b and name in n]
    if len(q) < 2:
        return "-"
    m, h = statistics.mean(q), t.ppf(0.975, len(q) - 1) * statistics.stdev(q) / len(q) ** 0.5
    return f"{m:.4f} [{m - h:.4f}, {m + h:.4f}]"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20_000)
    ap.add_argument("--out", default=None)
    ap.add_argument("--scenes", default="", help="comma-separated scene names (default: all)")
    a = ap.parse_args(argv)
    runs = take_turns(_CHILD, [str(a.steps), a.scenes], a.base, a.new, a.repeats)
    names = sorted(set(runs["base"][0]) | set(runs["new"][0]))
    lines = [f"| scene | base loop/bare ({a.repeats} turns) | new loop/bare ({a.repeats} turns) | base us/step (loop, best) | new us/step (loop, best) "
             "| new / base of loop/bare, turn by turn: mean [95 % interval] |",
             "|---|---|---|---|---|---|"]
    for n in names:
        cols = []
        for label in ("base", "new"):
            rs = [x[n][1] / x[n][0] for x in runs[label] if n in x]
            cols.append(", ".join(f"{v:.3f}" for v in rs) if rs else "-")
        best = [f"{min(x[n][1] for x in runs[lb] if n in x):.1f}" if any(n in x for x in runs[lb]) else "-"
                for lb in ("base", "new")]
        lines.append(f"| {n} | {cols[0]} | {cols[1]} | {best[0]} | {best[1]} | {_paired(runs, n)} |")
    load = runs["load"]
    lines.append(f"\none-minute load average as the turns started: {min(load):.1f}-{max(load):.1f} "
                 f"(median {statistics.median(load):.1f})")
    text = "\n".join(lines)
    print(text)
    if a.out:
        Path(a.out).write_text(text + "\n")
    json.dump(runs, sys.stderr if not a.out else open(Path(a.out).with_suffix(".json"), "w"))


if __name__ == "__main__":
    main()
