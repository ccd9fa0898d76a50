"""The paper's velocity analysis over runs that differ in sliding speed: C_x at fixed omega against v, and the
collapse of the spectra in the distance domain (section 2)."""
from __future__ import annotations

import numpy as np

__all__ = ["velocity_analysis"]


def velocity_analysis(results: list, omega_ref=(70.0, 140.0), omega_max: float | None = None) -> dict:
    """The paper's velocity analysis over results that differ in v.

    - C_x at fixed omega: the mean over ``omega_ref`` of each run's spectrum (averaged over seeds), fitted
      against v in log-log (eq. 6 predicts C_x ~ v^3 for model I; the paper measures v^(5/3) on concrete).
    - Collapse (section 2): in the distance domain zeta(s), s = v t, the spectrum is C_s(q) = v C_x(omega = q v);
      if the noise is set by position, curves for different v coincide. The spread is the mean over a common
      abscissa grid of the standard deviation across velocities of ln C; ``collapse_gain`` is the spread in the
      frequency domain (ln C_x at common omega) over that in the distance domain (ln v C_x at common q), both on
      the range where every curve is defined and below ``omega_max`` (default: no limit); NaN when the curves
      share no range of q (a record's lowest frequency times v_max / v_min above the highest one kept).
    """
    from scipy import stats

    by_v: dict = {}
    for r in results:
        by_v.setdefault(float(r["v"]), []).append(r)
    vs = np.array(sorted(by_v))
    if len(vs) < 2:
        raise ValueError("velocity analysis needs results at two or more velocities")
    curves = []
    for v in vs:
        rs = by_v[v]
        w = np.asarray(rs[0]["omega"])
        C = np.mean([np.interp(np.log(w), np.log(r["omega"]), np.log(r["C"])) for r in rs], axis=0)
        keep = w <= omega_max if omega_max else np.ones(len(w), bool)
        curves.append((v, w[keep], C[keep]))
    lo, hi = omega_ref
    level = []
    for v, w, lnC in curves:
        m = (w >= lo) & (w <= hi)
        if not m.any():
            raise ValueError(f"no spectral point of the run at v = {v:g} m/s lies in omega_ref {omega_ref}")
        level.append(float(np.mean(lnC[m])))
    level = np.array(level)
    res = stats.linregress(np.log(vs), level)
    tq = float(stats.t.ppf(0.975, max(len(vs) - 2, 1)))

    def spread(xs_list, ys_list):
        a = max(x[0] for x in xs_list)
        b = min(x[-1] for x in xs_list)
        if not b > a:
            return float("nan"), (a, b)
        g = np.linspace(a, b, 200)
        Y = np.array([np.interp(g, x, y) for x, y in zip(xs_list, ys_list)])
        return float(np.mean(np.std(Y, axis=0))), (float(np.exp(a)), float(np.exp(b)))

    s_freq, r_freq = spread([np.log(w) for _, w, _ in curves], [lnC for _, _, lnC in curves])
    s_dist, r_dist = spread([np.log(w / v) for v, w, _ in curves], [lnC + np.log(v) for v, _, lnC in curves])
    return {
        "velocities": vs.tolist(), "omega_ref": list(omega_ref), "ln_C_at_omega_ref": level.tolist(),
        "exponent": float(res.slope), "exponent_err": tq * float(res.stderr) if len(vs) > 2 else float("nan"),
        "spread_frequency_domain": s_freq, "frequency_range": r_freq,
        "spread_distance_domain": s_dist, "q_range": r_dist,
        # no common q range (the slowest run's lowest q above the fastest run's highest): no collapse measured
        "collapse_gain": s_freq / s_dist if s_dist > 0 else float("nan") if np.isnan(s_dist) else float("inf"),
    }
