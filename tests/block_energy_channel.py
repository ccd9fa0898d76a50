"""A recorded channel added as a user's plugin: the block's kinetic energy at each sample, this module alone.

Named in a scenario's ``plugins`` and ``channels``, it is recorded into ``trace.channels["block_kinetic_energy"]``
(J, one column): 0.5 M (v_x^2 + v_y^2) of the block, from pymunk's body buffer by its own compiled reduction.
"""
from __future__ import annotations

import numba
import numpy as np

from engine_sim.channels import BLOCK, BODY_FLOATS, CHANNELS, Channel, body_of


@numba.njit(cache=True)
def block_kinetic(ids, fl, tab, table, out):
    """out[0] = 0.5 M (v_x^2 + v_y^2) of the block (``table``: M; scene units); 0 if the block is asleep."""
    out[0] = 0.0
    for r in range(ids.shape[0]):
        kind, _ = body_of(tab, ids[r])
        if kind == BLOCK:
            f0 = BODY_FLOATS * r
            out[0] = 0.5 * table[0] * (fl[f0 + 2] * fl[f0 + 2] + fl[f0 + 3] * fl[f0 + 3])


@CHANNELS.register
class BlockKineticEnergy(Channel):
    """The block's kinetic energy (module docstring)."""

    name = "block_kinetic_energy"
    kind = "energy"
    quantity = "energy"
    reduction = block_kinetic

    def table(self):
        return np.array([self.scene.M])
