"""The project's modules, found from its package folders (so a new module is covered without a list to keep)."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("frictionnoise", "engine_sim", "reduced_models", "compare")


def project_modules() -> dict:
    """Module name -> source path of every module in the project's packages."""
    out = {}
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            if not (path.parent / "__init__.py").exists():
                continue  # a script beside package data (engine_sim/scenarios/data/make_reciprocating.py), not a module
            if path.relative_to(ROOT).parts[:2] == ("compare", "studies"):
                continue  # the research studies: not installed, run by their smokes in CI (.ci/run)
            if path.name == "__main__.py":
                continue  # `python -m package`: importing it runs the program
            parts = path.relative_to(ROOT).with_suffix("").parts
            out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out
