"""Families fitted to records of the exact simulators, and the ranking of the mechanisms."""
import dataclasses
import math

import numpy as np
import pytest

import reduced_models as rm
from compare.analysis.families import FAMILIES
from compare.analysis.family_fit import Grouped, fit_family, record_for, sampled_spectrum
from compare.analysis.identify import holm, identify, stationarity, vuong

DT = 1e-3
FLOOR = 1e-24  # m^2 s: a sensor's white noise of rms sqrt(2 pi FLOOR / DT) = 79 pm


def record(model, params, duration, seed):
    tr = rm.MODELS[model].simulate(params, duration, DT, seed=seed)
    noise = np.random.default_rng(seed + 1000).normal(0.0, math.sqrt(2 * math.pi * FLOOR / DT), len(tr.x))
    return tr.x + noise


@pytest.fixture(scope="module")
def model_I_record():
    return record("model_I", rm.spring_block.SpringBlockParams.reference(), 60.0, 11)


def test_model_I_fit_recovers_the_parameters_it_was_built_with(model_I_record):
    p = rm.spring_block.SpringBlockParams.reference()
    fam = FAMILIES["model_I"]
    truth, v = fam.from_model(p)
    fit = fit_family(record_for(model_I_record, DT), fam, v)
    # each identified parameter within two 95 % half-widths of its truth (a miss has probability < 1e-4 if the
    # interval is right; the coverage itself is the confusion study's to measure)
    for name in ("L", "a", "omega_c", "Q"):
        lo, hi = fit.intervals[name]
        width = math.log10(hi / lo) / 2
        assert abs(math.log10(fit.theta[name] / truth[name])) < 2 * width, name
    assert fit.floor == pytest.approx(FLOOR, rel=0.1)  # 3e4 ordinates under the floor: ~1 % scatter
    assert fit.intervals["omega_0"] is None  # the contact springs' damping corner shows 0.4 % at the peak only


def test_grouped_likelihood_is_the_whittle_sum_for_a_flat_mean(model_I_record):
    rec = record_for(model_I_record, DT)
    G = Grouped(rec)
    mu = 3e-3  # a model whose twice-differenced mean is flat: every group's mean equals each ordinate's
    flat = lambda w, q: np.full(np.shape(w), q[0]) / (np.abs(2 * np.sin(w * DT / 2) / DT) ** 4)
    direct = float(np.sum(np.log(mu) + rec.periodogram / mu))
    assert G.negloglik(flat, [mu]) == pytest.approx(direct, rel=1e-9)
    assert -np.sum(G.ordinate_loglik(flat, [mu])) == pytest.approx(direct, rel=1e-9)
    assert G.count.sum() == len(rec.omega)


def test_model_I_record_is_named_model_I(model_I_record):
    ranking = identify(x=model_I_record, dt=DT, v=5e-4)
    assert ranking[0].model == "model_I" and ranking[0].verdict == "fits"
    verdicts = {m.model: m.verdict for m in ranking}
    assert verdicts["model_II"] == verdicts["model_III"] == "rejected"
    assert verdicts["model_Iv"] == "indistinguishable"  # model I's family plus a line: one family on this band
    assert "line" in next(m.separate for m in ranking if m.model == "model_Iv")
    assert all(m.parameters["L"][2] == "m^2 s^-3" for m in ranking if m.model == "model_I")


def test_model_II_record_is_named_model_II():
    # 120 s: at 60 s the ageing family, its step near 200 rad/s and its resonance overdamped, follows model II's
    # omega^-(7 - s) range closely enough that Vuong's test leaves it indistinguishable (p = 0.09 at seed 12)
    p = rm.wear_particle.WearParticleParams()
    ranking = identify(x=record("model_II", p, 120.0, 12), dt=DT, v=p.v)
    assert ranking[0].model == "model_II" and ranking[0].verdict == "fits"
    assert {m.model: m.verdict for m in ranking}["model_I"] == "rejected"


def test_a_record_not_stationary_gets_no_mechanism(model_I_record):
    assert identify(x=model_I_record, dt=DT, v=5e-4, stationary=False) == []


def test_stationarity_flags_a_record_whose_level_jumps(model_I_record):
    # the model I record is stationary; doubling its fluctuation about the slide in the second half quadruples the
    # spectrum there, which every band sees
    assert stationarity(model_I_record, DT)["stationary"]
    t = np.arange(len(model_I_record)) * DT
    zeta = model_I_record - 5e-4 * t
    jumped = 5e-4 * t + np.where(t < t[-1] / 2, zeta, 2 * zeta)
    assert not stationarity(jumped, DT)["stationary"]
    assert identify(x=jumped, dt=DT, v=5e-4) == []


def test_holm_adjusts_as_the_step_down_method():
    # p = (0.01, 0.04, 0.03) over m = 3: sorted 0.01 x 3, 0.03 x 2, 0.04 x 1, running maximum
    np.testing.assert_allclose(holm([0.01, 0.04, 0.03]), [0.03, 0.06, 0.06])
    assert holm([0.5, 0.9])[1] == 1.0


def test_vuong_of_coinciding_models_is_one_and_of_a_clear_lead_small():
    rng = np.random.default_rng(0)
    a = rng.normal(size=1000)
    assert vuong(a, a) == (0.0, 1.0)
    z, p = vuong(a + 0.1, a + rng.normal(0, 0.1, 1000))
    assert z > 5 and p < 1e-6


def test_identify_rejects_an_unknown_model_and_a_bad_speed(model_I_record):
    with pytest.raises(ValueError, match="model_X"):
        identify(x=model_I_record, dt=DT, v=5e-4, models=["model_X"])
    with pytest.raises(ValueError, match="speed"):
        identify(x=model_I_record, dt=DT, v=-1.0)


def test_analyze_prints_the_ranking_first_and_writes_mechanisms(tmp_path, capsys):
    import json

    from compare.cli.main import main

    out = tmp_path / "out"
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "-o", str(out)]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].startswith("mechanisms (best first")
    assert printed[1].split()[0] == "model_I"  # the file is model I's reference case (scenarios/data/README.md)
    s = json.loads((out / "summary.json").read_text())
    best = s["mechanisms"][0]
    assert best["model"] == "model_I" and best["verdict"] in ("fits", "indistinguishable")
    assert set(best) >= {"model", "verdict", "p_value", "parameters", "separate"}
    value, half, unit = best["parameters"]["a"]
    assert unit == "m" and abs(value - 1e-3) < 2 * half  # built with a = 1 mm
    assert best["parameters"]["omega_c"] == "not identified"  # 548 rad/s lies above the 100 Hz file's Nyquist


def test_analyze_without_the_ranking_fits_no_family(tmp_path, capsys, monkeypatch):
    # --no-mechanisms: the exponent, floor and spectra as without it, no family fitted, no ranking printed or shown
    import json

    import compare.analysis.identify as identify_module
    from compare.cli.main import main

    def refused(*a, **k):
        raise AssertionError("identify called under --no-mechanisms")

    monkeypatch.setattr(identify_module, "identify", refused)
    out = tmp_path / "out"
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "--no-mechanisms", "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "mechanism" not in printed and "gamma = " in printed
    s = json.loads((out / "summary.json").read_text())
    assert s["mechanisms"] == [] and s["mechanisms_note"] == "not asked (--no-mechanisms)" and s["gamma"] > 0
    assert "Mechanisms: which model explains the record" not in (out / "index.html").read_text()
    f = tmp_path / "force.csv"
    f.write_text("t,F\n" + "\n".join(f"{i * 1e-3},{1 + 1e-3 * (i % 7)}" for i in range(5000)) + "\n")
    assert main(["analyze", str(f), "--force-col", "F", "--no-mechanisms", "-o", str(tmp_path / "o2")]) == 2
    assert "--no-mechanisms applies to displacement data" in capsys.readouterr().err


def test_fn_identify_takes_a_trace():
    import frictionnoise as fn

    p = fn.WearParticleParams()
    tr = fn.simulate(p, 30.0, seed=3)
    ranking = fn.identify(tr, v=p.v)
    assert isinstance(ranking[0], fn.Mechanism) and ranking[0].model == "model_II"


def test_the_explanation_page_example():
    # docs/explanation/identification.md: model I's reference case, 60 s at 1 kHz, seed 1, no floor
    import frictionnoise as fn

    p = fn.SpringBlockParams.reference()
    ranking = fn.identify(fn.simulate(p, 60.0, seed=1), v=p.v)
    verdicts = {m.model: m.verdict for m in ranking}
    assert ranking[0].model == "model_I" and verdicts["model_I"] == "fits"
    assert verdicts["model_II"] == verdicts["model_III"] == "rejected"
    assert verdicts["model_Iv"] == verdicts["model_ageing"] == verdicts["model_Ib"] == "indistinguishable"
    # "they coincide with model I on this band" (the page)
    assert all(m.coincides_with == "model_I" for m in ranking if m.model in ("model_Iv", "model_ageing", "model_Ib"))
    truth, _ = FAMILIES["model_I"].from_model(p)
    value, half, _ = ranking[0].parameters["L"]
    assert abs(value - truth["L"]) <= half
    # v / a = 0.5 rad/s near the bottom of the band (its lowest ordinate 0.1 rad/s): the likelihood is nearly flat
    # in a there, and where a quasi-Newton fit stops along it decides whether the profile bounds a on both sides
    # (rounding-level changes of the sums move it): either not identified, or an interval holding the built 1 mm
    # and wider than +-30 %
    a = ranking[0].parameters["a"]
    assert a == "not identified" or (abs(a[0] - truth["a"]) <= a[1] and a[1] > 0.3 * truth["a"])


# ----------------------------------------------------------------------------- coinciding families, exact cases
DT_FILE = 1e-2  # the shipped model I file's 100 Hz, 200 s: the record length and step of a shipped null table
N_FILE = 20_000


def closed_form_record(model, theta, v, seed):
    """A Gaussian record drawn from ``model``'s family at ``theta`` (its closed form), written to 1 pm as the
    shipped file is, the slide added."""
    from compare.analysis.synthetic import spectrum_record

    fam = FAMILIES[model]
    x = spectrum_record(N_FILE, DT_FILE, lambda w: fam.spectrum(theta, w, v), 2, seed=seed)
    return np.round((x + v * DT_FILE * np.arange(N_FILE)) * 1e12) / 1e12


@pytest.fixture(scope="module")
def model_I_closed_form_ranking():
    theta, v = FAMILIES["model_I"].from_model(rm.spring_block.SpringBlockParams.reference())
    return identify(x=closed_form_record("model_I", theta, v, seed=0), dt=DT_FILE, v=v)


def test_families_nesting_model_I_coincide_with_it_on_model_I_records(model_I_closed_form_ranking):
    # model Ib's micro level and the ageing step are absent from the record: their families are model I's there and
    # model I is named alone. Their gains are judged at 5 % (Holm) against the null table of this record length:
    # a record of model I fails this with probability at most 5 %, seed 0 taken as it came
    r = {m.model: m for m in model_I_closed_form_ranking}
    assert model_I_closed_form_ranking[0].model == "model_I" and r["model_I"].verdict == "fits"
    for other in ("model_Ib", "model_ageing", "model_Iv"):
        assert r[other].coincides_with == "model_I" and r[other].verdict == "indistinguishable", other
        assert r[other].separate, other
    # what would show a held feature says where it lies against the band (a longer record, a faster sampling, ...)
    for other in ("model_Ib", "model_ageing"):
        assert "rad/s" in r[other].separate and ("longer record" in r[other].separate
                                                 or "faster sampling" in r[other].separate), r[other].separate
    # their extra features are not identified: no interval
    for name in ("L2", "a2", "omega3"):
        assert r["model_Ib"].parameters[name] == "not identified"
    for name in ("b", "D_c"):
        assert r["model_ageing"].parameters[name] == "not identified"
    assert r["model_II"].coincides_with is None and r["model_III"].coincides_with is None
    d = r["model_Ib"].to_dict()
    assert d["coincides_with"] == "model_I" and set(d) >= {"model", "verdict", "p_value", "parameters", "separate"}
    # a model that coincides by its gain's test prints that test's Holm-adjusted p-value, the one nested_test quotes
    for other in ("model_Ib", "model_ageing"):
        m = r[other]
        if "Holm-adjusted p = " in m.nested_test:
            assert f"{m.p_value:.2g}" == m.nested_test.split("Holm-adjusted p = ")[1].split()[0], (other, m.nested_test)
            assert m.p_value >= 0.05


def test_a_family_nesting_model_I_never_fits_a_record_worse_than_model_I():
    # seed 0 of the 60 s null table's reference records (model I's simulator, white floor): fitted from model I's
    # parameters and its own grid start only, model Ib ended 2.8e-4 below model I's likelihood (T = -5.6e-4; seed 2:
    # T = -0.20). At its nesting point (the micro level at its neutral value) model Ib's spectrum is model I's, so a
    # descent started there as well ends at least as high: T >= 0 up to the rounding of sums over 3e4 ordinates.
    # The ageing family lacks model I's contacts' inertia: at its nesting point (no step) it is model I with massless
    # contacts, omega_1 -> infinity, which its fit must reach or beat (model I's fit puts omega_1 at 9.4e3 rad/s here,
    # above the band, where it still gains 1.66 over massless contacts; the ageing fit ends 0.28 below model I)
    p = rm.spring_block.SpringBlockParams.reference()
    x = record("model_I", p, 60.0, 0)
    v = float((x[-1] - x[0]) / (DT * (len(x) - 1)))
    rec = record_for(x, DT)
    fam = FAMILIES["model_I"]
    fit_I = fit_family(rec, fam, v)
    ib = fit_family(rec, FAMILIES["model_Ib"], v, start_theta=fit_I.theta, nested=fit_I)
    assert 2 * (fit_I.nll - ib.nll) >= -1e-6, 2 * (fit_I.nll - ib.nll)
    i = [q.name for q in fam.params].index("omega_1")
    massless = np.array(fit_I.params, dtype=float)  # log10 values, the floor's last
    massless[i] = math.log10(fam.params[i].bounds[1])
    nll_massless = Grouped(rec).negloglik(sampled_spectrum(fam, v, DT), massless)
    ageing = fit_family(rec, FAMILIES["model_ageing"], v, start_theta=fit_I.theta, nested=fit_I)
    assert ageing.nll <= nll_massless + 1e-6, (ageing.nll - fit_I.nll, nll_massless - fit_I.nll)


def test_identify_reports_its_progress_family_by_family(model_I_record):
    lines = []
    identify(x=model_I_record, dt=DT, v=5e-4, progress=lines.append)
    fitted = [ln for ln in lines if "family fitted in" in ln]
    # one fit per distinct family: model_Iv shares model I's
    assert len(fitted) == len({id(FAMILIES[n].shape) for n in rm.MODELS}) and lines[0].startswith("fitting model_I")


def test_a_micro_level_inside_the_band_is_model_Ib_not_model_I():
    # model Ib's closed form with its micro level tripling the omega^-4 level from 2 v / a2 = 20 rad/s up to
    # omega3 = 100 rad/s, a decade inside the 0.03-314 rad/s band: model I cannot make the step
    theta, v = FAMILIES["model_I"].from_model(rm.spring_block.SpringBlockParams.reference())
    theta = {**theta, "L2": 2 * theta["L"], "a2": 5e-5, "omega3": 100.0}
    ranking = identify(x=closed_form_record("model_Ib", theta, v, seed=0), dt=DT_FILE, v=v)
    r = {m.model: m for m in ranking}
    assert ranking[0].model == "model_Ib" and r["model_Ib"].verdict == "fits"
    assert r["model_I"].verdict == "rejected" and r["model_I"].coincides_with is None
    assert r["model_Ib"].parameters["L2"] != "not identified"


def test_the_ranking_prints_one_family_and_labels_the_half_width(model_I_closed_form_ranking):
    from compare.cli.mechanisms import ranking_lines

    lines = ranking_lines({"mechanisms": [m.to_dict() for m in model_I_closed_form_ranking]})
    assert "95 % half-width" in lines[0]
    assert lines[1].split()[:2] == ["model_I", "fits"]
    assert "coincide with it on this band" in lines[2]
    for other in ("model_Ib", "model_ageing", "model_Iv"):
        assert other in lines[2]
        assert not any(line.split()[:1] == [other] for line in lines)  # no line of its own: one family
    # a parameter not identified is printed so, never with an interval
    best = lines[1]
    assert "not identified: " in best and "omega_c" in best.split("not identified: ")[1]
    assert "omega_c =" not in best


def test_a_parameter_not_identified_never_gets_an_interval_printed():
    from compare.cli.mechanisms import ranking_lines

    m = {"model": "model_ageing", "verdict": "fits", "p_value": 1.0, "separate": "",
         "parameters": {"L": [1.1e-10, 5e-12, "m^2 s^-3"], "D_c": "not identified"}}
    line = ranking_lines({"mechanisms": [m]})[1]
    assert "L = 1.1e-10 +- 5e-12 m^2 s^-3" in line and "not identified: D_c" in line and "D_c =" not in line


# ----------------------------------------------------------------------------- a significant nested gain re-ranks
def test_reorder_puts_a_significant_nesting_family_above_model_I_and_an_unseen_one_below():
    from compare.analysis.identify import NestedGains, _reorder

    g = NestedGains("model_I", ("model_I", "model_Iv"), ("model_Ib", "model_ageing"),
                    {"model_Ib": (0.5, "", True), "model_ageing": (0.007, "", True)},
                    {"model_Ib": 0.5, "model_ageing": 0.014}, ("model_ageing",), ("model_Ib",))
    # the information criterion's order: model I's penalty for the step's two parameters kept it first
    bic_order = ["model_I", "model_Iv", "model_Ib", "model_ageing", "model_II"]
    assert _reorder(bic_order, g) == ["model_ageing", "model_I", "model_Iv", "model_Ib", "model_II"]
    # an unseen nesting family never ranks above model I's family, whatever the criterion says; a model outside the
    # nesting (model II) keeps its place
    assert _reorder(["model_Ib", "model_II", "model_I", "model_Iv", "model_ageing"], g) == [
        "model_II", "model_ageing", "model_I", "model_Iv", "model_Ib"]
    assert g.top == "model_ageing" and "significant" in g.describe("model_I") and g.describe("model_II") == ""


def test_a_chi2_gain_promotes_only_where_the_criterion_agrees():
    # no null table applies (a 3 s record at 100 Hz): the optimistic chi^2 p-value re-ranks only with the criterion
    from compare.analysis.identify import nested_gains

    theta, v = FAMILIES["model_I"].from_model(rm.spring_block.SpringBlockParams.reference())
    fits = {"model_I": fit_family(record_for(closed_form_record("model_I", theta, v, seed=0), DT_FILE),
                                  FAMILIES["model_I"], v)}
    # the ageing family's fit, stood in by model I's with a gain of T = 20 and its step's two parameters identified
    fits["model_ageing"] = dataclasses.replace(fits["model_I"], family="model_ageing", nll=fits["model_I"].nll - 10.0,
                                               intervals={**fits["model_I"].intervals, "b": (0.1, 0.5),
                                                          "D_c": (1e-5, 1e-3)})
    names = ["model_I", "model_ageing"]
    agree = nested_gains(names, fits, 300, DT_FILE, 0.05, {"model_I": 0.0, "model_ageing": -1.0})
    disagree = nested_gains(names, fits, 300, DT_FILE, 0.05, {"model_I": 0.0, "model_ageing": 1.0})
    # T = 20 against chi^2(2): p = 4.5e-5, significant in both; calibrated in neither
    assert agree.adjusted["model_ageing"] < 1e-4 and not agree.tests["model_ageing"][2]
    assert agree.promoted == ("model_ageing",) and disagree.promoted == () and disagree.unseen == ()


def test_a_strong_ageing_step_ranks_the_ageing_model_first_and_rejects_model_I():
    # the ageing family's closed form with its step (A / (A - B))^2 = 2.25 below v / D_c = 5 rad/s, 1.7 decades
    # inside the 200 s, 100 Hz band (0.03-314 rad/s), at alpha = 0.1 (the confusion table's ageing cell). Its gain
    # over model I is judged against the 200 s null table; the information criterion alone may keep model I first
    # (it charges the step's two parameters ln(n) / 2 each), the calibrated test does not
    theta, v = FAMILIES["model_ageing"].from_model(rm.ageing.AgeingParams(alpha=0.1))
    ranking = identify(x=closed_form_record("model_ageing", theta, v, seed=0), dt=DT_FILE, v=v)
    r = {m.model: m for m in ranking}
    assert ranking[0].model == "model_ageing", [(m.model, m.verdict, m.nested_test) for m in ranking]
    assert r["model_I"].verdict == r["model_Iv"].verdict == "rejected"
    assert "model_ageing" in r["model_I"].nested_test and r["model_I"].p_value < 0.05
    assert r["model_ageing"].parameters["b"] != "not identified"
    b, half, _ = r["model_ageing"].parameters["b"]
    assert abs(b - theta["b"]) <= half


@pytest.mark.slow
def test_model_I_records_keep_model_I_first_at_the_tables_false_alarm_rate():
    # 10 records of model I's simulator (60 s at 1 kHz, the white floor of the 60 s null tables; seeds 100-109, none
    # of the tables' 0-79): a nesting family's gain re-ranks a record at most at the Holm-adjusted level, 5 %. The
    # count of records with model I first is read against ">= 95 %" by its Clopper-Pearson interval: 8 of 10 has an
    # upper end of 0.975, 7 of 10 0.933 (contradicted). At a true re-ranking rate of 5 % the test fails with
    # probability P(Bin(10, 0.05) >= 3) = 1.2 %. (The null tables' page counts the rule's re-rankings over the
    # tables' own records, each read against the other point's table: the larger sample.)
    from compare.analysis.confusion import binomial_interval

    p = rm.spring_block.SpringBlockParams.reference()
    models = ("model_I", "model_Iv", "model_Ib", "model_ageing")
    first = [identify(x=record("model_I", p, 60.0, seed), dt=DT, v=p.v, models=models)[0].model
             for seed in range(100, 110)]
    k = sum(f in ("model_I", "model_Iv") for f in first)
    assert binomial_interval(k, len(first))[1] >= 0.95, first


@pytest.mark.slow
def test_the_ageing_record_the_criterion_kept_below_model_I_now_ranks_first():
    # the confusion table's ageing cell (alpha = 0.1, step at v / D_c = 5 rad/s, 60 s at 1 kHz, white floor), its
    # seed 0: the information criterion kept model I first on this record (the step's two parameters cost
    # ln(3e4) = 10.3, its gain T / 2 = 8.6); the 60 s null table calls T = 17.2 significant. The step lies about
    # 50 Fourier ordinates above the band's bottom: the fit does not always see it (a record of the same simulator
    # seed with another floor realisation held it neutral: docs/results/identification.md)
    from compare.analysis.confusion import CELLS, _record

    cell = next(c for c in CELLS if c.model == "model_ageing" and c.duration == 60.0)
    ranking = identify(x=_record(cell, 0), dt=DT, v=cell.params.v)
    r = {m.model: m for m in ranking}
    assert ranking[0].model == "model_ageing", [(m.model, m.verdict, m.nested_test) for m in ranking]
    assert r["model_ageing"].verdict == "fits" and r["model_I"].verdict == r["model_Iv"].verdict == "rejected"


# ----------------------------------------------------------------------------- model_Iv's resonance
def _slide_margin(p) -> float:
    """How far every contact of model_Iv stays from sticking through the vibration's cycle (N): the mean spring
    force over f_kin (m eta1 V, V ~ v), less the random force's largest offset alpha f_kin / 2 and the cycle's swing
    A sqrt(k0^2 + (m eta0 omega_v)^2) (the miniblock follows the substrate: its spring and damper carry the
    substrate's motion). Positive: the Coulomb part never engages and model_Iv is linear, model I plus its line."""
    return p.m * p.eta1 * p.v - p.alpha * p.f_kin / 2 - p.amplitude * math.hypot(p.k0, p.m * p.eta0 * p.omega_v)


@pytest.mark.slow
def test_model_Iv_whose_contacts_slide_throughout_has_model_I_resonance():
    # A = 10 um, alpha = 0.3: every contact slides through every cycle (margin 0.042 N), so the record is model I's
    # plus the line, and the fitted resonance covers sqrt(N k0 / M) = 547.7 rad/s (measured 547.2 [546.2, 548.2]).
    # At the reference (A = 30 um, alpha = 1: margin -0.22 N, contacts stick part of each cycle) the resonance lies
    # 0.4-0.8 % below it (docs/results/identification.md), a departure of the nonlinear contacts the family does
    # not hold
    p = dataclasses.replace(rm.vibrating_block.VibratingBlockParams.reference(), amplitude=10e-6, alpha=0.3)
    assert _slide_margin(p) > 0.03
    assert _slide_margin(rm.vibrating_block.VibratingBlockParams.reference()) < -0.2
    truth, V = FAMILIES["model_Iv"].from_model(p)
    m = identify(x=rm.MODELS["model_Iv"].simulate(p, 60.0, DT, seed=0).x, dt=DT, v=V, models=("model_Iv",))[0]
    lo, hi = m.fit.intervals["omega_c"]
    assert lo <= truth["omega_c"] <= hi
    assert any(abs(ln.omega - p.omega_v) < 1.0 for ln in m.lines)


def test_every_form_of_the_record_ranks_alike(model_I_record):
    # identify(t, x), identify(x=x, dt=dt) and identify(record) are one record: the same ranking to the last digit
    # (two families keep it short; the forms differ only in how dt is read)
    class Trace:
        t = np.arange(len(model_I_record)) * DT
        x = model_I_record

    models = ("model_I", "model_II")
    forms = [identify(Trace.t, Trace.x, v=5e-4, models=models), identify(x=Trace.x, dt=DT, v=5e-4, models=models),
             identify(Trace, v=5e-4, models=models)]
    rows = [[(m.model, m.verdict, m.p_value) for m in r] for r in forms]
    assert rows[0] == rows[1] == rows[2] and len(rows[0]) == 2


def test_the_order_x_dt_v_is_refused_naming_the_forms(model_I_record):
    for call in (lambda: identify(model_I_record, DT), lambda: identify(model_I_record, DT, 5e-4)):
        with pytest.raises(ValueError, match=r"identify\(t, x\) with times \(s\) and positions \(m\).*"
                                             r"identify\(x, dt, v\) is not one of them") as e:
            call()
        assert "\n" not in str(e.value)
    t = np.arange(len(model_I_record)) * DT
    with pytest.raises(ValueError, match="not both"):
        identify(t, model_I_record, dt=DT)
    with pytest.raises(ValueError, match="not uniform"):
        identify(t ** 1.01, model_I_record)
