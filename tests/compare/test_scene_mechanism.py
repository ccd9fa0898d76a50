"""A scene judged by the identification machinery: the family point it was built with, against its trace's fit."""
import math

import numpy as np
import pytest

import frictionnoise as fn
from compare.analysis.scene_mechanism import built_point, judge


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
