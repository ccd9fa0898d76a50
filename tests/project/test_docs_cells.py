"""The tutorials' command-line cells are tested by the documentation build: a ``!command`` cell whose command fails
or is not found fails ``sphinx -W`` (IPython alone only prints the shell's complaint), and a build started with the
environment's interpreter without activating it finds that environment's ``frictionnoise``
(docs/_ext/notebook_shell.py, called by docs/conf.py).
"""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("myst_nb", reason="the docs extra (pip install -e '.[docs]') builds the documentation")
pytestmark = pytest.mark.slow  # two small Sphinx builds, each starting a kernel (about 10 s together)

DOCS = Path(__file__).resolve().parents[2] / "docs"

CONF = f'''
import sys
sys.path.insert(0, {str(DOCS / "_ext")!r})
from notebook_shell import configure_kernels
configure_kernels()
extensions = ["myst_nb"]
source_suffix = {{".md": "myst-nb"}}
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_show_tb = True  # as docs/conf.py: the failing cell and its message in the build log
exclude_patterns = ["_build"]
'''

PAGE = """---
file_format: mystnb
kernelspec:
  name: python3
---
# A tutorial

```{{code-cell}} ipython3
!{command}
```
"""


def _build(tmp_path: Path, command: str) -> subprocess.CompletedProcess:
    src = tmp_path / "src"
    src.mkdir()
    (src / "conf.py").write_text(CONF, encoding="utf-8")
    (src / "index.md").write_text(PAGE.format(command=command), encoding="utf-8")
    # the environment's bin folder deliberately off PATH: the build must find frictionnoise by itself
    env = {**os.environ, "PATH": "/usr/bin:/bin"}
    env.pop("IPYTHONDIR", None)
    return subprocess.run([sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html", str(src), str(tmp_path / "out")],
                          capture_output=True, text=True, env=env, timeout=300)


def _log(done: subprocess.CompletedProcess) -> str:
    """The build's output and the full traceback Sphinx saves to a file on an exception (the cell's error is there)."""
    text = done.stdout + done.stderr
    saved = re.search(r"traceback has been saved in:\s*(\S+)", text)
    return text + (Path(saved.group(1)).read_text(encoding="utf-8") if saved else "")


def test_a_failing_command_cell_fails_the_build(tmp_path):
    done = _build(tmp_path, "frictionnoise analyze no-such-file.csv")
    assert done.returncode != 0
    assert "exited with status 2" in _log(done)


def test_a_command_not_found_fails_the_build(tmp_path):
    done = _build(tmp_path, "no-such-command-anywhere --help")
    assert done.returncode != 0
    assert "exited with status 127" in _log(done)


def test_a_working_command_cell_builds_with_the_environments_frictionnoise(tmp_path):
    done = _build(tmp_path, "frictionnoise --version")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "frictionnoise" in (tmp_path / "out" / "index.html").read_text(encoding="utf-8")


def test_the_documentation_configures_its_kernels():
    # docs/conf.py itself must install the start-up file: executing it sets IPYTHONDIR to a folder holding it. Run in
    # a child process: conf.py also sets PYTHONPATH and sys.path for the build, which would leak into later tests
    code = ("import os, runpy; runpy.run_path(os.environ['CONF']); print(os.environ['IPYTHONDIR'])")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "CONF": str(DOCS / "conf.py")})
    assert done.returncode == 0, done.stderr[-2000:]
    startup = Path(done.stdout.split()[-1]) / "profile_default" / "startup"
    assert any("_exit_code" in f.read_text() for f in startup.glob("*.py"))
