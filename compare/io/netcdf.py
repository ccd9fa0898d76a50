"""Traces and spectra as self-describing netCDF files, through xarray: what Stingray, DASCore and SurfaceTopography
users open without this package.

Every array of the object becomes a variable with a CF ``units`` attribute; scalars and the metadata (a nested
dictionary, as JSON) become attributes of the file; the class is named in the ``frictionnoise_class`` attribute so
that :func:`load_netcdf` rebuilds the same object. Arrays are written as they are (float64, int8, ...) without
compression or scaling, so a round trip is exact bit for bit. The ``.npz`` trace (:mod:`compare.io.traces`) stays the
fast default; netCDF is for exchange.

xarray and h5netcdf come with the ``netcdf`` extra (``pip install 'frictionnoise[netcdf]'``); without them these
functions raise :class:`NetcdfUnavailable`, whose message names the extra.
"""
from __future__ import annotations

import json
from dataclasses import fields, is_dataclass
from pathlib import Path

import numpy as np

from frictionnoise.base import atomic_write

__all__ = ["save_netcdf", "load_netcdf", "to_dataset", "from_dataset", "NetcdfUnavailable", "NetcdfFileError",
           "UNITS"]

FORMAT = "frictionnoise-netcdf-1"

# CF unit strings of the arrays of the traces (docs/reference/trace_format.md); a Spectrum's C carries its own unit
UNITS = {
    "t": "s", "x": "m", "v": "m/s", "F_t": "N", "F_n": "N", "F_drag": "N", "F_drive": "N", "pad_force": "N",
    "n_contact": "1", "n_pairs": "1", "penetration": "m", "work_drive": "J", "dissipated": "J", "mech_energy": "J",
    "work_recycle": "J", "p_state": "1", "p_force": "N", "particle_penetration": "m", "micro_force": "N",
    "vibration": "m", "work_vibration": "J", "force": "N", "omega": "rad/s", "n_avg": "1",
    "periodogram_domega": "rad/s",
}

# the classes a file can hold, by the module that defines each (imported only when read or written)
_CLASSES = {
    "EngineTrace": "engine_sim.record",
    "ModelTrace": "reduced_models.trace",
    "Spectrum": "compare.analysis.spectra",
}
_SAMPLE_AXIS = {"EngineTrace": "t", "ModelTrace": "t", "Spectrum": "omega"}


class NetcdfUnavailable(ImportError):
    """xarray or h5netcdf is not installed; the message names the extra that installs them."""


class NetcdfFileError(ValueError):
    """A file that is not a frictionnoise netCDF file; the message names the file and the problem."""


def _xarray():
    try:
        import h5netcdf  # noqa: F401  (the engine xarray is asked for below)
        import xarray
    except ImportError as err:
        raise NetcdfUnavailable(
            f"netCDF needs xarray and h5netcdf ({err.name} is not installed): pip install 'frictionnoise[netcdf]'"
        ) from None
    return xarray


def _class_name(obj) -> str:
    name = type(obj).__name__
    if not is_dataclass(obj) or name not in _CLASSES:
        raise TypeError(f"netCDF holds an EngineTrace, a ModelTrace or a Spectrum, not a {name}")
    return name


def to_dataset(obj):
    """The xarray Dataset of a trace or a spectrum (arrays as variables with units, the rest as attributes).

    Parameters
    ----------
    obj : engine_sim.EngineTrace, reduced_models.ModelTrace or compare.spectra.Spectrum
        What to convert (SI units).

    Returns
    -------
    xarray.Dataset
        One variable per array; the sample axis (``t`` in s, or ``omega`` in rad/s) is the coordinate of the
        dimension its length defines; other axes are named ``<variable>_<k>``. A ModelTrace's ``events`` are
        variables named ``events.<key>``, an EngineTrace's ``channels`` ``channels.<name>``.
    """
    xr = _xarray()
    name = _class_name(obj)
    axis = _SAMPLE_AXIS[name]
    n = len(getattr(obj, axis))
    data_vars, attrs, empty = {}, {"frictionnoise_class": name, "frictionnoise_format": FORMAT}, []

    def add(key, value, unit):
        value = np.asarray(value)
        dims = tuple(axis if (k == 0 and size == n and value.ndim >= 1) else f"{key}_{k}"
                     for k, size in enumerate(value.shape))
        var_attrs = {"units": unit} if unit else {}
        data_vars[key] = xr.Variable(dims, value, attrs=var_attrs)

    for f in fields(obj):
        value = getattr(obj, f.name)
        if f.name == "metadata" or f.name == "provenance":
            attrs[f.name] = json.dumps(value, default=_json_default)
        elif f.name in ("events", "channels"):  # a dict of arrays: one variable each
            for key, ev in value.items():
                add(f"{f.name}.{key}", ev, None)
        elif value is None:
            empty.append(f.name)
        elif isinstance(value, np.ndarray):
            unit = getattr(obj, "unit", None) if (name == "Spectrum" and f.name in ("C", "periodogram")) \
                else UNITS.get(f.name)
            add(f.name, value, unit)
        else:
            attrs[f.name] = value
    attrs["none_fields"] = json.dumps(empty)
    ds = xr.Dataset(data_vars, attrs=attrs)
    return ds.set_coords(axis)


def from_dataset(ds):
    """Rebuild the trace or spectrum that :func:`to_dataset` converted.

    Parameters
    ----------
    ds : xarray.Dataset
        A dataset written by :func:`to_dataset` (or read from a file :func:`save_netcdf` wrote).

    Returns
    -------
    engine_sim.EngineTrace, reduced_models.ModelTrace or compare.spectra.Spectrum
        The same object, its arrays with the dtypes and values they were written with.
    """
    from importlib import import_module

    name = ds.attrs.get("frictionnoise_class")
    if name not in _CLASSES:
        raise ValueError(f"not a frictionnoise dataset (frictionnoise_class = {name!r})")
    cls = getattr(import_module(_CLASSES[name]), name)
    none_fields = set(json.loads(ds.attrs.get("none_fields", "[]")))
    kwargs = {}
    for f in fields(cls):
        if f.name in ("metadata", "provenance"):
            if f.name in ds.attrs:
                kwargs[f.name] = json.loads(ds.attrs[f.name])
        elif f.name in ("events", "channels"):
            kwargs[f.name] = {k.split(".", 1)[1]: ds[k].values for k in ds.variables if k.startswith(f.name + ".")}
        elif f.name in none_fields:
            kwargs[f.name] = None
        elif f.name in ds.variables:
            kwargs[f.name] = ds[f.name].values
        elif f.name in ds.attrs:
            value = ds.attrs[f.name]
            kwargs[f.name] = value.item() if isinstance(value, np.generic) else value
    return cls(**kwargs)


def save_netcdf(obj, path) -> Path:
    """Write a trace or a spectrum to a netCDF-4 file (``.nc``), atomically.

    Parameters
    ----------
    obj : engine_sim.EngineTrace, reduced_models.ModelTrace or compare.spectra.Spectrum
        What to write.
    path : str or pathlib.Path
        The file; its suffix is set to ``.nc``.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    ds = to_dataset(obj)
    path = Path(path).with_suffix(".nc")
    atomic_write(path, write=lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))
    return path


def load_netcdf(path):
    """Read a file written by :func:`save_netcdf`.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.nc`` file.

    Returns
    -------
    engine_sim.EngineTrace, reduced_models.ModelTrace or compare.spectra.Spectrum
        The object written; :class:`NetcdfFileError` names the file and the problem otherwise.
    """
    xr = _xarray()
    path = Path(path)
    if not path.is_file():
        raise NetcdfFileError(f"{path}: no such file")
    try:
        with xr.open_dataset(path, engine="h5netcdf", mask_and_scale=False, decode_times=False) as ds:
            ds.load()
            return from_dataset(ds)
    except (OSError, ValueError) as err:
        raise NetcdfFileError(f"{path}: not a frictionnoise netCDF file ({err})") from None


def _json_default(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return str(value)
