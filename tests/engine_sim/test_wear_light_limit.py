"""The light-grain limit of the wear grains: the wedge regimes and the climb force against exact cases, and a grain
in the one-pad scene against them (compare/studies/wear_light_limit.py has the full table)."""
import math

import pytest

from compare.studies.wear_light_limit import measure
from engine_sim.wear import climb_force, regime_shares, wedge_regime

R, MU_PAD, MU_TRACK = 300e-6, 0.2, 1.2  # the wear study's pad radius and grain frictions


def _r_at(theta):
    """The grain radius whose contact normal lies at theta below the horizontal: sin theta = (R - r) / (R + r)."""
    return R * (1 - math.sin(theta)) / (1 + math.sin(theta))


def test_wedge_regime_changes_where_the_friction_cones_meet():
    phi, cone = math.atan(1 / MU_TRACK), math.atan(MU_PAD)
    r_trap, r_push = _r_at(phi + cone), _r_at(phi - cone)  # 37.4 and 106.3 um here
    assert r_trap == pytest.approx(37.4e-6, rel=2e-3) and r_push == pytest.approx(106.3e-6, rel=2e-3)
    assert wedge_regime(r_trap * (1 - 1e-6), R, MU_PAD, MU_TRACK)[0] == "trapped"
    assert wedge_regime(r_trap * (1 + 1e-6), R, MU_PAD, MU_TRACK)[0] == "wedged"
    assert wedge_regime(r_push * (1 - 1e-6), R, MU_PAD, MU_TRACK)[0] == "wedged"
    assert wedge_regime(r_push * (1 + 1e-6), R, MU_PAD, MU_TRACK)[0] == "pushed"
    # no pad friction: the cone is a line, and a grain is wedged only exactly at phi
    assert wedge_regime(_r_at(phi) * 0.999, R, 0.0, MU_TRACK)[0] == "trapped"
    assert wedge_regime(_r_at(phi) * 1.001, R, 0.0, MU_TRACK)[0] == "pushed"


def test_climb_force_exact_cases():
    # frictionless: climbing and descending cancel, whatever the spring (the force is odd in psi, the load even)
    assert climb_force(50e-6, R, 0.0, 0.05, 833.0) == pytest.approx(0.0, abs=1e-15)
    # a vanishing bump: the pad just slides over the grain, f = mu_pad x load (corrections of order (r / R))
    assert climb_force(1e-9, R, MU_PAD, 0.05, 833.0) == pytest.approx(MU_PAD * 0.05, rel=1e-3)
    # the closed form comes from the work (friction alone over a climb that ends where it began); the force balance
    # integrated over x is a second route: f = load tan(beta - psi), dx = (R + r) cos psi dpsi
    from scipy.integrate import quad

    load, kn, beta = 0.0425, 833.0, math.atan(MU_PAD)
    for r in (25e-6, 50e-6, 140e-6, 190e-6):
        psi0 = math.acos((R - r) / (R + r))
        def integrand(p):
            return (load + kn * ((R + r) * math.cos(p) + r - R)) * math.tan(beta - p) * math.cos(p)

        f = quad(integrand, -psi0, psi0)[0]
        assert climb_force(r, R, MU_PAD, load, kn) == pytest.approx(f / (2 * math.sin(psi0)), rel=1e-9)
    # beyond theta = atan(mu_pad) (r > 201.7 um here) the pad cannot slide up the grain: refused, not a number
    with pytest.raises(ValueError, match="cannot climb"):
        climb_force(205e-6, R, MU_PAD, load, kn)


def test_regime_shares_over_the_patches_friction():
    # without a spread, the one regime of wedge_regime; with the study's (alpha = 1: mu_track 0.6-1.8) the shares of
    # the uniform patch friction above 1 / tan(theta - cone) (trapped) and below 1 / tan(theta + cone) (pushed)
    for r in (25e-6, 50e-6, 140e-6):
        sh = regime_shares(r, R, MU_PAD, MU_TRACK, 0.0)
        assert sh[wedge_regime(r, R, MU_PAD, MU_TRACK)[0]] == 1.0 and sum(sh.values()) == 1.0
    theta, cone = math.asin((R - 25e-6) / (R + 25e-6)), math.atan(MU_PAD)
    sh = regime_shares(25e-6, R, MU_PAD, MU_TRACK, 1.0)
    assert sh["trapped"] == pytest.approx((1.8 - 1 / math.tan(theta - cone)) / 1.2, rel=1e-12)  # 0.709
    assert sh["pushed"] == 0.0 and sum(sh.values()) == pytest.approx(1.0)
    sh = regime_shares(140e-6, R, MU_PAD, MU_TRACK, 1.0)  # pushed on 80 % of the patches, wedged on the grippiest
    assert sh["trapped"] == 0.0 and sh["pushed"] == pytest.approx(0.801, abs=1e-3)


def test_a_trapped_grain_costs_the_pad_the_quasi_static_climb():
    # A 25 um grain (trapped regime) at the study's grain mass and step: the pad climbs over it every time it meets
    # it. The mean force over the trapped samples must read the climb's statics: measured +3.4 to +7.2 % over steps of
    # 2.5e-5 to 1.6e-6 s and masses of 1e-7 to 1e-3 kg (the statics leave out the pad's damping, inertia and the
    # block's spring); 10 % bounds it. Pushed: a 140 um grain slides ahead with a force of order mu_track m g: the
    # statics give mu_track m g / (1 - mu_track tan a) for a push at a below the horizontal, 1.3-4.3 x across the pad's
    # friction cone (measured 4.4 x: the steep edge); the bound of 10 is the measurement's, not the statics'
    # (on the grippiest patches, mu > 1.56, the grain is wedged and the statics set no upper bound).
    trapped = measure(25e-6, 1e-5, 20, 1e-4, seed=0, duration=4.0)
    assert trapped["regime"] == "trapped" and trapped["trapped_frac"] > 0.05
    assert trapped["F_trapped_N"] == pytest.approx(trapped["climb_N"], rel=0.10)
    pushed = measure(140e-6, 1e-5, 20, 1e-4, seed=0, duration=2.0)
    assert pushed["regime"] == "pushed" and pushed["trapped_frac"] == 0 and pushed["moving_frac"] > 0.5
    assert 1 < pushed["F_moving_N"] / pushed["mu_track_m_g_N"] < 10
    assert abs(trapped["energy_balance_rel"]) < 0.01 and abs(pushed["energy_balance_rel"]) < 0.01


@pytest.mark.slow  # four 4 s runs at 16 substeps: 25 s
def test_lighter_grains_keep_the_trapped_force_and_lose_the_pushed_one():
    # A decade lighter (1e-5 -> 1e-6 kg, same step 6.25e-6 s, seed 0, 4 s): the trapped 25 um grain's force stays (the
    # light limit exists: measured 16.36 -> 16.01 mN, -2.1 %; 10 s x 2 seeds: -0.4 %), the wedged 80 um grain, pushed
    # all the time, loses its force with its mass (measured 1.97 -> 0.20 mN, 9.8x; 10 s x 2 seeds: 8.8x, 9.7x).
    # Bounds: 5 % for the trapped force, a factor 4 for the fall (a force proportional to m falls 10x).
    heavy, light = (measure(25e-6, m, 20, 6.25e-6, seed=0, duration=4.0) for m in (1e-5, 1e-6))
    assert light["F_trapped_N"] == pytest.approx(heavy["F_trapped_N"], rel=0.05)
    heavy, light = (measure(80e-6, m, 20, 6.25e-6, seed=0, duration=4.0) for m in (1e-5, 1e-6))
    assert heavy["regime"] == "wedged" and heavy["trapped_frac"] == 0 == light["trapped_frac"]
    assert heavy["F_moving_N"] / light["F_moving_N"] > 4
