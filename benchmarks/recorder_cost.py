"""The recorder's own cost per shipped scene on two source trees, taking turns: CPU microseconds per
``Recorder.sample()`` and per output step (its pymunk steps and the sample), the medians over N output steps of one
warmed scene, so that a drift in the machine's speed hits both trees. On a loaded machine a turn now and then runs at
half speed: read the best turns (the medians are printed beside them).

    python -m benchmarks.recorder_cost BASE_TREE NEW_TREE [--repeats 3] [--outputs 600] [--out FILE.md]

Each turn is one process per tree (cwd = the tree, so its own engine_sim is imported); turns alternate base, new,
base, new, ... The CPU clock (time.thread_time) is what another process on the machine does not advance.
"""
import argparse
import statistics
import sys

from benchmarks.interleave_commits import take_turns

_CHILD = """
import json, sys, time
import numpy as np
from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.record import Recorder
clock = time.thread_time
out = {}
n_out = int(sys.argv[1])
for name, path in sorted(shipped_scenarios().items()):
    scene = Scene(load_scenario(path))
    scene.advance(200)
    rec = Recorder(scene, n_out + 1)
    rec.sample()
    ts, tl = [], []
    for k in range(n_out):
        if k % 64 == 0:
            scene.maintain()
        t0 = clock()
        scene.advance(scene.n_sub)
        t1 = clock()
        rec.sample()
        t2 = clock()
        ts.append(t2 - t1)
        tl.append(t2 - t0)
    out[name] = [float(np.median(ts)) * 1e6, float(np.median(tl)) * 1e6]
print(json.dumps(out))
"""


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--outputs", type=int, default=600)
    ap.add_argument("--out", default=None)
    a = ap.parse_args(argv)
    runs = take_turns(_CHILD, [str(a.outputs)], a.base, a.new, a.repeats)
    med = statistics.median
    lines = [f"| scene | recorder us per sample, base ({a.repeats} turns) | new | new / base (best turns) | new / base "
             "(medians) | output step us (steps + sample), base, best | new, best | new / base (best) |",
             "|---|---|---|---|---|---|---|---|"]
    for n in sorted(runs["base"][0]):
        sb, sn = [x[n][0] for x in runs["base"]], [x[n][0] for x in runs["new"]]
        lb, ln = [x[n][1] for x in runs["base"]], [x[n][1] for x in runs["new"]]
        lines.append(f"| {n} | {', '.join(f'{v:.1f}' for v in sb)} | {', '.join(f'{v:.1f}' for v in sn)} | "
                     f"{min(sn) / min(sb):.2f} | {med(sn) / med(sb):.2f} | {min(lb):.0f} | {min(ln):.0f} | "
                     f"{min(ln) / min(lb):.3f} |")
    text = "\n".join(lines)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
