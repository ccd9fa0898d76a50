"""Does contact ageing give C_x ~ v^(5/3)? C_x at omega ~ 0.4 1/s and the omega^-4 band level against v.

    .venv/bin/python -m compare.studies.velocity_scaling [--quick]

Measured fact (the paper, text after eq. A12 and Fig. 15): rubber on concrete, C_x(omega ~ 0.4 1/s) ~ v^(5/3) over
2.2-425 um/s, where model I's eq. (A12) gives v^3.

What is fixed and where it comes from:
- A - B: the steady-state slope d mu / d ln v of rubber A on concrete, fitted here to the paper's Table 1 (the data
  of its Fig. 9; both loads pooled).
- B / A, D_c and the fresh-contact age theta_r: assumptions, scanned (no values for rubber could be verified).
- Model I's block, springs, renewal length a = 1 mm, N = 30, alpha = 1, F_kin = 5 N: the paper's reference case,
  independent of v; model I's m eta1 = f_kin / v (eq. A12's assumption that v f'_kin(v) is constant, a log law).
- The ageing model's contacts carry F_N / N = 0.67 N (F_N = 20 N, mu ~ 0.5 as in Table 1) at every speed.

Simulations: 900 s (the paper's run length) sampled at 100 Hz, 2 seeds per speed, 10 speeds from 2 um/s to 2 mm/s
(1/3 decade apart). C_x(0.4) is the band average over 0.3-0.55 rad/s (Welch segments of a quarter run); the omega^-4 level is the band average of
omega^4 C_x over 5-50 rad/s (the paper's reference band; at the two top speeds it reaches into v/a). Exponents: least
squares of ln C on ln v over all (speed, seed) points of a range, 95 % interval from Student's t with the residual
scatter (so curvature widens it); over the full range and over the paper's 2-431 um/s. Each run is cached in
study-results/velocity_scaling_runs.json (delete it to recompute). Writes study-results/velocity_scaling.md
and .png.
"""
from __future__ import annotations

import json
import math
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy import stats

from compare.analysis.spectra import band_average, displacement_spectrum
from reduced_models import ageing as ag
from reduced_models import rate_state as rs
from reduced_models import spring_block as sb
from compare.studies.study_page import write_page

RES = Path("study-results")
CACHE = RES / "velocity_scaling_runs.json"
SPEEDS = 2e-6 * 10 ** (np.arange(10) / 3)  # 2 um/s ... 2 mm/s
PAPER = SPEEDS <= 4.4e-4  # 2-431 um/s, the paper's 2.2-425 um/s
OMEGA, BAND04, BAND4 = 0.4, (0.3, 0.55), (5.0, 50.0)

# Table 1 of the paper, rubber A on concrete: (v um/s, mu) at F_N = 32.86 N (rows 1-3) and 60.72 N (rows 4-7)
TABLE1_CONCRETE = [(16, 0.43), (37, 0.54), (101, 0.57), (2.24, 0.36), (146, 0.65), (268, 0.74), (425, 0.81)]


def fig9_slope():
    v, mu = np.array(TABLE1_CONCRETE).T
    r = stats.linregress(np.log(v), mu)
    t = stats.t.ppf(0.975, len(v) - 2)
    return r.slope, t * r.stderr


def exponent(v, C):
    x, y = np.log(np.asarray(v)), np.log(np.asarray(C))
    r = stats.linregress(x, y)
    return r.slope, stats.t.ppf(0.975, len(x) - 2) * r.stderr


def configs(a_minus_b):
    """The simulated cases: name -> parameters at speed v."""
    out = {"model I": lambda v: sb.SpringBlockParams(v=v)}
    for ratio, Dc in ((1 / 3, 1e-4), (2 / 3, 1e-4), (1 / 3, 1e-3)):
        A = a_minus_b / (1 - ratio)
        B = A - a_minus_b
        out[f"ageing B/A={ratio:.2f} D_c={Dc:.0e}"] = (lambda v, A=A, B=B, Dc=Dc: ag.AgeingParams(v=v, A=A, B=B, D_c=Dc))
        for th in (1e-3, 1e-2):
            if ratio == 2 / 3 and th == 1e-3:
                continue
            out[f"ageing+reset B/A={ratio:.2f} D_c={Dc:.0e} theta_r={th:.0e}"] = (
                lambda v, A=A, B=B, Dc=Dc, th=th: ag.AgeingParams(v=v, A=A, B=B, D_c=Dc, renewal_state=th))
    return out


def run_one(p, seed, duration):
    mod = sb if isinstance(p, sb.SpringBlockParams) else ag
    t0 = time.process_time()
    tr = mod.simulate(p, duration, 1e-2, seed=seed)
    cpu = time.process_time() - t0
    sp = displacement_spectrum(tr.t, tr.x)
    # C_x(0.4) from segments a quarter of the run (resolution 2 pi / 225 s = 0.028 rad/s): the default 16 segments
    # resolve 0.11 rad/s, and on an omega^-4 slope their window's main lobe lifts the 0.3-0.55 rad/s band by ~1.5
    slow = displacement_spectrum(tr.t, tr.x, nperseg=len(tr.t) // 4)
    return {"C04": float(band_average(slow, list(BAND04))[0]),
            "lvl4": float(band_average(sp, list(BAND4), sp.C * sp.omega**4)[0]),
            "v_mean": float(sp.provenance.get("mean_velocity", p.v)), "cpu": cpu,
            "theory04": float(band_average(slow, list(BAND04), mod.theory_spectrum(p, slow.omega))[0])}


def theory_scan(a_minus_b):
    """Linear-response exponents (no state reset) on a grid of B/A and D_c: C_x(0.4) from eq. (A10) with the
    ageing slope, local exponent extremes and the least-squares exponent over both ranges."""
    vs = np.logspace(np.log10(2e-6), np.log10(2e-3), 61)
    paper = vs <= 4.4e-4
    rows = []
    for ratio in (0.0, 1 / 3, 0.5, 2 / 3, 0.9):
        A = a_minus_b / (1 - ratio)
        B = A - a_minus_b
        for Dc in (1e-5, 1e-4, 1e-3, 1e-2):
            C = np.array([ag.theory_spectrum(ag.AgeingParams(v=v, A=A, B=B, D_c=Dc), np.array([OMEGA]))[0] for v in vs])
            loc = np.gradient(np.log(C), np.log(vs))
            rows.append((ratio, Dc, np.polyfit(np.log(vs), np.log(C), 1)[0],
                         np.polyfit(np.log(vs[paper]), np.log(C[paper]), 1)[0], loc.min(), loc.max()))
    C1 = np.array([sb.theory_spectrum(sb.SpringBlockParams(v=v), np.array([OMEGA]))[0] for v in vs])
    m1 = (np.polyfit(np.log(vs), np.log(C1), 1)[0], np.polyfit(np.log(vs[paper]), np.log(C1[paper]), 1)[0])
    return rows, m1, vs, C1


def a_for_five_thirds():
    """Model I's renewal length a at which the least-squares exponent of C_x(0.4) over 2-431 um/s is 5/3."""
    vs = np.logspace(np.log10(2.2e-6), np.log10(4.25e-4), 40)
    def expo(a):
        C = [sb.theory_spectrum(sb.SpringBlockParams(v=v, a=a), np.array([OMEGA]))[0] for v in vs]
        return np.polyfit(np.log(vs), np.log(C), 1)[0]
    from scipy.optimize import brentq
    return brentq(lambda la: expo(10**la) - 5 / 3, -6.5, -2.5), expo


def kc_peak():
    """The spectral signature near k_c (needs B > A). In the paper's geometry (constant drive force) B > A makes the
    whole block's steady sliding unstable at any k0 (the friction slope at omega -> 0, (f_n / v)(A - B), is
    negative), so the signature belongs to a spring-driven slider: its displacement answers a force noise with
    chi = 1 / (k + i omega [(sigma / V)(A - B / (1 + i omega D_c / V)) + eta]), whose |chi|^2 peaks near
    (V / D_c) sqrt((B - A) / A) as k -> k_c. Default spring-slider parameters (B = 2 A)."""
    p = rs.SpringSliderParams()
    kc = rs.critical_stiffness(p)
    w0 = rs.onset_frequency(p)
    w = np.logspace(np.log10(w0) - 2, np.log10(w0) + 2, 801)
    curves = {}
    for f in (2.0, 1.2, 1.05):
        chi = 1.0 / (f * kc + 1j * w * (p.sigma / p.V_lp * rs.rate_sensitivity(p.A, p.B, p.D_c, p.V_lp, w) + p.eta))
        curves[f] = np.abs(chi) ** 2
    peaks = {f: w[np.argmax(c)] for f, c in curves.items()}
    return p, kc, w0, w, curves, peaks


def main(quick=False):
    slope, slope_ci = fig9_slope()
    cache = json.loads(CACHE.read_text()) if CACHE.exists() else {}
    cfg = configs(slope)
    seeds = (0,) if quick else (0, 1)
    duration = 300.0 if quick else 900.0
    for name, make in cfg.items():
        for v in SPEEDS:
            for s in seeds:
                key = f"{name}|{v:.4e}|{s}|{duration}"
                if key in cache:
                    continue
                cache[key] = run_one(make(v), s, duration)
                CACHE.write_text(json.dumps(cache, indent=0))
                print(key, cache[key], f"load {os.getloadavg()[0]:.1f}", flush=True)
    # exponents
    table = []
    for name in cfg:
        rec = [(v, cache[f"{name}|{v:.4e}|{s}|{duration}"]) for v in SPEEDS for s in seeds]
        vv = np.array([r["v_mean"] for _, r in rec])
        nominal = np.array([v for v, _ in rec])
        C04 = np.array([r["C04"] for _, r in rec])
        L4 = np.array([r["lvl4"] for _, r in rec])
        inpaper = nominal <= 4.4e-4
        table.append((name, exponent(vv, C04), exponent(vv[inpaper], C04[inpaper]), exponent(vv, L4),
                      exponent(vv[inpaper], L4[inpaper]), np.median(C04 / np.array([r["theory04"] for _, r in rec]))))
    rows, m1, vs, C1 = theory_scan(slope)
    a53, expo = a_for_five_thirds()
    base, kc, w0, w, curves, peaks = kc_peak()
    write(slope, slope_ci, table, rows, m1, a53, base, kc, w0, peaks, duration, seeds, cache, cfg)
    figure(cache, cfg, duration, seeds, w, curves, w0)


def answer(table, speedup):
    """The plain answer, with the numbers of this run; ``speedup`` the largest mean speed / nominal speed of the
    reset runs."""
    t = {name: rest for name, *rest in table}
    f = lambda e: f"{e[0]:.2f} +- {e[1]:.2f}"
    m1 = t["model I"]
    plain = [k for k in t if k.startswith("ageing ")]
    reset = [k for k in t if k.startswith("ageing+reset")]
    lo = min(reset, key=lambda k: t[k][3][0])
    hi = max(reset, key=lambda k: t[k][3][0])
    c04 = [t[k][1][0] for k in reset]
    excess = [t[k][4] for k in reset]
    return [
        "Measured: C_x(0.4 1/s) ~ v^(5/3) for rubber on concrete over 2.2-425 um/s. Exponents below are over "
        "2-431 um/s, with 95 % intervals.",
        f"- Model I: C_x(0.4) ~ v^({f(m1[1])}), omega^-4 level ~ v^({f(m1[3])}): v^3, as eq. (A12) says.",
        "- Ageing contacts whose state only evolves by the state law (no reset at renewal) do NOT give 5/3: the state "
        "softens the contacts' friction slope from A to A - B at frequencies below v / D_c, which lifts C_x more at "
        "high speed, so the exponent rises above 3: C_x(0.4) ~ v^(" + ", ".join(f(t[k][1]) for k in plain) +
        ") for " + "; ".join(k.replace("ageing ", "") for k in plain) + " (linear theory: 3.0-4.0 over the whole "
        "B/A, D_c grid below).",
        "- Ageing contacts that restart young when they renew (state reset to a fresh age theta_r, then healing as "
        "log time) make low speeds noisier, because a contact that lived longer loses more strength when it "
        f"renews. The omega^-4 band level then scales as v^({f(t[lo][3])}) ({lo.replace('ageing+reset ', '')}) to "
        f"v^({f(t[hi][3])}) ({hi.replace('ageing+reset ', '')}): 5/3 lies inside this family (near B/A = 0.5 at "
        "D_c = 0.1 mm by interpolation between the two simulated ratios, not simulated itself), almost independent "
        "of theta_r (1 or 10 ms). At omega = 0.4 1/s itself, though, the same runs give exponents "
        f"{min(c04):.2f}-{max(c04):.2f} (intervals +-0.1-0.2), so ageing with renewal reproduces a v^(5/3) band "
        "level but not, with these parameters, the measured exponent at 0.4 1/s. (A reading not tested here: "
        "0.4 1/s lies below v / a at the top speeds, where every model flattens toward v^1, and near v / D_c in "
        "the middle, where the reset pulses change from steps to bumps.)",
        "- Model I alone reaches 5/3 at 0.4 1/s if the renewal length a is about 0.06 mm instead of 1 mm (table "
        "below): then 0.4 1/s lies below v / a at most speeds, in the omega^-2 part of the spectrum, which a "
        "measured omega^-4 spectrum down to 0.4 1/s would rule out.",
        "- What an experiment could check: with reset, (i) the mean speed at fixed drive rises (renewed contacts are "
        f"weaker: up to {speedup:.1f}x here at fixed F_drive), (ii) the omega^-4 level's exponent steepens with speed "
        f"(curved log-log plot, middle panel), (iii) C_x(0.4) exceeds the linear-response prediction by "
        f"{min(excess):.1f}-{max(excess):.0f}x (median over speeds). With B > A "
        "(not rubber on concrete) a spring-driven slider shows a quasi-periodic peak near (V / D_c) sqrt((B - A)/A) "
        "that sharpens as k -> k_c (right panel, last section).",
    ]


def write(slope, slope_ci, table, rows, m1, a53, base, kc, w0, peaks, duration, seeds, cache, cfg):
    f = lambda e: f"{e[0]:.2f} +- {e[1]:.2f}"
    speedup = max(r["v_mean"] / float(k.split("|")[1]) for k, r in cache.items() if k.startswith("ageing+reset"))
    cpu = [r["cpu"] for k, r in cache.items() if k.startswith("ageing") and k.endswith(f"|{duration}")]
    L = ["# Velocity scaling of C_x: does contact ageing give v^(5/3)?", "",
         "Produced by `python -m compare.studies.velocity_scaling` (method, fixed values and their sources in its "
         "docstring). Speeds 2 um/s - 2 mm/s, 10 per 3 decades; "
         f"{duration:.0f} s runs at 100 Hz, seeds {list(seeds)}. Exponents: least squares of ln C on ln v, "
         "95 % interval (Student t on the residual scatter).", "",
         "## Answer", "", *answer(table, speedup), "",
         "## Inputs", "",
         f"- A - B = {slope:.3f} +- {slope_ci:.3f} (95 %): slope of mu against ln v for rubber A on concrete, the 7 "
         "rows of the paper's Table 1 (the data of its Fig. 9), both loads pooled. Positive: steady sliding is "
         "velocity strengthening, so steady sliding cannot turn to stick-slip at any stiffness (k_c < 0).",
         "- B / A in {1/3, 2/3} (simulated; 0-0.9 in the linear theory), D_c in {0.1, 1} mm (1e-5 to 1e-2 m in the "
         "theory), fresh-contact age theta_r in {1, 10} ms: assumptions. F_N = 20 N (mu ~ 0.5), a = 1 mm, N = 30, "
         "alpha = 1: model I's reference case.", "",
         "## Simulated exponents", "",
         "| case | C_x(0.4) 2um-2mm/s | C_x(0.4) 2-431 um/s | omega^-4 level 2um-2mm/s | omega^-4 level 2-431 um/s | "
         "C_x(0.4) sim / linear theory (median) |", "|---|---|---|---|---|---|"]
    for name, e1, e2, e3, e4, ratio in table:
        L.append(f"| {name} | {f(e1)} | {f(e2)} | {f(e3)} | {f(e4)} | {ratio:.2f} |")
    L += ["", "## Linear-response exponents of C_x(0.4) (no state reset; eq. A10 with the ageing slope)", "",
          f"Model I: {m1[0]:.2f} over 2 um/s-2 mm/s, {m1[1]:.2f} over 2-431 um/s (not 3: at omega = 0.4 the top "
          f"speeds pass v/a = 0.4 1/s, where C_x(omega) turns to the omega^-2 regime, ~ a v). Model I's exponent over "
          f"2.2-425 um/s is 5/3 when a = {10**a53 * 1e3:.1f} mm; then omega = 0.4 lies below v/a for most speeds "
          f"and C_x there is no longer ~ omega^-4.", "",
          "| B/A | D_c (m) | exponent 2um-2mm/s | exponent 2-431 um/s | local min | local max |", "|---|---|---|---|---|---|"]
    for r in rows:
        L.append(f"| {r[0]:.2f} | {r[1]:.0e} | {r[2]:.2f} | {r[3]:.2f} | {r[4]:.2f} | {r[5]:.2f} |")
    L += ["", "## Near the critical stiffness (needs B > A, unlike Fig. 9)", "",
          "With the paper's constant drive force, B > A makes the whole block's steady sliding unstable at any k0 "
          "(the friction's slope at omega -> 0, N (f_n / v)(A - B), is negative), so no quasi-periodic peak can sit on "
          "a steady spectrum there. A spring-driven slider (stiffness k to a load point) has one: its displacement "
          "answers a force noise with chi = 1 / (k + i omega [(sigma / V)(A - B / (1 + i omega D_c / V)) + eta]). "
          f"Default spring-slider (A = {base.A}, B = {base.B}, D_c = {base.D_c} m, V = {base.V_lp} m/s): "
          f"(V / D_c) sqrt((B - A) / A) = {w0:.3f} rad/s; |chi|^2 peaks at " +
          ", ".join(f"{w:.3f} rad/s (k = {f_} k_c)" for f_, w in peaks.items()) +
          ", its height growing as (k - k_c)^-2.", "",
          f"Cost: ageing-model runs of {duration:.0f} s at 100 Hz took {np.median(cpu):.2f} s CPU (median; "
          f"{min(cpu):.2f}-{max(cpu):.2f}) under a load of 6-14 on 2 cores.", ""]
    write_page(RES / "velocity_scaling.md", L, load=False)


def figure(cache, cfg, duration, seeds, w, curves, w0):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for name in cfg:
        vv = np.array([[cache[f"{name}|{v:.4e}|{s}|{duration}"]["v_mean"] for s in seeds] for v in SPEEDS]).mean(1)
        c = np.array([[cache[f"{name}|{v:.4e}|{s}|{duration}"]["C04"] for s in seeds] for v in SPEEDS])
        l4 = np.array([[cache[f"{name}|{v:.4e}|{s}|{duration}"]["lvl4"] for s in seeds] for v in SPEEDS])
        ax[0].loglog(vv, c.mean(1), "o-", ms=3, label=name)
        ax[1].loglog(vv, l4.mean(1), "o-", ms=3, label=name)
    for a_ in ax[:2]:
        v = np.array([2e-6, 2e-3])
        ref = a_.get_lines()[0].get_ydata()[3] if a_.get_lines() else 1.0
        for e, ls in ((3, ":"), (5 / 3, "--")):
            a_.loglog(v, ref * (v / SPEEDS[3]) ** e, "k" + ls, lw=0.8, label=f"v^{e:.3g}")
        a_.axvspan(2.2e-6, 4.25e-4, color="0.9", zorder=0)
        a_.set_xlabel("mean sliding speed v (m/s)")
    ax[0].set_ylabel("C_x(omega = 0.4 1/s) (m^2 s)")
    ax[1].set_ylabel("<omega^4 C_x> over 5-50 rad/s (m^2 s^-3)")
    ax[0].legend(fontsize=6)
    for f_, c in curves.items():
        ax[2].loglog(w, c, label=f"k = {f_} k_c")
    ax[2].axvline(w0, color="k", ls="--", lw=0.8, label="(V/D_c) sqrt((B-A)/A)")
    ax[2].set_xlabel("omega (rad/s)")
    ax[2].set_ylabel("|chi|^2 (m^2/Pa^2 per unit area)")
    ax[2].legend(fontsize=7)
    ax[2].set_title("spring-slider, B = 2A, near k_c")
    fig.tight_layout()
    fig.savefig(RES / "velocity_scaling.png", dpi=110)


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
