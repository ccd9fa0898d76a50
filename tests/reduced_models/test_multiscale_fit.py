"""Model Ib's parameter-measuring procedures (reduced_models/multiscale_fit.py, compare/studies/scene_multiscale.py)
on exact cases: model Ib simulations and closed-form spectra whose parameters are known."""
import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from reduced_models import multiscale as ms
from reduced_models import spring_block as m1
from reduced_models.multiscale_fit import (RenewalLevel, fit_renewal_levels, renewal_force_spectrum, renewal_statistics,
                                           rigid_micro_params)

REF = ms.MultiscaleParams.reference()


def _tolerances(n1):
    """3 sigma bounds from the renewals per contact n1 = v T / a2 (the sum of K independent contacts is a process with
    one contact's correlation, so K does not shorten it). alpha: Var of a variance estimate of a Gaussian process,
    2 x (two-sided correlation time 7 tau0 / 6) / T, so sd(alpha)/alpha <= 0.5 sqrt(2.33 / n1) = 0.76 / sqrt(n1);
    a: an integrated autocorrelation over a window M of N samples has relative variance 2 (2M + 1) / N (Madras &
    Sokal), with the window M = 2 a the procedure integrates over: sd(a)/a <= sqrt(8 / n1). Both bounds are
    conservative (measured scatter over 6 seeds of 300 s: 0.35 % for alpha2, 1.6 % for a2, against 0.63 % and 2.3 %)."""
    return 3 * 0.76 / math.sqrt(n1), 3 * math.sqrt(8.0 / n1)


@pytest.mark.parametrize("dt_out", [1e-3, 4e-3])
def test_micro_level_given_back_from_a_model_Ib_run(dt_out):
    # 300 s of the reference case: 15,000 renewals per micro contact, 4.5 M in all. The trace holds the micro
    # force sum averaged over each output interval (tau2 = a2 / v = 20 ms, so dt_out / tau2 = 0.05 and 0.2):
    # the procedure corrects that to first order (residual O((dt/tau2)^2) < 0.4 %).
    T = 300.0
    tr = ms.simulate(REF, T, dt_out, seed=3)
    K = REF.N * REF.n_micro
    n1 = REF.v * T / REF.a2
    tol_alpha, tol_a = _tolerances(n1)  # 1.9 % and 6.9 %
    lv = renewal_statistics(tr.x, tr.events["force_micro"], K, offset=REF.F_kin2, averaged_dt=dt_out)
    assert lv.f_kin == pytest.approx(REF.f_kin2, rel=1e-3)  # the mean is the given offset (a model trace has none)
    assert lv.alpha == pytest.approx(REF.alpha2, rel=tol_alpha)
    assert lv.a == pytest.approx(REF.a2, rel=tol_a)
    assert lv.n_renewals == pytest.approx(K * n1, rel=0.1)
    if dt_out == 4e-3:
        # the correction is needed: without it alpha2 reads 1 - 0.2/6 = 3.3 % low, outside the tolerance
        raw = renewal_statistics(tr.x, tr.events["force_micro"], K, offset=REF.F_kin2)
        assert abs(raw.alpha / REF.alpha2 - 1) > tol_alpha


@pytest.mark.slow
def test_macro_level_given_back_from_a_model_Ib_run():
    # the same procedure on the macro sum F1 = force - force_micro (N = 30 contacts, a = 1 mm): 900 s gives only
    # 450 renewals per contact, so the bounds are 3.6 % (alpha) and 40 % (a).
    T = 900.0
    tr = ms.simulate(REF, T, 1e-3, seed=5)
    n1 = REF.v * T / REF.a
    tol_alpha, tol_a = _tolerances(n1)
    lv = renewal_statistics(tr.x, tr.force - tr.events["force_micro"], REF.N, offset=REF.F_kin, averaged_dt=1e-3)
    assert lv.alpha == pytest.approx(REF.alpha, rel=tol_alpha)
    assert lv.a == pytest.approx(REF.a, rel=tol_a)


def test_two_level_spectral_fit_on_its_closed_form():
    # Noise-free input: the band means of two renewal spectra (A8); the fit must return the four numbers to the
    # optimizer's tolerance (1e-4), from a start 2-30x away.
    v = 5e-3
    w = np.geomspace(1.0, 3000.0, 20000)
    slow, fast = (4e-4, 0.035), (9e-6, 0.011)
    C = renewal_force_spectrum(w, v, *slow) + renewal_force_spectrum(w, v, *fast)
    (s, f), res = fit_renewal_levels(w, C, v, np.geomspace(4.0, 1500.0, 31), levels=2, guess=(2e-4, 0.05))
    assert res < 1e-6
    for got, want in ((s, slow), (f, fast)):
        assert got.a == pytest.approx(want[0], rel=1e-4) and got.amplitude == pytest.approx(want[1], rel=1e-4)
    (one,), res1 = fit_renewal_levels(w, renewal_force_spectrum(w, v, *slow), v, np.geomspace(4.0, 1500.0, 31), levels=1,
                                      guess=(1e-3, 0.01))
    assert one.a == pytest.approx(slow[0], rel=1e-4) and one.amplitude == pytest.approx(slow[1], rel=1e-4)


def test_rigid_micro_contact_passes_the_fast_force_unfiltered():
    # model Ib with one stiff micro contact per pad must be model I driven by the sum of the two force spectra:
    # C_x = |Z|^2 (C_f1 + C_f2) / N with model I's Z, to O(m2 omega^2 / k2) = 1e-4 at 3000 rad/s.
    base = replace(m1.SpringBlockParams.reference(), k1=0.0)
    slow = RenewalLevel(f_kin=math.nan, a=1e-3, amplitude=0.1)
    fast = RenewalLevel(f_kin=math.nan, a=2e-5, amplitude=0.03)
    pb = rigid_micro_params(base, slow, fast)
    assert pb.alpha * pb.f_kin == pytest.approx(0.1) and pb.alpha2 * pb.f_kin2 == pytest.approx(0.03)
    assert pb.m * pb.eta1 == pytest.approx(base.m * base.eta1)  # the friction slope stays model I's
    w = np.geomspace(0.5, 3000.0, 200)
    Z = ms.transfer_functions(ms.MultiscaleParams(N=base.N, v=base.v, a=base.a, k0=base.k0, k1=0.0, M=base.M, m=base.m,
                                                  eta0=base.eta0, eta1=base.eta1, alpha=base.alpha, F_drive=base.F_drive,
                                                  F_kin=base.F_kin, n_micro=0, F_kin2=0.0), w)[0]
    want = np.abs(Z) ** 2 * (renewal_force_spectrum(w, base.v, 1e-3, 0.1) + renewal_force_spectrum(w, base.v, 2e-5, 0.03)) / base.N
    np.testing.assert_allclose(ms.theory_spectrum(pb, w), want, rtol=2e-3)


def _fake_scene_trace(p, T=300.0, dt=1e-3, seed=7, columns="pads"):
    """An engine-like trace from a model Ib run: the block's x; pad forces f_kin + F1 / sqrt(N) in every column (one
    contact's mean, variance and correlation, which is all model I's extraction reads; the columns are not
    independent, which it does not see); micro-pad forces summed per pad (F2 / N each, plus the mean: their sum is
    the micro force sum) or as one column; and the metadata a pads_multiscale scene carries."""
    tr = ms.simulate(p, T, dt, seed=seed)
    n = len(tr.t)
    F1, F2 = tr.force - tr.events["force_micro"], tr.events["force_micro"]
    micro = np.repeat(((F2 + p.F_kin2) / p.N)[:, None], p.N, axis=1) if columns == "pads" else (F2 + p.F_kin2)
    law = {"law": "linear", "c": p.m * p.eta1, "b": 0.0, "v_c": 1.0, "load_per_pad": 1.0}
    law2 = {"law": "linear", "c": p.m2 * p.eta3, "b": 0.0, "v_c": 1.0, "load_per_pad": 0.1}
    scene = {"pads": {"N": p.N, "mass": p.m, "k0": p.k0, "c0": p.m * p.eta0, "foot_length": 0.0}, "friction_law": law,
             "length_scale": p.a, "effective_mass": p.M, "block_mass": p.M, "substrate": {"alpha": p.alpha},
             "micro": {"n": p.n_micro, "mass": p.m2, "k": p.k2, "c": p.m2 * p.eta2, "length_scale": p.a2,
                       "friction_law": law2, "patch_contrast": p.alpha2}}
    return SimpleNamespace(t=tr.t, x=tr.x, pad_force=np.repeat((p.f_kin + F1 / np.sqrt(p.N))[:, None], p.N, axis=1),
                           micro_force=micro, n_contact=np.full(n, p.N), F_n=np.full(n, p.N * 1.0),
                           F_drag=np.full(n, p.N * p.m * p.eta1 * p.v), metadata={"scene": scene})


@pytest.mark.slow  # fast tier under a minute: run in CI's slow tier (the estimator itself has fast tests above)
@pytest.mark.parametrize("columns", ["pads", "sum"])
def test_multiscale_params_from_a_trace(columns):
    # The builder on an engine-like trace made from a model Ib run with known parameters: the layout comes back
    # exactly from the metadata, f_kin2 from the recorded mean, alpha2 and a2 (measured) within the statistical
    # bounds above, and the MultiscaleParams it builds slides steadily with the measured speed.
    from compare.report.studies.scene_multiscale import multiscale_parameters, multiscale_params

    p = REF
    tr = _fake_scene_trace(p, columns=columns)
    ex = multiscale_parameters(tr)
    tol_alpha, tol_a = _tolerances(p.v * 300.0 / p.a2)
    for k in ("m2", "k2", "eta2", "eta3", "a2"):
        assert ex[k]["value"] == pytest.approx(getattr(p, k), rel=1e-9), k
    assert ex["n_micro"]["value"] == p.n_micro
    assert ex["f_kin2"]["value"] == pytest.approx(p.f_kin2, rel=1e-3)
    # the trace's forces are interval averages here (dt_out / tau2 = 0.05), which the builder does not undo (an
    # engine records samples): alpha2 reads up to 1 - 0.05/6 = 0.8 % low, added to the tolerance
    assert ex["alpha2"]["value"] == pytest.approx(p.alpha2, rel=tol_alpha + 0.009)
    assert ex["a2"]["measured"] == pytest.approx(p.a2, rel=tol_a + 0.02)
    pb = multiscale_params(ex)
    assert pb.n_micro == p.n_micro and pb.eta1 == pytest.approx(p.eta1, rel=1e-9)
    assert pb.v == pytest.approx(p.v, rel=0.02)


def test_builder_names_what_is_missing():
    from compare.report.studies.scene_multiscale import multiscale_parameters

    tr = _fake_scene_trace(REF, T=2.0)
    del tr.metadata["scene"]["micro"]
    with pytest.raises(ValueError, match="micro"):
        multiscale_parameters(tr)
    tr = _fake_scene_trace(REF, T=2.0)
    del tr.micro_force
    with pytest.raises(ValueError, match="micro_force"):
        multiscale_parameters(tr)


def test_study_skips_with_a_reason_when_the_scene_is_not_shipped(monkeypatch):
    # an install whose scenarios lack pads_multiscale (the study reads the list when it runs)
    import engine_sim

    from compare.report.studies import scene_multiscale

    shipped = engine_sim.shipped_scenarios()
    monkeypatch.setattr(engine_sim, "shipped_scenarios",
                        lambda: {k: v for k, v in shipped.items() if k != scene_multiscale.NAME})
    res = scene_multiscale.run(True, 0)
    assert "not shipped" in res.numbers["skipped"] and "Skipped" in res.html and res.figures == ()


def test_averaged_record_block_means():
    # every k-th time and position; pad forces, contact counts and drag averaged over each k steps (exact means)
    from compare.report.studies.scene_rough_multiscale import averaged_record

    n, k = 103, 10
    t = np.arange(n) * 1e-4
    f = np.stack([np.arange(n, dtype=float), 2.0 * np.arange(n)], axis=1)
    tr = SimpleNamespace(t=t, x=5e-3 * t, pad_force=f, n_contact=np.full(n, 2.0), F_n=np.ones(n), F_drag=t.copy(),
                         metadata={})
    a = averaged_record(tr, k)
    assert len(a.t) == 10 and np.array_equal(a.t, t[:100:10]) and np.array_equal(a.x, tr.x[:100:10])
    np.testing.assert_allclose(a.pad_force[:, 0], np.arange(10) * 10 + 4.5, rtol=0, atol=1e-12)
    np.testing.assert_allclose(a.pad_force[:, 1], 2 * (np.arange(10) * 10 + 4.5), rtol=0, atol=1e-12)


@pytest.mark.slow
@pytest.mark.extended  # two 600 s model Ib runs (about 2 min of CPU); CI runs the same study part on the
# pads_multiscale scene in the installed quick report (tests/compare/test_report_cli.py) and on 2 s traces above
@pytest.mark.parametrize("case", ["reference", "strong"])
def test_study_part_reads_model_Ib_built_from_its_own_run(case):
    # End to end: a "scene" that is model Ib itself (600 s), measured by the builder, compared by the study part.
    # Per band the closed form with the measured parameters must read the run within a factor 1.7: the macro
    # estimates rest on n1 = v T / a = 300 renewals per contact, so sd(a)/a <= sqrt(8/300) = 16 % and
    # sd(alpha^2)/alpha^2 <= 2 x 0.76 / sqrt(300) = 9 % (bounds above); C_x ~ (alpha f_kin)^2 / a in the omega^-4
    # band gives ~19 % sd, 3 sigma ~ exp(0.55) = 1.7. Measured (seeds 7, 8): 0.92-1.30. Gamma per regime against
    # the model's closed-form slope over the same band within 1.5 x the fit's 95 % half-width (measured within 1x).
    from compare.report.studies.multiscale import strong_cases
    from compare.report.studies.scene_multiscale import scene_against_model_Ib

    p = REF if case == "reference" else strong_cases()["R = 1000, v/a2 = 500 rad/s"]
    res = scene_against_model_Ib("model Ib run", None, False, 0, trace=_fake_scene_trace(p, T=600.0, seed=0))
    r = np.array([b["ratio"] for b in res.numbers["band_ratios_vs_model_Ib"]])
    assert np.all((r > 1 / 1.7) & (r < 1.7)), r
    fits = res.numbers["fits"]
    assert len(fits) == (1 if case == "reference" else 3)  # the strong case has a crossover: both regimes fitted
    for name, f in fits.items():
        assert f["gamma"] == pytest.approx(f["gamma_model_Ib"], abs=1.5 * f["gamma_err"]), (name, f)
    assert len(res.figures) == 1 and res.figures[0].png[:4] == b"\x89PNG"
