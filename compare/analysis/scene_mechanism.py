"""A scene judged by the identification machinery: the spectral family's parameters the scene was built with (its
scenario's values) against those fitted from its trace (:func:`compare.analysis.identify.identify`).

A scene of pads on friction-patch tracks is built as model I (section 3): its family point takes the renewal length
a and the patches' spread alpha from the scenario's substrate, the pads' number, stiffness and mass and the block's
mass from the scenario, the friction slope c from its law and f_kin as the mean tangential pad force (the law's
mu0 times the mean load per pad, measured from the trace; :func:`compare.analysis.extract.model_I_parameters`). An
asperity field is built as model III (section 6), its contact statistics from the trace
(:func:`compare.analysis.extract.model_III_parameters`). Other scenes (wear particles, rough profiles) declare no
family point: their ranking is reported without a comparison.

A patch scene's level L is built from the substrate's nominal spread alpha: the ensemble's mean. A record holds its
own patches (N T v / a of them), whose spread scatters about alpha, and its periodogram scatters about its mean;
the level's interval holds both (:func:`compare.analysis.family_fit.segments_of`). :func:`level_checks` measures,
without a fit, what the built level rests on: the record's own spread (sqrt(12) rms / f_kin of the pad forces,
eq. A7), the friction slope the block answers with (its velocity against the summed pad force below the
resonance, where model I gives dv = F / (N c)), and the record's periodogram over the built spectrum on the band
between the renewal corner and the resonance.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from .families import FAMILIES

__all__ = ["built_point", "judge", "level_checks"]


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


def level_checks(trace, theta: dict, v: float) -> dict:
    """What a patch scene's built model I level rests on, measured on its trace without a fit (module docstring).

    Parameters
    ----------
    trace : engine_sim trace
        A patch scene's trace: ``t`` (s), ``x`` (m), ``pad_force`` (N, samples x pads), its description.
    theta : dict
        The model I family point it was built as (:func:`built_point`).
    v : float
        Its mean sliding speed (Units: m/s).

    Returns
    -------
    dict
        ``alpha``: {``built``, ``trace``} the patches' spread, the substrate's and the record's own (sqrt(12) rms
        of the pad forces over their mean, eq. A7); ``level_trace_alpha``: the built level with the record's own
        spread, L alpha_trace^2 / alpha_built^2 (Units: m^2 s^-3); ``slope``: {``built``, ``trace``} N c (N s/m),
        the law's and the one the block answers with (the block's velocity, averaged over 50 / omega_c, regressed
        on the summed pad force: dv = -F / (N c) below the resonance); ``level_ratio``: {``band`` (rad/s),
        ``ratio``, ``se``}: the mean over the band [2 v / a, omega_c / 2] of the twice-differenced periodogram over
        the built spectrum (1 where the record stands at its built level), and its standard error (the ordinates'
        scatter over the square root of their number).
    """
    from .extract import model_I_parameters
    from .family_fit import record_for

    ex = model_I_parameters(trace)
    alpha_b = float(ex["alpha"]["substrate_value"])
    alpha_t = float(ex["alpha"]["value"])
    t = np.asarray(trace.t, dtype=float)
    x = np.asarray(trace.x, dtype=float)
    dt = float(np.median(np.diff(t)))
    # the block's mean velocity over blocks of 50 / omega_c, against the summed pad force over the same blocks
    k = max(1, int(round(50.0 / (theta["omega_c"] * dt))))
    n = (len(x) - 1) // k
    vel = np.diff(x[:n * k + 1:k]) / (k * dt)
    F = np.asarray(trace.pad_force, dtype=float).sum(axis=1)[:n * k].reshape(n, k).mean(axis=1)
    vel, F = vel - vel.mean(), F - F.mean()
    Nc_trace = float(abs(np.dot(F, F) / np.dot(vel, F)))
    Nc_built = float(ex["N"]["value"] * ex["c"]["value"])
    rec = record_for(x, dt)
    lo, hi = 2.0 * v / theta["a"], theta["omega_c"] / 2.0
    w = rec.omega
    keep = (w >= lo) & (w <= hi)
    gain = np.abs(2.0 * np.sin(w[keep] * dt / 2.0) / dt) ** (2 * rec.order)
    r = rec.periodogram[keep] / (gain * FAMILIES["model_I"].spectrum(theta, w[keep], v))
    return {"alpha": {"built": alpha_b, "trace": alpha_t},
            "level_trace_alpha": float(theta["L"] * (alpha_t / alpha_b) ** 2),
            "slope": {"built": Nc_built, "trace": Nc_trace},
            "level_ratio": {"band": [float(lo), float(hi)], "ratio": float(np.mean(r)),
                            "se": float(np.std(r) / np.sqrt(len(r)))}}


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
        ``within``} for the built model's identified parameters (``fitted`` "not identified" otherwise),
        ``cannot_separate``, and for a scene built as model I ``checks`` (:func:`level_checks`, with
        ``within_trace_alpha``: whether the fitted level's interval holds the built level at the record's own
        spread; None where L is not identified).
    """
    from .identify import identify

    t = np.asarray(trace.t, dtype=float)
    dt = float(np.median(np.diff(t)))
    v_rec = float((trace.x[-1] - trace.x[0]) / (t[-1] - t[0]))
    if ranking is None:
        ranking = identify(x=trace.x, dt=dt, v=v_rec)
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
    if model == "model_I":
        checks = level_checks(trace, theta, point[2])
        iv = mine.fit.intervals.get("L")
        checks["within_trace_alpha"] = None if iv is None else bool(iv[0] <= checks["level_trace_alpha"] <= iv[1])
        out["checks"] = checks
    return out
