"""The command line's input layer: every path a subcommand reads or writes, checked for kind (file or folder)
and for format by content, not by name. Each problem is one :class:`InputError` whose message names the path and
the problem; the CLI prints it as one line and exits 2 before anything is written.

Formats by content: an NPZ trace is a zip archive (``PK`` magic); TOML and CSV are UTF-8 text without NUL
bytes; a TOML file that holds no settings (empty or only comments) is refused rather than run as defaults. The
checks of a file read (:func:`input_file`, :func:`sniff`, :func:`read_toml`) are :mod:`frictionnoise.base`'s, shared
with ``engine_sim.load_scenario``; this module adds the folders written into.
"""
from __future__ import annotations

import os
from pathlib import Path

from frictionnoise.base import InputError, input_file, read_toml, sniff

__all__ = ["InputError", "input_file", "sniff", "read_toml", "output_folder"]


def output_folder(path) -> Path:
    """``path`` as a folder to write into: absent (created later) or a folder; not a file, and not under one; its
    nearest existing folder takes a new folder (tried before any work starts)."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise InputError(f"{p}: exists and is not a folder")
    for parent in p.absolute().parents:
        if parent.exists():
            if not parent.is_dir():
                raise InputError(f"{p}: {parent} is a file, not a folder")
            if not os.access(parent, os.W_OK | os.X_OK):
                raise InputError(f"{p}: {parent} is not writable")
            _probe(p, parent)
            break
    return p


def _probe(p: Path, parent: Path) -> None:
    """Make and remove a folder in ``parent``: the one test that holds for every file system and user (a
    superuser passes os.access everywhere, yet /proc or a read-only mount refuses the folder)."""
    import tempfile

    try:
        os.rmdir(tempfile.mkdtemp(prefix=".frictionnoise-probe-", dir=parent))
    except OSError as e:
        raise InputError(f"{p}: cannot write into {parent} ({e.strerror or e})") from None
