"""Every shipped scene against the reduced model that fits it, built from the scene's own measured parameters.
The scene's parts name the model (``reduced_model``) and the quick run's length (``quick_duration``): model I for
pads on tracks (here), model III for a sole on sparse asperities (:mod:`.scene_asperity`), paired runs and model II
for wear particles (:mod:`.scene_wear`).

One study per shipped scenario (``STUDIES``); :func:`scene_result` also serves ``frictionnoise compare``.
"""
from __future__ import annotations

import math
from functools import partial

import numpy as np

from ...analysis.fits import flag_mark
from ..html import pct
from ..html import esc, paragraphs, span, table
from ...analysis.spectra import displacement_spectrum
from ..study import Figure, Study, StudyResult
from ..verdict import NOT_A_POWER_LAW, fit_text, ratio_verdict
from ._common import segment_samples, balances, energy_text, band_ratios, line_text, log_err, param_rows, ratio_range, ratio_rows, record_fit, require_band, run_scene, timing

# (quick, full) cost of each scene's study in CPU seconds, as benchmarks/bench_report.py measures them (quick: load
# 2-4, the wear pair at load 4-5; full: the whole report at load 4-5), so the report's pool starts the longest first and its workers end
# together (the wear pair, pads_multiscale with both models, the line-scan and rough-profile substrates, whose pads
# cost about 1.5 CPU s per simulated second, lead; a friction-patch scene costs about 0.35)
SCENE_COSTS = {"pads_with_wear": (17.0, 58.4), "pads_multiscale": (25.0, 16.5), "line_scan_example": (14.3, 21.2),
               "pads_rough_profile": (13.0, 18.9), "pads_rate_state": (10.2, 9.7), "asperity_field": (8.9, 10.4),
               "pads_friction_patches": (3.9, 3.9), "constant_velocity": (4.9, 3.9), "leonardo_slider": (5.5, 4.1),
               "spring_slider_rate_state": (4.7, 5.4), "tilted_plane": (4.6, 3.4)}


# a shaken scene's verdict against model I: the model holds no vibration, so the comparison is descriptive
SHAKEN = "shaken scene: model I holds no vibration; read the in-band effect against the unshaken twin"


def fitting_part(sc):
    """The scene's part that names the reduced model fitting it (``reduced_model``, a key of
    ``reduced_models.MODELS``) and the recorded seconds of a quick comparison (``quick_duration``): its wear
    particles when it has any, else its friction law if that names one, else its substrate."""
    return next(part for part in (sc.wear_part, sc.law_part, sc.substrate_part) if part.reduced_model)


# Recorded seconds of a scene in the full report, by the reduced model it is compared with (the quick report takes
# each part's ``quick_duration``, 8-16 s; ``frictionnoise compare`` and the other models the scenario's own duration).
# 12.5 s is the shortest record whose spectra hold 4 s Welch segments (2^12 samples at 1 ms; 5 of them, half
# overlapping): they resolve 3-30 v/a and the ratio bands down to 4 frequency steps, and gamma's 95 % half-width is
# about 0.2 on the friction-patch scenes (sqrt(9/5) that of a 20 s record). Model III's comparison below its corner
# v/w needs segments of about 8 s, so asperity_field records 20 s. Per scene: python -m benchmarks.bench_report.
FULL_DURATION = {"model_I": 12.5, "model_II": 12.5, "model_ageing": 12.5, "model_III": 20.0}


def full_duration(sc) -> float | None:
    """Recorded seconds of ``sc`` in the full report (None: the scenario's own duration)."""
    return FULL_DURATION.get(fitting_part(sc).reduced_model)

# each reduced model's comparison with a scene: (module of this package, function), looked up when called
COMPARISONS = {"model_I": ("scenes", "_model_I_result"), "model_II": ("scene_wear", "wear_result"),
               "model_III": ("scene_asperity", "asperity_result"),
               "model_ageing": ("scene_rate_state", "ageing_result"), "spring_slider": ("scene_rate_state", "slider_result")}
# models compared beside the fitting one on the same trace, when a part names them (``also_fits``)
BESIDE = {"model_Ib": ("scene_multiscale", "scene_against_model_Ib")}
SCENE_RUNS = {"model_II": 2}  # scene runs a comparison makes when not 1: model II's pairs the scene with and without


def scene_runs(sc) -> int:
    """How many times the comparison that fits ``sc`` runs the scene (for a progress bar's total)."""
    return SCENE_RUNS.get(fitting_part(sc).reduced_model, 1)


def beside_results(sc, seed, trace) -> list:
    """The comparisons of the models the scene's arrangement names beside the fitting one (``also_fits``), on
    ``trace``."""
    from importlib import import_module

    out = []
    for key in sc.arrangement_part.also_fits:
        module, function = BESIDE[key]
        out.append(getattr(import_module(f".{module}", __package__), function)(sc.name, sc, False, seed, trace=trace))
    return out


def scene_result(name, sc, quick, seed, trace=None, duration=None, progress=None, band=None) -> StudyResult:
    """One scenario against the reduced model its parts name (runs it unless given a trace); ``band`` (rad/s),
    when given, replaces the comparison's own fit band (3-30 v/a for model I) where the comparison takes one."""
    import inspect
    from importlib import import_module

    part = fitting_part(sc)
    if part.reduced_model not in COMPARISONS:
        raise ValueError(f"scene {name}: no comparison with {part.reduced_model} (comparisons: {', '.join(COMPARISONS)})")
    module, function = COMPARISONS[part.reduced_model]
    compare = getattr(import_module(f".{module}", __package__), function)
    extra = {}
    if band is not None:
        if "band" not in inspect.signature(compare).parameters:
            raise ValueError(f"--band: the comparison with {part.reduced_model} sets its own band")
        extra["band"] = tuple(band)
    return compare(name, sc, quick, seed, trace, duration or (part.quick_duration if quick else None), progress,
                   **extra)


def _model_I_result(name, sc, quick, seed, trace, duration, progress, band=None) -> StudyResult:
    from reduced_models import spring_block

    from .. import plots
    from ...analysis.extract import model_I_parameters, spring_block_params

    tr, wall, T = run_scene(sc, quick, seed, trace, duration, progress)
    nper = segment_samples(len(tr.t), float(tr.t[1] - tr.t[0]), quick)
    spec = displacement_spectrum(tr.t, tr.x, nperseg=nper)
    ex = model_I_parameters(tr, sc)
    w0 = ex["v"]["value"] / ex["a"]["value"]
    band = band or (3 * w0, 30 * w0)  # the renewal band, unless the command gives one (compare --band)
    a_sub = getattr(sc.substrate, "a", None)  # the patches' renewal length (a rough track's roll-off: a longer advice)
    require_band(spec, band, T, float(tr.t[1] - tr.t[0]), 3 * sc.steady_velocity / a_sub if a_sub else None)
    fit = record_fit(tr.t, tr.x, band=band)  # the record model over the renewal band, eq. (6)'s omega^-4
    p = spring_block_params(ex)
    m1 = spring_block.simulate(p, T, tr.t[1] - tr.t[0], seed=seed)
    s1 = displacement_spectrum(m1.t, m1.x, nperseg=nper)
    fit_m1 = record_fit(m1.t, m1.x, band=band, stationarity=False)  # exact simulator: stationary by construction
    top = min(2000.0, math.pi / (tr.t[1] - tr.t[0]) / 2)
    edges = np.logspace(np.log10(max(2.0, 4 * spec.omega_min)), np.log10(top), 7 if quick else 9)
    ratios = band_ratios(spec, spring_block.theory_spectrum(p, spec.omega), edges)
    # is the substrate force white above v/a (C_f ~ omega^-2 for a piecewise-constant force)?
    # the pads' force through its running sum (integrate), so a flatter force than omega^-1.05 is fitted too
    fit_f = record_fit(tr.t, tr.pad_force.sum(axis=1), band=band, quantity="F", integrate=True)
    wstar, wc = ex["omega_star"]["value"], ex["omega_c"]["value"]
    viscous = band[1] < 0.3 * min(wstar, wc)
    worst = max(abs(math.log(b["ratio"])) for b in ratios)
    d = {
        **fit.to_dict(), "model_I_sim": fit_m1.to_dict(), "band_ratios_vs_model_I": ratios,
        "model_I_within_factor_1p5": bool(worst < math.log(1.5)), "substrate_force_fit": fit_f.to_dict(),
        "extracted": ex, "wall_s": wall, "duration_s": T, "us_per_step": tr.metadata["us_per_step"],
        "mean_velocity": ex["v"]["value"], "law_velocity": sc.steady_velocity, **balances(tr),
    }
    w = np.logspace(np.log10(spec.omega_min), np.log10(spec.omega_max), 300)
    fig = plots.spectrum_figure([(spec, f"scene {name}, {T:g} s"), (s1, "model I simulation, extracted parameters")],
                                [(w, spring_block.theory_spectrum(p, w), "model I (A10), extracted parameters")],
                                fits=[(fit, "scene ")], band=band, title=f"Scene {name} against model I")
    verdict = " (within a factor 1.5)." if worst < math.log(1.5) else f" (outside a factor 1.5: worst band x{math.exp(worst):.2f})."
    a_sub_text = f" (substrate: {1e3 * a_sub:.3f} mm)" if a_sub else ""
    alpha_sub = getattr(sc.substrate, "alpha", None)
    alpha_text = f" (substrate: {alpha_sub:g})" if alpha_sub is not None and math.isfinite(alpha_sub) else ""
    parts = [
        esc(sc.description.replace("\n", " ")),
        f"{T:g} s simulated in {wall:.1f} s ({tr.metadata['us_per_step']:.0f} us per step). Mean speed "
        f"{1e3 * ex['v']['value']:.3f} mm/s (friction law: {1e3 * sc.steady_velocity:.3f} mm/s); force balance "
        f"{pct(d['force_balance_rel'])}; {energy_text(d)}.",
        f"Scene gamma = {fit_text(fit, 3)} over {span(band[0], band[1])} rad/s; model I with the extracted "
        f"parameters: {fit_text(fit_m1, 3)}. Per-band ratio scene / model I (A10): {ratio_range(ratios)} over "
        f"{span(edges[0], edges[-1])} rad/s" + verdict,
        f"omega* = {wstar:.0f} rad/s, omega_c = {wc:.0f} rad/s; the fit band ends at {band[1]:.0f} rad/s: "
        + ("viscous response across it. " if viscous else "it reaches the crossover, the response is not purely viscous. ")
        + f"Substrate force on the pads: omega^-({fit_text(fit_f)}) (model I: omega^-2). Renewal length "
        f"{1e3 * ex['a']['value']:.3f} mm{a_sub_text}, alpha = {ex['alpha']['value']:.3f}{alpha_text}.",
    ]
    if line_text(tr):
        parts.append(line_text(tr))
    if sc.drive_part.extra_mass > 0:  # a drive with a body of its own on a rope (Leonardo's slider)
        parts.append(
            f"Leonardo's slider: model I uses M = block + hanging mass = {ex['M']['value']:.4g} kg (the rope taut). Above "
            f"the bare block's resonance on its pads, sqrt(N k0 / M_block) = {math.sqrt(ex['N']['value'] * sc.pads.k0 / sc.block.M):.0f} "
            "rad/s, the block moves apart from the hanging mass: the rope joint is not perfectly rigid in pymunk's "
            "solver (it stretched by up to 0.33 um, measured), so the top band exceeds model I (see the ratio table).")
    text = (paragraphs(parts)
            + table("Model I parameters extracted from the scene", ["parameter", "value", "unit", "provenance"], param_rows(ex))
            + table("C_x(scene) / C_x(model I, A10), per log band", ["band (rad/s)", "ratio"], ratio_rows(ratios)))
    caption = (f"Scene {name} ({T:g} s) against model I simulated and in closed form (A10), both with the parameters "
               f"extracted from the scene. Scene / (A10) {ratio_range(ratios)} per band over {span(edges[0], edges[-1])} "
               f"rad/s{verdict[:-1]}; gamma = {fit.gamma:.2f} ± {fit.gamma_err:.2f}{flag_mark(fit)} (scene) and "
               f"{fit_m1.gamma:.2f} ± {fit_m1.gamma_err:.2f}{flag_mark(fit_m1)} (model I) over the shaded band.")
    verdict = ratio_verdict(f"scenarios/{name}", "C_x / model I (A10)", ratios, 1.5, "1 (model I)")
    if tr.metadata.get("line_removed"):  # model I holds no vibration: the in-band effect is read against the twin
        from dataclasses import replace

        verdict = replace(verdict, agree=None, flags=(SHAKEN,), by=f"{verdict.by}; {SHAKEN}")
    verdicts = (verdict,)
    return StudyResult(f"scenarios/{name}", f"Scene: {name}", d, (Figure(f"scene_{name}", plots.figure_png_bytes(fig), caption),),
                       text, (timing(f"scene {name}", f"{T:g} s, dt = {sc.run.dt:g} s", f"{wall:.2f}", f"{log_err(ratios):.3f}"),),
                       verdicts)


METHOD = [
    "Each shipped scene runs with its own seed and is compared with the reduced model its parts name, built from "
    "parameters measured on the scene itself (tables in each section: value, unit and provenance). Pads on friction "
    "patches or rough tracks go to model I; a sole on sparse asperities to model III; wear particles to a paired "
    "run without them and model II built from their episodes. The other models do not apply to a scene: the pad "
    "scenes have no wear particles, and their contacts are spring-mounted pads rather than a rigid flat block on "
    "sparse asperities.",
    "Model I against a pad scene: gamma is fitted over 3-30 v/a, v the measured speed and a the renewal length "
    "(12/7 x the pad forces' correlation length in sliding distance); model I is simulated with the extracted "
    "parameters and the same band, and the scene's C_x is divided by model I's closed form (A10) in log bands. The "
    "verdict is whether every band lies within a factor 1.5. Model I assumes a viscous response, which holds below "
    "omega* = N c / M and the resonance omega_c = sqrt(N k0 / M), and a substrate force on each pad that renews "
    "abruptly (C_f ~ omega^-2 above v/a); each section gives omega*, omega_c, the band's top and the measured "
    "slope of the substrate force.",
    f"A fit whose log-log residuals curve or whose band spans less than a decade is marked ({NOT_A_POWER_LAW}); "
    "its exponent is stated but no verdict rests on it.",
]


def method_result(quick: bool, seed: int) -> StudyResult:
    """The method shared by every scene section, said once before them."""
    return StudyResult("scenes_method", "Scenes against the reduced models: the method", {"method": METHOD},
                       html=paragraphs(METHOD))


METHOD_STUDY = Study("scenes_method", "scenes: method", method_result, cost=0.0)


def _run_shipped(name: str, quick: bool, seed: int) -> list:
    """The scene against its reduced model; a scene with micro-pads also against model Ib, on the same run."""
    from engine_sim import load_scenario, shipped_scenarios
    from engine_sim.scene import describe

    sc = load_scenario(shipped_scenarios()[name])
    part = fitting_part(sc)
    # the full report's shorter record applies to the comparisons it was measured on (models I, II, III)
    duration = part.quick_duration if quick else full_duration(sc)
    if "micro" not in describe(sc):
        return [scene_result(name, sc, quick, seed, duration=duration)]
    from .scene_multiscale import scene_against_model_Ib

    trace = run_scene(sc, quick, seed, None, duration, None)[0]
    return [scene_result(name, sc, quick, seed, trace=trace),
            scene_against_model_Ib(name, sc, quick, seed, trace=trace)]


# The scenes of the quick report's default selection: one for each of the paper's mechanisms, each against its
# reduced model (clean sliding on friction patches, model I; wear particles, model II; a sole on sparse asperities,
# model III). With ``--all-scenes`` the quick report runs every shipped scene at its quick length; the full report
# always does.
HEADLINE_SCENES = ("pads_friction_patches", "pads_with_wear", "asperity_field")


def scene_studies() -> list:
    """One study per shipped scenario, in the order engine_sim lists them."""
    from engine_sim import shipped_scenarios

    costs = {name: SCENE_COSTS.get(name, (5.0, 10.0)) for name in shipped_scenarios()}  # (quick, full) CPU s
    return [Study(f"scenarios/{name}", f"scene {name}", partial(_run_shipped, name), cost=full, quick_cost=quick,
                  headline=name in HEADLINE_SCENES)
            for name, (quick, full) in costs.items()]
