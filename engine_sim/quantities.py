"""Units as instrument files write them, read by one parser for time series and profiles (pint).

A unit is parsed by pint (``MPa``, ``in``, ``kip``, ``gf``, ``mm/sec``, ``microns``, ``µm``) and checked against
the *role* of its column, which fixes the dimension it must have: length, force, stress, time, velocity or
dimensionless. Three explicit rules on top of pint, each recorded in :attr:`Unit.rule`:

- a mass unit on a force column (``g``, ``kg``, ``lb``: tribometers write grams for gram-force) is read as that
  unit's weight under standard gravity (``g`` -> gram-force, 9.80665e-3 N);
- ``A`` on a length column is the angstrom (pint's ``A`` is the ampere);
- a spelled-out name may be written in any case (``Micrometer``, ``MICRONS``: four letters or more, letters
  only); a symbol never (``Mm`` is the megametre, ``mm`` the millimetre).

A unit pint cannot parse, or one whose dimension does not fit the column's role, is a :class:`UnitError` naming
it. Nothing here knows files: the readers (``engine_sim.profile_file``, ``compare.io.measured``) say where.
"""
from __future__ import annotations

import functools
import re
from dataclasses import dataclass

__all__ = ["Unit", "UnitError", "parse_unit", "split_header", "ROLES", "STANDARD_GRAVITY"]

from frictionnoise.base import STANDARD_GRAVITY  # noqa: E402  (m/s^2: defines gram-force and kilogram-force)

# a role's dimension, as pint's dimensionality: exponents of [mass], [length], [time]
ROLES = {
    "length": {"[length]": 1},
    "force": {"[mass]": 1, "[length]": 1, "[time]": -2},
    "stress": {"[mass]": 1, "[length]": -1, "[time]": -2},
    "time": {"[time]": 1},
    "velocity": {"[length]": 1, "[time]": -1},
    "dimensionless": {},
}
_MASS = {"[mass]": 1}
_DIMENSIONLESS = ("-", "1", "—", "–")  # what exports write in a units row for a pure number (mu, a count)


class UnitError(ValueError):
    """A unit that cannot be read, or that does not fit its column's role: ``unit`` as written and ``reason``
    ("not a unit pint knows", "a force, not a length unit"); the message is "unit 'X' is <reason>"."""

    def __init__(self, unit: str, reason: str):
        super().__init__(f"unit {unit!r} is {reason}")
        self.unit, self.reason = unit, reason


@dataclass(frozen=True)
class Unit:
    """A unit as read: ``text`` as written, ``name`` as pint spells it, ``factor`` (SI units per file unit),
    ``role`` the dimension it has (a key of :data:`ROLES`) and ``rule`` the explicit rule applied, if any."""

    text: str
    name: str
    factor: float
    role: str
    rule: str = ""

    @property
    def written(self) -> str:
        """The unit as written, without brackets, the micro sign read as "u" (``µm`` -> ``um``)."""
        return _clean(self.text).replace("\u00b5", "u").replace("\u03bc", "u")


@functools.lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry()


def _clean(text: str) -> str:
    return text.strip().strip("[](){}").strip()


def _quantity(text: str):
    """pint's quantity of one ``text`` unit, or None when pint does not know it (spelled-out names in any case)."""
    ureg = _registry()
    tries = [text]
    if re.fullmatch(r"[A-Za-z]{4,}", text) and text.lower() != text:
        tries.append(text.lower())  # a spelled-out name; symbols stay as written (Mm is not mm)
    for t in tries:
        try:
            q = ureg.Quantity(1.0, t)
        except Exception:  # pint's parser raises many kinds (tokenize errors, assertions) on text that is no unit
            continue
        if not isinstance(q, ureg.Quantity):
            continue
        return q
    return None


def _dims(q) -> dict:
    return {k: v for k, v in dict(q.dimensionality).items() if v}


def parse_unit(text: str, roles) -> Unit:
    """The unit ``text`` read for a column whose role is one of ``roles`` (a role name or a tuple of them, the
    first that fits wins).

    Raises
    ------
    UnitError
        ``text`` is not a unit pint knows, or its dimension fits none of ``roles``.
    """
    roles = (roles,) if isinstance(roles, str) else tuple(roles)
    t = _clean(text)
    if t in _DIMENSIONLESS or t == "":
        if "dimensionless" in roles:
            return Unit(text, "dimensionless", 1.0, "dimensionless")
        raise UnitError(text.strip(), f"a pure number, not a {' or '.join(roles)} unit")
    if "length" in roles and t in ("A", "Å"):
        return Unit(text, "angstrom", 1e-10, "length", "A read as the angstrom")
    q = _quantity(t)
    if q is None:
        raise UnitError(t, "not a unit pint knows")
    dims = _dims(q)
    base = q.to_base_units()
    factor = float(base.magnitude)
    for role in roles:
        if dims == ROLES[role]:
            return Unit(text, f"{q.units:~}" or t, factor, role)
    if "force" in roles and dims == _MASS:
        return Unit(text, f"{t}f", factor * STANDARD_GRAVITY, "force",
                    f"{t} on a force column read as {t}-force (x {STANDARD_GRAVITY} m/s^2)")
    kind = next((r for r, d in ROLES.items() if d == dims), None) or (
        "a mass" if dims == _MASS else f"of dimension {q.dimensionality}")
    raise UnitError(t, f"{kind if kind.startswith(('a ', 'of ')) else 'a ' + kind}, not a {' or '.join(roles)} unit")


_BRACKET = re.compile(r"^(?P<name>.*?)\s*[\[(](?P<unit>[^\])]*)[\])]\s*$")
_SLASH = re.compile(r"^(?P<name>.+?)\s*/\s*(?P<unit>[^/\s]+)$")
_SUFFIX = re.compile(r"^(?P<name>.+?)[_\s]+(?P<unit>[^_\s]+)$")


def split_header(header: str) -> tuple[str, str | None, bool]:
    """(name, unit text or None, stated) of a column header: a bracketed unit (``x [mm]``, ``F(N)``,
    ``Effective_Normal_stress(MPa)``) is *stated* whatever it says (an unknown one is refused later, never
    dropped); a unit after a slash, an underscore or a space (``t/s``, ``x_um``, ``Raw Micrometer``) counts only
    when pint reads it as a length, force, mass, stress, time or velocity."""
    h = header.strip()
    m = _BRACKET.match(h)
    if m and m.group("unit").strip():
        return m.group("name").strip(), m.group("unit").strip(), True
    for pat in (_SLASH, _SUFFIX):
        m = pat.match(h)
        if m:
            q = _quantity(m.group("unit"))
            if q is not None and (_dims(q) in ROLES.values() or _dims(q) == _MASS) and _dims(q):
                return m.group("name").strip(), m.group("unit"), True
    return h, None, False
