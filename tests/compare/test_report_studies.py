"""The report as studies: the registry, the writers (table of contents, numbered captions, nested summary
keys), the progress lines a log sees, --version, and the help every subcommand carries."""
import io
import json
import re

import pytest

from compare.report import studies
from compare.cli import main
from compare.cli.parser import build_parser
from compare.report.html import page, summary_of, write_report
from compare.cli.progress import StageProgress
from compare.report.build import build_report
from compare.report.study import Figure, Study, StudyResult


def _png() -> bytes:
    from compare.report import plots
    from compare.analysis.spectra import displacement_spectrum
    import numpy as np

    t = np.arange(4096) * 1e-3
    x = np.cumsum(np.cumsum(np.random.default_rng(0).standard_normal(t.size))) * 1e-9
    return plots.figure_png_bytes(plots.spectrum_figure([(displacement_spectrum(t, x), "random walk")]))


def _stub(quick, seed):
    """Two sections and a numbers-only result, the way a real study returns them."""
    png = _png()
    return [StudyResult("stub_a", "Stub A", {"x": seed + 1.5}, (Figure("stub_a", png, "Stub A: 1 against 1."),),
                        "<p>a</p>", ({"model": "stub", "run": "-", "wall_s": "0.0", "mean_abs_log_ratio": "0"},)),
            StudyResult("scenarios/stub_b", "Stub B", {"y": [1, 2]}, (Figure("stub_b", png, "Stub B."),), "<p>b</p>"),
            StudyResult("stub_c", "", {"z": 3})]


STUB = Study("stub_a", "stub", _stub)


def test_registry_keys_labels_unique_and_every_scene_present():
    from engine_sim import shipped_scenarios

    keys = [s.key for s in studies.STUDIES]
    labels = [s.label for s in studies.STUDIES]
    assert len(set(keys)) == len(keys) and len(set(labels)) == len(labels)
    assert {f"scenarios/{n}" for n in shipped_scenarios()} <= set(keys)
    assert keys[0] == "model_I" and keys.index("model_I") < keys.index("model_III") < keys.index("model_II")
    assert max(keys.index(k) for k in keys if not k.startswith("scenarios/") and k != "engine_work_precision") \
        < min(keys.index(k) for k in keys if k.startswith("scenarios/"))  # the models first, then the scenes
    quick = [s.key for s in studies.selected(True)]
    assert "engine_work_precision" not in quick and "engine_work_precision" in [s.key for s in studies.selected(False)]
    assert all(s.alone == (s.key == "engine_work_precision") for s in studies.STUDIES)


def test_summary_nests_keys_and_keeps_numbers_only_results():
    res = _stub(False, 0)
    s = summary_of(res, {"version": "v", "scenarios": {}})
    assert s["stub_a"] == {"x": 1.5} and s["scenarios"] == {"stub_b": {"y": [1, 2]}} and s["stub_c"] == {"z": 3}


def test_page_has_contents_anchors_and_numbered_captions():
    html = page(_stub(False, 0), {"version": "v", "seed": 0})
    links = re.findall(r"<a href='#([^']+)'>", html)
    ids = re.findall(r"<section id='([^']+)'>", html)
    assert links == ids and len(ids) == 2  # the numbers-only result has no section
    assert re.findall(r"<b>Figure (\d+)\.</b>", html) == ["1", "2"]
    assert "(figures/stub_b.png)" in html


def test_a_quick_page_says_how_to_get_every_other_scene():
    # `report --quick` runs the headline scenes only; its page names `--quick --all-scenes` for the others (the
    # installed report's test reads an all-scenes run, which has no such line)
    quick = page(_stub(True, 0), {"version": "v", "seed": 0, "quick": True, "all_scenes": False})
    every = page(_stub(True, 0), {"version": "v", "seed": 0, "quick": True, "all_scenes": True})
    assert "<code>--quick --all-scenes</code> adds every other shipped scene" in quick
    assert "--all-scenes" not in every and "quick mode (shorter runs)" in every


def test_build_report_with_stub_study_writes_every_file(tmp_path):
    events = []
    results, summary = build_report(quick=True, seed=2, studies=[STUB],
                                    progress=lambda label, ev, wall=None: events.append((label, ev)))
    assert events == [("stub", "start"), ("stub", "done")]
    assert summary["stub_a"] == {"x": 3.5} and summary["timings"][0]["model"] == "stub"
    assert [r.title for r in results if r.title][-1] == "Speed against error"
    out = write_report(tmp_path / "r", results, summary)
    assert sorted(p.name for p in (out / "figures").iterdir()) == ["stub_a.png", "stub_b.png"]
    assert json.loads((out / "summary.json").read_text())["scenarios"]["stub_b"] == {"y": [1, 2]}


def test_the_pool_starts_the_costliest_study_of_each_report_first():
    # on two workers a long study started last leaves the other worker idle for most of it: the pool starts the
    # studies by their cost in the report being built (quick or full), in measured CPU seconds
    from engine_sim import shipped_scenarios

    from compare.report.build import pool_order
    from compare.report.studies.scenes import SCENE_COSTS

    a, b, c = (Study("a", "a", None, cost=50.0, quick_cost=2.0), Study("b", "b", None, cost=5.0, quick_cost=20.0),
               Study("c", "c", None))  # c: cost 1, the same in both reports
    assert pool_order([a, b, c], quick=True) == [1, 0, 2] and pool_order([a, b, c], quick=False) == [0, 1, 2]
    assert set(SCENE_COSTS) == set(shipped_scenarios())  # a scene without a measured cost would start at random
    assert all(s.cost_in(q) > 0 for q in (True, False) for s in studies.selected(q, True) if s.key != "scenes_method")


def test_studies_marked_alone_run_last_after_the_speed_table():
    order = []

    def first(quick, seed):
        order.append("pooled")
        return StudyResult("first", "First", {"q": quick})

    def timed_alone(quick, seed):
        order.append("alone")
        return StudyResult("alone", "Alone", {"n": 1})

    results, summary = build_report(quick=False, studies=[Study("alone", "alone", timed_alone, alone=True),
                                                         Study("first", "first", first)], workers=1)
    assert order == ["pooled", "alone"]
    assert [r.key for r in results] == ["first", "timings", "alone"]
    assert list(summary).index("alone") < list(summary).index("timings")  # as before: the speed table's numbers last


def test_progress_without_a_terminal_prints_one_line_per_stage():
    buf = io.StringIO()  # not a tty, as in a log or CI
    with StageProgress(["a", "b"], desc="report", stream=buf) as p:
        p("a", "start")
        p("b", "start")
        p("b", "done", 1.25)
        p("a", "done", 2.0)
    lines = buf.getvalue().splitlines()
    assert len(lines) == 2
    assert re.fullmatch(r"report: \[1/2\] b done in 1\.2 s \(\d+\.\d s elapsed\)", lines[0]), lines[0]
    assert lines[1].startswith("report: [2/2] a done in 2.0 s")


def test_progress_bar_names_the_running_stages():
    buf = io.StringIO()
    with StageProgress(["model I", "model II"], stream=buf, tty=True) as p:
        p("model I", "start")
        p("model II", "start")
        p("model I", "done", 1.0)
        assert p.bar.postfix == "running: model II"
    assert "running: model I, model II" in buf.getvalue()


def test_version(capsys):
    from reduced_models._version import package_version

    with pytest.raises(SystemExit) as e:
        main(["--version"])
    assert e.value.code == 0
    assert capsys.readouterr().out.strip() == f"frictionnoise {package_version()}"


def test_every_subcommand_has_a_one_line_help_and_seed_is_documented():
    ap = build_parser()
    sub = next(a for a in ap._actions if a.dest == "command")
    helps = {c.dest: c.help for c in sub._choices_actions}
    assert set(helps) == set(sub.choices) and all(h and "\n" not in h for h in helps.values())
    for name, parser in sub.choices.items():
        seed = [a for a in parser._actions if "--seed" in a.option_strings]
        if name in ("report", "run", "compare", "render"):
            assert seed and seed[0].help and "seed" in seed[0].help, name
    assert "no --seed" in helps["analyze"] and "seed" in helps["sweep"]


def test_run_progress_without_a_terminal_prints_tenths():
    from compare.cli.progress import progress_bar as _progress_bar

    buf = io.StringIO()
    bar, update = _progress_bar("scene", stream=buf)
    with bar:
        for k in range(1, 101):
            update(0.06 * k, 6.0)
    lines = buf.getvalue().splitlines()
    assert len(lines) == 10, lines
    assert lines[0].startswith("scene: 0.6/6.0 s simulated (10 %; ") and lines[-1].startswith("scene: 6.0/6.0 s simulated (100 %;")
    assert all(re.search(r"\d+\.\d s elapsed$", ln) for ln in lines)


def test_run_progress_total_is_warm_up_plus_duration_from_the_start():
    """`run --duration D`: the bar's total is what the run simulates, the warm-up plus D, before the first report
    and after the run's own reports (engine_sim.run counts the warm-up in), and its label names the warm-up."""
    import engine_sim
    from compare.cli.progress import progress_bar as _progress_bar
    from engine_sim import load_scenario

    sc = load_scenario("pads_friction_patches").with_run(warmup=0.03)
    buf = io.StringIO()
    bar, update = _progress_bar("scene", stream=buf, warmup=0.03, duration=0.05, tty=True)
    with bar:
        assert bar.total == pytest.approx(0.08) and "0.03 s warm-up + 0.1 s recorded" in bar.postfix
        seen = []
        engine_sim.run(sc, duration=0.05, progress=lambda d, t: (seen.append((d, t)), update(d, t)))
        assert seen[0][0] == pytest.approx(0.03)  # its first report comes after the warm-up
        assert bar.total == pytest.approx(0.08 + sc.run.dt_out) and bar.n == bar.total  # plus the sample at t = 0
        assert "0.03 s warm-up + 0.1 s recorded; now recorded" in bar.postfix


def test_paired_runs_fill_one_bar_and_logs_name_the_warm_up():
    """compare on a wear scene simulates two runs (with and without particles): one bar of both, run by run."""
    from compare.cli.progress import progress_bar as _progress_bar

    buf = io.StringIO()
    bar, update = _progress_bar("wear", stream=buf, warmup=1.0, duration=4.0, runs=2)
    with bar:
        for _ in range(2):
            for k in range(10, 51):
                update(0.1 * k, 5.0)
    lines = buf.getvalue().splitlines()
    assert lines[0].startswith("wear: 1.0/10.0 s simulated (10 %; run 1/2: 1 s warm-up + 4.0 s recorded; now recorded)")
    assert lines[-1].startswith("wear: 10.0/10.0 s simulated (100 %; run 2/2: ")
    assert len(lines) == 10 and bar.n == bar.total == 10.0
    tty = io.StringIO()
    bar, update = _progress_bar("w", stream=tty, warmup=1.0, duration=4.0, runs=2, tty=True)
    with bar:
        assert bar.total == 10.0 and bar.postfix == ("0.0/10.0 s simulated (run 1/2: 1 s warm-up + 4.0 s recorded; "
                                                     "now warm-up, not recorded)")
        update(2.0, 5.0)
    # the bar's text: the count after the time, never opened by tqdm's ", " (it had read "| , 0.0/10.0 s ...")
    drawn = tty.getvalue().replace("\r", "\n").splitlines()[-1]
    assert "| ," not in drawn and ", 2.0/10.0 s simulated (run 1/2" in drawn, drawn


def test_process_pool_returns_results_and_ends_its_workers_on_an_interrupt():
    # compare.report.pool: the report's worker processes (spawned). Results come back; a KeyboardInterrupt in the parent
    # while a worker is busy ends that worker at once (terminate, then kill) instead of waiting for its task.
    import math
    import multiprocessing
    import time

    from compare.report.pool import process_pool

    with process_pool(1) as pool:
        assert pool.submit(math.factorial, 10).result(timeout=60) == 3628800
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        with process_pool(1) as pool:
            busy = pool.submit(time.sleep, 60)
            while not busy.running():
                time.sleep(0.01)
            procs = multiprocessing.active_children()  # the pool's worker, running its task
            raise KeyboardInterrupt
    # ended well before its 60 s task would have let it go: a worker signalled while it was still starting up may
    # take a moment to be reaped, so its end is awaited for up to 30 s (a worker left running its task stays alive)
    while any(p.is_alive() for p in procs) and time.perf_counter() - t0 < 30:
        time.sleep(0.05)
    assert time.perf_counter() - t0 < 30 and procs and not any(p.is_alive() for p in procs)


def test_each_shipped_scene_goes_to_the_study_of_its_layout(monkeypatch):
    # the parts name the model (compare.report.studies.scenes.fitting_part): wear particles -> the paired runs and
    # model II (scene_wear), sparse asperities -> model
    # III (scene_asperity, 16 s quick runs), the rate-and-state law -> the ageing model or the spring-slider
    # (scene_rate_state), every other substrate -> model I. The studies' bodies run in the slow tier (quick report
    # of every scene, install test): a wear or asperity scene costs 4-7 s of CPU even when too short to fit, the two
    # rate-and-state scenes 19 s.
    from compare.report.studies import scene_asperity, scene_rate_state, scene_wear, scenes
    from engine_sim import load_scenario, shipped_scenarios

    calls = []

    def stub(kind):
        return lambda name, sc, quick, seed, trace, duration, progress: calls.append((name, kind, duration))
    monkeypatch.setattr(scene_wear, "wear_result", stub("model II"))
    monkeypatch.setattr(scene_asperity, "asperity_result", stub("model III"))
    monkeypatch.setattr(scenes, "_model_I_result", stub("model I"))
    monkeypatch.setattr(scene_rate_state, "ageing_result", stub("model ageing"))
    monkeypatch.setattr(scene_rate_state, "slider_result", stub("spring slider"))
    for name, path in shipped_scenarios().items():
        scenes.scene_result(name, load_scenario(path), True, 0)
    kinds = {name: kind for name, kind, _ in calls}
    assert kinds["pads_with_wear"] == "model II" and kinds["asperity_field"] == "model III"
    assert kinds["pads_friction_patches"] == kinds["pads_rough_profile"] == kinds["line_scan_example"] == "model I"
    assert kinds["pads_rate_state"] == "model ageing" and kinds["spring_slider_rate_state"] == "spring slider"
    assert dict((n, d) for n, _, d in calls)["asperity_field"] == 16.0


def test_first_report_tutorial_states_what_the_full_report_adds():
    """docs/tutorials/first_report.md: without --quick the scenes run 12.5 s (asperity_field 20 s,
    spring_slider_rate_state its 30 s), and the full report adds model Ib on the rough scene (three seeds of 12.5 s) and the work-precision study (four
    step settings, run alone)."""
    from pathlib import Path

    from engine_sim import load_scenario, shipped_scenarios
    from compare.report.studies import scene_rough_multiscale, work_precision
    from compare.report.studies.scenes import full_duration

    text = " ".join((Path(__file__).parents[2] / "docs/tutorials/first_report.md").read_text().split())
    assert ("for 12.5 s of simulated time each (`asperity_field` for 20 s, `spring_slider_rate_state` for its "
            "scenario's 30 s)") in text
    assert "three seeds of 12.5 s" in text and "at four step settings, run alone" in text
    full = {}
    for name, path in shipped_scenarios().items():
        sc = load_scenario(path)
        full[name] = full_duration(sc) or sc.run.duration
    assert full.pop("spring_slider_rate_state") == 30.0 and full.pop("asperity_field") == 20.0
    assert set(full.values()) == {12.5}
    only_full = [s for s in studies.selected(False) if s not in studies.selected(True, all_scenes=True)]
    assert only_full == [scene_rough_multiscale.STUDY, work_precision.STUDY] and work_precision.STUDY.alone
    assert (scene_rough_multiscale.SEEDS, scene_rough_multiscale.DURATION, len(work_precision.SETTINGS)) == (3, 12.5, 4)


def test_report_says_at_its_start_how_many_studies_on_how_many_workers(tmp_path, monkeypatch, capsys):
    # the first progress line comes when the first study ends (about 70 s into a quick report): one line at the
    # start, on the progress lines' stream, says what runs and when to expect results
    monkeypatch.setattr(studies, "selected", lambda quick, all_scenes=False: [STUB])
    assert main(["report", "--quick", "--workers", "1", "-o", str(tmp_path / "r")]) == 0
    lines = capsys.readouterr().err.splitlines()
    assert lines[0] == ("report: 1 study on 1 worker; the first line of results comes when the first study ends, "
                        "then one a study"), lines
    assert lines[1].startswith("report: [1/1] stub done"), lines
    alone = Study("stub_alone", "stub alone", lambda quick, seed: StudyResult("stub_alone", "", {"w": 1}), alone=True)
    monkeypatch.setattr(studies, "selected", lambda quick, all_scenes=False: [STUB, alone])
    assert main(["report", "--quick", "--workers", "2", "-o", str(tmp_path / "s")]) == 0
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("report: 2 studies on 2 workers (1 alone after the others); the first line"), lines


def test_welch_segments_are_capped_in_seconds_not_samples():
    # the shipped scenes (1 ms output) keep their 2^12 (quick) and 2^13 samples; a trace at a fine output step (a
    # shaken scene at 40 samples per period, 2.5e-5 s) gets segments as long in time, so its fit band stays
    # resolvable: capped at 2^13 samples it resolved nothing below 31 rad/s at any length, and compare asked a 4 s
    # run for "at least 3 s" (a new user's check)
    from compare.report.studies._common import segment_samples

    assert segment_samples(15_000, 1e-3, True) == 2**12 and segment_samples(30_000, 1e-3, False) == 2**13
    assert segment_samples(6_000, 1e-3, False) == 2**10  # a third of a short record
    n = segment_samples(120_000, 2.5e-5, False)  # 3 s at 2.5e-5 s: a third of the record, 1 s
    assert n == 2**15 and segment_samples(10**7, 2.5e-5, False) == 2**18  # 6.6 s: the longest power of two <= 8.2 s
