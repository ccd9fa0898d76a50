"""Every public function has a numpydoc docstring: a Parameters section when it takes parameters and a Returns
(or Yields) section when it returns a value. "Public" is what the packages export: the names in ``__all__`` of
``frictionnoise``, ``reduced_models``, ``engine_sim`` and ``compare``, and of the modules those lists name.
Classes need a docstring; their public methods are held to the same rule as functions."""
import ast
import importlib
import inspect
import re
import textwrap
import types

PACKAGES = ("frictionnoise", "reduced_models", "engine_sim", "compare")


def _public():
    """(qualified name, object) of every public function, class and method, each once."""
    seen, out = set(), []

    def add(qual, obj):
        if id(obj) in seen:
            return
        seen.add(id(obj))
        out.append((qual, obj))
        if inspect.isclass(obj):
            for name, member in vars(obj).items():
                if name.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if inspect.isfunction(member):
                    add(f"{qual}.{name}", member)

    def walk(mod, depth):
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name)
            if isinstance(obj, types.ModuleType):
                if depth == 0:
                    walk(obj, 1)
            elif inspect.isfunction(obj) or inspect.isclass(obj):
                add(f"{mod.__name__}.{name}", obj)

    for pkg in PACKAGES:
        walk(importlib.import_module(pkg), 0)
    return out


def _sections(doc: str) -> set:
    return set(re.findall(r"^(\w[\w ]*)\n-{3,}$", doc, flags=re.M))


def _returns_value(func) -> bool:
    try:
        src = textwrap.dedent(inspect.getsource(func))
    except (OSError, TypeError):
        return False
    tree = ast.parse(src)
    body = tree.body[0]
    for node in ast.walk(body):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)) and node is not body:
            continue
        if isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            # a return inside a nested function belongs to it
            if any(node in ast.walk(n) for n in ast.walk(body)
                   if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)) and n is not body):
                continue
            return True
    return False


def _problems(qual, obj) -> list:
    doc = inspect.getdoc(obj) or ""
    if not doc.strip():
        return [f"{qual}: no docstring"]
    if inspect.isclass(obj):
        return []
    found, out = _sections(doc), []
    params = [p for p in inspect.signature(obj).parameters.values() if p.name not in ("self", "cls")]
    if params and "Parameters" not in found:
        out.append(f"{qual}: no Parameters section")
    if _returns_value(obj) and not {"Returns", "Yields"} & found:
        out.append(f"{qual}: no Returns section")
    return out


def test_public_api_is_found():
    names = {q for q, _ in _public()}
    assert "frictionnoise.simulate" in names and "reduced_models.spring_block.theory_spectrum" in names
    assert len(names) > 80


def test_every_public_function_has_numpydoc_sections():
    problems = [p for q, o in _public() for p in _problems(q, o)]
    assert not problems, f"{len(problems)} docstrings lack numpydoc sections:\n" + "\n".join(problems)
