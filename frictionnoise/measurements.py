"""Measured data from Python: read an instrument's export, analyse a displacement x(t) or a friction force F(t).

:func:`read_measured` reads CSV, semicolon- or tab-separated text with a preamble, a units row and decimal
commas, into SI units; :func:`analyze_displacement` and :func:`analyze_force` give the spectra of eq. (2)
and their power-law fits.
"""
from __future__ import annotations

from dataclasses import dataclass

from compare.fits import PowerLawFit, fit_power_law
from compare.io.measured import MeasuredData, read_measured
from compare.report.measured_report import ForceAnalysis, analyze_force
from compare.spectra import (Spectrum, displacement_spectrum, force_spectrum, friction_coefficient_spectrum,
                             rms_from_spectrum)

__all__ = ["read_measured", "MeasuredData", "analyze_displacement", "DisplacementAnalysis", "analyze_force",
           "ForceAnalysis"]


@dataclass(frozen=True)
class DisplacementAnalysis:
    """What a displacement record x(t) gives. Spectra in the eq. (2) convention.

    Attributes
    ----------
    C_x : Spectrum
        Displacement spectrum of zeta = x - (x0 + v t) (m^2 s).
    fit : PowerLawFit
        C_x ~ omega^-gamma: ``fit.gamma``, its 95 % half-width ``fit.gamma_err``, the band (rad/s), the flags.
    mean_velocity : float
        The fitted sliding speed v (m/s).
    zeta_rms : float
        rms of zeta over the resolved band, eq. (4) (m).
    C_mu : Spectrum
        Friction-coefficient spectrum omega^4 C_x / g^2 (s) of a free block (eq. 3 divided by (M g)^2).
    mu_rms : float
        rms of mu over the resolved band (dimensionless).
    C_F : Spectrum or None
        Force spectrum M^2 omega^4 C_x (N^2 s, eq. 3), when a mass was given.
    mass : float or None
        The block mass M (kg), when given.
    """

    C_x: Spectrum
    fit: PowerLawFit
    mean_velocity: float
    zeta_rms: float
    C_mu: Spectrum
    mu_rms: float
    C_F: Spectrum | None = None
    mass: float | None = None


def analyze_displacement(t, x=None, *, mass: float | None = None, band=None, method: str | None = None,
                         g: float = 9.81) -> DisplacementAnalysis:
    """C_x, its exponent gamma, the velocity and C_mu of a displacement record; C_F when the mass is known.

    gamma, C_x and C_mu do not depend on the block's mass; only C_F = M^2 omega^4 C_x (eq. 3) does.

    Parameters
    ----------
    t : array_like or MeasuredData
        Times (s), uniformly sampled; or a record read by :func:`read_measured` (then ``x`` is its ``x``).
    x : array_like, optional
        Positions (m) at ``t``.
    mass : float, optional
        Block mass M (kg): adds C_F.
    band : tuple of float, optional
        Fit band (rad/s); default: the widest straight stretch (see :func:`compare.fits.fit_power_law`).
    method : {"whittle", "lsq"}, optional
        Fit method; default :data:`compare.fits.DEFAULT_METHOD`.
    g : float, optional
        Gravitational acceleration for C_mu (m/s^2).

    Returns
    -------
    DisplacementAnalysis
        The spectra, the fit, the velocity and the rms values.
    """
    if isinstance(t, MeasuredData):
        if t.x is None:
            raise ValueError(f"{t.source}: the record holds no displacement column")
        t, x = t.t, t.x
    if x is None:
        raise ValueError("give x(t): the positions (m) at the times t (s)")
    if mass is not None and not mass > 0:
        raise ValueError(f"mass must be positive (got {mass!r})")
    spec = displacement_spectrum(t, x)
    fit = fit_power_law(spec, band=band, method=method)
    cmu = friction_coefficient_spectrum(spec, g)
    return DisplacementAnalysis(
        C_x=spec, fit=fit, mean_velocity=float(spec.provenance["mean_velocity"]), zeta_rms=rms_from_spectrum(spec),
        C_mu=cmu, mu_rms=rms_from_spectrum(cmu), C_F=None if mass is None else force_spectrum(spec, mass),
        mass=mass)
