"""Model I with ageing contacts: the spring-block model whose miniblocks' friction follows rate-and-state.

Model I (Xu, Zhou & Persson 2025, section 3 and Appendix A) gives each miniblock a friction f_kin + m eta1 v_i and
a random force f_i = alpha f_kin (r - 0.5) that renews once at a random point of every sliding distance a (eq. 5).
Here the deterministic part is the rate-and-state law of :mod:`reduced_models.rate_state` acting on the contact's
normal load f_n = F_N / N, referenced to the mean sliding speed v:

    F_i = f_n [mu_v + A ln(v_i / v) + B ln(v theta_i / D_c)],     mu_v = F_drive / F_N,

so steady sliding at v carries F_drive (the state at its steady value D_c / v). Each contact's state theta_i ages
while it holds and evolves with its slip by the ageing or slip law; optionally (``renewal_state``) the state also
restarts at a fresh contact's age when the contact renews, together with its random force.

The miniblocks are massless: their inertial mode (rate eta1 ~ 3e7 1/s in model I) lies four decades above any
output band, so each miniblock's spring and damper carry its friction at every instant,

    k0 (x - x_i) + m eta0 (x' - x_i') = F_i(v_i, theta_i) + f_i,        M x'' = F_drive - sum_i (F_i + f_i),

and (A1) is unchanged. The lateral springs k1 of model I are left out (they cancel from the block's motion in the
linear model; here each contact is independent). Integrated in z = x - v t, u = x', the springs' stretches
s_i = x - x_i, the direct-effect forces D_i = f_n A ln(v_i / v) and the states (theta_i v / D_c for the ageing law,
its logarithm for the slip law), with an embedded Dormand-Prince 5(4) pair, its dense output for the samples and for
the renewal times (the block's displacement v t + z crossing each renewal position), restarting at each renewal.

Reduction to model I: B = 0 and ``linear_direct=True`` (F_i = f_n mu_v + (f_n A / v)(v_i - v)) is model I with
m eta1 = f_n A / v and N f_kin = F_kin (:func:`equivalent_model_I`); the brief form m eta1 = A f_kin / v is f_n = f_kin.

Linear response about steady sliding (``renewal_state=None``): both state laws give the contact a dynamic friction
slope c(omega) = (f_n / v)(A - B / (1 + i omega D_c / v)) in place of model I's m eta1, so C_x = |Z|^2 C_f / N (A10)
with Z from (A5) with that slope (:func:`transfer_function`) and C_f of the renewal force (A8) unchanged.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from frictionnoise.base import check_fields, check_number

from . import rate_state as _rs
from ._version import package_version
from .ageing_kernel import renew, run
from .trace import ModelTrace

__all__ = ["AgeingParams", "simulate", "theory_spectrum", "transfer_function", "random_force_spectrum",
           "friction_slope", "equivalent_model_I", "asymptotic_spectrum", "RESPONSE", "fit_band", "PARAMS",
           "SWEEP_SERIES", "default_duration", "default_dt_out"]

RESPONSE = "viscous"  # below the block's resonance, zeta = -F / (i omega N c(omega)), the ageing form of eq. (A6)
SWEEP_SERIES = "x"  # a sweep task returns the spectrum of the block's displacement, C_x

_BLOCK_INTERVALS = 256  # renewal intervals drawn per miniblock at a time (the draws of model I, same order)


@dataclass(frozen=True)
class AgeingParams:
    """Model I with rate-and-state contacts, SI units. Defaults: model I's reference case (section 4) for the block,
    springs and renewal; rate-and-state values for rubber on concrete as stated in
    for ``python -m compare.studies.velocity_scaling`` (A - B = 0.08 from the paper's Fig. 9 / Table 1; B / A and D_c
    assumed).

    Attributes
    ----------
    N, v, a, k0, M, m, eta0, alpha, F_drive, F_kin
        As in :class:`reduced_models.spring_block.SpringBlockParams` (N, m/s, m, N/m, kg, kg, 1/s, -, N, N); m enters
        only through the damper m eta0 (the miniblocks' inertia is neglected). F_kin sets the random force,
        f_i = alpha (F_kin / N)(r - 0.5).
    F_N : float
        Total normal load on the contacts (Units: N); each carries f_n = F_N / N. mu_v = F_drive / F_N.
    A, B : float
        Direct and evolution coefficients of the contacts' rate-and-state law (A > 0, B >= 0).
    D_c : float
        Critical slip distance of the state (Units: m).
    law : str
        State law, "ageing" or "slip" (:data:`reduced_models.rate_state.STATE_LAWS`).
    renewal_state : float or None
        None: the state evolves continuously through renewals. A value theta_r (Units: s): the state restarts at
        theta_r when the contact renews (a fresh contact of age theta_r).
    linear_direct : bool
        Linearise the direct effect about v, F = f_n mu_v + (f_n A / v)(v_i - v) + f_n B ln(v theta / D_c).
    """

    N: int = 30
    v: float = 0.5e-3
    a: float = 1e-3
    k0: float = 1e4
    M: float = 1.0
    m: float = 1e-5
    eta0: float = 0.8e4
    alpha: float = 1.0
    F_drive: float = 10.0
    F_kin: float = 5.0
    F_N: float = 20.0
    A: float = 0.12
    B: float = 0.04
    D_c: float = 1e-4
    law: str = "ageing"
    renewal_state: float | None = None
    linear_direct: bool = False

    def __post_init__(self):
        check_fields(self, integer=("N",), positive=("N", "v", "a", "k0", "M", "m", "F_drive", "F_N", "A", "D_c"),
                     non_negative=("eta0", "alpha", "F_kin", "B"))
        if self.law not in _rs.STATE_LAWS:
            raise ValueError(f"law must be one of {sorted(_rs.STATE_LAWS)} (got {self.law!r})")
        if self.renewal_state is not None:
            check_number("renewal_state", self.renewal_state, positive=True)
        if not isinstance(self.linear_direct, bool):
            raise ValueError(f"linear_direct must be True or False (got {self.linear_direct!r})")
        if self.linear_direct and self.law == "slip" and self.B > 0:
            raise ValueError("linear_direct needs law = 'ageing' when B > 0 (the slip law takes ln of the speed)")

    @classmethod
    def reference(cls) -> "AgeingParams":
        """The reference case: model I's (paper section 4) with ageing contacts at this class's default A, B, D_c.

        Returns
        -------
        AgeingParams
            The defaults of every field (SI units).
        """
        return cls()

    @property
    def f_n(self) -> float:
        """Normal load per contact (Units: N)."""
        return self.F_N / self.N

    @property
    def f_kin(self) -> float:
        """Random force scale per contact, F_kin / N (Units: N)."""
        return self.F_kin / self.N

    @property
    def mu_v(self) -> float:
        """Friction coefficient of steady sliding at v, F_drive / F_N."""
        return self.F_drive / self.F_N

    @property
    def tau0(self) -> float:
        """Mean renewal interval of one contact, a / v (Units: s)."""
        return self.a / self.v

    def to_dict(self) -> dict:
        """The parameters as a JSON-able dict (SI units).

        Returns
        -------
        dict
            Field name -> value.
        """
        return asdict(self)


# ----------------------------------------------------------------------------- theory
def friction_slope(params: AgeingParams, omega) -> np.ndarray:
    """c(omega) = (f_n / v)(A - B / (1 + i omega D_c / v)) (Units: N s/m): one contact's friction per unit of
    velocity perturbation at angular frequency omega, both state laws (:func:`rate_state.rate_sensitivity`)."""
    p = params
    return p.f_n / p.v * _rs.rate_sensitivity(p.A, p.B, p.D_c, p.v, omega)


def transfer_function(params: AgeingParams, omega) -> np.ndarray:
    """Z(omega) of eq. (A5) with massless miniblocks and m eta1 -> c(omega) (Units: m/N)."""
    p = params
    w = np.asarray(omega, dtype=float)
    iw = 1j * w
    c0 = p.m * p.eta0
    Q0 = -p.M * w**2 + p.N * p.k0 + iw * p.N * c0
    Q1 = p.k0 + iw * (c0 + friction_slope(p, w))
    P0 = p.N * p.k0 + iw * p.N * c0
    P1 = p.k0 + iw * c0
    return -P0 / (Q0 * Q1 - P0 * P1)


def random_force_spectrum(params: AgeingParams, omega) -> np.ndarray:
    """C_f of one contact's renewal force, eq. (A8) with <cos omega tau> = exp(-s^2 omega^2 / 2) cos(omega tau0),
    s^2 = tau0^2 / 6 (Units: N^2 s)."""
    p = params
    w = np.asarray(omega, dtype=float)
    mean_cos = np.exp(-(p.tau0**2 / 6.0) * w**2 / 2.0) * np.cos(w * p.tau0)
    return p.v / (12.0 * np.pi * p.a) * p.f_kin**2 * p.alpha**2 / w**2 * (1.0 - mean_cos)


def theory_spectrum(params: AgeingParams, omega) -> np.ndarray:
    """C_x(omega) = |Z|^2 C_f / N, eq. (A10) with the rate-and-state slope (Units: m^2 s). The linear response about
    steady sliding; exact for ``renewal_state=None`` to first order in the renewal forces."""
    return np.abs(transfer_function(params, omega)) ** 2 * random_force_spectrum(params, omega) / params.N


def asymptotic_spectrum(params: AgeingParams, omega) -> np.ndarray:
    """eq. (A11) with m eta1 -> c(omega): alpha^2 v f_kin^2 / (12 pi N a |c(omega)|^2 omega^4) (Units: m^2 s), for
    v/a << omega << the block's resonance."""
    p = params
    w = np.asarray(omega, dtype=float)
    return p.alpha**2 * p.v * p.f_kin**2 / (12.0 * np.pi * p.N * p.a * np.abs(friction_slope(p, w)) ** 2 * w**4)


def default_duration(params: AgeingParams) -> float:
    """Simulated seconds of a run when the caller sets none (Units: s)."""
    return 300.0


def default_dt_out(params: AgeingParams) -> float:
    """Output step of a run when the caller sets none (Units: s)."""
    return 1e-3


def fit_band(params: AgeingParams, dt_out: float | None = None) -> tuple[float, float]:
    """The omega^-4 band: 10 v/a to a tenth of the block's resonance sqrt(N k0 / M) (Units: rad/s)."""
    return 10 * params.v / params.a, math.sqrt(params.N * params.k0 / params.M) / 10


def equivalent_model_I(params: AgeingParams):
    """Model I's parameters that the linearised, B = 0 ageing model reduces to: m eta1 = f_n A / v, the same random
    force (N f_kin = F_kin) and F_drive = F_kin + N f_n A (steady sliding of model I)."""
    from .spring_block import SpringBlockParams
    p = params
    return SpringBlockParams(N=p.N, v=p.v, a=p.a, k0=p.k0, k1=0.0, M=p.M, m=p.m, eta0=p.eta0, alpha=p.alpha,
                             F_kin=p.F_kin, F_drive=p.F_kin + p.N * p.f_n * p.A)


def _renewal_block(p: AgeingParams, rng: np.random.Generator, b: int):
    """Renewals of distance block b, drawn as model I draws them: one per contact in each interval [j a, (j+1) a)."""
    nb = _BLOCK_INTERVALS
    j = np.arange(b * nb, (b + 1) * nb, dtype=float)
    r_pos = rng.random((p.N, nb))
    r_val = rng.random((p.N, nb))
    pos = ((j[None, :] + r_pos) * p.a).ravel()
    idx = np.repeat(np.arange(p.N), nb)
    val = (p.alpha * p.f_kin * (r_val - 0.5)).ravel()
    order = np.argsort(pos, kind="stable")
    return pos[order], idx[order].astype(np.int64), val[order]


def _initial_state(p: AgeingParams, rng: np.random.Generator):
    """Model I's start: steady sliding (v_i = v, steady state, each spring carrying f_n mu_v), then the first random
    forces switched on, which the massless contacts answer at once by a jump of speed. Returns the state, the
    random forces, the kernel's parameter vector, the error scales and the renewal state (nan: none)."""
    N = p.N
    first = p.alpha * p.f_kin * (rng.random(N) - 0.5)
    law = _rs.STATE_LAWS[p.law].code
    pars = np.array([N, p.v, p.k0, p.M, p.m * p.eta0, p.F_drive, p.f_n, p.mu_v, p.A, p.B, p.D_c, law,
                     int(p.linear_direct)], dtype=float)
    y = np.zeros(2 + 3 * N)
    y[1] = p.v
    y[2:2 + N] = p.f_n * p.mu_v / p.k0
    y[2 + 2 * N:] = 1.0 if law == 0 else 0.0
    fr = np.zeros(N)
    for i in range(N):
        renew(y, fr, i, first[i], pars, np.nan)
    # error scales: the block's displacement 1e-3 a; its velocity the larger of v and the ringing speed of the block
    # on its springs after one renewal, sqrt(N k0 / M) alpha f_kin / (N k0); stretches f_kin / k0; forces f_n A
    ring = math.sqrt(N * p.k0 / p.M) * max(p.alpha, 1e-3) * p.f_kin / (N * p.k0)
    scale = np.concatenate([[1e-3 * p.a, max(p.v, ring)], np.full(N, p.f_kin / p.k0), np.full(N, p.f_n * p.A),
                            np.ones(N)])
    reset_q = np.nan if p.renewal_state is None else p.renewal_state * p.v / p.D_c
    return y, fr, pars, scale, reset_q


def simulate(params: AgeingParams, duration: float, dt_out: float = 1e-3, seed=None, *, rtol: float = 1e-6,
             max_steps: int = 200_000_000) -> ModelTrace:
    """Simulate model I with ageing contacts and sample the block every ``dt_out`` seconds.

    Starts from steady sliding with the first random forces applied (as model I); the renewal positions and values
    are drawn exactly as model I draws them, so a seed gives both models the same renewals.

    Parameters
    ----------
    params : AgeingParams
    duration, dt_out : float
        Simulated time and output step (Units: s).
    seed : int or numpy.random.Generator
    rtol : float
        Local error tolerance per step, relative to the scales 1e-3 a (z), max(v, the block's ringing speed after
        one renewal) (u), f_kin / k0 (s_i), f_n A (D_i), 1 (state).

    Returns
    -------
    ModelTrace
        ``x`` block position, ``force`` the summed random force averaged over each output interval,
        ``events`` renewal ``times`` and contact ``index``.
    """
    p = params
    check_number("duration", duration, positive=True)
    check_number("dt_out", dt_out, positive=True)
    n = int(round(duration / dt_out))
    if n < 2:
        raise ValueError(f"duration {duration!r} s holds fewer than two output steps of {dt_out!r} s")
    check_number("rtol", rtol, positive=True, below=1e-2)
    rng = np.random.default_rng(seed)
    y, fr, pars, scale, reset_q = _initial_state(p, rng)
    N = p.N
    xs = np.empty(n + 1)  # one sample beyond the last, so that the last force interval is integrated in full
    fsum = np.zeros(n + 1)
    n_ev_est = int(N * (p.v * duration * 1.5 / p.a + 2 * _BLOCK_INTERVALS)) + 16
    ev_time = np.empty(n_ev_est)
    ev_index = np.empty(n_ev_est, dtype=np.int64)
    counters = np.zeros(2, dtype=np.int64)
    pos = np.empty(0)
    idx = np.empty(0, dtype=np.int64)
    val = np.empty(0)
    ptr, b, ev_count, t, h, k_out = 0, 0, 0, 0.0, min(dt_out, 1e-4), 0
    while k_out < n + 1:
        if len(pos) - ptr < 2 * N:
            new = _renewal_block(p, rng, b)
            b += 1
            pos = np.concatenate([pos[ptr:], new[0]])
            idx = np.concatenate([idx[ptr:], new[1]])
            val = np.concatenate([val[ptr:], new[2]])
            ptr = 0
        if ev_count + len(pos) > len(ev_time):
            grow = max(len(ev_time), len(pos))
            ev_time = np.concatenate([ev_time, np.empty(grow)])
            ev_index = np.concatenate([ev_index, np.empty(grow, dtype=np.int64)])
        start = ptr
        t, h, k_out, ptr, new_count, status = run(
            y, fr, t, h, k_out, n + 1, dt_out, xs, fsum, pos, idx, val, ptr, len(pos) - N, pars, rtol, scale, reset_q,
            ev_time, ev_count, max_steps - int(counters.sum()), counters)
        ev_index[ev_count:new_count] = idx[start:ptr]
        ev_count = new_count
        if status == 1:
            raise RuntimeError(f"ageing.simulate: more than max_steps = {max_steps} steps before t = {t:.6g} s")
        if status == 2:
            raise RuntimeError(f"ageing.simulate: the step size underflowed at t = {t:.6g} s: the integrator cannot "
                               f"honour rtol = {rtol!r} there")
    xs = xs[:n]
    if not np.all(np.isfinite(xs)):
        raise FloatingPointError("the ageing model produced non-finite positions; please report the parameters")
    force = fsum[:n] / dt_out
    meta = {
        "model": "I with ageing (rate-and-state) contacts",
        "params": p.to_dict(),
        "seed": seed if isinstance(seed, (int, type(None))) else "Generator",
        "duration": n * dt_out,
        "dt_out": dt_out,
        "rtol": rtol,
        "method": "massless miniblocks; Dormand-Prince 5(4) with dense output, restarted at each renewal; numba",
        "steps_accepted": int(counters[0]),
        "steps_rejected": int(counters[1]),
        "version": package_version(),
        "n_renewals": ev_count,
    }
    events = {"times": ev_time[:ev_count].copy(), "index": ev_index[:ev_count].copy()}
    return ModelTrace(t=np.arange(n) * dt_out, x=xs, force=force, events=events, metadata=meta)


PARAMS = AgeingParams
