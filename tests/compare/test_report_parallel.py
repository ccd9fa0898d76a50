"""The report's studies run in worker processes give the same numbers as in one process, every progress event
arrives, and the particles' cost ratio is measured with both scenes taking turns."""
import math

import pytest

from compare.cli import main
from compare.report.build import run_studies
from compare.report.studies import model_ageing, model_III
from engine_sim import load_scenario, shipped_scenarios
from engine_sim.timing import step_costs


def _flat(d, prefix=""):
    """Numbers of a nested summary as {path: value}."""
    out = {}
    if isinstance(d, dict):
        for k, v in d.items():
            out.update(_flat(v, f"{prefix}/{k}"))
    elif isinstance(d, (list, tuple)):
        for i, v in enumerate(d):
            out.update(_flat(v, f"{prefix}[{i}]"))
    elif isinstance(d, (int, float)) and not isinstance(d, bool):
        out[prefix] = float(d)
    return out


@pytest.mark.slow  # report studies in worker processes
def test_studies_in_workers_match_one_process():
    # Two seeded studies: model I with ageing contacts (about 1 s) listed before model III (tens of seconds, two
    # results: N = 30 and N = 300). The pool starts the costlier first, so the results must come back in the listed
    # order, not in the pool's; model III's two results test a study that returns several. Any seeded study tests
    # "the same numbers": the cheapest pair that also tests the order and the several results is this one.
    studies = [model_ageing.STUDY, model_III.STUDY]
    labels = [st.label for st in studies]
    serial_events, pooled_events = [], []
    serial = run_studies(studies, True, 0, 1, lambda label, ev, wall=None: serial_events.append((label, ev)))
    pooled = run_studies(studies, True, 0, 2, lambda label, ev, wall=None: pooled_events.append((label, ev)))
    assert serial_events == [(labels[0], "start"), (labels[0], "done"), (labels[1], "start"), (labels[1], "done")]
    assert sorted(pooled_events) == sorted(serial_events)
    assert pooled_events[0] == (labels[1], "start")  # the costliest first
    assert [r.key for rs in serial for r in rs] == ["models/model_ageing", "model_III", "model_III_N300"]
    for res_a, res_b in zip(serial, pooled, strict=True):
        assert len(res_a) == len(res_b)
        for a_, b_ in zip(res_a, res_b):
            assert (a_.key, a_.title) == (b_.key, b_.title)
            a, b = _flat(a_.numbers), _flat(b_.numbers)
            assert a.keys() == b.keys() and len(a) > 10
            # seeded studies: equal up to the last bits of a floating-point sum (wall times excluded)
            for k in a:
                if "wall" not in k:
                    assert b[k] == pytest.approx(a[k], rel=1e-9, abs=1e-300, nan_ok=True), k  # nan: a test not run


@pytest.mark.slow  # report stages in worker processes
@pytest.mark.timing  # the particles' cost per step against the twin's
def test_particles_cost_more_side_by_side():
    # 50 grains cost 1.4-1.6x the particle-free twin at 20 iterations (compare/studies/wear_iterations.py);
    # asserted only as "more", since a timing can be disturbed, and as finite positive numbers
    sc = load_scenario(shipped_scenarios()["pads_with_wear"])
    us_w, us_0 = step_costs([sc, sc.with_wear(count=0)], seed=0, warmup=0.5, chunks=4)
    assert all(math.isfinite(u) and u > 0 for u in (us_w, us_0))
    assert us_w > 1.1 * us_0, (us_w, us_0)


def test_workers_below_one_is_a_user_error(tmp_path, capsys):
    assert main(["report", "--quick", "--workers", "0", "-o", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--workers" in err and "Traceback" not in err
    assert not (tmp_path / "r").exists()
