"""`frictionnoise scenarios`: the shipped files (package data of engine_sim) listed, printed or copied."""
from __future__ import annotations

import sys

from .options import UserError

__all__ = ["cmd_scenarios"]


def cmd_scenarios(args) -> int:
    """Each shipped scenario's name and the first whole sentence of its description, wrapped to the terminal's
    width (``COLUMNS``, else the terminal's, else 100) under a hanging indent; words are never cut. With ``--all``,
    then every other shipped file (sweeps, data, profiles) one a line. With a NAME, that shipped file's text on
    stdout, or with ``--copy DEST`` the file copied (:func:`_copy_shipped`)."""
    import shutil
    import textwrap

    from engine_sim import ScenarioError, load_scenario, shipped_scenarios
    from engine_sim.shipped import scenario_summary, shipped_files, shipped_path

    if args.copy is not None and args.name is None:
        raise UserError("scenarios --copy DEST: name the shipped file to copy (frictionnoise scenarios NAME --copy DEST)")
    if args.name is not None:
        try:
            src = shipped_path(args.name)
        except ScenarioError as e:
            raise UserError(str(e)) from None
        if args.copy is None:
            sys.stdout.write(src.read_text(encoding="utf-8"))
        else:
            print(_copy_shipped(src, args.copy))
        return 0
    shipped = shipped_scenarios()
    width = max(map(len, shipped), default=0)
    columns = max(shutil.get_terminal_size((100, 24)).columns, width + 40)
    for name, path in shipped.items():
        sentence = scenario_summary(load_scenario(path).description, width=10**6)  # the whole first sentence
        print(textwrap.fill(sentence, width=columns - 1, initial_indent=f"{name:{width}s}  ",
                            subsequent_indent=" " * (width + 2), break_long_words=False, break_on_hyphens=False))
    if args.all:
        print("\nsweeps, example data and profiles (frictionnoise scenarios NAME prints one, --copy DEST copies it):")
        print("\n".join(f for f in shipped_files() if "/" in f))
    return 0


def _copy_shipped(src, dest) -> str:
    """Copy the shipped file ``src`` to ``dest`` (an existing folder: a file of the same name in it; else the new
    file's path, its folder created) and return where it went. A user error, nothing written, if the target exists
    or cannot be written."""
    import shutil
    from pathlib import Path

    target = Path(dest) / src.name if Path(dest).is_dir() else Path(dest)
    if target.exists():
        raise UserError(f"{target}: already exists; frictionnoise scenarios --copy never overwrites (remove it or "
                        "name another DEST)")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, target)
    except OSError as e:
        raise UserError(f"{target}: cannot be written ({e.strerror or e})") from None
    return str(target)
