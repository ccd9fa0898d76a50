"""Which of the paper's mechanisms a displacement record points to: every registered model's spectral family fitted
(:mod:`compare.analysis.family_fit`), ranked, and compared with the best by a likelihood-ratio test in both
directions.

Lines: the record's spectral lines (a drive's or the mains' frequency; model_Iv's vibration) are found, subtracted and
their skirts left out before any family is fitted (:mod:`compare.analysis.lines`): a nuisance term every family
carries alike, never a mechanism; model_Iv is model I's family, and its line is named in what would separate them.

Ranking: by the Bayesian information criterion of the Whittle fit, nll + k ln(n) / 2 (n Fourier ordinates, k
fitted parameters with the floor), so a family that only adds a feature the record does not show ranks below the
one without it; criteria within 1 of the lowest count as a tie, won by the family with fewer parameters. Models
whose families are one (model_Iv is model I's family plus a line) share one fit. Between model I's family and a
family nesting it (below), the calibrated test of the nesting family's gain decides the order, not the criterion:
a significant gain ranks the nesting family above model I's, an insignificant one below it.

Comparison: each model against the best by Vuong's test (Vuong 1989, Econometrica 57, 307) on the per-ordinate
log-likelihood differences d_j: Z = sum d_j / (sqrt(n) sd(d)); the one-sided p-value 1 - Phi(Z) is the chance of a
lead this large were the model as close to the record as the best. The parameter counts enter the ranking only
(Schwarz's correction inside Z would reject a family that nests the best and adds a feature the record does not
show, for a penalty far larger than its tiny sd(d)): a richer family that fits no better is "indistinguishable", not
rejected. Where two families coincide on the record (sd(d) = 0) p = 1. The p-values of the comparisons are adjusted
by Holm's step-down method (Holm 1979). A model is "rejected" at adjusted p < alpha.

Nested gains: a family nesting model I's by features with a neutral value (model Ib's micro level, the ageing
step) fits every record at least as well as model I's; its gain T = 2 (nll_I - nll_other) is judged against the
simulated null table of the pair, record length and sampling step (:mod:`compare.analysis.null_tables`) where one
applies, else against chi^2 with the identified extra parameters' count (optimistic: the extra corner is not
identified under the null, so the fit's search over it inflates T); these p-values are Holm-adjusted across the
nesting models (:func:`nested_gains`). A gain significant at adjusted p < alpha ranks its family above model I's
and rejects model I's family (model_I and model_Iv, p the gain's adjusted p-value): by the table's calibration,
model I's own records are re-ranked at most at the rate alpha. A gain judged by chi^2 does so only where the
information criterion agrees (the optimistic p alone would re-rank model I's records too often). A gain not
significant, or a fit that held the extra features at their neutral values, makes the nesting model model I's
family on this record: its extra parameters are "not identified", it ranks below model I and stands as model I
stands (it coincides with the best where model I is the best, else shares model I's verdict and p-value, with
``coincides_with`` naming model I).

Coinciding families: a model whose family is the best's (model_Iv is model I's family plus a line), or a nesting
family whose gain the record does not show while model I is the best, coincides with the best: one family on this
record's band.

Verdicts: the best "fits" when every other model is rejected or coincides with it; else the best is
"indistinguishable". Every model not rejected but the best is "indistinguishable", with what would separate it (a
coinciding one names the best in ``coincides_with``). A record flagged as not stationary gets no mechanism.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np
from scipy import stats

import reduced_models

from . import null_tables
from .families import FAMILIES, MARGIN, Family
from . import lines as lines_mod
from .band_stationarity import stationarity
from .family_fit import (FamilyFit, Grouped, cell_of, fit_family, record_for, sampled_spectrum, segments_of,
                         without)

__all__ = ["Mechanism", "NestedGains", "identify", "holm", "nested_gains", "vuong", "stationarity", "record_stationarity"]

_BASE = ("model_I",)  # fitted first: the families below extend its spectrum and start from its fit, and from its
#   maximum at their nesting point, so that their gain over it is never negative (fit_family's ``nested``)
_EXTENDS_I = ("model_Ib", "model_ageing")
_TIE = 1.0  # information criteria closer than this rank as equal (a difference of 1 is no evidence either way)
MIN_SAMPLES = 4000  # the shortest record ranked: 4 s at 1 kHz, about the shortest length at which the exponent's
# coverage is measured (2^12 = 4096, docs/results/exponent_coverage.md); a level's scatter comes from eight segments
# of 500 samples each


@dataclass(frozen=True)
class Mechanism:
    """One registered model's standing for a record.

    Attributes
    ----------
    model : str
        Its key in :data:`reduced_models.MODELS`.
    verdict : str
        "fits", "indistinguishable" or "rejected".
    p_value : float
        Holm-adjusted p-value of the test "as close to the record as the best" (1 for the best itself); for a
        model coinciding with the best by its gain's test, that test's Holm-adjusted p-value (``nested_test``); for
        model I's family rejected by a nesting family's significant gain, that gain's.
    parameters : dict
        Name -> [value, 95 % half-width, unit] or "not identified".
    separate : str
        What would separate it from the best ("" for a rejected model or a best that fits alone).
    bic : float
        Its information criterion (lower is better).
    fit : FamilyFit
    coincides_with : str or None
        The best model, where this one's family is the best's on the record's band; model I, where this one nests
        model I's family by a gain the record does not show and model I is not the best (module docstring).
    nested_test : str
        How a nesting model's gain over model I was judged, or which nesting family's gain rejects model I's family
        ("" otherwise).
    lines : tuple of Line
        The record's spectral lines, subtracted before every family was fitted (:mod:`compare.analysis.lines`).
    """

    model: str
    verdict: str
    p_value: float
    parameters: dict
    separate: str
    bic: float
    fit: FamilyFit
    coincides_with: str | None = None
    nested_test: str = ""
    lines: tuple = ()

    def to_dict(self) -> dict:
        """summary.json's form of this standing.

        Returns
        -------
        dict
            ``model``, ``verdict``, ``p_value``, ``parameters``, ``separate``, ``coincides_with`` (the best, or
            None), ``nested_test``, ``bic``, ``band_rad_s`` (rad/s), ``floor_m2s`` (m^2 s), ``cannot_separate``
            (the model's parameters the family lumps together) and ``lines`` (the lines subtracted as nuisance
            terms, each ``omega_rad_s``, ``amplitude_m``, ``excess``).
        """
        return {"model": self.model, "verdict": self.verdict, "p_value": float(self.p_value),
                "parameters": self.parameters, "separate": self.separate, "coincides_with": self.coincides_with,
                "nested_test": self.nested_test, "bic": float(self.bic),
                "band_rad_s": [float(b) for b in self.fit.band], "floor_m2s": float(self.fit.floor),
                "cannot_separate": FAMILIES[self.model].cannot_separate,
                "lines": [ln.to_dict() for ln in self.lines]}


def holm(p) -> np.ndarray:
    """Holm's step-down adjustment of p-values (each adjusted p-value compared with the level directly).

    Parameters
    ----------
    p : array_like
        Raw p-values.

    Returns
    -------
    numpy.ndarray
        Adjusted p-values, monotone in the raw ones, at most 1.
    """
    p = np.asarray(p, dtype=float)
    m = len(p)
    order = np.argsort(p)
    adj = np.empty(m)
    running = 0.0
    for rank, i in enumerate(order):
        running = max(running, (m - rank) * p[i])
        adj[i] = min(1.0, running)
    return adj


def vuong(l_best: np.ndarray, l_other: np.ndarray) -> tuple[float, float]:
    """Vuong's statistic and its one-sided p-value that the other model is as close to the record as the best.

    Parameters
    ----------
    l_best, l_other : ndarray
        Per-ordinate log-likelihoods of the two fitted models.

    Returns
    -------
    (float, float)
        Z and 1 - Phi(Z); (0, 1) where the two coincide on the record.
    """
    d = l_best - l_other
    n = len(d)
    sd = float(np.std(d))
    lr = float(np.sum(d))
    if not sd > 1e-12 * max(1.0, float(np.mean(np.abs(l_best)))):
        return 0.0, 1.0
    z = lr / (math.sqrt(n) * sd)
    return z, float(stats.norm.sf(z))


def _extra(best: str, other: str) -> list:
    """The parameters of ``other``'s family that ``best``'s lacks."""
    names = {p.name for p in FAMILIES[best].params}
    return [p.name for p in FAMILIES[other].params if p.name not in names]


def _nests(best: str, other: str, fits: dict) -> bool:
    """Whether ``other``'s family extends ``best``'s on this record: it carries every parameter of ``best`` the
    record identifies (model I's contacts' inertia above the band is not one; the ageing family, whose miniblocks
    are massless, lacks it) and adds a feature with a neutral value, where it is ``best``'s family."""
    fam_b, fam_o = FAMILIES[best], FAMILIES[other]
    if fam_b.shape is fam_o.shape:
        return False
    seen = {p.name for p in fam_b.params if fits[best].intervals.get(p.name) is not None}
    extra = set(_extra(best, other))
    return seen <= {p.name for p in fam_o.params} and any(p.neutral is not None for p in fam_o.params
                                                           if p.name in extra)


def _nested_p(best: str, other: str, fits: dict, n_samples: int, dt: float) -> tuple:
    """The p-value of ``other``'s gain over ``best`` (it nests it, :func:`_nests`), how it was judged, and whether
    that p-value is calibrated: 1 where the fit held its extra features neutral; the pair's simulated null table
    where one applies (:mod:`compare.analysis.null_tables`); chi^2 with the identified extra parameters' count
    otherwise (optimistic: not calibrated)."""
    fit_o = fits[other]
    seen = [n for n in _extra(best, other) if fit_o.intervals.get(n) is not None]
    if not seen:
        return 1.0, "its extra features held neutral (not seen)", True
    t = null_tables.statistic(fits[best].nll, fit_o.nll)
    table = null_tables.lookup(best, other, n_samples, dt)
    if table is not None:
        return table.p_value(t), f"T = {t:.3g} against the simulated null ({table.n} records of {best})", True
    return (float(stats.chi2.sf(max(t, 0.0), len(seen))), f"T = {t:.3g} against chi^2({len(seen)}) (no null table)",
            False)


@dataclass(frozen=True)
class NestedGains:
    """The gains of the families nesting model I's over it on one record, and what they decide.

    Attributes
    ----------
    root : str
        The nested model (model_I, or model_Iv where model_I is not compared).
    family : tuple of str
        The compared models whose family is the root's (model_I and model_Iv).
    nesting : tuple of str
        The compared models whose family nests the root's (:func:`_nests`).
    tests : dict
        Nesting model -> (raw p-value, how T was judged, whether that p-value is calibrated).
    adjusted : dict
        Nesting model -> Holm-adjusted p-value (among the nesting models).
    promoted : tuple of str
        The nesting models ranked above the root's family: a significant gain (adjusted p < alpha) judged against a
        simulated null table, or against chi^2 where the information criterion agrees.
    unseen : tuple of str
        The nesting models whose gain is not significant: the root's family on this record.
    """

    root: str
    family: tuple
    nesting: tuple
    tests: dict
    adjusted: dict
    promoted: tuple
    unseen: tuple

    @property
    def top(self) -> str | None:
        """The promoted model with the smallest adjusted p-value (None where none is promoted)."""
        return min(self.promoted, key=lambda n: self.adjusted[n]) if self.promoted else None

    def describe(self, model: str) -> str:
        """``nested_test`` of ``model``: how its gain over the root was judged, or for a member of the root's family
        rejected by a nesting family's gain, which one; "" otherwise."""
        if model in self.tests:
            return f"{self.tests[model][1]}; Holm-adjusted p = {self.adjusted[model]:.2g}"
        if model in self.family and self.promoted:
            return (f"nested in {self.top}, whose gain over {self.root} ({self.tests[self.top][1]}) is significant: "
                    f"Holm-adjusted p = {self.adjusted[self.top]:.2g}")
        return ""


def nested_gains(names, fits: dict, n_samples: int, dt: float, alpha: float, bic: dict | None = None):
    """The gains of the compared families nesting model I's over it (:class:`NestedGains`), or None where no model
    of model I's family is compared.

    Parameters
    ----------
    names : sequence of str
        The compared models.
    fits : dict
        Model -> its :class:`~compare.analysis.family_fit.FamilyFit`.
    n_samples : int
        The record's length in samples (picks the null table).
    dt : float
        Sampling step (Units: s).
    alpha : float
        Level of the Holm-adjusted tests.
    bic : dict, optional
        Model -> information criterion; a gain judged by chi^2 (no null table) promotes its family only where the
        criterion ranks it above the root too. Without it, only calibrated gains promote.

    Returns
    -------
    NestedGains or None
    """
    shape_I = FAMILIES[_BASE[0]].shape
    family = [n for n in names if FAMILIES[n].shape is shape_I]
    if not family:
        return None
    root = _BASE[0] if _BASE[0] in family else family[0]
    nesting = [n for n in names if n not in family and _nests(root, n, fits)]
    tests = {n: _nested_p(root, n, fits, n_samples, dt) for n in nesting}
    adjusted = dict(zip(nesting, (float(a) for a in holm([tests[n][0] for n in nesting])))) if nesting else {}
    promoted = tuple(n for n in nesting if adjusted[n] < alpha
                     and (tests[n][2] or (bic is not None and bic[n] < bic[root])))
    unseen = tuple(n for n in nesting if adjusted[n] >= alpha)
    return NestedGains(root, tuple(family), tuple(nesting), tests, adjusted, promoted, unseen)


def _reorder(ranked: list, gains) -> list:
    """The ranking with model I's family moved below every promoted nesting family and every unseen nesting family
    that ranked above a member of model I's family moved just below the family (:class:`NestedGains`); the order
    is otherwise kept."""
    if gains is None:
        return ranked
    ranked = list(ranked)
    for n in gains.promoted:
        i = ranked.index(n)
        ahead = [m for m in ranked[:i] if m in gains.family]
        if ahead:
            ranked = [m for m in ranked[:i + 1] if m not in ahead] + ahead + ranked[i + 1:]
    for n in gains.unseen:
        last = max(ranked.index(m) for m in gains.family if m in ranked)
        if ranked.index(n) < last:
            ranked.remove(n)
            ranked.insert(last, n)  # just below the family's last member (the removal shifted it up by one)
    return ranked


def _judge_nested(gains, best: str, fits: dict, rejected: dict, coincides: dict, p_of: dict, tie: dict) -> None:
    """Apply the nested gains' verdicts (module docstring) to the comparisons with the best, in place: an unseen
    nesting family is model I's family (its extra parameters not identified; it coincides with the best where model
    I is the best, else shares model I's verdict and p-value); a promoted one rejects model I's family."""
    root_best = best in gains.family
    for n in gains.unseen:
        fits[n] = replace(fits[n], intervals={**fits[n].intervals, **{e: None for e in _extra(gains.root, n)}})
        tie[n] = best if root_best else gains.root
        if root_best:
            coincides[n], p_of[n] = True, gains.adjusted[n]
    if gains.promoted:
        for n in gains.family:
            rejected[n], coincides[n], p_of[n] = True, False, gains.adjusted[gains.top]
            tie.pop(n, None)
    if not root_best:
        for n in gains.unseen:
            rejected[n], coincides[n], p_of[n] = rejected[gains.root], False, p_of[gains.root]


def _separate(best: str, other: str, fits: dict, v: float) -> str:
    """What would tell ``other`` from ``best`` on a record like this one."""
    fam_o, fit_o = FAMILIES[other], fits[other]
    if FAMILIES[best].shape is fam_o.shape:
        bits = ["the same spectral family on this band"]
        if fam_o.line or FAMILIES[best].line:
            bits.append("the vibration's line (and its harmonics) in the raw spectrum, or a record without the "
                        "substrate's vibration")
        return "; ".join(bits)
    bits, unseen = [], {}  # what would show a feature -> the parameters placing it
    lo, hi = fit_o.band
    feats = fam_o.features(fit_o.theta, v)
    shared_names = {p.name for p in FAMILIES[best].params}
    for p in fam_o.params:
        f = feats[p.name]
        if fit_o.intervals.get(p.name) is not None or f is None or p.name in shared_names:
            continue
        if f < lo * MARGIN:
            where = f"a longer record (its feature near {f:.3g} rad/s lies below the band)"
        elif f > hi / MARGIN:
            where = f"a faster sampling or a quieter sensor (its feature near {f:.3g} rad/s lies above the band)"
        else:
            where = (f"a longer record or a quieter sensor (its feature near {f:.3g} rad/s does not show on this "
                     "band)" if p.name in fit_o.held else
                     f"a longer record or a quieter sensor (its feature near {f:.3g} rad/s is too faint to place)")
        unseen.setdefault(where, []).append(p.name)
    bits += [f"{other}'s {', '.join(names)}: {where}" for where, names in unseen.items()]
    r_b, r_o = reduced_models.MODELS[best].RESPONSE, reduced_models.MODELS[other].RESPONSE
    if r_b != r_o:
        bits.append(f"an independent force record (the x-F phase differs between the {r_b} and {r_o} responses)")
    bits.append("a velocity series (the corners move with v as each model predicts)")
    return "; ".join(dict.fromkeys(bits))


def record_stationarity(x, dt: float) -> dict:
    """The band test (:func:`compare.analysis.band_stationarity.stationarity`) on the record as :func:`identify`
    fits it: its lines removed and their skirts left out.

    Parameters
    ----------
    x : array_like
        Displacement record (Units: m), uniformly sampled.
    dt : float
        Sampling step (Units: s).
    """
    x, _, skirts = _without_lines(np.asarray(x, dtype=float), dt)
    return stationarity(x, dt, skirts=skirts)


def _without_lines(x: np.ndarray, dt: float):
    """(the record with its lines removed, the lines found, their skirts): :func:`compare.analysis.lines.
    remove_lines` on a record long enough to search, else the record as it is."""
    if len(x) > 4 * lines_mod.WINDOW:
        return lines_mod.remove_lines(x, dt)
    return x, [], []


_FORMS = "identify(t, x) with times (s) and positions (m), identify(record), or identify(x=x, dt=dt)"


def _record_arrays(t, x, positional, dt):
    """(positions, sampling step) of the forms :func:`identify` takes; a ValueError naming them for any other."""
    if positional or (x is not None and np.ndim(x) == 0):
        raise ValueError(f"identify takes the record as analyze_displacement does: {_FORMS}; "
                         "identify(x, dt, v) is not one of them (v is a keyword: v=...)")
    if t is not None and hasattr(t, "t") and hasattr(t, "x"):
        if x is not None:
            raise ValueError(f"a record carries its own positions: give identify(record) alone, or {_FORMS}")
        if getattr(t, "segmented", False):
            raise ValueError("the record's time stamps break into segments: identification needs one uniform record "
                             "(resample it, or pass one segment)")
        times = np.asarray(t.t, dtype=float)
        return t.x, float(np.median(np.diff(times))) if dt is None else dt
    if x is None:
        raise ValueError(f"no positions: {_FORMS}")
    if t is None:
        return x, dt
    if dt is not None:
        raise ValueError(f"give the times t or the step dt, not both: {_FORMS}")
    times = np.asarray(t, dtype=float)
    if times.shape != np.shape(x):
        raise ValueError(f"t holds {times.size} times and x {np.size(x)} positions: {_FORMS}")
    steps = np.diff(times)
    if times.size > 1 and not np.allclose(steps, steps[0], rtol=1e-6, atol=0.0):
        raise ValueError("the times are not uniform: identification needs one uniform record (resample it)")
    return x, float(steps[0]) if times.size > 1 else None


def too_short(n: int) -> str:
    """Why a record of ``n`` samples is not ranked, and what would help."""
    return (f"the record holds {n} samples; the mechanism ranking needs at least {MIN_SAMPLES} (its families' corners "
            f"and a level's scatter over eight segments): record longer, or at a higher sampling rate")


def identify(t=None, x=None, *positional, dt: float | None = None, v: float | None = None, models=None,
             alpha: float = 0.05, stationary: bool | None = None, progress=None) -> list:
    """The registered models ranked for a displacement record, best first, with verdicts and parameters.

    The record is given as :func:`compare.analysis.displacement.analyze_displacement` takes it: ``identify(t, x)``
    (times, then positions), or ``identify(record)``; or by keywords, ``identify(x=x, dt=dt)``. A call in the order
    ``identify(x, dt, v)`` (a number second, or a third positional argument) is refused with a ValueError that
    names these forms.

    Parameters
    ----------
    t : array_like or record
        Sample times (Units: s), uniform; or a record with attributes ``t`` (s) and ``x`` (m) (a
        :class:`~compare.io.measured.MeasuredData`, a model's or a scene's trace).
    x : array_like, optional
        Positions (Units: m) at ``t`` (or at steps of ``dt``), the slide included (twice differenced away).
    dt : float, optional
        Sampling step (Units: s), with ``x`` and no ``t``.
    v : float, optional
        Mean sliding speed (Units: m/s); default (x[-1] - x[0]) / duration.
    models : iterable of str, optional
        Keys of :data:`reduced_models.MODELS` to compare; default every registered model.
    alpha : float, optional
        Level of the Holm-adjusted comparisons.
    stationary : bool, optional
        False for a record flagged as not stationary: no mechanism is named (an empty list). None (default): the
        record's halves are compared by the band test (:func:`compare.analysis.band_stationarity.stationarity`,
        the lines' skirts left out).
    progress : callable, optional
        Called with one line (str) as each family's fit starts and ends, with its time (a long record's fits take
        minutes: a 600 s record at 1 kHz holds 3e5 ordinates).

    Returns
    -------
    list of Mechanism
        Best first.
    """
    x, dt = _record_arrays(t, x, positional, dt)
    if dt is None or not (dt > 0 and math.isfinite(dt)):
        raise ValueError(f"the sampling step dt must be positive, in s (got {dt!r})")
    x = np.asarray(x, dtype=float)
    if len(x) < MIN_SAMPLES:
        raise ValueError(too_short(len(x)))
    if v is None and len(x) > 1:
        v = float((x[-1] - x[0]) / (dt * (len(x) - 1)))
    x, found, skirts = _without_lines(x, dt)
    if stationary is None:
        stationary = stationarity(x, dt, skirts=skirts)["stationary"]
    if not stationary:
        return []
    if v is None:
        v = float((x[-1] - x[0]) / (dt * (len(x) - 1)))
    if not (v > 0 and math.isfinite(v)):
        raise ValueError(f"the mean sliding speed must be positive (got {v!r} m/s); pass v")
    names = list(models) if models is not None else list(reduced_models.MODELS)
    for n in names:
        if n not in FAMILIES:
            raise ValueError(f"no spectral family for model {n!r}; families: {', '.join(FAMILIES)}")
    rec = without(record_for(x, dt), skirts)
    segments = segments_of(x, dt)
    G = Grouped(rec)
    n_ord = len(rec.omega)
    fits, shared = {}, {}
    base = None  # model I's fit: the start of the families that extend it
    order = sorted(names, key=lambda n: n not in _BASE)
    distinct = len({id(FAMILIES[n].shape) for n in names})
    for n in order:
        fam: Family = FAMILIES[n]
        key = id(fam.shape)
        if key not in shared:
            nested = base if n in _EXTENDS_I else None
            t0 = time.perf_counter()
            if progress is not None:
                progress(f"fitting {n}'s family ({len(shared) + 1}/{distinct}, {len(rec.omega)} ordinates)")
            shared[key] = fit_family(rec, fam, v, start_theta=None if nested is None else nested.theta,
                                     nested=nested, segments=segments)
            if progress is not None:
                progress(f"{n}'s family fitted in {time.perf_counter() - t0:.1f} s")
            if n in _BASE:
                base = shared[key]
        f = shared[key]
        fits[n] = f if f.family == n else replace(f, family=n)
    bic = {n: fits[n].nll + fits[n].n_free * math.log(n_ord) / 2 for n in names}
    # near-ties (within _TIE: a richer family whose extra features stay neutral, up to the optimiser's precision) go
    # to the family with fewer parameters
    ranked = sorted(names, key=lambda n: bic[n])
    close = [n for n in ranked if bic[n] <= bic[ranked[0]] + _TIE]
    first = min(close, key=lambda n: (len(FAMILIES[n].params), names.index(n)))
    ranked = [first] + [n for n in ranked if n != first]
    # the families nesting model I's: their gains over it tested, Holm-adjusted among themselves; a significant gain
    # ranks the nesting family above model I's, an insignificant one below it (module docstring)
    gains = nested_gains(names, fits, len(x), dt, alpha, bic)
    ranked = _reorder(ranked, gains)
    best = ranked[0]
    G_fine = None if all(FAMILIES[n].smooth for n in names) else Grouped(rec, fine=True)
    ll = {n: (G if FAMILIES[n].smooth else G_fine).ordinate_loglik(sampled_spectrum(FAMILIES[n], v, dt,
                                                                                     cell_of(rec, FAMILIES[n])),
                                                                    np.asarray(fits[n].params)) for n in names}
    raw = [vuong(ll[best], ll[n])[1] for n in ranked[1:]]
    adj = holm(raw) if raw else np.array([])
    p_of = dict(zip(ranked[1:], (float(a) for a in adj)))
    rejected = {n: bool(p < alpha) for n, p in p_of.items()}
    coincides = {n: FAMILIES[n].shape is FAMILIES[best].shape for n in ranked[1:]}
    tie = {n: best for n in ranked[1:] if coincides[n]}  # coincides_with
    if gains is not None:
        _judge_nested(gains, best, fits, rejected, coincides, p_of, tie)
    alone = all(rejected[n] or coincides[n] for n in ranked[1:])
    out = []
    for i, n in enumerate(ranked):
        if i == 0:
            verdict, p, sep = ("fits" if alone else "indistinguishable"), 1.0, ""
        else:
            verdict = "rejected" if rejected[n] and not coincides[n] else "indistinguishable"
            p = p_of[n]
            sep = "" if verdict == "rejected" else _separate(best, n, fits, v)
        if sep and found and (FAMILIES[n].line or FAMILIES[best].line):
            sep += "; lines found and subtracted here: " + ", ".join(f"{ln.omega:.4g} rad/s" for ln in found)
        out.append(Mechanism(n, verdict, p, fits[n].parameters(FAMILIES[n]), sep, bic[n], fits[n],
                             tie.get(n) if i > 0 else None, gains.describe(n) if gains is not None else "",
                             tuple(found)))
    return out
