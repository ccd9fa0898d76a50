"""The before/after tools of benchmarks/bench_vs_ref.py: the summary diff, and the rules that assign each differing
key to a cause or list it as unexplained."""
import math

from benchmarks.bench_vs_ref import diff_summaries, rel_diff, study_walls
from benchmarks.summary_causes import explain


def test_rel_diff_none_nan_and_equal():
    assert rel_diff(1.0, 1.0) == 0.0
    assert rel_diff(None, None) == 0.0 and rel_diff(float("nan"), float("nan")) == 0.0
    assert math.isinf(rel_diff(None, 1.0))
    assert math.isclose(rel_diff(1.0, 1.1), 0.1 / 1.1)


def _summary(gamma, ratio, extra=None):
    s = {"scenarios": {"pads_friction_patches": {"gamma": gamma, "wall_s": 3.0, "mean_speed": 4.9},
                       "pads_rough_profile": {"gamma": gamma + 0.5}},
         "model_I": {"band_ratios_vs_A10": [{"ratio": ratio}], "wall_s": 0.1}}
    s.update(extra or {})
    return s


def test_diff_lists_moved_keys_apart_from_timings():
    d = diff_summaries(_summary(4.0, 1.0), _summary(4.1, 1.0))
    assert set(d["differ"]) == {"scenarios/pads_friction_patches/gamma", "scenarios/pads_rough_profile/gamma"}
    assert d["timings_differ"] == []
    d2 = diff_summaries(_summary(4.0, 1.0), {**_summary(4.0, 1.0), "model_I": {"wall_s": 9.0,
                                                                              "band_ratios_vs_A10": [{"ratio": 1.0}]}})
    assert d2["differ"] == {} and d2["timings_differ"] == ["model_I/wall_s"]


def test_every_rule_and_what_no_rule_explains():
    ref = _summary(4.0, 1.0)
    # a fit key of an identical-trace scene, a rough-profile key, model I rounding: all explained
    head = _summary(4.1, 1.0 + 3e-11, {"model_Ib": {"reference": {"R": 1.0}}})
    e = explain(diff_summaries(ref, head))
    assert e["unexplained"] == [] and e["new_in_head"]["unexplained"] == []
    assert sum(map(len, e["causes"].values())) == 3
    # a non-fit number of an identical-trace scene, model I beyond rounding, an unknown new study: not explained
    head["scenarios"]["pads_friction_patches"]["mean_speed"] = 5.0
    head["model_I"]["band_ratios_vs_A10"][0]["ratio"] = 1.001
    head["new_study"] = {"x": 1.0}
    e = explain(diff_summaries(ref, head))
    assert e["unexplained"] == ["model_I/band_ratios_vs_A10[0]/ratio", "scenarios/pads_friction_patches/mean_speed"]
    assert e["new_in_head"]["unexplained"] == ["new_study/x"]


def test_study_walls_reads_scenes_and_models():
    assert study_walls(_summary(4.0, 1.0)) == {"scene pads_friction_patches": 3.0, "model_I": 0.1}
