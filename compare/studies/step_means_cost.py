"""What exact per-step force means would cost if the contacts were read from Python after every pymunk step.

An output step's mean contact force is the sum of the arbiters' impulses over its pymunk steps divided by its
duration; pymunk hands the impulses of the last step only, so a recorder that averages must read them after every
step. This measures the cheapest such reader on each shipped scene: after each ``space.step``, one
``pymunk.batch.get_space_arbiters`` call (body ids, contact count, total impulse) and one numba kernel that adds each
arbiter's impulse to its sliding body's sums, against the bare ``space.step`` loop on the same scene, interleaved,
best of three. A ratio above the recorder's budget (1.15 of today's loop) says the means need the step loop itself
to leave Python (pymunk's C step and the accumulation in one compiled loop).

    python -m compare.studies.step_means_cost [--steps 20000] [NAME ...]
"""
from __future__ import annotations

import argparse
import time

import numba
import numpy as np
import pymunk.batch as B

from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.contact_order import body_of
from engine_sim.sample_layout import SLIDER

_FIELDS = (B.ArbiterFields.BODY_A_ID | B.ArbiterFields.BODY_B_ID | B.ArbiterFields.CONTACT_COUNT
           | B.ArbiterFields.TOTAL_IMPULSE)


@numba.njit(cache=True)
def _accumulate(ai, af, tab, acc):
    """acc[i] += the impulse on sliding body i (x, y) of every arbiter it is part of (on A: +J, on B: -J)."""
    for r in range(ai.shape[0] // 3):
        if ai[3 * r + 2] <= 0:
            continue
        for s in range(2):
            kind, i = body_of(tab, ai[3 * r + s])
            if kind == SLIDER:
                sg = 1.0 if s == 0 else -1.0
                acc[i, 0] += sg * af[2 * r]
                acc[i, 1] += sg * af[2 * r + 1]


def cost(name: str, n_steps: int, repeat: int = 3) -> tuple[float, float]:
    """(bare us/step, us/step with the per-step reader), best of ``repeat`` interleaved turns."""
    scene = Scene(load_scenario(shipped_scenarios()[name]))
    # steps the scene itself: it times pymunk's step bare and with a reader after each step, inside an output step
    scene.advance(2000)
    tab = np.array(sorted((b.id, SLIDER, i) for i, b in enumerate(scene.sliders)), dtype=np.int64).reshape(-1, 3)
    acc = np.zeros((len(scene.sliders), 2))
    buf = B.Buffer()
    space, step, dt = scene.space, scene.space.step, scene.dt
    chunk = 64 * scene.n_sub
    n_chunks = max(1, n_steps // chunk)
    bare, read = [], []
    for _ in range(repeat):
        for timed in (bare, read):
            total = 0.0
            for _ in range(n_chunks):
                scene.maintain()
                t0 = time.perf_counter()
                if timed is bare:
                    for _ in range(chunk):
                        step(dt)
                else:
                    for _ in range(chunk):
                        step(dt)
                        buf.clear()
                        B.get_space_arbiters(space, _FIELDS, buf)
                        _accumulate(np.frombuffer(buf.int_buf(), dtype=np.int64), np.frombuffer(buf.float_buf()),
                                    tab, acc)
                total += time.perf_counter() - t0
            scene.steps += n_chunks * chunk
            timed.append(total / (n_chunks * chunk) * 1e6)
    return min(bare), min(read)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*")
    ap.add_argument("--steps", type=int, default=20_000)
    a = ap.parse_args(argv)
    print("| scene | bare us/step | with per-step reader us/step | ratio |")
    print("|---|---|---|---|")
    for name in a.names or list(shipped_scenarios()):
        b, r = cost(name, a.steps)
        print(f"| {name} | {b:.1f} | {r:.1f} | {r / b:.3f} |", flush=True)


if __name__ == "__main__":
    main()
