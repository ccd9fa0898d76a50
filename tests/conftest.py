"""The fast tier touches every module, so no module ships untested. After a run of the whole test folder
(`python -m pytest -m "not slow"`, no file or -k selection) the project's modules that no selected test imported
are listed and the run fails. A module counts when a file with a selected test imports it (an import statement
anywhere in the file, or a module first loaded while the file was collected), or when it was loaded while the tests
ran, and so does every module these import at their top, transitively (read from their source). A module that only
files whose tests were all deselected import does not count. Subprocesses are not seen: a module only reached
through `python -m ...` counts as untouched (the strict side).

Under pytest-xdist (``-n 2``, the README's fast-tier command) each worker lists what its own tests left
untouched and the controller fails the run on the modules every worker left untouched.

With FRICTIONNOISE_CALLED=1 the check is stricter: a function of the module must have run in this process (a
global trace function that returns None, so no line is traced; it costs about 40 % more CPU time, measured on
four test files, so it is not the default)."""
from __future__ import annotations

import os
import sys
import threading
from pathlib import Path

import pytest

from tests.modules import PACKAGES, ROOT, project_modules
_PREFIXES = tuple(str(ROOT / p) + "/" for p in PACKAGES)
_CALLED = bool(os.environ.get("FRICTIONNOISE_CALLED"))
_called: set = set()
_seen_code: set = set()
_by_file: dict = {}  # test file -> project modules first imported while it was collected
_state = {"loaded": set(), "after_collection": None, "selected_files": set()}


def _trace(frame, event, arg):
    code = frame.f_code
    if code not in _seen_code:  # each code object once: the common case is one set lookup
        _seen_code.add(code)
        if code.co_name != "<module>" and code.co_filename.startswith(_PREFIXES):
            _called.add(code.co_filename)


def _loaded() -> set:
    return {m for m in list(sys.modules) if m.split(".")[0] in PACKAGES}


def _defines_functions(path: Path) -> bool:
    return any(hasattr(c, "co_code") for c in compile(path.read_text(), str(path), "exec").co_consts)


def pytest_configure(config):
    _state["loaded"] = _loaded()
    if _CALLED:
        sys.settrace(_trace)
        threading.settrace(_trace)


def _all_slow(path: Path) -> bool:
    """Is every test of this file marked slow (a module-level ``pytestmark = pytest.mark.slow`` or the marker on
    each test function)? Read from the source, before the file is imported."""
    import ast

    tree = ast.parse(path.read_text())

    def slow(node):  # pytest.mark.slow itself (a parametrize with a slow case among others is not)
        return ast.unparse(node).endswith("mark.slow")
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(tg, "id", "") == "pytestmark" for tg in node.targets):
            if slow(node.value):
                return True
    tests = [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))
             and n.name.startswith("test")]
    return bool(tests) and all(any(slow(d) for d in n.decorator_list) for n in tests)


def pytest_ignore_collect(collection_path, config):
    # the fast tier does not import files it would deselect whole (the fuzz tests' hypothesis alone costs 1 s)
    if config.option.markexpr == "not slow" and collection_path.suffix == ".py" \
            and collection_path.name.startswith("test_") and _all_slow(collection_path):
        return True
    return None


@pytest.fixture(scope="session")
def installed(tmp_path_factory):
    """A non-editable install of this checkout into a fresh venv (tests/installed.py), once per session."""
    from tests.installed import install_non_editable

    return install_non_editable(tmp_path_factory.mktemp("install"))


@pytest.fixture(scope="session")
def installed_all_scenes_report(installed):
    """(folder, wall s) of `frictionnoise report --quick --all-scenes` (the README's quick report with every shipped
    scene at its quick length) from the installed package, once per session: read by tests/project/test_install.py
    and tests/compare/test_report_cli.py."""
    from tests.installed import quick_report

    return quick_report(installed, "--all-scenes", out="rep-all")


def _shared_fixtures(item) -> list:
    """The fixtures of this test folder wider than a test (module or session scope) that ``item`` uses."""
    here = str(Path(__file__).resolve().parent) + "/"
    info = getattr(item, "_fixtureinfo", None)
    out = []
    for name, defs in (info.name2fixturedefs.items() if info is not None else ()):
        src = getattr(getattr(defs[-1].func, "__code__", None), "co_filename", "")
        if defs[-1].scope != "function" and src.startswith(here):
            out.append(f"{Path(src).stem}::{name}")
    return out


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist's own hook reads the xdist_group marks (--dist loadgroup)
def pytest_collection_modifyitems(config, items):
    # The slow tier runs in two groups (README, .ci/run): `slow and not timing` on both cores, `slow and timing`
    # (tests that measure a speed or a time bound) on one. A `timing` test outside the slow tier would run in
    # neither group's sense: refuse it.
    stray = [it.nodeid for it in items if it.get_closest_marker("timing") and not it.get_closest_marker("slow")]
    if stray:
        raise pytest.UsageError(f"tests marked timing but not slow (the timing group is part of the slow tier): "
                                f"{', '.join(stray)}")
    # The extended tests (full-size re-measurements of a study, left out of CI's run: README, .ci/run) are part of the
    # slow tier and of its group on both cores: one marked timing would run in no group.
    stray = [it.nodeid for it in items if it.get_closest_marker("extended")
             and (not it.get_closest_marker("slow") or it.get_closest_marker("timing"))]
    if stray:
        raise pytest.UsageError(f"tests marked extended must be slow and not timing: {', '.join(stray)}")
    # Under pytest-xdist with --dist loadgroup: tests that share a module- or session-scoped fixture of this folder
    # (a 60 s scene run, the install, a quick report) go to one worker, so the fixture is built once, not once
    # per worker. Groups are the connected sets of tests linked by such fixtures (found, not listed by hand).
    if not config.pluginmanager.hasplugin("xdist"):
        return
    parent: dict = {}

    def root(n):
        while parent.setdefault(n, n) != n:
            n = parent[n]
        return n
    shared = {it: _shared_fixtures(it) for it in items}
    for names in shared.values():
        for a in names[1:]:
            parent[root(a)] = root(names[0])
    for it, names in shared.items():
        if names:
            it.add_marker(pytest.mark.xdist_group(name=root(names[0])))


def pytest_collectreport(report):
    now = _loaded()
    if report.fspath and report.fspath.endswith(".py"):
        _by_file.setdefault(str(Path(report.fspath).resolve()), set()).update(now - _state["loaded"])
    _state["loaded"] = now


def pytest_collection_finish(session):
    _state["after_collection"] = _loaded()
    _state["selected_files"] = {str(Path(item.path).resolve()) for item in session.items}


def _imports(path: Path, package: str = "", everywhere: bool = False) -> set:
    """The module names a file imports: in its top-level statements (guarded ones too), or ``everywhere`` (a test
    file's test functions import what they exercise)."""
    import ast

    tree = ast.parse(path.read_text())
    if everywhere:
        nodes = list(ast.walk(tree))
    else:
        nodes, todo = [], list(tree.body)
        while todo:
            node = todo.pop()
            nodes.append(node)
            if isinstance(node, (ast.If, ast.Try)):
                todo.extend(node.body + node.orelse + getattr(node, "finalbody", [])
                            + [s for h in getattr(node, "handlers", []) for s in h.body])
    out = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{parent}.{base}" if base else parent
            out.add(base)
            out.update(f"{base}.{a.name}" for a in node.names)  # kept by the caller only if it is a module
    return out


def _with_imports(names: set) -> set:
    """``names`` and what they import at their top, transitively, with their parent packages: a module first
    imported by a deselected file is still imported by the selected file that imports its importer."""
    modules = project_modules()
    out, todo = set(), list(names)
    while todo:
        name = todo.pop()
        if name in out or name not in modules:
            continue
        out.add(name)
        todo.extend(name.rsplit(".", k)[0] for k in range(1, name.count(".") + 1))
        path = modules[name]
        todo.extend(_imports(path, name if path.name == "__init__.py" else name.rpartition(".")[0]))
    return out


def untouched_modules() -> list:
    """The project's modules no selected test imported (or, with FRICTIONNOISE_CALLED=1, called)."""
    if _CALLED:
        return [n for n, p in project_modules().items()
                if (str(p) not in _called if _defines_functions(p) else n not in sys.modules)]
    credited = _loaded() - (_state["after_collection"] or set())
    for f in _state["selected_files"]:
        credited |= _by_file.get(f, set()) | _imports(Path(f), everywhere=True)
    credited = _with_imports(credited)
    return [n for n in project_modules() if n not in credited]


def _whole_tier(session) -> bool:
    cfg = session.config
    return (cfg.args_source == pytest.Config.ArgsSource.TESTPATHS and not cfg.option.keyword
            and cfg.option.markexpr in ("", "not slow") and not cfg.option.collectonly)


_worker_lists: list = []  # under pytest-xdist (``-n 2``): each worker's untouched modules, gathered by the controller


@pytest.hookimpl(optionalhook=True)  # an xdist hook: without xdist installed, never called
def pytest_testnodedown(node, error):
    if "untouched" in getattr(node, "workeroutput", {}):
        _worker_lists.append(set(node.workeroutput["untouched"]))


def pytest_sessionfinish(session, exitstatus):
    if _CALLED:
        sys.settrace(None)
        threading.settrace(None)
    cfg = session.config
    if hasattr(cfg, "workerinput"):  # an xdist worker: hand its list to the controller, which decides
        cfg.workeroutput["untouched"] = untouched_modules()
        return
    if _whole_tier(session) and exitstatus == 0:
        if getattr(cfg.option, "numprocesses", None):  # a module is untouched if no worker touched it
            missed = sorted(set.intersection(*_worker_lists)) if _worker_lists else list(project_modules())
        else:
            missed = untouched_modules()
        if missed:
            session.exitstatus = pytest.ExitCode.TESTS_FAILED
        # written here, not in pytest_terminal_summary: under xdist the controller's summary comes first
        how = "called" if _CALLED else "imported"
        tr = cfg.pluginmanager.get_plugin("terminalreporter")
        line = (f"modules no selected test {how} ({len(missed)}): {', '.join(missed)}" if missed
                else f"every project module ({len(project_modules())}) {how} by a selected test")
        if tr is not None:
            tr.write_line(line, red=bool(missed))
        else:
            print(line, file=sys.stderr)
