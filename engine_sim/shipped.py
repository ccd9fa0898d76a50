"""The shipped scenarios and the one resolution of a scenario's name: where the scenario files are (package data of
``engine_sim``, the folder ``engine_sim/scenarios/``, installed with every install), which one a name or a path given
by a user means, the shipped file a name means (:func:`shipped_path`, for ``frictionnoise scenarios NAME``), and the
error a scenario raises (:class:`ScenarioError`, one line naming the file, the field and what is wrong).
"""
from __future__ import annotations

import difflib
import os
import re
from pathlib import Path

__all__ = ["SCENARIO_DIR", "ScenarioError", "shipped_file", "nearest_names", "resolve_scenario", "shipped_scenarios",
           "shipped_files", "shipped_path", "scenario_summary"]

# the shipped scenarios are package data of engine_sim, the package that reads them: a data folder beside this module
# (no __init__.py: not a module, nothing named ``scenarios`` at the top level of an install); a regular (non-zipped)
# install gives a real folder. Users and the docs write these files as ``scenarios/<file>`` (see shipped_file).
SCENARIO_DIR = Path(__file__).resolve().parent / "scenarios"


class ScenarioError(ValueError):
    """An invalid scenario: the message names the file (if any), the field and what is wrong."""


def shipped_file(arg, folder: str = "") -> str:
    """A file argument that need not exist where it is read: an existing path as given; else a path that starts
    with ``scenarios/`` (as the README writes the shipped examples) taken inside the installed :data:`SCENARIO_DIR`;
    else, with ``folder`` (``"sweeps"``), a bare name of a file shipped there (``velocity_model1``); else the
    argument as given (the reader then names the problem)."""
    if os.path.lexists(arg):
        return str(arg)
    p = Path(arg)
    candidates = []
    if p.parts and p.parts[0] == "scenarios":
        candidates.append(SCENARIO_DIR.joinpath(*p.parts[1:]))
    if folder and p.parent == Path("."):
        candidates += [SCENARIO_DIR / folder / p.name, SCENARIO_DIR / folder / f"{p.name}.toml"]
    return str(next((c for c in candidates if c.is_file()), arg))


def nearest_names(name: str, names) -> str:
    """'; did you mean X?' (or 'X or Y?') for the names closest to ``name`` by difflib's ratio, else ''."""
    close = difflib.get_close_matches(name, list(names), n=2, cutoff=0.6)
    if not close:
        close = [n for n in names if n.lower() == name.lower()]
    return f"; did you mean {' or '.join(close)}?" if close else ""


def resolve_scenario(name_or_path, others=(), others_kind: str = "") -> Path:
    """The file of a scenario given as a path or as the name of a shipped one: the one name resolution.

    An existing path wins over a shipped name of the same spelling; then a ``scenarios/...`` path inside the
    installed package (:func:`shipped_file`); then a bare name (no folder; with or without ``.toml``) of a shipped
    scenario (:func:`shipped_scenarios`). Anything else is a :class:`ScenarioError`, one line: a bare name offers
    the nearest shipped names (and of ``others``, the other names the caller takes, called ``others_kind``) and
    lists the shipped ones, as ``frictionnoise scenarios`` does; a path says "no such file".
    """
    found = shipped_file(name_or_path)
    if os.path.lexists(found):
        return Path(found)
    path = Path(name_or_path)
    shipped = shipped_scenarios()
    stem = path.name[:-5] if path.name.lower().endswith(".toml") else path.name
    if path.parent == Path(".") and stem in shipped:
        return shipped[stem]
    if path.parent != Path(".") or path.suffix.lower() not in ("", ".toml"):
        raise ScenarioError(f"{path}: no such file")
    also = f" or {others_kind}" if others else ""
    raise ScenarioError(f"{name_or_path}: no such file, nor a shipped scenario{also}"
                        f"{nearest_names(path.stem, [*shipped, *others])} (`frictionnoise scenarios` lists the shipped "
                        f"scenarios: {', '.join(shipped)}" + (f"; {others_kind}s: {', '.join(others)})" if others else ")"))


def shipped_scenarios() -> dict:
    """The scenes shipped in :data:`SCENARIO_DIR` (package data of engine_sim, installed with every install).

    Returns
    -------
    dict
        Name -> path of its TOML file.
    """
    return {p.stem: p for p in sorted(SCENARIO_DIR.glob("*.toml"))}


def shipped_files() -> list:
    """Every shipped file as it is named to a user, relative to :data:`SCENARIO_DIR` with ``/``: the scenes
    (``pads_friction_patches.toml``), the sweeps (``sweeps/...``), the example data (``data/...``) and the profiles
    (``profiles/...``); scripts and caches left out.

    Returns
    -------
    list of str
        The names, sorted (what ``frictionnoise scenarios --all`` lists and :func:`shipped_path` takes).
    """
    return sorted(p.relative_to(SCENARIO_DIR).as_posix() for p in SCENARIO_DIR.rglob("*")
                  if p.is_file() and p.suffix not in (".py", ".pyc"))


def shipped_path(name) -> Path:
    """The shipped file a name means, never a file of the current folder: a scene's name (``tilted_plane``), a file
    relative to the shipped folder with or without ``.toml`` (``sweeps/velocity_model1``,
    ``data/model1_synthetic_um.csv``), or either written as the docs do, ``scenarios/...``.

    Parameters
    ----------
    name : str or path-like
        The shipped file's name, as :func:`shipped_files` lists it (``.toml`` may be left out).

    Returns
    -------
    pathlib.Path
        The file inside the installed package data (read it, or copy it to start a file of your own).

    Raises
    ------
    ScenarioError
        No shipped file of that name: one line with the nearest names and how to list them.
    """
    parts = Path(name).parts
    rel = "/".join(parts[1:] if parts and parts[0] == "scenarios" else parts)
    files = shipped_files()
    for candidate in (rel, f"{rel}.toml"):
        if candidate in files:
            return SCENARIO_DIR.joinpath(*candidate.split("/"))
    short = [f[:-5] if f.endswith(".toml") else f for f in files]
    raise ScenarioError(f"{name}: not a shipped scenario, sweep or data file{nearest_names(rel, short)} "
                        f"(`frictionnoise scenarios --all` lists them)")


def scenario_summary(description: str, width: int = 110) -> str:
    """The first sentence of a scenario's description on one line, cut to ``width`` characters."""
    text = " ".join(description.split())
    end = re.search(r"(?<!Fig)(?<!eq)(?<!e\.g)\. (?=[A-Z(])", text)  # a sentence end, not an abbreviation
    first = text if end is None else text[: end.start() + 1]
    return first if len(first) <= width else first[: width - 3].rstrip() + "..."
