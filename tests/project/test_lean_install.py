"""A lean install: the shipped scenarios are package data of engine_sim (no top-level `scenarios` module), a shipped
file is had by name (`frictionnoise scenarios NAME [--copy DEST]`), and the core commands run without the extras
(dask, xarray/h5netcdf, openpyxl, npTDMS, SurfaceTopography, the docs and test tools), a command that needs one
naming it in one line."""
import fnmatch
import os
import subprocess
import sys
import tomllib
from dataclasses import replace
from pathlib import Path, PurePosixPath

import pytest

from compare.cli import main
from engine_sim import ScenarioError, load_scenario, shipped_scenarios
from engine_sim.shipped import SCENARIO_DIR, resolve_scenario, shipped_file, shipped_files, shipped_path

ROOT = Path(__file__).resolve().parents[2]

# the top-level modules of every extra (pyproject.toml's optional-dependencies) and of the docs and test tools
OPTIONAL = ("dask", "distributed", "xarray", "h5netcdf", "h5py", "netCDF4", "openpyxl", "nptdms", "SurfaceTopography",
            "sphinx", "numpydoc", "myst_parser", "myst_nb", "sphinxarg", "pydata_sphinx_theme", "ipykernel",
            "hypothesis", "selenium", "importlinter", "pytest")


def test_scenarios_name_prints_the_shipped_file(capsys):
    assert main(["scenarios", "tilted_plane"]) == 0
    assert capsys.readouterr().out == (SCENARIO_DIR / "tilted_plane.toml").read_text(encoding="utf-8")
    # a sweep or data file by its path in the shipped folder, with or without `scenarios/` and `.toml`
    for name in ("sweeps/velocity_model1", "scenarios/sweeps/velocity_model1.toml"):
        assert main(["scenarios", name]) == 0
        assert capsys.readouterr().out == (SCENARIO_DIR / "sweeps" / "velocity_model1.toml").read_text("utf-8")


def test_scenarios_copy_writes_the_shipped_file_and_never_overwrites(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["scenarios", "pads_friction_patches", "--copy", "mine.toml"]) == 0
    assert capsys.readouterr().out.strip() == "mine.toml"
    mine = tmp_path / "mine.toml"
    assert mine.read_bytes() == (SCENARIO_DIR / "pads_friction_patches.toml").read_bytes()
    copy, shipped = load_scenario(str(mine)), load_scenario("pads_friction_patches")
    assert replace(copy, name=shipped.name) == shipped  # the same scenario under the copy's name
    # into an existing folder: a file of the same name there
    (tmp_path / "d").mkdir()
    assert main(["scenarios", "data/model1_synthetic_um.csv", "--copy", "d"]) == 0
    assert (tmp_path / "d" / "model1_synthetic_um.csv").read_bytes() == \
        (SCENARIO_DIR / "data" / "model1_synthetic_um.csv").read_bytes()
    capsys.readouterr()
    mine.write_text("# my edits\n")
    assert main(["scenarios", "pads_friction_patches", "--copy", "mine.toml"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "mine.toml: already exists" in err, err
    assert mine.read_text() == "# my edits\n"  # nothing overwritten


def test_readme_copy_of_a_shipped_scene_runs(tmp_path, monkeypatch):
    # README: `frictionnoise scenarios tilted_plane --copy mine.toml`, a scene to start your own, then run it
    monkeypatch.chdir(tmp_path)
    assert main(["scenarios", "tilted_plane", "--copy", "mine.toml"]) == 0
    assert main(["run", "mine.toml", "--duration", "0.2", "-o", "r"]) == 0
    assert (tmp_path / "r" / "trace.npz").exists()


def test_scenarios_name_errors_are_one_line(capsys):
    assert main(["scenarios", "pads_friction_patch"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "did you mean pads_friction_patches" in err and "--all" in err, err
    assert main(["scenarios", "--copy", "x.toml"]) == 2
    assert "name the shipped file" in capsys.readouterr().err
    with pytest.raises(ScenarioError):
        shipped_path("../shipped.py")  # only the listed shipped files, never a path out of the folder


def test_scenarios_all_lists_the_sweeps_data_and_profiles(capsys):
    assert main(["scenarios", "--all"]) == 0
    out = capsys.readouterr().out.splitlines()
    listed = set(out)
    others = [f for f in shipped_files() if "/" in f]
    assert {"sweeps/velocity_model1.toml", "data/model1_synthetic_um.csv", "profiles/synthetic_scan_um.csv"} <= set(
        others) <= listed
    assert [ln.split()[0] for ln in out if ln and not ln[0].isspace()][: len(shipped_scenarios())] == sorted(
        shipped_scenarios())  # the scenes first, as without --all
    assert not any(f.endswith(".py") for f in shipped_files())  # the data's generator script is not a shipped file


def test_docs_paths_resolve_inside_the_package_from_any_folder(tmp_path, monkeypatch):
    # the README and the docs write shipped files as scenarios/...: from a folder without such a file, every shipped
    # file is read inside engine_sim's package data; a file of that spelling in the current folder wins
    monkeypatch.chdir(tmp_path)
    for f in shipped_files():
        assert shipped_file(f"scenarios/{f}") == str(SCENARIO_DIR.joinpath(*f.split("/"))), f
    assert resolve_scenario("scenarios/sweeps/velocity_model1.toml") == SCENARIO_DIR / "sweeps" / "velocity_model1.toml"
    assert resolve_scenario("pads_friction_patches") == SCENARIO_DIR / "pads_friction_patches.toml"
    (tmp_path / "scenarios" / "data").mkdir(parents=True)
    (tmp_path / "scenarios" / "data" / "model1_synthetic_um.csv").write_text("t,x\n")
    assert shipped_file("scenarios/data/model1_synthetic_um.csv") == "scenarios/data/model1_synthetic_um.csv"


PACKAGES = ("frictionnoise", "engine_sim", "reduced_models", "compare")


def test_every_shipped_file_is_package_data_and_no_scenarios_module_is_installed():
    # pyproject.toml's package-data globs cover every file of the shipped folder but its generator script (a new
    # file they missed would be lost by a non-editable install, silently); no top-level `scenarios` is a package
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    globs = cfg["package-data"]["engine_sim"]
    files = [p.relative_to(SCENARIO_DIR.parent).as_posix() for p in SCENARIO_DIR.rglob("*")
             if p.is_file() and "__pycache__" not in p.parts]

    def covered(f, g):  # setuptools' glob: a * never crosses a folder
        fp, gp = PurePosixPath(f).parts, PurePosixPath(g).parts
        return len(fp) == len(gp) and all(fnmatch.fnmatchcase(a, b) for a, b in zip(fp, gp))

    missed = [f for f in files if not any(covered(f, g) for g in globs)]
    assert missed == ["scenarios/data/make_reciprocating.py"], missed
    assert not any(i.startswith("scenarios") for i in cfg["packages"]["find"]["include"])
    # the data folders are found as namespace folders of engine_sim (setuptools ships them without warning); only the
    # project's four packages are searched, and the repository has no top-level scenarios folder to find
    assert all(i.split("*")[0].split(".")[0] in PACKAGES for i in cfg["packages"]["find"]["include"])
    assert not (ROOT / "scenarios").exists() and not (SCENARIO_DIR / "__init__.py").exists()


# run at start-up (a sitecustomize first on the path): the path finder no longer sees the optional modules, so
# `import` raises ModuleNotFoundError and importlib.util.find_spec answers None, as for a module never installed
# (pint asks find_spec before it imports dask; scipy asks sys.modules for sphinx)
_MISSING = """import sys
from importlib.machinery import PathFinder

class _Missing(PathFinder):
    @classmethod
    def find_spec(cls, name, path=None, target=None):
        return None if name.split(".")[0] in {names!r} else PathFinder.find_spec(name, path, target)

sys.meta_path[:] = [_Missing if f is PathFinder else f for f in sys.meta_path]
"""


def _blocker(tmp_path) -> dict:
    """An environment in which every optional module is missing, as an uninstalled one is (:data:`_MISSING`)."""
    block = tmp_path / "block"
    block.mkdir()
    (block / "sitecustomize.py").write_text(_MISSING.format(names=set(OPTIONAL)))
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(block), str(ROOT)])}


_CORE = """
import sys
import matplotlib, numba, numpy, pint, pymunk, scipy, tqdm  # the core dependencies
optional = lambda: {m.split(".")[0] for m in sys.modules} & set(sys.argv[2:])
theirs = optional()  # what those import on their own when it is there (pint's dask support)
from compare.cli.main import main
out = sys.argv[1]
rc = [main(["analyze", "scenarios/data/model1_synthetic_um.csv", "--mass", "1", "-o", out + "/a"]),
      main(["run", "pads_friction_patches", "--duration", "0.2", "-o", out + "/r"])]
import compare.report.studies, compare.report.build  # what `report` runs: every study's module
print(rc)
print(sorted(optional() - theirs))
"""


def test_core_commands_import_nothing_optional(tmp_path):
    # analyze on the shipped record, run by name and the report's modules, in a fresh interpreter with every extra
    # installed: they import no optional module beyond what the core dependencies import by themselves when it is
    # present (pint imports dask for its own dask support; without dask it does without)
    r = subprocess.run([sys.executable, "-c", _CORE, str(tmp_path), *OPTIONAL], cwd=tmp_path, capture_output=True,
                       text=True, timeout=600, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.splitlines()[-2:] == ["[0, 0]", "[]"], r.stdout


@pytest.mark.slow
def test_without_the_extras_run_compare_and_analyze_work_and_sweep_names_its_extra(tmp_path):
    env = _blocker(tmp_path)
    for args, made in ((["run", "pads_friction_patches", "--duration", "0.2", "-o", "r"], "r/trace.npz"),
                       (["analyze", "scenarios/data/model1_synthetic_um.csv", "--mass", "1", "-o", "a"], "a/index.html"),
                       (["compare", "pads_friction_patches", "--duration", "2", "-o", "c"], "c/summary.json")):
        r = subprocess.run([sys.executable, "-m", "compare.cli", *args], cwd=tmp_path, capture_output=True, text=True,
                           timeout=900, env=env)
        assert r.returncode == 0 and (tmp_path / made).exists(), (args, r.stderr[-2000:])
    r = subprocess.run([sys.executable, "-m", "compare.cli", "sweep", "scenarios/sweeps/velocity_model1.toml", "-o",
                        "s"], cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert "pip install 'frictionnoise[sweep]'" in r.stderr and not (tmp_path / "s").exists()


@pytest.mark.slow
def test_non_editable_install_has_no_scenarios_module_and_runs_from_another_folder(installed):
    py, exe, elsewhere, _, _ = installed
    r = subprocess.run([py, "-c", "import scenarios"], cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode != 0 and "No module named 'scenarios'" in r.stderr, r.stderr
    r = subprocess.run([exe, "run", "pads_friction_patches", "--duration", "0.2", "-o", "lean-run"], cwd=elsewhere,
                       capture_output=True, text=True)
    assert r.returncode == 0 and (elsewhere / "lean-run" / "trace.npz").exists(), r.stderr[-2000:]
    # every shipped file is in the install, and a copy of one is had by name
    listed = subprocess.run([py, "-c", "from engine_sim.shipped import shipped_files, SCENARIO_DIR\n"
                                       "print(SCENARIO_DIR); print('\\n'.join(shipped_files()))"],
                            cwd=elsewhere, check=True, capture_output=True, text=True).stdout.split()
    assert Path(listed[0]).is_relative_to(Path(py).parent.parent) and listed[1:] == shipped_files(), listed
    r = subprocess.run([exe, "scenarios", "sweeps/velocity_model1", "--copy", "lean-copy"], cwd=elsewhere,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert (elsewhere / "lean-copy").read_bytes() == (SCENARIO_DIR / "sweeps" / "velocity_model1.toml").read_bytes()
