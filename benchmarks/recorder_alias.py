"""Aliasing of the recorded forces: point samples once per output step against the output step's average.

The recorder (engine_sim/record.py) reads the contacts once per output step, so its force fields (F_t,
pad_force) are point samples of signals that vary within the step; a force sensor behind an anti-alias filter
reports averages. This measures the difference on a shipped scene: one run recorded at every pymunk step
(``dt_out = dt``; the path is the same as at the scene's own output step, only sampled more often), then

- point-sampled every m-th step (m = the scene's dt_out / dt: what the recorder delivers today), and
- block-averaged over m steps (what an averaging recorder would deliver),

and C_F of the whole friction force F_t of both, per log band up to the coarse Nyquist frequency, against the
true C_F (the every-step series' own spectrum over the same bands): point / true above 1 is power from above the
Nyquist frequency folded into the band; the block average is compared with the true spectrum times the
average's known filter |sin(w T/2) / (m sin(w dt/2))|^2 (T = m dt), which it should equal if it does not alias.

    python -m benchmarks.recorder_alias [--scene pads_rough_profile] [--duration 4] [--seed 0] [--smoke]
    python -m benchmarks.recorder_alias --scene scenarios/sweeps/pads_with_wear_study.toml --set wear.count=25

A scene with wear grains adds the same table for the grains' summed force on the pads (the wear study's C_F of the
grains and its eq. (B2) comparison read that force). ``--scene`` takes a shipped name or a scenario file, ``--set
section.key=value`` changes one field (repeatable).
"""
from __future__ import annotations

import argparse
import sys

import numpy as np

import engine_sim
from compare.analysis.spectra import band_average, force_series_spectrum
from engine_sim import load_scenario, shipped_scenarios


def _scenario(name: str, sets: list):
    """A shipped scene by name or a scenario file, with ``section.key=value`` changes (values read as TOML)."""
    import tomllib

    from engine_sim.scenario import scenario_from_dict
    sc = load_scenario(shipped_scenarios().get(name, name))
    if not sets:
        return sc
    d = sc.to_dict()
    for item in sets:
        key, _, val = item.partition("=")
        sec, _, field = key.partition(".")
        d[sec][field] = tomllib.loads(f"v = {val}")["v"]
    return scenario_from_dict(d, where=name)


def measure(name: str, duration: float, seed: int, sets: list = ()) -> dict:
    sc = _scenario(name, list(sets))
    m = int(round(sc.run.dt_out / sc.run.dt))
    fine = sc.with_run(dt_out=sc.run.dt, duration=duration)
    tr = engine_sim.run(fine, seed=seed)
    n = (len(tr.t) - 1) // m * m
    out = {"scene": name, "sets": list(sets), "m": m, "duration": duration,
           **_alias(tr.t[:n], tr.F_t[:n], m, sc.run.dt, sc.run.dt_out)}
    if tr.p_force.shape[1]:
        out["grains"] = _alias(tr.t[:n], tr.p_force[:n].sum(axis=1), m, sc.run.dt, sc.run.dt_out)
    return out


def _alias(t, F, m: int, dt: float, dt_out: float) -> dict:
    """Point samples and block averages of the every-step series F (every m-th of times t) against its own C_F."""
    t_c = t[::m]
    point = F[::m]
    avg = F.reshape(-1, m).mean(axis=1)
    nper = min(1024, len(t_c) // 4)
    sp, sa = force_series_spectrum(t_c, point, nperseg=nper), force_series_spectrum(t_c, avg, nperseg=nper)
    nyq = np.pi / dt_out
    d_omega = 2 * np.pi / (nper * dt_out)
    edges = np.geomspace(max(nyq / 256, 3 * d_omega), nyq, 9)
    sf = force_series_spectrum(t, F, nperseg=nper * m)
    rp, ra, rf = band_average(sp, edges), band_average(sa, edges), band_average(sf, edges)
    # a block average over m steps multiplies the true spectrum by |sin(w T/2) / (m sin(w dt/2))|^2 (T = m dt)
    w = sf.omega
    h2 = (np.sin(w * m * dt / 2) / (m * np.sin(w * dt / 2))) ** 2
    rh = band_average(sf, edges, values=h2 * sf.C)
    return {"edges_rad_s": edges.tolist(), "point_over_true": (rp / rf).tolist(),
            "average_over_true_filtered": (ra / rh).tolist(), "filter": (rh / rf).tolist()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="pads_rough_profile")
    ap.add_argument("--duration", type=float, default=4.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE")
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    r = measure(a.scene, 0.3 if a.smoke else a.duration, a.seed, a.set)
    print(f"{r['scene']}{' (' + ', '.join(r['sets']) + ')' if r['sets'] else ''}, {r['duration']:g} s, m = {r['m']} "
          "steps per output step. Per band: C_F of the point samples over the true C_F (the every-step series), C_F "
          "of the block averages over the true C_F times the block average's own filter, and that filter")
    for title, part in (("friction force F_t", r), ("grains' summed force on the pads", r.get("grains"))):
        if part is None:
            continue
        e = part["edges_rad_s"]
        print(f"\n{title}\n\n| band (rad/s) | point / true | average / (true x filter) | filter |\n|---|---|---|---|")
        for i in range(len(e) - 1):
            print(f"| {e[i]:.0f}-{e[i + 1]:.0f} | {part['point_over_true'][i]:.3f} | "
                  f"{part['average_over_true_filtered'][i]:.3f} | {part['filter'][i]:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
