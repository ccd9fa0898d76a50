"""Spectra, fits, parameter extraction and reports: turn traces into comparable numbers.

The folders are the roles, and imports run one way (``cli`` -> ``report`` | ``sweep`` -> ``io`` -> ``analysis``,
checked by import-linter, ``[tool.importlinter]`` in pyproject.toml):

- :mod:`compare.analysis`: numerics on arrays and traces (spectra, estimators, fits, parameter extraction,
  balances, episode statistics, the velocity and wear-study statistics, work-precision);
- :mod:`compare.io`: data in and out (measured text tables, input checks, traces, atomic output folders);
- :mod:`compare.report`: studies and their pages (study, studies/, html, plots: the only matplotlib importer);
- :mod:`compare.sweep`: sweep files, tasks and their scheduling;
- :mod:`compare.cli`: the ``frictionnoise`` command line.

The public names are imported on first use (PEP 562), so that `frictionnoise` starts without loading scipy and
a Ctrl-C during start-up reaches the command line's handler (one line, exit 130) instead of an import.
"""
from importlib import import_module

_PUBLIC = {
    "PowerLawFit": "analysis.fits", "fit_power_law": "analysis.fits", "Spectrum": "analysis.spectra",
    "band_average": "analysis.spectra", "displacement_spectrum": "analysis.spectra",
    "force_series_spectrum": "analysis.spectra", "force_spectrum": "analysis.spectra",
    "friction_coefficient_spectrum": "analysis.spectra", "log_bin": "analysis.spectra",
    "rms_from_spectrum": "analysis.spectra", "series_spectrum": "analysis.spectra",
}
__all__ = list(_PUBLIC)


def __getattr__(name):
    if name in _PUBLIC:
        return getattr(import_module(f".{_PUBLIC[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
