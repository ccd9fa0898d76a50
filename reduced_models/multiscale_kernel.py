"""The exact propagation of model Ib (:mod:`reduced_models.multiscale`): the closed (zeta, S, U) system in modal
form, the micro renewal draws and the two-level run around the numba kernel of :mod:`reduced_models._two_level`.
Computation only; the physics, the parameters (``p`` is a :class:`~reduced_models.multiscale.MultiscaleParams`) and
the closed forms are documented and live in :mod:`reduced_models.multiscale`."""
from __future__ import annotations

import numpy as np

from ._exact import Modes, first_order, modal_decomposition
from ._two_level import run_two_level, sort_windows
from ._version import package_version
from .spring_block_kernel import BLOCK_INTERVALS, renewal_block
from .trace import ModelTrace

__all__ = ["WINDOWS", "CROSSING_TOL", "second_order", "modal", "micro_windows", "simulate_two_level"]

WINDOWS = 256  # renewal windows generated at a time per level (memory independent of the run's length)
# renewal crossings located to 1e-6 a2 (a different uniform draw at the 20th bit; the motion between them stays exact)
CROSSING_TOL = 1e-6


def second_order(p):
    """Mass, damping and stiffness of the closed (zeta, S, U) system (:mod:`reduced_models.multiscale`)."""
    n = p.n_micro
    Md = np.array([p.M, p.m, p.m2])
    K = np.array([[p.N * p.k0, -p.k0, 0.0],
                  [-p.N * p.k0, p.k0 + n * p.k2, -p.k2],
                  [0.0, -n * p.k2, p.k2]])
    D = np.array([[p.N * p.m * p.eta0, -p.m * p.eta0, 0.0],
                  [-p.N * p.m * p.eta0, p.m * (p.eta0 + p.eta1) + n * p.m2 * p.eta2, -p.m2 * p.eta2],
                  [0.0, -n * p.m2 * p.eta2, p.m2 * (p.eta2 + p.eta3)]])
    return Md, D, K


def modal(p) -> Modes:
    """Modes of the 3-DOF system; column 0 of B is F1 (on S), column 1 is F2 (on U)."""
    Md, D, K = second_order(p)
    B = np.zeros((6, 2))
    B[4, 0] = -1.0 / p.m
    B[5, 1] = -1.0 / p.m2
    return modal_decomposition(first_order(Md, D, K), B)


def micro_windows(p, rng: np.random.Generator, b: int):
    """Micro renewal events for windows b*W .. (b+1)*W - 1 of length a2: each of the N n microblocks renews once
    per window at a uniform position, to alpha2 f_kin2 (r - 0.5). Sorted by position."""
    nm = p.N * p.n_micro
    r_pos = rng.random((WINDOWS, nm))
    r_val = rng.random((WINDOWS, nm))
    pos, val, idx = np.empty(WINDOWS * nm), np.empty(WINDOWS * nm), np.empty(WINDOWS * nm, dtype=np.int64)
    sort_windows(r_pos, r_val, float(b * WINDOWS), p.a2, p.alpha2 * p.f_kin2, pos, idx, val,
                 np.empty(nm + 1, dtype=np.int64), np.empty(nm, dtype=np.int64))
    return pos, idx, val, (b + 1) * WINDOWS * p.a2


def simulate_two_level(p, duration, dt_out, seed, micro_events, crossing_tol=CROSSING_TOL):
    """Run model Ib's two-level kernel (n_micro >= 0): macro renewals from model I's stream, micro ones from a child
    stream, the closed (zeta, S, U) system propagated exactly between them; the :class:`ModelTrace` of
    :func:`reduced_models.multiscale.simulate`."""
    n = int(round(duration / dt_out))
    md = modal(p)
    rng = np.random.default_rng(seed)
    rng2 = rng.spawn(1)[0]  # does not consume rng: the macro stream stays model I's
    f1 = p.alpha * p.f_kin * (rng.random(p.N) - 0.5)
    f2 = p.alpha2 * p.f_kin2 * (rng2.random(p.N * p.n_micro) - 0.5)
    sums = np.array([f1.sum(), f2.sum()])
    qr = np.zeros(len(md.lam_r))
    qc = np.zeros(len(md.lam_c), dtype=np.complex128)
    gr = md.B_r @ sums
    gc = md.B_c @ sums.astype(np.complex128)
    B1r, B2r = np.ascontiguousarray(md.B_r[:, 0]), np.ascontiguousarray(md.B_r[:, 1])
    B1c, B2c = np.ascontiguousarray(md.B_c[:, 0]), np.ascontiguousarray(md.B_c[:, 1])
    ilr = np.divide(1.0, md.lam_r, out=np.zeros_like(md.lam_r), where=md.lam_r != 0.0)
    lcr, lci, ilc = md.lam_c.real.copy(), md.lam_c.imag.copy(), 1.0 / md.lam_c
    x, F, F2 = np.empty(n), np.empty(n), np.empty(n)
    n1_est = int(p.N * (p.v * duration * 1.5 / p.a + 2 * BLOCK_INTERVALS)) + 16
    ev_time = np.empty(n1_est)
    ev_index = np.empty(n1_est, dtype=np.int64)
    n2_est = int(p.N * p.n_micro * (p.v * duration * 1.5 / p.a2 + 2 * WINDOWS)) + 16 if micro_events else 1
    ev2_time = np.empty(n2_est)
    tol = crossing_tol * p.a2  # position tolerance of a renewal crossing (Units: m)
    pos1 = pos2 = val1 = val2 = np.empty(0)
    idx1 = idx2 = np.empty(0, dtype=np.int64)
    ptr1 = ptr2 = 0
    b1 = b2 = 0
    bound1 = bound2 = -np.inf
    k, ev_count, ev2_count = 0, 0, 0
    stats = np.zeros(1, dtype=np.int64)
    scratch = (np.empty(len(md.lam_r)), np.empty(len(md.lam_r)), np.empty(len(md.lam_c), dtype=np.complex128),
               np.empty(len(md.lam_c), dtype=np.complex128))
    reach = -np.inf  # the kernel stops 4 output steps before the nearer loaded boundary
    while k < n:
        while bound1 <= reach or bound1 == -np.inf:
            new = renewal_block(p.macro, rng, b1)
            b1 += 1
            pos1, idx1, val1 = (np.concatenate([pos1[ptr1:], new[0]]), np.concatenate([idx1[ptr1:], new[1]]),
                                np.concatenate([val1[ptr1:], new[2]]))
            bound1, ptr1 = new[3], 0
            if ev_count + len(pos1) > len(ev_time):
                ev_time = np.concatenate([ev_time, np.empty(len(pos1) + len(ev_time))])
                ev_index = np.concatenate([ev_index, np.empty(len(pos1) + len(ev_index), dtype=np.int64)])
        while bound2 <= reach or bound2 == -np.inf:
            new = micro_windows(p, rng2, b2)
            b2 += 1
            pos2, idx2, val2 = (np.concatenate([pos2[ptr2:], new[0]]), np.concatenate([idx2[ptr2:], new[1]]),
                                np.concatenate([val2[ptr2:], new[2]]))
            bound2, ptr2 = new[3], 0
            if micro_events and ev2_count + len(pos2) > len(ev2_time):
                ev2_time = np.concatenate([ev2_time, np.empty(len(pos2) + len(ev2_time))])
        start1 = ptr1
        k, ptr1, ptr2, new_count, ev2_count = run_two_level(
            md.lam_r, ilr, md.c0_r, B1r, B2r, lcr, lci, ilc, md.c0_c, B1c, B2c, qr, gr, qc, gc, f1, f2, sums, p.v, dt_out,
            k, n, pos1, idx1, val1, ptr1, pos2, idx2, val2, ptr2, min(bound1, bound2), tol, x, F, F2,
            ev_time, ev_count, micro_events, ev2_time, ev2_count, stats, *scratch)
        ev_index[ev_count:new_count] = idx1[start1:ptr1]
        ev_count = new_count
        if k < n:
            reach = x[k] + 4.0 * p.v * dt_out
    if not np.all(np.isfinite(x)):
        raise FloatingPointError("model Ib produced non-finite positions; please report the parameters")
    meta = {
        "model": "Ib (multiscale)", "params": p.to_dict(), "seed": seed if isinstance(seed, (int, type(None))) else "Generator",
        "duration": n * dt_out, "dt_out": dt_out, "version": package_version(), "n_renewals": ev_count,
        "n_micro_renewals": ev2_count, "n_evaluations": int(stats[0]),
        "method": "exact modal propagation of the 3-DOF system block + sum of miniblocks + sum of microblocks "
                  "between renewals; renewal times by Newton on the exact solution; force sums updated per renewal",
    }
    events = {"times": ev_time[:ev_count].copy(), "index": ev_index[:ev_count].copy(), "force_micro": F2,
              "n_micro_renewals": ev2_count}
    if micro_events:
        events["micro_times"] = ev2_time[:ev2_count].copy()
    return ModelTrace(t=np.arange(n) * dt_out, x=x, force=F, events=events, metadata=meta)
