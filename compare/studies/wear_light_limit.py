"""Is there a light-grain limit? One pad, one grain of a fixed radius, against closed forms.

    python -m compare.studies.wear_light_limit [--radii 25,50,80,140] [--masses 1e-5] [--steps 1e-4,6.25e-6,1.5625e-6]
                                          [--iterations 20] [--seeds 0,1] [--duration S] [--out PREFIX] [--smoke]

The wear study's scene (``scenarios/sweeps/pads_with_wear_study.toml``: pads, track, grain frictions mu_pad = 0.2,
mu_track = 1.2, smooth track) reduced to what one grain meets: one pad under a block of 1/30 of the study's (so the
pad's load is the study's, 0.0425 N with its own weight), pulled at v = 5 mm/s by a stiff spring (1e4 N/m: the block
follows the set speed, where in the 30-pad scene the other pads hold it), and one grain of radius r (a log-normal
of width 1e-4) recycled ahead of the pad each time it is left behind. Every output step the recorder classifies the
grain as idle, trapped (touching the pad, slower than 0.1 v) or moving, with its force on the pad. Per run: the mean
force over the trapped samples and over the moving ones, the time fractions, the energy residual.

Two closed forms (:mod:`engine_sim.wear`) say what to expect of a rigid, non-rolling grain:

- :func:`~engine_sim.wear.wedge_regime` from the contact angle theta (sin theta = (R - r) / (R + r)) and the two
  friction angles: the pad climbs over a grain below 37.4 um (trapped), pushes one above 106 um ahead with a force of
  order mu_track m g (vanishing with m), and in between the grain is wedged, where rigid mechanics leaves the force
  undetermined;
- :func:`~engine_sim.wear.climb_force`: the mean force on a pad climbing quasi-statically over a stuck grain, from
  its load and normal spring (no fitted constant): the trapped samples' force should converge to it.

``--masses`` sets ``wear.min_mass`` (a grain heavier by its density, 2500 kg/m^3 x 1 mm deep, keeps its own mass: the
140 um grain weighs 1.5e-7 kg); ``--steps`` sets ``run.dt``, which the grain step rule cuts into substeps while
omega_g dt > 0.6 (1e-4 s gives the shipped 2.5e-5 s at 1e-5 kg); the table shows the step taken. The regimes are
those at the mean patch friction; the track's patches spread the grain-track friction over 0.6-1.8, so a grain
changes regime from patch to patch (``regime_shares``: the 25 um grain is trapped on 71 % of them). Finished runs
are kept in ``PREFIX.json`` (a rerun skips them) and ``PREFIX.md`` is rewritten after each (a hand-written section
starting "## Reading it (written by hand" below the table is kept). ``--smoke`` (CI): one 2 s run per regime at the shipped step.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

import engine_sim
from compare.analysis.balances import balances
from engine_sim import scenario_from_dict
from engine_sim.shipped import SCENARIO_DIR
from engine_sim.wear import climb_force, lightest_grain_mass, regime_shares, wedge_regime
from frictionnoise import G

BASE = SCENARIO_DIR / "sweeps" / "pads_with_wear_study.toml"
N_STUDY = 30  # pads of the study's scene: the one pad here carries 1/N_STUDY of its block
WARMUP = 0.2  # s, simulated before recording (the pad reaches its speed within ms)


def one_pad_scenario(r: float, mass: float, iterations: int, dt: float, duration: float, k_drive: float = 1e4):
    """The study's scene reduced to one pad at constant speed and one grain of radius r (m) and mass ``mass`` (kg)."""
    d = tomllib.loads(BASE.read_text())
    d["block"]["M"] = d["block"]["M"] / N_STUDY
    d["pads"]["N"] = 1
    d["drive"] = {"kind": "velocity", "v": d["drive"]["v"], "k_drive": k_drive}
    d["wear"].update(count=1, min_mass=mass, r_min=r * 0.999, r_max=r * 1.001, r_median=r, sigma=1e-4)
    d["run"].update(iterations=iterations, dt=dt, duration=duration, warmup=WARMUP)
    return scenario_from_dict(d, where=f"one-pad scene (r = {r:g} m)")


def closed_forms(sc) -> dict:
    """For the scenario's grain: its regime at the mean patch friction and its shares over the patches
    (engine_sim.wear), the quasi-static climb force (N; for the trapped regime) and mu_track m g (N, the grain's own
    mass)."""
    r, R, w = sc.wear.r_median, sc.pads.radius, sc.wear
    regime, theta = wedge_regime(r, R, w.mu_pad, w.mu_track)
    return {"regime": regime, "theta_deg": theta,
            "regime_shares": regime_shares(r, R, w.mu_pad, w.mu_track, getattr(sc.substrate, "alpha", 0.0)),
            "climb_N": climb_force(r, R, w.mu_pad, sc.normal_load_per_pad, sc.pads.k_normal),
            "m_grain_kg": lightest_grain_mass(w), "mu_track_m_g_N": w.mu_track * lightest_grain_mass(w) * G}


def measure(r, mass, iterations, dt, seed, duration) -> dict:
    """One run of the one-pad scene (grain radius r [m], ``wear.min_mass`` mass [kg], solver iterations, run.dt dt [s],
    duration [s] recorded after WARMUP): mean forces [N] on the pad over the trapped and the moving samples (None if
    there are none), the time fractions, the energy residual, the deepest grain overlap [m], the recycled count, the
    wall time [s] and the closed forms (:func:`closed_forms`)."""
    sc = one_pad_scenario(r, mass, iterations, dt, duration)
    t0 = time.perf_counter()
    tr = engine_sim.run(sc, seed=seed)
    wall = time.perf_counter() - t0
    F, st = tr.p_force[:, 0], tr.p_state[:, 0]
    trapped, moving = st == 1, st == 2
    return {"r_m": r, "mass_kg": mass, "iterations": iterations, "dt_step_s": tr.metadata["scene"]["grain_step"]["dt_step"],
            "seed": seed, "duration_s": duration,
            "F_trapped_N": float(F[trapped].mean()) if trapped.any() else None,
            "F_moving_N": float(F[moving].mean()) if moving.any() else None,
            "F_mean_N": float(F.mean()), "trapped_frac": float(trapped.mean()), "moving_frac": float(moving.mean()),
            "energy_balance_rel": float(balances(tr)["energy_balance_rel"]),
            "grain_overlap_max_m": float(tr.particle_penetration.max()), "recycled": int(tr.metadata["wear"]["recycled"]),
            "wall_s": wall, **closed_forms(sc)}


def _key(r, mass, it, dt, seed, duration):
    return f"r={r:g}|m={mass:g}|it={it}|dt={dt:g}|seed={seed}|T={duration:g}"


def _mn(vals, scale=1e3):
    v = [x for x in vals if x is not None]
    if not v:
        return "-"
    return " / ".join(f"{scale * x:.2f}" for x in v)


def markdown(runs: dict, meta: dict) -> str:
    rows = {}
    for rec in runs.values():
        rows.setdefault((rec["r_m"], rec["mass_kg"], rec["iterations"], rec["dt_step_s"]), []).append(rec)
    lines = ["# Is there a light-grain limit? One pad, one grain, against closed forms", "",
             f"Commands: {'; '.join(f'`{c}`' for c in meta['commands'])}  ",
             f"Wall time so far: {meta['wall_s']:.0f} s; runs: {len(runs)}; last update {meta['updated']}.", "",
             "Scene: the wear study's (`scenarios/sweeps/pads_with_wear_study.toml`) reduced to one pad under 1/30 of its block, "
             "pulled at 5 mm/s through a 1e4 N/m spring, and one grain of radius r recycled ahead of the pad (see the module "
             "docstring). Forces in mN, per seed (separated by /); F_trapped: mean over the samples where the grain touches "
             "the pad and is at rest, F_moving: where it touches and moves; climb: the quasi-static closed form "
             "(`engine_sim.wear.climb_force`) for a trapped grain; regime: `engine_sim.wear.wedge_regime` at the mean patch "
             "friction, patch shares: `regime_shares` over the patches' spread (alpha = 1: grain-track friction 0.6-1.8); "
             "mu_track m g with the grain's own mass (its density's where that exceeds min_mass).", "",
             "| r (um) | regime (theta) | patch shares t / w / p | mass (kg) | its | step (s) | F_trapped (mN) | climb (mN) | "
             "F_moving (mN) | mu_track m g (mN) | trapped fraction | moving fraction | energy resid. worst | wall s / sim s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (r, m, it, dt), rs in sorted(rows.items(), key=lambda kv: (kv[0][0], -kv[0][1], kv[0][2], -kv[0][3])):
        rs = sorted(rs, key=lambda x: x["seed"])
        a = closed_forms(one_pad_scenario(r, m, it, dt, rs[0]["duration_s"]))  # from the formulas of this version
        lines.append(
            f"| {1e6 * r:.0f} | {a['regime']} ({a['theta_deg']:.1f} deg) | "
            + " / ".join(f"{a['regime_shares'][k]:.2f}" for k in ("trapped", "wedged", "pushed"))
            + f" | {m:g} | {it} | {dt:.3g} | "
            f"{_mn([x['F_trapped_N'] for x in rs])} | {1e3 * a['climb_N']:.2f} | {_mn([x['F_moving_N'] for x in rs])} | "
            f"{1e3 * a['mu_track_m_g_N']:.3g} | "
            + " / ".join(f"{x['trapped_frac']:.3f}" for x in rs) + " | "
            + " / ".join(f"{x['moving_frac']:.3f}" for x in rs)
            + f" | {100 * max(abs(x['energy_balance_rel']) for x in rs):.2f} % | "
            f"{np.mean([x['wall_s'] / (x['duration_s'] + WARMUP) for x in rs]):.2f} |")
    return "\n".join(lines) + "\n"


_HAND = "## Reading it (written by hand"  # a discussion below the table, kept when the table is rewritten


def _write_md(path: Path, text: str):
    old = path.read_text() if path.exists() else ""
    path.write_text(text + ("\n" + old[old.index(_HAND):] if _HAND in old else ""))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--radii", default="25,50,80,140", help="um")
    ap.add_argument("--masses", default="1e-5", help="kg")
    ap.add_argument("--steps", default="2.5e-5,6.25e-6,1.5625e-6", help="s (run.dt; the grain step rule may cut it)")
    ap.add_argument("--iterations", default="20")
    ap.add_argument("--seeds", default="0,1")
    ap.add_argument("--duration", type=float, default=10.0)
    ap.add_argument("--out", default="study-results/wear_light_limit")
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    if a.smoke:
        for r in (25e-6, 50e-6, 140e-6):
            rec = measure(r, 1e-5, 20, 1e-4, 0, 2.0)
            print(f"r {1e6 * r:.0f} um ({rec['regime']}): F_trapped {_mn([rec['F_trapped_N']])} mN (climb "
                  f"{1e3 * rec['climb_N']:.2f}), F_moving {_mn([rec['F_moving_N']])} mN, energy residual "
                  f"{100 * rec['energy_balance_rel']:+.2f} %, {rec['wall_s']:.1f} s wall")
        return 0
    out_json, out_md = Path(a.out + ".json"), Path(a.out + ".md")
    store = json.loads(out_json.read_text()) if out_json.exists() else {"runs": {}, "commands": [], "wall_s": 0.0}
    cmd = "python -m compare.studies.wear_light_limit " + " ".join(argv if argv is not None else sys.argv[1:])
    for r in (float(x) * 1e-6 for x in a.radii.split(",")):
        for m in (float(x) for x in a.masses.split(",")):
            for it in (int(x) for x in a.iterations.split(",")):
                for dt in (float(x) for x in a.steps.split(",")):
                    for seed in (int(x) for x in a.seeds.split(",")):
                        k = _key(r, m, it, dt, seed, a.duration)
                        if k in store["runs"]:
                            continue
                        rec = measure(r, m, it, dt, seed, a.duration)
                        store["runs"][k] = rec
                        if cmd not in store["commands"]:  # the commands that ran something
                            store["commands"].append(cmd)
                        store["wall_s"] += rec["wall_s"]
                        store["updated"] = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
                        out_json.write_text(json.dumps(store, indent=1))
                        _write_md(out_md, markdown(store["runs"], store))
                        print(f"{k}: F_trapped {_mn([rec['F_trapped_N']])} mN, F_moving {_mn([rec['F_moving_N']])} mN, "
                              f"{rec['wall_s']:.0f} s", file=sys.stderr, flush=True)
    _write_md(out_md, markdown(store["runs"], store))  # also when every run was done before (a rewrite)
    return 0


if __name__ == "__main__":
    sys.exit(main())
