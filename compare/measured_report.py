"""The report of measured data (``frictionnoise analyze``): C_x, C_F (eq. 3), C_mu, the rms (eq. 4) and gamma of
a measured x(t). Beside its pipeline, ``compare.measured`` (reading the data)."""
from __future__ import annotations

from pathlib import Path

from reduced_models._version import package_version

from .fits import fit_power_law
from .html import esc, paragraphs
from .study import Figure, StudyResult

__all__ = ["build_measured_report"]


def build_measured_report(data, mass: float, band=None, g: float = 9.81):
    """Results (StudyResult list) and summary of measured x(t), with block mass ``mass`` (kg)."""
    from . import plots
    from .spectra import displacement_spectrum, force_spectrum, friction_coefficient_spectrum, rms_from_spectrum

    spec = displacement_spectrum(data.t, data.x)
    fit = fit_power_law(spec, band=band)
    cf = force_spectrum(spec, mass)
    cmu = friction_coefficient_spectrum(spec, g)
    zeta_rms = rms_from_spectrum(spec)
    mu_rms = rms_from_spectrum(cmu)
    summary = {"version": package_version(), "source": data.source, "mass_kg": mass, "n_samples": len(data.t),
               "dt_s": float(data.t[1] - data.t[0]), "resampled": data.resampled, "warning": data.warning,
               "gamma": fit.gamma, "gamma_err": fit.gamma_err, "band": list(fit.band), "fit": fit.to_dict(),
               "mean_velocity": spec.provenance["mean_velocity"], "zeta_rms_m": zeta_rms, "mu_rms": mu_rms,
               "spectrum_steps": spec.provenance["steps"]}
    text = paragraphs([
        f"{len(data.t)} samples every {data.t[1] - data.t[0]:.4g} s; mean velocity {1e3 * summary['mean_velocity']:.4g} mm/s"
        + (f". {esc(data.warning)}" if data.warning else "."),
        f"gamma = {fit.gamma:.3f} &plusmn; {fit.gamma_err:.3f} (95 %) over {fit.band[0]:.3g}-{fit.band[1]:.3g} rad/s"
        f"{' (automatic band)' if fit.band_auto else ''}; zeta_rms = {zeta_rms:.4g} m and mu_rms = {mu_rms:.4g} "
        "(dimensionless) over the resolved band (eq. 4). C_F = M^2 omega^4 C_x assumes the block is free (inertial "
        f"relation, eq. 3), with M = {mass:g} kg.",
        "Processing: " + esc("; ".join(spec.provenance["steps"])) + ".",
    ])
    figures = (
        Figure("measured_Cx", plots.figure_png_bytes(plots.spectrum_figure([(spec, "C_x")], fits=[(fit, "")], band=fit.band,
                                                                          title="Displacement spectrum")),
               f"C_x of the measured displacement (m^2 s) with the power-law fit: gamma = {fit.gamma:.2f} ± "
               f"{fit.gamma_err:.2f} over {fit.band[0]:.3g}-{fit.band[1]:.3g} rad/s (shaded)."),
        Figure("measured_CF", plots.figure_png_bytes(plots.spectrum_figure([(cf, "C_F = M^2 omega^4 C_x")], ylabel=r"$C_F$ (N$^2$ s)",
                                                                          title="Force spectrum (eq. 3)")),
               f"C_F (N^2 s) of a free block of M = {mass:g} kg, from C_x by eq. (3): slope {4 - fit.gamma:+.2f} in the fit band."),
        Figure("measured_Cmu", plots.figure_png_bytes(plots.spectrum_figure([(cmu, "C_mu = omega^4 C_x / g^2")], ylabel=r"$C_\mu$ (s)",
                                                                           title="Friction coefficient spectrum")),
               f"C_mu (s) = omega^4 C_x / g^2; mu_rms = {mu_rms:.3g} over the resolved band (eq. 4)."),
    )
    return [StudyResult("measured", f"Measured displacement: {Path(data.source).name}", {}, figures, text)], summary
