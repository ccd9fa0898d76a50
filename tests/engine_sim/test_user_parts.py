"""A user's parts as plugins: a friction law (tests/stribeck_law.py) and a recorded channel
(tests/block_energy_channel.py), each one module named in a scenario's ``plugins``, with no other file edited."""
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import engine_sim
from compare.analysis.extract import friction_slope
from engine_sim import ScenarioError, load_scenario
from engine_sim.scenario import resolve_scenario
from engine_sim.scene import describe

ROOT = Path(__file__).resolve().parents[2]
LAW = ROOT / "tests" / "stribeck_law.py"
CHANNEL = ROOT / "tests" / "block_energy_channel.py"
CLI = [str(Path(sys.executable).parent / "frictionnoise")]  # the installed command line


def _scene_file(tmp_path, name, plugins, friction=None, drive_v=5e-3, channels=()):
    """The shipped constant_velocity scene (30 pads on friction patches, driven at drive_v through a soft spring)
    with the plugins named relative to the file's folder, a [friction] section and channels."""
    text = resolve_scenario("constant_velocity").read_text()
    text = text.replace('name = "constant_velocity"', f'name = "{name}"')
    rel = [os.path.relpath(p, tmp_path) for p in plugins]
    head = f"plugins = {json.dumps(rel)}\n" + (f"channels = {json.dumps(list(channels))}\n" if channels else "")
    text = head + text
    if friction is not None:
        text = re.sub(r"\[friction\][^\[]*", "[friction]\n" + friction + "\n\n", text)
    text = re.sub(r"(?m)^v = 5e-3.*$", f"v = {drive_v!r}", text)
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


# dF/dv = c - 2 N_pad dmu (v / v_s^2) exp(-(v / v_s)^2) with N_pad = 0.0425 N: weakening for v in about
# (0.8, 2.95) mm/s, strengthening above; the drive's 5 mm/s lies on the strengthening branch (dF/dv = 2.6 N s/m)
STRIBECK = 'law = "stribeck"\nmu0 = 0.6\nc = 3.0\ndmu = 0.3\nv_s = 2.5e-3'


def test_no_file_of_the_package_names_the_plugins():
    # the law and the channel are registered by their own modules alone: no source of the package names them
    for pkg in ("engine_sim", "compare", "frictionnoise", "reduced_models"):
        for src in (ROOT / pkg).rglob("*.py"):
            text = src.read_text()
            assert "stribeck" not in text.lower() and "block_kinetic_energy" not in text, src


@pytest.fixture(scope="module")
def stribeck_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("stribeck")
    sc = load_scenario(_scene_file(tmp, "stribeck_pads", [LAW], STRIBECK)).with_run(duration=3.0, warmup=0.5)
    return sc, engine_sim.run(sc)


def test_stribeck_law_recorded_and_energy_balanced(stribeck_run):
    sc, tr = stribeck_run
    law = sc.law_part
    assert type(law).__name__ == "Stribeck" and tr.metadata["scenario"]["plugins"] == [str(LAW)]
    # the energy balance W_drive = dissipated + change of mechanical energy within 2 %, the tolerance the shipped
    # laws meet (tests/engine_sim/test_engine.py::test_energy_balance; measured here 2e-6)
    W, D, dE = tr.work_drive[-1], tr.dissipated[-1], tr.mech_energy[-1]
    assert abs(W - D - dE) < 0.02 * W
    # the force balance: contact friction plus the law's recorded velocity part against the drive, within 2 % as
    # for the linear law (measured 2e-5)
    assert np.mean(tr.F_t + tr.F_drag) == pytest.approx(np.mean(tr.F_drive), rel=0.02)
    # the recorded velocity part is the law's own: N (c v + N_pad dmu exp(-(v/v_s)^2)) at the pads' speed, which
    # the block's mean speed stands for to its fluctuation (measured 0.9 %; the bump is 2 % of the drag)
    v, load, s = np.mean(tr.v), sc.normal_load_per_pad, sc.friction
    g = s.c * v + load * s.dmu * np.exp(-(v / s.v_s) ** 2)
    assert np.mean(tr.F_drag) == pytest.approx(sc.pads.N * g, rel=0.02)
    # compare's slope is the law's, asked of the registry (Law.described_slope), at the operating point
    v0 = sc.steady_velocity
    assert friction_slope(describe(sc)["friction_law"], v0) == pytest.approx(law.slope(v0, load, s.c), rel=1e-12)
    assert law.slope(v0, load, s.c) > 0


def test_stribeck_point_on_the_weakening_branch_refused(tmp_path):
    bad = _scene_file(tmp_path, "stribeck_weak", [LAW], STRIBECK, drive_v=2e-3)  # dF/dv = -1.3 N s/m there
    with pytest.raises(ScenarioError, match=r"weakening branch .*friction\.c"):
        load_scenario(bad)
    out = tmp_path / "out"
    r = subprocess.run(CLI + ["run", str(bad), "-o", str(out)], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "stribeck_weak.toml" in lines[0] and "weakening branch" in lines[0]
    assert not out.exists()  # nothing written


def test_a_missing_plugin_or_channel_is_one_line(tmp_path):
    with pytest.raises(ScenarioError, match=r"plugins: .*no such file"):
        load_scenario(_scene_file(tmp_path, "nofile", [tmp_path / "absent.py"]))
    with pytest.raises(ScenarioError, match=r"channels: 'nothing' is not a registered channel"):
        load_scenario(_scene_file(tmp_path, "nochannel", [], channels=["nothing"]))


@pytest.mark.slow  # a compare of a 4 s scene run in a subprocess (~50 s wall)
def test_frictionnoise_compare_runs_a_scene_with_the_stribeck_law(tmp_path):
    path = _scene_file(tmp_path, "stribeck_pads", [LAW], STRIBECK)
    out = tmp_path / "cmp"
    r = subprocess.run(CLI + ["compare", str(path), "--duration", "4", "-o", str(out)], capture_output=True,
                       text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    s = json.loads((out / "summary.json").read_text())["scenarios"]["stribeck_pads"]
    assert abs(s["energy_balance_rel"]) < 0.02 and abs(s["force_balance_rel"]) < 0.02
    assert np.isfinite(s["gamma"]) and s["model_I_sim"]


def test_a_channel_plugin_is_recorded_and_changes_nothing_else(tmp_path):
    # the block's kinetic energy, by the channel's own kernel, against 0.5 M v^2 from the recorded speed: equal to
    # rounding (the block is guided: v_y = 0 to the solver's tolerance, 1e-9 relative in the energy)
    plain = load_scenario("constant_velocity").with_run(duration=0.5, warmup=0.1)
    sc = load_scenario(_scene_file(tmp_path, "with_channel", [CHANNEL], channels=["block_kinetic_energy"]))
    sc = sc.with_run(duration=0.5, warmup=0.1)
    tr, ref = engine_sim.run(sc), engine_sim.run(plain)
    ke = tr.channels["block_kinetic_energy"]
    assert ke.shape == (tr.t.size, 1)
    np.testing.assert_allclose(ke[:, 0], 0.5 * sc.block.M * tr.v ** 2, rtol=1e-9)
    for f in ("x", "v", "F_t", "F_n", "F_drag", "F_drive", "pad_force", "work_drive", "dissipated", "mech_energy"):
        assert np.array_equal(getattr(tr, f), getattr(ref, f)), f  # recording a channel changes no other field
    from compare.io.netcdf import load_netcdf, save_netcdf

    back = load_netcdf(save_netcdf(tr, tmp_path / "trace.nc"))  # the channel survives a netCDF round trip
    assert np.array_equal(back.channels["block_kinetic_energy"], ke)


@pytest.mark.slow  # a run and a compare of its trace in subprocesses (~40 s wall)
def test_a_channel_in_a_trace_file_and_compared(tmp_path):
    path = _scene_file(tmp_path, "with_channel", [CHANNEL], channels=["block_kinetic_energy"])
    run = tmp_path / "run"
    r = subprocess.run(CLI + ["run", str(path), "--duration", "4", "-o", str(run)], capture_output=True, text=True,
                       cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    from compare.io.traces import load_trace

    tr = load_trace(run / "trace.npz")
    np.testing.assert_allclose(tr.channels["block_kinetic_energy"][:, 0], 0.5 * 0.1 * tr.v ** 2, rtol=1e-9)
    # compare reads the trace in a fresh process: its metadata's plugins load the channel's module again
    r = subprocess.run(CLI + ["compare", str(run / "trace.npz"), "-o", str(tmp_path / "cmp")], capture_output=True,
                       text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def test_a_scenario_with_plugins_unpickles_in_a_fresh_process(tmp_path):
    # a spawned worker (the report's pool) unpickles the scenario before anything loaded its plugins
    import pickle

    sc = load_scenario(_scene_file(tmp_path, "stribeck_pads", [LAW], STRIBECK))
    blob = tmp_path / "sc.pkl"
    blob.write_bytes(pickle.dumps(sc))
    code = ("import pickle, sys; sc = pickle.loads(open(sys.argv[1], 'rb').read()); "
            "print(type(sc.law_part).__name__, sc.friction.dmu, sc.plugins == (sys.argv[2],))")
    r = subprocess.run([sys.executable, "-c", code, str(blob), str(LAW)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["Stribeck", "0.3", "True"]


def test_a_part_records_the_channels_it_declares(tmp_path):
    from types import SimpleNamespace as NS

    from engine_sim.channels import recorded_channels
    from engine_sim.plugins import load_plugins

    load_plugins([str(CHANNEL)])
    part = NS()
    law = NS(channels=("block_kinetic_energy",))  # a law that declares the channel
    scene = NS(sc=NS(channels=()), law=law, drive=part, substrate=part, arrangement=part, M=100.0)
    (ch,) = recorded_channels(scene)
    assert ch.name == "block_kinetic_energy" and ch.table()[0] == 100.0
    scene.sc.channels = ("block_kinetic_energy",)  # named by the scenario too: recorded once
    assert len(recorded_channels(scene)) == 1


def test_a_substrate_and_a_drive_from_a_plugin(tmp_path):
    # tests/relabelled_parts.py registers the shipped patches and velocity drive under new names: a scene of them,
    # named in [substrate] kind and [drive] kind, records the shipped scene's trace bit for bit
    path = _scene_file(tmp_path, "relabelled", [ROOT / "tests" / "relabelled_parts.py"])
    text = path.read_text().replace('kind = "patches"', 'kind = "relabelled_patches"')
    path.write_text(text.replace('kind = "velocity"', 'kind = "relabelled_velocity"'))
    sc = load_scenario(path).with_run(duration=0.3, warmup=0.1)
    assert (sc.substrate.kind, sc.drive.kind) == ("relabelled_patches", "relabelled_velocity")
    tr = engine_sim.run(sc)
    ref = engine_sim.run(load_scenario("constant_velocity").with_run(duration=0.3, warmup=0.1))
    for f in ("x", "v", "F_t", "F_n", "F_drag", "F_drive", "pad_force", "work_drive", "dissipated", "mech_energy"):
        assert np.array_equal(getattr(tr, f), getattr(ref, f)), f
