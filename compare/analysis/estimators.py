"""The spectral estimator's pure helpers (series checks, Welch and periodogram on the pre-whitened series, the
difference operator's exact gain, the pilot slope that sets the pre-whitening order); :mod:`compare.analysis.spectra`
builds :class:`~compare.analysis.spectra.Spectrum` objects from them."""
from __future__ import annotations

import math

import numpy as np
from scipy import fft as sp_fft
from scipy import signal

_MAX_PREWHITEN = 4
_PILOT_SAMPLES = 1 << 20  # the pilot slope estimate looks at most at this many samples


def as_series(t, y, name: str) -> tuple[np.ndarray, np.ndarray, float]:
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


def line_fit(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Least-squares line y = y0 + v t in closed form (np.polyfit's SVD costs 40x more at 1e7 samples).

    Sums use numpy's pairwise summation, not np.dot: BLAS reductions depend on the thread count, and the
    same input must give the same bits in a dask worker (one thread) as in the caller.
    """
    tm, ym = t.mean(), y.mean()
    dtt = t - tm
    v = float(np.sum(dtt * (y - ym)) / np.sum(dtt * dtt))
    return v, float(ym - v * tm)


def default_nperseg(n: int) -> int:
    """About 16-32 half-overlapping segments, a power of two, at least 256 samples."""
    if n < 256:
        return n
    return int(min(n, max(256, 2 ** int(math.floor(math.log2(n / 16))))))


def welch_dof(n_segments: int) -> float:
    """Equivalent degrees of freedom of a Hann-window Welch estimate with 50 % overlap.

    Welch (1967): nu = 2K / (1 + 2 c^2) for K segments, c = 0.167 the Hann 50 %-overlap correlation.
    """
    if n_segments <= 1:
        return 2.0
    return 2.0 * n_segments / (1.0 + 2.0 * 0.167**2)


# ----------------------------------------------------------------------------- estimator core
def difference_gain(omega: np.ndarray, dt: float, k: int) -> np.ndarray:
    """|H(omega)|^2 of the k-fold backward difference divided by dt^k: |2 sin(omega dt/2)/dt|^(2k)."""
    return np.abs(2.0 * np.sin(0.5 * omega * dt) / dt) ** (2 * k)


def welch(y: np.ndarray, dt: float, nperseg: int) -> tuple[np.ndarray, np.ndarray, int]:
    noverlap = nperseg // 2
    f, S = signal.welch(
        y, fs=1.0 / dt, window="hann", nperseg=nperseg, noverlap=noverlap, detrend="constant",
        scaling="density", return_onesided=True,
    )
    n_segments = 1 + (len(y) - nperseg) // (nperseg - noverlap)
    return f[1:], S[1:], n_segments  # drop the zero-frequency ordinate


def fast_length(n: int) -> int:
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


def periodogram(y: np.ndarray, dt: float) -> tuple[float, np.ndarray]:
    """Raw periodogram of y (mean removed), eq. (2) convention: C_j = dt |Y_j|^2 / (2 pi n), j = 1..n/2-ish.

    Returns (d_omega, C) without the zero-frequency ordinate and without the Nyquist ordinate of an even n
    (its distribution is chi-square with one degree of freedom, unlike the others). A length with a large
    prime factor would cost a slow FFT (10 s instead of 1.5 s at 10^7 samples), so the series is cut to the
    largest fast length when that drops at most 0.5 % (0.47 % of 10^7 samples), at the end.
    """
    n = fast_length(len(y))
    y = y[:n]
    Y = sp_fft.rfft(y - y.mean())
    P = (Y.real**2 + Y.imag**2) * (dt / (2.0 * np.pi * n))
    P = P[1:(n + 1) // 2]  # j = 1 .. ceil(n/2) - 1: every ordinate two degrees of freedom
    return 2.0 * np.pi / (n * dt), P


def pilot_gamma(z: np.ndarray, dt: float) -> float:
    """First slope estimate: the once-differenced series' Hann Welch slope, plus 2.

    A Hann estimate of a spectrum no steeper than about omega^-5 is barely biased, and the velocity
    spectrum of anything up to gamma ~ 7 is within that.
    """
    zz = z[: min(len(z), _PILOT_SAMPLES)]
    y = np.diff(zz) / dt
    nper = min(len(y), max(64, 2 ** int(math.floor(math.log2(max(len(y) / 32, 64))))))
    f, S, _ = welch(y, dt, nper)
    omega = 2 * np.pi * f
    keep = (omega >= 4 * omega[0]) & (omega <= omega[-1] / 4)
    if keep.sum() < 4:
        keep = slice(None)
    good = S[keep] > 0
    slope = np.polyfit(np.log(omega[keep][good]), np.log(S[keep][good]), 1)[0]
    return 2.0 - float(slope)


def auto_order(gamma: float) -> int:
    """Difference order leaving a differenced spectrum between about omega^-1 and omega^+1."""
    return int(np.clip(math.floor(gamma / 2.0 + 0.5), 0, _MAX_PREWHITEN))
