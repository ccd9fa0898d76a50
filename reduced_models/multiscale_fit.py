"""Model Ib's parameters measured from recorded forces: the estimators, on arrays (no engine, no files).

Two procedures, each stated where it is used:

1. :func:`renewal_statistics`: one level of renewing contacts from the sum of their forces (the micro level of a
   scene whose metadata gives n, m2, k2, a2 but not the friction it produced). For K independent contacts whose
   forces renew as in model I (eq. 5: a uniform value alpha f_kin (r - 1/2) once per window a of sliding):

   - f_kin = <G> / K (G the summed force);
   - the autocorrelation of G in sliding distance is one contact's (independent, identical contacts), whose
     integral is <tau^2> / (2 <tau>) = 7 a / 12 (:mod:`reduced_models.correlation`): a = (12/7) L_c, with L_c integrated
     over [0, 2a] (rho vanishes beyond the longest interval 2 a), a found as the fixed point from model I's
     first-zero estimate;
   - Var G = K (alpha f_kin)^2 / 12 (eq. A7): alpha f_kin = sqrt(12 Var G / K).

   Forces averaged over output intervals dt (model Ib's trace) lose variance: the mean over dt of a process
   whose correlation falls as 1 - tau / tau0 (a renewal rate 1/tau0 = v/a) has variance 1 - dt / (3 tau0) of the
   process's, to first order (the next term is O((dt/tau0)^2)); its correlation integral keeps its numerator, so
   L_c reads 1 / (1 - dt/(3 tau0)) too long. ``averaged_dt`` undoes both.

2. :func:`fit_renewal_levels`: one or two renewal levels from a force *spectrum*: the band-averaged spectrum of
   a contact's force is fitted by the sum of ``levels`` renewal spectra (A8), each with its own length a_k and
   amplitude A_k = alpha_k f_kin_k, by least squares on ln C over log bands (the same ordinates averaged in data
   and model). With one level it measures model I's (a, alpha) the same way, so model I and model Ib can be
   compared with parameters obtained by one procedure.

:func:`rigid_micro_params` turns two measured levels of a *single* contact (a pad on a rough track: its force
has a slow and a fast part but no second spring) into a :class:`~reduced_models.multiscale.MultiscaleParams`
with one stiff micro contact per miniblock, so that the fast force reaches the miniblock unfiltered (T2 = 1 to
1e-4 below 1e4 rad/s).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import multiscale as ms
from . import spring_block as m1
from .correlation import autocorrelation, correlation_integral, correlation_length

__all__ = ["RenewalLevel", "renewal_statistics", "renewal_force_spectrum", "fit_renewal_levels", "rigid_micro_params",
           "correlation_length"]


@dataclass(frozen=True)
class RenewalLevel:
    """One level of renewing contact forces, per contact: mean f_kin (Units: N), renewal length a (Units: m),
    amplitude = alpha f_kin (Units: N); n_renewals: renewals the estimate rests on (K x distance / a)."""

    f_kin: float
    a: float
    amplitude: float
    n_renewals: float = math.nan

    @property
    def alpha(self) -> float:
        return self.amplitude / self.f_kin if self.f_kin else math.inf


def renewal_statistics(x, G, n_contacts: int, *, offset: float = 0.0, averaged_dt: float | None = None,
                       max_lag_distance: float | None = None) -> RenewalLevel:
    """Procedure 1 of the module docstring: (f_kin, a, alpha f_kin) per contact from the sum ``G`` (Units: N)
    of ``n_contacts`` independent renewing forces sampled with the sliding distance ``x`` (Units: m).

    ``offset``: a constant added to G (a model trace records only the random part; the mean friction is then
    given, not measured). ``averaged_dt``: the output interval (Units: s) when G holds averages over it rather
    than samples; the variance and correlation length are corrected to first order in dt / tau0 (docstring).
    ``max_lag_distance``: where to stop the correlation integral if rho never reaches zero (default: a tenth of
    the record)."""
    x = np.asarray(x, dtype=float)
    G = np.asarray(G, dtype=float)
    K = int(n_contacts)
    if K < 1 or len(x) != len(G) or len(x) < 16:
        raise ValueError("renewal_statistics needs n_contacts >= 1 and x, G of the same length (>= 16 samples)")
    dist = float(x[-1] - x[0])
    v = dist / (averaged_dt * (len(x) - 1)) if averaged_dt else None
    # a from the first zero of rho, then integrated over the fixed window [0, 2a] (no renewal interval exceeds
    # 2 tau0, eq. 5, so rho vanishes beyond; a fixed window keeps the estimate's variance bounded, where the noisy
    # first zero of a long record can land far out), iterated to its fixed point
    rho, dx = autocorrelation(x, G)
    a = 12.0 / 7.0 * correlation_integral(rho, dx, max_lag_distance or dist / 10)
    s = 1.0
    for _ in range(6):
        s = 1.0 - averaged_dt * v / (3.0 * a) if averaged_dt else 1.0
        a = 12.0 / 7.0 * correlation_integral(rho, dx, window=2.0 * a) * s
    var = float(np.var(G)) / s
    return RenewalLevel(f_kin=(float(np.mean(G)) + offset) / K, a=a, amplitude=math.sqrt(12.0 * var / K),
                        n_renewals=K * dist / a)


def renewal_force_spectrum(omega, v: float, a: float, amplitude: float, closure: str = "cumulant") -> np.ndarray:
    """One contact's renewing-force spectrum, eq. (A8) (Units: N^2 s): ``reduced_models.multiscale``'s, public."""
    return ms.contact_force_spectrum(v, a, amplitude, omega, closure)


def _band_means(omega, values, edges):
    idx = np.digitize(omega, edges)
    return np.array([values[idx == j].mean() if np.any(idx == j) else np.nan for j in range(1, len(edges))])


def fit_renewal_levels(omega, C, v: float, edges, levels: int = 2, guess: tuple[float, float] | None = None,
                       closure: str = "cumulant") -> tuple[list[RenewalLevel], float]:
    """Procedure 2 of the module docstring: ``levels`` renewal spectra (A8) fitted to one contact's force
    spectrum ``C`` (Units: N^2 s, at ``omega`` in rad/s) at sliding speed ``v``, by least squares on the log of the
    band means over ``edges``. ``guess`` = (a, amplitude) of a single level (e.g. model I's extraction); a second
    level starts at a / 30 and amplitude / 3. Returns the levels, slowest first (f_kin left nan: a spectrum does
    not hold the mean), and the rms of ln(model / data) over the bands."""
    from scipy.optimize import least_squares

    omega, C = np.asarray(omega, float), np.asarray(C, float)
    keep = (omega >= edges[0]) & (omega <= edges[-1])
    omega, C = omega[keep], C[keep]
    data = _band_means(omega, C, edges)
    ok = np.isfinite(data) & (data > 0)
    if ok.sum() < 2 * levels + 1:
        raise ValueError(f"fit_renewal_levels: {ok.sum()} usable bands for {2 * levels} parameters")
    a0, A0 = guess if guess is not None else (v * 2 * math.pi / math.sqrt(edges[0] * edges[-1]), math.sqrt(data[ok][0]))
    p0 = [math.log(a0), math.log(A0)] + ([math.log(a0 / 30), math.log(A0 / 3)] if levels == 2 else [])

    def model(p):
        out = np.zeros_like(omega)
        for k in range(levels):
            out += renewal_force_spectrum(omega, v, math.exp(p[2 * k]), math.exp(p[2 * k + 1]), closure)
        return _band_means(omega, out, edges)[ok]

    res = least_squares(lambda p: np.log(model(p) / data[ok]), p0, method="lm")
    lv = sorted((RenewalLevel(f_kin=math.nan, a=math.exp(res.x[2 * k]), amplitude=math.exp(res.x[2 * k + 1]))
                 for k in range(levels)), key=lambda r: -r.a)
    return lv, float(np.sqrt(np.mean(res.fun ** 2)))


def rigid_micro_params(base: m1.SpringBlockParams, slow: RenewalLevel, fast: RenewalLevel) -> ms.MultiscaleParams:
    """Model Ib with the macro level of ``base`` (model I built from the same scene) and one stiff micro contact
    per miniblock carrying the fast level: a2 = fast.a, and the two amplitudes as measured. The mean friction
    per miniblock, base.F_kin / N, is shared between the levels in proportion to their amplitudes (so alpha2 =
    alpha; only the products alpha f_kin and alpha2 f_kin2 enter C_x). The micro contact is rigid on the scale
    of the bands: m2 = 1e-3 m, k2 = 10 k0 (resonance sqrt(10 k0 / (1e-3 m)) = 100 sqrt(k0/m)), eta2 critical,
    eta3 = 0 (the friction slope stays in eta1 = base's), so T2 = 1 + O(m2 omega^2 / k2) and the micro mass adds
    1e-3 to the miniblock's."""
    f_kin = base.F_kin / base.N
    A1, A2 = slow.amplitude, fast.amplitude
    alpha = (A1 + A2) / f_kin
    f1 = f_kin * A1 / (A1 + A2)
    m2, k2 = 1e-3 * base.m, 10.0 * base.k0
    return ms.MultiscaleParams(N=base.N, v=base.v, a=slow.a, k0=base.k0, k1=0.0, M=base.M, m=base.m, eta0=base.eta0,
                               eta1=base.eta1, eta_lat=0.0, alpha=alpha, F_drive=base.F_drive, F_kin=base.N * f1,
                               n_micro=1, m2=m2, k2=k2, eta2=2.0 * math.sqrt(k2 / m2), eta3=0.0, a2=fast.a,
                               alpha2=alpha, F_kin2=base.N * (f_kin - f1))
