"""compare.testing: the helpers users call in their own suites."""
import numpy as np
import pytest

from compare.testing import SpectralAssertionError, assert_spectral_slope
from tests.synthetic import power_law_series


def test_assert_spectral_slope_passes_and_fails_with_numbers():
    n = 2**17
    t = np.arange(n) * 1e-3
    x = power_law_series(4, n, 11)
    fit = assert_spectral_slope(t, x, expected=4.0, tol=0.1)
    assert abs(fit.gamma - 4) < 0.1
    with pytest.raises(SpectralAssertionError) as err:
        assert_spectral_slope(t, x, expected=5.0, tol=0.2, band=(2.0, 100.0))
    msg = str(err.value)
    assert "measured gamma = 3.9" in msg or "measured gamma = 4.0" in msg
    assert "expected 5 +- 0.2" in msg and "2-100 rad/s" in msg
    assert ("periodogram ordinates" if "whittle" in msg else "log bins") in msg  # what the fit counted
