"""The helpers the physics and the application share: the paper's g (:data:`G`), the installed version
(:func:`package_version`), the atomic file write (:func:`atomic_write`) and the one number check of every parameter
field (:func:`check_number`, :func:`check_fields`, and for a span of time :func:`check_seconds`).

This module imports the standard library only. ``engine_sim``, ``reduced_models`` and ``compare`` take these from
here, never from the user API around it (``frictionnoise``, whose ``__init__`` imports nothing but the standard
library), so importing a helper loads no numerics and the import graph never runs back up through the user API (the
contracts in ``pyproject.toml``). The number check gives the same one-line message wherever a field lives: a micro-pad
spring is ``pads.micro_k`` in a scenario and ``k2`` in model Ib; both say "must be > 0 (got -1.0)".
"""
from __future__ import annotations

import itertools
import math
import numbers
import os
from importlib import metadata as _metadata
from pathlib import Path

__all__ = ["G", "package_version", "atomic_write", "check_number", "check_fields", "check_seconds"]

G = 9.81  # m/s^2: the paper's g (standard gravity rounded as in Xu, Zhou & Persson 2025)

_counter = itertools.count()


def package_version() -> str:
    """The installed distribution's version.

    Returns
    -------
    str
        The version of the installed ``frictionnoise`` distribution, or ``"0+unknown"`` when running from a
        source tree that was never installed.
    """
    try:
        return _metadata.version("frictionnoise")
    except _metadata.PackageNotFoundError:
        return "0+unknown"


def atomic_write(path, data: bytes | str | None = None, *, write=None) -> Path:
    """Write a file atomically: a reader sees the old file or the whole new one, never a part.

    The content goes into a hidden temporary sibling, renamed over ``path`` when complete; on any error the
    temporary file is removed. The file is created 0666 less the umask, as :func:`open` does.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write.
    data : bytes or str, optional
        The content (text is written as UTF-8).
    write : callable, optional
        ``write(tmp_path)`` writes the temporary file itself (for writers that want a path, such as
        ``numpy.savez``); called after ``data`` is written, if both are given.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{next(_counter)}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, "wb") as fh:
            if data is not None:
                fh.write(data.encode() if isinstance(data, str) else data)
        if write is not None:
            write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def check_number(name: str, val, *, positive: bool = False, non_negative: bool = False, integer: bool = False,
                 below: float | None = None, why: str = ""):
    """``val`` as field ``name`` of a parameter object: a real number (not a bool), finite, a whole number if
    ``integer`` (returned as int; 3.0 is 3), > 0 if ``positive``, >= 0 if ``non_negative``, < ``below`` if given.
    Raises ValueError, one line: "{name} must be a number (got str 'x')", "... must be an integer (got 2.5)",
    "... must be finite (got nan)", "... must be > 0 (got -1.0)", "... must be >= 0 (got -1)", "... must be < 2
    (got 2.5)", each followed by ``why`` if given."""
    tail = f": {why}" if why else ""
    if isinstance(val, bool) or not isinstance(val, numbers.Real):
        raise ValueError(f"{name} must be a number (got {type(val).__name__} {val!r}){tail}")
    if not math.isfinite(val):
        raise ValueError(f"{name} must be finite (got {val!r}){tail}")
    if integer and not float(val).is_integer():
        raise ValueError(f"{name} must be an integer (got {val!r}){tail}")
    if positive and not val > 0:
        raise ValueError(f"{name} must be > 0 (got {val!r}){tail}")
    if non_negative and val < 0:
        raise ValueError(f"{name} must be >= 0 (got {val!r}){tail}")
    if below is not None and not val < below:
        raise ValueError(f"{name} must be < {below:g} (got {val!r}){tail}")
    return int(val) if integer else val


def check_fields(obj, *, positive=(), non_negative=(), integer=(), prefix: str = "") -> None:
    """:func:`check_number` on the named attributes of a (frozen) dataclass, named ``prefix + field``; integer
    fields are stored back as int. An integer field is checked >= 0 unless it is also listed ``positive``."""
    for name in dict.fromkeys([*integer, *positive, *non_negative]):
        val = check_number(prefix + name, getattr(obj, name), positive=name in positive,
                           non_negative=name in non_negative or name in integer, integer=name in integer)
        if name in integer:
            object.__setattr__(obj, name, val)


def check_seconds(name: str, val) -> float:
    """``val`` as a span of simulated or recorded time named ``name`` (a run's duration, an epoch, a checkpoint
    interval; an option's flag on the command line): a positive, finite number of seconds, returned as float.
    Raises ValueError, one line: "{name} must be a positive number of seconds (got {val!r})"."""
    if isinstance(val, bool) or not isinstance(val, numbers.Real) or not 0 < val < math.inf:
        raise ValueError(f"{name} must be a positive number of seconds (got {val!r})")
    return float(val)
