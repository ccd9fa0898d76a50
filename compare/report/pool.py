"""Worker processes that stop when asked: a process pool whose workers leave Ctrl-C to the parent, and which the
parent ends at once (terminate, then kill) when it is interrupted or fails, instead of waiting for the running
tasks at exit (which would print the workers' tracebacks). The workers can tell the parent when numba first
compiles in one of them (numba's "numba:compile" event), so the command line can say why the first run is slow."""
from __future__ import annotations

import signal
from contextlib import contextmanager

__all__ = ["process_pool"]


def _start_worker(compiled=None):
    # a terminal's Ctrl-C reaches the whole process group: the parent handles it and ends the workers
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if compiled is not None:
        from numba.core import event

        class _OnCompile(event.Listener):
            def on_start(self, ev):
                compiled.set()

            def on_end(self, ev):
                pass

        event.register("numba:compile", _OnCompile())


@contextmanager
def _watch(flag, on_compile, poll: float = 0.1):
    """Call ``on_compile()`` from a thread of this process when a worker sets ``flag`` (and once more at the end if
    it was set; an idempotent callable, such as :func:`compare.cli.compile_notice.announcer`'s, says it once)."""
    import threading

    done = threading.Event()

    def watch():
        while not done.is_set():
            if flag.wait(poll):
                on_compile()
                return

    thread = threading.Thread(target=watch, daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join()
        if flag.is_set():  # set as the pool closed, before the thread looked: said here (at most once if idempotent)
            on_compile()


def _end(pool, others: set, grace: float = 1.0):
    """Cancel the queued tasks and end the pool's workers: this process's multiprocessing children that are not in
    ``others`` (those it had before the pool)."""
    import multiprocessing

    procs = [p for p in multiprocessing.active_children() if p not in others]
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
def process_pool(workers: int, on_compile=None):
    """A ProcessPoolExecutor of ``workers`` spawned processes (spawn, not fork: the parent may hold threads, e.g.
    a progress bar's monitor, whose locks a fork would copy held). On any exception, KeyboardInterrupt included,
    queued tasks are cancelled and the worker processes ended before the exception goes on. ``on_compile()`` is
    called once, in this process, when numba first compiles a kernel in a worker (not on a disk-cache hit)."""
    from contextlib import nullcontext

    import multiprocessing
    import sys
    from concurrent.futures import ProcessPoolExecutor

    # the pool's semaphores, left to multiprocessing's resource tracker when Ctrl-C ends the workers and the CLI
    # exits at once, are cleaned up by it with a warning printed under our one line: the tracker (started with this
    # process's -W options) stays quiet (as the sweep's LocalCluster does)
    if "ignore:resource_tracker:UserWarning" not in sys.warnoptions:
        sys.warnoptions.append("ignore:resource_tracker:UserWarning")
    others = set(multiprocessing.active_children())  # children that are not the pool's, left alone by _end
    ctx = multiprocessing.get_context("spawn")
    flag = ctx.Event() if on_compile is not None else None
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_start_worker, initargs=(flag,))
    with _watch(flag, on_compile) if flag is not None else nullcontext():
        try:
            yield pool
        except BaseException:
            _end(pool, others)
            raise
        pool.shutdown()
