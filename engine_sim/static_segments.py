"""Static segments added to and removed from a pymunk space in batches, with chipmunk's own calls.

A streamed track adds and drops thousands of segments per simulated second. pymunk's public path costs
several microseconds of Python per segment beyond chipmunk's own work: the constructor's checks and its
attribute hooks, one property setter per friction, filter and neighbour pair, and ``Space.add`` /
``Space.remove`` with their checks. These functions make the same chipmunk calls in the same order and keep
pymunk's Python-side bookkeeping as pymunk keeps it (the shape's ``_body``, ``_shape``, ``_h`` and ``_space``,
the body's ``_shapes``, the space's ``_shapes`` and ``_removed_shapes``), so the shapes they make are
``pymunk.Segment`` objects that pymunk lists, queries, pickles and removes as its own. They rely on pymunk's
internals as of pymunk 7 (``tests/engine_sim/test_static_segments.py`` checks them against pymunk's public path).
"""
from __future__ import annotations

import weakref

import pymunk
from pymunk._chipmunk_cffi import ffi
from pymunk._chipmunk_cffi import lib as cp
from pymunk._util import _dead_ref

__all__ = ["add_segments", "remove_shapes", "segment_b"]

_NULL = ffi.NULL
_new = object.__new__
_setattr = object.__setattr__  # pymunk's own attribute hook, without its Python frame

segment_b = cp.cpSegmentShapeGetB  # segment_b(shape._shape).x: a segment's end b without pymunk's Vec2d


def _free(cp_shape) -> None:
    """Chipmunk's shape freed with its Python object, as pymunk's own finaliser frees it."""
    cp_space = cp.cpShapeGetSpace(cp_shape)
    if cp_space != _NULL:
        cp.cpSpaceRemoveShape(cp_space, cp_shape)
    cp.cpShapeFree(cp_shape)


def add_segments(space: pymunk.Space, body: pymunk.Body, a: list, b: list, radius: float, friction: list,
                 shape_filter: pymunk.ShapeFilter, a_prev: list, b_next: list) -> list:
    """Segments from ``a[i]`` to ``b[i]`` on ``body``, each with its friction and neighbours, added to ``space``
    in order: what ``pymunk.Segment(body, a, b, radius)``, setting ``friction`` and ``filter``,
    ``set_neighbors(a_prev, b_next)`` and ``space.add(*segments)`` make, with the same chipmunk calls.

    Parameters
    ----------
    space : pymunk.Space
        The space, not inside its step; ``body`` must already be in it.
    body : pymunk.Body
        The body the segments belong to (a track's: the space's static body).
    a, b : list
        End points, one (x, y) pair (tuple or list) per segment.
    radius : float
        The segments' radius.
    friction : list
        One friction coefficient per segment.
    shape_filter : pymunk.ShapeFilter
        The filter of every segment.
    a_prev, b_next : list
        Per segment, the points given to ``set_neighbors``: the previous segment's start and the next one's end.

    Returns
    -------
    list of pymunk.Segment
        The segments, in the order they were added.
    """
    assert not space._locked, "segments are added outside the space's step"
    assert body.space is space, "the segments' body must be in the space"
    new_seg, set_ud, set_fr = cp.cpSegmentShapeNew, cp.cpShapeSetUserData, cp.cpShapeSetFriction
    set_flt, set_nb, add = cp.cpShapeSetFilter, cp.cpSegmentShapeSetNeighbors, cp.cpSpaceAddShape
    gc, handle, new, cls, setattr = ffi.gc, ffi.new_handle, _new, pymunk.Segment, _setattr
    cp_body, cp_space = body._body, space._space
    body_ref, space_ref = weakref.ref(body), weakref.ref(space)
    body_shapes, space_shapes = body._shapes, space._shapes
    flt_p = ffi.new("cpShapeFilter *", tuple(shape_filter))  # converted once; owns the struct flt reads
    flt = flt_p[0]
    out = []
    append = out.append
    for pa, pb, mu, na, nb in zip(a, b, friction, a_prev, b_next):
        c = new_seg(cp_body, pa, pb, radius)
        seg = new(cls)
        setattr(seg, "_body", body_ref)
        body_shapes[seg] = None
        setattr(seg, "_shape", c := gc(c, _free))
        setattr(seg, "_h", h := handle(seg))
        set_ud(c, h)
        set_fr(c, mu)
        set_flt(c, flt)
        set_nb(c, na, nb)
        setattr(seg, "_space", space_ref)
        space_shapes[seg] = None
        add(cp_space, c)
        append(seg)
    return out


def remove_shapes(space: pymunk.Space, shapes) -> None:
    """Remove ``shapes`` from ``space`` and detach them from their body (``space.remove(*shapes)``, then
    ``shape.body = None`` for each), with the same chipmunk calls: their body no longer keeps them alive.

    Parameters
    ----------
    space : pymunk.Space
        The space that holds every one of ``shapes``, not inside its step.
    shapes : iterable of pymunk.Shape
        The shapes, each in ``space`` and on a body.
    """
    assert not space._locked, "shapes are removed outside the space's step"
    remove, set_body, cp_space = cp.cpSpaceRemoveShape, cp.cpShapeSetBody, space._space
    space_shapes, removed = space._shapes, space._removed_shapes
    setattr = _setattr
    for s in shapes:
        c = s._shape
        del space_shapes[s]  # a KeyError if the shape is not in the space
        removed[s] = None  # pymunk keeps removed shapes alive until its next step
        setattr(s, "_space", _dead_ref)
        remove(cp_space, c)
        del s._body()._shapes[s]
        set_body(c, _NULL)
        setattr(s, "_body", _dead_ref)
