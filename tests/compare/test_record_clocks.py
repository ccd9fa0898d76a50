"""Clocks and rows as loggers write them: a jittering clock told from gaps, NaN rows dropped and counted, and line
numbers as ``grep -n`` counts them whatever the line ends."""
import subprocess

import numpy as np
import pytest

from compare.io.measured import DataFileError, read_measured
from engine_sim.profile_file import ProfileError, read_line_scan


def test_jittering_clock_is_one_line_and_no_gaps(tmp_path, capsys):
    """A logger whose step wanders +-15 % around 0.156 s (0.133-0.179 s) drops no sample: no break, one line
    with the steps' range and spread, --resample named, the resampling in the record's provenance."""
    from compare.cli import main

    rng = np.random.default_rng(7)
    t = np.concatenate([[0.0], np.cumsum(0.156 * (1 + rng.uniform(-0.15, 0.15, 3000)))])
    x = 1e-3 * np.sin(t)
    f = tmp_path / "logger.csv"
    f.write_text("time (s),x (mm)\n" + "".join(f"{a:.4f},{b:.6f}\n" for a, b in zip(t, x)))
    d = read_measured(f)
    assert d.timeline.events == () and d.resampled
    assert d.warning.count("\n") == 0 and "jittering clock, no samples missing" in d.warning
    assert "--resample DT" in d.warning and d.layout["resampling"].startswith("jittering clock")
    steps = np.diff(t)
    assert f"steps {steps.min():.4g}-{steps.max():.4g} s" in d.warning
    assert main(["analyze", str(f), "-o", str(tmp_path / "o")]) == 0
    io = capsys.readouterr()
    assert "gap" not in io.out + io.err and io.err.count("jittering clock") == 1


def test_nan_rows_are_dropped_and_counted(tmp_path):
    t = 0.01 * np.arange(300)
    rows = [f"{a:.2f},{np.sin(a):.6f}" for a in t]
    for i in (50, 51, 200):
        rows[i] = f"{t[i]:.2f},NaN"
    f = tmp_path / "nan.csv"
    f.write_text("t_s,x_m\n" + "\n".join(rows) + "\n")
    d = read_measured(f)
    assert d.n_rows == 297 and d.layout["nan_rows_dropped"] == 3 and d.layout["nan_places"] == ["line 52", "line 53", "line 202"]
    assert "3 rows with NaN dropped (line 52, line 53, line 202)" in d.warning
    # the rows dropped leave gaps in the time stamps: the record is split there, each piece analysed
    assert [e.kind for e in d.timeline.events] == ["gap", "gap"] and d.segmented
    rows[100] = f"{t[100]:.2f},inf"
    f.write_text("t_s,x_m\n" + "\n".join(rows) + "\n")
    with pytest.raises(DataFileError, match=r"line 102: infinite value in column 'x_m'"):
        read_measured(f)


def _grep_n(path, needle):
    out = subprocess.run(["grep", "-n", needle, str(path)], capture_output=True, text=True, check=True).stdout
    return int(out.split(":", 1)[0])


@pytest.mark.parametrize("end", ["\r\n", "\r\r\n", "\n"])
def test_line_numbers_are_grep_n_numbers(tmp_path, end):
    pre = ["Scan Parameters", "Resolution,0.156,um", "", "Lateral (um),Total Profile (nm)"]
    rows = [f"{0.156 * i:.3f},{10.0 + i % 7:.1f}" for i in range(40)]
    rows[30] = "0.000,oops"
    f = tmp_path / "scan.csv"
    f.write_bytes(end.join(pre + rows + [""]).encode())
    with pytest.raises(ProfileError) as e:
        read_line_scan(f)
    assert f": line {_grep_n(f, 'oops')}:" in str(e.value)
    g = tmp_path / "log.csv"
    g.write_bytes(end.join(["run 1", "t (s),x (mm)"] + [f"{0.01 * i:.2f},{i}" for i in range(100)]
                           + ["0.99,zz", ""]).encode())
    with pytest.raises(DataFileError) as e:
        read_measured(g)
    assert f", line {_grep_n(g, 'zz')}:" in str(e.value)


@pytest.mark.parametrize("target", ["/proc/frictionnoise-out", "/proc/self/out", "FILE/out"])
def test_unwritable_output_refused_before_reading(tmp_path, capsys, target):
    """-o into /proc, under a file, ...: one line, exit 2, before the record is read (a file that does not
    exist is not named: the output is checked first)."""
    from compare.cli import main

    f = tmp_path / "f"
    f.write_text("x")
    target = target.replace("FILE", str(f))
    assert main(["analyze", str(tmp_path / "missing.csv"), "-o", target]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"frictionnoise: error: {target}: ") and "Traceback" not in err
