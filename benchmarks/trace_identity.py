"""Bitwise identity of scene traces between two source trees (e.g. main and a branch, as git worktrees).

Each shipped scenario (or the ones named) is run for a short time with the same seed by each tree's own code,
in a fresh process whose import path starts at that tree, and every array of the two traces is compared bit for
bit (numpy.array_equal on the raw arrays, NaN-aware). Prints one line per scenario and exits 1 if any array
differs.

    python -m benchmarks.trace_identity /work/wt/ref /work/wt/parts2 [--duration 2] [--seed 0] [NAME ...]
"""
import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

_RUN = r"""
import sys, numpy as np, dataclasses
import engine_sim
from engine_sim import load_scenario
sc = load_scenario(sys.argv[1]).with_run(duration=float(sys.argv[2]), warmup=0.2, seed=int(sys.argv[3]))
tr = engine_sim.run(sc)
arrays = {f.name: getattr(tr, f.name) for f in dataclasses.fields(tr) if isinstance(getattr(tr, f.name), np.ndarray)}
np.savez(sys.argv[4], **arrays)
"""


def run_in(tree: Path, name: str, duration: float, seed: int, out: Path):
    env = dict(os.environ, PYTHONPATH=str(tree), NUMBA_CACHE_DIR=str(out.parent / ("numba_" + tree.name)))
    subprocess.run([sys.executable, "-c", _RUN, name, str(duration), str(seed), str(out)], env=env, check=True,
                   cwd=str(tree))


def compare(a: Path, b: Path) -> tuple[list[str], list[str]]:
    """(names of the common arrays that differ, names of the arrays in one trace only)."""
    A, Bz = np.load(a), np.load(b)
    only = sorted(set(A.files) ^ set(Bz.files))
    bad = []
    for k in sorted(set(A.files) & set(Bz.files)):
        x, y = A[k], Bz[k]
        if x.shape != y.shape or x.dtype != y.dtype or not np.array_equal(x, y, equal_nan=x.dtype.kind == "f"):
            bad.append(k)
    return bad, only


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("tree_a", type=Path)
    ap.add_argument("tree_b", type=Path)
    ap.add_argument("names", nargs="*")
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    names = a.names
    if not names:
        sys.path.insert(0, str(a.tree_a))
        from engine_sim import shipped_scenarios
        names = list(shipped_scenarios())
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name in names:
            fa, fb = tmp / f"{name}_a.npz", tmp / f"{name}_b.npz"
            run_in(a.tree_a.resolve(), name, a.duration, a.seed, fa)
            run_in(a.tree_b.resolve(), name, a.duration, a.seed, fb)
            bad, only = compare(fa, fb)
            n = len(set(np.load(fa).files) & set(np.load(fb).files))
            print(f"{name}: {n - len(bad)} of {n} common arrays bitwise identical" + (f"; differ: {', '.join(bad)}" if bad else "")
                  + (f"; in one tree only: {', '.join(only)}" if only else ""))
            failed += bool(bad)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
