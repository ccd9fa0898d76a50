"""The scenario loader under fuzzed input: nothing but the documented ScenarioError escapes."""
import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from engine_sim.scenario import _SECTIONS, ScenarioError, scenario_from_dict
from engine_sim.substrates import SUBSTRATES as KINDS

values = st.one_of(st.none(), st.sampled_from(sorted(KINDS)), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
                   st.text(max_size=8), st.lists(st.integers(), max_size=3), st.dictionaries(st.text(max_size=4), st.integers(), max_size=2))
known = {sec: [f for f in cls.__dataclass_fields__] for sec, cls in _SECTIONS.items()}
known["substrate"] = sorted({f for k in KINDS.values() for f in k.Spec.__dataclass_fields__})  # every kind's fields
section = st.sampled_from(sorted(known)).flatmap(
    lambda sec: st.tuples(st.just(sec), st.dictionaries(st.sampled_from(known[sec] + ["bogus"]), values, max_size=4)))
docs = st.one_of(
    st.dictionaries(st.sampled_from(sorted(known) + ["name", "description", "extra"]), values, max_size=4),
    st.lists(section, max_size=4).map(dict),
    values,
)


@pytest.mark.slow  # hypothesis fuzzing of the loader
@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(docs)
def test_loader_raises_only_scenario_errors(doc):
    try:
        sc = scenario_from_dict(doc)
    except ScenarioError as e:
        assert str(e) and "\n" not in str(e)
        return
    # whatever loads is physically usable: a positive step within the spring limit, a sliding block
    assert 0 < sc.run.dt <= sc.dt_limit
    assert sc.steady_velocity > 0 and math.isfinite(sc.drive_force)
