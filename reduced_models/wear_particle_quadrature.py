"""The quadrature of model II's closed forms (:mod:`reduced_models.wear_particle`): Gauss-Legendre panels over the
quantile of a duration law's mean time, and the nodes and weights over a particle's two mean times (tau_A, tau_B)
for either link between them."""
from __future__ import annotations

import functools
import math

import numpy as np

__all__ = ["quantile_grid", "mean_time_pairs"]


@functools.lru_cache(maxsize=64)
def _legendre(n: int):
    """Gauss-Legendre nodes and weights on [-1, 1] (read-only: shared by every call; a fit of model II's family
    evaluates its closed form thousands of times, and numpy's leggauss took 60 % of each evaluation)."""
    u, wts = np.polynomial.legendre.leggauss(n)
    u.flags.writeable = wts.flags.writeable = False
    return u, wts


def quantile_grid(n: int, decades: float):
    """Gauss-Legendre nodes and weights for Int_0^1 du, in panels of about half a decade of tau."""
    u, wts = _legendre(n)
    panels = max(1, int(math.ceil(decades / 0.5)))
    edges = np.linspace(0.0, 1.0, panels + 1)
    nodes = np.concatenate([0.5 * (hi - lo) * u + 0.5 * (hi + lo) for lo, hi in zip(edges[:-1], edges[1:])])
    weights = np.concatenate([0.5 * (hi - lo) * wts for lo, hi in zip(edges[:-1], edges[1:])])
    return nodes, weights


def mean_time_pairs(P, order: int):
    """(tau_A, tau_B, weight) over the joint law of a particle's two mean times (``P`` a
    :class:`~reduced_models.wear_particle.WearParticleParams`; ``order`` Gauss-Legendre nodes per panel)."""
    dec = lambda law: math.log10(law.tau_max / law.tau_min)
    if P.tau_link == "same_rank":
        u, w = quantile_grid(order, max(dec(P.trapped), dec(P.sliding), 0.1))
        return P.trapped.means_at(u), P.sliding.means_at(u), w
    uA, wA = quantile_grid(order, dec(P.trapped)) if P.trapped.tau_min < P.trapped.tau_max else (np.array([0.0]), np.array([1.0]))
    uB, wB = quantile_grid(order, dec(P.sliding)) if P.sliding.tau_min < P.sliding.tau_max else (np.array([0.0]), np.array([1.0]))
    UA, UB = np.meshgrid(uA, uB, indexing="ij")
    return P.trapped.means_at(UA.ravel()), P.sliding.means_at(UB.ravel()), np.outer(wA, wB).ravel()
