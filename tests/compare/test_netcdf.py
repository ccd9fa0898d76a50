"""Traces and spectra through netCDF (compare/io/netcdf.py): written and read back bit for bit (same dtypes, same
values, same metadata), with units that xarray shows as CF ``units`` attributes; without the ``netcdf`` extra the
error names it."""
import sys

import numpy as np
import pytest

import frictionnoise as fn
from compare.io import netcdf

xr = pytest.importorskip("xarray", reason="the netcdf extra (pip install 'frictionnoise[netcdf]')")
pytest.importorskip("h5netcdf", reason="the netcdf extra (pip install 'frictionnoise[netcdf]')")


def _same(a, b):
    """Every field equal bit for bit: arrays of the same dtype and shape with identical bytes (NaN included)."""
    assert type(a) is type(b)
    for name, va in vars(a).items():
        vb = getattr(b, name)
        if isinstance(va, np.ndarray):
            assert va.dtype == vb.dtype and va.shape == vb.shape, name
            assert va.tobytes() == vb.tobytes(), name
        elif isinstance(va, dict) and va and isinstance(next(iter(va.values())), np.ndarray):
            assert va.keys() == vb.keys(), name
            for key in va:
                assert va[key].dtype == vb[key].dtype and va[key].tobytes() == vb[key].tobytes(), (name, key)
        else:
            assert va == vb, name


@pytest.fixture(scope="module")
def scene_trace():
    return fn.run_scene("pads_with_wear", duration=0.05, seed=3)  # wear grains: int8 states, 2-D pad columns


def test_a_scene_trace_round_trips_bit_for_bit(tmp_path, scene_trace):
    path = netcdf.save_netcdf(scene_trace, tmp_path / "trace")
    assert path.suffix == ".nc"
    back = netcdf.load_netcdf(path)
    _same(scene_trace, back)
    assert back.p_state.dtype == np.int8 and back.pad_force.ndim == 2


def test_units_and_metadata_are_readable_by_xarray_alone(tmp_path, scene_trace):
    path = netcdf.save_netcdf(scene_trace, tmp_path / "trace.nc")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert ds["x"].attrs["units"] == "m" and ds["F_t"].attrs["units"] == "N"
        assert ds["t"].attrs["units"] == "s" and "t" in ds.coords
        assert ds["x"].dims == ("t",) and ds["pad_force"].dims[0] == "t"
        np.testing.assert_array_equal(ds["x"].values, scene_trace.x)
        assert ds.attrs["frictionnoise_class"] == "EngineTrace"


def test_a_model_trace_and_its_spectrum_round_trip(tmp_path):
    trace = fn.simulate(fn.SpringBlockParams.reference(), 20.0, seed=1)
    _same(trace, netcdf.load_netcdf(netcdf.save_netcdf(trace, tmp_path / "model")))
    spec = fn.displacement_spectrum(trace.t, trace.x)
    back = netcdf.load_netcdf(netcdf.save_netcdf(spec, tmp_path / "spectrum"))
    _same(spec, back)
    with xr.open_dataset(tmp_path / "spectrum.nc", engine="h5netcdf") as ds:
        assert ds["C"].attrs["units"] == spec.unit and ds["omega"].attrs["units"] == "rad/s"


def test_a_file_that_is_not_ours_is_refused_by_name(tmp_path):
    bad = tmp_path / "other.nc"
    xr.Dataset({"a": ("n", np.arange(3.0))}).to_netcdf(bad, engine="h5netcdf")
    with pytest.raises(netcdf.NetcdfFileError, match="other.nc"):
        netcdf.load_netcdf(bad)
    with pytest.raises(netcdf.NetcdfFileError, match="no such file"):
        netcdf.load_netcdf(tmp_path / "missing.nc")


def test_without_the_extra_the_error_names_it(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "xarray", None)  # an import of xarray now raises ImportError
    trace = fn.simulate(fn.SpringBlockParams.reference(), 1.0, seed=0)
    with pytest.raises(netcdf.NetcdfUnavailable, match=r"frictionnoise\[netcdf\]"):
        netcdf.save_netcdf(trace, tmp_path / "t")
