"""The command line's input layer: every path a subcommand reads or writes, checked for kind (file or folder)
and for format by content, not by name. Each problem is one :class:`InputError` whose message names the path and
the problem; the CLI prints it as one line and exits 2 before anything is written.

Formats by content: an NPZ trace is a zip archive (``PK`` magic); TOML and CSV are UTF-8 text without NUL
bytes; a TOML file that holds no settings (empty or only comments) is refused rather than run as defaults.
"""
from __future__ import annotations

import os
from pathlib import Path

__all__ = ["InputError", "input_file", "sniff", "read_toml", "output_folder"]

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
