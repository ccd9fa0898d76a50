"""Measured friction force F(t): strokes, C_F, the force exponent, C_mu, and the report section.

Tribometers run at constant speed and record the friction force. A reciprocating test reverses every stroke;
the reversal (stop, stick, re-start) is a transient that does not belong to the sliding noise, so the record is
split into strokes, a stated length is cut at both ends of each, each stroke is detrended by its own line, and
the spectra of the strokes are averaged (:func:`compare.spectra.average_spectra`). A continuous (pin-on-disc)
record is one stroke.

Strokes are found, in this order of preference, from a direction column (runs of equal value), from the
position (turning points between crossings of the 10 % and 90 % levels of its range) or, for force-only files,
from the sign of the friction force (with hysteresis at half its median magnitude: the friction force opposes
the motion). The numerics here are pure; :func:`build_force_report` turns an analysis into report sections.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..analysis.displacement import C_F_NEEDS_MASS, DisplacementAnalysis
from ..analysis.fits import PowerLawFit, fit_power_law, flag_mark
from .html import esc, paragraphs, span, table
from .verdict import fit_text
from ..io.measured import MeasuredData, units_line
from ..analysis.spectra import Spectrum, rescaled, average_spectra, rms_from_spectrum, series_spectrum
from .study import Figure, StudyResult
from .timeline_section import timeline_html
from ..analysis.segments import with_line_flag

__all__ = ["Strokes", "ForceAnalysis", "find_strokes", "analyze_force", "build_force_report", "build_measured_report"]

_KEEP_FRACTION = 0.8  # a stroke shorter than this share of the median (after the cut) is partial: dropped
_DEFAULT_CUT = 0.1  # share of the median stroke duration cut at each end, unless a cut is given


@dataclass(frozen=True)
class Strokes:
    """Stroke split of a record. ``segments`` are the (start, stop) sample ranges used, after the cut."""

    method: str
    found: int
    segments: list
    dropped: list  # (stroke number, reason)
    cut_s: float
    duration_s: float  # median stroke duration before the cut
    used_s: float  # common length of every used stroke after the cut


def _runs(labels: np.ndarray) -> np.ndarray:
    """Boundaries (including 0 and len) of runs of equal labels."""
    change = np.flatnonzero(labels[1:] != labels[:-1]) + 1
    return np.concatenate([[0], change, [len(labels)]])


def _hysteresis(y: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """+1 after y rose above ``hi``, -1 after it fell below ``lo``; before the first crossing, the first state."""
    s = np.where(y > hi, 1, np.where(y < lo, -1, 0))
    idx = np.where(s != 0, np.arange(len(s)), 0)
    np.maximum.accumulate(idx, out=idx)
    state = s[idx]
    first = np.flatnonzero(s)
    if first.size:
        state[: first[0]] = s[first[0]]
    return state


def _position_boundaries(x: np.ndarray) -> np.ndarray:
    """Turning points of a back-and-forth position: the extreme between successive 10 %/90 % level crossings."""
    p1, p99 = np.percentile(x, [1, 99])
    amp = p99 - p1
    state = _hysteresis(x, p1 + 0.1 * amp, p1 + 0.9 * amp)
    runs = _runs(state)
    bounds = [0]
    for a, b in zip(runs[1:-1], runs[2:]):  # a state run [a, b) begins at a crossing; the turn lies before a
        prev = bounds[-1]
        seg = x[prev:a]
        if len(seg) == 0:
            continue
        turn = prev + (int(np.argmax(seg)) if state[a] < 0 else int(np.argmin(seg)))
        if turn > prev:
            bounds.append(turn)
    # a last partial stroke: the extreme in the direction of the last state, if the position came back from it
    prev = bounds[-1]
    seg = x[prev:]
    if len(seg) > 1:
        turn = int(np.argmax(seg)) if state[-1] > 0 else int(np.argmin(seg))
        if 0 < turn < len(seg) - 1 and abs(seg[-1] - seg[turn]) > 0.05 * amp:
            bounds.append(prev + turn)
    bounds.append(len(x))
    return np.asarray(bounds)


def find_strokes(data: MeasuredData, *, cut: float | None = None) -> Strokes:
    """Split a record into strokes (see the module docstring); ``cut`` seconds are removed at both ends."""
    n = len(data.t)
    dt = float(data.t[1] - data.t[0])
    if data.direction is not None:
        method, bounds = "direction column", _runs(np.asarray(data.direction))
    elif data.x is not None and np.ptp(data.x) > 0 and not _monotone(data.x):
        method, bounds = "sign of the position's derivative", _position_boundaries(np.asarray(data.x))
    elif data.F is not None:
        h = 0.5 * float(np.median(np.abs(data.F)))
        state = _hysteresis(np.asarray(data.F), -h, h)
        method, bounds = "sign of the friction force", _runs(state)
    else:
        method, bounds = "continuous", np.array([0, n])
    if len(bounds) <= 2:
        method = f"continuous (one stroke; split by {method})" if method != "continuous" else method
        bounds = np.array([0, n])
    lengths = np.diff(bounds)
    found = len(lengths)
    dur = float(np.median(lengths)) * dt
    if found == 1:
        cut_s = 0.0 if cut is None else float(cut)
    else:
        cut_s = _DEFAULT_CUT * dur if cut is None else float(cut)
    if cut_s < 0:
        raise ValueError(f"cut must be >= 0 s (got {cut_s})")
    c = int(round(cut_s / dt))
    inner = [(int(a) + c, int(b) - c) for a, b in zip(bounds[:-1], bounds[1:])]
    med = float(np.median([max(b - a, 0) for a, b in inner]))
    kept, dropped = [], []
    for i, (a, b) in enumerate(inner, start=1):
        if b - a < _KEEP_FRACTION * med or b - a < 64:
            dropped.append((i, f"partial: {(b - a) * dt:.4g} s after the cut, median {med * dt:.4g} s"))
        else:
            kept.append((a, b))
    if not kept:
        raise ValueError(f"no stroke is long enough after cutting {cut_s:.4g} s at each end "
                         f"({found} strokes of median {dur:.4g} s)")
    L = min(b - a for a, b in kept)
    segs = [(a, a + L) for a, _ in kept]
    return Strokes(method=method, found=found, segments=segs, dropped=dropped, cut_s=c * dt,
                   duration_s=dur, used_s=L * dt)


def _monotone(x: np.ndarray) -> bool:
    d = np.diff(x)
    return bool(np.all(d >= 0) or np.all(d <= 0)) or abs(x[-1] - x[0]) > 0.8 * np.ptp(x)


def _stroke_spectrum(t, y, strokes: Strokes, quantity: str, unit: str, prewhiten, nperseg) -> Spectrum:
    """Spectra of every stroke (each detrended by its own line, same pre-whitening order), averaged.

    By default each stroke is one Welch segment (the longest resolved wavelength; averaging comes from the
    strokes); a continuous record keeps the usual segment length.
    """
    a0, b0 = strokes.segments[0]
    if nperseg is None and len(strokes.segments) > 1:
        nperseg = b0 - a0  # one Hann segment per stroke: the strokes supply the averaging
    first = series_spectrum(t[a0:b0], y[a0:b0], quantity=quantity, unit=unit, detrend="linear",
                            prewhiten=prewhiten, nperseg=nperseg, name=quantity)
    k = first.provenance["prewhiten_order"]
    specs = [first] + [series_spectrum(t[a:b], y[a:b], quantity=quantity, unit=unit, detrend="linear",
                                       prewhiten=k, nperseg=first.provenance["nperseg"], name=quantity)
                       for a, b in strokes.segments[1:]]
    return specs[0] if len(specs) == 1 else average_spectra(specs, label="strokes")


@dataclass(frozen=True)
class ForceAnalysis:
    """Everything measured from a force record. Spectra in the eq. (2) convention."""

    data: MeasuredData
    strokes: Strokes
    C_F: Spectrum
    fit_F: PowerLawFit
    C_mu: Spectrum | None = None
    fit_mu: PowerLawFit | None = None
    C_x_equiv: Spectrum | None = None
    fit_x_equiv: PowerLawFit | None = None
    C_F_distance: Spectrum | None = None
    mass: float | None = None
    speed: float | None = None
    notes: list = field(default_factory=list)

    def summary(self) -> dict:
        """The analysis as JSON-able numbers (the report's summary.json).

        Returns
        -------
        dict
            Source, units, strokes, the force exponent with its 95 % interval and band (rad/s), F_rms (N), and
            the C_mu, equivalent-C_x and distance-domain entries when present.
        """
        st = self.strokes
        s = {
            "source": self.data.source, "units": self.data.units, "layout": self.data.layout,
            "n_samples": len(self.data.t), "dt_s": float(self.data.t[1] - self.data.t[0]),
            "resampled": self.data.resampled, "warning": self.data.warning,
            "strokes": {"method": st.method, "found": st.found, "used": len(st.segments),
                        "dropped": [{"stroke": i, "reason": r} for i, r in st.dropped],
                        "cut_each_end_s": st.cut_s, "median_duration_s": st.duration_s, "used_length_s": st.used_s},
            "force_exponent": self.fit_F.gamma, "force_exponent_err": self.fit_F.gamma_err,
            "band": list(self.fit_F.band), "fit_F": self.fit_F.to_dict(),
            "F_rms_N": rms_from_spectrum(self.C_F),
            "mean_abs_F_N": float(np.mean(np.abs(self.data.F))),
            "spectrum_steps": self.C_F.provenance["steps"], "notes": list(self.notes),
        }
        if self.fit_mu is not None:
            s["fit_mu"] = self.fit_mu.to_dict()
            s["mu_rms"] = rms_from_spectrum(self.C_mu)
            s["mean_abs_mu"] = float(np.mean(np.abs(self.data.F / self.data.N)))
        if self.fit_x_equiv is not None:
            s["mass_kg"] = self.mass
            s["equivalent_free_block_Cx"] = {"label": "equivalent C_x of a free block, C_F / (M^2 omega^4), eq. (3); "
                                                      "not a measured displacement",
                                             "fit": self.fit_x_equiv.to_dict()}
        if self.speed is not None:
            s["speed_m_per_s"] = self.speed
            s["stroke_length_m"] = self.speed * st.duration_s
            s["used_stroke_length_m"] = self.speed * st.used_s
            s["distance_domain"] = {"q_min_rad_per_m": self.C_F_distance.omega_min,
                                    "q_max_rad_per_m": self.C_F_distance.omega_max, "unit": "N^2 m"}
        return s


def analyze_force(data: MeasuredData, *, band=None, mass: float | None = None, speed: float | None = None,
                  cut: float | None = None, method: str | None = None, prewhiten="auto",
                  nperseg: int | None = None) -> ForceAnalysis:
    """C_F of a measured friction force (averaged over strokes), its exponent, and what follows from it.

    ``mass`` (kg) adds the equivalent C_x = C_F / (M^2 omega^4) of a free block (eq. 3); ``speed`` (m/s)
    adds the distance-domain spectrum C_F(q) = v C_F(omega = q v) (q in rad/m) and the stroke length; a
    normal-force column adds C_mu of mu(t) = F(t) / N(t).

    Parameters
    ----------
    data : MeasuredData
        A record with a friction-force column (and optionally normal force, position or direction).
    band : tuple of float, optional
        Fit band (Units: rad/s); default automatic.
    mass : float, optional
        Block mass M (Units: kg).
    speed : float, optional
        Imposed sliding speed (Units: m/s).
    cut : float, optional
        Seconds removed at each end of a stroke (Units: s); default 10 % of the median stroke.
    method : {"whittle", "lsq"}, optional
        Fit method (see :func:`compare.fits.fit_power_law`).
    prewhiten, nperseg
        As in :func:`compare.spectra.series_spectrum`.

    Returns
    -------
    ForceAnalysis
        The strokes, C_F (N^2 s) and its fit, and C_mu (s), the equivalent C_x (m^2 s) and C_F(q) (N^2 m) when
        their inputs were given.
    """
    if data.F is None:
        raise ValueError("the record holds no friction-force column")
    if data.segmented:
        raise ValueError(f"force data whose time stamps break ({data.timeline.events[0].describe()}; "
                         f"{len(data.timeline.events)} breaks in all): give --resample DT to put it on one grid")
    if mass is not None and not mass > 0:
        raise ValueError(f"mass must be positive (got {mass!r})")
    if speed is not None and not speed > 0:
        raise ValueError(f"speed must be positive (got {speed!r})")
    strokes = find_strokes(data, cut=cut)
    t, F = np.asarray(data.t), np.asarray(data.F)
    C_F = _stroke_spectrum(t, F, strokes, "F", "N^2 s", prewhiten, nperseg)
    fit_F = with_line_flag(fit_power_law(C_F, band=band, method=method), C_F)
    notes = []
    C_mu = fit_mu = None
    if data.N is not None:
        if np.any(data.N == 0):
            notes.append("the normal force is zero somewhere; C_mu not computed")
        else:
            C_mu = _stroke_spectrum(t, F / np.asarray(data.N), strokes, "mu", "s", prewhiten, nperseg)
            fit_mu = fit_power_law(C_mu, band=band, method=method)
    else:
        notes.append("no normal-force column: C_mu not computed")
    C_x = fit_x = None
    if mass is not None:
        C_x = rescaled(C_F, lambda w: 1.0 / (mass**2 * w**4), "x", "m^2 s",
                        f"equivalent free-block C_x = C_F / (M^2 omega^4), M = {mass:g} kg  [eq. (3)]")
        fit_x = fit_power_law(C_x, band=band, method=method)
    C_q = None
    if speed is not None:
        prov = dict(C_F.provenance)
        prov["steps"] = list(prov["steps"]) + [f"distance domain: q = omega / v, C(q) = v C(omega), v = {speed:g} m/s"]
        C_q = Spectrum(omega=C_F.omega / speed, C=C_F.C * speed, quantity="F(q)", unit="N^2 m", n_avg=C_F.n_avg,
                       dof=C_F.dof, provenance=prov)
    return ForceAnalysis(data=data, strokes=strokes, C_F=C_F, fit_F=fit_F, C_mu=C_mu, fit_mu=fit_mu, C_x_equiv=C_x,
                         fit_x_equiv=fit_x, C_F_distance=C_q, mass=mass, speed=speed, notes=notes)


def build_force_report(an: ForceAnalysis):
    """Results (StudyResult list) and the JSON summary of a force analysis."""
    from frictionnoise import package_version

    from . import plots

    summary = {"version": package_version(), "kind": "force", **an.summary()}
    d, st, f = an.data, an.strokes, an.fit_F
    paras = [
        f"{len(d.t)} samples every {d.t[1] - d.t[0]:.4g} s; {esc(units_line(d))}"
        + (f". {esc(d.warning)}" if d.warning else "."),
        f"Strokes found from the {esc(st.method)}: {st.found} found, {len(st.segments)} used, "
        f"{len(st.dropped)} dropped" + (" (" + "; ".join(f"stroke {i}: {esc(r)}" for i, r in st.dropped) + ")"
                                        if st.dropped else "")
        + f"; {st.cut_s:.4g} s cut at each end of a stroke (reversal transients); every stroke {st.used_s:.4g} s long "
          f"after the cut, detrended by its own line; spectra averaged over the strokes.",
        f"Force exponent: C_F ~ omega^-({fit_text(f, 3)}) (95 %, {f.method}) over "
        f"{span(f.band[0], f.band[1])} rad/s{' (automatic band)' if f.band_auto else ''}"
        + (f" <b>not a power law: {esc('; '.join(f.flags))}</b>" if f.flags else "")
        + f"; F_rms = {summary['F_rms_N']:.4g} N over the resolved band (eq. 4), mean |F| = {summary['mean_abs_F_N']:.4g} N.",
    ]
    if an.fit_mu is not None:
        paras.append(f"C_mu of mu(t) = F(t)/N(t): exponent {fit_text(an.fit_mu, 3)}; "
                     f"mu_rms = {summary['mu_rms']:.4g}, mean |mu| = {summary['mean_abs_mu']:.4g}.")
    if an.fit_x_equiv is not None:
        paras.append(f"Equivalent C_x of a free block of M = {an.mass:g} kg (C_F / (M^2 omega^4), eq. (3); inferred, "
                     f"not a measured displacement): gamma = {fit_text(an.fit_x_equiv, 3)}.")
    if an.speed is not None:
        paras.append(f"Sliding speed {an.speed:g} m/s: stroke length {summary['stroke_length_m']:.4g} m "
                     f"({summary['used_stroke_length_m']:.4g} m used); distance-domain spectrum over "
                     f"q = {span(an.C_F_distance.omega_min, an.C_F_distance.omega_max)} rad/m.")
    paras += [esc(n) for n in an.notes]
    paras.append("Processing: " + esc("; ".join(an.C_F.provenance["steps"])) + ".")
    figures = [Figure("measured_force_CF", plots.figure_png_bytes(plots.spectrum_figure(
        [(an.C_F, "C_F (measured)")], fits=[(f, "")], band=f.band, ylabel=r"$C_F$ (N$^2$ s)",
        title="Friction-force spectrum")),
        f"C_F of the measured friction force (N^2 s), averaged over {len(st.segments)} strokes, with the power-law fit: "
        f"C_F slope -{f.gamma:.2f} ± {f.gamma_err:.2f}{flag_mark(f)} over {span(f.band[0], f.band[1])} rad/s"
        + (" (not a power law: " + "; ".join(f.flags) + ")." if f.flags else "."))]
    dt = float(d.t[1] - d.t[0])
    rows = [[str(i + 1), f"{a * dt:.4g}", f"{b * dt:.4g}", "used"] for i, (a, b) in enumerate(st.segments)]
    tab = table("Strokes used (times after the cut; every used stroke trimmed to the same length) and dropped "
                "(stroke numbers count all strokes found)", ["#", "start (s)", "end (s)", "status"],
                rows + [[str(i), "", "", f"dropped: {esc(r)}"] for i, r in st.dropped])
    if an.C_F_distance is not None:
        fig = plots.spectrum_figure([(an.C_F_distance, "C_F(q), q = omega / v")], ylabel=r"$C_F(q)$ (N$^2$ m)",
                                    title=f"Friction force against sliding distance (v = {an.speed:g} m/s)")
        fig.axes[0].set_xlabel(r"$q$ (rad/m)")
        figures.append(Figure("measured_force_CF_distance", plots.figure_png_bytes(fig),
                              f"C_F in the distance domain: the same spectrum against q = omega / v, v = {an.speed:g} m/s."))
    if an.C_mu is not None:
        figures.append(Figure("measured_force_Cmu", plots.figure_png_bytes(plots.spectrum_figure(
            [(an.C_mu, "C_mu of F/N")], ylabel=r"$C_\mu$ (s)", title="Friction coefficient spectrum")),
            f"C_mu of mu(t) = F(t)/N(t): exponent {an.fit_mu.gamma:.2f} ± {an.fit_mu.gamma_err:.2f}{flag_mark(an.fit_mu)}."
            if an.fit_mu is not None else "C_mu of mu(t) = F(t)/N(t)."))
    if an.C_x_equiv is not None:
        figures.append(Figure("measured_force_Cx_equivalent", plots.figure_png_bytes(plots.spectrum_figure(
            [(an.C_x_equiv, "equivalent free-block C_x (eq. 3)")], title="Equivalent C_x of a free block (inferred)")),
            f"C_F / (M^2 omega^4) with M = {an.mass:g} kg: the displacement a free block would show (eq. 3), inferred."))
    result = StudyResult("measured", f"Measured friction force: {Path(d.source).name}", {}, tuple(figures),
                         paragraphs(paras) + tab)
    return [result], summary


def build_measured_report(an: DisplacementAnalysis, data):
    """Results (StudyResult list) and the JSON summary of a displacement analysis of the record ``data``.

    C_F and its figure appear only when the analysis was given a mass; otherwise the page says that C_F needs it.
    """
    from frictionnoise import package_version

    from . import plots

    fit, spec, segs = an.fit, an.C_x, an.segments
    summary = {"version": package_version(), "source": data.source, "n_samples": len(data.t),
               "dt_s": float(spec.provenance["dt"]), "resampled": data.resampled, "warning": data.warning,
               **an.summary()}
    if data.timeline is not None:
        summary["timeline"] = data.timeline.summary()
    relation = (f"C_F = M^2 omega^4 C_x assumes the block is free (inertial relation, eq. 3), with M = {an.mass:g} kg: "
                f"C_F ~ omega^-({fit_text(an.fit_F, 3)}), F_rms = {an.F_rms:.4g} N."
                if an.mass is not None else esc(C_F_NEEDS_MASS) + ".")
    every = "in uniform segments (below)" if segs is not None else f"every {spec.provenance['dt']:.4g} s"
    text = paragraphs([
        f"{len(data.t)} samples {every}; mean velocity {1e3 * an.mean_velocity:.4g} mm/s"
        + (f". {esc(data.warning)}" if data.warning else "."),
        f"gamma = {fit_text(fit, 3)} (95 %, {fit.method}) over "
        f"{span(fit.band[0], fit.band[1])} rad/s{' (automatic band)' if fit.band_auto else ''}"
        + (f" <b>not a power law: {esc('; '.join(fit.flags))}</b>" if fit.flags else "")
        + f"; zeta_rms = {an.zeta_rms:.4g} m and mu_rms = {an.mu_rms:.4g} (dimensionless, C_mu = omega^4 C_x / g^2 "
        "of a free block, whatever its mass) over the resolved band (eq. 4).",
        relation,
        "Processing: " + esc("; ".join(spec.provenance["steps"])) + ".",
    ]) + (timeline_html(data.timeline, an.segment_fits, segs.notes) if segs is not None else "")
    figures = [
        Figure("measured_Cx", plots.figure_png_bytes(plots.spectrum_figure([(spec, "C_x")], fits=[(fit, "")], band=fit.band,
                                                                          title="Displacement spectrum")),
               f"C_x of the measured displacement (m^2 s) with the power-law fit: gamma = {fit.gamma:.2f} ± "
               f"{fit.gamma_err:.2f}{flag_mark(fit)} over {span(fit.band[0], fit.band[1])} rad/s (shaded)."),
        Figure("measured_Cmu", plots.figure_png_bytes(plots.spectrum_figure([(an.C_mu, "C_mu = omega^4 C_x / g^2")],
                                                                           ylabel=r"$C_\mu$ (s)",
                                                                           title="Friction coefficient spectrum")),
               f"C_mu (s) = omega^4 C_x / g^2; mu_rms = {an.mu_rms:.3g} over the resolved band (eq. 4)."),
    ]
    if an.C_F is not None:
        figures.insert(1, Figure(
            "measured_CF", plots.figure_png_bytes(plots.spectrum_figure([(an.C_F, "C_F = M^2 omega^4 C_x")],
                                                                        ylabel=r"$C_F$ (N$^2$ s)",
                                                                        title="Force spectrum (eq. 3)")),
            f"C_F (N^2 s) of a free block of M = {an.mass:g} kg, from C_x by eq. (3): slope {4 - fit.gamma:+.2f} in the "
            "fit band."))
    return [StudyResult("measured", f"Measured displacement: {Path(data.source).name}", {}, tuple(figures), text)], summary
