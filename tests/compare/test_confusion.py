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


def test_a_criterion_is_read_against_the_clopper_pearson_interval():
    from compare.studies.confusion_table import judge

    # 99 of 99: interval (0.963, 1) lies above 0.90: met; 5 of 5: (0.478, 1) straddles it: not contradicted;
    # 2 of 10: (0.025, 0.556) lies below: contradicted. "At most 5 %": 0 of 100, interval (0, 0.036): met;
    # 3 of 10: (0.067, 0.652) lies above 5 %: contradicted
    assert judge(99, 99, ">=", 0.90) == "met"
    assert judge(100, 100, ">=", 0.90) == "met"
    # with the must-show's 100 records the criterion is the count itself: 75 of 100 for ">= 80 %" is not met,
    # although its interval (65-83 %) straddles 80 %; 5 of 100 for "<= 5 %" is met, 6 is not
    assert judge(75, 100, ">=", 0.80) == "not met"
    assert judge(80, 100, ">=", 0.80) == "met"
    assert judge(5, 100, "<=", 0.05) == "met" and judge(6, 100, "<=", 0.05) == "not met"
    assert judge(5, 5, ">=", 0.90) == "not contradicted"
    assert judge(2, 10, ">=", 0.90) == "contradicted"
    assert judge(0, 100, "<=", 0.05) == "met"
    assert judge(0, 5, "<=", 0.05) == "not contradicted"
    assert judge(3, 10, "<=", 0.05) == "contradicted"


def test_the_page_keeps_what_lies_outside_its_generated_part(tmp_path):
    from compare.studies.confusion_table import BEGIN, END, write_page

    page = tmp_path / "page.md"
    page.write_text(f"# Title\n\nintro\n\n{BEGIN}\n\nold table\n\n{END}\n\n## Scenes\n\nkept text\n")
    write_page("new table", page)
    text = page.read_text()
    assert "old table" not in text and "new table" in text
    assert text.startswith("# Title\n\nintro\n\n") and text.endswith("## Scenes\n\nkept text\n")


def test_parts_of_one_cell_add_up():
    from compare.studies.confusion_table import _add

    a = {"n": 2, "alone": 1, "best": {"model_I": 2}, "by_parameter": {"L": [1, 2]}, "seeds": [0, 1], "cpu_s": 1.0}
    b = {"n": 3, "alone": 3, "best": {"model_I": 1, "model_Ib": 2}, "by_parameter": {"L": [2, 3], "a": [1, 1]},
         "seeds": [2, 3, 4], "cpu_s": 2.0}
    s = _add(a, b)
    assert s["n"] == 5 and s["alone"] == 4 and s["cpu_s"] == 3.0 and s["seeds"] == [0, 1, 2, 3, 4]
    assert s["best"] == {"model_I": 3, "model_Ib": 2}
    assert s["by_parameter"] == {"L": [3, 5], "a": [1, 1]}


def test_many_parts_are_named_by_their_form_and_the_seeds_they_cover():
    from compare.analysis.confusion import CELLS
    from compare.studies.confusion_table import COMMAND, _commands_text, _key

    c60, c300 = (next(c for c in CELLS if c.duration == T) for T in (60.0, 300.0))
    parts = []
    for i, (cell, seeds) in enumerate([(c60, [0, 1]), (c60, [2, 3]), (c300, [0]), (c300, [1]), (c300, [2])]):
        parts.append((f"p{i}", {"command": f"cmd {i}", "cpu_s": 1.0, "cells": {_key(cell): {"seeds": seeds}}}))
    text = _commands_text([f"cmd {i}" for i in range(5)], parts)
    assert text.startswith(f"{COMMAND} --part NAME") and "in 5 parts" in text
    assert "60 s: seeds 0-3 in 2 parts; 300 s: seeds 0-2 in 3 parts" in text
    assert "cmd 1" not in text and text.endswith(f"{COMMAND} --combine")
    assert _commands_text(["cmd 0", "cmd 1"], parts[:2]) == f"cmd 0`, `cmd 1`, then `{COMMAND} --combine"


def test_an_interrupted_part_resumes_with_its_finished_cells(tmp_path, monkeypatch):
    import json

    import pytest

    from compare.studies import confusion_table as ct

    monkeypatch.setattr(ct, "PARTS", tmp_path)
    calls = []

    def stub(cell, seeds):
        if len(calls) == 2 and not resumed:
            raise KeyboardInterrupt  # interrupted while the third cell runs
        calls.append(cell)
        return {"n": len(seeds), "cpu_s": 1.0}

    monkeypatch.setattr(ct, "run_cell", stub)
    resumed = False
    with pytest.raises(KeyboardInterrupt):
        ct.main(["--quick", "--part", "p"])
    assert len(json.loads((tmp_path / "p.json").read_text())["cells"]) == 2
    resumed = True
    assert ct.main(["--quick", "--part", "p"]) == 0
    assert len(calls) == len(ct.QUICK_CELLS)  # the two finished cells were not run again
    assert len(json.loads((tmp_path / "p.json").read_text())["cells"]) == len(ct.QUICK_CELLS)
    calls.clear()
    assert ct.main(["--quick", "--part", "p", "--first-seed", "3"]) == 0  # another command: every cell runs
    assert len(calls) == len(ct.QUICK_CELLS)
