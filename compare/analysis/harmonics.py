"""A deterministic line and its harmonics fitted and removed from a sampled series (an imposed vibration's response
in a noise record), so the spectrum that follows holds the noise alone: the line is subtracted, not masked.

The series is modelled as ``y(t) = noise(t) + sum_k (a_k cos(k omega t) + b_k sin(k omega t))``, k = 1..K, with
``omega`` known (the vibration's, e.g. from the recorded substrate displacement ``s(t) = A sin(omega t)``). A
plain least-squares fit on ``y`` would be biased by a steep noise spectrum (C ~ omega^-gamma with gamma near 4: the
record's low-frequency wander leaks into the sinusoids through the rectangular window far more than the noise at
omega itself), so the fit is made on the series and the regressors differenced ``order`` times (differencing is
linear: the coefficients a_k, b_k are unchanged) and weighted by a Hann taper: the residual leakage then falls as
the taper's sidelobes, and the amplitudes' error is set by the noise's own density at k omega,
``sqrt(P_1(f) / T)`` per coefficient (P_1: the one-sided density of the series in units^2/Hz, T: the record's
length), the density of a least-squares sinusoid in white noise. Harmonics at or above the Nyquist frequency
pi / dt are left out of the fit (their amplitude is NaN): sampled, they coincide with a lower line (or with 0 or the
Nyquist frequency itself) and cannot be told from it, so a harmonic that aliases onto a kept one is fitted as part
of it, and a line at or above the Nyquist frequency is not removed at all (the record cannot show it).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["HarmonicFit", "remove_harmonics"]


@dataclass(frozen=True)
class HarmonicFit:
    """The fitted line: ``omega`` (rad/s), per harmonic k = 1..K the amplitude ``amplitude[k-1]`` =
    sqrt(a_k^2 + b_k^2) (the series' units) and phase ``phase[k-1]`` = atan2(a_k, b_k) (rad, of ``sin(k omega t +
    phase)``; both NaN for a harmonic at or above the Nyquist frequency, left out), and ``removed``: the fitted sum
    that was subtracted (one value per sample)."""

    omega: float
    amplitude: np.ndarray
    phase: np.ndarray
    removed: np.ndarray

    def to_dict(self) -> dict:
        """JSON-ready summary (no per-sample array)."""
        return {"omega": self.omega, "amplitude": [float(a) for a in self.amplitude],
                "phase": [float(p) for p in self.phase]}


def remove_harmonics(t, y, omega: float, *, harmonics: int = 4, order: int = 2) -> tuple[np.ndarray, HarmonicFit]:
    """Fit the line at ``omega`` and its harmonics in ``y`` and subtract it.

    Parameters
    ----------
    t : array_like
        Uniform sample times (Units: s).
    y : array_like
        The series (e.g. a position x(t), Units: m), same length as ``t``.
    omega : float
        The line's angular frequency (Units: rad/s), > 0.
    harmonics : int
        K, the number of harmonics fitted (k omega for k = 1..K), >= 1; those at or above the Nyquist frequency
        pi / dt are left out (amplitude NaN).
    order : int
        Differences taken of the series and the regressors before the fit (0-4): about gamma / 2 for a noise
        C ~ omega^-gamma (2 for a position record whose spectrum falls as omega^-4).

    Returns
    -------
    (y_clean, fit) : (numpy.ndarray, HarmonicFit)
        ``y`` less the fitted line (same length), and the fit.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.shape != y.shape or t.ndim != 1:
        raise ValueError(f"t and y must be 1-D of one length (got {t.shape} and {y.shape})")
    if not (np.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be finite and > 0 (got {omega!r})")
    if int(harmonics) != harmonics or harmonics < 1:
        raise ValueError(f"harmonics must be an integer >= 1 (got {harmonics!r})")
    if int(order) != order or not 0 <= order <= 4:
        raise ValueError(f"order must be an integer in 0-4 (got {order!r})")
    if len(y) < 4 * harmonics + 8 + order:
        raise ValueError(f"only {len(y)} samples for {harmonics} harmonics")
    nyquist = np.pi / float(np.median(np.diff(t)))  # rad/s
    kept = np.arange(1, harmonics + 1)
    kept = kept[kept * omega < nyquist * (1 - 1e-9)]
    amplitude, phase = np.full(harmonics, np.nan), np.full(harmonics, np.nan)
    if len(kept) == 0:  # the line itself at or above the Nyquist frequency: the record cannot show it
        return y.copy(), HarmonicFit(omega=float(omega), amplitude=amplitude, phase=phase, removed=np.zeros_like(y))
    k, harmonics = kept, len(kept)
    ph = np.outer(t - t[0], k * omega)
    X = np.concatenate([np.cos(ph), np.sin(ph)], axis=1)  # a_k then b_k
    # the trend the differences leave (a constant after one, nothing after two), fitted beside the line
    trend = np.vander(t - t[0], max(2 - order, 0) + 1, increasing=True) if order < 2 else np.zeros((len(t), 0))
    D = np.concatenate([X, trend], axis=1)
    Dd, yd = np.diff(D, n=order, axis=0), np.diff(y, n=order)
    w = np.sqrt(np.hanning(len(yd) + 2)[1:-1])  # Hann taper as least-squares weights (no zero weight)
    coef = np.linalg.lstsq(Dd * w[:, None], yd * w, rcond=None)[0]
    a, b = coef[:harmonics], coef[harmonics:2 * harmonics]
    removed = X @ coef[:2 * harmonics]
    amplitude[k - 1], phase[k - 1] = np.hypot(a, b), np.arctan2(a, b)
    fit = HarmonicFit(omega=float(omega), amplitude=amplitude, phase=phase, removed=removed)
    return y - removed, fit
