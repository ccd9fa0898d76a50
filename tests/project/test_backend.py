"""Importing any project module, and drawing with it, leaves matplotlib's backend as the program set it (no module
calls matplotlib.use at import)."""
import subprocess
import sys

import pytest

from tests.modules import project_modules


@pytest.mark.slow  # a fresh interpreter importing all the project (numba, scipy, dask, SurfaceTopography: about 6 s)
def test_importing_every_module_and_drawing_keeps_the_backend():
    modules = sorted(project_modules())
    assert len(modules) > 40 and "compare.report.plots" in modules and "engine_sim.render" in modules
    code = f"""
import matplotlib
matplotlib.use("svg")  # a backend the program chose; pyplot not imported
import importlib
for m in {modules!r}:
    importlib.import_module(m)
    assert matplotlib.get_backend() == "svg", (m, matplotlib.get_backend())
import numpy as np
from compare.report import plots
from compare.analysis.spectra import displacement_spectrum
t = np.arange(4096) * 1e-3
spec = displacement_spectrum(t, np.cumsum(np.random.default_rng(0).standard_normal(t.size)))
png = plots.figure_png_bytes(plots.spectrum_figure([(spec, "walk")]))
assert png[:4] == b"\\x89PNG", png[:8]
from engine_sim import Scene, load_scenario
from engine_sim.render import SceneRenderer
r = SceneRenderer(Scene(load_scenario("pads_friction_patches")))
img = r.frame()
assert img.shape[2] == 4 and img.std() > 10
assert matplotlib.get_backend() == "svg", matplotlib.get_backend()
import sys
assert "matplotlib.pyplot" not in sys.modules  # no figure manager was ever created
print("ok")
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr[-3000:]
