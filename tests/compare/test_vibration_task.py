"""compare.sweep.tasks on a shaken scene: the line removed before the spectrum and the mean forces kept."""
import math

import numpy as np
import pytest

from compare.sweep.spec import load_sweep
from compare.sweep.tasks import run_task
from engine_sim.scenario import SCENARIO_DIR

SWEEP = SCENARIO_DIR / "sweeps" / "vibration_sweep_force_1000hz.toml"


@pytest.mark.slow
def test_shaken_task_removes_the_line_and_keeps_the_mean_forces():
    spec = load_sweep(SWEEP)
    base = {"duration": 1.0, "run.warmup": 0.2, "vibration.frequency": 20.0}
    still = run_task(spec, {**base, "vibration.amplitude": 0.0}, 0)
    shaken = run_task(spec, {**base, "vibration.amplitude": 1e-4}, 0)
    assert "error" not in still and "error" not in shaken
    # the unshaken twin has no line to remove, and in steady sliding the friction's two parts balance the drive:
    # the block's momentum changes by M dv ~ 1e-5 N s over the 1 s record, so 1e-3 of the 2.3 N drive is ample
    assert "line_removed" not in still
    assert still["mean_F_t"] + still["mean_F_drag"] == pytest.approx(still["mean_F_drive"], rel=1e-3)
    # the shaken run: the line at omega_v and 3 harmonics fitted
    line = shaken["line_removed"]
    w = 2 * math.pi * 20.0
    assert line["omega"] == pytest.approx(w) and len(line["amplitude"]) == 4
    # the pads slide forward throughout (v / (A omega) / 0.055 = 7 > 1: the Coulomb part stays constant), so the
    # motion is linear: the block (0.1 kg) on the pads' springs (N k0 = 1e5 N/m) and the pads (0.03 kg) on the
    # viscous part (N c = 300 N s/m), all under the inertial force -m s''; the block's position relative to the
    # substrate then has the amplitude |x_b| below. The record's noise at 126 rad/s is far below this 5.7 um line
    # (C_x there ~1e-16 m^2 s over 1 s: ~1e-8 m), and 2 % covers the fit's 3 harmonics' leakage
    Mb, mp, K, C = 0.1, 30 * 1e-3, 30 * 3333.0, 300.0
    a = np.array([[K - Mb * w ** 2, -K], [-K, K + 1j * w * C - mp * w ** 2]])
    xb = np.linalg.solve(a, np.array([Mb, mp]) * w ** 2 * 1e-4)[0]
    assert line["amplitude"][0] == pytest.approx(abs(xb), rel=0.02)
    assert shaken["mean_F_drive"] == pytest.approx(still["mean_F_drive"], rel=1e-9)  # the same constant force
