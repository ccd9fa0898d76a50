"""Model II (wear particles) against exact spectra: the random telegraph and eq. (B2)."""
from dataclasses import replace

import numpy as np
import pytest

from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum, force_series_spectrum
from compare.analysis.assertions import assert_spectrum_matches
from reduced_models.wear_particle import (
    DurationLaw, WearParticleParams, power_law_prediction, simulate, theory_force_spectrum,
)


def lorentzian(w, dc, tA, tB):
    tc = tA * tB / (tA + tB)
    return dc**2 * tA * tB / (tA + tB) ** 2 * tc / (np.pi * (1 + (w * tc) ** 2))


def test_single_particle_random_telegraph_is_lorentzian():
    # One particle, exponential durations (50 ms trapped, 20 ms sliding), forces 0.3 / -0.1 N:
    # a random telegraph signal, corner 1/tau_c = 70 rad/s. 2000 s at 1 kHz; within 10 % per band
    # (measured within 3 %).
    p = WearParticleParams(n_particles=1, trapped=DurationLaw(0.05, 0.05), sliding=DurationLaw(0.02, 0.02),
                           c_A=0.3, c_B=-0.1, mode="telegraph")
    tr = simulate(p, 2000.0, 1e-3, seed=1)
    assert tr.force.mean() == pytest.approx((0.3 * 0.05 - 0.1 * 0.02) / 0.07, rel=0.02)
    sF = force_series_spectrum(tr.t, tr.force, nperseg=2**14)
    edges = np.logspace(0, np.log10(300), 9)
    exact = lambda w: lorentzian(w, 0.4, 0.05, 0.02) * np.sinc(w * 1e-3 / (2 * np.pi)) ** 2
    assert_spectrum_matches(sF, exact, edges, rtol=0.10)
    np.testing.assert_allclose(theory_force_spectrum(p, sF.omega, dt_avg=1e-3), exact(sF.omega), rtol=1e-12)


@pytest.fixture(scope="module")
def one_over_f_run():
    p = WearParticleParams.one_over_f()
    tr = simulate(p, 2000.0, 1e-3, seed=2)
    return p, tr, force_series_spectrum(tr.t, tr.force, nperseg=2**18)


def test_one_over_f_force_and_gamma_5(one_over_f_run):
    # tau over 10 ms - 100 s: 1/f between 10/tau_max = 0.1 and 0.1/tau_min = 10 rad/s (2 decades).
    p, tr, sF = one_over_f_run
    pred = power_law_prediction(p)
    assert pred["force_slope"] == -1 and pred["gamma"] == 5 and pred["band"] == pytest.approx((0.1, 10.0))
    fit_F = fit_power_law(sF, band=pred["band"])
    assert fit_F.gamma == pytest.approx(1.0, abs=0.1)  # measured 0.988 +- 0.044
    sx = displacement_spectrum(tr.t, tr.x, nperseg=2**18)
    assert fit_power_law(sx, band=pred["band"]).gamma == pytest.approx(5.0, abs=0.1)


def test_one_over_f_matches_B2_per_band(one_over_f_run):
    # Per band within 15 % of (B2) over 0.1-1000 rad/s (measured 0.89-1.04). The lowest band holds
    # ~14 Welch segments of 262 s, ~9 % scatter.
    p, _, sF = one_over_f_run
    edges = np.logspace(-1, 3, 9)
    assert_spectrum_matches(sF, lambda w: theory_force_spectrum(p, w, dt_avg=1e-3), edges, rtol=0.15)


def test_above_one_over_tau_min_the_slope_tends_to_minus_2(one_over_f_run):
    # Appendix B: for omega |t_j - t_k| >> 1, C_F ~ omega^-2 (gamma = 6). At 3-10 / tau_min the exact (B2)
    # local slope is -1.9 to -2.0; the simulation reads 2.04 +- 0.04.
    p, _, sF = one_over_f_run
    fit = fit_power_law(sF, band=(300.0, 1000.0))
    assert fit.gamma == pytest.approx(2.0, abs=0.15)


@pytest.mark.slow  # long model II runs (6-14 s)
def test_independent_times_bend_the_one_over_f_law():
    # With tau_A and tau_B drawn independently, (B2) carries a log divergence at small tau' and the
    # force spectrum is C_F ~ omega^-1 ln(1/(omega tau_min)), not omega^-1: the exact (B2) slope over
    # 0.1-10 rad/s is -1.20; the simulation (shorter run) must follow (B2), not the power-law rule.
    p = replace(WearParticleParams.one_over_f(300), tau_link="independent")
    w = np.logspace(-1, 1, 20)
    slope = np.polyfit(np.log(w), np.log(theory_force_spectrum(p, w)), 1)[0]
    assert slope == pytest.approx(-1.20, abs=0.03)
    tr = simulate(p, 1000.0, 1e-3, seed=3)
    sF = force_series_spectrum(tr.t, tr.force, nperseg=2**17)
    fit = fit_power_law(sF, band=(0.3, 10.0))
    assert fit.gamma > 1.1  # measured 1.27: steeper than 1/f, as (B2) says
    assert_spectrum_matches(sF, lambda w: theory_force_spectrum(p, w, dt_avg=1e-3), np.logspace(np.log10(0.3), 2, 6), 0.2)


def test_paper_cumulant_closure_overestimates_for_exponential_durations():
    # (B2) with the paper's exp(-s^2 omega^2 / 2) cos(omega tau), s = tau, against the exact
    # <cos omega tau> = 1/(1 + omega^2 tau^2) of exponential durations: higher by 10-25 % in the 1/f band.
    p = WearParticleParams.one_over_f(100)
    w = np.logspace(-1, 1, 9)
    r = theory_force_spectrum(p, w, closure="cumulant") / theory_force_spectrum(p, w)
    assert np.all((r > 1.05) & (r < 1.3)), r


@pytest.mark.slow  # long model II runs (6-14 s)
def test_fixed_and_pareto_laws_follow_B2():
    # Renewal processes with independent +-c forces: (B2) with the exact <cos> is exact for any law.
    for law in (DurationLaw(0.05, 0.05, "fixed"), DurationLaw(0.05, 0.05, "pareto", shape=2.5)):
        p = WearParticleParams(n_particles=20, trapped=law, sliding=law, c_A=0.1, c_B=0.05)
        tr = simulate(p, 500.0, 1e-3, seed=4)
        sF = force_series_spectrum(tr.t, tr.force, nperseg=2**14)
        edges = np.logspace(0, np.log10(300), 7)
        assert_spectrum_matches(sF, lambda w: theory_force_spectrum(p, w, dt_avg=1e-3), edges, rtol=0.15)


@pytest.mark.parametrize(
    "make, field",
    [(lambda: DurationLaw(1.0, 0.1), "tau_min"), (lambda: DurationLaw(-1.0, 1.0), "tau_min"),
     (lambda: DurationLaw(0.1, 1.0, "gamma"), "kind"), (lambda: DurationLaw(0.1, 0.1, "pareto", shape=0.5), "shape"),
     (lambda: WearParticleParams(n_particles=0), "n_particles"), (lambda: WearParticleParams(M=0.0), "M"),
     (lambda: WearParticleParams(mode="random"), "mode")],
)
def test_invalid_parameters(make, field):
    with pytest.raises(ValueError, match=field):
        make()
