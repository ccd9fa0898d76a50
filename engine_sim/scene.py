"""The pymunk scene: a block composed with its parts, sliding over a substrate.

The parts (``engine_sim/substrates``, ``arrangements``, ``drives``, ``laws`` and the wear particles, ``wear.py``) each build
their own pymunk objects; the scene holds the space, the block and the scene-unit values they share, and never
checks a part's kind. Only what changes the result is modelled: the block is a body without a shape (guided
horizontally by a groove joint unless the arrangement lets it rest on its feet); the pads are held by springs;
the friction law's Coulomb part is solved by pymunk's contact solver and its velocity part added per sliding body.
With the linear law no Python runs inside a step: even the constant drive force is a spring, since pymunk clears
body forces after every step.
"""
from __future__ import annotations

import numpy as np
import pymunk

from . import units as U
from .laws.linear import corrected_drag
from .scenario import G, Scenario
from .wear import grain_step

__all__ = ["Scene", "corrected_drag", "describe"]

_FAR = 1e9  # mm: the block's groove reaches this far either way


def describe(sc: Scenario) -> dict:
    """What an analysis needs to know of a scenario's scene, in SI units, so it never reads the scenario's layout
    (``compare.analysis.extract`` takes it from a trace's ``metadata["scene"]``):

    effective_mass: the mass the drive accelerates (kg; Leonardo's slider adds the hanging mass, rope taut);
    friction_law: the law's parameters per pad, for its slope dF/dv at any speed (law, c [N s/m], b, v_c [m/s],
    load_per_pad [N]); friction_slope: the slope of a pad column at the law's steady speed (N s/m); omega_star =
    N c / M (rad/s) and response: "viscous" if omega_star lies above the fit band's top 30 v/a (model I's C_x ~
    C_f / omega^2 there), else "inertial" (C_x = C_F / (M^2 omega^4)); length_scale: the substrate's renewal length
    a (m); pads: N, mass (kg), k0 (N/m), c0 (N s/m), foot_length (m); contact_width: the sole's width N foot_length
    (m; 0 for pads on tracks); substrate: the substrate part's own spec; and the arrangement's own entries (the
    micro-pads' ``micro``); grain_step: the grain step rule's substeps and step
    (:func:`engine_sim.wear.grain_step`)."""
    arr, p = sc.arrangement_part, sc.pads
    M = sc.block.M + sc.drive_part.extra_mass
    v = sc.steady_velocity
    c = sc.friction_slope(v)
    a = sc.substrate_part.length_scale
    omega_star = p.N * c / M
    return {
        "effective_mass": M, "block_mass": sc.block.M, "friction_slope": c, "omega_star": omega_star,
        "friction_law": sc.law_part.describe(arr.pad_load(), sc.friction.c),
        "response": "viscous" if omega_star > 30 * v / a else "inertial", "length_scale": a,
        "pads": {"N": p.N, "mass": p.mass, "k0": p.k0, "c0": p.c0, "foot_length": p.foot_length},
        "contact_width": arr.contact_width(), "substrate": sc.to_dict()["substrate"], **arr.describe(),
        "grain_step": grain_step(sc),
        **({} if sc.vibration is None else {"vibration": sc.vibration_part.describe()}),
    }


def _bind(part, ctx) -> None:
    """Convert what ``part`` (and the parts it builds with) declares it reads in scene units, once, and hand it
    its context."""
    for q in [part, *part.subparts()]:
        q.own = U.scene_values(q.scene_inputs())
        q.ctx = ctx


class Scene:
    """A built pymunk space for a scenario. Use :meth:`advance` to step; all state is in scene units.

    The scene's builder: every SI value the scene side reads is converted here, once (:mod:`engine_sim.units`).
    Each part gets its own values (``part.own``, what its ``scene_inputs`` names) and a context of what it needs of
    its neighbours (``part.ctx``: ``pad_radius``, ``segment_radius``, ``dt_si`` (the pymunk step in s) and
    ``velocity_si`` (m/s per scene velocity unit)), both immutable and in scene units. The scene's own values are
    read by the parts, the recorder and the renderer: ``dt``, ``n_sub``, ``M``, ``v_law`` (the law's steady speed),
    ``v_trap``, ``q_pad`` and ``mu_track`` (the shape frictions), ``width`` (the sole's contact width),
    ``slider_terms`` (per sliding body: mass, c, b N_pad, v_c)."""

    def __init__(self, sc: Scenario, seed: int | None = None):
        self.sc = sc
        self.seed = sc.run.seed if seed is None else int(seed)
        p, fr = sc.pads, sc.friction
        k_g = grain_step(sc)["substeps"]  # grains: run.dt cut so omega_g dt <= 0.6 (engine_sim.wear.grain_step)
        self.dt = U.to_scene(sc.run.dt, "time") / k_g
        self.n_sub = int(round(sc.run.dt_out / sc.run.dt)) * k_g
        space = pymunk.Space()
        space.gravity = (0.0, -U.to_scene(G, "acceleration"))
        space.iterations = sc.run.iterations
        self.slop = 1e-4  # mm; pymunk's default 0.1 mm is larger than the physics here
        space.collision_slop = self.slop
        self.space = space
        self.y_block = 10.0
        v0 = U.to_scene(sc.steady_velocity, "velocity")
        self.M, self.v_law = U.to_scene(sc.block.M, "mass"), v0
        self.R_pad = U.to_scene(p.radius, "length")
        self.v_trap = sc.wear.trapped_speed * v0  # a grain touching its pad is trapped below this mean speed
        # the parts
        parts = sc.fresh_parts()  # the scene's own: parts keep state while it steps
        self.substrate, self.arrangement = parts["substrate"], parts["arrangement"]
        self.law, self.drive = parts["law"], parts["drive"]
        ctx = U.SceneValues(pad_radius=self.R_pad, segment_radius=U.to_scene(sc.substrate.segment_radius, "length"),
                            dt_si=U.to_si(self.dt, "time"), velocity_si=U.to_si(1.0, "velocity"))
        for part in parts.values():
            if part is not None:
                _bind(part, ctx)
        self.run_ahead = 200 * v0 * self.dt * self.n_sub  # the tracks' margin ahead beyond the part's own
        block = pymunk.Body(self.M, float("inf"))
        block.position = (0.0, self.y_block)
        block.velocity = (v0, 0.0)
        space.add(block)
        if self.arrangement.guided:
            space.add(pymunk.GrooveJoint(space.static_body, block, (-_FAR, self.y_block), (_FAR, self.y_block), (0, 0)))
        self.block = block
        self.seeds = np.random.SeedSequence(self.seed).spawn(p.N + 1)  # one per track, stream N for the particles
        self.wear = parts["wear"]  # the grains part (a null part without particles)
        # pymunk multiplies shape frictions: with particles the pads carry q and the tracks mu / q (see wear.py)
        self.q_pad, f_particle = self.wear.friction_split(fr.mu0)
        self.mu_track = fr.mu0 / self.q_pad
        self.width = self.arrangement.width()
        # what the arrangement builds (see engine_sim/arrangements)
        self.pads, self.sliders, self.slider_load, self.slider_c = [], [], [], []
        self.tracks, self.pad_y, self.pad_x, self.track_surface, self.track_filter = [], [], [], [], []
        self.block_springs, self.slider_springs = [], []
        self.arrangement.build(self)
        self.drive.build(self)
        # the law's terms of each slider's load and c (scene units, as the parts hand them)
        self.slider_terms = np.array([(b.mass, c, bN, U.to_scene(vc, "velocity")) for b, (c, bN, vc) in zip(
            self.sliders, (self.law.drag_terms(load, c) for load, c in zip(self.slider_load, self.slider_c)))])
        self.ahead, self.behind = self.substrate.margins(self)
        rng = np.random.default_rng(self.seeds[p.N])  # the grains' sizes, then their places
        self.wear.build(self, rng, f_particle, U.scene_values(self.wear.draw_sizes(rng)))
        # an imposed vibration, built last: it shifts every body's velocity into the substrate's frame
        self.vibration = parts["vibration"]  # None without a [vibration] section (engine_sim/vibration.py)
        if self.vibration is not None:
            self.vibration.build(self)
        self.maintain()
        self.steps = 0

    # ------------------------------------------------------------------ pickling (checkpoints)
    def __setstate__(self, state):
        """A restored scene: the arrangement re-applies what pymunk does not save (segment neighbours)."""
        self.__dict__.update(state)
        self.arrangement.restore(self)

    @property
    def time(self) -> float:
        """Simulated time (s)."""
        return U.to_si(self.steps * self.dt, "time")

    def maintain(self):
        """Generate substrate ahead of each pad and drop it behind (call at least every few output steps)."""
        self.wear.maintain()  # first: grains behind their pad leave before the track under them is dropped
        self.arrangement.maintain(self)

    def advance(self, n: int):
        """n pymunk steps, as the friction law steps them (the linear law: no Python inside a step), or as the
        vibration steps them when the scene has one (engine_sim/vibration.py).

        Parameters
        ----------
        n : int
            Number of steps of ``dt`` (s) each.
        """
        (self.law if self.vibration is None else self.vibration).advance(self, n)
        self.steps += n
