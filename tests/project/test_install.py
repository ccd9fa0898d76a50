"""A non-editable install ships the scenarios: `pip install .` into a fresh venv, then run them by name from another
folder (the scenario files are package data: an install without them would lose every scene, silently). The install
and its one quick report (of every scene) are session fixtures (tests/installed.py, conftest.py): tests/compare/test_report_cli.py reads the
same every-scene report. The tests are in the slow tier's `timing` group (one core, nothing beside them): a quick report runs its
own worker processes on both cores."""
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = [pytest.mark.slow, pytest.mark.timing]


def _listed(exe, cwd) -> list:
    listed = subprocess.run([exe, "scenarios"], cwd=cwd, check=True, capture_output=True, text=True).stdout
    return [line.split()[0] for line in listed.splitlines() if line.strip() and not line[0].isspace()]


def test_non_editable_install_runs_shipped_scenarios_by_name(installed):
    from engine_sim import shipped_scenarios

    py, exe, elsewhere, t_install, isolation = installed
    names = _listed(exe, elsewhere)
    assert names == sorted(shipped_scenarios()), names  # every shipped scene, none lost
    t1 = time.perf_counter()
    r = subprocess.run([exe, "run", "pads_friction_patches", "--duration", "0.5", "-o", "out"], cwd=elsewhere,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    assert (elsewhere / "out" / "trace.npz").exists() and (elsewhere / "out" / "trace.json").exists()
    t2 = time.perf_counter()
    # the report's machinery (compare.studies once went uninstalled: report and compare failed after pip install .)
    r = subprocess.run([exe, "compare", "pads_friction_patches", "--duration", "2", "-o", "cmp"], cwd=elsewhere,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    assert (elsewhere / "cmp" / "index.html").exists() and (elsewhere / "cmp" / "summary.json").exists()
    # every package folder of the tree is installed but the research studies, which run from a checkout
    # (pyproject.toml excludes compare.studies; docs/explanation/benchmarks.md)
    tree = sorted(".".join(d.relative_to(ROOT).parts) for d in ROOT.rglob("__init__.py") for d in [d.parent]
                  if d.parts[len(ROOT.parts)] in {"frictionnoise", "engine_sim", "reduced_models", "compare"})
    studies = [m for m in tree if m == "compare.studies" or m.startswith("compare.studies.")]
    tree = [m for m in tree if m not in studies]
    r = subprocess.run([py, "-c", "import importlib, sys\nfor m in sys.argv[1:]: importlib.import_module(m)", *tree],
                       cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0 and len(tree) >= 6 and studies, (tree, r.stderr[-2000:])
    r = subprocess.run([py, "-c", "import compare.studies"], cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode != 0 and "No module named 'compare.studies'" in r.stderr, r.stderr[-2000:]
    print(f"install {t_install:.1f} s (build isolation: {'off' if isolation else 'on'}), "
          f"run by name {t2 - t1:.1f} s, compare {time.perf_counter() - t2:.1f} s, packages {tree}")


def _design(py, elsewhere) -> dict:
    """The installed package's registry: study key -> (quick, headline)."""
    import json

    out = subprocess.run([py, "-c", "import json; from compare.report import studies; print(json.dumps("
                                    "[[s.key, [s.quick, s.headline]] for s in studies.STUDIES]))"],
                         cwd=elsewhere, check=True, capture_output=True, text=True).stdout
    return {k: tuple(v) for k, v in json.loads(out)}


def _sections_hold_figures(html: str, names) -> None:
    """Each named scene is a section of the page, in its contents, with at least one figure."""
    import re

    for name in names:
        anchor = "s-" + re.sub(r"[^A-Za-z0-9_-]+", "-", f"scenarios/{name}")
        section = html.split(f"<section id='{anchor}'>", 1)
        assert len(section) == 2, f"no section for {name}"
        assert "<figure" in section[1].split("</section>", 1)[0], f"no figure in the section of {name}"
        assert f"href='#{anchor}'" in html, f"{name} not in the contents"


def _fits(node, path=""):
    """(path, fit) of every exponent fit in a summary.json: a dict with "gamma" and "gamma_err"."""
    if isinstance(node, dict):
        if "gamma" in node and "gamma_err" in node:
            yield path, node
        for k, v in node.items():
            yield from _fits(v, f"{path}/{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _fits(v, f"{path}[{i}]")


def _study_of(path: str) -> str:
    """The study key of a summary.json path from `_fits`: "/scenarios/NAME/..." -> "scenarios/NAME", "/KEY/..." ->
    "KEY"."""
    parts = path.strip("/").split("/")
    key = "/".join(parts[:2]) if parts[0] == "scenarios" else parts[0]
    return key.split("[", 1)[0]


# The README's main job. One quick report runs per session, with every scene (`--quick --all-scenes`): its models and
# headline scenes are those of `report --quick` (the same studies, code and seed, so the same numbers), and the
# registry asked of the installed package says `--quick` selects exactly these; the quick page's pointer to
# --all-scenes is tested in-process (tests/compare/test_report_studies.py). A second installed report would cost
# CI's timing group about a minute of both cores and check nothing these do not.
def test_non_editable_install_quick_report_holds_the_models_and_the_headline_scenes(installed,
                                                                                    installed_all_scenes_report):
    """`frictionnoise report --quick` (the README's first command) from another folder: its studies (the installed
    registry's quick selection) are the models and the headline scenes (compare.report.studies.scenes.HEADLINE_SCENES:
    one per mechanism of the paper); the installed quick report holds each, a section with a figure, and every
    exponent it quotes is the record model's, as docs/results/report_exponents.md quotes it."""
    import json

    py, exe, elsewhere, _, _ = installed
    design = _design(py, elsewhere)
    headline = sorted(k.split("/", 1)[1] for k, (quick, head) in design.items()
                      if k.startswith("scenarios/") and quick and head)
    assert headline == ["asperity_field", "pads_friction_patches", "pads_with_wear"], headline
    quick_keys = subprocess.run([py, "-c", "from compare.report import studies; "
                                           "print(' '.join(s.key for s in studies.selected(True)))"],
                                cwd=elsewhere, check=True, capture_output=True, text=True).stdout.split()
    assert sorted(k for k in quick_keys if k.startswith("scenarios/")) == [f"scenarios/{n}" for n in headline]
    assert {"model_I", "model_II", "model_III", "model_Ib"} <= set(quick_keys), quick_keys
    rep, wall = installed_all_scenes_report  # `report --quick --all-scenes -o rep-all` run by `exe` in `elsewhere`
    summary = json.loads((rep / "summary.json").read_text())
    assert set(headline) <= set(summary["scenarios"]), sorted(summary["scenarios"])
    assert {"model_I", "model_II", "model_III", "model_Ib"} <= set(summary), sorted(summary)
    _sections_hold_figures((rep / "index.html").read_text(), headline)
    # every exponent of the quick report's studies is the record model's (compare.analysis.record_model), fitted to
    # the record, and docs/results/report_exponents.md quotes each of them as this report reads it (seed 0, bit for bit)
    fits = {p: f for p, f in _fits(summary) if _study_of(p) in quick_keys}
    assert len(fits) >= 20 and {p for p, f in fits.items() if f.get("method") != "record"} == set()
    page = (ROOT / "docs" / "results" / "report_exponents.md").read_text()
    missing = [p for p, f in fits.items() if f"{f['gamma']:.3f} ± {f['gamma_err']:.3f}" not in page]
    assert not missing, missing
    print(f"quick report of every scene from the installed package: {wall:.1f} s, headline scenes {headline}")


# every scene at its quick length: about 70 s on 2 idle cores, once per session
def test_non_editable_install_all_scenes_report_holds_every_shipped_scene(installed, installed_all_scenes_report):
    """`frictionnoise report --quick --all-scenes` from another folder holds every shipped scene, not only the model
    sections. The design, asked of the installed package: the quick studies are one per shipped scene
    (`compare.report.studies.scenes.scene_studies`) plus the models and any quick study of a scene beside a model
    (pads_multiscale against model Ib); the full report adds no scene of its own. Each scene is in summary.json and
    is a section of index.html with at least one figure."""
    import json

    py, exe, elsewhere, _, _ = installed
    names = _listed(exe, elsewhere)
    design = _design(py, elsewhere)
    # every shipped scene has a study of its own (key scenarios/<name>) in the quick report; further studies of a
    # scene (scenarios/<name>_model_Ib: a model beside it) may be quick or left to the full report
    own = {k.split("/", 1)[1]: quick for k, (quick, _) in design.items() if k.split("/", 1)[-1] in names}
    assert sorted(own) == names and all(own.values()), (own, names)
    quick_keys = sorted(k.split("/", 1)[1] for k, (quick, _) in design.items() if k.startswith("scenarios/") and quick)
    rep, wall = installed_all_scenes_report
    summary = json.loads((rep / "summary.json").read_text())
    quick_keys = sorted({*quick_keys, "pads_multiscale_model_Ib"})  # the pads_multiscale study serves model Ib too
    assert sorted(summary["scenarios"]) == quick_keys, (sorted(summary["scenarios"]), quick_keys)
    for name in names:
        assert summary["scenarios"][name], name  # numbers, not an empty entry
    _sections_hold_figures((rep / "index.html").read_text(), names)
    print(f"quick report of every scene from the installed package: {wall:.1f} s, scenes {names}")
