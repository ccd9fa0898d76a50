"""Model I with ageing (rate-and-state) contacts, :mod:`reduced_models.ageing`, against its linear-response
spectrum (eq. A10 with the slope (f_n / v)(A - B / (1 + i omega D_c / v))), through the registration protocol."""
from __future__ import annotations

from ..study import Study
from .model_check import model_result

__all__ = ["STUDY"]


def _run(quick: bool, seed: int):
    return model_result("model_ageing", seed=seed, duration=300.0 if quick else 900.0)


STUDY = Study("models/model_ageing", "model I with ageing contacts", _run, quick=True, cost=2.0,
              quick_cost=1.0)  # CPU s (benchmarks/bench_report.py)
