"""The report's stages run in worker processes give the same numbers as in one process, every progress label
arrives, and the particles' cost ratio is measured with both scenes taking turns."""
import math

import pytest

from compare.cli import main
from compare.report import _run_stages
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


@pytest.mark.slow  # report stages in worker processes
def test_stages_in_workers_match_one_process():
    stages = [("model III", ["model III"]), ("model II", ["model II"])]
    serial_labels, pooled_labels = [], []
    serial = _run_stages(stages, True, 0, 1, serial_labels.append)
    pooled = _run_stages(stages, True, 0, 2, pooled_labels.append)
    assert serial_labels == ["model III", "model II"] and sorted(pooled_labels) == sorted(serial_labels)
    for (sec_a, sum_a, _), (sec_b, sum_b, _) in zip(serial, pooled):
        assert [s.title for s in sec_a] == [s.title for s in sec_b]
        a, b = _flat(sum_a), _flat(sum_b)
        assert a.keys() == b.keys() and len(a) > 10
        # seeded stages: equal up to the last bits of a floating-point sum (wall times excluded)
        for k in a:
            if "wall" not in k:
                assert b[k] == pytest.approx(a[k], rel=1e-9, abs=1e-300), k


@pytest.mark.slow  # report stages in worker processes
def test_particles_cost_more_side_by_side():
    # 50 grains cost 1.4-1.6x the particle-free twin at 20 iterations (benchmarks/wear_iterations.py);
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
