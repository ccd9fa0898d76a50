"""Wear particles in the scene (``pads_with_wear``): paired runs with and without particles (same seed and
substrate), the trap/release episodes, and model II (eq. B2) built from them against the particles' force."""
from __future__ import annotations

import math
from operator import attrgetter
from types import SimpleNamespace

import numpy as np

from ...analysis.fits import flag_mark
from ..html import esc, paragraphs, pct, span, table
from ...analysis.spectra import band_average, displacement_spectrum, force_series_spectrum
from ..study import Figure, StudyResult
from ..verdict import fit_text, flags_of, interval_verdict
from ._common import segment_samples, balances, record_fit, require_band, timed, timing, whole_run


def _paired(name, sc, quick, seed, trace, duration, progress) -> SimpleNamespace:
    """The paired runs (with and without particles, same seed and substrate) and what is measured on them:
    spectra, fits, per-band ratios, episodes, model II built from them, balances and the interleaved step cost."""
    from engine_sim.timing import step_costs

    from ...analysis.episodes import duration_summary, episodes, model_II_from_episodes

    T = duration or (sc.wear_part.quick_duration if quick else sc.run.duration)
    if trace is not None:
        tw, wall_w = trace, float(trace.metadata.get("wall_s", float("nan")))
        T = float(tw.t[-1])
    else:
        tw, wall_w = timed(whole_run, sc.with_run(duration=T), seed=seed, progress=progress)
    t0, wall_0 = timed(whole_run, sc.with_run(duration=T).with_wear(count=0), seed=seed, progress=progress)
    nper = segment_samples(len(tw.t), float(tw.t[1] - tw.t[0]), quick)
    runs = {"with": tw, "without": t0}
    specs = {k: displacement_spectrum(tr.t, tr.x, nperseg=nper) for k, tr in runs.items()}
    fspec = {k: force_series_spectrum(tr.t, tr.F_t, nperseg=nper) for k, tr in runs.items()}
    v0 = float(t0.x[-1] / t0.t[-1])
    vw = float(tw.x[-1] / tw.t[-1])
    band = (3 * v0 / sc.substrate.a, 30 * v0 / sc.substrate.a)
    require_band(specs["with"], band, T, float(tw.t[1] - tw.t[0]), 3 * sc.steady_velocity / sc.substrate.a)
    fits = {k: record_fit(tr.t, tr.x, band=band) for k, tr in runs.items()}  # the record model over 3-30 v/a
    dg = fits["with"].gamma - fits["without"].gamma
    dg_err = math.hypot(fits["with"].gamma_err, fits["without"].gamma_err)
    edges = np.logspace(np.log10(max(2.0, 4 * specs["with"].omega_min)), np.log10(min(1000.0, 0.25 * specs["with"].omega_max)),
                        6 if quick else 8)
    level = band_average(specs["with"], edges) / band_average(specs["without"], edges)
    levelF = band_average(fspec["with"], edges) / band_average(fspec["without"], edges)
    dt_out = float(tw.t[1] - tw.t[0])
    ep = episodes(tw.p_state, tw.p_force, dt_out)
    dur = duration_summary(ep)
    sp = force_series_spectrum(tw.t, tw.p_force.sum(axis=1), nperseg=nper)
    pred = model_II_from_episodes(ep, float(tw.t[-1]), sp.omega)
    r_b2 = band_average(sp, edges) / band_average(sp, edges, pred)
    # the particles' force, near 1/f (flatter than the record model's omega^-1.05): its running sum is fitted
    fit_p = record_fit(tw.t, tw.p_force.sum(axis=1), band=band, quantity="F", integrate=True)
    # the change in the friction force's spectrum, against the particles' own force and its B2 prediction
    dCF = band_average(fspec["with"], edges) - band_average(fspec["without"], edges)
    r_dCF = dCF / band_average(sp, edges, pred)
    wm = tw.metadata.get("wear", {})
    states = {n: float(np.mean(tw.p_state == c)) for c, n in ((0, "idle"), (1, "trapped"), (2, "moving"))}
    bal = {k: balances(tr) for k, tr in runs.items()}
    # the particles' cost, measured with both scenes taking turns (the runs' own wall times depend on what the
    # report runs beside them); the full report only: it is a speed number, and it costs the quick report 3 CPU s
    us_w, us_0 = (None, None) if quick else step_costs([sc, sc.with_wear(count=0)], seed=seed)
    cost_ratio = None if quick else us_w / us_0
    band_rows = [{"band": [float(edges[i]), float(edges[i + 1])], "C_x_ratio": float(level[i]), "C_F_ratio": float(levelF[i]),
                  "particle_force_over_B2": float(r_b2[i]), "delta_C_F_over_B2": float(r_dCF[i])} for i in range(len(level))]
    d = {
        **fits["with"].to_dict(), "without_particles": fits["without"].to_dict(), "delta_gamma": dg,
        "delta_gamma_err": dg_err, "target_delta_gamma_0p4_met": rise_verdict(name, fits, dg, dg_err).agree, "bands": band_rows,
        "particle_force_fit": fit_p.to_dict(), "episodes": dur, "state_fractions": states,
        "wear": {k: wm.get(k) for k in ("count", "recycled", "left_interface", "asleep_at_end")},
        "particle_penetration_max_m": float(tw.particle_penetration.max()), "pad_penetration_max_m": float(tw.penetration.max()),
        "mean_velocity": vw, "mean_velocity_without": v0, "law_velocity": sc.steady_velocity,
        **bal["with"], "without_balances": bal["without"], "wall_s": wall_w + wall_0, "duration_s": T,
        "us_per_step": tw.metadata["us_per_step"], "us_per_step_without": t0.metadata["us_per_step"],
        "cost_ratio_particles": cost_ratio, "cost_us_per_step_interleaved": [us_w, us_0],
    }
    return SimpleNamespace(T=T, tw=tw, t0=t0, wall_w=wall_w, wall_0=wall_0, specs=specs, fspec=fspec, fits=fits,
                           band=band, dg=dg, dg_err=dg_err, level=level, levelF=levelF, ep=ep, dur=dur, sp=sp,
                           r_b2=r_b2, fit_p=fit_p, r_dCF=r_dCF, wm=wm, states=states, us_w=us_w, us_0=us_0,
                           cost_ratio=cost_ratio, band_rows=band_rows, v0=v0, vw=vw, d=d)


def rise_verdict(name, fits, dg, dg_err):
    """The particles' target, a rise of gamma by at least 0.4 beyond the 95 % interval; no verdict when either
    paired fit is not a power law."""
    flags = flags_of(fits["with"]) + flags_of(fits["without"])
    return interval_verdict(f"scenarios/{name}", "rise of gamma, paired runs", dg, dg_err, 0.4,
                            "+0.4 or more (target)", flags=flags, direction="above")


def _cost_text(sc, us_w, us_0, cost_ratio) -> str:
    """The particles' cost per step, measured with both scenes taking turns (full report), or where to find it."""
    if cost_ratio is None:
        return ("their cost per step, measured with both scenes taking turns (the runs' own times depend on what "
                "ran beside them), is in the full report.")
    return (f"measured side by side, {us_w:.0f} and {us_0:.0f} us per step, a cost ratio of {cost_ratio:.2f} at "
            f"{sc.run.iterations} solver iterations.")


def _text(name, sc, m) -> str:
    """The section's prose and its per-band table."""
    (T, tw, t0, wall_w, wall_0, fits, band, dg, dg_err, level, dur, r_b2, fit_p, r_dCF, wm, states, us_w, us_0,
     cost_ratio, band_rows, v0, vw, d) = attrgetter(
        "T", "tw", "t0", "wall_w", "wall_0", "fits", "band", "dg", "dg_err", "level", "dur", "r_b2", "fit_p", "r_dCF",
        "wm", "states", "us_w", "us_0", "cost_ratio", "band_rows", "v0", "vw", "d")(m)
    tr_, mv_ = dur.get("trapped", {}), dur.get("moving", {})
    rise = rise_verdict(name, fits, dg, dg_err)
    target = {True: "The target (particles raise gamma by at least 0.4) is met beyond the uncertainty. ",
              False: "The target (a rise of at least 0.4) is not established beyond the uncertainty at this run length. ",
              None: "No verdict on the target (a rise of at least 0.4): the fits it rests on are not power laws over "
                    "the band, so their exponents are descriptive only. "}[rise.agree]
    text = paragraphs([
        esc(sc.description.replace("\n", " ")),
        f"Paired runs of {T:g} s (same seed and substrate): {wall_w:.1f} s with particles ({tw.metadata['us_per_step']:.0f} us "
        f"per step), {wall_0:.1f} s without ({t0.metadata['us_per_step']:.0f} us); " + _cost_text(sc, us_w, us_0, cost_ratio)
        + f" Mean speed {1e3 * vw:.3f} mm/s with particles, {1e3 * v0:.3f} mm/s without "
        f"(law: {1e3 * sc.steady_velocity:.3f}): the grains add friction. Energy balance with particles "
        f"{pct(d['energy_balance_rel'])} (recycling moved {pct(float(tw.work_recycle[-1] / tw.work_drive[-1]), 4)} of the "
        f"drive's work); deepest grain overlap with a track {1e6 * d['particle_penetration_max_m']:.2f} um; "
        f"{wm.get('recycled')} recyclings, {wm.get('left_interface')} grains left the interface.",
        f"gamma = {fit_text(fits['with'])} with particles and {fit_text(fits['without'])} without, over "
        f"{span(band[0], band[1])} rad/s (3-30 v/a): a change of {rise.measured} (95 %). " + target
        + f"C_x(with) / C_x(without) per band: {min(level):.2f}-{max(level):.2f}. The reference is this scene without "
        "particles, cavities included; pads_friction_patches (no cavities) reads gamma near 4: the cavities alone "
        "change the pads' force noise.",
        f"Particles were idle (not touching their pad) {100 * states['idle']:.0f} % of the time, trapped under a pad "
        f"{100 * states['trapped']:.0f} % and moving with it {100 * states['moving']:.0f} % (trapped: mean speed over the output "
        f"step below {sc.wear.trapped_speed:g} v). Trapped episodes: {tr_.get('count', 0)}, median "
        f"{1e3 * tr_.get('tau_median', float('nan')):.1f} ms, 90 % below {1e3 * tr_.get('tau_q90', float('nan')):.0f} ms; moving "
        f"episodes: {mv_.get('count', 0)}, median {1e3 * mv_.get('tau_median', float('nan')):.1f} ms, longest "
        f"{mv_.get('tau_max', float('nan')):.2f} s.",
        f"Model II assumptions. The particles' summed force falls as omega^-({fit_text(fit_p)}) over the "
        "band, not the 1/f (omega^-1) that gives gamma = 5: the episode durations are not spread log-uniformly over decades "
        "but are mostly short (set by a pad's passage over a grain and by the cavity spacing). Eq. (B2) built from the "
        f"measured episodes (independent rectangles) reads the particles' force spectrum within a factor "
        f"{max(max(r_b2), 1 / min(r_b2)):.1f} per band (ratios {min(r_b2):.2f}-{max(r_b2):.2f}); the change in the friction "
        f"force's spectrum, C_F(with) - C_F(without), is {min(r_dCF):.2f}-{max(r_dCF):.2f} of that prediction, because at "
        "constant drive the block's response feeds back on the contact force.",
        f"Caveat: grains weigh at least {sc.wear.min_mass:g} kg (wear.min_mass), raised from their physical mass so the "
        "contact solver holds them on the tracks, and that inertia is not neutral: the grains' mean force on the pads "
        "read 0.35, 0.47 and 0.55 N at 1e-4, 3e-4 and 1e-3 kg (pads_with_wear, 30 iterations, measured). These "
        "numbers are not the massless limit of real debris.",
        "Models I and III are not compared here: the paired run isolates what the particles change.",
    ]) + table("Paired runs per log band", ["band (rad/s)", "C_x with / without", "C_F with / without",
                                           "particle force / B2", "(C_F with - without) / B2"],
               [[f"{span(b['band'][0], b['band'][1])}", f"{b['C_x_ratio']:.3f}", f"{b['C_F_ratio']:.3f}",
                 f"{b['particle_force_over_B2']:.3f}", f"{b['delta_C_F_over_B2']:.3f}"] for b in band_rows])
    return text


def _figures(name, sc, m) -> tuple:
    """The paired C_x spectra, the force spectra beside model II, and the episodes' histogram."""
    from .. import plots
    from ...analysis.episodes import model_II_from_episodes

    (T, tw, specs, fspec, fits, band, dg, dg_err, level, ep, dur, sp, r_b2, fit_p) = attrgetter(
        "T", "tw", "specs", "fspec", "fits", "band", "dg", "dg_err", "level", "ep", "dur", "sp", "r_b2", "fit_p")(m)
    w = np.logspace(np.log10(sp.omega_min), np.log10(sp.omega_max), 200)
    fig1 = plots.spectrum_figure([(specs["with"], f"with {sc.wear.count} particles"), (specs["without"], "without (same seed, substrate)")],
                                 fits=[(fits["with"], "with "), (fits["without"], "without ")], band=band,
                                 title=f"Scene {name}: paired runs, {T:g} s each")
    fig2 = plots.spectrum_figure([(sp, "particles' summed force on the pads"), (fspec["with"], "friction contact force, with"),
                                  (fspec["without"], "friction contact force, without")],
                                 [(w, model_II_from_episodes(ep, float(tw.t[-1]), w), "model II (B2) from the measured episodes")],
                                 ylabel=r"$C_F$ (N$^2$ s)", title="Force spectra and model II built from the episodes")
    fig3 = plots.episode_histogram_figure(ep, "Trap/release episodes (all particles)")
    tr_, mv_ = dur.get("trapped", {}), dur.get("moving", {})
    figures = (
        Figure(f"scene_{name}", plots.figure_png_bytes(fig1),
               f"Scene {name}: C_x with and without {sc.wear.count} particles (paired runs, {T:g} s each, same seed and "
               f"substrate). gamma {fits['with'].gamma:.2f} ± {fits['with'].gamma_err:.2f}{flag_mark(fits['with'])} with, "
               f"{fits['without'].gamma:.2f} ± {fits['without'].gamma_err:.2f}{flag_mark(fits['without'])} without (a "
               f"change of {dg:+.2f} ± {dg_err:.2f}{flag_mark(fits['with']) or flag_mark(fits['without'])}); C_x {min(level):.1f}-"
               f"{max(level):.1f}x higher with particles per band."),
        Figure(f"scene_{name}_forces", plots.figure_png_bytes(fig2),
               f"The particles' force on the pads, the friction contact force of both runs, and model II (B2) built from "
               f"the measured episodes: particles' force / B2 {min(r_b2):.2f}-{max(r_b2):.2f} per band; the particles' "
               f"force falls as omega^-{fit_p.gamma:.2f} ± {fit_p.gamma_err:.2f}{flag_mark(fit_p)} (1/f would be omega^-1)."),
        Figure(f"scene_{name}_episodes", plots.figure_png_bytes(fig3),
               f"Durations and mean forces of the trapped ({tr_.get('count', 0)}, median "
               f"{1e3 * tr_.get('tau_median', float('nan')):.1f} ms), moving ({mv_.get('count', 0)}, median "
               f"{1e3 * mv_.get('tau_median', float('nan')):.1f} ms) and idle episodes: durations do not spread "
               "log-uniformly over decades."),
    )
    return figures


def wear_result(name, sc, quick, seed, trace, duration, progress) -> StudyResult:
    """A scene with wear particles against the same scene without them, and model II built from its episodes."""
    m = _paired(name, sc, quick, seed, trace, duration, progress)
    T, wall_w, wall_0 = m.T, m.wall_w, m.wall_0
    return StudyResult(f"scenarios/{name}", f"Scene: {name}", m.d, _figures(name, sc, m), _text(name, sc, m),
                       verdicts=(rise_verdict(name, m.fits, m.dg, m.dg_err),), timings=
                       (timing(f"scene {name} (paired)", f"2 x {T:g} s, dt = {sc.run.dt:g} s, {sc.run.iterations} iterations",
                               f"{wall_w + wall_0:.2f}", "n/a (paired comparison)"),))
