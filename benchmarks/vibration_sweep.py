"""The vibration sweep's answer: in-band C_x of each shaken cell over its unshaken twin (same seed), gamma, the mean
speed, against the rigid-contact prediction; the line at omega_v and its harmonics masked in the band.

Reads the task files of ``frictionnoise sweep scenarios/sweeps/vibration_sweep_{force,velocity}.toml -o DIR``:

    python -m benchmarks.vibration_sweep DIR_FORCE DIR_VELOCITY [--band 20 150]

Prediction (reduced_models.vibration): each pad's law is mu N sign(w) + c w on its velocity w relative to the
substrate. The block and pads, coupled to the substrate by the viscous part N c, follow its velocity except for the
share |i omega M| / |N c + i omega M| (M: block and pads), so the pads slip relative to it with the velocity
amplitude U = share A omega (rigid contacts, a slider held at v). The mean Coulomb part is mu N (2/pi) arcsin(v/U)
(1 for U <= v), its slope adds 2 mu N / (pi sqrt(U^2 - v^2)) to c, and eq. (A11)'s C_x ~ v / s^2 (the scene's
response is viscous: N c / M = 3000 rad/s lies above the band) gives the in-band factor, with the speed of the
constant force drive rising as the mean friction falls. The pads' compliance (mu N / k0 = 7.6 um; no reversal below
:func:`reduced_models.vibration.minimum_amplitude`) and their resonance (291 Hz) lie outside this prediction.
"""
import argparse
import json
from collections import defaultdict
from pathlib import Path

import numpy as np

from reduced_models.vibration import (compliant_mean_ratio, effective_slope, in_band_factor, minimum_amplitude,
                                      steady_speed)

N, M_TOT, C, MU_N, V = 30, 0.1 + 30 * 1e-3, 10.0, 0.6 * (0.1 * 9.81 / 30 + 1e-3 * 9.81), 5e-3
DEFLECTION = MU_N / 3333.0


def _load(folder):
    out = defaultdict(dict)
    for f in Path(folder, "tasks").glob("*.json"):
        d = json.loads(f.read_text())
        if "C" not in d or d["params"].get("duration") != 6.0:
            continue
        p = d["params"]
        out[(p["vibration.frequency"], p["vibration.amplitude"])][d["seed"]] = d
    return out


def _masked_level(d, band, f_v):
    w, C = np.asarray(d["omega"]), np.asarray(d["C"])
    m = (w >= band[0]) & (w < band[1])
    wv = 2 * np.pi * f_v
    for k in range(1, 8):  # the line and its harmonics, +-15 %
        m &= ~((w > 0.85 * k * wv) & (w < 1.15 * k * wv))
    return float(np.exp(np.mean(np.log(C[m])))), w[m], C[m]


def _gamma(w, C):
    if len(w) < 4:
        return float("nan")
    return float(-np.polyfit(np.log(w), np.log(C), 1)[0])


def prediction(f, A, constant_force):
    w = 2 * np.pi * f
    share = abs(1j * w * M_TOT) / abs(N * C + 1j * w * M_TOT)
    U = share * A * w
    if U <= V:
        return 1.0, 1.0, share, U
    F_per_pad = MU_N + C * V
    v1 = steady_speed(F_per_pad, MU_N, C, U) if constant_force else V
    s1 = float(effective_slope(v1, U, MU_N, C))
    return float(in_band_factor(V, v1, C, s1)), v1 / V, share, U


def source_factor(f, A, v1):
    """The noise source's own change: the patches' noise is a fluctuation of mu, so of the Coulomb part, whose cycle
    mean scales by the compliant contact's mean ratio R (Jenkins element at the pads' relative amplitude share A
    and xi = v1 / U); its power by R^2."""
    w = 2 * np.pi * f
    share = abs(1j * w * M_TOT) / abs(N * C + 1j * w * M_TOT)
    return compliant_mean_ratio(min(v1 / (share * A * w), 1.0), share * A / DEFLECTION) ** 2


def table(folder, constant_force, band):
    cells = _load(folder)
    twins = {}
    for (f, A), seeds in cells.items():
        if A == 0:
            twins.update(seeds)
    rows = []
    for (f, A), seeds in sorted(cells.items()):
        if A == 0:
            continue
        ratios, gammas, speeds = [], [], []
        for s, d in seeds.items():
            if s not in twins:
                continue
            lv, w, C = _masked_level(d, band, f)
            lv0, _, _ = _masked_level(twins[s], band, f)
            ratios.append(lv / lv0)
            gammas.append(_gamma(w, C))
            speeds.append(d["mean_velocity"] / twins[s]["mean_velocity"])
        if not ratios:
            continue
        pred, pspeed, share, U = prediction(f, A, constant_force)
        pred_src = pred * source_factor(f, A, pspeed * V)
        xi = V / (A * 2 * np.pi * f)
        n = len(ratios)
        ci = lambda x: 2 * np.std(x, ddof=1) / np.sqrt(n) if n > 1 else float("nan")  # noqa: E731
        rows.append((f, A, xi, share, V / U if U > 0 else float("inf"), np.mean(ratios), ci(ratios), pred, pred_src,
                     np.mean(gammas), ci(gammas), np.mean(speeds), pspeed,
                     A / float(minimum_amplitude(min(V / U, 1.0), DEFLECTION)) if U > V else 0.0, n))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("force")
    ap.add_argument("velocity")
    ap.add_argument("--band", nargs=2, type=float, default=(20.0, 150.0))
    a = ap.parse_args(argv)
    for label, folder, cf in (("constant force", a.force, True), ("constant velocity", a.velocity, False)):
        print(f"\n### {label}\n")
        print("| f (Hz) | A (um) | xi = v/(A omega) | held share | v/U | C_x / twin (band, line masked) | slope only | "
              "slope and source | "
              "gamma | speed / twin | predicted | A / A_min | seeds |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in table(folder, cf, a.band):
            f, A, xi, share, xu, rat, rci, pred, psrc, g, gci, sp, psp, amin, n = r
            print(f"| {f:.0f} | {A * 1e6:.0f} | {xi:.3g} | {share:.3f} | {xu:.3g} | {rat:.3f} +- {rci:.3f} | {pred:.3f} | "
                  f"{psrc:.3g} | "
                  f"{g:.2f} +- {gci:.2f} | {sp:.4f} | {psp:.4f} | {amin:.2g} | {n} |")


if __name__ == "__main__":
    main()
