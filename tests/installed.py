"""A non-editable install of this checkout into a fresh venv, and its quick report of every scene: built once per
test session (the fixtures ``installed`` and ``installed_all_scenes_report`` in conftest.py), shared by
tests/project/test_install.py and tests/compare/test_report_cli.py (one installed report per CI run: it keeps both
cores busy for one to two minutes)."""
import shutil
import site
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _ignore(folder, names):
    return [n for n in names if n in {".venv", ".git", "build", "__pycache__"} or n.endswith(".egg-info")]


def install_non_editable(tmp_path: Path):
    """(python, frictionnoise executable, a folder outside the source tree, install seconds, build isolation) of a
    non-editable install into a fresh venv under ``tmp_path``."""
    import setuptools

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
    r = subprocess.run([py, "-c", "import engine_sim, compare; print(engine_sim.__file__); print(compare.__file__)"],
                       cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    where = r.stdout.split()
    assert all(Path(w).is_relative_to(venv) for w in where), where  # the installed copy, not this checkout
    return py, venv / "bin" / "frictionnoise", elsewhere, time.perf_counter() - t0, bool(isolation)


def quick_report(installed, *extra: str, out: str = "rep") -> tuple:
    """`frictionnoise report --quick [extra] -o out` run by the installed executable in its folder outside the
    source tree, with the report's default workers: (output folder, wall seconds)."""
    _, exe, elsewhere, _, _ = installed
    t0 = time.perf_counter()
    r = subprocess.run([exe, "report", "--quick", *extra, "-o", out], cwd=elsewhere, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    return elsewhere / out, time.perf_counter() - t0
