"""A results page rebuilt by its study's code gives the committed table, compared as text (the tables hold no
timing):

- one row of docs/results/exponent_coverage.md (records of 2^12 samples, gamma = 2, no floor: seeds 0-199, the page's
  run at 2^12) recomputed by compare.studies.exponent_coverage;
- two rows of docs/results/wear_study_quick.md (the smooth track's particle-free twin and its 25 narrow grains, seeds
  0 and 1: 4 of the page's 16 tasks) by the page's own sweep file with its grid cut to those cells, run by the
  sweep runner the page's command uses and tabled by compare.studies.wear_study.
"""
from dataclasses import replace
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow  # 200 record-model fits of 4096 samples and the spectrum-and-band fits beside them (1-2 min)
@pytest.mark.extended  # CI runs the same cells on 20 other seeds against the page's claims
# (tests/compare/test_exponent_coverage.py) and the table's layout at smoke size
def test_exponent_coverage_row_rebuilds():
    from compare.studies import exponent_coverage as ec

    row = [ec.cell(4096, 2.0, "none", 200, True)]
    rebuilt = ec.table(row).splitlines()[2]
    committed = [line for line in (ROOT / "docs/results/exponent_coverage.md").read_text().splitlines()
                 if line.startswith("| 2^12 | 2 | none |")]
    assert committed == [rebuilt]


def _table_rows(page: Path) -> list:
    return [line for line in page.read_text().splitlines() if line.startswith("| ")]


@pytest.mark.slow  # 4 scene runs of 3.5 s, two of them with 25 wear grains (about a minute on an idle core)
def test_wear_quick_study_rows_rebuild(tmp_path):
    from compare.report.wear_study import cells
    from compare.studies import wear_study as ws
    from compare.sweep import load_results, load_sweep, run_sweep
    from engine_sim.shipped import shipped_file

    spec = load_sweep(shipped_file("scenarios/sweeps/wear_study_quick.toml"))
    cut = replace(spec, grid={**spec.grid, "wear.count": [0, 25], "study.size": ["narrow"],
                              "study.track": ["smooth"]})
    assert cut.grid["seed"] == [0, 1]  # the page's seeds: the cut keeps them
    report = run_sweep(cut, tmp_path, serial=True)
    assert report["failed"] == 0 and report["done"] == 4
    header, rule, *rebuilt = ws.table_lines(cells(load_results(tmp_path, cut)))
    committed = _table_rows(ROOT / "docs/results/wear_study_quick.md")
    assert committed[0] == header  # the same columns, no timing among them
    assert "wall_per_sim_s" not in header
    assert [r.split(" | ")[:3] for r in rebuilt] == [["| smooth", "-", "0"], ["| smooth", "narrow", "25"]]
    for row in rebuilt:
        assert row in committed
