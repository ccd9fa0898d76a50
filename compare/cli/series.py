"""`frictionnoise analyze` over several displacement records: the velocity series (C_x at one omega against v)."""
from __future__ import annotations

from pathlib import Path

from .options import UserError, output_dir


def analyze_series(args, read) -> int:
    """Several displacement records at different speeds: each analysed, then compared as a velocity series.

    ``read(path, args)`` reads one record as the analyze options describe it.
    """
    from ..analysis.displacement import analyze_displacement
    from ..analysis.velocity_series import velocity_series
    from ..report.html import write_report
    from ..report.series_report import build_series_report

    band = tuple(args.band) if args.band else None
    out = output_dir(args.output, f"analyze-series-{Path(args.data[0]).stem}", "index.html and summary.json")
    analyses = []
    for path in args.data:
        data = read(path, args)
        try:
            analyses.append(analyze_displacement(data, mass=args.mass, band=band, method=args.method,
                                                 discrete=args.discrete))
        except ValueError as e:
            raise UserError(f"{path}: {e}") from None
    try:
        series = velocity_series(analyses, omega=args.omega)
    except ValueError as e:
        raise UserError(str(e)) from None
    sections, summary = build_series_report(series, analyses, args.data)
    write_report(out, sections, summary, title=f"frictionnoise analyze: {len(args.data)} records against speed")
    for path, a in zip(args.data, analyses):
        print(f"{path}: v = {a.mean_velocity:.4g} m/s, gamma = {a.fit.gamma:.3f} +- {a.fit.gamma_err:.3f} over "
              f"{a.fit.band[0]:.3g}-{a.fit.band[1]:.3g} rad/s")
    s = series
    if s.omega_auto:
        print(f"omega = {s.omega:.4g} rad/s: inside every record's fit band ({s.common_band[0]:.3g}-"
              f"{s.common_band[1]:.3g} rad/s), where the least precise record's level is most precise "
              "(--omega W compares at another frequency)")
    print(f"wrote {out / 'index.html'}: C_x(omega = {s.omega:.4g} rad/s{', automatic' if s.omega_auto else ''}) ~ "
          f"v^({s.exponent:.3f} +- {s.exponent_err:.3f}) (95 %, {s.exponent_err_source}); collapse gain in "
          f"q = omega / v {s.collapse['collapse_gain']:.3g}; model I alpha^2/(N a) = "
          + ", ".join(f"{x:.3g}" for x in s.level_alpha2_Na) + " 1/m (assumes m eta1 v = f_kin)")
    return 0
