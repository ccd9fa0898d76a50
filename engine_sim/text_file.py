"""Text files as instruments write them, decoded and split into lines one way for every reader (time series and
profiles): UTF-8 (with or without a BOM), UTF-16 with a BOM, else latin-1 (Windows exports write the micro sign as
byte 0xB5); LF, CRLF, CR CR LF or lone CR line ends.

Line numbers are the ones ``grep -n`` prints: a line ends at LF, and the CRs before it belong to that end (a
CR CR LF file's line 28 is ``grep -n``'s 28, not 33). A file with no LF at all (old Mac exports: lone CRs) is
split at its CRs, where ``grep`` would see one line.
"""
from __future__ import annotations

import codecs
import re

__all__ = ["decode", "split_lines"]

_END = re.compile(r"\r*\n")


def decode(raw: bytes):
    """(text, encoding) of a text file's bytes, or None for a binary one: a BOM names UTF-8 or UTF-16; a NUL byte
    in the first 4 kB, or more than 1 % control characters read as latin-1, is binary; else UTF-8 if it decodes,
    else latin-1."""
    if raw.startswith(codecs.BOM_UTF8):
        return raw[3:].decode("utf-8", errors="strict"), "utf-8 (BOM)"
    if raw.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return raw.decode("utf-16"), "utf-16"
    if b"\x00" in raw[:4096]:
        return None
    try:
        return raw.decode("utf-8"), "utf-8"
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
        ctrl = sum(1 for c in text[:4096] if ord(c) < 32 and c not in "\r\n\t\f\v")
        return None if ctrl > 0.01 * min(len(text), 4096) else (text, "latin-1")


def split_lines(text: str) -> list:
    """The lines of ``text`` as ``grep -n`` counts them (see the module's docstring), without their ends."""
    if "\n" not in text:
        lines = text.split("\r")
    else:
        lines = _END.split(text)
        lines[-1] = lines[-1].rstrip("\r")  # a last line without its LF
    if lines and lines[-1] == "":
        lines.pop()
    return lines
