"""Scene and Recorder pickle through their own state methods (the checkpoints and the next issue's exact
continuation build on them)."""
import pickle

import numpy as np

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
    assert set(s2._pad_ids) == {p.id for p in s2.pads} and not set(s2._pad_ids) & set(scene._pad_ids)
    assert set(back._tab[:, 0]) == {s2.block.id, *(p.id for p in s2.pads)}
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
