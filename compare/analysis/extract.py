"""Parameters of the reduced models measured from an engine trace, each with its provenance.

Model I (spring-block) from a pad scene:

- N: pads in contact (mean of the recorded count); load per pad: mean normal contact force / N.
- a: the renewal length, from the pads' tangential-force autocorrelation in sliding distance. For
  renewals at distances a (1 + r - r') (section 3), the integral correlation length is
  <tau^2> / (2 <tau>) = 7 a / 12, so a = (12/7) Int rho(s) ds; cross-checked with the substrate's a.
- f_kin and alpha: the mean pad contact force is f_kin; a uniform random part alpha f_kin (r - 1/2) has
  rms alpha f_kin / sqrt(12) (eq. A7), so alpha = sqrt(12) rms / f_kin.
- c = dF/dv per pad (m eta1 in model I): from the friction law, checked against the recorded viscous force
  over the pads' speed; omega* = N c / M separates viscous (below) from inertial (above) response.

What the scene is (effective mass, friction law, length scale, pads, contact width) comes from the trace's
``metadata["scene"]`` (written by ``engine_sim.run``), not from the scenario's layout; a trace without it (older
files) is described from its scenario with ``engine_sim.scene.describe``.
"""
from __future__ import annotations

import math

import numpy as np

from reduced_models.correlation import correlation_length

__all__ = ["model_I_parameters", "spring_block_params", "model_III_parameters", "asperity_force_params", "scene_info",
           "friction_slope"]


def scene_info(trace, scenario=None) -> dict:
    """The scene's description carried by the trace (see ``engine_sim.scene.describe``)."""
    info = trace.metadata.get("scene")
    if info is None:
        if scenario is None:
            raise ValueError("the trace carries no scene description (metadata['scene']): pass its scenario")
        from engine_sim.scene import describe

        info = describe(scenario)
    return info


def friction_slope(law: dict, v: float) -> float:
    """dF/dv of the friction law per pad at speed v (N s/m), from the law's description in a trace
    (``metadata["scene"]["friction_law"]``), as the law registered under its name computes it
    (``engine_sim.laws.Law.described_slope``)."""
    from engine_sim.laws import LAWS

    return LAWS[law["law"]].described_slope(law, v)


def model_I_parameters(trace, scenario=None) -> dict:
    """Model I parameters of an engine trace: {name: {"value", "unit", "provenance", ...}}."""
    info = scene_info(trace, scenario)
    pads = info["pads"]
    N_contact = float(np.mean(trace.n_contact))
    load = float(np.mean(trace.F_n)) / max(N_contact, 1.0)
    v = float((trace.x[-1] - trace.x[0]) / (trace.t[-1] - trace.t[0]))
    f = trace.pad_force
    f_kin = float(np.mean(f))
    rms = float(np.mean(np.std(f, axis=0)))
    Lc = correlation_length(trace.x, f, 10 * info["length_scale"])
    a = 12.0 / 7.0 * Lc
    c_law = friction_slope(info["friction_law"], v)
    c_meas = float(np.mean(trace.F_drag) / (N_contact * v))
    M = info["effective_mass"]
    if M != info["block_mass"]:  # Leonardo's slider: the taut rope moves the hanging mass with the block
        M_prov = "scenario: block + hanging mass (Leonardo's slider, rope taut)"
    else:
        M_prov = "scenario"
    return {
        "N": {"value": N_contact, "unit": "", "provenance": "mean number of pads touching their track"},
        "load_per_pad": {"value": load, "unit": "N", "provenance": "mean normal contact force / N"},
        "v": {"value": v, "unit": "m/s", "provenance": "block displacement / time"},
        "a": {"value": a, "unit": "m", "provenance": "(12/7) x integral correlation length of the pad forces in distance",
              "substrate_value": info["length_scale"]},
        "f_kin": {"value": f_kin, "unit": "N", "provenance": "mean tangential contact force per pad"},
        "alpha": {"value": math.sqrt(12.0) * rms / f_kin, "unit": "", "provenance": "sqrt(12) x rms pad force / f_kin (eq. A7)",
                  "substrate_value": info["substrate"].get("alpha")},
        "c": {"value": c_law, "unit": "N s/m", "provenance": "friction law's slope at v (scenario)", "measured": c_meas,
              "measured_provenance": "mean F_drag / (N v): the law's secant at v, its slope only for a law through "
                                     "the origin"},
        "k0": {"value": pads["k0"], "unit": "N/m", "provenance": "scenario"},
        "M": {"value": M, "unit": "kg", "provenance": M_prov},
        "m": {"value": pads["mass"], "unit": "kg", "provenance": "scenario (pad mass)"},
        "eta0": {"value": pads["c0"] / pads["mass"], "unit": "1/s", "provenance": "scenario (c0 / m)"},
        "omega_star": {"value": N_contact * c_law / M, "unit": "rad/s",
                       "provenance": "N c / M: viscous response below, inertial above"},
        "omega_c": {"value": math.sqrt(N_contact * pads["k0"] / M), "unit": "rad/s",
                    "provenance": "sqrt(N k0 / M): block-on-pads resonance, the top of the omega^-4 band"},
    }


def spring_block_params(ex: dict):
    """A SpringBlockParams built from :func:`model_I_parameters` (k1 = 0, F_drive from steady sliding)."""
    from reduced_models.spring_block import SpringBlockParams

    N = max(1, int(round(ex["N"]["value"])))
    f_kin, c, v = ex["f_kin"]["value"], ex["c"]["value"], ex["v"]["value"]
    m = ex["m"]["value"]
    return SpringBlockParams(N=N, v=v, a=ex["a"]["value"], k0=ex["k0"]["value"], k1=0.0, M=ex["M"]["value"], m=m,
                             eta0=ex["eta0"]["value"], eta1=None, alpha=ex["alpha"]["value"],
                             F_drive=N * (f_kin + c * v), F_kin=N * f_kin)


def model_III_parameters(trace, scenario=None) -> dict:
    """Model III (section 6) contact statistics of an asperity-field trace: {name: {"value", "unit", "provenance"}}.

    w is the sole's width N foot_length; N the mean number of foot-asperity contact pairs; the model's cell
    is the substrate's, so p = N cell / w is the probability that a cell under the sole carries a *touching*
    asperity (the substrate's own p counts bumps too low to be touched as well); F_f is the mean tangential
    contact force and f0 = 2 F_f / N (model III's contact force is r f0 with r uniform in [0, 1]). The
    per-contact force distribution is measured on feet touching exactly one asperity: its coefficient of
    variation is compared with the uniform law's 1/sqrt(3)."""
    info = scene_info(trace, scenario)
    sub = info["substrate"]
    w = info["contact_width"]
    N = float(np.mean(trace.n_pairs))
    F_f = float(np.mean(trace.F_t))
    v = float((trace.x[-1] - trace.x[0]) / (trace.t[-1] - trace.t[0]))
    f = trace.pad_force
    single = f[np.abs(f) > 0]
    cv = float(np.std(single) / np.mean(single)) if single.size else float("nan")
    return {
        "w": {"value": w, "unit": "m", "provenance": "N x foot_length (scenario)"},
        "N": {"value": N, "unit": "", "provenance": "mean number of foot-asperity contact pairs"},
        "p": {"value": N * sub["cell"] / w, "unit": "", "provenance": "N cell / w: touching asperities per cell",
              "substrate_value": sub["p"]},
        "F_f": {"value": F_f, "unit": "N", "provenance": "mean tangential contact force"},
        "f0": {"value": 2.0 * F_f / N, "unit": "N", "provenance": "2 F_f / N (model III: mean contact force f0 / 2)"},
        "contact_force_cv": {"value": cv, "unit": "", "provenance": "std / mean of the tangential force of feet in contact "
                             "(model III's uniform r f0: 0.577)"},
        "n_rel_std": {"value": float(np.std(trace.n_pairs) / N), "unit": "", "provenance": "relative std of the number of contacts"},
        "v": {"value": v, "unit": "m/s", "provenance": "block displacement / time"},
        "M": {"value": info["block_mass"], "unit": "kg", "provenance": "scenario"},
        "omega_star": {"value": info["pads"]["N"] * friction_slope(info["friction_law"], v) / info["block_mass"], "unit": "rad/s",
                       "provenance": "N c / M: viscous response below, inertial above"},
    }


def asperity_force_params(ex: dict):
    """An AsperityForceParams with the contact statistics of :func:`model_III_parameters`."""
    from reduced_models.asperity_force import AsperityForceParams

    return AsperityForceParams(F_f=ex["F_f"]["value"], v=ex["v"]["value"], p=min(1.0, ex["p"]["value"]),
                               M=ex["M"]["value"], w=ex["w"]["value"], N=ex["N"]["value"])
