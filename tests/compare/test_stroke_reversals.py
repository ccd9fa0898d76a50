"""Strokes from the velocity's reversals, with hysteresis: a friction-damper record whose amplitude ramps up and
down is cut at every reversal, no stroke holds one, and the partial strokes dropped are counted."""
from types import SimpleNamespace

import numpy as np
import pytest

from compare.analysis.strokes import _position_boundaries, find_strokes


def _ramped(seed, noise=1e-4, phase=0.3):
    """Position of a shaker whose amplitude ramps 0.2 -> 1 -> 0.2 mm over 7 periods of 20 s (100 Hz): 14
    reversals, at the extremes of the sine."""
    t = 0.01 * np.arange(14000)
    amp = np.interp(t, [0, 70, 140], [0.2, 1.0, 0.2])
    x = amp * np.sin(2 * np.pi * 0.05 * t + phase) + noise * np.random.default_rng(seed).standard_normal(t.size)
    return t, x


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_ramped_amplitude_gives_a_stroke_per_reversal_none_holding_one(seed):
    t, x = _ramped(seed)
    turns = _position_boundaries(x)[1:-1]
    # the reversals of the noiseless motion: where its velocity changes sign
    v0 = np.gradient(_ramped(seed, noise=0.0)[1])
    true = np.flatnonzero(np.sign(v0[1:]) != np.sign(v0[:-1])) + 1
    assert len(turns) == len(true) == 14
    # each found within 0.3 s of the true one (the noise moves the sampled extreme of a flat top: at the
    # smallest amplitude, 0.2 mm, a noise of 0.1 um shifts it by about 0.1 s)
    assert np.max(np.abs(turns - true)) * 0.01 < 0.3
    d = SimpleNamespace(t=t, x=x, F=np.sign(v0), direction=None, segmented=False)
    s = find_strokes(d)
    assert 13 <= len(s.segments) <= 15 and s.found == 15
    assert len(s.dropped) == s.found - len(s.segments) == 2  # the two partial ends, counted
    for a, b in s.segments:
        assert not np.any((true > a) & (true < b - 1)), (a, b)  # no reversal inside a used stroke
