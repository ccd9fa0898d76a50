"""Model Ib: the multiscale spring-block model the paper proposes (Xu, Zhou & Persson 2025, Fig. 1c and
sections 10-11): model I (eqs. A1-A2) with n microblocks elastically tied to each miniblock::

    M x''     = F_drive - sum_i [k0 (x - x_i) + m eta0 (x' - x_i')]
    m x_i''   = -k0 (x_i - x) - m eta0 (x_i' - x') - m eta1 x_i' - f_kin - f_i(t)
                - sum_j [k2 (x_i - y_ij) + m2 eta2 (x_i' - y_ij')]
    m2 y_ij'' = -k2 (y_ij - x_i) - m2 eta2 (y_ij' - x_i') - m2 eta3 y_ij' - f_kin2 - f_ij(t)

f_i renews as in model I (once at a uniformly random point of each window a of the block's sliding, to
alpha f_kin (r - 0.5), eq. 5); f_ij renews the same way over windows a2, to alpha2 f_kin2 (r - 0.5). Steady
sliding: F_drive = N (m eta1 v + f_kin) + N n (m2 eta3 v + f_kin2). With n = 0 this is model I.

Exact simulation (O(1) per renewal)
-----------------------------------
In deviations about steady sliding, with S = sum_i zeta_i and U = sum_ij (y_ij - steady), the sums of the
equations over identical blocks close on (zeta, S, U) (the lateral springs k1 cancel in the sum):

    M zeta'' = -k0 (N zeta - S) - m eta0 (N zeta' - S')
    m S''    = -k0 (S - N zeta) - m eta0 (S' - N zeta') - m eta1 S' - k2 (n S - U) - m2 eta2 (n S' - U') - F1
    m2 U''   = -k2 (U - n S) - m2 eta2 (U' - n S') - m2 eta3 U' - F2

driven only by the force sums F1 = sum_i f_i and F2 = sum_ij f_ij. Renewal times are keyed to the block's
displacement, which this 3-DOF system alone determines; so a renewal costs a Newton solve on 6 modes and
an update of one force sum, whatever N and n (:mod:`reduced_models._two_level`).

Theory: the transfer-function route of Appendix A, one level down
------------------------------------------------------------------
Fourier transform, per microblock (zeta_ij its deviation):  Q2 zeta_ij = P2 zeta_i - f_ij, with
Q2 = -m2 w^2 + k2 + i w m2 (eta2 + eta3), P2 = k2 + i w m2 eta2. Per miniblock, (A3) gains the micro
springs: (Q1 + n P2) zeta_i = P1 zeta + P2 sum_j zeta_ij - f_i. Eliminating zeta_ij::

    Q1~ zeta_i = P1 zeta - (f_i + T2 sum_j f_ij),    Q1~ = Q1 + n P2 (Q2 - P2) / Q2,   T2 = P2 / Q2,

i.e. the miniblock carries, in series, the micro spring P2 and the microblock's own impedance
Q2 - P2 = -m2 w^2 + i w m2 eta3 (n of them in parallel), and the micro forces reach it filtered by T2. (A4)
is unchanged, so (A5) holds with Q1 -> Q1~: zeta = Z~ (1/N) sum_i (f_i + T2 sum_j f_ij), Z~ = -P0 / (Q0 Q1~
- P0 P1). With all forces independent, (A10) becomes::

    C_x(w) = |Z~(w)|^2 / N * [ C_f1(w) + n |T2(w)|^2 C_f2(w) ],

C_f1 and C_f2 from (A8) with (a, alpha f_kin) and (a2, alpha2 f_kin2). n = 0 gives (A10) exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictionnoise.base import check_fields

from . import spring_block as _m1
from .correlation import contact_force_spectrum
from .multiscale_kernel import CROSSING_TOL, simulate_two_level
from .trace import ModelTrace, check_run

__all__ = ["MultiscaleParams", "simulate", "theory_spectrum", "theory_components", "transfer_functions",
           "asymptotic_spectrum", "micro_macro_ratio", "crossover_frequency", "regime_frequencies", "RESPONSE",
           "fit_band"]

RESPONSE = "viscous"  # below omega_c the block follows Z~ = -1/(i omega (m eta1 + n m2 eta3))


@dataclass(frozen=True)
class MultiscaleParams(_m1.SpringBlockParams):
    """Parameters of model Ib, SI units. Defaults are :meth:`reference`.

    Model I's fields, inherited from :class:`~reduced_models.spring_block.SpringBlockParams` with their names,
    meaning and checks (k1 and eta_lat do not act on the block). Added:

    n_micro : int
        Microblocks (micro-asperity contacts) per miniblock; 0 is model I.
    m2 : float
        Microblock mass (Units: kg).
    k2 : float
        Spring between a miniblock and each of its microblocks (Units: N/m).
    eta2 : float
        Damping rate of that spring; force m2 eta2 (relative velocity) (Units: 1/s).
    eta3 : float
        Damping rate of the microblock's friction; force m2 eta3 y' (Units: 1/s).
    a2 : float
        Micro renewal length (Units: m).
    alpha2 : float
        Micro random force amplitude, f_ij = alpha2 f_kin2 (r - 0.5).
    F_kin2 : float
        Total micro kinetic friction N n f_kin2 (Units: N); must be 0 when n_micro = 0.
    eta1 : float or None
        None: derived from F_drive = N (m eta1 v + f_kin) + N n (m2 eta3 v + f_kin2).
    """

    n_micro: int = 10
    m2: float = 1e-11
    k2: float = 100.0
    eta2: float = 5e6
    eta3: float = 2e10
    a2: float = 1e-5
    alpha2: float = 1.0
    F_kin2: float = 0.03

    def __post_init__(self):
        self._check_fields()  # model I's field checks first (each names its field)
        check_fields(self, integer=("n_micro",), positive=("m2", "k2", "a2"),  # the scene's micro-pads: the same check
                     non_negative=("eta2", "eta3", "alpha2", "F_kin2"))
        n = self.n_micro
        if n == 0 and self.F_kin2 != 0:
            raise ValueError(f"F_kin2 = N n f_kin2 must be 0 when n_micro = 0 (got {self.F_kin2!r})")
        micro = self.micro_friction
        if self.eta1 is None or self.eta1_derived:
            if not self.F_drive > self.F_kin + micro:
                raise ValueError(f"F_drive = {self.F_drive!r} N must exceed F_kin + N n (m2 eta3 v + f_kin2) = "
                                 f"{self.F_kin + micro:.6g} N for steady sliding with eta1 > 0")
            eta1 = (self.F_drive - self.F_kin - micro) / (self.N * self.m * self.v)
            object.__setattr__(self, "eta1", eta1)
            object.__setattr__(self, "eta1_derived", True)
        self.macro  # model I's steady-sliding check on the macro level (eta1 > 0, given or derived)
        total = self.N * (self.m * self.eta1 * self.v + self.f_kin) + micro
        if not math.isclose(total, self.F_drive, rel_tol=1e-6):
            raise ValueError(f"eta1 = {self.eta1!r} 1/s does not give steady sliding: N (m eta1 v + f_kin) + "
                             f"N n (m2 eta3 v + f_kin2) = {total:.6g} N != F_drive = {self.F_drive!r} N "
                             "(leave eta1 unset to derive it)")

    @property
    def micro_friction(self) -> float:
        """The microblocks' steady friction N n (m2 eta3 v + f_kin2) (Units: N; 0 when n = 0)."""
        return self.N * self.n_micro * self.m2 * self.eta3 * self.v + self.F_kin2 if self.n_micro else 0.0

    @classmethod
    def reference(cls) -> "MultiscaleParams":
        """The paper's reference case (section 4) with a micro level, from contact mechanics.

        Each macro contact (D = 1 mm) holds n = 10 micro contacts of D2 = 10 um. As the paper does for the
        miniblocks: k2 ~ E D2 = 1e7 Pa * 1e-5 m = 100 N/m; m2 = 1e-11 kg, ten times rho D2^3 (the paper's
        m = 1e-5 kg is ten times rho D^3); a2 = D2 (sliding one contact diameter renews it). eta2 = 5e6 1/s is
        0.79 of critical damping 2 sqrt(k2 / m2) = 6.3e6 1/s. A micro contact carries the frictional shear
        stress tau_f ~ 1 MPa over D2^2: f_kin2 = 1e-4 N, so F_kin2 = N n f_kin2 = 0.03 N; its velocity
        dependence mirrors the paper's macro choice m eta1 v = f_kin: m2 eta3 v = f_kin2, eta3 = 2e10 1/s;
        alpha2 = 1 as alpha. eta1 = 3.29e7 1/s follows from steady sliding.

        Fairness of renewals keyed to the block's sliding: a micro contact's deflection f_kin2 / k2 =
        (tau_f / E) D2 = 1e-6 m = 0.1 a2 (0.2 a2 with its viscous force, 0.05 a2 for the random part), so it
        slides with its miniblock and renews once per a2 of sliding. This stops holding when tau_f approaches
        E (F_kin2 -> N n k2 a2 = 0.3 N here), or when alpha2 f_kin2 / (2 k2) approaches a2: the contact then
        sticks over distances beyond its size and its renewals follow its own stick-slip, not the block.
        A weaker caveat: the miniblock itself moves against the block by up to alpha f_kin / (2 k0) =
        8e-6 m = 0.8 a2 after a macro renewal, so micro renewal phases (not their rate) are off by up to one
        micro interval.

        Returns
        -------
        MultiscaleParams
            Model I's reference case with the micro level above.
        """
        return cls()

    @property
    def f_kin2(self) -> float:
        """Kinetic friction per microblock, F_kin2 / (N n) (Units: N); 0 when n = 0."""
        return self.F_kin2 / (self.N * self.n_micro) if self.n_micro else 0.0

    @property
    def tau2(self) -> float:
        """Mean renewal interval of one microblock, a2 / v (Units: s)."""
        return self.a2 / self.v

    @property
    def macro(self) -> _m1.SpringBlockParams:
        """Model I's parameters with this eta1: the macro level alone (F_drive reduced by the micro friction)."""
        return _m1.SpringBlockParams(N=self.N, v=self.v, a=self.a, k0=self.k0, k1=self.k1, M=self.M, m=self.m,
                                     eta0=self.eta0, eta1=self.eta1, eta_lat=self.eta_lat, alpha=self.alpha,
                                     F_drive=self.F_drive - self.micro_friction, F_kin=self.F_kin)

    def to_dict(self) -> dict:
        """The parameters as a JSON-able dict (SI units).

        Returns
        -------
        dict
            Model I's fields (as :meth:`SpringBlockParams.to_dict`), the micro level's, and f_kin, f_kin2 (N).
        """
        d = super().to_dict()
        d.update(f_kin=self.f_kin, f_kin2=self.f_kin2)
        return d


# ----------------------------------------------------------------------------- simulator
def simulate(params: MultiscaleParams, duration: float, dt_out: float = 1e-3, seed=None, *,
             micro_events: bool = False, crossing_tol: float = CROSSING_TOL) -> ModelTrace:
    """Simulate model Ib exactly between renewals and sample the block position every ``dt_out`` seconds.

    The macro renewals use the same random numbers as :func:`reduced_models.spring_block.simulate` with the
    same seed; the micro ones a child stream (``Generator.spawn``). With n_micro = 0 the run is model I's
    (same solver, same trace bit for bit). ``crossing_tol``: renewal crossings are located to this fraction of
    a2 in position (default 1e-6, i.e. 2e-8 s at the reference; the motion between renewals is exact
    whatever it is; benchmarks/bench_multiscale.py gives its cost against the trajectory error).

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    duration : float
        Simulated time (Units: s); ``round(duration / dt_out)`` samples, the first at t = 0.
    dt_out : float, optional
        Output step (Units: s).
    seed : int or numpy.random.Generator, optional
        Seed of the renewals' random numbers.
    micro_events : bool, optional
        Also return the micro renewal times (``events["micro_times"]``, Units: s).
    crossing_tol : float, optional
        Tolerance of the renewal crossings, as a fraction of a2 (dimensionless).

    Returns
    -------
    ModelTrace
        ``x`` the block's position, ``force`` the summed random force F1 + F2 averaged over each output
        interval; ``events``: ``times``, ``index`` of the macro renewals, ``force_micro`` (F2 averaged per
        interval), ``n_micro_renewals``, and ``micro_times`` if ``micro_events``.
    """
    check_run(duration, dt_out)
    if params.n_micro == 0:
        tr = _m1.simulate(params.macro, duration, dt_out, seed=seed)
        meta = {**tr.metadata, "model": "Ib (multiscale), n = 0: model I", "params": params.to_dict()}
        return ModelTrace(t=tr.t, x=tr.x, force=tr.force, events={**tr.events, "force_micro": np.zeros(len(tr.t)),
                          "n_micro_renewals": 0}, metadata=meta)
    return simulate_two_level(params, duration, dt_out, seed, micro_events, crossing_tol)


# ----------------------------------------------------------------------------- theory
def transfer_functions(params: MultiscaleParams, omega):
    """(Z~, T2): zeta = Z~ (1/N) sum_i (f_i + T2 sum_j f_ij), (A5) with Q1 -> Q1~ (module docstring).

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    Z : numpy.ndarray of complex
        The block's response to the mean miniblock force (Units: m/N).
    T2 : numpy.ndarray of complex
        How much of a micro force reaches its miniblock (dimensionless).
    """
    w = np.asarray(omega, dtype=float)
    p = params
    iw = 1j * w
    Q0 = -p.M * w**2 + p.N * p.k0 + iw * p.N * p.m * p.eta0
    P0 = p.N * p.k0 + iw * p.N * p.m * p.eta0
    Q1 = -p.m * w**2 + p.k0 + iw * p.m * (p.eta0 + p.eta1)
    P1 = p.k0 + iw * p.m * p.eta0
    Q2 = -p.m2 * w**2 + p.k2 + iw * p.m2 * (p.eta2 + p.eta3)
    P2 = p.k2 + iw * p.m2 * p.eta2
    Q1t = Q1 + p.n_micro * P2 * (Q2 - P2) / Q2
    return -P0 / (Q0 * Q1t - P0 * P1), P2 / Q2


def theory_components(params: MultiscaleParams, omega, closure: str = "cumulant"):
    """(macro, micro) parts of C_x: ``|Z~|^2 C_f1 / N`` and ``|Z~|^2 n |T2|^2 C_f2 / N``.

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.
    closure : {"cumulant", "exact"}, optional
        How eq. (A8) averages <cos omega tau> over the renewal interval (see :func:`theory_spectrum`).

    Returns
    -------
    macro, micro : numpy.ndarray
        The two parts at ``omega`` (Units: m^2 s); their sum is :func:`theory_spectrum`.
    """
    p = params
    Z, T2 = transfer_functions(p, omega)
    Cf1 = contact_force_spectrum(p.v, p.a, p.alpha * p.f_kin, omega, closure)
    Cf2 = contact_force_spectrum(p.v, p.a2, p.alpha2 * p.f_kin2, omega, closure)
    return np.abs(Z) ** 2 * Cf1 / p.N, np.abs(Z) ** 2 * p.n_micro * np.abs(T2) ** 2 * Cf2 / p.N


def theory_spectrum(params: MultiscaleParams, omega, closure: str = "cumulant") -> np.ndarray:
    """C_x(omega) = ``|Z~|^2 / N [C_f1 + n |T2|^2 C_f2]``, the generalisation of eq. (A10).

    ``closure``: how eq. (A8) averages <cos omega tau> over the renewal interval tau = tau0 (1 + r - r')
    (tau0 = a / v, r and r' uniform), at both levels: "cumulant" (default, the paper's) a Gaussian of tau's mean
    and variance, exp(-s^2 omega^2 / 2) cos(omega tau0), s^2 = tau0^2 / 6; "exact" tau's own triangular law,
    cos(omega tau0) sinc^2(omega tau0 / 2), as the simulators draw it. They differ by under 0.03 % below
    omega tau0 = 0.5 and by at most 5 % near omega tau0 = 4-6. With n = 0 it equals
    :func:`reduced_models.spring_block.theory_spectrum` (closure "cumulant").

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s; omega = 2 pi f), positive.
    closure : {"cumulant", "exact"}, optional
        How eq. (A8) averages <cos omega tau> over the renewal interval (see :func:`theory_spectrum`).

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s), two-sided in angular frequency (eq. 2).
    """
    c1, c2 = theory_components(params, omega, closure)
    return c1 + c2


def micro_macro_ratio(params: MultiscaleParams) -> float:
    """R = n (a / a2) (alpha2 f_kin2 / (alpha f_kin))^2, the micro part of C_x over the macro part.

    Where both forces are white (omega >> v/a2) and T2 ~ 1 (omega << omega3 = k2 / (m2 eta3)).

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).

    Returns
    -------
    float
        R (dimensionless); inf when the macro force has no fluctuation.
    """
    p = params
    if p.alpha * p.f_kin == 0:
        return math.inf
    return p.n_micro * (p.a / p.a2) * (p.alpha2 * p.f_kin2 / (p.alpha * p.f_kin)) ** 2


def crossover_frequency(params: MultiscaleParams) -> float:
    """omega_x, where the micro part overtakes the macro part below v/a2.

    There the micro force is still flat (C_f2 -> 7 a2 (alpha2 f_kin2)^2 / (144 pi v)) while the macro one falls as
    v (alpha f_kin)^2 / (12 pi a omega^2) (A9), so their ratio is R (7/12) (omega a2 / v)^2 and
    omega_x = (v / a2) sqrt(12 / (7 R)) (valid for R >> 1, omega_x >> v/a).

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).

    Returns
    -------
    float
        omega_x (Units: rad/s), or nan if the micro part never overtakes (R < 12/7).
    """
    R = micro_macro_ratio(params)
    if not R > 12.0 / 7.0:
        return math.nan
    return params.v / params.a2 * math.sqrt(12.0 / (7.0 * R))


def regime_frequencies(params: MultiscaleParams) -> dict:
    """The corner frequencies that bound the regimes of C_x.

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).

    Returns
    -------
    dict
        (Units: rad/s) ``v_over_a`` and ``v_over_a2`` (renewal rates); ``omega3`` = k2 / (m2 eta3) (the micro
        contact relaxes through its own friction: T2 falls as omega3/omega above); ``omega_c`` (block resonance
        sqrt(N k0 / M) or viscous N c / M, as in model I); ``omega2`` = sqrt(k2/m2) (micro resonance; overdamped
        when eta3 > omega2); ``omega_x`` (the crossover, nan if none).
    """
    p = params
    c = p.m * p.eta1 + p.n_micro * p.m2 * p.eta3
    return {"v_over_a": p.v / p.a, "v_over_a2": p.v / p.a2, "omega3": p.k2 / (p.m2 * p.eta3) if p.eta3 else math.inf,
            "omega_c": min(math.sqrt(p.N * p.k0 / p.M), p.N * c / p.M), "omega2": math.sqrt(p.k2 / p.m2),
            "omega_x": crossover_frequency(p)}


def asymptotic_spectrum(params: MultiscaleParams, omega, regime: str) -> np.ndarray:
    """Power-law asymptotes of the two parts of C_x, with c = m eta1 + n m2 eta3 (Z~ -> -1/(i omega c)).

    - "macro": v/a << omega << omega_c: alpha^2 v f_kin^2 / (12 pi N a c^2 omega^4) (eq. A11), gamma = 4;
    - "micro_low": omega << v/a2, omega_c: 7 n a2 (alpha2 f_kin2)^2 / (144 pi N v c^2 omega^2), gamma = 2;
    - "micro_white": v/a2 << omega << omega3, omega_c: n alpha2^2 v f_kin2^2 / (12 pi N a2 c^2 omega^4), 4;
    - "micro_filtered": omega3, v/a2 << omega << omega_c: "micro_white" * (omega3 / omega)^2, gamma = 6.

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.
    regime : {"macro", "micro_low", "micro_white", "micro_filtered"}
        Which asymptote.

    Returns
    -------
    numpy.ndarray
        The asymptote at ``omega`` (Units: m^2 s).
    """
    p = params
    w = np.asarray(omega, dtype=float)
    c = p.m * p.eta1 + p.n_micro * p.m2 * p.eta3
    if regime == "macro":
        return p.alpha**2 * p.v * p.f_kin**2 / (12 * np.pi * p.N * p.a * c**2 * w**4)
    white = p.n_micro * p.alpha2**2 * p.v * p.f_kin2**2 / (12 * np.pi * p.N * p.a2 * c**2 * w**4)
    if regime == "micro_low":
        return 7 * p.n_micro * p.a2 * (p.alpha2 * p.f_kin2) ** 2 / (144 * np.pi * p.N * p.v * c**2 * w**2)
    if regime == "micro_white":
        return white
    if regime == "micro_filtered":
        return white * (regime_frequencies(p)["omega3"] / w) ** 2
    raise ValueError(f"regime must be macro, micro_low, micro_white or micro_filtered (got {regime!r})")


def fit_band(params: MultiscaleParams, dt_out: float | None = None) -> tuple[float, float]:
    """The macro omega^-4 band as in model I: 10 v/a to omega_c / 10.

    Parameters
    ----------
    params : MultiscaleParams
        The model's parameters (SI units).
    dt_out : float, optional
        Output step (Units: s); unused, accepted as every model's ``fit_band`` is.

    Returns
    -------
    tuple of float
        (low, high) (Units: rad/s).
    """
    return 10 * params.v / params.a, regime_frequencies(params)["omega_c"] / 10


# What the sweep, the report and `frictionnoise compare` read of this model through reduced_models.MODELS
# (the protocol is described in reduced_models/__init__.py).
PARAMS = MultiscaleParams
SWEEP_SERIES = "x"  # a sweep task returns the spectrum of the block's displacement, C_x


def default_duration(params: MultiscaleParams) -> float:
    """Simulated seconds of a run when the caller sets none (Units: s)."""
    return 300.0


def default_dt_out(params: MultiscaleParams) -> float:
    """Output step of a run when the caller sets none (Units: s)."""
    return 1e-3
