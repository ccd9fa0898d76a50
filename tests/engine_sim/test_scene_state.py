"""Scene and Recorder pickle through their own state methods (the checkpoints and the next issue's exact
continuation build on them)."""
import pickle

import numpy as np
import pytest

import engine_sim
from engine_sim import Scene, load_scenario, scenario_from_dict
from engine_sim.record import Recorder


def _log_law():
    d = load_scenario("pads_friction_patches").to_dict()
    d["friction"].update(law="log", b=0.05, v_c=1e-3, c=5.0)
    return scenario_from_dict(d).with_run(duration=0.3, warmup=0.1)


def test_restored_scene_and_recorder_know_their_new_bodies():
    sc = _log_law()
    scene = Scene(sc)
    rec = Recorder(scene, 8)
    scene.advance(20)
    rec.sample()
    back = pickle.loads(pickle.dumps(rec))
    s2 = back.scene
    # pymunk ids are addresses: the restored bodies have new ones, and both parts re-read them
    assert not {p.id for p in s2.pads} & {p.id for p in scene.pads}
    assert set(back._tab[:, 0]) == {s2.block.id, *(p.id for p in s2.pads)}
    s2.advance(1)  # the log law reads the restored bodies' order: b N_pad on exactly the pads
    assert np.count_nonzero(s2.law._bN) == len(s2.pads)
    assert back.k == 1 and np.array_equal(back.out[:1], rec.out[:1])
    assert all(s.a.x for tr in s2.tracks for s in tr.segments)  # neighbours re-applied without error


def test_log_law_run_through_checkpoints_is_bitwise_the_uninterrupted_run():
    # before the scene re-read its pad ids on unpickling, a restored log-law scene applied the law's velocity
    # part to no body at all: the block sped up after the first checkpoint
    sc = _log_law()
    a = engine_sim.run(sc)
    b = engine_sim.run(sc, checkpoint_every=0.1)
    assert np.array_equal(a.x, b.x) and np.array_equal(a.F_drag, b.F_drag)
    assert np.all(np.abs(b.F_drag[1:]) > 0.5 * np.abs(b.F_drag[1]))  # the law acts throughout


@pytest.mark.slow  # about 10 s
@pytest.mark.timing  # a speed: beside a parallel worker at load 10 the ratio fell to 1.94; run alone
def test_step_costs_taking_turns_rank_the_wear_scene_above_the_patches():
    # engine_sim.timing: scenes measured in turns. The wear scene pays 20 solver iterations and 50 grains against
    # the patch scene's 2 iterations: 4.9x measured alone; 2x is far below that
    from engine_sim.timing import step_costs

    patches = load_scenario("pads_friction_patches")
    wear = load_scenario("pads_with_wear")
    c_patch, c_wear = step_costs([patches, wear], warmup=0.3, chunks=2)
    assert c_wear > 2.0 * c_patch, (c_patch, c_wear)
