"""Checkpoints of exact reduced-model runs: the state pickled beside the run's identity, written atomically."""
from __future__ import annotations

__all__ = ["save_checkpoint", "load_checkpoint"]


def _ckpt_key(params, n, dt_out, seed) -> dict:
    return {"params": params.to_dict(), "n": n, "dt_out": dt_out, "seed": seed if isinstance(seed, int) else repr(seed)}


def save_checkpoint(path, params, n, dt_out, seed, state):
    """Pickle the state next to its identity (params, length, step, seed); atomic rename."""
    import os
    import pickle
    import tempfile
    from pathlib import Path

    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    with os.fdopen(fd, "wb") as fh:
        pickle.dump({"key": _ckpt_key(params, n, dt_out, seed), "state": state}, fh, protocol=pickle.HIGHEST_PROTOCOL)
    os.replace(tmp, path)


def load_checkpoint(path, params, n, dt_out, seed):
    """The saved state if ``path`` holds a checkpoint of this very run, else None."""
    import pickle
    from pathlib import Path

    path = Path(path)
    if not path.exists():
        return None
    with open(path, "rb") as fh:
        data = pickle.load(fh)
    if data.get("key") != _ckpt_key(params, n, dt_out, seed):
        raise ValueError(f"{path}: checkpoint of a different run (parameters, duration, step or seed differ)")
    return data["state"]
