"""The layout rule of benchmarks/ and tests/, applied with `git mv`: rerun it after a merge that adds flat files.

    python .ci/reorganise.py [--dry-run]

benchmarks/ keeps the speed harness only: bench_*.py (each a measurement with its pytest-benchmark entries and a
table printed by ``main``), conftest.py, __init__.py, and trace_identity.py (the bitwise trace comparison of two
source trees). Every other benchmarks/NAME.py is a study and moves to compare/studies/NAME.py; the commit
comparison scripts that the harness's own comparison replaces (REPLACED) and every tracked file under
benchmarks/results/ are removed. References ``benchmarks.NAME`` / ``benchmarks/NAME.py`` in the tracked text files
follow the move.

tests/test_X.py moves to tests/<package>/test_X.py, the package being the one of PACKAGES that has a module or
subpackage named X (the module under test; of several, the shallowest), else the one its imports name most (ties: the first in PACKAGES), or
tests/project/ for the tests of the project as a whole (PROJECT: docs, install,
release, layout, source shape). Helper modules, fixtures (conftest.py) and data stay at tests/ (one place).
Paths built from ``__file__`` in a moved test are rewritten one level deeper, and ``tests/test_X.py`` references
in the tracked text files follow. Idempotent: a file already in place is left alone (and its paths are not rewritten again).
"""
import argparse
import ast
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("engine_sim", "reduced_models", "compare", "frictionnoise")
BENCH_KEEP = {"__init__", "conftest", "trace_identity"}
REPLACED = {"interleave_commits", "bench_vs_ref", "summary_causes", "recorder_cost", "maintain_cost"}  # the harness's --benchmark-compare does this
PROJECT = {"test_readme", "test_install", "test_lean_install", "test_citation", "test_code_shape", "test_docs_cells",
           "test_docs_browser", "test_docstrings", "test_backend", "test_release", "test_bench_harness", "test_benchmarks_layout", "test_study_pages",
           "test_results_pages"}
TEXT = (".py", ".md", ".toml", ".cff", ".txt", ".cfg", ".yml", ".yaml")
# a study's tables and figures go to study-results/ (not tracked) in the folder it runs from; a moved study sits one
# folder deeper
STUDY_PATHS = [(r"Path\(__file__\)\.(?:resolve\(\)\.)?parent / \"results\"", 'Path("study-results")'),
               (r"Path\(__file__\)\.resolve\(\)\.parents\[1\]", "Path(__file__).resolve().parents[2]"),
               (r"\bbenchmarks/results/", "study-results/")]
# a moved test sits one folder deeper: what its paths from __file__ become
DEEPER = [(r"Path\(__file__\)\.resolve\(\)\.parent\.parent(?![.\w])", "Path(__file__).resolve().parents[2]"),
          (r"Path\(__file__\)\.resolve\(\)\.parents\[1\]", "Path(__file__).resolve().parents[2]"),
          (r"Path\(__file__\)\.parents\[1\]", "Path(__file__).parents[2]"),
          (r"Path\(__file__\)\.parent / ", "Path(__file__).parents[1] / "),
          (r"Path\(__file__\)\.resolve\(\)\.parent / ", "Path(__file__).resolve().parents[1] / ")]


def git(*args, dry=False):
    print("git", *args)
    if not dry:
        subprocess.run(["git", *args], cwd=ROOT, check=True)


def tracked(*paths) -> list:
    out = subprocess.run(["git", "ls-files", *paths], cwd=ROOT, check=True, capture_output=True, text=True).stdout
    return [ROOT / p for p in out.splitlines() if (ROOT / p).exists()]


def package_of(test: Path) -> str:
    name = test.stem
    if name in PROJECT:
        return "project"
    subject = name[len("test_"):]
    depth = {}  # package -> the depth of its shallowest module or subpackage named like the test
    for p in PACKAGES:
        hits = [h for h in (ROOT / p).rglob(f"{subject}*") if h.name in (f"{subject}.py", subject)]
        if hits:
            depth[p] = min(len(h.relative_to(ROOT / p).parts) for h in hits)
    owners = [p for p in PACKAGES if depth.get(p) == min(depth.values())] if depth else []
    if len(owners) == 1:
        return owners[0]
    counts = Counter()
    for node in ast.walk(ast.parse(test.read_text())):
        names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
            [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
        for n in names:
            top = n.split(".")[0]
            if top in PACKAGES:
                counts[top] += 1
            elif top == "benchmarks":
                counts["engine_sim" if "bench_" in n else "compare"] += 0.5
    among = owners or PACKAGES
    if not any(counts[p] for p in among):
        return among[0] if owners else "project"
    best = max(counts[p] for p in among)
    return next(p for p in among if counts[p] == best)


def plan() -> tuple:
    moves, removals = {}, []
    for f in tracked("benchmarks"):
        rel = f.relative_to(ROOT)
        if rel.parts[1] == "results":
            removals.append(rel)
        elif f.suffix == ".py" and len(rel.parts) == 2:
            stem = f.stem
            if stem in REPLACED:
                removals.append(rel)
            elif stem not in BENCH_KEEP and not stem.startswith("bench_"):
                moves[rel] = Path("compare/studies") / rel.name
    for name in sorted(REPLACED):
        t = Path(f"tests/test_{name}.py")
        if (ROOT / t).exists():
            removals.append(t)
    for f in tracked("tests"):
        rel = f.relative_to(ROOT)
        if len(rel.parts) == 2 and rel.name.startswith("test_") and rel.suffix == ".py" and rel not in removals:
            moves[rel] = Path("tests") / package_of(f) / rel.name
    return moves, removals


# the references rewrite() follows, found by one scan of each file: a module path (benchmarks.NAME, tests.test_X) or a
# file path (benchmarks/NAME.py, tests/test_X.py); the name it holds is looked up in a table (one alternation of every
# name, tried at each character, made the dry run cost 30 s of CPU)
REFERENCE = re.compile(r"(?<![\w/])tests/test_\w+\.py|\btests\.test_\w+\b|\bbenchmarks\.\w+\b|\bbenchmarks/\w+\.py")


def rewrite(moves: dict, dry: bool):
    subs = {}  # a reference as written -> what it becomes
    # every study and every test in its folder, not only those moved now: a file merged later may name one moved before
    placed = dict(moves)
    for f in tracked("compare/studies", "tests"):
        rel = f.relative_to(ROOT)
        if rel.parts[0] == "compare" and rel.suffix == ".py" and rel.stem != "__init__":
            placed.setdefault(Path("benchmarks") / rel.name, rel)
        elif rel.parts[0] == "tests" and len(rel.parts) == 3 and rel.name.startswith("test_"):
            placed.setdefault(Path("tests") / rel.name, rel)
    for old, new in placed.items():
        if old.parts[0] == "benchmarks":
            subs[f"benchmarks.{old.stem}"] = f"compare.studies.{old.stem}"
            subs[f"benchmarks/{old.name}"] = f"compare/studies/{old.name}"
        else:
            subs[f"tests/{old.name}"] = str(new)
            subs[f"tests.{old.stem}"] = ".".join(new.with_suffix("").parts)
    moved = set(moves.values())
    for f in tracked():
        if f.suffix not in TEXT and f.name != "run" or f.name == "CHANGELOG.md" or f.parts[-2:] == (".ci", "reorganise.py"):
            continue
        text = f.read_text()
        out = text
        if subs:
            out = REFERENCE.sub(lambda m: subs.get(m.group(0), m.group(0)), out)
        rel = f.relative_to(ROOT)
        if rel in moved and rel.parts[0] == "compare":  # a study moved in this run
            for s, r in STUDY_PATHS:
                out = re.sub(s, r, out)
        elif rel.parts[0] != "benchmarks":
            out = re.sub(STUDY_PATHS[2][0], STUDY_PATHS[2][1], out)
        if rel in moved and rel.parts[0] == "tests":  # a test moved in this run: one folder deeper
            for s, r in DEEPER:
                out = re.sub(s, r, out)
        if out != text:
            print("rewrite", rel)
            if not dry:
                f.write_text(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dry-run", action="store_true")
    a = ap.parse_args(argv)
    moves, removals = plan()
    for rel in removals:
        git("rm", "-q", "-r", str(rel), dry=a.dry_run)
    for old, new in sorted(moves.items()):
        if not a.dry_run:
            (ROOT / new.parent).mkdir(parents=True, exist_ok=True)
            init = ROOT / new.parent / "__init__.py"
            if not init.exists():
                init.write_text("")
                git("add", str(init.relative_to(ROOT)))
        git("mv", str(old), str(new), dry=a.dry_run)
    rewrite(moves, a.dry_run)
    if not moves and not removals:
        print("nothing to move: the layout holds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
