"""Engine speed against error: wall time per simulated second against the error of C_x relative to a
converged run with the same seed (same substrate and forces), and the Pareto front. Used by
compare/studies/work_precision.py and the full `frictionnoise report`."""
from __future__ import annotations

import time

import numpy as np

from .spectra import band_average, displacement_spectrum

__all__ = ["engine_work_precision", "pareto"]

REFERENCE = (2.5e-5, 20)  # dt (s), solver iterations


def pareto(points) -> list:
    """Indices of (cost, error) points not dominated by another (both smaller-is-better)."""
    keep = []
    for i, (c, e) in enumerate(points):
        if not any(c2 <= c and e2 <= e and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            keep.append(i)
    return keep


def engine_work_precision(scenario, settings, duration: float, seed: int = 0, reference=REFERENCE) -> list[dict]:
    """Run the reference and each (dt, iterations) setting; error = mean over 8 log bands in 2-1000 rad/s of
    |ln C_x / C_x(reference)|. Returns rows with cost (wall s per simulated s), error and Pareto membership;
    the scenario's own (dt, iterations) is marked default. ``reference``: the (dt, iterations) of the converged
    run (default :data:`REFERENCE`)."""
    import engine_sim

    default = (scenario.run.dt, scenario.run.iterations)
    rows, ref = [], None
    reference = tuple(reference)
    for dt, it in [reference] + [s for s in settings if tuple(s) != reference]:
        sc = scenario.with_run(dt=dt, dt_out=1e-3, iterations=it, duration=duration, warmup=0.5)
        t0 = time.perf_counter()
        tr = engine_sim.run(sc, seed=seed)
        cost = (time.perf_counter() - t0) / duration
        spec = displacement_spectrum(tr.t, tr.x, nperseg=min(2**12, len(tr.t) // 2))
        if ref is None:
            ref, err = spec, 0.0
        else:
            edges = np.logspace(np.log10(max(2.0, 4 * spec.omega_min)), 3, 9)
            err = float(np.mean(np.abs(np.log(band_average(spec, edges) / band_average(ref, edges)))))
        rows.append({"dt": dt, "iterations": it, "cost": cost, "error": err, "reference": (dt, it) == reference,
                     "default": (dt, it) == default})
    front = set(pareto([(r["cost"], r["error"]) for r in rows[1:]]))
    for i, r in enumerate(rows[1:]):
        r["pareto"] = i in front
    rows[0]["pareto"] = None
    return rows
