"""Profiles as stylus exports write them: the spacing from the preamble or the mean step (never the median of
rounded positions), the Dektak header's units, CR CR LF line numbers as grep -n counts them, and the profile's
checksum and resampling in a run's metadata."""
import hashlib
import math
from pathlib import Path
import subprocess

import numpy as np
import pytest

from engine_sim.profile_file import ProfileError, read_line_scan
from engine_sim.substrates.line_scan import LineScanSpec, read_profile
from tests.instrument_files import dektak_export


@pytest.mark.parametrize("with_resolution", [True, False])
def test_dektak_like_export_spacing_is_the_scans_not_the_roundings(tmp_path, with_resolution):
    raw, h_um = dektak_export(with_resolution=with_resolution)
    f = tmp_path / "dektak.csv"
    f.write_bytes(raw)
    scan = read_line_scan(f)
    assert scan.x_unit == "um" and scan.height_unit == "Micrometer"  # 'Raw Micrometer': a spelled-out name
    assert np.median(np.diff(scan.x)) == pytest.approx(0.2e-6, rel=1e-9)  # what the median would give
    p = read_profile(LineScanSpec(file=str(f), detrend="none"))  # a point probe: the file's own grid
    # from the preamble: 0.156 um exactly; from the mean step: (1999.8 - 0.0) um / 12820, the last position
    # rounded to 0.1 um, so within 0.05 um / 2000 um = 2.5e-5 of 0.156 um
    assert p.native_dx == pytest.approx(0.156e-6, rel=1e-12 if with_resolution else 2.5e-5)
    np.testing.assert_array_equal(p.h, h_um * 1e-6)  # the heights as written: rounding is not interpolated
    assert "rounding in the export" in p.note
    assert scan.sha256 == hashlib.sha256(raw).hexdigest() == p.sha256


def test_dektak_like_error_line_is_grep_n(tmp_path):
    rows = [f"{0.156 * i:.1f},{1.0 + 0.01 * (i % 5):.4f}" for i in range(100)]
    rows[40] = "6.2,bad"
    raw, _ = dektak_export(rows=rows)
    f = tmp_path / "dektak.csv"
    f.write_bytes(raw)
    grep = int(subprocess.run(["grep", "-n", "bad", str(f)], capture_output=True, text=True).stdout.split(":")[0])
    with pytest.raises(ProfileError, match=rf"dektak.csv: line {grep}: '6.2,bad' is not a position"):
        read_line_scan(f)
    assert grep == 49  # 6 preamble lines, a blank, the header, then the 41st row


def test_line_scan_provenance_names_file_checksum_and_resampling(tmp_path):
    from engine_sim import scenario_from_dict, load_scenario
    from tests.stylus_export import stylus_export

    f = tmp_path / "export.csv"
    f.write_bytes(stylus_export())
    d = load_scenario("line_scan_example").to_dict()
    d["substrate"].update(file=str(f), x_unit="", height_unit="", dx=0.0)
    sc = scenario_from_dict(d)
    prov = sc.substrate_part.provenance()["profile"]
    assert prov["sha256"] == hashlib.sha256(f.read_bytes()).hexdigest() and prov["file"] == str(f)
    assert prov["resampling"] == sc.substrate_part.notes()[0] and "resampled from 0.156 um" in prov["resampling"]


@pytest.mark.slow
def test_run_records_the_profile_and_compare_takes_a_band(tmp_path, capsys):
    """A line_scan run's trace.json names the profile, its checksum and its resampling line; compare --band fits
    over the band given (a scan too short for 3-30 v/a needs one). About 30 s on a loaded machine."""
    import json

    from compare.cli import main
    from engine_sim import shipped_scenarios

    r, c = tmp_path / "r", tmp_path / "c"
    assert main(["run", "line_scan_example", "--duration", "2", "-o", str(r)]) == 0
    meta = json.loads((r / "trace.json").read_text())["profile"]
    shipped = Path(shipped_scenarios()["line_scan_example"]).parent / "profiles" / "synthetic_scan_um.csv"
    assert meta["sha256"] == hashlib.sha256(shipped.read_bytes()).hexdigest()
    assert meta["resampling"].startswith("synthetic_scan_um.csv: profile kept at its spacing 20 um")
    assert main(["compare", str(r / "trace.npz"), "--band", "30", "300", "-o", str(c)]) == 0
    s = json.loads((c / "summary.json").read_text())["scenarios"]["line_scan_example"]
    # the band quoted is the fitted one: the record's Fourier ordinates inside the band given, within one ordinate
    # spacing (2 pi / T) of its ends
    lo, hi = s["band"]
    assert 30.0 <= lo < 30.0 + 2 * math.pi / 2.0 and 300.0 - 2 * math.pi / 2.0 < hi <= 300.0
