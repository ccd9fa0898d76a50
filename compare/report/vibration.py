"""The vibration sweep's section (paper section 10: does a vibration out of the band show in the band?): each shaken
cell of pads_friction_patches against its unshaken twin (same seed), set against the rigid-contact predictions of
:mod:`reduced_models.vibration`.

Read from the task files of ``frictionnoise sweep scenarios/sweeps/vibration_sweep_<drive>_<f>hz.toml`` (the line at
omega_v and its harmonics already removed from x(t) by :func:`compare.analysis.harmonics.remove_harmonics`):
per cell the in-band C_x ratio to the twin (geometric mean of the log-binned C_x over the band), beside the square
of the measured Coulomb part's ratio (the patches' noise is a fluctuation of mu, so of the Coulomb part: a contact
that the vibration makes reverse averages the part and its fluctuation alike, and the power goes as its square), the
fitted gamma
(Whittle, the task's band), the mean Coulomb part of the friction (from the force balance) and the drive's mean
force over the twin's,
and the mean speed over the twin's; each as the mean over seeds with a Student-t 95 % interval of the paired values.

Prediction: each pad's law is mu N sign(w) + c w on its velocity w relative to the substrate. The block and pads,
carried by the viscous part N c, follow the substrate except for the share |i omega M| / |N c + i omega M| of its
velocity (M: block and pads), which the pads see as slip of amplitude U = share A omega. Rigid contacts: the mean
Coulomb part is (2/pi) arcsin(v/U) of its value (1 for U <= v). With the pads' springs and masses in the linear
motion the pads slip relative to the substrate with the share :meth:`VibratedScene.pad_share` of its motion, which
sets the onset of reversal, A_onset = v / (pad share omega), and an arcsin law of its own; a compliant contact (pad spring k0, deflection
d = mu N / k0) does not reverse below the minimum amplitude and reaches the arcsin law only at a few d (the Jenkins
element, :func:`reduced_models.vibration.compliant_mean_ratio`). The constant force drive's speed rises as the mean
falls (:func:`reduced_models.vibration.steady_speed`); the constant velocity drive's mean force falls with it.
"""
from __future__ import annotations

import json
import math
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["VibratedScene", "load_tasks", "cells", "prediction", "answer", "section"]


@dataclass(frozen=True)
class VibratedScene:
    """The shaken scene's constants (SI): pads N, block mass M (kg), pad mass m (kg), per-pad viscous c (N s/m),
    mu0, pad spring k0 (N/m), sliding speed v (m/s), the band (rad/s). Defaults: scenarios/sweeps/vibrated_patches
    and vibrated_velocity."""

    N: int = 30
    M: float = 0.1
    m: float = 1e-3
    c: float = 10.0
    mu0: float = 0.6
    k0: float = 3333.0
    v: float = 5e-3
    band: tuple = (20.0, 150.0)
    k_drive: float = 100.0
    warmup: float = 0.5
    duration: float = 11.0

    def relaxed_share(self) -> float:
        """The share of a step in the velocity drive's mean force that the record's mean sees as relaxed: the drive
        spring relaxes to a new mean friction through the viscous part with tau = N c / k_drive (3 s), from the
        start of the vibration; over a record from ``warmup`` to ``warmup + duration`` the mean keeps the fraction
        (tau / T) (exp(-w / tau) - exp(-(w + T) / tau)) of the step unrelaxed. Returns 1 less that fraction."""
        tau = self.N * self.c / self.k_drive
        return 1.0 - tau / self.duration * (math.exp(-self.warmup / tau) - math.exp(-(self.warmup + self.duration) / tau))

    def __post_init__(self):
        for name in ("M", "m", "c", "mu0", "k0", "v", "k_drive", "duration"):
            if not getattr(self, name) > 0:
                raise ValueError(f"VibratedScene.{name} must be > 0 (got {getattr(self, name)!r})")

    @property
    def mu_n(self) -> float:
        """Coulomb part per pad (N): mu0 times the pad's share of the block's weight and its own."""
        return self.mu0 * 9.81 * (self.M / self.N + self.m)

    def pad_share(self, omega: float) -> float:
        """|x_p| / A: the pads' slip amplitude relative to the substrate over its amplitude, for contacts that do
        not reverse (the motion is linear): the block (M) on the pads' springs (N k0), the pads (N m) on the viscous
        part (N c), every mass under the inertial force -m s''. Its rigid-pad limit (k0 -> inf) is the held share."""
        K, C, mp = self.N * self.k0, self.N * self.c, self.N * self.m
        a = np.array([[K - self.M * omega ** 2, -K], [-K, K + 1j * omega * C - mp * omega ** 2]])
        return float(abs(np.linalg.solve(a, np.array([self.M, mp]) * omega ** 2)[1]))

    @property
    def deflection(self) -> float:
        """mu N / k0 (m): the pad's deflection at the onset of slip, the scale of the minimum amplitude."""
        return self.mu_n / self.k0


def load_tasks(folders) -> list:
    """Every task result (dict) with a spectrum under ``folder/tasks`` for each folder."""
    out = []
    for folder in folders:
        for f in sorted(Path(folder, "tasks").glob("*.json")):
            d = json.loads(f.read_text())
            if "C" in d:
                out.append(d)
    return out


def _t95(n: int) -> float:
    from scipy.stats import t

    return float(t.ppf(0.975, n - 1)) if n > 1 else float("nan")


def _level(d, band) -> float:
    w, C = np.asarray(d["omega"]), np.asarray(d["C"])
    m = (w >= band[0]) & (w <= band[1])
    return float(np.exp(np.mean(np.log(C[m]))))


def _mean_ci(x) -> tuple[float, float]:
    """Mean and Student-t 95 % half-width of the finite values (a seed whose fit failed drops out)."""
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    if not len(x):
        return float("nan"), float("nan")
    return float(x.mean()), _t95(len(x)) * float(x.std(ddof=1)) / math.sqrt(len(x)) if len(x) > 1 else float("nan")


def _coulomb(d, sc: VibratedScene) -> float:
    """Mean Coulomb part of the friction (N) from the force balance: the drive's mean force less the viscous part's
    mean N c v (the law is linear in the relative velocity, whose mean is the mean speed, read from the positions).
    The sampled F_t is not used: the output step is phase-locked to the vibration (4 samples per period at 1 kHz),
    so the mean of its samples of a force that reverses each cycle is biased."""
    return d["mean_F_drive"] - sc.N * sc.c * d["mean_velocity"]


def _speed(F: float, sc: VibratedScene, ratio) -> float:
    """The constant force drive's steady speed V: the per-pad force F balances ratio(V) mu N + c V, with ratio(V)
    the mean Coulomb part's ratio at speed V (increasing in V), by bisection between v and F / c."""
    lo, hi = sc.v, F / sc.c
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) * sc.mu_n + sc.c * mid < F else (lo, mid)
    return 0.5 * (lo + hi)


def prediction(f: float, A: float, constant_force: bool, sc: VibratedScene = VibratedScene()) -> dict:
    """The mean Coulomb part's ratio to its unshaken value for the substrate shaken at f (Hz) with amplitude A (m),
    three ways: rigid pads (arcsin at the held share's slip amplitude), the linear pads' slip share (arcsin), a
    massless compliant pad (Jenkins element at the held share's amplitude); under the constant force drive each at
    its own steady speed (the speed rises as the mean falls), with that speed's ratio; under the constant velocity
    drive the drive force's and the speed's record means (the drive spring's relaxation included)."""
    from reduced_models.vibration import arcsin_ratio, compliant_mean_ratio

    w = 2 * math.pi * f
    M = sc.M + sc.N * sc.m
    share = abs(1j * w * M) / abs(sc.N * sc.c + 1j * w * M)
    pad = sc.pad_share(w)
    models = {"rigid": lambda V: float(arcsin_ratio(min(V / (share * A * w), 1.0))),
              "pads": lambda V: float(arcsin_ratio(min(V / (pad * A * w), 1.0))),
              "compliant": lambda V: float(compliant_mean_ratio(min(V / (share * A * w), 1.0),
                                                                share * A / sc.deflection, steps=1024, cycles=3))}
    out = {"share": share, "U": share * A * w, "A_over_deflection": share * A / sc.deflection, "pad_share": pad,
           "A_onset": sc.v / (pad * w), "drive_force": not constant_force}
    F = sc.mu_n + sc.c * sc.v  # per pad
    rel = sc.relaxed_share()
    for name, ratio in models.items():
        if constant_force:
            V = _speed(F, sc, ratio)
            out["coulomb_" + name], out["speed_" + name] = ratio(V), V / sc.v
        else:  # the record's means, with the drive spring's relaxation (VibratedScene.relaxed_share)
            R = ratio(sc.v)
            step = 1.0 - (R * sc.mu_n + sc.c * sc.v) / F  # the steady drive force's fall, over its unshaken value
            out["coulomb_" + name], out["drive_" + name] = R, 1.0 - step * rel
            # the block gains the stretch the spring gives up over the record: its mean speed rises by
            # dF (1 - rel) / (tau k_drive) = dF (1 - rel) / (N c), dF = step N F
            out["speed_" + name] = 1.0 + step * F * (1.0 - rel) / (sc.c * sc.v)
    return out


def cells(tasks: list, sc: VibratedScene = VibratedScene()) -> list:
    """One row per shaken cell (frequency, amplitude): paired ratios to the unshaken twin of the same seed (the task
    with amplitude 0), gamma, with their intervals, beside :func:`prediction`. ``constant_force`` is read from the
    twin's mean drive force (fixed under the force drive: every seed's equal)."""
    by = defaultdict(dict)
    for d in tasks:
        if "mean_F_drive" not in d or "vibration.amplitude" not in d["params"]:
            continue  # a task file written before the sweep kept its mean forces, or not a vibration sweep's
        p = d["params"]
        by[(p["vibration.frequency"], p["vibration.amplitude"])][d["seed"]] = d
    twins = {}
    for (f, A), seeds in by.items():
        if A == 0:
            twins.update(seeds)
    if not twins:
        return []
    drives = [d["mean_F_drive"] for d in twins.values()]
    constant_force = bool(np.ptp(drives) < 1e-9 * abs(np.mean(drives)))
    rows = []
    for (f, A), seeds in sorted(by.items()):
        pairs = [(d, twins[s]) for s, d in sorted(seeds.items()) if s in twins and A > 0]
        if not pairs:
            continue
        q = {"C_ratio": [_level(d, sc.band) / _level(t, sc.band) for d, t in pairs],
             "gamma": [d["fit"].get("gamma", np.nan) for d, _ in pairs],
             "gamma_twin": [t["fit"].get("gamma", np.nan) for _, t in pairs],
             # the seed's own shaken-minus-unshaken difference: the seeds' common scatter cancels in it
             "gamma_rise": [d["fit"].get("gamma", np.nan) - t["fit"].get("gamma", np.nan) for d, t in pairs],
             "coulomb": [_coulomb(d, sc) / _coulomb(t, sc) for d, t in pairs],
             "coulomb_sq": [(_coulomb(d, sc) / _coulomb(t, sc)) ** 2 for d, t in pairs],
             "drive": [d["mean_F_drive"] / t["mean_F_drive"] for d, t in pairs],
             "speed": [d["mean_velocity"] / t["mean_velocity"] for d, t in pairs]}
        row = {"frequency": f, "amplitude": A, "xi": sc.v / (A * 2 * math.pi * f), "seeds": len(pairs),
               "constant_force": constant_force, "line": float(np.mean([d.get("line_removed", {}).get("amplitude", [np.nan])[0]
                                                                       for d, _ in pairs]))}
        for k, x in q.items():
            row[k], row[k + "_ci"] = _mean_ci(x)
        row["gamma_fit_err"] = float(np.mean([d["fit"].get("gamma_err", np.nan) for d, _ in pairs]))
        row.update(prediction(f, A, constant_force, sc))
        rows.append(row)
    return rows


def _shows(r) -> bool:
    """The in-band level differs from the twin's beyond its interval."""
    return abs(r["C_ratio"] - 1) > r["C_ratio_ci"]


def answer(rows: list, sc: VibratedScene = VibratedScene()) -> str:
    """The paper's question answered in one paragraph, with the measured numbers."""
    parts = []
    for f in sorted({r["frequency"] for r in rows}):
        rs = [r for r in rows if r["frequency"] == f]
        inside = sc.band[0] <= 2 * math.pi * f <= sc.band[1]
        where = "inside the band" if inside else f"{2 * math.pi * f / sc.band[1]:.0f}x the band's top"
        for cf in (True, False):
            rr = sorted((r for r in rs if r["constant_force"] == cf), key=lambda r: r["amplitude"])
            if not rr:
                continue
            shown = [r for r in rr if _shows(r)]
            low = rr[-1]
            drive = "constant force" if cf else "constant velocity"
            txt = (f"{f:g} Hz ({where}), {drive}: at the largest amplitude ({low['amplitude'] * 1e6:.3g} um, xi = "
                   f"{low['xi']:.2g}, A / A_onset = {low['amplitude'] / low['A_onset']:.2g}) C_x in the band is "
                   f"{low['C_ratio']:.3g} &plusmn; {low['C_ratio_ci']:.2g} of the twin's, gamma {low['gamma']:.2f} "
                   f"&plusmn; {low['gamma_ci']:.2f} (twin {low['gamma_twin']:.2f})")
            if shown:
                quiet = [r for r in rr if not _shows(r) and r["amplitude"] < shown[0]["amplitude"]]
                txt += (f"; it shows from A = {shown[0]['amplitude'] * 1e6:.3g} um (xi = {shown[0]['xi']:.2g}, "
                        f"A / A_onset = {shown[0]['amplitude'] / shown[0]['A_onset']:.2g}) up")
                if quiet:
                    txt += (f", not at {quiet[-1]['amplitude'] * 1e6:.3g} um (A / A_onset = "
                            f"{quiet[-1]['amplitude'] / quiet[-1]['A_onset']:.2g}: "
                            f"{quiet[-1]['C_ratio']:.3g} &plusmn; {quiet[-1]['C_ratio_ci']:.2g})")
            else:
                txt += "; no amplitude of the sweep shows beyond its interval"
            parts.append(txt + ".")
    return " ".join(parts)


def section(rows: list, sc: VibratedScene = VibratedScene()):
    """The StudyResult: the table, the figure and the answer."""
    from . import plots
    from .html import paragraphs, table
    from .study import Figure, StudyResult

    head = ["f (Hz)", "drive", "A (um)", "xi", "A / A_onset", "C_x / twin", "(Coulomb / twin)^2", "gamma",
            "Coulomb / twin", "rigid", "linear pads", "compliant", "speed / twin", "drive force / twin", "seeds"]
    body = [[f"{r['frequency']:g}", "force" if r["constant_force"] else "velocity", f"{r['amplitude'] * 1e6:.3g}",
             f"{r['xi']:.3g}", f"{r['amplitude'] / r['A_onset']:.2g}",
             f"{r['C_ratio']:.3g} &plusmn; {r['C_ratio_ci']:.2g}",
             f"{r['coulomb_sq']:.3g} &plusmn; {r['coulomb_sq_ci']:.2g}",
             f"{r['gamma']:.2f} &plusmn; {r['gamma_ci']:.2f}", f"{r['coulomb']:.3f} &plusmn; {r['coulomb_ci']:.3f}",
             f"{r['coulomb_rigid']:.3f}", f"{r['coulomb_pads']:.3f}", f"{r['coulomb_compliant']:.3f}",
             f"{r['speed']:.3f} &plusmn; {r['speed_ci']:.3f}", f"{r['drive']:.3f} &plusmn; {r['drive_ci']:.3f}",
             str(r["seeds"])] for r in rows]
    fig = plots.vibration_figure(rows)
    html = paragraphs([answer(rows, sc)]) + table(
        "Shaken cells against their unshaken twins (95 % Student-t intervals over paired seeds; the line at omega_v "
        "and its first 4 harmonics fitted and removed from x(t) before the spectrum)", head, body)
    cap = ("In-band C_x over the unshaken twin, gamma, the mean Coulomb part over the twin's and the mean speed "
           "(constant force) against xi = v / (A omega_v): measured (95 % intervals over paired seeds) and the "
           "predictions (dashed: rigid pads; dash-dot: the linear pads' slip share; dotted: a massless compliant "
           "pad); thin vertical: the onset of reversal, A = v / (pad share omega_v).")
    return StudyResult("vibration_sweep", "Vibration out of and inside the band (paper section 10)",
                       {"rows": rows}, (Figure("vibration_sweep", plots.figure_png_bytes(fig), cap),), html)
