"""The engine at the edges of its stable region; each run asserts no NaN, contact overlap within the
collision slop, friction = drive and the energy balance within 2 %, and steady sliding."""
from dataclasses import replace

import numpy as np
import pytest

pytestmark = pytest.mark.slow  # hard cases: long or extreme runs

import engine_sim
from engine_sim import ScenarioError, load_scenario, scenario_from_dict, shipped_scenarios

BASE = load_scenario(shipped_scenarios()["pads_friction_patches"])


def _check(sc, tr, v_tol=0.05):
    assert np.all(np.isfinite(tr.x)) and np.all(np.isfinite(tr.pad_force))
    assert tr.penetration.max() < 2e-7  # m; the collision slop is 1e-7 m
    assert np.mean(tr.F_t + tr.F_drag) == pytest.approx(np.mean(tr.F_drive), rel=0.02)
    W = tr.work_drive[-1]
    assert (W - tr.dissipated[-1] - tr.mech_energy[-1]) / W == pytest.approx(0.0, abs=0.02)
    v = (tr.x[-1] - tr.x[0]) / tr.t[-1]
    assert v == pytest.approx(sc.steady_velocity, rel=v_tol)
    h = len(tr.t) // 2
    for q in np.array_split(np.arange(h, len(tr.t)), 4):
        assert (tr.x[q[-1]] - tr.x[q[0]]) / (tr.t[q[-1]] - tr.t[q[0]]) == pytest.approx(v, rel=0.10)


def test_time_step_at_the_claimed_limit():
    lim = BASE.dt_limit  # 1.47e-4 s: omega dt = 0.3 for the stiffest pad spring
    sc = BASE.with_run(dt=lim, dt_out=10 * lim, duration=3.0, warmup=0.5)
    _check(sc, engine_sim.run(sc))  # measured: v 4.992 mm/s, energy 7e-6


def test_tenth_of_the_normal_load():
    sc = replace(BASE, block=replace(BASE.block, M=BASE.block.M / 10)).with_run(duration=3.0, warmup=0.5)
    _check(sc, engine_sim.run(sc))  # measured: v 5.001 mm/s


def test_pmma_on_tile_speed_100_mm_per_s():
    # Table 3: PMMA on tile slid at 83-102 mm/s. Substrate streamed 20x faster; measured v 100.5 mm/s.
    sc = replace(BASE, drive=replace(BASE.drive, v=0.1)).with_run(duration=1.0, warmup=0.2)
    tr = engine_sim.run(sc)
    _check(sc, tr)
    assert tr.metadata["segments_generated"] > 3 * tr.metadata["segments_live"]


def test_steep_roughness_is_refused_at_load_with_its_limit():
    # rms slope 1 pins the block (measured: v = 0); the loader refuses it and names the limit
    rough = load_scenario(shipped_scenarios()["pads_rough_profile"]).to_dict()
    rough["substrate"]["rms_slope"] = 1.0
    with pytest.raises(ScenarioError, match=r"substrate.rms_slope = 1.0 exceeds the sliding limit 0.278"):
        scenario_from_dict(rough)


def test_time_step_beyond_the_limit_is_refused():
    with pytest.raises(ScenarioError, match=r"run.dt = 0.0003 s exceeds the pad spring limit 0.000147 s"):
        scenario_from_dict({"run": {"dt": 3e-4, "dt_out": 3e-3}})


@pytest.mark.timing  # CPU time per simulated second, far along the track against near its start
def test_cost_flat_and_substrate_bounded_over_two_metres():
    # 2 m of sliding at 100 mm/s. A scene that has slid 1.35 m steps no dearer than a fresh one (within 20 %), and
    # the live substrate does not grow: the segments alive at 2 m are no more than two chunks ahead and the kept
    # window behind, while > 25x as many were generated.
    import time

    from engine_sim.loop import warm_up
    from engine_sim.scene import Scene
    from engine_sim.units import LENGTH

    sc = replace(BASE, drive=replace(BASE.drive, v=0.1)).with_run(warmup=0.0)
    n_per_s = int(round(1.0 / sc.run.dt_out))
    far = Scene(sc)
    warm_up(far, int(13.5 * n_per_s))  # to 1.35 m, unrecorded: maintenance and stepping, what grows if anything does
    near = Scene(sc)
    warm_up(near, int(0.5 * n_per_s))  # past the start-up transient
    # The two scenes take turns chunk by chunk in this process, each chunk timed on the process's CPU clock, so a
    # neighbour process or a slower spell of the machine weighs on both alike (a fresh-clone CI read a late window
    # 1.25-1.30x an early one of the same run, on the wall and on the CPU clock, where the same test run alone read
    # 0.88-1.01). The floor of each scene's chunks: the rate has no trend but spikes (garbage collection of dropped
    # segments) that only add time.
    chunk = 8 * 64  # output steps (a multiple of the maintenance interval): 0.512 s simulated
    cost = {"near": [], "far": []}
    for _ in range(6):
        for name, scene in (("near", near), ("far", far)):
            c0 = time.process_time()
            warm_up(scene, chunk)
            cost[name].append(time.process_time() - c0)
    early, late = min(cost["near"]), min(cost["far"])
    # one-sided: the requirement guards against cost growing with the distance slid
    assert late <= 1.20 * early, cost
    warm_up(far, 20 * n_per_s - far.steps // far.n_sub)  # on to 20 s simulated
    x_far = far.block.position.x / LENGTH
    assert x_far > 1.99  # m
    generated = sum(t.generated for t in far.tracks)
    live = sum(len(t.segments) for t in far.tracks)
    assert generated > 25 * live  # measured 37x over 2 m
    assert live <= sc.pads.N * (2 * 32 + 12 + 1)  # two chunks ahead + the kept window


def test_a_thousand_wear_particles():
    # 1000 grains (34 per track) on pads_with_wear at 30 solver iterations: crowded grains push one another
    # ahead of the pads, and at the scenario's 20 iterations the contact solver is not converged for such
    # piles (10 iterations read 6.7 % off the energy balance and a 2x slower block; measured). Measured at 30:
    # no NaN, deepest grain overlap 2.1 um and pad overlap 2.3 um, none lost, energy 0.55 %, friction = drive
    # 0.16 %, block at 2.9 mm/s (grains add friction), 850 of 1000 grains asleep at the end.
    sc = load_scenario(shipped_scenarios()["pads_with_wear"])
    sc = sc.with_wear(count=1000, ahead=14e-3).with_run(duration=2.0, warmup=0.5, iterations=30)
    tr = engine_sim.run(sc)
    assert np.all(np.isfinite(tr.x)) and np.all(np.isfinite(tr.p_force))
    assert tr.particle_penetration.max() < 8e-6 and tr.penetration.max() < 8e-6
    assert tr.metadata["wear"]["left_interface"] == 0
    assert tr.metadata["wear"]["asleep_at_end"] > 500  # grains waiting ahead cost nothing
    assert np.mean(tr.F_t + tr.F_drag) == pytest.approx(np.mean(tr.F_drive), rel=0.02)
    W = tr.work_drive[-1]
    assert (W + tr.work_recycle[-1] - tr.dissipated[-1] - tr.mech_energy[-1]) / W == pytest.approx(0.0, abs=0.02)
    assert 0.5e-3 < tr.x[-1] / tr.t[-1] < sc.steady_velocity
