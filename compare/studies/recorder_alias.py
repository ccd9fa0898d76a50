"""The recorded forces against their exact means over the output step, per channel and log band.

The recorder (engine_sim/record.py) writes each force as its mean over the output step T by default
(``run.forces = "mean"``), from momenta read at the step's two ends (engine_sim/means.py). This
measures it on a shipped scene: one scene, one path, three recorders read it in the same loop,

- the default recording, every output step (what a run delivers);
- an every-step recording in the same mode (every pymunk step: the momenta give each step's own impulses, so its
  block average over the output step is the exact mean: the reference);
- an every-step recording of point samples (``forces = "point"``: each step's arbiter impulses / dt), taken every
  m-th step (what the recorder delivered before the means, and what the point mode still delivers).

Per channel (F_t, F_n, F_drag, F_drive, pad_force and micro_force: the spectra averaged over the bodies) and per
log band up to half the output Nyquist frequency: C_F of the default recording over C_F of the reference, and
C_F of their difference over the reference's (the error's share of the band); and the point samples' C_F over
the reference's (their aliasing).

One correction makes the reference exact where it would not be: pymunk moves a body by its velocity plus a
position-correction velocity (v_bias) where a contact overlaps, so the law's damper impulse -c v dt summed over a
step is the motion -c (dx + dv dt) less that part; the reference takes the dampers from the every-step velocities
themselves (c v per step), which the default recording cannot read (``damper_bias`` in the output: the part's rms
against F_t's fluctuation).

    python -m compare.studies.recorder_alias [--scene pads_rough_profile] [--duration 8] [--seed 0] [--smoke] [--json F]
    python -m compare.studies.recorder_alias --all --duration 8 --markdown study-results/recorder_alias_tables.md

``--scene`` takes a shipped name or a scenario file, ``--set section.key=value`` changes one field (repeatable).
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

from compare.analysis.spectra import band_average, force_series_spectrum
from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim import units as U
from engine_sim.record import Recorder
from engine_sim.loop import Loop, warm_up

CHANNELS = ("F_t", "F_n", "F_drag", "F_drive", "pad_force", "micro_force")


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


def record_three(sc, duration: float, seed: int):
    """The default recording, the every-step mean recording and the every-step point recording of one path, and
    per step the law's damper impulse rate from the sliders' own velocities, per slider (scene units)."""
    scene = Scene(sc, seed)
    warm_up(scene, int(round(sc.run.warmup / sc.run.dt_out)))
    n_sub = scene.n_sub
    n_out = int(round(duration / sc.run.dt_out))
    n_fine = (n_out - 1) * n_sub + 1
    coarse = Recorder(scene, n_out, forces="mean")
    fine = Recorder(scene, n_fine, forces="mean")
    point = Recorder(scene, n_fine, forces="point")
    c = scene.slider_terms[:, 1]
    bias = np.zeros((n_fine, len(scene.sliders)))  # c v_bias per step and slider (scene force units)
    prev = []  # the sliders' (x, v) at the previous step

    class Every:
        """The loop's recorder at every pymunk step: the default recording every n_sub-th, the two every-step
        recordings and the damper's bias at each."""

        def __init__(self):
            self.j = 0

        def sample(self):
            if self.j % n_sub == 0:
                coarse.sample()
            row = fine.k
            fine.sample()
            point.sample()
            st = fine.means_state[1:]
            if prev:
                bias[row] = c * ((st[:, 0] - prev[0]) / scene.dt - prev[1])
            prev[:] = st[:, 0].copy(), st[:, 2].copy()
            self.j += 1

    Loop(scene, Every(), n_out=n_fine, n_sub=1).run(n_fine)
    meta = {"scenario": sc.name}
    law_after = scene.law.impulses_after_step
    if law_after:
        bias[:] = 0.0  # no damper with the rate-and-state law in the shipped scenes (c = 0); its impulses are exact
    return coarse.trace(meta), fine.trace(meta), point.trace(meta), bias / U.FORCE, n_sub, scene


def _bands(t_c, nper, dt_out):
    """Log bands from the resolved bottom to half the Nyquist frequency: 7, or fewer on a short record (the smoke's
    0.3 s), so that each holds two spectral ordinates at least."""
    nyq = np.pi / dt_out
    d_omega = 2 * np.pi / (nper * dt_out)
    lo, hi = max(nyq / 256, 3 * d_omega), nyq / 2
    for k in range(8, 2, -1):
        edges = np.geomspace(lo, hi, k)
        if edges[1] - edges[0] >= 2 * d_omega:
            return edges
    return np.array([lo, hi])


def _spec(t, F, nper, edges):
    F = np.atleast_2d(F.T).T if F.ndim == 1 else F
    if not np.any(F - F.mean(axis=0)):  # an error of exactly zero
        return np.zeros(len(edges) - 1)
    acc = None
    for j in range(F.shape[1]):
        s = force_series_spectrum(t, F[:, j], nperseg=nper)
        b = band_average(s, edges)
        acc = b if acc is None else acc + b
    return acc / F.shape[1]


def measure(name: str, duration: float, seed: int, sets: list = ()) -> dict:
    sc = _scenario(name, list(sets))
    t0 = time.perf_counter()
    tc, tf, tp, bias, m, scene = record_three(sc, duration, seed)
    wall = time.perf_counter() - t0
    n = len(tc.t) - 1  # rows 1.. of the default recording cover fine rows (k-1) m + 1 .. k m
    corr_total = bias.sum(axis=1)
    refs = {
        "F_t": tf.F_t + corr_total, "F_drag": tf.F_drag - corr_total, "F_n": tf.F_n, "F_drive": tf.F_drive,
        "pad_force": tf.pad_force + bias[:, :tf.pad_force.shape[1]],
        "micro_force": tf.micro_force + bias[:, tf.pad_force.shape[1]:],
    }
    t_c = tc.t[1:n + 1]
    nper = min(1024, n // 4)
    edges = _bands(t_c, nper, sc.run.dt_out)
    out = {"scene": name, "sets": list(sets), "m": m, "duration": duration, "wall_s": wall,
           "edges_rad_s": edges.tolist(), "channels": {}}
    fluct = np.std(tf.F_t[1:])
    out["damper_bias_rms_over_F_t_rms"] = float(np.std(corr_total[1:]) / fluct) if fluct > 0 else 0.0
    for ch in CHANNELS:
        ref_all = refs[ch]
        if ref_all.ndim == 2 and ref_all.shape[1] == 0:
            continue
        ref = ref_all[1:n * m + 1].reshape((n, m) + ref_all.shape[1:]).mean(axis=1)
        got = getattr(tc, ch)[1:n + 1]
        pt = getattr(tp, ch)[m:n * m + 1:m]
        if np.std(ref) <= 1e-6 * np.abs(ref).mean() or np.abs(ref).max() < 1e-9:  # constant to 1e-6, or zero
            # (a constant force's drive; loads on flat tracks; a contact without friction)
            out["channels"][ch] = {"constant": True, "max_abs_error": float(np.abs(got - ref).max()),
                                   "mean": float(max(np.abs(ref).mean(), 1e-300))}
            continue
        sr, sg, se, sp = (_spec(t_c, a, nper, edges) for a in (ref, got, got - ref, pt))
        out["channels"][ch] = {"recorded_over_reference": (sg / sr).tolist(), "error_over_reference": (se / sr).tolist(),
                               "point_over_reference": (sp / sr).tolist(),
                               "max_abs_error": float(np.abs(got - ref).max()),
                               "rms_ref_fluct": float(np.std(ref - ref.mean(axis=0)))}
    return out


def markdown(r: dict) -> str:
    e = r["edges_rad_s"]
    lines = [f"**{r['scene']}**{' (' + ', '.join(r['sets']) + ')' if r['sets'] else ''}, {r['duration']:g} s, "
             f"m = {r['m']} pymunk steps per output step, {r['wall_s']:.0f} s wall; the dampers' position-correction "
             f"part: {r['damper_bias_rms_over_F_t_rms']:.2e} of F_t's rms", ""]
    chans = [c for c in CHANNELS if c in r["channels"] and not r["channels"][c].get("constant")]
    const = [c for c in CHANNELS if c in r["channels"] and r["channels"][c].get("constant")]
    lines.append("| band (rad/s) | " + " | ".join(f"{c}: recorded / ref (error / ref)" for c in chans) + " |")
    lines.append("|---|" + "---|" * len(chans))
    for i in range(len(e) - 1):
        cells = [f"{r['channels'][c]['recorded_over_reference'][i]:.4f} ({r['channels'][c]['error_over_reference'][i]:.1e})"
                 for c in chans]
        lines.append(f"| {e[i]:.0f}-{e[i + 1]:.0f} | " + " | ".join(cells) + " |")
    lines.append("| point samples / ref, worst band | " + " | ".join(
        f"{max(r['channels'][c]['point_over_reference'], key=lambda v: abs(np.log(v))):.3f}" for c in chans) + " |")
    if const:
        lines.append("")
        lines.append("Channels constant to 1e-6 of their mean or zero (no spectrum to compare): max |recorded - "
                     "reference| " + ", ".join(
                         f"{c} {r['channels'][c]['max_abs_error']:.1e} N (mean {r['channels'][c]['mean']:.2g} N)"
                         for c in const))
    return "\n".join(lines)


def worst(r: dict) -> dict:
    """Per channel the band ratio farthest from 1 (recorded / reference)."""
    return {c: max(v["recorded_over_reference"], key=lambda x: abs(np.log(x)))
            for c, v in r["channels"].items() if not v.get("constant")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="pads_rough_profile")
    ap.add_argument("--all", action="store_true", help="every shipped scene")
    ap.add_argument("--duration", type=float, default=8.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE")
    ap.add_argument("--smoke", action="store_true")
    ap.add_argument("--json", default=None)
    ap.add_argument("--markdown", default=None)
    a = ap.parse_args(argv)
    names = list(shipped_scenarios()) if a.all else [a.scene]
    results, texts = [], []
    for name in names:
        r = measure(name, 0.3 if a.smoke else a.duration, a.seed, a.set)
        results.append(r)
        texts.append(markdown(r))
        print(texts[-1] + "\n", flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n\n".join(texts) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
