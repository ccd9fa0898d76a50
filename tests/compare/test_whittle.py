"""compare.analysis.whittle: the debiased Whittle likelihood against closed forms; compare.analysis.synthetic's
records against their known autocovariance."""
import math

import numpy as np
import pytest

from compare.analysis.synthetic import power_law_record, sampled_power_law
from compare.analysis.whittle import (WhittleRecord, maximum_likelihood, negloglik, order_for, profile_interval)

DT = 1e-3


def _sampled(omega, p):
    return sampled_power_law(omega, p[0], p[1], DT)


def test_expected_periodogram_of_a_random_walk_is_flat():
    # A random walk's sampled spectrum is exactly A omega^-2 folded; once differenced it is white of level A, and a
    # white series' expected periodogram is its level at every Fourier ordinate (rounding only: 1e-12).
    # The taper (sum h^2 = 1) leaves a white level as it is: E I_j = B sum_t h_t^2.
    for taper in (0.0, 0.1, 1.0):
        rec = WhittleRecord(np.cumsum(np.ones(1000)), DT, 1, taper=taper)
        e = rec.expected(_sampled, (2.0, 3.0), images=None)
        np.testing.assert_allclose(e, 3.0, rtol=1e-12)


def test_tapered_periodogram_is_unbiased_for_white_noise():
    # The mean of 400 tapered periodograms of unit-variance white noise is dt / (2 pi) at every ordinate: 400
    # exponential ordinates average to within 5 sigma = 5 / sqrt(400) = 25 % each; the mean over all of them
    # (400 x 255) to within 1 %.
    rng = np.random.default_rng(0)
    P = np.mean([WhittleRecord(rng.standard_normal(512), DT, 0).periodogram for _ in range(400)], axis=0)
    level = DT / (2 * math.pi)
    assert np.max(np.abs(P / level - 1)) < 0.25 and abs(P.mean() / level - 1) < 0.01


@pytest.mark.parametrize("n", [64, 1000])
def test_expected_periodogram_of_omega4_is_the_finite_ma1_form(n):
    # Twice differenced, a sampled omega^-4 process is MA(1) with spectrum A (2 + cos omega dt) / 3: c(0) = 2/3 and
    # c(1) = 1/6 (times 2 pi A / dt). Over n samples the expected periodogram is A [2/3 + (1 - 1/n) cos(omega dt) / 3]
    # exactly (the Fejer kernel's finite-record bias is the 1 - 1/n); the FFT route must give it to rounding.
    rec = WhittleRecord(np.zeros(n + 2), DT, 2, taper=0.0)
    e = rec.expected(_sampled, (4.0, 2.5), images=None)
    want = 2.5 * (2.0 / 3.0 + (1.0 - 1.0 / rec.n) * np.cos(rec.omega * DT) / 3.0)
    np.testing.assert_allclose(e, want, rtol=1e-10)


def test_finer_grid_changes_a_singular_expectation_little():
    # gamma = 4.45 with k = 2 leaves omega^-0.45 at zero frequency (integrable, not a trigonometric polynomial):
    # the 4n-point grid and a 64n-point grid must agree within 0.5 %, well inside one ordinate's 100 % scatter.
    x = np.zeros(1026)
    coarse = WhittleRecord(x, DT, 2).expected(_sampled, (4.45, 1.0), images=None)
    fine = WhittleRecord(x, DT, 2, oversample=32).expected(_sampled, (4.45, 1.0), images=None)
    assert np.max(np.abs(coarse / fine - 1)) < 5e-3


def test_folding_images_converges_to_the_exact_fold():
    # omega^-4 folded with 3 images on each side leaves out about 2 (7)^-4 / (1 + 1) of the Nyquist level: < 1e-3.
    rec = WhittleRecord(np.zeros(512), DT, 2)
    exact = rec.expected(_sampled, (4.0, 1.0), images=None)
    approx = rec.expected(lambda w, p: p[1] * w ** -p[0], (4.0, 1.0), images=3)
    assert np.max(np.abs(approx / exact - 1)) < 1e-3


@pytest.mark.parametrize("gamma", [2.0, 4.0, 6.0])
def test_synthetic_records_have_the_known_autocovariance(gamma):
    # The k-th difference of power_law_record has c(0) = 2 pi A / dt * {1, 2/3, 11/20} for gamma = 2, 4, 6
    # (integral of A (2 sin/dt)^2k fold over the Nyquist band). Mean of 200 records of 1024 samples: the sample
    # variance's relative standard error is about sqrt(2 * 1.5 / 1024 / 200) = 0.4 %; allow 2 % (5 sigma).
    k = order_for(gamma)
    c0 = {2.0: 1.0, 4.0: 2.0 / 3.0, 6.0: 11.0 / 20.0}[gamma]
    v = np.mean([np.var(np.diff(power_law_record(1024, DT, gamma, seed=s), k) / DT**k) for s in range(200)])
    assert v / (2 * math.pi / DT) == pytest.approx(c0, rel=0.02)


def test_order_for_keeps_the_differenced_slope_integrable():
    assert [order_for(g) for g in (1.2, 2.0, 2.5, 2.6, 4.0, 5.0, 6.0, 20.0)] == [1, 1, 1, 2, 2, 3, 3, 6]


def test_maximum_likelihood_and_profile_interval_recover_a_floored_power_law():
    # One omega^-4 record of 2^11 samples with a floor crossing near 300 rad/s; parameters (gamma, ln A, ln B).
    # The profile interval must contain the truth here (seed 5: not tuned; a 95 % interval misses 1 seed in 20,
    # the coverage study measures the rate) and be narrower than 0.5 (the Cramer-Rao half-width here is ~0.2).
    A, floor_rms = 1.0, 2e-6
    x = power_law_record(2048, DT, 4.0, prefactor=A, floor_rms=floor_rms, seed=5)
    rec = WhittleRecord(x, DT, 2)

    def model(w, p):
        return sampled_power_law(w, p[0], math.exp(p[1]), DT) + math.exp(p[2])

    bounds = [(2.5, 4.9), (-30, 30), (-60, 0)]
    fit = maximum_likelihood(rec, model, (3.5, 0.0, -30.0), bounds=bounds, images=None)
    lo, hi = profile_interval(rec, model, fit, 0, bounds=bounds, images=None, step=0.1)
    assert lo < 4.0 < hi and hi - lo < 1.0
    assert fit.params[0] == pytest.approx(4.0, abs=0.5)
    # the functional form gives the same number as the record's method
    assert negloglik(x, DT, model, fit.params, 2, images=None) == pytest.approx(fit.nll, rel=1e-12)


@pytest.mark.parametrize("order", [0, 1, 3, 6])
@pytest.mark.parametrize("taper", [0.0, 0.1])
def test_white_expected_is_the_exact_quadratic_form(order, taper):
    # For white e of unit level the tapered transform of diff(e, k) / dt^k is a linear form of e, so E I_j is
    # 2 pi / dt * (dt / 2 pi) * sum_s |row_s|^2 / dt^2k, computed here from the explicit differencing matrix. Both
    # are exact: rounding only (1e-12 relative).
    from scipy import signal

    rec = WhittleRecord(np.random.default_rng(0).standard_normal(70 + order), 0.5, order, taper=taper)
    n = rec.n
    h = signal.windows.tukey(n, taper) if taper else np.ones(n)
    h = h / math.sqrt(float(np.sum(h * h)))
    D = np.zeros((n, n + order))
    for t in range(n):
        D[t, t:t + order + 1] = [(-1) ** (order - i) * math.comb(order, i) for i in range(order + 1)]
    exact = np.array([np.sum(np.abs((h * np.exp(-1j * w * 0.5 * np.arange(n))) @ D) ** 2) for w in rec.omega])
    np.testing.assert_allclose(rec.white_expected(), exact / 0.5 ** (2 * order), rtol=1e-12)


def test_white_expected_keeps_its_precision_far_below_the_nyquist_level():
    # Three differences of a white floor over 2^16 samples: the lowest ordinate is about 1e-19 of the highest. The
    # closed form must stay positive and rise as omega^6 where the taper's own leakage is smaller (between the
    # 50th and 100th ordinates the ratio is 2^6 within 10 %: the leakage, about 1e-19 of Nyquist, is < 1 % there).
    rec = WhittleRecord(np.zeros(2**16 + 3), DT, 3)
    b = rec.white_expected()
    assert np.all(b > 0)
    assert b[99] / b[49] == pytest.approx(2.0**6, rel=0.1)
