"""Model I on a vibrating substrate: the spring-block model of Xu, Zhou & Persson (2025, Appendix A) whose
miniblocks rub on a substrate that oscillates along the sliding direction as ``s(t) = A sin(omega_v t)``.

The law. Each miniblock's friction acts on its velocity relative to the substrate, ``w_i = x_i' - s'(t)``:

    f_fric,i = f_kin sign(w_i) + m eta1 w_i          (a set-valued Coulomb part: |f| <= f_kin while w_i = 0)

so that eq. (A2) reads

    m x_i'' = -k0 (x_i - x) - m eta0 (x_i' - x') - m eta1 w_i - f_kin sign(w_i) - f_i(t) + lateral      (A2v)

with (A1) unchanged. Without vibration the paper's model I slides at w_i ~ v = 0.5 mm/s, and its random forces
move w_i by at most alpha f_kin / (2 m eta1) = v / 2 (reference case), so w_i > 0 throughout, sign(w_i) = 1 and
(A2v) is (A2) exactly: the paper's model is the A = 0 case. With vibration the Coulomb part can reverse within a
cycle, and its cycle mean, a nonlinear function of the slow relative speed, has a slope that adds to m eta1:
the in-band noise changes through eq. (A11) (:mod:`reduced_models.vibration`). The random forces renew as in
model I, once at a random point within every distance a of the block's displacement relative to the substrate
(its running maximum, so a vibration does not renew a contact twice).

Numerics. The Coulomb part makes the model nonlinear, so the exact modal propagation of model I does not apply:
the equations are stepped at a fixed step h <= T_v / steps_per_period (in the prediction a whole number of
steps per period, so its cycle averages are exact; in ``simulate`` the largest such step that divides dt_out),
explicit for the springs and the block, implicit for the miniblocks' damping and friction, whose update is the proximal (soft-threshold) solution of the set-valued law:

    m (1 + h (eta0 + eta1)) w' + h f_kin sign(w') = m (x_i' - u') + h (F_i - m eta0 (u' - x'))

(u' = s'(t + h), F_i the spring, lateral and random forces). It is stable for any h (m eta1 = 333 N s/m makes
the explicit limit 6e-8 s); its error is O(h) in the vibration's phase and O(1/(h eta1)) in the miniblocks' lag.

Prediction (:func:`averaged_law`, :func:`theory_spectrum`). Far above the band the block sees the cycle-mean
friction of a miniblock as a function of its slow speed V, F(V), computed exactly for the discrete scheme as the
periodic steady state of one miniblock dragged at V (the block heavy: its response at omega_v is
N k0 A / (M omega_v^2) of A). Its slope s1 = F'(V) replaces m eta1 in eq. (A5)-(A10), and V the solution of
N F(V) = F_drive (the constant force drive speeds up as the mean friction falls): C_x = |Z_s1|^2 C_f(V) / N.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from frictionnoise.base import check_number

from ._version import package_version
from .spring_block import SpringBlockParams
from .trace import check_run
from .trace import ModelTrace

__all__ = ["VibratingBlockParams", "PARAMS", "simulate", "averaged_law", "steady_state", "theory_spectrum",
           "RESPONSE", "SWEEP_SERIES", "fit_band", "default_duration", "default_dt_out"]

RESPONSE = "viscous"  # as model I below its crossover, with the effective slope in place of m eta1
SWEEP_SERIES = "x"  # a sweep's task returns C_x of the block's displacement


@dataclass(frozen=True)
class VibratingBlockParams(SpringBlockParams):
    """Model I's parameters (:class:`SpringBlockParams`, the paper's reference case by default) and the substrate's
    vibration along the sliding direction, SI units.

    Attributes
    ----------
    amplitude : float
        Substrate displacement amplitude A (Units: m), >= 0; 0 is model I.
    omega_v : float
        Angular frequency of the vibration (Units: rad/s), > 0.
    steps_per_period : int
        Time steps per vibration period (the step is h = 2 pi / (omega_v steps_per_period)), >= 16.
    """

    amplitude: float = 0.0
    omega_v: float = 3000.0
    steps_per_period: int = 64

    def __post_init__(self):
        super().__post_init__()
        check_number("amplitude", self.amplitude, non_negative=True)
        check_number("omega_v", self.omega_v, positive=True)
        n = check_number("steps_per_period", self.steps_per_period, positive=True, integer=True)
        if n < 16:
            raise ValueError(f"steps_per_period must be >= 16 (got {n}): the vibration would not be resolved")
        object.__setattr__(self, "steps_per_period", n)

    @classmethod
    def reference(cls) -> "VibratingBlockParams":
        """The paper's reference case (:meth:`SpringBlockParams.reference`) on a substrate shaken at A = 30 um and
        omega_v = 3000 rad/s, 30 times the top of its omega^-4 band: the mean-field slope lowers the in-band C_x to
        0.544 of model I's (eq. A11 in :func:`theory_spectrum`).

        Returns
        -------
        VibratingBlockParams
            The reference case with amplitude = 3e-5 m, omega_v = 3000 rad/s.
        """
        return cls(amplitude=30e-6, omega_v=3000.0)

    @property
    def h(self) -> float:
        """The time step (Units: s)."""
        return 2.0 * math.pi / (self.omega_v * self.steps_per_period)


PARAMS = VibratingBlockParams
def _scalars(p: VibratingBlockParams) -> np.ndarray:
    b = p
    return np.array([b.M, b.m, b.k0, b.k1, b.eta0, b.eta1, b.eta_lat, b.f_kin, b.F_drive, p.amplitude, p.omega_v,
                     p.h, b.a])


# ----------------------------------------------------------------------------- kernels
@numba.njit(cache=True)
def _miniblock_velocity(m, h, eta0, eta1, fkin, xdi, u1, Fi, xd_block):
    """The proximal update of one miniblock's velocity (see the module docstring): returns x_i'(t + h)."""
    R = m * (xdi - u1) + h * (Fi - m * eta0 * (u1 - xd_block))
    thr = h * fkin
    if R > thr:
        w = (R - thr) / (m * (1.0 + h * (eta0 + eta1)))
    elif R < -thr:
        w = (R + thr) / (m * (1.0 + h * (eta0 + eta1)))
    else:
        w = 0.0
    return w + u1


@numba.njit(cache=True)
def _run(st, xi, xid, forces, pos, val, ptr, prm, n_sub, k, k_stop, out_x, out_s, out_f, ev_time, ev_index, n_ev):
    """Step the block and its N miniblocks from output sample k to k_stop (or until a miniblock's renewal list runs
    out). st = [x, x', d_max, step, x_start]; returns (k, n_ev)."""
    M, m, k0, k1, eta0, eta1, eta_lat, fkin, F, A, wv, h = (prm[0], prm[1], prm[2], prm[3], prm[4], prm[5], prm[6],
                                                         prm[7], prm[8], prm[9], prm[10], prm[11])
    N = xi.shape[0]
    lat = np.zeros(N)
    x, xd, dmax, step, x0 = st[0], st[1], st[2], int(st[3]), st[4]
    n_int = pos.shape[1]
    nxt = np.inf
    for i in range(N):
        nxt = min(nxt, pos[i, ptr[i]])
    while k < k_stop:
        if step % n_sub == 0:
            t = step * h
            out_x[k] = x - x0
            out_s[k] = A * math.sin(wv * t)
            sf = 0.0
            for i in range(N):
                sf += forces[i]
            out_f[k] = sf
            k += 1
            if k >= k_stop:
                break
        t1 = (step + 1) * h
        s1 = A * math.sin(wv * t1)
        u1 = A * wv * math.cos(wv * t1)
        # the block (A1), explicit
        Fb = F
        for i in range(N):
            Fb -= k0 * (x - xi[i]) + m * eta0 * (xd - xid[i])
        xd_new = xd + h * Fb / M
        # lateral springs (free ends), explicit on the old state
        for i in range(N):
            lat[i] = 0.0
        for i in range(N - 1):
            fl = k1 * (xi[i + 1] - xi[i]) + m * eta_lat * (xid[i + 1] - xid[i])
            lat[i] += fl
            lat[i + 1] -= fl
        # the miniblocks (A2v): damping and friction implicit
        for i in range(N):
            Fi = -k0 * (xi[i] - x) + lat[i] - forces[i]
            xid[i] = _miniblock_velocity(m, h, eta0, eta1, fkin, xid[i], u1, Fi, xd_new)
        for i in range(N):
            xi[i] += h * xid[i]
        xd = xd_new
        x += h * xd
        step += 1
        # renewals keyed to the block's running maximum displacement relative to the substrate
        d = x - x0 - s1
        if d > dmax:
            dmax = d
        if dmax >= nxt:
            nxt = np.inf
            out = False
            for i in range(N):
                while ptr[i] < n_int - 1 and pos[i, ptr[i]] <= dmax:
                    forces[i] = val[i, ptr[i]]
                    ptr[i] += 1
                    if n_ev < ev_time.shape[0]:
                        ev_time[n_ev] = step * h
                        ev_index[n_ev] = i
                    n_ev += 1
                if ptr[i] >= n_int - 1:
                    out = True
                nxt = min(nxt, pos[i, ptr[i]])
            if out:
                break
    st[0], st[1], st[2], st[3] = x, xd, dmax, step
    return k, n_ev


@numba.njit(cache=True)
def _one_miniblock(prm, V, n_cycles, n_avg):
    """Periodic steady state of one miniblock (no random force, no neighbours) whose block moves at the constant
    speed V: the cycle-mean friction it transmits, averaged over the last n_avg of n_cycles periods (Units: N);
    also the cycle-mean Coulomb sign and the fraction of steps it sticks."""
    m, k0, eta0, eta1, fkin, A, wv, h = prm[1], prm[2], prm[4], prm[5], prm[7], prm[9], prm[10], prm[11]
    n_per = int(round(2.0 * math.pi / (wv * h)))
    # start at steady sliding without vibration: the spring carries f_kin + m eta1 V
    xi = -(fkin + m * eta1 * V) / k0
    xid = V
    acc = 0.0
    sgn = 0.0
    stick = 0
    n_tot = n_cycles * n_per
    start = (n_cycles - n_avg) * n_per
    for step in range(n_tot):
        t0 = step * h
        x = V * t0
        t1 = t0 + h
        u1 = A * wv * math.cos(wv * t1)
        Fi = -k0 * (xi - x)
        xid = _miniblock_velocity(m, h, eta0, eta1, fkin, xid, u1, Fi, V)
        xi += h * xid
        if step >= start:
            w = xid - u1
            # the friction force on the miniblock this step: what the implicit update applied
            acc += k0 * (V * t1 - xi) + m * eta0 * (V - xid)  # = spring + damper force carried; mean = friction
            if w > 0.0:
                sgn += 1.0
            elif w < 0.0:
                sgn -= 1.0
            else:
                stick += 1
    n = n_tot - start
    return acc / n, sgn / n, stick / n


@numba.njit(cache=True)
def _mean_field(prm, N, F, n_cycles, n_avg):
    """Periodic steady state of the block and N identical miniblocks (no random forces) under the constant force
    F: the block's mean speed over the last n_avg of n_cycles vibration periods (Units: m/s). The block's own
    response at omega_v (N k0 A / (M omega_v^2) of A) is kept, which a block held at constant speed would miss."""
    M, m, k0, eta0, eta1, fkin, A, wv, h = (prm[0], prm[1], prm[2], prm[4], prm[5], prm[7], prm[9], prm[10],
                                            prm[11])
    n_per = int(round(2.0 * math.pi / (wv * h)))
    V0 = (F / N - fkin) / (m * eta1)
    if V0 < 0.0:
        V0 = 0.0
    x, xd = F / (N * k0), V0
    xi, xid = 0.0, V0
    n_tot = n_cycles * n_per
    start = (n_cycles - n_avg) * n_per
    x_start = 0.0
    for step in range(n_tot):
        if step == start:
            x_start = x
        t1 = (step + 1) * h
        u1 = A * wv * math.cos(wv * t1)
        xd_new = xd + h * (F - N * (k0 * (x - xi) + m * eta0 * (xd - xid))) / M
        Fi = -k0 * (xi - x)
        xid = _miniblock_velocity(m, h, eta0, eta1, fkin, xid, u1, Fi, xd_new)
        xi += h * xid
        xd = xd_new
        x += h * xd
    return (x - x_start) / ((n_tot - start) * h)


def _cycles(params: VibratingBlockParams) -> int:
    """Periods to run to a periodic state: 12 decay times of the slowest mode, k0 / (m eta1), at least 40."""
    b = params
    rate = min(b.k0 / (b.m * (b.eta1 + b.eta0)), b.eta1)
    return max(40, int(12.0 / (rate * 2 * math.pi / params.omega_v)) + 1)


# ----------------------------------------------------------------------------- simulator
def _renewals(p: SpringBlockParams, rng, n_int: int, j0: int):
    """Renewal positions and values of intervals j0 .. j0 + n_int - 1, per miniblock (rows)."""
    j = np.arange(j0, j0 + n_int, dtype=float)
    pos = (j[None, :] + rng.random((p.N, n_int))) * p.a
    val = p.alpha * p.f_kin * (rng.random((p.N, n_int)) - 0.5)
    return pos, val


def simulate(params: VibratingBlockParams, duration: float, dt_out: float = 5e-4, seed=None, *,
             warmup: float = 1.0) -> ModelTrace:
    """Simulate model I on a vibrating substrate and sample the block every ``dt_out``.

    Parameters
    ----------
    params : VibratingBlockParams
    duration : float
        Recorded time (Units: s).
    dt_out : float
        Output step (Units: s): a whole number of time steps, each at most ``params.h`` (so at least
        ``steps_per_period`` steps per vibration period; the step used is ``metadata["step"]``). Keep omega_v
        below pi / dt_out to keep the line out of aliasing.
    seed : int or numpy.random.Generator
    warmup : float
        Simulated and discarded first (Units: s): the miniblocks settle at rate k0 / (m eta1) (30 1/s in the
        reference case).

    Returns
    -------
    ModelTrace
        ``x`` the block's displacement in the laboratory (the line at omega_v included), ``force`` the summed
        random force at each sample, ``events``: ``substrate`` (s(t) at each sample, Units: m), ``times`` and
        ``index`` of the renewals.
    """
    check_run(duration, dt_out)
    if not (warmup >= 0 and math.isfinite(warmup)):
        raise ValueError(f"warmup must be a finite number of seconds >= 0 (got {warmup!r})")
    b = params
    n_sub = max(1, math.ceil(dt_out / params.h * (1 - 1e-12)))  # whole steps per sample, none longer than h
    h = dt_out / n_sub
    n_warm = int(math.ceil(warmup / (n_sub * h)))
    n = int(round(duration / (n_sub * h)))
    n_all = n_warm + n
    rng = np.random.default_rng(seed)
    forces = b.alpha * b.f_kin * (rng.random(b.N) - 0.5)
    v_max = b.F_drive / (b.N * b.m * b.eta1)  # no Coulomb part at all: the fastest mean speed
    n_int = int(1.5 * v_max * n_all * n_sub * h / b.a) + 8
    pos, val = _renewals(b, rng, n_int, 0)
    ptr = np.zeros(b.N, dtype=np.int64)
    x_a = b.F_drive / (b.N * b.k0)  # the springs' steady stretch
    st = np.array([x_a, b.v, 0.0, 0.0, x_a])
    xi = np.zeros(b.N)
    xid = np.full(b.N, b.v)
    out_x, out_s, out_f = np.empty(n_all), np.empty(n_all), np.empty(n_all)
    ev_time = np.empty(b.N * n_int + 16)
    ev_index = np.empty(len(ev_time), dtype=np.int64)
    prm = _scalars(params)
    prm[11] = h
    k, n_ev, j0 = 0, 0, n_int
    while k < n_all:
        k, n_ev = _run(st, xi, xid, forces, pos, val, ptr, prm, n_sub, k, n_all, out_x, out_s, out_f, ev_time,
                       ev_index, n_ev)
        if k < n_all:  # a renewal list ran out: append the next intervals (same stream, in order)
            more_pos, more_val = _renewals(b, rng, n_int, j0)
            j0 += n_int
            keep = [pos[i, ptr[i]:] for i in range(b.N)]
            width = max(len(r) for r in keep) + n_int
            new_pos = np.full((b.N, width), np.inf)
            new_val = np.zeros((b.N, width))
            for i in range(b.N):
                r = len(keep[i])
                new_pos[i, :r], new_val[i, :r] = keep[i], val[i, ptr[i]:]
                new_pos[i, r:r + n_int], new_val[i, r:r + n_int] = more_pos[i], more_val[i]
            pos, val, ptr = new_pos, new_val, np.zeros(b.N, dtype=np.int64)
            grow = b.N * n_int
            ev_time = np.concatenate([ev_time, np.empty(grow)])
            ev_index = np.concatenate([ev_index, np.empty(grow, dtype=np.int64)])
    if not np.all(np.isfinite(out_x)):
        raise FloatingPointError("vibrating model I produced non-finite positions; please report the parameters")
    t_warm = n_warm * n_sub * h
    sel = slice(n_warm, n_all)
    ev = min(n_ev, len(ev_time))
    keep_ev = ev_time[:ev] >= t_warm
    meta = {
        "model": "I on a vibrating substrate",
        "params": params.to_dict(),
        "seed": seed if isinstance(seed, (int, type(None))) else "Generator",
        "duration": n * n_sub * h, "dt_out": n_sub * h, "step": h, "warmup": t_warm,
        "method": "fixed step, explicit springs and block, proximal (soft-threshold) implicit miniblock friction",
        "version": package_version(), "n_renewals": int(keep_ev.sum()),
    }
    x = out_x[sel] - out_x[n_warm]
    return ModelTrace(t=np.arange(n) * n_sub * h, x=x, force=out_f[sel].copy(),
                      events={"substrate": out_s[sel].copy(), "times": ev_time[:ev][keep_ev] - t_warm,
                              "index": ev_index[:ev][keep_ev]}, metadata=meta)


# ----------------------------------------------------------------------------- prediction
def averaged_law(params: VibratingBlockParams, V, n_cycles: int | None = None) -> np.ndarray:
    """Cycle-mean friction F(V) of one miniblock dragged at the slow speed V over the vibrating substrate, from
    the periodic steady state of the discrete scheme (Units: N). Without vibration: f_kin + m eta1 V.

    The miniblock's transient decays at the rate k0 / (m eta1) (and m eta1 / m): ``n_cycles`` (default: 12
    decay times, at least 40 periods) are run and the last quarter averaged.
    """
    prm = _scalars(params)
    if n_cycles is None:
        n_cycles = _cycles(params)
    n_avg = max(1, n_cycles // 4)
    V = np.atleast_1d(np.asarray(V, dtype=float))
    return np.array([_one_miniblock(prm, float(v), n_cycles, n_avg)[0] for v in V])


def steady_state(params: VibratingBlockParams, rel_step: float = 1e-3) -> tuple[float, float]:
    """(V, s1): the mean speed under F_drive and the effective slope s1 = (1/N) dF_drive/dV of the contacts' mean
    friction law there (Units: m/s, N s/m), from the periodic steady state of the block and N identical
    miniblocks (``_mean_field``); s1 by a central difference of F_drive by +-``rel_step``."""
    b = params
    prm = _scalars(params)
    n_cycles = _cycles(params)
    n_avg = max(1, n_cycles // 4)
    V = _mean_field(prm, b.N, b.F_drive, n_cycles, n_avg)
    dF = rel_step * b.F_drive
    Vp = _mean_field(prm, b.N, b.F_drive + dF, n_cycles, n_avg)
    Vm = _mean_field(prm, b.N, b.F_drive - dF, n_cycles, n_avg)
    return V, 2 * dF / (b.N * (Vp - Vm))


def _transfer(b: SpringBlockParams, slope: float, w):
    """Z(omega) of eq. (A5) with the miniblock friction slope ``slope`` in place of m eta1 (Units: m/N)."""
    iw = 1j * w
    Q0 = -b.M * w**2 + b.N * b.k0 + iw * b.N * b.m * b.eta0
    Q1 = -b.m * w**2 + b.k0 + iw * (b.m * b.eta0 + slope)
    P0 = b.N * b.k0 + iw * b.N * b.m * b.eta0
    P1 = b.k0 + iw * b.m * b.eta0
    return -P0 / (Q0 * Q1 - P0 * P1)


def theory_spectrum(params: VibratingBlockParams, omega, state: tuple[float, float] | None = None) -> np.ndarray:
    """C_x(omega) below the vibration: eq. (A10) with the effective slope s1 in place of m eta1 and the renewal
    rate V / a of the new mean speed, C_x = |Z_s1|^2 C_f(V) / N (Units: m^2 s); the line at omega_v and its
    harmonics are not included. ``state``: (V, s1) from :func:`steady_state` (computed if not given)."""
    b = params
    V, s1 = steady_state(params) if state is None else state
    w = np.asarray(omega, dtype=float)
    tau0 = b.a / V
    mean_cos = np.exp(-(tau0**2 / 6.0) * w**2 / 2.0) * np.cos(w * tau0)
    Cf = V / (12.0 * np.pi * b.a) * b.f_kin**2 * b.alpha**2 / w**2 * (1.0 - mean_cos)  # eq. (A8) at speed V
    return np.abs(_transfer(b, s1, w)) ** 2 * Cf / b.N


def default_duration(params: VibratingBlockParams) -> float:
    """200 s: the omega^-4 band from 10 rad/s up, about 2 s of CPU (Units: s)."""
    return 200.0


def default_dt_out(params: VibratingBlockParams) -> float:
    """An output step that keeps the line at omega_v below the Nyquist frequency, at most 1 ms (Units: s)."""
    return min(1e-3, 0.5 * math.pi / params.omega_v)


def fit_band(params: VibratingBlockParams, dt_out: float | None = None) -> tuple[float, float]:
    """Model I's omega^-4 band (10 v/a to omega_c / 10, Units: rad/s), at the unshaken speed."""
    from .spring_block import fit_band as model_I_band
    return model_I_band(params, dt_out)
