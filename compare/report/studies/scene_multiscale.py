"""Study: the scene ``pads_multiscale`` (pads carrying micro-pads on micro-tracks) against model Ib built from its
own measured parameters; and :func:`multiscale_parameters`, which builds them from a trace.

Procedure (:func:`multiscale_parameters`, stated in the report as here):

- the macro level is model I's extraction (``compare.analysis.extract.model_I_parameters``: N, v, a from the pad forces'
  correlation length, f_kin and alpha from their mean and rms, the law's slope c, k0, m, eta0 = c0 / m, M);
- the micro level's layout comes from ``metadata["scene"]["micro"]``: n micro-pads per pad, m2 = their mass,
  k2 = the micro spring, eta2 = its damping / m2, a2 = the micro length scale, eta3 = the micro friction law's
  slope dF/dv at the measured speed / m2;
- what the metadata cannot give is measured from the recorded micro-pad forces (``trace.micro_force``, samples x
  columns, each column the tangential force of one micro-pad or the sum over one pad's n micro-pads) with
  :func:`reduced_models.multiscale_fit.renewal_statistics` on the sum over all N n micro-pads: f_kin2 = its mean /
  (N n), alpha2 f_kin2 = sqrt(12 Var / (N n)) (eq. A7), and a2 measured = (12/7) x its correlation length in sliding
  distance, reported beside the scenario's a2 (the model uses the scenario's);
- F_drive from steady sliding, N (f_kin + c v) + N n (f_kin2 + c2 v), with eta1 = c / m.

The procedure is tested on an exact case (tests/reduced_models/test_multiscale_fit.py): model Ib simulations with known
parameters give back alpha2 and a2 within their statistical tolerance.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_models import multiscale as ms
from reduced_models.multiscale_fit import renewal_statistics

from ..html import esc, paragraphs, rst_inline, span, table
from ..verdict import fit_text, ratio_verdict
from ..study import Study, StudyResult
from ._common import param_rows

__all__ = ["STUDY", "run", "multiscale_parameters", "multiscale_params", "NAME"]

NAME = "pads_multiscale"
PROCEDURE = __doc__.split("stated in the report as here):")[1].split("The procedure is")[0]


def multiscale_parameters(trace, scenario=None) -> dict:
    """Model Ib's parameters of a ``pads_multiscale`` trace: model I's (``compare.analysis.extract``) plus the micro level,
    {name: {"value", "unit", "provenance", ...}} (module docstring). Raises ValueError naming what is missing."""
    from ...analysis.extract import friction_slope, model_I_parameters, scene_info

    info = scene_info(trace, scenario)
    micro = info.get("micro")
    if not micro:
        raise ValueError("metadata['scene'] has no 'micro' entry: not a scene with micro-pads")
    rec = getattr(trace, "micro_force", None)
    if rec is None:
        raise ValueError("the trace records no micro_force (tangential force of the micro-pads)")
    ex = model_I_parameters(trace, scenario)
    N = max(1, int(round(ex["N"]["value"])))
    n = int(micro["n"])
    rec = np.asarray(rec, dtype=float)
    rec = rec[:, None] if rec.ndim == 1 else rec
    lv = renewal_statistics(trace.x, rec.sum(axis=1), N * n, max_lag_distance=10 * micro["length_scale"])
    v = ex["v"]["value"]
    m2 = float(micro["mass"])
    c2 = friction_slope(micro["friction_law"], v)
    return {**ex,
            "n_micro": {"value": n, "unit": "", "provenance": "scenario (micro-pads per pad)"},
            "m2": {"value": m2, "unit": "kg", "provenance": "scenario (micro-pad mass)"},
            "k2": {"value": float(micro["k"]), "unit": "N/m", "provenance": "scenario (micro spring)"},
            "eta2": {"value": float(micro["c"]) / m2, "unit": "1/s", "provenance": "scenario (micro spring damping / m2)"},
            "eta3": {"value": c2 / m2, "unit": "1/s", "provenance": "micro friction law's slope at the measured speed / m2"},
            "a2": {"value": float(micro["length_scale"]), "unit": "m", "provenance": "scenario (micro length scale)",
                   "measured": lv.a},
            "f_kin2": {"value": lv.f_kin, "unit": "N", "provenance": "mean micro-pad tangential force (recorded)"},
            "alpha2": {"value": lv.alpha, "unit": "", "provenance": "sqrt(12 Var / (N n)) / f_kin2 of the summed micro "
                       "forces (eq. A7)", "substrate_value": micro.get("patch_contrast")},
            "micro_renewals": {"value": N * n * (trace.x[-1] - trace.x[0]) / micro["length_scale"], "unit": "",
                               "provenance": "N n x distance / a2: what the micro estimates rest on"}}


def multiscale_params(ex: dict) -> ms.MultiscaleParams:
    """A MultiscaleParams from :func:`multiscale_parameters` (k1 = 0, eta1 = c / m, F_drive from steady sliding)."""
    N = max(1, int(round(ex["N"]["value"])))
    n = int(ex["n_micro"]["value"])
    v, f_kin, c, m = ex["v"]["value"], ex["f_kin"]["value"], ex["c"]["value"], ex["m"]["value"]
    m2, eta3, f_kin2 = ex["m2"]["value"], ex["eta3"]["value"], ex["f_kin2"]["value"]
    F_drive = N * (f_kin + c * v) + N * n * (f_kin2 + m2 * eta3 * v)
    return ms.MultiscaleParams(N=N, v=v, a=ex["a"]["value"], k0=ex["k0"]["value"], k1=0.0, M=ex["M"]["value"], m=m,
                               eta0=ex["eta0"]["value"], eta1=c / m, alpha=ex["alpha"]["value"], F_drive=F_drive,
                               F_kin=N * f_kin, n_micro=n, m2=m2, k2=ex["k2"]["value"], eta2=ex["eta2"]["value"],
                               eta3=eta3, a2=ex["a2"]["value"], alpha2=ex["alpha2"]["value"], F_kin2=N * n * f_kin2)


def scene_against_model_Ib(name, sc, quick, seed, trace=None) -> StudyResult:
    """The scene's C_x against model I and model Ib built from its measured parameters: overlaid spectra, per-band
    ratios, gamma per regime (fits over v/a-omega_x/2 and 2 omega_x-v/a2 where those bands span a factor 2.5,
    else over model I's 3-30 v/a band) with 95 % intervals."""
    from reduced_models import spring_block as m1

    from .. import plots
    from ...analysis.extract import spring_block_params
    from ...analysis.spectra import displacement_spectrum
    from ..study import Figure
    from ...analysis.record_model import expected_gamma
    from ._common import band_ratios, ratio_range, ratio_rows, record_fit, timed, whole_run

    if trace is None:
        trace, wall = timed(whole_run, sc.with_run(duration=12.0 if quick else sc.run.duration), seed=seed)
    else:
        wall = float(trace.metadata.get("wall_s", float("nan")))
    T = float(trace.t[-1])
    dt = float(trace.t[1] - trace.t[0])
    ex = multiscale_parameters(trace)
    pb = multiscale_params(ex)
    p1 = spring_block_params(ex)
    nper = min(2**13, 1 << int(math.floor(math.log2(len(trace.t) / 3))))
    spec = displacement_spectrum(trace.t, trace.x, nperseg=nper)
    top = min(2000.0, math.pi / dt / 2)
    edges = np.geomspace(max(2.0, 4 * spec.omega_min), top, 7 if quick else 9)
    rI = band_ratios(spec, m1.theory_spectrum(p1, spec.omega), edges)
    rIb = band_ratios(spec, ms.theory_spectrum(pb, spec.omega), edges)
    reg = ms.regime_frequencies(pb)
    w0, w2, wx = reg["v_over_a"], reg["v_over_a2"], reg["omega_x"]
    lo = 4 * spec.omega_min  # the lowest resolved frequency the fits use
    bands = {"model I band 3-30 v/a": (max(3 * w0, lo), min(30 * w0, top))}
    if math.isfinite(wx):
        bands["below omega_x (macro, gamma 4)"] = (max(3 * w0, lo), wx / 2)
        bands["omega_x to v/a2 (micro, gamma 2)"] = (max(2 * wx, lo), min(w2 / 2, top))
    fits = {}
    for k, b in bands.items():
        if b[1] > 2.5 * b[0]:  # a regime narrower than a factor 2.5 in this record is not fitted
            fit = record_fit(trace.t, trace.x, band=b)  # the record model over the regime's band
            f = fit.to_dict()
            # model Ib's closed form bends over the band: the exponent the same fit reads off it without noise
            f["gamma_model_Ib"] = expected_gamma(lambda w: ms.theory_spectrum(pb, w), fit, dt, b, sampled=False)
            fits[k] = f
    w = np.geomspace(spec.omega_min, spec.omega_max, 300)
    fig = plots.spectrum_figure([(spec, f"scene {name}, {T:g} s")],
                                [(w, m1.theory_spectrum(p1, w), "model I (A10), extracted"),
                                 (w, ms.theory_spectrum(pb, w), "model Ib, extracted")],
                                title=f"Scene {name} against models I and Ib")
    d = {"extracted": ex, "band_ratios_vs_model_I": rI, "band_ratios_vs_model_Ib": rIb, "fits": fits,
         "regimes_rad_s": reg, "duration_s": T, "wall_s": wall, "params_Ib": pb.to_dict()}
    gam = "; ".join(f"{esc(k)}: {fit_text(f)} over {span(f['band'][0], f['band'][1])} "
                    f"rad/s (model Ib {f['gamma_model_Ib']:.2f})" for k, f in fits.items())
    text = paragraphs([
        f"{T:g} s of {name}. Scene / model I per band {ratio_range(rI)}, scene / model Ib {ratio_range(rIb)} over "
        f"{span(edges[0], edges[-1])} rad/s. Gamma per regime: {gam}. Measured a2 "
        f"{1e6 * ex['a2']['measured']:.2f} um (scenario {1e6 * ex['a2']['value']:.2f} um); alpha2 {ex['alpha2']['value']:.3f} "
        f"(micro patch contrast {ex['alpha2'].get('substrate_value')}); f_kin2 {ex['f_kin2']['value']:.4g} N.",
        "Procedure: " + rst_inline(PROCEDURE),
    ]) + table("Model Ib parameters extracted from the scene", ["parameter", "value", "unit", "provenance"], param_rows(ex)) \
        + table("C_x(scene) / C_x(model I)", ["band (rad/s)", "ratio"], ratio_rows(rI)) \
        + table("C_x(scene) / C_x(model Ib)", ["band (rad/s)", "ratio"], ratio_rows(rIb))
    cap = (f"Scene {name} ({T:g} s) against models I and Ib in closed form, both with the scene's measured parameters: "
           f"scene / model I {ratio_range(rI)}, scene / model Ib {ratio_range(rIb)} per band.")
    verdicts = (ratio_verdict(f"scenarios/{name}_model_Ib", "C_x / model Ib", rIb, 1.5, "1 (model Ib)"),)
    return StudyResult(f"scenarios/{name}_model_Ib", f"Scene {name} against model Ib", d,
                       (Figure(f"scene_{name}_model_Ib", plots.figure_png_bytes(fig), cap),), text, verdicts=verdicts)


def run(quick: bool, seed: int) -> StudyResult:
    """The scene against model Ib, or a stated skip when the scene is not shipped (or records no micro forces)."""
    from engine_sim import load_scenario, shipped_scenarios

    shipped = shipped_scenarios()
    reason = None
    if NAME not in shipped:
        reason = f"the scenario {NAME} is not shipped in this version (it is being built in engine_sim)"
    else:
        try:
            return scene_against_model_Ib(NAME, load_scenario(shipped[NAME]), quick, seed)
        except ValueError as e:  # a trace without the micro metadata or the micro forces: say which
            reason = f"{NAME} ran but cannot be compared: {e}"
    return StudyResult(f"scenarios/{NAME}_model_Ib", f"Scene {NAME} against model Ib", {"skipped": reason},
                       (), paragraphs([f"Skipped: {esc(reason)}."]))


STUDY = Study(key=f"scenarios/{NAME}_model_Ib", label=f"scene {NAME} vs model Ib", run=run, quick=True, cost=20.0)
