"""Running a sweep: its tasks serially or on dask.distributed, each result stored as it completes (a rerun
completes only what is missing), and the stored results read back in a stable order."""
from __future__ import annotations

import json
import sys
from pathlib import Path

from frictionnoise.base import atomic_write

from .spec import SweepSpec, expand, task_id
from .tasks import run_task

__all__ = ["SchedulerError", "run_sweep", "load_results", "write_json"]


def write_json(path: Path, obj):
    atomic_write(path, json.dumps(obj))


class SchedulerError(RuntimeError):
    """The dask scheduler could not be reached; nothing was written."""


def require_dask() -> None:
    """Raise :class:`SchedulerError` naming the extra to install when dask.distributed is not installed."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise SchedulerError("a sweep on dask needs the sweep extra: pip install 'frictionnoise[sweep]' "
                             "(or run it in this process with --serial)") from None


def _connect(scheduler: str | None, workers: int, connect_timeout: float):
    """(client, cluster or None): a client of the scheduler at ``scheduler`` (given up after ``connect_timeout``
    seconds with a SchedulerError) or of a new LocalCluster of ``workers`` single-threaded processes."""
    import logging

    require_dask()
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
    # no dashboard; the scheduler's HTTP server (health routes), which distributed starts even without one and would
    # put on port 8787, on a free local port: a second cluster (another sweep, a user's dask) holds 8787, and
    # distributed's "Port 8787 is already in use" warning would be printed under the sweep's own lines
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                           scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
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
            write_json(out / "failures" / f"{tid}.json", res)
            failed += 1
        else:
            write_json(out / "tasks" / f"{tid}.json", res)
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
