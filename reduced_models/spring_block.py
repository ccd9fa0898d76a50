"""Model I: the spring-block model (Xu, Zhou & Persson 2025, section 3-4 and Appendix A).

A block of mass M is tied to N miniblocks of mass m by springs k0 with damping m eta0; each miniblock
feels a kinetic friction f_kin + m eta1 v_i and a random force f_i(t) that renews as the big block slides:
once at a random point within every distance a, to ``alpha f_kin (r - 0.5)`` (eq. 5). Neighbouring
miniblocks are coupled by springs k1 with damping m eta_lat (free ends).

In deviation coordinates about steady sliding (x = x_a + v t + zeta, x_i = v t + zeta_i, with
N k0 x_a = F_drive and N (m eta1 v + f_kin) = F_drive), eqs. (A1)-(A2) become linear with the random
forces as the only input:

    M zeta''   = -k0 sum_i (zeta - zeta_i) - m eta0 sum_i (zeta' - zeta_i')                       (A1)
    m zeta_i'' = -k0 (zeta_i - zeta) - m eta0 (zeta_i' - zeta') - m eta1 zeta_i' - f_i(t) + lateral (A2)

Between renewals the forcing is constant, so the state is propagated exactly in the eigenbasis of the
system matrix (q_k <- e^{lambda_k h} q_k + phi_1(lambda_k h) h g_k), with a step set only by the output
sampling. Renewal times are the times at which the big block's displacement v t + zeta(t) reaches each
renewal position, found by safeguarded Newton iteration on the exact solution.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from frictionnoise.base import check_fields, check_number

from ._checkpoint import load_checkpoint as _load_checkpoint, save_checkpoint as _save_checkpoint
from ._version import package_version
from .spring_block_kernel import BLOCK_INTERVALS, renewal_block  # noqa: F401  (model I's renewal draws, public here)
from .spring_block_kernel import contact_indices, initial_state, modal, run, second_order
from .trace import ModelTrace, check_run

__all__ = [
    "SpringBlockParams", "simulate", "theory_spectrum", "theory_spectrum_coupled", "random_force_spectrum",
    "transfer_function", "asymptotic_spectrum", "mean_renewal_interval", "rms_displacement",
    "displacement_variance", "crossover_frequency", "RESPONSE", "fit_band",
]

RESPONSE = "viscous"  # below omega_c the block follows Z = -1/(i omega m eta1), eq. (A6)


@dataclass(frozen=True)
class SpringBlockParams:
    """Parameters of model I, SI units. Defaults are the paper's reference case (section 4).

    Attributes
    ----------
    N : int
        Number of miniblocks (asperity contact regions).
    v : float
        Mean sliding speed (Units: m/s).
    a : float
        Renewal length: sliding distance over which a miniblock's random force renews once (Units: m).
    k0 : float
        Spring between the block and each miniblock (Units: N/m).
    k1 : float
        Lateral spring between neighbouring miniblocks, free ends (Units: N/m).
    M : float
        Block mass (Units: kg).
    m : float
        Miniblock mass (Units: kg).
    eta0 : float
        Damping rate of the block-miniblock springs; force m eta0 (relative velocity) (Units: 1/s).
    eta1 : float or None
        Damping rate of the miniblock's friction; force m eta1 v_i (Units: 1/s). None: derived from
        steady sliding, N (m eta1 v + f_kin) = F_drive, and re-derived when v, N, m or the forces change.
    eta_lat : float
        Damping rate of the lateral coupling (Units: 1/s).
    alpha : float
        Random force amplitude, f_i = alpha f_kin (r - 0.5) (eq. 5) (dimensionless).
    F_drive : float
        Constant driving force (Units: N).
    F_kin : float
        Total kinetic friction N f_kin (Units: N).
    """

    N: int = 30
    v: float = 0.5e-3
    a: float = 1e-3
    k0: float = 1e4
    k1: float = 1e2
    M: float = 1.0
    m: float = 1e-5
    eta0: float = 0.8e4
    eta1: float | None = None
    eta_lat: float = 0.0
    alpha: float = 1.0
    F_drive: float = 10.0
    F_kin: float = 5.0
    eta1_derived: bool = field(default=False, repr=False)

    def __post_init__(self):
        self._check_fields()
        self._settle_eta1()

    def _check_fields(self):
        """Model I's field checks (ValueError naming the field); model Ib's parameters run them too."""
        check_fields(self, integer=("N",), positive=("N", "v", "a", "k0", "M", "m", "F_drive"),
                     non_negative=("k1", "eta0", "eta_lat", "alpha", "F_kin"))

    def _settle_eta1(self):
        """eta1 from steady sliding, N (m eta1 v + f_kin) = F_drive, when not given (or derived before a replace);
        a given eta1 must satisfy it."""
        if self.eta1 is None or self.eta1_derived:
            if not self.F_drive > self.F_kin:
                raise ValueError(
                    f"F_drive must exceed F_kin = N f_kin for steady sliding with eta1 > 0 "
                    f"(got F_drive = {self.F_drive!r} N, F_kin = {self.F_kin!r} N)"
                )
            object.__setattr__(self, "eta1", (self.F_drive - self.F_kin) / (self.N * self.m * self.v))
            object.__setattr__(self, "eta1_derived", True)
        else:
            check_number("eta1", self.eta1, positive=True)
            if not math.isclose(self.N * (self.m * self.eta1 * self.v + self.f_kin), self.F_drive, rel_tol=1e-6):
                raise ValueError(
                    f"eta1 = {self.eta1!r} 1/s does not give steady sliding at v = {self.v!r} m/s: "
                    f"N (m eta1 v + f_kin) = {self.N * (self.m * self.eta1 * self.v + self.f_kin):.6g} N "
                    f"!= F_drive = {self.F_drive!r} N (leave eta1 unset to derive it)"
                )

    @classmethod
    def reference(cls) -> "SpringBlockParams":
        """The paper's reference case (section 4): eta1 = 3.33e7 1/s follows from steady sliding.

        Returns
        -------
        SpringBlockParams
            N = 30, v = 0.5 mm/s, a = 1 mm, k0 = 1e4 N/m, k1 = 100 N/m, M = 1 kg, m = 1e-5 kg, eta0 = 8e3 1/s, alpha = 1.
        """
        return cls()

    @property
    def f_kin(self) -> float:
        """Kinetic friction per miniblock (Units: N)."""
        return self.F_kin / self.N

    @property
    def tau0(self) -> float:
        """Mean renewal interval of one miniblock, a / v (Units: s)."""
        return self.a / self.v

    def to_dict(self) -> dict:
        """The parameters as a JSON-able dict (SI units).

        Returns
        -------
        dict
            Field name -> value; ``eta1_derived_from_steady_sliding`` says whether eta1 was derived.
        """
        d = asdict(self)
        d.pop("eta1_derived")
        d["eta1_derived_from_steady_sliding"] = self.eta1_derived
        return d


# ----------------------------------------------------------------------------- simulator
def simulate(params: SpringBlockParams, duration: float, dt_out: float = 1e-3, seed=None, *, contacts: bool = False,
             checkpoint: str | None = None, checkpoint_every: float | None = None) -> ModelTrace:
    """Simulate model I exactly and sample the block position every ``dt_out`` seconds.

    The block's motion depends only on the 2-DOF system of the block and the sum of the miniblocks, driven by
    the summed random force (the lateral forces cancel in the sum; see :func:`.spring_block_kernel.reduced_second_order`),
    and so do the renewal times, which are keyed to the block's displacement. That system is what is propagated
    unless ``contacts`` asks for the miniblocks themselves.

    Parameters
    ----------
    params : SpringBlockParams
    duration : float
        Simulated time (Units: s); ``round(duration / dt_out)`` samples are returned, the first at t = 0.
    dt_out : float
        Output step (Units: s). Any value works: propagation is exact between renewals.
    seed : int or numpy.random.Generator
    contacts : bool or sequence of int
        Also return miniblock displacements zeta_i(t_k) (``events["contacts"]``, shape (n, len), Units: m; all
        miniblocks for True, ``events["contact_index"]`` says which), from the full (N+1)-body system with the
        lateral springs k1, eta_lat: the only outputs those springs change. The block's trace is the same to
        the rounding of the eigen-decomposition (4.4e-14 m over 900 s of the reference case, where zeta is
        ~2e-3 m); the cost is ~5x the reduced run plus each requested miniblock's output.
    checkpoint, checkpoint_every : str, float
        If given, the full state is written (atomically) to ``checkpoint`` every ``checkpoint_every``
        simulated seconds, and a run started with the same file resumes from it: the result is identical,
        bit for bit, to an uninterrupted run (test: a run killed with SIGKILL and resumed).

    Returns
    -------
    ModelTrace
        ``x`` the big block's displacement, ``force`` the summed random force sum_i f_i averaged over each
        output interval, ``events`` with ``times`` (s) and ``index`` (miniblock) of every renewal.
    """
    check_run(duration, dt_out)
    n = int(round(duration / dt_out))
    md = modal(params, contacts)
    n_rows = md.C_r.shape[0]
    key_seed = seed if not n_rows else ("contacts", tuple(contact_indices(params, contacts).tolist()), seed)
    st = (_load_checkpoint(checkpoint, params, n, dt_out, key_seed) if checkpoint else None) or initial_state(
        params, md, n, duration, seed)
    save = (lambda state: _save_checkpoint(checkpoint, params, n, dt_out, key_seed, state)) if checkpoint else None
    run(params, md, st, n, dt_out, checkpoint_every, save)
    x, ev_count = st["x"], st["ev_count"]
    meta = {"model": "I (spring-block)", "params": params.to_dict(), "duration": n * dt_out, "dt_out": dt_out,
            "seed": seed if isinstance(seed, (int, type(None))) else "Generator", "version": package_version(),
            "method": ("exact modal propagation between renewals of the " + ("full (N+1)-body system" if contacts else
                       "2-DOF system block + sum of miniblocks") + "; renewal times by Newton on the exact solution"),
            "n_renewals": ev_count}
    events = {"times": st["ev_time"][:ev_count].copy(), "index": st["ev_index"][:ev_count].copy()}
    if n_rows:
        events["contacts"] = st["xc"]
        events["contact_index"] = contact_indices(params, contacts)
    return ModelTrace(t=np.arange(n) * dt_out, x=x, force=st["f"], events=events, metadata=meta)


# ----------------------------------------------------------------------------- theory
def random_force_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """C_f(omega) of one miniblock's random force, eq. (A8).

    The renewal interval's <cos omega tau> is closed as exp(-s^2 omega^2/2) cos(omega tau0), s^2 = tau0^2 / 6.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    numpy.ndarray
        C_f at ``omega`` (Units: N^2 s).
    """
    w = np.asarray(omega, dtype=float)
    tau0 = params.tau0
    mean_cos = np.exp(-(tau0**2 / 6.0) * w**2 / 2.0) * np.cos(w * tau0)
    return params.v / (12.0 * np.pi * params.a) * params.f_kin**2 * params.alpha**2 / w**2 * (1.0 - mean_cos)


def transfer_function(params: SpringBlockParams, omega) -> np.ndarray:
    """Z(omega) = -P0 / S of eq. (A5): zeta(omega) = Z (1/N) sum_i f_i(omega). Ignores k1.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    numpy.ndarray of complex
        Z at ``omega`` (Units: m/N).
    """
    w = np.asarray(omega, dtype=float)
    p = params
    iw = 1j * w
    Q0 = -p.M * w**2 + p.N * p.k0 + iw * p.N * p.m * p.eta0
    Q1 = -p.m * w**2 + p.k0 + iw * p.m * (p.eta0 + p.eta1)
    P0 = p.N * p.k0 + iw * p.N * p.m * p.eta0
    P1 = p.k0 + iw * p.m * p.eta0
    return -P0 / (Q0 * Q1 - P0 * P1)


def theory_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """C_x(omega) = ``|Z|^2 C_f / N``, eq. (A10), with the full Z of (A5) and C_f of (A8).

    C_f uses the paper's cumulant closure of <cos omega tau> (:func:`reduced_models.multiscale.theory_spectrum`
    offers the exact one).

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s), two-sided in angular frequency (eq. 2).
    """
    return np.abs(transfer_function(params, omega)) ** 2 * random_force_spectrum(params, omega) / params.N


def theory_spectrum_coupled(params: SpringBlockParams, omega) -> np.ndarray:
    """C_x(omega) with the lateral coupling k1, eta_lat included.

    ``sum_i |Z_i|^2 C_f``, Z_i from the full (N+1)-body dynamic stiffness (the generalisation of eq. A10 to
    non-identical miniblocks); one linear solve per frequency.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (Units: m^2 s).
    """
    Mm, D, K = second_order(params)
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    out = np.empty(len(w))
    rhs = np.zeros((params.N + 1, params.N))
    rhs[1 + np.arange(params.N), np.arange(params.N)] = -1.0
    for i, wi in enumerate(w):
        Zrow = np.linalg.solve(-wi**2 * Mm + 1j * wi * D + K, rhs)[0]
        out[i] = np.sum(np.abs(Zrow) ** 2)
    return out * random_force_spectrum(params, w)


def asymptotic_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """The omega^-4 asymptote, eq. (A11): alpha^2 v f_kin^2 / (12 pi N a (m eta1)^2 omega^4).

    Equals eq. (6)/(A12), alpha^2 v^3 / (12 pi N a omega^4), when m eta1 v = f_kin. Valid for v/a << omega << omega_c.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    omega : array_like
        Angular frequencies (Units: rad/s), positive.

    Returns
    -------
    numpy.ndarray
        The asymptote at ``omega`` (Units: m^2 s).
    """
    w = np.asarray(omega, dtype=float)
    p = params
    return p.alpha**2 * p.v * p.f_kin**2 / (12.0 * np.pi * p.N * p.a * (p.m * p.eta1) ** 2 * w**4)


def crossover_frequency(params: SpringBlockParams) -> float:
    """omega_c, the top of the omega^-4 band.

    The block-on-springs resonance sqrt(N k0 / M), or the viscous crossover N m eta1 / M if that is lower; from the
    expansion of S(omega) in (A5).

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).

    Returns
    -------
    float
        omega_c (Units: rad/s).
    """
    p = params
    return min(math.sqrt(p.N * p.k0 / p.M), p.N * p.m * p.eta1 / p.M)


def fit_band(params: SpringBlockParams, dt_out: float | None = None) -> tuple[float, float]:
    """The omega^-4 band of eq. (6): 10 v/a to omega_c / 10.

    May be empty (hi < 2 lo) when v/a approaches omega_c; callers then fall back on the automatic band.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    dt_out : float, optional
        Output step (Units: s); unused (the band does not depend on it), accepted as every model's ``fit_band`` is.

    Returns
    -------
    tuple of float
        (low, high) (Units: rad/s).
    """
    return 10 * params.v / params.a, crossover_frequency(params) / 10


def mean_renewal_interval(params: SpringBlockParams) -> float:
    """Mean time between renewals on the whole block, a / (N v) (Fig. 14).

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).

    Returns
    -------
    float
        The interval (Units: s).
    """
    return params.a / (params.N * params.v)


def displacement_variance(params: SpringBlockParams, L0) -> np.ndarray:
    """<(zeta(t + L0/v) - zeta(t))^2> for L0 >> a: the random walk of Appendix A.

    Each renewal interval tau of a force u moves the block by -u tau / (N m eta1); with the renewal rate
    N v / a, <u^2> = alpha^2 f_kin^2 / 12 and <tau^2> = 7 tau0^2 / 6 this diffuses as
    7 alpha^2 a L0 f_kin^2 / (72 N (m eta1 v)^2), i.e. 7 alpha^2 a L0 / (72 N) when m eta1 v = f_kin.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    L0 : float or array_like
        Sliding distance (Units: m).

    Returns
    -------
    numpy.ndarray
        The variance (Units: m^2).
    """
    p = params
    L0 = np.asarray(L0, dtype=float)
    return 7.0 * p.alpha**2 * p.a * L0 * p.f_kin**2 / (72.0 * p.N * (p.m * p.eta1 * p.v) ** 2)


def rms_displacement(params: SpringBlockParams, L0) -> np.ndarray:
    """zeta_rms after sliding L0, eq. (A13): sqrt(7 / (72 pi^2) L0 a / N) (times alpha f_kin / (m eta1 v)).

    The paper's estimate with the low-frequency cut-off omega_0 = pi v / L0.

    Parameters
    ----------
    params : SpringBlockParams
        The model's parameters (SI units).
    L0 : float or array_like
        Sliding distance (Units: m).

    Returns
    -------
    numpy.ndarray
        zeta_rms (Units: m).
    """
    return np.sqrt(displacement_variance(params, L0) / np.pi**2)


# What the sweep, the report and `frictionnoise compare` read of this model through reduced_models.MODELS
# (the protocol is described in reduced_models/__init__.py).
PARAMS = SpringBlockParams
SWEEP_SERIES = "x"  # a sweep task returns the spectrum of the block's displacement, C_x


def default_duration(params: SpringBlockParams) -> float:
    """Simulated seconds of a run when the caller sets none (Units: s)."""
    return 300.0


def default_dt_out(params: SpringBlockParams) -> float:
    """Output step of a run when the caller sets none (Units: s)."""
    return 1e-3
