"""Scenarios: frozen SI parameter sets for the engine scene, loaded from TOML and validated once.

A scenario file has a top-level ``name`` and ``description`` and the sections ``[block]``, ``[pads]``,
``[friction]``, ``[substrate]``, ``[drive]``, ``[wear]`` and ``[run]``; every key is optional (defaults below, SI units).
Unknown sections or keys, wrong types and out-of-range values raise :class:`ScenarioError` naming the
file, the field and the limit, including the time-step limit that the pad springs impose.
"""
from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field, fields, replace
from importlib import resources
from pathlib import Path

from frictionnoise import G

from .substrates import KINDS as SUBSTRATES, SubstrateSpec
from .substrates.patches import PatchesSpec
from .wear import WearSpec, check_wear

__all__ = ["ScenarioError", "Scenario", "BlockSpec", "PadSpec", "FrictionSpec", "SubstrateSpec", "DriveSpec",
           "WearSpec", "RunSpec", "load_scenario", "scenario_from_dict", "shipped_scenarios", "resolve_scenario",
           "scenario_summary", "SCENARIO_DIR"]

# the shipped scenarios are package data of the ``scenarios`` package (installed with every install, not found
# relative to a source tree); a regular (non-zipped) install gives a real folder
SCENARIO_DIR = Path(str(resources.files("scenarios")))

# Explicit spring forces are accurate for omega dt < 0.3 (DESIGN.md, measured on pymunk 7.3).
SPRING_OMEGA_DT = 0.3
# Spring damping is exact-exponential but its effect is slowed by x/(e^x - 1), x = c dt / m: keep x < 0.1.
SPRING_DAMPING_X = 0.1


class ScenarioError(ValueError):
    """An invalid scenario: the message names the file (if any), the field and what is wrong."""


@dataclass(frozen=True)
class BlockSpec:
    """The sliding block. M: mass (kg)."""

    M: float = 0.1


@dataclass(frozen=True)
class PadSpec:
    """Spring-mounted pads (asperity contact regions), one per substrate track.

    N: number of pads; mass (kg); radius (m); k0: tangential spring to the block (N/m); c0: its damping
    (N s/m); k_normal: normal spring (N/m), pre-compressed to carry M g cos(theta) / N; k1: lateral spring
    between neighbouring pads (N/m, free ends); c1: its damping (N s/m); track_spacing: offset of the tracks
    in y (m), which keeps each pad's broad phase to its own track; c_normal: damping of the normal spring
    (N s/m).

    On an "asperities" substrate the pads are the elastic sole of a flat block instead: N flat feet of length
    foot_length (m, ends rounded with ``radius``) side by side along one shared track, so the block's
    contact width is w = N foot_length; the normal springs are not pre-compressed and the block is free
    vertically, so its weight is shared by whichever feet stand on asperities (load redistribution).
    """

    N: int = 30
    mass: float = 1e-3
    radius: float = 0.3e-3
    k0: float = 3333.0
    c0: float = 0.0
    k_normal: float = 833.0
    k1: float = 0.0
    c1: float = 0.0
    track_spacing: float = 5e-3
    c_normal: float = 0.0
    foot_length: float = 1e-3


@dataclass(frozen=True)
class FrictionSpec:
    """Pad-substrate friction, velocity strengthening, per pad under load N_pad:

    law "linear": f = mu N_pad + c v (model I's f_kin + m eta1 v), c > 0 in N s/m;
    law "log": f = N_pad (mu + b ln(1 + v / v_c)) + c v, the rate-strengthening law of rubber and
    polymers (mu rises by b per e-fold of speed above v_c; c >= 0 optional).

    mu is the local patch value (see SubstrateSpec). The Coulomb part is solved by pymunk; the velocity
    part is a drag: linear as an exactly corrected damper, logarithmic as a force computed once per step
    from the pads' velocities (pymunk.batch), which is stable only for b N_pad dt / (v_c m_pad) < 0.5
    (the explicit-update limit; checked at load).
    """

    law: str = "linear"
    mu0: float = 0.6
    c: float = 10.0
    b: float = 0.0
    v_c: float = 1e-3


@dataclass(frozen=True)
class DriveSpec:
    """How the block is driven.

    kind "force": constant force; "tilted": the same force from gravity on a slope, F = M g sin(theta) with
    the pad load M g cos(theta); "velocity": the block is pulled at constant speed v through a spring of
    stiffness k_drive (N/m); "leonardo": Leonardo da Vinci's slider (paper Fig. 7), a hanging mass
    ``hanging_mass`` (kg) pulls the block through a rope over an ideal pulley, F = m_h g, the rope a
    slack-capable joint of length ``rope_length`` (m). ``force`` (N): if unset (and for "leonardo" if
    ``hanging_mass`` is unset), chosen so the friction law slides the block at ``v`` (m/s):
    F = N f(v). ``theta`` (rad) for "tilted".
    """

    kind: str = "force"
    v: float = 5e-3
    force: float | None = None
    theta: float | None = None
    k_drive: float = 1e3
    hanging_mass: float | None = None
    rope_length: float = 0.2


@dataclass(frozen=True)
class RunSpec:
    """dt: pymunk step (s); dt_out: output step (s), a multiple of dt; duration and warmup (s, the warm-up is
    simulated and discarded); iterations: pymunk solver iterations; seed."""

    dt: float = 1e-4
    dt_out: float = 1e-3
    duration: float = 60.0
    warmup: float = 1.0
    iterations: int = 10
    seed: int = 0


@dataclass(frozen=True)
class Scenario:
    name: str = "unnamed"
    description: str = ""
    block: BlockSpec = field(default_factory=BlockSpec)
    pads: PadSpec = field(default_factory=PadSpec)
    friction: FrictionSpec = field(default_factory=FrictionSpec)
    substrate: SubstrateSpec = field(default_factory=PatchesSpec)  # the kind's own spec (engine_sim/substrates/)
    drive: DriveSpec = field(default_factory=DriveSpec)
    wear: WearSpec = field(default_factory=WearSpec)
    run: RunSpec = field(default_factory=RunSpec)

    # ------------------------------------------------------------------ derived quantities (SI)
    @property
    def normal_load_per_pad(self) -> float:
        """Block weight share (times cos theta on a slope) plus the pad's weight (N)."""
        cos_t = math.cos(self.drive.theta) if self.drive.kind == "tilted" and self.drive.theta else 1.0
        return self.block.M * G * cos_t / self.pads.N + self.pads.mass * G

    def law_force(self, v: float) -> float:
        """The friction law's steady force per pad at sliding speed v >= 0 (N), with mu = mu0."""
        fr, Np = self.friction, self.normal_load_per_pad
        f = fr.mu0 * Np + fr.c * v
        if fr.law == "log":
            f += fr.b * Np * math.log1p(v / fr.v_c)
        return f

    def friction_slope(self, v: float) -> float:
        """dF/dv of the law per pad at speed v (N s/m): c, plus b N_pad / (v_c + v) for the log law."""
        fr = self.friction
        extra = fr.b * self.normal_load_per_pad / (fr.v_c + v) if fr.law == "log" else 0.0
        return fr.c + extra

    @property
    def drive_force(self) -> float:
        """The constant drive force (N)."""
        d = self.drive
        if d.kind == "tilted":
            return self.block.M * G * math.sin(d.theta)
        if d.kind == "leonardo" and d.hanging_mass is not None:
            return d.hanging_mass * G
        if d.force is not None:
            return d.force
        return self.pads.N * self.law_force(d.v)

    @property
    def hanging_mass(self) -> float:
        """Leonardo's slider: the hanging mass (kg) whose weight is the drive."""
        d = self.drive
        return d.hanging_mass if d.hanging_mass is not None else self.drive_force / G

    @property
    def steady_velocity(self) -> float:
        """The friction law's steady speed under the drive, N f(v) = F (m/s); <= 0 if F does not exceed the
        kinetic friction."""
        if self.drive.kind == "velocity":
            return self.drive.v
        target = self.drive_force / self.pads.N
        f0 = self.law_force(0.0)
        if target <= f0:
            return (target - f0) / max(self.friction_slope(0.0), 1e-300)
        hi = 1e-6
        while self.law_force(hi) < target:
            hi *= 2.0
            if hi > 1e6:
                return math.inf
        lo = 0.0
        for _ in range(200):  # bisection: f is increasing; 200 halvings reach double precision
            mid = 0.5 * (lo + hi)
            if self.law_force(mid) < target:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    @property
    def dt_limit(self) -> float:
        """Largest stable and accurate step: omega dt < 0.3 for the stiffest pad spring, and the spring
        damping c0 dt / m < 0.1 (s)."""
        p = self.pads
        k = p.k0 + p.k_normal + 4 * p.k1
        lim = SPRING_OMEGA_DT / math.sqrt(k / p.mass)
        c = p.c0 + p.c_normal + 2 * p.c1
        if c > 0:
            lim = min(lim, SPRING_DAMPING_X * p.mass / c)
        return lim

    def with_run(self, **kw) -> "Scenario":
        return replace(self, run=replace(self.run, **kw))

    def with_wear(self, **kw) -> "Scenario":
        """A copy with [wear] fields replaced, e.g. ``with_wear(count=0)`` for the particle-free twin of a paired run."""
        return replace(self, wear=replace(self.wear, **kw))

    def to_dict(self) -> dict:
        out = {"name": self.name, "description": self.description}
        for sec in _SECTIONS:
            obj = getattr(self, sec)
            out[sec] = {f.name: getattr(obj, f.name) for f in fields(obj)}
        return out


_SECTIONS = {"block": BlockSpec, "pads": PadSpec, "friction": FrictionSpec, "substrate": SubstrateSpec,
             "drive": DriveSpec, "wear": WearSpec, "run": RunSpec}
_CHOICES = {("friction", "law"): ("linear", "log"),
            ("drive", "kind"): ("force", "tilted", "velocity", "leonardo"),
            ("wear", "distribution"): ("lognormal", "power"), ("wear", "rotation"): ("locked", "free")}
_POSITIVE = {("block", "M"), ("pads", "N"), ("pads", "mass"), ("pads", "radius"), ("pads", "k0"),
             ("pads", "k_normal"), ("pads", "track_spacing"), ("friction", "v_c"), ("pads", "foot_length"), ("drive", "v"), ("drive", "k_drive"), ("drive", "hanging_mass"),
             ("drive", "rope_length"), ("run", "dt"), ("run", "dt_out"),
             ("run", "duration"), ("run", "iterations"),
             ("wear", "r_min"), ("wear", "r_max"), ("wear", "r_median"), ("wear", "sigma"), ("wear", "density"),
             ("wear", "trapped_speed"), ("wear", "ahead"), ("wear", "behind")}
_NON_NEGATIVE = {("pads", "c0"), ("pads", "k1"), ("pads", "c1"), ("pads", "c_normal"), ("friction", "mu0"), ("friction", "c"), ("friction", "b"),
                 ("run", "warmup"), ("run", "seed"), ("wear", "count"), ("wear", "exponent"), ("wear", "min_mass"), ("wear", "mu_track"), ("wear", "mu_pad")}


def _err(where: str, msg: str) -> ScenarioError:
    return ScenarioError(f"{where}: {msg}" if where else msg)


def _rules(sec, spec_cls=None):
    """(positive, non-negative, choices) for a section's fields; a substrate kind declares its own."""
    if sec == "substrate":
        part = next(k for k in SUBSTRATES.values() if k.Spec is spec_cls)
        return part.positive, part.non_negative, {**part.choices, "kind": tuple(SUBSTRATES)}
    pick = lambda table: {k for s, k in table if s == sec}  # noqa: E731
    return pick(_POSITIVE), pick(_NON_NEGATIVE), {k: v for (s, k), v in _CHOICES.items() if s == sec}


def _check_value(where, name, ftype, val, positive=False, non_negative=False, choices=None):
    is_int = "int" in str(ftype) and "float" not in str(ftype)
    if "str" in str(ftype):
        if not isinstance(val, str):
            raise _err(where, f"{name} must be a string (got {type(val).__name__} {val!r})")
        if choices and val not in choices:
            raise _err(where, f"{name} = {val!r} is not one of: {', '.join(choices)}")
        return val
    if val is None and "None" in str(ftype):
        return None
    if isinstance(val, bool) or not isinstance(val, (int, float)):
        raise _err(where, f"{name} must be a number (got {type(val).__name__} {val!r})")
    if is_int and not float(val).is_integer():
        raise _err(where, f"{name} must be an integer (got {val!r})")
    if not math.isfinite(val):
        raise _err(where, f"{name} must be finite (got {val!r})")
    if positive and not val > 0:
        raise _err(where, f"{name} must be > 0 (got {val!r})")
    if non_negative and val < 0:
        raise _err(where, f"{name} must be >= 0 (got {val!r})")
    return int(val) if is_int else float(val)


def _section(where, sec, cls, raw, strict=True):
    if sec == "substrate":  # the kind names the spec class
        kind = _check_value(where, "substrate.kind", str, raw.get("kind", "patches"), choices=tuple(SUBSTRATES))
        cls = SUBSTRATES[kind].Spec
        if not strict:  # traces written before issue 14 list every kind's substrate fields
            other = {f.name for k in SUBSTRATES.values() for f in fields(k.Spec)}
            raw = {k: v for k, v in raw.items() if k in {f.name for f in fields(cls)} or k not in other}
    valid = {f.name: f.type for f in fields(cls)}
    bad = sorted(set(raw) - set(valid))
    if bad:
        raise _err(where, f"unknown key {sec}.{bad[0]}; valid keys in [{sec}]: {', '.join(valid)}")
    pos, nonneg, choices = _rules(sec, cls)
    spec = cls(**{k: _check_value(where, f"{sec}.{k}", valid[k], v, k in pos, k in nonneg, choices.get(k))
                  for k, v in raw.items()})
    if sec == "substrate":
        try:
            spec = SUBSTRATES[spec.kind].prepare(spec, where)
        except ValueError as e:
            raise _err(where, str(e)) from None
    return spec


def scenario_from_dict(data: dict, where: str = "", strict: bool = True) -> Scenario:
    """Build and validate a Scenario from a TOML-like dict (SI units). ``strict=False`` (a trace's metadata) ignores
    substrate fields that belong to other substrate kinds, as written by versions before issue 14."""
    if not isinstance(data, dict):
        raise _err(where, "a scenario must be a table of sections")
    top_keys = {"name", "description", *_SECTIONS}
    unknown = sorted(set(data) - top_keys)
    if unknown:
        raise _err(where, f"unknown key {unknown[0]!r}; valid top-level keys: {', '.join(sorted(top_keys))}")
    parts = {}
    for sec, cls in _SECTIONS.items():
        raw = data.get(sec, {})
        if not isinstance(raw, dict):
            raise _err(where, f"[{sec}] must be a table (got {type(raw).__name__})")
        parts[sec] = _section(where, sec, cls, raw, strict)
    for key in ("name", "description"):
        if key in data and not isinstance(data[key], str):
            raise _err(where, f"{key} must be a string (got {type(data[key]).__name__})")
    sc = Scenario(name=data.get("name", "unnamed"), description=data.get("description", ""), **parts)
    _check_consistency(sc, where)
    return sc


def _check_consistency(sc: Scenario, where: str):
    r, p = sc.run, sc.pads
    if r.dt > sc.dt_limit:
        raise _err(where, f"run.dt = {r.dt:.3g} s exceeds the pad spring limit {sc.dt_limit:.3g} s "
                          f"(omega dt < {SPRING_OMEGA_DT} for k0 + k_normal + 4 k1 on the pad mass)")
    ratio = r.dt_out / r.dt
    if abs(ratio - round(ratio)) > 1e-9 * ratio or round(ratio) < 1:
        raise _err(where, f"run.dt_out = {r.dt_out:.6g} s must be a whole multiple of run.dt = {r.dt:.6g} s")
    if r.duration < 8 * r.dt_out:
        raise _err(where, f"run.duration = {r.duration:.3g} s is shorter than 8 output steps")
    if p.N > 32 and p.track_spacing < 4 * p.radius:
        raise _err(where, f"pads.track_spacing = {p.track_spacing:.3g} m must exceed 4 pad radii when N > 32")
    if p.track_spacing < 2.5 * (p.radius + sc.substrate.segment_radius):
        raise _err(where, f"pads.track_spacing = {p.track_spacing:.3g} m must exceed 2.5 (pad + segment radius) "
                          f"= {2.5 * (p.radius + sc.substrate.segment_radius):.3g} m")
    if sc.drive.kind == "tilted":
        if sc.drive.theta is None or not 0 < sc.drive.theta < math.pi / 2:
            raise _err(where, f"drive.theta must lie in (0, pi/2) rad for a tilted plane (got {sc.drive.theta!r})")
    fr = sc.friction
    if fr.law == "linear" and not fr.c > 0:
        raise _err(where, f"friction.c must be > 0 for the linear law (got {fr.c!r}): without velocity "
                          "strengthening the block has no steady sliding speed")
    if fr.law == "log":
        if not (fr.b > 0 or fr.c > 0):
            raise _err(where, "friction.b must be > 0 for the log law (or friction.c > 0)")
        x = fr.b * sc.normal_load_per_pad * r.dt / (fr.v_c * p.mass)
        if x > 0.5:
            v_min = fr.b * sc.normal_load_per_pad * r.dt / (0.5 * p.mass)
            raise _err(where, f"friction.v_c = {fr.v_c:.3g} m/s is below the explicit-update limit {v_min:.3g} m/s "
                              f"(b N_pad dt / (v_c m_pad) = {x:.3g} must be < 0.5, or the pads chatter)")
    if sc.drive.kind in ("force", "tilted", "leonardo"):
        v = sc.steady_velocity
        if not v > 0:
            raise _err(where, f"drive force {sc.drive_force:.4g} N does not exceed the kinetic friction "
                              f"{p.N * sc.friction.mu0 * sc.normal_load_per_pad:.4g} N: the block would not slide")
    sub = sc.substrate
    try:
        SUBSTRATES[sub.kind].validate(sub, sc, where)
    except ValueError as e:
        raise _err(where, str(e)) from None
    if sc.wear.count > 0:
        if not SUBSTRATES[sub.kind].hosts_wear:
            raise _err(where, f"wear particles need flat pad tracks (substrate.kind 'patches'; got {sub.kind!r})")
        try:
            check_wear(sc)
        except ValueError as e:
            raise _err(where, str(e)) from None


def resolve_scenario(name_or_path) -> Path:
    """The file of a scenario given as a path or as the name of a shipped one (``pads_friction_patches``, with
    or without ``.toml``): an existing path wins over a shipped name of the same spelling."""
    path = Path(name_or_path)
    if path.exists():
        return path
    shipped = shipped_scenarios()
    stem = path.name[:-5] if path.name.endswith(".toml") else path.name
    if path.parent == Path(".") and stem in shipped:
        return shipped[stem]
    raise ScenarioError(f"{path}: no such file, nor a shipped scenario (frictionnoise scenarios lists them: "
                        f"{', '.join(shipped)})")


def load_scenario(path) -> Scenario:
    """Read and validate a TOML scenario file, given as a path or a shipped scenario's name."""
    path = resolve_scenario(path)
    try:
        data = tomllib.loads(path.read_text())
    except UnicodeDecodeError:
        raise ScenarioError(f"{path}: not a text file") from None
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(f"{path}: not valid TOML ({e})") from None
    return scenario_from_dict(data, where=str(path))


def shipped_scenarios() -> dict:
    """name -> path of the scenarios shipped in the ``scenarios`` package."""
    return {p.stem: p for p in sorted(SCENARIO_DIR.glob("*.toml"))}


def scenario_summary(description: str, width: int = 110) -> str:
    """The first sentence of a scenario's description on one line, cut to ``width`` characters."""
    text = " ".join(description.split())
    end = re.search(r"(?<!Fig)(?<!eq)(?<!e\.g)\. (?=[A-Z(])", text)  # a sentence end, not an abbreviation
    first = text if end is None else text[: end.start() + 1]
    return first if len(first) <= width else first[: width - 3].rstrip() + "..."
