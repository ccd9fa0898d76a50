"""The report reads right at first sight: ratios in significant figures, expected disagreements said so."""
import re

from compare.report.html import verdict_table
from compare.report.study import StudyResult
from compare.report.studies._common import ratio_range, ratio_rows
from compare.report.verdict import fit_text, gamma_verdict, interval_verdict, ratio_verdict, summary_lines


def test_small_ratios_keep_their_significant_figures():
    ratios = [{"band": (0.1, 1.0), "ratio": 1.5e-4}, {"band": (1.0, 10.0), "ratio": 6.9e-4}]
    assert ratio_range(ratios) == "1.5e-04-6.9e-04"
    assert ratio_range(ratios, ".3f") == "1.50e-04-6.90e-04"
    assert [r[1] for r in ratio_rows(ratios)] == ["1.50e-04", "6.90e-04"]


def test_ratios_near_one_keep_their_fixed_decimals():
    ratios = [{"band": (0.1, 1.0), "ratio": 0.954}, {"band": (1.0, 10.0), "ratio": 1.041}]
    assert ratio_range(ratios) == "0.95-1.04"
    assert ratio_range(ratios, ".3f") == "0.954-1.041"
    assert ratio_range([{"band": (1, 2), "ratio": 0.05}, {"band": (2, 3), "ratio": 0.2}]) == "0.050-0.20"


def test_an_expected_disagreement_says_so_in_its_summary_row():
    v = ratio_verdict("scenarios/asperity_field", "C_F / model III", [1.5e-4, 6.9e-4], 1.5, "1 (no load sharing)",
                      expected="load sharing")
    assert v.agree is False and v.word == "disagrees"
    assert "as expected" in verdict_table([StudyResult("scenarios/asperity_field", "t", {}, (), "", (), (v,))])
    line = summary_lines({"verdicts": [v.to_dict()]})[0]
    assert "as expected" in line and "load sharing" in line


def test_an_agreement_carries_no_expectation_note():
    v = ratio_verdict("m", "C_x / x", [1.0, 1.1], 1.5, "1", expected="load sharing")
    assert v.agree is True and v.note == ""
    assert "as expected" not in summary_lines({"verdicts": [v.to_dict()]})[0]


def test_a_difference_that_rounds_to_zero_has_no_sign():
    # model III's N = 30 fit reads 5.98 against an exact 5.98 (-0.001): the quick report's summary row wrote "-0.00"
    flagged = {"gamma": 5.979, "gamma_err": 0.02, "flags": ["log-log residuals curve"]}
    for v in (gamma_verdict("model_III", "gamma", flagged, 5.98, "5.98"),
              gamma_verdict("model_III", "gamma", dict(flagged, flags=[]), 5.98, "5.98"),
              interval_verdict("wear", "rise", -0.001, 0.5, 0.0, "0", direction="above")):
        assert not re.search(r"[-+]0\.0+(?![0-9])", v.by + v.measured), (v.by, v.measured)
        assert v.by.startswith("0.00")
    assert fit_text({"gamma": -0.004, "gamma_err": 0.1}).startswith("0.00 ")
    assert gamma_verdict("m", "gamma", dict(flagged, flags=[]), 5.9, "5.9").by.startswith("+0.08")
