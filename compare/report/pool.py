"""Worker processes that stop when asked: a process pool whose workers leave Ctrl-C to the parent, and which the
parent ends at once (terminate, then kill) when it is interrupted or fails, instead of waiting for the running
tasks at exit (a Ctrl-C during `frictionnoise report` once took 15 s and printed the workers' tracebacks)."""
from __future__ import annotations

import signal
from contextlib import contextmanager

__all__ = ["process_pool"]


def _leave_sigint_to_parent():
    # a terminal's Ctrl-C reaches the whole process group: the parent handles it and ends the workers
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _end(pool, grace: float = 1.0):
    procs = list((getattr(pool, "_processes", None) or {}).values())  # ProcessPoolExecutor keeps them by pid
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=grace)
        if p.is_alive():
            p.kill()
            p.join(timeout=grace)


@contextmanager
def process_pool(workers: int):
    """A ProcessPoolExecutor of ``workers`` spawned processes (spawn, not fork: the parent may hold threads, e.g.
    a progress bar's monitor, whose locks a fork would copy held). On any exception, KeyboardInterrupt included,
    queued tasks are cancelled and the worker processes ended before the exception goes on."""
    import multiprocessing
    import sys
    from concurrent.futures import ProcessPoolExecutor

    # the pool's semaphores, left to multiprocessing's resource tracker when Ctrl-C ends the workers and the CLI
    # exits at once, are cleaned up by it with a warning printed under our one line: the tracker (started with this
    # process's -W options) stays quiet (as the sweep's LocalCluster does)
    if "ignore:resource_tracker:UserWarning" not in sys.warnoptions:
        sys.warnoptions.append("ignore:resource_tracker:UserWarning")
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                               initializer=_leave_sigint_to_parent)
    try:
        yield pool
    except BaseException:
        _end(pool)
        raise
    pool.shutdown()
