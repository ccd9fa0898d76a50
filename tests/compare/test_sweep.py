"""Sweeps: dask equals serial bit for bit; a killed sweep resumes only its missing tasks; the paper's
velocity analysis on model I (eq. 6 and the distance-domain collapse)."""
import json
import os
import signal
import subprocess
import sys
import time

import pytest

from compare.sweep import expand, load_results, load_sweep, run_sweep, task_id, velocity_analysis
from engine_sim.scenario import SCENARIO_DIR

SHIPPED = SCENARIO_DIR / "sweeps" / "velocity_model1.toml"


def _small(tmp_path, n_v=3, duration=60.0, seeds=(0, 1)):
    p = tmp_path / "small.toml"
    vs = [1e-4, 5e-4, 1e-3, 2e-3, 3e-3, 4e-3][:n_v]
    p.write_text(f'name = "small"\ntarget = "model_I"\n[fixed]\nduration = {duration}\ndt_out = 1e-3\n'
                 f"[grid]\nv = {vs}\nseed = {list(seeds)}\n")
    return p


@pytest.mark.slow  # dask cluster / long model I runs
def test_dask_local_cluster_equals_serial_bit_for_bit(tmp_path):
    # 30 s tasks (about 2 s each with their fits): what is compared is every number a task stores, and a task of
    # any length has the same ones (its spectrum and its record-model fit)
    spec = load_sweep(_small(tmp_path, duration=30.0))
    a = run_sweep(spec, tmp_path / "serial", serial=True)
    b = run_sweep(spec, tmp_path / "dask", workers=2)
    assert a["done"] == b["done"] == len(expand(spec)) == 6 and a["failed"] == b["failed"] == 0
    ra = {task_id(spec, r["params"], r["seed"]): r for r in load_results(tmp_path / "serial")}
    rb = {task_id(spec, r["params"], r["seed"]): r for r in load_results(tmp_path / "dask")}
    assert set(ra) == set(rb)
    for k in ra:  # spectra and fits identical, bit for bit (JSON keeps full float precision)
        assert ra[k]["C"] == rb[k]["C"] and ra[k]["omega"] == rb[k]["omega"] and ra[k]["fit"] == rb[k]["fit"]


@pytest.mark.slow  # dask cluster / long model I runs
def test_killed_sweep_reruns_only_missing_tasks(tmp_path):
    # 30 s tasks (3e4 samples: about 2 s each with their record-model fits) leave the kill, sent within 0.05 s of
    # the second task's file, seconds before the last task ends; the claim is the resume's bookkeeping, not the
    # physics, so the tasks need be no longer than that
    spec_path = _small(tmp_path, n_v=6, duration=30.0, seeds=(0,))
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "compare.cli", "sweep", str(spec_path), "--serial", "-o", str(out)]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline and len(list((out / "tasks").glob("*.json"))) < 2:
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done_before = len(list((out / "tasks").glob("*.json")))
    assert 2 <= done_before < 6, done_before
    before = {p.name: p.read_text() for p in (out / "tasks").glob("*.json")}
    spec = load_sweep(spec_path)
    res = run_sweep(spec, out, serial=True)
    assert res["ran"] == 6 - done_before and res["done"] == 6
    for name, text in before.items():  # finished tasks were not redone
        assert (out / "tasks" / name).read_text() == text
    again = run_sweep(spec, out, serial=True)
    assert again["ran"] == 0


def test_failed_task_is_reported_and_does_not_lose_the_others(tmp_path):
    p = tmp_path / "bad.toml"
    # v = 1e-3 works; a = 0 for the second grid value of a fails at construction inside the task
    p.write_text('name = "bad"\ntarget = "model_I"\n[fixed]\nduration = 20.0\n[grid]\nv = [1e-3, 2e-3]\n')
    spec = load_sweep(p)
    from dataclasses import replace
    spec = replace(spec, grid={"v": [1e-3, -1.0]})  # a bad value that slipped past validation
    res = run_sweep(spec, tmp_path / "o", serial=True)
    assert res["ran"] == 1 and res["failed"] == 1
    fail = json.loads(next((tmp_path / "o" / "failures").glob("*.json")).read_text())
    assert fail["params"]["v"] == -1.0 and "v must be > 0 (got -1.0)" in fail["error"]


@pytest.mark.slow  # five 120 s model I tasks with their record-model fits
def test_velocity_analysis_of_model_I(tmp_path):
    # The shipped sweep (5 velocities, 0.1-5 mm/s) at 120 s a run instead of its 600 s. Its spectra (16 Welch
    # segments, lowest omega 1.5 rad/s) still share a range of q = omega / v across the 50x in v below omega_max;
    # 60 s runs (lowest omega 3.1 rad/s) share none, so the collapse is not measured there. Eq. (6): C_x ~ v^3 at
    # fixed omega in the omega^-4 band; the distance-domain collapse cuts the spread at least 5x. Measured at 120 s,
    # seeds 0, 1, 2: v^2.976 +- 0.019, v^2.994 +- 0.072, v^3.007 +- 0.040 (95 %); collapse 48x, 40x, 30x (the
    # shipped 600 s, seed 0: v^2.994 +- 0.019, 38x, for 12x the CPU time).
    text = SHIPPED.read_text()
    assert "duration = 600.0" in text
    short = tmp_path / "velocity_120s.toml"
    short.write_text(text.replace("duration = 600.0", "duration = 120.0"))
    spec = load_sweep(short)
    run_sweep(spec, tmp_path / "v", serial=True)
    va = velocity_analysis(load_results(tmp_path / "v"), tuple(spec.analysis["omega_ref"]), spec.analysis["omega_max"])
    assert va["exponent"] == pytest.approx(3.0, abs=0.2)
    assert va["exponent_err"] < 0.2
    assert va["q_range"][1] > va["q_range"][0] and va["collapse_gain"] >= 5.0


def test_velocity_analysis_measures_no_collapse_without_a_common_q_range():
    # eq. (6)'s exact case C_x = v^3 omega^-4 at 0.1 and 5 mm/s: in q = omega / v every curve is q^-4 (C_s = v C_x),
    # a perfect collapse, but only where the curves share a range of q: over 3.1-150 rad/s they span 3.1e4-1.5e6 and
    # 620-3e4 1/m, nothing in common, so no collapse is measured (NaN, not a gain); from 0.3 rad/s they share 3e3-3e4
    import math

    import numpy as np

    def analysed(w_lo):
        w = np.geomspace(w_lo, 150.0, 40)
        return velocity_analysis([{"v": v, "omega": w.tolist(), "C": (v**3 * w**-4.0).tolist()} for v in (1e-4, 5e-3)],
                                 (70.0, 140.0), 150.0)

    short, long = analysed(3.1), analysed(0.3)
    assert short["exponent"] == pytest.approx(3.0) and math.isnan(short["collapse_gain"])
    assert long["q_range"][0] == pytest.approx(3e3) and long["collapse_gain"] > 1e6  # spread ~0 against ~4


def test_sweep_file_errors(tmp_path):
    from compare.sweep import SweepError

    p = tmp_path / "e.toml"
    p.write_text('target = "model_IV"\n[grid]\nv = [1e-3]\n')
    with pytest.raises(SweepError, match="target must be one of"):
        load_sweep(p)
    p.write_text('target = "model_I"\n[grid]\nv = [-1e-3]\n')
    with pytest.raises(SweepError, match=r"v must be > 0 \(got -0.001\)"):
        load_sweep(p)
    p.write_text('target = "model_I"\n[grid]\nvelocity = [1e-3]\n')
    with pytest.raises(SweepError, match="velocity"):
        load_sweep(p)


@pytest.mark.parametrize("body, needle", [
    ('[grid]\nvel = [1e-3]\n', "unknown key 'vel' in [grid]; valid names: F_drive, F_kin, M, N, a, alpha"),
    ('[fixed]\nduration = "long"\n[grid]\nv = [1e-3]\n',
     "fixed.duration must be a number of seconds in (0, 100000] (got 'long')"),
    ('[fixed]\nduration = nan\n[grid]\nv = [1e-3]\n', "fixed.duration must be a number of seconds"),
    ('[fixed]\nduration = -5.0\n[grid]\nv = [1e-3]\n', "fixed.duration must be a number of seconds"),
    ('[grid]\nv = ["fast"]\n', "grid.v must be a finite number (got 'fast')"),
    ('[grid]\nv = [inf]\n', "grid.v must be a finite number (got inf)"),
    ('[grid]\nN = [2.5]\n', "grid.N must be a whole number (got 2.5)"),
    ('[grid]\nv = [1e-3]\nseed = [-1]\n', "grid.seed must be a list of whole numbers from 0 to 2^63 - 1"),
    ('[grid]\nv = [1e-3]\n[analysis]\nomega = 3\n', "unknown key 'omega' in [analysis]"),
    ('[grid]\nv = [1e-3]\n[analysis]\nomega_ref = [140.0, 70.0]\n', "analysis.omega_ref must be two numbers"),
    ('name = 3\n[grid]\nv = [1e-3]\n', "name must be a string"),
    ('scenario = "x.toml"\n[grid]\nv = [1e-3]\n', "scenario = ... applies only to target = 'scenario'"),
    ('[fixed]\ndt_out = 1.0\nduration = 1.5\n[grid]\nv = [1e-3]\n', "duration = 1.5 s holds fewer than two steps"),
])
def test_sweep_file_validated_at_load(tmp_path, body, needle):
    """Every key's name, type and range is checked when the file is read, before any task runs (a misspelled
    grid key once reached the user as a TypeError from SpringBlockParams, `duration = "long"` failed every task)."""
    from compare.sweep import SweepError

    p = tmp_path / "s.toml"
    p.write_text('target = "model_I"\n' + body)
    with pytest.raises(SweepError) as e:
        load_sweep(p)
    assert needle in str(e.value) and "s.toml" in str(e.value)


@pytest.mark.slow  # a fresh interpreter importing dask, then the timeout (about 5 s)
@pytest.mark.timing  # exit within 14 s
def test_unreachable_scheduler_one_line_after_the_timeout_nothing_left(tmp_path):
    import socket

    s = socket.socket()
    s.bind(("127.0.0.1", 0))  # a port nobody listens on
    port = s.getsockname()[1]
    s.close()
    out = tmp_path / "o"
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "compare.cli", "sweep", str(_small(tmp_path)), "--scheduler",
                        f"tcp://127.0.0.1:{port}", "--connect-timeout", "1", "-o", str(out)],
                       capture_output=True, text=True, timeout=60)
    wall = time.perf_counter() - t0
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert f"no dask scheduler reachable at tcp://127.0.0.1:{port} within 1 s" in r.stderr
    assert not out.exists()
    assert wall < 14  # the 1 s timeout plus the interpreter and dask imports (was a 30 s hang and 59 lines)


def test_results_sorted_by_parameters(tmp_path):
    from compare.sweep.run import write_json as _write_json

    (tmp_path / "tasks").mkdir()
    for i, (v, seed) in enumerate([(3e-3, 0), (1e-4, 1), (1e-3, 0), (1e-4, 0)]):
        _write_json(tmp_path / "tasks" / f"{9 - i}.json", {"params": {"v": v, "duration": 5.0}, "seed": seed})
    got = [(r["params"]["v"], r["seed"]) for r in load_results(tmp_path)]
    assert got == [(1e-4, 0), (1e-4, 1), (1e-3, 0), (3e-3, 0)]


def test_a_narrowed_grid_reads_only_its_own_tasks(tmp_path):
    """A folder reused after its grid lost a value keeps the old tasks' files (the cache); the sweep counts, reports
    and loads only the grid's own (the wear study's folder had read '144/128 tasks done')."""
    out = tmp_path / "out"
    wide = _small(tmp_path, n_v=3, duration=20.0, seeds=(0,))
    assert run_sweep(load_sweep(wide), out, serial=True)["done"] == 3
    narrow = _small(tmp_path, n_v=2, duration=20.0, seeds=(0,))
    spec = load_sweep(narrow)
    r = subprocess.run([sys.executable, "-m", "compare.cli", "sweep", str(narrow), "--serial", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "2/2 tasks done (0 run now, 0 failed)" in r.stdout, r.stdout
    assert len(list((out / "tasks").glob("*.json"))) == 3  # the old task's file stays: widening again reuses it
    assert sorted(x["params"]["v"] for x in load_results(out, spec)) == [1e-4, 5e-4]
    assert len(load_results(out)) == 3
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_results"] == 2 and [x["v"] for x in summary["results"]] == [1e-4, 5e-4]


@pytest.mark.slow  # a LocalCluster of one worker (a few seconds)
def test_local_cluster_beside_another_on_8787_prints_nothing(capfd):
    # distributed starts its scheduler's HTTP server on port 8787 even without a dashboard and warns when another
    # cluster holds it: the sweep's cluster takes a free local port instead, so nothing is printed under its lines
    import socket
    import warnings

    from compare.sweep.run import _close, _connect

    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", 8787))
        holder.listen(1)
    except OSError:
        pass  # something else holds 8787 already: the same condition
    try:
        with warnings.catch_warnings(record=True) as caught:  # the CLI prints a warning on stderr
            warnings.simplefilter("always")
            client, cluster = _connect(None, 1, 10.0)
            assert client.submit(sum, [1, 2]).result() == 3
            _close(client, cluster)
    finally:
        holder.close()
    said = capfd.readouterr().err + "\n".join(str(w.message) for w in caught)
    assert "8787" not in said and "already in use" not in said, said


@pytest.mark.slow
def test_real_cluster_survives_a_killed_worker(tmp_path):
    """A `dask scheduler` and two `dask worker` processes on 127.0.0.1; one worker is killed (SIGKILL) while the
    sweep runs: the sweep completes on the other, with results identical to a serial run (wall times aside)."""
    import socket

    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    addr = f"tcp://127.0.0.1:{port}"
    dask = [os.path.join(os.path.dirname(sys.executable), "dask")]  # the venv's console script
    quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    procs = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              **quiet)]
    try:
        workers = [subprocess.Popen([*dask, "worker", addr, "--host", "127.0.0.1", "--nthreads", "1", "--no-nanny",
                                     "--no-dashboard"], **quiet) for _ in range(2)]
        procs += workers
        from distributed import Client

        with Client(addr, timeout="60s") as c:  # both workers up before the sweep starts
            c.wait_for_workers(2, timeout=120)
        # 30 s tasks (about 2 s each with their fits): the kill lands once the first has finished, 4 or more remain
        spec_path = _small(tmp_path, n_v=6, duration=30.0, seeds=(0,))
        out = tmp_path / "cluster"
        sweep = subprocess.Popen([sys.executable, "-m", "compare.cli", "sweep", str(spec_path), "--scheduler", addr,
                                  "-o", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.time() + 300
        while time.time() < deadline and len(list((out / "tasks").glob("*.json"))) < 1:
            assert sweep.poll() is None, sweep.communicate()
            time.sleep(0.05)
        done_at_kill = len(list((out / "tasks").glob("*.json")))
        workers[0].kill()  # mid-sweep: tasks remain
        workers[0].wait()
        so, se = sweep.communicate(timeout=600)
        assert sweep.returncode == 0, se[-3000:]
        assert 1 <= done_at_kill < 6 and "6/6 tasks done" in so, (done_at_kill, so)
        print(f"\ncluster: worker killed after {done_at_kill}/6 tasks; sweep completed on the other worker")
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
            p.wait()
    spec = load_sweep(spec_path)
    run_sweep(spec, tmp_path / "serial", serial=True)
    ra = {task_id(spec, r["params"], r["seed"]): r for r in load_results(tmp_path / "serial")}
    rb = {task_id(spec, r["params"], r["seed"]): r for r in load_results(out)}
    assert set(ra) == set(rb) and len(ra) == 6
    for k in ra:
        a, b = dict(ra[k]), dict(rb[k])
        a.pop("wall_s"), b.pop("wall_s")
        assert a == b


def test_the_sweep_file_example_lives_in_one_docstring():
    """compare/sweep/spec.py carries the sweep-file example; the tasks module points to it instead of a second copy."""
    import compare.sweep.spec as sweep_spec
    import compare.sweep.tasks as tasks

    assert "[grid]" in sweep_spec.__doc__ and "target =" in sweep_spec.__doc__
    assert "[grid]" not in tasks.__doc__ and ":mod:`compare.sweep.spec`" in tasks.__doc__


def test_without_dask_the_sweep_names_its_extra_and_writes_nothing(tmp_path):
    # dask is the `sweep` extra: an environment without it (simulated by a module that cannot be imported) gets one
    # line naming the extra, exit 2, before any output exists; --serial still runs
    blocker = tmp_path / "block"
    blocker.mkdir()
    (blocker / "distributed.py").write_text("raise ImportError('distributed is not installed')\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(blocker), os.environ.get("PYTHONPATH", ""), "."])}
    out = tmp_path / "o"
    one = str(_small(tmp_path, n_v=1, duration=20.0, seeds=(0,)))  # one task: what runs, not how much
    r = subprocess.run([sys.executable, "-m", "compare.cli", "sweep", one, "-o", str(out)],
                       capture_output=True, text=True, timeout=120, env=env)
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert "pip install 'frictionnoise[sweep]'" in r.stderr and "--serial" in r.stderr
    assert not out.exists()
    r = subprocess.run([sys.executable, "-m", "compare.cli", "sweep", one, "--serial", "-o", str(out)],
                       capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr
    assert (out / "summary.json").exists()
