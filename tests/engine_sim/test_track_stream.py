"""Streamed tracks: segments linked to their neighbours as pymunk's own Vec2d arithmetic links them (exact, so the
streaming's float path cannot move a bit of the scene), and dropped segments let go of (freed, not kept by the
static body)."""
import gc
import weakref

from engine_sim import Scene, load_scenario, shipped_scenarios


def _scene(name):
    return Scene(load_scenario(shipped_scenarios()[name]))


def _expected_links(segments, first_prev):
    """(a_prev, b_next) per segment of one chunk as the Vec2d arithmetic gives them: the previous segment's a (or
    a - (b - a) for a track's first), the next segment's b (or b + (b - a) for a chunk's last)."""
    out, prev = [], first_prev
    for i, s in enumerate(segments):
        a_prev = prev.a if prev is not None else s.a - (s.b - s.a)
        b_next = segments[i + 1].b if i + 1 < len(segments) else s.b + (s.b - s.a)
        out.append((tuple(a_prev), tuple(b_next)))
        prev = s
    return out


def test_neighbours_are_pymunks_vec2d_links():
    """Three chunks of a rough track, a line scan's track and a patch track with pits and one without, generated
    one at a time: every stored neighbour pair (the points given to set_neighbors) equals the Vec2d arithmetic's,
    bit for bit."""
    for name in ("pads_rough_profile", "line_scan_example", "pads_with_wear", "pads_friction_patches"):
        scene = _scene(name)
        tr = scene.tracks[0]
        prev = tr.segments[-1] if tr.segments else None
        for _ in range(3):
            n0 = len(tr.segments)
            tr._extend()
            segs = list(tr.segments)[n0:]
            want = _expected_links(segs, prev)
            got = [(tuple(a), tuple(b)) for a, b in list(tr.neighbors)[n0:]]
            assert got == want, name
            prev = segs[-1]


def test_dropped_segments_are_freed():
    """After the pads move on, the segments maintenance dropped are out of the space and off the static body, and
    nothing keeps them alive."""
    scene = _scene("pads_rough_profile")
    tr = scene.tracks[0]
    first = [weakref.ref(s) for s in list(tr.segments)[:5]]
    scene.advance(3000)
    scene.maintain()
    scene.advance(1)  # pymunk holds removed shapes until its next step
    gc.collect()
    assert tr.removed >= 5
    assert all(r() is None for r in first)
    live = set(scene.space.shapes)
    assert all(s in live for s in scene.space.static_body.shapes)  # the static body holds no dropped segment
