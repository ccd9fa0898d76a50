"""The sampled family of a fit (compare/analysis/family_fit.py): an evaluation kept and scaled to a new level equals
the family evaluated there."""
import math

import numpy as np

import reduced_models as rm
from compare.analysis.families import FAMILIES
from compare.analysis.family_fit import fit_family, record_for, sampled_spectrum, segments_of


def _q(fam, theta, floor):
    return np.array([math.log10(theta[p.name]) if p.log else theta[p.name] for p in fam.params] + [math.log10(floor)])


def test_a_level_step_reuses_the_kept_evaluation_and_equals_a_fresh_one():
    fam = FAMILIES["model_III"]
    w = np.linspace(0.1, 3000.0, 5000)
    q = _q(fam, {"L": 2e-9, "w": 1e-2}, 1e-24)
    kept = sampled_spectrum(fam, 0.1, 1e-3, cell=0.1)
    kept(w, q)
    calls = []
    shape = fam.shape
    object.__setattr__(fam, "shape", lambda *a: calls.append(1) or shape(*a))
    try:
        up = q.copy()
        up[0] += 0.37  # the level only
        up[-1] -= 1.0  # and the floor
        got = kept(w, up)
        assert calls == []  # scaled, not evaluated
        fresh = sampled_spectrum(fam, 0.1, 1e-3, cell=0.1)
        fresh.proportional = False  # evaluate every time
        want = fresh(w, up)
        assert len(calls) == 1
    finally:
        object.__setattr__(fam, "shape", shape)
    # rounding only: 10^0.37 applied to the kept values against the level inside the shape (a few 1e-16)
    assert np.max(np.abs(got / want - 1)) < 1e-13


def test_a_family_not_proportional_to_its_level_is_evaluated_every_time():
    # model Ib's micro level adds to L's term: ten times L is not ten times the family
    fam = FAMILIES["model_Ib"]
    th = {"L": 1.1e-10, "a": 1e-3, "omega_c": 548.0, "Q": 16.0, "omega_0": 1e5, "omega_1": 1e7, "L2": 1e-11,
          "a2": 1e-5, "omega3": 500.0}
    s = sampled_spectrum(fam, 5e-4, 1e-3)
    w = np.geomspace(0.1, 3000.0, 200)
    s(w, _q(fam, th, 1e-24))
    assert s.proportional is False


def test_an_ordinate_below_one_cell_gets_a_cell_that_stays_above_zero_frequency():
    # a 300 s record at 1 kHz groups 8 ordinates per cell; the lowest ordinates are single and their cells used to
    # reach omega = 0 exactly (the family infinite there, the whole likelihood infinite, no start found)
    fam = FAMILIES["model_III"]
    dw = 2 * math.pi / 300.0
    s = sampled_spectrum(fam, 0.1, 1e-3, cell=8 * dw)
    w = dw * np.arange(1, 20)
    vals = s(w, _q(fam, {"L": 2e-9, "w": 1e-2}, 1e-24))
    assert np.all(np.isfinite(vals)) and np.all(vals > 0)


def test_a_level_interval_holds_the_scatter_of_the_renewals_level():
    # Model I's level is the mean squared jump of the N T v / a = 900 renewals of a 60 s record: it scatters by
    # sqrt(1.8 / 900) = 4.5 % about the family's L, where the Whittle curvature, counting 3e4 ordinates, gives under
    # 1 %. With the record's segments the interval's half-width (natural log) is Student's t(7) times the batch
    # means' error: its expectation 2.36 x 4.5 % = 0.11, and a 8-segment estimate scatters by a quarter of itself;
    # asserted between 0.05 and 0.25, and at least the curvature's.
    p = rm.spring_block.SpringBlockParams.reference()
    fam = FAMILIES["model_I"]
    truth, v = fam.from_model(p)
    x = rm.spring_block.simulate(p, 60.0, 1e-3, seed=21).x
    x = x + np.random.default_rng(21).normal(0.0, math.sqrt(2 * math.pi * 1e-24 / 1e-3), len(x))
    rec = record_for(x, 1e-3)
    plain = fit_family(rec, fam, v)
    wide = fit_family(rec, fam, v, segments=segments_of(x, 1e-3))
    half = lambda f: math.log(f.intervals["L"][1] / f.intervals["L"][0]) / 2
    assert wide.theta["L"] == plain.theta["L"]  # the maximum is the same fit
    assert half(wide) >= half(plain)
    assert 0.05 < half(wide) < 0.25, half(wide)
    assert half(plain) < 0.05


def test_model_III_zero_spacing_is_read_from_a_long_record():
    # 300 s at 1 kHz: 1.5e5 ordinates in linear groups of 8, the last one partial. The window's zeros lie
    # 2 pi v / w = 62.83 rad/s apart; a candidate within 0.1 % of it (the start's scan covers +-1 %). The groups'
    # spacing read from the last two groups (a partial one) had put every candidate 12.5 % low.
    from compare.analysis.family_fit import Grouped, _zero_spacings

    p = rm.asperity_force.AsperityForceParams(v=0.1, N=100.0)
    rec = record_for(rm.asperity_force.simulate(p, 300.0, 1e-3, seed=0).x, 1e-3)
    spacing = _zero_spacings(Grouped(rec, fine=True))
    assert np.min(np.abs(spacing / (2 * np.pi * p.v / p.w) - 1)) < 1e-3, spacing
