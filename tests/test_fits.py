"""compare.fits: band handling, prefactor, and errors."""
import numpy as np
import pytest

from compare.fits import fit_power_law
from compare.spectra import displacement_spectrum
from tests.synthetic import power_law_series

DT = 1e-3


def test_prefactor_of_a_random_walk():
    # Random walk with unit steps: C(omega) = dt / (2 pi (2 sin(omega dt/2))^2) -> dt^-1/(2 pi) omega^-2
    # well below Nyquist. The fitted level at the band's centre (10 rad/s, where slope errors do not
    # lever it) must match within 5 % (the chi-square bias of mean ln C is undone in the prefactor).
    n = 2**20
    t = np.arange(n) * DT
    fit = fit_power_law(displacement_spectrum(t, power_law_series(2, n, 7)), band=(1.0, 100.0))
    assert fit.gamma == pytest.approx(2.0, abs=0.03)
    assert fit.level(10.0) == pytest.approx(1 / (2 * np.pi * DT) / 100.0, rel=0.05)
    d = fit.to_dict()
    assert set(["gamma", "gamma_err", "band"]) <= set(d) and d["band"] == [1.0, 100.0]


def test_auto_band_finds_the_straight_part_of_a_bent_spectrum():
    # OU position: flat below 1/tau = 1 rad/s, omega^-2 above. The auto band must lie in the omega^-2
    # part (gamma = 2 +- 0.1), start above the knee and span at least a decade.
    from tests.synthetic import ou_process
    n = 2**20
    t = np.arange(n) * DT
    fit = fit_power_law(displacement_spectrum(t, ou_process(n, DT, 1.0, 1.0, 3)))
    assert fit.gamma == pytest.approx(2.0, abs=0.1)
    assert fit.band[0] > 1.0 and fit.band[1] / fit.band[0] >= 10


def test_band_outside_resolved_range_is_rejected():
    n = 2**14
    spec = displacement_spectrum(np.arange(n) * DT, power_law_series(4, n, 0))
    with pytest.raises(ValueError, match="outside the resolved range"):
        fit_power_law(spec, band=(1e-3, 10.0))
    with pytest.raises(ValueError, match="outside the resolved range"):
        fit_power_law(spec, band=(1.0, 1e5))
    with pytest.raises(ValueError, match="0 < low < high"):
        fit_power_law(spec, band=(10.0, 1.0))
