"""Segments added and removed with chipmunk's own calls (engine_sim/static_segments.py) are pymunk's own: the
same chipmunk state as pymunk's public path builds, listed, pickled, queried and removed by pymunk as its own,
and freed once dropped."""
import gc
import pickle
import weakref

import pymunk
import pytest

from engine_sim.static_segments import add_segments, remove_shapes

_FLT = pymunk.ShapeFilter(group=3, categories=0b100, mask=0b110)
_A = [(0.0, 0.0), (1.0, 0.5), (2.0, 0.25)]
_B = [(1.0, 0.5), (2.0, 0.25), (3.0, 0.0)]
_MU = [0.6, 0.7, 0.8]
_PREV = [(-1.0, -0.5), (0.0, 0.0), (1.0, 0.5)]
_NEXT = [(2.0, 0.25), (3.0, 0.0), (4.0, -0.25)]


def _public(space):
    out = []
    for a, b, mu, na, nb in zip(_A, _B, _MU, _PREV, _NEXT):
        s = pymunk.Segment(space.static_body, a, b, 0.05)
        s.friction = mu
        s.filter = _FLT
        s.set_neighbors(na, nb)
        out.append(s)
    space.add(*out)
    return out


def _fast(space):
    return add_segments(space, space.static_body, _A, _B, 0.05, _MU, _FLT, _PREV, _NEXT)


def _state(s):
    return (type(s), tuple(s.a), tuple(s.b), s.radius, s.friction, s.filter, s.elasticity, s.sensor,
            s.collision_type, tuple(s.surface_velocity), s._hashid, tuple(s.bb), s.body, s.space)


def test_same_state_as_pymunks_public_path():
    """Every property pymunk reads, the hash ids chipmunk gives in order of insertion, and the bookkeeping of the
    space and the body match pymunk's own path, as does what a falling ball meets (the neighbours)."""
    spaces = [pymunk.Space(), pymunk.Space()]
    built = [_public(spaces[0]), _fast(spaces[1])]
    for space, segs in zip(spaces, built):
        assert list(space.shapes) == segs
        assert list(space.static_body.shapes) == segs
        assert all(pymunk.Shape._from_cp_shape(s._shape) is s for s in segs)  # chipmunk's user data: the handle
    for p, f in zip(*built):
        assert _state(p)[:-2] == _state(f)[:-2]
    traces = []
    for space in spaces:
        ball = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0, 0.2))
        ball.position = (0.97, 1.0)
        ball.velocity = (3.0, 0.0)
        c = pymunk.Circle(ball, 0.2)
        c.friction, c.filter = 0.5, _FLT
        space.add(ball, c)
        space.gravity = (0, -10)
        xs = []
        for _ in range(300):
            space.step(0.005)
            xs.append((ball.position.x, ball.position.y, ball.velocity.x, ball.velocity.y))
        traces.append(xs)
    assert traces[0] == traces[1]


def test_pickled_and_queried_as_pymunks():
    space = pymunk.Space()
    segs = _fast(space)
    q = space.point_query_nearest((1.5, 1.0), 2.0, pymunk.ShapeFilter())
    assert q.shape is segs[1]
    copy = pickle.loads(pickle.dumps(space))
    assert [_state(s)[:-2] for s in copy.shapes] == [_state(s)[:-2] for s in segs]


def test_removed_as_pymunk_removes_and_freed():
    """Removed shapes leave the space, chipmunk's index and their body; pymunk's public remove refuses them
    again; nothing keeps them alive after the space's next step; the rest stay."""
    space = pymunk.Space()
    segs = _fast(space)
    refs = [weakref.ref(s) for s in segs[:2]]
    remove_shapes(space, segs[:2])
    assert list(space.shapes) == segs[2:] and list(space.static_body.shapes) == segs[2:]
    assert all(s.space is None and s.body is None for s in segs[:2])
    assert space.point_query_nearest((0.5, 0.25), 0.3, pymunk.ShapeFilter()) is None
    with pytest.raises(AssertionError):
        space.remove(segs[0])
    with pytest.raises(KeyError):
        remove_shapes(space, segs[:1])
    space.remove(segs[2])  # pymunk's own remove takes the rest
    assert not space.shapes
    del segs
    space.step(0.01)
    gc.collect()
    assert all(r() is None for r in refs)
