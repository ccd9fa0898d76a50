"""Ctrl-C anywhere in the CLI: one line, exit 130, within about 2 s also for `report` and `sweep` (their worker
processes ended), no half-written output, completed sweep tasks kept. Real signals to child processes."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from engine_sim import shipped_scenarios

PATCHES = shipped_scenarios()["pads_friction_patches"]


def _descendants(pid: int) -> set:
    """Pids of every live descendant of ``pid`` (from /proc)."""
    children: dict = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            children.setdefault(int(fields[1]), []).append(int(d.name))
    out, todo = set(), [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.add(c)
            todo.append(c)
    return out


def _alive(pids) -> set:
    alive = set()
    for p in pids:
        try:
            st = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if st != "Z":
            alive.add(p)
    return alive


def _start(args):
    # restore SIGINT's default in the child: a shell that starts pytest in the background sets it to 'ignore',
    # the child would inherit that and Python would install no KeyboardInterrupt handler
    return subprocess.Popen([sys.executable, "-m", "compare.cli", *map(str, args)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def _interrupt(proc):
    """SIGINT; (seconds until exit, stderr, pids of descendants at the signal)."""
    kids = _descendants(proc.pid)
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=60)
    wall = time.perf_counter() - t0
    _, err = proc.communicate(timeout=60)  # (the stderr pipe closes when every descendant holding it has ended)
    return wall, err, kids


def _wait_for(cond, proc, timeout=120):
    t_end = time.time() + timeout
    while time.time() < t_end and not cond():
        assert proc.poll() is None, proc.stderr.read()[-2000:]
        time.sleep(0.05)
    assert cond()


def _without_progress(err: str) -> str:
    """stderr less the progress lines a log gets before the signal (one per tenth of a run; the report's line at
    its start and one per study ended): not the message."""
    return "".join(ln for ln in err.splitlines(keepends=True)
                   if " s simulated (" not in ln and not ln.startswith("report: "))


def _one_line_130(proc, err, wall, limit):
    assert proc.returncode == 130, err
    err = _without_progress(err)
    assert err.count("\n") == 1 and "Traceback" not in err and "interrupted" in err, err
    assert wall < limit, wall


@pytest.mark.slow  # a real report's worker pool, signalled once busy (about 7 s)
@pytest.mark.timing  # exit within 2.5 s of the signal, two worker processes of its own
def test_ctrl_c_during_report_ends_its_workers(tmp_path):
    out = tmp_path / "rep"
    proc = _start(["report", "--quick", "--workers", "2", "-o", out])
    _wait_for(lambda: len(_descendants(proc.pid)) >= 2, proc)  # the stage processes are up
    time.sleep(3.0)  # and busy with their stages
    wall, err, kids = _interrupt(proc)
    print(f"\nreport: exit {wall:.2f} s after SIGINT, {len(kids)} worker processes")
    _one_line_130(proc, err, wall, 2.5)  # measured ~0.3-1 s
    time.sleep(0.5)
    assert not _alive(kids), "worker processes left running"
    assert not out.exists() and not list(tmp_path.glob(".rep*"))  # nothing half-written


@pytest.mark.slow  # a dask LocalCluster started, a task completed, then signalled (about 11 s)
@pytest.mark.timing  # exit within 3 s of the signal, two dask workers of its own
def test_ctrl_c_during_sweep_keeps_completed_tasks(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text('name = "s"\ntarget = "model_I"\n[fixed]\nduration = 150.0\n[grid]\n'
                    'v = [1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 3e-3, 4e-3, 5e-3]\nseed = [0]\n')
    out = tmp_path / "sw"
    proc = _start(["sweep", spec, "--workers", "2", "-o", out])
    _wait_for(lambda: len(list((out / "tasks").glob("*.json"))) >= 1, proc, timeout=240)
    kept = {p.name: p.read_text() for p in (out / "tasks").glob("*.json")}
    wall, err, kids = _interrupt(proc)
    print(f"\nsweep: exit {wall:.2f} s after SIGINT, {len(kids)} descendant processes, {len(kept)} tasks kept")
    _one_line_130(proc, err, wall, 3.0)
    time.sleep(0.5)
    assert not _alive(kids), "dask worker processes left running"
    for name, text in kept.items():
        assert (out / "tasks" / name).read_text() == text
    assert not (out / "index.html").exists() and not list((out / "tasks").glob(".*"))  # no partial files
    assert 1 <= len(list((out / "tasks").glob("*.json"))) < 8


@pytest.mark.slow  # a scene task started in this process, then signalled (about 10 s)
@pytest.mark.timing  # exit within 3 s of the signal
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_signal_during_a_serial_scene_sweep_stores_no_partial_task(tmp_path, sig):
    # engine_sim.run answers SIGINT/SIGTERM by returning its trace so far, marked partial; a sweep task must not
    # store that as the task's result (a rerun would then skip the task): the sweep ends, exit 130, nothing stored
    spec = tmp_path / "s.toml"
    spec.write_text(f'name = "s"\ntarget = "scenario"\nscenario = "{PATCHES}"\n[fixed]\nduration = 60.0\n'
                    '"run.warmup" = 0.2\n[grid]\nseed = [0, 1]\n')
    out = tmp_path / "sw"
    proc = _start(["sweep", spec, "--serial", "-o", out])
    _wait_for(lambda: (out / "tasks").exists(), proc, timeout=120)
    time.sleep(3.0)  # into the first task's run (60 s of scene: tens of seconds of wall)
    assert proc.poll() is None
    kids = _descendants(proc.pid)
    t0 = time.perf_counter()
    proc.send_signal(sig)
    proc.wait(timeout=60)
    wall = time.perf_counter() - t0
    _, err = proc.communicate(timeout=60)
    _one_line_130(proc, err, wall, 3.0)
    assert not _alive(kids)
    assert not list((out / "tasks").glob("*")) and not (out / "index.html").exists(), list(out.rglob("*"))


# the fast tier keeps `run` (the same handler in main() serves every subcommand); render and compare wait longer
@pytest.mark.parametrize("cmd, delay", [(["run", PATCHES, "--duration", "30"], 1.5),  # warm-up or first samples
                                        pytest.param(["render", PATCHES, "--frames", "400"], 2.5,
                                                     marks=[pytest.mark.slow, pytest.mark.timing]),
                                        pytest.param(["compare", PATCHES, "--duration", "30"], 3.0,
                                                     marks=[pytest.mark.slow, pytest.mark.timing])])
def test_ctrl_c_in_other_subcommands(tmp_path, cmd, delay):
    out = tmp_path / "o"
    proc = _start([*cmd, "-o", out])
    time.sleep(delay)
    assert proc.poll() is None
    wall, err, _ = _interrupt(proc)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and wall < 2.0, (wall, err)
    err = _without_progress(err)
    assert err.startswith("frictionnoise: interrupted"), err  # every message of an interrupt: one prefix
    if cmd[0] == "run" and out.exists():  # interrupted while recording: the partial trace the README promises
        assert sorted(p.name for p in out.iterdir()) == ["trace.json", "trace.npz"]
        assert err.count("\n") == 1 and "partial trace" in err, err
        assert err.startswith("frictionnoise: interrupted (SIGINT) at t = "), err
    else:
        assert err.count("\n") == 1, err
        assert not out.exists() and not [p for p in tmp_path.iterdir() if p.name.startswith(".o")]


def test_ctrl_c_in_a_runs_warm_up_says_nothing_was_recorded(tmp_path):
    # a 60 s warm-up, signalled once the run has begun (after the forecast's note, which a run longer than a
    # minute prints before it starts): one line, with the prefix of the recording's message, that says the run was
    # stopped in its warm-up before anything was recorded, so nothing was written
    sc = tmp_path / "long_warmup.toml"
    text = Path(PATCHES).read_text()
    assert text.count("warmup = 1.0") == 1
    sc.write_text(text.replace("warmup = 1.0", "warmup = 60.0"))
    out, log = tmp_path / "o", tmp_path / "err.log"
    with open(log, "w") as f:
        proc = subprocess.Popen([sys.executable, "-m", "compare.cli", "run", str(sc), "--duration", "600", "-o",
                                 str(out)], stdout=subprocess.DEVNULL, stderr=f, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    _wait_for(lambda: "Ctrl-C stops it" in log.read_text(), proc, timeout=120)
    time.sleep(1.0)  # into the warm-up (about 20 s of wall)
    assert proc.poll() is None
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=60)
    assert proc.returncode == 130
    err = [ln for ln in log.read_text().splitlines() if "note:" not in ln and " s simulated (" not in ln]
    assert err == ["frictionnoise: interrupted: the run was stopped in its warm-up, before anything was recorded, so "
                   "nothing was written"], err
    assert not out.exists()


# engine_sim.run defers SIGINT/SIGTERM to its loop's consistent points (engine_sim/run.py, _Interrupts). Its first
# sample calls the recorder's numba kernel (engine_sim.reduction.reduce_sample) for the first time in the process:
# under a second to load it from the cache, about 9 s to compile it in a fresh clone, and a Ctrl-C deferred during
# that load would wait for it (the `run` case above allows 2 s from the signal to the exit). So run() loads the
# kernel before the deferral begins (_load_recorder_kernel); this checks that every deferral starts with it loaded.
def test_signals_are_deferred_only_once_the_recorders_kernel_is_loaded():
    code = (
        "import signal\n"
        "import sys, engine_sim\n"
        "R = sys.modules['engine_sim.run']\n"
        "from engine_sim.reduction import reduce_sample\n"
        "seen, real = [], signal.signal\n"
        "def spy(s, h):\n"
        "    if s == signal.SIGINT and isinstance(getattr(h, '__self__', None), R._Interrupts):\n"
        "        seen.append(len(reduce_sample.signatures))\n"
        "    return real(s, h)\n"
        "signal.signal = spy\n"
        "engine_sim.run(engine_sim.load_scenario(engine_sim.shipped_scenarios()['pads_friction_patches'])"
        ".with_run(duration=0.01, warmup=0.0))\n"
        "print(seen)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    seen = eval(r.stdout.strip().splitlines()[-1])
    assert seen, "engine_sim.run did not defer signals through _Interrupts, which this test watches"
    assert all(n > 0 for n in seen), f"kernel signatures loaded when the deferral began: {seen}"
