"""Wear particles in a scene: trap/release episodes, their distributions, and model II built from them.

Pure numerics on an engine trace (no I/O). An episode is a run of consecutive output samples in which a particle
keeps one state (0 idle: not touching its pad; 1 trapped: touching it and at rest on the substrate; 2 moving).
Its force is the mean tangential force the particle exerts on its pad over the episode.

Model II from the measured episodes: eq. (B2) sums independent rectangles. Written with the empirical law of
the episodes instead of P_A, P_B, c_A, c_B, it reads

    C_F(omega) = 1 / (pi T) * sum_k c_k^2 (1 - cos omega tau_k) / omega^2,

the sum over every particle's episodes k of duration tau_k and height c_k (episode force minus the particle's
mean force), T the run's duration. It is exact for rectangles of independent random sign, the assumption (B2)
rests on; correlations between a particle's successive episodes (a trapped episode ends when the pad drags the
grain away, so a moving one follows) are what it leaves out.
"""
from __future__ import annotations

import numpy as np

__all__ = ["episodes", "model_II_from_episodes", "duration_summary"]


def episodes(p_state: np.ndarray, p_force: np.ndarray, dt: float) -> dict:
    """Episodes of every particle: arrays ``state``, ``tau`` [s], ``force`` [N] (episode mean), ``c`` [N]
    (episode mean minus the particle's mean), ``particle``. The first and last episode of each particle are cut
    by the record and left out (their durations are unknown)."""
    st, tau, force, c, who = [], [], [], [], []
    n, P = p_state.shape
    for j in range(P):
        s = p_state[:, j]
        f = p_force[:, j]
        edges = np.flatnonzero(np.diff(s.astype(np.int16)) != 0) + 1
        starts = np.concatenate([[0], edges])
        ends = np.concatenate([edges, [n]])
        csum = np.concatenate([[0.0], np.cumsum(f)])
        mean_f = f.mean()
        for a, b in zip(starts[1:-1], ends[1:-1]):  # complete episodes only
            m = (csum[b] - csum[a]) / (b - a)
            st.append(s[a])
            tau.append((b - a) * dt)
            force.append(m)
            c.append(m - mean_f)
            who.append(j)
    return {"state": np.array(st, dtype=np.int8), "tau": np.array(tau), "force": np.array(force),
            "c": np.array(c), "particle": np.array(who, dtype=np.int64)}


def model_II_from_episodes(ep: dict, duration: float, omega) -> np.ndarray:
    """C_F(omega) [N^2 s] of the particles' summed force predicted by eq. (B2) with the measured episodes."""
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    tau, c2 = ep["tau"], ep["c"] ** 2
    out = np.empty(w.size)
    for i, wi in enumerate(w):
        out[i] = np.sum(c2 * (1.0 - np.cos(wi * tau))) / (np.pi * duration * wi**2)
    return out


def duration_summary(ep: dict) -> dict:
    """Counts, mean and quantiles of the trapped (1), moving (2) and idle (0) episode durations and forces."""
    out = {}
    for code, name in ((1, "trapped"), (2, "moving"), (0, "idle")):
        sel = ep["state"] == code
        t, f = ep["tau"][sel], ep["force"][sel]
        if t.size == 0:
            out[name] = {"count": 0}
            continue
        q = np.quantile(t, [0.1, 0.5, 0.9])
        out[name] = {"count": int(t.size), "tau_mean": float(t.mean()), "tau_q10": float(q[0]), "tau_median": float(q[1]),
                     "tau_q90": float(q[2]), "tau_max": float(t.max()), "force_mean": float(f.mean()),
                     "force_rms": float(np.sqrt(np.mean(f**2)))}
    return out
