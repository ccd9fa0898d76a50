"""frictionnoise: the displacement and force noise of sliding friction, from Python.

``import frictionnoise as fn`` gives what a notebook user calls, in SI units (m, kg, s, N; frequencies in
rad/s; spectra in the two-sided angular convention of eq. (2) of Xu, Zhou & Persson, Soft Matter 21, 7594
(2025), DOI 10.1039/d5sm00617a):

- **spectra and fits**: :func:`displacement_spectrum`, :func:`force_series_spectrum`, :func:`force_spectrum`,
  :func:`friction_coefficient_spectrum`, :func:`rms_from_spectrum`, :func:`band_average`, :func:`log_bin`,
  :class:`Spectrum`; :func:`fit_series` and :class:`RecordFit` (the record model: gamma of a time record, as the
  report quotes it), :func:`fit_power_law` and :class:`PowerLawFit` (a band of a spectrum); the test helpers
  :func:`assert_spectral_slope` and :func:`assert_spectrum_matches`;
- **the reduced models** I, Ib, II and III and their extensions: their parameters (:class:`SpringBlockParams`,
  :class:`MultiscaleParams`, :class:`WearParticleParams`, :class:`AsperityForceParams`, :class:`AgeingParams`
  for ageing contacts, :class:`VibratingBlockParams` for a shaken substrate; ``.reference()`` is the paper's case), :func:`simulate` and :func:`theory_spectrum` for any of them, :func:`model` and
  :data:`MODELS` for the modules;
- **scenes** (the pymunk engine): :func:`shipped_scenarios`, :func:`shipped_path` (a shipped scene, sweep or data
  file by name), :func:`load_scenario`, :func:`run_scene`,
  :func:`render_scene`, :func:`compare_scene`, :func:`save_trace` and :func:`load_trace`; :func:`save_netcdf` and
  :func:`load_netcdf` write and read a trace or a spectrum as netCDF for other tools (the ``netcdf`` extra);
- **measured data**: :func:`read_measured`, :func:`analyze_displacement` for x(t) and :func:`analyze_force` for a
  friction-force record; :func:`identify` ranks the paper's mechanisms for x(t) (:class:`Mechanism`).

The names above are imported on first use (PEP 562 ``__getattr__``): ``import frictionnoise`` loads no numerics.
:data:`G`, :func:`package_version` and :func:`atomic_write` are the shared helpers of :mod:`frictionnoise.base`, which
the packages below (``engine_sim``, ``reduced_models``, ``compare``) import directly: they never import this user API.
"""
from __future__ import annotations

from importlib import import_module

from .base import G, atomic_write, package_version

# name -> module that defines it (imported on first access)
_LAZY = {
    # spectra and fits
    "Spectrum": "compare.spectra", "displacement_spectrum": "compare.spectra",
    "force_series_spectrum": "compare.spectra", "series_spectrum": "compare.spectra",
    "force_spectrum": "compare.spectra", "friction_coefficient_spectrum": "compare.spectra",
    "rms_from_spectrum": "compare.spectra", "band_average": "compare.spectra", "log_bin": "compare.spectra",
    "PowerLawFit": "compare.fits", "fit_power_law": "compare.fits",
    "RecordFit": "compare.analysis.record_model", "fit_series": "compare.analysis.record_model",
    "assert_spectral_slope": "compare.testing", "assert_spectrum_matches": "compare.testing",
    # the reduced models
    "SpringBlockParams": "reduced_models", "MultiscaleParams": "reduced_models",
    "WearParticleParams": "reduced_models", "AsperityForceParams": "reduced_models",
    "AgeingParams": "reduced_models.ageing", "VibratingBlockParams": "reduced_models.vibrating_block",
    "ModelTrace": "reduced_models", "MODELS": "reduced_models",
    "simulate": "frictionnoise.models", "theory_spectrum": "frictionnoise.models", "model": "frictionnoise.models",
    # scenes
    "Scenario": "engine_sim", "EngineTrace": "engine_sim", "load_scenario": "engine_sim",
    "shipped_scenarios": "engine_sim", "shipped_path": "engine_sim.shipped", "run_scene": "frictionnoise.scenes", "render_scene": "frictionnoise.scenes",
    "compare_scene": "frictionnoise.scenes", "save_trace": "frictionnoise.scenes",
    "load_trace": "frictionnoise.scenes",
    # exchange with tools that read xarray (the netcdf extra)
    "save_netcdf": "compare.io.netcdf", "load_netcdf": "compare.io.netcdf",
    # measured data
    "MeasuredData": "frictionnoise.measurements", "read_measured": "frictionnoise.measurements",
    "DisplacementAnalysis": "frictionnoise.measurements", "analyze_displacement": "frictionnoise.measurements",
    "ForceAnalysis": "frictionnoise.measurements", "analyze_force": "frictionnoise.measurements",
    "identify": "compare.analysis.identify", "Mechanism": "compare.analysis.identify",
}

__all__ = ["G", "package_version", "atomic_write", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        value = getattr(import_module(_LAZY[name]), name)
        globals()[name] = value  # looked up once
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
