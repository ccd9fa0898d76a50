"""compare.report.vibration: the pairing of shaken cells with their unshaken twins, the intervals and the
predictions, on synthetic task results whose ratios are known exactly."""
import math

import numpy as np
import pytest

from compare.report.vibration import VibratedScene, cells, prediction, section

W = np.logspace(0, 3, 40)


def _task(f, A, seed, scale, drive=2.0, coulomb=0.8, speed=5e-3, gamma=4.0):
    return {"params": {"vibration.frequency": f, "vibration.amplitude": A}, "seed": seed, "omega": W.tolist(),
            "C": (scale * W ** -4.0).tolist(), "n_avg": [1] * len(W), "fit": {"gamma": gamma, "gamma_err": 0.1},
            "mean_velocity": speed, "mean_F_drive": drive, "mean_F_t": coulomb, "mean_F_drag": 1.5,
            "line_removed": {"amplitude": [A, 0.0, 0.0, 0.0]}}


def _sweep(twin_drives=(2.0, 2.0, 2.0)):
    twins = [_task(1000.0, 0.0, s, 1.0 + s, drive=d) for s, d in enumerate(twin_drives)]
    # the shaken cell's C is 0.4, 0.5, 0.6 of its twin's; its speed 1.2, 1.3, 1.4 of 5 mm/s, so its Coulomb part
    # (the drive's force less N c v = 300 N s/m times the speed) 0.2, 0.05, -0.1 N against the twin's 0.5 N
    shaken = [_task(1000.0, 1e-5, s, (1.0 + s) * (0.4 + 0.1 * s), drive=twin_drives[s], coulomb=0.0,
                    speed=5e-3 * (1.2 + 0.1 * s), gamma=3.9 + 0.1 * s) for s in range(3)]
    return twins + shaken


def test_paired_ratios_and_student_intervals():
    (r,) = cells(_sweep())
    t = 4.302652729911275  # Student-t 0.975 quantile, 2 degrees of freedom
    assert r["seeds"] == 3 and r["constant_force"]
    assert r["C_ratio"] == pytest.approx(0.5) and r["C_ratio_ci"] == pytest.approx(t * 0.1 / math.sqrt(3))
    assert r["coulomb"] == pytest.approx(0.1) and r["coulomb_ci"] == pytest.approx(t * 0.3 / math.sqrt(3))
    assert r["speed"] == pytest.approx(1.3) and r["gamma"] == pytest.approx(4.0)
    assert r["xi"] == pytest.approx(5e-3 / (1e-5 * 2 * math.pi * 1000))


def test_velocity_drive_recognised_by_its_varying_force():
    (r,) = cells(_sweep(twin_drives=(2.0, 2.1, 1.9)))
    assert not r["constant_force"] and "drive_rigid" in r


def test_no_twin_no_rows():
    assert cells([t for t in _sweep() if t["params"]["vibration.amplitude"] > 0]) == []


def test_prediction_limits():
    sc = VibratedScene()
    # below the threshold (slip amplitude U <= v) nothing changes
    p = prediction(20.0, 1e-7, True, sc)
    assert p["coulomb_rigid"] == 1.0 and p["speed_rigid"] == pytest.approx(1.0, abs=1e-9)  # bisection to 2^-40
    # far above it the rigid mean is the arcsin law of the pads' own slip amplitude U = share A omega
    p = prediction(1000.0, 1e-4, False, sc)
    assert p["coulomb_rigid"] == pytest.approx(2 / math.pi * math.asin(sc.v / p["U"]), rel=1e-12)
    step = 1 - (p["coulomb_rigid"] * sc.mu_n + sc.c * sc.v) / (sc.mu_n + sc.c * sc.v)
    assert p["drive_rigid"] == pytest.approx(1 - step * sc.relaxed_share())
    # the compliant pad lags the rigid law (less reduction) at an amplitude of a few deflections
    assert p["coulomb_compliant"] >= p["coulomb_rigid"]
    # constant force: the steady speed balances the drive, F = R(V) mu N + c V per pad
    q = prediction(1000.0, 1e-5, True, sc)
    V = q["speed_rigid"] * sc.v
    assert q["coulomb_rigid"] * sc.mu_n + sc.c * V == pytest.approx(sc.mu_n + sc.c * sc.v, rel=1e-9)
    with pytest.raises(ValueError, match="k0"):
        VibratedScene(k0=0.0)


def test_relaxed_share_of_an_exponential():
    """The record mean of a step relaxing as exp(-t / tau) from t = 0, over [w, w + T]: a closed form checked by
    quadrature."""
    sc = VibratedScene()
    tau = sc.N * sc.c / sc.k_drive
    t = np.linspace(sc.warmup, sc.warmup + sc.duration, 200001)
    assert 1 - np.trapezoid(np.exp(-t / tau), t) / sc.duration == pytest.approx(sc.relaxed_share(), rel=1e-9)


def test_section_has_table_figure_and_answer():
    res = section(cells(_sweep()))
    assert res.figures[0].png[:4] == b"\x89PNG"
    assert "1000 Hz" in res.html and "&plusmn;" in res.html


def test_sweep_report_of_a_vibration_sweep_carries_the_section():
    from compare.report.sweep_report import build_sweep_report
    from compare.sweep.spec import SweepSpec

    spec = SweepSpec(name="v", target="scenario", fixed={}, scenario="vibrated_patches.toml",
                     grid={"vibration.frequency": [1000.0], "vibration.amplitude": [0.0, 1e-5], "seed": [0, 1, 2]})
    results = [{**t, "wall_s": 1.0, "v": 5e-3} for t in _sweep()]
    out, summary = build_sweep_report(spec, results, [])
    assert [r.key for r in out] == ["results", "vibration_sweep"]
    assert summary["vibration"][0]["C_ratio"] == pytest.approx(0.5)


def test_task_files_without_mean_forces_are_left_out():
    old = [{k: v for k, v in t.items() if k != "mean_F_drive"} for t in _sweep()]
    assert cells(old) == []


@pytest.mark.parametrize("page", ["docs/results/vibration.md"])
def test_the_answers_measured_numbers_are_the_tables(page):
    # every "value ± interval" the answer's bullets quote is a cell of the page's table ; the prose had quoted 0.0464 ± 0.0033 where the
    # table reads 0.0464 ± 0.0031
    import re
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / page).read_text().replace("+-", "±")
    cells = {c.strip().split(" (twin")[0] for line in text.splitlines() if line.startswith("| ")
             for c in line.split("|")}
    bullets = text[text.index("The answer"):]
    start = bullets.index("\n- **")
    bullets = bullets[start:min(i for i in (bullets.find("\n- Not run"), bullets.find("\n## ")) if i > start)]
    quoted = re.findall(r"[+-]?\d[\d.e+-]* ± \d[\d.e+-]*\d", bullets)  # a paired rise keeps its sign
    assert len(quoted) >= 40, quoted
    assert [q for q in quoted if q not in cells] == []


def test_one_seed_gamma_table_quotes_each_fits_own_interval():
    # a sweep run with one seed: no Student-t interval over seeds, so the gamma table gives the fit's own 95 %
    # half-width (0.1 in every synthetic task) and the twin's gamma
    from compare.studies.vibration_sweep import gamma_markdown

    one = [t for t in _sweep() if t["seed"] == 1]
    (r,) = cells(one)
    assert r["seeds"] == 1 and math.isnan(r["gamma_ci"])
    row = gamma_markdown({"velocity": [r]}).splitlines()[2]
    assert "| 4.00 +- 0.10 | 4.00 | +0.00 | 1 |" in row and row.startswith("| 1000 | velocity | 10 |")


def test_gamma_rise_is_paired_by_seed():
    # the shaken cell's gamma 3.9, 4.0, 4.1 against twins of 4.0: rises -0.1, 0, +0.1, mean 0 with the Student-t
    # half-width of their scatter; twins whose own gammas scatter by 1 leave the paired rise unchanged
    from compare.studies.vibration_sweep import gamma_markdown

    t = 4.302652729911275
    tasks = _sweep()
    (r,) = cells(tasks)
    assert r["gamma_rise"] == pytest.approx(0.0, abs=1e-12) and r["gamma_rise_ci"] == pytest.approx(t * 0.1 / math.sqrt(3))
    for d in tasks:
        d["fit"]["gamma"] += d["seed"]  # the seed moves both runs of its pair alike
    (s,) = cells(tasks)
    assert s["gamma_ci"] > 2 and s["gamma_rise_ci"] == pytest.approx(r["gamma_rise_ci"])
    assert "| +0.00 +- 0.25 | 3 |" in gamma_markdown({"force": [s]}).splitlines()[2]
