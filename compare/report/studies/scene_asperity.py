"""A sole on sparse asperities (``asperity_field``) against model III with the same p, f0, w (paper section 7:
load redistribution), and the rigid-block counterfactual."""
from __future__ import annotations

import math

import numpy as np

from reduced_models import asperity_force

from ...analysis.fits import flag_mark
from ..html import esc, paragraphs, table
from ...analysis.spectra import band_average, force_series_spectrum
from ..study import Figure, StudyResult
from ..verdict import fit_text, ratio_verdict
from ..html import pct, span
from ._common import balances, energy_text, band_ratios, param_rows, ratio_rows, record_fit, run_scene, timing


def asperity_result(name, sc, quick, seed, trace, duration, progress) -> StudyResult:
    from .. import plots
    from ...analysis.extract import asperity_force_params, model_III_parameters

    tr, wall, T = run_scene(sc, quick, seed, trace, duration, progress)
    nper = min(2**15, 1 << int(math.floor(math.log2(len(tr.t) / 1.5))))
    ex = model_III_parameters(tr, sc)
    prm = asperity_force_params(ex)
    sF = force_series_spectrum(tr.t, tr.F_t, nperseg=nper)
    # the rigid-block counterfactual: every contact carrying the mean f0 / 2 whatever the load sharing
    sN = force_series_spectrum(tr.t, tr.n_pairs * (prm.f0 / 2), nperseg=nper)
    m3 = asperity_force.simulate(prm, T, seed=seed)
    s3 = force_series_spectrum(m3.t, m3.force, nperseg=min(nper, 1 << int(math.floor(math.log2(len(m3.t) / 2)))))
    w_vw = 2 * math.pi * prm.v / prm.w  # model III's corner 2 pi v / w
    w_foot = 2 * math.pi * prm.v / sc.pads.foot_length  # feet passing one another's asperities: a periodic line
    low = (max(3 * sF.omega_min, 0.25 * w_vw), w_vw)
    if low[0] > w_vw / 1.2:  # the band below model III's corner needs segments of about 3 x 1.2 x 2 pi / (2 pi v / w)
        dt_out = float(tr.t[1] - tr.t[0])
        n_need = 1 << math.ceil(math.log2(3 * 1.2 * 2 * math.pi / (w_vw * dt_out)))
        raise ValueError(f"a {T:g} s run is too short for the comparison below model III's corner 2 pi v / w = "
                         f"{w_vw:.2f} rad/s: it needs at least {1.5 * n_need * dt_out:.0f} s (--duration)")
    high = (2 * w_vw, min(0.6 * w_foot, math.pi / prm.dt / 4))
    edges_low = np.array(low)
    th_F = asperity_force.theory_force_spectrum(prm, sF.omega)
    r_low = band_average(sF, edges_low) / band_average(sF, edges_low, th_F)
    r_high = band_average(sF, np.array(high)) / band_average(sF, np.array(high), th_F)
    r_rigid = band_average(sN, edges_low) / band_average(sN, edges_low, asperity_force.theory_force_spectrum(prm, sN.omega))
    # the record model over the band above model III's corner (its omega^-2 force, gamma 6 for x); the forces
    # through their running sums (integrate): the scene's is nearly flat there, flatter than the model's omega^-1.05
    fitF = record_fit(tr.t, tr.F_t, band=high, quantity="F", integrate=True)
    fitF3 = record_fit(m3.t, m3.force, band=high, quantity="F", stationarity=False, integrate=True)  # exact simulator
    fit = record_fit(tr.t, tr.x, band=high)
    wstar = ex["omega_star"]["value"]
    ratios = band_ratios(sF, th_F, np.logspace(np.log10(low[0]), np.log10(high[1]), 7 if quick else 9))
    d = {
        **fit.to_dict(), "force_fit": fitF.to_dict(), "model_III_force_fit": fitF3.to_dict(),
        "model_III": prm.to_dict(), "C_F_ratio_below_v_over_w": float(r_low[0]),
        "C_F_ratio_above_v_over_w": float(r_high[0]), "rigid_counterfactual_ratio_below_v_over_w": float(r_rigid[0]),
        "band_ratios_vs_model_III_force": ratios, "bands": {"below": list(low), "above": list(high)},
        "extracted": ex, "wall_s": wall, "duration_s": T, "us_per_step": tr.metadata["us_per_step"],
        "mean_velocity": ex["v"]["value"], "law_velocity": sc.steady_velocity, **balances(tr),
        "response": "viscous" if high[1] < 0.3 * wstar else "mixed",
    }
    w = np.logspace(np.log10(sF.omega_min), np.log10(min(sF.omega_max, math.pi / prm.dt)), 300)
    fig = plots.spectrum_figure(
        [(sF, f"scene contact force, {T:g} s"), (sN, "rigid-block counterfactual: (f0/2) x contacts"),
         (s3, "model III simulation, same p, f0, w")],
        [(w, asperity_force.theory_force_spectrum(prm, w), "model III closed form")],
        fits=[(fitF, "scene ")], band=high, ylabel=r"$C_F$ (N$^2$ s)", title=f"Scene {name} against model III")
    text = paragraphs([
        esc(sc.description.replace("\n", " ")),
        f"{T:g} s simulated in {wall:.1f} s ({tr.metadata['us_per_step']:.0f} us per step). Mean speed "
        f"{1e3 * prm.v:.3f} mm/s (friction law: {1e3 * sc.steady_velocity:.3f} mm/s); friction balances the drive "
        f"to {pct(d['force_balance_rel'])}; {energy_text(d)}.",
        f"Model III with the scene's contact statistics (w = {1e3 * prm.w:.1f} mm, N = {prm.N:.1f} contacts, p = {prm.p:.4f} "
        f"per {1e3 * sc.substrate.cell:.2f} mm cell, f0 = {1e3 * prm.f0:.2f} mN) predicts a contact force with relative "
        f"std {math.sqrt(prm.N_w * asperity_force.grid_force_variance(prm)) / prm.F_f:.3f}; the scene's is "
        f"{float(np.std(tr.F_t) / np.mean(tr.F_t)):.4f}, although its number of contacts fluctuates by "
        f"{ex['n_rel_std']['value']:.3f} (relative std). <b>Load redistribution</b>: the block is free vertically, so "
        "its weight is shared by whichever feet stand on asperities and the Coulomb force mu x load hardly changes "
        "when contacts come and go (section 7).",
        f"C_F(scene) / C_F(model III) = {r_low[0]:.2e} below 2 pi v / w = {w_vw:.2f} rad/s (over {low[0]:.2f}-{low[1]:.2f} "
        f"rad/s) and {r_high[0]:.2e} above it ({high[0]:.2f}-{high[1]:.2f} rad/s). The rigid-block counterfactual "
        f"(each contact carrying f0/2) reads {r_rigid[0]:.2f} of model III below v/w: the number of contacts "
        "fluctuates somewhat less than model III's independent cells, but the remaining factor "
        f"{r_rigid[0] / r_low[0]:.0f} is the load sharing. "
        f"Force exponent above v/w: scene {fit_text(fitF)}, model III simulation "
        f"{fit_text(fitF3)} (closed form: 2). What remains in the scene is the "
        f"flank force of asperities entering and leaving the feet, with lines at the foot-passage frequency "
        f"2 pi v / foot = {w_foot:.1f} rad/s and its harmonics.",
        f"Response: omega* = N c / M = {wstar:.0f} rad/s, so the block responds viscously across the band "
        f"(C_x ~ C_F / omega^2, not model III's inertial C_F / (M^2 omega^4)); the scene's C_x reads "
        f"gamma = {fit_text(fit)} over {span(high[0], high[1])} rad/s. A weaker "
        "velocity strengthening would give an inertial band but no steady sliding under constant force.",
        "<b>Averaged force</b>: the scene's contact force is its mean over each output step (the recorder's default, "
        "from momenta read at the step's two ends). Its short asperity pulses make point samples alias: against the "
        "exact means of the same run, a point sample per output step reads C_F several times too high in a band "
        "below half the output Nyquist frequency (python -m compare.studies.recorder_alias): point samples "
        "would overstate the scene / model III ratios and flatten the force exponent with white aliased power.",
        "Models I and II do not apply to this scene: its feet see no friction patches, and it has no wear particles.",
    ]) + table("Model III parameters extracted from the scene", ["parameter", "value", "unit", "provenance"], param_rows(ex)) \
        + table("C_F(scene) / C_F(model III closed form), per log band", ["band (rad/s)", "ratio"], ratio_rows(ratios))
    caption = (f"Scene {name}: contact-force spectrum ({T:g} s) beside model III (simulated and closed form) with the "
               f"scene's p, f0, w, and the rigid-block counterfactual. Scene / model III {r_low[0]:.1e} below 2 pi v / w "
               f"and {r_high[0]:.1e} above; counterfactual / model III {r_rigid[0]:.2f} below: load sharing. C_F slope "
               f"above v/w (the legend's, -gamma): scene {-fitF.gamma:.2f} ± {fitF.gamma_err:.2f}{flag_mark(fitF)}, "
               f"model III {-fitF3.gamma:.2f} ± {fitF3.gamma_err:.2f}{flag_mark(fitF3)}.")
    return StudyResult(f"scenarios/{name}", f"Scene: {name}", d, (Figure(f"scene_{name}", plots.figure_png_bytes(fig), caption),),
                       text, (timing(f"scene {name}", f"{T:g} s, dt = {sc.run.dt:g} s", f"{wall:.2f}", "n/a (compared with model III)"),),
                       (ratio_verdict(f"scenarios/{name}", "C_F / model III, 2 bands",
                                      [float(r_low[0]), float(r_high[0])], 1.5, "1 (no load sharing)",
                                      expected="load sharing: the scene's free block carries its weight on whichever "
                                               "feet stand on asperities, model III does not (section 7)"),))
