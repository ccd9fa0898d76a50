"""Trace files: ``trace.npz`` (arrays, SI units) beside ``trace.json`` (metadata). Written atomically."""
from __future__ import annotations

import json
from dataclasses import MISSING, fields
from pathlib import Path

import numpy as np

from frictionnoise.base import atomic_write

__all__ = ["save_trace", "load_trace", "TraceFileError", "FORMAT"]

FORMAT = "frictionnoise-trace-2"
CHANNEL = "channel:"  # the .npz name of a recorded channel's array (engine_sim/channels.py) is this and its name


class TraceFileError(ValueError):
    """A file that is not a readable frictionnoise trace; the message names the file and the problem."""


def save_trace(trace, path) -> Path:
    """Write an EngineTrace to ``path`` (.npz) and its metadata to the same name with .json, atomically.

    Parameters
    ----------
    trace : engine_sim.EngineTrace
        The trace (arrays in SI units).
    path : str or pathlib.Path
        The file; its suffix is set to .npz.

    Returns
    -------
    pathlib.Path
        The .npz file written.
    """
    path = Path(path).with_suffix(".npz")
    arrays = {f.name: getattr(trace, f.name) for f in fields(trace) if f.name not in ("metadata", "channels")}
    arrays.update({CHANNEL + name: values for name, values in trace.channels.items()})  # one array a channel
    arrays["format"] = np.array(FORMAT)
    meta = {"format": FORMAT, **trace.metadata}

    def w_npz(tmp):
        with open(tmp, "wb") as fh:
            np.savez(fh, **arrays)

    atomic_write(path, write=w_npz)
    atomic_write(path.with_suffix(".json"), json.dumps(meta, indent=1, default=float))
    return path


def load_trace(path):
    """Read a trace written by :func:`save_trace`.

    Parameters
    ----------
    path : str or pathlib.Path
        The .npz file (its .json metadata beside it).

    Returns
    -------
    engine_sim.EngineTrace
        The arrays (SI units) and the metadata; :class:`TraceFileError` names the file and the problem otherwise.
    """
    from engine_sim.record import EngineTrace

    path = Path(path)
    if not path.exists():
        raise TraceFileError(f"{path}: no such file")
    try:
        data = np.load(path, allow_pickle=False)
        keys = set(data.files)
    except Exception:
        raise TraceFileError(f"{path}: not a .npz trace file") from None
    if "format" not in keys or str(data["format"]) != FORMAT:
        raise TraceFileError(f"{path}: not a frictionnoise trace (no '{FORMAT}' format tag)")
    need = [f.name for f in fields(EngineTrace) if f.name != "metadata" and f.default_factory is MISSING]
    optional = [f.name for f in fields(EngineTrace) if f.name not in ("metadata", "channels")
                and f.default_factory is not MISSING and f.name in keys]  # fields added later (micro_force)
    missing = [k for k in need if k not in keys]
    if missing:
        raise TraceFileError(f"{path}: trace is missing field {missing[0]!r}")
    meta_path = path.with_suffix(".json")
    if not meta_path.exists():
        raise TraceFileError(f"{meta_path}: metadata file missing (written beside the .npz)")
    try:
        meta = json.loads(meta_path.read_text())
    except json.JSONDecodeError as e:
        raise TraceFileError(f"{meta_path}: not valid JSON ({e})") from None
    channels = {k[len(CHANNEL):]: data[k] for k in data.files if k.startswith(CHANNEL)}
    return EngineTrace(**{k: data[k] for k in need + optional}, channels=channels, metadata=meta)
