"""The speed harness (pytest-benchmark): options, the ratios each benchmark states, and an injected slowdown.

    python -m pytest benchmarks                       # every benchmark at full size, a table of timings
    python -m pytest benchmarks --bench-smoke          # CI: smoke sizes, a few rounds
    python -m pytest benchmarks --benchmark-timer=time.process_time --benchmark-save=base   # store a run (.benchmarks/)
    python -m pytest benchmarks --benchmark-timer=time.process_time --benchmark-compare --benchmark-compare-fail=min:10%

docs/explanation/benchmarks.md says why pytest-benchmark and how to compare two commits.

A benchmark whose claim is a ratio (the project's loop against the bare pymunk step, the exact model I against an
explicit integrator) measures both sides in the same run and stores the ratio in ``benchmark.extra_info``; the
ratios are printed after the timing table and saved with the run (``--benchmark-json`` / ``--benchmark-save``).

``FRICTIONNOISE_BENCH_SLOWDOWN="NAME=0.2"`` makes the benchmark whose test name contains NAME 20 % slower: each timed
call is followed by a busy wait of 0.2 times its own CPU time. tests/ uses it to show that the comparison flags a
slowdown of that size.
"""
import os
import time

import pytest


def pytest_addoption(parser):
    parser.addoption("--bench-smoke", action="store_true", help="smoke sizes (CI): each benchmark in well under a second")


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


@pytest.fixture
def benchmark(benchmark, request):
    """pytest-benchmark's fixture; where FRICTIONNOISE_BENCH_SLOWDOWN names this test, every function it times is
    slowed by ``1 + fraction`` (the instance's class swapped for a subclass: the plugin accepts only its own type)."""
    fraction = _slowdown(request.node.name)
    if fraction:
        base = type(benchmark)

        class Slowed(base):
            def __call__(self, fn, *a, **k):
                return base.__call__(self, _slowed(fn, fraction), *a, **k)

            def pedantic(self, target, *a, **k):
                return base.pedantic(self, _slowed(target, fraction), *a, **k)

        benchmark.__class__ = Slowed
    return benchmark


_RATIOS = []


@pytest.fixture
def ratio(benchmark, request):
    """``ratio(name, value)``: a ratio measured in this run, stored with the benchmark and printed at the end."""
    def record(name: str, value: float):
        benchmark.extra_info[name] = value
        _RATIOS.append((request.node.name, name, value))
    return record


def pytest_terminal_summary(terminalreporter):
    if _RATIOS:
        terminalreporter.section("ratios measured in this run")
        for test, name, value in _RATIOS:
            terminalreporter.write_line(f"{test}: {name} = {value:.3g}")
