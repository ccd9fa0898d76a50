"""One line on a terminal before numba compiles the reduced models' kernels: the first run of a fresh install
compiles them for seconds each (about 8 s for model I) with nothing else to say so.

numba compiles only on a cache miss: :func:`compile_notice` listens for its "numba:compile" event (numba's event
API, fired after the disk cache missed, never on a hit) in this process; the report's worker processes listen for
the same event and call :func:`announcer`'s callable in this process. A sweep's dask workers are not watched: a
compile there delays the first tasks with no line. On a stream that is not a terminal (logs, tests) nothing is
printed.
"""
from __future__ import annotations

import sys
from contextlib import contextmanager

__all__ = ["MESSAGE", "compile_notice", "announcer"]

MESSAGE = "compiling kernels (first run only) ..."


def _say(stream):
    from tqdm import tqdm

    tqdm.write(MESSAGE, file=stream)  # above any progress bar, which is redrawn below it


@contextmanager
def compile_notice(stream=None, tty: bool | None = None, announce=None):
    """Within the block, the first numba compile in this process prints :data:`MESSAGE` once, on a terminal.
    ``announce`` (from :func:`announcer`) shares the once with other processes' compiles."""
    announce = announce if announce is not None else announcer(stream, tty)
    if announce is None:
        yield
        return
    from numba.core import event

    class _Listener(event.Listener):
        def on_start(self, ev):
            announce()

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", _Listener()):
        yield


def announcer(stream=None, tty: bool | None = None):
    """A callable that prints :data:`MESSAGE` once on a terminal (None off a terminal), for work that compiles in
    other processes: the report's pool calls it when numba first compiles in a worker
    (:func:`compare.report.pool.process_pool`)."""
    stream = stream if stream is not None else sys.stderr
    if not (stream.isatty() if tty is None else tty):
        return None
    import threading

    said, lock = [], threading.Lock()

    def announce():  # from this process's thread or the pool's watcher thread
        with lock:
            if not said:
                said.append(True)
                _say(stream)
    return announce
