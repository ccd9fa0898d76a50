"""The one number check of every parameter field, for scenario sections (``engine_sim``) and model parameters
(``reduced_models``) alike: the same rule gives the same one-line message wherever the field lives (a micro-pad
spring is ``pads.micro_k`` in a scenario and ``k2`` in model Ib; both say "must be > 0 (got -1.0)").
"""
from __future__ import annotations

import math
import numbers

__all__ = ["check_number", "check_fields"]


def check_number(name: str, val, *, positive: bool = False, non_negative: bool = False, integer: bool = False,
                 below: float | None = None, why: str = ""):
    """``val`` as field ``name`` of a parameter object: a real number (not a bool), finite, a whole number if
    ``integer`` (returned as int; 3.0 is 3), > 0 if ``positive``, >= 0 if ``non_negative``, < ``below`` if given.
    Raises ValueError, one line: "{name} must be a number (got str 'x')", "... must be an integer (got 2.5)",
    "... must be finite (got nan)", "... must be > 0 (got -1.0)", "... must be >= 0 (got -1)", "... must be < 2
    (got 2.5)", each followed by ``why`` if given."""
    tail = f": {why}" if why else ""
    if isinstance(val, bool) or not isinstance(val, numbers.Real):
        raise ValueError(f"{name} must be a number (got {type(val).__name__} {val!r}){tail}")
    if not math.isfinite(val):
        raise ValueError(f"{name} must be finite (got {val!r}){tail}")
    if integer and not float(val).is_integer():
        raise ValueError(f"{name} must be an integer (got {val!r}){tail}")
    if positive and not val > 0:
        raise ValueError(f"{name} must be > 0 (got {val!r}){tail}")
    if non_negative and val < 0:
        raise ValueError(f"{name} must be >= 0 (got {val!r}){tail}")
    if below is not None and not val < below:
        raise ValueError(f"{name} must be < {below:g} (got {val!r}){tail}")
    return int(val) if integer else val


def check_fields(obj, *, positive=(), non_negative=(), integer=(), prefix: str = "") -> None:
    """:func:`check_number` on the named attributes of a (frozen) dataclass, named ``prefix + field``; integer
    fields are stored back as int. An integer field is checked >= 0 unless it is also listed ``positive``."""
    for name in dict.fromkeys([*integer, *positive, *non_negative]):
        val = check_number(prefix + name, getattr(obj, name), positive=name in positive,
                           non_negative=name in non_negative or name in integer, integer=name in integer)
        if name in integer:
            object.__setattr__(obj, name, val)
