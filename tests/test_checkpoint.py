"""Runs that lose nothing: SIGKILL then resume gives the uninterrupted trace bit for bit (model I and the
engine); SIGINT stops cleanly with a checkpoint and a partial trace."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import engine_sim
from engine_sim import load_scenario, shipped_scenarios
from reduced_models.spring_block import SpringBlockParams, simulate

PATCHES = shipped_scenarios()["pads_friction_patches"]


def _kill_when(path, proc, timeout=120):
    t_end = time.time() + timeout
    while time.time() < t_end and not path.exists():
        if proc.poll() is not None:
            pytest.fail("the run finished before its first checkpoint; make it longer")
        time.sleep(0.01)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()


@pytest.mark.slow  # subprocess runs, killed and resumed
def test_model_I_killed_and_resumed_is_bitwise_identical(tmp_path):
    ck, res = tmp_path / "m1.ckpt", tmp_path / "m1.npz"
    script = tmp_path / "m1.py"
    script.write_text(textwrap.dedent(f"""
        import numpy as np
        from reduced_models.spring_block import SpringBlockParams, simulate
        tr = simulate(SpringBlockParams.reference(), 3000.0, 1e-3, seed=7, checkpoint={str(ck)!r}, checkpoint_every=300.0)
        np.savez({str(res)!r}, x=tr.x, f=tr.force, ev=tr.events["times"])
    """))
    proc = subprocess.Popen([sys.executable, str(script)])
    _kill_when(ck, proc)
    assert not res.exists()  # killed mid-run
    subprocess.run([sys.executable, str(script)], check=True)  # resumes from the checkpoint
    r = np.load(res)
    ref = simulate(SpringBlockParams.reference(), 3000.0, 1e-3, seed=7)
    assert np.array_equal(r["x"], ref.x) and np.array_equal(r["f"], ref.force)
    assert np.array_equal(r["ev"], ref.events["times"])


@pytest.mark.slow  # engine runs in subprocesses, 8-60 s
def test_engine_killed_and_resumed_is_bitwise_identical(tmp_path):
    out = tmp_path / "run"
    cmd = [sys.executable, "-m", "compare.cli", "run", str(PATCHES), "--duration", "8", "--seed", "3",
           "--checkpoint-every", "2", "-o", str(out)]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _kill_when(out / "checkpoint.pkl", proc)
    assert not (out / "trace.npz").exists()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    meta = json.loads((out / "trace.json").read_text())
    assert meta["resumed_from_checkpoint"] and not meta["partial"]
    got = np.load(out / "trace.npz")
    ref = engine_sim.run(load_scenario(PATCHES).with_run(duration=8.0), seed=3)  # no checkpoints at all
    assert np.array_equal(got["x"], ref.x) and np.array_equal(got["pad_force"], ref.pad_force)
    assert not (out / "checkpoint.pkl").exists()  # removed once complete


@pytest.mark.slow  # engine runs in subprocesses, 8-60 s
def test_sigint_writes_checkpoint_and_partial_trace(tmp_path):
    out = tmp_path / "run"
    cmd = [sys.executable, "-m", "compare.cli", "run", str(PATCHES), "--duration", "60", "--checkpoint-every", "1",
           "-o", str(out)]
    # a shell that starts pytest in the background sets SIGINT to 'ignore', the child would inherit it and Python
    # then installs no KeyboardInterrupt handler (the run completes with status 0): restore the default first
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    t_end = time.time() + 120
    while time.time() < t_end and not (out / "checkpoint.pkl").exists():
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    meta = json.loads((out / "trace.json").read_text())
    assert meta["partial"] is True and "Traceback" not in err and "rerun the same command to resume" in err
    tr = np.load(out / "trace.npz")
    assert 0.99 <= tr["t"][-1] < 60.0 and np.all(np.isfinite(tr["x"]))  # at least up to the first checkpoint
    assert (out / "checkpoint.pkl").exists()


@pytest.mark.slow  # engine runs in subprocesses, 8-60 s
def test_sigint_at_random_moments_then_resume_is_bitwise_identical(tmp_path):
    """A Ctrl-C lands anywhere in the loop (mid-step, mid-sample, mid-checkpoint); the checkpoint it leaves must
    resume without writing past the recorder's buffers (it once aborted with heap corruption in 3 of 3 tries)
    and give the uninterrupted trace bit for bit."""
    ref = engine_sim.run(load_scenario(PATCHES).with_run(duration=8.0), seed=3)
    rng = np.random.default_rng(2026)
    for i, delay in enumerate(rng.uniform(0.05, 1.5, size=3)):  # seconds of wall time after the first checkpoint
        out = tmp_path / f"run{i}"
        cmd = [sys.executable, "-m", "compare.cli", "run", str(PATCHES), "--duration", "8", "--seed", "3",
               "--checkpoint-every", "2", "-o", str(out)]
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        t_end = time.time() + 120
        while time.time() < t_end and not (out / "checkpoint.pkl").exists() and proc.poll() is None:
            time.sleep(0.005)
        time.sleep(delay)
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
        assert proc.returncode in (0, 130), err
        done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        assert done.returncode == 0, (delay, done.stderr[-2000:])
        got = np.load(out / "trace.npz")
        assert np.array_equal(got["x"], ref.x) and np.array_equal(got["pad_force"], ref.pad_force), delay


def test_recorder_refuses_to_write_past_its_buffers():
    from engine_sim.record import Recorder
    from engine_sim.scene import Scene

    rec = Recorder(Scene(load_scenario(PATCHES), seed=0), 2)
    rec.sample()
    rec.sample()
    with pytest.raises(IndexError, match="recorder full"):
        rec.sample()
