"""A user's parts, loaded by name from a scenario: its top-level ``plugins`` list.

Each entry is a Python file (``*.py``; a relative path is read from the scenario file's folder) or an importable
module name (``mylab.laws``). Loading one runs its registrations (``@LAWS.register``, ``@SUBSTRATES.register``,
``@DRIVES.register``, ``@ARRANGEMENTS.register``, ``@CHANNELS.register``), so the scenario's sections and
``channels`` may then name what it adds. A module is loaded once per process, under the name
``frictionnoise_plugin_<stem>`` for a file. The resolved entries (absolute paths) are kept in the scenario, so a
trace's metadata loads them again.
"""
from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path

__all__ = ["load_plugins"]


def _from_file(path: Path):
    """The module of a plugin file, imported once (by its resolved path)."""
    for mod in list(sys.modules.values()):
        if getattr(mod, "__plugin_file__", None) == str(path):
            return mod
    name = f"frictionnoise_plugin_{path.stem}"
    while name in sys.modules:  # two files of one stem: the second gets a suffix
        name += "_"
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    mod.__plugin_file__ = str(path)
    sys.modules[name] = mod
    try:
        spec.loader.exec_module(mod)
    except BaseException:
        del sys.modules[name]
        raise
    return mod


def load_plugins(entries, base: Path | None = None) -> tuple:
    """Import the plugins ``entries`` (module docstring) and return them resolved: files as absolute paths,
    modules by name.

    Parameters
    ----------
    entries : list of str
        Files (``*.py``) or module names.
    base : pathlib.Path, optional
        The folder a relative file is read from (the scenario file's; None: the working directory).

    Returns
    -------
    tuple of str
        The entries resolved, in their order.

    Raises
    ------
    ValueError
        One line naming the entry: not a list of strings, no such file, not importable, or an error while it
        loads.
    """
    if not isinstance(entries, (list, tuple)) or not all(isinstance(e, str) for e in entries):
        raise ValueError(f"plugins must be a list of file paths or module names (got {entries!r})")
    out = []
    for entry in entries:
        if entry.endswith(".py"):
            path = Path(entry).expanduser()
            if not path.is_absolute():
                path = (base or Path.cwd()) / path
            path = path.resolve()
            if not path.is_file():
                raise ValueError(f"plugins: {entry!r}: no such file ({path})")
            load = lambda p=path: _from_file(p)  # noqa: E731
            resolved = str(path)
        else:
            load = lambda e=entry: importlib.import_module(e)  # noqa: E731
            resolved = entry
        try:
            load()
        except ModuleNotFoundError as e:
            raise ValueError(f"plugins: {entry!r} cannot be imported ({e})") from None
        except Exception as e:
            raise ValueError(f"plugins: {entry!r} failed to load: {type(e).__name__}: {e}") from None
        out.append(resolved)
    return tuple(out)
