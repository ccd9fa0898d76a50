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

import numba
import numpy as np

from .trace import ModelTrace
from ._version import package_version

__all__ = [
    "SpringBlockParams", "simulate", "theory_spectrum", "theory_spectrum_coupled", "random_force_spectrum",
    "transfer_function", "asymptotic_spectrum", "mean_renewal_interval", "rms_displacement",
    "displacement_variance", "crossover_frequency",
]

_BLOCK_INTERVALS = 256  # renewal intervals generated per miniblock at a time (memory independent of length)


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
        if isinstance(self.N, bool) or not isinstance(self.N, (int, np.integer)) or self.N < 1:
            raise ValueError(f"N must be an integer >= 1 (got {self.N!r})")
        for name in ("v", "a", "k0", "M", "m", "F_drive"):
            val = getattr(self, name)
            if not (isinstance(val, (int, float)) and math.isfinite(val) and val > 0):
                raise ValueError(f"{name} must be a positive finite number (got {val!r})")
        for name in ("k1", "eta0", "eta_lat", "alpha", "F_kin"):
            val = getattr(self, name)
            if not (isinstance(val, (int, float)) and math.isfinite(val) and val >= 0):
                raise ValueError(f"{name} must be a non-negative finite number (got {val!r})")
        if self.eta1 is None or self.eta1_derived:
            if not self.F_drive > self.F_kin:
                raise ValueError(
                    f"F_drive must exceed F_kin = N f_kin for steady sliding with eta1 > 0 "
                    f"(got F_drive = {self.F_drive!r} N, F_kin = {self.F_kin!r} N)"
                )
            object.__setattr__(self, "eta1", (self.F_drive - self.F_kin) / (self.N * self.m * self.v))
            object.__setattr__(self, "eta1_derived", True)
        elif not (math.isfinite(self.eta1) and self.eta1 > 0):
            raise ValueError(f"eta1 must be a positive finite number (got {self.eta1!r})")
        elif not math.isclose(self.N * (self.m * self.eta1 * self.v + self.f_kin), self.F_drive, rel_tol=1e-6):
            raise ValueError(
                f"eta1 = {self.eta1!r} 1/s does not give steady sliding at v = {self.v!r} m/s: "
                f"N (m eta1 v + f_kin) = {self.N * (self.m * self.eta1 * self.v + self.f_kin):.6g} N "
                f"!= F_drive = {self.F_drive!r} N (leave eta1 unset to derive it)"
            )

    @classmethod
    def reference(cls) -> "SpringBlockParams":
        """The paper's reference case (section 4): eta1 = 3.33e7 1/s follows from steady sliding."""
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
        d = asdict(self)
        d.pop("eta1_derived")
        d["eta1_derived_from_steady_sliding"] = self.eta1_derived
        return d


# ----------------------------------------------------------------------------- linear system
def _second_order(p: SpringBlockParams):
    """Mass, damping and stiffness matrices of (A1)-(A2) with lateral coupling; coordinate 0 is the block."""
    n = p.N + 1
    Mm = np.diag([p.M] + [p.m] * p.N)
    K = np.zeros((n, n))
    D = np.zeros((n, n))
    K[0, 0], D[0, 0] = p.N * p.k0, p.N * p.m * p.eta0
    K[0, 1:] = K[1:, 0] = -p.k0
    D[0, 1:] = D[1:, 0] = -p.m * p.eta0
    idx = np.arange(1, n)
    K[idx, idx] += p.k0
    D[idx, idx] += p.m * (p.eta0 + p.eta1)
    for i in range(1, p.N):
        j = i + 1
        for mat, c in ((K, p.k1), (D, p.m * p.eta_lat)):
            mat[i, i] += c
            mat[j, j] += c
            mat[i, j] -= c
            mat[j, i] -= c
    return Mm, D, K


def _modal(p: SpringBlockParams):
    """Eigen-decomposition of the first-order system y' = A y + B f, y = (zeta, zeta_i, zeta', zeta_i')."""
    Mm, D, K = _second_order(p)
    n = p.N + 1
    minv = 1.0 / np.diag(Mm)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -minv[:, None] * K
    A[n:, n:] = -minv[:, None] * D
    lam, V = np.linalg.eig(A)
    # Translation invariance gives an exact zero eigenvalue; eig returns it as ~1e-10. Make it exact.
    i0 = int(np.argmin(np.abs(lam)))
    lam[i0] = 0.0
    Vi = np.linalg.inv(V)
    B = np.zeros((2 * n, p.N))
    B[n + 1 + np.arange(p.N), np.arange(p.N)] = -1.0 / p.m  # the force -f_i on miniblock i
    Bm = Vi @ B
    c0 = V[0, :].copy()
    # The state and forcing are real, so the amplitudes of a conjugate pair of modes are conjugate:
    # keep one of each pair (Im lambda > 0) with weight 2 on its contribution to zeta, and every real mode.
    scale = np.maximum(np.abs(lam), 1.0)
    real = np.abs(lam.imag) <= 1e-12 * scale
    upper = lam.imag > 1e-12 * scale
    if 2 * upper.sum() + real.sum() != len(lam):
        raise np.linalg.LinAlgError("eigenvalues of the model I system do not pair up; please report the parameters")
    return _Modes(
        lam_r=np.ascontiguousarray(lam[real].real), c0_r=np.ascontiguousarray(c0[real].real),
        B_r=np.ascontiguousarray(Bm[real].real),
        lam_c=np.ascontiguousarray(lam[upper]), c0_c=np.ascontiguousarray(2.0 * c0[upper]),
        B_c=np.ascontiguousarray(Bm[upper]),
    )


@dataclass(frozen=True)
class _Modes:
    """Modal form: real modes (r) and one mode of each conjugate pair (c, weight 2 folded into c0_c).
    zeta = sum c0_r q_r + Re sum c0_c q_c; q' = lambda q + B f."""

    lam_r: np.ndarray
    c0_r: np.ndarray
    B_r: np.ndarray
    lam_c: np.ndarray
    c0_c: np.ndarray
    B_c: np.ndarray


# ----------------------------------------------------------------------------- numba kernel
@numba.njit(cache=True)
def _phi1_r(z):
    """(e^z - 1) / z for real z, stable near 0."""
    if abs(z) < 1e-8:
        return 1.0 + 0.5 * z
    return np.expm1(z) / z


@numba.njit(cache=True)
def _phi1_c(z):
    if abs(z) < 1e-8:
        return 1.0 + 0.5 * z
    return (np.exp(z) - 1.0) / z


@numba.njit(cache=True)
def _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h):
    """(zeta, zeta') of the big block a time h ahead of the modal state (exact, constant forcing)."""
    z = 0.0
    dz = 0.0
    for k in range(lr.shape[0]):
        e = np.exp(lr[k] * h)
        z += cr[k] * (e * qr[k] + _phi1_r(lr[k] * h) * h * gr[k])
        dz += cr[k] * (lr[k] * e * qr[k] + e * gr[k])
    for k in range(lc.shape[0]):
        e = np.exp(lc[k] * h)
        z += (cc[k] * (e * qc[k] + _phi1_c(lc[k] * h) * h * gc[k])).real
        dz += (cc[k] * (lc[k] * e * qc[k] + e * gc[k])).real
    return z, dz


@numba.njit(cache=True)
def _advance(lr, qr, gr, lc, qc, gc, h):
    for k in range(lr.shape[0]):
        z = lr[k] * h
        qr[k] = np.exp(z) * qr[k] + _phi1_r(z) * h * gr[k]
    for k in range(lc.shape[0]):
        z = lc[k] * h
        qc[k] = np.exp(z) * qc[k] + _phi1_c(z) * h * gc[k]


@numba.njit(cache=True)
def _crossing(lr, cr, qr, gr, lc, cc, qc, gc, v, t, s, h_max, f_hi):
    """Time h in (0, h_max] at which v (t + h) + zeta(t + h) reaches s (safeguarded Newton).

    f_hi is the (non-negative) overshoot at h_max; the root is bracketed in [0, h_max].
    """
    z0, dz0 = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    f_lo = v * t + z0 - s
    lo, hi = 0.0, h_max
    h = h_max * (-f_lo) / (f_hi - f_lo) if f_hi > f_lo else 0.5 * h_max
    for _ in range(100):
        z, dz = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h)
        f = v * (t + h) + z - s
        if f < 0.0:
            lo = h
        else:
            hi = h
        if hi - lo <= 1e-15 * h_max:
            break
        d = v + dz
        h_new = h - f / d if d > 0.0 else 0.5 * (lo + hi)
        if not (lo < h_new < hi):
            h_new = 0.5 * (lo + hi)
        if abs(h_new - h) <= 1e-14 * h_max:
            h = h_new
            break
        h = h_new
    return min(max(h, lo), hi)


@numba.njit(cache=True)
def _run(lr, cr, Br, lc, cc, Bc, qr, gr, qc, gc, forces, v, dt, k0, k1, ev_pos, ev_idx, ev_val, ptr,
         boundary, x_out, f_out, ev_time, ev_count):
    """Step output intervals k0..k1-1; stop early (return k) when the block nears the loaded boundary.

    Returns (k_reached, ptr, ev_count). x_out[k] = position at t_k, f_out[k] = mean summed force over
    [t_k, t_k + dt).
    """
    nr = lr.shape[0]
    nc = lc.shape[0]
    Er = np.empty(nr)
    Pr = np.empty(nr)
    Ec = np.empty(nc, dtype=np.complex128)
    Pc = np.empty(nc, dtype=np.complex128)
    for k in range(nr):
        Er[k] = np.exp(lr[k] * dt)
        Pr[k] = _phi1_r(lr[k] * dt) * dt
    for k in range(nc):
        Ec[k] = np.exp(lc[k] * dt)
        Pc[k] = _phi1_c(lc[k] * dt) * dt
    fsum = 0.0
    for i in range(forces.shape[0]):
        fsum += forces[i]
    n_ev = ev_pos.shape[0]
    qnr = np.empty(nr)
    qnc = np.empty(nc, dtype=np.complex128)
    zeta, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    for k in range(k0, k1):
        t = k * dt
        x_out[k] = v * t + zeta
        if x_out[k] + 4.0 * v * dt > boundary:
            return k, ptr, ev_count
        # Fast path: one exact step with the precomputed propagator, kept if no renewal is crossed.
        zn = 0.0
        for j in range(nr):
            qnr[j] = Er[j] * qr[j] + Pr[j] * gr[j]
            zn += cr[j] * qnr[j]
        for j in range(nc):
            qnc[j] = Ec[j] * qc[j] + Pc[j] * gc[j]
            zn += (cc[j] * qnc[j]).real
        if ptr >= n_ev or v * (t + dt) + zn < ev_pos[ptr]:
            qr[:] = qnr
            qc[:] = qnc
            zeta = zn
            f_out[k] = fsum
            continue
        # Slow path: locate each renewal inside the step and propagate exactly to it.
        h_left = dt
        impulse = 0.0
        over = v * (t + dt) + zn - ev_pos[ptr]
        while True:
            h = _crossing(lr, cr, qr, gr, lc, cc, qc, gc, v, t, ev_pos[ptr], h_left, over)
            _advance(lr, qr, gr, lc, qc, gc, h)
            impulse += fsum * h
            t += h
            h_left -= h
            i = ev_idx[ptr]
            df = ev_val[ptr] - forces[i]
            forces[i] = ev_val[ptr]
            fsum = 0.0  # summed afresh, not incremented, so re-entering the kernel cannot change its bits
            for j in range(forces.shape[0]):
                fsum += forces[j]
            for j in range(nr):
                gr[j] += Br[j, i] * df
            for j in range(nc):
                gc[j] += Bc[j, i] * df
            ev_time[ev_count] = t
            ev_count += 1
            ptr += 1
            if ptr >= n_ev:
                break
            z_end, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, h_left)
            over = v * (t + h_left) + z_end - ev_pos[ptr]
            if over < 0.0:
                break
        _advance(lr, qr, gr, lc, qc, gc, h_left)
        impulse += fsum * h_left
        f_out[k] = impulse / dt
        zeta, _ = _state_at(lr, cr, qr, gr, lc, cc, qc, gc, 0.0)
    return k1, ptr, ev_count


# ----------------------------------------------------------------------------- simulator
def _renewal_block(p: SpringBlockParams, rng: np.random.Generator, b: int):
    """Renewal events for distance block b: one per miniblock in each interval [j a, (j+1) a)."""
    nb = _BLOCK_INTERVALS
    j = np.arange(b * nb, (b + 1) * nb, dtype=float)
    r_pos = rng.random((p.N, nb))
    r_val = rng.random((p.N, nb))
    pos = ((j[None, :] + r_pos) * p.a).ravel()
    idx = np.repeat(np.arange(p.N), nb)
    val = (p.alpha * p.f_kin * (r_val - 0.5)).ravel()
    order = np.argsort(pos, kind="stable")
    return pos[order], idx[order].astype(np.int64), val[order], (b + 1) * nb * p.a


def simulate(params: SpringBlockParams, duration: float, dt_out: float, seed=None, *,
             checkpoint: str | None = None, checkpoint_every: float | None = None) -> ModelTrace:
    """Simulate model I exactly and sample the block position every ``dt_out`` seconds.

    Parameters
    ----------
    params : SpringBlockParams
    duration : float
        Simulated time (Units: s); ``round(duration / dt_out)`` samples are returned, the first at t = 0.
    dt_out : float
        Output step (Units: s). Any value works: propagation is exact between renewals.
    seed : int or numpy.random.Generator
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
    if not (isinstance(duration, (int, float)) and duration > 0 and math.isfinite(duration)):
        raise ValueError(f"duration must be a positive number of seconds (got {duration!r})")
    if not (isinstance(dt_out, (int, float)) and dt_out > 0 and math.isfinite(dt_out)):
        raise ValueError(f"dt_out must be a positive number of seconds (got {dt_out!r})")
    n = int(round(duration / dt_out))
    if n < 2:
        raise ValueError(f"duration {duration!r} s holds fewer than two output steps of {dt_out!r} s")
    md = _modal(params)
    every = n if not checkpoint_every else max(1, int(round(checkpoint_every / dt_out)))
    st = _load_checkpoint(checkpoint, params, n, dt_out, seed) if checkpoint else None
    if st is None:
        rng = np.random.default_rng(seed)
        forces = params.alpha * params.f_kin * (rng.random(params.N) - 0.5)
        st = {
            "rng": rng, "forces": forces, "qr": np.zeros(len(md.lam_r)),
            "qc": np.zeros(len(md.lam_c), dtype=np.complex128), "gr": md.B_r @ forces,
            "gc": md.B_c @ forces.astype(np.complex128), "x": np.empty(n), "f": np.empty(n),
            "ev_time": np.empty(int(params.N * (params.v * duration * 1.5 / params.a + 2 * _BLOCK_INTERVALS)) + 16),
            "ev_index": None, "ev_count": 0, "k": 0, "b": 0, "pos": np.empty(0), "idx": np.empty(0, dtype=np.int64),
            "val": np.empty(0), "ptr": 0, "boundary": -np.inf,
        }
        st["ev_index"] = np.empty(len(st["ev_time"]), dtype=np.int64)
    rng, forces, qr, qc, gr, gc = st["rng"], st["forces"], st["qr"], st["qc"], st["gr"], st["gc"]
    x, f = st["x"], st["f"]
    k, b, pos, idx, val, ptr, boundary = st["k"], st["b"], st["pos"], st["idx"], st["val"], st["ptr"], st["boundary"]
    ev_time, ev_index, ev_count = st["ev_time"], st["ev_index"], st["ev_count"]
    need_block = st.get("need_block", True)
    next_ckpt = (k // every + 1) * every
    while k < n:
        if need_block:  # the kernel stopped near the end of the loaded renewals: load the next distance block
            new_pos, new_idx, new_val, boundary = _renewal_block(params, rng, b)
            b += 1
            pos = np.concatenate([pos[ptr:], new_pos])
            idx = np.concatenate([idx[ptr:], new_idx])
            val = np.concatenate([val[ptr:], new_val])
            ptr = 0
            if ev_count + len(pos) > len(ev_time):
                grow = max(len(ev_time), len(pos))
                ev_time = np.concatenate([ev_time, np.empty(grow)])
                ev_index = np.concatenate([ev_index, np.empty(grow, dtype=np.int64)])
        start = ptr
        k_stop = min(n, next_ckpt)
        # the kernel writes x, f rows k..k_stop-1 and one event per renewal passed, unchecked (numba)
        if not (x.shape[0] >= k_stop and f.shape[0] >= k_stop and ev_time.shape[0] >= ev_count + len(pos) - ptr
                and qr.shape == gr.shape == md.lam_r.shape and qc.shape == gc.shape == md.lam_c.shape):
            raise RuntimeError(f"spring_block._run: buffers too small (x {x.shape[0]}, f {f.shape[0]} rows for "
                               f"{k_stop}; events {ev_time.shape[0]} for {ev_count + len(pos) - ptr})")
        k_new, ptr, new_count = _run(md.lam_r, md.c0_r, md.B_r, md.lam_c, md.c0_c, md.B_c, qr, gr, qc, gc, forces,
                                     params.v, dt_out, k, k_stop, pos, idx, val, ptr, boundary, x, f, ev_time, ev_count)
        ev_index[ev_count:new_count] = idx[start:ptr]
        ev_count = new_count
        need_block = k_new < k_stop
        k = k_new
        if k == k_stop and k < n:
            next_ckpt += every
            if checkpoint:
                _save_checkpoint(checkpoint, params, n, dt_out, seed, dict(
                    rng=rng, forces=forces, qr=qr, qc=qc, gr=gr, gc=gc, x=x, f=f, ev_time=ev_time, ev_index=ev_index,
                    ev_count=ev_count, k=k, b=b, pos=pos, idx=idx, val=val, ptr=ptr, boundary=boundary,
                    need_block=need_block))
    if not np.all(np.isfinite(x)):
        raise FloatingPointError("model I produced non-finite positions; please report the parameters")
    meta = {
        "model": "I (spring-block)",
        "params": params.to_dict(),
        "seed": seed if isinstance(seed, (int, type(None))) else "Generator",
        "duration": n * dt_out,
        "dt_out": dt_out,
        "method": "exact modal propagation between renewals; renewal times by Newton on the exact solution",
        "version": package_version(),
        "n_renewals": ev_count,
    }
    return ModelTrace(t=np.arange(n) * dt_out, x=x, force=f,
                      events={"times": ev_time[:ev_count].copy(), "index": ev_index[:ev_count].copy()},
                      metadata=meta)


def _ckpt_key(params, n, dt_out, seed) -> dict:
    return {"params": params.to_dict(), "n": n, "dt_out": dt_out, "seed": seed if isinstance(seed, int) else repr(seed)}


def _save_checkpoint(path, params, n, dt_out, seed, state):
    """Pickle the state next to its identity (params, length, step, seed); atomic rename."""
    import os
    import pickle
    import tempfile
    from pathlib import Path

    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    with os.fdopen(fd, "wb") as fh:
        pickle.dump({"key": _ckpt_key(params, n, dt_out, seed), "state": state}, fh, protocol=pickle.HIGHEST_PROTOCOL)
    os.replace(tmp, path)


def _load_checkpoint(path, params, n, dt_out, seed):
    """The saved state if ``path`` holds a checkpoint of this very run, else None."""
    import pickle
    from pathlib import Path

    path = Path(path)
    if not path.exists():
        return None
    with open(path, "rb") as fh:
        data = pickle.load(fh)
    if data.get("key") != _ckpt_key(params, n, dt_out, seed):
        raise ValueError(f"{path}: checkpoint of a different run (parameters, duration, step or seed differ)")
    return data["state"]


# ----------------------------------------------------------------------------- theory
def random_force_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """C_f(omega) of one miniblock's random force, eq. (A8) with <cos omega tau> = exp(-s^2 omega^2/2)
    cos(omega tau0), s^2 = tau0^2 / 6 (Units: N^2 s)."""
    w = np.asarray(omega, dtype=float)
    tau0 = params.tau0
    mean_cos = np.exp(-(tau0**2 / 6.0) * w**2 / 2.0) * np.cos(w * tau0)
    return params.v / (12.0 * np.pi * params.a) * params.f_kin**2 * params.alpha**2 / w**2 * (1.0 - mean_cos)


def transfer_function(params: SpringBlockParams, omega) -> np.ndarray:
    """Z(omega) = -P0 / S of eq. (A5): zeta(omega) = Z (1/N) sum_i f_i(omega) (Units: m/N). Ignores k1."""
    w = np.asarray(omega, dtype=float)
    p = params
    iw = 1j * w
    Q0 = -p.M * w**2 + p.N * p.k0 + iw * p.N * p.m * p.eta0
    Q1 = -p.m * w**2 + p.k0 + iw * p.m * (p.eta0 + p.eta1)
    P0 = p.N * p.k0 + iw * p.N * p.m * p.eta0
    P1 = p.k0 + iw * p.m * p.eta0
    return -P0 / (Q0 * Q1 - P0 * P1)


def theory_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """C_x(omega) = |Z|^2 C_f / N, eq. (A10), full Z of (A5) and C_f of (A8) (Units: m^2 s)."""
    return np.abs(transfer_function(params, omega)) ** 2 * random_force_spectrum(params, omega) / params.N


def theory_spectrum_coupled(params: SpringBlockParams, omega) -> np.ndarray:
    """C_x(omega) with the lateral coupling k1, eta_lat included: sum_i |Z_i|^2 C_f, Z_i from the full
    (N+1)-body dynamic stiffness (the generalisation of eq. A10 to non-identical miniblocks)."""
    Mm, D, K = _second_order(params)
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    out = np.empty(len(w))
    rhs = np.zeros((params.N + 1, params.N))
    rhs[1 + np.arange(params.N), np.arange(params.N)] = -1.0
    for i, wi in enumerate(w):
        Zrow = np.linalg.solve(-wi**2 * Mm + 1j * wi * D + K, rhs)[0]
        out[i] = np.sum(np.abs(Zrow) ** 2)
    return out * random_force_spectrum(params, w)


def asymptotic_spectrum(params: SpringBlockParams, omega) -> np.ndarray:
    """eq. (A11): alpha^2 v f_kin^2 / (12 pi N a (m eta1)^2 omega^4); equals eq. (6)/(A12),
    alpha^2 v^3 / (12 pi N a omega^4), when m eta1 v = f_kin. Valid for v/a << omega << omega_c."""
    w = np.asarray(omega, dtype=float)
    p = params
    return p.alpha**2 * p.v * p.f_kin**2 / (12.0 * np.pi * p.N * p.a * (p.m * p.eta1) ** 2 * w**4)


def crossover_frequency(params: SpringBlockParams) -> float:
    """omega_c: where the block-on-springs resonance sqrt(N k0 / M) ends the omega^-4 band, or the viscous
    crossover N m eta1 / M if that is lower (Units: rad/s). From the expansion of S(omega) in (A5)."""
    p = params
    return min(math.sqrt(p.N * p.k0 / p.M), p.N * p.m * p.eta1 / p.M)


def mean_renewal_interval(params: SpringBlockParams) -> float:
    """Mean time between renewals on the whole block, a / (N v) (Fig. 14) (Units: s)."""
    return params.a / (params.N * params.v)


def displacement_variance(params: SpringBlockParams, L0) -> np.ndarray:
    """<(zeta(t + L0/v) - zeta(t))^2> for L0 >> a: the random walk of Appendix A (Units: m^2).

    Each renewal interval tau of a force u moves the block by -u tau / (N m eta1); with the renewal rate
    N v / a, <u^2> = alpha^2 f_kin^2 / 12 and <tau^2> = 7 tau0^2 / 6 this diffuses as
    7 alpha^2 a L0 f_kin^2 / (72 N (m eta1 v)^2), i.e. 7 alpha^2 a L0 / (72 N) when m eta1 v = f_kin.
    """
    p = params
    L0 = np.asarray(L0, dtype=float)
    return 7.0 * p.alpha**2 * p.a * L0 * p.f_kin**2 / (72.0 * p.N * (p.m * p.eta1 * p.v) ** 2)


def rms_displacement(params: SpringBlockParams, L0) -> np.ndarray:
    """zeta_rms after sliding L0, eq. (A13): sqrt(7 / (72 pi^2) L0 a / N) (times alpha f_kin / (m eta1 v)),
    the paper's estimate with the low-frequency cut-off omega_0 = pi v / L0 (Units: m)."""
    return np.sqrt(displacement_variance(params, L0) / np.pi**2)
