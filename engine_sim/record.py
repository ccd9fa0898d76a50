"""Recording a scene at the output rate, in bulk (pymunk.batch), and the trace it produces (SI units).

Per output sample: the block's position and velocity; per sliding body (the pads, and the micro-pads they may
carry; ``Scene.sliders``), the tangential and normal contact force and whether it touches its track; the drive's
work and the power dissipated by the friction law (Coulomb part -f_t v and viscous part c v^2), integrated by
trapezoids, and the mechanical energy, for the energy balance W_drive (+ W_recycle) = dissipated + change of
mechanical energy. Dissipation is measured, not inferred: at every contact the friction power -F_t (v_A(p) -
v_B(p))_t (tangential force times slip at the contact point p, rotation included), plus the friction law's drag and
the springs' damping. With the log law the velocity part b N_pad ln(1 + v/v_c) enters the drag force and its power.
With wear particles: per particle and sample its state (0 idle: not touching its pad; 1 trapped: touching and slower
than the trapped threshold; 2 moving) and the tangential force it exerts on its pad.

The forces are means over the output step that ends at the sample (``run.forces = "mean"``, the default): from the
momenta and places read at the samples (``engine_sim.means``; :data:`FORCE_CHANNELS` says how each is made), so
nothing is read between samples. ``run.forces = "point"`` records the contact forces of the last pymunk step
instead (arbiter impulse / dt), which alias. The powers and the grains' forces are read at the sample.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pymunk.batch as B
from pymunk._chipmunk import lib

from . import sample_layout as R, units as U
from .batch_reader import BatchReader
from .channels import recorded_channels
from .reduction import reduce_sample, slider_velocities
from .sample_layout import COLS, MS_COLS, PRM, VIB_COLS

__all__ = ["EngineTrace", "Recorder", "step_weights", "FORCE_CHANNELS"]

# How each recorded force is made in the default recording (run.forces = "mean"), by trace field: "exact" (the mean
# over the output step from momenta and known impulses), "quadrature" (a smooth spring force integrated from the
# step's two ends) or "point" (the last pymunk step's contact force at the sample). Measured against the exact means
# on every shipped scene by `python -m compare.studies.recorder_alias --all`. The first sample of a recording has no output step
# before it: its forces are point samples.
FORCE_CHANNELS = {
    "F_t": "exact: the sliders' total tangential contact force, from the sliding system's momentum (its springs "
           "cancel) less the drive's and the law's impulses; but where contacts overlap on slanted surfaces pymunk's "
           "position correction moves the sliders without momentum, which the dampers' part reads as drag",
    "F_drag": "exact: the law's dampers (-c (dx + dv dt) summed over the step; see F_t for the position correction) "
              "and its per-step impulses",
    "F_drive": "quadrature for a velocity drive (its spring, from both ends of the step); a constant force is constant "
               "to 1e-9",
    "F_n": "exact for a block free vertically (its momentum); else quadrature: the sum of the sliders' own balances",
    "pad_force": "quadrature: the pad's momentum change less its springs' impulses (elastic part by quadrature, "
                 "damping part from the change of the spring's length), the law's and gravity's",
    "micro_force": "quadrature: as pad_force, per micro-pad",
    "p_force": "point: a grain touches its pad and its track at once, so momenta cannot separate its force on the pad",
}


# the per-trace text of the channels whose making depends on the scene (FORCE_CHANNELS gives both cases)
_F_N = {True: "quadrature: the sum of the sliders' own balances (a guided block: the guide's force is unknown)",
        False: "exact: the block is free vertically, so from its momentum"}
_F_DRIVE = {True: "exact: a constant force, constant to 1e-9",
            False: "quadrature: a velocity drive's spring, from both ends of the step"}
FIRST_SAMPLE = "point: the first sample has no output step before it, so its forces are point samples"


def force_channels(scene, forces: str) -> dict:
    """How each force of this scene's trace is made (``metadata["force_channels"]``): :data:`FORCE_CHANNELS`
    with F_n and F_drive as they apply to ``scene`` (guided block or not; constant-force drive or not), and the
    first sample's forces (``"first_sample"``); all point samples when ``forces`` is "point"."""
    if forces != "mean":
        point = "point: the contact force of the last pymunk step before the sample (aliases)"
        return {c: point for c in FORCE_CHANNELS}
    return {**FORCE_CHANNELS, "F_n": _F_N[bool(scene.arrangement.guided)],
            "F_drive": _F_DRIVE[bool(scene.sc.drive_part.constant_force)], "first_sample": FIRST_SAMPLE}


_STEPS, _VIB = PRM.index("steps"), PRM.index("vib_x")  # steps, then w0..w3; vib_x, vib_y, vib_bx, vib_by, vib_lx, vib_ly


def step_weights(n: int) -> np.ndarray:
    """Weights (w0, w1, w2, w3) of the mean over n pymunk steps of a force f that is a smooth function of the
    bodies' places: mean_{j=1..n} f_j = w0 f_0 + w1 f_1 + w2 f_n + w3 f_(n+1), with f_j the force at the places of
    step j (pymunk evaluates a spring after moving the bodies, so step j sees the places after j steps; f_0 and f_n
    are the values at the two samples, f_1 and f_(n+1) one step on, X + V dt, which the samples also know). Exact for
    f a cubic in j; for f = e^(i omega t), its error at omega T = pi/2 (half the output Nyquist frequency, T = n dt) is
    0.9 % in amplitude, 1.7 % in power (0.1 % at pi/4); the trapezoid's is 38 % in power there."""
    if n == 1:
        return np.array([0.0, 0.0, 1.0, 0.0])
    nodes = np.array([0.0, 1.0, n, n + 1.0])
    j = np.arange(1, n + 1, dtype=float)
    A = np.vstack([nodes ** p for p in range(4)])
    b = np.array([np.sum(j ** p) for p in range(4)])
    return np.linalg.solve(A, b) / n



@dataclass(frozen=True)
class EngineTrace:
    """A recorded scene run (SI units). ``t`` [s], ``x`` [m] (block position from its start), ``v`` [m/s];
    the forces are means over the output step ending at each sample, but ``p_force`` (a point sample; see
    :data:`FORCE_CHANNELS` and ``metadata["forces"]``); ``F_t``, ``F_n`` [N]: summed tangential and normal contact
    force on the sliding bodies (pads and any micro-pads;
    tangential positive against the sliding direction, i.e. the Coulomb part of the friction law); ``F_drag`` [N]:
    the velocity part of the law summed over them (c v, plus b N_pad ln(1 + v/v_c) for the log law), so F_t + F_drag
    is the whole friction force; ``F_drive`` [N]: the drive's force (for Leonardo's slider the hanging weight); ``pad_force`` [N] (samples x pads), tangential (the N pads only); ``n_contact``: pads
    touching their track; ``n_pairs``: pad-substrate contact pairs (a foot may stand on several asperities); ``penetration`` [m]: the deepest overlap of any pad with its track (pymunk's
    contact distance; 0 when no contact overlaps); ``work_drive``, ``dissipated``, ``mech_energy`` [J] cumulative from the first
    sample; ``work_recycle`` [J]: energy moved into the scene by recycling wear particles (their change of potential
    energy minus the kinetic energy taken away); ``p_state`` (samples x particles, int8: 0 idle, 1 trapped,
    2 moving), ``p_force`` [N] (samples x particles): tangential force of each particle on its pad, positive
    against sliding; ``particle_penetration`` [m]: the deepest overlap of any particle with its track (contact distance);
    ``micro_force`` [N] (samples x micro-pads): tangential contact force of each sliding body beyond the pads (the
    micro-pads, pad by pad: columns i n .. (i + 1) n - 1 belong to pad i; no columns in other scenes);
    ``metadata``: scenario, seed, version, timings, particle counts."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F_t: np.ndarray
    F_n: np.ndarray
    F_drag: np.ndarray
    F_drive: np.ndarray
    pad_force: np.ndarray
    n_contact: np.ndarray
    n_pairs: np.ndarray
    penetration: np.ndarray
    work_drive: np.ndarray
    dissipated: np.ndarray
    mech_energy: np.ndarray
    work_recycle: np.ndarray
    p_state: np.ndarray
    p_force: np.ndarray
    particle_penetration: np.ndarray
    micro_force: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    metadata: dict = field(default_factory=dict)
    # [vibration] (engine_sim/vibration.py): s(t) of the shaken part [m] (0 without vibration) and the work it
    # did [J] (the inertial force on every body in the substrate's frame, or the shaker's force on the block)
    vibration: np.ndarray = field(default_factory=lambda: np.zeros(0))
    work_vibration: np.ndarray = field(default_factory=lambda: np.zeros(0))
    # the channels the scenario names or its parts declare (engine_sim/channels.py): name -> (samples x columns), SI
    channels: dict = field(default_factory=dict)


class Recorder:
    """Samples a :class:`~engine_sim.scene.Scene` into preallocated arrays."""

    _BODY = (B.BodyFields.BODY_ID | B.BodyFields.POSITION | B.BodyFields.VELOCITY
             | B.BodyFields.ANGULAR_VELOCITY)
    _ARB = (B.ArbiterFields.BODY_A_ID | B.ArbiterFields.BODY_B_ID | B.ArbiterFields.CONTACT_COUNT
            | B.ArbiterFields.TOTAL_IMPULSE | B.ArbiterFields.NORMAL | B.ArbiterFields.POINT_A_1
            | B.ArbiterFields.POINT_B_1 | B.ArbiterFields.DISTANCE_1)

    def __init__(self, scene, n_samples: int, forces: str | None = None):
        self.scene = scene
        self.forces = scene.sc.run.forces if forces is None else forces  # "mean" or "point" (RunSpec)
        N = len(scene.pads)
        n_p = scene.wear.count
        self.k = 0
        self.t = np.empty(n_samples)
        # scalar channels per sample, columns in sample_layout.COLS order (one array: numba's dispatch cost grows with
        # the number of arguments, and this kernel runs every output step)
        self.out = np.empty((n_samples, len(COLS) + len(VIB_COLS)))  # the vibration's two columns last
        self.out[:, len(COLS):] = 0.0  # written per sample only when the scene has a vibration
        self.pad_force = np.empty((n_samples, N))
        self.micro_force = np.empty((n_samples, len(scene.sliders) - N))
        self.n_contact = np.empty(n_samples, dtype=np.int32)
        self.p_state = np.zeros((n_samples, n_p), dtype=np.int8)
        self.p_force = np.zeros((n_samples, n_p))
        self.recycle = np.zeros(n_samples)
        # per grain (sample_layout.G_*): mass, moment, radius, asleep, last place; carried across epochs (checkpoint.py)
        self.grain_table = scene.wear.recorder_table()
        self.x0 = None
        # the means' state from sample to sample (engine_sim.means): momenta, places and spring forces, spring lengths
        self.means_state = np.zeros((1 + len(scene.sliders), MS_COLS))
        self.spring_lengths = np.zeros(len(scene.block_springs) + len(scene.slider_springs))
        self.last_steps = None  # the scene's step count at the previous sample
        # the recorded channels (engine_sim/channels.py), one buffer (samples x columns, scene units) each
        self.channel_out = {ch.name: np.zeros((n_samples, ch.columns)) for ch in recorded_channels(scene)}
        self._tables()

    def _tables(self):
        """What the kernel needs of the scene, asked of its parts (bodies, springs, scene-unit constants); pymunk ids
        are addresses, so this is rebuilt after unpickling."""
        scene = self.scene
        drive = scene.drive
        # body table: sorted ids -> (kind, index); kinds 0 block, 1 sliding body (pads first), 2 particle, 3 a body of
        # the drive's (Leonardo's hanging mass)
        rows = [(scene.block.id, R.BLOCK, 0)] + [(b.id, R.SLIDER, i) for i, b in enumerate(scene.sliders)]
        rows += [(b.id, R.GRAIN, j) for j, b in enumerate(scene.wear.bodies)]
        rows += [(b.id, R.DRIVE_BODY, j) for j, b in enumerate(drive.bodies)]
        rows.sort()
        self._tab = np.array(rows, dtype=np.int64).reshape(-1, 3)
        self._bodies = BatchReader(scene.space, self._BODY, "bodies")
        self._arbiters = BatchReader(scene.space, self._ARB, "arbiters")
        # scalars for the kernel, in sample_layout.PRM order (the drive anchor's place and speed and x0 are set per sample)
        prm = {"dt": scene.dt, "M": scene.M, "g": -scene.space.gravity.y, "v_trap": scene.v_trap,
               "dt_out": scene.dt * scene.n_sub, "pulled": float(drive.pulled),
               "means": float(self.forces == "mean"), "guided": float(scene.arrangement.guided),
               "law_after": float(scene.law.impulses_after_step),
               "pair_mid": float(scene.vibration is not None and scene.vibration.active)}
        sp = drive.spring  # its stiffness, rest length and anchor offset are constant; the anchor body moves
        prm.update(drive_k=sp.stiffness, drive_rest=sp.rest_length)
        self._prm = np.array([prm.get(name, 0.0) for name in PRM])
        self._anchor = (sp.b._body, sp.anchor_b.x)  # the anchor body's C handle (chipmunk's getters read it)
        self._drive_mass = np.array([b.mass for b in drive.bodies], dtype=float)
        # springs with energy as arrays for vectorised lengths: (slider, anchors, rest length, stiffness, damping);
        # slider-slider springs use both positions; springs without stiffness (pure dampers) store none
        index = {b: i for i, b in enumerate(scene.sliders)}
        bs = [(index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness, c.damping)
              for c in scene.block_springs if c.stiffness > 0]
        pp = [(index[c.a], index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness, c.damping)
              for c in scene.slider_springs if c.stiffness > 0]
        self._bs = np.array(bs).reshape(-1, 8)
        self._pp = np.array(pp).reshape(-1, 9)
        # every spring for the means (body a: -1 the block, else a slider; body b; anchors; rest; stiffness; the
        # damping pymunk applies per step, c_eff = (e^x - 1) / (K dt), x = c K dt, K = 1/m_a + 1/m_b)
        sp = []
        for c in list(scene.block_springs) + list(scene.slider_springs):
            a = -1 if c.a is scene.block else index[c.a]
            K = 1.0 / c.a.mass + 1.0 / c.b.mass
            x = c.damping * K * scene.dt
            sp.append((a, index[c.b], *c.anchor_a, *c.anchor_b, c.rest_length, c.stiffness,
                       np.expm1(x) / (K * scene.dt)))
        self._sp = np.array(sp, dtype=float).reshape(-1, 9)
        self._weights = {}
        self._law_totals = scene.law.impulse_totals(scene)  # the law's, updated in place as it steps
        # a law's own velocity part at each sample, by its kernel at the sliders' velocities (Law.recorded_drag;
        # None: the drag_terms form alone, which the reduction computes, and zeros here)
        self._drag = scene.law.recorded_drag(scene)
        self._v_sl = np.zeros(len(scene.sliders))
        self._f_v = np.zeros(len(scene.sliders))
        self._channels = [(ch.kernel, np.asarray(ch.table(), dtype=float), self.channel_out[ch.name])
                          for ch in recorded_channels(scene)]
        self._n_last = -1  # the step count whose weights prm holds

    def __getstate__(self):
        state = self.__dict__.copy()
        for k in ("_tab", "_bodies", "_arbiters", "_prm", "_anchor", "_drive_mass", "_bs", "_pp",
                  "_sp", "_weights", "_law_totals", "_drag", "_v_sl", "_f_v", "_channels", "_n_last"):
            del state[k]  # derived from the scene (pymunk ids change on unpickling; batch buffers do not pickle)
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._tables()

    def sample(self):
        sc, k = self.scene, self.k
        if not 0 <= k < self.t.shape[0]:  # reduce_sample writes row k unchecked (numba): never past the buffers
            raise IndexError(f"recorder full: sample {k} of {self.t.shape[0]}")
        ids, fl = self._bodies.read()
        ai, af = self._arbiters.read()
        prm = self._prm
        if self.x0 is None:
            self.x0 = float(sc.block.position.x)
        prm[R.X0] = self.x0  # per sample: a checkpoint's restore sets x0 on a new recorder
        anchor, offset = self._anchor  # the drive's anchor body does not rotate: its point is the body's plus offset
        prm[R.ANCHOR_X] = lib.cpBodyGetPosition(anchor).x + offset
        prm[R.ANCHOR_V] = lib.cpBodyGetVelocity(anchor).x
        self._interval(prm)
        sc.wear.mark_sleeping(self.grain_table)
        self.recycle[k] = sc.wear.recycle_work
        if self._drag is not None:
            slider_velocities(ids, fl, self._tab, self._v_sl)
            self._drag[0](self._v_sl, self._drag[1], self._f_v)
        reduce_sample(ids, fl, ai, af, self._tab, self.grain_table, self._bs, self._pp, self._prm, sc.slider_terms,
                      self._f_v, self._drive_mass, k, self.out, self.pad_force, self.micro_force, self.n_contact,
                      self.p_state, self.p_force, self._sp, self.means_state, self.spring_lengths, self._law_totals)
        vib = getattr(sc, "vibration", None)
        if vib is not None:
            out, c = self.out, len(COLS)
            out[k, c], out[k, c + 1] = vib.record(sc, out[k, R.MOM_X], out[k, R.MOM_Y])
        self.t[k] = U.to_si(sc.steps * sc.dt, "time")
        for kernel, table, buf in self._channels:
            kernel(ids, fl, self._tab, table, buf[k])
        self.k += 1

    def _interval(self, prm):
        """The output step since the previous sample into ``prm``: its pymunk steps (0 at the first sample), the
        quadrature weights (:func:`step_weights`) and a vibration's known impulses over it and over its last pymunk
        step (per unit mass, for the step's mean velocity, :func:`engine_sim.reduction.step_mean_velocity`)."""
        sc = self.scene
        n = 0 if self.last_steps is None else sc.steps - self.last_steps
        prm[_STEPS] = n
        if n > 0:
            if n != self._n_last:
                w = self._weights.get(n)
                if w is None:
                    w = self._weights[n] = step_weights(n)
                prm[_STEPS + 1:_STEPS + 5] = w
                self._n_last = n
        vib = sc.vibration
        if vib is not None:  # over the output step (none at the first sample) and over its last pymunk step
            prm[_VIB:_VIB + 6] = vib.impulses(sc.steps if n == 0 else self.last_steps, sc.steps)
        self.last_steps = sc.steps

    def trace(self, metadata: dict) -> EngineTrace:
        n = self.k
        t = self.t[:n]
        o = {c: self.out[:n, i] for i, c in enumerate(COLS)}
        dt_s = U.to_scene(np.diff(t), "time")  # the output steps in scene time (ms), for the scene's powers
        cum = lambda p: U.to_si(np.concatenate([[0.0], np.cumsum(0.5 * (p[1:n] + p[: n - 1]) * dt_s)]), "energy")
        si = U.to_si
        metadata = {**metadata, **self.scene.wear.trace_metadata(int(o["stale"].sum())), "forces": self.forces,
                    "force_channels": force_channels(self.scene, self.forces)}
        return EngineTrace(
            t=t - t[0], x=si(o["x"] - o["x"][0], "length"), v=si(o["v"], "velocity"), F_t=o["F_t"].copy(),
            F_n=o["F_n"].copy(), F_drag=o["F_drag"].copy(), F_drive=o["F_drive"].copy(),
            pad_force=self.pad_force[:n], n_contact=self.n_contact[:n], n_pairs=o["pairs"].astype(np.int32),
            penetration=si(o["penetration"], "length"), work_drive=cum(o["power_in"]),
            dissipated=cum(o["power_out"]), mech_energy=si(o["mech"] - o["mech"][0], "energy"),
            work_recycle=si(self.recycle[:n] - self.recycle[0], "energy"),
            p_state=self.p_state[:n], p_force=si(self.p_force[:n], "force"),
            particle_penetration=si(o["p_pen"], "length"), micro_force=si(self.micro_force[:n], "force"),
            metadata=metadata, vibration=si(self.out[:n, len(COLS)], "length"),
            work_vibration=cum(self.out[:n, len(COLS) + 1]),
            channels={ch.name: si(self.channel_out[ch.name][:n], ch.quantity) for ch in recorded_channels(self.scene)},
        )
