"""Parameter sweeps: a grid over model or scenario parameters and seeds, run serially or on
dask.distributed, with per-task results cached on disk (a rerun completes only what is missing).

Sweep file (TOML)::

    name = "velocity_model1"
    target = "model_I"            # model_I | model_II | model_III | scenario
    scenario = "../pads_friction_patches.toml"   # for target = "scenario", relative to this file
    [fixed]                       # held fixed: model parameters, or run settings (duration, dt_out)
    duration = 300.0
    [grid]                        # the Cartesian product of these lists; "seed" sets the seeds
    v = [1e-4, 5e-4, 1e-3]
    seed = [0]
    [analysis]
    omega_ref = [70.0, 140.0]     # band (rad/s) for C_x at fixed omega against v

Each task returns its log-binned spectrum and fit, never the raw trace. Pure numerics except
:func:`run_sweep`, which does the I/O and scheduling.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from frictionnoise import atomic_write

__all__ = ["SweepSpec", "SweepError", "SchedulerError", "load_sweep", "expand", "run_task", "run_sweep", "load_results",
           "velocity_analysis"]

_TARGETS = ("model_I", "model_II", "model_III", "scenario")
_RUN_KEYS = {"duration", "dt_out"}


class SweepError(ValueError):
    """An invalid sweep file: the message names the file and the field."""


@dataclass(frozen=True)
class SweepSpec:
    name: str
    target: str
    fixed: dict
    grid: dict
    analysis: dict = field(default_factory=dict)
    scenario: str | None = None
    description: str = ""


# a task's simulated duration when the sweep sets none (as in run_task)
_DEFAULT_DURATION = {"model_I": lambda p: 300.0, "model_II": lambda p: 500.0, "model_III": lambda p: 2**18 * p.dt}
_TOP = {"name": str, "description": str, "target": str, "scenario": str, "fixed": dict, "grid": dict,
        "analysis": dict}
_MAX_DURATION = 1e5  # s of simulated time per task


def _params_class(target):
    if target == "model_I":
        from reduced_models.spring_block import SpringBlockParams
        return SpringBlockParams
    if target == "model_III":
        from reduced_models.asperity_force import AsperityForceParams
        return AsperityForceParams
    from reduced_models.wear_particle import WearParticleParams
    return WearParticleParams


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _model_fields(target) -> dict:
    """Settable fields of a model's parameters: name -> default value (its type is the expected one)."""
    import dataclasses

    out = {}
    for f in dataclasses.fields(_params_class(target)):
        if not f.init or not f.repr:
            continue  # derived flags, not parameters
        # a field built by a factory (e.g. a distribution spec) is left to the model's own validation
        out[f.name] = f.default if f.default is not dataclasses.MISSING else (_ANY if f.default_factory
                                                                             is not dataclasses.MISSING else None)
    return out


_ANY = object()


def _check_value(where: str, key: str, v, expected):
    """Type per key: numbers where the default is a number (finite; ints where an int is expected), strings and
    booleans where those are."""
    if expected is _ANY:
        return
    if isinstance(expected, bool):
        ok = isinstance(v, bool)
        kind = "true or false"
    elif isinstance(expected, int):
        ok = isinstance(v, int) and not isinstance(v, bool)
        kind = "a whole number"
    elif isinstance(expected, float) or expected is None:
        ok = _is_number(v)
        kind = "a finite number"
    elif isinstance(expected, str):
        ok = isinstance(v, str)
        kind = "a string"
    else:
        ok = True
        kind = ""
    if not ok:
        raise SweepError(f"{where}: {key} must be {kind} (got {v!r})")


def _check_run(where: str, key: str, v):
    if not _is_number(v) or not 0 < v <= _MAX_DURATION:
        raise SweepError(f"{where}: {key} must be a number of seconds in (0, {_MAX_DURATION:g}] (got {v!r})")


def load_sweep(path) -> SweepSpec:
    """Read and validate a sweep file, every key and every grid point, before anything runs: unknown keys are
    named with the list of valid ones; types and ranges are checked per key (the models' own validation names
    the field for ranges)."""
    from .inputs import InputError, read_toml

    path = Path(path)
    try:
        d = read_toml(path, "sweep TOML file")
    except InputError as e:
        raise SweepError(str(e)) from None
    bad = sorted(set(d) - set(_TOP))
    if bad:
        raise SweepError(f"{path}: unknown key {bad[0]!r}; valid keys: {', '.join(sorted(_TOP))}")
    for k, typ in _TOP.items():
        if k in d and not isinstance(d[k], typ):
            raise SweepError(f"{path}: {k} must be a {'table' if typ is dict else 'string'} (got {d[k]!r})")
    target = d.get("target")
    if target not in _TARGETS:
        raise SweepError(f"{path}: target must be one of {', '.join(_TARGETS)} (got {target!r})")
    grid, fixed, analysis = d.get("grid", {}), d.get("fixed", {}), d.get("analysis", {})
    if not grid or not all(isinstance(v, list) and v for v in grid.values()):
        raise SweepError(f"{path}: [grid] must hold non-empty lists of values")
    scen = d.get("scenario")
    if target == "scenario":
        if not scen:
            raise SweepError(f"{path}: target = 'scenario' needs scenario = <path>")
        scen = str((path.parent / scen).resolve())
        if not Path(scen).exists():
            raise SweepError(f"{path}: scenario {scen}: no such file")
    elif scen is not None:
        raise SweepError(f"{path}: scenario = ... applies only to target = 'scenario' (target is {target!r})")
    if target != "scenario":
        model = _model_fields(target)
        valid = sorted(model) + sorted(_RUN_KEYS)
        for sec, table in (("fixed", fixed), ("grid", grid)):
            for key in table:
                if key == "seed" and sec == "grid":
                    continue
                if key not in model and key not in _RUN_KEYS:
                    extra = ", seed" if sec == "grid" else ""
                    raise SweepError(f"{path}: unknown key {key!r} in [{sec}]; valid names: {', '.join(valid)}{extra}")
                values = table[key] if sec == "grid" else [table[key]]
                for v in values:
                    if key in _RUN_KEYS:
                        _check_run(path, f"{sec}.{key}", v)
                    else:
                        _check_value(path, f"{sec}.{key}", v, model[key])
    else:
        for sec, table in (("fixed", fixed), ("grid", grid)):
            for key in table:
                if key == "duration":
                    for v in (table[key] if sec == "grid" else [table[key]]):
                        _check_run(path, f"{sec}.{key}", v)
                elif key == "seed" and sec == "grid":
                    pass
                elif "." not in key:
                    raise SweepError(f"{path}: unknown key {key!r} in [{sec}]; scenario parameters are written "
                                     "section.key (e.g. drive.v), besides duration and seed")
    seeds = grid.get("seed", [0])
    if not all(isinstance(x, int) and not isinstance(x, bool) and 0 <= x < 2**63 for x in seeds):
        raise SweepError(f"{path}: grid.seed must be a list of whole numbers >= 0 (got {seeds!r})")
    bad = sorted(set(analysis) - {"omega_ref", "omega_max", "wear"})  # wear = true: compare/wear_study.py's statistics
    if bad:
        raise SweepError(f"{path}: unknown key {bad[0]!r} in [analysis]; valid names: omega_max, omega_ref, wear")
    ref = analysis.get("omega_ref")
    if ref is not None and not (isinstance(ref, list) and len(ref) == 2 and all(_is_number(x) for x in ref)
                                and 0 < ref[0] < ref[1]):
        raise SweepError(f"{path}: analysis.omega_ref must be two numbers 0 < lo < hi in rad/s (got {ref!r})")
    om = analysis.get("omega_max")
    if om is not None and not (_is_number(om) and om > 0):
        raise SweepError(f"{path}: analysis.omega_max must be a positive number in rad/s (got {om!r})")
    spec = SweepSpec(name=d.get("name", path.stem), target=target, fixed=fixed, grid=grid, analysis=analysis,
                     scenario=scen, description=d.get("description", ""))
    try:  # every grid point's parameters once (the models' and the scenario's own range checks)
        for params, _ in expand(spec):
            obj, run = _build(spec, params)
            if target in ("model_I", "model_II", "model_III"):
                step = obj.dt if target == "model_III" else run.get("dt_out", 1e-3)
                dur = run.get("duration", _DEFAULT_DURATION[target](obj))
                if not dur >= 2 * step:
                    raise SweepError(f"{path}: duration = {dur:g} s holds fewer than two steps of {step:.3g} s "
                                     f"(at {', '.join(f'{k} = {v}' for k, v in params.items())})")
    except (TypeError, ValueError) as e:
        if isinstance(e, SweepError):
            raise
        raise SweepError(f"{path}: {e}") from None
    return spec


def expand(spec: SweepSpec):
    """[(params, seed)] over the grid's Cartesian product (seed from grid["seed"], default [0])."""
    keys = [k for k in spec.grid if k != "seed"]
    seeds = spec.grid.get("seed", [0])
    out = []
    for combo in itertools.product(*(spec.grid[k] for k in keys)):
        params = {**spec.fixed, **dict(zip(keys, combo))}
        for s in seeds:
            out.append((params, int(s)))
    return out


def task_id(spec: SweepSpec, params: dict, seed: int) -> str:
    key = json.dumps({"target": spec.target, "scenario": spec.scenario, "params": params, "seed": seed}, sort_keys=True)
    return hashlib.sha1(key.encode()).hexdigest()[:16]


def _build(spec: SweepSpec, params: dict):
    """The model parameters (or scenario) and run settings of one grid point; raises on bad values."""
    model = {k: v for k, v in params.items() if k not in _RUN_KEYS}
    run = {k: v for k, v in params.items() if k in _RUN_KEYS}
    if spec.target == "model_I":
        from reduced_models.spring_block import SpringBlockParams
        return SpringBlockParams(**model), run
    if spec.target == "model_III":
        from reduced_models.asperity_force import AsperityForceParams
        return AsperityForceParams(**model), run
    if spec.target == "model_II":
        from reduced_models.wear_particle import WearParticleParams
        return WearParticleParams(**model), run
    from engine_sim.scenario import load_scenario, scenario_from_dict
    base = load_scenario(spec.scenario).to_dict()
    from .wear_study import expand_factors  # the wear study's named factors (study.size, study.track)
    for k, v in expand_factors(model).items():
        sec, _, key = k.partition(".")
        if not key or sec not in base or not isinstance(base[sec], dict):
            raise ValueError(f"scenario parameter {k!r} must be written section.key, e.g. drive.v")
        base[sec][key] = v
    if "duration" in run:
        base["run"]["duration"] = run["duration"]
    return scenario_from_dict(base, where=spec.scenario), run


def run_task(spec: SweepSpec, params: dict, seed: int) -> dict:
    """Run one grid point; return its log-binned C_x, fit and timings (JSON-ready). Never raises: an error
    is returned as {"error": ...} with the parameters, so one failure loses nothing else."""
    from .fits import fit_power_law
    from .spectra import displacement_spectrum, log_bin

    t0 = time.perf_counter()
    extra = {}
    try:
        obj, run = _build(spec, params)
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
        spec_x = displacement_spectrum(tr.t, tr.x)
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
    done = list((out / "tasks").glob("*.json"))
    return {"done": len(done), "ran": ran, "failed": failed, "total": len(expand(spec))}


def _order_key(r: dict):
    """Sort key of a result: its parameters by name (numbers before strings), then its seed."""
    def one(v):
        return (0, v, "") if isinstance(v, (int, float)) and not isinstance(v, bool) else (1, 0, json.dumps(v))
    return tuple(one(r["params"][k]) for k in sorted(r["params"])) + (one(r["seed"]),)


def load_results(out_dir) -> list:
    """The stored task results, sorted by their parameters (then seed), whatever order they completed in."""
    rs = [json.loads(p.read_text()) for p in Path(out_dir, "tasks").glob("*.json")]
    return sorted(rs, key=_order_key)


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
