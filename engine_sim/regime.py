"""Regimes of the scene: the limits that the scene's geometry and pymunk's solver put on a scenario, derived from
the scenario's own numbers and checked when it is loaded.

Each part states its limits (``Arrangement.limits``, ``Drive.limits``, ``Substrate.pad_depth``); this module
gathers them, adds the wear grains' solver limit and refuses the first one a scenario breaks, in one line naming
the field, its value and the limit (:func:`check_regimes`). What each limit protects (SI units throughout):

- the pad's tangential spring (length ``LT``): the largest friction of a pad column, on the stickiest patch, must
  stretch k0 by less than LT, or the pad passes its spring's anchor and the spring pushes it backwards
  (:data:`engine_sim.arrangements.LT`);
- the pre-compressed normal spring (length ``LN``): its compression F_s / k_normal must stay below LN, and the
  softening it adds to the pad's tangential stiffness, F_s / LN, below ``SOFTENING`` k0;
- the relief under a pad: the load N_pad / k_normal must cover the depth the pad follows below the track's datum on
  all but ``HANG_FRACTION`` of its path, or the pad hangs on its spring over the valleys;
- the contact's thickness: the distance a pad falls in one step under its load, (N_pad / m) dt^2, must stay below
  the track's segment radius, so a pad that leaves a rough track for one step never lands past the segment's
  centre line (pymunk pushes overlaps beyond its slop back out, from whichever side is nearer);
- a normal vibration (``engine_sim.vibration``): its peak speed A omega over one step below the segment radius,
  and its amplitude below the normal spring's travel LN - F_s / k_normal;
- the time step: omega dt < ``SPRING_OMEGA_DT`` and c dt / m < ``SPRING_DAMPING_X`` for every spring, the block's
  modes on its mounts and the drive spring included;

The mass ratios of the wear grains set no limit here: a grain of m_g squeezed by its pad (m_p) would keep
(1 + m_g / m_p)^-n of the pad's approach velocity after n Gauss-Seidel iterations of one step, which asks 17
iterations at m_g / m_p = 0.1 and 162 at 0.01; but pymunk warm-starts each contact's impulse from the step before,
and the project's measurements contradict that bound (a trapped grain of 1e-7 kg, 1e-4 of its pad, reads the
quasi-static climb within 4 % at 20 iterations: docs/explanation/wear_mass_limit.md). The grains' limit that holds
is the step's, omega_g dt <= 0.6, which ``engine_sim.wear.grain_step`` meets with substeps.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from frictionnoise.base import G

__all__ = ["Limit", "limits", "check_regimes", "mass_limit", "SOFTENING", "HANG_FRACTION", "LOST_CONTACT_S", "PARTIAL_LOSS_FRACTION",
           "SPRING_OMEGA_DT", "SPRING_DAMPING_X"]

# Explicit spring forces are accurate for omega dt < 0.3 (DESIGN.md, measured on pymunk 7.3).
SPRING_OMEGA_DT = 0.3
# Spring damping is exact-exponential but its effect is slowed by x/(e^x - 1), x = c dt / m: keep x < 0.1.
SPRING_DAMPING_X = 0.1
SOFTENING = 0.1  # the normal spring's geometric softening F_s / LN may change the pad's tangential stiffness by 10 %
HANG_FRACTION = 0.01  # a pad may hang over at most 1 % of its track's length
# a run whose pads all leave their tracks for longer than this stops (engine_sim.run), its trace marked partial
LOST_CONTACT_S = 0.1
# a run with at least this fraction of its pads off their tracks (others on theirs) for LOST_CONTACT_S warns
PARTIAL_LOSS_FRACTION = 0.1


@dataclass(frozen=True)
class Limit:
    """One regime limit: ``field`` (the scenario field it bounds, e.g. ``"block.M"``), its ``value`` and the
    ``limit`` (SI, in ``unit``), ``upper`` (True: value <= limit), ``why`` (what breaks beyond, one clause) and
    ``fix`` (other changes that would bring the scene inside, beside moving the field past its limit)."""

    field: str
    value: float
    limit: float
    unit: str
    why: str
    upper: bool = True
    fix: str = ""  # other changes that bring the scene inside, after the field's own ("or raise pads.k0 above ...")

    @property
    def ok(self) -> bool:
        return self.value <= self.limit if self.upper else self.value >= self.limit

    def message(self) -> str:
        word = "exceeds the limit" if self.upper else "is below the limit"
        u = f" {self.unit}" if self.unit else ""
        move = f"{'lower' if self.upper else 'raise'} {self.field} {'below' if self.upper else 'above'} {self.limit:.4g}{u}"
        return (f"{self.field} = {self.value:.4g}{u} {word} {self.limit:.4g}{u}: {self.why} "
                f"({move}{' or ' + self.fix if self.fix else ''})")


def mass_limit(sc, load_limit: float) -> float:
    """The block mass (kg) at which the column load ``normal_load_per_pad`` reaches ``load_limit`` (N): the load is
    M g cos(theta) / N plus the column's own weight, linear in M."""
    per_kg = G * sc.drive_part.load_factor() / sc.pads.N
    return (load_limit - sc.arrangement_part.column_mass * G) / per_kg


def load_limit(force, bound: float) -> float:
    """The largest column load L (N) with ``force(L) <= bound``, for a force increasing with the load (bisection
    to 1e-12 relative; 0 if even L = 0 exceeds it)."""
    if force(0.0) > bound:
        return 0.0
    hi = 1.0
    while force(hi) <= bound:
        hi *= 2.0
        if hi > 1e30:
            return math.inf
    lo = 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if force(mid) <= bound else (lo, mid)
        if hi - lo <= 1e-12 * hi:
            break
    return lo


def dt_limit(field: str, sc, omega: float = 0.0, damping_rate: float = 0.0, what: str = "") -> Limit:
    """The run.dt limit of one oscillator: omega dt < SPRING_OMEGA_DT (rad/s) and c dt / m < SPRING_DAMPING_X
    (``damping_rate`` = c / m, 1/s)."""
    lims = [SPRING_OMEGA_DT / omega] if omega > 0 else []
    lims += [SPRING_DAMPING_X / damping_rate] if damping_rate > 0 else []
    lim = min(lims) if lims else math.inf
    return Limit(field, sc.run.dt, lim, "s", f"{what}: omega dt < {SPRING_OMEGA_DT} and c dt / m < "
                                            f"{SPRING_DAMPING_X} for pymunk's explicit springs")


def limits(sc) -> list:
    """Every regime limit of a scenario, the parts' own first (:class:`Limit` each)."""
    out = list(sc.arrangement_part.limits())
    out += sc.drive_part.limits()
    if sc.vibration_part is not None:
        out += sc.vibration_part.limits()
    return out


def check_regimes(sc) -> None:
    """Raise ValueError with the first limit the scenario breaks (one line: field, value, limit, why)."""
    for lim in limits(sc):
        if not lim.ok:
            raise ValueError(lim.message())
