"""A measured friction-force record F(t): C_F averaged over its strokes (and over the uniform pieces of a record
whose time stamps break), the force exponent, C_mu, the equivalent C_x of a free block and C_F(q).

The strokes are found and cut by :mod:`compare.analysis.strokes`. A record whose time stamps break (rate changes,
gaps, repeated or backward stamps: :mod:`compare.analysis.timeline`) is analysed as its pieces, every used stroke
intersected with every uniform segment: each piece on its own, and all of them together on one common window
(:func:`compare.analysis.segments.piece_spectra`): one Hann window per stroke as long as the strokes, so a stroke
broken by a gap gives pieces too short to enter and is named; a continuous record takes the default window of its
longest piece. Pure numerics: ``data`` is any record with the attributes of compare.io.measured.MeasuredData.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .fits import PowerLawFit, fit_power_law
from .record_model import RecordFit, processing_steps
from .segments import SegmentSpectra, piece_spectra, segment_fits, with_line_flag
from .spectra import Spectrum, rescaled, rms_from_spectrum
from .strokes import Strokes, find_strokes, stroke_pieces, stroke_spectrum

__all__ = ["ForceAnalysis", "analyze_force", "mu_source", "block_means"]


@dataclass(frozen=True)
class ForceAnalysis:
    """Everything measured from a force record. Spectra in the eq. (2) convention.

    ``pieces`` (a record whose stamps break): the per-piece spectra and their combination (``C_F`` is it);
    ``piece_strokes`` the stroke number of each piece; ``piece_fits`` one dict per piece with its own fit."""

    data: object
    strokes: Strokes
    C_F: Spectrum
    fit_F: PowerLawFit | RecordFit
    C_mu: Spectrum | None = None
    fit_mu: PowerLawFit | RecordFit | None = None
    C_x_equiv: Spectrum | None = None
    fit_x_equiv: PowerLawFit | RecordFit | None = None
    C_F_distance: Spectrum | None = None
    mass: float | None = None
    speed: float | None = None
    notes: list = field(default_factory=list)
    pieces: SegmentSpectra | None = None
    piece_fits: list | None = None

    def summary(self) -> dict:
        """The analysis as JSON-able numbers (the report's summary.json).

        Returns
        -------
        dict
            Source, units, strokes, the force exponent with its 95 % interval and band (rad/s), F_rms (N), and
            the C_mu entries (``mu_source``: the column mu was read from, or F/N), equivalent-C_x and
            distance-domain entries when present; ``blocks`` (a multi-block export: :func:`block_means`, beside
            the pooled means) and the reader's ``note``; for a record whose time stamps
            break, its ``timeline`` (segments and breaks) and ``pieces`` (stroke, rows, times (s), step (s), own
            fit, in the combined spectrum or not) and the common window ``piece_window_s`` (s).
        """
        st, d = self.strokes, self.data
        s = {
            "source": d.source, "units": d.units, "layout": d.layout,
            "n_samples": len(d.t),
            "dt_s": float(self.C_F.provenance["dt"] if self.pieces is not None else d.t[1] - d.t[0]),
            "resampled": d.resampled, "warning": d.warning, "note": getattr(d, "note", None),
            "strokes": {"method": st.method, "found": st.found, "used": len(st.segments),
                        "dropped": [{"stroke": i, "reason": r} for i, r in st.dropped],
                        "cut_each_end_s": st.cut_s, "median_duration_s": st.duration_s, "used_length_s": st.used_s},
            "force_exponent": self.fit_F.gamma, "force_exponent_err": self.fit_F.gamma_err,
            "band": list(self.fit_F.band), "fit_F": self.fit_F.to_dict(),
            "F_rms_N": rms_from_spectrum(self.C_F),
            "mean_abs_F_N": float(np.mean(np.abs(d.F))),
            "spectrum_steps": processing_steps(self.C_F.provenance["steps"], self.fit_F, integrated=True),
            "notes": list(self.notes),
        }
        if self.pieces is not None:
            s["timeline"] = d.timeline.summary()
            s["pieces"] = self.piece_fits
            s["piece_window_s"] = self.pieces.window_s
        if self.fit_mu is not None:
            s["mu_source"] = mu_source(d)
            s["fit_mu"] = self.fit_mu.to_dict()
            s["mu_rms"] = rms_from_spectrum(self.C_mu)
            s["mean_abs_mu"] = float(np.mean(np.abs(_mu(d))))
        if getattr(d, "blocks", ()):
            s["blocks"] = block_means(d)
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


def _piece_rows(t, ss: SegmentSpectra, numbers, band, method) -> list:
    """segment_fits of the pieces with each piece's stroke number and its first and last time stamp (s)."""
    rows = segment_fits(ss, band=band, method=method)
    for row, num in zip(rows, numbers):
        row.update(stroke=int(num), t_start_s=float(t[row["start_row"]]), t_stop_s=float(t[row["stop_row"] - 1]))
    return rows


def block_means(data) -> list:
    """The mean |F| (N), mean |mu| and mean |N| (N) of each block of a multi-block export (``data.blocks``: the
    steps of a UMT export run at different loads, where the pooled means mix them), with its title, place and first
    and last time (s)."""
    F, mu = np.abs(np.asarray(data.F, float)), _mu(data)
    t = np.asarray(data.t, float)
    out = []
    for b in data.blocks:
        a, z = b["start"], b["stop"]
        row = {"block": b["block"], "title": b["title"], "place": b["place"], "start_row": a, "stop_row": z,
               "t_start_s": float(t[a]), "t_stop_s": float(t[z - 1]), "mean_abs_F_N": float(np.mean(F[a:z]))}
        if mu is not None:
            row["mean_abs_mu"] = float(np.mean(np.abs(mu[a:z])))
        if data.N is not None:
            row["mean_abs_N_N"] = float(np.mean(np.abs(np.asarray(data.N, float)[a:z])))
        out.append(row)
    return out


def mu_source(data) -> str:
    """What the friction coefficient mu(t) of a record is: the file's own column (named) or F(t)/N(t) (the
    columns named), as :func:`_mu` takes it; the label of C_mu in every output."""
    units = getattr(data, "units", None) or {}
    if getattr(data, "mu", None) is not None:
        col = units.get("mu", {}).get("column")
        return f"the column {col!r}" if col else "the file's friction-coefficient column"
    F, N = units.get("force", {}).get("column"), units.get("normal", {}).get("column")
    return f"mu(t) = F(t)/N(t) (columns {F!r} / {N!r})" if F and N else "mu(t) = F(t)/N(t)"


def _mu(data):
    """The friction coefficient: the file's own mu column when it has one, else F / N (None when N is absent or
    zero somewhere)."""
    if getattr(data, "mu", None) is not None:
        return np.asarray(data.mu, float)
    if data.N is None or np.any(np.asarray(data.N) == 0):
        return None
    return np.asarray(data.F, float) / np.asarray(data.N, float)


def _spectra(data, strokes, prewhiten, nperseg, band, method):
    """(C_F, C_mu or None, pieces or None, piece rows or None, notes): stroke-averaged, or over the uniform pieces
    of a record whose time stamps break."""
    t, F = np.asarray(data.t, float), np.asarray(data.F, float)
    mu = _mu(data)
    if not getattr(data, "segmented", False):
        C_F = stroke_spectrum(t, F, strokes, "F", "N^2 s", prewhiten, nperseg)
        C_mu = None if mu is None else stroke_spectrum(t, mu, strokes, "mu", "s", prewhiten, nperseg)
        return C_F, C_mu, None, None, []
    found = stroke_pieces(strokes, data.timeline)
    if not found:
        raise ValueError("no used stroke overlaps a uniform segment of the time stamps")
    numbers, pieces = zip(*found)
    longest = max(pieces, key=lambda p: p.n * p.dt)
    kw = dict(detrend="linear", prewhiten=prewhiten)
    if nperseg is not None:
        kw["window"] = nperseg * longest.dt
    elif len(strokes.segments) > 1:
        kw["span"] = strokes.used_s  # one window per stroke, as on a uniform record
    notes = []
    if "span" in kw and max(p.n * p.dt for p in pieces) < strokes.used_s * (1 - 1e-9):
        del kw["span"]  # every stroke is broken: the default window of the longest piece
        notes.append("every used stroke is broken by the time stamps: the common window is the default one of the "
                     "longest piece, not one stroke")
    ss = piece_spectra(t, F, pieces, quantity="F", unit="N^2 s", name="F", **kw)
    C_mu = None
    if mu is not None:
        kw.pop("span", None)
        kw.update(window=ss.window_s, prewhiten=ss.combined.provenance["prewhiten_order"])
        C_mu = piece_spectra(t, mu, pieces, quantity="mu", unit="s", name="mu", **kw).combined
    used = len(ss.used)
    notes.append(f"time stamps break: {len(pieces)} uniform pieces of {len(strokes.segments)} used strokes; {used} "
                 f"cover the common window of {ss.window_s:.4g} s and make the combined spectrum")
    return ss.combined, C_mu, ss, _piece_rows(t, ss, numbers, band, method), notes + list(ss.notes)


def _record_fits(data, strokes, band, mass):
    """(fit_F, fit_mu or None, fit_x_equiv or None) by the record model of the one uninterrupted stroke: a force
    spectrum is flatter than the record model's least exponent (omega^-1.05; model I's force is white), so each
    series is fitted through its running sum, whose spectrum is omega^-2 times the series' (as the wear study
    does), and the exponent is given back less 2 (:func:`compare.analysis.record_model.fit_series`)."""
    from .record_model import fit_series

    if getattr(data, "segmented", False) or len(strokes.segments) != 1:
        why = ("its time stamps break" if getattr(data, "segmented", False) else
               f"it holds {len(strokes.segments)} strokes")
        raise ValueError(f"method 'record' fits one uninterrupted stroke (a constant-velocity record) and {why}; "
                         "use method 'whittle' (the default for force data), which averages the strokes' spectra")
    a, b = strokes.segments[0]
    t = np.asarray(data.t, float)[a:b]
    fit_F = fit_series(t, np.asarray(data.F, float)[a:b], band=band, quantity="F", integrate=True)
    mu = _mu(data)
    fit_mu = None if mu is None else fit_series(t, mu[a:b], band=band, quantity="mu", integrate=True)
    fit_x = None if mass is None else fit_F.derived(-4.0, 1.0 / mass**2, "x", "m^2 s")
    return fit_F, fit_mu, fit_x


def analyze_force(data, *, band=None, mass: float | None = None, speed: float | None = None,
                  cut: float | None = None, method: str | None = None, prewhiten="auto",
                  nperseg: int | None = None) -> ForceAnalysis:
    """C_F of a measured friction force (averaged over strokes), its exponent, and what follows from it.

    ``mass`` (kg) adds the equivalent C_x = C_F / (M^2 omega^4) of a free block (eq. 3); ``speed`` (m/s)
    adds the distance-domain spectrum C_F(q) = v C_F(omega = q v) (q in rad/m) and the stroke length; a
    normal-force column adds C_mu of mu(t) = F(t) / N(t), a friction-coefficient column (``data.mu``) C_mu of that
    column (it wins over F/N; :func:`mu_source` names which). A record whose time stamps break (``data.segmented``)
    is analysed over its uniform pieces (see the module docstring), with the same outputs.

    Parameters
    ----------
    data : compare.io.measured.MeasuredData
        A record with a friction-force column (and optionally normal force, position or direction).
    band : tuple of float, optional
        Fit band (Units: rad/s); default automatic.
    mass : float, optional
        Block mass M (Units: kg).
    speed : float, optional
        Imposed sliding speed (Units: m/s).
    cut : float, optional
        Seconds removed at each end of a stroke (Units: s); default 10 % of the median stroke.
    method : {"whittle", "lsq", "record"}, optional
        Fit method: a band fit of the stroke-averaged Welch spectrum (:func:`compare.analysis.fits.fit_power_law`;
        default ``"whittle"``; the combined spectrum of a record whose stamps break carries no raw periodogram and
        is fitted by least squares), or ``"record"``: the record model (C = A omega^-gamma plus a white floor, the
        debiased Whittle likelihood of the whole record) of the running sum of F (and of mu), the exponent less 2,
        for a record of one stroke with unbroken time stamps (a constant-velocity rig); a ValueError otherwise.
    prewhiten, nperseg
        As in :func:`compare.analysis.spectra.series_spectrum` (``nperseg`` in samples of the longest piece).

    Returns
    -------
    ForceAnalysis
        The strokes, C_F (N^2 s) and its fit, and C_mu (s), the equivalent C_x (m^2 s) and C_F(q) (N^2 m) when
        their inputs were given; the pieces and their own fits when the stamps break.
    """
    if data.F is None:
        raise ValueError("the record holds no friction-force column")
    if mass is not None and not mass > 0:
        raise ValueError(f"mass must be positive (got {mass!r})")
    if speed is not None and not speed > 0:
        raise ValueError(f"speed must be positive (got {speed!r})")
    strokes = find_strokes(data, cut=cut)
    record = method == "record"
    if record:
        fit_F, fit_mu, fit_x = _record_fits(data, strokes, band, mass)
    C_F, C_mu, pieces, rows, notes = _spectra(data, strokes, prewhiten, nperseg, band, None if record else method)
    if not record:
        fit_F = with_line_flag(fit_power_law(C_F, band=band, method=method), C_F)
        if fit_F.flags and len(strokes.segments) == 1 and pieces is None:
            fit_F = replace(fit_F, notes=list(fit_F.notes) + [
                "one uninterrupted stroke: method 'record' (analyze --method record) fits the whole record, the "
                "record model through the force's running sum, over every Fourier frequency"])
        fit_mu = None if C_mu is None else with_line_flag(fit_power_law(C_mu, band=band, method=method), C_mu)
        fit_x = None
    if C_mu is None and data.N is not None:
        notes.append("the normal force is zero somewhere; C_mu not computed")
    elif C_mu is None:
        notes.append("no normal-force or friction-coefficient column: C_mu not computed")
    C_x = None
    if mass is not None:
        C_x = rescaled(C_F, lambda w: 1.0 / (mass**2 * w**4), "x", "m^2 s",
                       f"equivalent free-block C_x = C_F / (M^2 omega^4), M = {mass:g} kg  [eq. (3)]")
        if not record:
            fit_x = fit_power_law(C_x, band=band, method=method)
    C_q = None
    if speed is not None:
        prov = dict(C_F.provenance)
        prov["steps"] = list(prov["steps"]) + [f"distance domain: q = omega / v, C(q) = v C(omega), v = {speed:g} m/s"]
        C_q = Spectrum(omega=C_F.omega / speed, C=C_F.C * speed, quantity="F(q)", unit="N^2 m", n_avg=C_F.n_avg,
                       dof=C_F.dof, provenance=prov)
    return ForceAnalysis(data=data, strokes=strokes, C_F=C_F, fit_F=fit_F, C_mu=C_mu, fit_mu=fit_mu, C_x_equiv=C_x,
                         fit_x_equiv=fit_x, C_F_distance=C_q, mass=mass, speed=speed, notes=notes, pieces=pieces,
                         piece_fits=rows)
