"""Sweep files: a grid over model or scenario parameters and seeds, checked whole before any task runs.

Sweep file (TOML)::

    name = "velocity_model1"
    target = "model_I"            # a model of reduced_models.MODELS (model_I, model_Ib, ...) or scenario
    scenario = "../pads_friction_patches.toml"   # for target = "scenario", relative to this file
    [fixed]                       # held fixed: model parameters, or run settings (duration, dt_out)
    duration = 300.0
    [grid]                        # the Cartesian product of these lists; "seed" sets the seeds
    v = [1e-4, 5e-4, 1e-3]
    seed = [0]
    [analysis]
    omega_ref = [70.0, 140.0]     # band (rad/s) for C_x at fixed omega against v

This module reads and checks the file (:func:`load_sweep`), expands its grid (:func:`expand`) and builds one
grid point's parameters (:func:`build_point`); :mod:`compare.sweep.tasks` runs them. The models are those
registered in ``reduced_models.MODELS``: their parameter classes, default durations and output steps are read there.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from frictionnoise.base import check_seed

__all__ = ["SweepSpec", "SweepError", "load_sweep", "expand", "task_id", "build_point", "RUN_KEYS", "SCENARIO",
           "targets", "model_of"]

SCENARIO = "scenario"  # the target that runs a scene; every other target is a registered model
RUN_KEYS = {"duration", "dt_out"}


class SweepError(ValueError):
    """An invalid sweep file: the message names the file and the field."""


@dataclass(frozen=True)
class SweepSpec:
    name: str
    target: str
    fixed: dict
    grid: dict
    analysis: dict = field(default_factory=dict)
    scenario: str | None = None
    description: str = ""


_TOP = {"name": str, "description": str, "target": str, "scenario": str, "fixed": dict, "grid": dict,
        "analysis": dict}
_MAX_DURATION = 1e5  # s of simulated time per task


def _models() -> dict:
    from reduced_models import MODELS

    return MODELS


def targets() -> tuple:
    """The valid sweep targets: the registered models, then ``scenario``."""
    return (*_models(), SCENARIO)


def model_of(spec: "SweepSpec"):
    """The registered model module a model sweep runs."""
    return _models()[spec.target]


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _model_fields(target) -> dict:
    """Settable fields of a model's parameters: name -> default value (its type is the expected one)."""
    import dataclasses

    out = {}
    for f in dataclasses.fields(_models()[target].PARAMS):
        if not f.init or not f.repr:
            continue  # derived flags, not parameters
        # a field built by a factory (e.g. a distribution spec) is left to the model's own validation
        out[f.name] = f.default if f.default is not dataclasses.MISSING else (_ANY if f.default_factory
                                                                             is not dataclasses.MISSING else None)
    return out


_ANY = object()


def _check_value(where: str, key: str, v, expected):
    """Type per key: numbers where the default is a number (finite; ints where an int is expected), strings and
    booleans where those are."""
    if expected is _ANY:
        return
    if isinstance(expected, bool):
        ok = isinstance(v, bool)
        kind = "true or false"
    elif isinstance(expected, int):
        ok = isinstance(v, int) and not isinstance(v, bool)
        kind = "a whole number"
    elif isinstance(expected, float) or expected is None:
        ok = _is_number(v)
        kind = "a finite number"
    elif isinstance(expected, str):
        ok = isinstance(v, str)
        kind = "a string"
    else:
        ok = True
        kind = ""
    if not ok:
        raise SweepError(f"{where}: {key} must be {kind} (got {v!r})")


def _check_run(where: str, key: str, v):
    if not _is_number(v) or not 0 < v <= _MAX_DURATION:
        raise SweepError(f"{where}: {key} must be a number of seconds in (0, {_MAX_DURATION:g}] (got {v!r})")


def load_sweep(path) -> SweepSpec:
    """Read and validate a sweep file, every key and every grid point, before anything runs: unknown keys are
    named with the list of valid ones; types and ranges are checked per key (the models' own validation names
    the field for ranges)."""
    from ..io.inputs import InputError, read_toml

    path = Path(path)
    try:
        d = read_toml(path, "sweep TOML file")
    except InputError as e:
        raise SweepError(str(e)) from None
    bad = sorted(set(d) - set(_TOP))
    if bad:
        raise SweepError(f"{path}: unknown key {bad[0]!r}; valid keys: {', '.join(sorted(_TOP))}")
    for k, typ in _TOP.items():
        if k in d and not isinstance(d[k], typ):
            raise SweepError(f"{path}: {k} must be a {'table' if typ is dict else 'string'} (got {d[k]!r})")
    target = d.get("target")
    if target not in targets():
        raise SweepError(f"{path}: target must be one of {', '.join(targets())} (got {target!r})")
    grid, fixed, analysis = d.get("grid", {}), d.get("fixed", {}), d.get("analysis", {})
    if not grid or not all(isinstance(v, list) and v for v in grid.values()):
        raise SweepError(f"{path}: [grid] must hold non-empty lists of values")
    scen = d.get("scenario")
    if target == SCENARIO:
        if not scen:
            raise SweepError(f"{path}: target = 'scenario' needs scenario = <path>")
        scen = str((path.parent / scen).resolve())
        if not Path(scen).exists():
            raise SweepError(f"{path}: scenario {scen}: no such file")
    elif scen is not None:
        raise SweepError(f"{path}: scenario = ... applies only to target = 'scenario' (target is {target!r})")
    if target != SCENARIO:
        model = _model_fields(target)
        valid = sorted(model) + sorted(RUN_KEYS)
        for sec, table in (("fixed", fixed), ("grid", grid)):
            for key in table:
                if key == "seed" and sec == "grid":
                    continue
                if key not in model and key not in RUN_KEYS:
                    extra = ", seed" if sec == "grid" else ""
                    raise SweepError(f"{path}: unknown key {key!r} in [{sec}]; valid names: {', '.join(valid)}{extra}")
                values = table[key] if sec == "grid" else [table[key]]
                for v in values:
                    if key in RUN_KEYS:
                        _check_run(path, f"{sec}.{key}", v)
                    else:
                        _check_value(path, f"{sec}.{key}", v, model[key])
    else:
        for sec, table in (("fixed", fixed), ("grid", grid)):
            for key in table:
                if key == "duration":
                    for v in (table[key] if sec == "grid" else [table[key]]):
                        _check_run(path, f"{sec}.{key}", v)
                elif key == "seed" and sec == "grid":
                    pass
                elif "." not in key:
                    raise SweepError(f"{path}: unknown key {key!r} in [{sec}]; scenario parameters are written "
                                     "section.key (e.g. drive.v), besides duration and seed")
    seeds = grid.get("seed", [0])
    try:  # each seed by the one rule frictionnoise.base.check_seed
        if not isinstance(seeds, list):
            raise ValueError(seeds)
        for x in seeds:
            check_seed("grid.seed", x)
    except ValueError:
        raise SweepError(f"{path}: grid.seed must be a list of whole numbers from 0 to 2^63 - 1 (got {seeds!r})") from None
    bad = sorted(set(analysis) - {"omega_ref", "omega_max", "wear"})  # wear = true: the wear study's statistics
    if bad:
        raise SweepError(f"{path}: unknown key {bad[0]!r} in [analysis]; valid names: omega_max, omega_ref, wear")
    ref = analysis.get("omega_ref")
    if ref is not None and not (isinstance(ref, list) and len(ref) == 2 and all(_is_number(x) for x in ref)
                                and 0 < ref[0] < ref[1]):
        raise SweepError(f"{path}: analysis.omega_ref must be two numbers 0 < lo < hi in rad/s (got {ref!r})")
    om = analysis.get("omega_max")
    if om is not None and not (_is_number(om) and om > 0):
        raise SweepError(f"{path}: analysis.omega_max must be a positive number in rad/s (got {om!r})")
    spec = SweepSpec(name=d.get("name", path.stem), target=target, fixed=fixed, grid=grid, analysis=analysis,
                     scenario=scen, description=d.get("description", ""))
    try:  # every grid point's parameters once (the models' and the scenario's own range checks)
        for params, _ in expand(spec):
            obj, run = build_point(spec, params)
            if target != SCENARIO:
                model = _models()[target]
                step = run.get("dt_out", model.default_dt_out(obj))
                dur = run.get("duration", model.default_duration(obj))
                if not dur >= 2 * step:
                    raise SweepError(f"{path}: duration = {dur:g} s holds fewer than two steps of {step:.3g} s "
                                     f"(at {', '.join(f'{k} = {v}' for k, v in params.items())})")
    except (TypeError, ValueError) as e:
        if isinstance(e, SweepError):
            raise
        raise SweepError(f"{path}: {e}") from None
    return spec


def _without_grains(params: dict) -> str | None:
    """For a grid point with ``wear.count = 0``, its parameters less those that mean nothing without grains (the
    other ``wear.*`` fields and the wear study's ``study.size``), as a key; None for any other point."""
    if params.get("wear.count", None) != 0:
        return None
    return json.dumps({k: v for k, v in params.items() if not (k.startswith("wear.") or k == "study.size")},
                      sort_keys=True)


def expand(spec: SweepSpec):
    """[(params, seed)] over the grid's Cartesian product (seed from grid["seed"], default [0]). Points without
    grains (``wear.count = 0``) that differ only in grain fields are one run, kept at its first occurrence: the
    wear study's particle-free twin is the same scene, bit for bit, for every size distribution (wear_study.toml's 24
    twins are 8 runs)."""
    keys = [k for k in spec.grid if k != "seed"]
    seeds = spec.grid.get("seed", [0])
    out, seen = [], set()
    for combo in itertools.product(*(spec.grid[k] for k in keys)):
        params = {**spec.fixed, **dict(zip(keys, combo))}
        twin = _without_grains(params)
        if twin is not None:
            if twin in seen:
                continue
            seen.add(twin)
        for s in seeds:
            out.append((params, int(s)))
    return out


def task_id(spec: SweepSpec, params: dict, seed: int) -> str:
    key = json.dumps({"target": spec.target, "scenario": spec.scenario, "params": params, "seed": seed}, sort_keys=True)
    return hashlib.sha1(key.encode()).hexdigest()[:16]


def build_point(spec: SweepSpec, params: dict):
    """The model parameters (or scenario) and run settings of one grid point; raises on bad values."""
    model = {k: v for k, v in params.items() if k not in RUN_KEYS}
    run = {k: v for k, v in params.items() if k in RUN_KEYS}
    if spec.target != SCENARIO:
        return model_of(spec).PARAMS(**model), run
    from engine_sim.scenario import load_scenario, scenario_from_dict
    base = load_scenario(spec.scenario).to_dict()
    from ..analysis.wear_study import expand_factors  # the wear study's named factors (study.size, study.track)
    for k, v in expand_factors(model).items():
        sec, _, key = k.partition(".")
        if not key or sec not in base or not isinstance(base[sec], dict):
            raise ValueError(f"scenario parameter {k!r} must be written section.key, e.g. drive.v")
        base[sec][key] = v
    if "duration" in run:
        base["run"]["duration"] = run["duration"]
    return scenario_from_dict(base, where=spec.scenario), run
