"""What the subcommands share: the user-error exception and the checks of their common arguments (output
folder, seed, scenario), each refusing bad input with one line."""
from __future__ import annotations

__all__ = ["UserError", "output_dir", "check_seed", "scenario_path", "load_scenario_arg", "usable_cores"]


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


def check_seed(seed):
    if seed is not None and not 0 <= seed < 2**63:
        raise UserError(f"--seed must be a whole number from 0 to 2^63 - 1 (got {seed})")


def scenario_path(arg) -> str:
    """A scenario argument as a path: an existing path as given (it wins over a shipped name of the same
    spelling), else the shipped scenario of that name, else as given (the input layer then names the problem)."""
    import os

    from engine_sim import ScenarioError
    from engine_sim.scenario import resolve_scenario

    if os.path.lexists(arg):
        return arg
    try:
        return str(resolve_scenario(arg))
    except ScenarioError:
        return arg


def load_scenario_arg(path):
    from engine_sim import ScenarioError, scenario_from_dict

    from ..io.inputs import read_toml

    path = scenario_path(path)
    data = read_toml(path, "scenario TOML file")
    try:
        return scenario_from_dict(data, where=str(path))
    except ScenarioError as e:
        raise UserError(str(e)) from None


def usable_cores(cap: int) -> int:
    import os

    n = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cap, n))
