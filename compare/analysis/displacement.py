"""A measured displacement record x(t): its noise spectrum C_x, exponent gamma, sliding velocity and C_mu, and
C_F when the block's mass is known.

x(t) = v t + zeta(t): v is fitted, C_x is the spectrum of zeta in the eq. (2) convention. gamma, C_x, v and
C_mu = omega^4 C_x / g^2 (section 2: the friction coefficient of a free block, C_F / (M g)^2) do not depend on
the block's mass; only C_F = M^2 omega^4 C_x (eq. 3) does, so C_F is computed only when a mass is given. Both
fit methods of :func:`compare.analysis.fits.fit_power_law` apply to every spectrum here.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from frictionnoise.base import STANDARD_GRAVITY

from .fits import PowerLawFit, fit_power_law
from .record_model import RecordFit, check_record, fit_record, processing_steps
from .segments import SegmentSpectra, segment_fits, segment_spectra, with_line_flag
from .spectra import (Spectrum, displacement_spectrum, force_spectrum, friction_coefficient_spectrum,
                      rms_from_spectrum)

__all__ = ["DisplacementAnalysis", "analyze_displacement", "C_F_NEEDS_MASS", "METHODS"]

METHODS = ("record", "whittle", "lsq")  # record: compare.analysis.record_model (default); the others: compare.analysis.fits
PIECE_SHARE = 0.75  # a record in pieces: the record model fits its longest piece alone from this share of the samples

C_F_NEEDS_MASS = ("C_F not computed: C_F = M^2 omega^4 C_x (eq. 3) needs the block mass M (--mass, kg); gamma, C_x "
                  "and C_mu do not depend on it")


@dataclass(frozen=True)
class DisplacementAnalysis:
    """What a displacement record x(t) gives. Spectra in the eq. (2) convention.

    Attributes
    ----------
    C_x : Spectrum
        Displacement spectrum of zeta = x - (x0 + v t) (m^2 s).
    fit : RecordFit or PowerLawFit
        C_x ~ omega^-gamma: ``fit.gamma``, its 95 % half-width ``fit.gamma_err``, the band (rad/s), the flags
        (a :class:`~compare.analysis.record_model.RecordFit` also the floor and its crossover).
    mean_velocity : float
        The fitted sliding velocity v (m/s).
    zeta_rms : float
        rms of zeta over the resolved band, eq. (4) (m): sqrt(2 Int C_x domega) from the Welch segment's frequency
        step to the Nyquist frequency, so it leaves out the drift and periods longer than a segment (a record's own
        standard deviation holds them).
    C_mu : Spectrum
        Friction-coefficient spectrum omega^4 C_x / g^2 of a free block (s).
    fit_mu : PowerLawFit
        C_mu ~ omega^-(gamma - 4), fitted over the band of ``fit``.
    mu_rms : float
        rms of mu over the exponent's fitted band (dimensionless): omega^4 C_x weighs a sensor's white floor as
        omega^4, so above the band, where the floor takes over, it would measure the sensor, not the friction.
    g : float
        Gravitational acceleration used for C_mu (m/s^2).
    mass : float or None
        The block mass M (kg), when given.
    C_F : Spectrum or None
        Force spectrum M^2 omega^4 C_x (N^2 s, eq. 3), when a mass was given.
    fit_F : PowerLawFit or None
        C_F ~ omega^-(gamma - 4), fitted over the band of ``fit``, when a mass was given.
    F_rms : float or None
        rms of the force over the exponent's fitted band (N), when a mass was given (as ``mu_rms``).
    segments : SegmentSpectra or None
        The per-segment spectra of a record whose time stamps break (C_x is their combination), else None.
    segment_fits : list or None
        One dict per segment with its own fit (:func:`compare.analysis.segments.segment_fits`), else None.
    """

    C_x: Spectrum
    fit: RecordFit | PowerLawFit
    mean_velocity: float
    zeta_rms: float
    C_mu: Spectrum
    fit_mu: RecordFit | PowerLawFit
    mu_rms: float
    g: float
    mass: float | None = None
    C_F: Spectrum | None = None
    fit_F: RecordFit | PowerLawFit | None = None
    F_rms: float | None = None
    segments: SegmentSpectra | None = None
    segment_fits: list | None = None

    @property
    def notes(self) -> list:
        """What was not computed, and why."""
        return [] if self.mass is not None else [C_F_NEEDS_MASS]

    @property
    def rms_band(self) -> list:
        """The band (rad/s) ``mu_rms`` and ``F_rms`` integrate: the fitted band within the spectrum's frequencies."""
        return list(_rms_band(self.fit, self.C_x))

    def summary(self) -> dict:
        """The analysis as JSON-ready numbers.

        Returns
        -------
        dict
            ``gamma``, ``gamma_err``, ``band`` (rad/s), ``fit`` (C_x), ``fit_mu``, ``mean_velocity`` (m/s),
            ``zeta_rms_m`` (m) with ``zeta_rms_band`` (rad/s: the resolved band it integrates, from the Welch
            segment's frequency step to the Nyquist frequency), ``mu_rms`` with ``mu_rms_band`` (rad/s: the fitted band
            within the spectrum's, which ``F_rms_N`` integrates too); ``fit_F`` and ``F_rms_N`` (N) only when a mass was
            given.
        """
        s = {"kind": "displacement", "mass_kg": self.mass, "gamma": self.fit.gamma, "gamma_err": self.fit.gamma_err,
             "band": list(self.fit.band), "fit": self.fit.to_dict(), "mean_velocity": self.mean_velocity,
             "zeta_rms_m": self.zeta_rms, "zeta_rms_band": [self.C_x.omega_min, self.C_x.omega_max],
             "fit_mu": self.fit_mu.to_dict(), "mu_rms": self.mu_rms, "mu_rms_band": self.rms_band, "g_m_per_s2": self.g,
             "spectrum_steps": processing_steps(self.C_x.provenance["steps"], self.fit), "notes": self.notes}
        if self.fit_F is not None:
            s["fit_F"] = self.fit_F.to_dict()
            s["F_rms_N"] = self.F_rms
        if self.segment_fits is not None:
            s["segment_fits"] = self.segment_fits
        return s


def _rms_band(fit, C_x) -> tuple:
    """The fitted band within the Welch spectrum's frequencies (rad/s): what mu_rms and F_rms integrate."""
    return max(fit.band[0], C_x.omega_min), min(fit.band[1], C_x.omega_max)


def _band_rms(spectrum, band) -> float:
    """rms over ``band`` (rad/s, eq. 4), NaN where the band holds fewer than two of the spectrum's frequencies (a fit
    whose band collapsed onto one ordinate)."""
    try:
        return rms_from_spectrum(spectrum, band=band)
    except ValueError:
        return float("nan")


def analyze_displacement(t, x=None, *, mass: float | None = None, band=None, method: str | None = None,
                         g: float = STANDARD_GRAVITY, timeline=None, discrete: bool = False) -> DisplacementAnalysis:
    """C_x, its exponent gamma, the velocity and C_mu of a displacement record; C_F when the mass is known.

    Parameters
    ----------
    t : array_like or record
        Times (s), uniformly sampled or in uniform segments (then give ``timeline``); or a record with attributes
        ``t`` (s) and ``x`` (m), such as :class:`compare.io.measured.MeasuredData` (then ``x`` is not given, and a
        segmented record brings its own timeline).
    x : array_like, optional
        Positions (m) at ``t``.
    mass : float, optional
        Block mass M (kg): adds C_F = M^2 omega^4 C_x (eq. 3) and its exponent gamma - 4.
    band : tuple of float, optional
        Fit band (rad/s): the Fourier ordinates the likelihood sums over; default all of them (the record model), or
        the widest straight stretch (:func:`compare.analysis.fits.fit_power_law`). C_mu and C_F are fitted over the
        band of the C_x fit.
    method : {"record", "whittle", "lsq"}, optional
        Fit method. Default ``"record"``: the record model C_x = A omega^-gamma + B fitted by the debiased Whittle
        likelihood of the whole record (:func:`compare.analysis.record_model.fit_record`; C_mu's and C_F's
        exponents follow as gamma - 4). ``"whittle"`` and ``"lsq"`` fit the Welch spectrum over a band
        (:func:`compare.analysis.fits.fit_power_law`). A record in uniform segments: the record model fits its
        longest segment alone when asked for (``"record"``) or, by default, when that segment holds at least
        :data:`PIECE_SHARE` of the samples (a row dropped near an end); else the segments' combined Welch spectrum
        is fitted by least squares over its band (it keeps no single periodogram for the Whittle fits).
    g : float, optional
        Gravitational acceleration for C_mu (m/s^2); default standard gravity, 9.80665 (the value the reader
        converts a gram-force by), for a record measured on Earth; the paper's models use 9.81 (``frictionnoise.G``).
    timeline : compare.analysis.timeline.Timeline, optional
        The breaks of ``t``: each uniform segment is estimated on its own and their spectra combined
        (:func:`compare.analysis.segments.segment_spectra`).
    discrete : bool, optional
        The record is of a discrete-time process (a simulation's cumulative sum of random steps): the record model
        fits the power law's discrete form (:func:`compare.analysis.record_model.fit_record`); default a continuous
        process sampled, as an instrument records it. The record model only.

    Returns
    -------
    DisplacementAnalysis
        The spectra, the fits, the velocity and the rms values.
    """
    if x is None:
        if not hasattr(t, "t"):
            raise ValueError("give x(t): the positions (m) at the times t (s)")
        if getattr(t, "x", None) is None:
            raise ValueError(f"{getattr(t, 'source', 'the record')}: the record holds no displacement column")
        if getattr(t, "segmented", False):
            timeline = t.timeline
        t, x = t.t, t.x
    if mass is not None and not (mass > 0 and np.isfinite(mass)):
        raise ValueError(f"mass must be positive, in kg (got {mass!r})")
    if method not in (None,) + METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)} (got {method!r})")
    if discrete and method not in (None, "record"):
        raise ValueError("discrete applies to the record model (method 'record')")
    segs = piece = None
    if timeline is not None:  # time stamps in uniform segments: each on its own, and their spectra averaged
        segs = segment_spectra(t, x, timeline, quantity="x", unit="m^2 s", detrend="linear", name="x")
        C_x = segs.combined
        if method in (None, "record"):
            # the record model needs one uniform record: the longest piece when asked for, or when it holds most of
            # the record (a dropped row near an end); else the pieces' combined spectrum is fitted over its band
            usable = timeline.usable()
            piece = max(usable, key=lambda s: s.n)
            total = sum(s.n for s in usable)
            share = piece.n / total
            if method is None and share < PIECE_SHARE:
                piece = None
                if discrete:
                    raise ValueError(f"discrete applies to the record model of one uniform record; the longest of "
                                     f"this record's {len(usable)} pieces holds {100 * share:.0f} % of its samples "
                                     f"(resample it onto one grid, or give method 'record' to fit that piece)")
    else:
        t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
        check_record(x, "x", "m")
        C_x = displacement_spectrum(t, x)
    if method in (None, "record") and (segs is None or piece is not None):
        dt = float(C_x.provenance["dt"]) if piece is None else piece.dt
        rows = slice(None) if piece is None else slice(piece.start, piece.stop)
        tp, xp = np.asarray(t[rows], dtype=float), np.asarray(x[rows], dtype=float)
        z = xp - np.polyval(np.polyfit(tp - tp[0], xp, 1), tp - tp[0])
        fit = with_line_flag(fit_record(z, dt, band=band, discrete=discrete), C_x)
        if piece is not None:
            fit = replace(fit, notes=fit.notes + (
                f"the record is in {len(usable)} uniform pieces: the record model was fitted to the "
                f"longest, data rows {piece.start + 1}-{piece.stop} ({piece.n} of {total} samples, "
                f"{100 * piece.n / total:.0f} %); the others enter the combined spectrum only (--resample DT puts "
                "the whole record on one grid)",))
        fit_mu = fit.derived(4.0, 1.0 / g**2, "mu", "s")
    else:
        fit = with_line_flag(fit_power_law(C_x, band=band, method=method), C_x)
        fit_mu = None
    C_mu = friction_coefficient_spectrum(C_x, g)
    if fit_mu is None:
        fit_mu = with_line_flag(fit_power_law(C_mu, band=fit.band, method=fit.method), C_mu)
    rb = _rms_band(fit, C_x)
    C_F = fit_F = F_rms = None
    if mass is not None:
        C_F = force_spectrum(C_x, mass)
        fit_F = (fit.derived(4.0, mass**2, "F", "N^2 s") if fit.method == "record" else
                 with_line_flag(fit_power_law(C_F, band=fit.band, method=fit.method), C_F))
        F_rms = _band_rms(C_F, rb)
    return DisplacementAnalysis(C_x=C_x, fit=fit, mean_velocity=float(C_x.provenance["mean_velocity"]),
                                zeta_rms=rms_from_spectrum(C_x), C_mu=C_mu, fit_mu=fit_mu,
                                mu_rms=_band_rms(C_mu, rb),
                                g=g, mass=mass, C_F=C_F, fit_F=fit_F, F_rms=F_rms, segments=segs,
                                segment_fits=None if segs is None else segment_fits(segs, band=band, method=method))
