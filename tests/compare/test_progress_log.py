"""Progress of a run in a log file (stderr not a terminal): a line every tenth of the work and at least every
HEARTBEAT_S of wall time."""
import io
import re

import numpy as np


def test_run_progress_in_a_log_at_least_every_heartbeat(monkeypatch):
    """A log (no terminal) gets a line at least every HEARTBEAT_S of wall time, with the simulated time last
    reported, even when the run reports nothing (a slow warm-up); here HEARTBEAT_S is cut to 0.2 s."""
    import time

    from compare.cli import progress

    monkeypatch.setattr(progress, "HEARTBEAT_S", 0.2)
    buf = io.StringIO()
    bar, update = progress.progress_bar("slow", stream=buf, warmup=1.0, duration=100.0)
    with bar:
        time.sleep(0.75)  # no report: the heartbeat speaks (at 0.2, 0.4, 0.6 s; it looks every 0.05 s)
        update(1.5, 101.0)  # a report below the next tenth, 0.15 s after the last line: no line of its own
        time.sleep(0.3)
        update(1.6, 101.0)  # a line with these figures, from the report or the heartbeat after it
        time.sleep(0.3)
    lines = buf.getvalue().splitlines()
    beats = [ln for ln in lines if "as last reported; still running" in ln]
    assert len(beats) >= 3, lines  # 0.2, 0.4, 0.6 s with no report; then one whenever 0.2 s pass without a line
    assert beats[0].startswith("slow: 0.0/101.0 s simulated as last reported; still running (0 %; 1 s warm-up")
    assert any(ln.startswith("slow: 1.6/101.0 s simulated") for ln in lines), lines
    gaps = np.diff([float(re.search(r"([\d.]+) s elapsed$", ln).group(1)) for ln in lines])
    assert np.all(gaps < 0.2 + 0.15), lines  # never longer than the heartbeat (+ its 0.05 s look and slack)
