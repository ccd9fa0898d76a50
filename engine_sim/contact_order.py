"""The order of a sample's contacts: pymunk body ids to (kind, index) in the recorder's body table, and the arbiters
sorted by their bodies, contact point and impulse, so that sums over contacts do not depend on the order pymunk's
batch lists them in (its hash set's, with bodies named by address; both vary from run to run).
"""
from __future__ import annotations

import numba
import numpy as np

from .sample_layout import AF, JX, JY, PAX, PAY, STATIC

__all__ = ["body_of", "arbiter_keys", "arbiter_order"]


@numba.njit(cache=True)
def body_of(tab, body_id):
    """(kind, index) of a pymunk body id in the sorted body table; (STATIC, 0) for a body not in it."""
    lo, hi = 0, tab.shape[0]
    while lo < hi:  # bisection on the id column in place (a column view per call costs more than the search)
        mid = (lo + hi) // 2
        if tab[mid, 0] < body_id:
            lo = mid + 1
        else:
            hi = mid
    if lo < tab.shape[0] and tab[lo, 0] == body_id:
        return tab[lo, 1], tab[lo, 2]
    return STATIC, 0


@numba.njit(cache=True)
def _less(key, af, r, q):
    """Arbiter r before q: by the bodies' (kind, index), then contact point and impulse (all deterministic)."""
    for c in range(4):
        if key[r, c] != key[q, c]:
            return key[r, c] < key[q, c]
    for c in (PAX, PAY, JX, JY):
        if af[AF * r + c] != af[AF * q + c]:
            return af[AF * r + c] < af[AF * q + c]
    return False


@numba.njit(cache=True)
def arbiter_keys(ai, tab):
    """Each arbiter's bodies as (kind, index) of A, then of B (:func:`body_of`), one row per arbiter: looked up
    once per sample for the sort and the sums that follow."""
    n = ai.shape[0] // 3
    key = np.empty((n, 4), dtype=np.int64)
    for r in range(n):
        for s in range(2):
            key[r, 2 * s], key[r, 2 * s + 1] = body_of(tab, ai[3 * r + s])
    return key


@numba.njit(cache=True)
def arbiter_order(key, af):
    """The arbiters in a fixed order (tens to hundreds of rows). pymunk's batch lists them in its hash set's
    order and names bodies by address, both of which vary from run to run, and so would the last bits of per-pad and
    summed forces and of the friction power. Bodies are keyed by their (kind, index) in the body table
    (:func:`arbiter_keys`)."""
    n = key.shape[0]
    code = np.empty(n, dtype=np.int64)  # the bodies' keys in one integer, ordered as _less orders them
    for r in range(n):
        code[r] = ((((key[r, 0] + 1) << 20) + key[r, 1]) << 23) + ((key[r, 2] + 1) << 20) + key[r, 3]
    # a stable sort on the bodies first, then insertion by _less (the same stable order, from a nearly sorted start)
    order = np.argsort(code, kind="mergesort")
    for i in range(1, n):
        r = order[i]
        j = i - 1
        while j >= 0 and (code[r] < code[order[j]] or (code[r] == code[order[j]] and _less(key, af, r, order[j]))):
            order[j + 1] = order[j]
            j -= 1
        order[j + 1] = r
    return order
