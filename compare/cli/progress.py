"""Progress of a multi-stage job on stderr: a bar naming the running stages on a terminal, one line per
finished stage with its own and the total elapsed time otherwise (logs, CI)."""
from __future__ import annotations

import sys
import time

__all__ = ["StageProgress"]


class StageProgress:
    """Callable as ``progress(label, event, wall)`` (see ``compare.report.run_studies``); use as a context manager.

    stream : where to write (default stderr); tty : draw a bar (default: whether the stream is a terminal)."""

    def __init__(self, labels, desc: str = "report", stream=None, tty: bool | None = None):
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty() if tty is None else tty
        self.total = len(labels)
        self.desc = desc
        self.done = 0
        self.running: list = []
        self.t0 = time.perf_counter()
        self.bar = None
        if self.tty:
            from tqdm import tqdm

            self.bar = tqdm(total=self.total, desc=desc, unit="stage", file=self.stream)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.bar is not None:
            self.bar.close()
        return False

    def __call__(self, label: str, event: str, wall: float | None = None):
        if event == "start":
            self.running.append(label)
        elif event == "done":
            if label in self.running:
                self.running.remove(label)
            self.done += 1
            if self.bar is None:
                own = f" in {wall:.1f} s" if wall is not None else ""
                print(f"{self.desc}: [{self.done}/{self.total}] {label} done{own} "
                      f"({time.perf_counter() - self.t0:.1f} s elapsed)", file=self.stream, flush=True)
        if self.bar is not None:
            self.bar.set_postfix_str("running: " + ", ".join(self.running) if self.running else "")
            self.bar.n = self.done
            self.bar.refresh()
