"""Parameter sweeps: a grid over the parameters and seeds of a registered reduced model or a scenario, run serially
or on dask.distributed, with per-task results cached on disk.

:mod:`.spec` reads and checks a sweep file, :mod:`.tasks` runs one grid point, :mod:`.run` schedules the tasks and
reads their stored results. The velocity analysis of a sweep's results is :mod:`compare.analysis.velocity`'s.
"""
from ..analysis.velocity import velocity_analysis
from .run import SchedulerError, load_results, run_sweep
from .spec import SweepError, SweepSpec, build_point, expand, load_sweep, task_id
from .tasks import run_task

__all__ = ["SweepSpec", "SweepError", "SchedulerError", "load_sweep", "expand", "task_id", "build_point", "run_task",
           "run_sweep", "load_results", "velocity_analysis"]
