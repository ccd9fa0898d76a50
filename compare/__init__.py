"""Spectra, fits, parameter extraction and reports: turn traces into comparable numbers.

The public names are imported on first use (PEP 562), so that `frictionnoise` starts without loading scipy and
a Ctrl-C during start-up reaches the command line's handler (one line, exit 130) instead of an import.
"""
from importlib import import_module

_PUBLIC = {
    "PowerLawFit": "fits", "fit_power_law": "fits", "Spectrum": "spectra", "band_average": "spectra",
    "displacement_spectrum": "spectra", "force_series_spectrum": "spectra", "force_spectrum": "spectra",
    "friction_coefficient_spectrum": "spectra", "log_bin": "spectra", "rms_from_spectrum": "spectra",
    "series_spectrum": "spectra",
}
__all__ = list(_PUBLIC)


def __getattr__(name):
    if name in _PUBLIC:
        return getattr(import_module(f".{_PUBLIC[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
