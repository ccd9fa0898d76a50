"""The rate-and-state spring-slider against rsfmodel (jrleeman/rsfmodel, Leeman & May; quasi-static, scipy odeint).

rsfmodel is not a dependency and none of its code is in this repository: point RSFMODEL_PATH at a checkout of it
(``git clone https://github.com/jrleeman/rsfmodel``; measured with commit d04d546) and run

    RSFMODEL_PATH=/tmp/rsfmodel_src .venv/bin/python -m compare.studies.rate_state_vs_rsfmodel

Cases (rsfmodel's example units in SI: D_c = 10 um, mu0 = 0.6, V_ref = 1 um/s, k = 1e-3 per um of the friction
coefficient, i.e. k / sigma = 1e3 1/m):
0. rsfmodel's own example, a = 0.005, b = 0.01, k = 2 k_c, step 1 -> 10 um/s at t = 10 s, ageing law (with the slip
   law both codes run away: a tenfold step leaves the slip law's finite basin of steady sliding);
1. the velocity step 1 -> 10 um/s at t = 10 s with a = 0.01, b = 0.005 (steady-state strengthening), both laws,
   40 s at 100 Hz;
2. a = 0.005, b = 0.01, k = 1.2 k_c, step 1 -> 1.2 um/s at t = 10 s: decaying oscillations, both laws, 200 s;
3. the same at k = k_c with the step 1 -> 1.05 um/s: the neutral oscillation, both laws, 200 s.
Our slider runs quasi-static (eta = 0) as rsfmodel does. Writes study-results/rate_state_vs_rsfmodel.md.
"""
from __future__ import annotations

import os
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import scipy.integrate

from reduced_models import rate_state as rs
from compare.studies.study_page import write_page

OUT = Path("study-results") / "rate_state_vs_rsfmodel.md"


def _rsfmodel():
    path = os.environ.get("RSFMODEL_PATH")
    if not path:
        sys.exit("set RSFMODEL_PATH to a checkout of github.com/jrleeman/rsfmodel")
    if not hasattr(scipy.integrate, "cumtrapz"):  # rsfmodel calls the name scipy removed in 1.14
        scipy.integrate.cumtrapz = scipy.integrate.cumulative_trapezoid
    sys.path.insert(0, path)
    from rsfmodel import rsf, staterelations
    return rsf, staterelations


def run_rsfmodel(p: rs.SpringSliderParams, t, vlp):
    rsf, st = _rsfmodel()
    m = rsf.Model()
    m.mu0, m.a, m.k, m.v, m.vref = p.mu0, p.A, p.k / p.sigma, p.V0, p.V0
    s = st.DieterichState() if p.law == "ageing" else st.RuinaState()
    s.b, s.Dc = p.B, p.D_c
    m.state_relations = [s]
    m.time, m.loadpoint_velocity = t, vlp
    t0 = time.perf_counter()
    r = m.solve()
    return r.friction.copy(), r.slider_velocity.copy(), r.states[:, 0].copy(), time.perf_counter() - t0


def compare(p, duration, t_step, v2):
    t = np.arange(0, duration + 1e-9, 0.01)
    vlp = np.where(t >= t_step, v2, p.V_lp)
    mu_r, V_r, th_r, el_r = run_rsfmodel(p, t, vlp)
    t0 = time.perf_counter()
    tr = rs.simulate(p, len(t) * 0.01, 0.01, load_steps=[(t_step, v2)], rtol=1e-11)
    el = time.perf_counter() - t0
    return {"dmu": np.abs(tr.mu - mu_r).max(), "dV": np.abs(tr.V / V_r - 1).max(),
            "dtheta": np.abs(tr.theta / th_r - 1).max(), "mu_range": np.ptp(mu_r), "V_range": (V_r.min(), V_r.max()),
            "t_rsf": el_r, "t_ours": el}


def main():
    base = rs.SpringSliderParams(A=0.005, B=0.01, D_c=1e-5, mu0=0.6, V0=1e-6, sigma=1e7, k=1e10, V_lp=1e-6, eta=0.0)
    kc = rs.critical_stiffness(base)
    rs.simulate(base, 1.0, 0.1)  # compile
    rows = [("rsfmodel's example: k = 2 k_c, step 1 -> 10 um/s, a = 0.005, b = 0.01, ageing",
             compare(base, 40.0, 10.0, 1e-5))]
    for law in ("ageing", "slip"):
        p = replace(base, law=law, A=0.01, B=0.005)
        rows.append((f"velocity step 1 -> 10 um/s, a = 0.01, b = 0.005, {law}", compare(p, 40.0, 10.0, 1e-5)))
    for law in ("ageing", "slip"):
        p = replace(base, law=law, k=1.2 * kc)
        rows.append((f"k = 1.2 k_c, step 1 -> 1.2 um/s, {law}", compare(p, 200.0, 10.0, 1.2e-6)))
    for law in ("ageing", "slip"):
        p = replace(base, law=law, k=kc)
        rows.append((f"k = k_c, step 1 -> 1.05 um/s, {law}", compare(p, 200.0, 10.0, 1.05e-6)))
    lines = ["# Rate-and-state spring-slider against rsfmodel", "",
             "Produced by `RSFMODEL_PATH=... python -m compare.studies.rate_state_vs_rsfmodel` (rsfmodel commit d04d546, "
             "scipy odeint, rtol = atol = 1e-12 in (mu, theta); ours: Dormand-Prince 5(4) in (ln V, ln theta), "
             "rtol = 1e-11, eta = 0). Sampled at 100 Hz; maxima over every sample.", "",
             "| case | max abs diff mu | friction range | max rel diff V | max rel diff theta | V range (m/s) | rsfmodel s | ours s |",
             "|---|---|---|---|---|---|---|---|"]
    for name, r in rows:
        lines.append(f"| {name} | {r['dmu']:.2e} | {r['mu_range']:.4f} | {r['dV']:.2e} | {r['dtheta']:.2e} | "
                     f"{r['V_range'][0]:.3g}-{r['V_range'][1]:.3g} | {r['t_rsf']:.3f} | {r['t_ours']:.3f} |")
    write_page(OUT, lines)


if __name__ == "__main__":
    main()
