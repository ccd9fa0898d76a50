"""Study: does model Ib, measured from ``pads_rough_profile`` at two scales, read that scene's C_x better than
model I?

Procedure (stated in the report as here). Per seed, the scene runs ``T`` seconds, recorded every step and
analysed at 1 ms with the pad forces averaged over each 1 ms (:func:`averaged_record`: a once-per-output-step
sample of the contact force aliases contact jitter into the top bands); then

1. model I as the report builds it (``compare.analysis.extract``): a = (12/7) x the pad forces' correlation length in
   sliding distance, alpha = sqrt(12) rms / f_kin, c from the law, k0, m, M from the scene (the "before"), from
   the pad forces sampled once per output step (as ``run.forces = "point"`` records them), and again from the averaged
   ones (as the recorder's default, and so the scenes study, has them);
2. the pad forces' spectrum (Welch, averaged over the pads) over 30 log bands from 4 frequency steps to half
   the output Nyquist is fitted by the sum of two renewal spectra (A8) at the measured speed, each with its own
   length and amplitude (:func:`reduced_models.multiscale_fit.fit_renewal_levels`): the slow level is the
   macro renewal (a, alpha f_kin), the fast one the finer roughness (a2, alpha2 f_kin2). Model Ib
   (:func:`~reduced_models.multiscale_fit.rigid_micro_params`) keeps model I's macro parameters and puts the fast
   level on one stiff micro contact per pad (a pad on a rough track has no second spring: T2 = 1 in the bands);
3. as a control for the procedure, the same spectral fit with one level (model I, spectral fit): it tells a
   better model from a better fit;
4. as a diagnostic for the response, the measured pad-force spectrum itself through model I's transfer
   function, C_x = |Z|^2 <C_f> / N (A5, A10 without any force model): where this misses, no force model can help.

Per-band ratios scene / closed form in the report's bands for model I (the scenes study's edges), three seeds,
geometric mean and its 95 % interval (t with 2 degrees of freedom on ln ratio).
"""
from __future__ import annotations

import math

import numpy as np

from reduced_models import multiscale as ms
from reduced_models import spring_block as m1
from reduced_models.multiscale_fit import RenewalLevel, fit_renewal_levels, rigid_micro_params

from ..html import paragraphs, span, table
from ...analysis.spectra import displacement_spectrum, force_series_spectrum
from ..study import Figure, Study, StudyResult
from ..verdict import Verdict
from ._common import band_ratios, timed, timing, whole_run

__all__ = ["STUDY", "run", "two_scale_comparison"]

NAME = "pads_rough_profile"
SEEDS = 3
DT_OUT = 1e-3  # s: the analysis step (the scene's own output step)
DURATION = 12.5  # s per seed, recorded every step: the shortest run whose spectra keep 4 s segments (2^12 samples)
T975 = {2: 4.303, 3: 3.182, 4: 2.776}  # Student t, 95 % two-sided, by degrees of freedom
MODELS = ("model I (report: sampled pad forces)", "model I (averaged pad forces)", "model I (spectral fit)",
          "model Ib (two-scale fit)", "measured force through model I's Z")


def averaged_record(tr, k: int):
    """The trace at every k-th step, its pad forces averaged over each k steps (not sampled): what steps 1-4 need
    (t, x, pad_force, n_contact, F_n, F_drag, metadata). Sampling the pad force once per output step aliases the
    contact jitter above the output Nyquist into the top bands (measured on an 8 s run recorded every step: 1 ms
    samples read 2.2x and 5.7x the per-step record's force spectrum in 498-884 and 884-1571 rad/s; 1 ms averages
    read 0.94x and 0.92x, the sinc^2 of the average)."""
    from types import SimpleNamespace

    n = (len(tr.t) // k) * k

    def mean(a):
        return a[:n].reshape(n // k, k, *a.shape[1:]).mean(axis=1)
    return SimpleNamespace(t=tr.t[:n:k], x=tr.x[:n:k], pad_force=mean(tr.pad_force), n_contact=mean(tr.n_contact),
                           F_n=mean(tr.F_n), F_drag=mean(tr.F_drag), metadata=tr.metadata)


def two_scale_comparison(tr, force_average_dt: float | None = None, sampled=None) -> dict:
    """Steps 1-4 of the module docstring on one trace: parameters and per-band ratios (JSON-able), and the
    spectra for a figure under "_spectra". ``force_average_dt``: the pad forces are averages over this interval
    (s), and their spectrum is divided by the average's exact gain sinc^2(omega dt / 2); None: samples.
    ``sampled``: the same run with its pad forces sampled once per output step (what ``run.forces = "point"``
    records), for model I from point samples; default ``tr``."""
    from ...analysis.extract import model_I_parameters, spring_block_params

    dt = float(tr.t[1] - tr.t[0])
    nper = min(2**12, 1 << int(math.floor(math.log2(len(tr.t) / 3))))
    spec = displacement_spectrum(tr.t, tr.x, nperseg=nper)
    ex = model_I_parameters(tr)
    p1 = spring_block_params(ex)
    v, f_kin = p1.v, p1.F_kin / p1.N
    f = tr.pad_force
    fs = [force_series_spectrum(tr.t, f[:, i], nperseg=nper) for i in range(f.shape[1])]
    Cf = np.mean([s.C for s in fs], axis=0)
    wf = fs[0].omega
    if force_average_dt:
        Cf = Cf / np.sinc(wf * force_average_dt / (2 * np.pi)) ** 2
    top = min(2000.0, math.pi / dt / 2)
    fit_edges = np.geomspace(4 * wf[1], top, 31)
    guess = (p1.a, p1.alpha * f_kin)
    (one,), res1 = fit_renewal_levels(wf, Cf, v, fit_edges, levels=1, guess=guess)
    (slow, fast), res2 = fit_renewal_levels(wf, Cf, v, fit_edges, levels=2, guess=guess)
    p1s = m1.SpringBlockParams(**{**_fields(p1), "a": one.a, "alpha": one.amplitude / f_kin})
    pb = rigid_micro_params(p1, slow, fast)
    Z, _ = ms.transfer_functions(ms.MultiscaleParams(**{**_fields(p1), "n_micro": 0, "F_kin2": 0.0}), spec.omega)
    forced = np.abs(Z) ** 2 * np.interp(spec.omega, wf, Cf) / p1.N
    edges = np.geomspace(max(2.0, 4 * spec.omega_min), top, 9)
    p1r = spring_block_params(model_I_parameters(sampled)) if sampled is not None else p1
    theories = (m1.theory_spectrum(p1r, spec.omega), m1.theory_spectrum(p1, spec.omega), m1.theory_spectrum(p1s, spec.omega),
                ms.theory_spectrum(pb, spec.omega), forced)
    ratios = {name: [b["ratio"] for b in band_ratios(spec, th, edges)] for name, th in zip(MODELS, theories)}
    lv = {"one_level": _level(one, f_kin), "slow": _level(slow, f_kin), "fast": _level(fast, f_kin)}
    return {"edges_rad_s": edges.tolist(), "ratios": ratios, "levels": lv, "fit_rms_ln": {"one_level": res1, "two_level": res2},
            "model_I_extracted": {"a": p1.a, "alpha": p1.alpha, "f_kin": f_kin, "v": v},
            "model_I_report_extracted": {"a": p1r.a, "alpha": p1r.alpha},
            "v_over_a2": v / fast.a, "v_over_a": v / slow.a,
            "_spectra": (spec, wf, Cf, p1, p1s, pb, fit_edges)}


def _fields(p: m1.SpringBlockParams) -> dict:
    return {k: getattr(p, k) for k in ("N", "v", "a", "k0", "M", "m", "eta0", "eta1", "alpha", "F_drive", "F_kin")} | {"k1": 0.0}


def _level(lv: RenewalLevel, f_kin: float) -> dict:
    return {"a_m": lv.a, "amplitude_N": lv.amplitude, "alpha_if_all_f_kin": lv.amplitude / f_kin}


def summarize(per_seed: list) -> dict:
    """Across seeds: per band and model, the geometric mean ratio and its 95 % interval (t on ln ratio), and the
    band-averaged |ln ratio| per seed."""
    out = {}
    k = len(per_seed)
    for name in MODELS:
        L = np.log(np.array([s["ratios"][name] for s in per_seed]))
        mean = L.mean(axis=0)
        half = T975.get(k - 1, 1.96) * L.std(axis=0, ddof=1) / math.sqrt(k) if k > 1 else np.full_like(mean, np.nan)
        out[name] = {"ratio": np.exp(mean).tolist(), "lo": np.exp(mean - half).tolist(), "hi": np.exp(mean + half).tolist(),
                     "mean_abs_ln_per_seed": np.mean(np.abs(L), axis=1).tolist()}
    return out


def _figure(first, name, T):
    from .. import plots

    spec, wf, Cf, p1, p1s, pb, fit_edges = first["_spectra"]
    w = np.geomspace(spec.omega_min, spec.omega_max, 300)
    fig = plots.spectrum_figure([(spec, f"scene {name}, {T:g} s")],
                                [(w, m1.theory_spectrum(p1, w), "model I (A10), extracted from the averaged pad forces"),
                                 (w, m1.theory_spectrum(p1s, w), "model I, one-level spectral fit"),
                                 (w, ms.theory_spectrum(pb, w), "model Ib, two-scale fit")],
                                title=f"{name}: model I against model Ib measured at two scales")
    ff = plots.new_figure(6.4, 4.6)
    ax = ff.add_subplot()
    ww = np.geomspace(fit_edges[0], fit_edges[-1], 300)
    m = (wf >= fit_edges[0]) & (wf <= fit_edges[-1])
    ax.loglog(wf[m], Cf[m], ".", ms=2, color="0.5", label="pad force, mean over pads (Welch)")
    lv = first["levels"]
    v = first["model_I_extracted"]["v"]
    from reduced_models.multiscale_fit import renewal_force_spectrum as rfs
    one = rfs(ww, v, lv["one_level"]["a_m"], lv["one_level"]["amplitude_N"])
    two = rfs(ww, v, lv["slow"]["a_m"], lv["slow"]["amplitude_N"]) + rfs(ww, v, lv["fast"]["a_m"], lv["fast"]["amplitude_N"])
    ax.loglog(ww, one, "--", label="one renewal level (A8), fitted")
    ax.loglog(ww, two, "-", label="two renewal levels (A8), fitted")
    ax.set_xlabel(r"$\omega$ (rad/s)")
    ax.set_ylabel(r"$C_f$ per pad (N$^2$ s)")
    ax.legend(fontsize=7)
    ax.set_title("Pad force: the fits that build the models", fontsize=9)
    ff.tight_layout()
    return plots.figure_png_bytes(fig), plots.figure_png_bytes(ff)


def run(quick: bool, seed: int) -> StudyResult:
    """Three seeds of the scene (``DURATION`` s each; quick: one seed of 6 s, said so), steps 1-4 on each."""
    from types import SimpleNamespace

    from engine_sim import load_scenario, shipped_scenarios

    sc = load_scenario(shipped_scenarios()[NAME])
    T, seeds = (6.0, [seed]) if quick else (DURATION, [seed + i for i in range(SEEDS)])
    per_seed, wall = [], 0.0
    k = int(round(DT_OUT / sc.run.dt))
    for s in seeds:  # recorded every step, analysed at DT_OUT with the pad forces averaged (averaged_record)
        tr, w = timed(whole_run, sc.with_run(duration=T, dt_out=sc.run.dt), seed=s)
        wall += w
        sampled = SimpleNamespace(t=tr.t[::k], x=tr.x[::k], pad_force=tr.pad_force[::k], n_contact=tr.n_contact[::k],
                                  F_n=tr.F_n[::k], F_drag=tr.F_drag[::k], metadata=tr.metadata)
        per_seed.append(two_scale_comparison(averaged_record(tr, k), force_average_dt=DT_OUT, sampled=sampled))
    summ = summarize(per_seed)
    first = per_seed[0]
    png_c, png_f = _figure(first, NAME, T)
    edges = first["edges_rad_s"]
    bands = [f"{span(edges[i], edges[i + 1])}" for i in range(len(edges) - 1)]

    def cell(name, i):
        r = summ[name]
        return f"{r['ratio'][i]:.2f} ({r['lo'][i]:.2f}-{r['hi'][i]:.2f})" if len(seeds) > 1 else f"{r['ratio'][i]:.2f}"
    rows = [[b] + [cell(n, i) for n in MODELS] for i, b in enumerate(bands)]
    rows.append(["mean |ln ratio| per seed"] + [", ".join(f"{x:.2f}" for x in summ[n]["mean_abs_ln_per_seed"]) for n in MODELS])
    lvs = [s["levels"] for s in per_seed]
    mI = summ[MODELS[0]]["mean_abs_ln_per_seed"]
    mIb = summ[MODELS[3]]["mean_abs_ln_per_seed"]
    better = sum(b < a for a, b in zip(mI, mIb))
    verdict = (f"Model Ib reads the scene better than model I in {better} of {len(seeds)} seeds by the band-averaged "
               f"|ln ratio| (model I {', '.join(f'{x:.2f}' for x in mI)}; model Ib {', '.join(f'{x:.2f}' for x in mIb)}).")
    parts = [
        f"<b>Procedure.</b> {len(seeds)} seed(s) of {NAME}, {T:g} s each, recorded every step and analysed at "
        f"{1e3 * DT_OUT:g} ms with the pad forces averaged over each output interval (a once-per-step sample of the contact "
        "force aliases contact jitter above the output Nyquist into the top bands: 2.2x and 5.7x in the top two). "
        "Model I as the report builds it (a from the pad "
        "forces' correlation length, alpha from their rms), from the forces sampled once per output step (the recorder's "
        "point mode: the before) and from the averaged forces (the recorder's default). Model Ib: the pad-force spectrum, averaged over pads, fitted "
        "over 30 log bands (4 frequency steps to half the output Nyquist) by the sum of two renewal spectra (A8) at the "
        "measured speed; the slow level is the macro renewal (a, alpha f_kin), the fast one the finer roughness (a2, "
        "alpha2 f_kin2), carried by one stiff micro contact per pad (T2 = 1 in the bands: the pads have no second "
        "spring). Controls: the same fit with one level (model I, spectral fit), and the measured pad-force spectrum "
        "through model I's transfer function (no force model at all).",
        "Measured levels (seed by seed): slow a = " + ", ".join(f"{1e3 * lv['slow']['a_m']:.3f}" for lv in lvs)
        + " mm, fast a2 = " + ", ".join(f"{1e6 * lv['fast']['a_m']:.1f}" for lv in lvs) + " um (v/a2 = "
        + ", ".join(f"{s['v_over_a2']:.0f}" for s in per_seed) + " rad/s); amplitudes slow "
        + ", ".join(f"{1e3 * lv['slow']['amplitude_N']:.1f}" for lv in lvs) + " mN, fast "
        + ", ".join(f"{1e3 * lv['fast']['amplitude_N']:.1f}" for lv in lvs) + " mN; one-level fit a = "
        + ", ".join(f"{1e3 * lv['one_level']['a_m']:.3f}" for lv in lvs) + " mm (report's extraction: "
        + ", ".join(f"{1e3 * s['model_I_report_extracted']['a']:.3f}" for s in per_seed) + " mm from sampled forces, "
        + ", ".join(f"{1e3 * s['model_I_extracted']['a']:.3f}" for s in per_seed) + " mm from averaged ones); rms ln misfit of the force "
        "spectrum one / two levels: " + ", ".join(f"{s['fit_rms_ln']['one_level']:.2f} / {s['fit_rms_ln']['two_level']:.2f}"
                                                 for s in per_seed) + ".",
        verdict,
    ]
    if quick:
        parts.append("Quick report: one seed of 6 s, no interval; the full report runs three seeds of "
                     f"{DURATION:g} s.")
    text = paragraphs(parts) + table(
        "C_x(scene) / C_x(model), per log band: geometric mean over seeds (95 % interval)",
        ["band (rad/s)", *MODELS], rows)
    numbers = {"procedure": __doc__.split("Procedure (stated in the report as here).")[1].strip(), "duration_s": T,
               "seeds": seeds, "per_seed": [{k: v for k, v in s.items() if not k.startswith("_")} for s in per_seed],
               "summary": summ, "model_Ib_better_seeds": better, "scene_wall_s": wall}
    cap1 = (f"{NAME}, seed {seeds[0]}, {T:g} s: scene C_x against model I (report's extraction), model I from a one-level "
            f"fit of the pad-force spectrum, and model Ib from a two-level fit. {verdict}")
    cap2 = ("Pad-force spectrum (mean over the pads) and the renewal spectra (A8) fitted to it, one and two levels: "
            "the parameters of the models in the previous figure.")
    verdicts = (Verdict("scenarios/pads_rough_profile_model_Ib", "mean |ln C_x ratio|, Ib vs I", f"{np.mean(mIb):.2f} against {np.mean(mI):.2f}"
                        + (f" ({len(seeds)} seeds)" if len(seeds) > 1 else " (1 seed)"), "Ib closer, every seed",
                        better == len(seeds), f"closer in {better} of {len(seeds)} seeds"),)
    return StudyResult("scenarios/pads_rough_profile_model_Ib", f"Model Ib measured from {NAME} at two scales", numbers,
                       (Figure("model_Ib_rough_cx", png_c, cap1), Figure("model_Ib_rough_force", png_f, cap2)), text,
                       (timing(f"scene {NAME} x {len(seeds)} (model Ib fit)", f"{T:g} s each", f"{wall:.2f}",
                               f"{float(np.mean(mIb)):.3f}"),), verdicts)


STUDY = Study(key="scenarios/pads_rough_profile_model_Ib", label="model Ib on the rough scene", run=run, quick=False, cost=75.4)
