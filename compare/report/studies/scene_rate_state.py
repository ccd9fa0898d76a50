"""Scenes with the rate_state friction law against their reduced models, built from the scene's own parameters:

- pads sliding steadily (B < A) against model I with ageing contacts (:mod:`reduced_models.ageing`): the pads'
  patch noise (a, alpha, f_kin) measured as for model I (:func:`compare.analysis.extract.model_I_parameters`), the
  contacts' A, B, D_c and state law from the scene's friction law, F_N = N x load per pad, F_drive the drive force;
  the scene's C_x against the model's linear-response spectrum (A10 with the slope (f_n / v)(A - B / (1 + i omega
  D_c / v))) per band, and against the model simulated with the same parameters;
- the one-pad spring-slider (B >= A) against the closed forms of :mod:`reduced_models.rate_state`: its stiffness k
  (the drive spring in series with the pad spring) against k_c = N_pad (B - A) / D_c, whether it sticks and slips,
  and its stick-slip period against the neutral period at onset 2 pi D_c / (V sqrt((B - A) / A)).
"""
from __future__ import annotations

import math

import numpy as np

from ...analysis.spectra import displacement_spectrum
from ..html import esc, paragraphs, span, table
from ..study import Figure, StudyResult
from ..verdict import Verdict, fit_text, ratio_verdict
from ._common import segment_samples, balances, band_ratios, log_err, param_rows, ratio_range, ratio_rows, record_fit, require_band, run_scene, timing

__all__ = ["ageing_params", "ageing_result", "slider_result"]


def ageing_params(tr, sc, ex=None):
    """AgeingParams of a pad scene with the rate_state law: ``ex`` the model I extraction of the trace."""
    from reduced_models.ageing import AgeingParams

    from ...analysis.extract import model_I_parameters

    ex = ex or model_I_parameters(tr, sc)
    fr = sc.friction
    N = int(round(ex["N"]["value"]))
    load = ex["load_per_pad"]["value"]
    return AgeingParams(N=N, v=ex["v"]["value"], a=ex["a"]["value"], k0=ex["k0"]["value"], M=ex["M"]["value"],
                        m=ex["m"]["value"], eta0=ex["eta0"]["value"], alpha=ex["alpha"]["value"],
                        F_drive=sc.drive_force, F_kin=N * ex["f_kin"]["value"], F_N=N * load, A=fr.A, B=fr.B,
                        D_c=fr.D_c, law=fr.state_law)


def ageing_result(name, sc, quick, seed, trace, duration, progress) -> StudyResult:
    """The pad scene against model I with ageing contacts (module docstring)."""
    from reduced_models import ageing

    from .. import plots
    from ...analysis.extract import model_I_parameters

    tr, wall, T = run_scene(sc, quick, seed, trace, duration, progress)
    dt_out = float(tr.t[1] - tr.t[0])
    nper = segment_samples(len(tr.t), float(tr.t[1] - tr.t[0]), quick)
    spec = displacement_spectrum(tr.t, tr.x, nperseg=nper)
    ex = model_I_parameters(tr, sc)
    p = ageing_params(tr, sc, ex)
    w0 = p.v / p.a
    band = (3 * w0, 30 * w0)
    require_band(spec, band, T, dt_out, 3 * sc.steady_velocity / sc.substrate.a)
    fit = record_fit(tr.t, tr.x, band=band)  # the record model over the renewal band
    sim = ageing.simulate(p, T, dt_out, seed=seed)
    s_sim = displacement_spectrum(sim.t, sim.x, nperseg=nper)
    fit_sim = record_fit(sim.t, sim.x, band=band, stationarity=False)  # exact simulator
    top = min(2000.0, math.pi / dt_out / 2)
    edges = np.logspace(np.log10(max(2.0, 4 * spec.omega_min)), np.log10(top), 7 if quick else 9)
    ratios = band_ratios(spec, ageing.theory_spectrum(p, spec.omega), edges)
    ratios_sim = band_ratios(s_sim, ageing.theory_spectrum(p, s_sim.omega), edges)
    worst = max(abs(math.log(b["ratio"])) for b in ratios)
    d = {**fit.to_dict(), **balances(tr), "model_ageing_sim": fit_sim.to_dict(), "band_ratios_vs_model_ageing": ratios,
         "model_ageing_sim_vs_theory": ratios_sim, "within_factor_1p5": bool(worst < math.log(1.5)),
         "ageing_params": p.to_dict(), "extracted": ex, "wall_s": wall, "duration_s": T,
         "us_per_step": tr.metadata["us_per_step"], "mean_velocity": p.v, "law_velocity": sc.steady_velocity}
    w = np.logspace(np.log10(spec.omega_min), np.log10(spec.omega_max), 300)
    fig = plots.spectrum_figure([(spec, f"scene {name}, {T:g} s"), (s_sim, "model_ageing simulated, scene parameters")],
                                [(w, ageing.theory_spectrum(p, w), "model_ageing linear response (A10)")],
                                fits=[(fit, "scene ")], band=band, title=f"Scene {name} against model_ageing")
    verdict = " (within a factor 1.5)." if worst < math.log(1.5) else f" (outside a factor 1.5: worst ln ratio {worst:.2f})."
    parts = [
        esc(sc.description.replace("\n", " ")),
        f"{T:g} s simulated in {wall:.1f} s ({tr.metadata['us_per_step']:.0f} us per step). Mean speed "
        f"{1e3 * p.v:.3f} mm/s (steady law: {1e3 * sc.steady_velocity:.3f} mm/s).",
        f"Scene gamma = {fit.gamma:.3f} &plusmn; {fit.gamma_err:.3f} over {span(band[0], band[1])} rad/s (3-30 v/a); "
        f"model_ageing simulated with the scene's parameters: {fit_sim.gamma:.3f} &plusmn; {fit_sim.gamma_err:.3f}. "
        f"Per-band ratio scene / linear response: {ratio_range(ratios)} over {span(edges[0], edges[-1])} rad/s"
        + verdict + f" The model's own simulation / linear response: {ratio_range(ratios_sim)}.",
        f"The contacts' slope turns from (A - B) f_n / v to A f_n / v above v / D_c = {p.v / p.D_c:.3g} rad/s.",
    ]
    rows = [[k, f"{v:.4g}" if isinstance(v, float) else esc(str(v)), "", "scene (friction law) or extracted"]
            for k, v in p.to_dict().items()]
    text = (paragraphs(parts)
            + table("model_ageing parameters from the scene", ["parameter", "value", "unit", "provenance"], rows)
            + table("Model I parameters extracted from the scene", ["parameter", "value", "unit", "provenance"], param_rows(ex))
            + table("C_x(scene) / C_x(model_ageing, linear response), per log band", ["band (rad/s)", "ratio"],
                    ratio_rows(ratios)))
    caption = (f"Scene {name} ({T:g} s) against model I with ageing contacts, simulated and in linear response, both "
               f"with the scene's parameters. Scene / theory {ratio_range(ratios)} per band; gamma = {fit.gamma:.2f} "
               f"± {fit.gamma_err:.2f} (scene) and {fit_sim.gamma:.2f} ± {fit_sim.gamma_err:.2f} (model).")
    verdicts = (ratio_verdict(f"scenarios/{name}", "C_x / model I with ageing contacts (A10)", ratios, 1.5,
                              "1 (model_ageing)"),)
    return StudyResult(f"scenarios/{name}", f"Scene: {name}", d, (Figure(f"scene_{name}", plots.figure_png_bytes(fig), caption),),
                       text, (timing(f"scene {name}", f"{T:g} s, dt = {sc.run.dt:g} s", f"{wall:.2f}", f"{log_err(ratios):.3f}"),),
                       verdicts)


def cycle_period(v, dt: float, shortest: float) -> float:
    """The stick-slip period (s): the lag of the highest autocorrelation of the block's speed between ``shortest``
    (s, beyond the block's ringing on its springs) and a third of the record."""
    x = v - np.mean(v)
    n = len(x)
    f = np.fft.rfft(x, 2 * n)
    ac = np.fft.irfft(f * np.conj(f))[:n]
    lo, hi = int(math.ceil(shortest / dt)), n // 3
    if hi <= lo + 1:
        return float("nan")
    return float((lo + int(np.argmax(ac[lo:hi]))) * dt)


def slider_result(name, sc, quick, seed, trace, duration, progress) -> StudyResult:
    """The one-pad spring-slider against the closed forms (module docstring)."""
    from reduced_models import rate_state as rs

    from .. import plots

    tr, wall, T = run_scene(sc, quick, seed, trace, duration, progress)
    fr = sc.friction
    V = sc.steady_velocity
    N_pad = sc.normal_load_per_pad
    k0, kd = sc.pads.k0, sc.drive.k_drive
    k = k0 * kd / (k0 + kd)
    p = rs.SpringSliderParams(A=fr.A, B=fr.B, D_c=fr.D_c, mu0=fr.mu_ref, V0=fr.V0, sigma=N_pad, k=k, V_lp=V,
                              law=fr.state_law)
    kc = rs.critical_stiffness(p)
    period0 = rs.onset_period(p)
    t = tr.t
    v = np.gradient(tr.x, t)
    half = t >= t[0] + 0.5 * (t[-1] - t[0])  # the second half: past the start's transient
    ring = 2 * math.pi * math.sqrt(sc.block.M / (k0 + kd))  # the block's period on its springs (s)
    period = cycle_period(v[half], float(t[1] - t[0]), 3 * ring)
    stick = bool(np.max(v[half]) > 2 * V)  # steady sliding stays near V; slips exceed it many times
    spec = displacement_spectrum(t, tr.x, nperseg=1 << int(math.floor(math.log2(len(t) / 3))))
    w_on = 2 * math.pi / period0
    band = (2 * w_on, 20 * w_on)  # the harmonics of stick-slip above the onset frequency
    fit = record_fit(t, tr.x, band=band)  # the record model over the stick-slip harmonics
    d = {**fit.to_dict(), "k": k, "k_c": kc, "k_over_k_c": k / kc, "onset_period": period0, "stick_slip_period": period,
         "sticks": stick, "v_min_over_V": float(np.min(v[half]) / V), "v_max_over_V": float(np.max(v[half]) / V),
         "wall_s": wall, "duration_s": T, "us_per_step": tr.metadata["us_per_step"],
         "stick_slip_as_predicted": bool(stick == (k < kc)), **balances(tr)}
    parts = [
        esc(sc.description.replace("\n", " ")),
        f"{T:g} s simulated in {wall:.1f} s ({tr.metadata['us_per_step']:.0f} us per step). Stiffness k = {k:.4g} N/m "
        f"(k_drive in series with k0) = {k / kc:.3f} k_c, k_c = N_pad (B - A) / D_c = {kc:.4g} N/m.",
        (f"Over the second half the speed ranges {d['v_min_over_V']:.3g}-{d['v_max_over_V']:.3g} V: "
         + ("stick-slip" if stick else "steady sliding") + (", as k " + ("<" if k < kc else ">") + " k_c predicts. "
                                                            if d["stick_slip_as_predicted"] else ", against the prediction. ")
         + f"Stick-slip period {period:.3g} s against the neutral period at onset 2 pi D_c / (V sqrt((B - A)/A)) = "
           f"{period0:.3g} s (the two agree only at k -> k_c; below it the cycles are nonlinear and longer)."),
    ]
    parts.append(f"C_x falls as omega^-{fit_text(fit)} over {span(band[0], band[1])} "
                 "rad/s (2-20 times the onset frequency): the harmonics of the stick-slip cycle.")
    fig = plots.spectrum_figure([(spec, f"scene {name}, {T:g} s")], fits=[(fit, "scene ")], band=band,
                                title=f"Scene {name}: k = {k / kc:.2f} k_c")
    caption = (f"Scene {name}: the block's C_x, k = {k / kc:.2f} k_c; gamma = {fit.gamma:.2f} ± {fit.gamma_err:.2f} "
               "over the shaded band (2-20 times the neutral frequency at onset).")
    motion = "stick-slip" if stick else "steady sliding"
    verdicts = (Verdict(f"scenarios/{name}", "stick-slip or steady sliding, k against k_c", f"{motion} at k = {k / kc:.2f} k_c",
                        "stick-slip iff k < k_c = N_pad (B - A) / D_c", d["stick_slip_as_predicted"],
                        f"speed {d['v_min_over_V']:.3g}-{d['v_max_over_V']:.3g} V over the second half"),)
    return StudyResult(f"scenarios/{name}", f"Scene: {name}", d,
                       (Figure(f"scene_{name}", plots.figure_png_bytes(fig), caption),), paragraphs(parts),
                       (timing(f"scene {name}", f"{T:g} s, dt = {sc.run.dt:g} s", f"{wall:.2f}", "n/a"),), verdicts)
