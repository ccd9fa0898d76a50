"""`frictionnoise analyze`: measured x(t) through the pipeline; malformed files rejected with line numbers."""
import json

import numpy as np
import pytest

from compare.cli import main
from compare.io.measured import DataFileError, read_displacement_csv, read_measured, units_line
from engine_sim.shipped import SCENARIO_DIR
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
    assert main(["analyze", str(f), "--mass", "1.0", "--x-unit", "um", "--band", "5", "50", "--no-mechanisms", "-o",
                 str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["gamma"] == pytest.approx(4.0, abs=0.15)
    assert s["mean_velocity"] == pytest.approx(5e-4, rel=0.02)
    assert s["zeta_rms_m"] > 0 and (out / "figures" / "measured_CF.png").exists()


@pytest.mark.parametrize(
    "rows, match",
    [(["0.0,1.0", "0.01,abc"], "line 3: non-numeric")],
)
def test_malformed_rows_give_line_numbers(tmp_path, rows, match):
    f = tmp_path / "bad.csv"
    f.write_text("t,x\n" + "\n".join(rows) + "\n")
    with pytest.raises(DataFileError, match=match):
        read_displacement_csv(f, time_unit="s", x_unit="m")


def test_gap_and_jitter(tmp_path):
    t = np.arange(200) * 0.01
    t_gap = np.concatenate([t[:100], t[100:] + 0.5])
    f = tmp_path / "gap.csv"
    _write(f, t_gap, np.zeros(200))
    d = read_displacement_csv(f)  # a gap is a break between two uniform segments, reported where it is
    assert d.segmented and not d.resampled and [e.kind for e in d.timeline.events] == ["gap"]
    gap = d.timeline.events[0]
    assert (gap.line, gap.time, gap.size) == (102, pytest.approx(0.99), pytest.approx(0.51))
    # a stamp that steps back or repeats is a break too, with its line (compare.analysis.timeline)
    t_back = np.concatenate([t[:100], t[100:] - 0.015])
    _write(f, t_back, np.zeros(200))
    ev = read_displacement_csv(f).timeline.events
    assert [(e.kind, e.line) for e in ev] == [("backward", 102)] and ev[0].size == pytest.approx(-0.005)
    _write(f, np.concatenate([t[:100], t[100:] - 0.005]), np.zeros(200))  # one half step, then the rate again
    assert [e.kind for e in read_displacement_csv(f).timeline.events] == ["short step"]
    rng = np.random.default_rng(0)
    t_j = t + rng.uniform(-1e-4, 1e-4, 200)  # 1 % jitter
    _write(f, t_j, 1e3 * t_j, header="time_s,x")
    d = read_displacement_csv(f, x_unit="mm")
    assert d.resampled and "resampled" in d.warning and "%" in d.warning
    steps = np.diff(d.t)  # the grid step is the median step of the record
    assert np.ptp(steps) < 1e-12 and steps[0] == pytest.approx(0.01, rel=2e-3)
    # x = 1 m/s * t survives interpolation, up to the 6-decimal rounding of t in the file (5e-7 s -> 5e-7 m)
    np.testing.assert_allclose(d.x, d.t + d.x[0], atol=2e-6)


def test_cli_bad_data_is_a_one_line_error(tmp_path, capsys):
    f = tmp_path / "bad.csv"
    f.write_text("t_s,x_m\n0,1\n0.1,x\n")
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--mass", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bad.csv, line 3" in err and not out.exists()
    assert main(["analyze", str(f), "--mass", "-1", "-o", str(out)]) == 2
    assert "--mass must be positive" in capsys.readouterr().err


# ----------------------------------------------------------------------------- instrument exports
def test_shipped_um_file_is_read_in_micrometres_from_its_header(tmp_path, capsys):
    # without --x-unit the unit comes from the column name x_um (read as metres it would give v = 496 m/s). The
    # file is model I at v = 0.5 mm/s; the fitted mean velocity must be 5e-4 m/s within 2 % (200 s of a 0.1 mm
    # rms noise).
    out = tmp_path / "out"
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "--mass", "1", "--no-mechanisms", "-o",
                 str(out)]) == 0
    printed = capsys.readouterr().out
    assert "'x_um' in um (from the header)" in printed and "'time_s' in s (from the header)" in printed
    s = json.loads((out / "summary.json").read_text())
    assert s["mean_velocity"] == pytest.approx(5e-4, rel=0.02)
    assert s["units"]["x"] == {"column": "x_um", "unit": "um", "from": "header"}


def _export(path, t, cols, *, sep=";", decimal_comma=True, preamble=("Instrument: X", "Date;2024-05-01", ""),
            header=None, units=None, fmt="{:.6f}"):
    lines = list(preamble)
    lines.append(sep.join(header))
    if units is not None:
        lines.append(sep.join(units))
    for i in range(len(t)):
        cells = [fmt.format(v[i]) for v in [t] + list(cols)]
        if decimal_comma:
            cells = [c.replace(".", ",") for c in cells]
        lines.append(sep.join(cells))
    path.write_text("\n".join(lines) + "\n", encoding="latin-1")


def test_instrument_export_with_preamble_units_row_semicolons_and_decimal_commas(tmp_path):
    # The values written are read back exactly (to the 6 printed decimals), scaled by the units row
    # (ms, um in latin-1 "µm", mN); the layout is reported.
    t = np.arange(100) * 2.0  # ms
    x = np.linspace(0, 50, 100)  # um
    F = np.sin(t / 10.0) * 300  # mN
    f = tmp_path / "export.txt"
    _export(f, t, [x, F], header=["Time", "Pos", "Ff"], units=["ms", "µm", "mN"])
    d = read_measured(f, x_col="Pos", force_col="Ff")
    np.testing.assert_allclose(d.t, t * 1e-3, atol=1e-12)
    np.testing.assert_allclose(d.x, x * 1e-6, atol=1e-12)
    np.testing.assert_allclose(d.F, F * 1e-3, atol=1e-9)
    assert d.layout["separator"] == "semicolon" and d.layout["decimal_comma"]
    assert d.layout["preamble_lines"] == 2 and d.layout["header_line"] == 4 and d.layout["units_row_line"] == 5
    assert d.units["x"] == {"column": "Pos", "unit": "um", "from": "units row"}
    # the line `analyze` prints says what it skipped (docs/reference/trace_format.md: "skipped and counted")
    assert units_line(d).endswith("; 2 non-blank preamble lines above the header (line 4) skipped"), units_line(d)


def test_units_from_bracketed_headers_in_a_tab_file_and_contradictions(tmp_path):
    t = np.arange(100) * 1e-3
    f = tmp_path / "tab.tsv"
    _export(f, t, [t * 2, t * 0 + 1.5], sep="\t", decimal_comma=False, preamble=(),
            header=["t [s]", "x [mm]", "F(N)"])
    d = read_measured(f, force_col="F", x_col="x")
    assert d.units["force"]["unit"] == "N" and d.units["x"]["unit"] == "mm"
    np.testing.assert_allclose(d.x, t * 2e-3, atol=1e-12)
    with pytest.raises(DataFileError, match=r"line 1: the header gives column 'x \[mm\]' in mm but --x-unit um"):
        read_measured(f, x_col="x", x_unit="um")
    g = tmp_path / "bare.csv"
    _export(g, t, [t], sep=",", decimal_comma=False, preamble=(), header=["t", "x"])
    with pytest.raises(DataFileError, match=r"line 1: column 't' names no unit .*give --time-unit"):
        read_measured(g)
    assert read_measured(g, time_unit="s", x_unit="m").units["x"]["from"] == "argument"


def test_only_what_cannot_be_read_is_refused(tmp_path):
    # A bad cell in an unused column is fine; in a used column it is an error with the file's line number.
    t = np.arange(100) * 1e-3
    f = tmp_path / "e.csv"
    _export(f, t, [t, t], sep=",", decimal_comma=False, preamble=("meta",), header=["t_s", "x_m", "temp"])
    lines = f.read_text().splitlines()
    lines[10] = lines[10].rsplit(",", 1)[0] + ",n/a"  # the unused third column
    f.write_text("\n".join(lines) + "\n")
    assert len(read_measured(f).t) == 100
    lines[20] = lines[20].split(",")[0] + ",oops," + lines[20].split(",")[2]
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFileError, match=r"line 21: non-numeric value 'oops' in column 'x_m'"):
        read_measured(f)
    # a row with a cell more than the header (a stray separator, or a decimal comma in a comma-separated file) is
    # named, not read by position; a closing separator (an empty last cell) is none
    lines[20] = lines[21] + ",2,5"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFileError, match=r"line 21: 5 cells where the header has 3"):
        read_measured(f)
    lines[20] = lines[21] + ","
    f.write_text("\n".join(lines) + "\n")
    assert len(read_measured(f).t) == 100


# ----------------------------------------------------------------------------- force data
RECIP = "scenarios/data/reciprocating_force.txt"


@pytest.mark.parametrize("extra, method", [([], "sign of the friction force"),
                                           (["--x-col", "Position"], "sign of the position's derivative"),
                                           (["--direction-col", "Direction"], "direction column")])
def test_reciprocating_force_exponent_and_strokes(tmp_path, extra, method):
    # scenarios/data/README.md: C_F ~ omega^-1.2 by construction; 10 strokes in the file, 8 full and 2 partial
    # (5 s of 12 s each, so 2.6 s remain after the 1.2 s cuts: below 80 % of the median, dropped).
    if not extra:  # the whole command once, report included
        out = tmp_path / "out"
        assert main(["analyze", RECIP, "--force-col", "Ff", "--normal-col", "Fn", "--speed", "2.5e-3", "--mass", "1",
                     "-o", str(out)] + extra) == 0
        s = json.loads((out / "summary.json").read_text())
    else:  # the other stroke finders through the same analysis, without drawing the report's figures again (4 s)
        from compare.report.measured_report import analyze_force

        cols = {"--x-col": "x_col", "--direction-col": "direction_col"}
        data = read_measured(RECIP, force_col="Ff", normal_col="Fn", require_x=False, **{cols[extra[0]]: extra[1]})
        s = analyze_force(data, speed=2.5e-3, mass=1.0).summary()
    st = s["strokes"]
    assert st["method"] == method and st["found"] == 10 and st["used"] == 8 and len(st["dropped"]) == 2
    assert st["cut_each_end_s"] == pytest.approx(1.2, abs=0.01)  # 10 % of the 12 s stroke
    f = s["fit_F"]
    assert abs(f["gamma"] - 1.2) <= f["gamma_err"], f
    assert f["gamma_err"] < 0.25 and f["band"][1] / f["band"][0] >= 10
    assert s["stroke_length_m"] == pytest.approx(0.030, rel=0.01)
    # mu = F/N with N = 10 N +- 0.1 %: the same exponent within its interval; the free-block C_x is C_F/(M^2 w^4)
    assert abs(s["fit_mu"]["gamma"] - 1.2) <= s["fit_mu"]["gamma_err"]
    assert s["equivalent_free_block_Cx"]["fit"]["gamma"] == pytest.approx(f["gamma"] + 4, abs=1e-9)
    assert "eq. (3)" in s["equivalent_free_block_Cx"]["label"]


def test_continuous_force_series(tmp_path, capsys):
    # A pin-on-disc record: F = 5 N + noise with C_F ~ omega^-1 (tests.synthetic.pink_noise), 2^16 samples at
    # 1 kHz in mN. One stroke (the force never changes sign), no cut; --mass not needed.
    from tests.synthetic import pink_noise
    n = 2**16
    t = np.arange(n) * 1e-3
    F = 5000.0 + 50.0 * pink_noise(n, seed=11) / pink_noise(n, seed=11).std()
    f = tmp_path / "pod.csv"
    _export(f, t, [F], sep=",", decimal_comma=False, preamble=(), header=["time_s", "Ff [mN]"], fmt="{:.4f}")
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--force-col", "Ff", "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["strokes"]["found"] == 1 and s["strokes"]["used"] == 1 and s["strokes"]["cut_each_end_s"] == 0
    # the label is one phrase: "strokes (one stroke: no reversal in ...)", no parenthesis inside a parenthesis
    assert s["strokes"]["method"] == "one stroke: no reversal in the sign of the friction force"
    assert "strokes (one stroke: no reversal in the sign of the friction force): 1 found" in capsys.readouterr().out
    assert abs(s["fit_F"]["gamma"] - 1.0) <= s["fit_F"]["gamma_err"], s["fit_F"]
    assert s["mean_abs_F_N"] == pytest.approx(5.0, rel=1e-3)
    assert "C_mu not computed" in " ".join(s["notes"])
    # without --force-col the second column is taken for x(t): its header's unit (mN) is not a displacement unit
    assert main(["analyze", str(f), "-o", str(tmp_path / "o2")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'Ff [mN]' is in mN" in err and not (tmp_path / "o2").exists(), err


def test_stroke_averaged_whittle_interval_covers_over_seeds():
    # The data set's generator with 30 other seeds, 8 used strokes each: the Whittle interval, whose Fisher
    # information counts the 8 averaged periodograms, must cover 1.2 in >= 25 of 30 (P(<= 24) = 0.3 % at 95 %
    # coverage), the mean estimate within 3 standard errors of 1.2, and the half-width / 1.96 must match the
    # scatter within 35 % (the sd of 30 values is uncertain by 13 %). Measured: 28/30, bias +0.012, ratio 0.85.
    import importlib.util
    from compare.io.measured import MeasuredData
    from compare.report.measured_report import analyze_force
    spec = importlib.util.spec_from_file_location("make_reciprocating", SCENARIO_DIR / "data" / "make_reciprocating.py")
    mr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mr)
    est, err = [], []
    for seed in range(30):
        t, _, F, _, d = mr.make(seed)
        data = MeasuredData(t=t, x=None, source="mc", resampled=False, warning=None, n_rows=len(t), F=F,
                            direction=d.astype(float))
        a = analyze_force(data, method="whittle")
        assert len(a.strokes.segments) == 8 and a.C_F.periodogram_count == 8
        est.append(a.fit_F.gamma)
        err.append(a.fit_F.gamma_err)
    est, err = np.array(est), np.array(err)
    assert np.sum(np.abs(est - 1.2) <= err) >= 25
    assert abs(est.mean() - 1.2) < 3 * est.std(ddof=1) / np.sqrt(30)
    assert np.mean(err) / 1.96 == pytest.approx(est.std(ddof=1), rel=0.35)


# ----------------------------------------------------------------------------- x(t) without a mass
GAMMA, V, DT, N = 4.5, 5e-4, 1e-2, 2**12  # a gamma between the experiments' 4 and 5; 0.5 mm/s; 100 Hz for 41 s


def _record(seed, n=N):
    from compare.analysis.synthetic import power_law_record

    t = np.arange(n) * DT
    z = power_law_record(n, DT, GAMMA, seed=seed)  # a sampled omega^-4.5 process: folded at Nyquist, as a sensor's
    return t, V * t + 1e-6 * z / z.std()  # zeta of 1 um rms over the window


@pytest.mark.parametrize("method", ["record", "whittle", "lsq"])
def test_gamma_of_x_without_a_mass_covers_the_truth_over_seeds(method):
    # A sampled omega^-4.5 process with a drift, line-removed by analyze, 20 seeds of 2^12 samples (a lab's length):
    # the 95 % interval must hold 4.5 in >= 15 of 20 (P(<= 14) = 0.3 % at the nominal 95 % coverage) and the mean
    # estimate lie within 3 standard errors of 4.5. Measured: record 19/20, mean 4.497 (s.e. 0.008); the band fits,
    # flagged on every record (their band is under a decade), whittle 18/20, 4.70 (0.16), lsq 20/20, 4.56 (0.10).
    from compare.analysis.displacement import C_F_NEEDS_MASS, analyze_displacement

    est, hit = [], 0
    for seed in range(20):
        a = analyze_displacement(*_record(seed), method=method)
        est.append(a.fit.gamma)
        hit += abs(a.fit.gamma - GAMMA) <= a.fit.gamma_err
        assert a.fit.method == method and a.C_F is None and a.fit_F is None and a.notes == [C_F_NEEDS_MASS]
        # C_mu = omega^4 C_x / g^2 (section 2): the same fit shifted by 4, whatever the mass
        assert a.fit_mu.gamma == pytest.approx(a.fit.gamma - 4, abs=1e-9) and a.fit_mu.band == a.fit.band
        assert a.mean_velocity == pytest.approx(V, rel=1e-3)  # 1 um of noise over 0.16 m of travel
    est = np.array(est)
    assert hit >= 15, (hit, est)
    assert abs(est.mean() - GAMMA) < 3 * est.std(ddof=1) / np.sqrt(len(est))


def test_a_mass_adds_C_F_and_changes_nothing_else():
    # eq. (3): C_F = M^2 omega^4 C_x, so the force exponent is gamma - 4 exactly; gamma, C_x and C_mu are the
    # same numbers, bit for bit, with or without the mass, at any length: 2^12 samples (the test's two record-model
    # fits take 1.5 s of CPU, 10 s at 2^15).
    from compare.analysis.displacement import analyze_displacement
    from compare.analysis.spectra import rms_from_spectrum

    t, x = _record(0, n=2**12)
    bare, heavy = analyze_displacement(t, x), analyze_displacement(t, x, mass=2.0)
    assert heavy.fit == bare.fit and np.array_equal(heavy.C_x.C, bare.C_x.C) and np.array_equal(heavy.C_mu.C, bare.C_mu.C)
    assert heavy.zeta_rms == bare.zeta_rms and heavy.mu_rms == bare.mu_rms and heavy.notes == []
    np.testing.assert_allclose(heavy.C_F.C, 4.0 * heavy.C_x.omega**4 * heavy.C_x.C, rtol=1e-12)
    assert heavy.fit_F.gamma == pytest.approx(bare.fit.gamma - 4, abs=1e-9)
    assert heavy.F_rms == rms_from_spectrum(heavy.C_F, band=heavy.rms_band)  # over the fitted band, as mu_rms
    assert "fit_F" in heavy.summary() and "fit_F" not in bare.summary()
    with pytest.raises(ValueError, match="mass must be positive"):
        analyze_displacement(t, x, mass=float("nan"))


def test_cli_x_in_micrometres_without_a_mass(tmp_path, capsys, monkeypatch):
    # `frictionnoise analyze x_um.csv --x-unit um --time-unit s`: no mass, exit 0, gamma and C_x; the summary is the
    # Python analysis of the same file; C_F is said to need --mass, not computed. One record, so the check on the
    # truth is at 1.5 half-widths (2.9 sigma, a 0.4 % chance of a false failure).
    from compare.analysis.displacement import C_F_NEEDS_MASS, analyze_displacement

    t, x = _record(0)
    monkeypatch.chdir(tmp_path)
    with open("x_um.csv", "w") as fh:  # full double precision: the record's high-frequency noise is ~1e-7 um
        fh.write("t,x\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, x * 1e6)))
    assert main(["analyze", "x_um.csv", "--x-unit", "um", "--time-unit", "s", "--no-mechanisms"]) == 0
    printed = capsys.readouterr().out
    assert "gamma = " in printed and "C_F not computed" in printed and "--mass" in printed
    out = tmp_path / "analyze-x_um"
    s = json.loads((out / "summary.json").read_text())
    a = analyze_displacement(read_measured("x_um.csv", x_unit="um", time_unit="s"))
    assert (s["gamma"], s["gamma_err"], s["zeta_rms_m"]) == (a.fit.gamma, a.fit.gamma_err, a.zeta_rms)
    # zeta_rms integrates the resolved band (eq. 4), which the summary and the printed line name
    from compare.analysis.spectra import rms_from_spectrum

    assert s["zeta_rms_band"] == [a.C_x.omega_min, a.C_x.omega_max]
    assert rms_from_spectrum(a.C_x, band=tuple(s["zeta_rms_band"])) == pytest.approx(s["zeta_rms_m"], rel=1e-12)
    lo, hi = s["zeta_rms_band"]
    assert f"zeta_rms = {s['zeta_rms_m']:.4g} m over {lo:.3g}-{hi:.4g} rad/s (eq. 4)" in printed, printed
    assert abs(s["gamma"] - GAMMA) <= 1.5 * s["gamma_err"], s["fit"]
    assert s["mass_kg"] is None and "fit_F" not in s and s["notes"] == [C_F_NEEDS_MASS]
    assert s["fit_mu"]["gamma"] == pytest.approx(s["gamma"] - 4, abs=1e-9)
    assert sorted(p.name for p in (out / "figures").iterdir()) == ["measured_Cmu.png", "measured_Cx.png"]
    html = (out / "index.html").read_text()
    assert "needs the block mass" in html and "<title>frictionnoise analyze: x_um.csv</title>" in html
    # --method lsq for displacement data (it was refused), and --mass adds C_F's exponent, gamma - 4
    assert main(["analyze", "x_um.csv", "--x-unit", "um", "--time-unit", "s", "--method", "lsq", "--mass", "2",
                 "-o", "lsq"]) == 0
    s = json.loads((tmp_path / "lsq" / "summary.json").read_text())
    assert s["fit"]["method"] == "lsq" and abs(s["gamma"] - GAMMA) <= 1.5 * s["gamma_err"], s["fit"]
    assert s["fit_F"]["gamma"] == pytest.approx(s["gamma"] - 4, abs=1e-9) and s["mass_kg"] == 2.0
    assert (tmp_path / "lsq" / "figures" / "measured_CF.png").exists()


@pytest.mark.parametrize("method", ["whittle", "lsq"])
def test_shipped_model_I_file_without_a_mass(tmp_path, method):
    # scenarios/data/README.md: model I's displacement, omega^-4 between 10 v/a and omega_c/10 (5-50 rad/s, eq. 6).
    # Measured: whittle 4.001 +- 0.088, lsq 4.008 +- 0.110.
    out = tmp_path / "out"
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "--band", "5", "50", "--method", method,
                 "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert abs(s["gamma"] - 4.0) <= s["gamma_err"] and s["fit"]["method"] == method, s["fit"]
    assert s["mean_velocity"] == pytest.approx(5e-4, rel=0.02) and s["zeta_rms_m"] > 0 and s["mu_rms"] > 0


def test_latin1_export_with_crlf_reads_on_the_command_line(tmp_path, capsys):
    # an instrument's 8-bit export: the micro sign as latin-1 byte 0xB5 in the header, CRLF line ends. The record is
    # a steady 10 um/s slide, so the mean velocity must read 1e-5 m/s (the header's um taken, not m); a binary file
    # (control bytes throughout) stays refused
    t = np.arange(4000) * 0.01
    x = 10.0 * t + 0.01 * np.sin(3.0 * t)
    f = tmp_path / "x_micro.csv"
    f.write_bytes(("time (s),x (\u00b5m)\r\n" + "".join(f"{a:.4f},{b:.6f}\r\n" for a, b in zip(t, x))).encode("latin-1"))
    out = tmp_path / "out"
    assert main(["analyze", str(f), "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["mean_velocity"] == pytest.approx(1e-5, rel=1e-3)
    b = tmp_path / "noise.bin"
    b.write_bytes(bytes(range(1, 256)) * 20)  # not UTF-8, and 25 % control bytes read as latin-1
    assert main(["analyze", str(b), "-o", str(tmp_path / "out2")]) == 2
    assert "binary data" in capsys.readouterr().err


def test_shipped_model_I_file_by_the_record_model(tmp_path, capsys, monkeypatch):
    # Model I's spectrum is omega^-2 below v/a = 0.5 rad/s, bumps near 2 rad/s (the renewal closure) and rises over
    # omega^-4 above about 60 rad/s (the block's resonance at 548 rad/s folded to 80 rad/s by the 100 Hz sampling),
    # with a local exponent within 0.01 of 4 only between about 4 and 40 rad/s in the theory of the parameters that
    # made the file. Without --band the record model must find such a band: the split test cuts the record where the
    # spectrum changes, and the fit over the kept band with the most frequencies holds 4 in its 95 % interval, with
    # no flag (3.98 +- 0.12 over 3.1-31 rad/s measured; the whole record's best power law is 3.89 +- 0.03). Over
    # 2-60 rad/s given by --band the interval must hold 4 as well.
    from compare.cli import commands

    assert commands.PROGRESS_SAMPLES == 2**15  # the measured-data tutorial: progress from 2^15 samples
    monkeypatch.setattr(commands, "PROGRESS_SAMPLES", 0)  # a long record's progress lines, on this short one
    out = tmp_path / "out"
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "-o", str(out)]) == 0
    f = json.loads((out / "summary.json").read_text())["fit"]
    assert f["method"] == "record" and f["power_law"] and not f["flags"] and f["decades"] >= 1.0 - 1e-3, f
    assert f["gamma_interval"][0] <= 4.0 <= f["gamma_interval"][1], f
    cap = capsys.readouterr()
    assert "gamma = " in cap.out
    assert "fitting the exponent" in cap.err and "fitting model_I's family" in cap.err  # progress, on stderr
    html = (out / "index.html").read_text()
    # the ranking is on the page, ahead of the exponent's section
    assert "Mechanisms: which model explains the record" in html
    assert html.index("Mechanisms: which model") < html.index("Measured displacement")
    assert main(["analyze", "scenarios/data/model1_synthetic_um.csv", "--band", "2", "60", "--no-mechanisms", "-o",
                 str(out)]) == 0
    f = json.loads((out / "summary.json").read_text())["fit"]
    assert f["gamma_interval"][0] <= 4.0 <= f["gamma_interval"][1] and f["power_law"], f


@pytest.mark.parametrize("values, match", [
    (lambda t, rng: np.full(len(t), 12.5), "x is constant"),
    (lambda t, rng: np.round(0.3 * np.cumsum(rng.standard_normal(len(t)))), "at the file's resolution"),
])
def test_a_channel_without_a_spectrum_is_one_line_exit_2(tmp_path, capsys, values, match):
    # A saturated or disconnected sensor (constant), and a record written at the file's resolution (a random walk
    # of 0.3 um steps written in whole um: most rows repeat the one before): one line, exit 2, nothing written.
    t = np.arange(4000) * 0.01
    path = tmp_path / "x_um.csv"
    _write(path, t, values(t, np.random.default_rng(0)))
    out = tmp_path / "out"
    assert main(["analyze", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert match in err and len(err.splitlines()) == 1 and not out.exists(), err


def test_a_record_in_pieces_says_why_it_is_fitted_by_least_squares(tmp_path, capsys):
    # a gap cuts a model I record into two uniform pieces: their combined Welch spectrum keeps no single periodogram,
    # so neither the record model nor the Whittle fit applies; the terminal and summary.json say so under the fit
    tr = simulate(SpringBlockParams.reference(), 120.0, dt_out=2e-3, seed=2)
    t = np.concatenate([tr.t[:30000], tr.t[30000:] + 1.0])  # a 1 s gap in the middle
    f = tmp_path / "pieces.csv"
    _write(f, t, 1e6 * tr.x)
    assert main(["analyze", str(f), "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "lsq" in out and "fitted by least squares" in out and "pieces or strokes" in out
    fit = json.loads((tmp_path / "out" / "summary.json").read_text())["fit"]
    assert fit["method"] == "lsq" and any("least squares" in note for note in fit["notes"])


def test_summary_units_preamble_and_gravity(tmp_path):
    # an instrument export: six "#" comment lines, the header, a units row; the layout counts the comment lines as
    # the preamble the file holds; the record fit's dimensional fields carry their units; C_mu's g is standard
    # gravity, the constant the reader converts a gram-force by
    from compare.analysis.synthetic import power_law_record
    from engine_sim.quantities import STANDARD_GRAVITY as READER_G, parse_unit
    from frictionnoise.base import STANDARD_GRAVITY

    n = 4096
    x = power_law_record(n, 1e-3, 4.0, prefactor=1e-10, seed=0)
    f = tmp_path / "rig.csv"
    head = ["# TriboRig export", "# Operator: lab", "# Date: today", "# Sample rate: 1000 Hz", "# Channel 1: LVDT", "#"]
    f.write_text("\n".join(head + ["Time,Displacement", "s,um"]
                           + [f"{i * 1e-3:.3f},{v * 1e6:.6f}" for i, v in enumerate(x)]) + "\n")
    d = read_measured(f)
    assert d.layout["preamble_lines"] == 6 and d.layout["comment_lines"] == 6 and d.layout["header_line"] == 7
    assert units_line(d).endswith("; 6 non-blank preamble lines above the header (line 7) skipped")
    out = tmp_path / "out"
    assert main(["analyze", str(f), "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    units = s["fit"]["units"]
    assert units["floor"] == "m^2 s" and units["floor_rms"] == "m" and units["crossover"] == "rad/s"
    assert units["prefactor"] == "m^2 s (rad/s)^gamma" and s["fit_mu"]["units"]["prefactor"] == "s (rad/s)^gamma"
    assert s["g_m_per_s2"] == STANDARD_GRAVITY == READER_G == 9.80665
    assert parse_unit("g", ("force",)).factor == pytest.approx(1e-3 * s["g_m_per_s2"], rel=1e-12)
    from compare.analysis.displacement import analyze_displacement

    fit = analyze_displacement(d).fit
    assert " m rms" in str(fit) or "no white floor" in str(fit)


def test_analyze_discrete_fits_a_simulated_random_walk_and_is_refused_where_it_does_not_apply(tmp_path, capsys):
    # a double sum of white noise (a simulation written step by step) in a file: `--discrete` fits its spectrum's own
    # form (2 sin(omega dt / 2) / dt)^-4 and says so (summary.json's notes); the default folded law reads it with a
    # floor near Nyquist and a note naming --discrete (compare.analysis.record_model; the fits page's numbers:
    # tests/compare/test_record_model.py); on force data or a band fit the option is refused, one line, exit 2
    rng = np.random.default_rng(0)
    n = 4096
    t = 1e-2 * np.arange(n)
    f = tmp_path / "walk.csv"
    _write(f, t, 1e-3 * t + 1e-3 * np.cumsum(np.cumsum(rng.standard_normal(n))))
    runs = {}
    for name, extra in (("folded", []), ("discrete", ["--discrete"])):
        assert main(["analyze", str(f), "--no-mechanisms", "-o", str(tmp_path / name)] + extra) == 0
        runs[name] = json.loads((tmp_path / name / "summary.json").read_text())["fit"]
    capsys.readouterr()
    assert runs["discrete"]["gamma_interval"][0] <= 4 <= runs["discrete"]["gamma_interval"][1]
    assert runs["discrete"]["band_end"] != "floor"
    assert any(s.startswith("fitted as a discrete-time process") for s in runs["discrete"]["notes"])
    assert runs["folded"]["band_end"] == "floor" and any("--discrete" in s for s in runs["folded"]["notes"])
    for extra, match in ((["--method", "lsq"], "--discrete applies to the record model"),
                         (["--force-col", "x_um"], "--discrete applies to displacement data")):
        assert main(["analyze", str(f), "--discrete", "-o", str(tmp_path / "no")] + extra) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and match in err and not (tmp_path / "no").exists()


def test_a_dropped_row_leaves_the_record_model_on_the_longest_piece(tmp_path, capsys):
    # one row missing at line 900 of 2^14 (an omega^-4 record at 1 kHz): the longest uniform piece holds 95 % of the
    # samples, so the record model fits it alone and says so (compare.analysis.displacement.PIECE_SHARE), with the
    # interval of a record of its length (half-width about 0.02 here, not the band fit of the pieces' combined
    # spectrum, which the short piece's window would hold to half a decade); with the gap in the middle the pieces'
    # spectrum is fitted by least squares as before, unless the record model is asked for
    from compare.analysis.synthetic import power_law_record

    n, dt = 2**14, 1e-3
    x = power_law_record(n, dt, 4.0, seed=0)
    t = np.arange(n) * dt
    for name, drop in (("end", 899), ("middle", n // 2)):
        keep = np.ones(n, bool)
        keep[drop] = False
        _write(tmp_path / f"{name}.csv", t[keep], 1e6 * x[keep])
    assert main(["analyze", str(tmp_path / "end.csv"), "--no-mechanisms", "-o", str(tmp_path / "a")]) == 0
    fit = json.loads((tmp_path / "a" / "summary.json").read_text())["fit"]
    assert fit["method"] == "record" and fit["n_samples"] == n - 900 and fit["decades"] > 3
    assert fit["gamma_interval"][0] <= 4 <= fit["gamma_interval"][1] and fit["gamma_err"] < 0.05
    assert any("fitted to the longest, data rows 900-16383 (15484 of 16383 samples, 95 %)" in s for s in fit["notes"])
    assert "the record model was fitted to the longest" in capsys.readouterr().out
    assert main(["analyze", str(tmp_path / "middle.csv"), "--no-mechanisms", "-o", str(tmp_path / "b")]) == 0
    assert json.loads((tmp_path / "b" / "summary.json").read_text())["fit"]["method"] == "lsq"
    assert main(["analyze", str(tmp_path / "middle.csv"), "--method", "record", "--no-mechanisms",
                 "-o", str(tmp_path / "c")]) == 0
    fit = json.loads((tmp_path / "c" / "summary.json").read_text())["fit"]
    assert fit["method"] == "record" and fit["n_samples"] == n // 2  # the first piece, rows 1-8192


def test_the_ranking_says_which_speed_it_used_and_when_the_record_speeds_up():
    # summary.json's speed: the record's mean speed from its ends, the halves' mean speeds, and a note where they
    # differ by more than a factor 2 (here 1 and 3 m/s: a record that accelerates); --speed replaces it, no note
    from types import SimpleNamespace

    from compare.cli.mechanisms import SPEED_RATIO, _speed, ranking_lines

    t = np.arange(1001) * 1e-3
    data = SimpleNamespace(t=t, x=np.where(t < 0.5, t, 0.5 + 3 * (t - 0.5)))
    sp = _speed(data, 2.0, None)
    assert sp["halves"] == pytest.approx([1.0, 3.0]) and SPEED_RATIO < 3
    assert "first half and 3 m/s over its second" in sp["note"] and "--speed" in sp["note"]
    lines = ranking_lines({"mechanisms": [], "mechanisms_note": "none", "speed": sp})
    assert "sliding speed 2 m/s (the record's mean speed (its ends))" in lines and lines[-1].startswith("NOTE: ")
    assert _speed(SimpleNamespace(t=t), 2.0, None)["halves"] == []  # a record without positions: no halves
    stated = _speed(data, 2.0, 0.1)
    assert stated["value"] == 0.1 and stated["source"] == "--speed" and "note" not in stated
    steady = _speed(SimpleNamespace(t=t, x=t), 1.0, None)
    assert "note" not in steady


@pytest.mark.slow  # two identifications of a 20 s record (about 30 s at load 3)
def test_speed_states_the_drive_of_a_record_that_drifts(tmp_path):
    # Model III's record (w = 1 cm, v = 0.1 m/s, N = 100) holds v t plus a fluctuation whose mean force is not the
    # drive's, so the block drifts backward (-0.9 m/s over 20 s): from its ends no sliding speed, no mechanism; with
    # the drive's speed stated, its own family fits and places the window within 1 % (its interval: 1e-5)
    import reduced_models as rm

    p = rm.asperity_force.AsperityForceParams(v=0.1, N=100.0)
    tr = rm.asperity_force.simulate(p, 20.0, 1e-3, seed=0)
    f = tmp_path / "m3.csv"
    _write(f, tr.t, tr.x * 1e6)
    out = tmp_path / "out"
    assert main(["analyze", str(f), "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["mechanisms"] == [] and "--speed" in s["mechanisms_note"] and s["speed"]["value"] < 0
    assert main(["analyze", str(f), "--speed", "0.1", "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["speed"]["source"] == "--speed" and s["mechanisms"][0]["model"] == "model_III"
    assert s["mechanisms"][0]["verdict"] == "fits"
    assert s["mechanisms"][0]["parameters"]["w"][0] == pytest.approx(p.w, rel=1e-2)
