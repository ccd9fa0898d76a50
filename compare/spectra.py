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
from scipy import fft as sp_fft
from scipy import signal

__all__ = [
    "Spectrum",
    "displacement_spectrum",
    "series_spectrum",
    "force_series_spectrum",
    "force_spectrum",
    "friction_coefficient_spectrum",
    "rms_from_spectrum",
    "log_bin",
    "band_average",
    "average_spectra",
    "G_STANDARD",
]

from frictionnoise import G as G_STANDARD  # noqa: E402  (m/s^2, the paper's g, defined once)
_MAX_PREWHITEN = 4
_PILOT_SAMPLES = 1 << 20  # the pilot slope estimate looks at most at this many samples


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


# ----------------------------------------------------------------------------- validation
def _as_series(t, y, name: str) -> tuple[np.ndarray, np.ndarray, float]:
    """Check a sampled series and return (t, y, dt). Raises ValueError naming the problem."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.ndim != 1 or y.ndim != 1:
        raise ValueError(f"t and {name} must be one-dimensional (got shapes {t.shape} and {y.shape})")
    if len(t) != len(y):
        raise ValueError(f"t and {name} have different lengths ({len(t)} vs {len(y)})")
    if len(t) < 8:
        raise ValueError(f"only {len(t)} samples: too few for a spectrum")
    for label, arr in (("t", t), (name, y)):
        bad = ~np.isfinite(arr)
        if bad.any():
            raise ValueError(
                f"{label} contains {int(bad.sum())} NaN/inf values, first at index {int(np.argmax(bad))}"
            )
    steps = np.diff(t)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise ValueError(f"t is not strictly increasing at index {i + 1} (t[{i}]={t[i]!r}, t[{i + 1}]={t[i + 1]!r})")
    dt = (t[-1] - t[0]) / (len(t) - 1)
    spread = float(np.max(np.abs(steps - dt)) / dt)
    # A grid built as arange(n)*dt carries rounding of order eps * t_max / dt; allow that.
    tol = max(1e-6, 64 * np.finfo(float).eps * float(np.max(np.abs(t))) / dt)
    if spread > tol:
        raise ValueError(
            f"t is not uniformly sampled: steps range from {steps.min():.6g} s to {steps.max():.6g} s "
            f"({100 * spread:.3g} % of the mean step); resample onto a uniform grid first"
        )
    return t, y, float(dt)


def _line_fit(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Least-squares line y = y0 + v t in closed form (np.polyfit's SVD costs 40x more at 1e7 samples).

    Sums use numpy's pairwise summation, not np.dot: BLAS reductions depend on the thread count, and the
    same input must give the same bits in a dask worker (one thread) as in the caller.
    """
    tm, ym = t.mean(), y.mean()
    dtt = t - tm
    v = float(np.sum(dtt * (y - ym)) / np.sum(dtt * dtt))
    return v, float(ym - v * tm)


def _default_nperseg(n: int) -> int:
    """About 16-32 half-overlapping segments, a power of two, at least 256 samples."""
    if n < 256:
        return n
    return int(min(n, max(256, 2 ** int(math.floor(math.log2(n / 16))))))


def _welch_dof(n_segments: int) -> float:
    """Equivalent degrees of freedom of a Hann-window Welch estimate with 50 % overlap.

    Welch (1967): nu = 2K / (1 + 2 c^2) for K segments, c = 0.167 the Hann 50 %-overlap correlation.
    """
    if n_segments <= 1:
        return 2.0
    return 2.0 * n_segments / (1.0 + 2.0 * 0.167**2)


# ----------------------------------------------------------------------------- estimator core
def _difference_gain(omega: np.ndarray, dt: float, k: int) -> np.ndarray:
    """|H(omega)|^2 of the k-fold backward difference divided by dt^k: |2 sin(omega dt/2)/dt|^(2k)."""
    return np.abs(2.0 * np.sin(0.5 * omega * dt) / dt) ** (2 * k)


def _welch(y: np.ndarray, dt: float, nperseg: int) -> tuple[np.ndarray, np.ndarray, int]:
    noverlap = nperseg // 2
    f, S = signal.welch(
        y, fs=1.0 / dt, window="hann", nperseg=nperseg, noverlap=noverlap, detrend="constant",
        scaling="density", return_onesided=True,
    )
    n_segments = 1 + (len(y) - nperseg) // (nperseg - noverlap)
    return f[1:], S[1:], n_segments  # drop the zero-frequency ordinate


def _fast_length(n: int) -> int:
    """The largest length <= n that scipy.fft transforms fast, if it drops at most 0.5 % of n; else n.

    (A short series costs little whatever its length; cutting 4 % of a 2400-sample stroke would move the
    frequency grid for nothing.)
    """
    if hasattr(sp_fft, "prev_fast_len"):
        m = int(sp_fft.prev_fast_len(n, real=True))
    else:  # scipy < 1.15
        m = n
        while m > 0.995 * n and sp_fft.next_fast_len(m, real=True) != m:
            m -= 1
    return m if n - m <= 0.005 * n else n


def _periodogram(y: np.ndarray, dt: float) -> tuple[float, np.ndarray]:
    """Raw periodogram of y (mean removed), eq. (2) convention: C_j = dt |Y_j|^2 / (2 pi n), j = 1..n/2-ish.

    Returns (d_omega, C) without the zero-frequency ordinate and without the Nyquist ordinate of an even n
    (its distribution is chi-square with one degree of freedom, unlike the others). A length with a large
    prime factor would cost a slow FFT (10 s instead of 1.5 s at 10^7 samples), so the series is cut to the
    largest fast length when that drops at most 0.5 % (0.47 % of 10^7 samples), at the end.
    """
    n = _fast_length(len(y))
    y = y[:n]
    Y = sp_fft.rfft(y - y.mean())
    P = (Y.real**2 + Y.imag**2) * (dt / (2.0 * np.pi * n))
    P = P[1:(n + 1) // 2]  # j = 1 .. ceil(n/2) - 1: every ordinate two degrees of freedom
    return 2.0 * np.pi / (n * dt), P


def _pilot_gamma(z: np.ndarray, dt: float) -> float:
    """First slope estimate: the once-differenced series' Hann Welch slope, plus 2.

    A Hann estimate of a spectrum no steeper than about omega^-5 is barely biased, and the velocity
    spectrum of anything up to gamma ~ 7 is within that.
    """
    zz = z[: min(len(z), _PILOT_SAMPLES)]
    y = np.diff(zz) / dt
    nper = min(len(y), max(64, 2 ** int(math.floor(math.log2(max(len(y) / 32, 64))))))
    f, S, _ = _welch(y, dt, nper)
    omega = 2 * np.pi * f
    keep = (omega >= 4 * omega[0]) & (omega <= omega[-1] / 4)
    if keep.sum() < 4:
        keep = slice(None)
    good = S[keep] > 0
    slope = np.polyfit(np.log(omega[keep][good]), np.log(S[keep][good]), 1)[0]
    return 2.0 - float(slope)


def _auto_order(gamma: float) -> int:
    """Difference order leaving a differenced spectrum between about omega^-1 and omega^+1."""
    return int(np.clip(math.floor(gamma / 2.0 + 0.5), 0, _MAX_PREWHITEN))


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
    if detrend == "linear":
        v, y0 = _line_fit(t - t[0], y)
        z = y - (y0 + v * (t - t[0]))
        rate_unit = {"x": "m/s", "F": "N/s", "mu": "1/s"}.get(quantity, "per s")
        steps.append(f"removed fitted line {name}0 + v t, v = {v:.6g} {rate_unit}")
    elif detrend == "constant":
        v = 0.0
        z = y - y.mean()
        steps.append(f"removed mean {y.mean():.6g}")
    elif detrend == "none":
        v = 0.0
        z = y
    else:
        raise ValueError(f"detrend must be 'linear', 'constant' or 'none' (got {detrend!r})")

    auto = prewhiten == "auto"
    pilot = None
    if auto:
        pilot = _pilot_gamma(z, dt)
        k = _auto_order(pilot)
        steps.append(f"pilot slope gamma ~ {pilot:.2f} -> pre-whitening order {k}")
    else:
        try:
            k = int(prewhiten)
        except (TypeError, ValueError):
            raise ValueError(f"prewhiten must be a non-negative integer or 'auto' (got {prewhiten!r})") from None
        if not 0 <= k <= 6:
            raise ValueError(f"prewhiten must be between 0 and 6 (got {k})")
    nperseg0 = nperseg

    def welch_recoloured(k):
        zk = np.diff(z, n=k) / dt**k if k else z
        nps = min(nperseg0, len(zk))
        f, S, n_segments = _welch(zk, dt, nps)
        omega = 2.0 * np.pi * f
        C = S / (4.0 * np.pi)
        if k:
            C = C / _difference_gain(omega, dt, k)
        return zk, nps, n_segments, omega, C

    zk, nperseg, n_segments, omega, C = welch_recoloured(k)
    if auto:
        # The pilot (a short Hann estimate of the velocity) can miss by one order near the k boundaries
        # (gamma 6 read as 7.1-7.4 in 10 % of 2^16-sample series), and an over-differenced series (a rising
        # spectrum) leaks through the rectangular window of the raw periodogram. Check the order once on the
        # pre-whitened estimate itself, whose slope is unbiased, and redo it if the order changes.
        keep = (omega >= 4 * omega[0]) & (omega <= omega[-1] / 16)
        if keep.sum() >= 4 and np.all(C[keep] > 0):
            refined = -float(np.polyfit(np.log(omega[keep]), np.log(C[keep]), 1)[0])
            k2 = _auto_order(refined)
            if k2 != k:
                steps.append(f"slope of the order-{k} estimate gamma ~ {refined:.2f} -> pre-whitening order {k2}")
                k = k2
                zk, nperseg, n_segments, omega, C = welch_recoloured(k)
    if k:
        steps.append(f"differenced {k}x (divided by dt^{k})")
    steps.append(f"Welch: Hann window, nperseg = {nperseg}, 50 % overlap, {n_segments} segments")
    steps.append("C(omega) = S(f) / (4 pi)  [eq. (2) convention]")
    if k:
        steps.append(f"re-coloured by |2 sin(omega dt/2)/dt|^-{2 * k}")
    d_omega, P = _periodogram(zk, dt)
    if k:
        P = P / _difference_gain(d_omega * np.arange(1, len(P) + 1), dt, k)
    n_raw = int(round(2.0 * np.pi / (d_omega * dt)))
    steps.append(f"raw periodogram (rectangular window) of the {'differenced ' if k else ''}series over "
                 f"{n_raw} samples{f' (the last {len(zk) - n_raw} dropped for a fast FFT length)' if n_raw < len(zk) else ''}"
                 f", re-coloured alike: for the Whittle fit")

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
    """C_x(omega) of the noise zeta = x - (x0 + v t), eq. (2), with v fitted (Units: m^2 s).

    See :func:`series_spectrum` for the parameters. ``provenance["mean_velocity"]`` is the fitted v.
    """
    return series_spectrum(t, x, quantity="x", unit="m^2 s", detrend=detrend, prewhiten=prewhiten,
                           nperseg=nperseg, name="x")


def force_series_spectrum(t, F, *, prewhiten: int | str = "auto", nperseg: int | None = None) -> Spectrum:
    """C_F(omega) of a recorded force series F(t) (mean removed), eq. (2) convention (Units: N^2 s)."""
    return series_spectrum(t, F, quantity="F", unit="N^2 s", detrend="constant", prewhiten=prewhiten,
                           nperseg=nperseg, name="F")


def _rescaled(spec: Spectrum, factor, quantity: str, unit: str, step: str) -> Spectrum:
    """Multiply C (and the raw periodogram) by ``factor(omega)``."""
    prov = dict(spec.provenance)
    prov["steps"] = list(prov.get("steps", [])) + [step]
    prov["quantity"] = quantity
    P = None if spec.periodogram is None else spec.periodogram * factor(spec.periodogram_omega)
    return replace(spec, C=spec.C * factor(spec.omega), quantity=quantity, unit=unit, provenance=prov, periodogram=P)


def force_spectrum(spectrum: Spectrum, mass: float) -> Spectrum:
    """C_F = M^2 omega^4 C_x, eq. (3) (inertial relation; Units: N^2 s)."""
    if spectrum.quantity != "x":
        raise ValueError(f"force_spectrum needs a displacement spectrum (got quantity {spectrum.quantity!r})")
    if not mass > 0:
        raise ValueError(f"mass must be positive (got {mass!r})")
    return _rescaled(spectrum, lambda w: mass**2 * w**4, "F", "N^2 s",
                     f"C_F = M^2 omega^4 C_x with M = {mass:g} kg  [eq. (3)]")


def friction_coefficient_spectrum(spectrum: Spectrum, g: float = G_STANDARD) -> Spectrum:
    """C_mu = omega^4 C_x / g^2 (section 2; Units: s)."""
    if spectrum.quantity != "x":
        raise ValueError(
            f"friction_coefficient_spectrum needs a displacement spectrum (got quantity {spectrum.quantity!r})"
        )
    return _rescaled(spectrum, lambda w: w**4 / g**2, "mu", "s",
                     f"C_mu = omega^4 C_x / g^2 with g = {g:g} m/s^2  [section 2]")


def check_band(spectrum: Spectrum, band) -> tuple[float, float]:
    """(low, high) of a frequency band (rad/s) inside the spectrum's resolved range, or ValueError."""
    lo, hi = map(float, band)
    if not 0 < lo < hi:
        raise ValueError(f"band must satisfy 0 < low < high (got {band!r})")
    if lo < spectrum.omega_min * (1 - 1e-9) or hi > spectrum.omega_max * (1 + 1e-9):
        raise ValueError(
            f"band ({lo:.4g}, {hi:.4g}) rad/s lies outside the resolved range "
            f"({spectrum.omega_min:.4g}, {spectrum.omega_max:.4g}) rad/s"
        )
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
    """sqrt(2 Int C domega) over ``band`` (default: all resolved frequencies), eq. (4).

    For an un-binned spectrum each ordinate stands for a frequency cell of width d_omega (rectangle
    rule, which is what Parseval's theorem sums); a log-binned spectrum is integrated by trapezoids.
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

    Each bin's ``C`` is the arithmetic mean of its ordinates (an unbiased level); its ``omega`` is the
    geometric mean of the members' frequencies. ``n_avg`` counts the members. ``provenance`` gains
    ``log_mean_C``: the mean of ln C over each bin, which for a power law sits exactly on the line at the
    bin's geometric-mean frequency (the fit in :mod:`compare.fits` uses it).
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

    Evaluate a theory on ``spectrum.omega`` and pass it as ``values`` to average it over exactly the
    same ordinates, so per-band ratios carry no binning bias.
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
