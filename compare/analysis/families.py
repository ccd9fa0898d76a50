"""Spectral families: what each registered model predicts of C_x(omega) in the parameters a record can identify.

Every registered model (:data:`reduced_models.MODELS`) has an omega^-4 range, so an exponent alone never names a
mechanism; the corners, resonances and level steps do (Xu, Zhou & Persson 2025, Appendices A and B). A family is the
model's displacement spectrum rewritten in those parameters, the sliding speed v being known from the record:

- model I (eqs. A5-A11): ``L omega^-4 R(omega a / v) G(omega)``, the omega^-4 level L (proportional to
  alpha^2 v f_kin^2 / (N a (m eta1)^2), eq. A11), the renewal length a (corner near v/a), the block's resonance
  omega_c = sqrt(N k0 / M), its quality Q, the contact springs' damping corner omega_0 = k0 / (m eta0) and the
  contacts' own friction rate omega_1 = eta1 (their inertia). Q is the resonance's quality as the record shows it,
  with both dampings: 1 / Q = 1 / Q_c + omega_c / omega_0, Q_c = N m eta1 / (M omega_c) the contacts' own (at
  r = 1 and omega_c << omega_0, G's imaginary part is 1 / Q_c + omega_c / omega_0). A record places the
  resonance's width, not its two sources apart: with Q_c as the parameter, Q_c and omega_0 trade along a flat
  direction wherever omega_0 lies above the band, and Q_c's interval held the resonance's width, not Q_c. R(x) = 1 - cos(x)
  sinc^2(x / 2) is the renewal force's (1 - <cos omega tau>) of eq. (A8) over the renewal interval's own law,
  tau = (a / v)(1 + r - r') with r, r' uniform, as the simulators and the scenes' patch tracks draw it (the paper's
  cumulant closure exp(-x^2/12) cos x differs from it by up to 5 % at x = 4-6, which long records resolve);
  G = |(1 - r^2 / (1 + i omega / omega_0))(1 + i omega / omega_1) + i r / Q_c|^-2, r = omega / omega_c, is
  |Z|^2 (m eta1 omega)^2 of eq. (A5) exactly (the miniblock's inertia in the factor with omega_1: negligible for the
  paper's reference, omega / eta1 ~ 1e-5, but 10-30 % at the resonance's flanks for a scene's 1 g pads).
- model Ib: model I plus the micro level ``L2 omega^-4 R(omega a2 / v) / (1 + (omega / omega3)^2)``.
- model II (eq. B2 and eq. 3): ``S C_x^(1)(omega; s, 1/omega_hi, 1/omega_lo)``, the closed form of one particle of
  force 1 N on a 1 kg block with both states' mean times log-uniform in [1/omega_hi, 1/omega_lo] and
  c(tau) ~ tau^kappa, beta + beta' = s = 2 - 4 kappa: the level S = n c^2 / M^2, s and the two corners, never beta
  and beta' apart. Between the corners (B2) falls as gamma = 6 - s / 2 up to a logarithm (each state's term
  P c^2 ~ tau^-beta, averaged through 1 / (tau + tau') over the other state's times, gives C_F ~ omega^(beta - 2)):
  the paper's C_F ~ omega^(beta + beta' - 3), gamma = 7 - s, agrees with it at s = 2 (flicker noise) only.
- model III (section 6): ``L omega^-4 sinc^2(omega w / (2 v))``, gamma = 4 below 2 pi v / w and 6 above, with the
  window's zeros at multiples of 2 pi v / w (the continuum limit of the sampled moving window).
- the ageing model: model I (without omega_1: its miniblocks are massless) with the contacts' friction slope
  c(omega) = c_inf (1 - b / (1 + i omega D_c / v)), b = B / A, in place of m eta1, in the level and the resonance's
  damping: a level step of (A / (A - B))^2 below v / D_c.
- model_Iv (the shaken block) is model I's family at its mean speed, plus its line at the vibration frequency (a
  nuisance term of the fit). Exact where every contact slides through the whole cycle (m eta1 V > alpha f_kin / 2
  + A sqrt(k0^2 + (m eta0 omega_v)^2): the Coulomb part never engages and the model is linear); where contacts
  stick for part of each cycle the record's resonance lies below sqrt(N k0 / M) (0.4-0.8 % measured at A = 10-60 um,
  omega_v = 2000-3000 rad/s) and its quality below the mean-field one: no closed form is stated for that shift.

A parameter is identified by a record only when its feature (the frequency listed for it by
:meth:`Family.feature`) lies inside the record's band by at least :data:`MARGIN`; otherwise it is "not identified".
Every family here takes the sliding speed v (m/s) as known.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

import reduced_models
from reduced_models import ageing, asperity_force, multiscale, spring_block, vibrating_block, wear_particle

from .family_kernels import contact_spectrum, window_spectrum

__all__ = ["Param", "Family", "FAMILIES", "MARGIN", "family_of", "identified", "contacts_quality"]

MARGIN = 10**0.25  # a feature counts as inside a band when it lies a quarter decade inside either end


@dataclass(frozen=True)
class Param:
    """One parameter of a family.

    Attributes
    ----------
    name : str
    unit : str
        Its SI unit as printed (e.g. "m^2 s^-3").
    log : bool
        Fitted as its logarithm (a positive scale).
    bounds : tuple of float
        The range a fit may search (Units: ``unit``).
    neutral : float or None
        The value at which the parameter's feature vanishes (no step, no micro level): where a record does not
        identify it, a fit holds it there so that the levels it does identify keep their meaning.
    """

    name: str
    unit: str
    log: bool
    bounds: tuple
    neutral: float | None = None


@dataclass(frozen=True)
class Family:
    """A spectral family: C_x(omega) in the parameters a record can identify.

    Attributes
    ----------
    name : str
    params : tuple of Param
    shape : callable
        ``shape(theta, omega, v)``: C_x (Units: m^2 s, two-sided, eq. 2) at angular frequencies ``omega`` (rad/s),
        ``theta`` a dict name -> value in the parameters' units, ``v`` the sliding speed (m/s).
    features : callable
        ``features(theta, v)``: dict name -> the angular frequency (rad/s) where that parameter's feature lies, or
        None for a level (identified wherever the family has any band).
    from_model : callable
        ``from_model(params)``: (theta, v) of a registered model's parameter point.
    cannot_separate : str
        The combinations of the model's own parameters a record cannot take apart.
    line : bool
        The model adds a spectral line (a nuisance term of the fit).
    smooth : bool
        Smooth on a 0.5 % frequency scale (a fit may group ordinates); False for model III, whose window's zeros
        repeat every 2 pi v / w and need every ordinate.
    """

    name: str
    params: tuple
    shape: Callable
    features: Callable
    from_model: Callable
    cannot_separate: str
    line: bool = False
    smooth: bool = True

    def spectrum(self, theta: dict, omega, v: float) -> np.ndarray:
        """C_x(omega) (Units: m^2 s) at ``theta`` (dict name -> value) and sliding speed ``v`` (m/s)."""
        missing = [p.name for p in self.params if p.name not in theta]
        if missing:
            raise ValueError(f"family {self.name!r}: theta lacks {missing[0]!r}")
        return self.shape(theta, np.asarray(omega, dtype=float), v)

    def feature(self, name: str, theta: dict, v: float):
        """The angular frequency (rad/s) of parameter ``name``'s feature, or None for a level."""
        return self.features(theta, v)[name]


def identified(feature, band) -> bool:
    """Whether a feature at angular frequency ``feature`` (rad/s; None: a level) lies inside ``band`` (lo, hi)
    (rad/s) by at least :data:`MARGIN`."""
    if feature is None:
        return True
    lo, hi = band
    return bool(lo * MARGIN <= feature <= hi / MARGIN)


# ----------------------------------------------------------------------------- shapes
def contacts_quality(Q: float, omega_c: float, omega_0: float) -> float:
    """The contacts' own quality Q_c from the resonance's Q and the springs' share omega_c / omega_0:
    1 / Q_c = 1 / Q - omega_c / omega_0 (module docstring); NaN where the springs alone damp more than Q says
    (no physical point: a fit's likelihood is then infinite)."""
    inv = 1.0 / Q - omega_c / omega_0
    return 1.0 / inv if inv > 0 else math.nan


def _contact(th, w, v, **extra):
    Qc = contacts_quality(th["Q"], th["omega_c"], th["omega_0"])
    if not math.isfinite(Qc):
        return np.full(np.shape(w), math.nan)
    return contact_spectrum(w, L=th["L"], a_v=th["a"] / v, omega_c=th["omega_c"], Q=Qc, omega_0=th["omega_0"],
                            **extra)


def _model_I(th, w, v):
    return _contact(th, w, v, inv_omega_1=1.0 / th["omega_1"])


def _model_Ib(th, w, v):
    return _contact(th, w, v, inv_omega_1=1.0 / th["omega_1"], L2=th["L2"], a2_v=th["a2"] / v, omega3=th["omega3"])


def _ageing(th, w, v):
    # massless miniblocks: no inertia term
    return _contact(th, w, v, b=th["b"], dc_v=th["D_c"] / v)


def _model_III(th, w, v):
    return window_spectrum(w, L=th["L"], width=th["w"], v=v)


_N_NODES = 384  # log-spaced nodes of model II's closed form; interpolated in log-log between them
_ORDER = 6  # Gauss-Legendre points per half decade of mean times: within 2e-9 of 12 points for s = 1-3


def _model_II(th, w, v):
    kappa = (2.0 - th["s"]) / 4.0
    lo, hi = sorted((th["omega_lo"], th["omega_hi"]))  # the two corners, whichever way a search names them
    law = wear_particle.DurationLaw(1.0 / hi, 1.0 / lo)
    one = wear_particle.WearParticleParams(n_particles=1, trapped=law, sliding=law, c_A=1.0, c_B=1.0,
                                           kappa_A=kappa, kappa_B=kappa, M=1.0, v=v)
    w = np.asarray(w, dtype=float)
    if w.size <= _N_NODES:
        return th["S"] * wear_particle.theory_spectrum(one, w, order=_ORDER)
    # the closed form is smooth on a log scale (corners of Lorentzians): 384 nodes over the band, log-log
    # interpolation, within 1e-4 of the direct evaluation (tests/compare/test_families.py)
    nodes = np.geomspace(w.min(), w.max(), _N_NODES)
    vals = np.log(wear_particle.theory_spectrum(one, nodes, order=_ORDER))
    return th["S"] * np.exp(np.interp(np.log(w), np.log(nodes), vals))


# ----------------------------------------------------------------------------- from a model's parameters
def _I_point(p, slope, v, mass=None):
    """Model I's family point at the contacts' friction slope ``slope`` (N s/m) and speed ``v`` (m/s); ``mass`` the
    miniblock's (kg; None: massless, omega_1 at its bound)."""
    wc = math.sqrt(p.N * p.k0 / p.M)
    w0 = p.k0 / (p.m * p.eta0) if p.eta0 > 0 else _I_PARAMS[4].bounds[1]
    w1 = slope / mass if mass else _I_PARAMS[5].bounds[1]
    L = p.alpha**2 * v * p.f_kin**2 / (12 * np.pi * p.N * p.a * slope**2)  # eq. (A11)
    Q = 1.0 / (p.M * wc / (p.N * slope) + wc / w0)  # both dampings (module docstring)
    return {"L": L, "a": p.a, "omega_c": wc, "Q": Q, "omega_0": w0, "omega_1": w1}


def _from_I(p):
    return _I_point(p, p.m * p.eta1, p.v, p.m), p.v


def _from_Iv(p):
    V, s1 = vibrating_block.steady_state(p)
    return _I_point(p, s1, V, p.m), V


def _from_Ib(p):
    c = p.m * p.eta1 + p.n_micro * p.m2 * p.eta3
    th = _I_point(p, c, p.v, p.m + p.n_micro * p.m2)
    th.update(L2=float(multiscale.asymptotic_spectrum(p, 1.0, "micro_white")), a2=p.a2,
              omega3=multiscale.regime_frequencies(p)["omega3"])
    return th, p.v


def _from_ageing(p):
    c_inf = p.f_n * p.A / p.v  # the friction slope above v / D_c, where the state cannot follow
    th = _I_point(p, c_inf, p.v)
    del th["omega_1"]  # massless miniblocks
    th.update(b=p.B / p.A, D_c=p.D_c)
    return th, p.v


def _from_II(p):
    if p.trapped != p.sliding or p.kappa_A != p.kappa_B or p.trapped.kind != "exponential":
        raise ValueError("model II's family is stated for equal exponential duration laws and kappa_A = kappa_B "
                         "(the record sees their sum beta + beta' only)")
    S = p.n_particles * (p.c_A**2 + p.c_B**2) / 2 / p.M**2
    return {"S": S, "s": 2 - 2 * (p.kappa_A + p.kappa_B), "omega_lo": 1 / p.trapped.tau_max,
            "omega_hi": 1 / p.trapped.tau_min}, p.v


def _from_III(p):
    # continuum limit of the sampled window: C_F(0) = sigma_g^2 dt N_w^2 / (2 pi)
    L = asperity_force.grid_force_variance(p) * p.dt * p.N_w**2 / (2 * np.pi * p.M**2)
    return {"L": L, "w": p.w}, p.v


# ----------------------------------------------------------------------------- the registry
_LEVEL4 = "m^2 s^-3"  # C_x omega^4: m^2 s (rad/s)^4
_I_PARAMS = (Param("L", _LEVEL4, True, (1e-40, 1e10)), Param("a", "m", True, (1e-9, 1e3)),
             Param("omega_c", "rad/s", True, (1e-3, 1e9)), Param("Q", "", True, (0.05, 1e4)),
             Param("omega_0", "rad/s", True, (1e-3, 1e12)), Param("omega_1", "rad/s", True, (1e-3, 1e12)))


def _I_features(th, v):
    # the springs' damping corner shows where the block's fall steepens from omega^-8 to omega^-6, at omega_0 itself
    return {"L": None, "a": 2 * v / th["a"], "omega_c": th["omega_c"], "Q": th["omega_c"], "omega_0": th["omega_0"],
            "omega_1": th.get("omega_1")}


_I_SEP = "alpha, N, f_kin and m eta1 only through the level L ~ alpha^2 v f_kin^2 / (N a (m eta1)^2) (eq. A11)"

FAMILIES: dict = {}
FAMILIES["model_I"] = Family("model_I", _I_PARAMS, _model_I, _I_features, _from_I, _I_SEP)
FAMILIES["model_Iv"] = replace(FAMILIES["model_I"], name="model_Iv", from_model=_from_Iv, line=True,
                               cannot_separate=_I_SEP + "; the vibration only through its line and the mean speed")
FAMILIES["model_Ib"] = Family(
    "model_Ib",
    _I_PARAMS + (Param("L2", _LEVEL4, True, (1e-40, 1e10), neutral=1e-40), Param("a2", "m", True, (1e-12, 1e3)),
                 Param("omega3", "rad/s", True, (1e-3, 1e9))),
    _model_Ib, lambda th, v: {**_I_features(th, v), "L2": 2 * v / th["a2"], "a2": 2 * v / th["a2"],
                              "omega3": th["omega3"]},
    _from_Ib, _I_SEP + "; n, alpha2, f_kin2 only through the micro level L2")
FAMILIES["model_ageing"] = Family(
    "model_ageing",
    _I_PARAMS[:5] + (Param("b", "", False, (0.0, 0.99), neutral=0.0), Param("D_c", "m", True, (1e-12, 1e3))),
    _ageing, lambda th, v: {**_I_features(th, v), "b": v / th["D_c"], "D_c": v / th["D_c"]},
    _from_ageing, "f_n A (with alpha, N, f_kin) only through the level; B / A through the step (A / (A - B))^2")
FAMILIES["model_II"] = Family(
    "model_II",
    (Param("S", "N^2 kg^-2", True, (1e-40, 1e20)), Param("s", "", False, (-2.0, 4.0)),
     Param("omega_lo", "rad/s", True, (1e-6, 1e8)), Param("omega_hi", "rad/s", True, (1e-6, 1e8))),
    _model_II, lambda th, v: {"S": None, "s": math.sqrt(th["omega_lo"] * th["omega_hi"]), "omega_lo": th["omega_lo"],
                              "omega_hi": th["omega_hi"]},
    _from_II, "the number of particles, their forces and the mass only through S = n c^2 / M^2; beta and beta' "
              "only through their sum s")
FAMILIES["model_III"] = Family(
    "model_III", (Param("L", _LEVEL4, True, (1e-40, 1e10)), Param("w", "m", True, (1e-9, 1e3))),
    _model_III, lambda th, v: {"L": None, "w": 2 * np.pi * v / th["w"]},
    _from_III, "the contacts' number, forces and the mass only through the level L", smooth=False)


def family_of(model: str) -> Family:
    """The spectral family of registered model ``model`` (a key of :data:`reduced_models.MODELS`).

    Returns
    -------
    Family
        KeyError naming the models with a family otherwise.
    """
    if model not in reduced_models.MODELS:
        raise KeyError(f"no model {model!r}; registered: {', '.join(reduced_models.MODELS)}")
    try:
        return FAMILIES[model]
    except KeyError:
        raise KeyError(f"model {model!r} declares no spectral family (compare/analysis/families.py); "
                       f"families: {', '.join(FAMILIES)}") from None
