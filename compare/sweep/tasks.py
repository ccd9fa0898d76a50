"""One sweep task: a grid point run and reduced to its log-binned spectrum and fit, never the raw trace.

A model target runs the registered model (``reduced_models.MODELS``: its simulator, default duration and output
step, fit band and the series whose spectrum it returns); the target ``scenario`` runs the scene. The sweep file's
format is in :mod:`compare.sweep.spec`; :mod:`compare.sweep.run` schedules the tasks and stores their results.
"""
from __future__ import annotations

import math
import time

from .spec import SCENARIO, SweepSpec, build_point, model_of

__all__ = ["run_task"]


def _run_model(spec: SweepSpec, obj, run: dict, seed: int):
    """(trace, sliding speed, fit band, series name) of a registered model's task."""
    model = model_of(spec)
    dt_out = run.get("dt_out", model.default_dt_out(obj))
    tr = model.simulate(obj, run.get("duration", model.default_duration(obj)), dt_out, seed=seed)
    return tr, obj.v, model.fit_band(obj, dt_out), model.SWEEP_SERIES


def _run_scene(spec: SweepSpec, sc, seed: int, extra: dict):
    """(trace, sliding speed, fit band, series name) of a scene's task; the wear study's statistics go to ``extra``."""
    import engine_sim

    tr = engine_sim.run(sc, seed=seed)
    if tr.metadata.get("partial"):  # stopped by SIGINT/SIGTERM: not a result; the interrupt ends the sweep
        raise KeyboardInterrupt
    v = sc.steady_velocity
    band = (3 * v / sc.substrate.a, 30 * v / sc.substrate.a)
    if spec.analysis.get("wear"):  # the wear study's per-task statistics
        from ..analysis.wear_study import task_stats
        extra["wear"] = task_stats(tr, sc, band)
    vib = sc.vibration
    if vib is not None and vib.amplitude > 0:
        tr = _line_removed(tr, vib, extra)
    return tr, v, band, "x"


def _line_removed(tr, vib, extra: dict):
    """A shaken scene's trace with the line at the vibration's frequency and its first 4 harmonics fitted and
    removed from the position (:func:`compare.analysis.harmonics.remove_harmonics`, 2 differences: the scene's
    C_x falls near omega^-4), so the spectrum and fit hold the noise alone; the fitted line goes to ``extra``."""
    from dataclasses import replace

    from ..analysis.harmonics import remove_harmonics

    x, fit = remove_harmonics(tr.t, tr.x, 2 * math.pi * vib.frequency, harmonics=4, order=2)
    extra["line_removed"] = fit.to_dict()
    return replace(tr, x=x)


def _mean_forces(tr) -> dict:
    """Mean forces over the record (N): the drive's, the friction's Coulomb part F_t and viscous part F_drag."""
    return {"mean_F_drive": float(tr.F_drive.mean()), "mean_F_t": float(tr.F_t.mean()),
            "mean_F_drag": float(tr.F_drag.mean())}


def run_task(spec: SweepSpec, params: dict, seed: int) -> dict:
    """Run one grid point; return its log-binned spectrum (C_x, or C_F for a model whose ``SWEEP_SERIES`` is
    "force"), fit and timings (JSON-ready). Never raises: an error is returned as {"error": ...} with the
    parameters, so one failure loses nothing else."""
    from ..analysis.record_model import fit_series
    from ..analysis.spectra import displacement_spectrum, force_series_spectrum, log_bin

    t0 = time.perf_counter()
    extra = {}
    try:
        obj, run = build_point(spec, params)
        if spec.target == SCENARIO:
            tr, v, band, series = _run_scene(spec, obj, seed, extra)
            extra.update(_mean_forces(tr))
        else:
            tr, v, band, series = _run_model(spec, obj, run, seed)
        # a wear-study task's spectrum and fit on its own segments (the default ones leave a 3 s run's band unresolved)
        nper = extra["wear"]["nperseg"] if "wear" in extra else None
        if series == "x":
            spec_x = displacement_spectrum(tr.t, tr.x, nperseg=nper)
        else:
            spec_x = force_series_spectrum(tr.t, getattr(tr, series), nperseg=nper)
        if band is not None and band[1] < 2 * band[0]:
            band = None  # the model's own band has closed (e.g. v/a near omega_c): use the automatic one
        try:
            y = tr.x if series == "x" else getattr(tr, series)
            y = y.sum(axis=1) if y.ndim > 1 else y
            # the record model on the record; a force through its running sum (model II's 1/f is flatter than the
            # model's omega^-1.05)
            fit = fit_series(tr.t, y, band=band, quantity="x" if series == "x" else "F",
                             integrate=series != "x").to_dict()
        except ValueError as e:
            fit = {"error": str(e)}
        lb = log_bin(spec_x, 20)
        return {"params": params, "seed": seed, "v": v, "omega": lb.omega.tolist(), "C": lb.C.tolist(),
                "n_avg": lb.n_avg.tolist(), "fit": fit, "wall_s": time.perf_counter() - t0,
                "mean_velocity": float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])), **extra}
    except Exception as e:  # reported with its parameters; the sweep goes on
        return {"params": params, "seed": seed, "error": f"{type(e).__name__}: {e}", "wall_s": time.perf_counter() - t0}
