"""Where the scene departs from the arcsin law (2/pi) arcsin(xi), and why: measured on a flat track of uniform friction
(patches, alpha = 0), substrate shaken along x, mean Coulomb friction over whole periods from the drive's force.

1. compliance: the shipped pads (k0 = 3333 N/m, mu N / k0 = 7.6 um) at xi = 0.5, 10 Hz, amplitude 3-300 um (the
   speed v = xi A omega set to keep xi), stiff velocity drive; against a massless pad on its spring k0 behind a
   Coulomb contact (:func:`reduced_models.vibration.compliant_mean_ratio`);
2. resonance: the same pads at xi = 0.5, A = 200 um, 10-450 Hz (pad resonance sqrt(k0/m) = 290 Hz);
3. the shipped scene (pads_friction_patches: 0.1 kg block, constant force, c = 10 N s/m per pad) at xi 0.1-0.9,
   10 Hz: the mean friction (Coulomb + viscous), the mean speed, and how much of the substrate's velocity the block
   follows (the block's velocity amplitude at omega in the substrate's frame over A omega: 1 held in the laboratory,
   0 dragged along).

    python -m compare.studies.vibration_departures [--periods P]
"""
import argparse
import os
import time
import tomllib

import numpy as np

import engine_sim
from engine_sim import scenario_from_dict, shipped_scenarios
from reduced_models.vibration import arcsin_ratio, compliant_mean_ratio


def flat(A, f, v, k0=3333.0, c0=0.0, dt=1e-4, periods=5, dt_out=None):
    d = {"name": "flat", "block": {"M": 0.1},
         "pads": {"N": 30, "mass": 1e-3, "radius": 0.3e-3, "k0": k0, "c0": c0, "k_normal": 833.0, "track_spacing": 5e-3},
         "friction": {"law": "linear", "mu0": 0.6, "c": 0.01}, "substrate": {"kind": "patches", "a": 1e-3, "alpha": 0.0},
         "drive": {"kind": "velocity", "v": v, "k_drive": 5e5},
         "run": {"dt": dt, "dt_out": dt_out or dt, "duration": periods / f, "warmup": max(0.2, 2 / f), "iterations": 10,
                 "seed": 0}}
    if A > 0:
        d["vibration"] = {"target": "substrate", "direction": "parallel", "amplitude": A, "frequency": f}
    return scenario_from_dict(d)


def coulomb(tr, c=0.01, N=30):
    return float(np.mean(tr.F_drive[:-1]) - c * N * tr.metadata["scenario"]["drive"]["v"])


def ratio(A, f, xi, **kw):
    v = xi * A * 2 * np.pi * f
    c0 = coulomb(engine_sim.run(flat(0.0, f, v, **kw)))
    return coulomb(engine_sim.run(flat(A, f, v, **kw))) / c0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--periods", type=int, default=5)
    a = ap.parse_args(argv)
    t0 = time.time()
    print(f"load average: {os.getloadavg()[0]:.2f} (2 cores)\n")
    xi = 0.5
    d = 0.6 * (0.1 * 9.81 / 30 + 1e-3 * 9.81) / 3333.0  # mu N / k0 of the shipped pads (m)
    print(f"## 1. Pad compliance (xi = {xi}, 10 Hz, k0 = 3333 N/m, mu N / k0 = {d * 1e6:.2f} um)\n")
    print("| A (um) | A / (mu N / k0) | measured / unshaken | compliant pad (Jenkins) | rigid arcsin |")
    print("|---|---|---|---|---|")
    for A in (3e-6, 6e-6, 12e-6, 25e-6, 50e-6, 100e-6, 300e-6):
        r = ratio(A, 10.0, xi, periods=a.periods)
        print(f"| {A * 1e6:.0f} | {A / d:.2g} | {r:.4f} | {float(compliant_mean_ratio(xi, A / d)):.4f} | "
              f"{float(arcsin_ratio(xi)):.4f} |")
    print(f"\n## 2. Pad resonance (xi = {xi}, A = 200 um, sqrt(k0/m) / 2 pi = {np.sqrt(3333 / 1e-3) / 2 / np.pi:.0f} Hz)\n")
    print("| f (Hz) | f / f_pad | measured / unshaken | rigid arcsin |")
    print("|---|---|---|---|")
    for f in (10.0, 50.0, 100.0, 200.0, 290.0, 450.0):
        r = ratio(200e-6, f, xi, periods=a.periods)
        print(f"| {f:.0f} | {f / 290.6:.2f} | {r:.4f} | {float(arcsin_ratio(xi)):.4f} |")
    print("\n## 3. The shipped scene (pads_friction_patches, constant force, 0.1 kg block, c = 10 N s/m per pad), 10 Hz\n")
    print("| xi | A (um) | mean friction / unshaken | mean speed / unshaken | block's share of A omega in the substrate frame |")
    print("|---|---|---|---|---|")
    base = tomllib.loads(shipped_scenarios()["pads_friction_patches"].read_text())
    f, v = 10.0, 5e-3
    run = {**base["run"], "duration": a.periods / f, "warmup": 0.5, "dt_out": 1e-4}
    tr0 = engine_sim.run(scenario_from_dict({**base, "run": run}))
    F0, V0 = np.mean((tr0.F_t + tr0.F_drag)[:-1]), (tr0.x[-1] - tr0.x[0]) / tr0.t[-1]
    for x in (0.1, 0.3, 0.5, 0.7, 0.9):
        A = v / (x * 2 * np.pi * f)
        tr = engine_sim.run(scenario_from_dict({**base, "run": run, "vibration": {
            "target": "substrate", "direction": "parallel", "amplitude": A, "frequency": f}}))
        F1, V1 = np.mean((tr.F_t + tr.F_drag)[:-1]), (tr.x[-1] - tr.x[0]) / tr.t[-1]
        w = 2 * np.pi * f
        X = np.column_stack([np.sin(w * tr.t[:-1]), np.cos(w * tr.t[:-1]), np.ones(len(tr.t) - 1)])
        cs = np.linalg.lstsq(X, tr.v[:-1], rcond=None)[0]
        held = np.hypot(cs[0], cs[1]) / (A * w)
        print(f"| {x} | {A * 1e6:.0f} | {F1 / F0:.4f} | {V1 / V0:.4f} | {held:.3f} |")
    print(f"\nwall {time.time() - t0:.0f} s; load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
