"""The user API, ``import frictionnoise as fn``: what a notebook calls, checked on numbers with known answers."""
import subprocess
import sys

import numpy as np
import pytest

import frictionnoise as fn


def test_import_is_light_and_the_shared_helpers_stay():
    # `import frictionnoise` must not load the numerics: engine_sim, reduced_models and compare import it
    code = ("import sys, frictionnoise; from frictionnoise import G, package_version, atomic_write; "
            "import frictionnoise.base; "
            "print(sorted(m for m in ('numpy', 'compare', 'engine_sim', 'reduced_models') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
    assert fn.G == 9.81


def test_every_public_name_resolves_and_has_a_docstring():
    for name in fn.__all__:
        obj = getattr(fn, name)
        if callable(obj) and not isinstance(obj, dict):
            assert (obj.__doc__ or "").strip(), name
    assert "simulate" in dir(fn)
    with pytest.raises(AttributeError):
        fn.no_such_name  # noqa: B018


def test_model_I_simulated_against_its_closed_form():
    p = fn.SpringBlockParams.reference()
    assert fn.model(p) is fn.MODELS["model_I"] and fn.model("model_I") is fn.MODELS["model_I"]
    tr = fn.simulate(p, 300.0, seed=0)
    spec = fn.displacement_spectrum(tr.t, tr.x)
    # four half-decade bands over 5-500 rad/s, all above v/a = 0.5 rad/s; 300 s gives 28 Welch ordinates in the
    # lowest band; over seeds 0-5 the band ratios to eq. (A10) spread 0.94-1.13, so 20 % is about 4 sd
    edges = np.array([5.0, 15.8, 50.0, 158.0, 500.0])
    fn.assert_spectrum_matches(spec, lambda w: fn.theory_spectrum(p, w), edges, rtol=0.2)
    # eq. (6): omega^-4 between v/a and omega_c; the Whittle 95 % half-width over 5-50 rad/s is about 0.07
    fit = fn.assert_spectral_slope(tr.t, tr.x, expected=4.0, tol=0.15, band=(5.0, 50.0))
    assert fit.power_law


def test_analyze_displacement_needs_no_mass_and_reads_the_speed():
    p = fn.SpringBlockParams.reference()
    # 100 Hz: what follows holds exactly or concerns the mean speed, at any output step (at the 1 kHz default each
    # of the two record-model fits below took 19 s of CPU, at 100 Hz 2-4 s)
    tr = fn.simulate(p, 120.0, dt_out=1e-2, seed=1)
    a = fn.analyze_displacement(tr.t, tr.x)
    # the speed is the least-squares slope of x(t) (the linear detrend of eq. 2's zeta = x - v t), and the
    # model's v up to the block's low-frequency random walk (Appendix A), 0.2 % over 120 s
    assert a.mean_velocity == pytest.approx(np.polyfit(tr.t, tr.x, 1)[0], rel=1e-9)
    assert a.mean_velocity == pytest.approx(p.v, rel=0.01)
    assert a.C_F is None and a.mass is None
    # C_mu = omega^4 C_x / g^2 exactly (eq. 3 over (M g)^2), g standard gravity for a record measured on Earth
    # (the gram-force's constant; the paper's models round it to fn.G = 9.81); C_F = M^2 omega^4 C_x with the mass
    assert a.g == 9.80665
    np.testing.assert_allclose(a.C_mu.C, a.C_x.omega**4 * a.C_x.C / a.g**2, rtol=1e-12)
    b = fn.analyze_displacement(tr.t, tr.x, mass=2.0)
    np.testing.assert_allclose(b.C_F.C, 4.0 * b.C_x.omega**4 * b.C_x.C, rtol=1e-12)
    assert b.fit.gamma == a.fit.gamma


def test_measured_file_through_the_api():
    path = fn.shipped_path("data/model1_synthetic_um.csv")
    data = fn.read_measured(path, x_unit="um")
    a = fn.analyze_displacement(data, band=(5.0, 50.0))
    # the synthetic record is model I's reference case (scenarios/data/README.md): gamma 4 within the interval
    assert abs(a.fit.gamma - 4.0) <= a.fit.gamma_err
    with pytest.raises(ValueError, match="mass must be positive"):
        fn.analyze_displacement(data, mass=0.0)


def test_unknown_model_is_named():
    with pytest.raises(KeyError, match="model_I"):
        fn.model("model_IV")
    with pytest.raises(KeyError, match="SpringBlockParams"):
        fn.simulate(object(), 1.0)


def test_a_scene_runs_renders_and_round_trips(tmp_path):
    tr = fn.run_scene("pads_friction_patches", duration=0.3, seed=0)
    assert tr.t[1] - tr.t[0] == pytest.approx(1e-3)  # the scenario's dt_out, SI seconds
    # the block slides at the friction law's steady speed, 5 mm/s (scenario comments), within the patch noise:
    # 0.3 s is 1.5 renewal lengths, so allow 10 %
    v = np.polyfit(tr.t, tr.x, 1)[0]
    assert v == pytest.approx(5e-3, rel=0.1)
    fn.save_trace(tr, tmp_path / "trace.npz")
    back = fn.load_trace(tmp_path / "trace.npz")
    np.testing.assert_array_equal(back.x, tr.x)  # bit for bit
    frames = fn.render_scene("pads_friction_patches", tmp_path / "frames", frames=2, duration=0.01, dpi=40)
    assert len(frames) == 2 and frames[0].ndim == 3
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == ["frame_000.png", "frame_001.png"]
