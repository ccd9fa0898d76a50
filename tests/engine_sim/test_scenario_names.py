"""Shipped scenarios have names: `frictionnoise run NAME` from any folder; an existing path wins over a name."""
import pytest

from compare.cli import main
from engine_sim import ScenarioError, load_scenario, shipped_scenarios
from engine_sim.scenario import resolve_scenario, scenario_summary


def test_name_resolves_from_another_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert resolve_scenario("pads_friction_patches") == shipped_scenarios()["pads_friction_patches"]
    assert resolve_scenario("pads_friction_patches.toml") == shipped_scenarios()["pads_friction_patches"]
    assert load_scenario("leonardo_slider").drive.kind == "leonardo"


def test_existing_path_wins_over_shipped_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pads_friction_patches.toml").write_text('name = "mine"\n[block]\nM = 0.2\n')
    sc = load_scenario("pads_friction_patches.toml")
    assert (sc.name, sc.block.M) == ("mine", 0.2)


def test_unknown_name_lists_the_shipped_ones(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ScenarioError, match="pads_with_wear"):
        resolve_scenario("no_such_scene")
    with pytest.raises(ScenarioError):  # a path with folders is never taken for a name
        resolve_scenario("some/dir/pads_friction_patches")
    assert main(["run", "no_such_scene"]) == 2
    assert "no_such_scene" in capsys.readouterr().err


@pytest.mark.parametrize("columns", [80, 100, 200])
def test_scenarios_command_prints_whole_first_sentences_wrapped(columns, capsys, monkeypatch):
    """Each scene's name, then the first sentence of its description whole (never cut mid-word, no "..."), wrapped
    to the terminal's width under a hanging indent."""
    monkeypatch.setenv("COLUMNS", str(columns))
    assert main(["scenarios"]) == 0
    lines = capsys.readouterr().out.splitlines()
    names = sorted(shipped_scenarios())
    assert [ln.split()[0] for ln in lines if not ln.startswith(" ")] == names
    assert all(len(ln) < columns for ln in lines)
    text = " ".join(ln.strip() for ln in lines)
    for name in names:
        first = scenario_summary(load_scenario(name).description, width=10**6)
        assert f"{name} {first}" in " ".join(text.split()), name
        assert first.endswith(".") and "..." not in first


def test_summary_keeps_abbreviations_whole():
    assert scenario_summary("A slider (paper Fig. 7) on pads. More text.") == "A slider (paper Fig. 7) on pads."


def test_shipped_names_are_the_scene_files_of_engine_sims_package_data():
    # the scenes are package data of engine_sim (engine_sim/scenarios/, installed with every install, not a module):
    # `frictionnoise scenarios` lists exactly its scene files, and nothing named `scenarios` is importable
    import importlib.util
    from pathlib import Path

    import engine_sim

    folder = Path(engine_sim.__file__).parent / "scenarios"
    assert sorted(p.stem for p in folder.glob("*.toml")) == sorted(shipped_scenarios())
    assert all(Path(p).parent == folder for p in shipped_scenarios().values())
    assert not (folder / "__init__.py").exists() and importlib.util.find_spec("scenarios") is None
