"""The closed forms of friction under vibration (reduced_models.vibration) against exact cycle averages."""
import numpy as np
import pytest

from reduced_models.vibration import (
    arcsin_ratio, contact_fraction_normal, effective_slope, force_controlled_mean, force_controlled_slope,
    in_band_factor, lift_off_amplitude, backward_slip, compliant_mean_ratio, minimum_amplitude, mean_sign, slip_fraction, steady_speed, velocity_controlled_friction,
)

# a cycle sampled at 2^20 equally spaced phases (midpoints): the mean of a function with a few jumps per cycle
# is exact to ~ (jumps) / 2^20 ~ 2e-6; every comparison below is held to 1e-5
THETA = (np.arange(2**20) + 0.5) * 2 * np.pi / 2**20


def _cycle_mean(f):
    return float(np.mean(f(THETA)))


@pytest.mark.parametrize("xi", [0.0, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.0, 1.5, 10.0])
def test_arcsin_law_is_the_cycle_mean_of_the_sign(xi):
    U = 2e-3  # m/s
    V = xi * U
    exact = _cycle_mean(lambda th: np.sign(V + U * np.cos(th)))
    assert float(arcsin_ratio(xi)) == pytest.approx(exact, abs=1e-5)
    assert float(mean_sign(V, U)) == pytest.approx(exact, abs=1e-5)
    assert float(mean_sign(-V, U)) == pytest.approx(-exact, abs=1e-5)  # odd in V


def test_arcsin_limits():
    # xi -> 0: (2/pi) xi (the mean is linear in V: a viscous law of slope 2 f / (pi U)); xi -> 1: 1 - (2/pi)
    # sqrt(2 (1 - xi)) (a square-root cusp); beyond 1: exactly 1
    for xi in (1e-6, 1e-4):
        assert float(arcsin_ratio(xi)) == pytest.approx(2 * xi / np.pi, rel=1e-7)
    for e in (1e-6, 1e-8):
        assert float(arcsin_ratio(1 - e)) == pytest.approx(1 - (2 / np.pi) * np.sqrt(2 * e), abs=1e-3 * np.sqrt(e))
    assert np.all(arcsin_ratio([1.0, 1.2, 100.0]) == 1.0)
    with pytest.raises(ValueError, match="xi"):
        arcsin_ratio(-0.1)


@pytest.mark.parametrize("xi", [0.05, 0.3, 0.6, 0.9])
def test_effective_slope_is_the_derivative_of_the_mean_friction(xi):
    U, f, c = 3e-3, 0.2, 50.0
    V = xi * U
    h = 1e-7 * U  # central difference: error ~ h^2 f''' ~ 1e-12 relative
    num = (velocity_controlled_friction(V + h, U, f, c) - velocity_controlled_friction(V - h, U, f, c)) / (2 * h)
    assert float(effective_slope(V, U, f, c)) == pytest.approx(float(num), rel=1e-6)
    assert float(effective_slope(V, U, f, c)) == pytest.approx(c + 2 * f / (np.pi * np.sqrt(U**2 - V**2)), rel=1e-12)
    assert float(effective_slope(1.2 * U, U, f, c)) == c  # beyond xi = 1 the Coulomb part is flat


@pytest.mark.parametrize("G,B", [(0.3, 0.05), (0.3, 0.2), (0.3, 0.6), (0.05, 0.3), (-0.2, 0.5), (0.05, 0.05)])
def test_force_controlled_mean_and_slip_fraction_are_exact_cycle_means(G, B):
    f, c = 0.15, 300.0
    soft = lambda th: np.sign(G + B * np.sin(th)) * np.maximum(np.abs(G + B * np.sin(th)) - f, 0.0) / c  # noqa: E731
    assert float(force_controlled_mean(G, B, f, c)) == pytest.approx(_cycle_mean(soft), abs=1e-5 * B / c)
    frac = _cycle_mean(lambda th: (np.abs(G + B * np.sin(th)) > f).astype(float))
    assert float(slip_fraction(G, B, f)) == pytest.approx(frac, abs=1e-5)
    # the slope c / fraction is d<friction>/d<slip rate>: check d<slip rate>/dG = fraction / c
    h = 1e-7
    d = (force_controlled_mean(G + h, B, f, c) - force_controlled_mean(G - h, B, f, c)) / (2 * h)
    assert float(d) == pytest.approx(frac / c, rel=1e-5, abs=1e-9)
    if frac > 0:  # (0.05, 0.05) never slips: the contact sticks through the cycle
        assert float(force_controlled_slope(G, B, f, c)) == pytest.approx(c / frac, rel=1e-5)


def test_force_controlled_tends_to_velocity_controlled_for_large_amplitude():
    # B >> f: soft(y, f) ~ y - f sign(y), and the slope c / fraction -> c + 2 f / (pi sqrt(U^2 - V^2)) with
    # U = B / c, V = G / c. The correction is second order in f / B: at f / B = 1e-3 the two agree to ~1e-5
    f, c, B = 1e-3, 300.0, 1.0
    for G in (0.1, 0.5, 0.8):
        assert float(force_controlled_slope(G, B, f, c)) == pytest.approx(
            float(effective_slope(G / c, B / c, f, c)), rel=1e-4)


def test_unshaken_limits():
    # B = 0: soft threshold (slides at (G - f) / c, slope c); U = 0: the constant Coulomb force, slope c
    assert float(force_controlled_mean(0.5, 0.0, 0.2, 100.0)) == pytest.approx(3e-3)
    assert float(slip_fraction(0.5, 0.0, 0.2)) == 1.0
    assert float(mean_sign(1e-3, 0.0)) == 1.0
    assert float(effective_slope(1e-3, 0.0, 0.2, 7.0)) == 7.0


def test_in_band_factor_through_A11():
    # C_x ~ v / s^2 (eq. A11 with the slope s of the mean friction law in place of m eta1)
    assert float(in_band_factor(1.0, 1.0, 300.0, 600.0)) == pytest.approx(0.25)
    assert float(in_band_factor(1.0, 2.0, 300.0, 300.0)) == pytest.approx(2.0)
    assert float(in_band_factor(0.5e-3, 0.5e-3, 333.3, 333.3)) == 1.0


def test_steady_speed_solves_the_mean_law():
    f, c, F = 1 / 6, 333.3, 1 / 3  # model I's reference per miniblock: v = (F - f) / c = 0.5 mm/s unshaken
    assert steady_speed(F, f, c, 0.0) == pytest.approx((F - f) / c, rel=1e-12)
    for U in (1e-4, 1e-3, 1e-2):
        V = steady_speed(F, f, c, U)
        assert float(velocity_controlled_friction(V, U, f, c)) == pytest.approx(F, rel=1e-12)
    # a vibration fast against V removes the Coulomb part: V -> F / c
    assert steady_speed(F, f, c, 1e3) == pytest.approx(F / c, rel=1e-3)


def test_lift_off_and_contact_fraction():
    # a free rigid load: A omega^2 = g_eff; a pad on its normal spring: A = load / |m omega^2 - k|
    assert lift_off_amplitude(100.0, 9.81 * 0.1, 0.1) * 100.0**2 == pytest.approx(9.81)
    assert lift_off_amplitude(10.0, 0.04, 1e-3, 833.0) == pytest.approx(0.04 / (833.0 - 0.1))
    g = np.array([0.5, 1.0, 2.0, 4.0])
    for gi, fr in zip(g, contact_fraction_normal(g)):
        exact = _cycle_mean(lambda th: (1 + gi * np.sin(th) > 0).astype(float))
        assert fr == pytest.approx(exact, abs=1e-5)


@pytest.mark.parametrize("xi", [0.1, 0.5, 0.9])
def test_backward_slip_and_the_compliant_contact(xi):
    A = 1.0
    exact = _cycle_mean(lambda th: np.maximum(A * np.cos(th) - xi * A, 0.0)) * 2 * np.pi  # integral over a cycle
    assert float(backward_slip(xi)) == pytest.approx(exact, abs=1e-5)
    # stiff limit: the Jenkins element tends to the arcsin law; the departure goes as d / A (the spring's travel
    # 2 d per reversal out of the cycle's): at A / d = 1e4, within 1e-3
    assert compliant_mean_ratio(xi, 1e4) == pytest.approx(float(arcsin_ratio(xi)), abs=1e-3)
    # soft limit: A << d, the contact only sticks and slides forward; the spring's swing (backward slip
    # ~ 2 A) lowers the mean by a fraction of order A / d: at A / d = 1e-3, within 3e-3 of 1
    assert compliant_mean_ratio(xi, 1e-3) == pytest.approx(1.0, abs=3e-3)
    # the minimum amplitude: just below it the stretch never reaches -d (no backward sliding), just above it does
    a_min = float(minimum_amplitude(xi, 1.0))
    th = 2 * np.pi * np.arange(1, 4 * 4096 + 1) / 4096
    for fac, reverses in ((0.98, False), (1.02, True)):
        u = fac * a_min * (xi * th - np.sin(th))
        from reduced_models.vibration import _play
        z = _play(np.diff(np.concatenate([[0.0], u])))
        assert (z[-4096:].min() <= -1.0 + 1e-12) == reverses
