"""Model II: wear particles trapped and released at the interface (Xu, Zhou & Persson 2025, section 5,
Appendix B, Fig. 3).

Each of N particles alternates between a trapped state A and a sliding state B. Durations in each state
follow a law with a per-particle mean tau_A,n (tau_B,n) drawn log-uniform between tau_min and tau_max;
the force on the block is c_A (trapped) or c_B (sliding). The friction force fluctuation is
F_1(t) = sum_n f_n(t), a sum of rectangles (eq. B1), and the block obeys M zeta'' = -F_1 (eq. 1).

Two force modes:

- ``"independent"`` (default): every episode's force is +-c with a random sign, so different rectangles
  are uncorrelated. This is the assumption under which eq. (B2) holds exactly (the cross terms of (B1)
  average to zero), with <cos omega tau> taken over the duration law.
- ``"telegraph"``: the force alternates deterministically between c_A and c_B (a random telegraph
  signal); its exact spectrum is a Lorentzian with tau_c = tau_A tau_B / (tau_A + tau_B). Over a
  log-uniform spread of times it gives the same 1/f level as (B2) but corners shifted by up to 2x.

Eq. (B2)::

    C_F(omega) = (N/pi) Int dtau dtau' P_A(tau) P_B(tau') / (omega^2 (tau + tau'))
                 [c_A^2 (1 - <cos omega tau_A>) + c_B^2 (1 - <cos omega tau_B>)];

with P c^2 ~ tau^-beta and tau^-beta', C_F ~ omega^(beta + beta' - 3); log-uniform times (beta = beta' = 1)
give 1/f force noise and C_x ~ omega^-5.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np
from scipy import integrate

from frictionnoise.base import check_fields, check_seconds

from ._version import package_version
from .wear_particle_kernel import run
from .wear_particle_quadrature import mean_time_pairs
from .wear_particle_spectrum_kernel import b2_sum, closure_terms, telegraph_sum
from .trace import ModelTrace

__all__ = ["DurationLaw", "WearParticleParams", "simulate", "theory_force_spectrum", "theory_spectrum",
           "power_law_prediction", "RESPONSE", "fit_band"]

RESPONSE = "inertial"  # C_x = C_F / (M^2 omega^4), eq. (3): the block has no velocity-strengthening friction


def fit_band(params: "WearParticleParams", dt_out: float | None = None):
    """The band of the model's power law: None, the automatic band.

    The exponent depends on the duration laws (eq. B2), so the automatic straight-stretch band of
    ``compare.fits.fit_power_law`` is used.

    Parameters
    ----------
    params : WearParticleParams
        The model's parameters (SI units).
    dt_out : float, optional
        Output step (Units: s); unused, accepted as every model's ``fit_band`` is.

    Returns
    -------
    None
    """
    return None

_LAWS = ("exponential", "fixed", "pareto")
_MODES = ("independent", "telegraph")
_LINKS = ("independent", "same_rank")


@dataclass(frozen=True)
class DurationLaw:
    """How long a particle stays in one state.

    Each particle n gets a mean duration tau_n drawn log-uniform in [tau_min, tau_max] (one value when they
    are equal); its durations then follow ``kind``: ``"exponential"`` (mean tau_n), ``"fixed"`` (= tau_n),
    or ``"pareto"`` (shape ``shape`` > 1, scale set so the mean is tau_n; one scale only: tau_min = tau_max).

    Attributes
    ----------
    tau_min, tau_max : float
        Range of per-particle mean durations (Units: s).
    kind : str
    shape : float
        Pareto tail exponent (P(tau > x) ~ x^-shape); ignored otherwise.
    """

    tau_min: float
    tau_max: float
    kind: str = "exponential"
    shape: float = 2.5

    def __post_init__(self):
        if self.kind not in _LAWS:
            raise ValueError(f"kind must be one of {', '.join(_LAWS)} (got {self.kind!r})")
        for name in ("tau_min", "tau_max"):
            val = getattr(self, name)
            if not (isinstance(val, (int, float)) and math.isfinite(val) and val > 0):
                raise ValueError(f"{name} must be a positive duration in seconds (got {val!r})")
        if self.tau_min > self.tau_max:
            raise ValueError(f"tau_min ({self.tau_min!r} s) must not exceed tau_max ({self.tau_max!r} s)")
        if self.kind == "pareto":
            if not self.shape > 1:
                raise ValueError(f"shape must exceed 1 for a Pareto law with a finite mean (got {self.shape!r})")
            if self.tau_min != self.tau_max:
                raise ValueError("pareto durations take one scale: set tau_max equal to tau_min")

    def means_at(self, u: np.ndarray) -> np.ndarray:
        """Per-particle mean durations, log-uniform in [tau_min, tau_max].

        Parameters
        ----------
        u : array_like
            Uniform variates in [0, 1) (dimensionless).

        Returns
        -------
        numpy.ndarray
            The mean durations (Units: s).
        """
        a, b = math.log(self.tau_min), math.log(self.tau_max)
        return np.exp(a + (b - a) * np.asarray(u, dtype=float))

    def mean_cos(self, omega: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """<cos(omega T)> for durations T of this law with mean tau (broadcasting omega against tau).

        Parameters
        ----------
        omega : array_like
            Angular frequencies (Units: rad/s).
        tau : array_like
            Mean durations (Units: s).

        Returns
        -------
        numpy.ndarray
            <cos(omega T)> (dimensionless).
        """
        x = omega * tau
        if self.kind == "exponential":
            return 1.0 / (1.0 + x**2)
        if self.kind == "fixed":
            return np.cos(x)
        a = self.shape
        scale = float(np.mean(tau)) * (a - 1) / a
        out = np.empty(np.shape(omega))
        for i, w in np.ndenumerate(np.broadcast_to(omega, np.shape(omega))):
            # a scale^a Int_scale^inf cos(w t) t^(-a-1) dt, by QAWF for the oscillatory tail
            tail = integrate.quad(lambda t: t ** (-a - 1), scale, np.inf, weight="cos", wvar=w, limlst=200)[0]
            out[i] = a * scale**a * tail
        return out

    @property
    def code(self) -> int:
        return _LAWS.index(self.kind)


@dataclass(frozen=True)
class WearParticleParams:
    """Parameters of model II, SI units.

    Attributes
    ----------
    n_particles : int
    trapped, sliding : DurationLaw
        Durations in the trapped (A) and sliding (B) states.
    c_A, c_B : float
        Force on the block from one particle when trapped / sliding (Units: N). In "independent" mode the
        episode force is +-c with a random sign; in "telegraph" mode it is exactly c.
    kappa_A, kappa_B : float
        Optional dependence on the particle's mean duration: c(tau) = c (tau / tau_min)^kappa.
    mode : str
        "independent" or "telegraph" (see the module docstring).
    tau_link : str
        How a particle's two mean times are drawn: "independent" (P_A(tau) P_B(tau') as in eq. B2) or
        "same_rank" (one uniform variate sets both, so a slow-to-release particle is also slow to be
        re-trapped; with equal laws tau_B = tau_A).
    M : float
        Block mass (Units: kg).
    v : float
        Mean sliding speed, only to build x = v t + zeta (Units: m/s).
    """

    n_particles: int = 1000
    trapped: DurationLaw = field(default_factory=lambda: DurationLaw(1e-2, 1e2))
    sliding: DurationLaw = field(default_factory=lambda: DurationLaw(1e-2, 1e2))
    c_A: float = 0.01
    c_B: float = 0.01
    kappa_A: float = 0.0
    kappa_B: float = 0.0
    mode: str = "independent"
    tau_link: str = "independent"
    M: float = 1.0
    v: float = 0.5e-3

    def __post_init__(self):
        if isinstance(self.n_particles, bool) or not isinstance(self.n_particles, (int, np.integer)) or self.n_particles < 1:
            raise ValueError(f"n_particles must be an integer >= 1 (got {self.n_particles!r})")
        for name in ("trapped", "sliding"):
            if not isinstance(getattr(self, name), DurationLaw):
                raise ValueError(f"{name} must be a DurationLaw (got {type(getattr(self, name)).__name__})")
        for name in ("c_A", "c_B"):
            val = getattr(self, name)
            if not (isinstance(val, (int, float)) and math.isfinite(val)):
                raise ValueError(f"{name} must be a finite force in N (got {val!r})")
        check_fields(self, positive=("M", "v"))
        if self.mode not in _MODES:
            raise ValueError(f"mode must be one of {', '.join(_MODES)} (got {self.mode!r})")
        if self.tau_link not in _LINKS:
            raise ValueError(f"tau_link must be one of {', '.join(_LINKS)} (got {self.tau_link!r})")

    @classmethod
    def one_over_f(cls, n_particles: int = 1000) -> "WearParticleParams":
        """Log-uniform relaxation times over 4 decades (10 ms to 100 s), the same for both states.

        Every particle gives a Lorentzian of level ~ tau and corner 1/tau, and the log-uniform spread sums them to
        exact 1/f force noise between the corners, gamma = 5.

        With independently drawn tau_A and tau_B (``tau_link="independent"``) eq. (B2) has a logarithmic
        divergence at small tau' (the weight 1/(tau + tau')): C_F ~ omega^-1 ln(1/(omega tau_min)), which
        reads as a slope of about -1.25 over 0.1-10 rad/s here.

        Parameters
        ----------
        n_particles : int, optional
            Number of particles.

        Returns
        -------
        WearParticleParams
            The 1/f case, with the trapped and sliding times of a particle linked (``tau_link="same_rank"``).
        """
        return cls(n_particles=n_particles, tau_link="same_rank")

    def to_dict(self) -> dict:
        """The parameters as a JSON-able dict (SI units).

        Returns
        -------
        dict
            Field name -> value (the duration laws as dicts).
        """
        return asdict(self)


# ----------------------------------------------------------------------------- simulator
def simulate(params: WearParticleParams, duration: float, dt_out: float = 1e-3, seed=None) -> ModelTrace:
    """Event-driven simulation; the force is an exact sum of rectangles, returned as interval averages.

    The block moves by M zeta'' = -(F - <F>) integrated exactly over each interval, using each interval's
    force integral and first moment (no within-step approximation). <F> is the ensemble mean (0 in
    "independent" mode; sum_n (c_A tau_A + c_B tau_B)/(tau_A + tau_B) in "telegraph" mode).

    Parameters
    ----------
    params : WearParticleParams
        The model's parameters (SI units).
    duration : float
        Simulated time (Units: s).
    dt_out : float, optional
        Output step (Units: s).
    seed : int or numpy.random.Generator, optional
        Seed of the durations' random numbers.

    Returns
    -------
    ModelTrace
        ``t`` (s), ``x`` (m), ``force`` (N: the particles' summed force averaged over each output step).
    """
    check_seconds("duration", duration)
    check_seconds("dt_out", dt_out)
    n = int(round(duration / dt_out))
    if n < 2:
        raise ValueError(f"duration {duration!r} s holds fewer than two output steps of {dt_out!r} s")
    rng = np.random.default_rng(seed)
    P = params
    uA = rng.random(P.n_particles)
    uB = uA if P.tau_link == "same_rank" else rng.random(P.n_particles)
    tauA = P.trapped.means_at(uA)
    tauB = P.sliding.means_at(uB)
    cA = P.c_A * (tauA / P.trapped.tau_min) ** P.kappa_A
    cB = P.c_B * (tauB / P.sliding.tau_min) ** P.kappa_B
    kinds = np.array([P.trapped.code, P.sliding.code], dtype=np.int64)
    shapes = np.array([P.trapped.shape, P.sliding.shape])
    I = np.zeros(n)
    J = np.zeros(n)
    counts = np.zeros(2, dtype=np.int64)
    kernel_seed = int(rng.integers(0, 2**31 - 1))  # numba's own generator, seeded from the caller's
    # the kernel writes I, J, counts unchecked (numba): sizes checked here
    if not (I.shape == J.shape == (n,) and counts.shape == (2,) and kinds.shape == shapes.shape == (2,)
            and tauA.shape == tauB.shape == cA.shape == cB.shape == (P.n_particles,)):
        raise RuntimeError("wear_particle_kernel.run: buffer sizes do not match n and n_particles")
    run(kernel_seed, n, dt_out, kinds, shapes, tauA, tauB, cA, cB, P.mode == "telegraph", I, J, counts)
    mean_F = float(np.sum((cA * tauA + cB * tauB) / (tauA + tauB))) if P.mode == "telegraph" else 0.0
    # M zeta'' = -(F - mean_F): over [t_k, t_k+1], zeta' gains -(I_k - mean_F dt)/M and zeta gains
    # zeta'_k dt - (J_k - mean_F dt^2 / 2)/M exactly.
    dI = -(I - mean_F * dt_out) / P.M
    dJ = -(J - mean_F * dt_out**2 / 2) / P.M
    vel = np.concatenate([[0.0], np.cumsum(dI[:-1])])
    zeta = np.concatenate([[0.0], np.cumsum(vel[:-1] * dt_out + dJ[:-1])])
    t = np.arange(n) * dt_out
    meta = {
        "model": "II (wear particle)", "params": params.to_dict(), "mode": P.mode,
        "seed": seed if isinstance(seed, (int, type(None))) else "Generator", "duration": n * dt_out,
        "dt_out": dt_out, "version": package_version(), "mean_force": mean_F,
        "method": "event-driven sum of rectangles (numba), exact interval integrals and first moments",
    }
    return ModelTrace(t=t, x=P.v * t + zeta, force=I / dt_out,
                      events={"episodes_trapped": int(counts[0]), "episodes_sliding": int(counts[1]),
                              "tau_A": tauA, "tau_B": tauB}, metadata=meta)


# ----------------------------------------------------------------------------- theory
def theory_force_spectrum(params: WearParticleParams, omega, *, closure: str = "exact", order: int = 12,
                          dt_avg: float | None = None) -> np.ndarray:
    """C_F(omega) of the particles' summed force.

    Mode "independent": eq. (B2), integrated over the joint law of the per-particle means (independent:
    P_A(tau) P_B(tau') as in the paper; same_rank: one variate) by Gauss-Legendre panels. ``closure="exact"``
    uses the duration law's own <cos omega tau> (1/(1 + omega^2 tau^2) for exponential); ``closure="cumulant"``
    uses the paper's exp(-s^2 omega^2/2) cos(omega tau) with s^2 = tau^2 (exponential), 0 (fixed) or the Pareto
    variance. Mode "telegraph": the exact random-telegraph Lorentzian sum over the same distribution,
    (c_A - c_B)^2 p_A p_B tau_c / (pi (1 + omega^2 tau_c^2)).

    Parameters
    ----------
    params : WearParticleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.
    closure : {"exact", "cumulant"}, optional
        The average of <cos omega tau> over a duration law.
    order : int, optional
        Gauss-Legendre points per panel of the integral over the per-particle means.
    dt_avg : float, optional
        Averaging interval (Units: s): the spectrum of the force averaged over intervals of that length (as
        ``simulate`` returns it), i.e. times sinc^2(omega dt_avg / 2) (aliases neglected: they fall as omega^-4).

    Returns
    -------
    numpy.ndarray
        C_F at ``omega`` (Units: N^2 s).
    """
    P = params
    if closure not in ("exact", "cumulant"):
        raise ValueError(f"closure must be 'exact' or 'cumulant' (got {closure!r})")
    w = np.ascontiguousarray(np.atleast_1d(np.asarray(omega, dtype=float)).ravel())
    TA, TB, W = mean_time_pairs(P, order)
    cA = P.c_A * (TA / P.trapped.tau_min) ** P.kappa_A
    cB = P.c_B * (TB / P.sliding.tau_min) ** P.kappa_B
    out = np.empty(len(w))
    if P.mode == "telegraph":
        pApB = TA * TB / (TA + TB) ** 2
        telegraph_sum(w, W * (cA - cB) ** 2 * pApB, TA * TB / (TA + TB), out)
        return P.n_particles * out * _avg_gain(w, dt_avg)
    # Each state's term of (B2) depends on its own mean time only, save for the weight 1 / (tau + tau'): summing
    # that weight over the other state's times first makes the cost per frequency the number of distinct times of
    # each state (96 + 96 at order 12 over 4 decades) instead of their pairs (96 x 96); the same sum, reordered.
    out[:] = 0.0
    for law, T, c in ((P.trapped, TA, cA), (P.sliding, TB, cB)):
        Tu, inv = np.unique(T, return_inverse=True)
        K = np.bincount(inv, weights=W / (TA + TB), minlength=len(Tu))
        cu = np.empty(len(Tu))
        cu[inv] = c
        mode, s, tab = closure_terms(law, closure, w, Tu)
        b2_sum(w, Tu, K, cu**2, mode, s, tab, out)
    return P.n_particles / np.pi * out * _avg_gain(w, dt_avg)


def _avg_gain(w, dt_avg):
    return 1.0 if dt_avg is None else np.sinc(w * dt_avg / (2 * np.pi)) ** 2


def theory_spectrum(params: WearParticleParams, omega, **kw) -> np.ndarray:
    """C_x = C_F / (M^2 omega^4), eq. (3).

    Parameters
    ----------
    params : WearParticleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.
    **kw
        Passed to :func:`theory_force_spectrum` (``closure``, ``order``, ``dt_avg``).

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s).
    """
    w = np.asarray(omega, dtype=float)
    return theory_force_spectrum(params, w, **kw) / (params.M**2 * w**4)


def power_law_prediction(params: WearParticleParams) -> dict:
    """The Appendix B power law C_F ~ omega^(beta + beta' - 3) and the band where it holds.

    For log-uniform per-particle means, P(tau) ~ tau^-1, and c^2(tau) ~ tau^(2 kappa), so
    beta = 1 - 2 kappa_A, beta' = 1 - 2 kappa_B. The power law holds between the corners, about
    10 / tau_max and 0.1 / tau_min (for 4 decades of tau this leaves 2 decades); above 1/tau_min C_F
    tends to omega^-2 (gamma = 6), below 1/tau_max it flattens (gamma = 4).

    Parameters
    ----------
    params : WearParticleParams
        The model's parameters (SI units).

    Returns
    -------
    dict
        ``beta``, ``beta_prime``, ``force_slope`` (the exponent of C_F), ``gamma`` (of C_x = 4 - force_slope),
        ``band`` ((low, high) in rad/s, or None when the corners leave none) and a ``note``.
    """
    beta = 1 - 2 * params.kappa_A
    beta_p = 1 - 2 * params.kappa_B
    slope = beta + beta_p - 3
    lo = 10.0 / min(params.trapped.tau_max, params.sliding.tau_max)
    hi = 0.1 / max(params.trapped.tau_min, params.sliding.tau_min)
    return {"beta": beta, "beta_prime": beta_p, "force_slope": slope, "gamma": 4 - slope,
            "band": (lo, hi) if hi > lo else None,
            "note": "valid between the corners 10/tau_max and 0.1/tau_min; omega^-2 above 1/tau_min"}


# What the sweep, the report and `frictionnoise compare` read of this model through reduced_models.MODELS
# (the protocol is described in reduced_models/__init__.py).
PARAMS = WearParticleParams
SWEEP_SERIES = "x"  # a sweep task returns the spectrum of the block's displacement, C_x


def default_duration(params: WearParticleParams) -> float:
    """Simulated seconds of a run when the caller sets none (Units: s)."""
    return 500.0


def default_dt_out(params: WearParticleParams) -> float:
    """Output step of a run when the caller sets none (Units: s)."""
    return 1e-3
