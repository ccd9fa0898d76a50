"""Wear particles: the size laws, the friction split, the episode analysis against exact cases, and a short
scene run (no grain through its track, none lost, trap and release both seen, energy closed)."""
import numpy as np
import pytest

import engine_sim
from compare.analysis.spectra import band_average, force_series_spectrum
from compare.analysis.episodes import duration_summary, episodes, model_II_from_episodes
from engine_sim import ScenarioError, load_scenario, scenario_from_dict, shipped_scenarios
from engine_sim.scenario import WearSpec
from engine_sim.wear import draw_radii, pad_friction_split

WEAR = shipped_scenarios()["pads_with_wear"]


def test_radius_laws_respect_their_range_and_shape():
    rng = np.random.default_rng(1)
    ln = draw_radii(WearSpec(distribution="lognormal", r_min=20e-6, r_max=150e-6, r_median=50e-6, sigma=0.5), 20000, rng)
    assert ln.min() >= 20e-6 and ln.max() <= 150e-6
    # median of the truncated law: the cut removes 3.3 % below and 3.4 % above, so it stays at 50 um (within 2 %)
    assert np.median(ln) == pytest.approx(50e-6, rel=0.02)
    pw = draw_radii(WearSpec(distribution="power", r_min=20e-6, r_max=150e-6, exponent=3.0), 20000, rng)
    # P(r) ~ r^-3 on [a, b]: mean = 2 a b / (a + b) exactly; 20000 draws give 0.4 % (1 sigma)
    a, b = 20e-6, 150e-6
    assert pw.mean() == pytest.approx(2 * a * b / (a + b), rel=0.015)


def test_friction_split_gives_the_wanted_pairs():
    q, f = pad_friction_split(0.6, 0.2, 1.2)
    assert f * q == pytest.approx(0.2) and f * 0.6 / q == pytest.approx(1.2)
    # in a built scene, the pairs pymunk forms (products of shape frictions) are the ones the scenario asks for
    from engine_sim import Scene

    sc = load_scenario(WEAR)
    scene = Scene(sc)
    pad_mu = next(iter(scene.pads[0].shapes)).friction
    track_mu = np.array([s.friction for tr in scene.tracks for s in tr.segments])
    grain_mu = np.array([s.friction for s in scene.wear.shapes])
    # patches: mu0 (1 + alpha (r - 1/2)), mean mu0 = 0.6, spread alpha mu0 / sqrt(12) = 0.17 per patch; the live
    # patches of 30 tracks (~700 segments, pits' walls in their patch's mu) average it to 0.006 (1 sigma)
    assert np.mean(pad_mu * track_mu) == pytest.approx(sc.friction.mu0, abs=0.03)
    np.testing.assert_allclose(grain_mu * pad_mu, sc.wear.mu_pad, rtol=1e-12)  # grain on pad: exactly mu_pad
    assert np.mean(grain_mu[0] * track_mu) == pytest.approx(sc.wear.mu_track, rel=0.03)  # same 1 % sampling, 3 sigma


@pytest.mark.slow  # fast tier under a minute: run in CI's slow tier
def test_episodes_and_B2_against_exact_rectangles():
    # Independent rectangles of random sign (B2's assumption): durations exponential (mean 20 ms), heights +-c.
    # The empirical (B2) must read the periodogram of the series within the Welch scatter (31 half-overlapping
    # segments; measured within 3 % above 10 rad/s; bound 25 %).
    rng = np.random.default_rng(3)
    dt, n, P = 1e-3, 2**17, 8
    state = np.zeros((n, P), dtype=np.int8)
    force = np.zeros((n, P))
    for j in range(P):
        k = 0
        s = int(rng.integers(1, 3))
        while k < n:
            L = max(1, int(rng.exponential(20.0)))
            state[k:k + L, j] = s
            force[k:k + L, j] = rng.choice([-1.0, 1.0]) * 0.05
            s = 3 - s
            k += L
    ep = episodes(state, force, dt)
    assert set(np.unique(ep["state"])) == {1, 2}
    summ = duration_summary(ep)
    assert summ["trapped"]["tau_mean"] == pytest.approx(0.0205, rel=0.1)  # exponential(20) floored at 1 sample
    t = np.arange(n) * dt
    S = force_series_spectrum(t, force.sum(axis=1), nperseg=2**13)
    edges = np.logspace(np.log10(4 * S.omega_min), np.log10(300.0), 8)  # the lowest Welch bins are biased
    r = band_average(S, edges) / band_average(S, edges, model_II_from_episodes(ep, t[-1], S.omega))
    assert np.all(np.abs(r - 1) < 0.25), r


def test_wear_validation_names_the_limit():
    with pytest.raises(ScenarioError, match=r"lets the smallest particle .* tunnel"):
        scenario_from_dict({"wear": {"count": 10, "r_min": 2e-6, "r_max": 50e-6}, "run": {"dt": 1e-4}})
    with pytest.raises(ScenarioError, match="must not exceed the pad radius"):
        scenario_from_dict({"wear": {"count": 10, "r_max": 1e-3}})
    with pytest.raises(ScenarioError, match="wear particles need flat pad tracks"):
        scenario_from_dict({"wear": {"count": 10}, "substrate": {"kind": "self_affine"}})
    with pytest.raises(ScenarioError, match=r"cannot hold 34 particles per track"):
        scenario_from_dict({"wear": {"count": 1000}})


@pytest.mark.slow  # paired wear runs
def test_pads_with_wear_keeps_its_grains_and_closes_energy():
    # 3 s. Measured (20 s): deepest grain overlap 4.1 um, none lost, ~1150 recyclings, trapped 7 %, moving 27 %,
    # energy 1.5-1.8 %. Bounds: 8 um, 0 lost, both states seen, 2 %.
    sc = load_scenario(WEAR).with_run(duration=3.0, warmup=0.5)
    tr = engine_sim.run(sc)
    assert np.all(np.isfinite(tr.x)) and np.all(np.isfinite(tr.p_force))
    assert tr.particle_penetration.max() < 8e-6
    w = tr.metadata["wear"]
    assert w["left_interface"] == 0 and w["recycled"] > 10 and w["count"] == 50
    assert np.mean(tr.p_state == 1) > 0.01 and np.mean(tr.p_state == 2) > 0.05
    resid = tr.work_drive[-1] + tr.work_recycle[-1] - tr.dissipated[-1] - tr.mech_energy[-1]
    assert abs(resid) < 0.02 * tr.work_drive[-1]
    assert np.mean(tr.F_t + tr.F_drag) == pytest.approx(np.mean(tr.F_drive), rel=0.02)
    # the particle-free twin: same substrate and seed, no grains
    tr0 = engine_sim.run(sc.with_wear(count=0))
    assert tr0.p_state.shape[1] == 0 and tr0.x[-1] > tr.x[-1]  # grains add friction


@pytest.mark.slow  # fast tier under a minute: run in CI's slow tier
@pytest.mark.timing  # a frame's cost against pymunk's drawing
def test_render_colours_grains_by_the_recorders_state_within_the_frame_budget(tmp_path):
    # 30 pads on their tracks and 100 grains: a frame costs at most a fifth of pymunk's own matplotlib drawing, measured
    # in turns (an absolute budget failed whenever other processes shared the cores); grains coloured by the
    # recorder's states, the trace's own classifier
    from tests.frame_budget import frame_cost_ratio
    from engine_sim import Scene
    from engine_sim.record import Recorder
    from engine_sim.render import SceneRenderer
    from engine_sim.wear import STATE_COLORS

    sc = load_scenario(WEAR).with_wear(count=100)
    scene = Scene(sc)
    scene.advance(3000)
    scene.maintain()
    r = SceneRenderer(scene)
    rec = Recorder(scene, 40)
    for _ in range(40):  # the renderer observes the output steps the trace records
        scene.advance(scene.n_sub)
        rec.sample()
        r.observe()
    r.frame()
    ratio = frame_cost_ratio(r)
    print(f"frame cost / pymunk.matplotlib_util: {ratio:.2f}")
    assert ratio < 0.2  # measured 0.03-0.04 (pymunk draws every segment and constraint as a patch)
    assert np.array_equal(r.states, rec.p_state[-1])  # one classifier: frame colours are the recorded states
    assert np.count_nonzero(rec.p_state[-1]) > 0  # some grains touch their pads (else the check says nothing)
    colours = r.panels[0]["artists"]["grains"].get_facecolor()
    assert len(colours) == 100 and np.allclose(colours, STATE_COLORS[rec.p_state[-1]])
    r.save_png(tmp_path / "f.png")
    assert (tmp_path / "f.png").stat().st_size > 5000
    r.close()


def test_a_stale_grain_arbiter_is_left_out_of_the_sample():
    # pymunk re-lists a woken grain's cached arbiters with the contact data of its old place until the next step
    # (after an epoch's restore every grain wakes; a 60 s run of 1000 grains read grain-track overlaps of 15 and
    # 85 mm there). Made here by hand: a sleeping grain moved 1 mm along and 0.1 mm into its track, then woken. Its
    # stale arbiter would read a 100 um overlap; the recorder must skip it (counted) and read no overlap above 1 um.
    from engine_sim import Scene
    from engine_sim.record import Recorder
    from engine_sim.sample_layout import COLS

    stale = COLS.index("stale")
    sc = load_scenario(WEAR).with_wear(count=60)
    scene = Scene(sc, seed=0)
    for k in range(100):
        if k % 10 == 0:
            scene.maintain()
        scene.advance(scene.n_sub)
    clean = Recorder(scene, 1)
    clean.sample()
    assert clean.out[0, stale] == 0  # a live scene's arbiters are fresh: nothing skipped
    b = next(b for b in scene.wear.bodies if b.is_sleeping)
    b.position = (b.position.x + 1.0, b.position.y - 0.1)  # scene units (mm)
    b.activate()
    rec = Recorder(scene, 1)
    rec.sample()
    assert rec.out[0, stale] >= 1  # the stale arbiter, counted
    assert rec.trace({}).particle_penetration[0] < 1e-6  # m: the overlap it would have read (100 um) left out
