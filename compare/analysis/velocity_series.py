"""Several measured displacement records at different sliding speeds (the paper's Tables 1-3 and Fig. 15): C_x at
one angular frequency omega against the mean speed v with its velocity exponent, the collapse in q = omega / v
(section 2), and model I's level alpha^2 / (N a) from each record's omega^-4 band (eq. 6 / A12).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .displacement import DisplacementAnalysis
from .velocity import velocity_analysis

__all__ = ["VelocitySeries", "velocity_series", "LEVEL_HALF_WIDTH", "MODEL_I_ASSUMPTION"]

LEVEL_HALF_WIDTH = 10**0.1  # C_x(omega) is the average over omega / 10^0.1 .. omega * 10^0.1 (a fifth of a decade)
MODEL_I_ASSUMPTION = ("alpha^2/(N a) = 12 pi omega^4 C_x / v^3 is eq. (6) of model I solved for its level: it assumes "
                      "model I's friction law, m eta1 v = f_kin (each junction's kinetic force set by the sliding speed)")


@dataclass(frozen=True)
class VelocitySeries:
    """C_x(omega) against v over records at different speeds.

    Attributes
    ----------
    omega : float
        The angular frequency of the comparison (rad/s).
    omega_auto : bool
        True when ``omega`` is the default: inside the band common to every record's fit band, where the least
        precise record's level is most precise.
    common_band : tuple of float
        The intersection of the records' fit bands (rad/s).
    v : ndarray
        Each record's mean sliding velocity (m/s).
    C_at_omega : ndarray
        Each record's C_x at ``omega`` (m^2 s).
    ln_C_err : ndarray
        Standard error of ln C_at_omega from the spectrum's band averaging (dimensionless).
    exponent, exponent_err : float
        C_x(omega) ~ v^exponent, and its 95 % half-width.
    exponent_err_source : str
        ``"per-record"`` (weighted least squares with the errors ``ln_C_err``) or ``"residual scatter"`` (when the
        scatter about the line is more than those errors explain, chi-square p < 0.05, or no per-record error).
    level_alpha2_Na : ndarray
        Model I's alpha^2/(N a) of each record: the geometric mean over its fit band of 12 pi omega^4 C_x / v^3
        (1/m: m^2 s * s^-4 / (m/s)^3).
    gamma, gamma_err : ndarray
        Each record's spectral exponent and its 95 % half-width (model I's level is meaningful where gamma ~ 4).
    collapse : dict
        The spread of ln C across records in omega and in q = omega / v (:func:`compare.analysis.velocity.velocity_analysis`).
    """

    omega: float
    omega_auto: bool
    common_band: tuple
    v: np.ndarray
    C_at_omega: np.ndarray
    ln_C_err: np.ndarray
    exponent: float
    exponent_err: float
    exponent_err_source: str
    level_alpha2_Na: np.ndarray
    gamma: np.ndarray
    gamma_err: np.ndarray
    collapse: dict

    def summary(self) -> dict:
        """JSON-ready numbers (SI units)."""
        return {"omega_rad_per_s": self.omega, "omega_auto": self.omega_auto, "common_band": list(self.common_band),
                "level_window_factor": LEVEL_HALF_WIDTH, "v_m_per_s": self.v.tolist(),
                "C_x_at_omega_m2s": self.C_at_omega.tolist(), "ln_C_err": self.ln_C_err.tolist(),
                "exponent": self.exponent, "exponent_err": self.exponent_err,
                "exponent_err_source": self.exponent_err_source, "gamma": self.gamma.tolist(),
                "gamma_err": self.gamma_err.tolist(), "model_I_alpha2_over_Na": self.level_alpha2_Na.tolist(),
                "model_I_assumption": MODEL_I_ASSUMPTION, "collapse": self.collapse}


def _level(an: DisplacementAnalysis, omega: float) -> tuple:
    """ln C_x at omega and its standard error: from the record model's fit where the record has one
    (:meth:`compare.analysis.record_model.RecordFit.ln_level`, the Fisher information of gamma and A), else from the
    spectrum's points within a factor LEVEL_HALF_WIDTH (below).

    Each point is moved to omega along the record's fitted slope, so the average is not biased by the window's
    asymmetry. A Welch ordinate averaged over ``dof`` chi-square degrees of freedom has E[ln C] = ln C_true +
    psi(dof/2) - ln(dof/2) and var(ln C) = psi'(dof/2) (corrected here); adjacent ordinates of a Hann window overlap,
    so half the points count as independent.
    """
    from scipy.special import digamma, polygamma

    if hasattr(an.fit, "ln_level") and an.fit.level_cov:
        return an.fit.ln_level(omega)
    spec = an.C_x
    m = (spec.omega >= omega / LEVEL_HALF_WIDTH) & (spec.omega <= omega * LEVEL_HALF_WIDTH)
    if not m.any():
        raise ValueError(f"no point of the spectrum lies within a factor {LEVEL_HALF_WIDTH:.3g} of omega = {omega:g} rad/s")
    nu = np.asarray(spec.dof * spec.n_avg[m], float)
    lnC = np.log(spec.C[m]) + an.fit.gamma * np.log(spec.omega[m] / omega) - (digamma(nu / 2) - np.log(nu / 2))
    k_indep = max(1.0, m.sum() / 2.0)
    return float(np.mean(lnC)), float(np.sqrt(np.mean(polygamma(1, nu / 2)) / k_indep))


def _exponent(lnv, y, s) -> tuple:
    """Weighted least squares y = a + b ln v with errors s; the 95 % half-width of b and which error it rests on."""
    from scipy import stats

    n = len(y)
    X = np.column_stack([np.ones(n), lnv])
    W = 1.0 / s**2
    cov = np.linalg.inv(X.T @ (X * W[:, None]))
    a, b = cov @ (X.T @ (W * y))
    chi2 = float(np.sum(W * (y - a - b * lnv) ** 2))
    dof = n - 2
    if dof > 0 and stats.chi2.sf(chi2, dof) < 0.05:  # the per-record errors do not explain the scatter
        return float(b), float(stats.t.ppf(0.975, dof) * np.sqrt(cov[1, 1] * chi2 / dof)), "residual scatter"
    return float(b), float(stats.norm.ppf(0.975) * np.sqrt(cov[1, 1])), "per-record"


def _best_omega(analyses: list, lo: float, hi: float) -> float:
    """The frequency of the comparison: inside the band every record's power law holds (lo-hi), where the least
    precise record's level is most precise (the smallest largest standard error of ln C_x over a log grid of 200);
    the geometric centre of the band for fits without a level covariance."""
    grid = np.geomspace(lo, hi, 200)
    if not all(hasattr(a.fit, "ln_level") and a.fit.level_cov for a in analyses):
        return float(np.sqrt(lo * hi))
    worst = [max(a.fit.ln_level(w)[1] for a in analyses) for w in grid]
    return float(grid[int(np.argmin(worst))])


def velocity_series(analyses: list, omega: float | None = None) -> VelocitySeries:
    """C_x at one omega against v over several records, the exponent, the q = omega / v collapse, model I's level.

    Parameters
    ----------
    analyses : list of DisplacementAnalysis
        Two or more records (:func:`compare.analysis.displacement.analyze_displacement`) at different speeds.
    omega : float, optional
        Angular frequency (rad/s) of the comparison; default: inside the band common to every record's fit band
        (an error if the bands do not overlap), where the least precise record's level is most precise
        (:func:`_best_omega`; the band's geometric centre for fits of a binned spectrum).

    Returns
    -------
    VelocitySeries
    """
    if len(analyses) < 2:
        raise ValueError("a velocity series needs two or more records at different speeds")
    v = np.array([a.mean_velocity for a in analyses])
    if np.any(v <= 0) or len(np.unique(v)) < 2:
        raise ValueError(f"the records' mean speeds must be positive and not all equal (got {', '.join(f'{x:.4g}' for x in v)} m/s)")
    lo = max(a.fit.band[0] for a in analyses)
    hi = min(a.fit.band[1] for a in analyses)
    auto = omega is None
    if auto:
        if not hi > lo:
            raise ValueError(f"the records' fit bands do not overlap (common band {lo:.4g}-{hi:.4g} rad/s): give --omega "
                             "inside every record's spectrum")
        omega = _best_omega(analyses, lo, hi)
    elif not (np.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be a positive angular frequency in rad/s (got {omega})")
    levels = np.array([_level(a, omega) for a in analyses])
    b, err, source = _exponent(np.log(v), levels[:, 0], levels[:, 1])
    runs = [{"v": float(x), "omega": a.C_x.omega, "C": a.C_x.C} for x, a in zip(v, analyses)]
    col = velocity_analysis(runs, omega_ref=(omega / LEVEL_HALF_WIDTH, omega * LEVEL_HALF_WIDTH))
    collapse = {k: col[k] for k in ("spread_frequency_domain", "frequency_range", "spread_distance_domain", "q_range",
                                    "collapse_gain")}
    level = []
    for x, a in zip(v, analyses):
        m = (a.C_x.omega >= a.fit.band[0]) & (a.C_x.omega <= a.fit.band[1])
        level.append(float(np.exp(np.mean(np.log(12 * np.pi * a.C_x.omega[m] ** 4 * a.C_x.C[m] / x**3)))))
    return VelocitySeries(omega=float(omega), omega_auto=auto, common_band=(float(lo), float(hi)), v=v,
                          C_at_omega=np.exp(levels[:, 0]), ln_C_err=levels[:, 1], exponent=b, exponent_err=err,
                          exponent_err_source=source, level_alpha2_Na=np.array(level),
                          gamma=np.array([a.fit.gamma for a in analyses]),
                          gamma_err=np.array([a.fit.gamma_err for a in analyses]), collapse=collapse)
