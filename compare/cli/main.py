"""The `frictionnoise` command line. User errors print one line and exit 2; no tracebacks."""
from __future__ import annotations

import sys

from ..io.inputs import InputError
from .options import UserError
from .parser import build_parser

__all__ = ["main"]


def _sigterm(signum, frame):
    raise KeyboardInterrupt


def _exit_now(status: int):
    """End the command line after an interrupt without the interpreter's exit. Everything is cleaned up by then
    (outputs are written atomically, worker processes ended), but the interrupt may have landed inside a library's
    import (numba loads its typing registries lazily, on a run's first kernel), after which the interpreter's own
    exit can end the process by the signal (status -2) instead of ``status``; and dask's threads hold that exit for
    seconds after a sweep."""
    import os

    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)


def main(argv=None) -> int:
    """Run the command line. Exit status: 0 done, 1 some work failed (sweep tasks; a run that lost its contacts,
    partial trace written), 2 a user error (one line), 130 interrupted by Ctrl-C (SIGINT; SIGTERM likewise, 143 when
    a run stopped on it), no traceback."""
    import signal
    import threading

    try:
        ap = build_parser()
        args = ap.parse_args(argv)
    except KeyboardInterrupt:  # Ctrl-C while the parser is built: nothing started, nothing written
        print("frictionnoise: interrupted", file=sys.stderr)
        return 130
    if args.command is None:
        ap.print_help()
        return 0
    main_thread = threading.current_thread() is threading.main_thread()
    old = signal.signal(signal.SIGTERM, _sigterm) if main_thread else None
    try:
        rc = args.func(args)
        if rc in (130, 143) and argv is None:  # interrupted, handled and reported (outputs written or none)
            _exit_now(rc)
        return rc
    except (UserError, InputError) as e:
        print("frictionnoise: error: " + " ".join(str(e).split()), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("frictionnoise: interrupted; no output written for the unfinished step", file=sys.stderr)
        if argv is None:
            _exit_now(130)
        return 130
    except BrokenPipeError:  # the reader of a pipe closed it (`frictionnoise scenarios | head`): stop quietly
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at the interpreter's exit
        return 141
    finally:
        if main_thread:
            signal.signal(signal.SIGTERM, old)
            if argv is None:  # the command line itself: the work is over, a late Ctrl-C must not kill the exit
                signal.signal(signal.SIGINT, signal.SIG_IGN)

