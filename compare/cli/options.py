"""What the subcommands share: the user-error exception and the checks of their common arguments (output
folder, seed, scenario), each refusing bad input with one line."""
from __future__ import annotations

import os

from frictionnoise.base import sniff

__all__ = ["UserError", "output_dir", "check_seed", "check_seconds_options", "scenario_path", "shipped_file",
           "load_scenario_arg", "data_table", "usable_cores"]


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
    """``--seed``, if given, by the one rule :func:`frictionnoise.base.check_seed`, the one line naming the flag."""
    from frictionnoise.base import check_seed as rule

    if seed is not None:
        try:
            rule("--seed", seed)
        except ValueError as e:
            raise UserError(str(e)) from None


def scenario_path(arg, models=()) -> str:
    """A scenario argument as a path (:func:`engine_sim.scenario.resolve_scenario`, the one name resolution;
    ``models``: the reduced models' names the command also takes, offered among the nearest names)."""
    from engine_sim import ScenarioError
    from engine_sim.shipped import resolve_scenario

    try:
        return str(resolve_scenario(arg, models, "reduced model"))
    except ScenarioError as e:
        raise UserError(str(e)) from None


def shipped_file(arg, folder: str = "") -> str:
    """A file argument that need not exist where the command runs (:func:`engine_sim.scenario.shipped_file`,
    imported when a command reads a file: building the parser loads no numerics)."""
    from engine_sim.shipped import shipped_file as shipped

    return shipped(arg, folder)


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
    """The validated scenario named by a command's argument (a path or a shipped name), read by the one loader
    (:func:`engine_sim.load_scenario`). A table of numbers given where a scenario belongs is one line pointing to
    ``frictionnoise analyze``."""
    from engine_sim import ScenarioError, load_scenario

    path = scenario_path(path, models)
    try:
        return load_scenario(path)
    except ScenarioError as e:
        if os.path.isfile(path) and sniff(path) == "text" and data_table(path):
            raise UserError(f"{path}: a table of numbers (measured data), not a scenario TOML file; analyse measured "
                            f"x(t) or F(t) with `frictionnoise analyze {path}`") from None
        raise UserError(str(e)) from None


def usable_cores(cap: int) -> int:
    import os

    n = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cap, n))
