"""Line scans as instruments write them (engine_sim.profile_file): a stylus-profilometer export with its preamble,
latin-1 units and empty trailing columns, in every line-end convention; the same numbers as SurfaceTopography reads;
and every bad profile refused in one line naming the file and the line."""

import numpy as np
import pytest

from engine_sim.profile_file import ProfileError, read_line_scan
from tests.stylus_export import POINTS, SHIPPED, SPACING_UM, stylus_export, stylus_heights


def _written(tmp_path, data: bytes, name="scan.csv"):
    f = tmp_path / name
    f.write_bytes(data)
    return f


def _expected_heights(n=POINTS):
    """The export's heights as written: angstrom with one decimal, back in metres."""
    x_um = SPACING_UM * np.arange(n)
    h_A = np.array([float(f"{v:.1f}") for v in 1e10 * (stylus_heights(n) + 2e-3 * x_um * 1e-6 + 0.8e-6)])
    return x_um * 1e-6, h_A * 1e-10


@pytest.mark.parametrize("newline", ["\r\n", "\n", "\r"])
def test_stylus_export_is_read_with_the_units_it_states(tmp_path, newline):
    f = _written(tmp_path, stylus_export(newline=newline))
    s = read_line_scan(f)  # no unit declared: both come from the header "Lateral (µm),Total Profile (Å),,"
    assert (s.x_unit, s.height_unit) == ("µm", "Å")
    assert s.x_unit_from == s.height_unit_from == "the file (line 15)"
    assert s.data_lines == (16, 15 + POINTS)
    x, h = _expected_heights()
    # the file's numbers are decimal strings: x exact to 3 decimals in um, heights to 0.1 A; float parsing and one
    # multiplication by the unit's factor leave at most a few ulps
    np.testing.assert_allclose(s.x, x, rtol=1e-15, atol=1e-22)
    np.testing.assert_allclose(s.h, h, rtol=1e-15, atol=1e-25)
    assert s.metadata["Resolution"] == "0.156 µm/pt" and s.metadata["Stylus Radius"] == "2 µm"


def test_shipped_export_is_the_generators():
    assert SHIPPED.read_bytes() == stylus_export()  # rewrite it with `python -m tests.stylus_export`


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "utf-16"])
def test_encodings_other_than_latin1(tmp_path, encoding):
    text = stylus_export(n=40).decode("latin-1")
    f = _written(tmp_path, text.encode(encoding))
    s = read_line_scan(f)
    x, h = _expected_heights(40)
    assert s.x_unit == "µm" and s.height_unit == "Å"
    np.testing.assert_allclose(s.h, h, rtol=1e-15, atol=1e-25)


def test_declared_units_fill_in_and_must_agree(tmp_path):
    rows = "".join(f"{i * 0.5},{np.sin(i / 3):.6f}\n" for i in range(20))
    plain = _written(tmp_path, rows.encode(), "plain.txt")
    with pytest.raises(ProfileError, match=r"plain.txt: no unit for the positions: the file states none; set "
                                           r"substrate.x_unit"):
        read_line_scan(plain)
    s = read_line_scan(plain, "mm", "um")
    assert s.x[1] == pytest.approx(0.5e-3, rel=1e-15) and s.x_unit_from == "substrate.x_unit"
    named = _written(tmp_path, ("x [mm]\th [nm]\n" + rows.replace(",", "\t")).encode(), "named.txt")
    s = read_line_scan(named, "mm")  # agrees with the header: fine
    assert s.h[1] == pytest.approx(np.sin(1 / 3) * 1e-9, rel=1e-6)  # 6 decimals written
    with pytest.raises(ProfileError, match=r"named.txt: line 1: the header gives the heights in nm but "
                                           r"substrate.height_unit = 'um'"):
        read_line_scan(named, "", "um")


def _one_line(e) -> str:
    msg = str(e.value)
    assert "\n" not in msg
    return msg


BAD = {  # name: (data rows replacing the export's, the line named, what the message says)
    "no_numbers": (["Lateral,Profile,,", "none,recorded,,"], None, "no rows of numbers"),
    "one_column": ([f"{10.0 + i}" for i in range(20)], 16, "one column of numbers"),
    "one_point": (["0.000,12.5,,"], 16, "one point"),
    "nan_height": ([f"{i * 0.156:.3f},{'NaN' if i == 5 else 10.0 + i},," for i in range(20)], 21,
                   "height nan is not a number"),
    "backwards": ([f"{(i if i != 7 else 3) * 0.156:.3f},{10.0 + i},," for i in range(20)], 23,
                  "position 0.468 does not increase"),
    "not_a_number": ([f"{i * 0.156:.3f},{'---' if i == 9 else 10.0 + i},," for i in range(20)], 25,
                     "is not a position and a height"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_profiles_name_the_file_and_line(tmp_path, case):
    rows, line, what = BAD[case]
    f = _written(tmp_path, stylus_export(rows=rows, newline="\r\n"), f"{case}.csv")
    with pytest.raises(ProfileError) as e:
        read_line_scan(f)
    msg = _one_line(e)
    assert msg.startswith(f"{f}: " + (f"line {line}: " if line else "")), msg
    assert what in msg


def test_unknown_unit_is_refused(tmp_path):
    text = stylus_export(n=20).decode("latin-1").replace("Total Profile (Å)", "Total Profile (mV)")
    f = _written(tmp_path, text.encode("latin-1"))
    with pytest.raises(ProfileError) as e:
        read_line_scan(f)
    assert _one_line(e).startswith(f"{f}: line 15: column 2 ('Total Profile (mV)') is in 'mV', not a length unit")


def test_npy_needs_declared_units(tmp_path):
    np.save(tmp_path / "a.npy", np.column_stack([np.arange(10.0), np.zeros(10)]))
    with pytest.raises(ProfileError, match="a.npy: no unit for the positions"):
        read_line_scan(tmp_path / "a.npy")
    assert read_line_scan(tmp_path / "a.npy", "um", "nm").x[1] == pytest.approx(1e-6, rel=1e-15)


def test_same_numbers_as_surface_topography(tmp_path):
    """SurfaceTopography reads the export (its XYZ reader knows this kind of header) to the same numbers; it shifts
    positions to start at 0 and gives heights in the lateral unit."""
    st = pytest.importorskip("SurfaceTopography")
    import warnings

    for newline in ("\r\n", "\r"):
        f = _written(tmp_path, stylus_export(newline=newline), f"e{len(newline)}.csv")
        ours = read_line_scan(f)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t = st.read_topography(str(f))
        assert t.unit == "µm" and t.nb_grid_pts == (POINTS,)
        # both parse the same decimal strings; ST multiplies by its height scale (1e-4 um per A) first: 1e-15
        np.testing.assert_allclose(t.heights() * 1e-6, ours.h, rtol=1e-14, atol=1e-24)
        np.testing.assert_allclose(t.positions() * 1e-6, ours.x - ours.x[0], rtol=1e-14, atol=1e-21)


def test_binary_file_without_a_reader_says_so(tmp_path):
    f = _written(tmp_path, b"\x00\x01\x02binary" * 100, "scan.opdx")
    with pytest.raises(ProfileError) as e:
        read_line_scan(f)
    assert _one_line(e).startswith(f"{f}: ")
    assert "SurfaceTopography" in str(e.value)
