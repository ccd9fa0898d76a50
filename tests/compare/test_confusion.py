"""The confusion study's bookkeeping on one short cell (the table itself: compare/studies/confusion_table.py)."""
from compare.analysis.confusion import SMOKE_CELLS, run_cell


def test_a_model_I_cell_counts_each_record_once():
    cell = SMOKE_CELLS[0]
    assert cell.model == "model_I" and cell.duration == 30.0
    r = run_cell(cell, [0])
    assert r["n"] == 1 and sum(r["best"].values()) <= 1
    assert r["alone"] + r["wrong_alone"] + r["coincides"] + r["indistinguishable"] <= 1
    assert 0 <= r["covered"] <= r["intervals"] <= len(("L", "a", "omega_c", "Q", "omega_0"))
    # the true model ranked first or indistinguishable: the table's >= 90 % event, one record
    assert r["first_or_indistinguishable"] == 1


def test_quick_table_is_a_smoke_of_the_whole_command(tmp_path):
    # compare/studies/confusion_table.py --quick: the command that rebuilds docs/results/identification.md, on three 10 s
    # cells with one seed, writes a table with one row per cell and the pooled coverage
    from compare.studies.confusion_table import main
    from compare.analysis.confusion import QUICK_CELLS

    out = tmp_path / "table.md"
    main(["--quick", "--out", str(out)])
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| model_")]
    assert [r.split(" | ")[0][2:] for r in rows] == [c.model for c in QUICK_CELLS]
    assert all(" | 10 | " in r and "/1 (" in r for r in rows)  # each count of one record with its interval
    assert "Pooled coverage" in text


def test_binomial_interval_is_clopper_pearson():
    from compare.analysis.confusion import binomial_interval

    # 90 of 100: the exact interval (0.824, 0.951) (Clopper & Pearson 1934; scipy's binomtest agrees)
    lo, hi = binomial_interval(90, 100)
    assert abs(lo - 0.8238) < 1e-3 and abs(hi - 0.9510) < 1e-3
    assert binomial_interval(0, 10)[0] == 0.0 and binomial_interval(10, 10)[1] == 1.0
