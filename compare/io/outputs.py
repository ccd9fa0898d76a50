"""Outputs written atomically: a folder built in a hidden temporary sibling and renamed into place when complete
(:func:`atomic_folder`); single files through the distribution's one writer (:func:`atomic_write`, defined in
:mod:`frictionnoise` so that engine_sim's checkpoints use the same one)."""
from __future__ import annotations

import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

from frictionnoise.base import atomic_write

__all__ = ["atomic_folder", "atomic_write"]


@contextmanager
def atomic_folder(out_dir):
    """Yield a temporary folder; on success it replaces ``out_dir``, on any error it is removed and
    ``out_dir`` stays as it was."""
    out_dir = Path(out_dir).resolve()
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.tmp-", dir=out_dir.parent))
    tmp.chmod(0o755)
    try:
        yield tmp
        if out_dir.exists():
            old = out_dir.with_name(f".{out_dir.name}.old-{os.getpid()}")
            out_dir.rename(old)
            tmp.rename(out_dir)
            shutil.rmtree(old, ignore_errors=True)
        else:
            tmp.rename(out_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
