"""What the subcommands share: the user-error exception and the checks of their common arguments (output
folder, seed, scenario), each refusing bad input with one line."""
from __future__ import annotations

import os

__all__ = ["UserError", "output_dir", "check_seed", "check_seconds_options", "scenario_path", "shipped_file",
           "load_scenario_arg", "nearest_names", "data_table", "usable_cores"]


class UserError(Exception):
    """An error in the user's input: printed as one line, exit status 2."""


# names that end like a file: `-o ms.npz` would make a folder named ms.npz
_FILE_SUFFIXES = frozenset({".npz", ".npy", ".json", ".html", ".htm", ".png", ".gif", ".pdf", ".svg", ".pkl", ".csv",
                            ".txt", ".toml", ".zip"})


def output_dir(arg, default, writes: str):
    """The folder a command writes into (``-o DIR``, else ``default``). An ``-o`` name ending in a file suffix
    is refused (unless that folder exists already): every command writes several files into a folder."""
    from pathlib import Path

    from ..io.inputs import output_folder

    if arg is not None:
        suffix = Path(arg).suffix.lower()
        if suffix in _FILE_SUFFIXES and not Path(arg).is_dir():
            raise UserError(f"-o/--output {arg}: names a folder, not a {suffix} file (the command writes {writes} into "
                            f"it); give a folder name without the {suffix} suffix")
    return output_folder(arg or default)


def check_seconds_options(args, *names):
    """Each named option of ``args`` that is given, as a span of seconds: the rule is
    :func:`frictionnoise.base.check_seconds`, the one line names the flag (``--checkpoint-every``)."""
    from frictionnoise.base import check_seconds

    for name in names:
        val = getattr(args, name)
        if val is not None:
            try:
                check_seconds("--" + name.replace("_", "-"), val)
            except ValueError as e:
                raise UserError(str(e)) from None


def check_seed(seed):
    if seed is not None and not 0 <= seed < 2**63:
        raise UserError(f"--seed must be a whole number from 0 to 2^63 - 1 (got {seed})")


def scenario_path(arg, models=()) -> str:
    """A scenario argument as a path: an existing path as given (it wins over a shipped name of the same
    spelling), else a ``scenarios/...`` path inside the installed package (:func:`shipped_file`), else the shipped
    scenario of that name. A bare name (no folder) that is neither is a UserError that
    offers the nearest shipped names (and of ``models``, the other names the command takes) and points to
    ``frictionnoise scenarios``; any other path is returned as given (the input layer then names the problem)."""
    from pathlib import Path

    from engine_sim import ScenarioError, shipped_scenarios
    from engine_sim.scenario import resolve_scenario

    if os.path.lexists(arg):
        return arg
    shipped = shipped_file(arg)  # scenarios/... as the docs write it, inside an installed package
    if shipped != arg:
        return shipped
    try:
        return str(resolve_scenario(arg))
    except ScenarioError:
        pass
    p = Path(arg)
    if p.parent != Path(".") or p.suffix.lower() not in ("", ".toml"):
        return arg
    raise UserError(f"{arg}: no such file, nor a shipped scenario{' or reduced model' if models else ''}"
                    f"{nearest_names(p.stem, [*shipped_scenarios(), *models])}"
                    " (`frictionnoise scenarios` lists the shipped scenarios"
                    + (f"; reduced models: {', '.join(models)})" if models else ")"))


def shipped_file(arg, folder: str = "") -> str:
    """A file argument that need not exist where the command runs: an existing path as given; else a path that
    starts with ``scenarios/`` (as the README writes the shipped examples) taken inside the installed
    ``scenarios`` package; else, with ``folder`` (``"sweeps"``), a bare name of a file shipped there
    (``velocity_model1``); else the argument as given (the input layer then names the problem)."""
    from pathlib import Path

    from engine_sim.scenario import SCENARIO_DIR

    if os.path.lexists(arg):
        return arg
    p = Path(arg)
    candidates = []
    if p.parts and p.parts[0] == "scenarios":
        candidates.append(SCENARIO_DIR.joinpath(*p.parts[1:]))
    if folder and p.parent == Path("."):
        candidates += [SCENARIO_DIR / folder / p.name, SCENARIO_DIR / folder / f"{p.name}.toml"]
    return str(next((c for c in candidates if c.is_file()), arg))


def nearest_names(name: str, names) -> str:
    """'; did you mean X?' (or 'X or Y?') for the names closest to ``name`` by difflib's ratio, else ''."""
    import difflib

    close = difflib.get_close_matches(name, list(names), n=2, cutoff=0.6)
    if not close:
        close = [n for n in names if n.lower() == name.lower()]
    return f"; did you mean {' or '.join(close)}?" if close else ""


def data_table(path) -> bool:
    """Whether a text file reads as a table of numbers (a CSV/TXT data export) rather than TOML: from its first line
    that splits, by one separator, into two or more numbers (decimal commas allowed with ';' or tab), at least two
    lines do and they are most of the lines (a TOML array spread over lines is not a table)."""
    with open(path, "rb") as fh:
        lines = [ln for ln in fh.read(8192).decode("utf-8", "replace").splitlines()[:200] if ln.strip()]
    for sep in (",", ";", "\t"):
        numeric = [_numeric_row(ln, sep) for ln in lines]
        if True in numeric:
            rest = numeric[numeric.index(True):]
            if sum(rest) >= 2 and 2 * sum(rest) > len(rest):
                return True
    return False


def _numeric_row(line: str, sep: str) -> bool:
    cells = [c.strip() for c in line.split(sep) if c.strip()]
    return len(cells) >= 2 and all(_number(c if sep == "," else c.replace(",", ".")) for c in cells)


def _number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def load_scenario_arg(path, models=()):
    """The validated scenario named by a command's argument (a path or a shipped name; see :func:`scenario_path`).
    A table of numbers given where a scenario belongs is one line pointing to ``frictionnoise analyze``."""
    from engine_sim import ScenarioError, scenario_from_dict

    from ..io.inputs import InputError, read_toml, sniff

    path = scenario_path(path, models)
    try:
        data = read_toml(path, "scenario TOML file")
    except InputError:
        if os.path.isfile(path) and sniff(path) == "text" and data_table(path):
            raise UserError(f"{path}: a table of numbers (measured data), not a scenario TOML file; analyse measured "
                            f"x(t) or F(t) with `frictionnoise analyze {path}`") from None
        raise
    try:
        return scenario_from_dict(data, where=str(path))
    except ScenarioError as e:
        raise UserError(str(e)) from None


def usable_cores(cap: int) -> int:
    import os

    n = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cap, n))
