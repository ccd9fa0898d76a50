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
