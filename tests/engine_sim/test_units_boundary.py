"""The scene's units are converted at its boundary only (DESIGN.md: "converted only at the scene boundary").

The scene works in mm, g and ms; every factor between those and SI is 1e3 or 1e-3 (length, mass, time, stiffness,
acceleration, energy, rate; force, velocity and damping are 1), and every factor is named in ``engine_sim.units``.
A conversion is therefore one of three things in the source, and each is looked for with ``ast`` in every module of
engine_sim (the shipped scenarios' data folder aside: package data and the script that writes an instrument's file
in the instrument's units):

1. a factor of ``engine_sim.units`` named (``U.LENGTH``, ``from .units import MASS``, ...): allowed in units.py only;
2. a call of its converters (``to_scene``, ``to_si``): allowed in the scene's boundary modules only, the builder
   (scene.py: SI in), the recorder (record.py: SI out) and the two renderers (render.py, side_render.py: scene
   geometry labelled in SI); every part reads the values the builder converted for it (``part.own``, ``part.ctx``);
3. a multiplication or division by the literal 1e3, 1000, 1e-3 or 0.001: nowhere, except inside an f-string's
   replacement field, which formats an SI value for a person (``f"{r * 1e3:.3g} mm"``), never a value the scene
   computes with.

What this cannot see: a factor bound to another name first (``k = 1e3`` then ``x * k``) or written as another
expression (``10**3``); no module does that with a unit factor (line_scan names a dimensionless fraction 1e-3 of a
tolerance, ``_FILLED``), and the checker's own test below shows what it catches.
"""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ENGINE = ROOT / "engine_sim"
UNITS_MODULE = ENGINE / "units.py"
BOUNDARY = {ENGINE / n for n in ("scene.py", "record.py", "render.py", "side_render.py")}
SKIP = ENGINE / "scenarios"  # package data and its generator
FACTORS = {"LENGTH", "MASS", "TIME", "STIFFNESS", "ACCEL", "ENERGY", "VELOCITY", "FORCE", "DAMPING"}
CONVERTERS = {"to_scene", "to_si", "scene_values"}
LITERALS = {1e3, 1e-3}  # 1000 == 1e3 and 0.001 == 1e-3 compare equal


def _units_aliases(tree) -> set:
    """Names bound to the module engine_sim.units (``from . import units as U``, ``import engine_sim.units as u``)."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            for a in node.names:
                if a.name == "units" and (node.level or node.module == "engine_sim"):
                    names.add(a.asname or a.name)
        elif isinstance(node, ast.Import):
            names |= {a.asname for a in node.names if a.name == "engine_sim.units" and a.asname}
    return names


def conversions(source: str, boundary: bool = False) -> list:
    """(line, what) of each conversion in ``source`` outside the unit module (rules 1-3 of the module docstring);
    ``boundary``: the module is one of the scene's boundary modules, which may call the converters."""
    tree = ast.parse(source)
    aliases = _units_aliases(tree)
    in_fstring = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FormattedValue):
            in_fstring |= {id(n) for n in ast.walk(node.value)}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[-1] == "units":
            found += [(node.lineno, f"imports {a.name}") for a in node.names if a.name in FACTORS | CONVERTERS]
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
            if node.attr in FACTORS:
                found.append((node.lineno, f"factor {node.value.id}.{node.attr}"))
            elif node.attr in CONVERTERS and not boundary:
                found.append((node.lineno, f"converter {node.value.id}.{node.attr} outside the boundary"))
        elif isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)) and id(node) not in in_fstring:
            for side in (node.left, node.right):
                if isinstance(side, ast.Constant) and type(side.value) in (int, float) and side.value in LITERALS:
                    found.append((node.lineno, f"literal factor {side.value!r}"))
    return sorted(found)


def _engine_modules():
    return [p for p in sorted(ENGINE.rglob("*.py")) if p != UNITS_MODULE and SKIP not in p.parents]


def test_no_conversion_outside_the_unit_module():
    bad = [f"{p.relative_to(ROOT)}:{line}: {what}" for p in _engine_modules()
           for line, what in conversions(p.read_text(encoding="utf-8"), p in BOUNDARY)]
    assert not bad, "mm-g-ms conversions outside engine_sim/units.py:\n" + "\n".join(bad)


def test_the_checker_finds_each_kind_of_conversion():
    """Each rule flags its conversion and passes its allowed form (a test of the test above)."""
    src = ("from .. import units as U\n"
           "a = r * U.LENGTH\n"            # rule 1
           "b = U.to_scene(r, 'length')\n"  # rule 2 (outside the boundary)
           "c = 1e3 * r\n"                 # rule 3
           "d = r / 1000\n"                # rule 3, written as an int
           "e = f'{r * 1e3:.3g} mm'\n"     # allowed: SI formatted for a person
           "g = 1e-3\n")                   # allowed: a value, not a factor applied
    assert [line for line, _ in conversions(src)] == [2, 3, 4, 5]
    assert [line for line, _ in conversions(src, boundary=True)] == [2, 4, 5]
    assert conversions("from engine_sim.units import LENGTH\n") == [(1, "imports LENGTH")]


def test_the_unit_module_round_trips_every_dimension():
    """to_si inverts to_scene for every dimension (to 1 ulp: x * 1e3 / 1e3 need not be x), and the factors are the
    mm-g-ms ones: 1 N = 1 g mm/ms^2, 1 m/s = 1 mm/ms, 1 J = 1e3 N mm, 1 N/m = 1e-3 N/mm, 1/s = 1e-3 /ms."""
    import math

    from engine_sim import units as U

    expect = {"length": 1e3, "mass": 1e3, "time": 1e3, "rate": 1e-3, "stiffness": 1e-3, "acceleration": 1e-3,
              "energy": 1e3, "velocity": 1.0, "force": 1.0, "damping": 1.0}
    assert set(expect) == set(U.DIMENSIONS)
    for dim, f in expect.items():
        assert U.to_scene(0.37, dim) == 0.37 * f if dim != "rate" else U.to_scene(0.37, dim) == 0.37 / 1e3
        assert math.isclose(U.to_si(U.to_scene(0.37, dim), dim), 0.37, rel_tol=2.3e-16)


def test_each_part_reads_its_own_values_and_context_in_scene_units():
    """The builder hands every part of a scene its declared fields converted once (a pad's radius 0.3e-3 m reads
    0.3 mm, its k0 3333 N/m reads 3.333 N/mm) and one shared context; neither can be changed."""
    import pytest

    from engine_sim import Scene, load_scenario
    from engine_sim import units as U

    sc = load_scenario("pads_multiscale")
    scene = Scene(sc, seed=0)
    arr = scene.arrangement
    assert arr.own.radius == U.to_scene(sc.pads.radius, "length") and arr.own.k0 == U.to_scene(sc.pads.k0, "stiffness")
    assert arr.micro_substrate.own.a == U.to_scene(sc.pads.micro_a, "length")  # the micro-tracks' own substrate
    parts = [scene.substrate, arr, scene.law, scene.drive, scene.wear, arr.micro_substrate]
    assert all(p.ctx is scene.substrate.ctx for p in parts)
    assert scene.substrate.ctx.pad_radius == U.to_scene(sc.pads.radius, "length")
    with pytest.raises(AttributeError, match="immutable"):
        arr.own.radius = 1.0
    with pytest.raises(AttributeError, match="no scene value"):
        arr.ctx.block_mass
