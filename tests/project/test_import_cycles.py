"""No import cycle anywhere in the project: the module import graph of every package (grimp, the graph
import-linter reads; imports inside functions count, for a lazy import ties two modules together as firmly as one at
the top) has no strongly connected component of more than one module (Tarjan's algorithm). A failure names each
cycle: its modules, and each import between them with its file, line and text, so it can be cut along a concept.

A package family keeps its base in a module of its own (``engine_sim/laws/law.py``: the spec, the base class and the
registry) that the package's ``__init__`` re-exports beside importing the shipped kinds; a kind imports the base
module, never the package, which would close a cycle through the ``__init__``."""
import importlib
import textwrap
from pathlib import Path

import grimp

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("engine_sim", "reduced_models", "compare", "frictionnoise", "benchmarks")  # a package joins by its name


def import_cycles(graph) -> list:
    """The strongly connected components of ``graph`` (a grimp ImportGraph) with more than one module, each sorted,
    in the order of their first module (Tarjan's algorithm, iterative: no recursion limit on a long chain)."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    succ = {m: sorted(graph.find_modules_directly_imported_by(m)) for m in graph.modules}
    for root in sorted(succ):
        if root in index:
            continue
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        work = [(root, iter(succ[root]))]
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(succ.get(w, ()))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return sorted(out)


def describe(graph, cycle) -> str:
    """A cycle in words: its modules, then every import between two of them, one line each (the first line of the
    file that makes it: ``importer -> imported  (line N: text)``)."""
    members = set(cycle)
    lines = [f"cycle of {len(cycle)} modules: {', '.join(cycle)}"]
    for m in cycle:
        for t in sorted(graph.find_modules_directly_imported_by(m) & members):
            details = sorted(graph.get_import_details(importer=m, imported=t), key=lambda d: d["line_number"])
            where = f"line {details[0]['line_number']}: {details[0]['line_contents']}" if details else "no line"
            lines.append(f"  {m} -> {t}  ({where})")
    return "\n".join(lines)


def test_no_import_cycle_in_the_project(monkeypatch):
    monkeypatch.syspath_prepend(str(ROOT))  # benchmarks/ is not installed: read from the checkout
    graph = grimp.build_graph(*PACKAGES, cache_dir=None)
    assert len(graph.modules) > 200  # every package read (about 210 modules)
    cycles = import_cycles(graph)
    assert not cycles, f"{len(cycles)} import cycles:\n" + "\n".join(describe(graph, c) for c in cycles)


def test_the_finder_names_a_cycle_through_a_package_init_and_a_lazy_import(tmp_path, monkeypatch):
    """The shape the project's families had: a package whose ``__init__`` holds the base and imports its kinds at
    the bottom, a kind importing the base from the package; and two modules tied by an import inside a function.
    Both are found, with their lines; a module that only imports into a cycle is not part of it."""
    pkg = tmp_path / "cyclepkg"
    (pkg / "family").mkdir(parents=True)
    files = {
        "__init__.py": "",
        "family/__init__.py": "class Base:\n    pass\n\n\nfrom . import kind  # noqa\n",
        "family/kind.py": "from . import Base\n\n\nclass Kind(Base):\n    pass\n",
        "a.py": "def f():\n    from .b import g\n    return g\n",
        "b.py": "from .a import f\n\n\ndef g():\n    return f\n",
        "user.py": "from .family import Base\nfrom .a import f\n",
    }
    for name, text in files.items():
        (pkg / name).write_text(textwrap.dedent(text))
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.invalidate_caches()
    graph = grimp.build_graph("cyclepkg", cache_dir=None)
    cycles = import_cycles(graph)
    assert cycles == [["cyclepkg.a", "cyclepkg.b"], ["cyclepkg.family", "cyclepkg.family.kind"]]
    text = describe(graph, cycles[0])
    assert "cyclepkg.a -> cyclepkg.b  (line 2: from .b import g)" in text
    assert "cyclepkg.b -> cyclepkg.a  (line 1: from .a import f)" in text
    text = describe(graph, cycles[1])
    assert "cyclepkg.family.kind -> cyclepkg.family  (line 1: from . import Base)" in text
    assert "cyclepkg.family -> cyclepkg.family.kind  (line 5: from . import kind  # noqa)" in text


def test_the_finder_on_a_graph_built_by_hand():
    """Tarjan's components against ones read off by eye: a -> b -> c -> a and c -> d -> e -> d, f -> a: two
    cycles ({a, b, c}, {d, e}); f, which only reaches them, and a module importing nothing are in none."""
    graph = grimp.ImportGraph()
    for importer, imported in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d"), ("d", "e"), ("e", "d"), ("f", "a")]:
        graph.add_import(importer=importer, imported=imported, line_number=1, line_contents=f"import {imported}")
    graph.add_module("g")
    assert import_cycles(graph) == [["a", "b", "c"], ["d", "e"]]
