"""The substrate maintenance's own cost (``Scene.maintain()``: track streaming and particle recycling) on two source
trees, in CPU microseconds.

    python -m benchmarks.maintain_cost BASE_TREE NEW_TREE [--repeats 3] [--chunks 45] [NAME ...]
    python -m benchmarks.maintain_cost BASE_TREE --same-process [--calls 200] [NAME ...]   (cwd = the new tree)

Taking turns (the default): one process per tree (cwd = the tree, so its own engine_sim is imported), turns
alternating base, new, base, new, ...; each runs the project's loop as ``benchmarks.bench_engine`` does (per
output step ``scene.advance`` and ``rec.sample()``, ``scene.maintain()`` every 64 output steps) over ``--chunks``
chunks of one warmed scene and times maintain() alone, per output step: its mean, its median over the chunks (a
chunk in which no track grows: removal only) and the mean of the chunks above the median (the tracks grow
together, every few chunks, in some of these).

Same process (``--same-process``): two scenes of one scenario in this process, one whose tracks run the base tree's
track classes (read from its ``engine_sim/substrate.py`` and ``engine_sim/substrates/line_scan.py``), one this
tree's; their bodies moved by 64 output steps of steady sliding before each call, without stepping, the two
maintained in turn. The load of the machine and the garbage collector hit both alike, so the ratio is steadier
than between processes; the absolute times are not those of a run (no steps between the calls).

The CPU clock (time.thread_time) is what another process on the machine does not advance.
"""
import argparse
import ast
import importlib.util
import json
import statistics
import sys
import time
from pathlib import Path

from benchmarks.interleave_commits import take_turns

_CHILD = """
import json, sys, time
import numpy as np
from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.record import Recorder
clock = time.thread_time
n_chunks, names = int(sys.argv[1]), sys.argv[2].split(",")
out = {}
for name in names:
    scene = Scene(load_scenario(shipped_scenarios()[name]))
    scene.advance(2000)
    rec = Recorder(scene, n_chunks * 64 + 1)
    rec.sample()
    ts = []
    for _ in range(n_chunks):
        t0 = clock()
        scene.maintain()
        ts.append((clock() - t0) / 64 * 1e6)
        for _ in range(64):
            scene.advance(scene.n_sub)
            rec.sample()
    ts = np.array(ts)
    med = float(np.median(ts))
    out[name] = {"mean": float(ts.mean()), "median": med, "above": float(ts[ts > med].mean())}
print(json.dumps(out))
"""


def _base_classes(base: Path) -> dict:
    """The base tree's track classes by name, loaded beside this tree's engine_sim."""
    spec = importlib.util.spec_from_file_location("base_substrate", base / "engine_sim" / "substrate.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    import numpy as np

    tree = ast.parse((base / "engine_sim" / "substrates" / "line_scan.py").read_text())
    cls = [n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "ProfileTrack"]
    ns = {"StreamedTrack": mod.StreamedTrack, "np": np}
    exec(compile(ast.Module(cls, []), "base_line_scan", "exec"), ns)
    return {"PatchTrack": mod.PatchTrack, "SelfAffineTrack": mod.SelfAffineTrack, "BumpTrack": mod.BumpTrack,
            "ProfileTrack": ns["ProfileTrack"]}


def same_process(base: Path, names: list, calls: int) -> dict:
    """{name: {"base": us per call, "new": us per call, "ratio": new / base}} (see the module's docstring)."""
    from engine_sim import Scene, load_scenario, shipped_scenarios

    classes = _base_classes(base)
    clock = time.thread_time
    out = {}
    for name in names:
        sc = load_scenario(shipped_scenarios()[name])
        scenes = {"base": Scene(sc), "new": Scene(sc)}
        for tr in scenes["base"].tracks:
            tr.__class__ = classes[type(tr).__name__]
        s = scenes["new"]
        d = s.v_law * s.dt * s.n_sub * 64
        tot = {"base": 0.0, "new": 0.0}
        order = ["base", "new"]
        for _ in range(calls):
            for label in order:
                scene = scenes[label]
                for b in [scene.block, *scene.sliders]:
                    x, y = b.position
                    b.position = (x + d, y)
                t0 = clock()
                scene.space._removed_shapes.clear()  # as the next step would: what it frees is maintenance's
                scene.maintain()
                tot[label] += clock() - t0
            order.reverse()
        made = {label: sum(t.generated for t in s.tracks) for label, s in scenes.items()}
        assert made["base"] == made["new"], made
        out[name] = {"base": tot["base"] / calls * 1e6, "new": tot["new"] / calls * 1e6,
                     "ratio": tot["new"] / tot["base"], "segments_per_call": made["new"] / calls}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("base")
    ap.add_argument("new", nargs="?", default=None)
    ap.add_argument("names", nargs="*")
    ap.add_argument("--same-process", action="store_true")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--chunks", type=int, default=45)
    ap.add_argument("--calls", type=int, default=200)
    a = ap.parse_intermixed_args(argv)
    names = a.names or ["line_scan_example", "pads_rough_profile", "pads_multiscale"]
    if a.same_process:
        if a.new is not None:
            names = [a.new, *a.names]
        sys.path.insert(0, ".")
        res = same_process(Path(a.base), names, a.calls)
        print("| scene | base us/call | new us/call | new / base | segments per call |")
        print("|---|---|---|---|---|")
        for n, r in res.items():
            print(f"| {n} | {r['base']:.0f} | {r['new']:.0f} | {r['ratio']:.3f} | {r['segments_per_call']:.0f} |")
        return
    runs = take_turns(_CHILD, [str(a.chunks), ",".join(names)], a.base, a.new, a.repeats)
    print("| scene | tree | mean us per output step (turns) | median chunk | mean above the median |")
    print("|---|---|---|---|---|")
    for n in names:
        for label in ("base", "new"):
            rs = [r[n] for r in runs[label]]
            f = lambda k: ", ".join(f"{r[k]:.0f}" for r in rs)
            print(f"| {n} | {label} | {f('mean')} | {f('median')} | {f('above')} |")
    print(json.dumps(runs), file=sys.stderr)


if __name__ == "__main__":
    main()
