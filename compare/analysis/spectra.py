"""Power spectra in the convention of Xu, Zhou & Persson (Soft Matter 21, 7594, 2025).

Convention (eq. 2): two-sided in angular frequency,

.. math:: C_x(\\omega) = \\frac{1}{2\\pi}\\int dt\\, \\langle\\zeta(t)\\zeta(0)\\rangle e^{i\\omega t},

so that :math:`\\zeta_{rms}^2 = 2\\int_0^\\infty C_x\\, d\\omega` (eq. 4). From a one-sided PSD
``S(f)`` in units^2/Hz (``scipy.signal.welch``), ``C(omega) = S(f) / (4 pi)``.

Steep spectra leak through any finite window (a Hann Welch estimate reads a true omega^-6 as about
omega^-6.4). The estimator therefore pre-whitens: it differences the series ``k`` times, so the
differenced spectrum is roughly flat, estimates that with Welch/Hann, and divides by the exact
transfer function of the difference operator, ``|2 sin(omega dt / 2) / dt|^(2k)``.

Everything here is pure numerics: no files, no plots.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

__all__ = [
    "Spectrum",
    "displacement_spectrum",
    "series_spectrum",
    "force_series_spectrum",
    "force_spectrum",
    "friction_coefficient_spectrum",
    "rms_from_spectrum",
    "log_bin",
    "rescaled",
    "band_average",
    "average_spectra",
    "G_STANDARD",
]

from frictionnoise.base import G as G_STANDARD  # noqa: E402  (m/s^2, the paper's g, defined once)
from .estimators import as_series as _as_series, default_nperseg as _default_nperseg, welch_dof as _welch_dof  # noqa: E402
from .prewhitening import (  # noqa: E402
    checked_order, detrended, periodogram_recoloured, prewhitening_order, welch_recoloured,
)


@dataclass(frozen=True)
class Spectrum:
    """A one-sided array of a two-sided spectrum, C(omega) for omega > 0 (eq. 2 convention).

    Attributes
    ----------
    omega : ndarray
        Angular frequencies (Units: rad/s), increasing, all > 0.
    C : ndarray
        Spectral density (Units: ``unit``; m^2 s for displacement, N^2 s for force).
    quantity : str
        What the spectrum is of: ``"x"``, ``"F"``, ``"mu"`` or a user label.
    unit : str
        Unit of ``C``.
    n_avg : ndarray
        Number of raw Welch ordinates averaged into each point (1 for a raw spectrum).
    dof : float
        Equivalent chi-square degrees of freedom of one raw Welch ordinate.
    provenance : dict
        How the spectrum was made (the processing chain, every parameter that mattered).
    periodogram : ndarray or None
        The raw (rectangular-window) periodogram of the k-times differenced series, re-coloured by
        ``|2 sin(omega dt/2)/dt|^-2k`` and in the same units and convention as ``C``, on the grid
        ``omega_j = j * periodogram_domega`` (j = 1, 2, ...). The Whittle fit in :mod:`compare.fits`
        uses it; ``None`` for spectra built from binned or stored data.
    periodogram_domega : float
        Frequency step of ``periodogram`` (Units: rad/s).
    periodogram_count : int
        Number of independent raw periodograms averaged into ``periodogram`` (e.g. strokes); each ordinate
        is then a chi-square with ``2 * periodogram_count`` degrees of freedom.
    """

    omega: np.ndarray
    C: np.ndarray
    quantity: str
    unit: str
    n_avg: np.ndarray
    dof: float
    provenance: dict = field(default_factory=dict)
    periodogram: np.ndarray | None = field(default=None, repr=False, compare=False)
    periodogram_domega: float = 0.0
    periodogram_count: int = 1

    @property
    def periodogram_omega(self) -> np.ndarray | None:
        """Frequencies of :attr:`periodogram` (Units: rad/s), or None."""
        if self.periodogram is None:
            return None
        return self.periodogram_domega * np.arange(1, len(self.periodogram) + 1)

    @property
    def omega_min(self) -> float:
        return float(self.omega[0])

    @property
    def omega_max(self) -> float:
        return float(self.omega[-1])

    def __len__(self) -> int:
        return len(self.omega)


def series_spectrum(
    t,
    y,
    *,
    quantity: str = "y",
    unit: str = "",
    detrend: str = "constant",
    prewhiten: int | str = "auto",
    nperseg: int | None = None,
    name: str = "y",
) -> Spectrum:
    """Spectrum of a uniformly sampled series in the eq. (2) convention, with pre-whitening.

    Parameters
    ----------
    t, y : array_like
        Uniform sample times (Units: s) and values.
    detrend : {"linear", "constant", "none"}
        What is removed from ``y`` before estimation. ``"linear"`` fits and removes ``y0 + v t``
        (``v`` is recorded); ``"constant"`` removes the mean.
    prewhiten : int or "auto"
        Number ``k`` of differences taken before the Welch estimate; the estimate is then divided
        by ``|2 sin(omega dt/2)/dt|^(2k)``, which is exact for the difference filter. ``"auto"``
        picks ``k = round(gamma_pilot / 2)`` from a pilot slope estimate.
    nperseg : int, optional
        Welch segment length in samples (default: about 16 half-overlapping segments).
    quantity, unit : str
        What the spectrum is of and the unit of its ``C`` (e.g. "x", "m^2 s"), recorded on the result.
    name : str
        The series' name in error messages and in the provenance.

    Returns
    -------
    Spectrum
        C(omega) for omega > 0 (Units: rad/s), two-sided in angular frequency (eq. 2), with the raw
        periodogram for the Whittle fit and ``provenance`` (the processing chain).
    """
    t, y, dt = _as_series(t, y, name)
    n = len(y)
    if nperseg is None:
        nperseg = _default_nperseg(n)
    nperseg = int(nperseg)
    if nperseg < 8:
        raise ValueError(f"nperseg = {nperseg} is too short (at least 8 samples)")
    if nperseg > n:
        raise ValueError(f"only {n} samples, fewer than one segment (nperseg = {nperseg})")

    steps = []
    z, v = detrended(t, y, detrend, quantity, name, steps)
    k, pilot, auto = prewhitening_order(prewhiten, z, dt, steps)
    nperseg0 = nperseg
    zk, nperseg, n_segments, omega, C = welch_recoloured(z, dt, nperseg0, k)
    if auto:
        k, (zk, nperseg, n_segments, omega, C) = checked_order(z, dt, nperseg0, k, (zk, nperseg, n_segments, omega, C),
                                                               steps)
    if k:
        steps.append(f"differenced {k}x (divided by dt^{k})")
    steps.append(f"Welch: Hann window, nperseg = {nperseg}, 50 % overlap, {n_segments} segments")
    steps.append("C(omega) = S(f) / (4 pi)  [eq. (2) convention]")
    if k:
        steps.append(f"re-coloured by |2 sin(omega dt/2)/dt|^-{2 * k}")
    d_omega, P = periodogram_recoloured(zk, dt, k, steps)

    provenance = {
        "quantity": quantity,
        "n_samples": n,
        "dt": dt,
        "duration": float(t[-1] - t[0]),
        "detrend": detrend,
        "mean_velocity": float(v),
        "window": "hann",
        "nperseg": nperseg,
        "noverlap": nperseg // 2,
        "n_segments": int(n_segments),
        "prewhiten_order": k,
        "prewhiten_auto": auto,
        "pilot_gamma": pilot,
        "steps": steps,
    }
    return Spectrum(
        omega=omega, C=C, quantity=quantity, unit=unit, n_avg=np.ones(len(omega), dtype=int),
        dof=_welch_dof(n_segments), provenance=provenance, periodogram=P, periodogram_domega=d_omega,
    )


def displacement_spectrum(t, x, *, detrend: str = "linear", prewhiten: int | str = "auto",
                          nperseg: int | None = None) -> Spectrum:
    """C_x(omega) of the noise zeta = x - (x0 + v t), eq. (2), with v fitted.

    Parameters
    ----------
    t : array_like
        Uniform sample times (Units: s).
    x : array_like
        Positions (Units: m).
    detrend, prewhiten, nperseg
        As in :func:`series_spectrum` (default: the linear trend v t removed, pre-whitening chosen from a pilot
        slope).

    Returns
    -------
    Spectrum
        C_x (Units: m^2 s) against omega (Units: rad/s); ``provenance["mean_velocity"]`` is the fitted v (m/s).
    """
    return series_spectrum(t, x, quantity="x", unit="m^2 s", detrend=detrend, prewhiten=prewhiten,
                           nperseg=nperseg, name="x")


def force_series_spectrum(t, F, *, prewhiten: int | str = "auto", nperseg: int | None = None) -> Spectrum:
    """C_F(omega) of a recorded force series F(t), mean removed, eq. (2) convention.

    Parameters
    ----------
    t : array_like
        Uniform sample times (Units: s).
    F : array_like
        Forces (Units: N).
    prewhiten, nperseg
        As in :func:`series_spectrum`.

    Returns
    -------
    Spectrum
        C_F (Units: N^2 s) against omega (Units: rad/s).
    """
    return series_spectrum(t, F, quantity="F", unit="N^2 s", detrend="constant", prewhiten=prewhiten,
                           nperseg=nperseg, name="F")


def rescaled(spec: Spectrum, factor, quantity: str, unit: str, step: str) -> Spectrum:
    """Multiply C (and the raw periodogram) by ``factor(omega)``."""
    prov = dict(spec.provenance)
    prov["steps"] = list(prov.get("steps", [])) + [step]
    prov["quantity"] = quantity
    P = None if spec.periodogram is None else spec.periodogram * factor(spec.periodogram_omega)
    return replace(spec, C=spec.C * factor(spec.omega), quantity=quantity, unit=unit, provenance=prov, periodogram=P)


def force_spectrum(spectrum: Spectrum, mass: float) -> Spectrum:
    """C_F = M^2 omega^4 C_x, eq. (3): the force spectrum of a free block (inertial relation).

    Parameters
    ----------
    spectrum : Spectrum
        A displacement spectrum (``quantity == "x"``, m^2 s).
    mass : float
        The block mass M (Units: kg).

    Returns
    -------
    Spectrum
        C_F (Units: N^2 s) on the same frequencies.
    """
    if spectrum.quantity != "x":
        raise ValueError(f"force_spectrum needs a displacement spectrum (got quantity {spectrum.quantity!r})")
    if not mass > 0:
        raise ValueError(f"mass must be positive (got {mass!r})")
    return rescaled(spectrum, lambda w: mass**2 * w**4, "F", "N^2 s",
                     f"C_F = M^2 omega^4 C_x with M = {mass:g} kg  [eq. (3)]")


def friction_coefficient_spectrum(spectrum: Spectrum, g: float = G_STANDARD) -> Spectrum:
    """C_mu = omega^4 C_x / g^2 (paper section 2), the friction coefficient's spectrum.

    Parameters
    ----------
    spectrum : Spectrum
        A displacement spectrum (``quantity == "x"``, m^2 s).
    g : float, optional
        Gravitational acceleration (Units: m/s^2).

    Returns
    -------
    Spectrum
        C_mu (Units: s) on the same frequencies.
    """
    if spectrum.quantity != "x":
        raise ValueError(
            f"friction_coefficient_spectrum needs a displacement spectrum (got quantity {spectrum.quantity!r})"
        )
    return rescaled(spectrum, lambda w: w**4 / g**2, "mu", "s",
                     f"C_mu = omega^4 C_x / g^2 with g = {g:g} m/s^2  [section 2]")


def check_band(spectrum: Spectrum, band) -> tuple[float, float]:
    """(low, high) of a frequency band (rad/s) inside the spectrum's resolved range, or ValueError."""
    lo, hi = map(float, band)
    if not 0 < lo < hi:
        raise ValueError(f"band must satisfy 0 < low < high (got {band!r})")
    below, above = lo < spectrum.omega_min * (1 - 1e-9), hi > spectrum.omega_max * (1 + 1e-9)
    if below or above:
        where = ("it lies wholly outside" if lo >= spectrum.omega_max or hi <= spectrum.omega_min else
                 "it reaches beyond both ends of" if below and above else
                 "its low end lies below" if below else "its high end lies above")
        raise ValueError(f"band ({lo:.4g}, {hi:.4g}) rad/s: {where} the resolved range ({spectrum.omega_min:.4g}, "
                         f"{spectrum.omega_max:.4g}) rad/s (from the record's segment length to its Nyquist frequency)")
    return lo, hi


def _band_mask(spectrum: Spectrum, band) -> np.ndarray:
    if band is None:
        return np.ones(len(spectrum.omega), dtype=bool)
    lo, hi = check_band(spectrum, band)
    mask = (spectrum.omega >= lo) & (spectrum.omega <= hi)
    if mask.sum() < 2:
        raise ValueError(f"band ({lo:.4g}, {hi:.4g}) rad/s holds fewer than two spectral ordinates")
    return mask


def rms_from_spectrum(spectrum: Spectrum, band=None) -> float:
    """sqrt(2 Int C domega) over a band, eq. (4).

    For an un-binned spectrum each ordinate stands for a frequency cell of width d_omega (rectangle rule, which is
    what Parseval's theorem sums); a log-binned spectrum is integrated by trapezoids.

    Parameters
    ----------
    spectrum : Spectrum
        Any spectrum in the eq. (2) convention.
    band : tuple of float, optional
        (low, high) (Units: rad/s); default all resolved frequencies.

    Returns
    -------
    float
        The rms (Units: the square root of the spectrum's unit over s, e.g. m for C_x).
    """
    mask = _band_mask(spectrum, band)
    om, C = spectrum.omega[mask], spectrum.C[mask]
    if np.all(spectrum.n_avg == 1) and len(spectrum.omega) > 1:
        d_omega = spectrum.omega[1] - spectrum.omega[0]
        integral = float(np.sum(C) * d_omega)
    else:
        integral = float(np.trapezoid(C, om))
    return math.sqrt(2.0 * integral)


def log_bin(spectrum: Spectrum, bins_per_decade: int = 10, band=None) -> Spectrum:
    """Average a spectrum in logarithmic frequency bins.

    Each bin's ``C`` is the arithmetic mean of its ordinates (an unbiased level); its ``omega`` is the geometric
    mean of the members' frequencies. ``n_avg`` counts the members. ``provenance`` gains ``log_mean_C``: the mean
    of ln C over each bin, which for a power law sits exactly on the line at the bin's geometric-mean frequency
    (the least-squares fit in :mod:`compare.fits` uses it).

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum to bin.
    bins_per_decade : int, optional
        Number of bins per decade of frequency.
    band : tuple of float, optional
        (low, high) (Units: rad/s) to bin; default all.

    Returns
    -------
    Spectrum
        The binned spectrum (same units).
    """
    if bins_per_decade < 1:
        raise ValueError(f"bins_per_decade must be >= 1 (got {bins_per_decade})")
    mask = _band_mask(spectrum, band)
    om, C, w = spectrum.omega[mask], spectrum.C[mask], spectrum.n_avg[mask]
    pos = C > 0
    om, C, w = om[pos], C[pos], w[pos]
    if len(om) == 0:
        raise ValueError("spectrum has no positive ordinates to bin")
    edges_log = np.arange(math.floor(np.log10(om[0]) * bins_per_decade),
                          math.ceil(np.log10(om[-1]) * bins_per_decade) + 2) / bins_per_decade
    idx = np.digitize(np.log10(om), edges_log) - 1
    uniq, inv, counts = np.unique(idx, return_inverse=True, return_counts=True)
    wsum = np.bincount(inv, weights=w)
    omega_b = np.exp(np.bincount(inv, weights=w * np.log(om)) / wsum)
    C_b = np.bincount(inv, weights=w * C) / wsum
    logC_b = np.bincount(inv, weights=w * np.log(C)) / wsum
    n_b = np.bincount(inv, weights=w).astype(int)
    prov = dict(spectrum.provenance)
    prov["steps"] = list(prov.get("steps", [])) + [f"log-binned, {bins_per_decade} bins per decade"]
    prov["log_mean_C"] = logC_b
    prov["bins_per_decade"] = bins_per_decade
    return replace(spectrum, omega=omega_b, C=C_b, n_avg=n_b, provenance=prov)


def band_average(spectrum: Spectrum, edges, values=None) -> np.ndarray:
    """Mean of ``values`` (default ``spectrum.C``) over the ordinates inside each band [edges[i], edges[i+1]).

    Evaluate a theory on ``spectrum.omega`` and pass it as ``values`` to average it over exactly the same
    ordinates, so per-band ratios carry no binning bias.

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum whose frequencies define the ordinates.
    edges : array_like
        Band edges (Units: rad/s), increasing.
    values : array_like, optional
        Values on ``spectrum.omega`` (e.g. a closed form); default ``spectrum.C``.

    Returns
    -------
    numpy.ndarray
        One mean per band (the unit of ``values``).
    """
    edges = np.asarray(edges, dtype=float)
    vals = spectrum.C if values is None else np.asarray(values, dtype=float)
    if vals.shape != spectrum.omega.shape:
        raise ValueError(f"values has shape {vals.shape}, spectrum has {spectrum.omega.shape}")
    out = np.empty(len(edges) - 1)
    for i in range(len(edges) - 1):
        m = (spectrum.omega >= edges[i]) & (spectrum.omega < edges[i + 1])
        if not m.any():
            raise ValueError(f"band [{edges[i]:.4g}, {edges[i + 1]:.4g}) rad/s holds no spectral ordinate")
        out[i] = np.sum(vals[m] * spectrum.n_avg[m]) / np.sum(spectrum.n_avg[m])
    return out


def average_spectra(spectra, *, label: str = "records") -> Spectrum:
    """Mean of spectra of equally long, equally processed records (e.g. the strokes of a reciprocating test).

    All must share the frequency grid (same dt, length, nperseg and pre-whitening order). The Welch
    ordinates and the raw periodograms are averaged; the degrees of freedom add up, and
    ``periodogram_count`` counts the averaged records (the Whittle fit uses it).
    """
    spectra = list(spectra)
    if not spectra:
        raise ValueError("no spectra to average")
    first = spectra[0]
    for s in spectra[1:]:
        if s.omega.shape != first.omega.shape or not np.allclose(s.omega, first.omega, rtol=1e-9, atol=0):
            raise ValueError("spectra to average must share the frequency grid (same dt, length and nperseg)")
        if s.provenance.get("prewhiten_order") != first.provenance.get("prewhiten_order"):
            raise ValueError("spectra to average must share the pre-whitening order")
    m = len(spectra)
    C = np.mean([s.C for s in spectra], axis=0)
    P = None
    if all(s.periodogram is not None for s in spectra) and len({len(s.periodogram) for s in spectra}) == 1:
        P = np.mean([s.periodogram for s in spectra], axis=0)
    prov = dict(first.provenance)
    prov["steps"] = list(prov.get("steps", [])) + [f"averaged over {m} {label}"]
    prov["n_records"] = m
    return replace(first, C=C, dof=first.dof * m, provenance=prov, periodogram=P,
                   periodogram_count=sum(s.periodogram_count for s in spectra) if P is not None else 1)
