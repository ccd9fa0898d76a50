"""Model I on a vibrating substrate (reduced_models.vibrating_block) against model I, the closed forms of
reduced_models.vibration and its own in-band prediction."""
import math

import numpy as np
import pytest

from compare.spectra import band_average, displacement_spectrum
from reduced_models.spring_block import SpringBlockParams, theory_spectrum as model_I_spectrum
from reduced_models.vibrating_block import (
    VibratingBlockParams, averaged_law, simulate, steady_state, theory_spectrum,
)
from reduced_models.vibration import force_controlled_mean, in_band_factor

REF = SpringBlockParams.reference()
DURATION, DT_OUT, NPERSEG = 200.0, 5e-4, 2**12
EDGES = np.array([10.0, 20.0, 50.0])  # rad/s: above 10 v/a for v <= 1 mm/s, below omega_c / 10 = 55 rad/s


def _sigma(edges, duration=DURATION, dt=DT_OUT, nperseg=NPERSEG):
    """Relative standard deviation of a Welch band mean: Hann segments half overlapping, n_seg of them, each
    ordinate's estimate ~ chi^2 with 2 n_seg 0.9 degrees of freedom (overlap loss), and Hann-adjacent ordinates
    correlated, counted as 1 in 1.5 independent."""
    n_seg = (duration / dt - nperseg) / (nperseg / 2) + 1
    d_omega = 2 * np.pi / (nperseg * dt)
    n_ord = np.diff(edges) / d_omega / 1.5
    return 1.0 / np.sqrt(0.9 * n_seg * n_ord)


@pytest.fixture(scope="module")
def paired_runs():
    """The reference case unshaken and shaken at omega_v = 3000 rad/s (5.5 omega_c, 55 times the band's top) with
    A = 30 um, same seed: ~6 s of wall time."""
    out = {}
    for A in (0.0, 3e-5):
        p = VibratingBlockParams(amplitude=A)
        tr = simulate(p, DURATION, DT_OUT, seed=1)
        out[A] = (p, tr, displacement_spectrum(tr.t, tr.x, nperseg=NPERSEG), steady_state(p))
    return out


def test_validation():
    with pytest.raises(ValueError, match="amplitude"):
        VibratingBlockParams(amplitude=-1e-6)
    with pytest.raises(ValueError, match="omega_v"):
        VibratingBlockParams(omega_v=0.0)
    with pytest.raises(ValueError, match="omega_v"):
        VibratingBlockParams(omega_v=float("nan"))
    with pytest.raises(ValueError, match="steps_per_period"):
        VibratingBlockParams(steps_per_period=8)
    with pytest.raises(ValueError, match="alpha"):  # model I's own fields and checks
        VibratingBlockParams(alpha=-1.0)
    p = VibratingBlockParams(amplitude=1e-5)
    assert p.eta1 == REF.eta1 and p.to_dict()["amplitude"] == 1e-5


def test_without_vibration_it_is_model_I():
    # A = 0: the averaged law is model I's f_kin + m eta1 V (sign = +1 throughout), exactly; the mean-field steady
    # state slides at v with slope m eta1 (the discrete scheme's fixed point is exact for a constant force)
    p = VibratingBlockParams(amplitude=0.0)
    V = np.array([0.5, 1.0, 2.0]) * REF.v
    np.testing.assert_allclose(averaged_law(p, V), REF.f_kin + REF.m * REF.eta1 * V, rtol=1e-9)
    v, s = steady_state(p)
    assert v == pytest.approx(REF.v, rel=1e-9)
    assert s == pytest.approx(REF.m * REF.eta1, rel=1e-6)


def test_averaged_law_in_the_force_controlled_limit():
    # omega_v = 3000 rad/s >> k0 / (m eta1) = 30 1/s: the miniblock is dragged with the substrate and the force
    # available to it oscillates with amplitude B = A |k0 - m omega^2 + i omega m eta0|; its slip obeys
    # (m eta0 + m eta1) w + f_kin sign(w) = G + B sin, whose cycle mean is the closed form force_controlled_mean.
    # Neglected: the spring's own oscillation k0 y against B (k0 / ((m eta1) omega) = 1 %) and the miniblock's
    # inertia (m omega / (m eta1) = 1e-4): tolerance 2 % on the mean friction's Coulomb part
    for A in (2e-5, 5e-5):
        p = VibratingBlockParams(amplitude=A)
        w = p.omega_v
        B = A * abs(REF.k0 - REF.m * w**2 + 1j * w * REF.m * REF.eta0)
        c = REF.m * (REF.eta0 + REF.eta1)
        for V in (0.5 * REF.v, REF.v, 2 * REF.v):
            lo, hi = 0.0, 2.0  # G with force_controlled_mean(G) = V (increasing in G)
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if force_controlled_mean(mid, B, REF.f_kin, c) < V else (lo, mid)
            closed = 0.5 * (lo + hi) - REF.m * REF.eta0 * V  # the damper's mean share carries no friction
            coulomb = averaged_law(p, V)[0] - REF.m * REF.eta1 * V
            assert coulomb == pytest.approx(closed - REF.m * REF.eta1 * V, rel=0.02, abs=0.005 * REF.f_kin)


def test_minimum_amplitude():
    # compliance: below A_min = (G0 - f_kin) / B-per-metre the available force never falls to f_kin, the
    # contact never sticks, and nothing changes (G0 - f_kin = m eta1 v = 0.167 N; B / A ~ 1e4 N/m: A_min = 16.7 um)
    v1, s1 = steady_state(VibratingBlockParams(amplitude=1.5e-5))
    assert v1 == pytest.approx(REF.v, rel=1e-3)
    assert s1 == pytest.approx(REF.m * REF.eta1, rel=1e-3)
    v2, s2 = steady_state(VibratingBlockParams(amplitude=2.0e-5))
    assert s2 > 1.1 * REF.m * REF.eta1


def test_unshaken_run_matches_A10_per_band(paired_runs):
    # the stepped scheme at A = 0 against model I's closed form (A10); tolerance 4 sigma of the band mean plus
    # 3 % for the scheme's O(h) error (h = 33 us against the 30 1/s miniblock relaxation and 548 rad/s resonance)
    p, tr, spec, _ = paired_runs[0.0]
    ratio = band_average(spec, EDGES) / band_average(spec, EDGES, model_I_spectrum(REF, spec.omega))
    tol = 4 * _sigma(EDGES) + 0.03
    assert np.all(np.abs(ratio - 1) < tol), (ratio, tol)


def test_shaken_run_matches_its_in_band_prediction_per_band(paired_runs):
    # A = 30 um: the effective slope s1 and the new speed V (steady_state) through eq. (A10); same tolerance
    p, tr, spec, state = paired_runs[3e-5]
    ratio = band_average(spec, EDGES) / band_average(spec, EDGES, theory_spectrum(p, spec.omega, state))
    tol = 4 * _sigma(EDGES) + 0.03
    assert np.all(np.abs(ratio - 1) < tol), (ratio, tol)


def test_in_band_factor_and_speed_against_the_unshaken_twin(paired_runs):
    # the paired ratio over the whole band 10-50 rad/s against (V / v) (m eta1 / s1)^2 of eq. (A11): the two
    # levels each scatter by sigma (independent at worst), the ratio by sqrt(2) sigma; 4 of those plus 3 %
    p0, tr0, spec0, _ = paired_runs[0.0]
    p1, tr1, spec1, (V, s1) = paired_runs[3e-5]
    band = [EDGES[0], EDGES[-1]]
    measured = band_average(spec1, band)[0] / band_average(spec0, band)[0]
    predicted = float(in_band_factor(REF.v, V, REF.m * REF.eta1, s1))
    assert predicted < 0.7  # a clear change: the vibration lowers the in-band noise
    tol = 4 * math.sqrt(2) * _sigma(np.array(band))[0] + 0.03
    assert measured == pytest.approx(predicted, abs=tol * predicted)
    # the mean speed rises as the mean friction falls (constant force drive); the paired difference
    # removes the random forces' common drift (+-1 % of v over 200 s): within 10 % of the predicted rise
    v0 = np.polyfit(tr0.t, tr0.x, 1)[0]
    v1 = np.polyfit(tr1.t, tr1.x, 1)[0]
    assert v1 - v0 == pytest.approx(V - REF.v, rel=0.10)


def test_line_at_omega_v(paired_runs):
    # the block's linear response to the substrate at omega_v: the springs pass N k0 x (substrate - miniblock lag)
    # to the block; the miniblocks follow the substrate (omega_v >> k0/(m eta1)), so the block moves with amplitude
    # about N k0 A / |N k0 - M omega_v^2| (its own resonance at 548 rad/s); the line's height from a least-squares
    # sine fit, within 10 % (the Coulomb part's harmonics and the miniblocks' small lag shift it)
    p, tr, _, _ = paired_runs[3e-5]
    w = p.omega_v
    X = np.column_stack([np.sin(w * tr.t), np.cos(w * tr.t), tr.t, np.ones_like(tr.t)])
    coef = np.linalg.lstsq(X, tr.x, rcond=None)[0]
    amp = math.hypot(coef[0], coef[1])
    pred = REF.N * REF.k0 * p.amplitude / abs(REF.N * REF.k0 - REF.M * w**2)
    assert amp == pytest.approx(pred, rel=0.10)
    np.testing.assert_allclose(tr.events["substrate"], p.amplitude * np.sin(w * (tr.t + tr.metadata["warmup"])),
                               atol=1e-9 * p.amplitude + 1e-15)


def test_reference_case_is_shaken_and_compare_runs_it(tmp_path):
    # `.reference()` is the paper's case on a shaken substrate (30 um at 3000 rad/s), so `frictionnoise compare
    # model_Iv` shows the vibration's effect: the closed form's in-band level 0.544 of the unshaken one (eq. A11
    # with the mean-field slope; the value docs/results/vibration.md quotes a measurement against), and the
    # simulated run against its closed form within the report's factor 1.25 (measured 0.935-1.078, 200 s)
    import json
    from dataclasses import replace

    from compare.cli import main

    r = VibratingBlockParams.reference()
    assert (r.amplitude, r.omega_v) == (30e-6, 3000.0)
    w = np.array([10.0, 20.0, 50.0])
    np.testing.assert_allclose(theory_spectrum(r, w) / theory_spectrum(replace(r, amplitude=0.0), w), 0.544, rtol=2e-3)
    assert main(["compare", "model_Iv", "-o", str(tmp_path / "c")]) == 0
    m = json.loads((tmp_path / "c" / "summary.json").read_text())["models"]["model_Iv"]
    assert m["params"]["amplitude"] == 30e-6
    assert "<title>frictionnoise compare: model_Iv</title>" in (tmp_path / "c" / "index.html").read_text()
    assert all(0.8 < b["ratio"] < 1.25 for b in m["band_ratios_vs_closed_form"]), m["band_ratios_vs_closed_form"]
