"""Model I with ageing contacts (reduced_models.ageing) against model I and its own linear response."""
from dataclasses import replace

import numpy as np
import pytest

from compare.analysis.spectra import band_average, displacement_spectrum
from reduced_models import ageing as ag
from reduced_models import spring_block as sb

# Model I's reference damping, m eta1 = 333 N s/m, as f_n A / v with F_N = 20 N: A = 0.25.
LINEAR_B0 = ag.AgeingParams(B=0.0, A=0.25, linear_direct=True)


def test_equivalent_model_I_has_the_reference_damping():
    q = ag.equivalent_model_I(LINEAR_B0)
    assert q.m * q.eta1 == pytest.approx(LINEAR_B0.f_n * LINEAR_B0.A / LINEAR_B0.v, rel=1e-12)
    assert q.m * q.eta1 == pytest.approx(sb.SpringBlockParams.reference().m * sb.SpringBlockParams.reference().eta1,
                                         rel=1e-12)
    assert q.f_kin == LINEAR_B0.f_kin


def test_reduces_to_model_I_trace_for_trace():
    # B = 0 with the direct effect linearised is model I with m eta1 = f_n A / v; the renewals are drawn as model I
    # draws them, so one seed gives one path. Differences: the miniblocks' inertia (model I; rate eta1 = 3e7 1/s,
    # effect ~ omega / eta1 < 1e-4 in the output band) and the integrator's tolerance. Measured: 1.1e-10 m over
    # 20 s against zeta_rms = 4.1e-5 m, renewal times within 2.2e-7 s.
    q = ag.equivalent_model_I(LINEAR_B0)
    a = ag.simulate(LINEAR_B0, 20.0, 1e-3, seed=1)
    b = sb.simulate(q, 20.0, 1e-3, seed=1)
    za, zb = a.x - LINEAR_B0.v * a.t, b.x - q.v * b.t
    assert np.abs(za - zb).max() < 1e-4 * zb.std()
    np.testing.assert_allclose(a.events["times"], b.events["times"], atol=1e-5)
    np.testing.assert_array_equal(a.events["index"], b.events["index"])


def test_theory_reduces_to_eq_A10():
    # Same Z as (A5) with m eta1 -> f_n A / v, except model I's miniblock inertia -m omega^2 in Q1: relative
    # m omega / (m eta1) < 3e-5 up to 1000 rad/s.
    w = np.logspace(-1, 3, 30)
    np.testing.assert_allclose(ag.theory_spectrum(LINEAR_B0, w), sb.theory_spectrum(ag.equivalent_model_I(LINEAR_B0), w),
                               rtol=1e-4)


def test_friction_slope_limits():
    # The contact's dynamic slope: (f_n / v) A above v / D_c, (f_n / v)(A - B) below.
    p = ag.AgeingParams()
    lo, hi = ag.friction_slope(p, np.array([1e-6 * p.v / p.D_c, 1e6 * p.v / p.D_c]))
    assert abs(lo - p.f_n * (p.A - p.B) / p.v) < 1e-5 * p.f_n * p.A / p.v
    assert abs(hi - p.f_n * p.A / p.v) < 1e-5 * p.f_n * p.A / p.v


@pytest.fixture(scope="module")
def small_alpha_runs():
    """900 s at 1 kHz (the paper's run) for both state laws, renewal forces small against the direct effect
    (alpha f_kin / (f_n A) = 0.42) so that the linear response holds."""
    out = {}
    for law in ("ageing", "slip"):
        p = ag.AgeingParams(alpha=0.2, law=law)
        tr = ag.simulate(p, 900.0, 1e-3, seed=0)
        out[law] = (p, displacement_spectrum(tr.t, tr.x))
    return out


@pytest.mark.slow
@pytest.mark.parametrize("law", ["ageing", "slip"])
def test_simulation_matches_its_linear_response_per_band(small_alpha_runs, law):
    # 9 log bands over 0.5-250 rad/s. Statistical scatter of a band average: ~7 % in the lowest band (as model I's
    # test), less above; 15 % is ~2 sigma at the bottom. Measured ratios (seed 0): 0.95-1.07 for both laws. The
    # state's crossover v / D_c = 5 rad/s lies inside, so the bands test A - B / (1 + i omega D_c / v), not a constant.
    p, spec = small_alpha_runs[law]
    edges = np.logspace(np.log10(0.5), np.log10(250), 10)
    ratio = band_average(spec, edges) / band_average(spec, edges, ag.theory_spectrum(p, spec.omega))
    assert np.all(np.abs(ratio - 1) < 0.15), ratio
    # and the state matters there: the B = 0 theory is off by more than the tolerance in the low bands
    lowband = band_average(spec, edges[:3])
    no_state = band_average(spec, edges[:3], ag.theory_spectrum(replace(p, B=0.0), spec.omega))
    assert np.all(lowband / no_state > 1.3)


def test_seeded_bit_for_bit():
    p = ag.AgeingParams()
    a, b = ag.simulate(p, 2.0, 1e-3, seed=5), ag.simulate(p, 2.0, 1e-3, seed=5)
    assert np.array_equal(a.x, b.x) and np.array_equal(a.force, b.force)


def test_force_channel_is_the_interval_mean_of_the_random_forces():
    # Sum of the renewal forces, piecewise constant between renewals, averaged over each output interval: its
    # mean over the run equals the time-weighted mean of the piecewise-constant sum to rounding.
    p = ag.AgeingParams()
    tr = ag.simulate(p, 5.0, 1e-3, seed=2)
    assert np.abs(tr.force).max() <= p.N * p.alpha * p.f_kin / 2 + 1e-12
    assert tr.force.std() > 0


@pytest.mark.parametrize("field, value, message", [
    ("A", 0.0, "A must be > 0"), ("A", -0.1, "A must be > 0"), ("D_c", 0.0, "D_c must be > 0"),
    ("B", -0.1, "B must be >= 0"), ("renewal_state", 0.0, "renewal_state must be > 0"),
    ("law", "rate", "law must be one of"), ("F_N", 0.0, "F_N must be > 0"),
])
def test_bad_parameters_name_the_field(field, value, message):
    with pytest.raises(ValueError, match=message):
        ag.AgeingParams(**{field: value})


def test_continuous_ageing_steepens_the_velocity_dependence():
    # eq. (A11) with the ageing slope: C_x ~ v^3 / |R|^2, R = A - B / (1 + i x), x = omega D_c / v, and
    # |R|^2 = A^2 - (2 A B - B^2) / (1 + x^2) falls as v rises (x falls) whenever 0 < B < 2 A: the exponent
    # d ln C_x / d ln v is 3 + (2AB - B^2) 2 x^2 / ((1 + x^2)^2 |R|^2) >= 3, never 5/3. Checked against that
    # closed form to 1e-6 (central differences in ln v, step 1e-4) on a grid of B/A, D_c, v.
    w = np.array([0.4, 5.0, 30.0])
    for ratio in (0.0, 1 / 3, 2 / 3, 0.9):
        A = 0.08 / (1 - ratio)
        for Dc in (1e-5, 1e-4, 1e-3):
            for v in (2e-6, 2e-5, 2e-4, 2e-3):
                p = [ag.AgeingParams(v=v * f, A=A, B=A - 0.08, D_c=Dc) for f in (np.exp(-1e-4), np.exp(1e-4))]
                slope = np.log(ag.asymptotic_spectrum(p[1], w) / ag.asymptotic_spectrum(p[0], w)) / 2e-4
                x2 = (w * Dc / v) ** 2
                B = A - 0.08
                R2 = A**2 - (2 * A * B - B**2) / (1 + x2)
                np.testing.assert_allclose(slope, 3 + (2 * A * B - B**2) * 2 * x2 / ((1 + x2) ** 2 * R2), rtol=1e-6)
                assert np.all(slope >= 3 - 1e-9)
