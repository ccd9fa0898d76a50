"""What extending the scene asks: compare computes a law's slope by asking the law registry, never by a law's name."""
import re
from pathlib import Path

import pytest

from compare.analysis.extract import friction_slope
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.laws import LAWS
from engine_sim.scene import describe

ROOT = Path(__file__).resolve().parent.parent


def test_compare_names_no_law():
    src = (ROOT / "compare/analysis/extract.py").read_text()
    named = [name for name in LAWS if re.search(rf"[\"']{name}[\"']", src)]
    assert not named, f"compare/analysis/extract.py names the laws {named}: ask engine_sim.laws.LAWS instead"


@pytest.mark.parametrize("name", sorted(shipped_scenarios()))
def test_the_described_slope_is_the_recorded_velocity_part(name):
    # compare reads the slope of the velocity part the recorder records (drag_terms: c v + b N_pad ln(1 + v/v_c));
    # where the law strengthens, that is the law's own slope: exactly for the linear and log laws, to 2e-3 for the
    # rate-and-state law's steady log form (b = A - B, v_c = v_ss) against its exact asinh at the shipped speeds
    # (tests/test_rate_state_law.py); a weakening rate-and-state pad records no steady velocity part (b = 0)
    sc = load_scenario(name)
    law, load, v = sc.law_part, sc.arrangement_part.pad_load(), sc.steady_velocity
    desc = describe(sc)["friction_law"]
    got = friction_slope(desc, v)
    c, bN, vc = law.drag_terms(load, desc["c"])
    assert got == pytest.approx(c + bN / (vc + v), rel=1e-12)
    if law.slope(v, load, desc["c"]) > 0:
        assert got == pytest.approx(law.slope(v, load, desc["c"]), rel=2e-3 if desc["law"] == "rate_state" else 1e-12)
