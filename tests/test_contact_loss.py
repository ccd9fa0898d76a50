"""A run that loses every contact stops, and keeps what it recorded as a partial trace (engine_sim.run)."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import engine_sim
from engine_sim.regime import LOST_CONTACT_S
from engine_sim.run import ContactWatch

LIFT_OFF = Path(__file__).parent / "data" / "lift_off.toml"


def test_contact_watch_counts_samples_without_contact_in_a_row():
    w = ContactWatch(1e-3)
    assert w.limit == round(LOST_CONTACT_S / 1e-3) == 100
    assert not any(w.lost(0) for _ in range(100))  # exactly the stated time: still running
    assert not w.lost(3)  # a contact resets the count
    assert not any(w.lost(0) for _ in range(100))
    assert w.lost(0)  # one sample more than the stated time without contact


def test_a_scene_that_drops_its_load_stops_with_a_partial_trace():
    tr = engine_sim.run(LIFT_OFF)
    meta, nc = tr.metadata, tr.n_contact
    assert meta["partial"] and meta["stopped_by"] == "contact_lost"
    assert meta["stop_reason"].startswith("contact lost: no pad touched its track from t = ")
    n_lost = ContactWatch(1e-3).limit + 1
    assert len(tr.t) < 1001  # stopped before the 1 s asked
    assert (nc[-n_lost:] == 0).all()  # the last 0.101 s without a contact
    assert (nc[1:100] > 0).all()  # and the block stood on its asperities before the shaker lifted it
    t_lost = float(meta["stop_reason"].split("from t = ")[1].split(" s")[0])
    assert np.isclose(t_lost, tr.t[-n_lost], atol=1e-3)


def test_run_command_says_the_run_stopped_and_writes_the_partial_trace(tmp_path):
    r = subprocess.run([sys.executable, "-m", "compare.cli", "run", str(LIFT_OFF), "-o", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("frictionnoise: contact lost: no pad touched its track") and "partial trace" in last
    meta = json.loads((tmp_path / "trace.json").read_text())
    assert meta["partial"] is True and meta["stopped_by"] == "contact_lost"
