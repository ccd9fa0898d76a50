"""Friction under an imposed vibration: the closed forms (pure functions, SI units).

A contact slides at the slow relative speed V while a vibration adds a periodic part to its relative motion. Two
limits have closed forms:

* **Velocity controlled** (a rigid contact, a slider whose own speed stays V through each cycle: a heavy block, a
  stiff or kinematic drive): the relative velocity is ``V + U cos(theta)`` with ``U = A omega_v`` for a substrate
  oscillating as ``A sin(omega_v t)`` along the sliding direction. The mean of ``sign(v_rel)`` over a cycle is
  ``(2/pi) arcsin(xi)``, ``xi = V / U`` < 1, else 1 (Storck et al., Ultrasonics 40, 2002,
  doi:10.1016/S0041-624X(02)00126-9). For the law ``f = f_c sign(v_rel) + c v_rel`` the mean friction
  ``F(V) = f_c (2/pi) arcsin(V/U) + c V`` has the slope ``c + 2 f_c / (pi sqrt(U^2 - V^2))``, an extra viscous
  term.
* **Force controlled** (an overdamped contact dragged along by its substrate, as model I's miniblocks are when
  ``omega_v`` lies far above ``k0 / (m eta1)``): the force available to the contact is ``G + B sin(theta)`` and
  the contact slips at ``soft(G + B sin theta, f_c) / c`` (``soft(y, f) = sign(y) max(|y| - f, 0)``), sticking
  while ``|G + B sin theta| <= f_c``. The mean slip rate and the slipping fraction of the cycle have closed forms
  (:func:`force_controlled_mean`, :func:`slip_fraction`); the slope of the mean friction against the mean slip
  rate is ``c / slip_fraction``. For ``B >> f_c`` it tends to the velocity-controlled slope with
  ``U = B / c``.

The in-band factor: below the crossover of model I the displacement spectrum is eq. (A11),
``C_x = alpha^2 v f_kin^2 / (12 pi N a (m eta1)^2 omega^4)``; it goes as ``v / s^2`` with ``s`` the slope of the
contacts' mean friction law (``m eta1`` without vibration, Appendix A's generalisation ``v f'_kin(v)``). A vibration
far above the band replaces ``s`` by its effective slope and ``v`` by the new mean speed (a constant force drive
speeds up as the mean friction falls), so the in-band level changes by ``(v1 / v0) (s0 / s1)^2`` while its
exponent stays 4 (:func:`in_band_factor`).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["arcsin_ratio", "mean_sign", "velocity_controlled_friction", "effective_slope", "force_controlled_mean",
           "slip_fraction", "force_controlled_slope", "in_band_factor", "steady_speed", "lift_off_amplitude",
           "contact_fraction_normal", "backward_slip", "minimum_amplitude", "compliant_mean_ratio"]


def arcsin_ratio(xi) -> np.ndarray:
    """Mean friction under vibration over its unshaken value, ``(2/pi) arcsin(xi)`` for ``0 <= xi < 1``, else 1.

    Parameters
    ----------
    xi : float or array_like
        ``V / (A omega_v)``: sliding speed over the vibration's velocity amplitude (dimensionless, >= 0).
    """
    xi = np.asarray(xi, dtype=float)
    if np.any(xi < 0) or np.any(np.isnan(xi)):
        raise ValueError("xi must be >= 0 (V / (A omega_v))")
    return (2.0 / np.pi) * np.arcsin(np.minimum(xi, 1.0))


def mean_sign(V, U) -> np.ndarray:
    """Cycle mean of ``sign(V + U cos theta)``: ``(2/pi) arcsin(V/U)`` for ``|V| < U``, else ``sign(V)``.

    Parameters
    ----------
    V : float or array_like
        Slow relative speed (Units: m/s), either sign.
    U : float or array_like
        Velocity amplitude of the vibration, ``A omega_v`` (Units: m/s), >= 0.
    """
    V, U = np.broadcast_arrays(np.asarray(V, dtype=float), np.asarray(U, dtype=float))
    if np.any(U < 0):
        raise ValueError("U must be >= 0")
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(U > 0, V / np.where(U > 0, U, 1.0), np.sign(V) * np.inf)
    return (2.0 / np.pi) * np.arcsin(np.clip(r, -1.0, 1.0))


def velocity_controlled_friction(V, U, f_c: float, c: float = 0.0) -> np.ndarray:
    """Mean friction ``f_c <sign(v_rel)> + c V`` of the law ``f_c sign(v_rel) + c v_rel`` with
    ``v_rel = V + U cos theta`` (Units: N)."""
    return f_c * mean_sign(V, U) + c * np.asarray(V, dtype=float)


def effective_slope(V, U, f_c: float, c: float = 0.0) -> np.ndarray:
    """d/dV of :func:`velocity_controlled_friction`: ``c + 2 f_c / (pi sqrt(U^2 - V^2))`` for ``|V| < U``, else
    ``c`` (Units: N s/m). Diverges (integrably) as ``|V| -> U``."""
    V, U = np.broadcast_arrays(np.asarray(V, dtype=float), np.asarray(U, dtype=float))
    d2 = U**2 - V**2
    with np.errstate(divide="ignore", invalid="ignore"):
        extra = np.where(d2 > 0, 2.0 * f_c / (np.pi * np.sqrt(np.where(d2 > 0, d2, 1.0))), 0.0)
    return c + extra


def _phi(cc) -> np.ndarray:
    """Cycle mean of ``max(sin theta - cc, 0)``: 0 for cc >= 1, -cc for cc <= -1, else
    ``(2 sqrt(1 - cc^2) - cc (pi - 2 arcsin cc)) / (2 pi)``."""
    cc = np.asarray(cc, dtype=float)
    cl = np.clip(cc, -1.0, 1.0)
    mid = (2.0 * np.sqrt(1.0 - cl**2) - cl * (np.pi - 2.0 * np.arcsin(cl))) / (2.0 * np.pi)
    return np.where(cc >= 1.0, 0.0, np.where(cc <= -1.0, -cc, mid))


def _above(cc) -> np.ndarray:
    """Fraction of a cycle with ``sin theta > cc``."""
    cl = np.clip(np.asarray(cc, dtype=float), -1.0, 1.0)
    return (np.pi - 2.0 * np.arcsin(cl)) / (2.0 * np.pi)


def force_controlled_mean(G, B, f_c: float, c: float) -> np.ndarray:
    """Cycle-mean slip rate ``<soft(G + B sin theta, f_c)> / c`` of a contact whose available force oscillates
    (Units: m/s).

    Parameters
    ----------
    G : float or array_like
        Mean force available to the contact (spring force minus the random force) (Units: N).
    B : float
        Amplitude of its oscillation (Units: N), > 0.
    f_c : float
        Coulomb part of the contact's friction (Units: N).
    c : float
        Viscous slope of the contact's friction (Units: N s/m), > 0.
    """
    if not B > 0:
        G = np.asarray(G, dtype=float)
        return np.sign(G) * np.maximum(np.abs(G) - f_c, 0.0) / c
    G = np.asarray(G, dtype=float)
    return B * (_phi((f_c - G) / B) - _phi((f_c + G) / B)) / c


def slip_fraction(G, B, f_c: float) -> np.ndarray:
    """Fraction of the cycle in which ``|G + B sin theta| > f_c`` (the contact slips); equals
    ``c d<slip rate>/dG``."""
    G = np.asarray(G, dtype=float)
    if not B > 0:
        return (np.abs(G) > f_c).astype(float)
    return _above((f_c - G) / B) + _above((f_c + G) / B)


def force_controlled_slope(G, B, f_c: float, c: float) -> np.ndarray:
    """Slope of the mean friction against the mean slip rate, ``c / slip_fraction`` (Units: N s/m)."""
    return c / slip_fraction(G, B, f_c)


def in_band_factor(v0: float, v1: float, s0: float, s1) -> np.ndarray:
    """C_x(shaken) / C_x(unshaken) in model I's omega^-4 band through eq. (A11): ``(v1 / v0) (s0 / s1)^2``.

    Parameters
    ----------
    v0, v1 : float
        Mean sliding speed without and with vibration (Units: m/s); equal under a velocity drive.
    s0, s1 : float
        Slope of the contacts' mean friction law without (``m eta1``) and with vibration (Units: N s/m).
    """
    return (v1 / v0) * (s0 / np.asarray(s1, dtype=float)) ** 2


def steady_speed(F: float, f_c: float, c: float, U: float) -> float:
    """Mean speed V of a contact under the constant force F in the velocity-controlled limit:
    ``f_c (2/pi) arcsin(V / U) + c V = F`` (Units: m/s); ``(F - f_c) / c`` when U = 0 (bisection: the left side
    increases with V)."""
    if not c > 0:
        raise ValueError("c must be > 0 for a steady speed")
    lo, hi = 0.0, max(F / c, 1e-300)
    if F <= 0:
        return 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if float(velocity_controlled_friction(mid, U, f_c, c)) < F:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def lift_off_amplitude(omega_v: float, load: float, mass: float, k_normal: float = 0.0) -> float:
    """Smallest amplitude of a normal vibration ``A sin(omega_v t)`` of the substrate that lifts a load off it
    (Units: m).

    A body of ``mass`` pressed on the substrate by ``load`` (its weight plus any preload, Units: N) through a
    spring of stiffness ``k_normal`` (N/m; 0 for a free load) feels, while it follows the substrate, the contact
    force ``load + (k_normal - mass omega_v^2) A sin(omega_v t)``; it lifts off where that reaches zero:
    ``A = load / |mass omega_v^2 - k_normal|``. For a free rigid load this is ``A omega_v^2 = g_eff`` with
    ``g_eff = load / mass`` the load's effective gravity. At ``mass omega_v^2 = k_normal`` (the pad's normal
    resonance) any amplitude lifts it (returns 0).
    """
    d = abs(mass * omega_v**2 - k_normal)
    return load / d if d > 0 else 0.0


def contact_fraction_normal(gamma) -> np.ndarray:
    """Fraction of a cycle in which ``1 + gamma sin theta > 0`` (the rigid-contact normal force of a substrate
    vibrating normally stays compressive): 1 for gamma <= 1, else ``1/2 + arcsin(1/gamma) / pi``. This is the
    bound for a load held on the substrate; a free load that lifts off lands later (a bouncing ball's flight),
    so its contact fraction is smaller."""
    gamma = np.asarray(gamma, dtype=float)
    with np.errstate(divide="ignore"):
        inv = np.where(gamma > 1.0, 1.0 / np.where(gamma > 1.0, gamma, 1.0), 1.0)
    return np.where(gamma <= 1.0, 1.0, 0.5 + np.arcsin(inv) / np.pi)


def backward_slip(xi) -> np.ndarray:
    """Distance the substrate moves back past a slider held at V in each cycle, over A:
    ``2 (sqrt(1 - xi^2) - xi arccos xi)`` for ``xi < 1``, else 0 (the integral of ``A omega cos - V`` over the
    part of the cycle where it is positive)."""
    xi = np.minimum(np.asarray(xi, dtype=float), 1.0)
    return 2.0 * (np.sqrt(1.0 - xi**2) - xi * np.arccos(xi))


def minimum_amplitude(xi, deflection: float) -> np.ndarray:
    """The smallest amplitude at which a compliant contact slides backwards at all (Units: m): a contact behind a
    spring, which slides only once the spring carries its Coulomb force (``deflection = mu N / k``), needs the
    backward slip of a cycle to exceed the spring's travel from one sliding state to the other, ``2 deflection``:
    ``A_min = deflection / (sqrt(1 - xi^2) - xi arccos xi)``. Below it the contact only sticks and slides forward,
    and its mean friction falls by the spring's elastic swing alone, a fraction of order A / deflection
    (:func:`compliant_mean_ratio`); far above it the arcsin law holds (Popov and co-workers' minimum amplitude of
    contact compliance)."""
    return 2.0 * deflection / backward_slip(xi)


def compliant_mean_ratio(xi, a_over_d, steps: int = 4096, cycles: int = 4) -> np.ndarray:
    """Mean friction over its unshaken value for a massless contact on a spring (a Jenkins element: spring k in
    series with a Coulomb slider of force mu N) dragged at V over a substrate oscillating as ``A sin(omega t)``.

    The spring's stretch z follows the relative displacement ``u = V t - A sin(omega t)`` through the play
    operator, ``z <- clip(z + du, -d, d)`` with ``d = mu N / k``, and the friction is ``k z``: in units of d,
    ``u / d = (A / d) (xi theta - sin theta)``. The mean of ``z / d`` over the last cycle of ``cycles``
    (``steps`` per cycle; periodic after the first). Tends to ``(2/pi) arcsin(xi)`` as ``A / d -> inf`` (the
    departure goes as d / A) and to 1 as ``A / d -> 0``.

    Parameters
    ----------
    xi : float
        V / (A omega).
    a_over_d : float
        Amplitude over the contact's deflection mu N / k (dimensionless).
    """
    th = 2 * np.pi * np.arange(1, cycles * steps + 1) / steps
    du = np.diff(np.concatenate([[0.0], float(a_over_d) * (float(xi) * th - np.sin(th))]))
    z = _play(du)
    return float(np.mean(z[-steps:]))


def _play(du):
    z = np.empty(len(du))
    zc = 1.0  # steady sliding: the spring carries the Coulomb force
    for i, d in enumerate(du):
        zc = min(1.0, max(-1.0, zc + d))
        z[i] = zc
    return z
