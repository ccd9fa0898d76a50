"""The `frictionnoise` command line. User errors print one line and exit 2; no tracebacks."""
from __future__ import annotations

import argparse
import sys

__all__ = ["main"]


class UserError(Exception):
    """An error in the user's input: printed as one line, exit status 2."""


def _build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="frictionnoise",
        description="Displacement noise of sliding friction: reduced models, scenes and spectra.",
    )
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    rep = sub.add_parser("report", help="the main job: the paper's model figures, fits and timings as an HTML report")
    rep.add_argument("-o", "--output", default="frictionnoise-report", help="output folder (default: %(default)s)")
    rep.add_argument("--quick", action="store_true", help="shorter runs (under a minute)")
    rep.add_argument("--seed", type=int, default=0, help="random seed (default: %(default)s)")
    rep.set_defaults(func=_cmd_report)
    return ap


def _cmd_report(args) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from .report import build_report, write_report

    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise UserError(f"{out}: exists and is not a folder")
    from engine_sim import shipped_scenarios

    stages = ["model I reference", "model I variations", "model III", "model II"] + list(shipped_scenarios())
    with tqdm(total=len(stages), desc="report", unit="stage", file=sys.stderr,
              disable=not sys.stderr.isatty()) as bar:
        def progress(stage):
            bar.set_postfix_str(stage)
            bar.update(1)
        sections, summary = build_report(quick=args.quick, seed=args.seed, progress=progress)
    path = write_report(out, sections, summary)
    print(f"wrote {path / 'index.html'} ({summary['total_wall_s']:.1f} s)")
    for key in ("model_I", "model_III", "model_II"):
        f = summary[key]
        print(f"  {key:10s} gamma = {f['gamma']:.3f} +- {f['gamma_err']:.3f} over {f['band'][0]:.3g}-{f['band'][1]:.3g} rad/s")
    return 0


def main(argv=None) -> int:
    ap = _build_parser()
    args = ap.parse_args(argv)
    if args.command is None:
        ap.print_help()
        return 0
    try:
        return args.func(args)
    except UserError as e:
        print(f"frictionnoise: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
