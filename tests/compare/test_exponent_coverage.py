"""compare.studies.exponent_coverage: the quick mode (a CI smoke) runs every cell and writes its table."""
import re

from compare.studies import exponent_coverage


def test_quick_mode_writes_the_table(tmp_path):
    # Every gamma (2, 4, 6) with every floor (none, at Nyquist, dominant): 9 rows of 2 seeds at 2^10 samples, with
    # the record model's and the old estimator's columns and the pooled coverage of 18 intervals.
    out = tmp_path / "coverage.md"
    assert exponent_coverage.main(["--quick", "--out", str(out)]) == 0
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| 2^10 |")]
    assert len(rows) == 9
    assert {r.split("|")[2].strip() for r in rows} == {"2", "4", "6"}
    assert {r.split("|")[3].strip() for r in rows} == {"none", "at Nyquist", "dominant"}
    assert all(len(r.strip("|").split("|")) == 16 for r in rows)
    assert re.search(r"pooled coverage [\d.]+ % \(\d+/18;", text)
