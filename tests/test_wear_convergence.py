"""Issue 17, item 1: the grain mass that pads_with_wear ships (wear.min_mass = 1e-4 kg) is converged in the solver
settings under the grain step rule (engine_sim.wear.grain_step: omega_g dt <= 0.6, here 2 substeps of 5e-5 s).

Measured (benchmarks/results/wear_convergence.md, 8 s runs, 1 s warm-up, seeds 0-2, paired): at 1e-4 kg and the
rule's step of 5e-5 s the grains' mean force on the pads reads 0.3925, 0.3789, 0.3618 N with energy residuals of
0.10-0.14 %; the step before the rule (1e-4 s, omega_g dt 0.65) read 1.0 +- 0.3 % less. At 1e-5 kg and above
omega_g dt 0.81 the same changes are +30-60 % with energy residuals of 2.4-8.1 %. The runs are deterministic, so
seed 0 below reproduces the table's seed-0 number; the bounds (6 % for a settings change, 1 % energy) leave room
for an engine change that moves them a little and fail if the shipped mass stops being converged in the settings.
"""
import numpy as np
import pytest

import engine_sim
from compare.studies._common import balances
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.wear import grain_step


def _grain_force(sc, seed=0):
    tr = engine_sim.run(sc, seed=seed)
    return float(tr.p_force.sum(axis=1).mean()), balances(tr)["energy_balance_rel"], tr


def test_grain_step_rule_is_the_measured_clean_branch():
    # omega_g dt <= 0.6 for the lightest grain: 1e-4 kg at run.dt 1e-4 s (0.65 by itself) takes 2 substeps; 1e-5 kg
    # takes 4 (2.5e-5 s, measured clean: residual 0.23 %); the trace states the rule
    sc = load_scenario(shipped_scenarios()["pads_with_wear"])
    g = grain_step(sc)
    assert g["substeps"] == 2 and g["dt_step"] == pytest.approx(5e-5) and g["omega_g_dt"] <= 0.6
    assert grain_step(sc.with_wear(min_mass=1e-5))["substeps"] == 4
    assert grain_step(sc.with_wear(count=0))["substeps"] == 1
    tr = engine_sim.run(sc.with_run(duration=0.02, warmup=0.0))
    assert tr.metadata["scene"]["grain_step"]["substeps"] == 2 and tr.metadata["steps"] == 2 * 10 * 20  # 20 output steps of 10 run.dt, each cut in 2


@pytest.mark.slow
def test_shipped_grain_mass_is_converged_in_iterations_and_dt():
    sc = load_scenario(shipped_scenarios()["pads_with_wear"]).with_run(duration=8.0, warmup=1.0)
    assert sc.wear.min_mass == 1e-4 and sc.run.iterations == 20 and grain_step(sc)["dt_step"] == 5e-5  # the measured setting
    f20, e20, tr = _grain_force(sc)
    f40, e40, _ = _grain_force(sc.with_run(iterations=40))
    fdt, edt, _ = _grain_force(sc.with_run(dt=2.5e-5))  # half the rule's step
    assert 0.3 < f20 < 0.45  # measured 0.3925 N (seeds 0-2: 0.362-0.393)
    assert abs(f40 / f20 - 1) < 0.06, f"doubling the iterations moved the grains' force by {100 * (f40 / f20 - 1):+.1f} %"
    assert abs(fdt / f20 - 1) < 0.06, f"halving dt moved the grains' force by {100 * (fdt / f20 - 1):+.1f} %"
    assert max(abs(e20), abs(e40), abs(edt)) < 0.01
    assert tr.metadata["wear"]["left_interface"] == 0 and tr.particle_penetration.max() < 8e-6
    assert np.all(np.isfinite(tr.p_force))
