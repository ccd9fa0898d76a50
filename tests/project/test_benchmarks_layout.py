"""benchmarks/ holds the speed harness only: at most 20 tracked files, no results, every module a harness file
(bench_*.py), its conftest, or the bitwise trace comparison; the studies are modules of compare.studies
(.ci/reorganise.py keeps the rule, docs/explanation/benchmarks.md states it)."""
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _tracked(folder: str) -> list:
    out = subprocess.run(["git", "ls-files", folder], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return out.split()


def test_benchmarks_is_the_harness_only():
    files = _tracked("benchmarks")
    assert 0 < len(files) <= 20, files
    assert not [f for f in files if f.startswith("benchmarks/results")], files
    names = {Path(f).name for f in files}
    assert names <= {"__init__.py", "conftest.py", "trace_identity.py"} | {n for n in names if n.startswith("bench_")}
    assert all(f.endswith(".py") for f in files), files


def test_the_layout_rule_has_nothing_left_to_move():
    r = subprocess.run(["python3", ".ci/reorganise.py", "--dry-run"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0 and "git mv" not in r.stdout and "git rm" not in r.stdout, r.stdout[-2000:]


def test_every_benchmark_script_has_a_harness_entry():
    import ast

    missing = set()
    for f in _tracked("benchmarks"):
        p = Path(f)
        if p.name.startswith("bench_"):
            tree = ast.parse((ROOT / p).read_text())
            if not any(isinstance(n, ast.FunctionDef) and n.name.startswith("test_") for n in tree.body):
                missing.add(p.stem)
    assert not missing, missing
