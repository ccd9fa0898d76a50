"""Rate-and-state friction on each sliding body: f = mu0 N_pad + c v + N_pad mu_rs(v, theta), theta one state per pad.

The velocity-and-state part is the regularised law of Rice, Lapusta & Ranjith (2001) (also Lapusta et al. 2000),

    mu_rs(V, theta) = A asinh[ V / (2 V0) exp(psi / A) ],    psi = mu_ref + B ln(V0 theta / D_c),        (1)

which equals the rate-and-state law mu_ref + A ln(V / V0) + B ln(V0 theta / D_c) of
:mod:`reduced_models.rate_state` once X = V exp(psi / A) / (2 V0) >> 1 (asinh X = ln 2X + 1 / (4 X^2) + ...:
X ~ 150 in pads_rate_state) and stays finite (zero) at V = 0, where the log form diverges. It is odd in V.
The Coulomb part mu0 N_pad is pymunk's contact solver's, as for every law (mu0 = 0 leaves only (1)).

Stepping: after each pymunk step (springs, contacts, drive: v* = v + dt F / m), one numba kernel,
:func:`rs_step`, on the velocities read through pymunk.batch:

1. the state, exactly at the step's speed V = |v| (pymunk moved the body with its start-of-step velocity v, the one
   this kernel wrote after the previous step) held over the step: the ageing law
   theta' = 1 - V theta / D_c gives theta(t + dt) = theta e^-x + dt (1 - e^-x) / x, x = V dt / D_c (dt at V = 0);
   the slip law, ln(V theta / D_c) decaying as e^-x, gives theta(t + dt) = (D_c / V)(V theta / D_c)^(e^-x)
   (unchanged at V = 0). Both are exact for constant V, hence unconditionally stable;
2. the friction (1) as an implicit (backward Euler) impulse on the body's velocity at the new state,
   m (u - v*) = -dt N_pad mu_rs(u, theta), solved by safeguarded Newton in [0, v*] (mu_rs is increasing and odd in
   u, so the root is unique and |u| <= |v*|): unconditionally stable however steep the slope dmu_rs/dV
   (A exp(psi / A) / (2 V0) at V = 0, far above the explicit limit m / (N_pad dt)); u is written back through
   pymunk.batch as the body's velocity, the one pymunk moves it with over the next step (Lie splitting: the other
   forces explicit as pymunk steps them, the law implicit; first order in dt).

What remains explicit is the coupling of the state to the speed over a step; its accuracy needs the state's
relaxation resolved, V dt / D_c <= 0.1 at the drive's speed (checked at load), and the splitting needs the pad's
spring period resolved as every law does (the arrangement's dt limit). A state the slider must reach through
fast slips (stick-slip) is aged at each step's speed, so the slips' state drop is resolved while V dt / D_c stays
small during them (the spring-slider's slips reach 50 V: 0.05).

The recorder reads the law's drag in the log law's form; here that is the steady-state law,
N_pad (A - B) ln(1 + v / v_ss), v_ss = V0 exp(-mu_ref / (A - B)) (B < A; none for B >= A), so the recorded drag
and the energy balance leave out the state's excursions from steady state.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
import pymunk.batch as PB

from .law import LAWS, FrictionSpec
from .linear import Linear
from .log import log_slope

STATE_LAWS = {"ageing": 0, "slip": 1}
RESOLVE = 0.1  # largest V dt / D_c at the steady speed: the state's relaxation length resolved by 10 steps


@dataclass(frozen=True)
class RateStateSpec(FrictionSpec):
    """A, B: direct and evolution coefficients; D_c (m): the state's slip distance; V0 (m/s): the reference speed;
    mu_ref: the rate-and-state friction at steady sliding at V0 (above the Coulomb mu0); theta0 (s): the pads'
    initial state (None: the steady value D_c / v at the scene's speed); state_law: "ageing" or "slip"; c (N s/m):
    an optional viscous part (>= 0)."""

    law: str = "rate_state"
    mu0: float = 0.0
    c: float = 0.0
    A: float = 0.01
    B: float = 0.005
    D_c: float = 1e-5
    V0: float = 1e-6
    mu_ref: float = 0.1
    theta0: float | None = None
    state_law: str = "ageing"


def steady_mu(v: float, A: float, B: float, V0: float, mu_ref: float) -> float:
    """mu_rs of (1) in steady state theta = D_c / v (v >= 0): A asinh(e^(mu_ref / A) (v / V0)^(1 - B / A) / 2)."""
    if v <= 0.0:
        if B < A:
            return 0.0
        return A * math.asinh(0.5 * math.exp(mu_ref / A)) if B == A else math.inf
    ln_x = mu_ref / A + (1.0 - B / A) * math.log(v / V0) - math.log(2.0)
    return A * (ln_x + math.log1p(math.exp(-2 * ln_x)) / 2 + math.log(2.0)) if ln_x > 20 else A * math.asinh(math.exp(ln_x))


@LAWS.register
class RateState(Linear):
    """Per sliding body a state theta (s), aged per step in numba; the friction (1) applied as an implicit impulse
    through pymunk.batch (module docstring)."""

    name = "rate_state"
    scene_units = {"V0": "velocity"}
    Spec = RateStateSpec
    impulses_after_step = True
    per_step_impulses = True
    positive = frozenset({"A", "D_c", "V0", "theta0"})
    non_negative = frozenset({"mu0", "c", "B", "mu_ref"})
    choices = {"state_law": tuple(STATE_LAWS)}

    @property
    def reduced_model(self) -> str:
        """model_ageing for velocity-strengthening steady sliding (B < A: pads sliding steadily, their noise);
        the spring-slider (B >= A: stick-slip below k_c)."""
        return "model_ageing" if self.spec.B < self.spec.A else "spring_slider"

    @property
    def quick_duration(self) -> float:
        return 12.0

    @classmethod
    def validate(cls, s, sc):
        v = sc.drive.v if hasattr(sc.drive, "v") else None
        for load, m in sc.arrangement_part.sliders(sc):
            if v is not None and v * sc.run.dt / s.D_c > RESOLVE:
                raise ValueError(f"friction.D_c = {s.D_c:.3g} m is not resolved by run.dt = {sc.run.dt:.3g} s at "
                                 f"{v:.3g} m/s: V dt / D_c = {v * sc.run.dt / s.D_c:.3g} must be <= {RESOLVE} (the "
                                 "state is updated at the start-of-step speed)")

    def force(self, v, load, c):
        s = self.spec
        return s.mu0 * load + c * v + load * steady_mu(v, s.A, s.B, s.V0, s.mu_ref)

    def slope(self, v, load, c):
        """Steady-state dF/dv: c + N_pad (A - B) X / (v sqrt(1 + X^2)), X the asinh's argument ((A - B) N_pad / v in
        the log regime). The instantaneous slope at fixed state is A N_pad / v there."""
        s = self.spec
        if v <= 0.0:
            return c if s.B < s.A else -math.inf
        ln_x = s.mu_ref / s.A + (1.0 - s.B / s.A) * math.log(v / s.V0) - math.log(2.0)
        r = 1.0 / math.sqrt(1.0 + math.exp(-2 * ln_x)) if ln_x < 300 else 1.0
        return c + load * (s.A - s.B) * r / v

    def steady_v_c(self) -> float:
        """v_ss = V0 exp(-mu_ref / (A - B)) (m/s): the steady law is N_pad (A - B) ln(v / v_ss) in the log regime."""
        s = self.spec
        return s.V0 * math.exp(-s.mu_ref / (s.A - s.B)) if s.B < s.A else math.inf

    def drag_terms(self, load, c):
        s = self.spec
        if s.B < s.A:
            return c, (s.A - s.B) * load, self.steady_v_c()
        return c, 0.0, 1.0

    def describe(self, load, c):
        """The log law's keys (b = A - B, v_c = v_ss: the steady law, for compare's slope) and the law's own."""
        s = self.spec
        ok = s.B < s.A
        return {"law": self.name, "c": c, "b": (s.A - s.B) if ok else 0.0, "v_c": self.steady_v_c() if ok else None,
                "load_per_pad": load, "A": s.A, "B": s.B, "D_c": s.D_c, "V0": s.V0, "mu_ref": s.mu_ref, "mu0": s.mu0,
                "state_law": s.state_law}

    @classmethod
    def described_slope(cls, law, v):
        """The steady law's slope, in the log law's form (b = A - B, v_c = v_ss)."""
        return log_slope(law, v)

    # ------------------------------------------------------------------ scene side (scene units; theta in s)
    def states(self, scene) -> np.ndarray:
        """The sliding bodies' states theta (s), in the order of ``scene.sliders`` (kept across checkpoints)."""
        self._ensure(scene)
        return self.theta

    def _ensure(self, scene):
        """Per sliding body (``scene.sliders`` order): theta (s), started at theta0 or in steady state."""
        if getattr(self, "theta", None) is None or len(self.theta) != len(scene.sliders):
            s = self.spec
            th0 = s.theta0 if s.theta0 is not None else s.D_c / self.sc.steady_velocity  # s (SI)
            self.theta = np.full(len(scene.sliders), th0)

    def _per_body(self, scene):
        """Per body of the space in the batch's order: the index of each sliding body in ``scene.sliders`` (-1 for
        the others), N_pad A (scene force units; 0 for the others) and masses."""
        rd = PB.Buffer()
        PB.get_space_bodies(scene.space, PB.BodyFields.BODY_ID, rd)
        ids = np.frombuffer(rd.int_buf(), dtype=np.int64)
        where = {b.id: k for k, b in enumerate(scene.sliders)}
        idx = np.array([where.get(int(i), -1) for i in ids], dtype=np.int64)
        A = self.spec.A
        NA = np.array([A * scene.slider_load[k] if k >= 0 else 0.0 for k in idx])
        m = np.array([scene.sliders[k].mass if k >= 0 else 1.0 for k in idx])
        return idx, NA, m

    def advance(self, scene, n):
        s = self.spec
        self._ensure(scene)
        idx, NA, m = self._per_body(scene)
        th = np.array([self.theta[k] if k >= 0 else 1.0 for k in idx])
        vp = np.array([scene.sliders[k].velocity.x if k >= 0 else 0.0 for k in idx])
        dt = scene.dt
        params = np.array([s.A, s.B, s.D_c, self.own.V0, s.mu_ref, self.ctx.dt_si, float(STATE_LAWS[s.state_law]),
                           self.ctx.velocity_si])
        step, space, rd, wr = scene.space.step, scene.space, PB.Buffer(), PB.Buffer()
        acc = np.zeros(NA.size)  # the law's impulses over the steps, per body: the recorder's mean drag
        for _ in range(n):
            step(dt)
            rd.clear()
            PB.get_space_bodies(space, PB.BodyFields.VELOCITY, rd)
            vel = np.frombuffer(rd.float_buf()).copy()
            if vel.shape[0] != 2 * NA.size:  # the kernel reads and writes by body index, unchecked (numba)
                raise RuntimeError(f"rate_state law: {vel.shape[0] // 2} bodies in the space, {NA.size} expected")
            rs_step(vel, NA, m, th, vp, params, dt, acc)
            wr.clear()
            wr.set_float_buf(vel.tobytes())
            PB.set_space_bodies(space, PB.BodyFields.VELOCITY, wr)
        for j, k in enumerate(idx):
            if k >= 0:
                self.theta[k] = th[j]
        self._add_impulses(scene, idx, acc)


@numba.njit(cache=True)
def asinh_scaled(v, ln_s):
    """asinh(v e^ln_s) for v >= 0 without overflow."""
    if v <= 0.0:
        return 0.0
    ln_x = ln_s + math.log(v)
    if ln_x > 20.0:
        return ln_x + math.log(2.0)
    return math.asinh(math.exp(ln_x))


@numba.njit(cache=True)
def rs_step(vel, NA, m, th, vp, prm, dt, acc):
    """The law's share of one step, after pymunk's, on the bodies with NA > 0 (``vel`` and ``th`` in place; its
    impulse m (u - v*) added to ``acc``).

    ``vel`` holds v* = v + dt F / m: the velocities after pymunk's forces and constraints over the step, over which
    it moved each body with its start-of-step velocity v (``vp``, what this kernel wrote at the end of the previous
    step). The state is aged exactly at |v| held over the step; then the end-of-step velocity u solves
    m (u - v*) = dt f(u), f(u) = -N_pad A asinh(u e^(psi / A) / (2 V0)) (backward Euler in the law, safeguarded
    Newton: u has v*'s sign and |u| <= |v*|). Scene units for vel, NA, m, dt, vp; prm = A, B, D_c [m],
    V0 [scene velocity], mu_ref, dt [s], state law code (0 ageing, 1 slip), scene velocity -> m/s."""
    A, B, Dc, V0, mu_ref, dts, law, to_si = prm[0], prm[1], prm[2], prm[3], prm[4], prm[5], prm[6], prm[7]
    for i in range(NA.shape[0]):
        if NA[i] <= 0.0:
            continue
        V = abs(vp[i]) * to_si
        x = V * dts / Dc
        t = th[i]
        if law == 0.0:
            if x > 1e-12:
                t = t * math.exp(-x) - dts * math.expm1(-x) / x
            else:
                t = t + dts * (1.0 - V * t / Dc)
        elif V > 0.0:
            t = Dc / V * math.exp(math.log(V * t / Dc) * math.exp(-x))
        th[i] = t
        w = vel[2 * i]
        speed = abs(w)
        if speed > 0.0:
            ln_s = (mu_ref + B * math.log(V0 * to_si * t / Dc)) / A - math.log(2.0 * V0)
            # h(r) = r - speed + c asinh(r e^ln_s) is increasing in r with its root in (0, speed]
            u = abs(vp[i])  # last step's root: Newton starts next to this one's in steady sliding
            lo, hi, u = 0.0, speed, u if 0.0 < u < speed else speed
            c = dt * NA[i] / m[i]
            e2 = math.exp(-2.0 * ln_s) if ln_s > -300.0 else math.inf
            for _ in range(100):
                h = u - speed + c * asinh_scaled(u, ln_s)
                if h > 0.0:
                    hi = u
                else:
                    lo = u
                un = u - h / (1.0 + c / math.sqrt(e2 + u * u))
                if abs(un - u) <= 1e-13 * speed:  # before the bracket test: a converged step may land on its edge
                    u = un
                    break
                if not (lo < un < hi):
                    un = 0.5 * (lo + hi)
                u = un
            vel[2 * i] = math.copysign(u, w)
            acc[i] += m[i] * (vel[2 * i] - w)
        vp[i] = vel[2 * i]
