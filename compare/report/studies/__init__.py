"""The report's studies, in page order. A study is one module defining ``STUDY`` (see ``compare.report.study``);
the scenes contribute one study per shipped scenario."""
from __future__ import annotations

from . import model_I, model_II, model_III, model_ageing, multiscale, scene_rough_multiscale, work_precision
from .scenes import METHOD_STUDY, scene_studies

__all__ = ["STUDIES", "selected"]

STUDIES = [model_I.STUDY, multiscale.STUDY, model_III.STUDY, model_II.STUDY, model_ageing.STUDY, METHOD_STUDY,
           *scene_studies(), scene_rough_multiscale.STUDY, work_precision.STUDY]


def selected(quick: bool, all_scenes: bool = False) -> list:
    """The studies of a report, in page order: the full report runs them all; the quick one its headline studies
    (the models and the scenes of the paper's three mechanisms), or every quick study with ``all_scenes``."""
    if not quick:
        return list(STUDIES)
    return [s for s in STUDIES if s.quick and (s.headline or all_scenes)]
