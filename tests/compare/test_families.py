"""Spectral families against each registered model's own closed form (reduced_models' theory_spectrum)."""
import numpy as np
import pytest

import reduced_models as rm
from compare.analysis.families import FAMILIES, MARGIN, family_of, identified

POINTS = {
    "model_I": lambda: rm.spring_block.SpringBlockParams.reference(),
    "model_Ib": lambda: rm.multiscale.MultiscaleParams.reference(),
    "model_ageing": lambda: rm.ageing.AgeingParams.reference(),
    "model_II": lambda: rm.wear_particle.WearParticleParams(kappa_A=0.1, kappa_B=0.1, c_A=0.02),
    "model_III": lambda: rm.asperity_force.AsperityForceParams.reference(),
    "model_Iv": lambda: rm.vibrating_block.VibratingBlockParams.reference(),
}

# Largest relative deviation of the family from the model's theory_spectrum, (below omega_c / 3, everywhere), and
# why it is not zero. The families average eq. (A8) over the renewal interval's own triangular law (what the
# simulators draw); the closed forms use the paper's cumulant closure: the test multiplies them by the ratio of the
# two (1 - <cos omega tau>) (``_closure_ratio``), so what is left is the family's own approximation:
# - models I and Iv: eq. (A5) exactly (the miniblock's inertia in omega_1): rounding, measured < 1e-12.
# - the ageing model (massless miniblocks): exact (5e-15).
# - model Ib: the micro contacts' transfer P2 / Q2 taken as a first-order filter at omega3 and their impedance left
#   out of the block's damping: 1.5e-3 below the resonance, 1.2 % at the peak.
# - model II: the log-log interpolation between the closed form's 384 nodes (6e-5 measured).
# - model III: the continuum window sinc^2 against the sampled grid's Dirichlet kernel, (omega dt)^2 / 24 and more
#   beside the zeros: 1.9e-3 at omega dt = 0.15 ("below" for this model), 5 % at pi / 4 (the model's own fit band's
#   top); compared where the window is not near a zero.
TOL = {"model_I": (1e-9, 1e-9), "model_Ib": (3e-3, 0.02), "model_Iv": (1e-9, 1e-9), "model_ageing": (1e-12, 1e-12),
       "model_II": (2e-4, 2e-4), "model_III": (3e-3, 0.06)}
RENEWING = ("model_I", "model_Iv", "model_ageing")  # eq. (A8)'s renewal force at the level a alone


def _closure_ratio(x):
    """(1 - cos x sinc^2(x / 2)) / (1 - exp(-x^2 / 12) cos x): the triangular law's over the cumulant closure's."""
    return (1 - np.cos(x) * np.sinc(x / (2 * np.pi)) ** 2) / (1 - np.exp(-x * x / 12) * np.cos(x))


def test_renewal_law_is_the_triangular_intervals_the_simulators_draw():
    # <cos omega tau> over tau = tau0 (1 + r - r'), r, r' uniform, by quadrature on a fine grid of (r, r')
    r = (np.arange(2000) + 0.5) / 2000
    d = (r[:, None] - r[None, :]).ravel()
    for x in (0.3, 2.0, 5.0, 11.0):
        direct = 1 - np.mean(np.cos(x * (1 + d)))
        fam = family_of("model_I")
        th = {"L": 1.0, "a": 1.0, "omega_c": 1e12, "Q": 1.0, "omega_0": 1e14, "omega_1": 1e12}
        got = fam.spectrum(th, [x], 1.0)[0] * x**4  # v = a = 1: x = omega; the block's factor 1 to 1e-12
        assert got == pytest.approx(direct, rel=1e-5)  # midpoint rule on 2000^2 points: error ~ (x / 2000)^2


def test_every_registered_model_declares_a_family():
    assert set(rm.MODELS) <= set(FAMILIES)
    for name in rm.MODELS:
        assert family_of(name).name == name


@pytest.mark.parametrize("name", sorted(POINTS))
def test_family_equals_the_model_closed_form(name):
    p = POINTS[name]()
    fam = family_of(name)
    theta, v = fam.from_model(p)
    top = np.pi / p.dt / 4 if name == "model_III" else 1e4
    w = np.geomspace(1e-2, top, 500)
    model = rm.MODELS[name]
    if name == "model_Iv":
        exact = model.theory_spectrum(p, w, rm.vibrating_block.steady_state(p))
    elif name == "model_Ib":
        exact = model.theory_spectrum(p, w, closure="exact")  # both levels' renewals over the triangular law
    else:
        exact = model.theory_spectrum(p, w)
    if name in RENEWING and name != "model_Ib":
        exact = exact * _closure_ratio(w * theta["a"] / v)
    r = fam.spectrum(theta, w, v) / exact
    if name == "model_III":
        keep = np.abs(np.sin(w * p.w / (2 * p.v))) > 0.1
        w, r = w[keep], r[keep]
    below = w < (0.15 / p.dt if name == "model_III" else theta.get("omega_c", np.inf) / 3)
    tol_below, tol_all = TOL[name]
    assert np.max(np.abs(r[below] - 1)) < tol_below
    assert np.max(np.abs(r - 1)) < tol_all


def test_model_I_level_and_corner_are_eq_A11():
    # The family's omega^-4 level is eq. (A11) and its corner at v/a: far above v/a and below omega_c the family is
    # L omega^-4 (to (omega / omega_c)^2 and exp(-x^2/12): 1e-4 at omega = 100 v/a = 50 rad/s here).
    p = rm.spring_block.SpringBlockParams.reference()
    fam = family_of("model_I")
    theta, v = fam.from_model(p)
    assert theta["L"] == pytest.approx(float(rm.spring_block.asymptotic_spectrum(p, 1.0)), rel=1e-12)
    assert theta["omega_c"] == pytest.approx(np.sqrt(p.N * p.k0 / p.M), rel=0.01)
    assert fam.spectrum(theta, [50.0], v)[0] * 50.0**4 == pytest.approx(theta["L"], rel=2e-2)


def test_ageing_step_is_A_over_A_minus_B_squared():
    p = rm.ageing.AgeingParams.reference()
    fam, mI = family_of("model_ageing"), family_of("model_I")
    theta, v = fam.from_model(p)
    w = np.array([1e-3 * v / p.D_c, 1e3 * v / p.D_c])
    massless = {**theta, "omega_1": 1e12}  # model I's miniblock inertia out of the way (omega / omega_1 < 1e-9)
    ratio = fam.spectrum(theta, w, v) / mI.spectrum(massless, w, v)
    # the step factor |1 - b / (1 + i x)|^-2 at x = 1e-3 and 1e3: (A / (A - B))^2 to O(x^2), 1 to O(b / x)
    assert ratio[0] == pytest.approx((p.A / (p.A - p.B)) ** 2, rel=1e-5)
    assert ratio[1] == pytest.approx(1.0, rel=1e-3)


def test_identified_needs_the_feature_inside_the_band():
    band = (1.0, 100.0)
    assert identified(None, band)
    assert identified(10.0, band)
    assert not identified(1.0, band) and not identified(100.0, band)
    assert identified(1.0001 * MARGIN, band) and not identified(0.9999 * MARGIN, band)


def test_unknown_model_is_named():
    with pytest.raises(KeyError, match="model_X"):
        family_of("model_X")


def test_Q_is_the_resonance_quality_with_both_dampings():
    # Q is what a record places: the resonance's width from the contacts' damping and the springs' together,
    # 1 / Q = 1 / Q_c + omega_c / omega_0. The reference's springs add omega_c / omega_0 = 0.0044 to 1 / Q_c = 0.055
    # (8 % of the width). With Q held, moving omega_0 from the reference's 1.25e5 rad/s to 1e12 changes the family
    # on a 1 kHz record's band (to pi / dt) by at most (omega / omega_0)^2-order terms and the springs' r^2 u against
    # r / Q_c far above the resonance: measured 0.6 %; 1 % is the bound asserted. With Q_c held instead, the peak
    # moves by the 8 % of its width squared, 17 %.
    p = rm.spring_block.SpringBlockParams.reference()
    fam = family_of("model_I")
    theta, v = fam.from_model(p)
    wc, w0 = np.sqrt(p.N * p.k0 / p.M), p.k0 / (p.m * p.eta0)
    Qc = p.N * p.m * p.eta1 / (p.M * wc)
    assert 1 / theta["Q"] == pytest.approx(1 / Qc + wc / w0, rel=1e-12)
    w = np.geomspace(0.1, np.pi / 1e-3, 2000)
    far = fam.spectrum({**theta, "omega_0": 1e12}, w, v) / fam.spectrum(theta, w, v)
    assert np.max(np.abs(far - 1)) < 0.01
    contacts_only = fam.spectrum({**theta, "Q": Qc, "omega_0": 1e12}, [wc], v) / fam.spectrum(theta, [wc], v)
    assert contacts_only[0] > 1.1
    assert not np.isfinite(fam.spectrum({**theta, "Q": 2 * w0 / wc}, [1.0], v)[0])  # springs alone damp more


@pytest.mark.parametrize("s", [1.0, 2.0, 3.0])
def test_model_II_falls_as_six_minus_half_s_between_its_corners(s):
    # (B2) with log-uniform mean times: each state's term P c^2 ~ tau^-beta, averaged through 1 / (tau + tau') over
    # the other state's times, gives C_F ~ omega^(beta - 2), so gamma = 6 - s / 2 between the corners, up to the
    # logarithm that average leaves (measured 5.59, 5.11, 4.63 for s = 1, 2, 3 over 0.1-10 rad/s with the corners at
    # 1e-4 and 1e4 rad/s); 0.15 allows that logarithm. The paper's gamma = 7 - s meets it at s = 2 alone.
    fam = family_of("model_II")
    w = np.array([0.1, 10.0])
    c = fam.spectrum({"S": 1.0, "s": s, "omega_lo": 1e-4, "omega_hi": 1e4}, w, 5e-4)
    gamma = -np.log(c[1] / c[0]) / np.log(w[1] / w[0])
    assert abs(gamma - (6 - s / 2)) < 0.15
    if s != 2.0:
        assert abs(gamma - (7 - s)) > 0.3
