"""Runs that lose nothing: SIGKILL then resume gives the uninterrupted trace bit for bit (model I and the
engine); SIGINT stops cleanly with a checkpoint and a partial trace."""
import json
import os
import shutil
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


def _cli(*args):
    return [sys.executable, "-m", "compare.cli", *map(str, args)]


def _popen(cmd, **kw):
    # a shell that starts pytest in the background sets SIGINT to 'ignore', the child would inherit it and Python
    # then installs no KeyboardInterrupt handler (the run completes with status 0): restore the default first
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL), **kw)


@pytest.mark.slow  # fast tier under a minute: run in CI's slow tier
def test_checkpointing_does_not_change_the_bits(tmp_path):
    """Every run passes through the same pickle round trip at its epochs, so a checkpoint file, its interval and
    a resume change nothing (before, a checkpointed run departed from a plain one at the first checkpoint)."""
    # (the rough profile, where a checkpointed run once departed from a plain one, costs 4x more per step: it is
    # in the slow test below)
    # Two epochs of 0.5 s and a tail, as the 2.5 s runs with 1 s epochs (and 1 s warmup) had before, at 40 % of the cost: a
    # checkpointed run departs from a plain one at its first round trip, and any departure shows in the last bits of
    # the 500 output steps that follow it; the resume starts at t = 1 s and runs the tail.
    sc = load_scenario(PATCHES).with_run(duration=1.25, warmup=0.25)  # (the warmup does not bear on the bits)
    ref = engine_sim.run(sc, seed=1, epoch=0.5)
    assert ref.metadata["epoch_s"] == 0.5 and ref.metadata["checkpoint_every_s"] is None
    for every in (0.5, 1.0):
        ck = tmp_path / f"ck{every}.pkl"
        got = engine_sim.run(sc, seed=1, epoch=0.5, checkpoint=ck, checkpoint_every=every)
        assert np.array_equal(got.x, ref.x) and np.array_equal(got.pad_force, ref.pad_force), every
        assert ck.exists()  # the last epoch that is a whole interval: t = 1 s
        again = engine_sim.run(sc, seed=1, epoch=0.5, checkpoint=ck, checkpoint_every=every)  # resumes at 1 s
        assert again.metadata["resumed_from_checkpoint"]
        for f in ("t", "x", "v", "pad_force", "work_drive", "dissipated", "mech_energy"):
            assert np.array_equal(getattr(again, f), getattr(ref, f)), f
    other = engine_sim.run(sc.with_run(duration=0.5), seed=1, epoch=0.25)  # the epoch belongs to the run's definition
    assert other.metadata["epoch_s"] == 0.25


def test_checkpoint_interval_rounds_to_whole_epochs():
    from engine_sim.checkpoint import checkpoint_interval as every

    assert every(1000, 1e-3, 2.4) == 2000 and every(1000, 1e-3, 0.1) == 1000 and every(1000, 1e-3, None) is None


def test_default_epochs_keep_the_round_trip_cost_small():
    """The cost model's epochs for the shipped scenes (measured shares in benchmarks/bench_epoch.py)."""
    from engine_sim.epoch import TARGET_SHARE, default_epoch, estimated_costs
    from engine_sim.scene import Scene

    for name in ("pads_friction_patches", "pads_rough_profile"):
        sc = load_scenario(shipped_scenarios()[name])
        scene = Scene(sc, 0)
        ep = default_epoch(scene, sc.run.dt_out)
        rt, step = estimated_costs(scene)
        assert ep == int(ep) and rt / (ep / sc.run.dt_out * step) <= TARGET_SHARE, (name, ep)


@pytest.mark.slow  # engine runs in subprocesses
def test_engine_killed_and_resumed_is_bitwise_identical(tmp_path):
    out = tmp_path / "run"
    cmd = _cli("run", PATCHES, "--duration", "4", "--seed", "3", "--epoch", "1", "--checkpoint-every", "1", "-o", out)
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _kill_when(out / "checkpoint.pkl", proc)
    assert not (out / "trace.npz").exists()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    meta = json.loads((out / "trace.json").read_text())
    assert meta["resumed_from_checkpoint"] and not meta["partial"]
    got = np.load(out / "trace.npz")
    ref = engine_sim.run(load_scenario(PATCHES).with_run(duration=4.0), seed=3, epoch=1.0)  # no checkpoints at all
    assert np.array_equal(got["x"], ref.x) and np.array_equal(got["pad_force"], ref.pad_force)
    assert not (out / "checkpoint.pkl").exists()  # removed once complete
    assert sorted(p.name for p in out.iterdir()) == ["trace.json", "trace.npz"]  # no temporary files left


@pytest.mark.slow  # engine runs in subprocesses
@pytest.mark.parametrize("sig, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_writes_checkpoint_and_partial_trace(tmp_path, sig, status):
    out = tmp_path / "run"
    proc = _popen(_cli("run", PATCHES, "--duration", "60", "--epoch", "1", "--checkpoint-every", "1", "-o", out))
    t_end = time.time() + 120
    while time.time() < t_end and not (out / "checkpoint.pkl").exists():
        time.sleep(0.01)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == status, err
    meta = json.loads((out / "trace.json").read_text())
    assert meta["partial"] is True and meta["interrupted_by"] == sig.name
    assert "Traceback" not in err and "rerun the same command to resume from t = " in err
    tr = np.load(out / "trace.npz")
    assert 0.99 <= tr["t"][-1] < 60.0 and np.all(np.isfinite(tr["x"]))  # at least up to the first checkpoint
    assert meta["checkpoint_at_s"] >= 1.0 and meta["checkpoint_at_s"] % 1.0 == 0  # on an epoch
    assert (out / "checkpoint.pkl").exists()


def test_checkpoint_of_another_run_or_corrupt_is_refused(tmp_path, capsys):
    from compare.cli import main

    out = tmp_path / "run"
    sc = load_scenario(PATCHES).with_run(duration=1.5)
    out.mkdir()
    engine_sim.run(sc, seed=3, epoch=1.0, checkpoint=out / "checkpoint.pkl", checkpoint_every=1.0)  # leaves t = 1 s
    base = ["run", str(PATCHES), "--duration", "1.5", "--epoch", "1", "--checkpoint-every", "1", "-o", str(out)]
    for extra, needle in ((["--seed", "4"], "(seed differs)"), (["--seed", "3", "--duration", "2"], "(duration differs)"),
                          (["--seed", "3", "--epoch", "0.5"], "epoch differs")):
        args = base + extra
        assert main(args) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and needle in err and "delete it" in err, err
    (out / "checkpoint.pkl").write_bytes(b"\x80\x05garbage")
    assert main(base + ["--seed", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not a readable checkpoint" in err and "delete it" in err, err
    assert sorted(p.name for p in out.iterdir()) == ["checkpoint.pkl"]  # no trace written


# (scene, simulated seconds, epoch): short runs with a few epochs each (rough profile and wear cost 2-4 ms per
# output step and 0.7-1.4 s per round trip, so they get fewer)
_SIGNAL_SCENES = [("pads_friction_patches", 3.0, 0.5), ("pads_rough_profile", 2.0, 1.0), ("pads_with_wear", 2.0, 1.0),
                  ("leonardo_slider", 3.0, 0.5), ("asperity_field", 3.0, 0.5)]


@pytest.mark.slow
def test_real_signals_at_random_moments_then_resume_is_bitwise_identical(tmp_path):
    """`frictionnoise run` interrupted by real SIGINT and SIGKILL at seeded random moments
    (a second interrupt, of the other kind, lands during the resume), then resumed to the end, equals a plain run
    that never checkpointed in every recorded array, bit for bit, on five scenes (SIGINT first on three, SIGKILL
    first on two); no crash, no traceback. The hazards it watches: an interrupt that leaves the loop's and the recorder's counters apart (a resume would write
    past the buffers), and a checkpointed run that departs from a plain one at its first checkpoint."""
    rng = np.random.default_rng(2026_11_23)
    counts = {"SIGINT": 0, "SIGKILL": 0, "during resume": 0, "finished before the signal": 0, "crashes": 0,
              "differing arrays": 0, "arrays compared": 0}
    orders = ((signal.SIGINT, signal.SIGKILL), (signal.SIGKILL, signal.SIGINT))
    for trial, (name, T, epoch) in enumerate(_SIGNAL_SCENES):
        path = tmp_path / f"{name}.toml"  # the shipped scene with a 0.2 s warm-up (1 s costs up to 4 s per start)
        text = shipped_scenarios()[name].read_text()
        assert "warmup = 1.0" in text
        path.write_text(text.replace("warmup = 1.0", "warmup = 0.2"))
        ref = engine_sim.run(load_scenario(path).with_run(duration=T), seed=5, epoch=epoch)  # never checkpointed
        wall = ref.metadata["wall_s"] + 2.0  # + interpreter start and imports
        first, second = orders[trial % 2]
        out = tmp_path / f"{name}-{trial}"
        cmd = _cli("run", path, "--duration", T, "--seed", 5, "--epoch", epoch, "--checkpoint-every", epoch,
                   "-o", out)
        # a run (or its resume) that finishes before its signal: start again from nothing with the seeded moments
        # halved, until both signals land (a child's speed varies with the machine's load; CI once delivered 6 of 10)
        for attempt in range(5):
            shutil.rmtree(out, ignore_errors=True)
            scale = 0.5 ** attempt
            delivered = 0
            for sig, frac in ((first, scale * rng.uniform(0.4, 1.0)), (second, scale * rng.uniform(0.2, 0.8))):
                proc = _popen(cmd)
                try:
                    proc.wait(timeout=frac * wall)
                except subprocess.TimeoutExpired:
                    proc.send_signal(sig)
                _, err = proc.communicate(timeout=120)
                if proc.returncode == 0:
                    counts["finished before the signal"] += 1
                    break
                delivered += 1
                counts[sig.name] += 1
                counts["during resume"] += sig is second
                ok = proc.returncode == (130 if sig == signal.SIGINT else -signal.SIGKILL)
                counts["crashes"] += not ok or "Traceback" in err
                assert ok and "Traceback" not in err, (name, sig, proc.returncode, err[-2000:])
            if delivered == 2:
                break
        done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        counts["crashes"] += done.returncode != 0
        assert done.returncode == 0 and "Traceback" not in done.stderr, (name, done.stderr[-2000:])
        got = np.load(out / "trace.npz")
        for f in (f for f in got.files if f != "format"):
            counts["arrays compared"] += 1
            same = np.array_equal(got[f], getattr(ref, f))
            counts["differing arrays"] += not same
            assert same, (name, trial, f)
        assert not (out / "checkpoint.pkl").exists()
    print("\nreal interrupts then resume:", ", ".join(f"{k}: {v}" for k, v in counts.items()))
    assert counts["SIGINT"] + counts["SIGKILL"] >= 8 and counts["during resume"] >= 3
    assert counts["crashes"] == 0 and counts["differing arrays"] == 0


def test_recorder_refuses_to_write_past_its_buffers():
    from engine_sim.record import Recorder
    from engine_sim.scene import Scene

    rec = Recorder(Scene(load_scenario(PATCHES), seed=0), 2)
    rec.sample()
    rec.sample()
    with pytest.raises(IndexError, match="recorder full"):
        rec.sample()
