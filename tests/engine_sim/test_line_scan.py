"""The line_scan substrate: a measured profile read with its units, resampled, detrended, reduced to what a pad can
feel (closed by the pad's disc, resampled where the pad's path does not change), mirrored or tiled, and the pads
sliding over it."""
import re
from pathlib import Path

import numpy as np
import pytest

import engine_sim
from engine_sim import ScenarioError, Scene, load_scenario, scenario_from_dict
from engine_sim.substrates.line_scan import LineScanSpec, ProfileTrack, pad_closing, pad_path, read_profile
from tests.stylus_export import SPACING_UM, stylus_export


def _scene_dict(file, **sub):
    d = load_scenario("line_scan_example").to_dict()
    d["substrate"].update(file=str(file), **sub)
    return d


def test_units_resampling_and_detrend(tmp_path):
    x_mm = np.linspace(0.0, 10.0, 501)  # 20 um spacing
    h_um = 5.0 + 0.3 * x_mm + 2.0 * np.sin(2 * np.pi * x_mm / 2.5)  # offset + tilt + a 2.5 mm wave
    f = tmp_path / "scan.csv"
    f.write_text("x (mm),h (um)\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(x_mm, h_um)))
    p = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="none"))  # a point probe
    dx, h = p.dx, p.h
    assert dx == pytest.approx(20e-6, rel=1e-12)
    np.testing.assert_allclose(h, h_um * 1e-6, rtol=0, atol=1e-18)  # units only: same points
    # resampled at 50 um: linear interpolation of a sine sampled every 20 um errs by at most
    # (2 pi / 2.5 mm)^2 (20 um)^2 / 8 x 2 um = 1.3e-3 um
    p = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", dx=50e-6, detrend="none"))
    dx, h = p.dx, p.h
    grid = np.arange(h.size) * 50e-6
    assert h.size == 201
    np.testing.assert_allclose(h, 1e-6 * (5.0 + 0.3e3 * grid + 2.0 * np.sin(2 * np.pi * grid / 2.5e-3)), atol=1.5e-9)
    # linear detrend removes offset and tilt exactly: what is left is the wave less its own least-squares line
    h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="linear")).h
    wave = 2e-6 * np.sin(2 * np.pi * x_mm / 2.5)
    wave -= np.polyval(np.polyfit(x_mm, wave, 1), x_mm)
    np.testing.assert_allclose(h, wave, rtol=0, atol=1e-15)  # 1e-9 of the wave's 2 um amplitude: rounding
    h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="mean")).h
    assert abs(h.mean()) < 1e-18


def test_npy_either_orientation_matches_csv(tmp_path):
    xy = np.column_stack([np.arange(64) * 1e-5, np.cos(np.arange(64) / 5.0) * 1e-6])
    np.save(tmp_path / "a.npy", xy)
    np.save(tmp_path / "b.npy", xy.T)
    (tmp_path / "c.csv").write_text("".join(f"{a:.17g},{b:.17g}\n" for a, b in xy))
    out = [read_profile(LineScanSpec(file=str(tmp_path / n), x_unit="m", height_unit="m"))
           for n in ("a.npy", "b.npy", "c.csv")]
    for p in out[1:]:
        assert p.dx == out[0].dx
        np.testing.assert_array_equal(p.h, out[0].h)


@pytest.mark.parametrize("extend", ["mirror", "tile"])
def test_track_continues_the_profile(extend):
    import pymunk

    h = np.array([0.0, 1.0, 3.0, 2.0, 5.0, 4.0]) * 1e-3
    tr = ProfileTrack(pymunk.Space(), 0.0, h, 0.01, extend, 0.6, 0.05, pymunk.ShapeFilter(),
                      np.random.default_rng(0), x_start=0.0, chunk_points=7)
    tr.maintain(0.0, 0.5, 1.0)
    ys = np.array([s.a.y for s in tr.segments] + [tr.segments[-1].b.y])
    period = 10 if extend == "mirror" else 6
    seq = np.concatenate([h, h[-2:0:-1]]) if extend == "mirror" else h  # one period
    expect = seq[(tr.entry + np.arange(ys.size)) % period]
    np.testing.assert_array_equal(ys, expect)
    xs = np.array([s.a.x for s in tr.segments])
    np.testing.assert_allclose(np.diff(xs), 0.01, rtol=1e-12)  # the grid, unbroken across chunks
    if extend == "mirror":  # no step at the joins: no jump larger than the profile's own
        assert np.max(np.abs(np.diff(ys))) <= np.max(np.abs(np.diff(h)))


def test_loader_finds_names_and_refuses_bad_profiles(tmp_path):
    sc = load_scenario("line_scan_example")
    assert sc.substrate.kind == "line_scan" and sc.substrate.file.endswith("synthetic_scan_um.csv")
    p = read_profile(sc.substrate, sc.pads.radius)
    slope = np.sqrt(np.mean(np.diff(p.h) ** 2)) / p.dx
    assert 0.03 < slope < 0.1  # the README's 0.075 before the pads' closing; below the limit 1/(6 mu0) = 0.278
    with pytest.raises(ScenarioError, match="substrate.file = 'nope.csv': not found"):
        scenario_from_dict(_scene_dict("nope.csv"))
    steep = tmp_path / "steep.csv"
    # a triangle wave of slope 1 and period 2 mm: far longer than the pad (0.35 mm), which follows it
    steep.write_text("".join(f"{i * 5e-5:.17g},{abs((i * 5e-5) % 2e-3 - 1e-3):.17g}\n" for i in range(200)))
    with pytest.raises(ScenarioError, match="rms slope 0.9.* exceeds the sliding limit 0.278"):
        scenario_from_dict(_scene_dict(steep, x_unit="m", height_unit="m"))
    with pytest.raises(ScenarioError, match="substrate.x_unit = 'inch' is not one of"):
        scenario_from_dict(_scene_dict(steep, x_unit="inch"))
    with pytest.raises(ScenarioError, match="unknown key substrate.alpha"):  # each kind has its own fields
        scenario_from_dict(_scene_dict(steep, alpha=1.0))


def test_scene_tracks_are_the_profile_entered_at_random_places():
    sc = load_scenario("line_scan_example")
    h = read_profile(sc.substrate, sc.pads.radius).h
    seq = np.concatenate([h, h[-2:0:-1], h])  # mirrored: the tracks may sit in the reflected half
    scene = Scene(sc)
    starts = set()
    for i, tr in enumerate(scene.tracks):
        ys = np.array([s.a.y for s in list(tr.segments)[:5]]) - (scene.track_surface[i] - sc.substrate.segment_radius * 1e3)
        k = int(np.argmin([np.sum((seq[j:j + 5] * 1e3 - ys) ** 2) for j in range(2 * h.size)]))
        np.testing.assert_allclose(ys, seq[k:k + 5] * 1e3, atol=1e-12)  # mm: the profile itself
        starts.add(tr.entry)
    assert len(starts) > 20  # 30 pads at independent places (collisions in ~2000 entries are rare)


@pytest.mark.slow
def test_pads_slide_over_the_measured_profile():
    sc = load_scenario("line_scan_example")
    tr = engine_sim.run(sc, duration=3.0)
    v = (tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0])
    # measured 4.92 mm/s for the law's 5.00: the profile's slopes make pads dwell (as on pads_rough_profile,
    # 4.87); 5 % would mean the block no longer follows the law
    assert v == pytest.approx(sc.steady_velocity, rel=0.05)
    resid = tr.work_drive[-1] - tr.dissipated[-1] - tr.mech_energy[-1]
    assert abs(resid / tr.work_drive[-1]) < 2e-3  # measured 2.6e-4, as the other pad scenes
    assert np.mean(tr.n_contact) > 29  # every pad stays on its track (measured 29.9)


# ------------------------------------------------------------------------------------- what a pad can feel of a profile
def test_closing_keeps_the_pads_path_and_fills_only_what_it_bridges():
    rng = np.random.default_rng(7)
    dx, R = 1e-6, 0.35e-3
    h = np.cumsum(rng.standard_normal(4000)) * 0.05e-6  # a rough random walk, steps of 50 nm rms
    closed = pad_closing(h, dx, R)
    assert np.all(closed >= h - 1e-21)  # the closing lies on or above the profile
    # a disc's path over the closing is its path over the profile (dilation of the closing = dilation): both are
    # maxima over the same grid of the same sums, so equal to rounding
    np.testing.assert_allclose(pad_path(closed, dx, R), pad_path(h, dx, R), rtol=0, atol=1e-18)
    np.testing.assert_allclose(pad_closing(closed, dx, R), closed, rtol=0, atol=1e-18)  # idempotent


def test_closing_of_a_groove_is_the_discs_arc_and_of_a_gentle_wave_is_the_wave():
    dx, R = 0.5e-6, 0.35e-3
    i = np.arange(-2000, 2001)
    x = dx * i
    h = np.where(np.abs(i) < 40, -5e-6, 0.0)  # a groove 40 um wide and 5 um deep in a flat
    closed = pad_closing(h, dx, R)
    rim = 40 * dx  # the disc rests on the grid points at +-20 um, the groove's edges
    inside = np.abs(i) < 40
    arc = np.sqrt(R**2 - rim**2) - np.sqrt(R**2 - x[inside] ** 2)  # the disc's lower edge (<= 0, rims at 0)
    np.testing.assert_allclose(closed[inside], arc, rtol=0, atol=1e-18)
    assert closed[x.size // 2] == pytest.approx(-(R - np.sqrt(R**2 - rim**2)), rel=1e-12)  # 0.57 um, not 5 um
    np.testing.assert_array_equal(closed[~inside], 0.0)
    # a wave whose curvature A q^2 is half the disc's 1/R: the disc touches it everywhere, nothing is filled (a
    # whole number of periods, symmetric about both ends, so that the mirrored continuation is the same wave)
    q = 2 * np.pi / 200e-6
    wave = 0.5 / (R * q**2) * np.cos(q * x)
    # on the grid the disc touches only grid points: it may settle by up to the sag of its arc between two of them,
    # dx^2 / (8 R) = 0.09 nm (measured 0.18 nm at most: dilation and erosion each)
    np.testing.assert_allclose(pad_closing(wave, dx, R), wave, rtol=0, atol=2 * dx**2 / (8 * R) * 1.01)


def _stylus_scenario(tmp_path, **sub):
    f = tmp_path / "export.csv"
    f.write_bytes(stylus_export())
    return scenario_from_dict(_scene_dict(f, x_unit="", height_unit="", dx=0.0, **sub))


def test_stylus_export_is_resampled_to_what_the_pad_can_feel(tmp_path):
    sc = _stylus_scenario(tmp_path)
    part = sc.substrate_part
    p = part.profile
    R = sc.pads.radius + sc.substrate.segment_radius
    assert p.native_dx == pytest.approx(SPACING_UM * 1e-6, rel=1e-12)
    k = int(round(p.dx / p.native_dx))
    assert k > 10 and p.dx <= sc.pads.radius  # far coarser than the file's 0.156 um, never coarser than a pad
    # the rule, checked independently of the module's own bookkeeping: the pad's path over the track (linear between
    # its points) against its path over the file's detrended profile, away from the ends the disc overhangs
    from engine_sim.profile_file import read_line_scan

    raw = read_line_scan(sc.substrate.file)
    idx = np.arange(raw.h.size)
    h = raw.h - np.polyval(np.polyfit(idx * p.native_dx, raw.h, 1), idx * p.native_dx)
    n = (p.h.size - 1) * k + 1
    track = np.interp(idx[:n], idx[:n:k], p.h)
    m = int(np.sqrt(2 * R * np.ptp(h)) / p.native_dx) + 1
    err = pad_path(track, p.native_dx, R)[m:n - m] - pad_path(h[:n], p.native_dx, R)[m:n - m]
    rms = np.sqrt(np.mean(err**2))
    assert rms <= sc.substrate.path_tolerance * (1 + 1e-9)  # the stated rule: within 0.1 um rms
    # the module leaves out a margin set by the closing's height range, this test a wider one (the profile's): the
    # ends the disc overhangs differ a little (measured 0.4 %)
    assert rms == pytest.approx(p.path_error, rel=0.02)
    assert part.notes() == [p.note]
    assert p.note.startswith(f"export.csv: profile resampled from 0.156 um to {p.dx * 1e6:.3g} um: the pad cannot "
                             "resolve shorter wavelengths")
    # a tighter tolerance, a finer grid
    finer = _stylus_scenario(tmp_path, path_tolerance=0.02e-6).substrate_part.profile
    assert finer.dx < p.dx and finer.path_error <= 0.02e-6 * (1 + 1e-9)


def test_bad_profile_from_the_command_line_exits_2_and_writes_nothing(tmp_path, capsys):
    from compare.cli import main

    f = tmp_path / "scan.csv"
    f.write_bytes(stylus_export(rows=[f"{i * 0.156:.3f},{'NaN' if i == 5 else 10.0 + i},," for i in range(20)]))
    toml = tmp_path / "scene.toml"
    toml.write_text(f'[substrate]\nkind = "line_scan"\nfile = "{f.name}"\n')
    out = tmp_path / "out"
    assert main(["run", str(toml), "-o", str(out), "--duration", "0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"{f}: line 21: height nan is not a number" in err, err
    assert not out.exists()


@pytest.mark.slow
@pytest.mark.timing
def test_stylus_export_at_native_spacing_runs_3_s_in_under_30_s(tmp_path):
    """The profilometer export as the line_scan file at its native spacing (dx = 0: the pads' rule
    picks the grid), 3 s simulated after the 1 s warm-up, through the command line: the resampling line printed
    before the run, under 30 s wall for the whole command (imports, profile, probe and run). Measured 51 s under a
    load of 13 on 2 cores (6 helpers); the timing tier runs alone on one core."""
    import subprocess
    import sys
    import time

    toml = tmp_path / "stylus.toml"
    text = (Path(engine_sim.__file__).parent / "scenarios" / "line_scan_example.toml").read_text()
    for key, val in (("file", '"synthetic_stylus_export.csv"'), ("x_unit", '""'), ("height_unit", '""'),
                     ("dx", "0.0")):
        text = re.sub(rf"(?m)^{key} = .*$", f"{key} = {val}", text)
    toml.write_text(text)
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "compare.cli", "run", str(toml), "--duration", "3", "-o",
                        str(tmp_path / "out")], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    assert r.returncode == 0, r.stderr[-2000:]
    assert ("synthetic_stylus_export.csv: profile resampled from 0.156 um to 13.6 um: the pad cannot resolve shorter "
            "wavelengths") in r.stderr
    print(f"wall {wall:.1f} s")
    assert wall < 30.0
