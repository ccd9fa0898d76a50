"""What a rigid grain does under a sliding pad, in closed form: the wedge regimes and the quasi-static climb force.

A grain of radius r meets the front of a circular pad of radius R, both on one flat track, at the contact angle theta
(sin theta = (R - r) / (R + r)); the pad's friction cone and the grain's friction with the track decide whether the
track holds it (trapped), the pad pushes it ahead, or it is wedged (:func:`wedge_regime`, :func:`regime_shares`);
:func:`climb_force` is the mean force on a pad climbing over a trapped grain. They say what to expect of the wear
particles of :mod:`engine_sim.wear` (compare/studies/wear_light_limit.py holds the scene against them).
"""
from __future__ import annotations

import math

__all__ = ["wedge_regime", "regime_shares", "climb_force"]


def wedge_regime(r: float, R: float, mu_pad: float, mu_track: float) -> tuple[str, float]:
    """What a rigid, non-rolling, massless grain of radius r does when the front of a sliding circular pad of radius R
    (resting on the same flat track; r and R in one length unit, only their ratio counts) reaches it, on a track
    whose friction with the grain is mu_track: ("trapped" | "wedged" | "pushed", theta in degrees).

    The pad's contact normal on the grain points forward and down at theta below the horizontal, sin theta =
    (R - r) / (R + r). The pad's contact force lies within its friction cone, theta +- atan(mu_pad); a massless grain
    sliding on the track needs a force at phi = atan(1 / mu_track) below the horizontal. If the whole cone is steeper
    than phi the track holds the grain and the pad climbs over it (trapped: the force is set by the pad's springs,
    :func:`climb_force`); if it is shallower the grain slides ahead with a force of order mu_track m g (pushed, zero
    in the light limit); if it contains phi the grain is wedged: every force along phi balances it, so rigid-body
    mechanics leaves its magnitude undetermined (a static indeterminacy, as of a Coulomb wedge), and a contact
    solver picks one through its step, iterations and mass ratio (``python -m compare.studies.wear_light_limit``). On a
    track of friction patches mu_track varies from patch to patch (:func:`regime_shares`)."""
    theta = math.asin((R - r) / (R + r))
    phi, cone = math.atan2(1.0, mu_track), math.atan(mu_pad)
    regime = "trapped" if theta - cone > phi else "pushed" if theta + cone < phi else "wedged"
    return regime, math.degrees(theta)


def regime_shares(r: float, R: float, mu_pad: float, mu_track: float, alpha: float) -> dict:
    """The shares of a track's patches on which a grain of radius r is trapped, wedged or pushed
    (:func:`wedge_regime`), when the grain-track friction on a patch is mu_track (1 + alpha (u - 1/2)) with u uniform
    on [0, 1] (the friction patches' law, section 3; pymunk's product of shape frictions carries the patch's spread to
    the grain-track pair). The grain is trapped where that friction exceeds 1 / tan(theta - atan(mu_pad)) and pushed
    where it is below 1 / tan(theta + atan(mu_pad)). alpha = 0: one regime, as :func:`wedge_regime`."""
    theta, cone = math.asin((R - r) / (R + r)), math.atan(mu_pad)
    lo, hi = mu_track * (1 - alpha / 2), mu_track * (1 + alpha / 2)
    if hi <= lo:
        return {k: float(k == wedge_regime(r, R, mu_pad, mu_track)[0]) for k in ("trapped", "wedged", "pushed")}

    def share_above(mu):  # of the uniform friction on [lo, hi]
        return min(1.0, max(0.0, (hi - mu) / (hi - lo)))

    trapped = share_above(1 / math.tan(theta - cone)) if theta > cone else 0.0
    pushed = 1.0 - share_above(1 / math.tan(theta + cone)) if theta + cone < math.pi / 2 else 0.0
    return {"trapped": trapped, "wedged": 1.0 - trapped - pushed, "pushed": pushed}


def climb_force(r: float, R: float, mu_pad: float, load: float, k_normal: float) -> float:
    """Mean tangential force (N, against sliding) on a pad of radius R (m) that climbs quasi-statically over a grain of
    radius r (m) stuck on a flat track, averaged over the horizontal distance of the climb (time at constant speed).
    For a trapped grain (:func:`wedge_regime`); defined while the contact angle theta exceeds atan(mu_pad) (else the
    pad could not slide up the grain: ValueError).

    The pad's centre runs on the circle of radius R + r about the grain's centre, at angle psi from the vertical,
    from -psi0 to psi0 (cos psi0 = (R - r) / (R + r): back on the track); it slides over the grain with friction
    mu_pad = tan(beta). Its load is ``load`` (N: block share plus its weight) plus its normal spring k_normal (N/m)
    times the lift (R + r) cos psi + r - R. Vertical balance N (cos psi + mu_pad sin psi) = load(psi) gives the contact
    force N, and the force on the pad against sliding is f = N (mu_pad cos psi - sin psi) = load tan(beta - psi).
    Over the whole climb the lift returns to zero and the load is a function of it, so the work f dx is the friction
    work alone, mu_pad N (R + r) dpsi, and the mean is (mu_pad / (2 sin psi0)) Int load / (cos psi + mu_pad sin psi)
    dpsi, in closed form with A = load + k_normal (r - R), B = k_normal (R + r):

        mean = mu / (2 sin psi0) [ A (artanh sin(psi0 + beta) + artanh sin(psi0 - beta)) / sqrt(1 + mu^2)
                                   + B (2 psi0 + mu ln(cos(psi0 - beta) / cos(psi0 + beta))) / (1 + mu^2) ]

    Without friction climbing and descending cancel (mean 0). No inertia, damping or tangential spring (they add the
    few percent measured)."""
    theta = math.asin((R - r) / (R + r))
    beta = math.atan(mu_pad)
    if not theta > beta:
        raise ValueError(f"climb_force: a grain of r = {r:g} under a pad of R = {R:g} meets it at "
                         f"{math.degrees(theta):.1f} deg, not above the pad's friction angle {math.degrees(beta):.1f} "
                         "deg: the pad cannot climb it")
    mu, psi0 = mu_pad, math.pi / 2 - theta
    A, B = load + k_normal * (r - R), k_normal * (R + r)
    sec_int = (math.atanh(math.sin(psi0 + beta)) + math.atanh(math.sin(psi0 - beta))) / math.sqrt(1 + mu * mu)
    cos_int = (2 * psi0 + mu * math.log(math.cos(psi0 - beta) / math.cos(psi0 + beta))) / (1 + mu * mu)
    return mu / (2 * math.sin(psi0)) * (A * sec_int + B * cos_int)
