"""Numbers a study measured reach the repository only through a page the study writes or a test: the studies'
scratch folder (the one each writes to in the folder it runs from, gitignored) is no source. A tracked file may name
a file in that folder only as its own output, a study module compare/studies/NAME.py or a benchmark
benchmarks/bench_NAME.py naming a file whose name begins with NAME; any other mention would point a reader to a number
that nothing in the repository keeps true, so the prose points to the study's command instead."""
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRATCH = re.compile("study-results" + r"/([A-Za-z0-9_][\w.-]*)")  # a file named inside the folder


def _own_output(path: str, name: str) -> bool:
    p = Path(path)
    if p.suffix != ".py" or p.parent.as_posix() not in ("compare/studies", "benchmarks"):
        return False
    stem = p.stem.removeprefix("bench_")
    return name.startswith(stem)


def cited_scratch(files) -> list:
    """(path, line number, name) of each mention of a scratch file in ``files`` (path, text) that is not the
    mentioning module's own output."""
    out = []
    for path, text in files:
        for i, line in enumerate(text.splitlines(), 1):
            out += [(path, i, m.group(1)) for m in SCRATCH.finditer(line) if not _own_output(path, m.group(1))]
    return out


def _tracked():
    names = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    for name in names:
        p = ROOT / name
        if p.is_file() and p.suffix in (".py", ".md", ".toml", ".txt", ".cff", ".cfg", ".ipynb", ".rst", ".yml", "") :
            yield name, p.read_text(errors="replace")


def test_no_tracked_file_cites_a_study_scratch_file():
    found = cited_scratch(_tracked())
    assert not found, "scratch files cited as a source (point to the study's command or its docs page): " + "; ".join(
        f"{p}:{i} {n}" for p, i, n in found)


def test_the_check_tells_a_citation_from_a_study_naming_its_own_output():
    scratch = "study-results" + "/"
    files = [("docs/results/x.md", f"gamma 4.00 +- 0.05 (`{scratch}wear_base_scene.md`)"),
             ("compare/studies/wear_base_scene.py", f'default="{scratch}wear_base_scene"'),
             ("compare/studies/step_ledger.py", f"measured 1e-5 ({scratch}vibration.md)"),
             ("benchmarks/bench_ageing.py", f"Writes {scratch}ageing_cost.md."),
             ("docs/explanation/benchmarks.md", f"write their tables to `{scratch}` in the folder they run from")]
    assert cited_scratch(files) == [("docs/results/x.md", 1, "wear_base_scene.md"),
                                    ("compare/studies/step_ledger.py", 1, "vibration.md")]
