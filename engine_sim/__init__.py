"""The pymunk scene: a block on spring-mounted pads sliding over random substrate tracks.

``run(scenario, duration=None, seed=None)`` returns an :class:`EngineTrace` in SI units; scenarios are
TOML files (the shipped ones in ``engine_sim/scenarios/``) or :class:`Scenario` objects. The scene works in mm, g,
ms internally (``engine_sim.units``) and converts only at its boundary. Whatever steps a :class:`Scene` steps it with
:class:`Loop` (sample, maintenance, pymunk steps per output step).
"""
from .loop import Loop
from .record import EngineTrace
from .run import run
from .scenario import Scenario, ScenarioError, load_scenario, scenario_from_dict, shipped_scenarios
from .scene import Scene

__all__ = ["run", "EngineTrace", "Scenario", "ScenarioError", "load_scenario", "scenario_from_dict",
           "shipped_scenarios", "Scene", "Loop"]
