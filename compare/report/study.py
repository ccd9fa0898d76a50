"""What a report study is and what it returns.

A study computes: it runs models or scenes, fits and compares, and returns a :class:`StudyResult` (its
numbers for summary.json, its figures as PNG bytes, its prose and tables as an HTML fragment). It writes no
files and prints nothing. The registry (``compare.report.studies.STUDIES``) lists the studies in page order; the
report runs them (``compare.report.build``) and the writers turn their results into files (``compare.report.html``), as
emcee's sampler computes and its backends store.

A new study is one module ``compare/report/studies/<name>.py`` defining ``STUDY = Study(...)`` and one line in
``compare/report/studies/__init__.py``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

__all__ = ["Figure", "StudyResult", "Study"]


@dataclass(frozen=True)
class Figure:
    """One figure of a study.

    name : file stem under figures/, e.g. "fig13_model_I" (the writer adds ".png").
    png : the PNG bytes.
    caption : what is compared and the verdict in numbers (the writer numbers the figures).
    """
    name: str
    png: bytes
    caption: str


@dataclass(frozen=True)
class StudyResult:
    """What a study returns.

    key : top-level key in summary.json (a key with a "/" nests: "scenarios/asperity_field" goes to
        summary["scenarios"]["asperity_field"]).
    title : section heading; an empty title makes a numbers-only result (summary.json, no section).
    numbers : JSON-able; goes to summary.json[key].
    figures : tuple of :class:`Figure`.
    html : prose and tables, an HTML fragment (no <html>/<body>); ``compare.report.html`` has helpers.
    timings : rows for the report's speed table, dicts with "model", "run", "wall_s" (a string, as shown)
        and "mean_abs_log_ratio" (a string: the band-averaged |ln simulation / reference|, or why none).
    verdicts : tuple of :class:`compare.report.verdict.Verdict`, the rows this study puts in the report's summary
        table (what is compared, the key number with its interval, agrees or not and by how much).
    """
    key: str
    title: str
    numbers: dict
    figures: tuple = ()
    html: str = ""
    timings: tuple = ()
    verdicts: tuple = ()


@dataclass(frozen=True)
class Study:
    """One entry of the registry.

    key : the key of its (first) result.
    label : progress label shown by the CLI.
    run : run(quick, seed) -> StudyResult, or a list of StudyResult. Seeded on its own: the numbers do not
        depend on which process runs it or what runs beside it.
    quick : part of the quick report (``--quick --all-scenes``).
    headline : part of the quick report's default selection (``--quick``): the models and the scenes of the paper's
        three mechanisms (:data:`compare.report.studies.scenes.HEADLINE_SCENES`); the other quick studies join it
        with ``--all-scenes``. The full report runs every study.
    alone : measures speed, so it runs after the others, in the report's own process, with nothing beside it.
    cost : its cost in the full report, in CPU seconds as benchmarks/bench_report.py measures them, so the pool
        hands the longest studies to its workers first and they end together.
    quick_cost : the same in the quick report (default: ``cost``).
    """
    key: str
    label: str
    run: Callable[[bool, int], StudyResult | list]
    quick: bool = True
    headline: bool = True
    alone: bool = False
    cost: float = 1.0
    quick_cost: float | None = None

    def cost_in(self, quick: bool) -> float:
        """Its cost (CPU s) in the quick or full report."""
        return self.quick_cost if quick and self.quick_cost is not None else self.cost
