"""The velocity part of the shipped laws as the recorder reads it at a sample, in one compiled form (scene units).

A law hands the recorder its velocity part through :meth:`engine_sim.laws.Law.recorded_drag`: a numba kernel
``kernel(v, rows, out)`` and one row of parameters per sliding body. The kernel writes into ``out[i]`` the x force
g(v[i]) of the law's velocity part on sliding body i at its velocity v[i] (the body's own force; the recorder counts
it against sliding). The linear, log and rate-and-state laws share :func:`log_drag`; a law of another velocity form
brings its own kernel of the same signature.
"""
from __future__ import annotations

import numba
import numpy as np

__all__ = ["log_drag"]


@numba.njit(cache=True)
def log_drag(v, rows, out):
    """g(v) = c v + b N_pad ln(1 + |v| / v_c) sign(v) per sliding body; ``rows``: (c, b N_pad, v_c) per body
    (b N_pad = 0: the viscous part alone)."""
    for i in range(v.shape[0]):
        vx = v[i]
        f_v = rows[i, 0] * vx
        if rows[i, 1] > 0.0:
            f_v += np.sign(vx) * rows[i, 1] * np.log1p(abs(vx) / rows[i, 2])
        out[i] = f_v
