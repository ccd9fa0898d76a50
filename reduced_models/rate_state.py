"""Rate-and-state friction and the single spring-slider of the geophysics literature.

The law (Dieterich 1979; Ruina 1983; see Marone, Annu. Rev. Earth Planet. Sci. 26, 643 (1998)):

    mu(V, theta) = mu0 + A ln(V / V0) + B ln(V0 theta / D_c)

with one of two state laws (the registry :data:`STATE_LAWS`):

    ageing (Dieterich):  d theta / dt = 1 - V theta / D_c
    slip (Ruina):        d theta / dt = -(V theta / D_c) ln(V theta / D_c)

Steady state: theta_ss = D_c / V, mu_ss = mu0 + (A - B) ln(V / V0).

The spring-slider (per unit area): a spring of stiffness k (Pa/m) pulled at V_lp loads a slider under normal
stress sigma (Pa); the quasi-dynamic balance with radiation damping eta (Pa s/m; Rice 1993, eta = G / (2 c_s)) is

    k (V_lp t - delta) + tau_0 = sigma mu(V, theta) + eta V.

Differentiated in time and written in psi = ln(V / V0), phi = ln(V0 theta / D_c) (so that V and theta, which span
many decades in stick-slip, are integrated with a relative accuracy):

    dphi/dt = (V0 / D_c) e^-phi - V / D_c             (ageing)     or   -(V / D_c)(psi + phi)   (slip)
    dpsi/dt = [k (V_lp - V) - sigma B dphi/dt] / (sigma A + eta V)
    ddelta/dt = V

Linearised about steady sliding at V, the friction answers a velocity perturbation with the frequency-dependent
rate sensitivity d mu / d ln V = A - B / (1 + i omega D_c / V) (:func:`rate_sensitivity`), which gives the
critical stiffness k_c = sigma (B - A) / D_c and, at k_c, the neutral oscillation at angular frequency
(V / D_c) sqrt((B - A) / A) (Ruina 1983; Gu, Rice, Ruina & Tse, J. Mech. Phys. Solids 32, 167 (1984)).
With radiation damping the characteristic equation is

    (sigma A + eta V) (D_c / V) s^2 + (sigma (A - B) + eta V + k D_c) s + k V = 0,

so eta shifts k_c by -eta V / D_c and the period by the factor sqrt(1 + eta V / (sigma A)): the default eta keeps
both within 1e-4 of the quasi-static closed forms at the default parameters (:meth:`SpringSliderParams.quasi_static_error`).

Integration: an embedded Dormand-Prince 5(4) pair with its 4th-order dense output (Hairer, Norsett & Wanner,
Solving ODEs I, sec. II.5-6), step-size control on the local error in (psi, phi) (absolute, i.e. relative in V
and theta) and in delta (relative to D_c + |delta|), compiled with numba. In log variables the system is only
mildly stiff (stiffness ratio k D_c / (sigma A) near steady sliding), so the explicit pair takes steps set by
accuracy except for very stiff springs; ``python -m compare.studies.rate_state_work_precision`` gives its
work-precision table against a Radau (implicit, stiff) solution at rtol 1e-13.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from frictionnoise.base import check_fields, check_number

from ._version import package_version
from .rate_state_kernel import DORMAND_PRINCE, segment

__all__ = [
    "SpringSliderParams", "SliderTrace", "STATE_LAWS", "simulate", "friction", "steady_state_mu",
    "steady_state_theta", "critical_stiffness", "onset_period", "onset_frequency", "rate_sensitivity",
    "velocity_step_mu", "healing_per_decade", "characteristic_roots", "DORMAND_PRINCE",
]


@dataclass(frozen=True)
class StateLaw:
    """One state evolution law: its name, the kernel's code, and theta after a slip ``s`` at constant V from theta0
    (the exact solution used by :func:`velocity_step_mu`)."""

    name: str
    code: int
    doc: str

    def theta_after_slip(self, theta0, V, D_c, s):
        theta0, s = np.asarray(theta0, dtype=float), np.asarray(s, dtype=float)
        if self.code == 0:  # ageing: theta' = 1 - V theta / D_c, linear in theta with rate V / D_c per unit time
            return D_c / V + (theta0 - D_c / V) * np.exp(-s / D_c)
        # slip: ln(V theta / D_c) decays as exp(-s / D_c)
        return D_c / V * np.exp(np.log(V * theta0 / D_c) * np.exp(-s / D_c))


STATE_LAWS = {
    "ageing": StateLaw("ageing", 0, "d theta/dt = 1 - V theta / D_c (Dieterich): theta grows as time in stationary contact"),
    "slip": StateLaw("slip", 1, "d theta/dt = -(V theta / D_c) ln(V theta / D_c) (Ruina): theta evolves only with slip"),
}


@dataclass(frozen=True)
class SpringSliderParams:
    """Rate-and-state spring-slider, SI units per unit area.

    Defaults: a laboratory rock case (A, B, D_c of the order of Marone 1998's Table; rsfmodel's example, a = 0.005,
    b = 0.01, D_c = 10 um, V = 1 um/s) under 10 MPa with the spring at twice k_c (steady sliding stable).

    Attributes
    ----------
    A : float
        Direct-effect coefficient, > 0 (dimensionless).
    B : float
        Evolution-effect coefficient, >= 0 (dimensionless).
    D_c : float
        Critical slip distance, > 0 (Units: m).
    mu0 : float
        Friction coefficient at steady sliding at V0 (dimensionless).
    V0 : float
        Reference speed, > 0 (Units: m/s).
    sigma : float
        Normal stress, > 0 (Units: Pa).
    k : float
        Spring stiffness per unit area, > 0 (Units: Pa/m).
    V_lp : float
        Load-point speed, >= 0 (Units: m/s).
    law : str
        State law, a key of :data:`STATE_LAWS` ("ageing" or "slip").
    eta : float
        Radiation damping, >= 0 (Units: Pa s/m). Default G / (2 c_s) for G = 30 GPa, c_s = 3 km/s. eta = 0 is the
        quasi-static slider, accepted only for k >= k_c (below k_c its slip speed runs away in finite time).
    """

    A: float = 0.005
    B: float = 0.01
    D_c: float = 1e-5
    mu0: float = 0.6
    V0: float = 1e-6
    sigma: float = 1e7
    k: float = 1e10
    V_lp: float = 1e-6
    law: str = "ageing"
    eta: float = 5e6
    _law: StateLaw = field(default=None, repr=False, compare=False)

    def __post_init__(self):
        check_fields(self, positive=("A", "D_c", "V0", "sigma", "k"), non_negative=("B", "V_lp", "eta"))
        check_number("mu0", self.mu0)
        if self.law not in STATE_LAWS:
            raise ValueError(f"law must be one of {sorted(STATE_LAWS)} (got {self.law!r})")
        object.__setattr__(self, "_law", STATE_LAWS[self.law])
        kc = critical_stiffness(self)
        if self.eta == 0 and self.k < kc:
            raise ValueError(f"k = {self.k:.4g} Pa/m is below k_c = {kc:.4g} Pa/m with eta = 0: the quasi-static "
                             f"slider runs away in finite time there (give eta > 0)")

    def quasi_static_error(self, V: float | None = None) -> float:
        """Relative shift of k_c by radiation damping, eta V / (sigma |B - A|) (or eta V / (sigma A) if B = A)."""
        V = self.V_lp if V is None else V
        return self.eta * V / (self.sigma * (abs(self.B - self.A) or self.A))

    def to_dict(self) -> dict:
        d = asdict(self)
        d.pop("_law")
        return d


@dataclass(frozen=True)
class SliderTrace:
    """A sampled spring-slider run.

    Attributes
    ----------
    t : ndarray
        Times (Units: s), uniform from 0.
    V : ndarray
        Slip speed (Units: m/s).
    mu : ndarray
        Friction coefficient mu(V, theta).
    theta : ndarray
        State (Units: s).
    slip : ndarray
        Slip delta since t = 0 (Units: m).
    load : ndarray
        Load-point displacement since t = 0 (Units: m).
    metadata : dict
        Parameters, tolerance, steps taken, method.
    """

    t: np.ndarray
    V: np.ndarray
    mu: np.ndarray
    theta: np.ndarray
    slip: np.ndarray
    load: np.ndarray
    metadata: dict = field(default_factory=dict)


# ----------------------------------------------------------------------------- closed forms
def friction(params: SpringSliderParams, V, theta):
    """mu = mu0 + A ln(V / V0) + B ln(V0 theta / D_c) (dimensionless)."""
    p = params
    return p.mu0 + p.A * np.log(np.asarray(V) / p.V0) + p.B * np.log(p.V0 * np.asarray(theta) / p.D_c)


def steady_state_theta(params: SpringSliderParams, V):
    """theta_ss = D_c / V, both state laws (Units: s)."""
    return params.D_c / np.asarray(V, dtype=float)


def steady_state_mu(params: SpringSliderParams, V):
    """mu_ss = mu0 + (A - B) ln(V / V0) (dimensionless)."""
    return params.mu0 + (params.A - params.B) * np.log(np.asarray(V, dtype=float) / params.V0)


def rate_sensitivity(A, B, D_c, V, omega):
    """d mu / d ln V at angular frequency omega about steady sliding at V: A - B / (1 + i omega D_c / V).

    Both state laws linearise to d(delta ln theta)/dt = -(V / D_c)(delta ln theta + delta ln V). The limits are the
    direct effect A (omega >> V / D_c) and the steady-state slope A - B (omega << V / D_c). Complex, dimensionless.
    """
    w = np.asarray(omega, dtype=float)
    return A - B / (1.0 + 1j * w * D_c / V)


def critical_stiffness(params: SpringSliderParams, V: float | None = None, quasi_static: bool = True) -> float:
    """k_c = sigma (B - A) / D_c (Units: Pa/m); with ``quasi_static=False``, the radiation-damped value
    (sigma (B - A) - eta V) / D_c at speed V (default V_lp). Negative when steady sliding is always stable."""
    p = params
    kc = p.sigma * (p.B - p.A) / p.D_c
    if not quasi_static:
        kc -= p.eta * (p.V_lp if V is None else V) / p.D_c
    return kc


def onset_frequency(params: SpringSliderParams, V: float | None = None) -> float:
    """Angular frequency of the neutral oscillation at k_c, (V / D_c) sqrt((B - A) / A) (Units: rad/s)."""
    p = params
    V = p.V_lp if V is None else V
    if not p.B > p.A:
        raise ValueError(f"B must exceed A for an oscillatory onset (got A = {p.A!r}, B = {p.B!r})")
    return V / p.D_c * math.sqrt((p.B - p.A) / p.A)


def onset_period(params: SpringSliderParams, V: float | None = None) -> float:
    """Period of the neutral oscillation at k_c, 2 pi D_c / (V sqrt((B - A) / A)) (Units: s)."""
    return 2.0 * math.pi / onset_frequency(params, V)


def characteristic_roots(params: SpringSliderParams, V: float | None = None) -> np.ndarray:
    """Roots s (1/s) of the linearised radiation-damped slider about steady sliding at V (module docstring):
    steady sliding is stable iff both have negative real parts."""
    p = params
    V = p.V_lp if V is None else V
    L = p.D_c / V
    return np.roots([(p.sigma * p.A + p.eta * V) * L, p.sigma * (p.A - p.B) + p.eta * V + p.k * p.D_c, p.k * V])


def velocity_step_mu(params: SpringSliderParams, V1: float, V2: float, slip):
    """Friction after the slip speed is stepped from V1 (steady state) to V2, as a function of the slip since the
    step (Units: m): the direct effect A ln(V2 / V1) at slip 0, then the state evolving over D_c at constant V2
    (exact for both laws: :meth:`StateLaw.theta_after_slip`). An infinitely stiff machine's response."""
    p = params
    theta = p._law.theta_after_slip(p.D_c / V1, V2, p.D_c, slip)
    return friction(p, V2, theta)


def healing_per_decade(params: SpringSliderParams) -> float:
    """Growth of the peak friction per decade of hold time in slide-hold-slide with the ageing law, B ln 10, for
    holds long against D_c / V_lp on a stiff machine (theta grows as the hold time) (dimensionless)."""
    return params.B * math.log(10.0)


# ----------------------------------------------------------------------------- simulator
def _check_run(duration, dt_out, rtol):
    check_number("duration", duration, positive=True)
    check_number("dt_out", dt_out, positive=True)
    n = int(round(duration / dt_out))
    if n < 2:
        raise ValueError(f"dt_out = {dt_out!r} s leaves fewer than two output samples in duration = {duration!r} s")
    if n > 10**8:
        raise ValueError(f"dt_out = {dt_out!r} s asks for {n} samples (more than 1e8): give a larger dt_out")
    check_number("rtol", rtol, positive=True, below=1e-2, why="the local error tolerance of the integrator")
    if rtol < 1e-13:
        raise ValueError(f"rtol must be >= 1e-13 (got {rtol!r}): below it the double-precision steps cannot honour it")
    return n


def simulate(params: SpringSliderParams, duration: float, dt_out: float | None = None, V_init: float | None = None,
             theta_init: float | None = None, *, load_steps=None, rtol: float = 1e-8,
             max_steps: int = 50_000_000) -> SliderTrace:
    """Integrate the spring-slider (module docstring) and sample it every ``dt_out`` seconds.

    Parameters
    ----------
    params : SpringSliderParams
    duration : float
        Simulated time (Units: s); ``round(duration / dt_out)`` samples, the first at t = 0.
    dt_out : float, optional
        Output step (Units: s); default duration / 10000. Any value: outputs come from the dense output, so the
        integrator's steps are set by ``rtol`` alone.
    V_init : float, optional
        Initial slip speed (Units: m/s), > 0; default V_lp (V0 if V_lp = 0).
    theta_init : float, optional
        Initial state (Units: s), > 0; default steady state at V_init, D_c / V_init.
    load_steps : sequence of (t, V_lp), optional
        Piecewise-constant load-point speed: from each time t (s) on, the load point moves at V_lp (m/s); before
        the first entry it moves at ``params.V_lp``. The integrator restarts at each switch (no step across it).
    rtol : float
        Local error tolerance per step: absolute in ln V and ln theta (so relative in V and theta), relative to
        D_c + |slip| in slip. Between 1e-13 and 1e-2.
    max_steps : int
        Accepted plus rejected steps allowed before RuntimeError.

    Returns
    -------
    SliderTrace
    """
    p = params
    dt_out = duration / 10000 if dt_out is None else dt_out
    n = _check_run(duration, dt_out, rtol)
    V_init = (p.V_lp if p.V_lp > 0 else p.V0) if V_init is None else check_number("V_init", V_init, positive=True)
    theta_init = p.D_c / V_init if theta_init is None else check_number("theta_init", theta_init, positive=True)
    segments = [(0.0, p.V_lp)]
    for t_s, v_s in (load_steps or []):
        check_number("load_steps time", t_s, non_negative=True)
        check_number("load_steps V_lp", v_s, non_negative=True)
        if t_s <= segments[-1][0] and len(segments) > 1:
            raise ValueError(f"load_steps times must increase (got {t_s!r} after {segments[-1][0]!r})")
        if t_s == 0.0:
            segments[0] = (0.0, v_s)
        else:
            segments.append((float(t_s), float(v_s)))
    t_final = (n - 1) * dt_out
    y = np.array([math.log(V_init / p.V0), math.log(p.V0 * theta_init / p.D_c), 0.0])
    out = np.empty((n, 3))
    out[0] = y
    counters = np.zeros(2, dtype=np.int64)
    t, h, k_out = 0.0, min(dt_out, 1e-3 * p.D_c / V_init), 1
    for j, (t0, vlp) in enumerate(segments):
        t_end = min(segments[j + 1][0], t_final) if j + 1 < len(segments) else t_final
        if t_end <= t:
            continue
        pars = np.array([p.sigma, p.k, p.A, p.B, p.D_c, p.V0, p.eta, vlp])
        t, h, k_out, status = segment(y, t, t_end, h, k_out, n, dt_out, out, pars, p._law.code, rtol,
                                       max_steps - counters.sum(), counters)
        if status == 1:
            raise RuntimeError(f"rate_state.simulate: more than max_steps = {max_steps} steps before t = {t:.6g} s "
                               f"(rtol = {rtol!r}); raise max_steps or rtol")
        if status == 2:
            raise RuntimeError(f"rate_state.simulate: the step size underflowed at t = {t:.6g} s: the integrator "
                               f"cannot honour rtol = {rtol!r} there (slip speed {p.V0 * math.exp(y[0]):.3g} m/s)")
    if k_out < n:  # the last sample lies on t_final up to rounding
        out[k_out:] = y
    t_arr = np.arange(n) * dt_out
    V = p.V0 * np.exp(out[:, 0])
    theta = p.D_c / p.V0 * np.exp(out[:, 1])
    mu = p.mu0 + p.A * out[:, 0] + p.B * out[:, 1]
    load = np.zeros(n)
    for j, (t0, vlp) in enumerate(segments):
        t1 = segments[j + 1][0] if j + 1 < len(segments) else np.inf
        load += vlp * np.clip(np.minimum(t_arr, t1) - t0, 0.0, None)
    meta = {
        "model": "rate-and-state spring-slider",
        "params": p.to_dict(),
        "duration": n * dt_out,
        "dt_out": dt_out,
        "V_init": V_init,
        "theta_init": theta_init,
        "load_steps": [list(s) for s in segments],
        "rtol": rtol,
        "steps_accepted": int(counters[0]),
        "steps_rejected": int(counters[1]),
        "method": "Dormand-Prince 5(4) with 4th-order dense output in (ln V, ln theta, slip), numba",
        "version": package_version(),
    }
    return SliderTrace(t=t_arr, V=V, mu=mu, theta=theta, slip=out[:, 2].copy(), load=load, metadata=meta)
