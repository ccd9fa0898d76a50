"""engine_sim.batch_reader against pymunk's public batch calls, and the arbiter order against its definition."""
import numpy as np
import pymunk
import pymunk.batch as B

from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.batch_reader import BatchReader
from engine_sim.record import Recorder
from engine_sim.contact_order import _less, arbiter_keys, arbiter_order


def _public(space, fields, kind):
    buf = B.Buffer()
    (B.get_space_bodies if kind == "bodies" else B.get_space_arbiters)(space, fields, buf)
    return np.frombuffer(buf.int_buf(), dtype=np.int64).copy(), np.frombuffer(buf.float_buf()).copy()


def test_reads_what_pymunk_batch_reads_while_the_arrays_grow_and_shrink():
    """A space that gains bodies (pymunk's arrays reallocate: the views must follow) and loses them again: every
    read equals pymunk.batch's own, value for value, for bodies and arbiters."""
    space = pymunk.Space()
    space.gravity = (0, -10)
    floor = pymunk.Segment(space.static_body, (-100, 0), (100, 0), 1)
    space.add(floor)
    bodies = BatchReader(space, Recorder._BODY, "bodies")
    arbiters = BatchReader(space, Recorder._ARB, "arbiters")
    added = []
    for n in (1, 3, 40, 200, 5):
        while len(added) < n:
            b = pymunk.Body(1, 10)
            b.position = (-90 + (len(added) % 90) * 2.0, 1.5 + 3 * (len(added) // 90))
            added.append((b, pymunk.Circle(b, 0.9)))
            space.add(*added[-1])
        while len(added) > n:
            space.remove(*added.pop())
        for _ in range(5):
            space.step(0.01)
        for reader, kind, fields in ((bodies, "bodies", Recorder._BODY), (arbiters, "arbiters", Recorder._ARB)):
            ints, floats = reader.read()
            ref_i, ref_f = _public(space, fields, kind)
            assert np.array_equal(ints, ref_i) and np.array_equal(floats, ref_f), (kind, n)
        assert bodies.read()[0].size == n + 1  # an id per body, the space's static body too


def test_the_arbiter_order_is_the_insertion_order_of_its_comparison():
    """arbiter_order sorts on the bodies' key first and then by _less: the permutation must be the stable insertion
    sort by _less itself (the definition), here on a scene with many contacts per pad pair (pads_multiscale) and on
    shuffled copies of its batch."""
    sc = Scene(load_scenario(shipped_scenarios()["pads_multiscale"]))
    sc.advance(500)
    rec = Recorder(sc, 2)
    ai, af = (a.copy() for a in rec._arbiters.read())
    n = ai.size // 3
    rng = np.random.default_rng(1)
    for trial in range(4):
        perm = np.arange(n) if trial == 0 else rng.permutation(n)
        a2 = ai.reshape(n, 3)[perm].ravel().copy()
        f2 = af.reshape(n, -1)[perm].ravel().copy()
        key = arbiter_keys(a2, rec._tab)
        ref = list(range(n))
        for i in range(1, n):  # the definition: stable insertion by _less
            r, j = ref[i], i - 1
            while j >= 0 and _less(key, f2, r, ref[j]):
                ref[j + 1] = ref[j]
                j -= 1
            ref[j + 1] = r
        assert list(arbiter_order(key, f2)) == ref
