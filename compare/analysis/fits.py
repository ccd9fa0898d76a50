"""Power-law fits C(omega) = A omega^-gamma to spectra, with an honest uncertainty.

Two methods share the band rules below; ``method="whittle"`` is the default (:data:`DEFAULT_METHOD`), chosen from
``python -m compare.studies.fit_methods`` (README, "Exponent fits": over 500 seeds of omega^-2, -4, -5, -6 at 2^14-2^18
samples it met |bias| < 0.02 and 93-97 % coverage in all 12 rows, least squares in 10, with an interval 8-16 %
narrower).

Whittle
-------
The raw periodogram of the k-times differenced series, re-coloured by |2 sin(omega dt/2)/dt|^-2k
(``Spectrum.periodogram``), is fitted by maximum Whittle likelihood: each ordinate is exponential with mean
A omega^-gamma (a mean of K when K periodograms were averaged). A is profiled out; ``gamma_se`` is the inverse
square root of the observed Fisher information of the profile (divided by sqrt(K)), ``gamma_err = 1.96 gamma_se``.

Least squares (``method="lsq"``)
--------------------------------
The spectrum is log-binned (10 bins per decade by default). Each bin carries the mean of ln C over
its raw Welch ordinates and the geometric-mean frequency; for a power law that point lies exactly on
the line, and the chi-square bias of E[ln C_hat] (digamma(nu/2) - ln(nu/2)) is the same for every raw
ordinate, so it shifts the prefactor, not the slope. A weighted least-squares line (weights = number of
raw ordinates in the bin) is fitted to (ln omega, mean ln C).

Uncertainty: ``gamma_se`` is the standard error of the slope: the larger of (a) the value from the
scatter of the binned ordinates about the line (the residual variance, so curvature or extra noise
widen it) and (b) the value expected from the Welch chi-square scatter alone (a floor against a run
of ordinates that happen to scatter little). ``gamma_err`` is the
half-width of the 95 % confidence interval, ``t_{0.975, n-2} * gamma_se``. Its coverage over 500 seeds of
synthetic power laws: docs/results/exponent_fits.md (``python -m compare.studies.fit_methods``).

Not a power law
---------------
``flags`` (and ``power_law = False``) mark a band narrower than a decade, and a quadratic term in ln omega
significant at 95 %: a score test on the band's raw periodogram ordinates at the Whittle fit (standard normal
under the power law), or, for a spectrum without a raw periodogram, a weighted quadratic fit to the binned
ordinates with their known variance.

Automatic band: within [4 d_omega, omega_Nyquist / 16] (below, the Hann main lobe of the lowest ordinates;
above, aliasing of the sampled series bends steep spectra: a sampled omega^-2k process is flatter than
the continuous one by about k u^2/6 in local slope at u = omega dt, 0.03 at k = 3 and omega_N/16), the widest contiguous run of bins spanning at
least ``min_decades`` whose fit has a reduced chi-square consistent with the expected Welch scatter
(within 3 sigma of the chi-square distribution) is chosen; ties go to the smaller chi-square.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import special, stats

from .spectra import Spectrum, check_band, log_bin

__all__ = ["PowerLawFit", "fit_power_law", "flag_mark", "METHODS", "DEFAULT_METHOD"]

# Adjacent raw Hann ordinates are correlated: the power correlation of neighbours is (2/3)^2 = 0.444 and
# of next neighbours (1/6)^2 = 0.028, so the variance of a mean of m neighbours is inflated by
# 1 + 2 (0.444 + 0.028) = 1.94 over m independent ordinates.
_HANN_NEIGHBOUR_INFLATION = 1.94
_CURVATURE_Z = float(stats.norm.ppf(0.975))  # two-sided 95 % test of the quadratic term
# The binned-ordinate variance model under-predicts the scatter of the quadratic coefficient: over 150 seeds of
# omega^-2 (n = 2^16) its z had a standard deviation of 1.14, so the fallback test (used only for spectra without
# a raw periodogram) inflates the variance by 1.14^2.
_BINNED_CURVATURE_INFLATION = 1.14**2


@dataclass(frozen=True)
class PowerLawFit:
    """Result of :func:`fit_power_law`: C = prefactor * omega^-gamma over ``band``.

    ``gamma_err`` is the 95 % confidence half-width; ``gamma_se`` the 1-sigma standard error.
    ``prefactor`` has units of C times (rad/s)^gamma.
    """

    gamma: float
    gamma_err: float
    prefactor: float
    band: tuple[float, float]
    gamma_se: float
    n_points: int
    chi2_red: float
    band_auto: bool
    quantity: str = "x"
    notes: list = field(default_factory=list)
    method: str = "lsq"
    flags: tuple = ()
    curvature: float = 0.0
    curvature_z: float = 0.0

    @property
    def power_law(self) -> bool:
        """False when a flag says the spectrum is not a power law over the band (see ``flags``)."""
        return not self.flags

    def level(self, omega):
        """The fitted line, prefactor * omega^-gamma.

        Parameters
        ----------
        omega : array_like
            Angular frequencies (Units: rad/s).

        Returns
        -------
        numpy.ndarray
            The line's level at ``omega`` (the fitted spectrum's unit).
        """
        return self.prefactor * np.asarray(omega, dtype=float) ** (-self.gamma)

    def to_dict(self) -> dict:
        """JSON-ready: the keys ``gamma``, ``gamma_err``, ``band`` plus the rest.

        Returns
        -------
        dict
            Every field (arrays as lists), and ``power_law``.
        """
        return {
            "gamma": self.gamma, "gamma_err": self.gamma_err, "band": [self.band[0], self.band[1]],
            "gamma_se": self.gamma_se, "prefactor": self.prefactor, "n_points": self.n_points,
            "chi2_red": self.chi2_red, "band_auto": self.band_auto, "quantity": self.quantity,
            "confidence": 0.95, "method": self.method, "power_law": self.power_law, "flags": list(self.flags),
            "curvature": self.curvature, "curvature_z": self.curvature_z, "notes": list(self.notes),
        }

    def __str__(self) -> str:
        flag = f" [NOT A POWER LAW: {'; '.join(self.flags)}]" if self.flags else ""
        return (f"gamma = {self.gamma:.3f} +- {self.gamma_err:.3f} (95 %, {self.method}) over "
                f"{self.band[0]:.3g}-{self.band[1]:.3g} rad/s{' (auto band)' if self.band_auto else ''}{flag}")


def _wls(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> tuple[float, float, float, np.ndarray]:
    """Weighted least-squares line y = a + b x. Returns (a, b, se_b from residuals, residuals)."""
    W = w.sum()
    xm = np.sum(w * x) / W
    ym = np.sum(w * y) / W
    sxx = np.sum(w * (x - xm) ** 2)
    b = np.sum(w * (x - xm) * (y - ym)) / sxx
    a = ym - b * xm
    r = y - (a + b * x)
    n = len(x)
    s2 = np.sum(w * r**2) / (n - 2) if n > 2 else np.inf
    return float(a), float(b), float(math.sqrt(s2 / sxx)), r


def _binned(spectrum: Spectrum, bins_per_decade: int):
    b = spectrum if "log_mean_C" in spectrum.provenance else log_bin(spectrum, bins_per_decade)
    logC = np.asarray(b.provenance.get("log_mean_C", np.log(b.C)))
    # Expected variance of one raw ln C ordinate: trigamma(nu/2) for a chi-square with nu dof.
    var_raw = float(special.polygamma(1, b.dof / 2.0))
    var_bin = var_raw * np.where(b.n_avg > 1, _HANN_NEIGHBOUR_INFLATION, 1.0) / b.n_avg
    return b, np.log(b.omega), logC, var_bin


def _auto_band(lnw, lnC, var, w, min_decades):
    n = len(lnw)
    min_span = min_decades * math.log(10)
    best = None  # (span, -chi2, i, j)
    fallback = None
    for i in range(n):
        for j in range(i + 3, n):  # at least 4 points
            span = lnw[j] - lnw[i]
            if span < min_span * 0.999:
                continue
            sl = slice(i, j + 1)
            a, b, _, r = _wls(lnw[sl], lnC[sl], w[sl])
            dof = j - i + 1 - 2
            chi2 = float(np.sum(r**2 / var[sl]) / dof)
            limit = 1.0 + 3.0 * math.sqrt(2.0 / dof)
            if chi2 <= limit:
                key = (round(span, 6), -chi2)
                if best is None or key > best[0]:
                    best = (key, i, j)
            if abs(span - min_span) < math.log(10) / 8 or span < min_span * 1.2:
                if fallback is None or chi2 < fallback[0]:
                    fallback = (chi2, i, j)
    if best is not None:
        return best[1], best[2], True
    if fallback is not None:
        return fallback[1], fallback[2], False
    return 0, n - 1, False


METHODS = ("whittle", "lsq")
DEFAULT_METHOD = "whittle"  # chosen from the table of docs/results/exponent_fits.md (compare.studies.fit_methods)


def _whittle_gamma(lnw: np.ndarray, P: np.ndarray) -> tuple[float, float, float, int]:
    """Whittle maximum-likelihood fit of P_j ~ A omega_j^-gamma * Exp(1) over the given raw ordinates.

    With u = ln omega - mean(ln omega), the negative log-likelihood sum(ln S + P/S) profiled over A
    (A_hat = mean(P omega^gamma)) is f(gamma) = m ln mean(P e^{gamma u}) - gamma sum(u) + const, strictly
    convex (f'' = m Var_w(u) with weights w ~ P e^{gamma u}), so Newton's method from the log-periodogram
    slope converges. Returns (gamma, se, ln A, iterations); se = f''(gamma_hat)^-1/2 is the observed
    Fisher information of the profile (Whittle 1953; each ordinate of an Exp(1) has unit score variance).
    """
    m = len(P)
    lnP = np.log(P)
    mu = lnw.mean()
    u = lnw - mu
    suu = float(np.sum(u * u))
    g = -float(np.sum(u * (lnP - lnP.mean())) / suu)  # start: the log-periodogram regression
    it = 0
    for it in range(1, 60):
        z = lnP + g * u
        w = np.exp(z - z.max())
        w /= w.sum()
        Eu = float(np.sum(w * u))
        Vu = float(np.sum(w * (u - Eu) ** 2))
        step = Eu / max(Vu, 1e-300)  # f'/f'' with f' = m E_w[u], f'' = m Var_w[u]
        step = float(np.clip(step, -1.0, 1.0))
        g -= step
        if abs(step) < 1e-10:
            break
    z = lnP + g * u
    zmax = z.max()
    w = np.exp(z - zmax)
    lnA = float(zmax + math.log(w.sum() / m) + g * mu)  # ln mean(P omega^gamma)
    w /= w.sum()
    Eu = float(np.sum(w * u))
    Vu = float(np.sum(w * (u - Eu) ** 2))
    return g, 1.0 / math.sqrt(m * Vu), lnA, it


def _curvature_test(lnw: np.ndarray, lnC: np.ndarray, var: np.ndarray) -> tuple[float, float]:
    """Quadratic term of ln C against ln omega, weighted by the known variance of the averaged ordinates.

    Fits ln C = a + b u + c u^2 (u centred ln omega) by weighted least squares with weights 1/var, var the
    expected variance of each bin's mean ln C (trigamma of the Welch dof over the bin's ordinates, with
    the Hann neighbour inflation). Returns (c, z = c / se_c); se_c from the known variances, so |z| > 1.96
    is significant at 95 % (two-sided) under a pure power law.
    """
    if len(lnw) < 4:
        return 0.0, 0.0
    var = var * _BINNED_CURVATURE_INFLATION
    u = lnw - np.average(lnw, weights=1.0 / var)
    X = np.column_stack([np.ones_like(u), u, u * u])
    Wt = 1.0 / var
    XtWX = X.T @ (X * Wt[:, None])
    cov = np.linalg.inv(XtWX)
    coef = cov @ (X.T @ (Wt * lnC))
    c = float(coef[2])
    return c, c / math.sqrt(float(cov[2, 2]))


def _curvature_score(lnw: np.ndarray, P: np.ndarray, gamma: float, lnA: float, count: int) -> tuple[float, float]:
    """Score test of a quadratic term in ln S(omega) at the Whittle fit (raw periodogram ordinates).

    Under the power law each ratio r_j = P_j / (A omega_j^-gamma) is a mean of ``count`` independent Exp(1)
    variables (variance 1/count). With q the square of the centred ln omega, made orthogonal to (1, u), the
    score of the quadratic coefficient is sum (r_j - 1) q_j, of variance sum q_j^2 / count: z is standard
    normal under a pure power law. Returns (c, z) with c = sum (r - 1) q / sum q^2 the one-step estimate of
    the quadratic coefficient (per (ln omega)^2).
    """
    u = lnw - lnw.mean()
    q = u * u
    X = np.column_stack([np.ones_like(u), u])
    q = q - X @ np.linalg.lstsq(X, q, rcond=None)[0]
    r = P * np.exp(gamma * lnw - lnA)
    sqq = float(np.sum(q * q))
    if sqq <= 0:
        return 0.0, 0.0
    score = float(np.sum((r - 1.0) * q))
    return score / sqq, score / math.sqrt(sqq / count)


def _given_band(spectrum: Spectrum, band, bins_per_decade: int):
    """(lo, hi, log bins, ln omega, ln C, var, first bin, last bin) of a band the caller gives (rad/s)."""
    lo, hi = check_band(spectrum, band)
    b, lnw, lnC, var = _binned(spectrum, bins_per_decade)
    keep = (b.omega >= lo) & (b.omega <= hi)
    if keep.sum() < 3:
        raise ValueError(f"band ({lo:.4g}, {hi:.4g}) rad/s holds fewer than 3 log bins; widen it")
    return lo, hi, b, lnw, lnC, var, int(np.argmax(keep)), int(len(keep) - 1 - np.argmax(keep[::-1]))


def _automatic_band(spectrum: Spectrum, bins_per_decade: int, min_decades: float, notes: list):
    """(lo, hi, log bins, ln omega, ln C, var, first bin, last bin) of the straightest band of ``min_decades``
    between 4 frequency steps and a sixteenth of the Nyquist frequency (rad/s); what it had to give up goes to
    ``notes``."""
    raw_step = spectrum.omega[0] if np.all(spectrum.n_avg == 1) else spectrum.omega_min
    dt = spectrum.provenance.get("dt")
    top = math.pi / dt / 16 if dt else spectrum.omega_max
    lo, hi = 4 * raw_step, min(top, spectrum.omega_max)
    if hi <= lo * 1.5:
        raise ValueError(
            f"too few resolved frequencies for an automatic band ({lo:.4g}-{hi:.4g} rad/s); "
            "use a longer record, or fit the whole record by the record model (analyze's default for displacement, "
            "compare.analysis.record_model.fit_record)"
        )
    b, lnw, lnC, var = _binned(spectrum, bins_per_decade)
    inside = (b.omega >= lo) & (b.omega <= hi)
    idx = np.flatnonzero(inside)
    avail = (lnw[idx[-1]] - lnw[idx[0]]) / math.log(10) if len(idx) > 1 else 0.0
    if len(idx) < 4:
        raise ValueError("too few log bins for an automatic band; give the band (band=, --band LO HI)")
    md = min(min_decades, avail)
    if md < min_decades:
        # no width here: the band's own width (from its end ordinates) is the one the flag states
        notes.append(f"under a decade lies between 4 Welch frequency steps and a sixteenth of the Nyquist frequency "
                     f"({lo:.3g}-{hi:.3g} rad/s); fitted over all of it")
    ii, jj, ok = _auto_band(lnw[idx], lnC[idx], var[idx], b.n_avg[idx].astype(float), md)
    if not ok:
        notes.append("no band of the requested width is a straight power law within its scatter; "
                     "reporting the straightest one")
    return lo, hi, b, lnw, lnC, var, int(idx[ii]), int(idx[jj])


def fit_power_law(spectrum: Spectrum, band=None, *, bins_per_decade: int = 10,
                  min_decades: float = 1.0, method: str | None = None) -> PowerLawFit:
    """Fit C(omega) = A omega^-gamma over a band, or over an automatically chosen one.

    ``method``: ``"lsq"`` (weighted least squares on log-binned Welch ordinates) or ``"whittle"`` (Whittle
    likelihood on the raw periodogram of the pre-whitened series; needs a spectrum from
    :func:`compare.spectra.series_spectrum` or its wrappers). ``None`` takes :data:`DEFAULT_METHOD`, falling
    back to ``"lsq"`` (with a note) for a spectrum that carries no raw periodogram. See the module docstring
    for both methods, the band rules and the meaning of the uncertainty. The fit carries ``flags`` when the
    band spans less than a decade or the log-log residuals curve significantly (``power_law`` is then False).

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum to fit (any quantity, eq. 2 convention).
    band : tuple of float, optional
        (low, high) (Units: rad/s); default the widest straight stretch between 4 frequency steps and Nyquist/16.
    bins_per_decade : int, optional
        Log bins per decade (least squares, the automatic band and the curvature test of binned spectra).
    min_decades : float, optional
        The automatic band's least width (decades of frequency).
    method : {"whittle", "lsq"}, optional
        The estimator; default :data:`DEFAULT_METHOD`.

    Returns
    -------
    PowerLawFit
        ``gamma`` (dimensionless), ``gamma_err`` (its 95 % half-width), ``gamma_se`` (1 sigma), ``prefactor`` A
        (the spectrum's unit times (rad/s)^gamma), ``band`` (rad/s), ``flags`` and ``method``.
    """
    notes = []
    if method is None:
        method = DEFAULT_METHOD
        if method == "whittle" and spectrum.periodogram is None:
            method = "lsq"
            notes.append("the spectrum keeps no single raw periodogram (a record in pieces or strokes, or stored "
                         "data), so the Whittle fit cannot apply: fitted by least squares on its log-binned ordinates")
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)} (got {method!r})")
    if method == "whittle" and spectrum.periodogram is None:
        raise ValueError("the Whittle fit needs the raw periodogram, which this spectrum does not carry "
                         "(made from binned or stored data); use method='lsq'")
    if band is not None:
        lo, hi, b, lnw, lnC, var, i, j = _given_band(spectrum, band, bins_per_decade)
    else:
        lo, hi, b, lnw, lnC, var, i, j = _automatic_band(spectrum, bins_per_decade, min_decades, notes)
    auto = band is None
    sl = slice(i, j + 1)
    npts = j - i + 1
    # Least squares on the binned ordinates (also the chi-square that both methods report).
    w = b.n_avg[sl].astype(float)
    a, slope, se, r = _wls(lnw[sl], lnC[sl], w)
    wm = 1.0 / var[sl]
    x_m = np.sum(wm * lnw[sl]) / wm.sum()
    se = max(se, float(math.sqrt(1.0 / np.sum(wm * (lnw[sl] - x_m) ** 2))))
    chi2 = float(np.sum(r**2 / var[sl]) / max(npts - 2, 1))
    band_out = (float(b.omega[i]), float(b.omega[j])) if band is None else (lo, hi)
    # The raw periodogram ordinates of the band (for the Whittle fit, and for the curvature test of both).
    wh = None
    if spectrum.periodogram is not None:
        if band is None:  # the raw ordinates of the chosen bins: half a bin beyond the end bins' centres
            half = 10 ** (0.5 / bins_per_decade)
            wlo, whi = max(band_out[0] / half, lo), min(band_out[1] * half, hi)
        else:
            wlo, whi = lo, hi
        om = spectrum.periodogram_omega
        sel = (om >= wlo * (1 - 1e-12)) & (om <= whi * (1 + 1e-12)) & (spectrum.periodogram > 0)
        if sel.sum() >= 8:
            lnw_raw, P_raw = np.log(om[sel]), spectrum.periodogram[sel]
            g, g_se, lnA, _ = _whittle_gamma(lnw_raw, P_raw)
            # K averaged periodograms: each ordinate is Gamma(K, S/K), the log-likelihood K times the Whittle one.
            wh = (g, g_se / math.sqrt(spectrum.periodogram_count), lnA, (float(om[sel][0]), float(om[sel][-1])),
                  int(sel.sum()))
        elif method == "whittle":
            raise ValueError(f"band ({wlo:.4g}, {whi:.4g}) rad/s holds {int(sel.sum())} periodogram ordinates; "
                             "the Whittle fit needs at least 8")
    if method == "lsq":
        tq = float(stats.t.ppf(0.975, max(npts - 2, 1)))
        # ln C_hat is biased low by digamma(nu/2) - ln(nu/2) for every raw ordinate; undo it in the prefactor.
        bias = float(special.digamma(b.dof / 2.0) - math.log(b.dof / 2.0))
        gamma, gamma_se, gamma_err, prefactor = -slope, se, tq * se, float(math.exp(a - bias))
        n_used = npts
    else:
        gamma, gamma_se, lnA, raw_band, n_used = wh
        if band is None:
            band_out = raw_band  # the first and last raw ordinates used
        gamma_err, prefactor = float(stats.norm.ppf(0.975)) * gamma_se, float(math.exp(lnA))
    flags = []
    decades = math.log10(band_out[1] / band_out[0])
    if decades < 1.0 - 1e-9:
        flags.append(f"band spans {decades:.2f} decades (< 1)")
    if wh is not None:
        curv, curv_z = _curvature_score(lnw_raw, P_raw, wh[0], wh[2], spectrum.periodogram_count)
    else:
        curv, curv_z = _curvature_test(lnw[sl], lnC[sl], var[sl])
    if abs(curv_z) > _CURVATURE_Z:
        flags.append(f"log-log residuals curve (quadratic term {curv:+.3g} per (ln omega)^2, "
                     f"{abs(curv_z):.1f} sigma)")
    return PowerLawFit(
        gamma=gamma, gamma_err=gamma_err, prefactor=prefactor, band=band_out, gamma_se=gamma_se,
        n_points=n_used, chi2_red=chi2, band_auto=auto, quantity=spectrum.quantity, notes=notes,
        method=method, flags=tuple(flags), curvature=curv, curvature_z=curv_z,
    )


def flag_mark(fit) -> str:
    """A short mark for tables and legends: "" for a power law, " (not a power law)" when the fit carries flags
    (a :class:`PowerLawFit` or its ``to_dict()``; the flags themselves are in the JSON and the fit's text)."""
    flags = fit.get("flags") if isinstance(fit, dict) else getattr(fit, "flags", ())
    return " (not a power law)" if flags else ""
