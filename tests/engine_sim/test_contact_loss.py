"""A run that loses every contact stops, and keeps what it recorded as a partial trace (engine_sim.run)."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import engine_sim
from engine_sim.regime import LOST_CONTACT_S
from engine_sim.run import ContactWatch

LIFT_OFF = Path(__file__).parents[1] / "data" / "lift_off.toml"


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
    # and the block stood on its asperities until the shaker's upward acceleration passed g:
    # A omega^2 sin(omega t) = g at t = asin(1/3) / omega = 8.9 ms (3 g peak at 6.1 Hz)
    assert (nc[1:8] > 0).all()
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
    # the whole reason, with the time the run stopped, in trace.json; the line names both files
    assert "the run stopped at t = " in meta["stop_reason"] and meta["stop_reason"].endswith("after the warm-up)")
    assert "trace.npz" in last and "trace.json" in last


def test_stop_reason_names_the_stop_time_as_the_last_recorded_sample():
    tr = engine_sim.run(LIFT_OFF)
    t_stop = float(tr.metadata["stop_reason"].split("the run stopped at t = ")[1].split(" s")[0])
    assert np.isclose(t_stop, tr.t[-1], atol=1e-3)  # printed to 1 ms
    assert "recorded time" in tr.metadata["stop_reason"]


def test_negative_normal_force_for_longer_than_the_stated_time_stops_the_run():
    """Pads pushed through their tracks: every pad still 'in contact' (pymunk sees the overlap from the far side)
    while F_n < 0. The stop comes one sample after LOST_CONTACT_S of it, not before."""
    w = ContactWatch(1e-3, 30)
    assert all(w.see(30, -1.0, k) is None for k in range(100))
    assert w.see(30, 2.0, 100) is None  # a positive sample resets the count
    assert all(w.see(30, -1.0, k) is None for k in range(101, 201))
    assert w.see(30, -1.0, 201) == "pushed_through" and w.start["pushed_through"] == 101


def test_a_sizeable_fraction_of_pads_off_their_tracks_warns_once_and_the_run_goes_on():
    """3 of 30 pads (10 %) off their tracks for longer than LOST_CONTACT_S while 27 keep theirs: one warning line
    that says how many, from when and that the time is recorded time; 2 of 30 (below the fraction) says nothing."""
    w = ContactWatch(1e-3, 30)
    assert all(w.see(28, 1.0, k) is None for k in range(500)) and not w.warnings
    assert all(w.see(27, 1.0, k) is None for k in range(500, 700))
    assert len(w.warnings) == 1 and "\n" not in w.warnings[0]
    assert w.warnings[0].startswith("3 of 30 pads lost contact") and "from t = 0.500 s (recorded time)" in w.warnings[0]
    assert all(w.see(20, 1.0, k) is None for k in range(700, 900)) and len(w.warnings) == 1


def test_a_run_records_its_warnings_in_the_metadata():
    tr = engine_sim.run(LIFT_OFF, duration=0.05)  # before the shaker lifts the block: every foot on its asperity
    assert tr.metadata["warnings"] == []
