"""The `frictionnoise report` job: run the registered studies (``compare.report.studies.STUDIES``), in worker
processes when asked, and gather their results; ``compare.report.html`` writes them.

:func:`build_report` computes (no files); :func:`compare.report.html.write_report` writes index.html, summary.json and
figures/ atomically.
"""
from __future__ import annotations

import time

from frictionnoise.base import package_version

from .html import paragraphs, summary_of, table
from .study import StudyResult

__all__ = ["build_report", "build_scene_report", "build_model_report", "run_studies", "pool_order"]

CONVENTIONS = "C(omega) two-sided in angular frequency, eq. (2); gamma_err = 95 % half-width"


def _run_study(study, quick: bool, seed: int):
    """(results, wall seconds, CPU seconds) of one study. Module-level, so a worker process can run it: every study
    draws its own seeded random numbers, so where it runs does not change it."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = study.run(quick, seed)
    return (list(out) if isinstance(out, (list, tuple)) else [out]), time.perf_counter() - t0, time.process_time() - c0


def pool_order(studies, quick: bool) -> list:
    """Indices of ``studies`` in the order the pool starts them: the costliest first (``Study.cost_in``, CPU s in the
    quick or full report), so that on two workers the longest runs do not start last and the workers end together."""
    return sorted(range(len(studies)), key=lambda i: -studies[i].cost_in(quick))


def run_studies(studies, quick: bool, seed: int, workers: int = 1, progress=None, on_compile=None,
                seconds=None) -> list:
    """Results of each study (a list of StudyResult per study), in the given order.

    With workers > 1 they run in that many worker processes (:func:`compare.report.pool.process_pool`), the
    costliest first (``Study.cost_in``). ``progress(label, event, wall)`` is called with event "start" when a study
    starts (in a pool: when a worker takes it, from the pool's first-in first-out order) and "done" when it has
    finished (wall: its own seconds; None at "start"). ``on_compile()`` is called once when numba first compiles
    in a worker process. ``seconds``, a dict, receives {label: {"wall_s", "cpu_s"}} of each study (CPU: its own
    process's, user + system)."""
    progress = progress or (lambda label, event, wall=None: None)
    seconds = {} if seconds is None else seconds
    if workers <= 1 or len(studies) <= 1:
        out = []
        for st in studies:
            progress(st.label, "start", None)
            res, wall, cpu = _run_study(st, quick, seed)
            out.append(res)
            seconds[st.label] = {"wall_s": wall, "cpu_s": cpu}
            progress(st.label, "done", wall)
        return out
    from concurrent.futures import as_completed

    from .pool import process_pool

    with process_pool(workers, on_compile) as pool:  # on Ctrl-C or an error its processes end at once
        order = pool_order(studies, quick)
        futures = {pool.submit(_run_study, studies[i], quick, seed): i for i in order}
        queue = list(order)
        for i in queue[:workers]:
            progress(studies[i].label, "start", None)
        started = min(workers, len(queue))
        out = [None] * len(studies)
        for fut in as_completed(futures):
            i = futures[fut]
            out[i], wall, cpu = fut.result()
            seconds[studies[i].label] = {"wall_s": wall, "cpu_s": cpu}
            progress(studies[i].label, "done", wall)
            if started < len(queue):
                progress(studies[queue[started]].label, "start", None)
                started += 1
    return out


def _row(r: dict) -> list:
    """A speed-table row as text (n/a where a number is None)."""
    fmt = lambda v: "n/a" if v is None else v if isinstance(v, str) else f"{v:.4g}"
    return [r["model"], r["run"], fmt(r["wall_s"]), fmt(r["mean_abs_log_ratio"])]


def _speed(rows: list, title: str, note: str) -> StudyResult:
    return StudyResult("timings", title, rows, html=(paragraphs([note]) if note else "") + table(
        "Runs in this report", ["model", "run", "wall (s)", "mean |ln ratio|"],
        [_row(r) for r in rows]))


def build_report(quick: bool = False, seed: int = 0, progress=None, workers: int = 1, studies=None,
                 on_compile=None, all_scenes: bool = False):
    """Run every study and gather the results. Returns (results, summary): a list of StudyResult in page order
    and the dict for summary.json.

    ``studies`` defaults to the registry's selection for ``quick`` and ``all_scenes``. ``workers`` > 1 runs them in that many
    processes (identical numbers: each study is seeded on its own); studies marked ``alone`` (they measure
    speed) run afterwards in this process. ``progress`` and ``on_compile`` as in :func:`run_studies`."""
    from . import studies as registry

    studies = registry.selected(quick, all_scenes) if studies is None else list(studies)
    header = {"version": package_version(), "quick": quick, "all_scenes": not quick or all_scenes, "seed": seed, "workers": workers,
              "conventions": CONVENTIONS, "scenarios": {}}
    t0 = time.perf_counter()
    pooled = [s for s in studies if not s.alone]
    alone = [s for s in studies if s.alone]
    seconds: dict = {}
    results = [r for rs in run_studies(pooled, quick, seed, workers, progress, on_compile, seconds) for r in rs]
    speed = _speed([t for r in results for t in r.timings], "Speed against error",
        "Wall time of each run in this report (after JIT warm-up) and its band-averaged |ln(simulation / exact "
        "theory)|, which for the exact reduced-model simulators is sampling noise; for the scenes it is the "
        "distance to model I built from the scene's measured parameters. The explicit baseline for model I, the "
        "engine's loop overhead and the work-precision tables are in benchmarks/ (see the README)."
        + (f" The runs ran {workers} at a time, each in its own process." if workers > 1 else ""))
    alone_results = [r for rs in run_studies(alone, quick, seed, 1, progress, seconds=seconds) for r in rs]
    # page: the studies, the speed table, then the studies that ran alone; summary.json: the speed table last
    summary = summary_of(results + alone_results + [speed], header)
    summary["total_wall_s"] = time.perf_counter() - t0
    summary["study_seconds"] = seconds  # where the time went: each study's wall and CPU seconds
    return results + [speed] + alone_results, summary


def build_scene_report(sc, trace=None, duration=None, seed=None, progress=None, band=None):
    """Results and summary for one scene (``frictionnoise compare``); ``band`` (rad/s) replaces the fit band."""
    from .studies.scenes import scene_result

    header = {"version": package_version(), "quick": False, "seed": seed if seed is not None else sc.run.seed,
              "conventions": CONVENTIONS, "scenarios": {}}
    extra = []
    if sc.arrangement_part.also_fits:  # e.g. micro-pads: model Ib beside model I, on the same trace (as the report)
        from .studies.scenes import beside_results, run_scene

        trace = run_scene(sc, False, header["seed"], trace, duration, progress)[0]
        extra = beside_results(sc, header["seed"], trace)
    res = scene_result(sc.name, sc, False, header["seed"], trace=trace, duration=duration, progress=progress,
                       band=band)
    speed = StudyResult("timings", "Speed", list(res.timings), html=table(
        "Run", ["what", "run", "wall (s)", "mean |ln ratio| vs model I"],
        [_row(r) for r in res.timings]))
    results = [res, *extra, speed]
    return results, summary_of(results, header)


def build_model_report(name: str, seed: int = 0, duration: float | None = None):
    """Results and summary for one registered reduced model against its closed form (``frictionnoise compare
    MODEL``)."""
    from .studies.model_check import model_result

    header = {"version": package_version(), "quick": False, "seed": seed, "conventions": CONVENTIONS}
    res = model_result(name, seed=seed, duration=duration)
    speed = StudyResult("timings", "Speed", list(res.timings), html=table(
        "Run", ["what", "run", "wall (s)", "mean |ln ratio| vs closed form"], [_row(r) for r in res.timings]))
    results = [res, speed]
    return results, summary_of(results, header)
