"""The report of a measured velocity series: several displacement records at different speeds (the paper's Fig. 15)."""
from __future__ import annotations

from pathlib import Path

from ..analysis.velocity_series import LEVEL_HALF_WIDTH, MODEL_I_ASSUMPTION, VelocitySeries
from .html import esc, paragraphs, span, table
from .study import Figure, StudyResult


def build_series_report(series: VelocitySeries, analyses: list, sources: list):
    """Results (StudyResult list) and the JSON summary of a velocity series over the records ``sources``."""
    from frictionnoise.base import package_version

    from . import plots

    s = series
    names = [Path(p).name for p in sources]
    summary = {"version": package_version(), "kind": "velocity_series", "sources": list(sources),
               "records": [a.summary() for a in analyses], "velocity_series": s.summary()}
    how = ("the geometric centre of the band common to every record's fit band"
           if s.omega_auto else "given with --omega")
    err_how = ("weighted least squares in log-log with each record's error of ln C_x from the spectrum's band "
               "averaging" if s.exponent_err_source == "per-record" else
               "least squares in log-log, interval from the residual scatter (the per-record errors do not explain it)")
    col = s.collapse
    rows = [[esc(n), f"{1e3 * v:.4g}", f"{g:.2f} ± {ge:.2f}", f"{c:.3e}", f"{e:.3f}", f"{lv:.3e}"]
            for n, v, g, ge, c, e, lv in zip(names, s.v, s.gamma, s.gamma_err, s.C_at_omega, s.ln_C_err,
                                              s.level_alpha2_Na)]
    text = paragraphs([
        f"{len(analyses)} records. omega* = {s.omega:.4g} rad/s ({how}; the records' fit bands share "
        f"{span(*s.common_band)} rad/s). C_x(omega*) is the average of each spectrum over a factor "
        f"{LEVEL_HALF_WIDTH:.3g} either side of omega*, moved along the record's slope.",
        f"C_x(omega*) ~ v^({s.exponent:.3f} ± {s.exponent_err:.3f}) (95 %, {err_how}). Model I predicts v^3 (eq. 6); "
        "the paper measures v^(5/3) on concrete.",
        f"Collapse in q = omega / v (section 2): the spread of ln C across records is {col['spread_frequency_domain']:.3g} "
        f"at common omega and {col['spread_distance_domain']:.3g} for v C_x(q v) at common q (gain "
        f"{col['collapse_gain']:.3g}; above 1 the noise is set by position).",
        esc(MODEL_I_ASSUMPTION) + "; the level is the geometric mean over each record's fit band, meaningful where "
        "gamma is near 4.",
    ]) + table("Records", ["file", "v (mm/s)", "gamma (95 %)", "C_x(omega*) (m^2 s)", "s.e. of ln C_x",
                           "model I alpha^2/(N a) (1/m)"], rows)
    fig15 = plots.velocity_series_figure([(a.C_x.omega, a.C_x.C, f"v = {1e3 * v:.3g} mm/s")
                                          for a, v in zip(analyses, s.v)], s.v, s.C_at_omega, s.exponent,
                                         s.exponent_err, s.omega)
    coll = plots.collapse_figure([(a.C_x.omega / v, v * a.C_x.C, f"v = {1e3 * v:.3g} mm/s")
                                  for a, v in zip(analyses, s.v)])
    figures = (
        Figure("series_Cx", plots.figure_png_bytes(fig15),
               f"Left: C_x against omega for each speed; right: C_x(omega* = {s.omega:.3g} rad/s) against v with "
               f"the fitted v^({s.exponent:.2f} ± {s.exponent_err:.2f}) (like the paper's Fig. 15)."),
        Figure("series_collapse", plots.figure_png_bytes(coll),
               "The spectra in the distance domain: v C_x(omega = q v) against q = omega / v (section 2)."),
    )
    return [StudyResult("velocity_series", "Measured velocity series", {}, figures, text)], summary
