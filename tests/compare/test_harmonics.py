"""compare.analysis.harmonics: a known line removed from synthetic power-law records (exact cases: the exponent
of the noise is known, and so are the line's amplitudes)."""
import numpy as np
import pytest

from compare.analysis.fits import fit_power_law
from compare.analysis.harmonics import remove_harmonics
from compare.analysis.spectra import displacement_spectrum

DT, N = 2.5e-4, 2 ** 16  # the vibration sweep's output step; 16.4 s
BAND = (20.0, 150.0)     # rad/s, the sweep's band
W_LINE = 2 * np.pi * 20  # 126 rad/s: a line inside the band


def _record(gamma_half: int, seed: int):
    """(t, noise, one-sided density of the noise at f [units^2/Hz]): white noise summed ``gamma_half`` times
    (C ~ omega^-2 gamma_half exactly, the summation's gain |2 sin(omega dt / 2)|^-2 at these frequencies)."""
    rng = np.random.default_rng(seed)
    s = 1e-7
    x = rng.normal(0, s, N)
    for _ in range(gamma_half):
        x = np.cumsum(x)
    t = np.arange(N) * DT

    def density(f):
        return 2 * s ** 2 * DT / (2 * np.sin(np.pi * f * DT)) ** (2 * gamma_half)
    return t, x, density


@pytest.mark.parametrize("gamma_half", [1, 2])
@pytest.mark.parametrize("seed", [0, 1])
def test_line_in_band_removed_exponent_and_amplitude_recovered(gamma_half, seed):
    t, noise, density = _record(gamma_half, seed)
    amps = (np.sqrt(density(20.0) / t[-1]) * 300, np.sqrt(density(40.0) / t[-1]) * 30)  # far above the noise
    line = amps[0] * np.sin(W_LINE * t + 0.4) + amps[1] * np.sin(2 * W_LINE * t - 1.0)
    g_true = 2 * gamma_half
    polluted = fit_power_law(displacement_spectrum(t, noise + line), band=BAND)
    clean, fit = remove_harmonics(t, noise + line, W_LINE, harmonics=3, order=gamma_half)
    got = fit_power_law(displacement_spectrum(t, clean), band=BAND)
    # the unremoved line biases the exponent far outside its interval: the test sees the line
    assert abs(polluted.gamma - g_true) > 3 * polluted.gamma_err
    # the exponent of the noise alone recovered within its 95 % interval (widened by the 1.5 the
    # random field's own scatter of this band fit allows, a 2-sigma margin at these record lengths)
    assert abs(got.gamma - g_true) <= 1.5 * got.gamma_err, (got.gamma, got.gamma_err)
    # each amplitude within 5 standard errors: a least-squares sinusoid's coefficient in noise of one-sided
    # density P_1 over a record of length T has the error sqrt(P_1 / T); the Hann weights widen it by
    # sqrt(sum w^4 n / (sum w^2)^2) = sqrt(1.5) (w^2 the Hann taper), within the factor 5 / 3 of margin kept here
    for k, (a, f) in enumerate(zip(amps, (20.0, 40.0))):
        se = np.sqrt(1.5 * density(f) / t[-1])
        assert abs(fit.amplitude[k] - a) < 5 * se, (k, fit.amplitude[k], a, se)
    assert fit.phase[0] == pytest.approx(0.4, abs=5 * np.sqrt(1.5 * density(20.0) / t[-1]) / amps[0])
    # the third harmonic (absent) is at the noise's level
    assert fit.amplitude[2] < 5 * np.sqrt(1.5 * density(60.0) / t[-1])


def test_no_line_changes_nothing_beyond_one_bin():
    """Without a line the removal takes out only the noise's own content at k omega (a few raw ordinates):
    the band fit is unchanged within a tenth of its interval."""
    t, noise, _ = _record(2, 3)
    a = fit_power_law(displacement_spectrum(t, noise), band=BAND)
    b = fit_power_law(displacement_spectrum(t, remove_harmonics(t, noise, W_LINE, order=2)[0]), band=BAND)
    assert abs(a.gamma - b.gamma) < 0.1 * a.gamma_err


def test_aliased_harmonics_still_removed():
    """A line at the Nyquist frequency's half with harmonics above the Nyquist frequency: 3 f samples as f, so the
    fundamental's fit takes it in, and the record returns to its noise."""
    t, noise, _ = _record(1, 4)
    w = np.pi / (2 * DT)  # f = fs / 4: 2 f aliases onto Nyquist, 3 f onto f
    line = 1e-5 * np.sin(w * t + 0.3) + 3e-6 * np.cos(3 * w * t)
    clean, _ = remove_harmonics(t, noise + line, w, harmonics=4, order=1)
    assert np.std(clean - noise) < 1e-3 * np.std(line)


def test_harmonics_past_nyquist_left_out_not_splitting_the_line():
    """A 15.9 um line at fs / 4 fitted with 4 harmonics: 2f, 3f, 4f lie at or above the Nyquist frequency and are
    left out (NaN), so the fundamental's amplitude is the line's, not split with the 3rd harmonic that samples as
    it (half each, the minimum-norm answer). Tolerance 1 %: the noise's error sqrt(1.5 P_1 / T) is below 1e-3 of
    the line here. A line at the Nyquist frequency itself is not removed (its samples cannot show it)."""
    t, noise, _ = _record(1, 4)
    w = np.pi / (2 * DT)
    clean, fit = remove_harmonics(t, noise + 15.9e-6 * np.sin(w * t + 0.3), w, harmonics=4, order=1)
    assert fit.amplitude[0] == pytest.approx(15.9e-6, rel=0.01) and np.all(np.isnan(fit.amplitude[1:]))
    assert np.std(clean - noise) < 1e-3 * 15.9e-6
    y = noise + 1e-5 * np.cos(np.pi / DT * t)
    same, fit = remove_harmonics(t, y, np.pi / DT, harmonics=4, order=1)
    assert np.array_equal(same, y) and np.all(np.isnan(fit.amplitude))


@pytest.mark.parametrize("kw, field", [({"omega": 0.0}, "omega"), ({"omega": float("nan")}, "omega"),
                                       ({"harmonics": 0}, "harmonics"), ({"order": 5}, "order")])
def test_bad_input_names_the_field(kw, field):
    t = np.arange(1000) * DT
    args = {"omega": 100.0, **kw}
    with pytest.raises(ValueError, match=field):
        remove_harmonics(t, np.sin(t), **args)
