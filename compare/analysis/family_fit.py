"""A spectral family fitted to one record by the Whittle likelihood, the sensor floor a nuisance term.

The record is differenced twice (every family's common omega^-4 range becomes flat) and held as a
:class:`~compare.analysis.whittle.WhittleRecord`; a family (:mod:`compare.analysis.families`) plus a white floor
C_0 (Units: m^2 s; a sensor's white noise of rms sigma at step dt has C_0 = sigma^2 dt / (2 pi), eq. 2) is its model.
Positive parameters are fitted as their base-10 logarithms.

The fit runs on the Whittle likelihood of the differenced periodogram with adjacent ordinates grouped
(:class:`Grouped`: the lowest 64 alone, then bins 0.5 % wide in frequency, each bin's m ordinates entering as
m [ln mu_b + mean(I)_b / mu_b], exact when the model's mean is constant over the bin), its mean the differencing
gain times the model folded at Nyquist and the floor; a grid over the corner parameters gives the start. The bins'
width is set by the sharpest feature, a resonance: of quality Q its flanks change the mean by a factor e over
1 / (2 Q) in frequency, 3 % for model I's reference (Q = 17); with bins 1 % wide its fitted omega_c fell 0.3 % below
the truth on 60 s records (intervals +-0.2 %) and Q by up to 23 %; at 0.5 % the fits of 8 such records are those
at 0.2 % to a small fraction of their intervals (omega_c and Q covered in 7 of 8 with either, the same record
missing), at 2.5 times the cost of 1 % bins (0.2 %: five times). L-BFGS-B runs on the likelihood per ordinate,
restarted from its own end while that gains (:func:`_descend`), and stops on a relative change of 1e-11
(:data:`_STOP`). This leaves out the finite record's leakage,
small once two differences flatten the spectrum; ``exact=True`` polishes the maximum on the debiased likelihood of
:mod:`compare.analysis.whittle` (records of at most :data:`EXACT_N` samples: its mean costs 0.03 s per evaluation at
2e4 samples and 1.5 s at 4e5). Every family compared on one record must be fitted alike.

The 95 % intervals (:mod:`compare.analysis.family_intervals`) come from the curvature of the grouped negative
log-likelihood at the maximum over every free parameter and the floor (finite differences on the fitted scale;
log-fitted parameters get asymmetric ends), a corner's from its profile likelihood (the other parameters fitted
again at each step), and the place of model III's comb of zeros from the debiased likelihood. A
parameter whose feature (:meth:`Family.feature`) lies outside the band where the fitted family stands above the
floor is "not identified": no interval; so is a scale whose 95 % interval spans more than a factor 100, and so are
the parameters placing a feature (a step, a micro level) whose amplitude the record does not tell from its neutral
value.

A level's interval also holds the record's own scatter of its level (:func:`segments_of`): a renewal force's
spectrum is set by the squared jumps of the renewals the record holds, N T v / a of them, so its level scatters by
sqrt(1.8 / (N T v / a)) about the mean (4.5 % for model I's reference at 60 s, 1.2 % at 900 s: relative variance
1.4 of one uniform jump's square and 0.2 covariance with each neighbour), while the Whittle curvature counts the
ordinates only (0.6 %). The scatter of the level over :data:`SEGMENTS` consecutive segments of the record (batch
means) measures it without knowing N; the level's interval is the wider of the curvature's and the batch means'
(Student's t with SEGMENTS - 1 degrees of freedom).
"""
from __future__ import annotations

import copy
import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize, stats

from . import family_intervals
from .families import Family, identified
from .whittle import WhittleFit, WhittleRecord, maximum_likelihood

__all__ = ["FamilyFit", "Grouped", "fit_family", "record_for", "sampled_spectrum", "SampledSpectrum", "cell_of", "ORDER",
           "EXACT_N", "SEGMENTS", "segments_of", "without"]

ORDER = 2  # differences: every family's omega^-4 range flat, the floor rising as omega^4
EXACT_N = 2**15  # records up to this many samples get the debiased likelihood's maximum
_GRID = 9  # trial points per corner parameter when choosing a start (5 missed a resonance between two of them)
_ALONE = 64  # lowest ordinates kept alone
_FINE_GROUPS = 20_000  # linear groups of a family that is not smooth: 4000 ordinates per model III zero spacing at
#   400 s and v / w = 10 /s become 400 groups
_BIN = 0.005  # relative width of a bin above them (module docstring)
_STOP = {"ftol": 1e-11, "gtol": 1e-9, "maxiter": 2000}  # L-BFGS-B's stopping rule, module docstring


def record_for(x, dt: float) -> WhittleRecord:
    """The :class:`~compare.analysis.whittle.WhittleRecord` every family is fitted to (differenced :data:`ORDER`
    times), so that their likelihoods compare.

    Parameters
    ----------
    x : array_like
        Displacement record (Units: m), uniformly sampled.
    dt : float
        Sampling step (Units: s).
    """
    return WhittleRecord(np.asarray(x, dtype=float), dt, ORDER)


def without(record: WhittleRecord, spans) -> WhittleRecord:
    """A copy of ``record`` whose ordinates inside the frequency ``spans`` ((low, high), rad/s: a line's skirt,
    :func:`compare.analysis.lines.remove_lines`) are left out of the grouped likelihood; the record itself unchanged.
    Its expected-periodogram machinery (``exact=True``) is not available on the copy."""
    if not spans:
        return record
    keep = np.ones(len(record.omega), bool)
    for lo, hi in spans:
        keep &= ~((record.omega >= lo) & (record.omega <= hi))
    out = copy.copy(record)
    out.omega, out.periodogram, out.memo = record.omega[keep], record.periodogram[keep], {}
    out.n = record.n  # the ordinates' spacing 2 pi / (n dt) is the record's
    return out


class Grouped:
    """A record's differenced periodogram with adjacent ordinates grouped (module docstring).

    Parameters
    ----------
    record : WhittleRecord
    fine : bool, optional
        Linear groups of :attr:`run` adjacent ordinates instead of 0.5 % bins (for a family that is not smooth on the
        bins' scale), at most :data:`_FINE_GROUPS` of them.

    Attributes
    ----------
    omega : ndarray
        Each group's mean frequency (Units: rad/s).
    index : ndarray
        Each ordinate's group.
    mean : ndarray
        Each group's mean ordinate.
    count : ndarray
        Ordinates per group.
    gain : ndarray
        The differencing gain |2 sin(omega dt / 2) / dt|^(2k) at ``omega``.
    """

    def __init__(self, record: WhittleRecord, fine: bool = False):
        w, I = record.omega, record.periodogram
        k = min(_ALONE, len(w))
        self.run = max(1, math.ceil(len(w) / _FINE_GROUPS)) if fine else 0  # ordinates per linear group
        if fine:
            idx = np.concatenate([np.arange(k), k + (np.arange(len(w) - k) // self.run)])
        elif len(w) > k:
            edges = np.geomspace(w[k], w[-1] * (1 + 1e-12), max(2, int(math.log(w[-1] / w[k]) / _BIN) + 1))
            idx = np.concatenate([np.arange(k), k + np.searchsorted(edges[1:-1], w[k:], side="right")])
        else:
            idx = np.arange(len(w))
        self.count = np.bincount(idx).astype(float)
        keep = self.count > 0
        self.omega = (np.bincount(idx, weights=w) / np.maximum(self.count, 1))[keep]
        self.mean = (np.bincount(idx, weights=I) / np.maximum(self.count, 1))[keep]
        self.count = self.count[keep]
        self.index = (np.cumsum(keep) - 1)[idx]  # each ordinate's group
        self.periodogram = I
        self.dt = record.dt
        self.gain = np.abs(2.0 * np.sin(self.omega * record.dt / 2.0) / record.dt) ** (2 * record.order)

    def ordinate_loglik(self, sampled, q) -> np.ndarray:
        """Each ordinate's log-likelihood -(ln mu + I / mu), mu its group's mean (Vuong's test compares them)."""
        mu = (self.gain * sampled(self.omega, q))[self.index]
        return -(np.log(mu) + self.periodogram / mu)

    def negloglik(self, sampled, q) -> float:
        """sum_b m_b [ln mu_b + mean_b / mu_b], mu_b = gain x ``sampled(omega_b, q)`` (inf where mu <= 0)."""
        return self.negloglik_of(self.gain * sampled(self.omega, q))

    def negloglik_of(self, mu) -> float:
        """sum_b m_b [ln mu_b + mean_b / mu_b] for the groups' expected means ``mu`` (inf where mu <= 0)."""
        if not np.all(mu > 0):
            return math.inf
        return float(np.sum(self.count * (np.log(mu) + self.mean / mu)))


@dataclass(frozen=True)
class FamilyFit:
    """A family's maximum-likelihood fit to one record.

    Attributes
    ----------
    family : str
    theta : dict
        Name -> fitted value (the parameters' units, :class:`~compare.analysis.families.Param`).
    floor : float
        The white floor C_0 (Units: m^2 s).
    nll : float
        The debiased Whittle negative log-likelihood at the maximum.
    intervals : dict
        Name -> (low, high) 95 % ends, or None where the parameter is not identified.
    band : tuple
        (low, high) (rad/s): the lowest Fourier frequency to where the fitted family meets the floor.
    n_free : int
        Parameters the record identifies, the floor included (the information criterion's count).
    held : tuple of str
        Parameters held at their neutral value (their feature does not show) and those sharing its feature.
    v : float
        The sliding speed the family was evaluated at (Units: m/s).
    """

    family: str
    theta: dict
    floor: float
    nll: float
    intervals: dict
    band: tuple
    n_free: int
    v: float
    converged: bool = True
    params: tuple = field(default=(), repr=False)
    held: tuple = ()

    def parameters(self, fam: Family) -> dict:
        """Name -> [value, 95 % half-width, unit] or "not identified" (summary.json's form). A log-fitted
        parameter's half-width is the larger distance from its value to an end of its interval."""
        out = {}
        for p in fam.params:
            iv = self.intervals.get(p.name)
            if iv is None:
                out[p.name] = "not identified"
            else:
                val = self.theta[p.name]
                out[p.name] = [float(val), float(max(val - iv[0], iv[1] - val)), p.unit]
        return out


def _to_theta(fam: Family, q) -> dict:
    return {p.name: (10.0 ** q[i] if p.log else float(q[i])) for i, p in enumerate(fam.params)}


# a corner parameter x places its feature at frequency c x^e (c in units of the speed v): how a search spreads it
_FEATURE_LAW = {"a": (2.0, -1), "a2": (2.0, -1), "w": (2 * math.pi, -1), "D_c": (1.0, -1), "omega_c": (None, 1),
                "omega3": (None, 1), "omega_lo": (None, 1), "omega_hi": (None, 1)}
_REACH = 30.0  # a search keeps a corner's feature within this factor of the band's ends


def _param_at(name: str, f: float, v: float) -> float:
    """log10 of corner parameter ``name`` whose feature lies at angular frequency ``f`` (rad/s)."""
    c, e = _FEATURE_LAW[name]
    return math.log10(f) if c is None else math.log10(c * v / f)


def _bounds(fam: Family, v: float, lo: float, hi: float):
    """The search box on the fitted scale: each parameter's own bounds, a corner's narrowed so that its feature
    stays within :data:`_REACH` of the band (lo, hi) (rad/s) (beyond, the record cannot tell where it is), and the
    floor's log10 (m^2 s)."""
    out = []
    for p in fam.params:
        b = (math.log10(p.bounds[0]), math.log10(p.bounds[1])) if p.log else p.bounds
        if p.name in _FEATURE_LAW:
            ends = sorted((_param_at(p.name, lo / _REACH, v), _param_at(p.name, hi * _REACH, v)))
            b = (max(b[0], ends[0]), min(b[1], ends[1]))
        out.append(b)
    return out + [(-80.0, 20.0)]


# parameters restarted from the first maximum at a second value (factor of the band's top): the contacts' inertia
# corner just above the band, where a scene's gram-sized pads put it (a 10-30 % tilt of the resonance's flanks)
_RESTARTS = {"omega_1": 3.0}
# parameters restarted from the first maximum at these multiples of its value: a window of width w / 2 or w / 3 has
# every second or third zero of the window w, a local maximum where 2 of 20 records of model III's confusion cell
# (60 s) ended from the start's best grid point
_MULTIPLES = {"w": (2.0, 3.0)}
# parameters placing a comb of zeros: read again on the debiased likelihood (family_intervals.comb_on_debiased)
_COMBS = ("w",)
COMB_EXACT_N = family_intervals.COMB_EXACT_N

_IMAGES = 2  # aliasing images each side: a family falling as omega^-4 leaves out 5^-4 of its Nyquist level


_SUB = 4  # sub-points averaged over each ordinate's cell for a family that is not smooth


def cell_of(record: WhittleRecord, fam: Family):
    """The width (rad/s) of a linear group of ordinates (:class:`Grouped` with ``fine``) for a family that is not
    smooth, else None."""
    if fam.smooth:
        return None
    return max(1, math.ceil(len(record.omega) / _FINE_GROUPS)) * 2.0 * math.pi / (record.n * record.dt)


class SampledSpectrum:
    """The sampled record's spectrum of family ``fam`` at speed ``v`` (m/s) and step ``dt`` (s): the family folded at
    Nyquist (:func:`~compare.analysis.whittle.folded`'s sum, all images in one call of the family) plus the white
    floor, which a sensor adds after sampling. Called as ``spectrum(omega, q)`` (Units: m^2 s), ``q`` the
    fitted-scale parameters with log10 of the floor last.

    ``cell`` (rad/s, the ordinates' spacing 2 pi / (n dt)): the family is averaged over each ordinate's cell at
    :data:`_SUB` points, a first account of the finite record's leakage for a family with exact zeros (model III's
    window): without it an ordinate at a zero, which leakage fills, reads thousands of times its mean. An ordinate
    below one cell's width gets a cell as wide as its own frequency.

    A family proportional to its level (L or S: every family but model Ib, whose micro level adds; checked on the
    first call) is evaluated once per value of its other parameters: the last :data:`_KEPT` evaluations are kept
    and scaled to a new level, so that the likelihood's steps in the level and the floor (two of every gradient's
    finite differences, most of the curvature's) cost no evaluation of the family. Scaled and evaluated values
    differ by rounding (1e-16 relative).
    """

    def __init__(self, fam: Family, v: float, dt: float, cell: float | None = None):
        step = 2.0 * math.pi / dt
        self.fam, self.v = fam, v
        self._shifts = np.array([0.0] + [m * step for m in range(1, _IMAGES + 1) for _ in (0, 1)])
        self._signs = np.array([1.0] + [s for _ in range(_IMAGES) for s in (1.0, -1.0)])
        self._cell = cell
        self._offsets = np.zeros(1) if cell is None else (np.arange(_SUB) + 0.5) / _SUB - 0.5  # in cells
        self.level = next((i for i, p in enumerate(fam.params) if p.name in ("L", "S")), None)
        self.proportional = None  # decided on the first call
        self._kept = {}

    def part(self, w, q) -> np.ndarray:
        """The folded family alone (no floor) at ``w`` (rad/s) and fitted-scale parameters ``q`` (Units: m^2 s)."""
        w = np.asarray(w, dtype=float)
        # an ordinate's cell never reaches zero frequency, where the family is infinite: below one cell's width the
        # cell narrows to the ordinate's own frequency (the lowest ordinates, each a group of its own)
        width = 0.0 if self._cell is None else np.minimum(self._cell, w)
        wo = (w[None, :] + self._offsets[:, None] * width).ravel()
        ws = np.abs(self._shifts[:, None] + self._signs[:, None] * wo[None, :])
        vals = self.fam.shape(_to_theta(self.fam, q), ws.ravel(), self.v).reshape(ws.shape).sum(axis=0)
        return vals.reshape(len(self._offsets), len(w)).mean(axis=0)

    def _is_proportional(self, w, q) -> bool:
        """Ten times the level gives ten times the family at ``q``, to 1e-12."""
        if self.level is None:
            return False
        up = np.array(q, dtype=float)
        up[self.level] += 1.0
        return bool(np.allclose(self.part(w, up), 10.0 * self.part(w, q), rtol=1e-12, atol=0.0))

    def scaled_part(self, w, q) -> np.ndarray:
        """:meth:`part`, scaled from a kept evaluation at the same other parameters where the family is
        proportional to its level."""
        q = np.asarray(q, dtype=float)
        if self.proportional is None:
            self.proportional = self._is_proportional(w, q)
        if not self.proportional:
            return self.part(w, q)
        j = self.level
        key = (id(w), tuple(q[:j]) + tuple(q[j + 1:-1]))
        hit = self._kept.get(key)
        if hit is not None and hit[0] is w:
            return hit[2] * 10.0 ** (q[j] - hit[1])
        out = self.part(w, q)
        if len(self._kept) >= _KEPT:
            self._kept.pop(next(iter(self._kept)))  # the oldest
        self._kept[key] = (w, float(q[j]), out)  # w kept alive with it, so that its id stays its own
        return out

    def __call__(self, w, q) -> np.ndarray:
        return self.scaled_part(w, q) + 10.0 ** q[-1]


_KEPT = 16  # family evaluations a SampledSpectrum keeps (a gradient of model Ib's ten parameters takes eleven)


def sampled_spectrum(fam: Family, v: float, dt: float, cell: float | None = None) -> SampledSpectrum:
    """The sampled record's spectrum of family ``fam`` plus the white floor (:class:`SampledSpectrum`).

    Returns
    -------
    SampledSpectrum
        ``spectrum(omega, q)`` (Units: m^2 s), ``q`` the fitted-scale parameters with log10 of the floor last.
    """
    return SampledSpectrum(fam, v, dt, cell)


def _start(G: Grouped, fam: Family, v: float, start_theta: dict | None):
    """A start: the floor from the top tenth of the band, every level from the band's middle, the corners from a
    grid over the band (the best of the grouped likelihood), unless ``start_theta`` is given."""
    w, I = G.omega, G.mean
    C = I / G.gain
    top = w > 0.9 * w[-1]
    floor0 = math.log10(max(float(np.mean(C[top])), 1e-300))
    mid = (w > w[0] * 10) & (w < w[-1] / 10) if w[-1] > 100 * w[0] else slice(None)
    lev4 = math.log10(max(float(np.median((C * w**4)[mid])), 1e-300))
    spectrum = sampled_spectrum(fam, v, G.dt, None if fam.smooth else G.run * (G.omega[1] - G.omega[0]))
    lo, hi = w[0], w[-1]
    base = []
    for p in fam.params:
        if start_theta is not None and p.name in start_theta:
            val = start_theta[p.name]
            base.append(math.log10(val) if p.log else val)
        elif p.name in ("L", "L2"):
            base.append(lev4 - (2.0 if p.name == "L2" else 0.0))
        elif p.name == "S":
            base.append(lev4)
        elif p.log:
            base.append(None)  # a corner: from the grid below
        else:
            base.append(0.5 * (p.bounds[0] + p.bounds[1]) if p.name != "s" else 2.0)
    base.append(floor0)
    free = [i for i, b in enumerate(base) if b is None]
    if not free:
        return np.array(base, dtype=float)
    # each corner parameter's trial values place its feature over the band (and one beyond each end)
    freqs = np.geomspace(lo / 3, hi * 3, _GRID)
    # a sharp feature (a resonance of quality 10 or more) is narrower than the grid's spacing (0.6-0.8 decade) and on
    # a long record its likelihood is too: the flattened spectrum's highest peaks are tried as well (measured on
    # 900 s records of model I: the grid alone started between 209 and 1401 rad/s, the fit then stopped in a maximum
    # 3e5 below the one at the resonance, 548 rad/s)
    freqs = np.concatenate([freqs, _peaks(G)])
    if not fam.smooth:
        # a family with repeating zeros (model III's window) has a likelihood with a mode at every shift of its zeros
        # against the ordinates: the zeros' spacing is read from the periodogram's own periodicity (the strongest
        # periods of its logarithm along the ordinates, and twice and three times them)
        freqs = np.concatenate([freqs, _zero_spacings(G)])
    # a resonance of quality 1 or 10; its spring damping and the contacts' inertia unseen (:data:`_RESTARTS` tries the
    # inertia near the band once the rest is fitted: on the grid it mimics a resonance's fall)
    fixed_start = {"Q": [0.0, 1.0], "omega_0": [math.log10(hi * 1e3)], "omega_1": [math.log10(hi * 1e3)]}
    trials = [fixed_start[fam.params[i].name] if fam.params[i].name in fixed_start
              else [_param_at(fam.params[i].name, f, v) for f in freqs] for i in free]
    bnd = _bounds(fam, v, lo, hi)
    levels = [k for k, p in enumerate(fam.params) if p.name in ("L", "S")]
    def trial(q):
        """(q with its levels matched to the record, its likelihood)."""
        q = np.clip(q, [b[0] for b in bnd], [b[1] for b in bnd])
        # the level that best matches this shape (the median ratio of ordinate to model)
        floor = 10.0 ** q[-1]
        part = spectrum.scaled_part(w, q)
        for j in levels:
            ratio = max(float(np.median(I / (G.gain * (part + floor)))), 1e-300)
            q[j] += math.log10(ratio)
            part = spectrum.scaled_part(w, q)
        return q, G.negloglik_of(G.gain * (part + floor))

    best, best_v = None, math.inf
    for combo in itertools.product(*trials):
        q = np.array([c if c is not None else 0.0 for c in base], dtype=float)
        q[free] = combo
        if fam.name == "model_II" and q[3] <= q[2]:
            continue
        q, val = trial(q)
        if val < best_v:
            best, best_v = q, val
    if not fam.smooth:
        # the likelihood of a comb of zeros has a mode at every alignment of its zeros with the ordinates, 1e-4 apart
        # in the spacing on a 60 s record (a zero's width over the band's top): each corner scanned over +-1 % of
        # its start in steps of 2e-4, the descent taking it from there
        for i in free:
            for d in np.log10(1.0 + np.linspace(-0.01, 0.01, 101)):
                q = best.copy()
                q[i] += d
                q, val = trial(q)
                if val < best_v:
                    best, best_v = q, val
    return best


def _peaks(G: Grouped, count: int = 2) -> np.ndarray:
    """The ``count`` highest local maxima (rad/s) of the flattened spectrum C omega^4 of the grouped periodogram,
    smoothed over five groups, below the top tenth of the band (where the floor rises as omega^4)."""
    y = np.log(np.maximum(G.mean / G.gain * G.omega**4, 1e-300))
    y = np.convolve(y, np.ones(5) / 5, mode="same")
    inner = np.arange(2, len(y) - 2)
    inner = inner[G.omega[inner] < 0.9 * G.omega[-1]]
    top = inner[(y[inner] > y[inner - 1]) & (y[inner] >= y[inner + 1])]
    return G.omega[top[np.argsort(y[top])[::-1][:count]]]


def _zero_spacings(G: Grouped, peaks: int = 4) -> np.ndarray:
    """Candidate spacings (rad/s) of a comb of zeros in an ungrouped periodogram: the ``peaks`` strongest periods of
    log I along the ordinates (between 3 ordinates and a third of them), each also doubled and tripled.

    Each period is refined between the Fourier frequencies of log I (the amplitude's maximum within half a bin, on
    a grid of 1/40 bin): a whole-bin period is 2 % off for a comb of 50 periods, which misplaces the band's top zeros
    by their own width and left a 60 s record of model III starting at three times the spacing."""
    y = np.log(np.maximum(G.mean, 1e-300))
    y = y - np.convolve(y, np.ones(101) / 101, mode="same")  # the slow trend out
    P = np.abs(np.fft.rfft(y)) ** 2
    k = np.arange(len(P))
    ok = (k >= 3) & (k <= len(y) / 3)
    top = k[ok][np.argsort(P[ok])[-peaks:]]
    j = np.arange(len(y))
    fine = []
    for kk in top:
        shifts = kk + np.linspace(-0.5, 0.5, 41)
        amp = np.abs(np.exp(-2j * np.pi * np.outer(shifts, j) / len(y)) @ y)
        fine.append(shifts[int(np.argmax(amp))])
    step = float(np.median(np.diff(G.omega)))  # the linear groups' spacing (the last group may be partial)
    spacing = len(y) / np.array(fine) * step
    return np.concatenate([spacing, 2 * spacing, 3 * spacing])


SEGMENTS = 8  # consecutive segments of a record whose levels' scatter widens a level's interval


def segments_of(x, dt: float, count: int = SEGMENTS) -> list:
    """The :func:`record_for` of ``count`` consecutive equal segments of record ``x`` (Units: m) at step ``dt`` (s),
    for :func:`fit_family`'s level interval; empty when a segment would hold fewer than 256 samples."""
    x = np.asarray(x, dtype=float)
    m = len(x) // count
    if m < 256:
        return []
    return [record_for(x[i * m:(i + 1) * m], dt) for i in range(count)]


def _level_scatter(spectrum: "SampledSpectrum", q, band, segments) -> float | None:
    """The 95 % half-width (natural log) of the family's level from the scatter of its ratio to the fit over the
    record's ``segments`` (each the sum of its ordinates over the sum of the fit's means, where the family stands
    above the floor inside ``band``, its lowest three ordinates left out): Student's t over the segments' log ratios'
    standard error. None without segments or where fewer than two hold 16 such ordinates."""
    logs = []
    floor = 10.0 ** q[-1]
    for seg in segments:
        w = seg.omega
        keep = (w >= max(band[0], 4 * w[0])) & (w <= band[1])
        if keep.sum() < 16:
            continue
        part = spectrum.part(w[keep], q)
        dom = part > floor
        if dom.sum() < 16:
            continue
        gain = np.abs(2.0 * np.sin(w[keep][dom] * seg.dt / 2.0) / seg.dt) ** (2 * seg.order)
        logs.append(math.log(float(np.sum(seg.periodogram[keep][dom]) / np.sum(gain * (part[dom] + floor)))))
    if len(logs) < 2:
        return None
    return float(stats.t.ppf(0.975, len(logs) - 1) * np.std(logs, ddof=1) / math.sqrt(len(logs)))


def _band(record: WhittleRecord, fam: Family, theta: dict, floor: float, v: float):
    """From the lowest Fourier frequency to where the family meets the floor (Nyquist if it never does)."""
    w = record.omega
    above = fam.shape(theta, w, v) > floor
    hi = float(w[np.nonzero(above)[0][-1]]) if above.any() else float(w[0])
    return float(w[0]), hi


def _identify(record: WhittleRecord, fam: Family, v: float, q):
    """(q, identified per parameter, band) at fitted parameters ``q``."""
    q = np.array(q, dtype=float)
    theta = _to_theta(fam, q)
    band = _band(record, fam, theta, 10.0 ** q[-1], v)
    feats = fam.features(theta, v)
    return q, [identified(feats[p.name], band) for p in fam.params], band


_DESCENTS = 6  # L-BFGS-B restarted from its own end while it gains more than _GAIN


def _descend(grouped, q0, bounds, per: float):
    """L-BFGS-B from ``q0`` on the negative log-likelihood per ordinate (``per``: one over their number), restarted
    from where it stops while a restart gains more than :data:`_GAIN` (at most :data:`_DESCENTS` runs). Returns
    scipy's result with ``fun`` the likelihood itself.

    Per ordinate: L-BFGS-B's first step goes to the minimum of a quadratic of unit curvature, a gradient's length
    away; on the sum over 3e4 ordinates (a gradient of 1e4 per decade) that step reached the search box's ends,
    where the family is not finite, and the run ended after one iteration where it began (measured on model_Iv's
    60 s records: 1300 short of the maximum). Its memory of the curvature, built along a narrow valley (omega_c
    against Q and the contacts' inertia), can also end a run early: hence the restarts."""
    def f(q):
        return grouped(q) * per

    res = optimize.minimize(f, q0, method="L-BFGS-B", bounds=bounds, options=_STOP)
    for _ in range(_DESCENTS - 1):
        again = optimize.minimize(f, res.x, method="L-BFGS-B", bounds=bounds, options=_STOP)
        gained = (res.fun - again.fun) / per
        if again.fun < res.fun:
            res = again
        if not gained > _GAIN:
            break
    res.fun = grouped(res.x)
    return res


_GAIN = 0.02  # a restart's gain below which a descent has stopped (the likelihood's units; a 95 % drop is 1.92)


def fit_family(record: WhittleRecord, fam: Family, v: float, *, start_theta: dict | None = None,
               nested: FamilyFit | None = None, exact: bool = False, segments=()) -> FamilyFit:
    """Maximum-likelihood fit of family ``fam`` plus a white floor to ``record``, with 95 % intervals.

    Parameters
    ----------
    record : WhittleRecord
        From :func:`record_for` (displacement, Units: m).
    fam : Family
        The family (:data:`compare.analysis.families.FAMILIES`).
    v : float
        The record's mean sliding speed (Units: m/s).
    start_theta : dict, optional
        Name -> value to start from (e.g. the values a simulated record was built with); the grid otherwise.
    nested : FamilyFit, optional
        The fit of a family that ``fam`` nests (model I's, for model Ib and the ageing family) on the same record:
        the descent also starts from its maximum mapped into ``fam`` at the nesting point (:func:`_nesting_start`),
        and the better end is kept, so that ``fam`` never fits the record worse than the family it nests.
    exact : bool, optional
        Polish the maximum on the debiased likelihood (records of at most :data:`EXACT_N` samples; 5-15 s more per
        family on a loaded 2-core machine at 2e4 samples). Every family compared on one record must be fitted alike.
    segments : list of WhittleRecord, optional
        The record's consecutive segments (:func:`segments_of`): the level's interval then holds the scatter of the
        level over them (module docstring); none: the curvature's alone.

    Returns
    -------
    FamilyFit
    """
    G = Grouped(record, fine=not fam.smooth)
    spectrum = sampled_spectrum(fam, v, record.dt, cell_of(record, fam))
    bounds = _bounds(fam, v, G.omega[0], G.omega[-1])
    q0 = _start(G, fam, v, start_theta)

    def grouped(q):
        val = G.negloglik(spectrum, q)
        return val if math.isfinite(val) else 1e300

    per = 1.0 / float(G.count.sum())
    res = _descend(grouped, q0, bounds, per)
    q_nest = None if nested is None else _nesting_start(fam, nested, q0, bounds)
    if q_nest is not None:
        res = _better(res, _descend(grouped, q_nest, bounds, per))
    seen = _identify(record, fam, v, res.x)[1] if any(p.name in _MULTIPLES for p in fam.params) else None
    for i, p in enumerate(fam.params):
        starts = []
        if p.name in _RESTARTS:
            starts.append(math.log10(_RESTARTS[p.name] * G.omega[-1]))
        if seen is not None and seen[i]:  # a comb the band shows (on a record without one: 2 s more at 400 s)
            starts += [res.x[i] + math.log10(k) for k in _MULTIPLES.get(p.name, ())]
        for value in starts:
            q1 = res.x.copy()
            q1[i] = min(max(value, bounds[i][0]), bounds[i][1])
            again = _descend(grouped, q1, bounds, per)
            if again.fun < res.fun:
                res = again
    q, ident, band = _identify(record, fam, v, res.x)
    unseen = [i for i, p in enumerate(fam.params) if not ident[i] and p.neutral is not None]
    neutral = []
    for _ in range(2):
        if unseen:
            # a feature the record does not show: hold its amplitude at the neutral value, and the parameters that
            # share its feature (its corner) where they are, and fit the rest again
            res, neutral = _hold(fam, v, grouped, res.x, bounds, unseen, neutral, per, q_nest)
        if exact and record.n <= EXACT_N:
            fit = maximum_likelihood(record, spectrum, res.x, bounds=bounds, images=None)
        else:
            fit = WhittleFit(tuple(map(float, res.x)), float(res.fun), bool(res.success))
        q, ident, band = _identify(record, fam, v, fit.params)
        for i in neutral:
            ident[i] = False
        intervals = family_intervals.intervals(fam, grouped, q, ident, neutral, bounds, _FEATURE_LAW, per)
        # a feature whose amplitude the record does not tell from its neutral value (no interval, or one holding it)
        # is not seen either: held and fitted again once
        unseen = [i for i, p in enumerate(fam.params) if i not in neutral and p.neutral is not None
                  and (intervals[p.name] is None or intervals[p.name][0] <= p.neutral <= intervals[p.name][1])]
        if not unseen:
            break
    lev = next((i for i, p in enumerate(fam.params) if p.name in ("L", "S")), None)
    if lev is not None and intervals.get(fam.params[lev].name) is not None and segments:
        half = _level_scatter(spectrum, q, band, segments)
        lo, hi = intervals[fam.params[lev].name]
        val = 10.0 ** q[lev]
        if half is not None:
            intervals[fam.params[lev].name] = (min(lo, val * math.exp(-half)), max(hi, val * math.exp(half)))
    comb = next((i for i, p in enumerate(fam.params) if p.name in _COMBS), None)
    if (comb is not None and intervals.get(fam.params[comb].name) is not None and record.n <= COMB_EXACT_N
            and len(record.omega) == (record.n + 1) // 2 - 1):  # every ordinate kept: no line's skirt left out
        read = family_intervals.comb_on_debiased(record, spectrum, q, comb,
                                                 tuple(math.log10(e) for e in intervals[fam.params[comb].name]))
        if read is not None:
            q = np.array(q, dtype=float)
            q[comb] = read[0]
            intervals[fam.params[comb].name] = (10.0 ** read[1][0], 10.0 ** read[1][1])
    theta = _to_theta(fam, q)
    n_free = 1 + sum(1 for i in range(len(fam.params)) if i not in neutral and ident[i])  # what the band shows
    return FamilyFit(fam.name, theta, 10.0 ** q[-1], fit.nll, intervals, band, n_free, v, fit.converged, tuple(q),
                     tuple(fam.params[i].name for i in neutral))


def _hold(fam: Family, v: float, grouped, q, bounds, unseen, neutral, per: float, q_nest=None):
    """Hold the amplitudes ``unseen`` at their neutral values and the parameters sharing their features where they
    are (narrowing ``bounds`` in place), and fit the rest again from ``q`` and, where given, from the nesting start
    ``q_nest`` (:func:`_nesting_start`; its held parameters set as held), keeping the better end. Returns (result,
    held indices)."""
    q = np.array(q, dtype=float)
    feats = fam.features(_to_theta(fam, q), v)
    names = {fam.params[i].name for i in unseen}
    held = set(neutral) | {j for j, p in enumerate(fam.params)
                           if feats[p.name] is not None and any(feats[p.name] == feats[n] for n in names)}
    held |= set(unseen)
    for i in held:
        p = fam.params[i]
        if i in unseen:
            q[i] = math.log10(p.neutral) if p.log else p.neutral
        bounds[i] = (q[i], q[i])
    lo, hi = [b[0] for b in bounds], [b[1] for b in bounds]
    res = _descend(grouped, np.clip(q, lo, hi), bounds, per)
    if q_nest is not None:
        qn = np.array(q_nest, dtype=float)
        qn[sorted(held)] = q[sorted(held)]
        res = _better(res, _descend(grouped, np.clip(qn, lo, hi), bounds, per))
    return res, sorted(held)


def _nesting_start(fam: Family, nested: FamilyFit, q0, bounds):
    """The maximum of ``nested``'s fit mapped into ``fam`` at the nesting point, on the fitted scale (floor last):
    the shared parameters and the floor at their fitted values, each amplitude with a neutral value (model Ib's
    micro level, the ageing step) at it, the parameters placing those features (their corners: where the amplitude
    is neutral the family does not depend on them) from ``q0``, the start of ``fam``'s own descent; clipped to
    ``bounds``. There ``fam``'s spectrum is ``nested``'s wherever ``nested``'s parameters that ``fam`` lacks do not
    act on the band (model I's contacts' inertia, which the ageing family lacks, above it: :func:`compare.analysis.
    identify._nests`). None where ``nested`` shares no parameter with ``fam``."""
    names = [p.name for p in fam.params]
    if not any(n in nested.theta for n in names):
        return None
    q = np.array(q0, dtype=float)
    for i, p in enumerate(fam.params):
        if p.name in nested.theta:
            val = nested.theta[p.name]
        elif p.neutral is not None:
            val = p.neutral
        else:
            continue
        q[i] = math.log10(val) if p.log else val
    q[-1] = math.log10(nested.floor)
    return np.clip(q, [b[0] for b in bounds], [b[1] for b in bounds])


def _better(a, b):
    """The descent (scipy result) with the lower negative log-likelihood; ``a`` on a tie."""
    return b if b.fun < a.fun else a

