"""compare.analysis.record_model: the power law + floor fitted by the debiased Whittle likelihood, against exact
records (compare.analysis.synthetic) and the closed forms they are drawn from."""
import math

import numpy as np
import pytest
from scipy import special, stats

from compare.analysis.power_floor import PowerFloorProfile
from compare.analysis.record_model import check_record, expected_gamma, fit_record
from compare.analysis.synthetic import power_law_record
from compare.analysis.whittle import WhittleRecord

DT = 1e-3


@pytest.mark.parametrize("gamma", [1.05, 2.0, 4.0, 6.0, 9.0])
def test_fold_matches_hurwitz_zeta(gamma):
    # The Euler-Maclaurin tail beyond |m| = 3 is accurate to 1e-6 of the folded sum (its next term's bound).
    rec = WhittleRecord(np.random.default_rng(0).standard_normal(256), DT, 1)
    u = rec.grid_u
    exact = special.zeta(gamma, u) + special.zeta(gamma, 1 - u)
    np.testing.assert_allclose(PowerFloorProfile([rec], True).fold(gamma), exact, rtol=1e-6)


def test_coverage_of_a_floored_omega4_record():
    # 60 records of 2^10 samples, omega^-4 with a floor crossing at the band's geometric middle (the hardest floor
    # of the coverage page). The 95 % interval must cover 4 in at least 51 of 60: Binomial(60, 0.95) falls below 51
    # with probability 0.0006 (a true 95 % fails this test about once in 1700 runs).
    n, hits = 1024, 0
    w1, wn = 2 * math.pi / (n * DT), math.pi / DT
    rms = math.sqrt(2 * math.pi * math.sqrt(w1 * wn) ** -4.0 / DT)
    assert stats.binom.cdf(50, 60, 0.95) < 1e-3
    for seed in range(60):
        f = fit_record(power_law_record(n, DT, 4.0, floor_rms=rms, seed=seed), DT, stationarity=False)
        hits += f.gamma_low <= 4.0 <= f.gamma_high
    assert hits >= 51


def test_levels_of_a_long_record():
    # 2^16 samples, A = 1, floor 1e-3 m rms (B = rms^2 dt / 2 pi, crossing the power law at 281 rad/s). The fitted level at the identified band's
    # geometric middle, where the exponent's error does not lever it, must be within 5 % (its standard error is
    # about 1 / sqrt(32768) per ordinate pooled over the band: < 1 %); the floor within 10 % (its ordinates:
    # the 90 % above the crossover).
    rms = 1e-3
    f = fit_record(power_law_record(2**16, DT, 4.0, floor_rms=rms, seed=11), DT, stationarity=False)
    mid = math.sqrt(f.band[0] * f.band[1])
    assert f.level(mid) == pytest.approx(mid**-4.0, rel=0.05)
    assert f.floor_rms == pytest.approx(rms, rel=0.1)
    assert f.crossover == pytest.approx((rms**2 * DT / (2 * math.pi)) ** (-1 / 4), rel=0.1)
    assert f.band[1] == pytest.approx(f.crossover)
    assert f.order == 2 and f.power_law
    assert f.band_end == "floor"
    assert f"over the power law above {f.crossover:.3g} rad/s: the floor ends the band" in str(f)


def test_a_clean_power_law_is_identified_over_every_frequency():
    # Without a floor the identified band runs from the first Fourier frequency to the last: log10(n/2) decades,
    # 3.3 at 2^12 samples (the band must span a decade from 2^12 samples on).
    f = fit_record(power_law_record(4096, DT, 6.0, seed=2), DT)
    assert f.decades > 3.0 and f.order == 3
    assert f.band_end == "last frequency" and "departs" not in str(f) and "ends the band" not in str(f)
    # the interval by the name summary.json gives it
    assert f.gamma_interval == (f.gamma_low, f.gamma_high) and f.to_dict()["gamma_interval"] == list(f.gamma_interval)


def test_given_band_restricts_the_ordinates():
    x = power_law_record(4096, DT, 4.0, seed=3)
    f = fit_record(x, DT, band=(10.0, 100.0), stationarity=False)
    w = 2 * math.pi / (4094 * DT) * np.arange(1, 2047)  # twice differenced: 4094 samples
    assert f.n_points == int(np.sum((w >= 10.0) & (w <= 100.0)))
    assert not f.band_auto and 10.0 <= f.band[0] < f.band[1] <= 100.0
    assert f.band_end == "given"
    with pytest.raises(ValueError, match="holds 0 Fourier frequencies"):
        fit_record(x, DT, band=(1000.0, 1000.5))


def test_split_half_test_flags_a_record_whose_level_changes():
    # The second half 3x louder (9x in C_x): the likelihood-ratio statistic grows like n; p is ~0 at 2^12.
    x = power_law_record(4096, DT, 4.0, seed=4)
    x[2048:] = x[2048] + 3.0 * (x[2048:] - x[2048])
    f = fit_record(x, DT)
    assert f.stationarity_p < 1e-6 and not f.power_law and "not stationary" in f.flags[0]


@pytest.mark.parametrize("x, match", [
    (np.full(500, 2.5), "x is constant"),
    (np.round(np.cumsum(np.random.default_rng(0).standard_normal(500)) * 0.05), "at the file's resolution"),
    (np.arange(20.0), "only 20 samples"),
])
def test_records_without_a_spectrum_are_refused_in_one_line(x, match):
    with pytest.raises(ValueError, match=match) as e:
        check_record(x, "x", "m")
    assert "\n" not in str(e.value)


def test_expected_periodogram_of_a_dominant_floor_returns_the_truth():
    # Whittle's likelihood is maximised by the truth when the periodogram is its own expectation. 2^16 samples of
    # omega^-6 (three differences) with a floor meeting the power law at the band's geometric middle: the floor's
    # differenced expectation spans 1e-19 to 1 of its Nyquist level and its share of the mean is about e^30, so
    # the profile must resolve both. The tolerance 1e-3 is the profile's search precision (xatol 1e-5 in gamma,
    # 1e-6 in the ln share) with margin.
    n, g = 2**16, 6.0
    rec = WhittleRecord(np.zeros(n + 3), DT, 3)
    w1, wn = 2 * math.pi / (n * DT), math.pi / DT
    B = math.sqrt(w1 * wn) ** -g
    prof = PowerFloorProfile([rec], True)
    a, am = prof.unit(g)
    rec.periodogram = a * am * (2 * math.pi / DT) ** -g + B * rec.white_expected()
    from compare.analysis.power_floor import minimum

    gamma, _, t = minimum(PowerFloorProfile([rec], True), 3.0, 6.95, None)
    A_fit, B_fit = PowerFloorProfile([rec], True).levels(gamma, t)
    assert gamma == pytest.approx(g, abs=1e-3)
    assert B_fit == pytest.approx(B, rel=1e-2)


def test_split_test_on_exact_expectations():
    # With the periodogram equal to its expectation, Whittle's likelihood is maximised by the truth: one power law
    # gives LR = 0 at every knot (p = 1 up to the profile's search precision), and a corner at 300 rad/s (omega^-4
    # below, omega^-6 above, continuous; 195 ordinates below it) is rejected; without a floor in the model each side
    # of the knot nearest the corner is one power law but for the ordinates between them, so that knot, within a
    # quarter decade (their spacing) of the corner, is the best. (With a floor free on each side, a side's floor
    # absorbs part of the bend and the best knot moves.)
    from compare.analysis.record_model import split_p

    rec = WhittleRecord(np.zeros(4096 + 3), DT, 3)  # three differences: fitted exponents from 3 to 6.95
    band = (float(rec.omega[0]), float(rec.omega[-1]))
    rec.periodogram = rec.expected(lambda w, p: w**-4.0, ())
    assert split_p(rec, True, band)[0] > 0.99
    rec.periodogram = rec.expected(lambda w, p: w**-4.0 * np.minimum(1.0, (300.0 / w) ** 2), ())
    assert split_p(rec, True, band)[0] < 1e-6
    p, knot = split_p(rec, False, band)
    assert p < 1e-6 and abs(math.log10(knot / 300.0)) <= 0.25


def test_spectrum_record_of_a_power_law_is_power_law_record():
    # spectrum_record folds with 8 images where power_law_record sums the fold exactly (Hurwitz zeta): for
    # omega^-4 the 8-image fold leaves out about 17^-3 / 3 of the Nyquist level, so with the same seed the two
    # records agree to 1e-3 of their rms.
    from compare.analysis.synthetic import spectrum_record

    a = spectrum_record(2048, DT, lambda w: w**-4.0, 2, seed=3)
    b = power_law_record(2048, DT, 4.0, seed=3)
    assert np.max(np.abs(a - b)) < 1e-3 * np.std(b)


def _folded(omega, gamma, dt=DT):
    """A omega^-gamma (A = 1) folded at Nyquist: the sampled record's spectrum, by Hurwitz zeta sums."""
    u = np.asarray(omega) * dt / (2 * math.pi)
    return (2 * math.pi / dt) ** -gamma * (special.zeta(gamma, u) + special.zeta(gamma, 1 - u))


@pytest.mark.parametrize("gamma, band", [(4.0, None), (4.0, (10.0, 300.0)), (2.5, (3.0, 100.0))])
def test_expected_gamma_of_a_power_law_is_its_exponent(gamma, band):
    # Fitted to its own expected periodogram, a power law's exponent comes back to the optimiser's tolerance (1e-5
    # in gamma, xatol of the Brent step), well inside 1e-3: the reference a closed form gives the report is exact.
    fit = fit_record(power_law_record(4096, DT, gamma, seed=0), DT, band=band, stationarity=False)
    assert abs(expected_gamma(lambda w: _folded(w, gamma), fit, DT, band) - gamma) < 1e-3


def test_expected_gamma_weights_every_ordinate_not_every_decade():
    # omega^-4 below 100 rad/s and omega^-6 above (continuous at the corner), over 10-1000 rad/s: half the band's
    # decades are at each exponent, so a line through log bins reads 5, but 90 % of the Fourier ordinates lie
    # above the corner; the same fit without noise reads nearer 6 than 5, and it is what records of it converge to.
    def spectrum(w):
        w = np.asarray(w)
        return np.where(w < 100.0, w ** -4.0, 1e4 * w ** -6.0)
    x = power_law_record(2**14, DT, 5.0, seed=1)
    fit = fit_record(x, DT, band=(10.0, 1000.0), stationarity=False)
    g = expected_gamma(spectrum, fit, DT, (10.0, 1000.0))
    assert 5.5 < g < 6.0


def test_expected_gamma_folds_a_continuous_closed_form():
    # A continuous omega^-4 folded by 8 images each side leaves out about 17^-3 / 3 of its Nyquist level: over
    # 10-300 rad/s the noise-free fit still reads 4 within 1e-3.
    band = (10.0, 300.0)
    fit = fit_record(power_law_record(4096, DT, 4.0, seed=0), DT, band=band, stationarity=False)
    assert abs(expected_gamma(lambda w: np.asarray(w) ** -4.0, fit, DT, band, sampled=False) - 4.0) < 1e-3


def test_a_searched_band_is_fitted_at_its_own_differencing_order():
    # Model I's reference case at 1 kHz: omega^-2 below v/a = 0.5 rad/s, omega^-4 to the resonance at 548 rad/s,
    # omega^-8 to -10 above it, so the whole record asks for differencing order 5 (exponents 7-10.95). The band
    # search keeps the lower bands; each must be fitted at the order its own exponent asks for, not held at the
    # limit of the whole record's (which read 10.95 at the limit over 0.2-3.6 rad/s on this record, 7.00 on 120 s).
    # The fit must stop below the resonance and hold the exponent the same fit reads off eq. (A10) over its band;
    # one record, so within 1.5 half-widths (2.9 sigma: a 0.4 % chance of a false failure).
    from reduced_models import spring_block

    p = spring_block.SpringBlockParams.reference()
    tr = spring_block.simulate(p, 30.0, 1e-3, seed=1)
    f = fit_record(tr.x, 1e-3, stationarity=False)
    assert f.power_law and f.fit_band and f.fit_band[1] < spring_block.crossover_frequency(p)
    # What ends the band is the resonance's approach, a departure of another shape: the words say so and name the
    # band above, and do not call it a floor taking over (a floor term may be fitted inside the band, below it).
    text = str(f)
    assert f.band_end == "departure" and f.band[1] == pytest.approx(f.fit_band[1], rel=0.01), (f.band, f.crossover)
    assert f"the band ends at {f.band[1]:.3g} rad/s, where the spectrum departs" in text, text
    assert "not at a white floor" in text and "over the power law above" not in text, text
    for _, _, g, lo, hi, k in f.segments:  # no kept band's interval at its order's limits
        assert 2 * k - 3 + 1e-3 < lo or k == 1, f.segments
        assert hi < 2 * k + 0.95 - 1e-3, f.segments
    ref = expected_gamma(lambda w: spring_block.theory_spectrum(p, w), f, 1e-3, f.fit_band, sampled=False)
    assert abs(f.gamma - ref) <= 1.5 * f.gamma_err, (f, ref)


def test_a_line_in_the_record_changes_nothing():
    # Differencing k >= 1 times removes a line exactly (the once-differenced pilot keeps a constant, which the
    # taper-weighted mean removes), so a drift added or a fitted line removed leaves the fit as it is, to the
    # rounding of the differences (the line is 5x the record's rms over its length: 1e-9 of gamma here).
    t = np.arange(4096) * DT
    x = power_law_record(4096, DT, 4.5, seed=3)
    drift = x + 5 * x.std() * t / t[-1]
    detrended = drift - np.polyval(np.polyfit(t, drift, 1), t)
    fits = [fit_record(y, DT, stationarity=False) for y in (x, drift, detrended)]
    for f in fits[1:]:
        assert (f.gamma, f.gamma_low, f.gamma_high) == pytest.approx((fits[0].gamma, fits[0].gamma_low,
                                                                      fits[0].gamma_high), abs=1e-6)


def test_an_anti_aliased_record_reads_steeper_up_to_nyquist():
    # The model folds the power law at Nyquist, as sampling a continuous process does. A record whose sampled
    # spectrum is omega^-4.5 up to Nyquist without its images (an ideal anti-aliasing filter at Nyquist) has about
    # half the model's power there, and the same fit without noise reads it steeper: 4.576 at 2^12 samples (4.575 at
    # 2^15), where records of 2^12 give a half-width of 0.05, so intervals miss 4.5 (25 of 200 seeds covered). Over a
    # band stopping at a quarter of Nyquist the images weigh (1/7)^4.5 = 2e-4 and both read 4.5 to 1e-3.
    fit = fit_record(power_law_record(4096, DT, 4.5, seed=0), DT, order=2, stationarity=False)

    def unfolded(w):
        return np.asarray(w) ** -4.5
    assert abs(expected_gamma(lambda w: _folded(w, 4.5), fit, DT) - 4.5) < 1e-3
    assert expected_gamma(unfolded, fit, DT) == pytest.approx(4.576, abs=2e-3)
    band = (fit.band[0], 0.25 * math.pi / DT)
    assert abs(expected_gamma(unfolded, fit, DT, band) - 4.5) < 1e-3


@pytest.mark.parametrize("floor_rms", [0.0, 3e-9])
def test_interpolated_search_finds_the_exact_fit(monkeypatch, floor_rms):
    # A record of 2^15 samples is searched on an interpolant of the expected periodogram in gamma; the same search
    # with every evaluation exact (INTERPOLATE_FROM above the length) must give gamma and both interval ends within
    # 1e-3 of the half-width: the interpolant is checked to INTERPOLATION_TOL = 1e-3 in the nll at each result,
    # which moves an end by at most 1e-3 / (3.84 / half-width), a quarter of that.
    from compare.analysis import power_floor
    from compare.analysis.power_floor import interval, minimum

    x = power_law_record(2**15, DT, 4.0, floor_rms=floor_rms, seed=3)

    def fit():
        prof = PowerFloorProfile([WhittleRecord(x, DT, 2)], True)
        g, nll, _ = minimum(prof, 1.05, 4.95, None)
        return (g, *interval(prof, g, nll, 1.05, 4.95)[:2]), nll

    (g, lo, hi), nll = fit()
    monkeypatch.setattr(power_floor, "INTERPOLATE_FROM", 2**40)
    (g0, lo0, hi0), nll0 = fit()
    half = 0.5 * (hi0 - lo0)
    assert max(abs(g - g0), abs(lo - lo0), abs(hi - hi0)) < 1e-3 * half
    assert nll == pytest.approx(nll0, abs=1e-3)


def test_an_interpolant_off_the_exact_profile_is_not_used(monkeypatch):
    # With a tolerance no interpolant meets, minimum() and interval() fall back to exact evaluations everywhere and
    # must return the exact search's result to the last digit.
    from compare.analysis import power_floor
    from compare.analysis.power_floor import interval, minimum

    x = power_law_record(2**15, DT, 4.0, seed=4)

    def fit():
        prof = PowerFloorProfile([WhittleRecord(x, DT, 2)], True)
        g, nll, _ = minimum(prof, 1.05, 4.95, None)
        return (g, nll, *interval(prof, g, nll, 1.05, 4.95))

    monkeypatch.setattr(power_floor, "INTERPOLATION_TOL", -1.0)
    fallback = fit()
    monkeypatch.setattr(power_floor, "INTERPOLATE_FROM", 2**40)
    assert fallback == fit()


def test_the_taper_the_docs_state_is_the_one_the_processing_line_names():
    # whittle_vs_lsq.md: the record model's periodogram is under a Tukey taper of 5 % cosine ends; the band fits'
    # under a rectangular window. The code's taper, the page and each fit's Processing step say the same.
    from pathlib import Path

    from compare.analysis.fits import fit_power_law
    from compare.analysis.record_model import processing_steps
    from compare.analysis.spectra import displacement_spectrum
    from compare.analysis.whittle import TAPER

    page = (Path(__file__).resolve().parents[2] / "docs" / "explanation" / "whittle_vs_lsq.md").read_text()
    assert f"Tukey window with {100 * TAPER / 2:g} % cosine ends" in page and "rectangular window" in page
    n = 4096
    x = power_law_record(n, DT, 4.0, seed=0)
    spec = displacement_spectrum(np.arange(n) * DT, x)
    rec = processing_steps(spec.provenance["steps"], fit_record(x, DT, stationarity=False))
    band = processing_steps(spec.provenance["steps"], fit_power_law(spec, band=(30.0, 1000.0), method="whittle"))
    assert f"under a Tukey taper (a cosine over {100 * TAPER / 2:g} % of the record at each end)" in rec[-1]
    assert not any("rectangular" in s for s in rec)
    assert band[-1].startswith("raw periodogram (rectangular window)") and not any("Tukey" in s for s in band)


def test_a_discrete_random_walk_reads_lower_unless_the_band_stops_at_a_quarter_of_nyquist():
    # docs/explanation/whittle_vs_lsq.md: double sums of white noise (2^12 samples, seeds 0-7) have the spectrum
    # (2 sin(omega dt / 2))^-4, above the folded omega^-4 toward Nyquist; the fit takes the rise for a floor that ends
    # the band and reads gamma lower (3.79-3.97, 5 of 8 intervals holding 4); stopped at a quarter of Nyquist it
    # reads 3.95-4.05 and every interval holds 4
    n = 4096
    default, quarter = [], []
    for seed in range(8):
        rng = np.random.default_rng(seed)
        x = 1e-4 * np.arange(n) * DT + 1e-9 * np.cumsum(np.cumsum(rng.standard_normal(n)))
        default.append(fit_record(x, DT))
        quarter.append(fit_record(x, DT, band=(2 * math.pi / (n * DT), math.pi / DT / 4)))
    assert sum(f.gamma_low <= 4 <= f.gamma_high for f in default) == 5
    assert all(f.band_end == "floor" and not f.flags and 0.1e-9 < f.floor_rms < 0.3e-9 for f in default)
    assert 3.79 <= min(f.gamma for f in default) and max(f.gamma for f in default) < 3.97 + 5e-4
    assert all(f.gamma_low <= 4 <= f.gamma_high for f in quarter)
    assert min(f.gamma for f in quarter) >= 3.95 - 5e-4 and max(f.gamma for f in quarter) <= 4.05 + 5e-4
    # the floor that ends the band sits in the top half-decade below Nyquist: the fit's note names the discrete form
    assert all(any("discrete=True" in n for n in f.notes) for f in default)
    assert all(f"\n  note: {f.notes[0]}" in str(f) for f in default)  # printed with the fit in Python too


def test_the_discrete_form_fits_a_discrete_random_walk():
    # fit_record(..., discrete=True) models (2 sin(omega dt / 2) / dt)^-gamma, the exact spectrum of a double sum of
    # white noise (docs/explanation/whittle_vs_lsq.md): on the same records as above, each interval of half-width
    # about 0.06 holds 4 (8 of 8; at 95 % coverage 7 or 8 of 8 happen with probability 0.94), the mean lies within
    # 0.03 of 4 (its standard error is about 0.014 here), and no floor ends the band; a 30-step-rms white floor added
    # is found as such (its rms within 10 %: its level is fitted from the top decade's thousands of ordinates)
    n = 4096
    fits, noisy = [], []
    for seed in range(8):
        rng = np.random.default_rng(seed)
        walk = 1e-9 * np.cumsum(np.cumsum(rng.standard_normal(n)))
        x = 1e-4 * np.arange(n) * DT + walk
        fits.append(fit_record(x, DT, discrete=True))
        noisy.append(fit_record(x + 30e-9 * rng.standard_normal(n), DT, discrete=True, stationarity=False))
    assert sum(f.gamma_low <= 4 <= f.gamma_high for f in fits) >= 7
    assert abs(np.mean([f.gamma for f in fits]) - 4) < 0.03
    assert all(f.band_end != "floor" and f.floor_rms < 0.1e-9 for f in fits)
    assert all(any(n.startswith("fitted as a discrete-time process") for n in f.notes) for f in fits)
    assert sum(f.gamma_low <= 4 <= f.gamma_high for f in noisy) >= 7
    assert all(f.band_end == "floor" and abs(f.floor_rms / 30e-9 - 1) < 0.1 for f in noisy)


def test_a_band_above_nyquist_is_said_to_end_there():
    x = power_law_record(4096, DT, 4.0, seed=0)
    f = fit_record(x, DT, band=(1.0, 1e5), stationarity=False)
    assert any("above the record's Nyquist frequency 3142 rad/s" in n for n in f.notes)
    assert not any("Nyquist frequency" in n for n in fit_record(x, DT, band=(1.0, 1e3), stationarity=False).notes)
