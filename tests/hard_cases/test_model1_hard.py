"""Model I at the edges: extreme output steps, mass ratios, N = 1, no noise, extreme speeds."""
from dataclasses import replace

import numpy as np
import pytest

pytestmark = pytest.mark.slow  # hard cases: long or extreme runs

from compare.analysis.spectra import band_average, displacement_spectrum
from compare.analysis.assertions import assert_spectrum_matches
from reduced_models.spring_block import SpringBlockParams, displacement_variance, simulate, theory_spectrum

REF = SpringBlockParams.reference()


@pytest.mark.parametrize("dt_out, duration", [(0.1, 900.0), (1e-5, 20.0)])
def test_reference_stiffness_at_extreme_output_steps(dt_out, duration):
    tr = simulate(REF, duration, dt_out, seed=1)
    assert np.all(np.isfinite(tr.x))
    # mean velocity within 1 % of v, or within 4 sigma of the random walk (Appendix A) for short runs
    L0 = REF.v * tr.t[-1]
    sigma = np.sqrt(displacement_variance(REF, L0)) / L0
    v_mean = (tr.x[-1] - tr.x[0]) / tr.t[-1]
    assert abs(v_mean / REF.v - 1) < max(0.01, 4 * sigma)


def test_dt_out_0p1_spectrum_below_nyquist():
    # At 10 Hz sampling the spectrum up to ~5 rad/s is still (A10) (aliasing of the omega^-4 tail adds
    # ~ (omega / (2 omega_N - omega))^4, < 1 % below 5 rad/s). 3600 s: 0.5-5 rad/s within 15 %.
    tr = simulate(REF, 3600.0, 0.1, seed=2)
    spec = displacement_spectrum(tr.t, tr.x, nperseg=2048)
    assert_spectrum_matches(spec, lambda w: theory_spectrum(REF, w), np.logspace(np.log10(0.5), np.log10(5), 4), 0.15)


def test_mass_ratio_1e5_and_1e6():
    # The reference has M/m = 1e5; push m down 10x (M/m = 1e6): still finite and on (A10) in 5-50 rad/s.
    p = replace(REF, m=1e-6)
    tr = simulate(p, 300.0, 1e-3, seed=3)
    spec = displacement_spectrum(tr.t, tr.x)
    assert_spectrum_matches(spec, lambda w: theory_spectrum(p, w), [5.0, 15.0, 50.0], 0.15)


def test_single_miniblock():
    p = replace(REF, N=1, k1=0.0)
    tr = simulate(p, 900.0, 1e-2, seed=4)
    assert np.all(np.isfinite(tr.x))
    spec = displacement_spectrum(tr.t, tr.x)
    assert_spectrum_matches(spec, lambda w: theory_spectrum(p, w), np.logspace(0, np.log10(50), 4), 0.15)


def test_no_noise_means_no_displacement_noise():
    # alpha = 0: every random force is zero; the block slides at exactly v from the steady state.
    tr = simulate(replace(REF, alpha=0.0), 100.0, 1e-3, seed=5)
    assert np.max(np.abs(tr.x - REF.v * tr.t)) < 1e-15
    assert np.all(tr.force == 0.0)


@pytest.mark.parametrize("v", [1e-7, 0.1])
def test_extreme_speeds(v):
    # eta1 follows the steady-sliding rule (1.7e11 1/s at 0.1 um/s, 1.7e5 1/s at 100 mm/s). The run
    # spans 40 renewal lengths; the omega^-4 band [10 v/a, 100 v/a] must sit on (A10) within 15 %.
    p = replace(REF, v=v)
    tau0 = p.a / p.v
    tr = simulate(p, 400 * tau0, tau0 / 200, seed=6)
    assert np.all(np.isfinite(tr.x))
    spec = displacement_spectrum(tr.t, tr.x)
    w0 = p.v / p.a
    edges = [10 * w0, 30 * w0, 100 * w0]
    r = band_average(spec, edges) / band_average(spec, edges, theory_spectrum(p, spec.omega))
    assert np.all(np.abs(r - 1) < 0.15), r


def test_model_Ib_at_one_micrometre_per_second():
    # Model Ib (multiscale) at v = 1 um/s: eta1 = 1.7e10 1/s from steady sliding, micro renewals every
    # a2 / v = 10 s per contact, 12 M of them over 400 renewal lengths a. The macro omega^-4 band
    # [10 v/a, 100 v/a] sits on the closed form within 15 % (2 bands of ~300 ordinates each, 6 % scatter;
    # measured 1.04 and 1.00).
    from reduced_models import multiscale as ms

    p = replace(ms.MultiscaleParams.reference(), v=1e-6)
    tau0 = p.a / p.v
    tr = ms.simulate(p, 400 * tau0, tau0 / 200, seed=6)
    assert np.all(np.isfinite(tr.x))
    spec = displacement_spectrum(tr.t, tr.x)
    w0 = p.v / p.a
    edges = [10 * w0, 30 * w0, 100 * w0]
    r = band_average(spec, edges) / band_average(spec, edges, ms.theory_spectrum(p, spec.omega))
    assert np.all(np.abs(r - 1) < 0.15), r
