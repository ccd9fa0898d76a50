"""Identification of a 400 s displacement record at 1 kHz: `compare.analysis.identify.identify` over every
registered model's family (target: 15 s of wall time on the 2-core machine).

    python -m benchmarks.bench_identify [--smoke]
    python -m pytest benchmarks/bench_identify.py      # the harness's entry (test_identify_400s)

The record is model I's reference case with a white sensor floor of 1e-24 m^2 s; --smoke (and --bench-smoke) use
10 s. Both time one call after a warm-up on a short record (numba's kernels compiled or loaded) and state, in the
same run, the CPU time of the compiled family shapes against the same equations as array operations on the
frequencies one evaluation of model I's family takes (every ordinate group and aliasing image of the record).
"""
import argparse
import math
import os
import time

import numpy as np

import reduced_models as rm
from compare.analysis.families import FAMILIES
from compare.analysis.identify import identify

DT = 1e-3


def record(T: float):
    """Model I's reference case, ``T`` seconds at 1 kHz, with a white sensor floor of 1e-24 m^2 s."""
    p = rm.spring_block.SpringBlockParams.reference()
    tr = rm.spring_block.simulate(p, T, DT, seed=0)
    return tr.x + np.random.default_rng(1).normal(0.0, math.sqrt(2 * math.pi * 1e-24 / DT), len(tr.x)), p.v


def _array_form(th, w, v):
    """Model I's family as numpy array operations (compare.analysis.families' equations)."""
    x = w * th["a"] / v
    renewal = 1.0 - np.cos(x) * np.sinc(x / (2.0 * np.pi)) ** 2
    r = w / th["omega_c"]
    Qc = 1.0 / (1.0 / th["Q"] - th["omega_c"] / th["omega_0"])  # the contacts' share of the resonance's damping
    z = (1.0 - r * r / (1.0 + 1j * w / th["omega_0"])) * (1.0 + 1j * w / th["omega_1"]) + 1j * r / Qc
    return th["L"] * renewal / (np.abs(z) ** 2 * w**4)


def shape_ratio(repeat: int = 200) -> float:
    """CPU time of model I's family as array operations over its compiled form, on 4000 frequencies (800 ordinate
    groups of a 400 s record times five aliasing images)."""
    th = {"L": 1.1e-10, "a": 1e-3, "omega_c": 548.0, "Q": 16.4, "omega_0": 1e6, "omega_1": 1e6}
    w, v, fam = np.geomspace(0.016, 3e4, 4000), 5e-4, FAMILIES["model_I"]
    fam.shape(th, w, v)  # compiled or loaded

    def cpu(fn):
        c0 = time.process_time()
        for _ in range(repeat):
            fn(th, w, v)
        return time.process_time() - c0
    return cpu(_array_form) / cpu(fam.shape)


def test_identify_400s(benchmark, ratio, smoke):
    """The harness's entry: one identification of a 400 s record at 1 kHz (10 s under --bench-smoke), every
    registered model's family; the compiled shapes' speed-up over array operations stated in the same run."""
    x, v = record(10.0 if smoke else 400.0)
    identify(x=x[:4096], dt=DT, v=v)  # warm-up: numba's kernels
    c0 = time.process_time()
    ranking = benchmark.pedantic(identify, kwargs={"x": x, "dt": DT, "v": v}, rounds=1 if not smoke else 2, iterations=1)
    ratio("CPU / wall of the timed calls", (time.process_time() - c0) / benchmark.stats.stats.total)
    benchmark.extra_info["load_average"] = os.getloadavg()[0]  # the machine's load: a wall time reads with it
    # only that it ran and did not reject the record's own model: the confusion study measures what it names
    assert any(m.model == "model_I" and m.verdict != "rejected" for m in ranking)
    ratio("model I's family, array operations / compiled (CPU)", shape_ratio())


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--smoke", action="store_true")
    a = ap.parse_args(argv)
    T = 10.0 if a.smoke else 400.0
    x, v = record(T)
    identify(x=x[:8192], dt=DT, v=v)  # warm-up
    w0, c0 = time.perf_counter(), time.process_time()
    ranking = identify(x=x, dt=DT, v=v)
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"identify, {T:g} s at 1 kHz ({len(x)} samples), {len(ranking)} models: wall {wall:.2f} s, CPU {cpu:.2f} s "
          f"(load average {os.getloadavg()[0]:.1f}); best {ranking[0].model} ({ranking[0].verdict}); model I's "
          f"family as array operations / compiled: {shape_ratio():.2f} (CPU)")


if __name__ == "__main__":
    main()
