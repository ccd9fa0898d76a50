"""What extending the scene asks: compare computes a law's slope by asking the law registry, never by a law's name."""
import re
from pathlib import Path

import pytest

from compare.analysis.extract import friction_slope
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.laws import LAWS
from engine_sim.scene import describe

ROOT = Path(__file__).resolve().parents[2]


def test_compare_names_no_law():
    src = (ROOT / "compare/analysis/extract.py").read_text()
    named = [name for name in LAWS if re.search(rf"[\"']{name}[\"']", src)]
    assert not named, f"compare/analysis/extract.py names the laws {named}: ask engine_sim.laws.LAWS instead"


@pytest.mark.parametrize("name", sorted(shipped_scenarios()))
def test_the_described_slope_is_the_recorded_velocity_part(name):
    # compare reads the slope of the velocity part the recorder records (drag_terms: c v + b N_pad ln(1 + v/v_c));
    # where the law strengthens, that is the law's own slope: exactly for the linear and log laws, to 2e-3 for the
    # rate-and-state law's steady log form (b = A - B, v_c = v_ss) against its exact asinh at the shipped speeds
    # (tests/engine_sim/test_rate_state_law.py); a weakening rate-and-state pad records no steady velocity part (b = 0)
    sc = load_scenario(name)
    law, load, v = sc.law_part, sc.arrangement_part.pad_load(), sc.steady_velocity
    desc = describe(sc)["friction_law"]
    got = friction_slope(desc, v)
    c, bN, vc = law.drag_terms(load, desc["c"])
    assert got == pytest.approx(c + bN / (vc + v), rel=1e-12)
    if law.slope(v, load, desc["c"]) > 0:
        assert got == pytest.approx(law.slope(v, load, desc["c"]), rel=2e-3 if desc["law"] == "rate_state" else 1e-12)


def test_a_scenario_builds_its_parts_once_and_a_scene_its_own():
    from engine_sim import Scene

    sc = load_scenario("pads_rate_state").with_run(warmup=0.0)
    assert sc.law_part is sc.law_part and sc.arrangement_part is sc.arrangement_part
    a, b = Scene(sc), Scene(sc)
    # a law's impulse totals are per scene: two scenes of one scenario share no part
    assert a.law is not b.law and a.law is not sc.law_part and a.drive is not b.drive
    a.advance(a.n_sub)
    assert a.law.impulse_totals(a) is not b.law.impulse_totals(b)


class _Scene:
    """A stand-in scene that logs what the loop asks of it."""

    n_sub = 3

    def __init__(self):
        self.log = []

    def maintain(self):
        self.log.append("maintain")

    def advance(self, n):
        self.log.append(f"advance {n}")


class _Recorder:
    def __init__(self, log):
        self.log = log

    def sample(self):
        self.log.append("sample")


def test_the_loop_samples_maintains_every_64_and_ends_a_recording_on_its_sample():
    from engine_sim.loop import MAINTAIN_EVERY, Loop

    s = _Scene()
    n = MAINTAIN_EVERY + 2
    seen = []
    loop = Loop(s, _Recorder(s.log), n_out=n, on_maintain=seen.append)
    loop.step()
    loop.run(n - 1)
    assert loop.k == n and seen == [0, MAINTAIN_EVERY]
    assert s.log[:3] == ["sample", "maintain", "advance 3"]
    assert s.log.count("sample") == n and s.log.count("advance 3") == n - 1 and s.log[-1] == "sample"
    i = [j for j, e in enumerate(s.log) if e == "sample"][MAINTAIN_EVERY]
    assert s.log[i + 1] == "maintain"  # right after the 65th sample, before its steps
    s.log.clear()
    Loop(s).run(2)  # a warm-up: no recorder, every output step steps
    assert s.log == ["maintain", "advance 3", "advance 3"]


FAMILIES = [("laws", "law"), ("drives", "drive"), ("substrates", "substrate"), ("arrangements", "arrangement")]


@pytest.mark.parametrize("package, base", FAMILIES)
def test_a_family_s_names_are_the_package_s_and_old_checkpoints_find_them(package, base):
    """Each family's base module (``engine_sim/laws/law.py``) is what the package re-exports: the names a plugin or
    a how-to imports from the package are the same objects, and a pickle naming a class by the package's path (a
    checkpoint written when the base was the package's ``__init__``) loads it."""
    import importlib
    import pickle
    import pkgutil

    pkg = importlib.import_module(f"engine_sim.{package}")
    mod = importlib.import_module(f"engine_sim.{package}.{base}")
    for name in mod.__all__:
        assert getattr(pkg, name) is getattr(mod, name), f"engine_sim.{package}.{name}"
    assert set(mod.__all__) <= set(pkg.__all__)
    spec = next(n for n in mod.__all__ if n.endswith("Spec"))
    assert pickle.loads(f"cengine_sim.{package}\n{spec}\n.".encode()) is getattr(mod, spec)
    # importing the package registers a kind from each of its other modules (a plugin's kinds may sit beside them)
    registry = next(getattr(mod, n) for n in mod.__all__ if n.isupper() and isinstance(getattr(mod, n), dict))
    kinds = {k.__module__ for k in registry.values() if k.__module__.startswith(f"engine_sim.{package}.")}
    assert kinds == {f"engine_sim.{package}.{m.name}" for m in pkgutil.iter_modules(pkg.__path__) if m.name != base}


def test_the_loop_at_a_finer_step_samples_each_and_maintains_as_a_run_does():
    # n_sub = 1 on a scene of 3 steps per output step: a sample before every pymunk step, the maintenance every
    # MAINTAIN_EVERY * 3 pymunk steps (where a run's loop maintains), none between
    from engine_sim.loop import MAINTAIN_EVERY, Loop

    s = _Scene()
    n = 3 * MAINTAIN_EVERY + 2
    seen = []
    Loop(s, _Recorder(s.log), n_out=n, on_maintain=seen.append, n_sub=1).run(n)
    assert seen == [0, 3 * MAINTAIN_EVERY]
    assert s.log.count("sample") == n and s.log.count("advance 1") == n - 1 and "advance 3" not in s.log
    with pytest.raises(ValueError, match="n_sub = 2 does not divide the scene's 3"):
        Loop(s, n_sub=2)
