"""What every package of the distribution shares, defined once: the standard gravity ``G``, the installed
version (:func:`package_version`) and the atomic file writer (:func:`atomic_write`).

A leaf: it imports nothing of the project, so ``engine_sim``, ``reduced_models`` and ``compare`` may all use it
without importing one another (DESIGN.md's dependency direction).
"""
from __future__ import annotations

import itertools
import os
from importlib import metadata as _metadata
from pathlib import Path

__all__ = ["G", "package_version", "atomic_write"]

_counter = itertools.count()

G = 9.81  # m/s^2: the paper's g (standard gravity rounded as in Xu, Zhou & Persson 2025)


def package_version() -> str:
    """The installed distribution's version, "0+unknown" when running from a source tree without install."""
    try:
        return _metadata.version("frictionnoise")
    except _metadata.PackageNotFoundError:
        return "0+unknown"


def atomic_write(path, data: bytes | str | None = None, *, write=None) -> Path:
    """Write ``path`` atomically: into a hidden temporary sibling, renamed over ``path`` when complete, so a
    reader sees the old file or the whole new one, never a part. Give ``data`` (bytes or text) or ``write``, a
    function that writes the temporary file given its path. On any error the temporary file is removed."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{next(_counter)}.tmp")
    # created 0666 less the umask, as open() does (mkstemp's 0600 made run's files unreadable to a group)
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
