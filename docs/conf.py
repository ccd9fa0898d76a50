"""Sphinx configuration of the frictionnoise documentation.

Build: ``python -m sphinx -W --keep-going -b html docs docs/_build/html`` (the ``docs`` extra installs the tools).
Tutorials are MyST markdown notebooks executed at every build (myst-nb, ``nb_execution_mode = "force"``); a cell
that raises fails the build, and so does a command-line cell (``!frictionnoise ...``) whose command fails.
"""
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # the source tree, also for the notebook kernels (below)
os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
# the tutorials' kernels draw inline (CI exports MPLBACKEND=Agg, under which a notebook shows no figure)
os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
sys.path.insert(0, str(ROOT / "docs" / "_ext"))
# the tutorials' command-line cells (``!frictionnoise ...``) run this environment's frictionnoise and fail the build
# when the command fails or is not found (docs/_ext/notebook_shell.py)
from notebook_shell import configure_kernels  # noqa: E402

configure_kernels()

from frictionnoise import package_version  # noqa: E402

project = "frictionnoise"
author = "the frictionnoise developers"
copyright = "2025-2026, the frictionnoise developers"
release = version = package_version()

extensions = [
    "myst_nb",  # MyST markdown pages and executed notebooks (brings myst_parser)
    "numpydoc",  # numpydoc docstrings: Parameters, Returns, ...
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax shipped with the site: equations render without a network
    "sphinxarg.ext",  # the CLI reference from its own argparse parser
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}
exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints", "jupyter_execute"]
root_doc = "index"

# executed tutorials: every build runs every notebook; an exception in a cell fails the build
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_in_temp = True  # files a tutorial writes go to a temporary folder, not into docs/
nb_execution_timeout = 300
nb_execution_show_tb = True
nb_merge_streams = True
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_ref_domains = ["std", "py"]  # markdown links: pages, labels and Python objects (not sphinx-argparse's domain)

autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "undoc-members": False}
autodoc_typehints = "none"  # the numpydoc sections carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "pydata_sphinx_theme"
html_title = f"frictionnoise {release}"
html_static_path = []
html_theme_options = {
    "navigation_depth": 2,
    "show_toc_level": 2,
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_last_updated_fmt = None
# the theme reads the colour mode from localStorage or this default; without one a first visit logs a console error
html_context = {"default_mode": "auto"}
