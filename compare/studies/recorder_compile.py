"""The cold-start compile time of the recorder's kernels on two source trees, taking turns: CPU seconds of the first
``Recorder.sample()`` of a scene in a process whose numba cache is empty (every kernel the sample calls compiles
there), then of the same in a second process on the cache the first wrote (what loads it). Turns alternate base,
new, base, new, ... so that a drift in the machine's speed hits both.

    python -m compare.studies.recorder_compile BASE_TREE NEW_TREE [--repeats 3] [--scene constant_velocity]

Each process runs with cwd = its tree (its own engine_sim) and NUMBA_CACHE_DIR a fresh folder per turn.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

_CHILD = """
import json, sys, time
from engine_sim import Scene, load_scenario
from engine_sim.record import Recorder
scene = Scene(load_scenario(sys.argv[1]))
scene.advance(scene.n_sub)  # not engine_sim.loop.Loop: this worker runs in older source trees too
rec = Recorder(scene, 4)
t0 = time.process_time()
rec.sample()
print(json.dumps(time.process_time() - t0))
"""


def _turn(tree: str, scene: str, cache: str) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=tree)
    p = subprocess.run([sys.executable, "-c", _CHILD, scene], cwd=tree, env=env, capture_output=True, text=True,
                       check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("base")
    ap.add_argument("new")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scene", default="constant_velocity")
    a = ap.parse_args(argv)
    cold = {"base": [], "new": []}
    warm = {"base": [], "new": []}
    load = []
    for r in range(a.repeats):
        for label, tree in (("base", a.base), ("new", a.new)):
            load.append(os.getloadavg()[0])
            with tempfile.TemporaryDirectory() as cache:
                cold[label].append(_turn(tree, a.scene, cache))
                warm[label].append(_turn(tree, a.scene, cache))
            print(f"turn {r + 1} {label}: cold {cold[label][-1]:.2f} s, cached {warm[label][-1]:.3f} s",
                  file=sys.stderr, flush=True)
    q = [n / b for b, n in zip(cold["base"], cold["new"])]
    print(f"{a.scene}: first sample, empty numba cache, CPU s: base {', '.join(f'{x:.2f}' for x in cold['base'])}; "
          f"new {', '.join(f'{x:.2f}' for x in cold['new'])}; new / base turn by turn "
          f"{', '.join(f'{x:.3f}' for x in q)} (median {statistics.median(q):.3f})")
    print(f"cached: base median {statistics.median(warm['base']):.3f} s, new {statistics.median(warm['new']):.3f} s; "
          f"one-minute load {min(load):.1f}-{max(load):.1f}")


if __name__ == "__main__":
    main()
