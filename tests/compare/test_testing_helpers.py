"""compare.testing: the helpers users call in their own suites."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from compare.analysis.fits import fit_power_law
from compare.analysis.record_model import fit_series
from compare.analysis.spectra import displacement_spectrum
from compare.analysis.synthetic import power_law_record
from compare.testing import SpectralAssertionError, assert_spectral_slope
from tests.synthetic import power_law_series

DT = 1e-3
ROOT = Path(__file__).resolve().parents[2]


def _covered(n_seeds: int, gamma: float, n: int, band, floor_rms: float = 0.0) -> int:
    """How many of ``n_seeds`` exact sampled omega^-gamma records (compare.analysis.synthetic) the helper's default
    fit covers: gamma within the fit's 95 % half-width, i.e. the assertion with tol = gamma_err holds (a fit a test
    flags by chance, such as the bend test at its 1 % level, is counted too: the coverage is the interval's)."""
    t = np.arange(n) * DT
    hits = 0
    for seed in range(n_seeds):
        x = power_law_record(n, DT, gamma, floor_rms=floor_rms, seed=seed)
        fit = assert_spectral_slope(t, x, expected=gamma, tol=np.inf, band=band, allow_flagged=True)
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
    assert "expected gamma = 5 +- 0.2" in msg and "given" in msg and "Fourier ordinates" in msg and "record" in msg
    assert "off by -1.0" in msg or "off by -0.9" in msg
    # a few lines a user reads: why, exponent with its interval, expectation, band, flags, what ends the band, the
    # fit's notes
    lines = msg.splitlines()
    ref = fit_series(t, x, band=(2.0, 100.0), stationarity=False)
    assert len(lines) == 6 + len(ref.notes) and lines[4] == "  flags: none" and lines[5].startswith("  band end: ")
    assert f"95 % interval [{ref.gamma_low:.3f}, {ref.gamma_high:.3f}]" in lines[1]


def test_a_flagged_fit_fails_by_default_and_names_its_flag():
    # 2^12 samples: the Welch band fit's automatic band spans well under a decade, a flag; the exponent itself is
    # right (tol = inf), so only the flag can fail the assertion
    n = 4096
    t = np.arange(n) * DT
    x = power_law_series(4, n, 3)
    with pytest.raises(SpectralAssertionError) as err:
        assert_spectral_slope(t, x, expected=4.0, tol=np.inf, method="whittle")
    msg = str(err.value)
    fit = fit_power_law(displacement_spectrum(t, x), method="whittle")
    assert fit.flags, "the record was chosen to give a flagged band fit"
    assert "NOT A POWER LAW" in msg and "allow_flagged=True" in msg
    assert f"  flags: {'; '.join(fit.flags)}" in msg.splitlines()
    assert len(msg.splitlines()) == 5
    # the opt-out checks gamma alone and returns the flagged fit
    ok = assert_spectral_slope(t, x, expected=4.0, tol=np.inf, method="whittle", allow_flagged=True)
    assert ok.flags == fit.flags
    # off and flagged: both reasons on the first line
    with pytest.raises(SpectralAssertionError, match="gamma is off by .* and the fit is flagged NOT A POWER LAW"):
        assert_spectral_slope(t, x, expected=7.0, tol=0.1, method="whittle")


def test_pytest_shows_a_failure_in_a_few_lines(tmp_path):
    # the helper hides its own frame (__tracebackhide__): pytest's report of a failing user test shows the user's
    # line and the message, not the helper's source and its array arguments
    (tmp_path / "test_user.py").write_text(
        "import numpy as np\n"
        "from compare.testing import assert_spectral_slope\n"
        "from compare.analysis.synthetic import power_law_record\n"
        "def test_slope():\n"
        "    x = power_law_record(4096, 1e-3, 4.0, seed=0)\n"
        "    assert_spectral_slope(np.arange(4096) * 1e-3, x, expected=5.0, tol=0.2)\n")
    out = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:randomly",
                          str(tmp_path / "test_user.py")], capture_output=True, text=True, cwd=tmp_path,
                         env={**os.environ, "PYTHONPATH": str(ROOT)}).stdout
    report = out.split("= FAILURES =", 1)[1].split("short test summary", 1)[0].splitlines()
    assert "spectral slope: gamma is off by" in out and "def assert_spectral_slope" not in out
    assert len(report) <= 16, out


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
    with pytest.raises(ValueError, match="discrete applies to method='record'"):
        assert_spectral_slope(t, x, expected=4.0, tol=0.2, method="lsq", discrete=True)


def test_a_discrete_walk_is_fitted_in_its_own_form_when_asked():
    # discrete=True hands the record to the record model's discrete form (docs/howto/slope_test.md): the same fit as
    # fit_series(..., discrete=True), number for number, and its note says which form was fitted
    rng = np.random.default_rng(0)
    t = np.arange(4096) * DT
    x = 1e-9 * np.cumsum(np.cumsum(rng.standard_normal(4096)))
    fit = assert_spectral_slope(t, x, expected=4.0, tol=0.2, discrete=True)
    ref = fit_series(t, x, stationarity=False, discrete=True)
    assert fit.gamma == ref.gamma and fit.gamma_interval == ref.gamma_interval
    assert any(n.startswith("fitted as a discrete-time process") for n in fit.notes)


def test_a_failing_walk_names_the_discrete_form_in_its_message():
    # a double sum of white noise fitted as a sampled continuous process reads low with a floor near Nyquist
    # (docs/explanation/whittle_vs_lsq.md); a failure's message carries that floor and the note naming discrete=True
    rng = np.random.default_rng(0)
    t = np.arange(4096) * DT
    x = 1e-9 * np.cumsum(np.cumsum(rng.standard_normal(4096)))
    with pytest.raises(SpectralAssertionError) as err:
        assert_spectral_slope(t, x, expected=4.0, tol=0.01)
    msg = str(err.value)
    assert "band end: white floor" in msg and "the floor ends the band" in msg and "discrete=True" in msg
