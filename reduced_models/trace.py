"""The trace every reduced model returns (what compare needs: t, x, metadata, plus model channels) and the run
arguments every model takes."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from frictionnoise.base import check_seconds

__all__ = ["ModelTrace", "check_run"]


@dataclass(frozen=True)
class ModelTrace:
    """A sampled run of a reduced model.

    Attributes
    ----------
    t : ndarray
        Sample times (Units: s), uniform, starting at 0.
    x : ndarray
        Block position x(t) = v t + zeta(t) relative to its start (Units: m).
    force : ndarray
        The model's fluctuating force on the block, averaged over [t_k, t_k + dt) (Units: N). Model I: the
        summed random force sum_i f_i on the miniblocks; model Ib: that plus the micro sum sum_ij f_ij (the
        micro part alone in ``events["force_micro"]``); model II: sum of particle forces; model III: the
        friction force F(t).
    events : dict
        Model-specific event records (arrays), e.g. model I renewal times and miniblock indices.
    metadata : dict
        Model name, parameters (SI), seed, package version, and how the run was made.
    """

    t: np.ndarray
    x: np.ndarray
    force: np.ndarray
    events: dict = field(default_factory=dict)
    metadata: dict = field(default_factory=dict)

    @property
    def dt(self) -> float:
        return float(self.t[1] - self.t[0])


def check_run(duration, dt_out):
    """The run arguments every reduced model takes: a positive duration holding at least two output steps."""
    check_seconds("duration", duration)
    check_seconds("dt_out", dt_out)
    if int(round(duration / dt_out)) < 2:
        raise ValueError(f"duration {duration!r} s holds fewer than two output steps of {dt_out!r} s")
