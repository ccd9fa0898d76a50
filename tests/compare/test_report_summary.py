"""The report leads with its verdicts, and its prose says no more than its fits allow: the summary table, the
verdicts on flagged fits, the prose against the flags, the terminal's lines, and the report's number format."""
import pytest

from compare.report.html import num, page, pct, rst_inline, span, summary_of
from compare.report.study import StudyResult
from compare.report.verdict import (NOT_A_POWER_LAW, Verdict, gamma_verdict, interval_verdict, prose_flag_problems,
                                    ratio_verdict, summary_lines)

CURVED = ("log-log residuals curve (quadratic term -0.611 per (ln omega)^2, 2.8 sigma)",)


def _fit(gamma, err, flags=()):
    return {"gamma": gamma, "gamma_err": err, "band": [15.0, 150.0], "flags": list(flags)}


def test_a_flagged_fit_gives_no_verdict_and_says_why():
    v = gamma_verdict("s", "gamma", _fit(3.89, 0.29, CURVED), 4.0, "4")
    assert v.agree is None and v.word == "no verdict" and NOT_A_POWER_LAW in v.measured and NOT_A_POWER_LAW in v.by
    # the same numbers without the flag: 0.11 from 4 inside a half-width of 0.29
    assert gamma_verdict("s", "gamma", _fit(3.89, 0.29), 4.0, "4").agree is True
    # 0.5 from 4 with a half-width of 0.29: outside
    assert gamma_verdict("s", "gamma", _fit(3.5, 0.29), 4.0, "4").agree is False
    with pytest.raises(ValueError, match="agree must be None"):
        Verdict("s", "x", "1", "1", True, "0", flags=CURVED)


def test_a_target_resting_on_flagged_fits_is_not_met():
    # the paired wear runs: +0.91 +- 0.37 against a target of +0.4 would be met beyond the interval (0.54 > 0.4),
    # but both fits are flagged, so there is no verdict
    assert interval_verdict("w", "rise", 0.91, 0.37, 0.4, "+0.4", direction="above").agree is True
    v = interval_verdict("w", "rise", 0.91, 0.37, 0.4, "+0.4", flags=CURVED, direction="above")
    assert v.agree is None and NOT_A_POWER_LAW in v.measured


def test_the_checker_catches_a_claim_on_a_flagged_fit():
    # the sentences the wear section printed on two flagged fits: both are caught
    numbers = {"gamma": 3.89, "gamma_err": 0.29, "flags": list(CURVED),
               "without_particles": {"gamma": 2.98, "gamma_err": 0.23, "flags": list(CURVED)}}
    old = StudyResult("scenarios/pads_with_wear", "Scene", numbers, html=(
        "<p>gamma = 3.89 &plusmn; 0.29 with particles and 2.98 &plusmn; 0.23 without. The target is met beyond the "
        "uncertainty.</p>"))
    assert len(prose_flag_problems(old)) == 2
    honest = StudyResult("scenarios/pads_with_wear", "Scene", numbers, html=(
        f"<p>gamma = 3.89 &plusmn; 0.29 ({NOT_A_POWER_LAW}) with particles and 2.98 &plusmn; 0.23 ({NOT_A_POWER_LAW}) "
        "without. No verdict on the target.</p>"))
    assert prose_flag_problems(honest) == []
    # a verdict sentence on a flagged fit is caught even when it carries the flag
    claim = StudyResult("k", "K", {"gamma": 5.98, "gamma_err": 0.02, "flags": ["band spans 0.90 decades (< 1)"]},
                        html=f"<p>gamma = 5.98 &plusmn; 0.02 ({NOT_A_POWER_LAW}) agrees with 6.</p>")
    assert len(prose_flag_problems(claim)) == 1


@pytest.mark.slow  # two quick studies (model III and model I, about 10 s of CPU)
def test_real_studies_state_their_flags():
    from compare.report.studies import model_I, model_III

    results = model_III.run(True, 0) + model_I.run(True, 0)
    flagged = [r for r in results if r.numbers.get("flags")] + [
        v for r in results for v in r.numbers.values() if isinstance(v, dict) and v.get("flags")]
    assert flagged, "model III at N = 30 (quick) and two model I variations are flagged: the check must meet them"
    assert [p for r in results for p in prose_flag_problems(r)] == []
    lines = summary_lines(summary_of(results, {}))
    no_verdict = [ln for ln in lines if ln.strip().startswith("no verdict")]
    assert no_verdict and all(NOT_A_POWER_LAW in ln for ln in no_verdict), lines


def test_terminal_lines_are_the_table_rows_in_plain_text():
    r = StudyResult("model_III", "Model III", {}, verdicts=(
        gamma_verdict("model_III", "gamma, N = 30", _fit(5.98, 0.02, CURVED), 5.9, "5.90"),
        ratio_verdict("model_III", "C_F / exact", [0.96, 1.10], 1.25, "1")))
    lines = summary_lines(summary_of([r], {}))
    assert len(lines) == 2 and "&" not in "".join(lines) and "<" not in "".join(lines)
    assert lines[0].split()[:2] == ["no", "verdict"] and f"5.98 ± 0.02 ({NOT_A_POWER_LAW})" in lines[0]
    assert lines[1].split()[0] == "agrees" and "x1.10" in lines[1]


def test_summary_table_follows_the_contents_and_links_each_row():
    rs = [StudyResult("a", "A", {}, verdicts=(ratio_verdict("a", "C_x / theory", [0.9, 1.1], 1.25, "1"),)),
          StudyResult("scenarios/b", "B", {}, verdicts=(ratio_verdict("scenarios/b", "C_x / model I", [0.5, 2.0], 1.5, "1"),))]
    html = page(rs, {"version": "0"})
    assert html.index("id='contents'") < html.index("id='summary'") < html.index("<section")
    assert "href='#s-a'" in html and "href='#s-scenarios-b'" in html
    assert "class='agree'" in html and "class='disagree'" in html


def test_one_number_format():
    assert span(3.07, 1.57e3) == "3.07-1570"  # not "3.07-1.57e+03"
    assert span(1.79e-4, 0.00424) == "1.79e-04-4.24e-03"  # both ends alike
    assert num(2.5e-7) == "2.50e-07" and num(float("nan")) == "n/a" and num(-1e-9, 3) == "-1.00e-09"
    assert num(-0.004, 1) == "-0.004" and num(0.00001) == "1.00e-05"
    assert pct(-1e-7) == "0 % (below 0.001 %)" and pct(0.00106) == "+0.106 %"  # never "-0.000 %"


def test_docstring_markup_is_rendered():
    from compare.report.studies.scene_multiscale import PROCEDURE

    out = rst_inline(PROCEDURE)
    assert "``" not in out and ":func:" not in out and "<code>compare.analysis.extract.model_I_parameters</code>" in out
    assert rst_inline(":func:`~reduced_models.multiscale_fit.rigid_micro_params`") == "<code>rigid_micro_params</code>"


def test_a_report_without_a_seed_says_none():
    html = page([StudyResult("a", "A", {})], {"version": "0"})
    assert "seed" not in html.split("</p>")[0]
