"""The wear study (does debris steepen the spectrum?): its factors, its per-cell statistics on cases with exact
answers, and its sweep files; the slow check that a cell with particles reads the slope measured against its twin."""
import math
from pathlib import Path

import numpy as np
import pytest

from compare.sweep import SweepError, expand, load_sweep
from compare.analysis.wear_study import cells, expand_factors, mean_interval as _mean_interval

SWEEPS = Path(__file__).resolve().parents[2] / "engine_sim" / "scenarios" / "sweeps"


def test_factors_stand_for_the_issues_distributions_and_name_bad_values():
    f = expand_factors({"study.size": "broad", "study.track": "cavities", "wear.count": 5})
    assert f["wear.sigma"] == 0.8 and f["wear.r_median"] == 50e-6 and f["substrate.pit_p"] == 0.5 and f["wear.count"] == 5
    p = expand_factors({"study.size": "power"})
    assert p["wear.distribution"] == "power" and p["wear.exponent"] == 3.0 and (p["wear.r_min"], p["wear.r_max"]) == (20e-6, 200e-6)
    with pytest.raises(ValueError, match="study.size = 'wide'"):
        expand_factors({"study.size": "wide"})
    with pytest.raises(ValueError, match="unknown study factor 'study.colour'"):
        expand_factors({"study.colour": "red"})


def test_interval_is_the_larger_of_seed_scatter_and_fit_intervals():
    # two seeds 1 and 3: sd sqrt(2), t(0.975, 1 dof) = 12.706: half-width 12.706 sqrt(2) / sqrt(2) = 12.706
    m, half, seeds, fits = _mean_interval([1.0, 3.0], [0.1, 0.1])
    assert m == 2.0 and seeds == pytest.approx(12.7062, rel=1e-4) and half == seeds
    # identical seeds: the fits' intervals combined over the mean, sqrt(0.3^2 + 0.4^2) / 2 = 0.25
    m, half, seeds, fits = _mean_interval([4.0, 4.0], [0.3, 0.4])
    assert seeds == 0.0 and half == pytest.approx(0.25)


def _task(count, size, track, seed, gamma, err, cx, cfg=None, b2=None):
    w = {"count": count, "fit_x": {"gamma": gamma, "gamma_err": err, "power_law": True}, "Cx_bands": cx,
         "energy_balance_rel": 0.001, "energy_flag": False, "wall_per_sim_s": 1.0, "grain_step": {"substeps": 4},
         "fit_CF_friction": {"gamma": 2.0, "gamma_err": 0.1}}
    if count:
        w.update({"CFg_bands": cfg, "B2_bands": b2, "trapped_frac": 0.1, "moving_frac": 0.2, "covered_fraction": 0.01,
                  "F_g_mean": 0.2, "left_interface": 0, "grain_overlap_max_m": 1e-6,
                  "fit_CF_grains": {"gamma": 1.5, "gamma_err": 0.2}})
    return {"params": {"wear.count": count, "study.size": size, "study.track": track}, "seed": seed,
            "fit": {"gamma": 0.0, "gamma_err": 1.0}, "wear": w}


def test_cells_pair_each_seed_with_its_twin_on_the_same_track():
    rs = [_task(0, s, "smooth", k, 4.0 + 0.1 * k, 0.1, [1.0, 1.0, 1.0]) for s in ("narrow", "broad") for k in (0, 1)]
    rs += [_task(0, "narrow", "cavities", k, 3.0, 0.1, [2.0, 2.0, 2.0]) for k in (0, 1)]
    rs += [_task(50, "narrow", "smooth", k, 4.5 + 0.1 * k, 0.1, [4.0, 2.0, 1.0], [2.0, 2.0, 2.0], [1.0, 4.0, 2.0]) for k in (0, 1)]
    rows = {(r["count"], r["size"], r["track"]): r for r in cells(rs)}
    assert set(rows) == {(0, "-", "smooth"), (0, "-", "cavities"), (50, "narrow", "smooth")}  # twins once per track
    twin, c = rows[(0, "-", "smooth")], rows[(50, "narrow", "smooth")]
    assert twin["n"] == 2 and twin["gamma"] == pytest.approx(4.05)
    assert c["delta_gamma"] == pytest.approx(0.5) and c["delta_gamma_per_seed"] == pytest.approx([0.5, 0.5])
    assert c["delta_gamma_err"] == pytest.approx(math.hypot(0.1, 0.1) * math.sqrt(2) / 2)  # seeds agree: fits' part
    assert c["Cx_ratio_bands"] == pytest.approx([4.0, 2.0, 1.0]) and c["B2_ratio_bands"] == pytest.approx([2.0, 0.5, 1.0])


def test_study_sweeps_load_with_the_issues_factors():
    full, quick = load_sweep(SWEEPS / "wear_study.toml"), load_sweep(SWEEPS / "wear_study_quick.toml")
    # the issue's counts less 200 (left out for the 2 h budget, runs at the 30 s floor), 3 sizes, 2 tracks,
    # 4 seeds (the issue's minimum); the particle-free twin once per track and seed (not once per size: the same scene)
    assert len(expand(full)) == (5 * 3 + 1) * 2 * 4 and full.grid["wear.count"] == [0, 5, 10, 25, 50, 100]
    assert full.grid["seed"] == [0, 1, 2, 3] and set(full.grid["study.size"]) == {"narrow", "broad", "power"}
    assert full.fixed["duration"] >= 30 and full.analysis["wear"] and quick.analysis["wear"]
    mass = load_sweep(SWEEPS / "wear_study_mass.toml")  # the mass systematic: the same cells and seeds, 10x heavier
    assert mass.fixed["wear.min_mass"] == 1e-4 and set(mass.grid["wear.count"]) <= set(full.grid["wear.count"])
    assert set(mass.grid["seed"]) <= set(full.grid["seed"]) and mass.fixed["duration"] == full.fixed["duration"]


def test_particle_free_twin_runs_once_per_track_and_seed():
    quick = load_sweep(SWEEPS / "wear_study_quick.toml")
    pts = expand(quick)
    twins = [(p["study.track"], s) for p, s in pts if p["wear.count"] == 0]
    assert sorted(twins) == sorted({(t, s) for t in ("smooth", "cavities") for s in (0, 1)})  # each once
    # kept at its first occurrence (the grid's first size), so a sweep folder written before keeps its cached twins
    assert {p["study.size"] for p, _ in pts if p["wear.count"] == 0} == {quick.grid["study.size"][0]}
    assert len(pts) == (1 * 3 + 1) * 2 * 2
    # a grid without a wear count is left as it was
    from compare.sweep import SweepSpec
    spec = SweepSpec(name="v", target="scenario", fixed={}, grid={"drive.v": [1e-3, 2e-3], "seed": [0, 1]},
                     analysis={}, scenario=str(SWEEPS / "pads_with_wear_study.toml"))
    assert len(expand(spec)) == 4


def test_bad_study_factor_in_a_sweep_is_one_line_naming_it(tmp_path):
    text = (SWEEPS / "wear_study_quick.toml").read_text().replace('"narrow", "broad"', '"narrow", "wide"')
    text = text.replace('scenario = "', f'scenario = "{SWEEPS}/')
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(SweepError, match="study.size = 'wide'") as e:
        load_sweep(p)
    assert "\n" not in str(e.value)


@pytest.mark.slow  # fast tier under a minute: run in CI's slow tier
def test_substepped_grains_resume_bit_for_bit(tmp_path):
    # the grain step rule cuts run.dt into fixed substeps (4 on the study's scene), so a run interrupted at an epoch
    # and resumed from its checkpoint is the uninterrupted run, bit for bit
    import engine_sim
    from engine_sim import load_scenario

    sc = load_scenario(str(SWEEPS / "pads_with_wear_study.toml")).with_wear(count=10).with_run(duration=0.3, warmup=0.05)
    a = engine_sim.run(sc, epoch=0.1)
    assert a.metadata["scene"]["grain_step"]["substeps"] == 4
    ck = tmp_path / "checkpoint.pkl"
    b = engine_sim.run(sc, epoch=0.1, checkpoint=str(ck), checkpoint_every=0.1)
    assert b.metadata["checkpoint_every_s"] == pytest.approx(0.1) and b.metadata["round_trips_s"] is not None
    for name in ("x", "F_t", "p_force", "p_state", "particle_penetration", "work_drive"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


# The slow check of the study's verdict: one cell with particles (25 narrow grains) against its particle-free twin
# (same track, substrate and seed), through the sweep's own task (compare.sweep.run_task with the wear hook), 12 s each,
# every exponent by the record model (compare.analysis.record_model.fit_series over 15-150 rad/s).
# MEASURED (seed 0): smooth track, rise -0.032 +- 0.405 (95 %; twin 3.895 +- 0.305, with grains 3.863 +- 0.266; C_x
# 1.84, 17.45, 12.50x per band); cavity track, rise +0.148 +- 0.489 (twin 3.365 +- 0.422, with grains 3.513 +- 0.247;
# C_x 2.31, 9.91, 4.89x per band). What 12 s resolves: the grains add noise in every band, and on both tracks the
# rise stays below +1, the steepening by one power (omega^-4 to omega^-5) of the paper's section 10. What it does
# not: the rise's sign on either track (each interval contains 0: a paired run of 12 s is too short for a rise of a
# few tenths). The runs are deterministic: these are the numbers the test recomputes; the assertions hold the
# verdicts, not the digits.
# Tolerance: each exponent's 95 % half-width is the record model's profile interval (pooled coverage 94.4 % on
# synthetic power laws with a floor, docs/results/exponent_coverage.md); the rise's is the two added in quadrature,
# as for independent records. The twin and the cell share their substrate, so their errors may be correlated: the
# quadrature then overstates the rise's width, which makes "below +1" conservative and "contains 0" lenient.
_CELL = {"wear.count": 25, "study.size": "narrow"}
_CELL_T = 12.0


def _paired_rise(track, seed=0):
    from compare.sweep import SweepSpec, run_task

    spec = SweepSpec(name="wear_cell", target="scenario", fixed={"duration": _CELL_T, "run.warmup": 0.5}, grid={},
                     analysis={"wear": True}, scenario=str(SWEEPS / "pads_with_wear_study.toml"))
    cell = run_task(spec, {**spec.fixed, **_CELL, "study.track": track}, seed)
    twin = run_task(spec, {**spec.fixed, **_CELL, "study.track": track, "wear.count": 0}, seed)
    assert "error" not in cell and "error" not in twin, (cell.get("error"), twin.get("error"))
    g, g0 = cell["wear"]["fit_x"], twin["wear"]["fit_x"]
    ratio = np.asarray(cell["wear"]["Cx_bands"]) / np.asarray(twin["wear"]["Cx_bands"])
    return g["gamma"] - g0["gamma"], math.hypot(g["gamma_err"], g0["gamma_err"]), ratio, cell, twin


@pytest.mark.slow
@pytest.mark.extended  # four 12 s scene runs with grains (about 2 min of CPU); CI runs the same cell against its twin
# at 3.5 s in tests/project/test_study_pages.py::test_wear_quick_study_rows_rebuild
@pytest.mark.parametrize("track", ["smooth", "cavities"])
def test_cell_with_particles_against_its_twin(track):
    d, err, ratio, cell, twin = _paired_rise(track)
    print(f"\n25 narrow grains, {track} track, seed 0, {_CELL_T:g} s: gamma {cell['wear']['fit_x']['gamma']:.3f} +- "
          f"{cell['wear']['fit_x']['gamma_err']:.3f}, twin {twin['wear']['fit_x']['gamma']:.3f} +- "
          f"{twin['wear']['fit_x']['gamma_err']:.3f}: rise {d:+.3f} +- {err:.3f} (95 %); C_x / twin per band "
          f"{', '.join(f'{r:.2f}' for r in ratio)}; energy {100 * cell['wear']['energy_balance_rel']:+.3f} %")
    assert abs(cell["wear"]["energy_balance_rel"]) < 0.01 and cell["wear"]["left_interface"] == 0
    assert np.all(ratio > 1)  # the grains add noise in every band (quick study: 2.7-31x per band)
    if track == "smooth":
        # the base scene at omega^-4 (60 s x 3 seeds, band fit: 4.00 +- 0.05)
        assert 3.6 < twin["wear"]["fit_x"]["gamma"] < 4.4
    measured = {"smooth": "-0.032 +- 0.405", "cavities": "+0.148 +- 0.489"}[track]
    assert d + err < 1, f"measured below +1 (not toward omega^-5): {measured}; now {d:+.3f} +- {err:.3f}"
    assert d - err < 0 < d + err, f"measured without a resolved sign: {measured}; now {d:+.3f} +- {err:.3f}"


def test_mass_sensitivity_pairs_seeds_and_widens_the_intervals():
    from compare.analysis.wear_study import mass_sensitivity, widen

    def row(count, track, gammas, err=0.1, dg=None):
        r = {"count": count, "size": "narrow" if count else "-", "track": track, "seeds": [0, 1, 2],
             "gamma_per_seed": gammas, "gamma": sum(gammas) / 3, "gamma_err": err}
        if dg is not None:
            r.update(delta_gamma=dg, delta_gamma_err=err)
        return r

    light = [row(0, "smooth", [4.0, 4.0, 4.0]), row(25, "smooth", [4.0, 4.2, 4.4], dg=0.2)]
    heavy = [dict(row(25, "smooth", [4.7, 4.3, 4.5]), seeds=[2, 0, 1])]  # every seed +0.3 at 10x the mass, listed out
    # of order: pairs are matched by seed, not by position
    s = mass_sensitivity(light, heavy, decades=1.0)
    t = s["tracks"]["smooth"]
    assert t["per_decade"] == pytest.approx(0.3) and t["err"] == pytest.approx(0.0, abs=1e-12) and t["n"] == 3
    assert t["systematic"] == pytest.approx(0.3)
    w = {r["count"]: r for r in widen(light, s)}
    assert "gamma_err_total" not in w[0]  # the twin carries no grains
    assert w[25]["gamma_err_total"] == pytest.approx(math.hypot(0.1, 0.3))
    assert w[25]["delta_gamma_err_total"] == pytest.approx(math.hypot(0.1, 0.3))
    # a lighter rerun (decades = -1) of the same change reads the same slope per decade with the opposite sign
    assert mass_sensitivity(light, heavy, decades=-1.0)["tracks"]["smooth"]["per_decade"] == pytest.approx(-0.3)
    with pytest.raises(ValueError, match="same grain mass"):
        mass_sensitivity(light, heavy, decades=0.0)


def test_wear_task_fits_its_spectrum_on_the_wear_studys_segments():
    # a 3 s task (the quick study's length): the pipeline's default segments left the band's bottom (15 rad/s)
    # unresolved and every row of results.csv carried that error beside the wear fit that worked
    from compare.sweep import SweepSpec, run_task

    spec = SweepSpec(name="wear_cell", target="scenario", fixed={"duration": 3.0, "run.warmup": 0.5}, grid={},
                     analysis={"wear": True}, scenario=str(SWEEPS / "pads_with_wear_study.toml"))
    res = run_task(spec, {**spec.fixed, "wear.count": 0, "study.track": "smooth"}, 0)
    assert "error" not in res and "error" not in res["fit"], res.get("error") or res["fit"]
    assert res["fit"]["gamma"] == res["wear"]["fit_x"]["gamma"]


def test_mass_split_pairs_seeds_and_reads_the_light_limit_parts():
    from compare.analysis.wear_study import mass_split

    def task(seed, trapped, moving, cx):
        t = _task(25, "narrow", "smooth", seed, 4.0, 0.1, cx, [1.0] * 3, [1.0] * 3)
        t["wear"].update(F_g_trapped=trapped, F_g_moving=moving)
        return t

    light = [task(0, 0.10, 0.05, [1.0, 1.0, 1.0]), task(1, 0.20, 0.10, [2.0, 2.0, 2.0]), task(2, 0.3, 0.3, [1, 1, 1])]
    heavy = [task(1, 0.20, 1.00, [4.0, 2.0, 2.0]), task(0, 0.10, 0.50, [2.0, 1.0, 1.0])]  # a pushed part 10x: the
    # moving force goes with the mass, the trapped one stays; seed 2 has no partner and is left out
    (r,) = mass_split(light, heavy)
    assert r["seeds"] == [0, 1] and (r["count"], r["size"], r["track"]) == (25, "narrow", "smooth")
    assert r["trapped_ratio"] == pytest.approx(1.0) and r["moving_ratio"] == pytest.approx(10.0)
    assert r["moving_share"] == pytest.approx([1 / 3, 5 / 6]) and r["Cx_ratio_bands"] == pytest.approx([2.0, 1.0, 1.0])
    assert r["F_trapped"] == pytest.approx([0.15, 0.15]) and r["F_moving"] == pytest.approx([0.075, 0.75])
    assert mass_split(light, []) == []


def test_report_answer_states_the_cells_rise_in_numbers():
    # the page's answer paragraph reads the same exact cells: +0.50 in both seeds on the smooth track, no interval
    # excludes 0 from above less than it (0.5 - 0.1 > 0), C_x 4.00x the twin in the first band
    from compare.report.wear_study import answer

    rs = [_task(0, "narrow", "smooth", k, 4.0 + 0.1 * k, 0.1, [1.0, 1.0, 1.0]) for k in (0, 1)]
    rs += [_task(50, "narrow", "smooth", k, 4.5 + 0.1 * k, 0.1, [4.0, 2.0, 1.0], [2.0, 2.0, 2.0], [1.0, 4.0, 2.0])
           for k in (0, 1)]
    text = answer(cells(rs))
    assert "gamma 4.05 &plusmn;" in text and "by +0.50 to +0.50 over 1 cells (1 of them up)" in text
    assert "1 cells steeper and 0 flatter" in text and "C_x 4.00, 2.00, 1.00x the twin's per band" in text


def test_report_answer_says_how_many_runs_the_record_model_flags():
    # a run whose fit is flagged (not one power law over the band) is counted in the answer, twins apart; with none
    # flagged the answer says nothing of flags
    from compare.report.wear_study import answer

    rs = [_task(0, "narrow", "smooth", k, 4.0, 0.1, [1.0, 1.0, 1.0]) for k in (0, 1)]
    rs += [_task(50, "narrow", "smooth", k, 4.5, 0.1, [4.0, 2.0, 1.0], [2.0, 2.0, 2.0], [1.0, 4.0, 2.0]) for k in (0, 1)]
    assert "flags" not in answer(cells(rs))
    rs[2]["wear"]["fit_x"]["power_law"] = False
    assert "flags 1 of those 2 runs and 0 of the 2 twins as not one power law" in answer(cells(rs))
