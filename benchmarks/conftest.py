"""The speed harness (pytest-benchmark): options, the ratios each benchmark states, an injected slowdown, and the
comparison of this tree with another, interleaved round by round.

    python -m pytest benchmarks                       # every benchmark at full size, a table of timings
    python -m pytest benchmarks --bench-smoke          # CI: smoke sizes, a few rounds
    python -m pytest benchmarks --bench-smoke --benchmark-disable --benchmark-against=../base   # this tree vs ../base

docs/explanation/benchmarks.md says why pytest-benchmark and how to compare two commits.

A benchmark whose claim is a ratio (the project's loop against the bare pymunk step, the exact model I against an
explicit integrator) measures both sides in the same run and stores the ratio in ``benchmark.extra_info``; the
ratios are printed after the timing table and saved with the run (``--benchmark-json`` / ``--benchmark-save``).

``--benchmark-against=TREE`` compares each entry with the same entry of the source tree TREE (a worktree of the
base commit): two worker processes, one per tree, each importing its own tree's modules, pinned to one core, run
the entry's timed call in turn, round by round (ABAB..., the order swapped every round), each round timed on the
process's CPU clock. Round i gives the ratio r_i = new_i / base_i; the entry's figure is the median of the r_i over
all rounds of all process pairs, with its distribution-free 95 % interval (order statistics of the binomial), and
the entry fails when that median exceeds 1 + PERCENT / 100 (``--benchmark-against-fail``, 10 by default). Both
trees see the same machine within a round, so the load that moves sequential runs by tens of per cent on 2 shared
cores cancels in the ratio.

``FRICTIONNOISE_BENCH_SLOWDOWN="NAME=0.2"`` makes the benchmark whose test name contains NAME 20 % slower: each timed
call is followed by a busy wait of 0.2 times its own CPU time (in the comparison: in this tree's worker only).
tests/ uses it to show that the comparison flags a slowdown of that size.
"""
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parents[1]  # the source tree these entries belong to


def pytest_addoption(parser):
    parser.addoption("--bench-smoke", action="store_true", help="smoke sizes (CI): each benchmark in well under a second")
    g = parser.getgroup("frictionnoise: this tree against another, interleaved (benchmarks/conftest.py)")
    g.addoption("--benchmark-against", metavar="TREE",
                help="compare each entry's CPU time with the same entry of the source tree TREE, the two run round "
                     "by round in two worker processes; an entry fails when its median new / base exceeds the threshold")
    g.addoption("--benchmark-against-rounds", type=int, default=30, metavar="N",
                help="rounds per process pair (default 30)")
    g.addoption("--benchmark-against-pairs", type=int, default=2, metavar="N",
                help="worker process pairs, started afresh (default 2)")
    g.addoption("--benchmark-against-round-time", type=float, default=0.05, metavar="S",
                help="CPU seconds a round aims at: the entry's call is repeated to reach it (default 0.05)")
    g.addoption("--benchmark-against-fail", type=float, default=10.0, metavar="PERCENT",
                help="fail an entry whose median new / base exceeds 1 + PERCENT / 100 (default 10)")
    g.addoption("--benchmark-against-core", type=int, default=None, metavar="CPU",
                help="the core both workers are pinned to (default: the lowest this process may use)")


@pytest.fixture
def smoke(request) -> bool:
    """True under --bench-smoke: the benchmarks pick their small sizes."""
    return request.config.getoption("--bench-smoke")


def _slowdown(test_name: str) -> float:
    spec = os.environ.get("FRICTIONNOISE_BENCH_SLOWDOWN", "")
    if not spec:
        return 0.0
    name, _, factor = spec.partition("=")
    if not name or not factor:
        raise ValueError(f"FRICTIONNOISE_BENCH_SLOWDOWN={spec!r}: expected NAME=FRACTION, e.g. spectrum=0.2")
    return float(factor) if name in test_name else 0.0


def _slowed(fn, fraction: float):
    """``fn`` followed by a busy wait of ``fraction`` times its own duration (a slowdown by 1 + fraction), both in
    this process's CPU time, the clock the comparison reads (``--benchmark-timer=time.process_time``)."""
    def slow(*a, **k):
        t0 = time.process_time()
        out = fn(*a, **k)
        end = t0 + (1.0 + fraction) * (time.process_time() - t0)
        while time.process_time() < end:
            pass
        return out
    return slow


# One tree's worker: argv = module, entry, its parameters (JSON), smoke (0/1), slowdown fraction, core. It calls the
# entry once with stand-ins for the harness's fixtures, keeping the call the entry hands to ``benchmark``, and says
# how many more calls the entry planned (-1: any number); then each line "N" on stdin runs that call N times and
# answers their CPU seconds. Only the protocol uses stdout (the entry's
# prints go to stderr), so the worker depends on nothing in the other tree but the entry's name and fixtures.
_WORKER = r"""
import importlib, inspect, json, os, shutil, sys, tempfile, time, types
module, entry, params, smoke, fraction, core = sys.argv[1:]
params, smoke, fraction = json.loads(params), smoke == "1", float(fraction)
os.sched_setaffinity(0, {int(core)})
answer, sys.stdout = sys.stdout, sys.stderr

def run(call, n):
    target, args, kwargs, setup, iterations = call
    total = 0.0
    for _ in range(n):
        a, k = args, kwargs
        if setup is not None:
            got = setup()
            if got:
                a, k = got
        t0 = time.process_time()
        for _ in range(iterations):
            out = target(*a, **k)
        if fraction:  # the injected slowdown: a busy wait of `fraction` times the call's own CPU time
            end = t0 + (1.0 + fraction) * (time.process_time() - t0)
            while time.process_time() < end:
                pass
        total += time.process_time() - t0
    return out, total

class Benchmark:
    def __init__(self):
        self.extra_info, self.call, self.stats, self.left = {}, None, None, -1
    def __call__(self, target, *args, **kwargs):
        out = self.pedantic(target, args, kwargs)
        self.left = -1  # the harness repeats such a call at will
        return out
    def pedantic(self, target, args=(), kwargs=None, setup=None, rounds=1, warmup_rounds=0, iterations=1):
        # the calls the entry planned, less the one made here: some cannot go on (a recorder's buffer fills)
        self.call, self.left = (target, tuple(args), dict(kwargs or {}), setup, iterations), rounds + warmup_rounds - 1
        out, t = run(self.call, 1)
        self.stats = types.SimpleNamespace(stats=types.SimpleNamespace(total=t, min=t, median=t))
        return out

bench, tmp = Benchmark(), tempfile.mkdtemp()
fixtures = {"benchmark": bench, "smoke": smoke, "ratio": lambda name, value: None, "tmp_path": __import__("pathlib").Path(tmp)}
fn = getattr(importlib.import_module(module), entry)
missing = [p for p in inspect.signature(fn).parameters if p not in params and p not in fixtures]
if missing:
    raise SystemExit(f"{entry}: the comparison provides no fixture {missing[0]!r}")
fn(**{p: params[p] if p in params else fixtures[p] for p in inspect.signature(fn).parameters})
if bench.call is None:
    raise SystemExit(f"{entry} timed nothing")
print("ready", bench.left, file=answer, flush=True)
for line in sys.stdin:
    print(json.dumps(run(bench.call, int(line))[1]), file=answer, flush=True)
shutil.rmtree(tmp, ignore_errors=True)
"""


def median_interval(xs, level: float = 0.95):
    """(median, lo, hi): the median of ``xs`` and its distribution-free interval [x_(k), x_(n-k+1)], k the largest
    with P(Binomial(n, 1/2) <= k - 1) <= (1 - level) / 2 (at least ``level`` for any continuous distribution)."""
    x = sorted(xs)
    n, cdf, k = len(x), 0.0, 0
    while k < n and cdf + math.comb(n, k) / 2**n <= (1 - level) / 2:
        cdf += math.comb(n, k) / 2**n
        k += 1
    if k == 0:  # too few values for the level: the whole range
        return statistics.median(x), x[0], x[-1]
    return statistics.median(x), x[k - 1], x[n - k]


def interleaved(module: str, entry: str, params: dict, base_tree, *, smoke: bool, rounds: int = 30, pairs: int = 2,
                round_time: float = 0.05, core: int = 0, slowdown: float = 0.0) -> dict:
    """This tree's entry against ``base_tree``'s, round by round: {"ratio", "lo", "hi" (median of new / base over
    every round and its 95 % interval), "pairs" (each process pair's median), "rounds", "calls" (calls per round),
    "base_s", "new_s" (median CPU seconds of one call)}. ``slowdown`` slows this tree's worker only."""
    env = {k: v for k, v in os.environ.items() if k != "FRICTIONNOISE_BENCH_SLOWDOWN"}

    def start(tree, fraction, log):
        p = subprocess.Popen([sys.executable, "-c", _WORKER, module, entry, json.dumps(params), str(int(smoke)),
                              str(fraction), str(core)], cwd=tree, env=env, stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, stderr=log, text=True)
        ready = p.stdout.readline().split()
        if not ready or ready[0] != "ready":
            p.kill()
            p.wait()
            log.seek(0)
            raise RuntimeError(f"{entry}: the worker in {tree} did not start:\n{log.read()[-2000:]}")
        p.log, p.left = log, int(ready[1])
        return p

    def ask(p, n):
        p.stdin.write(f"{n}\n")
        p.stdin.flush()
        line = p.stdout.readline()
        if not line:
            p.log.seek(0)
            raise RuntimeError(f"{entry}: a worker stopped:\n{p.log.read()[-2000:]}")
        return json.loads(line)

    ratios, per_pair, base_s, new_s, calls = [], [], [], [], 1
    for k in range(pairs):
        with tempfile.TemporaryFile("w+") as log_b, tempfile.TemporaryFile("w+") as log_n:
            w = {"base": start(base_tree, 0.0, log_b), "new": start(HERE, slowdown, log_n)}
            try:
                left = min(q.left for q in w.values())
                if left < 0:  # calls repeat at will: about round_time per round
                    calls = max(1, math.ceil(round_time / max(ask(w["base"], 1), 1e-6)))
                    ask(w["new"], 1)
                else:  # as many rounds of one call as the entry planned
                    calls = 1
                mine = []
                for i in range(rounds if left < 0 else min(rounds, left)):
                    t = {side: ask(w[side], calls) for side in (("base", "new") if (i + k) % 2 == 0 else ("new", "base"))}
                    mine.append(t["new"] / t["base"])
                    base_s.append(t["base"] / calls)
                    new_s.append(t["new"] / calls)
                ratios += mine
                per_pair.append(statistics.median(mine))
            finally:
                for p in w.values():
                    p.stdin.close()
                    p.wait()
    m, lo, hi = median_interval(ratios)
    return {"ratio": m, "lo": lo, "hi": hi, "pairs": per_pair, "rounds": len(ratios), "calls": calls,
            "base_s": statistics.median(base_s), "new_s": statistics.median(new_s)}


_AGAINST = []  # (test name, result, flagged) of each entry compared in this session


def _compare(request, fraction: float):
    """Run the interleaved comparison of this entry; fail the test when it is slower than the threshold allows."""
    cfg = request.config
    node = request.node
    core = cfg.getoption("--benchmark-against-core")
    params = dict(node.callspec.params) if hasattr(node, "callspec") else {}  # a parametrized entry's values
    res = interleaved(node.module.__name__, node.originalname, params, Path(cfg.getoption("--benchmark-against")).resolve(),
                      smoke=cfg.getoption("--bench-smoke"), rounds=cfg.getoption("--benchmark-against-rounds"),
                      pairs=cfg.getoption("--benchmark-against-pairs"),
                      round_time=cfg.getoption("--benchmark-against-round-time"),
                      core=min(os.sched_getaffinity(0)) if core is None else core, slowdown=fraction)
    res["load"] = os.getloadavg()[0]
    limit = 1 + cfg.getoption("--benchmark-against-fail") / 100
    flagged = res["ratio"] > limit
    _AGAINST.append((node.name, res, flagged))
    if flagged:
        pytest.fail(f"{node.name}: new / base CPU time {_describe(res)} exceeds {limit:.2f}", pytrace=False)


def _describe(r: dict) -> str:
    pairs = ", ".join(f"{p:.3f}" for p in r["pairs"])
    return (f"{r['ratio']:.3f} [{r['lo']:.3f}, {r['hi']:.3f}] (median of {r['rounds']} paired rounds of {r['calls']} "
            f"call(s), 95 %; pair medians {pairs}; {r['base_s'] * 1e3:.3g} / {r['new_s'] * 1e3:.3g} ms per call; "
            f"load {r['load']:.1f})")


@pytest.fixture
def benchmark(benchmark, request):
    """pytest-benchmark's fixture. Under --benchmark-against, the entry's timed call is first compared with the
    other tree's (:func:`interleaved`); where FRICTIONNOISE_BENCH_SLOWDOWN names this test, every function it times
    is slowed by ``1 + fraction`` (the instance's class swapped for a subclass: the plugin accepts only its own
    type)."""
    fraction = _slowdown(request.node.name)
    against = request.config.getoption("--benchmark-against")
    if not fraction and not against:
        return benchmark
    base = type(benchmark)

    def prepared(fn):
        if against:
            _compare(request, fraction)
        return _slowed(fn, fraction) if fraction else fn

    class Harnessed(base):
        def __call__(self, fn, *a, **k):
            return base.__call__(self, prepared(fn), *a, **k)

        def pedantic(self, target, *a, **k):
            return base.pedantic(self, prepared(target), *a, **k)

    benchmark.__class__ = Harnessed
    return benchmark


_RATIOS = []


@pytest.fixture
def ratio(benchmark, request):
    """``ratio(name, value)``: a ratio measured in this run, stored with the benchmark and printed at the end."""
    def record(name: str, value: float):
        benchmark.extra_info[name] = value
        _RATIOS.append((request.node.name, name, value))
    return record


def pytest_terminal_summary(terminalreporter, config):
    if _RATIOS:
        terminalreporter.section("ratios measured in this run")
        for test, name, value in _RATIOS:
            terminalreporter.write_line(f"{test}: {name} = {value:.3g}")
    if _AGAINST:
        limit = 1 + config.getoption("--benchmark-against-fail") / 100
        terminalreporter.section(f"against {config.getoption('--benchmark-against')}: new / base CPU time, "
                                 f"interleaved (flagged above {limit:.2f})")
        for test, res, flagged in _AGAINST:
            terminalreporter.write_line(f"{test}: new / base CPU time {_describe(res)}{'  FLAGGED' if flagged else ''}")
