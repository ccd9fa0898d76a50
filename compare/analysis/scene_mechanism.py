"""A scene judged by the identification machinery: the spectral family's parameters the scene was built with (its
scenario's values) against those fitted from its trace (:func:`compare.analysis.identify.identify`).

A scene of pads on friction-patch tracks is built as model I (section 3): its family point takes the renewal length
a and the patches' spread alpha from the scenario's substrate, the pads' number, stiffness and mass and the block's
mass from the scenario, the friction slope c from its law and f_kin as the mean tangential pad force (the law's
mu0 times the mean load per pad, measured from the trace; :func:`compare.analysis.extract.model_I_parameters`). An
asperity field is built as model III (section 6), its contact statistics from the trace
(:func:`compare.analysis.extract.model_III_parameters`). Other scenes (wear particles, rough profiles) declare no
family point: their ranking is reported without a comparison.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .families import FAMILIES

__all__ = ["built_point", "judge"]


def built_point(trace):
    """The family point a scene was built as.

    Parameters
    ----------
    trace : engine_sim trace
        A scene's trace with its description (``metadata["scene"]``).

    Returns
    -------
    (str, dict, float) or None
        (model, theta, v): the registered model, its family's parameters (their units,
        :data:`compare.analysis.families.FAMILIES`) and the mean sliding speed (m/s); None for a scene built as no
        registered model.
    """
    from .extract import (asperity_force_params, model_I_parameters, model_III_parameters, scene_info,
                          spring_block_params)

    info = scene_info(trace)
    kind = info.get("substrate", {}).get("kind")
    grains = (info.get("grain_step") or {}).get("m_grain") is not None  # wear particles on the tracks
    if kind == "patches" and not grains and info.get("contact_width", 0.0) == 0.0:
        ex = model_I_parameters(trace)
        p = spring_block_params(ex)
        p = replace(p, a=ex["a"]["substrate_value"], alpha=ex["alpha"]["substrate_value"])
        theta, v = FAMILIES["model_I"].from_model(p)
        return "model_I", theta, v
    if info.get("contact_width", 0.0) > 0:  # a sole of feet on an asperity field
        ex = model_III_parameters(trace)
        theta, v = FAMILIES["model_III"].from_model(asperity_force_params(ex))
        return "model_III", theta, v
    return None


def judge(trace, ranking=None) -> dict:
    """The ranking of a scene's trace and, where the scene was built as a registered model, its parameters against
    the fitted ones.

    Parameters
    ----------
    trace : engine_sim trace
        A scene's trace (``t`` in s, ``x`` in m) with its description.
    ranking : list of Mechanism, optional
        Its ranking, if already computed; :func:`compare.analysis.identify.identify` otherwise.

    Returns
    -------
    dict
        ``best`` (the first model) and ``verdict``; ``built_as`` (model or None); ``rank`` and ``built_verdict``
        (that model's place, from 1, and verdict); ``parameters``: name -> {``built``, ``fitted``, ``half_width``,
        ``within``} for the built model's identified parameters (``fitted`` "not identified" otherwise), and
        ``cannot_separate``.
    """
    from .identify import identify

    t = np.asarray(trace.t, dtype=float)
    dt = float(np.median(np.diff(t)))
    v_rec = float((trace.x[-1] - trace.x[0]) / (t[-1] - t[0]))
    if ranking is None:
        ranking = identify(trace.x, dt, v_rec)
    out = {"best": ranking[0].model if ranking else None, "verdict": ranking[0].verdict if ranking else None,
           "built_as": None, "rank": None, "built_verdict": None, "parameters": {}, "cannot_separate": ""}
    point = built_point(trace)
    if point is None or not ranking:
        return out
    model, theta, _ = point
    out["built_as"] = model
    k, mine = next((i, m) for i, m in enumerate(ranking) if m.model == model)
    out["rank"], out["built_verdict"] = k + 1, mine.verdict
    out["cannot_separate"] = FAMILIES[model].cannot_separate
    for name, got in mine.parameters.items():
        if isinstance(got, str):
            out["parameters"][name] = {"built": float(theta[name]), "fitted": got, "half_width": None, "within": None}
            continue
        value, half, _ = got
        iv = mine.fit.intervals[name]
        out["parameters"][name] = {"built": float(theta[name]), "fitted": float(value), "half_width": float(half),
                                   "within": bool(iv[0] <= theta[name] <= iv[1])}
    return out
