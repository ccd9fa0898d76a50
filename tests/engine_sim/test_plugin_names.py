"""Plugins under stable names, so numba's cache beside a plugin finds its module in every later process, and
plugins and channels that fail to load or are misdeclared stop a run with one line (exit 2, nothing written).

numba's cache records the name of the module a kernel was compiled in, and a later process imports that name to
use the cache: each case runs two fresh processes on one cache, the second calling the kernel off it."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from engine_sim.channels import CHANNELS, Channel, check_channel

ROOT = Path(__file__).resolve().parents[2]
CHANNEL = ROOT / "tests" / "block_energy_channel.py"
CLI = [str(Path(sys.executable).parent / "frictionnoise")]

# loads the plugins named on the command line, then calls every registered channel's cached kernel once
_CALL = """
import sys
import numpy as np
from engine_sim.channels import CHANNELS
from engine_sim.plugins import load_plugins
load_plugins(sys.argv[1:])
for name, cls in sorted(CHANNELS.items()):
    out = np.zeros(cls.columns)
    cls.reduction(np.zeros(0, np.int64), np.zeros(0), np.zeros((0, 3), np.int64), np.ones(1), out)
    print(name)
"""


def _call(entries, cwd, pythonpath=()):
    """A fresh process loading ``entries`` and calling their kernels; the completed process."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), *map(str, pythonpath)])}
    env.pop("NUMBA_CACHE_DIR", None)  # the cache beside each plugin file, as a user's
    env.pop("NUMBA_DISABLE_JIT", None)
    return subprocess.run([sys.executable, "-c", _CALL, *map(str, entries)], capture_output=True, text=True,
                          cwd=cwd, env=env)


def _copy(src: Path, dest: Path, name: str | None = None) -> Path:
    """The example channel's module at ``dest``, its channel renamed to ``name`` if given."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    text = src.read_text()
    dest.write_text(text if name is None else text.replace('"block_kinetic_energy"', f'"{name}"'))
    return dest


def test_two_plugin_files_of_one_name_each_keep_their_cache(tmp_path):
    # first both files in one process (the second file's name must not depend on the first), then the second alone
    a = _copy(CHANNEL, tmp_path / "a" / "chan.py")
    b = _copy(CHANNEL, tmp_path / "b" / "chan.py", "block_ke_b")
    r = _call([a, b], tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["block_ke_b", "block_kinetic_energy"]
    r = _call([b], tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["block_ke_b"]


@pytest.mark.parametrize("first", ["file", "module"])
def test_a_plugin_named_as_a_file_and_as_a_module_shares_its_cache(tmp_path, first):
    # mylab/chan.py loaded as a file and as the module mylab.chan, one after the other in fresh processes
    _copy(CHANNEL, tmp_path / "pkg" / "mylab" / "__init__.py").write_text("")
    path = _copy(CHANNEL, tmp_path / "pkg" / "mylab" / "chan.py")
    runs = [([path], ()), (["mylab.chan"], [tmp_path / "pkg"])]
    for entries, pythonpath in (runs if first == "file" else runs[::-1]):
        r = _call(entries, tmp_path, pythonpath)
        assert r.returncode == 0, r.stderr
        assert r.stdout.split() == ["block_kinetic_energy"]


def _scene(tmp_path, plugin: Path, channels=()) -> Path:
    """constant_velocity with the plugin and the channels named."""
    from engine_sim.scenario import resolve_scenario
    text = resolve_scenario("constant_velocity").read_text()
    head = f'plugins = ["{plugin.name}"]\n' + (f"channels = {list(channels)!r}\n".replace("'", '"') if channels
                                                else "")
    path = tmp_path / "scene.toml"
    path.write_text(head + text)
    return path


def _run_cli(tmp_path, scene):
    out = tmp_path / "out"
    r = subprocess.run(CLI + ["run", str(scene), "--duration", "0.1", "-o", str(out)], capture_output=True,
                       text=True, cwd=tmp_path)
    return r, out


def test_a_plugin_that_fails_to_load_is_one_line_naming_its_file(tmp_path):
    bad = tmp_path / "broken_law.py"
    bad.write_text("raise RuntimeError('the lab constant is missing\\nsecond line')\n")
    r, out = _run_cli(tmp_path, _scene(tmp_path, bad))
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and str(bad) in lines[0] and "the lab constant is missing" in lines[0], lines
    assert not out.exists()


def test_a_misdeclared_channel_stops_the_run_before_it_starts(tmp_path):
    # the command line's end of register's check (every field's check: test_register_checks_every_field_...)
    field, value, allowed = "quantity", '"lenght"', "length"
    text = CHANNEL.read_text().replace(f'    {field} = "energy"', f"    {field} = {value}")
    assert text != CHANNEL.read_text()
    plugin = tmp_path / "my_channel.py"
    plugin.write_text(text)
    r, out = _run_cli(tmp_path, _scene(tmp_path, plugin, ["block_kinetic_energy"]))
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert "block_kinetic_energy" in lines[0] and field in lines[0] and value.strip('"') in lines[0]
    assert allowed in lines[0] and "my_channel.py" in lines[0]
    assert not out.exists()  # nothing written: the run never started


def _declared(**fields):
    """A Channel subclass with the example's declaration, ``fields`` changed (a value None removes the field)."""
    body = {"name": "probe_channel", "kind": "energy", "quantity": "energy", "reduction": staticmethod(len)}
    body.update(fields)
    return type("Probe", (Channel,), {k: v for k, v in body.items() if v is not None})


@pytest.mark.parametrize("fields, message", [
    ({"quantity": None}, r"channel 'probe_channel': quantity is not set; one of .*length.*energy"),
    ({"quantity": "Energy"}, r"quantity is 'Energy'; one of "),
    ({"kind": None}, r"kind is not set; one of force, impulse, state, energy"),
    ({"kind": "power"}, r"kind is 'power'"),
    ({"columns": 0}, r"columns is 0; an int >= 1"),
    ({"columns": 1.0}, r"columns is 1.0"),
    ({"name": ""}, r"channel 'Probe': name must be a non-empty string"),
    ({"reduction": None}, r"reduction is not set"),
])
def test_register_checks_every_field_of_a_channel(fields, message):
    cls = _declared(**fields)
    with pytest.raises(ValueError, match=message):
        CHANNELS.register(cls)
    assert cls.name not in CHANNELS or CHANNELS[cls.name] is not cls  # not registered


def test_a_well_declared_channel_passes_and_the_shipped_example_is_one():
    check_channel(_declared())
    sys.path.insert(0, str(CHANNEL.parent))
    try:
        import block_energy_channel  # noqa: F401  (registers the example, checked by register)
    finally:
        sys.path.remove(str(CHANNEL.parent))
    check_channel(CHANNELS["block_kinetic_energy"])


def test_a_file_plugin_answers_its_own_module_name_and_no_folder_name(tmp_path):
    # the names numba's cache may ask for: the file's stem (and its package's dotted name), never a plain folder
    import importlib

    from engine_sim.plugins import load_plugins, plugin_name

    path = _copy(CHANNEL, tmp_path / "plain_folder" / "alias_probe_chan.py", "alias_probe")
    load_plugins([str(path)])
    mod = sys.modules[plugin_name(path.resolve())]
    assert importlib.import_module("alias_probe_chan") is mod
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("plain_folder")
    assert plugin_name(path.resolve()) == plugin_name(path.resolve())
    assert plugin_name(path.resolve()) != plugin_name((tmp_path / "other" / path.name).resolve())
