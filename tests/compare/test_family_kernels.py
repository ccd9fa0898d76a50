"""The families' compiled shapes (compare/analysis/family_kernels.py) against the same equations written as array
operations: the compiled loops change the cost of a fit, not what it estimates."""
import numpy as np
import pytest

from compare.analysis.families import FAMILIES


def _renewal(x):
    return 1.0 - np.cos(x) * np.sinc(x / (2.0 * np.pi)) ** 2


def _block(w, th, slope=1.0):
    r = w / th["omega_c"]
    Qc = 1.0 / (1.0 / th["Q"] - th["omega_c"] / th["omega_0"])  # the contacts' share of the resonance's damping
    spring = 1.0 - r * r / (1.0 + 1j * w / th["omega_0"])
    inertia = 1j * w / (th["omega_1"] * slope) if "omega_1" in th else 0.0
    return 1.0 / np.abs(spring * (1.0 + inertia) + 1j * r / (Qc * slope)) ** 2


def _array_form(name, th, w, v):
    """families.py's equations (module docstring) as numpy expressions."""
    if name == "model_I":
        return th["L"] * _renewal(w * th["a"] / v) * _block(w, th) / w**4
    if name == "model_Ib":
        micro = th["L2"] * _renewal(w * th["a2"] / v) / (1.0 + (w / th["omega3"]) ** 2)
        return (th["L"] * _renewal(w * th["a"] / v) + micro) * _block(w, th) / w**4
    if name == "model_ageing":
        slope = 1.0 - th["b"] / (1.0 + 1j * w * th["D_c"] / v)
        return th["L"] * _renewal(w * th["a"] / v) * _block(w, th, slope) / (np.abs(slope) ** 2 * w**4)
    return th["L"] * np.sinc(w * th["w"] / (2 * np.pi * v)) ** 2 / w**4


I_POINT = {"L": 1.1e-10, "a": 1e-3, "omega_c": 548.0, "Q": 4.0, "omega_0": 3e3, "omega_1": 2e4}  # Q_c = 15
POINTS = {
    "model_I": I_POINT,
    "model_Ib": {**I_POINT, "L2": 3e-12, "a2": 2e-6, "omega3": 4e3},
    "model_ageing": {k: v for k, v in I_POINT.items() if k != "omega_1"} | {"b": 0.33, "D_c": 1e-4},
    "model_III": {"L": 2e-9, "w": 1e-2},
}


@pytest.mark.parametrize("name", sorted(POINTS))
def test_compiled_shape_equals_the_array_form(name):
    # 1e-3 to 3e4 rad/s (below the renewal corner to ten times a 1 kHz record's Nyquist, where its aliasing images
    # are evaluated), as a 2-d array as the fit passes it. Tolerance 2e-10 relative: the two forms differ by the
    # rounding of a few operations ordered differently (1e-16 each) amplified by the renewal factor's cancellation
    # 1 - cos x sinc^2(x/2) ~ x^2 / 3 at small x (1e-16 / 1.3e-6 = 7.5e-11 at x = omega a / v = 2e-3, the lowest
    # here; measured 4.7e-11 there, 7e-16 for model III); model III is compared
    # away from its window's zeros, where a relative error of the sine's argument of 1e-16 is relative error
    # 1e-16 x / |sin x| of the value.
    v = 0.1 if name == "model_III" else 5e-4
    w = np.geomspace(1e-3, 3e4, 20_000).reshape(4, -1)
    th = POINTS[name]
    got = FAMILIES[name].shape(th, w, v)
    want = _array_form(name, th, w, v)
    assert got.shape == w.shape
    keep = np.abs(np.sin(w * th["w"] / (2 * v))) > 1e-3 if name == "model_III" else np.ones(w.shape, bool)
    assert np.max(np.abs(got / want - 1)[keep]) < 2e-10


@pytest.mark.parametrize("name", sorted(POINTS))
def test_zero_frequency_gives_inf_as_the_array_form_does(name):
    # a sub-point of the lowest ordinate's cell can fall on omega = 0 (a 300 s record's model III fit does): the
    # value is infinite (or nan), which a fit reads as an infinite likelihood, not an exception
    v = 0.1 if name == "model_III" else 5e-4
    with np.errstate(divide="ignore", invalid="ignore"):
        got = FAMILIES[name].shape(POINTS[name], np.array([0.0, 1.0]), v)
    assert not np.isfinite(got[0]) and np.isfinite(got[1])
