"""What each `frictionnoise` subcommand does (the parser is :mod:`compare.cli.parser`, the entry point
:mod:`compare.cli.main`).
User errors raise :class:`UserError`: printed as one line, exit 2."""
from __future__ import annotations

import sys

from .options import (UserError, check_seconds_options, check_seed, load_scenario_arg, output_dir, scenario_path,
                      shipped_file, usable_cores)
from .progress import print_verdicts, progress_bar
from .record_summary import displacement_lines, force_lines, print_breaks

__all__ = ["cmd_analyze", "cmd_compare", "cmd_render", "cmd_report", "cmd_run", "cmd_sweep"]


def cmd_sweep(args) -> int:

    from tqdm import tqdm

    from ..report.sweep_report import build_sweep_report, write_sweep_outputs
    from ..sweep import SchedulerError, SweepError, load_results, load_sweep, run_sweep

    try:
        spec = load_sweep(shipped_file(args.sweep, "sweeps"))
    except SweepError as e:
        raise UserError(str(e)) from None
    if not 1 <= args.workers <= 64:
        raise UserError(f"--workers must be between 1 and 64 (got {args.workers})")
    if not 0 < args.connect_timeout <= 3600:
        raise UserError(f"--connect-timeout must be in (0, 3600] seconds (got {args.connect_timeout})")
    if not args.serial:
        from ..sweep.run import require_dask
        try:
            require_dask()  # before anything is written
        except SchedulerError as e:
            raise UserError(str(e)) from None
    out = output_dir(args.output, f"sweep-{spec.name}", "index.html, summary.json and its task cache")
    bar = tqdm(total=0, desc=spec.name, unit="task", file=sys.stderr, disable=not sys.stderr.isatty())

    def progress(done, total):
        bar.total = total
        bar.n = done
        bar.refresh()
    with bar:
        try:
            counts = run_sweep(spec, out, scheduler=args.scheduler, workers=args.workers, serial=args.serial,
                               progress=progress, connect_timeout=args.connect_timeout)
        except SchedulerError as e:
            raise UserError(str(e)) from None
    import json
    from ..sweep import expand, task_id
    ids = {task_id(spec, params, seed) for params, seed in expand(spec)}
    failures = [json.loads(p.read_text()) for p in sorted((out / "failures").glob("*.json")) if p.stem in ids]
    sections, summary = build_sweep_report(spec, load_results(out, spec), failures)
    write_sweep_outputs(out, sections, summary)
    print(f"{spec.name}: {counts['done']}/{counts['total']} tasks done ({counts['ran']} run now, "
          f"{counts['failed']} failed); wrote {out / 'index.html'}")
    va = summary.get("velocity_analysis")
    if va:
        print(f"  C_x at fixed omega ~ v^{va['exponent']:.3f} +- {va['exponent_err']:.3f}; distance-domain collapse "
              f"{va['collapse_gain']:.1f}x")
    return 0 if counts["failed"] == 0 else 1


def cmd_analyze(args) -> int:
    import time
    from pathlib import Path

    from ..report.html import write_report
    from ..io.measured import units_line
    from .mechanisms import mechanisms_of, ranking_lines, ranking_section

    force = args.force_col is not None
    _check_analyze_numbers(args)
    if force and args.no_mechanisms:
        raise UserError("--no-mechanisms applies to displacement data (force records are not ranked)")
    if force and args.discrete:
        raise UserError("--discrete applies to displacement data (a simulation's random walk), not to force data")
    if args.discrete and args.method not in (None, "record"):
        raise UserError(f"--discrete applies to the record model (--method record), not to --method {args.method}")
    if not force:
        for flag in ("normal_col", "direction_col", "cut", "force_unit", "mu_col", "contact_area"):
            if getattr(args, flag) is not None:
                raise UserError(f"--{flag.replace('_', '-')} applies to force data only (give --force-col)")
    if len(args.data) > 1:
        if force:
            raise UserError("several files make a velocity series of displacement records; force data: one file")
        if args.speed is not None:
            raise UserError("--speed states one record's sliding speed; a velocity series takes each record's own")
        from .series import analyze_series

        return analyze_series(args, _read_record)
    if args.omega is not None:
        raise UserError("--omega compares C_x across several records: give two or more displacement files")
    args.data = args.data[0]
    out = output_dir(args.output, f"analyze-{Path(args.data).stem}", "index.html and summary.json")
    data = _read_record(args.data, args)
    band = tuple(args.band) if args.band else None
    try:
        if force:
            from ..report.measured_report import analyze_force, build_force_report

            an = analyze_force(data, band=band, mass=args.mass, speed=args.speed, cut=args.cut, method=args.method)
            sections, summary = build_force_report(an)
        else:
            from ..analysis.displacement import analyze_displacement
            from ..report.measured_report import build_measured_report

            say = _stderr_progress if len(data.t) >= PROGRESS_SAMPLES else None
            t0 = time.perf_counter()
            if say:
                say(f"fitting the exponent of C_x ({len(data.t)} samples)")
            an = analyze_displacement(data, mass=args.mass, band=band, method=args.method, discrete=args.discrete)
            if say:
                say(f"exponent fitted in {time.perf_counter() - t0:.1f} s"
                    + ("" if args.no_mechanisms else "; naming the mechanism"))
            sections, summary = build_measured_report(an, data)
            if args.no_mechanisms:
                summary.update(units=data.units, mechanisms=[], stationarity=None,
                               mechanisms_note="not asked (--no-mechanisms)")
            else:
                summary.update(units=data.units, **mechanisms_of(
                    data, an.mean_velocity, an.fit.flags, progress=say,
                    stationarity_p=getattr(an.fit, "stationarity_p", None), speed=args.speed))
                sections = [ranking_section(summary)] + list(sections)
    except ValueError as e:
        raise UserError(f"{args.data}: {e}") from None
    write_report(out, sections, summary, title=f"frictionnoise analyze: {Path(args.data).name}")
    print("\n".join(([] if force or args.no_mechanisms else ranking_lines(summary))
                    + [f"{args.data}: {units_line(data)}"]))
    for line in (force_lines if force else displacement_lines)(summary, out / "index.html"):
        print(line)
    return 0


PROGRESS_SAMPLES = 2**15  # a record this long prints its analysis's progress (the ranking's fits take 15 s or more)


def _stderr_progress(line: str) -> None:
    """A progress line of a long analysis on stderr (the terminal's and a log's), flushed at once."""
    print(f"frictionnoise analyze: {line}", file=sys.stderr, flush=True)


def _read_record(path, args):
    """One measured record as the analyze options describe it (a UserError for what cannot be read)."""
    from ..io.inputs import input_file, sniff
    from ..io.measured import DataFileError, read_measured
    from ..io.sheets import binary_layout, is_many

    path = shipped_file(path)
    if not is_many(path) and sniff(input_file(path)) != "text" and binary_layout(path) is None:
        hint = "; a trace of `frictionnoise run` goes to `frictionnoise compare`" if str(path).endswith(".npz") else ""
        raise UserError(f"{path}: binary data, not a CSV text file{hint}")
    try:
        data = read_measured(path, time_col=args.time_col, x_col=args.x_col, force_col=args.force_col,
                             normal_col=args.normal_col, direction_col=args.direction_col, time_unit=args.time_unit,
                             x_unit=args.x_unit, force_unit=args.force_unit, require_x=args.force_col is None,
                             resample=args.resample, mu_col=args.mu_col, contact_area=args.contact_area)
    except DataFileError as e:
        raise UserError(str(e)) from None
    if data.note:
        print(f"frictionnoise: note: {data.note}", file=sys.stderr)  # the note names the file
    if data.warning:
        print(f"frictionnoise: warning: {data.warning}", file=sys.stderr)  # the warning names the file
    print_breaks(data.timeline)
    return data


def _check_analyze_numbers(args) -> None:
    import math

    for flag, value, what in (("--mass", args.mass, "kg"), ("--speed", args.speed, "m/s")):
        if value is not None and not (value > 0 and math.isfinite(value)):
            raise UserError(f"{flag} must be positive, in {what} (got {value})")
    if args.cut is not None and not (args.cut >= 0 and math.isfinite(args.cut)):
        raise UserError(f"--cut must be >= 0 s (got {args.cut})")
    if args.band is not None and not all(math.isfinite(b) for b in args.band):
        raise UserError(f"--band must be two finite frequencies in rad/s (got {args.band[0]} {args.band[1]})")


def cmd_render(args) -> int:

    from ..io.outputs import atomic_folder

    sc = load_scenario_arg(args.scenario)
    check_seed(args.seed)
    if not 1 <= args.frames <= 10_000:
        raise UserError(f"--frames must be between 1 and 10000 (got {args.frames})")
    check_seconds_options(args, "duration")
    from engine_sim.frames import draw_frames

    out = output_dir(args.output, f"render-{sc.name}",
                     "frame_000.png, frame_001.png, ... and with --gif animation.gif")
    with atomic_folder(out) as tmp:
        images = draw_frames(sc, args.frames, args.duration, args.seed, out=tmp, view=args.view)
        if args.gif:
            from PIL import Image

            frames = [Image.fromarray(im).convert("P", palette=Image.ADAPTIVE) for im in images]
            frames[0].save(tmp / "animation.gif", save_all=True, append_images=frames[1:], duration=120, loop=0)
    print(f"wrote {args.frames} frames{' and animation.gif' if args.gif else ''} to {out}")
    return 0


def cmd_run(args) -> int:
    sc = load_scenario_arg(args.scenario)
    check_seed(args.seed)
    check_seconds_options(args, "duration")
    out = output_dir(args.output, f"run-{sc.name}", "trace.npz and trace.json")
    check_seconds_options(args, "epoch", "checkpoint_every")
    ck = None if args.checkpoint_every is None else out / "checkpoint.pkl"
    created = not out.exists()
    try:
        return _run_into(args, sc, out, ck)
    except BaseException:
        if created and out.is_dir() and not any(out.iterdir()):
            out.rmdir()  # nothing half-written: a folder made for a checkpoint that never came
        raise


def _before_run(sc, args, resuming: bool):
    """What the run says before it starts: what its parts did to their inputs (a measured profile resampled), and
    its projected wall time when that exceeds a minute (engine_sim.forecast: a probe of about a second)."""
    from engine_sim.forecast import LONG_RUN_S, forecast

    from .compile_notice import compile_notice

    for note in sc.substrate_part.notes():
        print(f"frictionnoise: note: {note}", file=sys.stderr, flush=True)
    if resuming:
        return
    with compile_notice():  # the probe records a sample: the recorder's kernel loads (or compiles) here
        fc = forecast(sc, duration=args.duration, seed=args.seed)
    if fc.wall_s > LONG_RUN_S:
        print(f"frictionnoise: note: {fc.line()}; --duration shortens it, Ctrl-C stops it and keeps what was "
              "recorded", file=sys.stderr, flush=True)


def _run_into(args, sc, out, ck) -> int:
    import engine_sim

    from engine_sim.run import CheckpointError, TraceSizeError

    from ..io.traces import save_trace

    if ck is not None:
        out.mkdir(parents=True, exist_ok=True)

    def on_plan(epoch_s, every_s):
        if every_s is not None and abs(every_s - args.checkpoint_every) > 1e-9:
            print(f"checkpoints every {every_s:g} s (whole epochs of {epoch_s:g} s)", file=sys.stderr)
    from .compile_notice import compile_notice

    _before_run(sc, args, resuming=(resuming := ck is not None and ck.exists()))
    bar, update = progress_bar(sc.name, warmup=sc.run.warmup, duration=args.duration or sc.run.duration)
    try:
        with bar, compile_notice():  # the recorder's and friction laws' kernels compile on a fresh install
            tr = engine_sim.run(sc, duration=args.duration, seed=args.seed, progress=update, checkpoint=ck,
                                checkpoint_every=args.checkpoint_every, epoch=args.epoch, on_plan=on_plan)
    except (CheckpointError, TraceSizeError) as e:  # a checkpoint of another run or a corrupt one; a run too big
        raise UserError(str(e)) from None
    except KeyboardInterrupt:  # engine_sim.run returns a partial trace once it has recorded a sample
        where = f"before it resumed from {ck} (kept)" if resuming else "in its warm-up"
        print(f"frictionnoise: interrupted: the run was stopped {where}, before anything was recorded, so nothing "
              "was written", file=sys.stderr)
        return 130
    out.mkdir(parents=True, exist_ok=True)
    path = save_trace(tr, out / "trace.npz")
    meta = tr.metadata
    for w in meta.get("warnings", ()):
        print(f"frictionnoise: warning: {w}", file=sys.stderr)
    if meta["partial"]:  # interrupted, or stopped when the scene left its regime (exit 1)
        at = meta.get("checkpoint_at_s")
        why = meta.get("stop_reason") or (f"interrupted ({meta['interrupted_by']}) at t = {tr.t[-1]:.3f} s of "
                                          "recorded time (the progress line counts the warm-up too)")
        print(f"frictionnoise: {why}: partial trace (marked partial) written to {path} and "
              f"{path.with_suffix('.json')}"
              + (f"; rerun the same command to resume from t = {at:g} s" if at else ""), file=sys.stderr)
        return 1 if "stop_reason" in meta else 143 if meta["interrupted_by"] == "SIGTERM" else 130
    if ck is not None and ck.exists():
        ck.unlink()
    print(f"wrote {path} and {path.with_suffix('.json')} ({len(tr.t)} samples, {meta['wall_s']:.1f} s wall)")
    return 0


def _registered_model(source: str) -> bool:
    """Whether ``frictionnoise compare SOURCE`` names a registered reduced model (an existing path wins)."""
    import os

    from reduced_models import MODELS

    return source in MODELS and not os.path.lexists(source)


def _compare_model(args) -> int:
    """``frictionnoise compare MODEL``: the registered model's simulation against its closed form."""
    from ..report.build import build_model_report
    from ..report.html import write_report
    from .compile_notice import compile_notice

    check_seed(args.seed)
    check_seconds_options(args, "duration")
    if args.band:
        raise UserError("--band applies to a scene or a trace, not to a reduced model against its closed form")
    out = output_dir(args.output, f"compare-{args.source}", "index.html, summary.json and figures/")
    try:
        with compile_notice():  # the model's kernels compile on its first run after an install
            sections, summary = build_model_report(args.source, seed=args.seed or 0, duration=args.duration)
    except ValueError as e:  # e.g. a duration too short for the model's band
        raise UserError(f"{args.source}: {e}") from None
    path = write_report(out, sections, summary, title=f"frictionnoise compare: {args.source}")
    f = summary["models"][args.source]
    print(f"wrote {path / 'index.html'}: gamma = {f['gamma']:.3f} +- {f['gamma_err']:.3f} over "
          f"{f['band'][0]:.3g}-{f['band'][1]:.3g} rad/s; simulated / closed form per band "
          f"{min(b['ratio'] for b in f['band_ratios_vs_closed_form']):.3f}-"
          f"{max(b['ratio'] for b in f['band_ratios_vs_closed_form']):.3f}")
    return 0


def cmd_compare(args) -> int:
    from ..report.html import write_report
    from ..report.build import build_scene_report
    from ..io.traces import TraceFileError, load_trace
    from ..io.inputs import input_file, sniff
    from reduced_models import MODELS

    if _registered_model(args.source):
        return _compare_model(args)
    src = input_file(scenario_path(args.source, models=tuple(MODELS)))
    check_seed(args.seed)
    kind = sniff(src)
    if kind == "binary":
        raise UserError(f"{src}: binary data, neither a scenario TOML file nor a trace .npz")
    if src.suffix.lower() == ".npz" and kind != "npz":
        raise UserError(f"{src}: not a .npz trace file (text, not a zip archive)")
    check_seconds_options(args, "duration")
    if args.band and not 0 < args.band[0] < args.band[1] < float("inf"):
        raise UserError(f"--band must be two finite frequencies LO < HI in rad/s (got {args.band[0]} {args.band[1]})")
    trace = None
    if kind == "npz":
        from engine_sim import ScenarioError, scenario_from_dict

        try:
            trace = load_trace(src)
            sc = scenario_from_dict(trace.metadata.get("scenario", {}), where=f"{src} (metadata)", strict=False)
        except (TraceFileError, ScenarioError) as e:
            raise UserError(str(e)) from None
    else:
        sc = load_scenario_arg(src)
    out = output_dir(args.output, f"compare-{sc.name}", "index.html, summary.json and figures/")
    note = None
    if trace is not None and trace.metadata.get("partial"):
        note = f"{src} is a partial trace ({trace.metadata.get('stop_reason') or 'interrupted'} at t = {trace.t[-1]:.3f} s)"
    from .compile_notice import compile_notice

    try:
        with compile_notice():  # the reduced model's kernels compile on the first comparison after an install
            if trace is None:
                # the recorded duration as the study sets it (--duration, else the scenario's), times the scene
                # runs its comparison makes (a wear scene's: with and without its particles)
                from ..report.studies.scenes import scene_runs

                bar, update = progress_bar(sc.name, warmup=sc.run.warmup, duration=args.duration or sc.run.duration,
                                           runs=scene_runs(sc))
                with bar:
                    sections, summary = build_scene_report(sc, duration=args.duration, seed=args.seed,
                                                           progress=update, band=args.band)
            else:
                sections, summary = build_scene_report(sc, trace=trace, band=args.band)
    except ValueError as e:  # e.g. a record too short for the fit band
        raise UserError(f"{src}: {e}" + (f"; {note}" if note else "")) from None
    if note:
        summary["partial_trace"] = note
        print(f"frictionnoise: note: {note}; the spectra cover only what was recorded", file=sys.stderr)
    path = write_report(out, sections, summary, title=f"frictionnoise compare: {sc.name}")
    f = summary["scenarios"][sc.name]
    print(f"wrote {path / 'index.html'}: gamma = {f['gamma']:.3f} +- {f['gamma_err']:.3f} over "
          f"{f['band'][0]:.3g}-{f['band'][1]:.3g} rad/s")
    print_verdicts(summary)
    return 0


def cmd_report(args) -> int:
    out = output_dir(args.output, "frictionnoise-report", "index.html, summary.json and figures/")
    check_seed(args.seed)
    if args.workers is not None and args.workers < 1:
        raise UserError(f"--workers must be at least 1 (got {args.workers})")
    workers = args.workers or usable_cores(cap=4)
    from ..report import studies
    from ..report.html import write_report
    from .progress import StageProgress, report_start_line
    from ..report.build import build_report

    chosen = studies.selected(args.quick, args.all_scenes)
    from .compile_notice import announcer, compile_notice

    # kernels compiled in this process (the studies that run alone) or in the pool's workers: one line, once
    announce = announcer()
    with compile_notice(announce=announce), StageProgress([s.label for s in chosen], desc="report") as progress:
        progress.note(report_start_line(chosen, workers))
        results, summary = build_report(quick=args.quick, seed=args.seed, progress=progress, workers=workers,
                                        studies=chosen, on_compile=announce, all_scenes=args.all_scenes)
    path = write_report(out, results, summary)
    print(f"wrote {path / 'index.html'} ({summary['total_wall_s']:.1f} s)")
    print_verdicts(summary)
    return 0
