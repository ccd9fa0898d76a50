"""compare.studies.exponent_coverage: the quick mode (a CI smoke) runs every cell and writes its table; the page's
claims hold on its 2^12 cells with other seeds."""
import math
import re

import pytest
from scipy import stats

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


@pytest.mark.slow  # 180 record-model fits of 4096 samples (about a minute of one idle core)
def test_the_pages_claims_hold_on_its_2_12_cells_with_fewer_seeds():
    # The page's cells at 2^12 samples (gamma 2, 4, 6 with every floor), 20 seeds each (seeds 1000-1019, none of the
    # page's), held to the page's claims at the resolution 20 seeds allow:
    # - coverage: no cell outside the 0.0005-0.9995 quantiles of Binomial(20, 0.95) (at most 14 of 20 fails it), and
    #   the 180 intervals pooled inside those of Binomial(180, 0.95);
    # - bias: |mean bias| below a quarter of the median half-width, unless the excess is within 3.29 standard errors
    #   of the mean (half-width / (1.96 sqrt(20)) each): the claim is rejected only where 20 seeds show it false at
    #   p < 0.001 one-sided;
    # - the median half-width within 1.25x of the Cramer-Rao bound with the floor free (the page: 0.78-1.04);
    # - the band spans at least a decade on every clean power law (the page: 3.3 decades).
    seeds, first = 20, 1000
    rows = [exponent_coverage.cell(4096, g, where, seeds, False, first)
            for g in exponent_coverage.GAMMAS for where in exponent_coverage.FLOORS]
    lo, hi = stats.binom.ppf(0.0005, seeds, 0.95), stats.binom.ppf(0.9995, seeds, 0.95)
    assert lo == 15 and all(lo <= r["hits"] <= hi for r in rows), [(r["gamma"], r["floor"], r["hits"]) for r in rows]
    hits = sum(r["hits"] for r in rows)
    assert stats.binom.ppf(0.0005, 9 * seeds, 0.95) <= hits <= stats.binom.ppf(0.9995, 9 * seeds, 0.95), hits
    for r in rows:
        se = r["median_half"] / (1.96 * math.sqrt(seeds))
        assert abs(r["bias"]) - r["median_half"] / 4 < 3.29 * se, r
        assert r["median_half"] <= 1.25 * r["cr_half"], r
    assert all(r["min_decades"] >= 1.0 for r in rows if r["floor"] == "none")


def _without_wall(row):
    return {k: v for k, v in row.items() if k != "wall_s"}


def test_workers_and_merged_runs_give_the_serial_rows_bit_for_bit():
    # A record depends on its cell and seed only: fitted in two worker processes, or in two runs on seeds 0-1 and
    # 2-3 merged afterwards, every per-seed record and every column of the row equals the serial run's exactly
    # (== on floats, no tolerance), the dominant floor (the slowest fits) at 2^10 samples.
    from concurrent.futures import ProcessPoolExecutor

    serial = exponent_coverage.cell(1024, 4.0, "dominant", 4, True)
    with ProcessPoolExecutor(2) as pool:
        pooled = exponent_coverage.cell(1024, 4.0, "dominant", 4, True, pool=pool)
    assert [r["seed"] for r in serial["records"]] == [0, 1, 2, 3]
    assert _without_wall(pooled) == _without_wall(serial)
    parts = [exponent_coverage.cell(1024, 4.0, "dominant", 2, True, first) for first in (2, 0)]
    assert _without_wall(exponent_coverage.merged(parts)[0]) == _without_wall(serial)
    with pytest.raises(ValueError, match="a seed appears twice"):
        exponent_coverage.merged([parts[0], parts[0]])


def test_a_run_over_workers_stores_the_serial_rows_and_says_which_seeds(tmp_path):
    # The command line's run, seed by seed over all 9 cells in 2 worker processes, stores in --rows the rows the
    # serial cell() gives for those seeds (records and columns ==), and a command naming exactly those seeds.
    import json

    out = tmp_path / "rows.json"
    assert exponent_coverage.main(["--seeds", "2", "--first-seed", "5", "--lengths", "10", "--workers", "2",
                                   "--rows", str(out)]) == 0
    part = json.loads(out.read_text())
    assert part["command"].endswith("--seeds 2 --lengths 10 --first-seed 5")
    assert [(r["gamma"], r["floor"]) for r in part["rows"]] == [
        (g, w) for g in exponent_coverage.GAMMAS for w in exponent_coverage.FLOORS]
    for row in part["rows"][::4]:  # three of the nine cells (one per gamma) run again serially
        serial = exponent_coverage.cell(1024, row["gamma"], row["floor"], 2, True, 5)
        assert _without_wall(row) == json.loads(json.dumps(_without_wall(serial)))


def test_page_rows_read_back_print_as_they_stood(tmp_path):
    # A page written from 2 seeds per cell at 2^10 is read back (--from-page) and rebuilt (--combine): the table's
    # rows and the pooled coverage are the same text; a read-back row merged with a run on other seeds adds its
    # counts (2 + 2 seeds) and leaves the printed line for one computed afresh.
    page, part, again = tmp_path / "p.md", tmp_path / "rows.json", tmp_path / "again.md"
    assert exponent_coverage.main(["--quick", "--out", str(page)]) == 0
    assert exponent_coverage.main(["--from-page", str(page), "--lengths", "10", "--rows", str(part)]) == 0
    assert exponent_coverage.main(["--combine", str(part), "--out", str(again)]) == 0
    rows = [line for line in page.read_text().splitlines() if line.startswith("| 2^10 |")]
    assert len(rows) == 9
    assert rows == [line for line in again.read_text().splitlines() if line.startswith("| 2^10 |")]
    pooled = re.search(r"pooled coverage [^;]*;", page.read_text()).group(0)
    assert pooled in again.read_text()
    read = exponent_coverage.page_rows(page.read_text(), [10])["rows"][0]
    more = exponent_coverage.cell(1024, read["gamma"], read["floor"], 2, True, first=2)
    both = exponent_coverage.merged([read, more])[0]
    assert both["seeds"] == 4 and both["hits"] == read["hits"] + more["hits"]
    assert "line" not in both and exponent_coverage.table([both]).splitlines()[-1].startswith("| 2^10 | 2 | none | 4 |")
