"""Model III (asperity force) against the exact moving-window spectrum (sections 6-7, Fig. 6)."""
import numpy as np
import pytest

from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum, force_series_spectrum
from compare.analysis.assertions import assert_spectrum_matches
from reduced_models.asperity_force import (
    AsperityForceParams, grid_force_variance, simulate, theory_force_spectrum, theory_spectrum,
    theory_spectrum_sampled,
)


@pytest.mark.parametrize("N", [30, 300])
def test_grid_holds_the_papers_contacts_under_the_block(N):
    # section 7's picture, not its formulas restated: the window of N_w cells covers the block (w), the block moves
    # one cell per step (v dt = dx), the cells under it hold N asperities on average (p N_w = N), whose mean force
    # r f0 with r uniform in [0, 1] adds up to the friction force F_f
    p = AsperityForceParams.reference(N)
    assert p.N_w * p.dx == pytest.approx(p.w, rel=1e-12)
    assert p.v * p.dt == pytest.approx(p.dx, rel=1e-12)
    assert p.p * p.N_w == pytest.approx(N, rel=1e-12)
    assert p.p * p.N_w * p.f0 / 2 == pytest.approx(p.F_f, rel=1e-12)


@pytest.mark.parametrize("N", [30, 300])
def test_fig6_gamma_6_mean_force_and_exact_spectrum(N):
    p = AsperityForceParams.reference(N)
    tr = simulate(p, 2**20 * p.dt, seed=1)
    # mean force = F_f: the window mean over 2^20 steps has a relative scatter ~ 1e-3; 2 %.
    assert tr.force.mean() == pytest.approx(p.F_f, rel=0.02)
    # C_F within 10 % of the exact window-sum spectrum in every log band from 3 v/w to omega_N / 3
    # (measured: within 5 %).
    wN = np.pi / p.dt
    edges = np.logspace(np.log10(3 * p.v / p.w), np.log10(wN / 3), 9)
    sF = force_series_spectrum(tr.t, tr.force)
    assert_spectrum_matches(sF, lambda w: theory_force_spectrum(p, w), edges, rtol=0.10)
    # C_x of the sampled trajectory within 10 % of its exact form (eq. 3 with the sampled transfer)
    sx = displacement_spectrum(tr.t, tr.x)
    assert_spectrum_matches(sx, lambda w: theory_spectrum_sampled(p, w), edges, rtol=0.10)
    # gamma = 6 above the window's corner: band 30 v/w to omega_N / 4 (N = 30: 6.04 +- 0.15;
    # N = 300: 6.003 +- 0.016 measured). Below v/w the force is white, the free block's velocity
    # diffuses and C_x ~ omega^-4, which the automatic band picks for N = 30; hence the explicit band.
    fit = fit_power_law(sx, band=(30 * p.v / p.w, wN / 4))
    assert fit.gamma == pytest.approx(6.0, abs=0.15)


def test_theory_forms_agree_far_below_nyquist():
    p = AsperityForceParams.reference(300)
    w = np.array([1.0, 3.0, 10.0])
    np.testing.assert_allclose(theory_spectrum_sampled(p, w) / theory_spectrum(p, w), 1.0, atol=0.01)
    # zero frequency limit of the window sum: sigma_g^2 dt N_w^2 / (2 pi)
    w0 = np.array([1e-6])
    assert theory_force_spectrum(p, w0)[0] == pytest.approx(grid_force_variance(p) * p.dt * p.N_w**2 / (2 * np.pi), rel=1e-6)


@pytest.mark.parametrize("kw, field", [({"p": 0.0}, "p"), ({"p": 1.5}, "p"), ({"M": -1.0}, "M"), ({"w": 0.0}, "w"),
                                       ({"N": 0.01}, "N")])
def test_invalid_parameters(kw, field):
    with pytest.raises(ValueError, match=field):
        AsperityForceParams(**kw)
