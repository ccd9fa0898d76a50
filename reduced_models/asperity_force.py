"""Model III: the asperity-force model (Xu, Zhou & Persson 2025, sections 6-7, Fig. 4-6).

A flat block of width w slides at v over a rigid rough substrate. The sliding axis is cut into cells
dx = v dt; cell i carries a force f(i) = 0 with probability 1 - p and r f0 (r uniform in [0, 1]) with
probability p. The friction force is the sum over the N_w = w / dx cells under the block, a moving window:
F(t + dt) = F(t) + f(i + N_w) - f(i). On average N = p N_w contacts carry f0/2 each, so F_f = N f0 / 2.

The block obeys M x'' = F_drive - F(t) with F_drive = F_f (eq. 1), integrated exactly for the
piecewise-constant force. The window sum of i.i.d. cells has the exact spectrum (eq. 2 convention)

    C_F(omega) = sigma_g^2 dt / (2 pi) * sin^2(N_w omega dt / 2) / sin^2(omega dt / 2),

flat below 2 pi v / w and falling as omega^-2 above it, so C_x = C_F / (M^2 omega^4) ~ omega^-6 (Fig. 6).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numba
import numpy as np

from frictionnoise.base import check_fields, check_seconds

from ._version import package_version
from .trace import ModelTrace

__all__ = ["AsperityForceParams", "simulate", "theory_force_spectrum", "theory_spectrum",
           "theory_spectrum_sampled", "grid_force_variance", "RESPONSE", "fit_band"]

RESPONSE = "inertial"  # C_x = C_F / (M^2 omega^4), eq. (3): no velocity-strengthening friction on the block


def fit_band(params: "AsperityForceParams", dt_out: float | None = None) -> tuple[float, float]:
    """The omega^-6 band: 30 v / w (well above the window's first zero 2 pi v / w) to a quarter of the output
    Nyquist pi / dt_out (the grid's, by default).

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).
    dt_out : float, optional
        Output step (Units: s); default the grid step ``params.dt``.

    Returns
    -------
    tuple of float
        (low, high) (Units: rad/s).
    """
    dt = params.dt if dt_out is None else dt_out
    return 30 * params.v / params.w, math.pi / dt / 4


@dataclass(frozen=True)
class AsperityForceParams:
    """Parameters of model III, SI units; defaults are the paper's section 7 case with N = 30.

    Attributes
    ----------
    F_f : float
        Mean friction force, equal to the drive (Units: N).
    v : float
        Sliding speed (Units: m/s).
    p : float
        Probability that a cell carries an asperity contact, in (0, 1].
    M : float
        Block mass (Units: kg).
    w : float
        Block width along the sliding direction (Units: m).
    N : float
        Mean number of contacts under the block; sets dx = p w / N and f0 = 2 F_f / N.
    """

    F_f: float = 5.0
    v: float = 0.5e-3
    p: float = 0.1
    M: float = 1.0
    w: float = 0.01
    N: float = 30.0

    def __post_init__(self):
        check_fields(self, positive=("F_f", "v", "M", "w", "N"))
        if not (isinstance(self.p, (int, float)) and 0 < self.p <= 1):
            raise ValueError(f"p must lie in (0, 1] (got {self.p!r})")
        if self.N_w < 2:
            raise ValueError(f"N = {self.N!r} with p = {self.p!r} leaves fewer than 2 cells under the block")

    @classmethod
    def reference(cls, N: float = 30.0) -> "AsperityForceParams":
        """Section 7 of the paper: F_f = 5 N, v = 0.5 mm/s, p = 0.1, M = 1 kg, w = 1 cm.

        Parameters
        ----------
        N : float, optional
            Mean number of asperity contacts under the block (the paper shows 30 and 300).

        Returns
        -------
        AsperityForceParams
        """
        return cls(N=N)

    @property
    def dx(self) -> float:
        """Cell length p w / N (Units: m)."""
        return self.p * self.w / self.N

    @property
    def dt(self) -> float:
        """Time step dx / v (Units: s)."""
        return self.dx / self.v

    @property
    def N_w(self) -> int:
        """Cells under the block, w / dx = N / p."""
        return int(round(self.N / self.p))

    @property
    def f0(self) -> float:
        """Largest asperity force 2 F_f / N (Units: N)."""
        return 2.0 * self.F_f / self.N

    def to_dict(self) -> dict:
        """The parameters as a JSON-able dict (SI units), with the derived grid.

        Returns
        -------
        dict
            Field name -> value, plus ``dx`` (m), ``dt`` (s), ``N_w`` (cells under the block) and ``f0`` (N).
        """
        d = asdict(self)
        d.update(dx=self.dx, dt=self.dt, N_w=self.N_w, f0=self.f0)
        return d


def grid_force_variance(params: AsperityForceParams) -> float:
    """Variance of one cell's force: E[f^2] - E[f]^2 = p f0^2 / 3 - p^2 f0^2 / 4.

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).

    Returns
    -------
    float
        The variance (Units: N^2).
    """
    p, f0 = params.p, params.f0
    return p * f0**2 / 3.0 - (p * f0 / 2.0) ** 2


@numba.njit(cache=True)
def _run(seed, n, Nw, p, f0, F_f, M, dt, v, x_out, F_out):
    """One pass: draw cell forces ahead of the block (a ring of the N_w cells under it), the window sum,
    and the exact step of M zeta'' = F_f - F for piecewise-constant F. Returns the number of hit cells."""
    np.random.seed(seed)
    ring = np.empty(Nw)
    F = 0.0
    hits = 0
    for i in range(Nw):
        u = np.random.random()
        f = u * (f0 / p) if u < p else 0.0  # hit when u < p; then u / p is uniform in [0, 1)
        hits += u < p
        ring[i] = f
        F += f
    vel = 0.0
    zeta = 0.0
    for k in range(n):
        F_out[k] = F
        x_out[k] = v * (k * dt) + zeta
        a = (F_f - F) / M
        zeta += vel * dt + 0.5 * a * dt * dt
        vel += a * dt
        u = np.random.random()
        f = u * (f0 / p) if u < p else 0.0
        hits += u < p
        j = k % Nw
        F += f - ring[j]  # cell k leaves at the trailing edge, cell k + N_w enters at the front
        ring[j] = f
    return hits


def simulate(params: AsperityForceParams, duration: float, dt_out: float | None = None, seed=None) -> ModelTrace:
    """Grid forces, the moving-window friction force and the exact block trajectory (one numba pass).

    The step is set by the grid, ``params.dt = dx / v``. ``dt_out`` (default: the grid step) samples it: it
    must be a whole number s of grid steps; ``x`` is then every s-th position and ``force`` the mean of F over
    each output interval (same convention as the other models).

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).
    duration : float
        Simulated time (Units: s).
    dt_out : float, optional
        Output step (Units: s), a whole number of grid steps; default the grid step.
    seed : int or numpy.random.Generator, optional
        Seed of the grid's random forces.

    Returns
    -------
    ModelTrace
        ``force`` (N) is F(t) averaged over [t_k, t_k + dt_out); ``x`` (m) the block position v t + zeta with
        M zeta'' = F_f - F, zeta(0) = zeta'(0) = 0.
    """
    check_seconds("duration", duration)
    dt, Nw = params.dt, params.N_w
    stride = 1
    if dt_out is not None:
        check_seconds("dt_out", dt_out)
        stride = int(round(dt_out / dt))
        if stride < 1 or abs(stride * dt - dt_out) > 1e-9 * dt_out:
            raise ValueError(f"dt_out = {dt_out!r} s must be a whole number of grid steps dt = {dt!r} s "
                             "(model III's step is set by its grid, dx / v)")
    n = int(round(duration / dt))
    if n < 2 * stride:
        raise ValueError(f"duration {duration!r} s holds fewer than two steps of dt = {dt * stride:.3g} s")
    rng = np.random.default_rng(seed)
    F = np.empty(n)
    x = np.empty(n)
    kernel_seed = int(rng.integers(0, 2**31 - 1))  # numba's own generator, seeded from the caller's
    if not (x.shape[0] >= n and F.shape[0] >= n):  # the kernel writes rows 0..n-1 unchecked (numba)
        raise RuntimeError(f"asperity_force._run: buffers of {x.shape[0]}, {F.shape[0]} rows for {n} steps")
    n_hits = _run(kernel_seed, n, Nw, params.p, params.f0, params.F_f, params.M, dt, params.v, x, F)
    n_cells = n + Nw
    t = np.arange(n) * dt
    if stride > 1:
        m = n // stride
        t, x = t[: m * stride : stride], x[: m * stride : stride]
        F = F[: m * stride].reshape(m, stride).mean(axis=1)
    meta = {
        "model": "III (asperity force)", "params": params.to_dict(), "seed": seed if isinstance(seed, (int, type(None))) else "Generator",
        "duration": len(t) * dt * stride, "dt_out": dt * stride, "grid_dt": dt, "version": package_version(),
        "method": "moving-window sum of i.i.d. cell forces (numba, ring buffer); exact double integration of piecewise-constant force",
    }
    return ModelTrace(t=t, x=x, force=F, events={"n_contacts_mean": n_hits / n_cells * Nw},
                      metadata=meta)


def theory_force_spectrum(params: AsperityForceParams, omega) -> np.ndarray:
    """Exact C_F of the sampled moving-window force.

    sigma_g^2 dt/(2 pi) sin^2(N_w theta/2)/sin^2(theta/2), theta = omega dt. Valid for 0 < omega < pi / dt.

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), 0 < omega < pi / dt.

    Returns
    -------
    numpy.ndarray
        C_F at ``omega`` (Units: N^2 s).
    """
    w = np.asarray(omega, dtype=float)
    th = w * params.dt
    return grid_force_variance(params) * params.dt / (2 * np.pi) * np.sin(params.N_w * th / 2) ** 2 / np.sin(th / 2) ** 2


def theory_spectrum(params: AsperityForceParams, omega) -> np.ndarray:
    """C_x = C_F / (M^2 omega^4), eq. (3).

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), 0 < omega < pi / dt.

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s).
    """
    w = np.asarray(omega, dtype=float)
    return theory_force_spectrum(params, w) / (params.M**2 * w**4)


def theory_spectrum_sampled(params: AsperityForceParams, omega) -> np.ndarray:
    """C_x of the trajectory sampled at the grid.

    For a piecewise-constant force, ``x_{k+1} - 2 x_k + x_{k-1} = dt^2 (a_k + a_{k-1}) / 2``, so
    ``|H|^2 = dt^4 cos^2(theta/2) / (16 sin^4(theta/2)) / M^2``. Equals :func:`theory_spectrum` to O(theta^2).

    Parameters
    ----------
    params : AsperityForceParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), 0 < omega < pi / dt.

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s).
    """
    w = np.asarray(omega, dtype=float)
    th = w * params.dt
    gain = params.dt**4 * np.cos(th / 2) ** 2 / (16 * np.sin(th / 2) ** 4) / params.M**2
    return theory_force_spectrum(params, w) * gain


# What the sweep, the report and `frictionnoise compare` read of this model through reduced_models.MODELS
# (the protocol is described in reduced_models/__init__.py).
PARAMS = AsperityForceParams
SWEEP_SERIES = "x"  # a sweep task returns the spectrum of the block's displacement, C_x


def default_duration(params: AsperityForceParams) -> float:
    """Simulated seconds of a run when the caller sets none (Units: s)."""
    return 2**18 * params.dt  # 2^18 grid steps


def default_dt_out(params: AsperityForceParams) -> float:
    """Output step of a run when the caller sets none (Units: s)."""
    return params.dt  # the grid step: model III's own
