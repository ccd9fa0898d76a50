"""Progress of a multi-stage job on stderr: a bar naming the running stages on a terminal, one line per
finished stage with its own and the total elapsed time otherwise (logs, CI)."""
from __future__ import annotations

import sys
import threading
import time

__all__ = ["StageProgress", "print_verdicts", "progress_bar", "report_start_line"]


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

    def note(self, line: str):
        """One line on the progress lines' stream (above the bar on a terminal)."""
        if self.bar is not None:
            self.bar.write(line, file=self.stream)
        else:
            print(line, file=self.stream, flush=True)

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


HEARTBEAT_S = 30.0  # wall seconds: in a log, no longer than this between two progress lines


def report_start_line(studies, workers: int) -> str:
    """The report's first line: the progress lines come only as studies end (the first after about a minute)."""
    n, alone = len(studies), sum(s.alone for s in studies)
    return (f"report: {n} stud{'ies' if n > 1 else 'y'} on {workers} worker{'s' if workers > 1 else ''}"
            + (f" ({alone} alone after the others)" if alone else "")
            + "; the first line of results comes when the first study ends, then one a study")


class _Logged:
    """A progress bar used as a context manager, with a heartbeat: while it is open, a thread calls ``beat`` every
    second (it prints a line when the last one is ``HEARTBEAT_S`` old). Everything else is the tqdm bar's."""

    def __init__(self, bar, beat):
        self._bar, self._beat = bar, beat
        self._stop = threading.Event()
        self._thread = None

    def __enter__(self):
        self._bar.__enter__()
        if self._beat is not None:
            self._thread = threading.Thread(target=self._run, name="progress-heartbeat", daemon=True)
            self._thread.start()
        return self

    def _run(self):
        while not self._stop.wait(min(1.0, HEARTBEAT_S / 4)):
            self._beat()

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        return self._bar.__exit__(*exc)

    def __getattr__(self, name):
        return getattr(self._bar, name)


def progress_bar(desc, stream=None, *, warmup: float = 0.0, duration: float | None = None, runs: int = 1, tty=None):
    """A bar in simulated time on a terminal; otherwise (a log, CI) one line per tenth of the work with the
    elapsed wall time, and one at least every ``HEARTBEAT_S`` (30 s) of wall time while the bar is open (as a
    context manager), with the simulated time last reported. Its total is what will be simulated: ``runs`` x
    (``warmup``, simulated and not recorded, + the recorded ``duration``), known before the first report; the label
    names the warm-up and the run.

    Returns (bar, update); ``update(done, total)`` takes one run's seconds as ``engine_sim.run`` reports them
    (total = its warm-up + its recorded samples); a run that starts again from zero is the next run."""
    from tqdm import tqdm

    stream = stream or sys.stderr
    tty = stream.isatty() if tty is None else tty
    per_run = [warmup + duration if duration else 0.0]  # one run's simulated seconds, as far as known
    state = {"run": 0, "last": -1.0, "next_tenth": 1, "done": 0.0, "total": runs * per_run[0], "label": ""}
    bar = tqdm(total=runs * per_run[0] or 1.0, desc=desc, unit="s", file=stream, disable=not tty,
               bar_format="{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}{postfix}]")  # tqdm puts ", "
    # before a postfix: at the line's end it reads as tqdm's own (in the middle it would open the text with ", ")
    t0 = time.perf_counter()
    lock = threading.Lock()
    last_line = [t0]

    def label(done_run):
        which = f"run {state['run'] + 1}/{runs}: " if runs > 1 else ""
        part = "warm-up, not recorded" if done_run < warmup * (1 - 1e-9) else "recorded"
        return f"{which}{warmup:g} s warm-up + {per_run[0] - warmup:.1f} s recorded; now {part}"

    state["label"] = label(0.0)
    if duration:
        bar.set_postfix_str(f"0.0/{runs * per_run[0]:.1f} s simulated ({label(0.0)})")

    def line(tail=""):
        done_all, total_all = state["done"], state["total"]
        pct = f"{100 * done_all / total_all:.0f} %; " if total_all > 0 else ""
        print(f"{desc}: {done_all:.1f}/{total_all:.1f} s simulated{tail} ({pct}{state['label']}), "
              f"{time.perf_counter() - t0:.1f} s elapsed", file=stream, flush=True)
        last_line[0] = time.perf_counter()

    def update(done, total):
        with lock:
            if done < state["last"]:  # the next run began
                state["run"] = min(state["run"] + 1, runs - 1)
            state["last"] = done
            per_run[0] = total
            done_all, total_all = state["run"] * total + done, runs * total
            state.update(done=done_all, total=total_all, label=label(done))
            bar.total = total_all
            bar.n = done_all
            bar.set_postfix_str(f"{done_all:.1f}/{total_all:.1f} s simulated ({label(done)})")
            bar.refresh()
            k = state["next_tenth"]
            tenth = total_all > 0 and done_all >= k * total_all / 10 * (1 - 1e-9)
            if tenth:
                state["next_tenth"] = int(10 * done_all / total_all * (1 + 1e-9)) + 1
            if not tty and (tenth or time.perf_counter() - last_line[0] >= HEARTBEAT_S):
                line()

    def beat():
        with lock:
            if time.perf_counter() - last_line[0] >= HEARTBEAT_S:
                line(" as last reported; still running")

    return _Logged(bar, None if tty else beat), update


def print_verdicts(summary) -> None:
    """The page's summary table on stdout, one verdict a line, flags included (``report`` and ``compare``)."""
    from ..report.verdict import summary_lines

    for line in summary_lines(summary):
        print(line)
