"""CLI user errors: one line naming the file and field, exit status 2, no traceback, output untouched;
and a run -> compare round trip through trace files."""
import json

import numpy as np
import pytest

from compare.cli import main
from engine_sim import shipped_scenarios

PATCHES = shipped_scenarios()["pads_friction_patches"]


@pytest.fixture
def out(tmp_path):
    d = tmp_path / "out"
    d.mkdir()
    (d / "keep.txt").write_text("old report")
    return d


def _assert_user_error(capsys, out, *needles):
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert "Traceback" not in err
    for n in needles:
        assert n in err, err
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]
    assert (out / "keep.txt").read_text() == "old report"


def _toml(tmp_path, text):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("cmd", ["run", "compare"])
def test_missing_file(cmd, tmp_path, out, capsys):
    assert main([cmd, str(tmp_path / "nope.toml"), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "nope.toml", "no such file")


def test_unknown_key_lists_valid_keys(tmp_path, out, capsys):
    p = _toml(tmp_path, "[pads]\nstiffness = 3.0\n")
    assert main(["run", str(p), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "s.toml", "pads.stiffness", "valid keys in [pads]: N, mass, radius, k0")


def test_wrong_type(tmp_path, out, capsys):
    p = _toml(tmp_path, '[pads]\nk0 = "stiff"\n')
    assert main(["run", str(p), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "pads.k0 must be a number")


def test_negative_mass(tmp_path, out, capsys):
    p = _toml(tmp_path, "[block]\nM = -0.1\n")
    assert main(["compare", str(p), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "block.M must be > 0 (got -0.1)")


def test_time_step_beyond_the_spring_limit(tmp_path, out, capsys):
    p = _toml(tmp_path, "[run]\ndt = 5e-4\n")
    assert main(["run", str(p), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "run.dt = 0.0005 s exceeds the pad spring limit 0.000147 s")


def test_trace_of_another_format(tmp_path, out, capsys):
    f = tmp_path / "other.npz"
    np.savez(f, t=np.arange(10.0), x=np.zeros(10))
    assert main(["compare", str(f), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "other.npz", "not a frictionnoise trace")
    g = tmp_path / "junk.npz"
    g.write_text("not a zip")
    assert main(["compare", str(g), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "junk.npz", "not a .npz trace file")


def test_run_then_compare_round_trip(tmp_path, capsys):
    r = tmp_path / "r"
    assert main(["run", str(PATCHES), "--duration", "4", "--seed", "2", "-o", str(r)]) == 0
    meta = json.loads((r / "trace.json").read_text())
    assert meta["seed"] == 2 and meta["scenario"]["name"] == "pads_friction_patches"
    c = tmp_path / "c"
    assert main(["compare", str(r / "trace.npz"), "-o", str(c)]) == 0
    s = json.loads((c / "summary.json").read_text())
    fit = s["scenarios"]["pads_friction_patches"]
    # 4 s is a short record: the exponent is loose (+-0.4 at 95 %) but must still read the model I regime
    assert abs(fit["gamma"] - 4.0) < 0.5 + fit["gamma_err"]
    assert (c / "index.html").exists() and any((c / "figures").iterdir())
    html = (c / "index.html").read_text()  # the page says what it is: this command's page on this scene
    assert "<title>frictionnoise compare: pads_friction_patches</title>" in html
    assert "<h1>frictionnoise compare: pads_friction_patches</h1>" in html and "frictionnoise report" not in html
    # docs/tutorials/scene_against_model.md: the terminal prints gamma, then the verdicts, one line each, as the
    # page's summary table and summary.json's "verdicts"
    printed = capsys.readouterr().out.strip().splitlines()
    wrote = [i for i, line in enumerate(printed) if line.startswith(f"wrote {c / 'index.html'}: gamma = ")]
    assert len(wrote) == 1, printed
    verdicts = printed[wrote[0] + 1:]
    assert len(verdicts) == len(s["verdicts"]) >= 1, printed
    (v,) = [v for v in s["verdicts"] if v["study"] == "scenarios/pads_friction_patches"]
    assert v["verdict"] in ("agrees", "disagrees") and "id='summary'" in html and f">{v['verdict']}</td>" in html
    assert any(line.split()[0] == v["verdict"] and "scenarios/pads_friction_patches:" in line for line in verdicts)


def test_render_png_and_gif_headless(tmp_path):
    from PIL import Image

    out = tmp_path / "ren"
    assert main(["render", str(PATCHES), "--frames", "3", "--gif", "-o", str(out)]) == 0
    pngs = sorted(out.glob("frame_*.png"))
    assert len(pngs) == 3
    gif = Image.open(out / "animation.gif")
    assert gif.n_frames == 3
    arr = np.asarray(Image.open(pngs[0]).convert("L"), dtype=float)
    assert arr.std() > 10  # not blank


@pytest.mark.slow  # pymunk's matplotlib drawing takes 0.3-0.4 s a frame, twice
@pytest.mark.timing  # a frame's cost against pymunk's drawing
def test_render_frame_costs_a_fraction_of_pymunks_drawing():
    from engine_sim import Scene, load_scenario
    from engine_sim.render import SceneRenderer

    r = SceneRenderer(Scene(load_scenario(PATCHES)))
    r.frame()
    from tests.frame_budget import frame_cost_ratio

    ratio = frame_cost_ratio(r)  # against pymunk's own drawing in turns: an absolute budget failed on busy machines
    print(f"frame cost / pymunk.matplotlib_util: {ratio:.2f}")
    assert ratio < 0.2  # measured 0.03-0.04
    r.close()


# ----------------------------------------------------------------------------- the input layer (compare/inputs.py)
def _binary(tmp_path, name="b.toml"):
    p = tmp_path / name
    p.write_bytes(bytes(range(256)) * 4)
    return p


def _npz(tmp_path, name="t.npz"):
    p = tmp_path / name
    with open(p, "wb") as fh:  # np.savez would append .npz to the name
        np.savez(fh, t=np.arange(3.0))
    return p


def _text(name, text):
    def make(tmp_path):
        p = tmp_path / name
        p.write_text(text)
        return p
    return make


def _folder(tmp_path):
    (tmp_path / "adir").mkdir()
    return tmp_path / "adir"


_SOURCES = {  # (make the input, what the one line must say)
    "folder": (_folder, "is a folder, not a file"),
    "missing": (lambda tp: tp / "nope€.toml", "no such file"),
    "empty": (_text("e.toml", ""), "empty file"),
    "comments only": (_text("c.toml", "# nothing\n\n  # here\n"), "holds no settings"),
    "binary": (_binary, "binary data"),
}


@pytest.mark.parametrize("cmd", ["run", "render", "compare", "sweep", "analyze"])
@pytest.mark.parametrize("case", list(_SOURCES))
def test_bad_input_paths_one_line_exit_2(cmd, case, tmp_path, out, capsys):
    """A folder, a missing, empty, comment-only or binary file, for every subcommand that reads one: one line
    naming the path and the problem, exit 2, nothing written (an empty TOML once ran a default scene)."""
    make, needle = _SOURCES[case]
    src = make(tmp_path)
    if cmd == "analyze" and case in ("comments only", "binary"):
        needle = ""  # the CSV's content is compare.measured's to judge (another branch); kind and emptiness are ours
    extra = ["--mass", "1"] if cmd == "analyze" else []
    status = main([cmd, str(src), *extra, "-o", str(out)])
    if cmd == "analyze" and not needle:
        assert status in (0, 2)
        capsys.readouterr()
        return
    assert status == 2
    _assert_user_error(capsys, out, src.name, needle)


def test_format_by_content_not_name(tmp_path, out, capsys):
    z = _npz(tmp_path, "looks_like.toml")  # a zip archive named .toml
    assert main(["run", str(z), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "looks_like.toml", "is an NPZ archive, not a scenario TOML file")
    assert main(["compare", str(z), "-o", str(out)]) == 2  # compare reads it as the trace it is
    _assert_user_error(capsys, out, "looks_like.toml", "not a frictionnoise trace")
    csv = tmp_path / "data.npz"
    csv.write_text("t,x\n0,0\n1,1\n")  # text named .npz
    assert main(["compare", str(csv), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "data.npz", "not a .npz trace file (text, not a zip archive)")
    csv2 = tmp_path / "data.toml"
    csv2.write_text("t,x\n0,0\n1,1\n")  # CSV named .toml: a table of numbers, whatever its name
    assert main(["run", str(csv2), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "data.toml", "not a scenario TOML file", "frictionnoise analyze")
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n")  # text that is neither TOML nor a table
    assert main(["run", str(bad), "-o", str(out)]) == 2
    _assert_user_error(capsys, out, "bad.toml", "not valid TOML")
    bad.write_text('name = "s"\nv = [\n  1e-4, 2e-4,\n  3e-4, 4e-4,\n]\n[grid\nk = 1\nj = 2\nm = 3\n')  # numbers in a
    assert main(["run", str(bad), "-o", str(out)]) == 2  # broken TOML's array are not a data table
    _assert_user_error(capsys, out, "bad.toml", "not valid TOML")


@pytest.mark.parametrize("cmd", ["run", "render", "compare", "report"])
def test_output_where_a_folder_cannot_be(cmd, tmp_path, capsys):
    f = tmp_path / "a_file"
    f.write_text("x")
    src = [] if cmd == "report" else [str(PATCHES)]
    for o, needle in ((f, "exists and is not a folder"), (f / "sub", "is a file, not a folder")):
        assert main([cmd, *src, "-o", str(o)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and needle in err and "Traceback" not in err, err
    assert f.read_text() == "x"


@pytest.mark.parametrize("cmd", ["run", "render", "compare", "report"])
def test_output_named_like_a_file_is_refused(cmd, tmp_path, capsys):
    """`-o ms.npz` once made a folder named ms.npz: -o names a folder (README, --help), so a name ending in a
    file suffix is one line naming the option, exit 2, nothing created."""
    src = [] if cmd == "report" else [str(PATCHES)]
    for name in ("ms.npz", "frame.PNG", "out.json"):
        o = tmp_path / name
        assert main([cmd, *src, "-o", str(o)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "-o/--output" in err and name in err and "Traceback" not in err, err
        assert not o.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_output_folder_with_a_dot_is_still_a_folder(tmp_path, capsys):
    """Only file suffixes are refused: a folder `run.v2`, or an existing folder named like a file, is written into."""
    old = tmp_path / "old.npz"
    old.mkdir()
    for o in (tmp_path / "run.v2", old):
        assert main(["run", str(PATCHES), "--duration", "0.02", "-o", str(o)]) == 0
        assert sorted(p.name for p in o.iterdir()) == ["trace.json", "trace.npz"]


def test_run_help_says_o_is_a_folder(capsys):
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "DIR/trace.npz and DIR/trace.json" in out and "is refused" in out


def test_unit_options_read_the_micro_sign_as_files_write_it(tmp_path, capsys):
    from compare.cli.parser import build_parser

    for typed in ("\u00b5m", "\u03bcm", "um"):
        assert build_parser().parse_args(["analyze", "x.csv", "--x-unit", typed]).x_unit == "um"
    assert build_parser().parse_args(["analyze", "x.csv", "--time-unit", "\u00b5s"]).time_unit == "us"
    # a trace given to analyze: the message says where it goes
    z = tmp_path / "trace.npz"
    z.write_bytes(b"PK\x03\x04" + bytes(range(256)))
    assert main(["analyze", str(z), "-o", str(tmp_path / "a")]) == 2
    assert "frictionnoise compare" in capsys.readouterr().err


def test_analyze_help_names_the_default_fit_and_report_help_the_quick_selection(capsys):
    from compare.analysis.displacement import METHODS
    from compare.analysis.fits import DEFAULT_METHOD
    from compare.report.studies.scenes import HEADLINE_SCENES

    with pytest.raises(SystemExit):
        main(["analyze", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    # the record model is the displacement default (METHODS[0]); the band fit's default the force data's
    assert f"{METHODS[0]} (the power law plus a white floor" in out and "the default for displacement" in out
    assert (f"{DEFAULT_METHOD} (the Whittle likelihood over a band of the stroke-averaged Welch spectrum; the default "
            "for force") in out
    assert "--band LO HI fit band (rad/s); default (record): searched over every Fourier frequency" in out
    with pytest.raises(SystemExit):
        main(["report", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert all(name in out for name in HEADLINE_SCENES) and "--all-scenes" in out


@pytest.mark.parametrize("flag, value, needle", [("--duration", "nan", "--duration must be"),
                                                 ("--duration", "-1", "--duration must be"),
                                                 ("--duration", "inf", "--duration must be"),
                                                 ("--epoch", "0", "--epoch must be"),
                                                 ("--checkpoint-every", "nan", "--checkpoint-every must be")])
def test_run_number_flags(flag, value, needle, tmp_path, capsys):
    o = tmp_path / "o"
    assert main(["run", str(PATCHES), flag, value, "-o", str(o)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err, err
    assert not o.exists()


def test_unicode_paths_and_permissions(tmp_path, capsys):
    """A scenario and an output folder with non-ASCII names; run and report write 0666 less the umask (0644
    under umask 022), not mkstemp's 0600."""
    import os
    import shutil

    d = tmp_path / "données µm"
    d.mkdir()
    src = d / "scène ü.toml"
    shutil.copy(PATCHES, src)
    o = d / "sortie ✓"
    old = os.umask(0o022)
    try:
        assert main(["run", str(src), "--duration", "0.05", "-o", str(o)]) == 0
    finally:
        os.umask(old)
    for f in ("trace.npz", "trace.json"):
        assert (o / f).stat().st_mode & 0o777 == 0o644, f
    assert sorted(p.name for p in o.iterdir()) == ["trace.json", "trace.npz"]


def test_compare_says_a_trace_is_partial(tmp_path, capsys):
    import engine_sim
    from compare.io.traces import save_trace
    from engine_sim import load_scenario

    sc = load_scenario(PATCHES).with_run(warmup=0.25)  # (the warmup's length does not bear on what is checked)
    tr = engine_sim.run(sc.with_run(duration=0.5), seed=0)
    tr.metadata["partial"] = True
    save_trace(tr, tmp_path / "p.npz")
    # 0.5 s is too short for the report's band: one error line that also says the trace is partial (this was a
    # ValueError traceback)
    assert main(["compare", str(tmp_path / "p.npz"), "-o", str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err
    assert "is a partial trace (interrupted at t = 0.500 s)" in err and "Traceback" not in err, err
    assert err.count("\n") == 1 and "too short" in err and "at least 2 s" in err and not (tmp_path / "c").exists()
    long = engine_sim.run(sc.with_run(duration=2.0), seed=0)  # long enough for the fit band (15-150 rad/s)
    long.metadata["partial"] = True
    save_trace(long, tmp_path / "q.npz")
    import os

    old = os.umask(0o022)
    try:
        assert main(["compare", str(tmp_path / "q.npz"), "-o", str(tmp_path / "d")]) == 0
    finally:
        os.umask(old)
    assert (tmp_path / "d" / "summary.json").stat().st_mode & 0o777 == 0o644  # as run's files (report's writer)
    err = capsys.readouterr().err
    assert "note: " in err and "is a partial trace (interrupted at t = 2.000 s)" in err, err
    assert "partial trace" in json.loads((tmp_path / "d" / "summary.json").read_text())["partial_trace"]


def test_compare_too_short_for_the_asperity_comparison(out, capsys):
    # 2 s of asperity_field cannot resolve the band below model III's corner (3.97 rad/s): one line saying how long
    # it must be (it was 'band [18.41, 3.975) rad/s holds no spectral ordinate'), nothing written
    assert main(["compare", "asperity_field", "--duration", "2", "-o", str(out)]) == 2
    err = capsys.readouterr().err  # off a terminal the progress lines come first, then the one error line
    assert "Traceback" not in err
    last = err.strip().splitlines()[-1]
    assert last.startswith("frictionnoise: error:") and "too short" in last and "at least 12 s" in last, err
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]


def test_compare_too_short_for_the_model_I_band_says_how_long(out, capsys):
    # 1 s of a pad scene cannot resolve the fit band's bottom 3 v/a = 18.8 rad/s with its segments: one line saying
    # how long it must be (it was 'band (18.84, 188.4) rad/s lies outside the resolved range (24.54, 3142) rad/s',
    # found by running compare NAME --duration 1 over the shipped scenes: 5 of 9 ended so), nothing written
    # pads_with_wear (its paired runs) said the same (a 1 s run: band (15.51, 155.1) rad/s outside (24.54, 3142))
    # (and 0.2 s, whose v / a reads 3x the scene's, asked for 1 s, which then asked for 2)
    for name, d in (("tilted_plane", "1"), ("pads_with_wear", "1"), ("pads_friction_patches", "0.2")):
        assert main(["compare", name, "--duration", d, "-o", str(out)]) == 2
        last = capsys.readouterr().err.strip().splitlines()[-1]
        assert last.startswith("frictionnoise: error:") and "too short" in last and "s (--duration)" in last, last
        need = int(last.split("at least ")[1].split(" s")[0])
        assert need == 2, last  # 3 v/a = 15-19 rad/s needs segments of 512 samples at 1 ms, 3 of them
        assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]


# ----------------------------------------------------------------------------- pointers to the right command
@pytest.mark.parametrize("cmd", ["compare", "run", "render"])
@pytest.mark.parametrize("name, text", [("my.csv", "time_s,x_um\n0.00,0.0\n0.01,4.67\n0.02,9.37\n"),
                                        ("export.txt", "Instrument: X\nTime;Ff\ns;N\n0,0;1,5\n0,1;1,6\n0,2;1,4\n"),
                                        ("tab.dat", "t\tx\n0\t1e-6\n1\t2e-6\n")])
def test_a_data_table_points_to_analyze(cmd, name, text, tmp_path, out, capsys, monkeypatch):
    """Measured data given where a scenario or trace belongs: one line saying to use `frictionnoise analyze`
    (it was "not valid TOML"), exit 2, nothing written; CSV, ;-separated with decimal commas, tab-separated."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / name).write_text(text)
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main([cmd, name, "-o", str(out)]) == 2
    _assert_user_error(capsys, out, name, "measured data", f"`frictionnoise analyze {name}`")
    assert sorted(p.name for p in tmp_path.iterdir()) == before


@pytest.mark.parametrize("cmd", ["run", "compare", "render"])
def test_near_miss_scenario_name_suggests_the_name(cmd, tmp_path, capsys, monkeypatch):
    """A typo in a shipped name: "did you mean pads_with_wear?" and the pointer to `frictionnoise scenarios`; exit 2,
    one line, no output folder (neither -o's nor the default one)."""
    monkeypatch.chdir(tmp_path)
    assert main([cmd, "pads_with_wears"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert "pads_with_wears: no such file" in err and "did you mean pads_with_wear?" in err, err
    assert "`frictionnoise scenarios`" in err
    assert list(tmp_path.iterdir()) == []


def test_near_miss_names_of_models_and_far_misses(tmp_path, out, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["compare", "model_1", "-o", str(out)]) == 2  # compare also takes the registered models' names
    _assert_user_error(capsys, out, "model_1", "did you mean model_I", "reduced models: model_I")
    assert main(["run", "pads_friction_patchs.toml", "-o", str(out)]) == 2  # a name with .toml is a name too
    _assert_user_error(capsys, out, "did you mean pads_friction_patches?")
    assert main(["run", "zzz", "-o", str(out)]) == 2  # nothing close: no guess, still the pointer
    err = capsys.readouterr().err
    assert "did you mean" not in err and "`frictionnoise scenarios`" in err and err.count("\n") == 1, err
    assert main(["run", "sub/pads_with_wears", "-o", str(out)]) == 2  # a path with a folder is a path, not a name
    _assert_user_error(capsys, out, "no such file")


@pytest.mark.parametrize("args, needle", [(["--mass", "nan"], "--mass must be positive"),
                                          (["--mass", "0"], "--mass must be positive"),
                                          (["--mass=-inf"], "--mass must be positive"),
                                          (["--speed", "0"], "--speed must be positive"),
                                          (["--normal-col", "x"], "--normal-col applies to force data only"),
                                          (["--band", "nan", "10"], "--band must be two finite")])
def test_analyze_displacement_flags(args, needle, tmp_path, out, capsys):
    """x(t) needs no --mass and takes --method; the force-only flags and bad numbers are one line, exit 2."""
    f = tmp_path / "x.csv"
    t = np.arange(2000) * 1e-3
    f.write_text("t_s,x_mm\n" + "".join(f"{a:.3f},{b:.6f}\n" for a, b in zip(t, t)))
    assert main(["analyze", str(f), *args, "-o", str(out)]) == 2
    _assert_user_error(capsys, out, needle)


def test_shipped_examples_are_found_from_any_folder(tmp_path, monkeypatch):
    # the README's examples name shipped files as scenarios/...: from a folder that has none, they are taken from the
    # installed scenarios package (a sweep also by its bare name); an existing path of that spelling still wins
    from compare.cli.options import shipped_file
    from engine_sim.scenario import SCENARIO_DIR

    monkeypatch.chdir(tmp_path)
    assert shipped_file("scenarios/data/reciprocating_force.txt") == str(SCENARIO_DIR / "data" / "reciprocating_force.txt")
    assert shipped_file("velocity_model1", "sweeps") == str(SCENARIO_DIR / "sweeps" / "velocity_model1.toml")
    assert shipped_file("scenarios/sweeps/velocity_model1.toml") == str(SCENARIO_DIR / "sweeps" / "velocity_model1.toml")
    assert shipped_file("nothing_here.csv") == "nothing_here.csv"
    (tmp_path / "scenarios" / "data").mkdir(parents=True)
    (tmp_path / "scenarios" / "data" / "reciprocating_force.txt").write_text("t,F\n")
    assert shipped_file("scenarios/data/reciprocating_force.txt") == "scenarios/data/reciprocating_force.txt"


def test_run_takes_a_shipped_scenario_by_its_path_in_the_docs(tmp_path, monkeypatch):
    # the how-to "shake a scene" runs scenarios/sweeps/vibrated_patches.toml: from a folder that has no scenarios/
    # (a pip install) `run` takes it inside the installed package, as `sweep` and `analyze` take theirs
    from compare.cli.options import scenario_path
    from engine_sim.scenario import SCENARIO_DIR

    monkeypatch.chdir(tmp_path)
    assert scenario_path("scenarios/sweeps/vibrated_patches.toml") == str(SCENARIO_DIR / "sweeps" / "vibrated_patches.toml")
    assert scenario_path("scenarios/asperity_field.toml") == str(SCENARIO_DIR / "asperity_field.toml")
    assert main(["run", "scenarios/sweeps/vibrated_patches.toml", "-o", str(tmp_path / "r"), "--duration", "0.01"]) == 0
    assert (tmp_path / "r" / "trace.npz").is_file()


def test_a_mistyped_command_or_choice_gets_the_closest_one_suggested(capsys):
    # one line, exit 2, the program named once, and the valid name closest to the typo
    with pytest.raises(SystemExit) as e:
        main(["analyse", "x.csv"])
    err = capsys.readouterr().err
    assert e.value.code == 2
    assert err.count("\n") == 1 and "did you mean 'analyze'?" in err and "frictionnoise: error: frictionnoise" not in err
    with pytest.raises(SystemExit):
        main(["analyze", "x.csv", "--method", "lsqq"])
    err = capsys.readouterr().err
    assert "frictionnoise analyze: argument --method" in err and "did you mean 'lsq'?" in err


def test_a_mistyped_option_is_reported_by_its_command(capsys):
    # the command's own help named (not the top level's) and its closest option suggested; one line, exit 2
    with pytest.raises(SystemExit) as e:
        main(["analyze", "x.csv", "--bnad", "1", "10"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1, err
    assert "frictionnoise analyze: unrecognized arguments: --bnad" in err and "did you mean '--band'?" in err, err
    assert "(see frictionnoise analyze --help)" in err, err
    with pytest.raises(SystemExit):
        main(["--bnad"])  # no command: the top level's help
    err = capsys.readouterr().err
    assert "unrecognized arguments: --bnad (see frictionnoise --help)" in err, err
