"""Synthetic series with exactly known spectra, for tests (eq. 2 convention)."""
import numpy as np


def ou_process(n: int, dt: float, tau: float, sigma: float, seed: int) -> np.ndarray:
    """Exact discretisation of an Ornstein-Uhlenbeck process (AR(1) with rho = exp(-dt/tau)).

    Its spectrum is the Lorentzian C(omega) = sigma^2 tau / (pi (1 + omega^2 tau^2)) up to aliasing.
    """
    rng = np.random.default_rng(seed)
    rho = np.exp(-dt / tau)
    from scipy.signal import lfilter
    e = rng.standard_normal(n) * sigma * np.sqrt(1 - rho**2)
    e[0] = rng.standard_normal() * sigma
    return lfilter([1.0], [1.0, -rho], e)


def ou_spectrum(omega, tau: float, sigma: float):
    return sigma**2 * tau / (np.pi * (1.0 + (omega * tau) ** 2))


def pink_noise(n: int, seed: int) -> np.ndarray:
    """1/f noise by Fourier synthesis: Gaussian coefficients with |c|^2 ~ 1/f (exact, periodic)."""
    rng = np.random.default_rng(seed)
    k = np.fft.rfftfreq(n)
    amp = np.zeros_like(k)
    amp[1:] = k[1:] ** -0.5
    c = (rng.standard_normal(len(k)) + 1j * rng.standard_normal(len(k))) * amp
    return np.fft.irfft(c, n)


def power_law_series(gamma: int, n: int, seed: int) -> np.ndarray:
    """omega^-gamma series by integrating white (even gamma) or 1/f (odd gamma) noise gamma//2 times."""
    x = pink_noise(n, seed) if gamma % 2 else np.random.default_rng(seed).standard_normal(n)
    for _ in range(gamma // 2):
        x = np.cumsum(x)
    return x


def power_law_record(n: int, dt: float, gamma: float, seed: int, over: int = 4) -> np.ndarray:
    """n samples of a series whose sampled spectrum is omega^-gamma up to Nyquist (any real gamma), by Fourier synthesis.

    Gaussian coefficients with |c|^2 ~ omega^-gamma over a periodic series ``over`` times longer, of which the first
    n samples are returned: the window is not periodic, so an estimator meets the leakage of a real record. Nothing
    is folded at Nyquist: this is the record of an ideal anti-aliasing filter, not of a sampled continuous omega^-gamma
    process (:func:`compare.analysis.synthetic.power_law_record`), whose spectrum is about twice as high at Nyquist; the
    record model, which folds, reads it steeper (noise-free 4.576 for 4.5) unless its band stops below Nyquist.
    """
    rng = np.random.default_rng(seed)
    m = over * n
    w = 2 * np.pi * np.fft.rfftfreq(m, dt)
    amp = np.zeros_like(w)
    amp[1:] = w[1:] ** (-gamma / 2)
    c = (rng.standard_normal(len(w)) + 1j * rng.standard_normal(len(w))) * amp
    return np.fft.irfft(c, m)[:n]
