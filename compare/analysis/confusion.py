"""The confusion study of :func:`compare.analysis.identify.identify`: records simulated by each registered model's
exact simulator, with a white sensor floor, identified; per cell (model, parameter point, duration) the fraction of
seeds whose true model ranks first or indistinguishable from the first, is named alone, is displaced by a wrong
model named alone, and the coverage of the true family's 95 % intervals for the parameters the record identifies.

:data:`CELLS` are the stated grid; ``compare/studies/confusion_table.py`` runs it and writes docs/results/identification.md.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

import reduced_models as rm

from .families import FAMILIES
from .identify import identify

__all__ = ["Cell", "CELLS", "SMOKE_CELLS", "QUICK_CELLS", "run_cell", "binomial_interval", "DT", "FLOOR",
           "HALF_DECADE"]

DT = 1e-3  # 1 kHz
FLOOR = 1e-24  # m^2 s: a displacement sensor's white noise of rms sqrt(2 pi FLOOR / DT) = 79 pm


HALF_DECADE = 10**0.5  # a separating feature counts as inside a record's band when this far inside both ends


@dataclass(frozen=True)
class Cell:
    """One cell of the study: a registered model at one parameter point, recorded for ``duration`` seconds.

    Attributes
    ----------
    model : str
        Key of :data:`reduced_models.MODELS`.
    label : str
        The parameter point in words.
    params : object
        The model's parameters (SI units).
    duration : float
        Record length (Units: s).
    feature : float or None
        The angular frequency (rad/s) of the feature that separates the model from the others (a resonance, a
        corner, a level step), None where the point has none the record shows (model Ib's micro level below the
        floor of its macro level).
    feature_label : str
        That feature in words.
    """

    model: str
    label: str
    params: object
    duration: float
    feature: float | None = None
    feature_label: str = ""

    def feature_inside(self) -> bool:
        """Whether :attr:`feature` lies at least half a decade inside the record's band, from its lowest Fourier
        frequency 2 pi / T to Nyquist pi / dt (rad/s): where the must-show asks the true model named alone."""
        lo, hi = 2 * math.pi / self.duration, math.pi / DT
        return self.feature is not None and lo * HALF_DECADE <= self.feature <= hi / HALF_DECADE


def _points():
    """(model, label, parameters, separating feature (rad/s) or None, the feature in words) of the stated grid."""
    sb, wp, af, ms = rm.spring_block, rm.wear_particle, rm.asperity_force, rm.multiscale
    ref = sb.SpringBlockParams.reference()
    wc = math.sqrt(ref.N * ref.k0 / ref.M)
    return [
        ("model_I", "reference (a = 1 mm, v/a = 0.5 rad/s, omega_c = 548 rad/s)", ref, wc, "resonance omega_c"),
        ("model_I", "a = 10 mm (v/a = 0.05 rad/s)", sb.SpringBlockParams(a=1e-2), wc, "resonance omega_c"),
        ("model_Iv", "reference (A = 30 um at omega_v = 3000 rad/s)", rm.vibrating_block.VibratingBlockParams.reference(),
         wc, "resonance omega_c (the line lies above the band's top / 10^0.5)"),
        # the ageing family is the model's linear response about steady sliding: at its reference, renewal forces of
        # 2.1 times the direct effect's scale f_n A put the record at twice the family above the resonance; at
        # alpha = 0.1 (0.21 of it) the record is its family band by band (tests/compare/test_family_records.py)
        ("model_ageing", "alpha = 0.1 (b = B/A = 1/3, D_c = 0.1 mm: step at v/D_c = 5 rad/s)",
         rm.ageing.AgeingParams(alpha=0.1), 5.0, "level step at v / D_c"),
        ("model_II", "tau 10 ms-100 s, 1000 particles", wp.WearParticleParams(), 100.0, "corner 1/tau_min"),
        ("model_II", "tau 1 ms-1 s, kappa 0.1", wp.WearParticleParams(trapped=wp.DurationLaw(1e-3, 1.0),
                                                                    sliding=wp.DurationLaw(1e-3, 1.0),
                                                                    kappa_A=0.1, kappa_B=0.1),
         1.0, "corner 1/tau_max"),
        # model III's grid step dx / v = p w / (N v) must divide the 1 ms output step, and lie well below it: sampled
        # on its own grid the record falls below the continuum family toward Nyquist (0.22 of it over the top fifth
        # of the band: tests/compare/test_family_records.py); on a tenfold finer grid it is the family folded at
        # Nyquist to 4e-5. v = 0.1 m/s, N = 100: grid 0.1 ms, every tenth position recorded
        ("model_III", "w = 1 cm, v = 0.1 m/s, N = 100 (2 pi v / w = 63 rad/s; grid 0.1 ms)",
         af.AsperityForceParams(v=0.1, N=100.0), 2 * math.pi * 0.1 / 1e-2, "window corner 2 pi v / w"),
        ("model_Ib", "reference (micro level above 18 rad/s)", ms.MultiscaleParams.reference(), None,
         "none shown: the micro level is 4e-4 of the macro one"),
    ]


def _cells(durations, points):
    return tuple(Cell(m, lab, p, T, f, fl) for T in durations for (m, lab, p, f, fl) in points)


CELLS = _cells((60.0, 300.0, 900.0), _points())
SMOKE_CELLS = _cells((30.0,), _points()[::2])
QUICK_CELLS = _cells((10.0,), _points()[::2])  # a CI smoke: seconds per record


def binomial_interval(k: int, n: int, level: float = 0.95) -> tuple:
    """Clopper-Pearson interval of a fraction from ``k`` successes in ``n`` records (the table's criteria are read
    against it where a cell has fewer than 100 seeds: a criterion "at least p0" is shown when the interval's low end
    reaches p0, contradicted when its high end falls below p0).

    Returns
    -------
    (float, float)
        Low and high ends; (0, 1) for n = 0.
    """
    from scipy import stats

    if n == 0:
        return 0.0, 1.0
    a = 1 - level
    lo = 0.0 if k == 0 else float(stats.beta.ppf(a / 2, k, n - k + 1))
    hi = 1.0 if k == n else float(stats.beta.ppf(1 - a / 2, k + 1, n - k))
    return lo, hi


def _record(cell: Cell, seed: int) -> np.ndarray:
    tr = rm.MODELS[cell.model].simulate(cell.params, cell.duration, DT, seed=seed)
    noise = np.random.default_rng([seed, 1]).normal(0.0, math.sqrt(2 * math.pi * FLOOR / DT), len(tr.x))
    return tr.x + noise


def run_cell(cell: Cell, seeds) -> dict:
    """Identify one record per seed of ``cell``.

    Parameters
    ----------
    cell : Cell
    seeds : iterable of int
        The simulators' seeds (the floor's noise is seeded by (seed, 1)).

    Returns
    -------
    dict
        Counts over the seeds: ``n``, ``first_or_indistinguishable`` (the true model not rejected and ranked first
        or indistinguishable from the first), ``alone`` (ranked first with verdict "fits"), ``wrong_alone`` (another
        model ranked first with "fits" and the true model rejected; model_Iv counts as model I, its family),
        ``coincides`` (another model first with "fits", the true one not rejected: the same family on this band, its
        own feature unseen), ``indistinguishable`` (the first not alone), ``covered`` and ``intervals`` (the true
        family's identified parameters whose 95 % interval holds the value the record was built with), and the same
        per parameter in ``by_parameter`` (name -> (covered, intervals)), ``best`` (model -> times ranked first),
        ``cpu_s`` (the records' simulation and identification, CPU seconds).
    """
    fam = FAMILIES[cell.model]
    truth, v = fam.from_model(cell.params)
    same = {"model_I", "model_Iv"} if cell.model in ("model_I", "model_Iv") else {cell.model}  # one family
    out = {"n": 0, "first_or_indistinguishable": 0, "alone": 0, "wrong_alone": 0, "coincides": 0, "indistinguishable": 0,
           "covered": 0, "intervals": 0, "best": {}, "cpu_s": 0.0, "by_parameter": {}}
    for seed in seeds:
        c0 = time.process_time()
        ranking = identify(x=_record(cell, seed), dt=DT, v=v)
        out["cpu_s"] += time.process_time() - c0
        out["n"] += 1
        if not ranking:
            continue
        first = ranking[0]
        out["best"][first.model] = out["best"].get(first.model, 0) + 1
        mine = next(m for m in ranking if m.model == cell.model)
        ok_first = first.model in same or mine.verdict == "indistinguishable"
        out["first_or_indistinguishable"] += int(ok_first and mine.verdict != "rejected")
        out["alone"] += int(first.model in same and first.verdict == "fits")
        # a wrong model named alone: first with "fits" while the true model is rejected (a true model that only
        # coincides with the first on this band, its own feature unseen, is not contradicted)
        out["wrong_alone"] += int(first.model not in same and first.verdict == "fits" and mine.verdict == "rejected")
        out["coincides"] += int(first.model not in same and first.verdict == "fits" and mine.verdict != "rejected")
        out["indistinguishable"] += int(first.verdict == "indistinguishable")
        for name, iv in mine.fit.intervals.items():
            if iv is not None and name in truth:
                hit = int(iv[0] <= truth[name] <= iv[1])
                out["intervals"] += 1
                out["covered"] += hit
                k, n = out["by_parameter"].get(name, (0, 0))
                out["by_parameter"][name] = (k + hit, n + 1)
    return out
