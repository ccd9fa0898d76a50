"""A results page rebuilt by its study's code gives the committed table: one row of docs/results/exponent_coverage.md
(records of 2^12 samples, gamma = 2, no floor: seeds 0-59, the page's run at 2^12) recomputed by
compare.studies.exponent_coverage and compared as text with the committed row (the table holds no timing)."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow  # 60 record-model fits of 4096 samples and the spectrum-and-band fits beside them
def test_exponent_coverage_row_rebuilds():
    from compare.studies import exponent_coverage as ec

    row = [ec.cell(4096, 2.0, "none", 60, True)]
    rebuilt = ec.table(row).splitlines()[2]
    committed = [line for line in (ROOT / "docs/results/exponent_coverage.md").read_text().splitlines()
                 if line.startswith("| 2^12 | 2 | none |")]
    assert committed == [rebuilt]
