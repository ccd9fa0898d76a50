"""A scene judged by the identification machinery: the family point it was built with, against its trace's fit."""
import math

import numpy as np
import pytest

import frictionnoise as fn
from compare.analysis.scene_mechanism import built_point, judge, level_checks


@pytest.fixture(scope="module")
def patches_trace():
    return fn.run_scene("pads_friction_patches", duration=4.0)


def test_a_patch_scene_is_built_as_model_I_with_its_own_a_and_level(patches_trace):
    model, theta, v = built_point(patches_trace)
    assert model == "model_I"
    assert theta["a"] == 1e-3  # the scenario's substrate, not the trace's correlation estimate
    # eq. (A11) with the scenario's alpha = 1, N = 30, c = 10 N s/m and f_kin the mean pad force
    f_kin = float(np.mean(patches_trace.pad_force))
    level = v * f_kin**2 / (12 * math.pi * 30 * 1e-3 * 10.0**2)
    assert theta["L"] == pytest.approx(level, rel=0.02)  # f_kin: mean over the pads in contact, 1-2 % apart
    assert theta["omega_c"] == pytest.approx(math.sqrt(30 * 3333.0 / 0.1), rel=1e-9)
    assert theta["omega_1"] == pytest.approx(10.0 / 1e-3)  # the pads' friction rate c / m


def test_judge_reports_each_identified_parameter_against_its_built_value(patches_trace):
    j = judge(patches_trace)
    assert j["built_as"] == "model_I" and j["rank"] >= 1
    for name, row in j["parameters"].items():
        assert row["built"] > 0
        if isinstance(row["fitted"], str):
            assert row["fitted"] == "not identified" and row["within"] is None
        else:
            assert row["half_width"] > 0 and isinstance(row["within"], bool)
    assert "eq. A11" in j["cannot_separate"]
    assert set(j["checks"]) >= {"alpha", "slope", "level_ratio", "level_trace_alpha", "within_trace_alpha"}


def test_level_checks_measure_what_the_built_level_rests_on(patches_trace):
    model, theta, v = built_point(patches_trace)
    c = level_checks(patches_trace, theta, v)
    # below the resonance model I's block answers the summed pad force as dv = -F / (N c): the scene's linear law,
    # N = 30 pads of c = 10 N s/m (measured 299.94-299.96 on 60 s traces; 4 s hold 80 blocks of 50 ms)
    assert c["slope"]["built"] == pytest.approx(300.0)
    assert c["slope"]["trace"] == pytest.approx(300.0, rel=0.01)
    # the record's own spread: 30 pads cross 20 patches each in 4 s; alpha^2's relative scatter over 600 patches is
    # sqrt(1.8 / 600) = 5.5 %, so alpha lies within 15 % of the substrate's (more than five standard deviations)
    assert c["alpha"]["built"] == 1.0 and c["alpha"]["trace"] == pytest.approx(1.0, rel=0.15)
    assert c["level_trace_alpha"] == pytest.approx(theta["L"] * c["alpha"]["trace"] ** 2)
    # the periodogram over the built spectrum between 2 v / a and omega_c / 2: about 300 ordinates, each exponential
    # about its mean (s.e. ~6 %), and the level's own scatter over 600 patches (5.5 %): within 30 % of 1
    lr = c["level_ratio"]
    assert lr["band"] == pytest.approx([2 * v / 1e-3, theta["omega_c"] / 2])
    assert 0.03 < lr["se"] < 0.1 and lr["ratio"] == pytest.approx(1.0, abs=0.3)
