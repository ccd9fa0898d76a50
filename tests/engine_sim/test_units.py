"""Units as files write them (engine_sim.quantities, pint): the column's role fixes the dimension, the explicit
rules (gram-force, the angstrom, case only for spelled-out names), options that never override a stated unit, a
stress that needs an area, a friction-coefficient column analysed as mu."""
import json

import numpy as np
import pytest

from compare.io.measured import DataFileError, read_measured
from engine_sim.quantities import STANDARD_GRAVITY, UnitError, parse_unit, split_header


@pytest.mark.parametrize("text, role, factor", [
    ("in", "length", 0.0254), ("kip", "force", 4448.2216152605), ("gf", "force", 9.80665e-3),
    ("g", "force", 1e-3 * STANDARD_GRAVITY), ("MPa", "stress", 1e6), ("mm/sec", "velocity", 1e-3),
    ("microns", "length", 1e-6), ("µm", "length", 1e-6), ("μm", "length", 1e-6), ("Micrometer", "length", 1e-6),
    ("Mm", "length", 1e6), ("Å", "length", 1e-10), ("A", "length", 1e-10), ("sec", "time", 1.0),
    ("-", "dimensionless", 1.0), ("%", "dimensionless", 0.01),
])
def test_units_are_read_by_pint_with_the_stated_rules(text, role, factor):
    u = parse_unit(text, role)
    assert u.role == role and u.factor == pytest.approx(factor, rel=1e-12)  # exact definitions: round-off only


def test_symbols_keep_their_case_and_wrong_dimensions_are_refused():
    with pytest.raises(UnitError, match=r"'MM' is of dimension \[substance\]"):  # a symbol, no case folding:
        parse_unit("MM", "length")  # pint's megamolar, never the millimetre
    with pytest.raises(UnitError, match="'MPa' is a stress, not a force unit"):
        parse_unit("MPa", "force")
    with pytest.raises(UnitError, match="'g' is a mass, not a length unit"):
        parse_unit("g", "length")
    with pytest.raises(UnitError, match="'furlongz' is not a unit pint knows"):
        parse_unit("furlongz", "length")


@pytest.mark.parametrize("header, name, unit", [
    ("Effective_Normal_stress(MPa)", "Effective_Normal_stress", "MPa"), ("displacement (in)", "displacement", "in"),
    ("friction force (kip)", "friction force", "kip"), ("Raw Micrometer", "Raw", "Micrometer"), ("x_um", "x", "um"),
    ("t/s", "t", "s"), ("Fx", "Fx", None), ("normal_force", "normal_force", None), ("Height (V)", "Height", "V"),
])
def test_headers_state_units_in_brackets_or_after_a_separator(header, name, unit):
    assert split_header(header)[:2] == (name, unit)


def _table(path, header, rows, units_row=None):
    lines = [",".join(header)] + ([",".join(units_row)] if units_row else [])
    lines += [",".join(f"{v:.9g}" for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def _rows(n=256, seed=3):
    """Time and two columns, rounded as the file writes them (9 digits), so the reader's values are checked
    against the written numbers to round-off."""
    rng = np.random.default_rng(seed)
    t = 0.01 * np.arange(n)
    a, b = 2.0 + 0.1 * rng.standard_normal(n), 5.0 + 0.05 * rng.standard_normal(n)
    return tuple(np.array([float(f"{v:.9g}") for v in c]) for c in (t, a, b))


def test_stress_with_force_unit_is_refused_in_one_line(tmp_path, capsys):
    from compare.cli import main

    t, a, b = _rows()
    f = _table(tmp_path / "rock.csv", ["Time (s)", "Shear_stress(MPa)", "Effective_Normal_stress(MPa)"],
               np.column_stack([t, a, b]))
    out = tmp_path / "o"
    assert main(["analyze", str(f), "--force-col", "Shear_stress", "--force-unit", "N", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and not out.exists(), err
    assert f"{f}, line 1: the header gives column 'Shear_stress(MPa)' in MPa but --force-unit N was given" in err
    # without the option: a stress needs an area
    with pytest.raises(DataFileError, match=r"is a stress \(MPa\), not a force; .*--contact-area"):
        read_measured(f, force_col="Shear_stress", require_x=False)
    d = read_measured(f, force_col="Shear_stress", normal_col="Effective_Normal_stress", require_x=False,
                      contact_area=1e-4)
    np.testing.assert_allclose(d.F, a * 1e6 * 1e-4, rtol=1e-12)
    np.testing.assert_allclose(d.N, b * 1e6 * 1e-4, rtol=1e-12)


def test_inch_and_kip_are_read_as_such_and_never_as_mm_and_kn(tmp_path):
    t, a, b = _rows()
    f = _table(tmp_path / "damper.csv", ["time (s)", "displacement (in)", "friction force (kip)"],
               np.column_stack([t, a, b]))
    d = read_measured(f, x_col="displacement", force_col="friction force")
    np.testing.assert_allclose(d.x, a * 0.0254, rtol=1e-12)
    np.testing.assert_allclose(d.F, b * 4448.2216152605, rtol=1e-12)
    with pytest.raises(DataFileError, match=r"in in but --x-unit mm was given; an option never overrides"):
        read_measured(f, x_col="displacement", x_unit="mm")
    with pytest.raises(DataFileError, match=r"in kip but --force-unit kN was given"):
        read_measured(f, x_col="displacement", force_col="friction force", force_unit="kN")


def test_gram_force_from_a_units_row_and_a_mu_column_analysed(tmp_path, capsys):
    from compare.cli import main

    t, a, b = _rows(1024)
    mu = a / b
    a, b, mu = (np.array([float(f"{v:.9g}") for v in c]) for c in (a * 100, b * 100, mu))
    f = _table(tmp_path / "tribo.csv", ["T", "Ff", "Fz", "COF"], np.column_stack([t, a, b, mu]),
               units_row=["sec", "g", "g", ""])
    d = read_measured(f, time_col="T", force_col="Ff", normal_col="Fz", mu_col="COF", require_x=False)
    np.testing.assert_allclose(d.F, a * 9.80665e-3, rtol=1e-12)
    assert d.units["force"]["rule"].startswith("g on a force column read as g-force")
    assert d.units["mu"] == {"column": "COF", "unit": "1", "from": "role"}
    out = tmp_path / "o"
    assert main(["analyze", str(f), "--time-col", "T", "--force-col", "Ff", "--mu-col", "COF", "-o", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    # mean |mu| of the column as written (9 digits), not F / N of another column
    assert s["mean_abs_mu"] == pytest.approx(np.mean(np.abs(mu)), rel=1e-12)
    assert "'Ff' in g (from the units row; g on a force column read as g-force" in capsys.readouterr().out
