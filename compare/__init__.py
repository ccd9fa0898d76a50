"""Spectra, fits, parameter extraction and reports: turn traces into comparable numbers."""
from .fits import PowerLawFit, fit_power_law
from .spectra import (
    Spectrum, band_average, displacement_spectrum, force_series_spectrum, force_spectrum,
    friction_coefficient_spectrum, log_bin, rms_from_spectrum, series_spectrum,
)

__all__ = [
    "PowerLawFit", "fit_power_law", "Spectrum", "band_average", "displacement_spectrum",
    "force_series_spectrum", "force_spectrum", "friction_coefficient_spectrum", "log_bin",
    "rms_from_spectrum", "series_spectrum",
]
