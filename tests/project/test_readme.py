"""README.md is a front door: short, and its Python example runs as written."""
import contextlib
import io
import re
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_readme_is_short():
    text = README.read_text(encoding="utf-8")
    assert len(text.encode("utf-8")) <= 12 * 1024
    assert len(text.splitlines()) <= 150
    assert "10.1039/d5sm00617a" in text  # the paper's DOI


def test_readme_python_example_runs_as_written():
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)
    assert len(blocks) == 1
    code = blocks[0]
    assert len(code.strip().splitlines()) <= 12
    ns, out = {}, io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), ns)
    # what it prints is what it claims: model I's omega^-4 band (eq. 6) within the fit's own 95 % interval plus
    # the closed form's slope offset over 5-50 rad/s (3.99, not 4: the resonance at 548 rad/s bends it slightly)
    fit = ns["fit"]
    assert abs(fit.gamma - 4.0) <= fit.gamma_err + 0.02
    # per-band ratios to (A10): 300 s give 0.94-1.13 over seeds 0-5 in half-decade bands; a decade band scatters less
    assert all(0.8 < r < 1.25 for r in ns["ratio"])
    assert "gamma =" in out.getvalue() and "per band" in out.getvalue()


def test_docs_front_page_names_every_how_to():
    # docs/index.md's line on the how-to guides names each page of docs/howto/index.md's toctree ("shake a scene"
    # was missing); a new how-to fails here until it is named there
    docs = README.parent / "docs"
    toc = re.search(r"```\{toctree\}\n(.*?)```", (docs / "howto/index.md").read_text(), re.S).group(1)
    pages = {line.strip() for line in toc.splitlines() if line.strip() and not line.startswith(":")}
    named = {"add_substrate": "Add a substrate", "add_drive": "drive", "add_law": "friction law",
             "add_channel": "record a channel of your own",
             "add_model": "reduced model", "add_study": "report study", "dask_sweeps": "sweep on a dask cluster",
             "checkpoint_resume": "checkpoint and resume a long run", "slope_test": "test a spectral slope",
             "shake_a_scene": "shake a scene"}
    assert pages == set(named)
    front = " ".join(next(p for p in (docs / "index.md").read_text().split("\n- ") if "How-to guides" in p).split())
    assert all(phrase in front for phrase in named.values()), front


def test_plain_install_sentence_matches_what_is_installed():
    # README and the first-report tutorial install with a plain `pip install .`, which works (tests/project/test_install.py builds one and runs
    # the scenes, compare and the quick report from it) and leaves out benchmarks/, tests/ and compare.studies
    import tomllib

    root = README.parent
    for page in (README, root / "docs/tutorials/first_report.md"):
        text = " ".join(page.read_text(encoding="utf-8").split())
        assert "pip install . && frictionnoise report --quick -o report" in text or (
            "pip install . frictionnoise report --quick -o report" in text), page
        assert "not install `benchmarks/`, `tests/` or the studies (`compare.studies`)" in text, page
    found = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]["find"]
    assert not [p for p in found["include"] if p.startswith(("benchmarks", "tests"))], found
    assert "compare.studies*" in found["exclude"], found
    assert (root / "benchmarks/__init__.py").exists()
    assert "def install_non_editable" in (root / "tests/installed.py").read_text()


def _extended_tests(root: Path) -> list:
    """(file, line, count) of each test function marked ``extended`` under tests/: its count of collected tests is
    the product of its ``parametrize`` lists' lengths."""
    import ast

    out = []
    for path in sorted((root / "tests").rglob("test_*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.FunctionDef):
                continue
            marks = [d for d in node.decorator_list if isinstance(d, (ast.Attribute, ast.Call))]
            names = [ast.unparse(d.func if isinstance(d, ast.Call) else d) for d in marks]
            if "pytest.mark.extended" in names:
                count = 1
                for d in marks:
                    if isinstance(d, ast.Call) and ast.unparse(d.func) == "pytest.mark.parametrize":
                        count *= len(d.args[1].elts)
                line = next(d.lineno for d, n in zip(marks, names) if n == "pytest.mark.extended")
                out.append((path, line, count))
    return out


def test_readme_names_the_extended_tests_ci_leaves_out():
    # The README's test command leaves the `extended` tests out and says how many there are and how to run them;
    # CI runs the README's command (.ci/run), and every extended test says which smaller test CI runs in its place
    # (a comment on its marker line or the one below).
    text = README.read_text(encoding="utf-8")
    root = README.parent
    words = {"Five": 5, "Six": 6, "Seven": 7, "Eight": 8, "Nine": 9, "Ten": 10}
    m = re.search(r"(\w+) tests that re-measure a study at full size", text)
    assert m and m.group(1) in words, "the README names the count of extended tests"
    assert '-m "slow and not timing and not extended"' in text and "-m extended" in text
    assert '-m "slow and not timing and not extended"' in (root / ".ci" / "run").read_text()
    found = _extended_tests(root)
    assert sum(c for _, _, c in found) == words[m.group(1)], found
    for path, line, _ in found:
        lines = path.read_text().splitlines()
        assert "CI" in lines[line - 1] + " " + lines[line], (path, line)
