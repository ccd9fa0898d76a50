"""compare.extract reads what it needs of a scene from the trace (metadata["scene"]), not the scenario's layout."""
import dataclasses
import math

import pytest

import engine_sim
from compare.analysis.extract import model_I_parameters, scene_info
from engine_sim import load_scenario
from engine_sim.scene import describe


def test_trace_carries_the_scene_description_extract_needs():
    sc = load_scenario("pads_friction_patches").with_run(duration=0.5, warmup=0.2)
    tr = engine_sim.run(sc)
    info = tr.metadata["scene"]
    assert info == describe(sc)
    # the same parameters from the trace alone as from trace + scenario (older traces carry no description)
    old = dataclasses.replace(tr, metadata={k: v for k, v in tr.metadata.items() if k != "scene"})
    assert model_I_parameters(tr) == model_I_parameters(old, sc)
    with pytest.raises(ValueError, match="pass its scenario"):
        scene_info(old)
    # omega* = N c / M = 30 x 10 / 0.1 = 3000 rad/s, far above the fit band's top 30 v/a = 150 rad/s: viscous
    assert info["omega_star"] == pytest.approx(3000.0, rel=1e-12) and info["response"] == "viscous"


def test_effective_mass_of_leonardo_slider_is_block_plus_hanging_mass():
    sc = load_scenario("leonardo_slider")
    info = describe(sc)
    # the scenario's hanging mass, 0.2309 kg, is the drive N f(v) / g = 0.230905 kg that slides the law at v,
    # rounded; the accelerated mass is the block's plus it
    assert sc.pads.N * sc.law_force(sc.drive.v) / 9.81 == pytest.approx(0.2309, rel=1e-4)
    assert info["effective_mass"] == pytest.approx(0.1 + 0.2309, rel=1e-12)
    assert info["block_mass"] == sc.block.M
    sole = describe(load_scenario("asperity_field"))
    assert sole["contact_width"] == pytest.approx(30 * 0.4e-3, rel=1e-12)  # w = N foot_length = 12 mm
    assert sole["substrate"]["kind"] == "asperities" and math.isclose(sole["substrate"]["p"], 0.1)


def test_traces_written_before_substrate_parts_still_load():
    # a trace whose metadata lists every substrate kind's fields (as older traces do) is rejected by the strict
    # reader and read leniently by compare
    from engine_sim import ScenarioError, scenario_from_dict

    d = load_scenario("pads_rough_profile").to_dict()
    d["substrate"].update(alpha=1.0, cell=1e-4, p=0.1, pit_p=0.0)  # other kinds' defaults, as written then
    with pytest.raises(ScenarioError, match="unknown key substrate"):
        scenario_from_dict(d)
    sc = scenario_from_dict(d, strict=False)
    assert sc.substrate == load_scenario("pads_rough_profile").substrate
