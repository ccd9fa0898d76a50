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


@pytest.mark.slow
def test_non_editable_install_runs_shipped_scenarios_by_name(tmp_path):
    import setuptools

    from engine_sim import shipped_scenarios

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
    t_install = time.perf_counter() - t0
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    r = subprocess.run([py, "-c", "import engine_sim, scenarios; print(engine_sim.__file__); print(scenarios.__file__)"],
                       cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    where = r.stdout.split()
    assert all(Path(w).is_relative_to(venv) for w in where), where  # the installed copy, not this checkout
    exe = venv / "bin" / "frictionnoise"
    listed = subprocess.run([exe, "scenarios"], cwd=elsewhere, check=True, capture_output=True, text=True).stdout
    names = [line.split()[0] for line in listed.splitlines() if line.strip()]
    assert names == sorted(shipped_scenarios()), listed  # every shipped scene, none lost
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
