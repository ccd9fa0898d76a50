"""One stepping loop: outside engine_sim/loop.py nothing steps or maintains a scene (``.advance(`` or
``.maintain()``) but the places listed here, each with the reason engine_sim.loop.Loop cannot do its work.

The scan reads every source line of the packages and the benchmarks, code inside strings too (a worker's script),
and names each hit by its file and the innermost function, class or assignment around it."""
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("engine_sim", "compare", "frictionnoise", "reduced_models", "benchmarks")
STEPPING = re.compile(r"\.advance\(|\.maintain\(\)")

ALLOWED = {
    # the definitions and the scene's own use of them
    "engine_sim/scene.py::Scene.__init__": "a new scene's first maintenance lays the track under its pads",
    "engine_sim/scene.py::Scene.maintain": "the scene's maintenance calls its wear part's",
    "engine_sim/scene.py::Scene.advance": "the scene's advance hands the steps to its law or its vibration",
    "engine_sim/vibration.py::Vibration.advance": "a part's own stepping: the shaking steps the law step by step",
    # timings and observations inside an output step, which Loop runs as one
    "engine_sim/forecast.py::forecast": "times one maintenance apart from the output steps, to project each",
    "benchmarks/bench_engine.py::loop_ratio": "the bare pymunk step timed against the loop, and its maintenance "
                                              "kept out of the bare chunks' timers",
    "benchmarks/bench_engine.py::test_loop_against_bare_step": "warms up as the lockstep's base tree does",
    "benchmarks/bench_engine.py::_WORKER": "the lockstep worker warms up exactly as the base tree's worker does, so "
                                           "both trees time one state",
    "benchmarks/bench_vibration.py::stepping_minima": "times the part's stepping alone (space.step a no-op)",
    "benchmarks/bench_vibration.py::overhead": "times the stepping and the sample of one output step apart",
    "benchmarks/bench_vibration.py::advance_before": "the vibration part's former stepping, a part's advance",
    "compare/studies/step_means_cost.py::cost": "times pymunk's step bare and with a per-step reader",
    "compare/studies/energy_ledger.py::_step": "reads every body before and after each pymunk step",
    "compare/studies/energy_ledger.py::ledger": "maintains around _step, which reads every body before and after "
                                                "each pymunk step (Loop's advance has no such reading)",
    "compare/studies/recorder_compile.py::_CHILD": "a worker run in another source tree, timing the first sample",
}


def _names(tree):
    """(first line, last line, dotted name) of every function, class and top-level assignment."""
    out = []

    def walk(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                name = prefix + child.name
                out.append((child.lineno, child.end_lineno, name))
                walk(child, name + ".")
            elif isinstance(child, ast.Assign) and node is tree:
                for t in child.targets:
                    if isinstance(t, ast.Name):
                        out.append((child.lineno, child.end_lineno, t.id))
    walk(tree, "")
    return out


def _docstring_lines(tree) -> set:
    """The lines of every docstring (words about stepping, not stepping)."""
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(
                    first.value.value, str):
                lines.update(range(first.lineno, first.end_lineno + 1))
    return lines


def stepping_sites(root=ROOT, packages=PACKAGES):
    """{"path::name": [line numbers]} of every stepping call outside engine_sim/loop.py."""
    sites = {}
    for pkg in packages:
        for src in sorted((root / pkg).rglob("*.py")):
            rel = src.relative_to(root).as_posix()
            if rel == "engine_sim/loop.py":
                continue
            text = src.read_text()
            tree = ast.parse(text)
            names, docs = _names(tree), _docstring_lines(tree)
            for i, line in enumerate(text.splitlines(), 1):
                code = line.split("#", 1)[0]
                if i in docs or not STEPPING.search(code) or code.lstrip().startswith("def "):
                    continue
                around = [n for n in names if n[0] <= i <= n[1]]
                name = min(around, key=lambda n: n[1] - n[0])[2] if around else "<module>"
                sites.setdefault(f"{rel}::{name}", []).append(i)
    return sites


def test_nothing_steps_a_scene_outside_the_loop_but_the_listed_places():
    sites = stepping_sites()
    extra = {k: v for k, v in sites.items() if k not in ALLOWED}
    assert not extra, f"scenes stepped outside engine_sim.loop.Loop (use Loop, or list the place with why): {extra}"


def test_every_listed_place_still_steps():
    # a listed place that no longer steps comes off the list, so the list says what is true
    stale = set(ALLOWED) - set(stepping_sites())
    assert not stale, stale


def test_the_scan_finds_a_loop_written_again(tmp_path):
    # a benchmark's own loop and a worker script's are found, by function and by name; a docstring's or a
    # comment's mention is not
    (tmp_path / "benchmarks").mkdir()
    (tmp_path / "benchmarks" / "bench_x.py").write_text(
        'def chunk(s, rec):\n    """s.advance(1) in words"""\n    s.maintain()  # s.advance(2)\n'
        '    for _ in range(16):\n        s.advance(s.n_sub)\n        rec.sample()\n'
        '_CHILD = """\nscene.advance(2000)\n"""\n')
    assert stepping_sites(tmp_path, ("benchmarks",)) == {"benchmarks/bench_x.py::chunk": [3, 5],
                                                         "benchmarks/bench_x.py::_CHILD": [8]}
