"""The multiscale scene (pad arrangement "micro", scenario pads_multiscale): its loads and the scale
separations model Ib assumes, the validation of its micro fields, a bitwise resume from checkpoints, and its
spectra against model Ib."""
import math

import numpy as np
import pytest

import engine_sim
from compare.analysis.spectra import band_average, displacement_spectrum
from engine_sim import Scene, load_scenario, scenario_from_dict
from engine_sim.scenario import ScenarioError
from engine_sim.scene import describe
from reduced_models import multiscale as ms

MS = "pads_multiscale"


def _short(sc, duration, warmup=0.1):
    return sc.with_run(duration=duration, warmup=warmup)


def test_scene_builds_with_its_micro_pads_loads_and_orderings():
    sc = load_scenario(MS)
    p, arr = sc.pads, sc.arrangement_part
    scene = Scene(sc)
    n_sl = p.N * (1 + p.n_micro)
    assert len(scene.pads) == p.N and len(scene.sliders) == n_sl
    assert len(scene.space.bodies) == 2 + n_sl  # block, sliding bodies and the force drive's kinematic anchor
    # loads: the column carries the block's share and its own weight; N1 + n N2 is all of it (exact up to rounding)
    L = sc.block.M * 9.81 / p.N + (p.mass + p.n_micro * p.micro_mass) * 9.81
    assert sc.normal_load_per_pad == pytest.approx(L, rel=1e-12)
    assert arr.pad_load() + p.n_micro * arr.micro_load() == pytest.approx(L, rel=1e-12)
    assert arr.micro_load() == pytest.approx(p.micro_share * L / p.n_micro, rel=1e-12)
    # the default drive force slides a column at v: N (mu0 L + (c + n micro_c) v)
    v = sc.drive.v
    assert sc.drive_force == pytest.approx(p.N * (sc.friction.mu0 * L + (sc.friction.c + p.n_micro * p.micro_c) * v),
                                           rel=1e-12)
    assert sc.steady_velocity == pytest.approx(v, rel=1e-9)
    # the scale separations model Ib assumes, which the scene must keep
    w2 = math.sqrt(p.micro_k / p.micro_mass)
    assert w2 > 10 * 30 * v / sc.substrate.a  # micro resonance well above the fit band's top, 30 v/a
    assert w2 > 2 * math.pi * v / p.micro_a
    assert p.micro_a < sc.substrate.a  # micro renewal rate v/a2 above the macro one v/a
    assert sc.friction.mu0 * arr.micro_load() / p.micro_k < 0.2 * p.micro_a  # deflection well below a2
    assert sc.run.dt * math.sqrt((p.micro_k + p.micro_k_normal) / p.micro_mass) < 0.3  # pad-spring stability limit
    # what model Ib's comparison reads from a trace, and nothing for the other scenes
    micro = describe(sc)["micro"]
    assert set(micro) == {"n", "mass", "k", "c", "length_scale", "friction_law", "patch_contrast"}
    assert (micro["n"], micro["mass"], micro["k"], micro["c"], micro["length_scale"], micro["patch_contrast"]) == (
        p.n_micro, p.micro_mass, p.micro_k, p.micro_c_spring, p.micro_a, p.micro_alpha)
    assert set(micro["friction_law"]) == set(describe(sc)["friction_law"])
    assert micro["friction_law"]["c"] == p.micro_c and micro["friction_law"]["load_per_pad"] == arr.micro_load()
    assert "micro" not in describe(load_scenario("pads_friction_patches"))


def test_micro_fields_are_validated_one_line_naming_the_field():
    d = load_scenario(MS).to_dict()
    for key, val, msg in (("micro_share", 1.0, r"pads.micro_share must be < 1 \(got 1.0\): the pad keeps"),
                          ("micro_spacing", 3e-3, "pads.micro_spacing"),
                          ("micro_k", 1e4, "exceeds the pad spring limit"),
                          ("micro_mass", -1.0, "pads.micro_mass must be > 0")):
        bad = {**d, "pads": {**d["pads"], key: val}}
        with pytest.raises(ScenarioError, match=msg) as e:
            scenario_from_dict(bad)
        assert "\n" not in str(e.value)
    with pytest.raises(ScenarioError, match="unknown key pads.n_micro"):  # micro fields belong to the micro pads
        scenario_from_dict({"pads": {"n_micro": 2}})


def test_scene_and_model_Ib_check_the_micro_fields_alike():
    """One helper (frictionnoise.base.check_number) checks a micro-pad field in the scenario and its model Ib twin: the same
    bad value gives the same message after the field's name."""
    from dataclasses import replace

    from reduced_models.multiscale import MultiscaleParams

    d = load_scenario(MS).to_dict()
    ref = MultiscaleParams.reference()
    pairs = (("micro_mass", "m2"), ("micro_k", "k2"), ("micro_a", "a2"), ("micro_alpha", "alpha2"),
             ("micro_c_spring", "eta2"), ("n_micro", "n_micro"))
    checked = 0
    for scene_key, model_field in pairs:
        for val in (-1.0, float("nan"), 2.5, "x"):
            if (val == 2.5) != (scene_key == "n_micro") and val in (-1.0, 2.5):  # the scene needs a micro-pad (n >= 1),
                continue  # model Ib's n = 0 is model I: -1 is refused by different rules
            with pytest.raises(ScenarioError) as e_scene:
                scenario_from_dict({**d, "pads": {**d["pads"], scene_key: val}})
            with pytest.raises(ValueError) as e_model:
                replace(ref, **{model_field: val})
            tail = str(e_model.value).removeprefix(model_field)
            assert str(e_model.value).startswith(model_field + " must be ") and str(e_scene.value).endswith(
                f"pads.{scene_key}{tail}"), (str(e_scene.value), str(e_model.value))
            checked += 1
    assert checked == 5 * 3 + 3


@pytest.mark.slow  # fast tier under a minute; the log-law scene's resume test stays fast
def test_run_through_checkpoints_and_resume_is_bitwise_the_uninterrupted_run(tmp_path):
    # as tests/engine_sim/test_checkpoint.py does for the patches: every run passes through the same round trips (epochs of
    # 0.1 s here), so a checkpoint file and a resume from it change no bit
    sc = _short(load_scenario(MS), duration=0.25, warmup=0.05)
    ref = engine_sim.run(sc, seed=2, epoch=0.1)
    ck = tmp_path / "ck.pkl"
    got = engine_sim.run(sc, seed=2, epoch=0.1, checkpoint=ck, checkpoint_every=0.2)
    again = engine_sim.run(sc, seed=2, epoch=0.1, checkpoint=ck, checkpoint_every=0.2)  # resumes at 0.2 s
    assert again.metadata["resumed_from_checkpoint"]
    for f in ("t", "x", "v", "F_t", "F_n", "F_drag", "pad_force", "work_drive", "dissipated", "mech_energy"):
        assert np.array_equal(getattr(got, f), getattr(ref, f)), f
        assert np.array_equal(getattr(again, f), getattr(ref, f)), f
    assert ref.metadata["scene"]["micro"]["n"] == sc.pads.n_micro


def model_Ib_of(sc):
    """Model Ib built from a scene's parameters (model I's mapping, test_engine.model_I_of, plus the micro level:
    m2 = micro_mass, k2 = micro_k, m2 eta2 = micro_c_spring, m2 eta3 = micro_c, f_kin2 = mu0 N2, a2, alpha2); the
    pads' own contact carries N1. Without micro-pads: model I (n = 0)."""
    p, arr, mu0 = sc.pads, sc.arrangement_part, sc.friction.mu0
    kw = dict(N=p.N, v=sc.steady_velocity, a=sc.substrate.a, k0=p.k0, k1=p.k1, M=sc.block.M, m=p.mass,
              eta0=p.c0 / p.mass, alpha=sc.substrate.alpha, F_drive=sc.drive_force, F_kin=p.N * mu0 * arr.pad_load())
    if p.arrangement == "micro":
        kw.update(n_micro=p.n_micro, m2=p.micro_mass, k2=p.micro_k, eta2=p.micro_c_spring / p.micro_mass,
                  eta3=p.micro_c / p.micro_mass, a2=p.micro_a, alpha2=p.micro_alpha,
                  F_kin2=p.N * p.n_micro * mu0 * arr.micro_load())
    else:
        kw.update(n_micro=0, F_kin2=0.0)
    return ms.MultiscaleParams(**kw)


@pytest.mark.slow  # two 8 s scenes (~90 s wall)
def test_micro_level_raises_the_top_bands_as_model_Ib_predicts():
    # Same seed, drive, column friction law and macro pads: the scenes differ by the micro level. Model Ib built
    # from each scene's parameters predicts C_x(multiscale) / C_x(patches) of 2-10 between the fit band's top
    # 30 v/a = 150 rad/s and one third of the output Nyquist (1047 rad/s), and below 1 under v/a. The scene must
    # move the same way: above 1 in every top band, below 1 in the low bands. Measured (seed 5): 6.1, 8.6, 6.2, 4.3
    # against model Ib's 7.9, 9.8, 7.0, 4.6 over 150-1047 rad/s (0.77-0.94 of the prediction); 0.08, 0.10 against
    # 0.10, 0.10 over 4-12 rad/s. Only the direction is asserted: the magnitude is model Ib's to be tested by the
    # comparison study with the scene's measured parameters.
    ms_sc, pf_sc = (_short(load_scenario(n), duration=8.0, warmup=0.5) for n in (MS, "pads_friction_patches"))
    spec = {n: displacement_spectrum(tr.t, tr.x, nperseg=2**11) for n, tr in
            ((n, engine_sim.run(sc, seed=5)) for n, sc in (("ms", ms_sc), ("pf", pf_sc)))}
    top = np.geomspace(150.0, 1047.0, 5)
    low = np.geomspace(4.0, 12.0, 3)
    for edges, rises in ((top, True), (low, False)):
        meas = band_average(spec["ms"], edges) / band_average(spec["pf"], edges)
        pred = (band_average(spec["ms"], edges, ms.theory_spectrum(model_Ib_of(ms_sc), spec["ms"].omega))
                / band_average(spec["pf"], edges, ms.theory_spectrum(model_Ib_of(pf_sc), spec["pf"].omega)))
        print("bands", np.round(edges), "measured", np.round(meas, 2), "model Ib", np.round(pred, 2))
        assert np.all(pred > 1) if rises else np.all(pred < 1), pred  # what the model says, for these scenes
        assert np.all(meas > 1) if rises else np.all(meas < 1), (meas, pred)


@pytest.mark.slow  # a 4 s run and its analysis (~15 s)
def test_compare_puts_model_Ib_beside_model_I_for_micro_pads():
    # `frictionnoise compare` on a scene with micro-pads builds model Ib from the same trace, as the report does
    # (a new user found compare offering model I only, 4-38x off). Measured on a 4 s run: model Ib 0.81-1.20 per
    # band; bound 1.5 as for model I on the patch scenes
    import numpy as np

    from compare.report.build import build_scene_report
    from engine_sim import load_scenario, shipped_scenarios

    sc = load_scenario(shipped_scenarios()["pads_multiscale"])
    results, summary = build_scene_report(sc, duration=4.0, seed=0)
    r = np.array([b["ratio"] for b in summary["scenarios"]["pads_multiscale_model_Ib"]["band_ratios_vs_model_Ib"]])
    assert len(r) >= 5 and np.all(np.abs(np.log(r)) < np.log(1.5)), r
