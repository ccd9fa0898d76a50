"""compare.testing: the helpers users call in their own suites."""
import numpy as np
import pytest
from scipy import stats

from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum
from compare.analysis.synthetic import power_law_record
from compare.testing import SpectralAssertionError, assert_spectral_slope
from tests.synthetic import power_law_series

DT = 1e-3


def _covered(n_seeds: int, gamma: float, n: int, band, floor_rms: float = 0.0) -> int:
    """How many of ``n_seeds`` exact sampled omega^-gamma records (compare.analysis.synthetic) the helper's default
    fit covers: gamma within the fit's 95 % half-width, i.e. the assertion with tol = gamma_err holds."""
    t = np.arange(n) * DT
    hits = 0
    for seed in range(n_seeds):
        x = power_law_record(n, DT, gamma, floor_rms=floor_rms, seed=seed)
        fit = assert_spectral_slope(t, x, expected=gamma, tol=np.inf, band=band)
        hits += abs(fit.gamma - gamma) <= fit.gamma_err  # what the assertion with tol = gamma_err checks
    return hits


def _least_count(n_seeds: int) -> int:
    """The fewest covering intervals of n_seeds that a true 95 % coverage gives with probability >= 0.001
    (binomial: fewer reject the interval at p < 0.001)."""
    return int(stats.binom.ppf(0.001, n_seeds, 0.95))


@pytest.mark.parametrize("gamma, band", [(4.0, (20.0, 200.0)), (2.0, (20.0, 200.0)), (6.0, None)])
def test_default_record_model_interval_covers_the_true_exponent(gamma, band):
    # exact sampled omega^-gamma records of 2^12 samples (a 4 s lab record): the stated band holds ~120 Fourier
    # ordinates; None lets the record model find its own band. 40 seeds: under a true 95 % coverage fewer than
    # 33 covering intervals have probability < 0.001
    n_seeds = 40
    assert _covered(n_seeds, gamma, 4096, band) >= _least_count(n_seeds)


def test_record_model_interval_covers_with_a_sensor_floor():
    # omega^-4 with a white floor meeting the power law near 300 rad/s, inside the record (Nyquist 3142 rad/s) and
    # above the band's middle: the record model fits the floor as a term, so its interval still covers 4
    n_seeds = 30
    cross = 300.0
    floor_rms = np.sqrt(cross**-4.0 * 2 * np.pi / DT)  # level A omega^-4 = floor_rms^2 dt / (2 pi) at the crossing
    assert _covered(n_seeds, 4.0, 4096, None, floor_rms=floor_rms) >= _least_count(n_seeds)


def test_assert_spectral_slope_passes_and_fails_with_numbers():
    n = 2**15
    t = np.arange(n) * DT
    x = power_law_series(4, n, 11)
    fit = assert_spectral_slope(t, x, expected=4.0, tol=0.1)
    assert fit.method == "record" and abs(fit.gamma - 4) < 0.1
    with pytest.raises(SpectralAssertionError) as err:
        assert_spectral_slope(t, x, expected=5.0, tol=0.2, band=(2.0, 100.0))
    msg = str(err.value)
    assert "measured gamma = 3.9" in msg or "measured gamma = 4.0" in msg
    assert "expected 5 +- 0.2" in msg and "given band" in msg and "Fourier ordinates" in msg and "record" in msg


def test_band_fit_stays_reachable():
    # method="whittle" / "lsq" is the band fit of the Welch spectrum it was, number for number
    n = 2**15
    t = np.arange(n) * DT
    x = power_law_series(4, n, 11)
    for method in ("whittle", "lsq"):
        fit = assert_spectral_slope(t, x, expected=4.0, tol=0.2, band=(5.0, 100.0), method=method, nperseg=4096)
        ref = fit_power_law(displacement_spectrum(t, x, nperseg=4096), band=(5.0, 100.0), method=method)
        assert fit.gamma == ref.gamma and fit.gamma_err == ref.gamma_err and fit.method == method
    with pytest.raises(SpectralAssertionError, match="log bins"):
        assert_spectral_slope(t, x, expected=5.0, tol=0.2, band=(5.0, 100.0), method="lsq")


def test_wrong_method_or_welch_option_is_named():
    t = np.arange(4096) * DT
    x = power_law_series(4, 4096, 0)
    with pytest.raises(ValueError, match="'band': choose one of record, whittle, lsq"):
        assert_spectral_slope(t, x, expected=4.0, tol=0.2, method="band")
    with pytest.raises(ValueError, match="nperseg: Welch spectrum options"):
        assert_spectral_slope(t, x, expected=4.0, tol=0.2, nperseg=1024)
