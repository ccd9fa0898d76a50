"""analyze states one stationarity verdict: the exponent fit's split-half likelihood-ratio test when it ran, the
band test of compare.analysis.identify.stationarity only for a fit without one; and the split-half test's false
alarms on exactly stationary records hold its nominal 1 % (docs/results/stationarity.md)."""
import re

import numpy as np
import pytest
from scipy import stats

import compare.analysis.identify as identify_module
from compare.cli.mechanisms import BAND_TEST, SPLIT_HALF, mechanisms_of, ranking_lines

DT = 1e-3


class _Record:
    segmented = False
    t = np.arange(4096) * DT
    x = 1e-4 * t


@pytest.fixture
def no_ranking(monkeypatch):
    """identify returns no model (the verdict, not the ranking, is under test); calls of the band test are counted."""
    calls = []

    def band_test(x, dt, **kw):
        calls.append(len(x))
        return {"stationary": False, "ratios": [], "z": [], "bands": []}

    monkeypatch.setattr(identify_module, "identify", lambda *a, **k: [])
    monkeypatch.setattr(identify_module, "stationarity", band_test)
    return calls


def test_a_passed_split_half_test_is_the_verdict_and_the_band_test_is_not_run(no_ranking):
    out = mechanisms_of(_Record(), 1e-4, (), stationarity_p=0.16)
    assert no_ranking == []  # the band test, which would say "not stationary" here, is never asked
    assert out["stationarity"] == {"test": SPLIT_HALF, "stationary": True, "p_value": 0.16, "level": 0.01}
    assert out["mechanisms_note"] == ""
    line = ranking_lines(out)[-1]
    assert "stationary by the split-half" in line and "p = 0.16" in line and "NOT" not in line


def test_a_failed_split_half_test_names_no_mechanism_and_says_which_test(no_ranking):
    flag = "not stationary: the halves' spectra differ (split-half likelihood ratio, p = 0.003)"
    out = mechanisms_of(_Record(), 1e-4, (flag,), stationarity_p=0.003)
    assert no_ranking == []
    assert out["mechanisms_note"] == f"no mechanism named: {flag}"
    assert out["stationarity"]["stationary"] is False and out["stationarity"]["test"] == SPLIT_HALF
    lines = ranking_lines(out)
    assert any("NOT stationary by the split-half" in ln for ln in lines)
    assert not any("band levels" in ln for ln in lines)  # one test stated, the one the exponent's flag names


def test_a_fit_without_a_split_half_test_gets_the_band_test_and_says_so(no_ranking):
    out = mechanisms_of(_Record(), 1e-4, ())  # a --method whittle fit: no stationarity_p
    assert no_ranking == [4096]
    assert out["stationarity"]["test"] == BAND_TEST and not out["stationarity"]["stationary"]
    assert "band test" in out["mechanisms_note"] and "ran no stationarity test of its own" in out["mechanisms_note"]


def test_analyze_states_the_split_half_p_of_its_own_fit(tmp_path, capsys, monkeypatch):
    from compare.analysis.synthetic import power_law_record
    from compare.cli.main import main

    monkeypatch.setattr(identify_module, "identify", lambda *a, **k: [])
    n = 4096
    t = np.arange(n) * DT
    x = 1e-4 * t + 1e-9 * power_law_record(n, DT, 4.0, floor_rms=1e-3, seed=11)
    path = tmp_path / "rec_um.csv"
    np.savetxt(path, np.column_stack([t, x * 1e6]), delimiter=",", header="time_s,x_um", comments="", fmt="%.10g")
    assert main(["analyze", str(path), "-o", str(tmp_path / "out")]) == 0
    import json

    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["stationarity"]["test"] == SPLIT_HALF
    assert s["stationarity"]["p_value"] == pytest.approx(s["fit"]["stationarity_p"])
    assert s["stationarity"]["stationary"] == (not any(f.startswith("not stationary") for f in s["fit"]["flags"]))
    assert "stationarity: " in capsys.readouterr().out


@pytest.mark.slow
def test_the_split_half_false_alarm_rate_holds_its_level_on_stationary_records():
    # 100 exact omega^-4 records of 4096 samples (seeds apart from the results page's 0-199): the count of p < 0.01 is
    # Binomial(100, 0.01) at the nominal level; 6 or more has probability 5e-4 there (one-sided, p < 0.001)
    from compare.analysis.record_model import TEST_LEVEL, fit_record
    from compare.analysis.synthetic import power_law_record

    alarms = sum(fit_record(power_law_record(4096, DT, 4.0, seed=s), DT).stationarity_p < TEST_LEVEL
                 for s in range(1000, 1100))
    limit = int(stats.binom.isf(0.001, 100, TEST_LEVEL))  # P(X > limit) <= 0.001
    assert limit == 5
    assert alarms <= limit


def test_the_study_writes_its_page_with_the_binomial_verdict(tmp_path):
    from compare.studies.stationarity_false_alarm import binomial, main

    assert binomial(0, 200)[0] == 1.0
    p, (lo, hi) = binomial(2, 200)
    assert p == pytest.approx(stats.binom.sf(1, 200, 0.01)) and lo < 0.01 < hi
    assert binomial(8, 200)[0] > 0.001 > binomial(9, 200)[0]  # 9 of 200 at a nominal 1 % rejects it, 8 does not
    out = tmp_path / "page.md"
    main(["--quick", "--out", str(out), "--rows", str(tmp_path / "rows.json")])
    text = out.read_text()
    assert "Pooled split-half false-alarm rate" in text and "| 4096 | 6 | dominant | 3 |" in text
    assert "Records of a mechanism: model_I's reference case**, 10 s at 1 kHz (10000 samples)" in text
    main(["--page-from", str(tmp_path / "rows.json"), "--out", str(tmp_path / "again.md")])
    again = (tmp_path / "again.md").read_text()
    assert again.split("Written from")[0] == text.split("Measured in")[0]


def test_the_split_half_test_flags_a_record_whose_level_quadruples_halfway():
    # the one verdict still sees a real change: the fluctuation doubled in the second half (its spectrum x4), as the
    # band test's own test does with model I's record
    from compare.analysis.record_model import fit_record
    from compare.analysis.synthetic import power_law_record

    z = power_law_record(4096, DT, 4.0, seed=7)
    jumped = np.concatenate([z[:2048], z[2047] + 2 * (z[2048:] - z[2047])])  # continuous at the midpoint
    fit = fit_record(jumped, DT)
    assert fit.stationarity_p < 1e-6 and any(f.startswith("not stationary") for f in fit.flags)


def test_the_explanation_quotes_the_false_alarm_counts_of_the_results_page():
    from pathlib import Path

    docs = Path(__file__).resolve().parents[2] / "docs"
    results = (docs / "results" / "stationarity.md").read_text()
    split = re.search(r"false-alarm rate: (\d+)/(\d+) = ([\d.]+) %", results).groups()
    band = re.search(r"The band test on the same records: (\d+)/(\d+) = ([\d.]+) %", results).groups()
    text = " ".join((docs / "explanation" / "identification.md").read_text().split())
    assert f"flagged {split[0]} of {split[1]} ({split[2]} %" in text
    assert f"{band[0]} of {band[1]} ({band[2]} %)" in text
    model = re.search(r"the split-half test flags \*\*(\d+) of (\d+)\*\*", results).groups()
    assert f"{model[0]} of {model[1]} records of model I's reference case" in text
    assert f"{split[2]} %" in " ".join((docs / "explanation" / "whittle_vs_lsq.md").read_text().split())
