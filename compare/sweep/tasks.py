"""Parameter sweeps: a grid over model or scenario parameters and seeds, run serially or on
dask.distributed, with per-task results cached on disk (a rerun completes only what is missing).

The sweep file's format, with an example, is in :mod:`compare.sweep_spec`, which reads and checks it.

Each task returns its log-binned spectrum and fit, never the raw trace. Pure numerics except
:func:`run_sweep`, which does the I/O and scheduling.
"""
from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from frictionnoise import atomic_write

from .sweep_spec import SweepError, SweepSpec, build_point, expand, load_sweep, task_id

__all__ = ["SweepSpec", "SweepError", "SchedulerError", "load_sweep", "expand", "task_id", "run_task", "run_sweep",
           "load_results", "velocity_analysis"]


def run_task(spec: SweepSpec, params: dict, seed: int) -> dict:
    """Run one grid point; return its log-binned C_x, fit and timings (JSON-ready). Never raises: an error
    is returned as {"error": ...} with the parameters, so one failure loses nothing else."""
    from .fits import fit_power_law
    from .spectra import displacement_spectrum, log_bin

    t0 = time.perf_counter()
    extra = {}
    try:
        obj, run = build_point(spec, params)
        if spec.target == "model_I":
            from reduced_models import spring_block
            tr = spring_block.simulate(obj, run.get("duration", 300.0), run.get("dt_out", 1e-3), seed=seed)
            v = obj.v
            band = (10 * obj.v / obj.a, spring_block.crossover_frequency(obj) / 10)
        elif spec.target == "model_III":
            from reduced_models import asperity_force
            tr = asperity_force.simulate(obj, run.get("duration", 2**18 * obj.dt), seed=seed)
            v = obj.v
            band = (30 * obj.v / obj.w, math.pi / obj.dt / 4)
        elif spec.target == "model_II":
            from reduced_models import wear_particle
            tr = wear_particle.simulate(obj, run.get("duration", 500.0), run.get("dt_out", 1e-3), seed=seed)
            v = obj.v
            band = None
        else:
            import engine_sim
            tr = engine_sim.run(obj, seed=seed)
            v = obj.steady_velocity
            band = (3 * v / obj.substrate.a, 30 * v / obj.substrate.a)
            if spec.analysis.get("wear"):  # the wear study's per-task statistics (issue 17)
                from .wear_study import task_stats
                extra["wear"] = task_stats(tr, obj, band)
        # a wear-study task's spectrum and fit on its own segments (the default ones leave a 3 s run's band unresolved)
        spec_x = displacement_spectrum(tr.t, tr.x, nperseg=extra["wear"]["nperseg"] if "wear" in extra else None)
        if band is not None and band[1] < 2 * band[0]:
            band = None  # the model's own band has closed (e.g. v/a near omega_c): use the automatic one
        try:
            fit = fit_power_law(spec_x, band=band).to_dict()
        except ValueError as e:
            fit = {"error": str(e)}
        lb = log_bin(spec_x, 20)
        return {"params": params, "seed": seed, "v": v, "omega": lb.omega.tolist(), "C": lb.C.tolist(),
                "n_avg": lb.n_avg.tolist(), "fit": fit, "wall_s": time.perf_counter() - t0,
                "mean_velocity": float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])), **extra}
    except Exception as e:  # reported with its parameters; the sweep goes on
        return {"params": params, "seed": seed, "error": f"{type(e).__name__}: {e}", "wall_s": time.perf_counter() - t0}


def _write_json(path: Path, obj):
    atomic_write(path, json.dumps(obj))


class SchedulerError(RuntimeError):
    """The dask scheduler could not be reached; nothing was written."""


def _connect(scheduler: str | None, workers: int, connect_timeout: float):
    """(client, cluster or None): a client of the scheduler at ``scheduler`` (given up after ``connect_timeout``
    seconds with a SchedulerError) or of a new LocalCluster of ``workers`` single-threaded processes."""
    import logging

    from distributed import Client, LocalCluster

    if scheduler:
        # distributed logs every retry at ERROR with a traceback: quiet while connecting, the error says it all
        log = logging.getLogger("distributed")
        level = log.level
        log.setLevel(logging.CRITICAL)
        try:
            return Client(scheduler, timeout=f"{connect_timeout}s"), None
        except (OSError, TimeoutError, ValueError, TypeError) as e:
            reason = " ".join(str(e).split()) or type(e).__name__
            raise SchedulerError(f"no dask scheduler reachable at {scheduler} within {connect_timeout:g} s "
                                 f"({reason[:200]})") from None
        finally:
            log.setLevel(level)
    # silence_logs: the workers' warnings (a task cancelled by Ctrl-C, ...) would be printed under our one line
    # the workers' semaphores, left to multiprocessing's resource tracker when Ctrl-C ends them, are cleaned up by
    # it with a warning printed under our one line: the tracker (started with this process's -W options) stays quiet
    if "ignore:resource_tracker:UserWarning" not in sys.warnoptions:
        sys.warnoptions.append("ignore:resource_tracker:UserWarning")
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=logging.ERROR)
    return Client(cluster), cluster


def _close(client, cluster, interrupted: bool = False):
    """Close; on Ctrl-C (``interrupted``) at once: the local workers' processes are ended first (a graceful close
    took 13 s and logged the cancelled tasks), queued tasks are dropped with the client."""
    import logging
    import multiprocessing

    if interrupted:
        logging.getLogger("distributed").setLevel(logging.CRITICAL)  # the cancelled tasks' complaints
        procs = multiprocessing.active_children() if cluster is not None else []  # the LocalCluster's workers
        for p in procs:
            p.terminate()
        for p in procs:
            p.join(timeout=1)
            if p.is_alive():
                p.kill()
    for c in (client, cluster):
        if c is not None:
            try:
                c.close(timeout=0.2 if interrupted else 10)  # interrupted: the workers are gone already
            except BaseException:
                pass


def run_sweep(spec: SweepSpec, out_dir, *, scheduler: str | None = None, workers: int = 2, serial: bool = False,
              progress=None, connect_timeout: float = 10.0) -> dict:
    """Run the tasks whose results are not yet in ``out_dir/tasks``; return {"done", "ran", "failed", "total"}.

    ``serial``: in this process. Otherwise on dask.distributed: ``scheduler`` (an address such as
    tcp://host:8786, given up after ``connect_timeout`` seconds with a :class:`SchedulerError`, before anything
    is written) or a LocalCluster of ``workers`` single-threaded processes. Each task's result is stored as it
    completes, so an interrupted sweep (KeyboardInterrupt, which is re-raised once the workers are stopped) keeps
    what was done and a rerun completes only the rest.
    """
    out = Path(out_dir)
    todo = []
    for params, seed in expand(spec):
        tid = task_id(spec, params, seed)
        if not (out / "tasks" / f"{tid}.json").exists():
            todo.append((tid, params, seed))
    ran, failed = 0, 0
    client = cluster = None
    if todo and not serial:
        client, cluster = _connect(scheduler, workers, connect_timeout)
    (out / "tasks").mkdir(parents=True, exist_ok=True)
    (out / "failures").mkdir(exist_ok=True)

    def store(tid, res):
        nonlocal ran, failed
        if "error" in res:
            _write_json(out / "failures" / f"{tid}.json", res)
            failed += 1
        else:
            _write_json(out / "tasks" / f"{tid}.json", res)
            stale = out / "failures" / f"{tid}.json"
            if stale.exists():
                stale.unlink()
            ran += 1
        if progress is not None:
            progress(ran + failed, len(todo))

    if client is None:
        for tid, params, seed in todo:
            store(tid, run_task(spec, params, seed))
    else:
        from distributed import as_completed

        try:
            futs = {client.submit(run_task, spec, params, seed, pure=False, key=f"task-{tid}"): tid
                    for tid, params, seed in todo}
            for fut in as_completed(futs):
                store(futs[fut], fut.result())
        except BaseException:
            _close(client, cluster, interrupted=True)
            raise
        _close(client, cluster)
    ids = {task_id(spec, params, seed) for params, seed in expand(spec)}
    done = [p for p in (out / "tasks").glob("*.json") if p.stem in ids]
    return {"done": len(done), "ran": ran, "failed": failed, "total": len(ids)}


def _order_key(r: dict):
    """Sort key of a result: its parameters by name (numbers before strings), then its seed."""
    def one(v):
        return (0, v, "") if isinstance(v, (int, float)) and not isinstance(v, bool) else (1, 0, json.dumps(v))
    return tuple(one(r["params"][k]) for k in sorted(r["params"])) + (one(r["seed"]),)


def load_results(out_dir, spec: SweepSpec | None = None) -> list:
    """The stored task results, sorted by their parameters (then seed), whatever order they completed in.

    With ``spec``, only its grid's tasks: a folder reused after the grid changed keeps the old tasks' files (the
    cache), which are not part of this sweep.
    """
    paths = Path(out_dir, "tasks").glob("*.json")
    if spec is not None:
        ids = {task_id(spec, params, seed) for params, seed in expand(spec)}
        paths = [p for p in paths if p.stem in ids]
    return sorted((json.loads(p.read_text()) for p in paths), key=_order_key)


# ----------------------------------------------------------------------------- velocity analysis
def velocity_analysis(results: list, omega_ref=(70.0, 140.0), omega_max: float | None = None) -> dict:
    """The paper's velocity analysis over results that differ in v.

    - C_x at fixed omega: the mean over ``omega_ref`` of each run's spectrum (averaged over seeds), fitted
      against v in log-log (eq. 6 predicts C_x ~ v^3 for model I; the paper measures v^(5/3) on concrete).
    - Collapse (section 2): in the distance domain zeta(s), s = v t, the spectrum is C_s(q) = v C_x(omega = q v);
      if the noise is set by position, curves for different v coincide. The spread is the mean over a common
      abscissa grid of the standard deviation across velocities of ln C; ``collapse_gain`` is the spread in the
      frequency domain (ln C_x at common omega) over that in the distance domain (ln v C_x at common q), both on
      the range where every curve is defined and below ``omega_max`` (default: no limit).
    """
    from scipy import stats

    by_v: dict = {}
    for r in results:
        by_v.setdefault(float(r["v"]), []).append(r)
    vs = np.array(sorted(by_v))
    if len(vs) < 2:
        raise ValueError("velocity analysis needs results at two or more velocities")
    curves = []
    for v in vs:
        rs = by_v[v]
        w = np.asarray(rs[0]["omega"])
        C = np.mean([np.interp(np.log(w), np.log(r["omega"]), np.log(r["C"])) for r in rs], axis=0)
        keep = w <= omega_max if omega_max else np.ones(len(w), bool)
        curves.append((v, w[keep], C[keep]))
    lo, hi = omega_ref
    level = []
    for v, w, lnC in curves:
        m = (w >= lo) & (w <= hi)
        if not m.any():
            raise ValueError(f"no spectral point of the run at v = {v:g} m/s lies in omega_ref {omega_ref}")
        level.append(float(np.mean(lnC[m])))
    level = np.array(level)
    res = stats.linregress(np.log(vs), level)
    tq = float(stats.t.ppf(0.975, max(len(vs) - 2, 1)))

    def spread(xs_list, ys_list):
        a = max(x[0] for x in xs_list)
        b = min(x[-1] for x in xs_list)
        if not b > a:
            return float("nan"), (a, b)
        g = np.linspace(a, b, 200)
        Y = np.array([np.interp(g, x, y) for x, y in zip(xs_list, ys_list)])
        return float(np.mean(np.std(Y, axis=0))), (float(np.exp(a)), float(np.exp(b)))

    s_freq, r_freq = spread([np.log(w) for _, w, _ in curves], [lnC for _, _, lnC in curves])
    s_dist, r_dist = spread([np.log(w / v) for v, w, _ in curves], [lnC + np.log(v) for v, _, lnC in curves])
    return {
        "velocities": vs.tolist(), "omega_ref": list(omega_ref), "ln_C_at_omega_ref": level.tolist(),
        "exponent": float(res.slope), "exponent_err": tq * float(res.stderr) if len(vs) > 2 else float("nan"),
        "spread_frequency_domain": s_freq, "frequency_range": r_freq,
        "spread_distance_domain": s_dist, "q_range": r_dist,
        "collapse_gain": s_freq / s_dist if s_dist > 0 else float("inf"),
    }
