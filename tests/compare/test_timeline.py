"""Records as recorders write them: time stamps that change rate, skip, repeat or step back are found and reported
(row, time, size); the uniform stretches are analysed on their own and together, or resampled on request behind a
stated filter; a periodic (stick-slip) record is flagged, not fitted as a power law."""
import json

import numpy as np
import pytest

from compare.analysis.fits import fit_power_law
from compare.analysis.segments import line_power_flag, resample_record, segment_spectra
from compare.analysis.spectra import displacement_spectrum
from compare.analysis.timeline import find_segments
from compare.cli.main import main
from compare.io.measured import read_measured

BAND = (2 * np.pi * 2, 2 * np.pi * 50)  # rad/s: well inside every segment's resolved range


def test_breaks_are_found_where_they_are():
    t1 = np.arange(2000) * 1e-3  # 1 kHz for 2 s
    t2 = 2.0 + np.arange(1, 2001) * 0.5e-3  # then 2 kHz
    t3 = t2[-1] + 0.3 + np.arange(2000) * 0.5e-3  # a step of 0.3 s where 0.5 ms was the rule
    t4 = np.concatenate([t3[-1:], t3[-1] + np.arange(1, 101) * 0.5e-3])  # the last stamp written twice
    t5 = t4[-1] - 0.05 + np.arange(1, 101) * 0.5e-3  # the clock steps back: 0.0495 s from the last stamp
    t = np.concatenate([t1, t2, t3, t4, t5])
    tl = find_segments(t, lines=np.arange(t.size) + 3)  # a header and a units row above the data
    kinds = [(e.kind, e.row, e.line) for e in tl.events]
    assert kinds == [("rate change", 2000, 2003), ("gap", 4000, 4003), ("repeated", 6000, 6003),
                     ("backward", 6101, 6104)]
    rc, gap, rep, back = tl.events
    assert rc.time == pytest.approx(1.999) and rc.size == pytest.approx(0.5e-3, rel=1e-9)
    assert gap.time == pytest.approx(3.0) and gap.size == pytest.approx(0.3, rel=1e-9)
    assert "about 599 samples missing" in gap.detail  # 0.3 s / 0.5 ms - 1
    assert rep.size == 0.0 and back.size == pytest.approx(-0.0495, rel=1e-9)
    assert [(s.start, s.stop) for s in tl.segments] == [(0, 2000), (2000, 4000), (4000, 6000), (6000, 6101),
                                                         (6101, 6201)]
    assert [round(1 / s.dt) for s in tl.segments] == [1000, 2000, 2000, 2000, 2000]
    # the time printed with a line is that line's stamp; the stamp before the break follows it
    assert "line 4003 at t = 3.3 s, after t = 3 s: gap" in gap.describe()
    assert "line 2003 at t = 2.0005 s, after t = 1.999 s: rate change" in rc.describe()
    assert "line 6104 at t = " in back.describe() and back.time_after == pytest.approx(t[6101])
    assert all(e.time_after == t[e.row] for e in tl.events)


def test_a_block_and_a_nan_gap_are_printed_with_the_time_of_their_line(tmp_path, capsys):
    """The UMT export's step 2 (line 6032, its first row at t = 62.99 s, the last of step 1 at 59.99 s) and three
    NaN rows dropped from a uniform 1 kHz record: each break is printed with its own line's time."""
    from tests.instrument_files import umt_export

    raw, vals, where = umt_export()
    f = tmp_path / "umt.csv"
    f.write_bytes(raw)
    assert main(["analyze", str(f), "--time-col", "T", "--force-col", "Ff", "-o", str(tmp_path / "o1")]) == 0
    out = capsys.readouterr().out
    assert f"line {where['step2_line']} at t = 62.99 s, after t = 59.99 s: block (Step No. 2" in out, out
    lines = ["time (s),F (N)"] + [f"{1e-3 * i:.3f},{'nan' if 1000 <= i < 1003 else f'{np.sin(i / 7):.5f}'}"
                                  for i in range(4000)]
    g = tmp_path / "nan.csv"
    g.write_text("\n".join(lines) + "\n")
    d = read_measured(g, force_col="F", require_x=False)
    (gap,) = d.timeline.events
    assert gap.kind == "gap" and gap.line == 1005  # the header is line 1; rows 1000-1002 on lines 1002-1004
    assert "line 1005 at t = 1.003 s, after t = 0.999 s: gap" in gap.describe()


def test_jitter_is_one_segment():
    rng = np.random.default_rng(0)
    t = np.arange(1000) * 1e-3 + rng.uniform(-1e-4, 1e-4, 1000)  # +-10 % of the step, at most 20 % step to step
    tl = find_segments(t)
    assert tl.uniform and len(tl.segments) == 1
    assert 0.1 < tl.segments[0].spread <= 0.25


def _gamma4_record(seed, n=2**17, dt=0.5e-3):
    """x = v t + zeta, zeta twice-integrated white noise: C_x ~ |2 sin(omega dt/2)/dt|^-4, i.e. omega^-4 within
    0.3 % below 314 rad/s (the fit band's top); then the first 30 s kept at 1 kHz (every other sample) and 0.7 s
    dropped at t = 45 s."""
    rng = np.random.default_rng(seed)
    x = 1e-6 * np.cumsum(np.cumsum(rng.standard_normal(n))) + 1e-3 * np.arange(n) * dt
    t = np.arange(n) * dt
    keep = np.ones(n, bool)
    keep[:60000][1::2] = False
    keep &= ~((t > 45.0) & (t < 45.7))
    return t[keep], x[keep]


def _write(f, t, x, header="t (s),x (mm)"):
    f.write_text(header + "\n" + "".join(f"{a:.6f},{b:.9f}\n" for a, b in zip(t, 1e3 * x)))


def test_segments_combined_recover_the_exponent():
    """gamma = 4 is inside the combined fit's 95 % interval on at least 4 of 5 seeds (a correct 95 % interval
    covers the truth 4 or 5 times in 5 with probability 0.977; measured: 5 of 5). The slope bias of the discrete
    spectrum over the band is below 0.01 (see _gamma4_record)."""
    inside = 0
    for seed in range(5):
        t, x = _gamma4_record(seed)
        tl = find_segments(t)
        assert [e.kind for e in tl.events] == ["rate change", "gap"]
        ss = segment_spectra(t, x, tl, quantity="x", unit="m^2 s", detrend="linear", name="x")
        assert len(ss.used) == 3
        f = fit_power_law(ss.combined, band=BAND)
        inside += abs(f.gamma - 4.0) <= f.gamma_err
        assert not f.flags and line_power_flag(ss.combined, f.band) is None  # a power law, not lines
    assert inside >= 4


def test_resampling_states_its_filter_and_keeps_the_exponent():
    t, x = _gamma4_record(0)
    tl = find_segments(t)
    tu, cols, statement = resample_record(t, {"x": x}, tl, 1e-3)
    assert np.allclose(np.diff(tu), 1e-3, rtol=0, atol=1e-12)
    assert "Butterworth, order 8, at 400 Hz" in statement and "0.7 s of gaps bridged" in statement
    f = fit_power_law(displacement_spectrum(tu, cols["x"]), band=BAND)
    assert abs(f.gamma - 4.0) <= f.gamma_err + 0.02  # the 0.7 s straight line adds a little omega^-2 power


def test_sawtooth_is_flagged_not_a_power_law():
    """Stick 0.2 s, slip 10 um in 0.02 s, repeated: the spectrum is lines at the harmonics of 4.5 Hz."""
    t = np.arange(0, 60, 1e-3)
    period = 0.22
    phase = (t % period) / period
    x = 10e-6 * (np.floor(t / period) + np.clip((phase - 0.2 / 0.22) / (0.02 / 0.22), 0, 1))
    x += 1e-9 * np.random.default_rng(0).standard_normal(t.size)  # a sensor's noise floor
    spec = displacement_spectrum(t, x)
    fit = fit_power_law(spec, band=BAND)
    flag = line_power_flag(spec, fit.band)
    assert flag is not None and "periodic record" in flag


def test_analyze_reports_segments_and_the_exponent(tmp_path, capsys):
    t, x = _gamma4_record(1)
    f = tmp_path / "rig.csv"
    _write(f, t, x)
    d = read_measured(f)
    assert [e.kind for e in d.timeline.events] == ["rate change", "gap"]
    # header on line 1; rows 0-30000 at 1 kHz (t = 0 to 30 s: the step into t = 30 s is still 1 ms), row 30001 the
    # first at 0.5 ms, on line 30003
    assert d.timeline.events[0].line == 30003
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--mass", "1.0", "--band", f"{BAND[0]}", f"{BAND[1]}", "-o", str(out)]) == 0
    io = capsys.readouterr()
    assert "line 30003 at t = 30.0005 s, after t = 30 s: rate change" in io.out + io.err and "gap" in io.out + io.err
    s = json.loads((out / "summary.json").read_text())
    assert len(s["timeline"]["events"]) == 2 and len(s["timeline"]["segments"]) == 3
    assert abs(s["gamma"] - 4.0) <= s["gamma_err"] * 1.5  # one seed: 1.5 x the 95 % half-width
    assert len(s["segment_fits"]) == 3


def test_resample_on_request(tmp_path, capsys):
    # 2^16 samples: 30 s at 1 kHz then 2.8 s at 2 kHz, steps a uniform grid must resample (the gap at 45 s is for
    # the segment tests; a file of 2^17 costs this test twice the reading and the fit)
    t, x = _gamma4_record(2, n=2**16)
    f = tmp_path / "rig.csv"
    _write(f, t, x)
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--mass", "1.0", "--resample", "0.001", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "resampled onto a uniform 0.001 s grid" in err and "Butterworth, order 8, at 400 Hz" in err
    s = json.loads((out / "summary.json").read_text())
    assert s["resampled"] and s["dt_s"] == pytest.approx(1e-3) and "segment_fits" not in s
    # force records whose stamps break: tests/compare/test_force_timeline.py


def test_one_missing_sample_is_singular():
    t = np.concatenate([np.arange(100) * 1e-3, 0.101 + np.arange(100) * 1e-3])  # one 2 ms step: 1 sample missing
    (gap,) = find_segments(t).events
    assert gap.kind == "gap" and "about 1 sample missing" in gap.detail
