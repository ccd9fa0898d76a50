"""The kernels that execute the tutorials: their command-line cells find this environment's ``frictionnoise`` and
fail the build when the command does.

A tutorial runs a command-line step as an IPython shell cell (``!frictionnoise analyze ...``). IPython runs such a
cell through the shell and only records the exit status in ``_exit_code``: a command that fails, or that the shell
cannot find, prints to the page and raises nothing, so myst-nb's ``nb_execution_raise_on_error`` never sees it.
:func:`configure_kernels` gives every kernel started after it an IPython start-up file that raises on a non-zero
exit status, and puts the running interpreter's ``bin`` folder first on ``PATH`` (a build started as
``.venv/bin/python -m sphinx`` without activating the environment finds the ``frictionnoise`` it installed).
"""
import os
import sys
import tempfile
from pathlib import Path

# IPython runs every ``*.py`` of ``$IPYTHONDIR/profile_default/startup`` when a kernel starts
STARTUP = '''\
from IPython import get_ipython

_shell = get_ipython()
_plain_system = _shell.system


def _system_or_raise(cmd):
    _plain_system(cmd)
    code = _shell.user_ns.get("_exit_code", 0)
    if code:
        raise RuntimeError(f"the command-line cell exited with status {code}: {cmd}")


_shell.system = _system_or_raise
'''


def configure_kernels() -> Path:
    """Set ``PATH`` and ``IPYTHONDIR`` for the kernels this process starts; return the IPython folder made.

    The folder is a new temporary one (IPython writes its history and connection files there), so the build leaves
    nothing in ``docs/`` and an IPython profile of the user's is neither read nor changed.
    """
    ipython_dir = Path(tempfile.mkdtemp(prefix="frictionnoise-docs-ipython-"))
    startup = ipython_dir / "profile_default" / "startup"
    startup.mkdir(parents=True)
    (startup / "00-command-cells-raise.py").write_text(STARTUP, encoding="utf-8")
    os.environ["IPYTHONDIR"] = str(ipython_dir)
    bin_dir = str(Path(sys.executable).parent)
    os.environ["PATH"] = os.pathsep.join(p for p in (bin_dir, os.environ.get("PATH")) if p)
    return ipython_dir
