"""Profiles too short or too fine for the scene: refused in one line before any segment is laid, or repeated with
a warning on request; the spacing rule's error is always finite and a track never holds more segments than its
budget."""
import time

import numpy as np
import pytest

from engine_sim import ScenarioError, load_scenario, scenario_from_dict
from engine_sim.substrates.line_scan import _KEPT_RADII, TRACK_SEGMENTS, LineScanSpec, read_profile


def _afm_line_nm(path, n=134, step_nm=12.7, seed=1):
    """A short AFM line as its software writes it: positions and heights in nm, 1.7 um long."""
    rng = np.random.default_rng(seed)
    h = np.cumsum(rng.standard_normal(n)) * 0.3
    path.write_text("x (nm),z (nm)\n" + "".join(f"{i * step_nm:.2f},{v:.3f}\n" for i, v in enumerate(h)))
    return path


def _scene(file, **sub):
    d = load_scenario("line_scan_example").to_dict()
    d["substrate"].update(file=str(file), x_unit="", height_unit="", **sub)
    return d


def test_short_afm_line_in_nm_is_refused_in_one_line_exit_2_fast(tmp_path, capsys):
    from compare.cli import main

    f = _afm_line_nm(tmp_path / "afm.csv")
    toml = tmp_path / "scene.toml"
    toml.write_text(f'[substrate]\nkind = "line_scan"\nfile = "{f.name}"\n')
    out = tmp_path / "out"
    t0 = time.perf_counter()
    code = main(["run", str(toml), "-o", str(out), "--duration", "0.001"])
    wall = time.perf_counter() - t0
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1, err
    assert "afm.csv: the scan is 1.69 um long, shorter than" in err and "short_scan" in err
    assert not out.exists()
    # on main this set-up laid millions of segments (stopped at 150 s); the refusal needs only the file read.
    # Measured 0.3 s with 5 helpers on 2 cores; 5 s is the bound, far above any load seen here
    assert wall < 5.0


@pytest.mark.parametrize("length_mm, pad_radius_mm, a_mm, refused", [
    (0.05, 0.3, 1.0, True),   # a 50 um scan under a 0.3 mm pad
    (0.48, 0.3, 1.0, True),   # longer than the pad, shorter than a
    (1.5, 0.3, 1.0, False),   # long enough for both
])
def test_scan_shorter_than_the_pad_or_a_is_refused(tmp_path, length_mm, pad_radius_mm, a_mm, refused):
    n = 200
    f = tmp_path / "scan.csv"
    x = np.linspace(0.0, length_mm, n)
    f.write_text("x_mm,h_um\n" + "".join(f"{a:.6f},{0.2 * np.sin(40 * a):.5f}\n" for a in x))
    d = _scene(f, a=a_mm * 1e-3)
    d["pads"]["radius"] = pad_radius_mm * 1e-3
    if refused:
        with pytest.raises(ScenarioError, match=r"shorter than .*short_scan = \"repeat\""):
            scenario_from_dict(d)
    else:
        scenario_from_dict(d)


def test_short_scan_repeated_on_request_with_a_warning(tmp_path):
    f = _afm_line_nm(tmp_path / "afm.csv", n=400, step_nm=125.0)  # 50 um
    sc = scenario_from_dict(_scene(f, short_scan="repeat"))
    note = sc.substrate_part.notes()[0]
    assert "WARNING: the scan (49.9 um) is shorter than the renewal length substrate.a (1 mm)" in note
    assert "repeated 41 times" in note  # ceil(2 mm / 49.875 um)
    p = sc.substrate_part.profile
    assert np.isfinite(p.path_error) and (p.h.size - 1) * p.dx >= 2e-3 - 2 * p.dx


def test_spacing_never_finer_than_the_segment_budget(tmp_path):
    """A 2 mm scan on a 10 nm grid with a tolerance no resampling meets: the rule keeps the file's grid, the budget
    coarsens it to 6 R / TRACK_SEGMENTS and says so; an explicit finer substrate.dx is refused."""
    n = 200_001
    x = np.arange(n) * 10e-9
    h = 0.5e-6 * np.sin(2 * np.pi * x / 37e-6) + 0.05e-6 * np.sin(2 * np.pi * x / 0.3e-6)
    np.save(tmp_path / "fine.npy", np.column_stack([x, h]))
    R = 0.3e-3
    spec = LineScanSpec(file=str(tmp_path / "fine.npy"), x_unit="m", height_unit="m", path_tolerance=1e-12)
    p = read_profile(spec, R)
    finest = _KEPT_RADII * R / TRACK_SEGMENTS
    assert p.dx >= finest * (1 - 1e-9) and _KEPT_RADII * R / p.dx <= TRACK_SEGMENTS * (1 + 1e-9)  # round-off
    assert np.isfinite(p.path_error) and "segments per track" in p.note
    with pytest.raises(ValueError, match=r"substrate.dx = 1e-08 m would lay more than 20000 segments"):
        read_profile(LineScanSpec(file=str(tmp_path / "fine.npy"), x_unit="m", height_unit="m", dx=10e-9), R)
