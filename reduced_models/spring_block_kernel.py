"""The exact propagation of model I (:mod:`reduced_models.spring_block`): its linear system in modal form, the
renewal draws and the state of a run advanced between output steps. Computation only; the physics, the parameters
(``p`` is a :class:`~reduced_models.spring_block.SpringBlockParams`) and the closed forms are documented and live in
:mod:`reduced_models.spring_block`."""
from __future__ import annotations

import numpy as np

from ._exact import Modes, first_order, modal_decomposition, run_renewals

__all__ = ["BLOCK_INTERVALS", "second_order", "reduced_second_order", "contact_indices", "modal", "renewal_block",
           "initial_state", "next_block", "advance", "run"]

BLOCK_INTERVALS = 256  # renewal intervals generated per miniblock at a time (memory independent of length)


def second_order(p):
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


def reduced_second_order(p):
    """(A1)-(A2) for (zeta, S = sum_i zeta_i): summed over identical miniblocks the lateral forces cancel
    (each spring k1 pushes its two ends equally and oppositely), so the block sees this 2-DOF system driven by
    the force sum F = sum_i f_i alone, whatever k1 and eta_lat:

        M zeta'' = -k0 (N zeta - S) - m eta0 (N zeta' - S')
        m S''    = -k0 (S - N zeta) - m eta0 (S' - N zeta') - m eta1 S' - F
    """
    Md = np.array([p.M, p.m])
    K = np.array([[p.N * p.k0, -p.k0], [-p.N * p.k0, p.k0]])
    D = np.array([[p.N * p.m * p.eta0, -p.m * p.eta0], [-p.N * p.m * p.eta0, p.m * (p.eta0 + p.eta1)]])
    return Md, D, K


def contact_indices(p, contacts) -> np.ndarray:
    """Miniblock indices whose displacement is recorded: none (False), all (True) or the ones listed."""
    if contacts is False or contacts is None:
        return np.empty(0, dtype=np.int64)
    if contacts is True:
        return np.arange(p.N)
    idx = np.asarray(contacts, dtype=np.int64).ravel()
    if idx.size == 0 or idx.min() < 0 or idx.max() >= p.N:
        raise ValueError(f"contacts must be True or miniblock indices in 0..{p.N - 1} (got {contacts!r})")
    return idx


def modal(p, contacts=False) -> Modes:
    """Modal form of model I. Default: the reduced 2-DOF system (block + sum of miniblocks), with each
    miniblock's force entering through the same column. ``contacts`` (True or indices): the full (N+1)-body
    system with the lateral springs, and those miniblocks' displacements zeta_i as extra output rows."""
    sel = contact_indices(p, contacts)
    if not len(sel):
        Md, D, K = reduced_second_order(p)
        A = first_order(Md, D, K)
        B = np.zeros((4, p.N))
        B[3, :] = -1.0 / p.m  # every miniblock's force -f_i enters the summed equation
        return modal_decomposition(A, B)
    Mm, D, K = second_order(p)
    n = p.N + 1
    A = first_order(np.diag(Mm), D, K)
    B = np.zeros((2 * n, p.N))
    B[n + 1 + np.arange(p.N), np.arange(p.N)] = -1.0 / p.m  # the force -f_i on miniblock i
    rows = np.zeros((len(sel), 2 * n))
    rows[np.arange(len(sel)), 1 + sel] = 1.0
    return modal_decomposition(A, B, rows)


def renewal_block(p, rng: np.random.Generator, b: int):
    """Renewal events for distance block b: one per miniblock in each interval [j a, (j+1) a)."""
    nb = BLOCK_INTERVALS
    j = np.arange(b * nb, (b + 1) * nb, dtype=float)
    r_pos = rng.random((p.N, nb))
    r_val = rng.random((p.N, nb))
    pos = ((j[None, :] + r_pos) * p.a).ravel()
    idx = np.repeat(np.arange(p.N), nb)
    val = (p.alpha * p.f_kin * (r_val - 0.5)).ravel()
    order = np.argsort(pos, kind="stable")
    return pos[order], idx[order].astype(np.int64), val[order], (b + 1) * nb * p.a


def initial_state(p, md: Modes, n: int, duration: float, seed) -> dict:
    """The state of a run at t = 0: the generator, every miniblock's first force, modal coordinates at rest, output
    buffers of n samples and room for the expected renewals."""
    rng = np.random.default_rng(seed)
    forces = p.alpha * p.f_kin * (rng.random(p.N) - 0.5)
    n_rows = md.C_r.shape[0]
    ev_time = np.empty(int(p.N * (p.v * duration * 1.5 / p.a + 2 * BLOCK_INTERVALS)) + 16)
    return {"rng": rng, "forces": forces, "qr": np.zeros(len(md.lam_r)), "qc": np.zeros(len(md.lam_c), dtype=complex),
            "gr": md.B_r @ forces, "gc": md.B_c @ forces.astype(np.complex128), "x": np.empty(n), "f": np.empty(n),
            "xc": np.empty((n if n_rows else 0, n_rows)), "ev_time": ev_time,
            "ev_index": np.empty(len(ev_time), dtype=np.int64), "ev_count": 0, "k": 0, "b": 0, "pos": np.empty(0),
            "idx": np.empty(0, dtype=np.int64), "val": np.empty(0), "ptr": 0, "boundary": -np.inf, "need_block": True}


def next_block(p, st: dict):
    """Append the next distance block of renewals to the loaded ones (dropping those passed) and make room for
    their events."""
    new_pos, new_idx, new_val, st["boundary"] = renewal_block(p, st["rng"], st["b"])
    st["b"] += 1
    ptr = st["ptr"]
    st["pos"] = np.concatenate([st["pos"][ptr:], new_pos])
    st["idx"] = np.concatenate([st["idx"][ptr:], new_idx])
    st["val"] = np.concatenate([st["val"][ptr:], new_val])
    st["ptr"] = 0
    if st["ev_count"] + len(st["pos"]) > len(st["ev_time"]):
        grow = max(len(st["ev_time"]), len(st["pos"]))
        st["ev_time"] = np.concatenate([st["ev_time"], np.empty(grow)])
        st["ev_index"] = np.concatenate([st["ev_index"], np.empty(grow, dtype=np.int64)])


def advance(p, md: Modes, st: dict, k_stop: int, dt_out: float):
    """Propagate the run's state ``st`` (:func:`initial_state`) to output step ``k_stop``: the exact kernel between
    renewals, renewal blocks drawn as the kernel reaches the end of the loaded ones. Computation only."""
    nr, nc, n_rows = len(md.lam_r), len(md.lam_c), md.C_r.shape[0]
    scratch = (np.empty(nr), np.empty(nr), np.empty(nc, dtype=np.complex128), np.empty(nc, dtype=np.complex128),
               np.empty(nr), np.empty(nc, dtype=np.complex128))
    while st["k"] < k_stop:
        if st["need_block"]:  # the kernel stopped near the end of the loaded renewals
            next_block(p, st)
        x, f, xc, ev_time, pos, ptr = st["x"], st["f"], st["xc"], st["ev_time"], st["pos"], st["ptr"]
        qr, qc, gr, gc = st["qr"], st["qc"], st["gr"], st["gc"]
        # the kernel writes x, f (and xc when per-contact rows are asked) rows k..k_stop-1 and one event per renewal
        # passed, unchecked (numba): refuse buffers too small for that
        if not (x.shape[0] >= k_stop and f.shape[0] >= k_stop and (n_rows == 0 or xc.shape[0] >= k_stop)
                and ev_time.shape[0] >= st["ev_count"] + len(pos) - ptr
                and qr.shape == gr.shape == md.lam_r.shape and qc.shape == gc.shape == md.lam_c.shape):
            raise RuntimeError(f"spring_block.simulate: buffers too small (x {x.shape[0]}, f {f.shape[0]} rows for "
                               f"{k_stop}; events {ev_time.shape[0]} for {st['ev_count'] + len(pos) - ptr})")
        k_new, new_ptr, new_count = run_renewals(md.lam_r, md.c0_r, md.B_r, md.lam_c, md.c0_c, md.B_c, md.C_r, md.C_c,
                                                 qr, gr, qc, gc, st["forces"], p.v, dt_out, st["k"], k_stop, pos,
                                                 st["idx"], st["val"], ptr, st["boundary"], x, f, xc, ev_time,
                                                 st["ev_count"], *scratch)
        st["ev_index"][st["ev_count"]:new_count] = st["idx"][ptr:new_ptr]
        st["ev_count"], st["ptr"], st["k"] = new_count, new_ptr, k_new
        st["need_block"] = k_new < k_stop


def run(p, md: Modes, st: dict, n: int, dt_out: float, checkpoint_every: float | None = None, save=None):
    """Advance the run's state ``st`` to output step ``n``, handing it to ``save(st)`` (when given) every
    ``checkpoint_every`` simulated seconds before the end: the checkpoints of a long run, written by the caller."""
    every = n if not checkpoint_every else max(1, int(round(checkpoint_every / dt_out)))
    st.setdefault("xc", np.empty((0, md.C_r.shape[0])))
    st.setdefault("need_block", True)
    for k_stop in [*range((st["k"] // every + 1) * every, n, every), n]:  # the checkpoints, then the end
        advance(p, md, st, k_stop, dt_out)
        if save is not None and k_stop < n:
            save(st)
    if not np.all(np.isfinite(st["x"])):
        raise FloatingPointError("model I produced non-finite positions; please report the parameters")
