"""A user's parts, loaded by name from a scenario: its top-level ``plugins`` list.

Each entry is a Python file (``*.py``; a relative path is read from the scenario file's folder) or an importable
module name (``mylab.laws``). Loading one runs its registrations (``@LAWS.register``, ``@SUBSTRATES.register``,
``@DRIVES.register``, ``@ARRANGEMENTS.register``, ``@CHANNELS.register``), so the scenario's sections and
``channels`` may then name what it adds. A module is loaded once per process; a file under the name
``frictionnoise_plugin_<stem>_<hash>``, the hash that of its resolved path, so one file has one name in every
process whatever else was loaded before it. The resolved entries (absolute paths) are kept in the scenario, so a
trace's metadata loads them again.

A kernel compiled with ``numba.njit(cache=True)`` is cached beside its file with the name of the module it was
loaded under, and a later process imports that module by that name to use the cache. So one file may be named
both ways, as a file in one scenario and as a module in another: a module plugin is also entered in
``sys.modules`` under its file's plugin name, and a file plugin answers an import of a module name its path ends
with (``mylab/laws.py`` answers ``laws``, and ``mylab.laws`` if ``mylab`` holds an ``__init__.py``) when nothing
else on ``sys.path`` does.
"""
from __future__ import annotations

import hashlib
import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import re
import sys
import types
from pathlib import Path

__all__ = ["load_plugins"]


_FILES: dict = {}  # resolved path -> the module of each plugin file loaded in this process


def plugin_name(path: Path) -> str:
    """The module name of the plugin file ``path`` (resolved): its stem and a hash of the path, the same in every
    process."""
    stem = re.sub(r"\W", "_", path.stem)
    return f"frictionnoise_plugin_{stem}_{hashlib.sha256(str(path).encode()).hexdigest()[:12]}"


class _Existing(importlib.abc.Loader):
    """Loads an already imported module (or an empty namespace for its parents) under another name."""

    def __init__(self, mod):
        self.mod = mod

    def create_module(self, spec):
        return self.mod

    def exec_module(self, module):
        pass


class _FileAliases(importlib.abc.MetaPathFinder):
    """The last finder on ``sys.meta_path``: a module name that nothing else finds and that a loaded plugin
    file's path ends with is that file's module (module docstring); its parents, folders with an
    ``__init__.py`` each, are answered as empty namespaces. A folder without one is never answered."""

    def find_spec(self, fullname, path=None, target=None):
        want = fullname.split(".")
        for file, mod in list(_FILES.items()):
            names = Path(file).with_suffix("").parts
            for s in range(1, len(names)):
                chain = names[s:]  # the module's dotted name if the folder above names[s] were on sys.path
                if list(chain[:len(want)]) != want:
                    continue
                if not all((Path(*names[:j + 1]) / "__init__.py").is_file() for j in range(s, len(names) - 1)):
                    continue
                leaf = len(want) == len(chain)
                spec = importlib.machinery.ModuleSpec(
                    fullname, _Existing(mod if leaf else types.ModuleType(fullname)), is_package=not leaf)
                if not leaf:
                    spec.submodule_search_locations = []
                return spec
        return None


_FINDER = _FileAliases()


def _from_file(path: Path):
    """The module of a plugin file, imported once (by its resolved path)."""
    if str(path) in _FILES:
        return _FILES[str(path)]
    name = plugin_name(path)
    if _FINDER not in sys.meta_path:
        sys.meta_path.append(_FINDER)
    if name in sys.modules:  # imported as a module first (see load_plugins)
        _FILES[str(path)] = sys.modules[name]
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    mod.__plugin_file__ = str(path)
    sys.modules[name] = _FILES[str(path)] = mod
    try:
        spec.loader.exec_module(mod)
    except BaseException:
        del sys.modules[name], _FILES[str(path)]
        raise
    return mod


def _from_module(entry: str):
    """The module ``entry`` imported by its name, also entered under its file's plugin name (module docstring)."""
    mod = importlib.import_module(entry)
    file = getattr(mod, "__file__", None)
    if file is not None:
        sys.modules.setdefault(plugin_name(Path(file).resolve()), mod)
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
        is_file = entry.endswith(".py")
        if is_file:
            path = Path(entry).expanduser()
            if not path.is_absolute():
                path = (base or Path.cwd()) / path
            path = path.resolve()
            if not path.is_file():
                raise ValueError(f"plugins: {entry!r}: no such file ({path})")
            load = lambda p=path: _from_file(p)  # noqa: E731
            resolved = str(path)
        else:
            load = lambda e=entry: _from_module(e)  # noqa: E731
            resolved = entry
        try:
            load()
        except ModuleNotFoundError as e:
            if not is_file and e.name is not None and entry.startswith(e.name):
                raise ValueError(f"plugins: {entry!r} cannot be imported ({e})") from None
            raise ValueError(f"plugins: {entry!r}{_where(entry, is_file, resolved)} failed to load: "
                             f"{type(e).__name__}: {e}") from None
        except Exception as e:
            raise ValueError(f"plugins: {entry!r}{_where(entry, is_file, resolved)} failed to load: "
                             f"{type(e).__name__}: {_one_line(e)}") from None
        out.append(resolved)
    return tuple(out)


def _where(entry: str, is_file: bool, resolved: str) -> str:
    """`` (its file)``: a file entry's resolved path, unless the entry is that path; a module entry's file, when
    it can be found; else nothing."""
    if is_file:
        return "" if resolved == entry else f" ({resolved})"
    try:
        spec = importlib.util.find_spec(entry)
    except Exception:  # a parent package that fails to import
        return ""
    return f" ({spec.origin})" if spec is not None and spec.origin else ""


def _one_line(e: BaseException) -> str:
    """The first line of an exception's message (a compile error's message runs over many lines)."""
    text = str(e).strip()
    return text.splitlines()[0] if text else ""
