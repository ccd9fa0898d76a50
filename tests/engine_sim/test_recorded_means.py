"""Recorded forces as means over the output step (engine_sim.means): against the block average of the
same path recorded at every pymunk step, on cases where that average is the truth, and on a case whose contact force
is zero by construction."""
from pathlib import Path

import numpy as np
import pytest

import engine_sim
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.record import FORCE_CHANNELS, step_weights


def _pair(name, duration):
    """The default recording and the every-step point recording of one path (a scene's path does not depend on
    how often or how it is recorded: measured bit for bit on every shipped scene without grains), and m."""
    sc = load_scenario(shipped_scenarios()[name]).with_run(duration=duration, warmup=0.2)
    fine = engine_sim.run(sc.with_run(dt_out=sc.run.dt, forces="point"))
    coarse = engine_sim.run(sc)
    return coarse, fine, int(round(sc.run.dt_out / sc.run.dt))


def _block(a, m, n):
    """Row k (k >= 1) of the output step's mean: rows (k-1) m + 1 .. k m of the every-step series."""
    return a[1:n * m + 1].reshape((n, m) + a.shape[1:]).mean(axis=1)


@pytest.mark.parametrize("n", [1, 2, 10, 40])
def test_step_weights_integrate_a_cubic_in_the_step_index_exactly(n):
    w = step_weights(n)
    j = np.arange(1, n + 1, dtype=float)
    for p in range(4):
        f = lambda s: (s + 0.5) ** p  # noqa: E731
        assert w @ f(np.array([0.0, 1.0, n, n + 1.0])) == pytest.approx(np.mean(f(j)), rel=1e-12, abs=1e-12)


def test_means_equal_the_block_average_of_every_step_on_flat_tracks():
    # pads_friction_patches: flat tracks, pads never leave them, so every step's arbiter impulses are the whole
    # contact force (no contact re-forms: pymunk's first-contact arbiters report an accumulated impulse carried over
    # from the broken contact that they never applied) and no contact's position correction moves a pad along x.
    # There the block average of the every-step point recording is the exact mean: F_t and F_drag come from momenta
    # and must equal it to rounding (measured 1e-12 of the fluctuation); pad_force integrates the pad springs by
    # the cubic rule (measured rms error 1.3e-3 of the fluctuation, 8 s: within 1e-4 per band up to 1571 rad/s).
    tr, fine, m = _pair("pads_friction_patches", 0.3)
    n = len(tr.t) - 1
    for ch, tol in (("F_t", 1e-9), ("F_drag", 1e-9), ("pad_force", 1e-2)):
        ref = _block(getattr(fine, ch), m, n)
        got = getattr(tr, ch)[1:n + 1]
        rms = np.sqrt(np.mean((got - ref) ** 2))
        assert rms <= tol * np.std(ref - ref.mean(axis=0)), ch
    assert tr.metadata["forces"] == "mean" and fine.metadata["forces"] == "point"
    assert tr.metadata["force_channels"]["F_t"] == FORCE_CHANNELS["F_t"]


@pytest.mark.parametrize("name, F_n, F_drive", [
    ("pads_friction_patches", "quadrature", "exact"),  # a guided block pulled by a constant force
    ("asperity_field", "exact", "exact"),  # a sole free vertically, constant force
    ("constant_velocity", "quadrature", "quadrature"),  # guided, velocity drive
])
def test_force_channels_say_how_this_scenes_forces_are_made(name, F_n, F_drive):
    # metadata["force_channels"]: FORCE_CHANNELS's general text gives both cases of F_n and F_drive; each trace
    # says the one that applies to its scene, and that its first sample's forces are point samples
    sc = load_scenario(shipped_scenarios()[name])
    assert sc.arrangement_part.guided == (F_n == "quadrature") and sc.drive_part.constant_force == (F_drive == "exact")
    tr = engine_sim.run(sc.with_run(duration=0.02, warmup=0.01))
    ch = tr.metadata["force_channels"]
    assert ch["F_n"].split(":")[0] == F_n and ch["F_drive"].split(":")[0] == F_drive
    assert ("guided" in ch["F_n"]) == (F_n == "quadrature")
    assert ("velocity drive" in ch["F_drive"]) == (F_drive == "quadrature")
    assert "first sample" in ch["first_sample"] and ch["first_sample"].startswith("point")
    assert {k: v for k, v in ch.items() if k not in ("F_n", "F_drive", "first_sample")} == \
        {k: v for k, v in FORCE_CHANNELS.items() if k not in ("F_n", "F_drive")}
    point = engine_sim.run(sc.with_run(duration=0.02, warmup=0.01, forces="point")).metadata["force_channels"]
    assert set(point) == set(FORCE_CHANNELS) and all(v.startswith("point") for v in point.values())


def test_means_read_zero_where_the_contact_force_is_zero():
    # spring_slider_rate_state: mu0 = 0, so the pad's contact carries no tangential force at all; its friction is
    # the rate-and-state law's impulse, written after each pymunk step. The means must read zero contact force:
    # F_t from momenta up to the drive spring's quadrature (measured 1.4e-6 N against a 0.6 N drive), the pad force
    # up to the pad springs' quadrature during slips (measured 4.6e-4 N; its damper c0 sees the velocity before the
    # law's impulse, which the means correct for: uncorrected it read 0.067 N). The law's impulses are the whole
    # friction: F_drag balances the drive on average.
    sc = load_scenario(shipped_scenarios()["spring_slider_rate_state"]).with_run(duration=0.4)
    tr = engine_sim.run(sc)
    assert np.abs(tr.F_t[1:]).max() < 1e-5
    assert np.abs(tr.pad_force[1:]).max() < 2e-3
    assert np.mean(tr.F_drag[1:]) == pytest.approx(np.mean(tr.F_drive[1:]), rel=0.02)


def test_point_mode_is_the_last_steps_contact_force():
    # run.forces = "point": F_t is the sliders' arbiter impulses of the last step / dt, so at dt_out = dt the two
    # modes agree to rounding on flat tracks (momenta and arbiters describe the same step).
    sc = load_scenario(shipped_scenarios()["pads_friction_patches"]).with_run(duration=0.02, warmup=0.0)
    sc = sc.with_run(dt_out=sc.run.dt)
    a, b = engine_sim.run(sc.with_run(forces="point")), engine_sim.run(sc)
    assert np.allclose(a.F_t[1:], b.F_t[1:], rtol=0, atol=1e-10)
    assert np.allclose(a.pad_force[1:], b.pad_force[1:], rtol=0, atol=1e-10)


@pytest.mark.parametrize("target,direction", [("substrate", "parallel"), ("substrate", "normal"), ("block", "parallel")])
def test_means_take_a_vibrations_impulses_in_closed_form(target, direction):
    # A shaken scene: every body feels the substrate frame's inertial force (or the block the shaker's), which the
    # means add in closed form over each output step; on flat tracks F_t must still equal the block average of the
    # every-step contact forces to rounding (measured 2e-13 N against a 0.14-0.31 N rms).
    from dataclasses import replace
    path = Path(__file__).resolve().parents[2] / "engine_sim" / "scenarios" / "sweeps" / "vibrated_patches.toml"
    sc = load_scenario(path).with_run(duration=0.05, warmup=0.02)
    sc = replace(sc, vibration=replace(sc.vibration, amplitude=1e-5, frequency=200.0, target=target,
                                       direction=direction))
    fine = engine_sim.run(sc.with_run(dt_out=sc.run.dt, forces="point"))
    tr = engine_sim.run(sc)
    m, n = int(round(sc.run.dt_out / sc.run.dt)), len(tr.t) - 1
    assert np.abs(tr.F_t[1:n + 1] - _block(fine.F_t, m, n)).max() < 1e-9 * np.std(fine.F_t)


def test_trace_format_page_lists_every_array_of_the_trace():
    # docs/reference/trace_format.md's column table: every EngineTrace array (vibration and work_vibration were
    # missing), and x relative to the substrate in a shaken scene
    from dataclasses import fields

    from engine_sim.record import EngineTrace

    page = (Path(__file__).parents[2] / "docs/reference/trace_format.md").read_text()
    rows = [line for line in page.splitlines() if line.startswith("| `")]
    listed = {name for line in rows for name in line.split("|")[1].replace("`", "").replace(",", " ").split()}
    assert {f.name for f in fields(EngineTrace)} - {"metadata"} <= listed
    (x_row,) = [line for line in rows if line.startswith("| `x` |")]
    assert "relative to the substrate" in x_row and "x + vibration" in x_row
