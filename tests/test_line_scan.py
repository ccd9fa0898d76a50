"""The line_scan substrate: a measured profile read with declared units, resampled, detrended, mirrored or tiled,
and the pads sliding over it (issue 14's extension point)."""
import numpy as np
import pytest

import engine_sim
from engine_sim import ScenarioError, Scene, load_scenario, scenario_from_dict
from engine_sim.substrates.line_scan import LineScanSpec, ProfileTrack, read_profile


def _scene_dict(file, **sub):
    d = load_scenario("line_scan_example").to_dict()
    d["substrate"].update(file=str(file), **sub)
    return d


def test_units_resampling_and_detrend(tmp_path):
    x_mm = np.linspace(0.0, 10.0, 501)  # 20 um spacing
    h_um = 5.0 + 0.3 * x_mm + 2.0 * np.sin(2 * np.pi * x_mm / 2.5)  # offset + tilt + a 2.5 mm wave
    f = tmp_path / "scan.csv"
    f.write_text("x (mm),h (um)\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(x_mm, h_um)))
    dx, h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="none"))
    assert dx == pytest.approx(20e-6, rel=1e-12)
    np.testing.assert_allclose(h, h_um * 1e-6, rtol=0, atol=1e-18)  # units only: same points
    # resampled at 50 um: linear interpolation of a sine sampled every 20 um errs by at most
    # (2 pi / 2.5 mm)^2 (20 um)^2 / 8 x 2 um = 1.3e-3 um
    dx, h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", dx=50e-6, detrend="none"))
    grid = np.arange(h.size) * 50e-6
    assert h.size == 201
    np.testing.assert_allclose(h, 1e-6 * (5.0 + 0.3e3 * grid + 2.0 * np.sin(2 * np.pi * grid / 2.5e-3)), atol=1.5e-9)
    # linear detrend removes offset and tilt exactly: what is left is the wave less its own least-squares line
    _, h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="linear"))
    wave = 2e-6 * np.sin(2 * np.pi * x_mm / 2.5)
    wave -= np.polyval(np.polyfit(x_mm, wave, 1), x_mm)
    np.testing.assert_allclose(h, wave, rtol=0, atol=1e-15)  # 1e-9 of the wave's 2 um amplitude: rounding
    _, h = read_profile(LineScanSpec(file=str(f), x_unit="mm", height_unit="um", detrend="mean"))
    assert abs(h.mean()) < 1e-18


def test_npy_either_orientation_matches_csv(tmp_path):
    xy = np.column_stack([np.arange(64) * 1e-5, np.cos(np.arange(64) / 5.0) * 1e-6])
    np.save(tmp_path / "a.npy", xy)
    np.save(tmp_path / "b.npy", xy.T)
    (tmp_path / "c.csv").write_text("".join(f"{a:.17g},{b:.17g}\n" for a, b in xy))
    out = [read_profile(LineScanSpec(file=str(tmp_path / n))) for n in ("a.npy", "b.npy", "c.csv")]
    for dx, h in out[1:]:
        assert dx == out[0][0]
        np.testing.assert_array_equal(h, out[0][1])


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
    dx, h = read_profile(sc.substrate)
    slope = np.sqrt(np.mean(np.diff(h) ** 2)) / dx
    assert 0.05 < slope < 0.1  # the README's 0.075; below the sliding limit 1/(6 mu0) = 0.278
    with pytest.raises(ScenarioError, match="substrate.file = 'nope.csv': not found"):
        scenario_from_dict(_scene_dict("nope.csv"))
    steep = tmp_path / "steep.csv"
    steep.write_text("".join(f"{i * 1e-5:.17g},{(i % 2) * 1e-5:.17g}\n" for i in range(50)))  # slope 1
    with pytest.raises(ScenarioError, match="rms slope 1 .*exceeds the sliding limit 0.278"):
        scenario_from_dict(_scene_dict(steep, x_unit="m", height_unit="m"))
    with pytest.raises(ScenarioError, match="substrate.x_unit = 'inch' is not one of"):
        scenario_from_dict(_scene_dict(steep, x_unit="inch"))
    with pytest.raises(ScenarioError, match="unknown key substrate.alpha"):  # each kind has its own fields
        scenario_from_dict(_scene_dict(steep, alpha=1.0))


def test_scene_tracks_are_the_profile_entered_at_random_places():
    sc = load_scenario("line_scan_example")
    dx, h = read_profile(sc.substrate)
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
