"""The shape of the source, counted with ``ast``: every module opens with a docstring that says the
one concept it holds (modules are cut along concepts, not at a line count: a module is as long as its concept
needs, and one that holds two says two), no function over 100 lines except the declarative tables listed below (a function's docstring lines
not counted: numpydoc sections are wanted), and no private name (``_x``) of one project module used by another."""
import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("compare", "frictionnoise", "engine_sim", "reduced_models")  # the packages whose shape is held; a package joins by one name here
MAX_FUNCTION_LINES = 100
# functions that are declarative tables, allowed to be long: path relative to the root, function name
TABLES = {("compare/cli/parser.py", "build_parser")}  # the argparse table of the subcommands and their help


def _modules():
    for pkg in PACKAGES:
        yield from sorted((ROOT / pkg).rglob("*.py"))


def _name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _absolute(node: ast.ImportFrom, path: Path) -> str:
    """The module an ImportFrom names, made absolute from ``path``'s package."""
    if not node.level:
        return node.module or ""
    pkg = _name(path).split(".")
    if path.name != "__init__.py":
        pkg = pkg[:-1]
    pkg = pkg[:len(pkg) - (node.level - 1)]
    return ".".join(pkg + ([node.module] if node.module else []))


def _project(module: str) -> bool:
    return module.split(".")[0] in ("compare", "frictionnoise", "engine_sim", "reduced_models")


def _docstring_lines(tree) -> set:
    """Line numbers held by docstrings (module, class and function): not counted in a function's length."""
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                lines.update(range(first.lineno, first.end_lineno + 1))
    return lines


@pytest.mark.parametrize("path", list(_modules()), ids=lambda p: str(p.relative_to(ROOT)))
def test_module_concept_and_function_lengths(path):
    src = path.read_text()
    tree = ast.parse(src)
    doc = _docstring_lines(tree)
    rel = str(path.relative_to(ROOT))
    concept = ast.get_docstring(tree)
    if path.name != "__init__.py" or src.strip():
        assert concept and len(concept.split()) >= 3, f"{rel}: no docstring saying what the module holds"

    def length(node):  # a function: its lines less those of docstrings inside it
        return node.end_lineno - node.lineno + 1 - len(doc & set(range(node.lineno, node.end_lineno + 1)))

    long = [(node.name, length(node)) for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
            and length(node) > MAX_FUNCTION_LINES and (rel, node.name) not in TABLES]
    assert not long, f"{rel}: functions over {MAX_FUNCTION_LINES} lines: {long}"


@pytest.mark.parametrize("path", list(_modules()), ids=lambda p: str(p.relative_to(ROOT)))
def test_no_private_name_crosses_a_module(path):
    """``from m import _x`` and ``m._x`` with ``m`` another project module are refused; a private module
    (``studies/_common.py``) may be imported only by its own package's modules."""
    tree = ast.parse(path.read_text())
    me = _name(path)
    bad, modules = [], {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            src = _absolute(node, path)
            if not _project(src) or src == me:
                continue
            parts = src.split(".")
            for k, part in enumerate(parts):
                owner = ".".join(parts[:k])  # the package a private module belongs to
                if part.startswith("_") and not part.startswith("__") and not me.startswith(owner + "."):
                    bad.append(f"line {node.lineno}: from {src} import ... (a private module of {owner})")
            for a in node.names:
                if a.name.startswith("_") and not a.name.startswith("__"):
                    if not (ROOT / Path(*src.split("."), f"{a.name}.py")).exists():  # a private name, not a module
                        bad.append(f"line {node.lineno}: from {src} import {a.name}")
                    elif not me.startswith(src + "."):
                        bad.append(f"line {node.lineno}: from {src} import {a.name} (a private module of {src})")
                modules[a.asname or a.name] = f"{src}.{a.name}"
        elif isinstance(node, ast.Import):
            for a in node.names:
                if _project(a.name):
                    modules[a.asname or a.name.split(".")[0]] = a.name
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules
                and node.attr.startswith("_") and not node.attr.startswith("__")):
            bad.append(f"line {node.lineno}: {node.value.id}.{node.attr}")
    assert not bad, f"{path.relative_to(ROOT)}: private names of other modules: {bad}"
