"""Scenarios: frozen SI parameter sets for the engine scene, loaded from TOML and validated once.

A scenario file has a top-level ``name`` and ``description`` and the sections ``[block]``, ``[pads]``,
``[friction]``, ``[substrate]``, ``[drive]`` and ``[run]``; every key is optional (defaults below, SI units).
Unknown sections or keys, wrong types and out-of-range values raise :class:`ScenarioError` naming the
file, the field and the limit, including the time-step limit that the pad springs impose.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

__all__ = ["ScenarioError", "Scenario", "BlockSpec", "PadSpec", "FrictionSpec", "SubstrateSpec", "DriveSpec",
           "RunSpec", "load_scenario", "scenario_from_dict", "shipped_scenarios", "SCENARIO_DIR"]

SCENARIO_DIR = Path(__file__).resolve().parent.parent / "scenarios"
G = 9.81  # m/s^2

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
    in y (m), which keeps each pad's broad phase to its own track.
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


@dataclass(frozen=True)
class FrictionSpec:
    """Pad-substrate friction, linear velocity strengthening: f = mu N_pad + c v_pad (model I's
    f_kin + m eta1 v). mu is the local patch value (see SubstrateSpec); c in N s/m per pad."""

    law: str = "linear"
    mu0: float = 0.6
    c: float = 10.0


@dataclass(frozen=True)
class SubstrateSpec:
    """One independent track per pad.

    kind "patches": a flat track of friction patches; patch boundaries at (j + r_j) a (so renewal
    intervals follow model I's tau0 (1 + r - r')), each patch with mu = mu0 (1 + alpha (r - 1/2)).
    kind "self_affine": a randomly rough profile by Fourier synthesis (streamed FIR filtering of white
    noise): Hurst exponent ``hurst``, roll-off wavelength ``lambda_r`` (flat spectrum above it), short
    cut-off ``lambda_s``, rms slope ``rms_slope``, grid spacing lambda_s / 4; friction mu0 everywhere.
    ``a`` is then the renewal length used for the fit band (default: lambda_r).
    """

    kind: str = "patches"
    a: float = 1e-3
    alpha: float = 1.0
    segment_radius: float = 0.05e-3
    hurst: float = 0.8
    lambda_r: float = 2e-3
    lambda_s: float = 0.1e-3
    rms_slope: float = 0.1


@dataclass(frozen=True)
class DriveSpec:
    """How the block is driven.

    kind "force": constant force; "tilted": the same force from gravity on a slope, F = M g sin(theta) with
    the pad load M g cos(theta); "velocity": the block is pulled at constant speed v through a spring of
    stiffness k_drive (N/m). ``force`` (N): if unset, chosen so the friction law slides the block at ``v``
    (m/s): F = N (mu0 N_pad + c v). ``theta`` (rad) for "tilted".
    """

    kind: str = "force"
    v: float = 5e-3
    force: float | None = None
    theta: float | None = None
    k_drive: float = 1e3


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
    substrate: SubstrateSpec = field(default_factory=SubstrateSpec)
    drive: DriveSpec = field(default_factory=DriveSpec)
    run: RunSpec = field(default_factory=RunSpec)

    # ------------------------------------------------------------------ derived quantities (SI)
    @property
    def normal_load_per_pad(self) -> float:
        """Block weight share (times cos theta on a slope) plus the pad's weight (N)."""
        cos_t = math.cos(self.drive.theta) if self.drive.kind == "tilted" and self.drive.theta else 1.0
        return self.block.M * G * cos_t / self.pads.N + self.pads.mass * G

    @property
    def drive_force(self) -> float:
        """The constant drive force (N)."""
        if self.drive.kind == "tilted":
            return self.block.M * G * math.sin(self.drive.theta)
        if self.drive.force is not None:
            return self.drive.force
        return self.pads.N * (self.friction.mu0 * self.normal_load_per_pad + self.friction.c * self.drive.v)

    @property
    def steady_velocity(self) -> float:
        """The friction law's steady speed under the drive: F / N = mu0 N_pad + c v (m/s)."""
        if self.drive.kind == "velocity":
            return self.drive.v
        return (self.drive_force / self.pads.N - self.friction.mu0 * self.normal_load_per_pad) / self.friction.c

    @property
    def dt_limit(self) -> float:
        """Largest stable and accurate step: omega dt < 0.3 for the stiffest pad spring, and the spring
        damping c0 dt / m < 0.1 (s)."""
        p = self.pads
        k = p.k0 + p.k_normal + 4 * p.k1
        lim = SPRING_OMEGA_DT / math.sqrt(k / p.mass)
        c = p.c0 + 2 * p.c1
        if c > 0:
            lim = min(lim, SPRING_DAMPING_X * p.mass / c)
        return lim

    def with_run(self, **kw) -> "Scenario":
        return replace(self, run=replace(self.run, **kw))

    def to_dict(self) -> dict:
        out = {"name": self.name, "description": self.description}
        for sec in _SECTIONS:
            obj = getattr(self, sec)
            out[sec] = {f.name: getattr(obj, f.name) for f in fields(obj)}
        return out


_SECTIONS = {"block": BlockSpec, "pads": PadSpec, "friction": FrictionSpec, "substrate": SubstrateSpec,
             "drive": DriveSpec, "run": RunSpec}
_CHOICES = {("friction", "law"): ("linear",), ("substrate", "kind"): ("patches", "self_affine"),
            ("drive", "kind"): ("force", "tilted", "velocity")}
_POSITIVE = {("block", "M"), ("pads", "N"), ("pads", "mass"), ("pads", "radius"), ("pads", "k0"),
             ("pads", "k_normal"), ("pads", "track_spacing"), ("friction", "c"), ("substrate", "a"),
             ("substrate", "segment_radius"), ("substrate", "lambda_r"), ("substrate", "lambda_s"),
             ("substrate", "rms_slope"), ("drive", "v"), ("drive", "k_drive"), ("run", "dt"), ("run", "dt_out"),
             ("run", "duration"), ("run", "iterations")}
_NON_NEGATIVE = {("pads", "c0"), ("pads", "k1"), ("pads", "c1"), ("friction", "mu0"), ("substrate", "alpha"),
                 ("run", "warmup"), ("run", "seed")}


def _err(where: str, msg: str) -> ScenarioError:
    return ScenarioError(f"{where}: {msg}" if where else msg)


def _check_value(where, sec, key, ftype, val):
    name = f"{sec}.{key}"
    is_int = "int" in str(ftype) and "float" not in str(ftype)
    if "str" in str(ftype):
        if not isinstance(val, str):
            raise _err(where, f"{name} must be a string (got {type(val).__name__} {val!r})")
        choices = _CHOICES.get((sec, key))
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
    if (sec, key) in _POSITIVE and not val > 0:
        raise _err(where, f"{name} must be > 0 (got {val!r})")
    if (sec, key) in _NON_NEGATIVE and val < 0:
        raise _err(where, f"{name} must be >= 0 (got {val!r})")
    return int(val) if is_int else float(val)


def scenario_from_dict(data: dict, where: str = "") -> Scenario:
    """Build and validate a Scenario from a TOML-like dict (SI units)."""
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
        valid = {f.name: f.type for f in fields(cls)}
        bad = sorted(set(raw) - set(valid))
        if bad:
            raise _err(where, f"unknown key {sec}.{bad[0]}; valid keys in [{sec}]: {', '.join(valid)}")
        parts[sec] = cls(**{k: _check_value(where, sec, k, valid[k], v) for k, v in raw.items()})
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
    if sc.drive.kind in ("force", "tilted"):
        v = sc.steady_velocity
        if not v > 0:
            raise _err(where, f"drive force {sc.drive_force:.4g} N does not exceed the kinetic friction "
                              f"{p.N * sc.friction.mu0 * sc.normal_load_per_pad:.4g} N: the block would not slide")
    sub = sc.substrate
    if sub.kind == "self_affine":
        if not 0 < sub.hurst < 1:
            raise _err(where, f"substrate.hurst must lie in (0, 1) (got {sub.hurst!r})")
        if not sub.lambda_s < sub.lambda_r:
            raise _err(where, f"substrate.lambda_s = {sub.lambda_s!r} m must be shorter than lambda_r = {sub.lambda_r!r} m")
        limit = 1.0 / (6.0 * max(sc.friction.mu0, 1e-9))
        if sub.rms_slope > limit:
            raise _err(where, f"substrate.rms_slope = {sub.rms_slope!r} exceeds the sliding limit {limit:.3g} = 1/(6 mu0): "
                              "the steepest flanks (~4 rms slopes) near the locking slope 1/mu0 pin the pads "
                              "(measured on pads_rough_profile: rms slope 0.4 pins the block, 0.3 slides unsteadily)")
    if sc.substrate.alpha >= 2:
        raise _err(where, f"substrate.alpha = {sc.substrate.alpha!r} must be < 2 (patch friction stays positive)")


def load_scenario(path) -> Scenario:
    """Read and validate a TOML scenario file."""
    path = Path(path)
    if not path.exists():
        raise ScenarioError(f"{path}: no such file")
    try:
        data = tomllib.loads(path.read_text())
    except UnicodeDecodeError:
        raise ScenarioError(f"{path}: not a text file") from None
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(f"{path}: not valid TOML ({e})") from None
    return scenario_from_dict(data, where=str(path))


def shipped_scenarios() -> dict:
    """name -> path of the scenarios shipped in scenarios/."""
    return {p.stem: p for p in sorted(SCENARIO_DIR.glob("*.toml"))}
