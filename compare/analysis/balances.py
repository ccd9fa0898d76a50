"""Energy and force balances of an engine trace: how well a run conserves what it should."""
from __future__ import annotations

import numpy as np

__all__ = ["balances", "SAMPLES_PER_PERIOD"]

# Samples per vibration period from which a shaken scene's energy balance is resolved: the recorder integrates
# sampled powers by trapezoids, and past the pads' onset of reversal those powers carry harmonics of the vibration
# that fold onto their means when the output rate is a multiple of its frequency. Measured on the sweep's scenes at
# 1 kHz and 40 steps per period, past the onset: sampled every step (40 per period) within 6e-5 of the drive's
# work (0.1 s at 2.72 and 6.58 um), 8e-8 (3 s at 3 um); at 20 per period 7e-5 to 4.5e-4 over 0.1 s but 1.4e-3 and
# 1.5e-3 over 3 s at 3 um (two seeds); at 4 per period 5e-3 to 5e-2 (docs/results/vibration.md; `python -m
# compare.studies.energy_ledger` measures one sampling).
SAMPLES_PER_PERIOD = 40


def balances(tr) -> dict:
    """Energy and force balance of an engine trace, relative to the drive's work and force.

    W_drive + W_recycle (+ W_vibration in a shaken scene: the work of the inertial field or of the shaken guide) =
    dissipated + change of mechanical energy. ``energy_balance_resolved`` is False for a shaken trace sampled fewer
    than :data:`SAMPLES_PER_PERIOD` times per vibration period (``samples_per_vibration_period``), whose sampled powers
    do not resolve the vibration: its residual is then stated, not bounded.
    """
    w_vib = float(tr.work_vibration[-1]) if len(tr.work_vibration) else 0.0  # empty in a trace without the part
    resid = tr.work_drive[-1] + tr.work_recycle[-1] + w_vib - tr.dissipated[-1] - tr.mech_energy[-1]
    out = {"energy_balance_rel": float(resid / tr.work_drive[-1]),
           "force_balance_rel": float(np.mean(tr.F_t + tr.F_drag) / np.mean(tr.F_drive) - 1)}
    vib = (tr.metadata.get("scene") or {}).get("vibration")
    if vib and vib["amplitude"] > 0 and len(tr.t) > 1:
        n = 1.0 / (vib["frequency"] * float(tr.t[1] - tr.t[0]))
        out.update(samples_per_vibration_period=n, energy_balance_resolved=bool(n >= SAMPLES_PER_PERIOD * (1 - 1e-9)))
    return out

