"""The `frictionnoise` command line. User errors print one line and exit 2; no tracebacks."""
from __future__ import annotations

import argparse
import sys

from .inputs import InputError

__all__ = ["main"]


class UserError(Exception):
    """An error in the user's input: printed as one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse's usage errors as one line too (exit 2), like every other user error."""

    def error(self, message):
        self.exit(2, f"frictionnoise: error: {self.prog}: {message} (see {self.prog} --help)\n")


def _build_parser() -> argparse.ArgumentParser:
    ap = _Parser(
        prog="frictionnoise",
        description="Displacement noise of sliding friction: reduced models, scenes and spectra.",
    )
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    rep = sub.add_parser("report", help="the main job: the paper's model figures, fits and timings as an HTML report")
    rep.add_argument("-o", "--output", default="frictionnoise-report", help="output folder (default: %(default)s)")
    rep.add_argument("--quick", action="store_true", help="shorter runs (under a minute)")
    rep.add_argument("--seed", type=int, default=0, help="random seed (default: %(default)s)")
    rep.add_argument("--workers", type=int, default=None, metavar="N",
                     help="run the report's stages in N processes (default: the usable cores, at most 4; 1: in this "
                          "process); the numbers do not depend on it")
    rep.set_defaults(func=_cmd_report)

    run = sub.add_parser("run", help="run a scenario and write its trace (.npz + .json)")
    run.add_argument("scenario", help="scenario TOML file")
    run.add_argument("-o", "--output", default=None, help="output folder (default: run-<scenario name>)")
    run.add_argument("--duration", type=float, default=None, help="simulated seconds (default: the scenario's)")
    run.add_argument("--seed", type=int, default=None, help="random seed (default: the scenario's)")
    run.add_argument("--checkpoint-every", type=float, default=None, metavar="S",
                     help="checkpoint to DIR/checkpoint.pkl about every S simulated seconds (rounded to whole epochs, "
                          "at least one); rerunning the same command resumes from it, bit for bit")
    run.add_argument("--epoch", type=float, default=None, metavar="S",
                     help="simulated seconds between the run's state round trips (default: the scene's, chosen so "
                          "they cost at most 5 %% of the stepping); part of the run's definition, like --seed")
    run.set_defaults(func=_cmd_run)

    cmp_ = sub.add_parser("compare", help="report one scene (scenario TOML or trace .npz) against the reduced models")
    cmp_.add_argument("source", help="scenario TOML file or trace .npz written by `frictionnoise run`")
    cmp_.add_argument("-o", "--output", default=None, help="output folder (default: compare-<name>)")
    cmp_.add_argument("--duration", type=float, default=None, help="simulated seconds when running a scenario")
    cmp_.add_argument("--seed", type=int, default=None)
    cmp_.set_defaults(func=_cmd_compare)

    ren = sub.add_parser("render", help="render a scenario headless to PNG frames (and an animated GIF)")
    ren.add_argument("scenario", help="scenario TOML file")
    ren.add_argument("-o", "--output", default=None, help="output folder (default: render-<scenario name>)")
    ren.add_argument("--frames", type=int, default=12, help="number of frames (default: %(default)s)")
    ren.add_argument("--duration", type=float, default=0.6, help="simulated seconds spanned (default: %(default)s)")
    ren.add_argument("--gif", action="store_true", help="also write animation.gif")
    ren.add_argument("--seed", type=int, default=None)
    ren.set_defaults(func=_cmd_render)

    sw = sub.add_parser("sweep", help="run a parameter sweep (dask LocalCluster by default) and its report")
    sw.add_argument("sweep", help="sweep TOML file")
    sw.add_argument("-o", "--output", default=None, help="output folder, also the task cache (default: sweep-<name>)")
    sw.add_argument("--scheduler", default=None, help="address of a running dask scheduler, e.g. tcp://host:8786")
    sw.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default: %(default)s)")
    sw.add_argument("--serial", action="store_true", help="run in this process, without dask")
    sw.add_argument("--connect-timeout", type=float, default=10.0, metavar="S",
                    help="give up on --scheduler after S seconds (default: %(default)s)")
    sw.set_defaults(func=_cmd_sweep)

    an = sub.add_parser("analyze", help="analyse measured x(t) from a CSV file: spectra, gamma, rms, report")
    an.add_argument("data", help="CSV with a header row: time [s] and displacement columns")
    an.add_argument("--mass", type=float, required=True, help="block mass M (kg), for C_F = M^2 omega^4 C_x")
    an.add_argument("--time-col", default=None, help="time column name (default: the first)")
    an.add_argument("--x-col", default=None, help="displacement column name (default: the second)")
    an.add_argument("--x-unit", default="m", choices=["um", "mm", "m"], help="displacement unit (default: m)")
    an.add_argument("--band", type=float, nargs=2, default=None, metavar=("LO", "HI"), help="fit band (rad/s)")
    an.add_argument("-o", "--output", default=None, help="output folder (default: analyze-<file stem>)")
    an.set_defaults(func=_cmd_analyze)
    return ap


def _cmd_sweep(args) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from .report import build_sweep_report, write_sweep_outputs
    from .sweep import SchedulerError, SweepError, load_results, load_sweep, run_sweep

    try:
        spec = load_sweep(args.sweep)
    except SweepError as e:
        raise UserError(str(e)) from None
    if not 1 <= args.workers <= 64:
        raise UserError(f"--workers must be between 1 and 64 (got {args.workers})")
    if not 0 < args.connect_timeout <= 3600:
        raise UserError(f"--connect-timeout must be in (0, 3600] seconds (got {args.connect_timeout})")
    from .inputs import output_folder

    out = output_folder(args.output or f"sweep-{spec.name}")
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
    failures = [json.loads(p.read_text()) for p in sorted((out / "failures").glob("*.json"))]
    sections, summary = build_sweep_report(spec, load_results(out), failures)
    write_sweep_outputs(out, sections, summary)
    print(f"{spec.name}: {counts['done']}/{counts['total']} tasks done ({counts['ran']} run now, "
          f"{counts['failed']} failed); wrote {out / 'index.html'}")
    va = summary.get("velocity_analysis")
    if va:
        print(f"  C_x at fixed omega ~ v^{va['exponent']:.3f} +- {va['exponent_err']:.3f}; distance-domain collapse "
              f"{va['collapse_gain']:.1f}x")
    return 0 if counts["failed"] == 0 else 1


def _cmd_analyze(args) -> int:
    from pathlib import Path

    from .measured import DataFileError, read_displacement_csv
    from .report import build_measured_report, write_report

    from .inputs import input_file, output_folder, sniff

    if sniff(input_file(args.data)) != "text":  # kind, emptiness, binary; the format is read by compare.measured
        raise UserError(f"{args.data}: binary data, not a CSV text file")
    if not args.mass > 0:
        raise UserError(f"--mass must be positive (got {args.mass})")
    try:
        data = read_displacement_csv(args.data, args.time_col, args.x_col, args.x_unit)
    except DataFileError as e:
        raise UserError(str(e)) from None
    if data.warning:
        print(f"frictionnoise: warning: {data.warning}", file=sys.stderr)
    out = output_folder(args.output or f"analyze-{Path(args.data).stem}")
    try:
        sections, summary = build_measured_report(data, args.mass, band=tuple(args.band) if args.band else None)
    except ValueError as e:
        raise UserError(f"{args.data}: {e}") from None
    write_report(out, sections, summary)
    print(f"wrote {out / 'index.html'}: gamma = {summary['gamma']:.3f} +- {summary['gamma_err']:.3f} over "
          f"{summary['band'][0]:.3g}-{summary['band'][1]:.3g} rad/s")
    return 0


def _cmd_render(args) -> int:
    from pathlib import Path

    from .inputs import output_folder
    from .outputs import atomic_folder

    sc = _load_scenario(args.scenario)
    _check_seed(args.seed)
    if not 1 <= args.frames <= 10_000:
        raise UserError(f"--frames must be between 1 and 10000 (got {args.frames})")
    if not 0 < args.duration < float("inf"):
        raise UserError(f"--duration must be a positive number of seconds (got {args.duration})")
    from engine_sim import Scene
    from engine_sim.render import SceneRenderer

    out = output_folder(args.output or f"render-{sc.name}")
    scene = Scene(sc, args.seed)
    renderer = SceneRenderer(scene)
    steps = max(1, int(round(args.duration / sc.run.dt / args.frames)))
    images = []
    with atomic_folder(out) as tmp:
        for k in range(args.frames):
            img = renderer.frame()
            renderer.save_png(tmp / f"frame_{k:03d}.png")
            if args.gif:
                images.append(img.copy())
            scene.advance(steps)
            scene.maintain()
        if args.gif:
            from PIL import Image

            frames = [Image.fromarray(im).convert("P", palette=Image.ADAPTIVE) for im in images]
            frames[0].save(tmp / "animation.gif", save_all=True, append_images=frames[1:], duration=120, loop=0)
    renderer.close()
    print(f"wrote {args.frames} frames{' and animation.gif' if args.gif else ''} to {out}")
    return 0


def _check_seed(seed):
    if seed is not None and not 0 <= seed < 2**63:
        raise UserError(f"--seed must be a whole number from 0 to 2^63 - 1 (got {seed})")


def _load_scenario(path):
    from engine_sim import ScenarioError, scenario_from_dict

    from .inputs import read_toml

    data = read_toml(path, "scenario TOML file")
    try:
        return scenario_from_dict(data, where=str(path))
    except ScenarioError as e:
        raise UserError(str(e)) from None


def _progress_bar(desc):
    from tqdm import tqdm

    bar = tqdm(total=1.0, desc=desc, unit="s", file=sys.stderr, disable=not sys.stderr.isatty(),
               bar_format="{desc}: {percentage:3.0f}%|{bar}| {postfix} [{elapsed}<{remaining}]")

    def update(done, total):
        bar.total = total
        bar.n = done
        bar.set_postfix_str(f"{done:.1f}/{total:.1f} s simulated")
        bar.refresh()
    return bar, update


def _cmd_run(args) -> int:
    from .inputs import output_folder

    sc = _load_scenario(args.scenario)
    _check_seed(args.seed)
    if args.duration is not None and not 0 < args.duration < float("inf"):
        raise UserError(f"--duration must be a positive number of seconds (got {args.duration})")
    out = output_folder(args.output or f"run-{sc.name}")
    if args.epoch is not None and not 0 < args.epoch < float("inf"):
        raise UserError(f"--epoch must be a positive number of seconds (got {args.epoch})")
    ck = None
    if args.checkpoint_every is not None:
        if not 0 < args.checkpoint_every < float("inf"):
            raise UserError(f"--checkpoint-every must be a positive number of seconds (got {args.checkpoint_every})")
        ck = out / "checkpoint.pkl"
    created = not out.exists()
    try:
        return _run_into(args, sc, out, ck)
    except BaseException:
        if created and out.is_dir() and not any(out.iterdir()):
            out.rmdir()  # nothing half-written: a folder made for a checkpoint that never came
        raise


def _run_into(args, sc, out, ck) -> int:
    import engine_sim

    from engine_sim.run import CheckpointError

    from .traceio import save_trace

    if ck is not None:
        out.mkdir(parents=True, exist_ok=True)

    def on_plan(epoch_s, every_s):
        if every_s is not None and abs(every_s - args.checkpoint_every) > 1e-9:
            print(f"checkpoints every {every_s:g} s (whole epochs of {epoch_s:g} s)", file=sys.stderr)
    bar, update = _progress_bar(sc.name)
    with bar:
        try:
            tr = engine_sim.run(sc, duration=args.duration, seed=args.seed, progress=update, checkpoint=ck,
                                checkpoint_every=args.checkpoint_every, epoch=args.epoch, on_plan=on_plan)
        except CheckpointError as e:  # a checkpoint of another run, or a corrupt one
            raise UserError(str(e)) from None
    out.mkdir(parents=True, exist_ok=True)
    path = save_trace(tr, out / "trace.npz")
    meta = tr.metadata
    if meta["partial"]:
        at = meta.get("checkpoint_at_s")
        print(f"interrupted ({meta['interrupted_by']}) at t = {tr.t[-1]:.3f} s: partial trace (marked partial) "
              f"written to {path}" + (f"; rerun the same command to resume from t = {at:g} s" if at else ""),
              file=sys.stderr)
        return 143 if meta["interrupted_by"] == "SIGTERM" else 130
    if ck is not None and ck.exists():
        ck.unlink()
    print(f"wrote {path} and {path.with_suffix('.json')} ({len(tr.t)} samples, {meta['wall_s']:.1f} s wall)")
    return 0


def _cmd_compare(args) -> int:
    from pathlib import Path

    from .report import build_scene_report, write_report
    from .traceio import TraceFileError, load_trace

    from .inputs import input_file, output_folder, sniff

    src = input_file(args.source)
    _check_seed(args.seed)
    kind = sniff(src)
    if kind == "binary":
        raise UserError(f"{src}: binary data, neither a scenario TOML file nor a trace .npz")
    if src.suffix.lower() == ".npz" and kind != "npz":
        raise UserError(f"{src}: not a .npz trace file (text, not a zip archive)")
    if args.duration is not None and not 0 < args.duration < float("inf"):
        raise UserError(f"--duration must be a positive number of seconds (got {args.duration})")
    trace = None
    if kind == "npz":
        from engine_sim import ScenarioError, scenario_from_dict

        try:
            trace = load_trace(src)
            sc = scenario_from_dict(trace.metadata.get("scenario", {}), where=f"{src} (metadata)")
        except (TraceFileError, ScenarioError) as e:
            raise UserError(str(e)) from None
    else:
        sc = _load_scenario(src)
    out = output_folder(args.output or f"compare-{sc.name}")
    note = None
    if trace is not None and trace.metadata.get("partial"):
        note = f"{src} is a partial trace (interrupted at t = {trace.t[-1]:.3f} s)"
    try:
        if trace is None:
            bar, update = _progress_bar(sc.name)
            with bar:
                sections, summary = build_scene_report(sc, duration=args.duration, seed=args.seed, progress=update)
        else:
            sections, summary = build_scene_report(sc, trace=trace)
    except ValueError as e:  # e.g. a record too short for the fit band
        raise UserError(f"{src}: {e}" + (f"; {note}" if note else "")) from None
    if note:
        summary["partial_trace"] = note
        print(f"frictionnoise: note: {note}; the spectra cover only what was recorded", file=sys.stderr)
    path = write_report(out, sections, summary)
    f = summary["scenarios"][sc.name]
    print(f"wrote {path / 'index.html'}: gamma = {f['gamma']:.3f} +- {f['gamma_err']:.3f} over "
          f"{f['band'][0]:.3g}-{f['band'][1]:.3g} rad/s")
    return 0


def _usable_cores(cap: int) -> int:
    import os

    n = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cap, n))


def _cmd_report(args) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from .report import build_report, write_report

    from .inputs import output_folder

    out = output_folder(args.output)
    _check_seed(args.seed)
    if args.workers is not None and args.workers < 1:
        raise UserError(f"--workers must be at least 1 (got {args.workers})")
    workers = args.workers or _usable_cores(cap=4)
    from engine_sim import shipped_scenarios

    stages = (["model I reference", "model I variations", "model III", "model II"] + list(shipped_scenarios())
              + ([] if args.quick else ["work-precision"]))
    with tqdm(total=len(stages), desc="report", unit="stage", file=sys.stderr,
              disable=not sys.stderr.isatty()) as bar:
        def progress(stage):
            bar.set_postfix_str(stage)
            bar.update(1)
        sections, summary = build_report(quick=args.quick, seed=args.seed, progress=progress, workers=workers)
    path = write_report(out, sections, summary)
    print(f"wrote {path / 'index.html'} ({summary['total_wall_s']:.1f} s)")
    for key in ("model_I", "model_III", "model_II"):
        f = summary[key]
        print(f"  {key:10s} gamma = {f['gamma']:.3f} +- {f['gamma_err']:.3f} over {f['band'][0]:.3g}-{f['band'][1]:.3g} rad/s")
    return 0


def _sigterm(signum, frame):
    raise KeyboardInterrupt


def main(argv=None) -> int:
    """Run the command line. Exit status: 0 done, 1 some work failed (sweep tasks), 2 a user error (one line),
    130 interrupted by Ctrl-C (SIGINT; SIGTERM likewise, 143 when a run stopped on it), no traceback."""
    import signal
    import threading

    ap = _build_parser()
    args = ap.parse_args(argv)
    if args.command is None:
        ap.print_help()
        return 0
    main_thread = threading.current_thread() is threading.main_thread()
    old = signal.signal(signal.SIGTERM, _sigterm) if main_thread else None
    try:
        return args.func(args)
    except (UserError, InputError) as e:
        print("frictionnoise: error: " + " ".join(str(e).split()), file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("frictionnoise: interrupted; no output written for the unfinished step", file=sys.stderr)
        if argv is None:  # the command line itself: everything is cleaned up by now (outputs are written atomically,
            # worker processes ended); skip the interpreter's exit, where dask's threads held it 10 s after a sweep
            import os

            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(130)
        return 130
    finally:
        if main_thread:
            signal.signal(signal.SIGTERM, old)
            if argv is None:  # the command line itself: the work is over, a late Ctrl-C must not kill the exit
                signal.signal(signal.SIGINT, signal.SIG_IGN)


if __name__ == "__main__":
    sys.exit(main())
