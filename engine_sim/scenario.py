"""Scenarios: frozen SI parameter sets for the engine scene, loaded from TOML and validated once.

A scenario file has a top-level ``name`` and ``description`` (and optionally ``plugins``, a user's parts to load
first, :mod:`engine_sim.plugins`, and ``channels``, extra channels to record, :mod:`engine_sim.channels`) and the
sections ``[block]``, ``[pads]``, ``[friction]``, ``[substrate]``, ``[drive]``, ``[wear]`` and ``[run]``; every key
is optional (defaults below, SI units).
Unknown sections or keys, wrong types and out-of-range values raise :class:`ScenarioError` naming the
file, the field and the limit, including the time-step limit that the pad springs impose and the regimes of the
scene (:mod:`engine_sim.regime`: what its springs' lengths and pymunk's solver can carry).
"""
from __future__ import annotations

import pickle
from dataclasses import dataclass, field, fields, replace
from functools import cached_property
from pathlib import Path

from frictionnoise.base import G, InputError, check_number, read_toml

from .arrangements import ARRANGEMENTS, SPRING_DAMPING_X, SPRING_OMEGA_DT, PadSpec  # noqa: F401
from .channels import CHANNELS
from .drives import DRIVES, DriveSpec
from .drives.force import ForceSpec
from .laws import LAWS, FrictionSpec
from .plugins import load_plugins
from .regime import check_regimes
from .shipped import (SCENARIO_DIR, ScenarioError, nearest_names, resolve_scenario, scenario_summary,  # noqa: F401
                      shipped_file, shipped_scenarios)
from .substrates import SUBSTRATES, SubstrateSpec
from .substrates.patches import PatchesSpec
from .vibration import Vibration, VibrationSpec
from .wear import WearSpec, wear_part

__all__ = ["ScenarioError", "Scenario", "BlockSpec", "PadSpec", "FrictionSpec", "SubstrateSpec", "DriveSpec",
           "WearSpec", "RunSpec", "load_scenario", "scenario_from_dict", "shipped_scenarios", "resolve_scenario",
           "shipped_file", "nearest_names", "scenario_summary", "SCENARIO_DIR"]


@dataclass(frozen=True)
class BlockSpec:
    """The sliding block. M: mass (kg)."""

    M: float = 0.1


@dataclass(frozen=True)
class RunSpec:
    """dt: pymunk step (s); dt_out: output step (s), a multiple of dt; duration and warmup (s, the warm-up is
    simulated and discarded); iterations: pymunk solver iterations; seed; forces: "mean" (each recorded force is its
    mean over the output step, as a force sensor behind an anti-alias filter reports it) or "point" (the contact
    forces of the last pymunk step before each sample: point samples, which alias; the reference a study of that
    needs, recorded at every step)."""

    dt: float = 1e-4
    dt_out: float = 1e-3
    duration: float = 60.0
    warmup: float = 1.0
    iterations: int = 10
    seed: int = 0
    forces: str = "mean"


@dataclass(frozen=True)
class Scenario:
    name: str = "unnamed"
    description: str = ""
    block: BlockSpec = field(default_factory=BlockSpec)
    pads: PadSpec = field(default_factory=PadSpec)  # the arrangement's own spec (engine_sim/arrangements/)
    friction: FrictionSpec = field(default_factory=FrictionSpec)  # the law's own spec (engine_sim/laws/)
    substrate: SubstrateSpec = field(default_factory=PatchesSpec)  # the kind's own spec (engine_sim/substrates/)
    drive: DriveSpec = field(default_factory=ForceSpec)  # the drive's own spec (engine_sim/drives/)
    wear: WearSpec = field(default_factory=WearSpec)
    run: RunSpec = field(default_factory=RunSpec)
    vibration: VibrationSpec | None = None  # [vibration] (engine_sim/vibration.py); None: the section is absent
    plugins: tuple = ()  # a user's part modules, resolved (engine_sim/plugins.py), loaded before the sections are read
    channels: tuple = ()  # extra recorded channels by name (engine_sim/channels.py)

    # ------------------------------------------------------------------ the parts (engine_sim/*/): each asked, none checked
    # Each is built once per scenario, on first use, and answers the scenario's derived quantities; a scene builds
    # its own (:meth:`fresh_parts`), since parts keep state while a scene steps (a law's impulse totals, a drive's
    # bodies).
    @cached_property
    def drive_part(self):
        return _PARTS["drive"](self)

    @cached_property
    def law_part(self):
        return _PARTS["law"](self)

    @cached_property
    def arrangement_part(self):
        return _PARTS["arrangement"](self)

    @cached_property
    def substrate_part(self):
        return _PARTS["substrate"](self)

    @cached_property
    def vibration_part(self):
        return _PARTS["vibration"](self)

    @cached_property
    def wear_part(self):
        return _PARTS["wear"](self)

    def fresh_parts(self) -> dict:
        """New part objects for a scene, none of them the scenario's own.

        Returns
        -------
        dict
            Family (``"substrate"``, ``"arrangement"``, ``"law"``, ``"drive"``, ``"wear"``, ``"vibration"``) -> its
            part object (``"vibration"``: None without a ``[vibration]`` section).
        """
        return {family: make(self) for family, make in _PARTS.items()}

    def __getstate__(self):
        """The fields only: the parts built on first use are rebuilt after unpickling (a scene pickles its own)."""
        return {k: v for k, v in self.__dict__.items() if k not in _PARTS_ATTRS}

    def __reduce_ex__(self, protocol):
        """A scenario with plugins pickles its fields as bytes behind its plugins, so a process that unpickles it
        (a spawned worker) loads the plugins before it meets their specs."""
        if not self.plugins:
            return super().__reduce_ex__(protocol)
        return _with_plugins, (self.plugins, pickle.dumps(self.__getstate__(), protocol))

    # ------------------------------------------------------------------ derived quantities (SI)
    @property
    def normal_load_per_pad(self) -> float:
        """Block weight share (times cos theta on a slope) plus the weight of a pad column (N)."""
        return self.block.M * G * self.drive_part.load_factor() / self.pads.N + self.arrangement_part.column_mass * G

    def law_force(self, v: float) -> float:
        """The friction law's steady force per pad at a sliding speed, with mu = mu0.

        Parameters
        ----------
        v : float
            Sliding speed (Units: m/s), >= 0.

        Returns
        -------
        float
            The force (Units: N).
        """
        return self.law_part.force(v, self.normal_load_per_pad, self.friction.c)

    def column_force(self, v: float) -> float:
        """Steady friction of one pad column (a pad and what it carries) at a sliding speed.

        Parameters
        ----------
        v : float
            Sliding speed (Units: m/s), >= 0.

        Returns
        -------
        float
            The force (Units: N).
        """
        return self.arrangement_part.column_force(v)

    def friction_slope(self, v: float) -> float:
        """dF/dv of one pad column: c, plus b N_pad / (v_c + v) for the log law.

        Parameters
        ----------
        v : float
            Sliding speed (Units: m/s), >= 0.

        Returns
        -------
        float
            The slope (Units: N s/m).
        """
        return self.arrangement_part.column_slope(v)

    @property
    def drive_force(self) -> float:
        """The drive force (N); for a velocity drive the law's steady force at its speed."""
        return self.drive_part.force()

    @property
    def hanging_mass(self) -> float:
        """Mass the drive moves with the block (kg; Leonardo's slider: the hanging mass whose weight drives)."""
        return self.drive_part.extra_mass

    @property
    def steady_velocity(self) -> float:
        """The friction law's steady speed under the drive, N f(v) = F (m/s); <= 0 if F does not exceed the
        law's force as sliding starts, N f(0)."""
        return self.drive_part.steady_velocity()

    @property
    def dt_limit(self) -> float:
        """Largest stable and accurate step (s), set by the arrangement's springs (omega dt < 0.3, c dt / m < 0.1)."""
        return self.arrangement_part.dt_limit()

    def with_run(self, **kw) -> "Scenario":
        """A copy with ``[run]`` fields replaced, e.g. ``with_run(duration=10.0)``.

        Parameters
        ----------
        **kw
            ``[run]`` fields and their new values (SI units).

        Returns
        -------
        Scenario
        """
        return replace(self, run=replace(self.run, **kw))

    def with_wear(self, **kw) -> "Scenario":
        """A copy with ``[wear]`` fields replaced, e.g. ``with_wear(count=0)`` for the particle-free twin of a paired run.

        Parameters
        ----------
        **kw
            ``[wear]`` fields and their new values (SI units).

        Returns
        -------
        Scenario
        """
        return replace(self, wear=replace(self.wear, **kw))

    def to_dict(self) -> dict:
        """The scenario as a TOML-like dict (what :func:`scenario_from_dict` reads back).

        Returns
        -------
        dict
            ``name``, ``description`` and one dict per section, values in SI units.
        """
        out = {"name": self.name, "description": self.description}
        for sec in _SECTIONS:
            obj = getattr(self, sec)
            if obj is None:  # an optional section left out ([vibration])
                continue
            out[sec] = {f.name: getattr(obj, f.name) for f in fields(obj)}
        for key in ("plugins", "channels"):  # written only when given (a trace's metadata lists them then)
            if getattr(self, key):
                out[key] = list(getattr(self, key))
        return out


def _with_plugins(plugins, state: bytes) -> Scenario:
    """A scenario unpickled after its plugins are loaded (:meth:`Scenario.__reduce_ex__`)."""
    load_plugins(plugins)
    sc = object.__new__(Scenario)
    sc.__dict__.update(pickle.loads(state))
    return sc


# how each part family is built from its section (the section's kind names the class, engine_sim/*/)
_PARTS = {
    "substrate": lambda sc: SUBSTRATES[sc.substrate.kind](sc.substrate, sc),
    "arrangement": lambda sc: ARRANGEMENTS[sc.pads.arrangement](sc.pads, sc),
    "law": lambda sc: LAWS[sc.friction.law](sc.friction, sc),
    "drive": lambda sc: DRIVES[sc.drive.kind](sc.drive, sc),
    "wear": lambda sc: wear_part(sc.wear, sc),
    "vibration": lambda sc: None if sc.vibration is None else Vibration(sc.vibration, sc),
}
_PARTS_ATTRS = frozenset(f"{family}_part" for family in _PARTS)
_SECTIONS = {"block": BlockSpec, "pads": PadSpec, "friction": FrictionSpec, "substrate": SubstrateSpec,
             "drive": DriveSpec, "wear": WearSpec, "run": RunSpec, "vibration": VibrationSpec}
_OPTIONAL = {"vibration"}  # sections that are None when absent
_CHOICES = {("wear", "distribution"): ("lognormal", "power"), ("wear", "rotation"): ("locked", "free"),
            ("run", "forces"): ("mean", "point")}
_POSITIVE = {("block", "M"), ("run", "dt"), ("run", "dt_out"), ("run", "duration"), ("run", "iterations"),
             ("wear", "r_min"), ("wear", "r_max"), ("wear", "r_median"), ("wear", "sigma"), ("wear", "density"),
             ("wear", "trapped_speed"), ("wear", "ahead"), ("wear", "behind")}
_NON_NEGATIVE = {("run", "warmup"), ("run", "seed"), ("wear", "count"), ("wear", "exponent"), ("wear", "min_mass"),
                 ("wear", "mu_track"), ("wear", "mu_pad")}
# sections whose spec class is named by one of their keys: the part registry and that key (parsed in this order:
# the substrate names the default pad arrangement)
_KINDED = {"substrate": (SUBSTRATES, "kind"), "pads": (ARRANGEMENTS, "arrangement"), "friction": (LAWS, "law"),
           "drive": (DRIVES, "kind")}


def _err(where: str, msg: str) -> ScenarioError:
    return ScenarioError(f"{where}: {msg}" if where else msg)


def _rules(sec, spec_cls=None):
    """(positive, non-negative, choices) for a section's fields; a part kind declares its own."""
    if sec in _KINDED:
        registry, key = _KINDED[sec]
        part = next(k for k in registry.values() if k.Spec is spec_cls)
        return part.positive, part.non_negative, {**part.choices, key: tuple(registry)}
    if sec == "vibration":
        return Vibration.positive, Vibration.non_negative, Vibration.choices
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
    try:  # the one number check, shared with the reduced models' parameters (same rule, same message)
        val = check_number(name, val, positive=positive, non_negative=non_negative, integer=is_int)
    except ValueError as e:
        raise _err(where, str(e)) from None
    return val if is_int else float(val)


def _section(where, sec, cls, raw, strict=True, default=None):
    if sec in _KINDED:  # the kind names the spec class
        registry, key = _KINDED[sec]
        kind = _check_value(where, f"{sec}.{key}", str, raw.get(key, default or getattr(cls(), key)),
                            choices=tuple(registry))
        cls = registry[kind].Spec
        raw = {**raw, key: kind}
        if not strict:  # a trace's metadata may list fields of every kind: keep this kind's
            other = {f.name for k in registry.values() for f in fields(k.Spec)}
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
    """Build and validate a Scenario from a TOML-like dict (SI units).

    Parameters
    ----------
    data : dict
        The scenario's sections, as a TOML file reads (values in SI units).
    where : str, optional
        Where the data came from, for error messages (a file name).
    strict : bool, optional
        False (a trace's metadata) ignores substrate fields that belong to other substrate kinds (older traces
        list every kind's fields).

    Returns
    -------
    Scenario
        The validated scenario; :class:`ScenarioError` (one line naming the field) otherwise.
    """
    if not isinstance(data, dict):
        raise _err(where, "a scenario must be a table of sections")
    top_keys = {"name", "description", "plugins", "channels", *_SECTIONS}
    unknown = sorted(set(data) - top_keys)
    if unknown:
        raise _err(where, f"unknown key {unknown[0]!r}; valid top-level keys: {', '.join(sorted(top_keys))}")
    try:  # a user's parts register before the sections name them
        base = Path(where).parent if where and Path(where).is_file() else None
        plugins = load_plugins(data.get("plugins", []), base)
    except ValueError as e:
        raise _err(where, str(e)) from None
    channels = data.get("channels", [])
    if not isinstance(channels, list) or not all(isinstance(c, str) for c in channels):
        raise _err(where, f"channels must be a list of channel names (got {channels!r})")
    for c in channels:
        if c not in CHANNELS:
            raise _err(where, f"channels: {c!r} is not a registered channel (registered: "
                              f"{', '.join(CHANNELS) or 'none'}; name its module in plugins)")
    parts = {}
    for sec in sorted(_SECTIONS, key=lambda s: s != "substrate"):
        raw = data.get(sec, {})
        if not isinstance(raw, dict):
            raise _err(where, f"[{sec}] must be a table (got {type(raw).__name__})")
        if sec in _OPTIONAL and sec not in data:
            parts[sec] = None
            continue
        default = SUBSTRATES[parts["substrate"].kind].arrangement if sec == "pads" else None
        parts[sec] = _section(where, sec, _SECTIONS[sec], raw, strict, default)
    for key in ("name", "description"):
        if key in data and not isinstance(data[key], str):
            raise _err(where, f"{key} must be a string (got {type(data[key]).__name__})")
    sc = Scenario(name=data.get("name", "unnamed"), description=data.get("description", ""), **parts,
                  plugins=plugins, channels=tuple(channels))
    _check_consistency(sc, where)
    if strict:  # a trace's metadata is read as recorded, whatever regime it ran in
        try:
            check_regimes(sc)
        except ValueError as e:
            raise _err(where, str(e)) from None
    return sc


def _check_consistency(sc: Scenario, where: str):
    r = sc.run
    if r.dt > sc.dt_limit:
        raise _err(where, f"run.dt = {r.dt:.3g} s exceeds the pad spring limit {sc.dt_limit:.3g} s "
                          f"(omega dt < {SPRING_OMEGA_DT} for the stiffest pad spring on its mass)")
    ratio = r.dt_out / r.dt
    if abs(ratio - round(ratio)) > 1e-9 * ratio or round(ratio) < 1:
        raise _err(where, f"run.dt_out = {r.dt_out:.6g} s must be a whole multiple of run.dt = {r.dt:.6g} s")
    if r.duration < 8 * r.dt_out:
        raise _err(where, f"run.duration = {r.duration:.3g} s is shorter than 8 output steps")
    try:  # each part checks its own spec (one line naming the field)
        sc.arrangement_part.validate(sc.pads, sc)
        sc.law_part.validate(sc.friction, sc)
        sc.drive_part.validate(sc.drive, sc)
        sc.substrate_part.validate(sc.substrate, sc, where)
        sc.wear_part.validate(where)
        if sc.vibration is not None:
            Vibration.validate(sc.vibration, sc)
    except ValueError as e:
        raise _err(where, str(e)) from None


def load_scenario(path) -> Scenario:
    """Read and validate a TOML scenario file, given as a path or a shipped scenario's name: the one loader, which
    the command line and the Python API share.

    Parameters
    ----------
    path : str or pathlib.Path
        A scenario file, or the name of a shipped one (``"pads_friction_patches"``); an existing file wins
        (:func:`resolve_scenario`).

    Returns
    -------
    Scenario
        The validated scenario (SI units); :class:`ScenarioError` (one line naming the file and the problem)
        otherwise: no such file or name, a folder, an empty, binary, non-UTF-8 or invalid TOML file, one that holds
        no settings (only comments), or a field out of its range.
    """
    path = resolve_scenario(path)
    try:
        data = read_toml(path, "scenario TOML file")
    except InputError as e:
        raise ScenarioError(str(e)) from None
    return scenario_from_dict(data, where=str(path))
