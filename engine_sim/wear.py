"""Wear particles: rigid discs kept in the interface of each pad (section 5, Appendix B; the model II analogue).

Each particle belongs to one pad's track and collides only with that pad, that track and the particles on it
(the track's ShapeFilter category). A pad that reaches a particle either slides over it while the particle
stays at rest on the track (trapped) or drags it along (moving); which happens depends on the particle's
size, the contact angle and the two friction coefficients. By default a grain does not rotate (moment = inf),
as angular debris does not roll: a free disc squeezed between a sliding pad and the track rolls at v / 2 and is
never trapped. (A rotary damper to the ground would stop the rolling too, but it doubles the step cost and, stiff
against the grains' tiny moments of inertia, lets the contact solver squeeze particles through the track.)

Confinement: particles left more than ``behind`` behind their pad, pushed more than 3 ``ahead`` ahead of it,
or out of the interface (below the track surface or above the pad) are recycled to a random free place up to
``ahead`` in front of the pad, at rest on the track. The energy this moves in or out of the scene (the
particle's kinetic energy and the change of its potential energy) is accounted for in ``recycle_work``, so the
energy balance still closes. Idle particles at rest fall asleep (pymunk sleeping) and cost nothing until a
pad reaches them. Works in scene units (mm, g, ms).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk

from .parts import Part
from .grain_regimes import climb_force, regime_shares, wedge_regime  # the closed forms, importable from here too

__all__ = ["WearSpec", "NoWear", "wear_part", "check_wear", "draw_radii", "grain_step", "pad_friction_split", "wedge_regime", "regime_shares",
           "climb_force", "Wear"]

# No continuous collision detection in pymunk: a particle crosses a surface once v dt exceeds about 1.2 radii
# (DESIGN.md). Particles are held to WEAR_SPEED_FACTOR x the sliding speed x dt < WEAR_TUNNEL_FRACTION r_min;
# the tracks' segment radius (50 um by default) adds to the margin.
WEAR_SPEED_FACTOR = 10.0
WEAR_TUNNEL_FRACTION = 0.25
# The grain step rule (`python -m compare.studies.wear_convergence`): a grain of mass m_g squeezed by a pad feels
# the pad's springs, omega_g = sqrt((k0 + k_normal) / m_g). Every grain run measured with omega_g dt <= 0.65 closed
# the energy balance within 0.5 % (the clean branch); every one with omega_g dt >= 0.81 chattered (residual 2.4-8 %,
# grains sunk into the track at 1e-6 kg), whatever the solver iterations. The step is cut into substeps so that
# omega_g dt <= GRAIN_OMEGA_DT for the lightest grain.
GRAIN_OMEGA_DT = 0.6


@dataclass(frozen=True)
class WearSpec:
    """Wear particles as rigid circles (section 5, Appendix B), on the pads' flat tracks (substrate "patches").

    count: number of particles, dealt round-robin to the pads' tracks (each collides only with its own pad, its
    track and the particles on that track). Radii (m) follow ``distribution``: "lognormal" with median
    ``r_median`` and log-std ``sigma``, or "power" with P(r) ~ r^-``exponent``, both cut to [r_min, r_max].
    density (kg/m^3, per unit depth of a 2D disc: mass = density pi r^2 depth, depth = 1 mm), raised to at
    least ``min_mass`` (kg): pymunk's iterative contact solver loses a light grain squeezed by a heavy pad (mass
    ratios above ~1e3 at a few iterations push grains through the track). The raised inertia is not neutral:
    on pads_with_wear (30 iterations, 6 s) the grains' mean force on the pads read 0.35, 0.47 and 0.55 N at
    1e-4, 3e-4 and 1e-3 kg, and at 1e-5 kg the solver no longer closes the energy balance (3-4 %); mu_track,
    mu_pad: friction with the track and with the pad; rotation: "locked" (moment = inf: the grain slides but
    does not roll, as angular debris) or "free" (a rolling disc: squeezed under a sliding pad it rolls at v / 2
    and is never trapped; measured). A particle is "trapped" when it touches its pad and its mean speed over the
    last output step is below ``trapped_speed`` x the sliding speed (at rest relative to the substrate), "moving" when it touches its pad
    and moves faster, and "idle" when it does not touch its pad. Particles more than ``behind`` (m) behind their
    pad are recycled to a random place up to ``ahead`` (m) in front of it, at rest on the track; particles
    that leave the interface (above their pad or below the track surface) are counted and recycled too.
    Idle particles at rest fall asleep (pymunk sleeping), so they cost nothing until a pad reaches them.
    """

    count: int = 0
    distribution: str = "lognormal"
    r_min: float = 20e-6
    r_max: float = 150e-6
    r_median: float = 50e-6
    sigma: float = 0.6
    exponent: float = 2.0
    density: float = 2500.0
    min_mass: float = 0.0
    mu_track: float = 0.8
    mu_pad: float = 0.4
    rotation: str = "locked"
    trapped_speed: float = 0.1
    ahead: float = 2e-3
    behind: float = 1e-3


def check_wear(sc) -> None:
    """Raise ValueError (naming the field) if the scenario's particles cannot be simulated faithfully."""
    w, p, r = sc.wear, sc.pads, sc.run
    if not w.r_min < w.r_max:
        raise ValueError(f"wear.r_min = {w.r_min!r} m must be below wear.r_max = {w.r_max!r} m")
    if w.r_max > p.radius:
        raise ValueError(f"wear.r_max = {w.r_max!r} m must not exceed the pad radius {p.radius!r} m")
    v_max = WEAR_SPEED_FACTOR * max(sc.steady_velocity, 1e-12)
    if v_max * r.dt > WEAR_TUNNEL_FRACTION * w.r_min:
        raise ValueError(f"run.dt = {r.dt:.3g} s lets the smallest particle (wear.r_min = {w.r_min:.3g} m) tunnel: "
                         f"{WEAR_SPEED_FACTOR:g} x the sliding speed x dt must stay below {WEAR_TUNNEL_FRACTION} r_min, "
                         f"so dt <= {WEAR_TUNNEL_FRACTION * w.r_min / v_max:.3g} s")
    per_track = math.ceil(w.count / p.N)
    need = p.radius + per_track * 4 * w.r_max
    if w.ahead < need:
        raise ValueError(f"wear.ahead = {w.ahead:.3g} m cannot hold {per_track} particles per track: it must reach "
                         f"past the pad by 4 r_max per particle, at least {need:.3g} m")
    if w.ahead < 2 * p.radius or w.behind < p.radius:
        raise ValueError(f"wear.ahead (>= 2 pad radii) and wear.behind (>= 1 pad radius) must reach past the pad "
                         f"(got {w.ahead!r}, {w.behind!r} m)")


_DEPTH = 1e-3  # m: the depth of a 2D disc, for its mass


def draw_radii(spec, n: int, rng: np.random.Generator) -> np.ndarray:
    """n radii (m): log-normal (median r_median, log-std sigma) or power law P(r) ~ r^-exponent, in [r_min, r_max]."""
    lo, hi = spec.r_min, spec.r_max
    if spec.distribution == "lognormal":
        out = np.empty(0)
        while out.size < n:  # truncated by rejection
            r = spec.r_median * np.exp(spec.sigma * rng.standard_normal(2 * n + 8))
            out = np.concatenate([out, r[(r >= lo) & (r <= hi)]])
        return out[:n]
    u = rng.random(n)
    a = 1.0 - spec.exponent
    if abs(a) < 1e-12:
        return lo * (hi / lo) ** u
    return (lo**a + u * (hi**a - lo**a)) ** (1.0 / a)


def lightest_grain_mass(spec) -> float:
    """The lightest grain's mass (kg): the smallest disc (r_min, 1 mm deep) or ``min_mass`` if larger."""
    return max(spec.density * math.pi * spec.r_min**2 * _DEPTH, spec.min_mass)


def grain_step(sc) -> dict:
    """The pymunk step of a scene with grains, derived here and only here (the scene and the trace metadata read it).

    With omega_g = sqrt((k0 + k_normal) / m_g) for the lightest grain (the pad's tangential and normal springs acting
    on a grain squeezed under it), the scenario's ``run.dt`` is cut into ``substeps`` equal steps, the fewest with
    omega_g dt / substeps <= GRAIN_OMEGA_DT (0.6). Without grains: one substep. The substeps are fixed for the whole
    run (not switched on contact), so a run stays one deterministic sequence of equal steps and continues exactly
    across epochs and checkpoints. Returns {"substeps", "dt_step" [s], "omega_g" [rad/s], "omega_g_dt" (per
    substep), "m_grain" [kg], "omega_dt_max"}."""
    dt = sc.run.dt
    if not sc.wear.count:
        return {"substeps": 1, "dt_step": dt, "omega_g": None, "omega_g_dt": None, "m_grain": None,
                "omega_dt_max": GRAIN_OMEGA_DT}
    m = lightest_grain_mass(sc.wear)
    omega = math.sqrt((sc.pads.k0 + sc.pads.k_normal) / m)
    n = max(1, math.ceil(omega * dt / GRAIN_OMEGA_DT * (1 - 1e-12)))
    return {"substeps": n, "dt_step": dt / n, "omega_g": omega, "omega_g_dt": omega * dt / n, "m_grain": m,
            "omega_dt_max": GRAIN_OMEGA_DT}


def pad_friction_split(mu0: float, mu_pad: float, mu_track: float) -> tuple[float, float]:
    """Shape frictions (q for the pads, f for the particles) so that pymunk's products give the wanted pairs.

    pymunk's arbiter friction is the product of the two shapes' values. With the pads at q, the track at
    mu / q (so pad-track stays mu), and the particles at f: particle-pad = f q = mu_pad and particle-track
    = f mu0 / q = mu_track at the mean patch value mu0; hence q = sqrt(mu_pad mu0 / mu_track), f = mu_pad / q."""
    if mu_pad <= 0 or mu_track <= 0 or mu0 <= 0:
        return 1.0, max(mu_pad, 0.0)
    q = math.sqrt(mu_pad * mu0 / mu_track)
    return q, mu_pad / q


STATE_COLORS = np.array([[0.6, 0.6, 0.6, 1.0], [0.12, 0.47, 0.71, 1.0], [0.89, 0.10, 0.11, 1.0]])  # RGBA by state
STATE_NAMES = ("idle", "trapped", "moving")


def wear_part(spec, scenario):
    """The scene's grains part for a [wear] spec: :class:`Wear` when it asks for particles, else :class:`NoWear`."""
    return Wear(spec, scenario) if spec.count else NoWear(spec, scenario)


class NoWear(Part):
    """The grains part of a scene without wear particles: it builds nothing, records nothing and draws nothing. The
    scene, the recorder, the renderer and the run ask it exactly what they ask :class:`Wear`."""

    count = 0
    bodies: tuple = ()
    recycle_work = 0.0  # scene energy units
    reduced_model = None  # no particles: the substrate's model fits the scene
    quick_duration = None

    scene_units = {"ahead": "length", "behind": "length"}

    def draw_sizes(self, rng) -> dict:
        """The grains' random sizes drawn from ``rng`` (a scene's own): name -> (SI array, dimension), converted by
        the scene's builder and handed to :meth:`build`."""
        return {}

    def validate(self, where: str = "") -> None:
        """Raise ValueError (naming the field) if the scene cannot hold the particles."""

    def friction_split(self, mu0: float) -> tuple[float, float]:
        """(q_pad, particle friction): the pads' shape friction factor and the particles' (see
        :func:`pad_friction_split`); without particles the pads carry the track's friction alone."""
        return 1.0, 0.0

    def build(self, scene, rng, particle_friction: float, grains) -> None:
        """Add the particles to ``scene.space`` (scene units), placing them with ``rng`` (the generator
        :meth:`draw_sizes` drew from); ``grains``: what :meth:`draw_sizes` drew, in scene units."""

    def maintain(self) -> None:
        """Recycle particles that left their place (every few output steps)."""

    def recorder_table(self) -> np.ndarray:
        """Per particle: mass, moment (0 if locked), radius, asleep flag, last known x, y (scene units)."""
        return np.zeros((0, 6))

    def mark_sleeping(self, table: np.ndarray) -> None:
        """Write each particle's asleep flag into column 3 of the recorder's table."""

    def trace_metadata(self, stale: int) -> dict:
        """Entries of the trace's metadata: the stale grain arbiters the recorder left out."""
        return {}

    def run_metadata(self) -> dict:
        """Entries of the run's metadata: counts, radii and tracks of the particles."""
        return {}

    def view(self, scene, view: dict) -> dict:
        """The renderer's view (``arrangements.Arrangement.view``) as the particles need it."""
        return view

    def observer(self, scene):
        """What classifies the particles' states for the renderer (the recorder's classifier)."""
        return _NoStates()

    def key(self) -> list:
        """(label, RGBA colour) entries of the renderer's key."""
        return []

    def draw(self, states) -> dict:
        """Shapes to draw (``render.py``: name -> (kind, data, style)), scene units."""
        return {}

    side_exaggeration = 1000  # the largest vertical exaggeration the side view may use (grains: discs drawn E:1)
    side_pads = 1000  # the most pads the side view shows

    def side(self, scene, lay, states) -> dict:
        """Shapes of the side view (``engine_sim.side_view``, display mm): none without particles."""
        return {}


class _NoStates:
    states = np.zeros(0, dtype=int)

    def observe(self):
        pass


class _States:
    """The particles' states (0 idle, 1 trapped, 2 moving) at the latest observed output step, from a recorder that
    keeps only its latest sample: the trace's own classifier."""

    def __init__(self, scene):
        from .record import Recorder
        self._rec = Recorder(scene, 1)

    def observe(self):
        self._rec.k = 0
        self._rec.sample()

    @property
    def states(self) -> np.ndarray:
        if self._rec.k == 0:
            self.observe()
        return self._rec.p_state[0].astype(int)


class Wear(NoWear):
    """The particles of a scene (``wear.count > 0``): built into the scene's space by :meth:`build`."""

    reduced_model = "model_II"  # the key in reduced_models.MODELS of the model that fits a scene with particles
    # s recorded by each of a quick comparison's paired runs (with and without particles): 4 s hold the band 3-30 v/a
    # with 1 s Welch segments (7 half-overlapping), and the pair (about 16 CPU s, after 1 s of warm-up each) keeps the
    # quick report under 30 s on two cores
    quick_duration = 4.0

    def validate(self, where: str = "") -> None:
        sc = self.sc
        if not sc.substrate_part.hosts_wear or not sc.arrangement_part.hosts_wear:
            raise ValueError(f"wear particles need flat pad tracks (substrate.kind 'patches', pads.arrangement "
                             f"'tracks'; got {sc.substrate.kind!r}, {sc.pads.arrangement!r})")
        check_wear(sc)

    def friction_split(self, mu0: float) -> tuple[float, float]:
        return pad_friction_split(mu0, self.spec.mu_pad, self.spec.mu_track)

    def draw_sizes(self, rng):
        """Radii ``r`` (m) and masses ``mass`` (kg, a disc of depth _DEPTH, at least min_mass) of the grains."""
        spec = self.spec
        self.radii_m = draw_radii(spec, spec.count, rng)
        return {"r": (self.radii_m, "length"),
                "mass": (np.maximum(spec.density * math.pi * self.radii_m**2 * _DEPTH, spec.min_mass), "mass")}

    def build(self, scene, rng, particle_friction: float, grains) -> None:
        spec = self.spec
        self.scene, self.rng = scene, rng
        space = scene.space
        N = len(scene.pads)
        self.r, self.mass = grains.r, grains.mass
        locked = spec.rotation == "locked"
        self.moment = np.full(spec.count, np.inf) if locked else 0.5 * self.mass * self.r**2
        self.track = np.arange(spec.count) % N
        self.surface = np.array([scene.track_surface[i] for i in self.track])  # track top (y, mm)
        self.ahead, self.behind = self.own.ahead, self.own.behind
        self.R_pad = self.ctx.pad_radius
        self.floor_depth = scene.substrate.floor_depth()
        self.bodies, self.shapes = [], []
        self.recycled = 0
        self.lost = 0  # left the interface (above the pad or below the track) rather than falling behind
        self.recycle_work = 0.0  # scene energy units
        for j in range(spec.count):
            b = pymunk.Body(float(self.mass[j]), float(self.moment[j]))
            s = pymunk.Circle(b, float(self.r[j]))
            s.friction = particle_friction
            s.filter = scene.track_filter[self.track[j]]
            b.position = (0.0, -1e3)  # placed by _place below
            space.add(b, s)
            self.bodies.append(b)
            self.shapes.append(s)
        for j in range(spec.count):  # spread over [pad + R, pad + ahead] of their tracks at the start
            if not self._place(j, initial=True, tries=200):
                raise ValueError(f"wear: no free place for particle {j} ahead of pad {self.track[j]} "
                                 f"(wear.ahead = {spec.ahead} m is too short for wear.count = {spec.count})")
        # idle particles at rest sleep until a pad reaches them (pads and block never rest)
        space.sleep_time_threshold = 20.0  # ms
        # mm/ms = 2 mm/s: a resting grain gains g dt = 1e-3 mm/ms per step before its contact stops it
        space.idle_speed_threshold = 2e-3

    @property
    def count(self) -> int:
        return len(self.bodies)

    def _free(self, j, x) -> bool:
        r, tr = self.r[j], self.track[j]
        for k in np.flatnonzero(self.track == tr):
            if k != j and abs(self.bodies[k].position.x - x) < r + self.r[k] and self.bodies[k].position.y < self.surface[k] + 3 * self.R_pad:
                return False
        return True

    def _place(self, j, initial=False, tries=8) -> bool:
        """Put particle j at rest on its track at a random free place ahead of its pad; False if none found."""
        b = self.bodies[j]
        pad = self.scene.pads[self.track[j]]
        r = self.r[j]
        x0 = pad.position.x + self.R_pad + r
        for _ in range(tries):
            x = x0 + self.rng.random() * (self.ahead - self.R_pad - r)
            if self._free(j, x):
                y = self.surface[j] + r
                if not initial:
                    g = -self.scene.space.gravity.y
                    v, w = b.velocity, b.angular_velocity
                    ke = 0.5 * b.mass * (v.x**2 + v.y**2) + (0.5 * b.moment * w * w if w else 0.0)
                    self.recycle_work += b.mass * g * (y - b.position.y) - ke
                b.position = (x, y)
                b.velocity = (0.0, 0.0)
                b.angular_velocity = 0.0
                b.angle = 0.0
                if not initial:
                    b.activate()
                return True
        return False

    def maintain(self):
        """Recycle particles left behind, pushed far ahead, or out of the interface (every few output steps)."""
        for j, b in enumerate(self.bodies):  # asleep ones too: a grain left behind must go before its track does
            pad = self.scene.pads[self.track[j]]
            x, y = b.position
            below = y < self.surface[j] - self.floor_depth  # fell through the track (deeper than any pit)
            above = y > pad.position.y + self.R_pad + 2 * self.r[j]
            if below or above:
                if self._place(j):
                    self.lost += 1
                    self.recycled += 1
            elif x < pad.position.x - self.behind or x > pad.position.x + 3 * self.ahead:
                if self._place(j):
                    self.recycled += 1

    def recorder_table(self) -> np.ndarray:
        moment = np.where(np.isfinite(self.moment), self.moment, 0.0)  # locked grains: no rotational energy
        n = self.count
        table = np.column_stack([self.mass, moment, self.r, np.zeros(n), np.zeros(n), np.zeros(n)]).astype(float)
        for j, b in enumerate(self.bodies):
            table[j, 4:6] = b.position.x, b.position.y
        return table

    def mark_sleeping(self, table: np.ndarray) -> None:
        for j, b in enumerate(self.bodies):
            table[j, 3] = b.is_sleeping

    def trace_metadata(self, stale: int) -> dict:
        return {"stale_arbiters_skipped": stale}

    def run_metadata(self) -> dict:
        return {"wear": {"count": self.count, "recycled": self.recycled, "left_interface": self.lost,
                         "radii_m": self.radii_m.tolist(), "track": self.track.tolist(),
                         "asleep_at_end": int(sum(b.is_sleeping for b in self.bodies))}}

    def view(self, scene, view: dict) -> dict:
        """Grains of tens of um: the view zooms onto the first pad's track and draws the pads at their true size."""
        surf = scene.track_surface[0]
        return {**view, "window": 0.6 * self.spec.ahead, "ylim": (surf - 0.3, surf + 0.9),
                "ylabel": "y (mm): the first pad's track", "block_top": view["block_top"], "true_size": True}

    def observer(self, scene):
        return _States(scene)

    def key(self) -> list:
        return [(f"grain {n}", c) for n, c in zip(STATE_NAMES, STATE_COLORS)]

    def draw(self, states) -> dict:
        xy, r = self.snapshot()
        return {"grains": ("discs", (xy, 2 * r, STATE_COLORS[states]), {"zorder": 4})}

    side_exaggeration = 2  # grains of tens of um: ellipses at most 2:1
    side_pads = 4  # four pads, each over its grains, large enough to see them

    def side(self, scene, lay, states):
        """The grains on the shown pads' tracks, within their slots, at the view's exaggeration (ellipses: a disc
        of radius r drawn r wide and E r tall), coloured by state."""
        xy, r = self.snapshot()
        bx = scene.block.position.x
        th = np.linspace(0, 2 * np.pi, 25)
        polys, colours = [], []
        for j, (x, y) in enumerate(xy):
            i = int(self.track[j])
            if i >= lay.n_show or abs(x - bx) > 0.48 * lay.pad_win - r[j]:
                continue
            cx, cy = x - bx + lay.x0[i] + lay.pad_at, lay.y(y - scene.track_surface[i])
            polys.append(np.column_stack([cx + r[j] * np.cos(th), cy + lay.E * r[j] * np.sin(th)]))
            colours.append(STATE_COLORS[states[j]])
        return {"grains": ("polys", polys, {"facecolors": colours or "none", "edgecolors": "k", "linewidths": 0.3,
                                            "zorder": 5})}

    def snapshot(self):
        """(positions (n, 2), radii) in scene units, for rendering. A grain's state (idle, trapped, moving) is the
        recorder's alone (engine_sim.record: touching its pad, mean speed over the output step)."""
        xy = np.array([(b.position.x, b.position.y) for b in self.bodies])
        return xy, self.r
