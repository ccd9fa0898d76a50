"""The record model C_x(omega) = A omega^-gamma + B, fitted by the debiased Whittle likelihood (module
``compare.analysis.record_model``).

A sampled record is the physical spectrum A omega^-gamma folded at Nyquist (exactly, by Hurwitz zeta sums) plus a
sensor's white floor B (a level of the sampled record, Units: m^2 s; rms sqrt(2 pi B / dt)). A record filtered below
Nyquist before sampling (an instrument's anti-aliasing filter) lacks the folded images, about half the model's power
at Nyquist for omega^-4 and steeper, and is read steeper (omega^-4.5 up to Nyquist unfolded: 4.576 without noise);
a band below the filter's corner removes that (below a quarter of Nyquist: 4.500). :func:`fit_record`
differences the record k times (:func:`compare.analysis.whittle.order_for` of a pilot slope, raised while the
exponent's interval reaches the order's limit 2k + 1), and maximises the debiased Whittle likelihood
(:mod:`compare.analysis.whittle`) over all Fourier ordinates: A and the floor's share are profiled out exactly for
each gamma, so the likelihood is a function of gamma alone, and the 95 % interval is where twice its rise stays
below chi2_1(0.95) = 3.84. The floor is bounded at zero, not log-parametrised, so a record without one is fitted at
B = 0 and the interval stays valid there.

Reported with the exponent: the **identified band**, from the lowest fitted Fourier frequency to where the power law
falls to the floor (omega_x = (A / B)^(1/gamma), or the highest when the floor never takes over); the floor and its
crossover; a **bend test** (Rao's efficient score for changes of the exponent at knots every half decade inside the
band, :func:`compare.analysis.power_floor.bend_p`); and a **split-half test** of stationarity: the model fitted to each
half of the record apart and to both with shared parameters, twice the log-likelihood gain read against the same gain
of each half's four quarters (:func:`_split_half`: flagged only where the gain exceeds both chi2 and that
reference), so that a non-Gaussian record's over-dispersed likelihood ratios do not pass for a change between the
halves.

Without a band given, a record whose spectrum may bend (bend test p < :data:`SCREEN_LEVEL`: a corner, a folded
resonance, the other side of a crossover between mechanisms) is searched by binary segmentation: a band is kept when the split
test (:func:`split_p`: the model fitted on each side of a knot apart and over the whole band, knots every quarter
decade, Bonferroni over the knots) does not reject at :data:`TEST_LEVEL`, else cut at its best knot and each side
searched alike, down to a decade, each band at the differencing order its own exponent asks for; of the kept bands
the one with the most Fourier ordinates is fitted, and every kept band is reported (``segments``). The bend
test is the cheap screen (no refit), the split test the decision: a searched record is flagged only when no band of a
decade is left, one not searched when its bend test rejects at :data:`TEST_LEVEL`, and either when the split-half
test does (``flags``; ``power_law`` False).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import stats

from .power_floor import PowerFloorProfile, above_rounding, bend_p, interval, keep_band, level_cov, minimum
from .whittle import MAX_ORDER, TAPER, WhittleRecord, order_for

__all__ = ["RecordFit", "fit_record", "fit_series", "expected_gamma", "split_p", "split_half_references", "TEST_LEVEL", "SCREEN_LEVEL",
           "GAMMA_MIN", "check_record", "band_end_words", "BAND_ENDS", "RECORD_UNITS", "spectrum_unit_of",
           "processing_steps"]

TEST_LEVEL = 0.01  # the bend, split and split-half tests flag a record (or cut a band) below it
STATIONARITY_BLOCKS = 8  # the split-half test's blocks: its halves' likelihood ratio is read against their quarters'
SCREEN_LEVEL = 0.1  # below it the bend test (a score test: no refit) hands the band to the split test (refits)
GAMMA_MIN = 1.05  # a sampled omega^-gamma with gamma <= 1 has infinite variance (its folded sum diverges)
_HEADROOM = 0.95  # gamma < 2k + 0.95: the differenced spectrum's zero-frequency peak omega^-0.95 is still integrable
BAND_ENDS = ("floor", "departure", "last frequency", "given")  # what ends the identified band (RecordFit.band_end)


@dataclass(frozen=True)
class RecordFit:
    """A record's C_x = A omega^-gamma + B fitted by the debiased Whittle likelihood (:func:`fit_record`).

    ``gamma_low``/``gamma_high``: the 95 % profile-likelihood interval; ``gamma_err`` its half-width. ``prefactor``
    A (Units: C's unit times (rad/s)^gamma); ``floor`` B (C's unit) and ``floor_rms`` sqrt(2 pi B / dt) (the
    record's unit); ``crossover`` where A omega^-gamma = B (rad/s; inf without a floor); ``band`` the identified band
    (rad/s): from the lowest Fourier frequency to the crossover or Nyquist. ``stationarity_p``: the split-half test's
    p-value, ``stationarity_lr`` its two likelihood ratios (LR_h of the halves, LR_w of their quarters; NaN when not
    run); ``bend_p``: the bend test's. ``segments``: when the band was searched, every band kept as one power law,
    (low, high, gamma, gamma_low, gamma_high, differencing order), in rising frequency; the fit is the one of them
    with the most Fourier ordinates. ``fit_band``: the band whose ordinates were fitted (rad/s; given or searched;
    empty when every ordinate was), the one to hand :func:`expected_gamma`. ``band_end``: what ends the identified
    band at its top (:data:`BAND_ENDS`): ``"floor"`` when the fitted floor crosses the power law inside the fitted
    ordinates (the flat ordinates above the crossover were fitted as white); ``"departure"`` when the band search cut
    the band below the record's highest frequency (the spectrum above departs from this power law in another shape:
    a resonance's approach, a corner; a floor term fitted inside the band lies below the power law there);
    ``"last frequency"`` when the band reaches the highest Fourier frequency; ``"given"`` when the band was given.
    ``record_unit``: the unit of the fitted record (``"m"``; ``"N s"`` for a force fitted through its running sum),
    the unit of ``floor_rms``; ``floor`` is in its square times s; ``spectrum_unit`` the unit of the spectrum
    ``level`` gives (``"m^2 s"``; a derived fit's: ``"s"`` for C_mu, ``"N^2 s"`` for C_F) (:meth:`units`).
    """

    gamma: float
    gamma_low: float
    gamma_high: float
    prefactor: float
    floor: float
    floor_rms: float
    crossover: float
    band: tuple
    order: int
    n_samples: int
    nll: float
    stationarity_p: float
    bend_p: float
    quantity: str = "x"
    flags: tuple = ()
    notes: tuple = field(default=())
    method: str = "record"
    band_auto: bool = True
    n_points: int = 0
    level_cov: tuple = ()
    segments: tuple = ()
    fit_band: tuple = ()
    band_end: str = "last frequency"
    record_unit: str = ""
    spectrum_unit: str = ""
    stationarity_lr: tuple = ()

    @property
    def gamma_err(self) -> float:
        """Half-width of the 95 % interval."""
        return 0.5 * (self.gamma_high - self.gamma_low)

    @property
    def gamma_interval(self) -> tuple[float, float]:
        """The 95 % profile-likelihood interval (gamma_low, gamma_high), as summary.json's ``gamma_interval``."""
        return (self.gamma_low, self.gamma_high)

    @property
    def power_law(self) -> bool:
        """False when a flag says the record is not a stationary power law (see ``flags``)."""
        return not self.flags

    @property
    def decades(self) -> float:
        """Width of the identified band (decades)."""
        return math.log10(self.band[1] / self.band[0])

    def level(self, omega):
        """The fitted power law A omega^-gamma at ``omega``, without the floor.

        Parameters
        ----------
        omega : array_like
            Angular frequencies (Units: rad/s).

        Returns
        -------
        ndarray
            A omega^-gamma (Units: those of the fitted spectrum, e.g. m^2 s).
        """
        return self.prefactor * np.asarray(omega, dtype=float) ** (-self.gamma)

    def ln_level(self, omega: float) -> tuple[float, float]:
        """ln(A omega^-gamma) at ``omega`` (rad/s) and its standard error from the Fisher information of the fit
        (``level_cov``: the covariance of (gamma, ln A), the floor profiled out).

        Parameters
        ----------
        omega : float
            Angular frequency (Units: rad/s).

        Returns
        -------
        (float, float)
            ln C and its 1-sigma error (dimensionless).
        """
        lw = math.log(omega)
        value = math.log(self.prefactor) - self.gamma * lw
        if not self.level_cov:
            return value, math.nan
        vgg, vga, vaa = self.level_cov
        return value, math.sqrt(max(vgg * lw * lw - 2.0 * vga * lw + vaa, 0.0))

    def derived(self, power: float, factor: float, quantity: str, spectrum_unit: str = "") -> "RecordFit":
        """The fit of factor * omega^power * C (e.g. C_mu = omega^4 C_x / g^2): gamma and its interval less
        ``power``, the prefactor times ``factor``; floor, crossover and band stay those of the fitted record.

        Parameters
        ----------
        power : float
            The exponent of omega multiplying the spectrum (dimensionless).
        factor : float
            The constant multiplying it (its unit converts the prefactor's).
        quantity : str
            What the derived spectrum is of (``"mu"``, ``"F"``, ...).
        spectrum_unit : str, optional
            The derived spectrum's unit (``"s"`` for C_mu, ``"N^2 s"`` for C_F), the prefactor's with (rad/s)^gamma.

        Returns
        -------
        RecordFit
            The derived fit.
        """
        return replace(self, gamma=self.gamma - power, gamma_low=self.gamma_low - power,
                       gamma_high=self.gamma_high - power, prefactor=self.prefactor * factor, quantity=quantity,
                       spectrum_unit=spectrum_unit,
                       segments=tuple((a, b, g - power, lo - power, hi - power, k)
                                      for a, b, g, lo, hi, k in self.segments))

    def units(self) -> dict:
        """The unit of every dimensional number of :meth:`to_dict` (SI; frequencies in rad/s; the prefactor's in
        terms of the fitted record's spectrum at the derived exponent).

        Returns
        -------
        dict
            Field name -> unit, e.g. ``{"floor": "m^2 s", "floor_rms": "m", "crossover": "rad/s", ...}``; the floor's
            entries empty when the record's unit is not known.
        """
        u = self.record_unit
        return {"floor": spectrum_unit_of(u), "floor_rms": u,
                "prefactor": f"{self.spectrum_unit} (rad/s)^gamma" if self.spectrum_unit else "",
                "crossover": "rad/s", "band": "rad/s", "fit_band": "rad/s", "segments.band": "rad/s"}

    def to_dict(self) -> dict:
        """JSON-ready: every field plus ``gamma_err``, ``power_law``, ``decades``, ``confidence`` and ``units`` (the
        unit of each dimensional field, :meth:`units`).

        Returns
        -------
        dict
            The fit's numbers (SI units, frequencies in rad/s).
        """
        return {"gamma": self.gamma, "gamma_err": self.gamma_err, "gamma_se": self.gamma_err / 1.96, "gamma_interval": [self.gamma_low, self.gamma_high],
                "confidence": 0.95, "prefactor": self.prefactor, "floor": self.floor, "floor_rms": self.floor_rms,
                "crossover": None if math.isinf(self.crossover) else self.crossover,
                "band": [self.band[0], self.band[1]], "decades": self.decades, "differencing_order": self.order,
                "n_samples": self.n_samples, "stationarity_p": self.stationarity_p,
                "stationarity_lr": list(self.stationarity_lr),
                "bend_p": self.bend_p, "quantity": self.quantity, "method": self.method,
                "power_law": self.power_law, "flags": list(self.flags), "notes": list(self.notes),
                "band_auto": self.band_auto, "n_points": self.n_points,
                "segments": [{"band": [a, b], "gamma": g, "gamma_interval": [lo, hi], "differencing_order": k}
                             for a, b, g, lo, hi, k in self.segments],
                "fit_band": list(self.fit_band) if self.fit_band else None, "band_end": self.band_end,
                "record_unit": self.record_unit, "units": self.units()}

    def __str__(self) -> str:
        flag = f" [NOT A POWER LAW: {'; '.join(self.flags)}]" if self.flags else ""
        floor = band_end_words(self.band_end, self.floor_rms, self.crossover, self.band[1], self.gamma,
                               [s[:3] for s in self.segments], f" {self.record_unit}" if self.record_unit else "")
        return (f"gamma = {self.gamma:.3f} +- {self.gamma_err:.3f} (95 % [{self.gamma_low:.3f}, {self.gamma_high:.3f}], "
                f"record model: debiased Whittle) over {self.band[0]:.3g}-{self.band[1]:.3g} rad/s ({self.decades:.1f} decades)"
                f"{floor}{flag}" + "".join(f"\n  note: {n}" for n in self.notes))


RECORD_UNITS = {"x": "m", "F": "N", "mu": ""}  # a record's unit by what it is of (SI; mu is dimensionless)


def spectrum_unit_of(unit: str) -> str:
    """The unit of the spectrum (eq. 2 convention) of a record in ``unit``: "m" -> "m^2 s", "N s" -> "(N s)^2 s",
    "" (dimensionless) -> "s"."""
    if not unit:
        return "s"
    return f"({unit})^2 s" if " " in unit else f"{unit}^2 s"


def processing_steps(steps, fit, integrated: bool = False) -> list:
    """A spectrum's processing steps (its provenance, for the figure's Welch estimate) as they concern ``fit``: for
    the record model, the raw rectangular-window periodogram the band fits use is replaced by what the record model
    fits, the periodogram of the differenced record under the Tukey taper (:data:`compare.analysis.whittle.TAPER`).

    Parameters
    ----------
    steps : list of str
        The spectrum's ``provenance["steps"]``.
    fit : RecordFit or PowerLawFit
        The exponent's fit.
    integrated : bool, optional
        The record was fitted through its running sum.

    Returns
    -------
    list of str
        The steps, the last one naming the fit's own periodogram.
    """
    if getattr(fit, "method", None) != "record":
        return list(steps)
    kept = [s for s in steps if not s.startswith("raw periodogram")]
    what = "the running sum of the record" if integrated else "the record"
    return kept + [f"exponent: the record model, fitted to the periodogram of {what} differenced {fit.order}x under "
                   f"a Tukey taper (a cosine over {100 * TAPER / 2:g} % of the record at each end) by the debiased "
                   "Whittle likelihood; the Welch estimate above is the figure's"]


def band_end_words(end: str, floor_rms: float, crossover, top: float, gamma: float, segments=(), unit: str = "") -> str:
    """The floor and what ends the identified band, as the clause that follows an exponent ("; ...").

    Parameters
    ----------
    end : str
        :attr:`RecordFit.band_end` (one of :data:`BAND_ENDS`).
    floor_rms : float
        The fitted floor's rms (the record's unit; 0 without a floor).
    crossover : float or None
        Where the power law meets the floor (Units: rad/s; None or inf without a floor).
    top : float
        The identified band's upper end (Units: rad/s).
    gamma : float
        The fitted exponent, compared with the next kept band's.
    segments : sequence of (low, high, gamma), optional
        The kept bands of the band search (rad/s): the first one starting at ``top`` or above is named as what
        follows a departure.
    unit : str, optional
        The floor's unit, with its leading space (``" m"``).

    Returns
    -------
    str
        ``"; white floor ..., over the power law above ... rad/s: the floor ends the band"``, or the floor below the
        power law (or none) followed, for a departure, by where and how the spectrum leaves the power law.
    """
    if end == "floor":
        return (f"; white floor {floor_rms:.3g}{unit} rms, over the power law above {crossover:.3g} rad/s: the floor "
                "ends the band")
    if end != "departure":
        if not floor_rms > 0:
            return "; no white floor detected"
        where = (f"it would cross the power law at {crossover:.3g} rad/s, above the given band" if end == "given"
                 and crossover is not None and math.isfinite(crossover) else
                 "no floor resolved: it dominates at no frequency of the record")
        return f"; a floor term of {floor_rms:.3g}{unit} rms fitted, below the power law over the whole band ({where})"
    nxt = next((s for s in segments if s[0] >= top * (1 - 1e-9)), None)
    shape = ("no band of a decade above it holds one power law" if nxt is None else
             f"{'steeper' if nxt[2] > gamma else 'flatter'} above: {nxt[2]:.2f} over {nxt[0]:.3g}-{nxt[1]:.3g} rad/s")
    floor = (f"; a floor term of {floor_rms:.3g}{unit} rms fitted inside the band, below the power law there"
             if floor_rms > 0 else "; no white floor detected")
    return (f"{floor}; the band ends at {top:.3g} rad/s, where the spectrum departs from this power law in another "
            f"shape, not at a white floor ({shape})")


def _pilot(x: np.ndarray, dt: float) -> float:
    """A first slope: the Whittle fit of a power law alone to the once-differenced record's periodogram over its
    lowest decade (where a floor is least), plus 2; clipped to [GAMMA_MIN, 2 MAX_ORDER]."""
    rec = WhittleRecord(x, dt, 1)
    m = max(8, len(rec.omega) // 10)
    lw = np.log(rec.omega[:m])
    lp = np.log(np.maximum(rec.periodogram[:m], 1e-300))
    slope = float(np.polyfit(lw, lp, 1)[0])
    return float(np.clip(2.0 - slope, GAMMA_MIN + 0.1, 2 * MAX_ORDER))


def _fit_band(rec, floor, band):
    """(profile, (gamma, nll, ln ratio, low, high, low at the wall, high at the wall, wall low, wall high)) of the
    power law (+ floor) over the Fourier ordinates of the differenced record ``rec`` inside ``band`` (None: all)."""
    k = rec.order
    prof = PowerFloorProfile([rec], floor, keep_band(rec, band))
    lo, hi = max(GAMMA_MIN, 2 * k - 3.0), 2 * k + _HEADROOM
    g, nll, t = minimum(prof, lo, hi, None)
    g_lo, g_hi, wall_lo, wall_hi = interval(prof, g, nll, lo, hi)
    return prof, (g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi)


def _fit_order(x, dt, k, floor, band, discrete=False):
    rec = WhittleRecord(x, dt, k, discrete=discrete)
    return (rec, *_fit_band(rec, floor, band))


def _lr_apart(recs, floor, keep, lo, hi, g0) -> float:
    """Twice the log-likelihood gain of fitting equally long records apart over fitting them with shared parameters."""
    for r in recs[1:]:
        r.memo = recs[0].memo  # equally long records (same n, dt, order, taper): the same expected periodograms
    apart = sum(minimum(PowerFloorProfile([r], floor, keep), lo, hi, g0)[1] for r in recs)
    together = minimum(PowerFloorProfile(recs, floor, keep), lo, hi, g0)[1]
    return max(0.0, 2.0 * (together - apart))


def split_half_references(lr_h: float, lr_w: float, dof: int = 3) -> tuple[float, float]:
    """The two p-values of the split-half test's likelihood ratios (:func:`_split_half`): LR_h against chi2 with
    ``dof`` degrees of freedom, and F = (LR_h / dof) / (LR_w / 6 dof) against F(dof, 6 dof) (NaN without LR_w); the
    test's p-value is the larger."""
    p_chi2 = float(stats.chi2.sf(lr_h, dof))
    if not math.isfinite(lr_w):
        return p_chi2, math.nan
    dof_w = 2 * (STATIONARITY_BLOCKS // 2 - 1) * dof
    return p_chi2, float(stats.f.sf((lr_h / dof) / max(lr_w / dof_w, 1e-12), dof, dof_w))


def _split_half(x, dt, k, floor, g0, band, discrete=False) -> tuple:
    """The split-half test of stationarity (module docstring): (p-value, LR_h, LR_w); NaNs when the halves are too
    short to fit, LR_w NaN (and chi2 alone) when the quarters are, or hold fewer than 16 of the band's ordinates.

    The record's first 8 b samples (b = n // :data:`STATIONARITY_BLOCKS`) are cut into halves and each half into four
    blocks. LR_h, twice the likelihood gain of fitting the halves apart, is read two ways: against chi2 with p
    degrees of freedom (p the model's parameters, 3 with a floor, 2 without), its law for a stationary record whose
    periodogram ordinates are independent and Gaussian; and against LR_w, the same gain of fitting each half's four
    blocks apart, summed over the halves: F = (LR_h / p) / (LR_w / 6p), F-distributed with (p, 6p) degrees of
    freedom. A non-Gaussian record (renewal or shot noise, such as model I's contact renewals) correlates the
    ordinates across frequencies and makes both ratios larger than chi2 by about one factor, which the quotient
    cancels; on a short Gaussian record a floor the blocks do not resolve takes degrees of freedom from both, which
    the F reference does not know. The p-value is the larger of the two (an intersection-union test: it rejects
    only where both do), so its level holds where either reference does (docs/results/stationarity.md).
    """
    nan = (math.nan, math.nan, math.nan)
    if len(x) < 64 + 2 * k:
        return nan

    def make(y):
        return WhittleRecord(y, dt, k, discrete=discrete)

    def inside(rec):
        return len(rec.omega) if band is None else int(np.sum((rec.omega >= band[0] * (1 - 1e-12))
                                                              & (rec.omega <= band[1] * (1 + 1e-12))))
    lo, hi = max(GAMMA_MIN, 2 * k - 3.0), 2 * k + _HEADROOM
    dof = 3 if floor else 2
    b = len(x) // STATIONARITY_BLOCKS
    blocks = [make(x[i * b:(i + 1) * b]) for i in range(STATIONARITY_BLOCKS)] if b >= 64 + k else []
    if blocks and inside(blocks[0]) < 16:
        blocks = []
    half = STATIONARITY_BLOCKS // 2 * b if blocks else len(x) // 2
    halves = [make(x[:half]), make(x[half:2 * half])]
    if inside(halves[0]) < 8:
        return nan
    between = _lr_apart(halves, floor, keep_band(halves[0], band), lo, hi, g0)
    if not blocks:  # quarters too short to fit, or holding too few of the band's ordinates: chi2 alone
        return split_half_references(between, math.nan, dof)[0], between, math.nan
    keep_b = keep_band(blocks[0], band)
    q = STATIONARITY_BLOCKS // 2
    within = _lr_apart(blocks[:q], floor, keep_b, lo, hi, g0) + _lr_apart(blocks[q:], floor, keep_b, lo, hi, g0)
    return max(split_half_references(between, within, dof)), between, within


def _band_fit(rec, floor, band):
    """(gamma, nll) of the power law (+ floor) over the Fourier ordinates of ``rec`` inside ``band``."""
    k = rec.order
    g, nll, _ = minimum(PowerFloorProfile([rec], floor, keep_band(rec, band)), max(GAMMA_MIN, 2 * k - 3.0),
                        2 * k + _HEADROOM, None)
    return g, nll


def split_p(rec: WhittleRecord, floor: bool, band) -> tuple[float, float | None]:
    """The likelihood-ratio test for a change of the spectrum inside ``band``: (Bonferroni p-value, best knot).

    At each knot kappa (every quarter decade, at least half a decade and 16 Fourier ordinates inside either end) the
    model is fitted to each side apart and to the whole band; twice the gain, LR(kappa), is chi2 with 3 degrees of
    freedom (2 without a floor) under one power law (+ floor): every parameter may differ across the knot, so a
    corner, a level step and a local rise all count. A floor at its bound of zero on one side makes the law a
    mixture with fewer degrees of freedom, so the chi2 tail is conservative there. With K knots,
    p = min(1, K P(chi2 > max LR)) (Bonferroni). (1, None) when no knot fits.
    """
    lo, hi = band
    full = _band_fit(rec, floor, band)[1]
    ln10 = math.log(10.0)
    best, knot, count = 0.0, None, 0
    for lk in np.arange(math.log(lo) + 0.5 * ln10, math.log(hi) - 0.5 * ln10 + 1e-9, 0.25 * ln10):
        kappa = math.exp(lk)
        below = int(np.sum((rec.omega >= lo) & (rec.omega < kappa)))
        above = int(np.sum((rec.omega > kappa) & (rec.omega <= hi)))
        if min(below, above) < 16:
            continue
        count += 1
        lr = 2.0 * (full - _band_fit(rec, floor, (lo, kappa))[1] - _band_fit(rec, floor, (kappa, hi))[1])
        if lr > best:
            best, knot = lr, kappa
    if not count:
        return 1.0, None
    return float(min(1.0, count * stats.chi2.sf(best, 3 if floor else 2))), knot


def _differenced(x, dt, discrete=False):
    """order -> the record differenced that many times (:class:`WhittleRecord`), each made when first asked for and
    kept, so that every band fitted at one order shares its expected periodograms."""
    made = {}

    def get(k):
        if k not in made:
            made[k] = WhittleRecord(x, dt, k, discrete=discrete)
        return made[k]
    return get


def _at_its_order(get, floor, band, k):
    """(record, profile, result) of the power law (+ floor) over ``band`` at the differencing order its own estimate
    asks for: from order ``k``, raised while the interval reaches the order's upper limit 2k + 0.95, lowered while
    the estimate asks for a lower order (:func:`compare.analysis.whittle.order_for`; an estimate at the lower limit
    2k - 3 always does), each order tried once. A band whose spectrum is flatter or steeper than the whole record's
    is so fitted at its own order, not held at the limit of the record's."""
    tried = set()
    while True:
        tried.add(k)
        rec = get(k)
        prof, res = _fit_band(rec, floor, band)
        if res[6] and k < MAX_ORDER and k + 1 not in tried:
            k += 1
            continue
        want = order_for(res[0])
        if want < k and want not in tried:
            k = want
            continue
        return rec, prof, res


def _segments(get, floor, band, k, out):
    """Binary segmentation: a band whose split test (:func:`split_p`, at the band's own differencing order,
    :func:`_at_its_order` from ``k``) does not reject at :data:`TEST_LEVEL` is kept (as (ordinates, band, record,
    profile, result)); a rejected one is cut at its best knot and each side searched the same way. Sides shorter
    than a decade are dropped."""
    lo, hi = band
    if hi / lo < 10 * (1 - 1e-9):
        return out
    rec, prof, res = _at_its_order(get, floor, band, k)
    p, knot = split_p(rec, floor, band)
    if p >= TEST_LEVEL or knot is None:
        out.append((prof.m, band, rec, prof, res))
        return out
    _segments(get, floor, (lo, knot), rec.order, out)
    _segments(get, floor, (knot, hi), rec.order, out)
    return out


def _narrowed(x, dt, k, floor, omega, discrete=False):
    """The band of a record whose spectrum bends: of the binary segmentation's kept bands (:func:`_segments`, each
    fitted at its own differencing order), the one with the most Fourier ordinates. Returns (record, profile,
    result, bend p, band, segments), segments the kept bands as (low, high, gamma, low end, high end, order) in
    rising frequency; or None when no band of a decade or more is kept."""
    kept = _segments(_differenced(x, dt, discrete), floor, (float(omega[0]), float(omega[-1])), k, [])
    if not kept:
        return None
    kept.sort(key=lambda c: c[1])
    segments = tuple((band[0], band[1], res[0], res[3], res[4], rec.order) for _, band, rec, _, res in kept)
    _, band, rec, prof, res = max(kept, key=lambda c: c[0])
    return rec, prof, res, bend_p(prof, res[0], res[2]), band, segments


def check_record(x, name: str = "x", unit: str = "", *, resolution: bool = True) -> None:
    """ValueError, in one line saying what would help, for a record no spectrum can be fitted to: too few samples,
    a constant channel, or one that changes in fewer than half its steps (written at the file's resolution).

    Parameters
    ----------
    x : ndarray
        The record.
    name, unit : str
        How the message names the channel and its unit.
    resolution : bool, optional
        Refuse a record that stays the same in more than half its steps (default). Off for a simulator's
        piecewise-constant output (model III's force holds between contact events), which no file rounded.
    """
    n = len(x)
    if n < 32:
        raise ValueError(f"{name}: only {n} samples; a spectral fit needs at least 32 (a longer record)")
    steps = np.diff(x)
    if not np.any(steps):
        raise ValueError(f"{name} is constant ({x[0]:.6g} {unit}) over all {n} samples: a saturated or disconnected "
                         "sensor has no spectrum (check the channel)".replace(" )", ")"))
    still = float(np.mean(steps == 0))
    if resolution and still > 0.5:
        q = float(np.min(np.abs(steps[steps != 0])))
        raise ValueError(f"{name} stays the same in {100 * still:.0f} % of its {n - 1} steps (smallest change "
                         f"{q:.3g} {unit}): the record is at the file's resolution and its spectrum is the rounding's; "
                         "export it with more digits (a finer unit or more decimals), or the motion stopped for most "
                         "of the record (a stalled block)".replace(" )", ")"))


def fit_record(x, dt: float, *, floor: bool = True, order: int | None = None, band=None, quantity: str = "x",
               stationarity: bool = True, unit: str | None = None, discrete: bool = False) -> RecordFit:
    """Fit C_x = A omega^-gamma + B to a uniformly sampled record by the debiased Whittle likelihood.

    Parameters
    ----------
    x : array_like
        The record (e.g. positions, Units: m), uniformly sampled, trend removed or not (differencing removes
        polynomials of degree below k).
    dt : float
        Sampling step (Units: s).
    floor : bool, optional
        Fit a white floor B >= 0 (default); False fits the power law alone.
    order : int, optional
        Differencing order k; default from a pilot slope (:func:`compare.analysis.whittle.order_for`), raised while
        the interval reaches the order's limit 2k + 1.
    band : tuple of float, optional
        (low, high) (Units: rad/s): the likelihood over the Fourier ordinates inside only (the expectation still
        holds every frequency's leakage); default all of them.
    quantity : str, optional
        What the record is of (``"x"``, ``"F"``, ...), carried to the result.
    stationarity : bool, optional
        Run the split-half test (thirteen more fits: the halves and their quarters, apart and together).
    unit : str, optional
        The record's unit (SI); default from ``quantity`` (:data:`RECORD_UNITS`: ``"m"`` for x, ``"N"`` for F, ``""``
        for mu), carried to the result as ``record_unit``.
    discrete : bool, optional
        The record is of a discrete-time process (a cumulative sum of random steps, a simulation's update rule):
        fit C = A (2 sin(omega dt / 2) / dt)^-gamma + B, the power law's discrete form, instead of the continuous law
        folded at Nyquist (default: a continuous process sampled, what an instrument records). A discrete random
        walk read as a sampled continuous one has more power toward Nyquist than the folded law (52 % more at half
        Nyquist for gamma 4), which the fit takes for a floor and a lower gamma.

    Returns
    -------
    RecordFit
        gamma with its 95 % profile interval, A, B, the crossover, the identified band, flags and notes.
    """
    x = np.asarray(x, dtype=float)
    check_record(x, quantity)
    u = RECORD_UNITS.get(quantity, "") if unit is None else unit
    notes = []
    auto = band is None
    if band is not None and band[1] > math.pi / dt * (1 + 1e-9):
        notes.append(f"the band given ends at {band[1]:.4g} rad/s, above the record's Nyquist frequency "
                     f"{math.pi / dt:.4g} rad/s: its ordinates end there")
    if order is None:
        k = order_for(_pilot(x, dt))
        while True:
            rec, prof, res = _fit_order(x, dt, k, floor, band, discrete)
            if res[6] and k < MAX_ORDER:
                k += 1
                continue
            if order_for(res[0]) < k:  # over-differenced: the order the estimate itself asks for
                k = order_for(res[0])
                rec, prof, res = _fit_order(x, dt, k, floor, band, discrete)
            break
    else:
        k = int(order)
        rec, prof, res = _fit_order(x, dt, k, floor, band, discrete)
    g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi = res
    bend = bend_p(prof, g, t)
    searched, split_flag, segments, cut_above = False, None, (), False
    if band is None and bend < SCREEN_LEVEL:
        searched = True
        whole = (float(rec.omega[0]), float(rec.omega[-1]))
        narrowed = _narrowed(x, dt, k, floor, rec.omega, discrete)
        if narrowed is None:
            split_flag = (f"no band of a decade holds one power law (bend test p = {bend:.2g}; the split test rejects "
                          f"every band at {TEST_LEVEL:g})")
        elif narrowed[4] != whole:
            bend_whole = bend
            rec, prof, res, bend, trimmed, segments = narrowed
            g, nll, t, g_lo, g_hi, wall_lo, wall_hi, lo, hi = res
            k = rec.order
            cut_above = trimmed[1] < whole[1]
            notes.append(f"one power law does not fit every frequency (bend test p = {bend_whole:.2g}); "
                         f"fitted over {trimmed[0]:.3g}-{trimmed[1]:.3g} rad/s, of the bands where a split test "
                         f"(likelihood ratio at knots every quarter decade, Bonferroni, p >= {TEST_LEVEL:g}) finds "
                         "one power law the one with the most frequencies")
            if len(segments) > 1:
                notes.append("the bands where one power law holds: " + "; ".join(
                    f"{g_:.2f} [{a:.2f}, {b:.2f}] over {lo_:.3g}-{hi_:.3g} rad/s (order {k_})"
                    for lo_, hi_, g_, a, b, k_ in segments))
            band = trimmed
    if wall_hi or wall_lo:
        notes.append(f"the 95 % interval reaches the fitted range's {'upper' if wall_hi else 'lower'} limit "
                     f"{hi if wall_hi else lo:.2f} at differencing order {k}")
    A, B = prof.levels(g, t)
    w0, w1 = float(prof.omega[0]), float(prof.omega[-1])
    cross = (A / B) ** (1.0 / g) if B > 0 else math.inf
    if discrete:
        # where A (2 sin(omega dt / 2) / dt)^-gamma = B; that law never falls below A (dt / 2)^gamma (at Nyquist)
        cross = 2.0 / dt * math.asin(cross * dt / 2.0) if cross * dt / 2.0 < 1.0 else math.inf
        notes.append("fitted as a discrete-time process: C = A (2 sin(omega dt / 2) / dt)^-gamma + B, the power law "
                     "A omega^-gamma at low frequency")
    band_out = (w0, float(min(cross, w1)))
    end = ("floor" if cross < w1 else "given" if not auto else "departure" if cut_above else "last frequency")
    if end == "floor" and not discrete and cross > math.pi / dt / math.sqrt(10.0):
        notes.append("a floor that crosses the power law in the top half-decade below Nyquist is also what a "
                     "discrete-time process (a simulation's cumulative sum of random steps) shows when fitted as a "
                     "sampled continuous one: if the record is one, fit it as such (discrete=True; analyze "
                     "--discrete)")
    flags = []
    if (wall_lo and g - lo < 1e-3 and lo > GAMMA_MIN) or (wall_hi and hi - g < 1e-3):
        flags.append(f"gamma is not identified: the estimate sits at the fitted range's limit {lo if wall_lo else hi:.2f} "
                     f"at differencing order {k}")
    if band_out[1] <= w0 * 1.0001:
        notes.append("the floor lies above the power law at every fitted frequency: gamma is not identified")
        band_out = (w0, w0 * 1.0001)
    p, lr_h, lr_w = (_split_half(x, dt, k, floor, g, band, discrete) if stationarity else
                     (math.nan, math.nan, math.nan))
    if p < TEST_LEVEL:
        flags.append(f"not stationary: the halves' spectra differ (split-half likelihood ratio against the halves' "
                     f"own quarters, p = {p:.2g})")
    if split_flag:
        flags.append(split_flag)
    elif bend < TEST_LEVEL and not searched:
        flags.append(f"the spectrum bends within the band (bend test p = {bend:.2g})")
    return RecordFit(gamma=g, gamma_low=float(g_lo), gamma_high=float(g_hi), prefactor=A, floor=B,
                     floor_rms=math.sqrt(2.0 * math.pi * B / dt), crossover=cross, band=band_out, order=k,
                     n_samples=len(x), nll=nll, stationarity_p=p, stationarity_lr=(lr_h, lr_w), bend_p=bend,
                     quantity=quantity,
                     flags=tuple(flags), notes=tuple(notes), band_auto=auto, n_points=prof.m,
                     level_cov=level_cov(prof, g, t), segments=segments,
                     fit_band=tuple(map(float, band)) if band is not None else (), band_end=end,
                     record_unit=u, spectrum_unit=spectrum_unit_of(u))


def expected_gamma(spectrum, fit: RecordFit, dt: float, band=None, floor: bool = True, sampled: bool = True) -> float:
    """The exponent :func:`fit_record` converges to on records of ``spectrum``: the same fit (order, floor term,
    band, length) to the expected periodogram instead of a measured one. A closed form that is not a power law over
    the band (a window's zeros, a corner near it) has no single exponent; the one to compare a fit with is the one
    the same estimator reads off the closed form without noise, since the debiased Whittle likelihood weights
    every Fourier ordinate alike where a straight line through log bins weights every decade alike.

    Parameters
    ----------
    spectrum : callable
        omega (Units: rad/s) -> the sampled record's spectrum C^(s)(omega), folded at Nyquist (the record's unit^2 s).
    fit : RecordFit
        The fit of a record of it, whose ``order`` and ``n_samples`` are used.
    dt : float
        Sampling step (Units: s).
    band : tuple of float, optional
        The band the fit was given (Units: rad/s); default every ordinate.
    floor : bool, optional
        Whether the fit had its floor term (:func:`fit_record`'s default).
    sampled : bool, optional
        ``spectrum`` is already the sampled record's (default); False folds a continuous one at Nyquist by its 8
        nearest images on each side (omega^-2 leaves about 1/(2 pi^2 8) of its Nyquist level out, a few percent
        near Nyquist and nothing a band far below it feels beyond leakage).

    Returns
    -------
    float
        gamma of the noise-free fit.
    """
    k = fit.order
    rec = WhittleRecord(np.random.default_rng(0).standard_normal(fit.n_samples), dt, k)
    w = rec.grid_omega
    if sampled:
        values = np.asarray(spectrum(w), dtype=float)
    else:
        ws = 2.0 * math.pi / dt
        values = sum(np.asarray(spectrum(np.abs(w + m * ws)), dtype=float) for m in range(-8, 9))
    rec.periodogram = above_rounding(rec.expected_from_grid(values))
    prof = PowerFloorProfile([rec], floor, keep_band(rec, band))
    return minimum(prof, max(GAMMA_MIN, 2 * k - 3.0), 2 * k + _HEADROOM, fit.gamma)[0]


def fit_series(t, y, *, band=None, quantity: str = "x", stationarity: bool = True,
               integrate: bool = False, discrete: bool = False) -> RecordFit:
    """:func:`fit_record` of a record given with its sample times: the exponent every report, ``compare`` and sweep
    quotes of a time record (a scene's x(t) or F(t), a simulator's output).

    Parameters
    ----------
    t, y : array_like
        Sample times (Units: s, uniform) and the record (its own unit).
    band : tuple of float, optional
        (low, high) (Units: rad/s): the Fourier ordinates fitted; default the record model's own band search.
    quantity : str, optional
        ``"x"``, ``"F"``, ...: what the record is of.
    stationarity : bool, optional
        Run the split-half test (thirteen more fits): off only for an exact simulator, stationary by construction.
    integrate : bool, optional
        Fit the running sum of y dt and return the exponent of y (gamma - 2): for a spectrum flatter than
        omega^-1.05 (a 1/f force), which the record model cannot represent. The sum's transfer
        dt^2 / (4 sin^2(omega dt / 2)) is omega^-2 to (omega dt)^2 / 12 of it.
    discrete : bool, optional
        y is a discrete-time process (a cumulative sum of random steps, a simulation's update rule): its power law's
        discrete form is fitted (:func:`fit_record`).

    Returns
    -------
    RecordFit
    """
    t = np.asarray(t, dtype=float)
    dt = float(t[1] - t[0])
    y = np.asarray(y, dtype=float)
    if not integrate:
        return fit_record(y, dt, band=band, quantity=quantity, stationarity=stationarity, discrete=discrete)
    # a flat channel is refused as such, not as its (linear) running sum; a force that holds between events (an exact
    # simulator's) is not a rounded file
    check_record(y, quantity, resolution=False)
    z = np.cumsum(y - y.mean()) * dt
    u = RECORD_UNITS.get(quantity, "")
    fit = fit_record(z, dt, band=band, quantity=quantity, stationarity=stationarity, unit=f"{u} s".strip(),
                     discrete=discrete)
    return replace(fit.derived(2.0, 1.0, quantity, spectrum_unit_of(u)),
                   notes=fit.notes + ("fitted through the record's running sum (its spectrum omega^-2 times the "
                                      "record's): the floor and the exponents in the notes above are the sum's (2 "
                                      "above the record's); gamma and its segments are the record's",))
