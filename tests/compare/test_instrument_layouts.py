"""Every registered layout (compare.io.sheets) read from files the project writes the way rigs write them
(tests/instrument_files.py), values checked against the generator; refusals one line naming the file and the
place; a hypothesis fuzz of every reader; and an opt-in read of a local folder of real files."""
import json
import os
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from compare.io.measured import DataFileError, read_measured
from compare.io.sheets import LAYOUTS, SheetError, read_sheet
from tests.instrument_files import (UMT_HEADER, UMT_UNITS, look_ascii, stroke_files, tdms_file, umt_export,
                                    xlsx_book)

GF = 9.80665e-3  # N per gram-force


def test_layouts_are_registered_in_detection_order():
    assert list(LAYOUTS) == ["folder", "tdms", "xlsx", "look-ascii", "delimited"]


def test_umt_export_with_two_steps_bytes_as_the_rig_writes_them(tmp_path):
    raw, vals, where = umt_export()
    lines = raw.split(b"\r\n")
    assert lines[20] == UMT_HEADER.encode() and lines[21] == UMT_UNITS.encode() and lines[22] == b""
    assert lines[21].endswith(b",") and raw.count(b"\r\n") == raw.count(b"\n")  # trailing comma; CRLF only
    f = tmp_path / "umt.csv"
    f.write_bytes(raw)
    d = read_measured(f, time_col="T", force_col="Ff", normal_col="Fz", mu_col="COF", require_x=False)
    assert d.layout["header_line"] == 21 and d.layout["units_row_line"] == 22 and d.layout["blocks"] == 2
    assert d.n_rows == vals["T"].size
    np.testing.assert_allclose(d.F, vals["Ff"] * GF, rtol=1e-12)  # gram-force, from the units row
    np.testing.assert_allclose(d.mu, vals["COF"], rtol=0)
    block = [e for e in d.timeline.events if e.kind == "block"]
    assert len(block) == 1 and block[0].line == where["step2_line"] and "Step No. 2" in block[0].detail
    assert d.segmented and len(d.timeline.usable()) == 2


def test_umt_two_steps_analysed_mean_force_and_mu_by_hand(tmp_path, capsys):
    """The must-show: mean |F| and mean |mu| of the two-step export equal a hand computation from the numbers
    written, to 1e-4 relative (round-off only: the hand sum and the reader's see the same numbers)."""
    from compare.cli import main

    raw, vals, _ = umt_export()
    f = tmp_path / "umt.csv"
    f.write_bytes(raw)
    out = tmp_path / "o"
    assert main(["analyze", str(f), "--time-col", "T", "--force-col", "Ff", "--normal-col", "Fz", "--mu-col", "COF",
                 "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    hand_F = sum(abs(v) for v in vals["Ff"]) / len(vals["Ff"]) * GF
    hand_mu = sum(abs(v) for v in vals["COF"]) / len(vals["COF"])
    assert s["mean_abs_F_N"] == pytest.approx(hand_F, rel=1e-4)
    assert s["mean_abs_mu"] == pytest.approx(hand_mu, rel=1e-4)
    io = capsys.readouterr()
    assert "block (Step No. 2 begins" in io.out + io.err
    # the step boundary is a block of the export, said as a note, not a warning about the clock
    assert "note: " in io.err and "an export of 2 blocks (then Step No. 2 at line" in io.err
    assert "warning" not in io.err and "non-uniform" not in io.err, io.err
    # each block's means by hand (1 kg then 2 kg of load: the pooled means mix them), on the terminal and in JSON
    n1 = int(np.sum(vals["T"] < vals["T"][0] + 59.995))  # step 1: 60 s at 100 Hz
    assert n1 == 6000
    for k, rows in enumerate((slice(0, n1), slice(n1, None))):
        b = s["blocks"][k]
        assert b["mean_abs_F_N"] == pytest.approx(np.mean(np.abs(vals["Ff"][rows])) * GF, rel=1e-4)
        assert b["mean_abs_mu"] == pytest.approx(np.mean(np.abs(vals["COF"][rows])), rel=1e-4)
        assert f"block {k + 1}" in io.out and f"mean |F| = {b['mean_abs_F_N']:.4g} N" in io.out
    assert s["blocks"][1]["title"] == "Step No. 2" and s["note"].startswith(str(f))
    assert f"mean |F| = {s['mean_abs_F_N']:.4g} N, mean |mu| = {s['mean_abs_mu']:.4g} pooled over 2 blocks" in io.out
    html = (out / "index.html").read_text()
    assert "The export is made of 2 blocks" in html and "The time stamps break" not in html
    assert "By block (the pooled means above mix blocks run at different loads)" in html


def test_mu_column_labels_c_mu_by_its_column(tmp_path, capsys):
    """With --mu-col COF (and a normal force given too) C_mu is the spectrum of the column COF: HTML, terminal and
    summary.json say so and never call it F(t)/N(t); without --mu-col it is F/N, named by its columns."""
    from compare.cli import main

    raw, _, _ = umt_export(n1=3000, n2=2500)
    f = tmp_path / "umt.csv"
    f.write_bytes(raw)
    base = ["analyze", str(f), "--time-col", "T", "--force-col", "Ff", "--normal-col", "Fz"]
    assert main(base + ["--mu-col", "COF", "-o", str(tmp_path / "a")]) == 0
    s = json.loads((tmp_path / "a" / "summary.json").read_text())
    html = (tmp_path / "a" / "index.html").read_text()
    out = capsys.readouterr().out
    assert s["mu_source"] == "the column 'COF'"
    assert "C_mu of the column &#x27;COF&#x27;: exponent" in html and "F(t)/N(t)" not in html
    assert "C_mu of the column 'COF': exponent" in out
    assert main(base + ["-o", str(tmp_path / "b")]) == 0
    s = json.loads((tmp_path / "b" / "summary.json").read_text())
    assert s["mu_source"] == "mu(t) = F(t)/N(t) (columns 'Ff' / 'Fz')"
    assert "C_mu of mu(t) = F(t)/N(t) (columns 'Ff' / 'Fz'): exponent" in capsys.readouterr().out


def test_look_ascii_export_read_with_its_units(tmp_path):
    raw, vals = look_ascii()
    f = tmp_path / "p4321.txt"
    f.write_bytes(raw)
    d = read_measured(f, x_col="LP_Disp", force_col="Shr_stress", normal_col="Nor_stress", contact_area=2.5e-3)
    assert d.layout["layout"] == "look-ascii" and d.layout["records"] == 400
    np.testing.assert_allclose(d.x, vals["LP_Disp"] * 1e-6, rtol=1e-12)
    np.testing.assert_allclose(d.F, vals["Shr_stress"] * 1e6 * 2.5e-3, rtol=1e-12)
    f.write_bytes(raw.replace(b"number of records = 400", b"number of records = 500"))
    with pytest.raises(DataFileError, match=r"p4321.txt, line 2: number of records = 500 but 400 data rows"):
        read_measured(f)


def test_folder_and_glob_of_stroke_files_are_one_record(tmp_path):
    vals = stroke_files(tmp_path / "strokes")
    for path in (tmp_path / "strokes", str(tmp_path / "strokes" / "stroke_*.csv")):
        d = read_measured(path, force_col="Ff", require_x=False)
        np.testing.assert_allclose(d.F, vals["F"], rtol=0)
        assert d.layout["files"] == 4 and [e.kind for e in d.timeline.events] == ["block"] * 3
    (tmp_path / "strokes" / "stroke_003.csv").write_text("time (s),Ff (N)\n0,1\n0.01,oops\n")
    with pytest.raises(DataFileError, match=r"strokes, stroke_003.csv, line 3: non-numeric value 'oops'"):
        read_measured(tmp_path / "strokes", force_col="Ff", require_x=False)


def test_xlsx_and_tdms_read_and_refusals_name_cell_and_channel(tmp_path):
    pytest.importorskip("openpyxl")
    pytest.importorskip("nptdms")
    v = xlsx_book(tmp_path / "a.xlsx")
    d = read_measured(tmp_path / "a.xlsx", force_col="Ff", normal_col="Fn", require_x=False)
    np.testing.assert_allclose(d.F, v["F"], rtol=1e-15)  # xlsx keeps a decimal string of each double: 1 ulp
    xlsx_book(tmp_path / "b.xlsx", bad_cell="B50")
    with pytest.raises(DataFileError, match=r"b.xlsx, sheet 'Run 1', cell B50: non-numeric value 'n/a'"):
        read_measured(tmp_path / "b.xlsx", force_col="Ff", require_x=False)
    v = tdms_file(tmp_path / "a.tdms")
    d = read_measured(tmp_path / "a.tdms", force_col="Ff", normal_col="Fn", require_x=False)
    np.testing.assert_allclose(d.F, v["F"], rtol=0)
    np.testing.assert_allclose(d.t, v["t"], rtol=1e-12, atol=1e-15)  # from wf_increment
    with pytest.raises(DataFileError, match=r"a.tdms, group 'Friction', channel 'Ff', its properties: .* kN"):
        read_measured(tmp_path / "a.tdms", force_col="Ff", require_x=False, force_unit="kN")


@pytest.mark.parametrize("module, layout, extra", [("openpyxl", "xlsx", "xlsx"), ("nptdms", "tdms", "tdms")])
def test_missing_extra_is_named_in_one_line(tmp_path, monkeypatch, module, layout, extra):
    pytest.importorskip(module)
    f = tmp_path / f"a.{layout}"
    (xlsx_book if layout == "xlsx" else tdms_file)(f)
    monkeypatch.setitem(sys.modules, module, None)  # as if not installed
    with pytest.raises(SheetError, match=rf"reading it needs .* \(pip install 'frictionnoise\[{extra}\]'\)"):
        read_sheet(f)


# ------------------------------------------------------------------------------------------------------- fuzz
# a failing file is reported as drawn: shrinking whole files took minutes on this machine for no clearer example
_NO_SHRINK = (Phase.explicit, Phase.reuse, Phase.generate)
_SEEDS = {
    "delimited": lambda: umt_export(n1=80, n2=70)[0],
    "look-ascii": lambda: look_ascii(n=70)[0],
}


def _mutate(raw: bytes, data) -> bytes:
    """Cut, overwrite or insert bytes at places hypothesis draws (line ends, separators, digits, NULs, text)."""
    b = bytearray(raw)
    for _ in range(data.draw(st.integers(1, 4))):
        op = data.draw(st.sampled_from(["cut", "put", "insert", "truncate"]))
        i = data.draw(st.integers(0, max(0, len(b) - 1)))
        junk = data.draw(st.binary(min_size=1, max_size=6) | st.sampled_from(
            [b"\r", b"\r\r\n", b",", b";", b"nan", b"inf", b"1e999", b"x", b"\xb5m", b"(kip)", b"Step No. 3\r\n"]))
        if op == "cut":
            del b[i:i + len(junk)]
        elif op == "put":
            b[i:i + len(junk)] = junk
        elif op == "insert":
            b[i:i] = junk
        else:
            del b[i:]
    return bytes(b)


@pytest.mark.parametrize("name", sorted(_SEEDS))
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture],
          phases=_NO_SHRINK)
@given(data=st.data())
def test_fuzzed_files_are_read_or_refused_in_one_line(tmp_path, name, data):
    """Budget: 60 examples per text layout (about 10 s each on a loaded machine). Every outcome is a record or a
    DataFileError of one line naming the file (and, for a place in it, "line N")."""
    f = tmp_path / "fuzz.csv"
    f.write_bytes(_mutate(_SEEDS[name](), data))
    try:
        read_measured(f, time_col=None if name == "look-ascii" else "T",
                      force_col="Shr_stress" if name == "look-ascii" else "Ff", require_x=False,
                      contact_area=1e-4)
    except DataFileError as e:
        msg = str(e)
        assert "\n" not in msg and msg.startswith(str(f)), msg


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture],
          phases=_NO_SHRINK)
@given(cells=st.lists(st.one_of(st.none(), st.floats(allow_nan=True), st.text(st.characters(min_codepoint=32), max_size=5)), min_size=3,
                      max_size=12), row=st.integers(3, 80), col=st.integers(1, 3))
def test_fuzzed_workbooks_refused_naming_sheet_and_cell(tmp_path, cells, row, col):
    """Budget: 30 workbooks with arbitrary values written into a row of a good one."""
    openpyxl = pytest.importorskip("openpyxl")
    f = tmp_path / "fuzz.xlsx"
    xlsx_book(f)
    wb = openpyxl.load_workbook(f)
    for k, c in enumerate(cells[:col]):
        wb.active.cell(row=row, column=k + 1, value=c)
    wb.save(f)
    try:
        read_measured(f, force_col="Ff", require_x=False)
    except DataFileError as e:
        msg = str(e)
        # a place when the problem has one (a cell); a whole-record refusal (too few rows, no uniform stretch)
        # names the file
        assert "\n" not in msg and msg.startswith(str(f)), msg
        assert "sheet 'Run 1', " in msg or "data rows" in msg or "time stamps" in msg, msg


@given(data=st.data())
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture],
          phases=_NO_SHRINK)
def test_fuzzed_tdms_and_folders_exit_2_in_one_line(tmp_path, data):
    """Budget: 30 damaged TDMS files through the command line: exit 0 or 2, one line, no traceback."""
    pytest.importorskip("nptdms")
    from compare.cli import main

    f = tmp_path / "fuzz.tdms"
    tdms_file(f, n=80)
    f.write_bytes(_mutate(f.read_bytes(), data))
    out = tmp_path / "o"
    code = main(["analyze", str(f), "--force-col", "Ff", "-o", str(out)])
    assert code in (0, 2)


@pytest.mark.slow
@pytest.mark.skipif(not os.environ.get("FRICTIONNOISE_REAL_FILES"), reason="set FRICTIONNOISE_REAL_FILES to a "
                    "folder of real instrument files (none shipped)")
def test_real_files_read_or_refused_in_one_line():
    """Every file in $FRICTIONNOISE_REAL_FILES read by its layout (a Sheet with a header and rows) or refused in
    one line naming it; prints what each gave."""
    folder = Path(os.environ["FRICTIONNOISE_REAL_FILES"])
    files = sorted(p for p in folder.rglob("*") if p.is_file())
    assert files, f"{folder}: no files"
    for p in files:
        try:
            s = read_sheet(p)
            print(f"{p}: {s.layout}, {len(s.header)} columns ({', '.join(map(str, s.header))[:100]}), "
                  f"{len(s.rows)} rows, {len(s.blocks) + 1} blocks")
            assert s.rows and s.header
        except SheetError as e:
            print(f"refused: {e}")
            assert "\n" not in str(e) and str(e).startswith(str(p))


@given(data=st.data())
@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture],
          phases=_NO_SHRINK)
def test_fuzzed_stroke_folders_exit_0_or_2_in_one_line(tmp_path, data, capsys):
    """Budget: 20 folders of stroke files with one file damaged, through the command line: exit 0, or 2 with one
    line naming the folder (and the file and line when the problem has a place)."""
    from compare.cli import main

    folder = tmp_path / "strokes"
    stroke_files(folder, n=120)
    victim = folder / f"stroke_{data.draw(st.integers(1, 4)):03d}.csv"
    victim.write_bytes(_mutate(victim.read_bytes(), data))
    code = main(["analyze", str(folder), "--force-col", "Ff", "-o", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code in (0, 2) and "Traceback" not in err
    if code == 2:
        line = [ln for ln in err.splitlines() if ln.startswith("frictionnoise: error:")]
        assert len(line) == 1 and line[0].startswith(f"frictionnoise: error: {folder}"), err


def test_umt_page_command_with_x_col_cuts_strokes_at_the_position_reversals(tmp_path, capsys):
    """docs/reference/layouts/umt.md promises that `--x-col X` cuts a UMT record's strokes at the reversals of
    its position: its command, run on the generator's export, says so. The export's position is a 0.1 Hz sine over
    60 s and 50 s (with a 3 s pause between the steps): reversals every 5 s, so 11-12 strokes per step."""
    from pathlib import Path

    from compare.cli import main

    page = (Path(__file__).resolve().parents[2] / "docs" / "reference" / "layouts" / "umt.md").read_text()
    cmd = next(line for line in page.splitlines() if line.startswith("frictionnoise analyze") and "--x-col X" in line)
    raw, _, _ = umt_export()
    f = tmp_path / "run.csv"
    f.write_bytes(raw)
    args = cmd.split()[1:]
    args[args.index("run.csv")] = str(f)
    assert main(args + ["-o", str(tmp_path / "o")]) == 0
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["strokes"]["method"] == "sign of the position's derivative" and 20 <= s["strokes"]["found"] <= 24
    assert "strokes (sign of the position's derivative)" in capsys.readouterr().out


def test_blocks_on_a_resampled_grid_and_a_block_of_nan_rows(tmp_path):
    """Blocks put on one grid (--resample 0.01 s, the export's own step) span their own stamps, not the 3 s pause
    between the steps; a step whose friction column is all NaN leaves one block: no block list, no note."""
    raw, vals, _ = umt_export(n1=3000, n2=2500)
    f = tmp_path / "umt.csv"
    f.write_bytes(raw)
    d = read_measured(f, time_col="T", force_col="Ff", require_x=False, resample=0.01)
    assert [(b["start"], b["stop"]) for b in d.blocks] == [(0, 3000), (3299, 5799)]  # 29.99 s + 3 s pause + 25 s
    assert "blocks of the export" in d.note and "put on the one grid" in d.note
    lines = raw.decode("latin-1").split("\r\n")
    i = lines.index("Step No. 2")
    data = [k for k in range(i, len(lines)) if lines[k] and lines[k][0] in "-0123456789"]
    for k in data:
        cells = lines[k].split(",")
        cells[9] = "nan"
        lines[k] = ",".join(cells)
    g = tmp_path / "nan_step.csv"
    g.write_bytes("\r\n".join(lines).encode("latin-1"))
    d = read_measured(g, time_col="T", force_col="Ff", require_x=False)
    assert d.blocks == () and d.note is None and "2500 rows with NaN dropped" in d.warning
