"""A reader of pymunk's batch data (bodies or arbiters of a space) that keeps its call state between reads.

:func:`pymunk.batch.get_space_bodies` and :func:`~pymunk.batch.get_space_arbiters` build their iteration struct and
look up pymunk's iterator function on every call, and the caller then wraps each buffer in a new numpy view: about
6 us per read of a few tens of bodies, against 2-3 us for the C iteration itself. The recorder reads twice per output
step, so :class:`BatchReader` makes the struct, the function pointer and the numpy views once and calls the same C
function pymunk's does. A view is rebuilt when pymunk's array moves (it grows by reallocation), so the data are
always the array's own; ``tests/engine_sim/test_batch_reader.py`` checks them against pymunk's public calls.
"""
from __future__ import annotations

import numpy as np
import pymunk.batch as B
from pymunk._chipmunk import ffi, lib

__all__ = ["BatchReader"]

_EACH = {"bodies": ("cpSpaceEachBody", "pmSpaceBodyGetIteratorFuncBatched"),
         "arbiters": ("cpSpaceEachCachedArbiter", "pmSpaceArbiterIteratorFuncBatched")}


class BatchReader:
    """The ``fields`` of every body (``kind="bodies"``, :class:`pymunk.batch.BodyFields`) or of every cached arbiter
    (``"arbiters"``, :class:`pymunk.batch.ArbiterFields`) of ``space``, as pymunk's batch functions give them.

    Parameters
    ----------
    space : pymunk.Space
    fields : pymunk.batch.BodyFields or pymunk.batch.ArbiterFields
    kind : {"bodies", "arbiters"}
    """

    def __init__(self, space, fields, kind: str):
        each, iterator = _EACH[kind]
        self._space = space._space
        self._each = getattr(lib, each)
        self._iterator = ffi.addressof(lib, iterator)
        self._buffer = B.Buffer()  # owns the two C arrays (pymunk frees them with it)
        self._ints, self._floats = self._buffer._int_arr, self._buffer._float_arr
        self._data = ffi.new("pmBatchedData *")
        self._data.fields = fields.value
        self._data.floatArray = self._floats
        self._data.intArray = self._ints
        self._int_view = self._float_view = None
        self._int_at = self._float_at = None

    def read(self) -> tuple[np.ndarray, np.ndarray]:
        """(ints, floats): the int64 and float64 values of this read, in pymunk's order (views valid until the next
        read)."""
        ints, floats = self._ints, self._floats
        ints.num = floats.num = 0
        self._each(self._space, self._iterator, self._data)
        if self._int_at != (ints.arr, ints.max):
            self._int_at = (ints.arr, ints.max)
            self._int_view = np.frombuffer(ffi.buffer(ints.arr, 8 * ints.max), dtype=np.int64)
        if self._float_at != (floats.arr, floats.max):
            self._float_at = (floats.arr, floats.max)
            self._float_view = np.frombuffer(ffi.buffer(floats.arr, 8 * floats.max), dtype=np.float64)
        return self._int_view[:ints.num], self._float_view[:floats.num]
