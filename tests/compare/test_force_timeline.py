"""Friction-force records whose time stamps break (rate changes, gaps): every used stroke is cut where the time
line breaks, the uniform pieces are analysed on their own and together on one common window, exactly as a
displacement record's segments are; a stick-slip sawtooth is flagged, not fitted as a power law; the command line
lists the pieces, and a record without a usable uniform stretch is one line, exit 2, nothing written."""
import importlib.util
import json
from dataclasses import replace

import numpy as np
import pytest

from compare.analysis.force import analyze_force
from compare.analysis.strokes import find_strokes, stroke_spectrum
from compare.analysis.timeline import find_segments
from compare.cli.main import main
from compare.io.measured import MeasuredData
from engine_sim.shipped import SCENARIO_DIR

BAND = (2 * np.pi * 4, 2 * np.pi * 50)  # rad/s: above the lowest bin of the 0.512 s common window (12.3 rad/s)


def _record(t, F, **kw):
    """A record with its stamps as written and their time line (what compare.io.measured.read_measured returns)."""
    tl = find_segments(t)
    return MeasuredData(t=t - t[0], x=None, source="synthetic", resampled=False, warning=None, n_rows=t.size, F=F,
                        timeline=tl, **kw)


def _random_walk_force(seed, n=2**16, dt=0.5e-3):
    """F = 5 N + a random walk (integrated white noise) at 2 kHz: C_F ~ |2 sin(omega dt/2)/dt|^-2, exponent 2.
    Recorded as a rig with a rate change and a gap writes it: the first 15 s at 1 kHz (every other sample), then
    2 kHz, 0.5 s of samples lost at t = 24 s. At 1 kHz the sampled walk is a walk of step 1 ms, whose local slope
    differs from -2 by 2 x^2 / 3 at x = omega dt / 2: 0.016 at 50 Hz, so the fitted exponent over 4-50 Hz is biased
    by about -0.006, an eighth of its 95 % half-width (about 0.05)."""
    rng = np.random.default_rng(seed)
    F = 5.0 + 1e-3 * np.cumsum(rng.standard_normal(n))
    t = np.arange(n) * dt
    keep = np.ones(n, bool)
    keep[:30000][1::2] = False
    keep &= ~((t > 24.0) & (t < 24.5))
    return t[keep], F[keep]


def test_rate_change_and_gap_pieces_and_the_exponent_over_seeds():
    """The combined exponent's 95 % interval holds 2 on at least 16 of 20 seeds (a correct 95 % interval fails that
    with probability 0.3 %; measured: 19 of 20), and the mean of the 20 estimates is within 3 standard errors of 2
    plus the 0.006 sampling bias (see _random_walk_force)."""
    est, inside = [], 0
    for seed in range(20):
        t, F = _random_walk_force(seed)
        a = analyze_force(_record(t, F), band=BAND, method="lsq")
        if seed == 0:  # where the pieces are: rows, first and last stamps, steps
            rows = [(p["stroke"], p["start_row"], p["stop_row"], round(1 / p["dt_s"]), p["in_combined"])
                    for p in a.piece_fits]
            assert rows == [(1, 0, 15001, 1000, True), (1, 15001, 33001, 2000, True), (1, 33001, 49537, 2000, True)]
            assert [p["t_start_s"] for p in a.piece_fits] == pytest.approx([0.0, 15.0005, 24.5], abs=1e-9)
            assert [e.kind for e in a.data.timeline.events] == ["rate change", "gap"]
            assert a.pieces.window_s == pytest.approx(0.512)  # 1024 samples of the longest piece (18000 at 0.5 ms)
            s = a.summary()
            assert len(s["pieces"]) == 3 and s["timeline"]["events"][1]["kind"] == "gap"
            assert all(p["fit"] is not None for p in s["pieces"])  # each piece's own exponent
        f = a.fit_F
        assert not f.flags
        est.append(f.gamma)
        inside += abs(f.gamma - 2.0) <= f.gamma_err
    est = np.array(est)
    assert inside >= 16
    assert abs(est.mean() - 2.0) <= 3 * est.std(ddof=1) / np.sqrt(est.size) + 0.006


def _reciprocating(seed):
    spec = importlib.util.spec_from_file_location("make_reciprocating", SCENARIO_DIR / "data" / "make_reciprocating.py")
    mr = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mr)
    return mr.make(seed)


def test_a_gap_inside_one_stroke_drops_its_pieces_and_keeps_the_others_exactly():
    """scenarios/data/make_reciprocating.py (C_F ~ omega^-1.2, 250 Hz, strokes of 12 s: 8 full, 2 partial) with
    0.5 s of samples lost inside the fifth stroke found (t = 46.0-46.5 s; it runs 41-53 s). The stroke is still
    full on the clock (12 s) and used, but cut into two pieces shorter than the one-stroke window: both named, and
    the combined spectrum is the mean of the other 7 strokes' spectra, which the uniform record gives as they are
    (the same rows by time, the same window 2400 - k samples): equal to rounding."""
    t, _, F, Fn, d = _reciprocating(3)
    gap = (t > 46.0) & (t < 46.5)
    broken = _record(t[~gap], F[~gap], N=Fn[~gap], direction=d[~gap].astype(float))
    a = analyze_force(broken, speed=2.5e-3, method="lsq")
    st = a.strokes
    assert st.found == 10 and len(st.segments) == 8 and st.used_s == pytest.approx(9.6)
    hit = [p for p in a.piece_fits if p["stroke"] == 5]
    assert [(p["t_start_s"], p["t_stop_s"]) for p in hit] == [pytest.approx((42.2, 46.0)), pytest.approx((46.5, 51.796))]  # 9.6 s from 42.2 s, 4 ms steps
    assert not any(p["in_combined"] for p in hit) and sum(p["in_combined"] for p in a.piece_fits) == 7
    assert sum("shorter than the common window" in n for n in a.notes) == 2
    whole = MeasuredData(t=t, x=None, source="whole", resampled=False, warning=None, n_rows=t.size, F=F, N=Fn,
                         direction=d.astype(float))
    ust = find_strokes(whole)
    seven = replace(ust, segments=[s for i, s in enumerate(ust.segments) if i != 3])
    ref = stroke_spectrum(t, F, seven, "F", "N^2 s", "auto", None)
    assert np.allclose(a.C_F.omega, ref.omega, rtol=1e-9, atol=0)  # steps: the median vs t[1] - t[0]
    assert np.allclose(a.C_F.C, ref.C, rtol=1e-9, atol=0)
    f = a.fit_F
    assert abs(f.gamma - 1.2) <= f.gamma_err, f  # one seed, the exact construction's exponent
    assert abs(a.fit_mu.gamma - 1.2) <= a.fit_mu.gamma_err  # N = 10 N +- 0.1 %: C_mu has the same exponent
    assert a.C_F_distance.omega_min == pytest.approx(a.C_F.omega_min / 2.5e-3)


def test_stick_slip_sawtooth_across_a_rate_change_is_flagged():
    """Stick 0.2 s (F rising 4 -> 5 N), slip 0.02 s, repeated, written at 1 kHz then 2 kHz: lines at the harmonics
    of 4.5 Hz carry nearly all the power; the fit says it is not a power law."""
    t = np.concatenate([np.arange(0, 30, 1e-3), 30 + np.arange(1, 60001) * 0.5e-3])
    period, stick = 0.22, 0.2
    ph = t % period
    F = np.where(ph < stick, 4.0 + ph / stick, 5.0 - (ph - stick) / (period - stick))
    F += 1e-4 * np.random.default_rng(0).standard_normal(t.size)  # a load cell's noise floor
    a = analyze_force(_record(t, F), band=(2 * np.pi * 2, 2 * np.pi * 50))
    assert [e.kind for e in a.data.timeline.events] == ["rate change"]
    assert any("periodic record" in fl and "not a power law" in fl for fl in a.fit_F.flags)
    assert not a.fit_F.to_dict()["power_law"]


def _csv(path, t, F):
    path.write_text("time (s);Ff (N)\n" + "".join(f"{a:.6f};{b:.6f}\n" for a, b in zip(t, F)))


def test_cli_lists_the_pieces_and_refuses_a_record_without_a_uniform_stretch(tmp_path, capsys):
    t, F = _random_walk_force(4)
    f = tmp_path / "rig.csv"
    _csv(f, t, F)
    out = tmp_path / "out"
    assert main(["analyze", str(f), "--force-col", "Ff", "--band", str(BAND[0]), str(BAND[1]), "-o", str(out)]) == 0
    io = capsys.readouterr()
    text = io.out + io.err
    # the header is line 1: row 15002 (1-based), the first at 0.5 ms, is on line 15003, printed with its own
    # stamp (15 s + 0.5 ms) and the stamp before (15 s)
    assert "line 15003 at t = 15.0005 s, after t = 15 s: rate change" in text and ": gap (" in text
    assert "uniform pieces (strokes cut at the breaks): 3, 3 in the combined spectrum" in text
    assert "piece 3: stroke 1, rows 33002-49537, t = 24.5-32.7675 s, step 0.0005 s" in text
    s = json.loads((out / "summary.json").read_text())
    assert [p["start_row"] for p in s["pieces"]] == [0, 15001, 33001] and len(s["timeline"]["segments"]) == 3
    assert abs(s["fit_F"]["gamma"] - 2.0) <= 1.5 * s["fit_F"]["gamma_err"]  # one seed: 1.5 x the half-width
    assert "Uniform pieces" in (out / "index.html").read_text()
    # --resample still puts the record on one grid, its filter stated
    assert main(["analyze", str(f), "--force-col", "Ff", "--resample", "0.001", "-o", str(tmp_path / "r")]) == 0
    err = capsys.readouterr().err
    assert "Butterworth, order 8, at 400 Hz" in err
    assert "pieces" not in json.loads((tmp_path / "r" / "summary.json").read_text())
    # the rate changes every 40 rows: no uniform stretch of 64 rows anywhere
    steps = np.where((np.arange(4000) // 40) % 2 == 0, 1e-3, 0.5e-3)
    bad = tmp_path / "bad.csv"
    _csv(bad, np.concatenate([[0.0], np.cumsum(steps)]), np.ones(4001))
    assert main(["analyze", str(bad), "--force-col", "Ff", "-o", str(tmp_path / "b")]) == 2
    io = capsys.readouterr()
    assert io.err.count("\n") == 1 and str(bad) in io.err and "no stretch of 64" in io.err, io.err
    assert not (tmp_path / "b").exists()
