"""The layout of a recorder's sample, shared by its kernels (:mod:`engine_sim.reduction`, :mod:`engine_sim.means`,
:mod:`engine_sim.contact_order`) and the recorder (:mod:`engine_sim.record`): the scalar columns of a row, the scalar
parameters of a sample, the means' state, the body kinds of the body table, the floats of an arbiter in pymunk's batch
buffer and the grain table's columns. The kernels read columns and parameters by these names (numba freezes
module-level integers as constants); this module imports nothing.
"""
from __future__ import annotations

__all__ = ["COLS", "VIB_COLS", "PRM", "MS_COLS", "AF", "STALE_TOL"]

# columns of the recorder's scalar buffer, one row per sample
COLS = ("x", "v", "F_t", "F_n", "F_drag", "F_drive", "penetration", "power_in", "power_out", "mech", "pairs", "p_pen",
        "stale", "momentum_x", "momentum_y")
X, V, F_T, F_N, F_DRAG, F_DRIVE, PEN, POWER_IN, POWER_OUT, MECH, PAIRS, P_PEN, STALE, MOM_X, MOM_Y = range(len(COLS))
# the vibration's two columns, after COLS in the recorder's rows, written by engine_sim.vibration.Vibration.record
VIB_COLS = ("vib_disp", "vib_power")
# the scalar parameters of a sample (Recorder._prm), scene units; pulled: index of the body the drive spring pulls among
# the drive's bodies (-1: the block); means: 1 to record the forces as means over the output step (:func:`means`), 0 for
# point samples; steps: pymunk steps since the previous sample (0 at the first); w0..w3: the quadrature weights of a
# smooth force over those steps (record.step_weights); guided: 1 if a guide holds the block's height; vib_x, vib_y: a
# vibration's impulse per unit mass on every body over those steps, vib_bx, vib_by: its impulse on the block alone,
# vib_lx, vib_ly: per unit mass over the last pymunk step (all six from Vibration.impulses); law_after: 1 if the law's
# per-step impulses act after pymunk's step (Law.impulses_after_step); pair_mid: 1 (a shaken scene) to pair the last
# step's dissipative impulses with the step's mean velocity (:func:`step_mean_velocity`), 0 with v_after
PRM = ("drive_k", "anchor_x", "drive_rest", "anchor_v", "x0", "dt", "M", "g", "v_trap", "dt_out", "pulled", "means",
       "steps", "w0", "w1", "w2", "w3", "guided", "vib_x", "vib_y", "vib_bx", "vib_by", "vib_lx", "vib_ly", "law_after",
       "pair_mid")
(DRIVE_K, ANCHOR_X, DRIVE_REST, ANCHOR_V, X0, DT, MASS, GRAV, V_TRAP, DT_OUT, PULLED, MEANS, STEPS, W0, W1, W2, W3,
 GUIDED, VIB_X, VIB_Y, VIB_BX, VIB_BY, VIB_LX, VIB_LY, LAW_AFTER, PAIR_MID) = range(len(PRM))
# the means' state carried from sample to sample (engine_sim/means.py; rows: 0 the sliding system, 1 + i slider i):
# system row [P_x, P_y, drive force, drive force one step ahead]; slider rows [x, y, vx, vy, spring force x, y, one step
# ahead x, y, the law's impulse total]
MS_COLS = 9
# body kinds in the body table (rows: id, kind, index within its kind); STATIC: a body not in the table
BLOCK, SLIDER, GRAIN, DRIVE_BODY, STATIC = 0, 1, 2, 3, -1
# floats per arbiter in the batch buffer and their order: impulse, normal, point A 1, point B 1, distance 1
AF = 9
JX, JY, NX, NY, PAX, PAY, PBX, PBY, DIST = range(AF)
# the grain table (per grain): mass, moment (0 if locked), radius, asleep (set each sample), last known x, y
G_MASS, G_MOMENT, G_R, G_ASLEEP, G_X, G_Y = range(6)
# A grain's contact point lies on its circle (pymunk computes contacts from the positions the step ends with); one
# farther than this fraction of the radius off it belongs to a stale arbiter (see stale)
STALE_TOL = 0.01
