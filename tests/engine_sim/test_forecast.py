"""A run's wall time projected before it starts (engine_sim.forecast): close to the run's own, and a line that says
what it rests on."""
import time

import pytest

import engine_sim
from engine_sim import load_scenario
from engine_sim.forecast import LONG_RUN_S, forecast


def test_forecast_line_and_arithmetic():
    sc = load_scenario("pads_friction_patches")
    f = forecast(sc, duration=2.0)
    assert f.simulated_s == pytest.approx(sc.run.warmup + 2.0)
    n_out = round((sc.run.warmup + 2.0) / sc.run.dt_out) + 1
    assert f.wall_s == pytest.approx(2 * f.build_s + f.per_simulated_s * sc.run.dt_out * n_out, rel=1e-12)
    assert 1 <= f.probe_outputs <= 64
    assert f.line().startswith("projected wall time about ") and "wall s per simulated s" in f.line()
    # a run of 10^4 simulated seconds of this scene (tens of microseconds a step) is well over a minute
    assert forecast(sc, duration=1e4).wall_s > LONG_RUN_S


@pytest.mark.slow
@pytest.mark.timing
def test_forecast_is_near_the_run():
    """The projection against the run it projects, one after the other in this process (the numba kernels loaded
    by the first): within a factor 3 either way, enough to tell a run of seconds from one of many minutes. Measured
    run/forecast 1.15 under a load of 5 and 3.2 under a load of 10 on 2 cores, where other processes' bursts
    lengthen the run more than the probe's median step; the timing tier runs alone on one core."""
    sc = load_scenario("line_scan_example")
    engine_sim.run(sc, duration=0.05)  # loads the kernels, reads the profile: the fixed costs of a fresh process
    f = forecast(sc, duration=3.0)
    t0 = time.perf_counter()
    engine_sim.run(sc, duration=3.0)
    wall = time.perf_counter() - t0
    print(f"forecast {f.wall_s:.1f} s, run {wall:.1f} s")
    assert 1 / 3 < wall / f.wall_s < 3.0
