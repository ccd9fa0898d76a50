"""One rule per run field: a run's duration and seed are checked by one function each (frictionnoise.base), which
the Python API applies naming the argument and the command line applies naming the flag, both before anything
runs or is written."""
from pathlib import Path

import pytest

import engine_sim
from frictionnoise.base import check_seconds, check_seed

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("compare", "frictionnoise", "engine_sim", "reduced_models")


def _sources():
    for pkg in PACKAGES:
        yield from (p for p in (ROOT / pkg).rglob("*.py"))


@pytest.mark.parametrize("text", ["{name} must be a positive number of seconds",
                                  "{name} must be a whole number from 0 to 2^63", "2**63"])
def test_each_rule_is_written_once(text):
    """The rule's wording and bound appear in one module of the packages: the shared helpers."""
    where = [p.relative_to(ROOT).as_posix() for p in _sources() if text in p.read_text(encoding="utf-8")]
    assert where == ["frictionnoise/base.py"]


@pytest.mark.parametrize("bad", [-1, 2**63, 1.5, True, "3"])
def test_the_seed_rule(bad):
    with pytest.raises(ValueError, match=r"^seed must be a whole number from 0 to 2\^63 - 1 \(got "):
        check_seed("seed", bad)
    assert check_seed("seed", 2**63 - 1) == 2**63 - 1


def test_the_api_refuses_a_bad_seed_and_duration_before_it_steps():
    sc = engine_sim.load_scenario("constant_velocity")
    with pytest.raises(ValueError, match=r"^seed must be a whole number"):
        engine_sim.run(sc, duration=0.01, seed=-3)
    with pytest.raises(ValueError, match=r"^duration must be a positive number of seconds"):
        engine_sim.run(sc, duration=0.0)
    with pytest.raises(ValueError, match=r"^seconds must be a positive"):
        check_seconds("seconds", float("nan"))


@pytest.mark.parametrize("args, line", [(["--seed", "-3"], "--seed must be a whole number from 0 to 2^63 - 1 (got -3)"),
                                        (["--duration", "-1"], "--duration must be a positive number of seconds")])
def test_the_command_line_names_the_flag(tmp_path, capsys, args, line):
    """The same rule's line, naming the flag, exit 2, no traceback, no output folder."""
    from compare.cli import main

    out = tmp_path / "out"
    assert main(["run", "constant_velocity", *args, "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert line in err and "Traceback" not in err
    assert not out.exists()
