"""One line on a terminal before numba compiles the reduced models' kernels: the first run of a fresh install
compiles them for seconds each (about 8 s for model I) with nothing else to say so.

numba compiles only on a cache miss: :func:`compile_notice` listens for its "numba:compile" event (fired after
the disk cache missed, never on a hit) in this process; :func:`cold_kernels` reads the disk cache's index for work
that runs in other processes (the report's pool). On a stream that is not a terminal (logs, tests) nothing is
printed.
"""
from __future__ import annotations

import sys
from contextlib import contextmanager

__all__ = ["MESSAGE", "compile_notice", "cold_kernels", "announce_cold"]

MESSAGE = "compiling kernels (first run only) ..."


def _say(stream):
    from tqdm import tqdm

    tqdm.write(MESSAGE, file=stream)  # above any progress bar, which is redrawn below it


@contextmanager
def compile_notice(stream=None, tty: bool | None = None):
    """Within the block, the first numba compile in this process prints :data:`MESSAGE` once, on a terminal."""
    stream = stream if stream is not None else sys.stderr
    if not (stream.isatty() if tty is None else tty):
        yield
        return
    from numba.core import event

    class _Listener(event.Listener):
        said = False

        def on_start(self, ev):
            if not self.said:
                self.said = True
                _say(stream)

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", _Listener()):
        yield


def cold_kernels(modules=None) -> list:
    """Names of the kernels (numba dispatchers compiled on their own, not inlined) of ``modules`` (default: the
    reduced models') whose disk cache holds nothing valid for this source and numba, i.e. that the next run will
    compile. Reads numba's cache index (not a public API): if that fails, reports none."""
    try:
        from numba.core.dispatcher import Dispatcher

        if modules is None:
            from reduced_models import _exact, _two_level, asperity_force, spring_block, wear_particle
            modules = (_exact, _two_level, asperity_force, spring_block, wear_particle)
        cold = []
        for mod in modules:
            for name, obj in vars(mod).items():
                if isinstance(obj, Dispatcher) and obj.targetoptions.get("inline") in (None, "never") \
                        and not obj.signatures and not obj._cache._cache_file._load_index():
                    cold.append(f"{mod.__name__}.{name}")
        return cold
    except Exception:  # a numba whose cache internals differ: no notice rather than a wrong one
        return []


def announce_cold(stream=None, tty: bool | None = None) -> bool:
    """Print :data:`MESSAGE` on a terminal if the next run will compile a kernel (see :func:`cold_kernels`)."""
    stream = stream if stream is not None else sys.stderr
    if (stream.isatty() if tty is None else tty) and cold_kernels():
        _say(stream)
        return True
    return False
