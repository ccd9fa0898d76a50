"""`frictionnoise analyze`: measured x(t) through the pipeline; malformed files rejected with line numbers."""
import json

import numpy as np
import pytest

from compare.cli import main
from compare.measured import DataFileError, read_displacement_csv
from reduced_models.spring_block import SpringBlockParams, simulate


def _write(path, t, x_um, header="time_s,x_um"):
    with open(path, "w") as fh:
        fh.write(header + "\n")
        for a, b in zip(t, x_um):
            fh.write(f"{a:.6f},{b:.6f}\n")


def test_analyze_recovers_gamma_4_from_a_model_I_csv_in_micrometres(tmp_path):
    # Model I reference, 600 s sampled at 100 Hz (Nyquist 314 rad/s), written in um with 1e-6 um precision
    # (the zeta noise is ~1e-5 um at 50 rad/s, so 6 decimals keep it). The fit over 5-50 rad/s
    # (10 v/a to omega_c/10) must read 4 +- 0.15.
    tr = simulate(SpringBlockParams.reference(), 600.0, 1e-2, seed=3)
    f = tmp_path / "sensor.csv"
    _write(f, tr.t, tr.x * 1e6)
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--mass", "1.0", "--x-unit", "um", "--band", "5", "50", "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["gamma"] == pytest.approx(4.0, abs=0.15)
    assert s["mean_velocity"] == pytest.approx(5e-4, rel=0.02)
    assert s["zeta_rms_m"] > 0 and (out / "figures" / "measured_CF.png").exists()


@pytest.mark.parametrize(
    "rows, match",
    [(["0.0,1.0", "0.01,abc"], "line 3: non-numeric"),
     (["0.0,1.0", "0.01,1.0", "0.005,1.0"], "line 4: time 0.005 does not increase"),
     (["0.0,1.0", "0.01,1.0", "0.01,2.0"], "line 4: time 0.01 does not increase")],
)
def test_malformed_rows_give_line_numbers(tmp_path, rows, match):
    f = tmp_path / "bad.csv"
    f.write_text("t,x\n" + "\n".join(rows) + "\n")
    with pytest.raises(DataFileError, match=match):
        read_displacement_csv(f)


def test_gap_and_jitter(tmp_path):
    t = np.arange(200) * 0.01
    t_gap = np.concatenate([t[:100], t[100:] + 0.5])
    f = tmp_path / "gap.csv"
    _write(f, t_gap, np.zeros(200))
    with pytest.raises(DataFileError, match=r"line 102: gap of 0.51 s"):
        read_displacement_csv(f)
    rng = np.random.default_rng(0)
    t_j = t + rng.uniform(-1e-4, 1e-4, 200)  # 1 % jitter
    _write(f, t_j, 1e3 * t_j)
    d = read_displacement_csv(f, x_unit="mm")
    assert d.resampled and "resampled" in d.warning and "%" in d.warning
    steps = np.diff(d.t)  # the grid step is the median step of the record
    assert np.ptp(steps) < 1e-12 and steps[0] == pytest.approx(0.01, rel=2e-3)
    # x = 1 m/s * t survives interpolation, up to the 6-decimal rounding of t in the file (5e-7 s -> 5e-7 m)
    np.testing.assert_allclose(d.x, d.t + d.x[0], atol=2e-6)


def test_cli_bad_data_is_a_one_line_error(tmp_path, capsys):
    f = tmp_path / "bad.csv"
    f.write_text("t,x\n0,1\n0.1,x\n")
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--mass", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bad.csv, line 3" in err and not out.exists()
    assert main(["analyze", str(f), "--mass", "-1", "-o", str(out)]) == 2
    assert "--mass must be positive" in capsys.readouterr().err
