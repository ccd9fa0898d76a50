"""A non-editable install ships the scenarios: `pip install .` into a fresh venv, then run them by name from
another folder (issue 14: a non-editable install used to lose every scene, silently)."""
import shutil
import site
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _ignore(folder, names):
    return [n for n in names if n in {".venv", ".git", "build", "__pycache__"} or n.endswith(".egg-info")]


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(python, frictionnoise executable, a folder outside the source tree, install seconds, build isolation) of a
    non-editable install into a fresh venv."""
    import setuptools

    tmp_path = tmp_path_factory.mktemp("install")
    t0 = time.perf_counter()
    src = tmp_path / "src"
    shutil.copytree(ROOT, src, ignore=_ignore)  # build from a copy: setuptools writes build/ into the source
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    py = venv / "bin" / "python"
    purelib = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], check=True,
                             capture_output=True, text=True).stdout.strip()
    # the dependencies (and pip) come from this interpreter's site-packages, appended after the fresh venv's own:
    # a plain path line in a .pth file does not run the .pth hooks there (so this checkout's editable finder stays
    # out) and the fresh install comes first on sys.path
    Path(purelib, "_parent_site.pth").write_text("\n".join(site.getsitepackages()) + "\n")
    # with a recent enough setuptools here, build without isolation (no registry access); else pip fetches it
    isolation = ["--no-build-isolation"] if int(setuptools.__version__.split(".")[0]) >= 77 else []
    r = subprocess.run([py, "-m", "pip", "install", "-q", "--no-deps", *isolation, str(src)], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    r = subprocess.run([py, "-c", "import engine_sim, scenarios; print(engine_sim.__file__); print(scenarios.__file__)"],
                       cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    where = r.stdout.split()
    assert all(Path(w).is_relative_to(venv) for w in where), where  # the installed copy, not this checkout
    return py, venv / "bin" / "frictionnoise", elsewhere, time.perf_counter() - t0, bool(isolation)


def _listed(exe, cwd) -> list:
    listed = subprocess.run([exe, "scenarios"], cwd=cwd, check=True, capture_output=True, text=True).stdout
    return [line.split()[0] for line in listed.splitlines() if line.strip()]


@pytest.mark.slow
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
    # every package folder of the tree is installed
    tree = sorted(".".join(d.relative_to(ROOT).parts) for d in ROOT.rglob("__init__.py") for d in [d.parent]
                  if d.parts[len(ROOT.parts)] in {"frictionnoise", "engine_sim", "reduced_models", "compare", "scenarios"})
    r = subprocess.run([py, "-c", "import importlib, sys\nfor m in sys.argv[1:]: importlib.import_module(m)", *tree],
                       cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0 and len(tree) >= 6, (tree, r.stderr[-2000:])
    print(f"install {t_install:.1f} s (build isolation: {'off' if isolation else 'on'}), "
          f"run by name {t2 - t1:.1f} s, compare {time.perf_counter() - t2:.1f} s, packages {tree}")


@pytest.mark.slow  # the quick report: about 2-3 min on 2 cores
def test_non_editable_install_quick_report_holds_every_shipped_scene(installed):
    """Issue 14's must-show: `frictionnoise report --quick` from another folder holds every shipped scene (it used
    to hold the model sections only, silently). The design, asked of the installed package: the quick report's
    studies are one per shipped scene (`compare.studies.scenes.scene_studies`) plus the models and any quick
    study of a scene beside a model (pads_multiscale against model Ib); the full report adds no scene of its own. Each scene is in summary.json and is a section of index.html
    with at least one figure."""
    import json
    import re

    py, exe, elsewhere, _, _ = installed
    names = _listed(exe, elsewhere)
    design = subprocess.run([py, "-c", "import json; from compare import studies; print(json.dumps("
                                       "[[s.key, s.quick] for s in studies.STUDIES]))"],
                            cwd=elsewhere, check=True, capture_output=True, text=True).stdout
    design = dict(json.loads(design))
    # the design: every shipped scene has a study of its own (key scenarios/<name>) in the quick report; further
    # studies of a scene (scenarios/<name>_model_Ib: a model beside it) may be quick or left to the full report
    own = {k.split("/", 1)[1]: quick for k, quick in design.items() if k.split("/", 1)[-1] in names}
    assert sorted(own) == names and all(own.values()), (own, names)
    quick_keys = sorted(k.split("/", 1)[1] for k, quick in design.items() if k.startswith("scenarios/") and quick)
    t0 = time.perf_counter()
    r = subprocess.run([exe, "report", "--quick", "-o", "rep"], cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    summary = json.loads((elsewhere / "rep" / "summary.json").read_text())
    assert sorted(summary["scenarios"]) == quick_keys, (sorted(summary["scenarios"]), quick_keys)
    html = (elsewhere / "rep" / "index.html").read_text()
    for name in names:
        assert summary["scenarios"][name], name  # numbers, not an empty entry
        anchor = "s-" + re.sub(r"[^A-Za-z0-9_-]+", "-", f"scenarios/{name}")
        section = html.split(f"<section id='{anchor}'>", 1)
        assert len(section) == 2, f"no section for {name}"
        assert "<figure" in section[1].split("</section>", 1)[0], f"no figure in the section of {name}"
        assert f"href='#{anchor}'" in html, f"{name} not in the contents"
    print(f"quick report from the installed package: {time.perf_counter() - t0:.1f} s, scenes {names}")
