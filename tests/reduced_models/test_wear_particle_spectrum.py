"""Model II's closed form, eq. (B2), from the parallel kernel against the direct per-frequency quadrature."""
import math

import numpy as np
import pytest

from reduced_models.wear_particle import DurationLaw, WearParticleParams, theory_force_spectrum
from reduced_models.wear_particle_quadrature import mean_time_pairs


def reference_b2(P, w, closure="exact", order=12):
    """Eq. (B2) by the same Gauss-Legendre nodes, one frequency at a time in numpy (the quadrature written as the
    paper states it: 1 - <cos omega tau>, no rewriting)."""
    TA, TB, W = mean_time_pairs(P, order)
    cA = P.c_A * (TA / P.trapped.tau_min) ** P.kappa_A
    cB = P.c_B * (TB / P.sliding.tau_min) ** P.kappa_B
    out = np.empty(len(w))
    if P.mode == "telegraph":
        tc = TA * TB / (TA + TB)
        for i, wi in enumerate(w):
            out[i] = np.sum(W * (cA - cB) ** 2 * TA * TB / (TA + TB) ** 2 * tc / (np.pi * (1 + (wi * tc) ** 2)))
        return P.n_particles * out

    def omc(law, wi, tau):
        if closure == "exact":
            return 1.0 - law.mean_cos(np.full(np.shape(tau), wi), tau)
        s2 = {"exponential": tau**2, "fixed": 0.0 * tau}.get(law.kind)
        if s2 is None:
            a = law.shape
            s2 = tau**2 / (a * (a - 2)) if a > 2 else np.full(np.shape(tau), np.inf)
        return 1.0 - np.exp(-s2 * wi**2 / 2) * np.cos(wi * tau)

    for i, wi in enumerate(w):
        num = cA**2 * omc(P.trapped, wi, TA) + cB**2 * omc(P.sliding, wi, TB)
        out[i] = np.sum(W * num / (wi**2 * (TA + TB)))
    return P.n_particles / np.pi * out


CASES = {
    "independent, exponential": WearParticleParams(kappa_A=0.2, kappa_B=-0.1),
    "same_rank": WearParticleParams.one_over_f(),
    "fixed and exponential": WearParticleParams(trapped=DurationLaw(1e-2, 1e1, kind="fixed"), c_B=0.02),
    "pareto": WearParticleParams(trapped=DurationLaw(0.1, 0.1, kind="pareto", shape=2.5),
                                 sliding=DurationLaw(0.05, 0.05)),
    "telegraph": WearParticleParams(mode="telegraph", c_A=0.03, c_B=-0.01),
}


@pytest.mark.parametrize("closure", ["exact", "cumulant"])
@pytest.mark.parametrize("case", list(CASES))
def test_kernel_equals_the_direct_quadrature(case, closure):
    # The kernel writes 1 - cos x as 2 sin^2(x/2); the direct form loses ~1e-16 / x^2 of relative precision at small
    # x = omega tau, ~1e-11 at omega tau_min = 1e-3 (the lowest frequency below). Every other step is the same sum in
    # another order (~1e-15): equal within 1e-9.
    P = CASES[case]
    w = np.logspace(-1, 3, 40) if P.trapped.kind != "pareto" else np.logspace(-1, 3, 12)
    np.testing.assert_allclose(theory_force_spectrum(P, w, closure=closure), reference_b2(P, w, closure), rtol=1e-9)


def test_kernel_rejects_an_unknown_closure():
    with pytest.raises(ValueError, match="closure"):
        theory_force_spectrum(WearParticleParams(), [1.0], closure="gaussian")


def test_dt_avg_applies_the_interval_average():
    P = WearParticleParams()
    w = np.array([1.0, 100.0, 1000.0])
    gain = np.sinc(w * 1e-3 / (2 * math.pi)) ** 2
    np.testing.assert_allclose(theory_force_spectrum(P, w, dt_avg=1e-3), theory_force_spectrum(P, w) * gain, rtol=1e-14)
