"""Spectral lines found and subtracted before the families are fitted (compare/analysis/lines.py)."""
import math

import numpy as np
import pytest

import reduced_models as rm
from compare.analysis.family_fit import record_for, without
from compare.analysis.lines import FALSE, remove_lines

DT = 1e-3


def _noise(n, seed):
    """A record whose twice-differenced spectrum is white: white accelerations summed twice (m)."""
    return np.cumsum(np.cumsum(np.random.default_rng(seed).normal(0.0, 1e-9, n)))


def test_a_sinusoid_is_found_at_its_frequency_and_subtracted():
    # A sinusoid of 1e-9 m at 1234.567 rad/s (off the ordinates' grid) on 60 s of noise whose differenced level is
    # 1e-18 m^2 per sample: it stands ~1e5 times the median. Found within 1e-3 of an ordinate's spacing
    # (0.105 rad/s; measured 2e-5 rad/s) and its amplitude within 1 % (the noise's share of it is 1e-3).
    n = 60_000
    t = np.arange(n) * DT
    x = _noise(n, 3) + 1e-9 * np.sin(1234.567 * t + 0.3)
    clean, lines, skirts = remove_lines(x, DT)
    assert len(lines) >= 1
    assert lines[0].omega == pytest.approx(1234.567, abs=1e-4)
    assert lines[0].amplitude == pytest.approx(1e-9, rel=0.01)
    lo, hi = skirts[0]
    assert lo < 1234.567 < hi and hi - lo < 2.0  # a pure sinusoid: the taper's leakage only
    rec = record_for(clean, DT)
    near = np.abs(rec.omega - 1234.567) < 1.0
    assert rec.periodogram[near].max() < 30 * np.median(rec.periodogram)  # no line left
    kept = without(rec, skirts)
    assert len(kept.omega) == len(rec.omega) - int(np.sum((rec.omega >= lo) & (rec.omega <= hi)))


def test_a_record_without_a_line_keeps_all_its_ordinates():
    # White differenced noise: a false line has probability FALSE = 0.1 % (one seed, stated, not tuned)
    x = _noise(60_000, 5)
    clean, lines, skirts = remove_lines(x, DT)
    assert FALSE == 1e-3
    assert lines == [] and skirts == []
    assert np.array_equal(clean, x)


def test_model_Iv_line_and_its_skirt_are_taken_out():
    # model_Iv's reference: the substrate's 30 um at 3000 rad/s moves the block by 1.04 um there (1.7e8 times the
    # median ordinate), its third harmonic aliases to 9000 - 2 pi / dt = 2716.8 rad/s; the line's skirt (the
    # vibration mixed with the block's noise) spans tens of rad/s about 3000.
    p = rm.vibrating_block.VibratingBlockParams.reference()
    x = rm.vibrating_block.simulate(p, 60.0, DT, seed=0).x
    clean, lines, skirts = remove_lines(x, DT)
    assert lines[0].omega == pytest.approx(3000.0, abs=1e-3)
    assert any(abs(ln.omega - (9000.0 - 2 * math.pi / DT)) < 0.01 for ln in lines[1:])
    lo, hi = skirts[0]
    assert lo < 2990.0 and hi > 3010.0
