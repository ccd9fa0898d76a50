"""The helpers the physics and the application share: the paper's g (:data:`G`) and standard gravity
(:data:`STANDARD_GRAVITY`, a measured record's and the gram-force's), the installed version
(:func:`package_version`), the atomic file write (:func:`atomic_write`), the checks of an input file's kind and format
by content (:func:`input_file`, :func:`sniff`, :func:`read_toml`: a scenario file read by ``engine_sim.load_scenario``,
a sweep or measured data read by the command line) and the one number check of every parameter field
(:func:`check_number`, :func:`check_fields`, and for a span of time :func:`check_seconds`).

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

__all__ = ["G", "STANDARD_GRAVITY", "package_version", "atomic_write", "InputError", "input_file", "sniff", "read_toml",
           "check_number", "check_fields", "check_seconds", "check_seed"]

G = 9.81  # m/s^2: the paper's g (standard gravity rounded as in Xu, Zhou & Persson 2025), for its models
STANDARD_GRAVITY = 9.80665  # m/s^2: standard gravity, which defines the gram-force; a measured record's g

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


_ZIP_MAGIC = (b"PK\x03\x04", b"PK\x05\x06")
_SNIFF = 4096


class InputError(ValueError):
    """A path that cannot be used as given: the message names it and says why."""


def input_file(path) -> Path:
    """``path`` as a readable, non-empty regular file, or an InputError."""
    p = Path(path)
    if not os.path.lexists(p):
        raise InputError(f"{p}: no such file")
    if p.is_dir():
        raise InputError(f"{p}: is a folder, not a file")
    if not p.exists():
        raise InputError(f"{p}: broken link")
    if not p.is_file():
        raise InputError(f"{p}: not a regular file")
    try:
        size = p.stat().st_size
        with open(p, "rb"):
            pass
    except OSError as e:
        raise InputError(f"{p}: cannot be read ({e.strerror})") from None
    if size == 0:
        raise InputError(f"{p}: empty file")
    return p


def sniff(path) -> str:
    """'npz' (a zip archive), 'text' or 'binary', from the file's first bytes. Text is UTF-8, or the 8-bit text
    instruments write (latin-1, as a micro sign 0xB5 in a header): no NUL byte and, read as latin-1, at most 1 %
    control characters other than tab, line ends and form feed."""
    with open(path, "rb") as fh:
        head = fh.read(_SNIFF)
    if head[:4] in _ZIP_MAGIC:
        return "npz"
    if b"\x00" in head:
        return "binary"
    try:
        head.decode("utf-8")
    except UnicodeDecodeError as e:
        if e.start < len(head) - 4:  # not just a multi-byte character cut at the sniff boundary
            control = sum(b < 32 and b not in b"\t\n\r\f" or 127 <= b < 160 for b in head)
            return "text" if control <= 0.01 * len(head) else "binary"
    return "text"


def read_toml(path, what: str = "TOML file") -> dict:
    """A TOML file's table; refuses folders, empty, binary, invalid and settings-free (comment-only) files."""
    import tomllib

    p = input_file(path)
    kind = sniff(p)
    if kind == "npz":
        raise InputError(f"{p}: is an NPZ archive, not a {what}")
    if kind == "binary":
        raise InputError(f"{p}: binary data, not a {what}")
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except UnicodeDecodeError:
        raise InputError(f"{p}: not UTF-8 text, not a {what}") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{p}: not valid TOML ({e})") from None
    if not data:
        raise InputError(f"{p}: holds no settings (empty or only comments); nothing to run")
    return data


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


def check_seed(name: str, val) -> int:
    """``val`` as a random seed named ``name`` (a run's seed; an option's flag on the command line): a whole number
    from 0 to 2^63 - 1 (numpy's SeedSequence and the trace's int64 metadata hold it), returned as int. Raises
    ValueError, one line: "{name} must be a whole number from 0 to 2^63 - 1 (got {val!r})"."""
    if isinstance(val, bool) or not isinstance(val, numbers.Integral) or not 0 <= val < 2**63:
        raise ValueError(f"{name} must be a whole number from 0 to 2^63 - 1 (got {val!r})")
    return int(val)
