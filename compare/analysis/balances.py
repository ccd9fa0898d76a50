"""Energy and force balances of an engine trace: how well a run conserves what it should."""
from __future__ import annotations

import numpy as np

__all__ = ["balances"]


def balances(tr) -> dict:
    """Energy and force balance of an engine trace, relative to the drive's work and force."""
    resid = tr.work_drive[-1] + tr.work_recycle[-1] - tr.dissipated[-1] - tr.mech_energy[-1]
    return {"energy_balance_rel": float(resid / tr.work_drive[-1]),
            "force_balance_rel": float(np.mean(tr.F_t + tr.F_drag) / np.mean(tr.F_drive) - 1)}
