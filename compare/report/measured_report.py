"""The report pages of a measured record: a friction force F(t) (:func:`build_force_report`, from
:func:`compare.analysis.force.analyze_force`) or a displacement x(t) (:func:`build_measured_report`), each with the
account of its time stamps' breaks and uniform segments when it has them."""
from __future__ import annotations

from pathlib import Path

from ..analysis.displacement import C_F_NEEDS_MASS, DisplacementAnalysis
from ..analysis.fits import flag_mark
from ..analysis.force import ForceAnalysis, analyze_force, mu_source
from ..analysis.strokes import Strokes, find_strokes
from .html import esc, fixed, paragraphs, span, table
from .verdict import fit_text
from ..io.measured import units_line
from .study import Figure, StudyResult
from .timeline_section import pieces_html, timeline_html

__all__ = ["Strokes", "ForceAnalysis", "find_strokes", "analyze_force", "build_force_report", "build_measured_report",
           "displacement_figure", "exponent_text", "floor_words"]


def build_force_report(an: ForceAnalysis):
    """Results (StudyResult list) and the JSON summary of a force analysis."""
    from frictionnoise.base import package_version

    from . import plots

    summary = {"version": package_version(), "kind": "force", **an.summary()}
    d, st, f = an.data, an.strokes, an.fit_F
    paras = [
        f"{len(d.t)} samples " + ("in uniform segments (below)" if an.pieces is not None else
                                  f"every {d.t[1] - d.t[0]:.4g} s") + f"; {esc(units_line(d))}"
        + (f". {esc(d.note)}" if getattr(d, "note", None) else "")
        + (f". {esc(d.warning)}" if d.warning else "."),
        f"Strokes ({esc(st.method)}): {st.found} found, {len(st.segments)} used, "
        f"{len(st.dropped)} dropped" + (" (" + "; ".join(f"stroke {i}: {esc(r)}" for i, r in st.dropped) + ")"
                                        if st.dropped else "")
        + f"; {st.cut_s:.4g} s cut at each end of a stroke (reversal transients); every stroke {st.used_s:.4g} s long "
          "after the cut, detrended by its own line; spectra averaged over the "
        + ("uniform pieces of the strokes (below)." if an.pieces is not None else "strokes."),
        f"Force exponent: C_F ~ omega^-({fit_text(f, 3)}) (95 %, {f.method}) over "
        f"{span(f.band[0], f.band[1])} rad/s{' (automatic band)' if f.band_auto else ''}"
        + (f" <b>not a power law: {esc('; '.join(f.flags))}</b>" if f.flags else "")
        + f"; F_rms = {summary['F_rms_N']:.4g} N over the resolved band (eq. 4), mean |F| = {summary['mean_abs_F_N']:.4g} N.",
    ]
    if an.fit_mu is not None:
        paras.append(f"C_mu of {esc(mu_source(d))}: exponent {fit_text(an.fit_mu, 3)}; "
                     f"mu_rms = {summary['mu_rms']:.4g}, mean |mu| = {summary['mean_abs_mu']:.4g}.")
    if summary.get("blocks"):
        paras.append(f"By block (the pooled means above mix blocks run at different loads): " + "; ".join(
            f"block {b['block']}{esc(' (' + b['title'] + ')') if b['title'] else ''}, t = {b['t_start_s']:.6g}-"
            f"{b['t_stop_s']:.6g} s: mean |F| = {b['mean_abs_F_N']:.4g} N"
            + (f", mean |mu| = {b['mean_abs_mu']:.4g}" if "mean_abs_mu" in b else "")
            + (f", mean |N| = {b['mean_abs_N_N']:.4g} N" if "mean_abs_N_N" in b else "") for b in summary["blocks"])
            + ".")
    if an.fit_x_equiv is not None:
        paras.append(f"Equivalent C_x of a free block of M = {an.mass:g} kg (C_F / (M^2 omega^4), eq. (3); inferred, "
                     f"not a measured displacement): gamma = {fit_text(an.fit_x_equiv, 3)}.")
    if an.speed is not None:
        paras.append(f"Sliding speed {an.speed:g} m/s: stroke length {summary['stroke_length_m']:.4g} m "
                     f"({summary['used_stroke_length_m']:.4g} m used); distance-domain spectrum over "
                     f"q = {span(an.C_F_distance.omega_min, an.C_F_distance.omega_max)} rad/m.")
    paras += [esc(n) for n in an.notes]
    paras.append("Processing: " + esc("; ".join(summary["spectrum_steps"])) + ".")
    figures = [Figure("measured_force_CF", plots.figure_png_bytes(plots.spectrum_figure(
        [(an.C_F, "C_F (measured)")], fits=[(f, "")], band=f.band, ylabel=r"$C_F$ (N$^2$ s)",
        title="Friction-force spectrum")),
        f"C_F of the measured friction force (N^2 s), averaged over {len(st.segments)} strokes"
        + (f" ({len(an.pieces.used)} uniform pieces)" if an.pieces is not None else "") + ", with the power-law fit: "
        f"C_F slope -{f.gamma:.2f} ± {f.gamma_err:.2f}{flag_mark(f)} over {span(f.band[0], f.band[1])} rad/s"
        + (" (not a power law: " + "; ".join(f.flags) + ")." if f.flags else "."))]
    nums = st.numbers or range(1, len(st.segments) + 1)
    rows = [[str(i), f"{d.t[a]:.4g}", f"{d.t[a] + st.used_s:.4g}", "used"] for i, (a, _) in zip(nums, st.segments)]
    tab = table("Strokes used (times after the cut; every used stroke trimmed to the same length) and dropped "
                "(stroke numbers count all strokes found)", ["#", "start (s)", "end (s)", "status"],
                rows + [[str(i), "", "", f"dropped: {esc(r)}"] for i, r in st.dropped])
    if an.pieces is not None:
        tab += pieces_html(d.timeline, an.piece_fits)
    if an.C_F_distance is not None:
        fig = plots.spectrum_figure([(an.C_F_distance, "C_F(q), q = omega / v")], ylabel=r"$C_F(q)$ (N$^2$ m)",
                                    title=f"Friction force against sliding distance (v = {an.speed:g} m/s)")
        fig.axes[0].set_xlabel(r"$q$ (rad/m)")
        figures.append(Figure("measured_force_CF_distance", plots.figure_png_bytes(fig),
                              f"C_F in the distance domain: the same spectrum against q = omega / v, v = {an.speed:g} m/s."))
    if an.C_mu is not None:
        figures.append(Figure("measured_force_Cmu", plots.figure_png_bytes(plots.spectrum_figure(
            [(an.C_mu, f"C_mu of {mu_source(d)}")], ylabel=r"$C_\mu$ (s)", title="Friction coefficient spectrum")),
            f"C_mu of {mu_source(d)}: exponent {an.fit_mu.gamma:.2f} ± {an.fit_mu.gamma_err:.2f}{flag_mark(an.fit_mu)}."
            if an.fit_mu is not None else f"C_mu of {mu_source(d)}."))
    if an.C_x_equiv is not None:
        figures.append(Figure("measured_force_Cx_equivalent", plots.figure_png_bytes(plots.spectrum_figure(
            [(an.C_x_equiv, "equivalent free-block C_x (eq. 3)")], title="Equivalent C_x of a free block (inferred)")),
            f"C_F / (M^2 omega^4) with M = {an.mass:g} kg: the displacement a free block would show (eq. 3), inferred."))
    result = StudyResult("measured", f"Measured friction force: {Path(d.source).name}", {}, tuple(figures),
                         paragraphs(paras) + tab)
    return [result], summary


def exponent_text(fit, digits: int = 3, pm: str = "&plusmn;") -> str:
    """An exponent as the page states it: "3.988 &plusmn; 0.052 (95 % [3.937, 4.041], record)", the +- half the
    interval's width (the rule of the terminal's line and of docs/explanation/identification.md); a band fit's
    interval is gamma +- its half-width. ``pm``: the sign as the text it goes into writes it (a caption is
    escaped: "±")."""
    lo = getattr(fit, "gamma_low", fit.gamma - fit.gamma_err)
    hi = getattr(fit, "gamma_high", fit.gamma + fit.gamma_err)
    return (f"{fixed(fit.gamma, digits)} {pm} {fit.gamma_err:.{digits}f} (95 % [{lo:.{digits}f}, {hi:.{digits}f}], "
            f"{fit.method}){flag_mark(fit)}")


def floor_words(fit) -> str:
    """The sensor's white floor and why the band ends where it does, as a sentence of the page: the record model's
    :func:`~compare.analysis.record_model.band_end_words` with the floor's level in m rms and m^2 s; a band fit of
    the Welch spectrum fits no floor and says so."""
    if getattr(fit, "method", "") != "record":
        return (f"No floor term: the {fit.method} fit takes a power law alone over the band "
                f"{span(fit.band[0], fit.band[1])} rad/s of the Welch spectrum"
                + (" (given)." if not fit.band_auto else " (its widest straight stretch)."))
    from ..analysis.record_model import band_end_words

    words = band_end_words(fit.band_end, fit.floor_rms, fit.crossover, fit.band[1], fit.gamma,
                           [s[:3] for s in fit.segments], " m").lstrip("; ")
    level = (f" (level B = {fit.floor:.3g} m^2 s of C_x)" if fit.floor > 0 else "")
    if fit.floor > 0:
        words = words.replace(" rms", f" rms{level}", 1)
    else:
        words = words.replace("no white floor detected", "no white floor resolved (B = 0: the fit's floor term sits "
                              "at its bound)", 1)
    why = {"floor": "", "departure": "",
           "last frequency": f"; the band reaches the record's highest frequency, {fit.band[1]:.4g} rad/s (Nyquist)",
           "given": f"; the band ends at {fit.band[1]:.4g} rad/s, the band given (--band)"}[fit.band_end]
    return "Sensor floor and band end: " + esc(words + why) + "."


def _fitted_band(fit, C_x) -> tuple:
    """The band whose ordinates the fit summed over (rad/s): the given or searched band, else the record's whole
    range of Fourier frequencies (the record model) or the fit's band (a band fit of the Welch spectrum)."""
    if getattr(fit, "method", "") != "record":
        return tuple(fit.band)
    if fit.fit_band:
        return tuple(fit.fit_band)
    import math

    m = fit.n_samples - fit.order  # the differenced record's Fourier ordinates j = 1 .. ceil(m/2) - 1
    return (fit.band[0], (math.ceil(m / 2) - 1) * 2 * math.pi / (m * float(C_x.provenance["dt"])))


def _binned_periodogram(C_x, top: float, per_decade: int = 20):
    """The raw periodogram C_x carries (the differenced record's, re-coloured to C_x) up to ``top`` (rad/s),
    averaged in log bins: the record's whole resolution, down to its lowest Fourier frequency 2 pi / (n dt)."""
    from types import SimpleNamespace

    import numpy as np

    w, p = C_x.periodogram_omega, np.asarray(C_x.periodogram, dtype=float)
    w, p = w[w <= top], p[w <= top]
    edges = np.logspace(np.log10(w[0]) - 1e-9, np.log10(w[-1]) + 1e-9,
                        max(2, int(np.ceil(per_decade * np.log10(w[-1] / w[0]))) + 1))
    idx = np.searchsorted(edges, w, side="right") - 1
    cnt = np.bincount(idx, minlength=len(edges))
    keep = cnt > 0
    om = np.exp(np.bincount(idx, weights=np.log(w), minlength=len(edges))[keep] / cnt[keep])
    return SimpleNamespace(omega=om, C=np.bincount(idx, weights=p, minlength=len(edges))[keep] / cnt[keep])


def displacement_figure(an: DisplacementAnalysis):
    """The displacement spectrum's figure and caption: the Welch C_x; for the record model, which fits every Fourier
    ordinate of the record, the record's periodogram below the Welch average (log-binned, down to the band's lowest
    frequency) and the fitted model A omega^-gamma + B (its power law alone over the identified band); the band the
    fit summed over, shaded.

    Returns
    -------
    (matplotlib.figure.Figure, str)
        The figure and its caption (plain text: the page escapes it).
    """
    import numpy as np

    from . import plots

    fit, spec = an.fit, an.C_x
    fitted = _fitted_band(fit, spec)
    measured = [(spec, f"C_x, Welch (segments of {spec.provenance.get('nperseg', '?')} samples)")]
    record = getattr(fit, "method", "") == "record"
    join = 2.0 * spec.omega_min  # the periodogram below the Welch average, overlapping it by an octave
    has_pgram = record and spec.periodogram is not None and spec.periodogram_omega[0] < spec.omega_min
    if has_pgram:
        measured.append((_binned_periodogram(spec, join), f"C_x, periodogram of the whole record (below {join:.3g} rad/s)"))
    fig = plots.spectrum_figure(measured, fits=[(fit, "")], band=fitted, title="Displacement spectrum")
    ax = fig.axes[0]
    if record:
        w = np.logspace(np.log10(fitted[0]), np.log10(fitted[1]), 200)
        ax.loglog(w, fit.level(w) + fit.floor, color="C3", lw=1.0, zorder=5,
                  label=r"fitted model $A\omega^{-\gamma} + B$" if fit.floor > 0 else
                  r"fitted model $A\omega^{-\gamma}$ (no floor resolved)")
        if fit.floor > 0:
            ax.axhline(fit.floor, color="C3", ls=":", lw=1.0, zorder=3, label=f"white floor B ({fit.floor_rms:.3g} m rms)")
        if fit.band_end == "floor":
            ax.axvline(fit.band[1], color="0.3", ls="--", lw=0.8, zorder=3, label=f"crossover {fit.band[1]:.3g} rad/s")
        handles, labels = ax.get_legend_handles_labels()  # the fit lines' labels (mathtext) have a legend of their own
        # below the axes: inside, it covered the Welch points and the floor it names
        ax.legend(handles=[h for h, lab in zip(handles, labels) if not lab.startswith("$")], fontsize=7,
                  loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
        fig.tight_layout()
    lo = min(fitted[0], fit.band[0], spec.omega_min, spec.periodogram_omega[0] if has_pgram else np.inf)
    ax.set_xlim(lo / 1.3, max(fitted[1], spec.omega_max) * 1.3)
    pgram = (f" (from {spec.omega_min:.3g} rad/s); below {join:.3g} rad/s the periodogram of the whole record "
             f"({spec.provenance.get('prewhiten_order', 2)}-times differenced, rectangular window, re-coloured to C_x, "
             f"averaged in 20 bins a decade), which reaches the record's lowest Fourier frequency "
             f"{spec.periodogram_omega[0]:.3g} rad/s"
             + (" as the fit does" if fitted[0] <= 1.01 * spec.periodogram_omega[0] else "") if has_pgram else "")
    model = (f"; the fitted record model A ω^-γ + B (red; B dotted: {fit.floor_rms:.3g} m rms) and its power law "
             f"alone over the identified band {span(fit.band[0], fit.band[1])} rad/s (black)"
             if record and fit.floor > 0 else
             f"; the fitted record model, a power law with no floor resolved (red), and the power law over the "
             f"identified band {span(fit.band[0], fit.band[1])} rad/s (black)" if record else
             f"; the power-law fit over {span(fit.band[0], fit.band[1])} rad/s (black)")
    caption = (f"C_x of the measured displacement (m^2 s): the Welch average{pgram}{model}; gamma = "
               f"{exponent_text(fit, pm='±')}. Shaded: the band the fit summed over, {span(*fitted)} rad/s"
               + ("" if not record or fit.fit_band else " (every Fourier ordinate of the record)") + ".")
    return fig, caption


def build_measured_report(an: DisplacementAnalysis, data):
    """Results (StudyResult list) and the JSON summary of a displacement analysis of the record ``data``.

    C_F and its figure appear only when the analysis was given a mass; otherwise the page says that C_F needs it.
    """
    from frictionnoise.base import package_version

    from . import plots

    fit, spec, segs = an.fit, an.C_x, an.segments
    summary = {"version": package_version(), "source": data.source, "n_samples": len(data.t),
               "dt_s": float(spec.provenance["dt"]), "resampled": data.resampled, "warning": data.warning,
               "layout": data.layout, **an.summary()}
    if data.timeline is not None:
        summary["timeline"] = data.timeline.summary()
    relation = (f"C_F = M^2 omega^4 C_x assumes the block is free (inertial relation, eq. 3), with M = {an.mass:g} kg: "
                f"C_F ~ omega^-({fit_text(an.fit_F, 3)}), F_rms = {an.F_rms:.4g} N over the fitted band."
                if an.mass is not None else esc(C_F_NEEDS_MASS) + ".")
    every = "in uniform segments (below)" if segs is not None else f"every {spec.provenance['dt']:.4g} s"
    text = paragraphs([
        f"{len(data.t)} samples {every}; mean velocity {1e3 * an.mean_velocity:.4g} mm/s"
        + (f". {esc(data.warning)}" if data.warning else "."),
        f"gamma = {exponent_text(fit)} over "
        f"{span(fit.band[0], fit.band[1])} rad/s{' (automatic band)' if fit.band_auto else ''}"
        + (f" <b>not a power law: {esc('; '.join(fit.flags))}</b>" if fit.flags else "")
        + f"; zeta_rms = {an.zeta_rms:.4g} m over the resolved band (eq. 4) and mu_rms = {an.mu_rms:.4g} "
        f"(dimensionless, C_mu = omega^4 C_x / g^2 of a free block, whatever its mass) over {span(*an.rms_band)} rad/s, "
        "the fitted band within the Welch spectrum's (omega^4 weighs a sensor's white floor above it, which is not friction).",
        floor_words(fit),
        relation,
        "Processing: " + esc("; ".join(summary["spectrum_steps"])) + ".",
    ]) + (timeline_html(data.timeline, an.segment_fits, segs.notes) if segs is not None else "")
    cx_figure, cx_caption = displacement_figure(an)
    figures = [
        Figure("measured_Cx", plots.figure_png_bytes(cx_figure), cx_caption),
        Figure("measured_Cmu", plots.figure_png_bytes(plots.spectrum_figure([(an.C_mu, "C_mu = omega^4 C_x / g^2")],
                                                                           ylabel=r"$C_\mu$ (s)",
                                                                           title="Friction coefficient spectrum")),
               f"C_mu (s) = omega^4 C_x / g^2; mu_rms = {an.mu_rms:.3g} over {span(*an.rms_band)} rad/s, the fitted band "
               "within the Welch spectrum's (eq. 4)."),
    ]
    if an.C_F is not None:
        figures.insert(1, Figure(
            "measured_CF", plots.figure_png_bytes(plots.spectrum_figure([(an.C_F, "C_F = M^2 omega^4 C_x")],
                                                                        ylabel=r"$C_F$ (N$^2$ s)",
                                                                        title="Force spectrum (eq. 3)")),
            f"C_F (N^2 s) of a free block of M = {an.mass:g} kg, from C_x by eq. (3): slope {4 - fit.gamma:+.2f} in the "
            "fit band."))
    return [StudyResult("measured", f"Measured displacement: {Path(data.source).name}", {}, tuple(figures), text)], summary
