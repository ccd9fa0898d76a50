"""Any registered reduced model against its own closed form: ``frictionnoise compare MODEL``.

The model is read from ``reduced_models.MODELS`` and used only through the registration protocol (its ``PARAMS``
defaults, ``default_duration``, ``default_dt_out``, ``simulate``, ``theory_spectrum``, ``fit_band``, ``RESPONSE``),
so a newly registered model is compared with no edit here: the simulated C_x is fitted over the model's band and
divided, band by band, by the closed form.
"""
from __future__ import annotations

import math

import numpy as np

from ...analysis.spectra import displacement_spectrum
from ..html import esc, paragraphs, span, table
from ..verdict import fit_text, ratio_verdict
from ...analysis.fits import flag_mark
from ..study import Figure, StudyResult
from ._common import band_ratios, log_err, ratio_range, ratio_rows, record_fit, timed, timing

__all__ = ["model_result", "N_BANDS"]

N_BANDS = 6  # log bands of the per-band ratio simulation / closed form


def _ratio_edges(spec, band) -> np.ndarray:
    """Log band edges over the fit band, or over the resolved range below a quarter of the Nyquist frequency when
    the model names none (rad/s)."""
    lo, hi = band if band is not None else (4 * spec.omega_min, spec.omega_max / 4)
    return np.geomspace(max(lo, 2 * spec.omega_min), min(hi, spec.omega_max / 2), N_BANDS + 1)


def model_result(name: str, seed: int = 0, duration: float | None = None, params=None) -> StudyResult:
    """The registered model ``name`` (its ``PARAMS.reference()`` case, or its ``PARAMS()`` defaults where it has
    none, unless ``params``) run for ``duration`` seconds
    (default: its ``default_duration``) at its ``default_dt_out``, against its closed form ``theory_spectrum``.

    Returns a StudyResult under ``models/<name>`` with gamma over the model's fit band (the automatic band when
    it names none, or when its band has closed), the per-band ratios simulation / closed form and the run's wall
    time. Raises KeyError naming the registered models for an unknown ``name``."""
    from reduced_models import model as registered

    from .. import plots

    model = registered(name)
    p = params if params is not None else getattr(model.PARAMS, "reference", model.PARAMS)()
    dt_out = model.default_dt_out(p)
    T = float(duration if duration is not None else model.default_duration(p))
    tr, wall = timed(model.simulate, p, T, dt_out, seed=seed)
    spec = displacement_spectrum(tr.t, tr.x)
    band = model.fit_band(p, dt_out)
    if band is not None and not band[1] >= 2 * band[0]:
        band = None  # the model's band has closed: the automatic one
    fit = record_fit(tr.t, tr.x, band=band, stationarity=False)  # exact simulator: stationary by construction
    edges = _ratio_edges(spec, band)
    ratios = band_ratios(spec, model.theory_spectrum(p, spec.omega), edges)
    worst = max(abs(math.log(b["ratio"])) for b in ratios)
    numbers = {**fit.to_dict(), "model": name, "response": model.RESPONSE, "duration_s": T, "dt_out_s": dt_out,
               "seed": seed, "wall_s": wall, "band_ratios_vs_closed_form": ratios, "worst_abs_log_ratio": worst,
               "params": p.to_dict()}
    w = np.geomspace(spec.omega_min, spec.omega_max, 300)
    fig = plots.spectrum_figure([(spec, f"{name} simulated, {T:g} s")], [(w, model.theory_spectrum(p, w),
                                                                          f"{name} closed form")],
                                fits=[(fit, "")], band=band, title=f"{name} against its closed form")
    caption = (f"{name} simulated for {T:g} s (seed {seed}) against its closed form; per-band ratio "
               f"{ratio_range(ratios)} over {span(edges[0], edges[-1])} rad/s; gamma = {fit.gamma:.2f} ± "
               f"{fit.gamma_err:.2f}{flag_mark(fit)} over the shaded band.")
    where = f"{span(band[0], band[1])} rad/s (the model's band)" if band else (
        f"{span(fit.band[0], fit.band[1])} rad/s (the automatic band: the model names none)")
    text = paragraphs([
        f"Model {esc(name)} ({esc(model.__name__)}), its reference parameters (summary.json: params), {T:g} s simulated at dt_out = "
        f"{dt_out:.3g} s in {wall:.2f} s; response {esc(model.RESPONSE)}.",
        f"gamma = {fit_text(fit, 3)} over {where}. Simulated C_x over the closed form, "
        f"per log band: {ratio_range(ratios)} (worst |ln ratio| {worst:.3f}).",
    ]) + table(f"C_x({name} simulated) / C_x(closed form), per log band", ["band (rad/s)", "ratio"],
               ratio_rows(ratios))
    return StudyResult(f"models/{name}", f"{name} against its closed form", numbers,
                       (Figure(f"model_{name}", plots.figure_png_bytes(fig), caption),), text,
                       (timing(name, f"{T:g} s, dt_out = {dt_out:.3g} s", f"{wall:.3f}", f"{log_err(ratios):.3f}"),),
                       (ratio_verdict(f"models/{name}", "C_x / its closed form", ratios, 1.25, "1 (closed form)"),))
